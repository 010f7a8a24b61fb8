"""ASCE 7-16 Chapters 1, 11 and 12: the equivalent lateral force (ELF) procedure, pure functions.

Every function cites its table, section or equation of ASCE 7-16.  Units: accelerations in g, periods in s,
heights in mm at the interface (converted to ft where the code's equation is in ft: T_a of Eq. 12.8-7),
weights and forces in N (any consistent force unit works).

Sources: ASCE/SEI 7-16 "Minimum Design Loads and Associated Criteria for Buildings and Other Structures".  The
standard's own text could not be read here; the clauses were checked against secondary copies found with the
project's search tool: Eqs. 12.8-2 ... 12.8-7 and 12.8-11/12 and k (Sec. 12.8.3) in ideCAD's ASCE 7-16 help
pages ("12.8 Equivalent Lateral Force Method") and published ASCE 7-16 calculations; Sec. 12.8.6 and 12.12.1 in
ideCAD's "Determination and Limitation of Story Drifts per ASCE 7-16" and STRUCTURE magazine's "ASCE 7-16
Provisions for Lateral Drift Determination" (Sec. 12.8.6.2: drift at the computed period, no C_u T_a cap);
Eqs. 12.8-16/17 (theta, theta_max = 0.5 / (beta C_d) <= 0.25, theta <= 0.10 needs no P-Delta) as quoted from
ASCE 7-10 (unchanged in 7-16) on eng-tips and by Dlubal; Table 12.8-1's values in the asce7-16 Python package
and a vendor's tool (rhces.com); Table 12.12-1 "all other structures" (0.020 / 0.015 / 0.010 h_sx) in the ASCE 7-22
summary of callout.app (the same values as 7-16); Sec. 12.3.4.2 (rho = 1.3 in SDC D-F unless a condition is met)
quoted in a Santa Ana permit calculation.  Tables 1.5-2, 11.6-1 and 11.6-2 and Sec. 11.6's S_1 >= 0.75 g rule are
from the standard as recalled (Table 11.6's D rows, S_DS >= 0.50 and S_D1 >= 0.20, agree with the ASCE 7-22
worked example of steelcalculator.app); check them against the standard.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from .._validation import finite_array, finite_scalar, positive, show
from .systems import SeismicSystem, seismic_system

FT = 304.8
"""mm per ft: h_n of Eq. 12.8-7 is in ft."""

RISK_CATEGORIES = ("I", "II", "III", "IV")
"""Risk categories of ASCE 7-16 Table 1.5-1."""

IMPORTANCE_FACTORS = {"I": 1.0, "II": 1.0, "III": 1.25, "IV": 1.5}
"""Seismic importance factor I_e by risk category: ASCE 7-16 Table 1.5-2."""

UPPER_LIMIT_COEFFICIENTS = ((0.1, 1.7), (0.15, 1.6), (0.2, 1.5), (0.3, 1.4), (0.4, 1.4))
"""(S_D1 in g, C_u) of ASCE 7-16 Table 12.8-1 "Coefficient for upper limit on calculated period": 1.7 at
S_D1 <= 0.1, 1.4 at S_D1 >= 0.4.  Between the printed values C_u is interpolated linearly (the practice of
FEMA P695 Sec. 5.2.5's use of the table and of design software; the table itself prints no interpolation
note in the copies read, so this is stated as an assumption)."""

ALLOWABLE_DRIFT_RATIOS = {"I": 0.020, "II": 0.020, "III": 0.015, "IV": 0.010}
"""Delta_a / h_sx of ASCE 7-16 Table 12.12-1, row "All other structures", by risk category."""

SDC_SHORT = ((0.167, "A", "A"), (0.33, "B", "C"), (0.50, "C", "D"), (math.inf, "D", "D"))
"""ASCE 7-16 Table 11.6-1: (S_DS upper bound (exclusive), SDC for Risk Category I/II/III, SDC for IV)."""

SDC_ONE_SECOND = ((0.067, "A", "A"), (0.133, "B", "C"), (0.20, "C", "D"), (math.inf, "D", "D"))
"""ASCE 7-16 Table 11.6-2: (S_D1 upper bound (exclusive), SDC for Risk Category I/II/III, SDC for IV)."""

BOUNDARY_TOLERANCE = 1e-9
"""Relative distance below a row boundary of Tables 11.6-1/2 at which a value counts as on the boundary (rounding
of S_DS = 2/3 S_MS and S_D1 = 2/3 S_M1 in floating point)."""

THETA_AMPLIFY = 0.10
"""ASCE 7-16 Sec. 12.8.7: P-Delta need not be considered where theta <= 0.10; above it, displacements and
forces are multiplied by 1 / (1 - theta) (the clause's alternative to a rational analysis)."""

THETA_CAP = 0.25
"""ASCE 7-16 Eq. 12.8-17: theta_max = 0.5 / (beta C_d) <= 0.25."""


def risk_category(value: object) -> str:
    """``value`` as one of :data:`RISK_CATEGORIES` ("I" ... "IV", case-insensitive; 1-4 accepted); ValueError
    naming the value otherwise (ASCE 7-16 Table 1.5-1)."""
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool) and 1 <= int(value) <= 4:
        return RISK_CATEGORIES[int(value) - 1]
    if isinstance(value, str) and value.strip().upper() in RISK_CATEGORIES:
        return value.strip().upper()
    raise ValueError(f"risk_category must be one of {', '.join(RISK_CATEGORIES)} (ASCE 7-16 Table 1.5-1), "
                     f"got {show(value)}")


