"""Robustness of the ddc2d executable (issue 8): fuzzed inputs, a run killed mid-write, and
memcheck of small models.

Fuzz: mutated copies of the example namelists (shrunk so that each run takes milliseconds),
of a namelist with element and point CSVs, and of the TWODD decks: byte flips, truncation,
huge numbers, NaN, repeated groups, dropped lines. Every run must end by itself with a
status of 0-3 or 5 (no signal, no Fortran runtime error, no hang) and a failed run must
leave no output file; a successful one a complete file. DDC2D_FUZZ_COUNT sets the number of runs.
"""

import os
import random
import re
import shutil
import signal
import subprocess
import time
from concurrent.futures import ThreadPoolExecutor

import h5py
import pytest

from conftest import REPO_ROOT, ddc2d_exe
from ddc2d_h5 import is_complete

FUZZ_COUNT = int(os.environ.get("DDC2D_FUZZ_COUNT", "2000"))
GOOD_POLYLINE = REPO_ROOT / "tests/data/input/good_polyline.nml"
RUN_TIMEOUT = 60.0
CRASH_MARKS = ("Fortran runtime error", "Backtrace", "ERROR STOP", "Segmentation fault",
               "Program received signal")


def shrink(text):
    """Make a model cheap: at most 8 elements per segment, at most 6 x 6 grid points, at
    most 4 steps per leg of a load path and 4 growth steps (a single digit, so that a
    mutated digit gives at most 9)."""
    for name, most in (("elements", 8), ("steps", 4)):
        text = re.sub(rf"\b({name}\s*=\s*)([0-9, ]+)",
                      lambda m, most=most: m.group(1) + ", ".join(
                          str(min(int(v), most)) for v in m.group(2).split(",") if v.strip())
                      + " ", text)
    text = re.sub(r"\b(nx|ny|points)(\s*=\s*)(\d+)",
                  lambda m: f"{m.group(1)}{m.group(2)}{min(int(m.group(3)), 6)}", text)
    return text


def seeds():
    """(name, text, kind) of every input the fuzzer mutates."""
    found = []
    for path in sorted((REPO_ROOT / "input").glob("*.nml")):
        text = path.read_text()
        if "&sweep" in text.lower():
            continue
        found.append((path.name, shrink(text), "nml"))
    found.append(("good_polyline.nml", GOOD_POLYLINE.read_text(), "nml"))
    found.append(("elements.csv", (REPO_ROOT / "tests/data/input/csv/elements.csv").read_text(),
                  "csv"))
    for path in sorted((REPO_ROOT / "tests/reference/twodd/inputs").glob("*.txt")):
        found.append((path.name, path.read_text(), "twodd"))
    return found


def mutate(text, rng):
    """One random mutation of the kinds the issue lists."""
    kind = rng.randrange(7)
    if kind == 0 and text:  # byte flips
        data = bytearray(text.encode())
        for _ in range(rng.randint(1, 4)):
            data[rng.randrange(len(data))] = rng.randrange(1, 256)
        return data.decode("latin-1")
    if kind == 1:  # truncation
        return text[: rng.randrange(len(text) + 1)]
    numbers = list(re.finditer(r"-?\d+\.\d*(?:[eE][-+]?\d+)?", text))
    if kind in (2, 3) and numbers:  # huge numbers, NaN / Inf in place of a real
        m = rng.choice(numbers)
        new = rng.choice(["1e308", "-1e308", "1e400", "1e-320"]) if kind == 2 else \
            rng.choice(["NaN", "Inf", "-Infinity", "nan"])
        return text[: m.start()] + new + text[m.end():]
    groups = list(re.finditer(r"&\w+[^&]*?/", text, flags=re.DOTALL))
    if kind == 4 and groups:  # a repeated group
        g = rng.choice(groups)
        return text[: g.end()] + "\n" + g.group(0) + text[g.end():]
    lines = text.splitlines(keepends=True)
    if kind == 5 and lines:  # a dropped line
        del lines[rng.randrange(len(lines))]
        return "".join(lines)
    if lines:  # a duplicated line
        i = rng.randrange(len(lines))
        lines.insert(i, lines[i])
    return "".join(lines)


