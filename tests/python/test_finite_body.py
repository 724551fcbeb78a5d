"""Finite bodies (docs/finite-bodies.md) through the command line, with the executable under
test (DDC2D_EXE, see conftest.py).

- The 10 m square of the issue, 40 elements per side, under pressure, under u = eps x and
  under both: the interior stress is uniform, at the centre and 1.4 m from a corner, to
  1e-9 (quadratic elements hold a uniform state exactly; the constant elements of a
  TWODD-style boundary were 2.9 % off at the centre).
- A crack, and a frictional fault, in a square whose sides carry the tractions of the same
  fracture's solution in the infinite plane: the body gives that solution back, its DDs
  converging at order 2 as the sides are refined (the tractions are linear along each side).
- Bad input: one message naming &body, exit 2, no result file.
"""

import subprocess

import h5py
import numpy as np
import pytest

from conftest import ddc2d_exe, solve_text

MODEL = "&model youngs_modulus = 25000, poissons_ratio = 0.25 /\n"
PROBES = "x,y\n0,0\n-3.6,-3.6\n3.6,-3.6\n3.6,3.6\n-3.6,3.6\n6,0\n"
EPS = 1.0e-3


def square_sides(values):
    """&body of the square (-5..5)^2 counter-clockwise, 40 elements per side, with the
    given per-side entries (a dict of namelist text)."""
    entries = ", ".join(f"{name} = {text}" for name, text in values.items())
    return ("&body x = -5, 5, 5, -5,  y = -5, -5, 5, 5,  elements = 40, "
            f"{entries} /\n")


LOADINGS = {
    # every side: normal traction -10
    "traction": (square_sides({"condition": "'traction'", "bc_n": "-10"}), -10.0,
                 -10.0 * 0.5 / (2 * 10000.0)),
    # u = eps x: along s from the side's first vertex to its next, and along the outward n
    "displacement": (square_sides({
        "condition": "'displacement'",
        "bc_s": f"{-5 * EPS}, {-5 * EPS}, {-5 * EPS}, {-5 * EPS}",
        "bc_s_end": f"{5 * EPS}, {5 * EPS}, {5 * EPS}, {5 * EPS}",
        "bc_n": f"{5 * EPS}"}), 2 * 10000.0 * EPS / 0.5, EPS),
    # the normal displacement given, no shear traction
    "mixed": (square_sides({"condition": "'mixed_ss_un'", "bc_n": f"{5 * EPS}"}),
              2 * 10000.0 * EPS / 0.5, EPS),
}


@pytest.mark.parametrize("loading", sorted(LOADINGS))
def test_uniform_states_of_the_square(tmp_path, loading):
    body, stress, strain = LOADINGS[loading]
    (tmp_path / "probes.csv").write_text(PROBES)
    result = solve_text(tmp_path, "square", MODEL + body +
                        "&points name = 'probes', file = 'probes.csv' /\n")
    with h5py.File(result) as f:
        g = f["fields/probes"]
        x, y, flag = g["x"][:], g["y"][:], g["near_element"][:]
        inside = flag != 3
        assert list(flag) == [0, 0, 0, 0, 0, 3]
        assert np.all(np.isnan(g["sxx"][:][~inside]))
        for name, expected in (("sxx", stress), ("syy", stress), ("sxy", 0.0)):
            np.testing.assert_allclose(g[name][:][inside], expected, rtol=0,
                                       atol=1e-9 * abs(stress), err_msg=name)
        np.testing.assert_allclose(g["ux"][:][inside], strain * x[inside], rtol=0,
                                   atol=1e-9 * abs(strain) * 5)
        np.testing.assert_allclose(g["uy"][:][inside], strain * y[inside], rtol=0,
                                   atol=1e-9 * abs(strain) * 5)
        assert "3 outside the body" in g["near_element"].attrs["coding"].decode()


def square_vertices(half, per_side):
    """Vertices of the square (-half..half)^2, counter-clockwise, per_side per side."""
    t = np.linspace(-half, half, per_side + 1)[:-1]
    x = np.concatenate([t, np.full(per_side, half), -t, np.full(per_side, -half)])
    y = np.concatenate([np.full(per_side, -half), t, np.full(per_side, half), -t])
    return x, y


def numbers(values):
    return ", ".join(f"{v:.17g}" for v in values)


CRACK = ("&fracture name = 'crack', x = -1, 1, y = 0, 0, elements = 20, "
         "condition = 'traction' /\n")
