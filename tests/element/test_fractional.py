"""The discretisations of D^r (vdw_frames.element.fractional): their arguments are refused by name."""

import math

import numpy as np
import pytest

from vdw_frames.element.fractional import METHODS, get_method


@pytest.mark.parametrize("method", sorted(METHODS))
@pytest.mark.parametrize("count", [2.7, "5", True, math.inf, math.nan, 0, -1, None])
def test_weights_take_only_whole_counts(method, count):
    with pytest.raises(ValueError, match="count must be a whole number >= 1"):
        get_method(method).weights(0.5, count)


@pytest.mark.parametrize("method", sorted(METHODS))
def test_integral_counts_of_any_integer_type_give_the_same_weights(method):
    scheme = get_method(method)
    np.testing.assert_array_equal(scheme.weights(0.5, 3.0), scheme.weights(0.5, np.int64(3)))
    assert scheme.weights(0.5, 3).size == 3


def test_a_count_beyond_the_memory_limit_is_refused_before_allocating():
    with pytest.raises(ValueError, match=r"weights\(count = 1000000000000\) needs"):
        get_method("trapezoidal").weights(0.5, 10**12)


@pytest.mark.parametrize("dt, match", [(0.0, "dt must be > 0"), (-0.01, "dt must be > 0"),
                                       (math.nan, "dt must be finite"), (1e-300, "outside the range"),
                                       (1e300, "outside the range")])
def test_symbol_and_weights_refuse_bad_steps(dt, match):
    scheme = get_method("damped")
    with pytest.raises(ValueError, match=match):
        scheme.symbol(1.0, dt)
    with pytest.raises(ValueError, match=match):
        scheme.weights(0.5, 3, dt)


def test_symbol_refuses_non_finite_frequencies():
    with pytest.raises(ValueError, match="omega must be finite"):
        get_method("bdf2").symbol([1.0, math.inf], 0.01)
