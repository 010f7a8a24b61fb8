"""Fluid viscous and friction dampers driven alone (vdw_frames.element.devices.device_response), against closed
forms written in the tests: the energy per cycle of a nonlinear dashpot, lambda C omega^alpha u0^(1 + alpha) with
lambda integrated numerically here; a friction damper's loop area 4 F_s (u0 - F_s/k) and its force history
against an elastic-perfectly-plastic return mapping written here; the bad inputs every device refuses."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

import vdw_frames as vdw
from vdw_frames.element.devices import device_response
from vdw_frames.element.viscous import energy_factor

ALPHAS = (0.3, 0.5, 0.75, 1.0)


def cycle_integral(alpha):
    """lambda(alpha) = int_0^(2 pi) |cos theta|^(1 + alpha) d theta (-), by quadrature: the work of
    F = C |v|^alpha sgn(v) over one cycle of u0 sin(omega t) is C (u0 omega)^alpha u0 times it."""
    quarter, _ = quad(lambda theta: math.cos(theta) ** (1.0 + alpha), 0.0, math.pi / 2, epsabs=0.0, epsrel=1e-13)
    return 4.0 * quarter


def one_minus_cosine(amplitude, frequency, cycles, steps_per_cycle):
    """u0 (1 - cos omega t) (mm) from rest (zero deformation and velocity, so Newmark's velocity starts right)
    and its step (s); a steady sine of amplitude u0 about u0 once started."""
    dt = 1.0 / (frequency * steps_per_cycle)
    t = np.arange(cycles * steps_per_cycle + 1) * dt
    return amplitude * (1.0 - np.cos(2 * np.pi * frequency * t)), dt


@pytest.mark.parametrize("alpha", ALPHAS)
def test_the_energy_factor_is_the_cycle_integral_of_the_dashpot_work(alpha):
    assert energy_factor(alpha) == pytest.approx(cycle_integral(alpha), rel=1e-12)
    assert cycle_integral(1.0) == pytest.approx(math.pi, rel=1e-13)


# A nonlinear dashpot alone is refused (test_a_fluid_viscous_damper_refuses_bad_input_naming_the_value): alpha < 1
# is driven through a brace only.
@pytest.mark.parametrize(("alpha", "brace"), [(alpha, True) for alpha in ALPHAS] + [(1.0, False)],
                         ids=[f"alpha={alpha}-brace" for alpha in ALPHAS] + ["alpha=1-dashpot"])
def test_a_nonlinear_dashpot_dissipates_lambda_C_omega_alpha_u0_1_plus_alpha_a_cycle(alpha, brace):
    """The last of four cycles of a steady sine: heat per cycle against lambda C omega^alpha u0^(1 + alpha)
    (Soong and Dargush 1997, Sec. 6.2): asserted to 1e-4, inside the issue's 0.5 % (measured: 8e-7 for a linear
    dashpot, 1e-6 to 4.5e-6 with a brace 1e4 times stiffer than the dashpot's peak force per mm: the brace's
    deformation, 1e-4 of the amplitude and a quarter-cycle out of phase, changes the dashpot's amplitude to
    second order only)."""
    C, u0, frequency, steps = 250.0, 20.0, 1.5, 2000
    omega = 2 * np.pi * frequency
    peak_force = C * (omega * u0) ** alpha
    stiffness = 1e4 * peak_force / u0 if brace else None
    damper = vdw.FluidViscousDamper(C, alpha, stiffness=stiffness)
    deformation, dt = one_minus_cosine(u0, frequency, 4, steps)
    response = device_response(damper, deformation, dt)
    per_cycle = response["heat"][-1] - response["heat"][-1 - steps]
    expected = cycle_integral(alpha) * C * omega**alpha * u0 ** (1.0 + alpha)
    assert per_cycle == pytest.approx(expected, rel=1e-4)
    # The frame's trapezoidal work of the force on the deformation over the cycle is the heat (the brace's
    # stored energy returns to its value a cycle before).
    force = response["force"][-1 - steps:]
    work = np.sum(0.5 * (force[1:] + force[:-1]) * np.diff(deformation[-1 - steps:]))
    stored = response["stored"][-1] - response["stored"][-1 - steps]
    assert work == pytest.approx(per_cycle + stored, rel=1e-10)


@pytest.mark.parametrize("alpha", [0.3, 0.5, 1.0])
def test_a_damper_with_a_brace_dissipates_what_its_dashpot_force_does_on_the_dashpot(alpha):
    """Heat + stored energy F^2 / (2 K_b) equals the trapezoidal work of the force on the device's deformation,
    step by step, with a soft brace (K_b twice the peak force per amplitude: it deforms by up to half the
    amplitude)."""
    C, u0, frequency = 250.0, 20.0, 1.5
    omega = 2 * np.pi * frequency
    damper = vdw.FluidViscousDamper(C, alpha, stiffness=2.0 * C * (omega * u0) ** alpha / u0)
    deformation, dt = one_minus_cosine(u0, frequency, 3, 500)
    response = device_response(damper, deformation, dt)
    force = response["force"]
    work = np.concatenate([[0.0], np.cumsum(0.5 * (force[1:] + force[:-1]) * np.diff(deformation))])
    np.testing.assert_allclose(response["heat"] + response["stored"], work, rtol=0, atol=1e-10 * work.max())
    np.testing.assert_allclose(response["stored"], force**2 / (2 * damper.stiffness), rtol=1e-13, atol=0)
    assert np.all(np.diff(response["heat"]) >= -1e-9 * work.max())  # a dashpot never gives heat back


@pytest.mark.parametrize("alpha", [0.3, 0.5, 1.0])
def test_a_damper_with_a_soft_brace_converges_at_second_order_to_the_maxwell_equation(alpha):
    """The series form dF/dt = K_b (du/dt - sgn(F) (|F|/C)^(1/alpha)) under u0 (1 - cos omega t), solved by
    scipy's Radau to 1e-12 (the reference), with a brace as stiff as the dashpot's peak force per amplitude
    (the brace takes a large share): the implicit trapezoid's force is within 1e-4 of the peak at 400 steps a
    cycle (measured 1.2e-5 to 1.6e-5) and its error falls by 4 (measured 3.995 to 4.000) when the step halves:
    second order."""
    C, u0, frequency = 250.0, 20.0, 1.5
    omega = 2 * np.pi * frequency
    stiffness = C * (omega * u0) ** alpha / u0

    def rate(t, force):
        dashpot = np.sign(force[0]) * (abs(force[0]) / C) ** (1.0 / alpha)
        return [stiffness * (u0 * omega * np.sin(omega * t) - dashpot)]

    reference = solve_ivp(rate, (0.0, 2.0 / frequency), [0.0], method="Radau", rtol=1e-12, atol=1e-9,
                          dense_output=True)
    errors = []
    for steps in (200, 400):
        deformation, dt = one_minus_cosine(u0, frequency, 2, steps)
        force = device_response(vdw.FluidViscousDamper(C, alpha, stiffness), deformation, dt)["force"]
        expected = reference.sol(np.arange(deformation.size) * dt)[0]
        errors.append(np.abs(force - expected).max() / np.abs(expected).max())
    assert errors[1] < 1e-4
    assert 3.5 < errors[0] / errors[1] < 4.5


def trapezoidal_maxwell_by_bisection(deformation, dt, C, alpha, stiffness):
    """The forces (N) of the implicit trapezoid on the Maxwell form (the rule viscous_trial states), written out:
    each step's F + K dt/2 g(F) = F_n + K (u - u_n) - K dt/2 g(F_n), g(F) = sgn(F) (|F|/C)^(1/alpha), solved by
    bisection on [0, |right side|] in logarithms (no overflow) to the last bit."""
    def dashpot_term(force):  # K dt/2 g(F) for F > 0, capped where it overflows
        return math.exp(min(700.0, math.log(stiffness * dt / 2) + math.log(force / C) / alpha)) if force > 0 else 0.0

    force, dashpot_velocity = np.zeros(deformation.size), 0.0
    for n in range(1, deformation.size):
        target = force[n - 1] + stiffness * (deformation[n] - deformation[n - 1] - dt / 2 * dashpot_velocity)
        low, high = 0.0, abs(target)
        while True:
            middle = 0.5 * (low + high)
            if middle in (low, high):
                break
            low, high = (low, middle) if middle + dashpot_term(middle) > abs(target) else (middle, high)
        force[n] = math.copysign(middle, target)
        dashpot_velocity = math.copysign((middle / C) ** (1.0 / alpha), target)
    return force


@pytest.mark.parametrize(("C", "alpha", "stiffness", "dt", "deformation"), [
    (1e5, 0.05, 1e6, 0.01, [0.0, 1e-3, 50.0, 48.0, -20.0]),  # a jump from a small force of the same sign
    (2e4, 0.1, 1e6, 0.01, [0.0, 1e-6, 1e3, 1e3, -1e3, 5.0]),
    (1.0, 0.02, 1e6, 0.01, [0.0, 1e-9, 1e4]),  # g(|target|) overflows: NaN before the fix
], ids=["alpha=0.05", "alpha=0.1", "alpha=0.02-overflow"])
def test_a_small_alpha_damper_solves_its_step_equation_after_a_sudden_jump(C, alpha, stiffness, dt, deformation):
    """Small exponents (0 < alpha < 0.3, accepted) under a step that multiplies the force: the Newton iteration
    warm-started from the last (small) force overshoots to ~|target| and then fell by only (1 - alpha) an
    iteration (0.05: the force 311607 N after 100 iterations against the root 158464 N), or overflowed g into NaN;
    against the bisection above, 1e-12."""
    history = np.array(deformation)
    response = device_response(vdw.FluidViscousDamper(C, alpha, stiffness), history, dt)
    expected = trapezoidal_maxwell_by_bisection(history, dt, C, alpha, stiffness)
    assert np.isfinite(response["force"]).all() and np.isfinite(response["heat"]).all()
    np.testing.assert_allclose(response["force"], expected, rtol=1e-12, atol=0)


def elastic_perfectly_plastic(deformation, slip_force, stiffness):
    """The force (N) of an elastic-perfectly-plastic spring along a deformation history (mm) from rest: the
    return mapping written out (elastic predictor, projection onto |F| <= F_s)."""
    force = np.zeros_like(deformation)
    for n in range(1, deformation.size):
        trial = force[n - 1] + stiffness * (deformation[n] - deformation[n - 1])
        force[n] = min(max(trial, -slip_force), slip_force)
    return force


@pytest.mark.parametrize("magnification", [1.0, 0.7])
def test_a_friction_damper_follows_the_elastic_perfectly_plastic_return_mapping(magnification):
    """An irregular history (a decaying sine with a drift and noise): the device's force is the EPP spring's at
    magnification x the drift, and the story's is magnification x that (1e-12)."""
    slip_force, stiffness = 4.0e5, 5.0e4
    rng = np.random.default_rng(30)
    t = np.arange(3001) * 0.005
    drift = 25.0 * np.exp(-0.1 * t) * np.sin(2 * np.pi * 1.3 * t) + 3.0 * t + np.cumsum(rng.normal(0, 0.3, t.size))
    drift -= drift[0]
    damper = vdw.FrictionDamper(slip_force, stiffness, magnification=magnification)
    response = device_response(damper, drift, 0.005)
    expected = magnification * elastic_perfectly_plastic(magnification * drift, slip_force, stiffness)
    assert np.abs(expected).max() == pytest.approx(magnification * slip_force)  # it slips
    np.testing.assert_allclose(response["force"], expected, rtol=0, atol=1e-12 * slip_force)


