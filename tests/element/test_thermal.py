"""Walls that heat: time-temperature superposition, the heat of the diffusive representation, and the
coupled mechanical-thermal problem, each against an independent reference."""

import dataclasses
import math

import numpy as np
import pytest
from builders import TABLE4
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from vdw_frames import FDMKDamper, SupportedDamper, WallLimits
from vdw_frames.element.bank import WallBank
from vdw_frames.element.thermal import (
    ISD110_LOSS_PEAK,
    WLF,
    Arrhenius,
    LogLinear,
    ThermalProperties,
    diffusive_nodes,
    diffusive_weights,
    log10_shift,
    node_coefficients,
)

LAWS = [WLF(C1=8.86, C2=101.6, reference=21.2, valid=(-20.0, 80.0)),
        Arrhenius(activation_energy=1.0e5, reference=21.2, valid=(-20.0, 80.0)),
        ISD110_LOSS_PEAK]
ENORMOUS = 1e12  # MPa/K: a heat capacity that keeps the temperature where it starts


def thermal_wall(temperature=21.2, heat_capacity=1.8, cooling_time=math.inf, law=ISD110_LOSS_PEAK, **parameters):
    values = dict(TABLE4, area=1e5, thickness=10.0) | parameters
    return FDMKDamper(**values, thermal=ThermalProperties(law, heat_capacity, temperature, cooling_time))


def drive(wall, displacement, dt):
    """(force N, temperature degC, heat N*mm) histories of ``wall`` under ``displacement`` (mm) from rest."""
    state = wall.new_state(dt, memory="exact")
    force, temperature, heat = (np.zeros(displacement.size) for _ in range(3))
    temperature[0] = state.temperature
    for n in range(1, displacement.size):
        force[n] = state.trial(displacement[n])[0]
        state.commit()
        temperature[n], heat[n] = state.temperature, state.heat
    return force, temperature, heat


# ------------------------------------------------------------------------------- superposition
@pytest.mark.parametrize("law", LAWS, ids=["WLF", "Arrhenius", "LogLinear"])
def test_time_temperature_superposition_is_exact_for_the_fdmk_model(law):
    wall = FDMKDamper(**TABLE4)
    frequencies = np.geomspace(0.01, 100.0, 61)
    for temperature in (-10.0, 0.0, 10.0, 21.2, 35.0, 60.0):
        if not law.valid[0] <= temperature <= law.valid[1]:
            continue  # beyond the range the law is held at its end (test_beyond_its_range_...)
        shift = 10.0 ** float(law.log10_shift(temperature))
        at_temperature = wall.at_temperature(temperature, law).complex_modulus(frequencies)
        shifted_frequency = wall.complex_modulus(shift * frequencies)
        np.testing.assert_allclose(at_temperature, shifted_frequency, rtol=1e-12)


def test_shift_laws_follow_their_formulas():
    wlf, arrhenius, log_linear = LAWS
    assert float(wlf.log10_shift(41.2)) == pytest.approx(-8.86 * 20.0 / (101.6 + 20.0), rel=1e-14)
    kelvin, reference = 41.2 + 273.15, 21.2 + 273.15
    assert float(arrhenius.log10_shift(41.2)) == pytest.approx(1e5 / 8.314462618 * (1 / kelvin - 1 / reference)
                                                               / math.log(10.0), rel=1e-12)
    # Ver & Beranek Table 14.1: the ISD-110 loss peak moves one decade per (65.6 - 26.7) / 2 K.
    assert float(log_linear.log10_shift(21.2 + 19.45)) == pytest.approx(-1.0, rel=1e-12)


@pytest.mark.parametrize("law", LAWS, ids=["WLF", "Arrhenius", "LogLinear"])
def test_the_kernel_row_of_every_law_is_the_law(law):
    # The compiled update evaluates every law as -slope d / (1 + curvature d) (thermal.log10_shift of the law's
    # kernel_row).  The reference is each law's printed formula, over its valid range and beyond; Arrhenius's
    # 1/T - 1/T_ref written (T_ref - T) / (T T_ref), the difference taken in degC, which keeps its digits near T_ref.
    _, slope, curvature, reference = law.kernel_row()
    temperatures = np.linspace(law.valid[0] - 10.0, law.valid[1] + 10.0, 401)
    rows = np.array([log10_shift(slope, curvature, reference, float(t)) for t in temperatures])
    if isinstance(law, Arrhenius):
        kelvin, reference_kelvin = temperatures + 273.15, law.reference + 273.15
        expected = (law.activation_energy / 8.314462618 * (law.reference - temperatures) / (kelvin * reference_kelvin)
                    / math.log(10.0))
    elif isinstance(law, WLF):
        expected = -law.C1 * (temperatures - law.reference) / (law.C2 + temperatures - law.reference)
    else:
        expected = -(temperatures - law.reference) / law.degrees_per_decade
    np.testing.assert_allclose(rows, expected, rtol=1e-13, atol=1e-16)


