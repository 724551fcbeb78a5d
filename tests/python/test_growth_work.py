"""The work criterion of fracture growth (docs/theory/growth.md#the-work-criterion): the
efficiency E = dW_ext / da of trial kinks against closed forms (E / 2 = K^2 (1 - nu^2) / E_young
for frictionless faces), the kink of an inclined crack against the maximum energy release rate
direction of a short kink (Nuismer 1975), a frictional fault that grows in shear, 1 and 2
threads, and bad input."""

import os
import re
import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import PLOT_SCRIPT, ddc2d_exe
from ddc2d.plot import figures as plot_figures
from ddc2d.reader import load_result

NU = 0.25
E_YOUNG = 1.0
HALF_LENGTH = 1.0


def crack_model(stress, elements, growth, mu=0.0):
    """A straight crack from (-1, 0) to (1, 0) under remote `stress`, growing by 'work'."""
    return (f"&model youngs_modulus = {E_YOUNG}, poissons_ratio = {NU} /\n"
            f"&remote_stress {stress} /\n"
            f"&fracture name = 'crack', x = -1, 1, y = 0, 0, elements = {elements}, "
            f"mu = {mu} /\n"
            f"&growth steps = 1, toughness = 1.0e-6, increment = 0.02, criterion = 'work', "
            f"tips = 'most_critical', {growth} /\n")


def run(folder, text, threads=1):
    model = folder / "model.nml"
    model.write_text(text)
    out = folder / f"model{threads}.h5"
    # OpenBLAS on one thread: its blocking depends on its thread count; ddc2d's own loops
    # are what the thread count varies.
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OPENBLAS_NUM_THREADS="1")
    done = subprocess.run([str(ddc2d_exe()), str(model), "-o", str(out)], capture_output=True,
                          text=True, timeout=600, env=env)
    return done, out


def growth_of(path):
    with h5py.File(path, "r") as f:
        g = f["growth"]
        t = g["trials"]
        record = {k: g[k][()] for k in ("end", "k1", "k2", "angle", "efficiency", "reason")}
        record["threshold"] = g.attrs["work_threshold"]
        record["trials"] = {k: t[k][()] for k in t}
    return record


def energy_release_rate(k):
    """K^2 (1 - nu^2) / E_young (plane strain)."""
    return k**2 * (1.0 - NU**2) / E_YOUNG


def test_mode_one_crack_releases_g_and_grows_straight(tmp_path):
    # Increment 0.02: 1 % of the crack length 2.
    done, out = run(tmp_path, crack_model("syy = 1.0e-3", 200, "angle_range = 10"))
    assert done.returncode == 0, done.stdout + done.stderr
    g = growth_of(out)
    expected = energy_release_rate(1.0e-3 * np.sqrt(np.pi * HALF_LENGTH))
    grew = g["reason"] == 0
    assert grew.sum() == 1
    assert g["efficiency"][grew][0] / 2 == pytest.approx(expected, rel=0.02)
    assert abs(g["angle"][grew][0]) < 1e-3
    # The default threshold is 2 G_c = 2 K_Ic^2 (1 - nu^2) / E_young.
    assert g["threshold"] == pytest.approx(2 * energy_release_rate(1.0e-6), rel=1e-12)


def test_frictionless_mode_two_crack_releases_g(tmp_path):
    done, out = run(tmp_path, crack_model("sxy = 1.0e-3", 200,
                                          "angle_range = 5, angle_step = 5"))
    assert done.returncode == 0, done.stdout + done.stderr
    trials = growth_of(out)["trials"]
    straight = trials["trial_angle"] == 0.0
    expected = energy_release_rate(1.0e-3 * np.sqrt(np.pi * HALF_LENGTH))
    assert straight.sum() == 2
    # The straight trial slips (state 1) and releases the mode II energy.
    assert list(trials["trial_state"][straight]) == [1, 1]
    assert trials["trial_efficiency"][straight] / 2 == pytest.approx([expected] * 2, rel=0.02)


