"""Boundary checks shared by the public API: every failure is a ValueError naming the value.

One rule for numeric arguments: Python and numpy numbers are accepted (arrays where arrays make sense);
bools, strings and complex numbers are refused.  Messages show numbers as plain Python numbers
(``0.01``, never ``np.float64(0.01)``): build them with :func:`show`.
"""

from __future__ import annotations

import math
import numbers

import numpy as np
from numpy.typing import ArrayLike, DTypeLike

MEMORY_LIMIT_BYTES = 2 * 1024**3
"""Largest result (bytes) an analysis may allocate: 2 GiB.  Requests beyond it are refused before any
allocation, with the step count and the memory they would take.  A 200 000-step run of a 10-story frame
needs about 0.2 GiB."""

SIMULATION_STEP_RANGE = (1e-9, 1e3)
"""Time steps (s) :func:`vdw_frames.simulate` accepts: far beyond any seismic analysis either way, and
inside the range where Newmark's coefficients 4/dt^2 and 2/dt are ordinary floats.  The walls' time
stepping (:func:`time_step`) accepts the same range: dt^-r and 1/dt stay ordinary floats in it."""


def show(value: object) -> str:
    """``repr`` of ``value`` with numpy scalars (also inside lists and tuples) shown as the Python
    numbers they hold: ``0.01``, not ``np.float64(0.01)``."""
    return repr(_plain(value))


def _plain(value: object) -> object:
    if isinstance(value, np.generic) or (isinstance(value, np.ndarray) and value.ndim == 0):
        return value.item()
    if isinstance(value, (list, tuple)):
        return type(value)(_plain(item) for item in value) if type(value) in (list, tuple) else value
    return value


def _refuse_non_number(name: str, value: object) -> None:
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise ValueError(f"{name} must be a real number, got {show(value)}")
    # numpy documents iscomplexobj for input "of any type", but its stub narrows it to array-likes.
    if np.iscomplexobj(value):  # type: ignore[arg-type]
        raise ValueError(f"{name} must be a real number, got {show(value)}")


def finite_scalar(name: str, value: object) -> float:
    """Return ``value`` as a float, or raise ValueError if it is not a finite real number.

    Python and numpy numbers (and 0-d arrays) are accepted; bools, strings and complex numbers are not.
    """
    _refuse_non_number(name, value)
    if isinstance(value, np.ndarray):
        if value.ndim != 0 or value.dtype.kind not in "iuf":
            raise ValueError(f"{name} must be a real number, got {show(value)}")
        value = value.item()
    if not isinstance(value, (numbers.Real, np.integer, np.floating)):
        raise ValueError(f"{name} must be a real number, got {show(value)}")
    try:
        number = float(value)
    except OverflowError:
        number = math.inf
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {show(value)}") from None
    if not math.isfinite(number):
        raise ValueError(f"{name} must be finite, got {show(value)}")
    return number


def non_negative(name: str, value: object) -> float:
    """A finite real number >= 0."""
    number = finite_scalar(name, value)
    if number < 0.0:
        raise ValueError(f"{name} must be >= 0, got {show(value)}")
    return number


def positive(name: str, value: object) -> float:
    """A finite real number > 0."""
    number = finite_scalar(name, value)
    if number <= 0.0:
        raise ValueError(f"{name} must be > 0, got {show(value)}")
    return number


def _has_bool_or_text(values: list | tuple) -> bool:
    """Whether a (nested) list or tuple holds a bool or a string (numpy would quietly convert them)."""
    stack = [values]
    while stack:
        items = stack.pop()
        for item in items:
            if isinstance(item, (bool, np.bool_, str, bytes)):
                return True
            if isinstance(item, (list, tuple)):
                stack.append(item)
    return False


def _number_array(name: str, values: ArrayLike, dtype: DTypeLike, kinds: str, what: str) -> np.ndarray:
    """``values`` as an array of ``dtype``; bools and strings (which numpy would convert) refused."""
    if isinstance(values, (bool, np.bool_, str, bytes)) or (
            isinstance(values, (list, tuple)) and _has_bool_or_text(values)):
        raise ValueError(f"{name} must be {what}, got {show(values)}")
    if isinstance(values, np.ndarray) and values.dtype.kind not in kinds:
        raise ValueError(f"{name} must be {what}, got an array of dtype {values.dtype}")
    try:
        return np.asarray(values, dtype=dtype)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{name} must be {what}") from None


def finite_array(name: str, values: ArrayLike, ndim: int | None = 1) -> np.ndarray:
    """A float64 array with only finite entries (and ``ndim`` dimensions when given).

    Numbers, sequences of numbers and numeric numpy arrays are accepted; bools, strings and complex
    values are refused.
    """
    if np.iscomplexobj(values):
        raise ValueError(f"{name} must be real, got complex values")
    array = _number_array(name, values, float, "iuf", "real numbers")
    if ndim is not None and array.ndim != ndim:
        raise ValueError(f"{name} must be {ndim}-dimensional, got shape {array.shape}")
    bad = ~np.isfinite(array)
    if bad.any() and array.ndim == 0:
        raise ValueError(f"{name} must be finite, got {show(array)}")
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        index_text = index[0] if len(index) == 1 else index
        raise ValueError(f"{name} must be finite, got {show(array[index])} at index {index_text}")
    return array


def finite_complex_array(name: str, values: ArrayLike) -> np.ndarray:
    """A complex128 array (any shape; scalars become 0-d) with only finite entries; bools and strings
    are refused."""
    array = _number_array(name, values, complex, "iufc", "numbers")
    bad = ~np.isfinite(array)
    if bad.any():
        raise ValueError(f"{name} must be finite, got {show(array[bad].flat[0])}")
    return array


