"""Every example model in input/ runs to exit 0 with the executable under test (DDC2D_EXE).

The examples run at full size: in a Debug build (-fcheck=all) each takes under about 3 s
on 2 cores (about 15 s for the set), so no reduced copy is needed. Parameter sweeps
(a &sweep group) run their first task. Only namelist models count as examples: files
without a &model group (e.g. classic TWODD decks) are not run here.

Besides the exit status, each gallery model is checked for what its comment block says
it shows (states, which tips slip more), so that a figure in the gallery (docs/gallery.md) cannot
silently turn into something else.
"""

import math
import os
import re
import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import REPO_ROOT, ddc2d_exe, kgd_viscosity_solution
from ddc2d.reader import STATE_CODES, attr_text, decode, index_of_extreme, is_complete

INPUT = REPO_ROOT / "input"
EXAMPLES = sorted(p for p in INPUT.glob("*.nml")
                  if re.search(r"^\s*&model\b", p.read_text(), re.IGNORECASE | re.MULTILINE))


def is_sweep(path):
    return re.search(r"^\s*&sweep\b", path.read_text(), re.IGNORECASE | re.MULTILINE)


def run_example(path, out):
    args = [str(ddc2d_exe()), str(path), "-o", str(out)]
    if is_sweep(path):
        args += ["--task", "0"]
    return subprocess.run(args, capture_output=True, text=True, timeout=300)


def states_of(f, name):
    """The element states of fracture `name` (numpy array)."""
    names = [decode(n) for n in f["fractures/name"][()]]
    index = names.index(name)
    first = f["fractures/first_element"][index]
    last = f["fractures/last_element"][index]
    return f["elements/state"][first - 1:last]


def tip_k2(f):
    return np.abs(f["tips/k2"][()])


def test_there_are_enough_examples():
    gallery = [p for p in EXAMPLES if not is_sweep(p)]
    assert len(gallery) >= 8
    for name in ("paper_fault_slip", "paper_fault_stick", "segmented_right_step",
                 "segmented_left_step", "ramped_fault", "intersecting_faults",
                 "branching_fault", "splayed_fault", "curved_fault", "en_echelon",
                 "pressurized_fracture_near_fault"):
        assert INPUT / f"{name}.nml" in EXAMPLES


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_runs(path, tmp_path):
    text = path.read_text()
    assert text.startswith("!"), f"{path.name} must start with a comment block"
    out = tmp_path / f"{path.stem}.h5"
    done = run_example(path, out)
    assert done.returncode == 0, f"{path.name}: {done.stderr}"
    # A Debug build (-fcheck=all) warns of every hidden array copy: none in a model's run.
    assert "Fortran runtime" not in done.stderr, done.stderr[-2000:]
    if is_sweep(path):
        assert list(tmp_path.glob(f"{path.stem}_task*.h5")), done.stdout
        return
    with h5py.File(out, "r") as f:
        assert is_complete(f.attrs)
        kinds = [attr_text(f["fields"][g].attrs, "kind") for g in f.get("fields", {})]
        assert "grid" in kinds, f"{path.name} has no grid"
        check = EXPECTED.get(path.stem)
        if check is not None:
            check(f)


# ------------------------------------------------------------------ what each example shows


def _all(f, name, state):
    assert np.all(states_of(f, name) == STATE_CODES[state]), (name, states_of(f, name))


def _some(f, name, state):
    assert np.any(states_of(f, name) == STATE_CODES[state]), (name, state)


def check_right_step(f):
    _all(f, "west", "slip")
    _all(f, "east", "slip")
    k2 = tip_k2(f)  # tips: west outer, west inner, east inner, east outer
    assert k2[1] > k2[0] and k2[2] > k2[3]  # releasing: the inner tips slip more


