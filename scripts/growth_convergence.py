#!/usr/bin/env python3
"""Convergence study of fracture growth (the command ddc2d-growth-convergence).

    scripts/growth_convergence.py --help

The command runs the module ddc2d.growth_convergence of the ddc2d Python package (python/, installed
editable into build/venv by scripts/setup.sh; docs/python.md), where it is documented.
Started by a Python that lacks the package or what it needs, it runs itself again with
build/venv's (scripts/ddc2d_venv.py).
"""

import sys

try:
    from ddc2d.growth_convergence import main
except ImportError as exc:
    from ddc2d_venv import rerun_in_venv  # beside this script: its folder is on sys.path

    rerun_in_venv("growth_convergence.py", exc, __file__)

if __name__ == "__main__":
    sys.exit(main())
