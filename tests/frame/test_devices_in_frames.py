"""Fluid viscous and friction dampers in frames, against independent references: a linear FVD frame against its
exact frequency-domain (FFT) solution assembled in the test; nonlinear FVDs against the continuous equations of
motion (scipy's Radau); a friction oscillator against its exact piecewise solution; the energy balance of a
yielding frame with P-Delta and every kind of device; devices on one story in parallel; a device's
magnification against the scaled device it is equivalent to (the scaling proved below); restarts against the
uninterrupted run; result files; the deprecated keyword ``walls=``."""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest
from reference import tapered_sine
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import vdw_frames as vdw
from vdw_frames.element.thermal import ISD110_LOSS_PEAK, ThermalProperties
from vdw_frames.frame.results import FrameState, SimulationResult
from vdw_frames.motion import default_record

MASSES = np.array([400.0, 380.0, 360.0, 300.0])
STIFFNESSES = [3.0e5, 2.6e5, 2.2e5, 1.7e5]
HEIGHTS = [3500.0] * 4


def four_story(devices, **options):
    return vdw.ShearBuilding(MASSES, STIFFNESSES, story_heights=HEIGHTS, devices=devices, **options)


# ---------------------------------------------------------------------------------------------- frequency domain
def story_assembly(per_story):
    """(..., n) story stiffnesses -> (..., n, n): story k between floors k-1 and k, written out."""
    n = per_story.shape[-1]
    matrix = np.zeros((*per_story.shape, n), dtype=per_story.dtype)
    for k in range(n):
        matrix[..., k, k] += per_story[..., k]
        if k > 0:
            matrix[..., k - 1, k - 1] += per_story[..., k]
            matrix[..., k - 1, k] -= per_story[..., k]
            matrix[..., k, k - 1] -= per_story[..., k]
    return matrix


def fvd_stiffness(damper, omega):
    """magnification^2 x K*(omega) of a linear FVD (N/mm), written out: i omega C, in series with K_b if any."""
    dashpot = 1j * omega * damper.C
    along = dashpot if damper.stiffness is None else damper.stiffness * dashpot / (damper.stiffness + dashpot)
    return damper.magnification**2 * along


def tustin_response(building, ground, dt, pad_factor=6):
    """Floor displacements (mm, steps x floors) of ``building`` (linear stories, linear FVDs only) under
    ``ground`` (mm/s^2, every dt s) by the FFT: U(f) = -(K + i w C + K_d(w) - w^2 M)^-1 M 1 A_g(f) at the
    warped frequency f_w = tan(pi f dt) / (pi dt), the continuous system's response under the bilinear
    transform.  Zero padded to ``pad_factor`` times the record (odd: no Nyquist bin, where f_w is infinite)."""
    size = pad_factor * ground.size + 1
    frequency = np.fft.rfftfreq(size, dt)
    omega = 2 * np.pi * np.tan(np.pi * frequency * dt) / (np.pi * dt)
    per_story = np.tile(np.asarray(building.stiffnesses, dtype=complex), (omega.size, 1))
    for story, damper in building.other_device_list:
        per_story[:, story - 1] += fvd_stiffness(damper, omega)
    dynamic = (story_assembly(per_story) - omega[:, None, None] ** 2 * np.diag(building.masses)
               + 1j * omega[:, None, None] * np.asarray(building.damping_matrix))
    transfer = np.linalg.solve(dynamic, np.broadcast_to(-np.asarray(building.masses, dtype=complex),
                                                        (omega.size, building.stories))[..., None])[..., 0]
    spectrum = np.fft.rfft(ground, size)
    return np.fft.irfft(transfer * spectrum[:, None], size, axis=0)[: ground.size]


