"""Shared fixtures: the command line of ddc2d-plot as a module, and small synthetic ddc2d
result files.

The synthetic files follow the HDF5 layout of docs/output-reference.md#layout (as written by
ddc2d): strings are stored as blank-padded fixed-length bytes, as the Fortran writer does.
Tests read result files with ddc2d.reader, the reader of the ddc2d package (installed
editable into build/venv by scripts/setup.sh).
"""

import os
import subprocess
import sys
from pathlib import Path

import h5py
import matplotlib
import numpy as np
import pytest

import ddc2d.plot.cli

sys.dont_write_bytecode = True
matplotlib.use("Agg")  # the figures are drawn into files only, as ddc2d-plot does

REPO_ROOT = Path(__file__).resolve().parents[2]
SCRIPTS = REPO_ROOT / "scripts"
PLOT_SCRIPT = SCRIPTS / "ddc2d-plot"

LENGTH_UNIT = "km"
STRESS_UNIT = "MPa"

# Fracture A: 4 elements along +x from (-1, 0) to (1, 0), lengths 0.5.
# Fracture B: 3 elements on a polyline (0, 1) -> (0.3, 1.4) -> (0.3, 2.4), lengths 0.5, 0.5, 0.5.
FRACTURE_A = {
    "x": [-1.0, -0.5, 0.0, 0.5, 1.0],
    "y": [0.0, 0.0, 0.0, 0.0, 0.0],
}
FRACTURE_B = {
    "x": [0.0, 0.3, 0.3, 0.3],
    "y": [1.0, 1.4, 1.9, 2.4],
}
# Element states, one of every kind on A; open/slip/stick on B. Codes as ddc2d writes them
# (0 free, 1 stick, 2 slip, 3 open; test_ddc2d_h5.py checks them against ddc2d's output).
STATES = [1, 2, 3, 2, 0, 3, 1]
DS = [-1.0e-3, -2.5e-3, -3.0e-3, -1.5e-3, 4.0e-4, 0.0, 2.0e-4]
DN = [0.0, 0.0, -2.0e-3, 0.0, -1.0e-4, -7.0e-4, 0.0]

# The coding ddc2d writes on /fields/<name>/near_element: ddc2d-plot masks the points
# that it calls 'on' (an element).
NEAR_ELEMENT_CODING = ("0 clear, 1 within one element length of an element centre (reduced "
                       "accuracy), 2 on an element or at an element end (value NaN)")
GRID_NX, GRID_NY = 5, 4
GRID_NAN_POINT = (1, 2)  # (row j, column i) of the point on an element: NaN, flagged 2
GRID_NEAR_POINT = (2, 3)  # a point close to an element: finite, flagged 1


def _fixed_strings(values, width=16):
    """Blank-padded fixed-length byte strings, as written from Fortran."""
    return np.array([v.ljust(width).encode() for v in values], dtype=f"S{width}")


def _text(value):
    return np.bytes_(value.encode())


def element_arrays():
    """Element geometry and values of the synthetic model, as numpy arrays."""
    xb, yb, xe, ye, fid = [], [], [], [], []
    for number, fracture in enumerate((FRACTURE_A, FRACTURE_B), start=1):
        for k in range(len(fracture["x"]) - 1):
            xb.append(fracture["x"][k])
            yb.append(fracture["y"][k])
            xe.append(fracture["x"][k + 1])
            ye.append(fracture["y"][k + 1])
            fid.append(number)
    xb, yb, xe, ye = map(np.array, (xb, yb, xe, ye))
    n = xb.size
    ds = np.array(DS)
    dn = np.array(DN)
    return {
        "x_begin": xb, "y_begin": yb, "x_end": xe, "y_end": ye,
        "x_mid": 0.5 * (xb + xe), "y_mid": 0.5 * (yb + ye),
        "half_length": 0.5 * np.hypot(xe - xb, ye - yb),
        "fracture_id": np.array(fid, dtype=np.int32),
        "condition": np.array([5, 5, 5, 5, 1, 5, 5], dtype=np.int32),  # contact, traction
        "bc_s": np.zeros(n), "bc_n": np.zeros(n),
        "ds": ds, "dn": dn, "opening": -dn,
        "shear_traction": np.linspace(-3.0, 3.0, n),
        "normal_traction": np.linspace(-10.0, 0.0, n),
        "us_minus": 0.5 * ds, "un_minus": 0.5 * dn,
        "us_plus": -0.5 * ds, "un_plus": -0.5 * dn,
        "state": np.array(STATES, dtype=np.int32),
        "mu": np.full(n, 0.6), "sf": np.full(n, 1.0), "pressure": np.zeros(n),
    }


