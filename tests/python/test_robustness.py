"""Robustness of the ddc2d executable (docs/troubleshooting.md): fuzzed inputs, a run killed
mid-write, output targets that are not regular files, file-size limits and full file
systems, huge inputs, and memcheck of small models.

Fuzz: mutated copies of the example namelists (shrunk so that each run takes milliseconds),
of a namelist with element and point CSVs, and of the TWODD decks: byte flips, truncation,
huge numbers, NaN, repeated groups, dropped lines. Every run must end by itself with a
status of 0-3 or 5 (no signal, no Fortran runtime error, no hang) and a failed run must
leave no output file; a successful one a complete file. DDC2D_FUZZ_COUNT sets the number of runs.
Huge inputs: lines of 10^5 characters, 10^6 values in one array, groups without
their closing /, CSV files of 10^7 rows, generated in a temporary folder: each a clear
message or a correct run, within a time and a memory bound.

Every wait here is for a condition with a deadline (no sleep stands in for one), and the
deadlines assume a loaded machine: scripts/test.sh runs this file again beside a CPU hog.
"""

import os
import random
import re
import resource
import shutil
import signal
import socket
import stat
import subprocess
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import h5py
import pytest

from conftest import REPO_ROOT, ddc2d_exe
from ddc2d.reader import is_complete

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
    """One random mutation: seven kinds."""
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
        # The file may vanish between two looks (it is renamed, or it is that empty test
        # file): one stat per look, its absence meaning size 0.
        while process.poll() is None and time.monotonic() < deadline:
            if file_size(partial) > 0:
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


def file_size(path):
    """Size of the file at path, 0 when there is none (one system call: no check-then-act)."""
    try:
        return path.stat().st_size
    except FileNotFoundError:
        return 0


# ---------------------------------------------------------------- output targets

def grid_model(nx, ny=None):
    """A pressurised crack of 10 elements with an nx x ny grid (60 bytes a point in HDF5,
    about 180 in the --res tables)."""
    return ("&model youngs_modulus = 1.0, poissons_ratio = 0.25 /\n"
            "&fracture x = -1.0, 1.0, y = 0.0, 0.0, elements = 10, condition = 'traction', "
            "bc_n = -1.0 /\n"
            f"&grid xmin = -3, xmax = 3, nx = {nx}, ymin = -3, ymax = 3, ny = {ny or nx} /\n")


def run_ddc2d(args, cwd, timeout=RUN_TIMEOUT, **options):
    return subprocess.run([str(ddc2d_exe()), *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, timeout=timeout, env={**os.environ, "OMP_NUM_THREADS": "1",
                                                           "OPENBLAS_NUM_THREADS": "1"},
                          **options)


def error_lines(done):
    return [line for line in done.stderr.splitlines() if line.startswith("ddc2d: error")]


def partial_files(*folders):
    return [p for folder in folders for p in folder.iterdir() if p.name.endswith(".partial")]


def file_type(path):
    return stat.S_IFMT(os.lstat(path).st_mode)


def assert_complete_h5(path):
    with h5py.File(path, "r") as f:
        assert is_complete(f.attrs)


def make_special(kind, path, keep):
    """Make a device node, FIFO, socket or folder at path; keep collects what must stay
    open during the run (the FIFO's reader, the socket)."""
    if kind == "device":
        if os.geteuid() != 0:
            pytest.skip("making a device node (mknod) needs root")
        # The null device's numbers, in a temporary folder: the real /dev/null is not touched.
        os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(1, 3))
    elif kind == "fifo":
        os.mkfifo(path)
        # A reader, so that a program writing into the FIFO would not block but be caught.
        keep.append(os.open(path, os.O_RDONLY | os.O_NONBLOCK))
    elif kind == "socket":
        # A socket's path holds at most 107 bytes (AF_UNIX), less than a temporary folder in
        # the build tree may take: bound by its name alone, from its folder.
        server = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        here = os.getcwd()
        os.chdir(path.parent)
        try:
            server.bind(path.name)
        finally:
            os.chdir(here)
        keep.append(server)
    else:
        path.mkdir()


SPECIAL_WORDS = {"device": "character device", "fifo": "FIFO", "socket": "socket",
                 "folder": "folder"}


