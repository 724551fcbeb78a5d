"""One version and one licence, though several files write them (CTest package_metadata,
label lint).

The version is project(VERSION) of CMakeLists.txt, given by CTest as DDC2D_VERSION (read
from CMakeLists.txt when this runs by hand). The program's echo (src/version.f90.in), the
pkg-config file and the Lmod module file are configured from it by CMake (the CTest
install checks the installed ones); what cannot be configured is held to it here: the
Python package (ddc2d.__version__, which python/pyproject.toml reads, so that python/ alone
builds), CITATION.cff, the Spack package's newest version() and every ddc2d@VERSION and
modulefiles/ddc2d/VERSION.lua that the documentation and the packaging name.

The licence is MIT: LICENSE, python/LICENSE (its copy in the Python package), CITATION.cff,
python/pyproject.toml, the Spack package and the pkg-config file say so.
"""

import ast
import os
import re
import tomllib
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
SPACK_PACKAGE = REPO_ROOT / "packaging" / "spack" / "ddc2d" / "package.py"
PYTHON = REPO_ROOT / "python"
#: Where a version is named in the text: `spack dev-build ddc2d@0.1.0`, an Lmod file.
NAMED_VERSION = re.compile(r"ddc2d@(\d[\w.]*)|modulefiles/ddc2d/(\d[\w.]*?)\.lua")
#: Text that names versions of the program (CHANGELOG.md names every release: not here).
NAMING_FILES = (REPO_ROOT / "README.md", *sorted((REPO_ROOT / "docs").rglob("*.md")),
                *sorted((REPO_ROOT / "packaging").rglob("*.*")))


def project_version():
    """DDC2D_VERSION, else the VERSION of project() in CMakeLists.txt."""
    if os.environ.get("DDC2D_VERSION"):
        return os.environ["DDC2D_VERSION"]
    found = re.search(r"^project\(ddc2d\s+VERSION\s+([\d.]+)",
                      (REPO_ROOT / "CMakeLists.txt").read_text(), re.MULTILINE)
    assert found, "no project(ddc2d VERSION ...) in CMakeLists.txt"
    return found[1]


def citation_field(name):
    """A top-level scalar of CITATION.cff (YAML; no YAML reader is needed for these)."""
    found = re.search(rf"^{name}:\s*(\S+)\s*$", (REPO_ROOT / "CITATION.cff").read_text(),
                      re.MULTILINE)
    assert found, f"CITATION.cff has no top-level {name}"
    return found[1].strip("'\"")


def spack_calls(name):
    """The first argument of each call `name(...)` in the Spack package's class body."""
    tree = ast.parse(SPACK_PACKAGE.read_text())
    return [node.value.args[0].value for node in ast.walk(tree)
            if isinstance(node, ast.Expr) and isinstance(node.value, ast.Call)
            and getattr(node.value.func, "id", None) == name]


def python_version():
    """ddc2d.__version__ as python/src/ddc2d/__init__.py assigns it."""
    tree = ast.parse((PYTHON / "src" / "ddc2d" / "__init__.py").read_text())
    for node in tree.body:
        if isinstance(node, ast.Assign) and [getattr(t, "id", "") for t in node.targets] == \
                ["__version__"]:
            return ast.literal_eval(node.value)
    pytest.fail("python/src/ddc2d/__init__.py assigns no __version__")


def pyproject():
    return tomllib.loads((PYTHON / "pyproject.toml").read_text())


def version_key(text):
    return tuple(int(part) if part.isdigit() else part for part in text.split("."))


def test_the_python_package_has_the_programs_version():
    project = pyproject()
    assert "version" not in project["project"], "pyproject.toml: a version of its own"
    assert "version" in project["project"]["dynamic"]
    assert project["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "ddc2d.__version__"}
    assert python_version() == project_version(), "ddc2d.__version__ against project(VERSION)"


def test_citation_and_spack_have_the_programs_version():
    assert citation_field("version") == project_version(), "CITATION.cff version"
    versions = spack_calls("version")
    assert versions, "the Spack package has no version()"
    assert max(versions, key=version_key) == project_version(), "the Spack package's newest"


def test_the_text_names_the_programs_version():
    named = {(path.relative_to(REPO_ROOT).as_posix(), number)
             for path in NAMING_FILES for found in NAMED_VERSION.finditer(path.read_text())
             for number in found.groups() if number}
    assert named, "no ddc2d@VERSION found: has the documentation of Spack moved?"
    other = sorted(entry for entry in named if entry[1] != project_version())
    assert not other, f"versions other than {project_version()}: {other}"


def test_the_licence_is_mit_everywhere():
    licence = (REPO_ROOT / "LICENSE").read_text()
    assert licence.startswith("MIT License\n")
    assert (PYTHON / "LICENSE").read_text() == licence, "python/LICENSE is not LICENSE's copy"
    assert citation_field("license") == "MIT"
    assert pyproject()["project"]["license"] == "MIT"
    assert pyproject()["project"]["license-files"] == ["LICENSE"]
    assert spack_calls("license") == ["MIT"]
    pc = (REPO_ROOT / "packaging" / "ddc2d.pc.in").read_text()
    assert re.search(r"^License: MIT$", pc, re.MULTILINE), "ddc2d.pc.in: License: MIT"
