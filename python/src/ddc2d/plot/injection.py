"""What ddc2d-plot draws of a fluid injection (docs/plotting.md#fluid-injection), without
drawing it: the slip fronts of each fracture against the square root of time, with the
self-similar closed form where it applies (closed_form_front), the pressure and slip profiles
at chosen times, and the seismic moment against the injected volume. Needs numpy, never
matplotlib; ddc2d.plot.figures draws it.

The closed form (ddc2d.injection; docs/theory/injection.md#the-self-similar-front) is the
front of one planar fault in an unbounded medium under uniform stress and friction, with one
constant overpressure held at a point of it. closed_form_front decides from the result file
whether the model is that one, and says why not when it is not.
"""

import math
from typing import Any

import numpy as np

from ..injection import front_factor, injection_parameter, overpressure_profile
from ..reader import CONDITION_CODES, Arrays, ResultData, ResultError, is_tie

#: The profiles drawn by default: this many times spaced evenly in the square root of the
#: time since the first source started (pressure spreads as sqrt(t)), each the step nearest
#: to it.
DEFAULT_PROFILES = 4
#: Relative tolerance of "uniform", "straight" and "on the element" (values within it of
#: each other count as equal): loose enough for the rounding of a written file.
UNIFORM_RTOL = 1e-9


def has_injection(result: ResultData) -> bool:
    """True for a result with fluid sources (/injection) whose history records the
    slipping patches (/history/front_begin)."""
    history = result["history"]
    return (_entry(result, "injection") is not None and history is not None
            and "front_begin" in history)


def _entry(result, key):
    """result[key], None where a result (a hand-made dict) has no such entry."""
    try:
        return result[key]
    except KeyError:
        return None


def start_time(result: ResultData) -> float:
    """t0: when the first source starts (its `start`, or the path's first time when it has
    none)."""
    sources = result["injection"]
    first = float(result["history"]["time"][0])
    starts = np.where(np.isnan(sources["start"]), first, sources["start"])
    return float(np.min(starts)) if starts.size else first


def time_label(result: ResultData, t0: float) -> str:
    """The axis label of sqrt(t - t0) in the model's time unit."""
    unit = result["time_unit"]
    since = "t" if t0 == 0.0 else f"t - {t0:g}"
    return rf"$\sqrt{{{since}}}$" + (f" [{unit}$^{{1/2}}$]" if unit else "")


def _fracture_slice(fracture):
    return slice(fracture["first"] - 1, fracture["last"])


def source_positions(result: ResultData) -> list[tuple[int, float]]:
    """(fracture index from 0, arc length from the fracture's first vertex) of each source's
    point, in /injection order: along the element of its fracture that holds the point
    (the first of two at an end they share)."""
    e, sources = result["elements"], result["injection"]
    positions = []
    for fracture_id, x, y in zip(sources["fracture_id"], sources["x"], sources["y"]):
        index = int(fracture_id) - 1
        part = _fracture_slice(result["fractures"][index])
        xb, yb = e["x_begin"][part], e["y_begin"][part]
        dx, dy = e["x_end"][part] - xb, e["y_end"][part] - yb
        length = np.hypot(dx, dy)
        along = ((x - xb) * dx + (y - yb) * dy) / length
        across = np.abs((x - xb) * dy - (y - yb) * dx) / length
        tolerance = UNIFORM_RTOL * float(np.max(length))
        held = np.flatnonzero((across <= tolerance) & (along >= -tolerance)
                              & (along <= length + tolerance))
        if not held.size:
            raise ResultError(f"source at ({x:g}, {y:g}) is not on fracture {index + 1}")
        k = int(held[0])
        positions.append((index, float(np.sum(length[:k]) + min(max(along[k], 0.0),
                                                                 length[k]))))
    return positions


def front_series(result: ResultData) -> list[dict[str, Any]]:
    """One dict per fracture whose patch slips or opens at some step, in fracture order:
    ``fracture`` (index from 0), ``name``, ``begin`` and ``end`` (the fronts of each step,
    /history front_begin and front_end; NaN where nothing slips), measured from ``origin``
    (the arc length of the fracture's first source, whose name is ``source``; 0 and None
    for a fracture without a source: from its first vertex)."""
    history = result["history"]
    sources = result["injection"]
    origins: dict[int, tuple[float, str]] = {}
    for (index, arc), name in zip(source_positions(result), sources["name"]):
        origins.setdefault(index, (arc, name))
    series = []
    for index, fracture in enumerate(result["fractures"]):
        begin = np.asarray(history["front_begin"][:, index], dtype=float)
        if not np.any(np.isfinite(begin)):
            continue
        origin, source = origins.get(index, (0.0, None))
        series.append({"fracture": index, "name": fracture["name"] or fracture["label"],
                       "begin": begin - origin,
                       "end": np.asarray(history["front_end"][:, index], dtype=float) - origin,
                       "origin": origin, "source": source})
    return series


