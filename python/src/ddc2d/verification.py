"""The scored verification suite (docs/verification.md): rows of ddc2d results against
closed forms and published values, and the table made of them. The command
ddc2d-verification-table, in the repository also scripts/verification-table.

    ddc2d-verification-table ROWS_DIR [-o docs/verification.md] [--check]

The tests of the CTest label `verification` (tests/verification/) each run ddc2d on a
model, compare one quantity with its reference at a stated tolerance, and write that row
as JSON (write_row) into ROWS_DIR (<build>/verification/rows). This command writes the
table of every row into the page (default docs/verification.md), keeping the page's text
above the table; --check writes nothing and exits 1 when the committed table differs from
the rows (other rows, another pass/fail, or a number beyond NUMBER_RTOL). Exit status 2:
no rows, a bad row or a page without the table's marker.
"""

import argparse
import json
import math
import sys
from pathlib import Path

from .paths import source_tree

#: Every row has these keys. `tolerance_kind` is 'relative' (error = |value - reference| /
#: |reference|) or 'absolute' (error = |value - reference|, in the quantity's unit);
#: `order` is the observed order of convergence over three levels (ddc2d.richardson) or
#: None where it does not apply.
ROW_KEYS = ("id", "benchmark", "reference", "quantity", "tolerance", "tolerance_kind",
            "value", "reference_value", "error", "mesh", "order", "passed")
#: The page's text above this line is kept; the table is written below it.
TABLE_MARKER = "<!-- table written by ddc2d-verification-table: do not edit below -->"
#: Numbers of the committed table agree with the rows' within this relative amount (the
#: table prints 5 significant digits; round-off differences between CPUs stay far below).
NUMBER_RTOL = 1e-3
#: An error or an order agrees within this share of the row's tolerance / this amount:
#: errors near zero differ between CPUs in their last digits.
ERROR_SHARE_OF_TOLERANCE = 0.02
ORDER_ATOL = 0.05
COLUMNS = ("id", "benchmark", "quantity", "reference", "mesh", "ddc2d", "reference value",
           "error", "tolerance", "observed order", "result")


def make_row(id, benchmark, reference, quantity, value, reference_value, tolerance,
             mesh, tolerance_kind="relative", order=None):
    """One row: the error of `value` against `reference_value` by `tolerance_kind`, and
    whether it is within `tolerance`."""
    if tolerance_kind == "relative":
        error = abs(value - reference_value) / abs(reference_value)
    elif tolerance_kind == "absolute":
        error = abs(value - reference_value)
    else:
        raise ValueError(f"tolerance_kind must be 'relative' or 'absolute', not "
                         f"{tolerance_kind!r}")
    return {"id": id, "benchmark": benchmark, "reference": reference, "quantity": quantity,
            "tolerance": float(tolerance), "tolerance_kind": tolerance_kind,
            "value": float(value), "reference_value": float(reference_value),
            "error": float(error), "mesh": mesh,
            "order": None if order is None else float(order),
            "passed": bool(error <= tolerance)}


def write_row(row, folder):
    """Write `row` as <folder>/<id>.json (the folder is made when missing)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{row['id']}.json").write_text(json.dumps(row, indent=1) + "\n")


def load_rows(folder):
    """Every row of `folder`, sorted by id. Raises ValueError on a file that is no row."""
    rows = []
    for path in sorted(Path(folder).glob("*.json")):
        row = json.loads(path.read_text())
        missing = [k for k in ROW_KEYS if k not in row]
        if missing:
            raise ValueError(f"{path}: not a verification row (no {', '.join(missing)})")
        rows.append(row)
    return sorted(rows, key=lambda r: r["id"])


def number(value):
    """A number as the table prints it: 5 significant digits."""
    return f"{value:.5g}"


def cell(text):
    return str(text).replace("|", "\\|")


def table_lines(rows):
    """The markdown table of `rows`, one line each."""
    lines = ["| " + " | ".join(COLUMNS) + " |", "|" + " --- |" * len(COLUMNS)]
    for row in rows:
        unit = "" if row["tolerance_kind"] == "relative" else " (absolute)"
        order = "-" if row["order"] is None else f"{row['order']:.2f}"
        cells = (f"`{row['id']}`", row["benchmark"], row["quantity"], row["reference"],
                 row["mesh"], number(row["value"]), number(row["reference_value"]),
                 number(row["error"]), number(row["tolerance"]) + unit, order,
                 "pass" if row["passed"] else "**FAIL**")
        lines.append("| " + " | ".join(cell(c) for c in cells) + " |")
    return lines


def split_page(text):
    """The page's text up to and including the marker line; ValueError without one."""
    head, marker, _ = text.partition(TABLE_MARKER)
    if not marker:
        raise ValueError(f"the page has no line {TABLE_MARKER!r}")
    return head + marker + "\n"


