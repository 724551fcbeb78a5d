"""scripts/comp2ddm2nml: comp2DDM Excel workbooks (Ritz, Mutlu & Pollard 2012) to ddc2d.

Workbooks are built here in both formats (.xlsx with openpyxl, .xls with xlwt), converted,
and run with the real executable ($DDC2D_EXE, see conftest.py):

* the paper's own results (tests/reference/ritz2012/R2_straight_n100_mu0.6_sf0, computed
  by comp2DDM.m): DDs to 1e-7 of the peak DD, the same element states, tractions, and the
  observation grid in the paper's point order;
* models of our own with several fractures of different lengths and label cells mixed in,
  against a hand-written namelist of the same model (polyline &fracture groups instead of
  element files): DDs to 1e-12 of the peak, identical states and fields;
* every class of bad workbook: one message naming the file, sheet and cell, exit status
  2, no output file.
"""

import contextlib
import csv
import io
import math
import os
import shutil
import subprocess
import sys
import zipfile

import h5py
import numpy as np
import openpyxl
import pytest
import xlwt

from conftest import REPO_ROOT, ddc2d_exe
from ddc2d import comp2ddm2nml

SCRIPT = REPO_ROOT / "scripts" / "comp2ddm2nml"
REFERENCE = REPO_ROOT / "tests" / "reference" / "ritz2012" / "R2_straight_n100_mu0.6_sf0"
SHEETS = ("parm", "no", "px", "py", "mu", "sf")
PARM_NAMES = ("nu", "E", "sxx", "syy", "sxy", "n_fractures", "xmin", "nx", "xmax", "ymin",
              "ny", "ymax")
FORMATS = ("xlsx", "xls")
STATE_NAMES = {1: "stick", 2: "slip", 3: "open"}
# An .xlsx cannot hold NaN (openpyxl writes an empty cell; Excel and xlsxwriter show the
# error #NUM!), so NaN goes in as #NUM!. Inf is written as this number, then replaced in
# the sheet's XML by a number too large for a double (1E999, read back as Inf).
INF_MARK = 987654321.75


class Error:
    """A spreadsheet error value such as #DIV/0! in a cell."""

    def __init__(self, text):
        self.text = text


class Formula:
    """A formula (.xlsx only) that openpyxl stores without a computed value."""

    def __init__(self, text):
        self.text = text


# ----------------------------------------------------------------------------- workbooks

def write_xlsx(path, sheets):
    """Write {sheet: {(row, col): value}} (1-based) as .xlsx with openpyxl."""
    book = openpyxl.Workbook()
    book.remove(book.active)
    patches = {}
    for index, (name, cells) in enumerate(sheets.items(), start=1):
        sheet = book.create_sheet(name)
        for (row, col), value in cells.items():
            if isinstance(value, Formula):
                value = value.text
            elif isinstance(value, Error):
                value = value.text  # openpyxl stores these strings as error cells
            elif isinstance(value, float) and math.isnan(value):
                value = "#NUM!"
            elif isinstance(value, float) and math.isinf(value):
                patches[f"xl/worksheets/sheet{index}.xml"] = True
                value = INF_MARK if value > 0 else -INF_MARK
            sheet.cell(row=row, column=col, value=value)
    book.save(path)
    if patches:
        with zipfile.ZipFile(path) as source:
            entries = [(info, source.read(info.filename)) for info in source.infolist()]
        with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as target:
            for info, data in entries:
                if info.filename in patches:
                    data = data.replace(f"<v>{INF_MARK!r}</v>".encode(), b"<v>1E999</v>")
                target.writestr(info, data)
    return path


def write_xls(path, sheets):
    """Write {sheet: {(row, col): value}} (1-based) as .xls with xlwt."""
    book = xlwt.Workbook()
    for name, cells in sheets.items():
        sheet = book.add_sheet(name)
        for (row, col), value in cells.items():
            if isinstance(value, Error):
                sheet.row(row - 1).set_cell_error(col - 1, value.text)
            elif isinstance(value, Formula):
                raise TypeError("formulas without a stored value are an .xlsx case")
            else:
                sheet.write(row - 1, col - 1, value)
    book.save(str(path))
    return path


def write_workbook(path, sheets):
    return write_xlsx(path, sheets) if path.suffix == ".xlsx" else write_xls(path, sheets)