def test_a_frequency_shift_changes_the_storage_and_loss_stiffness_by_different_factors():
    wall = thermal_wall()
    factors = wall.property_factors([0.0, 21.2, 40.0], 0.6)
    np.testing.assert_allclose(factors.storage[1], 1.0, rtol=1e-12)
    for k, temperature in enumerate(factors.temperatures):
        shifted, nominal = (wall.at_temperature(t).complex_stiffness(0.6) for t in (temperature, 21.2))
        assert factors.storage[k] == pytest.approx(shifted.real / nominal.real, rel=1e-12)
        assert factors.loss[k] == pytest.approx(shifted.imag / nominal.imag, rel=1e-12)
    assert abs(factors.loss_factor_ratio[0] - 1.0) > 0.1  # the loss factor is not preserved
    supported = SupportedDamper(wall, 5e4)
    assert supported.property_factors([40.0], 0.6).storage[0] == pytest.approx(
        supported.at_temperature(40.0).storage_stiffness(0.6) / supported.at_temperature(21.2).storage_stiffness(0.6),
        rel=1e-12)


def test_a_wall_at_rest_away_from_the_reference_answers_at_its_own_temperature():
    wall = thermal_wall(temperature=5.0)
    np.testing.assert_allclose(wall.complex_stiffness([0.3, 1.0, 3.0]),
                               wall.at_temperature(5.0).complex_stiffness([0.3, 1.0, 3.0]), rtol=1e-14)


# ------------------------------------------------------------------------------- diffusive representation
@pytest.mark.parametrize("dt", [0.001, 0.002, 0.004, 0.005, 0.01, 0.02])
def test_the_diffusive_representation_reproduces_s_to_the_r(dt):
    nodes = diffusive_nodes(dt)
    omega = np.geomspace(2 * np.pi * 0.01, np.pi / dt, 2000)
    s = 1j * omega
    for r in (0.05, 0.2, 0.35, 0.5, 0.65, 0.8, 0.95, 0.99, 1.0):
        weights, dashpot, spring = diffusive_weights(r, nodes)
        approximation = (weights * s[:, None] / (s[:, None] + nodes)).sum(axis=1) + dashpot * s + spring
        assert np.abs(approximation / s**r - 1.0).max() <= 3.5e-3


def test_node_coefficients_integrate_a_relaxing_mode_exactly():
    # For an input rising linearly by dx over a step, phi' = -xi phi + dx/dt: its end value and its dissipation
    # int xi phi^2 dt (work less the change of phi^2 / 2) against solve_ivp, from slow (z = 1e-4, the series)
    # to fast (z = 30) modes.
    dt, dx, phi0 = 0.01, 0.7, -0.3
    nodes = np.array([1e-2, 1.0, 4.0, 30.0, 3000.0])
    coefficients = node_coefficients(nodes, dt)
    for xi, (e, gain, work) in zip(nodes, coefficients, strict=True):
        def rate(t, y, xi=xi):
            return [-xi * y[0] + dx / dt, xi * y[0] ** 2]

        exact = solve_ivp(rate, (0.0, dt), [phi0, 0.0], rtol=1e-12, atol=1e-15, method="DOP853").y[:, -1]
        end = e * phi0 + gain * dx
        assert end == pytest.approx(exact[0], rel=1e-9, abs=1e-14)
        dissipated = gain * phi0 * dx + work * dx**2 - 0.5 * (end**2 - phi0**2)
        assert dissipated == pytest.approx(exact[1], rel=1e-8, abs=1e-14)


# ------------------------------------------------------------------------------- heat
@pytest.mark.parametrize("r", [0.3, 0.6, 1.0])
def test_the_heat_of_a_steady_cycle_equals_the_loop_area(r):
    wall = thermal_wall(heat_capacity=ENORMOUS, r=r)
    frequency, amplitude, per_cycle, cycles = 1.0, 20.0, 400, 8
    dt = 1.0 / (frequency * per_cycle)
    time = np.arange(cycles * per_cycle + 1) * dt
    _, temperature, heat = drive(wall, amplitude * np.sin(2 * np.pi * frequency * time), dt)
    assert np.ptp(temperature) < 1e-6  # isothermal
    last_cycle = heat[-1] - heat[-1 - per_cycle]
    loop_area = np.pi * float(wall.loss_stiffness(frequency)) * amplitude**2
    assert last_cycle == pytest.approx(loop_area, rel=5e-3)


@pytest.mark.parametrize("law", LAWS, ids=["WLF", "Arrhenius", "LogLinear"])
def test_a_heating_wall_steps_with_the_viscosities_of_its_committed_temperature(law):
    # The compiled update takes a_T^r from an anchor's exp and a series in the small change since (kernel
    # _shift_factor); the reference is the law evaluated afresh, 10^(r log10 a_T), at the committed
    # temperature (measured within 9e-16).  Dropping the x^4 term shows (4e-14 at x = 1e-3).
    r, dt = 0.6, 0.005
    wall = thermal_wall(law=law, r=r)  # heated by 29-36 K, within every law's valid range (kept)
    bank = WallBank((wall,), dt, 1200, "damped", "fast")
    start = bank.arrays.constants[0, 2:4].copy()  # eta1, eta2 at 21.2 degC, the laws' reference
    anchors, last = 0, math.nan
    for d in 15.0 * np.sin(2 * np.pi * 1.5 * np.arange(1, 1201) * dt):
        bank.commit([d])
        temperature = float(bank.state("temperature")[0])
        factor = 10.0 ** (r * law.log10_shift(temperature))
        np.testing.assert_allclose(bank.arrays.constants[0, 2:4], start * factor, rtol=1e-14)
        anchor = float(bank.state("shift_anchor")[0])
        anchors += anchor != last
        last = anchor
    assert 20.0 < temperature - 21.2 < law.valid[1] - 21.2
    assert anchors > 20  # many anchors, and many steps on the series between them


