#!/usr/bin/env bash
# Set everything up and run the whole test suite:
#   1. scripts/setup.sh (Debian packages and the Python venv, only what is missing);
#   2. the Debug build (-fcheck=all, -ffpe-trap=invalid,zero) and its CTest suites, through
#      the `debug` workflow preset (configure, build, test);
#   3. pytest on tests/python (plot script, TWODD scripts and the command line), with the
#      Debug executable.
# Exits non-zero when any step fails (pytest's "no tests collected" counts as a failure).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

scripts/setup.sh
cmake --workflow --preset debug
DDC2D_EXE="$repo_root/build/debug/app/ddc2d" build/venv/bin/python -m pytest tests/python
