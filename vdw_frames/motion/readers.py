"""Ground-motion files: PEER AT2 and two-column text readers, and an AT2 writer.

Units: files in the unit their header states (AT2; g when it states none) or the unit given (two-column)
are converted to mm/s^2 (:data:`UNITS`; g with :data:`G`).
Bad files are a ValueError naming the file and, where it applies, the line; a reader returns a
:class:`GroundMotion` (finite values) or raises ValueError, nothing else.

Real-world variants accepted by both readers: line ends "\\n", "\\r\\n", "\\r\\r\\n" and "\\r"; a UTF-8
byte-order mark; a DOS end-of-file mark (^Z) at the end; Fortran output, i.e. ``D`` exponents
(``1.0D-03``) and fixed-width values written without a separator (``-.39E-02-.33E-02``: each value
has a decimal point or an exponent letter, and each after the first starts with its sign, so a split
is never a guess).  Gzip, zip, UTF-16 and other binary files get a message that says so.
"""

from __future__ import annotations

import os
import re
from collections.abc import Sequence
from itertools import pairwise
from pathlib import Path

import numpy as np

from .._files import file_path, read_text, replace_file
from .._validation import show, whole_number
from .record import G, GroundMotion

TWO_COLUMN_TOLERANCE = 1e-3
"""Two-column files: each time must lie within this fraction of dt of t0 + i dt (float32 time columns,
e.g. 0.09999999 at dt = 0.01, are off by ~1e-6 dt)."""

UNITS = {"g": G, "mm/s2": 1.0, "cm/s2": 10.0, "m/s2": 1000.0, "in/s2": 25.4}
"""Acceleration units read by :func:`read_two_column` and from AT2 headers, with their factor to mm/s^2
(1 in = 25.4 mm exactly).  Spellings are normalised first (:func:`acceleration_unit`): case, ``sec`` for
``s``, ``/s/s``, ``/s^2``, ``/s**2`` and ``/s²`` for ``/s2``, and ``gal`` for ``cm/s2``."""

_OTHER_QUANTITIES = {**dict.fromkeys(("mm/s", "cm/s", "m/s", "in/s"), "velocity"),
                     **dict.fromkeys(("mm", "cm", "m", "in"), "displacement")}
_TIME_UNITS = {**dict.fromkeys(("s", "sec", "secs", "second", "seconds"), 1.0),
               **dict.fromkeys(("ms", "msec", "msecs", "millisecond", "milliseconds"), 1e-3)}
# Time units no record states its step in: after DT they are refused, not taken for other text (read as s).
_OTHER_TIME_UNITS = frozenset(("min", "mins", "minute", "minutes", "h", "hr", "hrs", "hour", "hours", "us",
                               "usec", "microsecond", "microseconds", "ns", "nanosecond", "nanoseconds"))
# An AT2 header's unit statement: "IN UNITS OF G", "UNITS OF CM/S/S.", "The units are (g)", "UNITS: gal".
_UNIT_STATEMENT = re.compile(r"\bUNITS?\s*(?:\b(?:OF|ARE|IS|IN)\b|[:=])\s*[:=]?\s*\(?\s*([^\s,;()]*)", re.IGNORECASE)
# A unit written anywhere in a header line without "UNITS": a length over a time (squared, or over a time
# again), "ACCELERATION IN CM/S/S", "(cm/s2)", "[m/s^2]", "ACCEL. CM/SEC/SEC", "ft/s2" (found, then refused),
# "cm/s" (found, then refused as a velocity); a length times a time to the power -2, "cm s-2", "m·s⁻²"; gal;
# g in brackets or after "IN": "(g)", "[G]", "ACCELERATION IN G".  Dates (09/20/99) and "N/S" are not units.
_LENGTH = r"(?:mm|cm|m|km|in|inch|inches|ft|feet|foot)"
_TIME = r"(?:s|secs?|seconds?)"
_SLASH_UNIT = re.compile(rf"(?<![A-Za-z_/])({_LENGTH}\s*/\s*{_TIME}(?:\s*/\s*{_TIME}|\s*(?:\^|\*\*)?\s*2|\u00b2)?)"
                         r"(?![\w/])", re.IGNORECASE)
_NEGATIVE_POWER_UNIT = re.compile(rf"(?<![A-Za-z_/])({_LENGTH})\s*[\s.*\u00b7]\s*{_TIME}\s*(?:\^|\*\*)?\s*"
                                  r"(?:[-\u2212]\s*2|\u207b\u00b2)(?![\w/])", re.IGNORECASE)
