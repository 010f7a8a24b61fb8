"""Shear building + Newmark integrator with FDMK dampers, against independent solutions."""

import warnings

import numpy as np
import pytest
from reference import tapered_sine
from scipy import signal

from vdw_frames import FDMKDamper, GroundMotion, ShearBuilding, read_at2, simulate

WALL = FDMKDamper(G1=0.0, G2=3.0, eta1=0.3, eta2=2.0, r=0.5, area=2.0e5, thickness=10.0)


def ten_story(walls=True):
    stiffness = [300e3 * (1 - 0.05 * i) for i in range(10)]
    walls = {story: [WALL, WALL] for story in range(1, 11)} if walls else None
    return ShearBuilding([300.0] * 10, stiffness, walls=walls, story_heights=[3500.0] * 10)


def smooth_motion(dt, duration=20.0):
    t = np.arange(round(duration / dt) + 1) * dt
    a = tapered_sine(t, 1.2, 2000.0, 4.0, duration) + tapered_sine(t, 3.1, 1000.0, 4.0, duration)
    return GroundMotion(a, dt, name="smooth")


def drifts(displacement):
    return np.diff(np.hstack([np.zeros((displacement.shape[0], 1)), displacement]), axis=1)


@pytest.fixture(scope="module")
def exact_drift():
    fine = 0.0025 / 4
    return drifts(ten_story().stationary_response(smooth_motion(fine).acceleration, fine, pad_factor=8)), fine


def test_peak_drifts_match_frequency_domain_solution_with_second_order(exact_drift):
    reference, fine = exact_drift
    building = ten_story()
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
    building = ten_story(walls=False)
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
    building = ten_story()
    result = simulate(building, smooth_motion(0.01))
    for d, (story, wall) in enumerate(building.wall_list[:4]):
        alone = wall.force(result.drift[:, story - 1], 0.01)
        np.testing.assert_allclose(result.wall_force[:, d], alone, rtol=1e-9, atol=1e-9 * np.abs(alone).max())
    np.testing.assert_allclose(result.story_wall_force[:, 0], result.wall_force[:, 0] + result.wall_force[:, 1])


def test_energy_balance_and_base_shear_identity():
    building = ten_story()
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


def test_rayleigh_damping_gives_the_ratio_in_the_named_modes():
    building = ShearBuilding([200.0, 150.0, 100.0], [2e5, 1.5e5, 1e5], damping_ratio=0.04, damping_modes=(1, 3))
    phi, omega = building.mode_shapes, building.circular_frequencies
    modal = phi.T @ building.damping_matrix @ phi
    assert modal[0, 0] / (2 * omega[0]) == pytest.approx(0.04, rel=1e-12)
    assert modal[2, 2] / (2 * omega[2]) == pytest.approx(0.04, rel=1e-12)
    # Two-story check of the eigenvalues: m = 1, k = 1 chain gives w^2 = (3 -+ sqrt 5) / 2.
    two = ShearBuilding([1.0, 1.0], [1.0, 1.0])
    np.testing.assert_allclose(two.circular_frequencies**2, [(3 - 5**0.5) / 2, (3 + 5**0.5) / 2], rtol=1e-12)


def test_time_step_rules():
    building = ten_story(walls=False)
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


@pytest.mark.parametrize("kwargs, match", [
    (dict(masses=[1.0, -2.0]), "masses must be > 0"), (dict(masses=[1.0, np.nan]), "masses must be finite"),
    (dict(stiffnesses=[1.0, 0.0]), "stiffnesses must be > 0"), (dict(stiffnesses=[1.0]), "stiffnesses has 1"),
    (dict(damping_ratio=1.0), "damping_ratio"), (dict(damping_ratio=-0.1), "damping_ratio"),
    (dict(damping_modes=(1, 3)), "damping_modes"), (dict(walls={3: WALL}), "story"),
    (dict(walls={0: WALL}), "story"), (dict(walls={1: "wall"}), "FDMKDamper"),
    (dict(story_heights=[3000.0]), "story_heights"), (dict(story_heights=[3000.0, -1.0]), "story_heights"),
    (dict(damping_modes=(1, None)), "damping_modes"), (dict(damping_modes=(1, np.inf)), "damping_modes"),
    (dict(damping_modes=2), "damping_modes"), (dict(walls=[WALL]), "walls must be a dict"),
])
def test_building_validation(kwargs, match):
    arguments = dict(masses=[1.0, 1.0], stiffnesses=[1.0, 1.0]) | kwargs
    with pytest.raises(ValueError, match=match):
        ShearBuilding(**arguments)


def test_warns_when_strain_leaves_identified_range():
    wall = FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5, area=2e5, strain_range=(2.0, 3.0))
    building = ShearBuilding([300.0], [3e5], walls={1: wall})
    with pytest.warns(UserWarning, match=r"outside the range.*story 1: 6 % \(range 200-300 %\)"):
        simulate(building, smooth_motion(0.01, duration=4.0))
    with pytest.warns(UserWarning, match=r"story 1: 582 % \(range 200-300 %\)"):
        simulate(building, smooth_motion(0.01, duration=4.0).scaled(100.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        big = smooth_motion(0.01, duration=4.0).scaled(1.0)
        unbounded = ShearBuilding([300.0], [3e5], damping_modes=(1, 1), walls={1: FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5)})
        simulate(unbounded, big)


from shared_data import SHARED

RECORDS = sorted(SHARED.glob("*.[aA][tT]2")) if SHARED.is_dir() else []


@pytest.mark.parametrize("name", [p.name for p in RECORDS] or ["(none)"])
def test_energy_balance_closes_on_every_shared_record(name):
    if not RECORDS:
        pytest.skip(f"shared ground motions not found at {SHARED}")
    motion = read_at2(SHARED / name)
    result = simulate(ten_story(), motion)
    energy = result.energy
    # The bar is 0.5 % of the peak input energy; average acceleration closes it to rounding.
    assert np.abs(energy.balance_error).max() < 1e-9 * np.abs(energy.input).max()
    assert energy.wall_work[-1] > 0.2 * energy.input[-1]  # the walls do real work


def _fast_versus_exact(r, dt, duration):
    wall = FDMKDamper(G1=0.5, G2=3.0, eta1=0.3, eta2=2.0, r=r, area=2.0e5)
    building = ShearBuilding([300.0, 300.0, 250.0], [2e5, 1.8e5, 1.5e5], walls={1: [wall, wall], 3: wall})
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


def test_fast_memory_meets_the_bar_over_100000_steps():
    peak, force = _fast_versus_exact(0.6, 0.001, 100.0)
    assert peak <= 1e-6 and force <= 1e-6, (peak, force)
