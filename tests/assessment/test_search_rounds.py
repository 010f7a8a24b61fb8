"""The records' hunt-and-fill searches advancing together in rounds (SearchGroup: each round one run_lanes call a
batch, one lane a record still searching), against each record searched alone: hunt_and_fill driving simulate one
analysis at a time (the assessment's search before the lanes).

Tolerance: none.  A lane runs simulate's own compiled step, so every run (intensity, collapsed, converged, peak drift
ratio, steps), every bracket and every warning text are compared with ==.  The records: two dt, different lengths,
one standing at the cap, one hunting down, and one beyond the walls' exact memory (FastMemory.exact_below = 2048
steps), which lane_batches keeps apart from the shorter ones of its dt when there are walls."""

from __future__ import annotations

import concurrent.futures
import os

import numpy as np
import pytest
from builders import FITTED300
from shared_data import REPO

import vdw_frames as vdw
from vdw_frames import _warnings
from vdw_frames.assessment import collapse
from vdw_frames.assessment.collapse import CollapseCriterion, RecordSearchError, SearchGroup, _run_searches
from vdw_frames.assessment.hunt_fill import HuntAndFill, Run, hunt_and_fill
from vdw_frames.frame.lanes import run_lanes

G = vdw.G
UNIT = 1.0 / G  # a record's acceleration x S_T / g
SETTINGS = HuntAndFill(start=0.3 * G, cap=2.0 * G, max_runs=6)
CRITERION = CollapseCriterion(drift_ratio=0.10)


def small_frame(walls=False):
    """3 stories, T1 = 0.69 s bare, 2 % hardening, heavy P-Delta (test_collapse_assessment's frame); ``walls``: a
    300 % wall of the paper (strain range 300 %, so a collapse run warns) in stories 1 and 2."""
    masses = np.array([100.0, 100.0, 80.0])
    weights = masses * G
    above = np.cumsum(weights[::-1])[::-1]
    wall = vdw.FDMKDamper(**FITTED300, area=0.05e6, thickness=10.0, strain_range=(2.25, 4.5))
    return vdw.ShearBuilding(masses, [4.0e4, 3.5e4, 3.0e4], story_heights=[3500.0] * 3, gravity_loads=3.0 * above,
                             hysteresis=[vdw.Bilinear(f, 0.02)
                                         for f in 0.15 * weights.sum() * np.array([1.0, 0.85, 0.55])],
                             devices={1: wall, 2: wall} if walls else None)


def ramped_sine(name, amplitude, frequency, seconds, dt):
    t = np.arange(0.0, seconds, dt)
    return vdw.GroundMotion(amplitude * np.sin(2.0 * np.pi * frequency * t) * np.minimum(t / 1.5, 1.0), dt, name)


@pytest.fixture(scope="module")
def records():
    """The shipped synthetic record's first 600 and 2100 samples (the latter beyond 2048 steps), 400 of them read at
    0.02 s, a weak sine (stands at the cap) and a strong one at 0.02 s (collapses at the start)."""
    kt = vdw.read_at2(REPO / "vdw_frames" / "motion" / "data" / "synthetic_kt_035g.AT2")
    samples = 3.0 * kt.acceleration  # about 1 g
    return [vdw.GroundMotion(samples[:600], 0.01, "kt 600"),
            vdw.GroundMotion(samples[:400], 0.02, "kt 400 at 0.02 s"),
            ramped_sine("weak", 0.02 * G, 1.2, 4.0, 0.01),
            vdw.GroundMotion(samples[:2100], 0.01, "kt 2100"),
            ramped_sine("strong", 12.0 * G, 1.0, 5.0, 0.02)]


def simulated(building, motion, settings=SETTINGS):
    """The reference: hunt_and_fill driving simulate, and the warnings of its analyses."""
    label = motion.name

    def analyse(intensity):
        result = vdw.simulate(building, motion.scaled(UNIT * intensity), collapse_drift_ratio=CRITERION.drift_ratio)
        return Run(float(intensity), CRITERION.collapsed(result, label), bool(result.converged),
                   float(np.max(result.peak_drift_ratio)), int(result.time.size))

    with _warnings.collect() as caught:
        found = hunt_and_fill(analyse, settings, label)
    return found, tuple(caught)


class SerialExecutor(concurrent.futures.Executor):
    """Every task run at once, in the caller's thread."""

    def submit(self, fn, /, *args, **kwargs):
        future = concurrent.futures.Future()
        try:
            future.set_result(fn(*args, **kwargs))
        except BaseException as error:
            future.set_exception(error)
        return future


@pytest.fixture
def lane_calls(monkeypatch):
    """The records (names) of every run_lanes call the searches make."""
    calls = []

    def counted(building, motions, scales, **options):
        calls.append(tuple(motion.name for motion in motions))
        return run_lanes(building, motions, scales, **options)

    monkeypatch.setattr(collapse, "run_lanes", counted)
    return calls