def nuismer_angle(k1, k2):
    """Kink angle [degree] of the largest energy release rate of an infinitesimal kink whose
    K are the parent tip's stress factors at the kink angle (Nuismer 1975): the maximum of
    k_tt^2 + k_rt^2 over theta in [-90, 90] degrees, on a 0.001 degree grid."""
    theta = np.radians(np.linspace(-90.0, 90.0, 180001))
    c, s = np.cos(theta / 2), np.sin(theta)
    k_tt = c * (k1 * c**2 - 1.5 * k2 * s)
    k_rt = 0.5 * c * (k1 * s + k2 * (3 * np.cos(theta) - 1))
    return np.degrees(theta[np.argmax(k_tt**2 + k_rt**2)])


def test_inclined_crack_kinks_towards_the_largest_energy_release(tmp_path):
    # Uniaxial tension 1e-3 at 45 degrees to the crack: K_I = K_II.
    done, out = run(tmp_path, crack_model("sxx = 0.5e-3, syy = 0.5e-3, sxy = 0.5e-3", 400,
                                          "angle_range = 65"))
    assert done.returncode == 0, done.stdout + done.stderr
    g = growth_of(out)
    grew = g["reason"] == 0
    reference = nuismer_angle(g["k1"][grew][0], g["k2"][grew][0])
    assert reference == pytest.approx(-53.13, abs=0.01)
    assert abs(g["angle"][grew][0] - reference) <= 3.0


FAULT = """\
&model youngs_modulus = 1.0e4, poissons_ratio = 0.25 /
&remote_stress sxx = -100, syy = -100, sxy = 40 /
&fracture name = 'fault', x = -1, 1, y = 0, 0, elements = 40, mu = 0.3 /
&growth steps = 1, toughness = 1.0e-3, increment = 0.1, criterion = 'work', new_mu = 0.3,
        angle_range = 85 /
"""


def test_frictional_fault_grows_in_shear(tmp_path):
    done, out = run(tmp_path, FAULT)
    assert done.returncode == 0, done.stdout + done.stderr
    g = growth_of(out)
    # No trial kink opens under the confining pressure; both tips grow by slipping kinks.
    assert not np.any(g["trials"]["trial_state"] == 2)
    assert list(g["reason"]) == [0, 0]
    assert np.all(np.abs(g["angle"]) <= 30.0)


def test_one_and_two_threads_agree(tmp_path):
    one_done, one = run(tmp_path, FAULT, threads=1)
    two_done, two = run(tmp_path, FAULT, threads=2)
    assert one_done.returncode == 0 and two_done.returncode == 0
    a, b = growth_of(one), growth_of(two)
    for key in ("angle", "efficiency"):
        np.testing.assert_array_equal(a[key], b[key])
    for key in a["trials"]:
        np.testing.assert_array_equal(a["trials"][key], b["trials"][key])


SLIDING_FLAW = """\
&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /
&remote_stress sxx = -2.0, syy = -100.0 /
&fracture name = 'flaw', x = -0.70710678, 0.70710678, y = -0.70710678, 0.70710678,
          elements = 20, condition = 'contact', mu = 0.6, sf = 1.0 /
&growth steps = 2, toughness = 2.0, new_sf = 0.0, criterion = 'work', {options} /
"""

INCLINED_CRACK = crack_model("sxx = 0.5e-3, syy = 0.5e-3, sxy = 0.5e-3", 40,
                             "{options}").replace("tips = 'most_critical', ", "")

# Each model, and the largest share of the grid's trials the seeded search may take: the
# climbs take 3 trials and one per angle step walked (measured 0.16, 0.28, 0.22, 0.39: under
# 'opening' the sliding flaw's climb walks from the estimate's 70 degrees to the last kink
# that opens, near 20).
SEARCHED_MODELS = {
    "inclined crack in tension": (INCLINED_CRACK, 0.25),
    "frictional fault": (FAULT.replace("angle_range = 85", "angle_range = 85, {options}"), 0.35),
    "sliding flaw, any": (SLIDING_FLAW.replace("{options}", "work_mode = 'any', {options}"),
                          0.3),
    "sliding flaw, opening": (SLIDING_FLAW.replace("{options}",
                                                   "work_mode = 'opening', {options}"), 0.5),
}