@pytest.mark.parametrize("u0_over_uy", [1.5, 4.0, 20.0])
def test_a_friction_damper_loop_has_the_area_4_Fs_u0_minus_uy(u0_over_uy):
    """The loop of a steady sine: 4 F_s (u0 - F_s/k) (the rigid-plastic rectangle less its elastic parts), by
    the trapezoidal work of the force on the deformation and by the device's heat, within 1e-5 (measured
    <= 6e-7; the trapezoid is exact on the loop's straight pieces, off only on the two steps where it starts
    to slip; the heat is off by half that step's force change times its slip)."""
    slip_force, stiffness, frequency, steps = 4.0e5, 5.0e4, 1.0, 4000
    u0 = u0_over_uy * slip_force / stiffness
    deformation, dt = one_minus_cosine(u0, frequency, 3, steps)
    response = device_response(vdw.FrictionDamper(slip_force, stiffness), deformation, dt)
    force, cycle = response["force"], slice(-1 - steps, None)
    area = np.sum(0.5 * (force[cycle][1:] + force[cycle][:-1]) * np.diff(deformation[cycle]))
    expected = 4.0 * slip_force * (u0 - slip_force / stiffness)
    assert area == pytest.approx(expected, rel=1e-5)
    assert response["heat"][-1] - response["heat"][-1 - steps] == pytest.approx(expected, rel=1e-5)