NARROW = [WLF(C1=8.86, C2=101.6, reference=21.2, valid=(18.0, 40.0)),
          LogLinear(degrees_per_decade=19.45, reference=21.2, valid=(18.0, 40.0))]


@pytest.mark.parametrize("law", NARROW, ids=["WLF", "LogLinear"])
@pytest.mark.parametrize("cooling_time", [math.inf, 3.0], ids=["adiabatic", "cooling"])
@pytest.mark.parametrize("maxwell", [True, False], ids=["Maxwell", "Kelvin only"])
def test_a_heating_wall_takes_the_same_steps_on_the_update_s_straight_path_as_on_its_general_one(law, cooling_time,
                                                                                               maxwell):
    # A wall whose temperature is all that is followed goes straight through the update (base.heating_only); the same
    # wall with a limit it never reaches goes the general way, with every check.  The steps are the same
    # inlined functions in the same order, so the two walls agree to the last bit (as long as LLVM compiles
    # the two inlined copies alike, which it does).  The wall heats beyond its law's range (clamped there).
    parameters = {} if maxwell else {"G2": 0.0}
    plain = thermal_wall(law=law, r=0.6, heat_capacity=1.0, cooling_time=cooling_time, **parameters)
    limited = dataclasses.replace(plain, limits=WallLimits(strain=1e6))
    bank = WallBank((plain, limited), 0.005, 1500, "damped", "fast")
    assert list(bank.state("heating_only")) == [1.0, 0.0]
    for d in 20.0 * np.sin(2 * np.pi * 1.5 * np.arange(1, 1501) * 0.005):
        bank.commit([d, d])
    for column in ("temperature", "heat", "stored", "parameter_loss", "outside"):
        values = bank.state(column)
        assert values[0] == values[1], column
    assert bank.state("parameter_loss")[0] != 0.0 and bank.state("outside")[0] > 0
    np.testing.assert_array_equal(bank.arrays.constants[0], bank.arrays.constants[1])


@pytest.mark.parametrize("law", NARROW, ids=["WLF", "LogLinear"])
@pytest.mark.parametrize("limits", [None, WallLimits(strain=1e6)], ids=["straight", "general"])
def test_a_wall_outside_its_law_s_range_is_noted_at_its_first_step_there_and_steps_at_the_range_s_end(law, limits):
    # References: the committed temperature history itself (the first step above the range's end) and the law
    # evaluated afresh at that end, 10^(r log10 a_T(T_high)).
    r, dt = 0.6, 0.005
    wall = dataclasses.replace(thermal_wall(law=law, r=r), limits=limits)
    bank = WallBank((wall,), dt, 1500, "damped", "fast")
    start = bank.arrays.constants[0, 2:4].copy()
    temperatures = []
    for d in 20.0 * np.sin(2 * np.pi * 1.5 * np.arange(1, 1501) * dt):
        bank.commit([d])
        temperatures.append(float(bank.state("temperature")[0]))
        if temperatures[-1] <= law.valid[1]:
            assert bank.state("outside")[0] == -1.0
    first = int(np.argmax(np.array(temperatures) > law.valid[1]))
    assert first > 0 and temperatures[-1] > law.valid[1] + 5.0
    assert bank.state("outside")[0] == first + 1  # the step (time / dt) of the first committed state outside
    np.testing.assert_allclose(bank.arrays.constants[0, 2:4], start * 10.0 ** (r * law.log10_shift(law.valid[1])),
                               rtol=1e-14)
    # A wall at rest below the range is outside from its first step on, at the range's lower end.
    cold = WallBank((dataclasses.replace(thermal_wall(law=law, r=r, temperature=10.0), limits=limits),), dt, 10,
                    "damped", "fast")
    cold.commit([0.0])
    assert cold.state("outside")[0] == 1.0
    np.testing.assert_allclose(cold.arrays.constants[0, 2:4], start * 10.0 ** (r * law.log10_shift(law.valid[0])),
                               rtol=1e-14)


def test_an_isothermal_thermal_wall_steps_exactly_as_the_plain_wall():
    time = np.arange(3001) * 0.005
    displacement = 15.0 * np.sin(2 * np.pi * 0.8 * time) * np.minimum(time, 1.0)
    plain = FDMKDamper(**TABLE4, area=1e5, thickness=10.0)
    heated = thermal_wall(heat_capacity=1e300)
    np.testing.assert_allclose(heated.force(displacement, 0.005), plain.force(displacement, 0.005),
                               rtol=1e-12, atol=1e-12 * np.abs(plain.force(displacement, 0.005)).max())