@pytest.mark.parametrize("name", SEARCHED_MODELS)
def test_seeded_search_chooses_the_grid_angles_in_fewer_trials(tmp_path, name):
    # The climb from the kinked-crack estimate (and from straight ahead under 'any') against
    # every angle of the range: the same reasons, angles within the angle step (5 degrees),
    # and fewer trials.
    text, largest_share = SEARCHED_MODELS[name]
    found = {}
    for search in ("seeded", "grid"):
        (tmp_path / search).mkdir()
        done, out = run(tmp_path / search, text.replace("{options}",
                                                         f"angle_search = '{search}'"))
        assert done.returncode == 0, done.stdout + done.stderr
        found[search] = growth_of(out)
    seeded, grid = found["seeded"], found["grid"]
    np.testing.assert_array_equal(seeded["reason"], grid["reason"])
    assert np.all(np.abs(seeded["angle"] - grid["angle"]) <= 5.0), (seeded["angle"],
                                                                    grid["angle"])
    assert (len(seeded["trials"]["trial_angle"])
            <= largest_share * len(grid["trials"]["trial_angle"]))


def test_mode_one_crack_takes_three_trials_per_tip(tmp_path):
    # The estimate is straight ahead; its neighbours a step either way bracket it, and the
    # parabola's vertex lies on it: no fourth solve.
    done, out = run(tmp_path, crack_model("syy = 1.0e-3", 40, "tips = 'all'")
                    .replace("tips = 'most_critical', ", ""))
    assert done.returncode == 0, done.stdout + done.stderr
    trials = growth_of(out)["trials"]
    for record in (1, 2):
        angles = trials["trial_angle"][trials["trial_record"] == record]
        np.testing.assert_allclose(np.sort(angles), [-5.0, 0.0, 5.0], atol=1e-12)


def test_opening_mode_grows_opening_kinks_and_any_mode_notes_friction(tmp_path):
    # The sliding flaw's most productive kink slips on its frictional new faces under 'any'
    # (the note says so, /growth/slip_share above 1/2); under 'opening' the chosen kink opens.
    chosen_state = {}
    for mode in ("any", "opening"):
        (tmp_path / mode).mkdir()
        done, out = run(tmp_path / mode,
                        SLIDING_FLAW.replace("{options}", f"work_mode = '{mode}'"))
        assert done.returncode == 0, done.stdout + done.stderr
        g = growth_of(out)
        with h5py.File(out, "r") as f:
            share = f["growth/slip_share"][()]
            assert f["growth"].attrs["work_mode"].decode() == mode
        trials = g["trials"]
        states = []
        for record, angle in enumerate(g["angle"], start=1):
            mine = (trials["trial_record"] == record) & np.isclose(trials["trial_angle"], angle,
                                                                   rtol=0, atol=1e-9)
            states.append(int(trials["trial_state"][mine][0]))
        chosen_state[mode] = states
        notes = [line for line in done.stdout.splitlines() if "slip of frictional faces" in line]
        assert np.all(share > 0.5)
        assert len(notes) == 1 and notes[0].strip().startswith("note: 4 of 4 kinks"), notes
        assert ("work_mode = 'opening' grows" in notes[0]) == (mode == "any"), notes[0]
    assert chosen_state["any"] == [1, 1, 1, 1]
    assert chosen_state["opening"] == [2, 2, 2, 2]


@pytest.mark.parametrize("setting, message", [
    ("criterion = 'works'", "criterion = 'works' is not one of 'mts', 'work'"),
    ("criterion = 'work', work_mode = 'wings'",
     "work_mode = 'wings' is not one of 'any', 'opening'"),
    ("criterion = 'work', angle_search = 'full'",
     "angle_search = 'full' is not one of 'seeded', 'grid'"),
    ("criterion = 'work', angle_range = 180", "angle_range = 180.000 must lie in (0, 180)"),
    ("criterion = 'work', angle_range = 0", "angle_range = 0.00000 must lie in (0, 180)"),
    ("criterion = 'work', angle_step = 0", "angle_step = 0.00000 must be positive"),
    ("criterion = 'work', angle_step = -5", "angle_step = -5.00000 must be positive"),
    # Not finite: reported, not compared (Debug traps an ordered comparison with NaN).
    ("criterion = 'work', angle_step = NaN", "angle_step = NaN is not a finite number"),
    ("criterion = 'work', angle_range = -Inf", "angle_range = -Inf is not a finite number"),
])
def test_bad_work_input(tmp_path, setting, message):
    text = ("&model youngs_modulus = 1.0, poissons_ratio = 0.25 /\n&remote_stress syy = 1 /\n"
            "&fracture name = 'crack', x = -1, 1, y = 0, 0, elements = 10, mu = 0 /\n"
            f"&growth steps = 1, toughness = 1, {setting} /\n")
    done, _ = run(tmp_path, text)
    assert done.returncode == 2
    errors = [line for line in done.stderr.splitlines() if "error" in line]
    assert len(errors) == 1 and message in errors[0], done.stderr


