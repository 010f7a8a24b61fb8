"""The data of Xu, Li & Shen (2016), "Fractional-derivative Maxwell Kelvin model for '5+4' viscoelastic
damping wall subjected to large deformation", as printed, and the parameter sets this package recommends.

Printed data (values exactly as in the paper, in the paper's units)
-------------------------------------------------------------------
``TABLES[strain]`` for strain = 225, 300, 450 (%; Tables 1, 2, 3, all at 21.2 degC), one numpy array
(read-only) per column, in the order of ``FREQUENCIES`` (Hz):

    storage_modulus      G'    MPa
    loss_modulus         G''   MPa
    loss_factor          the column printed as "eta (MPa*s)"; its values are G''/G' (dimensionless)
    storage_stiffness    K'_d  **kN/mm**   (not N/mm: numerically equal to G' in MPa, see the report)
    loss_stiffness       K''_d **kN/mm**
    damping_coefficient  C_d   **kN*s/mm** (as printed; it is not K''_d / omega, see the report)

``COLUMN_UNITS`` repeats these units.  ``TABLE4`` holds the paper's "best-fitting parameters" (MPa,
MPa*s^r, -), ``TABLE5`` its loop areas (kN*mm) and their differences Delta (%, eq. (13)).

The printed closed forms (NOT the model)
----------------------------------------
:func:`printed_eq7_modulus` and :func:`printed_eq8_moduli` to :func:`printed_eq11_damping_coefficient`
transcribe eqs. (6b)/(7) and (8)-(11) as printed.  They do not follow from the model's defining
eqs. (3)-(5) (:class:`~vdw_frames.element.damper.FDMKDamper` implements those); they are here only so that
:mod:`vdw_frames.paper.report` can show what Table 4 gives under them.  Do not use them for anything else.

Recommended parameter sets
--------------------------
:func:`fitted` returns this package's identification (:func:`vdw_frames.paper.identification.identify`) of each
strain level's Tables 1-3 data, never the paper's Table 4 (which reproduces none of the tables, under
the model or under the printed formulas).  The objective is the paper's (12) with **relative**
residuals: sum over the six frequencies of ((G'_model - G'_test)/G'_test)^2 + ((G''_model -
G''_test)/G''_test)^2.  Why relative: at 300 % and 450 % strain G'' is 3.5-12 times smaller than G',
so the absolute sum of squares all but ignores G'' -- the absolute fits miss G'' by up to 46 % and 50 %
-- although G'' is what sets the energy a damper dissipates (loop area pi K'' U^2).  Relative residuals
weigh both moduli by their percentage error and cut the worst G'' error to 16 % and 6 % while the
worst G' error rises from 22 % to 30 % and from 17 % to 27 %.  At 225 % neither objective can follow
the measured fall of G' with frequency (a passive linear model's G' cannot fall, see the report); the
relative set misses G' by up to 79 % there and G'' by up to 34 % (absolute: 61 % and 63 %).

Fit quality (``FIT_QUALITY``; relative SSE, max |relative error| in G' and G'' over 0.5-10 Hz):

    225 %:  SSE 1.520,  G' 78.6 %,  G'' 34.3 %   (G1 = 0 and r = 1 on their bounds)
    300 %:  SSE 0.3213, G' 29.6 %,  G'' 15.7 %   (G1 = 0 on its bound)
    450 %:  SSE 0.1579, G' 27.0 %,  G''  6.0 %

``tests/paper/test_data.py`` re-runs the identification and checks that it reproduces the stored numbers.

Cautions (numbers in the report, ``vdw-frames paper-report``):

* Geometry: the default A = 1e6 mm^2 and h = 10 mm are the paper's stated values (A/h = 1e5 mm), but its
  printed K'_d = G' implies A/h = 1000 mm and its measured loop areas imply A/h = 1430-2920 mm: a damper
  built with the stated A and h is 34-100 times stronger than the tested wall.  The moduli are what the
  identification determines; pass the ``area`` and ``thickness`` of the wall you design.
* The 225 % set is a viscoelastic fluid (G1 = 0, r = 1): no static stiffness.
* The data determine the moduli over 0.5-10 Hz better than the parameters: at 450 % pinning r anywhere in
  0.1-0.6 raises the relative sum by at most 1.3 %, so r (and the split between the branches) is barely
  determined there; outside 0.5-10 Hz the sets are extrapolations.

Strain range (``FIT_RANGE``, % shear strain): each set is assigned the strain amplitudes nearer to its
test strain than to another one -- boundaries at the midpoints 262.5 % and 375 % -- and no further
than the tested envelope 225-450 %: 225 % -> [225, 262.5], 300 % -> [262.5, 375], 450 % -> [375, 450].
The data say nothing below 225 % or above 450 % (and the moduli change strongly with strain: G' at
0.5-10 Hz is 0.96-2.65 MPa at 225 % but 2.65-3.54 MPa at 450 %), so the outer ends are not open: a
simulation whose peak strain leaves the interval is extrapolating and is warned about it.  One model
over the whole range, for strain-compatible analyses: :func:`vdw_frames.paper.strain_dependence.strain_dependent`.
"""

