"""Collect the outputs of a ddc2d parameter sweep into one summary table, and plot it.

    collect-sweep DIR [--plot RESULT --against PARAM] [--format png|pdf|svg]

Reads every complete task output ``DIR/<stem>_task<K>.h5`` (root attribute complete = 1)
and writes ``DIR/<stem>_summary.csv`` and ``DIR/<stem>_summary.h5`` (one dataset per
column, its unit in a ``units`` attribute), one row per task, ordered by task: ``task``,
the swept parameters (from the /sweep group, in &sweep order) and the results

* ``peak_slip``: max |ds| over the elements [length unit];
* ``peak_opening``: max opening over the elements, 0 when none opens [length unit];
* ``stick``, ``slip``, ``open``: number of elements in each state;
* ``max_abs_k1``, ``max_abs_k2``: max |K_I|, |K_II| over the crack tips (NaN without tips);

and, when the tasks grow fractures (a ``&growth`` group; the columns of the first task's
file name the fractures):

* ``growth_steps``: steps in which a tip grew; ``growth_start``: the load step (1-based, 1
  without a load path) in which a tip first grew or a new fracture started, 0 when none did;
  ``end_reason``: ``arrested``, ``step_limit`` or ``failed``;
* ``grown_length_<fracture>``: length grown at both tips of each fracture [length unit];
* ``k_eq_ratio``: the largest K_eq / toughness of the last step's records (below 1: every
  tip left is subcritical);

and, when the tasks have fluid sources (&injection), at the path's last step:

* ``injected_volume``: the volume the sources let in [length^2];
* ``slipping_length_<fracture>``, ``front_half_length_<fracture>`` (NaN where nothing
  slips) and ``moment_<fracture>`` of every fracture [length, length, stress length^2].

The CSV header gives each column's unit in brackets as the tips table of ddc2d-plot does
(``peak_slip [m]``, ``remote_angle [deg]``, ``max_abs_k1 [MPa m^0.5]``; none for counts and
dimensionless parameters such as mu), from the root attributes length_unit, stress_unit
and time_unit of the task files; the plot's axes are labelled the same way.

Tasks without a complete output are listed on standard error (run the sweep again: only
they run). With --plot, also writes ``DIR/<stem>_<RESULT>_vs_<PARAM>.<fmt>``: RESULT against
PARAM, one line per combination of the other parameters. Exit status 0 on success, 2 when
DIR holds no sweep output or RESULT / PARAM is not a column.
"""

import argparse
import csv
import re
import sys
from pathlib import Path

import h5py
import numpy as np

from .files import atomic_path
from .reader import (
    STATE_CODES,
    ResultError,
    attr_text,
    is_complete,
    read_elements,
    read_fractures,
    read_growth,
    read_history,
    read_sweep,
    read_tips,
)

RESULTS = ("peak_slip", "peak_opening", "stick", "slip", "open", "max_abs_k1", "max_abs_k2")
#: Columns of a growth run besides its grown_length_<fracture> (see growth_summary)
GROWTH_RESULTS = ("growth_steps", "growth_start", "end_reason", "k_eq_ratio")
GROWN_LENGTH = "grown_length_"
#: Columns of a task with fluid sources besides its per-fracture ones (injection_summary)
INJECTION_RESULTS = ("injected_volume",)
#: The per-fracture columns of a task with fluid sources, <prefix><fracture>: the /history
#: dataset of each prefix and the unit kind of its column
INJECTION_FRACTURE_RESULTS = {"slipping_length_": ("slipping_length", "length"),
                              "front_half_length_": (None, "length"),
                              "moment_": ("moment", "moment")}
