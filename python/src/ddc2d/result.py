"""A ddc2d result file as a Python object: ``open_result(path)`` -> ``Result``.

The arrays are those of the one reader (ddc2d.reader.load_result, which the command-line
tools use too), with the unit of every dataset read from its ``units`` attribute
(docs/output-reference.md#codings-and-units), the input echo and the provenance (root
attributes). ``Result.to_xarray`` gives an observation set or the loading history as an
xarray Dataset with named dimensions, coordinates and units.
"""

from pathlib import Path
from typing import TYPE_CHECKING, Any, overload

import h5py
import numpy as np

from .reader import Arrays, Coding, FilePath, Loaded, ResultError, load_result

if TYPE_CHECKING:
    import xarray

#: Quantities of an observation set (docs/output-reference.md), in the order shown.
FIELD_QUANTITIES = ("ux", "uy", "sxx", "syy", "sxy", "near_element")
#: Datasets of /history with one value per step and element (the strengths in force where
#: a strength law can change them).
HISTORY_ELEMENT_DATASETS = ("ds", "dn", "state", "shear_traction", "normal_traction",
                            "mu_in_force", "sf_in_force", "tensile_strength_in_force")
#: Datasets of /history with one value per step and tip.
HISTORY_TIP_DATASETS = ("k1", "k2", "grown_length")
#: Datasets of /history with one value per step and fracture (fluid sources:
#: docs/injection.md#output).
HISTORY_FRACTURE_DATASETS = ("slipping_length", "front_begin", "front_end", "moment")
#: Datasets of /history with one value per step besides the loads and the time.
HISTORY_STEP_VARIABLES = ("injected_volume", "stored_volume", "leaked_volume",
                          "fluid_efficiency", "flow_iterations", "flow_residual")
#: The name of the loading history in ``Result.to_xarray``.
HISTORY = "history"


def open_result(path: FilePath) -> "Result":
    """Read the ddc2d result file at `path` (HDF5) into a Result; raises
    ddc2d.ResultError, naming the file and the problem, when it is missing, unreadable or
    not a ddc2d result."""
    loaded = load_result(path)
    try:
        with h5py.File(path, "r") as handle:
            units = read_units(handle)
    except OSError as exc:  # load_result has read it: only a race ends here
        raise ResultError(f"cannot read '{path}': {exc}") from exc
    return Result(loaded, units)


def read_units(handle: h5py.Group) -> dict[str, str]:
    """The ``units`` attribute of every dataset of an open file, by path without the
    leading slash ('elements/ds' -> 'm')."""
    units: dict[str, str] = {}

    def visit(name: str, item: Any) -> None:
        if isinstance(item, h5py.Dataset) and "units" in item.attrs:
            value = item.attrs["units"]
            units[name] = (value.decode() if isinstance(value, bytes) else str(value)).strip()

    handle.visititems(visit)
    return units


