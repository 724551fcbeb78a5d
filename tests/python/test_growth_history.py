"""Fracture growth along a loading history
(docs/theory/growth.md#growth-along-a-loading-history): wings off a closed sliding flaw (the
flaw of docs/theory/growth.md#convergence-with-the-increment: 2 m at 45 degrees, mu 0.6,
toughness 2) under an axial load syy rising from -5 to -100 MPa at sxx = -5 MPa.

- The wings do not depend on how finely the same path is divided: 5 and 20 load steps end
  with the same wing length within 10 %.
- Growth starts at the load step where a fixed-load run at that level first grows (the
  criterion reaches the toughness and the kink opens), with the same K_eq.
- After a reversal (sxx and syy swap) the flaw slips back, the wings close and nothing grows;
  the element count never falls.
- /history records every load step's geometry: its element count, the grown length per tip
  (the sum of /growth's lengths up to that step) and rows that follow the elements."""

import subprocess

import h5py
import numpy as np
import pytest

from conftest import ddc2d_exe

FLAW = """\
&model youngs_modulus = 50000.0, poissons_ratio = 0.25, length_unit = 'm', stress_unit = 'MPa' /
&remote_stress sxx = -5.0, syy = -5.0 /
&fracture name = 'flaw', x = -0.70710678, 0.70710678, y = -0.70710678, 0.70710678,
          elements = 40, condition = 'contact', mu = 0.6, sf = 0.0 /
"""
GROWTH = "&growth steps = 40, toughness = 2.0, increment = 0.1 {extra}/\n"
TOUGHNESS = 2.0
OPEN = 3


def run(folder, name, text):
    """Solve a model; the result file's path."""
    model = folder / f"{name}.nml"
    model.write_text(text)
    out = folder / f"{name}.h5"
    done = subprocess.run([str(ddc2d_exe()), str(model), "-o", str(out)], capture_output=True,
                          text=True, timeout=900)
    assert done.returncode == 0, done.stdout + done.stderr
    return out, done.stdout


def rising(steps):
    return FLAW + f"&load_path syy = -5, -100, steps = {steps} /\n" + GROWTH.format(extra="")


@pytest.fixture(scope="module")
def rising_runs(tmp_path_factory):
    """The rising load in 5 and in 20 steps: {steps: (result file, stdout)}."""
    folder = tmp_path_factory.mktemp("rising")
    return {n: run(folder, f"rising{n}", rising(n)) for n in (5, 20)}


def wing_lengths(path):
    with h5py.File(path, "r") as f:
        return f["history/grown_length"][-1, :]


def test_wings_do_not_depend_on_the_division_of_the_path(rising_runs):
    coarse = wing_lengths(rising_runs[5][0])
    fine = wing_lengths(rising_runs[20][0])
    assert coarse.shape == fine.shape == (2,)
    # The wings grew (far beyond the first increment) and arrested.
    assert np.all(fine >= 0.5)
    np.testing.assert_allclose(coarse, fine, rtol=0.10)
    # The model is point-symmetric, and so are its wings.
    np.testing.assert_allclose(fine[0], fine[1], rtol=1e-6)
    for path, _ in rising_runs.values():
        with h5py.File(path, "r") as f:
            assert f["growth"].attrs["end_reason"] == b"arrested"


