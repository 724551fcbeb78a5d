"""The strengths in force made visible, end to end: ddc2d writes the friction, cohesion and
tensile strength in force of every step of a loading history (/history) and the elastic
DDs of elastic joints (/elements), and ddc2d-plot's profile figure draws exactly those
values (docs/theory/strength.md)."""

import re
import subprocess
import sys

import h5py
import numpy as np

from conftest import PLOT_SCRIPT, ddc2d_exe, solve_text
from ddc2d import open_result
from ddc2d.plot import data as plot_data
from ddc2d.plot import figures as plot_figures
from ddc2d.reader import load_result

# A slip-weakening fault (mu 0.6 -> 0.3 over d_c = 5e-4 m) under s_n = -10 MPa, sheared past
# its peak strength of 6 MPa: sxy 0 -> 7.5 in 10 steps (0.75 MPa each).
D_C = 5.0e-4
WEAKENING = f"""\
&model title = 'weakening', youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress syy = -10 /
&fracture name = 'fault', x = -1, 1, y = 0, 0, elements = 20, mu = 0.6, mu_dynamic = 0.3,
          slip_weakening_distance = {D_C} /
&load_path sxy = 0, 7.5, steps = 10 /
"""
COULOMB = WEAKENING.replace("mu_dynamic = 0.3,", "").replace(
    f"slip_weakening_distance = {D_C}", "")
# A joint of shear stiffness 1e5 MPa/m (normal rigid) sheared past its strength.
KS = 1.0e5
JOINT = f"""\
&model title = 'joint', youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress syy = -10, sxy = 7 /
&fracture name = 'joint', x = -1, 1, y = 0, 0, elements = 20, mu = 0.6,
          shear_stiffness = {KS:g} /
"""
# An intact fault of tensile strength 2 MPa (cohesion 5 MPa) under a tension of 3 MPa: it
# opens, and the tensile strength in force drops to 0 where it does.
TENSILE = """\
&model title = 'tensile', youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress syy = 3 /
&fracture name = 'fault', x = -1, 1, y = 0, 0, elements = 20, mu = 0.6, sf = 5,
          tensile_strength = 2 /
"""


def drawn_profile(path):
    """The result at `path`, its first fracture's profile data and the profile figure's
    lines by gid, and the figure's number of panels (the figure is closed)."""
    result = load_result(path)
    fracture = result["fractures"][0]
    profile = plot_data.fracture_profile(result["elements"], fracture["first"],
                                         fracture["last"])
    fig = plot_figures.plot_profile(result, fracture, profile)
    try:
        lines = {line.get_gid(): line for ax in fig.axes for line in ax.get_lines()
                 if line.get_gid()}
        return result, profile, lines, len(fig.axes)
    finally:
        plot_figures.plt.close(fig)


def test_history_holds_the_friction_of_the_slip_weakening_law(tmp_path):
    path = solve_text(tmp_path, "weakening", WEAKENING)
    with h5py.File(path, "r") as f:
        h = f["history"]
        mu, sf, t = (h[key][()] for key in ("mu_in_force", "sf_in_force",
                                             "tensile_strength_in_force"))
        assert mu.shape == sf.shape == t.shape == (11, 20)
        units = h["sf_in_force"].attrs["units"]
        assert (units.decode() if isinstance(units, bytes) else units).strip() == "MPa"
        # The law of the slip path written in the same steps (the sum of |ds| increments):
        # the fixed point stops when mu changes by less than 1e-12.
        path_length = np.cumsum(np.abs(np.diff(h["ds"][()], axis=0, prepend=0.0)), axis=0)
        np.testing.assert_allclose(mu, 0.6 - 0.3 * np.minimum(path_length / D_C, 1.0),
                                   rtol=0.0, atol=1e-10)
        assert np.all(mu[:8] == 0.6)  # intact up to sxy = 5.25 < 6
        assert mu[-1].min() < 0.55 and mu[-1].max() - mu[-1].min() > 0.03
        assert np.all(sf == 0.0) and np.all(t == 0.0)
        # The last step is /elements: exact.
        np.testing.assert_array_equal(mu[-1], f["elements/mu_in_force"][()])
    coulomb = solve_text(tmp_path, "coulomb", COULOMB)
    with h5py.File(coulomb, "r") as f:  # Coulomb's strengths cannot change: not written
        assert "mu_in_force" not in f["history"] and "sf_in_force" not in f["history"]
    result = load_result(path)
    assert result["history"]["mu_in_force"].shape == (11, 20)
    # Result.to_xarray: the strengths in force on (step, element), with their units.
    history = open_result(path).to_xarray("history")
    with h5py.File(path, "r") as f:
        for key in ("mu_in_force", "sf_in_force", "tensile_strength_in_force"):
            assert history[key].dims == ("step", "element"), key
            np.testing.assert_array_equal(history[key].values, f["history"][key][()])
    assert history["sf_in_force"].attrs["units"] == "MPa"