@pytest.mark.parametrize("brace", [True, False], ids=["with-brace", "pure-dashpot"])
def test_a_linear_fvd_frame_is_the_tustin_transform_of_the_continuous_frame(brace):
    """Newmark's average acceleration (the frame) and the implicit trapezoid (the FVD's dashpot) are both the
    trapezoidal rule, so the discrete frame is the bilinear (Tustin) transform s = 2/dt (z - 1)/(z + 1) of the
    continuous one: under the sampled record its response equals the continuous frequency response evaluated at
    the warped frequency f_w = tan(pi f dt) / (pi dt), exactly (up to the wrap-around of the zero padding,
    here far below the tolerance).  The reference is assembled in the test (masses, story stiffnesses, the
    inherent damping matrix and each FVD's i omega C in series with K_b); asserted to 1e-10 of the peak, inside
    the issue's 1e-6 (measured: 1.8e-14 with braces, 1.6e-14 for pure dashpots).  The record starts at
    a_g = 0: a discrete system started at rest under a_g,0 != 0 is not the z-transform's, whose history is
    zero before its first sample."""
    stiffness = (lambda k: k) if brace else (lambda k: None)
    building = four_story({1: vdw.FluidViscousDamper(2500.0, 1.0, stiffness(1.5e5)),
                           2: [vdw.FluidViscousDamper(1500.0, 1.0, stiffness(8e4), magnification=0.8),
                               vdw.FluidViscousDamper(800.0, 1.0, stiffness(4e4))],
                           4: vdw.FluidViscousDamper(1200.0, 1.0, stiffness(1e5), magnification=1.3)})
    motion = default_record()
    assert motion.acceleration[0] == 0.0
    result = vdw.simulate(building, motion)
    expected = tustin_response(building, motion.acceleration, motion.dt)
    peak = np.abs(expected).max()
    assert peak > 10.0  # the frame moves (mm)
    np.testing.assert_allclose(result.displacement, expected, rtol=0, atol=1e-10 * peak)


def continuous_response(building, ground, duration):
    """Floor displacements (mm) of ``building`` (linear stories, FVDs with braces) under the ground acceleration
    ``ground(t)`` (mm/s^2), as functions of t: the equations of motion in first-order form, state (u, v, F)
    with every damper's force F obeying dF/dt = K_b (f dd/dt - sgn(F) (|F|/C)^(1/alpha)) (f its
    magnification, d its story's drift), solved by scipy's Radau to 1e-9 (1e-10 changes no digit of the
    errors below)."""
    n, masses = building.stories, np.asarray(building.masses)
    stiffness = story_assembly(np.asarray(building.stiffnesses))
    damping = np.asarray(building.damping_matrix)
    dampers = building.other_device_list
    column = np.array([story - 1 for story, _ in dampers])
    f = np.array([damper.magnification for _, damper in dampers])
    C = np.array([damper.C for _, damper in dampers])
    alpha = np.array([damper.alpha for _, damper in dampers])
    brace = np.array([damper.stiffness for _, damper in dampers])

    def rate(t, state):
        u, v, force = state[:n], state[n:2 * n], state[2 * n:]
        story_force = np.bincount(column, f * force, minlength=n)
        story_rate = v - np.concatenate([[0.0], v[:-1]])
        dashpot = np.sign(force) * (np.abs(force) / C) ** (1.0 / alpha)
        floor_force = story_force - np.concatenate([story_force[1:], [0.0]])  # story k pushes floors k and k-1
        acceleration = (-masses * ground(t) - damping @ v - stiffness @ u - floor_force) / masses
        return np.concatenate([v, acceleration, brace * (f * story_rate[column] - dashpot)])

    solution = solve_ivp(rate, (0.0, duration), np.zeros(2 * n + len(dampers)), method="Radau", rtol=1e-9,
                         atol=1e-8, dense_output=True)
    return lambda t: solution.sol(t)[:n].T


@pytest.mark.slow
def test_a_frame_with_nonlinear_fvds_converges_at_second_order_to_its_equations_of_motion():
    """A linear four-story frame with nonlinear FVDs (alpha 0.3 and 0.5, braces, magnifications 1 and 0.8)
    under a tapered 1.5 Hz sine against its continuous equations of motion (:func:`continuous_response`): the
    displacements within 5e-3 of the peak at dt = 0.005 s (measured 2.9e-3; 1.2e-2 at 0.01 s, 7.3e-4 at
    0.0025 s), the error falling by 4 (3.5 to 4.5; measured 4.00) when the step halves: Newmark and the
    dampers' trapezoid together, second order.  Newton takes at most 4 corrections a step on average (measured
    2.96: the dampers' tangent is consistent)."""
    building = four_story({1: vdw.FluidViscousDamper(6000.0, 0.3, 2e5),
                           2: vdw.FluidViscousDamper(3000.0, 0.5, 1.2e5, magnification=0.8),
                           3: vdw.FluidViscousDamper(2500.0, 0.5, 1e5)})
    duration = 6.0

    def ground(t):
        return tapered_sine(t, 1.5, 3000.0, 1.0, duration)

    reference = continuous_response(building, ground, duration)
    errors = []
    for dt in (0.01, 0.005):
        t = np.arange(round(duration / dt) + 1) * dt
        result = vdw.simulate(building, vdw.GroundMotion(ground(t), dt))
        expected = reference(t)
        errors.append(np.abs(result.displacement - expected).max() / np.abs(expected).max())
        assert result.newton_iterations <= 4 * t.size
    assert errors[1] < 5e-3
    assert 3.5 < errors[0] / errors[1] < 4.5


