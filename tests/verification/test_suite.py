"""ASCE 7-16 Sec. 16.2 suite selection and scaling: the 90 % rule at every period of the range, minimal factors,
and the period range against a state-space eigen-solution of a frame with r = 1 walls written here."""

import numpy as np
import pytest
from scipy.linalg import eig, eigh
from verification_cases import three_story

from vdw_frames import GroundMotion
from vdw_frames.motion import response_spectrum
from vdw_frames.verification import Site
from vdw_frames.verification.suite import period_range, scaled_suite

SITE = Site(1.5, 0.9, 8.0)


def state_space_periods(building):
    """Periods 2 pi / |s| of the oscillatory eigenvalues of x' = A x, x = [u, v, q]: M v' = -K u - C v - T^T f,
    f = (A/t)(G1 d + eta1 d') + q per story, q' = -(G2/eta2) q + (A/t) G2 d' (Maxwell branch), d = T u."""
    n = building.stories
    m, k, c = building.mass_matrix, building.stiffness_matrix, building.damping_matrix
    t = np.eye(n) - np.eye(n, k=-1)  # drifts d = T u
    walls = [wall for story in range(1, n + 1) for wall in building.walls[story]]
    kw = np.diag([w.area / w.thickness * w.G1 for w in walls])
    cw = np.diag([w.area / w.thickness * w.eta1 for w in walls])
    g2 = np.diag([w.area / w.thickness * w.G2 for w in walls])
    relax = np.diag([w.G2 / w.eta2 for w in walls])
    minv = np.linalg.inv(m)
    a = np.zeros((3 * n, 3 * n))
    a[:n, n:2 * n] = np.eye(n)
    a[n:2 * n, :n] = -minv @ (k + t.T @ kw @ t)
    a[n:2 * n, n:2 * n] = -minv @ (c + t.T @ cw @ t)
    a[n:2 * n, 2 * n:] = -minv @ t.T
    a[2 * n:, n:2 * n] = g2 @ t
    a[2 * n:, 2 * n:] = -relax
    s = eig(a, right=False)
    s = s[s.imag > 1e-9]
    return np.sort(2 * np.pi / np.abs(s))[::-1]


def test_period_range_from_state_space_periods(building):
    periods = state_space_periods(building)
    assert periods.size == 3
    bounds = period_range(building)
    np.testing.assert_allclose(bounds.periods[:3], periods, rtol=1e-8)
    # the 90 %-mass mode from the bare frame's real modes, computed here
    _w2, phi = eigh(building.stiffness_matrix, building.mass_matrix)
    masses = np.array(building.masses)
    effective = (phi.T @ masses) ** 2 / np.einsum("ij,ij->j", phi, masses[:, None] * phi)
    cumulative = np.cumsum(effective) / masses.sum()
    mode = int(np.argmax(cumulative >= 0.9)) + 1
    assert bounds.mass_mode == mode
    assert bounds.upper == pytest.approx(2 * periods[0], rel=1e-8)
    assert bounds.lower == pytest.approx(min(0.2 * periods[0], periods[mode - 1]), rel=1e-8)
    # the walls matter: the bare frame's T_1 is different
    assert abs(periods[0] - building.periods[0]) > 0.01 * periods[0]


def test_scaled_suite_meets_90_percent_with_minimal_factors(building, records):
    suite = scaled_suite(building, SITE, records, one_per_event=False)
    assert len(suite.motions) == 11 and suite.factors.shape == (11,)
    bounds = period_range(building)
    periods = suite.periods
    assert periods[0] == pytest.approx(bounds.lower) and periods[-1] == pytest.approx(bounds.upper)
    assert np.all(periods[1:] / periods[:-1] <= 1.01 + 1e-12)
    t0, ts = 0.2 * 0.9 / 1.5, 0.9 / 1.5  # the MCE_R branches below T_L = 8 s, written out
    target = np.array([1.5 * (0.4 + 0.6 * t / t0) if t < t0 else 1.5 if t <= ts else 0.9 / t
                       for t in periods]) * 9806.65
    spectra = np.array([response_spectrum(m.scaled(f).acceleration, m.dt, periods, 0.05)
                        for m, f in zip(suite.motions, suite.factors, strict=True)])
    mean = spectra.mean(axis=0)
    assert np.all(mean >= 0.9 * target * (1 - 1e-9))
    assert np.min(mean / target) == pytest.approx(0.9, rel=1e-9)
    for j in range(11):  # any one factor 1 % lower breaks the rule somewhere in the range
        lowered = spectra.copy()
        lowered[j] *= 0.99
        assert np.any(lowered.mean(axis=0) < 0.9 * target)


def test_selection_takes_the_smallest_shape_misfits(building, records):
    suite = scaled_suite(building, SITE, records, one_per_event=False)
    periods = suite.periods
    target = SITE.spectrum(periods) * 9806.65
    misfits = []
    for motion in records:
        residual = np.log(response_spectrum(motion.acceleration, motion.dt, periods) / target)
        misfits.append(np.std(residual))  # rms about the best log-fit
    expected = sorted(np.argsort(misfits)[:11].tolist())
    chosen = sorted(records.index(m) for m in suite.motions)
    assert chosen == expected
    np.testing.assert_allclose(np.sort(suite.misfits), np.sort(misfits)[:11], rtol=1e-9)


def test_a_user_suite_of_eleven_keeps_every_record(building, records):
    suite = scaled_suite(building, SITE, records[:11])
    assert set(suite.motions) == set(records[:11])


def test_bad_suites_are_refused(building, records):
    with pytest.raises(ValueError, match="10 records given"):
        scaled_suite(building, SITE, records[:10])
    with pytest.raises(ValueError, match="count = 10"):
        scaled_suite(building, SITE, records, count=10)
    short = GroundMotion(records[0].acceleration[:150], 0.01, name="short one")
    with pytest.raises(ValueError, match=r"'short one' lasts 1\.49 s.*too short for the period range"):
        scaled_suite(building, SITE, [short, *records[:11]])
    with pytest.raises(ValueError, match="no story heights"):
        scaled_suite(three_story(heights=False), SITE, records)
