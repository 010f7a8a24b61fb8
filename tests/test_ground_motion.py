"""Ground motions: AT2 and two-column readers, scaling, resampling, response spectrum, synthetic record."""

from __future__ import annotations

import importlib.util
import math
import re
from pathlib import Path

import numpy as np
import pytest
from scipy import signal
from shared_data import REPO, shared_record

from vdw_frames import motion as gm
from vdw_frames.motion import G, GroundMotion

# From the table in ../shared/ground_motions/README.md: file -> (NPTS, DT s).
SHARED_RECORDS = {
    "IELC180.AT2": (4000, 0.01),
    "elCentro.AT2": (1559, 0.02),
    "ARL360.at2": (2000, 0.02),
    "RIO270.AT2": (1800, 0.02),
    "HWA002-N.AT2": (20000, 0.004),
}


shared = shared_record


def independent_values(path: Path) -> list[float]:
    """The numbers after the line holding NPTS, parsed here without the package (in g)."""
    lines = path.read_bytes().decode("ascii").replace("\r", "\n").split("\n")
    count_line = next(i for i, line in enumerate(lines) if "NPTS" in line)
    return [float(token) for line in lines[count_line + 1:] for token in line.split()]


def sdof_peak_lsim(motion: GroundMotion, period: float, damping_ratio: float) -> float:
    """omega^2 max|u| from scipy.signal.lsim (matrix exponential, linear input interpolation)."""
    omega = 2.0 * math.pi / period
    system = signal.StateSpace([[0.0, 1.0], [-omega**2, -2.0 * damping_ratio * omega]], [[0.0], [-1.0]],
                               [[1.0, 0.0]], [[0.0]])
    _, displacement, _ = signal.lsim(system, motion.acceleration, motion.time)
    return omega**2 * np.max(np.abs(displacement))


# --------------------------------------------------------------------------------------------------
# read_at2 on the real records


@pytest.mark.parametrize("file_name", sorted(SHARED_RECORDS))
def test_read_at2_shared_records(file_name):
    path = shared(file_name)
    npts, dt = SHARED_RECORDS[file_name]
    motion = gm.read_at2(path)
    expected = independent_values(path)
    assert motion.name == Path(file_name).stem
    assert motion.acceleration.size == npts == len(expected)
    assert motion.dt == dt
    assert motion.acceleration[0] == pytest.approx(expected[0] * 9806.65, rel=1e-15)
    assert motion.acceleration[-1] == pytest.approx(expected[-1] * 9806.65, rel=1e-15)
    assert motion.pga == pytest.approx(max(abs(value) for value in expected) * 9806.65, rel=1e-15)
    assert motion.duration == pytest.approx((npts - 1) * dt, rel=1e-12)


def test_read_at2_known_values():
    motion = gm.read_at2(shared("IELC180.AT2"))
    assert motion.acceleration[0] == pytest.approx(-0.6403182e-02 * 9806.65, rel=1e-15)
    assert motion.acceleration[4] == pytest.approx(0.6890377e-02 * 9806.65, rel=1e-15)
    assert motion.pga / G == pytest.approx(0.3129, abs=5e-5)  # El Centro 1940, 180: PGA 0.313 g
    elcentro = gm.read_at2(shared("elCentro.AT2"))
    assert elcentro.acceleration[:3] == pytest.approx(np.array([0.00630, 0.00364, 0.00099]) * G, rel=1e-15)


# --------------------------------------------------------------------------------------------------
# read_at2 on variants written here

VALUES = [0.1, -0.25, 0.3125, 0.0, -0.5, 0.125, 0.0625]


def write(tmp_path, text: str, name: str = "record.AT2", newline: str = "\n") -> Path:
    path = tmp_path / name
    path.write_bytes(text.replace("\n", newline).encode("ascii"))
    return path


def at2_text(count_line: str = "NPTS=     7, DT= .01000 SEC", values=None) -> str:
    values = VALUES if values is None else values
    rows = ["".join(f"{value:>15}" for value in values[i:i + 5]) for i in range(0, len(values), 5)]
    return "\n".join(["PEER STRONG MOTION DATABASE RECORD.", "SOME EVENT, SOME STATION, 000",
                      "ACCELERATION TIME HISTORY IN UNITS OF G", count_line, *rows]) + "\n"


