#!/usr/bin/env bash
# Install what ddc2d needs to build, test and plot, and nothing that is already there.
#
#   scripts/setup.sh [--mpi] [--tests]
#
# 1. Debian packages (compiler, CMake, Ninja, OpenBLAS/LAPACK, serial HDF5, h5dump,
#    python3 + venv, valgrind for the memcheck tests, stress-ng for the CPU hog beside the
#    second run of the process-level tests in scripts/test.sh): installed with apt-get only when
#    one of them is missing. With --mpi also Open MPI and ScaLAPACK (openmpi-bin,
#    libopenmpi-dev, libscalapack-openmpi-dev) for the MPI build (cmake --preset mpi).
# 2. A Python virtual environment in build/venv with the ddc2d Python package of this
#    working tree (python/, docs/python.md) installed editable with its extra 'test': numpy,
#    h5py, matplotlib, xarray, xlrd and openpyxl (comp2ddm2nml reads .xls / .xlsx
#    workbooks), pytest and xlwt (the tests write .xls workbooks), all from PyPI; FORD
#    (the API pages, scripts/build-api-docs.sh) and the linters fortitude-lint, ruff and mypy:
#    created/installed only when missing or broken (a ddc2d package that is not this
#    working tree's is installed over).
# 3. With --tests, pFUnit 4.14 for the Fortran test suites (scripts/setup-pfunit.sh): an
#    installed one that CMake finds (PFUNIT_DIR, CMAKE_PREFIX_PATH), else the one built
#    earlier into build/pfunit, else built there once from $PFUNIT_SOURCE (a tarball or
#    folder) or a clone of its public repository; with MPI when the MPI packages are there.
#
# Idempotent: a second run only checks and takes a few seconds. Works from any folder.
# Needs root (or sudo) only when Debian packages are missing.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

debian_packages=(gfortran cmake ninja-build libopenblas-dev liblapack-dev libhdf5-dev libhmat-oss-dev
                 hdf5-tools python3 python3-venv valgrind stress-ng)
# The MPI build: Open MPI with its Fortran mpi_f08 module, and ScaLAPACK (with BLACS) built
# for it. Not libhdf5-openmpi-dev: the output stays serial HDF5, written by one process.
mpi_packages=(openmpi-bin libopenmpi-dev libscalapack-openmpi-dev)
# The ddc2d package (editable) with the extra that the tests need, and PyPI packages beyond
# it; each one's import name is the same.
package_spec="$repo_root/python[test]"
python_packages=(ford)
package_modules="ddc2d, numpy, h5py, matplotlib, xarray, pytest, xlrd, openpyxl, xlwt, scipy"
python_modules="$package_modules, ford"
# Linters run by the tests, as PyPI package:executable in the venv's bin/.
# Pinned: their default rule sets change between releases.
python_tools=(fortitude-lint==0.10.0:fortitude ruff==0.17.6:ruff mypy==2.4.1:mypy)
venv_dir="$repo_root/build/venv"

say() { printf 'setup: %s\n' "$*"; }
die() { printf 'setup: error: %s\n' "$*" >&2; exit 1; }

tools=(gfortran cmake ninja h5dump python3)
with_tests=0
for argument in "$@"; do
    case "$argument" in
        --mpi) debian_packages+=("${mpi_packages[@]}"); tools+=(mpiexec mpif90) ;;
        # pFUnit's build runs m4 and git (for a clone when no source is given); the install
        # test loads the installed module file with Lmod.
        --tests) with_tests=1; debian_packages+=(m4 git lmod); tools+=(m4 git) ;;
        *) die "unknown argument '$argument' (usage: scripts/setup.sh [--mpi] [--tests])" ;;
    esac
done

# ---------------------------------------------------------------- Debian packages
is_installed() {
    # dpkg-query prints nothing (and fails) for unknown packages; removed packages
    # report "deinstall ok config-files", so look for the exact installed status.
    [[ "$(dpkg-query -W -f='${Status}' "$1" 2>/dev/null || true)" == "install ok installed" ]]
}

if ! command -v dpkg-query > /dev/null 2>&1; then
    die "dpkg-query not found: this script supports Debian (12) and derivatives only"
fi

missing=()
for package in "${debian_packages[@]}"; do
    is_installed "$package" || missing+=("$package")
done

if ((${#missing[@]} > 0)); then
    say "missing Debian packages: ${missing[*]}"
    if ((EUID == 0)); then
        as_root=()
    elif command -v sudo > /dev/null 2>&1; then
        as_root=(sudo)
    else
        die "not root and no sudo: install as root: apt-get install ${missing[*]}"
    fi
    say "running apt-get update"
    "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
        apt-get update -o DPkg::Lock::Timeout=900
    say "running apt-get install ${missing[*]}"
    "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
        apt-get install -y -o DPkg::Lock::Timeout=900 "${missing[@]}"
    for package in "${missing[@]}"; do
        is_installed "$package" || die "Debian package '$package' is still not installed"
    done
else
    say "Debian packages present: ${debian_packages[*]}"
fi

for tool in "${tools[@]}"; do
    command -v "$tool" > /dev/null 2>&1 || die "'$tool' not found on PATH after installation"
done

# ---------------------------------------------------------------- Python venv
venv_python="$venv_dir/bin/python"

venv_works() {
    [[ -x "$venv_python" ]] && "$venv_python" -c 'import sys' > /dev/null 2>&1
}
missing_tools() {
    local tool
    for tool in "${python_tools[@]}"; do
        [[ -x "$venv_dir/bin/${tool#*:}" ]] || printf '%s\n' "${tool%%:*}"
    done
}
package_from_tree() {
    # `import ddc2d` finds this working tree's python/src/ddc2d (an editable install).
    "$venv_python" -c 'import pathlib, sys, ddc2d
sys.exit(pathlib.Path(ddc2d.__file__).resolve().parent != pathlib.Path(sys.argv[1]))' \
        "$repo_root/python/src/ddc2d" > /dev/null 2>&1
}
venv_complete() {
    venv_works && "$venv_python" -c "import $python_modules" > /dev/null 2>&1 \
        && package_from_tree && [[ -z "$(missing_tools)" ]]
}

if venv_complete; then
    say "Python venv ready: $venv_dir ($python_modules)"
else
    if ! venv_works; then
        # Absent, or left broken (e.g. its base interpreter was removed): (re)create it.
        say "creating Python venv $venv_dir with $(command -v python3)"
        mkdir -p "$(dirname "$venv_dir")"
        python3 -m venv --clear "$venv_dir" \
            || die "'python3 -m venv' failed (on Debian, is python3-venv installed?)"
    fi
    if ! package_from_tree || ! "$venv_python" -c "import $package_modules" > /dev/null 2>&1
    then
        say "installing the ddc2d package of $repo_root/python (editable) with its" \
            "dependencies from PyPI"
        "$venv_python" -m pip install --quiet --editable "$package_spec"
    fi
    missing_python=()
    for package in "${python_packages[@]}"; do
        "$venv_python" -c "import $package" > /dev/null 2>&1 || missing_python+=("$package")
    done
    mapfile -t -O "${#missing_python[@]}" missing_python < <(missing_tools)
    if ((${#missing_python[@]} > 0)); then
        say "installing into the venv from PyPI: ${missing_python[*]}"
        "$venv_python" -m pip install --quiet "${missing_python[@]}"
    fi
    venv_complete || die "the venv still cannot import $python_modules"
    say "Python venv ready: $venv_dir"
fi

# ---------------------------------------------------------------- pFUnit
if ((with_tests)); then
    "$repo_root/scripts/setup-pfunit.sh"
fi
