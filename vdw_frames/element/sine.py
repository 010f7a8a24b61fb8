"""The sinusoidal test of a damper alone (the paper's Section 3.1 loops and Table 5 areas).

Transients: the displacement U sin(omega t) starts from rest, and a fractional element forgets its start
only as a power law, not exponentially.  Measured with the default discretisation and 200 steps per
cycle, for r = 0.1 ... 1 at 0.5 and 10 Hz (Table 4's parameters among them), the loop area of the n-th
cycle differs from the steady value pi K'' U^2 by up to 10 % (n = 1; 15 % for the recommended 225 %
set at 0.5 Hz), 1.1 % (n = 2), 0.2 % (n = 3) and 0.07 % from n = 5 on; what remains after ten cycles
(<= 0.05 %, worst for a classical Maxwell branch at 10 Hz, whose loss modulus is small) is the
discretisation, not the transient.  The default ``cycles=5`` therefore gives the steady loop to 0.1 %;
``tests/test_sine.py::test_last_loop_is_steady`` asserts this bound.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validation import positive, require_finite, whole_number
from .damper import FDMKDamper
from .supported import WALL_TYPES
from .fractional import DEFAULT_METHOD

SAMPLES_PER_CYCLE = 200  # omega*dt = 0.031: the default method's error r (omega dt)^2 / 6 <= 1.6e-4


@dataclass(frozen=True)
class SineTestResult:
    """Result of :func:`sine_test`.  Arrays cover the whole test; scalars are from the last full cycle.

    time (s), displacement (mm), force (N); loop_area (N*mm, energy dissipated in the last cycle);
    storage_stiffness and loss_stiffness (N/mm, least-squares fit F ~ K' u + (K''/omega) du/dt + c on the
    last cycle); effective_stiffness (N/mm, peak-to-peak force / peak-to-peak displacement);
    equivalent_damping_ratio (-, W_D / (2 pi K_eff U^2)).
    """

    damper: FDMKDamper
    amplitude: float
    frequency: float
    dt: float
    cycles: int
    time: np.ndarray
    displacement: np.ndarray
    force: np.ndarray
    loop_area: float
    storage_stiffness: float
    loss_stiffness: float
    effective_stiffness: float
    equivalent_damping_ratio: float

    @property
    def last_cycle(self) -> slice:
        """Slice of the arrays covering the last full cycle (both end points included)."""
        samples = round(1.0 / (self.frequency * self.dt))
        return slice(self.time.size - 1 - samples, self.time.size)


def sine_test(damper: FDMKDamper, amplitude: float, frequency: float, dt: float | None = None,
              cycles: int = 5, method=DEFAULT_METHOD) -> SineTestResult:
    """Drive ``damper`` with u(t) = amplitude * sin(2 pi frequency t) from rest for ``cycles`` cycles.

    amplitude in mm, frequency in Hz, dt in s (default: 200 samples per cycle).  The period must be a
    whole number of steps.  Returns a :class:`SineTestResult` (N, mm, N*mm, N/mm).
    """
    if not isinstance(damper, WALL_TYPES):
        raise ValueError(f"damper must be an FDMKDamper or a SupportedDamper, got {type(damper).__name__}")
    amplitude = positive("amplitude", amplitude)
    frequency = positive("frequency", frequency)
    if dt is None:
        dt = 1.0 / (frequency * SAMPLES_PER_CYCLE)
    dt = positive("dt", dt)
    cycles = whole_number("cycles", cycles, 1)
    steps_per_cycle = 1.0 / (frequency * dt)
    samples = round(steps_per_cycle)
    if samples < 8 or abs(steps_per_cycle - samples) > 1e-6 * steps_per_cycle:
        raise ValueError(
            f"dt = {dt!r} s must divide the period 1/{frequency!r} Hz into a whole number (>= 8) of steps; "
            f"e.g. dt = {1.0 / (frequency * max(round(steps_per_cycle), 8))!r}"
        )

    omega = 2.0 * np.pi * frequency
    time = np.arange(cycles * samples + 1) * dt
    displacement = amplitude * np.sin(omega * time)
    force = damper.force(displacement, dt, method=method)
    require_finite("sine-test force", force)

    last = slice(time.size - 1 - samples, time.size)
    u, F = displacement[last], force[last]
    loop_area = float(np.sum(0.5 * (F[1:] + F[:-1]) * np.diff(u)))
    # One period sampled without its repeated end point: sin and cos are orthogonal there.
    phase = omega * time[last][:-1]
    basis = np.column_stack([amplitude * np.sin(phase), amplitude * np.cos(phase), np.ones_like(phase)])
    (storage, loss, _), *_ = np.linalg.lstsq(basis, F[:-1], rcond=None)
    effective = float((F.max() - F.min()) / (u.max() - u.min()))
    # A damper with no stiffness and no viscosity dissipates nothing: ratio 0, not 0/0.
    damping_ratio = loop_area / (2.0 * np.pi * effective * amplitude**2) if effective > 0.0 else 0.0
    return SineTestResult(damper, amplitude, frequency, dt, cycles, time, displacement, force,
                          loop_area, float(storage), float(loss), effective, float(damping_ratio))
