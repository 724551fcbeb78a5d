"""New fractures inside the rock (&initiation;
docs/fracture-growth.md#new-fractures-inside-the-rock).

A straight frictionless fault (2 m, mu = sf = 0, closed and sliding under sxx = 0,
syy = -20, sxy = 10 MPa: its slip is linear in the load) with &growth steps = 1, an
increment of 0.39 m (the tips' zones, where nothing starts) and a toughness no tip reaches,
so that the only thing that can happen is one initiation (probe_distance 0.2 m):

- the probed tension is the field at the probe point: the same model without &initiation,
  with a &grid through every probe point (both sides of every vertex outside the tips'
  zones, at probe_distance along the element normal), gives the tension /growth/initiations
  records to 1e-9, at the point with the largest tension (ties: the lowest element);
- the new tail runs perpendicular to the maximum tension at that point in the field
  without it, within 5 degrees;
- nothing starts with tensile_strength 0.1 % above the largest probed tension, one tail
  with 0.1 % below;
- at fixed probe_distance the initiation load (tensile_strength / probed tension per unit
  load) and point converge as the 20, 40, 80 element meshes halve the elements (observed
  order from ddc2d.richardson; the probe distance must span a few elements);
- a flaw point under tension starts a crack of flaw_length perpendicular to the tension;
- under criterion = 'work' a flaw searches the orientations of its first crack: under
  uniaxial tension the best is the open crack across the tension, with the efficiency of a
  Griffith crack; under all-round compression, with frictional new elements, the sliding
  crack that maximizes tau (tau - mu sigma_n), with its efficiency, where MTS starts
  nothing; it starts when its efficiency reaches the work threshold, not below;
- bad input: one message naming &initiation and the variable, exit 2.
"""

import math
import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import PLOT_SCRIPT, REPO_ROOT, ddc2d_exe
from ddc2d.plot import figures as plot_figures
from ddc2d.reader import load_result
from ddc2d.richardson import extrapolate

SXX, SYY, SXY = 0.0, -20.0, 10.0
PROBE = 0.2
HEADER = f"""\
&model youngs_modulus = 50000.0, poissons_ratio = 0.25, length_unit = 'm', stress_unit = 'MPa' /
&remote_stress sxx = {SXX}, syy = {SYY}, sxy = {SXY} /
"""
FAULT = ("&fracture name = 'fault', x = -1.0, 1.0, y = 0.0, 0.0, elements = {n}, "
         "condition = 'contact', mu = 0.0, sf = 0.0 /\n")
INCREMENT = 0.39
GROWTH = f"&growth steps = 1, toughness = 1.0e6, increment = {INCREMENT} /\n"