def layout(model, labels=False):
    """The comp2DDM sheets of a model dict (parm list, counts, px, py, mu, sf columns);
    numbers from cell A1, or from B2 with labels (see add_labels)."""
    sheets = {"parm": {(1, 1 + k): v for k, v in enumerate(model["parm"])},
              "no": {(1, 1 + k): v for k, v in enumerate(model["counts"])}}
    for name in ("px", "py", "mu", "sf"):
        sheets[name] = {(1 + i, 1 + k): v for k, column in enumerate(model[name])
                        for i, v in enumerate(column)}
    return add_labels(sheets) if labels else sheets


def add_labels(sheets):
    """The sheets moved by one row and one column, with label cells around the numbers: a
    title in A1, a header row, a label column, a note right of the numbers and a note
    under the shortest column. xlsread, and so the converter, ignore them."""
    labelled = {}
    for name, cells in sheets.items():
        moved = {(r + 1, c + 1): v for (r, c), v in cells.items()}
        if not cells:
            labelled[name] = moved
            continue
        width = max(c for _, c in cells)
        height = max(r for r, _ in cells)
        moved[1, 1] = f"comp2DDM sheet {name}"
        for k in range(1, width + 1):
            moved[1, k + 1] = (PARM_NAMES[k - 1] if name == "parm" and k <= 12
                               else f"fracture {k}")
        for i in range(1, height + 1):
            moved[i + 1, 1] = ("values" if name in ("parm", "no") else
                               f"{'vertex' if name in ('px', 'py') else 'element'} {i}")
        moved[2, width + 3] = "note: units m and MPa"
        lengths = {k: max((r for (r, c) in cells if c == k), default=0)
                   for k in range(1, width + 1)}
        shortest = min(lengths, key=lengths.get)
        if lengths[shortest] < height:
            moved[lengths[shortest] + 2, shortest + 1] = "(end of this fracture)"
        labelled[name] = moved
    return labelled


def read_reference_model():
    """The reference case's workbook layout, from its CSV files."""
    def rows(name):
        with open(REFERENCE / f"{name}.csv") as stream:
            return [[float(v) for v in row] for row in csv.reader(stream) if row]

    parm = rows("parm")[0]
    for k in (5, 7, 10):  # n_fractures, nx, ny: integers in the sheet
        parm[k] = int(parm[k])
    counts = [int(v) for v in rows("no")[0]]
    model = {"parm": parm, "counts": counts}
    for name in ("px", "py", "mu", "sf"):
        table = rows(name)
        model[name] = [[row[k] for row in table if k < len(row)] for k in range(len(counts))]
    return model


def reference_table(name):
    return np.genfromtxt(REFERENCE / name, delimiter=",", names=True)


# ----------------------------------------------------------------------------- running

def run(args, cwd):
    return subprocess.run([str(a) for a in args], cwd=cwd, capture_output=True, text=True,
                          timeout=300, check=False)


def convert(workbook, cwd, *options):
    """The converter as a program (scripts/comp2ddm2nml): exit status, stdout, stderr."""
    return run([sys.executable, SCRIPT, workbook, *options], cwd)


def convert_in_process(workbook, cwd, *options):
    """The converter's main() in this process, in cwd, as convert() returns it: the
    bad-workbook cases check its messages, and the hundred of them as programs would
    spend most of their time starting Python (the program's own exit status and streams
    are checked by convert() in the other tests)."""
    args = [str(a) for a in (workbook, *options)]
    stdout, stderr = io.StringIO(), io.StringIO()
    previous = os.getcwd()
    os.chdir(cwd)
    try:
        with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
            try:
                status = comp2ddm2nml.main(args)
            except SystemExit as stop:
                status = stop.code
    finally:
        os.chdir(previous)
    return subprocess.CompletedProcess(args, status, stdout.getvalue(), stderr.getvalue())


def convert_and_solve(workbook, tmp_path, stem, *options):
    """Convert the workbook to tmp_path/out/<stem>.nml and run it; returns the HDF5 path."""
    out = tmp_path / "out"
    out.mkdir(exist_ok=True)
    done = convert(workbook, tmp_path, "-o", out / f"{stem}.nml", *options)
    assert done.returncode == 0, done.stderr
    assert done.stderr == ""
    return solve(out / f"{stem}.nml", tmp_path)