def _uniform(values: np.ndarray) -> bool:
    values = np.asarray(values, dtype=float)
    scale = float(np.max(np.abs(values))) if values.size else 0.0
    return bool(np.all(np.abs(values - values[0]) <= UNIFORM_RTOL * scale))


def _straight(e: Arrays, part: slice) -> bool:
    dx, dy = e["x_end"][part] - e["x_begin"][part], e["y_end"][part] - e["y_begin"][part]
    length = np.hypot(dx, dy)
    cross = (dx * dy[0] - dy * dx[0]) / (length * length[0])
    turn = (dx * dx[0] + dy * dy[0]) > 0.0
    return bool(np.all(np.abs(cross) <= UNIFORM_RTOL) and np.all(turn))


def _model_problem(result):
    """Why the model is not the closed form's (one source, one fault, its setting), '' when
    it is; the checks need no solution."""
    sources, history, attrs = result["injection"], result["history"], result["attrs"]
    if len(sources["name"]) != 1:
        return f"{len(sources['name'])} sources"
    if not np.isfinite(sources["overpressure"][0]):
        return "a rate source"
    if np.isfinite(sources["stop"][0]) and sources["stop"][0] < history["time"][-1]:
        return "the source is shut in"
    if len(result["fractures"]) != 1:
        return f"{len(result['fractures'])} fractures"
    if attrs.get("domain") == "half_plane":
        return "a half-plane"
    if attrs.get("symmetry", "none") not in ("none", ""):
        return "symmetry lines"
    if any(result["remote_stress_gradient"]) or result["pore_fluid"][1] != 0.0:
        return "the stress or the pore pressure changes with depth"
    if any(np.ptp(values) > 0.0 for values in history["loads"].values()):
        return "the path changes the remote stress or the pore pressure"
    return ""


def _fault_problem(e, part):
    """Why the fault's elements are not the closed form's (straight, contact, uniform
    friction, no cohesion or other strength, uniform flow properties and pressure), ''
    when they are."""
    if not _straight(e, part):
        return "the fault is not straight"
    if "condition" in e and np.any(e["condition"][part] != CONDITION_CODES["contact"]):
        return "elements that are not contact elements"
    for key, what in (("mu", "the friction"), ("pressure", "the pressure"),
                      ("diffusivity", "the diffusivity"),
                      ("transmissivity", "the transmissivity")):
        if key not in e:
            return f"no {key} in the file"
        if not _uniform(e[key][part]):
            return f"{what} varies along the fault"
    if np.any(e["sf"][part] != 0.0):
        return "a cohesion"
    for key, none in (("mu_dynamic", e["mu"][part]), ("shear_stiffness", np.inf),
                      ("normal_stiffness", np.inf)):
        if key in e and np.any(e[key][part] != none):
            return f"{key} (the closed form has Coulomb friction alone)"
    return ""


def remote_tractions(result: ResultData, index: int) -> tuple[float, float]:
    """(normal, shear) traction of the remote stress (root attribute remote_stress) on the
    straight fracture `index` (from 0), normal tension positive; the shear's sign is that
    of the slip it drives along the fracture's direction."""
    e = result["elements"]
    k = result["fractures"][index]["first"] - 1
    dx, dy = e["x_end"][k] - e["x_begin"][k], e["y_end"][k] - e["y_begin"][k]
    c, s = dx / math.hypot(dx, dy), dy / math.hypot(dx, dy)
    sxx, syy, sxy = result["remote_stress"]
    normal = sxx * s * s + syy * c * c - 2.0 * sxy * s * c
    shear = (syy - sxx) * s * c + sxy * (c * c - s * s)
    return float(normal), float(shear)


