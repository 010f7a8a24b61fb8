"""verify runs its analyses as lanes (vdw_frames.frame.lanes): the result equals, field by field, the one the
analyses run one by one through simulate give -- the simulate-based path verify took before 0.3.0, written out
here: per analysis ``_summary(simulate(...))`` (wall_peaks, device_peaks and unacceptable_reasons of the full
histories).

Reference: simulate, the single analysis (itself checked against OpenSees, closed forms and the frequency domain
in tests/frame and tests/element).  Tolerance: none.  A lane runs simulate's own compiled step and its wall
demands are formed in the operations wall_peaks applies to the histories (numpy.gradient's differences,
numpy.cumsum's running sum of trapezoids), so every array is compared with np.array_equal and every text with ==.

The frame: four stories; two identical walls that heat (one group of the kernel, each half its area) beside a
nonlinear fluid viscous damper, a heating wall that fails at a strain limit, a wall beside a friction damper, a
thinner wall with a narrow identified range; records of 4.6-8 s (all within the exact memory's 2048 steps)."""

import concurrent.futures
import dataclasses
import importlib
import warnings

import numpy as np
import pytest
from shared_data import REPO
from verification_cases import r1_wall, synthetic_records

from vdw_frames import FluidViscousDamper, FrictionDamper, GroundMotion, ShearBuilding, _warnings, read_at2, simulate
from vdw_frames._parallel import Collected, reissue
from vdw_frames.element import ThermalProperties, WallLimits
from vdw_frames.element.thermal import ISD110_LOSS_PEAK
from vdw_frames.frame import NewtonRaphson
from vdw_frames.frame.lanes import run_lanes
from vdw_frames.verification import Site
from vdw_frames.verification.verify import PropertyBounds, verify

verify_module = importlib.import_module("vdw_frames.verification.verify")  # the package's name is the function

SITE = Site(1.5, 0.9, 8.0)
HEAT = ThermalProperties(ISD110_LOSS_PEAK, 1.8, 21.2)


def four_story(strain_limit: float = 4.5) -> ShearBuilding:
    hot = dataclasses.replace(r1_wall(), thermal=HEAT)
    weak = dataclasses.replace(r1_wall(), thermal=HEAT, limits=WallLimits(strain=strain_limit))
    thin = dataclasses.replace(r1_wall(0.8), thickness=8.0, area=1.6e5, strain_range=(0.5, 2.2))
    return ShearBuilding(masses=(100.0, 100.0, 90.0, 80.0), stiffnesses=(1.2e5, 1.1e5, 1.0e5, 0.8e5),
                         damping_ratio=0.03, story_heights=(3500.0, 3200.0, 3200.0, 3200.0),
                         devices={1: [hot, hot, FluidViscousDamper(300.0, 0.5, stiffness=5e4)], 2: weak,
                                  3: [r1_wall(), FrictionDamper(2e4, 6e4)], 4: thin})


def one_by_one(variants, suite, *, collapse_drift_ratio, valid_drift_ratio, executor, progress, cases):
    """verify's analyses as it ran them before 0.3.0: one simulate each, its summary from the full histories,
    its package warnings re-issued once, naming the record and the case (the old _run_all)."""
    collected = {}
    for c, variant in enumerate(variants):
        for r, (motion, factor) in enumerate(zip(suite.motions, suite.factors, strict=True)):
            with _warnings.collect() as caught:
                result = simulate(variant, motion.scaled(float(factor)), collapse_drift_ratio=collapse_drift_ratio)
                summary = verify_module._summary(result, valid_drift_ratio)
            collected[(c, r)] = Collected(summary, tuple(caught))
    reissue(collected, lambda key: f"{suite.motions[key[1]].name} ({cases[key[0]][0]})", stacklevel=3)
    return {key: each.value for key, each in collected.items()}


def assert_equal(lanes, reference, where="result"):
    """Every field of two results equal: arrays with np.array_equal (NaN where NaN), the rest with ==."""
    if dataclasses.is_dataclass(reference) and not isinstance(reference, type):
        assert type(lanes) is type(reference), where
        for item in dataclasses.fields(reference):
            assert_equal(getattr(lanes, item.name), getattr(reference, item.name), f"{where}.{item.name}")
    elif isinstance(reference, dict):
        assert lanes.keys() == reference.keys(), where
        for key in reference:
            assert_equal(lanes[key], reference[key], f"{where}[{key!r}]")
    elif isinstance(reference, np.ndarray):
        assert lanes.dtype == reference.dtype, where
        assert np.array_equal(lanes, reference, equal_nan=reference.dtype.kind == "f"), where
    elif isinstance(reference, (tuple, list)):
        assert len(lanes) == len(reference), where
        for i, (got, want) in enumerate(zip(lanes, reference, strict=True)):
            assert_equal(got, want, f"{where}[{i}]")
    else:
        assert lanes == reference, where


def caught_verify(building, records, **options):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = verify(building, SITE, records, bounds=PropertyBounds(0.8, 1.25), progress=False, **options)
    return result, [(w.category, str(w.message)) for w in caught]


