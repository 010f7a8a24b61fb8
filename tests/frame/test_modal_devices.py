"""modal_analysis with fluid viscous and friction dampers (issue 30): linear FVDs exactly, nonlinear FVDs and
friction dampers by equivalent linearisation at a stated story drift amplitude.  References: the closed-form
roots of one-story characteristic polynomials, and the energy ratio E_D / (4 pi E_S) of a device driven by a
sine in the time domain (``device_response``).  Units N-mm-s-tonne."""

from __future__ import annotations

import numpy as np
import pytest

from vdw_frames import FDMKDamper, FluidViscousDamper, FrictionDamper, ShearBuilding
from vdw_frames.element.devices import device_response
from vdw_frames.frame import modal_analysis

MASS, STIFFNESS = 400.0, 1.6e5  # one story: omega_0 = 20 rad/s


def one_story(device, damping_ratio=0.02):
    return ShearBuilding([MASS], [STIFFNESS], damping_ratio=damping_ratio, devices={1: device})


def upper_root(coefficients):
    roots = np.roots(coefficients)
    return roots[np.argmax(roots.imag)]


@pytest.mark.parametrize("magnification", [1.0, 0.8])
def test_linear_fvd_without_brace_is_the_closed_form_root_of_the_quadratic(magnification):
    device = FluidViscousDamper(800.0, 1.0, magnification=magnification)
    building = one_story(device)
    c = building.damping_matrix[0, 0]
    # m s^2 + (c + f^2 C) s + k = 0
    s = upper_root([MASS, c + magnification**2 * 800.0, STIFFNESS])
    result = modal_analysis(building)
    assert result.poles[0] == pytest.approx(s, rel=1e-12)
    assert result.damping_ratios[0] == pytest.approx(-s.real / abs(s), rel=1e-12)
    assert result.drift_amplitudes is None and result.linearisation == ()


def test_linear_fvd_with_brace_is_the_closed_form_root_of_the_cubic():
    C, brace, f = 1500.0, 4e4, 1.3
    building = one_story(FluidViscousDamper(C, 1.0, stiffness=brace, magnification=f))
    c = building.damping_matrix[0, 0]
    # (m s^2 + c s + k)(K_b + C s) + f^2 K_b C s = 0: the story's k(s) = f^2 K_b C s / (K_b + C s)
    quadratic = np.array([MASS, c, STIFFNESS])
    cubic = np.polymul(quadratic, [C, brace]) + np.array([0.0, 0.0, f**2 * brace * C, 0.0])
    s = upper_root(cubic)
    result = modal_analysis(building)
    assert result.poles[0] == pytest.approx(s, rel=1e-12)
    # The energy estimate uses K*(omega) of the same damper: exact for the real mode it describes.
    assert 0.0 < result.energy_damping_ratios[0] < 1.0


def loop_energy_ratio(device, amplitude, omega, story_stiffness, storage=True):
    """E_D / (4 pi E_S) of a one-story frame whose device is driven through u_0 sin(omega t) (the story's
    drift), from the time-domain loop of ``device_response``: E_D the loop area of the last cycle, E_S =
    (k + K_eff) u_0^2 / 2 with the device's effective stiffness K_eff = (F(u_max) - F(u_min)) / (2 u_0), the
    forces at the loop's extreme displacements (FEMA 356 Sec. 9.3.3); ``storage=False``: E_S = k u_0^2 / 2,
    the frame's strain energy alone (FEMA 356 eq. 9-36's W_k for velocity-dependent devices)."""
    samples, cycles = 4000, 12
    dt = 2.0 * np.pi / omega / samples
    t = np.arange(samples * cycles + 1) * dt
    drift = amplitude * np.sin(omega * t)
    force = device_response(device, drift, dt)["force"]
    last = slice(samples * (cycles - 1), samples * cycles + 1)
    u, F = drift[last], force[last]
    dissipated = np.sum(0.5 * (F[1:] + F[:-1]) * np.diff(u))
    storage = (F[np.argmax(u)] - F[np.argmin(u)]) / (2.0 * amplitude) if storage else 0.0
    return dissipated / (4.0 * np.pi * 0.5 * (story_stiffness + storage) * amplitude**2)


