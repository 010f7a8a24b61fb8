"""The site and its target spectrum: ASCE 7-16 Sec. 11.4 (site coefficients, MCE_R response spectrum).

Equations (ASCE 7-16 Sec. 11.4.4-11.4.7):

* Eq. 11.4-1 S_MS = F_a S_S and Eq. 11.4-2 S_M1 = F_v S_1 (Sec. 11.4.4), F_a from Table 11.4-1 and F_v from
  Table 11.4-2 with straight-line interpolation between the tabulated columns (the notes under the tables);
* Eq. 11.4-3 S_DS = 2/3 S_MS and Eq. 11.4-4 S_D1 = 2/3 S_M1 (Sec. 11.4.5);
* the design response spectrum (Sec. 11.4.6, Fig. 11.4-1) with T_0 = 0.2 S_D1 / S_DS and T_S = S_D1 / S_DS:
  S_a = S_DS (0.4 + 0.6 T / T_0) for T < T_0 (Eq. 11.4-5), S_a = S_DS for T_0 <= T <= T_S,
  S_a = S_D1 / T for T_S < T <= T_L (Eq. 11.4-6), S_a = S_D1 T_L / T^2 for T > T_L (Eq. 11.4-7);
* the MCE_R response spectrum is 1.5 times the design spectrum (Sec. 11.4.7): the same branches with S_MS and
  S_M1 in place of S_DS and S_D1 (T_0 and T_S are unchanged by the factor).

Sources of the numbers (ASCE 7-16 itself was not at hand: read from secondary sources): Tables
11.4-1 and 11.4-2 and the equations are as transcribed by the USGS design-maps code (usgs/earthquake-design-ws,
``site-amplification.json`` key "ASCE7-16") and two other transcriptions that agree on every numeric cell.  In
ASCE 7-16 the cells of Site Class E at S_S >= 1.0 and S_1 >= 0.2 and all of Site Class F print "See Section
11.4.8" instead of a number (the transcriptions disagree on the E row at S_1 >= 0.2); those are refused here.

Sec. 11.4.8 requires a ground motion hazard analysis (Chapter 21) for structures with damping systems on sites
with S_1 >= 0.6, for Site Class E with S_S >= 1.0 and for Site Class D and E with S_1 >= 0.2 (its exceptions are
not available to structures with damping systems, and concern the equivalent lateral force procedure anyway);
Site Class F needs a site response analysis (Sec. 21.1).  :meth:`Site.from_mapped` refuses those cases, naming
the clause: give S_MS and S_M1 from the site-specific procedure to :class:`Site` directly.

Units: spectral values in g (as the standard tabulates them), periods s; :meth:`Site.spectral_acceleration`
returns mm/s^2 (g = 9806.65 mm/s^2).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .._validation import finite_array, non_negative, positive, show
from ..asce7.elf import risk_category
from ..motion.record import G

SITE_CLASSES = ("A", "B", "C", "D", "E", "F")
"""Site classes of ASCE 7-16 Sec. 11.4.3 (Chapter 20)."""

SS_COLUMNS = (0.25, 0.50, 0.75, 1.00, 1.25, 1.50)
"""S_S (g) of the columns of ASCE 7-16 Table 11.4-1 (the first is "<= 0.25", the last ">= 1.5")."""
S1_COLUMNS = (0.1, 0.2, 0.3, 0.4, 0.5, 0.6)
"""S_1 (g) of the columns of ASCE 7-16 Table 11.4-2 (the first is "<= 0.1", the last ">= 0.6")."""

_SEE = float("nan")  # a cell printing "See Section 11.4.8" instead of a number
FA_TABLE = {
    # ASCE 7-16 Table 11.4-1, short-period site coefficient F_a (USGS earthquake-design-ws and two transcriptions).
    "A": (0.8, 0.8, 0.8, 0.8, 0.8, 0.8),
    "B": (0.9, 0.9, 0.9, 0.9, 0.9, 0.9),
    "C": (1.3, 1.3, 1.2, 1.2, 1.2, 1.2),
    "D": (1.6, 1.4, 1.2, 1.1, 1.0, 1.0),
    "E": (2.4, 1.7, 1.3, _SEE, _SEE, _SEE),
}
FV_TABLE = {
    # ASCE 7-16 Table 11.4-2, long-period site coefficient F_v (USGS earthquake-design-ws and two transcriptions;
    # the E cells at S_1 >= 0.2 disagree between them, so they are refused as "See Section 11.4.8").  The D cells
    # at S_1 >= 0.2 carry footnote a: "Also, see requirements for site-specific ground motions in Section 11.4.8."
    "A": (0.8, 0.8, 0.8, 0.8, 0.8, 0.8),
    "B": (0.8, 0.8, 0.8, 0.8, 0.8, 0.8),
    "C": (1.5, 1.5, 1.5, 1.5, 1.5, 1.4),
    "D": (2.4, 2.2, 2.0, 1.9, 1.8, 1.7),
    "E": (4.2, _SEE, _SEE, _SEE, _SEE, _SEE),
}


def site_class(value: object) -> str:
    """``value`` as one of :data:`SITE_CLASSES` (case-insensitive); ValueError naming it otherwise."""
    if isinstance(value, str) and value.strip().upper() in SITE_CLASSES:
        return value.strip().upper()
    raise ValueError(f"site_class must be one of {', '.join(SITE_CLASSES)} (ASCE 7-16 Sec. 11.4.3), got {show(value)}")


def _interpolate(table: dict, columns: tuple, value: float, cls: str, name: str, table_name: str) -> float:
    row = np.array(table[cls])
    clipped = min(max(value, columns[0]), columns[-1])
    right = int(np.searchsorted(columns, clipped))
    needed = row[[right]] if columns[right] == clipped else row[[right - 1, right]]
    if np.isnan(needed).any():
        raise ValueError(f"ASCE 7-16 Table {table_name} gives no coefficient for Site Class {cls} at {name} = "
                         f"{show(value)} g (the cell says \"See Section 11.4.8\"): a ground motion hazard analysis "
                         "(Chapter 21) is required; give S_MS and S_M1 from it")
    return float(np.interp(clipped, columns, row))


def site_coefficients(ss: float, s1: float, site: str) -> tuple[float, float]:
    """(F_a, F_v) of ASCE 7-16 Tables 11.4-1 and 11.4-2 for the mapped S_S and S_1 (g, >= 0) on Site Class
    ``site``, with the straight-line interpolation the tables' notes prescribe (constant beyond the first and
    last columns).  ValueError for Site Class F (a site response analysis, Sec. 21.1, is required) and for the
    Site Class E cells that print "See Section 11.4.8" (S_S >= 1.0, S_1 >= 0.2) or that interpolation would need.
    The Site Class D values at S_1 >= 0.2 are returned (they are tabulated, with footnote a pointing to
    Sec. 11.4.8; :meth:`Site.from_mapped` applies that clause)."""
    ss = non_negative("S_S", ss)
    s1 = non_negative("S_1", s1)
    cls = site_class(site)
    if cls == "F":
        raise ValueError("Site Class F: ASCE 7-16 Tables 11.4-1 and 11.4-2 give no coefficients (\"See Section "
                         "11.4.8\"); a site response analysis (Sec. 21.1) is required; give S_MS and S_M1 from it")
    return (_interpolate(FA_TABLE, SS_COLUMNS, ss, cls, "S_S", "11.4-1"),
            _interpolate(FV_TABLE, S1_COLUMNS, s1, cls, "S_1", "11.4-2"))


def mce_spectrum(periods: ArrayLike, sms: float, sm1: float, tl: float) -> np.ndarray:
    """The ASCE 7-16 MCE_R response spectrum S_a (g) at ``periods`` (s, >= 0; any shape): the design spectrum's
    branches, Eqs. 11.4-5 to 11.4-7, with S_MS and S_M1 (g) in place of S_DS and S_D1 (Sec. 11.4.7: 1.5 times
    the design spectrum), T_0 = 0.2 S_M1 / S_MS, T_S = S_M1 / S_MS, long-period transition ``tl`` (s)."""
    sms, sm1, tl = _spectral_parameters(sms, sm1, tl)
    periods = finite_array("periods", periods, ndim=None)
    if (periods < 0).any():
        raise ValueError(f"periods must be >= 0 s, got {show(periods[periods < 0].flat[0])}")
    ts = sm1 / sms
    t0 = 0.2 * ts
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(periods < t0, sms * (0.4 + 0.6 * periods / t0),            # Eq. 11.4-5
                        np.where(periods <= ts, sms,                                # plateau
                                 np.where(periods <= tl, sm1 / periods,             # Eq. 11.4-6
                                          sm1 * tl / periods**2)))                  # Eq. 11.4-7


def _spectral_parameters(sms: object, sm1: object, tl: object) -> tuple[float, float, float]:
    sms_value = positive("S_MS", sms)
    sm1_value = positive("S_M1", sm1)
    tl_value = positive("T_L", tl)
    if sm1_value > sms_value * tl_value:
        raise ValueError(f"S_M1 = {show(sm1)} g is larger than S_MS x T_L = {show(sms)} g x {show(tl)} s = "
                         f"{sms_value * tl_value:.6g} g s: T_S = S_M1 / S_MS = {sm1_value / sms_value:.6g} s would lie "
                         "beyond T_L, and the spectrum's branches (ASCE 7-16 Sec. 11.4.6) would be out of order")
    return sms_value, sm1_value, tl_value


SITE_CONSISTENCY_TOLERANCE = 0.005
"""How far (relative to S_MS, S_M1) a :class:`Site` given with its mapped values and site coefficients may
find F_a S_S and F_v S_1 from them (ASCE 7-16 Eqs. 11.4-1, 11.4-2): 0.5 %, the rounding of values printed to
three significant figures (as design-map tools print them); a larger gap means the values do not belong
together."""


def _product(mapped: float | None, coefficient: float | None) -> float | None:
    return None if mapped is None or coefficient is None else mapped * coefficient


@dataclass(frozen=True)
class Site:
    """The site of a design: the MCE_R spectral parameters and the building's risk category.

    ``sms``, ``sm1`` (g, > 0): S_MS and S_M1 (ASCE 7-16 Eqs. 11.4-1, 11.4-2, or a site-specific procedure);
    ``tl`` (s, > 0): the long-period transition period T_L (Figs. 22-14 to 22-17); S_M1 <= S_MS T_L (else T_S
    would lie beyond T_L).  ``risk_category``: "I" ... "IV" (Table 1.5-1), which sets the acceptance of
    Chapter 16.  ``ss``, ``s1`` (g), ``site_class``, ``fa``, ``fv``: how S_MS and S_M1 were found when they came
    from mapped values (:meth:`from_mapped`); None when given directly.  Each given is > 0, and where both a
    mapped value and its coefficient are given, F_a S_S and F_v S_1 must equal S_MS and S_M1 within
    :data:`SITE_CONSISTENCY_TOLERANCE` (0.5 %); ValueError naming the value otherwise.
    """

    sms: float
    sm1: float
    tl: float
    risk_category: str = "II"
    ss: float | None = None
    s1: float | None = None
    site_class: str | None = None
    fa: float | None = None
    fv: float | None = None

    def __post_init__(self) -> None:
        sms, sm1, tl = _spectral_parameters(self.sms, self.sm1, self.tl)
        object.__setattr__(self, "sms", sms)
        object.__setattr__(self, "sm1", sm1)
        object.__setattr__(self, "tl", tl)
        object.__setattr__(self, "risk_category", risk_category(self.risk_category))
        for name, label in (("ss", "S_S"), ("s1", "S_1"), ("fa", "F_a"), ("fv", "F_v")):
            if getattr(self, name) is not None:  # mapped values and site coefficients are > 0 (Sec. 11.4.2-11.4.4)
                object.__setattr__(self, name, positive(f"{name} ({label}, {'g' if name[0] == 's' else '-'})",
                                                        getattr(self, name)))
        if self.site_class is not None:
            object.__setattr__(self, "site_class", site_class(self.site_class))
        for spectral, mapped, coefficient, equation in (("sms", "ss", "fa", "11.4-1"), ("sm1", "s1", "fv", "11.4-2")):
            value, product = getattr(self, spectral), _product(getattr(self, mapped), getattr(self, coefficient))
            if product is not None and abs(product - value) > SITE_CONSISTENCY_TOLERANCE * value:
                factors = f"{show(getattr(self, coefficient))} x {show(getattr(self, mapped))}"
                raise ValueError(f"{spectral} = {show(value)} g disagrees with {coefficient} x {mapped} = "
                                 f"{factors} = {product:.6g} g "
                                 f"(ASCE 7-16 Eq. {equation}; tolerance {SITE_CONSISTENCY_TOLERANCE:.1%} of "
                                 f"{spectral}): give values that belong together")

    @classmethod
    def from_mapped(cls, ss: float, s1: float, site: str, tl: float, risk_category: str = "II",
                    damping_system: bool = True) -> Site:
        """The site from the mapped MCE_R parameters S_S and S_1 (g) and the site class: S_MS = F_a S_S and
        S_M1 = F_v S_1 (ASCE 7-16 Eqs. 11.4-1, 11.4-2; :func:`site_coefficients`).

        Refused (ValueError naming the clause) where ASCE 7-16 Sec. 11.4.8 requires a ground motion hazard
        analysis instead: Site Class F; Site Class E with S_S >= 1.0; Site Class D or E with S_1 >= 0.2; and,
        for a structure with a damping system (``damping_system``, default True: a building with walls), any
        site with S_1 >= 0.6.  The clause's exceptions concern the equivalent lateral force procedure and are
        not available to damped structures, so none is applied."""
        ss_value = positive("S_S", ss)
        s1_value = positive("S_1", s1)
        letter = site_class(site)
        if not isinstance(damping_system, (bool, np.bool_)):
            raise ValueError(f"damping_system must be True or False, got {show(damping_system)}")
        reason = None
        if damping_system and s1_value >= 0.6:
            reason = f"a structure with a damping system on a site with S_1 = {show(s1)} g >= 0.6"
        elif letter in ("D", "E") and s1_value >= 0.2:
            reason = f"Site Class {letter} with S_1 = {show(s1)} g >= 0.2"
        elif letter == "E" and ss_value >= 1.0:
            reason = f"Site Class E with S_S = {show(ss)} g >= 1.0"
        if reason is not None:
            raise ValueError(f"ASCE 7-16 Sec. 11.4.8 requires a ground motion hazard analysis (Sec. 21.2) for "
                             f"{reason}; the tabulated site coefficients may not be used: give S_MS and S_M1 from the "
                             "site-specific procedure (Sec. 21.4) instead of S_S, S_1 and the site class")
        fa, fv = site_coefficients(ss_value, s1_value, letter)
        return Site(fa * ss_value, fv * s1_value, tl, risk_category, ss_value, s1_value, letter, fa, fv)

    @property
    def sds(self) -> float:
        """S_DS = 2/3 S_MS (g; ASCE 7-16 Eq. 11.4-3)."""
        return 2.0 * self.sms / 3.0

    @property
    def sd1(self) -> float:
        """S_D1 = 2/3 S_M1 (g; ASCE 7-16 Eq. 11.4-4)."""
        return 2.0 * self.sm1 / 3.0

    @property
    def ts(self) -> float:
        """T_S = S_D1 / S_DS = S_M1 / S_MS (s; ASCE 7-16 Sec. 11.4.6)."""
        return self.sm1 / self.sms

    @property
    def t0(self) -> float:
        """T_0 = 0.2 S_D1 / S_DS (s; ASCE 7-16 Sec. 11.4.6)."""
        return 0.2 * self.ts

    def spectrum(self, periods: ArrayLike) -> np.ndarray:
        """The MCE_R response spectrum S_a (g) at ``periods`` (s): :func:`mce_spectrum`."""
        return mce_spectrum(periods, self.sms, self.sm1, self.tl)

    def spectral_acceleration(self, periods: ArrayLike) -> np.ndarray:
        """The MCE_R response spectrum in mm/s^2 at ``periods`` (s): the target of ASCE 7-16 Sec. 16.2.1."""
        return self.spectrum(periods) * G

    def describe(self) -> str:
        """One line: the parameters and where they come from."""
        text = (f"S_MS = {self.sms:.4g} g, S_M1 = {self.sm1:.4g} g, T_L = {self.tl:g} s (T_0 = {self.t0:.3f} s, "
                f"T_S = {self.ts:.3f} s), Risk Category {self.risk_category}")
        if self.site_class is not None:
            text += (f"; from S_S = {self.ss:.4g} g, S_1 = {self.s1:.4g} g, Site Class {self.site_class}: "
                     f"F_a = {self.fa:.4g}, F_v = {self.fv:.4g} (ASCE 7-16 Tables 11.4-1, 11.4-2)")
        return text


SITE_KEYS = ("sms", "sm1", "tl", "ss", "s1", "site_class", "risk_category")
"""The keys :func:`site_from_values` reads (the ``[site]`` table of a building file)."""


def site_from_values(values: dict, damping_system: bool = True) -> Site:
    """A :class:`Site` from a dict with some of :data:`SITE_KEYS`: either ``sms`` and ``sm1`` or ``ss``, ``s1``
    and ``site_class``, and ``tl``; ``risk_category`` defaults to "II".  ValueError naming what is missing,
    unknown or contradictory.  ``damping_system``: as :meth:`Site.from_mapped` (Sec. 11.4.8's S_1 >= 0.6 rule)."""
    if not isinstance(values, dict):
        raise ValueError(f"the site must be a table of {', '.join(SITE_KEYS)}, got {show(values)}")
    unknown = sorted(set(values) - set(SITE_KEYS))
    if unknown:
        raise ValueError(f"unknown site keys {unknown}; expected some of {list(SITE_KEYS)}")
    given = {key for key, value in values.items() if value is not None}
    direct, mapped = {"sms", "sm1"} & given, {"ss", "s1", "site_class"} & given
    if "tl" not in given:
        raise ValueError("the site needs tl (T_L, s: the long-period transition period of ASCE 7-16 Sec. 11.4.6)")
    category: Any = values.get("risk_category")  # checked by Site (I-IV or 1-4)
    if category is None:
        category = "II"
    if direct and mapped:
        raise ValueError(f"give the site either as sms and sm1 or as ss, s1 and site_class, not both "
                         f"(got {sorted(direct | mapped)})")
    if direct:
        if direct != {"sms", "sm1"}:
            raise ValueError(f"the site needs both sms and sm1 (g), got only {sorted(direct)}")
        return Site(values["sms"], values["sm1"], values["tl"], category)
    if mapped != {"ss", "s1", "site_class"}:
        missing = sorted({"ss", "s1", "site_class"} - mapped) if mapped else ["sms", "sm1"]
        raise ValueError(f"the site needs sms and sm1 (g), or ss, s1 and site_class; missing {missing}")
    return Site.from_mapped(values["ss"], values["s1"], values["site_class"], values["tl"], category,
                            damping_system=damping_system)
