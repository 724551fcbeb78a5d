#!/usr/bin/env bash
# Lint the Python of python/, scripts/, tests/ and docs/examples/ with ruff (rules in ruff.toml):
#
#   scripts/lint-python.sh [more ruff check options, e.g. --fix or --statistics]
#
# Runs build/venv/bin/ruff check from the repository root (install it into the venv with
# build/venv/bin/python -m pip install ruff). ruff finds *.py files by itself; the Python
# scripts without a .py suffix are listed in ruff.toml (extend-include), and this script
# fails when one of them is missing there, rather than leaving it unchecked.
# Exit status: 0 clean, 1 findings or an unlisted script, 2 no ruff in the venv.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
ruff="$repo_root/build/venv/bin/ruff"
if [[ ! -x "$ruff" ]]; then
    echo "lint-python: no $ruff: run build/venv/bin/python -m pip install ruff" >&2
    exit 2
fi

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
exec "$ruff" check "$@"