def solve(nml, cwd):
    result = nml.with_suffix(".h5")
    done = run([ddc2d_exe(), nml, "-o", result], cwd)
    assert done.returncode == 0, done.stdout + done.stderr
    return result


def elements(result):
    with h5py.File(result) as f:
        return {key: f["elements"][key][...] for key in f["elements"]}


def grid(result, name="grid"):
    with h5py.File(result) as f:
        g = f["fields"][name]
        return {key: g[key][...] for key in g}, (int(g.attrs["ny"]), int(g.attrs["nx"]))


def reference_states(ref, peak):
    """Stick / slip / open of each element of the paper's results, from its DDs."""
    small = 1e-7 * peak
    return np.where(ref["Dn"] < -small, 3, np.where(np.abs(ref["Ds"]) > small, 2, 1))


# ----------------------------------------------------------------------------- the paper

def check_reference(result):
    """The converted reference model's results against the paper's code's results."""
    ref = reference_table("reference_elements.csv")
    ours = elements(result)
    n = ref.size
    assert ours["ds"].size == n
    np.testing.assert_allclose(ours["x_begin"], ref["xbeg"], rtol=0, atol=1e-14)
    np.testing.assert_allclose(ours["y_end"], ref["yend"], rtol=0, atol=1e-14)
    peak = max(np.abs(ref["Ds"]).max(), np.abs(ref["Dn"]).max())
    # Columns Ds, Dn, Ss, Sn are ddc2d's ds, dn, shear_traction, normal_traction (the
    # paper's code uses the same conventions: tests/fortran/test_contact.pf, ritz2012_reference).
    for key, theirs in (("ds", "Ds"), ("dn", "Dn")):
        difference = np.abs(ours[key] - ref[theirs]).max()
        assert difference <= 1e-7 * peak, f"{key}: {difference / peak:.3e} of the peak DD"
    stress = max(np.abs(ref["Ss"]).max(), np.abs(ref["Sn"]).max())
    for key, theirs in (("shear_traction", "Ss"), ("normal_traction", "Sn")):
        difference = np.abs(ours[key] - ref[theirs]).max()
        assert difference <= 1e-7 * stress, f"{key}: {difference / stress:.3e} of the scale"
    states = reference_states(ref, peak)
    assert (states == 2).all()  # the paper's case: every element slips
    np.testing.assert_array_equal(ours["state"], states)
    np.testing.assert_allclose(ours["mu"], ref["mu"], rtol=0, atol=0)
    np.testing.assert_allclose(ours["sf"], ref["Sf"], rtol=0, atol=0)

    # The paper's grid is meshgrid(linspace(xmin, xmax, nx), linspace(ymin, ymax, ny)),
    # listed as XG(:): column by column, y fastest. ddc2d's arrays are (ny, nx), so the
    # paper's point k is the k-th of ravel(order='F').
    theirs = reference_table("reference_grid.csv")
    field, shape = grid(result)
    assert shape == (14, 13) and shape[0] * shape[1] == theirs.size
    for key in ("x", "y"):
        np.testing.assert_allclose(field[key].ravel(order="F"), theirs[key], rtol=0,
                                   atol=1e-14, err_msg=key)
    assert (field["near_element"] == 0).all()
    for key in ("ux", "uy", "sxx", "syy", "sxy"):
        scale = np.abs(theirs[key]).max()
        difference = np.abs(field[key].ravel(order="F") - theirs[key]).max()
        assert difference <= 1e-7 * scale, f"grid {key}: {difference / scale:.3e} of scale"


@pytest.mark.parametrize("labels", [False, True], ids=["plain", "labels"])
@pytest.mark.parametrize("fmt", FORMATS)
def test_reference_case(fmt, labels, tmp_path):
    workbook = write_workbook(tmp_path / f"R2_straight.{fmt}",
                              layout(read_reference_model(), labels=labels))
    result = convert_and_solve(workbook.name, tmp_path, "R2_straight")
    check_reference(result)
    text = (tmp_path / "out" / "R2_straight.nml").read_text()
    assert "comp2DDM workbook R2_straight." + fmt in text
    assert "elements_file = 'R2_straight_fracture1.csv'" in text
    assert "nx = 13" in text and "ny = 14" in text