_GAL = re.compile(r"(?<![\w/])(gals?)(?![\w/])", re.IGNORECASE)
# A short word, or a word with a character other than a letter (a ratio, "%g", "milli-g", "g's"), after
# "ACCELERATION IN" or in brackets after "ACCELERATION" is a unit too, even one not read here ("ACCELERATION [mg]",
# "ACCEL. IN FT/S2", "ACCELERATION IN %G"); in brackets, a ratio with a scale before it too ("(10^-2 m/s2)"):
# refused, never read as g (nor as the ratio without its scale).
_MARKED_WORD = r"[^\s()\[\],;]*[^A-Za-z\s()\[\],;][^\s()\[\],;]*"
_UNIT_WORD = rf"(?:[A-Za-z]{{1,4}}|{_MARKED_WORD})"
_BRACKETED_UNIT = rf"(?:[A-Za-z]{{1,4}}|[^()\[\],;]*/[^()\[\],;]*|{_MARKED_WORD})"
_ACCELERATION_UNIT = re.compile(r"\bACCEL(?:ERATIONS?|\.)?\s*(?:(?:TIME\s+)?(?:HISTORY|SERIES)\s*)?"
                                rf"(?:IN\s+(?!UNITS?\b)({_UNIT_WORD})(?![\w/]|\s*/)|[(\[]\s*({_BRACKETED_UNIT})\s*[)\]])",
                                re.IGNORECASE)
_G_PLURAL = re.compile(r"g'?s", re.IGNORECASE)  # "g's", "Gs": g
_G = re.compile(r"[(\[]\s*(g)\s*[)\]]|\bIN\s+(g)\b(?![/-])", re.IGNORECASE)
# A header naming another quantity: "VELOCITY TIME HISTORY", "DISPLACEMENT TIME SERIES".
_OTHER_HISTORY = re.compile(r"\b(VELOCITY|DISPLACEMENT)\s+(?:TIME\s+)?(?:HISTORY|SERIES)\b", re.IGNORECASE)

AT2_HEADER_LINES = 10  # the NPTS/DT line must be among the first 10 non-blank lines
_NPTS = re.compile(r"\bNPTS\s*=\s*([^\s,]*)", re.IGNORECASE)
_DT = re.compile(r"\bDT\s*=\s*([^\s,]*)(?:[ \t]+([A-Za-z]+))?", re.IGNORECASE)
# The legacy PEER (and FEMA P695, NGA-West1) count line: the numbers first, then their labels.
_LEGACY_COUNT = re.compile(r"^\s*([^\s,]+)[\s,]+([^\s,]+)[\s,]+NPTS\s*,?\s*DT\b", re.IGNORECASE)
_NEWLINE = re.compile(r"\r*\n|\r")  # "\n", "\r\n", "\r\r\n" and a lone "\r" all end one line
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:([EeDd])([+-]?)(\d+))?")
_CONTROL = re.compile(r"[\x00-\x1f\x7f]")


def _record_lines(path: str | os.PathLike[str], what: str) -> tuple[Path, list[str]]:
    """The file's lines (a trailing DOS ^Z and blank lines dropped); header bytes that are not UTF-8
    (e.g. a Latin-1 station name) are replaced, since only numbers are read from the file."""
    path, text = read_text(path, what, strict=False)
    text = text.rstrip()
    while text.endswith("\x1a"):
        text = text[:-1].rstrip()
    return path, _NEWLINE.split(text)


def _number_texts(token: str) -> list[str] | None:
    """The Python float texts of one whitespace-free token, or None if it is not numeric.

    A plain number gives itself; Fortran's ``1.0D-03`` gives ``1.0E-03``; values written without a
    separator (``-.39E-02-.33E-02``) give each value, provided each has a decimal point or an exponent
    letter and each after the first starts with its sign.  Anything else is refused rather than guessed
    (``12.34512.345`` has no unique split; ``0.1234-100`` may be Fortran's E-less exponent).
    """
    parts = list(_NUMBER.finditer(token))
    if not parts or parts[0].start() != 0 or any(a.end() != b.start() for a, b in pairwise(parts)) \
            or parts[-1].end() != len(token):
        return None
    if len(parts) > 1 and not all(("." in part.group(0) or part.group(1)) and (k == 0 or part.group(0)[0] in "+-")
                                  for k, part in enumerate(parts)):
        return None
    return [part.group(0).replace("D", "E").replace("d", "e") for part in parts]