def friction_oscillator(m, K, slip, k, X0, times):
    """x(t) (mm) of the undamped oscillator m x'' + K x + F = 0 with an elastic-perfectly-plastic friction
    force F (stiffness k, slip force ``slip``), released at rest from x = X0 having slipped to F = +slip: exact,
    phase by phase -- sticking (stiffness K + k, about the centre where the two springs balance) until
    |F| reaches the slip force, slipping (stiffness K, about -F/K) until the velocity reverses -- each phase a
    cosine, its end found by brentq to 1e-15; elastic for ever once a stick ends in a reversal."""
    x0, v0, force, sticking, start = X0, 0.0, slip, True, 0.0
    out, done = np.empty_like(times), 0
    while True:
        w = math.sqrt((K + k) / m if sticking else K / m)
        centre = (k * x0 - force) / (K + k) if sticking else -force / K

        def x(t, x0=x0, v0=v0, w=w, centre=centre):
            return centre + (x0 - centre) * np.cos(w * t) + v0 / w * np.sin(w * t)

        def v(t, x0=x0, v0=v0, w=w, centre=centre):
            return -(x0 - centre) * w * math.sin(w * t) + v0 * math.cos(w * t)

        reversal = (math.atan2(v0 / w, x0 - centre) % math.pi) / w or math.pi / w
        end, slipping = math.inf, None
        if sticking:
            direction = 1.0 if x(reversal) > x0 else -1.0
            target = x0 + (direction * slip - force) / k  # where the force reaches +-slip
            if (target - x0) * (target - x(reversal)) < 0.0:  # before the reversal: it slips
                end = brentq(lambda t, target=target: x(t) - target, 0.0, reversal, xtol=1e-15, rtol=1e-15)
                slipping = direction * slip
        else:
            end = reversal
        upto = int(np.searchsorted(times, start + end, side="right"))
        out[done:upto] = x(times[done:upto] - start)
        done = upto
        if done >= times.size or end == math.inf:
            return out
        x0, v0, start = float(x(end)), v(end) if sticking else 0.0, start + end
        sticking, force = slipping is None, force if slipping is None else slipping


def test_a_friction_damper_in_an_oscillator_follows_the_exact_piecewise_solution():
    """An undamped one-story frame with a friction damper, released from 100 mm having slipped (a FrameState:
    the restart replays the drift into the damper), against :func:`friction_oscillator`: eleven slip phases,
    each after a stick, then elastic vibration from 3.2 s on, over 4 s.  Within 5e-5 of the release
    displacement at dt = 0.5 ms (measured 1.5e-5), the error falling by 4 (3.5 to 4.5; measured 4.1) when
    the step halves: the return mapping is exact and the slip and stick events cost no order."""
    m, K, slip, k, X0 = 100.0, 1e4, 5e4, 5e4, 100.0
    building = vdw.ShearBuilding([m], [K], damping_ratio=0.0, devices={1: vdw.FrictionDamper(slip, k)})
    errors = []
    for dt in (0.0005, 0.00025):
        state = FrameState(step=1, dt=dt, displacement=[X0], velocity=[0.0],
                           acceleration=[-(K * X0 + slip) / m], drift=[[0.0], [X0]])
        result = vdw.simulate(building, vdw.GroundMotion(np.zeros(round(4.0 / dt) + 1), dt), initial_state=state)
        expected = friction_oscillator(m, K, slip, k, X0, result.time - dt)
        errors.append(np.abs(result.displacement[:, 0] - expected).max() / X0)
        assert result.device_force[0, 0] == slip and np.abs(result.device_force).max() == slip
    assert expected.min() < -85.0 and np.abs(expected[-2000:]).max() < 5.0  # it slipped back, then stuck
    assert errors[0] < 5e-5
    assert 3.5 < errors[0] / errors[1] < 4.5


