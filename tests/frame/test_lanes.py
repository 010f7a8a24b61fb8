"""The lanes engine (vdw_frames.frame.lanes): every lane of a batch against simulate run one by one on the same
record -- the single analysis, itself checked against OpenSees and closed forms elsewhere
(test_against_opensees.py, test_inelastic.py, test_devices_in_frames.py).

Tolerance: none.  A lane runs the single analysis's own compiled step (integrator.advance, the same operations
in the same order), so histories, peaks, collapse times, Newton counts and wall failures are compared with
np.array_equal / ==.  (The one documented exception, walls on a record within the exact memory's length batched
with a longer one, is avoided here: every wall record is longer than FastMemory.exact_below = 2048 steps.)"""

import dataclasses
import pickle
import re

import numpy as np
import pytest
from builders import example_ten_story, mixed_devices_building, tapered_sine_pair
from shared_data import REPO

from vdw_frames import FluidViscousDamper, FrictionDamper, GroundMotion, ShearBuilding, _warnings, read_at2, simulate
from vdw_frames.element.limits import WallLimits
from vdw_frames.frame import lanes as lanes_module
from vdw_frames.frame.lanes import run_lanes

HISTORIES = ("displacement", "velocity", "acceleration", "drift", "story_shear", "story_wall_force", "base_shear",
             "group_force", "group_strain", "group_temperature", "group_amplitude", "device_force",
             "device_deformation", "device_velocity")


def quiet_simulate(building, motion):
    """simulate's result, with the package warnings it issued (``result.caught``) instead of issuing them."""
    with _warnings.collect() as caught:
        result = simulate(building, motion)
    object.__setattr__(result, "caught", tuple(caught))
    return result


def shortened(motion, values):
    """The first ``values`` samples of ``motion``, as a record of its own."""
    return GroundMotion(motion.acceleration[:values], motion.dt, name=f"{motion.name} ({values})")


def assert_lane_is_simulate(lane, result):
    """Every history, peak and outcome of ``lane`` equal (bit for bit) to ``result``'s."""
    assert lane.error is None
    assert lane.warnings == result.caught  # the same warnings (category and text), in the same order
    assert lane.steps == result.time.size
    assert (lane.converged, lane.collapsed, lane.collapse_time) == (result.converged, result.collapsed,
                                                                    result.collapse_time)
    assert lane.newton_iterations == result.newton_iterations
    for name, history in lane.histories.items():
        assert np.array_equal(history, getattr(result, name)), name
    assert np.array_equal(lane.peak_drift, result.peak_drift)
    if result.peak_drift_ratio is not None:
        assert np.array_equal(lane.peak_drift_ratio, result.peak_drift_ratio)
    assert np.array_equal(lane.peak_absolute_acceleration, result.peak_absolute_acceleration)
    assert lane.peak_base_shear == result.peak_base_shear
    assert np.array_equal(lane.peak_story_wall_force, result.peak_story_wall_force)
    assert np.array_equal(lane.residual_drift, result.residual_drift)
    assert np.array_equal(lane.peak_group_strain, np.abs(result.group_strain).max(axis=0, initial=0.0))
    if result.group_temperature.size:
        assert np.array_equal(lane.peak_group_temperature, result.group_temperature.max(axis=0), equal_nan=True)
    if result.group_failure.size:
        assert np.array_equal(lane.group_failure_step, result.group_failure[:, 0])
    for name in ("force", "deformation", "velocity"):
        assert np.array_equal(getattr(lane, f"peak_device_{name}"),
                              np.abs(getattr(result, f"device_{name}")).max(axis=0, initial=0.0))


@pytest.fixture(scope="module")
def record():
    return read_at2(REPO / "vdw_frames" / "motion" / "data" / "synthetic_kt_035g.AT2")