def run_one(case):
    index, name, text, kind, folder = case
    work = folder / f"case{index:05d}"
    work.mkdir()
    shutil.copytree(REPO_ROOT / "tests/data/input/csv", work / "csv")
    data = text.encode("latin-1", errors="replace")
    if kind == "csv":  # the mutated element CSV under the unchanged model that reads it
        (work / "csv" / "elements.csv").write_bytes(data)
        source = work / "model.nml"
        shutil.copy(GOOD_POLYLINE, source)
    else:
        source = work / ("model.nml" if kind == "nml" else "deck.txt")
        source.write_bytes(data)
    args = [str(ddc2d_exe())] + (["--twodd"] if kind == "twodd" else []) + \
        [source.name, "-o", "out.h5"]
    try:
        done = subprocess.run(args, cwd=work, capture_output=True, timeout=RUN_TIMEOUT,
                              env={**os.environ, "OMP_NUM_THREADS": "1",
                                   "OPENBLAS_NUM_THREADS": "1"})
    except subprocess.TimeoutExpired:
        return f"{name} #{index}: no answer within {RUN_TIMEOUT} s", work
    stderr = done.stderr.decode(errors="replace")
    problems = []
    if done.returncode not in (0, 1, 2, 3, 5):  # 5: too large for this machine's memory
        problems.append(f"exit status {done.returncode}")
    if any(mark in stderr for mark in CRASH_MARKS):
        problems.append("crashed: " + stderr[-300:])
    out, partial = work / "out.h5", work / "out.h5.partial"
    if partial.exists():
        problems.append("left out.h5.partial")
    if done.returncode == 0:
        try:
            with h5py.File(out, "r") as f:
                if not is_complete(f.attrs):
                    problems.append("output not marked complete")
        except OSError as exc:
            problems.append(f"exit 0 but no readable output: {exc}")
    elif out.exists():
        problems.append(f"exit {done.returncode} but out.h5 exists")
    elif done.returncode != 0 and not stderr.strip():
        problems.append(f"exit {done.returncode} without a message")
    if problems:
        return f"{name} #{index}: " + "; ".join(problems), work
    shutil.rmtree(work)
    return None, None


def test_fuzzed_inputs_fail_cleanly(tmp_path):
    rng = random.Random(20261121)
    sources = seeds()
    cases = []
    for index in range(FUZZ_COUNT):
        name, text, kind = sources[index % len(sources)]
        for _ in range(rng.randint(1, 3)):
            text = mutate(text, rng)
        cases.append((index, name, text, kind, tmp_path))
    with ThreadPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(run_one, cases))
    failures = [message for message, _ in results if message]
    assert not failures, f"{len(failures)} of {FUZZ_COUNT} fuzzed runs misbehaved:\n" + \
        "\n".join(failures[:20])