@pytest.mark.parametrize("method", ["lemke", "newton"])
def test_reference_case_lcp_methods(method, tmp_path):
    workbook = write_workbook(tmp_path / "R2.xlsx", layout(read_reference_model()))
    result = convert_and_solve(workbook.name, tmp_path, "R2", "--lcp-method", method)
    check_reference(result)
    with h5py.File(result) as f:
        assert f["solver"].attrs["method"].decode().strip() == method


def test_reference_check_can_fail(tmp_path):
    """The comparison catches a wrong model: the paper's case with mu 0.6 -> 0.59."""
    model = read_reference_model()
    model["mu"] = [[0.59] * len(model["mu"][0])]
    workbook = write_workbook(tmp_path / "R2_wrong.xlsx", layout(model))
    result = convert_and_solve(workbook.name, tmp_path, "R2_wrong")
    with pytest.raises(AssertionError, match="ds"):
        check_reference(result)


# ----------------------------------------------------------------------------- our models

def three_fractures():
    """Fractures of 9, 14 and 5 elements: a kinked one that opens, one that partly slips
    and partly sticks (friction per element), one that sticks; cohesion per element.

    Numbers are rounded to 12 decimals: openpyxl writes a float with 16 significant digits,
    so a workbook holds exactly these numbers and the hand-written namelist can use them.
    """
    f1 = [(-1.8 + 0.2 * i, 0.9 + (0.02 * i if i <= 5 else 0.1 - 0.03 * (i - 5)))
          for i in range(10)]
    a = math.radians(60.0)
    f2 = [(0.2 + 0.1 * i * math.cos(a), -1.6 + 0.1 * i * math.sin(a)) for i in range(15)]
    f3 = [(-1.2 + 0.013 * i, -1.5 + 0.17 * i) for i in range(6)]
    fractures = [[(round(x, 12), round(y, 12)) for x, y in f] for f in (f1, f2, f3)]
    mu = [[0.6] * 9, [0.3] * 7 + [0.9] * 7, [0.6, 0.7, 0.8, 0.7, 0.6]]
    sf = [[1.0] * 9, [round(0.5 + 0.1 * i, 12) for i in range(14)], [2.0] * 5]
    return {
        "parm": [0.25, 50000.0, -40.0, 3.0, 10.0, 3, -2.0, 9, 2.0, -2.1, 7, 1.9],
        "counts": [9, 14, 5],
        "px": [[x for x, _ in f] for f in fractures],
        "py": [[y for _, y in f] for f in fractures],
        "mu": mu, "sf": sf,
    }


def one_element_and_long():
    """A one-element fracture beside one of 25 elements; a grid of one column (the paper's
    linspace(xmin, xmax, 1) is xmax)."""
    long = [(round(-1.0 + 0.08 * i, 12), round(0.3 - 0.02 * i, 12)) for i in range(26)]
    short = [(0.4, 1.0), (0.7, 1.25)]
    return {
        "parm": [0.3, 30000.0, -60.0, -20.0, 18.0, 2, -5.0, 1, 0.5, -1.0, 5, 1.0],
        "counts": [1, 25],
        "px": [[x for x, _ in short], [x for x, _ in long]],
        "py": [[y for _, y in short], [y for _, y in long]],
        "mu": [[0.4], [0.5] * 25], "sf": [[0.0], [0.2] * 25],
    }


def hand_written_namelist(model):
    """The same model as polyline &fracture groups (one element per segment, friction and
    cohesion per segment), written independently of the converter."""
    p = model["parm"]
    nx, ny = p[7], p[10]
    xmin = p[8] if nx == 1 else p[6]  # the paper's linspace(a, b, 1) is b
    ymin = p[11] if ny == 1 else p[9]
    lines = [f"&model youngs_modulus = {p[1]!r}, poissons_ratio = {p[0]!r} /",
             f"&remote_stress sxx = {p[2]!r}, syy = {p[3]!r}, sxy = {p[4]!r} /"]
    for k in range(len(model["counts"])):
        def values(key, k=k):
            return ", ".join(repr(float(v)) for v in model[key][k])
        lines.append(f"&fracture name = 'f{k + 1}', x = {values('px')}, y = {values('py')},"
                     f"\n  elements = 1, condition = 'contact', mu = {values('mu')},"
                     f"\n  sf = {values('sf')} /")
    lines.append(f"&grid name = 'grid', xmin = {xmin!r}, xmax = {p[8]!r}, nx = {nx}, "
                 f"ymin = {ymin!r}, ymax = {p[11]!r}, ny = {ny} /")
    return "\n".join(lines) + "\n"


