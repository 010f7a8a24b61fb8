"""The P695 search of one record (RecordSearch), whose analyses run as single lanes of the lanes engine on a reused
workspace, against the same hunt-and-fill driving simulate one analysis at a time (the search the assessment ran
before the lanes).  Reference: hunt_and_fill with simulate; equal to the bit (a lane runs simulate's own step), so
every run's intensity, outcome, peak drift ratio and step count are compared with ==, and the warnings by their
text."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

import vdw_frames as vdw
from vdw_frames import _warnings, config
from vdw_frames.assessment.collapse import CollapseCriterion, RecordSearch
from vdw_frames.assessment.hunt_fill import HuntAndFill, Run, hunt_and_fill
from vdw_frames.element.limits import WallLimits


def motions():
    """Three ramped sines of different frequencies and lengths (dt 0.01 s, unit amplitude 1 g)."""
    out = []
    for frequency, seconds in ((0.6, 6.0), (1.1, 8.0), (0.45, 5.0)):
        t = np.arange(0.0, seconds, 0.01)
        out.append(vdw.GroundMotion(vdw.G * np.sin(2.0 * np.pi * frequency * t) * np.minimum(t / 2.0, 1.0), 0.01,
                                    f"sine {frequency} Hz"))
    return out


def example(wall_limit=None):
    building = config.load_building(Path(__file__).parents[2] / "examples" / "ten_story.toml")
    if wall_limit is None:
        return building.without_devices()
    return building.with_devices({story: tuple(dataclasses.replace(wall, limits=WallLimits(strain=wall_limit))
                                               for wall in walls) for story, walls in building.devices.items()})


def simulated_search(building, motion, unit, criterion, settings):
    """The reference: hunt_and_fill driving simulate (the assessment's search before the lanes)."""
    label = motion.name

    def analyse(intensity):
        result = vdw.simulate(building, motion.scaled(unit * intensity), collapse_drift_ratio=criterion.drift_ratio)
        collapsed = criterion.collapsed(result, label)
        return Run(float(intensity), collapsed, bool(result.converged), float(np.max(result.peak_drift_ratio)),
                   int(result.time.size))

    return hunt_and_fill(analyse, settings, label)


@pytest.mark.slow
@pytest.mark.parametrize("wall_limit, criterion", [
    (None, CollapseCriterion(drift_ratio=0.10)),
    (2.0, CollapseCriterion(drift_ratio=0.10, wall_failure=True)),
])
def test_a_record_searched_on_lanes_equals_its_search_with_simulate(wall_limit, criterion):
    building = example(wall_limit)
    settings = HuntAndFill(start=0.3 * vdw.G, cap=4.0 * vdw.G, max_runs=6)
    collapsed = 0
    for motion in motions():
        with _warnings.collect() as on_lanes:
            found = RecordSearch(building, motion, 1.0 / vdw.G, criterion, settings).run()
        with _warnings.collect() as simulated:
            reference = simulated_search(building, motion, 1.0 / vdw.G, criterion, settings)
        assert found == reference  # every run (intensity, collapsed, converged, peak drift ratio, steps) and bracket
        assert [w.message for w in on_lanes] == [w.message for w in simulated]
        collapsed += not found.censored
    assert collapsed >= 2  # searches that hunted, bisected and filled
