"""The ground-motion record: a uniformly sampled acceleration history, its scaling and resampling.

Units: acceleration mm/s^2, time and time step s.  Files in g are converted with :data:`G` =
9806.65 mm/s^2 per g.  Every value leaving this sub-package is finite: bad input is a ValueError naming
the value (and, for files, the file and the line).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .. import _warnings
from .._validation import check_memory, finite_array, finite_scalar, non_negative, positive, show, whole_number
from .spectrum import spectral_accelerations

G = 9806.65
"""Standard gravity, mm/s^2 per g."""

STEP_TOLERANCE = 1e-6
"""Relative tolerance within which a requested time step must divide the record step (a float32 step,
e.g. ``np.float32(0.01)``, is within 3e-8 of the float64 one)."""

_RESAMPLING_BYTES_PER_STEP = 24  # the interpolated array, its temporaries and the record's copy

UNIT_SLIP_BELOW = 1.0
"""Target accelerations (mm/s^2) below this warn: 1 mm/s^2 is 1e-4 g, far below any seismic target, and a
target typed in g (0.4 for 0.4 g) lands here."""


def target_acceleration(name: str, target: object, stacklevel: int = 2) -> float:
    """A target acceleration in mm/s^2 (finite, > 0); below :data:`UNIT_SLIP_BELOW` (1 mm/s^2) it warns
    (``UserWarning``), naming the target and what it would be if it was meant in g."""
    value = positive(name, target)
    if value < UNIT_SLIP_BELOW:
        _warnings.warn(f"{name} = {show(target)} mm/s^2 is below {UNIT_SLIP_BELOW:g} mm/s^2 (1e-4 g): targets are in "
                       f"mm/s^2; did you mean {show(target)} g = {value * G:.6g} mm/s^2 (multiply by vdw_frames.G)?",
                       UserWarning, stacklevel=stacklevel + 1)
    return value


@dataclass(frozen=True, eq=False)
class GroundMotion:
    """A uniformly sampled ground acceleration record.

    ``acceleration`` mm/s^2 (1-D, finite, non-empty; stored as a read-only copy), ``dt`` s (> 0),
    ``name`` a label (file stem for records read from files).  Sample ``i`` is at time ``i * dt``.
    ``metadata``: None or a frozen dataclass describing the record (e.g. the FEMA P695 sets'
    :class:`~vdw_frames.motion.p695.RecordMetadata`); scaling and resampling keep it.
    """

    acceleration: np.ndarray
    dt: float
    name: str = ""
    metadata: object = None

    def __post_init__(self) -> None:
        acceleration = finite_array("acceleration", self.acceleration).copy()
        if acceleration.size < 2:
            raise ValueError(f"acceleration must hold at least 2 samples, got {acceleration.size}")
        acceleration.flags.writeable = False
        if not isinstance(self.name, str):
            raise ValueError(f"name must be a string, got {show(self.name)}")
        object.__setattr__(self, "acceleration", acceleration)
        object.__setattr__(self, "dt", positive("dt", self.dt))
        metadata = self.metadata
        params = getattr(type(metadata), "__dataclass_params__", None)  # set on every dataclass
        frozen = params is not None and not isinstance(metadata, type) and bool(params.frozen)
        if metadata is not None and not frozen:
            raise ValueError(f"metadata must be None or a frozen dataclass instance, got {type(metadata).__name__}")

    def __repr__(self) -> str:
        return (f"GroundMotion(name={self.name!r}, points={self.acceleration.size}, dt={self.dt!r} s, "
                f"pga={self.pga / G:.4g} g)")

    @property
    def time(self) -> np.ndarray:
        """Sample times, s: ``0, dt, ..., (n-1) dt``."""
        return np.arange(self.acceleration.size) * self.dt

    @property
    def pga(self) -> float:
        """Peak ground acceleration max |a|, mm/s^2."""
        return float(np.max(np.abs(self.acceleration)))

    @property
    def duration(self) -> float:
        """Time of the last sample, ``(n - 1) * dt``, s (0 for a single sample)."""
        return (self.acceleration.size - 1) * self.dt

    def scaled(self, factor: float) -> GroundMotion:
        """A new record with acceleration x ``factor`` (dimensionless, finite); dt, name and metadata kept."""
        factor = finite_scalar("factor", factor)
        with np.errstate(over="ignore"):
            acceleration = self.acceleration * factor
        if not np.isfinite(acceleration).all():  # named by the factor, not by a sample index
            raise ValueError(f"factor = {show(factor)} makes the acceleration of {self._label} (PGA "
                             f"{show(self.pga)} mm/s^2) overflow (inf); use a smaller factor")
        return GroundMotion(acceleration, self.dt, self.name, self.metadata)

    def scale_factor_to_pga(self, target: float) -> float:
        """The factor (dimensionless) that brings the PGA to ``target`` mm/s^2 (> 0; below 1 mm/s^2 warns:
        see :func:`target_acceleration`)."""
        return self._pga_factor(target, stacklevel=3)

    def scaled_to_pga(self, target: float) -> GroundMotion:
        """A new record scaled so that its PGA is ``target`` mm/s^2 (> 0; below 1 mm/s^2 warns)."""
        return self.scaled(self._pga_factor(target, stacklevel=3))

    def scale_factor_to_spectral_acceleration(self, target: float, period: float,
                                              damping_ratio: float = 0.05) -> float:
        """The factor (dimensionless) that brings the pseudo-acceleration Sa(``period`` s,
        ``damping_ratio``) of :func:`response_spectrum` to ``target`` mm/s^2 (> 0; below 1 mm/s^2 warns:
        see :func:`target_acceleration`)."""
        return self._spectral_factor(target, period, damping_ratio, stacklevel=3)

    def scaled_to_spectral_acceleration(self, target: float, period: float,
                                        damping_ratio: float = 0.05) -> GroundMotion:
        """A new record scaled so that Sa(``period`` s, ``damping_ratio``) is ``target`` mm/s^2 (below
        1 mm/s^2 warns)."""
        return self.scaled(self._spectral_factor(target, period, damping_ratio, stacklevel=3))

    def _pga_factor(self, target: float, stacklevel: int) -> float:
        target = target_acceleration("target PGA", target, stacklevel + 1)
        return target / self._nonzero("PGA", self.pga)

    def _spectral_factor(self, target: float, period: float, damping_ratio: float, stacklevel: int) -> float:
        target = target_acceleration("target spectral acceleration", target, stacklevel + 1)
        period = non_negative("period", period)
        spectral = float(self.spectrum(period, damping_ratio))
        return target / self._nonzero(f"Sa(T = {show(period)} s)", spectral)

    def spectrum(self, periods: ArrayLike, damping_ratio: float = 0.05) -> np.ndarray:
        """Pseudo-acceleration spectrum Sa (mm/s^2) at ``periods`` (s; 0 gives the PGA) and ``damping_ratio``
        (fraction of critical): :func:`vdw_frames.motion.spectrum.response_spectrum` of this record."""
        return spectral_accelerations(self.acceleration, self.dt, periods, damping_ratio)

    def acceleration_at(self, dt: float) -> np.ndarray:
        """Ground acceleration (mm/s^2, a new array) sampled every ``dt`` s from time 0.

        ``dt`` must be the record step or the record step divided by a whole number ``m`` (to a
        relative :data:`STEP_TOLERANCE` = 1e-6); in between samples the record is interpolated
        linearly, and the last sample is the record's last (``(n - 1) * m + 1`` values).  A larger
        ``dt``, or one that does not divide the record step, is a ValueError naming both steps; so is a
        ``dt`` whose samples would exceed the memory limit (``vdw_frames._validation.MEMORY_LIMIT_BYTES``,
        2 GiB), refused before allocating with the number of steps and the memory.
        """
        substeps = self.substeps(dt)
        self._check_memory(f"dt = {dt!r} s", substeps, "use a larger dt")
        return self.interpolated(substeps)

    def interpolated(self, substeps: int) -> np.ndarray:
        """Ground acceleration (mm/s^2, a new array) with ``substeps`` (a whole number from :meth:`substeps`)
        steps in each record step, linear in between: ``(n - 1) * substeps + 1`` values.  A ``substeps`` whose
        values would exceed the memory limit (2 GiB, as for :meth:`acceleration_at`) is a ValueError naming it,
        before allocating."""
        substeps = whole_number("substeps", substeps, 1)
        shown = f"{substeps}" if substeps < 10**15 else f"about 1e{math.floor(math.log10(substeps))}"
        self._check_memory(f"substeps = {shown}", substeps, "use fewer substeps")
        acceleration = self.acceleration
        if substeps == 1:
            return acceleration.copy()
        fractions = np.arange(substeps) / substeps
        between = acceleration[:-1, None] + np.diff(acceleration)[:, None] * fractions
        return np.concatenate([between.ravel(), acceleration[-1:]])

    def resampled(self, dt: float) -> GroundMotion:
        """The record sampled every ``dt`` s (see :meth:`acceleration_at`); its step is the record step
        divided by the whole number of sub-steps (equal to ``dt`` within 1e-6 relative)."""
        substeps = self.substeps(dt)
        self._check_memory(f"dt = {dt!r} s", substeps, "use a larger dt")
        return GroundMotion(self.interpolated(substeps), self.dt / substeps, self.name, self.metadata)

    def substeps(self, dt: float) -> int:
        """The whole number ``m`` of steps of ``dt`` s in one record step (see :meth:`acceleration_at`);
        ValueError for a ``dt`` that is larger or does not divide the record step.  The step to
        integrate with is ``self.dt / m`` (``dt`` within 1e-6 relative)."""
        dt = positive("dt", dt)
        if dt > self.dt * (1.0 + STEP_TOLERANCE):
            raise ValueError(f"time step dt = {dt!r} s is larger than the record step {self.dt!r} s "
                             f"of {self._label}; use the record step or a whole fraction of it")
        ratio = self.dt / dt
        substeps = round(ratio)
        if abs(ratio - substeps) > STEP_TOLERANCE * ratio:
            raise ValueError(f"time step dt = {dt!r} s does not divide the record step {self.dt!r} s "
                             f"of {self._label} (ratio {ratio!r} is not a whole number)")
        return substeps

    def _check_memory(self, what: str, substeps: int, hint: str) -> None:
        """Refuse ``substeps`` steps in each record step beyond the memory limit (``what`` names the request)."""
        check_memory(f"{what} on {self._label} ({self.acceleration.size} samples every {self.dt!r} s)",
                     (self.acceleration.size - 1) * substeps + 1, _RESAMPLING_BYTES_PER_STEP, hint)

    def _nonzero(self, what: str, value: float) -> float:
        if value == 0.0:
            raise ValueError(f"cannot scale {self._label}: its {what} is 0")
        return value

    @property
    def _label(self) -> str:
        return f"ground motion {self.name!r}" if self.name else "the ground motion"
