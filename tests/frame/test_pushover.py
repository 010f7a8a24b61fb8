"""Pushover (FEMA P695 Sec. 6.3) against closed-form results for shear buildings."""

from __future__ import annotations

import math

import numpy as np
import pytest
from pushover_reference import bilinear_frame, modal_pattern, physical_path

import vdw_frames as vdw
from vdw_frames.frame.pushover import pushover

G = vdw.G
GOLDEN = (1.0 + math.sqrt(5.0)) / 2.0


def two_story(strengths=(3.0e5, 1.6e5), hardening=0.0, *, gravity=None, walls=None, k=1.0e5, m=100.0, h=3000.0):
    return vdw.ShearBuilding([m, m], [k, k], story_heights=[h, h],
                             hysteresis=[vdw.Bilinear(f, hardening) for f in strengths],
                             gravity_loads=gravity, devices=walls)


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


# ---------------------------------------------------------------------------------------------- several softening
ISSUE_FRAME = dict(masses=[250.0, 250.0, 200.0], k=[60.0e3, 55.0e3, 40.0e3], h=[4000.0, 3500.0, 3500.0],
                   yield_forces=[c * 700.0 * G for c in (0.075, 0.065, 0.04)], hardening=[0.01, 0.02, 0.02])
SEVERAL_SOFTENING = {
    # issue 29 A.1: stories 1 and 2 soften past yield (story 3 would harden); story 1 localises; modal loads
    "issue frame": (ISSUE_FRAME, "modal", 0),
    # two stories both softening past yield; story 2 is the weaker under the pattern and localises
    "2 stories, story 2 localises": (dict(masses=[300.0, 300.0], k=[50.0e3, 45.0e3], h=[4000.0, 4000.0],
                                          yield_forces=[2.2e6, 1.0e6], hardening=[0.0, 0.01]), [1.0, 1.0], 1),
    # three stories all softening past yield; story 2 localises, stories 1 and 3 unload
    "3 stories, all soften": (dict(masses=[300.0, 300.0, 300.0], k=[50.0e3, 45.0e3, 40.0e3],
                                   h=[4000.0, 3500.0, 3500.0], yield_forces=[2.6e6, 1.9e6, 1.5e6],
                                   hardening=[0.0, 0.0, 0.005]), [1.0, 2.0, 3.0], 1),
    # frames on which the Newton iteration of version 0.2 converged to two stories going opposite ways (drifts
    # +500 / -473 mm; +249 / -238 mm) and gave mu_T 2.17 and 1.19 without a word; the physical path: 12.5, 7.05
    "2 stories, once a wrong branch": (dict(masses=[250.0, 300.0], k=[60.0e3, 58.0e3], h=[4300.0, 4100.0],
                                            yield_forces=[c * 550.0 * G for c in (0.085, 0.055)],
                                            hardening=[0.001, 0.005]), "modal", 1),
    "3 stories, once a wrong branch": (dict(masses=[160.0, 200.0, 235.0], k=[64.0e3, 67.0e3, 31.0e3],
                                            h=[3700.0, 4000.0, 4100.0],
                                            yield_forces=[c * 595.0 * G for c in (0.040, 0.030, 0.045)],
                                            hardening=[0.0094, 0.0056, 0.0066]), "modal", 1),
    # story 3 yields first and hardens (tangent b k - P/h > 0), then story 1 peaks: story 3 unloads from its
    # yielded state along its elastic line, story 2 (softening past yield, but stronger) never yields
    "3 stories, a hardening story unloads": (dict(masses=[300.0, 300.0, 300.0], k=[50.0e3, 45.0e3, 40.0e3],
                                                  h=[4000.0, 3500.0, 3500.0], yield_forces=[2.0e6, 2.1e6, 0.5e6],
                                                  hardening=[0.0, 0.0, 0.3]), [1.0, 1.0, 1.0], 0),
    # the same with story 3 hardening more, and yielding in reverse (kinematic hardening) as it unloads
    "3 stories, a hardening story yields in reverse": (dict(masses=[300.0, 300.0, 300.0], k=[50.0e3, 45.0e3, 40.0e3],
                                                            h=[4000.0, 3500.0, 3500.0],
                                                            yield_forces=[2.0e6, 2.1e6, 0.3e6],
                                                            hardening=[0.0, 0.0, 0.5]), [1.0, 1.0, 1.0], 0),
}


