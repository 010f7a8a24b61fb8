"""Building files (vdw_frames.config): what they may hold, one ValueError for anything malformed, encodings,
and the strain-compatible settings of strain-dependent walls."""

from __future__ import annotations

import json
import re
import warnings

import numpy as np
import pytest
from builders import README_WALL, replace_somewhere, three_story_spec, write_file
from hypothesis import given, settings
from hypothesis import strategies as st
from shared_data import shared_record

from vdw_frames import FDMKDamper, ShearBuilding, cli, paper
from vdw_frames.config import building_from_dict, load_analysis, load_building
from vdw_frames.element.thermal import ISD110_LOSS_PEAK, ThermalProperties
from vdw_frames.frame import StrainCompatibleOptions
from vdw_frames.motion import default_record_path


@pytest.mark.parametrize("data, match", [
    ({"masses": 5, "stiffnesses": [1.0]}, "masses must be a list"),
    ({"masses": [1.0], "stiffnesses": [1.0], "walls": 5}, "walls must be a list"),
    ({"masses": [1.0], "stiffnesses": [1.0], "damping_modes": 5}, "damping_modes must be a list"),
    ({"masses": [1.0, 1.0], "stiffnesses": [1.0, 1.0], "walls": [{"stories": [1, 1], "parameters": "fitted-300"}]},
     "distinct story numbers"),
    ({"masses": [1.0]}, "missing key 'stiffnesses'"),
    ({"masses": [1.0], "stiffnesses": [1.0], "floors": 1}, "unknown building keys"),
    ({"masses": [1.0], "stiffnesses": [1.0], "walls": [{"parameters": "fitted-999"}]}, "strain must be one of"),
    ({"masses": [1.0], "stiffnesses": [1.0], "walls": [{"parameters": {"G1": 1.0}}]}, "walls parameters"),
    ({"masses": [1.0], "stiffnesses": [1.0], "walls": [{"parameters": "fitted-300", "per_story": 0}]}, "per_story"),
])
def test_building_file_validation(data, match):
    with pytest.raises(ValueError, match=match):
        building_from_dict(data)


def test_wall_stories_are_whole_numbers_given_once_each():
    spec = three_story_spec()
    spec["walls"] = [{"stories": [1, 1.0], "parameters": dict(README_WALL)}]
    with pytest.raises(ValueError, match=r"distinct story numbers, got \[1, 1.0\]"):
        building_from_dict(spec)
    spec["walls"] = [{"stories": [1.0], "parameters": dict(README_WALL)}]
    as_float = building_from_dict(spec)
    spec["walls"] = [{"stories": [1], "parameters": dict(README_WALL)}]
    assert as_float.wall_list == building_from_dict(spec).wall_list == [(1, FDMKDamper(**README_WALL))]
    spec["walls"] = [{"stories": [1], "per_story": 10**18, "parameters": dict(README_WALL)}]
    with pytest.raises(ValueError, match="per_story must be at most 1000, got 1000000000000000000"):
        building_from_dict(spec)  # refused, not a list of 10^18 walls
    for stories in ([1.5], [True], ["1"], [0], [4], {"1": 1}, 1):
        spec["walls"] = [{"stories": stories, "parameters": dict(README_WALL)}]
        with pytest.raises(ValueError, match="stor"):
            building_from_dict(spec)


json_values = st.recursive(st.none() | st.booleans() | st.floats() | st.integers() | st.text(max_size=5),
                           lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=5), inner,
                                                                                         max_size=3), max_leaves=8)


@settings(max_examples=300, deadline=None)
@given(path=st.lists(st.integers(0, 10), min_size=1, max_size=4), value=json_values)
def test_any_malformed_building_is_a_value_error(path, value):
    spec = replace_somewhere(three_story_spec(), path, value)
    try:
        building = building_from_dict(spec)
    except ValueError:
        return
    assert isinstance(building, ShearBuilding)


@settings(max_examples=100, deadline=None)
@given(text=st.one_of(json_values.map(json.dumps), st.text(max_size=40)), suffix=st.sampled_from([".json", ".toml"]))
def test_any_building_file_text_is_a_value_error_naming_the_file_or_a_building(tmp_path_factory, text, suffix):
    path = tmp_path_factory.mktemp("building") / f"b{suffix}"
    path.write_text(text, encoding="utf-8")
    try:
        assert isinstance(load_building(path), ShearBuilding)
    except ValueError as error:
        assert str(error).startswith(str(path))


