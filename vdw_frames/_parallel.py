"""Fan independent tasks out to an executor: the one way :func:`~vdw_frames.run_batch`,
:func:`~vdw_frames.verify` and :func:`~vdw_frames.collapse_assessment` run their analyses.

:func:`fan_out` submits every task to an executor, gathers the results as they complete, collects the
package's warnings of each task (:func:`vdw_frames._warnings.collect`, a context variable: safe with
threads and processes alike) and draws a progress bar (tqdm) on standard error when it is a terminal.
The first failing task cancels the rest and raises, its message naming the task (``where``).
:func:`reissue` re-issues the collected warnings in the caller, once per text, in task order.

:func:`executor_for` gives the user's executor (any :class:`concurrent.futures.Executor`, or a Dask
``distributed.Client``, used through its ``get_executor()``) or an own pool over all cores, shut down after:
by default (None, or "threads") a thread pool, "processes" a process pool.  Threads are the default because
the analyses run in compiled code that releases the GIL (``nogil``, :mod:`vdw_frames._jit`): they run side by
side in one process, without a worker's start-up (its imports and compiled code loaded again) or a building
pickled for every task.

A cancelled fan-out (a failing task, Ctrl-C, SIGTERM) sets its **stop flag** (:func:`stop_flag`, one per
fan-out, seen by its tasks through a context variable), which the compiled time loop reads every step: a
thread's running analysis ends at its next step and its task raises :class:`Cancelled` (whose result nobody
reads), so an own thread pool is shut down within a step of every running analysis, not after it.  No worker
of an own process pool outlives its command:

* on an error, Ctrl-C (KeyboardInterrupt) or SIGTERM in the parent, the pending tasks are cancelled and
  the workers terminated at once (not waited for); KeyboardInterrupt and errors are re-raised, and SIGTERM
  (when its handler was the default) ends the process by SIGTERM once the workers are gone (an own thread
  pool's threads are gone by then too);
* each worker ignores SIGINT (the parent decides), and dies with its parent even if the parent is killed
  outright (SIGKILL): on Linux through ``prctl(PR_SET_PDEATHSIG, SIGTERM)``, and everywhere through a
  watchdog thread that polls, every ``WATCHDOG_INTERVAL`` s, whether its parent is still the one that
  started it.

Results do not depend on the executor: a task runs the same code, on the same data, in any of them.
"""

from __future__ import annotations

import concurrent.futures
import contextlib
import ctypes
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Hashable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

import numpy as np

from . import _warnings
from ._validation import show

K = TypeVar("K", bound=Hashable)
T = TypeVar("T")
R = TypeVar("R")

WATCHDOG_INTERVAL = 0.5  # s between a worker's checks that its parent lives (when PR_SET_PDEATHSIG is missing)
_PR_SET_PDEATHSIG = 1  # linux/prctl.h
_use_death_signal = sys.platform.startswith("linux")  # else (or if prctl fails) the watchdog alone
POOLS = ("threads", "processes")  # the kinds of own pool (executor_for), threads the default
_stop: ContextVar[np.ndarray | None] = ContextVar("vdw_frames_stop_flag", default=None)


class Cancelled(Exception):
    """A task's analysis was stopped by its fan-out's stop flag (another task failed, or Ctrl-C or SIGTERM):
    raised in the task, whose result nobody reads."""


def stop_flag() -> np.ndarray:
    """The (1,) int64 flag of the fan-out this task runs in (nonzero once it is cancelled; the compiled time
    loop reads it every step), or a flag of its own that nothing sets outside a fan-out."""
    flag = _stop.get()
    return np.zeros(1, dtype=np.int64) if flag is None else flag


def raise_if_stopped(flag: np.ndarray) -> None:
    """:class:`Cancelled` if ``flag`` (from :func:`stop_flag`) is set: the analysis it stopped is cut short."""
    if flag[0] != 0:
        raise Cancelled("the fan-out was cancelled: this analysis was stopped")


@dataclass(frozen=True)
class Collected(Generic[R]):
    """A task's result and the package warnings it issued (:class:`~vdw_frames._warnings.CollectedWarning`)."""

    value: R
    warnings: tuple[_warnings.CollectedWarning, ...]


def _collecting(function: Callable[[T], R], task: T, flag: np.ndarray) -> Collected[R]:
    # Module level: executors pickle it by name (``function`` must be module level too).  ``flag``: the
    # fan-out's stop flag (a process pool's worker gets a copy, never set: its workers are terminated instead).
    token = _stop.set(flag)
    try:
        with _warnings.collect() as caught:
            value = function(task)
    finally:
        _stop.reset(token)
    return Collected(value, tuple(caught))


# ---------------------------------------------------------------------------------------------- executors
def check_executor(executor: Any) -> None:
    """Refuse an ``executor`` that is neither None, "threads", "processes" (an own pool of that kind), a
    concurrent.futures executor (anything with a ``submit``) nor a Dask client, naming it."""
    if isinstance(executor, str):
        if executor not in POOLS:
            raise ValueError(f"executor must be a concurrent.futures.Executor, None, 'threads' or 'processes', "
                             f"got {show(executor)}")
        return
    if executor is not None and not callable(getattr(executor, "submit", None)):
        raise ValueError(f"executor must be a concurrent.futures.Executor, None, 'threads' or 'processes', got "
                         f"{show(executor)}")


