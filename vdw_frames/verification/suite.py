"""Selection and amplitude scaling of a suite of ground motions to the MCE_R spectrum: ASCE 7-16 Sec. 16.2.

ASCE 7-16 itself was not at hand: the rules below were read from secondary sources (the ASCE 7-16 chair's
slides on the new Chapter 16, Hamburger 2014, and a transcription of the ASCE 7-22 wording, believed the same in
substance for 2016; not verified against the printed 2016 text or its Supplement 1):

* Sec. 16.2.2: a suite of not fewer than 11 ground motions (:data:`MIN_RECORDS`);
* Sec. 16.2.3.1 period range: upper bound >= 2 T_1 (the largest first-mode period; 1.5 T_1 "if justified" is not
  offered here); lower bound <= 0.2 T_1 and low enough to include the modes needed for 90 % of the mass in
  the direction considered.  Implemented: ``T_upper = 2 T_1``, ``T_lower = min(0.2 T_1, T_90)``, the
  periods being those of the building *with its walls* (complex modal analysis,
  :func:`vdw_frames.frame.modal.modal_analysis`; amplitude-following walls fixed at the log-centre of their
  identified range, :meth:`ShearBuilding.walls_at`), T_90 the period (with walls) of the lowest mode at which
  the cumulative effective modal mass of the bare frame's real modes reaches 90 % (the walls hardly change the
  shapes; the participation of complex modes is not defined the same way);
* Sec. 16.2.3.2 amplitude scaling: the mean of the suite's spectra shall not fall below 90 % of the target at
  any period of the range.  The standard's spectra are maximum-direction spectra of the two components; a planar
  shear building takes one component, whose own 5 %-damped spectrum is used here (not larger than the
  maximum-direction spectrum: scaling it to the maximum-direction MCE_R target is conservative).

What this module adds, stated as its own choices (not the standard's):

* selection: each record's misfit of spectral shape is the root-mean-square, over periods evenly spaced in
  log T across the range, of ln(a_i S_i(T) / S_T(T)) with a_i = exp(mean ln(S_T / S_i)), the factor that best
  fits it in the log sense; the ``count`` records of smallest misfit are selected (with ``one_per_event``, at
  most one component of a FEMA P695 record);
* scaling ("one factor per record, as small as the rule allows"): record i gets f_i = c a_i, where c is the
  smallest common factor for which mean_i(f_i S_i(T)) >= 0.9 S_T(T) at every period of the grid.  At the
  governing period the mean is exactly 90 %, so lowering any one factor breaks the rule: no factor can be made
  smaller alone.  The rule is checked at the grid's periods (evenly spaced in log T, at most 1 % apart).
* records must last at least :data:`MIN_CYCLES` periods T_upper (shorter ones cannot build up the response at
  the long end of the range).

Units: spectral accelerations mm/s^2 (g only in :class:`~vdw_frames.verification.spectrum.Site`), periods s.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from .._validation import damping_ratio as _damping_ratio
from .._validation import show, whole_number
from ..frame.building import ShearBuilding
from ..frame.modal import modal_analysis
from ..motion.record import GroundMotion
from .spectrum import Site

MIN_RECORDS = 11
"""ASCE 7-16 Sec. 16.2.2: not fewer than 11 ground motions (secondary source: Hamburger 2014)."""
UPPER_FACTOR = 2.0
"""ASCE 7-16 Sec. 16.2.3.1: upper bound of the period range >= 2 T_1 (secondary source)."""
LOWER_FACTOR = 0.2
"""ASCE 7-16 Sec. 16.2.3.1: lower bound of the period range <= 0.2 T_1 (secondary source)."""
MASS_FRACTION = 0.9
"""ASCE 7-16 Sec. 16.2.3.1 (as transcribed for ASCE 7-22): the range includes the modes giving 90 % of the mass."""
MEAN_FRACTION = 0.9
"""ASCE 7-16 Sec. 16.2.3.2: the suite's mean spectrum >= 90 % of the target over the period range."""
MIN_CYCLES = 5.0
"""This package's rule, not the standard's: a record lasts at least 5 periods T_upper."""
GRID_RATIO = 1.01
"""Largest ratio of neighbouring periods of the grid on which the rules are applied (1 % steps)."""


@dataclass(frozen=True)
class PeriodRange:
    """The period range of ASCE 7-16 Sec. 16.2.3.1 for a building (module docstring).

    ``lower``, ``upper`` (s): T_lower = min(0.2 T_1, T_90), T_upper = 2 T_1.  ``periods`` (s): the periods of
    the building with its walls, mode 1 first (complex modal analysis); ``first_period`` = T_1;
    ``mass_participation`` (-): the cumulative effective mass fraction of the bare frame's modes 1, 2, ...;
    ``mass_mode``: the lowest mode at which it reaches 90 %; ``mass_period`` (s): T_90, that mode's period
    with walls.
    """

    lower: float
    upper: float
    periods: np.ndarray
    first_period: float
    mass_participation: np.ndarray
    mass_mode: int
    mass_period: float

    def describe(self) -> str:
        """One line stating the range and where its ends come from (the clause as read: module docstring)."""
        return (f"period range {self.lower:.3f} ... {self.upper:.3f} s (ASCE 7-16 Sec. 16.2.3.1, read in ASCE 7-22 "
                f"wording): T_upper = "
                f"2 T_1 = 2 x {self.first_period:.3f} s; T_lower = min(0.2 T_1 = {0.2 * self.first_period:.3f} s, "
                f"T_{self.mass_mode} = {self.mass_period:.3f} s where the modes reach "
                f"{100 * self.mass_participation[self.mass_mode - 1]:.1f} % of the mass); periods with the walls and "
                "linear devices (nonlinear FVDs and friction dampers left out)")