@pytest.mark.parametrize("via_link", [False, True], ids=["direct", "link"])
@pytest.mark.parametrize("kind", sorted(SPECIAL_WORDS))
@pytest.mark.parametrize("option", ["-o", "--res"])
def test_target_that_is_not_a_regular_file_is_refused(tmp_path, option, kind, via_link):
    # docs/output-reference.md#how-the-file-is-written: ddc2d replaces only regular files;
    # anything else is exit 3 before the solve, and stays what it was.
    (tmp_path / "m.nml").write_text(grid_model(5))
    target = tmp_path / "target"
    keep = []
    make_special(kind, target, keep)
    try:
        before = file_type(target)
        name = "target"
        if via_link:
            (tmp_path / "link").symlink_to("target")
            name = "link"
        args = ["m.nml", "-o", name] if option == "-o" else ["m.nml", "-o", "out.h5",
                                                             "--res", name]
        done = run_ddc2d(args, tmp_path)
        assert done.returncode == 3, done.stderr
        [line] = error_lines(done)
        assert name in line and SPECIAL_WORDS[kind] in line, line
        assert file_type(target) == before
        if via_link:
            assert os.readlink(tmp_path / "link") == "target"
        assert not (tmp_path / "out.h5").exists()
        assert partial_files(tmp_path) == []
        if kind == "fifo":  # nothing was written into it
            try:
                assert os.read(keep[0], 1) == b""
            except BlockingIOError:
                pass
    finally:
        for item in keep:
            item.close() if isinstance(item, socket.socket) else os.close(item)


@pytest.mark.parametrize("existing", [True, False], ids=["replaced", "created"])
@pytest.mark.parametrize("option", ["-o", "--res"])
def test_link_is_followed_and_stays(tmp_path, option, existing):
    # A chain of links (relative, then absolute) to a file in another folder: that file is
    # written (replaced or created), the links stay, the .partial lives beside the file.
    (tmp_path / "m.nml").write_text(grid_model(5))
    data, links = tmp_path / "data", tmp_path / "links"
    data.mkdir()
    links.mkdir()
    real = data / "real"
    if existing:
        real.write_text("old contents\n")
    (links / "middle").symlink_to(real)
    (links / "result").symlink_to("../links/middle")
    args = ["m.nml", "-o", "links/result"] if option == "-o" else \
        ["m.nml", "-o", "out.h5", "--res", "links/result"]
    done = run_ddc2d(args, tmp_path)
    assert done.returncode == 0, done.stderr
    assert os.readlink(links / "result") == "../links/middle"
    assert os.readlink(links / "middle") == str(real)
    assert file_type(real) == stat.S_IFREG
    if option == "-o":
        assert_complete_h5(real)
    else:
        assert "DISPLACEMENTS AND STRESSES" in real.read_text()
    assert partial_files(tmp_path, data, links) == []


