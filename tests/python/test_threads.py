"""What docs/performance.md#threads says of threads, checked on the executable: results are bit
for bit the same from run to run with the same OMP_NUM_THREADS and OPENBLAS_NUM_THREADS, and
with 1 and 2 OpenMP threads; 1 and 2 OpenBLAS threads sum the factorizations in other orders, so
there the results agree to round-off only (within 1e-10 of the largest magnitude of each kind of
quantity, the rule of tests/compare_results.py). tests/fortran/test_threads.pf checks the OpenMP
part inside one process."""

import os
import subprocess

import h5py
import numpy as np
import pytest

from compare_results import RTOL, differences
from conftest import REPO_ROOT, ddc2d_exe

#: A growth run with a grid (every OpenMP loop, the growth solver's borders) and a contact
#: model with stick, slip and open elements.
MODELS = {"growth": REPO_ROOT / "input" / "echelon_cracks_linking.nml",
          "contact": REPO_ROOT / "tests" / "data" / "mpi" / "kinked_fault.nml"}
#: (OpenMP threads, OpenBLAS threads) of the runs.
SETTINGS = ((1, 1), (2, 1), (2, 2))


def result_arrays(path):
    """Every dataset of the results (not /solver: its times and thread counts differ)."""
    found = {}
    with h5py.File(path, "r") as f:
        def visit(name, item):
            if isinstance(item, h5py.Dataset) and not name.startswith("solver"):
                found[name] = item[()]
        f.visititems(visit)
    return found


def bit_for_bit(a, b):
    """The datasets of two result files that are not identical, bit for bit."""
    x, y = result_arrays(a), result_arrays(b)
    assert x.keys() == y.keys()
    return [name for name in x
            if np.asarray(x[name]).tobytes() != np.asarray(y[name]).tobytes()]


@pytest.fixture(scope="module", params=sorted(MODELS))
def runs(request, tmp_path_factory):
    """The model run twice with each setting: {(omp, blas, run): result file}."""
    folder = tmp_path_factory.mktemp(request.param)
    files = {}
    for omp, blas in SETTINGS:
        for run in (1, 2):
            out = folder / f"omp{omp}_blas{blas}_{run}.h5"
            env = dict(os.environ, OMP_NUM_THREADS=str(omp), OPENBLAS_NUM_THREADS=str(blas))
            done = subprocess.run([str(ddc2d_exe()), str(MODELS[request.param]), "-o",
                                   str(out)], cwd=folder, env=env, capture_output=True,
                                  text=True, timeout=600)
            assert done.returncode == 0, done.stdout + done.stderr
            with h5py.File(out, "r") as f:
                assert int(f["solver"].attrs["threads"]) == omp
            files[omp, blas, run] = out
    return files


@pytest.mark.parametrize("omp, blas", SETTINGS)
def test_run_to_run_bit_for_bit(runs, omp, blas):
    assert bit_for_bit(runs[omp, blas, 1], runs[omp, blas, 2]) == []


def test_one_and_two_openmp_threads_bit_for_bit(runs):
    assert bit_for_bit(runs[1, 1, 1], runs[2, 1, 1]) == []


def test_one_and_two_openblas_threads_agree_to_round_off(runs):
    found = differences(runs[2, 1, 1], runs[2, 2, 1])
    worst = max(found, key=found.get)
    assert found[worst] <= RTOL, f"{worst} differs by {found[worst]:.1e}"



def waiting(tmp_path, **settings):
    """How the OpenMP threads of a run of ddc2d on 2 threads wait: the spin count libgomp
    took last (OMP_DISPLAY_ENV=verbose prints it at each start of the program) and the
    echo's line, with OMP_WAIT_POLICY and GOMP_SPINCOUNT unset unless given."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
    env.update(OMP_NUM_THREADS="2", OMP_DISPLAY_ENV="VERBOSE")
    env.update(settings)
    done = subprocess.run([str(ddc2d_exe()), str(MODELS["contact"]), "-o",
                           str(tmp_path / "wait.h5")], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    spins = [line.split("=")[1].strip().strip("'") for line in
             (done.stdout + done.stderr).splitlines() if "GOMP_SPINCOUNT =" in line]
    echo = [line.strip() for line in done.stdout.splitlines()
            if line.startswith("  openmp:")]
    assert len(echo) == 1, done.stdout
    return spins, echo[0]


def test_openmp_threads_wait_asleep_unless_the_user_chose(tmp_path):
    # Run again once, the second time without spinning.
    spins, echo = waiting(tmp_path)
    assert len(spins) == 2 and spins[-1] == "0", spins
    assert echo == ("openmp: 2 thread(s), waiting asleep (OMP_WAIT_POLICY=PASSIVE, set by "
                    "ddc2d)")
    spins, echo = waiting(tmp_path, OMP_WAIT_POLICY="ACTIVE")
    assert len(spins) == 1 and int(spins[0]) > 0, spins
    assert "OMP_WAIT_POLICY=ACTIVE" in echo and "as the user chose" in echo
    spins, echo = waiting(tmp_path, GOMP_SPINCOUNT="1000")
    assert spins == ["1000"], spins
    # One thread has nothing to wait for: no second start.
    spins, echo = waiting(tmp_path, OMP_NUM_THREADS="1")
    assert len(spins) == 1 and echo == "openmp: 1 thread(s)"


def blas_threads(tmp_path, model, **settings):
    """The BLAS threads a run of ddc2d recorded (root attribute blas_threads) and its echo's
    line about them, on 2 OpenMP threads with OPENBLAS_NUM_THREADS unset unless given."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS")}
    env.update(OMP_NUM_THREADS="2")
    env.update(settings)
    out = tmp_path / "blas.h5"
    done = subprocess.run([str(ddc2d_exe()), str(model), "-o", str(out)], cwd=tmp_path,
                          env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    echo = [line.strip() for line in done.stdout.splitlines()
            if line.startswith("  blas threads:")]
    assert len(echo) == 1, done.stdout
    with h5py.File(out, "r") as f:
        return int(f.attrs["blas_threads"]), echo[0]


def test_a_small_model_runs_one_blas_thread_unless_the_user_sets_them(tmp_path):
    own = min(os.cpu_count(), 64)  # OpenBLAS's own count: the cores, at most MAX_THREADS
    threads, echo = blas_threads(tmp_path, MODELS["contact"])
    assert threads == 1, echo
    assert own == 1 or "unknowns, below 4000" in echo, echo
    threads, echo = blas_threads(tmp_path, MODELS["contact"], OPENBLAS_NUM_THREADS="2")
    assert threads == 2 and echo == "blas threads: 2 (OPENBLAS_NUM_THREADS)"
    # 2000 elements, 4000 unknowns: the BLAS's own count.
    big = tmp_path / "big.nml"
    big.write_text("&model youngs_modulus = 1.0e4, poissons_ratio = 0.25 /\n"
                   "&remote_stress syy = 1.0 /\n"
                   "&fracture x = -1.0, 1.0, y = 0.0, 0.0, elements = 2000, "
                   "condition = 'traction' /\n")
    threads, echo = blas_threads(tmp_path, big)
    assert threads == own and echo == f"blas threads: {own}", echo
