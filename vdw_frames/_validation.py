"""Boundary checks shared by the public API: every failure is a ValueError naming the value.

One rule for numeric arguments: Python and numpy numbers are accepted (arrays where arrays make sense);
bools, strings and complex numbers are refused.  Messages show numbers as plain Python numbers
(``0.01``, never ``np.float64(0.01)``): build them with :func:`show`.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

MEMORY_LIMIT_BYTES = 2 * 1024**3
"""Largest result (bytes) an analysis may allocate: 2 GiB.  Requests beyond it are refused before any
allocation, with the step count and the memory they would take.  A 200 000-step run of a 10-story frame
needs about 0.2 GiB."""

SIMULATION_STEP_RANGE = (1e-9, 1e3)
"""Time steps (s) :func:`vdw_frames.simulate` accepts: far beyond any seismic analysis either way, and
inside the range where Newmark's coefficients 4/dt^2 and 2/dt are ordinary floats."""


def show(value) -> str:
    """``repr`` of ``value`` with numpy scalars (also inside lists and tuples) shown as the Python
    numbers they hold: ``0.01``, not ``np.float64(0.01)``."""
    return repr(_plain(value))


def _plain(value):
    if isinstance(value, np.generic) or (isinstance(value, np.ndarray) and value.ndim == 0):
        return value.item()
    if isinstance(value, (list, tuple)):
        return type(value)(_plain(item) for item in value) if type(value) in (list, tuple) else value
    return value


def _refuse_non_number(name: str, value) -> None:
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise ValueError(f"{name} must be a real number, got {show(value)}")
    if np.iscomplexobj(value):
        raise ValueError(f"{name} must be a real number, got {show(value)}")


def finite_scalar(name: str, value) -> float:
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


def non_negative(name: str, value) -> float:
    """A finite real number >= 0."""
    number = finite_scalar(name, value)
    if number < 0.0:
        raise ValueError(f"{name} must be >= 0, got {show(value)}")
    return number


def positive(name: str, value) -> float:
    """A finite real number > 0."""
    number = finite_scalar(name, value)
    if number <= 0.0:
        raise ValueError(f"{name} must be > 0, got {show(value)}")
    return number


def _has_bool_or_text(values) -> bool:
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


def _number_array(name: str, values, dtype, kinds: str, what: str) -> np.ndarray:
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


def finite_array(name: str, values, ndim: int | None = 1) -> np.ndarray:
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
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        index_text = index[0] if len(index) == 1 else index
        raise ValueError(f"{name} must be finite, got {show(array[index])} at index {index_text}")
    return array


def finite_complex_array(name: str, values) -> np.ndarray:
    """A complex128 array (any shape; scalars become 0-d) with only finite entries; bools and strings
    are refused."""
    array = _number_array(name, values, complex, "iufc", "numbers")
    bad = ~np.isfinite(array)
    if bad.any():
        raise ValueError(f"{name} must be finite, got {show(array[bad].flat[0])}")
    return array


def whole_number(name: str, value, minimum: int) -> int:
    """An integer >= ``minimum`` (Python or numpy; integral floats accepted; bools refused)."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value.item()
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer, float, np.floating)):
        raise ValueError(f"{name} must be a whole number >= {minimum}, got {show(value)}")
    if not math.isfinite(value) or int(value) != value or value < minimum:
        raise ValueError(f"{name} must be a whole number >= {minimum}, got {show(value)}")
    return int(value)


def damping_ratio(value, name: str = "damping_ratio") -> float:
    """A damping ratio in [0, 1)."""
    zeta = finite_scalar(name, value)
    if not 0.0 <= zeta < 1.0:
        raise ValueError(f"{name} must lie in [0, 1), got {show(value)}")
    return zeta


def require_finite(name: str, values) -> None:
    """Refuse an overflowed result (inf or NaN) instead of handing it to the user."""
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{name} overflowed (inf or NaN): the inputs or parameters are too large")


def positive_frequencies(name: str, values) -> np.ndarray:
    """Frequencies in Hz: finite and > 0 (scalars become 0-d arrays)."""
    array = finite_array(name, values, ndim=None)
    if (array <= 0.0).any():
        raise ValueError(f"{name} must be > 0 Hz, got {show(array[array <= 0.0].flat[0])}")
    return array


def check_memory(what: str, steps: int, bytes_per_step: float, hint: str = "") -> None:
    """Refuse, before allocating, ``steps`` steps of ``bytes_per_step`` bytes beyond
    :data:`MEMORY_LIMIT_BYTES`; the message gives the step count and the memory it would take."""
    needed = float(steps) * float(bytes_per_step)
    if needed > MEMORY_LIMIT_BYTES:
        advice = f"; {hint}" if hint else ""
        raise ValueError(f"{what} needs {steps:,.0f} steps, whose arrays would take {_size(needed)} "
                         f"(limit {_size(MEMORY_LIMIT_BYTES)}){advice}")


def _size(count: float) -> str:
    for unit, scale in (("TiB", 1024.0**4), ("GiB", 1024.0**3), ("MiB", 1024.0**2)):
        if count >= scale:
            return f"{count / scale:.3g} {unit}"
    return f"{count / 1024.0:.3g} KiB"


# ---------------------------------------------------------------------------------------------- files
def file_path(path, what: str = "file"):
    """``path`` (str or os.PathLike) as a :class:`pathlib.Path`; '' and None are refused."""
    import os
    from pathlib import Path

    if isinstance(path, bytes) or not isinstance(path, (str, os.PathLike)):
        raise ValueError(f"{what} must be a path (str or pathlib.Path), got {show(path)}")
    if str(path) == "":
        raise ValueError(f"{what} must be a path, got ''")
    return Path(path)


def read_text(path, what: str = "file", strict: bool = True):
    """(Path, text) of a text file; every failure is a ValueError naming the file.

    A missing file, a folder, an unreadable file, a gzip or zip archive, UTF-16 text and other binary
    data each get a message that says so.  A UTF-8 byte-order mark is dropped.  ``strict``: bytes that
    are not UTF-8 are an error naming the file and the position; otherwise they become U+FFFD (for
    free-text headers, e.g. Latin-1 station names).
    """
    path = file_path(path, what)
    if path.is_dir():
        raise ValueError(f"{path}: is a folder, not a {what}")
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise ValueError(f"{path}: no such {what}") from None
    except OSError as error:
        raise ValueError(f"{path}: cannot read the {what} ({error.strerror or error})") from None
    if data.startswith(b"\x1f\x8b"):
        raise ValueError(f"{path}: a gzip-compressed file; decompress it first (e.g. gunzip)")
    if data.startswith(b"PK\x03\x04"):
        raise ValueError(f"{path}: a zip archive; extract the {what} from it first")
    if data.startswith((b"\xff\xfe", b"\xfe\xff")) or _looks_utf16(data):
        raise ValueError(f"{path}: UTF-16 text; save it as UTF-8 or ASCII")
    nul = data.find(0)
    if nul >= 0:
        raise ValueError(f"{path}: binary data (a NUL byte at position {nul}), not a text {what}")
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        if strict:
            raise ValueError(f"{path}: not UTF-8 text (byte {data[error.start]:#04x} at position "
                             f"{error.start}); save it as UTF-8") from None
        text = data.decode("utf-8", errors="replace")
    return path, text


def _looks_utf16(data: bytes) -> bool:
    # ASCII text in UTF-16 without a byte-order mark: every other byte of the start is NUL.
    head = data[:200]
    return len(head) >= 4 and (head[1::2].count(0) >= len(head) // 2 - 1 or head[0::2].count(0) >= len(head) // 2 - 1)
