"""One model on many processes (docs/mpi.md): the MPI build against the serial one.

Run by CTest in the `mpi` preset's build (label mpi), which sets DDC2D_EXE (ddc2d built with
MPI), DDC2D_SERIAL_EXE (the serial program of the same build) and MPIEXEC. Every run has a
timeout, so a process that waits forever fails the test instead of hanging it.

- P = 1, 2 and 4 processes (grids 1 x 1, 1 x 2, 2 x 2) give the serial answer on the four models
  of docs/mpi.md#how-it-is-tested: DDs, tractions, face displacements, tips and fields within
  1e-10 of the largest magnitude of their kind of quantity (compare_results), the same element
  states and point flags, the same method, and a certificate and equilibrium residual that pass
  the same limits; a Newton solve records its factorizations (one per reduced system).
- On 4 processes, bad input, what is not distributed and a solver failure end every process
  with one message from the root, the documented exit status and no output file.
"""

import functools
import json
import os
import subprocess
import tempfile
from pathlib import Path

import h5py
import numpy as np
import pytest

from compare_results import RTOL, differences  # tests/ is on pytest's pythonpath (pytest.ini)
from ddc2d.reader import read_solver

REPO = Path(__file__).resolve().parents[2]
DATA = REPO / "tests" / "data"
MODELS = {
    "straight": REPO / "input" / "paper_fault_slip.nml",  # N = 500, every element slips
    "kinked": DATA / "mpi" / "kinked_fault.nml",  # stick, slip and open; block size 15
    "cohesion_lost": DATA / "mpi" / "kinked_cohesion_lost.nml",  # open_cohesion = 'lost'
    "twodd_symmetry": DATA / "mpi" / "twodd_symmetry.nml",  # TWODD conditions, x = 0 plane
    "half_plane": DATA / "mpi" / "half_plane.nml",  # contact and prescribed DDs
    "bimaterial": DATA / "mpi" / "bimaterial.nml",  # two materials, contact and traction
}
PROCESSES = (1, 2, 4)
RESIDUAL_LIMIT = 1e-8  # the equilibrium check of every solution (ddc_linalg_lu residual_tol)
TIMEOUT = 300


def executable(variable):
    value = os.environ.get(variable)
    if not value:
        raise AssertionError(f"{variable} is not set: run these tests through CTest in the "
                             "mpi preset's build (ctest --preset mpi)")
    return os.path.abspath(value) if os.sep in value else value


def environment():
    """Open MPI as root, more processes than cores, one thread per process; where OpenBLAS
    picks a kernel older than the CPU (the serial program then runs itself again with the
    newest one, the MPI program warns: docs/performance.md#the-blas-kernel), every process
    gets the serial program's kernel by OPENBLAS_CORETYPE, as the warning tells MPI users,
    so that both programs compute with the same kernel."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", OMPI_MCA_mpi_yield_when_idle="1")
    kernel, openblas_own = serial_kernels()
    if "OPENBLAS_CORETYPE" not in env and kernel != openblas_own:
        env["OPENBLAS_CORETYPE"] = kernel
    return env


@functools.lru_cache(maxsize=2)
def serial_kernels(own_choice=False):
    """(the kernel the serial program computes with, the one OpenBLAS chose by itself), from
    the result of a small model solved with the caller's environment; own_choice: without
    the caller's OPENBLAS_CORETYPE (where it forces a kernel, OpenBLAS chose none)."""
    env = {k: v for k, v in os.environ.items() if not (own_choice and k == "OPENBLAS_CORETYPE")}
    with tempfile.TemporaryDirectory() as folder:
        model = Path(folder) / "probe.nml"
        model.write_text("&model youngs_modulus = 1000, poissons_ratio = 0.25 /\n"
                         "&remote_stress syy = 1 /\n"
                         "&fracture x = -1, 1, y = 0, 0, elements = 4, "
                         "condition = 'traction' /\n")
        done = subprocess.run([executable("DDC2D_SERIAL_EXE"), str(model), "-o",
                               str(Path(folder) / "probe.h5")], capture_output=True, text=True,
                              timeout=TIMEOUT, check=False, env=env)
        assert done.returncode == 0, done.stdout + done.stderr
        with h5py.File(Path(folder) / "probe.h5") as f:
            kernel = f.attrs["blas_core"]
            chosen_by = f.attrs["blas_core_chosen_by"]
    kernel, chosen_by = (v.decode() if isinstance(v, bytes) else str(v)
                         for v in (kernel, chosen_by))
    marker = "OpenBLAS had chosen "
    own = chosen_by.split(marker)[1].rstrip(")") if marker in chosen_by else kernel
    return kernel, own