FAULT = "&fracture name = 'fault', x = -1, 1, y = -0.3, 0.3, elements = 20, mu = 0.6 /\n"
FRACTURES = {
    "crack": (CRACK, "sxx = 0, syy = 10, sxy = 5"),
    "fault": (FAULT, "sxx = -20, syy = -10, sxy = 8"),
}


@pytest.mark.parametrize("kind", sorted(FRACTURES))
def test_body_gives_back_the_infinite_plane(tmp_path, kind):
    fracture, remote = FRACTURES[kind]
    errors = []
    for per_side in (8, 16):
        x, y = square_vertices(4.0, per_side)
        np.savetxt(tmp_path / "vertices.csv", np.c_[x, y], delimiter=",", header="x,y",
                   comments="")
        plane = solve_text(tmp_path, f"plane{per_side}", MODEL + fracture +
                           f"&remote_stress {remote} /\n"
                           "&points name = 'v', file = 'vertices.csv' /\n")
        with h5py.File(plane) as f:
            stress = np.array([[f["fields/v/sxx"][:], f["fields/v/sxy"][:]],
                               [f["fields/v/sxy"][:], f["fields/v/syy"][:]]])
            dd = np.concatenate([f["elements/ds"][:], f["elements/dn"][:]])
            state = f["elements/state"][:]
        # Each side's traction at its first vertex and at its next, along s and outward n
        sides = {"bc_s": [], "bc_n": [], "bc_s_end": [], "bc_n_end": []}
        for k in range(len(x)):
            j = (k + 1) % len(x)
            s = np.array([x[j] - x[k], y[j] - y[k]]) / np.hypot(x[j] - x[k], y[j] - y[k])
            n = np.array([s[1], -s[0]])
            for end, vertex in (("", k), ("_end", j)):
                t = stress[:, :, vertex] @ n
                sides["bc_s" + end].append(t @ s)
                sides["bc_n" + end].append(t @ n)
        body = (f"&body x = {numbers(x)}, y = {numbers(y)}, elements = 1, "
                "condition = 'traction', " +
                ", ".join(f"{name} = {numbers(v)}" for name, v in sides.items()) + " /\n")
        inside = solve_text(tmp_path, f"body{per_side}", MODEL + fracture + body)
        with h5py.File(inside) as f:
            body_dd = np.concatenate([f["elements/ds"][:], f["elements/dn"][:]])
            assert list(f["elements/state"][:]) == list(state)
        errors.append(np.abs(body_dd - dd).max() / np.abs(dd).max())
    assert errors[1] < 1e-3, errors
    assert np.log2(errors[0] / errors[1]) > 1.9, errors


