"""A model too large for this machine's memory (docs/performance.md#the-memory-check): ddc2d
estimates the memory of the method it will use before allocating anything large, compares it
with what the machine or its cgroup offers, and refuses with one message and exit status 5, not
a Fortran runtime error; a model that fits echoes its estimate."""

import os
import re
import resource
import subprocess

import pytest

from conftest import ddc2d_exe
from ddc2d import benchmark  # ddc2d-benchmark: the benchmark's models

MODEL = """\
&model youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress sxx = -143.75, syy = -81.25, sxy = 54.13 /
&fracture name = 'fault', x = -1000, 1000, y = 0, 0, elements = {n}, mu = 0.6, sf = 1 /
{extra}"""


def run(tmp_path, n, extra=""):
    (tmp_path / "big.nml").write_text(MODEL.format(n=n, extra=extra))
    return subprocess.run([str(ddc2d_exe()), "big.nml"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=300)


@pytest.mark.parametrize("extra, method, need", [
    # newton from 300 contact elements on; every element slips from the start: A (32 N^2
    # bytes) and a reduced system of N unknowns (11 N^2 bytes). matrix = 'dense': 'auto'
    # would take a hierarchical matrix here (test_hierarchical.py).
    ("&solver matrix = 'dense' /\n", "newton", "1.7 TB"),
    ("&solver lcp_method = 'lemke' /\n", "lemke", "16 TB"),
    ("&load_path steps = 4, sxy = 0, 54.13 /\n&solver matrix = 'dense' /\n",
     "newton (loading history)", "3 TB"),
    ("&load_path steps = 4, sxy = 0, 54.13 /\n&solver lcp_method = 'lemke' /\n",
     "lemke (loading history)", "16 TB"),
])
def test_a_model_too_large_is_refused_with_exit_5(tmp_path, extra, method, need):
    done = run(tmp_path, 200000, extra)
    assert done.returncode == 5, done.stdout + done.stderr
    errors = [line for line in done.stderr.splitlines() if line.startswith("ddc2d: error: ")]
    assert len(errors) == 1, done.stderr
    assert errors[0].startswith(f"ddc2d: error: 200000 elements need about {need} of memory "
                                f"with the {method} method, but about ")
    assert " is available here (" in errors[0] and " elements fit. " in errors[0]
    assert "Error allocating" not in done.stderr and "Backtrace" not in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["big.nml"]  # no output at all


def test_a_model_that_fits_echoes_its_estimate(tmp_path):
    done = run(tmp_path, 40)
    assert done.returncode == 0, done.stderr
    memory = [line for line in done.stdout.splitlines() if line.startswith("  memory: ")]
    assert len(memory) == 1
    # 20 MB for the program, a little for 40 elements (Lemke below 300 contact elements).
    assert re.fullmatch(r"  memory: about 2\d MB needed \(lemke\), (.+ available \(.+\)|"
                        r"no limit found)", memory[0]), memory[0]


ADDRESS_SPACE_LIMIT = 700 * 2**20


def limit_address_space():
    """In the child: at most 700 MB of address space, far less than the machine offers."""
    resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE_LIMIT, ADDRESS_SPACE_LIMIT))


