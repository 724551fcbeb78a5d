#!/usr/bin/env python3
"""Hold the Fortran sources to the architecture (docs/ARCHITECTURE.md).

    check_sources.py [--graph] SOURCE_ROOT

1. Folders depend one way: the `use` lines of src/ and app/, mapped from module to the
   folder that defines it (src/*.f90 are the base, folder "."), form an acyclic graph.
2. File path = module name: src/a/b.f90 holds ddc_a_b (src/b.f90 holds ddc_b; app/b.f90
   holds ddc_app_b), so a reader finds a module from its name.
3. Every namelist statement of src/input/ declares exactly the variables of its group in
   the table of src/input/namelist_groups.f90, which the error messages print.
4. Every name imported by `use ..., only:` in src/, app/ and tests/ (the Fortran suites'
   .pf files too) is used in its file
   (gfortran does not warn about unused imports at module level).
5. The code map is a contract: the "uses" column of the folder table of
   docs/ARCHITECTURE.md lists exactly what each folder's code uses, a folder (`model`,
   `base` for src/*.f90) or a single module of one (`contact/options`); a folder edge
   the table does not list, a listed use the code does not have and a folder without a
   row are violations.
6. Nothing of the model is forgotten on the way to the other processes of the MPI build:
   every per-element array of `element_set` is in the one list `for_each_element_array`
   (src/model/types.f90), which allocation, selection, broadcast and the fingerprint go
   through; every
   other component of `element_set` and every component of `solver_options` is
   broadcast in src/parallel/model.f90 or marked there in a comment
   `! Root only: <reference> (why)`.
7. No error of a routine under test goes unseen: in the Fortran suites (tests/fortran/, .pf
   and .f90), a statement that passes `error` as the last argument of a routine (the
   project's convention for an error a routine returns, intent out) is followed, before the
   next such statement and before its procedure ends, by one that reads `allocated(error)`
   (an assertion or a branch), unless the procedure hands `error` on to its caller as an
   argument of its own.

8. Nothing that determines a result escapes the model fingerprint that --resume compares:
   every component of `model_type` (into its derived types), of `growth_options` and of
   `solver_options` is hashed in `hash_model` (src/model/fingerprint.f90) or marked there
   in a comment `! Not hashed: <reference> (why)` (a derived component's mark covers its
   components); the per-element arrays go through
   `for_each_element_array`, which `hash_model` calls.
9. The LCP solvers know nothing of faults: src/contact/lemke.f90, active_set.f90 and
   paper_lcp.f90 take plain arrays, and no chain of `use` lines leads from them to the
   fault law (ddc_contact_fault_law), which only the contact formulation and the solve
   layer use.
10. A growth criterion plugs in at one place: every criterion code of src/model/types.f90
    (`growth_criterion_<name>`) has a case in every `select case` on the criterion of
    src/growth/criterion.f90, each with a `case default` (an unknown code is an internal
    error, not silently one of the others), and no other file of src/growth/ reads
    `%criterion`.
11. No column of a run's records is forgotten on its way to the file and back: every array
    component of `history_record`, `tip_records`, `growth_record` (src/model/results.f90),
    `trial_records` (src/model/trial_records.f90) and `initiation_record`
    (src/model/initiations.f90) is in its one list (`for_each_history_column`,
    `for_each_tip_column`, ..., src/model/records.f90) under its own name, and a record's
    part with a list of its own (growth_record's tip rows and trials) is handed to that list;
    the routines that handle every column (the layout of a record, its appends, the HDF5
    writers, the restart reader) go through the list; and the dataset lists of
    python/src/ddc2d/reader.py name exactly the datasets the lists give /history and /growth.
12. The recipes of docs/ARCHITECTURE.md name what exists: every file of src/, app/,
    tests/ or scripts/ they name is there, and every procedure, type or list they name
    beside a file (`` `name` (`src/x/y.f90`) `` or `` `src/x/y.f90` (`name` ``) is a word
    of that file.
13. The strength laws are listed once: every entry of `for_each_law` (src/model/laws.f90)
    hands the per-element real array of `element_set` of its own name, and the list has
    `strength_law_count` (src/model/types.f90) entries; the fault law
    (src/contact/fault_law.f90) has each law as a component, sets it by name in
    `set_given` (a case per law, no other), gives it the list's default in `new_fault_law`
    (`given_or(<name>, <default>)`, no other), and `beyond_coulomb` reads exactly the laws
    the list marks beyond Coulomb; the &fracture and &growth namelist statements declare
    each law (`new_<name>` in &growth), and the arrays of their values that the readers
    build name them in the list's order; the routines that handle every law go through
    the list.
14. No test names the system's temporary folder: a quoted path that begins with /tmp in
    tests/ or scripts/ would bypass the TMPDIR of its own that CTest gives every test (and
    the check that the test left nothing there: tests/temporary_folders.py). The
    exceptions are the fallback of the Fortran suites run by hand
    (tests/fortran/support/temporary.f90) and this check's planted violations.

Prints every violation and exits 1 when there is one; --graph prints the folder graph.
"""
import ast
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


def test_sources(root):
    """The Fortran sources of tests/: the pFUnit suites (.pf) and plain Fortran."""
    return sorted(p for pattern in ("*.f90", "*.pf") for p in (root / "tests").rglob(pattern))


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
            edges[(here, there)].add((used, str(path.relative_to(root))))
    cycle = find_cycle(graph)
    if cycle:
        links = [f"{a} -> {b} ({example(edges[(a, b)])})" for a, b in itertools.pairwise(cycle)]
        problems.append("folder cycle: " + "; ".join(links))
    return graph, edges


def example(uses):
    """One `use` line of a folder edge, for messages: "src/a/b.f90 uses ddc_c_d"."""
    module, path = min(uses, key=lambda use: (use[1], use[0]))
    return f"{path} uses {module}"


