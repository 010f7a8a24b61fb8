"""One rule for numbers everywhere (vdw_frames._validation): numpy scalars accepted, bools and strings refused,
messages that print plain numbers, and analyses too large for memory refused before anything is allocated."""

from __future__ import annotations

import re
import tracemalloc

import numpy as np
import pytest
from builders import README_WALL, readme_ten_story
from shared_data import REPO

import vdw_frames as vdw
from vdw_frames import FDMKDamper, GroundMotion, ShearBuilding, paper, read_two_column, simulate, sine_test
from vdw_frames.motion import default_record


@pytest.mark.parametrize("kind", [int, float, np.int32, np.int64, np.float32, np.float64])
def test_python_and_numpy_numbers_are_accepted_alike(kind):
    damper = FDMKDamper(G1=kind(0), G2=kind(3), eta1=0.5, eta2=kind(2), r=0.5 if kind in (int, np.int32, np.int64)
                        else kind(0.5), area=kind(100000), thickness=kind(10))
    assert damper == FDMKDamper(G1=0.0, G2=3.0, eta1=0.5, eta2=2.0, r=0.5, area=1e5, thickness=10.0)
    frame = ShearBuilding(np.array([300, 300], dtype=kind), [kind(200000)] * 2, damping_ratio=0.05,
                          damping_modes=np.array([1, 2], dtype=np.int64 if kind in (float, np.float32, np.float64)
                                                  else kind), devices={np.int64(1): damper})
    assert frame.damping_modes == (1, 2) and frame.masses == (300.0, 300.0)
    result = sine_test(damper, kind(10), kind(1), cycles=kind(3))
    assert result.cycles == 3


