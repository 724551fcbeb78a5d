"""Compare ddc2d task outputs of a Slurm run with serial runs of the same tasks.

    python compare_outputs.py SLURM_DIR SERIAL_DIR STEM TASK [TASK ...]

For every task K, SLURM_DIR/<STEM>_task<K>.h5 and SERIAL_DIR/<STEM>_task<K>.h5 must both be
complete (root attribute complete = 1) and hold the same /elements, /tips and /fractures
datasets (integers equal, reals within 1e-12 relative, NaN where NaN) and the same /sweep
attributes. Exit status 0 when every task matches, 1 otherwise (each difference printed).
"""

import sys
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from ddc2d_h5 import is_complete

GROUPS = ("elements", "tips", "fractures")
RTOL = 1e-12


def task_file(folder, stem, task, width):
    return Path(folder) / f"{stem}_task{task:0{width}d}.h5"


def differences(a_path, b_path):
    """List of the differences between two result files."""
    found = []
    with h5py.File(a_path, "r") as a, h5py.File(b_path, "r") as b:
        for f, path in ((a, a_path), (b, b_path)):
            if not is_complete(f.attrs):
                found.append(f"{path}: not complete")
        for group in GROUPS:
            names = sorted(a[group])
            if names != sorted(b[group]):
                found.append(f"/{group}: datasets differ: {names} vs {sorted(b[group])}")
                continue
            for name in names:
                x, y = a[group][name][()], b[group][name][()]
                if x.shape != y.shape:
                    found.append(f"/{group}/{name}: shapes {x.shape} and {y.shape}")
                elif x.dtype.kind == "f":
                    scale = max(float(np.nanmax(np.abs(x))) if x.size else 0.0, 1e-300)
                    same = np.allclose(x, y, rtol=RTOL, atol=RTOL * scale, equal_nan=True)
                    if not same:
                        found.append(f"/{group}/{name}: max difference "
                                     f"{np.nanmax(np.abs(x - y)):.3e} (scale {scale:.3e})")
                elif not np.array_equal(x, y):
                    found.append(f"/{group}/{name}: values differ")
        # The swept values are the input's, stored unchanged by both runs: compared exactly.
        sweep_a, sweep_b = dict(a["sweep"].attrs), dict(b["sweep"].attrs)
        if sweep_a.keys() != sweep_b.keys() or any(
                np.any(sweep_a[key] != sweep_b[key]) for key in sweep_a):
            found.append(f"/sweep attributes differ: {sweep_a} vs {sweep_b}")
    return found


def main(argv):
    slurm_dir, serial_dir, stem, *tasks = argv
    tasks = [int(task) for task in tasks]
    bad = 0
    for task in tasks:
        with h5py.File(next(Path(slurm_dir).glob(f"{stem}_task*.h5")), "r") as f:
            width = max(4, len(str(int(f["sweep"].attrs["tasks"]) - 1)))
        a, b = task_file(slurm_dir, stem, task, width), task_file(serial_dir, stem, task, width)
        if not a.is_file() or not b.is_file():
            print(f"task {task}: missing {a if not a.is_file() else b}")
            bad += 1
            continue
        found = differences(a, b)
        for line in found:
            print(f"task {task}: {line}")
        bad += bool(found)
    print(f"compared {len(tasks)} tasks with their serial runs: {len(tasks) - bad} equal, "
          f"{bad} different")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