TABLE = Path("docs/ARCHITECTURE.md")
TABLE_SECTION = "## Folders and what flows between them"
TABLE_ROW = re.compile(r"^\|\s*`([^`]+)`[^|]*\|[^|]*\|([^|]*)\|\s*$", re.MULTILINE)


def folder_name(folder):
    return "base" if folder == "." else folder


def read_table(root, problems):
    """{folder: set of uses} from the folder table: a use is a folder ("." for the base)
    or "folder/file" for a single module; remarks in parentheses are not uses."""
    table = {}
    text = (root / TABLE).read_text()
    section = re.search(rf"^{TABLE_SECTION}$(.*?)(?=^## |\Z)", text, re.MULTILINE | re.DOTALL)
    for cell, uses in TABLE_ROW.findall(section.group(1) if section else ""):
        folder = "." if cell == "src/*.f90" else cell.strip().removesuffix("/")
        items = [item.strip() for item in
                 re.sub(r"\([^)]*\)", "", uses).replace("`", "").split(",")]
        items = [item for item in items if item and item != "nothing"]
        if folder in table:
            problems.append(f"{TABLE}: two rows for {folder_name(folder)}")
        table[folder] = {"." if item == "base" else item.removesuffix("/") for item in items}
    if not table:
        problems.append(f"{TABLE}: no folder table (| `folder/` | job | uses |) under "
                        f"'{TABLE_SECTION}'")
    return table


def check_table(root, graph, edges, problems):
    """The folder table's "uses" column against the `use` lines of the code."""
    table = read_table(root, problems)
    if not table:
        return
    for folder in sorted(set(table) - set(graph)):
        problems.append(f"{TABLE}: a row for {folder_name(folder)}, which holds no source")
    for folder in sorted(graph):
        if folder not in table:
            problems.append(f"{TABLE}: no row for {folder_name(folder)} in the folder table")
            continue
        listed = table[folder]
        used = set()
        for there in sorted(graph[folder]):
            single = {module: there + "/" + module.removeprefix(f"ddc_{there}_")
                      for module, _ in edges[(folder, there)]}
            used |= {there} | set(single.values())
            unlisted = {(module, path) for module, path in edges[(folder, there)]
                        if there not in listed and single[module] not in listed}
            if unlisted:
                singles = sorted({single[module] for module, _ in unlisted})
                what = ("base" if there == "." else
                        f"{there} (nor {' and '.join(singles)} one by one)")
                problems.append(f"{example(unlisted)}: the folder table of {TABLE} does not "
                                f"list {what} among the uses of {folder_name(folder)}")
        for item in sorted(listed - used):
            problems.append(f"{TABLE}: the row of {folder_name(folder)} lists {item}, which "
                            f"{folder_name(folder)} does not use")


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
    for path in fortran_files(root) + test_sources(root):
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


# The one list of per-element arrays, and the routines that must go through it.
ELEMENT_LIST = ("src/model/types.f90", "for_each_element_array")
THROUGH_ELEMENT_LIST = [("src/mesh/geometry.f90", "allocate_elements"),
                        ("src/model/types.f90", "select_elements"),
                        ("src/parallel/model.f90", "share_elements"),
                        ("src/model/fingerprint.f90", "hash_model")]
# Types the MPI build broadcasts: (file of the type, type, file of the broadcast, routine,
# how the routine names a component); per-element arrays go through the list above.
SHARED = [("src/model/types.f90", "element_set", "src/parallel/model.f90", "share_elements",
           "elements%"),
          ("src/contact/options.f90", "solver_options", "src/parallel/model.f90",
           "share_model", "model%solver%")]
ROOT_ONLY = re.compile(r"!\s*root only:\s*([\w%]+(?:\s*,\s*[\w%]+)*)", re.IGNORECASE)


def split_top_level(text):
    """Items of a comma-separated list, ignoring commas inside (...) and [...]."""
    items, depth, start = [], 0, 0
    for i, char in enumerate(text):
        depth += char in "([" and 1 or char in ")]" and -1 or 0
        if char == "," and depth == 0:
            items.append(text[start:i])
            start = i + 1
    return [item.strip() for item in items + [text[start:]] if item.strip()]


def type_components(text, name):
    """[(component, per-element array?, derived type or None)] of `type :: name`; None
    when the file has no such type."""
    found = re.search(rf"^\s*type\b[^\n]*::\s*{name}\s*$(.*?)^\s*end\s*type\s+{name}\b",
                      strip_comments(text), LINES | re.DOTALL)
    if not found:
        return None
    components = []
    for line in re.sub(r"&\s*\n\s*", " ", found.group(1)).splitlines():
        if "::" not in line or re.match(r"\s*procedure\b", line, re.IGNORECASE):
            continue
        spec, entities = line.split("::", 1)
        derived = re.match(r"\s*type\s*\(\s*(\w+)\s*\)", spec, re.IGNORECASE)
        for entity in split_top_level(entities):
            component = re.match(r"(\w+)\s*(\()?", entity)
            array = bool(component.group(2)) or "dimension" in spec.lower()
            components.append((component.group(1).lower(),
                               array and "allocatable" in spec.lower(),
                               derived.group(1).lower() if derived else None))
    return components


def leaf_references(text, name, prefix):
    """References prefix%a (prefix%a%b for a component of a derived type of the same
    file) of every component of type name that is not a per-element array."""
    references = []
    for component, per_element, derived in type_components(text, name):
        if per_element:
            continue
        inner = derived and type_components(text, derived)
        if inner:
            references += leaf_references(text, derived, f"{prefix}{component}%")
        else:
            references.append(f"{prefix}{component}")
    return references


def routine(root, file, name, problems):
    """The text of a subroutine (with comments), or None after a problem."""
    found = re.search(rf"^\s*(?:\w+\s+)*subroutine\s+{name}\b(.*?)^\s*end\s+subroutine\s+"
                      rf"{name}\b", (root / file).read_text(), LINES | re.DOTALL)
    if not found:
        problems.append(f"{file}: no subroutine {name}")
        return None
    return found.group(1)