@pytest.mark.slow  # compiles the lanes for the frame's devices (tens of seconds, cold); then about 5 s
def test_verify_on_lanes_equals_verify_on_simulate_field_by_field(monkeypatch):
    """The same verification on lanes (a thread pool of 2) and one simulate at a time: a suite of 12 records
    (two of other lengths, one of another dt), scaled; a low collapse limit makes the strongest analyses
    collapse, the model's validity limit flags others, the weak wall fails in some, the thin one goes beyond its
    identified strains (warnings).  Every table, statistic, demand, reason and warning equal."""
    records = synthetic_records(12, 5.0)
    records[3] = GroundMotion(records[3].acceleration[:461], 0.01, records[3].name)
    records[7] = GroundMotion(records[7].acceleration[:481], 0.01, records[7].name)
    kt = read_at2(REPO / "vdw_frames" / "motion" / "data" / "synthetic_kt_035g.AT2")
    records[5] = GroundMotion(kt.acceleration[:800:2], 0.02, "synthetic kt (every other value)")
    building = four_story()
    options = dict(count=12, collapse_drift_ratio=0.017, valid_drift_ratio=0.013)
    with concurrent.futures.ThreadPoolExecutor(2) as executor:
        lanes, lanes_warned = caught_verify(building, records, executor=executor, **options)
    monkeypatch.setattr(verify_module, "_run_all", one_by_one)
    reference, reference_warned = caught_verify(building, records, **options)
    assert_equal(lanes, reference)
    assert lanes_warned == reference_warned and any("outside the range" in text for _, text in reference_warned)
    # The case exercises what it says: collapses, other unacceptable responses, failed walls, heat, both dts.
    reasons = [reason for case in reference.unacceptable for reason in case]
    assert reference.collapsed.any() and not reference.collapsed.all()
    assert any("beyond the model's validity" in r and "collapse" not in r for r in reasons)
    assert any("wall(s) 3 (strain) failed" in r for r in reasons) and any(r == "" for r in reasons)
    assert any("wall(s) 5 strained beyond their identified range" in r for r in reasons)
    assert np.isfinite(reference.wall_peaks["temperature_rise"][:, :, :3]).all()
    assert np.isnan(reference.wall_peaks["temperature_rise"][:, :, 3:]).all()
    assert len({motion.dt for motion in reference.suite.motions}) == 2
    assert (reference.device_peaks["force"] > 0).all()


@pytest.mark.slow  # compiles the lanes for the frame's devices (tens of seconds, cold); then about 2 s
def test_a_lane_s_summary_equals_simulate_s_when_it_fails_to_converge_collapses_or_its_wall_fails():
    """verify's summary of a lane (_lane_summary) against that of simulate's result (_summary) of the same
    analysis: converged, collapsed, a wall failed mid-record, and every analysis stopped by Newton-Raphson
    settings that cannot converge (the friction damper makes the frame nonlinear)."""
    building = four_story(strain_limit=2.0)
    kt = read_at2(REPO / "vdw_frames" / "motion" / "data" / "synthetic_kt_035g.AT2")
    motions = [GroundMotion(kt.acceleration[:n], kt.dt, f"kt ({n} values)") for n in (500, 500, 420, 500)]
    scales = [0.5, 2.5, 4.0, 9.0]
    hopeless = NewtonRaphson(displacement_tolerance=1e-300, force_tolerance=1e-300, max_iterations=1,
                             fallback_iterations=1)
    outcomes = set()
    for newton in (None, hopeless):
        lanes = run_lanes(building, motions, scales, collapse_drift_ratio=0.03, newton=newton, wall_demands=True)
        for lane, motion, scale in zip(lanes, motions, scales, strict=True):
            with _warnings.collect() as caught:
                result = simulate(building, motion.scaled(scale), collapse_drift_ratio=0.03, newton=newton)
            assert lane.warnings == tuple(caught)
            summary = verify_module._summary(result, 0.02)
            assert_equal(verify_module._lane_summary(building, lane, 0.02), summary, f"x {scale}")
            outcomes.add((result.collapsed, result.converged, bool(result.wall_failed.any())))
            outcomes.add(summary["reasons"])
    assert {(False, True, False), (False, True, True), (True, True, True), (False, False, False)} <= outcomes
    assert "non-convergence" in outcomes


@pytest.mark.slow  # compiles the lanes for the frame's devices (tens of seconds, cold); then well under 1 s
def test_an_analysis_that_overflows_fails_with_simulate_s_message_the_others_of_its_batch_run():
    """A record of 1e160 mm/s^2 overflows the energies: verify's batch raises simulate's own ValueError, named by
    the analysis's label as verify named it (fan_out prefixes "verify: "); alone, the record beside it runs."""
    t = np.arange(300) * 0.01
    huge = GroundMotion(1e160 * np.sin(2 * np.pi * t), 0.01, "huge")
    calm = GroundMotion(300.0 * np.sin(2 * np.pi * t), 0.01, "calm")
    building = four_story()
    with pytest.raises(ValueError) as expected, _warnings.collect():  # its warnings before the error: not ours
        simulate(building, huge)
    batch = verify_module._Batch(building, (calm, huge), (1.0, 1.0), ("calm (nominal)", "huge (nominal)"), 0.1, None)
    with pytest.raises(ValueError) as raised:
        batch.run()
    assert str(raised.value) == f"the analysis of huge (nominal) failed: {expected.value}"
    assert "energy histories overflowed" in str(expected.value)
    (summary, caught), = verify_module._Batch(building, (calm,), (1.0,), ("calm (nominal)",), 0.1, None).run()
    with _warnings.collect() as issued:
        assert_equal(summary, verify_module._summary(simulate(building, calm), None))
    assert caught == tuple(issued)
