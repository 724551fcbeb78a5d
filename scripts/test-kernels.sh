#!/usr/bin/env bash
# Run the numerical test suites (CTest labels fortran and python) of the Debug build again
# with OpenBLAS on other kernels, so that no result depends on the CPU:
#
#   scripts/test-kernels.sh [CORE ...]     (default: native Nehalem Sandybridge Haswell)
#
# `native` is the kernel OpenBLAS picks for this CPU by itself (OPENBLAS_CORETYPE unset);
# the others are forced with OPENBLAS_CORETYPE. Nehalem (SSE only), Sandybridge (AVX) and
# Haswell (AVX2) run on any x86-64 machine of the last ten years. Each kernel is checked to
# be the one in use (OPENBLAS_VERBOSE=2 prints "Core: <name>"); a kernel the suites already
# ran with (the environment's, used by `ctest --preset debug` in scripts/test.sh, or an
# earlier one of the list) is not run twice; Haswell counts as tested where the native
# kernel is Zen (see below). Left out (they run in the main pass and, the
# process-level ones, again under load): python_robustness and python_robustness_huge
# (fuzzed and huge inputs, signals, file
# types, file-size and disk limits: how the program treats files and processes), python_plot
# (figures of synthetic result files; its few solved models check that what is drawn equals
# what the same run stored), python_comp2ddm (workbooks to namelists; the paper's model it
# solves is solved under every kernel by the contact suite and python_examples), python_venv
# (the scripts from a plain shell), python_figures (where a figure's parts lie on its
# canvas), python_converge (verdicts of refinement studies at 1e-3 and wider; the models
# it refines are solved under every kernel by the contact suite and python_examples),
# python_memory (the memory estimate against what a process may allocate, and the refusal
# of a model too large) and python_benchmark (the benchmark's records and timings): nothing
# they check depends on the last bits of a solve. Needs a configured and
# built debug preset (scripts/test.sh makes it). Exits non-zero when a kernel cannot be
# forced or a test fails.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
exe=build/debug/app/ddc2d
[[ -x "$exe" ]] || { echo "test-kernels: no $exe: run scripts/test.sh first" >&2; exit 2; }

# The kernel OpenBLAS uses with the given OPENBLAS_CORETYPE ('' for the native one).
kernel_in_use() {
    if [[ -n "$1" ]]; then
        OPENBLAS_VERBOSE=2 OPENBLAS_CORETYPE="$1" "$exe" --version 2>&1 >/dev/null
    else
        env -u OPENBLAS_CORETYPE OPENBLAS_VERBOSE=2 "$exe" --version 2>&1 >/dev/null
    fi | sed -n 's/^Core: //p'
}

left_out='^(python_robustness|python_robustness_huge|python_plot|python_comp2ddm|python_venv|python_figures|python_converge|python_memory|python_benchmark)$'
requested=("$@")
((${#requested[@]} > 0)) || requested=(native Nehalem Sandybridge Haswell)
done_cores=("$(OPENBLAS_VERBOSE=2 "$exe" --version 2>&1 >/dev/null | sed -n 's/^Core: //p')")
echo "test-kernels: the main run used kernel ${done_cores[0]:-unknown}" \
     "(OPENBLAS_CORETYPE in the environment: ${OPENBLAS_CORETYPE:-not set})"
# OpenBLAS's Zen target uses Haswell's dgemm, dtrsm and dgemv kernels: on an AMD EPYC
# (2026-11-27) five example models gave the same bits with the native Zen kernel and with
# Haswell forced (and other bits with Sandybridge), so a run on Zen has tested Haswell.
if [[ " ${done_cores[*]} " == *" Zen "* ]]; then
    echo "test-kernels: Zen uses OpenBLAS's Haswell kernels: Haswell counts as tested"
    done_cores+=(Haswell)
fi
ran=()
for core in "${requested[@]}"; do
    forced="$core"
    [[ "$core" == native ]] && forced=""
    used=$(kernel_in_use "$forced")
    if [[ -n "$forced" && "$used" != "$forced" ]]; then
        echo "test-kernels: OPENBLAS_CORETYPE=$forced gave kernel '${used:-none}'" >&2
        exit 1
    fi
    if [[ " ${done_cores[*]} " == *" $used "* ]]; then
        echo "test-kernels: kernel $used ($core) already tested"
        continue
    fi
    echo "test-kernels: the numerical suites with OpenBLAS kernel $used ($core)"
    if [[ -n "$forced" ]]; then
        OPENBLAS_CORETYPE="$forced" ctest --preset debug -L 'fortran|python' -E "$left_out"
    else
        env -u OPENBLAS_CORETYPE ctest --preset debug -L 'fortran|python' -E "$left_out"
    fi
    done_cores+=("$used")
    ran+=("$used")
done
echo "test-kernels: every suite passed with kernels ${ran[*]} (and ${done_cores[0]} in the" \
     "main run)"
