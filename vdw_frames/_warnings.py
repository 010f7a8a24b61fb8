"""The package's warnings, and a thread-safe way to collect them per task.

:func:`warn` is ``warnings.warn`` unless a :func:`collect` block is active *in the calling thread or
task* (a :class:`contextvars.ContextVar`, so threads never see each other's collectors).  Inside one
the warning is appended to that block's list instead; nothing touches ``warnings.filters`` or
``warnings.showwarning``, which ``warnings.catch_warnings`` would (process-wide, hence not thread-safe).
:func:`vdw_frames.run_batch` collects each analysis's warnings this way, whatever its executor.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass

_collector: ContextVar[list[CollectedWarning] | None] = ContextVar("vdw_frames_warning_collector", default=None)


@dataclass(frozen=True)
class CollectedWarning:
    """A warning caught by :func:`collect`: its category and its message text."""

    category: type[Warning]
    message: str


def warn(message: str, category: type[Warning] = UserWarning, stacklevel: int = 1) -> None:
    """Issue a package warning (``stacklevel`` as for ``warnings.warn``, counted from the caller)."""
    collected = _collector.get()
    if collected is not None:
        collected.append(CollectedWarning(category, str(message)))
        return
    warnings.warn(message, category, stacklevel=stacklevel + 1)


@contextmanager
def collect() -> Iterator[list[CollectedWarning]]:
    """``with collect() as caught:`` gathers the package warnings issued in this thread (or task) into
    the list ``caught`` of :class:`CollectedWarning`; blocks nest, the innermost collects."""
    caught: list[CollectedWarning] = []
    token = _collector.set(caught)
    try:
        yield caught
    finally:
        _collector.reset(token)
