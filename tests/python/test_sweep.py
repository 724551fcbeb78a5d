"""Parameter sweeps from the command line: --list, --task, SLURM_ARRAY_TASK_ID, skip and
redo, bad sweep input; scripts/submit-sweep (dry run and a stand-in sbatch) and
scripts/collect-sweep (tables and plot)."""

import csv
import os
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

from conftest import REPO_ROOT, ddc2d_exe
from ddc2d import collect_sweep
from ddc2d.reader import STATE_CODES, is_complete

EXAMPLE = REPO_ROOT / "input" / "sweep_friction_orientation.nml"
SUBMIT = REPO_ROOT / "scripts" / "submit-sweep"
COLLECT = REPO_ROOT / "scripts" / "collect-sweep"

SMALL = """&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /
&remote_stress sxx = -143.75, syy = -81.25, sxy = 54.13 /
&fracture name = 'fault', x = -1.0, 1.0, y = 0.0, 0.0, elements = 20, mu = 0.6, sf = 1.0 /
"""


def run(args, cwd, env_task=None):
    env = {key: value for key, value in os.environ.items() if key != "SLURM_ARRAY_TASK_ID"}
    env["OMP_NUM_THREADS"] = "1"
    if env_task is not None:
        env["SLURM_ARRAY_TASK_ID"] = env_task
    return subprocess.run([str(ddc2d_exe()), *map(str, args)], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=120)


def write_sweep(folder, text, name="small.nml"):
    path = Path(folder) / name
    path.write_text(SMALL + text)
    return path


def test_list_prints_tasks_and_parameters(tmp_path):
    done = run([EXAMPLE, "--list", "-o", "runs/out.h5"], tmp_path)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0] == "tasks: 40"
    assert len(lines) == 41
    assert lines[1] == "task 0: mu = 0.2, remote_angle = -80 -> runs/out_task0000.h5"
    assert lines[40] == "task 39: mu = 1, remote_angle = -10 -> runs/out_task0039.h5"
    assert not list(tmp_path.iterdir()), "--list writes nothing"


def test_task_output_skip_and_redo(tmp_path):
    sweep = write_sweep(tmp_path, "&sweep parameters = 'mu', 'remote_angle', "
                        "values_1 = 0.2, 0.6, values_2 = -30, -45 /\n")
    done = run([sweep, "--task", "2", "-o", "out.h5"], tmp_path)
    assert done.returncode == 0, done.stderr
    output = tmp_path / "out_task0002.h5"
    with h5py.File(output, "r") as f:
        assert is_complete(f.attrs)
        attrs = f["sweep"].attrs
        assert (attrs["task"], attrs["tasks"]) == (2, 4)
        assert attrs["parameters"] == b"mu, remote_angle"
        # Swept values are the input's decimals, stored and copied to the elements
        # unchanged (gfortran and Python both round a decimal correctly): exact.
        assert attrs["mu"] == 0.6 and attrs["remote_angle"] == -30.0
        assert np.all(f["elements/mu"][()] == 0.6)
        sxx, syy, sxy = f.attrs["remote_stress"]
        # s1 = -175 at -30 degrees, s3 = -50 (the base model's principal stresses)
        np.testing.assert_allclose([sxx, syy, sxy], [-143.75, -81.25, 54.13], atol=0.01)
    stamp = output.stat().st_mtime_ns

    again = run([sweep, "--task", "2", "-o", "out.h5"], tmp_path)
    assert again.returncode == 0, again.stderr
    assert "exists; skipped" in again.stdout
    assert output.stat().st_mtime_ns == stamp

    output.write_text("not an HDF5 file")
    redo = run([sweep, "--task", "2", "-o", "out.h5"], tmp_path)
    assert redo.returncode == 0, redo.stderr
    assert "incomplete or unreadable; running the task again" in redo.stdout
    with h5py.File(output, "r") as f:
        assert is_complete(f.attrs)


