"""The data of a hydraulic fracture's figure (docs/fluid-driven-fractures.md#hydraulic-fractures):
the half-length of each growing fracture (to its fronts), the net pressure and the opening
at its source against time, and the closed forms of the plane-strain fluid-driven fracture
(KGD) from a constant rate: the toughness-dominated solution (where the file holds the
toughness) and the viscosity-dominated solution of Adachi & Detournay (2002)."""

import math
from typing import Any

import numpy as np

from ..reader import ResultData

#: The viscosity-dominated KGD half-length: l = VISCOSITY_FACTOR (E' Q0^3 t^4 / (12 eta))^(1/6)
VISCOSITY_FACTOR = 0.61524
#: Its opening at the source: w0 = VISCOSITY_OPENING (12 eta Q0^3 t^2 / E')^(1/6), from
#: Adachi & Detournay's series: gamma (A0 + A1 + 4 B) with gamma = 0.6152, A0 = 3^(1/2),
#: A1 = -0.156, B = 0.0663
VISCOSITY_OPENING = 0.6152 * (math.sqrt(3.0) - 0.156 + 4.0 * 0.0663)


def is_hydraulic_fracture(result: ResultData) -> bool:
    """True for a result of fluid-driven growth: a history with the grown length of each
    growing end and the fluid's apertures."""
    history = result["history"]
    return history is not None and "grown_length" in history and "aperture" in history


def plane_strain_modulus(result: ResultData) -> float:
    """E' = 2 G / (1 - nu) from the file's root attributes."""
    attrs = result["attrs"]
    shear, poisson = float(np.ravel(attrs["shear_modulus"])[0]), float(
        np.ravel(attrs["poissons_ratio"])[0])
    return 2.0 * shear / (1.0 - poisson)


def fracture_series(result: ResultData) -> list[dict[str, Any]]:
    """One dict per growing fracture that holds a source: its name, the time, its
    half-length (half its length as given plus its ends' grown lengths), the net pressure
    (the fluid's pressure change plus the pore pressure, less the remote normal stress's
    compression) and the opening at the source (the mean over the elements at it)."""
    history, elements = result["history"], result["elements"]
    sources = result["injection"]
    series = []
    for fracture_id in sorted({int(v) for v in history["tip_fracture_id"]}):
        on_it = np.flatnonzero(sources["fracture_id"] == fracture_id)
        if on_it.size == 0:
            continue
        mine = elements["fracture_id"] == fracture_id
        given = mine & (history["state"][0] >= 0)
        length = float(np.sum(2.0 * elements["half_length"][given]))
        ends = np.flatnonzero(history["tip_fracture_id"] == fracture_id)
        half_length = 0.5 * (length + np.sum(history["grown_length"][:, ends], axis=1))
        x, y = sources["x"][on_it[0]], sources["y"][on_it[0]]
        distance = np.hypot(elements["x_mid"] - x, elements["y_mid"] - y)
        distance[~mine] = np.inf
        at = np.flatnonzero(distance <= distance.min() * (1.0 + 1e-6) + 1e-12)
        pressure = np.mean(history["pressure"][:, at], axis=1)
        series.append({"name": result["fractures"][fracture_id - 1]["name"],
                       "time": history["time"], "half_length": half_length,
                       "net_pressure": pressure + confinement_excess(result, at),
                       "opening": -np.mean(history["dn"][:, at], axis=1)})
    return series


def confinement_excess(result: ResultData, at: np.ndarray) -> float:
    """The pore pressure less the remote normal stress's compression on the elements at
    (their mean): what turns the fluid's pressure change into the net pressure."""
    elements = result["elements"]
    sxx, syy, sxy = (float(v) for v in result["remote_stress"][:3])
    dx = elements["x_end"][at] - elements["x_begin"][at]
    dy = elements["y_end"][at] - elements["y_begin"][at]
    cos, sin = dx / np.hypot(dx, dy), dy / np.hypot(dx, dy)
    normal = sxx * sin**2 + syy * cos**2 - 2.0 * sxy * sin * cos
    p0, dp_dy = (float(v) for v in result["pore_fluid"])
    return float(np.mean(p0 + dp_dy * elements["y_mid"][at] + normal))


def closed_forms(result: ResultData, time: np.ndarray) -> dict[str, np.ndarray]:
    """The KGD closed forms at `time` for the total rate of the rate sources (none where a
    source holds a pressure): ``toughness_*`` (half_length, net_pressure, opening) where the
    file holds the toughness, ``viscosity_*`` (half_length, opening) where it holds the
    viscosity."""
    sources = result["injection"]
    fluid = sources.get("fluid", {})
    if np.any(np.isfinite(sources["overpressure"])):
        return {}
    rate = float(np.nansum(sources["rate"]))
    e_prime = plane_strain_modulus(result)
    t = np.asarray(time, dtype=float)
    forms: dict[str, np.ndarray] = {}
    if "toughness" in fluid:
        toughness = float(fluid["toughness"])
        length = (e_prime * rate * t / (2.0 * math.sqrt(math.pi) * toughness))**(2.0 / 3.0)
        pressure = toughness / np.sqrt(math.pi * length)
        forms.update(toughness_half_length=length, toughness_net_pressure=pressure,
                     toughness_opening=4.0 * pressure * length / e_prime)
    if "viscosity" in fluid:
        mu_prime = 12.0 * float(fluid["viscosity"])
        forms["viscosity_half_length"] = VISCOSITY_FACTOR * (
            e_prime * rate**3 * t**4 / mu_prime)**(1.0 / 6.0)
        forms["viscosity_opening"] = VISCOSITY_OPENING * (
            mu_prime * rate**3 * t**2 / e_prime)**(1.0 / 6.0)
    return forms
