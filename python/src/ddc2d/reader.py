"""Read ddc2d result files (HDF5, docs/output-reference.md): the one reader of the package.

Used by ddc2d.open_result, ``ddc2d-plot``, ``collect-sweep``, ``compare-twodd``,
``ddc2d-benchmark`` and the tests. It knows

* how strings come back from h5py (blank- or NUL-padded fixed-length bytes: ``decode``);
* the codings of the integer datasets: ``load_result`` returns those the file carries
  (``codings``: the ``coding`` attribute of every dataset that has one, read by
  ``parse_coding``; ``coding_of`` picks one); ``STATE_NAMES``, ``CONDITION_NAMES`` and their
  inverses ``STATE_CODES``, ``CONDITION_CODES`` are what ddc2d writes, for files without the
  attribute and for tools that read single datasets;
* the groups of a result: ``load_result`` reads a whole file, ``read_elements``,
  ``read_fractures``, ``read_tips``, ``read_fields``, ``read_history``,
  ``read_injection``, ``read_growth``, ``read_cycle``, ``read_solver`` and ``read_sweep``
  one group of an open file; ``is_complete`` tells a finished file;
* the tie rule of every default that picks "the largest" or "the first": ``index_of_extreme``
  and ``is_tie`` (values within ``TIE_RTOL`` = 1e-9 relative count as equal, the lowest index
  wins), so that a choice never depends on last-bit rounding (symmetric models, other BLAS
  kernels on other CPUs).
"""

import os
import re
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Protocol

import h5py
import numpy as np
import numpy.typing as npt

#: A file name as the functions take it.
FilePath = str | os.PathLike[str]
#: A loaded result (load_result): plain Python and numpy objects by key.
Loaded = dict[str, Any]
#: Arrays by dataset name.
Arrays = dict[str, np.ndarray]
#: The meaning of each integer code of a dataset (code -> name).
Coding = dict[int, str]


class ResultData(Protocol):
    """What the figures and tools read a result through, ``result["elements"]``, ...: a
    ddc2d.Result or the dict of load_result."""

    def __getitem__(self, key: str, /) -> Any: ...

#: Element states as coded in /elements/state (and /history/state).
STATE_NAMES = {0: "free", 1: "stick", 2: "slip", 3: "open"}
STATE_CODES = {name: code for code, name in STATE_NAMES.items()}
#: Element conditions as coded in /elements/condition (1-4 are TWODD's KODE 1-4).
CONDITION_NAMES = {1: "traction", 2: "displacement", 3: "mixed_us_sn", 4: "mixed_ss_un",
                   5: "contact", 6: "prescribed_dd", 7: "rate_state"}
CONDITION_CODES = {name: code for code, name in CONDITION_NAMES.items()}

#: Codings assumed for a file whose dataset lacks its `coding` attribute, by dataset path.
DEFAULT_CODINGS = {"/elements/state": STATE_NAMES, "/elements/condition": CONDITION_NAMES}

#: /elements datasets a result must have (the others are read when present).
ELEMENT_DATASETS = ("x_begin", "y_begin", "x_end", "y_end", "ds", "dn")
#: /tips datasets, all present when the group is.
TIP_DATASETS = ("x", "y", "fracture_id", "element", "k1", "k2")
# The /history and /growth datasets are the columns of ddc2d's record lists
# (src/model/records.f90); the CTest architecture fails when these lists disagree with them.
#: Load quantities a /history may hold, in the order ddc2d writes them.
HISTORY_LOADS = ("sxx", "syy", "sxy", "dsxx_dy", "dsyy_dy", "dsxy_dy", "p0")
#: /history datasets of every loading history: DDs and states (steps, elements), leg_steps.
HISTORY_DATASETS = ("ds", "dn", "state", "leg_steps")
#: Per-step /history datasets beyond the loads, DDs and states (read when present).
HISTORY_STEP_DATASETS = ("shear_traction", "normal_traction", "mu_in_force", "sf_in_force",
                         "tensile_strength_in_force", "k1", "k2", "pivots",
                         "newton_iterations", "certificate_min_z", "certificate_min_w",
                         "certificate_max_complementarity", "equilibrium_residual")
