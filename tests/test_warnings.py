"""The one-release allowance for parameters that 0.3.0 made keyword-only."""

import numpy as np
import pytest

from vdw_frames.paper.data import printed_eq8_moduli, printed_eq10_stiffness


def test_keyword_only_parameters_given_by_position_still_work_with_a_deprecation_warning():
    # Reference: eq. (10) = eq. (8) * A / h, computed here from eq. (8) directly.
    storage, loss = printed_eq8_moduli(2.0, 1.0, 1.0, 1.0, 1.0, 0.5)
    with pytest.warns(DeprecationWarning, match=r"printed_eq10_stiffness\(\): pass area, thickness by keyword"):
        old = printed_eq10_stiffness(2.0, 1.0, 1.0, 1.0, 1.0, 0.5, 500.0, 5.0)
    np.testing.assert_allclose(old, (storage * 100.0, loss * 100.0), rtol=1e-15)
    with pytest.warns(DeprecationWarning, match="pass area by keyword"):
        only_area = printed_eq10_stiffness(2.0, 1.0, 1.0, 1.0, 1.0, 0.5, 500.0, thickness=5.0)
    np.testing.assert_array_equal(only_area, old)


def test_a_parameter_given_by_position_and_by_keyword_or_one_too_many_is_refused():
    with pytest.raises(TypeError, match="multiple values for area"):
        printed_eq10_stiffness(2.0, 1.0, 1.0, 1.0, 1.0, 0.5, 500.0, area=5.0)
    with pytest.raises(TypeError):
        printed_eq10_stiffness(2.0, 1.0, 1.0, 1.0, 1.0, 0.5, 500.0, 5.0, 3.0)