@pytest.mark.parametrize("newline", ["\n", "\r\n", "\r\r\n", "\r"])
def test_read_at2_line_ends(tmp_path, newline):
    motion = gm.read_at2(write(tmp_path, at2_text(), newline=newline))
    np.testing.assert_array_equal(motion.acceleration, np.array(VALUES) * G)
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
    (at2_text(values=VALUES[:3] + ["0.1x"] + VALUES[4:]), r"non-numeric value '0\.1x' on line 5"),
    (at2_text(values=VALUES[:6] + ["1.0-2"]), "non-numeric value '1.0-2' on line 6"),  # E-less exponent?
    (at2_text(values=VALUES[:6] + ["nan"]), "non-finite value 'nan' on line 6"),
    (at2_text(values=["-inf"] + VALUES[1:]), "non-finite value '-inf' on line 5"),
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
# GroundMotion


def test_ground_motion_properties_and_validation():
    motion = GroundMotion([0.0, 3.0, -4.0, 1.0], 0.02, name="m")
    np.testing.assert_allclose(motion.time, [0.0, 0.02, 0.04, 0.06], rtol=1e-15)
    assert motion.pga == 4.0
    assert motion.duration == pytest.approx(0.06, rel=1e-15)
    with pytest.raises(ValueError):
        motion.acceleration[0] = 1.0  # read-only
    source = np.array([1.0, 2.0])
    copy = GroundMotion(source, 0.1)
    source[0] = 99.0
    assert copy.acceleration[0] == 1.0
    for bad, match in [(dict(acceleration=[1.0, np.nan]), r"acceleration must be finite, got .*nan.* at index 1"),
                       (dict(acceleration=[]), "at least 2 samples, got 0"),
                       (dict(acceleration=[3.0]), "at least 2 samples, got 1"),
                       (dict(acceleration=[1.0, 2.0 + 1.0j]), "acceleration must be real"),
                       (dict(acceleration=[[1.0]]), "1-dimensional"),
                       (dict(dt=0.0), r"dt must be > 0, got 0\.0"),
                       (dict(dt=np.inf), "dt must be finite"),
                       (dict(dt="x"), "dt must be a real number")]:
        arguments = dict(acceleration=[1.0, 2.0], dt=0.01) | bad
        with pytest.raises(ValueError, match=match):
            GroundMotion(**arguments)


def test_scaling_to_pga():
    motion = gm.read_at2(shared("RIO270.AT2"))
    target = 0.4 * G
    scaled = motion.scaled_to_pga(target)
    assert scaled.pga == pytest.approx(target, rel=1e-12)
    assert scaled.name == motion.name and scaled.dt == motion.dt
    factor = motion.scale_factor_to_pga(target)
    np.testing.assert_allclose(scaled.acceleration, motion.acceleration * factor, rtol=1e-15)
    assert factor == pytest.approx(0.4 / (max(abs(v) for v in independent_values(shared("RIO270.AT2")))),
                                   rel=1e-12)
    np.testing.assert_array_equal(motion.scaled(-2.0).acceleration, -2.0 * motion.acceleration)
    with pytest.raises(ValueError, match="target PGA must be > 0"):
        motion.scaled_to_pga(0.0)
    with pytest.raises(ValueError, match="factor must be finite"):
        motion.scaled(np.nan)
    with pytest.raises(ValueError, match="its PGA is 0"):
        GroundMotion(np.zeros(3), 0.01, "quiet").scaled_to_pga(G)


def test_scaling_to_spectral_acceleration():
    motion = gm.read_at2(shared("ARL360.at2"))
    target, period = 0.8 * G, 0.7
    scaled = motion.scaled_to_spectral_acceleration(target, period, damping_ratio=0.03)
    assert float(scaled.spectrum(period, 0.03)) == pytest.approx(target, rel=1e-12)
    factor = motion.scale_factor_to_spectral_acceleration(target, period, 0.03)
    assert factor == pytest.approx(target / sdof_peak_lsim(motion, period, 0.03), rel=1e-8)
    assert motion.scale_factor_to_spectral_acceleration(G, 0.0) == pytest.approx(G / motion.pga, rel=1e-15)


