"""The sinusoidal test of a damper alone (the paper's Section 3.1 loops and Table 5 areas).

Transients: the displacement U sin(omega t) starts from rest, and a fractional element forgets its start
only as a power law, not exponentially.  Measured with the default discretisation and 200 steps per
cycle, for r = 0.1 ... 1 at 0.5 and 10 Hz (Table 4's parameters among them), the loop area of the n-th
cycle differs from the steady value pi K'' U^2 by up to 10 % (n = 1; 15 % for the recommended 225 %
set at 0.5 Hz), 1.1 % (n = 2), 0.2 % (n = 3) and 0.07 % from n = 5 on; what remains after ten cycles
(<= 0.05 %, worst for a classical Maxwell branch at 10 Hz, whose loss modulus is small) is the
discretisation, not the transient.  The default ``cycles=5`` therefore gives the steady loop to 0.1 %;
``tests/element/test_sine.py::test_last_loop_is_steady`` asserts this bound.

Walls only (FDMK walls, with or without a support), driven along the wall: the paper's material test.  The
other devices (fluid viscous, friction) are driven by :func:`vdw_frames.element.devices.device_response`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _warnings
from .._validation import SIMULATION_STEP_RANGE, check_memory, positive, time_step, whole_number
from .damper import FDMKDamper, driven_force
from .fractional import DEFAULT_METHOD, Discretisation, get_method
from .supported import WALL_TYPES, SupportedDamper

MIN_AMPLITUDE = 1e-100  # mm: far below any test; near 1e-308 the samples and forces lose their digits (subnormal)
SAMPLES_PER_CYCLE = 200  # omega*dt = 0.031: the default method's error r (omega dt)^2 / 6 <= 1.6e-4
MIN_SAMPLES_PER_CYCLE = 8
_BYTES_PER_STEP = 64  # time, displacement, force and the element's work arrays


@dataclass(frozen=True)
class SineTestResult:
    """Result of :func:`sine_test`.  Arrays cover the whole test; scalars are from the last full cycle.

    time (s), displacement (mm), force (N); loop_area (N*mm, energy dissipated in the last cycle);
    storage_stiffness and loss_stiffness (N/mm, least-squares fit F ~ K' u + (K''/omega) du/dt + c on the
    last cycle); effective_stiffness (N/mm, peak-to-peak force / peak-to-peak displacement);
    equivalent_damping_ratio (-, W_D / (2 pi K_eff U^2)); ``strain_amplitude`` (-, 3.0 = 300 %): the wall's own
    shear strain amplitude, U / thickness (with a support, the wall's steady share U |k_s / (k_s + K*(f))|).
    ``dt`` is the step used (s) and ``requested_dt`` the one asked for (None for the default): when the asked
    step does not divide the period into a whole number of steps, the nearest one that does is used, and the
    two differ.
    """

    damper: FDMKDamper | SupportedDamper
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
    requested_dt: float | None = None
    strain_amplitude: float | None = None

    @property
    def last_cycle(self) -> slice:
        """Slice of the arrays covering the last full cycle (both end points included)."""
        samples = round(1.0 / (self.frequency * self.dt))
        return slice(self.time.size - 1 - samples, self.time.size)


def sine_test(damper: FDMKDamper | SupportedDamper, amplitude: float, frequency: float, dt: float | None = None,
              cycles: int = 5, method: str | Discretisation = DEFAULT_METHOD) -> SineTestResult:
    """Drive ``damper`` with u(t) = amplitude * sin(2 pi frequency t) from rest for ``cycles`` cycles.

    amplitude in mm (at least MIN_AMPLITUDE, 1e-100), frequency in Hz, dt in s (default: 200 samples per
    cycle).  The period is sampled by a whole number (>= 8) of steps: a ``dt`` that does not divide it is
    replaced by the nearest step that does (``result.dt``; ``result.requested_dt`` keeps the one asked for).
    A test whose arrays would exceed the 2 GiB memory limit is refused before allocating; one whose force or
    loop overflows (absurd amplitudes) is a ValueError naming the amplitude and frequency.  Returns a
    :class:`SineTestResult` (N, mm, N*mm, N/mm).

    A ``UserWarning`` when the wall's strain amplitude (its own deformation amplitude / thickness: with a support,
    the wall's steady share of U) lies outside the damper's ``strain_range``, the strains its parameters were
    identified at: the loop is then an extrapolation of the model (as ``simulate`` warns).
    """
    if not isinstance(damper, WALL_TYPES):
        raise ValueError(f"damper must be an FDMKDamper or a SupportedDamper, got {type(damper).__name__}")
    amplitude = positive("amplitude", amplitude)
    if amplitude < MIN_AMPLITUDE:
        raise ValueError(f"amplitude = {amplitude!r} mm is below {MIN_AMPLITUDE:g} mm, where floating point loses the "
                         "test's displacements and forces (the results would be zeros)")
    frequency = positive("frequency", frequency)
    requested_dt = None if dt is None else time_step(dt)
    cycles = whole_number("cycles", cycles, 1)
    method = get_method(method)
    samples, dt = _steps_per_cycle(frequency, requested_dt, cycles)
    steps = cycles * samples + 1

    omega = 2.0 * np.pi * frequency
    time = np.arange(steps) * dt
    displacement = amplitude * np.sin(omega * time)
    overflow = (f"the sine test overflowed (inf or NaN) at amplitude = {amplitude!r} mm, frequency = "
                f"{frequency!r} Hz: the amplitude or the damper's parameters are too large")
    try:
        force = driven_force(damper, displacement, dt, method)  # its strain range is checked below, as a test's
    except ValueError:  # the force overflowed
        raise ValueError(overflow) from None
    last = slice(time.size - 1 - samples, time.size)
    u, F = displacement[last], force[last]
    with np.errstate(over="ignore", invalid="ignore"):
        loop_area = np.sum(0.5 * (F[1:] + F[:-1]) * np.diff(u))
        # One period sampled without its repeated end point: sin and cos are orthogonal there.
        phase = omega * time[last][:-1]
        basis = np.column_stack([np.sin(phase), np.cos(phase), np.ones_like(phase)])
        (storage, loss, _), *_ = np.linalg.lstsq(basis, F[:-1] / amplitude, rcond=None)
        effective = (F.max() - F.min()) / (u.max() - u.min())
        # A damper with no stiffness and no viscosity dissipates nothing: ratio 0, not 0/0.  The loop is taken per
        # unit amplitude squared, so that a tiny amplitude's area (F u, below 1e-308 N*mm) does not underflow to 0/0.
        unit_loop = np.sum(0.5 * (F[1:] + F[:-1]) / amplitude * (np.diff(u) / amplitude))
        damping_ratio = unit_loop / (2.0 * np.pi * effective) if effective > 0.0 else 0.0
    if not np.all(np.isfinite([loop_area, storage, loss, effective, damping_ratio])):
        raise ValueError(overflow)
    strain = _strain_amplitude(damper, amplitude, frequency)
    _warn_outside_identified(damper, strain)
    return SineTestResult(damper, amplitude, frequency, dt, cycles, time, displacement, force,
                          float(loop_area), float(storage), float(loss), float(effective), float(damping_ratio),
                          requested_dt, strain)


def _strain_amplitude(damper: FDMKDamper | SupportedDamper, amplitude: float, frequency: float) -> float:
    """The wall's own steady strain amplitude (-): U / thickness; in series with a support of stiffness k_s the
    wall deforms by U k_s / (k_s + K*(f)) (the two carry one force)."""
    if isinstance(damper, SupportedDamper):
        wall = complex(damper.damper.complex_stiffness(frequency))
        amplitude = amplitude * abs(damper.support_stiffness / (damper.support_stiffness + wall))
    return float(amplitude / damper.thickness)


def _warn_outside_identified(damper: FDMKDamper | SupportedDamper, strain: float) -> None:
    """Warn when ``strain`` (-) lies outside the damper's ``strain_range`` (its parameters' tested strains)."""
    if damper.strain_range is None:
        return
    low, high = damper.strain_range
    if low <= strain <= high:
        return
    side = "above" if strain > high else "below"
    _warnings.warn(f"sine_test: the wall's strain amplitude {100 * strain:.4g} % lies {side} the range its parameters "
                   f"were identified for ({100 * low:.4g}-{100 * high:.4g} %): the loop, stiffnesses and damping "
                   "ratio extrapolate the model there", UserWarning, stacklevel=3)


def _steps_per_cycle(frequency: float, dt: float | None, cycles: int) -> tuple[int, float]:
    """(steps a cycle, step in s): the default 200 steps, or the whole number nearest 1/(frequency dt)
    with the step that gives exactly that many (dt itself when it divides the period to 1e-9); the
    test's memory is checked before anything is allocated."""
    with np.errstate(over="ignore", divide="ignore"):
        steps_per_cycle = (np.float64(SAMPLES_PER_CYCLE) if dt is None
                           else np.float64(1.0) / (np.float64(frequency) * np.float64(dt)))
    check_memory(f"sine_test({cycles:,} cycles of {steps_per_cycle:,.0f} steps)",
                 cycles * steps_per_cycle + 1, _BYTES_PER_STEP, "use fewer cycles or a larger dt")
    samples = round(float(steps_per_cycle))
    if samples < MIN_SAMPLES_PER_CYCLE:
        raise ValueError(f"dt = {dt!r} s leaves fewer than {MIN_SAMPLES_PER_CYCLE} steps in the period "
                         f"1/{frequency!r} Hz; use dt <= {1.0 / (frequency * MIN_SAMPLES_PER_CYCLE)!r} s")
    if dt is None or abs(steps_per_cycle - samples) > 1e-9 * steps_per_cycle:
        dt = 1.0 / (frequency * samples)
    if not (np.isfinite(dt) and dt > 0.0):
        raise ValueError(f"frequency = {frequency!r} Hz is beyond what a time step can resolve")
    # The walls take steps in SIMULATION_STEP_RANGE only (their force refused any other, which read as an overflow)
    low, high = SIMULATION_STEP_RANGE
    if not low <= dt <= high:
        raise ValueError(f"frequency = {frequency!r} Hz is too {'low' if dt > high else 'high'}: {samples} steps a "
                         f"cycle take dt = {dt:.3g} s, outside the time steps the walls accept ({low:g} ... {high:g} "
                         f"s); at {samples} steps a cycle the frequency must lie in {1.0 / (high * samples):.3g} ... "
                         f"{1.0 / (low * samples):.3g} Hz")
    return samples, dt
