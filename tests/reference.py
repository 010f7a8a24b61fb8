"""Independent reference solutions for the tests (no code shared with the package's time stepping), and the
measures of agreement the tests compare with."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from scipy.linalg import eig
from scipy.signal import StateSpace, lsim

from vdw_frames import SupportedDamper


def closed_form_moduli(params, f):
    """(G', G'') in MPa of eqs. (3)-(5) at f (Hz) from the real closed form (no complex arithmetic)."""
    a = (2 * np.pi * np.asarray(f)) ** params["r"]
    c, q = np.cos(params["r"] * np.pi / 2), np.sin(params["r"] * np.pi / 2)
    g1, g2, e1, e2 = params["G1"], params["G2"], params["eta1"], params["eta2"]
    d = g2**2 + 2 * g2 * e2 * a * c + e2**2 * a**2
    return g1 + e1 * a * c + g2 * e2 * a * (g2 * c + e2 * a) / d, e1 * a * q + g2**2 * e2 * a * q / d


def fdmk_modulus(params, f):
    """G* of eqs. (3)-(5) (MPa) at f (Hz), written out with complex powers."""
    s_r = (2j * np.pi * np.asarray(f, dtype=float)) ** params["r"]
    maxwell = params["G2"] * params["eta2"] * s_r / (params["G2"] + params["eta2"] * s_r)
    return params["G1"] + params["eta1"] * s_r + maxwell


def wall_stiffness(params, area, thickness, omega):
    """K_w(i omega) (N/mm) from the real closed form of eqs. (3)-(5), written without the package."""
    if params["G2"] == 0.0 or params["eta2"] == 0.0:
        modulus = params["G1"] + params["eta1"] * (1j * omega) ** params["r"]
    else:
        storage, loss = closed_form_moduli(params, omega / (2 * np.pi))
        modulus = storage + 1j * loss
    return modulus * area / thickness


def series_transfer(params, area, thickness, support):
    """s -> K_w k_s / (K_w + k_s) on the imaginary axis (what frequency_domain_response asks for)."""
    def transfer(s):
        wall = wall_stiffness(params, area, thickness, np.asarray(s).imag)
        return wall * support / (wall + support)
    return transfer


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


def state_space_eigenvalues(building):
    """Eigenvalues of the first-order model with the walls' internal degrees of freedom.

    States: floor displacements u and velocities v; per wall the Maxwell dashpot's displacement q
    (c2 q' = k2 (w - q)) and, for a supported wall, the wall's own deformation w, a massless node
    (c1 w' = k_s (d - w) - k1 w - k2 (w - q)).  Written from the mechanics, not from k(s).
    """
    n = building.stories
    inverse_mass = np.diag(1.0 / np.asarray(building.masses))
    stiffness = np.array(building.stiffness_matrix)
    gravity = np.asarray(building.geometric_stiffness)
    for k in range(n):  # P-Delta: -P/h springs between the floors
        unit = np.zeros(n)
        unit[k] = 1.0
        if k:
            unit[k - 1] = -1.0
        stiffness += gravity[k] * np.outer(unit, unit)
    internal = sum(2 if isinstance(wall, SupportedDamper) else 1 for _, wall in building.wall_list)
    size = 2 * n + internal
    a = np.zeros((size, size))
    a[:n, n:2 * n] = np.eye(n)
    a[n:2 * n, :n] = -inverse_mass @ stiffness
    a[n:2 * n, n:2 * n] = -inverse_mass @ np.asarray(building.damping_matrix)
    column = 2 * n
    for story, wall in building.wall_list:
        b = np.zeros(n)
        b[story - 1] = 1.0
        if story > 1:
            b[story - 2] = -1.0
        material = wall.damper if isinstance(wall, SupportedDamper) else wall
        assert material.r == 1.0
        scale = material.area / material.thickness
        k1, c1, k2, c2 = (material.G1 * scale, material.eta1 * scale, material.G2 * scale, material.eta2 * scale)
        q = column
        column += 1
        if isinstance(wall, SupportedDamper):
            w = column
            column += 1
            k_s = wall.support_stiffness
            a[n:2 * n, :n] -= inverse_mass @ np.outer(b, k_s * b)
            a[n:2 * n, w] += inverse_mass @ b * k_s
            a[w, :n] += k_s * b / c1
            a[w, w] -= (k_s + k1 + k2) / c1
            a[w, q] += k2 / c1
            a[q, w] += k2 / c2
            a[q, q] -= k2 / c2
        else:
            a[n:2 * n, :n] -= inverse_mass @ np.outer(b, (k1 + k2) * b)
            a[n:2 * n, n:2 * n] -= inverse_mass @ np.outer(b, c1 * b)
            a[n:2 * n, q] += inverse_mass @ b * k2
            a[q, :n] += k2 / c2 * b
            a[q, q] -= k2 / c2
    values, vectors = eig(a)
    upper = values.imag > 1e-9 * np.abs(values)
    values, vectors = values[upper], vectors[:n, upper]
    order = np.argsort(np.abs(values))
    return values[order], vectors[:, order]


def sdof_peak_lsim(motion, period: float, damping_ratio: float) -> float:
    """omega^2 max|u| from scipy.signal.lsim (matrix exponential, linear input interpolation)."""
    omega = 2.0 * math.pi / period
    system = StateSpace([[0.0, 1.0], [-omega**2, -2.0 * damping_ratio * omega]], [[0.0], [-1.0]],
                        [[1.0, 0.0]], [[0.0]])
    _, displacement, _ = lsim(system, motion.acceleration, motion.time)
    return omega**2 * np.max(np.abs(displacement))


def at2_values(path: Path) -> list[float]:
    """The numbers after the line holding NPTS, parsed here without the package (in g)."""
    lines = path.read_bytes().decode("ascii").replace("\r", "\n").split("\n")
    count_line = next(i for i, line in enumerate(lines) if "NPTS" in line)
    return [float(token) for line in lines[count_line + 1:] for token in line.split()]


# ---------------------------------------------------------------------------------------------- agreement
def peak_deviation(drift, reference):
    """max over stories of |peak |drift| / peak |reference| - 1|."""
    return np.abs(np.abs(drift).max(axis=0) / np.abs(reference).max(axis=0) - 1.0).max()


def history_deviation(drift, reference):
    """max |drift - reference| / max |reference| over the whole history."""
    return np.abs(drift - reference).max() / np.abs(reference).max()