def test_sweep_task_file_targets(tmp_path):
    # The task file of a sweep: a FIFO there is refused (it would block the check for a
    # complete output), a link is followed.
    text = shrink((REPO_ROOT / "input/sweep_friction_orientation.nml").read_text())
    (tmp_path / "sweep.nml").write_text(text)
    listed = run_ddc2d(["sweep.nml", "--list", "-o", "out.h5"], tmp_path)
    assert listed.returncode == 0, listed.stderr
    task_file = re.search(r"task 0: .* -> (\S+)", listed.stdout).group(1)
    keep = []
    make_special("fifo", tmp_path / task_file, keep)
    try:
        done = run_ddc2d(["sweep.nml", "--task", "0", "-o", "out.h5"], tmp_path)
    finally:
        os.close(keep[0])
    assert done.returncode == 3, done.stderr
    assert "FIFO" in error_lines(done)[0]
    assert file_type(tmp_path / task_file) == stat.S_IFIFO
    (tmp_path / task_file).unlink()
    (tmp_path / "data").mkdir()
    (tmp_path / task_file).symlink_to("data/task0.h5")
    done = run_ddc2d(["sweep.nml", "--task", "0", "-o", "out.h5"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / task_file).is_symlink()
    assert_complete_h5(tmp_path / "data/task0.h5")
    # Run again: the complete file behind the link is recognised and skipped.
    again = run_ddc2d(["sweep.nml", "--task", "0", "-o", "out.h5"], tmp_path)
    assert again.returncode == 0 and "skipped" in again.stdout, again.stdout
    assert partial_files(tmp_path, tmp_path / "data") == []


# ----------------------------------------------- the scripts' own files

@pytest.mark.parametrize("kind", sorted(SPECIAL_WORDS))
def test_scripts_refuse_targets_that_are_not_regular_files(tmp_path, kind):
    # ddc2d.files, through which every tool writes its files.
    from ddc2d.files import write_text_atomically
    target, keep = tmp_path / "target", []
    make_special(kind, target, keep)
    (tmp_path / "link").symlink_to("target")
    try:
        before = file_type(target)
        for name in ("target", "link"):
            with pytest.raises(OSError, match=SPECIAL_WORDS[kind]):
                write_text_atomically(tmp_path / name, "text\n")
        assert file_type(target) == before and (tmp_path / "link").is_symlink()
        assert partial_files(tmp_path) == []
    finally:
        for item in keep:
            item.close() if isinstance(item, socket.socket) else os.close(item)


def test_scripts_follow_links_and_clean_up(tmp_path):
    from ddc2d.files import atomic_path, write_text_atomically
    (tmp_path / "data").mkdir()
    (tmp_path / "link.txt").symlink_to("data/real.txt")
    write_text_atomically(tmp_path / "link.txt", "new\n")
    assert (tmp_path / "link.txt").is_symlink()
    assert (tmp_path / "data/real.txt").read_text() == "new\n"
    with pytest.raises(RuntimeError), atomic_path(tmp_path / "link.txt") as temporary:
        temporary.write_text("half")
        raise RuntimeError("a failure half way")
    assert (tmp_path / "data/real.txt").read_text() == "new\n"
    assert partial_files(tmp_path, tmp_path / "data") == []


def test_twodd2nml_output_to_a_fifo_exits_3(tmp_path):
    # End to end: a script's -o naming a FIFO (with a reader) is refused, nothing written.
    keep = []
    make_special("fifo", tmp_path / "out.nml", keep)
    try:
        done = subprocess.run([str(REPO_ROOT / "build/venv/bin/python"),
                               str(REPO_ROOT / "scripts/twodd2nml"),
                               str(REPO_ROOT / "tests/reference/twodd/inputs/A1_press_n20.f60.txt"),
                               "-o", "out.nml"], cwd=tmp_path, capture_output=True, text=True,
                              timeout=RUN_TIMEOUT)
        assert done.returncode == 3, done.stderr
        assert "FIFO" in done.stderr
        assert file_type(tmp_path / "out.nml") == stat.S_IFIFO
        try:
            assert os.read(keep[0], 1) == b""
        except BlockingIOError:
            pass
    finally:
        os.close(keep[0])


# ------------------------------------------------- file-size limits, full disks

def limit_file_size(size):
    def limit():
        resource.setrlimit(resource.RLIMIT_FSIZE, (size, resource.getrlimit(
            resource.RLIMIT_FSIZE)[1]))
    return limit


@pytest.mark.parametrize("option", ["-o", "--res"])
def test_file_size_limit_is_exit_3_without_files(tmp_path, option):
    # ulimit -f: the write fails half way (no SIGXFSZ death), one message names the file
    # and the cause, and neither the file nor its .partial is left.
    (tmp_path / "m.nml").write_text(grid_model(100))  # 0.6 MB of HDF5, 1.8 MB of tables
    if option == "-o":
        args, name, limit = ["m.nml", "-o", "out.h5"], "out.h5", 300_000
    else:
        args, name, limit = ["m.nml", "-o", "out.h5", "--res", "r.txt"], "r.txt", 1_000_000
    done = run_ddc2d(args, tmp_path, preexec_fn=limit_file_size(limit))
    assert done.returncode == 3, done.stderr
    [line] = error_lines(done)
    assert f"writing {name} failed" in line and "ulimit -f" in line, line
    assert not (tmp_path / name).exists()
    assert partial_files(tmp_path) == []


@pytest.fixture
def small_file_system(tmp_path):
    """A 1 MiB tmpfs mounted in tmp_path (root only; skipped with the reason elsewhere)."""
    if os.geteuid() != 0:
        pytest.skip("mounting a small tmpfs needs root")
    folder = tmp_path / "small"
    folder.mkdir()
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1m", "ddc2d-test", str(folder)],
                          capture_output=True, text=True, timeout=60)
    if done.returncode != 0:
        pytest.skip(f"this machine does not allow mounting a tmpfs: {done.stderr.strip()}")
    try:
        yield folder
    finally:
        subprocess.run(["umount", str(folder)], capture_output=True, timeout=60)


