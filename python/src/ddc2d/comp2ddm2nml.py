"""Convert a comp2DDM Excel workbook (Ritz, Mutlu & Pollard 2012) into a ddc2d namelist.

usage: comp2ddm2nml WORKBOOK [-o OUT.nml] [--title T] [--length-unit U] [--stress-unit U]
                    [--lcp-method auto|lemke|newton]

The paper's Matlab script comp2DDM.m reads every model from an Excel workbook (.xls or
.xlsx) with xlsread, which keeps the numeric block of a sheet: rows and columns at its
edges that hold no number (labels) are dropped, and inside the block a text or empty cell
is blank. The sheets:

* parm: one row nu, E, sxx, syy, sxy, n_fractures, xmin, nx, xmax, ymin, ny, ymax (Poisson's
  ratio, Young's modulus, remote stress with tension positive, the number of fractures and
  the observation grid: nx points from xmin to xmax, ny from ymin to ymax);
* no: one row, the number of elements of each fracture;
* px, py: one column per fracture, its no + 1 vertex coordinates (element i runs from
  vertex i to vertex i + 1);
* mu, sf: one column per fracture, the friction coefficient and the frictional strength
  (cohesion) of each element.

The namelist OUT.nml (default: the workbook's name with .nml, in the current folder) has
&model (E, nu, units), &remote_stress, one &fracture per column (every element a
frictional contact element) whose elements are in the CSV file
<OUT stem>_fracture<k>.csv next to OUT.nml, one &grid and &solver. The grid is the paper's
meshgrid: ddc2d's /fields/grid arrays, shaped (ny, nx) from Python, read column by column
(numpy order='F') list the points in the order of the paper's XG(:), YG(:).

A workbook that does not fit the layout (a missing sheet, a cell that is not a number,
NaN or Inf, counts that disagree between the sheets, n_fractures, nx or ny not a positive
integer, ...) is reported in one message naming the file, the sheet and the cell, and
nothing is written; the outputs are written to temporary files that are renamed only when
all are complete. Reads .xls with the Python package xlrd and .xlsx with openpyxl (the
extra 'workbooks' of the ddc2d package; scripts/setup.sh installs both into build/venv);
without them, one line says which is missing.

Exit status: 0 success, 2 unreadable or malformed workbook (or bad usage), 3 the output
could not be written.
"""

import argparse
import math
import os
import sys
import tempfile
import zipfile
from pathlib import Path

from .files import regular_target

PROG = "comp2ddm2nml"
SHEETS = ("parm", "no", "px", "py", "mu", "sf")
PARM_NAMES = ("nu", "E", "sxx", "syy", "sxy", "n_fractures", "xmin", "nx", "xmax", "ymin",
              "ny", "ymax")
PARM_MEANINGS = ("Poisson's ratio", "Young's modulus", "remote stress sxx",
                 "remote stress syy", "remote stress sxy", "the number of fractures",
                 "grid xmin", "the number of grid points in x", "grid xmax", "grid ymin",
                 "the number of grid points in y", "grid ymax")
# ddc2d accepts reals that are 0 or of magnitude in [1e-50, 1e50]
# (docs/input-reference.md#the-input-file).
MIN_MAGNITUDE, MAX_MAGNITUDE = 1.0e-50, 1.0e50
MAX_COUNT = 2**31 - 1  # counts are default Fortran integers
XLS_MAGIC = b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1"
ZIP_MAGIC = b"PK\x03\x04"
CSV_HEADER = "x_begin,y_begin,x_end,y_end,mu,sf,pressure"
LCP_METHODS = ("auto", "lemke", "newton")


class WorkbookError(Exception):
    """A workbook that cannot be converted: the message names the file, sheet and cell."""


def column_letters(col):
    """Spreadsheet letters of a 1-based column number: 1 -> A, 27 -> AA."""
    letters = ""
    while col > 0:
        col, rest = divmod(col - 1, 26)
        letters = chr(ord("A") + rest) + letters
    return letters


def number(value):
    """A real as the shortest text that reads back to the same double."""
    return repr(float(value))


def shown(value):
    """A cell's number as a user typed it: 3 rather than 3.0."""
    return str(int(value)) if value.is_integer() and abs(value) < 1e15 else repr(value)


def one_line(exc):
    """An exception's text on one line."""
    return " ".join(str(exc).split()) or type(exc).__name__


def quoted(text):
    return "'" + text.replace("'", "''") + "'"


