"""The ddc2d Python package installed as users and developers install it (docs/python.md):

* ``pip install ./python`` into an empty virtual environment pulls numpy, h5py, matplotlib
  and xarray from PyPI, and every console entry point runs there;
* that copy, which knows no working tree, runs the program that ``cmake --install`` put
  under $DDC2D_ROOT or into the venv's own prefix (neither on PATH), and without one says
  in one line how to point at it;
* scripts/setup.sh installs the package of its own working tree editable into build/venv,
  and its completeness check counts it: a venv made before, with every other package,
  gets it on the next run, and the run after that finds it ready.

They install from a copy of python/ in a temporary folder (pip writes build files beside
the sources), which also shows that python/ builds alone: the installed package has the
program's version (DDC2D_VERSION: project(VERSION), given by CTest) and the MIT licence;
the program from DDC2D_BUILD_DIR (default build/debug) with DDC2D_CMAKE.
They need PyPI or pip's cache; CTest label install.
"""

import math
import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
BUILD_DIR = Path(os.environ.get("DDC2D_BUILD_DIR", REPO_ROOT / "build" / "debug"))
CMAKE = os.environ.get("DDC2D_CMAKE", "cmake")
#: The console entry points of python/pyproject.toml.
ENTRY_POINTS = ("ddc2d-plot", "collect-sweep", "submit-sweep", "twodd2nml", "comp2ddm2nml",
                "compare-twodd", "ddc2d-benchmark", "ddc2d-growth-convergence",
                "ddc2d-verification-table", "ddc2d-converge")
#: pip's network waits are its own; the whole install takes a minute or two.
TIMEOUT = 1200


def clean_environment():
    """This environment without an active venv or Python path: nothing of build/venv leaks
    into the new venv."""
    return {key: value for key, value in os.environ.items()
            if key not in ("VIRTUAL_ENV", "PYTHONPATH", "PYTHONHOME")}


def run(args, cwd):
    return subprocess.run([str(a) for a in args], cwd=cwd, env=clean_environment(),
                          capture_output=True, text=True, timeout=TIMEOUT)


def copy_package(destination):
    """python/ without what an earlier install left in it."""
    shutil.copytree(REPO_ROOT / "python", destination,
                    ignore=shutil.ignore_patterns("*.egg-info", "build", "__pycache__"))
    return destination


def make_venv(path, cwd):
    done = run([sys.executable, "-m", "venv", path], cwd)
    assert done.returncode == 0, done.stderr
    return path / "bin" / "python"


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """An empty venv into which `pip install ./python` installed the package: its folder."""
    root = tmp_path_factory.mktemp("pip")
    python = make_venv(root / "venv", root)
    assert run([python, "-c", "import numpy"], root).returncode != 0  # empty indeed
    done = run([python, "-m", "pip", "install", "--quiet", copy_package(root / "python")],
               root)
    assert done.returncode == 0, done.stdout + done.stderr
    return root / "venv"


def test_pip_install_into_an_empty_venv(installed):
    python, folder = installed / "bin" / "python", installed.parent
    show = ("import ddc2d, xarray; from importlib import metadata; print(ddc2d.__file__); "
            "print(ddc2d.__version__); print(metadata.version('ddc2d')); "
            "print(metadata.metadata('ddc2d')['License-Expression'])")
    done = run([python, "-c", show], folder)
    assert done.returncode == 0, done.stderr
    where, version, distribution_version, licence = done.stdout.split()
    assert Path(where).is_relative_to(installed)
    assert (Path(where).parent / "py.typed").is_file(), "the hints are not marked (PEP 561)"
    assert version == distribution_version == os.environ["DDC2D_VERSION"]
    assert licence == "MIT"
    for name in ENTRY_POINTS:
        done = run([installed / "bin" / name, "--help"], folder)
        assert done.returncode == 0, f"{name}: {done.stderr}"
        assert done.stdout.startswith("usage: "), f"{name}: {done.stdout}"
    # Without the extra 'workbooks', comp2ddm2nml says in one line what to install.
    (folder / "book.xlsx").write_bytes(b"")
    done = run([installed / "bin" / "comp2ddm2nml", "book.xlsx"], folder)
    assert done.returncode == 2
    assert done.stderr.strip().splitlines() == [
        ("comp2ddm2nml: error: the Python package openpyxl is missing: install it (pip "
         "install 'ddc2d[workbooks]'; in the repository: scripts/setup.sh)")]


