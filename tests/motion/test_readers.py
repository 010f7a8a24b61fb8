"""Readers and writer of ground-motion files (vdw_frames.motion.readers): AT2 files, real and written here in
every variant found in practice, two-column files, and write_at2, against values parsed here without the
package."""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pytest
from builders import VALUES_G, peer_at2, write_file
from reference import at2_values
from shared_data import shared_record

from vdw_frames import GroundMotion, read_at2, read_two_column
from vdw_frames import motion as gm
from vdw_frames.motion import G, write_at2

# From the table in ../shared/ground_motions/README.md: file -> (NPTS, DT s).
SHARED_RECORDS = {
    "IELC180.AT2": (4000, 0.01),
    "elCentro.AT2": (1559, 0.02),
    "ARL360.at2": (2000, 0.02),
    "RIO270.AT2": (1800, 0.02),
    "HWA002-N.AT2": (20000, 0.004),
}


# --------------------------------------------------------------------------------------------------
# read_at2 on the real records


@pytest.mark.records
@pytest.mark.parametrize("file_name", sorted(SHARED_RECORDS))
def test_read_at2_shared_records(file_name):
    path = shared_record(file_name)
    npts, dt = SHARED_RECORDS[file_name]
    motion = gm.read_at2(path)
    expected = at2_values(path)
    assert motion.name == Path(file_name).stem
    assert motion.acceleration.size == npts == len(expected)
    assert motion.dt == dt
    assert motion.acceleration[0] == pytest.approx(expected[0] * 9806.65, rel=1e-15)
    assert motion.acceleration[-1] == pytest.approx(expected[-1] * 9806.65, rel=1e-15)
    assert motion.pga == pytest.approx(max(abs(value) for value in expected) * 9806.65, rel=1e-15)
    assert motion.duration == pytest.approx((npts - 1) * dt, rel=1e-12)


@pytest.mark.records
def test_read_at2_known_values():
    motion = gm.read_at2(shared_record("IELC180.AT2"))
    assert motion.acceleration[0] == pytest.approx(-0.6403182e-02 * 9806.65, rel=1e-15)
    assert motion.acceleration[4] == pytest.approx(0.6890377e-02 * 9806.65, rel=1e-15)
    assert motion.pga / G == pytest.approx(0.3129, abs=5e-5)  # El Centro 1940, 180: PGA 0.313 g
    elcentro = gm.read_at2(shared_record("elCentro.AT2"))
    assert elcentro.acceleration[:3] == pytest.approx(np.array([0.00630, 0.00364, 0.00099]) * G, rel=1e-15)


# --------------------------------------------------------------------------------------------------
# read_at2 on variants written here


def write(tmp_path, text: str, name: str = "record.AT2", newline: str = "\n") -> Path:
    path = tmp_path / name
    path.write_bytes(text.replace("\n", newline).encode("ascii"))
    return path


def at2_text(count_line: str = "NPTS=     7, DT= .01000 SEC", values=None) -> str:
    values = VALUES_G if values is None else values
    rows = ["".join(f"{value:>15}" for value in values[i:i + 5]) for i in range(0, len(values), 5)]
    return "\n".join(["PEER STRONG MOTION DATABASE RECORD.", "SOME EVENT, SOME STATION, 000",
                      "ACCELERATION TIME HISTORY IN UNITS OF G", count_line, *rows]) + "\n"


@pytest.mark.parametrize("newline", ["\n", "\r\n", "\r\r\n", "\r"])
def test_read_at2_line_ends(tmp_path, newline):
    motion = gm.read_at2(write(tmp_path, at2_text(), newline=newline))
    np.testing.assert_array_equal(motion.acceleration, np.array(VALUES_G) * G)
    assert motion.dt == 0.01
    assert motion.name == "record"


