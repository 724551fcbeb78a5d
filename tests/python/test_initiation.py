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
- bad input: one message naming &initiation and the variable, exit 2.
"""

import math
import subprocess

import h5py
import numpy as np
import pytest

from conftest import ddc2d_exe
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
    """tensile_strength 0.1 % above the largest probed tension: nothing; 0.1 % below: one."""
    largest = max(p[3] for p in field20)
    assert largest > 0.0
    above = initiations(run(folder, "above", tail_model(20, 1.001 * largest)))
    assert above["kind"].size == 0, "nothing starts above the largest probed tension"
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
