"""Compare a ddc2d result (HDF5) with a TWODD result print, quantity by quantity.

usage: compare-twodd OURS.h5 RES.txt [--rtol R] [--atol A]

RES.txt is a TWODD print: the classic single-precision one (4-digit E formats) or the
wide double-precision one (es24.15), or the tables `ddc2d --twodd DECK --res RES.txt`
writes. Elements are matched by order (BOUNDARY ELEMENT DATA and the midpoint table:
centre, length, DS, US(-), US(+), DN, UN(-), UN(+), UX(-), UY(-), UX(+), UY(+), SIGMA-S,
SIGMA-N); observation points by their coordinates, each to the nearest point of the HDF5
file (of points equally near within a relative 1e-9, the first in the file; TWODD skips
points near elements, so the print may hold fewer points than the HDF5 file).

A value passes when |ours - theirs| <= h + rtol |theirs| + atol * scale, where h is half a
unit in the last printed digit of the TWODD value (the print's own rounding), and scale
is the largest printed magnitude of that kind of quantity: element displacements and
DDs, point displacements, or stresses (boundary, points and the header's field stress).
Defaults rtol = 1e-4 (TWODD solves in single precision) and atol = 1e-5 suit the classic
print. Against a double-precision print --rtol 1e-9 --atol 1e-12 holds for well-conditioned
decks; a deck whose influence matrix is numerically singular (a closed contour, e.g. a hole
with KODE 3 elements) is determined only to rounding amplified by the conditioning: use
--atol 1e-9 for its points, and do not expect its DDs to agree (docs/compatibility.md).

Prints the largest absolute and relative difference per quantity. Exit status: 0 all
within tolerance, 1 some quantity beyond it (or elements / points that do not match),
2 unreadable input.
"""

import argparse
import math
import re
import sys

import h5py
import numpy as np

from . import reader

ELEMENT_DATA = ["X (CENTER)", "Y (CENTER)", "LENGTH"]
MIDPOINT = ["DS", "US(-)", "US(+)", "DN", "UN(-)", "UN(+)", "UX(-)", "UY(-)", "UX(+)",
            "UY(+)", "SIGMA-S", "SIGMA-N"]
POINT = ["UX", "UY", "SIGXX", "SIGYY", "SIGXY"]
#: The STATE column of ddc2d's --res tables of models with contact elements.
STATE_WORDS = set(reader.STATE_NAMES.values())

NUMBER = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([EeDd][+-]?\d+)?$")


class InputError(Exception):
    """An input file that cannot be read."""


def half_unit(token):
    """Half a unit in the last digit of a printed number ('0.175E+01' -> 0.005)."""
    mantissa, _, exponent = token.upper().replace("D", "E").partition("E")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 0.5 * 10.0 ** (int(exponent or 0) - decimals)


def parse_print(path):
    """The three tables of a TWODD print: values and half units, shape (rows, columns)."""
    try:
        with open(path, encoding="ascii", errors="replace") as handle:
            lines = handle.read().splitlines()
    except OSError as exc:
        raise InputError(f"{path}: cannot read: {exc}") from exc
    tables = {"elements": [], "midpoints": [], "points": []}
    section = None
    field_stress = 0.0
    for line in lines:
        upper = line.upper()
        if "COMPONENT OF FIELD STRESS" in upper and "=" in line:
            try:
                field_stress = max(field_stress, abs(float(line.split("=")[1].split()[0])))
            except (ValueError, IndexError):
                pass
        if "BOUNDARY ELEMENT DATA" in upper:
            section = "elements"
            continue
        if "MIDPOINTS OF BO" in upper:
            section = "midpoints"
            continue
        if "SPECIFIED POINT" in upper:
            section = "points"
            continue
        if section is None:
            continue
        tokens = line.split()
        while tokens and (set(tokens[-1]) <= {"*"} or tokens[-1] in STATE_WORDS):
            tokens.pop()  # the flag mark and the element state of ddc2d's tables
        if len(tokens) < 3 or not tokens[0].isdigit():
            continue
        if not all(NUMBER.match(t) or t.lower() == "nan" for t in tokens[1:]):
            continue
        tables[section].append(tokens[1:])
    result = {}
    for name, rows in tables.items():
        if not rows:
            result[name] = (np.zeros((0, 0)), np.zeros((0, 0)))
            continue
        width = min(len(r) for r in rows)
        values = np.array([[float(t.upper().replace("D", "E")) for t in r[:width]]
                           for r in rows])
        halves = np.array([[half_unit(t) if t.lower() != "nan" else 0.0 for t in r[:width]]
                           for r in rows])
        result[name] = (values, halves)
    result["field_stress"] = field_stress
    if result["midpoints"][0].size == 0:
        raise InputError(f"{path}: no table of displacements and stresses at element "
                         "midpoints found: not a TWODD print?")
    return result