def check_left_step(f):
    _all(f, "west", "slip")
    _all(f, "east", "slip")
    k2 = tip_k2(f)
    assert k2[1] < 0.9 * k2[0] and k2[2] < 0.9 * k2[3]  # restraining: inner tips clamped
    # The mean stress midway between the overlapping tips, at the grid point (0, 0), is more
    # compressive than remote. (The grid holds the origin; a grid without it would have
    # points equally near, and the tie rule would pick the first of them.)
    grid = f["fields/map"]
    x, y = grid["x"][()], grid["y"][()]
    j, i = np.unravel_index(index_of_extreme(np.hypot(x, y), "min"), x.shape)
    assert abs(x[j, i]) <= 1e-9 * 3000.0 and abs(y[j, i]) <= 1e-9 * 3000.0, (x[j, i], y[j, i])
    remote = f.attrs["remote_stress"]
    assert 0.5 * (grid["sxx"][j, i] + grid["syy"][j, i]) < 0.5 * (remote[0] + remote[1])


def check_ramp(f):
    state = states_of(f, "flat-ramp-flat")
    assert np.all(state[:150] == STATE_CODES["slip"]) and np.all(state[266:] == STATE_CODES["slip"])
    assert np.all(state[150:266] == STATE_CODES["stick"])  # the ramp


def check_branching(f):
    _all(f, "main", "slip")
    state = states_of(f, "branch")
    assert state[0] == STATE_CODES["stick"] and state[-1] == STATE_CODES["slip"]


def check_curved(f):
    state = states_of(f, "arc")
    assert state[0] == STATE_CODES["stick"] and state[-1] == STATE_CODES["stick"]
    assert state[150] == STATE_CODES["slip"]


def check_pressurized_near_fault(f):
    _all(f, "hydrofracture", "open")
    _some(f, "fault", "slip")
    _some(f, "fault", "stick")


def check_splayed(f):
    _all(f, "main", "slip")
    _all(f, "splay_north", "stick")


def check_all_slip(*names):
    def check(f):
        for name in names:
            _all(f, name, "slip")
    return check


def growth_rows(f, fracture, end):
    """The /growth records of one tip (fracture name, end 0 begin / 1 end), in step order."""
    names = [decode(n) for n in f["fractures/name"][()]]
    g = f["growth"]
    return np.flatnonzero((g["fracture_id"][()] == names.index(fracture) + 1)
                          & (g["end"][()] == end))


def check_smooth_growth(f, fracture, steps, shrinking=True):
    """Both tips of a point-symmetric model grow `steps` times and arrest; after the first
    kink their angles keep one sign (no zig-zag) and, with `shrinking`, shrink; the tips stay
    point-symmetric."""
    g = f["growth"]
    assert decode(g.attrs["end_reason"]) == "arrested"
    begin, end = growth_rows(f, fracture, 0), growth_rows(f, fracture, 1)
    assert begin.size == end.size == steps + 1
    reason = g["reason"][()]
    assert np.all(reason[end[:-1]] == 0) and reason[end[-1]] == 1  # grew, then subcritical
    angle = g["angle"][()][end[1:-1]]
    assert np.all(np.sign(angle) == np.sign(angle[0]))
    assert not shrinking or np.all(np.diff(np.abs(angle)) < 0)
    assert g["k1"][end[0]] == 0.0  # the closed fault or flaw: the first kink is mode II
    np.testing.assert_allclose(abs(g["mts_angle"][end[0]]), 70.528779, atol=0.1)
    for key in ("x", "y"):  # point symmetry, to a tolerance
        np.testing.assert_allclose(g[key][()][begin], -g[key][()][end], atol=1e-9)


def check_wings(f):
    check_wings_of(f, 21)


def check_gypsum_sample(f):
    """The wings of the sample between platens grow 15 steps, open, and arrest inside the
    sample with their last elements within 10 degrees of its axis; the platens carry equal
    and opposite loads near E' times the strain (41 MPa). Their kinks keep one sign but stop
    shrinking near the platens (from 0.06 degrees on): the body's own field."""
    check_wings_of(f, 15, shrinking=False)
    e = f["elements"]
    created = e["created_step"][()]
    last = created == created.max()
    direction = np.degrees(np.arctan2(np.abs(e["y_end"][()] - e["y_begin"][()]),
                                      np.abs(e["x_end"][()] - e["x_begin"][()])))
    assert np.all(direction[last] > 80.0), direction[last]
    assert np.all(np.abs(f["tips/y"][()]) < 0.0762 - 0.01)
    force = f["body/side_force_y"][()]
    assert abs(force[0] + force[2]) < 1e-9 * force[0]
    np.testing.assert_allclose(force[0] / 0.0762, 6000 / (1 - 0.2**2) * 1e-3 / 0.1524,
                               rtol=0.05)