@pytest.mark.parametrize("walls", [False, True], ids=["bare", "walls"])
def test_searches_in_rounds_equal_each_record_searched_with_simulate(records, walls, lane_calls):
    building = small_frame(walls)
    grouped = SearchGroup(building, tuple(records), UNIT, CRITERION, SETTINGS).run()
    references = [simulated(building, motion) for motion in records]
    for motion, (found, caught), (reference, expected) in zip(records, grouped, references, strict=True):
        assert found == reference, motion.name  # every Run's fields, the bracket and the resolution
        assert caught == expected, motion.name  # the same warnings (category and text), in the same order
    by_name = {motion.name: found for motion, (found, _) in zip(records, grouped, strict=True)}
    assert by_name["weak"].censored and by_name["weak"].standing == SETTINGS.cap
    assert by_name["strong"].runs[0].collapsed and by_name["strong"].runs[1].intensity < SETTINGS.start  # hunted down
    bisected = by_name["kt 600"]  # hunted up to a collapse, then bisected to the tolerance
    assert not bisected.censored and bisected.collapsing / bisected.standing <= 1.0 + SETTINGS.tolerance
    assert len(bisected.runs) > 4 and bisected.runs[-1].intensity < max(run.intensity for run in bisected.runs)
    assert sum(len(found.runs) for found, _ in grouped) == sum(len(names) for names in lane_calls)
    # rounds: several records a call, never two dt (or, with walls, two sides of the exact memory) in one
    assert max(len(names) for names in lane_calls) >= 2
    dt = {motion.name: motion.dt for motion in records}
    assert all(len({dt[name] for name in names}) == 1 for names in lane_calls)
    # one dt, but the walls take the exact memory for the 600 steps and the fast one for the 2100: apart with walls
    together = any({"kt 600", "kt 2100"} <= set(names) for names in lane_calls)
    assert together is not walls
    if walls:
        assert any(expected for _, expected in references)  # the walls beyond their strain range warned


def test_any_executor_gives_the_searches_and_warnings_of_each_record_alone(records, monkeypatch, lane_calls):
    """_run_searches (the assessment's searches) with one worker counted (groups of two records): a serial executor
    and two threads give each record's simulate search, and the warning texts in record order."""
    monkeypatch.setattr(os, "cpu_count", lambda: 1)
    building = small_frame(walls=True)
    references = [simulated(building, motion) for motion in records]
    runs = []
    for executor in (SerialExecutor(), concurrent.futures.ThreadPoolExecutor(2)):
        with executor:
            runs.append(_run_searches(building, records, UNIT, CRITERION, SETTINGS, (), executor=executor,
                                      progress=False))
    assert any(len(names) > 1 for names in lane_calls)  # records advanced together
    for results, messages in runs:
        assert results == [reference for reference, _ in references]
        assert messages == [w.message for _, caught in references for w in caught]
    assert runs[0] == runs[1]


def test_a_record_that_cannot_run_fails_its_search_with_the_message_of_a_record_alone(records):
    """A record whose scaled acceleration overflows at the start (2 g x 1e308 mm/s^2): the lane's error, named as the
    one-record search named it ("collapse assessment, record 'NAME': NAME at S_T = 2 g: ...")."""
    building = small_frame()
    settings = HuntAndFill(start=2.0 * G, cap=4.0 * G, max_runs=4)
    boom = vdw.GroundMotion(np.full(300, 1.0e308), 0.01, "boom")
    lane, = run_lanes(building, [boom], [UNIT * 2.0 * G], collapse_drift_ratio=0.10)
    assert lane.error is not None and "not finite" in lane.error
    alone = f"boom at S_T = 2 g: {lane.error}"
    with pytest.raises(RecordSearchError) as caught:
        SearchGroup(building, (records[0], boom), UNIT, CRITERION, settings).run()
    assert str(caught.value) == alone and caught.value.record == "boom"
    with pytest.raises(ValueError) as caught:
        _run_searches(building, [records[0], boom], UNIT, CRITERION, settings, (), executor=SerialExecutor(),
                      progress=False)
    assert str(caught.value) == f"collapse assessment, record 'boom': {alone}"


def test_a_record_collapsing_at_no_shaking_is_refused_as_hunt_and_fill_refuses_it(records):
    """A sine of 1e5 g collapses the frame even at start / 1.8^12: the refusal of hunt_and_fill with simulate."""
    building = small_frame()
    huge = ramped_sine("huge", 1.0e5 * G, 1.0, 3.0, 0.01)
    with pytest.raises(ValueError, match="collapses even at") as refused:
        simulated(building, huge)
    with pytest.raises(ValueError) as caught:
        _run_searches(building, [records[2], huge], UNIT, CRITERION, SETTINGS, (), executor=SerialExecutor(),
                      progress=False)
    assert str(caught.value) == f"collapse assessment, record 'huge': {refused.value}"


def test_a_round_whose_lanes_together_exceed_the_memory_limit_runs_them_in_smaller_calls(records, monkeypatch,
                                                                                          lane_calls):
    """The memory limit lowered to 2 x (400 x 104 + S) bytes (S: a lane's state and result, lane_state_bytes): one
    lane of each record fits (kt 600: 600 steps x 104 bytes, the ground and two walls' exact memory, + S), and so do
    the two records at 0.02 s together (2 x (400 x 104 + S)), but not kt 600 and the weak sine (2 x (600 x 104 + S)):
    the searches run, in calls within the limit, and equal each record searched alone with simulate (computed under
    the usual limit); before, the round was refused ("split the batch") although every record alone ran."""
    from vdw_frames import _validation
    from vdw_frames.frame.lanes import lane_state_bytes

    building = small_frame(walls=True)
    references = [simulated(building, motion) for motion in records]
    state = lane_state_bytes(building)
    limit = 2 * (400 * 104 + state)
    monkeypatch.setattr(_validation, "MEMORY_LIMIT_BYTES", limit)
    grouped = SearchGroup(building, tuple(records), UNIT, CRITERION, SETTINGS).run()
    assert list(grouped) == references
    steps = {motion.name: motion.acceleration.size for motion in records}
    exact = {name: size <= 2048 for name, size in steps.items()}  # FastMemory.exact_below
    for names in lane_calls:
        bytes_per_step = 8 + (8 * 6 * 2 if exact[names[0]] else 0)
        assert len(names) * (max(steps[name] for name in names) * bytes_per_step + state) <= limit, names
    assert any(len(names) == 2 for names in lane_calls)  # the records at 0.02 s still share a call
    assert {"kt 600", "weak"} not in [set(names) for names in lane_calls]
