"""Every script of scripts/ runs as docs/plotting.md#how-the-scripts-run writes it, from a plain
shell: with only the system's python3 on PATH (no venv activated, no ddc2d package nor numpy,
h5py, matplotlib, xlrd, openpyxl), a Python script, a thin command over the ddc2d package,
runs itself again with build/venv's Python (scripts/ddc2d_venv.py), so that
`scripts/ddc2d-plot RESULT.h5 -o DIR` works as written; without a venv it says in one line
what is missing."""

import os
import shutil
import subprocess
import sys

import pytest

from conftest import REPO_ROOT, SCRIPTS, write_result

#: Folders of a plain shell's PATH: the system's python3, no venv, no pyenv.
SYSTEM_PATH = "/usr/bin:/bin"
#: Every command-line script of scripts/ (Python and shell).
COMMANDS = ("ddc2d-plot", "collect-sweep", "compare-twodd", "benchmark.py", "comp2ddm2nml",
            "twodd2nml", "submit-sweep", "make-gallery", "growth_convergence.py", "converge.py",
            "verification-table", "ddc2d-seas")
#: The Python scripts: each runs a module of the ddc2d package (python/, in build/venv).
NEEDS_VENV = {name: "ddc2d" for name in COMMANDS if name != "make-gallery"}


def plain_environment():
    """The environment of a plain shell: PATH without the venv, no Python variables."""
    env = {key: value for key, value in os.environ.items()
           if key not in ("VIRTUAL_ENV", "PYTHONPATH", "PYTHONHOME", "PYENV_VERSION")}
    env["PATH"] = SYSTEM_PATH
    return env


def system_python():
    """The python3 of a plain shell (skip when the system has none)."""
    python = shutil.which("python3", path=SYSTEM_PATH)
    if python is None:
        pytest.skip(f"no python3 in {SYSTEM_PATH}")
    return python


def run_plain(args, cwd):
    return subprocess.run([str(a) for a in args], cwd=cwd, env=plain_environment(),
                          capture_output=True, text=True, timeout=300, check=False)


def test_every_script_is_listed():
    """A new script of scripts/ gets a line here (or is a module, *.py without a main)."""
    commands = {path.name for path in SCRIPTS.iterdir()
                if path.is_file() and os.access(path, os.X_OK) and path.suffix != ".sh"}
    assert commands == set(COMMANDS)


@pytest.mark.parametrize("name", COMMANDS)
def test_help_runs_from_a_plain_shell(name, tmp_path):
    system_python()
    done = run_plain([SCRIPTS / name, "--help"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert "usage" in done.stdout.lower() or name in done.stdout, done.stdout
    assert done.stderr == ""


def test_the_system_python_lacks_what_the_scripts_need():
    """Otherwise the tests above would not show the rerun (they pass all the same)."""
    done = subprocess.run([system_python(), "-c", "import ddc2d"], env=plain_environment(),
                          capture_output=True, text=True, timeout=60, check=False)
    if done.returncode == 0:
        pytest.skip("the system python3 has the ddc2d package: nothing to rerun")


def test_plot_from_a_plain_shell_as_the_readme_writes_it(tmp_path):
    """scripts/ddc2d-plot RESULT.h5 -o DIR (docs/plotting.md), started by the system's
    python3 through the script's #! line."""
    system_python()
    result = write_result(tmp_path / "small.h5")
    done = run_plain([SCRIPTS / "ddc2d-plot", result, "-o", tmp_path / "figures"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "figures" / "small_map_grid1_max_shear.png").is_file()
    assert (tmp_path / "figures" / "small_tips.csv").is_file()


@pytest.mark.parametrize("name", sorted(NEEDS_VENV))
def test_without_a_venv_one_line_says_what_is_missing(name, tmp_path):
    """A copy of scripts/ in a folder without build/venv, started by a Python that lacks
    the packages (-S: no site packages): exit status 2 and one line naming the package."""
    copy = tmp_path / "clone" / "scripts"
    shutil.copytree(SCRIPTS, copy, ignore=shutil.ignore_patterns("__pycache__"))
    done = subprocess.run([sys.executable, "-S", str(copy / name), "--help"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=60, check=False)
    if name == "comp2ddm2nml":  # its packages are needed only for a workbook
        done = subprocess.run([sys.executable, "-S", str(copy / name), "book.xlsx"],
                              cwd=tmp_path, capture_output=True, text=True, timeout=60,
                              check=False)
    assert done.returncode == 2, done.stdout + done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"{name}: error: the Python package ")
    assert "missing" in lines[0] and "scripts/setup.sh" in lines[0]
    assert f"package {NEEDS_VENV[name]} is missing" in lines[0]
    # The copy's own (absent) venv is named, not the repository's (the copy may lie in the
    # repository's build tree: CTest's temporary folders).
    assert f"{REPO_ROOT.as_posix()}/build/venv" not in lines[0]
