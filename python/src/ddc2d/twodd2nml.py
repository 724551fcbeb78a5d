"""Convert a classic TWODD deck (Crouch & Starfield 1983, ch. 5) into a ddc2d namelist.

usage: twodd2nml DECK [-o OUT.nml]

The deck is read as Fortran list-directed input, record by record: a title line;
NUMBS, NUMOS, KSYM; PR, E, XSYM, YSYM; PXX, PYY, PXY; NUMBS segment records
NUM, XBEG, YBEG, XEND, YEND, KODE, BVS, BVN; NUMOS observation records
XBEG, YBEG, XEND, YEND, NUMPB. Blank lines are skipped, a record may continue on the next
line, values beyond those a record needs are ignored.

The namelist has one &fracture per segment (named segment_<k>, condition from KODE, bc_s
and bc_n the given values) and one &line per observation record (points = NUMPB + 2, or 1
when the ends coincide), so that `ddc2d OUT.nml` solves the same model as
`ddc2d --twodd DECK`. Decks with symmetry (KSYM 2-4) get a &symmetry group
(kind = 'x', 'y' or 'both', xsym, ysym).

Exit status: 0 success, 2 unreadable or malformed deck (the message names the line).
"""

import argparse
import math
import sys
from pathlib import Path

from .files import write_text_atomically

# KODE 1-4 are ddc2d's condition codes 1-4 (reader.CONDITION_NAMES, checked by
# test_ddc2d_h5.py).
CONDITIONS = {1: "traction", 2: "displacement", 3: "mixed_us_sn", 4: "mixed_ss_un"}
SYMMETRY_KINDS = {1: "none", 2: "x", 3: "y", 4: "both"}
# The namelist reader gained an optional &symmetry group (kind, xsym, ysym) when True.
SYMMETRY_IN_NAMELIST = True


class DeckError(Exception):
    """A malformed deck: the message names the file and the line."""


class Deck:
    """The lines of a deck and a cursor over list-directed records."""

    def __init__(self, path):
        self.path = str(path)
        try:
            text = Path(path).read_text()
        except (OSError, UnicodeDecodeError) as exc:
            raise DeckError(f"{self.path}: cannot read: {exc}") from exc
        if not text.strip():
            raise DeckError(f"{self.path}: the file is empty")
        self.lines = text.splitlines()
        self.last = 1  # line 1 is the title

    def record(self, types, what):
        """Read one record of the given types (int or float); returns (values, line)."""
        tokens, first = [], None
        while len(tokens) < len(types):
            while self.last < len(self.lines) and not self.lines[self.last].strip():
                self.last += 1
            if self.last >= len(self.lines):
                line = len(self.lines) + 1 if first is None else first
                if first is None:
                    raise DeckError(f"{self.path}: line {line}: the deck ends too early: "
                                    f"expected {what}")
                raise DeckError(f"{self.path}: line {line}: too few values for {what}")
            if first is None:
                first = self.last + 1
            text = self.lines[self.last].split("/")[0]
            tokens += [t for t in text.replace(",", " ").split()]
            self.last += 1
        values = []
        for kind, token in zip(types, tokens):
            try:
                if kind is int:
                    values.append(int(token))
                else:
                    value = float(token.replace("d", "e").replace("D", "E"))
                    if not math.isfinite(value):
                        raise DeckError(f"{self.path}: line {first}: {what}: {token} is not "
                                        "a finite number")
                    values.append(value)
            except ValueError as exc:
                kind_name = "an integer" if kind is int else "a number"
                raise DeckError(f"{self.path}: line {first}: cannot read {what}: {token!r} "
                                f"is not {kind_name}") from exc
        return values, first


