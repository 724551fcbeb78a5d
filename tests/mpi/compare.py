"""Compare two ddc2d result files of the same model (the MPI tests).

    python compare.py REFERENCE RESULT [--rtol R] [--processes P]

Every dataset of /elements, /tips and /fields must agree: integers (states, flags, element
numbers) equal, NaN at the same places, reals within R (default 1e-10) of the dataset's
largest magnitude in REFERENCE. With --processes, RESULT's /solver attribute `processes`
must be P. Prints the largest difference; exit status 0 when they agree, 1 otherwise.
"""

import argparse
import sys

import h5py
import numpy as np


def relative_difference(reference, other, where):
    """max |other - reference| / max |reference|; NaN where NaN, integers equal."""
    a, b = reference[()], other[()]
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


def differences(reference, other):
    """Largest relative difference of every dataset of /elements, /tips and /fields."""
    names = []
    for group in ("elements", "tips", "fields"):
        if group not in reference:
            assert group not in other, f"/{group} only in the second file"
            continue
        reference[group].visititems(lambda name, item, group=group: names.append(
            f"/{group}/{name}") if isinstance(item, h5py.Dataset) else None)
    return {name: relative_difference(reference[name], other[name], name) for name in names}


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("reference")
    parser.add_argument("result")
    parser.add_argument("--rtol", type=float, default=1e-10)
    parser.add_argument("--processes", type=int, default=None)
    args = parser.parse_args(argv)
    try:
        with h5py.File(args.reference, "r") as reference, h5py.File(args.result, "r") as other:
            found = differences(reference, other)
            if args.processes is not None:
                processes = int(other["solver"].attrs["processes"])
                assert processes == args.processes, f"{processes} processes, not {args.processes}"
    except AssertionError as problem:
        print(f"{args.result}: {problem}")
        return 1
    worst = max(found, key=found.get)
    print(f"{args.result}: largest relative difference {found[worst]:.2e} ({worst}) over "
          f"{len(found)} datasets (limit {args.rtol:g})")
    return 0 if found[worst] <= args.rtol else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