@pytest.mark.parametrize("name", list(SEVERAL_SOFTENING))
def test_several_softening_stories_follow_the_physical_branch(name):
    """Issue 29 A.1: with two or three stories whose post-yield tangent is negative, the whole capacity path
    (drifts of every story, at every point, before and after the peak) against the closed form of
    :func:`physical_path`, to 1e-6; V_max, delta_u and mu_T (eqs. 6-6 to 6-8 with phi_1, T1 from numpy)."""
    frame, pattern, localising = SEVERAL_SOFTENING[name]
    masses = np.asarray(frame["masses"])
    gravity = np.cumsum((masses * G)[::-1])[::-1]  # the weight above each story
    building = bilinear_frame(**frame, gravity=gravity)
    shape, t1 = modal_pattern(masses, frame["k"], gravity, frame["h"])
    loads = masses * shape if pattern == "modal" else np.asarray(pattern, dtype=float)
    drifts, peak, c = physical_path(frame["k"], frame["yield_forces"], frame["hardening"], gravity,
                                    np.asarray(frame["h"]), loads)
    assert c == localising
    assert sum(np.asarray(frame["hardening"]) * frame["k"] < gravity / frame["h"]) >= 2  # several would soften
    result = pushover(building, pattern, 0.10)
    np.testing.assert_allclose(result.pattern, loads / loads.sum(), rtol=1e-12)
    assert result.max_base_shear == pytest.approx(peak, rel=1e-9)
    top = int(np.argmax(result.base_shear))
    assert result.ultimate_roof_displacement is not None and top < result.base_shear.size - 2
    scale = float(np.max(np.abs(result.story_drift)))
    for j, (load, measured) in enumerate(zip(result.base_shear, result.story_drift, strict=True)):
        np.testing.assert_allclose(measured, drifts(load, j > top), rtol=1e-6, atol=1e-6 * scale, err_msg=f"point {j}")
    past = result.story_drift[top + 1:]
    assert np.all(np.diff(past[:, c]) > 0)  # the localising story's drift only grows
    others = np.delete(past, c, axis=1)
    assert np.all(np.diff(others, axis=0) < 0)  # every other story unloads
    # FEMA P695 eqs. (6-6)-(6-8) by hand: C0 from phi_1, delta_y,eff at T1, delta_u where V = 0.8 V_max (a
    # straight descending branch: the roof displacement is the sum of the closed-form drifts there).
    c0 = shape[-1] * np.sum(masses * shape) / np.sum(masses * shape**2)
    delta_y = c0 * peak / (masses.sum() * G) * G / (4.0 * math.pi**2) * t1**2
    delta_u = float(np.sum(drifts(0.8 * peak, True)))
    assert result.period == pytest.approx(t1, rel=1e-9)
    assert result.yield_roof_displacement == pytest.approx(delta_y, rel=1e-9)
    assert result.ultimate_roof_displacement == pytest.approx(delta_u, rel=1e-6)
    assert result.period_based_ductility == pytest.approx(delta_u / delta_y, rel=1e-6)


def test_equal_strengths_the_lowest_story_localises():
    """The tie of the branch rule: two identical elastic-perfectly-plastic stories both carrying the whole base
    shear (the load on the roof) reach F_y at once; the lower one takes the plateau, the upper one stays at F_y / k."""
    k, fy = 1.0e5, 2.0e5
    building = vdw.ShearBuilding([100.0, 100.0], [k, k], story_heights=[3000.0, 3000.0],
                                 hysteresis=[vdw.Bilinear(fy), vdw.Bilinear(fy)])
    result = pushover(building, [0.0, 1.0], 0.02)
    plateau = result.base_shear >= fy * (1.0 - 1e-12)
    assert plateau.sum() > 10 and np.all(result.base_shear[plateau] == pytest.approx(fy, rel=1e-12))
    np.testing.assert_allclose(result.story_drift[plateau, 1], fy / k, rtol=1e-12)
    np.testing.assert_allclose(result.story_drift[plateau, 0], result.roof_displacement[plateau] - fy / k, rtol=1e-12)


