#!/usr/bin/env python3
"""Hold the documentation to the repository (CTest docs_checks).

    check_docs.py SOURCE_ROOT

1. The repository explains itself: no source, test, script, Python module, example input,
   README or page of docs/ cites a design note outside it ("SPEC section 7", "SPEC-GROWTH
   1.4") or an issue of the tracker ("issue 26"); they cite the pages of docs/ instead.
2. Every relative link and image of README.md and docs/ resolves: the file exists and, for
   a link to a heading (`page.md#heading`, `#heading`), the heading does (GitHub's anchors:
   lower case, punctuation dropped, spaces as hyphens). Web addresses are not followed.
3. Every module of src/ and app/, and every public procedure and generic interface of
   one, has a `!>` summary line right above it (FORD's API pages show it).
4. Every page of docs/ that src/, app/, tests/ (not tests/reference/), scripts/, python/ or
   input/ names (`docs/theory/growth.md`, `docs/theory/growth.md#closed-kinks`, in a comment, a
   message or a test) exists, and so does the heading after `#` (the anchors of check 2).

The checker and its test (tests/architecture/) name what they look for and plant
violations: checks 1 and 4 skip them.

Prints every violation and exits 1 when there is one.
"""
import re
import sys
from pathlib import Path

#: Where the repository's own text lives (tests/reference/ holds TWODD's prints: not ours).
CITING_FOLDERS = ("src", "app", "tests", "scripts", "python", "input", "docs")
CITING_SUFFIXES = {".f90", ".F90", ".pf", ".c", ".py", ".sh", ".nml", ".md", ".txt", ".cmake",
                   ".toml", ".json", ".in", ""}
SKIPPED = ("tests/reference/", "tests/data/twodd/")
#: Check 4 reads the code, tests, scripts and example inputs.
NAMING_FOLDERS = ("src", "app", "tests", "scripts", "python", "input")
#: The checker and its test name the patterns (and plant violations) on purpose.
SELF = ("tests/architecture/check_docs.py", "tests/architecture/test_check_docs.py")
DESIGN_NOTE = re.compile(r"\bSPEC(?:-[A-Z]+)?\b(?=[\s,.;:)]|$)")
ISSUE = re.compile(r"\bissues?\s+#?\d+", re.IGNORECASE)
DOC_PAGE = re.compile(r"(?<![\w./-])docs/[\w./-]*?\.md(?:#[\w-]+)?")
LINK = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
FENCE = re.compile(r"^\s*(```|~~~)")


def repository_texts(root, folders=CITING_FOLDERS, top_level=True):
    """The text files of the folders (less SKIPPED and SELF), then those at the top level."""
    for folder in folders:
        for path in sorted((root / folder).rglob("*")):
            relative = path.relative_to(root).as_posix()
            if path.is_file() and path.suffix in CITING_SUFFIXES and \
                    not relative.startswith(SKIPPED) and relative not in SELF and \
                    "__pycache__" not in relative:
                yield path
    for name in ("README.md", "CMakeLists.txt", "CHANGELOG.md"):
        if top_level and (root / name).is_file():
            yield root / name


def text_lines(path):
    """(line number, line) of a text file; none for a file that is not UTF-8."""
    try:
        return list(enumerate(path.read_text().splitlines(), start=1))
    except UnicodeDecodeError:
        return []


def check_citations(root, problems):
    """Check 1: no design note and no issue of the tracker is cited."""
    for path in repository_texts(root):
        for number, line in text_lines(path):
            for pattern, what in ((DESIGN_NOTE, "a design note outside the repository"),
                                  (ISSUE, "an issue of the tracker")):
                found = pattern.search(line)
                if found:
                    problems.append(f"{path.relative_to(root)}:{number}: cites {what} "
                                    f"('{found.group(0)}'): cite the page of docs/ instead")


def anchor(heading):
    """GitHub's anchor of a Markdown heading."""
    text = re.sub(r"[`*]|<[^>]+>", "", heading.strip().lower())
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def markdown_lines(path):
    """(line number, line) outside fenced code blocks."""
    inside = False
    for number, line in enumerate(path.read_text().splitlines(), start=1):
        if FENCE.match(line):
            inside = not inside
            continue
        if not inside:
            yield number, line