def whole_number(name: str, value: object, minimum: int) -> int:
    """An integer >= ``minimum`` (Python or numpy; integral floats accepted; bools refused)."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value.item()
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer, float, np.floating)):
        raise ValueError(f"{name} must be a whole number >= {minimum}, got {show(value)}")
    # (a Python int may be beyond any float: compared as an int, never converted)
    if isinstance(value, (float, np.floating)) and not (math.isfinite(value) and float(value).is_integer()):
        raise ValueError(f"{name} must be a whole number >= {minimum}, got {show(value)}")
    if int(value) < minimum:
        raise ValueError(f"{name} must be a whole number >= {minimum}, got {show(value)}")
    return int(value)


def scaled_value(name: str, value: float, factor: float, factor_name: str = "factor") -> float:
    """``value * factor``, or a ValueError naming the factor when the product overflows."""
    product = value * factor
    if not math.isfinite(product):
        raise ValueError(f"{factor_name} = {show(factor)} makes {name} = {show(value)} x {show(factor)} overflow "
                         "(inf); use a smaller factor")
    return product


def wall_geometry(area: object, thickness: object) -> tuple[float, float]:
    """A wall's (area mm^2, layer thickness mm): both finite and > 0, and area / thickness (the stiffness
    per MPa, mm) a finite number, else a ValueError naming them."""
    area_value, thickness_value = positive("area", area), positive("thickness", thickness)
    if not math.isfinite(area_value / thickness_value):
        raise ValueError(f"area / thickness = {show(area)} mm^2 / {show(thickness)} mm overflows (inf): the wall's "
                         "stiffness per MPa is beyond any float; use a thicker layer or a smaller area")
    return area_value, thickness_value


def fractional_order(value: object, name: str = "r") -> float:
    """A fractional order r in (0, 1] (r = 1: classical dashpots)."""
    r = finite_scalar(name, value)
    if not 0.0 < r <= 1.0:
        raise ValueError(f"{name} must lie in (0, 1], got {show(value)}")
    return r


def refuse_non_numbers(name: str, values: object) -> None:
    """ValueError when ``values`` (a value or a nested sequence) holds a bool or a string, which numpy would
    quietly convert to numbers."""
    items = np.asarray(values, dtype=object).ravel() if not isinstance(values, (str, bytes)) else [values]
    for item in items:
        if isinstance(item, (bool, np.bool_, str, bytes)):
            raise ValueError(f"{name} must be real numbers, got {show(item)}")


def text(name: str, value: object) -> str:
    """A string (a name, a source, a label): anything else is refused, never converted."""
    if not isinstance(value, str):
        raise ValueError(f"{name} must be a string, got {show(value)}")
    return value


def damping_ratio(value: object, name: str = "damping_ratio") -> float:
    """A damping ratio in [0, 1)."""
    zeta = finite_scalar(name, value)
    if not 0.0 <= zeta < 1.0:
        raise ValueError(f"{name} must lie in [0, 1), got {show(value)}")
    return zeta


def require_finite(name: str, values: ArrayLike) -> None:
    """Refuse an overflowed result (inf or NaN) instead of handing it to the user."""
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{name} overflowed (inf or NaN): the inputs or parameters are too large")


def time_step(value: object, name: str = "dt") -> float:
    """A time step in s: finite, > 0 and within :data:`SIMULATION_STEP_RANGE` (1e-9 ... 1e3 s)."""
    dt = positive(name, value)
    low, high = SIMULATION_STEP_RANGE
    if not low <= dt <= high:
        raise ValueError(f"{name} = {show(value)} s is outside the range of time steps accepted "
                         f"({low:g} ... {high:g} s)")
    return dt


def positive_frequencies(name: str, values: ArrayLike) -> np.ndarray:
    """Frequencies in Hz: finite and > 0 (scalars become 0-d arrays)."""
    array = finite_array(name, values, ndim=None)
    if (array <= 0.0).any():
        raise ValueError(f"{name} must be > 0 Hz, got {show(array[array <= 0.0].flat[0])}")
    return array


def check_memory(what: str, steps: float, bytes_per_step: float, hint: str = "", unit: str = "steps") -> None:
    """Refuse, before allocating, ``steps`` steps (or other ``unit``: grid points, ...) of ``bytes_per_step``
    bytes beyond :data:`MEMORY_LIMIT_BYTES`; the message gives the count and the memory it would take."""
    try:
        count_value = float(steps)
    except OverflowError:  # an int beyond any float
        count_value = math.inf
    needed = count_value * float(bytes_per_step)
    if needed > MEMORY_LIMIT_BYTES:
        advice = f"; {hint}" if hint else ""
        if count_value < 1e15:
            count = f"{steps:,.0f}"
        elif math.isfinite(count_value):
            count = f"{count_value:.3g}"
        elif isinstance(steps, int):
            count = f"about 1e{len(str(abs(steps))) - 1}"
        else:
            count = "over 1e308"
        raise ValueError(f"{what} needs {count} {unit}, whose arrays would take {_size(needed)} "
                         f"(limit {_size(MEMORY_LIMIT_BYTES)}){advice}")


def _size(count: float) -> str:
    if not math.isfinite(count):
        return "more than any memory"
    for unit, scale in (("TiB", 1024.0**4), ("GiB", 1024.0**3), ("MiB", 1024.0**2)):
        if count >= scale:
            return f"{count / scale:.3g} {unit}"
    return f"{count / 1024.0:.3g} KiB"