def check_wings_of(f, steps, shrinking=True):
    check_smooth_growth(f, "flaw", steps, shrinking)
    created = f["elements/created_step"][()]
    assert np.all(f["elements/state"][()][created > 0] == STATE_CODES["open"])


def check_tail_cracks(f):
    check_smooth_growth(f, "fault", 11)


def check_restraining_bend_tails(f):
    """Tails start at both corners of the restraining bend, above the rock's strength: at the
    west corner (0, 0) in step 1, at the east corner in step 2, each perpendicular to the
    maximum tension there (-97.5 and 82.7 degrees from +x, 0.5 degree); both grow and the
    run arrests."""
    rows = f["growth/initiations"]
    assert list(rows["kind"][()]) == [1, 1] and list(rows["step"][()]) == [1, 2]
    np.testing.assert_allclose(rows["x"][()], [0.0, 0.433013], atol=1e-9)
    np.testing.assert_allclose(rows["y"][()], [0.0, 0.25], atol=1e-9)
    assert np.all(rows["tension"][()] >= rows.attrs["tensile_strength"])
    np.testing.assert_allclose(rows["angle"][()], [-97.5, 82.7], atol=0.5)
    names = [decode(n) for n in f["fractures/name"][()]]
    assert [names[k - 1] for k in rows["fracture_id"][()]] == ["fault_tail1", "fault_tail2"]
    assert decode(f["growth"].attrs["end_reason"]) == "arrested"
    for k in rows["fracture_id"][()]:
        assert f["growth/length"][()][f["growth/fracture_id"][()] == k].sum() > 0.05


def check_releasing_bend_tails(f):
    """Tails start at both corners of the releasing bend, above the rock's strength: at the
    west corner (0, 0) in step 1, at the east corner (0, -0.5) in step 2, each into the
    corner's inside, perpendicular to the maximum tension there (-128.8 and 51.3 degrees from
    +x, 0.5 degree); both open (K_I above the toughness, no K_II to speak of), grow at least
    0.05 m further, every element of theirs open, and stop at the toughness: in the last two
    steps K_eq stays within 2 % of it and they grow less than 2 mm (they hover at K_eq =
    toughness while the fault's tips grow, so whether the last one grew is not checked)."""
    rows = f["growth/initiations"]
    assert list(rows["kind"][()]) == [1, 1] and list(rows["step"][()]) == [1, 2]
    np.testing.assert_allclose(rows["x"][()], [0.0, 0.0], atol=1e-9)
    np.testing.assert_allclose(rows["y"][()], [0.0, -0.5], atol=1e-9)
    assert np.all(rows["tension"][()] >= rows.attrs["tensile_strength"])
    np.testing.assert_allclose(rows["angle"][()], [-128.8, 51.3], atol=0.5)
    names = [decode(n) for n in f["fractures/name"][()]]
    assert [names[k - 1] for k in rows["fracture_id"][()]] == ["fault_tail1", "fault_tail2"]
    g = f["growth"]
    toughness = g.attrs["toughness"]
    for name in ("fault_tail1", "fault_tail2"):
        tip = growth_rows(f, name, 1)
        assert g["k1"][tip[0]] > 5.0 * toughness and abs(g["k2"][tip[0]]) < 0.2 * g["k1"][tip[0]]
        assert g["length"][()][tip].sum() > 0.05
        assert np.all(g["k_eq"][()][tip[-2:]] < 1.02 * toughness)
        assert g["length"][()][tip[-2:]].sum() < 0.002
        own = f["elements/fracture_id"][()] == names.index(name) + 1
        assert np.all(f["elements/state"][()][own] == STATE_CODES["open"])