def _floats(tokens: list[str], line_numbers: list[int], source: Path) -> tuple[np.ndarray, list[int]]:
    """``tokens`` as floats and the line of each; a non-numeric or non-finite token is a ValueError
    naming file and line."""
    try:
        values = np.array(tokens, dtype=float)
    except ValueError:
        texts, lines = [], []
        for token, line in zip(tokens, line_numbers, strict=True):
            numbers = _number_texts(token)
            if numbers is None:
                raise ValueError(f"{source}: non-numeric value {token!r} on line {line}") from None
            texts.extend(numbers)
            lines.extend([line] * len(numbers))
        tokens, line_numbers = texts, lines
        values = np.array(texts, dtype=float)
    bad = ~np.isfinite(values)
    if bad.any():
        index = int(np.argmax(bad))
        raise ValueError(f"{source}: non-finite value {tokens[index]!r} on line {line_numbers[index]}")
    return values, line_numbers


def _to_mm_s2(values: np.ndarray, factor: float, unit: str, line_numbers: list[int], source: Path) -> np.ndarray:
    with np.errstate(over="ignore"):
        converted = values * factor
    overflow = ~np.isfinite(converted)
    if overflow.any():
        index = int(np.argmax(overflow))
        raise ValueError(f"{source}: value {show(values[index])} {unit} on line {line_numbers[index]} "
                         f"overflows when converted to mm/s^2")
    return converted


def acceleration_unit(unit: object, name: str = "unit") -> float:
    """The factor to mm/s^2 of the acceleration unit ``unit`` (a key of :data:`UNITS`, in any of the
    spellings described there); a ValueError naming ``name`` otherwise, saying so when ``unit`` is a unit
    of velocity or displacement."""
    if not isinstance(unit, str):
        raise ValueError(f"{name} must be a string such as 'g' or 'cm/s2', got {show(unit)}")
    key = unit.strip().lower().replace("\u00b2", "2").replace("**2", "2").replace("^2", "2")
    key = re.sub(r"(?<=/)sec(?:s|onds?)?", "s", key).replace("/s/s", "/s2")
    key = "cm/s2" if key in ("gal", "gals") else key
    if key in UNITS:
        return UNITS[key]
    accepted = ", ".join(map(repr, UNITS))
    if key in _OTHER_QUANTITIES:
        raise ValueError(f"{name} {unit!r} is a unit of {_OTHER_QUANTITIES[key]}: ground motions are accelerations "
                         f"({accepted})")
    raise ValueError(f"unknown {name} {unit!r}; use one of {accepted}")


def _stated_units(line: str) -> list[str]:
    """The units ``line`` names, as written (see the patterns above), in the order they appear."""
    found: list[tuple[int, str]] = []
    for match in _UNIT_STATEMENT.finditer(line):
        found.append((match.start(1), match.group(1).rstrip(".")))
    for pattern in (_SLASH_UNIT, _GAL, _G, _ACCELERATION_UNIT):
        found.extend((match.start(), next(group for group in match.groups() if group is not None))
                     for match in pattern.finditer(line))
    found.extend((match.start(), f"{match.group(1)}/s2") for match in _NEGATIVE_POWER_UNIT.finditer(line))
    found = [(start, "g" if _G_PLURAL.fullmatch(unit) else unit.strip()) for start, unit in found]
    return [unit for _, unit in sorted(set(found))]  # one unit found by two patterns counts once


def _header_unit(header: list[tuple[int, str]], path: Path) -> tuple[float, str]:
    """(factor to mm/s^2, unit) of the values of an AT2 file, from the units its header lines name
    (:func:`_stated_units`; g when they name none); a ValueError for a header that names a velocity or
    displacement history, names a unit that is not an acceleration unit read here, or two different units."""
    stated: list[tuple[int, str, float]] = []
    for number, line in header:
        other = _OTHER_HISTORY.search(line)
        if other:
            raise ValueError(f"{path}: line {number} says this is a {other.group(1).lower()} history "
                             f"({line.strip()!r}); read_at2 reads acceleration histories (.AT2)")
        for unit in _stated_units(line):
            try:
                stated.append((number, unit, acceleration_unit(re.sub(r"\s+", "", unit), "header unit")))
            except ValueError as error:
                raise ValueError(f"{path}: line {number} states units {unit!r} ({line.strip()!r}), which read_at2 "
                                 f"cannot read as an acceleration: {error}") from None
    if len({factor for *_, factor in stated}) > 1:
        first, second = stated[0], next(s for s in stated if s[2] != stated[0][2])
        raise ValueError(f"{path}: the header states two units, {first[1]!r} on line {first[0]} and {second[1]!r} "
                         f"on line {second[0]}")
    return (stated[0][2], stated[0][1]) if stated else (G, "g")


