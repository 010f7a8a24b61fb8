"""collapse_assessment kept its analyses' wall-strain warnings and dropped every other one: a wall heated past its
shift law's range said nothing, though simulate of the same run says so."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import vdw_frames as vdw
from vdw_frames.assessment import collapse_assessment
from vdw_frames.assessment.hunt_fill import HuntAndFill
from vdw_frames.collapse_report import markdown
from vdw_frames.element import catalogue
from vdw_frames.element.thermal import LogLinear, ThermalProperties


def test_the_analyses_other_warnings_are_kept_and_said():
    # A wall whose shift law holds over 20-21.5 degC only, from 21.2 degC: every analysis heats it past the range.
    narrow = LogLinear(degrees_per_decade=19.45, reference=21.2, valid=(20.0, 21.5))
    wall = dataclasses.replace(catalogue.fitted(300, area=2e4, thickness=10.0),
                               thermal=ThermalProperties(narrow, 1.8, 21.2))
    masses = np.array([200.0, 150.0])
    weight = masses.sum() * vdw.G
    building = vdw.ShearBuilding(masses, [2e5, 1.5e5], story_heights=[3500.0] * 2, gravity_loads=[1.2e7, 0.6e7],
                                 hysteresis=[vdw.Bilinear(0.15 * weight, 0.0), vdw.Bilinear(0.12 * weight, 0.0)],
                                 devices={1: [wall], 2: [wall]})
    t = np.arange(0.0, 8.0, 0.01)
    records = [vdw.GroundMotion(vdw.G * np.sin(2.0 * np.pi * f * t) * np.minimum(t / 2.0, 1.0), 0.01, f"sine {f}")
               for f in (1.5, 2.5)]
    with pytest.warns(UserWarning, match="shift law's range"):  # simulate of such a run says so
        vdw.simulate(building, records[0].scaled(0.2))
    with pytest.warns(UserWarning, match=r"collapse_assessment: \d+ other warning\(s\) .*shift law's range"):
        result = collapse_assessment(building, records, record_set="far-field", sdc="Dmax", progress=False,
                                         search=HuntAndFill(start=0.2 * vdw.G, cap=4.0 * vdw.G, max_runs=8))
    assert len(result.other_warnings) == result.total_analyses  # one per analysis: each heated its walls past 21.5
    assert all("shift law's range" in message for message in result.other_warnings)
    report = markdown({"walls": result})
    assert (f"- walls: {len(result.other_warnings)} other warning(s) from the analyses (e.g. "
            f"\"{result.other_warnings[0]}\")") in report