def test_a_wall_held_at_another_temperature_follows_the_wall_at_that_temperature():
    time = np.arange(4001) * 0.0025
    displacement = 15.0 * np.sin(2 * np.pi * 1.2 * time)
    held = thermal_wall(temperature=5.0, heat_capacity=ENORMOUS)
    reference = held.at_temperature(5.0).force(displacement, 0.0025)
    np.testing.assert_allclose(held.force(displacement, 0.0025), reference, atol=1e-9 * np.abs(reference).max())


# Random drives heat adiabatic walls past their shift law's range, on purpose: WallState says so once a run.
@pytest.mark.filterwarnings("ignore:WallState. wall temperature:UserWarning")
@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**16), r=st.floats(0.05, 1.0), harmonic=st.booleans())
def test_an_adiabatic_wall_never_cools(seed, r, harmonic):
    rng = np.random.default_rng(seed)
    dt, steps = 0.01, 600
    if harmonic:
        displacement = rng.uniform(1, 30) * np.sin(2 * np.pi * rng.uniform(0.1, 5.0) * np.arange(steps) * dt)
    else:
        displacement = np.cumsum(rng.normal(0.0, 2.0, steps))
    _, temperature, heat = drive(thermal_wall(heat_capacity=1e-3, r=r), displacement, dt)
    assert np.all(np.diff(temperature) >= -1e-12 * np.abs(temperature).max())
    assert np.all(np.diff(heat) >= 0.0)


# It starts hot, above its shift law's range, on purpose (WallState says so once).
@pytest.mark.filterwarnings("ignore:WallState. wall temperature:UserWarning")
def test_with_cooling_the_temperature_relaxes_to_ambient_at_its_time_constant():
    dt, tau = 0.01, 3.0
    loading = 20.0 * np.sin(2 * np.pi * 2.0 * np.arange(501) * dt)
    displacement = np.concatenate([loading, np.full(1500, loading[-1])])  # then held still
    wall = thermal_wall(temperature=10.0, heat_capacity=1e-2, cooling_time=tau)
    _, temperature, _ = drive(wall, displacement, dt)
    rest = np.arange(600, displacement.size)  # after the springpots' own relaxation has died out
    excess = temperature[rest] - 10.0
    assert excess[0] > 1.0
    expected = excess[0] * np.exp(-(rest - rest[0]) * dt / tau)
    np.testing.assert_allclose(excess, expected, rtol=2e-3)


# ------------------------------------------------------------------------------- the coupled problem
def coupled_reference(strain, time, *, G1, G2, eta1, eta2, capacity, law, temperature0):
    """r = 1 Kelvin + Maxwell with eta(T) = eta_ref a_T(T), heated by its dissipation eta1 eps'^2 + sigma2^2 /
    eta2 (per unit volume): solve_ivp on (sigma2, T) for a strain given as a dense function."""
    def shift(T):
        return 10.0 ** float(law.log10_shift(T))

    def rate(t, y):
        sigma2, T = y
        a = shift(T)
        eps_dot = strain(t, 1)
        return [G2 * eps_dot - G2 * sigma2 / (eta2 * a), (eta1 * a * eps_dot**2 + sigma2**2 / (eta2 * a)) / capacity]

    solution = solve_ivp(rate, (time[0], time[-1]), [0.0, temperature0], t_eval=time, rtol=1e-10, atol=1e-12,
                         method="LSODA", max_step=0.01)
    sigma2, T = solution.y
    eps = strain(time, 0)
    stress = G1 * eps + eta1 * np.array([shift(t) for t in T]) * strain(time, 1) + sigma2
    return stress, T


def test_the_coupled_problem_of_a_classical_wall_matches_solve_ivp_at_first_order_or_better():
    parameters = dict(G1=0.4, G2=2.0, eta1=0.15, eta2=0.5)
    amplitude, frequency, area, thickness, capacity = 3.0, 1.0, 1e5, 10.0, 0.6

    def strain(t, derivative):  # smooth start: eps = A sin^2-ramped sine
        ramp, ramp_dot = np.minimum(t, 1.0), np.where(t < 1.0, 1.0, 0.0)
        w = 2 * np.pi * frequency
        if derivative == 0:
            return amplitude * ramp * np.sin(w * t)
        return amplitude * (ramp_dot * np.sin(w * t) + ramp * w * np.cos(w * t))

    wall = FDMKDamper(**parameters, r=1.0, area=area, thickness=thickness,
                      thermal=ThermalProperties(ISD110_LOSS_PEAK, capacity, 21.2))
    errors = []
    for dt in (0.004, 0.002, 0.001):
        time = np.arange(round(6.0 / dt) + 1) * dt
        force, temperature, _ = drive(wall, strain(time, 0) * thickness, dt)
        stress, reference_temperature = coupled_reference(strain, time, **parameters, capacity=capacity,
                                                          law=ISD110_LOSS_PEAK, temperature0=21.2)
        reference_force = stress * area
        errors.append((np.abs(force[1:] - reference_force[1:]).max() / np.ptp(reference_force),
                       np.abs(temperature - reference_temperature).max() / np.ptp(reference_temperature)))
    errors = np.array(errors)
    assert np.ptp(reference_temperature) > 20.0  # the wall does heat (and soften) a lot
    assert errors[-1].max() <= 5e-3
    assert np.all(errors[:-1] / errors[1:] >= 1.8)  # first order or better under halving