def period_range(building: ShearBuilding) -> PeriodRange:
    """The period range (s) of ASCE 7-16 Sec. 16.2.3.1 for ``building``, its periods computed with its walls
    and linear devices (module docstring: T_lower = min(0.2 T_1, T_90), T_upper = 2 T_1).  Amplitude-following
    walls are fixed at the log-centre of their identified range (:meth:`ShearBuilding.walls_at`); nonlinear
    FVDs and friction dampers are left out (:meth:`ShearBuilding.without_nonlinear_devices`: the period must
    not depend on an assumed amplitude)."""
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    fixed = building.walls_at() if building.strain_dependent else building
    modal = modal_analysis(fixed.without_nonlinear_devices())
    periods = np.asarray(modal.periods, dtype=float)
    # effective modal masses of the bare frame's real modes (mass-normalised shapes): (phi^T M 1)^2
    masses = np.asarray(building.masses, dtype=float)
    gamma = building.mode_shapes.T @ masses
    participation = np.cumsum(gamma**2) / masses.sum()
    mass_mode = int(np.searchsorted(participation, MASS_FRACTION - 1e-12) + 1)
    mass_mode = min(mass_mode, building.stories)
    mass_period = float(periods[mass_mode - 1]) if mass_mode <= periods.size else float(building.periods[mass_mode - 1])
    first = float(periods[0])
    return PeriodRange(lower=min(LOWER_FACTOR * first, mass_period), upper=UPPER_FACTOR * first, periods=periods,
                       first_period=first, mass_participation=participation, mass_mode=mass_mode,
                       mass_period=mass_period)


def period_grid(lower: float, upper: float) -> np.ndarray:
    """Periods (s) from ``lower`` to ``upper`` (both included), evenly spaced in log T at most 1 % apart."""
    points = max(2, math.ceil(math.log(upper / lower) / math.log(GRID_RATIO)) + 1)
    return np.geomspace(lower, upper, points)


@dataclass(frozen=True)
class ScaledSuite:
    """A suite of records selected and scaled to the MCE_R spectrum (ASCE 7-16 Sec. 16.2; module docstring).

    ``motions``: the selected records as given (unscaled, mm/s^2); ``factors`` (-): the amplitude factor of
    each; ``misfits`` (-): each one's misfit of spectral shape (rms of log residuals); ``site``; ``range``
    (:class:`PeriodRange`); ``periods`` (s): the grid over the range; ``spectra`` (mm/s^2, (records, periods)):
    the unscaled records' spectra on it; ``target`` (mm/s^2): the MCE_R spectrum there; ``damping_ratio``;
    ``governing_period`` (s): where the mean is exactly 90 % of the target; ``candidates``: how many records
    the suite was chosen from.
    """

    motions: tuple[GroundMotion, ...]
    factors: np.ndarray
    misfits: np.ndarray
    site: Site
    range: PeriodRange
    periods: np.ndarray
    spectra: np.ndarray
    target: np.ndarray
    damping_ratio: float
    governing_period: float
    candidates: int

    @property
    def scaled_motions(self) -> tuple[GroundMotion, ...]:
        """The records times their factors."""
        return tuple(motion.scaled(float(f)) for motion, f in zip(self.motions, self.factors, strict=True))

    @property
    def scaled_spectra(self) -> np.ndarray:
        """Spectra of the scaled records on ``periods`` (mm/s^2, (records, periods))."""
        return self.spectra * self.factors[:, None]

    @property
    def mean_spectrum(self) -> np.ndarray:
        """The suite's mean spectrum on ``periods`` (mm/s^2)."""
        return self.scaled_spectra.mean(axis=0)

    @property
    def component_note(self) -> str:
        """What the suite's spectra are: one horizontal component's, standing in for the clause's
        maximum-direction spectra (module docstring), as the report and the console print it."""
        return ("the clause scales maximum-direction spectra of the two horizontal components; this planar analysis "
                f"takes one component per record, and that component's own {100 * self.damping_ratio:g} %-damped "
                "spectrum stands in for the maximum-direction spectrum (it is not larger, so scaling it to the "
                "maximum-direction MCE_R target is conservative)")

    @property
    def ratio(self) -> np.ndarray:
        """mean spectrum / target on ``periods`` (-): >= 0.9 everywhere (Sec. 16.2.3.2)."""
        return self.mean_spectrum / self.target