@contextmanager
def executor_for(executor: Any = None) -> Iterator[concurrent.futures.Executor]:
    """``with executor_for(executor) as pool:`` -- the user's ``executor`` (a Dask ``distributed.Client``
    through its ``get_executor()``), or a new pool over all cores, shut down on leaving: None or "threads" a
    thread pool (:func:`thread_pool`), "processes" a process pool (:func:`process_pool`).  On an error,
    KeyboardInterrupt or SIGTERM inside the block, a process pool's workers are terminated first; a thread
    pool's running analyses have been stopped by their fan-out's flag and are waited for (module docstring)."""
    check_executor(executor)
    if executor is not None and not isinstance(executor, str):
        if not isinstance(executor, concurrent.futures.Executor) and callable(getattr(executor, "get_executor", None)):
            executor = executor.get_executor()  # a distributed.Client: its futures are not concurrent.futures'
        yield executor
        return
    processes = executor == "processes"
    pool = process_pool() if processes else thread_pool()
    try:
        with _sigterm_raises():
            yield pool
    except _Terminated:
        _stop_now(pool)
        _die_by_sigterm()
        raise
    except BaseException:
        _stop_now(pool)
        raise
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def _stop_now(pool: concurrent.futures.Executor) -> None:
    """A failing block's own pool: a process pool's workers terminated; a thread pool's pending tasks
    cancelled and its threads joined (their analyses stop at their next step: the fan-out set its flag)."""
    if isinstance(pool, concurrent.futures.ProcessPoolExecutor):
        terminate(pool)
    else:
        pool.shutdown(wait=True, cancel_futures=True)


def thread_pool(max_workers: int | None = None) -> concurrent.futures.ThreadPoolExecutor:
    """A thread pool (default: one thread per core) for the package's analyses, which release the GIL."""
    return concurrent.futures.ThreadPoolExecutor(max_workers=max_workers or os.cpu_count() or 1,
                                                 thread_name_prefix="vdw_frames")


def process_pool(max_workers: int | None = None) -> concurrent.futures.ProcessPoolExecutor:
    """A process pool (default: one worker per core) whose workers ignore SIGINT and die with this process."""
    return concurrent.futures.ProcessPoolExecutor(max_workers=max_workers or os.cpu_count() or 1,
                                                  initializer=_worker_start, initargs=(os.getpid(),))


def terminate(pool: concurrent.futures.ProcessPoolExecutor) -> None:
    """Cancel the pool's pending tasks and terminate its workers now (the running tasks are lost)."""
    workers = list((getattr(pool, "_processes", None) or {}).values())  # before shutdown forgets them
    pool.shutdown(wait=False, cancel_futures=True)
    for worker in workers:
        if worker.is_alive():
            worker.terminate()
    for worker in workers:
        worker.join(5.0)
        if worker.is_alive():  # SIGTERM ignored or blocked: SIGKILL
            worker.kill()
            worker.join(5.0)


# ---------------------------------------------------------------------------------------------- the fan-out
def fan_out(function: Callable[[T], R], tasks: Mapping[K, T], executor: concurrent.futures.Executor, *,
            where: Callable[[K], str], progress: bool = False, unit: str = "analyses",
            tally: Callable[[R], int] | None = None, tally_unit: str = "analyses",
            sizes: Mapping[K, int] | None = None) -> dict[K, Collected[R]]:
    """Run ``function(task)`` for every task of ``tasks`` on ``executor``, submitted in the mapping's order;
    returns {key: :class:`Collected`} (the result and the task's package warnings).

    ``function`` must be picklable (module level) for process pools.  The first failing task cancels the
    others (and, through :func:`executor_for`, terminates an own pool's workers) and raises: a ValueError
    becomes ``ValueError(f"{where(key)}: {error}")``, any other error gets ``where(key)`` as a note
    (Python >= 3.11); the running tasks' analyses are stopped (the fan-out's stop flag, module docstring).
    KeyboardInterrupt cancels the same way and is re-raised.  ``progress``: a tqdm bar
    of tasks (``unit``) on standard error, drawn only when it is a terminal; ``tally`` adds a running count
    of ``tally(result)`` (``tally_unit``); ``sizes``: what each task counts for on the bar (a task of many
    analyses, counted in analyses), 1 each by default.
    """
    results: dict[K, Collected[R]] = {}
    futures: dict[concurrent.futures.Future[Collected[R]], K] = {}
    flag = np.zeros(1, dtype=np.int64)  # this fan-out's stop flag (module docstring)
    try:
        for key, task in tasks.items():
            futures[executor.submit(_collecting, function, task, flag)] = key
        total = len(futures) if sizes is None else sum(sizes[key] for key in tasks)
        with _progress_bar(progress, total, unit) as bar:
            tallied = 0
            for future in concurrent.futures.as_completed(futures):
                key = futures[future]
                try:
                    results[key] = future.result()
                except Exception as error:
                    place = where(key)
                    if isinstance(error, ValueError):
                        raise ValueError(f"{place}: {error}") from error
                    if hasattr(error, "add_note"):  # Python >= 3.11
                        error.add_note(place)
                    raise
                if bar is not None:
                    if tally is not None:
                        tallied += tally(results[key].value)
                        bar.set_postfix_str(f"{tallied} {tally_unit}", refresh=False)
                    bar.update(1 if sizes is None else sizes[key])
    except BaseException:
        flag[0] = 1  # running analyses stop at their next step (a thread's; a process's are terminated)
        for future in futures:
            future.cancel()
        raise
    return results


