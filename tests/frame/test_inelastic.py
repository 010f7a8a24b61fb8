"""Inelastic shear buildings (yielding stories, P-Delta): the yielding path against the linear one, OpenSees's
Steel01 and BoucWen frames, second-order convergence, energy balance, collapse, free vibration, Newton's
failures reported.  Story materials alone: test_hysteresis.py."""

from __future__ import annotations

import concurrent.futures
import warnings

import numpy as np
import opensees_frame
import pytest
from builders import (
    INELASTIC_FRACTIONAL_WALL,
    TEN_STORY_HEIGHTS,
    TEN_STORY_MASSES,
    TEN_STORY_STIFFNESSES,
    yielding_ten_story,
)
from reference import peak_deviation
from shared_data import SHARED, shared_record

from vdw_frames import Bilinear, BoucWen, G, GroundMotion, ShearBuilding, read_at2, run_batch, simulate
from vdw_frames.frame import NewtonRaphson

pytestmark = pytest.mark.records  # every analysis here runs a recorded accelerogram


def test_linear_limit_equals_the_linear_path():
    motion = read_at2(shared_record("RIO270.AT2")).scaled_to_pga(0.4 * G)
    linear = ShearBuilding(TEN_STORY_MASSES, TEN_STORY_STIFFNESSES, story_heights=TEN_STORY_HEIGHTS,
                           devices={s: INELASTIC_FRACTIONAL_WALL for s in range(1, 7)})
    strong = yielding_ten_story(strength=1e3, walls=INELASTIC_FRACTIONAL_WALL, gravity=False)  # never yields
    expected, result = simulate(linear, motion), simulate(strong, motion)
    scale = np.abs(expected.displacement).max()
    assert np.abs(result.displacement - expected.displacement).max() <= 1e-12 * scale
    assert np.abs(result.wall_force - expected.wall_force).max() <= 1e-12 * np.abs(expected.wall_force).max()
    assert result.energy.hysteretic[-1] == pytest.approx(0.0, abs=1e-9 * result.energy.input[-1])


@pytest.mark.opensees
def test_bilinear_frame_matches_opensees_steel01(ops):
    # Steel01 springs (b = hardening), P-Delta as negative-stiffness zeroLengths, rayleigh(a0, 0, a1, 0) on the
    # springs, r = 1 walls as Elastic + Maxwell; El Centro scaled so that stories reach ductility >= 4.
    motion = read_at2(shared_record("elCentro.AT2"))
    building = yielding_ten_story()
    result = simulate(building, motion)
    displacement, reaction, spring_force = opensees_frame.run(building, motion.acceleration, motion.dt, reactions=True,
                                                              tolerance=1e-10)
    drift = opensees_frame.drifts(displacement)
    assert result.peak_ductility.max() >= 4.0
    assert peak_deviation(result.drift, drift) < 0.01  # measured 0.13 % (the r = 1 walls' discretisations differ)
    peak = np.abs(drift).max(axis=0)
    assert (np.abs(result.residual_drift - drift[-1]) / peak).max() < 0.02  # measured 0.14 %
    story1 = spring_force[:, 0]
    assert np.abs(result.story_shear[:, 0] - story1).max() < 0.01 * np.abs(story1).max()  # measured 0.18 %
    # Base shear is the force through story 1: the ground's reaction (opposite sign), within 0.6 % of its peak.
    assert np.abs(result.base_shear + reaction).max() < 0.006 * np.abs(reaction).max()


@pytest.mark.opensees
def test_opensees_and_vdw_frames_converge_together_under_dt_refinement(ops):
    # At a quarter of the record step the two discretisations of the walls agree 15x more closely.
    motion = read_at2(shared_record("elCentro.AT2"))
    building = yielding_ten_story()
    dt = motion.dt / 4
    result = simulate(building, motion, dt=dt)
    displacement, reaction, _spring_force = opensees_frame.run(building, motion.acceleration_at(dt), dt, reactions=True,
                                                              tolerance=1e-10)
    assert peak_deviation(result.drift, opensees_frame.drifts(displacement)) < 2e-4  # measured 0.009 %
    assert np.abs(result.base_shear + reaction).max() < 1e-3 * np.abs(reaction).max()