from __future__ import annotations

from collections import namedtuple
from collections.abc import Sequence
from typing import TypedDict

import numpy as np
from numpy.typing import ArrayLike

from .._warnings import keyword_only_since_0_3

# The recommended sets live in the element's catalogue (a building file reads them without the identification);
# their names here are the same objects.
from ..element.catalogue import AREA, FIT_RANGE, FITTED, STRAINS, THICKNESS, fitted
from ..element.catalogue import strain_key as _strain_key

__all__ = [
    "AREA", "COLUMN_UNITS", "FITTED", "FIT_QUALITY", "FIT_RANGE", "FREQUENCIES", "RECOMMENDED_RESIDUAL", "STRAINS",
    "TABLE4", "TABLE5", "TABLES", "TEMPERATURE", "THICKNESS", "Table5Row", "fitted", "printed_eq7_modulus",
    "printed_eq8_moduli", "printed_eq9_loss_factor", "printed_eq10_stiffness", "printed_eq11_damping_coefficient",
    "table_moduli",
]

FREQUENCIES = np.array([0.5, 1.0, 1.5, 2.0, 5.0, 10.0])  # Hz
TEMPERATURE = 21.2  # degC

COLUMN_UNITS = {
    "storage_modulus": "MPa",
    "loss_modulus": "MPa",
    "loss_factor": "- (printed header: eta (MPa*s))",
    "storage_stiffness": "kN/mm",
    "loss_stiffness": "kN/mm",
    "damping_coefficient": "kN*s/mm",
}


def _frozen(values: ArrayLike) -> np.ndarray:
    array = np.array(values, dtype=float)
    array.flags.writeable = False
    return array


def _table(storage: Sequence[float], loss: Sequence[float], factor: Sequence[float], storage_k: Sequence[float],
           loss_k: Sequence[float], damping: Sequence[float]) -> dict[str, np.ndarray]:
    columns = zip(COLUMN_UNITS, (storage, loss, factor, storage_k, loss_k, damping), strict=True)
    return {name: _frozen(values) for name, values in columns}


TABLES = {
    225: _table([2.65, 1.79, 1.34, 1.16, 1.00, 0.96], [0.76, 1.05, 0.85, 0.89, 0.91, 0.94],
                [0.29, 0.59, 0.63, 0.77, 0.91, 0.98], [2.65, 1.79, 1.34, 1.16, 1.00, 0.96],
                [0.76, 1.05, 0.85, 0.89, 0.91, 0.94], [1.52, 0.70, 0.57, 0.45, 0.40, 0.38]),
    300: _table([2.36, 2.69, 1.89, 2.43, 2.20, 2.10], [0.67, 0.63, 0.63, 0.62, 0.61, 0.50],
                [0.29, 0.23, 0.33, 0.26, 0.28, 0.24], [2.36, 2.69, 1.89, 2.43, 2.20, 2.10],
                [0.67, 0.63, 0.63, 0.62, 0.61, 0.50], [1.34, 0.42, 0.42, 0.31, 0.28, 0.25]),
    450: _table([3.54, 3.20, 2.89, 2.72, 2.71, 2.65], [0.29, 0.29, 0.32, 0.33, 0.34, 0.36],
                [0.08, 0.09, 0.11, 0.12, 0.13, 0.14], [3.54, 3.20, 2.89, 2.72, 2.71, 2.65],
                [0.29, 0.29, 0.32, 0.33, 0.34, 0.36], [0.58, 0.19, 0.21, 0.17, 0.16, 0.11]),
}

class _Parameters(TypedDict):
    """FDMK parameters by name: G1, G2 (MPa), eta1, eta2 (MPa*s^r), r (-)."""

    G1: float
    G2: float
    eta1: float
    eta2: float
    r: float


TABLE4: _Parameters = {"G1": 8.69, "G2": 3.58, "eta1": 0.75, "eta2": 0.98, "r": 0.60}  # MPa, MPa, MPa*s^r, MPa*s^r, -