#: Runs the namelist argv[1] with ddc2d.run (output argv[2]) and prints K_I of its first tip;
#: prints the error and exits 3 when no program is found.
RUN_MODEL = """\
import sys, ddc2d
try:
    result = ddc2d.run(sys.argv[1], output=sys.argv[2])
except FileNotFoundError as error:
    print(error)
    sys.exit(3)
print(result.tips["k1"][0])
"""


def test_the_copy_runs_the_installed_program(installed, tmp_path):
    """Not on PATH: nothing found (one line: how to point at it), then the program of a
    prefix named by DDC2D_ROOT, then the one installed into the venv's own prefix."""
    python = installed / "bin" / "python"
    model = shutil.copy(REPO_ROOT / "input" / "pressurized_crack.nml", tmp_path)
    environment = {key: value for key, value in clean_environment().items()
                   if key not in ("DDC2D_EXE", "DDC2D_ROOT")}
    environment["PATH"] = "/usr/bin:/bin"
    assert shutil.which("ddc2d", path=environment["PATH"]) is None

    def run_model(output, **extra):
        return subprocess.run([str(python), "-c", RUN_MODEL, str(model), str(output)],
                              cwd=tmp_path, env={**environment, **extra}, capture_output=True,
                              text=True, timeout=TIMEOUT)

    done = run_model(tmp_path / "none.h5")
    assert done.returncode == 3, done.stdout + done.stderr
    message = done.stdout.strip()
    assert "\n" not in message and message.startswith("no ddc2d executable: "), message
    assert "DDC2D_EXE=" in message and f"cmake --install BUILD --prefix {installed}" in message
    k_exact = 10.0 * math.sqrt(math.pi)  # p sqrt(pi a) of the example's crack
    prefix = tmp_path / "prefix"
    for where, extra in ((prefix, {"DDC2D_ROOT": str(prefix)}), (installed, {})):
        done = run([CMAKE, "--install", BUILD_DIR, "--prefix", where], tmp_path)
        assert done.returncode == 0, done.stdout + done.stderr
        done = run_model(tmp_path / f"{where.name}.h5", **extra)
        assert done.returncode == 0, done.stdout + done.stderr
        assert abs(float(done.stdout) - k_exact) <= 0.01 * k_exact, done.stdout


def test_setup_installs_the_package_of_its_working_tree(tmp_path):
    """A working tree whose build/venv has every package (through a path file to this
    tree's build/venv) and the linters but not its own ddc2d package."""
    clone = tmp_path / "clone"
    (clone / "scripts").mkdir(parents=True)
    shutil.copy(REPO_ROOT / "scripts" / "setup.sh", clone / "scripts")
    copy_package(clone / "python")
    venv = clone / "build" / "venv"
    python = make_venv(venv, tmp_path)
    ours = sysconfig.get_path("purelib")  # build/venv's site-packages: this test runs there
    purelib = run([python, "-c", "import sysconfig; print(sysconfig.get_path('purelib'))"],
                  tmp_path).stdout.strip()
    # A plain path line: build/venv's own path files (its editable ddc2d) are not read.
    (Path(purelib) / "project_packages.pth").write_text(ours + "\n")
    for tool in ("ruff", "fortitude", "mypy"):
        (venv / "bin" / tool).symlink_to(Path(sys.prefix) / "bin" / tool)
    before = run([python, "-c", "import ddc2d"], tmp_path)
    assert before.returncode != 0, "the clone's venv already imports a ddc2d package"

    first = run(["bash", clone / "scripts" / "setup.sh"], tmp_path)
    assert first.returncode == 0, first.stdout + first.stderr
    assert f"installing the ddc2d package of {clone}/python (editable)" in first.stdout
    done = run([python, "-c", "import ddc2d; print(ddc2d.__file__)"], tmp_path)
    assert Path(done.stdout.strip()) == clone / "python" / "src" / "ddc2d" / "__init__.py"

    second = run(["bash", clone / "scripts" / "setup.sh"], tmp_path)
    assert second.returncode == 0, second.stdout + second.stderr
    assert "Python venv ready" in second.stdout and "installing" not in second.stdout
