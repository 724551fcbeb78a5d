"""Compare two ddc2d result files of the same model (the MPI tests).

    python compare.py REFERENCE RESULT [--rtol R] [--processes P]

Both files are read with scripts/ddc2d_h5.py. Every array of /elements, /tips, /fields and
/history must agree: integers (states, flags, element numbers) equal, NaN at the same
places, reals within R (default 1e-10) of the largest magnitude in REFERENCE of that kind of
quantity (as scripts/compare-twodd scales): element displacements (DDs, face
displacements), point displacements, stresses (tractions, field stresses), stress
intensity factors; any other array by its own largest magnitude. An array that is round-off
noise by itself (the shear traction on a pressurized crack, Ds of a crack under normal load)
is thereby measured against its quantity, not against its noise. The fields' kind and shape
must be equal. With --processes, RESULT's /solver attribute `processes` must be P. Prints
the largest difference; exit status 0 when they agree, 1 otherwise.
"""

import argparse
import sys
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))  # ddc2d_h5
from ddc2d_h5 import load_result, read_solver

#: The kinds of quantity whose arrays share a scale, by array name.
KINDS = {
    "element displacement": ("ds", "dn", "opening", "us_minus", "un_minus", "us_plus",
                             "un_plus"),
    "point displacement": ("ux", "uy"),
    "stress": ("shear_traction", "normal_traction", "sxx", "syy", "sxy"),
    "stress intensity": ("k1", "k2"),
}


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
    """max |b - a| / scale (the difference itself when the scale is 0); NaN where NaN,
    integers (and text) equal."""
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape, f"{where}: shapes {a.shape} and {b.shape}"
    if a.dtype.kind != "f":
        assert np.array_equal(a, b), f"{where}: values differ"
        return 0.0
    assert np.array_equal(np.isnan(a), np.isnan(b)), f"{where}: NaN at other places"
    if a.size == 0 or np.all(np.isnan(a)):
        return 0.0
    difference = float(np.nanmax(np.abs(b - a)))
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
    scales = {}
    for name, values in reference.items():
        kind = kind_of(name)
        scales[kind] = max(scales.get(kind, 0.0), magnitude(values))
    return {name: relative_difference(reference[name], other[name], name, scales[kind_of(name)])
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
