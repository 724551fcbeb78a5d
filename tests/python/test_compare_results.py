"""tests/compare_results.py, the one comparer of ddc2d results that the MPI and Slurm tests
use: one tolerance rule (relative to the largest magnitude of a kind of quantity),
integers and NaN places exact, completeness, fractures and sweeps checked."""

import shutil

import h5py
import numpy as np
import pytest

import compare_results
from conftest import write_result


@pytest.fixture
def pair(tmp_path):
    """A synthetic result and an identical copy."""
    reference = write_result(tmp_path / "reference.h5")
    other = tmp_path / "other.h5"
    shutil.copy(reference, other)
    return reference, other


def change(path, dataset, index, value):
    with h5py.File(path, "r+") as f:
        data = f[dataset][...]
        data[index] = value
        f[dataset][...] = data


def test_identical_files_agree(pair, capsys):
    assert compare_results.main([str(p) for p in pair]) == 0
    assert "largest relative difference 0.00e+00" in capsys.readouterr().out


def test_the_tolerance_is_relative_to_the_kind_of_quantity(pair):
    reference, other = pair
    # /elements/ds: largest |DD| of the model 3e-3 (ds and dn are one kind).
    change(other, "elements/ds", 4, 4.0e-4 + 3e-3 * 5e-10)
    found = compare_results.differences(reference, other)
    assert found["/elements/ds"] == pytest.approx(5e-10, rel=1e-3)
    assert compare_results.main([str(reference), str(other)]) == 1
    assert compare_results.main([str(reference), str(other), "--rtol", "1e-9"]) == 0


def test_a_noise_array_is_measured_against_its_kind(pair):
    """un_plus is tiny on most elements; a change of 1e-11 of the largest DD passes at
    1e-10 though it is large against un_plus's own values."""
    reference, other = pair
    change(other, "elements/un_plus", 0, 3e-3 * 1e-11)
    assert compare_results.compare(reference, other)[0] == []


@pytest.mark.parametrize("dataset, index, value, words", [
    ("elements/state", 0, 2, "/elements/state: values differ"),
    ("fields/grid1/sxx", (0, 0), np.nan, "NaN at other places"),
])
def test_integers_and_nan_places_are_exact(pair, dataset, index, value, words):
    reference, other = pair
    change(other, dataset, index, value)
    problems, _ = compare_results.compare(reference, other, rtol=1.0)
    assert len(problems) == 1 and words in problems[0]


def test_an_incomplete_file_never_agrees(pair):
    reference, other = pair
    with h5py.File(other, "r+") as f:
        f.attrs["complete"] = np.int32(0)
    problems, _ = compare_results.compare(reference, other)
    assert problems == [f"{other}: not complete"]
    problems, _ = compare_results.compare(other, reference)
    assert problems == [f"{reference}: the reference {other} is not complete"]


def write_task(folder, task, value):
    """A task output of a 3-task sweep of mu."""
    folder.mkdir(exist_ok=True)
    path = write_result(folder / f"sweep_task{task:04d}.h5")
    with h5py.File(path, "r+") as f:
        sweep = f.create_group("sweep")
        sweep.attrs["task"] = np.int32(task)
        sweep.attrs["tasks"] = np.int32(3)
        sweep.attrs["parameters"] = np.bytes_(b"mu")
        sweep.attrs["mu"] = value
    return path


def test_sweep_tasks_are_compared_task_by_task(tmp_path, capsys):
    for task, mu in enumerate((0.4, 0.5, 0.6)):
        write_task(tmp_path / "serial", task, mu)
        write_task(tmp_path / "slurm", task, mu if task != 2 else 0.6000000001)
    args = [str(tmp_path / "serial"), str(tmp_path / "slurm"), "--stem", "sweep"]
    assert compare_results.main([*args, "--tasks", "0", "1"]) == 0
    assert "compared 2 tasks: 2 equal, 0 different" in capsys.readouterr().out
    assert compare_results.main([*args, "--tasks", "0", "1", "2"]) == 1
    out = capsys.readouterr().out
    assert "/sweep attributes differ" in out and "1 different" in out
    (tmp_path / "slurm" / "sweep_task0001.h5").unlink()
    assert compare_results.main([*args, "--tasks", "1"]) == 1
    assert "missing" in capsys.readouterr().out