@pytest.mark.parametrize("n, extra, what", [
    (20, "&load_path steps = 1000000, sxy = 0, 54.13 /\n",
     "the history of 20 elements at 1000001 steps (800 MB)"),
    (2000, "&solver lcp_method = 'lemke' /\n",
     "the LCP matrices of 2000 contact elements (Lemke) (704 MB)"),
])
def test_an_allocation_that_fails_all_the_same_is_a_clean_exit_5(tmp_path, n, extra, what):
    # The estimate (about 1.9 and 1.6 GB) passes against the machine's memory, but the
    # process may not have that much: the allocation itself fails, and must say what.
    (tmp_path / "big.nml").write_text(MODEL.format(n=n, extra=extra))
    done = subprocess.run([str(ddc2d_exe()), "big.nml"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=300, preexec_fn=limit_address_space,
                          env={**os.environ, "OMP_NUM_THREADS": "1",
                               "OPENBLAS_NUM_THREADS": "1"})
    assert done.returncode == 5, done.stdout + done.stderr
    errors = [line for line in done.stderr.splitlines() if line.startswith("ddc2d: error: ")]
    expected = (f"ddc2d: error: not enough memory for {what}; "
                "see the size guide in docs/performance.md#size-guide")
    assert errors == [expected], done.stderr
    assert "Error allocating" not in done.stderr and "Backtrace" not in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["big.nml"]


def test_help_gives_exit_status_5(tmp_path):
    done = subprocess.run([str(ddc2d_exe()), "--help"], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 0
    assert "5 the model is too large for the memory here" in " ".join(done.stdout.split())


UNITS = {"kB": 1e3, "MB": 1e6, "GB": 1e9, "TB": 1e12}


def run_with_peak(tmp_path, text):
    """Run a model on 2 threads: its standard output and its peak resident memory [bytes]."""
    (tmp_path / "model.nml").write_text(text)
    with open(tmp_path / "stderr.txt", "w") as errors:
        process = subprocess.Popen([str(ddc2d_exe()), "model.nml", "-o", "model.h5"],
                                   cwd=tmp_path, stdout=subprocess.PIPE, stderr=errors,
                                   text=True, env={**os.environ, "OMP_NUM_THREADS": "2",
                                                   "OPENBLAS_NUM_THREADS": "2"})
        stdout = process.stdout.read()
        process.stdout.close()
        # os.wait4: the peak resident memory of this child alone.
        _, status, usage = os.wait4(process.pid, 0)
    assert os.waitstatus_to_exitcode(status) == 0, stdout
    return stdout, usage.ru_maxrss * 1024.0


@pytest.mark.parametrize("case", ["straight", "mixed"])
def test_the_echoed_need_is_the_peak_memory_within_25_percent(tmp_path, case):
    # The benchmark's straight fault (every element slips) and kinked fault network (stick,
    # slip, open; its reduced system grows over 8 Newton iterations) at N = 2000: the need
    # echoed for the starting states against the peak resident memory of the run, K's local
    # re-solve included (its zones and kept rows: 161 MB of the network's 330 MB,
    # docs/theory/tips.md#cost).
    n = 2000
    stdout, peak = run_with_peak(tmp_path,
                                 benchmark.CASES[case](n, 0, 0) + "&solver lcp_method = 'auto' /\n")
    match = re.search(r"^  memory: about ([0-9.]+) (kB|MB|GB|TB) needed \(newton, from the "
                      r"starting states: (\d+) unknowns\), up to ([0-9.]+) (kB|MB|GB|TB) should "
                      r"every element slip and open; ([0-9.]+) (kB|MB|GB|TB) of it for K's local "
                      r"re-solve; ", stdout, re.MULTILINE)
    assert match, stdout
    need = float(match.group(1)) * UNITS[match.group(2)]
    worst = float(match.group(4)) * UNITS[match.group(5)]
    k_share = float(match.group(6)) * UNITS[match.group(7)]
    assert abs(need - peak) <= 0.25 * peak, (need, peak)
    assert 0 < k_share < need
    # The solve's own estimate at its largest (the old estimate) is far off its peak.
    assert worst - k_share > 1.5 * (peak - k_share), (worst, peak, k_share)


def test_a_hierarchical_solve_peaks_within_25_percent_of_its_echoed_need(tmp_path):
    # The benchmark's straight fault at N = 8000 on a hierarchical matrix: the run's
    # compressed operator and H-LU factors are freed before the midpoint responses assemble
    # their own matrices (when both were held, the peak was 193 MB against 133 MB echoed;
    # 117 MB since). K from the tip element: the solve's own memory (the K re-solve's share
    # is tested on the dense models above, where it is smaller than the solve's).
    stdout, peak = run_with_peak(tmp_path, benchmark.CASES["straight"](8000, 0, 0)
                                 + "&solver matrix = 'hierarchical', k_method = 'tip_element' /\n")
    match = re.search(r"^  memory: about ([0-9.]+) (kB|MB|GB|TB) needed \(newton, hierarchical "
                      r"matrix\)", stdout, re.MULTILINE)
    assert match, stdout
    need = float(match.group(1)) * UNITS[match.group(2)]
    assert abs(need - peak) <= 0.25 * peak, (need, peak)