@pytest.mark.slow  # compiles the lanes for its kind of building (tens of seconds a worker, cold)
def test_yielding_frame_with_p_delta_lanes_of_different_lengths_and_collapse_equal_simulate(record):
    """The example frame without its walls (Bilinear stories, P-Delta): an elastic-range lane, a yielding one,
    two that collapse at different times, and a shorter record: histories and peaks, to the bit."""
    building = example_ten_story().without_devices()
    motions = [record, record, record, record, shortened(record, 900)]
    scales = [0.3, 2.0, 4.0, 6.0, 3.0]
    lanes = run_lanes(building, motions, scales, record=HISTORIES)
    peaks = run_lanes(building, motions, scales)  # the ring of two rows: the same peaks
    collapsed = 0
    for motion, scale, lane, peak in zip(motions, scales, lanes, peaks, strict=True):
        result = quiet_simulate(building, motion.scaled(scale))
        assert_lane_is_simulate(lane, result)
        assert_lane_is_simulate(peak, result)
        collapsed += result.collapsed
    assert collapsed >= 2  # collapses inside the batch, at different steps
    assert len({lane.steps for lane in lanes}) >= 4


@pytest.mark.slow  # compiles the lanes for its kind of building (tens of seconds a worker, cold)
def test_walls_that_heat_follow_their_amplitude_and_fail_equal_simulate(record):
    """The example frame with its walls (strain-dependent, amplitude-following, heating, with limits); in one
    variant the limit is lowered so that walls fail: every lane's histories, temperatures, amplitudes and the
    step each wall failed at equal simulate's."""
    intact = example_ten_story()
    limit = 2.0  # 200 % shear strain: reached by the stronger runs
    failing = intact.with_devices({story: tuple(dataclasses.replace(wall, limits=WallLimits(strain=limit))
                                                for wall in walls) for story, walls in intact.devices.items()})
    motions = [record, shortened(record, 2200), record]
    scales = [1.0, 2.5, 3.0]
    failures = 0
    for building in (intact, failing):
        lanes = run_lanes(building, motions, scales, record=HISTORIES)
        for motion, scale, lane in zip(motions, scales, lanes, strict=True):
            result = quiet_simulate(building, motion.scaled(scale))
            assert result.group_temperature.size and result.group_amplitude.size
            assert_lane_is_simulate(lane, result)
            failures += int((result.group_failure[:, 0] >= 0).sum())
    assert failures > 0  # the failing variant's walls failed


@pytest.mark.slow  # compiles the lanes for its kind of building (tens of seconds a worker, cold)
def test_fluid_viscous_and_friction_dampers_equal_simulate(record):
    """Walls, a linear and a nonlinear FVD and friction dampers (builders.mixed_devices_building), and the
    yielding example frame with an FVD and a friction damper, on records of different lengths."""
    motions = tapered_sine_pair()
    motions = [motions[0], GroundMotion(motions[1].acceleration[:500], 0.01, "short")]
    building = mixed_devices_building()
    for lane, motion in zip(run_lanes(building, motions, record=HISTORIES), motions, strict=True):
        assert_lane_is_simulate(lane, quiet_simulate(building, motion))
    yielding = example_ten_story().without_devices().with_devices(
        {1: FluidViscousDamper(3000.0, 0.5, stiffness=2e5), 5: FrictionDamper(3e5, 2e5)})
    scales = [1.0, 2.0]
    for lane, scale in zip(run_lanes(yielding, [record, record], scales, record=HISTORIES), scales, strict=True):
        result = quiet_simulate(yielding, record.scaled(scale))
        assert_lane_is_simulate(lane, result)
        assert (lane.peak_device_force > 0).all()


@pytest.mark.slow  # compiles the lanes for its kind of building (tens of seconds a worker, cold)
def test_a_lane_collapsing_early_and_one_never_yielding_equal_each_run_alone():
    """Masking: a lane that collapses within a few steps stops, the other runs to its end: each equals the
    same lane run alone and simulate."""
    building = example_ten_story().without_devices()
    t = np.arange(1001) * 0.01
    violent = GroundMotion(np.where(t > 0.0, 3.0e5, 0.0), 0.01, "violent")  # 31 g from the first step
    gentle = GroundMotion(200.0 * np.sin(2 * np.pi * t), 0.01, "gentle")
    together = run_lanes(building, [violent, gentle], record=HISTORIES)
    alone = [run_lanes(building, [motion], record=HISTORIES)[0] for motion in (violent, gentle)]
    assert together[0].collapsed and 3 <= together[0].steps <= 20
    assert not together[1].collapsed and together[1].steps == t.size
    assert (together[1].peak_drift < building.yield_drifts).all()  # never yields
    for lane, single, motion in zip(together, alone, (violent, gentle), strict=True):
        result = quiet_simulate(building, motion)
        assert_lane_is_simulate(lane, result)
        assert_lane_is_simulate(single, result)


