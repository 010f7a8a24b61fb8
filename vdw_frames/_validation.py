"""Boundary checks shared by the public API: every failure is a ValueError naming the value."""

from __future__ import annotations

import math

import numpy as np


def finite_scalar(name: str, value) -> float:
    """Return ``value`` as a float, or raise ValueError if it is not a finite real number."""
    if np.iscomplexobj(value):
        raise ValueError(f"{name} must be a real number, got {value!r}")
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(number):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return number


def non_negative(name: str, value) -> float:
    """A finite real number >= 0."""
    number = finite_scalar(name, value)
    if number < 0.0:
        raise ValueError(f"{name} must be >= 0, got {value!r}")
    return number


def positive(name: str, value) -> float:
    """A finite real number > 0."""
    number = finite_scalar(name, value)
    if number <= 0.0:
        raise ValueError(f"{name} must be > 0, got {value!r}")
    return number


def finite_array(name: str, values, ndim: int | None = 1) -> np.ndarray:
    """A float64 array with only finite entries (and ``ndim`` dimensions when given)."""
    if np.iscomplexobj(values):
        raise ValueError(f"{name} must be real, got complex values")
    try:
        array = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an array of real numbers") from None
    if ndim is not None and array.ndim != ndim:
        raise ValueError(f"{name} must be {ndim}-dimensional, got shape {array.shape}")
    bad = ~np.isfinite(array)
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        index_text = index[0] if len(index) == 1 else index
        raise ValueError(f"{name} must be finite, got {array[index]!r} at index {index_text}")
    return array


def whole_number(name: str, value, minimum: int) -> int:
    """An integer >= ``minimum`` (bools and non-integral numbers refused)."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer, float, np.floating)):
        raise ValueError(f"{name} must be a whole number >= {minimum}, got {value!r}")
    if not math.isfinite(value) or int(value) != value or value < minimum:
        raise ValueError(f"{name} must be a whole number >= {minimum}, got {value!r}")
    return int(value)


def damping_ratio(value, name: str = "damping_ratio") -> float:
    """A damping ratio in [0, 1)."""
    zeta = finite_scalar(name, value)
    if not 0.0 <= zeta < 1.0:
        raise ValueError(f"{name} must lie in [0, 1), got {value!r}")
    return zeta


def require_finite(name: str, values) -> None:
    """Refuse an overflowed result (inf or NaN) instead of handing it to the user."""
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{name} overflowed (inf or NaN): the inputs or parameters are too large")


def positive_frequencies(name: str, values) -> np.ndarray:
    """Frequencies in Hz: finite and > 0 (scalars become 0-d arrays)."""
    array = finite_array(name, values, ndim=None)
    if (array <= 0.0).any():
        raise ValueError(f"{name} must be > 0 Hz, got {array[array <= 0.0].flat[0]!r}")
    return array