def test_history_follows_the_growing_geometry(rising_runs):
    path, stdout = rising_runs[20]
    with h5py.File(path, "r") as f:
        h, g = f["history"], f["growth"]
        count = h["element_count"][()]
        n = f["elements/x_begin"].shape[0]
        assert count.shape == (21,) and count[-1] == n and count[0] == 40
        assert np.all(np.diff(count) >= 0)
        assert h["ds"].shape == (21, n) and h["state"].shape == (21, n)
        created = f["elements/created_step"][()]
        load_step = g["load_step"][()]
        step = g["step"][()]
        assert np.all(np.diff(load_step) >= 0) and np.all(np.diff(step) >= 0)
        # Growth steps are counted where a tip grew: 1 .. steps_taken, each with growth and new
        # elements; the check that ends a load step uses up no number (its records carry the
        # next one), the last that of the arrest.
        taken = int(g.attrs["steps_taken"])
        grew = g["length"][()] > 0
        assert sorted(set(step[grew])) == list(range(1, taken + 1))
        assert sorted(set(created[created > 0])) == list(range(1, taken + 1))
        assert step.max() == taken + 1 and np.all(~grew[step == taken + 1])
        # An element made in growth step s has no value before the load step of s.
        made_in = {s: ls for s, ls, g_ in zip(step, load_step, grew) if g_}
        for e in np.flatnonzero(created > 0):
            first = made_in[created[e]] - 1
            assert np.all(np.isnan(h["ds"][:first, e])), e
            assert np.all(h["state"][:first, e] == -1), e
            assert np.isfinite(h["ds"][first, e]), e
        # The grown length per tip is the sum of the records' lengths up to each load step.
        grown = h["grown_length"][()]
        for t, (fid, end) in enumerate(zip(h["tip_fracture_id"][()], h["tip_end"][()])):
            mine = (g["fracture_id"][()] == fid) & (g["end"][()] == end)
            for k in range(21):
                expected = g["length"][mine & (load_step <= k + 1)].sum()
                assert grown[k, t] == pytest.approx(expected, abs=1e-12)
        # K of the final tips at every load step; the last one is that of /tips.
        np.testing.assert_allclose(h["k1"][-1, :], f["tips/k1"][()], rtol=1e-9)
    assert "load step 21 of 21 (syy = -100" in stdout
    assert "  load step 8 (syy = -38.25" in stdout
    # A line per growth step in which a tip grew, none for a load step without growth
    assert "0 tip(s) grew" not in stdout
    lines = [line for line in stdout.splitlines() if line.startswith("growth step ")]
    assert [int(line.split()[2].rstrip(":")) for line in lines] == list(range(1, taken + 1))
    first = [line for line in stdout.splitlines() if "load step 1 of 21 (" in line]
    assert len(first) == 2 and ": 0 growth steps, grown length 0" in first[1], first


def test_growth_starts_where_a_fixed_load_run_grows(rising_runs, tmp_path):
    path, _ = rising_runs[20]
    with h5py.File(path, "r") as f:
        g = f["growth"]
        syy = f["history/syy"][()]
        load_step, reason = g["load_step"][()], g["reason"][()]
        first = int(load_step[reason == 0].min())
        k_eq = {int(k): g["k_eq"][load_step == k][0] for k in np.unique(load_step)}
    # A fixed-load run at each level, one growth step: K_eq of the input's tips, and whether
    # they grow (critical, and the kink opens: below some load the 70.5 degree kink of the
    # closed flaw is itself closed, reason 6, in both runs).
    grows = []
    for k, level in enumerate(syy, start=1):
        text = FLAW.replace("syy = -5.0", f"syy = {float(level)!r}") + GROWTH.format(extra="")
        out, _ = run(tmp_path, f"level{k}", text.replace("steps = 40", "steps = 1"))
        with h5py.File(out, "r") as f:
            grows.append(bool(np.any(f["growth/reason"][()] == 0)))
            # The flaw slides whole at every level: its K does not depend on the path.
            if k <= first:
                assert f["growth/k_eq"][0] == pytest.approx(k_eq[k], rel=1e-6, abs=1e-9)
                critical = f["growth/k_eq"][0] >= TOUGHNESS
    assert 1 < first < len(syy)
    assert critical
    assert grows.index(True) + 1 == first


def test_reversal_closes_the_wings_and_nothing_grows(tmp_path):
    text = (FLAW + "&load_path sxx = -5, -5, -100, syy = -5, -100, -5, steps = 5, 5 /\n"
            + GROWTH.format(extra=""))
    path, stdout = run(tmp_path, "reversal", text)
    with h5py.File(path, "r") as f:
        h, g = f["history"], f["growth"]
        count = h["element_count"][()]
        peak = 5  # 0-based: load step 6, syy = -100
        assert count[peak] > 40
        assert np.all(count[peak:] == count[peak])
        assert not np.any((g["load_step"][()] > peak + 1) & (g["reason"][()] == 0))
        wings = f["elements/created_step"][()] > 0
        state = h["state"][()]
        assert np.sum(state[peak, wings] == OPEN) > 0
        assert np.sum(state[-1, wings] == OPEN) == 0
        # The flaw slips back: its mean slip changes sign.
        ds = h["ds"][()]
        assert np.mean(ds[peak, ~wings]) * np.mean(ds[-1, ~wings]) < 0
    assert "load step 11 (sxx = -100" in stdout and ": nothing grew" in stdout