def test_resampling_is_linear_interpolation():
    ramp = GroundMotion(3.0 + 7.0 * np.arange(11), 0.02, "ramp")
    fine = ramp.resampled(0.005)
    assert fine.acceleration.size == 41 and fine.dt == 0.005 and fine.name == "ramp"
    np.testing.assert_allclose(fine.acceleration, 3.0 + 7.0 * fine.time / 0.02, rtol=1e-14)
    np.testing.assert_allclose(ramp.acceleration_at(0.02 / 3), 3.0 + 7.0 * np.arange(31) / 3, rtol=1e-14)
    wiggle = GroundMotion([0.0, 4.0, -2.0], 0.1)
    np.testing.assert_allclose(wiggle.acceleration_at(0.025), [0, 1, 2, 3, 4, 2.5, 1, -0.5, -2], atol=1e-14)
    np.testing.assert_array_equal(wiggle.acceleration_at(0.1 * (1 + 1e-10)), wiggle.acceleration)


@pytest.mark.parametrize("dt, problem", [
    (0.015, "does not divide"), (0.0066, "does not divide"), (0.02 / 3 * (1 + 1e-5), "does not divide"),
    (0.04, "is larger than"), (0.0, "dt must be > 0"), (np.nan, "dt must be finite"),
])
def test_resampling_rejects(dt, problem):
    motion = GroundMotion([0.0, 1.0, 0.0], 0.02)
    with pytest.raises(ValueError, match=problem) as error:
        motion.resampled(dt)
    if "divide" in problem or "larger" in problem:
        assert repr(dt) in str(error.value) and "0.02" in str(error.value)


# --------------------------------------------------------------------------------------------------
# response spectrum


def test_response_spectrum_against_lsim():
    motion = gm.read_at2(shared("IELC180.AT2"))
    periods = np.array([0.1, 0.3, 1.0, 3.0])
    for damping_ratio in (0.0, 0.05, 0.2):
        spectrum = motion.spectrum(periods, damping_ratio)
        reference = [sdof_peak_lsim(motion, period, damping_ratio) for period in periods]
        np.testing.assert_allclose(spectrum, reference, rtol=1e-8)


def test_response_spectrum_resonant_harmonic_steady_state():
    # a_g = A sin(w t) at w = w_n: the steady response u = A / (2 zeta w^2) cos(w t) peaks at the
    # samples (T a multiple of dt); the linearly interpolated input has gain sinc^2(w dt / 2) at w.
    dt, period, zeta, amplitude = 0.01, 1.0, 0.05, 1000.0
    omega = 2.0 * math.pi / period
    time = np.arange(6001) * dt  # 60 s: the transient has decayed by exp(-zeta w 60) ~ 6e-9
    motion = GroundMotion(amplitude * np.sin(omega * time), dt)
    expected = amplitude / (2.0 * zeta) * np.sinc(omega * dt / (2.0 * math.pi)) ** 2
    assert float(motion.spectrum(period, zeta)) == pytest.approx(expected, rel=1e-6)


def test_response_spectrum_limits_and_shape():
    motion = gm.read_at2(shared("elCentro.AT2"))
    spectrum = motion.spectrum([[0.0, 1e-4], [0.5, 1.0]])
    assert spectrum.shape == (2, 2)
    assert spectrum[0, 0] == motion.pga
    assert spectrum[0, 1] == pytest.approx(motion.pga, rel=1e-3)  # rigid oscillator follows the ground
    assert float(motion.spectrum(2.0)) == pytest.approx(sdof_peak_lsim(motion, 2.0, 0.05), rel=1e-8)
    for periods, damping_ratio, match in [([-1.0], 0.05, "periods must be >= 0"),
                                          ([np.nan], 0.05, "periods must be finite"),
                                          ([1.0], 1.0, r"damping_ratio must lie in \[0, 1\), got 1\.0"),
                                          ([1.0], -0.1, "damping_ratio must lie in")]:
        with pytest.raises(ValueError, match=match):
            motion.spectrum(periods, damping_ratio)


