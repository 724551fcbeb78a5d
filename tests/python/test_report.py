"""What ddc2d tells the user on the terminal (app/report.f90): the echo of the model with
its domain, stress gradients, pore fluid, symmetry and loading history, notes on
implausible input, the points of each observation set that lie on an element, a warning
when a whole set does, and the units of K."""

import subprocess

import pytest

from conftest import REPO_ROOT, ddc2d_exe

# A half-plane normal fault under gravity with hydrostatic pore fluid.
GRAVITY = """\
&model title = 'normal fault', youngs_modulus = 30000, poissons_ratio = 0.25,
       domain = 'half_plane' /
&remote_stress dsyy_dy = 0.0265, dsxx_dy = 0.01325 /
&pore_fluid dp_dy = -0.00981 /
&fracture name = 'fault', x = 0, -1154.7, y = 0, -2000, elements = 40, mu = 0.6 /
&grid name = 'section', xmin = -3000, xmax = 2000, nx = 6, ymin = -3000, ymax = -10,
      ny = 4 /
"""
CRACK = """\
&model youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress sxx = -10, syy = -20 /
&fracture name = 'crack', x = -1, 1, y = 0, 0, elements = 10, condition = 'traction',
          bc_n = -5 /
"""


def run(args, cwd):
    return subprocess.run([str(ddc2d_exe()), *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, timeout=120)


def solve(tmp_path, text, name="m"):
    (tmp_path / f"{name}.nml").write_text(text)
    done = run([f"{name}.nml"], tmp_path)
    assert done.returncode == 0, done.stderr
    return done


def notes(done):
    return [line for line in done.stdout.splitlines() if line.startswith("note: ")]


def warnings(done):
    return [line for line in done.stderr.splitlines() if line.startswith("ddc2d: warning: ")]


def test_echo_of_a_gravity_model(tmp_path):
    lines = solve(tmp_path, GRAVITY).stdout.splitlines()
    assert "  youngs_modulus = 30000 MPa, poissons_ratio = 0.25" in lines
    assert "  domain: half_plane (free surface y = 0, the body y < 0)" in lines
    assert "  remote stress sxx, syy, sxy = 0 0 0 MPa at y = 0" in lines
    assert "  remote stress gradients dsxx_dy, dsyy_dy, dsxy_dy = 0.01325 0.0265 0 MPa/m" \
        in lines
    # The gradients as values at a reference depth: the deepest point of the model.
    assert ("    at y = -3000 m (the deepest point of the model): sxx, syy, sxy = "
            "-39.75 -79.5 0 MPa") in lines
    assert "  pore fluid p0 = 0 MPa, dp_dy = -0.00981 MPa/m, inside every contact element" \
        in lines
    assert "    at y = -3000 m: p = 29.43 MPa" in lines
    assert "  symmetry: none" in lines
    assert not notes(solve(tmp_path, GRAVITY))  # plausible: no notes


def test_echo_of_symmetry_and_loading_history(tmp_path):
    done = run([REPO_ROOT / "tests" / "data" / "history" / "good.nml", "-o", "h.h5"], tmp_path)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert "  loading history: 15 steps, legs of 4, 5, 5 increments" in lines
    assert "    sxy at the vertices: 0 4 4 4" in lines
    assert "    p0 at the vertices: 0 0 5 0" in lines
    done = run(["--twodd", REPO_ROOT / "tests" / "data" / "twodd" / "sym_ksym2.f60.txt", "-o",
                "s.h5"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert "  symmetry: x (xsym = 0, ysym = 0): image elements implicit" \
        in done.stdout.splitlines()


FLUID_NOTE = "note: the fluid pressure makes the effective normal stress tensile"


@pytest.mark.parametrize("change, words", [
    # syy = 0.0265 y would turn tensile with depth with the sign flipped (and with the
    # hydrostatic pore pressure the whole fault is then in effective tension: a second note).
    (("dsyy_dy = 0.0265", "dsyy_dy = -0.0265"),
     ["the remote syy = 0 + -0.0265 y turns tensile with depth: 79.5 MPa at y = -3000 m",
      "needs dsyy_dy > 0"]),
    (("dsxx_dy = 0.01325", "dsxx_dy = -0.01325"),
     ["the remote sxx = 0 + -0.01325 y turns tensile with depth"]),
    (("dp_dy = -0.00981", "dp_dy = 0.00981"),
     ["the pore pressure p0 + dp_dy y = 0 + 0.00981 y is negative: -29.43 MPa at y = -3000 m"]),
    # E in Pa, stresses in MPa: a strain of about 1e-9.
    (("youngs_modulus = 30000", "youngs_modulus = 3e10"),
     ["the largest stress given, 79.5 MPa, is 2.65E-09 times youngs_modulus = 3E+10",
      "check stress_unit"]),
    # Stresses in Pa, E in MPa: a strain of about 3000.
    (("dsyy_dy = 0.0265, dsxx_dy = 0.01325", "dsyy_dy = 26500, dsxx_dy = 13250"),
     ["the largest stress given, 79500000 MPa, is 2650 times", "check stress_unit"]),
])
def test_notes_on_implausible_input(tmp_path, change, words):
    done = solve(tmp_path, GRAVITY.replace(*change))
    found = notes(done)
    if change[1] == "dsyy_dy = -0.0265":
        assert len(found) == 2 and found[1].startswith(FLUID_NOTE), done.stdout
    else:
        assert len(found) == 1, done.stdout
    for word in words:
        assert word in found[0]


TENSILE = """\
&model youngs_modulus = 30000, poissons_ratio = 0.25 /
&remote_stress sxx = 1, syy = -10 /
&fracture name = 'joint', x = -1, 0, 1, y = 0, 0, 0, elements = 5, 5, mu = 0.5,
          sf = 0.5, 3, tensile_strength = 2 /
&fracture name = 'strong', x = -1, 1, y = 2, 2, elements = 10, mu = 0.5, sf = 3,
          tensile_strength = 2 /
"""


def test_a_capped_tensile_strength_is_echoed_in_force_with_a_note(tmp_path):
    # T is capped at the Coulomb apex sf/mu: 0.5/0.5 = 1 on the first segment of 'joint',
    # 6 on its second (and on 'strong', where T = 2 holds as given).
    done = solve(tmp_path, TENSILE)
    lines = done.stdout.splitlines()
    joint = lines.index("  fracture 1 joint: 10 elements, condition contact")
    assert lines[joint + 1] == ("    tensile_strength 1 .. 2 MPa in force (given 2 .. 2 MPa, "
                                "capped at sf/mu; lost once the element opens)")
    strong = lines.index("  fracture 2 strong: 10 elements, condition contact")
    assert lines[strong + 1] == ("    tensile_strength 2 .. 2 MPa (capped at sf/mu; lost once "
                                 "the element opens)")
    assert notes(done) == [
        ("note: fracture 1 joint: tensile_strength 2 MPa is above the Coulomb apex sf/mu on 5 "
         "of 10 elements and is capped there to 1 .. 1 MPa (where the shear strength "
         "sf - mu T vanishes); a tensile strength T needs sf >= mu T"),
        *[instant_tensile_note(k, name) for k, name in ((1, "joint"), (2, "strong"))]]
    # With the default sf = 0 the cap takes the whole tensile strength.
    done = solve(tmp_path, TENSILE.replace("sf = 0.5, 3,", ""))
    lines = done.stdout.splitlines()
    assert lines[joint + 1].startswith("    tensile_strength 0 .. 0 MPa in force (given 2 .. 2")
    assert "on 10 of 10 elements and is capped there to 0 .. 0 MPa" in notes(done)[0]


def test_a_capped_tensile_strength_of_new_elements_has_a_note(tmp_path):
    # &growth new_tensile_strength = 2 with new_sf = 0: the apex of every new element is 0,
    # which takes the whole tensile strength; with the tip elements' sf = 3, mu = 0.5 (apex 6)
    # it holds as given.
    growth = ("&fracture name = 'joint', x = -1, 1, y = 0, 0, elements = 10, mu = 0.5, sf = 3 /\n"
              "&growth steps = 1, toughness = 100, new_tensile_strength = 2{new_sf} /\n")
    text = TENSILE.split("&fracture")[0] + growth
    done = solve(tmp_path, text.format(new_sf=", new_sf = 0"))
    assert notes(done) == [
        ("note: &growth: new_tensile_strength 2 MPa is above the Coulomb apex sf/mu of the new "
         "contact elements of joint (new_sf, new_mu, or the values of their tip element) and is "
         "capped there to 0 .. 0 MPa (where the shear strength sf - mu T vanishes); a tensile "
         "strength T needs sf >= mu T (give new_sf)")]
    assert notes(solve(tmp_path, text.format(new_sf=""))) == []


def instant_tensile_note(k, name):
    return (f"note: fracture {k} {name}: the tensile strength drops at once on opening "
            "(opening_weakening_distance = 0) on 10 of 10 elements: the stress at a slip or "
            "opening front is singular, so the loads at which such strength fails depend on "
            "the element length; give opening_weakening_distance (a cohesive zone of at least "
            "3 elements) for failure loads that converge with the mesh")


# Strong patches (cohesion 6 -> 1, friction 0.6 -> 0.5) around a weak centre, d_c = 2e-5 m:
# the cohesive zone (9 pi / 32) G d_c / ((1 - nu)(tau_p - tau_r)) = 0.0785 m with G = 20000,
# nu = 0.25 and tau_p - tau_r = 5 + 0.1 * 10 = 6 MPa.
PATCHES = """\
&model youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress sxx = -10, syy = -10, sxy = 5 /
&fracture name = 'fault', x = -1, -0.4, 0.4, 1, y = 0, 0, 0, 0, elements = {n}, mu = 0.6,
          mu_dynamic = 0.5, sf = 6, 0, 6, sf_residual = 1, 0, 1,
          slip_weakening_distance = {d_c} /
"""


def echo_warnings(done):
    return [line for line in done.stdout.splitlines() if line.startswith("warning: ")]


def test_cohesive_zone_warning_and_instant_drop_note(tmp_path):
    # 50 elements of 0.04 m: the zone spans 1.96 element lengths, fewer than 3.
    done = solve(tmp_path, PATCHES.format(n="15, 20, 15", d_c="2e-5"))
    assert echo_warnings(done) == [
        ("warning: fracture 1 fault: the cohesive zone of slip_weakening_distance, about "
         "(9 pi / 32) G d / ((1 - nu)(tau_p - tau_r)) with tau_p - tau_r the drop of cohesion "
         "and friction at the remote normal stress, spans only 1.96 element lengths (fewer "
         "than 3 on 30 of 50 elements; zone 0.0785 m): its failure loads still depend on the "
         "element length; give a larger slip_weakening_distance or shorter elements")]
    assert not notes(done)
    # 100 elements of 0.02 m: 3.9 element lengths, resolved.
    done = solve(tmp_path, PATCHES.format(n="30, 40, 30", d_c="2e-5"))
    assert not echo_warnings(done) and not notes(done)
    # d_c = 0: the drop is at once, a note names slip_weakening_distance.
    done = solve(tmp_path, PATCHES.format(n="30, 40, 30", d_c="0"))
    assert not echo_warnings(done)
    assert notes(done) == [
        ("note: fracture 1 fault: cohesion or friction drops at once on slip "
         "(slip_weakening_distance = 0) on 100 of 100 elements: the stress at a slip or "
         "opening front is singular, so the loads at which such strength fails depend on the "
         "element length; give slip_weakening_distance (a cohesive zone of at least 3 "
         "elements) for failure loads that converge with the mesh")]


def test_note_on_a_weakening_distance_without_a_friction_drop(tmp_path):
    text = CRACK.replace("condition = 'traction',\n          bc_n = -5",
                         "mu = 0.6, slip_weakening_distance = 1e-3")
    found = notes(solve(tmp_path, text))
    assert found == [("note: fracture 1 crack: slip_weakening_distance is given, but neither "
                      "friction nor cohesion weakens on any of the 10 elements that have it "
                      "(mu_dynamic is not below mu, sf_residual not below sf): it does nothing "
                      "(give mu_dynamic < mu or sf_residual < sf)")]
    assert not notes(solve(tmp_path, text.replace("mu = 0.6,", "mu = 0.6, mu_dynamic = 0.4,")))


def test_no_weakening_note_where_only_the_cohesion_weakens(tmp_path):
    # The strong patches lose cohesion (6 -> 1) and keep their friction; the weak centre has
    # no cohesion to lose. The weakening distance acts on the patches: no note names it.
    text = PATCHES.format(n="15, 20, 15", d_c="2e-5").replace("mu_dynamic = 0.5, ", "")
    assert "mu_dynamic" not in text
    assert not [n for n in notes(solve(tmp_path, text)) if "slip_weakening_distance" in n]


@pytest.mark.parametrize("p0, tensile", [(25, True), (15, False)])
def test_note_when_the_fluid_makes_every_contact_tensile(tmp_path, p0, tensile):
    # The fault across syy = -20 (its normal stress) with p0 = 25: effective +5 on every
    # element, all open; with p0 = 15 it stays compressive. Remote tension alone (a crack
    # pulled open) gets no note: it is a model of its own.
    text = CRACK.replace("condition = 'traction',\n          bc_n = -5", "mu = 0.6") + \
        f"&pore_fluid p0 = {p0} /\n"
    found = notes(solve(tmp_path, text))
    if tensile:
        assert found == [FLUID_NOTE + (" on every contact element (5 .. 5 MPa, remote normal "
                                       "stress plus fluid pressure, above the tensile "
                                       "strength): every one opens whole")]
    else:
        assert found == []
    pulled = CRACK.replace("condition = 'traction',\n          bc_n = -5", "mu = 0.6")
    assert not notes(solve(tmp_path, pulled.replace("syy = -20", "syy = 20")))


WEAKENING = """\
&model youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress sxx = -10, syy = -20, sxy = 13 /
&fracture name = 'fault', x = -1, 1, y = 0, 0, elements = 10, mu = 0.6, mu_dynamic = 0.3 /
"""


def test_summary_counts_the_solves_of_changing_strengths(tmp_path):
    # Friction that drops at once where an element slips: the solve is repeated until no
    # strength in force changes, and the summary says how many solves it took.
    lines = solve(tmp_path, WEAKENING).stdout.splitlines()
    solved = [line for line in lines if line.startswith("solved with ")]
    assert len(solved) == 1 and " solves (strengths in force) on " in solved[0], solved
    assert int(solved[0].split(" in ")[1].split()[0]) > 1
    plain = solve(tmp_path, WEAKENING.replace(", mu_dynamic = 0.3", ""), "plain")
    assert [line for line in plain.stdout.splitlines() if " solves " in line] == []


def test_no_strain_note_for_twodd_decks(tmp_path):
    # TWODD decks carry no units (E = 1 and unit stresses are common): no strain note.
    done = run(["--twodd", REPO_ROOT / "tests" / "reference" / "twodd" / "inputs" /
                "A1_press_n20.f60.txt", "-o", "a.h5"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert not notes(done)


def test_points_on_elements_are_counted_and_a_set_all_on_elements_warned(tmp_path):
    text = CRACK + (
        "&line name = 'along', x_begin = -0.5, y_begin = 0, x_end = 0.5, y_end = 0, "
        "points = 5 /\n"
        "&line name = 'across', x_begin = 0, y_begin = -1, x_end = 0, y_end = 1, "
        "points = 5 /\n")
    done = solve(tmp_path, text)
    lines = done.stdout.splitlines()
    assert ("  line along: 5 points, 5 on an element (NaN), 0 within one element length of "
            "an element centre (reduced accuracy)") in lines
    assert ("  line across: 5 points, 1 on an element (NaN), 0 within one element length of "
            "an element centre (reduced accuracy)") in lines
    assert warnings(done) == [("ddc2d: warning: every point of line 'along' lies on an "
                               "element: all its values are NaN (move it off the fractures)")]


def test_k_has_units(tmp_path):
    done = solve(tmp_path, CRACK.replace("poissons_ratio = 0.25",
                                         "poissons_ratio = 0.25, length_unit = 'km'"))
    tips = [line for line in done.stdout.splitlines() if line.startswith("  tip ")]
    assert len(tips) == 2
    assert all(line.endswith(" MPa km^1/2") and "K_I = " in line for line in tips)


def test_opening_weakening_distance_is_read_echoed_and_checked(tmp_path):
    text = TENSILE.replace("tensile_strength = 2 /", "tensile_strength = 2,\n"
                           "          opening_weakening_distance = 1e-4 /")
    lines = solve(tmp_path, text).stdout.splitlines()
    strong = lines.index("  fracture 2 strong: 10 elements, condition contact")
    assert lines[strong + 1] == ("    tensile_strength 2 .. 2 MPa (capped at sf/mu; falls to 0 "
                                 "as the opening grows to opening_weakening_distance "
                                 "0.0001 .. 0.0001 m)")
    (tmp_path / "bad.nml").write_text(text.replace("= 1e-4", "= -1e-4"))
    done = run(["bad.nml"], tmp_path)
    assert done.returncode == 2
    assert ("(line 6): opening_weakening_distance(1) = -0.100000E-3 must be >= 0"
            in done.stderr), done.stderr
