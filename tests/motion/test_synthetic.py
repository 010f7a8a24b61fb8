"""The synthetic record (vdw_frames.motion.synthetic): seeded, shaped by its ground filter, and the shipped default
record is what ground_motions/make_records.py writes."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest
from shared_data import REPO

from vdw_frames import motion as gm
from vdw_frames.motion import G


def test_synthetic_ground_motion_is_seeded():
    first = gm.synthetic_ground_motion(duration=5.0, dt=0.01, pga=0.2 * G, seed=7)
    again = gm.synthetic_ground_motion(duration=5.0, dt=0.01, pga=0.2 * G, seed=7)
    other = gm.synthetic_ground_motion(duration=5.0, dt=0.01, pga=0.2 * G, seed=8)
    np.testing.assert_array_equal(first.acceleration, again.acceleration)
    assert not np.array_equal(first.acceleration, other.acceleration)
    assert first.acceleration.size == 501 and first.duration == pytest.approx(5.0)
    assert first.pga == pytest.approx(0.2 * G, rel=1e-12)
    assert first.acceleration[0] == 0.0  # the envelope starts at 0
    with pytest.raises(ValueError, match=r"ground_frequency = 60\.0 Hz must be below the Nyquist frequency 50\.0 Hz"):
        gm.synthetic_ground_motion(ground_frequency=60.0)


def test_synthetic_ground_motion_spectrum_follows_the_ground_filter():
    # Kanai-Tajimi filter at 2.5 Hz, damping 0.6: the Fourier amplitude peaks near 2.5 Hz, not at 10 Hz.
    motion = gm.synthetic_ground_motion(duration=40.0, dt=0.01, seed=3, strong_motion_end=35.0)
    amplitude = np.abs(np.fft.rfft(motion.acceleration))
    frequency = np.fft.rfftfreq(motion.acceleration.size, motion.dt)
    band = lambda low, high: amplitude[(frequency >= low) & (frequency < high)].mean()  # noqa: E731
    assert band(1.5, 3.5) > 2.0 * band(9.0, 11.0)
    assert band(1.5, 3.5) > 3.0 * band(0.0, 0.1)  # the high-pass filter removes the drift at 0 Hz


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