TASK_FILE = re.compile(r"(?P<stem>.+)_task(?P<task>\d+)\.h5$")
#: Unit of each column: 'length', 'stress', 'k' (stress length^0.5), 'stiffness' (stress /
#: length), 'area' (length^2), 'moment' (stress length^2), 'diffusivity' (length^2 / time),
#: 'transmissivity' (length^3 / (stress time)), a literal unit, or '' (counts, dimensionless
#: parameters). Per-fracture and per-source parameters fracture(K)%<name>,
#: injection(K)%<name> take the unit of <name>, the laws of new elements new_<name> that of
#: <name>.
COLUMN_UNITS = {"peak_slip": "length", "peak_opening": "length", "max_abs_k1": "k",
                "max_abs_k2": "k", "youngs_modulus": "stress", "sxx": "stress",
                "syy": "stress", "sxy": "stress", "remote_s1": "stress",
                "remote_s3": "stress", "remote_angle": "deg", "sf": "stress",
                "pressure": "stress", "overpressure": "stress", "rate": "diffusivity",
                "diffusivity": "diffusivity", "transmissivity": "transmissivity",
                "injected_volume": "area", "tensile_strength": "stress",
                "sf_residual": "stress", "slip_weakening_distance": "length",
                "opening_weakening_distance": "length", "shear_stiffness": "stiffness",
                "normal_stiffness": "stiffness"}


def column_units(columns, length_unit, stress_unit, time_unit=""):
    """The unit of every column (see COLUMN_UNITS), '' for none."""
    named = {"length": length_unit, "stress": stress_unit,
             "k": f"{stress_unit} {length_unit}^0.5".strip(), "area": f"{length_unit}^2",
             "moment": f"{stress_unit} {length_unit}^2",
             "stiffness": f"{stress_unit}/{length_unit}",
             "diffusivity": f"{length_unit}^2/{time_unit}",
             "transmissivity": f"{length_unit}^3/({stress_unit} {time_unit})"}
    units = {}
    for column in columns:
        name = column.split("%")[-1]
        kind = COLUMN_UNITS.get(name.removeprefix("new_"), "")
        if column.startswith(GROWN_LENGTH):
            kind = "length"
        for prefix, (_, unit) in INJECTION_FRACTURE_RESULTS.items():
            if column.startswith(prefix):
                kind = unit
        units[column] = named.get(kind, kind)
    return units


def labelled(column, units):
    """'peak_slip [m]', or the bare name for a column without a unit."""
    return f"{column} [{units[column]}]" if units[column] else column


def read_task(path):
    """(task, tasks, {parameter: value}, {result: value}, (length unit, stress unit)) of
    one complete output, or None."""
    try:
        with h5py.File(path, "r") as f:
            sweep = read_sweep(f) if is_complete(f.attrs) else None
            if sweep is None:
                return None
            elements = read_elements(path, f)
            results = summary(elements, read_tips(path, f))
            growth = read_growth(path, f)
            fractures = read_fractures(path, f, elements)
            if growth is not None:
                results.update(growth_summary(growth, fractures))
            if "injection" in f:
                history = read_history(path, f, elements["ds"].size)
                results.update(injection_summary(history, fractures))
            units = (attr_text(f.attrs, "length_unit"), attr_text(f.attrs, "stress_unit"),
                     attr_text(f.attrs, "time_unit"))
            return sweep["task"], sweep["tasks"], sweep["parameters"], results, units
    except (OSError, KeyError, ResultError):
        return None


def summary(elements, tips):
    """The RESULTS of one task from its /elements and /tips (see read_elements, read_tips).

    Peaks are maxima of values, never positions, so ties between elements do not matter.
    """
    ds, opening, state = elements["ds"], elements["opening"], elements["state"]
    k1, k2 = tips["k1"], tips["k2"]
    return {
        "peak_slip": float(np.max(np.abs(ds))) if ds.size else 0.0,
        "peak_opening": max(0.0, float(np.max(opening))) if opening.size else 0.0,
        "stick": int(np.count_nonzero(state == STATE_CODES["stick"])),
        "slip": int(np.count_nonzero(state == STATE_CODES["slip"])),
        "open": int(np.count_nonzero(state == STATE_CODES["open"])),
        "max_abs_k1": float(np.max(np.abs(k1))) if k1.size else float("nan"),
        "max_abs_k2": float(np.max(np.abs(k2))) if k2.size else float("nan"),
    }