def test_task_from_slurm_array_task_id(tmp_path):
    sweep = write_sweep(tmp_path, "&sweep parameters = 'sf', values_1 = 0, 1, 2 /\n")
    done = run([sweep, "-o", "out.h5"], tmp_path, env_task="1")
    assert done.returncode == 0, done.stderr
    with h5py.File(tmp_path / "out_task0001.h5", "r") as f:
        assert f["sweep"].attrs["sf"] == 1.0  # the input's value, stored: exact
    # --task wins over the variable
    done = run([sweep, "--task", "2", "-o", "out.h5"], tmp_path, env_task="0")
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "out_task0002.h5").is_file()
    assert not (tmp_path / "out_task0000.h5").exists()
    # a model without &sweep ignores the variable
    plain = tmp_path / "plain.nml"
    plain.write_text(SMALL)
    done = run([plain, "-o", "plain.h5"], tmp_path, env_task="5")
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "plain.h5").is_file()


def test_bad_sweep_usage_exits_2(tmp_path):
    sweep = write_sweep(tmp_path, "&sweep parameters = 'mu', values_1 = 0.2, 0.4 /\n")
    plain = tmp_path / "plain.nml"
    plain.write_text(SMALL)
    cases = [
        ([sweep, "--task", "2"], "task 2 is out of range: the sweep has 2 tasks"),
        ([sweep], "is a sweep of 2 tasks: give --task K (0 to 1) or --list"),
        ([sweep, "--task", "x1"], "--task x1: the task must be a number"),
        ([sweep, "--task", "-1"], "--task -1: the task must be a number"),
        ([sweep, "--list", "--task", "0"], "give --list or --task, not both"),
        ([plain, "--task", "0"], "has no &sweep group: --list and --task are for"),
        ([plain, "--list"], "has no &sweep group"),
    ]
    for args, message in cases:
        done = run(args, tmp_path)
        assert done.returncode == 2, (args, done.stdout, done.stderr)
        assert message in done.stderr, (args, done.stderr)
    done = run([sweep], tmp_path, env_task="7")
    assert done.returncode == 2 and "task 7 is out of range" in done.stderr
    bad = write_sweep(tmp_path, "&sweep parameters = 'friction', values_1 = 0.2 /\n",
                      name="bad.nml")
    done = run([bad, "--task", "0"], tmp_path)
    assert done.returncode == 2
    assert "&sweep (line 4): parameters(1): 'friction' is not a sweep parameter" in done.stderr
    assert not list(tmp_path.glob("*.h5")), "bad input leaves no output"


