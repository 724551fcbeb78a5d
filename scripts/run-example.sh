#!/usr/bin/env bash
# Set everything up, build the Release executable and run an example end to end:
#
#   scripts/run-example.sh [MODEL.nml]     (default: input/paper_fault_slip.nml)
#
# writes results/<model>.h5 and the figures of scripts/ddc2d-plot into results/.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
model="$(realpath "${1:-$repo_root/input/paper_fault_slip.nml}")"
cd "$repo_root"

scripts/setup.sh
cmake --preset release
cmake --build --preset release

name="$(basename "${model%.*}")"
mkdir -p results
build/release/app/ddc2d "$model" -o "results/$name.h5"
build/venv/bin/python scripts/ddc2d-plot "results/$name.h5" -o results
echo "run-example: result file results/$name.h5 and the figures above are in $repo_root/results"