@pytest.mark.parametrize("u0", [1.5, 1e160, 1e300, 1.7e308])
def test_a_friction_damper_complex_stiffness_is_the_closed_form_at_any_amplitude(u0):
    """K_eff = F_s / u0, K'' = 4 F_s (u0 - u_y) / (pi u0^2) (FEMA 356 Sec. 9.3.3, eq. 9-36), written here in
    higher precision (fractions of the exact binary values), within 1e-14; finite where u0^2 overflows (it
    raised OverflowError beyond u0 ~ 1.3e154; K'' -> 4 F_s / (pi u0) there)."""
    from fractions import Fraction

    slip_force, stiffness = 1.0e3, 2.0e3  # u_y = 0.5 mm
    value = complex(vdw.FrictionDamper(slip_force, stiffness).complex_stiffness(1.0, u0))
    exact_u0, exact_uy = Fraction(u0), Fraction(slip_force) / Fraction(stiffness)
    loss = 4 * Fraction(slip_force) * (exact_u0 - exact_uy) / exact_u0**2
    assert math.isfinite(value.real) and math.isfinite(value.imag)
    assert value.real == pytest.approx(float(Fraction(slip_force) / exact_u0), rel=1e-14)
    assert value.imag == pytest.approx(float(loss) / math.pi, rel=1e-14)
    if u0 >= 1e160:
        assert value.imag == pytest.approx(4.0 * slip_force / (math.pi * u0), rel=1e-14)