#: Per-step /history strings (read when present, decoded).
HISTORY_STRING_DATASETS = ("method", "fallback")
#: /history datasets of fracture growth along a load path, read when present
#: (docs/fracture-growth.md#output).
HISTORY_GROWTH_DATASETS = ("element_count", "grown_length", "tip_fracture_id", "tip_end")
#: /history datasets of a load path with a time axis (time) and of fluid sources
#: (docs/injection.md#output: pressure per element; injected volume per step; slipping
#: length, front positions and moment per fracture), read when present.
HISTORY_FLOW_DATASETS = ("time", "pressure", "injected_volume", "slipping_length",
                         "front_begin", "front_end", "moment")
#: /history datasets of flow coupled to the opening (&fluid; docs/fluid-driven-fractures.md
#: #output): aperture and flux per element; stored and leaked volume, fluid efficiency,
#: iterations and unbalanced volume of the coupled solve per step; read when present.
HISTORY_COUPLED_DATASETS = ("aperture", "flux", "stored_volume", "leaked_volume",
                            "fluid_efficiency", "flow_iterations", "flow_residual")
#: /injection datasets (docs/output-reference.md), one value per fluid source: overpressure
#: NaN for a rate source, rate NaN for a pressure source, start and stop NaN where not given.
INJECTION_DATASETS = ("fracture_id", "x", "y", "overpressure", "rate", "start", "stop")
#: /injection attributes of coupled flow (&fluid; with fluid-driven growth the toughness),
#: read into ``fluid`` where present.
FLUID_ATTRIBUTES = ("viscosity", "compressibility", "leak_off_coefficient", "toughness")
#: /growth datasets (fracture growth; docs/fracture-growth.md#output), one value per record
#: (tip and step).
GROWTH_DATASETS = ("step", "fracture_id", "end", "x", "y", "k1", "k2", "k_eq", "mts_angle",
                   "angle", "corrections", "k2_after", "length", "reason")
#: /growth datasets of fracture growth along a load path only, one value per record.
GROWTH_PATH_DATASETS = ("load_step",)
#: /growth datasets of the work criterion only, one value per record.
GROWTH_WORK_DATASETS = ("efficiency", "slip_share")
#: /growth/trials datasets of the work criterion, one value per trial kink.
GROWTH_TRIAL_DATASETS = ("trial_step", "trial_record", "trial_angle", "trial_efficiency",
                         "trial_state")
#: Datasets of /growth/initiations (&initiation), one value per new fracture started.
INITIATION_DATASETS = ("kind", "step", "load_step", "fracture_id", "parent", "element", "flaw",
                       "side", "x", "y", "probe_x", "probe_y", "tension", "angle")
#: Datasets of /growth/initiations/flaw_trials (criterion 'work' with flaw points), one value
#: per trial of a flaw's first crack.
FLAW_TRIAL_DATASETS = ("step", "flaw", "angle", "efficiency", "state")
#: /cycle datasets of an earthquake-cycle run (docs/output-reference.md#cycle): of every row
#: (time, largest slip rate and its element), of every row and recorded element (rows,
#: elements), of every row and observation point (rows, points), of every event, of the
#: recorded elements and of the points.
CYCLE_ROW_DATASETS = ("time", "max_slip_rate", "max_rate_element")
CYCLE_PROFILE_DATASETS = ("slip", "slip_rate", "shear_traction", "normal_traction", "state")
CYCLE_POINT_DATASETS = ("ux", "uy", "vx", "vy")
CYCLE_EVENT_DATASETS = ("event_start", "event_end", "event_element", "event_x", "event_y",
                        "event_peak_rate", "event_max_slip", "event_moment", "event_slip")
CYCLE_FIXED_DATASETS = ("elements", "profile", "distance", "point_x", "point_y")
#: Phases timed in /solver/seconds.
SOLVER_PHASES = ("assembly", "factorization", "lcp", "fields", "output", "total")