def read_at2(path: str | os.PathLike[str]) -> GroundMotion:
    """Read a PEER ``.AT2`` acceleration file into a :class:`GroundMotion` (mm/s^2, s).

    Units: the unit the header names (``IN UNITS OF G``, ``UNITS OF CM/S/S``, ``The units are (g)``,
    ``UNITS: gal``, and without the word: ``ACCELERATION IN CM/S/S``, ``ACCELERATION (cm/s2)``,
    ``Acceleration [m/s^2]``, ``ACCEL. CM/SEC/SEC``, ``cm s-2``; any unit of :data:`UNITS`); g only when
    the header names g or no unit at all (PEER's convention).  A header that names a velocity or
    displacement history (``VELOCITY TIME HISTORY``), names a unit that is not an acceleration unit read
    here (``ft/s2``, ``ACCELERATION [mg]``, ``cm/s``), or names two different units is a ValueError naming
    the line: such a file is never read as g.

    The header is free text; the count line is the first line (among the first 10 non-blank ones) that
    is either

    - a keyword line holding ``NPTS=``: e.g. ``NPTS=  4000, DT= .01000 SEC`` or NGA-West2's
      ``NPTS=   5590, DT=   .0050 SEC`` (spaces, trailing commas, lower-case keys accepted), or
    - a legacy line with the numbers first: ``  3930   0.01000    NPTS, DT`` (older PEER downloads,
      NGA-West1, the FEMA P695 set).

    DT is taken from that line only, in s unless a time unit follows it (``DT= 10 ms`` or ``DT= 10ms`` is
    0.01 s; ``SEC``, ``S`` and ``MS`` are read; any other unit written onto the number, or another time unit
    after it, ``DT= 0.02 MIN``, is refused).  The
    values, any number a line, follow it; surplus zeros on the last line of values (padding to a full
    line) are ignored.  The module docstring lists the other
    variants accepted.  ValueError, naming the file, for a missing, unreadable or binary file, an empty
    file, a missing or bad NPTS or DT, fewer or more values than NPTS, or a non-numeric or non-finite
    value (naming its line).  The record's name is the file stem.
    """
    path, lines = _record_lines(path, "AT2 file")
    numbered = [(number, line) for number, line in enumerate(lines, start=1) if line.strip()]
    if not numbered:
        raise ValueError(f"{path}: empty file")
    header = next((index for index, (_, line) in enumerate(numbered[:AT2_HEADER_LINES])
                   if _NPTS.search(line) or _LEGACY_COUNT.match(line)), None)
    if header is None:
        raise ValueError(f"{path}: missing NPTS (no 'NPTS= n, DT= dt' line and no legacy 'n dt NPTS, DT' "
                         f"line in the first {AT2_HEADER_LINES} lines)")
    count_line_number, count_line = numbered[header]
    keyword = _NPTS.search(count_line)
    if keyword:
        npts = _npts(keyword.group(1), path, count_line_number)
        dt_match = _DT.search(count_line)
        if not dt_match:
            raise ValueError(f"{path}: missing DT (no 'DT=' on the NPTS line, line {count_line_number})")
        dt = _dt(dt_match.group(1), path, count_line_number, dt_match.group(2))
    else:
        legacy = _LEGACY_COUNT.match(count_line)
        assert legacy is not None  # the count line is a keyword line or a legacy one
        npts = _npts(legacy.group(1), path, count_line_number)
        dt = _dt(legacy.group(2), path, count_line_number)
    factor, unit = _header_unit(numbered[:header + 1], path)  # the count line too ("NPTS=..., UNITS: CM/S2")
    tokens, line_numbers = [], []
    for number, line in numbered[header + 1:]:
        words = line.split()
        tokens.extend(words)
        line_numbers.extend([number] * len(words))
    values, line_numbers = _floats(tokens, line_numbers, path)
    if values.size < npts:
        raise ValueError(f"{path}: too few values: NPTS = {npts} on line {count_line_number} but "
                         f"{values.size} values follow")
    if values.size > npts:
        padding = values[npts:]
        if np.any(padding != 0.0) or line_numbers[-1] != line_numbers[npts - 1]:
            raise ValueError(f"{path}: too many values: NPTS = {npts} on line {count_line_number} but "
                             f"{values.size} values follow")
        values, line_numbers = values[:npts], line_numbers[:npts]
    return _motion(_to_mm_s2(values, factor, unit, line_numbers, path), dt, path.stem, path)


