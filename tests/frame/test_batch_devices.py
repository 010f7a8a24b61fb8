"""run_batch and IDA of a yielding frame with fluid viscous (linear and nonlinear) and friction dampers: every
peak equals that of simulate run one by one on the same building, and property factors scale every device's
force-defining property (C, slip force), checked against buildings written out by their constructors."""

import concurrent.futures

import numpy as np
import pytest
from builders import tapered_sine_pair

from vdw_frames import Bilinear, FluidViscousDamper, FrictionDamper, ShearBuilding, simulate
from vdw_frames.frame.batch import run_batch
from vdw_frames.frame.ida import incremental_dynamic_analysis

STORY_PEAKS = ("peak_drift", "peak_drift_ratio", "peak_absolute_acceleration", "peak_story_wall_force",
               "residual_drift")
DEVICES = ("force", "deformation", "velocity")


def device_frame(factor=1.0):
    """Three yielding stories (300, 300, 250 t; 200, 180, 150 kN/mm; 3.5 m) with a linear FVD (story 1), a
    nonlinear FVD with a brace on a diagonal (story 2) and two friction dampers (story 3); every C and slip force
    times ``factor``."""
    return ShearBuilding([300.0, 300.0, 250.0], [2e5, 1.8e5, 1.5e5], story_heights=[3500.0] * 3,
                         hysteresis=[Bilinear(1.2e6, 0.03), Bilinear(1.0e6, 0.03), Bilinear(0.7e6, 0.03)],
                         devices={1: FluidViscousDamper(400.0 * factor, 1.0),
                                  2: FluidViscousDamper(3000.0 * factor, 0.5, stiffness=1.5e5, magnification=0.85),
                                  3: [FrictionDamper(5e4 * factor, 8e4), FrictionDamper(5e4 * factor, 8e4)]})


def peaks_of(result):
    """The batch's peaks of one simulate result, computed here from its histories."""
    peaks = {"peak_drift": np.abs(result.drift).max(axis=0),
             "peak_drift_ratio": np.abs(result.drift).max(axis=0) / 3500.0,
             "peak_absolute_acceleration": np.abs(result.absolute_acceleration).max(axis=0),
             "peak_story_wall_force": np.abs(result.story_wall_force).max(axis=0),
             "residual_drift": result.drift[-1], "peak_base_shear": np.abs(result.base_shear).max()}
    peaks.update({f"peak_device_{name}": np.abs(getattr(result, f"device_{name}")).max(axis=0) for name in DEVICES})
    return peaks


def test_run_batch_of_every_device_kind_equals_simulate_one_by_one():
    motions, scales = tapered_sine_pair(), (0.6, 1.5)
    with concurrent.futures.ThreadPoolExecutor(2) as executor:
        batch = run_batch(device_frame(), motions, scales, executor, progress=False)
    assert batch.peak_device_force.shape == (2, 2, 4)
    yielded = False
    for m, motion in enumerate(motions):
        for s, scale in enumerate(scales):
            result = simulate(device_frame(), motion.scaled(scale))
            yielded |= bool((np.abs(result.drift).max(axis=0) > np.array([6.0, 5.56, 4.67])).any())
            expected = peaks_of(result)
            for name, value in expected.items():
                got = getattr(batch, name)[m, s]
                np.testing.assert_allclose(got, value, rtol=1e-12 if name == "peak_drift_ratio" else 0, atol=0,
                                           err_msg=name)
            assert (expected["peak_device_force"] > 1e4).all()  # every device worked
    assert yielded  # the stronger runs yield a story: the inelastic path is the one compared


def test_property_factors_scale_every_device_and_envelope_the_peaks():
    motions, factors = tapered_sine_pair()[:1], (0.8, 1.25)
    with concurrent.futures.ThreadPoolExecutor(2) as executor:
        batch = run_batch(device_frame(), motions, (1.0,), executor, progress=False, property_factors=factors)
    variants = {f: peaks_of(simulate(device_frame(f), motions[0])) for f in factors}
    for name in ("peak_drift", "peak_story_wall_force", *(f"peak_device_{d}" for d in DEVICES)):
        stacked = np.stack([variants[f][name] for f in factors])
        np.testing.assert_array_equal(getattr(batch, name)[0, 0], stacked.max(axis=0), err_msg=name)
        np.testing.assert_array_equal(batch.governing_factor[name][0, 0],
                                      np.array(factors)[np.argmax(stacked, axis=0)], err_msg=name)
    # more C and slip force: larger device forces, smaller drifts
    assert (batch.governing_factor["peak_device_force"][0, 0] == 1.25).all()
    assert variants[1.25]["peak_drift"][0] < variants[0.8]["peak_drift"][0]


def test_ida_of_every_device_kind_equals_simulate_one_by_one():
    motions = tapered_sine_pair()
    building = device_frame()
    period = float(building.periods[0])
    step = 0.4 * 9806.65
    with concurrent.futures.ThreadPoolExecutor(2) as executor:
        ida = incremental_dynamic_analysis(building, motions, step, 3 * step, executor=executor)
    for m, motion in enumerate(motions):
        assert ida.intensities[m].size >= 2
        for i, level in enumerate(ida.intensities[m]):
            factor = level / float(motion.spectrum(period, 0.05))  # Sa(T1, 5 %) scaled to the level
            result = simulate(building, motion.scaled(factor))
            assert ida.peak_drift_ratio[m][i] == pytest.approx(np.abs(result.drift).max() / 3500.0, rel=1e-12)
            assert ida.collapsed[m][i] == (result.collapsed or not result.converged)
