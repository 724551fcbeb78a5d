"""scripts/twodd2nml and scripts/compare-twodd, and the `ddc2d --twodd ... --res` path.

The ddc2d executable comes from the environment variable DDC2D_EXE (set by CTest or by
hand), else from build/debug (conftest.ddc2d_exe).
"""

import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import REPO_ROOT, ddc2d_exe

SCRIPTS = REPO_ROOT / "scripts"
REFERENCE = REPO_ROOT / "tests" / "reference" / "twodd"
DATA = REPO_ROOT / "tests" / "data" / "twodd"
CASES = ["A1_press_n20", "B1_rshear_n20"]


def run(args, cwd):
    return subprocess.run([str(a) for a in args], cwd=cwd, capture_output=True, text=True,
                          timeout=300)


def script(name, *args, cwd):
    return run([sys.executable, SCRIPTS / name, *args], cwd)


def run_deck(deck, tmp_path, name, res=None):
    out = tmp_path / f"{name}.h5"
    args = [ddc2d_exe(), "--twodd", deck, "-o", out]
    if res is not None:
        args += ["--res", res]
    done = run(args, tmp_path)
    assert done.returncode == 0, done.stderr
    return out


@pytest.mark.parametrize("case", CASES)
def test_twodd2nml_equals_deck(case, tmp_path):
    deck = REFERENCE / "inputs" / f"{case}.f60.txt"
    nml = tmp_path / f"{case}.nml"
    done = script("twodd2nml", deck, "-o", nml, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    text = nml.read_text()
    assert text.count("&fracture") == 1 and text.count("&line") == 4
    assert "points = 1 /" in text  # the coincident-end observation line
    from_nml = tmp_path / "from_nml.h5"
    done = run([ddc2d_exe(), nml, "-o", from_nml], tmp_path)
    assert done.returncode == 0, done.stderr
    from_deck = run_deck(deck, tmp_path, "from_deck")
    with h5py.File(from_nml) as a, h5py.File(from_deck) as b:
        for key in ("x_mid", "y_mid", "ds", "dn", "us_minus", "un_plus", "shear_traction",
                    "normal_traction"):
            np.testing.assert_allclose(a["elements"][key][...], b["elements"][key][...],
                                       rtol=0, atol=1e-13, err_msg=key)
        assert sorted(a["fields"]) == sorted(b["fields"])
        for name in a["fields"]:
            for key in ("x", "y", "ux", "uy", "sxx", "syy", "sxy"):
                np.testing.assert_allclose(a["fields"][name][key][...],
                                           b["fields"][name][key][...], rtol=0, atol=1e-13,
                                           err_msg=f"{name}/{key}")


@pytest.mark.parametrize("deck", ["sym_ksym2", "sym_ksym3", "sym_ksym4"])
def test_twodd2nml_symmetric_deck(deck, tmp_path):
    nml = tmp_path / f"{deck}.nml"
    done = script("twodd2nml", DATA / f"{deck}.f60.txt", "-o", nml, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert "&symmetry kind = " in nml.read_text()
    from_nml = tmp_path / "from_nml.h5"
    done = run([ddc2d_exe(), nml, "-o", from_nml], tmp_path)
    assert done.returncode == 0, done.stderr
    from_deck = run_deck(DATA / f"{deck}.f60.txt", tmp_path, "from_deck")
    with h5py.File(from_nml) as a, h5py.File(from_deck) as b:
        for key in ("ds", "dn", "us_minus", "normal_traction"):
            np.testing.assert_allclose(a["elements"][key][...], b["elements"][key][...],
                                       rtol=0, atol=1e-13, err_msg=key)
        for key in ("ux", "sxx", "sxy"):
            np.testing.assert_allclose(a["fields/line_1"][key][...],
                                       b["fields/line_1"][key][...], rtol=0, atol=1e-13)


def test_twodd2nml_rejects_bad_decks(tmp_path):
    done = script("twodd2nml", DATA / "bad_kode7.f60.txt", cwd=tmp_path)
    assert done.returncode == 2 and "line 5" in done.stderr and "KODE = 7" in done.stderr
    done = script("twodd2nml", DATA / "bad_too_few_lines.f60.txt", cwd=tmp_path)
    assert done.returncode == 2 and "line 7" in done.stderr
    done = script("twodd2nml", DATA / "bad_non_numeric.f60.txt", cwd=tmp_path)
    assert done.returncode == 2 and "line 4" in done.stderr


@pytest.mark.parametrize("case", CASES)
def test_compare_twodd_classic_and_wide(case, tmp_path):
    ours = run_deck(REFERENCE / "inputs" / f"{case}.f60.txt", tmp_path, case)
    classic = REFERENCE / "output_classic" / f"{case}.RESf60.txt"
    done = script("compare-twodd", ours, classic, cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "points matched: 26 of 26" in done.stdout
    wide = REFERENCE / "output_double_precision" / f"{case}.RESf60.txt"
    done = script("compare-twodd", ours, wide, "--rtol", "1e-9", "--atol", "1e-12",
                  cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr


def test_compare_twodd_fails_on_perturbed_print(tmp_path):
    ours = run_deck(REFERENCE / "inputs" / "A1_press_n20.f60.txt", tmp_path, "A1")
    lines = (REFERENCE / "output_classic" / "A1_press_n20.RESf60.txt").read_text()
    # DN of element 10 changed in its third digit: -3.840E+00 -> -3.850E+00.
    perturbed = lines.replace("-3.840E+00", "-3.850E+00", 1)
    assert perturbed != lines
    bad = tmp_path / "perturbed.txt"
    bad.write_text(perturbed)
    done = script("compare-twodd", ours, bad, cwd=tmp_path)
    assert done.returncode == 1, done.stdout
    assert "DN" in done.stdout and "FAIL" in done.stdout


def test_compare_twodd_unreadable_input(tmp_path):
    ours = run_deck(REFERENCE / "inputs" / "A1_press_n20.f60.txt", tmp_path, "A1")
    done = script("compare-twodd", ours, tmp_path / "missing.txt", cwd=tmp_path)
    assert done.returncode == 2
    junk = tmp_path / "junk.txt"
    junk.write_text("not a print\n")
    done = script("compare-twodd", ours, junk, cwd=tmp_path)
    assert done.returncode == 2
    done = script("compare-twodd", junk,
                  REFERENCE / "output_classic" / "A1_press_n20.RESf60.txt", cwd=tmp_path)
    assert done.returncode == 2


def test_cli_twodd_with_res(tmp_path):
    res = tmp_path / "A1.res.txt"
    ours = run_deck(REFERENCE / "inputs" / "A1_press_n20.f60.txt", tmp_path, "A1", res=res)
    assert ours.exists() and res.exists()
    assert not list(tmp_path.glob("*.partial"))
    text = res.read_text().splitlines()
    wide = (REFERENCE / "output_double_precision" / "A1_press_n20.RESf60.txt").read_text()
    wide = wide.splitlines()
    assert len(text) == len(wide)
    assert text[:24] == wide[:24]  # header block and headings line for line
    # Our own tables compare to the reference wide print at double precision.
    done = script("compare-twodd", ours, res, "--rtol", "1e-12", "--atol", "1e-14",
                  cwd=tmp_path)
    assert done.returncode == 0, done.stdout
    done = script("compare-twodd", ours, REFERENCE / "output_double_precision" /
                  "A1_press_n20.RESf60.txt", "--rtol", "1e-9", "--atol", "1e-12",
                  cwd=tmp_path)
    assert done.returncode == 0, done.stdout


def test_cli_twodd_symmetric_deck_and_flags(tmp_path):
    res = tmp_path / "sym.res.txt"
    run_deck(DATA / "sym_ksym4.f60.txt", tmp_path, "sym", res=res)
    text = res.read_text()
    assert "ARE LINES OF SYMMETRY" in text
    assert text.count("\n") > 40
    # A point near an element is computed and marked, with the footnote.
    near = tmp_path / "near.f60.txt"
    near.write_text("near\n1,1,1\n0.25,1.0,0.,0.\n0.,0.,0.\n"
                    "10,-1.0,0.0,1.0,0.0,1,0.0,-1.0\n-0.05,0.05,-0.05,0.05,0\n")
    res = tmp_path / "near.res.txt"
    run_deck(near, tmp_path, "near", res=res)
    rows = [line for line in res.read_text().splitlines() if line.endswith("  *")]
    assert len(rows) == 1 and "TWODD SKIPS SUCH POINTS" in res.read_text()


@pytest.mark.parametrize("deck, fragment", [
    ("bad_kode7.f60.txt", "line 5"),
    ("bad_negative_count.f60.txt", "line 5"),
    ("bad_non_numeric.f60.txt", "line 4"),
    ("bad_too_few_lines.f60.txt", "line 7"),
])
def test_cli_bad_decks_exit_2(deck, fragment, tmp_path):
    out = tmp_path / "bad.h5"
    done = run([ddc2d_exe(), "--twodd", DATA / deck, "-o", out, "--res", tmp_path / "r.txt"],
               tmp_path)
    assert done.returncode == 2, done.stderr
    assert deck in done.stderr and fragment in done.stderr
    assert not out.exists() and not (tmp_path / "r.txt").exists()


def test_cli_usage_errors(tmp_path):
    done = run([ddc2d_exe(), "--twodd"], tmp_path)
    assert done.returncode == 2
    done = run([ddc2d_exe(), "--twodd", "a.txt", "b.nml"], tmp_path)
    assert done.returncode == 2
    done = run([ddc2d_exe(), "--help"], tmp_path)
    assert done.returncode == 0 and "--twodd DECK" in done.stdout and "--res" in done.stdout