def dense_springpot(r, low, high, per_decade):
    """(xi_k rad/s, c_k s^-r, tail dashpot s^(1-r), tail spring s^-r): D^r x = sum_k c_k phi_k + dashpot x' +
    spring x, phi_k' = -xi_k phi_k + x', from rest; written here from the diffusive representation
    D^r x = int mu(xi) phi(xi) d xi, mu = sin(r pi) / pi xi^(r - 1), independently of the package's nodes.

    The trapezoidal rule in u = ln xi (mu d xi = sin(r pi) / pi e^(r u) du), ``per_decade`` nodes a decade from
    ``low`` to ``high``, the end nodes at half weight.  The rest of the infinite grid, in its asymptotic form, is
    summed exactly: above ``high`` (xi >> omega) a mode is a dashpot (s / (s + xi) ~ s / xi), below ``low``
    (xi << omega, xi t << 1) a spring (s / (s + xi) ~ 1); with the end node's other half,
    sum_{j >= 0}' h e^(-a (u_end + j h)) = e^(-a u_end) (h / 2) coth(a h / 2), a = 1 - r above and r below.
    The trapezoidal rule on the whole line is spectrally accurate (the integrand is analytic in a strip of
    half-width pi / 2 about the real u axis: error ~ exp(-pi^2 / h), 3.6e-8 at 4 nodes a decade); the tails'
    asymptotic forms are off by (omega / high)^(2 - r) and (low / omega)^(1 + r) of s^r."""
    count = round(math.log10(high / low) * per_decade) + 1
    xi = np.geomspace(low, high, count)
    h = math.log(xi[1] / xi[0])
    density = math.sin(r * math.pi) / math.pi
    weights = density * h * xi**r
    weights[[0, -1]] *= 0.5
    dashpot = density * xi[-1] ** (r - 1.0) * 0.5 * h / math.tanh(0.5 * (1.0 - r) * h)
    spring = density * xi[0] ** r * 0.5 * h / math.tanh(0.5 * r * h)
    return xi, weights, dashpot, spring


def fractional_coupled_reference(strain, time, r, *, G1, G2, eta1, eta2, capacity, law, temperature0, springpot):
    """0 < r < 1 Kelvin + Maxwell with eta(T) = eta_ref a_T(T)^r, heated adiabatically by the dissipation of both
    springpots (per unit volume): solve_ivp (BDF) on the diffusive states of a dense representation
    ``springpot`` = (xi, c, dashpot, spring) of D^r, for a strain given as a dense function.

    States: phi_k (the Kelvin springpot, input eps), psi_k (the Maxwell springpot, input eps_v), eps_v, T.
    The Maxwell branch, sigma2 = G2 (eps - eps_v) = eta2(T) D^r eps_v with eta2(T(t)) outside the derivative:
        G2 (eps - eps_v) = eta2(T) [sum_k c_k psi_k + dashpot eps_v' + spring eps_v],
    with the tail dashpot > 0 itself an ODE for eps_v, solved for eps_v'.  eta2(T) multiplies D^r eps_v, so no
    d eta2 / dt enters (differentiating the relation instead would add eta2' [..] and need eps_v'').
    Heat: P = eta1(T) [sum_k c_k xi_k phi_k^2 + dashpot eps'^2] + eta2(T) [sum_k c_k xi_k psi_k^2 + dashpot eps_v'^2]
    (a tail mode above the last node has phi = x' / xi: c xi phi^2 = c x'^2 / xi, summed: dashpot x'^2; those
    below store, never dissipate); dT/dt = P / (rho c).  Returns (stress MPa, T degC) at ``time``."""
    xi, c, dashpot, spring = springpot
    n = xi.size
    loss = c * xi

    def factor(T):
        return 10.0 ** (r * float(law.log10_shift(T)))

    def factor_slope(T):  # (for the Jacobian only: it steers Newton's iterations, not the solution)
        return (factor(T + 1e-4) - factor(T - 1e-4)) / 2e-4

    def unpack(t, y):
        psi, v, T = y[n:2 * n], y[2 * n], y[2 * n + 1]
        a = factor(T)
        eps, eps_dot = strain(t, 0), strain(t, 1)
        v_dot = (G2 * (eps - v) / (eta2 * a) - c @ psi - spring * v) / dashpot
        return a, eps, eps_dot, v_dot

    def rate(t, y):
        phi, psi = y[:n], y[n:2 * n]
        a, _, eps_dot, v_dot = unpack(t, y)
        power = a * (eta1 * (loss @ phi**2 + dashpot * eps_dot**2) + eta2 * (loss @ psi**2 + dashpot * v_dot**2))
        return np.concatenate([eps_dot - xi * phi, v_dot - xi * psi, [v_dot, power / capacity]])

    def jacobian(t, y):
        phi, psi, v, T = y[:n], y[n:2 * n], y[2 * n], y[2 * n + 1]
        a, eps, eps_dot, v_dot = unpack(t, y)
        slope = factor_slope(T)
        by_psi, by_v = -c / dashpot, -(G2 / (eta2 * a) + spring) / dashpot  # d v_dot / d (psi, v, T)
        by_T = -G2 * (eps - v) / (eta2 * a**2 * dashpot) * slope
        J = np.zeros((2 * n + 2, 2 * n + 2))
        J[np.arange(n), np.arange(n)] = -xi
        J[n:2 * n + 1, n:2 * n] = by_psi
        J[np.arange(n, 2 * n), np.arange(n, 2 * n)] -= xi
        J[n:2 * n + 1, 2 * n] = by_v
        J[n:2 * n + 1, 2 * n + 1] = by_T
        maxwell = 2.0 * a * eta2 * dashpot * v_dot / capacity
        J[-1, :n] = 2.0 * a * eta1 * loss * phi / capacity
        J[-1, n:2 * n] = 2.0 * a * eta2 * loss * psi / capacity + maxwell * by_psi
        J[-1, 2 * n] = maxwell * by_v
        power = eta1 * (loss @ phi**2 + dashpot * eps_dot**2) + eta2 * (loss @ psi**2 + dashpot * v_dot**2)
        J[-1, -1] = slope * power / capacity + maxwell * by_T
        return J

    start = np.zeros(2 * n + 2)
    start[-1] = temperature0
    tolerance = np.full(2 * n + 2, 1e-12)
    tolerance[-1] = 1e-9
    solution = solve_ivp(rate, (time[0], time[-1]), start, t_eval=time, method="BDF", jac=jacobian, rtol=1e-9,
                         atol=tolerance)
    assert solution.success, solution.message
    phi, v, T = solution.y[:n], solution.y[2 * n], solution.y[2 * n + 1]
    eps, eps_dot = strain(time, 0), strain(time, 1)
    rate_of_strain = c @ phi + dashpot * eps_dot + spring * eps  # D^r eps
    stress = G1 * eps + eta1 * np.array([factor(t) for t in T]) * rate_of_strain + G2 * (eps - v)
    return stress, T


