"""Closed forms that several test suites compare ddc2d with (tests/ is on pytest's path)."""

import math


def arc_crack_k(half_angle, radius=1.0, tension=1.0):
    """K_I, K_II at the tips of a traction-free circular-arc crack of radius `radius` and
    half-angle `half_angle` [rad] under remote isotropic tension `tension` (Sih, Paris &
    Erdogan 1962): K_I + i K_II = s sqrt(pi R sin a) (cos(a/2) + i sin(a/2)) /
    (1 + sin^2(a/2))."""
    scale = tension * math.sqrt(math.pi * radius * math.sin(half_angle))
    scale /= 1.0 + math.sin(half_angle / 2.0) ** 2
    return scale * math.cos(half_angle / 2.0), scale * math.sin(half_angle / 2.0)