class Sheet:
    """The cells of one sheet, as (kind, value) by 1-based (row, column).

    kind is 'number' (value a float), 'text', 'logical', 'date' or 'error' (value the
    error's text, e.g. '#DIV/0!'); empty cells are absent. The numeric block is the
    smallest rectangle holding every cell that is not text, as xlsread's numeric output:
    edge rows and columns of labels are left out.
    """

    def __init__(self, workbook, name, cells):
        self.workbook = workbook
        self.name = name
        self.cells = cells
        values = [key for key, (kind, _) in cells.items() if kind != "text"]
        self.value_rows = {}  # column -> the rows of its cells that are not text
        for row, col in sorted(values):
            self.value_rows.setdefault(col, []).append(row)
        if values:
            rows = [r for r, _ in values]
            cols = [c for _, c in values]
            self.top, self.bottom = min(rows), max(rows)
            self.left, self.right = min(cols), max(cols)
        else:
            self.top = self.bottom = self.left = self.right = None

    def where(self, row=None, col=None):
        text = f"{self.workbook.path}: sheet '{self.name}'"
        if row is not None:
            text += f", cell {column_letters(col)}{row} (row {row}, column {col})"
        return text

    def error(self, message, row=None, col=None):
        return WorkbookError(f"{self.where(row, col)}: {message}")

    def ref(self, row, col):
        """A short reference to a cell for use inside another cell's message."""
        return f"sheet '{self.name}', cell {column_letters(col)}{row}"

    def require_block(self, what):
        if self.top is None:
            raise self.error(f"the sheet holds no numbers; expected {what}")

    def value(self, row, col, what, empty_hint=""):
        """The finite number in a cell, else WorkbookError naming the cell.

        what names the value ('x of vertex 3 of fracture 2'); empty_hint is added to the
        message when the cell is empty.
        """
        kind, value = self.cells.get((row, col), ("empty", None))
        if kind == "number":
            if math.isnan(value):
                raise self.error(f"{what} is NaN", row, col)
            if math.isinf(value):
                raise self.error(f"{what} is {'-' if value < 0 else ''}Inf", row, col)
            if value != 0.0 and not MIN_MAGNITUDE <= abs(value) <= MAX_MAGNITUDE:
                raise self.error(f"{what} = {shown(value)}: a number must be 0 or of "
                                 f"magnitude between {MIN_MAGNITUDE:g} and {MAX_MAGNITUDE:g}",
                                 row, col)
            return value
        if kind == "empty":
            formula = self.workbook.formula(self.name, row, col)
            if formula is not None:
                raise self.error(f"{what} is the formula {formula} without a stored value; "
                                 "open and save the workbook in a spreadsheet program to "
                                 "compute it", row, col)
            raise self.error(f"the cell is empty; expected {what}{empty_hint}", row, col)
        if kind == "text":
            text = value if len(value) <= 40 else value[:37] + "..."
            raise self.error(f"expected {what}, a number, but the cell holds the text "
                             f"{text!r}", row, col)
        if kind == "logical":
            raise self.error(f"expected {what}, a number, but the cell holds the logical "
                             f"{'TRUE' if value else 'FALSE'}", row, col)
        if kind == "date":
            raise self.error(f"expected {what}, a number, but the cell holds a date", row, col)
        raise self.error(f"{what} is the error value {value}", row, col)

    def count(self, row, col, what):
        """A positive integer (stored as a number) in a cell."""
        value = self.value(row, col, what)
        if value != int(value) or not 1 <= value <= MAX_COUNT:
            raise self.error(f"{what} = {shown(value)} must be a positive integer", row, col)
        return int(value)

    def is_number_like(self, row, col):
        """True for a cell inside the data that is neither empty nor a label (text)."""
        return self.cells.get((row, col), ("empty", None))[0] not in ("empty", "text")