@pytest.mark.parametrize("r", [0.6, 0.822])
def test_the_coupled_problem_of_a_fractional_wall_matches_a_dense_diffusive_reference(r):
    # The reference: 4 nodes a decade from 1e-6 to 1e7 rad/s (53 a springpot), against s^r over 0.01-1000 rad/s
    # (the input: a 1 Hz carrier, its spectrum falling like omega^-3 from the kinks of eps'' at t = 0 and 1 s;
    # 1e-6 t < 3e-6 over the 3 s): measured 5e-7 (r = 0.6) and 2.9e-6 (r = 0.822); converged in itself to
    # 2.4e-8 of the ranges (6 nodes a decade from 1e-7 to 1e8 rad/s, rtol 1e-10, Radau).
    parameters = dict(G1=0.5, G2=3.0, eta1=0.3, eta2=2.0)
    amplitude, frequency, area, thickness, capacity, duration = 3.0, 1.0, 1e5, 10.0, 1.5, 3.0
    springpot = dense_springpot(r, 1e-6, 1e7, 4)
    xi, c, dashpot, spring = springpot
    s = 1j * np.geomspace(1e-2, 1e3, 2001)
    approximation = (c * s[:, None] / (s[:, None] + xi)).sum(axis=1) + dashpot * s + spring
    assert np.abs(approximation / s**r - 1.0).max() <= 1e-5

    def strain(t, derivative):  # smooth start: eps = A sin, ramped over the first second
        ramp, ramp_dot = np.minimum(t, 1.0), np.where(t < 1.0, 1.0, 0.0)
        w = 2 * np.pi * frequency
        if derivative == 0:
            return amplitude * ramp * np.sin(w * t)
        return amplitude * (ramp_dot * np.sin(w * t) + ramp * w * np.cos(w * t))

    wall = FDMKDamper(**parameters, r=r, area=area, thickness=thickness,
                      thermal=ThermalProperties(ISD110_LOSS_PEAK, capacity, 21.2))
    steps = (0.004, 0.002, 0.001)
    fine = np.arange(round(duration / steps[-1]) + 1) * steps[-1]
    stress, reference_temperature = fractional_coupled_reference(strain, fine, r, **parameters, capacity=capacity,
                                                                 law=ISD110_LOSS_PEAK, temperature0=21.2,
                                                                 springpot=springpot)
    reference_force = stress * area
    errors = []
    for dt in steps:
        every = round(dt / steps[-1])
        time = fine[::every]
        force, temperature, _ = drive(wall, strain(time, 0) * thickness, dt)
        errors.append((np.abs(force - reference_force[::every]).max() / np.ptp(reference_force),
                       np.abs(temperature - reference_temperature[::every]).max() / np.ptp(reference_temperature)))
    errors = np.array(errors)
    # Measured (force, temperature) at dt = 0.004, 0.002, 0.001 s, over a rise of 34.3 K (r = 0.6) and 36.4 K
    # (r = 0.822): r = 0.6 (2.7e-3, 1.0e-3), (1.5e-3, 7.3e-4), (7.6e-4, 1.0e-3); r = 0.822 (5.7e-3, 1.5e-3),
    # (3.0e-3, 9.3e-4), (1.4e-3, 3.6e-4).  The force falls at first order (the coupling's one-step lag), by
    # 1.77 and 2.05 (r = 0.6), 1.90 and 2.14 (r = 0.822).  The temperature does not keep falling: below ~1e-3 of
    # its range it meets the package's own heat quadrature (1.5 nodes a decade: a ripple of up to 3.5e-3 in s^r,
    # its nodes moving with dt), which no step size removes.  With that quadrature's nodes in place of the dense
    # ones for the heat alone (a diagnostic, not run here), the reference gives first order in both, 2.0-2.3 a
    # halving (r = 0.6: force 2.6e-3, 1.3e-3, 6.4e-4; temperature 3.8e-4, 1.8e-4, 8.5e-5).  That floor also moves
    # the force by ~2e-4, hence the first ratio's 1.77: asserted are 1.6 a halving and 3.3 over both.
    assert np.ptp(reference_temperature) > 20.0 and reference_temperature.max() < ISD110_LOSS_PEAK.valid[1]
    assert errors[-1].max() <= 5e-3
    assert np.all(errors[:-1, 0] / errors[1:, 0] >= 1.6)
    assert errors[0, 0] / errors[-1, 0] >= 3.3