def anchors_of(path):
    seen = {}
    anchors = set()
    for _, line in markdown_lines(path):
        heading = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if heading:
            base = anchor(heading.group(1))
            count = seen.get(base, 0)
            anchors.add(base if count == 0 else f"{base}-{count}")
            seen[base] = count + 1
        for name in re.findall(r"<a\s+(?:name|id)=\"([^\"]+)\"", line):
            anchors.add(name)
    return anchors


def check_links(root, problems):
    """Check 2: relative links and images of README.md and docs/ resolve."""
    pages = [root / "README.md"] + sorted((root / "docs").rglob("*.md"))
    for page in pages:
        for number, line in markdown_lines(page):
            for target in LINK.findall(re.sub(r"`[^`]*`", "", line)):
                if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.IGNORECASE):
                    continue  # a web address or mail link
                file_part, _, heading = target.partition("#")
                linked = (page.parent / file_part).resolve() if file_part else page
                where = f"{page.relative_to(root)}:{number}"
                if not linked.exists():
                    problems.append(f"{where}: link to {target}: no such file")
                elif heading and linked.suffix == ".md" and heading not in anchors_of(linked):
                    problems.append(f"{where}: link to {target}: no such heading in "
                                    f"{linked.relative_to(root)}")


def check_named_pages(root, problems):
    """Check 4: the pages of docs/ that code, tests, scripts and inputs name exist."""
    headings = {}
    for path in repository_texts(root, NAMING_FOLDERS, top_level=False):
        for number, line in text_lines(path):
            for found in DOC_PAGE.finditer(line):
                page, _, heading = found.group(0).partition("#")
                target = root / page
                where = f"{path.relative_to(root)}:{number}: names {found.group(0)}"
                if not target.is_file():
                    problems.append(f"{where}: no such file")
                    continue
                if target not in headings:
                    headings[target] = anchors_of(target)
                if heading and heading not in headings[target]:
                    problems.append(f"{where}: no such heading in {page}")


PUBLIC = re.compile(r"^\s*public\s*::((?:[^\n]*&\s*\n)*[^\n]*)", re.IGNORECASE | re.MULTILINE)
DEFINES = re.compile(r"^\s*(?:(?:pure|elemental|recursive|impure|module|integer|logical|"
                     r"real\(\w+\)|character\([^)]*\)|type\(\w+\))\s+)*"
                     r"(subroutine|function|interface|module)\s+(\w+)", re.IGNORECASE)


def check_summaries(root, problems):
    """Check 3: modules, public procedures and generic interfaces have a `!>` summary."""
    for path in sorted(p for folder in ("src", "app") for p in (root / folder).rglob("*.f90")):
        text = path.read_text()
        lines = text.splitlines()
        public = set()
        for names in PUBLIC.findall(text):
            public |= {n.strip().lower() for n in names.replace("&", " ").split(",") if n.strip()}
        for number, line in enumerate(lines, start=1):
            found = DEFINES.match(line)
            if not found or line.strip().lower().startswith(("module procedure", "end")):
                continue
            kind, name = found.group(1).lower(), found.group(2).lower()
            if kind != "module" and name not in public:
                continue
            above = number - 2
            while above >= 0 and lines[above].strip().startswith("!") and \
                    not lines[above].strip().startswith("!>"):
                above -= 1
            if above < 0 or not lines[above].strip().startswith("!>"):
                problems.append(f"{path.relative_to(root)}:{number}: {kind} {name} has no "
                                "'!>' summary line above it")


def main(argv):
    if len(argv) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    root = Path(argv[0]).resolve()
    problems = []
    check_citations(root, problems)
    check_links(root, problems)
    check_summaries(root, problems)
    check_named_pages(root, problems)
    for problem in problems:
        print(problem)
    if not problems:
        print("docs: no design note or issue cited; every relative link of README.md and "
              "docs/ resolves; every module and public procedure has a summary; every page "
              "of docs/ that the code, tests, scripts and inputs name exists")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