def test_progress_line_counts_the_weakening_solves(tmp_path):
    (tmp_path / "w.nml").write_text(WEAKENING)
    done = subprocess.run([str(ddc2d_exe()), "w.nml", "-o", "w.h5"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    steps = [line.strip() for line in done.stdout.splitlines()
             if line.strip().startswith("step ")]
    assert len(steps) == 11
    assert " solves, " not in steps[0]  # nothing slips: one solve
    # Slip weakening past the peak: the fixed point solves more than once.
    last = re.fullmatch(r"step 11 of 11 \(sxy = 7\.50*\): lemke, \d+ pivots in (\d+) solves, "
                        r"[\d.]+ s", steps[-1])
    assert last and int(last.group(1)) > 1, steps[-1]


def test_profile_draws_the_friction_in_force(tmp_path):
    result, profile, lines, panels = drawn_profile(solve_text(tmp_path, "weakening",
                                                              WEAKENING))
    assert [key for key, *_ in plot_data.strength_panels(result, result["fractures"][0])] \
        == ["friction"]
    assert panels == 2  # slip, friction (nothing opens)
    np.testing.assert_array_equal(lines["friction:$\\mu$ in force"].get_ydata(),
                                  result["elements"]["mu_in_force"])
    np.testing.assert_array_equal(lines["friction:$\\mu$ as given"].get_ydata(),
                                  np.full(20, 0.6))
    np.testing.assert_array_equal(lines["friction:$\\mu$ in force"].get_xdata(),
                                  profile["distance"])


def test_profile_draws_cohesion_and_tensile_strength(tmp_path):
    result, _, lines, _ = drawn_profile(solve_text(tmp_path, "tensile", TENSILE))
    t = lines["strength:tensile strength $T$ in force"].get_ydata()
    np.testing.assert_array_equal(t, result["elements"]["tensile_strength_in_force"])
    assert np.all(t[result["elements"]["state"] == 3] == 0.0) and np.any(t == 0.0)
    np.testing.assert_array_equal(lines["strength:cohesion $S_f$ in force"].get_ydata(),
                                  result["elements"]["sf_in_force"])
    assert "friction:$\\mu$ in force" not in lines  # no slip weakening: no panel


def test_joint_elastic_dds_and_their_panel(tmp_path):
    path = solve_text(tmp_path, "joint", JOINT)
    with h5py.File(path, "r") as f:
        e = {key: f["elements"][key][()] for key in ("ds", "ds_elastic", "dn_elastic",
                                                     "shear_traction")}
    # D_e = -t / k_s: the element's own traction over its stiffness (1e-12); normal rigid.
    np.testing.assert_allclose(e["ds_elastic"], -e["shear_traction"] / KS, rtol=1e-12,
                               atol=0.0)
    assert np.all(e["dn_elastic"] == 0.0)
    _, _, lines, _ = drawn_profile(path)
    np.testing.assert_array_equal(lines["joint:elastic slip"].get_ydata(), -e["ds_elastic"])
    np.testing.assert_array_equal(lines["joint:plastic slip"].get_ydata(),
                                  -e["ds"] + e["ds_elastic"])
    # A fracture without joints has no such datasets and no such panel.
    rigid = solve_text(tmp_path, "rigid", JOINT.replace(f"shear_stiffness = {KS:g}", ""))
    with h5py.File(rigid, "r") as f:
        assert "ds_elastic" not in f["elements"]
    _, _, lines, panels = drawn_profile(rigid)
    assert panels == 1 and not any(gid.startswith("joint:") for gid in lines)


def test_strength_panels_leave_out_what_a_fracture_lacks():
    # Residual cohesion alone: the cohesion is drawn, the tensile strength (0 throughout,
    # given and in force) is not, nor the friction (no slip weakening).
    ones = np.ones(3)
    elements = {"mu": 0.6 * ones, "mu_dynamic": 0.6 * ones, "mu_in_force": 0.6 * ones,
                "sf": 6.0 * ones, "sf_residual": ones, "sf_in_force": np.array([1.0, 6.0, 6.0]),
                "tensile_strength": 0.0 * ones, "tensile_strength_in_force": 0.0 * ones}
    panels = plot_data.strength_panels({"elements": elements}, {"first": 1, "last": 3})
    assert [(key, [text for text, *_ in lines]) for key, _, _, lines in panels] == \
        [("strength", ["cohesion $S_f$"])]
    np.testing.assert_array_equal(panels[0][3][0][1], [1.0, 6.0, 6.0])


def test_history_strengths_figure(tmp_path):
    path = solve_text(tmp_path, "weakening", WEAKENING)
    done = subprocess.run([sys.executable, str(PLOT_SCRIPT), str(path), "-o",
                           str(tmp_path / "fig"), "--history-elements", "10"],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "fig" / "weakening_history_strengths.png").read_bytes()[:4] == b"\x89PNG"
    coulomb = solve_text(tmp_path, "coulomb", COULOMB)
    done = subprocess.run([sys.executable, str(PLOT_SCRIPT), str(coulomb), "-o",
                           str(tmp_path / "fig")], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert not (tmp_path / "fig" / "coulomb_history_strengths.png").exists()
    result = load_result(path)
    fig = plot_figures.plot_history_strengths(result, [9])
    try:  # the stored values themselves: exact
        lines = {line.get_gid(): line for ax in fig.axes for line in ax.get_lines()}
        with h5py.File(path, "r") as f:
            for key in ("mu_in_force", "sf_in_force", "tensile_strength_in_force"):
                np.testing.assert_array_equal(lines[f"{key}:element_10"].get_ydata(),
                                              f["history"][key][:, 9])
                np.testing.assert_array_equal(lines[f"{key}:element_10"].get_xdata(),
                                              f["history/sxy"][()])
    finally:
        plot_figures.plt.close(fig)
