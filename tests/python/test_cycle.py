"""Earthquake cycles on rate-and-state faults (docs/earthquake-cycles.md,
docs/theory/cycles.md): the run against independent solutions, its invariances, the stop
where an effective normal stress reaches zero, --resume, the SEAS files and the figures.

* One element in the full plane is a spring-slider: its own self-stiffness k = G / (pi (1 -
  nu) a) and back-slip at V_p give tau = tau0 + k (delta - V_p t). scipy integrates the same
  equations (tests/spring_slider.py: DOP853 at rtol 1e-12); with the aging and the
  slip law ddc2d's event times (largest slip rate crossing 1e-3) agree within 1e-7 relative
  (measured: 4e-9 at tolerance 1e-7), its slip between events (rate below 2e-9) within 1e-8
  (measured 2.6e-9) and log10 of its state within 1e-3 (measured 4e-5).
* A fault that reaches the free surface with a > b everywhere, at steady state at V_p,
  stays there: back-slip leaves no stress, slip = V_p t within ten local errors the
  integrator accepts (tolerance dc = 8e-10; measured 1e-9), the slip rate V_p within 1e-6
  relative (the stress of that slip error over a sigma: 3e-7; measured 1.6e-7) and log10
  theta = log10(L / V_p) within 1e-7 (measured 5e-9); started at 3 V_p it relaxes to V_p.
* The quick model (a BP3-QD of a fifth of the size, ddc2d.seas.bp3_namelist): the first
  event time moves by less than 0.1 % when the tolerance is halved (measured 1e-6) and by
  less than 2 % from 100 to 50 m cells (measured 0.3 %).
* --resume of a finished run (to a later end_time) or of a checkpoint continues within the
  run's tolerance of the uninterrupted run: event times within 1e-7 relative.
"""

import re
import subprocess

import h5py
import numpy as np
import pytest

import ddc2d.plot.cli
import ddc2d.seas
from conftest import REPO_ROOT, ddc2d_exe
from ddc2d.reader import load_result, parse_coding
from spring_slider import CS, DC, ETA, F0, NU, SIGMA, SLIDER, V0, VP, B, E, spring_slider