def compare_models(converted, hand):
    ours, theirs = elements(converted), elements(hand)
    peak = max(np.abs(theirs["ds"]).max(), np.abs(theirs["dn"]).max())
    assert peak > 0
    for key in ("x_begin", "y_begin", "x_end", "y_end", "fracture_id", "mu", "sf"):
        np.testing.assert_array_equal(ours[key], theirs[key], err_msg=key)
    for key in ("ds", "dn"):
        np.testing.assert_allclose(ours[key], theirs[key], rtol=0, atol=1e-12 * peak,
                                   err_msg=key)
    np.testing.assert_array_equal(ours["state"], theirs["state"])
    a, shape_a = grid(converted)
    b, shape_b = grid(hand)
    assert shape_a == shape_b
    for key in ("x", "y", "near_element"):
        np.testing.assert_array_equal(a[key], b[key], err_msg=key)
    for key in ("ux", "uy", "sxx", "syy", "sxy"):
        scale = np.nanmax(np.abs(b[key]))
        np.testing.assert_allclose(a[key], b[key], rtol=0, atol=1e-12 * scale, err_msg=key)
    return ours


@pytest.mark.parametrize("fmt", FORMATS)
def test_three_fractures_with_labels(fmt, tmp_path):
    model = three_fractures()
    workbook = write_workbook(tmp_path / f"three.{fmt}", layout(model, labels=True))
    converted = convert_and_solve(workbook.name, tmp_path, "three")
    hand = tmp_path / "hand.nml"
    hand.write_text(hand_written_namelist(model))
    ours = compare_models(converted, solve(hand, tmp_path))
    counts = np.bincount(ours["fracture_id"])[1:]
    np.testing.assert_array_equal(counts, [9, 14, 5])
    # The model exercises every contact state, per fracture as designed.
    first, second, third = np.split(ours["state"], [9, 23])
    assert (first == 3).all(), first
    assert set(second[:7]) == {2} and set(second[7:]) == {1}, second
    assert (third == 1).all(), third
    for k in range(3):
        assert (tmp_path / "out" / f"three_fracture{k + 1}.csv").is_file()
    assert not list((tmp_path / "out").glob("*.partial"))


@pytest.mark.parametrize("fmt", FORMATS)
def test_one_element_fracture_and_single_column_grid(fmt, tmp_path):
    model = one_element_and_long()
    workbook = write_workbook(tmp_path / f"short_long.{fmt}", layout(model))
    converted = convert_and_solve(workbook.name, tmp_path, "short_long")
    hand = tmp_path / "hand.nml"
    hand.write_text(hand_written_namelist(model))
    ours = compare_models(converted, solve(hand, tmp_path))
    assert ours["ds"].size == 26 and np.abs(ours["ds"]).max() > 0
    field, shape = grid(converted)
    assert shape == (5, 1) and (field["x"] == 0.5).all()


def test_multi_fracture_check_can_fail(tmp_path):
    """compare_models catches a model that differs in one element's friction."""
    model = three_fractures()
    workbook = write_workbook(tmp_path / "three.xlsx", layout(model))
    converted = convert_and_solve(workbook.name, tmp_path, "three")
    model["mu"][1][6] = 0.9  # the last slipping element of fracture 2 would stick
    hand = tmp_path / "hand.nml"
    hand.write_text(hand_written_namelist(model))
    with pytest.raises(AssertionError):
        compare_models(converted, solve(hand, tmp_path))


def test_options_and_default_output(tmp_path):
    workbook = write_workbook(tmp_path / "R2.xls", layout(read_reference_model()))
    done = convert(workbook.name, tmp_path, "--title", "paper's fault",
                   "--length-unit", "km", "--stress-unit", "bar")
    assert done.returncode == 0, done.stderr
    text = (tmp_path / "R2.nml").read_text()
    assert "title = 'paper''s fault'" in text
    assert "length_unit = 'km'" in text and "stress_unit = 'bar'" in text
    assert "lcp_method = 'auto'" in text
    result = solve(tmp_path / "R2.nml", tmp_path)
    with h5py.File(result) as f:
        assert f.attrs["title"].decode().strip() == "paper's fault"
        assert f.attrs["length_unit"].decode().strip() == "km"