def echoed(stdout, name):
    """The number after `name = ` in the input echo, and the rest of its line."""
    for line in stdout.splitlines():
        match = re.search(rf"\b{name} = ([-+0-9.eE]+)(.*)", line)
        if match:
            return float(match.group(1)), match.group(2)
    return None


@pytest.mark.parametrize("criterion", ["work", "mts"])
def test_echo_names_the_trial_angles_and_threshold(tmp_path, criterion):
    # Given: the threshold as given; by default: 2 K_Ic^2 (1 - nu^2) / E, said so. Other
    # criteria echo none of them.
    for given in ("", ", work_threshold = 0.25"):
        text = ("&model youngs_modulus = 2.0, poissons_ratio = 0.25 /\n"
                "&remote_stress syy = 1 /\n"
                "&fracture name = 'crack', x = -1, 1, y = 0, 0, elements = 10, mu = 0 /\n"
                f"&growth steps = 1, toughness = 1, criterion = '{criterion}', "
                f"angle_range = 30, angle_step = 7.5{given} /\n")
        done, _ = run(tmp_path, text)
        assert done.returncode == 0, done.stdout + done.stderr
        names = ("angle_range", "angle_step", "work_threshold")
        if criterion == "mts":
            assert all(echoed(done.stdout, name) is None for name in names), done.stdout
            continue
        angle_range, rest = echoed(done.stdout, "angle_range")
        assert angle_range == 30.0 and rest.startswith(" degrees, angle_step = "), rest
        assert echoed(done.stdout, "angle_step")[0] == 7.5
        assert "    work_mode = 'any', angle_search = 'seeded'" in done.stdout.splitlines()
        threshold, rest = echoed(done.stdout, "work_threshold")
        if given:
            assert threshold == 0.25 and "default" not in rest
        else:
            assert threshold == pytest.approx(2 * (1 - NU**2) / 2.0, rel=1e-15)
            assert rest.endswith(" (default: 2 toughness^2 (1 - nu^2) / E)")


def test_trials_figure_draws_the_stored_trials(tmp_path):
    done, out = run(tmp_path, FAULT)
    assert done.returncode == 0, done.stdout + done.stderr
    proc = subprocess.run([sys.executable, str(PLOT_SCRIPT), str(out), "-o",
                           str(tmp_path / "fig")], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "fig" / "model1_growth_trials.png").read_bytes()[:4] == b"\x89PNG"
    result = load_result(out)
    g = growth_of(out)
    fig = plot_figures.plot_growth_trials(result)
    try:
        lines = {line.get_gid(): line for line in fig.axes[0].get_lines() if line.get_gid()}
        trials = g["trials"]
        for record, label in ((1, "step 1, fault begin"), (2, "step 1, fault end")):
            mine = trials["trial_record"] == record
            order = np.argsort(trials["trial_angle"][mine], kind="stable")
            line = lines[f"efficiency:{label}"]
            np.testing.assert_array_equal(line.get_xdata(), trials["trial_angle"][mine][order])
            candidate = np.isin(trials["trial_state"][mine][order], (1, 2))
            np.testing.assert_array_equal(line.get_ydata()[candidate],
                                          trials["trial_efficiency"][mine][order][candidate])
            assert np.all(np.isnan(line.get_ydata()[~candidate]))
            chosen = lines[f"chosen:{label}"]
            np.testing.assert_array_equal(chosen.get_xdata(), [g["angle"][record - 1]])
        np.testing.assert_array_equal(lines["work_threshold"].get_ydata(),
                                      [g["threshold"]] * 2)
    finally:
        plot_figures.plt.close(fig)


