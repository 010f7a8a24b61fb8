"""size_devices (issue 30): a target damping ratio in mode 1 reached with any device type.  References: the
one-story closed form for a linear FVD (xi = (c + C) / (2 sqrt(k m))), and the sized building's own
modal_analysis (the target to 1e-6).  Units N-mm-s-tonne."""

from __future__ import annotations

import numpy as np
import pytest

from vdw_frames import FDMKDamper, FluidViscousDamper, FrictionDamper, ShearBuilding
from vdw_frames.design import DeviceSizing, size_devices, size_walls
from vdw_frames.frame import modal_analysis

TARGET = 0.12
MASSES, STIFFNESSES = [300.0, 300.0, 250.0], [2.0e5, 1.8e5, 1.5e5]
HEIGHTS = [3500.0] * 3
DRIFT = 0.005 * np.array(HEIGHTS)  # design drift ratio 0.5 %: 17.5 mm a story


def frame(**options):
    return ShearBuilding(MASSES, STIFFNESSES, damping_ratio=0.02, story_heights=HEIGHTS, **options)


def test_one_story_linear_fvd_sizing_is_the_closed_form_coefficient():
    mass, stiffness = 400.0, 1.6e5
    building = ShearBuilding([mass], [stiffness], damping_ratio=0.02)
    c = building.damping_matrix[0, 0]
    sized = size_devices(building, FluidViscousDamper(100.0, 1.0, magnification=0.9), TARGET)
    # m s^2 + (c + f^2 C) s + k: xi = (c + f^2 C) / (2 sqrt(k m))
    expected = (2.0 * TARGET * np.sqrt(stiffness * mass) - c) / 0.9**2
    (device,) = sized.building.devices[1]
    coefficient = device.C
    assert coefficient == pytest.approx(expected, rel=1e-9)
    assert sized.damping_ratio == pytest.approx(TARGET, abs=1e-9)
    assert sized.drift_amplitudes is None and sized.linearisation == ()


TEMPLATES = {
    "wall": FDMKDamper(G1=0.5, G2=3.0, eta1=0.3, eta2=2.0, r=0.5, area=0.2e6),
    "linear FVD": FluidViscousDamper(500.0, 1.0, stiffness=1e5),
    "nonlinear FVD": FluidViscousDamper(2000.0, 0.5, stiffness=1e5),
    "friction": FrictionDamper(2.0e4, 4.0e4),  # slips at 0.5 mm, linearised at 17.5 mm
}


@pytest.mark.parametrize("name", TEMPLATES)
def test_each_device_type_meets_the_target_by_the_sized_buildings_modal_analysis(name):
    template = TEMPLATES[name]
    sized = size_devices(frame(), template, TARGET, distribution="stiffness", drift_amplitude=DRIFT)
    assert isinstance(sized, DeviceSizing)
    nonlinear = name in ("nonlinear FVD", "friction")
    modal = modal_analysis(sized.building, 1, drift_amplitude=DRIFT if nonlinear else None)
    assert modal.damping_ratios[0] == pytest.approx(TARGET, abs=1e-6)
    # The template scaled by factor x weight on every story (stiffness weights: k / k_max).
    for story, weight in zip((1, 2, 3), np.array(STIFFNESSES) / max(STIFFNESSES), strict=True):
        (device,) = sized.building.devices[story]
        assert device == template.resized(sized.factor * weight)
    if nonlinear:
        np.testing.assert_array_equal(sized.drift_amplitudes, DRIFT)
        assert len(sized.linearisation) == 3 and "17.5 mm" in sized.linearisation[0]
        assert "17.5 mm" in sized.report()
    else:
        assert sized.linearisation == ()


def test_friction_sizing_scales_slip_force_and_stiffness_together():
    template = TEMPLATES["friction"]
    sized = size_devices(frame(), template, TARGET, drift_amplitude=DRIFT)
    (device,) = sized.building.devices[1]
    assert device.slip_force / device.stiffness == pytest.approx(template.slip_force / template.stiffness, rel=1e-14)


def test_other_devices_are_kept_and_devices_of_the_templates_kind_replaced():
    wall = TEMPLATES["wall"]
    old = FluidViscousDamper(50.0, 1.0)
    building = frame(devices={1: [wall, old], 3: old})
    sized = size_devices(building, FluidViscousDamper(500.0, 1.0), TARGET, stories=[1, 2])
    assert sized.building.devices[1][0] == wall
    assert old not in sized.building.devices[1] and 3 not in sized.building.devices
    assert modal_analysis(sized.building, 1).damping_ratios[0] == pytest.approx(TARGET, abs=1e-6)


def test_existing_devices_scaled_alike():
    building = frame(devices={1: FluidViscousDamper(300.0, 1.0), 2: TEMPLATES["wall"]})
    sized = size_devices(building, None, TARGET, distribution="existing")
    assert sized.building.devices[1][0] == FluidViscousDamper(300.0 * sized.factor, 1.0)
    assert modal_analysis(sized.building, 1).damping_ratios[0] == pytest.approx(TARGET, abs=1e-6)


def test_size_walls_is_unchanged_and_equals_size_devices_for_a_wall():
    wall = TEMPLATES["wall"]
    walled = size_walls(frame(), wall, TARGET)
    sized = size_devices(frame(), wall, TARGET)
    assert walled.devices == sized.building.devices


def test_bad_requests_are_refused():
    with pytest.raises(ValueError, match=r"story 1's FVD.*drift_amplitude"):
        size_devices(frame(), TEMPLATES["nonlinear FVD"], TARGET)
    with pytest.raises(ValueError, match="device must be a damping device"):
        size_devices(frame(), "a damper", TARGET)
    with pytest.raises(ValueError, match="drift_amplitude must be > 0"):
        size_devices(frame(), TEMPLATES["friction"], TARGET, drift_amplitude=-1.0)
    with pytest.raises(ValueError, match="out of reach"):
        size_devices(frame(), TEMPLATES["friction"], 0.9, drift_amplitude=DRIFT)
    with pytest.raises(ValueError, match="no devices are needed"):
        size_devices(frame(), TEMPLATES["linear FVD"], 0.01)
