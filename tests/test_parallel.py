"""The fan-out (vdw_frames._parallel): results equal the tasks run one by one, on any executor; warnings
collected per task and re-issued once; the first failure or an interrupt cancels the rest; the progress bar
only on a terminal; the own pools (threads by default, "processes"); and no worker of an own process pool outlives
its command (SIGTERM, SIGKILL, Ctrl-C), checked on real processes through /proc and os.kill(pid, 0).  That a
cancelled fan-out stops a thread's running analysis: tests/frame/test_stop.py."""

from __future__ import annotations

import concurrent.futures
import io
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
import warnings
from pathlib import Path

import pytest
from commands import start_and_wait

from vdw_frames import _parallel, _warnings


def cube_warning_on_even(n: int) -> int:
    """n^3 (the reference: Python's own arithmetic), warning once for an even n and twice alike for n = 4."""
    if n % 2 == 0:
        _warnings.warn(f"{n} is even", RuntimeWarning)
    if n == 4:
        _warnings.warn(f"{n} is even", RuntimeWarning)  # a duplicate: re-issued once
    return n**3


def fail_at_three(n: int) -> int:
    if n == 3:
        raise ValueError("three is refused")
    if n == 5:
        raise ZeroDivisionError("five")
    return n


class Serial:
    """A concurrent.futures-like executor that runs each task at once."""

    def __init__(self) -> None:
        self.ran: list[int] = []

    def submit(self, function, *args):
        future: concurrent.futures.Future = concurrent.futures.Future()
        self.ran.append(args[1])  # (function, task, the fan-out's stop flag)
        try:
            future.set_result(function(*args))
        except BaseException as error:
            future.set_exception(error)
        return future


@pytest.mark.parametrize("kind", ["serial", "threads", "processes"])
def test_results_and_warnings_equal_the_tasks_run_one_by_one(kind):
    tasks = {(n % 3, n): n for n in range(8)}
    with warnings.catch_warnings(record=True) as expected_warnings:
        warnings.simplefilter("always")
        expected = {key: cube_warning_on_even(n) for key, n in tasks.items()}
    assert len(expected_warnings) == 5
    if kind == "serial":
        executor = Serial()
        collected = _parallel.fan_out(cube_warning_on_even, tasks, executor, where=str)
    else:
        pool = concurrent.futures.ThreadPoolExecutor(3) if kind == "threads" else None
        with _parallel.executor_for(pool) as executor:
            collected = _parallel.fan_out(cube_warning_on_even, tasks, executor, where=str)
        if pool is not None:
            pool.shutdown()
    assert {key: each.value for key, each in collected.items()} == expected
    assert {key: [w.message for w in each.warnings] for key, each in collected.items()} == \
        {key: [f"{n} is even"] * ((n % 2 == 0) + (n == 4)) for key, n in tasks.items()}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        _parallel.reissue(collected, lambda key: f"task {key[1]}")
    # Once per text, in key order ((0, 0), (0, 6), (1, 4), (2, 2)); the caller of reissue is named.
    assert [str(w.message) for w in caught] == [f"task {n}: {n} is even" for n in (0, 6, 4, 2)]
    assert {w.category for w in caught} == {RuntimeWarning}
    assert {w.filename for w in caught} == {__file__}


def test_the_first_failure_names_its_task_and_cancels_the_rest():
    executor = Serial()
    with pytest.raises(ValueError, match=r"^the task 3: three is refused$") as raised:
        _parallel.fan_out(fail_at_three, {n: n for n in range(1, 5)}, executor, where=lambda n: f"the task {n}")
    assert isinstance(raised.value.__cause__, ValueError)
    with pytest.raises(ZeroDivisionError) as raised:
        _parallel.fan_out(fail_at_three, {5: 5, 6: 6}, Serial(), where=lambda n: f"the task {n}")
    if sys.version_info >= (3, 11):
        assert raised.value.__notes__ == ["the task 5"]
    # A two-thread pool whose tasks (all but task 1) wait until fan_out has returned: task 1's failure cancels
    # every task not yet started, so at most one more than tasks 0 and 1 ever starts (the thread freed by task 1
    # may take task 2 before the cancellation).  (Tasks that returned at once raced the cancellation.)
    release, started = threading.Event(), []

    def blocking(n: int) -> int:
        started.append(n)
        if n == 1:
            raise ValueError("one")
        release.wait(10)
        return n

    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        with pytest.raises(ValueError, match="task 1: one"):
            _parallel.fan_out(blocking, {n: n for n in range(20)}, pool, where=lambda n: f"task {n}")
        release.set()
    assert set(started) <= {0, 1, 2} and {0, 1} <= set(started)