def test_sigkill_mid_write_leaves_no_final_file(tmp_path):
    # A small model with a large grid: writing its fields takes a noticeable time. Each run
    # is killed at a different moment after its HDF5 file (OUT.h5.partial) has been started.
    (tmp_path / "big.nml").write_text(
        "&model youngs_modulus = 1.0, poissons_ratio = 0.25 /\n"
        "&fracture x = -1.0, 1.0, y = 0.0, 0.0, elements = 10, condition = 'traction', "
        "bc_n = -1.0 /\n"
        "&grid xmin = -3, xmax = 3, nx = 1500, ymin = -3, ymax = 3, ny = 1500 /\n")
    killed_mid_write = 0
    for k, delay in enumerate((0.0, 0.01, 0.03, 0.06, 0.1, 0.2, 0.4, 0.8)):
        out = tmp_path / f"out{k}.h5"
        partial = tmp_path / f"out{k}.h5.partial"
        process = subprocess.Popen([str(ddc2d_exe()), "big.nml", "-o", out.name],
                                   cwd=tmp_path, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 300
        # The writable-path check creates and removes an empty partial file first: wait for
        # the HDF5 file itself (it has a superblock as soon as it exists).
        while process.poll() is None and time.monotonic() < deadline:
            if partial.exists() and partial.stat().st_size > 0:
                break
            time.sleep(0.002)
        time.sleep(delay)
        process.send_signal(signal.SIGKILL)
        process.wait(timeout=60)
        if out.exists():
            # Killed after the rename, or finished first: the file must be complete.
            with h5py.File(out, "r") as f:
                assert is_complete(f.attrs), f"killed {delay} s into the write: incomplete"
        else:
            assert process.returncode == -signal.SIGKILL
            killed_mid_write += 1
    # The kills must have hit the write itself, not only the end of the run.
    assert killed_mid_write >= 3


MEMCHECK_MODELS = {
    "contact_kink.nml": "&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /\n"
                        "&remote_stress sxx = -143.75, syy = -81.25, sxy = 54.13 /\n"
                        "&fracture x = -1.0, 0.0, 0.8, y = 0.0, 0.0, 0.5, elements = 12, 12, "
                        "mu = 0.6, sf = 1.0 /\n"
                        "&fracture condition = 'traction', x = 0.0, 0.0, y = 0.5, 1.5, "
                        "elements = 6, bc_n = -100.0 /\n"
                        "&grid xmin = -2, xmax = 2, nx = 9, ymin = -1, ymax = 1, ny = 7 /\n"
                        "&line x_begin = -2, y_begin = 0.3, x_end = 2, y_end = 0.3, "
                        "points = 5 /\n",
    "bad.nml": "&model youngs_modulus = -1.0, poissons_ratio = 0.25 /\n"
               "&fracture x = -1.0, 1.0, y = 0.0, 0.0, elements = 4, mu = 0.6 /\n",
}


def memcheck(args, cwd):
    """Run ddc2d under valgrind memcheck (one thread); return the finished process."""
    return subprocess.run(["valgrind", "--error-exitcode=99", "--leak-check=full",
                           "--errors-for-leak-kinds=definite", str(ddc2d_exe()), *args,
                           "-o", "out.h5"], cwd=cwd, capture_output=True, text=True,
                          timeout=600, env={**os.environ, "OMP_NUM_THREADS": "1",
                                            "OPENBLAS_NUM_THREADS": "1"})


def assert_memcheck_clean(done, status):
    assert done.returncode != 99, done.stderr[-3000:]
    assert "ERROR SUMMARY: 0 errors" in done.stderr
    assert done.returncode == status, done.stderr[-2000:]


@pytest.mark.parametrize("model", sorted(MEMCHECK_MODELS) + ["A1_press_n20.f60.txt"])
def test_memcheck_clean(tmp_path, model):
    if model.endswith(".txt"):
        shutil.copy(REPO_ROOT / "tests/reference/twodd/inputs" / model, tmp_path / model)
        args = ["--twodd", model, "--res", "res.txt"]
    else:
        (tmp_path / model).write_text(MEMCHECK_MODELS[model])
        args = [model]
    assert_memcheck_clean(memcheck(args, tmp_path), 2 if model == "bad.nml" else 0)


@pytest.mark.parametrize("example", sorted(p.name for p in (REPO_ROOT / "input").glob("*.nml")))
def test_memcheck_examples(tmp_path, example):
    # Every example, shrunk to at most 8 elements per segment and 6 x 6 grid points so that
    # valgrind takes seconds; a sweep runs its first task.
    text = shrink((REPO_ROOT / "input" / example).read_text())
    (tmp_path / example).write_text(text)
    args = [example] + (["--task", "0"] if "&sweep" in text.lower() else [])
    assert_memcheck_clean(memcheck(args, tmp_path), 0)