class Workbook:
    """A workbook read with xlrd (.xls) or openpyxl (.xlsx)."""

    def __init__(self, path):
        self.path = str(path)
        self._formulas = None
        try:
            with open(path, "rb") as stream:
                head = stream.read(8)
        except OSError as exc:
            raise WorkbookError(f"{self.path}: cannot read: {exc.strerror or exc}") from exc
        if head.startswith(XLS_MAGIC):
            self.kind = "xls"
            self.sheets = self._read_xls(path)
        elif head.startswith(ZIP_MAGIC):
            self.kind = "xlsx"
            self.sheets = self._read_xlsx(path)
        else:
            raise WorkbookError(f"{self.path}: not an Excel workbook (.xls or .xlsx)")

    def _read_xls(self, path):
        import xlrd

        try:
            book = xlrd.open_workbook(path, on_demand=True)
            sheets = {}
            for name in book.sheet_names():
                sheet = book.sheet_by_name(name)
                cells = {}
                for r in range(sheet.nrows):
                    for c in range(sheet.ncols):
                        kind = sheet.cell_type(r, c)
                        value = sheet.cell_value(r, c)
                        if kind == xlrd.XL_CELL_NUMBER:
                            cells[r + 1, c + 1] = ("number", float(value))
                        elif kind == xlrd.XL_CELL_TEXT:
                            if value.strip():
                                cells[r + 1, c + 1] = ("text", value)
                        elif kind == xlrd.XL_CELL_DATE:
                            cells[r + 1, c + 1] = ("date", value)
                        elif kind == xlrd.XL_CELL_BOOLEAN:
                            cells[r + 1, c + 1] = ("logical", bool(value))
                        elif kind == xlrd.XL_CELL_ERROR:
                            text = xlrd.error_text_from_code.get(value, f"code {value}")
                            cells[r + 1, c + 1] = ("error", text)
                sheets[name] = cells
                book.unload_sheet(name)
            book.release_resources()
        except Exception as exc:  # xlrd raises many kinds on a damaged file
            raise WorkbookError(f"{self.path}: cannot read the .xls workbook: "
                                f"{one_line(exc)}") from exc
        return sheets

    @staticmethod
    def _xlsx_cells(worksheet):
        import datetime

        cells = {}
        for row in worksheet.iter_rows():
            for cell in row:
                value = cell.value
                if value is None:
                    continue
                key = (cell.row, cell.column)
                if cell.data_type == "e":
                    cells[key] = ("error", str(value))
                elif isinstance(value, bool):
                    cells[key] = ("logical", value)
                elif isinstance(value, (int, float)):
                    cells[key] = ("number", float(value))
                elif isinstance(value, (datetime.datetime, datetime.date, datetime.time,
                                        datetime.timedelta)):
                    cells[key] = ("date", value)
                elif str(value).strip():
                    cells[key] = ("text", str(value))
        return cells

    def _load_xlsx(self, path, data_only):
        import warnings

        import openpyxl

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # e.g. "data validation extension not supported"
            with open(path, "rb") as stream:  # a stream: no check of the file's extension
                return openpyxl.load_workbook(stream, data_only=data_only)

    def _read_xlsx(self, path):
        try:
            book = self._load_xlsx(path, data_only=True)
            sheets = {ws.title: self._xlsx_cells(ws) for ws in book.worksheets}
            book.close()
        except Exception as exc:  # openpyxl raises many kinds on a damaged file
            raise WorkbookError(f"{self.path}: cannot read the .xlsx workbook: "
                                f"{one_line(exc)}") from exc
        return sheets

    def formula(self, sheet, row, col):
        """The formula of an .xlsx cell whose value is missing (no cached result), or None."""
        if self.kind != "xlsx":
            return None
        if self._formulas is None:
            try:
                book = self._load_xlsx(self.path, data_only=False)
                self._formulas = {ws.title: ws for ws in book.worksheets}
            except (OSError, ValueError, KeyError, zipfile.BadZipFile):
                self._formulas = {}  # it was read once already; give up on the hint only
        worksheet = self._formulas.get(sheet)
        if worksheet is None:
            return None
        value = worksheet.cell(row=row, column=col).value
        return value if isinstance(value, str) and value.startswith("=") else None

    def sheet(self, name):
        if name in self.sheets:
            return Sheet(self, name, self.sheets[name])
        matches = [s for s in self.sheets if s.strip().lower() == name]
        if len(matches) == 1:
            return Sheet(self, matches[0], self.sheets[matches[0]])
        present = ", ".join(f"'{s}'" for s in self.sheets) or "none"
        raise WorkbookError(f"{self.path}: no sheet '{name}' (the comp2DDM layout needs "
                            f"the sheets {', '.join(SHEETS)}; this workbook has {present})")


