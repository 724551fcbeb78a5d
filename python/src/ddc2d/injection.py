"""Closed forms of fluid injection into a fault (docs/theory/injection.md): the pressure
that diffuses from a source along a straight fracture, and the self-similar slip front of a
planar fault under a constant overpressure at one point (Bhattacharya & Viesca 2019; Viesca
2021).

The front's half-length is ``a(t) = front_factor(T) * sqrt(4 alpha t)`` with the stress
injection parameter ``T = (f s0 - tau0) / (f dp)`` (``s0`` the effective normal stress as a
positive compression, ``tau0`` the shear stress, ``f`` the friction, ``dp`` the
overpressure); ``front_factor`` solves ``T = (2/pi) int_0^{pi/2} erfc(lambda cos z) dz``.
"""

import math

import numpy as np

#: Gauss-Legendre nodes and weights of the front's integral on [0, pi/2]
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(200)
_Z = (_NODES + 1.0) * math.pi / 4.0
_W = _WEIGHTS * math.pi / 4.0


def injection_parameter(friction: float, normal_stress: float, shear_stress: float,
                        overpressure: float) -> float:
    """T = (f s0 - tau0) / (f dp), s0 the effective normal stress as a compression."""
    return (friction * normal_stress - shear_stress) / (friction * overpressure)


def front_integral(factor: float) -> float:
    """(2/pi) int_0^{pi/2} erfc(factor cos z) dz: the T of a front factor."""
    values = np.array([math.erfc(factor * math.cos(z)) for z in _Z])
    return float(2.0 / math.pi * np.sum(_W * values))


def front_factor(parameter: float) -> float:
    """lambda(T): the half-length of the slipping patch over sqrt(4 alpha t), 0 < T < 1
    (bisection on front_integral, which falls from 1 to 0 as lambda grows)."""
    if not 0.0 < parameter < 1.0:
        raise ValueError(f"T = {parameter} must lie between 0 and 1 for a front to grow")
    low, high = 0.0, 1.0
    while front_integral(high) > parameter:
        high *= 2.0
    for _ in range(200):
        middle = 0.5 * (low + high)
        if front_integral(middle) > parameter:
            low = middle
        else:
            high = middle
    return 0.5 * (low + high)


def overpressure_profile(distance: np.ndarray, time: float, diffusivity: float,
                         overpressure: float) -> np.ndarray:
    """dp erfc(|s| / sqrt(4 alpha t)): the pressure a constant overpressure held at s = 0
    since t = 0 makes along a straight fracture."""
    scaled = np.abs(np.asarray(distance, dtype=float)) / math.sqrt(4.0 * diffusivity * time)
    return overpressure * np.array([math.erfc(z) for z in np.ravel(scaled)]).reshape(
        scaled.shape)


def marginal_slip_profile(xi: np.ndarray, factor: float) -> np.ndarray:
    """Slip over sqrt(4 alpha t) f dp / mu' of a marginally pressurized fault (T -> 1),
    xi = x / a: (2 lambda^2 / pi^{3/2}) [sqrt(1 - xi^2) - xi^2 artanh sqrt(1 - xi^2)]."""
    root = np.sqrt(np.clip(1.0 - np.asarray(xi, dtype=float) ** 2, 0.0, 1.0))
    tail = np.where(root < 1.0, np.arctanh(np.minimum(root, 1.0 - 1e-16)), 0.0)
    return 2.0 * factor**2 / math.pi**1.5 * (root - np.asarray(xi) ** 2 * tail)


def critical_slip_profile(xi: np.ndarray) -> np.ndarray:
    """Slip over sqrt(4 alpha t) f dp / mu' of a critically stressed fault (T -> 0),
    xi = x / a: (2 / pi^{3/2}) [artanh sqrt(1 - xi^2) - sqrt(1 - xi^2)]."""
    root = np.sqrt(np.clip(1.0 - np.asarray(xi, dtype=float) ** 2, 0.0, 1.0))
    return 2.0 / math.pi**1.5 * (np.arctanh(np.minimum(root, 1.0 - 1e-16)) - root)
