"""Build a ddc2d model in Python and write it as a namelist file.

    model = ddc2d.Model(youngs_modulus=50000, poissons_ratio=0.25, title="crack")
    model.remote_stress(sxx=0, syy=0, sxy=0)
    model.fracture([-1, 1], [0, 0], elements=200, condition="traction", bc_n=-10,
                   name="crack")
    model.grid(xmin=-2, xmax=2, nx=41, ymin=-1.5, ymax=1.5, ny=31, name="map")
    model.write("crack.nml")

Every method takes the variables of its namelist group (docs/input-reference.md) as
keyword arguments, under their names there; numbers, text, booleans and sequences of
them are written in namelist syntax, and nothing is checked here: ddc2d checks the
model (every problem at once, ddc2d.RunError from ddc2d.run).
"""

import math
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any, Self

from .reader import FilePath

#: Groups that a model has at most once (docs/input-reference.md#the-groups).
SINGLE_GROUPS = ("remote_stress", "pore_fluid", "solver", "symmetry", "load_path", "sweep",
                 "growth")
#: The order of the groups in the file: as in docs/input-reference.md.
GROUP_ORDER = ("model", "material", "remote_stress", "pore_fluid", "fracture", "grid", "line",
               "points", "solver", "symmetry", "load_path", "injection", "sweep", "growth")
#: Namelist lines are kept under this width (values wrap onto continuation lines).
LINE_WIDTH = 90


def namelist_value(value: Any) -> str:
    """`value` in namelist syntax: text quoted ('' doubles a quote), booleans .true. /
    .false., reals in full precision (repr), sequences comma-separated."""
    if isinstance(value, str):
        return "'" + value.replace("'", "''") + "'"
    if isinstance(value, bool):
        return ".true." if value else ".false."
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"{value} cannot be written: ddc2d takes finite numbers only")
        return repr(float(value))  # float(): numpy scalars print as np.float64(...)
    if hasattr(value, "tolist"):  # a numpy array or scalar
        return namelist_value(value.tolist())
    if isinstance(value, (list, tuple)):
        if not value:
            raise ValueError("an empty list cannot be written to a namelist")
        return ", ".join(namelist_value(v) for v in value)
    raise TypeError(f"{value!r} ({type(value).__name__}) is not a namelist value")


def namelist_group(group: str, variables: Mapping[str, Any]) -> str:
    """One group `&group name = value, ... /`, wrapped at LINE_WIDTH."""
    lines = [f"&{group}"]
    for name, value in variables.items():
        item = f"{name} = {namelist_value(value)}"
        if len(lines[-1]) + len(item) + 2 > LINE_WIDTH and lines[-1] != f"&{group}":
            lines[-1] += ","
            lines.append("    " + item)
        else:
            separator = " " if lines[-1] == f"&{group}" else ", "
            lines[-1] += separator + item
    lines[-1] += " /"
    return "\n".join(lines) + "\n"