def check_thrust_ramp_from_flaw(f):
    """The flaw under compression (its largest principal stress negative: no tension starts
    it) starts a sliding crack in step 1, at 30 degrees from +x (a thrust dipping towards the
    hinterland, 1 degree), its efficiency above the threshold; its upper tip grows to the
    surface (broke through it in step 6) and every element of it slips or opens (none
    sticks); its lower tip and the detachment's updip tip stop next to each other."""
    rows = f["growth/initiations"]
    assert list(rows["kind"][()]) == [2] and list(rows["step"][()]) == [1]
    assert rows["tension"][0] < 0.0
    assert abs(rows["angle"][0] - 30.0) < 1.0
    g = f["growth"]
    assert rows["efficiency"][0] >= g.attrs["work_threshold"]
    names = [decode(n) for n in f["fractures/name"][()]]
    assert names == ["detachment", "flaw1"]
    upper, lower = growth_rows(f, "flaw1", 1), growth_rows(f, "flaw1", 0)
    reason = g["reason"][()]
    assert reason[upper[-1]] == 3 and g["step"][upper[-1]] == 6  # surface
    assert np.all(reason[upper[:-1]] == 0)
    assert reason[lower[0]] == 2 and reason[growth_rows(f, "detachment", 1)[0]] == 2
    own = f["elements/fracture_id"][()] == 2
    states = f["elements/state"][()][own]
    assert np.all((states == STATE_CODES["slip"]) | (states == STATE_CODES["open"]))
    assert np.count_nonzero(states == STATE_CODES["slip"]) > own.sum() // 2


def check_growth_along_path(f, first_load_step, length):
    """Growth along a load path: nothing grows before `first_load_step` (1-based; the first
    load step with K_eq at the toughness), both tips end `length` long (to 1 mm: the length
    search resolves a stable length to 1/64 of an element, 0.6-0.8 mm here; to 1e-9 of each
    other, point-symmetric) and arrested, the grown elements are open, and the grown length
    never falls from one load step to the next."""
    g, h = f["growth"], f["history"]
    grew = g["load_step"][()][g["reason"][()] == 0]
    assert grew.min() == first_load_step
    assert decode(g.attrs["end_reason"]) == "arrested"
    grown = h["grown_length"][()]
    np.testing.assert_allclose(grown[-1], [length, length], atol=1e-3)
    assert abs(grown[-1, 0] - grown[-1, 1]) < 1e-9
    assert np.all(grown[:first_load_step - 1] == 0.0) and np.all(np.diff(grown, axis=0) >= 0)
    created = f["elements/created_step"][()]
    assert np.all(f["elements/state"][()][created > 0] == STATE_CODES["open"])


def check_grown_strength_laws(f):
    """The new elements take the tip element's laws as given and &growth's new_sf and
    new_tensile_strength; the input elements keep theirs."""
    e = f["elements"]
    new = e["created_step"][()] > 0
    assert new.sum() >= 4
    for name, grown, given in [("sf_residual", 0.2, 0.2), ("mu_dynamic", 0.45, 0.45),
                               ("slip_weakening_distance", 1e-4, 1e-4), ("sf", 2.0, 1.0),
                               ("tensile_strength", 3.0, 1.0)]:
        assert np.all(e[name][()][new] == grown) and np.all(e[name][()][~new] == given), name


def check_echelon_linking(f):
    """Step 2: the west inner tip links to east (5), the east one would close a contour
    (refused, 8 enclosing); the outer tips arrest; the link ends on a vertex of east, no tip
    there."""
    g = f["growth"]
    reason = g["reason"][()]
    assert list(reason[growth_rows(f, "west", 1)]) == [0, 5]
    assert list(reason[growth_rows(f, "east", 0)]) == [0, 8]
    assert b"8 enclosing" in g.attrs["reason_coding"]
    for fracture, outer in (("west", 0), ("east", 1)):
        assert reason[growth_rows(f, fracture, outer)][-1] == 1
    assert decode(g.attrs["end_reason"]) == "arrested"
    e = f["elements"]
    fid = e["fracture_id"][()]
    west = np.flatnonzero(fid == 1)
    link = (e["x_end"][()][west[-1]], e["y_end"][()][west[-1]])
    east = np.flatnonzero(fid == 2)
    assert np.any((e["x_begin"][()][east] == link[0]) & (e["y_begin"][()][east] == link[1]))
    assert not np.any(np.hypot(f["tips/x"][()] - link[0], f["tips/y"][()] - link[1]) < 1e-9)