def grid_arrays():
    """The 5 x 4 grid field: arrays shaped (ny, nx); one NaN point flagged 2."""
    x1 = np.linspace(-2.0, 2.0, GRID_NX)
    y1 = np.linspace(-1.5, 1.5, GRID_NY)
    x, y = np.meshgrid(x1, y1)
    sxx = -10.0 + x + 2.0 * y
    syy = -5.0 - x * y
    sxy = 0.5 * x - y
    ux = 1e-3 * x
    uy = -2e-3 * y
    near = np.zeros((GRID_NY, GRID_NX), dtype=np.int32)
    near[GRID_NAN_POINT] = 2
    near[GRID_NEAR_POINT] = 1
    for array in (sxx, syy, sxy, ux, uy):
        array[GRID_NAN_POINT] = np.nan
    return {"x": x, "y": y, "ux": ux, "uy": uy, "sxx": sxx, "syy": syy, "sxy": sxy,
            "near_element": near}


def write_result(path, with_fields=True, with_elements=True):
    """Write a small synthetic ddc2d result file at `path`; returns the path."""
    with h5py.File(path, "w") as f:
        for key, value in {
            "program": "ddc2d", "version": "0.1.0", "git_commit": "0123456789ab",
            "created": "2024-01-01T00:00:00", "title": "synthetic test",
            "input_file": "synthetic.nml", "input_text": "&model /",
            "length_unit": LENGTH_UNIT, "stress_unit": STRESS_UNIT,
            "conventions": "tension positive; Ds = us(-) - us(+), Dn = un(-) - un(+)",
            "open_cohesion": "lost", "lcp_method": "lemke",
        }.items():
            f.attrs[key] = _text(value)
        f.attrs["youngs_modulus"] = 50000.0
        f.attrs["poissons_ratio"] = 0.25
        f.attrs["shear_modulus"] = 20000.0
        f.attrs["remote_stress"] = np.array([-143.75, -81.25, 54.13])
        f.attrs["complete"] = np.int32(1)

        if with_elements:
            elements = f.create_group("elements")
            for key, value in element_arrays().items():
                elements.create_dataset(key, data=value)
            elements["state"].attrs["coding"] = _text("0 free, 1 stick, 2 slip, 3 open")

            fractures = f.create_group("fractures")
            fractures.create_dataset("name", data=_fixed_strings(["fault A", "B"]))
            fractures.create_dataset("first_element", data=np.array([1, 5], dtype=np.int32))
            fractures.create_dataset("last_element", data=np.array([4, 7], dtype=np.int32))

            tips = f.create_group("tips")
            tips.create_dataset("x", data=np.array([-1.0, 1.0, 0.0, 0.3]))
            tips.create_dataset("y", data=np.array([0.0, 0.0, 1.0, 2.4]))
            tips.create_dataset("fracture_id", data=np.array([1, 1, 2, 2], dtype=np.int32))
            tips.create_dataset("element", data=np.array([1, 4, 5, 7], dtype=np.int32))
            tips.create_dataset("k1", data=np.array([0.0, 0.0, 0.1, 0.0]))
            tips.create_dataset("k2", data=np.array([1.2, 1.1, -0.2, 0.3]))

        if with_fields:
            fields = f.create_group("fields")
            grid = fields.create_group("grid1")
            grid.attrs["kind"] = _text("grid")
            grid.attrs["nx"] = np.int32(GRID_NX)
            grid.attrs["ny"] = np.int32(GRID_NY)
            for key, value in grid_arrays().items():
                grid.create_dataset(key, data=value)
            grid["near_element"].attrs["coding"] = _text(NEAR_ELEMENT_CODING)
            line = fields.create_group("line1")
            line.attrs["kind"] = _text("line")
            line.attrs["nx"] = np.int32(6)
            line.attrs["ny"] = np.int32(1)
            t = np.linspace(0.0, 1.0, 6)
            for key, value in {"x": t, "y": 0.5 + 0 * t, "ux": t, "uy": t, "sxx": t,
                               "syy": t, "sxy": t,
                               "near_element": np.zeros(6, dtype=np.int32)}.items():
                line.create_dataset(key, data=value)

        solver = f.create_group("solver")
        solver.attrs["lcp_method"] = _text("lemke")
        solver.attrs["pivots"] = np.int32(9)
        solver.attrs["threads"] = np.int32(2)
        seconds = solver.create_group("seconds")
        for key in ("assembly", "factorization", "lcp", "fields", "output", "total"):
            seconds.create_dataset(key, data=0.01)
    return path