@pytest.mark.parametrize("count_line, dt", [
    ("NPTS=   7, DT=   .0050 SEC", 0.005),
    ("NPTS=   7, DT=   .0050 SEC,", 0.005),
    ("NPTS=7,DT=0.005,", 0.005),
    ("npts=   7, dt=   .0050 sec", 0.005),
    ("Npts = 7 , Dt = 5.0E-03 SEC", 0.005),
])
def test_read_at2_count_line_variants(tmp_path, count_line, dt):
    motion = gm.read_at2(write(tmp_path, at2_text(count_line)))
    assert motion.acceleration.size == 7
    assert motion.dt == dt


def test_read_at2_free_text_header_and_eight_values_a_line(tmp_path):
    values = [0.001 * k for k in range(-5, 6)]
    text = ("Data for a test record, free text with 11 points\n"
            "points at equal spacing of 0.02 sec, 8F10.5\nThe units are (g)\nNPTS=  11, DT= .02000 SEC\n"
            + "".join(f"{v:10.5f}" for v in values[:8]) + "\n" + "".join(f"{v:10.5f}" for v in values[8:]) + "\n")
    motion = gm.read_at2(write(tmp_path, text, "free.AT2"))
    np.testing.assert_allclose(motion.acceleration, np.array(values) * G, rtol=1e-15, atol=1e-12)
    assert motion.dt == 0.02


@pytest.mark.parametrize("text, problem", [
    (at2_text("NUMBER OF POINTS 7, DT= .01 SEC"), "missing NPTS"),
    (at2_text("NPTS= 7, STEP= .01 SEC"), "missing DT"),
    (at2_text("NPTS= 8, DT= .01 SEC"), "too few values"),
    (at2_text("NPTS= 6, DT= .01 SEC"), "too many values"),
    (at2_text("NPTS= 7, DT= -.01 SEC"), "DT must be a positive"),
    (at2_text("NPTS= 7, DT= 0 SEC"), "DT must be a positive"),
    (at2_text("NPTS= seven, DT= .01 SEC"), "NPTS must be a positive whole number"),
    (at2_text("NPTS= 0, DT= .01 SEC", values=[]), "NPTS must be a positive whole number"),
    (at2_text(values=[*VALUES_G[:3], "0.1x", *VALUES_G[4:]]), r"non-numeric value '0\.1x' on line 5"),
    (at2_text(values=[*VALUES_G[:6], "1.0-2"]), "non-numeric value '1.0-2' on line 6"),  # E-less exponent?
    (at2_text(values=[*VALUES_G[:6], "nan"]), "non-finite value 'nan' on line 6"),
    (at2_text(values=["-inf", *VALUES_G[1:]]), "non-finite value '-inf' on line 5"),
    ("", "empty file"),
    ("\r\n  \n\n", "empty file"),
])
def test_read_at2_rejects(tmp_path, text, problem):
    assert_rejected(gm.read_at2, write(tmp_path, text, "bad_record.AT2"), problem)


def assert_rejected(reader, path: Path, problem: str) -> None:
    """``reader(path)`` raises a ValueError naming the file and then the problem."""
    with pytest.raises(ValueError, match=re.escape(str(path)) + ".*" + problem):
        reader(path)


def test_read_at2_needs_npts_near_the_top(tmp_path):
    text = "\n".join([f"header line {i}" for i in range(12)] + ["NPTS= 1, DT= .01", "0.1"]) + "\n"
    with pytest.raises(ValueError, match=r"long_header\.AT2: missing NPTS"):
        gm.read_at2(write(tmp_path, text, "long_header.AT2"))


# --------------------------------------------------------------------------------------------------
# read_two_column


@pytest.mark.parametrize("unit, factor", [("g", 9806.65), ("mm/s2", 1.0), ("cm/s2", 10.0), ("m/s2", 1000.0)])
def test_read_two_column_units_and_separators(tmp_path, unit, factor):
    text = "# time (s), acceleration\n\n1.00, 0.5\n1.01 -0.25   # a comment\n1.02\t,0.125\n1.03 1e-3\n"
    motion = gm.read_two_column(write(tmp_path, text, "two.txt"), unit=unit)
    np.testing.assert_array_equal(motion.acceleration, np.array([0.5, -0.25, 0.125, 1e-3]) * factor)
    assert motion.dt == pytest.approx(0.01, rel=1e-12)
    assert motion.name == "two"


