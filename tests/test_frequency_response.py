"""Complex modulus of the FDMK model (eqs. (3)-(5)) against closed forms and limits."""

import numpy as np
import pytest

from vdw_frames import FDMKDamper

TABLE4 = dict(G1=8.69, G2=3.58, eta1=0.75, eta2=0.98, r=0.60)
FREQUENCIES = np.array([0.01, 0.5, 1.0, 1.5, 2.0, 5.0, 10.0, 100.0])


def closed_form(G1, G2, eta1, eta2, r, f):
    """G', G'' written out in real arithmetic (derivation in vdw_frames.element.damper's docstring)."""
    a = (2 * np.pi * f) ** r
    c, q = np.cos(r * np.pi / 2), np.sin(r * np.pi / 2)
    denominator = G2**2 + 2 * G2 * eta2 * a * c + eta2**2 * a**2
    storage = G1 + eta1 * a * c + G2 * eta2 * a * (G2 * c + eta2 * a) / denominator
    loss = eta1 * a * q + G2**2 * eta2 * a * q / denominator
    return storage, loss


@pytest.mark.parametrize("params", [TABLE4, dict(G1=0.0, G2=5.0, eta1=0.2, eta2=3.0, r=0.3),
                                    dict(G1=1.0, G2=0.5, eta1=2.0, eta2=0.1, r=0.95)])
def test_complex_modulus_matches_closed_form(params):
    damper = FDMKDamper(**params)
    storage, loss = closed_form(**params, f=FREQUENCIES)
    np.testing.assert_allclose(damper.storage_modulus(FREQUENCIES), storage, rtol=1e-13)
    np.testing.assert_allclose(damper.loss_modulus(FREQUENCIES), loss, rtol=1e-13)
    np.testing.assert_allclose(damper.loss_factor(FREQUENCIES), loss / storage, rtol=1e-13)
    scale = damper.area / damper.thickness
    np.testing.assert_allclose(damper.storage_stiffness(FREQUENCIES), storage * scale, rtol=1e-13)
    np.testing.assert_allclose(damper.loss_stiffness(FREQUENCIES), loss * scale, rtol=1e-13)
    np.testing.assert_allclose(damper.damping_coefficient(FREQUENCIES),
                               loss * scale / (2 * np.pi * FREQUENCIES), rtol=1e-13)


def test_table4_values_under_the_model():
    # Hand-checked anchor: G*(i pi) for Table 4 (f = 0.5 Hz) = 10.705 + 2.020i MPa.
    modulus = FDMKDamper(**TABLE4).complex_modulus(0.5)
    assert modulus.real == pytest.approx(10.70505, abs=1e-5)
    assert modulus.imag == pytest.approx(2.01998, abs=1e-5)


def test_r_equal_one_is_classical_kelvin_plus_maxwell():
    G1, G2, eta1, eta2 = 2.0, 3.0, 0.4, 1.5
    damper = FDMKDamper(G1, G2, eta1, eta2, r=1.0)
    omega = 2 * np.pi * FREQUENCIES
    tau = eta2 / G2
    storage = G1 + G2 * (omega * tau) ** 2 / (1 + (omega * tau) ** 2)
    loss = eta1 * omega + G2 * omega * tau / (1 + (omega * tau) ** 2)
    np.testing.assert_allclose(damper.storage_modulus(FREQUENCIES), storage, rtol=1e-13)
    np.testing.assert_allclose(damper.loss_modulus(FREQUENCIES), loss, rtol=1e-13)


def test_low_and_high_frequency_asymptotes():
    damper = FDMKDamper(**TABLE4)
    r, q, c = damper.r, np.sin(0.3 * np.pi), np.cos(0.3 * np.pi)
    low = 1e-6
    a = (2 * np.pi * low) ** r
    # omega -> 0: the Maxwell branch acts as its dashpot alone, G'' ~ (eta1 + eta2) omega^r sin(r pi/2).
    assert damper.storage_modulus(low) == pytest.approx(damper.G1, rel=1e-3)
    assert damper.loss_modulus(low) == pytest.approx((damper.eta1 + damper.eta2) * a * q, rel=1e-3)
    high = 1e9
    a = (2 * np.pi * high) ** r
    # omega -> infinity: the Maxwell branch acts as its spring, G2.
    assert damper.storage_modulus(high) == pytest.approx(damper.G1 + damper.G2 + damper.eta1 * a * c, rel=1e-4)
    assert damper.loss_modulus(high) == pytest.approx(damper.eta1 * a * q, rel=1e-4)


@pytest.mark.parametrize("zeroed", ["G2", "eta2"])
def test_maxwell_branch_off_when_G2_or_eta2_is_zero(zeroed):
    params = dict(TABLE4, **{zeroed: 0.0})
    kelvin_only = dict(TABLE4, G2=0.0, eta2=0.0)
    a = FDMKDamper(**params).complex_modulus(FREQUENCIES)
    b = FDMKDamper(**kelvin_only).complex_modulus(FREQUENCIES)
    expected = TABLE4["G1"] + TABLE4["eta1"] * (2j * np.pi * FREQUENCIES) ** TABLE4["r"]
    np.testing.assert_allclose(a, expected, rtol=1e-14)
    np.testing.assert_allclose(b, expected, rtol=1e-14)


def test_scalar_in_scalar_out():
    assert np.ndim(FDMKDamper(**TABLE4).storage_modulus(1.0)) == 0