# --------------------------------------------------------------------------------------------------
# synthetic record, writing, the shipped default


def test_synthetic_ground_motion_is_seeded():
    first = gm.synthetic_ground_motion(duration=5.0, dt=0.01, pga=0.2 * G, seed=7)
    again = gm.synthetic_ground_motion(duration=5.0, dt=0.01, pga=0.2 * G, seed=7)
    other = gm.synthetic_ground_motion(duration=5.0, dt=0.01, pga=0.2 * G, seed=8)
    np.testing.assert_array_equal(first.acceleration, again.acceleration)
    assert not np.array_equal(first.acceleration, other.acceleration)
    assert first.acceleration.size == 501 and first.duration == pytest.approx(5.0)
    assert first.pga == pytest.approx(0.2 * G, rel=1e-12)
    assert first.acceleration[0] == 0.0  # the envelope starts at 0
    with pytest.raises(ValueError, match="ground_frequency = 60.0 Hz must be below the Nyquist frequency 50.0 Hz"):
        gm.synthetic_ground_motion(ground_frequency=60.0)


def test_synthetic_ground_motion_spectrum_follows_the_ground_filter():
    # Kanai-Tajimi filter at 2.5 Hz, damping 0.6: the Fourier amplitude peaks near 2.5 Hz, not at 10 Hz.
    motion = gm.synthetic_ground_motion(duration=40.0, dt=0.01, seed=3, strong_motion_end=35.0)
    amplitude = np.abs(np.fft.rfft(motion.acceleration))
    frequency = np.fft.rfftfreq(motion.acceleration.size, motion.dt)
    band = lambda low, high: amplitude[(frequency >= low) & (frequency < high)].mean()  # noqa: E731
    assert band(1.5, 3.5) > 2.0 * band(9.0, 11.0)
    assert band(1.5, 3.5) > 3.0 * band(0.0, 0.1)  # the high-pass filter removes the drift at 0 Hz


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


def test_shipped_default_record_is_what_make_records_writes(tmp_path):
    path = gm.default_record_path()
    assert path.resolve() == (REPO / "vdw_frames" / "motion" / "data" / "synthetic_kt_035g.AT2").resolve()
    shipped = gm.read_at2(path)
    assert shipped.name == "synthetic_kt_035g"
    assert (shipped.acceleration.size, shipped.dt) == (2501, 0.01)
    assert shipped.pga == pytest.approx(0.35 * 9806.65, rel=1e-12)
    assert "SYNTHETIC" in path.read_text().splitlines()[0]

    spec = importlib.util.spec_from_file_location("make_records", REPO / "ground_motions" / "make_records.py")
    make_records = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(make_records)
    (regenerated_path,) = make_records.write_records(tmp_path)
    assert regenerated_path.name == path.name
    regenerated = gm.read_at2(regenerated_path)
    assert regenerated.dt == shipped.dt
    # to file precision: 8 significant digits, so at most one unit of the last digit apart
    np.testing.assert_allclose(regenerated.acceleration, shipped.acceleration, rtol=1e-7, atol=1e-9)


def test_default_record_path_joins_one_name_at_a_time(monkeypatch):
    """Python 3.10's ``Traversable.joinpath`` takes one name (several only from 3.11): the shipped record's
    path must be found through that contract (mypy for Python 3.10 flagged ``joinpath("data", name)``)."""
    from vdw_frames.motion import synthetic

    package = synthetic.resources.files(synthetic.__package__)

    class OneNameTraversable:
        def __init__(self, path):
            self.path = path

        def joinpath(self, child):
            return OneNameTraversable(self.path.joinpath(child))

        def __str__(self):
            return str(self.path)

    monkeypatch.setattr(synthetic.resources, "files", lambda anchor: OneNameTraversable(package))
    path = gm.default_record_path()
    assert path == Path(str(package)) / "data" / synthetic.DEFAULT_RECORD
    assert path.is_file()
