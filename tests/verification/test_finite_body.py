"""Finite bodies (docs/finite-bodies.md, docs/theory/finite-bodies.md) against closed forms.

- The 10 m square of the issue with 40 elements per side under a pressure of 10 MPa on every
  side, under u = eps x on its sides, and under the normal displacement of eps x with no
  shear traction: the interior stress is uniform (quadratic elements hold it exactly); the
  rows are the centre and the point 1.41 m from a corner, (-4, -4).
- Kelvin's force outside the square, its traction given on the square's sides, each side one
  element whose traction varies linearly between the exact values at its ends: the stress
  at the centre converges at order 2 (the given tractions' interpolation; the body's own
  error is of order 3, suite `body`).
"""

import math

import numpy as np

from ddc2d.richardson import extrapolate

E, NU = 25000.0, 0.25
G = E / (2 * (1 + NU))
EPS = 1.0e-3
MODEL = f"&model youngs_modulus = {E}, poissons_ratio = {NU} /\n"
PROBES = "x,y\n0,0\n-4,-4\n"


def square_text(entries):
    return (MODEL + "&body x = -5, 5, 5, -5,  y = -5, -5, 5, 5,  elements = 40, "
            + ", ".join(f"{k} = {v}" for k, v in entries.items()) + " /\n"
            "&points name = 'probes', file = 'probes.csv' /\n")


LOADINGS = {
    "pressure": ({"condition": "'traction'", "bc_n": "-10"}, -10.0,
                 "every side under a normal traction of -10 MPa", "s_xx = -10 MPa"),
    "displacement": ({"condition": "'displacement'", "bc_s": f"{-5 * EPS}",
                      "bc_s_end": f"{5 * EPS}", "bc_n": f"{5 * EPS}"},
                     2 * G * EPS / (1 - 2 * NU), "u = eps x on every side (eps = 1e-3)",
                     "s_xx = 2 G eps / (1 - 2 nu)"),
    "mixed": ({"condition": "'mixed_ss_un'", "bc_n": f"{5 * EPS}"},
              2 * G * EPS / (1 - 2 * NU),
              "u_n = eps x.n and no shear traction on every side (eps = 1e-3)",
              "s_xx = 2 G eps / (1 - 2 nu)"),
}


def test_square_uniform_states(solve, record, tmp_path):
    (tmp_path / "probes.csv").write_text(PROBES)
    rows = []
    for name, (entries, expected, loading, closed_form) in LOADINGS.items():
        model = tmp_path / f"{name}.nml"
        model.write_text(square_text(entries))
        sxx = solve(model, name).fields["probes"]["sxx"]
        for index, (where, tolerance) in enumerate((("centre", 1e-3), ("corner", 5e-3))):
            point = "(0, 0)" if where == "centre" else "(-4, -4), 1.41 m from a corner"
            rows.append(record(
                id=f"body-square-{name}-{where}",
                benchmark=f"10 m square body, {loading}",
                reference=f"uniform stress: {closed_form}",
                quantity=f"s_xx at {point} [MPa]", value=float(sxx[index]),
                reference_value=expected, tolerance=tolerance,
                mesh="40 elements per side (three nodes each)"))
    assert all(row["passed"] for row in rows), rows


FORCE = np.array([300.0, 500.0])
SOURCE = np.array([-7.0, 2.0])


def kelvin_stress(x, y):
    """Kelvin's plane-strain stress (sxx, syy, sxy) at (x, y) of FORCE at SOURCE."""
    r = np.array([x - SOURCE[0], y - SOURCE[1]])
    r2 = float(r @ r)
    s = np.zeros((2, 2))
    for i in range(2):
        for j in range(2):
            for k in range(2):
                s[i, j] += ((1 - 2 * NU) * ((i == k) * r[j] + (j == k) * r[i]
                                            - (i == j) * r[k]) / r2
                            + 2 * r[i] * r[j] * r[k] / r2**2) * FORCE[k]
    return -s / (4 * math.pi * (1 - NU))


def kelvin_square(per_side):
    """The square with per_side sides of one element per side of the square, each side's
    traction linear between Kelvin's tractions at its ends."""
    t = np.linspace(-5.0, 5.0, per_side + 1)[:-1]
    x = np.concatenate([t, np.full(per_side, 5.0), -t, np.full(per_side, -5.0)])
    y = np.concatenate([np.full(per_side, -5.0), t, np.full(per_side, 5.0), -t])
    values = {"bc_s": [], "bc_n": [], "bc_s_end": [], "bc_n_end": []}
    for k in range(len(x)):
        j = (k + 1) % len(x)
        s = np.array([x[j] - x[k], y[j] - y[k]])
        s /= np.linalg.norm(s)
        n = np.array([s[1], -s[0]])
        for end, vertex in (("", k), ("_end", j)):
            traction = kelvin_stress(x[vertex], y[vertex]) @ n
            values["bc_s" + end].append(traction @ s)
            values["bc_n" + end].append(traction @ n)

    def numbers(v):
        return ", ".join(f"{float(a):.17g}" for a in v)

    return (MODEL + f"&body x = {numbers(x)}, y = {numbers(y)}, elements = 1, "
            "condition = 'traction', "
            + ", ".join(f"{k} = {numbers(v)}" for k, v in values.items()) + " /\n"
            "&points name = 'probes', file = 'probes.csv' /\n")


def test_kelvin_force_outside(solve, record, tmp_path):
    (tmp_path / "probes.csv").write_text(PROBES)
    levels = (20, 40, 80)
    values = []
    for per_side in levels:
        model = tmp_path / f"kelvin{per_side}.nml"
        model.write_text(kelvin_square(per_side))
        values.append(float(solve(model, f"kelvin{per_side}").fields["probes"]["syy"][0]))
    exact = float(kelvin_stress(0.0, 0.0)[1, 1])
    order = extrapolate(values).order
    row = record(id="body-kelvin-force-centre",
                 benchmark="10 m square body, the tractions of a force of (300, 500) MN/m at "
                 "(-7, 2) outside it on its sides (linear along each element)",
                 reference="Kelvin's plane-strain solution", quantity="s_yy at the centre "
                 "[MPa]", value=values[-1], reference_value=exact, tolerance=1e-3,
                 mesh=f"{levels[-1]} elements per side (levels "
                      f"{', '.join(str(n) for n in levels)})", order=order)
    assert row["passed"], row
    assert order > 1.8, values