def test_a_building_with_friction_dampers_at_a_huge_drift_amplitude_has_the_bare_frames_modes():
    """K* ~ 1e-297 N/mm at a drift amplitude of 1e300 mm: the modes are the bare frame's, within 1e-12 (it
    raised OverflowError from F_s / u0^2)."""
    friction = vdw.FrictionDamper(1.0e3, 2.0e5)
    building = vdw.ShearBuilding([10.0, 10.0], [2.0e4, 2.0e4], devices={1: [friction], 2: [friction]})
    modes = vdw.modal_analysis(building, drift_amplitude=1e300)
    bare = vdw.modal_analysis(building.without_devices())
    np.testing.assert_allclose(modes.periods, bare.periods, rtol=1e-12)
    np.testing.assert_allclose(modes.damping_ratios, bare.damping_ratios, rtol=1e-12)


def test_a_devices_energy_per_cycle_beyond_the_float_range_is_refused_naming_the_amplitude():
    """The loop areas 4 F_s (u0 - u_y) and lambda C omega^alpha u0^(1 + alpha) overflow for a huge amplitude:
    a ValueError naming it (the FVD's raised OverflowError; the friction damper's returned inf)."""
    with pytest.raises(ValueError, match=r"amplitude = 1\.7e\+308 mm"):
        vdw.FrictionDamper(1.0e3, 2.0e5).energy_per_cycle(1.7e308)
    with pytest.raises(ValueError, match=r"amplitude = 1e\+300 mm and frequency = 1\.0 Hz"):
        vdw.FluidViscousDamper(100.0, 0.5, 1.0e4).energy_per_cycle(1e300, 1.0)
    with pytest.raises(ValueError, match=r"drift_amplitude = 1\.7e\+308 mm.*magnification 2\.0"):
        vdw.FrictionDamper(1.0e3, 2.0e5, magnification=2.0).story_stiffness(1.0, 1.7e308)


