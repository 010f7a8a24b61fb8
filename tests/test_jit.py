"""What vdw_frames._jit assumes of numba: a failure here names the assumption that broke, instead of the
package silently compiling without its versioned cache or with other error semantics."""

from __future__ import annotations

import re
from importlib.metadata import requires, version
from pathlib import Path

import numpy as np
from numba.core import caching
from packaging.specifiers import SpecifierSet

from vdw_frames import _jit
from vdw_frames.element import kernel


def test_numba_is_inside_the_pinned_range():
    pins = [r for r in requires("vdw-frames") or [] if re.match(r"numba\b", r)]
    assert len(pins) == 1, f"numba pin not found in the package metadata: {requires('vdw-frames')}"
    assert version("numba") in SpecifierSet(pins[0].removeprefix("numba")), (
        f"numba {version('numba')} is outside the tested range {pins[0]}: check vdw_frames/_jit.py's locators")


def test_numba_still_has_the_cache_classes_the_versioned_locators_extend():
    implementation = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl", None)
    assert implementation is not None, "numba.core.caching has no CacheImpl/_CacheImpl any more"
    for name in ("UserProvidedCacheLocator", "InTreeCacheLocator", "UserWideCacheLocator"):
        assert getattr(caching, name, None) or getattr(caching, "_" + name, None), f"numba lost {name}"
    # Installed once, ahead of numba's own locators.
    assert getattr(implementation, "_vdw_frames", False)
    assert implementation._locator_classes[0].__name__.startswith("VdwFrames")


def test_a_package_function_caches_under_the_fingerprint_folder():
    cache = kernel.set_coefficients._cache  # numba internals: what this test guards
    assert Path(cache.cache_path).name == _jit._TAG
    assert re.fullmatch(r"vdw-[0-9a-f]{16}", _jit._TAG)


def test_compiled_division_follows_ieee_not_python():
    @_jit.njit(cache=False)
    def divide(a, b):
        return a / b

    # error_model="numpy": x / 0 is inf or NaN (the package's finiteness checks catch it), never an exception.
    assert divide(1.0, 0.0) == np.inf
    assert np.isnan(divide(0.0, 0.0))
