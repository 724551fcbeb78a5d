"""Strength laws on growing fractures (docs/fracture-growth.md#strength-laws-on-new-elements).

- A mode I crack (2 m, contact elements, mu 0.6) under syy rising in steps of 0.025: it first
  grows at the first load step where the closed form K_I = syy sqrt(pi a) reaches the
  toughness, with or without a tensile strength on its new elements; in that load step the
  crack without it grows through the step limit, the one whose new elements must first break
  (new_tensile_strength 5, new_sf 10) grows less than a third as far.
- A fault with residual cohesion, slip weakening and tensile strength grows tails under a
  rising pore pressure: its new elements take the tip element's laws as given (the defaults),
  those given in &growth where given, and their strength state is in the file (strengths in
  force between the residual and the intact values, some weakened).
- The same fault resumed after a step limit inside its first load step equals the
  uninterrupted run to 1e-12 (its new elements' slip path and strengths in force go on).
- A crack of traction-given elements (no contact element) grows along a load path; its first
  growth step equals that of a fixed-load run at that load.
- New elastic joints grow; a resumed growth along a load path with them is refused.
- A sweep varies the laws of new elements by their &growth names; a task whose new residual
  exceeds the intact value is refused before anything runs (exit 2, one line).
"""
import math
import subprocess

import h5py
import numpy as np

import compare_results
from conftest import ddc2d_exe

CRACK = """\
&model youngs_modulus = 10000.0, poissons_ratio = 0.25 /
&fracture name = 'crack', x = -1.0, 1.0, y = 0.0, 0.0, elements = 20,
          condition = 'contact', mu = 0.6, sf = 0.0 /
&solver lcp_method = 'newton' /
&load_path syy = 0.0, 1.0, steps = 40 /
&growth steps = 3, toughness = {toughness}{extra} /
"""
# The closed-form onset syy = K_Ic / sqrt(pi a) = 0.5125 lies between two load steps.
TOUGHNESS = 0.5125 * math.sqrt(math.pi)

FAULT = """\
&model title = 'Fault grown with strength laws', youngs_modulus = 50000.0,
       poissons_ratio = 0.25, length_unit = 'm', stress_unit = 'MPa' /
&remote_stress sxx = -143.75, syy = -81.25, sxy = 54.13 /
&pore_fluid p0 = 0.0 /
&fracture name = 'fault', x = -1.0, 1.0, y = 0.0, 0.0, elements = 20,
          condition = 'contact', mu = 0.6, sf = 1.0, sf_residual = 0.2, mu_dynamic = 0.45,
          slip_weakening_distance = 1e-4, tensile_strength = 1.0 /
&load_path p0 = 0.0, {p0}, steps = {steps} /
&growth steps = {growth}, toughness = 4.0, new_sf = 2.0, new_tensile_strength = 3.0{extra} /
"""

FREE = """\
&model youngs_modulus = 10000.0, poissons_ratio = 0.25 /
&remote_stress syy = {syy} /
&fracture name = 'crack', x = -1.0, 1.0, y = 0.0, 0.0, elements = 20, condition = 'traction' /
&growth steps = 2, toughness = 0.886227 /
"""


