"""Compare ddc2d result files of the same model: the one comparer of the MPI and Slurm tests.

    python tests/compare_results.py REFERENCE RESULT [--rtol R] [--processes P]
    python tests/compare_results.py REFERENCE_DIR RESULT_DIR --stem STEM --tasks K [K ...]
                                    [--rtol R]

The second form compares the task outputs <STEM>_task<K>.h5 of two runs of a parameter
sweep (the Slurm array against serial runs), task by task. Both files are read with
ddc2d.reader (python/src/ddc2d/reader.py). They must

* both be complete (root attribute complete = 1);
* hold the same arrays of /elements, /tips, /fields, /history and /growth, of equal shapes
  (not /history's per-step solver record: how a step was solved, not its result; a resumed
  run solves its first steps without the earlier run's warm start);
  the same fractures (names and element ranges), the same codings, and the same /sweep
  attributes (task, tasks and the swept values, stored unchanged: compared exactly);
* agree value by value under one tolerance rule: integers (states, flags, element numbers)
  and text equal, NaN at the same places, and reals within R (default 1e-10) of the largest
  magnitude in REFERENCE of that kind of quantity (as scripts/compare-twodd scales):
  element displacements (DDs, face displacements), point displacements, stresses
  (tractions, field stresses), stress intensity factors (K_I, K_II, K_eq, K_II after a
  growth step's corrections); any other array by its own
  largest magnitude. An array that is round-off noise by itself (the shear traction on a
  pressurized crack, Ds of a crack under normal load) is thereby measured against its
  quantity, not against its noise.

With --processes, RESULT's /solver attribute `processes` must be P. Prints each problem
and the largest difference; exit status 0 when the files agree, 1 otherwise.
"""

import argparse
import sys
from pathlib import Path

import h5py
import numpy as np

from ddc2d.reader import load_result, read_solver, read_sweep

#: Default tolerance, relative to the largest magnitude of a kind of quantity.
RTOL = 1e-10
#: The kinds of quantity whose arrays share a scale, by array name.
KINDS = {
    "element displacement": ("ds", "dn", "opening", "us_minus", "un_minus", "us_plus",
                             "un_plus"),
    "point displacement": ("ux", "uy"),
    "stress": ("shear_traction", "normal_traction", "sxx", "syy", "sxy"),
    "stress intensity": ("k1", "k2", "k_eq", "k2_after"),
}


#: /history datasets that record how each step was solved (compared as no result): the
#: certificate and the residual are round-off sizes of that solve, scaled to 1 already
HISTORY_SOLVER_RECORD = ("pivots", "newton_iterations", "method", "fallback",
                         "certificate_min_z", "certificate_min_w",
                         "certificate_max_complementarity", "equilibrium_residual")


class Mismatch(AssertionError):
    """Two files that do not hold the same results (not a question of tolerance)."""


def kind_of(path):
    """The kind of quantity of an array (its path's last name), or the path itself."""
    name = path.rsplit("/", 1)[-1]
    return next((kind for kind, names in KINDS.items() if name in names), path)


def magnitude(a):
    """Largest finite |a| of a real array (0 for an empty or all-NaN one)."""
    a = np.asarray(a)
    if a.dtype.kind != "f" or a.size == 0 or np.all(np.isnan(a)):
        return 0.0
    return float(np.nanmax(np.abs(a)))


def relative_difference(a, b, where, scale):
    """max |b - a| / scale (the difference itself when the scale is 0); Mismatch when the
    shapes differ, NaN lies elsewhere, or integers (or text) differ."""
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape:
        raise Mismatch(f"{where}: shapes {a.shape} and {b.shape}")
    if a.dtype.kind != "f":
        if not np.array_equal(a, b):
            raise Mismatch(f"{where}: values differ")
        return 0.0
    if not np.array_equal(np.isnan(a), np.isnan(b)):
        raise Mismatch(f"{where}: NaN at other places")
    if a.size == 0 or np.all(np.isnan(a)):
        return 0.0
    difference = float(np.nanmax(np.abs(b - a)))
    return difference / scale if scale > 0 else difference


def arrays(result):
    """The result arrays of a loaded file (reader.load_result) by path: /elements, /tips,
    /fields, /history and /growth (their datasets, not their attributes)."""
    found = {f"/elements/{key}": value for key, value in result["elements"].items()}
    found.update({f"/tips/{key}": value for key, value in result["tips"].items()
                  if key != "k_unit"})
    for name, field in result["fields"].items():
        found.update({f"/fields/{name}/{key}": value for key, value in field.items()
                      if key != "codings"})
    for group in ("history", "growth"):
        if result[group] is not None:
            found.update({f"/{group}/{key}": value for key, value in result[group].items()
                          if key not in ("loads", "attrs", "reasons")
                          and not (group == "history" and key in HISTORY_SOLVER_RECORD)})
    return found