def spread(chunks: Sequence[Sequence[K]], done: Mapping[int, Collected[Any]]) -> dict[K, Collected[Any]]:
    """One :class:`Collected` an analysis from tasks that each ran several: task ``c`` ran the analyses
    ``chunks[c]`` (keys) and gave ``done[c]``, a (value, warnings) pair each in that order; the task's own warnings
    (issued outside its analyses) go with its first analysis."""
    collected: dict[K, Collected[Any]] = {}
    for c, chunk in enumerate(chunks):
        for key, (value, caught) in zip(chunk, done[c].value, strict=True):
            collected[key] = Collected(value, caught)
        first = chunk[0]
        collected[first] = Collected(collected[first].value, collected[first].warnings + done[c].warnings)
    return collected


def reissue(collected: Mapping[K, Collected[Any]], label: Callable[[K], str], stacklevel: int = 1) -> None:
    """Re-issue every task's package warnings as ``f"{label(key)}: {message}"``, in key order, once per
    (category, text); ``stacklevel`` as for ``warnings.warn``, counted from the caller."""
    reported: set[tuple[type[Warning], str]] = set()
    for key in sorted(collected):  # type: ignore[type-var]
        for caught in collected[key].warnings:
            text = f"{label(key)}: {caught.message}"
            if (caught.category, text) not in reported:
                reported.add((caught.category, text))
                _warnings.warn(text, caught.category, stacklevel=stacklevel + 1)


@contextmanager
def _progress_bar(progress: bool, total: int, unit: str) -> Iterator[Any]:
    """A tqdm bar of ``total`` ``unit`` on standard error if ``progress`` and it is a terminal, else None."""
    if not (progress and total and _is_terminal(sys.stderr)):
        yield None
        return
    from tqdm import tqdm

    with tqdm(total=total, unit="", desc=unit, file=sys.stderr, dynamic_ncols=True, leave=True) as bar:
        yield bar


def _is_terminal(stream: Any) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):  # replaced or closed stream
        return False


# ---------------------------------------------------------------------------------------------- signals
class _Terminated(BaseException):
    """SIGTERM arrived while an own pool ran (raised in the main thread by the handler)."""


@contextmanager
def _sigterm_raises() -> Iterator[None]:
    """While inside, SIGTERM raises :class:`_Terminated` in the main thread -- only where it is the main
    thread and SIGTERM's handler is the default (a user's handler is left alone)."""
    if threading.current_thread() is not threading.main_thread() or \
            signal.getsignal(signal.SIGTERM) is not signal.SIG_DFL:
        yield
        return

    def handler(signum: int, frame: Any) -> None:
        raise _Terminated()

    signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _die_by_sigterm() -> None:
    """End this process as the SIGTERM it received would have (its default action, status -15)."""
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    sys.stderr.flush()
    os.kill(os.getpid(), signal.SIGTERM)


def _worker_start(owner: int) -> None:
    """A pool worker's initializer: ignore SIGINT (Ctrl-C reaches the whole process group; the parent
    decides), take SIGTERM's default action (a forked worker inherits the parent's handler), and die with
    the parent: PR_SET_PDEATHSIG on Linux, and a watchdog thread everywhere (module docstring)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    parent = os.getppid()
    if _use_death_signal:
        with contextlib.suppress(OSError, AttributeError):  # no prctl in this libc: the watchdog alone
            ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, int(signal.SIGTERM), 0, 0, 0)
    if not _parent_lives(parent, owner):  # the parent died before the death signal was set
        os._exit(1)
    threading.Thread(target=_watch, args=(parent, owner), name="vdw_frames-parent-watchdog", daemon=True).start()


def _watch(parent: int, owner: int) -> None:
    while _parent_lives(parent, owner):
        time.sleep(WATCHDOG_INTERVAL)
    os._exit(1)


def _parent_lives(parent: int, owner: int) -> bool:
    """Whether the worker's parent is still ``parent`` (a dead parent's children are re-parented) and the
    process that made the pool, ``owner`` (the parent itself, or a fork server's parent), still exists."""
    if os.getppid() != parent:
        return False
    try:
        os.kill(owner, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # exists (another user's process would mean the pid was reused: rare, harmless)
        return True
    return True
