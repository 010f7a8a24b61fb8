"""EnergyHistory.shares: the balance's terms over the input energy, against energy conservation.

References: a damped linear frame left to vibrate freely ends at rest, so all the input has gone into its
inherent damping (the energy still in motion decays as exp(-2 zeta omega_1 t): below 1e-12 of it after 60 s
at zeta = 5 %, T_1 = 0.35 s); with walls and dampers beside the damping, what is still stored at rest is the
frame's residual strain only, and the terms add up to 1 within the balance's tolerance (1e-9 of the input here).
"""

from __future__ import annotations

import numpy as np
import pytest

import vdw_frames as vdw
from vdw_frames.motion import G, GroundMotion, default_record

WALL = vdw.FDMKDamper(G1=0.0, G2=3.0, eta1=0.3, eta2=2.0, r=0.5, area=2.0e5, thickness=10.0)


def _short_record() -> GroundMotion:
    record = default_record()
    return GroundMotion(record.acceleration[:600] * (0.3 * G / record.pga), record.dt)


def test_a_linear_frame_at_rest_has_put_all_its_input_into_its_damping():
    building = vdw.ShearBuilding([300.0, 250.0], [2.0e5, 1.5e5])
    shares = vdw.simulate(building, _short_record(), free_vibration=60.0).energy.shares()
    assert shares["inherent damping"] == pytest.approx(1.0, abs=1e-9)
    assert shares["frame strain and motion"] == pytest.approx(0.0, abs=1e-9)
    for name in ("walls", "other devices", "story yielding", "gravity (P-Delta)"):
        assert shares[name] == pytest.approx(0.0, abs=1e-12)  # (yielding: the rounding of F^2 / 2k against its work)


def test_the_shares_of_walls_dampers_damping_and_yielding_add_up_to_one():
    weight = np.array([300.0, 250.0]) * G
    building = vdw.ShearBuilding([300.0, 250.0], [2.0e5, 1.5e5], story_heights=[3500.0, 3500.0],
                                 gravity_loads=np.cumsum(weight[::-1])[::-1],
                                 hysteresis=[vdw.Bilinear(2.0e5, 0.02), vdw.Bilinear(1.5e5, 0.02)],
                                 devices={1: [WALL], 2: [vdw.FluidViscousDamper(C=150.0, alpha=1.0)]})
    result = vdw.simulate(building, _short_record().scaled(3.0), free_vibration=60.0)
    shares = result.energy.shares()
    assert result.peak_ductility.max() > 1.5  # the stories yielded
    assert shares["walls"] > 0.05 and shares["other devices"] > 0.05 and shares["story yielding"] > 0.05
    assert shares["gravity (P-Delta)"] < 0.0  # gravity does work as the frame sways
    assert sum(shares.values()) == pytest.approx(1.0, abs=1e-9)


def test_no_input_no_shares():
    building = vdw.ShearBuilding([300.0], [2.0e5])
    assert vdw.simulate(building, GroundMotion(np.zeros(50), 0.01)).energy.shares() == {}
