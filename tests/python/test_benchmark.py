"""scripts/benchmark.py on tiny sizes: it runs, prints a table and writes the JSON records
of SPEC section 6."""

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


def test_benchmark_bad_sizes(tmp_path):
    done = subprocess.run(
        [sys.executable, str(BENCHMARK), "--exe", str(ddc2d_exe()), "--sizes", "ten",
         "--case", "straight", "--json", str(tmp_path / "b.json")],
        capture_output=True, text=True)
    assert done.returncode == 2
    assert "--sizes" in done.stderr
    assert not (tmp_path / "b.json").exists()
