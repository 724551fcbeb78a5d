"""Where the ddc2d executable and the repository's folders are.

The package is installed editable from a working tree (scripts/setup.sh: build/venv), or
copied into a virtual environment (``pip install ./python``). In the first case the
tools keep their defaults inside the working tree (its builds, build/ for scratch files,
docs/gallery); in the second there is no working tree, and they look on PATH or use the
current folder instead.
"""

import os
import shutil
from pathlib import Path

#: The environment variable naming the executable (also read by the tests).
EXE_VARIABLE = "DDC2D_EXE"
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


def find_executable(given=None):
    """The ddc2d executable: `given`, else $DDC2D_EXE, else ddc2d on PATH, else a build of
    the working tree; None when there is none. An explicit choice comes before a search."""
    if given:
        return Path(given).resolve()
    if os.environ.get(EXE_VARIABLE):
        return Path(os.environ[EXE_VARIABLE]).resolve()
    on_path = shutil.which("ddc2d")
    if on_path:
        return Path(on_path).resolve()
    return built_executable()
