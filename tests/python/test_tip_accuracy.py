"""Accuracy of K (docs/theory/tips.md): the higher-order re-solve (the default) against
closed forms on straight, graded, circular-arc and frictional cracks: re-solved whole, its
order of convergence; by its local zones coupled to the rest (the default on larger
cracks), its error at any size; on models without a closed form, its convergence; and the
tip element's K (k_method = 'tip_element') on the arcs as the guide documents it, with the
Richardson value of three meshes (ddc2d.richardson)."""

import math
import re

import h5py
import numpy as np
import pytest
from closed_forms import arc_crack_k

from conftest import REPO_ROOT, solve_text
from ddc2d.richardson import extrapolate

RADIUS, TENSION = 1.0, 1.0
HEAD = "&model title = 'k', youngs_modulus = 50000.0, poissons_ratio = 0.25 /\n"


def polyline(x, y, extra="condition = 'traction', bc_s = 0.0, bc_n = 0.0"):
    xs = ", ".join(f"{v:.17g}" for v in x)
    ys = ", ".join(f"{v:.17g}" for v in y)
    return f"&fracture name = 'crack', x = {xs}, y = {ys}, elements = 1, {extra} /\n"


#: A zone larger than any crack here: the whole crack re-solved
WHOLE = 1000


def solve_k(folder, stem, text, k_method="auto", zone=None):
    """K_I, K_II of every tip and the /tips k_method attribute (zones of `zone` elements,
    default the program's)."""
    zone_text = f", k_zone_elements = {zone}" if zone else ""
    text += f"&solver k_method = '{k_method}'{zone_text} /\n"
    with h5py.File(solve_text(folder, stem, text), "r") as f:
        return f["tips/k1"][()], f["tips/k2"][()], f["tips"].attrs["k_method"].decode()


def arc_text(half_angle, n):
    """The arc in n equal chords, traction-free faces, sxx = syy = TENSION."""
    angles = np.linspace(-half_angle, half_angle, n + 1)
    return (HEAD + f"&remote_stress sxx = {TENSION}, syy = {TENSION}, sxy = 0.0 /\n"
            + polyline(RADIUS * np.sin(angles), RADIUS * np.cos(angles)))


def graded_x(n, ratio=3.0):
    """Vertices of a crack from -1 to 1 in n elements whose lengths fall geometrically by
    `ratio` from the centre to each tip."""
    half = n // 2
    lengths = ratio ** (-np.arange(half) / (half - 1))[::-1]
    lengths /= lengths.sum()
    left = np.concatenate([[-1.0], -1.0 + np.cumsum(lengths)])
    return np.concatenate([left, -left[-2::-1]])


def order_of(errors):
    """Observed orders of successive meshes each twice as fine."""
    errors = np.abs(np.asarray(errors))
    return np.log2(errors[:-1] / errors[1:])


# Half-angle [degrees], meshes [chords] of the arcs re-solved whole (the largest relative
# error of K_I, K_II on the middle mesh, the issue's 50 and 145 chords: measured 4e-7 and
# 1e-6, 1.1e-6 and 1.8e-7).
ARCS = {90: (25, 50, 100), 145: (73, 145, 290)}


@pytest.fixture(scope="module", params=sorted(ARCS), ids=lambda a: f"{a}deg")
def arc_errors(request, tmp_path_factory):
    """K_I, |K_II| / closed form - 1 at both tips on the arc's meshes, shape
    (mesh, mode, tip), by the re-solve of the whole arc."""
    half_angle = request.param
    folder = tmp_path_factory.mktemp("arc")
    exact = arc_crack_k(math.radians(half_angle), RADIUS, TENSION)
    errors = []
    for n in ARCS[half_angle]:
        k1, k2, method = solve_k(folder, f"arc{n}", arc_text(math.radians(half_angle), n),
                                 zone=WHOLE)
        assert method == "higher_order"
        errors.append((k1 / exact[0] - 1.0, np.abs(k2) / exact[1] - 1.0))
    return np.array(errors)