@pytest.mark.slow
@pytest.mark.opensees
def test_bouc_wen_frame_matches_opensees_bouc_wen(ops):
    # OpenSees integrates z by backward Euler (first order), vdw_frames by TR-BDF2 (second order); at dt / 16
    # both have converged to 0.25 % (measured deviation 3.4 %, 0.94 %, 0.24 % at dt, dt / 4, dt / 16).
    motion = read_at2(shared_record("elCentro.AT2")).scaled(1.2)
    building = yielding_ten_story(model=BoucWen)
    dt = motion.dt / 16
    result = simulate(building, motion, dt=dt)
    displacement, _, spring_force = opensees_frame.run(building, motion.acceleration_at(dt), dt, reactions=True,
                                                       tolerance=1e-10)
    drift = opensees_frame.drifts(displacement)
    assert result.peak_ductility.max() >= 4.0
    assert peak_deviation(result.drift, drift) < 0.01
    assert np.abs(result.story_shear[:, 0] - spring_force[:, 0]).max() < 0.01 * np.abs(spring_force[:, 0]).max()


@pytest.mark.slow
@pytest.mark.parametrize("model", [Bilinear, BoucWen])
def test_inelastic_frame_with_fractional_walls_converges_at_second_order(model):
    # Errors against a 16x finer solution; sub-steps of the record (linear interpolation of the ground motion).
    motion = read_at2(shared_record("elCentro.AT2")).scaled(1.2)
    motion = GroundMotion(motion.acceleration[:600], motion.dt, motion.name)  # the first 12 s: the strong part
    building = yielding_ten_story(model=model, walls=INELASTIC_FRACTIONAL_WALL)
    reference = simulate(building, motion, dt=motion.dt / 32, memory="exact")
    errors = []
    for sub in (2, 4, 8):
        result = simulate(building, motion, dt=motion.dt / sub, memory="exact")
        every = 32 // sub
        errors.append(np.abs(result.drift - reference.drift[::every]).max())
    assert result.peak_ductility.max() > 3.0
    ratios = [errors[0] / errors[1], errors[1] / errors[2]]
    assert min(ratios) > 3.0, ratios  # second order: 4 per halving


@pytest.mark.parametrize("name", sorted(p.name for p in SHARED.glob("*.[aA][tT]2")) if SHARED.is_dir() else ["(none)"])
def test_energy_balance_closes_at_ductility_four_on_every_shared_record(name):
    motion = read_at2(shared_record(name))
    building = yielding_ten_story(walls=INELASTIC_FRACTIONAL_WALL)
    # Scale each record to the smallest of a few intensities that takes some story to ductility 4.
    for sa in (0.2, 0.4, 0.7, 1.0, 1.5):
        result = simulate(building, motion.scaled_to_spectral_acceleration(sa * G, building.periods[0]))
        if result.peak_ductility.max() >= 4.0 or result.collapsed:
            break
    assert result.peak_ductility.max() >= 4.0 and result.converged
    energy = result.energy
    assert np.abs(energy.balance_error).max() < 0.005 * np.abs(energy.input).max()  # measured ~1e-13
    assert energy.hysteretic[-1] > 0.05 * energy.input[-1]  # the stories dissipate
    assert energy.p_delta[-1] <= 0.0