def importance_factor(risk: object) -> float:
    """Seismic importance factor I_e (-) for risk category ``risk``: ASCE 7-16 Table 1.5-2 (1.0 for I and II,
    1.25 for III, 1.5 for IV)."""
    return IMPORTANCE_FACTORS[risk_category(risk)]


def seismic_design_category(sds: float, sd1: float, s1: float | None, risk: object) -> str:
    """Seismic design category "A" ... "F" (ASCE 7-16 Sec. 11.6).

    ``sds``, ``sd1`` (g, > 0): S_DS and S_D1; ``s1`` (g, > 0, or None when unknown): the mapped S_1;
    ``risk``: the risk category.  Where S_1 >= 0.75 g: E for Risk Category I, II, III and F for IV.
    Otherwise the more severe of Table 11.6-1 (by S_DS) and Table 11.6-2 (by S_D1).  The exception of
    Sec. 11.6 that permits Table 11.6-1 alone (S_1 < 0.75 g and short-period conditions) is not applied.
    """
    sds = positive("sds (S_DS, g)", sds)
    sd1 = positive("sd1 (S_D1, g)", sd1)
    category = risk_category(risk)
    column = 2 if category == "IV" else 1
    if s1 is not None and positive("s1 (S_1, g)", s1) >= 0.75 * (1.0 - BOUNDARY_TOLERANCE):
        return "F" if category == "IV" else "E"
    # A value within BOUNDARY_TOLERANCE below a boundary counts as on it: S_D1 = 2/3 x 0.3 is 0.19999999999999998
    # in floating point, and the table puts S_D1 = 0.20 in the upper row.
    by_sds = str(next(row[column] for row in SDC_SHORT if sds < row[0] * (1.0 - BOUNDARY_TOLERANCE)))
    by_sd1 = str(next(row[column] for row in SDC_ONE_SECOND if sd1 < row[0] * (1.0 - BOUNDARY_TOLERANCE)))
    return max(by_sds, by_sd1)  # letters order as the categories' severity


def upper_limit_coefficient(sd1: float) -> float:
    """C_u (-) of ASCE 7-16 Table 12.8-1 at S_D1 = ``sd1`` (g): 1.7 at S_D1 <= 0.1, 1.4 at S_D1 >= 0.3, linear
    between the printed values (:data:`UPPER_LIMIT_COEFFICIENTS`)."""
    sd1 = positive("sd1 (S_D1, g)", sd1)
    values, coefficients = zip(*UPPER_LIMIT_COEFFICIENTS, strict=True)
    return float(np.interp(sd1, values, coefficients))


def approximate_period(height_mm: float, system: SeismicSystem | str) -> float:
    """T_a = C_t h_n^x (s; ASCE 7-16 Eq. 12.8-7, h_n in ft) for a structure ``height_mm`` (mm, > 0) tall, with C_t
    and x of ``system`` (a :class:`SeismicSystem` or its key; Table 12.8-2)."""
    spec = seismic_system(system)
    height_ft = positive("height (h_n, mm)", height_mm) / FT
    period = float(spec.ct * height_ft**spec.x)
    if not math.isfinite(period):
        raise ValueError(f"height h_n = {show(height_mm)} mm gives no finite T_a")
    return period


