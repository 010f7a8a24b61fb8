"""SupportedDamper: a wall in series with its support, against the series formula written out here.

The references never call the package's frequency-domain code: the wall's modulus is the closed form of
eqs. (3)-(5) (tests/reference.py) or s^r written out, the series assembly K_w k_s / (K_w + k_s) is
formed there, and time histories come from the FFT of that formula.  The supported walls in a frame:
tests/frame/test_supported_walls.py.
"""

import numpy as np
import pytest
import reference
from builders import ABEL, FITTED300, TABLE4, three_story, two_tone_motion
from reference import series_transfer, wall_stiffness

from vdw_frames import FDMKDamper, SupportedDamper, modal_analysis, simulate, sine_test

FREQUENCIES = np.array([0.05, 0.5, 1.0, 2.0, 5.0, 20.0])


def assembly(params, ratio, area=1e5):
    """A wall and a support of ``ratio`` x |K_w(1 Hz)|."""
    wall = FDMKDamper(**params, area=area)
    support = ratio * abs(wall_stiffness(params, area, 10.0, 2 * np.pi))
    return wall, SupportedDamper(wall, support)


# ------------------------------------------------------------------------------ frequency domain
@pytest.mark.parametrize("params", [TABLE4, FITTED300, ABEL])
@pytest.mark.parametrize("ratio", [0.3, 1.0, 3.0])
def test_complex_stiffness_is_the_series_formula(params, ratio):
    wall, supported = assembly(params, ratio)
    expected = series_transfer(params, wall.area, wall.thickness, supported.support_stiffness)(2j * np.pi * FREQUENCIES)
    np.testing.assert_allclose(supported.complex_stiffness(FREQUENCIES), expected, rtol=1e-12)
    np.testing.assert_allclose(supported.storage_stiffness(FREQUENCIES), expected.real, rtol=1e-12)
    np.testing.assert_allclose(supported.loss_stiffness(FREQUENCIES), expected.imag, rtol=1e-12)
    np.testing.assert_allclose(supported.damping_coefficient(FREQUENCIES), expected.imag / (2 * np.pi * FREQUENCIES),
                               rtol=1e-12)
    # Off the imaginary axis (the modal analysis evaluates it there): s^r written out, principal branch.
    s = np.array([-0.3 + 2.0j, -5.0 + 1.0j, 4.0 + 0.5j])
    x = np.abs(s) ** params["r"] * np.exp(1j * params["r"] * np.angle(s))
    modulus = params["G1"] + params["eta1"] * x
    if params["G2"] > 0:
        modulus = modulus + params["G2"] * params["eta2"] * x / (params["G2"] + params["eta2"] * x)
    k_w = modulus * wall.area / wall.thickness
    k_s = supported.support_stiffness
    np.testing.assert_allclose(supported.stiffness_transfer(s), k_w * k_s / (k_w + k_s), rtol=1e-12)


def test_support_softens_and_dissipates_less_and_the_limits():
    wall, supported = assembly(FITTED300, 1.0)
    k_w = wall.complex_stiffness(FREQUENCIES)
    # In series the assembly is softer than either part.
    softer = np.minimum(np.abs(k_w), supported.support_stiffness)
    assert np.all(np.abs(supported.complex_stiffness(FREQUENCIES)) < softer)
    # A support much softer than the wall: the assembly is the support.
    soft = SupportedDamper(wall, 1e-6 * np.abs(k_w).min())
    np.testing.assert_allclose(soft.complex_stiffness(FREQUENCIES), soft.support_stiffness, rtol=1e-5)


def test_modulus_methods_belong_to_the_material():
    _, supported = assembly(TABLE4, 1.0)
    assert not hasattr(supported, "complex_modulus") and not hasattr(supported, "storage_modulus")
    assert supported.r == TABLE4["r"] and supported.area == 1e5 and supported.thickness == 10.0


