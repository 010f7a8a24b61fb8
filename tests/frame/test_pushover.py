"""Pushover (FEMA P695 Sec. 6.3) against closed-form results for shear buildings."""

from __future__ import annotations

import math

import numpy as np
import pytest

import vdw_frames as vdw
from vdw_frames.frame.pushover import pushover

G = vdw.G
GOLDEN = (1.0 + math.sqrt(5.0)) / 2.0


def two_story(strengths=(3.0e5, 1.6e5), hardening=0.0, gravity=None, walls=None, k=1.0e5, m=100.0, h=3000.0):
    return vdw.ShearBuilding([m, m], [k, k], story_heights=[h, h],
                             hysteresis=[vdw.Bilinear(f, hardening) for f in strengths],
                             gravity_loads=gravity, walls=walls)


def test_elastic_perfectly_plastic_without_p_delta_closed_form():
    """Equal masses m and stiffnesses k: phi_1 = (1, golden ratio), omega_1^2 = (3 - sqrt 5) k / (2 m).  Modal loads
    (1, phi)/(1 + phi): story 2 carries phi/(1 + phi) of V, so V_max = min(F_y1, F_y2 (1 + phi)/phi)."""
    k, m = 1.0e5, 100.0
    building = two_story(k=k, m=m)
    result = pushover(building, "modal", 0.02)
    share = GOLDEN / (1.0 + GOLDEN)
    np.testing.assert_allclose(result.pattern, [1.0 - share, share], rtol=1e-12)
    v_max = min(3.0e5, 1.6e5 / share)
    assert result.max_base_shear == pytest.approx(v_max, rel=1e-12)
    # eq. (6-8) and (6-7) in closed form: C0 = phi (1 + phi) / (1 + phi^2), T1 from omega_1.
    c0 = GOLDEN * (1.0 + GOLDEN) / (1.0 + GOLDEN**2)
    omega2 = (3.0 - math.sqrt(5.0)) * k / (2.0 * m)
    assert result.c0 == pytest.approx(c0, rel=1e-12)
    assert result.period == pytest.approx(2.0 * math.pi / math.sqrt(omega2), rel=1e-12)
    delta_y = c0 * v_max / (2.0 * m * G) * G / (4.0 * math.pi**2) * (2.0 * math.pi) ** 2 / omega2
    assert result.yield_roof_displacement == pytest.approx(delta_y, rel=1e-12)
    assert result.weight == pytest.approx(2.0 * m * G)
    # Elastic branch: U = V (1/k + share/k); then a plateau at V_max with no strength loss: no delta_u.
    elastic = result.base_shear < v_max * (1.0 - 1e-9)
    np.testing.assert_allclose(result.roof_displacement[elastic], result.base_shear[elastic] * (1.0 + share) / k,
                               rtol=1e-9, atol=1e-9)
    assert np.all(result.base_shear[~elastic] == pytest.approx(v_max, rel=1e-10))
    assert result.ultimate_roof_displacement is None and result.period_based_ductility is None
    assert result.roof_displacement[-1] == pytest.approx(0.02 * 6000.0)


def test_p_delta_post_peak_slope_and_the_20_percent_strength_loss_point():
    """Story 1 yields first (hardening b) and carries P: its tangent past the peak is b k - P/h; the roof moves
    dU = dV (1 / (b k - P1/h) + share_2 / (k - P2/h)).  The peak is at story 1's yield: V_max = F_y (1 - P1/(h k)),
    and delta_u follows from the straight descending branch."""
    k, h, b = 1.0e5, 3000.0, 0.02
    p1, p2 = 2.0 * 100.0 * G * 10.0, 100.0 * G * 10.0  # heavy floors: a clearly negative post-yield tangent
    building = two_story(strengths=(1.0e5, 2.0e5), hardening=b, gravity=[p1, p2])
    result = pushover(building, [1.0, 1.0], 0.03, steps=600)
    share = 0.5
    k1, k2 = k - p1 / h, k - p2 / h
    tangent = b * k - p1 / h
    assert tangent < 0
    v_max = 1.0e5 * (1.0 - p1 / (h * k))
    assert result.max_base_shear == pytest.approx(v_max, rel=1e-9)
    peak_roof = v_max * (1.0 / k1 + share / k2)
    assert result.peak_roof_displacement == pytest.approx(peak_roof, rel=1e-9)
    slope = 1.0 / (1.0 / tangent + share / k2)
    after = (result.roof_displacement > peak_roof * 1.001) & (result.base_shear > 0)
    slopes = np.diff(result.base_shear[after]) / np.diff(result.roof_displacement[after])
    np.testing.assert_allclose(slopes, slope, rtol=1e-8)
    # In story 1's own terms: dV/dd_1 = b k - P/h.
    drift = result.story_drift[after, 0]
    np.testing.assert_allclose(np.diff(result.base_shear[after]) / np.diff(drift), tangent, rtol=1e-8)
    delta_u = peak_roof + 0.2 * v_max / -slope
    assert result.ultimate_roof_displacement == pytest.approx(delta_u, rel=0.005)
    assert result.period_based_ductility == pytest.approx(delta_u / result.yield_roof_displacement, rel=0.005)


