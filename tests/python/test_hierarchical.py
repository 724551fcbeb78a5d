"""Hierarchical matrices (&solver matrix = 'hierarchical', hmat-oss;
docs/theory/hierarchical.md) against the dense path: models of TWODD-style elements (the
TWODD reference decks, two cracks) and contact models solved by the Newton method on the
compressed operator (the benchmark's straight fault and kinked network, the examples'
branching and intersecting faults): the same element states, and DDs, K and fields within
1e-6 of the dense results relative to their largest value; 'auto'; bad input."""

import re
import subprocess
from pathlib import Path

import h5py
import numpy as np
import pytest

from conftest import REPO_ROOT, SCRIPTS, ddc2d_exe, solve_text
from ddc2d import benchmark

#: Accuracy asked of the hierarchical path, relative to the largest value of each quantity
RELATIVE = 1e-6

TWO_CRACKS = """\
&model title = 'two cracks', youngs_modulus = 50000.0, poissons_ratio = 0.25 /
&remote_stress sxx = 0.0, syy = 10.0, sxy = 3.0 /
&fracture name = 'a', x = -1.0, 1.0, y = 0.0, 0.0, elements = 1200,
          condition = 'traction', bc_s = 0.0, bc_n = 0.0 /
&fracture name = 'b', x = -1.0, 0.5, y = 0.3, 1.2, elements = 800,
          condition = 'traction', bc_s = 0.0, bc_n = 0.0 /
&grid name = 'map', xmin = -1.5, xmax = 1.5, nx = 21, ymin = -1.0, ymax = 1.5, ny = 21 /
"""


def test_the_input_reference_promises_what_is_tested_here():
    """The row of hmatrix_tolerance in docs/input-reference.md states RELATIVE as the gap to
    the dense DDs, K and fields: the bound these tests hold, not a measured value."""
    text = (REPO_ROOT / "docs" / "input-reference.md").read_text(encoding="utf-8")
    (row,) = [line for line in text.splitlines() if line.startswith("| `hmatrix_tolerance`")]
    bound = re.search(r"the DDs, `K` and fields are within ([0-9.e+-]+) of the dense ones",
                      row)
    assert bound and float(bound.group(1)) == RELATIVE, row


def solve_both(folder, stem, text, settings="", both=""):
    """Solve the model on the dense and on the hierarchical path (with `settings`; `both`:
    &solver settings of both runs); the two result files."""
    dense = solve_text(folder, f"{stem}_dense", text + f"&solver matrix = 'dense'{both} /\n")
    hierarchical = solve_text(folder, f"{stem}_hierarchical",
                              text + f"&solver matrix = 'hierarchical'{settings}{both} /\n")
    return dense, hierarchical


