"""The tie rule at every place a script picks "the largest", "the first" or a side: values
within a relative 1e-9 count as equal and the lowest index wins (reader.index_of_extreme), so
that no choice depends on last-bit rounding.

Each place is tested with an exact tie (symmetric data, equal in binary), with a near tie
(the later value ahead by a relative 1e-10, which must still give the lowest index) and
with a difference beyond the tolerance (a relative 1e-8 or more), which must not be
treated as a tie.
"""

import numpy as np
import pytest

from ddc2d import compare_twodd
from ddc2d.plot import data as plot_data

EXACT, NEAR, BEYOND = 0.0, 1e-10, 1e-8


@pytest.fixture(scope="module")
def compare_module():
    """compare-twodd as a module."""
    return compare_twodd


# ------------------------------------------------------------------ ddc2d-plot: history


def symmetric_history(ahead=EXACT):
    """A loading history of 6 elements whose slip profile is symmetric: elements 3 and 4
    (1-based) slip most, element 4 ahead by the relative amount `ahead`."""
    profile = np.array([1.0, 2.0, 3.0, 3.0 * (1.0 + ahead), 2.0, 1.0]) * 1e-4
    ramp = np.array([0.0, 0.5, 1.0, 1.0, 0.2])
    return {"loads": {"sxy": 10.0 * ramp}, "ds": -np.outer(ramp, profile),
            "dn": np.zeros((5, 6)), "state": np.ones((5, 6), dtype=int),
            "leg_steps": np.array([2, 2])}


@pytest.mark.parametrize("ahead, element", [(EXACT, 2), (NEAR, 2), (BEYOND, 3)])
def test_history_element_of_largest_slip(ahead, element):
    elements, steps = plot_data.history_choices(symmetric_history(ahead))
    assert elements == [element]  # 0-based: element 3, or 4 beyond the tolerance
    assert steps == [0, 2, 4]


@pytest.mark.parametrize("ahead, name", [(EXACT, "sxx"), (NEAR, "sxx"), (BEYOND, "sxy")])
def test_history_load_parameter_of_largest_range(ahead, name):
    # sxx and sxy both range over 10 (in file order, sxx first); sxy ahead by `ahead`.
    history = symmetric_history()
    history["loads"] = {"sxx": np.array([-5.0, 0.0, 5.0, 0.0, -5.0]),
                        "sxy": np.array([0.0, 5.0, 10.0 * (1.0 + ahead), 5.0, 0.0])}
    assert plot_data.history_parameter(history)[0] == name


# ------------------------------------------------------------------ ddc2d-plot: overview


@pytest.mark.parametrize("ahead, axis", [(EXACT, "x"), (NEAR, "x"), (BEYOND, "y")])
def test_overview_axis_of_a_fault_at_45_degrees(ahead, axis):
    # Two elements from (0, 0) to (1, 1 + ahead): as long in x as in y but for `ahead`.
    top = 1.0 + ahead
    elements = {"x_begin": np.array([0.0, 0.5]), "x_end": np.array([0.5, 1.0]),
                "y_begin": np.array([0.0, 0.5 * top]), "y_end": np.array([0.5 * top, top])}
    assert plot_data.overview_axis(elements) == axis


# ------------------------------------------------------------------ ddc2d-plot: receivers


def test_receiver_on_a_principal_plane_is_right_lateral():
    # Principal stresses along x and y: no shear on the vertical plane, but cos(90 deg)
    # rounds to 6e-17 and the resolved shear to -7.7e-15.
    remote = (-50.0, -175.0, 0.0)
    tau, _ = plot_data.resolved_traction(*remote, 90.0)
    assert tau < 0.0 and abs(tau) < 1e-13
    assert plot_data.Receiver(remote, 90.0).sense == "right"
    assert plot_data.Receiver((-100.0, -100.0, 0.0), 30.0).sense == "right"  # exact zero


@pytest.mark.parametrize("shear, sense", [(-NEAR * 175.0, "right"),
                                          (-BEYOND * 175.0, "left"), (1e-3, "right")])
def test_receiver_sense_near_zero_shear(shear, sense):
    # On a plane along x the remote shear is sxy; the largest component is 175.
    assert plot_data.Receiver((-50.0, -175.0, shear), 0.0).sense == sense


# ------------------------------------------------------------------ ddc2d-plot: colour limits


@pytest.mark.parametrize("below, symmetric", [(EXACT, False), (NEAR, False), (BEYOND, True)])
def test_colour_limits_when_a_percentile_meets_the_remote_value(below,
                                                                symmetric):
    # Half of the map sits at the remote value -112.5 (or `below` it, relative), the rest
    # above: only a real excursion below makes the limits symmetric about the remote value.
    centre = -112.5
    values = np.ma.masked_array(np.concatenate([
        np.full(50, centre * (1.0 + below)), centre + np.linspace(0.0, 10.0, 51)]))
    low, high = plot_data.default_clim(values, "mean", centre=centre)
    if symmetric:
        assert low + high == pytest.approx(2.0 * centre) and high > centre + 9.0
    else:
        assert low == pytest.approx(centre, rel=1e-8) and high > centre + 9.0


@pytest.mark.parametrize("spread, constant", [(EXACT, True), (NEAR, True), (BEYOND, False)])
def test_colour_limits_of_a_field_constant_but_for_rounding(spread, constant):
    values = np.ma.masked_array(5.0 * (1.0 + spread * np.linspace(0.0, 1.0, 101)))
    low, high = plot_data.default_clim(values, "max_shear")
    if constant:
        assert (low, high) == pytest.approx((2.5, 7.5), rel=1e-8)
    else:
        assert 5.0 <= low < high <= 5.0 * (1.0 + spread)


# ------------------------------------------------------------------ compare-twodd


@pytest.mark.parametrize("ahead, best", [(EXACT, 0), (NEAR, 0), (BEYOND, 1)])
def test_nearest_point_of_points_equally_near(compare_module, ahead, best):
    # Points left and right of (0, 0), the left one nearer by `ahead` (relative).
    points = np.array([[1.0, 0.0, 7.0], [-(1.0 - ahead), 0.0, 8.0], [0.0, 2.0, 9.0]])
    index, distance = compare_module.nearest_point(points, 0.0, 0.0)
    assert index == best
    assert distance == pytest.approx(1.0, rel=1e-7)


def test_nearest_point_of_an_exact_match(compare_module):
    points = np.array([[0.5, 0.5], [0.0, 0.0], [0.0, 0.0]])
    assert compare_module.nearest_point(points, 0.0, 0.0) == (1, 0.0)


@pytest.mark.parametrize("ahead, worst", [(EXACT, 1), (NEAR, 1), (BEYOND, 3)])
def test_worst_row(compare_module, ahead, worst):
    # Rows 1 and 3 exceed their tolerance by the same amount, row 3 ahead by `ahead`.
    diff = np.array([1.0, 3.0, 2.0, 3.0 * (1.0 + ahead)]) * 1e-3
    tol = np.full(4, 1e-3)
    assert compare_module.worst_row(diff, tol) == worst


def test_worst_row_counts_a_nan_as_the_worst(compare_module):
    diff = np.array([5.0, np.nan, 1.0, np.nan])
    assert compare_module.worst_row(diff, np.ones(4)) == 1
