"""Observed order and Richardson extrapolation (ddc2d.richardson) on sequences whose
limit and order are known."""

import math

import pytest

from ddc2d.richardson import error_estimate, extrapolate


@pytest.mark.parametrize("order", [1.0, 2.0, 0.5])
def test_power_law_sequence_gives_its_order_and_limit(order):
    limit, coefficient = 7.76335, 0.3
    values = [limit + coefficient * (0.1 / 2**level) ** order for level in range(4)]
    result = extrapolate(values)
    assert result.order == pytest.approx(order, rel=1e-9)
    assert result.extrapolated == pytest.approx(limit, rel=1e-12)
    assert error_estimate(values[0], result) == pytest.approx(values[0] - limit, rel=1e-9)
    assert result.differences_shrink


def test_growing_differences_give_negative_order_and_no_limit():
    result = extrapolate([1.0, 1.1, 1.4])
    assert result.order == pytest.approx(math.log(1 / 3) / math.log(2))
    assert not result.differences_shrink
    assert result.extrapolated is None
    assert error_estimate(1.0, result) is None


def test_differences_of_both_signs_oscillate_and_give_no_limit():
    # |d_2| < |d_1|, order 0.97: a power law would extrapolate, but the sign changed.
    result = extrapolate([1.97522, 1.6527, 1.81705])
    assert result.oscillates and result.extrapolated is None
    assert error_estimate(1.97522, result) is None
    assert not extrapolate([1.0 + 0.5**k for k in range(3)]).oscillates


def test_shrinking_is_checked_over_every_level():
    # The last two differences shrink, the first two did not.
    result = extrapolate([1.0, 1.1, 1.4, 1.5])
    assert not result.differences_shrink and result.extrapolated is None
    assert result.order == pytest.approx(math.log(3) / math.log(2))
    # A sign change among the first levels counts too.
    assert extrapolate([1.0, 0.0, 0.5, 0.75, 0.875]).oscillates


def test_settled_quantity_is_its_own_limit():
    result = extrapolate([2.0, 2.0, 2.0])
    assert result.order is None and result.extrapolated == 2.0


def test_one_step_without_change_gives_no_order():
    assert extrapolate([2.0, 2.5, 2.5]).differences_shrink
    assert not extrapolate([2.0, 2.0, 2.5]).differences_shrink
    assert extrapolate([2.0, 2.0, 2.5]).order is None


def test_refinement_ratio_three():
    values = [1.0 + 3.0 ** (-2 * level) for level in range(3)]
    result = extrapolate(values, ratio=3.0)
    assert result.order == pytest.approx(2.0)
    assert result.extrapolated == pytest.approx(1.0)


def test_too_few_levels_or_bad_ratio_refused():
    with pytest.raises(ValueError):
        extrapolate([1.0, 2.0])
    with pytest.raises(ValueError):
        extrapolate([1.0, 2.0, 3.0], ratio=1.0)