@pytest.mark.parametrize("call, match", [
    (lambda: FDMKDamper(**dict(README_WALL, G1="1.0")), "G1 must be a real number, got '1.0'"),
    (lambda: FDMKDamper(**dict(README_WALL, r=True)), "r must be a real number, got True"),
    (lambda: FDMKDamper(**dict(README_WALL, area=np.bool_(True))), "area must be a real number, got True"),
    (lambda: ShearBuilding([1.0, True], [1.0, 1.0]), "masses must be real numbers"),
    (lambda: ShearBuilding(["1", "2"], [1.0, 1.0]), "masses must be real numbers"),
    (lambda: ShearBuilding([1.0], [1.0], damping_ratio="0.05"), "damping_ratio must be a real number"),
    (lambda: GroundMotion(np.array([True, False]), 0.01),
     "acceleration must be real numbers, got an array of dtype bool"),
    (lambda: sine_test(FDMKDamper(**README_WALL), 10.0, 1.0, cycles=True),
     "cycles must be a whole number >= 1, got True"),
    (lambda: read_two_column(REPO / "README.md", skip_rows=1.5), "skip_rows must be a whole number >= 0, got 1.5"),
])
def test_bools_and_strings_are_refused_as_numbers(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_messages_print_plain_numbers():
    motion = GroundMotion([0.0, 1.0, 0.0], 0.02)
    calls = [
        lambda: vdw._validation.positive("dt", np.float64(-0.01)),
        lambda: GroundMotion(np.array([1.0, np.nan]), 0.01),
        lambda: GroundMotion([1.0, 2.0], np.float64(-0.01)),
        lambda: FDMKDamper(**dict(README_WALL, G1=np.float64(-1.0))),
        lambda: FDMKDamper(**dict(README_WALL, strain_range=(np.float64(3.0), np.float64(2.0)))),
        lambda: ShearBuilding(np.array([1.0, -1.0]), [1.0, 1.0]),
        lambda: ShearBuilding([1.0], [1.0], damping_ratio=np.float32(1.5)),
        lambda: ShearBuilding([1.0, 1.0], [1.0, 1.0], damping_modes=np.array([1, 5])),
        lambda: ShearBuilding([1.0], [1.0], devices={np.int64(4): FDMKDamper(**README_WALL)}),
        lambda: ShearBuilding([1.0], [1.0]).frequency_response(np.array([-1.0])),
        lambda: motion.spectrum(np.array([-1.0])),
        lambda: motion.spectrum(np.float64(1e9)),
        lambda: motion.resampled(np.float64(0.015)),
        lambda: FDMKDamper(**README_WALL).complex_modulus(np.array([np.float64(-2.0)])),
        lambda: vdw.identify(np.array([1.0, -2.0, 3.0]), [1.0, 1.0, 1.0], [1.0, 1.0, 1.0]),
        lambda: sine_test(FDMKDamper(**README_WALL), np.float64(-1.0), 1.0),
    ]
    for call in calls:
        with pytest.raises(ValueError) as error:
            call()
        assert "np." not in str(error.value) and "float64" not in str(error.value), str(error.value)
        assert re.search(r"-?\d", str(error.value))  # the value itself is named


def peak_allocation(call):
    """(the ValueError's message or None, the peak traced allocation in bytes) of ``call()``."""
    tracemalloc.start()
    try:
        call()
    except ValueError as error:
        message = str(error)
    else:
        message = None
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return message, peak


def test_analyses_too_large_for_memory_are_refused_before_allocating():
    motion = default_record()
    message, peak = peak_allocation(lambda: motion.resampled(2e-8))
    assert "needs 1,250,000,001 steps, whose arrays would take 27.9 GiB (limit 2 GiB)" in message
    assert peak < 20e6
    building = readme_ten_story()
    message, peak = peak_allocation(lambda: simulate(building, motion, dt=1e-7))
    assert "simulate (dt = 1e-07 s, 10 floors, 6 walls) needs 250,000,001 steps" in message and peak < 20e6
    message, peak = peak_allocation(lambda: sine_test(paper.fitted(300), 30.0, 1.0, cycles=100_000_000))
    assert "sine_test(100,000,000 cycles of 200 steps) needs 20,000,000,001 steps" in message and peak < 20e6
    message, _ = peak_allocation(lambda: vdw.motion.synthetic_ground_motion(duration=1e9))
    assert "needs 100,000,000,001 steps" in message


def test_interpolation_too_large_for_memory_is_refused_before_allocating():
    # interpolated(10**12) raised numpy's MemoryError; 10**7 allocated (n - 1) m + 1 values of 8 bytes unasked.
    motion = GroundMotion(np.sin(0.1 * np.arange(1001)), 0.01, "sine")
    message, peak = peak_allocation(lambda: motion.interpolated(10**7))
    # 1000 x 10**7 + 1 steps of 24 bytes (the array, its temporaries and the record's copy): 224 GiB.
    assert message == ("substeps = 10000000 on ground motion 'sine' (1001 samples every 0.01 s) needs "
                       f"10,000,000,001 steps, whose arrays would take {10_000_000_001 * 24 / 1024**3:.3g} GiB "
                       "(limit 2 GiB); use fewer substeps") and peak < 20e6
    for substeps, shown in ((10**12, "1000000000000"), (10**400, "about 1e400")):
        message, peak = peak_allocation(lambda m=substeps: motion.interpolated(m))
        assert message.startswith(f"substeps = {shown} on ground motion 'sine'") and "(limit 2 GiB)" in message
        assert peak < 20e6
    # Within the limit nothing changes: the interpolation acceleration_at gives.
    np.testing.assert_array_equal(motion.interpolated(4), motion.acceleration_at(0.0025))


def test_whole_numbers_beyond_any_float_are_compared_not_converted():
    # 10**400 raised OverflowError (math.isfinite converts to float) instead of being a number like any other.
    from vdw_frames._validation import whole_number

    assert whole_number("n", 10**400, 0) == 10**400
    for bad in (-(10**400), 2.5, float("inf"), np.float64("nan")):
        with pytest.raises(ValueError, match=r"n must be a whole number >= 0, got"):
            whole_number("n", bad, 0)
    with pytest.raises(ValueError, match=r"max_steps must be <= 2\*\*40"):
        vdw.element.FastMemory(max_steps=10**400)


def test_a_wall_bank_too_large_for_memory_is_refused_before_allocating():
    # 1.2e9 steps of exact memory raised MemoryError; 1e308 steps an OverflowError.
    from vdw_frames.element import FastMemory, WallBank

    wall = FDMKDamper(**README_WALL)
    with pytest.raises(ValueError, match=r"WallBank \(1 walls, exact memory\) needs 1,188,763,351 steps, whose arrays "
                                         r"would take 44.3 GiB"):
        WallBank((wall,), 0.01, 1_188_763_351, memory="exact")
    with pytest.raises(ValueError, match=r"steps must be at most 2\*\*40 = 1,099,511,627,776 with the fast memory"):
        WallBank((wall,), 0.01, 1e308, memory=FastMemory())
    with pytest.raises(ValueError, match="walls must be a sequence of walls, got float"):
        WallBank(1.5, 0.01, 10)


def test_a_tall_frame_s_damping_matrix_is_not_copied_by_simulate():
    """simulate passes the building's (cached, read-only) n x n damping matrix to the integrator as it is: its
    only n x n allocation is the step's work matrix (integrator.scratch), so its peak stays near n^2 floats,
    not twice that (a 10 000-story frame: 0.8 GB more).  Reference: the sizes of the arrays simulate needs."""
    motion = GroundMotion(100.0 * np.sin(0.1 * np.arange(20)), 0.01, "short")
    simulate(ShearBuilding([100.0] * 3, [1e5] * 3), motion)  # the compiled loop loaded before tracing
    n = 2000
    tall = ShearBuilding([100.0] * n, [1e5] * n)
    assert tall.damping_matrix.nbytes == 8 * n * n  # cached on the building, before the trace
    _, peak = peak_allocation(lambda: simulate(tall, motion))
    assert 8 * n * n < peak < 1.5 * 8 * n * n
