"""size_layers: the rule it states (the suite's smallest and largest followed amplitudes symmetric about
the centre of the identified range), checked by running the suite again in the test with simulate."""

import inspect
import warnings

import numpy as np
import pytest

import vdw_frames as vdw
from vdw_frames.design import size_layers
from vdw_frames.motion import synthetic_ground_motion


def three_story(walls):
    masses = np.array([300.0, 300.0, 250.0])
    weight = np.cumsum((masses * vdw.G)[::-1])[::-1]
    return vdw.ShearBuilding(masses=masses, stiffnesses=[1.5e5, 1.3e5, 1.0e5], story_heights=[3500.0] * 3,
                             gravity_loads=weight, hysteresis=[vdw.Bilinear(0.15 * w, 0.03) for w in weight],
                             devices=walls)


SUITE = [synthetic_ground_motion(duration=8.0, dt=0.01, seed=seed, strong_motion_end=5.0, pga=0.3 * vdw.G)
         for seed in (11, 12, 13)]


def test_the_layers_centre_the_suites_amplitudes_in_the_identified_range():
    family = vdw.paper.strain_dependent(area=0.3e6, thickness=10.0)
    fixed = vdw.paper.fitted(300, area=0.1e6, thickness=8.0)
    building = three_story({1: [family, fixed], 2: [family.resized(0.25e6)], 3: [family.resized(0.15e6)]})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sizing = size_layers(building, SUITE, tolerance=0.002)
        assert sizing.converged and sizing.walls == (0, 2, 3)
        # Re-run the suite on the returned building, in the test.
        peaks = np.array([vdw.simulate(sizing.building, motion).wall_amplitude.max(axis=0) for motion in SUITE])
    lowest, highest = peaks.min(axis=0)[[0, 2, 3]], peaks.max(axis=0)[[0, 2, 3]]
    np.testing.assert_allclose(sizing.lowest, lowest, rtol=1e-12)
    np.testing.assert_allclose(sizing.highest, highest, rtol=1e-12)
    np.testing.assert_allclose(np.sqrt(lowest * highest), np.sqrt(2.25 * 4.5), rtol=0.002)
    # Area / thickness kept (the stiffness at a given strain), the fixed wall untouched.
    for (_, before), (_, after) in zip(building.wall_list, sizing.building.wall_list, strict=True):
        assert after.area / after.thickness == pytest.approx(before.area / before.thickness, rel=1e-12)
    assert sizing.building.wall_list[1][1] == fixed
    assert sizing.inside.tolist() == list((lowest >= 2.25) & (highest <= 4.5))
    assert sizing.margin == pytest.approx(min((lowest / 2.25).min(), (4.5 / highest).min()), rel=1e-12)


def test_size_layers_needs_amplitude_following_walls_and_a_suite():
    fixed = three_story({1: [vdw.paper.fitted(300)]})
    with pytest.raises(ValueError, match="needs walls that follow their amplitude"):
        size_layers(fixed, SUITE)
    walled = three_story({1: [vdw.paper.strain_dependent()]})
    with pytest.raises(ValueError, match="motions must be a non-empty sequence"):
        size_layers(walled, [])
    with pytest.raises(ValueError, match=r"tolerance must be below 0\.5"):
        size_layers(walled, SUITE, tolerance=0.7)


def test_size_layers_refuses_unbounded_passes_before_any_work(monkeypatch):
    """max_iterations = 10**9 with a tolerance no pass can meet ran the suite 10**9 times: refused before the
    first analysis (the limit, 100 passes, named)."""
    from vdw_frames.design import layers

    def no_work(*args, **kwargs):
        raise AssertionError("the suite ran before max_iterations was checked")

    monkeypatch.setattr(layers, "_suite_amplitudes", no_work)
    walled = three_story({1: [vdw.paper.strain_dependent()]})
    with pytest.raises(ValueError, match=r"max_iterations must be at most 100 \(each pass runs the whole suite\), "
                                         r"got 1000000000"):
        size_layers(walled, SUITE, tolerance=1e-300, max_iterations=10**9)


@pytest.mark.slow  # compiles the lanes for amplitude-following walls on a yielding frame (tens of seconds, cold)
def test_the_suite_on_lanes_sizes_the_layers_as_simulate_one_record_at_a_time_does():
    """size_layers runs each pass's suite as lanes; given simulate's own ``dt`` option (which lanes do not take)
    it runs one simulate a record, as before 0.3.0.  Reference: that path.  Tolerance: none -- a lane is the
    single analysis's step in the same order (tests/frame/test_lanes.py), so every pass's amplitudes, hence the
    thicknesses, are equal to the bit, and so are the warnings."""
    family = vdw.paper.strain_dependent(area=0.3e6, thickness=10.0)
    building = three_story({1: [family], 2: [family.resized(0.25e6)]})
    suite = [SUITE[0], vdw.GroundMotion(SUITE[1].acceleration[:601], 0.01, "shorter"), SUITE[2]]
    runs = []
    for options in ({}, {"dt": 0.01}):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            sizing = size_layers(building, suite, tolerance=0.01, **options)
        runs.append((sizing, [(w.category, str(w.message)) for w in caught]))
    (lanes, lanes_warned), (one_by_one, warned) = runs
    assert lanes.iterations == one_by_one.iterations > 1
    for name in ("lowest", "highest", "strain_range"):
        assert np.array_equal(getattr(lanes, name), getattr(one_by_one, name)), name
    assert lanes.building.wall_list == one_by_one.building.wall_list and lanes.converged == one_by_one.converged
    assert lanes_warned == warned


def test_a_bad_collapse_limit_is_refused_as_simulate_refuses_it():
    """size_layers on lanes passes simulate's options to run_lanes: a collapse limit simulate refuses (0, < 0, NaN)
    is refused there too, naming it, before any analysis (it was taken as "never collapse" or as a limit every
    drift exceeds).  Reference: simulate's own refusal."""
    walled = three_story({1: [vdw.paper.strain_dependent()]})
    short = [vdw.GroundMotion(motion.acceleration[:200], motion.dt, motion.name) for motion in SUITE]
    for bad in (0.0, -0.05, float("nan")):
        with pytest.raises(ValueError, match="collapse_drift_ratio") as expected:
            vdw.simulate(walled, short[0], collapse_drift_ratio=bad)
        with pytest.raises(ValueError, match="collapse_drift_ratio") as raised:
            size_layers(walled, short, collapse_drift_ratio=bad)
        assert str(raised.value) == str(expected.value)
        with pytest.raises(ValueError, match="collapse_drift_ratio"):
            vdw.frame.lanes.run_lanes(walled, short, collapse_drift_ratio=bad)


def test_the_lanes_warnings_point_at_the_caller_of_size_layers():
    """The warnings each lane gives (here: amplitudes beyond the identified ones) are issued at the line that called
    size_layers, as verify re-issues its own (before: one frame further up, ``sys:1`` from a script's top level).
    Reference: the caller's own file and line."""
    walled = three_story({1: [vdw.paper.strain_dependent()]})
    short = [vdw.GroundMotion(motion.acceleration[:300], motion.dt, motion.name) for motion in SUITE]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        line = inspect.currentframe().f_lineno + 1  # type: ignore[union-attr]
        size_layers(walled, short, max_iterations=1)
    assert caught and all(w.category is UserWarning for w in caught)
    assert {(w.filename, w.lineno) for w in caught} == {(__file__, line)}
