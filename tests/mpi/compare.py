"""Compare two ddc2d result files of the same model (the MPI tests).

    python compare.py REFERENCE RESULT [--rtol R] [--processes P]

Both files are read with scripts/ddc2d_h5.py. Every array of /elements, /tips, /fields and
/history must agree: integers (states, flags, element numbers) equal, NaN at the same
places, reals within R (default 1e-10) of the array's largest magnitude in REFERENCE; the
fields' kind and shape equal. With --processes, RESULT's /solver attribute `processes` must
be P. Prints the largest difference; exit status 0 when they agree, 1 otherwise.
"""

import argparse
import sys
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))  # ddc2d_h5
from ddc2d_h5 import load_result, read_solver


def relative_difference(a, b, where):
    """max |b - a| / max |a|; NaN where NaN, integers (and text) equal."""
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape, f"{where}: shapes {a.shape} and {b.shape}"
    if a.dtype.kind != "f":
        assert np.array_equal(a, b), f"{where}: values differ"
        return 0.0
    assert np.array_equal(np.isnan(a), np.isnan(b)), f"{where}: NaN at other places"
    if a.size == 0 or np.all(np.isnan(a)):
        return 0.0
    scale = np.nanmax(np.abs(a))
    difference = np.nanmax(np.abs(b - a))
    return difference / scale if scale > 0 else difference


def arrays(result):
    """The results of a loaded file (ddc2d_h5.load_result) by path: /elements, /tips,
    /fields and /history."""
    found = {f"/elements/{key}": value for key, value in result["elements"].items()}
    found.update({f"/tips/{key}": value for key, value in result["tips"].items()
                  if key != "k_unit"})
    for name, field in result["fields"].items():
        found.update({f"/fields/{name}/{key}": value for key, value in field.items()})
    if result["history"] is not None:
        found.update({f"/history/{key}": value for key, value in result["history"].items()
                      if key != "loads"})
    return found


def differences(reference_path, other_path):
    """Largest relative difference of every result array of two files, by path."""
    reference, other = arrays(load_result(reference_path)), arrays(load_result(other_path))
    assert sorted(reference) == sorted(other), \
        f"different results: {sorted(set(reference) ^ set(other))}"
    return {name: relative_difference(reference[name], other[name], name)
            for name in reference}


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("reference")
    parser.add_argument("result")
    parser.add_argument("--rtol", type=float, default=1e-10)
    parser.add_argument("--processes", type=int, default=None)
    args = parser.parse_args(argv)
    try:
        found = differences(args.reference, args.result)
        if args.processes is not None:
            with h5py.File(args.result, "r") as f:
                processes = int(read_solver(f)["attrs"]["processes"])
            assert processes == args.processes, f"{processes} processes, not {args.processes}"
    except AssertionError as problem:
        print(f"{args.result}: {problem}")
        return 1
    worst = max(found, key=found.get)
    print(f"{args.result}: largest relative difference {found[worst]:.2e} ({worst}) over "
          f"{len(found)} arrays (limit {args.rtol:g})")
    return 0 if found[worst] <= args.rtol else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
