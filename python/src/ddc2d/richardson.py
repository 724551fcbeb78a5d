"""Observed order of convergence and Richardson extrapolation of a quantity computed on
a sequence of meshes, each refined from the one before by the same ratio (2 when every
element is halved). Used by ddc2d-converge and by the verification suite.

The values are ordered from the coarsest (the user's own mesh) to the finest. With the
last three f_a, f_b, f_c and the differences d_1 = f_b - f_a, d_2 = f_c - f_b, an error
that falls as h^p gives d_1 / d_2 = r^p, so

    p = ln(|d_1| / |d_2|) / ln r,     f_inf = f_c + d_2 / (r^p - 1).

The error estimate of a level is its distance from f_inf. A power law gives differences
of one sign that shrink at every refinement; over all levels given, differences that
change sign (an oscillating sequence) or do not shrink steadily get no f_inf: the order of
the last three is then no property of the sequence.
"""

import math
from dataclasses import dataclass
from itertools import pairwise


@dataclass(frozen=True)
class Extrapolation:
    """What three or more levels say about a quantity: the observed order p of the last
    three (None when the last two differences give none: both zero, or only one of them
    zero), whether the differences shrink (each smaller in size than the one before, over
    all levels), whether they change sign (oscillate), and the extrapolated value f_inf
    (None without an order, or where they oscillate or do not shrink)."""

    order: float | None
    extrapolated: float | None
    differences_shrink: bool
    oscillates: bool = False


def extrapolate(values, ratio=2.0):
    """Observed order and Richardson value from values ordered coarse to fine (at least
    three; the order from the last three, the checks of sign and shrinking over all). A
    quantity that no longer changes (d_1 = d_2 = 0) is its own limit, with no order.
    Raises ValueError with fewer than three values or a ratio not above 1."""
    if len(values) < 3:
        raise ValueError("an observed order needs at least three levels")
    if not ratio > 1.0:
        raise ValueError("the refinement ratio must be above 1")
    differences = [float(b) - float(a) for a, b in pairwise(values)]
    oscillates = any(a * b < 0.0 for a, b in pairwise(differences))
    f_c = float(values[-1])
    d_1, d_2 = differences[-2:]
    if d_1 == 0.0 and d_2 == 0.0:
        return Extrapolation(order=None, extrapolated=f_c, differences_shrink=True,
                             oscillates=oscillates)
    if d_1 == 0.0 or d_2 == 0.0:
        # One step moved and the other did not: no power law fits, and only a step
        # that stopped moving counts as shrinking.
        return Extrapolation(order=None, extrapolated=None, differences_shrink=d_2 == 0.0,
                             oscillates=oscillates)
    order = math.log(abs(d_1) / abs(d_2)) / math.log(ratio)
    shrink = all(abs(b) < abs(a) for a, b in pairwise(differences))
    extrapolated = f_c + d_2 / (ratio**order - 1.0) if shrink and not oscillates else None
    return Extrapolation(order=order, extrapolated=extrapolated, differences_shrink=shrink,
                         oscillates=oscillates)


def error_estimate(value, extrapolation):
    """Distance of one level's value from the extrapolated limit; None without one."""
    if extrapolation.extrapolated is None:
        return None
    return abs(float(value) - extrapolation.extrapolated)