# ---------------------------------------------------------------------------------------------- bad input
@pytest.mark.parametrize(("arguments", "named"), [
    (dict(C=100.0, alpha=0.0, stiffness=1e4), "alpha.*0.0"),
    (dict(C=100.0, alpha=-0.5, stiffness=1e4), r"alpha.*-0\.5"),
    (dict(C=100.0, alpha=1.2, stiffness=1e4), r"alpha.*1\.2"),
    (dict(C=100.0, alpha=math.nan, stiffness=1e4), "alpha.*nan"),
    (dict(C=100.0, alpha=0.5), r"alpha = 0\.5.*stiffness"),
    (dict(C=0.0, alpha=1.0), "C.*0.0"),
    (dict(C=-5.0, alpha=0.5, stiffness=1e4), r"C.*-5\.0"),
    (dict(C=math.inf, alpha=1.0), "C.*inf"),
    (dict(C=math.nan, alpha=1.0), "C.*nan"),
    (dict(C=100.0, alpha=0.5, stiffness=0.0), "stiffness.*0.0"),
    (dict(C=100.0, alpha=0.5, stiffness=-1e4), "stiffness.*-10000.0"),
    (dict(C=100.0, alpha=1.0, stiffness=math.inf), "stiffness.*inf"),
    (dict(C=100.0, alpha=1.0, magnification=0.0), "magnification.*0.0"),
    (dict(C=100.0, alpha=1.0, magnification=-0.7), r"magnification.*-0\.7"),
    (dict(C=100.0, alpha=1.0, magnification=math.nan), "magnification.*nan"),
])
def test_a_fluid_viscous_damper_refuses_bad_input_naming_the_value(arguments, named):
    with pytest.raises(ValueError, match=named):
        vdw.FluidViscousDamper(**arguments)


@pytest.mark.parametrize(("arguments", "named"), [
    (dict(slip_force=0.0, stiffness=1e4), "slip_force.*0.0"),
    (dict(slip_force=-3.0, stiffness=1e4), r"slip_force.*-3\.0"),
    (dict(slip_force=math.inf, stiffness=1e4), "slip_force.*inf"),
    (dict(slip_force=math.nan, stiffness=1e4), "slip_force.*nan"),
    (dict(slip_force=1e5, stiffness=0.0), "stiffness.*0.0"),
    (dict(slip_force=1e5, stiffness=-2.0), r"stiffness.*-2\.0"),
    (dict(slip_force=1e5, stiffness=math.inf), "stiffness.*inf"),
    (dict(slip_force=1e5, stiffness=1e4, magnification=0.0), "magnification.*0.0"),
    (dict(slip_force=1e5, stiffness=1e4, magnification=-1.0), r"magnification.*-1\.0"),
])
def test_a_friction_damper_refuses_bad_input_naming_the_value(arguments, named):
    with pytest.raises(ValueError, match=named):
        vdw.FrictionDamper(**arguments)