# ---------------------------------------------------------------------------------------------- every kind at once
HEAT = ThermalProperties(ISD110_LOSS_PEAK, 1.8, 21.2)
WALL = dataclasses.replace(vdw.FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5, area=3e5, thickness=8.0), thermal=HEAT)
LINEAR_FVD = vdw.FluidViscousDamper(1500.0, 1.0)
NONLINEAR_FVD = vdw.FluidViscousDamper(4000.0, 0.5, stiffness=1.2e5, magnification=0.85)
FRICTION = vdw.FrictionDamper(2.5e5, 8e4)


def five_story_every_kind(mixed=True):
    """A five-story yielding frame with P-Delta: a heating FDMK wall (story 1), a linear dashpot (2), a nonlinear
    FVD with a brace (3), a friction damper (4); ``mixed``: a nonlinear FVD and a friction damper together on
    story 5, else only the FVD there."""
    masses = np.array([400.0, 400.0, 380.0, 360.0, 300.0])
    weight = np.cumsum((masses * vdw.G)[::-1])[::-1]
    top = [vdw.FluidViscousDamper(2500.0, 0.5, stiffness=9e4)]
    if mixed:
        top.append(vdw.FrictionDamper(1.5e5, 6e4, magnification=1.2))
    return vdw.ShearBuilding(masses, [3.0e5, 2.7e5, 2.4e5, 2.0e5, 1.6e5], story_heights=[3500.0] * 5,
                             gravity_loads=weight, hysteresis=[vdw.Bilinear(0.12 * w, 0.03) for w in weight],
                             devices={1: WALL, 2: LINEAR_FVD, 3: NONLINEAR_FVD, 4: FRICTION, 5: top})