def test_read_two_column_skip_rows_and_name(tmp_path):
    path = write(tmp_path, "time,acc\r\n0,1\r\n0.5,2\r\n1.0,3\r\n", "titled.csv")
    motion = gm.read_two_column(path, unit="m/s2", skip_rows=1, name="titled record")
    np.testing.assert_array_equal(motion.acceleration, [1000.0, 2000.0, 3000.0])
    assert (motion.dt, motion.name) == (0.5, "titled record")


@pytest.mark.parametrize("text, problem", [
    ("0 1\n0.01 2\n0.0201 3\n0.03 4\n", "non-uniform time step at line 3"),
    ("0 1\n0.01 2\n0.02 3 4\n", "line 3 has 3 values"),
    ("0 1\n0.01 two\n", "non-numeric value 'two' on line 2"),
    ("0 1\n0.01 inf\n", "non-finite value 'inf' on line 2"),
    ("0 1\n", "at least 2 rows"),
    ("0 1\n0 2\n", "times must increase"),
])
def test_read_two_column_rejects(tmp_path, text, problem):
    assert_rejected(gm.read_two_column, write(tmp_path, text, "bad_two.txt"), problem)


def test_read_two_column_unknown_unit(tmp_path):
    with pytest.raises(ValueError, match="unknown unit 'ft/s2'"):
        gm.read_two_column(write(tmp_path, "0 1\n1 2\n"), unit="ft/s2")


# --------------------------------------------------------------------------------------------------
# write_at2


def test_write_at2_round_trip(tmp_path):
    motion = GroundMotion(np.array([0.123456789, -1.5, 2.0e-7, 0.0, 0.75, -0.3]) * G, 0.0025, "rt")
    path = gm.write_at2(motion, tmp_path / "rt.AT2", header="A TEST RECORD")
    lines = path.read_text().splitlines()
    assert lines[0] == "A TEST RECORD" and lines[3] == "NPTS=      6, DT= 0.0025 SEC"
    back = gm.read_at2(path)
    np.testing.assert_allclose(back.acceleration, motion.acceleration, rtol=5e-8)
    assert back.dt == 0.0025 and back.name == "rt"
    with pytest.raises(ValueError, match="would be read as the NPTS/DT line"):
        gm.write_at2(motion, tmp_path / "x.AT2", header=["NPTS= 6"])
    with pytest.raises(ValueError, match="at most 2 single lines"):
        gm.write_at2(motion, tmp_path / "x.AT2", header=["a", "b", "c"])


# --------------------------------------------------------------------------------------------------
# legacy and odd files


@pytest.mark.parametrize("count_line, dt", [
    ("    7   0.01000    NPTS, DT", 0.01),      # legacy PEER, FEMA P695
    ("7 0.0050 NPTS, DT", 0.005),                # NGA-West1
    ("   7,  .0050,  NPTS, DT", 0.005),
    ("NPTS=      7, DT=   .0050 SEC", 0.005),    # still: NGA-West2
])
def test_read_at2_reads_legacy_and_nga_count_lines(tmp_path, count_line, dt):
    rows = [" ".join(f"{v:.7E}" for v in VALUES_G[:5]), " ".join(f"{v:.7E}" for v in VALUES_G[5:])]
    motion = read_at2(write_file(tmp_path, "legacy.AT2", peer_at2(count_line, rows)))
    np.testing.assert_array_equal(motion.acceleration, np.array(VALUES_G) * G)
    assert motion.dt == dt