def run(args, cwd, check=True):
    done = subprocess.run([str(ddc2d_exe()), *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, timeout=300)
    if check:
        assert done.returncode == 0, done.stdout + done.stderr
    return done


def solved(tmp_path, text, name="model", extra=()):
    (tmp_path / f"{name}.nml").write_text(text)
    run([f"{name}.nml", "-o", f"{name}.h5", *extra], tmp_path)
    return load_result(tmp_path / f"{name}.h5")["cycle"]


@pytest.mark.parametrize("law", ["aging", "slip"])
def test_single_element_is_the_spring_slider(tmp_path, law):
    end = 5.0e8
    cycle = solved(tmp_path, SLIDER.format(end=end, law=law))
    events, solution = spring_slider(law, end)
    assert events.size == 2
    assert cycle["event_start"].size == events.size
    assert np.allclose(cycle["event_start"], events, rtol=1e-7, atol=0.0)
    quiet = cycle["max_slip_rate"] < 2.0e-9
    assert quiet.sum() > 100
    reference = solution(cycle["time"][quiet])
    assert np.max(np.abs(cycle["slip"][quiet, 0] - reference[0])) < 1e-8
    log_theta = reference[1] / np.log(10.0) + np.log10(DC / V0)
    assert np.max(np.abs(cycle["state"][quiet, 0] - log_theta)) < 1e-3
    assert cycle["attrs"]["end_reason"] == "end_time"


def steady_fault(v_init):
    """A velocity-strengthening fault from the surface, 45 degrees, 10 elements, at the
    steady-state stress of V_p."""
    a = 0.02
    tau = SIGMA * a * np.arcsinh(VP / (2 * V0) * np.exp((F0 + B * np.log(V0 / VP)) / a)) + \
        ETA * VP
    return f"""\
&model youngs_modulus = {E}, poissons_ratio = {NU}, domain = 'half_plane' /
&fracture name = 'fault', x = 0, 1000, y = 0, -1000, elements = 10,
  condition = 'rate_state', a = {a}, b = {B}, dc = {DC}, f0 = {F0}, v0 = {V0},
  v_init = {v_init}, sigma0 = {SIGMA}, tau0 = {-tau:.15g} /
&cycle end_time = 1e11, shear_wave_speed = {CS}, plate_rate = {VP}, output_interval = 1e9 /
"""


def test_steady_state_stays(tmp_path):
    cycle = solved(tmp_path, steady_fault(VP))
    t = cycle["time"]
    assert t[-1] == 1e11
    assert np.max(np.abs(cycle["slip"] - VP * t[:, None])) < 1e-6 * DC
    assert np.allclose(cycle["slip_rate"], VP, rtol=1e-6, atol=0.0)
    assert np.allclose(cycle["state"], np.log10(DC / VP), rtol=0.0, atol=1e-7)
    # The normal stress of that slip error (about 400 MPa/m times 8e-9)
    assert np.allclose(cycle["normal_traction"], -SIGMA, rtol=0.0, atol=1e-5)
    assert cycle["event_start"].size == 0


def test_creep_relaxes_to_the_plate_rate(tmp_path):
    cycle = solved(tmp_path, steady_fault(3.0 * VP))
    assert cycle["slip_rate"][0, 0] == pytest.approx(3.0 * VP, rel=1e-9)
    assert np.allclose(cycle["slip_rate"][-1], VP, rtol=1e-6, atol=0.0)


def quick(cell=100.0, tolerance=1e-7, years=80.0):
    """The quick model (input/seas/quick_cycle.nml): BP3-QD at a fifth of the size with
    BP3's L, to just after its first event."""
    return ddc2d.seas.bp3_namelist(cell=cell, scale=0.2, dc_scale=1.0, years=years,
                                   tolerance=tolerance)


def test_first_event_does_not_move_with_tolerance_or_cells(tmp_path):
    starts = {}
    for name, text in (("base", quick()), ("tight", quick(tolerance=5e-8)),
                       ("fine", quick(cell=50.0))):
        starts[name] = solved(tmp_path, text, name)["event_start"][0]
    assert abs(starts["tight"] / starts["base"] - 1.0) < 1e-3
    assert abs(starts["fine"] / starts["base"] - 1.0) < 2e-2


def test_normal_stress_at_zero_stops_and_keeps_the_run(tmp_path):
    # A thrust at 30 degrees with 1 MPa of normal stress: its slip unclamps the shallowest
    # element until nothing holds it.
    text = ddc2d.seas.bp3_namelist(dip=30.0, cell=200.0, scale=0.1, years=1.0)
    (tmp_path / "weak.nml").write_text(text.replace("sigma0 = 50", "sigma0 = 1"))
    done = run(["weak.nml"], tmp_path, check=False)
    assert done.returncode == 1, done.stdout + done.stderr
    assert done.stderr.count("ddc2d: error:") == 1
    assert "effective normal stress of element 1 reaches zero at t = " in done.stderr
    cycle = load_result(tmp_path / "weak.h5")["cycle"]
    assert cycle["attrs"]["end_reason"] == "normal_stress"
    assert cycle["attrs"]["end_element"] == 1
    assert cycle["time"].size > 1
    resumed = run(["weak.nml", "--resume", "weak.h5", "-o", "again.h5"], tmp_path, check=False)
    assert resumed.returncode == 2
    assert "stopped" in resumed.stderr


def test_resume_goes_on_as_the_run_would(tmp_path):
    whole = solved(tmp_path, SLIDER.format(end=5e8, law="aging"), "whole")
    solved(tmp_path, SLIDER.format(end=2e8, law="aging"), "first")
    resumed = solved(tmp_path, SLIDER.format(end=5e8, law="aging"), "resumed",
                     ["--resume", "first.h5"])
    assert resumed["event_start"].size == whole["event_start"].size == 2
    assert np.allclose(resumed["event_start"], whole["event_start"], rtol=1e-7, atol=0.0)
    assert resumed["slip"][-1, 0] == pytest.approx(whole["slip"][-1, 0], rel=1e-6)
    assert resumed["time"][-1] == whole["time"][-1]
    with h5py.File(tmp_path / "resumed.h5") as f:
        assert f.attrs["resumed_from"].decode() == "first.h5"


def test_a_checkpoint_is_not_complete_and_goes_on(tmp_path):
    # A run cut off leaves its last checkpoint: /cycle end_reason 'running'.
    solved(tmp_path, SLIDER.format(end=2e8, law="aging"), "cut")
    with h5py.File(tmp_path / "cut.h5", "r+") as f:
        f["cycle"].attrs["end_reason"] = np.bytes_("running")
    text = SLIDER.format(end=2e8, law="aging")
    (tmp_path / "cut.nml").write_text(text)
    done = run(["cut.nml", "--resume", "cut.h5", "-o", "on.h5"], tmp_path)
    assert "wrote on.h5" in done.stdout
    assert load_result(tmp_path / "on.h5")["cycle"]["attrs"]["end_reason"] == "end_time"


def test_a_sweep_of_a_cycle_model_runs_each_task_as_its_model(tmp_path):
    # docs/sweeps-and-slurm.md: a stiffer rock loads the slider faster, so the task of the
    # larger modulus has its first event earlier; each task equals its model run alone.
    base = SLIDER.format(end=5e8, law="aging")
    (tmp_path / "sweep.nml").write_text(base + "&sweep parameters = 'youngs_modulus', "
                                        "values_1 = 60000, 75000 /\n")
    for task in (0, 1):
        run(["sweep.nml", "--task", str(task), "-o", "sweep.h5"], tmp_path)
    tasks = [load_result(tmp_path / f"sweep_task000{k}.h5")["cycle"] for k in (0, 1)]
    alone = solved(tmp_path, base, "alone")
    assert tasks[1]["event_start"][0] < tasks[0]["event_start"][0]
    assert np.allclose(tasks[1]["event_start"], alone["event_start"], rtol=1e-12, atol=0.0)
    with h5py.File(tmp_path / "sweep_task0000.h5") as f:
        assert f.attrs["youngs_modulus"] == 60000.0 and f["sweep"].attrs["task"] == 0
        # The condition coding of a cycle model names its rate-and-state elements.
        assert parse_coding(f["elements/condition"].attrs["coding"])[7] == "rate_state"


def test_seas_files(tmp_path):
    (tmp_path / "surface.csv").write_text("x,y\n-2000,0\n1,0\n-1,0\n3200,0\n")
    text = ddc2d.seas.bp3_namelist(cell=200.0, scale=0.1, years=0.5,
                                   points_file="surface.csv")
    cycle = solved(tmp_path, text, "small")
    written = ddc2d.seas.write_seas(tmp_path / "small.h5", tmp_path / "seas", modeler="test")
    names = sorted(p.name for p in written)
    assert names == sorted([f"fltst_dp{d:03d}" for d in (0, 25, 50, 75, 100, 125, 150, 175,
                                                         200, 250, 300, 350)]
                           + ["srfst_fn-02", "srfst_fn+00", "srfst_fn-00", "srfst_fn+03",
                              "slip.dat", "shear_stress.dat", "normal_stress.dat"])
    lines = (tmp_path / "seas" / "fltst_dp000").read_text().splitlines()
    assert "# problem=SEAS Benchmark BP3-QD" in lines
    assert "# modeler=test" in lines
    assert "t slip slip_rate shear_stress normal_stress state" in lines
    data = np.array([[float(v) for v in line.split()] for line in lines
                     if line and not line.startswith("#") and not line.startswith("t ")])
    # The benchmark's signs: thrust slip and shear stress positive, compression positive.
    assert np.allclose(data[:, 0], cycle["time"], rtol=1e-12)
    assert np.allclose(data[:, 1], cycle["slip"][:, 0], rtol=1e-6, atol=1e-12)
    assert np.allclose(data[:, 3], -cycle["shear_traction"][:, 0], rtol=1e-6)
    assert np.allclose(data[:, 4], -cycle["normal_traction"][:, 0], rtol=1e-6)
    assert data[0, 3] == pytest.approx(26.546, abs=1e-3)
    profile = (tmp_path / "seas" / "slip.dat").read_text().splitlines()
    rows = [line for line in profile if line and line[0] not in "#xt"]
    first = [float(v) for v in rows[0].split()]
    assert first[:2] == [0.0, 0.0]
    assert np.allclose(first[2:], cycle["distance"], rtol=1e-6)
    assert len(rows) == cycle["time"].size + 1


def test_plots_of_a_cycle(tmp_path):
    text = ddc2d.seas.bp3_namelist(cell=200.0, scale=0.1, years=20.0)
    solved(tmp_path, text, "plotted")
    status = ddc2d.plot.cli.main([str(tmp_path / "plotted.h5"), "-o",
                                  str(tmp_path / "figures")])
    assert status == 0
    for kind in ("cycle_slip", "cycle_rate", "cycle_events"):
        assert (tmp_path / "figures" / f"plotted_{kind}.png").is_file()


BAD = {
    "b = 0.015": ("b = 0", ["&fracture", "b(1) = 0", "positive"]),
    "dc = 0.008": ("dc = -0.008", ["&fracture", "dc(1)", "positive"]),
    " tau0 = -30.0": (" tau0 = 30.0", ["tau0 = 30", "no initial state"]),
    "shear_wave_speed = 3464.0,": ("", ["&cycle", "shear_wave_speed or radiation_damping"]),
    "state_law = 'aging'": ("state_law = 'fast'", ["&cycle", "state_law = 'fast'"]),
    "sigma0 = 50.0, ": ("", ["&fracture", "sigma0 is required"]),
}


@pytest.mark.parametrize("old", BAD, ids=list(BAD))
def test_bad_input_exits_2_without_output(tmp_path, old):
    new, words = BAD[old]
    text = SLIDER.format(end=5e8, law="aging")
    assert old in text
    (tmp_path / "bad.nml").write_text(text.replace(old, new))
    done = run(["bad.nml"], tmp_path, check=False)
    assert done.returncode == 2, done.stdout + done.stderr
    assert done.stderr.count("ddc2d: error:") == 1
    for word in words:
        assert word in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.nml"]


EXAMPLES = {
    "bp3qd_thrust60": {"dip": 60.0, "thrust": True, "matrix": "hierarchical",
                       "points_file": "bp3qd_surface.csv"},
    "bp3qd_normal30": {"dip": 30.0, "thrust": False, "matrix": "hierarchical",
                       "points_file": "bp3qd_surface.csv"},
    "quick_cycle": {"cell": 100.0, "scale": 0.2, "dc_scale": 1.0, "years": 150.0},
}


@pytest.mark.parametrize("name", EXAMPLES)
def test_examples_are_bp3_as_specified(name):
    # input/seas/ holds what ddc2d.seas.bp3_namelist writes (below its comment block) ...
    text = (REPO_ROOT / "input" / "seas" / f"{name}.nml").read_text()
    assert text.startswith("!")
    body = "".join(line for line in text.splitlines(True) if not line.startswith("!"))
    assert body == ddc2d.seas.bp3_namelist(**EXAMPLES[name])
    if not name.startswith("bp3qd"):
        return
    # ... and that is BP3-QD's specification: 1600 cells of 25 m to 40 km, 1500 years,
    # tau0 = 26.546 MPa of the sign that drives V_init = +-1e-9 m/s, a from 0.010 to 0.025.
    values = re.sub(r"\s+", " ", body)
    counts = re.search(r"elements = ([\d, ]+),", values).group(1)
    assert sum(int(c) for c in counts.split(",")) == 1600
    thrust = EXAMPLES[name]["thrust"]
    assert f"v_init = {1e-9 if thrust else -1e-9:g}" in values
    assert f"tau0 = {'-' if thrust else ''}26.5461223651" in values
    assert f"end_time = {1500 * ddc2d.seas.YEAR:.12g}" in values
    a = [float(v) for v in re.search(r"a = ([\d., ]+), b =", values).group(1).split(",")]
    assert (a[0], a[-1], len(a)) == (0.01, 0.025, 122)
    assert "profile_spacing = 500" in values and "b = 0.015, dc = 0.008" in values
