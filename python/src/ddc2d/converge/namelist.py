"""Refine a ddc2d namelist model by powers of two, editing only the values refined.

The file is read into groups and items with the character span of every value
(comments and quoted text masked so that a `/`, `=` or `!` inside them is not taken for
syntax); a refined copy is the original text with those spans replaced, so comments,
layout and every other value stay as the user wrote them. Refined per level k (factor
2^k): every `&fracture elements` value multiplied, `&growth increment` and
`element_length` divided and `&growth steps` multiplied (the same grown length needs
twice the steps), `&load_path steps` multiplied (with a time axis: each time step halved,
the times kept). `&points file` becomes absolute, since the refined files are written
elsewhere. What cannot be refined raises RefineError naming the variable.
"""

import re
from dataclasses import dataclass, field
from pathlib import Path

#: What can be refined: elements (fracture elements), increment (growth increment and
#: element length), steps (load path steps).
REFINEMENTS = ("elements", "increment", "steps")

_GROUP = re.compile(r"&([A-Za-z_]\w*)")
_ITEM = re.compile(r"([A-Za-z_]\w*)\s*(\([^)]*\))?\s*=")
_REPEAT = re.compile(r"^(\d+)\*(.+)$")


class RefineError(Exception):
    """The model cannot be refined: the message says which variable and why."""


@dataclass
class Item:
    """One `name = values` of a group: the span of its values in the file (first token's
    start to last token's end) and the tokens."""

    name: str
    start: int
    end: int
    tokens: list


@dataclass
class Group:
    """One `&name ... /` group of the file with its items in order."""

    name: str
    line: int
    items: list = field(default_factory=list)

    def item(self, name):
        """The item `name` (lower case), or None."""
        return next((i for i in self.items if i.name == name), None)


def _mask(text):
    """The text, same length, with comments blanked and the inside of quoted strings
    replaced by letters (one token, no syntax)."""
    out, quote, comment = list(text), None, False
    for index, char in enumerate(text):
        if comment:
            if char == "\n":
                comment = False
            else:
                out[index] = " "
        elif quote:
            if char == quote:
                quote = None
            else:
                out[index] = "x"  # one token, whatever it holds
        elif char in "'\"":
            quote = char
        elif char == "!":
            comment, out[index] = True, " "
    return "".join(out)


def _item(name, text, masked, start, end):
    """The item `name` whose values lie in text[start:end]: tokens split at commas and
    blanks outside quotes, span from the first token's start to the last one's end (the
    separators and comments around them are not part of it)."""
    found = list(re.finditer(r"[^,\s]+", masked[start:end]))
    tokens = [text[start + m.start():start + m.end()] for m in found]
    if not found:
        return Item(name, start, start, tokens)
    return Item(name, start + found[0].start(), start + found[-1].end(), tokens)


def parse(text):
    """The groups of a namelist text; raises RefineError for a group without its `/`."""
    masked = _mask(text)
    groups, position = [], 0
    while (match := _GROUP.search(masked, position)) is not None:
        end = masked.find("/", match.end())
        line = text.count("\n", 0, match.start()) + 1
        if end < 0:
            raise RefineError(f"&{match.group(1)} on line {line} has no closing '/'")
        group = Group(match.group(1).lower(), line)
        items = list(_ITEM.finditer(masked, match.end(), end))
        for index, item in enumerate(items):
            value_end = items[index + 1].start() if index + 1 < len(items) else end
            group.items.append(_item(item.group(1).lower(), text, masked, item.end(),
                                     value_end))
        groups.append(group)
        position = end + 1
    return groups


def expand(tokens):
    """Tokens with repeat counts (`3*0.6`) written out."""
    values = []
    for token in tokens:
        repeat = _REPEAT.match(token)
        values.extend([repeat.group(2)] * int(repeat.group(1)) if repeat else [token])
    return values


def _number(token, kind, where):
    try:
        return kind(token.replace("d", "e").replace("D", "e"))
    except ValueError:
        raise RefineError(f"{where}: {token!r} is not a number") from None


def _scaled(item, factor, kind, where):
    """The item's values times `factor` as namelist text."""
    values = [_number(t, kind, where) * factor for t in expand(item.tokens)]
    if kind is int:
        return ", ".join(str(v) for v in values)
    return ", ".join(repr(float(v)) for v in values)


def _describe(group, groups):
    same = [g for g in groups if g.name == group.name]
    if len(same) == 1:
        return f"&{group.name}"
    name = group.item("name")
    label = f" '{name.tokens[0].strip(chr(39) + chr(34))}'" if name and name.tokens else ""
    return f"&{group.name}{label} (line {group.line})"


def check_refinable(groups, refine):
    """Raise RefineError for what the chosen refinements cannot refine."""
    names = {g.name for g in groups}
    if "model" not in names:
        raise RefineError("no &model group: not a ddc2d namelist (a TWODD deck? convert it "
                          "with twodd2nml first)")
    if "sweep" in names:
        raise RefineError("&sweep: a sweep is many models; study one of them (its values "
                          "written into the groups) instead")
    for group in groups:
        if group.name == "fracture" and "elements" in refine:
            if group.item("elements_file") is not None:
                raise RefineError(f"{_describe(group, groups)} elements_file: elements read "
                                  "from a file cannot be refined; give the fracture as x, y "
                                  "and elements, or leave elements out of --refine")
            if group.item("elements") is None:
                raise RefineError(f"{_describe(group, groups)}: no elements to refine")


def refined_text(text, groups, level, refine, folder):
    """The namelist text refined to `level` (factor 2^level) by the chosen refinements;
    files named in &points are made absolute (relative to `folder`, the model's)."""
    factor = 2**level
    edits = []
    for group in groups:
        where = _describe(group, groups)
        for item in group.items:
            key = (group.name, item.name)
            if key == ("fracture", "elements") and "elements" in refine:
                edits.append((item, _scaled(item, factor, int, f"{where} elements")))
            elif key in (("growth", "increment"), ("growth", "element_length")) and \
                    "increment" in refine:
                edits.append((item, _scaled(item, 1.0 / factor, float,
                                            f"{where} {item.name}")))
            elif (key == ("growth", "steps") and "increment" in refine) or \
                    (key == ("load_path", "steps") and "steps" in refine):
                edits.append((item, _scaled(item, factor, int, f"{where} steps")))
            elif key == ("points", "file") and item.tokens:
                path = Path(item.tokens[0].strip("'\""))
                absolute = str(path if path.is_absolute() else (folder / path).resolve())
                edits.append((item, "'" + absolute.replace("'", "''") + "'"))
    out = text
    for item, value in sorted(edits, key=lambda e: e[0].start, reverse=True):
        out = out[:item.start] + value + out[item.end:]
    return out
