"""numba's ``njit`` for the package: an on-disk cache that follows the package's sources, and no cache
where none can be written.

* numba's cache keys a compiled function on its own source file only: when a function it calls changes
  in another module (the FDMK kernel, say), a cached caller keeps running the old code.  The package's
  compiled functions are therefore cached in a sub-folder named after a fingerprint of the package's
  modules that hold compiled code (``__pycache__/vdw-<fingerprint>``, or the same under ``NUMBA_CACHE_DIR`` or the
  user-wide cache), so that any change recompiles everything; the folders of older fingerprints are
  removed when a new one is made.
* numba refuses to decorate a function with ``cache=True`` when it finds no writable cache location (a
  read-only install with an unwritable HOME, for example): ``import vdw_frames`` would then fail.
  Such a function is compiled without a cache instead, with one warning for the whole package.
* A cache file that cannot be read back (truncated by a full disk or a killed process: numba raises
  ``UnpicklingError`` on every later run) is dropped and the function recompiled, with one warning; a cache
  that cannot be written (a full disk: ``OSError`` from inside the first analysis) is given up for the
  rest of the process, with one warning, and the compiled code is used without it.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import shutil
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

from numba import njit as _numba_njit
from numba.core import caching

_PACKAGE = Path(__file__).resolve().parent
# What has been said or found once: a kind of warning given, or "unwritable" once a cache write failed (no
# later write is tried).
_said: set[str] = set()


def _fingerprint() -> str:
    """A digest of the package's modules that hold compiled code (the only ones compiled code can call)."""
    digest = hashlib.sha1()
    for path in sorted(_PACKAGE.rglob("*.py")):
        source = path.read_bytes()
        if b"njit" in source:
            digest.update(path.relative_to(_PACKAGE).as_posix().encode())
            digest.update(source)
    return "vdw-" + digest.hexdigest()[:16]


_TAG = _fingerprint()
_cleaned: set[str] = set()


def _versioned(locator: Any) -> type:
    """A subclass of numba's ``locator`` that serves the package's files from the fingerprint's sub-folder."""

    class Versioned(locator):
        def __init__(self, py_func: Callable[..., Any], py_file: str) -> None:
            super().__init__(py_func, py_file)
            self._cache_path: str = os.path.join(self._cache_path, _TAG)

        @classmethod
        def from_function(cls, py_func: Callable[..., Any], py_file: str) -> Any:
            if not Path(py_file).resolve().is_relative_to(_PACKAGE):
                return None  # other packages keep numba's own locators
            return super().from_function(py_func, py_file)

        def ensure_cache_path(self) -> None:
            super().ensure_cache_path()
            parent = os.path.dirname(self._cache_path)
            if parent not in _cleaned:  # once per folder and process: drop older fingerprints
                _cleaned.add(parent)
                for entry in Path(parent).glob("vdw-*"):
                    if entry.name != _TAG:
                        shutil.rmtree(entry, ignore_errors=True)

    Versioned.__name__ = f"VdwFrames{locator.__name__.lstrip('_')}"
    return Versioned


def _install_locators() -> None:
    # numba >= 0.60 names these without the leading underscore; guard both, and skip if neither exists.
    implementation = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl", None)
    names = ("UserProvidedCacheLocator", "InTreeCacheLocator", "UserWideCacheLocator")
    locators = [getattr(caching, name, None) or getattr(caching, "_" + name, None) for name in names]
    if implementation is None or None in locators or getattr(implementation, "_vdw_frames", False):
        return
    implementation._locator_classes = [_versioned(locator) for locator in locators] + list(
        implementation._locator_classes)
    implementation._vdw_frames = True


_install_locators()

_FunctionCache: Any = getattr(caching, "FunctionCache", None)


def _warn_once(kind: str, message: str, stacklevel: int = 1) -> None:
    """Warn of ``kind`` once a process; ``stacklevel`` counts from the caller, as in ``warnings.warn``."""
    if kind not in _said:
        _said.add(kind)
        warnings.warn(message, RuntimeWarning, stacklevel=stacklevel + 1)


if _FunctionCache is not None:

    class _GuardedCache(_FunctionCache):
        """numba's per-function cache, with a cache file that fails to load recompiled and a failed write
        dropped (module docstring)."""

        def load_overload(self, sig: Any, target_context: Any) -> Any:
            try:
                return super().load_overload(sig, target_context)
            except Exception as error:  # any unreadable cache file: compiling instead is always correct
                _warn_once("load", f"vdw_frames: numba's compilation cache in {self.cache_path} could not be read "
                           f"({type(error).__name__}: {error}); recompiling and replacing it")
                # The index names the data files: without it the next save starts afresh.
                with contextlib.suppress(OSError):
                    os.remove(self._cache_file._index_path)
                return None

        def save_overload(self, sig: Any, data: Any) -> None:
            if "unwritable" in _said:
                return
            try:
                super().save_overload(sig, data)
            except OSError as error:
                _said.add("unwritable")
                _warn_once("save", f"vdw_frames: numba's compilation cache could not be written in {self.cache_path} "
                           f"({error.strerror or error}); going on without it (compiled code is not kept between "
                           "runs; set NUMBA_CACHE_DIR to a folder with space)")


def _guard(dispatcher: Any) -> Any:
    """``dispatcher`` with its cache made a :class:`_GuardedCache` (same object layout: numba's own class
    extended, nothing else changed)."""
    cache = getattr(dispatcher, "_cache", None)
    if _FunctionCache is not None and type(cache) is _FunctionCache:
        cache.__class__ = _GuardedCache
    return dispatcher


def njit(*args: Any, cache: bool = False, allocates: bool = True, **options: Any) -> Any:
    """``numba.njit``, used as ``@njit(cache=True)``, with ``error_model="numpy"`` and ``nogil=True``; falls back to
    ``cache=False`` (one warning) when numba cannot place a cache for the function.

    ``allocates=False`` compiles the function without numba's runtime (NRT): it may then create no array
    (numba refuses to compile one that does), and in exchange keeps no reference counts.  numba counts a
    reference to every array an inlined helper takes, with an atomic increment and decrement, and cannot
    prune the pairs across a helper's branches: in the frame integrator that was over 90 % of the time of
    a step (20-30 ns per helper call against 1-2 ns without).  The step loops run on arrays allocated by
    their Python callers, so they are compiled this way.
    """

    # IEEE division (x / 0 is inf or NaN) instead of a Python ZeroDivisionError check on every division:
    # 20 % off the frame's step.  The compiled code already treats a non-finite value as a failure (the
    # integrator's NaN-aware norms, require_finite on every result), so no exception is lost.
    options.setdefault("error_model", "numpy")
    # Compiled code touches no Python object: it runs without the GIL, so the analyses of a thread pool (the
    # default executor, vdw_frames._parallel) run side by side.
    options.setdefault("nogil", True)
    if not allocates:
        options["_nrt"] = False  # numba's (underscored) target option; tests/test_jit.py checks it still works

    def compile_(function: Callable[..., Any]) -> Any:
        if cache:
            try:
                return _guard(_numba_njit(cache=True, **options)(function))
            except RuntimeError as error:
                if "cannot cache" not in str(error):
                    raise
                _warn_once("no cache", f"vdw_frames: numba cannot write a compilation cache here ({error}); "
                           "compiling without one (set NUMBA_CACHE_DIR to a writable folder to keep "
                           "compiled code between runs)", stacklevel=3)
        return _numba_njit(**options)(function)

    if args and callable(args[0]):
        return compile_(args[0])
    return compile_