def free_bytes(folder):
    info = os.statvfs(folder)
    return info.f_bavail * info.f_frsize


@pytest.mark.parametrize("option", ["-o", "--res"])
def test_result_larger_than_free_space_is_refused_before_the_solve(tmp_path, option,
                                                                    small_file_system):
    # 90000 points: at least 5.4 MB of HDF5, 16 MB of tables.
    (tmp_path / "m.nml").write_text(grid_model(300))
    args = ["m.nml", "-o", "small/out.h5"] if option == "-o" else \
        ["m.nml", "-o", "out.h5", "--res", "small/r.txt"]
    done = run_ddc2d(args, tmp_path)
    assert done.returncode == 3, done.stderr
    [line] = error_lines(done)
    need = "5.4 MB" if option == "-o" else "16 MB"
    assert f"needs at least {need}" in line and "has only 1 MB free" in line, line
    assert "memory:" not in done.stdout  # refused before the memory check and the solve
    assert list(small_file_system.iterdir()) == []


def test_full_file_system_mid_write_is_exit_3_without_files(tmp_path, small_file_system):
    # A line of points whose fields alone just fit: the checks before the solve pass, and
    # the file system fills up during the write.
    points = (free_bytes(small_file_system) - 2000) // 60
    (tmp_path / "m.nml").write_text(grid_model(points, 1))
    done = run_ddc2d(["m.nml", "-o", "small/out.h5"], tmp_path)
    assert done.returncode == 3, done.stderr
    [line] = error_lines(done)
    assert "writing small/out.h5 failed" in line and "file system is full" in line, line
    assert list(small_file_system.iterdir()) == []


def test_full_file_system_for_the_tables_is_exit_3_without_files(tmp_path,
                                                                  small_file_system):
    # gfortran does not report a full disk on buffered writes: the tables' size is checked.
    # A line of points whose rows (178 bytes and more) and element rows just fit the check
    # before the solve; the header and the element data overflow it.
    points = (free_bytes(small_file_system) - 10 * 299 - 100) // 178
    (tmp_path / "m.nml").write_text(grid_model(points, 1))
    done = run_ddc2d(["m.nml", "-o", "out.h5", "--res", "small/r.txt"], tmp_path)
    assert done.returncode == 3, done.stderr
    [line] = error_lines(done)
    assert "writing small/r.txt failed" in line and "file system is full" in line, line
    assert list(small_file_system.iterdir()) == []


# ------------------------------------------------------------- huge inputs

HUGE_TIMEOUT = 600.0
BASE_MODEL = ("&model youngs_modulus = 1.0, poissons_ratio = 0.25 /\n"
              "&fracture x = -1.0, 1.0, y = 0.0, 0.0, elements = 4, condition = 'traction', "
              "bc_n = -1.0 /\n")


def numbers(count, scale=1e-6):
    return ", ".join(f"{k * scale:.6f}" for k in range(count))


def write_rows(path, header, row, count, last):
    """A CSV of count equal rows, written in blocks: the test's own memory stays small, so
    that the peak memory measured (which includes the forked test before exec) is ddc2d's."""
    with open(path, "w") as f:
        f.write(header)
        f.writelines(row * min(100_000, count - start) for start in range(0, count, 100_000))
        f.write(last)