def test_runs_itself_with_the_venv_python(tmp_path):
    """Started by a Python without xlrd / openpyxl (-S: no site packages), the script runs
    itself again with build/venv's Python; a copy without a venv beside it says, in one
    line, what is missing (scripts/ddc2d_venv.py; test_venv.py runs every script so)."""
    venv_python = REPO_ROOT / "build" / "venv" / "bin" / "python"
    assert venv_python.is_file(), "the tests run in build/venv (scripts/setup.sh)"
    workbook = write_workbook(tmp_path / "R2.xlsx", layout(read_reference_model()))
    done = run([sys.executable, "-S", SCRIPT, workbook.name], tmp_path)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "R2.nml").is_file()
    (tmp_path / "R2.nml").unlink()
    copy = tmp_path / "clone" / "scripts"
    shutil.copytree(SCRIPT.parent, copy, ignore=shutil.ignore_patterns("__pycache__"))
    done = run([sys.executable, "-S", copy / SCRIPT.name, workbook.name], tmp_path)
    assert done.returncode == 2
    assert "missing" in done.stderr and len(done.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "R2.nml").exists()


# ----------------------------------------------------------------------------- bad input

def small_model():
    """Two fractures of 3 and 5 elements."""
    return {
        "parm": [0.25, 50000.0, -40.0, -10.0, 12.0, 2, -1.0, 5, 1.0, -1.0, 4, 1.0],
        "counts": [3, 5],
        "px": [[-0.8, -0.6, -0.4, -0.2], [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]],
        "py": [[0.5, 0.5, 0.55, 0.6], [-0.5, -0.4, -0.3, -0.2, -0.1, 0.0]],
        "mu": [[0.6] * 3, [0.5] * 5],
        "sf": [[0.0] * 3, [1.0] * 5],
    }


def put(sheet, row, col, value):
    """A change to one cell of the plain layout (numbers from A1)."""
    return lambda sheets: sheets[sheet].__setitem__((row, col), value)


def remove(sheet, row, col):
    return lambda sheets: sheets[sheet].pop((row, col))


def both(*changes):
    def change(sheets):
        for one in changes:
            one(sheets)
    return change


def drop_sheet(name):
    return lambda sheets: sheets.pop(name)


def drop_column(sheet, col):
    def change(sheets):
        for key in [key for key in sheets[sheet] if key[1] == col]:
            del sheets[sheet][key]
    return change


def column_to_labels(sheet, col):
    """Move column col one to the right and put labels in its place."""
    def change(sheets):
        cells = sheets[sheet]
        for (r, c) in sorted([key for key in cells if key[1] == col]):
            cells[r, c + 1] = cells[r, c]
            cells[r, c] = "label"
    return change


def only_a_label(sheet):
    return lambda sheets: sheets.__setitem__(sheet, {(1, 1): "elements"})