@pytest.mark.slow  # compiles the lanes for its kind of building (tens of seconds a worker, cold)
def test_the_workspace_is_reused_and_reset_between_batches(record):
    """A second batch of the same layout reuses the workspace (no new arrays) and starts from rest: its lanes
    equal those of the first batch of the same records."""
    building = example_ten_story()
    first = run_lanes(building, [record, record], [1.0, 2.0])
    space = lanes_module._cache.workspace
    arrays = space.arrays.out.displacement
    run_lanes(building, [record, record], [3.0, 0.5])
    again = run_lanes(building, [record, record], [1.0, 2.0])
    assert lanes_module._cache.workspace is space and space.arrays.out.displacement is arrays
    assert space.batches == 3
    for a, b in zip(first, again, strict=True):
        for field in dataclasses.fields(a):
            value_a, value_b = getattr(a, field.name), getattr(b, field.name)
            if isinstance(value_a, np.ndarray):
                assert np.array_equal(value_a, value_b, equal_nan=True), field.name
            elif field.name != "histories":
                assert value_a == value_b, field.name


@pytest.mark.slow  # compiles the lanes for its kind of building (tens of seconds a worker, cold)
def test_a_copy_of_the_building_takes_the_workspace_over_and_another_building_does_not(record):
    """A process pool's worker unpickles the building anew for every task: such a copy (an equal pickle) reuses
    the workspace; a different building gets its own.  Reference: simulate, to the bit."""
    building = example_ten_story()
    copy = pickle.loads(pickle.dumps(building))
    lane, = run_lanes(copy, [record], [1.5], record=list(HISTORIES))
    space = lanes_module._cache.workspace
    batches = space.batches
    again = pickle.loads(pickle.dumps(building))
    second, = run_lanes(again, [record], [1.5], record=list(HISTORIES))
    assert lanes_module._cache.workspace is space and space.batches == batches + 1
    for found in (lane, second):
        assert_lane_is_simulate(found, quiet_simulate(copy, record.scaled(1.5)))
    other = building.without_devices()
    bare, = run_lanes(other, [record], record=list(HISTORIES))
    assert lanes_module._cache.workspace is not space
    assert_lane_is_simulate(bare, quiet_simulate(other, record))


def test_bad_batches_are_refused_and_a_non_finite_lane_fails_alone(record):
    building = example_ten_story().without_devices()
    other = GroundMotion(record.acceleration, 0.02, "coarse")
    with pytest.raises(ValueError, match=r"must share dt.*0\.01.*0\.02.*split the batch"):
        run_lanes(building, [record, other])
    with pytest.raises(ValueError, match="at least one record"):
        run_lanes(building, [])
    with pytest.raises(ValueError, match="scales must be 2 finite factors"):
        run_lanes(building, [record, record], [1.0, np.nan])
    with pytest.raises(ValueError, match="record must be 'peaks' or"):
        run_lanes(building, [record], record=["temperature"])
    # A scale that overflows one lane's acceleration (inf): that lane fails with a message, the other runs.
    lanes = run_lanes(building, [record, record], [1e308, 1.0])
    assert not lanes[0].converged and lanes[0].steps == 0
    assert "not finite" in lanes[0].error and "this lane was not run" in lanes[0].error
    assert re.search(r"'synthetic_kt_035g' x 1e\+308 is -?inf at t = ", lanes[0].error)  # Python numbers, not reprs
    assert_lane_is_simulate(lanes[1], quiet_simulate(building, record))


def test_a_record_without_a_step_is_refused(record):
    """GroundMotion itself refuses fewer than 2 samples; the lanes refuse what slips through (a record whose
    samples were cut after it was made)."""
    building = example_ten_story().without_devices()
    empty = object.__new__(GroundMotion)
    object.__setattr__(empty, "acceleration", np.zeros(1))
    object.__setattr__(empty, "dt", record.dt)
    object.__setattr__(empty, "name", "empty")
    with pytest.raises(ValueError, match=r"'empty' has 1 value.*at least 2"):
        run_lanes(building, [record, empty])


