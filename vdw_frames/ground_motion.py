"""Ground motions: the record class, PEER AT2 and two-column readers, scaling, resampling, linear
elastic response spectra, and the seeded synthetic generator of the record that ships in
``ground_motions/``.

Units: acceleration mm/s^2, time and time step s, periods s, frequencies Hz.  Files in g are
converted with :data:`G` = 9806.65 mm/s^2 per g.  Every value leaving this module is finite: bad input
is a ValueError naming the value (and, for files, the file and the line).
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numba import njit

from ._validation import damping_ratio as _damping_ratio
from ._validation import finite_array, finite_scalar, non_negative, positive

G = 9806.65
"""Standard gravity, mm/s^2 per g."""

DEFAULT_RECORD = "synthetic_kt_035g.AT2"
"""File name of the record shipped in ``<repository>/ground_motions/``."""

STEP_TOLERANCE = 1e-9
"""Relative tolerance within which a requested time step must divide the record step."""

TWO_COLUMN_TOLERANCE = 1e-6
"""Two-column files: each time must lie within this fraction of dt of t0 + i dt."""

UNITS = {"g": G, "mm/s2": 1.0, "cm/s2": 10.0, "m/s2": 1000.0}
"""Acceleration units accepted by :func:`read_two_column`, with their factor to mm/s^2."""

AT2_HEADER_LINES = 10  # the NPTS/DT line must be among the first 10 non-blank lines
_NPTS = re.compile(r"\bNPTS\s*=\s*([^\s,]*)", re.IGNORECASE)
_DT = re.compile(r"\bDT\s*=\s*([^\s,]*)", re.IGNORECASE)
_NEWLINE = re.compile(r"\r*\n|\r")  # "\n", "\r\n", "\r\r\n" and a lone "\r" all end one line


@dataclass(frozen=True, eq=False)
class GroundMotion:
    """A uniformly sampled ground acceleration record.

    ``acceleration`` mm/s^2 (1-D, finite, non-empty; stored as a read-only copy), ``dt`` s (> 0),
    ``name`` a label (file stem for records read from files).  Sample ``i`` is at time ``i * dt``.
    """

    acceleration: np.ndarray
    dt: float
    name: str = ""

    def __post_init__(self):
        acceleration = finite_array("acceleration", self.acceleration).copy()
        if acceleration.size < 2:
            raise ValueError(f"acceleration must hold at least 2 samples, got {acceleration.size}")
        acceleration.flags.writeable = False
        if not isinstance(self.name, str):
            raise ValueError(f"name must be a string, got {self.name!r}")
        object.__setattr__(self, "acceleration", acceleration)
        object.__setattr__(self, "dt", positive("dt", self.dt))

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
        """A new record with acceleration x ``factor`` (dimensionless, finite); dt and name kept."""
        factor = finite_scalar("factor", factor)
        return GroundMotion(self.acceleration * factor, self.dt, self.name)

    def scale_factor_to_pga(self, target: float) -> float:
        """The factor (dimensionless) that brings the PGA to ``target`` mm/s^2 (> 0)."""
        target = positive("target PGA", target)
        return target / self._nonzero("PGA", self.pga)

    def scaled_to_pga(self, target: float) -> GroundMotion:
        """A new record scaled so that its PGA is ``target`` mm/s^2 (> 0)."""
        return self.scaled(self.scale_factor_to_pga(target))

    def scale_factor_to_spectral_acceleration(self, target: float, period: float,
                                              damping_ratio: float = 0.05) -> float:
        """The factor (dimensionless) that brings the pseudo-acceleration Sa(``period`` s,
        ``damping_ratio``) of :func:`response_spectrum` to ``target`` mm/s^2 (> 0)."""
        target = positive("target spectral acceleration", target)
        period = non_negative("period", period)
        spectral = float(response_spectrum(self, period, damping_ratio))
        return target / self._nonzero(f"Sa(T = {period!r} s)", spectral)

    def scaled_to_spectral_acceleration(self, target: float, period: float,
                                        damping_ratio: float = 0.05) -> GroundMotion:
        """A new record scaled so that Sa(``period`` s, ``damping_ratio``) is ``target`` mm/s^2."""
        return self.scaled(self.scale_factor_to_spectral_acceleration(target, period, damping_ratio))

    def acceleration_at(self, dt: float) -> np.ndarray:
        """Ground acceleration (mm/s^2, a new array) sampled every ``dt`` s from time 0.

        ``dt`` must be the record step or the record step divided by a whole number (to a relative
        1e-9); in between samples the record is interpolated linearly, and the last sample is the
        record's last (``(n - 1) * m + 1`` values for ``m`` sub-steps).  A larger ``dt``, or one that
        does not divide the record step, is a ValueError naming both steps.
        """
        substeps = self._substeps(dt)
        acceleration = self.acceleration
        if substeps == 1:
            return acceleration.copy()
        fractions = np.arange(substeps) / substeps
        between = acceleration[:-1, None] + np.diff(acceleration)[:, None] * fractions
        return np.concatenate([between.ravel(), acceleration[-1:]])

    def resampled(self, dt: float) -> GroundMotion:
        """The record sampled every ``dt`` s (see :meth:`acceleration_at`); its step is the record step
        divided by the whole number of sub-steps (equal to ``dt`` within 1e-9 relative)."""
        return GroundMotion(self.acceleration_at(dt), self.dt / self._substeps(dt), self.name)

    def _substeps(self, dt) -> int:
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

    def _nonzero(self, what: str, value: float) -> float:
        if value == 0.0:
            raise ValueError(f"cannot scale {self._label}: its {what} is 0")
        return value

    @property
    def _label(self) -> str:
        return f"ground motion {self.name!r}" if self.name else "the ground motion"


# --------------------------------------------------------------------------------------------------
# Linear SDOF response: the exact recurrence for piecewise-linear excitation (Nigam & Jennings 1969)


@njit(cache=True)
def _sdof_history(load, dt, omega, zeta):
    """Relative displacement u and velocity v of u'' + 2 zeta omega u' + omega^2 u = load(t), from rest,
    with ``load`` (per unit mass) linear between samples: exact at the samples.

    The coefficients are Nigam & Jennings' (1969), as tabulated by Chopra, *Dynamics of Structures*,
    Table 5.2.1, with k = omega^2 and m = 1.
    """
    root = math.sqrt(1.0 - zeta * zeta)
    damped = omega * root
    decay = math.exp(-zeta * omega * dt)
    sine = decay * math.sin(damped * dt)
    cosine = decay * math.cos(damped * dt)
    stiffness = omega * omega
    ratio = zeta / root
    a = ratio * sine + cosine
    b = sine / damped
    c = (2.0 * zeta / (omega * dt) + ((1.0 - 2.0 * zeta * zeta) / (damped * dt) - ratio) * sine
         - (1.0 + 2.0 * zeta / (omega * dt)) * cosine) / stiffness
    d = (1.0 - 2.0 * zeta / (omega * dt) + (2.0 * zeta * zeta - 1.0) / (damped * dt) * sine
         + 2.0 * zeta / (omega * dt) * cosine) / stiffness
    a_dot = -omega / root * sine
    b_dot = cosine - ratio * sine
    c_dot = (-1.0 / dt + (omega / root + ratio / dt) * sine + cosine / dt) / stiffness
    d_dot = (1.0 - ratio * sine - cosine) / (stiffness * dt)
    n = load.size
    u = np.zeros(n)
    v = np.zeros(n)
    for i in range(n - 1):
        u[i + 1] = a * u[i] + b * v[i] + c * load[i] + d * load[i + 1]
        v[i + 1] = a_dot * u[i] + b_dot * v[i] + c_dot * load[i] + d_dot * load[i + 1]
    return u, v


@njit(cache=True)
def _peak_displacements(acceleration, dt, omegas, zeta):
    """max |u| (mm) of the SDOF oscillators ``omegas`` (rad/s, > 0) under ground ``acceleration``."""
    load = -acceleration
    peaks = np.empty(omegas.size)
    for j in range(omegas.size):
        u, _ = _sdof_history(load, dt, omegas[j], zeta)
        peaks[j] = np.max(np.abs(u))
    return peaks


def response_spectrum(ground_motion: GroundMotion, periods, damping_ratio: float = 0.05) -> np.ndarray:
    """Linear elastic pseudo-acceleration spectrum Sa = omega^2 max|u|, mm/s^2, of ``ground_motion``.

    ``periods`` s (scalar or array, finite, >= 0; the result has the same shape); period 0 gives the
    PGA.  ``damping_ratio`` (fraction of critical) in [0, 1).  Each oscillator starts from rest and is
    integrated by the exact recurrence for an excitation linear between samples (Nigam & Jennings 1969);
    the peak is taken at the record's samples (for periods below ~10 dt the true peak between samples
    can be a little larger).
    """
    if not isinstance(ground_motion, GroundMotion):
        raise ValueError(f"ground_motion must be a GroundMotion, got {type(ground_motion).__name__}")
    periods = finite_array("periods", periods, ndim=None)
    if (periods < 0.0).any():
        raise ValueError(f"periods must be >= 0 s, got {periods[periods < 0.0].flat[0]!r}")
    zeta = _damping_ratio(damping_ratio)
    spectrum = np.full(periods.shape, ground_motion.pga)
    positive_periods = periods > 0.0
    omegas = 2.0 * np.pi / periods[positive_periods]
    peaks = _peak_displacements(ground_motion.acceleration, ground_motion.dt, omegas, zeta)
    spectrum[positive_periods] = omegas**2 * peaks
    return spectrum


# --------------------------------------------------------------------------------------------------
# Files


def _lines(path: Path) -> list[str]:
    return _NEWLINE.split(path.read_text(encoding="utf-8", errors="replace"))


def _floats(tokens: list[str], line_numbers: list[int], source: Path) -> np.ndarray:
    """``tokens`` as floats; a non-numeric or non-finite token is a ValueError naming file and line."""
    try:
        values = np.array(tokens, dtype=float)
    except ValueError:
        values = np.array([_float(token, line, source) for token, line in zip(tokens, line_numbers)])
    bad = ~np.isfinite(values)
    if bad.any():
        index = int(np.argmax(bad))
        raise ValueError(f"{source}: non-finite value {tokens[index]!r} on line {line_numbers[index]}")
    return values


def _float(token: str, line: int, source: Path) -> float:
    try:
        return float(token)
    except ValueError:
        raise ValueError(f"{source}: non-numeric value {token!r} on line {line}") from None


def read_at2(path) -> GroundMotion:
    """Read a PEER ``.AT2`` acceleration file (values in g) into a :class:`GroundMotion` (mm/s^2, s).

    The header is free text; the first line (among the first 10 non-blank ones) holding ``NPTS=`` is
    the count line, e.g. ``NPTS=  4000, DT= .01000 SEC`` or NGA-West2's ``NPTS=   5590, DT=   .0050
    SEC`` (spaces, trailing commas and lower-case keys accepted; DT in s).  The values, any number a
    line, follow that line.  Line ends "\\n", "\\r\\n", "\\r\\r\\n" and "\\r" are accepted.  ValueError,
    naming the file, for an empty file, a missing or bad NPTS or DT, fewer or more values than NPTS, or a
    non-numeric or non-finite value.  The record's name is the file stem.
    """
    path = Path(path)
    lines = _lines(path)
    numbered = [(number, line) for number, line in enumerate(lines, start=1) if line.strip()]
    if not numbered:
        raise ValueError(f"{path}: empty file")
    header = None
    for index, (number, line) in enumerate(numbered[:AT2_HEADER_LINES]):
        if _NPTS.search(line):
            header = index
            break
    if header is None:
        raise ValueError(f"{path}: missing NPTS (no 'NPTS=' in the first {AT2_HEADER_LINES} lines)")
    count_line_number, count_line = numbered[header]
    npts = _npts(_NPTS.search(count_line).group(1), path)
    dt = _dt(count_line, [line for _, line in numbered[:header]], path)
    tokens, line_numbers = [], []
    for number, line in numbered[header + 1:]:
        words = line.split()
        tokens.extend(words)
        line_numbers.extend([number] * len(words))
    values = _floats(tokens, line_numbers, path)
    if values.size < npts:
        raise ValueError(f"{path}: too few values: NPTS = {npts} on line {count_line_number} but "
                         f"{values.size} values follow")
    if values.size > npts:
        raise ValueError(f"{path}: too many values: NPTS = {npts} on line {count_line_number} but "
                         f"{values.size} values follow")
    return GroundMotion(values * G, dt, path.stem)


def _npts(text: str, path: Path) -> int:
    if not re.fullmatch(r"[0-9]+", text) or int(text) == 0:
        raise ValueError(f"{path}: NPTS must be a positive whole number, got {text!r}")
    return int(text)


def _dt(count_line: str, other_header_lines: list[str], path: Path) -> float:
    for line in [count_line, *other_header_lines]:
        match = _DT.search(line)
        if match:
            try:
                dt = float(match.group(1))
            except ValueError:
                dt = math.nan
            if not (math.isfinite(dt) and dt > 0.0):
                raise ValueError(f"{path}: DT must be a positive number of seconds, got {match.group(1)!r}")
            return dt
    raise ValueError(f"{path}: missing DT (no 'DT=' next to NPTS)")


def read_two_column(path, unit: str = "g", *, skip_rows: int = 0, name: str | None = None) -> GroundMotion:
    """Read a (time s, acceleration ``unit``) text file into a :class:`GroundMotion` (mm/s^2, s).

    ``unit`` is one of ``"g"``, ``"mm/s2"``, ``"cm/s2"``, ``"m/s2"``.  Columns are separated by
    whitespace and/or commas; ``#`` starts a comment; blank lines are skipped, and so are the first
    ``skip_rows`` lines (e.g. a column-title line).  Every other line must hold exactly two finite
    numbers.  Times must increase uniformly: each within 1e-6 dt of ``t0 + i dt`` (dt the mean step),
    else a ValueError naming the line.  The record starts at the first row (times are shifted to start
    at 0).  ``name`` defaults to the file stem.
    """
    if unit not in UNITS:
        raise ValueError(f"unknown unit {unit!r}; use one of {', '.join(map(repr, UNITS))}")
    path = Path(path)
    if not isinstance(skip_rows, int) or skip_rows < 0:
        raise ValueError(f"skip_rows must be a whole number >= 0, got {skip_rows!r}")
    tokens, line_numbers = [], []
    for number, line in enumerate(_lines(path)[skip_rows:], start=skip_rows + 1):
        words = re.split(r"[\s,]+", line.split("#", 1)[0].strip())
        if words == [""]:
            continue
        if len(words) != 2:
            raise ValueError(f"{path}: line {number} has {len(words)} values, expected 2 (time, acceleration)")
        tokens.extend(words)
        line_numbers.extend([number, number])
    rows = _floats(tokens, line_numbers, path).reshape(-1, 2)
    if rows.shape[0] < 2:
        raise ValueError(f"{path}: needs at least 2 rows (time, acceleration), found {rows.shape[0]}")
    time = rows[:, 0]
    dt = (time[-1] - time[0]) / (time.size - 1)
    if not dt > 0.0:
        raise ValueError(f"{path}: times must increase, got {time[0]!r} s to {time[-1]!r} s")
    off = np.abs(time - time[0] - np.arange(time.size) * dt) > TWO_COLUMN_TOLERANCE * dt
    if off.any():
        row = int(np.argmax(off))
        raise ValueError(f"{path}: non-uniform time step at line {line_numbers[2 * row]}: t = {time[row]!r} s, "
                         f"expected {time[0] + row * dt!r} s for a step of {dt!r} s")
    return GroundMotion(rows[:, 1] * UNITS[unit], dt, path.stem if name is None else name)


def write_at2(motion: GroundMotion, path, header: str | Sequence[str] = ()) -> Path:
    """Write ``motion`` (mm/s^2) as a PEER-layout ``.AT2`` file in g; returns the path.

    Layout: up to two free-text ``header`` lines (padded with the record's name), then ``ACCELERATION
    TIME HISTORY IN UNITS OF G``, then ``NPTS= n, DT= dt SEC`` (the 4th line, dt s written exactly),
    then the values, 5 a line, to 8 significant digits (so a read-back differs by < 5e-8 relative).
    """
    if not isinstance(motion, GroundMotion):
        raise ValueError(f"motion must be a GroundMotion, got {type(motion).__name__}")
    lines = header.splitlines() if isinstance(header, str) else [str(line) for line in header]
    if len(lines) > 2 or any("\n" in line or "\r" in line for line in lines):
        raise ValueError(f"header must be at most 2 single lines, got {header!r}")
    for line in lines:
        if _NPTS.search(line) or _DT.search(line):
            raise ValueError(f"header lines must not contain 'NPTS=' or 'DT=', got {line!r}")
    lines = (lines + [f"GROUND MOTION {motion.name or 'RECORD'}", ""])[:2]
    values = motion.acceleration / G
    rows = [" ".join(f"{value:15.7E}" for value in values[i:i + 5]) for i in range(0, values.size, 5)]
    text = "\n".join([*lines, "ACCELERATION TIME HISTORY IN UNITS OF G",
                      f"NPTS= {values.size:6d}, DT= {motion.dt!r} SEC", *rows]) + "\n"
    path = Path(path)
    path.write_text(text, encoding="ascii")
    return path


def repository_dir() -> Path:
    """The directory holding the ``vdw_frames`` package (the repository root in a checkout or an
    editable install)."""
    return Path(__file__).resolve().parent.parent


def default_record_path() -> Path:
    """Path of the shipped synthetic record ``<repository>/ground_motions/synthetic_kt_035g.AT2`` (in g,
    read it with :func:`read_at2`).  FileNotFoundError, naming where it looked, when the package is
    installed without its repository (the file is not package data)."""
    path = repository_dir() / "ground_motions" / DEFAULT_RECORD
    if not path.is_file():
        raise FileNotFoundError(f"the default ground motion is not at {path}: it ships with the repository's "
                                "ground_motions/ folder, next to the vdw_frames package")
    return path


def shared_records_dir() -> Path | None:
    """``<repository>/../shared/ground_motions`` (recorded accelerograms, .AT2 in g) as a Path, or None
    when that folder is absent (e.g. a fresh clone)."""
    path = repository_dir().parent / "shared" / "ground_motions"
    return path if path.is_dir() else None


# --------------------------------------------------------------------------------------------------
# Synthetic records


def jennings_envelope(time, rise_time: float, strong_motion_end: float, decay_rate: float) -> np.ndarray:
    """The Jennings, Housner & Tsai (1968) envelope (dimensionless, peak 1) at ``time`` s:
    (t / rise_time)^2 up to ``rise_time`` s, 1 up to ``strong_motion_end`` s, then
    exp(-``decay_rate`` (t - strong_motion_end)) with ``decay_rate`` 1/s (>= 0)."""
    time = finite_array("time", time, ndim=None)
    rise_time = positive("rise_time", rise_time)
    strong_motion_end = finite_scalar("strong_motion_end", strong_motion_end)
    if strong_motion_end < rise_time:
        raise ValueError(f"strong_motion_end = {strong_motion_end!r} s must be >= rise_time = {rise_time!r} s")
    decay_rate = non_negative("decay_rate", decay_rate)
    rising = np.clip(time / rise_time, 0.0, 1.0) ** 2
    return rising * np.exp(-decay_rate * np.clip(time - strong_motion_end, 0.0, None))


def _filtered(excitation, dt, frequency, damping_ratio):
    """Absolute acceleration of an SDOF (``frequency`` Hz, ``damping_ratio``) on a base moving with
    ``excitation`` mm/s^2: -(2 zeta omega u' + omega^2 u)."""
    omega = 2.0 * np.pi * frequency
    u, v = _sdof_history(-excitation, dt, omega, damping_ratio)
    return -(2.0 * damping_ratio * omega * v + omega**2 * u)


def synthetic_ground_motion(duration: float = 25.0, dt: float = 0.01, pga: float = 0.35 * G, seed: int = 1940,
                           *, ground_frequency: float = 2.5, ground_damping: float = 0.6,
                           high_pass_frequency: float = 0.25, high_pass_damping: float = 0.6,
                           rise_time: float = 2.0, strong_motion_end: float = 10.0, decay_rate: float = 0.2,
                           name: str = "synthetic") -> GroundMotion:
    """A seeded, reproducible synthetic accelerogram (mm/s^2): Clough-Penzien filtered white noise
    (a Kanai-Tajimi ground filter, ``ground_frequency`` Hz and ``ground_damping``, followed by a
    high-pass filter, ``high_pass_frequency`` Hz (0 to omit it) and ``high_pass_damping``, that removes
    the Kanai-Tajimi spectrum's drift at zero frequency), multiplied by :func:`jennings_envelope`
    (``rise_time`` s, ``strong_motion_end`` s, ``decay_rate`` 1/s) and scaled to ``pga`` mm/s^2.

    ``duration`` s is the time of the last sample (``round(duration / dt) + 1`` samples every ``dt``
    s).  The white noise is ``numpy.random.default_rng(seed).standard_normal``, taken as linear between
    samples, and the filters are integrated exactly (the recurrence of :func:`response_spectrum`).
    """
    duration = positive("duration", duration)
    dt = positive("dt", dt)
    pga = positive("pga", pga)
    if duration < dt:
        raise ValueError(f"duration = {duration!r} s must be at least one step dt = {dt!r} s")
    for label, value in (("ground_frequency", ground_frequency), ("high_pass_frequency", high_pass_frequency)):
        if non_negative(label, value) >= 0.5 / dt:
            raise ValueError(f"{label} = {value!r} Hz must be below the Nyquist frequency {0.5 / dt!r} Hz")
    positive("ground_frequency", ground_frequency)
    samples = round(duration / dt) + 1
    noise = np.random.default_rng(seed).standard_normal(samples)
    acceleration = _filtered(noise, dt, ground_frequency, _damping_ratio(ground_damping, "ground_damping"))
    if high_pass_frequency > 0.0:
        filtered = _filtered(acceleration, dt, high_pass_frequency, _damping_ratio(high_pass_damping, "high_pass_damping"))
        acceleration = filtered - acceleration  # the high-pass oscillator's relative acceleration
    acceleration = acceleration * jennings_envelope(np.arange(samples) * dt, rise_time, strong_motion_end,
                                                    decay_rate)
    return GroundMotion(acceleration, dt, name).scaled_to_pga(pga)