def test_smooth_peak_of_bouc_wen_stories():
    """Bouc-Wen stories (n = 1, beta = gamma = 1/2) with P-Delta: on loading from rest z = 1 - exp(-d/d_y), so
    V(d) = b k d + (1 - b) F_y (1 - exp(-d/d_y)) - P/h d, with its peak where b k - P/h + (1 - b) k exp(-d/d_y) = 0;
    on unloading dz/dd = 1/d_y exactly (while z > 0), an elastic line of slope k - P/h.  Two stories soften past
    their peaks; the one whose peak of V / S comes first localises, the other unloads.  Story shears against the
    backbone to 1e-3 of F_y (the accuracy of the package's TR-BDF2 update over 0.1 d_y sub-increments, about
    4e-4 of the force), the unloading story's drift against its elastic line to 1e-9."""
    masses = np.array([250.0, 250.0])
    k, fy, b, h = np.array([60.0e3, 50.0e3]), np.array([0.08, 0.04]) * 500.0 * G, np.array([0.01, 0.005]), 4000.0
    gravity = np.cumsum((masses * G)[::-1])[::-1]
    theta = gravity / h
    building = vdw.ShearBuilding(masses, k, story_heights=[h, h], gravity_loads=gravity,
                                 hysteresis=[vdw.BoucWen(f, bb) for f, bb in zip(fy, b, strict=True)])
    share = np.array([1.0, 0.5])  # loads (1, 1): story 2 carries half the base shear
    d_y = fy / k

    def backbone(j, d):
        return b[j] * k[j] * d + (1.0 - b[j]) * fy[j] * (1.0 - np.exp(-d / d_y[j])) - theta[j] * d

    d_peak = -d_y * np.log((theta - b * k) / ((1.0 - b) * k))
    peaks = np.array([backbone(j, d_peak[j]) for j in range(2)]) / share
    c = int(np.argmin(peaks))
    result = pushover(building, [1.0, 1.0], 0.08, steps=400)
    assert result.max_base_shear == pytest.approx(peaks[c], rel=1e-3)
    top = int(np.argmax(result.base_shear))
    # every story on its backbone up to the peak, and story c past it: its shear lambda S_j against V(d) there
    for j, points in ((0, slice(0, top + 1)), (1, slice(0, top + 1)), (c, slice(top, None))):
        np.testing.assert_allclose(result.base_shear[points] * share[j], backbone(j, result.story_drift[points, j]),
                                   rtol=1e-3, atol=1e-3 * fy[j])
    after = slice(top + 1, None)
    localised = result.story_drift[after, c]
    other = 1 - c
    unloading = result.story_drift[top, other] - (result.base_shear[top] - result.base_shear[after]) * share[other] \
        / (k[other] - theta[other])
    np.testing.assert_allclose(result.story_drift[after, other], unloading, rtol=1e-9, atol=1e-9 * d_y[other])
    assert np.all(np.diff(localised) > 0) and result.ultimate_roof_displacement is not None


@pytest.mark.parametrize("hardening", [1e-6, 1e-12, 1e-15])
def test_a_near_plateau_is_followed_to_the_target(hardening):
    """Story 2 of the first test with a hardening so small that one unit in the last place of the load factor
    moves the roof by up to a third of a millimetre (b = 1e-15: a tangent of 1e-10 N/mm): the path still
    reaches the target, every point in equilibrium.  Story 1 carries V = lambda elastically (d_1 = V / k),
    story 2 carries share x V on its post-yield line F = b k d + (1 - b) F_y."""
    k, fy = 1.0e5, 1.6e5
    result = pushover(two_story(hardening=hardening), "modal", 0.02)
    share = GOLDEN / (1.0 + GOLDEN)
    assert result.end == "target" and result.roof_displacement[-1] == pytest.approx(0.02 * 6000.0, rel=1e-12)
    assert np.all(np.diff(result.roof_displacement) > 0)
    np.testing.assert_allclose(result.story_drift[:, 0], result.base_shear / k, rtol=1e-12, atol=1e-12)
    yielded = result.story_drift[:, 1] > fy / k * (1.0 + 1e-9)
    assert yielded.sum() > 400
    drift = result.story_drift[yielded, 1]
    np.testing.assert_allclose(result.base_shear[yielded] * share, hardening * k * drift + (1.0 - hardening) * fy,
                               rtol=1e-12)


def test_increments_too_small_to_resolve_are_refused_not_followed_for_ever():
    # 1e-300 of the height: every increment lay below the equilibrium tolerance (1e-12 mm), the path stood still
    # and the loop went on for ever.  Just above the bound the elastic branch is the closed form
    # V / U = 1 / sum(S_k / (k_k - P_k / h_k)), S_k the pattern's share above story k.
    building = bilinear_frame([200.0, 150.0], [2e5, 1.5e5], [3500.0] * 2, [5e5] * 2, [0.01] * 2, [1e6, 5e5])
    with pytest.raises(ValueError, match=r"increments of 1.4e-299 mm, below the 1e-09 mm a pushover resolves"):
        pushover(building, [1.0, 2.0], target_drift_ratio=1e-300)
    result = pushover(building, [1.0, 2.0], target_drift_ratio=500 * 2e-9 / 7000.0)
    shares, stiffness = np.array([1.0, 2.0 / 3.0]), np.array([2e5, 1.5e5]) - np.array([1e6, 5e5]) / 3500.0
    assert result.base_shear[-1] / result.roof_displacement[-1] == pytest.approx(1.0 / np.sum(shares / stiffness),
                                                                                  rel=1e-12)
