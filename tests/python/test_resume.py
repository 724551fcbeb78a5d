"""--resume OLD.h5 (docs/theory/earth.md#what-a-step-hands-on): the result files a run refuses
to continue, those it accepts, and the continuation.

Every refusal exits 2 with one message naming the resume file, writes no output (nor a .partial
file) and leaves the resume file as it was; another model is named by the group and variable
that changed. A resumed result records the file it continued (resumed_from). A resumed run
equals the uninterrupted one to 1e-12 (tests/compare_results.py: every array of /elements,
/tips, /fields, /history and /growth): growth along a load path resumed after a shorter path
(the earlier run arrested) and after a step limit inside a load step, on the Lemke and on the
kept Newton path; growth at a fixed load after a step limit; a loading history with residual
cohesion and slip weakening (its memory: slip, strengths in force and slip path); a history
whose K comes from the local re-solve coupled to the rest of the model (the memory of the
model with higher-order zones).
"""

import subprocess

import h5py
import numpy as np
import pytest

import compare_results
import ddc2d
from conftest import ddc2d_exe

MODEL = """\
&model youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress syy = -10, sxy = 4 /
&pore_fluid p0 = 1 /
"""
HISTORY = MODEL + """\
&fracture x = -1, 1, y = 0, 0, elements = 6, mu = 0.6 /
&load_path sxy = {sxy}, {p0}steps = {steps} /
"""
GROWTH = """\
&model youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress syy = 10 /
&fracture name = 'crack', x = -1, 1, y = 0, 0, elements = 8, condition = 'traction' /
&growth steps = {steps}, toughness = 15.5, increment = 0.2 /
"""
# A sliding flaw whose wings grow as the axial load rises
GROWTH_PATH = """\
&model youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress syy = -10 /
&fracture name = 'flaw', x = -0.5, 0.5, y = -0.3, 0.3, elements = 6, mu = 0.3 /
&growth steps = 3, toughness = 5, increment = 0.1 /
"""
PATH = "&load_path sxx = -1, -1, syy = -1, -30, steps = 3 /\n"
PLAIN = MODEL + "&fracture x = -1, 1, y = 0, 0, elements = 6, mu = {mu} /\n"


def history(sxy="0, 4, 4", steps="2, 3", p0="", extra=""):
    return HISTORY.format(sxy=sxy, steps=steps, p0=p0) + extra


