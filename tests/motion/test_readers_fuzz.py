"""Reader fuzzing (hypothesis): generated real-world AT2 and two-column variants read to the values
they were written with; mutated files give a finite GroundMotion or a ValueError, never another
exception; write_at2 -> read_at2 round-trips any finite record and never destroys the target.

The expected values are parsed here with Python's float() from the very text written, independently
of the package's tokenizer.  ``VDW_FUZZ_EXAMPLES=5000 python -m pytest tests/motion/test_readers_fuzz.py``
fuzzes harder than the default 150 examples a test.
"""

from __future__ import annotations

import os
import re
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from vdw_frames.motion import G, GroundMotion, read_at2, read_two_column, write_at2

FUZZ = settings(max_examples=int(os.environ.get("VDW_FUZZ_EXAMPLES", "150")), deadline=None,
                suppress_health_check=[HealthCheck.too_slow])
LINE_ENDS = st.sampled_from(["\n", "\r\n", "\r\r\n", "\r"])
COUNT_LINES = [
    "NPTS= {n:6d}, DT= {dt} SEC",                # PEER NGA-West2
    "NPTS=   {n}, DT=   {dt} SEC,",
    "npts={n},dt={dt}",
    "Npts = {n} , Dt = {dt} sec",
    "  {n}   {dt}    NPTS, DT",                   # legacy PEER, FEMA P695
    "{n} {dt} NPTS, DT",                           # NGA-West1
    "{n:7d}{dt:>12}   NPTS,DT   (free text after)",
]
HEADER_TEXT = st.text(st.sampled_from("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefgh 0123456789.,:;-/()#'"), max_size=60)


def fortran_e(value: float, digits: int, letter: str = "E") -> str:
    """Fortran's Ew.d without the leading zero: -.3900E-02 (the mantissa in [0.1, 1))."""
    if value == 0.0:
        return f".{'0' * digits}{letter}+00"
    exponent = int(np.floor(np.log10(abs(value)))) + 1
    mantissa = round(abs(value) / 10.0**exponent, digits)
    if mantissa >= 1.0:
        mantissa, exponent = mantissa / 10.0, exponent + 1
    sign = "-" if value < 0 else ""
    return f"{sign}.{f'{mantissa:.{digits}f}'[2:]}{letter}{exponent:+03d}"


def format_values(values, style: str) -> list[str]:
    """Text fields of ``values`` in one of the styles found in real files."""
    if style == "E15.7":
        return [f"{v:15.7E}" for v in values]
    if style == "D":
        return [" " + f"{v:.6E}".replace("E", "D") for v in values]
    if style == "F10.5":
        return [f"{v:10.5f}" for v in values]
    if style == "repr":
        return [" " + repr(float(v)) for v in values]
    # fixed-width Fortran E: a negative value fills its field, so no separator is left
    digits = 4
    width = digits + 6
    return [f"{fortran_e(v, digits):>{width}}" for v in values]


STYLES = st.sampled_from(["E15.7", "D", "F10.5", "repr", "fixed"])
# Fortran's 2-digit exponents: |values| above 1e-60 g (or 0)
values_in_g = st.lists(st.one_of(st.floats(-2.0, 2.0, allow_nan=False).map(lambda v: v if abs(v) > 1e-60 else 0.0),
                                 st.just(0.0)), min_size=2, max_size=40)
steps = st.one_of(st.sampled_from(["0.005", ".0050", "0.01000", ".01", "0.02", "5.0E-03", "1.0D-02"]),
                  st.floats(1e-4, 0.1).map(lambda x: f"{x:.6f}"))


def parse(field: str) -> float:
    return float(field.replace("D", "E"))


