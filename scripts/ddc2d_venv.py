"""Run a script of scripts/ with the project's venv when this Python lacks its packages.

scripts/setup.sh installs the ddc2d Python package (python/) with numpy, h5py, matplotlib
and xarray into build/venv, not into the system Python, so that ``scripts/ddc2d-plot
RESULT.h5`` started by the ``#!/usr/bin/env python3`` of a plain shell would not find them.
Every script of scripts/ is a shim that imports its command from the package in a ``try``
and, on ImportError, calls ``rerun_in_venv`` (the script's own folder, where this module
lives, is on sys.path for a script run directly):

    try:
        from ddc2d.plot.cli import main
    except ImportError as exc:
        from ddc2d_venv import rerun_in_venv
        rerun_in_venv(PROGRAM, exc, __file__)

which runs the script again, with the same arguments, by build/venv/bin/python (the process
is replaced: nothing after the call runs), unless this Python already is the venv's (then
the venv lacks the package too, and a second try would not help): then it prints one line
that says what is missing and exits with status 2. This module imports nothing outside the
standard library.
"""

import os
import sys
from pathlib import Path

#: The project's venv (scripts/setup.sh).
VENV = Path(__file__).resolve().parents[1] / "build" / "venv"
#: Exit status of a script that cannot run (the scripts' "bad usage or input").
EXIT_MISSING = 2


def in_venv(venv=VENV):
    """True when this Python is the venv's (also when started through a link to it)."""
    return Path(sys.prefix).resolve() == venv.resolve()


def rerun_in_venv(program, error, script, argv=None, venv=VENV):
    """Replace this process by `script` run with `venv`'s Python and `argv` (default: this
    process's arguments), or, when there is no such Python or this is it, print what is
    missing (`error`, the ImportError) and exit with EXIT_MISSING. Never returns."""
    python = venv / "bin" / "python"
    arguments = sys.argv[1:] if argv is None else list(argv)
    if python.is_file() and not in_venv(venv):
        sys.stdout.flush()
        sys.stderr.flush()
        os.execv(python, [str(python), str(Path(script).resolve()), *arguments])
    where = f"{venv}'s Python lacks it too" if python.is_file() else f"there is no {python}"
    print(f"{program}: error: the Python package {error.name or error} is missing and "
          f"{where}: run scripts/setup.sh", file=sys.stderr)
    sys.exit(EXIT_MISSING)