# (id, change to the plain layout of small_model, sheet, row, col of the cell the message
#  names in the plain layout (None: a message about the whole sheet or workbook), message
#  fragment). With labels the numbers start at B2, so the cell moves by one row and one
#  column. Every case runs in both formats but formula_without_value (.xlsx only: .xls
#  writers store a formula's value).
BAD_CASES = [
    ("missing_sheet", drop_sheet("sf"), "", None, None,
     "no sheet 'sf' (the comp2DDM layout needs the sheets parm, no, px, py, mu, sf"),
    ("empty_sheet", only_a_label("no"), "no", None, None, "the sheet holds no numbers"),
    ("text_in_px", put("px", 3, 2, "0.2 m"), "px", 3, 2,
     "expected x of vertex 3 of fracture 2, a number, but the cell holds the text '0.2 m'"),
    ("px_too_short", remove("px", 6, 2), "px", 6, 2,
     ("the cell is empty; expected x of vertex 6 of fracture 2 (sheet 'no', cell {no2} "
      "gives 5 elements, so 6 values in this column)")),
    ("py_too_long", put("py", 5, 1, 0.7), "py", 5, 1,
     ("a value beyond the 4 of fracture 1 (sheet 'no', cell {no1} gives 3 elements); the "
      "counts of sheet 'no' and sheet 'py' disagree")),
    ("mu_too_short", remove("mu", 5, 2), "mu", 5, 2,
     "the cell is empty; expected friction coefficient of element 5 of fracture 2"),
    ("sf_too_long", put("sf", 4, 1, 0.0), "sf", 4, 1,
     "the counts of sheet 'no' and sheet 'sf' disagree"),
    ("nan", put("py", 2, 2, math.nan), "py", 2, 2,
     {"xls": "y of vertex 2 of fracture 2 is NaN",
      "xlsx": "y of vertex 2 of fracture 2 is the error value #NUM!"}),
    ("inf", put("sf", 3, 2, math.inf), "sf", 3, 2,
     "frictional strength of element 3 of fracture 2 is Inf"),
    ("error_value", put("mu", 2, 1, Error("#DIV/0!")), "mu", 2, 1,
     "friction coefficient of element 2 of fracture 1 is the error value #DIV/0!"),
    ("logical", put("px", 1, 1, True), "px", 1, 1, "the cell holds the logical TRUE"),
    ("formula_without_value", put("py", 3, 1, Formula("=A2+0.05")), "py", 3, 1,
     "y of vertex 3 of fracture 1 is the formula =A2+0.05 without a stored value"),
    ("n_fractures_above_no", put("parm", 1, 6, 3), "no", 1, 3,
     ("expected the number of elements of fracture 3: n_fractures = 3 (sheet 'parm', "
      "cell {parm6})")),
    ("n_fractures_below_no", put("parm", 1, 6, 1), "no", 1, 2,
     "a value for fracture 2, but n_fractures = 1"),
    ("column_missing", drop_column("px", 2), "px", 1, 2,
     ("the cell is empty; expected the column of fracture 2, but there are 2 fractures "
      "(n_fractures and sheet 'no'); the values of the sheet span column {first_column}")),
    ("column_extra", put("mu", 1, 3, 0.4), "mu", 1, 3,
     "a column of values for fracture 3, but there are 2 fractures"),
    ("label_column_inside", column_to_labels("mu", 2), "mu", 1, 2,
     "holds no values but lies between columns of values"),
    ("nx_not_integer", put("parm", 1, 8, 12.5), "parm", 1, 8,
     "nx (the number of grid points in x, value 8 of 12) = 12.5 must be a positive integer"),
    ("ny_zero", put("parm", 1, 11, 0), "parm", 1, 11,
     "ny (the number of grid points in y, value 11 of 12) = 0 must be a positive integer"),
    ("n_fractures_negative", put("parm", 1, 6, -2), "parm", 1, 6,
     ("n_fractures (the number of fractures, value 6 of 12) = -2 must be a positive "
      "integer")),
    ("no_not_integer", put("no", 1, 2, 4.5), "no", 1, 2,
     "the number of elements of fracture 2 = 4.5 must be a positive integer"),
    ("parm_short", remove("parm", 1, 12), "parm", 1, 12,
     "the cell is empty; expected ymax (grid ymax, value 12 of 12)"),
    ("parm_13_values", put("parm", 1, 13, 1.0), "parm", 1, 13, "a 13th value"),
    ("parm_value_far_right", put("parm", 1, 16, 7.0), "parm", 1, 16, "a 13th value"),
    ("no_value_far_right", put("no", 1, 5, 7.0), "no", 1, 5,
     "a value for fracture 5, but n_fractures = 2"),
    ("parm_second_row", put("parm", 2, 1, 0.3), "parm", 2, 1, "a second row of values"),
    ("parm_text", put("parm", 1, 2, "50 GPa"), "parm", 1, 2,
     ("expected E (Young's modulus, value 2 of 12), a number, but the cell holds the text "
      "'50 GPa'")),
    ("poissons_ratio", put("parm", 1, 1, 0.5), "parm", 1, 1,
     "nu (Poisson's ratio) = 0.5 must lie in (-1, 0.5)"),
    ("youngs_modulus", put("parm", 1, 2, -5.0), "parm", 1, 2,
     "E (Young's modulus) = -5 must be positive"),
    ("negative_friction", put("mu", 2, 2, -0.1), "mu", 2, 2,
     "friction coefficient of element 2 of fracture 2 = -0.1 must be >= 0"),
    ("negative_cohesion", put("sf", 3, 1, -1.0), "sf", 3, 1,
     "frictional strength of element 3 of fracture 1 = -1 must be >= 0"),
    ("zero_length_element", both(put("px", 3, 2, 0.1), put("py", 3, 2, -0.4)), "px", 3, 2,
     ("vertex 3 of fracture 2 equals vertex 2 (sheets 'px' and 'py'): element 2 has zero "
      "length")),
    ("out_of_range", put("px", 2, 1, 1e60), "px", 2, 1,
     ("x of vertex 2 of fracture 1 = 1e+60: a number must be 0 or of magnitude between "
      "1e-50 and 1e+50")),
]
BAD_PARAMS = [pytest.param(case, fmt, labels, id=f"{case[0]}-{fmt}-{label_id}")
              for case in BAD_CASES for fmt in FORMATS
              for labels, label_id in ((False, "plain"), (True, "labels"))
              if not (case[0] == "formula_without_value" and fmt == "xls")]