def test_settings_simulate_refuses_are_refused_with_simulate_s_message(record):
    """What simulate refuses before any work, run_lanes refuses with the same text (size_layers passes simulate's
    options to it): masses whose Newmark term overflows, a collapse limit of 0, < 0 or NaN.  Reference: simulate."""
    short = GroundMotion(record.acceleration[:50], record.dt, "short")
    heavy = ShearBuilding([1e305] * 2, [1e5] * 2)
    calls = [(heavy, {})] + [(example_ten_story().without_devices(), {"collapse_drift_ratio": bad})
                             for bad in (0.0, -0.1, float("nan"))]
    for building, options in calls:
        with pytest.raises(ValueError) as expected:
            simulate(building, short, **options)
        with pytest.raises(ValueError) as raised:
            run_lanes(building, [short], **options)
        assert str(raised.value) == str(expected.value)


def test_an_endless_free_vibration_is_refused_with_a_value_error(record):
    """1e308 s of rest after a record: run_lanes refuses it as too large for memory (a ValueError naming
    free_vibration, as simulate's), where rounding the rest first raised an OverflowError (inf steps)."""
    building = example_ten_story().without_devices()
    for free_vibration in (1e308, 1e9):
        with pytest.raises(ValueError, match=r"run_lanes \(2 lanes, free_vibration = .* use a shorter free_vibration"):
            run_lanes(building, [record, record], free_vibration=free_vibration)


def test_histories_beyond_the_memory_limit_are_refused_before_any_work():
    """1000 lanes of a 200 000-step record: their ground accelerations (1.6 GB) fit the 2 GiB limit, every row
    of the drift history of a 10-story frame besides them does not (8 (1 + 14 n + 12) bytes a lane and step,
    simulate's count of a row: 245 GB): refused with a ValueError naming the batch, before the workspace."""
    building = example_ten_story().without_devices()
    long = GroundMotion(np.zeros(200_000), 0.01, "long rest")
    with pytest.raises(ValueError, match=r"run_lanes \(1000 lanes of up to 200000 steps, 10 floors, 0 walls, "
                                         r"histories drift\).*keep fewer histories"):
        run_lanes(building, [long] * 1000, record=["drift"])


def _lane_memory(building, motion, lanes):
    """Peak bytes (tracemalloc) of one peaks-only run_lanes call of ``lanes`` lanes of ``motion``."""
    import tracemalloc

    tracemalloc.start()
    try:
        run_lanes(building, [motion] * lanes)
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_a_count_of_lanes_beyond_the_memory_limit_is_refused_before_any_work(monkeypatch):
    """A million lanes of a 41-step record fitted the per-step count (8 bytes a step: 328 MB) and died of
    MemoryError in their states and results.  Reference: the memory a lane takes, measured here (tracemalloc, 200
    and 600 lanes), which lane_state_bytes must cover without being far above it."""
    from vdw_frames import _validation
    from vdw_frames.frame.lanes import lane_bytes, lane_state_bytes

    building = example_ten_story().without_devices()
    short = GroundMotion(1000.0 * np.sin(np.linspace(0.0, 6.0, 41)), 0.02, "short")
    run_lanes(building, [short] * 2)  # compiled and its workspace made before measuring
    measured = (_lane_memory(building, short, 600) - _lane_memory(building, short, 200)) / 400
    counted = lane_state_bytes(building) + 41 * lane_bytes(building, 41, "fast")
    assert measured <= counted <= 2.0 * measured  # measured 10.5 KB, counted 15.5 KB
    # A limit the steps of 1000 lanes fit (328 KB) but not their states: refused, naming the count, before any work.
    monkeypatch.setattr(_validation, "MEMORY_LIMIT_BYTES", 1000 * counted - 1)
    with pytest.raises(ValueError, match=r"run_lanes \(1000 lanes of up to 41 steps, 10 floors, 0 walls: each lane's "
                                         r"state and result with its steps\) needs 1,000 lanes, whose arrays would "
                                         r"take .* \(limit .*\); split the batch"):
        run_lanes(building, [short] * 1000)
    monkeypatch.setattr(_validation, "MEMORY_LIMIT_BYTES", 1000 * counted)
    assert len(run_lanes(building, [short] * 1000)) == 1000