def _one_per_event(order: np.ndarray, motions: list[GroundMotion], count: int) -> list[int]:
    chosen: list[int] = []
    events: set[tuple[object, object]] = set()
    for index in order.tolist():
        metadata = motions[index].metadata
        key = (getattr(metadata, "record_set", None), getattr(metadata, "record_id", None))
        if key[1] is not None and key in events:
            continue
        events.add(key)
        chosen.append(index)
        if len(chosen) == count:
            break
    return chosen


def scaled_suite(building: ShearBuilding, site: Site, records: Iterable[GroundMotion], count: int = MIN_RECORDS,
                 *, damping_ratio: float = 0.05, one_per_event: bool = True) -> ScaledSuite:
    """Select ``count`` (>= 11) of ``records`` and scale them to ``site``'s MCE_R spectrum as ASCE 7-16 Sec. 16.2
    asks (module docstring: the clauses as read, and the selection and minimal-factor rule implemented).

    ``building``: a :class:`ShearBuilding` with story heights (drift ratios are what Sec. 16.4 checks); its
    periods with walls set the range (:func:`period_range`).  ``records``: GroundMotion objects (mm/s^2), e.g.
    ``fema_p695_records("far-field")``, or a user's own suite (pass ``count=len(records)`` to keep every
    one of them).  ``damping_ratio``: of the spectra (default 5 %, the
    MCE_R spectrum's).  ``one_per_event``: at most one component of each FEMA P695 record (records whose
    metadata has a ``record_id``).  ValueError naming the value for: fewer than 11 records asked for or given,
    records shorter than 5 T_upper, a building without story heights.
    """
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    if building.story_heights is None:
        raise ValueError("the building has no story heights: ASCE 7-16 Sec. 16.4 checks story drift ratios; give "
                         "story_heights (mm)")
    if not isinstance(site, Site):
        raise ValueError(f"site must be a Site, got {type(site).__name__}")
    count = whole_number("count", count, 1)
    if count < MIN_RECORDS:
        raise ValueError(f"count = {show(count)}: ASCE 7-16 Sec. 16.2.2 asks for not fewer than {MIN_RECORDS} "
                         "ground motions")
    if isinstance(records, GroundMotion):
        raise ValueError("records must be a list of GroundMotion objects, got one GroundMotion")
    motions = list(records)
    bad = next((m for m in motions if not isinstance(m, GroundMotion)), None)
    if bad is not None:
        raise ValueError(f"records must be GroundMotion objects, got {type(bad).__name__} {show(bad)}")
    if len(motions) < count:
        raise ValueError(f"{len(motions)} records given: ASCE 7-16 Sec. 16.2.2 asks for a suite of not fewer than "
                         f"{count} ground motions" + (f" (count = {count})" if count > MIN_RECORDS else ""))
    if not isinstance(one_per_event, (bool, np.bool_)):
        raise ValueError(f"one_per_event must be True or False, got {show(one_per_event)}")
    zeta = _damping_ratio(damping_ratio)
    bounds = period_range(building)
    shortest = MIN_CYCLES * bounds.upper
    for motion in motions:
        if motion.duration < shortest:
            raise ValueError(f"record {motion.name or '(unnamed)'!r} lasts {motion.duration:.4g} s, shorter than "
                             f"{MIN_CYCLES:g} x T_upper = {shortest:.4g} s (period range {bounds.lower:.3g} ... "
                             f"{bounds.upper:.3g} s): too short for the period range")
    periods = period_grid(bounds.lower, bounds.upper)
    target = site.spectral_acceleration(periods)
    spectra = np.array([motion.spectrum(periods, zeta) for motion in motions])
    if (spectra <= 0).any():
        row = int(np.nonzero((spectra <= 0).any(axis=1))[0][0])
        raise ValueError(f"record {motions[row].name or row!r} has a zero spectral acceleration in the period range")
    logs = np.log(target[None, :] / spectra)
    fit = logs.mean(axis=1)  # ln a_i: the best fit in the log sense
    misfit = np.sqrt(((logs - fit[:, None]) ** 2).mean(axis=1))
    order = np.argsort(misfit, kind="stable")
    chosen = _one_per_event(order, motions, count) if one_per_event else order[:count].tolist()
    if len(chosen) < count:
        raise ValueError(f"only {len(chosen)} distinct records among the {len(motions)} given (one component per "
                         f"record): ASCE 7-16 Sec. 16.2.2 asks for {count}; pass one_per_event=False to use both")
    shape_factors = np.exp(fit[chosen])
    mean = (spectra[chosen] * shape_factors[:, None]).mean(axis=0)
    needed = MEAN_FRACTION * target / mean
    governing = int(np.argmax(needed))
    factors = shape_factors * needed[governing]
    return ScaledSuite(motions=tuple(motions[i] for i in chosen), factors=factors, misfits=misfit[chosen],
                       site=site, range=bounds, periods=periods, spectra=spectra[chosen], target=target,
                       damping_ratio=zeta, governing_period=float(periods[governing]), candidates=len(motions))