def marks(pattern, text):
    """The references named by the comments of a pattern (Root only:, Not hashed:)."""
    return {reference.strip().lower() for names in pattern.findall(text)
            for reference in names.split(",")}


def names_in(code, reference):
    return re.search(rf"(?<![\w%]){re.escape(reference)}(?![\w%])", code, re.IGNORECASE)


def check_shared(root, problems):
    """Every component of the broadcast types reaches the other processes (item 6)."""
    types = (root / ELEMENT_LIST[0]).read_text()
    components = type_components(types, "element_set") or []
    if not components:
        problems.append(f"{ELEMENT_LIST[0]}: no type element_set")
    listing = routine(root, *ELEMENT_LIST, problems)
    if listing is not None:
        code = strip_comments(listing)
        for component, per_element, _ in components:
            if per_element and not names_in(code, f"elements%{component}"):
                problems.append(f"{ELEMENT_LIST[0]}: the per-element array {component} of "
                                f"element_set is missing from {ELEMENT_LIST[1]}, so it is "
                                "not allocated, selected or broadcast")
    for file, name in THROUGH_ELEMENT_LIST:
        text = routine(root, file, name, problems)
        if text is not None and not names_in(strip_comments(text), ELEMENT_LIST[1]):
            problems.append(f"{file}: {name} does not go through {ELEMENT_LIST[1]}")
    for type_file, name, file, broadcast, prefix in SHARED:
        text = routine(root, file, broadcast, problems)
        if text is None:
            continue
        code = strip_comments(text)
        root_only = marks(ROOT_ONLY, text)
        references = leaf_references((root / type_file).read_text(), name, prefix)
        if not references:
            problems.append(f"{type_file}: no type {name}")
        for reference in references:
            if not names_in(code, reference) and reference not in root_only:
                problems.append(f"{file}: {broadcast} does not broadcast {reference} "
                                f"(a component of {name}) nor marks it "
                                f"'! Root only: {reference} (why)'")
        for reference in sorted(root_only - set(references)):
            if reference.startswith(prefix):
                problems.append(f"{file}: {broadcast} marks {reference} root only, which "
                                f"is no component of {name}")


# The fingerprint (check 8): the routine that hashes, the files of the types it covers.
FINGERPRINT = ("src/model/fingerprint.f90", "hash_model")
HASHED_TYPE_FILES = ("src/model/types.f90", "src/contact/options.f90", "src/model/cycles.f90",
                     "src/model/body.f90")
NOT_HASHED = re.compile(r"!\s*not hashed:\s*([\w%]+(?:\s*,\s*[\w%]+)*)", re.IGNORECASE)


def hashed_references(root, name, prefix):
    """References prefix%a%b of every leaf component of type name, through the derived
    types of HASHED_TYPE_FILES; element_set's per-element arrays are left out."""
    components = None
    for file in HASHED_TYPE_FILES:
        components = type_components((root / file).read_text(), name)
        if components is not None:
            break
    references = []
    for component, per_element, derived in components or []:
        if name == "element_set" and per_element:
            continue
        if derived and any(type_components((root / f).read_text(), derived) is not None
                           for f in HASHED_TYPE_FILES):
            references += hashed_references(root, derived, f"{prefix}{component}%")
        else:
            references.append(f"{prefix}{component}")
    return references


def hashes(code, reference):
    """Whether code names reference, an array's subscripts allowed: model%a(i)%b."""
    parts = [re.escape(part) for part in reference.split("%")]
    pattern = r"(?<![\w%])" + r"(?:\s*\([^()]*\))?\s*%\s*".join(parts) + r"(?!\w)"
    return re.search(pattern, code, re.IGNORECASE)


def covers(mark, reference):
    """A mark names the reference or a derived component that holds it."""
    return reference == mark or reference.startswith(mark + "%")


def check_fingerprint(root, problems):
    """Every component of the model is hashed or marked not hashed (item 8)."""
    file, name = FINGERPRINT
    text = routine(root, file, name, problems)
    if text is None:
        return
    code = strip_comments(text)
    marked = marks(NOT_HASHED, text)
    references = hashed_references(root, "model_type", "model%")
    if not references:
        problems.append(f"{HASHED_TYPE_FILES[0]}: no type model_type")
    for reference in references:
        if not hashes(code, reference) and not any(covers(m, reference) for m in marked):
            problems.append(f"{file}: {name} does not hash {reference} nor marks it "
                            f"'! Not hashed: {reference} (why)'")
    for reference in sorted(m for m in marked if not any(covers(m, r) for r in references)):
        problems.append(f"{file}: {name} marks {reference} not hashed, which is no "
                        "component of the model")


# The LCP solvers (check 9) and the module they must not reach.
LCP_SOLVERS = ("src/contact/lemke.f90", "src/contact/active_set.f90",
               "src/contact/paper_lcp.f90")
FAULT_LAW = "ddc_contact_fault_law"


def module_uses(root):
    """{module: set of the modules its file uses} of src/ and app/."""
    uses = {}
    for path in fortran_files(root):
        text = strip_comments(path.read_text())
        for name in MODULE.findall(text):
            uses[name.lower()] = {used.lower() for used in USE.findall(text)}
    return uses


def use_chain(uses, start, goal):
    """The shortest chain of modules from start to goal along `use` lines, or None."""
    chains = {start: [start]}
    queue = [start]
    for module in queue:
        if module == goal:
            return chains[module]
        for used in sorted(uses.get(module, ())):
            if used not in chains:
                chains[used] = chains[module] + [used]
                queue.append(used)
    return None


def check_lcp_solvers(root, problems):
    """Check 9: no LCP solver reaches the fault law, directly or through other modules."""
    uses = module_uses(root)
    for file in LCP_SOLVERS:
        module = expected_module(root / file, root)
        if module not in uses:
            problems.append(f"{file}: no module {module} (an LCP solver of check 9)")
            continue
        chain = use_chain(uses, module, FAULT_LAW)
        if chain:
            problems.append(f"{file}: the LCP solver {module} reaches the fault law "
                            f"({' -> '.join(chain)}); the solvers take plain arrays")