#: Relative tolerance of the tie rule (index_of_extreme, is_tie).
TIE_RTOL = 1e-9


class ResultError(Exception):
    """The result file is missing, unreadable or not laid out as a ddc2d result."""


# --------------------------------------------------------------------------- ties


def index_of_extreme(values: npt.ArrayLike, kind: str = "max", rtol: float = TIE_RTOL) -> int:
    """Index of the largest (kind 'max') or smallest ('min') value, defined under ties.

    Returns the lowest index among the values within ``rtol * |extreme|`` of the extreme
    (an infinite extreme ties only with itself), so that two values equal but for
    rounding (the two centre elements of a symmetric fault) always give the same answer.
    NaN values are ignored. ``values`` is flattened (C order), as ``np.argmax`` does.
    Raises ValueError when there is no value that is not NaN, or for another kind.
    """
    if kind not in ("max", "min"):
        raise ValueError(f"index_of_extreme: kind must be 'max' or 'min', not {kind!r}")
    values = np.asarray(values, dtype=float).ravel()
    present = values[~np.isnan(values)]
    if present.size == 0:
        raise ValueError("index_of_extreme: no value that is not NaN")
    extreme = present.max() if kind == "max" else present.min()
    if np.isinf(extreme):
        near = values == extreme
    else:
        near = np.abs(values - extreme) <= rtol * abs(extreme)
    return int(np.flatnonzero(near)[0])


def is_tie(a: float, b: float, scale: float | None = None, rtol: float = TIE_RTOL) -> bool:
    """True when a and b are equal under the tie rule: ``|a - b| <= rtol * scale``, with
    ``scale`` the larger of |a| and |b| unless given (e.g. the magnitude of the data that
    a and b are compared within)."""
    if scale is None:
        scale = max(abs(a), abs(b))
    return abs(a - b) <= rtol * scale


# --------------------------------------------------------------------------- strings


def decode(value: Any) -> str:
    """Return an HDF5 string value (bytes, numpy bytes/str, 0-d or 1-element array) as str.

    Strings written from Fortran come back from h5py as blank- or NUL-padded bytes; an
    array of several strings comes back joined by blanks.
    """
    if isinstance(value, np.ndarray):
        if value.size != 1:
            return " ".join(decode(v) for v in value.ravel())
        value = value.ravel()[0]
    if isinstance(value, (bytes, np.bytes_)):
        value = bytes(value).decode("utf-8", errors="replace")
    return str(value).rstrip("\x00 ").strip()


def is_text(value: Any) -> bool:
    """True for an attribute value that is a string (or an array of strings)."""
    return isinstance(value, (bytes, np.bytes_, str)) or (
        isinstance(value, np.ndarray) and value.dtype.kind in "SUO")


def decoded_attrs(attrs: Mapping[str, Any]) -> dict[str, Any]:
    """The attributes of an HDF5 object as a dict, strings decoded, numbers as stored."""
    return {key: decode(value) if is_text(value) else value for key, value in attrs.items()}


def attr_text(attrs: Mapping[str, Any], name: str, default: str = "") -> str:
    """A string attribute as str, or `default` when absent."""
    return decode(attrs[name]) if name in attrs else default


def attr_int(attrs: Mapping[str, Any], name: str, default: int) -> int:
    """An integer attribute (scalar or 1-element array) as int, or `default` when absent."""
    if name not in attrs:
        return default
    return int(np.asarray(attrs[name]).ravel()[0])


def units_of(dataset: h5py.Dataset) -> str:
    """The `units` attribute of a dataset as str ('' when it has none)."""
    return attr_text(dataset.attrs, "units")


def parse_coding(text: Any) -> Coding:
    """A `coding` attribute ('0 free (TWODD-style condition), 1 stick, ...') as a dict
    code -> name (the first word after each code)."""
    return {int(code): name for code, name in re.findall(r"(\d+) ([A-Za-z_]+)", decode(text))}