# ------------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("make, match", [
    (lambda: ThermalProperties(ISD110_LOSS_PEAK, 0.0), "heat_capacity must be > 0, got 0.0"),
    (lambda: ThermalProperties(ISD110_LOSS_PEAK, -1.5), "heat_capacity must be > 0, got -1.5"),
    # Below air's rho c (1.2e-3 J/(cm^3 K)): 5e-324 made the temperatures inf, 1e-300 rises of 1e210 K.
    (lambda: ThermalProperties(ISD110_LOSS_PEAK, 5e-324), r"heat_capacity 5e-324 MPa/K .* below 0.001, about air's"),
    (lambda: ThermalProperties(ISD110_LOSS_PEAK, 1e-300), r"heat_capacity 1e-300 MPa/K .* below 0.001"),
    (lambda: ThermalProperties(ISD110_LOSS_PEAK, 9.99e-4), r"heat_capacity 0.000999 MPa/K .* below 0.001"),
    (lambda: ThermalProperties(ISD110_LOSS_PEAK, 1.8, -300.0), r"temperature must be above absolute zero .* -300.0"),
    (lambda: ThermalProperties(ISD110_LOSS_PEAK, 1.8, 20.0, -5.0), "cooling_time must be > 0, got -5.0"),
    (lambda: WLF(8.86, 0.0, 21.2, (0.0, 40.0)), "C2 must be > 0, got 0.0"),
    (lambda: WLF(8.86, -50.0, 21.2, (0.0, 40.0)), "C2 must be > 0, got -50.0"),
    (lambda: WLF(8.86, 50.0, 21.2, (-40.0, 40.0)), r"valid must hold the reference .* above -28.8"),
    (lambda: ThermalProperties(WLF(8.86, 50.0, 21.2, (-20.0, 40.0)), 1.8, -30.0), "at or below T_ref - C2"),
    (lambda: Arrhenius(-1.0, 21.2, (0.0, 40.0)), "activation_energy must be > 0, got -1.0"),
    (lambda: LogLinear(19.45, -300.0, (-400.0, 0.0)), "reference must be above absolute zero"),
    (lambda: FDMKDamper(**TABLE4, thermal="hot"), "thermal must be ThermalProperties"),
    (lambda: FDMKDamper(**TABLE4).at_temperature(30.0), "needs a shift law"),
    (lambda: FDMKDamper(**TABLE4).property_factors([30.0], 1.0), "thermal description"),
    (lambda: thermal_wall().property_factors([-300.0], 1.0), "above absolute zero"),
    # Below absolute zero every law refuses, the log-linear one too (it gave K* = 6e12 N/mm at -300 degC).
    (lambda: LogLinear(19.45, 21.2, (0.0, 70.0)).log10_shift(-300.0), "at or below absolute zero"),
    (lambda: thermal_wall().at_temperature(-300.0), "above absolute zero"),
    (lambda: FDMKDamper(**TABLE4).at_temperature(-300.0, ISD110_LOSS_PEAK), "above absolute zero"),
    # Kelvin typed where degC is meant: above 200 degC, with the degC value suggested.
    (lambda: ThermalProperties(ISD110_LOSS_PEAK, 1.8, 294.15), r"temperature 294.15 degC is above 200 .*21 degC"),
    (lambda: Arrhenius(1.0e5, 294.15, (273.15, 313.15)), r"reference 294.15 degC is above 200 degC.*kelvin"),
    (lambda: LogLinear(19.45, 21.2, (0.0, 350.0)), "valid high end 350.0 degC is above 200"),
    (lambda: thermal_wall().at_ambient(303.15), "subtract 273.15"),
    (lambda: thermal_wall().at_temperature(283.15), "subtract 273.15"),
    (lambda: thermal_wall().property_factors([283.15], 1.0), "above 200 degC"),
    (lambda: WallLimits(temperature=353.15), "temperature limit 353.15 degC is above 200"),
    # A WLF law with C1 <= 0 would make the wall stiffen as it heats.
    (lambda: WLF(-8.86, 101.6, 21.2, (0.0, 40.0)), "C1 must be > 0"),
    (lambda: WLF(0.0, 101.6, 21.2, (0.0, 40.0)), "C1 must be > 0"),
    # A temperature limit on a wall that never heats could never be reached.
    (lambda: FDMKDamper(**TABLE4, limits=WallLimits(temperature=80.0)), "needs a wall with a thermal description"),
    (lambda: dataclasses.replace(thermal_wall(), thermal=None, limits=WallLimits(temperature=80.0)),
     "never heats"),
])
def test_non_physical_thermal_data_is_refused_naming_the_value(make, match):
    with pytest.raises(ValueError, match=match):
        make()