# The records' columns (check 11): (type, its file, its list, how the list names a component).
RECORD_LISTS = "src/model/records.f90"
RECORDS = [("history_record", "src/model/results.f90", "for_each_history_column", "history%"),
           ("tip_records", "src/model/results.f90", "for_each_tip_column", "rows%"),
           ("growth_record", "src/model/results.f90", "for_each_growth_column", "record%"),
           ("trial_records", "src/model/trial_records.f90", "for_each_trial_column", "trials%"),
           ("initiation_record", "src/model/initiations.f90", "for_each_initiation_column",
            "record%")]
# A record's part that has a list of its own, and the list that must hand it to that list:
# (list, the part as it names it, the part's list).
RECORD_PARTS = [("for_each_growth_column", "record%tip_records", "for_each_tip_column"),
                ("for_each_growth_column", "record%trials", "for_each_trial_column"),
                ("for_each_initiation_column", "record%trials", "for_each_trial_column")]
# The routines that handle every column of a record, and the list each goes through.
THROUGH_RECORD_LISTS = [("src/model/records.f90", "lay_out_history", "for_each_history_column"),
                        ("src/model/records.f90", "empty_growth_record",
                         "for_each_growth_column"),
                        ("src/model/records.f90", "lay_out_tip_rows", "for_each_tip_column"),
                        ("src/model/records.f90", "append_tip_rows", "for_each_tip_column"),
                        ("src/model/records.f90", "append_trial_rows",
                         "for_each_trial_column"),
                        ("src/model/records.f90", "empty_initiation_record",
                         "for_each_initiation_column"),
                        ("src/model/records.f90", "append_initiation",
                         "for_each_initiation_column"),
                        ("src/output/hdf5_records.f90", "write_history",
                         "for_each_history_column"),
                        ("src/output/hdf5_records.f90", "write_growth", "for_each_growth_column"),
                        ("src/output/hdf5_records.f90", "write_growth_elements",
                         "for_each_growth_column"),
                        ("src/output/hdf5_initiations.f90", "write_initiations",
                         "for_each_initiation_column"),
                        ("src/output/restart_read.f90", "read_restart",
                         "for_each_history_column"),
                        ("src/output/restart_read.f90", "read_growth", "for_each_growth_column")]
# A list line: call action%on_<shape>(column('<name>', <kind>, ...), <record>%<component>)
LIST_ENTRY = re.compile(r"call\s+action\s*%\s*on_(\w+)\s*\(\s*column\s*\(\s*'(\w+)'\s*,"
                        r"\s*(\w+).*,\s*(\w+)\s*%\s*(\w+)\s*\)$", re.IGNORECASE)
# The Python reader, and which of its lists holds which columns: (constant, record, kinds or
# shape); the rest of a record's columns (and the datasets write_history writes beside them)
# are in the lists of REST.
PYTHON_READER = "python/src/ddc2d/reader.py"
PYTHON_LISTS = [("HISTORY_GROWTH_DATASETS", "for_each_history_column",
                 {"column_growth_steps", "column_growing_tips", "column_growing_tip_steps"}),
                ("HISTORY_STRING_DATASETS", "for_each_history_column", {"strings"}),
                ("HISTORY_FLOW_DATASETS", "for_each_history_column",
                 {"column_time_steps", "column_flow_element_steps", "column_flow_steps",
                  "column_fracture_steps"}),
                ("HISTORY_COUPLED_DATASETS", "for_each_history_column",
                 {"column_coupled_element_steps", "column_coupled_steps"}),
                ("GROWTH_PATH_DATASETS", "for_each_tip_column", {"column_path_records"}),
                ("GROWTH_DATASETS", "for_each_tip_column", {"column_records"}),
                ("GROWTH_WORK_DATASETS", "for_each_tip_column", {"column_work_records"}),
                ("GROWTH_TRIAL_DATASETS", "for_each_trial_column", {"column_trials"}),
                ("INITIATION_DATASETS", "for_each_initiation_column", {"column_records"}),
                ("FLAW_TRIAL_DATASETS", "for_each_trial_column", {"column_trials"})]
# The datasets of a trial column (ddc_model_records' trial_dataset): in /growth/trials,
# in /growth/initiations/flaw_trials.
TRIAL_DATASETS = {"GROWTH_TRIAL_DATASETS": lambda name: "trial_" + ("record" if name == "owner"
                                                                    else name),
                  "FLAW_TRIAL_DATASETS": lambda name: "flaw" if name == "owner" else name}
REST = ("HISTORY_DATASETS", "HISTORY_STEP_DATASETS")
# Columns that are not datasets of their group: the load (one dataset per quantity, the
# Python list HISTORY_LOADS against load_path_names) and /elements/created_step (read_elements
# reads every dataset of /elements).
NOT_LISTED_KINDS = {"column_loads", "column_elements"}


def list_entries(root, name, problems):
    """[(shape, column name, kind, record, component)] of a record's list."""
    text = routine(root, RECORD_LISTS, name, problems)
    if text is None:
        return []
    entries = []
    for _, statement in statements(text):
        found = LIST_ENTRY.match(statement)
        if found:
            entries.append(found.groups())
        elif re.match(r"call\s+action\s*%", statement, re.IGNORECASE):
            problems.append(f"{RECORD_LISTS}: {name} has an entry not of the form "
                            "call action%on_<shape>(column('<name>', <kind>, ...), "
                            f"<record>%<component>): {statement}")
    return entries