def check_hydraulic_fracture(f):
    rows = growth_rows(f, "hydrofracture", 1)  # the lower tip
    assert list(f["growth/reason"][()][rows]) == [0] * 9 + [5]  # links in step 10
    _some(f, "fault", "slip")
    _all(f, "hydrofracture", "open")
    # The link splits a fault element: the fault has one element more.
    fid = f["elements/fracture_id"][()]
    assert np.count_nonzero(fid == 1) == 101


def check_joint_to_surface(f):
    """The upper tip breaks through the surface: its last element ends on y = 0 and the
    mouth is no tip; the lower tip arrests."""
    reason = f["growth/reason"][()]
    assert reason[growth_rows(f, "joint", 1)[-1]] == 3  # the upper tip: through the surface
    assert reason[growth_rows(f, "joint", 0)[-1]] == 1  # the lower tip: arrested
    assert decode(f["growth"].attrs["end_reason"]) == "arrested"
    e = f["elements"]
    last = f["fractures/last_element"][()][0] - 1
    assert abs(e["y_end"][()][last]) <= 1e-12
    assert max(e["y_begin"][()].max(), np.delete(e["y_end"][()], last).max()) < -2.5
    assert np.all(f["tips/y"][()] < -2.5)


def check_progressive_failure(f):
    """The centre slips from 6 MPa, the patches fail over 7.25-7.5 MPa and keep 1 MPa."""
    h = f["history"]
    sxy, ds = h["sxy"][()], h["ds"][()]
    moving = np.abs(ds) > 0
    full = int(np.argmax(moving.all(axis=1)))
    partial = moving[full - 1].sum()
    assert abs(sxy[full] - 7.5) < 1e-9 and 40 < partial < 100, (sxy[full], partial)
    sf = f["elements/sf_in_force"][()]
    x = f["elements/x_mid"][()]
    assert np.all(sf[np.abs(x) > 0.4] == 1.0) and np.all(sf[np.abs(x) < 0.4] == 0.0)


def check_joint_set(f):
    """Sticking joints deform by traction / stiffness; the joints triple the crack's opening."""
    e = f["elements"]
    fid, state = e["fracture_id"][()], e["state"][()]
    joints = (fid > 1) & (state == STATE_CODES["stick"])
    assert joints.sum() > 400
    for dd, traction, stiffness in (("ds", "shear_traction", "shear_stiffness"),
                                    ("dn", "normal_traction", "normal_stiffness")):
        assert np.allclose(e[dd][joints] * e[stiffness][joints], -e[traction][joints],
                           rtol=1e-9, atol=1e-8)
    # Centre opening of the same crack in intact rock: 4 (1 - nu^2) p_net a / E.
    intact = 4.0 * (1.0 - 0.25 ** 2) * 7.0 * 1.0 / 20000.0
    opening = -e["dn"][fid == 1]
    assert 2.5 * intact < opening.max() < 3.5 * intact, (opening.max(), intact)
    for name in ("joint_2", "joint_3"):
        _some(f, name, "slip")
    for name in ("joint_1", "joint_4"):
        _all(f, name, "stick")


def check_slip_weakening_thrust(f):
    """The weakening segment ruptures whole at the dynamic friction; the strong one stops it."""
    e = f["elements"]
    y, state, ds, mu = (e[k][()] for k in ("y_mid", "state", "ds", "mu_in_force"))
    upper = y > -3000.0
    assert np.all(state[upper] == STATE_CODES["slip"])
    assert np.all(np.abs(ds[upper]) > 0.05) and np.allclose(mu[upper], 0.45, rtol=1e-12)
    assert np.all(ds[state == STATE_CODES["slip"]] < 0)  # reverse
    lower_slipping = np.count_nonzero(state[~upper] == STATE_CODES["slip"])
    assert 10 < lower_slipping < 90 and np.allclose(mu[~upper], 0.7, rtol=1e-12), \
        lower_slipping
    assert np.nanmax(f["fields/surface/uy"][()]) > 0.5


