#!/usr/bin/env bash
# Set everything up and run the whole test suite:
#   1. scripts/setup.sh --mpi --tests (Debian packages, with Open MPI and ScaLAPACK, the
#      Python venv and pFUnit, only what is missing: pFUnit is built once into build/pfunit,
#      from $PFUNIT_SOURCE when set, unless CMake finds an installed one);
#   2. the Debug build (-fcheck=all, -ffpe-trap=invalid,zero, -Werror) and every CTest test
#      through the `debug` workflow preset (configure, build, test): the pFUnit suites, the
#      pytest files, the lint, valgrind memcheck (labels fortran, python, lint, memcheck);
#      then the `slurm` test preset: the sweep on a local Slurm (label slurm, which the
#      `debug` test preset leaves out: it starts daemons as root);
#   3. the MPI build (Debug, -Werror) and its tests through the `mpi` workflow preset
#      (label mpi: 1, 2 and 4 processes against the serial program, errors on 4 processes),
#      then the `mpi-slurm` test preset (a 2-task job on the local Slurm);
#   4. the numerical suites again under other OpenBLAS kernels (scripts/test-kernels.sh);
#   5. the process-level tests (python_robustness, python_memory, the Slurm tests and the
#      MPI build's process-level cases) a second time beside a CPU hog
#      (stress-ng --cpu 4, bounded by --timeout and stopped when they end), so that a test
#      that races with a process or a file, or assumes an idle machine, fails here. The
#      fuzz test makes DDC2D_FUZZ_COUNT=400 runs in this pass (2000 in the first).
# Exits non-zero when any step fails.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

scripts/setup.sh --mpi --tests
cmake --workflow --preset debug
ctest --preset slurm
cmake --workflow --preset mpi
ctest --preset mpi-slurm
scripts/test-kernels.sh

# 5. Under load. The hog stops by itself after hog_limit seconds should this script die.
hog_limit=1500
say() { echo "test.sh: $*"; }
say "process-level tests again beside stress-ng --cpu 4 (at most ${hog_limit} s)"
stress-ng --cpu 4 --timeout "${hog_limit}s" --quiet &
hog=$!
trap 'kill "$hog" 2>/dev/null || true' EXIT
start=$SECONDS
DDC2D_FUZZ_COUNT=400 ctest --preset debug -R '^(python_robustness|python_memory)$'
ctest --preset slurm
# The MPI build's process-level cases: agreement on an error, resume, one rank, the
# collectives, and one whole distributed solve (the other numerical cases gain nothing
# from a loaded machine but time).
ctest --preset mpi -R '^(mpi_error|mpi_resume|mpi_one_process|mpi_straight|parallel_collective)$'
ctest --preset mpi-slurm
kill "$hog" 2>/dev/null || true
wait "$hog" 2>/dev/null || true
say "process-level tests passed under load in $((SECONDS - start)) s"
