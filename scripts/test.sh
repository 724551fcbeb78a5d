#!/usr/bin/env bash
# Set everything up and run the whole test suite:
#   1. scripts/setup.sh --mpi (Debian packages, with Open MPI and ScaLAPACK, and the Python
#      venv, only what is missing);
#   2. the Debug build (-fcheck=all, -ffpe-trap=invalid,zero, -Werror) and every CTest test
#      through the `debug` workflow preset (configure, build, test): the Fortran suites, the
#      pytest files, the lint, valgrind memcheck and the sweep on a local Slurm
#      (labels fortran, python, lint, memcheck, slurm);
#   3. the MPI build (Debug, -Werror) and its tests through the `mpi` workflow preset
#      (label mpi: 1, 2 and 4 processes against the serial program, errors on 4 processes,
#      a 2-task job on the local Slurm);
#   4. the numerical suites again under other OpenBLAS kernels (scripts/test-kernels.sh).
# Exits non-zero when any step fails.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

scripts/setup.sh --mpi
cmake --workflow --preset debug
cmake --workflow --preset mpi
scripts/test-kernels.sh