def read_deck(path):
    """Parse a deck into a dict; raises DeckError with the line number."""
    deck = Deck(path)
    title = deck.lines[0].strip() or Path(path).stem
    (numbs, numos, ksym), line = deck.record([int] * 3, "NUMBS, NUMOS, KSYM")
    if numbs < 1:
        raise DeckError(f"{deck.path}: line {line}: NUMBS = {numbs} must be at least 1")
    if numos < 0:
        raise DeckError(f"{deck.path}: line {line}: NUMOS = {numos} must be 0 or more")
    if ksym not in SYMMETRY_KINDS:
        raise DeckError(f"{deck.path}: line {line}: KSYM = {ksym} must be 1, 2, 3 or 4")
    (pr, e, xsym, ysym), line = deck.record([float] * 4, "PR, E, XSYM, YSYM")
    if not -1.0 < pr < 0.5:
        raise DeckError(f"{deck.path}: line {line}: PR = {pr} must lie in (-1, 0.5)")
    if not e > 0.0:
        raise DeckError(f"{deck.path}: line {line}: E = {e} must be positive")
    (pxx, pyy, pxy), _ = deck.record([float] * 3, "PXX, PYY, PXY")
    segments = []
    for k in range(1, numbs + 1):
        what = f"boundary segment {k} of {numbs} (NUM, XBEG, YBEG, XEND, YEND, KODE, BVS, BVN)"
        (num, xb, yb, xe, ye, kode, bvs, bvn), line = deck.record(
            [int, float, float, float, float, int, float, float], what)
        if num < 1:
            raise DeckError(f"{deck.path}: line {line}: segment {k}: NUM = {num} must be at "
                            "least 1")
        if kode not in CONDITIONS:
            raise DeckError(f"{deck.path}: line {line}: segment {k}: KODE = {kode} must be "
                            "1, 2, 3 or 4")
        if xb == xe and yb == ye:
            raise DeckError(f"{deck.path}: line {line}: segment {k}: its ends coincide")
        segments.append({"num": num, "x": (xb, xe), "y": (yb, ye), "kode": kode, "bvs": bvs,
                         "bvn": bvn})
    lines = []
    for k in range(1, numos + 1):
        what = f"observation line {k} of {numos} (XBEG, YBEG, XEND, YEND, NUMPB)"
        (xb, yb, xe, ye, numpb), line = deck.record([float] * 4 + [int], what)
        if numpb < 0:
            raise DeckError(f"{deck.path}: line {line}: observation line {k}: NUMPB = "
                            f"{numpb} must be 0 or more")
        points = 1 if (xb == xe and yb == ye) else numpb + 2
        lines.append({"x_begin": xb, "y_begin": yb, "x_end": xe, "y_end": ye,
                      "points": points})
    return {"title": title, "pr": pr, "e": e, "ksym": ksym, "xsym": xsym, "ysym": ysym,
            "sxx": pxx, "syy": pyy, "sxy": pxy, "segments": segments, "lines": lines}


def number(value):
    """A real as the shortest text that reads back to the same double."""
    return repr(float(value))


def quoted(text):
    return "'" + text.replace("'", "''") + "'"


def to_namelist(model, source):
    """The namelist text of a parsed deck."""
    out = [f"! Converted from the TWODD deck {source} by twodd2nml.",
           "! Units: TWODD decks carry none; ddc2d labels them m and Pa (any consistent set).",
           f"&model title = {quoted(model['title'])}, youngs_modulus = {number(model['e'])},",
           (f"       poissons_ratio = {number(model['pr'])}, length_unit = 'm', "
            "stress_unit = 'Pa' /"),
           (f"&remote_stress sxx = {number(model['sxx'])}, syy = {number(model['syy'])}, "
            f"sxy = {number(model['sxy'])} /")]
    if model["ksym"] != 1:
        out.append(f"&symmetry kind = '{SYMMETRY_KINDS[model['ksym']]}', "
                   f"xsym = {number(model['xsym'])}, ysym = {number(model['ysym'])} /")
    for k, s in enumerate(model["segments"], start=1):
        out.append(f"&fracture name = 'segment_{k}', x = {number(s['x'][0])}, "
                   f"{number(s['x'][1])}, y = {number(s['y'][0])}, {number(s['y'][1])},")
        out.append(f"          elements = {s['num']}, condition = '{CONDITIONS[s['kode']]}', "
                   f"bc_s = {number(s['bvs'])}, bc_n = {number(s['bvn'])} /")
    for k, o in enumerate(model["lines"], start=1):
        out.append(f"&line name = 'line_{k}', x_begin = {number(o['x_begin'])}, "
                   f"y_begin = {number(o['y_begin'])}, x_end = {number(o['x_end'])}, "
                   f"y_end = {number(o['y_end'])}, points = {o['points']} /")
    return "\n".join(out) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="twodd2nml", description="Convert a classic TWODD deck into a ddc2d namelist.")
    parser.add_argument("deck", help="the TWODD deck")
    parser.add_argument("-o", "--output", help="namelist file to write (default: stdout)")
    args = parser.parse_args(argv)
    try:
        model = read_deck(args.deck)
    except DeckError as exc:
        print(f"twodd2nml: error: {exc}", file=sys.stderr)
        return 2
    if model["ksym"] != 1 and not SYMMETRY_IN_NAMELIST:
        print(f"twodd2nml: error: {args.deck}: KSYM = {model['ksym']} (symmetry "
              f"{SYMMETRY_KINDS[model['ksym']]}): the ddc2d namelist input has no symmetry "
              f"group yet; run this deck directly with `ddc2d --twodd {args.deck}`",
              file=sys.stderr)
        return 2
    text = to_namelist(model, args.deck)
    if args.output:
        try:
            write_text_atomically(args.output, text)
        except OSError as exc:
            print(f"twodd2nml: error: cannot write {args.output}: {exc}", file=sys.stderr)
            return 3
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