def run_parallel(processes, args, cwd, timeout=TIMEOUT):
    command = [executable("MPIEXEC"), "-q", "--oversubscribe", "-n", str(processes),
               executable("DDC2D_EXE"), *map(str, args)]
    return subprocess.run(command, cwd=cwd, capture_output=True, text=True, timeout=timeout,
                          env=environment(), check=False)


def run_serial(args, cwd):
    return subprocess.run([executable("DDC2D_SERIAL_EXE"), *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, timeout=TIMEOUT, env=environment(),
                          check=False)


@pytest.fixture(scope="module")
def serial_result(tmp_path_factory):
    """The serial program's result file of a model (each model solved once)."""
    folder = tmp_path_factory.mktemp("serial")
    done = {}

    def result(model):
        if model not in done:
            out = folder / f"{model}.h5"
            run = run_serial([MODELS[model], "-o", out], folder)
            assert run.returncode == 0, run.stdout + run.stderr
            done[model] = out
        return done[model]

    return result


def check_solver_record(reference, other, processes):
    a, b = read_solver(reference)["attrs"], read_solver(other)["attrs"]
    for key in ("method", "lcp_solves", "newton_iterations", "elements_free", "elements_stick",
                "elements_slip", "elements_open"):
        assert a[key] == b[key], f"/solver {key}: {a[key]} serial, {b[key]} parallel"
    for record in (a, b):
        tolerance = record["certificate_tolerance"]
        if record["method"] == "newton":
            assert record["certificate_min_z"] >= -tolerance
            assert record["certificate_min_w"] >= -tolerance
            assert record["certificate_max_complementarity"] <= tolerance
        assert record["equilibrium_residual"] <= RESIDUAL_LIMIT
    if b["method"] == "newton":
        # The distributed Newton method factorizes every reduced system anew, and says so.
        assert b["factorizations"] >= 1, "/solver factorizations = 0 after a Newton solve"
        assert b["low_rank_updates"] == 0 and b["factorization_reuses"] == 0
        assert b["factorizations"] <= b["newton_iterations"]
    assert b["processes"] == processes
    assert int(np.prod(b["process_grid"])) == processes
    assert "processes" not in a  # the serial program's layout has no process attributes


@pytest.mark.parametrize("processes", PROCESSES)
@pytest.mark.parametrize("model", MODELS)
def test_same_answer_as_serial(model, processes, serial_result, tmp_path):
    out = tmp_path / f"{model}_p{processes}.h5"
    run = run_parallel(processes, [MODELS[model], "-o", out], tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == [out.name]
    found = differences(serial_result(model), out)
    with h5py.File(serial_result(model)) as reference, h5py.File(out) as other:
        check_solver_record(reference, other, processes)
    worst = max(found, key=found.get)
    print(f"{model}, {processes} processes: largest relative difference {found[worst]:.2e} "
          f"({worst}) over {len(found)} arrays")
    assert found[worst] <= RTOL, f"{worst} differs by {found[worst]:.3e} (limit {RTOL})"


ERRORS = {
    "bad_input": (DATA / "input" / "bad_mu.nml", 2, ["bad_mu.nml", "&fracture 1", "mu(2)"]),
    "lemke": (DATA / "input" / "good_polyline.nml", 2,
              ["good_polyline.nml", "with 4 processes", "lcp_method = 'lemke'",
               "one process"]),
    "load_path": (DATA / "history" / "good.nml", 2,
                  ["good.nml", "with 4 processes", "&load_path", "one process"]),
    "strength": (DATA / "input" / "good_strength.nml", 2,
                 ["good_strength.nml", "with 4 processes",
                  "tensile_strength, sf_residual, mu_dynamic or a joint stiffness",
                  "one process"]),
    "growth": (DATA / "growth" / "good.nml", 2,
               ["good.nml", "with 4 processes", "&growth", "one process"]),
    "cycle": (DATA / "cycle" / "good_slider.nml", 2,
              ["good_slider.nml", "with 4 processes", "&cycle", "one process"]),
    "hierarchical": (DATA / "mpi" / "hierarchical.nml", 2,
                     ["hierarchical.nml", "with 4 processes", "matrix = 'hierarchical'",
                      "one process"]),
    "solver_failure": (DATA / "mpi" / "unbalanced_hole.nml", 1,
                       ["influence matrix is numerically singular", "relative residual"]),
}


@pytest.mark.parametrize("case", ERRORS)
def test_error_on_four_processes(case, tmp_path):
    model, status, words = ERRORS[case]
    run = run_parallel(4, [model, "-o", tmp_path / "out.h5"], tmp_path)
    assert run.returncode == status, run.stdout + run.stderr
    assert run.stderr.count("ddc2d: error:") == 1, run.stderr
    for word in words:
        assert word in run.stderr
    assert list(tmp_path.iterdir()) == []  # neither the output nor a .partial file


def test_resume_on_four_processes_is_refused(tmp_path):
    # Refused before anything is read: the resume file need not exist.
    run = run_parallel(4, [DATA / "growth" / "good.nml", "--resume", "absent.h5", "-o",
                           tmp_path / "out.h5"], tmp_path)
    assert run.returncode == 2, run.stdout + run.stderr
    assert run.stderr.count("ddc2d: error:") == 1, run.stderr
    assert "--resume runs on one process (mpiexec -n 1)" in run.stderr
    assert list(tmp_path.iterdir()) == []


def test_resume_continues_the_run_on_a_single_process(tmp_path):
    # A growth run of 2 steps continued to 4 by --resume: the MPI program on one process
    # continues it as the serial program does (it does not start again from the beginning).
    growth = ("&model youngs_modulus = 50000, poissons_ratio = 0.25 /\n"
              "&remote_stress syy = 10 /\n"
              "&fracture name = 'crack', x = -1, 1, y = 0, 0, elements = 8, "
              "condition = 'traction' /\n"
              "&growth steps = {steps}, toughness = 15.5, increment = 0.2 /\n")
    (tmp_path / "old.nml").write_text(growth.format(steps=2))
    (tmp_path / "new.nml").write_text(growth.format(steps=4))
    old = run_serial([tmp_path / "old.nml", "-o", tmp_path / "old.h5"], tmp_path)
    assert old.returncode == 0, old.stdout + old.stderr
    # A resumed run takes the earlier records over as they are, a fresh one computes them:
    # mark the first record, so that only a resumed run can carry the mark.
    with h5py.File(tmp_path / "old.h5", "r+") as before:
        mark = 1.5 * before["growth/k_eq"][0]
        before["growth/k_eq"][0] = mark
    resumed = [tmp_path / "new.nml", "--resume", tmp_path / "old.h5"]
    serial = run_serial(resumed + ["-o", tmp_path / "serial.h5"], tmp_path)
    assert serial.returncode == 0, serial.stdout + serial.stderr
    run = run_parallel(1, resumed + ["-o", tmp_path / "single.h5"], tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
    found = differences(tmp_path / "serial.h5", tmp_path / "single.h5")
    assert "/growth/k1" in found and max(found.values()) <= RTOL
    with h5py.File(tmp_path / "old.h5") as before, h5py.File(tmp_path / "single.h5") as after:
        assert after["growth/step"].shape[0] > before["growth/step"].shape[0]
        assert after["growth/k_eq"][0] == mark, "the run started again instead of resuming"


def test_one_process_runs_what_is_not_distributed(tmp_path):
    # A loading history (Lemke's method) on one process runs as in the serial build.
    model = DATA / "history" / "good.nml"
    serial = run_serial([model, "-o", tmp_path / "serial.h5"], tmp_path)
    assert serial.returncode == 0, serial.stdout + serial.stderr
    run = run_parallel(1, [model, "-o", tmp_path / "one.h5"], tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
    found = differences(tmp_path / "serial.h5", tmp_path / "one.h5")
    assert "/history/ds" in found and max(found.values()) <= RTOL
    with h5py.File(tmp_path / "one.h5") as one:
        assert read_solver(one)["attrs"]["processes"] == 1


def test_blas_kernel_older_than_the_cpu_warns_without_running_again(tmp_path):
    # The stand-in for openblas_get_corename (tests/fake_openblas_core.c) reports Prescott:
    # the MPI program, whose processes mpiexec started, warns once (the root) with the
    # variable to set and how to pass it, and runs on (OpenBLAS loaded once per process).
    lib = os.environ.get("DDC2D_FAKE_CORE_LIB")
    flags = set(next((line for line in Path("/proc/cpuinfo").read_text().splitlines()
                      if line.startswith("flags")), "").split())
    if not lib or not {"avx2", "fma"} <= flags:
        pytest.skip("needs DDC2D_FAKE_CORE_LIB and a CPU with AVX2")
    env = {k: v for k, v in environment().items() if k != "OPENBLAS_CORETYPE"}
    env.update(LD_PRELOAD=str(Path(lib).resolve()), OPENBLAS_VERBOSE="2")
    command = [executable("MPIEXEC"), "-q", "--oversubscribe", "-n", "2", "-x", "LD_PRELOAD",
               "-x", "OPENBLAS_VERBOSE", executable("DDC2D_EXE"), MODELS["straight"], "-o",
               str(tmp_path / "out.h5")]
    run = subprocess.run(command, cwd=tmp_path, capture_output=True, text=True,
                         timeout=TIMEOUT, env=env, check=False)
    assert run.returncode == 0, run.stdout + run.stderr
    warnings = [line for line in run.stderr.splitlines()
                if line.startswith("ddc2d: warning: OpenBLAS runs its Prescott kernel")]
    assert len(warnings) == 1, run.stderr
    assert "mpiexec -x OPENBLAS_CORETYPE=" in warnings[0]
    # The real OpenBLAS chose its own kernel, in each process once (it was started once)
    assert run.stderr.count(f"Core: {serial_kernels(own_choice=True)[1]}") == 2, run.stderr
    assert run.stderr.count("Core: ") == 2, run.stderr


def test_benchmark_records_every_process(tmp_path):
    # scripts/benchmark.py --mpi 2: per-process peak RSS and the grid in the JSON records.
    exe = Path(executable("DDC2D_EXE"))
    out = tmp_path / "bench.json"
    done = subprocess.run(
        [executable("DDC2D_PYTHON"), str(REPO / "scripts" / "benchmark.py"), "--exe", str(exe),
         "--sizes", "12,30", "--case", "mixed", "--json", str(out), "--threads", "1",
         "--grid", "5", "--mpi", "2", "--block-size", "8", "--mpiexec", executable("MPIEXEC"),
         "--lu-exe", str(exe.parent.parent / "tests" / "ddc2d_lu_benchmark")],
        capture_output=True, text=True, timeout=TIMEOUT, env=environment(), check=False)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "rank RSS MB" in done.stdout
    records = json.loads(out.read_text())
    assert [r["n"] for r in records] == [12, 30]
    for r in records:
        assert r["processes"] == 2 and r["process_grid"] == [1, 2] and r["block_size"] == 8
        assert len(r["peak_rss_mb_per_rank"]) == 2
        assert all(v > 1.0 for v in r["peak_rss_mb_per_rank"])
        assert r["peak_rss_mb"] == max(r["peak_rss_mb_per_rank"])
        assert r["method"] == "newton" and sum(r["states"].values()) == r["n"]
