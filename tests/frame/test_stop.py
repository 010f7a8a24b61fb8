"""A cancelled fan-out stops its running analyses (vdw_frames._parallel's stop flag, read by the compiled time loop
every step): on the default thread pool, a task that fails ends the other task's long analysis at its next step
instead of after it, and an analysis that starts with the flag set makes no step.  Reference: what each analysis
does uncancelled -- its whole record: every row (the short one), or a time measured in the same run (the long one:
ten times that of a tenth of it) -- against what it did.  And a command (a subprocess) on the default thread pool
ends within a step of its analyses on SIGTERM or Ctrl-C, by that signal, as it does on a process pool."""

from __future__ import annotations

import signal
import threading
import time

import numpy as np
import pytest
from builders import example_ten_story
from commands import start_and_wait

from vdw_frames import GroundMotion, _parallel, simulate
from vdw_frames.frame.lanes import run_lanes

DT = 0.01


def sine(steps: int, amplitude: float = 300.0) -> GroundMotion:
    """A 1 Hz ground acceleration of ``amplitude`` mm/s^2 (the frame stays elastic), ``steps`` values at DT s."""
    return GroundMotion(amplitude * np.sin(2.0 * np.pi * DT * np.arange(steps)), DT, name="sine")


def test_an_analysis_started_under_a_set_flag_makes_no_step_and_raises_cancelled():
    frame = example_ten_story().without_devices()
    short = sine(400)
    assert simulate(frame, short).time.size == 400 and run_lanes(frame, [short])[0].steps == 400  # uncancelled
    stopped = np.ones(1, dtype=np.int64)
    for analysis in (lambda _: simulate(frame, short), lambda _: run_lanes(frame, [short, short])):
        with pytest.raises(_parallel.Cancelled, match="cancelled"):
            _parallel._collecting(analysis, None, stopped)
    # outside a fan-out the flag is a fresh one, never set: the same analyses run to the end
    assert simulate(frame, short).time.size == 400


def test_a_failing_task_stops_a_running_analysis_on_the_default_thread_pool():
    frame = example_ten_story().without_devices()
    run_lanes(frame, [sine(400)])  # compiled (or loaded) before anything is timed
    steps = 3_000_000  # 30 000 s of shaking: seconds, uncancelled
    began = time.perf_counter()
    run_lanes(frame, [sine(steps // 10)] * 2)
    uncancelled = 10.0 * (time.perf_counter() - began)  # (the time is linear in the steps)
    long = sine(steps)
    started, outcome = threading.Event(), {}

    def task(kind: str) -> str:
        if kind == "fail":
            started.wait(60)
            time.sleep(0.3)  # the analysis is inside its compiled loop
            raise ValueError("refused")
        started.set()
        began = time.perf_counter()
        try:
            lanes = run_lanes(frame, [long, long])
        except _parallel.Cancelled:
            outcome["analysis"] = "cancelled"
            outcome["seconds"] = time.perf_counter() - began
            raise
        outcome["analysis"] = f"finished {lanes[0].steps} steps"
        return "done"

    with pytest.raises(ValueError, match=r"^task fail: refused$"), _parallel.executor_for(None) as pool:
        assert isinstance(pool, __import__("concurrent.futures").futures.ThreadPoolExecutor)
        _parallel.fan_out(task, {"analysis": "analysis", "fail": "fail"}, pool, where=lambda key: f"task {key}")
    # the pool was shut down (its threads joined) before the error left the block: the analysis had ended, long
    # before its record's end (the failure came 0.3 s after it started)
    assert outcome["analysis"] == "cancelled"
    assert outcome["seconds"] < 0.5 * uncancelled, (outcome, uncancelled)


# A command whose default thread pool runs two long analyses (a 100-story frame, 2e6 steps each), after timing one
# of a fiftieth of that record (the reference: the whole takes fifty times as long; the time is linear in the steps).
COMMAND = """
import os, sys, time
os.cpu_count = lambda: 2
import numpy as np
from vdw_frames import GroundMotion, ShearBuilding, _parallel
from vdw_frames.frame.lanes import run_lanes

folder = sys.argv[1]
frame = ShearBuilding([500.0] * 100, np.linspace(8e5, 4e5, 100), story_heights=[3500.0] * 100)
record = GroundMotion(300.0 * np.sin(2.0 * np.pi * 0.01 * np.arange(2_000_000)), 0.01, name="sine")
part = GroundMotion(record.acceleration[:40_000], 0.01)
run_lanes(frame, [part])  # compiled (or loaded)
began = time.perf_counter()
run_lanes(frame, [part])
with open(os.path.join(folder, "uncancelled"), "w") as handle:
    handle.write(repr(50.0 * (time.perf_counter() - began)))


def analysis(n):
    open(os.path.join(folder, f"task{n}"), "w").close()
    return run_lanes(frame, [record])[0].steps


if __name__ == "__main__":
    with _parallel.executor_for(None) as pool:
        _parallel.fan_out(analysis, {0: 0, 1: 1}, pool, where=str)
"""


@pytest.mark.skipif(not hasattr(signal, "SIGKILL"), reason="POSIX signals")
@pytest.mark.parametrize("how", ["SIGTERM", "SIGINT"])
def test_a_signal_ends_a_command_on_the_default_thread_pool_within_a_step_of_its_analyses(tmp_path, how):
    """SIGTERM or Ctrl-C while both threads of the default pool are inside their analyses: the command ends (by
    that signal, as with a process pool: tests/test_parallel.py) well before the analyses would have, its pool's
    threads joined first (a thread left running would keep the process alive until its analysis ended)."""
    script = tmp_path / "command.py"
    script.write_text(COMMAND)
    command = start_and_wait(script, tmp_path, "task*", 2, "the analyses", seconds=120.0)
    time.sleep(0.5)  # both inside their compiled loops
    uncancelled = float((tmp_path / "uncancelled").read_text())
    signalled = time.monotonic()
    command.send_signal(getattr(signal, how))
    try:
        status = command.wait(max(uncancelled, 60.0))
    finally:
        command.kill()
    ended = time.monotonic() - signalled
    stderr = command.stderr.read().decode() if command.stderr else ""
    assert status == -getattr(signal, how), stderr
    if how == "SIGINT":
        assert "KeyboardInterrupt" in stderr
    assert ended < min(0.25 * uncancelled, 5.0), (ended, uncancelled)


def refuse_or_analyse(kind: str) -> int:
    """A task: "fail" raises at once, "short" runs a 400-step analysis (its rows filled)."""
    if kind == "fail":
        raise ValueError("refused")
    return run_lanes(example_ten_story().without_devices(), [sine(400)])[0].steps


def test_a_cancelled_fan_out_leaves_no_flag_set_for_the_next_one_on_a_kept_pool():
    """A fan-out cancelled by a failing task, then another on the same kept thread pool (whose threads ran the first):
    the second's analyses run to their record's end (400 rows), as does one outside any fan-out."""
    from vdw_frames.frame import worker_pool

    with worker_pool() as pool:
        with pytest.raises(ValueError, match="refused"):
            _parallel.fan_out(refuse_or_analyse, {0: "short", 1: "fail", 2: "short"}, pool, where=str)
        again = _parallel.fan_out(refuse_or_analyse, {k: "short" for k in range(4)}, pool, where=str)
    assert [again[k].value for k in range(4)] == [400] * 4
    assert refuse_or_analyse("short") == 400 and _parallel.stop_flag()[0] == 0
    with pytest.raises(ValueError, match=r"kind must be one of threads, processes, got 'x'"):
        worker_pool("x")
