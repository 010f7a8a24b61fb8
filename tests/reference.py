"""Independent reference solutions for the tests (no code shared with the package's time stepping)."""

from __future__ import annotations

import numpy as np


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