def read_ours(path):
    """Element columns and points (x, y, UX, UY, SIGXX, SIGYY, SIGXY) of a ddc2d result."""
    try:
        with h5py.File(path, "r") as f:
            found = reader.read_elements(path, f)
            e = {k: np.asarray(found[k], dtype=float) for k in (
                "x_begin", "y_begin", "x_end", "y_end", "x_mid", "y_mid", "half_length", "ds",
                "dn", "us_minus", "un_minus", "us_plus", "un_plus", "shear_traction",
                "normal_traction")}
            points = [np.column_stack([np.ravel(field[k]) for k in (
                "x", "y", "ux", "uy", "sxx", "syy", "sxy")])
                for field in reader.read_fields(f).values()]
    except (OSError, KeyError, reader.ResultError) as exc:
        raise InputError(f"{path}: cannot read ddc2d results: {exc}") from exc
    length = 2.0 * e["half_length"]
    safe = np.where(length > 0, length, 1.0)
    c = (e["x_end"] - e["x_begin"]) / safe
    s = (e["y_end"] - e["y_begin"]) / safe
    elements = np.column_stack([e["x_mid"], e["y_mid"], length])
    midpoints = np.column_stack([
        e["ds"], e["us_minus"], e["us_plus"], e["dn"], e["un_minus"], e["un_plus"],
        e["us_minus"] * c - e["un_minus"] * s, e["us_minus"] * s + e["un_minus"] * c,
        e["us_plus"] * c - e["un_plus"] * s, e["us_plus"] * s + e["un_plus"] * c,
        e["shear_traction"], e["normal_traction"]])
    points = np.vstack(points) if points else np.zeros((0, 7))
    return elements, midpoints, points


def worst_row(diff, tol):
    """Row whose difference exceeds its tolerance most (NaN counts as the most); of rows
    equal within the tie rule, the first (reader.index_of_extreme)."""
    excess = diff - tol
    return reader.index_of_extreme(np.where(np.isnan(excess), np.inf, excess))


def nearest_point(points, x, y):
    """(index, distance) of the row of `points` (x, y, ...) nearest to (x, y); of points at
    distances equal within the tie rule, the first (reader.index_of_extreme)."""
    distance = np.hypot(points[:, 0] - x, points[:, 1] - y)
    best = reader.index_of_extreme(distance, "min")
    return best, float(distance[best])


