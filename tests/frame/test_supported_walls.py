"""Supported walls (a wall in series with its support) in the frame: the frame's frequency response, its time
history against the FFT solution of the series formula written out here, what is reported per wall and per
story, and batches."""

from __future__ import annotations

import concurrent.futures

import numpy as np
from builders import FITTED300, three_story, two_tone_motion
from reference import wall_stiffness

from vdw_frames import FDMKDamper, SupportedDamper, run_batch, simulate


def supported_frame():
    """The three-story frame, story 1: a supported and a bare wall; story 2: a supported wall; story 3: a bare wall."""
    wall = FDMKDamper(**FITTED300, area=3e5)
    return three_story({1: [SupportedDamper(wall, 8e4), wall], 2: SupportedDamper(wall, 2e5), 3: wall})


def smooth_motion(dt, duration=10.0):
    return two_tone_motion(dt, duration, (1.3, 2000.0), (3.7, 800.0), ramp=3.0)


def test_frame_frequency_response_assembles_the_series_formula():
    building = supported_frame()
    f = np.array([0.3, 1.0, 1.7, 4.0])
    omega = 2 * np.pi * f
    m, c = np.diag(building.masses), np.asarray(building.damping_matrix)
    response = building.frequency_response(f)
    for k, w in enumerate(omega):
        per_story = np.array(building.stiffnesses, dtype=complex)
        for story, wall in building.wall_list:
            params = {name: getattr(wall.damper if isinstance(wall, SupportedDamper) else wall, name)
                      for name in ("G1", "G2", "eta1", "eta2", "r")}
            k_w = wall_stiffness(params, wall.area, wall.thickness, w)
            if isinstance(wall, SupportedDamper):
                k_w = k_w * wall.support_stiffness / (k_w + wall.support_stiffness)
            per_story[story - 1] += k_w
        stiffness = (np.diag(per_story + np.r_[per_story[1:], 0.0]) - np.diag(per_story[1:], 1)
                     - np.diag(per_story[1:], -1))
        expected = np.linalg.solve(stiffness - w**2 * m + 1j * w * c, -np.asarray(building.masses))
        np.testing.assert_allclose(response[k], expected, rtol=1e-11)


def test_frame_time_history_matches_the_fft_solution_with_second_order():
    building = supported_frame()
    fine = 0.0025
    exact = np.diff(building.stationary_response(smooth_motion(fine).acceleration, fine, pad_factor=8),
                    axis=1, prepend=0.0)
    errors = []
    for dt in (0.01, 0.005):
        result = simulate(building, smooth_motion(dt))
        expected = exact[:: round(dt / fine)]
        errors.append(np.abs(result.drift - expected).max() / np.abs(expected).max())
    assert errors[1] < 1e-3, errors
    assert errors[0] / errors[1] > 3.5, errors


def test_wall_strain_and_story_drift_are_both_reported_and_energy_balances():
    building = supported_frame()
    result = simulate(building, smooth_motion(0.005))
    # Same kernel: each wall's force is the assembly's force under its story drift.
    for index, (story, wall) in enumerate(building.wall_list):
        alone = wall.force(result.drift[:, story - 1], 0.005)
        np.testing.assert_allclose(result.wall_force[:, index], alone, atol=1e-9 * np.abs(alone).max())
    # Series: the support carries the wall's force, so drift = wall deformation + force / k_s.
    for index, (story, wall) in enumerate(building.wall_list):
        drift = result.drift[:, story - 1]
        wall_deformation = result.wall_strain[:, index] * wall.thickness
        if isinstance(wall, SupportedDamper):
            support_deformation = result.wall_force[:, index] / wall.support_stiffness
            assert np.abs(wall_deformation + support_deformation - drift).max() <= 1e-9 * np.abs(drift).max()
            assert np.abs(wall_deformation).max() < 0.9 * np.abs(drift).max()  # the wall sees less than the drift
        else:
            np.testing.assert_allclose(wall_deformation, drift, atol=1e-12 * np.abs(drift).max())
    # The story's reported strain is its most strained wall's: on story 1 the unsupported one.
    np.testing.assert_allclose(result.story_wall_strain[:, 0], result.drift[:, 0] / 10.0, atol=1e-12)
    energy = result.energy
    assert np.abs(energy.balance_error).max() <= 1e-9 * np.abs(energy.input).max()
    assert energy.wall_work[-1] > 0.2 * energy.input[-1]  # the walls do dissipate


def test_batch_accepts_supported_walls():
    building = supported_frame()
    motion = smooth_motion(0.01, duration=6.0)
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        batch = run_batch(building, [motion], [1.0], executor=pool, progress=False)
    np.testing.assert_array_equal(batch.peak_drift[0, 0], simulate(building, motion).peak_drift)
