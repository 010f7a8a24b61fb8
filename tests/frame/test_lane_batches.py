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
