"""docs/examples/paper_fault.py, the notebook-style example of docs/python.md, run as a user
runs it (in a fresh folder, matplotlib's Agg backend): it writes its figures and the
friction sweep's table, and its model is the one of input/paper_fault_slip.nml."""

import csv
import itertools
import os
import subprocess
import sys

import numpy as np

import ddc2d
from conftest import REPO_ROOT, ddc2d_exe

EXAMPLE = REPO_ROOT / "docs" / "examples" / "paper_fault.py"
#: The same model and program: only the last bits of a solve may differ (threads, BLAS).
RTOL = 1e-9


def test_paper_fault_example(tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg", DDC2D_EXE=str(ddc2d_exe()))
    done = subprocess.run([sys.executable, str(EXAMPLE)], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    for name in ("paper_fault_slip.png", "paper_fault_max_shear.png",
                 "paper_fault_friction_sweep.png"):
        assert (tmp_path / name).read_bytes()[:4] == b"\x89PNG", name
    with open(tmp_path / "paper_fault_friction_sweep.csv") as table:
        sweep = {float(row["mu"]): float(row["peak_slip [m]"]) for row in csv.DictReader(table)}
    assert sorted(sweep) == [0.3, 0.4, 0.5, 0.6, 0.7]

    # The namelist file's run: the same slip as the example's model and its sweep's mu 0.6.
    reference = ddc2d.run(REPO_ROOT / "input" / "paper_fault_slip.nml",
                          output=tmp_path / "namelist.h5", executable=ddc2d_exe())
    peak = np.max(np.abs(reference.elements["ds"]))
    assert abs(sweep[0.6] - peak) <= RTOL * peak
    built = ddc2d.open_result(tmp_path / "paper_fault.h5")
    np.testing.assert_allclose(built.elements["ds"], reference.elements["ds"], rtol=0,
                               atol=RTOL * peak)
    # The paper's closed form (3.285e-4 m) within the 500 elements' accuracy, less slip
    # with more friction, and none at 0.7 (strength 57.9 MPa above the shear 54.13 MPa).
    assert abs(peak - 3.285e-4) < 0.01 * 3.285e-4
    slips = [sweep[mu] for mu in sorted(sweep)]
    assert all(a > b for a, b in itertools.pairwise(slips))
    assert sweep[0.7] < 1e-12