def check_record_lists(root, problems):
    """Every column of the records is in its list under its own name (check 11)."""
    entries = {}
    for record, file, name, prefix in RECORDS:
        components = type_components((root / file).read_text(), record)
        if components is None:
            problems.append(f"{file}: no type {record}")
            continue
        entries[name] = list_entries(root, name, problems)
        listed = {}
        for _, column, _, holder, component in entries[name]:
            if f"{holder}%".lower() != prefix:
                problems.append(f"{RECORD_LISTS}: {name} lists {holder}%{component}, which is "
                                f"not a column of its {record} ({prefix}...)")
                continue
            listed[component.lower()] = column
            if column.lower() != component.lower():
                problems.append(f"{RECORD_LISTS}: {name} names the column {prefix}{component} "
                                f"'{column}' (a column is named after its component)")
        for component, array, _ in components:
            if array and component not in listed:
                problems.append(f"{file}: the column {component} of {record} is "
                                f"missing from {name}, so it is not laid out, written or read")
    for name, part, visitor in RECORD_PARTS:
        text = routine(root, RECORD_LISTS, name, problems)
        call = rf"call\s+{visitor}\s*\(\s*{re.escape(part)}\s*,"
        if text is not None and not re.search(call, strip_comments(text), re.IGNORECASE):
            problems.append(f"{RECORD_LISTS}: {name} does not hand {part} to {visitor}")
    for file, name, visitor in THROUGH_RECORD_LISTS:
        text = routine(root, file, name, problems)
        if text is not None and not names_in(strip_comments(text), visitor):
            problems.append(f"{file}: {name} does not go through {visitor}")
    check_python_lists(root, entries, problems)


def python_lists(root, problems):
    """{constant: tuple of strings} of the module-level tuples of the Python reader."""
    lists = {}
    try:
        tree = ast.parse((root / PYTHON_READER).read_text())
    except (OSError, SyntaxError) as failure:
        problems.append(f"{PYTHON_READER}: cannot be read ({failure})")
        return lists
    for node in tree.body:
        if isinstance(node, ast.Assign) and isinstance(node.value, ast.Tuple):
            for target in node.targets:
                if isinstance(target, ast.Name):
                    lists[target.id] = tuple(ast.literal_eval(node.value))
    return lists


def check_python_lists(root, entries, problems):
    """The dataset lists of the Python reader name the datasets of the record lists."""
    lists = python_lists(root, problems)
    wanted = [constant for constant, _, _ in PYTHON_LISTS] + list(REST) + ["HISTORY_LOADS"]
    for constant in wanted:
        if constant not in lists:
            problems.append(f"{PYTHON_READER}: no list {constant}")
    if any(constant not in lists for constant in wanted):
        return
    rest = set()
    for constant, name, kinds in PYTHON_LISTS:
        dataset = TRIAL_DATASETS.get(constant, lambda column: column)
        expected = {dataset(column) for shape, column, kind, _, _ in entries.get(name, [])
                    if kind.lower() in kinds or shape.lower() in kinds}
        compare_names(f"{PYTHON_READER}: {constant}", lists[constant], expected,
                      f"the columns of {name} it holds", problems)
    for shape, column, kind, _, _ in entries.get("for_each_history_column", []):
        if kind.lower() not in NOT_LISTED_KINDS and not any(
                column in lists[constant] for constant, name, _ in PYTHON_LISTS
                if name == "for_each_history_column"):
            rest.add(column)
    writer = routine(root, "src/output/hdf5_records.f90", "write_history", problems) or ""
    rest |= set(re.findall(r"call\s+write_\w+\s*\(\s*writer%group\s*,\s*'(\w+)'",
                           strip_comments(writer)))
    compare_names(f"{PYTHON_READER}: {' + '.join(REST)}",
                  sum((lists[constant] for constant in REST), ()), rest,
                  "the other datasets of /history", problems)
    names = re.search(r"load_path_names\(\d+\)\s*=\s*\[[^:\]]*::((?:[^\]])*)\]",
                      (root / "src/model/types.f90").read_text())
    loads = tuple(re.findall(r"'(\w+)'", names.group(1))) if names else ()
    if lists["HISTORY_LOADS"] != loads:
        problems.append(f"{PYTHON_READER}: HISTORY_LOADS {list(lists['HISTORY_LOADS'])} is not "
                        f"load_path_names {list(loads)} (src/model/types.f90)")


def compare_names(what, names, expected, meaning, problems):
    for name in sorted(set(expected) - set(names)):
        problems.append(f"{what} lacks '{name}', one of {meaning}")
    for name in sorted(set(names) - set(expected)):
        problems.append(f"{what} names '{name}', which is not one of {meaning}")


def statements(text):
    """(line number, statement) of Fortran text, continuation lines joined, comments cut."""
    joined, start = "", 0
    for number, line in enumerate(text.splitlines(), start=1):
        code = re.sub(r"!.*", "", line) if "'" not in line and '"' not in line else line
        if not joined:
            start = number
        joined += " " + code.strip()
        if joined.rstrip().endswith("&"):
            joined = joined.rstrip()[:-1]
            continue
        yield start, joined.strip()
        joined = ""


def check_errors_seen(root, problems):
    """Check 7: an error returned by a routine under test is read before it can be lost."""
    begins = re.compile(r"^(?:(?:pure|elemental|recursive|impure|integer|real(?:\(\w+\))?|"
                        r"logical)\s+)*(?:subroutine|function)\s+\w+\s*(\([^)]*\))?",
                        re.IGNORECASE)
    ends = re.compile(r"^end\s+(?:subroutine|function)\b", re.IGNORECASE)
    passes = re.compile(r"[(,]\s*error\s*\)", re.IGNORECASE)  # last argument: intent(out)
    reads = re.compile(r"(?:allocated|message_of)\s*\(\s*error\s*\)", re.IGNORECASE)
    for path in test_sources(root):
        pending, handed_on = None, False
        where = path.relative_to(root)
        for number, statement in statements(path.read_text()):
            start = begins.match(statement)
            if start and not ends.match(statement):
                pending = None
                handed_on = bool(start.group(1) and passes.search(start.group(1)))
                continue
            if ends.match(statement):
                if pending and not handed_on:
                    problems.append(f"{where}:{pending}: the error this call returns is never "
                                    "read: assert on allocated(error) after it")
                pending = None
                continue
            read = reads.search(statement)
            if read:
                pending = None
            if passes.search(reads.sub("", statement)) and not statement.lower().startswith(
                    ("type(", "class(")):
                if pending and not handed_on:
                    problems.append(f"{where}:{pending}: the error this call returns is lost: "
                                    f"line {number} passes error again before it is read")
                pending = number