def fail_soon_or_sleep(n: int) -> int:
    if n == 1:
        time.sleep(0.5)
        raise ValueError("task 1 is refused")
    time.sleep(60)
    return n


def test_a_failure_on_an_own_process_pool_terminates_the_running_tasks_rather_than_wait_for_them():
    began = time.monotonic()
    with pytest.raises(ValueError, match=r"^task 1: task 1 is refused$"), _parallel.executor_for("processes") as pool:
        workers = []  # the pool's worker pids, read once fan_out has started them
        threading.Timer(0.2, lambda: workers.extend(pool._processes or ())).start()
        _parallel.fan_out(fail_soon_or_sleep, {n: n for n in range(4)}, pool, where=lambda n: f"task {n}")
    assert time.monotonic() - began < 20  # the other tasks sleep 60 s
    # Asked of the system, not of multiprocessing's Process objects: the pool's own thread may reap a worker
    # that this thread's Process object still reports alive.
    assert len(workers) == (os.cpu_count() or 1)
    assert not [pid for pid in workers if alive(pid)]


def test_keyboard_interrupt_cancels_the_rest_and_is_re_raised():
    started = []

    def interrupted(n: int) -> int:
        started.append(n)
        if n == 0:
            time.sleep(0.2)
            raise KeyboardInterrupt
        time.sleep(0.2)
        return n

    with concurrent.futures.ThreadPoolExecutor(1) as pool, pytest.raises(KeyboardInterrupt):
        _parallel.fan_out(interrupted, {n: n for n in range(10)}, pool, where=str)
    assert started in ([0], [0, 1])  # the thread may take task 1 before the interrupt cancels the rest


def test_the_progress_bar_is_drawn_only_on_a_terminal(monkeypatch):
    class Terminal(io.StringIO):
        def isatty(self) -> bool:
            return True

    for stream, drawn in ((Terminal(), True), (io.StringIO(), False)):
        monkeypatch.setattr(sys, "stderr", stream)
        collected = _parallel.fan_out(len, {k: "ab" * k for k in range(1, 4)}, Serial(), where=str, progress=True,
                                      unit="records", tally=lambda value: value, tally_unit="analyses")
        assert collected[3].value == 6
        text = stream.getvalue()
        assert ("3/3" in text and "records" in text and "12 analyses" in text) if drawn else text == ""
    monkeypatch.setattr(sys, "stderr", Terminal())
    _parallel.fan_out(len, {1: "a"}, Serial(), where=str, progress=False)
    assert sys.stderr.getvalue() == ""
    # Tasks of several analyses each (verify's batches of lanes): the bar counts what each stands for, 1 + 2 + 3.
    monkeypatch.setattr(sys, "stderr", Terminal())
    _parallel.fan_out(len, {k: "ab" * k for k in range(1, 4)}, Serial(), where=str, progress=True,
                      sizes={1: 1, 2: 2, 3: 3})
    assert "6/6" in sys.stderr.getvalue() and "3/3" not in sys.stderr.getvalue()


def test_executors_are_checked_and_a_dask_client_is_used_through_its_executor():
    for wrong in ("x", 3):
        with (pytest.raises(ValueError, match=r"executor must be a concurrent\.futures\.Executor, None, 'threads' or "
                                              rf"'processes', got {wrong!r}$"),
              _parallel.executor_for(wrong)):
            pass
    pool = concurrent.futures.ThreadPoolExecutor(1)

    class Client:  # the part of distributed.Client the fan-out uses
        def submit(self, *args):
            raise AssertionError("a client's own futures are not concurrent.futures'")

        def get_executor(self):
            return pool

    with _parallel.executor_for(Client()) as executor:
        assert executor is pool
        assert _parallel.fan_out(abs, {0: -2}, executor, where=str)[0].value == 2
    pool.shutdown()


