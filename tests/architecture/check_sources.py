#!/usr/bin/env python3
"""Hold the Fortran sources to the architecture (docs/ARCHITECTURE.md).

    check_sources.py [--graph] SOURCE_ROOT

1. Folders depend one way: the `use` lines of src/ and app/, mapped from module to the
   folder that defines it (src/*.f90 are the base, folder "."), form an acyclic graph.
2. File path = module name: src/a/b.f90 holds ddc_a_b (src/b.f90 holds ddc_b; app/b.f90
   holds ddc_app_b), so a reader finds a module from its name.
3. Every namelist statement of src/input/ declares exactly the variables of its group in
   the table of src/input/namelist_groups.f90, which the error messages print.
4. Every name imported by `use ..., only:` in src/, app/ and tests/ is used in its file
   (gfortran does not warn about unused imports at module level).

Prints every violation and exits 1 when there is one; --graph prints the folder graph.
"""
import itertools
import re
import sys
from collections import defaultdict
from pathlib import Path

LINES = re.IGNORECASE | re.MULTILINE
MODULE = re.compile(r"^\s*module\s+(\w+)\s*$", LINES)
USE = re.compile(r"^\s*use\s*(?:,\s*(?:non_)?intrinsic\s*::)?\s*(\w+)", LINES)
GROUP = re.compile(
    r"group_spec\('(\w+)',\s*\.(?:true|false)\.,\s*((?:'[^']*'(?:\s*//\s*&\s*)?\s*)+)\)",
    re.IGNORECASE)
NAMELIST = re.compile(r"^\s*namelist\s*/(\w+)/\s*((?:[^\n]*&\s*\n)*[^\n]*)", LINES)


def fortran_files(root):
    return sorted(p for folder in ("src", "app") for p in (root / folder).rglob("*.f90"))


def folder_of(path, root):
    parts = path.relative_to(root).parts
    if parts[0] == "app":
        return "app"
    return "/".join(parts[1:-1]) or "."


def expected_module(path, root):
    parts = list(path.relative_to(root).with_suffix("").parts)
    if parts[0] == "src":
        parts = parts[1:]
    return "ddc_" + "_".join(parts)


def find_cycle(graph):
    """A list of folders forming a cycle, or None (depth-first search)."""
    state = {}
    stack = []

    def visit(node):
        state[node] = "open"
        stack.append(node)
        for nxt in sorted(graph[node]):
            if state.get(nxt) == "open":
                return stack[stack.index(nxt):] + [nxt]
            if nxt not in state:
                found = visit(nxt)
                if found:
                    return found
        stack.pop()
        state[node] = "done"
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node)
            if found:
                return found
    return None


def strip_comments(text):
    return re.sub(r"!.*", "", text)


def check_folders(root, problems):
    module_folder = {}
    uses = []
    for path in fortran_files(root):
        text = strip_comments(path.read_text())
        for name in MODULE.findall(text):
            module_folder[name.lower()] = folder_of(path, root)
            if name.lower() != expected_module(path, root):
                problems.append(f"{path.relative_to(root)}: holds module {name}, expected "
                                f"{expected_module(path, root)} (file path = module name)")
        uses += [(path, used.lower()) for used in USE.findall(text)]
    module_folder["ddc_version"] = "."  # generated from src/version.f90.in
    graph = defaultdict(set)
    edges = defaultdict(set)
    for path, used in uses:
        if used not in module_folder:
            continue  # intrinsic or external (hdf5, omp_lib)
        here, there = folder_of(path, root), module_folder[used]
        graph[here]
        if here != there:
            graph[here].add(there)
            edges[(here, there)].add(f"{path.relative_to(root)} uses {used}")
    cycle = find_cycle(graph)
    if cycle:
        links = [f"{a} -> {b} ({min(edges[(a, b)])})" for a, b in itertools.pairwise(cycle)]
        problems.append("folder cycle: " + "; ".join(links))
    return graph


def check_namelists(root, problems):
    """Number of namelist statements checked against the group table."""
    table_text = (root / "src/input/namelist_groups.f90").read_text()
    table = {}
    for name, spec in GROUP.findall(table_text):
        variables = "".join(re.findall(r"'([^']*)'", spec)).split()
        table[name.lower()] = [v.split(":")[0].lower() for v in variables]
    if not table:
        problems.append("src/input/namelist_groups.f90: no group_spec table found")
    checked = 0
    for path in sorted((root / "src/input").glob("*.f90")):
        for group, names in NAMELIST.findall(strip_comments(path.read_text())):
            checked += 1
            declared = [n.strip().lower() for n in names.replace("&", " ").split(",")]
            expected = table.get(group.lower())
            if expected is None:
                problems.append(f"{path.relative_to(root)}: namelist /{group}/ has no entry "
                                "in the group table")
            elif declared != expected:
                problems.append(f"{path.relative_to(root)}: namelist /{group}/ declares "
                                f"{declared}, the group table lists {expected}")
    if checked != len(table):
        problems.append(f"src/input: {checked} namelist statements for the {len(table)} groups "
                        "of the table; every group needs exactly one reader")
    return checked


USE_ONLY = re.compile(r"^\s*use\b[^\n]*?\bonly\s*:((?:[^\n]*&\s*\n)*[^\n]*)", LINES)


def check_imports(root, problems):
    """Names imported with `use ..., only:` that the file never mentions again."""
    for path in sorted(fortran_files(root) + sorted((root / "tests").glob("*.f90"))):
        text = strip_comments(path.read_text())
        rest = USE_ONLY.sub("", text)
        words = {w.lower() for w in re.findall(r"\b\w+\b", rest)}
        words |= {k.lower() for k in re.findall(r"[\d.]_(\w+)", rest)}  # 1.0_wp
        for names in USE_ONLY.findall(text):
            for item in names.replace("&", " ").split(","):
                local = item.split("=>")[0].strip().lower()
                if local.startswith(("operator(", "assignment(")):
                    continue
                if local and local not in words:
                    problems.append(f"{path.relative_to(root)}: imports {local} but does not "
                                    "use it")


def main(argv):
    graph_wanted = "--graph" in argv
    args = [a for a in argv if a != "--graph"]
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    root = Path(args[0]).resolve()
    problems = []
    graph = check_folders(root, problems)
    namelists = check_namelists(root, problems)
    check_imports(root, problems)
    if graph_wanted:
        for folder in sorted(graph):
            print(f"{folder}: {', '.join(sorted(graph[folder])) or '-'}")
    for problem in problems:
        print(problem)
    if not problems:
        print(f"architecture: {len(graph)} folders, no cycle; module names follow their paths; "
              f"the {namelists} namelist statements match the group table; every import is used")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