def test_building_files_may_start_with_a_bom_and_must_be_utf8(tmp_path, capsys):
    spec = json.dumps(three_story_spec())
    assert load_building(write_file(tmp_path, "bom.json", b"\xef\xbb\xbf" + spec.encode())).stories == 3
    toml = "\ufeffmasses = [300.0]\nstiffnesses = [2e5]\n"
    assert load_building(write_file(tmp_path, "bom.toml", toml.encode("utf-8"))).stiffnesses == (2e5,)
    latin = write_file(tmp_path, "latin1.toml",
                       "# b\xe2timent\nmasses = [300.0]\nstiffnesses = [2e5]\n".encode("latin-1"))
    assert cli.main(["simulate", str(latin), "--record", str(default_record_path())]) == 2
    assert f"{latin}: not UTF-8 text (byte 0xe2 at position 3); save it as UTF-8" in capsys.readouterr().err


# ---------------------------------------------------------------------------------------------- strain-dependent
def strain_dependent_building_data(**extra):
    data = {"masses": [600.0, 450.0], "stiffnesses": [3e5, 2e5], "story_heights": [4000.0, 3500.0],
            "walls": [{"stories": "all", "parameters": "strain-dependent", "area": 0.5e6, "thickness": 10.0}]}
    data.update(extra)
    return data


