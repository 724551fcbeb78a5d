#!/usr/bin/env bash
# Lint the Python of python/, scripts/, tests/ and docs/examples/ with ruff (rules in ruff.toml),
# then the type hints of the ddc2d package (python/src/ddc2d) with mypy (its settings in
# python/pyproject.toml: the public API is typed, and mypy checks the hints against the code
# and every call):
#
#   scripts/lint-python.sh [more ruff check options, e.g. --fix or --statistics]
#
# Runs build/venv/bin/ruff check and build/venv/bin/mypy from the repository root (both
# installed into the venv by scripts/setup.sh). ruff finds *.py files by itself; the Python
# scripts without a .py suffix are listed in ruff.toml (extend-include), and this script
# fails when one of them is missing there, rather than leaving it unchecked.
# Exit status: 0 clean, 1 findings or an unlisted script, 2 no ruff or mypy in the venv.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
ruff="$repo_root/build/venv/bin/ruff"
mypy="$repo_root/build/venv/bin/mypy"
for tool in "$ruff" "$mypy"; do
    if [[ ! -x "$tool" ]]; then
        echo "lint-python: no $tool: run scripts/setup.sh" >&2
        exit 2
    fi
done

checked="$("$ruff" check --show-files)"
unlisted=()
for file in scripts/*; do
    [[ -f "$file" && "$file" != *.py ]] || continue
    head -n 1 "$file" | grep -q '^#!.*python' || continue
    grep -qxF "$repo_root/$file" <<< "$checked" || unlisted+=("$file")
done
if ((${#unlisted[@]} > 0)); then
    echo "lint-python: Python scripts that ruff does not check (add them to extend-include" \
         "in ruff.toml): ${unlisted[*]}" >&2
    exit 1
fi

echo "lint-python: $("$ruff" --version), $(grep -vc '\.toml$' <<< "$checked") Python files"
status=0
"$ruff" check "$@" || status=1
# The cache in build/, not in the working tree's root.
"$mypy" --config-file python/pyproject.toml --cache-dir build/mypy_cache python/src/ddc2d \
    || status=1
exit "$status"