def test_a_device_of_an_unknown_type_in_a_building_is_refused_naming_its_type():
    class Sponge:
        magnification = 1.0

    with pytest.raises(ValueError, match=r"devices\[2\].*FluidViscousDamper.*FrictionDamper.*got Sponge"):
        vdw.ShearBuilding([300.0, 300.0], [2e5, 2e5], devices={2: [vdw.FrictionDamper(1e5, 1e4), Sponge()]})


# ---------------------------------------------------------------------------------------------- the float range
@pytest.mark.parametrize("make", [
    lambda m: vdw.FluidViscousDamper(100.0, 1.0, magnification=m),
    lambda m: vdw.FrictionDamper(1.0e3, 2.0e5, magnification=m),
    lambda m: vdw.FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5, magnification=m),
])
@pytest.mark.parametrize("magnification", [1e200, 1e-200])
def test_a_magnification_whose_square_leaves_the_float_range_is_refused_naming_it(make, magnification):
    """The story sees magnification^2 x the device's stiffness: at 1e200 story_stiffness raised OverflowError (a
    traceback), at 1e-200 the square was 0 (a device the story does not see).  Both refused at construction."""
    with pytest.raises(ValueError, match=re.escape(f"magnification = {magnification:g}: its square")):
        make(magnification)
    device = make(1e150)  # square 1e300: accepted
    assert device.magnification == 1e150


def test_a_fvd_whose_loss_stiffness_overflows_is_its_brace_not_nan():
    """K* = K_b i q / (1 + i q), q = omega C_eq / K_b: as q -> inf, K* -> K_b (the oil locks, the brace carries the
    motion).  Where omega C_eq overflowed, K* was NaN; where omega = 0, 0 even if C (omega u0)^alpha overflows.
    Reference: the closed form K_b (q^2 + i q) / (1 + q^2) written here, at q = 3 and q = 1e250 (its limit K_b)."""
    brace = 1.0e5
    linear = vdw.FluidViscousDamper(brace * 3.0 / (2.0 * math.pi), 1.0, stiffness=brace)  # q = 3 at 1 Hz
    np.testing.assert_allclose(linear.complex_stiffness(1.0), brace * (9.0 + 3.0j) / 10.0, rtol=1e-14)
    huge = vdw.FluidViscousDamper(1.0e300, 1.0, stiffness=brace)
    np.testing.assert_allclose(huge.complex_stiffness([0.0, 1.0e-55, 1.0e10]),
                               [0.0, brace * (1.0 + 1j / (2.0 * math.pi * 1.0e-55 * 1.0e300 / brace)), brace],
                               rtol=1e-14)
    nonlinear = vdw.FluidViscousDamper(1.0e300, 0.3, stiffness=brace)
    np.testing.assert_allclose(nonlinear.complex_stiffness([0.0, 1.0e10], 1e-10), [0.0, brace], rtol=1e-14)
    with pytest.raises(ValueError, match=r"K\*\(f\) overflowed \(inf\) at f = 1e\+306 Hz"):
        vdw.FluidViscousDamper(100.0, 1.0).complex_stiffness([1.0, 1.0e306])
    with pytest.raises(ValueError, match=r"equivalent coefficient overflowed \(inf\) at frequency = 1e-300 Hz"):
        nonlinear.equivalent_coefficient(1.0e-300, 1.0e-300)
    with pytest.raises(ValueError, match=r"magnification\^2 \(1e\+150\^2\) exceeds"):
        vdw.FluidViscousDamper(1.0e300, 1.0, stiffness=1.0e300, magnification=1e150).story_stiffness(1.0)


