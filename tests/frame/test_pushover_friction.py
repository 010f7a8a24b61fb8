"""Pushover with friction dampers: elastic-perfectly-plastic springs in parallel with the stories."""

from __future__ import annotations

import numpy as np
import pytest

import vdw_frames as vdw
from vdw_frames.frame.pushover import pushover


def test_one_story_with_a_friction_damper_is_the_sum_of_the_two_laws():
    """One story, Bilinear (k, F_y, b) in parallel with a friction damper (k_f, F_s, magnification f): its shear
    at drift d under monotonic loading is F_y + b k (d - F_y / k) past yield (k d before) plus f min(f k_f d, F_s),
    written here by hand; a fluid viscous damper on the same story adds nothing (no static force)."""
    k, fy, b, kf, fs, f = 1.0e5, 3.0e5, 0.05, 4.0e4, 1.0e5, 0.8
    building = vdw.ShearBuilding([100.0], [k], story_heights=[3000.0], hysteresis=[vdw.Bilinear(fy, b)],
                                 devices={1: [vdw.FrictionDamper(fs, kf, magnification=f),
                                              vdw.FluidViscousDamper(500.0, 0.5, stiffness=1e5)]})
    result = pushover(building, [1.0], 0.02, steps=400)
    d = result.roof_displacement
    frame = np.where(d < fy / k, k * d, fy + b * k * (d - fy / k))
    friction = f * np.minimum(f * kf * d, fs)
    np.testing.assert_allclose(result.base_shear, frame + friction, rtol=1e-9, atol=1e-6)
    assert result.max_base_shear == pytest.approx(fy + b * k * (d[-1] - fy / k) + f * fs, rel=1e-9)
    # the elastic static model has the damper's stiffness before it slips: T1 = 2 pi sqrt(m / (k + f^2 k_f))
    assert result.elastic_period == pytest.approx(2 * np.pi * np.sqrt(100.0 / (k + f**2 * kf)), rel=1e-12)
