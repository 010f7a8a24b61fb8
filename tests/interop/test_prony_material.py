"""Prony series of FDMK walls as native OpenSees materials (vdw_frames.interop.opensees.prony_material): a
steady-state sine test of OpenSees's own Parallel/Maxwell materials against the series, and a frame built
from them against vdw_frames.simulate of the exact walls."""

from __future__ import annotations

import warnings

import numpy as np
import opensees_frame
import pytest
from builders import BOTH_BRANCHES, fractional_ten_story
from reference import peak_deviation
from shared_data import shared_record

from vdw_frames import FDMKDamper, simulate
from vdw_frames.interop.opensees import prony_material
from vdw_frames.motion import read_at2

pytestmark = pytest.mark.opensees

BAND = (0.1, 10.0)  # Hz: the band of a building's first few modes
WALL = FDMKDamper(**BOTH_BRANCHES, r=0.5, area=1.0e6, thickness=10.0)


def test_opensees_prony_material_has_the_series_complex_stiffness():
    # A steady-state sine test of the native material: zeroLength, imposed u = U sin(w t) after a smooth
    # start, the last cycles' force fitted to K' u + (K''/w) u'.  dt = tau_min / 20 (OpenSees's Maxwell is
    # second order in dt / tau).
    ops = opensees_frame.opensees()
    prony = WALL.prony(*BAND, tolerance=0.01)
    for frequency in (0.3, 1.0, 3.0):
        omega = 2.0 * np.pi * frequency
        dt = min(prony.relaxation_times.min() / 20.0, 1.0 / (200.0 * frequency))
        t = np.arange(round((12.0 / frequency + 3.0 * prony.relaxation_times.max()) / dt)) * dt
        ramp = np.clip(t * frequency / 2.0, 0.0, 1.0)  # two cycles to full amplitude
        u = 5.0 * ramp**2 * (3.0 - 2.0 * ramp) * np.sin(omega * t)
        ops_force = opensees_frame.imposed_force(ops, lambda ops: prony_material(ops, 1, prony), u, dt)
        last = t > t[-1] - 2.0 / frequency
        design = np.column_stack([np.sin(omega * t[last]), np.cos(omega * t[last])]) * 5.0
        storage, loss = np.linalg.lstsq(design, ops_force[last], rcond=None)[0]
        expected = prony.complex_stiffness(frequency)
        assert abs(storage + 1j * loss - expected) / abs(expected) < 1e-3, frequency  # measured 5e-6 - 3e-5


@pytest.mark.records
def test_native_prony_frame_matches_simulate_within_two_percent():
    # The 10-story frame of the bridge tests with fractional walls; OpenSees runs each wall as its Prony
    # series (1 % on 0.1-10 Hz), vdw_frames the exact walls; both at a quarter of the record's step, where
    # both have converged (measured 0.05 %; 1.3 % at the record's step, where OpenSees's Maxwell is coarse).
    record = read_at2(shared_record("elCentro.AT2"))
    building = fractional_ten_story()
    dt = record.dt / 4
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        expected = simulate(building, record, dt=dt)
    displacement, fits = opensees_frame.run_prony(building, record.acceleration_at(dt), dt, *BAND)
    assert peak_deviation(opensees_frame.drifts(displacement), expected.drift) < 0.02
    assert all(fit.error <= 0.01 for fit in fits.values())


def test_prony_material_needs_a_prony_series():
    with pytest.raises(ValueError, match="PronySeries"):
        prony_material(opensees_frame.opensees(), 1, WALL)