@pytest.mark.parametrize("alpha", [0.5, 0.3])
def test_nonlinear_fvd_damping_equals_the_time_domain_energy_ratio(alpha):
    amplitude = 20.0  # mm of story drift
    # A stiff brace: the damper's storage K' (25 N/mm at alpha = 0.5) is 1.5e-4 of the story's k, left out of E_S.
    device = FluidViscousDamper(2.0e4, alpha, stiffness=2e7)
    building = one_story(device, damping_ratio=0.0)
    result = modal_analysis(building, drift_amplitude=amplitude)
    omega = 2.0 * np.pi * result.linearisation_frequencies[0]
    assert abs(result.poles[0]) == pytest.approx(omega, rel=1e-11)  # linearised at the mode's own |s|
    reference = loop_energy_ratio(device, amplitude, omega, STIFFNESS, storage=False)
    assert 0.01 < reference < 0.3
    assert result.damping_ratios[0] == pytest.approx(reference, rel=5e-3)
    assert result.energy_damping_ratios[0] == pytest.approx(reference, rel=5e-3)
    assert "20 mm" in result.linearisation[0] and "FVD" in result.linearisation[0]
    np.testing.assert_array_equal(result.drift_amplitudes, [amplitude])


def test_friction_damper_is_the_closed_form_secant_and_energy_linearisation():
    slip, k_d, u0 = 2.0e5, 1.0e5, 10.0  # slips at 2 mm, linearised at 10 mm
    building = one_story(FrictionDamper(slip, k_d))
    c = building.damping_matrix[0, 0]
    effective = slip / u0
    loss = 4.0 * slip * (u0 - slip / k_d) / (np.pi * u0**2)
    omega = np.sqrt((STIFFNESS + effective) / MASS)  # |s| of m s^2 + c' s + k' is sqrt(k'/m)
    s = upper_root([MASS, c + loss / omega, STIFFNESS + effective])
    result = modal_analysis(building, drift_amplitude=u0)
    assert result.poles[0] == pytest.approx(s, rel=1e-11)
    bare_ratio = c / (2.0 * MASS * omega)
    assert result.damping_ratios[0] == pytest.approx(bare_ratio + loss / (2.0 * (STIFFNESS + effective)), rel=1e-11)
    # and the time-domain loop of the same damper at u0 gives the same added ratio
    assert result.damping_ratios[0] - bare_ratio == pytest.approx(
        loop_energy_ratio(FrictionDamper(slip, k_d), u0, omega, STIFFNESS), rel=5e-3)


def test_below_the_slip_a_friction_damper_is_a_spring():
    building = one_story(FrictionDamper(2.0e5, 1.0e5), damping_ratio=0.0)
    result = modal_analysis(building, drift_amplitude=1.0)
    assert result.damping_ratios[0] == pytest.approx(0.0, abs=1e-12)
    assert result.periods[0] == pytest.approx(2 * np.pi / np.sqrt((STIFFNESS + 1.0e5) / MASS), rel=1e-12)


def test_mixed_building_per_story_amplitudes_and_each_mode_at_its_own_frequency():
    wall = FDMKDamper(G1=0.5, G2=3.0, eta1=0.3, eta2=2.0, r=0.5, area=0.2e6, magnification=1.2)
    building = ShearBuilding([300.0, 300.0, 250.0], [2e5, 1.8e5, 1.5e5], devices={
        1: [wall, FrictionDamper(1e5, 8e4)], 2: FluidViscousDamper(1500.0, 0.5, stiffness=1e5),
        3: FluidViscousDamper(600.0, 1.0)})
    result = modal_analysis(building, drift_amplitude=[12.0, 10.0, 6.0])
    assert result.modes.tolist() == [1, 2, 3]
    np.testing.assert_allclose(2 * np.pi * result.linearisation_frequencies, np.abs(result.poles), rtol=1e-11)
    assert len(result.linearisation) == 2 and "story 1" in result.linearisation[0]
    assert "12 mm" in result.linearisation[0] and "10 mm" in result.linearisation[1]
    # Larger amplitudes: the friction damper's secant stiffness and the FVD's C_eq fall, mode 1 lengthens.
    larger = modal_analysis(building, 1, drift_amplitude=[24.0, 20.0, 12.0])
    assert larger.periods[0] > result.periods[0]