def test_read_at2_takes_dt_only_from_the_count_line_and_says_what_is_missing(tmp_path):
    rows = [" ".join(str(v) for v in VALUES_G)]
    with pytest.raises(ValueError, match=r"missing NPTS \(no 'NPTS= n, DT= dt' line and no legacy 'n dt NPTS, DT'"):
        read_at2(write_file(tmp_path, "none.AT2", peer_at2("7 points at 0.01 s", rows)))
    decoy = peer_at2("NPTS= 7", rows, header=("RECORDED AT DT= 0.005 SEC", "STATION"))
    with pytest.raises(ValueError, match=r"missing DT \(no 'DT=' on the NPTS line, line 3\)"):
        read_at2(write_file(tmp_path, "decoy.AT2", decoy))
    decoy = peer_at2("NPTS= 7, DT= 0.02", rows, header=("RECORDED AT DT= 0.005 SEC", "STATION"))
    assert read_at2(write_file(tmp_path, "decoy2.AT2", decoy)).dt == 0.02


def test_write_at2_writes_a_non_ascii_name_over_an_existing_file(tmp_path):
    path = write_file(tmp_path, "record.AT2", "OLD")
    motion = GroundMotion(np.array(VALUES_G) * G, 0.01, "Tōhoku")
    assert write_at2(motion, path) == path
    assert path.read_text(encoding="utf-8").splitlines()[0] == "GROUND MOTION Tōhoku"
    back = read_at2(path)
    np.testing.assert_allclose(back.acceleration, motion.acceleration, rtol=5e-8)
    assert list(tmp_path.iterdir()) == [path]


def test_a_refused_or_failed_write_at2_never_destroys_the_target(tmp_path, monkeypatch):
    path = write_file(tmp_path, "record.AT2", "OLD CONTENT")
    for name in ("quake NPTS= 5, DT= 0.1", "two\nlines"):
        with pytest.raises(ValueError, match="rename the record"):
            write_at2(GroundMotion([1.0, 2.0], 0.01, name), path)
        assert path.read_bytes() == b"OLD CONTENT"
    with pytest.raises(ValueError, match=r"header line '12 0\.01 NPTS, DT' would be read as the NPTS/DT line"):
        write_at2(GroundMotion([1.0, 2.0], 0.01, "x"), path, header=["12 0.01 NPTS, DT"])
    assert path.read_bytes() == b"OLD CONTENT"

    def fail(source, target):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "replace", fail)
    with pytest.raises(ValueError, match=r"record\.AT2: cannot write \(No space left on device\)"):
        write_at2(GroundMotion([1.0, 2.0], 0.01, "x"), path)
    assert path.read_bytes() == b"OLD CONTENT" and list(tmp_path.iterdir()) == [path]


def test_readers_read_fortran_numbers_and_refuse_ambiguous_ones(tmp_path):
    rows = ["  .1000D+00 -.2500D+00  .3125D+00  .0000D+00-.5000D+00", " 1.25D-01-6.25D-02"]
    motion = read_at2(write_file(tmp_path, "fortran.AT2", peer_at2("    7   0.01000    NPTS, DT", rows)))
    np.testing.assert_array_equal(motion.acceleration, np.array([0.1, -0.25, 0.3125, 0.0, -0.5, 0.125, -0.0625]) * G)
    text = "0.00 1.0D-03\n0.01-.39E-02\n0.02 -.33E-02\n"
    motion = read_two_column(write_file(tmp_path, "fortran.txt", text), unit="m/s2")
    np.testing.assert_array_equal(motion.acceleration, np.array([1.0e-3, -0.39e-2, -0.33e-2]) * 1000.0)
    for token in ("1.0-2", "12.34512.345", "-.39E-02.33E-02x"):  # no unique reading: refused, not guessed
        with pytest.raises(ValueError, match=f"non-numeric value '{re.escape(token)}' on line 5"):
            read_at2(write_file(tmp_path, "ambiguous.AT2", peer_at2("NPTS= 2, DT= 0.01", [f"0.1 {token}"])))


