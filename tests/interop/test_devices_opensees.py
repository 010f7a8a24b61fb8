"""Fluid viscous and friction dampers exported to OpenSees (vdw_frames.interop.opensees.device_material).

References: OpenSees's own materials, run by OpenSeesPy (``ViscousDamper``: Akcelyan and Lignos's adaptive
Dormand-Prince integration of the Maxwell law; ``Viscous``; ``ElasticPP``), in OpenSees's own Newmark-Newton
loop, against :func:`vdw_frames.simulate` (the package's implicit-trapezoid FVD and return-mapping friction
rules, its own integrator).  The frames: ``tests/opensees_frame.py`` (``Steel01`` stories, the P-Delta
spring, Rayleigh a0 M + a1 K on the story springs, one ``zeroLength`` element per device without Rayleigh).
Both sides use Newmark's average acceleration on the same step, Newton to 1e-12 mm.
"""

import dataclasses
import warnings

import numpy as np
import opensees_frame
import pytest
from builders import FRACTIONAL_WALL_A, three_story
from opensees_frame import imposed_force
from reference import history_deviation, peak_deviation

from vdw_frames import Bilinear, FDMKDamper, FluidViscousDamper, FrictionDamper, ShearBuilding, simulate
from vdw_frames.element.devices import device_response
from vdw_frames.frame import NewtonRaphson
from vdw_frames.interop.opensees import device_element, device_material, device_material_arguments
from vdw_frames.motion import G, synthetic_ground_motion

pytestmark = pytest.mark.opensees

TIGHT = NewtonRaphson(displacement_tolerance=1e-12, force_tolerance=1e-13, max_iterations=50)

NONLINEAR_FVD = FluidViscousDamper(2.5e4, 0.5, 2.0e5)  # N (s/mm)^0.5, -, N/mm
LINEAR_FVD = FluidViscousDamper(1.0e3, 1.0, 2.0e5)  # N s/mm, -, N/mm
DASHPOT = FluidViscousDamper(1.0e3, 1.0)
FRICTION = FrictionDamper(1.5e5, 1.0e5)  # N, N/mm


def yielding_three_story(device):
    """tests/builders.three_story with Bilinear stories (0.25 x the weight above, 3 % hardening), P-Delta (the
    weight above) and ``device`` on every story."""
    building = three_story()
    weight_above = np.cumsum((np.asarray(building.masses) * G)[::-1])[::-1]  # N
    return ShearBuilding(building.masses, building.stiffnesses, story_heights=building.story_heights,
                         hysteresis=[Bilinear(force, 0.03) for force in 0.25 * weight_above],
                         gravity_loads=weight_above, devices={story: [device] for story in (1, 2, 3)})


def synthetic():
    """A seeded synthetic record: 15 s at 0.01 s, PGA 0.4 g (Clough-Penzien)."""
    return synthetic_ground_motion(duration=15.0, dt=0.01, pga=0.4 * G)


def both(building, motion, dt):
    """(vdw_frames result, OpenSees drifts (mm)) of ``building`` under ``motion`` on steps of ``dt`` s (the
    record interpolated linearly on both sides)."""
    result = simulate(building, motion, dt=dt, newton=TIGHT)
    drift = opensees_frame.drifts(opensees_frame.run(building, motion.acceleration_at(dt), dt, tolerance=1e-12))
    return result, drift


def check_the_devices_matter(result, building):
    """The devices' peak force is a real share of the story spring's and the stories yield: the comparison
    tests both."""
    assert (result.peak_ductility > 1.5).all(), result.peak_ductility
    share = np.abs(result.device_force).max(axis=0) / np.abs(result.story_shear).max(axis=0)
    assert (share > 0.05).all(), share


