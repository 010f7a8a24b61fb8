"""The frame by ASCE 7-16 Chapter 12: a shear building designed by the equivalent lateral force procedure.

:func:`design_frame` takes a site, a seismic force-resisting system, the seismic weight of each floor and the
story heights, and returns a :class:`FrameDesign`: the :class:`~vdw_frames.frame.ShearBuilding` (masses, story
stiffnesses, yield strengths, P-Delta loads) and every intermediate quantity of ASCE 7-16 Sec. 12.8.

The procedure (the functions of :mod:`vdw_frames.asce7`):

1. I_e (Table 1.5-2), the SDC (Sec. 11.6), rho (Sec. 12.3.4: 1.0 in SDC B-C, 1.3 in D-F unless given), the
   height limit of Table 12.2-1 for the SDC (footnotes not applied);
2. T_a = C_t h_n^x (Eq. 12.8-7), C_u (Table 12.8-1);
3. stiffness, iterated with the analytical period T_1 of the bare elastic frame (masses = weights / g): the
   drift forces use C_s at T_1 (Sec. 12.8.6.2: no C_u T_a cap) without Eq. 12.8-5 (Sec. 12.8.6.1) but with
   Eq. 12.8-6, distributed with k(T_1) (Eq. 12.8-12).  Each story's stiffness is the largest of

   - the drift limit: delta_x = C_d delta_xe / I_e (Eq. 12.8-15) times 1 / (1 - theta) where theta > 0.10
     (Sec. 12.8.7) must not exceed Delta_a / rho (Table 12.12-1, Sec. 12.12.1.1).  With delta_xe = V_x / k_x and
     theta = P_x / (k_x h_sx): k_1 = C_d V_x / (I_e Delta_a / rho) where that gives theta <= 0.10; otherwise the
     smaller of k_1 + P_x / h_sx (amplified) and 10 P_x / h_sx (theta = 0.10, not amplified);
   - stability: theta <= theta_max = 0.5 / (beta C_d) (Eq. 12.8-17, beta = 1), k_x >= P_x / (theta_max h_sx);
   - ``minimum_stiffness``.

   T_1 depends on the stiffness and the stiffness on T_1: a fixed point, iterated until T_1 changes by less
   than :data:`PERIOD_TOLERANCE` (relative), at most :data:`MAX_ITERATIONS` times (ValueError beyond);
4. strength: T = min(T_1, C_u T_a) (Sec. 12.8.2), C_s with its governing equation (Eqs. 12.8-2 ... 12.8-6),
   V = C_s W (Eq. 12.8-1), F_x = C_vx V (Eqs. 12.8-11/12, k(T)), V_x (Eq. 12.8-13); each story's yield strength
   = V_x x the P-Delta factor 1 / (1 - theta) where theta > 0.10 (Sec. 12.8.7: member forces too) x
   ``overstrength`` x ``strength_scale``.

Drift is always checked with the unreduced Chapter 12 forces: ``strength_scale`` (Chapter 18's V_min / V)
reduces strength only.

Units: N, mm, s, tonne; accelerations of the site in g.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import eigh_tridiagonal

from .._files import write_csv
from .._validation import finite_array, finite_scalar, positive, show
from ..asce7 import elf as code
from ..asce7.systems import SeismicSystem, seismic_system
from ..frame.building import ShearBuilding
from ..frame.hysteresis import STORY_MODELS, Bilinear, BoucWen
from ..motion.record import G
from ..verification.spectrum import Site

PERIOD_TOLERANCE = 1e-10
"""Relative change of T_1 between two iterations of the stiffness at which the fixed point is accepted."""

MAX_ITERATIONS = 200
"""Most iterations of stiffness and T_1 (:func:`design_frame`): the iteration contracts (drift forces fall
with T_1 as 1 / T, stiffness with them, T_1 as the square root), about 40 suffice."""

BETA = 1.0
"""beta of ASCE 7-16 Eq. 12.8-17 (shear demand / shear capacity): 1.0, which Sec. 12.8.7 permits."""

ELF_PERIOD_LIMIT = 3.5
"""ASCE 7-16 Table 12.6-1: in SDC D-F the ELF procedure is permitted for regular structures above
:data:`ELF_HEIGHT_LIMIT` with T < 3.5 T_S."""

ELF_HEIGHT_LIMIT = 160.0 * code.FT
"""ASCE 7-16 Table 12.6-1 (mm): in SDC D-F the ELF procedure is permitted for regular structures not exceeding
160 ft (48.8 m) in structural height at any period (ideCAD's copy of the table)."""


@dataclass(frozen=True)
class FrameDesign:
    """A frame designed by ASCE 7-16 Sec. 12.8 (:func:`design_frame`); arrays are per story, story 1 first.

    building: the designed :class:`ShearBuilding` (masses = weights / g, tonne; stiffnesses N/mm; story
    heights mm; gravity loads P_x N; Bilinear (or the user's) story models with the strengths).
    site, system, risk_category, importance (I_e), sdc, rho, height (h_n, mm).
    ta, cu (s, -): T_a (Eq. 12.8-7) and C_u (Table 12.8-1); analytical_period T_1 (s, bare elastic frame);
    period T = min(T_1, C_u T_a) (Sec. 12.8.2; strength); drift_period (s, = T_1, Sec. 12.8.6.2).
    cs, cs_equation: C_s for strength and its governing equation ("12.8-2" ...); cs_drift: C_s of the drift
    forces (Eq. 12.8-5 not applied, Sec. 12.8.6.1).  weight W (N), base_shear V = C_s W (N), strength_scale.
    k (Sec. 12.8.3, at T), cvx (Eq. 12.8-12), forces F_x (N), story_shears V_x (N) for strength;
    drift_story_shears (N): V_x of the drift forces.  strengths (N) = V_x x p_delta_factors x overstrength x
    strength_scale.  elastic_drifts delta_xe (mm, story drifts under the drift forces), design_drifts delta_x
    (mm, Eq. 12.8-15 x P-Delta factor), allowable_drifts Delta_a / rho (mm), theta (Eq. 12.8-16), theta_max
    (Eq. 12.8-17), p_delta_factors (1 / (1 - theta) where theta > 0.10, else 1), stiffnesses (N/mm),
    governing ("drift" | "stability" | "minimum" per story), iterations (of T_1), assumptions (every stated
    assumption, in words).
    """

    building: ShearBuilding
    site: Site
    system: SeismicSystem
    risk_category: str
    importance: float
    sdc: str
    rho: float
    height: float
    ta: float
    cu: float
    analytical_period: float
    period: float
    drift_period: float
    cs: float
    cs_equation: str
    cs_drift: float
    weight: float
    base_shear: float
    strength_scale: float
    k: float
    cvx: np.ndarray
    forces: np.ndarray
    story_shears: np.ndarray
    strengths: np.ndarray
    elastic_drifts: np.ndarray
    design_drifts: np.ndarray
    allowable_drifts: np.ndarray
    theta: np.ndarray
    theta_max: float
    stiffnesses: np.ndarray
    governing: tuple[str, ...]
    assumptions: tuple[str, ...]
    overstrength: float = 1.0
    drift_equation: str = ""
    drift_k: float = 1.0
    drift_story_shears: np.ndarray | None = None
    p_delta_factors: np.ndarray | None = None
    iterations: int = 0

    def summary(self) -> dict[str, Any]:
        """The scalars of the design (units in the keys' docs of :class:`FrameDesign`)."""
        return {
            "system": self.system.key, "risk_category": self.risk_category, "importance": self.importance,
            "sdc": self.sdc, "rho": self.rho, "height_mm": self.height, "height_ft": self.height / code.FT,
            "r": self.system.r, "omega0": self.system.omega0, "cd": self.system.cd,
            "sds_g": self.site.sds, "sd1_g": self.site.sd1, "s1_g": self.site.s1, "tl_s": self.site.tl,
            "ta_s": self.ta, "cu": self.cu, "cu_ta_s": self.cu * self.ta, "analytical_period_s": self.analytical_period,
            "period_s": self.period, "drift_period_s": self.drift_period, "cs": self.cs,
            "cs_equation": self.cs_equation, "cs_drift": self.cs_drift, "cs_drift_equation": self.drift_equation,
            "weight_n": self.weight, "base_shear_n": self.base_shear, "strength_scale": self.strength_scale,
            "overstrength": self.overstrength, "k": self.k, "drift_k": self.drift_k, "theta_max": self.theta_max,
            "iterations": self.iterations,
        }

    def rows(self) -> list[dict[str, Any]]:
        """One dict per story (story 1 first), every per-story quantity; units in the keys."""
        heights = np.asarray(self.building.story_heights)
        drift_shears = self.drift_story_shears if self.drift_story_shears is not None else self.story_shears
        factors = self.p_delta_factors if self.p_delta_factors is not None else np.ones(heights.size)
        loads = np.asarray(self.building.gravity_loads)
        weights = loads - np.append(loads[1:], 0.0)  # the floor weights back from P_x
        rows = []
        for i in range(heights.size):
            rows.append({
                "story": i + 1, "height_mm": float(heights[i]), "weight_n": float(weights[i]),
                "cvx": float(self.cvx[i]), "force_n": float(self.forces[i]),
                "story_shear_n": float(self.story_shears[i]),
                "drift_story_shear_n": float(drift_shears[i]), "gravity_load_n": float(loads[i]),
                "stiffness_n_per_mm": float(self.stiffnesses[i]), "governing": self.governing[i],
                "elastic_drift_mm": float(self.elastic_drifts[i]), "design_drift_mm": float(self.design_drifts[i]),
                "allowable_drift_mm": float(self.allowable_drifts[i]),
                "drift_ratio": float(self.design_drifts[i] / heights[i]), "theta": float(self.theta[i]),
                "theta_max": self.theta_max, "p_delta_factor": float(factors[i]),
                "strength_n": float(self.strengths[i]),
            })
        return rows

    def table(self) -> str:
        """The ELF table as markdown: the scalars with their clauses, then one row per story, then the
        assumptions."""
        s = self.summary()
        s1 = "not given" if self.site.s1 is None else f"{self.site.s1:.4g} g"
        lines = [
            f"## Frame by ASCE 7-16 Chapter 12 (ELF, Sec. 12.8): {self.system.name}",
            "",
            f"- System: {self.system.describe()}",
            f"- Site: S_DS = {self.site.sds:.4g} g, S_D1 = {self.site.sd1:.4g} g, S_1 = {s1}, "
            f"T_L = {self.site.tl:g} s; Risk Category {self.risk_category}, I_e = {self.importance:g} (Table 1.5-2); "
            f"SDC {self.sdc} (Sec. 11.6); rho = {self.rho:g} (Sec. 12.3.4)",
            f"- h_n = {self.height:.6g} mm = {s['height_ft']:.4g} ft; W = {self.weight:.6g} N",
            f"- T_a = C_t h_n^x = {self.ta:.4f} s (Eq. 12.8-7); C_u = {self.cu:.4g} (Table 12.8-1); "
            f"C_u T_a = {s['cu_ta_s']:.4f} s",
            f"- T_1 = {self.analytical_period:.4f} s (bare elastic frame, {self.iterations} iterations); "
            f"T = min(T_1, C_u T_a) = {self.period:.4f} s (Sec. 12.8.2)",
            f"- C_s = {self.cs:.5g} (Eq. {self.cs_equation}); V = C_s W = {self.base_shear:.6g} N (Eq. 12.8-1); "
            f"k = {self.k:.4g} (Sec. 12.8.3)",
            f"- Drift forces: T_1 = {self.drift_period:.4f} s (Sec. 12.8.6.2), C_s = {self.cs_drift:.5g} "
            f"(Eq. {self.drift_equation}; Eq. 12.8-5 not applied, Sec. 12.8.6.1), k = {self.drift_k:.4g}",
            f"- Strength = V_x x P-Delta factor x overstrength {self.overstrength:g} x strength_scale "
            f"{self.strength_scale:g}; theta_max = {self.theta_max:.4g} (Eq. 12.8-17, beta = {BETA:g})",
            "",
            "| story | h (mm) | C_vx | F_x (N) | V_x (N) | V_x drift (N) | P_x (N) | k (N/mm) | governs | "
            "delta_xe (mm) | delta_x (mm) | Delta_a/rho (mm) | theta | 1/(1-theta) | strength (N) |",
            "|" + "---|" * 15,
        ]
        for row in self.rows():
            lines.append(
                f"| {row['story']} | {row['height_mm']:.6g} | {row['cvx']:.4f} | {row['force_n']:.6g} | "
                f"{row['story_shear_n']:.6g} | {row['drift_story_shear_n']:.6g} | {row['gravity_load_n']:.6g} | "
                f"{row['stiffness_n_per_mm']:.6g} | {row['governing']} | {row['elastic_drift_mm']:.4g} | "
                f"{row['design_drift_mm']:.4g} | {row['allowable_drift_mm']:.4g} | {row['theta']:.4f} | "
                f"{row['p_delta_factor']:.4f} | {row['strength_n']:.6g} |")
        lines += ["", "Assumptions:", *[f"- {text}" for text in self.assumptions]]
        return "\n".join(lines) + "\n"

    def save(self, path: Any) -> Any:
        """Write :meth:`rows` as CSV to ``path`` (atomically, :func:`vdw_frames._files.write_csv`); returns the
        path."""
        return write_csv(path, self.rows(), "ELF table")


def _story_model(story_model: object, hardening: float) -> Callable[[float], Bilinear | BoucWen]:
    """A function yield force (N) -> story model."""
    if story_model is None:
        return lambda strength: Bilinear(strength, hardening)
    if not callable(story_model):
        raise ValueError(f"story_model must be a function of the yield force (N) returning a Bilinear or "
                         f"BoucWen model (e.g. vdw_frames.BoucWen), got {show(story_model)}")
    return story_model


def first_period(masses: np.ndarray, stiffnesses: np.ndarray) -> float:
    """T_1 (s) of the bare elastic shear building: the smallest eigenvalue of M^-1/2 K M^-1/2 (tridiagonal).
    ``masses`` tonne, ``stiffnesses`` N/mm (story 1 first)."""
    k_next = np.append(stiffnesses[1:], 0.0)
    with np.errstate(over="ignore", invalid="ignore"):
        diagonal = (stiffnesses + k_next) / masses
        off = -stiffnesses[1:] / np.sqrt(masses[:-1] * masses[1:])
    if not (np.isfinite(diagonal).all() and np.isfinite(off).all()):
        raise ValueError(f"the story stiffnesses {show(stiffnesses.tolist())} N/mm over the masses overflow: "
                         "give stiffnesses and weights of a building")
    if masses.size == 1:
        omega2 = float(diagonal[0])
    else:
        omega2 = float(eigh_tridiagonal(diagonal, off, eigvals_only=True, select="i", select_range=(0, 0))[0])
    return 2.0 * math.pi / math.sqrt(omega2)


def _story_shears(weights: np.ndarray, heights_above_base: np.ndarray, k: float, base_shear: float) -> tuple[
        np.ndarray, np.ndarray, np.ndarray]:
    """(C_vx, F_x, V_x): Eqs. 12.8-11, 12.8-12 and V_x = sum of F_i above (Eq. 12.8-13)."""
    cvx = code.vertical_distribution(weights, heights_above_base, k)
    forces = cvx * base_shear
    return cvx, forces, np.cumsum(forces[::-1])[::-1]


def _drift_stiffness(shears: np.ndarray, loads: np.ndarray, heights: np.ndarray, allowable: np.ndarray, cd: float,
                     ie: float) -> np.ndarray:
    """The least stiffness (N/mm) of each story whose design drift with P-Delta (Sec. 12.8.7) meets ``allowable``:
    k_1 = C_d V_x / (I_e allowable) where theta = P_x / (k_1 h_sx) <= 0.10, else the smaller of k_1 + P_x / h_sx
    (amplified drift at the limit) and the stiffness at theta = 0.10 (not amplified)."""
    plain = cd * shears / (ie * allowable)
    # theta = 0.10 there; 1e-12 stiffer so that rounding cannot put theta a hair above 0.10 (and amplify the drift)
    threshold = loads / (code.THETA_AMPLIFY * heights) * (1.0 + 1e-12)
    return np.where(plain >= threshold, plain, np.minimum(plain + loads / heights, threshold))


def _floors(weights: ArrayLike, story_heights: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """(w, h) checked: one weight (N, > 0) and one height (mm, > 0) a story."""
    w = finite_array("weights", weights)
    h = finite_array("story_heights", story_heights)
    if w.size == 0:
        raise ValueError("weights must hold one seismic weight (N) a floor, got none")
    if w.size != h.size:
        raise ValueError(f"weights has {w.size} values and story_heights {h.size}: give one of each a story")
    if (w <= 0).any():
        raise ValueError(f"weights must be > 0 (N), got {show(w[w <= 0].tolist())} at floor(s) "
                         f"{(np.flatnonzero(w <= 0) + 1).tolist()}")
    if (h <= 0).any():
        raise ValueError(f"story_heights must be > 0 (mm), got {show(h[h <= 0].tolist())} at story(ies) "
                         f"{(np.flatnonzero(h <= 0) + 1).tolist()}")
    return w, h


def _factors(overstrength: float, strength_scale: float, minimum_stiffness: ArrayLike,
             stories: int) -> tuple[float, float, np.ndarray]:
    """(overstrength >= 1, strength_scale in (0, 1], minimum stiffness per story >= 0) checked."""
    overstrength = finite_scalar("overstrength", overstrength)
    if overstrength < 1.0:
        raise ValueError(f"overstrength must be >= 1 (strength / design story shear), got {show(overstrength)}")
    strength_scale = finite_scalar("strength_scale", strength_scale)
    if not 0.0 < strength_scale <= 1.0:
        raise ValueError(f"strength_scale must lie in (0, 1], got {show(strength_scale)}")
    if np.ndim(minimum_stiffness) == 0:
        minimum = np.full(stories, finite_scalar("minimum_stiffness", minimum_stiffness))
    else:
        minimum = finite_array("minimum_stiffness", minimum_stiffness)
    if minimum.size != stories or (minimum < 0).any():
        raise ValueError(f"minimum_stiffness must be one value >= 0 (N/mm) or one a story ({stories}), got "
                         f"{show(minimum_stiffness)}")
    return overstrength, strength_scale, minimum


def _check_height(spec: SeismicSystem, sdc: str, height: float) -> None:
    """ValueError where the system is not permitted in the SDC or h_n exceeds its Table 12.2-1 limit."""
    height_ft = height / code.FT
    limit = spec.height_limit_ft(sdc)
    if limit is not None and limit == 0.0:
        raise ValueError(f"{spec.name} are not permitted (NP) in Seismic Design Category {sdc} (ASCE 7-16 "
                         f"{spec.table_row}; footnotes not applied)")
    if limit is not None and height_ft > limit:
        raise ValueError(f"height h_n = {height:.6g} mm = {height_ft:.4g} ft exceeds the {limit:g} ft limit of "
                         f"{spec.name} in Seismic Design Category {sdc} (ASCE 7-16 {spec.table_row}; footnotes "
                         "not applied)")


@dataclass(frozen=True)
class _Stiffness:
    """The result of the fixed point of stiffness and T_1."""

    stiffnesses: np.ndarray
    governing: tuple[str, ...]
    analytical_period: float
    drift_period: float
    cs_drift: float
    drift_equation: str
    drift_k: float
    drift_shears: np.ndarray
    iterations: int


def _stiffness(site: Site, spec: SeismicSystem, ie: float, w: np.ndarray, h: np.ndarray, *, allowable: np.ndarray,
               minimum: np.ndarray, start: float) -> _Stiffness:
    """Iterate stiffness and T_1 to their fixed point, from T_1 = ``start`` (s)."""
    masses, loads, levels = w / G, np.cumsum(w[::-1])[::-1], np.cumsum(h)
    stability = loads / (code.theta_max(BETA, spec.cd) * h)
    drift_period = start
    for iteration in range(1, MAX_ITERATIONS + 1):
        cs_drift, drift_equation = code.seismic_response_coefficient(site.sds, site.sd1, site.s1, site.tl,
                                                                     drift_period, spec.r, ie, minimum=False)
        drift_k = code.distribution_exponent(drift_period)
        _, _, drift_shears = _story_shears(w, levels, drift_k, cs_drift * float(w.sum()))
        by_drift = _drift_stiffness(drift_shears, loads, h, allowable, spec.cd, ie)
        stiffnesses = np.maximum(np.maximum(by_drift, stability), minimum)
        t1 = first_period(masses, stiffnesses)
        if abs(t1 - drift_period) <= PERIOD_TOLERANCE * t1:
            candidates = np.vstack([by_drift, stability, minimum])
            governing = tuple(("drift", "stability", "minimum")[int(np.argmax(column))] for column in candidates.T)
            return _Stiffness(stiffnesses, governing, t1, drift_period, cs_drift, drift_equation, drift_k,
                              drift_shears, iteration)
        drift_period = t1
    raise ValueError(f"the analytical period T_1 did not settle in {MAX_ITERATIONS} iterations of stiffness "
                     f"and drift forces (last T_1 = {drift_period:.6g} s); give a minimum_stiffness")


def design_frame(site: Site, system: str | SeismicSystem, weights: ArrayLike, story_heights: ArrayLike, *,
                 risk_category: object = None, rho: float | None = None, overstrength: float = 1.0,
                 hardening: float = 0.03, minimum_stiffness: ArrayLike = 0.0, story_model: object = None,
                 strength_scale: float = 1.0, damping_ratio: float = 0.05,
                 damping_modes: tuple[int, int] = (1, 2)) -> FrameDesign:
    """Design a shear-building frame by ASCE 7-16 Sec. 12.8 (ELF); see the module docstring for the procedure.

    Parameters
    ----------
    site : vdw_frames.verification.Site
        S_MS, S_M1 (g; S_DS = 2/3 S_MS, S_D1 = 2/3 S_M1), T_L (s), and S_1 (g) when known (Eq. 12.8-6, Sec. 11.6).
    system : str or SeismicSystem
        "steel-smf", "steel-imf", "steel-omf", "rc-smf" (:data:`vdw_frames.asce7.SYSTEMS`) or a SeismicSystem.
    weights : sequence of float
        Seismic weight of each floor (N, > 0; floor 1 first).  Masses = weights / g; P_x = the weights above.
    story_heights : sequence of float
        h_sx (mm, > 0; story 1 first), as many as ``weights``.
    risk_category : "I" ... "IV", optional
        Default: the site's.
    rho : float, optional
        Redundancy factor (1.0 or 1.3, Sec. 12.3.4).  Default 1.0 in SDC B-C, 1.3 in D-F.
    overstrength : float
        Story yield strength / design story shear (>= 1; default 1.0, the code minimum as P695 archetypes are
        designed; the system's Omega_0 is the upper bound the user may give).
    hardening : float
        Post-yield stiffness ratio of the Bilinear stories (0 <= b < 1).
    minimum_stiffness : float or sequence of float
        Least story stiffness (N/mm, >= 0), one value or one a story.
    story_model : callable, optional
        yield force (N) -> a Bilinear or BoucWen model (e.g. ``vdw_frames.BoucWen``); default Bilinear with
        ``hardening``.
    strength_scale : float
        0 < s <= 1: the design story shears for strength are multiplied by it (Chapter 18's V_min / V).
        Drift is checked with the unreduced Chapter 12 forces.
    damping_ratio, damping_modes
        The building's inherent damping (ShearBuilding); the default modes (1, 2) become (1, 1) for one story.

    Returns
    -------
    FrameDesign

    Raises
    ------
    ValueError
        Naming the value: an unknown system or risk category; weights and story heights of different lengths
        or not > 0; a height beyond the system's limit for the SDC (Table 12.2-1) or a system not permitted in
        it; SDC A (Sec. 11.7: ELF does not apply); a strength_scale outside (0, 1]; no fixed point of T_1; a
        story with theta > theta_max.
    """
    if not isinstance(site, Site):
        raise ValueError(f"site must be a vdw_frames.verification.Site (S_MS, S_M1, T_L, ...), got {show(site)}")
    spec = seismic_system(system)
    category = code.risk_category(site.risk_category if risk_category is None else risk_category)
    w, h = _floors(weights, story_heights)
    overstrength, strength_scale, minimum = _factors(overstrength, strength_scale, minimum_stiffness, h.size)
    make_model = _story_model(story_model, hardening)
    ie = code.importance_factor(category)
    sdc = code.seismic_design_category(site.sds, site.sd1, site.s1, category)
    if sdc == "A":
        raise ValueError(f"the site is Seismic Design Category A (S_DS = {site.sds:.4g} g, S_D1 = {site.sd1:.4g} g): "
                         "ASCE 7-16 Sec. 11.7 applies, not the ELF procedure of Sec. 12.8")
    height = float(h.sum())
    _check_height(spec, sdc, height)
    rho_value = code.default_redundancy_factor(sdc) if rho is None else positive("rho", rho)
    if rho_value not in (1.0, 1.3):
        raise ValueError(f"rho must be 1.0 or 1.3 (ASCE 7-16 Sec. 12.3.4), got {show(rho)}")
    divisor = code.design_drift_limit_divisor(spec, sdc, rho_value)
    loads = np.cumsum(w[::-1])[::-1]  # P_x: the weight at and above story x
    weight = float(w.sum())
    allowable = code.allowable_story_drift_ratio(category) * h / divisor
    ta = code.approximate_period(height, spec)
    cu = code.upper_limit_coefficient(site.sd1)
    limit_theta = code.theta_max(BETA, spec.cd)

    found = _stiffness(site, spec, ie, w, h, allowable=allowable, minimum=minimum, start=cu * ta)
    stiffnesses, t1 = found.stiffnesses, found.analytical_period
    elastic = found.drift_shears / stiffnesses
    theta = code.stability_coefficient(loads, code.design_displacement(elastic, spec.cd, ie), ie,
                                       found.drift_shears, h, spec.cd)
    for story, value in enumerate(theta, start=1):
        code.check_stability(value, limit_theta, story)
    factors = np.array([code.p_delta_amplification(value) for value in theta])
    design_drifts = code.design_displacement(elastic, spec.cd, ie) * factors

    period = min(t1, cu * ta)
    cs, equation = code.seismic_response_coefficient(site.sds, site.sd1, site.s1, site.tl, period, spec.r, ie)
    base_shear = cs * weight
    k = code.distribution_exponent(period)
    cvx, forces, shears = _story_shears(w, np.cumsum(h), k, base_shear)
    with np.errstate(over="ignore"):
        strengths = shears * factors * overstrength * strength_scale
    if not np.isfinite(strengths).all():
        raise ValueError(f"the story strengths overflow (overstrength = {show(overstrength)}, story shears up to "
                         f"{shears.max():.6g} N)")
    models = [make_model(float(value)) for value in strengths]
    for story, model in enumerate(models, start=1):
        if not isinstance(model, STORY_MODELS):
            raise ValueError(f"story_model returned {show(model)} for story {story}; it must return a Bilinear "
                             "or BoucWen model")
    modes = None if h.size == 1 and tuple(damping_modes) == (1, 2) else damping_modes  # one story: its only mode
    building = ShearBuilding(w / G, stiffnesses, damping_ratio=damping_ratio, damping_modes=modes,
                             story_heights=h, hysteresis=models, gravity_loads=loads)
    assumptions = _assumptions(spec, site, category, sdc, rho_value, rho is None, divisor, strength_scale, period,
                               height)
    return FrameDesign(
        building=building, site=site, system=spec, risk_category=category, importance=ie, sdc=sdc, rho=rho_value,
        height=height, ta=ta, cu=cu, analytical_period=t1, period=period, drift_period=found.drift_period, cs=cs,
        cs_equation=equation, cs_drift=found.cs_drift, weight=weight, base_shear=base_shear,
        strength_scale=strength_scale, k=k, cvx=cvx, forces=forces, story_shears=shears, strengths=strengths,
        elastic_drifts=elastic, design_drifts=design_drifts, allowable_drifts=allowable, theta=theta,
        theta_max=limit_theta, stiffnesses=stiffnesses, governing=found.governing, assumptions=assumptions,
        overstrength=overstrength, drift_equation=found.drift_equation, drift_k=found.drift_k,
        drift_story_shears=found.drift_shears, p_delta_factors=factors, iterations=found.iterations)


def _assumptions(spec: SeismicSystem, site: Site, category: str, sdc: str, rho: float, default_rho: bool,  # noqa: PLR0917
                 divisor: float, strength_scale: float, period: float, height: float) -> tuple[str, ...]:
    """Every assumption of the design, in words."""
    assumptions = [
        f"System coefficients R = {spec.r:g}, Omega_0 = {spec.omega0:g}, C_d = {spec.cd:g} and height limits from "
        f"ASCE 7-16 {spec.table_row}; footnotes of Table 12.2-1 that raise height limits are not applied.",
        "T_1 is the first period of the bare elastic shear building (masses = weights / g, no P-Delta, no devices).",
        "Drift forces use T_1 without the C_u T_a cap (Sec. 12.8.6.2) and without Eq. 12.8-5 (Sec. 12.8.6.1); "
        "Eq. 12.8-6 applies where S_1 >= 0.6 g; k at T_1.",
        "Strength uses T = min(T_1, C_u T_a) (Sec. 12.8.2); C_u interpolated linearly in Table 12.8-1.",
        f"theta_max = 0.5 / (beta C_d) with beta = {BETA:g} (Sec. 12.8.7 permits 1.0); P_x = the seismic weight at "
        "and above the story (no separate gravity load combination).",
        "Where theta > 0.10 the drifts and story strengths are multiplied by 1 / (1 - theta) (Sec. 12.8.7's "
        "alternative to a rational analysis).",
        f"Drift limit: Table 12.12-1 'all other structures' ({code.allowable_story_drift_ratio(category):g} h_sx), "
        + (f"divided by rho = {rho:g} (Sec. 12.12.1.1, moment frame in SDC {sdc})." if divisor != 1.0 else
           "not divided by rho (Sec. 12.12.1.1 applies to moment frames in SDC D-F only)."),
        ("rho = 1.3 (ASCE 7-16 Sec. 12.3.4.2; the conditions for 1.0 are not checked: give rho=1.0 where they are "
         "met)." if default_rho and rho == 1.3 else f"rho = {rho:g} (Sec. 12.3.4)."),
        *([f"Story strengths are V_x (Q_E) without rho: ASCE 7-16 Sec. 12.4.2.1 takes E_h = rho Q_E = {rho:g} Q_E "
           "for member design; give overstrength to include it."] if rho != 1.0 else []),
        f"Drift is checked with the unreduced Chapter 12 forces; strength_scale = {strength_scale:g} scales "
        "strength only.",
        "The structure is taken as regular (no irregularity of Tables 12.3-1/12.3-2 is checked), with no "
        "torsion and no accidental eccentricity (a planar shear building).",
    ]
    if site.s1 is None:
        assumptions.append("S_1 is not known (site given by S_MS, S_M1): Eq. 12.8-6 and the S_1 >= 0.75 g rule of "
                           "Sec. 11.6 are not applied.")
    if sdc in ("D", "E", "F") and height > ELF_HEIGHT_LIMIT and period >= ELF_PERIOD_LIMIT * site.ts:
        assumptions.append(f"h_n > 160 ft and T = {period:.3f} s >= 3.5 T_S = {ELF_PERIOD_LIMIT * site.ts:.3f} s "
                           f"in SDC {sdc}: "
                           "ASCE 7-16 Table 12.6-1 does not permit the ELF procedure here (modal response spectrum "
                           "analysis, Sec. 12.9, or response history analysis is required); the ELF forces are used "
                           "as a preliminary design, to be verified by response history analysis.")
    return tuple(assumptions)