def read_codings(handle: h5py.Group) -> dict[str, Coding]:
    """The `coding` attribute of every dataset of an open file that has one, parsed
    (parse_coding), by dataset path ('/elements/state', '/fields/map/near_element', ...);
    DEFAULT_CODINGS for the datasets that are there without one."""
    codings: dict[str, Coding] = {}

    def visit(name: str, item: Any) -> None:
        if isinstance(item, h5py.Dataset):
            if "coding" in item.attrs:
                codings["/" + name] = parse_coding(item.attrs["coding"])
            elif "/" + name in DEFAULT_CODINGS:
                codings["/" + name] = dict(DEFAULT_CODINGS["/" + name])

    handle.visititems(visit)
    return codings


def coding_of(result: ResultData, path: str, default: Coding | None = None) -> Coding:
    """The coding (code -> name) of the dataset `path` of a loaded result: the file's, else
    DEFAULT_CODINGS's, else `default` (an empty dict when None)."""
    found = result["codings"].get(path, DEFAULT_CODINGS.get(path, default))
    return dict(found or {})


def code_of(coding: Coding, name: str) -> int:
    """The code of `name` in a coding (code -> name); KeyError naming the codes known."""
    for code, known in coding.items():
        if known == name:
            return code
    raise KeyError(f"no code for '{name}' in the coding {coding}")


def is_complete(attrs: Mapping[str, Any], when_missing: bool = False) -> bool:
    """True when the root attributes mark the file complete (`complete` = 1, written last
    by ddc2d); `when_missing` is the answer for a file without the attribute."""
    return attr_int(attrs, "complete", 1 if when_missing else 0) == 1


# --------------------------------------------------------------------------- whole file


def load_result(path: FilePath) -> Loaded:
    """Read a ddc2d result file into plain Python / numpy objects.

    Returns a dict with keys ``path``, ``attrs`` (root attributes; strings decoded),
    ``length_unit``, ``stress_unit``, ``title``, ``complete`` (True unless the root
    attribute `complete` says otherwise), ``elements`` (dict name -> 1-D array),
    ``fractures`` (list of dicts name / first / last / label, 1-based inclusive element
    range), ``fields`` (dict name -> dict with ``kind``, ``nx``, ``ny`` and the arrays),
    ``tips`` (dict of 1-D arrays x, y, fracture_id, element, k1, k2 and ``k_unit``; empty
    arrays without /tips), ``remote_stress`` ((sxx, syy, sxy) or None),
    ``remote_stress_gradient`` ((dsxx_dy, dsyy_dy, dsxy_dy)) and ``pore_fluid`` ((p0,
    dp_dy)), zeros when the file predates them, ``time_unit`` ('' without a time axis),
    ``codings`` (read_codings), ``history`` (see read_history; None without /history),
    ``injection`` (see read_injection; None without fluid sources), ``growth`` (see
    read_growth; None without /growth) and ``cycle`` (see read_cycle; None without /cycle).
    Raises ResultError with a message naming the file and the problem.
    """
    path = Path(path)
    if not path.exists():
        raise ResultError(f"cannot open '{path}': no such file")
    if path.is_dir():
        raise ResultError(f"cannot open '{path}': it is a folder, not a result file")
    try:
        handle = h5py.File(path, "r")
    except OSError as exc:
        raise ResultError(f"cannot read '{path}': not a readable HDF5 file ({exc})") from exc
    try:
        with handle:
            return _read_open_file(path, handle)
    except ResultError:
        raise
    except (OSError, KeyError, ValueError, TypeError, IndexError) as exc:
        raise ResultError(f"cannot read '{path}': damaged or unexpected content ({exc})") from exc


