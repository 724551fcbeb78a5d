"""Shared helpers of the verification suite (docs/verification.md): run ddc2d on a model in
a temporary folder, and record a row.

Each test writes its rows (ddc2d.verification.write_row) into $DDC2D_VERIFICATION_ROWS,
which CTest sets to <build>/verification/rows; run alone (plain pytest) a test writes them
into its temporary folder. DDC2D_EXE is the program (ddc2d.run finds one otherwise).
"""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from ddc2d import open_result, run
from ddc2d.paths import find_executable
from ddc2d.verification import make_row, write_row

sys.dont_write_bytecode = True

REPO_ROOT = Path(__file__).resolve().parents[2]
MODELS = Path(__file__).resolve().parent / "models"
#: Seconds one run may take (the largest model here solves in a few seconds).
RUN_TIMEOUT = 600


@pytest.fixture
def solve(tmp_path):
    """solve(model, name, options=()) -> ddc2d.Result: a ddc2d.Model or a namelist file,
    run in the test's temporary folder with one thread."""

    def _solve(model, name, options=()):
        return run(model, output=tmp_path / f"{name}.h5", threads=1, options=options,
                   timeout=RUN_TIMEOUT)

    return _solve


@pytest.fixture
def record(tmp_path):
    """record(**row) -> the row (ddc2d.verification.make_row), written for the table."""
    folder = Path(os.environ.get("DDC2D_VERIFICATION_ROWS", tmp_path / "rows"))

    def _record(**values):
        row = make_row(**values)
        write_row(row, folder)
        return row

    return _record


@pytest.fixture
def solve_deck(tmp_path):
    """solve_deck(text, name) -> ddc2d.Result: a TWODD deck (its text), run with --twodd
    in the test's temporary folder."""

    def _solve(text, name):
        deck = tmp_path / f"{name}.f60.txt"
        deck.write_text(text)
        out = tmp_path / f"{name}.h5"
        done = subprocess.run([str(find_executable()), "--twodd", str(deck), "-o", str(out)],
                              capture_output=True, text=True, timeout=RUN_TIMEOUT,
                              env=dict(os.environ, OMP_NUM_THREADS="1",
                                       OPENBLAS_NUM_THREADS="1"))
        assert done.returncode == 0, done.stderr
        return open_result(out)

    return _solve
