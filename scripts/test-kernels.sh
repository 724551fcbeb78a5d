#!/usr/bin/env bash
# Run the numerical test suites (CTest labels fortran and python) of the Debug build again
# with OpenBLAS forced to other kernels, so that no result depends on the CPU:
#
#   scripts/test-kernels.sh [CORE ...]     (default: Nehalem Sandybridge Haswell)
#
# Each kernel is checked to be the one in use (OPENBLAS_VERBOSE=2 prints "Core: <name>")
# before its run. Nehalem (SSE only), Sandybridge (AVX) and Haswell (AVX2) run on any
# x86-64 machine of the last ten years. Needs a configured and built debug preset
# (scripts/test.sh makes it). Exits non-zero when a kernel cannot be forced or a test fails.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
exe=build/debug/app/ddc2d
[[ -x "$exe" ]] || { echo "test-kernels: no $exe: run scripts/test.sh first" >&2; exit 2; }

cores=("$@")
((${#cores[@]} > 0)) || cores=(Nehalem Sandybridge Haswell)
native_core=$(env -u OPENBLAS_CORETYPE OPENBLAS_VERBOSE=2 "$exe" --version 2>&1 >/dev/null \
              | sed -n 's/^Core: //p')
echo "test-kernels: this CPU's own OpenBLAS kernel is ${native_core:-unknown}" \
     "(OPENBLAS_CORETYPE in the environment: ${OPENBLAS_CORETYPE:-not set})"
for core in "${cores[@]}"; do
    used=$(OPENBLAS_VERBOSE=2 OPENBLAS_CORETYPE="$core" "$exe" --version 2>&1 >/dev/null \
           | sed -n 's/^Core: //p')
    if [[ "$used" != "$core" ]]; then
        echo "test-kernels: OPENBLAS_CORETYPE=$core gave kernel '${used:-none}'" >&2
        exit 1
    fi
    echo "test-kernels: the numerical suites with OpenBLAS kernel $core"
    OPENBLAS_CORETYPE="$core" ctest --preset debug -L 'fortran|python'
done
echo "test-kernels: every suite passed with kernels ${cores[*]}"