def test_readers_accept_a_bom_crlf_zero_padding_ctrl_z_and_float32_times(tmp_path):
    rows = [" ".join(f"{v:.4f}" for v in VALUES_G[:5]), " ".join(f"{v:.4f}" for v in [*VALUES_G[5:], 0.0, 0.0, 0.0])]
    text = "\ufeff" + peer_at2("NPTS= 7, DT= 0.01", rows).replace("\n", "\r\n") + "\x1a"
    motion = read_at2(write_file(tmp_path, "dos.AT2", text.encode("utf-8")))
    np.testing.assert_array_equal(motion.acceleration, np.array(VALUES_G) * G)
    extra_line = peer_at2("NPTS= 7, DT= 0.01", [*rows, "0.0 0.0"])
    with pytest.raises(ValueError, match="too many values: NPTS = 7 on line 4 but 12 values follow"):
        read_at2(write_file(tmp_path, "extra.AT2", extra_line))  # zeros beyond the last line of values: not padding
    nonzero = peer_at2("NPTS= 6, DT= 0.01", rows)
    with pytest.raises(ValueError, match="too many values"):
        read_at2(write_file(tmp_path, "nonzero.AT2", nonzero))
    times = np.float32(np.arange(12) * 0.01)
    assert f"{times[10]:.8g}" == "0.099999994" or f"{times[10]:.8g}" == "0.1"
    lines = "".join(f"{t:.8g}, {k}\n" for k, t in enumerate(times))
    motion = read_two_column(write_file(tmp_path, "float32.csv", ("\ufeff" + lines).encode("utf-8")), unit="mm/s2")
    np.testing.assert_array_equal(motion.acceleration, np.arange(12.0))
    assert motion.dt == pytest.approx(0.01, rel=1e-6)
    with pytest.raises(ValueError, match="non-uniform time step at line 3"):
        read_two_column(write_file(tmp_path, "uneven.txt", "0 1\n0.01 2\n0.02002 3\n0.03 4\n"))


# --------------------------------------------------------------------------------------------------
# units: the header's (AT2), the argument's (two-column); factors to mm/s^2 by definition of the units


def at2_with_header(tmp_path, header_line: str, count_line: str = "NPTS=      7, DT= .01000 SEC") -> Path:
    rows = [" ".join(f"{v:.7E}" for v in VALUES_G[:5]), " ".join(f"{v:.7E}" for v in VALUES_G[5:])]
    return write_file(tmp_path, "units.AT2", peer_at2(count_line, rows, header=("PEER RECORD", header_line)))


@pytest.mark.parametrize("header_line, factor", [
    ("ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.1 Hz LP=15.0 Hz", G),
    ("The units are (g)", G),
    ("SOME STATION, NO UNIT STATED", G),  # PEER's convention
    ("ACCELERATION TIME HISTORY IN UNITS OF CM/S/S", 10.0),
    ("ACCELERATION IN UNITS OF CM/SEC/SEC.", 10.0),
    ("units of gal", 10.0),
    ("UNITS: m/s^2", 1000.0),
    ("UNITS OF MM/SEC**2", 1.0),
    ("The units are (in/s2)", 25.4),
])
def test_read_at2_converts_the_units_its_header_states(tmp_path, header_line, factor):
    motion = read_at2(at2_with_header(tmp_path, header_line))
    np.testing.assert_allclose(motion.acceleration, np.array(VALUES_G) * factor, rtol=1e-15)