def _read_open_file(path: Path, handle: h5py.File) -> Loaded:
    elements = read_elements(path, handle)
    count = elements["ds"].size
    if "state" not in elements:
        elements["state"] = np.zeros(count, dtype=int)
    return {
        "path": path,
        "attrs": decoded_attrs(handle.attrs),
        "title": attr_text(handle.attrs, "title"),
        "length_unit": attr_text(handle.attrs, "length_unit"),
        "stress_unit": attr_text(handle.attrs, "stress_unit"),
        "time_unit": attr_text(handle.attrs, "time_unit"),
        "complete": is_complete(handle.attrs, when_missing=True),
        "elements": elements,
        "fractures": read_fractures(path, handle, elements),
        "fields": read_fields(handle),
        "tips": read_tips(path, handle),
        "remote_stress": read_remote_stress(path, handle),
        "remote_stress_gradient": read_root_reals(path, handle, "remote_stress_gradient", 3),
        "pore_fluid": read_root_reals(path, handle, "pore_fluid", 2),
        "codings": read_codings(handle),
        "history": read_history(path, handle, count),
        "injection": read_injection(path, handle),
        "growth": read_growth(path, handle),
        "cycle": read_cycle(path, handle),
        "body": read_body(path, handle),
    }


# --------------------------------------------------------------------------- groups


def read_elements(path: FilePath, handle: h5py.Group) -> Arrays:
    """Every dataset of /elements as a 1-D array (dict name -> array); checks that the
    datasets of ELEMENT_DATASETS are there with one value per element."""
    if "elements" not in handle or not isinstance(handle["elements"], h5py.Group):
        raise ResultError(f"'{path}' has no /elements group: not a ddc2d result file")
    elements = {key: np.asarray(item[()]).ravel() for key, item in handle["elements"].items()
                if isinstance(item, h5py.Dataset)}
    for key in ELEMENT_DATASETS:
        if key not in elements:
            raise ResultError(f"'{path}' lacks /elements/{key}: not a ddc2d result file")
    count = elements["ds"].size
    for key in ELEMENT_DATASETS:
        if elements[key].size != count:
            raise ResultError(
                f"'{path}': /elements/{key} has {elements[key].size} values, "
                f"/elements/ds has {count}"
            )
    return elements


def read_fractures(path: FilePath, handle: h5py.Group, elements: Arrays) -> list[dict[str, Any]]:
    """Fractures from /fractures, or (if absent) from runs of equal /elements/fracture_id:
    a list of dicts ``name``, ``first``, ``last`` (1-based, inclusive) and ``label`` (the
    name made usable in file names, unique)."""
    count = elements["ds"].size
    fractures: list[dict[str, Any]] = []
    if "fractures" in handle:
        group = handle["fractures"]
        first = np.asarray(group["first_element"][()]).ravel().astype(int)
        last = np.asarray(group["last_element"][()]).ravel().astype(int)
        if "name" in group:
            names = [decode(v) for v in np.asarray(group["name"][()]).ravel()]
        else:
            names = [""] * first.size
        if not (first.size == last.size == len(names)):
            raise ResultError(f"'{path}': /fractures datasets differ in length")
        for index, (name, lo, hi) in enumerate(zip(names, first, last), start=1):
            if not 1 <= lo <= hi <= count:
                raise ResultError(
                    f"'{path}': fracture {index} has element range {lo}..{hi} "
                    f"outside 1..{count}"
                )
            fractures.append({"name": name, "first": int(lo), "last": int(hi)})
    elif count > 0:
        ids = elements.get("fracture_id", np.ones(count, dtype=int))
        starts = [0] + [i for i in range(1, count) if ids[i] != ids[i - 1]]
        ends = starts[1:] + [count]
        for lo, hi in zip(starts, ends):
            fractures.append({"name": "", "first": lo + 1, "last": hi})
    used = set()
    for index, fracture in enumerate(fractures, start=1):
        label = re.sub(r"[^A-Za-z0-9_.-]+", "_", fracture["name"]).strip("_.") or f"{index}"
        if label in used:
            label = f"{label}_{index}"
        used.add(label)
        fracture["label"] = label
    return fractures