class Model:
    """A ddc2d model: the &model group and the groups added by the methods below."""

    def __init__(self, youngs_modulus: float | None, poissons_ratio: float | None,
                 **model: Any) -> None:
        """`youngs_modulus`, `poissons_ratio` and the other &model variables (title,
        length_unit, stress_unit, domain, interface_y); with domain = 'bimaterial' the two
        are None and material() gives each half-plane's."""
        self.groups: list[tuple[str, dict[str, Any]]] = [
            ("model", {k: v for k, v in {"youngs_modulus": youngs_modulus,
                                         "poissons_ratio": poissons_ratio, **model}.items()
                       if v is not None})]
        #: Point sets of &points: the name -> (x, y), written to CSV files by write().
        self.point_sets: dict[str, tuple[list[float], list[float]]] = {}

    def _add(self, group: str, variables: Mapping[str, Any]) -> Self:
        if group in SINGLE_GROUPS:
            self.groups = [(g, v) for g, v in self.groups if g != group]
        self.groups.append((group, {k: v for k, v in variables.items() if v is not None}))
        return self

    def material(self, name: str, youngs_modulus: float, poissons_ratio: float) -> Self:
        """&material: the material 'upper' or 'lower' of two bonded half-planes
        (domain = 'bimaterial')."""
        return self._add("material", {"name": name, "youngs_modulus": youngs_modulus,
                                      "poissons_ratio": poissons_ratio})

    def remote_stress(self, sxx: float = 0.0, syy: float = 0.0, sxy: float = 0.0,
                      **gradients: float) -> Self:
        """&remote_stress: the remote stress [stress unit] and dsxx_dy, ... (replaces an
        earlier one)."""
        return self._add("remote_stress", {"sxx": sxx, "syy": syy, "sxy": sxy, **gradients})

    def pore_fluid(self, p0: float = 0.0, dp_dy: float = 0.0) -> Self:
        """&pore_fluid: pore pressure at y = 0 and its change with y."""
        return self._add("pore_fluid", {"p0": p0, "dp_dy": dp_dy})

    def fracture(self, x: Iterable[float], y: Iterable[float], elements: int | Iterable[int],
                 condition: str = "contact", name: str | None = None, **values: Any) -> Self:
        """&fracture: a polyline through the vertices (x, y) cut into `elements` equal
        elements (one count, or one per segment), with its condition and values (mu, sf,
        pressure for 'contact'; bc_s, bc_n for the others; the strength laws)."""
        return self._add("fracture", {"name": name, "x": list(x), "y": list(y),
                                      "elements": elements, "condition": condition,
                                      **values})

    def grid(self, xmin: float, xmax: float, nx: int, ymin: float, ymax: float, ny: int,
             name: str | None = None) -> Self:
        """&grid: nx x ny observation points from (xmin, ymin) to (xmax, ymax)."""
        return self._add("grid", {"name": name, "xmin": xmin, "xmax": xmax, "nx": nx,
                                  "ymin": ymin, "ymax": ymax, "ny": ny})

    def line(self, x_begin: float, y_begin: float, x_end: float, y_end: float, points: int,
             name: str | None = None) -> Self:
        """&line: `points` equally spaced observation points from begin to end."""
        return self._add("line", {"name": name, "x_begin": x_begin, "y_begin": y_begin,
                                  "x_end": x_end, "y_end": y_end, "points": points})

    def points(self, x: Iterable[float], y: Iterable[float], name: str) -> Self:
        """&points: observation points at (x, y), written to <namelist stem>_<name>.csv
        beside the namelist file."""
        self.point_sets[name] = (list(x), list(y))
        return self._add("points", {"name": name})

    def solver(self, **values: Any) -> Self:
        """&solver: lcp_method, open_cohesion, block_size."""
        return self._add("solver", values)

    def symmetry(self, **values: Any) -> Self:
        """&symmetry: kind, xsym, ysym."""
        return self._add("symmetry", values)

    def load_path(self, steps: int | Iterable[int], **loads: Any) -> Self:
        """&load_path: steps per leg and the loads at every vertex (sxx, ..., p0) and
        their times (time)."""
        return self._add("load_path", {"steps": steps, **loads})

    def injection(self, fracture: str, x: float, y: float, name: str | None = None,
                  **values: Any) -> Self:
        """&injection: a fluid source at (x, y) on the fracture named `fracture`, with
        overpressure or rate, and start, stop (one group per source; the path needs times:
        load_path(time=...))."""
        return self._add("injection", {"name": name, "fracture": fracture, "x": x, "y": y,
                                       **values})

    def growth(self, steps: int, toughness: float, **values: Any) -> Self:
        """&growth: most steps, toughness K_Ic and increment, element_length, tips, ..."""
        return self._add("growth", {"steps": steps, "toughness": toughness, **values})

    def namelist(self, stem: str = "model") -> str:
        """The namelist text; &points files are named <stem>_<name>.csv."""
        order = {group: index for index, group in enumerate(GROUP_ORDER)}
        text = []
        for group, variables in sorted(self.groups, key=lambda item: order[item[0]]):
            if group == "points":
                variables = {**variables, "file": f"{stem}_{variables['name']}.csv"}
            text.append(namelist_group(group, variables))
        return "".join(text)

    def write(self, path: FilePath) -> Path:
        """Write the namelist to `path` and the &points files beside it; returns the path."""
        path = Path(path)
        for name, (x, y) in self.point_sets.items():
            rows = "".join(f"{a!r},{b!r}\n" for a, b in zip(map(float, x), map(float, y)))
            (path.parent / f"{path.stem}_{name}.csv").write_text("x,y\n" + rows)
        path.write_text(self.namelist(path.stem))
        return path
