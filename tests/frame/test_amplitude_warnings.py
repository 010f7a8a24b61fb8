"""What a frame with amplitude-following walls warns about: an amplitude above the identified ones, or one
that never reaches them (extrapolations), not the ramp below them at a record's start and end (counted)."""

import warnings

import numpy as np
import pytest

import vdw_frames as vdw
from vdw_frames.motion import default_record


def frame(thickness, top=1.0):
    """Three stories with a strain-dependent wall each, of layer ``thickness`` mm (the top story's times
    ``top``), A / t fixed."""
    masses = np.array([400.0, 400.0, 380.0])
    weight = np.cumsum((masses * vdw.G)[::-1])[::-1]
    walls = {}
    for story in (1, 2, 3):
        t = thickness * (top if story == 3 else 1.0)
        walls[story] = [vdw.paper.strain_dependent(area=0.3e6 * t / 8.0, thickness=t)]
    return vdw.ShearBuilding(masses=masses, stiffnesses=[3.0e5, 2.7e5, 2.4e5], story_heights=[3500.0] * 3,
                             gravity_loads=weight, walls=walls)


def test_an_amplitude_above_the_identified_ones_warns_naming_the_story():
    thin = frame(1.0)
    with pytest.warns(UserWarning, match=r"wall strain amplitude outside the amplitudes .*story 1: up to \d+ %"):
        result = vdw.simulate(thin, default_record())
    amplitude = result.wall_amplitude.max(axis=0)
    above = result.wall_time_outside_range[:, 1]
    # The warning is about amplitudes the test can see: above 450 % for as long as reported.
    assert amplitude.max() > 4.5
    dt = result.time[1] - result.time[0]
    np.testing.assert_allclose(above, [(result.wall_amplitude[:, w] > 4.5 + 1e-12).sum() * dt for w in range(3)],
                               atol=1.5 * dt)


def test_time_below_the_range_is_counted_not_warned():
    building = frame(8.0, top=0.6)
    motion = default_record()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        scale = 3.2 / vdw.simulate(building, motion).wall_amplitude.max()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = vdw.simulate(building, motion.scaled(scale))
    peaks = result.wall_amplitude.max(axis=0)
    assert np.all(peaks > 2.25) and np.all(peaks < 4.5)
    dt = result.time[1] - result.time[0]
    below = result.wall_time_outside_range[:, 0]
    np.testing.assert_allclose(below, [(result.wall_amplitude[1:, w] < 2.25 - 1e-12).sum() * dt for w in range(3)],
                               atol=1.5 * dt)
    assert np.all(below > 1.0)


def test_walls_that_never_reach_the_range_warn():
    with pytest.warns(UserWarning, match=r"story 1: at most \d+ %, below the range 225-450 % throughout"):
        vdw.simulate(frame(40.0), default_record().scaled(0.5))