def read_fields(handle: h5py.Group) -> dict[str, dict[str, Any]]:
    """Every group of /fields as a dict name -> {kind, nx, ny, ``codings`` (dataset name ->
    its parsed `coding` attribute: near_element) and each dataset as an array}; empty
    without /fields."""
    fields: dict[str, dict[str, Any]] = {}
    if "fields" not in handle:
        return fields
    for name, group in handle["fields"].items():
        if not isinstance(group, h5py.Group):
            continue
        field: dict[str, Any] = {
            "kind": attr_text(group.attrs, "kind"),
            "nx": attr_int(group.attrs, "nx", 0),
            "ny": attr_int(group.attrs, "ny", 0),
            "codings": {},
        }
        for key, item in group.items():
            if isinstance(item, h5py.Dataset):
                field[key] = np.asarray(item[()])
                if "coding" in item.attrs:
                    field["codings"][key] = parse_coding(item.attrs["coding"])
        fields[name] = field
    return fields


def read_tips(path: FilePath, handle: h5py.Group) -> dict[str, Any]:
    """The /tips datasets as 1-D arrays (empty arrays without the group) and ``k_unit``,
    the unit of K (the `units` of /tips/k1, else built from the root units)."""
    stress = attr_text(handle.attrs, "stress_unit")
    length = attr_text(handle.attrs, "length_unit")
    tips: dict[str, Any] = {key: np.zeros(0) for key in TIP_DATASETS}
    tips["k_unit"] = f"{stress} {length}^0.5".strip() if stress or length else ""
    if "tips" not in handle:
        return tips
    group = handle["tips"]
    for key in TIP_DATASETS:
        if key not in group:
            raise ResultError(f"'{path}' lacks /tips/{key}")
        tips[key] = np.asarray(group[key][()]).ravel()
        if tips[key].size != tips["x"].size:
            raise ResultError(f"'{path}': /tips datasets differ in length")
    if "units" in group["k1"].attrs:
        tips["k_unit"] = units_of(group["k1"])
    return tips


def read_remote_stress(path: FilePath, handle: h5py.Group) -> tuple[float, ...] | None:
    """The root attribute remote_stress as (sxx, syy, sxy), or None when absent."""
    if "remote_stress" not in handle.attrs:
        return None
    return read_root_reals(path, handle, "remote_stress", 3)


def read_root_reals(path: FilePath, handle: h5py.Group, name: str, size: int) -> tuple[float, ...]:
    """A root attribute of `size` reals as a tuple; zeros when absent (files written
    before ddc2d stored it, e.g. remote_stress_gradient and pore_fluid)."""
    if name not in handle.attrs:
        return (0.0,) * size
    values = np.asarray(handle.attrs[name], dtype=float).ravel()
    if values.size != size:
        raise ResultError(f"'{path}': root attribute {name} has {values.size} values, "
                          f"expected {size}")
    return tuple(float(v) for v in values)


def read_history(path: FilePath, handle: h5py.Group, count: int) -> dict[str, Any] | None:
    """/history as a dict (``loads``: name -> (steps,), ``ds``, ``dn``, ``state``:
    (steps, elements), ``leg_steps``; when the file has them, ``shear_traction``,
    ``normal_traction`` (steps, elements), ``k1``, ``k2`` (steps, tips), ``pivots``,
    ``newton_iterations``, ``certificate_min_z``, ``certificate_min_w``,
    ``certificate_max_complementarity``, ``equilibrium_residual`` (steps,), the strengths in
    force ``mu_in_force``, ``sf_in_force``, ``tensile_strength_in_force`` (steps, elements)
    and ``method``,
    ``fallback``: one str per step; with
    fracture growth ``element_count`` (steps,), ``grown_length`` (steps, tips),
    ``tip_fracture_id``, ``tip_end`` (tips,), and element rows NaN (state -1) before an
    element was made; with a time axis ``time`` (steps,) and with fluid sources
    ``pressure`` (steps, elements), ``injected_volume`` (steps,), ``slipping_length``,
    ``front_begin``, ``front_end``, ``moment`` (steps, fractures); with coupled flow
    ``aperture``, ``flux`` (steps, elements), ``stored_volume``, ``leaked_volume``,
    ``fluid_efficiency``, ``flow_iterations``, ``flow_residual`` (steps,)), or None when the
    file has no loading history."""
    if "history" not in handle:
        return None
    group = handle["history"]
    history: dict[str, Any] = {
        "loads": {k: np.asarray(group[k][()]) for k in HISTORY_LOADS if k in group}}
    for key in HISTORY_DATASETS:
        history[key] = np.asarray(group[key][()])
    for key in (HISTORY_STEP_DATASETS + HISTORY_GROWTH_DATASETS + HISTORY_FLOW_DATASETS
                + HISTORY_COUPLED_DATASETS):
        if key in group:
            history[key] = np.asarray(group[key][()])
    for key in HISTORY_STRING_DATASETS:
        if key in group:
            history[key] = [decode(v) for v in group[key][()]]
    if history["ds"].ndim != 2 or history["ds"].shape[1] != count:
        raise ResultError(f"'{path}': /history/ds has shape {history['ds'].shape}, "
                          f"expected (steps, {count})")
    return history