Table5Row = namedtuple("Table5Row", "frequency strain theoretical experimental delta")
Table5Row.__doc__ = "One row of Table 5: Hz, %, kN*mm, kN*mm, % (Delta of eq. (13), as printed)."
TABLE5 = (
    Table5Row(0.5, 225, 2279.0, 2413.0, 5.6),
    Table5Row(1.5, 225, 2104.0, 2249.0, 6.9),
    Table5Row(0.5, 300, 2849.0, 2826.0, 0.8),
    Table5Row(1.5, 300, 2445.0, 2540.0, 3.7),
    Table5Row(0.5, 450, 5240.0, 5394.0, 2.9),
    Table5Row(1.5, 450, 4427.0, 4530.0, 2.3),
)


def table_moduli(strain: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(FREQUENCIES in Hz, G' in MPa, G'' in MPa) of the table for ``strain`` (225, 300 or 450 %)."""
    table = TABLES[_strain_key(strain)]
    return FREQUENCIES, table["storage_modulus"], table["loss_modulus"]


# ---------------------------------------------------------------------------- recommended parameter sets
RECOMMENDED_RESIDUAL = "relative"

# FITTED (identify(*table_moduli(strain), residual="relative").params): vdw_frames.element.catalogue.

FIT_QUALITY = {  # relative SSE, max |relative error| of G' and of G'' over the six frequencies
    225: {"sse": 1.5199190989974034, "storage": 0.7857779085933676, "loss": 0.3433724128570297},
    300: {"sse": 0.3213029904399966, "storage": 0.2961850942681107, "loss": 0.1566195980277456},
    450: {"sse": 0.15788682990806244, "storage": 0.26963071379193315, "loss": 0.05994714816674129},
}



# ------------------------------------------------------------ the printed closed forms: NOT the model
def printed_eq7_modulus(omega: ArrayLike, G1: float, G2: float, eta1: float, eta2: float, r: float) -> np.ndarray:
    """sigma~/eps~ of the printed eq. (7) (= eq. (6b) with D^r -> (i omega)^r), complex, omega in rad/s.

    NOT the model: (6b) does not follow from eqs. (3)-(5) (see :mod:`vdw_frames.paper.report`).
    """
    x = (1j * np.asarray(omega, dtype=float)) ** r
    numerator = G2 * eta1 * eta2 * x * (G1 + eta1 * x)
    denominator = (G1 * eta2 + eta1 * eta2 * x) * (G2 * eta2 + eta2**2 * x) + G2 * eta2**2 * x
    return numerator / denominator


def printed_eq8_moduli(omega: ArrayLike, G1: float, G2: float, eta1: float, eta2: float,
                       r: float) -> tuple[np.ndarray, np.ndarray]:
    """(G', G'') of the printed eq. (8), omega in rad/s.  NOT the model."""
    a = np.asarray(omega, dtype=float) ** r
    c, q = np.cos(r * np.pi / 2), np.sin(r * np.pi / 2)
    storage = (G1 * G2 * eta2**2 * a * q + G2 * eta2 * eta1**2 * a * np.sin(r * np.pi)) / np.cos(r * np.pi)
    loss = (G1 * G2 * eta2 * eta1 * a * c + G2 * eta1 * eta2**2 * a * c + a**2 * c) / np.sin(r * np.pi)
    return storage, loss


def printed_eq9_loss_factor(omega: ArrayLike, G1: float, G2: float, eta1: float, eta2: float, r: float) -> np.ndarray:
    """The printed eq. (9): G''/G' of eq. (8).  NOT the model."""
    storage, loss = printed_eq8_moduli(omega, G1, G2, eta1, eta2, r)
    return loss / storage


@keyword_only_since_0_3
def printed_eq10_stiffness(omega: ArrayLike, G1: float, G2: float, eta1: float, eta2: float, r: float, *,
                           area: float = AREA, thickness: float = THICKNESS) -> tuple[np.ndarray, np.ndarray]:
    """(K'_d, K''_d) of the printed eq. (10) = eq. (8) * A / h, in N/mm for A in mm^2, h in mm.  NOT the model."""
    storage, loss = printed_eq8_moduli(omega, G1, G2, eta1, eta2, r)
    return storage * area / thickness, loss * area / thickness


@keyword_only_since_0_3
def printed_eq11_damping_coefficient(omega: ArrayLike, G1: float, G2: float, eta1: float, eta2: float, r: float, *,
                                     area: float = AREA, thickness: float = THICKNESS) -> np.ndarray:
    """C_d of the printed eq. (11) = K''_d(10) / omega, in N*s/mm.  NOT the model."""
    loss = printed_eq10_stiffness(omega, G1, G2, eta1, eta2, r, area=area, thickness=thickness)[1]
    return loss / np.asarray(omega, dtype=float)