class Result:
    """The contents of one result file.

    Attributes (arrays are numpy arrays; element and tip numbers in the file are 1-based):

    * ``path``, ``title``, ``complete`` (False when the run did not finish),
      ``length_unit``, ``stress_unit``, ``time_unit`` ('' without a time axis);
    * ``provenance``: every root attribute (strings decoded): program, version,
      git_commit, created, input_file, the material, the remote stress, ...;
    * ``input_text``: the namelist file the run read, as it was;
    * ``elements``: name -> array, one value per element (x_begin ... ds, dn, state, ...);
    * ``fractures``: a list of dicts (name, first, last: 1-based inclusive element range);
    * ``tips``: name -> array, one value per crack tip (x, y, k1, k2, ...);
    * ``fields``: observation set name -> dict (kind 'grid', 'line' or 'points', nx, ny
      and the arrays x, y, ux, uy, sxx, syy, sxy, near_element);
    * ``history``: the loading history (loads, ds, dn, state shaped (steps, elements),
      ...) or None; ``growth``: the growth records (one per tip per step) or None;
    * ``injection``: the fluid sources (name, fracture_id, x, y, overpressure, rate, start,
      stop; one value per source) or None;
      ``cycle``: an earthquake-cycle run (rows, recorded elements, points, events:
      ddc2d.reader.read_cycle) or None;
    * ``units``: dataset path -> unit ('elements/ds' -> 'm'); ``unit(path)`` reads it;
    * ``codings``: the meaning of every integer code ('/elements/state' -> {0: 'free', ...}).
    """

    def __init__(self, loaded: Loaded, units: dict[str, str]) -> None:
        self.path: Path = loaded["path"]
        self.title: str = loaded["title"]
        self.complete: bool = loaded["complete"]
        self.length_unit: str = loaded["length_unit"]
        self.stress_unit: str = loaded["stress_unit"]
        self.time_unit: str = loaded["time_unit"]
        self.provenance: dict[str, Any] = loaded["attrs"]
        self.input_text: str = loaded["attrs"].get("input_text", "")
        self.elements: Arrays = loaded["elements"]
        self.fractures: list[dict[str, Any]] = loaded["fractures"]
        self.tips: Arrays = {k: v for k, v in loaded["tips"].items() if k != "k_unit"}
        self.fields: dict[str, dict[str, Any]] = loaded["fields"]
        self.history: dict[str, Any] | None = loaded["history"]
        self.growth: dict[str, Any] | None = loaded["growth"]
        self.injection: dict[str, Any] | None = loaded["injection"]
        self.cycle: dict[str, Any] | None = loaded["cycle"]
        self.codings: dict[str, Coding] = loaded["codings"]
        self.units = units
        self._loaded = loaded

    def __getitem__(self, key: str) -> Any:
        """The entry `key` of the reader's dict (ddc2d.reader.load_result), so that the
        functions of ddc2d.plot, written for it, take a Result."""
        return self._loaded[key]

    def __repr__(self) -> str:
        return (f"<ddc2d.Result '{self.path}': {self.elements['ds'].size} elements, "
                f"{self.tips['x'].size} tips, fields {sorted(self.fields)}"
                f"{', history' if self.history is not None else ''}"
                f"{', growth' if self.growth is not None else ''}"
                f"{', cycle' if self.cycle is not None else ''}>")

    def unit(self, path: str) -> str:
        """The unit of a dataset ('elements/ds', 'fields/map/sxx'); '' when it has none."""
        return self.units.get(path.strip("/"), "")

    @overload
    def to_xarray(self, name: None = None) -> "dict[str, xarray.Dataset]": ...

    @overload
    def to_xarray(self, name: str) -> "xarray.Dataset": ...

    def to_xarray(self, name: str | None = None
                  ) -> "xarray.Dataset | dict[str, xarray.Dataset]":
        """An observation set (`name` of /fields) or the loading history ('history') as an
        xarray.Dataset; without a name, a dict of every one of them by name.

        A grid gives 2-D variables on the dimensions (y, x) with the grid lines as
        coordinates; a line or a point set gives 1-D variables along ``point`` (numbered
        from 1) with x and y as coordinates. The history gives ds, dn, state, ... on
        (step, element) and K on (step, tip), steps and elements numbered from 1 as in the
        file, with the loads as coordinates along ``step``; the strengths in force
        (mu_in_force, sf_in_force, tensile_strength_in_force) where the file holds them.
        A path with a time axis has ``time`` as a coordinate along ``step`` too
        (``.swap_dims(step="time")`` puts the steps on it); with fluid sources ``pressure``
        is on (step, element), ``injected_volume`` on step, and slipping_length,
        front_begin, front_end and moment on (step, fracture), the fractures numbered from 1
        with their names as the coordinate ``fracture_name``; with coupled flow (&fluid)
        ``aperture`` and ``flux`` on (step, element), the volumes, ``fluid_efficiency``,
        ``flow_iterations`` and ``flow_residual`` on step. Every variable carries its
        ``units`` attribute."""
        if name is None:
            names = list(self.fields) + ([HISTORY] if self.history is not None else [])
            return {each: self.to_xarray(each) for each in names}
        if name == HISTORY and HISTORY not in self.fields:
            if self.history is None:
                raise KeyError(f"'{self.path}' has no loading history")
            return self._history_dataset()
        if name not in self.fields:
            raise KeyError(f"'{self.path}' has no observation set '{name}' (it has: "
                           f"{', '.join(self.fields) or 'none'})")
        return self._field_dataset(name)

    def _field_dataset(self, name: str) -> "xarray.Dataset":
        import xarray as xr  # only here: reading a file needs no xarray

        field = self.fields[name]
        units = {q: self.unit(f"fields/{name}/{q}") for q in ("x", *FIELD_QUANTITIES)}
        present = [q for q in FIELD_QUANTITIES if q in field]
        coords: dict[str, Any]
        variables: dict[str, Any]
        if field["kind"] == "grid":
            shape = (field["ny"], field["nx"])
            x = np.reshape(field["x"], shape)[0, :]
            y = np.reshape(field["y"], shape)[:, 0]
            coords = {"x": ("x", x, {"units": units["x"]}),
                      "y": ("y", y, {"units": units["x"]})}
            variables = {q: (("y", "x"), np.reshape(field[q], shape), {"units": units[q]})
                         for q in present}
        else:
            x = np.ravel(field["x"])
            coords = {"point": ("point", np.arange(1, x.size + 1)),
                      "x": ("point", x, {"units": units["x"]}),
                      "y": ("point", np.ravel(field["y"]), {"units": units["x"]})}
            variables = {q: ("point", np.ravel(field[q]), {"units": units[q]}) for q in present}
        return xr.Dataset(variables, coords=coords,
                          attrs={"name": name, "kind": field["kind"], "source": str(self.path)})

    def _history_dataset(self) -> "xarray.Dataset":
        import xarray as xr

        history = self.history
        assert history is not None, "to_xarray asks only a result with a history"
        steps, elements = history["ds"].shape
        coords: dict[str, Any] = {"step": ("step", np.arange(1, steps + 1)),
                                  "element": ("element", np.arange(1, elements + 1))}
        for load, values in history["loads"].items():
            coords[load] = ("step", values, {"units": self.unit(f"history/{load}")})
        if "time" in history:
            coords["time"] = ("step", history["time"], {"units": self.unit("history/time")})
        if any(key in history for key in HISTORY_FRACTURE_DATASETS):
            coords["fracture"] = ("fracture", np.arange(1, len(self.fractures) + 1))
            coords["fracture_name"] = ("fracture", [f["name"] for f in self.fractures])
        variables: dict[str, Any] = {}
        for dims, keys in ((("step", "element"),
                            HISTORY_ELEMENT_DATASETS + ("pressure", "aperture", "flux")),
                           (("step", "tip"), HISTORY_TIP_DATASETS),
                           (("step", "fracture"), HISTORY_FRACTURE_DATASETS),
                           (("step",), HISTORY_STEP_VARIABLES)):
            for key in keys:
                if key in history and np.ndim(history[key]) == len(dims):
                    variables[key] = (dims, history[key],
                                      {"units": self.unit(f"history/{key}")})
        return xr.Dataset(variables, coords=coords,
                          attrs={"name": HISTORY, "source": str(self.path)})
