"""Walls' geometry factor (issue 30): a wall of magnification f acts on its story as the same wall with
its moduli and viscosities times f^2 (deformation f x drift, force f x its own on the story), and every
device class satisfies the Device protocol.  Units N-mm-s-tonne."""

from __future__ import annotations

import numpy as np
import pytest
from builders import README_WALL, TABLE4
from reference import tapered_sine

from vdw_frames import (
    FDMKDamper,
    FluidViscousDamper,
    FrictionDamper,
    GroundMotion,
    ShearBuilding,
    StrainDependentDamper,
    SupportedDamper,
    simulate,
)
from vdw_frames.element.device import Device
from vdw_frames.frame.building import static_wall_stiffness

FACTOR = 1.7  # a toggle-like geometry: the wall deforms 1.7 x the drift
MASSES, STIFFNESSES = [200.0, 180.0, 150.0], [120e3, 100e3, 80e3]


def motion():
    dt = 0.01
    t = np.arange(600) * dt
    return GroundMotion(tapered_sine(t, 1.3, 2000.0, ramp=1.0, duration=t[-1]), dt)


def wall(magnification=1.0, factor=1.0, **parameters):
    values = {name: factor * value for name, value in dict(README_WALL, **parameters).items() if name != "r"}
    return FDMKDamper(**values, r=README_WALL["r"], area=0.4e6, thickness=10.0, magnification=magnification)


def building(devices):
    return ShearBuilding(MASSES, STIFFNESSES, damping_ratio=0.03, devices=devices)


DEVICES = [
    FDMKDamper(**TABLE4),
    SupportedDamper(FDMKDamper(**TABLE4, magnification=0.8), 5e4),
    StrainDependentDamper.constant(FDMKDamper(**TABLE4), (2.25, 4.5)),
    FluidViscousDamper(100.0, 0.5, stiffness=2e4),
    FrictionDamper(1e5, 5e4),
]


@pytest.mark.parametrize("device", DEVICES, ids=lambda d: type(d).__name__)
def test_every_device_class_is_a_device(device):
    assert isinstance(device, Device)
    assert isinstance(device.describe(), str) and device.describe()
    assert device.magnification == (0.8 if isinstance(device, SupportedDamper) else 1.0)


@pytest.mark.parametrize("value", [0.0, -1.0, float("nan"), float("inf")])
def test_a_bad_wall_magnification_is_refused_naming_it(value):
    with pytest.raises(ValueError, match="magnification"):
        FDMKDamper(**TABLE4, magnification=value)
    with pytest.raises(ValueError, match="magnification"):
        StrainDependentDamper.from_nodes({"strains": (2.0, 4.0), **{k: (v, v) for k, v in TABLE4.items()}},
                                         magnification=value)


def test_magnified_wall_gives_the_story_response_of_the_f2_stiffer_wall_in_time():
    # Reference: the f^2-scaled wall of magnification 1 (the model's linearity: f (K (f d)) = (f^2 K) d).
    magnified = building({1: wall(FACTOR), 3: [wall(FACTOR), wall()]})
    scaled = building({1: wall(factor=FACTOR**2), 3: [wall(factor=FACTOR**2), wall()]})
    ground = motion()
    a, b = simulate(magnified, ground), simulate(scaled, ground)
    peak = np.abs(b.displacement).max()
    assert np.abs(a.displacement - b.displacement).max() <= 1e-12 * peak
    assert np.abs(a.story_wall_force - b.story_wall_force).max() <= 1e-12 * np.abs(b.story_wall_force).max()
    # Along the wall: f x the drift, and the force the story sees divided by f.
    assert np.allclose(a.wall_strain[:, 0] * 10.0, FACTOR * a.drift[:, 0], rtol=0, atol=1e-12 * peak)
    assert np.allclose(FACTOR * a.wall_force[:, 0], b.wall_force[:, 0], rtol=1e-12,
                       atol=1e-12 * np.abs(b.wall_force).max())


def test_magnified_supported_wall_is_the_f2_stiffer_assembly_in_time_and_frequency():
    support = 3e4
    magnified = building({2: SupportedDamper(wall(FACTOR), support)})
    scaled = building({2: SupportedDamper(wall(factor=FACTOR**2), FACTOR**2 * support)})
    ground = motion()
    a, b = simulate(magnified, ground), simulate(scaled, ground)
    assert np.abs(a.displacement - b.displacement).max() <= 1e-12 * np.abs(b.displacement).max()
    f = np.linspace(0.0, 8.0, 41)
    np.testing.assert_allclose(magnified.frequency_response(f), scaled.frequency_response(f), rtol=1e-13, atol=0)
    np.testing.assert_allclose(static_wall_stiffness(magnified), static_wall_stiffness(scaled), rtol=1e-14)


def test_magnified_wall_has_the_frequency_response_and_static_stiffness_of_the_f2_stiffer_wall():
    parameters = dict(G1=0.5)  # a static stiffness to compare
    magnified = building({1: wall(FACTOR, **parameters), 2: wall(0.6, **parameters)})
    scaled = building({1: wall(factor=FACTOR**2, **parameters), 2: wall(factor=0.36, **parameters)})
    f = np.linspace(0.0, 8.0, 41)
    np.testing.assert_allclose(magnified.frequency_response(f), scaled.frequency_response(f), rtol=1e-13, atol=0)
    np.testing.assert_allclose(static_wall_stiffness(magnified), static_wall_stiffness(scaled), rtol=1e-14)
    assert static_wall_stiffness(magnified)[0] == pytest.approx(FACTOR**2 * 0.5 * 0.4e6 / 10.0, rel=1e-14)
    # The Device protocol's story stiffness: magnification^2 K*(f), the f^2-scaled wall's K*.
    np.testing.assert_allclose(wall(FACTOR).story_stiffness(f), wall(factor=FACTOR**2).complex_stiffness(
        np.where(f > 0, f, 1.0)) * (f > 0) + (f == 0) * wall(factor=FACTOR**2).stiffness_transfer(0.0), rtol=1e-14)


def test_walls_of_different_magnification_on_one_story_are_stepped_apart():
    # Two equal walls with magnifications 1 and 2 act as the wall plus the wall x 4 (not as two walls of
    # one magnification: grouping them would step both with one deformation).
    ground = motion()
    a = simulate(building({2: [wall(), wall(2.0)]}), ground)
    b = simulate(building({2: [wall(), wall(factor=4.0)]}), ground)
    assert a.group_force.shape[1] == 2
    assert np.abs(a.displacement - b.displacement).max() <= 1e-12 * np.abs(b.displacement).max()


def test_strain_dependent_wall_keeps_its_magnification_and_is_linearised_at_the_device_strain():
    family = StrainDependentDamper.from_nodes({"strains": (2.0, 4.0), "G1": (1.0, 0.5), "G2": (3.0, 2.0),
                                               "eta1": (0.3, 0.2), "eta2": (2.0, 1.5), "r": (0.5, 0.5)},
                                              thickness=10.0, magnification=1.5)
    assert family.at(3.0).magnification == 1.5
    assert StrainDependentDamper.constant(wall(1.5), (2.0, 4.0)).magnification == 1.5
    # Drift 20 mm -> wall 30 mm -> strain 3.0: the wall at 300 %, seen by the story times 1.5^2.
    f = np.array([0.5, 1.0, 2.0])
    np.testing.assert_allclose(family.story_stiffness(f, 20.0), 2.25 * family.complex_stiffness(f, 3.0), rtol=1e-14)
    with pytest.raises(ValueError, match="drift_amplitude"):
        family.story_stiffness(f)