def page_text(head, rows):
    return head + "\n" + "\n".join(table_lines(rows)) + "\n"


def parse_table(text):
    """The rows of a page's table as id -> (ddc2d, reference value, error, order or None,
    passed)."""
    body = text.partition(TABLE_MARKER)[2]
    parsed = {}
    for line in body.splitlines():
        if not line.startswith("| `"):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split(" | ")]
        order = None if cells[9] == "-" else float(cells[9])
        parsed[cells[0].strip("`")] = (float(cells[5]), float(cells[6]), float(cells[7]),
                                       order, cells[10] == "pass")
    return parsed


def differences(text, rows):
    """How the table of the page `text` differs from `rows`: a list of sentences (empty
    when they agree: same ids, pass/fail and orders; numbers within NUMBER_RTOL, errors
    within ERROR_SHARE_OF_TOLERANCE of the tolerance)."""
    table = parse_table(text)
    found = []
    ids = {r["id"] for r in rows}
    for extra in sorted(set(table) - ids):
        found.append(f"{extra}: in the table, but no test wrote this row")
    for row in rows:
        if row["id"] not in table:
            found.append(f"{row['id']}: a row the table does not have")
            continue
        value, reference, error, order, passed = table[row["id"]]
        if passed != row["passed"]:
            found.append(f"{row['id']}: the table says {'pass' if passed else 'FAIL'}")
        for name, shown, now in (("ddc2d", value, row["value"]),
                                 ("reference value", reference, row["reference_value"])):
            if not math.isclose(shown, now, rel_tol=NUMBER_RTOL, abs_tol=1e-300):
                found.append(f"{row['id']}: {name} {shown:.5g} in the table, now {now:.5g}")
        if abs(error - row["error"]) > max(NUMBER_RTOL * abs(row["error"]),
                                           ERROR_SHARE_OF_TOLERANCE * row["tolerance"]):
            found.append(f"{row['id']}: error {error:.5g} in the table, now "
                         f"{row['error']:.5g}")
        if (order is None) != (row["order"] is None) or (
                order is not None and abs(order - row["order"]) > ORDER_ATOL):
            found.append(f"{row['id']}: observed order {order} in the table, now "
                         f"{row['order']}")
    return found


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="ddc2d-verification-table",
        description="Write docs/verification.md from the rows of the verification tests, "
                    "or check the committed table against them.")
    parser.add_argument("rows", type=Path, help="folder of the rows (JSON files)")
    tree = source_tree()
    parser.add_argument("-o", "--page", type=Path, required=tree is None,
                        default=tree / "docs" / "verification.md" if tree else None,
                        help="the page (default: docs/verification.md of the working "
                             "tree the package runs from)")
    parser.add_argument("--check", action="store_true",
                        help="write nothing; exit 1 when the page's table differs")
    args = parser.parse_args(argv)
    try:
        rows = load_rows(args.rows)
        if not rows:
            raise ValueError(f"no rows in {args.rows}: run ctest -L verification first")
        text = args.page.read_text()
        head = split_page(text)
    except (OSError, ValueError) as error:
        print(f"ddc2d-verification-table: {error}", file=sys.stderr)
        return 2
    if args.check:
        found = differences(text, rows)
        for line in found:
            print(f"ddc2d-verification-table: {line}", file=sys.stderr)
        if found:
            print("ddc2d-verification-table: regenerate the table with "
                  f"ddc2d-verification-table {args.rows}", file=sys.stderr)
        return 1 if found else 0
    args.page.write_text(page_text(head, rows))
    failed = sum(not r["passed"] for r in rows)
    print(f"{args.page}: {len(rows)} rows, {failed} failed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