def check_injection_well(f):
    """The fault sticks until day 22, then slips around the junction with the fracture; the
    patch reaches the fault's top (its first vertex, 2 km depth) on day 25 and spans 1050 m
    of the 1155 m fault on day 30, with up to 14.7 mm of normal slip; the fracture never
    slips."""
    h, e = f["history"], f["elements"]
    time, state = h["time"][()], h["state"][()]
    fault, fracture = (slice(first - 1, last) for first, last in
                       zip(f["fractures/first_element"][()], f["fractures/last_element"][()]))
    slipping = np.any(state[:, fault] == STATE_CODES["slip"], axis=1)
    assert abs(time[np.argmax(slipping)] - 22.0) < 1e-9 and np.all(slipping[22:])
    # Where it starts: 50 m (10 elements) around the junction, half the fault's length down.
    half = 0.5 * np.sum(2.0 * e["half_length"][fault])
    first = np.argmax(slipping)
    assert h["front_begin"][first, 0] < half < h["front_end"][first, 0]
    assert 45.0 < h["slipping_length"][first, 0] < 55.0
    top = np.flatnonzero(h["front_begin"][:, 0] == 0.0)
    assert abs(time[top[0]] - 25.0) < 1e-9 and np.all(np.diff(top) == 1)
    assert 1045.0 < h["slipping_length"][-1, 0] < 1055.0 and 1154.0 < 2 * half < 1156.0
    assert np.all(state[:, fracture] == STATE_CODES["stick"])
    assert abs(h["pressure"][first, fault][115] - 2.1) < 0.05  # at the junction
    ds = e["ds"][fault]
    assert np.all(ds <= 0.0) and abs(ds.min() + 0.0147) < 0.0002  # normal slip


def test_layered_k_approach_script(tmp_path):
    """examples/layered/k_approach.py (docs/layered-rock.md#what-to-expect) at two gaps: K_I
    at the upper tip rises as it nears a softer bed, falls as it nears a stiffer one."""
    script = REPO_ROOT / "examples" / "layered" / "k_approach.py"
    done = subprocess.run([sys.executable, str(script), "--gaps", "0.5", "0.12", "--output",
                           str(tmp_path / "k.png")],
                          capture_output=True, text=True, timeout=300, cwd=tmp_path,
                          env=dict(os.environ, DDC2D_EXE=str(ddc2d_exe())))
    assert done.returncode == 0, done.stderr
    rows = [line.split() for line in done.stdout.splitlines()[2:4]]
    stiff_below = [float(row[1]) for row in rows]
    soft_below = [float(row[3]) for row in rows]
    assert 1.0 < stiff_below[0] < stiff_below[1], done.stdout
    assert 1.0 > soft_below[0] > soft_below[1], done.stdout
    assert (tmp_path / "k.png").stat().st_size > 0


def check_crack_toward_soft_layer(f):
    """The tip near the soft bed has the larger K_I, both above the one material's."""
    y, k1 = f["tips/y"][()], f["tips/k1"][()]
    griffith = 10.0 * np.sqrt(np.pi)
    upper, lower = k1[np.argmax(y)], k1[np.argmin(y)]
    assert upper > 1.4 * griffith and griffith < lower < upper, (upper, lower)


def check_crack_grows_to_soft_layer(f):
    """The upper tip stops before the interface (reason 9, 0.05 m below it) with the larger
    K_I, above the one material's for the grown crack; the lower tip grows to the step
    limit."""
    g = f["growth"]
    stops = np.flatnonzero(g["reason"][()] == 9)
    assert stops.size == 1 and g["y"][stops[0]] == pytest.approx(-0.05, abs=1e-9)
    assert decode(g.attrs["end_reason"]) == "step_limit"
    y, k1 = f["tips/y"][()], f["tips/k1"][()]
    upper, lower = k1[np.argmax(y)], k1[np.argmin(y)]
    griffith = 10.0 * np.sqrt(np.pi * 0.5 * (y.max() - y.min()))
    assert upper > 1.5 * griffith and griffith < lower < upper, (upper, lower, griffith)