# ---------------------------------------------------------------------------------------------- processes
SCRIPT = """
import os, sys, time
os.cpu_count = lambda: 2  # a pool of two workers, whatever the machine
from vdw_frames import _parallel
_parallel._use_death_signal = {death_signal}
folder = sys.argv[1]

def slow(n):
    with open(os.path.join(folder, f"worker{{os.getpid()}}"), "w") as handle:
        handle.write(str(os.getpid()))
    time.sleep(120)
    return n

if __name__ == "__main__":
    with _parallel.executor_for("processes") as pool:
        _parallel.fan_out(slow, {{n: n for n in range(6)}}, pool, where=str)
"""


def alive(pid: int) -> bool:
    """Whether process ``pid`` exists and is not a zombie (a dead child not yet reaped by its new parent)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (FileNotFoundError, IndexError):
        return not sys.platform.startswith("linux")  # no /proc: os.kill's answer
    return state not in ("Z", "X")


def start_and_find_workers(tmp_path: Path, death_signal: bool) -> tuple[subprocess.Popen, list[int]]:
    script = tmp_path / "fan_out.py"
    script.write_text(textwrap.dedent(SCRIPT.format(death_signal=death_signal)))
    command = start_and_wait(script, tmp_path, "worker*", 2, "the workers")
    time.sleep(0.2)  # both pid files written
    workers = [int(path.read_text()) for path in tmp_path.glob("worker*")]
    assert all(alive(pid) for pid in workers) and command.pid not in workers
    return command, workers


def gone_within(pids: list[int], seconds: float) -> float:
    """Seconds until every process of ``pids`` is gone (an AssertionError after ``seconds``)."""
    began = time.monotonic()
    while any(alive(pid) for pid in pids):
        if time.monotonic() - began > seconds:
            survivors = [pid for pid in pids if alive(pid)]
            for pid in survivors:  # clean up before failing
                os.kill(pid, signal.SIGKILL)
            raise AssertionError(f"workers {survivors} outlived their command by {seconds} s")
        time.sleep(0.02)
    return time.monotonic() - began


pytestmark_posix = pytest.mark.skipif(not hasattr(signal, "SIGKILL"), reason="POSIX signals")


@pytestmark_posix
@pytest.mark.parametrize("death_signal", [True, False], ids=["death-signal", "watchdog-only"])
@pytest.mark.parametrize("how", ["SIGTERM", "SIGKILL", "SIGINT"])
def test_no_worker_outlives_its_command(tmp_path, how, death_signal):
    if death_signal and not sys.platform.startswith("linux"):
        pytest.skip("PR_SET_PDEATHSIG is Linux's")
    command, workers = start_and_find_workers(tmp_path, death_signal)
    command.send_signal(getattr(signal, how))
    status = command.wait(30)
    stderr = command.stderr.read().decode() if command.stderr else ""
    # SIGTERM: the parent terminates its workers, then dies by SIGTERM; SIGINT: KeyboardInterrupt re-raised
    # after the workers are terminated (Python then ends by SIGINT); SIGKILL: the workers follow their parent.
    expected = -getattr(signal, how)
    assert status == expected, stderr
    if how == "SIGINT":
        assert "KeyboardInterrupt" in stderr
    # Well under the 120 s the tasks sleep; the watchdog polls every WATCHDOG_INTERVAL s.
    assert gone_within(workers, 2 * _parallel.WATCHDOG_INTERVAL + 3.0) < 2 * _parallel.WATCHDOG_INTERVAL + 3.0


def test_the_own_pools_are_threads_by_default_or_processes_over_every_core():
    threads, processes = concurrent.futures.ThreadPoolExecutor, concurrent.futures.ProcessPoolExecutor
    for kind, pool_class in ((None, threads), ("threads", threads), ("processes", processes)):
        with _parallel.executor_for(kind) as pool:
            assert type(pool) is pool_class
            assert pool._max_workers == (os.cpu_count() or 1)
            # each task sees its fan-out's stop flag, unset while nothing failed; outside a fan-out, a flag of its own
            collected = _parallel.fan_out(flag_value, {0: 0, 1: 1}, pool, where=str)
            assert [collected[k].value for k in (0, 1)] == [0, 0]
    assert _parallel.stop_flag()[0] == 0 and _parallel.stop_flag() is not _parallel.stop_flag()


def flag_value(_: int) -> int:
    return int(_parallel.stop_flag()[0])