def write_huge(case, folder):
    """Write the input of a case; return the input's name and the size of what it reads."""
    if case == "long_comment":
        text = "! " + "c" * 100_000 + "\n" + BASE_MODEL
    elif case == "long_line":
        text = BASE_MODEL.replace("bc_n = -1.0", "bc_n = -1.0" + " " * 100_000)
    elif case == "long_title":
        text = BASE_MODEL.replace("0.25 /", "0.25, title = '" + "t" * 100_000 + "' /")
    elif case == "million_values":
        text = ("&model youngs_modulus = 1.0, poissons_ratio = 0.25 /\n"
                "&fracture condition = 'traction', bc_n = -1.0, elements = 1, x = "
                + numbers(1_000_000) + ", y = " + numbers(1_000_000, 0.0) + " /\n")
    elif case == "no_slash_last":
        text = BASE_MODEL + "&grid xmin = -1, xmax = 1, nx = 3, ymin = 1, ymax = 2, ny = 3\n"
    elif case == "no_slash_first":
        text = BASE_MODEL.replace("0.25 /", "0.25", 1)
    elif case == "csv_points":
        write_rows(folder / "rows.csv", "x, y\n", "0.5, 4.0\n", 10_000_000 - 1, "0.5, abc\n")
        text = BASE_MODEL + "&points file = 'rows.csv' /\n"
    else:  # csv_elements
        write_rows(folder / "rows.csv", "x_begin, y_begin, x_end, y_end, mu, sf, pressure\n",
                   "0,0,1,0,0.6,0,0\n", 10_000_000, "")
        text = "&model youngs_modulus = 1.0, poissons_ratio = 0.25 /\n" \
               "&fracture elements_file = 'rows.csv' /\n"
    (folder / "model.nml").write_text(text)
    return "model.nml", sum(p.stat().st_size for p in folder.iterdir())


# case: (exit status, what the message or the run must show)
HUGE_CASES = {
    "long_comment": (0, None),
    "long_line": (0, None),
    "long_title": (0, None),
    "million_values": (2, "more values than an array of this group holds"),
    "no_slash_last": (2, "a group not closed by /"),
    "no_slash_first": (2, "namelist not terminated"),
    "csv_points": (2, "rows.csv line 10000001: field 2 'abc' is not a number"),
    "csv_elements": (2, "rows.csv line 1000002: more than 1000000 data rows"),
}


def run_measured(args, cwd, timeout):
    """Run with a deadline; (exit status, stderr, peak resident memory in bytes)."""
    with open(cwd / "stderr.txt", "wb") as err:
        process = subprocess.Popen(args, cwd=cwd, stdout=subprocess.DEVNULL, stderr=err,
                                   env={**os.environ, "OMP_NUM_THREADS": "1",
                                        "OPENBLAS_NUM_THREADS": "1"})
        timer = threading.Timer(timeout, process.kill)
        timer.start()
        try:
            _, status, usage = os.wait4(process.pid, 0)
        finally:
            timer.cancel()
    process.returncode = os.waitstatus_to_exitcode(status)
    return process.returncode, (cwd / "stderr.txt").read_text(errors="replace"), \
        usage.ru_maxrss * 1024


