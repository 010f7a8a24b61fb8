"""lane_batches: which analyses may share one run_lanes call (every lane then equals simulate: one dt, and with
walls one side of the exact memory's length, which simulate chooses by the record's steps).  Expected batches
written out by hand from the rule."""

import numpy as np
import pytest
from verification_cases import three_story

from vdw_frames import GroundMotion
from vdw_frames.element.bank import memory_strategy
from vdw_frames.frame.lanes import LANES_PER_TASK, lane_batches


def record(values, dt=0.01):
    return GroundMotion(np.zeros(values), dt, f"{values} x {dt}")


def test_batches_split_by_dt_by_the_exact_memory_s_length_and_by_key_and_keep_their_order():
    below = memory_strategy("fast").exact_below  # simulate's exact memory up to this many steps
    motions = [record(500), record(below + 10), record(500, 0.02), record(below), record(700), record(below + 1)]
    analyses = list("abcdef")
    walled, bare = three_story(), three_story(walls=False)
    # 6 analyses on one worker: at least four tasks, so batches of at most ceil(6 / 4) = 2
    assert lane_batches(walled, motions, analyses) == [["a", "d"], ["e"], ["b", "f"], ["c"]]
    assert lane_batches(bare, motions, analyses) == [["a", "b"], ["d", "e"], ["f"], ["c"]]  # no walls: no memory
    # 1 s of rest after each record: record(below) goes past the exact memory's length, record(700) does not
    assert lane_batches(walled, motions, analyses, free_vibration=1.0) == [["a", "e"], ["b", "d"], ["f"], ["c"]]
    assert lane_batches(bare, motions, analyses, apart=[0, 1, 0, 1, 0, 1]) == [["a", "e"], ["b", "d"], ["f"], ["c"]]
    assert lane_batches(bare, motions, analyses, workers=0) == lane_batches(bare, motions, analyses)
    assert lane_batches(walled, motions, analyses, workers=None) == [["a", "d", "e"], ["b", "f"], ["c"]]  # no pool
    assert lane_batches(bare, [record(500)] * 6, analyses, workers=2) == [[a] for a in analyses]  # ceil(6 / 8)
    many = lane_batches(bare, [record(500)] * 200, list(range(200)), workers=None)
    assert [len(batch) for batch in many] == [LANES_PER_TASK] * 4 + [200 - 4 * LANES_PER_TASK]
    with pytest.raises(ValueError, match="one record"):
        lane_batches(bare, motions, analyses[:3])


def test_records_beyond_the_fast_memory_s_horizon_share_a_batch_only_with_their_own_length():
    """The fast memory's modes are built for the record's steps, at least FastMemory.max_steps, and a batch builds them
    for its longest record: with max_steps = 3000, records of 2500 and 2900 steps share (both 3000), 4000 and 4000
    too, but not 2900 and 4000.  Reference: simulate of each record alone, which its batch's lane equals to the bit;
    the lane of the 2500-step record run beside the 4000-step one did not (its walls took the 4000-step modes)."""
    from builders import FITTED300
    from shared_data import REPO

    import vdw_frames as vdw
    from vdw_frames.element.fast_memory import FastMemory
    from vdw_frames.frame.lanes import run_lanes

    memory = FastMemory(max_steps=3000)
    walled = three_story()
    assert lane_batches(walled, [record(2500), record(4000), record(2900), record(4000)], list("abcd"), memory=memory,
                        workers=None) == [["a", "c"], ["b", "d"]]
    assert lane_batches(walled, [record(2500), record(4000)], list("ab"), workers=None) == [["a", "b"]]  # default 2**20
    kt = vdw.read_at2(REPO / "vdw_frames" / "motion" / "data" / "synthetic_kt_035g.AT2").acceleration
    samples = 3.0 * np.concatenate([kt, kt])
    motions = [GroundMotion(samples[:2500], 0.01, "2500"), GroundMotion(samples[:4000], 0.01, "4000")]
    walled = vdw.ShearBuilding([100.0, 100.0, 80.0], [4.0e4, 3.5e4, 3.0e4], story_heights=[3500.0] * 3,
                               devices={1: vdw.FDMKDamper(**FITTED300, area=0.05e6, thickness=10.0)})  # r = 0.589
    alone = [vdw.simulate(walled, motion, memory=memory) for motion in motions]
    batched = [lane for batch in lane_batches(walled, motions, [0, 1], memory=memory, workers=None)
               for lane in run_lanes(walled, [motions[k] for k in batch], memory=memory)]
    for lane, reference in zip(batched, alone, strict=True):
        assert np.array_equal(lane.peak_drift, reference.peak_drift)
        assert np.array_equal(lane.residual_drift, reference.residual_drift)
    together = run_lanes(walled, motions, memory=memory)[0]  # why they must stay apart
    assert not np.array_equal(together.residual_drift, alone[0].residual_drift)


def test_batches_stay_within_the_memory_limit_of_a_run_lanes_call(monkeypatch):
    """A batch runs whenever each of its records alone would: lane_batches cuts a group so that its lanes together
    (run_lanes' count: lanes x (longest record x lane_bytes + lane_state_bytes)) stay within the limit.  Reference:
    the byte count written out from row_bytes' rule (8 a step of ground, 6 floats a wall of exact memory) and the cut
    by hand."""
    from vdw_frames import _validation
    from vdw_frames.frame.lanes import lane_bytes, lane_state_bytes

    walled = three_story()  # one wall (verification_cases), three floors
    assert lane_bytes(walled, 500, "exact") == 8 + 8 * 6 * len(walled.wall_list)
    assert lane_bytes(walled, 500, "exact", histories=True) == 8 + 8 * (6 * len(walled.wall_list) + 14 * 3 + 12)
    below = memory_strategy("fast").exact_below
    assert lane_bytes(walled, below + 1, "fast") == 8  # the fast memory keeps no exact memory a step
    per_step, state = lane_bytes(walled, 700, "exact"), lane_state_bytes(walled)
    # room for two lanes of 700 steps, or one of 1400, but not three of 700 or two of 1000 (a batch's lanes all
    # count its longest record); a record alone beyond the limit stays alone (run_lanes refuses it, naming it)
    monkeypatch.setattr(_validation, "MEMORY_LIMIT_BYTES", 2 * (700 * per_step + state))
    motions = [record(700), record(500), record(700), record(1000), record(300), record(1400), record(3000)]
    assert lane_batches(walled, motions, list("abcdefg"), memory="exact", workers=None) == \
        [["a", "b"], ["c"], ["d"], ["e"], ["f"], ["g"]]
    assert lane_batches(walled, motions[:2], list("ab"), memory="exact", workers=None) == [["a", "b"]]
    monkeypatch.setattr(_validation, "MEMORY_LIMIT_BYTES", 2 * (700 * per_step + state) - 1)
    assert lane_batches(walled, motions[:2], list("ab"), memory="exact", workers=None) == [["a"], ["b"]]
