"""ddc2d-growth-convergence, run as scripts/growth_convergence.py (the convergence study of
docs/theory/growth.md#convergence-with-the-increment) on a tiny study: it runs ddc2d once per
element count and increment, writes the table and the figure, and its exit status says whether
the arrest length and final direction converged."""

import csv
import subprocess
import sys

import h5py
import pytest

from conftest import REPO_ROOT, SCRIPTS, ddc2d_exe
from ddc2d import growth_convergence

SCRIPT = SCRIPTS / "growth_convergence.py"


def test_tiny_study_writes_table_and_figure(tmp_path):
    figure = tmp_path / "study.png"
    done = subprocess.run([sys.executable, str(SCRIPT), "--exe", str(ddc2d_exe()), "--work",
                           str(tmp_path / "runs"), "--figure", str(figure), "--elements", "20",
                           "--increments", "0.2,0.1"], capture_output=True, text=True,
                          timeout=600)
    # Exit 1 exactly when a run missed the targets of
    # docs/theory/growth.md#convergence-with-the-increment (20 elements with an increment of 0.2
    # may: the arrest length is resolved to one increment).
    assert done.returncode == (1 if "not converged" in done.stdout else 0), \
        done.stdout + done.stderr
    assert figure.read_bytes()[:4] == b"\x89PNG"
    with open(tmp_path / "runs" / "growth_convergence.csv") as f:
        rows = list(csv.DictReader(f))
    assert [(r["elements"], float(r["increment"])) for r in rows] == [("20", 0.2), ("20", 0.1)]
    for r in rows:
        # 20 elements of 0.1: the increments are never shorter than an element.
        assert float(r["element_length"]) == pytest.approx(0.1)
        assert r["end_reason"] == "arrested"
        assert 0.5 < float(r["arrest_length"]) < 2.0
        assert abs(float(r["final_direction"]) - 90.0) < 10.0
        # A finite first kink is below the MTS angle (it grows toward it as it shrinks).
        assert 50.0 < float(r["first_angle"]) < 70.53


def test_default_output_is_results_in_the_current_folder(tmp_path):
    # Not the gallery's tracked figure: results/ in the folder it runs in.
    gallery = REPO_ROOT / "docs" / "gallery" / "growth_convergence.png"
    before = gallery.read_bytes()
    done = subprocess.run([sys.executable, str(SCRIPT), "--exe", str(ddc2d_exe()), "--elements",
                           "20", "--increments", "0.2"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode in (0, 1), done.stdout + done.stderr
    results = tmp_path / "results"
    assert (results / "growth_convergence.png").read_bytes()[:4] == b"\x89PNG"
    assert (results / "growth-convergence" / "growth_convergence.csv").is_file()
    assert gallery.read_bytes() == before


def test_k_method_reaches_every_run(tmp_path):
    """--k-method higher_order: every run's namelist asks for it, its result says the
    re-solve gave K, and the table has the column."""
    done = subprocess.run([sys.executable, str(SCRIPT), "--exe", str(ddc2d_exe()), "--work",
                           str(tmp_path / "runs"), "--figure", str(tmp_path / "study.png"),
                           "--elements", "20", "--increments", "0.2", "--k-method",
                           "higher_order"], capture_output=True, text=True, timeout=600)
    assert done.returncode in (0, 1), done.stdout + done.stderr
    with open(tmp_path / "runs" / "growth_convergence.csv") as f:
        rows = list(csv.DictReader(f))
    assert [r["k_method"] for r in rows] == ["higher_order"]
    result = tmp_path / "runs" / "wing_n20_d0.2_higher_order.h5"
    with h5py.File(result, "r") as f:
        assert f["tips"].attrs["k_method"].decode() == "higher_order"


def test_check_flags_what_the_targets_forbid():
    module = growth_convergence
    row = {"elements": 40, "increment": 0.05, "arrest_length": 1.0, "final_direction": 92.0,
           "end_reason": "arrested"}
    assert module.check([row, dict(row, increment=0.1, arrest_length=1.09)]) == []
    assert len(module.check([row, dict(row, increment=0.1, arrest_length=1.2)])) == 1
    assert len(module.check([row, dict(row, increment=0.1, final_direction=98.0)])) == 1
    assert len(module.check([row, dict(row, increment=0.2, end_reason="step_limit")])) == 1
