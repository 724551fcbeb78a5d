#!/usr/bin/env bash
# Build the API pages of ddc2d with FORD from the `!>` comments of src/ and app/:
#
#   scripts/build-api-docs.sh [OUTPUT_DIR]     (default build/api; open OUTPUT_DIR/index.html)
#
# FORD comes from the venv of scripts/setup.sh (build/venv). Exits non-zero when FORD fails
# or warns, so that the CTest api_docs keeps the pages free of warnings.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
output="$(realpath -m "${1:-$repo_root/build/api}")"
ford="$repo_root/build/venv/bin/ford"
[[ -x "$ford" ]] || { echo "build-api-docs: no $ford: run scripts/setup.sh" >&2; exit 2; }

log="$(mktemp)"
trap 'rm -f "$log"' EXIT
cd "$repo_root/docs/api"
"$ford" --output_dir "$output" ford.md > "$log" 2>&1 || { cat "$log"; exit 1; }
if grep -qi 'warning' "$log"; then
    cat "$log"
    echo "build-api-docs: FORD warned (above)" >&2
    exit 1
fi
echo "build-api-docs: the API pages are in $output/index.html"
