"""Design verification of a building with walls as ASCE 7-16 asks: the site's MCE_R spectrum (Sec. 11.4),
the selection and amplitude scaling of a suite of records (Sec. 16.2), the analyses at nominal, upper- and
lower-bound wall properties (Sec. 18.2.4.5 as read from secondary sources), the acceptance of Sec. 16.4 and the
device test demands of Sec. 18.6.

- :mod:`.spectrum`: :class:`Site`, :func:`mce_spectrum`, :func:`site_coefficients` (Tables 11.4-1, 11.4-2);
- :mod:`.suite`: :func:`period_range` and :func:`scaled_suite` (Sec. 16.2.3), :class:`ScaledSuite`;
- :mod:`.verify`: :func:`verify`, :class:`PropertyBounds`, :class:`VerificationResult` (acceptance of
  Sec. 16.4, :class:`WallDemand` per wall, the prototype test specification).

ASCE 7-16 itself was not at hand when this was written: every clause, table and rule here was read from
secondary sources (transcriptions, implementers' code, the committee chair's slides), as each docstring says.

Units: spectral accelerations in g where the standard tabulates them (else mm/s^2), periods s, N, mm, s.
"""

from ..asce7.elf import RISK_CATEGORIES
from .spectrum import SITE_CLASSES, Site, mce_spectrum, site_coefficients, site_from_values
from .suite import PeriodRange, ScaledSuite, period_range, scaled_suite
from .verify import (
    Criterion,
    DeviceDemand,
    PropertyBounds,
    VerificationResult,
    WallDemand,
    composed_factors,
    stiffness_factors,
    verify,
)

__all__ = ["RISK_CATEGORIES", "SITE_CLASSES", "Criterion", "DeviceDemand", "PeriodRange", "PropertyBounds",
           "ScaledSuite", "Site", "VerificationResult", "WallDemand", "composed_factors", "mce_spectrum",
           "period_range", "scaled_suite", "site_coefficients", "site_from_values", "stiffness_factors", "verify"]