def _motion(acceleration: np.ndarray, dt: float, name: str, path: Path) -> GroundMotion:
    try:
        return GroundMotion(acceleration, dt, name)
    except ValueError as error:  # e.g. a single sample
        raise ValueError(f"{path}: {error}") from None


def _npts(text: str, path: Path, line: int) -> int:
    if not re.fullmatch(r"[0-9]+", text) or int(text) == 0:
        raise ValueError(f"{path}: NPTS must be a positive whole number, got {text!r} on line {line}")
    return int(text)


def _dt(text: str, path: Path, line: int, word: str | None = None) -> float:
    """DT in s from its text: a number, optionally with a time unit written onto it (``.0050SEC``,
    ``10ms``) or as the next ``word`` (``.0050 SEC``, ``10 ms``; another time unit, ``MIN``, is refused; any
    other word is other text)."""
    match = _NUMBER.match(text)
    numbers = _number_texts(match.group(0)) if match else None
    suffix = text[match.end():] if match else ""
    if suffix and suffix.isalpha() and suffix.lower() not in _TIME_UNITS:
        raise ValueError(f"{path}: DT unit {suffix!r} on line {line} is not a time unit read_at2 reads "
                         f"(s, sec or ms), in {text!r}")
    if word is not None and word.lower() in _OTHER_TIME_UNITS:
        raise ValueError(f"{path}: DT unit {word!r} on line {line} is not a time unit read_at2 reads "
                         f"(s, sec or ms), in {text + ' ' + word!r}")
    unit = suffix or (word if word is not None and word.lower() in _TIME_UNITS else "") or "s"
    dt = float(numbers[0]) * _TIME_UNITS[unit.lower()] if numbers and (suffix == "" or suffix.isalpha()) \
        else float("nan")
    if not (np.isfinite(dt) and dt > 0.0):
        raise ValueError(f"{path}: DT must be a positive time step (s or ms), got {text!r} on line {line}")
    return dt


def read_two_column(path: str | os.PathLike[str], unit: str = "g", *, skip_rows: int = 0,
                    name: str | None = None) -> GroundMotion:
    """Read a (time s, acceleration ``unit``) text file into a :class:`GroundMotion` (mm/s^2, s).

    ``unit`` is one of ``"g"``, ``"mm/s2"``, ``"cm/s2"``, ``"m/s2"``, ``"in/s2"`` (other spellings as
    :data:`UNITS` says; a velocity or displacement unit, or an unknown one, is a ValueError).  Columns are separated by
    whitespace and/or commas; ``#`` starts a comment; blank lines are skipped, and so are the first
    ``skip_rows`` lines (e.g. a column-title line).  Every other line must hold exactly two finite
    numbers (the variants of the module docstring accepted).  Times must increase uniformly: each within
    :data:`TWO_COLUMN_TOLERANCE` (1e-3) dt of ``t0 + i dt`` (dt the mean step), else a ValueError
    naming the line.  The record starts at the first row (times are shifted to start at 0).  ``name``
    defaults to the file stem.
    """
    factor = acceleration_unit(unit)
    skip_rows = whole_number("skip_rows", skip_rows, 0)
    if name is not None and not isinstance(name, str):
        raise ValueError(f"name must be a string, got {show(name)}")
    path, lines = _record_lines(path, "two-column file")
    tokens, line_numbers = [], []
    for number, line in enumerate(lines[skip_rows:], start=skip_rows + 1):
        words = re.split(r"[\s,]+", line.split("#", 1)[0].strip())
        if words == [""]:
            continue
        if len(words) != 2:  # maybe values written without a separator
            split = [_number_texts(word) for word in words]
            if all(split):
                words = [text for texts in split if texts is not None for text in texts]
        if len(words) != 2:
            raise ValueError(f"{path}: line {number} has {len(words)} values, expected 2 (time, acceleration)")
        tokens.extend(words)
        line_numbers.extend([number, number])
    values, line_numbers = _floats(tokens, line_numbers, path)
    rows = values.reshape(-1, 2)
    if rows.shape[0] < 2:
        raise ValueError(f"{path}: needs at least 2 rows (time, acceleration), found {rows.shape[0]}")
    time = rows[:, 0]
    with np.errstate(over="ignore", invalid="ignore"):
        dt = (time[-1] - time[0]) / (time.size - 1)
    if not (np.isfinite(dt) and dt > 0.0):
        raise ValueError(f"{path}: times must increase, got {show(time[0])} s to {show(time[-1])} s")
    off = np.abs(time - time[0] - np.arange(time.size) * dt) > TWO_COLUMN_TOLERANCE * dt
    if off.any():
        row = int(np.argmax(off))
        raise ValueError(f"{path}: non-uniform time step at line {line_numbers[2 * row]}: t = {show(time[row])} s, "
                         f"expected {show(time[0] + row * dt)} s for a step of {show(dt)} s")
    acceleration = _to_mm_s2(rows[:, 1], factor, unit, line_numbers[1::2], path)
    return _motion(acceleration, float(dt), path.stem if name is None else name, path)