def run(args, cwd):
    return subprocess.run([str(ddc2d_exe()), *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, timeout=120)


def earlier_run(folder, text, name="old"):
    """Run a model; its complete result folder/name.h5."""
    (folder / f"{name}.nml").write_text(text)
    done = run([f"{name}.nml", "-o", f"{name}.h5"], folder)
    assert done.returncode == 0, done.stderr
    return folder / f"{name}.h5"


@pytest.fixture(scope="module")
def whole_run(tmp_path_factory):
    """whole_run(text): the result of an uninterrupted run of a model, made once for this
    file: several cases compare with the same run (the wings' 40 growth steps along their path
    cost seconds in the Debug build). Read only: each case resumes into a folder of its own."""
    results = {}

    def result(text):
        if text not in results:
            results[text] = earlier_run(tmp_path_factory.mktemp("whole"), text, "whole")
        return results[text]
    return result


def resume(folder, text, old):
    (folder / "new.nml").write_text(text)
    return run(["new.nml", "--resume", old, "-o", "new.h5"], folder)


def assert_refused(done, folder, words, old=None, before=None):
    assert done.returncode == 2, done.stdout + done.stderr
    errors = [line for line in done.stderr.splitlines() if "error:" in line]
    assert len(errors) == 1, done.stderr
    assert words in errors[0], errors[0]
    assert not (folder / "new.h5").exists()
    assert not list(folder.glob("*.partial"))
    if old is not None:
        assert old.read_bytes() == before


def set_attribute(path, name, value):
    with h5py.File(path, "r+") as f:
        f.attrs[name] = value


@pytest.mark.parametrize("case, words", [
    ("missing", "--resume absent.h5: does not exist"),
    ("folder", "--resume folder.h5: is a folder, not a result file"),
    ("text", "--resume text.h5: is not an HDF5 file"),
])
def test_what_is_not_a_result_file_is_refused(tmp_path, case, words):
    if case == "folder":
        (tmp_path / "folder.h5").mkdir()
    if case == "text":
        (tmp_path / "text.h5").write_text("not a result\n")
    old = {"missing": "absent.h5", "folder": "folder.h5", "text": "text.h5"}[case]
    assert_refused(resume(tmp_path, history(), old), tmp_path, words)


@pytest.mark.parametrize("change, words", [
    (("complete", np.int32(0)), "is incomplete: the run that wrote it did not finish"),
    (("version", np.bytes_("0.0.1")), "was written by ddc2d 0.0.1, this is"),
    (("model_fingerprint", np.bytes_("0123456789ABCDEF")), "is the result of another model"),
])
def test_incomplete_or_foreign_files_are_refused(tmp_path, change, words):
    old = earlier_run(tmp_path, history())
    set_attribute(old, *change)
    before = old.read_bytes()
    assert_refused(resume(tmp_path, history(), "old.h5"), tmp_path, "--resume old.h5: " + words,
                   old, before)


@pytest.mark.parametrize("new, words", [
    (history(extra="&solver lcp_method = 'lemke' /\n"),
     "is the result of another model: &solver lcp_method: not given before, 'lemke' now"),
    (history().replace("mu = 0.6", "mu = 0.5"),
     "is the result of another model: &fracture mu: 0.6 before, 0.5 now (only &growth steps"),
    # the title does not count: the changed value is named
    (history().replace("&model ", "&model title = 'other', ").replace("mu = 0.6", "mu = 0.5"),
     "is the result of another model: &fracture mu: 0.6 before, 0.5 now"),
    (history().replace("syy = -10", "syy = -10, sxx = -2"),
     "is the result of another model: &remote_stress sxx: not given before, -2 now"),
    (PLAIN.format(mu=0.6), ("--resume continues a growth run, a loading history or a cycle run, "
                            "and new.nml has none of &growth, &load_path, &cycle")),
    (GROWTH.format(steps=3), "is not a growth run (no /growth), and new.nml has &growth"),
    (history(steps="2, 2"), ("the &load_path of new.nml has 5 steps, fewer than the 6 of the "
                             "earlier run")),
    (history(sxy="0, 3, 4"), "step 2 of the &load_path of new.nml has sxy = 1.5"),
    # p0 held at its &pore_fluid value by the earlier path, varied by the new one
    (history(p0="p0 = 1, 1, 2, "), "step 4 of the &load_path of new.nml has p0 = 1.33"),
])
def test_another_model_or_path_is_refused(tmp_path, new, words):
    old = earlier_run(tmp_path, history())
    before = old.read_bytes()
    assert_refused(resume(tmp_path, new, "old.h5"), tmp_path, words, old, before)


def test_a_result_that_is_not_a_growth_run_or_history_is_refused(tmp_path):
    old = earlier_run(tmp_path, PLAIN.format(mu=0.6))
    before = old.read_bytes()
    assert_refused(resume(tmp_path, GROWTH.format(steps=3), "old.h5"), tmp_path,
                   "holds neither a growth run (/growth) nor a loading history (/history)",
                   old, before)


def test_growth_and_history_must_match(tmp_path):
    earlier_run(tmp_path, GROWTH.format(steps=3), "growth")
    assert_refused(resume(tmp_path, history(), "growth.h5"), tmp_path,
                   "--resume growth.h5: is a growth run, and new.nml has no &growth")
    earlier_run(tmp_path, GROWTH_PATH + PATH, "both")
    assert_refused(resume(tmp_path, GROWTH_PATH, "both.h5"), tmp_path,
                   "--resume both.h5: holds a loading history, and new.nml has no &load_path")
    earlier_run(tmp_path, GROWTH_PATH, "fixed")
    assert_refused(resume(tmp_path, GROWTH_PATH + PATH, "fixed.h5"), tmp_path,
                   "--resume fixed.h5: holds no loading history (/history), and new.nml has "
                   "a &load_path")


@pytest.mark.parametrize("args, words", [
    (["new.nml", "--resume"], "option --resume needs the result file"),
    (["new.nml", "--resume", "-o", "x.h5"], "option --resume needs the result file"),
    (["new.nml", "--resume", ""], "the --resume file name is empty"),
    (["--twodd", "deck.txt", "--resume", "old.h5"], "not a TWODD deck (--twodd) or a sweep"),
    (["new.nml", "--list", "--resume", "old.h5"], "not a TWODD deck (--twodd) or a sweep"),
    (["new.nml", "--resume", "old.h5", "--task", "0"], "not a TWODD deck (--twodd) or a sweep"),
])
def test_resume_usage_errors(tmp_path, args, words):
    (tmp_path / "new.nml").write_text(history())
    assert_refused(run(args, tmp_path), tmp_path, words)


def test_resume_of_a_sweep_is_refused(tmp_path):
    old = earlier_run(tmp_path, history())
    (tmp_path / "new.nml").write_text(history(extra="&sweep parameters = 'mu', "
                                              "values_1 = 0.5, 0.6 /\n"))
    done = run(["new.nml", "--resume", "old.h5", "-o", "new.h5"], tmp_path)
    assert_refused(done, tmp_path, "new.nml is a sweep (&sweep): --resume continues one", old,
                   old.read_bytes())


@pytest.mark.parametrize("old_text, new_text", [
    (history(), history(sxy="0, 4, 4, 2", steps="2, 3, 2")),
    (history(), history(sxy="0, 4, 4, 4", steps="2, 3, 1").replace("p0 = 1", "p0 = 1.0")),
    (GROWTH.format(steps=2), GROWTH.format(steps=5)),
    (GROWTH_PATH + PATH, GROWTH_PATH.replace("steps = 3", "steps = 5")
     + "&load_path sxx = -1, -1, -1, syy = -1, -30, -40, steps = 3, 1 /\n"),
])
def test_a_result_of_the_same_model_passes(tmp_path, old_text, new_text):
    old = earlier_run(tmp_path, old_text)
    done = resume(tmp_path, new_text, "old.h5")
    assert done.returncode == 0, done.stderr
    with h5py.File(old) as a, h5py.File(tmp_path / "new.h5") as b:
        assert a.attrs["model_fingerprint"] == b.attrs["model_fingerprint"]


def test_the_output_may_be_the_resume_file(tmp_path):
    old = earlier_run(tmp_path, GROWTH.format(steps=2))
    (tmp_path / "new.nml").write_text(GROWTH.format(steps=4))
    done = run(["new.nml", "--resume", "old.h5", "-o", "old.h5"], tmp_path)
    assert done.returncode == 0, done.stderr
    with h5py.File(old) as f:
        assert f.attrs["complete"] == 1
        assert b"steps = 4" in f.attrs["input_text"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["new.nml", "old.h5", "old.nml"]


def test_every_result_records_its_fingerprint(tmp_path):
    plain = earlier_run(tmp_path, PLAIN.format(mu=0.6), "a")
    again = earlier_run(tmp_path, "! the same model\n" + PLAIN.format(mu=0.6), "b")
    other = earlier_run(tmp_path, PLAIN.format(mu=0.5), "c")
    prints = []
    for path in (plain, again, other):
        with h5py.File(path) as f:
            prints.append(f.attrs["model_fingerprint"].decode().strip())
    assert all(len(p) == 16 and int(p, 16) >= 0 for p in prints)
    assert prints[0] == prints[1] != prints[2]


def test_elastic_joints_history_is_refused(tmp_path):
    """Refused, and the run that wrote the file said so in its echo."""
    joints = ", shear_stiffness = 1000, normal_stiffness = 1000 /"
    (tmp_path / "old.nml").write_text(history().replace("mu = 0.6 /", "mu = 0.6" + joints))
    done = run(["old.nml", "-o", "old.h5"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert ("--resume cannot continue this history: its elastic joints' memory is their "
            "plastic slip") in done.stdout
    old = tmp_path / "old.h5"
    new = history(sxy="0, 4, 4, 2", steps="2, 3, 2").replace("mu = 0.6 /", "mu = 0.6" + joints)
    assert_refused(resume(tmp_path, new, "old.h5"), tmp_path,
                   "elastic joints (shear_stiffness, normal_stiffness) cannot be resumed", old,
                   old.read_bytes())


# The wings of the flaw of docs/theory/growth.md#convergence-with-the-increment (20 elements) as syy
# rises from -5 to -100 MPa.
WINGS = """&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /
&remote_stress sxx = -5.0, syy = -5.0 /
&fracture name = 'flaw', x = -0.70710678, 0.70710678, y = -0.70710678, 0.70710678,
          elements = 20, mu = 0.6, sf = 0.0 /
&growth steps = {steps}, toughness = 2.0, increment = 0.2 /
{solver}"""
WINGS_PATH = "&load_path syy = -5, -52.5, -100, steps = 5, 5 /\n"
WINGS_HALF = "&load_path syy = -5, -52.5, steps = 5 /\n"
WEAKENING = (PLAIN.format(mu="0.6, sf = 1, sf_residual = 0.2, mu_dynamic = 0.45, "
                          "slip_weakening_distance = 1e-5")
             + "&load_path sxy = {path} /\n")
# A fault longer than the K re-solve's two zones (32 elements each): K couples them to the
# rest of the model, whose own friction memory the file keeps (/elements/ds_k_memory)
COUPLED_K = ("&model youngs_modulus = 30000, poissons_ratio = 0.25 /\n"
             "&remote_stress sxx = -50, syy = -50 /\n"
             "&fracture x = -1, 1, y = 0, 0, elements = 100, mu = 0.6 /\n"
             "&solver lcp_method = 'newton' /\n"
             "&load_path sxy = {path} /\n")


@pytest.mark.parametrize("old_text, new_text", [
    # along a load path: the earlier run arrested at the end of a shorter path
    (WINGS.format(steps=40, solver="") + WINGS_HALF,
     WINGS.format(steps=40, solver="") + WINGS_PATH),
    # stopped by the step limit inside a load step
    (WINGS.format(steps=2, solver="") + WINGS_PATH, WINGS.format(steps=40, solver="") + WINGS_PATH),
    # the kept (Newton) path: the resumed run's first solve starts cold
    (WINGS.format(steps=2, solver="&solver lcp_method = 'newton' /") + WINGS_PATH,
     WINGS.format(steps=40, solver="&solver lcp_method = 'newton' /") + WINGS_PATH),
    # at a fixed load, after a step limit
    (WINGS.format(steps=2, solver="").replace("syy = -5.0", "syy = -100.0"),
     WINGS.format(steps=40, solver="").replace("syy = -5.0", "syy = -100.0")),
    # a loading history whose elements lose cohesion and weaken as they slip
    (WEAKENING.format(path="0, 6, steps = 4"), WEAKENING.format(path="0, 6, -6, steps = 4, 10")),
    # a fault that slips, then sticks after the resume, its K by the coupled re-solve (the
    # earlier run's memory of the model with higher-order zones restored; 2.3e-3 off before)
    (COUPLED_K.format(path="0, 40, steps = 8"), COUPLED_K.format(path="0, 40, -40, steps = 8, 16")),
])
def test_a_resumed_run_equals_the_uninterrupted_one(tmp_path, whole_run, old_text, new_text):
    earlier_run(tmp_path, old_text)
    whole = whole_run(new_text)
    done = resume(tmp_path, new_text, "old.h5")
    assert done.returncode == 0, done.stderr
    problems, report = compare_results.compare(whole, tmp_path / "new.h5", rtol=1e-12)
    assert not problems, problems
    assert "largest relative difference" in report
    with h5py.File(tmp_path / "old.h5") as old, h5py.File(tmp_path / "new.h5") as new, \
            h5py.File(whole) as uninterrupted:
        # The resumed result names the file it continued and when that was written, and so
        # does the run's log.
        assert new.attrs["resumed_from"] == b"old.h5"
        assert new.attrs["resumed_from_created"] == old.attrs["created"]
        assert f"  resumed from old.h5 (written {old.attrs['created'].decode()})" in \
            done.stdout.splitlines()
        assert "resumed_from" not in uninterrupted.attrs
        # The earlier run did less: the resumed one went on.
        if "growth" in new:
            assert new["growth/step"].size > old["growth/step"].size
        else:
            assert new["history/pivots"].size > old["history/pivots"].size
    # The Python reader shows it with the rest of the provenance.
    assert ddc2d.open_result(tmp_path / "new.h5").provenance["resumed_from"] == "old.h5"


def test_a_run_that_stopped_at_a_failed_step_goes_on(tmp_path, whole_run):
    """A growth run whose step failed (exit status 6) ends as a step limit does: its file, the
    steps before the failure with /growth end_reason 'failed' and the failure, goes on where
    it stopped and gives the uninterrupted run. (Here the file of a run stopped by the step
    limit, marked failed as such a run marks it.)"""
    text = GROWTH.format(steps=4)
    earlier_run(tmp_path, GROWTH.format(steps=2))
    with h5py.File(tmp_path / "old.h5", "r+") as f:
        assert f["growth"].attrs["steps_taken"] == 2
        f["growth"].attrs["end_reason"] = np.bytes_("failed")
        f["growth"].attrs["failure"] = np.bytes_("growth step 3: contact: ...")
    done = resume(tmp_path, text, "old.h5")
    assert done.returncode == 0, done.stderr
    problems, _ = compare_results.compare(whole_run(text), tmp_path / "new.h5", rtol=1e-12)
    assert not problems, problems
    with h5py.File(tmp_path / "new.h5") as f:
        assert "failure" not in f["growth"].attrs


def test_a_run_that_arrests_at_once_when_resumed(tmp_path, whole_run):
    """The earlier run's step limit was its last growing step: the resumed run arrests in its
    first step without solving, and its result (the final solve's record included) is the
    uninterrupted run's."""
    fixed = WINGS.format(steps=40, solver="").replace("syy = -5.0", "syy = -100.0")
    whole = whole_run(fixed)
    with h5py.File(whole) as f:
        taken = int(f["growth"].attrs["steps_taken"])
        method = f["solver"].attrs["method"]
    earlier_run(tmp_path, fixed.replace("steps = 40", f"steps = {taken}"))
    done = resume(tmp_path, fixed, "old.h5")
    assert done.returncode == 0, done.stderr
    assert f"growth step {taken + 1}: 0 tip(s) grew" in done.stdout
    problems, _ = compare_results.compare(whole, tmp_path / "new.h5", rtol=1e-12)
    assert not problems, problems
    with h5py.File(tmp_path / "new.h5") as f:
        assert f["growth"].attrs["end_reason"] == b"arrested"
        assert f["solver"].attrs["method"] == method


def test_nothing_left_to_do_is_refused(tmp_path):
    old = earlier_run(tmp_path, history())
    assert_refused(resume(tmp_path, history(), "old.h5"), tmp_path,
                   "nothing is left to do; extend &load_path", old, old.read_bytes())
    fixed = WINGS.format(steps=40, solver="").replace("syy = -5.0", "syy = -100.0")
    old = earlier_run(tmp_path, fixed)
    with h5py.File(old) as f:
        assert f["growth"].attrs["end_reason"] == b"arrested"
    assert_refused(resume(tmp_path, fixed.replace("steps = 40", "steps = 50"), "old.h5"),
                   tmp_path,
                   "ended (arrested) where this model ends too", old, old.read_bytes())