@pytest.mark.parametrize(("alpha", "brace", "q", "error", "tolerance"), [
    (0.5, 1000.0, 0.125, 0.0, 0.015),
    (0.3, 1000.0, 0.066, 0.0, 0.015),
    (0.3, 100.0, 0.658, 0.114, 0.005),
    (0.3, 30.0, 2.193, -0.172, 0.005),
])
def test_a_braced_nonlinear_fvds_linearisation_against_the_steady_state_of_the_maxwell_equation(
        alpha, brace, q, error, tolerance):
    """The equivalent linear K* of a nonlinear FVD with a brace takes the dashpot's motion as a sine: the
    accuracy that vdw_frames.element.viscous and docs/theory.rst state.  Reference: F = K_b (u - u_d),
    u_d' = sgn(F) (|F| / C)^(1/alpha) under u = u0 sin(omega t), solved by scipy to a steady state; its
    energy per cycle (pi u0 x the first harmonic's quadrature part) against pi K'' u0^2."""
    coefficient, u0, frequency = 100.0, 5.0, 1.0
    omega = 2.0 * math.pi * frequency
    damper = vdw.FluidViscousDamper(coefficient, alpha, stiffness=brace)
    assert cycle_integral(alpha) * coefficient * omega**alpha * u0 ** (alpha - 1.0) / math.pi / brace == \
        pytest.approx(q, abs=5e-4)

    def rate(t, state):
        force = brace * (u0 * math.sin(omega * t) - state[0])
        return [math.copysign(abs(force / coefficient) ** (1.0 / alpha), force)]

    solution = solve_ivp(rate, (0.0, 12.0), [0.0], rtol=1e-10, atol=1e-12, dense_output=True, max_step=1e-3)
    t = np.linspace(11.0, 12.0, 20001)[:-1]  # the 12th cycle: steady
    force = brace * (u0 * np.sin(omega * t) - solution.sol(t)[0])
    energy = math.pi * u0 * 2.0 * np.mean(force * np.cos(omega * t))
    linearised = math.pi * complex(damper.complex_stiffness(frequency, u0)).imag * u0**2
    assert linearised / energy - 1.0 == pytest.approx(error, abs=tolerance)


@pytest.mark.parametrize("device", [vdw.FrictionDamper(1.0e3, 2.0e5), vdw.FluidViscousDamper(100.0, 0.5, 1.0e4)])
def test_complex_stiffness_without_an_amplitude_names_its_own_argument(device):
    """complex_stiffness takes the device's own amplitude ``amplitude``: without it the error said "give
    drift_amplitude", an argument of story_stiffness that complex_stiffness does not take."""
    with pytest.raises(ValueError, match=r"K\* depends on its amplitude: give amplitude \(mm, the device's own"):
        device.complex_stiffness(1.0)
    with pytest.raises(ValueError, match=r"give drift_amplitude \(mm\), the story drift amplitude"):
        device.story_stiffness(1.0)


def test_a_trial_or_a_drive_that_overflows_is_refused_and_the_state_kept():
    """DeviceState.trial and device_response returned inf (a pure dashpot at a 1e300 mm step; a damper whose
    energy F^2 / (2 K_b) overflows): a ValueError naming the deformation instead, the committed state untouched.
    Reference: a pure dashpot from rest, F = C v with Newmark's v = 2 u / dt."""
    from vdw_frames.element.devices import DeviceState

    state = DeviceState(vdw.FluidViscousDamper(1.0e5, 1.0), 0.01)
    with pytest.raises(ValueError, match=r"trial at deformation 1e\+300 mm overflowed \(inf\)"):
        state.trial(1e300)
    with pytest.raises(ValueError, match="commit needs a trial first"):
        state.commit()
    force, tangent = state.trial(1.0)
    assert force == pytest.approx(1.0e5 * 2.0 * 1.0 / 0.01, rel=1e-15)
    assert tangent == pytest.approx(2.0 * 1.0e5 / 0.01, rel=1e-15)
    history = 100.0 * np.sin(np.linspace(0.0, 20.0, 2001))
    with pytest.raises(ValueError, match=r"overflowed \(inf\) at step 1, deformation 0\.99998"):
        device_response(vdw.FluidViscousDamper(1.0e300, 0.5, stiffness=1.0e300), history, 0.01)
