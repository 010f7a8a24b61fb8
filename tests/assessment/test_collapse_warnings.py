"""collapse_assessment counts analyses, not warnings: an amplitude-following wall outside its range gives two
strain-range warnings in one analysis (its amplitude and its peak strain, issue 29 A.4), which made the CLI
print "825 of 415 analyses took walls outside the strains ..." for examples/ten_story.toml."""

from __future__ import annotations

from pathlib import Path

import numpy as np

import vdw_frames as vdw
from vdw_frames import _warnings, config
from vdw_frames.assessment.collapse import CollapseCriterion, RecordSearch
from vdw_frames.assessment.hunt_fill import HuntAndFill
from vdw_frames.frame.time_history import is_strain_range_warning


def test_one_analysis_gives_one_strain_warning_saying_both():
    # One run of the example frame's strain-dependent walls at 3 x a record: its walls go beyond 450 % in
    # both amplitude and peak strain, said in one warning (simulate joins them).
    building = config.load_building(Path(__file__).parents[2] / "examples" / "ten_story.toml")
    t = np.arange(0.0, 6.0, 0.01)
    motion = vdw.GroundMotion(3.0 * vdw.G * np.sin(2.0 * np.pi * 0.6 * t) * np.minimum(t / 2.0, 1.0), 0.01, "sine")
    with _warnings.collect() as one_run:
        result = vdw.simulate(building, motion)
    strain = [w for w in one_run if is_strain_range_warning(w.message)]
    assert len(strain) == 1
    assert "wall peak strain outside the range" in strain[0].message
    assert "wall strain amplitude outside the amplitudes" in strain[0].message
    assert result.peak_wall_strain.max() > 4.5 and result.wall_amplitude.max() > 4.5


def test_a_record_search_gives_at_most_one_strain_warning_per_analysis():
    """The search of one record (three analyses at 1, 1.8 and 3.24 x 0.2 g on the ten-story example, each with its
    walls beyond 450 %): as many strain-range warnings as analyses that had one, not two per analysis."""
    building = config.load_building(Path(__file__).parents[2] / "examples" / "ten_story.toml")
    t = np.arange(0.0, 6.0, 0.01)
    motion = vdw.GroundMotion(vdw.G * np.sin(2.0 * np.pi * 0.6 * t) * np.minimum(t / 2.0, 1.0), 0.01, "sine")
    search = RecordSearch(building, motion, 1.0 / vdw.G,  # the motion times intensity / g
                          CollapseCriterion(drift_ratio=0.10),
                          HuntAndFill(start=0.2 * vdw.G, cap=0.6 * vdw.G, max_runs=3))
    with _warnings.collect() as caught:
        found = search.run()
    strain = [w for w in caught if is_strain_range_warning(w.message)]
    assert 0 < len(strain) <= len(found.runs)