def check_fault_across_layers(f):
    """Split at the interface; every element slips, more in the soft upper bed."""
    e = f["elements"]
    y, ds = e["y_mid"][()], e["ds"][()]
    assert y.size == 42 and np.any(e["y_end"][()] == 0.0)
    _all(f, "fault", "slip")
    assert np.max(np.abs(ds[y > 0])) > 1.5 * np.max(np.abs(ds[y < 0])), ds


def check_kgd(f):
    """61 steps to 64 elements per wing, every element open; the half-length to the fronts
    within 0.3 % and the net pressure at the well within 0.75 % of the toughness solution
    (K_m = 7.2: the viscosity's share of the apparent toughness and of the pressure drop
    moves the net pressure by 0.3 % from that of K_m = 23)."""
    h = f["history"]
    t = h["time"][-1]
    e_prime = 30000.0 / (1.0 - 0.25**2)
    length = (e_prime * 1.0e-4 * t / (2.0 * math.sqrt(math.pi)))**(2.0 / 3.0)
    assert h["time"].shape == (61,) and h["element_count"][-1] == 128
    _all(f, "crack", "open")
    assert abs((0.1 + h["grown_length"][-1].mean()) / length - 1.0) < 0.003
    x = f["elements/x_mid"][()]
    well = np.argsort(np.abs(x))[:2]
    net = h["pressure"][-1][well].mean() - 1.0
    assert abs(net * math.sqrt(math.pi * length) - 1.0) < 0.0075


def check_kgd_viscous(f):
    """61 steps to 70 elements per wing, every element open; the half-length to the fronts
    and the opening at the well within 1.6 % of Adachi & Detournay's viscosity solution."""
    h = f["history"]
    length, opening = kgd_viscosity_solution(h["time"][-1], 30000.0 / (1.0 - 0.25**2), 1.0e-9,
                                             1.0e-4)
    assert h["time"].shape == (61,) and h["element_count"][-1] == 140
    _all(f, "crack", "open")
    assert abs((0.125 + h["grown_length"][-1].mean()) / length - 1.0) < 0.016
    x = f["elements/x_mid"][()]
    well = np.argsort(np.abs(x))[:2]
    assert abs(-h["dn"][-1][well].mean() / opening - 1.0) < 0.016


EXPECTED = {
    "crack_toward_soft_layer": check_crack_toward_soft_layer,
    "crack_grows_to_soft_layer": check_crack_grows_to_soft_layer,
    "fault_across_layers": check_fault_across_layers,
    "injection_well_normal_fault": check_injection_well,
    "strong_patch_progressive_failure": check_progressive_failure,
    "joint_set_pressurized_crack": check_joint_set,
    "slip_weakening_thrust": check_slip_weakening_thrust,
    "wing_cracks_sliding_flaw": check_wings,
    "gypsum_sample_wing_cracks": check_gypsum_sample,
    "fault_tail_cracks": check_tail_cracks,
    "restraining_bend_tails": check_restraining_bend_tails,
    "releasing_bend_tails": check_releasing_bend_tails,
    "thrust_ramp_from_flaw": check_thrust_ramp_from_flaw,
    "wings_rising_axial_load": lambda f: check_growth_along_path(f, 6, 0.9768),
    "tail_cracks_rising_pore_pressure": lambda f: check_growth_along_path(f, 1, 0.9085),
    "fault_grown_with_strength_laws": check_grown_strength_laws,
    "echelon_cracks_linking": check_echelon_linking,
    "hydraulic_fracture_toward_fault": check_hydraulic_fracture,
    "hydraulic_fracture_kgd": check_kgd,
    "hydraulic_fracture_kgd_viscous": check_kgd_viscous,
    "joint_growing_to_surface": check_joint_to_surface,
    "segmented_right_step": check_right_step,
    "segmented_left_step": check_left_step,
    "ramped_fault": check_ramp,
    "branching_fault": check_branching,
    "curved_fault": check_curved,
    "pressurized_fracture_near_fault": check_pressurized_near_fault,
    "splayed_fault": check_splayed,
    "intersecting_faults": check_all_slip("right-lateral", "left-lateral"),
    "en_echelon": check_all_slip(*[f"segment_{k}" for k in range(1, 6)]),
    "paper_fault_slip": check_all_slip("fault"),
    "paper_fault_stick": lambda f: _all(f, "fault", "stick"),
}
