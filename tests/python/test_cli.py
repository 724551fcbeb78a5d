"""The ddc2d command line (docs/getting-started.md#the-command-line): usage, exit codes, output
files, bad input.

Every failing run must exit with its documented status, print one message naming what was
wrong, and leave neither the output file nor a .partial file behind.
"""

import itertools
import subprocess

import h5py
import numpy as np
import pytest

from conftest import REPO_ROOT, ddc2d_exe
from ddc2d.reader import is_complete

GOOD_MODEL = """\
&model youngs_modulus = 1.0, poissons_ratio = 0.25 /
&fracture x = -1.0, 1.0, y = 0.0, 0.0, elements = 20, condition = 'traction',
          bc_n = -1.0 /
"""


def run(args, cwd):
    return subprocess.run([str(ddc2d_exe()), *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, timeout=120)


def leftovers(folder):
    return sorted(p.name for p in folder.iterdir() if p.suffix in (".h5", ".partial"))


def test_version_and_help(tmp_path):
    done = run(["--version"], tmp_path)
    assert done.returncode == 0
    assert done.stdout.startswith("ddc2d ")
    done = run(["--help"], tmp_path)
    assert done.returncode == 0
    assert "usage: ddc2d INPUT.nml" in done.stdout


@pytest.mark.parametrize("args, words", [
    ([], "no input file"),
    (["--frobnicate"], "unknown option --frobnicate"),
    (["model.nml", "-o"], "needs a file name"),
])
def test_bad_usage_exits_2(tmp_path, args, words):
    done = run(args, tmp_path)
    assert done.returncode == 2
    assert words in done.stderr


def test_good_model_writes_complete_file(tmp_path):
    (tmp_path / "crack.nml").write_text(GOOD_MODEL)
    done = run(["crack.nml"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert leftovers(tmp_path) == ["crack.h5"]  # default name: input base name + .h5
    with h5py.File(tmp_path / "crack.h5") as f:
        assert is_complete(f.attrs)
        dn = f["elements/dn"][:]
        assert dn.shape == (20,)
        assert np.all(dn < 0.0)  # the pressurized crack opens
        assert b"bc_n = -1.0" in f.attrs["input_text"]


def test_output_option_overrides_default(tmp_path):
    (tmp_path / "crack.nml").write_text(GOOD_MODEL)
    done = run(["crack.nml", "-o", "other.h5"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert leftovers(tmp_path) == ["other.h5"]


def test_missing_input_file(tmp_path):
    done = run(["absent.nml"], tmp_path)
    assert done.returncode == 2
    assert "absent.nml" in done.stderr
    assert leftovers(tmp_path) == []


@pytest.mark.parametrize("option", ["-o", "--res"])
def test_unwritable_output_path_exits_3(tmp_path, option):
    # docs/troubleshooting.md#exit-status: 3 = reading or writing a file failed; a missing
    # folder is not created.
    (tmp_path / "crack.nml").write_text(GOOD_MODEL)
    done = run(["crack.nml", option, "no/such/folder/out.h5"], tmp_path)
    assert done.returncode == 3, done.stderr
    assert "no/such/folder/out.h5" in done.stderr
    assert "no/such/folder does not exist" in done.stderr
    assert [line for line in done.stderr.splitlines() if line.startswith("ddc2d:")] == [
        line for line in done.stderr.splitlines() if "no/such/folder" in line]
    assert leftovers(tmp_path) == []
    assert not (tmp_path / "no").exists()


def test_output_path_that_is_a_folder_exits_3(tmp_path):
    # A folder as target is refused like every target that is not a regular file.
    (tmp_path / "crack.nml").write_text(GOOD_MODEL)
    (tmp_path / "out").mkdir()
    done = run(["crack.nml", "-o", "out"], tmp_path)
    assert done.returncode == 3, done.stderr
    assert "out is a folder" in done.stderr


@pytest.mark.parametrize("text, words", [
    (GOOD_MODEL.replace("youngs_modulus", "youngs_modulu"), ["youngs_modulu"]),
    (GOOD_MODEL.replace("youngs_modulus = 1.0", "youngs_modulus = -1.0"),
     ["&model", "youngs_modulus"]),
    (GOOD_MODEL.replace("poissons_ratio = 0.25", "poissons_ratio = 0.5"),
     ["&model", "poissons_ratio"]),
    (GOOD_MODEL.replace("elements = 20", "elements = 0"), ["&fracture", "elements"]),
    (GOOD_MODEL.replace("bc_n = -1.0", "bc_n = NaN"), ["&fracture", "bc_n"]),
    (GOOD_MODEL.replace("bc_n = -1.0", "bc_n = 1e308"), ["&fracture", "bc_n", "1e50"]),
    (GOOD_MODEL.replace("youngs_modulus = 1.0", "youngs_modulus = 1e-320"),
     ["&model", "youngs_modulus", "1e-50"]),
    (GOOD_MODEL.replace("y = 0.0, 0.0", "y = 0.0"), ["&fracture", "y"]),
    (GOOD_MODEL.split("&fracture")[0], ["&fracture"]),
    (GOOD_MODEL + "&grid nx = 0, ny = 3, xmin = 0, xmax = 1, ymin = 0, ymax = 1 /\n",
     ["&grid", "nx"]),
    (GOOD_MODEL.replace("condition = 'traction',", "condition = 'contact', mu = -0.1,")
     .replace("bc_n = -1.0", ""), ["&fracture", "mu"]),
])
def test_bad_input_exits_2_without_output(tmp_path, text, words):
    (tmp_path / "bad.nml").write_text(text)
    done = run(["bad.nml"], tmp_path)
    assert done.returncode == 2, done.stdout + done.stderr
    assert "bad.nml" in done.stderr
    for word in words:
        assert word in done.stderr
    assert leftovers(tmp_path) == []


def test_duplicate_fracture_is_bad_input(tmp_path):
    # Elements on top of each other would make the influence matrix singular; the mesh
    # checks reject them before any solve.
    text = GOOD_MODEL + ("&fracture x = -1.0, 1.0, y = 0.0, 0.0, elements = 20, "
                         "condition = 'traction' /\n")
    (tmp_path / "dup.nml").write_text(text)
    done = run(["dup.nml"], tmp_path)
    assert done.returncode == 2
    assert "duplicates" in done.stderr
    assert leftovers(tmp_path) == []


BAD_FILES = sorted(p for folder in ("input", "half_plane", "history", "growth", "bimaterial",
                                    "cycle")
                   for p in (REPO_ROOT / "tests" / "data" / folder).glob("bad_*.nml"))


@pytest.mark.parametrize("bad", BAD_FILES, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_every_bad_input_file_exits_2_without_output(tmp_path, bad):
    # The Fortran suites check each message in detail; here the executable itself must
    # answer each of them with exit 2, a message naming the file, and no output file.
    done = run([bad, "-o", tmp_path / "out.h5"], tmp_path)
    assert done.returncode == 2, done.stdout + done.stderr
    assert bad.name in done.stderr
    assert done.stderr.count("ddc2d: error:") == 1
    assert leftovers(tmp_path) == []


BRANCH_MODEL = """\
&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /
&remote_stress sxx = -143.75, syy = -81.25, sxy = 54.13 /
&fracture name = 'main', x = -1.0, 0.0, 1.0, y = 0.0, 0.0, 0.0, elements = 30, 30,
          mu = 0.6, sf = 1.0 /
&fracture name = 'branch', x = 0.0, 0.6128355545, y = 0.0, -0.5142300877, elements = 24,
          mu = 0.6, sf = 1.0 /
&solver lcp_method = '{method}' /
"""


def test_solver_failure_exits_1_and_auto_records_its_fallback(tmp_path):
    # A branch at 40 degrees: Lemke ends on a ray (exit 1, no file); 'auto' then asks the
    # Newton method and says so in /solver.
    (tmp_path / "lemke.nml").write_text(BRANCH_MODEL.format(method="lemke"))
    done = run(["lemke.nml"], tmp_path)
    assert done.returncode == 1, done.stdout + done.stderr
    assert "Lemke ended on a ray" in done.stderr
    assert leftovers(tmp_path) == []
    (tmp_path / "auto.nml").write_text(BRANCH_MODEL.format(method="auto"))
    done = run(["auto.nml"], tmp_path)
    assert done.returncode == 0, done.stderr
    with h5py.File(tmp_path / "auto.h5") as f:
        assert f["solver"].attrs["method"] == b"newton"
        assert b"Lemke ended on a ray" in f["solver"].attrs["fallback"]
        assert f["solver"].attrs["certificate_max_complementarity"] <= \
            f["solver"].attrs["certificate_tolerance"]


# A sliding flaw of 1000 elements (the size at which the solvers report their phases) whose
# wings grow three steps, each with a few quick corrector solves.
LARGE_GROWTH = """\
&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /
&remote_stress sxx = -5.0, syy = -60.0 /
&fracture name = 'flaw', x = -0.70710678, 0.70710678, y = -0.70710678, 0.70710678,
          elements = 1000, mu = 0.6, sf = 0.0 /
&growth steps = 3, toughness = 2.0, increment = 0.01 /
"""


def test_growth_steps_hold_the_solver_lines(tmp_path):
    """Within a growth step the Newton iterations of its corrector solves are shown only once
    the step has run 5 s (docs/fracture-growth.md#while-it-runs): a quicker step prints its
    own line only; the solve of the input geometry before the first step prints its own."""
    (tmp_path / "large.nml").write_text(LARGE_GROWTH)
    done = run(["large.nml"], tmp_path)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    steps = [i for i, line in enumerate(lines) if line.startswith("growth step ")]
    assert len(steps) == 3
    assert any("newton iteration" in line for line in lines[:steps[0]])
    for before, after in itertools.pairwise(steps):
        seconds = float(lines[after].split("solve(s),")[1].split()[0])
        newton = [line for line in lines[before + 1:after] if "newton iteration" in line]
        # Without the hold 12 or more such lines came between two of these steps.
        assert seconds >= 5.0 or not newton, lines[before:after + 1]
