"""The seeded synthetic accelerogram generator and the record that ships with the package.

Units: acceleration mm/s^2, time s, frequencies Hz.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from .._validation import check_memory, finite_array, finite_scalar, non_negative, positive, show
from .._validation import damping_ratio as _damping_ratio
from .record import G, GroundMotion
from .spectrum import sdof_history

DEFAULT_RECORD = "synthetic_kt_035g.AT2"
"""File name of the synthetic record shipped as package data (``vdw_frames/motion/data/``)."""


def default_record_path() -> Path:
    """Path of the shipped synthetic record ``synthetic_kt_035g.AT2`` (0.35 g, 25 s at 0.01 s, in g;
    read it with :func:`~vdw_frames.read_at2`).  It is package data, found with ``importlib.resources``."""
    # One name a joinpath: Python 3.10's Traversable takes one (several only from 3.11).
    return Path(str(resources.files(__package__).joinpath("data").joinpath(DEFAULT_RECORD)))


def default_record() -> GroundMotion:
    """The shipped synthetic record as a :class:`GroundMotion` (mm/s^2)."""
    from .readers import read_at2

    return read_at2(default_record_path())


def jennings_envelope(time: ArrayLike, rise_time: float, strong_motion_end: float, decay_rate: float) -> np.ndarray:
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


def _filtered(excitation: np.ndarray, dt: float, frequency: float, damping_ratio: float) -> np.ndarray:
    """Absolute acceleration of an SDOF (``frequency`` Hz, ``damping_ratio``) on a base moving with
    ``excitation`` mm/s^2: -(2 zeta omega u' + omega^2 u)."""
    omega = 2.0 * np.pi * frequency
    u, v = sdof_history(-excitation, dt, omega, damping_ratio)
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
    s; more than the 2 GiB memory limit would take is refused before allocating).  The white noise is
    ``numpy.random.default_rng(seed).standard_normal``, taken as linear between samples, and the filters
    are integrated exactly (the recurrence of :func:`response_spectrum`).
    """
    duration = positive("duration", duration)
    dt = positive("dt", dt)
    pga = positive("pga", pga)
    if duration < dt:
        raise ValueError(f"duration = {duration!r} s must be at least one step dt = {dt!r} s")
    for label, value in (("ground_frequency", ground_frequency), ("high_pass_frequency", high_pass_frequency)):
        if non_negative(label, value) >= 0.5 / dt:
            raise ValueError(f"{label} = {show(value)} Hz must be below the Nyquist frequency {0.5 / dt!r} Hz")
    positive("ground_frequency", ground_frequency)
    samples = round(duration / dt) + 1
    check_memory(f"synthetic_ground_motion(duration = {duration!r} s, dt = {dt!r} s)", samples, 64,
                 "use a larger dt or a shorter duration")
    noise = np.random.default_rng(seed).standard_normal(samples)
    acceleration = _filtered(noise, dt, ground_frequency, _damping_ratio(ground_damping, "ground_damping"))
    if high_pass_frequency > 0.0:
        damping = _damping_ratio(high_pass_damping, "high_pass_damping")
        filtered = _filtered(acceleration, dt, high_pass_frequency, damping)
        acceleration = filtered - acceleration  # the high-pass oscillator's relative acceleration
    acceleration = acceleration * jennings_envelope(np.arange(samples) * dt, rise_time, strong_motion_end,
                                                    decay_rate)
    return GroundMotion(acceleration, dt, name).scaled_to_pga(pga)
