#!/usr/bin/env bash
# One model on two processes through Slurm (docs/mpi.md#submit), on a single-node Slurm
# started as for the sweep test (local_slurm.sh):
#
#   run_slurm_mpi_test.sh DDC2D_EXE DDC2D_SERIAL_EXE MPIEXEC WORK_DIR
#
# A batch job with 2 tasks runs the MPI ddc2d on tests/data/mpi/kinked_fault.nml twice:
# with `srun --mpi=pmix` (the Slurm way; the configuration's MpiDefault is none, as on many
# clusters, so the job asks for PMIx itself) and with Open MPI's mpiexec (which takes the
# allocation from Slurm's environment). Both results must equal the serial program's
# (tests/compare_results.py: 1e-10 of the largest magnitude of each kind of quantity, states
# equal) and record
# 2 processes. Every wait has a timeout.
#
# Like the sweep test it needs root and a machine without a Slurm of its own; elsewhere it
# says why and exits 77 (skipped). Exclude it with `ctest --preset mpi -LE slurm`.
set -euo pipefail

skip() { echo "SKIPPED: $*; exclude this test with: ctest --preset mpi -LE slurm"; exit 77; }

if [[ $# -ne 4 ]]; then
    echo "usage: $0 DDC2D_EXE DDC2D_SERIAL_EXE MPIEXEC WORK_DIR" >&2
    exit 2
fi
exe="$(realpath "$1")"
serial="$(realpath "$2")"
mpiexec="$3"
work="$(realpath -m "$4")"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
python="${DDC2D_PYTHON:-$repo/build/venv/bin/python}"
model="$repo/tests/data/mpi/kinked_fault.nml"
wait_limit=600
start_time=$SECONDS

say() { printf '[slurm mpi test %4ds] %s\n' $((SECONDS - start_time)) "$*"; }
fail() { say "FAIL: $*"; exit 1; }

[[ -x "$exe" && -x "$serial" ]] || fail "no executables $exe, $serial"
[[ -x "$python" ]] || fail "no Python at $python (run scripts/setup.sh or set DDC2D_PYTHON)"

# shellcheck source=local_slurm.sh
source "$repo/tests/slurm/local_slurm.sh"
require_local_slurm "the Slurm MPI test"
start_local_slurm "$work" "$python"

OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 "$serial" "$model" -o "$work/serial.h5" >/dev/null \
    || fail "the serial run failed"
{
    echo '#!/bin/bash'
    echo '#SBATCH --job-name=ddc2d-mpi-test'
    echo '#SBATCH --ntasks=2'
    echo '#SBATCH --cpus-per-task=1'
    echo '#SBATCH --time=00:05:00'
    echo "#SBATCH --output=$work/job.out"
    echo 'set -e'
    echo '# Open MPI as root (this test runs as root); the threads of each task are its cores.'
    echo 'export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1'
    echo 'export OMP_NUM_THREADS=$SLURM_CPUS_PER_TASK OPENBLAS_NUM_THREADS=$SLURM_CPUS_PER_TASK'
    echo "srun --mpi=pmix '$exe' '$model' -o '$work/srun.h5'"
    echo "'$mpiexec' '$exe' '$model' -o '$work/mpiexec.h5'"
} >"$work/job.sbatch"
phase=$SECONDS
job=$(timeout "$wait_limit" sbatch --parsable --wait "$work/job.sbatch") \
    || fail "the job failed or timed out; its output:
$(grep -v 'array temporary\|^At line' "$work/job.out" 2>/dev/null || true)"
say "job $job (2 tasks) done in $((SECONDS - phase)) s"
for launcher in srun mpiexec; do
    "$python" "$repo/tests/compare_results.py" "$work/serial.h5" "$work/$launcher.h5" \
        --processes 2 || fail "the $launcher result differs from the serial run"
done
say "PASS: srun --mpi=pmix and mpiexec in a 2-task batch job give the serial answer"