def growth_summary(growth, fractures):
    """The growth columns of one task from its /growth (read_growth) and fractures."""
    attrs = growth["attrs"]
    last = growth["step"] == np.max(growth["step"]) if growth["step"].size else []
    k_eq = growth["k_eq"][last] if growth["step"].size else np.array([])
    results = {"growth_steps": int(attrs["steps_taken"]), "growth_start": growth_start(growth),
               "end_reason": str(attrs["end_reason"]),
               "k_eq_ratio": float(np.max(k_eq)) / float(attrs["toughness"]) if k_eq.size
               else float("nan")}
    for index, fracture in enumerate(fractures, start=1):
        grown = growth["length"][growth["fracture_id"] == index]
        results[GROWN_LENGTH + fracture["name"]] = float(np.sum(grown))
    return results


def injection_summary(history, fractures):
    """The injection columns of one task from its /history (read_history) and fractures:
    the path's last step."""
    results = {"injected_volume": float(history["injected_volume"][-1])}
    for index, fracture in enumerate(fractures):
        for prefix, (key, _) in INJECTION_FRACTURE_RESULTS.items():
            if key is None:  # the half-length, from the fronts
                value = 0.5 * (history["front_end"][-1, index]
                               - history["front_begin"][-1, index])
            else:
                value = history[key][-1, index]
            results[prefix + fracture["name"]] = float(value)
    return results


def growth_start(growth):
    """The load step (1-based; 1 without a load path) of the first growth step in which a
    tip grew (its record's length > 0) or a new fracture started; 0 when none did."""
    load_step = growth.get("load_step", np.ones_like(growth["step"]))
    starts = list(load_step[growth["length"] > 0])
    if "initiations" in growth:
        starts += list(growth["initiations"]["load_step"])
    return int(min(starts)) if starts else 0


def is_result(column):
    """Whether a summary column is a result (else the task number or a swept parameter)."""
    return (column in RESULTS or column in GROWTH_RESULTS or column in INJECTION_RESULTS
            or column.startswith((GROWN_LENGTH, *INJECTION_FRACTURE_RESULTS)))


def collect(folder):
    """The sweep's stem, the rows of the summary and the unit of every column; exits 2 when
    there is nothing to collect."""
    by_stem = {}
    for path in sorted(Path(folder).glob("*_task*.h5")):
        match = TASK_FILE.match(path.name)
        if match:
            by_stem.setdefault(match["stem"], []).append(path)
    if not by_stem:
        sys.stderr.write(f"collect-sweep: no task outputs (*_task<K>.h5) in {folder}\n")
        sys.exit(2)
    if len(by_stem) > 1:
        sys.stderr.write(f"collect-sweep: outputs of several sweeps in {folder}: "
                         f"{', '.join(sorted(by_stem))}; give one sweep per folder\n")
        sys.exit(2)
    stem, paths = next(iter(by_stem.items()))
    rows, tasks, unreadable = [], 0, []
    for path in paths:
        record = read_task(path)
        if record is None:
            unreadable.append(path.name)
            continue
        task, tasks, parameters, results, units = record
        rows.append({"task": task, **parameters, **results})
    if not rows:
        sys.stderr.write(f"collect-sweep: no complete task output in {folder}\n")
        sys.exit(2)
    rows.sort(key=lambda row: row["task"])
    missing = sorted(set(range(tasks)) - {row["task"] for row in rows})
    if unreadable:
        sys.stderr.write(f"collect-sweep: incomplete or unreadable: {', '.join(unreadable)}\n")
    if missing:
        sys.stderr.write(f"collect-sweep: {len(missing)} of {tasks} tasks have no complete "
                         f"output: {', '.join(map(str, missing))}\n")
    return stem, rows, column_units(rows[0], *units)


