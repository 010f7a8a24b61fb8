"""Wall failures recorded by run_batch and the IDA: each against runs of simulate made in the test, the
wall-failure fragility against a maximum-likelihood fit written here, and the option that makes a wall
failure a collapse."""

import concurrent.futures
import dataclasses
import warnings

import numpy as np
import pytest
from scipy import optimize, stats

import vdw_frames as vdw
from vdw_frames.element.limits import WallLimits
from vdw_frames.motion import synthetic_ground_motion

WALL = vdw.FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5, area=2e5, thickness=8.0)
LIMITS = WallLimits(strain=1.2, source="a test value")


def three_story(limits=LIMITS):
    masses = np.array([300.0, 300.0, 250.0])
    weight = np.cumsum((masses * vdw.G)[::-1])[::-1]
    wall = dataclasses.replace(WALL, limits=limits)
    return vdw.ShearBuilding(masses=masses, stiffnesses=[1.5e5, 1.3e5, 1.0e5], story_heights=[3500.0] * 3,
                             gravity_loads=weight, hysteresis=[vdw.Bilinear(0.1 * w, 0.03) for w in weight],
                             devices={1: [wall], 2: [wall.resized(1.9e5)], 3: [wall.resized(1.5e5)]})


MOTIONS = [synthetic_ground_motion(duration=8.0, dt=0.01, seed=seed, strong_motion_end=5.0, name=f"s{seed}")
           for seed in (1, 2, 3, 4)]


def quiet(function, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return function(*args, **kwargs)


def test_run_batch_records_which_walls_failed_and_when():
    building = three_story()
    scales = [0.5, 1.5, 3.0]
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        batch = quiet(vdw.run_batch, building, MOTIONS[:2], scales, executor=pool, progress=False)
    assert batch.wall_failed.shape == (2, 3, 3) and batch.wall_stories == (1, 2, 3)
    assert batch.wall_failed.any() and not batch.wall_failed.all()
    for m, motion in enumerate(MOTIONS[:2]):
        for s, scale in enumerate(scales):
            result = quiet(vdw.simulate, building, motion.scaled(scale))
            np.testing.assert_array_equal(batch.wall_failed[m, s], result.wall_failed)
            for w, time in enumerate(result.wall_failure_time):
                if time is None:
                    assert batch.wall_failure_time.mask[m, s, w]
                else:
                    assert batch.wall_failure_time[m, s, w] == time


def _first_failure_level(building, motion, levels, period):
    """The first Sa level at which any wall fails, by simulate level after level (None: none up to the last
    level run, which stops at collapse)."""
    factor = motion.scale_factor_to_spectral_acceleration(1.0, period)
    for level in levels:
        result = quiet(vdw.simulate, building, motion.scaled(factor * level))
        if result.wall_failed.any():
            return level, result
        if result.collapsed or not result.converged:
            return None, result
    return None, None


def test_the_ida_reports_the_first_wall_failure_of_every_record_and_its_fragility():
    building = three_story()
    period = building.periods[0]
    step, cap = 0.1 * vdw.G, 1.0 * vdw.G
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        ida = quiet(vdw.incremental_dynamic_analysis, building, MOTIONS, step, cap, executor=pool)
    levels = ida.levels
    expected = [_first_failure_level(building, motion, levels, period)[0] for motion in MOTIONS]
    assert all(level is not None for level in expected), "the test needs every record's walls to fail"
    np.testing.assert_allclose(ida.wall_failure_intensity.filled(np.nan), expected, rtol=1e-12)
    assert "wall failure not included" in ida.limit_states
    # The wall-failure fragility against a maximum-likelihood lognormal fit written here (every record
    # failed: no censoring): median = geometric mean, dispersion = the (biased) standard deviation of logs.
    logs = np.log(np.array(expected))
    fragility = ida.fragility("wall failure")
    assert fragility.median == pytest.approx(np.exp(logs.mean()), rel=1e-4)
    assert fragility.dispersion == pytest.approx(logs.std(), rel=1e-3)
    # The same by a likelihood maximised here, as a check on the closed form.
    def negative_log_likelihood(params):
        return -np.sum(stats.norm.logpdf(logs, params[0], abs(params[1])))
    best = optimize.minimize(negative_log_likelihood, [logs.mean() + 0.1, 0.5], method="Nelder-Mead",
                             options=dict(xatol=1e-10, fatol=1e-12))
    assert fragility.median == pytest.approx(np.exp(best.x[0]), rel=1e-4)
    # Wall failure is not collapse: the walls failed at or below each record's collapse level.
    collapse = ida.collapse_intensity
    for m in range(len(MOTIONS)):
        if not np.ma.getmaskarray(collapse)[m]:
            assert ida.wall_failure_intensity[m] <= collapse[m]


def test_wall_failure_counts_as_collapse_only_when_asked():
    building = three_story()
    step, cap = 0.1 * vdw.G, 0.6 * vdw.G
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        counted = quiet(vdw.incremental_dynamic_analysis, building, MOTIONS[:2], step, cap, executor=pool,
                        wall_failure_collapse=True)
    assert "or the failure of any wall" in counted.limit_states
    np.testing.assert_array_equal(counted.collapse_intensity.filled(0.0), counted.wall_failure_intensity.filled(0.0))
    with pytest.raises(ValueError, match="wall_failure_collapse must be True or False"):
        vdw.incremental_dynamic_analysis(building, MOTIONS[:1], step, cap, wall_failure_collapse="yes")
    with pytest.raises(ValueError, match="limit_state must be 'collapse' or 'wall failure'"):
        counted.fragility("walls")