def read_parm(book):
    """Sheet parm: the 12 numbers of its one row, checked; returns a dict and the cells."""
    sheet = book.sheet("parm")
    layout = ", ".join(PARM_NAMES)
    sheet.require_block(f"one row: {layout}")
    row = sheet.top
    if sheet.bottom != row:
        later = min(r for (r, c) in sheet.cells if r > row and sheet.is_number_like(r, c))
        col = min(c for (r, c) in sheet.cells if r == later and sheet.is_number_like(r, c))
        raise sheet.error(f"a second row of values; sheet 'parm' holds one row: {layout}",
                          later, col)
    left = sheet.left
    if sheet.right > left + len(PARM_NAMES) - 1:
        col = min(c for (r, c) in sheet.cells
                  if c >= left + len(PARM_NAMES) and sheet.is_number_like(r, c))
        raise sheet.error(f"a 13th value; sheet 'parm' holds 12: {layout}", row, col)
    values, cells = {}, {}
    for k, (name, meaning) in enumerate(zip(PARM_NAMES, PARM_MEANINGS)):
        col = left + k
        what = f"{name} ({meaning}, value {k + 1} of 12)"
        if name in ("n_fractures", "nx", "ny"):
            values[name] = sheet.count(row, col, what)
        else:
            values[name] = sheet.value(row, col, what)
        cells[name] = (row, col)
    nu, e = values["nu"], values["E"]
    if not -1.0 < nu < 0.5:
        raise sheet.error(f"nu (Poisson's ratio) = {shown(nu)} must lie in (-1, 0.5)",
                          *cells["nu"])
    if not e > 0.0:
        raise sheet.error(f"E (Young's modulus) = {shown(e)} must be positive", *cells["E"])
    return sheet, values, cells


def read_counts(book, parm_sheet, nfrac, nfrac_cell):
    """Sheet no: one row of n_fractures positive integers."""
    sheet = book.sheet("no")
    nfrac_ref = f"n_fractures = {nfrac} ({parm_sheet.ref(*nfrac_cell)})"
    sheet.require_block(f"one row with the number of elements of each fracture; {nfrac_ref}")
    row = sheet.top
    if sheet.bottom != row:
        later = min(r for (r, c) in sheet.cells if r > row and sheet.is_number_like(r, c))
        col = min(c for (r, c) in sheet.cells if r == later and sheet.is_number_like(r, c))
        raise sheet.error("a second row of values; sheet 'no' holds one row: the number of "
                          "elements of each fracture", later, col)
    width = sheet.right - sheet.left + 1
    if width > nfrac:
        col = min(c for (r, c) in sheet.cells
                  if c >= sheet.left + nfrac and sheet.is_number_like(r, c))
        raise sheet.error(f"a value for fracture {col - sheet.left + 1}, but {nfrac_ref}",
                          row, col)
    if width < nfrac:
        raise sheet.error(f"the cell is empty; expected the number of elements of fracture "
                          f"{width + 1}: {nfrac_ref}", row, sheet.right + 1)
    counts = [sheet.count(row, sheet.left + k, f"the number of elements of fracture {k + 1}")
              for k in range(nfrac)]
    return sheet, counts


def read_columns(book, name, per_fracture, counts, no_sheet, extra, what):
    """Sheets px, py, mu, sf: column k of the numeric block holds counts[k] + extra values.

    Returns the values per fracture and their (row, col) cells.
    """
    sheet = book.sheet(name)
    nfrac = len(counts)
    sheet.require_block(f"one column per fracture ({nfrac}) with its {per_fracture}")
    width = sheet.right - sheet.left + 1
    for k in range(width):
        col = sheet.left + k
        if col not in sheet.value_rows:
            raise sheet.error(f"column {column_letters(col)} holds no values but lies between "
                              "columns of values; comp2DDM would read it as the column of "
                              f"fracture {k + 1}", sheet.top, col)
    if width != nfrac:
        if width > nfrac:
            col = sheet.left + nfrac
            row = sheet.value_rows[col][0]
            problem = f"a column of values for fracture {nfrac + 1}"
        else:
            row, col = sheet.top, sheet.right + 1
            problem = f"the cell is empty; expected the column of fracture {width + 1}"
        span = (f"column {column_letters(sheet.left)}" if width == 1 else
                f"columns {column_letters(sheet.left)} to {column_letters(sheet.right)}")
        raise sheet.error(f"{problem}, but there are {nfrac} fractures (n_fractures and "
                          f"sheet 'no'); the values of the sheet span {span}", row, col)
    values, cells = [], []
    for k, n in enumerate(counts):
        col = sheet.left + k
        need = n + extra
        count_ref = f"{no_sheet.ref(no_sheet.top, no_sheet.left + k)} gives {n} elements"
        column, where = [], []
        for i in range(need):
            row = sheet.top + i
            column.append(sheet.value(row, col, f"{what} {i + 1} of fracture {k + 1}",
                                      f" ({count_ref}, so {need} values in this column)"))
            where.append((row, col))
        last = sheet.value_rows[col][-1]
        if last >= sheet.top + need:
            first = min(r for r in sheet.value_rows[col] if r >= sheet.top + need)
            raise sheet.error(f"a value beyond the {need} of fracture {k + 1} ({count_ref}); "
                              f"the counts of sheet 'no' and sheet '{name}' disagree",
                              first, col)
        values.append(column)
        cells.append(where)
    return sheet, values, cells