# The growth criterion (check 10): where its codes are, and the one module that dispatches.
CRITERIA = "src/model/types.f90"
DISPATCH = "src/growth/criterion.f90"
SELECT_CRITERION = re.compile(r"select\s+case\s*\(\s*[\w%]*%criterion\s*\)(.*?)end\s+select",
                              re.IGNORECASE | re.DOTALL)


def check_criteria(root, problems):
    """Every growth criterion has a case in each dispatch, the only reader (check 10)."""
    codes = set()
    for names in re.findall(r"^\s*integer\s*,\s*parameter\s*::([^\n]*)",
                            strip_comments((root / CRITERIA).read_text()), LINES):
        codes |= {code.lower() for code in re.findall(r"\b(growth_criterion_\w+)\s*=", names)}
    if not codes:
        problems.append(f"{CRITERIA}: no growth criterion (growth_criterion_<name>)")
    dispatch = strip_comments((root / DISPATCH).read_text())
    dispatches = 0
    for name, body in re.findall(r"^\s*(?:\w+\s+)*subroutine\s+(\w+)\b(.*?)^\s*end\s+"
                                 r"subroutine\s+\1\b", dispatch, LINES | re.DOTALL):
        for block in SELECT_CRITERION.findall(body):
            dispatches += 1
            cases = {case.lower() for listed in re.findall(r"\bcase\s*\(([^)]*)\)", block,
                                                           re.IGNORECASE)
                     for case in re.findall(r"\w+", listed)}
            for code in sorted(codes - cases):
                problems.append(f"{DISPATCH}: {name} has no case for {code}")
            if not re.search(r"\bcase\s+default\b", block, re.IGNORECASE):
                problems.append(f"{DISPATCH}: {name} dispatches on the criterion without a "
                                "case default (an unknown criterion must be an internal "
                                "error)")
    if not dispatches:
        problems.append(f"{DISPATCH}: no select case on the growth criterion")
    for path in sorted((root / "src/growth").glob("*.f90")):
        where = path.relative_to(root)
        if str(where) != DISPATCH and re.search(r"%\s*criterion\b",
                                                strip_comments(path.read_text()),
                                                re.IGNORECASE):
            problems.append(f"{where}: reads the growth criterion (%criterion) outside "
                            f"{DISPATCH}, the one place that dispatches on it")


# The strength laws (check 13): the one list, the constant of its length, the fault law.
LAW_LIST = ("src/model/laws.f90", "for_each_law")
LAW_COUNT = ("src/model/types.f90", "strength_law_count")
FAULT_LAW_FILE = "src/contact/fault_law.f90"
# A list line: call action%on_law(law('<name>', <default>, <quantity>, <units>,
# beyond_coulomb=.<true|false>.[, at_most='<x>']), elements%<component>)
LAW_ENTRY = re.compile(r"call\s+action\s*%\s*on_law\s*\(\s*law\s*\(\s*'(\w+)'\s*,\s*([\w.]+)\s*,"
                       r"\s*\w+\s*,\s*\w+\s*,\s*beyond_coulomb\s*=\s*\.(true|false)\.\s*"
                       r"(?:,\s*at_most\s*=\s*'\w*'\s*)?\)\s*,\s*elements\s*%\s*(\w+)\s*\)$",
                       re.IGNORECASE)
# The namelist statements that declare the laws (with a prefix), and the array constructor
# that gathers the values read in the list's order: (file, group, prefix, routine, what
# opens the constructor).
LAW_NAMELISTS = [("src/input/namelist_fracture.f90", "fracture", "", "read_fracture_groups",
                  "reshape("),
                 ("src/input/namelist_growth.f90", "growth", "new_", "read_growth_group",
                  "check_new_laws(")]
# The routines that handle every law, and what of the list each goes through.
THROUGH_LAW_LIST = [("src/model/laws.f90", "default_strength_laws", "strength_laws"),
                    ("src/mesh/geometry.f90", "allocate_elements", "default_strength_laws"),
                    ("src/growth/new_fracture.f90", "add_fracture", "default_strength_laws"),
                    ("src/growth/extension.f90", "take_new_element_laws", "strength_laws"),
                    ("src/model/element_laws.f90", "fault_law_of", "law_values"),
                    ("src/input/namelist_fracture.f90", "read_fracture_groups",
                     "strength_laws"),
                    ("src/input/namelist.f90", "build_model", "strength_laws"),
                    ("src/input/namelist_growth.f90", "check_new_laws", "strength_laws"),
                    ("src/sweep/tasks.f90", "parse_parameter", "strength_laws"),
                    ("src/sweep/tasks.f90", "new_law_problem", "strength_laws"),
                    ("src/output/hdf5.f90", "write_strength_laws", "law_values"),
                    ("app/report.f90", "print_growth_options", "strength_laws"),
                    ("src/run/memory.f90", "records_strengths", "laws_allocated")]


def procedure(root, file, name, problems):
    """The text of a subroutine or function (with comments), or None after a problem."""
    found = re.search(rf"^[ \t]*(?:[\w()]+[ \t]+)*(subroutine|function)[ \t]+{name}\b(.*?)"
                      rf"^\s*end\s+\1\s+{name}\b", (root / file).read_text(),
                      LINES | re.DOTALL)
    if not found:
        problems.append(f"{file}: no subroutine or function {name}")
        return None
    return found.group(2)