def test_arc_k_within_1e_5_on_the_issue_meshes(arc_errors):
    """90 degrees on 50 chords, 145 degrees on 145: K_I and K_II within 1e-5 (the issue
    asks for 1 %), the same at both tips."""
    assert np.max(np.abs(arc_errors[1])) < 1e-5
    assert np.max(np.abs(arc_errors[:, :, 0] - arc_errors[:, :, 1])) < 1e-7


def test_arc_k_converges_at_least_as_one_over_n_squared(arc_errors):
    """Observed orders of K_I and K_II over the three meshes (measured 3.0-3.3)."""
    for mode in (0, 1):
        assert np.all(order_of(arc_errors[:, mode, 0]) > 2.5)


def frictional_text(n):
    """A straight crack of half-length 1 in n contact elements (mu 0.6) under sxx = syy =
    -50, sxy = 40: every element slips, K_II = 10 sqrt(pi), K_I = 0."""
    x = np.linspace(-1.0, 1.0, n + 1)
    return (HEAD + "&remote_stress sxx = -50.0, syy = -50.0, sxy = 40.0 /\n"
            + polyline(x, 0.0 * x, "condition = 'contact', mu = 0.6"))


def straight_text(x):
    return HEAD + "&remote_stress sxx = 0.0, syy = 1.0, sxy = 0.5 /\n" + polyline(x, 0.0 * x)


# The local re-solve (zones of the default 32 elements, coupled to the rest): crack and
# closed-form K_I, K_II. Measured largest errors: 1.6e-8, 3.9e-7, 2.5e-7, 6.5e-7, 2.7e-7,
# 1.0e-5, 2.3e-6, 1.6e-8 (docs/theory/tips.md#the-size-of-the-zones).
SQRT_PI = math.sqrt(math.pi)
LOCAL = {
    "straight_100": (lambda: straight_text(np.linspace(-1.0, 1.0, 101)), (SQRT_PI, 0.5 * SQRT_PI)),
    "straight_400": (lambda: straight_text(np.linspace(-1.0, 1.0, 401)), (SQRT_PI, 0.5 * SQRT_PI)),
    "graded_100": (lambda: straight_text(graded_x(100)), (SQRT_PI, 0.5 * SQRT_PI)),
    "arc90_100": (lambda: arc_text(math.radians(90), 100), arc_crack_k(math.radians(90))),
    "arc90_200": (lambda: arc_text(math.radians(90), 200), arc_crack_k(math.radians(90))),
    "arc145_145": (lambda: arc_text(math.radians(145), 145), arc_crack_k(math.radians(145))),
    "arc145_290": (lambda: arc_text(math.radians(145), 290), arc_crack_k(math.radians(145))),
    "frictional_100": (lambda: frictional_text(100), (0.0, 10.0 * SQRT_PI)),
}


@pytest.mark.parametrize("case", sorted(LOCAL))
def test_local_re_solve_within_2e_5(tmp_path, case):
    """Cracks longer than two zones: K by the zones coupled to the rest within 2e-5 of the
    closed forms (the issue asks for 1e-4), at both tips; K_I of the closed frictional
    crack 0."""
    make_text, exact = LOCAL[case]
    k1, k2, method = solve_k(tmp_path, case, make_text())
    assert method == "higher_order"
    if exact[0] == 0.0:
        assert np.all(k1 == 0.0)
    else:
        assert np.max(np.abs(k1 / exact[0] - 1.0)) < 2e-5
    assert np.max(np.abs(np.abs(k2) / exact[1] - 1.0)) < 2e-5


def zones_and_whole(folder, text):
    """(K_I, K_II) of the model's tips re-solved whole and by the default zones, both by
    the re-solve."""
    ks = []
    for stem, k_method, zone in (("whole", "higher_order", WHOLE), ("zones", "auto", None)):
        k1, k2, method = solve_k(folder, stem, text, k_method, zone=zone)
        assert method == "higher_order"
        ks.append((k1, k2))
    return ks