def write_tables(folder, stem, rows, units):
    """DIR/<stem>_summary.csv (units in the header) and .h5 (units as attributes); returns
    their paths."""
    columns = list(rows[0])
    csv_path = Path(folder) / f"{stem}_summary.csv"
    with atomic_path(csv_path) as temporary, open(temporary, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow([labelled(column, units) for column in columns])
        for row in rows:
            writer.writerow([repr(row[c]) if isinstance(row[c], float) else row[c]
                             for c in columns])
    h5_path = Path(folder) / f"{stem}_summary.h5"
    with atomic_path(h5_path) as temporary, h5py.File(temporary, "w") as f:
        f.attrs["columns"] = ", ".join(columns)
        for column in columns:
            values = [row[column] for row in rows]
            if isinstance(values[0], str):  # end_reason: HDF5 wants variable-length strings
                values = np.array(values, dtype=h5py.string_dtype())
            dataset = f.create_dataset(column, data=np.array(values))
            if units[column]:
                dataset.attrs["units"] = units[column]
    return csv_path, h5_path


def plot(folder, stem, rows, units, result, against, fmt):
    """RESULT against PARAM, one line per combination of the other parameters."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    others = [name for name in rows[0] if not is_result(name)
              and name not in ("task", against)]
    groups = {}
    for row in rows:
        groups.setdefault(tuple(row[name] for name in others), []).append(row)
    figure, axes = plt.subplots(figsize=(7, 4.5))
    for key, members in sorted(groups.items()):
        members.sort(key=lambda row: row[against])
        label = ", ".join(f"{name} = {value:g}" + (f" {units[name]}" if units[name] else "")
                          for name, value in zip(others, key))
        axes.plot([row[against] for row in members], [row[result] for row in members],
                  marker="o", label=label or None)
    axes.set_xlabel(labelled(against, units))
    axes.set_ylabel(labelled(result, units))
    axes.set_title(f"{stem}: {result} against {against}")
    axes.grid(True, alpha=0.3)
    if others:
        axes.legend(fontsize="small")
    figure.tight_layout()
    path = Path(folder) / f"{stem}_{result}_vs_{against}.{fmt}"
    with atomic_path(path) as temporary:
        figure.savefig(temporary, dpi=120, format=fmt)
    plt.close(figure)
    return path


def main(argv=None):
    parser = argparse.ArgumentParser(description="Summarise the outputs of a ddc2d sweep.")
    parser.add_argument("folder", help="folder of the task outputs")
    parser.add_argument("--plot", metavar="RESULT",
                        help=f"result to plot: {', '.join(RESULTS)}, and of growth runs "
                        f"growth_steps, growth_start, k_eq_ratio, {GROWN_LENGTH}<fracture>")
    parser.add_argument("--against", metavar="PARAM", help="swept parameter on the x axis")
    parser.add_argument("--format", default="png", choices=("png", "pdf", "svg"))
    args = parser.parse_args(argv)
    if bool(args.plot) != bool(args.against):
        parser.error("--plot and --against go together")

    stem, rows, units = collect(args.folder)
    for path in write_tables(args.folder, stem, rows, units):
        print(f"wrote {path}")
    if args.plot:
        parameters = [name for name in rows[0] if not is_result(name) and name != "task"]
        results = [name for name in rows[0] if is_result(name) and name != "end_reason"]
        if args.plot not in results:
            parser.error(f"--plot {args.plot}: the results are {', '.join(results)}")
        if args.against not in parameters:
            parser.error(f"--against {args.against}: the parameters of this sweep are "
                         f"{', '.join(parameters)}")
        figure = plot(args.folder, stem, rows, units, args.plot, args.against, args.format)
        print(f"wrote {figure}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