def quiet_simulate(*args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # the wall's strain-range warning: tested elsewhere
        return vdw.simulate(*args, **kwargs)


@pytest.fixture(scope="module")
def every_kind():
    return quiet_simulate(five_story_every_kind(), default_record().scaled(1.5))


def test_every_kind_of_device_in_a_yielding_frame_closes_the_energy_balance(every_kind):
    """input = kinetic + frame strain + hysteretic + inherent damping + device work + P-Delta: asserted to 1e-10
    of the input, inside the issue's 1e-4 (measured 8.6e-15: average acceleration with trapezoidal work
    balances to the iteration tolerance); with the devices' work split into the wall's heat and stored energy
    (its own states, a diffusive representation) and the other devices' heat and stored energy, to 1e-3
    (measured 1.5e-4: the wall's split is exact only to its representation, as for walls alone)."""
    result, energy = every_kind, every_kind.energy
    scale = energy.input.max()
    assert np.abs(result.residual_drift).max() > 1.0  # the stories yielded (mm)
    assert energy.hysteretic[-1] > 0.05 * scale and energy.p_delta.min() < 0.0
    assert np.abs(energy.balance_error).max() <= 1e-10 * scale
    assert np.abs(energy.heat_balance_error).max() <= 1e-3 * scale
    # each kind did some of the work
    assert energy.wall_heat[-1] > 0.02 * scale and energy.device_heat[-1] > 0.1 * scale


def test_each_device_heat_and_stored_energy_are_the_work_of_its_force_on_its_deformation(every_kind):
    """From the histories alone: int F du (trapezoids, along the device) = heat + stored, device by device
    (1e-9 of its work; measured <= 5e-15), and the deformation is magnification x the story drift (1e-15)."""
    result = every_kind
    devices = result.building.other_device_list
    assert [type(device).__name__ for _, device in devices] == [
        "FluidViscousDamper", "FluidViscousDamper", "FrictionDamper", "FluidViscousDamper", "FrictionDamper"]
    force, deformation = result.device_force, result.device_deformation
    work = np.concatenate([np.zeros((1, force.shape[1])),
                           np.cumsum(0.5 * (force[1:] + force[:-1]) * np.diff(deformation, axis=0), axis=0)])
    scale = np.abs(work).max(axis=0)
    assert np.all(scale > 0.0)
    np.testing.assert_array_less(np.abs(result.device_heat + result.device_stored - work).max(axis=0),
                                 1e-9 * scale)
    for column, (story, device) in enumerate(devices):
        np.testing.assert_allclose(deformation[:, column], device.magnification * result.drift[:, story - 1],
                                   rtol=1e-15, atol=0)
    # the summed histories of the energy account are the devices'
    np.testing.assert_allclose(result.energy.device_heat, result.device_heat.sum(axis=1), rtol=1e-15)
    np.testing.assert_allclose(result.energy.device_stored, result.device_stored.sum(axis=1), rtol=1e-15)
    # stored: F^2 / (2 K_b) in a brace, F^2 / (2 k) in a friction damper
    for column, (_, device) in enumerate(devices):
        if device.stiffness is not None:
            np.testing.assert_allclose(result.device_stored[:, column],
                                       force[:, column] ** 2 / (2 * device.stiffness), rtol=1e-12, atol=0)


def test_devices_on_one_story_act_in_parallel(every_kind):
    """The force the devices put into each story is the sum of magnification x device force over its devices
    (1e-12; measured 2e-16); story 5's FVD and friction damper together."""
    result = every_kind
    expected = np.zeros_like(result.story_wall_force)
    for column, (story, device) in enumerate(result.building.other_device_list):
        expected[:, story - 1] += device.magnification * result.device_force[:, column]
    scale = np.abs(result.story_wall_force).max()
    np.testing.assert_allclose(result.story_wall_force[:, 1:], expected[:, 1:], rtol=0, atol=1e-12 * scale)
    assert np.abs(expected[:, 4]).max() > 0.0


def test_every_kind_restarts_from_a_state_as_the_uninterrupted_run(every_kind):
    """simulate(..., initial_state=result.state_at(k)) replays the drift history into the devices (their forces,
    dashpot motion, slip and heat) and goes on as the run that was never stopped (1e-12; measured: identical
    but for the story device force, 4e-16)."""
    result = every_kind
    motion = default_record().scaled(1.5)
    for k in (700, 1400):
        restarted = quiet_simulate(result.building, motion, initial_state=result.state_at(k))
        for name in ("displacement", "story_wall_force", "device_force", "device_deformation", "device_velocity",
                     "device_heat", "device_stored"):
            whole, rest = getattr(result, name)[k:], getattr(restarted, name)
            np.testing.assert_allclose(rest, whole, rtol=0, atol=1e-12 * np.abs(whole).max(), err_msg=name)
        np.testing.assert_allclose(restarted.energy.device_heat, result.energy.device_heat[k:],
                                   rtol=0, atol=1e-12 * result.energy.device_heat[-1])
        assert np.abs(restarted.energy.balance_error).max() <= 1e-10 * result.energy.input.max()


def test_every_kind_round_trips_through_a_result_file(every_kind, tmp_path):
    """SimulationResult.save / load: the devices (every kind, their parameters and stories) and every device
    history and energy come back as they were (bit for bit)."""
    path = tmp_path / "every_kind.npz"
    every_kind.save(path)
    loaded = SimulationResult.load(path)
    assert loaded.building.devices == every_kind.building.devices
    for name in ("displacement", "story_wall_force", "device_force", "device_deformation", "device_velocity",
                 "device_heat", "device_stored"):
        np.testing.assert_array_equal(getattr(loaded, name), getattr(every_kind, name), err_msg=name)
    for name in ("input", "wall_work", "wall_heat", "device_heat", "device_stored"):
        np.testing.assert_array_equal(getattr(loaded.energy, name), getattr(every_kind.energy, name), err_msg=name)


# ---------------------------------------------------------------------------------------------- geometry
@pytest.mark.parametrize("alpha", [0.5, 1.0])
@pytest.mark.parametrize("magnification", [0.6, 2.5])
def test_a_magnified_fvd_is_the_fvd_of_C_f_to_the_1_plus_alpha_and_K_b_f_squared(alpha, magnification):
    """An FVD of magnification f is, in the story, the FVD of coefficient C f^(1 + alpha), brace K_b f^2 and
    magnification 1.  Proof: the device moves u = f d (d the drift) and adds f F to the story shear, with
    F = K_b (u - u_d) and du_d/dt = sgn(F) (|F|/C)^(1/alpha).  In the story's variables F' = f F and
    u_d' = u_d / f: F' = f^2 K_b (d - u_d') and du_d'/dt = sgn(F') (|F'| / (f C))^(1/alpha) / f
    = sgn(F') (|F'| / (C f^(1 + alpha)))^(1/alpha) -- the damper (C f^(1 + alpha), K_b f^2) across d.  The
    implicit trapezoid is the same rule in either set of variables, so the two are stepped alike up to
    rounding, through 2500 steps of a yielding frame: measured <= 1.3e-13 of the peak in displacements and
    heat, <= 7.4e-13 in forces and 1.2e-12 in the stored energy (quadratic in the force); asserted to 1e-12,
    2e-12 and 4e-12.  Likewise a friction damper of magnification f is (F_s f, k f^2)."""
    C, stiffness, slip, friction_stiffness = 3000.0, 1.2e5, 2e5, 7e4
    f = magnification
    magnified = {2: [vdw.FluidViscousDamper(C, alpha, stiffness, magnification=f),
                     vdw.FrictionDamper(slip, friction_stiffness, magnification=f)]}
    scaled = {2: [vdw.FluidViscousDamper(C * f ** (1 + alpha), alpha, stiffness * f**2),
                  vdw.FrictionDamper(slip * f, friction_stiffness * f**2)]}
    masses = np.array([400.0, 380.0, 360.0, 300.0])
    weight = np.cumsum((masses * vdw.G)[::-1])[::-1]
    options = dict(gravity_loads=weight, hysteresis=[vdw.Bilinear(0.1 * w, 0.03) for w in weight])
    motion = default_record().scaled(1.5)
    one, other = (vdw.simulate(four_story(devices, **options), motion) for devices in (magnified, scaled))

    def close(actual, desired, tolerance, name):
        np.testing.assert_allclose(actual, desired, rtol=0, atol=tolerance * np.abs(desired).max(), err_msg=name)

    close(one.displacement, other.displacement, 1e-12, "displacement")
    close(one.device_heat, other.device_heat, 1e-12, "device_heat")
    close(one.story_wall_force, other.story_wall_force, 2e-12, "story_wall_force")
    # along the device: f x the scaled one's deformation, its force / f
    close(one.device_deformation, f * other.device_deformation, 2e-12, "device_deformation")
    close(f * one.device_force, other.device_force, 2e-12, "device_force")
    close(one.device_stored, other.device_stored, 4e-12, "device_stored")  # quadratic in the force
    assert np.abs(one.residual_drift).max() > 1.0  # stories yielded: the frame is not linear


# ---------------------------------------------------------------------------------------------- the keyword
def test_walls_is_a_deprecated_name_of_devices():
    wall = vdw.FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5, area=3e5, thickness=8.0)
    with pytest.warns(DeprecationWarning, match=r"walls=.*deprecated.*devices="):
        old = vdw.ShearBuilding(MASSES, STIFFNESSES, walls={1: wall, 3: [wall, wall]})
    new = vdw.ShearBuilding(MASSES, STIFFNESSES, devices={1: wall, 3: [wall, wall]})
    assert old.devices == new.devices == {1: (wall,), 3: (wall, wall)}
    motion = vdw.GroundMotion(default_record().acceleration[:600], 0.01)
    np.testing.assert_array_equal(vdw.simulate(old, motion).displacement, vdw.simulate(new, motion).displacement)
    with pytest.warns(DeprecationWarning), pytest.raises(ValueError, match=r"devices= only.*not both"):
        vdw.ShearBuilding(MASSES, STIFFNESSES, devices={2: FRICTION}, walls={1: wall})


def test_dataclasses_replace_with_walls_keeps_working_and_keeps_the_other_devices():
    """``dataclasses.replace(building, walls=...)``, the way to swap walls before 0.3 (and still in
    :mod:`vdw_frames.frame.strain_compatible`'s docstring), replaces the walls with a DeprecationWarning: the
    building's own devices come back as ``devices=`` and are not a second keyword; its other devices stay."""
    wall = vdw.FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5, area=3e5, thickness=8.0)
    other = wall.resized(2e5)
    building = vdw.ShearBuilding(MASSES, STIFFNESSES, devices={1: [wall, LINEAR_FVD], 2: wall})
    with pytest.warns(DeprecationWarning, match="walls="):
        replaced = dataclasses.replace(building, walls={2: other, 3: [other, other]})
    assert replaced.devices == {1: (LINEAR_FVD,), 2: (other,), 3: (other, other)}
    assert replaced.devices == building.with_walls({2: other, 3: [other, other]}).devices
    with pytest.warns(DeprecationWarning):
        bare = vdw.ShearBuilding(MASSES, STIFFNESSES)
        assert dataclasses.replace(bare, walls={4: wall}).devices == {4: (wall,)}