def closed_form_front(result: ResultData) -> tuple[dict[str, Any] | None, str]:
    """The self-similar front where it applies: ({fracture (index from 0), parameter T,
    factor lambda(T), diffusivity alpha, overpressure dp, start t0, origin (the source's arc
    length)}, ''), the patch's half-length then lambda sqrt(4 alpha (t - t0)); else (None,
    why not). It applies to one overpressure source that is not shut in, on the model's
    only fracture, straight, of contact elements with uniform friction, no cohesion and no
    other strength law, uniform diffusivity, transmissivity and pressure, in a full plane
    without symmetry lines, under a remote stress and pore pressure that change neither
    with depth nor along the path, with 0 < T < 1 (the fault sticks before the source and
    the source can make it slip) and an overpressure below the effective normal stress
    (nothing opens)."""
    problem = _model_problem(result)
    if problem:
        return None, problem
    e = result["elements"]
    part = _fracture_slice(result["fractures"][0])
    problem = _fault_problem(e, part)
    if problem:
        return None, problem
    normal, shear = remote_tractions(result, 0)
    compression = -(normal + float(e["pressure"][part][0]))
    friction = float(e["mu"][part][0])
    overpressure = float(result["injection"]["overpressure"][0])
    if not 0.0 < overpressure < compression:
        return None, (f"the overpressure {overpressure:g} is not between 0 and the effective "
                      f"normal stress {compression:g}")
    parameter = injection_parameter(friction, compression, abs(shear), overpressure)
    if not 0.0 < parameter < 1.0 or is_tie(parameter, 0.0, 1.0) or is_tie(parameter, 1.0):
        return None, f"T = {parameter:.4g} (a front grows for 0 < T < 1)"
    return {"fracture": 0, "parameter": parameter, "factor": front_factor(parameter),
            "diffusivity": float(e["diffusivity"][part][0]), "overpressure": overpressure,
            "start": start_time(result), "origin": source_positions(result)[0][1]}, ""


def profile_steps(result: ResultData, times: list[float] | None = None) -> list[int]:
    """Steps (from 0, increasing, each once) of the profiles: the step nearest to each of
    `times` (in the path's time range, else ResultError), or the step after t0 =
    start_time nearest to each of DEFAULT_PROFILES times spaced evenly in sqrt(t - t0)
    (the last one the path's end; any step where none lies after t0). Of two steps
    equally near, the earlier."""
    time = np.asarray(result["history"]["time"], dtype=float)
    candidates = np.arange(time.size)
    if times is None:
        t0 = start_time(result)
        times = [t0 + (time[-1] - t0) * (k / DEFAULT_PROFILES) ** 2
                 for k in range(1, DEFAULT_PROFILES + 1)]
        if np.any(time > t0):
            candidates = np.flatnonzero(time > t0)
    else:
        for t in times:
            if not time[0] <= t <= time[-1]:
                raise ResultError(f"time {t:g} is not in the path's times {time[0]:g} to "
                                  f"{time[-1]:g}")
    return sorted({int(candidates[np.argmin(np.abs(time[candidates] - t))]) for t in times})


def profile_fractures(result: ResultData, steps: list[int]) -> list[int]:
    """The fractures (indices from 0) whose profiles are drawn: those with a pressure change
    or a slip at one of the steps (the pressure reached them, or they slip); the sources'
    fractures when there is none."""
    history = result["history"]
    chosen = []
    for index, fracture in enumerate(result["fractures"]):
        part = _fracture_slice(fracture)
        if np.any(history["pressure"][steps, part] != 0.0) or \
                np.any(history["ds"][steps, part] != 0.0):
            chosen.append(index)
    return chosen or sorted({index for index, _ in source_positions(result)})


def pressure_profile(result: ResultData, form: dict[str, Any], distance: np.ndarray,
                     step: int) -> np.ndarray:
    """The closed form's pressure dp erfc(|s - s0| / sqrt(4 alpha (t - t0))) at `distance`
    along its fault at `step` (0 before t0)."""
    elapsed = float(result["history"]["time"][step]) - form["start"]
    if elapsed <= 0.0:
        return np.zeros_like(distance)
    return overpressure_profile(distance - form["origin"], elapsed, form["diffusivity"],
                                form["overpressure"])


def moment_series(result: ResultData) -> list[tuple[int, str]]:
    """(index from 0, name) of every fracture with a seismic moment at some step."""
    moment = result["history"]["moment"]
    return [(index, fracture["name"] or fracture["label"])
            for index, fracture in enumerate(result["fractures"])
            if np.any(moment[:, index] != 0.0)]