def test_a_kinked_fault_has_a_zone_at_its_kink(tmp_path):
    """A frictional fault with an 11-degree kink at its middle (60 elements a side, slipping
    under sxy = 54.13): K by the default zones within 1e-5 of the whole re-solve (measured
    4e-7). Recovered DDs cannot follow the DD across a kink: without the kink's own zone K
    was 0.8 % off."""
    text = ("&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /\n"
            "&remote_stress sxx = -143.75, syy = -81.25, sxy = 54.13 /\n"
            "&fracture name = 'fault', x = -1.0, 0.0, 1.0, y = 0.0, 0.1, 0.0, elements = 60, "
            "mu = 0.6, sf = 1.0, condition = 'contact' /\n")
    (_, k2_whole), (_, k2_zones) = zones_and_whole(tmp_path, text)
    assert np.max(np.abs(k2_zones / k2_whole - 1.0)) < 1e-5


def test_a_crack_across_two_materials_has_a_zone_where_they_meet(tmp_path):
    """A pressurized crack of 200 elements across the interface of two bonded half-planes
    (E 40000 below, 5000 above; straight, no kink where it crosses): K by the default zones
    within 1e-5 of the whole re-solve (measured 1.9e-6). The DD is not smooth where the
    materials meet, and the crossing has a full zone of its own however little the crack
    turns there: with 2 elements a side K was 7.2e-5 off."""
    text = ("&model domain = 'bimaterial', interface_y = 0.0 /\n"
            "&material name = 'lower', youngs_modulus = 40000.0, poissons_ratio = 0.2 /\n"
            "&material name = 'upper', youngs_modulus = 5000.0, poissons_ratio = 0.3 /\n"
            "&fracture name = 'crack', x = 0.1, 0.0, y = -2.05, 1.95, elements = 200, "
            "condition = 'traction', bc_s = 0.0, bc_n = -10.0 /\n")
    (k1_whole, _), (k1_zones, _) = zones_and_whole(tmp_path, text)
    assert np.max(np.abs(k1_zones / k1_whole - 1.0)) < 1e-5


@pytest.mark.parametrize("graded", [False, True], ids=["equal", "graded_3_to_1"])
def test_straight_crack_k(tmp_path, graded):
    """Straight crack of half-length 1 under syy = 1, sxy = 0.5, in 10, 20, 40 equal
    elements or elements graded 3:1 toward the tips: K within 5e-6 of sqrt(pi) and
    0.5 sqrt(pi) on 20 elements (the issue asks for 0.5 %; measured 9.5e-7 and 2.2e-6),
    order above 2.5 (measured 2.9-3.1)."""
    errors = []
    for n in (10, 20, 40):
        x = graded_x(n) if graded else np.linspace(-1.0, 1.0, n + 1)
        text = (HEAD + "&remote_stress sxx = 0.0, syy = 1.0, sxy = 0.5 /\n"
                + polyline(x, 0.0 * x))
        k1, k2, _ = solve_k(tmp_path, f"straight{n}", text)
        errors.append(max(np.max(np.abs(k1 / math.sqrt(math.pi) - 1.0)),
                          np.max(np.abs(k2 / (0.5 * math.sqrt(math.pi)) - 1.0))))
    assert errors[1] < 5e-6
    assert np.all(order_of(errors) > 2.5)


def test_tip_element_k_on_a_graded_crack_is_what_the_guide_says(tmp_path):
    """The tip element's K on 20 elements graded 3:1: 3.8 % high (docs/theory/tips.md
    #graded-tips), flagged graded; the re-solve flags nothing."""
    x = graded_x(20)
    text = HEAD + "&remote_stress sxx = 0.0, syy = 1.0, sxy = 0.0 /\n" + polyline(x, 0.0 * x)
    k1, _, method = solve_k(tmp_path, "tip_element", text, "tip_element")
    assert method.startswith("tip_element")
    assert k1 / math.sqrt(math.pi) - 1.0 == pytest.approx([0.038, 0.038], abs=1e-3)
    with h5py.File(tmp_path / "tip_element.h5", "r") as f:
        assert np.all(f["tips/graded"][()] == 1)
    solve_k(tmp_path, "re_solve", text)
    with h5py.File(tmp_path / "re_solve.h5", "r") as f:
        assert np.all(f["tips/graded"][()] == 0)


def scaled(example, factor):
    """input/<example> with every fracture's element count times `factor`, without its
    observation sets."""
    text = (REPO_ROOT / "input" / example).read_text()
    text = re.sub(r"elements\s*=\s*(\d+)",
                  lambda m: f"elements = {round(int(m.group(1)) * factor)}", text)
    return re.sub(r"&(grid|line|points)\b.*?/\s*\n", "", text, flags=re.DOTALL)