@pytest.mark.parametrize("header_line, expected_mm_s2", [
    # Spellings without the word UNITS, each read once as g (x 9806.65 or x 980.665 too large); the values in
    # the file are 30, -12.5 and 0.25 of the unit the header names, converted here by hand.
    ("ACCELERATION IN CM/S/S", [300.0, -125.0, 2.5]),
    ("ACCELERATION (cm/s2)", [300.0, -125.0, 2.5]),
    ("Acceleration [m/s^2]", [30000.0, -12500.0, 250.0]),
    ("ACCEL. CM/SEC/SEC", [300.0, -125.0, 2.5]),
    ("acceleration (gal)", [300.0, -125.0, 2.5]),
    ("ACCELERATION, cm s-2", [300.0, -125.0, 2.5]),
    ("ACCELERATION IN MM / S / S", [30.0, -12.5, 0.25]),
    ("ACCELERATION [in/sec\u00b2]", [762.0, -317.5, 6.35]),  # 1 in = 25.4 mm
    ("ACCELERATION IN G", [294199.5, -122583.125, 2451.6625]),  # g = 9806.65 mm/s^2
    ("ACCELERATION [g]", [294199.5, -122583.125, 2451.6625]),
    ("ACCELERATION IN G'S", [294199.5, -122583.125, 2451.6625]),
    ("Acceleration (g's)", [294199.5, -122583.125, 2451.6625]),
    ("CHI-CHI 09/20/99, HWA002, N/S (CWB)", [294199.5, -122583.125, 2451.6625]),  # no unit named: g
])
def test_read_at2_reads_units_named_without_the_word_units(tmp_path, header_line, expected_mm_s2):
    text = peer_at2("NPTS= 3, DT= 0.01", ["30.0 -12.5 0.25"], header=("PEER RECORD", header_line))
    motion = read_at2(write_file(tmp_path, "spelled.AT2", text.encode("utf-8")))
    np.testing.assert_allclose(motion.acceleration, expected_mm_s2, rtol=1e-15)


@pytest.mark.parametrize("header_line, problem", [
    ("ACCELERATION [mg]", r"line 2 states units 'mg' .*unknown header unit 'mg'"),
    ("ACCELERATION IN FT/S2", r"line 2 states units 'FT/S2' .*unknown header unit 'FT/S2'"),
    ("Acceleration (ft/sec^2)", r"line 2 states units 'ft/sec\^2' .*unknown header unit"),
    ("ACCELERATION IN CM/S", r"line 2 states units 'CM/S' .*is a unit of velocity"),
    ("ACCELERATION (cm/s2), PEAK 0.3 (g)", r"the header states two units, 'cm/s2' on line 2 and 'g' on line 2"),
    # Read as g (x 1000 and x 100 too large) or as the ratio without its scale (x 100) before the review of issue 29.
    ("Acceleration in milli-g", r"line 2 states units 'milli-g' .*unknown header unit 'milli-g'"),
    ("ACCELERATION IN %G", r"line 2 states units '%G' .*unknown header unit '%G'"),
    ("ACCELERATION (10^-2 m/s2)", r"line 2 states units '10\^-2 m/s2' .*unknown header unit"),
])
def test_read_at2_refuses_a_named_unit_it_cannot_read_rather_than_reading_g(tmp_path, header_line, problem):
    text = peer_at2("NPTS= 3, DT= 0.01", ["30.0 -12.5 0.25"], header=("PEER RECORD", header_line))
    assert_rejected(read_at2, write_file(tmp_path, "unread.AT2", text), problem)


@pytest.mark.parametrize("header_line, problem", [
    ("VELOCITY TIME HISTORY IN UNITS OF CM/SEC", "line 2 says this is a velocity history"),
    ("DISPLACEMENT TIME SERIES IN UNITS OF CM", "line 2 says this is a displacement history"),
    ("IN UNITS OF CM/S", "line 2 states units 'CM/S' .* is a unit of velocity"),
    ("IN UNITS OF FURLONGS/FORTNIGHT", "line 2 states units 'FURLONGS/FORTNIGHT'.* unknown header unit"),
])
def test_read_at2_refuses_other_quantities_and_units_it_cannot_read(tmp_path, header_line, problem):
    assert_rejected(read_at2, at2_with_header(tmp_path, header_line), problem)


