"""The loading history end to end: ddc2d on a &load_path model writes /history, and
scripts/ddc2d-plot draws its hysteresis from exactly those values."""

import subprocess
import sys

import h5py
import numpy as np

from conftest import PLOT_SCRIPT, ddc2d_exe
from ddc2d.plot import data as plot_data
from ddc2d.plot import figures as plot_figures
from ddc2d.reader import STATE_CODES, load_result

# The play-operator crack of docs/theory/earth.md#checks-against-closed-forms, coarse: slips
# above 6 MPa, sticks while the shear is unloaded by less than 12 MPa, slips back below -2 MPa.
PATH_MODEL = """\
&model title = 'play', youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress syy = -10 /
&fracture name = 'fault', x = -1, 1, y = 0, 0, elements = 20, mu = 0.6 /
&load_path sxy = 0, 10, -10, steps = 10, 20 /
"""


def solve(tmp_path, text=PATH_MODEL):
    model = tmp_path / "path.nml"
    model.write_text(text)
    return subprocess.run([str(ddc2d_exe()), str(model), "-o", str(tmp_path / "path.h5")],
                          capture_output=True, text=True, timeout=120)


def test_history_layout_and_last_step(tmp_path):
    done = solve(tmp_path)
    assert done.returncode == 0, done.stderr
    with h5py.File(tmp_path / "path.h5", "r") as f:
        h = f["history"]
        assert h["ds"].shape == h["dn"].shape == h["state"].shape == (31, 20)
        # ddc2d interpolates a + (b - a) (j / n) along each leg, numpy counts in steps of 1:
        # two computations, equal to a few units in the last place of the loads (10 MPa).
        np.testing.assert_allclose(h["sxy"][()], np.r_[np.arange(0, 10.5, 1.0),
                                                        np.arange(9.0, -10.5, -1.0)],
                                   rtol=0.0, atol=1e-13)
        assert "p0" not in h  # only the quantities the path varies beyond the stress
        # The last step's DDs are written to /elements unchanged: exact.
        np.testing.assert_array_equal(f["elements/ds"][()], h["ds"][-1])
        assert np.all(h["certificate_max_complementarity"][()] <= 1e-8)
        assert list(h["leg_steps"][()]) == [10, 20]
        # No slip up to 6 MPa (steps 1-7; at 6 MPa the traction just reaches the strength):
        # the slip increments stay nonbasic in the LCP, so they are exactly zero.
        assert np.all(h["ds"][:7] == 0.0)
        # Sticks from 9 down to -1 MPa (steps 12-22; at -2 MPa it reaches the strength
        # again). Stick keeps both slip increments nonbasic (exactly zero), so the slip
        # stays the loaded one bit for bit.
        assert np.all(h["state"][11:22] == STATE_CODES["stick"])
        np.testing.assert_array_equal(h["ds"][11:22], np.repeat(h["ds"][10:11], 11, axis=0))
        # The last step's load is the path's last vertex itself, sxx and syy are not varied:
        # stored unchanged, exact.
        assert tuple(f.attrs["remote_stress"]) == (0.0, -10.0, -10.0)
        # Per step: tractions of every element, K of every tip, the method of each step.
        assert h["shear_traction"].shape == h["normal_traction"].shape == (31, 20)
        assert h["k1"].shape == h["k2"].shape == (31, 2)
        np.testing.assert_allclose(h["shear_traction"][-1], f["elements/shear_traction"][()],
                                   rtol=0, atol=1e-12 * np.max(np.abs(h["shear_traction"])))
        np.testing.assert_allclose(h["k2"][-1], f["tips/k2"][()], rtol=1e-12)
        assert [m.decode().strip("\x00 ") for m in h["method"][()]] == ["lemke"] * 31
        assert list(h["newton_iterations"][()]) == [0] * 31
    # One progress line per step, flushed as it goes.
    steps = [line for line in done.stdout.splitlines() if line.strip().startswith("step ")]
    assert len(steps) == 31 and steps[-1].strip().startswith("step 31 of 31 (sxy = -10")


def test_path_without_contact_is_bad_input(tmp_path):
    done = solve(tmp_path, PATH_MODEL.replace("mu = 0.6", "condition = 'traction'"))
    assert done.returncode == 2
    assert "a load path needs contact elements" in done.stderr
    assert not (tmp_path / "path.h5").exists()


