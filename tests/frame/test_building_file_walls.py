"""Building files whose walls heat, fail and follow their amplitude: the file's tables give the same walls
as the Python constructors, and malformed tables are refused naming the key."""

import dataclasses
import math

import pytest

from vdw_frames import paper
from vdw_frames.config import building_from_dict, load_analysis
from vdw_frames.element.limits import WallLimits
from vdw_frames.element.thermal import ISD110_LOSS_PEAK, WLF, Arrhenius, ThermalProperties

TOML = '''masses = [600.0, 450.0]
stiffnesses = [3e5, 2e5]
story_heights = [4000.0, 3500.0]

[[walls]]
stories = "all"
parameters = "strain-dependent"
area = 0.5e6

[walls.thermal]
shift = "isd110-loss-peak"
heat_capacity = 1.8
temperature = 5.0
cooling_time = 900.0

[walls.limits]
strain = 8.5
residual = 0.05
source = "a stated source"

[[walls]]
stories = [1]
parameters = "fitted-300"

[walls.thermal]
shift = {law = "wlf", C1 = 8.0, C2 = 120.0, reference = 21.2, valid = [0, 60], source = "test constants"}
heat_capacity = 2.0
'''


def test_walls_with_thermal_and_limit_tables_are_the_constructors_walls(tmp_path):
    path = tmp_path / "walls.toml"
    path.write_text(TOML)
    building, options = load_analysis(path)
    assert options == {}  # a time-history analysis: the strain-dependent walls follow their amplitude
    thermal = ThermalProperties(ISD110_LOSS_PEAK, 1.8, 5.0, 900.0)
    limits = WallLimits(strain=8.5, residual=0.05, source="a stated source")
    expected = paper.strain_dependent(area=0.5e6, thermal=thermal, limits=limits)
    walls = building.wall_list
    assert [story for story, _ in walls] == [1, 1, 2]
    assert walls[0][1] == expected and walls[2][1] == expected
    wlf = WLF(8.0, 120.0, 21.2, (0.0, 60.0), "test constants")
    assert walls[1][1] == dataclasses.replace(paper.fitted(300), thermal=ThermalProperties(wlf, 2.0))
    assert walls[1][1].thermal.temperature == 21.2  # the law's reference when not given
    assert walls[1][1].thermal.cooling_time == math.inf


def test_an_arrhenius_law_from_a_file():
    data = {"masses": [100.0], "stiffnesses": [1e5], "walls": [{
        "parameters": "fitted-225", "thermal": {"heat_capacity": 1.6, "shift": {
            "law": "arrhenius", "activation_energy": 2.0e5, "reference": 21.2, "valid": [0.0, 50.0]}}}]}
    wall = building_from_dict(data).wall_list[0][1]
    assert wall.thermal == ThermalProperties(Arrhenius(2.0e5, 21.2, (0.0, 50.0)), 1.6)


def base(**wall):
    return {"masses": [100.0], "stiffnesses": [1e5], "walls": [{"parameters": "fitted-300", **wall}]}


@pytest.mark.parametrize("wall, match", [
    ({"thermal": {"shift": "isd110-loss-peak"}}, r"walls thermal needs shift and heat_capacity"),
    ({"thermal": {"shift": "rubber", "heat_capacity": 1.8}},
     r"walls thermal shift must be one of \['isd110-loss-peak'\]"),
    ({"thermal": {"shift": {"law": "wlf", "C1": 8.0, "reference": 21.2, "valid": [0, 60]}, "heat_capacity": 1.8}},
     r"walls thermal shift \(wlf\) needs \['C2'\]"),
    ({"thermal": {"shift": {"law": "wlf", "C1": 8.0, "C2": -5.0, "reference": 21.2, "valid": [0, 60]},
                  "heat_capacity": 1.8}}, r"C2"),
    ({"thermal": {"shift": {"law": "wlf", "C1": 8.0, "C2": 100.0, "reference": 21.2, "valid": 5},
                  "heat_capacity": 1.8}}, r"valid must be \[low, high\]"),
    ({"thermal": {"shift": "isd110-loss-peak", "heat_capacity": 0.0}}, r"heat_capacity must be > 0"),
    ({"thermal": {"shift": "isd110-loss-peak", "heat_capacity": 1.8, "cooling": 5}},
     r"unknown walls thermal keys \['cooling'\]"),
    ({"thermal": 3}, r"walls thermal must be a table"),
    ({"limits": {"strain": 0.0}}, r"strain must be > 0, got 0.0"),
    ({"limits": {"residual": 1.0}}, r"residual must lie in \[0, 1\)"),
    ({"limits": {"rupture": 8.5}}, r"unknown walls limits keys \['rupture'\]"),
    ({"limits": {}}, r"limits need a strain, stress or temperature limit, got none"),
    ({"limits": {"source": "a source"}}, r"limits need a strain, stress or temperature limit, got none"),
    ({"stories": []}, r"walls stories must be 'all' or a list of distinct story numbers, got \[\] \(no story\)"),
    # Kelvin typed where degC is meant; a temperature limit on a wall that never heats; cooling by a word unknown.
    ({"thermal": {"shift": "isd110-loss-peak", "heat_capacity": 1.8, "temperature": 294.15}},
     r"temperature 294.15 degC is above 200 degC.*subtract 273.15"),
    ({"thermal": {"shift": {"law": "arrhenius", "activation_energy": 2e5, "reference": 294.15,
                            "valid": [273.15, 323.15]}, "heat_capacity": 1.8}}, r"reference 294.15 degC is above 200"),
    ({"limits": {"temperature": 80.0}}, r"needs a wall with a thermal description"),
    ({"thermal": {"shift": "isd110-loss-peak", "heat_capacity": 1.8, "cooling_time": "fast"}},
     r"cooling_time must be a time in s or \"conduction\""),
])
def test_malformed_wall_tables_are_refused_naming_the_key(wall, match):
    with pytest.raises(ValueError, match=match):
        building_from_dict(base(**wall))


def test_conduction_cooling_is_each_wall_s_own_conduction_time():
    # Reference: h^2 / (pi^2 kappa), kappa = 0.1 mm^2/s, by hand for each wall's layer thickness.
    data = {"masses": [100.0, 100.0], "stiffnesses": [1e5, 1e5], "walls": [{
        "stories": "all", "parameters": "fitted-300", "thickness": [8.29, 2.37],
        "thermal": {"shift": "isd110-loss-peak", "heat_capacity": 1.8, "cooling_time": "conduction"}}]}
    walls = building_from_dict(data).wall_list
    for (_, wall), thickness in zip(walls, (8.29, 2.37), strict=True):
        assert wall.thermal.cooling_time == pytest.approx(thickness**2 / (math.pi**2 * 0.1), rel=1e-14)