def read_workbook(path):
    """Read and check a comp2DDM workbook; returns the model as a dict."""
    book = Workbook(path)
    parm_sheet, parm, parm_cells = read_parm(book)
    nfrac = parm["n_fractures"]
    no_sheet, counts = read_counts(book, parm_sheet, nfrac, parm_cells["n_fractures"])
    px_sheet, px, px_cells = read_columns(book, "px", "vertex x coordinates", counts,
                                          no_sheet, 1, "x of vertex")
    _, py, _ = read_columns(book, "py", "vertex y coordinates", counts, no_sheet, 1,
                            "y of vertex")
    mu_sheet, mu, mu_cells = read_columns(book, "mu", "friction coefficients", counts,
                                          no_sheet, 0, "friction coefficient of element")
    sf_sheet, sf, sf_cells = read_columns(book, "sf", "frictional strengths", counts,
                                          no_sheet, 0, "frictional strength of element")
    for sheet, values, cells, name in ((mu_sheet, mu, mu_cells, "friction coefficient"),
                                       (sf_sheet, sf, sf_cells, "frictional strength")):
        for k, column in enumerate(values):
            for i, value in enumerate(column):
                if value < 0.0:
                    raise sheet.error(f"{name} of element {i + 1} of fracture {k + 1} = "
                                      f"{shown(value)} must be >= 0", *cells[k][i])
    for k, (xs, ys) in enumerate(zip(px, py)):
        for i in range(1, len(xs)):
            if xs[i] == xs[i - 1] and ys[i] == ys[i - 1]:
                raise px_sheet.error(f"vertex {i + 1} of fracture {k + 1} equals vertex {i} "
                                     f"(sheets 'px' and 'py'): element {i} has zero length",
                                     *px_cells[k][i])
    return {"parm": parm, "counts": counts, "px": px, "py": py, "mu": mu, "sf": sf}


def grid_axis(vmin, vmax, n):
    """The paper's linspace(vmin, vmax, n) as ddc2d's (min, max, n): one point is vmax."""
    return (vmax, vmax, 1) if n == 1 else (vmin, vmax, n)


def to_outputs(model, source, stem, title, length_unit, stress_unit, lcp_method):
    """The namelist text and the element CSV texts {file name: text} of a model."""
    parm = model["parm"]
    nfrac = parm["n_fractures"]
    files = {}
    fracture_groups = []
    for k in range(nfrac):
        name = f"{stem}_fracture{k + 1}.csv"
        px, py, mu, sf = (model[key][k] for key in ("px", "py", "mu", "sf"))
        comment = (f"# fracture {k + 1} of the comp2DDM workbook {source} (column {k + 1} of "
                   "the sheets px, py, mu, sf)")
        rows = [comment, CSV_HEADER]
        for i in range(model["counts"][k]):
            rows.append(",".join(number(v) for v in (px[i], py[i], px[i + 1], py[i + 1],
                                                     mu[i], sf[i], 0.0)))
        files[name] = "\n".join(rows) + "\n"
        fracture_groups.append(f"&fracture name = 'fracture_{k + 1}', "
                               f"elements_file = {quoted(name)} /")
    xmin, xmax, nx = grid_axis(parm["xmin"], parm["xmax"], parm["nx"])
    ymin, ymax, ny = grid_axis(parm["ymin"], parm["ymax"], parm["ny"])
    nelements = sum(model["counts"])
    out = [
        f"! Converted by comp2ddm2nml from the comp2DDM workbook {source}",
        "! (the Excel input of Ritz, Mutlu & Pollard 2012, Computers & Geosciences 45:304-312).",
        "! parm: nu, E, sxx, syy, sxy, n_fractures, xmin, nx, xmax, ymin, ny, ymax;",
        "! no: elements per fracture; px, py, mu, sf: one column per fracture.",
        f"! {nfrac} fracture(s), {nelements} elements, every one a frictional contact element",
        "! (fracture k: column k; its elements are in the file named by elements_file).",
        "! Tension positive; Ds = us(-) - us(+), Dn = un(-) - un(+): opening has Dn < 0.",
        f"! Units: {length_unit} and {stress_unit} (the paper uses m and MPa).",
        "! The grid is the paper's meshgrid: /fields/grid arrays, (ny, nx) from Python, read",
        "! column by column (numpy order='F') give the paper's XG(:), YG(:) order.",
        (f"&model title = {quoted(title)}, youngs_modulus = {number(parm['E'])}, "
         f"poissons_ratio = {number(parm['nu'])},"),
        f"       length_unit = {quoted(length_unit)}, stress_unit = {quoted(stress_unit)} /",
        (f"&remote_stress sxx = {number(parm['sxx'])}, syy = {number(parm['syy'])}, "
         f"sxy = {number(parm['sxy'])} /"),
        *fracture_groups,
        f"&grid name = 'grid', xmin = {number(xmin)}, xmax = {number(xmax)}, nx = {nx},",
        f"      ymin = {number(ymin)}, ymax = {number(ymax)}, ny = {ny} /",
        f"&solver lcp_method = {quoted(lcp_method)} /",
    ]
    return "\n".join(out) + "\n", files


