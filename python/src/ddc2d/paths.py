"""Where the ddc2d executable and the repository's folders are.

The package is installed editable from a working tree (scripts/setup.sh: build/venv), or
copied into a virtual environment (``pip install ./python``). In the first case the
tools keep their defaults inside the working tree (its builds, build/ for scratch files,
docs/gallery); in the second there is no working tree: the program is then one installed
by ``cmake --install`` (on PATH, into this Python environment's prefix, or where
$DDC2D_ROOT says, as the module file sets it), and the tools use the current folder.
"""

import os
import shutil
import sys
from pathlib import Path

#: The environment variable naming the executable (also read by the tests).
EXE_VARIABLE = "DDC2D_EXE"
#: The prefix of an installed ddc2d, as its module file sets it (packaging/lmod).
ROOT_VARIABLE = "DDC2D_ROOT"
#: Builds of a working tree, in the order tried (CMake presets).
PRESETS = ("release", "debug")


def source_tree():
    """The working tree this package runs from (python/src/ddc2d/ is in it), or None when
    the package was installed as a copy."""
    root = Path(__file__).resolve().parents[3]
    if (root / "python" / "pyproject.toml").is_file() and (root / "CMakeLists.txt").is_file():
        return root
    return None


def built_executable():
    """A ddc2d built in the working tree (release, then debug preset), or None."""
    root = source_tree()
    for preset in PRESETS if root else ():
        exe = root / "build" / preset / "app" / "ddc2d"
        if exe.is_file():
            return exe
    return None


def installed_executables():
    """Where `cmake --install` may have put ddc2d beside this package: the bin/ of this
    Python environment's prefix (`--prefix` of the venv: found though the venv is not
    activated, as in a Jupyter kernel), then of $DDC2D_ROOT."""
    prefixes = [sys.prefix] + ([os.environ[ROOT_VARIABLE]] if os.environ.get(ROOT_VARIABLE)
                               else [])
    return [Path(prefix) / "bin" / "ddc2d" for prefix in prefixes]


def find_executable(given=None):
    """The ddc2d executable: `given`, else $DDC2D_EXE, else ddc2d on PATH, else one
    installed beside this package (installed_executables), else a build of the working
    tree; None when there is none. An explicit choice comes before a search."""
    if given:
        return Path(given).resolve()
    if os.environ.get(EXE_VARIABLE):
        return Path(os.environ[EXE_VARIABLE]).resolve()
    on_path = shutil.which("ddc2d")
    if on_path:
        return Path(on_path).resolve()
    installed = [exe for exe in installed_executables() if os.access(exe, os.X_OK)]
    if installed:
        return installed[0].resolve()
    return built_executable()


def not_found_message(exe=None):
    """One line: no ddc2d program (at `exe`, when one was named), and how to point at it."""
    where = f" at {exe}" if exe else ""
    return (f"no ddc2d executable{where}: give executable=..., set {EXE_VARIABLE}=/path/to/"
            f"ddc2d, put ddc2d on PATH, or install it beside this package (cmake --install "
            f"BUILD --prefix {sys.prefix})")