def differences(reference_path, other_path):
    """Largest relative difference of every result array of two files, by path (the
    tolerance rule's measure); Mismatch when the files do not hold the same results."""
    reference, other = load_result(reference_path), load_result(other_path)
    if not reference["complete"]:
        raise Mismatch(f"the reference {reference_path} is not complete")
    if not other["complete"]:
        raise Mismatch("not complete")
    for key in ("fractures", "codings"):
        if reference[key] != other[key]:
            raise Mismatch(f"/{key} differ: {reference[key]} and {other[key]}")
    reference, other = arrays(reference), arrays(other)
    if sorted(reference) != sorted(other):
        raise Mismatch(f"different results: {sorted(set(reference) ^ set(other))}")
    scales = {}
    for name, values in reference.items():
        kind = kind_of(name)
        scales[kind] = max(scales.get(kind, 0.0), magnitude(values))
    return {name: relative_difference(reference[name], other[name], name, scales[kind_of(name)])
            for name in reference}


def sweep_of(path):
    """The /sweep of a task output (reader.read_sweep), None when it has none."""
    with h5py.File(path, "r") as f:
        return read_sweep(f)


def compare(reference_path, other_path, rtol=RTOL, processes=None):
    """The problems of `other_path` against `reference_path` as lines of text (none when
    they agree): a Mismatch, a sweep that differs, a process count that is not
    `processes`, or the largest difference beyond rtol. Also the line that reports the
    largest difference, last."""
    try:
        found = differences(reference_path, other_path)
    except Mismatch as problem:
        return [f"{other_path}: {problem}"], ""
    problems = []
    if sweep_of(reference_path) != sweep_of(other_path):
        problems.append(f"{other_path}: /sweep attributes differ: {sweep_of(reference_path)} "
                        f"and {sweep_of(other_path)}")
    if processes is not None:
        with h5py.File(other_path, "r") as f:
            count = int(read_solver(f)["attrs"]["processes"])
        if count != processes:
            problems.append(f"{other_path}: {count} processes, not {processes}")
    worst = max(found, key=found.get)
    report = (f"{other_path}: largest relative difference {found[worst]:.2e} ({worst}) over "
              f"{len(found)} arrays (limit {rtol:g})")
    if found[worst] > rtol:
        problems.append(report)
    return problems, report


def task_file(folder, stem, task):
    """The output of sweep task `task` in `folder`: <stem>_task<K>.h5, K zero-padded to
    the width ddc2d gives every task of the sweep (at least 4 digits)."""
    matches = sorted(Path(folder).glob(f"{stem}_task*.h5"))
    if not matches:
        return Path(folder) / f"{stem}_task{task:04d}.h5"
    with h5py.File(matches[0], "r") as f:
        width = max(4, len(str(int(f["sweep"].attrs["tasks"]) - 1)))
    return Path(folder) / f"{stem}_task{task:0{width}d}.h5"


def pairs(args):
    """(reference, result) file pairs of the command line."""
    if args.tasks is None:
        return [(Path(args.reference), Path(args.result))]
    return [(task_file(args.reference, args.stem, task), task_file(args.result, args.stem, task))
            for task in args.tasks]


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("reference", help="reference file (or folder, with --tasks)")
    parser.add_argument("result", help="file (or folder, with --tasks) to check")
    parser.add_argument("--rtol", type=float, default=RTOL)
    parser.add_argument("--processes", type=int, default=None)
    parser.add_argument("--stem", help="sweep: the stem of the task outputs")
    parser.add_argument("--tasks", type=int, nargs="+", help="sweep: the tasks to compare")
    args = parser.parse_args(argv)
    if (args.tasks is None) != (args.stem is None):
        parser.error("--stem and --tasks go together")
    bad = 0
    for reference, result in pairs(args):
        missing = [path for path in (reference, result) if not path.is_file()]
        problems, report = ([f"missing {missing[0]}"], "") if missing else \
            compare(reference, result, args.rtol, args.processes)
        for line in problems:
            print(line)
        if report and not problems:
            print(report)
        bad += bool(problems)
    if args.tasks is not None:
        print(f"compared {len(args.tasks)} tasks: {len(args.tasks) - bad} equal, "
              f"{bad} different")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