def test_goes_past_the_peak_until_no_strength_is_left():
    building = two_story(strengths=(1.0e5, 2.0e5), gravity=[2.0e7, 1.0e7])
    result = pushover(building, "triangular", 0.5)
    assert result.end == "no strength left"
    assert result.base_shear[-1] <= 0.0 < result.base_shear[-2]
    assert result.roof_drift_ratio[-1] < 0.5
    np.testing.assert_allclose(result.pattern, [1 / 3, 2 / 3])  # m h_x: floors at h and 2 h


def test_walls_take_their_static_stiffness():
    """Maxwell-only walls (G1 = 0) add nothing at zero frequency; a Kelvin branch adds G1 A / h, in series with
    the support for a SupportedDamper: the elastic roof flexibility is sum share_j / (k_j + k_w,j)."""
    bare = pushover(two_story(), [1.0, 1.0], 0.005)
    maxwell = vdw.paper.fitted(300, area=0.5e6, thickness=10.0)
    assert maxwell.G1 == 0.0
    same = pushover(two_story(walls={1: maxwell, 2: maxwell}), [1.0, 1.0], 0.005)
    np.testing.assert_array_equal(same.base_shear, bare.base_shear)
    kelvin = vdw.FDMKDamper(G1=0.2, G2=2.0, eta1=0.1, eta2=1.0, r=0.5, area=1.0e5, thickness=10.0)
    k_wall = 0.2 * 1.0e5 / 10.0
    k_support = 5.0e3
    walled = pushover(two_story(walls={1: kelvin, 2: vdw.SupportedDamper(kelvin, k_support)}), [1.0, 1.0], 0.005)
    series = k_wall * k_support / (k_wall + k_support)
    np.testing.assert_allclose(walled.wall_stiffness, [k_wall, series], rtol=1e-12)
    first = 1  # the first increment is elastic
    flexibility = 1.0 / (1.0e5 + k_wall) + 0.5 / (1.0e5 + series)
    assert walled.roof_displacement[first] / walled.base_shear[first] == pytest.approx(flexibility, rel=1e-10)


def test_a_snap_back_is_reported_with_where_and_why():
    """Story 1 softens at -P/h = -5 kN/mm after yielding while story 2 (1 kN/mm, half the load) unloads: the
    roof would have to move back, which roof displacement control cannot follow."""
    building = vdw.ShearBuilding([100.0, 100.0], [1.0e5, 1.0e3], story_heights=[3000.0, 3000.0],
                                 hysteresis=[vdw.Bilinear(1.0e5), None], gravity_loads=[5000.0 * 3000.0, 0.0])
    with pytest.raises(ValueError, match=r"pushover stopped at a roof displacement of .* mm .*base shear .* kN.*"
                                         r"snaps back \(story 1 softens"):
        pushover(building, [1.0, 1.0], 0.1)


@pytest.mark.parametrize("kwargs, match", [
    ({"target_drift_ratio": 0.0}, "target_drift_ratio must be > 0"),
    ({"target_drift_ratio": 1.5}, "at most 1"),
    ({"pattern": "uniform"}, "pattern must be one of"),
    ({"pattern": [1.0]}, "pattern has 1 loads for 2 floors"),
    ({"pattern": [1.0, -1.0]}, "must be >= 0 and not all zero"),
    ({"pattern": [0.0, 0.0]}, "must be >= 0 and not all zero"),
    ({"steps": 0}, "steps must be a whole number"),
    ({"steps": 10**6}, "steps must be at most"),
    ({"period": -1.0}, "period must be > 0"),
])
def test_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        pushover(two_story(), **kwargs)


def test_needs_story_heights_and_a_stable_frame():
    with pytest.raises(ValueError, match="story_heights"):
        pushover(vdw.ShearBuilding([100.0], [1.0e5]))
    unstable = vdw.ShearBuilding([100.0], [1.0e3], story_heights=[3000.0], gravity_loads=[1.0e7])
    with pytest.raises(ValueError, match="unstable under its gravity loads"):
        pushover(unstable)