def cell_text(sheet, row, col):
    return f"sheet '{sheet}', cell {chr(64 + col)}{row} (row {row}, column {col}): "


@pytest.mark.parametrize("case, fmt, labels", BAD_PARAMS)
def test_bad_workbook(case, fmt, labels, tmp_path):
    name, change, sheet, row, col, fragment = case
    sheets = layout(small_model())
    change(sheets)
    shift = 1 if labels else 0
    if labels:
        sheets = add_labels(sheets)
    workbook = write_workbook(tmp_path / f"bad_{name}.{fmt}", sheets)
    out = tmp_path / "out"
    out.mkdir()
    done = convert_in_process(workbook.name, tmp_path, "-o", out / "model.nml")
    assert done.returncode == 2, done.stdout + done.stderr
    assert done.stdout == ""
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    where = f"comp2ddm2nml: error: {workbook.name}: "
    if row is not None:
        where += cell_text(sheet, row + shift, col + shift)
    elif sheet:
        where += f"sheet '{sheet}': "
    assert lines[0].startswith(where), lines[0]
    cells = {"no1": f"{chr(65 + shift)}{1 + shift}", "no2": f"{chr(66 + shift)}{1 + shift}",
             "parm6": f"{chr(70 + shift)}{1 + shift}", "first_column": chr(65 + shift)}
    if isinstance(fragment, dict):
        fragment = fragment[fmt]
    assert fragment.format(**cells) in lines[0], lines[0]
    assert list(out.iterdir()) == []


@pytest.mark.parametrize("fmt", FORMATS)
def test_bad_cases_are_good_without_the_change(fmt, tmp_path):
    """The workbook the bad cases start from converts (so each message is the change's)."""
    for labels in (False, True):
        workbook = write_workbook(tmp_path / f"good_{labels}.{fmt}",
                                  layout(small_model(), labels=labels))
        done = convert_in_process(workbook.name, tmp_path, "-o",
                                  tmp_path / f"good_{labels}.nml")
        assert done.returncode == 0, done.stderr


def test_unreadable_workbooks(tmp_path):
    (tmp_path / "notes.xlsx").write_text("nu, E\n0.25, 50000\n")
    (tmp_path / "broken.xlsx").write_bytes(b"PK\x03\x04" + b"\0" * 100)
    (tmp_path / "broken.xls").write_bytes(b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1" + b"\0" * 100)
    for name, fragment in (("missing.xls", "cannot read"),
                           ("notes.xlsx", "not an Excel workbook (.xls or .xlsx)"),
                           ("broken.xlsx", "cannot read the .xlsx workbook"),
                           ("broken.xls", "cannot read the .xls workbook")):
        done = convert(name, tmp_path)
        assert done.returncode == 2, done.stderr
        lines = done.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith(f"comp2ddm2nml: error: {name}: ")
        assert fragment in lines[0], lines[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["broken.xls", "broken.xlsx",
                                                         "notes.xlsx"]


def test_unwritable_output_leaves_nothing(tmp_path):
    workbook = write_workbook(tmp_path / "two.xlsx", layout(small_model()))
    done = convert(workbook.name, tmp_path, "-o", tmp_path / "no_such_folder" / "m.nml")
    assert done.returncode == 3 and "cannot write" in done.stderr
    # A failure after the first element file was renamed into place: the second one's
    # name is taken by a folder. Everything written is removed again.
    out = tmp_path / "out"
    (out / "m_fracture2.csv").mkdir(parents=True)
    done = convert(workbook.name, tmp_path, "-o", out / "m.nml")
    assert done.returncode == 3, done.stderr
    assert len(done.stderr.strip().splitlines()) == 1
    assert [p.name for p in out.iterdir()] == ["m_fracture2.csv"]