class Report:
    """Per-quantity differences and the verdict."""

    def __init__(self, rtol, atol):
        self.rtol, self.atol = rtol, atol
        self.failed = False
        print(f"{'quantity':<22}{'max |diff|':>13}{'max rel diff':>14}{'worst row':>11}"
              f"{'tolerance used':>16}  verdict")

    def compare(self, label, ours, theirs, halves, scale):
        diff = np.abs(ours - theirs)
        tol = halves + self.rtol * np.abs(theirs) + self.atol * scale
        nan_mismatch = np.isnan(ours) != np.isnan(theirs)
        both_nan = np.isnan(ours) & np.isnan(theirs)
        diff = np.where(both_nan, 0.0, diff)
        rel = np.where(np.abs(theirs) > 0, diff / np.where(theirs != 0, np.abs(theirs), 1.0),
                       np.where(diff > 0, np.inf, 0.0))
        bad = nan_mismatch | (diff > tol)
        worst = worst_row(diff, tol) if diff.size else 0
        verdict = "FAIL" if bad.any() else "ok"
        self.failed |= bool(bad.any())
        max_diff = float(np.max(diff)) if diff.size else 0.0
        max_rel = float(np.max(rel)) if rel.size else 0.0
        print(f"{label:<22}{max_diff:13.3e}{max_rel:14.3e}{worst + 1:11d}"
              f"{float(tol[worst]) if tol.size else 0.0:16.3e}  {verdict}")

    def fail(self, message):
        self.failed = True
        print(f"mismatch: {message}")


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="compare-twodd",
        description="Compare a ddc2d result (HDF5) with a TWODD result print.")
    parser.add_argument("ours", help="ddc2d result file (.h5)")
    parser.add_argument("res", help="TWODD print (classic or wide format)")
    parser.add_argument("--rtol", type=float, default=1e-4,
                        help="relative tolerance (default 1e-4)")
    parser.add_argument("--atol", type=float, default=1e-5,
                        help="absolute tolerance as a fraction of each column's largest "
                             "printed magnitude (default 1e-5)")
    args = parser.parse_args(argv)
    if not (args.rtol >= 0 and args.atol >= 0 and math.isfinite(args.rtol + args.atol)):
        print("compare-twodd: error: tolerances must be finite and >= 0", file=sys.stderr)
        return 2
    try:
        theirs = parse_print(args.res)
        elements, midpoints, points = read_ours(args.ours)
    except InputError as exc:
        print(f"compare-twodd: error: {exc}", file=sys.stderr)
        return 2

    report = Report(args.rtol, args.atol)
    values, halves = theirs["midpoints"]
    pv, ph = theirs["points"]
    # Scales of the absolute tolerance: displacements of the elements, displacements of the
    # points, and stresses (boundary, points, field stress) each share one, so that a
    # column that should vanish (a traction-free face) is judged against the load.
    stress_columns = [values[:, 10:12].ravel() if values.shape[1] >= 12 else np.zeros(0),
                      pv[:, 4:7].ravel() if pv.shape[1] >= 7 else np.zeros(0),
                      np.array([theirs["field_stress"]])]
    stress_scale = float(np.nanmax(np.abs(np.concatenate(stress_columns))))
    element_scale = float(np.nanmax(np.abs(values[:, :10]))) if values.size else 0.0
    point_scale = float(np.nanmax(np.abs(pv[:, 2:4]))) if pv.shape[1] >= 7 else 0.0
    if values.shape[0] != midpoints.shape[0] or values.shape[1] < 12:
        report.fail(f"{values.shape[0]} elements with {values.shape[1]} columns in the print,"
                    f" {midpoints.shape[0]} in {args.ours}")
    else:
        ev, eh = theirs["elements"]
        if ev.shape[0] == elements.shape[0] and ev.shape[1] >= 5:
            # KODE, X, Y, LENGTH, ANGLE, ...: centre and length are columns 2-4.
            for k, label in enumerate(ELEMENT_DATA):
                report.compare(label, elements[:, k], ev[:, k + 1], eh[:, k + 1],
                               float(np.max(np.abs(ev[:, 1:4]))))
        elif ev.size:
            report.fail(f"{ev.shape[0]} rows in BOUNDARY ELEMENT DATA, "
                        f"{elements.shape[0]} elements in {args.ours}")
        for k, label in enumerate(MIDPOINT):
            report.compare(label, midpoints[:, k], values[:, k], halves[:, k],
                           stress_scale if k >= 10 else element_scale)

    if pv.size:
        if pv.shape[1] < 7:
            report.fail("the points table has fewer than 7 columns")
        else:
            matched = []
            for row, (x, y) in enumerate(pv[:, :2]):
                if points.shape[0] == 0:
                    report.fail(f"point {row + 1} ({x:g}, {y:g}) of the print: {args.ours} "
                                "has no observation points")
                    break
                best, distance = nearest_point(points, x, y)
                reach = 2.0 * math.hypot(ph[row, 0], ph[row, 1]) + 1e-9 * max(1.0, abs(x),
                                                                            abs(y))
                if distance > reach:
                    report.fail(f"point {row + 1} ({x:g}, {y:g}) of the print is not in "
                                f"{args.ours}")
                    continue
                matched.append((row, best))
            if matched:
                rows = np.array([m[0] for m in matched])
                ours = points[[m[1] for m in matched]]
                for k, label in enumerate(POINT):
                    report.compare(f"point {label}", ours[:, 2 + k], pv[rows, 2 + k],
                                   ph[rows, 2 + k], stress_scale if k >= 2 else point_scale)
                print(f"points matched: {len(matched)} of {pv.shape[0]} in the print "
                      f"({points.shape[0]} in {args.ours})")
    print("result: " + ("FAIL (beyond tolerance)" if report.failed else "all within tolerance"))
    return 1 if report.failed else 0


if __name__ == "__main__":
    sys.exit(main())
