"""Ground motions (vdw_frames.motion.record): properties and checks, scaling to a PGA or a spectral acceleration
(against the records' own values and scipy's lsim), resampling by linear interpolation."""

from __future__ import annotations

import numpy as np
import pytest
from reference import at2_values, sdof_peak_lsim
from shared_data import shared_record

from vdw_frames import motion as gm
from vdw_frames.motion import G, GroundMotion


def test_ground_motion_properties_and_validation():
    motion = GroundMotion([0.0, 3.0, -4.0, 1.0], 0.02, name="m")
    np.testing.assert_allclose(motion.time, [0.0, 0.02, 0.04, 0.06], rtol=1e-15)
    assert motion.pga == 4.0
    assert motion.duration == pytest.approx(0.06, rel=1e-15)
    with pytest.raises(ValueError):
        motion.acceleration[0] = 1.0  # read-only
    source = np.array([1.0, 2.0])
    copy = GroundMotion(source, 0.1)
    source[0] = 99.0
    assert copy.acceleration[0] == 1.0
    for bad, match in [(dict(acceleration=[1.0, np.nan]), r"acceleration must be finite, got .*nan.* at index 1"),
                       (dict(acceleration=[]), "at least 2 samples, got 0"),
                       (dict(acceleration=[3.0]), "at least 2 samples, got 1"),
                       (dict(acceleration=[1.0, 2.0 + 1.0j]), "acceleration must be real"),
                       (dict(acceleration=[[1.0]]), "1-dimensional"),
                       (dict(dt=0.0), r"dt must be > 0, got 0\.0"),
                       (dict(dt=np.inf), "dt must be finite"),
                       (dict(dt="x"), "dt must be a real number")]:
        arguments = dict(acceleration=[1.0, 2.0], dt=0.01) | bad
        with pytest.raises(ValueError, match=match):
            GroundMotion(**arguments)


@pytest.mark.records
def test_scaling_to_pga():
    motion = gm.read_at2(shared_record("RIO270.AT2"))
    target = 0.4 * G
    scaled = motion.scaled_to_pga(target)
    assert scaled.pga == pytest.approx(target, rel=1e-12)
    assert scaled.name == motion.name and scaled.dt == motion.dt
    factor = motion.scale_factor_to_pga(target)
    np.testing.assert_allclose(scaled.acceleration, motion.acceleration * factor, rtol=1e-15)
    assert factor == pytest.approx(0.4 / (max(abs(v) for v in at2_values(shared_record("RIO270.AT2")))),
                                   rel=1e-12)
    np.testing.assert_array_equal(motion.scaled(-2.0).acceleration, -2.0 * motion.acceleration)
    with pytest.raises(ValueError, match="target PGA must be > 0"):
        motion.scaled_to_pga(0.0)
    with pytest.raises(ValueError, match="factor must be finite"):
        motion.scaled(np.nan)
    with pytest.raises(ValueError, match="its PGA is 0"):
        GroundMotion(np.zeros(3), 0.01, "quiet").scaled_to_pga(G)


@pytest.mark.records
def test_scaling_to_spectral_acceleration():
    motion = gm.read_at2(shared_record("ARL360.at2"))
    target, period = 0.8 * G, 0.7
    scaled = motion.scaled_to_spectral_acceleration(target, period, damping_ratio=0.03)
    assert float(scaled.spectrum(period, 0.03)) == pytest.approx(target, rel=1e-12)
    factor = motion.scale_factor_to_spectral_acceleration(target, period, 0.03)
    assert factor == pytest.approx(target / sdof_peak_lsim(motion, period, 0.03), rel=1e-8)
    assert motion.scale_factor_to_spectral_acceleration(G, 0.0) == pytest.approx(G / motion.pga, rel=1e-15)


def test_resampling_is_linear_interpolation():
    ramp = GroundMotion(3.0 + 7.0 * np.arange(11), 0.02, "ramp")
    fine = ramp.resampled(0.005)
    assert fine.acceleration.size == 41 and fine.dt == 0.005 and fine.name == "ramp"
    np.testing.assert_allclose(fine.acceleration, 3.0 + 7.0 * fine.time / 0.02, rtol=1e-14)
    np.testing.assert_allclose(ramp.acceleration_at(0.02 / 3), 3.0 + 7.0 * np.arange(31) / 3, rtol=1e-14)
    wiggle = GroundMotion([0.0, 4.0, -2.0], 0.1)
    np.testing.assert_allclose(wiggle.acceleration_at(0.025), [0, 1, 2, 3, 4, 2.5, 1, -0.5, -2], atol=1e-14)
    np.testing.assert_array_equal(wiggle.acceleration_at(0.1 * (1 + 1e-10)), wiggle.acceleration)


@pytest.mark.parametrize("dt, problem", [
    (0.015, "does not divide"), (0.0066, "does not divide"), (0.02 / 3 * (1 + 1e-5), "does not divide"),
    (0.04, "is larger than"), (0.0, "dt must be > 0"), (np.nan, "dt must be finite"),
])
def test_resampling_rejects(dt, problem):
    motion = GroundMotion([0.0, 1.0, 0.0], 0.02)
    with pytest.raises(ValueError, match=problem) as error:
        motion.resampled(dt)
    if "divide" in problem or "larger" in problem:
        assert repr(dt) in str(error.value) and "0.02" in str(error.value)