def test_weak_frame_with_p_delta_collapses_cleanly():
    motion = read_at2(shared_record("RIO270.AT2")).scaled_to_pga(1.0 * G)
    building = yielding_ten_story(strength=0.03, hardening=0.0, walls=None)
    result = simulate(building, motion, collapse_drift_ratio=0.10)
    assert result.collapsed and result.converged
    assert result.collapse_time == pytest.approx(result.time[-1])
    assert result.time[-1] < motion.duration
    assert np.abs(result.drift_ratio[-1]).max() > 0.10 >= np.abs(result.drift_ratio[:-1]).max()
    for history in (result.displacement, result.story_shear, result.base_shear, result.energy.input):
        assert np.isfinite(history).all() and history.shape[0] == result.time.size
    # Without the check the leaning frame runs away (the linearised P-Delta grows without bound): the analysis
    # goes on past the collapse time (or stops where Newton gives up), never raises, and stays finite.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        free = simulate(building, motion, collapse_drift_ratio=None)
    assert not free.collapsed and free.time[-1] > result.collapse_time
    assert np.abs(free.drift_ratio).max() > 1.0 and np.isfinite(free.displacement).all()


def test_sharp_bouc_wen_story_at_the_record_step_converges():
    # Increments of several yield drifts a step through a knee of exponent 50 (a near-bilinear story): the
    # update once returned a non-root there, and a NaN state passed Newton's norm.
    motion = read_at2(shared_record("elCentro.AT2"))
    weight = 100.0 * 9806.65
    building = ShearBuilding([100.0], [1e5], story_heights=[3000.0], hysteresis=[BoucWen(0.1 * weight, 0.02, 50.0)])
    result = simulate(building, motion)
    assert result.converged and not result.collapsed and np.isfinite(result.displacement).all()
    assert result.peak_ductility[0] > 2.0
    assert np.abs(result.energy.balance_error).max() < 1e-6 * result.energy.input.max()


@pytest.mark.parametrize("divisions, free_vibration, gravity", [(128, 0.0, True), (1, 60.0, False)])
def test_small_steps_and_long_rest_converge(divisions, free_vibration, gravity):
    # The force test's scale includes the inertia terms before they cancel (m 4/dt^2 |u|): at dt / 128, and
    # at rest after a record without P-Delta, the tolerance stays above the residual's round-off.
    motion = read_at2(shared_record("elCentro.AT2")).scaled(1.2)
    motion = GroundMotion(motion.acceleration[:400], motion.dt, motion.name)  # 8 s
    building = yielding_ten_story(walls=INELASTIC_FRACTIONAL_WALL, gravity=gravity)
    result = simulate(building, motion, dt=motion.dt / divisions, free_vibration=free_vibration)
    assert result.converged and result.peak_ductility.max() > 1.0
    assert result.time[-1] == pytest.approx(motion.duration + free_vibration)


def test_free_vibration_appends_rest_and_residual_drift_is_measured_at_rest():
    motion = read_at2(shared_record("RIO270.AT2")).scaled_to_pga(0.6 * G)
    building = yielding_ten_story(walls=INELASTIC_FRACTIONAL_WALL)
    result = simulate(building, motion, free_vibration=10.0)
    assert result.time[-1] == pytest.approx(motion.duration + 10.0)
    assert not result.ground_acceleration[-int(10.0 / motion.dt):].any()
    assert np.abs(result.velocity[-1]).max() < 0.02 * np.abs(result.velocity).max()  # at rest
    np.testing.assert_array_equal(result.residual_drift, result.drift[-1])
    assert np.abs(result.residual_drift).max() > 1.0  # mm: the frame yielded and kept a permanent set


def test_nonconvergence_is_reported_not_raised():
    motion = read_at2(shared_record("RIO270.AT2")).scaled_to_pga(0.6 * G)
    building = yielding_ten_story(model=BoucWen, walls=INELASTIC_FRACTIONAL_WALL)
    hopeless = NewtonRaphson(displacement_tolerance=1e-300, force_tolerance=1e-300, max_iterations=1,
                             fallback_iterations=1)
    with pytest.warns(RuntimeWarning, match=r"did not converge \(story \d+"):
        result = simulate(building, motion, newton=hopeless)
    assert not result.converged and not result.collapsed
    assert np.isfinite(result.displacement).all() and result.time[-1] < motion.duration
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with concurrent.futures.ThreadPoolExecutor(1) as pool:
            batch = run_batch(building, [motion], [0.5, 1.0], executor=pool, progress=False, newton=hopeless)
    assert batch.converged.tolist() == [[False, False]]
