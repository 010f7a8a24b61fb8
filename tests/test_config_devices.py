"""Building files with every device kind (vdw_frames.config ``[[devices]]``): the file gives the building the
constructor gives, a simulation of it survives SimulationResult.save/load, and a malformed device group is
one ValueError naming what is wrong."""

from __future__ import annotations

import dataclasses
import json
import sys

import numpy as np
import pytest
from builders import MIXED_DEVICES_TOML, mixed_devices_building, tapered_pulse, write_file

from vdw_frames import FluidViscousDamper, FrictionDamper, paper, simulate
from vdw_frames.config import building_from_dict, load_building
from vdw_frames.frame import SimulationResult

if sys.version_info >= (3, 11):
    import tomllib
else:  # Python 3.10: the same parser, as a package
    import tomli as tomllib


def same_building(one, other):
    """Whether two buildings are equal field by field (ShearBuilding compares by identity)."""
    return all(getattr(one, item.name) == getattr(other, item.name) for item in dataclasses.fields(one))


def test_a_file_with_every_device_kind_is_the_constructor_s_building(tmp_path):
    built = mixed_devices_building()
    read = load_building(write_file(tmp_path, "mixed.toml", MIXED_DEVICES_TOML))
    assert same_building(read, built)
    assert [type(device).__name__ for _, device in read.device_list] == [
        "FDMKDamper", "FluidViscousDamper", "FluidViscousDamper", "FrictionDamper", "FrictionDamper"]
    assert [story for story, _ in read.other_device_list] == [2, 3, 4, 4]


def test_the_same_devices_in_json_and_as_wall_type_groups(tmp_path):
    data = tomllib.loads(MIXED_DEVICES_TOML)
    wall_group = data.pop("walls")[0]
    data["devices"].insert(0, {"type": "wall", **wall_group})  # the wall as a [[devices]] group
    assert same_building(load_building(write_file(tmp_path, "mixed.json", json.dumps(data))),
                          mixed_devices_building())


def test_device_parameters_one_per_listed_story():
    spec = {"masses": [1.0, 1.0, 1.0], "stiffnesses": [1e3] * 3,
            "devices": [{"type": "friction", "stories": [3, 1], "slip_force": [10.0, 20.0], "stiffness": 5.0,
                         "magnification": [0.5, 1.0]}]}
    assert building_from_dict(spec).device_list == [(1, FrictionDamper(20.0, 5.0)),
                                                    (3, FrictionDamper(10.0, 5.0, magnification=0.5))]


def test_a_story_holds_its_walls_first_then_the_devices_in_file_order():
    spec = {"masses": [1.0], "stiffnesses": [1e3],
            "devices": [{"type": "fluid_viscous", "C": 2.0, "alpha": 1.0},
                        {"type": "friction", "slip_force": 3.0, "stiffness": 4.0}],
            "walls": [{"parameters": "fitted-300"}]}
    assert building_from_dict(spec).devices[1] == (paper.fitted(300), FluidViscousDamper(2.0, 1.0),
                                                   FrictionDamper(3.0, 4.0))


@pytest.mark.parametrize("group, match", [
    ({"type": "hydraulic"}, r"unknown device type 'hydraulic'; the known types are \['fluid_viscous', 'friction', "
                            r"'wall'\]"),
    ({"type": 3}, "unknown device type 3"),
    ({"C": 1.0, "alpha": 1.0}, "needs a type"),
    ("friction", "must be a table"),
    ({"type": "friction", "C": 1.0, "slip_force": 1.0, "stiffness": 1.0}, r"unknown friction device keys \['C'\]"),
    ({"type": "friction", "slip_force": 1.0}, "missing 1 required positional argument: 'stiffness'"),
    ({"type": "friction", "slip_force": -1.0, "stiffness": 1.0}, "slip_force must be > 0, got -1"),
    ({"type": "fluid_viscous", "C": 1.0, "alpha": 0.5}, "needs a stiffness"),
    ({"type": "fluid_viscous", "C": 1.0, "alpha": 1.5}, r"alpha must be in \(0, 1\], got 1.5"),
    ({"type": "fluid_viscous", "C": 1.0, "alpha": 1.0, "magnification": 0.0}, "magnification must be > 0"),
    ({"type": "fluid_viscous", "C": [1.0, 2.0], "alpha": 1.0}, "one number or one per listed story"),
    ({"type": "fluid_viscous", "C": 1.0, "alpha": 1.0, "per_story": 1001}, "at most 1000"),
    ({"type": "fluid_viscous", "C": 1.0, "alpha": 1.0, "stories": [2]},
     "fluid_viscous device story must be a story number in 1 ... 1, got 2"),
    ({"type": "friction", "slip_force": 1.0, "stiffness": 1.0, "stories": [1, 1]},
     r"friction devices stories must be 'all' or a list of distinct story numbers, got \[1, 1\]"),
    ({"type": "wall", "parameters": "fitted-300", "C": 1.0}, "unknown walls keys"),
])
def test_malformed_device_groups_are_refused_naming_the_value(group, match):
    with pytest.raises(ValueError, match=match):
        building_from_dict({"masses": [1.0], "stiffnesses": [1e3], "devices": [group]})


def test_devices_must_be_a_list_of_groups():
    with pytest.raises(ValueError, match="devices must be a list"):
        building_from_dict({"masses": [1.0], "stiffnesses": [1e3], "devices": {"type": "friction"}})


def test_a_simulation_of_every_device_kind_survives_save_and_load(tmp_path):
    building = load_building(write_file(tmp_path, "mixed.toml", MIXED_DEVICES_TOML))
    result = simulate(building, tapered_pulse())
    # Every device worked (the test is not about zeros), and the energy balance closes with four kinds at once.
    assert (np.abs(result.device_force).max(axis=0) > 1e3).all()
    assert np.abs(result.energy.balance_error).max() <= 1e-4 * result.energy.input.max()
    loaded = SimulationResult.load(result.save(tmp_path / "mixed.npz"))
    assert same_building(loaded.building, building)
    for item in dataclasses.fields(SimulationResult):
        value = getattr(result, item.name)
        if isinstance(value, np.ndarray):
            assert np.array_equal(getattr(loaded, item.name), value), item.name
    for name in ("device_heat", "device_stored", "input", "wall_work"):
        assert np.array_equal(getattr(loaded.energy, name), getattr(result.energy, name)), name


def test_a_saved_result_with_device_histories_of_the_wrong_shape_is_refused(tmp_path):
    building = mixed_devices_building()
    result = simulate(building, tapered_pulse())
    broken = dataclasses.replace(result, device_velocity=result.device_velocity[:, :3])
    with pytest.raises(ValueError, match="device_velocity"):
        SimulationResult.load(broken.save(tmp_path / "broken.npz"))