@st.composite
def at2_files(draw):
    """(bytes, expected values in g, expected dt)."""
    values = draw(values_in_g)
    style = draw(STYLES)
    per_line = draw(st.integers(1, 8))
    fields = format_values(values, style)
    rows = [fields[i:i + per_line] for i in range(0, len(fields), per_line)]
    if draw(st.booleans()) and len(rows[-1]) < per_line:  # zero padding to a full last line
        rows[-1] = rows[-1] + format_values([0.0] * (per_line - len(rows[-1])), style)
    dt_text = draw(steps)
    count = draw(st.sampled_from(COUNT_LINES)).format(n=len(values), dt=dt_text)
    header = draw(st.lists(HEADER_TEXT, min_size=0, max_size=3))
    # Free text that names no unit (the files are in g): no ratio, brackets, "IN ...", gal or UNITS statement.
    assume(not any(re.search(r"/|[(\[]|\bIN\b|\bGALS?\b|UNIT|\bS\W*2", line, re.I) for line in header))
    if draw(st.booleans()):
        header.insert(0, "SAMPLED AT DT= 0.5 SEC (a decoy: DT is read from the NPTS line only)")
    header = [line for line in header if line.strip()]
    assume(not any(re.search(r"NPTS", line, re.I) for line in header))
    newline = draw(LINE_ENDS)
    text = newline.join([*header, count, *("".join(row) for row in rows)])
    text += draw(st.sampled_from(["", newline, newline * 3, "\x1a", newline + "\x1a", newline + "\x1a\x1a" + newline]))
    data = text.encode("ascii")
    if draw(st.booleans()):  # a Latin-1 station name in the header: not UTF-8, only free text
        data = b"STATION S\xe3O PAULO" + newline.encode() + data
    if draw(st.booleans()):
        data = b"\xef\xbb\xbf" + data
    expected = [parse(field) for field in fields]
    return data, expected, parse(dt_text)


# One folder for the module's generated files, removed when the run ends (a folder per example was left behind).
_SCRATCH = tempfile.TemporaryDirectory(prefix="vdw_fuzz_")


def write_bytes(data: bytes, name: str) -> Path:
    folder = Path(tempfile.mkdtemp(dir=_SCRATCH.name))
    path = folder / name
    path.write_bytes(data)
    return path


@FUZZ
@given(at2_files())
def test_read_at2_reads_generated_variants_exactly(file):
    data, expected, dt = file
    motion = read_at2(write_bytes(data, "generated.AT2"))
    np.testing.assert_array_equal(motion.acceleration, np.array(expected) * G)
    assert motion.dt == dt
    assert motion.name == "generated"


def mutations(data: bytes):
    alphabet = [*b"0123456789.-+eEdD \t\r\n,=NPTSDTx", 0, 0x1A, 0xFF, 0xEF, 0xBB, 0xBF]
    return st.lists(st.tuples(st.sampled_from(["delete", "insert", "replace"]),
                              st.integers(0, max(len(data) - 1, 0)), st.sampled_from(alphabet)),
                    min_size=1, max_size=6)


def mutate(data: bytes, edits) -> bytes:
    buffer = bytearray(data)
    for operation, drawn_position, byte in edits:
        position = min(drawn_position, len(buffer))
        if operation == "delete" and position < len(buffer):
            del buffer[position]
        elif operation == "insert":
            buffer.insert(position, byte)
        elif position < len(buffer):
            buffer[position] = byte
    return bytes(buffer)


def assert_valid_or_value_error(reader, path: Path) -> None:
    try:
        motion = reader(path)
    except ValueError as error:
        assert str(error)  # a message, and only a ValueError reaches the caller
        return
    assert isinstance(motion, GroundMotion)
    assert motion.acceleration.size >= 2 and np.all(np.isfinite(motion.acceleration))
    assert np.isfinite(motion.dt) and motion.dt > 0.0


@FUZZ
@given(st.data())
def test_read_at2_on_mutated_files_returns_a_record_or_a_value_error(data):
    original, _, _ = data.draw(at2_files())
    mutated = mutate(original, data.draw(mutations(original)))
    assert_valid_or_value_error(read_at2, write_bytes(mutated, "mutated.AT2"))


@FUZZ
@given(st.binary(max_size=300))
def test_read_at2_on_arbitrary_bytes_returns_a_record_or_a_value_error(data):
    assert_valid_or_value_error(read_at2, write_bytes(b"NPTS= 3, DT= 0.01\n" + data, "bytes.AT2"))
    assert_valid_or_value_error(read_at2, write_bytes(data, "bytes.AT2"))


