#!/usr/bin/env bash
# Make pFUnit 4.14 (the Fortran test framework) available to the test build, once:
#
#   scripts/setup-pfunit.sh        (run by scripts/setup.sh --tests)
#
# 1. A pFUnit that CMake finds already is used as it is: PFUNIT_DIR, PFUNIT_ROOT or
#    CMAKE_PREFIX_PATH in the environment (what a Spack or module install sets). The build
#    finds it the same way when run with the same environment.
# 2. Else the pFUnit built by an earlier run into build/pfunit is reused (tests/CMakeLists.txt
#    looks there); it is rebuilt when Open MPI has been installed since it was built without.
# 3. Else pFUnit is built there from $PFUNIT_SOURCE (a tarball or a folder holding its
#    source with the submodules), or from a clone of its public repository at v4.14.0:
#    with MPI when mpif90 is on PATH, its own tests off; 3-4 minutes on 2 cores.
# Needs gfortran, cmake, ninja, m4, python3 (and git for the clone): scripts/setup.sh
# installs them first.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
prefix="$repo_root/build/pfunit"
complete_mark="$prefix/ddc2d-complete"
tag=v4.14.0
repository=https://github.com/Goddard-Fortran-Ecosystem/pFUnit.git

say() { printf 'setup: %s\n' "$*"; }
die() { printf 'setup: error: %s\n' "$*" >&2; exit 1; }

work="$(mktemp -d "${TMPDIR:-/tmp}/ddc2d-pfunit.XXXXXX")"
trap 'rm -rf "$work"' EXIT

# The folder of the PFUNITConfig.cmake that CMake finds with this environment alone (not
# build/pfunit), or nothing.
installed_pfunit() {
    mkdir -p "$work/probe"
    cat > "$work/probe/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.25)
project(find_pfunit LANGUAGES Fortran)
find_package(PFUNIT 4.14 QUIET)
if(PFUNIT_FOUND)
    file(WRITE ${CMAKE_BINARY_DIR}/pfunit_dir "${PFUNIT_DIR}")
endif()
EOF
    cmake -S "$work/probe" -B "$work/probe/build" > "$work/probe.log" 2>&1 || return 0
    [[ -f "$work/probe/build/pfunit_dir" ]] && cat "$work/probe/build/pfunit_dir"
    return 0
}

found="$(installed_pfunit)"
if [[ -n "$found" ]]; then
    say "pFUnit found by CMake at $found: used as it is"
    exit 0
fi

mpi=no
command -v mpif90 > /dev/null 2>&1 && mpi=yes
if [[ -f "$complete_mark" ]]; then
    if [[ "$mpi" == no ]] || grep -qx 'mpi=yes' "$complete_mark"; then
        say "pFUnit ready: $prefix ($(tr '\n' ' ' < "$complete_mark"))"
        exit 0
    fi
    say "Open MPI is here now but $prefix was built without MPI: building it again"
fi

# ---------------------------------------------------------------- the source
source="${PFUNIT_SOURCE:-}"
if [[ -z "$source" ]]; then
    say "cloning pFUnit $tag from $repository"
    git clone --quiet --recurse-submodules --depth 1 --branch "$tag" "$repository" \
        "$work/pFUnit" || die "git clone of $repository failed (no network? set PFUNIT_SOURCE
       to a pFUnit $tag tarball or folder, or PFUNIT_DIR to an installed pFUnit)"
    source_dir="$work/pFUnit"
elif [[ -d "$source" ]]; then
    source_dir="$source"
elif [[ -f "$source" ]]; then
    mkdir -p "$work/source"
    tar -xzf "$source" -C "$work/source" || die "PFUNIT_SOURCE=$source: not a readable tarball"
    source_dir="$(find "$work/source" -mindepth 1 -maxdepth 1 -type d | head -n 1)"
else
    die "PFUNIT_SOURCE=$source: no such file or folder"
fi
[[ -f "$source_dir/CMakeLists.txt" && -d "$source_dir/extern/fArgParse/src" ]] \
    || die "$source holds no pFUnit source with its submodules (extern/fArgParse missing)"

# ---------------------------------------------------------------- the build
options=(-G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$prefix"
         -DCMAKE_Fortran_COMPILER=gfortran -DENABLE_TESTS=NO)
[[ "$mpi" == yes ]] || options+=(-DSKIP_MPI=YES)
say "building pFUnit (MPI: $mpi) from ${source:-$repository} into $prefix"
start=$SECONDS
rm -rf "$prefix"
cmake -S "$source_dir" -B "$work/build" "${options[@]}" > "$work/configure.log" 2>&1 \
    || { tail -n 30 "$work/configure.log" >&2; die "configuring pFUnit failed"; }
cmake --build "$work/build" --target install > "$work/build.log" 2>&1 \
    || { tail -n 30 "$work/build.log" >&2; die "building pFUnit failed"; }
# Written last: a build that stopped half way is not taken for a complete one.
printf 'version=%s\nmpi=%s\n' "$tag" "$mpi" > "$complete_mark"
say "pFUnit built into $prefix in $((SECONDS - start)) s"