BAD = {
    "two vertices": ("&body x = 0, 1, y = 0, 0, elements = 4 /\n", "at least 3 vertices"),
    "no area": ("&body x = 0, 1, 2, y = 0, 1, 2, elements = 4 /\n", "enclose no area"),
    "crossing sides": ("&body x = 0, 1, 1, 0, y = 0, 1, 0, 1, elements = 4 /\n",
                       "cross"),
    "unknown condition": (square_sides({"condition": "'contact'"}), "condition(1)"),
    "fracture outside": (square_sides({"bc_n": "-1"}) +
                         "&fracture x = 4, 6, y = 0, 0, elements = 4, mu = 0.6 /\n", "not inside"),
    "remote stress": (square_sides({"bc_n": "-1"}) + "&remote_stress syy = -1 /\n",
                      "&remote_stress"),
    "unbalanced": (square_sides({"bc_n": "-10, 0, 0, 0"}), "not in equilibrium"),
    "initiation": (square_sides({"bc_n": "-1"}) +
                   "&fracture x = -1, 1, y = 0, 0, elements = 4, mu = 0.6 /\n"
                   "&growth steps = 2, toughness = 1 /\n"
                   "&initiation tensile_strength = 10, probe_distance = 0.1 /\n",
                   "&initiation"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_body_input(tmp_path, case):
    text, words = BAD[case]
    (tmp_path / "bad.nml").write_text(MODEL + text)
    done = subprocess.run([str(ddc2d_exe()), "bad.nml", "-o", "bad.h5"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 2, done.stdout + done.stderr
    assert "&body" in done.stderr and words in done.stderr, done.stderr
    assert not (tmp_path / "bad.h5").exists()


def test_sample_between_platens(tmp_path):
    """A sample squeezed between platens (normal displacement given on the ends, no shear
    traction there: free to slide sideways) with a frictional flaw: the ends carry equal
    and opposite forces, /body holds every node, the map draws the outline."""
    from ddc2d.plot.figures import plot_map
    from ddc2d.reader import load_result

    text = (MODEL +
            "&body x = -0.05, 0.05, 0.05, -0.05,  y = -0.1, -0.1, 0.1, 0.1,\n"
            "      elements = 10, 20, 10, 20,\n"
            "      condition = 'mixed_ss_un', 'traction', 'mixed_ss_un', 'traction',\n"
            "      bc_n = -1.0e-4, 0, -1.0e-4, 0 /\n"
            "&fracture name = 'flaw', x = -0.01, 0.01, y = -0.01, 0.01, elements = 20, "
            "mu = 0.6 /\n"
            "&grid name = 'map', xmin = -0.06, xmax = 0.06, nx = 13, ymin = -0.11, "
            "ymax = 0.11, ny = 12 /\n")
    result = solve_text(tmp_path, "sample", text)
    with h5py.File(result) as f:
        body = f["body"]
        assert body["x"].shape == (3 * 60,)
        force_y = body["side_force_y"][:]
        # the platens push: a compressive load near E' strain times the width, balanced
        assert force_y[0] > 0 and abs(force_y[0] + force_y[2]) < 1e-9 * force_y[0]
        strain = 2e-4 / 0.2
        assert 0.8 < force_y[0] / (25000 / (1 - 0.25**2) * strain * 0.1) < 1.0
        np.testing.assert_allclose(body["side_force_x"][:], 0, atol=1e-9 * force_y[0])
        assert np.count_nonzero(f["fields/map/near_element"][:] == 3) > 0
        assert set(f["elements/state"][:]) <= {1, 2}
    figure = plot_map(load_result(result), "map", "max_shear")
    assert any(artist.get_gid() == "body" for artist in figure.axes[0].patches)


GROWTH = ("&fracture name = 'flaw', x = -0.70710678, 0.70710678, y = -0.70710678, "
          "0.70710678, elements = 10, mu = 0.6, sf = 1.0 /\n"
          "&growth steps = 5, toughness = 2.0, increment = 0.2, new_sf = 0.0 /\n")
GROWTH_MODEL = "&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /\n"


def test_growth_in_larger_bodies_tends_to_the_plane(tmp_path):
    """Wings off a 2 m sliding flaw, 5 steps, in squares of half-size 10, 20 and 40 m whose
    sides carry the remote stress of the infinite plane's model: the wings' tips and their
    K_I after growing tend to the plane's as the square grows, the difference falling as the
    square of the flaw's size over the body's (the body's effect on the flaw)."""
    plane = solve_text(tmp_path, "plane", GROWTH_MODEL +
                       "&remote_stress sxx = -2.0, syy = -100.0 /\n" + GROWTH)
    with h5py.File(plane) as f:
        tips = np.concatenate([f["tips/x"][:], f["tips/y"][:]])
        k1 = f["tips/k1"][:]
    tip_differences, k_differences = [], []
    for half in (10, 20, 40):
        body = (f"&body x = -{half}, {half}, {half}, -{half}, y = -{half}, -{half}, {half}, "
                f"{half}, elements = 10, bc_n = -100, -2, -100, -2 /\n")
        result = solve_text(tmp_path, f"body{half}", GROWTH_MODEL + body + GROWTH)
        with h5py.File(result) as f:
            assert f["growth/step"][:].max() == 5
            tip_differences.append(np.abs(np.concatenate([f["tips/x"][:], f["tips/y"][:]])
                                          - tips).max())
            k_differences.append(np.abs(f["tips/k1"][:] - k1).max())
    for differences in (tip_differences, k_differences):
        ratios = np.array(differences[:-1]) / np.array(differences[1:])
        assert np.all(ratios > 3.5), differences
    assert k_differences[-1] < 0.01 * abs(k1).max()


def test_wing_stops_short_of_the_boundary(tmp_path):
    """The gallery's sample with its flaw moved up near the top platen: the upper wing
    reaches the platen and stops there (reason intersection), inside the sample, less than
    one increment (3 mm) from it; the lower wing arrests."""
    from conftest import REPO_ROOT

    text = (REPO_ROOT / "input" / "gypsum_sample_wing_cracks.nml").read_text()
    text = text.replace("y = -0.00449, 0.00449,", "y = 0.04051, 0.04949,")
    result = solve_text(tmp_path, "near", text)
    with h5py.File(result) as f:
        g = f["growth"]
        upper = np.flatnonzero(g["end"][:] == 1)  # the flaw's end: its upper tip
        assert g["reason"][:][upper[-1]] == 2
        assert 0.0762 - 0.003 < f["tips/y"][:].max() < 0.0762
        lower = np.flatnonzero(g["end"][:] == 0)
        assert g["reason"][:][lower[-1]] == 1
