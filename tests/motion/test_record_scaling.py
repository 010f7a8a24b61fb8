"""Scaling a record: a factor that overflows the acceleration is refused, named by the factor; a target that
looks typed in g warns."""

import warnings

import numpy as np
import pytest

from vdw_frames.motion import G, GroundMotion


def test_a_factor_that_overflows_is_refused_and_named():
    motion = GroundMotion(np.array([0.0, 2.0e300, -1.0e300]), 0.01, "quake")
    refused = r"factor = 10000000000.0 makes the acceleration of .*quake.* overflow \(inf\)"
    with pytest.raises(ValueError, match=refused):
        motion.scaled(1.0e10)
    scaled = motion.scaled(0.5)  # finite factors that stay finite are exact
    np.testing.assert_array_equal(scaled.acceleration, [0.0, 1.0e300, -0.5e300])
    assert (scaled.dt, scaled.name) == (motion.dt, motion.name)


def test_a_target_below_1_mm_s2_warns_that_it_may_be_in_g():
    motion = GroundMotion(np.array([0.0, 3000.0, -1500.0]), 0.01, "quake")
    with pytest.warns(UserWarning, match=r"target PGA = 0.4 mm/s\^2 is below 1 mm/s\^2 .*did you mean 0.4 g = "
                                         r"3922.66 mm/s\^2"):
        scaled = motion.scaled_to_pga(0.4)
    assert scaled.pga == pytest.approx(0.4, rel=1e-15)  # the warning does not alter the request
    with pytest.warns(UserWarning, match=r"target PGA = 0.4 mm/s\^2"):
        assert motion.scale_factor_to_pga(0.4) == pytest.approx(0.4 / 3000.0, rel=1e-15)
    with pytest.warns(UserWarning, match=r"target spectral acceleration = 0.25 mm/s\^2 .* 0.25 g = 2451.66 mm/s\^2"):
        motion.scaled_to_spectral_acceleration(0.25, 0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # 1 mm/s^2 and above are taken as they are
        motion.scaled_to_pga(1.0)
        motion.scale_factor_to_spectral_acceleration(0.4 * G, 0.5)
