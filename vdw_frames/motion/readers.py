"""Ground-motion files: PEER AT2 and two-column text readers, and an AT2 writer.

Units: files in g (AT2) or the stated unit (two-column) are converted to mm/s^2 with :data:`G`.
Bad files are a ValueError naming the file and, where it applies, the line.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from .record import G, GroundMotion

TWO_COLUMN_TOLERANCE = 1e-6
"""Two-column files: each time must lie within this fraction of dt of t0 + i dt."""

UNITS = {"g": G, "mm/s2": 1.0, "cm/s2": 10.0, "m/s2": 1000.0}
"""Acceleration units accepted by :func:`read_two_column`, with their factor to mm/s^2."""

AT2_HEADER_LINES = 10  # the NPTS/DT line must be among the first 10 non-blank lines
_NPTS = re.compile(r"\bNPTS\s*=\s*([^\s,]*)", re.IGNORECASE)
_DT = re.compile(r"\bDT\s*=\s*([^\s,]*)", re.IGNORECASE)
_NEWLINE = re.compile(r"\r*\n|\r")  # "\n", "\r\n", "\r\r\n" and a lone "\r" all end one line


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