@st.composite
def two_column_files(draw):
    """(bytes, unit, expected times, expected accelerations in the unit)."""
    count = draw(st.integers(2, 40))
    dt = draw(st.sampled_from([0.005, 0.01, 0.02, 0.1]))
    t0 = draw(st.sampled_from([0.0, 1.0, 12.5]))
    float32_times = draw(st.booleans())
    times = [f"{np.float32(t0 + i * dt):.9g}" if float32_times else f"{t0 + i * dt:.6f}" for i in range(count)]
    values = draw(st.lists(st.floats(-500.0, 500.0, allow_nan=False), min_size=count, max_size=count))
    style = draw(STYLES)
    fields = [field.strip() for field in format_values(values, style)]
    separator = draw(st.sampled_from([" ", "  ", "\t", ",", ", ", " , "]))
    lines = [f"{t}{separator}{a}" for t, a in zip(times, fields, strict=True)]
    for _ in range(draw(st.integers(0, 3))):  # comments and blank lines anywhere
        lines.insert(draw(st.integers(0, len(lines))), draw(st.sampled_from(["", "# a comment", "   "])))
    lines[-1] += draw(st.sampled_from(["", "  # trailing comment"]))
    newline = draw(LINE_ENDS)
    data = (newline.join(lines) + draw(st.sampled_from(["", newline, "\x1a"]))).encode("ascii")
    if draw(st.booleans()):
        data = b"\xef\xbb\xbf" + data
    unit = draw(st.sampled_from(["g", "mm/s2", "cm/s2", "m/s2"]))
    return data, unit, [float(t) for t in times], [parse(field) for field in fields]


FACTORS = {"g": G, "mm/s2": 1.0, "cm/s2": 10.0, "m/s2": 1000.0}


@FUZZ
@given(two_column_files())
def test_read_two_column_reads_generated_variants_exactly(file):
    data, unit, times, accelerations = file
    motion = read_two_column(write_bytes(data, "generated.txt"), unit=unit)
    np.testing.assert_array_equal(motion.acceleration, np.array(accelerations) * FACTORS[unit])
    assert motion.dt == pytest.approx((times[-1] - times[0]) / (len(times) - 1), rel=1e-12)


@FUZZ
@given(st.data())
def test_read_two_column_on_mutated_files_returns_a_record_or_a_value_error(data):
    original, unit, _, _ = data.draw(two_column_files())
    mutated = mutate(original, data.draw(mutations(original)))
    assert_valid_or_value_error(lambda path: read_two_column(path, unit=unit), write_bytes(mutated, "mutated.txt"))


names = st.one_of(st.text(max_size=30), st.sampled_from(["Tōhoku", "NPTS= 5, DT= 0.1", "x DT= 1", "12 0.01 NPTS, DT",
                                                          "two\nlines", "tab\there", "", "El Centro 1940"]))


@FUZZ
@given(values=st.lists(st.floats(-1e300, 1e300, allow_nan=False, allow_subnormal=False), min_size=2, max_size=30),
       dt=st.floats(1e-6, 10.0), name=names)
def test_write_at2_round_trips_or_refuses_without_touching_the_file(values, dt, name):
    motion = GroundMotion(values, dt, name)
    path = write_bytes(b"PREVIOUS CONTENT", "record.AT2")
    try:
        written = write_at2(motion, path)
    except ValueError as error:
        # Refused names are exactly those the reader would misread, or that would break the layout.
        assert re.search(r"[\x00-\x1f\x7f]|NPTS\s*=|DT\s*=|NPTS\s*,?\s*DT", name, re.I), (name, error)
        assert path.read_bytes() == b"PREVIOUS CONTENT"
        assert list(path.parent.iterdir()) == [path]  # no temporary file left behind
        return
    assert written == path and list(path.parent.iterdir()) == [path]
    back = read_at2(path)
    np.testing.assert_allclose(back.acceleration, motion.acceleration, rtol=6e-8, atol=1e-290)
    assert back.dt == motion.dt
    assert path.read_bytes().decode("utf-8").split("\n")[0] == f"GROUND MOTION {name or 'RECORD'}"