def test_read_at2_reads_a_unit_stated_on_the_count_line(tmp_path):
    # Before the review of issue 29 the count line's unit was not looked at and the values were read as g (x 981).
    text = peer_at2("NPTS= 3, DT= 0.01 SEC, UNITS: CM/S2", ["30.0 -12.5 0.25"], header=("PEER RECORD", "STATION"))
    motion = read_at2(write_file(tmp_path, "count.AT2", text))
    np.testing.assert_allclose(motion.acceleration, [300.0, -125.0, 2.5], rtol=1e-15)  # 1 cm = 10 mm
    text = peer_at2("NPTS= 3, DT= 0.01 SEC, UNITS: FT/S2", ["30.0 -12.5 0.25"], header=("PEER RECORD", "STATION"))
    assert_rejected(read_at2, write_file(tmp_path, "feet.AT2", text), r"line 3 states units 'FT/S2'")


def test_read_at2_refuses_a_header_stating_two_units(tmp_path):
    rows = [" ".join(f"{v:.7E}" for v in VALUES_G)]
    text = peer_at2("NPTS= 7, DT= 0.01", rows, header=("UNITS OF CM/S2", "IN UNITS OF G"))
    assert_rejected(read_at2, write_file(tmp_path, "two_units.AT2", text),
                    "the header states two units, 'CM/S2' on line 1 and 'G' on line 2")


@pytest.mark.parametrize("count_line, dt", [
    ("NPTS= 7, DT= 10ms", 0.01), ("NPTS= 7, DT= 10 MS", 0.01), ("NPTS= 7, DT= .01SEC", 0.01),
    ("NPTS= 7, DT= 0.02 s", 0.02), ("NPTS= 7, DT= 0.02 (a remark)", 0.02),
])
def test_read_at2_reads_dt_in_the_time_unit_it_states(tmp_path, count_line, dt):
    assert read_at2(at2_with_header(tmp_path, "IN UNITS OF G", count_line)).dt == pytest.approx(dt, rel=1e-15)


@pytest.mark.parametrize("count_line, unit", [("NPTS= 7, DT= 10min", "min"), ("NPTS= 7, DT= 0.02 MIN", "MIN"),
                                              ("NPTS= 7, DT= 5 us", "us")])
def test_read_at2_refuses_a_dt_unit_it_cannot_read(tmp_path, count_line, unit):
    """Written onto the number or as the next word: a time unit it does not read is refused, not read as s."""
    assert_rejected(read_at2, at2_with_header(tmp_path, "IN UNITS OF G", count_line),
                    f"DT unit '{unit}' on line 3 is not a time unit")


@pytest.mark.parametrize("unit, factor", [("in/s2", 25.4), ("CM/SEC/SEC", 10.0), ("gal", 10.0), ("m/s^2", 1000.0),
                                          ("G", G)])
def test_read_two_column_reads_every_spelling_of_its_units(tmp_path, unit, factor):
    motion = read_two_column(write_file(tmp_path, "two.txt", "0 0.5\n0.01 -0.25\n"), unit=unit)
    np.testing.assert_allclose(motion.acceleration, np.array([0.5, -0.25]) * factor, rtol=1e-15)


@pytest.mark.parametrize("unit, problem", [("cm/s", "unit 'cm/s' is a unit of velocity"),
                                           ("m", "unit 'm' is a unit of displacement"),
                                           (9.81, "unit must be a string")])
def test_read_two_column_refuses_units_that_are_not_accelerations(tmp_path, unit, problem):
    with pytest.raises(ValueError, match=problem):
        read_two_column(write_file(tmp_path, "two.txt", "0 0.5\n0.01 -0.25\n"), unit=unit)


@pytest.mark.parametrize("header", [["ACCELERATION IN UNITS OF CM/S2"], ["VELOCITY TIME HISTORY"],
                                    ["ACCELERATION (cm/s2)"], ["PEAK 0.3 (g)"]])
def test_write_at2_refuses_a_header_line_that_would_be_read_as_units(tmp_path, header):
    motion = GroundMotion(np.array(VALUES_G) * G, 0.01, "rt")
    with pytest.raises(ValueError, match="would be read as a statement of the file's units or quantity"):
        write_at2(motion, tmp_path / "x.AT2", header=header)
    assert not (tmp_path / "x.AT2").exists()