def seismic_response_coefficient(sds: float, sd1: float, s1: float | None, tl: float, period: float,  # noqa: PLR0917
                                 r: float, ie: float, *, minimum: bool = True) -> tuple[float, str]:
    """(C_s, the equation that governs) of ASCE 7-16 Sec. 12.8.1.1.

    C_s = S_DS / (R / I_e) (Eq. 12.8-2), which need not exceed S_D1 / (T R / I_e) for T <= T_L (Eq. 12.8-3) or
    S_D1 T_L / (T^2 R / I_e) for T > T_L (Eq. 12.8-4), and shall not be less than 0.044 S_DS I_e >= 0.01
    (Eq. 12.8-5) nor, where S_1 >= 0.6 g, 0.5 S_1 / (R / I_e) (Eq. 12.8-6).  ``sds``, ``sd1``, ``s1`` in g
    (``s1`` None: not known, Eq. 12.8-6 not applied), ``tl`` and ``period`` in s, ``r`` and ``ie``
    dimensionless.  ``minimum`` False leaves out Eq. 12.8-5 (Sec. 12.8.6.1: it need not be applied to the
    forces that compute drift); Eq. 12.8-6 applies either way.  The equation is returned as "12.8-2" ...
    "12.8-6" (both minima of Eq. 12.8-5 are "12.8-5").
    """
    sds = positive("sds (S_DS, g)", sds)
    sd1 = positive("sd1 (S_D1, g)", sd1)
    tl = positive("tl (T_L, s)", tl)
    period = positive("period (T, s)", period)
    r = positive("r (R)", r)
    ie = positive("ie (I_e)", ie)
    cs, equation = sds / (r / ie), "12.8-2"
    if period <= tl:
        cap, cap_equation = sd1 / (period * r / ie), "12.8-3"
    else:
        cap, cap_equation = sd1 * tl / period / period / (r / ie), "12.8-4"  # period**2 would overflow
    if cap < cs:
        cs, equation = cap, cap_equation
    if minimum:
        floor = max(0.044 * sds * ie, 0.01)
        if floor > cs:
            cs, equation = floor, "12.8-5"
    if s1 is not None and positive("s1 (S_1, g)", s1) >= 0.6:
        floor = 0.5 * s1 / (r / ie)
        if floor > cs:
            cs, equation = floor, "12.8-6"
    if not math.isfinite(cs):
        raise ValueError(f"C_s is not finite for S_DS = {show(sds)}, S_D1 = {show(sd1)}, T = {show(period)} s, "
                         f"R = {show(r)}, I_e = {show(ie)}: give values of a building")
    return float(cs), equation


def distribution_exponent(period: float) -> float:
    """k (-) of ASCE 7-16 Sec. 12.8.3: 1 for T <= 0.5 s, 2 for T >= 2.5 s, linear between (the clause permits
    2 or the interpolation; the interpolation is used)."""
    period = positive("period (T, s)", period)
    return float(min(max(1.0 + (period - 0.5) / 2.0, 1.0), 2.0))


def vertical_distribution(weights: ArrayLike, heights_above_base: ArrayLike, k: float) -> np.ndarray:
    """C_vx = w_x h_x^k / sum_i w_i h_i^k (-; ASCE 7-16 Eq. 12.8-12) for each level (level 1 first).

    ``weights`` w_x (N, > 0) and ``heights_above_base`` h_x (mm, > 0: the level's height above the base; any
    length unit gives the same C_vx) of the same length; ``k`` in [1, 2] (:func:`distribution_exponent`).
    """
    w = finite_array("weights", weights)
    h = finite_array("heights_above_base", heights_above_base)
    if w.size == 0 or w.size != h.size:
        raise ValueError(f"weights ({w.size} values) and heights_above_base ({h.size} values) must have the "
                         "same, non-zero length")
    if (w <= 0).any():
        raise ValueError(f"weights must be > 0, got {show(w.tolist())}")
    if (h <= 0).any():
        raise ValueError(f"heights_above_base must be > 0, got {show(h.tolist())}")
    k = finite_scalar("k", k)
    if not 1.0 <= k <= 2.0:
        raise ValueError(f"k must lie in [1, 2] (ASCE 7-16 Sec. 12.8.3), got {show(k)}")
    with np.errstate(over="ignore"):
        products = w / w.max() * (h / h.max()) ** k  # scaled: the ratios are the same, no overflow
    return products / products.sum()


def allowable_story_drift_ratio(risk: object) -> float:
    """Delta_a / h_sx (-) of ASCE 7-16 Table 12.12-1, "All other structures": 0.020 for Risk Category I and II,
    0.015 for III, 0.010 for IV."""
    return ALLOWABLE_DRIFT_RATIOS[risk_category(risk)]