def test_the_search_starts_from_the_estimate_of_the_open_part_of_k(tmp_path):
    # A traction crack pressed shut (K_I = -K_II < 0): the estimate takes max(K_I, 0), as
    # the MTS angle does, so the first trial is the pure mode II kink at -70.53 degrees
    # (with the negative K_I it would be near -5). Under 'opening' no straight trial comes
    # first.
    text = ("&model youngs_modulus = 1.0, poissons_ratio = 0.25 /\n"
            "&remote_stress syy = -1.0e-3, sxy = 1.0e-3 /\n"
            "&fracture name = 'crack', x = -1, 1, y = 0, 0, elements = 20, "
            "condition = 'traction', bc_s = 0, bc_n = 0 /\n"
            "&growth steps = 1, toughness = 1.0e-6, increment = 0.1, criterion = 'work', "
            "work_mode = 'opening' /\n")
    done, out = run(tmp_path, text)
    assert done.returncode == 0, done.stdout + done.stderr
    g = growth_of(out)
    assert g["k1"][0] < 0.0 and g["k2"][0] == pytest.approx(-g["k1"][0], rel=1e-2)
    trials = g["trials"]
    for record in (1, 2):
        first = trials["trial_angle"][trials["trial_record"] == record][0]
        assert abs(abs(first) - 70.53) < 0.01, first


def test_a_grid_search_result_is_not_resumed_by_the_seeded_search(tmp_path):
    # angle_search is in the model's fingerprint: its steps were searched another way.
    (tmp_path / "grid").mkdir()
    done, old = run(tmp_path / "grid", FAULT.replace("angle_range = 85",
                                                      "angle_range = 85, angle_search = 'grid'"))
    assert done.returncode == 0, done.stderr
    (tmp_path / "two.nml").write_text(FAULT.replace("steps = 1,", "steps = 2,"))
    resumed = subprocess.run([str(ddc2d_exe()), str(tmp_path / "two.nml"), "--resume", str(old),
                              "-o", str(tmp_path / "resumed.h5")], capture_output=True,
                             text=True, timeout=600)
    assert resumed.returncode == 2
    assert "is the result of another model" in resumed.stderr, resumed.stderr
    assert not (tmp_path / "resumed.h5").exists()


def test_resumed_run_goes_on_with_its_trials(tmp_path):
    # Two steps at once, and one step resumed for a second: the same records and trials
    # (the resumed run factorizes its first solve anew: equal within round-off).
    two = FAULT.replace("steps = 1,", "steps = 2,")
    (tmp_path / "full").mkdir()
    full_done, full = run(tmp_path / "full", two)
    assert full_done.returncode == 0, full_done.stderr
    (tmp_path / "one").mkdir()
    one_done, one = run(tmp_path / "one", FAULT)
    assert one_done.returncode == 0, one_done.stderr
    (tmp_path / "two.nml").write_text(two)
    resumed = tmp_path / "resumed.h5"
    done = subprocess.run([str(ddc2d_exe()), str(tmp_path / "two.nml"), "--resume", str(one),
                           "-o", str(resumed)], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    a, b = growth_of(full), growth_of(resumed)
    np.testing.assert_array_equal(a["reason"], b["reason"])
    np.testing.assert_allclose(b["angle"], a["angle"], rtol=1e-9)
    np.testing.assert_allclose(b["efficiency"], a["efficiency"], rtol=1e-9)
    for key in ("trial_step", "trial_record", "trial_state"):
        np.testing.assert_array_equal(a["trials"][key], b["trials"][key])
    np.testing.assert_allclose(b["trials"]["trial_angle"], a["trials"]["trial_angle"],
                               rtol=1e-9)
    # Efficiencies of stuck trials are round-off around 0: compared absolutely.
    scale = np.nanmax(np.abs(a["trials"]["trial_efficiency"]))
    np.testing.assert_allclose(b["trials"]["trial_efficiency"], a["trials"]["trial_efficiency"],
                               rtol=0, atol=1e-9 * scale)