# ---------------------------------------------------------------------------------------------- materials
def test_material_arguments_fold_the_magnification_in():
    # The module docstring's scaling, in numbers: f^2 K_b, f^(1 + alpha) C; f^2 C; f^2 k, F_s / (f k).
    f = 1.7
    cases = [(FluidViscousDamper(2.0e4, 0.5, 1.0e5, f), "ViscousDamper", (f**2 * 1.0e5, f**1.5 * 2.0e4, 0.5)),
             (FluidViscousDamper(300.0, 1.0, magnification=f), "Viscous", (f**2 * 300.0, 1.0)),
             (FrictionDamper(1.0e5, 2.0e4, f), "ElasticPP", (f**2 * 2.0e4, 1.0e5 / (f * 2.0e4)))]
    for device, kind, parameters in cases:
        name, *values = device_material_arguments(device)
        assert name == kind
        assert values == pytest.approx(parameters, rel=1e-15)
    with pytest.raises(ValueError, match="WallBridge"):
        device_material_arguments(FDMKDamper(G1=0.0, G2=3.0, eta1=0.3, eta2=2.0, r=0.5))


@pytest.mark.parametrize("device", [NONLINEAR_FVD, LINEAR_FVD, DASHPOT, FRICTION])
def test_scaled_material_is_the_device_at_magnified_deformation(ops, device):
    # OpenSees against itself: the story-unit material of a device with magnification f, driven by a drift d,
    # gives f x (the f = 1 material driven by f d).  This checks the docstring's proof with OpenSees's own
    # integration (DP's relative error control is scale-free; its absolute one, 1e-10 N, is not: measured
    # 3e-12 to 7e-11, bar 1e-9).
    f, dt = 1.7, 0.01
    t = np.arange(301) * dt
    drift = 15.0 * (1.0 - np.cos(2.0 * np.pi * 1.2 * t)) * np.exp(-0.3 * t)
    scaled = imposed_force(ops, lambda o: device_material(o, 7, dataclasses.replace(device, magnification=f)),
                           drift, dt)
    plain = imposed_force(ops, lambda o: device_material(o, 7, device), f * drift, dt)
    assert np.abs(scaled).max() > 1e3  # N: a real force
    assert np.abs(scaled - f * plain).max() <= 1e-9 * np.abs(scaled).max()


@pytest.mark.parametrize("device, bar, measured", [
    (FluidViscousDamper(5.0e3, 0.5, 2.0e4, 1.7), 4e-3, 2.3e-3),  # O(dt^2): trapezoid against Dormand-Prince
    (FluidViscousDamper(300.0, 1.0, 2.0e4, 0.8), 4e-3, 1.3e-3),
    (FluidViscousDamper(300.0, 1.0, magnification=1.3), 1e-8, 1e-10),  # C v on both sides
    (FrictionDamper(1.0e5, 2.0e4, 0.6), 1e-9, 3e-12),  # the same return mapping
])
def test_exported_material_equals_the_device_driven_alone(ops, device, bar, measured):
    # Imposed drift u = 20 (1 - cos 2 pi t) mm: OpenSees's material against vdw_frames' device_response (the
    # device stepped as the frame steps it).  The FVDs with a brace differ by the two integrators' O(dt^2)
    # (halving dt divides it by about 4); the others are the same rule.
    deviations = []
    for dt in (0.01, 0.005):
        t = np.arange(round(3.0 / dt) + 1) * dt
        drift = 20.0 * (1.0 - np.cos(2.0 * np.pi * t))
        exported = imposed_force(ops, lambda o: device_material(o, 7, device), drift, dt)
        own = device_response(device, drift, dt)["force"]
        deviations.append(np.abs(exported - own).max() / np.abs(own).max())
    assert deviations[0] < bar, (deviations, measured)
    if bar > 1e-6:
        assert 3.5 < deviations[0] / deviations[1] < 4.5, deviations  # second order


def test_device_element_refuses_bad_nodes(ops):
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(1, 0.0)
    ops.node(2, 0.0)
    with pytest.raises(ValueError, match="node_j must be the tag of an existing node"):
        device_element(ops, 5, 1, 3, FRICTION)
    with pytest.raises(ValueError, match="two different nodes"):
        device_element(ops, 5, 1, 1, FRICTION)
    assert device_element(ops, 5, 1, 2, FRICTION) == 5
    assert list(ops.getEleTags()) == [5]
    ops.wipe()


