"""The Kirsch hole with TWODD boundary elements (docs/verification.md): a traction-free
circular hole of radius a in a remote uniaxial tension s along x, given as a classic TWODD
deck (docs/compatibility.md), a quarter of the circle with symmetry about both axes
(KSYM = 4). Kirsch (1898), e.g. Jaeger, Cook & Zimmerman (2007) section 8.4."""

import math

import numpy as np

from ddc2d.richardson import extrapolate

#: Elements on the quarter circle of the three levels (the whole hole has four times as
#: many); the row is the last's.
LEVELS = (25, 50, 100)
S, A = 10.0, 1.0


def kirsch_deck(n):
    """The deck: n straight traction-free elements (KOD 1) from (a, 0) to (0, a), counter-
    clockwise so that the body lies on their negative side; points on the y axis from
    r = 1.25 a to 3 a and on the x axis from 1.25 a to 3 a (6 interior points each)."""
    lines = [f"Kirsch hole n={n}", f"{n},2,4", "0.25,50000.0,0.,0.", f"{S},0.,0."]
    theta = np.linspace(0.0, math.pi / 2, n + 1)
    x, y = (A * np.cos(theta)).tolist(), (A * np.sin(theta)).tolist()
    x[-1] = 0.0  # on the symmetry line exactly
    for k in range(n):
        lines.append(f"1,{x[k]!r},{y[k]!r},{x[k + 1]!r},{y[k + 1]!r},1,0.0,0.0")
    lines += ["0.0,1.25,0.0,3.0,6", "1.25,0.0,3.0,0.0,6"]
    return "\n".join(lines) + "\n"


def kirsch_stress(x, y):
    """(sxx, syy, sxy) of the Kirsch solution at (x, y)."""
    r, theta = np.hypot(x, y), np.arctan2(y, x)
    q2, q4 = (A / r) ** 2, (A / r) ** 4
    c2, s2 = np.cos(2 * theta), np.sin(2 * theta)
    srr = S / 2 * (1 - q2) + S / 2 * (1 - 4 * q2 + 3 * q4) * c2
    stt = S / 2 * (1 + q2) - S / 2 * (1 + 3 * q4) * c2
    srt = -S / 2 * (1 + 2 * q2 - 3 * q4) * s2
    c, s = np.cos(theta), np.sin(theta)
    return (srr * c**2 + stt * s**2 - 2 * srt * s * c,
            srr * s**2 + stt * c**2 + 2 * srt * s * c,
            (srr - stt) * s * c + srt * (c**2 - s**2))


def test_kirsch_hole(solve_deck, record):
    results = [solve_deck(kirsch_deck(n), f"kirsch{n}") for n in LEVELS]
    hoop = []
    for r in results:
        points = r.fields
        xs = np.concatenate([f["x"] for f in points.values()])
        ys = np.concatenate([f["y"] for f in points.values()])
        computed = [np.concatenate([f[name] for f in points.values()])
                    for name in ("sxx", "syy", "sxy")]
        exact = kirsch_stress(xs, ys)
        worst = max(float(np.max(np.abs(c - e))) for c, e in zip(computed, exact,
                                                                  strict=True))
        nearest = int(np.argmin(np.hypot(xs, ys - 1.25 * A)))
        hoop.append((float(computed[0][nearest]), float(exact[0][nearest])))
    # Every stress at every point within 1 % of the remote stress on the finest mesh.
    assert worst < 1e-2 * S, f"largest stress error {worst} of remote {S}"
    values = [h[0] for h in hoop]
    row = record(id="kirsch-hoop-stress", benchmark="Kirsch hole (TWODD deck, KSYM = 4) "
                 "under a uniaxial tension",
                 reference="s_tt = s/2 (1 + a^2/r^2) - s/2 (1 + 3 a^4/r^4) cos 2 theta "
                           "(Kirsch 1898)",
                 quantity="s_xx at (0, 1.25 a), 1.93 s [MPa] (every stress at 16 points "
                          "within 1 % of s)",
                 value=values[-1], reference_value=hoop[-1][1], tolerance=2e-3,
                 mesh=f"{4 * LEVELS[-1]} elements on the hole (levels "
                      f"{', '.join(str(4 * n) for n in LEVELS)})",
                 order=extrapolate(values).order)
    assert row["passed"], row
