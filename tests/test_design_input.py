"""Design inputs (vdw_frames.config.load_design_input, ``vdw-frames design-building``): the values read are the
file's, masses become weights m g, a relative records folder is the file's neighbour, a prototype is the device
its keys make; anything malformed is one ValueError naming the file and what is wrong."""

from __future__ import annotations

import json

import pytest

from vdw_frames import FluidViscousDamper, paper
from vdw_frames.config import load_design_input
from vdw_frames.motion import G

BASE = {"site": {"sms": 0.9, "sm1": 0.45, "tl": 8.0}, "building": {"weights": [2.0e6, 1.5e6],
                                                                    "story_heights": [4000.0, 3500.0]}}


def write(tmp_path, data, name="input.json"):
    path = tmp_path / name
    path.write_text(json.dumps(data))
    return path


def test_the_values_are_the_file_s(tmp_path):
    (tmp_path / "records").mkdir()
    data = {**BASE, "building": {"masses": [200.0, 150.0], "story_heights": [4000, 3500], "damping_modes": [1, 2]},
            "design": {"system": "rc-smf", "device": "fvd", "target_damping": 0.2, "overstrength": 2.0,
                       "bounds": [0.9, 1.1], "records": "records", "p695": True, "rounds": 3,
                       "prototype": {"type": "fluid_viscous", "C": 10.0, "alpha": 0.4, "stiffness": 1.0e4},
                       "device_limits": {"stroke": 80.0}}}
    given = load_design_input(write(tmp_path, data))
    assert given.weights == (200.0 * G, 150.0 * G) and given.story_heights == (4000.0, 3500.0)
    assert (given.site.sms, given.site.sm1, given.site.tl, given.site.risk_category) == (0.9, 0.45, 8.0, "II")
    assert given.frame_options == {"damping_modes": (1, 2), "overstrength": 2.0}
    assert (given.system, given.device, given.target_damping, given.rounds, given.p695) == ("rc-smf", "fvd", 0.2, 3,
                                                                                            True)
    assert (given.bounds.lower, given.bounds.upper, given.bounds.source) == (0.9, 1.1, "stated in the design input")
    assert given.records == str(tmp_path / "records")
    assert given.prototype == FluidViscousDamper(10.0, 0.4, stiffness=1.0e4)
    assert given.device_limits == {"stroke": 80.0}


def test_a_wall_prototype_and_a_named_record_set(tmp_path):
    data = {**BASE, "design": {"records": "far-field", "prototype": {"type": "wall", "parameters": "fitted-225",
                                                                      "thickness": 12.0}}}
    given = load_design_input(write(tmp_path, data))
    assert given.records == "far-field" and given.prototype == paper.fitted(225, thickness=12.0)
    assert given.device is None and given.bounds is None


@pytest.mark.parametrize(("change", "words"), [
    ({"extra": 1}, "unknown design input keys"),
    ({"site": {"sms": 0.9, "sm1": 0.45}}, "the site needs tl"),
    ({"building": {"weights": [1.0], "masses": [1.0], "story_heights": [1.0]}}, "either weights"),
    ({"building": {"weights": [1.0, True], "story_heights": [1.0, 1.0]}}, "weights must be a list of numbers"),
    ({"building": {"weights": "1", "story_heights": [1.0]}}, "weights must be a list of numbers"),
    ({"building": {"weights": [1.0, 2.0], "story_heights": [1.0]}}, "weights and story heights of different lengths"),
    ({"building": {"weights": [1.0], "story_heights": [1.0], "damping_modes": 3}}, "damping_modes must be a list"),
    ({"building": {"weights": [1.0]}}, "needs story_heights"),
    ({"design": {"device": "lead"}}, "unknown design device 'lead'"),
    ({"design": {"colour": "red"}}, "unknown design keys"),
    ({"design": {"bounds_source": "x"}}, "bounds_source without bounds"),
    ({"design": {"bounds": [0.8]}}, "bounds must be [lambda_min, lambda_max]"),
    ({"design": {"p695": "yes"}}, "p695 must be true or false"),
    ({"design": {"records": ""}}, "records must be a FEMA P695 set name or a folder"),
    ({"design": {"system": 8}}, "system must be a name"),
    ({"design": {"device_limits": {"depth": 1.0}}}, "unknown design device_limits keys"),
    ({"design": {"device": "walls", "prototype": {"type": "friction", "slip_force": 1.0, "stiffness": 1.0}}},
     "the design prototype is of type 'friction' but device is 'walls'"),
    ({"design": {"prototype": {"type": "friction", "slip_force": 1.0, "stiffness": 1.0, "stories": [1]}}},
     "one device: no stories"),
    ({"design": {"prototype": {"type": "fluid_viscous", "C": 1.0, "alpha": 0.5}}}, "needs a stiffness"),
    ({"design": {"prototype": {"type": "lead"}}}, "unknown device type 'lead'"),
])
def test_a_malformed_input_is_one_value_error_naming_the_file(tmp_path, change, words):
    path = write(tmp_path, {**BASE, **change})
    with pytest.raises(ValueError, match=r"input\.json") as raised:
        load_design_input(path)
    assert words in str(raised.value)
