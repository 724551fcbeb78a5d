"""Observed order of convergence and Richardson extrapolation of a quantity computed on
a sequence of meshes, each refined from the one before by the same ratio (2 when every
element is halved). Used by ddc2d-converge and by the verification suite.

The values are ordered from the coarsest (the user's own mesh) to the finest. With the
last three f_a, f_b, f_c and the differences d_1 = f_b - f_a, d_2 = f_c - f_b, an error
that falls as h^p gives d_1 / d_2 = r^p, so

    p = ln(|d_1| / |d_2|) / ln r,     f_inf = f_c + d_2 / (r^p - 1).

The error estimate of a level is its distance from f_inf.
"""

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Extrapolation:
    """What three or more levels say about a quantity: the observed order p (None when
    the last two differences give none: both zero, or only one of them zero), the
    extrapolated value f_inf (None without an order) and whether the differences
    shrink (|d_2| < |d_1|)."""

    order: float | None
    extrapolated: float | None
    differences_shrink: bool


def extrapolate(values, ratio=2.0):
    """Observed order and Richardson value from values ordered coarse to fine (at least
    three; the last three are used). A quantity that no longer changes (d_1 = d_2 = 0)
    is its own limit, with no order. Raises ValueError with fewer than three values or
    a ratio not above 1."""
    if len(values) < 3:
        raise ValueError("an observed order needs at least three levels")
    if not ratio > 1.0:
        raise ValueError("the refinement ratio must be above 1")
    f_a, f_b, f_c = (float(v) for v in values[-3:])
    d_1, d_2 = f_b - f_a, f_c - f_b
    if d_1 == 0.0 and d_2 == 0.0:
        return Extrapolation(order=None, extrapolated=f_c, differences_shrink=True)
    if d_1 == 0.0 or d_2 == 0.0:
        # One step moved and the other did not: no power law fits, and only a step
        # that stopped moving counts as shrinking.
        return Extrapolation(order=None, extrapolated=None, differences_shrink=d_2 == 0.0)
    order = math.log(abs(d_1) / abs(d_2)) / math.log(ratio)
    shrink = abs(d_2) < abs(d_1)
    extrapolated = f_c + d_2 / (ratio**order - 1.0) if shrink else None
    return Extrapolation(order=order, extrapolated=extrapolated, differences_shrink=shrink)


def error_estimate(value, extrapolation):
    """Distance of one level's value from the extrapolated limit; None without one."""
    if extrapolation.extrapolated is None:
        return None
    return abs(float(value) - extrapolation.extrapolated)