def test_submit_sweep_dry_run_script(tmp_path):
    done = subprocess.run(
        [sys.executable, str(SUBMIT), str(EXAMPLE), "--exe", str(ddc2d_exe()), "--dry-run",
         "--max-parallel", "3", "--cpus-per-task", "2", "--output-dir", str(tmp_path / "o")],
        capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    script = Path(done.stdout.strip())
    assert script == tmp_path / "o" / "sweep_friction_orientation.sbatch"
    text = script.read_text()
    assert "#SBATCH --array=0-39%3\n" in text
    assert "#SBATCH --cpus-per-task=2\n" in text
    assert f"#SBATCH --output={tmp_path}/o/logs/sweep_friction_orientation_%A_%a.out" in text
    assert 'threads="${SLURM_CPUS_PER_TASK:-1}"' in text
    assert 'export OMP_NUM_THREADS="$threads"' in text
    assert 'export OPENBLAS_NUM_THREADS="$threads"' in text
    assert (f"exec {ddc2d_exe().resolve()} {EXAMPLE} -o {tmp_path}/o/sweep_friction_orientation.h5"
            ' --task "$SLURM_ARRAY_TASK_ID"') in text
    assert (tmp_path / "o" / "logs").is_dir()


def test_submit_sweep_calls_sbatch(tmp_path):
    fake = tmp_path / "bin"
    fake.mkdir()
    record = tmp_path / "sbatch_args"
    (fake / "sbatch").write_text(f'#!/bin/sh\necho "$@" > {record}\necho "4321;cluster"\n')
    (fake / "sbatch").chmod(0o755)
    env = dict(os.environ, PATH=f"{fake}:{os.environ['PATH']}")
    done = subprocess.run(
        [sys.executable, str(SUBMIT), str(EXAMPLE), "--exe", str(ddc2d_exe()),
         "--output-dir", str(tmp_path / "o"), "--partition=long", "--time=00:05:00"],
        capture_output=True, text=True, env=env, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "4321"
    script = tmp_path / "o" / "sweep_friction_orientation.sbatch"
    assert record.read_text().split() == ["--parsable", str(script)]
    # The extra options are in the script itself, which is what sbatch runs.
    assert "#SBATCH --partition=long\n#SBATCH --time=00:05:00\n" in script.read_text()


def test_submit_sweep_dry_run_keeps_sbatch_options(tmp_path):
    done = subprocess.run(
        [sys.executable, str(SUBMIT), str(EXAMPLE), "--exe", str(ddc2d_exe()), "--dry-run",
         "--output-dir", str(tmp_path / "o"), "--time", "00:10:00", "--mem=2G", "-p",
         "long queue", "--exclusive"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    text = Path(done.stdout.strip()).read_text()
    assert ("#SBATCH --time 00:10:00\n#SBATCH --mem=2G\n#SBATCH -p 'long queue'\n"
            "#SBATCH --exclusive\n") in text
    # Every #SBATCH line comes before the first command (sbatch stops reading them there).
    lines = text.splitlines()
    first_command = next(i for i, line in enumerate(lines)
                         if line and not line.startswith("#"))
    assert all(not line.startswith("#SBATCH") for line in lines[first_command:])


def test_submit_sweep_bad_sweep_exits_2(tmp_path):
    bad = write_sweep(tmp_path, "&sweep parameters = 'mu', values_1 = -1 /\n", name="bad.nml")
    done = subprocess.run([sys.executable, str(SUBMIT), str(bad), "--exe", str(ddc2d_exe()),
                           "--dry-run"], capture_output=True, text=True, cwd=tmp_path,
                          timeout=60)
    assert done.returncode == 2
    assert "mu must be >= 0" in done.stderr


def test_collect_sweep_tables_and_plot(tmp_path):
    sweep = write_sweep(tmp_path, "&sweep parameters = 'mu', 'remote_angle', "
                        "values_1 = 0.2, 0.8, values_2 = -60, -30 /\n")
    runs = tmp_path / "runs"
    runs.mkdir()
    for task in (0, 1, 3):
        done = run([sweep, "--task", str(task), "-o", runs / "small.h5"], tmp_path)
        assert done.returncode == 0, done.stderr
    done = subprocess.run([sys.executable, str(COLLECT), str(runs), "--plot", "peak_slip",
                           "--against", "remote_angle"], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert "1 of 4 tasks have no complete output: 2" in done.stderr
    with open(runs / "small_summary.csv") as handle:
        header = next(csv.reader(handle))
    # Units in the header, as in the tips table of ddc2d-plot.
    assert header == ["task", "mu", "remote_angle [deg]", "peak_slip [m]", "peak_opening [m]",
                      "stick", "slip", "open", "max_abs_k1 [MPa m^0.5]",
                      "max_abs_k2 [MPa m^0.5]"]
    with open(runs / "small_summary.csv") as handle:
        rows = [{name.split(" [")[0]: value for name, value in row.items()}
                for row in csv.DictReader(handle)]
    assert [row["task"] for row in rows] == ["0", "1", "3"]
    # The summary holds values of the task files themselves (a maximum picks one stored
    # value, |.| and the CSV's repr round trip are exact): equal bit for bit, no tolerance.
    for row, task in zip(rows, (0, 1, 3)):
        with h5py.File(runs / f"small_task{task:04d}.h5", "r") as f:
            assert float(row["peak_slip"]) == np.max(np.abs(f["elements/ds"][()]))
            state = f["elements/state"][()]
            assert int(row["slip"]) == np.count_nonzero(state == STATE_CODES["slip"])
            assert int(row["stick"]) == np.count_nonzero(state == STATE_CODES["stick"])
            assert float(row["max_abs_k2"]) == np.max(np.abs(f["tips/k2"][()]))
            assert float(row["mu"]) == f["sweep"].attrs["mu"]
    # mu = 0.2 slips at -30 degrees, mu = 0.8 sticks
    assert int(rows[1]["slip"]) == 20 and float(rows[1]["peak_slip"]) > 1e-3
    # A sticking element's slip is a nonbasic LCP variable (Lemke) or fixed (Newton): zero.
    assert int(rows[2]["stick"]) == 20 and float(rows[2]["peak_slip"]) == 0.0
    with h5py.File(runs / "small_summary.h5", "r") as f:
        assert list(f["task"][()]) == [0, 1, 3]
        assert f["peak_slip"].attrs["units"] == "m"
        assert f["remote_angle"].attrs["units"] == "deg"
        assert "units" not in f["mu"].attrs
        # The same numbers written to both tables: exact.
        np.testing.assert_array_equal(f["peak_slip"][()],
                                      [float(row["peak_slip"]) for row in rows])
    plot = runs / "small_peak_slip_vs_remote_angle.png"
    assert plot.stat().st_size > 5000
    collect = collect_sweep
    stem, collected, units = collect.collect(runs)
    figure_path = collect.plot(tmp_path, stem, collected, units, "peak_slip", "remote_angle",
                               "svg")
    text = figure_path.read_text()
    assert "peak_slip [m]" in text and "remote_angle [deg]" in text and "mu = 0.2" in text

    done = subprocess.run([sys.executable, str(COLLECT), str(runs), "--plot", "peak_slip",
                           "--against", "sf"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 2
    assert "the parameters of this sweep are mu, remote_angle" in done.stderr
    done = subprocess.run([sys.executable, str(COLLECT), str(tmp_path / "nothing")],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 2


WING_SWEEP = """&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /
&remote_stress sxx = -5.0, syy = -100.0 /
&fracture name = 'flaw', x = -0.70710678, 0.70710678, y = -0.70710678, 0.70710678,
          elements = 20, condition = 'contact', mu = 0.6, sf = 0.0 /
&growth steps = 3, toughness = 2.0, new_sf = 0.0 /
&sweep parameters = 'mu', 'remote_angle', values_1 = 0.6, values_2 = 60, 90, 110 /
"""


def test_every_task_of_a_growth_sweep_grows_and_is_collected(tmp_path):
    # &growth with &sweep runs each task's growth (docs/sweeps-and-slurm.md#collecting-the-results);
    # collect-sweep adds the growth columns, each equal to what the task file holds.
    sweep = tmp_path / "wings.nml"
    sweep.write_text(WING_SWEEP)
    runs = tmp_path / "runs"
    runs.mkdir()
    for task in range(3):
        done = run([sweep, "--task", str(task), "-o", runs / "wings.h5"], tmp_path)
        assert done.returncode == 0, done.stderr
        assert "growth: " in done.stdout
    done = subprocess.run([sys.executable, str(COLLECT), str(runs), "--plot",
                           "grown_length_flaw", "--against", "remote_angle"],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    with open(runs / "wings_summary.csv") as handle:
        rows = [{name.split(" [")[0]: value for name, value in row.items()}
                for row in csv.DictReader(handle)]
        header = handle.seek(0) or next(csv.reader(handle))
    assert header[-5:] == ["growth_steps", "growth_start", "end_reason", "k_eq_ratio",
                           "grown_length_flaw [m]"]
    for row, task in zip(rows, range(3)):
        with h5py.File(runs / f"wings_task{task:04d}.h5", "r") as f:
            growth = f["growth"]
            assert int(row["growth_steps"]) == growth.attrs["steps_taken"]
            assert row["end_reason"] == growth.attrs["end_reason"].decode()
            assert float(row["grown_length_flaw"]) == pytest.approx(
                np.sum(growth["length"][()]), rel=1e-12)
            last = growth["step"][()] == growth["step"][()].max()
            assert float(row["k_eq_ratio"]) == pytest.approx(
                growth["k_eq"][()][last].max() / growth.attrs["toughness"], rel=1e-12)
    # sigma_1 at 45 degrees to the flaw: both wings grow every step (2 x 3 x 0.2 m: the
    # default increment is twice the tip element of 0.1 m); at 15 degrees the flaw slips
    # and its tips are critical, but their whole kinks close: they grow by shorter ones, so
    # less; at 65 degrees it sticks.
    assert [row["growth_steps"] for row in rows] == ["3", "3", "0"]
    # At a fixed load growth starts in load step 1, or not at all.
    assert [row["growth_start"] for row in rows] == ["1", "1", "0"]
    assert 0 < float(rows[0]["grown_length_flaw"]) < float(rows[1]["grown_length_flaw"])
    assert float(rows[1]["grown_length_flaw"]) == pytest.approx(1.2, rel=1e-6)
    assert float(rows[0]["k_eq_ratio"]) > 1.0 and int(rows[0]["slip"]) == 20
    assert int(rows[2]["stick"]) == 20 and float(rows[2]["grown_length_flaw"]) == 0.0
    with h5py.File(runs / "wings_summary.h5", "r") as f:
        assert [v.decode() for v in f["end_reason"][()]] == [r["end_reason"] for r in rows]
        assert f["grown_length_flaw"].attrs["units"] == "m"
    assert (runs / "wings_grown_length_flaw_vs_remote_angle.png").stat().st_size > 5000


def test_growth_start_is_the_first_load_step_with_growth():
    """growth_start: the load step of the first record that grew (length > 0), or of the
    first new fracture started inside the rock, whichever is earlier; 0 without either; 1
    at a fixed load (no load_step column)."""
    growth = {"step": np.array([1, 1, 2, 2, 3, 3]), "load_step": np.array([1, 1, 2, 3, 3, 4]),
              "length": np.array([0.0, 0.0, 0.0, 0.1, 0.1, 0.0])}
    assert collect_sweep.growth_start(growth) == 3
    assert collect_sweep.growth_start({**growth, "initiations": {"load_step": np.array([2])}}) \
        == 2
    assert collect_sweep.growth_start({**growth, "length": np.zeros(6)}) == 0
    fixed = {key: value for key, value in growth.items() if key != "load_step"}
    assert collect_sweep.growth_start(fixed) == 1


HALF_PLANE = """&model youngs_modulus = 40000, poissons_ratio = 0.25, domain = 'half_plane' /
&remote_stress sxx = -2.0, dsxx_dy = 0.065, dsyy_dy = 0.026 /
&fracture name = 'thrust', x = 0, -5196.152, y = 0, -3000, elements = 20, mu = 0.6,
          sf = 0.5 /
"""


def test_list_refuses_a_sweep_whose_tasks_cannot_run(tmp_path):
    # A half-plane needs syy = sxy = 0: remote_angle = 0 keeps it, 30 and 60 do not. --list
    # (and so submit-sweep) says so before anything is submitted, naming the file, &sweep,
    # the parameter, its value and the task; --task says the same.
    sweep = tmp_path / "half.nml"
    sweep.write_text(HALF_PLANE + "&sweep parameters = 'mu', 'remote_angle',\n"
                     "       values_1 = 0.6, values_2 = 0, 30, 60 /\n")
    done = run([sweep, "--list"], tmp_path)
    assert done.returncode == 2, done.stdout
    assert done.stdout == ""
    errors = [line for line in done.stderr.splitlines() if "&sweep" in line]
    assert len(errors) == 2, done.stderr
    assert errors[0].startswith(f"ddc2d: error: {sweep}: &sweep (line 5): task 1 (mu = 0.6, "
                                "remote_angle = 30): remote_angle = 30 gives the remote stress")
    assert "syy and sxy must be 0" in errors[0]
    assert errors[1].startswith(f"{sweep}: &sweep (line 5): task 2 (mu = 0.6, remote_angle = 60)")
    done = run([sweep, "--task", "1"], tmp_path)
    assert done.returncode == 2
    assert "&sweep (line 5): task 1 (mu = 0.6, remote_angle = 30): remote_angle = 30" \
        in done.stderr
    done = run([sweep, "--task", "0"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert [p.name for p in tmp_path.glob("*.h5")] == ["half_task0000.h5"]
    # submit-sweep stops at the same message, before writing or submitting anything.
    done = subprocess.run([sys.executable, str(SUBMIT), str(sweep), "--exe", str(ddc2d_exe()),
                           "--output-dir", str(tmp_path / "o")], capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 2
    assert "task 1 (mu = 0.6, remote_angle = 30)" in done.stderr
    assert not list(tmp_path.glob("o/*.sbatch"))


def test_sweep_of_a_stress_the_load_path_holds(tmp_path):
    path_model = SMALL + "&load_path steps = 4, sxy = 40, 60 /\n"
    # The path gives sxy at its vertices: sweeping sxy would have no effect.
    sweep = tmp_path / "bad.nml"
    sweep.write_text(path_model + "&sweep parameters = 'sxy', values_1 = 1, 2 /\n")
    done = run([sweep, "--list"], tmp_path)
    assert done.returncode == 2
    assert ("&sweep (line 5): parameters(1) = 'sxy' sets the remote sxy, which &load_path "
            "gives at every vertex") in done.stderr
    # sxx, which the path holds fixed, is swept: every step of the task has the task's sxx.
    sweep = tmp_path / "good.nml"
    sweep.write_text(path_model + "&sweep parameters = 'sxx', values_1 = -150, -120 /\n")
    done = run([sweep, "--task", "1", "-o", "out.h5"], tmp_path)
    assert done.returncode == 0, done.stderr
    with h5py.File(tmp_path / "out_task0001.h5", "r") as f:
        # The swept value itself, copied: exact.
        assert f.attrs["remote_stress"][0] == -120.0


WEAKENING = """&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /
&remote_stress sxx = -143.75, syy = -81.25, sxy = 54.13 /
&fracture name = 'weak', x = -1.0, 1.0, y = 0.0, 0.0, elements = 10, mu = 0.6, sf = 1.0,
          sf_residual = 0.4, mu_dynamic = 0.4, slip_weakening_distance = 1e-4 /
&fracture name = 'plain', x = -1.0, 1.0, y = 2.0, 2.0, elements = 10, mu = 0.6, sf = 1.0 /
"""


@pytest.mark.parametrize("swept, low, residual", [("sf", "0.2", "sf_residual = 0.4"),
                                                   ("mu", "0.3", "mu_dynamic = 0.4")])
def test_sweep_below_the_residual_strength_is_refused(tmp_path, swept, low, residual):
    # One model with sf below sf_residual (or mu below mu_dynamic) is refused; a sweep to
    # such a value must not lower the residual to it (or turn weakening off) without a word.
    sweep = tmp_path / "weak.nml"
    sweep.write_text(WEAKENING + f"&sweep parameters = '{swept}', values_1 = 0.8, {low} /\n")
    expected = (f"{sweep}: &sweep (line 6): task 1 ({swept} = {low}): {swept} = {low} is "
                f"below {residual} of fracture 1 weak")
    done = run([sweep, "--list"], tmp_path)
    assert done.returncode == 2, done.stdout
    assert done.stdout == ""
    errors = [line for line in done.stderr.splitlines() if "&sweep" in line]
    assert errors == [line for line in done.stderr.splitlines() if line.strip()]
    assert len(errors) == 1 and errors[0].startswith("ddc2d: error: " + expected), done.stderr
    done = run([sweep, "--task", "1", "-o", "out.h5"], tmp_path)
    assert done.returncode == 2
    assert done.stderr.startswith("ddc2d: error: " + expected), done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["weak.nml"], "nothing written"
    # The task above the residual runs, with the residual as given.
    done = run([sweep, "--task", "0", "-o", "out.h5"], tmp_path)
    assert done.returncode == 0, done.stderr
    with h5py.File(tmp_path / "out_task0000.h5", "r") as f:
        elements = f["elements"]
        weak = elements["fracture_id"][()] == 1
        assert np.all(elements["sf_residual"][()][weak] == 0.4)
        assert np.all(elements["mu_dynamic"][()][weak] == 0.4)


def test_sweep_refusal_follows_the_value_in_force(tmp_path):
    # 'mu' sets every fracture to 0.3, then fracture(1)%mu sets the weakening fracture back
    # to 0.6, above its mu_dynamic: the plain fracture has no mu_dynamic, so every task runs.
    sweep = tmp_path / "order.nml"
    sweep.write_text(WEAKENING + "&sweep parameters = 'mu', 'fracture(1)%mu', combine = 'zip',"
                     " values_1 = 0.3, 0.35, values_2 = 0.6, 0.5 /\n")
    done = run([sweep, "--list"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[0] == "tasks: 2"
    # The other order leaves 0.3 on the weakening fracture: refused, naming 'mu'.
    sweep.write_text(WEAKENING + "&sweep parameters = 'fracture(1)%mu', 'mu', combine = 'zip',"
                     " values_1 = 0.6, 0.5, values_2 = 0.3, 0.45 /\n")
    done = run([sweep, "--list"], tmp_path)
    assert done.returncode == 2
    assert ("task 0 (fracture(1)%mu = 0.6, mu = 0.3): mu = 0.3 is below mu_dynamic = 0.4 of "
            "fracture 1 weak") in done.stderr
    assert "task 1 " not in done.stderr


FLOW = """&model youngs_modulus = 30000.0, poissons_ratio = 0.25, length_unit = 'm',
       stress_unit = 'MPa', time_unit = 'h' /
&remote_stress syy = -10.0, sxy = 4.5 /
&fracture name = 'fault', x = -4.0, 4.0, y = 0.0, 0.0, elements = 40, mu = 0.6, sf = 0.0,
          diffusivity = 1.0, transmissivity = 1.0 /
&fracture name = 'dry', x = -4.0, 4.0, y = 3.0, 3.0, elements = 4, mu = 0.6 /
&injection name = 'well', fracture = 'fault', x = 0.0, y = 0.0, overpressure = 5.0 /
&load_path time = 0.0, 0.4, steps = 2 /
"""


def test_sweep_of_injection_and_hydraulic_parameters(tmp_path):
    # docs/sweeps-and-slurm.md#the-parameters: a source's overpressure and a fracture's
    # transmissivity, each task's values in its model, and collect-sweep's injection columns.
    sweep = tmp_path / "flow.nml"
    sweep.write_text(FLOW + "&sweep parameters = 'overpressure', 'fracture(1)%transmissivity', "
                     "values_1 = 4.0, 5.0, values_2 = 1.0, 2.0 /\n")
    runs = tmp_path / "runs"
    runs.mkdir()
    volume = {}
    for task, (overpressure, transmissivity) in enumerate([(4, 1), (4, 2), (5, 1), (5, 2)]):
        done = run([sweep, "--task", str(task), "-o", runs / "flow.h5"], tmp_path)
        assert done.returncode == 0, done.stderr
        with h5py.File(runs / f"flow_task{task:04d}.h5", "r") as f:
            assert f["injection/overpressure"][0] == overpressure
            fid = f["elements/fracture_id"][()]
            assert np.all(f["elements/transmissivity"][()][fid == 1] == transmissivity)
            assert np.all(f["elements/diffusivity"][()][fid == 1] == 1.0)
            assert np.all(f["elements/transmissivity"][()][fid == 2] == 0.0)  # dry: no flow
            volume[overpressure, transmissivity] = f["history/injected_volume"][-1]
    # The pressure diffuses with alpha alone and scales with the overpressure; the stored
    # volume is (T / alpha) times its integral: the values act as the model's own would.
    assert volume[4, 2] == pytest.approx(2.0 * volume[4, 1], rel=1e-9)
    assert volume[5, 1] == pytest.approx(1.25 * volume[4, 1], rel=1e-9)
    done = subprocess.run([sys.executable, str(COLLECT), str(runs)], capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    with open(runs / "flow_summary.csv") as handle:
        header = next(csv.reader(handle))
        rows = [dict(zip(header, row)) for row in csv.reader(handle)]
    assert header[:3] == ["task", "overpressure [MPa]", "fracture(1)%transmissivity [m^3/(MPa h)]"]
    assert header[10:] == ["injected_volume [m^2]", "slipping_length_fault [m]",
                           "front_half_length_fault [m]", "moment_fault [MPa m^2]",
                           "slipping_length_dry [m]", "front_half_length_dry [m]",
                           "moment_dry [MPa m^2]"]
    for row, task in zip(rows, range(4)):
        with h5py.File(runs / f"flow_task{task:04d}.h5", "r") as f:
            h = f["history"]
            assert float(row["injected_volume [m^2]"]) == h["injected_volume"][-1]
            assert float(row["slipping_length_fault [m]"]) == h["slipping_length"][-1, 0]
            assert float(row["front_half_length_fault [m]"]) == pytest.approx(
                0.5 * (h["front_end"][-1, 0] - h["front_begin"][-1, 0]), rel=1e-15)
            assert float(row["moment_fault [MPa m^2]"]) == h["moment"][-1, 0]
        assert np.isnan(float(row["front_half_length_dry [m]"]))  # the dry one sticks
        assert float(row["moment_dry [MPa m^2]"]) == 0.0


@pytest.mark.parametrize("parameter, value, message", [
    ("rate", 1.0, "parameters(1) = 'rate': no &injection gives a rate"),
    ("injection(1)%rate", 1.0, "'injection(1)%rate': &injection 1 'well' does not give a rate"),
    ("injection(2)%overpressure", 1.0, "has 1 &injection group(s); K must be 1 to 1"),
    ("injection(a)%overpressure", 1.0, "write injection(K)%overpressure with K"),
    ("injection(1)%mu", 1.0, "a source's sweep parameters are overpressure and rate"),
    ("fracture(2)%diffusivity", 1.0, "'fracture(2)%diffusivity': fracture 2 'dry' does not"),
    ("fracture(1)%storativity", 1.0, "are mu, sf, pressure, diffusivity, transmissivity and the"),
    ("transmissivity", 0.0, "values_1(1) = 0.00000: transmissivity must be positive"),
])
def test_bad_flow_sweeps_exit_2(tmp_path, parameter, value, message):
    sweep = tmp_path / "flow.nml"
    sweep.write_text(FLOW + f"&sweep parameters = '{parameter}', values_1 = {value} /\n")
    done = run([sweep, "--list"], tmp_path)
    assert done.returncode == 2, done.stdout
    assert message in done.stderr and done.stderr.count("ddc2d: error:") == 1, done.stderr


def test_a_swept_source_value_reaches_its_source_only(tmp_path):
    sweep = tmp_path / "two.nml"
    sweep.write_text(FLOW + "&injection name = 'sink', fracture = 'fault', x = 2.1, y = 0.0, "
                     "rate = -0.1 /\n&sweep parameters = 'injection(2)%rate', 'overpressure', "
                     "values_1 = -0.2, values_2 = 3.0 /\n")
    done = run([sweep, "--task", "0", "-o", "two.h5"], tmp_path)
    assert done.returncode == 0, done.stderr
    with h5py.File(tmp_path / "two_task0000.h5", "r") as f:
        assert list(f["injection/overpressure"][()][:1]) == [3.0]
        assert list(f["injection/rate"][()][1:]) == [-0.2]
        assert np.isnan(f["injection/rate"][0]) and np.isnan(f["injection/overpressure"][1])


def test_the_strength_laws_of_the_fractures_are_swept(tmp_path):
    """A fracture's own strength laws are sweep parameters as the new_* ones of &growth are:
    <law> on the contact elements of every fracture, fracture(K)%<law> on fracture K's; a task
    whose mu_dynamic would exceed mu is refused as one model is."""
    sweep = tmp_path / "laws.nml"
    sweep.write_text(WEAKENING + "&sweep parameters = 'slip_weakening_distance', "
                     "'fracture(1)%mu_dynamic', combine = 'zip', values_1 = 5e-5, 2e-4, "
                     "values_2 = 0.45, 0.7 /\n")
    done = run([sweep, "--list"], tmp_path)
    assert done.returncode == 2
    assert ("task 1 (slip_weakening_distance = 0.0002, fracture(1)%mu_dynamic = 0.7): "
            "fracture(1)%mu_dynamic = 0.7 is above mu = 0.6 of fracture 1 weak") in done.stderr
    assert "task 0 " not in done.stderr
    done = run([sweep, "--task", "0", "-o", "out.h5"], tmp_path)
    assert done.returncode == 0, done.stderr
    with h5py.File(tmp_path / "out_task0000.h5", "r") as f:
        elements = f["elements"]
        weak = elements["fracture_id"][()] == 1
        assert np.all(elements["slip_weakening_distance"][()] == 5e-5)
        assert np.all(elements["mu_dynamic"][()][weak] == 0.45)
        # The plain fracture keeps its friction: no mu_dynamic given is mu's.
        assert np.all(elements["mu_dynamic"][()][~weak] == 0.6)
        assert f["sweep"].attrs["parameters"] == b"slip_weakening_distance, fracture(1)%mu_dynamic"