def test_a_nonlinear_device_without_an_amplitude_is_refused_naming_it():
    building = ShearBuilding([300.0, 300.0], [2e5, 1.8e5], devices={2: FluidViscousDamper(1500.0, 0.5, stiffness=1e5)})
    with pytest.raises(ValueError, match=r"story 2.s FVD C=1500.*alpha=0.5.*drift_amplitude"):
        modal_analysis(building)
    with pytest.raises(ValueError, match="drift_amplitude must be > 0"):
        modal_analysis(building, drift_amplitude=[5.0, 0.0])
    with pytest.raises(ValueError, match="one a story"):
        modal_analysis(building, drift_amplitude=[5.0, 4.0, 3.0])
    with pytest.raises(ValueError, match="drift_amplitude"):
        modal_analysis(building, drift_amplitude=float("nan"))


def test_strain_dependent_walls_are_fixed_at_the_strain_of_the_stated_drift():
    from vdw_frames.paper import strain_dependent

    family = strain_dependent()
    wall = type(family)(**{**{name: getattr(family, name) for name in ("strains", "G1", "G2", "eta1", "eta2", "r")},
                           "area": 0.3e6, "thickness": 8.0, "magnification": 1.25})
    building = ShearBuilding([300.0, 300.0], [2e5, 1.8e5], devices={1: wall, 2: wall})
    # drift 20 mm -> wall 25 mm -> strain 25 / 8 = 3.125: the wall at that strain on both stories
    reference = modal_analysis(building.walls_at(25.0 / 8.0))
    result = modal_analysis(building, drift_amplitude=20.0)
    np.testing.assert_allclose(result.poles, reference.poles, rtol=1e-12)
    assert "strain amplitude 3.125" in result.linearisation[0]
    with pytest.raises(ValueError, match=r"strain-dependent FDMK wall.*drift_amplitude"):
        modal_analysis(building)


def test_linearised_poles_are_roots_of_the_characteristic_matrix_built_here():
    # T(s) = s^2 M + s C + K + sum_stories B^T (K'(w) + s K''(w) / w) B with K' + i K'' = story_stiffness(w / 2 pi)
    # at the story's drift amplitude and w = |s|, assembled here from the devices' own K* (tridiagonal).
    devices = {1: FrictionDamper(1e5, 8e4), 2: FluidViscousDamper(1500.0, 0.5, stiffness=1e5),
               3: FluidViscousDamper(3000.0, 0.35, stiffness=2e5, magnification=1.4)}
    building = ShearBuilding([300.0, 300.0, 250.0], [2e5, 1.8e5, 1.5e5], devices=devices)
    amplitude = np.array([12.0, 10.0, 6.0])
    result = modal_analysis(building, drift_amplitude=amplitude)
    mass, damping = np.diag(building.masses), building.damping_matrix
    for s in result.poles:
        omega = abs(s)
        story = np.array(building.stiffnesses, dtype=complex)
        for k, device in devices.items():
            value = complex(device.story_stiffness(omega / (2 * np.pi), amplitude[k - 1])[()])
            story[k - 1] += value.real + s * value.imag / omega
        stiffness = np.diag(story + np.append(story[1:], 0.0)) - np.diag(story[1:], 1) - np.diag(story[1:], -1)
        matrix = s**2 * mass + s * damping + stiffness
        singular = np.linalg.svd(matrix, compute_uv=False)
        assert singular[-1] <= 1e-11 * singular[0]


def test_complex_modes_keeps_its_old_walls_keyword_with_a_deprecation_warning():
    """complex_modes(building, walls=False) (before 0.3) is complex_modes(building, devices=False): the bare frame,
    whose undamped poles are i omega with omega^2 the eigenvalues of M^-1 K (scipy's eigh, written here)."""
    from scipy.linalg import eigh

    from vdw_frames.frame.modal import complex_modes

    building = ShearBuilding([200.0, 150.0], [3e5, 2e5], damping_ratio=0.0,
                             devices={1: [FluidViscousDamper(500.0, 1.0)]})
    with pytest.warns(DeprecationWarning, match=r"complex_modes\(walls=...\) is deprecated.*devices="):
        poles, _, _ = complex_modes(building, walls=False)
    omega = np.sqrt(eigh(np.asarray(building.stiffness_matrix), np.diag([200.0, 150.0]), eigvals_only=True))
    np.testing.assert_allclose(poles, 1j * omega, rtol=1e-10, atol=1e-12 * omega.max())
    damped, _, _ = complex_modes(building, devices=True)
    assert (damped.real < 0).all()  # walls=True would have kept the dashpot: devices=True does
