"""What vdw_frames._jit assumes of numba: a failure here names the assumption that broke, instead of the
package silently compiling without its versioned cache or with other error semantics."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from importlib.metadata import requires, version
from pathlib import Path

import numpy as np
import pytest
from numba.core import caching, errors
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


def test_allocates_false_compiles_without_reference_counts_and_refuses_an_allocation():
    # The step loops rely on numba's (underscored) _nrt option: no reference counting, no allocation.
    @_jit.njit(cache=False, inline="always")
    def branchy(arrays, i, x):
        if arrays[0][i] == 0.0:
            return x, 1.0
        if x > arrays[1][i]:
            return arrays[1][i], 0.0
        return x * arrays[2][i], arrays[2][i]

    def loop(arrays, out):
        for i in range(out.shape[0] // 2):
            out[i], out[-1 - i] = branchy(arrays, i, 2.0)

    arrays = (np.array([1.0, 0.0, 3.0]), np.array([1.0, 5.0, 3.0]), np.array([2.0, 2.0, 2.0]))
    expected = np.zeros(6)
    loop(arrays, expected)  # plain Python
    assert list(expected) == [1.0, 2.0, 4.0, 2.0, 1.0, 0.0]
    for allocates in (True, False):
        compiled, out = _jit.njit(cache=False, allocates=allocates)(loop), np.zeros(6)
        compiled(arrays, out)
        assert list(out) == list(expected)
        # With numba's runtime, the helper's array arguments are counted (what the option avoids); without, never.
        assert ("NRT_incref" in next(iter(compiled.inspect_llvm().values()))) == allocates

    @_jit.njit(cache=False, allocates=False)
    def allocate(n):
        return np.zeros(n)

    with pytest.raises(errors.TypingError):
        allocate(3)


# A package function compiled in a fresh cache folder (NUMBA_CACHE_DIR), in a separate process each time.
WEIGHTS = """if True:
    import json
    {prelude}
    from vdw_frames.element.fractional import get_method
    print(json.dumps([get_method(name).weights(0.5, 12, 0.01).tolist() for name in ("trapezoidal", "bdf2")]))
"""
CACHE_WARNING = "RuntimeWarning: vdw_frames: numba's compilation cache"


def run_weights(cache, prelude=""):
    """(weights, stderr) of WEIGHTS run with NUMBA_CACHE_DIR = ``cache``; fails on a non-zero exit."""
    environment = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    run = subprocess.run([sys.executable, "-c", WEIGHTS.format(prelude=prelude)], env=environment,
                         capture_output=True, text=True, timeout=600, check=False)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout), run.stderr


def expected_weights():
    from vdw_frames.element.fractional import get_method

    return [get_method(name).weights(0.5, 12, 0.01).tolist() for name in ("trapezoidal", "bdf2")]


@pytest.mark.parametrize("kind", ["nbi", "nbc"])
def test_a_truncated_cache_file_is_recompiled_with_one_warning(tmp_path, kind):
    # A truncated index (or data file) made every later run fail with UnpicklingError.
    first, stderr = run_weights(tmp_path)
    assert first == expected_weights() and CACHE_WARNING not in stderr
    files = sorted(tmp_path.rglob(f"fractional.*.{kind}"))
    assert len(files) == 2  # the trapezoidal and BDF2 weight functions
    for path in files:
        path.write_bytes(path.read_bytes()[:40])
    again, stderr = run_weights(tmp_path)
    assert again == first
    assert stderr.count(CACHE_WARNING) == 1 and "could not be read" in stderr and "recompiling" in stderr
    _, stderr = run_weights(tmp_path)  # replaced: read back without a word
    assert CACHE_WARNING not in stderr


def test_a_full_disk_under_the_cache_runs_without_it_with_one_warning(tmp_path):
    # simulate raised a raw OSError [Errno 28] when numba could not write its cache.
    full = """from numba.core import caching
    def full(self, *args):
        raise OSError(28, "No space left on device")
    caching.IndexDataCacheFile._open_for_write = full"""
    weights, stderr = run_weights(tmp_path, full)
    assert weights == expected_weights()
    assert stderr.count(CACHE_WARNING) == 1 and "could not be written" in stderr
    assert "No space left on device" in stderr and not list(tmp_path.rglob("*.nbi"))


def test_the_package_compiles_without_the_gil():
    # Threads run the analyses side by side only if the compiled entry points release the GIL (that they do:
    # tests/frame/test_stop.py, whose failing task runs while another thread's analysis is compiled code).
    from vdw_frames.frame import lane_kernel

    for function in (lane_kernel.integrate_lanes, lane_kernel.run_lane, _jit.njit(cache=False)(lambda x: x)):
        assert function.targetoptions["nogil"] is True