def run(folder, name, text, expect=0):
    """Run ddc2d on the model text; the result file (or the finished process when it must
    fail)."""
    model = folder / f"{name}.nml"
    model.write_text(text)
    out = folder / f"{name}.h5"
    done = subprocess.run([str(ddc2d_exe()), str(model), "-o", str(out)], capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == expect, done.stdout + done.stderr
    return out if expect == 0 else done


def probes(n):
    """Probe points of the n-element straight fault: both sides of every vertex outside the
    tips' zones (closer to a tip than the increment), at PROBE along the normal (0, 1); in
    the order element, end, side."""
    vertices = np.linspace(-1.0, 1.0, n + 1)
    points = []
    for k in range(n):
        for vertex in (vertices[k], vertices[k + 1]):
            if 1.0 - abs(vertex) < INCREMENT:
                continue
            for side in (-1, 1):
                points.append((k + 1, vertex, side * PROBE))
    return points


def max_tension(sxx, syy, sxy):
    """Maximum principal stress (tension positive) and its direction [degree]."""
    tension = 0.5 * (sxx + syy) + np.hypot(0.5 * (sxx - syy), sxy)
    return tension, np.degrees(0.5 * np.arctan2(2.0 * sxy, sxx - syy))


def probe_field(folder, n):
    """(element, x, y, tension, direction) at every probe point of the n-element fault, from
    a &grid on the model without &initiation: its nodes every element length along x and at
    y = -PROBE, 0, PROBE hold every probe point (those at y = 0 are on the fault)."""
    out = run(folder, f"field_{n}", HEADER + FAULT.format(n=n) +
              f"&grid name = 'probes', xmin = -1.0, xmax = 1.0, nx = {n + 1}, "
              f"ymin = {-PROBE}, ymax = {PROBE}, ny = 3 /\n")
    with h5py.File(out, "r") as f:
        field = f["fields/probes"]
        tension, direction = max_tension(field["sxx"][()], field["syy"][()], field["sxy"][()])
    values = []
    for k, x, y in probes(n):
        i = round((x + 1.0) * n / 2.0)
        j = round((y + PROBE) / PROBE)
        values.append((k, x, y, tension[j, i], direction[j, i]))
    return values


def initiations(out):
    """The /growth/initiations columns of a result file, as a dict of arrays."""
    with h5py.File(out, "r") as f:
        group = f["growth/initiations"]
        return {name: item[()] for name, item in group.items()
                if isinstance(item, h5py.Dataset)}


def flaw_trials(out):
    """The /growth/initiations/flaw_trials columns of a result file, as a dict of arrays."""
    with h5py.File(out, "r") as f:
        group = f["growth/initiations/flaw_trials"]
        return {name: group[name][()] for name in group}


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    return tmp_path_factory.mktemp("initiation")


@pytest.fixture(scope="module")
def field20(folder):
    return probe_field(folder, 20)


def tail_model(n, strength):
    """The n-element fault with &initiation at this tensile strength."""
    return (HEADER + FAULT.format(n=n) + GROWTH +
            f"&initiation tensile_strength = {float(strength)!r}, probe_distance = {PROBE} /\n")


def test_probed_tension_is_the_field_there(folder, field20):
    """The tail starts at the largest probed tension, which is the field at that point."""
    largest = max(p[3] for p in field20)
    rows = initiations(run(folder, "tail20", tail_model(20, 0.5 * largest)))
    assert rows["kind"].tolist() == [1], "one tail starts"
    # ties: the lowest element among the probes with the largest tension
    first = min((p for p in field20 if p[3] >= largest * (1.0 - 1e-9)), key=lambda p: p[0])
    assert rows["element"][0] == first[0], "the tie goes to the lowest element"
    assert (rows["probe_x"][0], rows["probe_y"][0]) == pytest.approx(first[1:3], abs=1e-12)
    assert rows["tension"][0] == pytest.approx(largest, rel=1e-9), "probed = field"


def test_tail_runs_perpendicular_to_the_tension(folder, field20):
    """The new crack's direction against the maximum tension before it existed."""
    largest = max(p[3] for p in field20)
    rows = initiations(run(folder, "tail20_angle", tail_model(20, 0.5 * largest)))
    point = next(p for p in field20 if p[0] == rows["element"][0] and
                 abs(p[2] - rows["probe_y"][0]) < 1e-12 and abs(p[1] - rows["probe_x"][0]) < 1e-12)
    difference = (rows["angle"][0] - point[4] - 90.0) % 180.0
    assert min(difference, 180.0 - difference) < 5.0, (rows["angle"][0], point[4])
    with h5py.File(folder / "tail20_angle.h5", "r") as f:
        names = [name.decode().strip() for name in f["fractures/name"][()]]
        first = f["fractures/first_element"][()][-1] - 1
        e = f["elements"]
        along = math.degrees(math.atan2(e["y_end"][first] - e["y_begin"][first],
                                        e["x_end"][first] - e["x_begin"][first]))
    assert names == ["fault", "fault_tail1"]
    difference = (along - rows["angle"][0]) % 360.0
    assert min(difference, 360.0 - difference) < 1e-9, "the tail's element has the angle"


def test_nothing_starts_above_the_largest_tension(folder, field20):
    """tensile_strength 0.1 % above the largest probed tension: nothing, and the file keeps
    that tension and its probe point (the first of equal ones, as the tie rule orders them);
    0.1 % below: one."""
    largest = max(p[3] for p in field20)
    assert largest > 0.0
    out = run(folder, "above", tail_model(20, 1.001 * largest))
    above = initiations(out)
    assert above["kind"].size == 0, "nothing starts above the largest probed tension"
    first = next(p for p in field20 if p[3] >= largest * (1.0 - 1e-9))
    kept = load_result(out)["growth"]["initiations"]["attrs"]
    assert kept["largest_tension"] == pytest.approx(largest, rel=1e-9)
    assert (kept["largest_tension_x"], kept["largest_tension_y"]) == \
        pytest.approx(first[1:3], abs=1e-12)
    assert kept["largest_tension_step"] == 1
    below = initiations(run(folder, "below", tail_model(20, 0.999 * largest)))
    assert below["kind"].size == 1


def test_initiation_converges_with_the_mesh(folder):
    """At fixed probe_distance, as the elements halve (20, 40, 80), the initiation point is
    the same vertex (the first outside the tips' zones, 0.4 m from the tips) and the
    initiation load (strength / tension per unit load: the model is linear) converges: the
    differences shrink, observed order > 0.5."""
    strength = 1.0
    loads, points = [], []
    for n in (20, 40, 80):
        rows = initiations(run(folder, f"mesh{n}", tail_model(n, strength)))
        loads.append(strength / rows["tension"][0])
        points.append((abs(rows["x"][0]), rows["y"][0]))
    assert points == [pytest.approx((0.6, 0.0), abs=1e-12)] * 3, points
    result = extrapolate(loads, 2.0)
    assert result.differences_shrink, loads
    assert result.order is not None and result.order > 0.5, (loads, result.order)
    assert abs(loads[-1] - result.extrapolated) < 0.01 * result.extrapolated


def test_flaw_starts_perpendicular_to_the_tension(folder):
    """A flaw 30 m from a crack under sxx = 10 MPa (maximum tension 13.0 MPa) starts a crack
    of flaw_length perpendicular to the tension, centred on the point."""
    # A traction-free crack: it has no contact elements to probe beside.
    crack = FAULT.format(n=10).replace("condition = 'contact', mu = 0.0, sf = 0.0",
                                       "condition = 'traction'")
    text = (HEADER.replace(f"sxx = {SXX}", "sxx = 10.0") + crack + GROWTH +
            "&initiation tensile_strength = 5.0, probe_distance = 0.05, flaw_x = 0.0, "
            "flaw_y = 30.0, flaw_length = 0.2 /\n")
    rows = initiations(run(folder, "flaw", text))
    flaw = np.flatnonzero(rows["kind"] == 2)
    assert flaw.size == 1
    k = flaw[0]
    # 30 m away the crack's own field is a few 1e-4 of the remote one
    tension, direction = max_tension(10.0, SYY, SXY)
    assert rows["tension"][k] == pytest.approx(tension, rel=1e-2)
    difference = (rows["angle"][k] - direction - 90.0) % 180.0
    assert min(difference, 180.0 - difference) < 5.0
    with h5py.File(folder / "flaw.h5", "r") as f:
        f_id = rows["fracture_id"][k] - 1
        first = f["fractures/first_element"][f_id] - 1
        last = f["fractures/last_element"][f_id] - 1
        e = f["elements"]
        ends = np.array([[e["x_begin"][first], e["y_begin"][first]],
                         [e["x_end"][last], e["y_end"][last]]])
    assert np.hypot(*(ends[1] - ends[0])) >= 0.2 - 1e-12
    assert ends.mean(axis=0) == pytest.approx([0.0, 30.0], abs=0.05)


def test_flaw_elements_are_intact_rock_but_for_the_new_element_laws(folder):
    """A flaw's elements take no strength law of the model's elements (the fault's tensile
    strength and slip weakening), only the new-element values &growth gives."""
    # One element: its ends are tips, so nothing is probed beside it and the flaw starts.
    fault = ("&fracture name = 'fault', x = -1.0, 1.0, y = 0.0, 0.0, elements = 1, "
             "mu = 0.6, sf = 2.0, tensile_strength = 1.0, mu_dynamic = 0.5, "
             "slip_weakening_distance = 1e-4 /\n")
    growth = GROWTH.replace(" /", ", new_mu = 0.3, new_mu_dynamic = 0.2 /")
    text = (HEADER.replace(f"sxx = {SXX}", "sxx = 10.0") + fault + growth +
            "&initiation tensile_strength = 5.0, probe_distance = 0.05, flaw_x = 0.0, "
            "flaw_y = 30.0, flaw_length = 0.2 /\n")
    out = run(folder, "flaw_laws", text)
    rows = initiations(out)
    assert list(rows["kind"]) == [2]
    with h5py.File(out, "r") as f:
        f_id = rows["fracture_id"][0] - 1
        flaw = slice(f["fractures/first_element"][f_id] - 1, f["fractures/last_element"][f_id])
        e = f["elements"]
        assert e["tensile_strength"][0] == 1.0 and e["slip_weakening_distance"][0] == 1e-4
        assert np.all(e["mu"][flaw] == 0.3) and np.all(e["mu_dynamic"][flaw] == 0.2)
        assert np.all(e["sf"][flaw] == 0.0) and np.all(e["tensile_strength"][flaw] == 0.0)
        assert np.all(e["slip_weakening_distance"][flaw] == 0.0)


@pytest.mark.parametrize("group, variable", [
    ("tensile_strength = 5.0", "probe_distance is required"),
    ("tensile_strength = 0.0, probe_distance = 0.05", "tensile_strength"),
    ("tensile_strength = -1.0, probe_distance = 0.05", "tensile_strength"),
    (("tensile_strength = 5.0, probe_distance = 0.05, flaw_x = 0.5, flaw_y = 0.0, "
      "flaw_length = 0.1"), "flaw_x(1)"),
])
def test_bad_input(folder, group, variable):
    """One message naming &initiation and the variable, exit 2."""
    done = run(folder, "bad", HEADER + FAULT.format(n=10) + GROWTH + f"&initiation {group} /\n",
               expect=2)
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    assert "&initiation" in lines[0] and variable in lines[0], lines[0]


def test_along_a_load_path(folder):
    """The load scaled by k = 1 .. 10 (load steps 1 .. 10, k = 10 the fixed load of the
    other tests; the model is linear): the tail starts in the first load step whose probed
    tension, k / 10 of the full load's, reaches the strength, and records that tension."""
    full = initiations(run(folder, "full", tail_model(20, 1.0)))["tension"][0]
    strength = 0.55 * full
    path = ("&load_path sxx = 0.0, 0.0, syy = -2.0, -20.0, sxy = 1.0, 10.0, steps = 9 /\n")
    rows = initiations(run(folder, "path", tail_model(20, strength) + path))
    assert rows["load_step"].tolist() == [6], "k = 6 is the first with 0.6 full >= 0.55 full"
    assert rows["tension"][0] == pytest.approx(0.6 * full, rel=1e-6)


def test_resume_is_refused(folder):
    """--resume of a run with &initiation: one message naming &initiation, exit 2."""
    out = run(folder, "resumable", tail_model(20, 1.0))
    done = subprocess.run([str(ddc2d_exe()), str(folder / "resumable.nml"), "--resume",
                           str(out), "-o", str(folder / "resumed.h5")], capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 2, done.stdout + done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "&initiation" in lines[0], done.stderr


def test_a_vertex_one_increment_from_a_tip_is_in_its_zone(folder):
    """An increment of 0.4 m, four elements of the 20: the vertices 0.4 m from the tips lie on
    the edge of the tips' zones, and the edge belongs to the zone whatever the round-off. The
    tail starts at the largest tension outside the zones, the vertices 0.5 m from the centre
    (it started at 0.6 m, in the tip's singular field)."""
    text = (HEADER + FAULT.format(n=20) + GROWTH.replace(f"increment = {INCREMENT}",
                                                         "increment = 0.4")
            + f"&initiation tensile_strength = 1.0, probe_distance = {PROBE} /\n")
    rows = initiations(run(folder, "zone_edge", text))
    assert rows["kind"].tolist() == [1], "one tail starts"
    assert abs(rows["x"][0]) == pytest.approx(0.5, abs=1e-12), rows["x"]


WEDGE = REPO_ROOT / "tests" / "data" / "growth" / "tail_wedge.nml"


def test_tails_at_a_narrow_wedge_are_solved(folder):
    """tests/data/growth/tail_wedge.nml: the tails of steps 5 and 6 start at fault vertices at
    about 30 degrees to the fault, where Lemke ends on a ray and the Newton method's states
    cycle; its way out of the cycle solves them (docs/contact-and-strength.md#junctions). All
    6 steps run, each starting a tail, the last at the end of the fault's grown part; the
    final solve is Newton's after Lemke failed, in equilibrium."""
    done = subprocess.run([str(ddc2d_exe()), str(WEDGE), "-o", str(folder / "wedge.h5")],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    rows = initiations(folder / "wedge.h5")
    assert rows["step"].tolist() == [1, 2, 3, 4, 5, 6]
    np.testing.assert_allclose(rows["x"][4:], [-1.72811, 1.72835], atol=1e-5)
    np.testing.assert_allclose(rows["y"][4:], [1.04984, -1.54986], atol=1e-5)
    with h5py.File(folder / "wedge.h5", "r") as f:
        solver = f["solver"].attrs
        assert f["growth"].attrs["steps_taken"] == 6
        assert solver["method"] == b"newton"
        assert solver["fallback"].startswith(b"lemke failed: contact: LCP: Lemke ended on a ray")
        assert solver["equilibrium_residual"] < 1e-10


def test_a_failed_growth_step_keeps_the_steps_before(folder):
    """The same model with Lemke alone: step 5's solve fails (a ray). The run writes the 4
    steps before it, complete, with /growth end_reason 'failed' and the failure, and exits
    with status 6; the message names the step and the new fracture. A run with &initiation
    is not resumed, failed or not."""
    model = folder / "wedge_lemke.nml"
    model.write_text(WEDGE.read_text() + "&solver lcp_method = 'lemke' /\n")
    out = folder / "wedge_lemke.h5"
    done = subprocess.run([str(ddc2d_exe()), str(model), "-o", str(out)], capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 6, done.stdout + done.stderr
    message = done.stderr.strip().splitlines()
    assert len(message) == 1, done.stderr
    assert message[0].startswith("ddc2d: error: growth step 5, new fracture 'fault_tail5': "
                                 "contact: LCP: Lemke ended on a ray"), message[0]
    assert "the result holds the 4 growth step(s) before it (end_reason failed)" in message[0]
    assert f"wrote {out}" in done.stdout
    with h5py.File(out, "r") as f:
        growth = f["growth"].attrs
        assert f.attrs["complete"] == 1
        assert growth["end_reason"] == b"failed" and growth["steps_taken"] == 4
        assert growth["failure"].startswith(b"growth step 5, new fracture 'fault_tail5'")
        assert f["growth/step"][()].max() == 4
    assert initiations(out)["step"].tolist() == [1, 2, 3, 4]
    resumed = subprocess.run([str(ddc2d_exe()), str(model), "--resume", str(out), "-o",
                              str(folder / "wedge_resumed.h5")], capture_output=True, text=True,
                             timeout=600)
    assert resumed.returncode == 2 and "&initiation" in resumed.stderr, resumed.stderr


# A flaw under the work criterion: a crack of FLAW_LENGTH centred on the origin, the only other
# fracture a 2 cm crack 100 m away (its field there is a 1e-8 of the remote one) whose
# friction (mu = 10) locks it under compression. Plane strain, E = 50 GPa, nu = 0.25. A
# constant-DD crack of n elements overestimates a crack's work by 1/n (measured: 5.0, 2.5,
# 1.25 % at 20, 40, 80 elements), so efficiencies are compared with the closed forms after
# Richardson extrapolation from 10 and 20 elements.
YOUNG, NU = 50000.0, 0.25
FLAW_LENGTH = 0.2
FAR_CRACK = ("&fracture name = 'far', x = -0.01, 0.01, y = -100.0, -100.0, elements = 4, "
             "condition = 'contact', mu = 10.0 /\n")


def flaw_model(stress, elements=20, criterion="work", new_mu=0.0, threshold=1.0e6,
               strength=1.0e3):
    """One flaw at the origin in `elements` elements; &growth with an increment of a quarter
    of the flaw and tip trials within 10 degrees (the tips do not matter here)."""
    sxx, syy, sxy = stress
    return (HEADER.replace(f"sxx = {SXX}, syy = {SYY}, sxy = {SXY}",
                           f"sxx = {sxx!r}, syy = {syy!r}, sxy = {sxy!r}") + FAR_CRACK +
            f"&growth steps = 1, toughness = 1.0e6, increment = {FLAW_LENGTH / 4}, "
            f"element_length = {FLAW_LENGTH / elements}, criterion = '{criterion}', "
            f"angle_step = 5.0, angle_range = 10.0, work_threshold = {threshold!r}, "
            f"new_mu = {new_mu!r} /\n"
            f"&initiation tensile_strength = {strength!r}, probe_distance = 0.05, "
            f"flaw_x = 0.0, flaw_y = 0.0, flaw_length = {FLAW_LENGTH} /\n")


def rotated(s1, s2, degrees):
    """(sxx, syy, sxy) of principal stresses s1 along `degrees` from x, s2 across it."""
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    return (s1 * c * c + s2 * s * s, s1 * s * s + s2 * c * c, (s1 - s2) * s * c)


def best_sliding_cracks(stress, mu):
    """Orientations [degree] and efficiency pi a (1 - nu^2) tau (tau - mu |sigma_n|) / E of
    the closed frictional cracks of half-length a that maximize it (sigma_n < 0 everywhere):
    the work of the remote shear traction tau on the slip of a crack driven by
    tau - mu |sigma_n| (Pollard & Segall 1987), over a 0.001-degree grid. The two conjugate
    orientations, symmetric about the most compressive stress, tie."""
    sxx, syy, sxy = stress
    angles = np.radians(np.arange(-90.0, 90.0, 0.001))
    c, s = np.cos(angles), np.sin(angles)
    normal = sxx * s * s + syy * c * c - 2.0 * sxy * s * c
    shear = np.abs((syy - sxx) * s * c + sxy * (c * c - s * s))
    drive = np.maximum(shear - mu * np.abs(normal), 0.0)
    efficiency = math.pi * 0.5 * FLAW_LENGTH * (1.0 - NU**2) * shear * drive / YOUNG
    peaks = (efficiency > np.roll(efficiency, 1)) & (efficiency >= np.roll(efficiency, -1))
    assert np.count_nonzero(peaks) == 2
    return np.degrees(angles[peaks]), efficiency.max()


def orientation_gap(a, b):
    """Difference of two crack orientations [degree], modulo half a turn."""
    difference = (a - b) % 180.0
    return min(difference, 180.0 - difference)


def best_trial(trials):
    """Index of the best trial that opens or slips."""
    return np.nanargmax(np.where(trials["state"] >= 1, trials["efficiency"], np.nan))


def extrapolated(coarse, fine):
    """The efficiency of 10 and 20 elements extrapolated to zero element length (order 1)."""
    return 2.0 * fine - coarse


def test_work_flaw_under_tension_opens_across_it(folder):
    """Uniaxial tension of 10 MPa at 22 degrees: the best trial crack is the open one across
    the tension (orientation 112 = -68 degrees, between grid angles), within 1 degree, and
    its efficiency, extrapolated, is a Griffith crack's pi a sigma^2 (1 - nu^2) / E (its work
    per unit length, its G) within 0.5 %; it starts (threshold below it) in that direction."""
    sigma = 10.0
    griffith = math.pi * 0.5 * FLAW_LENGTH * sigma**2 * (1.0 - NU**2) / YOUNG
    stress = rotated(sigma, 0.0, 22.0)
    efficiency = []
    for n in (10, 20):
        out = run(folder, f"work_flaw_tension{n}",
                  flaw_model(stress, elements=n, threshold=0.5 * griffith))
        rows = initiations(out)
        assert rows["kind"].tolist() == [2]
        assert orientation_gap(rows["angle"][0], -68.0) < 1.0, rows["angle"]
        efficiency.append(rows["efficiency"][0])
        trials = flaw_trials(out)
        # The grid (36 orientations every 5 degrees), then the refinement
        assert trials["angle"][:36] == pytest.approx(np.arange(-90.0, 90.0, 5.0), abs=1e-9)
        assert np.nanmax(trials["efficiency"]) == pytest.approx(efficiency[-1], rel=1e-12)
        assert set(trials["state"][:36]) == {2}, "every trial crack opens under tension"
    assert extrapolated(*efficiency) == pytest.approx(griffith, rel=0.005)


@pytest.fixture(scope="module")
def compression_search(folder):
    """Principal stresses -10 and -40 MPa (s1 at 10 degrees), frictional new elements
    (new_mu = 0.6), a work threshold nothing reaches: the flaw's searches of the first
    check with 10 and 20 elements, and the expected best sliding crack."""
    stress = rotated(-10.0, -40.0, 10.0)
    searches = []
    for n in (10, 20):
        out = run(folder, f"work_flaw_search{n}", flaw_model(stress, elements=n, new_mu=0.6))
        searches.append((flaw_trials(out), initiations(out)))
    return stress, searches, best_sliding_cracks(stress, 0.6)


def test_work_flaw_under_compression_slides(folder, compression_search):
    """All-round compression: no trial opens, some slip; the best sliding crack is one of
    the closed form's two conjugate ones within 1 degree, its efficiency extrapolated within
    0.5 %; nothing starts below the threshold."""
    _, searches, (angles, efficiency) = compression_search
    found = []
    for trials, rows in searches:
        assert rows["kind"].size == 0
        assert 2 not in set(trials["state"]) and 1 in set(trials["state"])
        best = best_trial(trials)
        gap = min(orientation_gap(trials["angle"][best], angle) for angle in angles)
        assert gap < 1.0, (trials["angle"][best], angles)
        found.append(trials["efficiency"][best])
    assert extrapolated(*found) == pytest.approx(efficiency, rel=0.005)


@pytest.fixture(scope="module")
def started_flaw(folder, compression_search):
    """The flaw under compression (20 elements) with the work threshold 0.1 % below its best
    efficiency: the result file, the stress, the best efficiency and its trial's angle."""
    stress, searches, _ = compression_search
    trials = searches[1][0]
    best = best_trial(trials)
    top = float(trials["efficiency"][best])
    out = run(folder, "work_flaw_below", flaw_model(stress, new_mu=0.6, threshold=0.999 * top))
    return out, stress, top, trials["angle"][best]


def test_work_flaw_starts_at_its_threshold(folder, started_flaw):
    """The flaw under compression (20 elements) starts a sliding crack when the work
    threshold is 0.1 % below its best efficiency, in the best trial's direction; not 0.1 %
    above it; MTS starts nothing there (no tension)."""
    out, stress, top, angle = started_flaw
    below = initiations(out)
    assert below["kind"].tolist() == [2]
    assert below["efficiency"][0] == pytest.approx(top, rel=1e-9)
    assert orientation_gap(below["angle"][0], angle) < 1e-6
    above = initiations(run(folder, "work_flaw_above",
                            flaw_model(stress, new_mu=0.6, threshold=1.001 * top)))
    assert above["kind"].size == 0
    mts = initiations(run(folder, "mts_flaw_compression",
                          flaw_model(stress, criterion="mts", new_mu=0.6, strength=1.0e-3)))
    assert mts["kind"].size == 0


def test_flaw_trials_figure_draws_the_stored_trials(folder, started_flaw):
    """ddc2d-plot writes <stem>_flaw_trials.png; its line is the stored trials (sorted by
    direction, the stuck ones left out of the line), the started direction marked, the
    threshold dashed."""
    out = started_flaw[0]
    done = subprocess.run([sys.executable, str(PLOT_SCRIPT), str(out), "-o",
                           str(folder / "figures")], capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    assert (folder / "figures" / "work_flaw_below_flaw_trials.png").read_bytes()[:4] == \
        b"\x89PNG"
    trials, rows = flaw_trials(out), initiations(out)
    fig = plot_figures.plot_flaw_trials(load_result(out))
    try:
        lines = {line.get_gid(): line for line in fig.axes[0].get_lines() if line.get_gid()}
        order = np.argsort(trials["angle"], kind="stable")
        line = lines["efficiency:step 1, flaw1"]
        np.testing.assert_array_equal(line.get_xdata(), trials["angle"][order])
        candidate = np.isin(trials["state"][order], (1, 2))
        np.testing.assert_array_equal(line.get_ydata()[candidate],
                                      trials["efficiency"][order][candidate])
        assert np.all(np.isnan(line.get_ydata()[~candidate]))
        chosen = lines["chosen:step 1, flaw1"].get_xdata()
        assert chosen.size == 1 and orientation_gap(chosen[0], rows["angle"][0]) < 1e-9
        with h5py.File(out, "r") as f:
            threshold = f["growth"].attrs["work_threshold"]
        np.testing.assert_array_equal(lines["work_threshold"].get_ydata(), [threshold] * 2)
    finally:
        plot_figures.plt.close(fig)