def write_atomically(texts):
    """Write {path: text}: all to temporaries first, then rename them (the .nml last).

    On failure, removes every temporary and every file already renamed; raises OSError.
    """
    temporaries, done = [], []
    try:
        # Links followed, anything but a regular file refused (ddc2d.files).
        texts = [(regular_target(path), text) for path, text in texts]
        for path, text in texts:
            fd, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.",
                                             suffix=".partial")
            temporaries.append((temporary, path))
            with os.fdopen(fd, "w") as stream:
                stream.write(text)
        for temporary, path in temporaries:
            os.chmod(temporary, 0o644)
            os.replace(temporary, path)
            done.append(path)
    except OSError:
        for temporary, _ in temporaries:
            Path(temporary).unlink(missing_ok=True)
        for path in done:
            path.unlink(missing_ok=True)
        raise


def require_workbook_readers():
    """Exit with one line when xlrd or openpyxl is missing (the extra 'workbooks')."""
    try:
        import openpyxl  # noqa: F401
        import xlrd  # noqa: F401
    except ImportError as exc:
        print(f"{PROG}: error: the Python package {exc.name or exc} is missing: install "
              "it (pip install 'ddc2d[workbooks]'; in the repository: scripts/setup.sh)",
              file=sys.stderr)
        sys.exit(2)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    parser = argparse.ArgumentParser(
        prog=PROG, description="Convert a comp2DDM Excel workbook (Ritz, Mutlu & Pollard "
        "2012; sheets parm, no, px, py, mu, sf) into a ddc2d namelist and element CSVs.")
    parser.add_argument("workbook", help="the workbook (.xls or .xlsx)")
    parser.add_argument("-o", "--output", help="namelist file to write (default: the "
                        "workbook's name with .nml, in the current folder); the element "
                        "files <stem>_fracture<k>.csv go next to it")
    parser.add_argument("--title", help="&model title (default: the workbook's name)")
    parser.add_argument("--length-unit", default="m", help="length unit label (default m)")
    parser.add_argument("--stress-unit", default="MPa", help="stress unit label (default MPa)")
    parser.add_argument("--lcp-method", default="auto", choices=LCP_METHODS,
                        help="&solver lcp_method (default auto)")
    args = parser.parse_args(argv)
    require_workbook_readers()

    output = Path(args.output) if args.output else Path(Path(args.workbook).stem + ".nml")
    source = " ".join(str(args.workbook).split())  # one line in a comment
    try:
        model = read_workbook(args.workbook)
    except WorkbookError as exc:
        print(f"{PROG}: error: {exc}", file=sys.stderr)
        return 2
    title = args.title if args.title is not None else Path(args.workbook).stem
    nml, csvs = to_outputs(model, source, output.stem, title, args.length_unit,
                           args.stress_unit, args.lcp_method)
    texts = [(output.parent / name, text) for name, text in csvs.items()]
    texts.append((output, nml))
    try:
        write_atomically(texts)
    except OSError as exc:
        print(f"{PROG}: error: cannot write {output} and its element files: "
              f"{exc.strerror or exc}", file=sys.stderr)
        return 3
    print(f"{PROG}: wrote {output} ({model['parm']['n_fractures']} fracture(s), "
          f"{sum(model['counts'])} elements, element files {output.stem}_fracture*.csv)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