@pytest.fixture
def result_file(tmp_path):
    """A synthetic result with 2 fractures, a 5 x 4 grid and a line."""
    return write_result(tmp_path / "synthetic.h5")


@pytest.fixture
def result_file_without_fields(tmp_path):
    """A synthetic result without /fields."""
    return write_result(tmp_path / "nofields.h5", with_fields=False)


@pytest.fixture(scope="session")
def plot_module():
    """The command line of ddc2d-plot (ddc2d.plot.cli)."""
    return ddc2d.plot.cli


def solve_text(folder, stem, text, timeout=300):
    """Write `text` to folder/<stem>.nml and solve it with ddc2d_exe() (asserting success);
    returns the result file folder/<stem>.h5."""
    (folder / f"{stem}.nml").write_text(text)
    done = subprocess.run([str(ddc2d_exe()), f"{stem}.nml", "-o", f"{stem}.h5"], cwd=folder,
                          capture_output=True, text=True, timeout=timeout)
    assert done.returncode == 0, done.stdout + done.stderr
    return folder / f"{stem}.h5"


def kgd_viscosity_solution(t, e_prime, viscosity, rate):
    """KGD, viscosity-dominated, zero toughness (Adachi & Detournay 2002): the half-length
    0.61524 (E' Q0^3 t^4 / mu')^(1/6) and the opening at the source gamma (A0 + A1 + 4 B)
    (mu' Q0^3 t^2 / E')^(1/6), their series' gamma = 0.6152, A0 = 3^(1/2), A1 = -0.156,
    B = 0.0663; mu' = 12 eta."""
    mu_prime = 12.0 * viscosity
    length = 0.61524 * (e_prime * rate**3 * t**4 / mu_prime)**(1.0 / 6.0)
    omega0 = 0.6152 * (3.0**0.5 - 0.156 + 4.0 * 0.0663)
    return length, omega0 * (mu_prime * rate**3 * t**2 / e_prime)**(1.0 / 6.0)


def ddc2d_exe():
    """The ddc2d executable under test: $DDC2D_EXE, else the Debug build of scripts/test.sh.

    No other build is guessed: an old build elsewhere under build/ would be tested silently.
    """
    exe = os.environ.get("DDC2D_EXE")
    if exe:
        return Path(exe).resolve()
    exe = REPO_ROOT / "build" / "debug" / "app" / "ddc2d"
    if exe.is_file():
        return exe
    raise AssertionError("set DDC2D_EXE to the ddc2d executable to test (there is no "
                         "build/debug/app/ddc2d; scripts/test.sh builds it)")
