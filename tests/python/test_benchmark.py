"""scripts/benchmark.py on tiny sizes: it runs, prints a table and writes the JSON records
of docs/performance.md#the-benchmark."""

import json
import subprocess
import sys

import pytest

from conftest import REPO_ROOT, ddc2d_exe

BENCHMARK = REPO_ROOT / "scripts" / "benchmark.py"
PHASES = {"assembly", "factorization", "lcp", "fields", "output", "total"}


def lu_exe():
    exe = ddc2d_exe().resolve().parent.parent / "tests" / "ddc2d_lu_benchmark"
    assert exe.is_file(), f"{exe} missing: build the tests"
    return exe


@pytest.mark.parametrize("case,method", [("straight", "auto"), ("mixed", "newton"),
                                         ("mixed", "lemke")])
def test_benchmark_records(tmp_path, case, method):
    out = tmp_path / "bench.json"
    done = subprocess.run(
        [sys.executable, str(BENCHMARK), "--exe", str(ddc2d_exe()), "--sizes", "12,30",
         "--case", case, "--json", str(out), "--threads", "1", "--grid", "5",
         "--lcp-method", method, "--lu-exe", str(lu_exe())],
        capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "total" in done.stdout and "LU ref" in done.stdout
    records = json.loads(out.read_text())
    assert [r["n"] for r in records] == [12, 30]
    for r in records:
        assert r["case"] == case
        assert r["threads"] == 1
        assert set(r["seconds"]) == PHASES
        assert all(v >= 0.0 for v in r["seconds"].values())
        assert r["seconds"]["total"] >= r["seconds"]["lcp"]
        assert r["lu_reference_seconds"] > 0.0
        assert r["peak_rss_mb"] > 1.0
        expected = "lemke" if method != "newton" else "newton"
        assert r["method"] == expected and r["fallback"] == ""
        assert sum(r["states"].values()) == r["n"]
        if case == "mixed":
            assert all(r["states"][s] > 0 for s in ("stick", "slip", "open")), r["states"]
        assert r["blas"] and r["blas_core"], "the BLAS and its kernel"
        assert r["estimated_mb"] > 1.0
        assert abs(r["untimed_share"]) < 1.0


def test_benchmark_thread_list(tmp_path):
    _, records = run_benchmark(tmp_path, "--case", "straight", "--grid", "0",
                               "--threads", "1,2")
    assert [(r["threads"], r["n"]) for r in records] == [(1, 12), (1, 30), (2, 12), (2, 30)]


def run_benchmark(tmp_path, *options, sizes="12,30"):
    out = tmp_path / "bench.json"
    done = subprocess.run(
        [sys.executable, str(BENCHMARK), "--exe", str(ddc2d_exe()), "--sizes", sizes,
         "--json", str(out), "--threads", "1", "--lu-exe", str(lu_exe()), *options],
        capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return done.stdout, json.loads(out.read_text())


def test_benchmark_history_against_lemke(tmp_path):
    stdout, records = run_benchmark(tmp_path, "--case", "history", "--steps", "9",
                                    "--lcp-method", "newton", "--compare-lemke")
    assert "10 steps" in stdout and "same states: True" in stdout
    for r in records:
        assert r["steps"] == 10 and r["fallback_steps"] == 0
        assert r["method"] == "newton" and r["newton_iterations"] >= 10
        # The states change at most at the vertices: the factors are reused in between.
        assert r["factorization_reuses"] > 0
        assert r["lemke"]["same_states"] and r["lemke"]["max_dd_difference"] < 1e-10
        assert r["lemke"]["seconds"] > 0.0 and r["lemke"]["pivots"] > 0


def test_benchmark_fields(tmp_path):
    _, records = run_benchmark(tmp_path, "--case", "fields", "--grid", "8")
    for r in records:
        assert r["case"] == "fields"
        assert r["fields_over_lu"] == r["seconds"]["fields"] / r["lu_reference_seconds"]


def test_benchmark_bad_sizes(tmp_path):
    done = subprocess.run(
        [sys.executable, str(BENCHMARK), "--exe", str(ddc2d_exe()), "--sizes", "ten",
         "--case", "straight", "--json", str(tmp_path / "b.json")],
        capture_output=True, text=True)
    assert done.returncode == 2
    assert "--sizes" in done.stderr
    assert not (tmp_path / "b.json").exists()


def test_benchmark_growth_history(tmp_path):
    # The growth case's flaw along 3 load steps (syy from -2 to -100): the wings grow at
    # some of them; the record has the load steps and the growth steps.
    stdout, records = run_benchmark(tmp_path, "--case", "growth-history", "--steps", "3",
                                    "--lcp-method", "newton", sizes="100")
    assert "growth steps" in stdout and "N_final" in stdout and "4 steps" in stdout
    (r,) = records
    assert r["case"] == "growth-history" and r["method"] == "newton"
    assert r["steps"] == 4 and r["end_reason"] == "arrested"
    assert r["growth_steps"] >= 1 and r["n_final"] > r["n"]
    # The two point-symmetric tips grow alike, by at most an increment of 20 elements per
    # growth step (a kink shortened to the stable length has fewer).
    new = r["n_final"] - r["n"]
    assert new % 2 == 0 and new <= 2 * 20 * r["growth_steps"], (new, r["growth_steps"])
    assert sum(r["states"].values()) == r["n_final"]
    assert r["total_over_lu"] == r["seconds"]["total"] / r["lu_reference_seconds"]


def test_benchmark_injection(tmp_path):
    # The injection case on 40 elements, 10 steps: the patch around the held overpressure
    # slips and grows; the record has the steps.
    stdout, records = run_benchmark(tmp_path, "--case", "injection", "--steps", "10",
                                    sizes="40")
    assert "11 steps" in stdout
    (r,) = records
    assert r["case"] == "injection" and r["steps"] == 11
    assert 0 < r["states"]["slip"] < r["n"] and r["states"]["open"] == 0
    assert r["total_over_lu"] == r["seconds"]["total"] / r["lu_reference_seconds"]


def test_benchmark_kgd(tmp_path):
    # The KGD case ending with 30 elements after 5 growth steps (20 at the start): every
    # element open, one history row per step and the initial one; the total time is the
    # whole run's.
    stdout, records = run_benchmark(tmp_path, "--case", "kgd", "--steps", "5", sizes="30")
    assert "6 steps" in stdout
    (r,) = records
    assert r["case"] == "kgd" and r["steps"] == 6 and r["n"] == 30
    assert r["states"]["open"] == 30
    assert r["seconds"]["total"] > r["seconds"]["lcp"]


def test_benchmark_growth(tmp_path):
    # 80 and 100 elements: on fewer, the increment of 20 elements (over 1 m) makes the first
    # kink a closed one, which does not grow (docs/theory/growth.md#closed-kinks).
    stdout, records = run_benchmark(tmp_path, "--case", "growth", "--steps", "2",
                                    "--lcp-method", "newton", sizes="80,100")
    assert "growth steps" in stdout and "N_final" in stdout
    for r in records:
        assert r["case"] == "growth" and r["method"] == "newton"
        assert r["growth_steps"] == 2 and r["end_reason"] == "step_limit"
        # Both tips grow by 20 elements per step; each step solves at least once.
        assert r["n_final"] == r["n"] + 2 * 2 * 20
        assert r["solves"] >= 1 + r["growth_steps"]
        assert sum(r["states"].values()) == r["n_final"]
        assert r["total_over_lu"] == r["seconds"]["total"] / r["lu_reference_seconds"]
        # Counts over the whole run (at these sizes the new unknowns outnumber what an
        # update takes: suite growth_solver checks the bordering).
        assert r["factorizations"] >= 1 and r["newton_iterations"] >= r["solves"]


def test_benchmark_growth_work(tmp_path):
    # One growth step of the growth case's flaw by the work criterion, beside the MTS run of
    # the same model: the seeded search takes at least its three trials per tip (two tips)
    # and fewer than the grid's 37.
    stdout, records = run_benchmark(tmp_path, "--case", "growth-work", "--steps", "1",
                                    "--lcp-method", "newton", sizes="80")
    assert "x the MTS run" in stdout and "per growth step" in stdout
    r = records[0]
    assert r["case"] == "growth-work" and r["growth_steps"] == 1
    assert 1 + 2 * 3 <= r["solves"] < 1 + 2 * 37
    assert r["solves_per_step"] == r["solves"] / r["growth_steps"]
    assert r["updates_per_step"] == r["low_rank_updates"] / r["growth_steps"]
    assert r["mts"]["growth_steps"] == 1 and r["mts"]["solves"] >= 2
    assert r["over_mts"] == r["seconds"]["total"] / r["mts"]["seconds"]


def test_benchmark_hierarchical_matrix(tmp_path):
    """--matrix hierarchical --compare-dense: the records say which matrix, its compression
    and its gap to the dense run; the fitted time exponent and the figure."""
    figure = tmp_path / "scaling.png"
    stdout, records = run_benchmark(tmp_path, "--case", "mixed", "--grid", "0",
                                    "--lcp-method", "newton", "--matrix", "hierarchical",
                                    "--compare-dense", "--figure", str(figure),
                                    sizes="300,600")
    assert [r["n"] for r in records] == [300, 600]
    for r in records:
        assert r["matrix"] == "hierarchical" and r["method"] == "newton"
        assert 0.0 < r["compression_ratio"] < 1.0
        assert r["error_vs_dense"]["same_states"]
        assert r["error_vs_dense"]["max_dd_difference"] <= 1e-6
        assert r["time_exponent"] == records[0]["time_exponent"]
    assert "hierarchical matrix" in stdout and "grows as N^" in stdout
    assert figure.stat().st_size > 10_000
