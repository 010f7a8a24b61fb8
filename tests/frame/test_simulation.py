"""Time histories of shear buildings with FDMK walls (vdw_frames.simulate: the Newmark-Newton integrator and
the fixed-wall run), against independent solutions: the frequency domain, scipy's lsim, the element alone."""

import re
import warnings

import numpy as np
import pytest
from builders import (
    BOTH_BRANCHES,
    README_WALL,
    light_ten_story,
    readme_ten_story,
    tapered_pulse,
    three_story,
    two_tone_motion,
)
from scipy import signal
from shared_data import SHARED

from vdw_frames import Bilinear, FDMKDamper, GroundMotion, ShearBuilding, read_at2, simulate
from vdw_frames.motion import default_record

RECORDS = sorted(SHARED.glob("*.[aA][tT]2")) if SHARED.is_dir() else []


def smooth_motion(dt, duration=20.0):
    return two_tone_motion(dt, duration, (1.2, 2000.0), (3.1, 1000.0), ramp=4.0)


def drifts(displacement):
    return np.diff(np.hstack([np.zeros((displacement.shape[0], 1)), displacement]), axis=1)


@pytest.fixture(scope="module")
def exact_drift():
    fine = 0.0025 / 4
    return drifts(light_ten_story().stationary_response(smooth_motion(fine).acceleration, fine, pad_factor=8)), fine


def test_peak_drifts_match_frequency_domain_solution_with_second_order(exact_drift):
    reference, fine = exact_drift
    building = light_ten_story()
    history_errors = []
    for dt in (0.01, 0.005, 0.0025):
        result = simulate(building, smooth_motion(dt))
        expected = reference[:: round(dt / fine)]
        if dt == 0.005:
            peak_error = np.abs(result.peak_drift / np.abs(expected).max(axis=0) - 1).max()
            assert peak_error < 0.003  # the bar; measured 0.10 %
        history_errors.append(np.abs(result.drift - expected).max() / np.abs(expected).max())
    ratios = np.array(history_errors[:-1]) / np.array(history_errors[1:])
    assert ratios.min() > 3.5, (history_errors, ratios)


def test_frame_without_dampers_matches_lsim():
    building = light_ten_story(walls=False)
    motion = smooth_motion(0.002, duration=12.0)
    n = building.stories
    minv = np.linalg.inv(building.mass_matrix)
    system = signal.StateSpace(
        np.block([[np.zeros((n, n)), np.eye(n)], [-minv @ building.stiffness_matrix, -minv @ building.damping_matrix]]),
        np.concatenate([np.zeros(n), -np.ones(n)])[:, None], np.hstack([np.eye(n), np.zeros((n, n))]), np.zeros((n, 1)))
    _, expected, _ = signal.lsim(system, motion.acceleration, motion.time)
    result = simulate(building, motion)
    assert np.abs(result.displacement - expected).max() < 2e-4 * np.abs(expected).max()


def test_damper_forces_equal_the_element_alone_under_the_same_drift():
    # One kernel: the frame's trial/commit stepping equals FDMKDamper.force on the drift history.
    building = light_ten_story()
    result = simulate(building, smooth_motion(0.01))
    for d, (story, wall) in enumerate(building.wall_list[:4]):
        alone = wall.force(result.drift[:, story - 1], 0.01)
        np.testing.assert_allclose(result.wall_force[:, d], alone, rtol=1e-9, atol=1e-9 * np.abs(alone).max())
    np.testing.assert_allclose(result.story_wall_force[:, 0], result.wall_force[:, 0] + result.wall_force[:, 1])


def test_energy_balance_and_base_shear_identity():
    building = light_ten_story()
    result = simulate(building, smooth_motion(0.01))
    energy = result.energy
    assert np.abs(energy.balance_error).max() < 1e-9 * np.abs(energy.input).max()
    assert energy.wall_work[-1] > 0 and energy.inherent_damping[-1] > 0
    # Base shear = the force through story 1 = (equilibrium of all floors) the floors' inertia forces plus
    # the mass-proportional damping forces, which act between the floors and the ground.
    a0, a1 = building.rayleigh_coefficients
    masses = np.asarray(building.masses)
    expected = -(result.absolute_acceleration @ masses) - a0 * (result.velocity @ masses)
    np.testing.assert_allclose(result.base_shear, expected, atol=1e-9 * np.abs(expected).max())
    # ... and, term by term: story-1 spring, story-1 walls and the stiffness-proportional damping force.
    direct = (building.stiffnesses[0] * result.drift[:, 0] + result.story_wall_force[:, 0]
              + a1 * building.stiffnesses[0] * result.velocity[:, 0])
    np.testing.assert_allclose(result.base_shear, direct, atol=1e-9 * np.abs(expected).max())