def test_hysteresis_figure_draws_the_history(tmp_path):
    assert solve(tmp_path).returncode == 0
    proc = subprocess.run([sys.executable, str(PLOT_SCRIPT), str(tmp_path / "path.h5"), "-o",
                           str(tmp_path / "fig"), "--history-elements", "10,20",
                           "--history-steps", "11,31"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "fig" / "path_history.png").read_bytes()[:4] == b"\x89PNG"
    result = load_result(tmp_path / "path.h5")
    with h5py.File(tmp_path / "path.h5", "r") as f:
        ds, sxy = f["history/ds"][()], f["history/sxy"][()]
    elements, steps = plot_data.history_choices(result["history"], [10, 20], [11, 31])
    fig = plot_figures.plot_history(result, elements, steps)
    try:  # the figure draws the stored values themselves: exact
        loop, profile = fig.axes
        (line,) = [ln for ln in loop.get_lines() if ln.get_gid() == "element_20"]
        np.testing.assert_array_equal(line.get_xdata(), sxy)
        np.testing.assert_array_equal(line.get_ydata(), -ds[:, 19])
        (line,) = [ln for ln in profile.get_lines() if ln.get_gid() == "step_31"]
        np.testing.assert_array_equal(line.get_ydata(), -ds[30])
        # Against the distance along the fault (20 elements of 0.1 over 2 m), not the
        # element number: midpoints 0.05 .. 1.95, to rounding of the summed lengths.
        np.testing.assert_allclose(line.get_xdata(), np.arange(0.05, 2.0, 0.1), rtol=0,
                                   atol=1e-12)
        assert profile.get_xlabel() == "distance along the fracture [m]"
        # One arrow per leg at its middle (rows 6 -> 7 and 21 -> 22), pointing the way the
        # load runs: up the first leg, down the unloading one.
        arrows = [a for a in loop.texts if a.get_gid() == "direction"]
        assert [(a.xyann[0], a.xy[0]) for a in arrows[2:]] == [(sxy[5], sxy[6]),
                                                               (sxy[20], sxy[21])]
        assert sxy[6] > sxy[5] and sxy[21] < sxy[20]
    finally:
        plot_figures.plt.close(fig)
    # Defaults: the element of largest slip, the path's vertices. The fault is symmetric:
    # elements 10 and 11 slip equally but for the last bits, which depend on the BLAS
    # kernel (CPU); the tie rule takes the lower, element 10, on every CPU.
    peak = np.max(np.abs(ds), axis=0)
    np.testing.assert_allclose(peak[10], peak[9], rtol=1e-12)  # a tie: what is tested here
    assert plot_data.history_choices(result["history"]) == ([9], [0, 10, 30])


def test_default_steps_of_a_growth_run_stopped_inside_the_path(tmp_path):
    """A growth run that reaches its step limit in load step 4 of the path's 9 (vertices at
    steps 1, 5 and 9): the default steps are those it reached, the path's start and its last
    step, and the figures draw."""
    text = PATH_MODEL.split("&load_path")[0] + (
        "&growth steps = 2, toughness = 0.5, increment = 0.2 /\n"
        "&load_path sxy = 0, 10, 0, steps = 4, 4 /\n")
    assert solve(tmp_path, text).returncode == 0
    result = load_result(tmp_path / "path.h5")
    assert result["history"]["ds"].shape[0] == 4
    assert plot_data.history_choices(result["history"])[1] == [0, 3]
    proc = subprocess.run([sys.executable, str(PLOT_SCRIPT), str(tmp_path / "path.h5"), "-o",
                           str(tmp_path / "fig")], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr


def test_history_step_out_of_range_exits_2(tmp_path):
    assert solve(tmp_path).returncode == 0
    proc = subprocess.run([sys.executable, str(PLOT_SCRIPT), str(tmp_path / "path.h5"), "-o",
                           str(tmp_path / "fig"), "--history-steps", "32"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2
    assert "step 32 is not in 1..31" in proc.stderr


def test_equal_history_profiles_say_so(tmp_path):
    # The fault sticks from step 12 on: its slip profile at step 15 is that of step 11, bit
    # for bit, and would hide under it.
    assert solve(tmp_path).returncode == 0
    result = load_result(tmp_path / "path.h5")
    elements, steps = plot_data.history_choices(result["history"], [10], [11, 15, 31])
    assert plot_data.same_profiles(-result["history"]["ds"][steps]) == [None, 0, None]
    fig = plot_figures.plot_history(result, elements, steps)
    try:
        profile = fig.axes[1]
        labels = [text.get_text() for text in profile.get_legend().get_texts()]
        assert labels[1].endswith("(same as step 11)") and "same" not in labels[0] + labels[2]
        lines = {ln.get_gid(): ln for ln in profile.get_lines()}
        # drawn apart: each its own line style and marker
        assert lines["step_11"].get_linestyle() != lines["step_15"].get_linestyle()
        assert lines["step_11"].get_marker() != lines["step_15"].get_marker()
    finally:
        plot_figures.plt.close(fig)


def test_profiles_of_several_fractures_run_along_each(result_file):
    # The synthetic model: fracture A of four 0.5 elements, B of three; a NaN between them
    # keeps one line from joining them.
    result = load_result(result_file)
    values = np.arange(7.0)
    distance, joined = plot_data.along_fractures(result, values)
    np.testing.assert_allclose(distance, [0.25, 0.75, 1.25, 1.75, np.nan, 0.25, 0.75, 1.25],
                               rtol=1e-12)
    np.testing.assert_array_equal(joined, [0, 1, 2, 3, np.nan, 4, 5, 6])
