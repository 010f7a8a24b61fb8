"""Seismic force-resisting systems: ASCE 7-16 Table 12.2-1 (R, Omega_0, C_d, height limits) and Table 12.8-2
(C_t, x of the approximate period).

Every number carries its table and row.  The standard's own Table 12.2-1 could not be read here: R = 8,
Omega_0 = 3, C_d = 5.5 of steel special moment frames (row C.1) agree with the worked examples read (e.g.
steelcalculator.app's ASCE 7-22 ELF example); the other rows' coefficients (C.3 steel intermediate, C.4 steel
ordinary, C.5 reinforced-concrete special moment frames) and all height limits are from the standard as
recalled (they are unchanged since ASCE 7-05).  Check them against ASCE 7-16 before relying on them.
Table 12.8-2 (C_t, x) agrees with the secondary copies read (design-software pages, permit calculations).

Footnotes of Table 12.2-1 that raise or relax the height limits (e.g. for one-story buildings or light roofs
with intermediate and ordinary steel moment frames, Sec. 12.2.5.6, 12.2.5.7) are NOT applied: the limits
here are the table's plain entries.

Height limits (ft) by seismic design category: ``None`` = NL (not limited), ``0.0`` = NP (not permitted).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from .._validation import non_negative, positive, show, text

SDC_LETTERS = ("A", "B", "C", "D", "E", "F")
"""Seismic design categories of ASCE 7-16 Sec. 11.6."""

PERIOD_PARAMETERS: dict[str, tuple[float, float]] = {
    # ASCE 7-16 Table 12.8-2 "Values of approximate period parameters C_t and x" (h_n in ft).
    "steel-moment-frame": (0.028, 0.8),  # steel moment-resisting frames
    "concrete-moment-frame": (0.016, 0.9),  # concrete moment-resisting frames
    "steel-eccentrically-braced-frame": (0.03, 0.75),  # steel eccentrically braced frames
    "steel-buckling-restrained-braced-frame": (0.03, 0.75),  # steel buckling-restrained braced frames
    "other": (0.02, 0.75),  # all other structural systems
}
"""C_t and x of ASCE 7-16 Table 12.8-2 by structural system, for h_n in ft (T_a = C_t h_n^x, Eq. 12.8-7)."""

PERIOD_ROWS = {
    "steel-moment-frame": "Table 12.8-2, steel moment-resisting frames",
    "concrete-moment-frame": "Table 12.8-2, concrete moment-resisting frames",
    "steel-eccentrically-braced-frame": "Table 12.8-2, steel eccentrically braced frames",
    "steel-buckling-restrained-braced-frame": "Table 12.8-2, steel buckling-restrained braced frames",
    "other": "Table 12.8-2, all other structural systems",
}
"""The row of ASCE 7-16 Table 12.8-2 each key of :data:`PERIOD_PARAMETERS` comes from."""


@dataclass(frozen=True)
class SeismicSystem:
    """One seismic force-resisting system of ASCE 7-16 Table 12.2-1 with its Table 12.8-2 period parameters.

    ``key``: the short name (:data:`SYSTEMS`); ``name``: the table's wording; ``table_row``: where the
    design coefficients come from; ``r`` R (response modification coefficient), ``omega0`` Omega_0 (overstrength
    factor), ``cd`` C_d (deflection amplification factor), all dimensionless; ``height_limits_ft``: SDC ("B" ..
    "F") -> the structural height limit h_n in ft, None = NL (not limited), 0.0 = NP (not permitted);
    ``ct``, ``x``: C_t and x of Table 12.8-2 (h_n in ft; T_a in s); ``period_row``: their row;
    ``moment_frame``: True for moment-resisting frames (ASCE 7-16 Sec. 12.12.1.1: drift limit divided by rho
    in SDC D-F).
    """

    key: str
    name: str
    table_row: str
    r: float
    omega0: float
    cd: float
    height_limits_ft: dict[str, float | None] = field(hash=False)
    ct: float
    x: float
    period_row: str
    moment_frame: bool = True

    def __post_init__(self) -> None:
        for name in ("key", "name", "table_row", "period_row"):
            if not text(name, getattr(self, name)).strip():
                raise ValueError(f"{name} must not be empty")
        for name, label in (("r", "R"), ("omega0", "Omega_0"), ("cd", "C_d"), ("ct", "C_t"), ("x", "x")):
            object.__setattr__(self, name, positive(f"{name} ({label})", getattr(self, name)))
        limits = self.height_limits_ft
        if not isinstance(limits, dict) or set(limits) != set(SDC_LETTERS[1:]):
            raise ValueError(f"height_limits_ft must map each of B, C, D, E, F to a height in ft (None = NL, "
                             f"0.0 = NP), got {show(limits)}")
        object.__setattr__(self, "height_limits_ft", {
            sdc: None if limits[sdc] is None else non_negative(f"height_limits_ft[{sdc!r}] (ft)", limits[sdc])
            for sdc in SDC_LETTERS[1:]})
        if not isinstance(self.moment_frame, bool):
            raise ValueError(f"moment_frame must be True or False, got {show(self.moment_frame)}")

    def height_limit_ft(self, sdc: str) -> float | None:
        """The height limit (ft) in seismic design category ``sdc``: None = not limited (NL), 0.0 = not
        permitted (NP).  SDC A has no limits (ASCE 7-16 Sec. 11.7 applies instead of Table 12.2-1)."""
        letter = str(sdc).strip().upper()
        if letter not in SDC_LETTERS:
            raise ValueError(f"seismic design category must be one of {', '.join(SDC_LETTERS)}, got {show(sdc)}")
        if letter == "A":
            return None
        return self.height_limits_ft[letter]

    def describe(self) -> str:
        """One line: the system, its coefficients and where they come from."""
        limits = ", ".join(f"{sdc}: {'NL' if limit is None else 'NP' if limit == 0.0 else f'{limit:g} ft'}"
                           for sdc, limit in self.height_limits_ft.items())
        return (f"{self.name} (ASCE 7-16 {self.table_row}): R = {self.r:g}, Omega_0 = {self.omega0:g}, "
                f"C_d = {self.cd:g}; height limits {limits}; C_t = {self.ct:g}, x = {self.x:g} "
                f"(ASCE 7-16 {self.period_row})")


def _limits(b: float | None, c: float | None, d: float | None, e: float | None,
            f: float | None) -> dict[str, float | None]:
    return {"B": b, "C": c, "D": d, "E": e, "F": f}


def _period_of(kind: str) -> dict[str, Any]:
    """C_t, x and their row of Table 12.8-2 for the structure type ``kind`` (a key of PERIOD_PARAMETERS)."""
    ct, x = PERIOD_PARAMETERS[kind]
    return {"ct": ct, "x": x, "period_row": PERIOD_ROWS[kind]}


NL = None  # not limited
NP = 0.0  # not permitted

SYSTEMS: dict[str, SeismicSystem] = {
    "steel-smf": SeismicSystem(
        "steel-smf", "Steel special moment frames", "Table 12.2-1 row C.1", r=8.0, omega0=3.0, cd=5.5,
        height_limits_ft=_limits(NL, NL, NL, NL, NL),
        **_period_of("steel-moment-frame")),
    "steel-imf": SeismicSystem(
        "steel-imf", "Steel intermediate moment frames", "Table 12.2-1 row C.3", r=4.5, omega0=3.0, cd=4.0,
        # D: 35 ft, E and F: NP (the footnotes that permit taller or lighter buildings are not applied)
        height_limits_ft=_limits(NL, NL, 35.0, NP, NP),
        **_period_of("steel-moment-frame")),
    "steel-omf": SeismicSystem(
        "steel-omf", "Steel ordinary moment frames", "Table 12.2-1 row C.4", r=3.5, omega0=3.0, cd=3.0,
        # D, E, F: NP (the footnotes that permit light one-story buildings are not applied)
        height_limits_ft=_limits(NL, NL, NP, NP, NP),
        **_period_of("steel-moment-frame")),
    "rc-smf": SeismicSystem(
        "rc-smf", "Special reinforced concrete moment frames", "Table 12.2-1 row C.5", r=8.0, omega0=3.0,
        cd=5.5, height_limits_ft=_limits(NL, NL, NL, NL, NL),
        **_period_of("concrete-moment-frame")),
}
"""The seismic force-resisting systems the design knows (ASCE 7-16 Table 12.2-1 part C, Table 12.8-2)."""


def seismic_system(key: object) -> SeismicSystem:
    """The :class:`SeismicSystem` named ``key`` (one of :data:`SYSTEMS`, case-insensitive), or ``key`` itself
    when it is one; ValueError listing the keys otherwise."""
    if isinstance(key, SeismicSystem):
        return key
    if isinstance(key, str) and key.strip().lower() in SYSTEMS:
        return SYSTEMS[key.strip().lower()]
    raise ValueError(f"system must be one of {', '.join(SYSTEMS)} (ASCE 7-16 Table 12.2-1), got {show(key)}")