def run(folder, name, text, *extra):
    """Solve a model; its result file."""
    (folder / f"{name}.nml").write_text(text)
    done = subprocess.run([str(ddc2d_exe()), f"{name}.nml", "-o", f"{name}.h5", *extra],
                          cwd=folder, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    return folder / f"{name}.h5"


def growth_by_load_step(path):
    """Load of each load step, and the length grown at each end in each load step."""
    with h5py.File(path, "r") as f:
        g = f["growth"]
        load = f["history/syy"][:]
        grown = np.zeros(load.size)
        for step, length, end in zip(g["load_step"][:], g["length"][:], g["end"][:]):
            if end == 1:
                grown[step - 1] += length
    return load, grown


def test_tensile_strength_on_new_elements_slows_growth(tmp_path):
    plain = run(tmp_path, "plain", CRACK.format(toughness=TOUGHNESS, extra=""))
    strong = run(tmp_path, "strong", CRACK.format(
        toughness=TOUGHNESS, extra=", new_sf = 10.0, new_tensile_strength = 5.0"))
    load, grown_plain = growth_by_load_step(plain)
    _, grown_strong = growth_by_load_step(strong)
    onset = np.argmax(load * math.sqrt(math.pi) >= TOUGHNESS)
    assert np.flatnonzero(grown_plain)[0] == onset
    assert np.flatnonzero(grown_strong)[0] == onset
    # Without strength the crack runs through the step limit (3 increments of 0.2).
    assert math.isclose(grown_plain[onset], 0.6, rel_tol=1e-12)
    assert 0.0 < grown_strong[onset] < grown_plain[onset] / 3
    with h5py.File(strong, "r") as f:
        e = f["elements"]
        new = e["created_step"][:] > 0
        assert np.all(e["tensile_strength"][:][new] == 5.0)
        assert np.all(e["tensile_strength"][:][~new] == 0.0)


def test_new_elements_take_the_tip_law_as_given_and_carry_its_state(tmp_path):
    # Three growth steps: the tails' new elements slip and weaken from the third on.
    path = run(tmp_path, "fault", FAULT.format(p0=30.0, steps=2, growth=3, extra=""))
    with h5py.File(path, "r") as f:
        e = {k: v[:] for k, v in f["elements"].items()}
    new = e["created_step"] > 0
    assert new.sum() >= 4
    # The tip element's laws as given (not as weakened), and those &growth gives.
    for name, value in [("sf_residual", 0.2), ("mu_dynamic", 0.45),
                        ("slip_weakening_distance", 1e-4), ("mu", 0.6), ("sf", 2.0),
                        ("tensile_strength", 3.0)]:
        assert np.all(e[name][new] == value), name
    # Their strengths in force: weakened where they slipped, never beyond the laws' bounds.
    mu_in, sf_in = e["mu_in_force"][new], e["sf_in_force"][new]
    assert np.all((mu_in >= 0.45 - 1e-12) & (mu_in <= 0.6 + 1e-12))
    assert np.all((sf_in >= 0.2 - 1e-12) & (sf_in <= 2.0 + 1e-12))
    assert np.any(mu_in < 0.6 - 1e-3) and np.any(sf_in < 2.0 - 1e-3)
    extra = ", new_mu_dynamic = 0.5, new_slip_weakening_distance = 2e-4"
    override = run(tmp_path, "override", FAULT.format(p0=30.0, steps=2, growth=3, extra=extra))
    with h5py.File(override, "r") as f:
        e = {k: v[:] for k, v in f["elements"].items()}
    new = e["created_step"] > 0
    assert np.all(e["mu_dynamic"][new] == 0.5)
    assert np.all(e["slip_weakening_distance"][new] == 2e-4)
    assert np.all(e["mu_dynamic"][~new] == 0.45)


def test_resume_with_strength_laws_on_grown_elements(tmp_path):
    # The earlier run stops at its step limit inside the first load step.
    whole_text = FAULT.format(p0=30.0, steps=2, growth=3, extra="")
    run(tmp_path, "old", FAULT.format(p0=30.0, steps=2, growth=1, extra=""))
    whole = run(tmp_path, "whole", whole_text)
    run(tmp_path, "new", whole_text, "--resume", "old.h5")
    problems, _ = compare_results.compare(whole, tmp_path / "new.h5", rtol=1e-12)
    assert not problems, problems
    with h5py.File(tmp_path / "old.h5") as old, h5py.File(whole) as w:
        assert old["elements/x_mid"].size < w["elements/x_mid"].size


def test_growth_along_a_load_path_without_contact_elements(tmp_path):
    path = run(tmp_path, "path", FREE.format(syy=0.0)
               + "&load_path syy = 0.0, 0.6, steps = 6 /\n")
    fixed = run(tmp_path, "fixed", FREE.format(syy=0.6))
    with h5py.File(path, "r") as a, h5py.File(fixed, "r") as b:
        ga, gb = a["growth"], b["growth"]
        first_a = (ga["step"][:] == 1) & (ga["length"][:] > 0)
        first_b = (gb["step"][:] == 1) & (gb["length"][:] > 0)
        assert first_a.sum() == first_b.sum() == 2
        assert np.all(ga["load_step"][:][first_a] == 7)
        for name in ("k1", "k2", "length", "x", "y", "angle"):
            assert np.allclose(ga[name][:][first_a], gb[name][:][first_b], rtol=1e-10,
                               atol=1e-12), name


def test_a_sweep_varies_the_laws_of_new_elements(tmp_path):
    sweep = (CRACK.format(toughness=TOUGHNESS, extra=", new_sf = 10.0")
             + "&grid name = 'map', xmin = -2, xmax = 2, nx = 5, ymin = -1, ymax = 1, ny = 3 /\n"
             + "&sweep parameters = 'new_tensile_strength', values_1 = 0.0, 5.0 /\n")
    for task, strength in enumerate((0.0, 5.0)):
        run(tmp_path, "sweep", sweep, "--task", str(task))
        with h5py.File(tmp_path / f"sweep_task000{task}.h5", "r") as f:
            e = f["elements"]
            new = e["created_step"][()] > 0
            assert new.any() and np.all(e["tensile_strength"][()][new] == strength)
            assert f["sweep"].attrs["new_tensile_strength"] == strength
    # A residual above the intact value is refused for every task, before any runs.
    (tmp_path / "bad.nml").write_text(sweep.replace(
        "'new_tensile_strength', values_1 = 0.0, 5.0", "'new_sf_residual', values_1 = 11.0"))
    done = subprocess.run([str(ddc2d_exe()), "bad.nml", "--list"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert done.stderr.count("\n") == 1
    assert ("task 0 (new_sf_residual = 11): new_sf_residual = 11 exceeds new_sf = 10"
            in done.stderr)


def test_elastic_joints_grow_and_their_resume_is_refused(tmp_path):
    """New elastic joints (solved whole, not on the kept Newton path) grow open, unloaded; a
    resumed growth along the load path is refused: their memory is the plastic slip, which
    the file does not hold."""
    joints = ", new_shear_stiffness = 1000.0, new_normal_stiffness = 2000.0"
    text = CRACK.format(toughness=TOUGHNESS, extra=joints)
    path = run(tmp_path, "joints", text)
    with h5py.File(path, "r") as f:
        e = f["elements"]
        new = e["created_step"][()] > 0
        assert new.any() and np.all(e["normal_stiffness"][()][new] == 2000.0)
        # Open faces carry no traction: the joints of the grown, open crack are unloaded.
        assert np.all(e["state"][()][new] == 3)
        assert np.all(np.abs(e["dn_elastic"][()][new]) < 1e-15)
    (tmp_path / "more.nml").write_text(text.replace("steps = 3", "steps = 5"))
    done = subprocess.run([str(ddc2d_exe()), "more.nml", "--resume", "joints.h5", "-o",
                           "more.h5"], cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert done.stderr.strip().endswith("growth along a load path with elastic joints "
                                        "(shear_stiffness, normal_stiffness) cannot be resumed")
    assert not (tmp_path / "more.h5").exists()
