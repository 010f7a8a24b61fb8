"""Every public constructor and every reader under hostile input (hypothesis): bad input is a ValueError,
never another exception, never an object holding NaN or inf, and never slow (a deadline on each example).

Constructors: those of ``vdw_frames.__all__`` and the input dataclasses of the sub-packages (shift laws,
thermal descriptions, wall limits, memories, discretisations, Prony series, wall banks and states,
hysteresis states, Newton and strain-compatible settings, fragilities, frame states, sites, seismic systems, bounds,
collapse criteria, search settings, record metadata).  Each example replaces one or two arguments of a
valid call by a hostile value: NaN, inf, huge, subnormal and negative numbers, huge integers, bools,
strings, bytes, None, complex numbers, numpy scalars and arrays of any shape, lists of mixed content,
foreign objects.  Readers: ``read_at2`` and ``read_two_column`` on generated and arbitrary text with
hostile arguments, and ``config.load_building``, ``load_analysis`` and ``load_verification`` on building
files with a hostile value anywhere and on arbitrary text.

``VDW_FUZZ_EXAMPLES=2000 python -m pytest tests/test_fuzz_constructors.py`` fuzzes harder than the
default (200 examples a constructor, 300 a reader: about 15 s in all).
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import tempfile
from datetime import timedelta
from pathlib import Path

import numpy as np
import pytest
from builders import TABLE4, replace_somewhere
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import vdw_frames
from vdw_frames import (
    Bilinear,
    BoucWen,
    FDMKDamper,
    FluidViscousDamper,
    FrictionDamper,
    GroundMotion,
    ShearBuilding,
    StrainDependentDamper,
    SupportedDamper,
    ThermalProperties,
    WallLimits,
    read_at2,
    read_two_column,
)
from vdw_frames import config as building_files
from vdw_frames.asce7 import SeismicSystem
from vdw_frames.assessment import CollapseCriterion, HuntAndFill
from vdw_frames.element import (
    ISD110_LOSS_PEAK,
    WLF,
    Arrhenius,
    DampedTwoStep,
    FastMemory,
    LogLinear,
    PronySeries,
    WallBank,
    WallState,
)
from vdw_frames.frame import Fragility, NewtonRaphson, StrainCompatibleOptions
from vdw_frames.frame.hysteresis import StoryState
from vdw_frames.frame.results import FrameState
from vdw_frames.motion import RecordMetadata
from vdw_frames.paper import strain_dependent
from vdw_frames.verification import PropertyBounds, Site

EXAMPLES = int(os.environ.get("VDW_FUZZ_EXAMPLES", "200"))
# The deadline is per example and generous (a loaded 2-core machine): a constructor takes microseconds to
# milliseconds, a reader a few milliseconds; what it catches is work that grows without bound.
FUZZ = settings(max_examples=EXAMPLES, deadline=timedelta(seconds=5),
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                       HealthCheck.function_scoped_fixture])
READERS = settings(FUZZ, max_examples=int(1.5 * EXAMPLES))


class Foreign:
    """An object of no type the package knows."""

    def __repr__(self) -> str:
        return "Foreign()"


ODD = [math.nan, math.inf, -math.inf, 1e308, -1e308, 5e-324, -0.0, 0.0, 2**63, -(2**63), 10**400,
       np.float64("nan"), np.float32(1e30), np.float16(1.0), np.int64(-1), np.uint8(3), np.bool_(True),
       np.array(1.5), np.array([1.0, 2.0]), np.array([[1.0]]), np.array([]), np.array(["a"]), np.array([1 + 1j]),
       Foreign(), [], (), {}, [1.0, "x"], [[1.0], [2.0, 3.0]], [math.nan], (1.0, 2.0, 3.0), {"a": 1}, "", "1.0",
       b"1", 1j, True, False, None]
HOSTILE = st.one_of(
    st.sampled_from(ODD),
    st.floats(),
    st.floats(-10.0, 10.0),
    st.integers(-(2**70), 2**70),
    st.integers(-3, 3),
    st.text(max_size=6),
    st.complex_numbers(max_magnitude=10.0),
    st.lists(st.one_of(st.floats(), st.integers(-5, 5), st.text(max_size=2), st.none()), max_size=4),
    st.tuples(st.floats(), st.floats()),
)

WALL = FDMKDamper(**TABLE4, area=1e5, thickness=10.0)
STRAIN_DEPENDENT = strain_dependent()
THERMAL = ThermalProperties(ISD110_LOSS_PEAK, 1.8, 21.2, 600.0)


def frame_state() -> dict:
    return dict(step=2, dt=0.01, displacement=[1.0, 2.0], velocity=[0.0, 1.0], acceleration=[0.5, 0.0],
                drift=[[0.0, 0.0], [0.5, 0.5], [1.0, 1.0]])


# name: (constructor, the arguments of a valid call)
CONSTRUCTORS = {
    "Bilinear": (Bilinear, dict(yield_force=1e5, hardening=0.02)),
    "BoucWen": (BoucWen, dict(yield_force=1e5, hardening=0.02, exponent=2.0, beta=0.6, gamma=0.4)),
    "FDMKDamper": (FDMKDamper, dict(**TABLE4, area=1e5, thickness=10.0, strain_range=(2.25, 4.5), thermal=THERMAL,
                                    limits=WallLimits(strain=8.5))),
    "FluidViscousDamper": (FluidViscousDamper, dict(C=2000.0, alpha=0.5, stiffness=1e5, magnification=0.9)),
    "FrictionDamper": (FrictionDamper, dict(slip_force=2e5, stiffness=8e4, magnification=1.2)),
    "GroundMotion": (GroundMotion, dict(acceleration=[0.0, 100.0, -50.0, 0.0], dt=0.01, name="x", metadata=None)),
    "ShearBuilding": (ShearBuilding, dict(masses=[500.0, 400.0], stiffnesses=[6e5, 4e5], damping_ratio=0.05,
                                          damping_modes=(1, 2),
                                          devices={1: [WALL, FluidViscousDamper(2e3, 0.5, 1e5)],
                                                   2: FrictionDamper(2e5, 8e4)},
                                          story_heights=[3000.0, 3000.0],
                                          hysteresis=[Bilinear(1e5), None], gravity_loads=[1e6, 5e5],
                                          damping_model="rayleigh")),
    "StrainDependentDamper": (StrainDependentDamper, {field.name: getattr(STRAIN_DEPENDENT, field.name)
                                                      for field in dataclasses.fields(STRAIN_DEPENDENT)}),
    "SupportedDamper": (SupportedDamper, dict(damper=WALL, support_stiffness=1e5)),
    "ThermalProperties": (ThermalProperties, dict(shift=ISD110_LOSS_PEAK, heat_capacity=1.8, temperature=21.2,
                                                  cooling_time=600.0)),
    "WallLimits": (WallLimits, dict(strain=8.5, stress=2.0, temperature=80.0, residual=0.1, source="a test")),
    "WLF": (WLF, dict(C1=8.0, C2=120.0, reference=21.2, valid=(0.0, 60.0), source="a test")),
    "Arrhenius": (Arrhenius, dict(activation_energy=2e5, reference=21.2, valid=(0.0, 60.0), source="a test")),
    "LogLinear": (LogLinear, dict(degrees_per_decade=19.45, reference=21.2, valid=(0.0, 70.0), source="a test")),
    "DampedTwoStep": (DampedTwoStep, dict(rho_infinity=0.5)),
    "FastMemory": (FastMemory, dict(tolerance=1e-10, window=16, max_steps=2**20, exact_below=2048)),
    "PronySeries": (PronySeries, dict(equilibrium_stiffness=1.0, branches=[[1.0, 0.1]], f_min=0.1, f_max=10.0,
                                      tolerance=0.01, error=0.005)),
    "WallBank": (WallBank, dict(walls=(WALL,), dt=0.01, steps=100, method=DampedTwoStep(), memory="exact")),
    "WallState": (WallState, dict(damper=WALL, dt=0.01, method="damped", memory="exact")),
    "StoryState": (StoryState, dict(model=Bilinear(1e3), stiffness=1e3)),
    "Fragility": (Fragility, dict(median=0.5, dispersion=0.4)),
    "NewtonRaphson": (NewtonRaphson, dict(displacement_tolerance=1e-8, force_tolerance=1e-9, max_iterations=25,
                                          fallback_iterations=200)),
    "StrainCompatibleOptions": (StrainCompatibleOptions, dict(effective_strain_ratio=0.65, initial_strain=3.0,
                                                              tolerance=0.01, max_iterations=20)),
    "FrameState": (FrameState, frame_state()),
    "Site": (Site, dict(sms=1.5, sm1=0.9, tl=8.0, risk_category="II", ss=1.25, s1=0.6, site_class="C", fa=1.2,
                        fv=1.5)),
    "SeismicSystem": (SeismicSystem, dict(key="steel-smf", name="Steel special moment frames",
                                          table_row="Table 12.2-1 row C.1", r=8.0, omega0=3.0, cd=5.5,
                                          height_limits_ft={"B": None, "C": None, "D": 160.0, "E": 100.0, "F": 0.0},
                                          ct=0.028, x=0.8, period_row="Table 12.8-2", moment_frame=True)),
    "PropertyBounds": (PropertyBounds, dict(lower=0.8, upper=1.2, source="a test")),
    "CollapseCriterion": (CollapseCriterion, dict(drift_ratio=0.1, non_convergence=True, wall_failure=False)),
    "HuntAndFill": (HuntAndFill, dict(start=0.1, cap=5.0, growth=1.8, tolerance=0.02, fill_ratio=1.1, max_runs=12)),
    "RecordMetadata": (RecordMetadata, dict(record_set="far-field", record_id=1, record_sequence_number=953,
                                            event="Northridge", year=1994, station="Beverly Hills", component="MUL009",
                                            magnitude=6.7, distance=17.2, joyner_boore_distance=9.4, site_class="D",
                                            fault_type="Thrust", normalization_factor=0.65, normalized=False,
                                            pulse=None)),
}
# Fields that may hold inf by design: an adiabatic wall never cools.
INFINITE_ALLOWED = {("ThermalProperties", "cooling_time")}
# The compiled kernel's working arrays (sentinels such as -inf for "not yet"), not values handed out.
INTERNAL = {("WallBank", "arrays")}


def test_every_public_constructor_is_fuzzed():
    """The table above covers every class of ``vdw_frames.__all__``."""
    top = {name for name in vdw_frames.__all__ if isinstance(getattr(vdw_frames, name), type)}
    assert top <= set(CONSTRUCTORS), sorted(top - set(CONSTRUCTORS))


def test_the_valid_calls_are_valid():
    for name, (constructor, arguments) in CONSTRUCTORS.items():
        assert_finite(name, constructor(**arguments))


def assert_finite(name: str, value: object, field: str = "", depth: int = 0) -> None:
    """No NaN or inf anywhere in what a constructor returned (its fields, their fields, arrays, containers)."""
    if depth > 4 or value is None or isinstance(value, (str, bytes, bool, np.bool_)) or (name, field) in INTERNAL:
        return
    if isinstance(value, (int, np.integer)):
        return
    if isinstance(value, (float, np.floating)):
        assert math.isfinite(value) or (name, field) in INFINITE_ALLOWED, f"{name}.{field} = {value!r}"
        return
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "fc":
            assert np.isfinite(value).all(), f"{name}.{field} holds {value!r}"
        return
    if isinstance(value, (list, tuple)):
        for item in value:
            assert_finite(name, item, field, depth + 1)
        return
    if isinstance(value, dict):
        for item in value.values():
            assert_finite(name, item, field, depth + 1)
        return
    if dataclasses.is_dataclass(value):
        for item in dataclasses.fields(value):
            assert_finite(type(value).__name__, getattr(value, item.name), item.name, depth + 1)


@pytest.mark.parametrize("name", sorted(CONSTRUCTORS))
@FUZZ
@given(data=st.data())
def test_constructors_take_valid_values_or_raise_value_error(name, data):
    constructor, valid = CONSTRUCTORS[name]
    keys = data.draw(st.lists(st.sampled_from(sorted(valid)), min_size=1, max_size=2, unique=True), label="arguments")
    arguments = dict(valid)
    for key in keys:
        arguments[key] = data.draw(HOSTILE, label=key)
    try:
        made = constructor(**arguments)
    except ValueError as error:
        assert str(error)
        return
    assert_finite(name, made)


# What the fuzzing found (each passed silently, or raised TypeError, OverflowError or MemoryError, before).
FOUND = [
    ("WLF", "source", math.nan, "source must be a string, got nan"),
    ("Arrhenius", "source", 3, "source must be a string, got 3"),
    ("LogLinear", "source", None, "source must be a string, got None"),
    ("PropertyBounds", "source", math.nan, "source must be a string, got nan"),
    ("Fragility", "dispersion", math.nan, "dispersion must be finite, got nan"),
    ("Fragility", "median", 0.0, "median must be > 0, got 0.0"),
    ("PronySeries", "equilibrium_stiffness", Foreign(), "equilibrium_stiffness must be a real number"),
    ("PronySeries", "equilibrium_stiffness", math.nan, "equilibrium_stiffness must be finite"),
    ("PronySeries", "branches", Foreign(), "branches must be real numbers"),
    ("PronySeries", "branches", [1.0, 2.0, 3.0], r"branches must be an \(n, 2\) array.* got shape \(3,\)"),
    ("PronySeries", "f_max", 0.05, "f_max must exceed f_min"),
    ("RecordMetadata", "component", math.nan, "component must be a string, got nan"),
    ("RecordMetadata", "year", 10**400, None),  # a whole number, however large: accepted
    ("RecordMetadata", "normalized", "no", "normalized must be True or False, got 'no'"),
    ("RecordMetadata", "distance", -1.0, "distance must be >= 0"),
    ("FastMemory", "exact_below", 10**400, None),
    ("NewtonRaphson", "max_iterations", 10**400, None),
    ("StrainCompatibleOptions", "max_iterations", -(10**400), "max_iterations must be a whole number >= 1"),
    ("FrameState", "step", 10**400, "drift must hold step . 1 = .* rows"),
    ("WallBank", "walls", math.nan, "walls must be a sequence of walls, got float"),
    ("WallBank", "steps", 1_188_763_351, r"needs 1,188,763,351 steps, whose arrays would take"),
    ("WallBank", "steps", 1e308, r"needs 1e\+308 steps, whose arrays would take more than any memory"),
    ("WallBank", "steps", 10**400, r"needs about 1e400 steps, whose arrays would take more than any memory"),
]


@pytest.mark.parametrize("name, argument, value, match", FOUND,
                         ids=[f"{name}.{argument}-{index}" for index, (name, argument, _, _) in enumerate(FOUND)])
def test_what_the_fuzzing_found(name, argument, value, match):
    constructor, valid = CONSTRUCTORS[name]
    arguments = dict(valid, **{argument: value})
    if match is None:
        assert_finite(name, constructor(**arguments))
        return
    with pytest.raises(ValueError, match=match):
        constructor(**arguments)


def test_a_hysteresis_model_or_shift_law_that_is_not_a_name_is_a_value_error():
    # ``model = [...]`` and ``law = [...]`` raised TypeError (unhashable type: 'list') from the building file's reader.
    spec = building_spec()
    spec["hysteresis"]["model"] = []
    with pytest.raises(ValueError, match=r"hysteresis must be a table with model = 'bilinear' or 'bouc-wen'"):
        building_files.load_building(written(json.dumps(spec), "building.json"))
    spec = building_spec()
    spec["walls"][0]["thermal"]["shift"]["law"] = []
    with pytest.raises(ValueError, match=r"walls thermal shift must be one of .* or a table with law = "):
        building_files.load_building(written(json.dumps(spec), "building.json"))


# ------------------------------------------------------------------------------------------------ readers
# One folder for the module's generated files, removed when the run ends (a folder per example was left behind).
_SCRATCH = tempfile.TemporaryDirectory(prefix="vdw_fuzz_")


def written(data: bytes | str, name: str) -> Path:
    path = Path(tempfile.mkdtemp(dir=_SCRATCH.name)) / name
    path.write_bytes(data.encode("utf-8", "surrogatepass") if isinstance(data, str) else data)
    return path


def assert_record_or_value_error(read, *arguments, **options) -> None:
    try:
        motion = read(*arguments, **options)
    except ValueError as error:
        assert str(error)
        return
    assert isinstance(motion, GroundMotion)
    assert motion.acceleration.size >= 1 and np.isfinite(motion.acceleration).all()
    assert math.isfinite(motion.dt) and motion.dt > 0.0


TOKENS = st.one_of(st.sampled_from(["0.1", "-2.5E-03", ".1D+01", "1e999", "-1e-999", "nan", "inf", "NaN", "1,5",
                                    "0x10", "1_000", "--1", "+", "E", "1.2.3", "\u0661", "½", "NPTS=", "DT=", "SEC"]),
                   st.floats().map(repr), st.integers(-(10**30), 10**30).map(str), st.text(max_size=4))
HEADERS = st.sampled_from(["ACCELERATION TIME HISTORY IN UNITS OF G", "UNITS OF CM/S/S", "UNITS: M/S2",
                           "VELOCITY TIME HISTORY IN UNITS OF CM/S", "DISPLACEMENT IN CM", "IN/S/S", "",
                           "PEER NGA STRONG MOTION DATABASE RECORD"])


@st.composite
def at2_texts(draw) -> str:
    """AT2-like text: header lines (some naming units), a count line of hostile tokens, hostile values."""
    header = draw(st.lists(st.one_of(HEADERS, st.text(max_size=30)), max_size=4))
    npts, dt = draw(TOKENS), draw(TOKENS)
    count = draw(st.sampled_from([f"NPTS= {npts}, DT= {dt} SEC", f"{npts} {dt} NPTS, DT", f"NPTS={npts}",
                                  f"DT= {dt}", f"NPTS= {npts}, DT= {dt} {draw(st.sampled_from(['MS', 'S', 'MIN']))}"]))
    values = draw(st.lists(TOKENS, max_size=12))
    separator = draw(st.sampled_from([" ", "\n", ",", "\t"]))
    return "\n".join([*header, count, separator.join(values)])


@READERS
@given(text=st.one_of(at2_texts(), st.text(max_size=200)))
def test_read_at2_on_hostile_text_returns_a_record_or_a_value_error(text):
    assert_record_or_value_error(read_at2, written(text, "hostile.AT2"))


@READERS
@given(text=st.one_of(at2_texts(), st.text(max_size=120)), path=st.one_of(HOSTILE, st.just("")))
def test_read_at2_on_hostile_paths_is_a_value_error(text, path):
    if isinstance(path, str) and path:
        path = written(text, "x.AT2").parent / "missing" / path
    assert_record_or_value_error(read_at2, path)


@st.composite
def two_column_texts(draw) -> str:
    rows = draw(st.lists(st.tuples(TOKENS, TOKENS), max_size=10))
    separator = draw(st.sampled_from([" ", ",", "\t", ";"]))
    return "\n".join(f"{time}{separator}{value}" for time, value in rows)


@READERS
@given(text=st.one_of(two_column_texts(), st.text(max_size=150)),
       unit=st.one_of(st.sampled_from(["g", "mm/s2", "cm/s2", "m/s2", "in/s2", "G", "gal", "cm/s/s", ""]), HOSTILE),
       skip_rows=st.one_of(st.integers(-2, 3), HOSTILE), name=st.one_of(st.none(), st.text(max_size=8), HOSTILE))
def test_read_two_column_on_hostile_text_and_arguments_returns_a_record_or_a_value_error(text, unit, skip_rows, name):
    assert_record_or_value_error(read_two_column, written(text, "hostile.txt"), unit, skip_rows=skip_rows, name=name)


def building_spec() -> dict:
    """A building file (JSON) with every optional table: hysteresis, walls with thermal and limits, site,
    verification, strain-compatible settings."""
    return {
        "masses": [500.0, 400.0, 300.0], "stiffnesses": [6e5, 5e5, 4e5], "story_heights": [3500.0] * 3,
        "damping_ratio": 0.05, "damping_modes": [1, 2], "damping_model": "rayleigh",
        "gravity_loads": [1.2e7, 7e6, 3e6],
        "hysteresis": {"model": "bouc-wen", "yield_forces": [2e6, 1.6e6, 1e6], "hardening": 0.03, "exponent": 2.0},
        "walls": [{"stories": [1, 2], "per_story": 2, "parameters": dict(TABLE4), "area": [1e5, 2e5],
                   "thickness": 10.0,
                   "thermal": {"shift": {"law": "wlf", "C1": 8.0, "C2": 120.0, "reference": 21.2, "valid": [0, 60],
                                         "source": "a test"}, "heat_capacity": 1.8, "temperature": 21.2,
                               "cooling_time": 600.0},
                   "limits": {"strain": 8.5, "stress": 2.0, "temperature": 80.0, "residual": 0.0, "source": "x"}},
                  {"stories": "all", "parameters": "fitted-300"}],
        "site": {"sms": 1.5, "sm1": 0.9, "tl": 8.0, "risk_category": "II"},
        "verification": {"bounds": [0.8, 1.2], "bounds_source": "a test"},
    }


JSON_VALUES = st.recursive(st.none() | st.booleans() | st.floats() | st.integers(-(2**70), 2**70)
                           | st.text(max_size=5),
                           lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=5), inner,
                                                                                         max_size=3), max_leaves=6)
LOADERS = [building_files.load_building, building_files.load_analysis, building_files.load_verification]


def assert_loaded_or_value_error(path: Path) -> None:
    for load in LOADERS:
        try:
            loaded = load(path)
        except ValueError as error:
            assert str(error).startswith(str(path)), error  # the message names the file
            continue
        building = loaded[0] if isinstance(loaded, tuple) else loaded
        assert isinstance(building, ShearBuilding)
        assert_finite("building", building)
        if isinstance(loaded, tuple):
            assert_finite(load.__name__, loaded[1:])


@READERS
@given(path=st.lists(st.integers(0, 12), min_size=1, max_size=5), value=JSON_VALUES)
def test_building_files_with_a_hostile_value_anywhere_load_or_raise_value_error(path, value):
    spec = replace_somewhere(building_spec(), path, value)
    assert_loaded_or_value_error(written(json.dumps(spec), "building.json"))


@READERS
@given(text=st.one_of(st.text(max_size=80), JSON_VALUES.map(json.dumps),
                      st.sampled_from(['masses = [1e400]\nstiffnesses = [1]', 'masses = [nan]\nstiffnesses = [1]',
                                       'masses = [1]\nstiffnesses = [inf]', "masses = 1\n[site]\nsms = 'a'",
                                       'masses = [1]\nstiffnesses = [1]\n[[walls]]\nstories = "all"\n'
                                       'parameters = "fitted-1e999"'])),
       suffix=st.sampled_from([".json", ".toml", ".txt"]))
def test_arbitrary_building_file_text_loads_or_raises_value_error(text, suffix):
    assert_loaded_or_value_error(written(text, f"building{suffix}"))
