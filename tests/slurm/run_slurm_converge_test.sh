#!/usr/bin/env bash
# Integration test of ddc2d-converge --slurm on a real Slurm (single node, localhost):
#
#   run_slurm_converge_test.sh DDC2D_EXE WORK_DIR
#
# Starts a Slurm of its own as run_slurm_test.sh does (local_slurm.sh; skipped, exit 77,
# where it cannot), submits the three levels of the paper's fault (input/paper_fault_slip.nml
# without its map) as a job array with scripts/converge.py --slurm, waits, gathers them with
# --collect, and checks that every level ran as one task of the array and that K_II (from
# the tip element) extrapolates to its closed form 4.38 sqrt(pi) within 1e-3.
set -euo pipefail

skip() { echo "SKIPPED: $*; exclude this test with: ctest --preset debug -LE slurm"; exit 77; }

if [[ $# -ne 2 ]]; then
    echo "usage: $0 DDC2D_EXE WORK_DIR" >&2
    exit 2
fi
exe="$(realpath "$1")"
work="$(realpath -m "$2")"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
python="${DDC2D_PYTHON:-$repo/build/venv/bin/python}"
wait_limit=600
start_time=$SECONDS

say() { printf '[slurm converge %4ds] %s\n' $((SECONDS - start_time)) "$*"; }
fail() { say "FAIL: $*"; exit 1; }

[[ -x "$exe" ]] || fail "no executable $exe"
[[ -x "$python" ]] || fail "no Python at $python (run scripts/setup.sh or set DDC2D_PYTHON)"

# shellcheck source=local_slurm.sh
source "$repo/tests/slurm/local_slurm.sh"
require_local_slurm "the Slurm test of ddc2d-converge"
start_local_slurm "$work" "$python"

model="$work/paper_fault_slip.nml"
grep -v '^&grid' "$repo/input/paper_fault_slip.nml" >"$model"
# K from the tip element: a first-order quantity the study extrapolates (the default
# higher-order re-solve's K is within 1e-5 on every level).
echo "&solver k_method = 'tip_element' /" >>"$model"
out="$work/study"
job=$("$python" "$repo/scripts/converge.py" "$model" --exe "$exe" -o "$out" --slurm \
    --job-name ddc2d-converge-test)
[[ "$job" =~ ^[0-9]+$ ]] || fail "converge.py --slurm printed '$job', not a job id"
say "submitted the levels as job $job"
deadline=$((SECONDS + wait_limit))
while [[ -n "$(squeue -h -j "$job" -o %i 2>/dev/null)" ]]; do
    ((SECONDS < deadline)) || fail "job $job not done within ${wait_limit} s"
    sleep 0.5
done
for level in 0 1 2; do
    [[ -f "$out/paper_fault_slip_level$level.h5" ]] || fail "level $level wrote no result"
    [[ -f "$out/logs/paper_fault_slip_${job}_$level.out" ]] || fail "no log of task $level"
done
"$python" "$repo/scripts/converge.py" "$model" -o "$out" --collect >"$work/collect.txt" \
    || fail "--collect failed: $(cat "$work/collect.txt")"
"$python" - "$out/STUDY.json" <<'PY' || fail "K_II of the study is off (above)"
import json, math, sys
entry = json.load(open(sys.argv[1]))["quantities"]["k2/fault/end"]
exact = 4.38 * math.sqrt(math.pi)
print("K_II per level", entry["values"], "extrapolated", entry["extrapolated"])
sys.exit(0 if abs(entry["extrapolated"] - exact) <= 1e-3 * exact else 1)
PY
say "PASS: the three levels ran as job $job; K_II extrapolates to 4.38 sqrt(pi)"
