#!/usr/bin/env python3
"""How far a model's results are from the converged ones (the command ddc2d-converge).

    scripts/converge.py MODEL.nml --help

The command runs the module ddc2d.converge.cli of the ddc2d Python package (python/, installed
editable into build/venv by scripts/setup.sh; docs/python.md), where it is documented.
Started by a Python that lacks the package or what it needs, it runs itself again with
build/venv's (scripts/ddc2d_venv.py).
"""

import sys

try:
    from ddc2d.converge.cli import main
except ImportError as exc:
    from ddc2d_venv import rerun_in_venv  # beside this script: its folder is on sys.path

    rerun_in_venv("converge.py", exc, __file__)

if __name__ == "__main__":
    sys.exit(main())