def default_redundancy_factor(sdc: str) -> float:
    """rho (-) of ASCE 7-16 Sec. 12.3.4: 1.0 in SDC B and C (Sec. 12.3.4.1), 1.3 in D-F (Sec. 12.3.4.2) unless
    one of that clause's conditions is shown to be met (which the caller states by giving rho = 1.0)."""
    return 1.3 if str(sdc).strip().upper() in ("D", "E", "F") else 1.0


def design_drift_limit_divisor(system: SeismicSystem | str, sdc: str, rho: float) -> float:
    """The divisor of Delta_a: rho for moment frames in SDC D-F (ASCE 7-16 Sec. 12.12.1.1), 1 otherwise."""
    if seismic_system(system).moment_frame and str(sdc).strip().upper() in ("D", "E", "F"):
        return positive("rho", rho)
    return 1.0


def design_displacement(elastic: ArrayLike, cd: float, ie: float) -> np.ndarray:
    """delta_x = C_d delta_xe / I_e (ASCE 7-16 Eq. 12.8-15), in the unit of ``elastic`` (mm)."""
    return finite_array("elastic displacement (delta_xe)", elastic) * positive("cd (C_d)", cd) / positive(
        "ie (I_e)", ie)


def stability_coefficient(gravity_load: ArrayLike, design_drift: ArrayLike, ie: float, story_shear: ArrayLike,
                          story_height: ArrayLike, cd: float) -> np.ndarray:
    """theta = P_x Delta I_e / (V_x h_sx C_d) (-; ASCE 7-16 Eq. 12.8-16), per story.

    ``gravity_load`` P_x (N, >= 0: the vertical design load at and above the story, no load factor above 1.0),
    ``design_drift`` Delta (mm: the design story drift, with C_d), ``story_shear`` V_x (N, > 0: the seismic
    shear that acts with it), ``story_height`` h_sx (mm, > 0); ``ie``, ``cd`` dimensionless.  For a shear
    story of stiffness k_x, Delta I_e / C_d = V_x / k_x and theta = P_x / (k_x h_sx).
    """
    p = finite_array("gravity_load (P_x, N)", gravity_load)
    drift = finite_array("design_drift (Delta, mm)", design_drift)
    v = finite_array("story_shear (V_x, N)", story_shear)
    h = finite_array("story_height (h_sx, mm)", story_height)
    if not p.size == drift.size == v.size == h.size:
        raise ValueError(f"P_x ({p.size}), Delta ({drift.size}), V_x ({v.size}) and h_sx ({h.size}) must have "
                         "the same length")
    if (p < 0).any() or (v <= 0).any() or (h <= 0).any():
        raise ValueError("P_x must be >= 0, V_x and h_sx > 0")
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        theta = p * drift * positive("ie (I_e)", ie) / (v * h * positive("cd (C_d)", cd))
    if not np.isfinite(theta).all():
        raise ValueError("theta is not finite for these P_x, Delta, V_x and h_sx: give values of a building")
    return theta


def theta_max(beta: float, cd: float) -> float:
    """theta_max = 0.5 / (beta C_d) <= 0.25 (-; ASCE 7-16 Eq. 12.8-17).  ``beta``: the ratio of shear demand to
    shear capacity of the story (> 0; the clause permits 1.0 conservatively); ``cd``: C_d."""
    return float(min(0.5 / (positive("beta", beta) * positive("cd (C_d)", cd)), THETA_CAP))


def p_delta_amplification(theta: float) -> float:
    """1 / (1 - theta) where theta > 0.10, else 1 (-; ASCE 7-16 Sec. 12.8.7's alternative to a rational
    analysis).  theta >= 1 is refused (no stable story)."""
    theta = finite_scalar("theta", theta)
    if theta >= 1.0:
        raise ValueError(f"theta = {show(theta)} >= 1: the story is unstable under its gravity load")
    return 1.0 / (1.0 - theta) if theta > THETA_AMPLIFY else 1.0


def check_stability(theta: float, limit: float, story: int) -> None:
    """ValueError naming ``story`` where theta > theta_max (ASCE 7-16 Sec. 12.8.7: "the structure is potentially
    unstable and shall be redesigned")."""
    # A story designed to theta_max exactly may land a rounding error above it: 1e-12 relative is accepted.
    if finite_scalar("theta", theta) > finite_scalar("theta_max", limit) * (1.0 + 1e-12):
        raise ValueError(f"story {story}: theta = {theta:.4g} exceeds theta_max = {limit:.4g} (ASCE 7-16 Eqs. "
                         "12.8-16, 12.8-17): the structure is potentially unstable and shall be redesigned "
                         "(a stiffer story)")