def test_substeps_interpolate_the_record_and_other_steps_are_refused():
    building = light_ten_story(walls=False)
    motion = smooth_motion(0.01, duration=4.0)
    coarse = simulate(building, motion)
    fine = simulate(building, motion, dt=0.005)
    assert fine.time.size == 2 * coarse.time.size - 1
    assert fine.ground_acceleration[1] == pytest.approx(0.5 * (motion.acceleration[0] + motion.acceleration[1]))
    # Same response sampled twice as often, up to Newmark's O(dt^2) error.
    assert np.abs(fine.drift[::2] - coarse.drift).max() < 1e-2 * np.abs(fine.drift).max()  # measured 0.5 %
    for bad in (0.02, 0.003):
        with pytest.raises(ValueError, match="dt"):
            simulate(building, motion, dt=bad)
    with pytest.raises(ValueError, match="ground_motion must be a GroundMotion"):
        simulate(building, motion.acceleration)


def test_warns_when_strain_leaves_identified_range():
    wall = FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5, area=2e5, strain_range=(2.0, 3.0))
    building = ShearBuilding([300.0], [3e5], devices={1: wall})
    with pytest.warns(UserWarning, match=r"outside the range.*story 1: 6 % \(range 200-300 %\)"):
        simulate(building, smooth_motion(0.01, duration=4.0))
    with pytest.warns(UserWarning, match=r"story 1: 582 % \(range 200-300 %\)"):
        simulate(building, smooth_motion(0.01, duration=4.0).scaled(100.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        big = smooth_motion(0.01, duration=4.0).scaled(1.0)
        unbounded = ShearBuilding([300.0], [3e5], damping_modes=(1, 1),
                                  devices={1: FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5)})
        simulate(unbounded, big)


@pytest.mark.records
@pytest.mark.parametrize("name", [p.name for p in RECORDS] or ["(none)"])
def test_energy_balance_closes_on_every_shared_record(name):
    if not RECORDS:
        pytest.skip(f"shared ground motions not found at {SHARED}")
    motion = read_at2(SHARED / name)
    result = simulate(light_ten_story(), motion)
    energy = result.energy
    # The bar is 0.5 % of the peak input energy; average acceleration closes it to rounding.
    assert np.abs(energy.balance_error).max() < 1e-9 * np.abs(energy.input).max()
    assert energy.wall_work[-1] > 0.2 * energy.input[-1]  # the walls do real work


def _fast_versus_exact(r, dt, duration):
    wall = FDMKDamper(**BOTH_BRANCHES, r=r, area=2.0e5)
    building = three_story({1: [wall, wall], 3: wall}, story_heights=None)
    t = np.arange(round(duration / dt) + 1) * dt
    # Broadband and long: a chirp from 0.2 to 8 Hz under a slow envelope, so the whole memory matters.
    ground = 3000.0 * np.sin(2 * np.pi * (0.2 + 3.9 * t / duration) * t) * np.sin(np.pi * t / duration) ** 2
    motion = GroundMotion(ground, dt)
    fast, exact = simulate(building, motion, memory="fast"), simulate(building, motion, memory="exact")
    peak = np.abs(fast.peak_drift / exact.peak_drift - 1).max()
    force = np.abs(fast.wall_force - exact.wall_force).max() / np.abs(exact.wall_force).max()
    return peak, force


@pytest.mark.parametrize("r", [0.05, 0.5, 0.99, 1.0])
@pytest.mark.parametrize("dt, duration", [(0.001, 20.0), (0.02, 400.0)])
def test_fast_memory_meets_the_bar_against_exact(r, dt, duration):
    # The bar for making "fast" the default: <= 1e-6 on peak drifts and force histories.
    peak, force = _fast_versus_exact(r, dt, duration)
    assert peak <= 1e-6 and force <= 1e-6, (peak, force)


@pytest.mark.slow
def test_fast_memory_meets_the_bar_over_100000_steps():
    peak, force = _fast_versus_exact(0.6, 0.001, 100.0)
    assert peak <= 1e-6 and force <= 1e-6, (peak, force)


def test_simulate_accepts_a_float32_step():
    frame = ShearBuilding([300.0, 250.0], [2e5, 1.5e5], devices={1: FDMKDamper(**README_WALL)})
    motion = tapered_pulse()
    for step in (0.01, 0.005):
        single = simulate(frame, motion, dt=np.float32(step))
        double = simulate(frame, motion, dt=step)
        np.testing.assert_array_equal(single.time, double.time)
        np.testing.assert_array_equal(single.displacement, double.displacement)
    np.testing.assert_array_equal(motion.resampled(np.float32(0.005)).acceleration,
                                  motion.resampled(0.005).acceleration)


def test_realistic_long_runs_are_not_refused():
    building = readme_ten_story()
    motion = default_record()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        long_run = simulate(building, motion, dt=motion.dt / 80)  # 200 001 steps
        coarse = simulate(building, motion)
    assert long_run.time.size == 200_001
    # Finer steps change the linear response only by Newmark's O(dt^2) error.
    assert long_run.peak_drift.max() == pytest.approx(coarse.peak_drift.max(), rel=2e-2)


def test_steps_out_of_range_and_unknown_methods_and_memories_are_refused():
    frame = ShearBuilding([300.0], [2e5], devices={1: FDMKDamper(**README_WALL)})
    motion = tapered_pulse()
    cases = [
        (lambda: simulate(frame, GroundMotion([0.0, 1.0, 0.0], 1e-300)), r"dt = 1e-300 s is outside the range"),
        (lambda: simulate(frame, GroundMotion([0.0, 1.0, 0.0], 1e300)), r"dt = 1e\+300 s is outside the range"),
        (lambda: simulate(frame.without_walls(), motion, method="x"), "method must be one of .*got 'x'"),
        (lambda: simulate(frame.without_walls(), motion, memory="x"), "memory must be one of .*got 'x'"),
    ]
    for call, match in cases:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            with pytest.raises(ValueError, match=match):
                call()


def test_a_building_unstable_under_its_gravity_loads_is_refused_naming_the_story():
    # Story 2: P/h = 3.6e6 N / 3000 mm = 1200 N/mm above its 1000 N/mm: K + K_G is not positive definite.
    def building(load_2, hysteresis=None, walls=None):
        return ShearBuilding([100.0, 100.0], [5000.0, 1000.0], story_heights=[3000.0, 3000.0],
                             gravity_loads=[6.0e6, load_2], hysteresis=hysteresis, devices=walls)

    motion = tapered_pulse()
    for unstable in (building(3.6e6), building(3.6e6, hysteresis=[None, Bilinear(2.0e4, 0.05)])):
        with pytest.raises(ValueError, match=r"simulate: the frame is unstable under its gravity loads: story 2's "
                                             r"P/h = 1200 N/mm is not below its stiffness at rest \(k0 and walls\) "
                                             r"1000 N/mm"):
            simulate(unstable, motion, collapse_drift_ratio=None)
    assert simulate(building(2.7e6), motion).converged  # P/h = 900 N/mm: stable
    # A wall's static stiffness G1 A / h = 0.5 MPa x 1e5 mm^2 / 10 mm = 5000 N/mm steadies the story, as
    # modal_analysis counts it.
    kelvin = FDMKDamper(G1=0.5, G2=0.0, eta1=0.05, eta2=0.0, r=0.5, area=1.0e5, thickness=10.0)
    assert simulate(building(3.6e6, walls={2: kelvin}), motion).converged


@pytest.mark.parametrize("free_vibration, steps", [(1e12, r"50,000,000,000,\d+"), (1e306, r"5e\+307"),
                                                   (1e308, "over 1e308")])
def test_a_free_vibration_too_long_to_run_is_refused_by_name(free_vibration, steps):
    # Before: the steps were blamed (and at 1e308 s an OverflowError escaped).
    frame = ShearBuilding([300.0], [2e5])
    refused = (rf"simulate with free_vibration = {re.escape(repr(free_vibration))} s \(dt = 0.02 s.*\) "
               rf"needs {steps} steps.*; use a shorter free_vibration")
    with pytest.raises(ValueError, match=refused):
        simulate(frame, GroundMotion([0.0, 1000.0, 0.0], 0.02), free_vibration=free_vibration)


def test_masses_that_overflow_the_newmark_terms_are_refused_by_name():
    # Before: 4 m / dt^2 = inf made the first step fail to converge, with a warning about story 1.
    with pytest.raises(ValueError, match=r"masses up to 1e\+308 t with dt = 0.02 s overflow Newmark's 4 m / dt\^2"):
        simulate(ShearBuilding([1e308, 1e308], [1e5, 1e5]), GroundMotion([0.0, 1000.0, 0.0], 0.02))


def test_an_overflowing_analysis_names_the_record_and_its_pga():
    # Before: only "the energy histories overflowed", whatever the input that overflowed.
    motion = GroundMotion(np.array([0.0, 1.0, -1.0, 0.0]) * 9806.65e300, 0.01, "quake")
    with pytest.raises(ValueError, match=r"overflowed \(inf or NaN\).*\(ground motion 'quake', PGA 9.80665e\+303 "
                                         r"mm/s\^2 = 1e\+300 g\)"):
        simulate(ShearBuilding([300.0], [2e5]), motion)
