"""The P695 searches in rounds (RecordsSearch: every record's hunt-and-fill advancing one run a round, the round's
runs being lanes of one compiled call) against each record searched alone with simulate (RecordSearch, the
search the assessment ran before).  Reference: RecordSearch, i.e. hunt_and_fill driving simulate one run at a
time; equal to the bit (the lanes run simulate's own step), so every run's intensity, outcome, peak drift ratio
and step count are compared with ==, and the warnings by their text."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

import vdw_frames as vdw
from vdw_frames import _warnings, config
from vdw_frames.assessment.collapse import CollapseCriterion, RecordSearch, RecordsSearch
from vdw_frames.assessment.hunt_fill import HuntAndFill, Run, hunt_and_fill, searching
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


@pytest.mark.parametrize("wall_limit, criterion", [
    (None, CollapseCriterion(drift_ratio=0.10)),
    (2.0, CollapseCriterion(drift_ratio=0.10, wall_failure=True)),
])
def test_records_searched_in_rounds_equal_each_searched_alone(wall_limit, criterion):
    building = example(wall_limit)
    settings = HuntAndFill(start=0.3 * vdw.G, cap=4.0 * vdw.G, max_runs=6)
    records = motions()
    together = RecordsSearch(building, tuple(records), 1.0 / vdw.G, criterion, settings).run()
    collapsed = 0
    for motion, (found, warned) in zip(records, together, strict=True):
        with _warnings.collect() as caught:
            alone = RecordSearch(building, motion, 1.0 / vdw.G, criterion, settings).run()
        assert found == alone  # every run (intensity, collapsed, converged, peak drift ratio, steps) and bracket
        assert [w.message for w in warned] == [w.message for w in caught]
        collapsed += not found.censored
    assert collapsed >= 2  # searches that hunted, bisected and filled


def test_the_search_generator_is_hunt_and_fill():
    """searching() sent the runs of a known threshold yields the intensities hunt_and_fill runs."""
    settings = HuntAndFill(start=1.0, cap=100.0, max_runs=8)
    seen = []

    def run(intensity):
        seen.append(intensity)
        return hunt_fill_run(intensity)

    expected = hunt_and_fill(run, settings)
    steps = searching(settings)
    intensity, sent = next(steps), []
    try:
        while True:
            sent.append(intensity)
            intensity = steps.send(hunt_fill_run(intensity))
    except StopIteration as done:
        assert done.value == expected
    assert sent == seen and len(seen) >= 5


def hunt_fill_run(intensity):
    """A record that collapses from 7.3 on."""
    return Run(intensity, intensity >= 7.3, True, min(intensity / 73.0, 0.2))