def law_entries(root, problems):
    """[(name, default, beyond Coulomb?)] of the list of the strength laws."""
    file, name = LAW_LIST
    text = procedure(root, file, name, problems)
    if text is None:
        return []
    entries = []
    for _, statement in statements(text):
        found = LAW_ENTRY.match(statement)
        if found:
            law, default, beyond, component = found.groups()
            if law.lower() != component.lower():
                problems.append(f"{file}: {name} hands elements%{component} as the law "
                                f"'{law}' (a law is named after its array)")
            entries.append((law.lower(), default.lower(), beyond.lower() == "true"))
        elif re.match(r"call\s+action\s*%", statement, re.IGNORECASE):
            problems.append(f"{file}: {name} has an entry not of the form call action%on_law("
                            "law('<name>', <default>, <quantity>, <units>, beyond_coulomb=..."
                            f"), elements%<name>): {statement}")
    return entries


def check_law_count(root, laws, problems):
    file, constant = LAW_COUNT
    found = re.search(rf"\b{constant}\s*=\s*(\d+)", strip_comments((root / file).read_text()))
    if not found:
        problems.append(f"{file}: no {constant}")
    elif int(found.group(1)) != len(laws):
        problems.append(f"{file}: {constant} = {found.group(1)}, but {LAW_LIST[1]} "
                        f"({LAW_LIST[0]}) lists {len(laws)} laws")


def check_law_arrays(root, laws, problems):
    """Every law is a per-element real array of element_set."""
    types = strip_comments((root / "src/model/types.f90").read_text())
    found = re.search(r"^\s*type\b[^\n]*::\s*element_set\s*$(.*?)^\s*end\s*type",
                      types, LINES | re.DOTALL)
    arrays = set()
    for line in re.sub(r"&\s*\n\s*", " ", found.group(1) if found else "").splitlines():
        if "::" in line and re.match(r"\s*real\b[^:]*allocatable", line, re.IGNORECASE):
            arrays |= {m.lower() for m in re.findall(r"(\w+)\s*\(\s*:\s*\)",
                                                     line.split("::", 1)[1])}
    for law, _, _ in laws:
        if law not in arrays:
            problems.append(f"{LAW_LIST[0]}: the law {law} of {LAW_LIST[1]} is no per-element "
                            "real array of element_set (src/model/types.f90)")


def reached_names(text, start, seen=None):
    """The law%<name> references of a procedure of the fault law and of the procedures of the
    law it calls (law%<procedure>())."""
    seen = seen if seen is not None else set()
    if start in seen:
        return set()
    seen.add(start)
    found = re.search(rf"^[ \t]*(?:[\w()]+[ \t]+)*(subroutine|function)[ \t]+{start}\b(.*?)"
                      rf"^\s*end\s+\1\s+{start}\b", text, LINES | re.DOTALL)
    if not found:
        return set()
    body = strip_comments(found.group(2))
    names = {n.lower() for n in re.findall(r"\blaw\s*%\s*(\w+)\b(?!\s*\()", body)}
    for called in re.findall(r"\blaw\s*%\s*(\w+)\s*\(\s*\)", body):
        names |= reached_names(text, called.lower(), seen)
    return names


def check_fault_law(root, laws, problems):
    """The fault law has each law, sets it by name, defaults it as the list does, and goes
    beyond Coulomb on the laws the list marks so."""
    text = (root / FAULT_LAW_FILE).read_text()
    names = {law for law, _, _ in laws}
    components = {c for c, _, _ in type_components(text, "fault_law") or []}
    for law in sorted(names - components):
        problems.append(f"{FAULT_LAW_FILE}: fault_law has no component {law}, a law of "
                        f"{LAW_LIST[1]} ({LAW_LIST[0]})")
    setter = procedure(root, FAULT_LAW_FILE, "set_given", problems) or ""
    cases = {c.lower() for c in re.findall(r"\bcase\s*\(\s*'(\w+)'\s*\)",
                                           strip_comments(setter), re.IGNORECASE)}
    compare_names(f"{FAULT_LAW_FILE}: set_given", cases, names, f"the laws of {LAW_LIST[1]}",
                  problems)
    # new_fault_law's own statements, not those of its internal given_or
    maker = re.split(r"^\s*contains\s*$", procedure(root, FAULT_LAW_FILE, "new_fault_law",
                                                     problems) or "", maxsplit=1,
                     flags=re.IGNORECASE | re.MULTILINE)[0]
    defaults = {n.lower(): d.lower() for n, d in re.findall(
        r"\bgiven_or\s*\(\s*(\w+)\s*,\s*([\w.]+)\s*\)",
        re.sub(r"&\s*\n\s*", " ", strip_comments(maker)), re.IGNORECASE)}
    compare_names(f"{FAULT_LAW_FILE}: new_fault_law's given_or", defaults, names,
                  f"the laws of {LAW_LIST[1]}", problems)
    for law, default, _ in laws:
        if law in defaults and defaults[law] != default:
            problems.append(f"{FAULT_LAW_FILE}: new_fault_law gives {law} the default "
                            f"{defaults[law]}, {LAW_LIST[1]} ({LAW_LIST[0]}) {default}")
    read = reached_names(text, "beyond_coulomb") & names
    beyond = {law for law, _, marked in laws if marked}
    for law in sorted(beyond - read):
        problems.append(f"{LAW_LIST[0]}: {LAW_LIST[1]} marks {law} beyond Coulomb, which "
                        f"beyond_coulomb ({FAULT_LAW_FILE}) does not read")
    for law in sorted(read - beyond):
        problems.append(f"{LAW_LIST[0]}: {LAW_LIST[1]} does not mark {law} beyond Coulomb, "
                        f"which beyond_coulomb ({FAULT_LAW_FILE}) reads")