def read_injection(path: FilePath, handle: h5py.Group) -> dict[str, Any] | None:
    """/injection, the fluid sources, as a dict: ``name`` (a list of str) and the 1-D arrays
    of INJECTION_DATASETS, one value per source (``fracture_id`` 1-based), and ``fluid``,
    the attributes of FLUID_ATTRIBUTES the file holds (a dict, empty without &fluid); None
    when the file has no fluid sources."""
    if "injection" not in handle:
        return None
    group = handle["injection"]
    sources: dict[str, Any] = {"name": [decode(v) for v in np.ravel(group["name"][()])]}
    for key in INJECTION_DATASETS:
        sources[key] = np.asarray(group[key][()]).ravel()
        if sources[key].size != len(sources["name"]):
            raise ResultError(f"'{path}': /injection datasets differ in length")
    # Coupled flow (&fluid): the fluid, and a hydraulic fracture's toughness.
    sources["fluid"] = {key: float(np.ravel(group.attrs[key])[0]) for key in FLUID_ATTRIBUTES
                        if key in group.attrs}
    return sources


BODY_DATASETS = ("x", "y", "side", "us", "un", "ts", "tn", "side_force_x", "side_force_y",
                 "vertex_x", "vertex_y")


def read_body(path: FilePath, handle: h5py.Group) -> dict[str, Any] | None:
    """/body, the boundary of a finite body (docs/finite-bodies.md#output), as a dict of
    1-D arrays (BODY_DATASETS); None when the model has no body."""
    if "body" not in handle:
        return None
    group = handle["body"]
    missing = [key for key in BODY_DATASETS if key not in group]
    if missing:
        raise ResultError(f"'{path}': /body lacks {', '.join(missing)}")
    return {key: np.asarray(group[key][()]).ravel() for key in BODY_DATASETS}


