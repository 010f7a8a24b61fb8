"""numba's ``njit`` with on-disk caching that degrades to no caching where no cache can be written.

numba refuses to decorate a function with ``cache=True`` when it finds no writable cache location
(a read-only install with an unwritable HOME, for example): ``import vdw_frames`` would then fail.
Here such a function is compiled without a cache instead, with one warning for the whole package.
"""

from __future__ import annotations

import warnings

from numba import njit as _numba_njit

_warned = False


def njit(*args, cache: bool = False, **options):
    """``numba.njit``, used as ``@njit(cache=True)``; falls back to ``cache=False`` (one warning) when
    numba cannot place a cache for the function."""

    def compile_(function):
        global _warned
        if cache:
            try:
                return _numba_njit(cache=True, **options)(function)
            except RuntimeError as error:
                if "cannot cache" not in str(error):
                    raise
                if not _warned:
                    _warned = True
                    warnings.warn(f"vdw_frames: numba cannot write a compilation cache here ({error}); "
                                  "compiling without one (set NUMBA_CACHE_DIR to a writable folder to keep "
                                  "compiled code between runs)", RuntimeWarning, stacklevel=3)
        return _numba_njit(**options)(function)

    if args and callable(args[0]):
        return compile_(args[0])
    return compile_
