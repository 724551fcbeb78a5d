#!/usr/bin/env bash
# Set everything up and run the whole test suite:
#   1. scripts/setup.sh (Debian packages and the Python venv, only what is missing);
#   2. the Debug build (-fcheck=all, -ffpe-trap=invalid,zero, -Werror) and every CTest test
#      through the `debug` workflow preset (configure, build, test): the Fortran suites, the
#      pytest files, the lint, valgrind memcheck and the sweep on a local Slurm
#      (labels fortran, python, lint, memcheck, slurm);
#   3. the numerical suites again under other OpenBLAS kernels (scripts/test-kernels.sh).
# Exits non-zero when any step fails.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

scripts/setup.sh
cmake --workflow --preset debug
scripts/test-kernels.sh