@pytest.mark.records
def test_building_files_with_strain_dependent_walls(tmp_path, capsys):
    path = tmp_path / "walls.toml"
    path.write_text('masses = [600.0, 450.0]\nstiffnesses = [3e5, 2e5]\nstrain_compatible = true\n\n'
                    '[[walls]]\nstories = "all"\nparameters = "strain-dependent"\narea = 0.5e6\n')
    building, options = load_analysis(path)
    assert options == {"strain_compatible": True}
    assert [w for _, w in building.wall_list] == [paper.strain_dependent(area=0.5e6)] * 2
    record = str(shared_record("elCentro.AT2"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        assert cli.main(["simulate", str(path), "--record", record, "--pga", "0.8"]) == 0
    out = capsys.readouterr().out
    assert "strain-compatible analysis converged in" in out and "story 1 " in out
    # A table of settings, in JSON.
    table = tmp_path / "walls.json"
    table.write_text(json.dumps(strain_dependent_building_data(
        strain_compatible={"effective_strain_ratio": 1.0, "max_iterations": 5})))
    assert load_analysis(table)[1] == {"strain_compatible": StrainCompatibleOptions(effective_strain_ratio=1.0,
                                                                                    max_iterations=5)}
    # Strain-dependent walls without the key: the time-history analysis, the walls following their amplitude.
    bare = tmp_path / "bare.json"
    bare.write_text(json.dumps(strain_dependent_building_data()))
    assert load_analysis(bare)[1] == {}
    assert load_building(bare).strain_dependent
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        assert cli.main(["simulate", str(bare), "--record", record]) == 0
    assert "strain-compatible" not in capsys.readouterr().out


@pytest.mark.parametrize("value, match", [
    ("yes", "strain_compatible must be true, false or a table"),
    ({"ratio": 0.5}, r"unknown strain_compatible keys \['ratio'\]"),
    ({"effective_strain_ratio": 2.0}, r"effective_strain_ratio must lie in \(0, 1\]"),
])
def test_building_file_strain_compatible_validation(value, match):
    with pytest.raises(ValueError, match=match):
        building_from_dict(strain_dependent_building_data(strain_compatible=value))


def test_a_strain_compatible_table_cannot_ask_for_unbounded_work(tmp_path, capsys):
    # A 12-line file asking for 1e9 analyses and a tolerance no double can meet: one error line, exit 2,
    # before any analysis runs.
    path = tmp_path / "loop.toml"
    path.write_text('masses = [10, 10]\nstiffnesses = [20000, 20000]\nstory_heights = [3000, 3000]\n'
                    '[strain_compatible]\ntolerance = 0.01\nmax_iterations = 1000000000\n'
                    '[[walls]]\nstories = "all"\narea = 10000\nthickness = 2\nparameters = "strain-dependent"\n')
    assert cli.main(["simulate", str(path), "--record", str(default_record_path())]) == 2
    error = capsys.readouterr().err
    assert "max_iterations = 1000000000 exceeds 200" in error and len(error.strip().splitlines()) == 1
    path.write_text(path.read_text().replace("max_iterations = 1000000000", "max_iterations = 20")
                    .replace("tolerance = 0.01", "tolerance = 1e-300"))
    with pytest.raises(ValueError, match=r"tolerance = 1e-300 is below 1e-12"):
        load_analysis(path)


# ---------------------------------------------------------------------------------------------- keys and lengths
@pytest.mark.parametrize("text, key", [
    ('{"masses": [1.0], "stiffnesses": [1.0], "masses": [2.0]}', "masses"),
    ('{"masses": [1.0], "stiffnesses": [1.0], "walls": [{"parameters": "fitted-300", "area": 1e5, "area": 2e5}]}',
     "area"),
])
def test_a_json_key_given_twice_is_refused_naming_it(tmp_path, text, key):
    path = write_file(tmp_path, "twice.json", text)
    assert json.loads(text)  # json alone keeps the last value silently
    with pytest.raises(ValueError) as error:
        load_building(path)
    assert str(error.value) == (f"{path}: the key {key!r} is given twice in one JSON object (which one is meant? "
                                "json would keep the last silently)")


@pytest.mark.parametrize("table, message", [
    ({"site": {"sms": 1.5, "sm1": 0.9, "tl": 8.0, "riskcategory": "II"}}, "unknown site keys ['riskcategory']"),
    ({"verification": {"bounds": [0.8, 1.2], "bound_source": "x"}}, "unknown verification keys ['bound_source']"),
])
def test_site_and_verification_tables_are_checked_on_every_load(tmp_path, table, message):
    spec = dict(three_story_spec(), **table)
    path = write_file(tmp_path, "typo.json", json.dumps(spec))
    for load in (load_building, load_analysis):
        with pytest.raises(ValueError, match=re.escape(message)):
            load(path)


def test_a_list_of_the_wrong_length_is_named_before_the_walls():
    spec = {"masses": [100.0] * 3, "stiffnesses": [1e5] * 4, "walls": [{"parameters": "fitted-300", "area": [1e6] * 4}]}
    with pytest.raises(ValueError) as error:
        building_from_dict(spec)
    assert str(error.value) == "stiffnesses must give one value per story: masses gives 3 stories, stiffnesses 4 values"
    for key in ("story_heights", "gravity_loads"):
        spec = dict(three_story_spec(), **{key: [1e3, 1e3]})
        with pytest.raises(ValueError, match=f"{key} must give one value per story: masses gives 3 stories, {key} 2"):
            building_from_dict(spec)


@pytest.mark.parametrize("cooling", [[1.0, 2.0], np.array([1.0, 2.0])])
def test_a_cooling_time_that_is_not_one_number_is_named(cooling):
    with pytest.raises(ValueError, match=r"^cooling_time must be a time in s, got "):
        ThermalProperties(ISD110_LOSS_PEAK, 1.8, cooling_time=cooling)
    spec = dict(three_story_spec())
    spec["walls"] = [{"parameters": "fitted-300", "thermal": {"shift": "isd110-loss-peak", "heat_capacity": 1.8,
                                                              "cooling_time": [1.0, 2.0]}}]
    with pytest.raises(ValueError, match=r"^cooling_time must be a time in s, got \[1.0, 2.0\]"):
        building_from_dict(spec)


def test_reading_a_building_file_imports_neither_the_paper_nor_scipy_optimize(tmp_path):
    """The parameter catalogue lives with the element (vdw_frames.element.catalogue); the paper's modules
    re-export the same objects under their old names."""
    import os
    import subprocess
    import sys

    from shared_data import REPO

    from vdw_frames.element import catalogue
    from vdw_frames.paper import data, strain_dependence

    path = write_file(tmp_path, "walls.json", json.dumps(three_story_spec()))
    code = ("import sys; from vdw_frames.config import load_building; load_building(sys.argv[1]); "
            "print(sorted(m for m in sys.modules if m.startswith(('vdw_frames.paper', 'scipy.optimize'))))")
    done = subprocess.run([sys.executable, "-c", code, str(path)], capture_output=True, text=True, check=True,
                          env={**os.environ, "PYTHONPATH": str(REPO)})
    assert done.stdout == "[]\n"
    assert paper.fitted is data.fitted is catalogue.fitted and data.FITTED is catalogue.FITTED
    assert strain_dependence.strain_dependent is paper.strain_dependent is catalogue.strain_dependent
    assert strain_dependence.STRAIN_DEPENDENT_COMMON is catalogue.STRAIN_DEPENDENT_COMMON
    assert paper.fitted(300) == catalogue.fitted(300.0)
