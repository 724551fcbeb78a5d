"""The documentation checks fail when fed a planted violation (CTest docs_checks_planted).

Each case copies what the checks read (src/, app/, tests/fortran, scripts/, input/, docs/,
README.md) to a temporary folder, plants one violation and expects check_docs.py to exit 1
naming it; the copy as it is must pass, so each failure comes from the planted line alone.
"""

import shutil
import sys
from pathlib import Path

import pytest

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
REPO_ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))

import check_docs  # noqa: E402  (imported from this folder)


@pytest.fixture
def tree(tmp_path):
    """A copy of what the checks read."""
    for folder in ("src", "app", "scripts", "input", "docs", "tests/fortran", "python/src"):
        shutil.copytree(REPO_ROOT / folder, tmp_path / folder)
    shutil.copy(REPO_ROOT / "README.md", tmp_path)
    for name in ("CITATION.cff", "CHANGELOG.md", "LICENSE"):
        if (REPO_ROOT / name).exists():
            shutil.copy(REPO_ROOT / name, tmp_path)
    return tmp_path


def expect_violation(root, capsys, text):
    status = check_docs.main([str(root)])
    out = capsys.readouterr().out
    assert status == 1 and text in out, out


def append(path, text):
    path.write_text(path.read_text() + text)


def test_copy_passes(tree, capsys):
    assert check_docs.main([str(tree)]) == 0, capsys.readouterr().out


def test_design_note_citation_fails(tree, capsys):
    append(tree / "src/contact/lemke.f90", "! Lexicographic rule (SPEC section 4).\n")
    expect_violation(tree, capsys, "src/contact/lemke.f90:")


def test_issue_reference_fails(tree, capsys):
    append(tree / "docs/fracture-growth.md", "\nAdded in issue 25.\n")
    expect_violation(tree, capsys, "cites an issue of the tracker ('issue 25')")


def test_missing_file_link_fails(tree, capsys):
    append(tree / "README.md", "\nSee [the manual](docs/no-such-page.md).\n")
    expect_violation(tree, capsys, "link to docs/no-such-page.md: no such file")


def test_missing_heading_link_fails(tree, capsys):
    append(tree / "docs/getting-started.md", "\nSee [groups](input-reference.md#no-such-group).\n")
    expect_violation(tree, capsys, "no such heading in docs/input-reference.md")


def test_public_procedure_without_summary_fails(tree, capsys):
    path = tree / "src/text.f90"
    text = path.read_text()
    start = text.index("    !> Real as short text")
    end = text.index("\n", start) + 1
    path.write_text(text[:start] + text[end:])
    expect_violation(tree, capsys, "src/text.f90:")


def test_named_page_without_heading_fails(tree, capsys):
    append(tree / "src/contact/lemke.f90", "! Lemke (docs/theory/contact.md#no-such).\n")
    expect_violation(tree, capsys, "names docs/theory/contact.md#no-such: no such heading in "
                     "docs/theory/contact.md")


def test_named_missing_page_fails(tree, capsys):
    append(tree / "input/paper_fault_history.nml", "! See docs/no-such-page.md.\n")
    expect_violation(tree, capsys, "names docs/no-such-page.md: no such file")


def test_web_addresses_and_code_are_not_links(tree, capsys):
    append(tree / "docs/plotting.md", "\nSee [pFUnit](https://github.com/x/y#z) and "
           "`[a](missing.md)`.\n\n```\n[b](also-missing.md)\n```\n")
    assert check_docs.main([str(tree)]) == 0, capsys.readouterr().out