# ---------------------------------------------------------------------------------------------- frames
@pytest.mark.records
def test_yielding_frame_with_nonlinear_fvds_matches_opensees_viscous_damper(ops, record):
    # The test: 3 stories, Bilinear (Steel01) stories with P-Delta, an FVD (alpha = 0.5, K_b = 2e5 N/mm)
    # on every story, El Centro x 1.5 (stories reach ductility 3-4; the dampers' peak force is 17-44 % of the
    # story spring's).  Peak drifts within 1 %: measured 0.20 % at dt = 0.01 s (the record's 0.02 s halved), 0.046 % at
    # 0.005 s: the difference is the two FVD integrators' O(dt^2) (0.91 % at the record's own 0.02 s, a step
    # several times the brace-dashpot relaxation time, where the trapezoid rings and Dormand-Prince sub-steps).
    building = yielding_three_story(NONLINEAR_FVD)
    motion = record.scaled(1.5)
    deviations = {}
    for dt in (0.01, 0.005):
        result, expected = both(building, motion, dt)
        deviations[dt] = peak_deviation(result.drift, expected)
        assert deviations[dt] < 0.01, deviations  # the bar
        assert history_deviation(result.drift, expected) < 0.01
    assert deviations[0.01] < 3e-3, deviations  # measured 2.0e-3
    assert deviations[0.01] / deviations[0.005] > 3.0, deviations  # second order: measured 4.4
    check_the_devices_matter(result, building)


@pytest.mark.parametrize("device, bar, measured", [
    (NONLINEAR_FVD, 3e-3, 7.9e-4),  # ductility 3.3-4.8
    (LINEAR_FVD, 3e-3, 1.2e-3),  # alpha = 1 through ViscousDamper too
    (DASHPOT, 1e-9, 8e-14),  # Viscous: C v, Newmark's velocity on both sides
])
def test_frame_with_fvds_under_a_synthetic_record_matches_opensees(ops, device, bar, measured):
    building = yielding_three_story(device)
    result, expected = both(building, synthetic(), 0.01)
    deviation = peak_deviation(result.drift, expected)
    assert deviation < bar, (deviation, measured)
    assert history_deviation(result.drift, expected) < max(bar, 1e-9) * 1.5
    check_the_devices_matter(result, building)


@pytest.mark.parametrize("magnification", [1.0, 0.8])
def test_frame_with_friction_dampers_matches_opensees_elastic_pp(ops, magnification):
    # ElasticPP is the friction damper's own law (the same return mapping): whole histories within 1e-6 of the
    # peak (measured 1e-12), with the dampers slipping (slip force reached on every story).
    device = dataclasses.replace(FRICTION, magnification=magnification)
    building = yielding_three_story(device)
    result, expected = both(building, synthetic(), 0.01)
    assert history_deviation(result.drift, expected) < 1e-6
    assert peak_deviation(result.drift, expected) < 1e-6
    assert np.allclose(np.abs(result.device_force).max(axis=0), device.slip_force, rtol=1e-12)  # every one slips
    check_the_devices_matter(result, building)


@pytest.mark.records
def test_walls_through_the_bridge_beside_native_devices_equal_simulate(ops, record):
    # Every kind in one OpenSees model: fractional walls through WallBridge, friction dampers (ElasticPP) and
    # linear dashpots (Viscous) as native elements, on the fractional ten-story frame.  The three rules are
    # the package's own (walls: the same kernel; friction and dashpot: the same exact rules), so the model
    # equals simulate to the Newton tolerance (measured 1.3e-12 in peak drifts; bar 1e-9, as the bridge's tests).
    devices = {story: (FRACTIONAL_WALL_A, dataclasses.replace(FRICTION, slip_force=2.0e5, magnification=0.9))
               for story in range(1, 11)}
    devices[3] = devices[3] + (dataclasses.replace(DASHPOT, magnification=1.2),)
    building = ShearBuilding([500.0] * 10, np.linspace(800e3, 400e3, 10), devices=devices)  # builders' fractional
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # the walls' strain-range warning: not what is tested
        expected = simulate(building, record, newton=TIGHT)
    displacement, bridge = opensees_frame.run_bridged(building, record.acceleration, record.dt, step_by_step=True)
    drift = opensees_frame.drifts(displacement)
    assert bridge.failed_step is None and len(bridge) == 10
    assert peak_deviation(drift, expected.drift) < 1e-9
    assert history_deviation(drift, expected.drift) < 1e-9
    assert np.abs(expected.device_force[:, :10]).max() == pytest.approx(2.0e5, rel=1e-12)  # the dampers slip