def read_growth(path: FilePath, handle: h5py.Group) -> dict[str, Any] | None:
    """/growth of a fracture growth run as a dict: every dataset of GROWTH_DATASETS (1-D,
    one value per record: one record per tip per step), ``attrs`` (strings decoded: toughness,
    end_reason, ...) and ``reasons`` (code -> name, from the attribute reason_coding); under
    the work criterion also ``efficiency``, ``slip_share`` and ``trials`` (dict of
    GROWTH_TRIAL_DATASETS, one value per trial kink), and with flaw points ``flaw_trials``
    (dict of FLAW_TRIAL_DATASETS, one value per trial of a flaw's first crack) and
    ``flaw_starts`` (``flaw``, ``step`` and ``angle`` of every flaw that started, from
    /growth/initiations); with &initiation
    ``initiations`` (dict of INITIATION_DATASETS, one value per new fracture, and ``attrs``:
    its settings and, when a check started nothing, ``largest_tension`` with its
    ``largest_tension_x``, ``_y`` and ``_step``); None when the file has no /growth."""
    if "growth" not in handle:
        return None
    group = handle["growth"]
    growth: dict[str, Any] = {}
    for key in GROWTH_DATASETS + GROWTH_PATH_DATASETS + GROWTH_WORK_DATASETS:
        if key not in group:
            if key not in GROWTH_DATASETS:
                continue
            raise ResultError(f"'{path}' lacks /growth/{key}")
        growth[key] = np.asarray(group[key][()]).ravel()
        if growth[key].size != growth["step"].size:
            raise ResultError(f"'{path}': /growth datasets differ in length")
    if "trials" in group:
        growth["trials"] = {key: np.asarray(group["trials"][key][()]).ravel()
                            for key in GROWTH_TRIAL_DATASETS}
    if "initiations" in group:
        rows = group["initiations"]
        growth["initiations"] = {key: np.asarray(rows[key][()]).ravel()
                                 for key in INITIATION_DATASETS}
        growth["initiations"]["attrs"] = decoded_attrs(rows.attrs)
    if "initiations/flaw_trials" in group:
        trials = group["initiations/flaw_trials"]
        growth["flaw_trials"] = {key: np.asarray(trials[key][()]).ravel()
                                 for key in FLAW_TRIAL_DATASETS}
        rows = group["initiations"]
        flaws = np.asarray(rows["kind"][()]).ravel() == 2
        growth["flaw_starts"] = {key: np.asarray(rows[key][()]).ravel()[flaws]
                                 for key in ("flaw", "step", "angle")}
    growth["attrs"] = decoded_attrs(group.attrs)
    growth["reasons"] = parse_coding(group.attrs.get("reason_coding", ""))
    return growth


def read_cycle(path: FilePath, handle: h5py.Group) -> dict[str, Any] | None:
    """/cycle of an earthquake-cycle run as a dict: every dataset of the CYCLE_ lists (rows
    first: ``slip`` (rows, recorded elements), ``ux`` (rows, points), ``event_slip``
    (events, recorded elements)), ``attrs`` (strings decoded: state_law, end_reason,
    time_unit, ...) and ``resume`` (the datasets and attributes of /cycle/resume); None when
    the file has no /cycle."""
    if "cycle" not in handle:
        return None
    group = handle["cycle"]
    cycle: dict[str, Any] = {"attrs": decoded_attrs(group.attrs)}
    for key in (CYCLE_ROW_DATASETS + CYCLE_PROFILE_DATASETS + CYCLE_POINT_DATASETS
                + CYCLE_EVENT_DATASETS + CYCLE_FIXED_DATASETS):
        if key not in group:
            raise ResultError(f"'{path}' lacks /cycle/{key}")
        cycle[key] = np.asarray(group[key][()])
    rows = cycle["time"].size
    for key in CYCLE_PROFILE_DATASETS:
        if cycle[key].shape != (rows, cycle["profile"].size):
            raise ResultError(f"'{path}': /cycle/{key} has shape {cycle[key].shape}, "
                              f"expected ({rows}, {cycle['profile'].size})")
    resume = group["resume"]
    cycle["resume"] = {key: np.asarray(item[()]) for key, item in resume.items()}
    cycle["resume"].update(decoded_attrs(resume.attrs))
    return cycle


def read_solver(handle: h5py.Group) -> dict[str, Any]:
    """/solver: ``attrs`` (strings decoded) and ``seconds`` (phase -> float, every phase of
    SOLVER_PHASES from /solver/seconds)."""
    group = handle["solver"]
    return {"attrs": decoded_attrs(group.attrs),
            "seconds": {phase: float(group["seconds"][phase][()]) for phase in SOLVER_PHASES}}


def read_sweep(handle: h5py.Group) -> dict[str, Any] | None:
    """/sweep of a sweep task: ``task``, ``tasks`` and ``parameters`` (dict name -> value,
    in &sweep order), or None when the file is not a sweep task."""
    if "sweep" not in handle:
        return None
    attrs = handle["sweep"].attrs
    names = [name.strip() for name in decode(attrs["parameters"]).split(",")]
    return {"task": int(attrs["task"]), "tasks": int(attrs["tasks"]),
            "parameters": {name: float(attrs[name]) for name in names}}