def write_at2(motion: GroundMotion, path: str | os.PathLike[str], header: str | Sequence[str] = ()) -> Path:
    """Write ``motion`` (mm/s^2) as a PEER-layout ``.AT2`` file in g; returns the path.

    Layout: up to two free-text ``header`` lines (padded with ``GROUND MOTION <name>``), then
    ``ACCELERATION TIME HISTORY IN UNITS OF G``, then ``NPTS= n, DT= dt SEC`` (the 4th line, dt s
    written exactly), then the values, 5 a line, to 8 significant digits (so a read-back differs by
    < 5e-8 relative).  Text is UTF-8 (plain ASCII unless the header or name is not).

    Everything is checked before the file is touched: header lines must be single lines without
    control characters, and neither they nor the name line may look like a count line (``NPTS=``,
    ``DT=`` or ``n dt NPTS, DT``), which :func:`read_at2` would take for one.  The file is written to a
    temporary file in the same folder and renamed over ``path``, so a failure never destroys an existing
    file.  ValueError for a bad argument, a missing folder or a folder given as ``path``.
    """
    if not isinstance(motion, GroundMotion):
        raise ValueError(f"motion must be a GroundMotion, got {type(motion).__name__}")
    if isinstance(header, str):
        lines = header.splitlines()
    elif isinstance(header, Sequence) and all(isinstance(line, str) for line in header):
        lines = list(header)
    else:
        raise ValueError(f"header must be a string or a sequence of strings, got {show(header)}")
    if len(lines) > 2 or any(_CONTROL.search(line) for line in lines):
        raise ValueError(f"header must be at most 2 single lines without control characters, got {header!r}")
    name_line = f"GROUND MOTION {motion.name or 'RECORD'}"
    lines = [*lines, name_line, ""][:2]
    for line in lines:
        if _CONTROL.search(line):
            raise ValueError(f"record name {motion.name!r} has a control character; rename the record "
                             f"or pass header=[line1, line2]")
        what = f"record name {motion.name!r}" if line == name_line else f"header line {line!r}"
        if _NPTS.search(line) or _DT.search(line) or _LEGACY_COUNT.match(line):
            raise ValueError(f"{what} would be read as the NPTS/DT line (it contains 'NPTS=', 'DT=' or "
                             f"'n dt NPTS, DT'); rename the record or pass other header lines")
        if _stated_units(line) or _OTHER_HISTORY.search(line):
            raise ValueError(f"{what} would be read as a statement of the file's units or quantity (it contains "
                             "'UNITS OF ...', 'VELOCITY TIME HISTORY' or the like); the file states its units "
                             "(g) itself: rename the record or pass other header lines")
    values = motion.acceleration / G
    rows = [" ".join(f"{value:15.7E}" for value in values[i:i + 5]) for i in range(0, values.size, 5)]
    text = "\n".join([*lines, "ACCELERATION TIME HISTORY IN UNITS OF G",
                      f"NPTS= {values.size:6d}, DT= {motion.dt!r} SEC", *rows]) + "\n"
    path = file_path(path, "AT2 file")
    replace_file(path, text.encode("utf-8"))
    return path