def check_law_namelists(root, laws, problems):
    """The namelists declare each law; the values read are gathered in the list's order."""
    for file, group, prefix, reader, opening in LAW_NAMELISTS:
        text = strip_comments((root / file).read_text())
        wanted = [prefix + law for law, _, _ in laws]
        names = []
        for found_group, listed in NAMELIST.findall(text):
            if found_group.lower() == group:
                names = [n.strip().lower() for n in listed.replace("&", " ").split(",")]
        if not names:
            problems.append(f"{file}: no namelist /{group}/")
            continue
        for name in wanted:
            if name not in names:
                problems.append(f"{file}: namelist /{group}/ does not declare {name}, a law "
                                f"of {LAW_LIST[1]}")
        body = re.sub(r"&\s*\n\s*", " ", strip_comments(procedure(root, file, reader,
                                                                   problems) or ""))
        gathered = re.search(re.escape(opening) + r"\s*\[([^\]]*)\]", body, re.IGNORECASE)
        order = [n.strip().lower() for n in gathered.group(1).split(",")] if gathered else []
        if order != wanted:
            problems.append(f"{file}: {reader} gathers the laws' values as {order}, not in the "
                            f"order of {LAW_LIST[1]} {wanted}")


def check_laws(root, problems):
    """Check 13: the list of the strength laws agrees with what holds and reads them."""
    laws = law_entries(root, problems)
    if not laws:
        problems.append(f"{LAW_LIST[0]}: {LAW_LIST[1]} lists no law")
        return
    check_law_count(root, laws, problems)
    check_law_arrays(root, laws, problems)
    check_fault_law(root, laws, problems)
    check_law_namelists(root, laws, problems)
    for file, name, through in THROUGH_LAW_LIST:
        text = procedure(root, file, name, problems)
        if text is not None and not names_in(strip_comments(text), through):
            problems.append(f"{file}: {name} does not go through {through} (the list of "
                            f"the strength laws, {LAW_LIST[0]})")


# A file of the repository named in the recipes, and a name written beside it.
RECIPE_PATH = r"(?:src|app|tests|scripts)/[\w./-]+\.(?:f90|pf|py|c|sh)"
NAME_THEN_PATH = re.compile(r"`(\w+)`\s*\(\s*`(" + RECIPE_PATH + r")`")
PATH_THEN_NAME = re.compile(r"`(" + RECIPE_PATH + r")`\s*\(\s*`(\w+)`")


def check_recipes(root, problems):
    """Check 12: the recipes name files that exist and names those files hold."""
    text = (root / TABLE).read_text()
    recipes = text[text.find("## Recipes"):]
    for path in sorted(set(re.findall(r"`(" + RECIPE_PATH + r")`", recipes))):
        if not (root / path).is_file():
            problems.append(f"{TABLE}: a recipe names {path}, which does not exist")
    pairs = [(n, p) for n, p in NAME_THEN_PATH.findall(recipes)]
    pairs += [(n, p) for p, n in PATH_THEN_NAME.findall(recipes)]
    for name, path in sorted(set(pairs)):
        if (root / path).is_file() and not re.search(
                rf"\b{name}\b", (root / path).read_text(), re.IGNORECASE):
            problems.append(f"{TABLE}: a recipe names {name} in {path}, which has no {name}")


#: Where tests and scripts live, and the files that may name /tmp: the Fortran suites'
#: fallback and the planted violations of this check.
TEMPORARY_FOLDERS = ("tests", "scripts")
TEMPORARY_SKIPPED = ("tests/data/", "tests/reference/")
TEMPORARY_ALLOWED = ("tests/fortran/support/temporary.f90",
                     "tests/architecture/test_check_sources.py")
SYSTEM_TEMPORARY = re.compile(r"['\"]/tmp(?=[/'\"])")


def check_temporary_paths(root, problems):
    """Check 13: no test or script writes into /tmp by name."""
    for folder in TEMPORARY_FOLDERS:
        for path in sorted((root / folder).rglob("*")):
            relative = path.relative_to(root).as_posix()
            if not path.is_file() or relative.startswith(TEMPORARY_SKIPPED) or \
                    relative in TEMPORARY_ALLOWED or "__pycache__" in relative:
                continue
            try:
                lines = path.read_text().splitlines()
            except UnicodeDecodeError:
                continue
            for number, line in enumerate(lines, start=1):
                if SYSTEM_TEMPORARY.search(line):
                    problems.append(f"{relative}:{number}: names /tmp: write into the "
                                    "test's own temporary folder ($TMPDIR, tmp_path, "
                                    "temporary_path)")


def main(argv):
    graph_wanted = "--graph" in argv
    args = [a for a in argv if a != "--graph"]
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    root = Path(args[0]).resolve()
    problems = []
    graph, edges = check_folders(root, problems)
    check_table(root, graph, edges, problems)
    namelists = check_namelists(root, problems)
    check_imports(root, problems)
    check_shared(root, problems)
    check_errors_seen(root, problems)
    check_fingerprint(root, problems)
    check_lcp_solvers(root, problems)
    check_criteria(root, problems)
    check_record_lists(root, problems)
    check_laws(root, problems)
    check_recipes(root, problems)
    check_temporary_paths(root, problems)
    if graph_wanted:
        for folder in sorted(graph):
            print(f"{folder}: {', '.join(sorted(graph[folder])) or '-'}")
    for problem in problems:
        print(problem)
    if not problems:
        print(f"architecture: {len(graph)} folders, no cycle, every folder edge listed in "
              f"{TABLE}; module names follow their paths; the {namelists} namelist "
              "statements match the group table; every import is used; every component of "
              "element_set and solver_options is broadcast or marked root only; every "
              "error a test gets is read; every component of the model is hashed in its "
              "fingerprint or marked not hashed; no LCP solver reaches the fault law; "
              "every growth criterion has its case in each dispatch, the only reader of "
              "the criterion; every column of the history and growth records is in its "
              "list, and the Python reader knows its dataset; the strength laws are listed "
              "once, as the element arrays, the fault law and the namelists have them; the "
              "recipes name what exists; no test names /tmp")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