@pytest.mark.parametrize("case", sorted(HUGE_CASES))
def test_huge_input_is_a_clear_message_or_a_correct_run(tmp_path, case):
    name, size = write_huge(case, tmp_path)
    status, expected = HUGE_CASES[case]
    code, stderr, peak = run_measured([str(ddc2d_exe()), name, "-o", "out.h5"], tmp_path,
                                      HUGE_TIMEOUT)
    assert code != -signal.SIGKILL, f"no answer within {HUGE_TIMEOUT} s"
    assert not any(mark in stderr for mark in CRASH_MARKS), stderr[-2000:]
    assert code == status, stderr[-2000:]
    # Memory in proportion to the input: its text, its numbers, and the program itself.
    assert peak < 4 * size + 300_000_000, f"peak memory {peak} bytes for {size} bytes of input"
    errors = [line for line in stderr.splitlines() if line.startswith("ddc2d: error")]
    if status == 0:
        assert errors == []
        assert_complete_h5(tmp_path / "out.h5")
        with h5py.File(tmp_path / "out.h5", "r") as f:
            stored = f.attrs["input_text"].decode()
            if "/input_text" in stored:  # a long input: the attribute points to the dataset
                stored = f["input_text"][0].decode()
        assert stored.strip() == (tmp_path / name).read_text().strip()
    else:
        assert len(errors) == 1 and expected in errors[0], stderr[-2000:]
        assert not (tmp_path / "out.h5").exists()
    assert partial_files(tmp_path) == []


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
    # The work criterion's trial kinks, and a flaw point that starts a crack
    "work_criterion.nml": "&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /\n"
                          "&remote_stress syy = 10.0, sxy = 5.0 /\n"
                          "&fracture x = -1.0, 1.0, y = 0.0, 0.0, elements = 10, mu = 0.0 /\n"
                          "&growth steps = 2, toughness = 1.0, increment = 0.2, "
                          "criterion = 'work', angle_step = 15 /\n",
    "flaw.nml": "&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /\n"
                "&remote_stress sxx = 10.0, syy = -20.0, sxy = 10.0 /\n"
                "&fracture x = -1.0, 1.0, y = 0.0, 0.0, elements = 1, mu = 0.6, sf = 2.0 /\n"
                "&growth steps = 2, toughness = 1.0e6, increment = 0.39 /\n"
                "&initiation tensile_strength = 5.0, probe_distance = 0.05, flaw_x = 0.0, "
                "flaw_y = 30.0, flaw_length = 0.2 /\n",
    # Hierarchical matrices (hmat-oss through src/linalg/hmatrix.c): an elastic solve with
    # a grid (rectangular field matrix), and a contact history (reduced systems, refinement)
    "hierarchical_cracks.nml": "&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /\n"
                               "&remote_stress syy = 10.0, sxy = 3.0 /\n"
                               "&fracture condition = 'traction', x = -1.0, 1.0, y = 0.0, 0.0, "
                               "elements = 40 /\n"
                               "&fracture condition = 'traction', x = -1.0, 0.5, y = 0.3, 1.2, "
                               "elements = 30 /\n"
                               "&grid xmin = -2, xmax = 2, nx = 9, ymin = -1, ymax = 2, ny = 7 /\n"
                               "&solver matrix = 'hierarchical', hmatrix_leaf_size = 8 /\n",
    "hierarchical_history.nml": "&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /\n"
                                "&remote_stress sxx = -5.0, syy = -20.0, sxy = 0.0 /\n"
                                "&fracture x = -1.0, 0.0, 0.8, y = 0.0, 0.0, 0.5, "
                                "elements = 30, 30, mu = 0.6, sf = 0.0, pressure = 12.0 /\n"
                                "&load_path sxy = 0.0, 8.0, -8.0, steps = 2, 2 /\n"
                                "&solver matrix = 'hierarchical', hmatrix_leaf_size = 8 /\n",
    "bad.nml": "&model youngs_modulus = -1.0, poissons_ratio = 0.25 /\n"
               "&fracture x = -1.0, 1.0, y = 0.0, 0.0, elements = 4, mu = 0.6 /\n",
}


def memcheck(args, cwd, threads=1):
    """Run ddc2d under valgrind memcheck (one thread unless told); return the finished
    process."""
    env = {k: v for k, v in os.environ.items() if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
    env.update(OMP_NUM_THREADS=str(threads), OPENBLAS_NUM_THREADS="1")
    return subprocess.run(["valgrind", "--error-exitcode=99", "--leak-check=full",
                           "--errors-for-leak-kinds=definite", str(ddc2d_exe()), *args,
                           "-o", "out.h5"], cwd=cwd, capture_output=True, text=True,
                          timeout=600, env=env)


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


def test_memcheck_on_two_threads_starts_once(tmp_path):
    # With several OpenMP threads the program runs itself again to set how they wait
    # (docs/performance.md#threads), but not under valgrind, whose tool that would start.
    (tmp_path / "kink.nml").write_text(MEMCHECK_MODELS["contact_kink.nml"])
    done = memcheck(["kink.nml"], tmp_path, threads=2)
    assert_memcheck_clean(done, 0)
    assert "openmp: 2 thread(s), spinning after each parallel region" in done.stdout


@pytest.mark.parametrize("example", sorted(p.name for p in (REPO_ROOT / "input").glob("*.nml")))
def test_memcheck_examples(tmp_path, example):
    # Every example, shrunk to at most 8 elements per segment and 6 x 6 grid points so that
    # valgrind takes seconds; a sweep runs its first task.
    text = shrink((REPO_ROOT / "input" / example).read_text())
    (tmp_path / example).write_text(text)
    args = [example] + (["--task", "0"] if "&sweep" in text.lower() else [])
    assert_memcheck_clean(memcheck(args, tmp_path), 0)