def relative_gap(a, b, scale=None):
    """Largest |a - b| over `scale` (default: the largest |a|), finite entries."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    keep = np.isfinite(a)
    if scale is None:
        scale = np.max(np.abs(a[keep]))
    return float(np.max(np.abs(a[keep] - b[keep])) / scale)


def assert_same_results(dense_file, hierarchical_file, compressed=True):
    """Same states; DDs, K and every field within RELATIVE of the dense ones; compressed:
    the hierarchical matrix is smaller than the dense one (not so for a few elements)."""
    with h5py.File(dense_file, "r") as d, h5py.File(hierarchical_file, "r") as h:
        np.testing.assert_array_equal(d["elements/state"][()], h["elements/state"][()])
        dds = np.concatenate([d["elements/ds"][()], d["elements/dn"][()]])
        assert relative_gap(dds, np.concatenate([h["elements/ds"][()],
                                                 h["elements/dn"][()]])) <= RELATIVE
        ks = np.concatenate([d["tips/k1"][()], d["tips/k2"][()]])
        if np.any(ks != 0.0):
            assert relative_gap(ks, np.concatenate([h["tips/k1"][()],
                                                    h["tips/k2"][()]])) <= RELATIVE
        # Each field against the largest of its kind (displacements: or the largest DD,
        # where the field's displacements vanish by symmetry).
        for name in d.get("fields", {}):
            for quantities, floor in ((("ux", "uy"), np.max(np.abs(dds))),
                                      (("sxx", "syy", "sxy"), 0.0)):
                scale = max(floor, *(np.nanmax(np.abs(d[f"fields/{name}/{q}"][()]))
                                     for q in quantities))
                for q in quantities:
                    assert relative_gap(d[f"fields/{name}/{q}"][()], h[f"fields/{name}/{q}"][()],
                                        scale) <= RELATIVE, q
        solver = h["solver"].attrs
        assert solver["matrix"].decode().strip() == "hierarchical"
        assert solver["compression_ratio"] > 0.0
        assert solver["compression_ratio"] < 1.0 or not compressed
        assert solver["hmatrix_tolerance"] == pytest.approx(1e-6, rel=1e-12)
        assert solver["equilibrium_residual"] <= 1e-8
        assert "matrix" not in d["solver"].attrs  # a dense run does not say


def test_cracks_match_the_dense_solve(tmp_path):
    assert_same_results(*solve_both(tmp_path, "cracks", TWO_CRACKS))


DECKS = {"A1_press_n20": REPO_ROOT / "tests" / "reference" / "twodd" / "inputs",
         "B1_rshear_n20": REPO_ROOT / "tests" / "reference" / "twodd" / "inputs",
         "A1_half_ksym2": REPO_ROOT / "tests" / "data" / "twodd"}


@pytest.mark.parametrize("deck", sorted(DECKS))
def test_twodd_decks_match_the_dense_solve(tmp_path, deck):
    """TWODD decks (pressure, shear, a symmetry plane) with leaves of 4 unknowns, so that
    most blocks are compressed."""
    nml = tmp_path / f"{deck}.nml"
    done = subprocess.run([str(SCRIPTS / "twodd2nml"), str(DECKS[deck] / f"{deck}.f60.txt"),
                           "-o", str(nml)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert_same_results(*solve_both(tmp_path, deck, nml.read_text(),
                                    ", hmatrix_leaf_size = 4"), compressed=False)


@pytest.mark.parametrize("case", ["straight", "mixed"])
def test_benchmark_contact_models_match_the_dense_solve(tmp_path, case):
    """N = 2000: every element slipping (straight), or stick, slip and open over several
    Newton iterations (mixed)."""
    text = benchmark.CASES[case](2000, 21, 0)
    dense, hierarchical = solve_both(tmp_path, case, text)
    assert_same_results(dense, hierarchical)
    with h5py.File(hierarchical, "r") as h:
        assert h["solver"].attrs["method"].decode().strip() == "newton"


@pytest.mark.parametrize("example", ["branching_fault", "intersecting_faults",
                                     "thrust_fault_surface", "buried_dipping_fault_slip",
                                     "crack_toward_soft_layer"])
def test_example_faults_match_the_dense_solve(tmp_path, example):
    """Examples in the full plane, in the half-plane (a thrust fault with pore pressure
    to the surface, a buried fault of given slip) and in two bonded half-planes (a crack
    near the interface), the contact ones by the Newton method on both paths (the dense
    path's 'auto' takes Lemke below 300 contact elements, which may choose other states
    where the contact problem has more than one solution)."""
    text = (REPO_ROOT / "input" / f"{example}.nml").read_text()
    assert_same_results(*solve_both(tmp_path, example, text, both=", lcp_method = 'newton'"))


def test_two_materials_match_the_dense_solve(tmp_path):
    """The frictional fault across the interface of two bonded half-planes
    (input/fault_across_layers.nml) at 401 elements, without its fields: the kernel of two
    materials is compressed as the others are; the same states, DDs and K within RELATIVE."""
    text = (REPO_ROOT / "input" / "fault_across_layers.nml").read_text()
    text = "".join(line + "\n" for line in text.splitlines()
                   if not line.startswith(("&grid", "&line")))
    text = text.replace("elements = 41", "elements = 401")
    assert_same_results(*solve_both(tmp_path, "layers", text,
                                    both=", lcp_method = 'newton', k_method = 'tip_element'"))


def test_loading_history_matches_the_dense_solve(tmp_path):
    """The benchmark's history (the straight fault loaded, unloaded and loaded the other
    way, 9 steps, N = 600) on both matrices by the Newton method: the same states at every
    step, DDs and K within RELATIVE; the compressed operator is assembled once."""
    text = benchmark.CASES["history"](600, 0, 9)
    dense, hierarchical = solve_both(tmp_path, "history", text, both=", lcp_method = 'newton'")
    with h5py.File(dense, "r") as d, h5py.File(hierarchical, "r") as h:
        np.testing.assert_array_equal(d["history/state"][()], h["history/state"][()])
        for name in ("ds", "dn"):
            scale = np.max(np.abs(d["history/ds"][()]))
            assert relative_gap(d[f"history/{name}"][()], h[f"history/{name}"][()],
                                scale) <= RELATIVE
        assert relative_gap(d["history/k2"][()], h["history/k2"][()]) <= RELATIVE
        assert h["solver"].attrs["matrix"].decode().strip() == "hierarchical"
    assert_same_results(dense, hierarchical)


def echo_of(folder, stem, text):
    """Solve; the echo lines that name the matrix."""
    (folder / f"{stem}.nml").write_text(text)
    done = subprocess.run([str(ddc2d_exe()), f"{stem}.nml", "-o", f"{stem}.h5"], cwd=folder,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    return [line for line in done.stdout.splitlines() if line.startswith("  matrix: ")]


def test_auto_takes_the_hierarchical_matrix_from_the_crossover(tmp_path):
    """'auto' (the default): dense below hierarchical_min_elements elements, hierarchical
    from there on (docs/theory/hierarchical.md#choosing-the-matrix), dense for a model it
    does not solve, and the echo says which and why."""
    small = TWO_CRACKS.replace("elements = 800,", "elements = 80,").replace(
        "elements = 1200,", "elements = 120,")
    assert echo_of(tmp_path, "small", small) == [
        f"  matrix: dense (200 elements: below {CROSSOVER} a dense matrix is faster)"]
    with h5py.File(tmp_path / "small.h5", "r") as f:
        assert "matrix" not in f["solver"].attrs
    large = TWO_CRACKS.replace("elements = 800,", "elements = 1,").replace(
        "elements = 1200,", f"elements = {CROSSOVER},")
    expected = (f"  matrix: hierarchical ({CROSSOVER + 1} elements, from {CROSSOVER} on a "
                "hierarchical matrix is faster)")
    assert echo_of(tmp_path, "large", large) == [expected]
    with h5py.File(tmp_path / "large.h5", "r") as f:
        assert f["solver"].attrs["matrix"].decode().strip() == "hierarchical"
    lemke = benchmark.CASES["straight"](40, 0, 0) + "&solver lcp_method = 'lemke' /\n"
    refusal = ("  matrix: dense (a hierarchical matrix does not solve this model: "
               "docs/theory/hierarchical.md#what-it-solves)")
    assert echo_of(tmp_path, "lemke", lemke) == [refusal]


#: hierarchical_min_elements of src/run/memory.f90
CROSSOVER = int(next(line.split("=")[1].split("!")[0] for line in
                     (REPO_ROOT / "src" / "run" / "memory.f90").read_text().splitlines()
                     if "integer, parameter :: hierarchical_min_elements" in line))


BAD = [
    ("matrix = 'sparse'", "matrix = 'sparse' is not one of 'auto', 'dense', 'hierarchical'"),
    ("hmatrix_tolerance = 0.0", "hmatrix_tolerance = "),
    ("hmatrix_tolerance = 1.0", "hmatrix_tolerance = "),
    ("hmatrix_leaf_size = 1", "hmatrix_leaf_size = 1 must be at least 2"),
    ("hmatrix_eta = 0.0", "hmatrix_eta = "),
    ("matrix = 'hierarchical', lcp_method = 'lemke'",
     ("matrix = 'hierarchical' does not solve lcp_method = 'lemke'")),
]


@pytest.mark.parametrize("settings, message", BAD, ids=[b[0] for b in BAD])
def test_bad_solver_settings(tmp_path, settings, message):
    """One message naming &solver and the variable, exit 2, no result file."""
    text = benchmark.CASES["straight"](40, 0, 0) + f"&solver {settings} /\n"
    (tmp_path / "bad.nml").write_text(text)
    done = subprocess.run([str(ddc2d_exe()), "bad.nml", "-o", "bad.h5"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2, done.stdout + done.stderr
    errors = [line for line in done.stderr.splitlines() if line.startswith("ddc2d: error: ")]
    assert len(errors) == 1 and "&solver" in errors[0] and message in errors[0], done.stderr
    assert not Path(tmp_path / "bad.h5").exists()


UNSUPPORTED = [
    ("&growth toughness = 1.0, steps = 2 /\n", "fracture growth (&growth)"),
    ("&fracture name = 'crack', x = 3, 4, y = 0, 0, elements = 4, condition = 'traction' /\n",
     "contact elements beside elements of other conditions"),
    (("&fracture name = 'joint', x = 3, 4, y = 0, 0, elements = 4, mu = 0.6, sf = 0,\n"
      "          shear_stiffness = 1e4 /\n"), "elastic joints"),
]


@pytest.mark.parametrize("extra, what", UNSUPPORTED, ids=[u[1] for u in UNSUPPORTED])
def test_what_the_hierarchical_path_does_not_solve_is_refused(tmp_path, extra, what):
    text = (benchmark.CASES["straight"](40, 0, 0) + extra
            + "&solver matrix = 'hierarchical' /\n")
    (tmp_path / "model.nml").write_text(text)
    done = subprocess.run([str(ddc2d_exe()), "model.nml", "-o", "model.h5"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2, done.stdout + done.stderr
    errors = [line for line in done.stderr.splitlines() if line.startswith("ddc2d: error: ")]
    assert len(errors) == 1, done.stderr
    assert f"matrix = 'hierarchical' does not solve {what} yet" in errors[0], errors[0]
    assert not (tmp_path / "model.h5").exists()