# ------------------------------------------------------------------------------ a very stiff support is rigid
def smooth_motion(dt, duration=10.0):
    return two_tone_motion(dt, duration, (1.3, 2000.0), (3.7, 800.0), ramp=3.0)


def test_very_stiff_support_gives_the_rigid_result_within_1e_9():
    wall = FDMKDamper(**FITTED300, area=3e5)
    stiff = SupportedDamper(wall, 1e15)  # |K_w| ~ 1e5 N/mm: the support takes 1e-10 of the deformation
    np.testing.assert_allclose(stiff.complex_stiffness(FREQUENCIES), wall.complex_stiffness(FREQUENCIES), rtol=1e-9)
    t = np.arange(2001) * 0.005
    u = reference.tapered_sine(t, 1.5, 25.0, 2.0, t[-1])
    rigid = wall.force(u, 0.005)
    assert np.abs(stiff.force(u, 0.005) - rigid).max() <= 1e-9 * np.abs(rigid).max()
    motion = smooth_motion(0.01)
    a = simulate(three_story({1: wall, 2: wall}), motion)
    b = simulate(three_story({1: stiff, 2: stiff}), motion)
    assert np.abs(b.displacement - a.displacement).max() <= 1e-9 * np.abs(a.displacement).max()
    assert np.abs(b.wall_strain - a.wall_strain).max() <= 1e-9 * np.abs(a.wall_strain).max()
    modes_a = modal_analysis(three_story({1: wall, 2: wall}))
    modes_b = modal_analysis(three_story({1: stiff, 2: stiff}))
    np.testing.assert_allclose(modes_b.poles, modes_a.poles, rtol=1e-9)


# ------------------------------------------------------------------------------ time domain
def tapered_sine_errors(params, ratio, steps=(0.2, 0.1, 0.05), frequency=1.0, duration=8.0):
    """max |F - F_exact| / max |F_exact| of the assembly and of the bare wall at omega dt in ``steps``.

    F_exact: the FFT solution of the series formula (resp. the wall alone) on a 4x finer grid.
    """
    wall, supported = assembly(params, ratio)
    errors = {"supported": [], "bare": []}
    for theta in steps:
        dt = theta / (2 * np.pi * frequency)
        fine = dt / 4
        t = np.arange(round(duration / fine) + 1) * fine
        u = reference.tapered_sine(t, frequency, 30.0, ramp=2.0, duration=duration)
        for name, element, support in (("supported", supported, supported.support_stiffness), ("bare", wall, np.inf)):
            transfer = (series_transfer(params, wall.area, wall.thickness, support) if np.isfinite(support) else
                        lambda s: wall_stiffness(params, wall.area, wall.thickness, np.asarray(s).imag))
            exact = reference.frequency_domain_response(transfer, u, fine)
            force = element.force(u[::4], dt)
            errors[name].append(np.max(np.abs(force - exact[::4])) / np.max(np.abs(exact)))
    return {name: np.array(values) for name, values in errors.items()}


@pytest.mark.parametrize("params", [TABLE4, FITTED300, ABEL])
@pytest.mark.parametrize("ratio", [0.3, 1.0, 3.0])
def test_force_matches_fft_of_the_series_assembly_with_the_bare_elements_accuracy_and_order(params, ratio):
    errors = tapered_sine_errors(params, ratio)
    supported, bare = errors["supported"], errors["bare"]
    assert supported[0] < 0.01  # the bare element's bar at omega dt = 0.2 (test_damped_two_step)
    # Same order: halving dt divides the error by ~4 (measured 3.97-4.00).
    assert (supported[:-1] / supported[1:]).min() >= 3.5, supported
    # Same accuracy: the support is exact, so only the wall's share of the deformation carries the
    # discretisation error; measured 0.2-0.8 x the bare element's.
    assert np.all(supported <= bare), (supported, bare)