@pytest.mark.parametrize("example, tip, factors, tolerance", [
    ("joint_set_pressurized_crack.nml", 0, (0.5, 1.0, 2.0), 1e-3),
    ("en_echelon.nml", 2, (0.25, 0.5, 1.0), 1e-4),
    ("branching_fault.nml", 0, (0.5, 1.0, 2.0), 1e-4),
])
def test_example_k_converges(tmp_path, example, tip, factors, tolerance):
    """Models without a closed form (a pressurized crack among elastic joints, echelon and
    branching frictional faults): |K| of one tip on three meshes, each twice as fine as the
    one before, differs between the first two by less than `tolerance` (relative; measured
    1.9e-4, 2.8e-5, 3.5e-8), and the differences shrink at least fourfold (measured 6.9,
    6.5, 17) where the tip element's K on the joint set moves by 1.5 % between the
    example's mesh and one twice as fine. (The joint set's coarser meshes, a quarter of the
    example's, are not yet converged in the joints' states: K moves by 2e-4 twice.) The
    fractures are re-solved whole there (the convergence of the re-solve's elements); the
    default zones on the finest mesh give |K| within `tolerance` of that."""
    values = []
    for factor in factors:
        k1, k2, method = solve_k(tmp_path, f"level{factor}", scaled(example, factor),
                                 "higher_order", zone=WHOLE)
        assert method == "higher_order"
        values.append(math.hypot(k1[tip], k2[tip]))
    values = np.array(values)
    differences = np.abs(np.diff(values)) / values[-1]
    assert differences[0] < tolerance
    assert differences[1] < differences[0] / 4
    k1, k2, method = solve_k(tmp_path, "zones", scaled(example, factors[-1]), "higher_order")
    assert method == "higher_order"
    assert math.hypot(k1[tip], k2[tip]) / values[-1] - 1.0 == pytest.approx(0.0, abs=tolerance)


# The tip element's K on the arcs (k_method = 'tip_element'): the documented relative
# errors of K_I and K_II on the coarsest of three meshes (docs/theory/tips.md
# #curved-cracks-and-the-tip-element).
TIP_ELEMENT_ARCS = {90: ((50, 100, 200), 0.0351, 0.0250),
                    145: ((145, 290, 580), 0.0663, 0.0127)}


@pytest.fixture(scope="module", params=sorted(TIP_ELEMENT_ARCS), ids=lambda a: f"{a}deg")
def tip_element_arc(request, tmp_path_factory):
    half_angle = request.param
    folder = tmp_path_factory.mktemp("arc_tip_element")
    exact = arc_crack_k(math.radians(half_angle), RADIUS, TENSION)
    errors = []
    for n in TIP_ELEMENT_ARCS[half_angle][0]:
        k1, k2, _ = solve_k(folder, f"arc{n}", arc_text(math.radians(half_angle), n),
                            "tip_element")
        errors.append((k1 / exact[0] - 1.0, np.abs(k2) / exact[1] - 1.0))
    return half_angle, np.array(errors)


def test_tip_element_arc_error_as_documented(tip_element_arc):
    half_angle, errors = tip_element_arc
    _, k1_error, k2_error = TIP_ELEMENT_ARCS[half_angle]
    assert errors[0, 0] == pytest.approx([k1_error, k1_error], abs=5e-4)
    assert errors[0, 1] == pytest.approx([k2_error, k2_error], abs=5e-4)


@pytest.mark.parametrize("mode", [0, 1], ids=["K_I", "K_II"])
def test_tip_element_arc_error_falls_about_as_one_over_n_and_extrapolates(tip_element_arc,
                                                                          mode):
    """Observed order 0.6-0.9, below 1 and far from 2, and the Richardson value of the
    three meshes within 0.5 % of the closed form."""
    _, errors = tip_element_arc
    result = extrapolate(1.0 + errors[:, mode, 0])
    assert result.differences_shrink
    assert 0.45 < result.order < 1.05
    assert result.extrapolated == pytest.approx(1.0, abs=5e-3)
