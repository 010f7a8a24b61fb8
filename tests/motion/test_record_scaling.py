"""Scaling a record: a factor that overflows the acceleration is refused, named by the factor."""

import numpy as np
import pytest

from vdw_frames.motion import GroundMotion


def test_a_factor_that_overflows_is_refused_and_named():
    motion = GroundMotion(np.array([0.0, 2.0e300, -1.0e300]), 0.01, "quake")
    refused = r"factor = 10000000000.0 makes the acceleration of .*quake.* overflow \(inf\)"
    with pytest.raises(ValueError, match=refused):
        motion.scaled(1.0e10)
    scaled = motion.scaled(0.5)  # finite factors that stay finite are exact
    np.testing.assert_array_equal(scaled.acceleration, [0.0, 1.0e300, -0.5e300])
    assert (scaled.dt, scaled.name) == (motion.dt, motion.name)