@pytest.mark.parametrize("memory", ["exact", "fast"])
def test_kernel_is_the_discrete_series_transfer_function(memory):
    # Convolution quadrature = the transfer function at s = delta(zeta)/dt; with the closed-form
    # elimination of the internal node the assembly's stepping is exactly the series formula at that
    # symbol (up to rounding and the fast memory's 3e-9).
    from vdw_frames.element.fractional import get_method

    scheme = get_method("damped")
    _, supported = assembly(TABLE4, 0.7)
    dt, steps = 0.01, 3001
    t = np.arange(steps) * dt
    u = reference.tapered_sine(t, 2.0, 30.0, ramp=3.0, duration=t[-1])
    k_s = supported.support_stiffness

    def discrete(s):
        x = scheme.symbol(np.asarray(s).imag, dt) ** TABLE4["r"]
        g1, g2, e1, e2 = TABLE4["G1"], TABLE4["G2"], TABLE4["eta1"], TABLE4["eta2"]
        k_w = (g1 + e1 * x + g2 * e2 * x / (g2 + e2 * x)) * supported.area / supported.thickness
        return k_w * k_s / (k_w + k_s)

    expected = reference.frequency_domain_response(discrete, u, dt, pad_factor=64)
    force = supported.force(u, dt, memory=memory)
    assert np.max(np.abs(force - expected)) <= 1e-7 * np.max(np.abs(expected))


def test_trial_commit_state_reproduces_force():
    _, supported = assembly(FITTED300, 0.5)
    t = np.arange(1500) * 0.004
    u = 20 * np.sin(2 * np.pi * 1.1 * t) * np.sin(0.7 * t)
    state = supported.new_state(0.004)
    stepped = []
    for value in u:
        state.trial(value + 3.0)
        force, tangent = state.trial(value)
        stepped.append(force)
        state.commit()
    np.testing.assert_allclose(stepped, supported.force(u, 0.004), rtol=1e-12, atol=1e-6)
    # The tangent of the assembly: the wall's tangent in series with the support.
    wall_state = supported.damper.new_state(0.004)
    _, wall_tangent = wall_state.trial(0.0)
    k_s = supported.support_stiffness
    assert tangent == pytest.approx(wall_tangent * k_s / (wall_tangent + k_s), rel=1e-12)


def test_sine_test_loop_is_pi_times_the_series_loss_stiffness():
    _, supported = assembly(FITTED300, 1.0)
    result = sine_test(supported, 20.0, 1.0)
    expected = series_transfer(FITTED300, 1e5, 10.0, supported.support_stiffness)(np.array([2j * np.pi]))[0]
    assert result.loop_area == pytest.approx(np.pi * expected.imag * 20.0**2, rel=1e-3)  # steady loop: 0.1 %
    assert result.storage_stiffness == pytest.approx(expected.real, rel=1e-3)
    assert result.loss_stiffness == pytest.approx(expected.imag, rel=1e-3)


# ------------------------------------------------------------------------------ property bounds
def test_scaled_scales_the_wall_and_keeps_the_support():
    _, supported = assembly(FITTED300, 1.0)
    upper = supported.scaled(1.2)
    assert upper.support_stiffness == supported.support_stiffness
    k_w = 1.2 * wall_stiffness(FITTED300, 1e5, 10.0, 2 * np.pi * FREQUENCIES)
    k_s = supported.support_stiffness
    np.testing.assert_allclose(upper.complex_stiffness(FREQUENCIES), k_w * k_s / (k_w + k_s), rtol=1e-12)


@pytest.mark.parametrize("bad", [0.0, -1.0, np.nan, np.inf, "stiff", None])
def test_support_stiffness_is_validated(bad):
    with pytest.raises(ValueError, match="support_stiffness"):
        SupportedDamper(FDMKDamper(**TABLE4), bad)


def test_only_fdmk_walls_can_be_supported():
    with pytest.raises(ValueError, match="FDMKDamper"):
        SupportedDamper(SupportedDamper(FDMKDamper(**TABLE4), 1e5), 1e5)
