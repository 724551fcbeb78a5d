"""Where a result came from (docs/output-reference.md): the BLAS, its kernel and who chose it,
the compiler and its options, the CPU and the thread counts, in the result file's root
attributes (the BLAS pair in /solver too), the echo and one line of the summary; and the
start-up check of the kernel: a kernel the user chose is respected, one OpenBLAS chose below the
CPU's instruction set makes the serial program run itself again once with OPENBLAS_CORETYPE set.

The second part preloads a stand-in for openblas_get_corename (tests/fake_openblas_core.c,
$DDC2D_FAKE_CORE_LIB) that reports "Prescott" unless OPENBLAS_CORETYPE is set, on a CPU
with AVX2 (else skipped): the real OpenBLAS still computes with its own kernel.
"""

import os
import subprocess
from pathlib import Path

import h5py
import pytest

from conftest import ddc2d_exe

MODEL = """\
&model youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress sxx = -143.75, syy = -81.25, sxy = 54.13 /
&fracture x = -1, 1, y = 0, 0, elements = 40, mu = 0.6, sf = 1 /
"""
TEXT_ATTRIBUTES = ("blas", "blas_core", "blas_core_chosen_by", "compiler", "compiler_options",
                   "cpu")


def run(tmp_path, env_changes, unset=()):
    """ddc2d on the model with the environment changed; the OpenMP threads' waiting is set, so
    that the program runs itself again for its BLAS kernel alone (tests/python/test_threads.py
    checks the other start)."""
    (tmp_path / "fault.nml").write_text(MODEL)
    env = {k: v for k, v in os.environ.items()
           if k not in ("OPENBLAS_CORETYPE", "DDC2D_OPENBLAS_CHOSE", *unset)}
    env.update({"OMP_WAIT_POLICY": "PASSIVE"}, **env_changes)
    return subprocess.run([str(ddc2d_exe()), "fault.nml", "-o", "out.h5"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=120, env=env)


def attributes(path):
    with h5py.File(path, "r") as f:
        def text(v):
            return v.decode() if isinstance(v, bytes) else str(v)
        root = {k: text(f.attrs[k]).strip() for k in TEXT_ATTRIBUTES}
        root.update(threads=int(f.attrs["threads"]), blas_threads=int(f.attrs["blas_threads"]))
        solver = {k: text(f["solver"].attrs[k]).strip() for k in ("blas", "blas_core")}
    return root, solver


def uses_openblas():
    out = subprocess.run(["ldd", str(ddc2d_exe())], capture_output=True, text=True).stdout
    return "openblas" in out


def cpu_flags():
    try:
        return set(next(line for line in Path("/proc/cpuinfo").read_text().splitlines()
                        if line.startswith("flags")).split())
    except (OSError, StopIteration):
        return set()


def cpu_has_avx2():
    return {"avx2", "fma"} <= cpu_flags()


def test_the_result_says_how_it_was_computed(tmp_path):
    done = run(tmp_path, {"OMP_NUM_THREADS": "2", "OPENBLAS_NUM_THREADS": "1"})
    assert done.returncode == 0, done.stdout + done.stderr
    root, solver = attributes(tmp_path / "out.h5")
    for name in TEXT_ATTRIBUTES:
        assert root[name], f"root attribute {name} is empty"
    assert root["threads"] == 2
    assert solver == {"blas": root["blas"], "blas_core": root["blas_core"]}
    assert "GCC" in root["compiler"] or "Fortran" in root["compiler"], root["compiler"]
    # OpenBLAS's own choice, unless it chose a kernel older than the CPU (OpenBLAS 0.3.21
    # runs Prescott on CPUs it does not know): ddc2d then runs itself again with the
    # newest kernel the CPU has (docs/performance.md#the-blas-kernel).
    chosen_by = root["blas_core_chosen_by"]
    if chosen_by != "the BLAS":
        newest = "SkylakeX" if {"avx512f", "avx512bw", "avx512vl", "avx512dq"} <= cpu_flags() \
            else "Haswell"
        assert cpu_has_avx2() and root["blas_core"] == newest, (chosen_by, root["blas_core"])
        assert chosen_by.startswith(f"ddc2d (OPENBLAS_CORETYPE={newest}; OpenBLAS had chosen "), \
            chosen_by
    lines = [line for line in done.stdout.splitlines() if line.startswith("  computed with ")]
    assert len(lines) == 1, done.stdout
    assert f"(kernel {root['blas_core']}, chosen by {chosen_by})" in lines[0]
    assert "2 OpenMP thread(s)" in lines[0]
    assert f"  blas: {root['blas']}; kernel {root['blas_core']}" in done.stdout
    if uses_openblas():
        assert root["blas"].startswith("OpenBLAS ") and root["blas_threads"] == 1, root


@pytest.mark.skipif(not uses_openblas(), reason="ddc2d is not linked to OpenBLAS")
def test_a_kernel_the_user_chose_is_respected(tmp_path):
    # As scripts/test-kernels.sh runs the suites: no re-run, no warning.
    done = run(tmp_path, {"OPENBLAS_CORETYPE": "Nehalem", "OPENBLAS_VERBOSE": "2"})
    assert done.returncode == 0, done.stdout + done.stderr
    assert done.stderr.count("Core: Nehalem") == 1, done.stderr  # started once
    assert "ddc2d: warning" not in done.stderr
    root, solver = attributes(tmp_path / "out.h5")
    assert solver["blas_core"] == "Nehalem"
    assert root["blas_core_chosen_by"] == "the user (OPENBLAS_CORETYPE=Nehalem)"
    if cpu_has_avx2():
        assert "is the user's choice; this CPU could run " in done.stdout


def fake_core_library():
    lib = os.environ.get("DDC2D_FAKE_CORE_LIB")
    if not lib or not Path(lib).is_file():
        pytest.skip("DDC2D_FAKE_CORE_LIB (the build's ddc2d_fake_core) not given")
    if not cpu_has_avx2():
        pytest.skip("this CPU has no AVX2: an SSE kernel is no worse than it")
    return str(Path(lib).resolve())


@pytest.mark.skipif(not uses_openblas(), reason="ddc2d is not linked to OpenBLAS")
def test_an_old_kernel_makes_the_program_run_again_once(tmp_path):
    done = run(tmp_path, {"LD_PRELOAD": fake_core_library(), "OPENBLAS_VERBOSE": "2"})
    assert done.returncode == 0, done.stdout + done.stderr
    assert "ddc2d: warning" not in done.stderr, done.stderr
    # The echo is printed once, by the second process, with the kernel ddc2d asked for.
    assert done.stdout.count("ddc2d model: ") == 1, done.stdout
    assert done.stderr.count("Core: ") == 2, done.stderr  # OpenBLAS loaded twice
    root, solver = attributes(tmp_path / "out.h5")
    best = ("SkylakeX" if {"avx512f", "avx512bw", "avx512vl", "avx512dq"} <= cpu_flags()
            else "Haswell")
    assert solver["blas_core"] == best
    assert root["blas_core_chosen_by"] == (f"ddc2d (OPENBLAS_CORETYPE={best}; OpenBLAS had "
                                           "chosen Prescott)")


@pytest.mark.skipif(not uses_openblas(), reason="ddc2d is not linked to OpenBLAS")
def test_a_rerun_that_does_not_take_warns_instead_of_looping(tmp_path):
    done = run(tmp_path, {"LD_PRELOAD": fake_core_library(), "OPENBLAS_VERBOSE": "2",
                          "DDC2D_TEST_CORENAME": "Prescott"})
    assert done.returncode == 0, done.stdout + done.stderr
    assert done.stderr.count("Core: ") == 2, done.stderr  # ran again once, not more
    warnings = [line for line in done.stderr.splitlines() if line.startswith("ddc2d: warning")]
    assert len(warnings) == 1, done.stderr
    assert "although ddc2d set OPENBLAS_CORETYPE=" in warnings[0]
    root, _ = attributes(tmp_path / "out.h5")
    assert root["blas_core"] == "Prescott"
