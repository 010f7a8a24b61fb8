"""Independent reference solutions for the tests (no code shared with the package's time stepping)."""

from __future__ import annotations

import numpy as np


def closed_form_moduli(params, f):
    """(G', G'') in MPa of eqs. (3)-(5) at f (Hz) from the real closed form (no complex arithmetic)."""
    a = (2 * np.pi * np.asarray(f)) ** params["r"]
    c, q = np.cos(params["r"] * np.pi / 2), np.sin(params["r"] * np.pi / 2)
    g1, g2, e1, e2 = params["G1"], params["G2"], params["eta1"], params["eta2"]
    d = g2**2 + 2 * g2 * e2 * a * c + e2**2 * a**2
    return g1 + e1 * a * c + g2 * e2 * a * (g2 * c + e2 * a) / d, e1 * a * q + g2**2 * e2 * a * q / d


def smooth_step(x):
    """C-infinity step from 0 (x <= 0) to 1 (x >= 1)."""
    x = np.clip(np.asarray(x, dtype=float), 0.0, 1.0)
    with np.errstate(divide="ignore", over="ignore"):
        rise = np.where(x > 0.0, np.exp(-1.0 / np.where(x > 0.0, x, 1.0)), 0.0)
        fall = np.where(x < 1.0, np.exp(-1.0 / np.where(x < 1.0, 1.0 - x, 1.0)), 0.0)
    return rise / (rise + fall)


def tapered_sine(t, frequency, amplitude, ramp, duration):
    """A sine of ``frequency`` Hz switched on over ``ramp`` s and off over the last ``ramp`` s."""
    envelope = smooth_step(t / ramp) * smooth_step((duration - t) / ramp)
    return amplitude * np.sin(2.0 * np.pi * frequency * t) * envelope


def frequency_domain_response(transfer, signal, dt, pad_factor=16):
    """Causal response of a linear operator given by its transfer function ``transfer(s)`` (s in rad/s).

    The signal (sampled at dt, zero before t = 0 and after its end) is zero padded to ``pad_factor``
    times its length, so the periodic FFT solution equals the causal one up to the wrap-around of the
    response's tail; for a smooth signal the sampling error is spectrally small.
    """
    n = signal.size
    size = pad_factor * n
    spectrum = np.fft.rfft(signal, size)
    omega = 2.0 * np.pi * np.fft.rfftfreq(size, dt)
    response = np.fft.irfft(transfer(1j * omega) * spectrum, size)
    return response[:n]


def tapered_sine_error(damper, dt, method, frequency=1.0, duration=8.0):
    """max |F - F_exact| / max |F_exact| of ``damper.force`` for a tapered 30 mm sine.

    The exact response is the frequency-domain solution on a 4x finer grid (spectrally accurate there).
    """
    fine = dt / 4
    t_fine = np.arange(round(duration / fine) + 1) * fine
    u_fine = tapered_sine(t_fine, frequency, 30.0, ramp=2.0, duration=duration)
    exact = frequency_domain_response(damper.transfer, u_fine / damper.thickness, fine) * damper.area
    force = damper.force(u_fine[::4], dt, method=method)
    return np.max(np.abs(force - exact[::4])) / np.max(np.abs(exact))


def discrete_transfer_error(damper, scheme, memory, steps, dt=0.01):
    """max |F - F_discrete| / max |F_discrete| for a tapered 2 Hz sine of ``steps`` samples.

    Convolution quadrature is the transfer function evaluated at s = delta(zeta) / dt, so the FFT solution
    with that symbol equals the time stepping up to rounding: this checks the kernel, not the method.
    """
    t = np.arange(steps) * dt
    u = tapered_sine(t, 2.0, 30.0, ramp=3.0, duration=t[-1])
    discrete = lambda s: damper.transfer(scheme.symbol(s.imag, dt))  # noqa: E731
    expected = frequency_domain_response(discrete, u / damper.thickness, dt, pad_factor=64) * damper.area
    force = damper.force(u, dt, method=scheme, memory=memory)
    return np.max(np.abs(force - expected)) / np.max(np.abs(expected))
