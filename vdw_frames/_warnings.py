"""The package's warnings, and a thread-safe way to collect them per task.

:func:`warn` is ``warnings.warn`` unless a :func:`collect` block is active *in the calling thread or
task* (a :class:`contextvars.ContextVar`, so threads never see each other's collectors).  Inside one
the warning is appended to that block's list instead; nothing touches ``warnings.filters`` or
``warnings.showwarning``, which ``warnings.catch_warnings`` would (process-wide, hence not thread-safe).
:func:`vdw_frames.run_batch` collects each analysis's warnings this way, whatever its executor.
"""

from __future__ import annotations

import functools
import inspect
import warnings
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from typing import ParamSpec, TypeVar

_P = ParamSpec("_P")
_R = TypeVar("_R")

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


def keyword_only_since_0_3(function: Callable[_P, _R]) -> Callable[_P, _R]:
    """Let ``function``'s keyword-only parameters still be given by position, in their order, for one release
    (0.3.0 made them keyword-only), with a DeprecationWarning naming them."""
    parameters = inspect.signature(function).parameters.values()
    positional = sum(p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD) for p in parameters)
    keyword_only = [p.name for p in parameters if p.kind is p.KEYWORD_ONLY]

    @functools.wraps(function)
    def accept_positions(*args: _P.args, **kwargs: _P.kwargs) -> _R:
        extra = args[positional:]
        if extra and len(extra) <= len(keyword_only):
            names = keyword_only[:len(extra)]
            clash = [name for name in names if name in kwargs]
            if clash:  # the function's own TypeError would name only one
                raise TypeError(f"{function.__name__}() got multiple values for {', '.join(clash)}")
            warnings.warn(f"{function.__name__}(): pass {', '.join(names)} by keyword; by position is deprecated "
                          "since 0.3.0 and will be refused in 0.4.0", DeprecationWarning, stacklevel=2)
            kwargs.update(zip(names, extra, strict=True))
            args = args[:positional]  # type: ignore[assignment]  # _P.args narrowed to the positional ones
        return function(*args, **kwargs)

    return accept_positions
