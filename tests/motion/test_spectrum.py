"""Response spectra (vdw_frames.motion.spectrum): against scipy's lsim and a resonant steady state, limits,
shapes and the range of periods accepted."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from reference import sdof_peak_lsim
from scipy import signal
from shared_data import shared_record

from vdw_frames import motion as gm
from vdw_frames.motion import GroundMotion, default_record


@pytest.mark.records
def test_response_spectrum_against_lsim():
    motion = gm.read_at2(shared_record("IELC180.AT2"))
    periods = np.array([0.1, 0.3, 1.0, 3.0])
    for damping_ratio in (0.0, 0.05, 0.2):
        spectrum = motion.spectrum(periods, damping_ratio)
        reference = [sdof_peak_lsim(motion, period, damping_ratio) for period in periods]
        np.testing.assert_allclose(spectrum, reference, rtol=1e-8)


def test_response_spectrum_resonant_harmonic_steady_state():
    # a_g = A sin(w t) at w = w_n: the steady response u = A / (2 zeta w^2) cos(w t) peaks at the
    # samples (T a multiple of dt); the linearly interpolated input has gain sinc^2(w dt / 2) at w.
    dt, period, zeta, amplitude = 0.01, 1.0, 0.05, 1000.0
    omega = 2.0 * math.pi / period
    time = np.arange(6001) * dt  # 60 s: the transient has decayed by exp(-zeta w 60) ~ 6e-9
    motion = GroundMotion(amplitude * np.sin(omega * time), dt)
    expected = amplitude / (2.0 * zeta) * np.sinc(omega * dt / (2.0 * math.pi)) ** 2
    assert float(motion.spectrum(period, zeta)) == pytest.approx(expected, rel=1e-6)


@pytest.mark.records
def test_response_spectrum_limits_and_shape():
    motion = gm.read_at2(shared_record("elCentro.AT2"))
    spectrum = motion.spectrum([[0.0, 1e-4], [0.5, 1.0]])
    assert spectrum.shape == (2, 2)
    assert spectrum[0, 0] == motion.pga
    assert spectrum[0, 1] == pytest.approx(motion.pga, rel=1e-3)  # rigid oscillator follows the ground
    assert float(motion.spectrum(2.0)) == pytest.approx(sdof_peak_lsim(motion, 2.0, 0.05), rel=1e-8)
    for periods, damping_ratio, match in [([-1.0], 0.05, "periods must be >= 0"),
                                          ([np.nan], 0.05, "periods must be finite"),
                                          ([1.0], 1.0, r"damping_ratio must lie in \[0, 1\), got 1\.0"),
                                          ([1.0], -0.1, "damping_ratio must lie in")]:
        with pytest.raises(ValueError, match=match):
            motion.spectrum(periods, damping_ratio)


def test_periods_outside_the_accepted_range_are_refused_and_its_ends_are_exact():
    motion = default_record()
    for period in (1e-160, 1e300, -0.0 + 1e-9):
        with pytest.raises(ValueError, match=re.escape(f"period {period!r} s is outside the range")):
            motion.spectrum(period)
    # The ends of the accepted range (1e-6 and 1e5 record steps) against scipy's exact linear simulation.
    rigid, longest = 1e-6 * motion.dt, 1e5 * motion.dt
    assert float(motion.spectrum(rigid)) == pytest.approx(motion.pga, rel=1e-8)
    omega = 2 * np.pi / longest
    system = signal.StateSpace([[0, 1], [-omega**2, -2 * 0.05 * omega]], [[0], [-1]], [[1, 0]], [[0]])
    _, u, _ = signal.lsim(system, motion.acceleration, motion.time)
    assert float(motion.spectrum(longest)) == pytest.approx(omega**2 * np.abs(u).max(), rel=1e-6)
    assert float(motion.spectrum(0.0)) == motion.pga