# ------------------------------------------------------------------------------- one rule beyond the range
@pytest.mark.filterwarnings("ignore:wall temperature outside its shift law:UserWarning")  # beyond it on purpose
def test_beyond_its_range_every_frequency_domain_path_holds_the_law_at_the_range_s_end_as_the_time_domain_does():
    # References: the law's printed formula evaluated here at the range's end, log10 a_T = -(T - T_ref) / 19.45
    # (ISD110_LOSS_PEAK, range 0 ... 70 degC), and the force of the time domain's update, which holds its law there.
    r = TABLE4["r"]
    held = 10.0 ** (r * -(70.0 - 21.2) / ((65.6 - 26.7) / 2.0))
    plain = FDMKDamper(**dict(TABLE4, area=1e5, thickness=10.0))
    at_end = dataclasses.replace(plain, eta1=plain.eta1 * held, eta2=plain.eta2 * held)
    frequencies = np.array([0.2, 0.6, 2.0])
    with pytest.warns(UserWarning, match=r"temperature 100 degC is outside the shift law's range 0 \.\.\. 70 degC"):
        hot = thermal_wall(temperature=100.0, heat_capacity=ENORMOUS)
        stiffness = hot.complex_stiffness(frequencies)
    np.testing.assert_allclose(stiffness, at_end.complex_stiffness(frequencies), rtol=1e-13)
    with pytest.warns(UserWarning, match="evaluated at 70 degC, the range's end"):
        np.testing.assert_allclose(thermal_wall().at_temperature(200.0).complex_stiffness(frequencies),
                                   at_end.complex_stiffness(frequencies), rtol=1e-13)
    with pytest.warns(UserWarning, match="outside the shift law's range"):
        factors = thermal_wall().property_factors([150.0, 70.0], 0.6)
    np.testing.assert_array_equal(factors.storage[0], factors.storage[1])
    np.testing.assert_array_equal(factors.loss[0], factors.loss[1])
    nominal = plain.complex_stiffness(0.6)
    assert factors.loss[0] == pytest.approx(at_end.loss_stiffness(0.6) / nominal.imag, rel=1e-12)
    # The time domain, from rest at 100 degC (a heat capacity that keeps it there), steps as the held wall.
    time = np.arange(2001) * 0.005
    displacement = 12.0 * np.sin(2 * np.pi * 0.9 * time)
    reference = at_end.force(displacement, 0.005)
    np.testing.assert_allclose(hot.force(displacement, 0.005), reference, atol=1e-9 * np.abs(reference).max())
    # Below the range alike: the lower end.
    cold_factor = 10.0 ** (r * -(0.0 - 21.2) / ((65.6 - 26.7) / 2.0))
    with pytest.warns(UserWarning, match="evaluated at 0 degC"):
        cold = thermal_wall().at_temperature(-40.0)
    assert cold.eta1 == pytest.approx(plain.eta1 * cold_factor, rel=1e-13)


def test_an_isothermal_wall_drops_its_temperature_limit_and_keeps_the_others():
    wall = dataclasses.replace(thermal_wall(), limits=WallLimits(strain=8.5, temperature=80.0, source="s"))
    assert wall.at_temperature(30.0).limits == WallLimits(strain=8.5, source="s")
    only_heat = dataclasses.replace(thermal_wall(), limits=WallLimits(temperature=80.0))
    assert only_heat.at_temperature(30.0).limits is None


def test_the_conduction_time_is_the_slowest_mode_of_a_layer_between_plates():
    # Reference: h^2 / (pi^2 kappa) by hand for the example roof wall's 2.37 mm layers, kappa = 1e-7 m^2/s.
    from vdw_frames.element.thermal import conduction_time

    assert conduction_time(2.37) == pytest.approx(2.37**2 / (math.pi**2 * 0.1), rel=1e-14)
    assert conduction_time(2.37) == pytest.approx(5.69, abs=0.005)
    with pytest.raises(ValueError, match="thickness must be > 0"):
        conduction_time(0.0)
