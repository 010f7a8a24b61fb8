"""Design verification of a building with walls: ASCE 7-16 Chapter 16 analyses at the Chapter 18 property bounds.

:func:`verify` selects and scales a suite to the site's MCE_R spectrum (:mod:`.suite`, Sec. 16.2), runs it at the
nominal, upper- and lower-bound wall properties and judges the results:

* **bounds** (Sec. 18.2.4.5, property modification factors; the clause's text was searched for and NOT found,
  so its composition of lambda_ae, lambda_test and lambda_spec is offered as recalled, :func:`composed_factors`):
  the user states the combined factors lambda_min <= 1 <= lambda_max (:class:`PropertyBounds`, or
  :meth:`PropertyBounds.from_parts`) and whether they include temperature, applied to every wall as
  ``wall.scaled(lambda)`` (moduli and viscosities times lambda: K*(f) scales, the loss factor does not).  Walls
  with a thermal description (:class:`~vdw_frames.ThermalProperties`) also heat in every analysis, and an
  ambient temperature range (``PropertyBounds(ambient=(coldest, hottest))``) starts each wall, besides lambda,
  at the end of the range that bounds the case's quantity -- the upper bound (forces) at the end of the larger
  |K*|, the lower bound (displacements) at that of the smaller K'' (:meth:`PropertyBounds.ambient_end`): K'
  and K'' change by different factors, reported at the first mode (:func:`stiffness_factors`).
* **unacceptable responses** (Sec. 16.4.1.1): an analysis whose story drift ratio exceeded the collapse limit
  (``collapse_drift_ratio``), that did not converge, whose drift ratio exceeded ``valid_drift_ratio`` (the
  largest drift the story models are valid for, if given), in which a wall failed (its
  :class:`~vdw_frames.element.limits.WallLimits`), or in which a wall's strain went beyond the upper end of the
  amplitudes its parameters were identified for (``strain_range``: the wall model is not valid there).  Allowed
  per bound: Risk Category I and II, not more than 1 of the suite (the ASCE 7-16 chair's slides, Hamburger 2014:
  "For Risk Category II Structures not more than 1 motion can produce unacceptable response"); Risk Category III
  and IV: none -- from recollection of the standard, NOT verified in any source read (the strict reading).
* **story drift statistic** (Sec. 16.4.1.2, as transcribed for ASCE 7-22; believed the same for 7-16, not
  verified; the outputs cite it as read in ASCE 7-22 wording, :data:`DRIFT_CLAUSE`): per story and bound,
  the mean over the suite of the peak drift ratio <= 2 x the allowable drift of Table 12.12-1 (row "all other
  structures": 0.020, 0.020, 0.015, 0.010 h_sx for Risk Categories I, II, III, IV; the table was NOT read
  from the standard: values as recalled and partly corroborated by secondary sources), i.e. 0.040 for Risk
  Category II.  Where some response is unacceptable the statistic is taken over the acceptable ones as
  max(mean, 1.2 x median) (the ASCE 7-22 transcription's rule; conservative); where none is acceptable, the
  mean of all, the unacceptable ones included (this package's fallback, not read in the clause's
  transcription).  The outputs name each case's statistic and how many records stand behind it
  (:func:`drift_statistic_basis`).  Compared to a relative 1e-12, so that a mean exactly at the limit passes
  despite round-off.
* **device test demands** (Sec. 18.6, prototype tests; its text was NOT read): per wall, over the suite and the
  bounds: the largest deformation (mm, the wall's own: strain x thickness), strain (-), velocity (mm/s, the
  central-difference derivative of the deformation history), force (N), energy of one cycle (N mm: the work
  f d(delta) between successive upward zero crossings of the deformation) and cumulative energy (N mm: the work
  over the record), and temperature rise (K, walls that heat); from them, the prototype test specification
  written by :func:`prototype_test_specification` (this package's rule, stated there).
* **other devices** (fluid viscous and friction dampers, :mod:`vdw_frames.element.devices`): each bound scales
  every such device by its lambda through ``device.scaled(lambda)`` -- a fluid viscous damper's C (its force at
  a given velocity: lambda_max gives the largest damper forces, lambda_min the least damping, so usually the
  largest displacements), a friction damper's slip force (the largest forces at lambda_max; whether the
  smaller slip force gives the larger drifts depends on the amplitude, and both bounds are run and reported);
  exponent alpha, brace and elastic stiffness are kept.  One pair of factors serves
  every device of the building (a device kind with factors of its own needs a verification of its own).  Per
  device, :class:`DeviceDemand` reports the largest force (N), deformation (mm) and velocity (mm/s) along the
  device over the suite, at each bound.  ASCE 7-16 Sec. 18.1 (definitions, read in an extract of the 2016
  text) calls a device velocity-dependent when its force-displacement relation is primarily a function of the
  relative velocity between its ends, displacement-dependent when its force response is primarily a function
  of the relative displacement (the ASCE 7-22 draft's Sec. 18.1.2, read too, classes devices the same way, "or
  a combination thereof"); that the device demands are the force, displacement and velocity at both bounds is
  this package's reading of Sec. 18.2.4.5 and 18.6 (their text was NOT read).

Units: N, mm, s; drift ratios -, energies N mm, temperatures K.
"""

from __future__ import annotations

import concurrent.futures
import math
import os
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .. import _warnings
from .._parallel import check_executor, executor_for, fan_out, reissue, spread
from .._validation import positive, show, text
from ..element.bank import group_walls
from ..element.device import Device
from ..element.kernel import FAILURE_MODES
from ..element.thermal import service_temperature
from ..element.viscous import FluidViscousDamper
from ..frame.building import ShearBuilding, is_wall
from ..frame.lanes import LaneResult, lane_batches, run_lanes
from ..frame.results import SimulationResult
from ..motion.record import GroundMotion
from . import spectrum
from .spectrum import Site
from .suite import MIN_RECORDS, ScaledSuite, period_range, scaled_suite

ALLOWABLE_DRIFT = {"I": 0.020, "II": 0.020, "III": 0.015, "IV": 0.010}
"""ASCE 7-16 Table 12.12-1, "all other structures", Delta_a / h_sx by Risk Category (NOT read from the standard:
recalled, partly corroborated by secondary sources)."""
DRIFT_FACTOR = 2.0
"""ASCE 7-16 Sec. 16.4.1.2: the mean drift limit is 2 x Table 12.12-1 (ASCE 7-22 wording, secondary)."""
ALLOWED_UNACCEPTABLE = {"I": 1, "II": 1, "III": 0, "IV": 0}
"""ASCE 7-16 Sec. 16.4.1.1: unacceptable responses allowed in a suite (I, II: Hamburger 2014; III, IV: recalled,
not verified)."""
MEDIAN_FACTOR = 1.2
"""Where responses are unacceptable: the drift statistic is max(mean, 1.2 x median) of the acceptable ones
(ASCE 7-22 wording as transcribed; not verified for ASCE 7-16)."""
DRIFT_CLAUSE = ("ASCE 7-16 Sec. 16.4.1.2 (read in ASCE 7-22 wording), Table 12.12-1 (values recalled, not read "
                "from the standard)")
"""How the outputs cite the drift criterion: the clause was read in a transcription of the ASCE 7-22 wording
(:data:`DRIFT_FACTOR`, :data:`MEDIAN_FACTOR`), the table's values recalled (:data:`ALLOWABLE_DRIFT`)."""
UNACCEPTABLE_CLAUSE = {
    **dict.fromkeys(("I", "II"), "ASCE 7-16 Sec. 16.4.1.1 (read in the ASCE 7-16 chair's slides, Hamburger 2014)"),
    **dict.fromkeys(("III", "IV"), "ASCE 7-16 Sec. 16.4.1.1 (Risk Category III-IV's count recalled, not read)")}
"""How the outputs cite the count of unacceptable responses, by Risk Category (:data:`ALLOWED_UNACCEPTABLE`)."""


def drift_statistic_basis(acceptable: int, records: int) -> str:
    """What the drift statistic of a case is (Sec. 16.4.1.2, read in ASCE 7-22 wording), given how many of the
    suite's ``records`` gave an ``acceptable`` response: the mean of all of them when every one is acceptable;
    max(mean, 1.2 x median) of the acceptable ones when some are not; when none is, the mean of all, the
    unacceptable ones included -- this package's fallback, not read in the clause's transcription."""
    if acceptable == records:
        return f"mean of all {records} records"
    if acceptable > 0:
        return f"max(mean, {MEDIAN_FACTOR:g} x median) of the {acceptable} acceptable of {records} records"
    return f"mean of all {records} records, unacceptable ones included (none acceptable)"


AGING_ENVIRONMENT_WEIGHT = 0.75
"""The share of the aging and environmental factor's departure from 1 that enters lambda_max and lambda_min: ASCE
7-16 Sec. 18.2.4.5, Eqs. 18.2-1 and 18.2-2, as RECALLED (the same form as Sec. 17.2.8.4, Eqs. 17.2-1 and
17.2-2, for isolators): lambda_max = (1 + 0.75 (lambda_ae,max - 1)) lambda_test,max lambda_spec,max and
lambda_min = (1 - 0.75 (1 - lambda_ae,min)) lambda_test,min lambda_spec,min.  The clause's text was searched for
and NOT found in the stored sources (FEMA P-1050's chapter on ASCE 7-16 Chapter 18, read, confirms only that the
2016 edition added "sections for the determination of the maximum and minimum damper properties"): check the
composition against the standard before relying on it."""


def _factor_pair(name: str, value: object) -> tuple[float, float]:
    """(lambda_min <= 1, lambda_max >= 1) of one source of variation, as given."""
    if not isinstance(value, (tuple, list)) or len(value) != 2:
        raise ValueError(f"{name} must be (lambda_min, lambda_max), got {show(value)}")
    low, high = (positive(f"{name} lambda", v) for v in value)
    if not low <= 1.0 <= high:
        raise ValueError(f"{name} must be (lambda_min <= 1, lambda_max >= 1), got {show(value)}")
    return low, high


def composed_factors(aging_environment: tuple[float, float] = (1.0, 1.0), testing: tuple[float, float] = (1.0, 1.0),
                     specification: tuple[float, float] = (1.0, 1.0)) -> tuple[float, float]:
    """(lambda_min, lambda_max) (-) composed from their parts as ASCE 7-16 Sec. 18.2.4.5 does (Eqs. 18.2-1 and 18.2-2
    as recalled, NOT read: :data:`AGING_ENVIRONMENT_WEIGHT`): each part a (min, max) pair around 1 --
    ``aging_environment`` (lambda_ae: aging, contamination, environmental exposure, and temperature unless the
    walls' own law bounds it: :class:`PropertyBounds` ``lambda_includes_temperature``), ``testing``
    (lambda_test: the prototype tests' variation, heating, rate and cycle effects) and ``specification``
    (lambda_spec: the manufacturing tolerance the specification allows).

        lambda_max = (1 + 0.75 (lambda_ae,max - 1)) lambda_test,max lambda_spec,max
        lambda_min = (1 - 0.75 (1 - lambda_ae,min)) lambda_test,min lambda_spec,min
    """
    ae_min, ae_max = _factor_pair("aging_environment", aging_environment)
    test_min, test_max = _factor_pair("testing", testing)
    spec_min, spec_max = _factor_pair("specification", specification)
    upper = (1.0 + AGING_ENVIRONMENT_WEIGHT * (ae_max - 1.0)) * test_max * spec_max
    lower = (1.0 - AGING_ENVIRONMENT_WEIGHT * (1.0 - ae_min)) * test_min * spec_min
    return lower, upper


BOUND_QUANTITIES = {"upper": "forces", "lower": "displacements"}
"""What each bound is for (ASCE 7-16 Sec. 18.2.4.5's intent, as this package reads it): the upper-bound
(maximum) properties give the larger damper and frame forces, the lower-bound (minimum) ones the larger
displacements and drifts; every response quantity is then taken from the case that governs it."""


@dataclass(frozen=True)
class PropertyBounds:
    """Property modification factors of the walls (ASCE 7-16 Sec. 18.2.4.5): the combined ``lower``
    (lambda_min, 0 < lambda_min <= 1) and ``upper`` (lambda_max >= 1) factors, applied as ``wall.scaled(lambda)``;
    ``source``: where they come from (stated in the report).  :meth:`from_parts` composes them from the aging and
    environment, testing and specification factors (:func:`composed_factors`).

    ``ambient`` (degC, (coldest, hottest)), optional: the range of temperatures the walls serve in (service
    temperatures: above absolute zero, at most 200 degC).  Each bound then starts every wall (``wall.at_ambient``,
    heating from there) at the end of the range that makes it bound its quantity (:data:`BOUND_QUANTITIES`),
    chosen per wall at the first mode's frequency (:meth:`ambient_end`): the upper bound (forces) at the end of
    the larger force per unit deformation |K*|, the lower bound (displacements) at the end of the smaller loss
    stiffness K'' (the energy a cycle dissipates, pi K'' d^2).  A temperature is not one factor: it shifts the
    wall along its own frequency curve, and K' and K'' move differently -- colder is always stiffer (an FDMK wall's
    K' rises with frequency) but not always more damped: past the Maxwell branch's loss peak K'' falls with
    frequency, so a cold wall can dissipate less (the paper's sets as one family, at 318 % and 10 degC: K' x 1.30
    but K'' x 0.834 at 0.607 Hz, the example frame's first mode; at 30 degC x 0.77 and x 0.72).  Where the end
    of the smaller K'' is not that of the smaller K', no single end bounds both; :func:`verify` warns then.  The
    nominal analyses keep the walls' own temperature.  Every wall needs a thermal description with an ambient
    range.

    ``lambda_includes_temperature``: whether lambda_min and lambda_max already include the effect of
    temperature (True), or not (False), or it is not stated (None, the default; the report says so).  With an
    ambient range it must not be True: temperature would be counted twice.
    """

    lower: float
    upper: float
    source: str = "stated by the user"
    ambient: tuple[float, float] | None = None
    lambda_includes_temperature: bool | None = None

    def __post_init__(self) -> None:
        lower, upper = positive("lambda_min", self.lower), positive("lambda_max", self.upper)
        if lower > 1.0:
            raise ValueError(f"lambda_min must be <= 1 (the lower-bound properties), got {show(self.lower)}")
        if upper < 1.0:
            raise ValueError(f"lambda_max must be >= 1 (the upper-bound properties), got {show(self.upper)}")
        object.__setattr__(self, "lower", lower)
        object.__setattr__(self, "upper", upper)
        text("source", self.source)
        if self.lambda_includes_temperature is not None and not isinstance(self.lambda_includes_temperature, bool):
            raise ValueError(f"lambda_includes_temperature must be True, False or None (not stated), got "
                             f"{show(self.lambda_includes_temperature)}")
        if self.ambient is not None:
            values = self.ambient
            if not isinstance(values, (tuple, list)) or len(values) != 2:
                raise ValueError(f"ambient must be (coldest, hottest) in degC, got {show(values)}")
            cold, hot = (service_temperature("ambient temperature", value) for value in values)
            if not cold <= hot:
                raise ValueError(f"ambient must be (coldest, hottest) in degC, coldest first, got {show(values)}")
            if self.lambda_includes_temperature:
                raise ValueError(f"an ambient range {show(values)} degC with lambda_includes_temperature=True would "
                                 "count temperature twice: give lambda without temperature, or no ambient range")
            object.__setattr__(self, "ambient", (cold, hot))

    @classmethod
    def from_parts(cls, aging_environment: tuple[float, float] = (1.0, 1.0),
                   testing: tuple[float, float] = (1.0, 1.0), specification: tuple[float, float] = (1.0, 1.0), *,
                   source: str = "stated by the user", ambient: tuple[float, float] | None = None,
                   lambda_includes_temperature: bool | None = None) -> PropertyBounds:
        """Bounds whose lambda_min and lambda_max are :func:`composed_factors` of the parts (each (min, max), -);
        ``source`` gets the parts appended."""
        lower, upper = composed_factors(aging_environment, testing, specification)
        parts = (f"lambda_ae {show(tuple(aging_environment))}, lambda_test {show(tuple(testing))}, lambda_spec "
                 f"{show(tuple(specification))} composed as ASCE 7-16 Eqs. 18.2-1 and 18.2-2 (as recalled)")
        return cls(lower, upper, f"{source}; {parts}", ambient, lambda_includes_temperature)

    @property
    def cases(self) -> tuple[tuple[str, float], ...]:
        """(name, lambda) of the analyses: nominal, upper bound, lower bound."""
        return (("nominal", 1.0), ("upper", self.upper), ("lower", self.lower))

    def ambient_end(self, wall: Any, case: str, frequency: float) -> float | None:
        """The ambient temperature (degC) ``wall`` starts from in ``case``; None: its own (nominal, or no ambient
        range).  The end of the range that bounds the case's quantity (class docstring): "upper", the larger
        |K*(frequency)|; "lower", the smaller K''(frequency); the wall isothermal at each end (an amplitude-dependent
        wall at the centre of its range), ``frequency`` in Hz.  The colder end where the two ends tie."""
        if self.ambient is None or case == "nominal":
            return None
        _thermal_needed(wall, self.ambient)
        cold, hot = self.ambient
        stiffness = [complex(_isothermal(wall.at_ambient(t)).complex_stiffness(positive("frequency", frequency)))
                     for t in (cold, hot)]
        if case == "upper":
            return cold if abs(stiffness[0]) >= abs(stiffness[1]) else hot
        return hot if stiffness[1].imag < stiffness[0].imag else cold

    def discordant(self, wall: Any, frequency: float) -> bool:
        """True when the lower bound's end (the smaller K'') is not also the end of the smaller K' for ``wall`` at
        ``frequency`` (Hz): no one ambient end bounds both (False without an ambient range)."""
        if self.ambient is None:
            return False
        end = self.ambient_end(wall, "lower", frequency)
        storage = [float(_isothermal(wall.at_ambient(t)).storage_stiffness(frequency)) for t in self.ambient]
        softer = self.ambient[0] if storage[0] < storage[1] else self.ambient[1]
        return storage[0] != storage[1] and end != softer

    def temperature(self, case: str) -> float | None:
        """Deprecated: the ends are chosen per wall (:meth:`ambient_end`).  The coldest end for "upper", the
        hottest for "lower" (what the bounds took before 0.3.0), None for "nominal" or without a range."""
        warnings.warn("PropertyBounds.temperature is deprecated: each bound's ambient end is chosen per wall by the "
                      "quantity it bounds (PropertyBounds.ambient_end)", DeprecationWarning, stacklevel=2)
        if self.ambient is None or case == "nominal":
            return None
        return self.ambient[0] if case == "upper" else self.ambient[1]

    def wall(self, wall: Any, case: str, frequency: float | None = None) -> Any:
        """``wall`` as analysed in ``case`` ("nominal", "upper", "lower"): at the case's ambient end, if any
        (:meth:`ambient_end` at ``frequency`` Hz), then times its lambda.  Without ``frequency`` an ambient
        range is deprecated: the ends taken before 0.3 (the coldest for "upper", the hottest for "lower") are used,
        with a DeprecationWarning; from 0.4 it will be needed."""
        factor = dict(self.cases)[case]
        if self.ambient is not None and case != "nominal":
            if frequency is None:
                warnings.warn("PropertyBounds.wall without the frequency (Hz) at which the ambient end is chosen is "
                              "deprecated: the coldest end is used for 'upper' and the hottest for 'lower', "
                              "whichever bounds the quantity; give the first mode's (PropertyBounds.building finds "
                              "it)", DeprecationWarning, stacklevel=2)
                _thermal_needed(wall, self.ambient)
                temperature: float | None = self.ambient[0] if case == "upper" else self.ambient[1]
            else:
                temperature = self.ambient_end(wall, case, frequency)
            wall = wall.at_ambient(temperature)
        return wall.scaled(factor) if factor != 1.0 else wall

    def device(self, device: Device, case: str) -> Device:
        """A device that is not a wall as analysed in ``case``: ``device.scaled(lambda)`` (a fluid viscous
        damper's C, a friction damper's slip force; module docstring), itself at the nominal case."""
        factor = dict(self.cases)[case]
        return device.scaled(factor) if factor != 1.0 else device

    def building(self, building: ShearBuilding, case: str, frequency: float | None = None) -> ShearBuilding:
        """``building`` with every wall as analysed in ``case`` (:meth:`wall`) and every other device too
        (:meth:`device`), each on its story in its place; ``frequency`` (Hz) at which the ambient ends are chosen,
        by default 1 / T_1 of ``building`` with its walls (complex modal analysis)."""
        if self.ambient is not None and case != "nominal" and frequency is None:
            for _, wall in building.wall_list:
                _thermal_needed(wall, self.ambient)
            frequency = 1.0 / period_range(building).first_period
        return building.with_devices({
            story: tuple(self.wall(device, case, frequency) if is_wall(device) else self.device(device, case)
                         for device in devices)
            for story, devices in building.devices.items()})


def _thermal_needed(wall: Any, ambient: tuple[float, float]) -> None:
    if wall.thermal is None:
        raise ValueError(f"ambient bounds {ambient} degC need walls with a thermal description "
                         "(thermal=ThermalProperties(...)); a wall has none")


def stiffness_factors(building: ShearBuilding, bounds: PropertyBounds, frequency: float) -> np.ndarray:
    """(cases, walls, 2): K'(f) and K''(f) of every wall in each case of ``bounds`` over the nominal wall's, at
    ``frequency`` (Hz), each wall isothermal at the temperature it starts from (amplitude-dependent walls at
    the centre, in logarithm, of their identified range; a temperature beyond the shift law's range held at its
    end, as the analyses do).  With lambda only both columns are lambda."""
    factors = np.empty((len(bounds.cases), len(building.wall_list), 2))
    for c, (case, _) in enumerate(bounds.cases):
        for j, (_, wall) in enumerate(building.wall_list):
            nominal, bounded = _isothermal(wall), _isothermal(bounds.wall(wall, case, frequency))
            factors[c, j] = (bounded.storage_stiffness(frequency) / nominal.storage_stiffness(frequency),
                             bounded.loss_stiffness(frequency) / nominal.loss_stiffness(frequency))
    return factors


def _isothermal(wall: Any) -> Any:
    """The wall at its starting temperature and, for an amplitude-dependent wall, at its range's centre."""
    if wall.follows_amplitude:
        wall = wall.at(wall.centre_strain)
    thermal = wall.thermal
    return wall.at_temperature(thermal.temperature) if thermal is not None else wall


@dataclass(frozen=True)
class WallDemand:
    """The test demands on one wall over the suite and the bounds (Sec. 18.6; units in the names' docs).

    ``story``; ``wall``: its index in ``building.wall_list``; ``deformation`` (mm), ``strain`` (-),
    ``velocity`` (mm/s), ``force`` (N): largest magnitudes; ``cycle_energy`` (N mm): the largest work of one
    cycle; ``cumulative_energy`` (N mm): the largest work over one record; ``temperature_rise`` (K; None when
    the wall does not heat); ``governing``: "bound, record" of the largest deformation only (every other value
    is the largest over all the bounds and records, each from its own: ``VerificationResult.wall_peaks``);
    ``cooling_time`` (s): its thermal description's (inf: adiabatic, the heat kept in the layers; None when
    the wall does not heat).
    """

    story: int
    wall: int
    deformation: float
    strain: float
    velocity: float
    force: float
    cycle_energy: float
    cumulative_energy: float
    temperature_rise: float | None
    governing: str
    cooling_time: float | None = None


@dataclass(frozen=True)
class DeviceDemand:
    """The demands on one device that is not a wall (a fluid viscous or friction damper) over the suite, at
    each bound (module docstring): ``story``; ``device``: its index in ``building.other_device_list`` (the
    columns of a result's device histories); ``description``: ``device.describe()`` (nominal properties);
    ``velocity_dependent``: True for a fluid viscous damper; ``force`` (N), ``deformation`` (mm) and
    ``velocity`` (mm/s): case name ("nominal", "upper", "lower") -> the largest magnitude along the device
    over the suite's records."""

    story: int
    device: int
    description: str
    velocity_dependent: bool
    force: dict[str, float]
    deformation: dict[str, float]
    velocity: dict[str, float]


@dataclass(frozen=True)
class Criterion:
    """One acceptance criterion: ``name``, ``clause``, ``passed``, ``value`` and ``limit`` (its units in
    ``text``), ``governing`` ("bound, record / story" that decides it) and a one-line ``text``."""

    name: str
    clause: str
    passed: bool
    value: float
    limit: float
    governing: str
    text: str


@dataclass(frozen=True)
class VerificationResult:
    """What :func:`verify` found (module docstring).

    ``suite`` (:class:`~vdw_frames.verification.suite.ScaledSuite`); ``bounds``; ``cases``: (name, lambda) of
    the analyses; ``peak_drift_ratio`` (-, (cases, records, stories)); ``collapsed``, ``converged`` (bool,
    (cases, records)); ``unacceptable``: per case and record the reasons ("" when acceptable);
    ``drift_statistic`` (-, (cases, stories)): the mean, or the statistic of Sec. 16.4.1.2 with unacceptable
    responses (:meth:`drift_statistic_basis` says which, over how many records); ``drift_limit`` (-);
    ``allowed_unacceptable``; ``criteria``; ``walls`` (:class:`WallDemand` per wall); ``wall_peaks``: each
    analysis's :func:`wall_peaks`, name -> (cases, records, walls) (:meth:`wall_governing` names the analysis of
    each wall's largest); ``specification``: the prototype test specification text; ``first_period`` (s, with
    walls);
    ``stiffness_factors`` (-, (cases, walls, 2)): each case's K' and K'' of every wall over the nominal, at
    1 / ``first_period`` (:func:`stiffness_factors`; they differ where an ambient range is bounded);
    ``ambient_ends`` (degC, (cases, walls)): the ambient temperature each wall starts from in each case
    (:meth:`PropertyBounds.ambient_end`; None: its own).  ``devices``: a :class:`DeviceDemand` per device that
    is not a wall; ``device_peaks``: each analysis's :func:`device_peaks`, name -> (cases, records, devices).
    """

    site: Site
    suite: ScaledSuite
    bounds: PropertyBounds
    cases: tuple[tuple[str, float], ...]
    peak_drift_ratio: np.ndarray
    collapsed: np.ndarray
    converged: np.ndarray
    unacceptable: tuple[tuple[str, ...], ...]
    drift_statistic: np.ndarray
    drift_limit: float
    allowed_unacceptable: int
    criteria: tuple[Criterion, ...]
    walls: tuple[WallDemand, ...]
    wall_peaks: dict[str, np.ndarray]
    specification: str
    first_period: float
    stiffness_factors: np.ndarray
    ambient_ends: tuple[tuple[float | None, ...], ...] = ()
    devices: tuple[DeviceDemand, ...] = ()
    device_peaks: dict[str, np.ndarray] = field(default_factory=dict)

    def ambient_range(self, case: str) -> str:
        """The ambient temperatures (degC) the walls start from in ``case``, as text ("" for their own)."""
        c = [name for name, _ in self.cases].index(case)
        ends = sorted({end for end in self.ambient_ends[c] if end is not None}) if self.ambient_ends else []
        return " and ".join(f"{end:g} degC" for end in ends)

    def drift_statistic_basis(self, case: str) -> str:
        """What ``drift_statistic`` holds for ``case`` and over how many of the suite's records (the module
        function :func:`drift_statistic_basis`), e.g. "max(mean, 1.2 x median) of the 2 acceptable of 11
        records"."""
        reasons = self.unacceptable[[name for name, _ in self.cases].index(case)]
        return drift_statistic_basis(sum(not reason for reason in reasons), len(reasons))

    def wall_governing(self, name: str, wall: int) -> str:
        """"case, record" of the analysis that gave wall ``wall``'s (index in ``walls``) largest ``name``
        (one of :data:`WALL_PEAKS`) in ``wall_peaks``: the first such analysis, cases in order; "" where the
        wall does not heat (temperature_rise)."""
        return _governing(self.wall_peaks[name][:, :, wall], self.cases, _record_names(self.suite.motions))

    @property
    def passed(self) -> bool:
        """True when every criterion passed."""
        return all(criterion.passed for criterion in self.criteria)


# ----------------------------------------------------------------------------------------------- the demands
def wall_histories(result: SimulationResult) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(deformation mm, velocity mm/s, force N) histories of every wall, (steps, walls): deformation = strain x
    thickness (the wall's own), velocity its central-difference derivative (``numpy.gradient``)."""
    thickness = np.array([wall.thickness for _, wall in result.building.wall_list], dtype=float)
    deformation = result.wall_strain * thickness
    dt = float(result.time[1] - result.time[0]) if result.time.size > 1 else 1.0
    velocity = np.gradient(deformation, dt, axis=0) if deformation.shape[0] > 1 else np.zeros_like(deformation)
    return deformation, velocity, result.wall_force


def cycle_energies(deformation: np.ndarray, force: np.ndarray) -> tuple[float, float]:
    """(largest work of one cycle, total work) of one wall (N mm): the trapezoidal work sum f d(delta) over the
    history, and over each cycle between successive upward zero crossings of ``deformation`` (mm), the
    crossing taken at the first sample >= 0 after one < 0.  Without a complete cycle, the largest is the total."""
    work = np.concatenate([[0.0], np.cumsum(0.5 * (force[1:] + force[:-1]) * np.diff(deformation))])
    crossings = np.nonzero((deformation[:-1] < 0.0) & (deformation[1:] >= 0.0))[0] + 1
    total = float(work[-1])
    if crossings.size < 2:
        return total, total
    return float(np.max(np.diff(work[crossings]))), total


def unacceptable_reasons(result: SimulationResult, valid_drift_ratio: float | None = None) -> list[str]:
    """Why one analysis's response is unacceptable in the sense of ASCE 7-16 Sec. 16.4.1.1 (module docstring):
    collapse, non-convergence, a drift ratio (-) beyond ``valid_drift_ratio``, a failed wall, a wall strained
    beyond the upper end of its identified range.  Empty when acceptable."""
    return _reasons(result.building, collapsed=bool(result.collapsed), collapse_time=result.collapse_time,
                    converged=bool(result.converged), peak_drift_ratio=result.peak_drift_ratio,
                    failed=result.wall_failed, failure_mode=result.wall_failure_mode,
                    peak_strain=np.abs(result.wall_strain).max(axis=0, initial=0.0),
                    valid_drift_ratio=valid_drift_ratio)


def _reasons(building: ShearBuilding, *, collapsed: bool, collapse_time: float | None, converged: bool,
             peak_drift_ratio: np.ndarray | None, failed: np.ndarray, failure_mode: Sequence[str],
             peak_strain: np.ndarray, valid_drift_ratio: float | None) -> list[str]:
    """:func:`unacceptable_reasons` of an analysis's outcome (collapse time s), peak drift ratios (-), each wall's
    failure (bool, and its mode) and peak |strain| (-, over the whole analysis), per wall of
    ``building.wall_list``: from a simulation's histories or a lane's peaks alike."""
    walls = building.wall_list
    peak_drift = peak_drift_ratio
    reasons = []
    if collapsed:
        reasons.append(f"collapse (drift ratio beyond the collapse limit at {collapse_time:.3g} s)")
    if not converged:
        reasons.append("non-convergence")
    if valid_drift_ratio is not None and peak_drift is not None and np.max(peak_drift) > valid_drift_ratio:
        story = int(np.argmax(peak_drift)) + 1
        reasons.append(f"drift ratio {np.max(peak_drift):.4g} in story {story} beyond the model's validity "
                       f"({valid_drift_ratio:g})")
    if failed.any():
        reasons.append("wall(s) " + ", ".join(f"{j + 1} ({failure_mode[j]})"
                                             for j in np.nonzero(failed)[0].tolist()) + " failed")
    beyond = []
    for j, (_, wall) in enumerate(walls):
        identified = wall.strain_range
        if identified is not None and not failed[j] and peak_strain[j] > identified[1]:
            beyond.append((j, peak_strain[j], identified[1]))
    if beyond:
        worst = max(beyond, key=lambda item: item[1] / item[2])
        reasons.append("wall(s) " + ", ".join(str(j + 1) for j, _, _ in beyond) + " strained beyond their identified "
                       f"range (up to {100 * worst[1]:.0f} % against {100 * worst[2]:.0f} % in wall {worst[0] + 1})")
    return reasons


WALL_PEAKS = ("deformation", "strain", "velocity", "force", "cycle_energy", "cumulative_energy", "temperature_rise")
"""The per-wall peaks of one analysis (:func:`wall_peaks`): mm, -, mm/s, N, N mm, N mm, K."""


def wall_peaks(result: SimulationResult) -> dict[str, np.ndarray]:
    """The device demands of one analysis, per wall in ``building.wall_list`` order (:data:`WALL_PEAKS`):
    largest |deformation| (mm), |strain| (-), |velocity| (mm/s, :func:`wall_histories`), |force| (N), the
    largest work of one cycle and the total work (N mm, :func:`cycle_energies`), the largest temperature rise
    (K; NaN for walls that do not heat).  A wall that failed (its limits) is taken up to the step it failed at:
    what follows is no longer the device's deformation."""
    deformation, velocity, force = wall_histories(result)
    walls = len(result.building.wall_list)
    dt = float(result.time[1] - result.time[0]) if result.time.size > 1 else 1.0
    ends = [deformation.shape[0] if t is None else min(round(float(t) / dt) + 1, deformation.shape[0])
            for t in result.wall_failure_time]
    strain = np.abs(result.wall_strain)
    peaks: dict[str, list[float]] = {name: [] for name in WALL_PEAKS[:-1]}
    for j, end in enumerate(ends):
        rows = slice(0, max(end, 1))
        largest, total = cycle_energies(deformation[rows, j], force[rows, j])
        for name, value in (("deformation", np.abs(deformation[rows, j]).max(initial=0.0)),
                            ("strain", strain[rows, j].max(initial=0.0)),
                            ("velocity", np.abs(velocity[rows, j]).max(initial=0.0)),
                            ("force", np.abs(force[rows, j]).max(initial=0.0)),
                            ("cycle_energy", largest), ("cumulative_energy", total)):
            peaks[name].append(float(value))
    rise = result.peak_temperature_rise
    return {**{name: np.array(values, dtype=float).reshape(walls) for name, values in peaks.items()},
            "temperature_rise": np.full(walls, np.nan) if rise is None else np.asarray(rise, dtype=float)}


DEVICE_PEAKS = ("force", "deformation", "velocity")
"""The per-device peaks of one analysis (:func:`device_peaks`): N, mm, mm/s."""


def device_peaks(result: SimulationResult) -> dict[str, np.ndarray]:
    """The largest |force| (N), |deformation| (mm) and |velocity| (mm/s) along every device that is not a wall,
    (devices,) in ``building.other_device_list`` order: the maxima of the result's ``device_force``,
    ``device_deformation`` and ``device_velocity`` histories (Newmark's velocity, as the devices were stepped)."""
    count = len(result.building.other_device_list)
    return {name: np.abs(getattr(result, f"device_{name}")).max(axis=0, initial=0.0).reshape(count)
            for name in DEVICE_PEAKS}


def _summary(result: SimulationResult, valid_drift_ratio: float | None) -> dict[str, Any]:
    """What verify keeps of one analysis, from its full histories: outcome, peak drift ratios, reasons it is
    unacceptable, wall and device peaks (the definition; verify takes the same from its lanes:
    :func:`_lane_summary`)."""
    peak_drift = result.peak_drift_ratio
    assert peak_drift is not None  # verify refuses buildings without story heights
    return {"collapsed": bool(result.collapsed), "converged": bool(result.converged),
            "peak_drift_ratio": np.asarray(peak_drift, dtype=float),
            "reasons": "; ".join(unacceptable_reasons(result, valid_drift_ratio)), **wall_peaks(result),
            **{f"device_{name}": value for name, value in device_peaks(result).items()}}


def _lane_summary(building: ShearBuilding, lane: LaneResult, valid_drift_ratio: float | None) -> dict[str, Any]:
    """:func:`_summary` of the analysis from its lane (:func:`~vdw_frames.frame.lanes.run_lanes` with
    ``wall_demands``): the same values, to the bit (tests/verification/test_verify_lanes.py)."""
    assert lane.peak_drift_ratio is not None and lane.wall_demands is not None  # story heights; wall demands asked
    group = group_walls(building.wall_list)[1]  # type: ignore[arg-type]  # fixed walls: verify's buildings
    failed = lane.group_failure_step[group] >= 0
    modes = lane.group_failure_mode
    rise = lane.peak_temperature_rise
    assert modes is not None  # run_lanes gives every lane's
    reasons = _reasons(building, collapsed=lane.collapsed, collapse_time=lane.collapse_time, converged=lane.converged,
                       peak_drift_ratio=lane.peak_drift_ratio, failed=failed,
                       failure_mode=[FAILURE_MODES[int(modes[g])] for g in group],
                       peak_strain=lane.peak_group_strain[group], valid_drift_ratio=valid_drift_ratio)
    walls = len(building.wall_list)
    return {"collapsed": lane.collapsed, "converged": lane.converged,
            "peak_drift_ratio": np.asarray(lane.peak_drift_ratio, dtype=float), "reasons": "; ".join(reasons),
            **{name: lane.wall_demands[name] for name in WALL_PEAKS[:-1]},
            "temperature_rise": np.full(walls, np.nan) if rise is None else rise[group],
            **{f"device_{name}": getattr(lane, f"peak_device_{name}") for name in DEVICE_PEAKS}}


@dataclass(frozen=True)
class _Batch:
    """Analyses of the verification on one bound's ``building``, each under ``motions[i].scaled(factors[i])``,
    run as the lanes of one compiled call (:func:`~vdw_frames.frame.lanes.run_lanes`); ``labels`` name them."""

    building: ShearBuilding
    motions: tuple[GroundMotion, ...]
    factors: tuple[float, ...]
    labels: tuple[str, ...]
    collapse_drift_ratio: float
    valid_drift_ratio: float | None

    def run(self) -> list[tuple[dict[str, Any], tuple[_warnings.CollectedWarning, ...]]]:
        """Each analysis's :func:`_summary` and the warnings simulate would have issued for it; an analysis that
        cannot run raises simulate's ValueError, named by its label."""
        lanes = run_lanes(self.building, self.motions, self.factors, collapse_drift_ratio=self.collapse_drift_ratio,
                          wall_demands=True)
        out = []
        for lane, label in zip(lanes, self.labels, strict=True):
            if lane.error is not None:
                raise ValueError(f"the analysis of {label} failed: {lane.error}")
            out.append((_lane_summary(self.building, lane, self.valid_drift_ratio), lane.warnings))
        return out


def _run(batch: _Batch) -> list[tuple[dict[str, Any], tuple[_warnings.CollectedWarning, ...]]]:
    return batch.run()  # module level: executors pickle it by name


# ----------------------------------------------------------------------------------------------- acceptance
def acceptance(peak_drift_ratio: np.ndarray, unacceptable: Sequence[Sequence[str]], risk: str = "II", *,
               cases: Sequence[str] = ("nominal", "upper", "lower"), records: Sequence[str] | None = None,
               allowable_drift_ratio: float | None = None) -> tuple[tuple[Criterion, ...], np.ndarray, float, int]:
    """The acceptance criteria of ASCE 7-16 Sec. 16.4.1.1 and 16.4.1.2 (module docstring) for peak story drift
    ratios (-, (cases, records, stories)) and each analysis's reasons of unacceptable response ("" when
    acceptable; (cases, records)).  ``risk``: Risk Category; ``allowable_drift_ratio``: Delta_a / h_sx of Table
    12.12-1 if not the "all other structures" row.  Returns (criteria, drift statistic (cases, stories), drift
    limit, unacceptable responses allowed): per case one criterion for the count and one for the drift."""
    drifts = np.asarray(peak_drift_ratio, dtype=float)
    if drifts.ndim != 3 or not np.isfinite(drifts).all() or (drifts < 0).any():
        raise ValueError(f"peak_drift_ratio must be finite, >= 0 and shaped (cases, records, stories), got shape "
                         f"{drifts.shape}")
    category = spectrum.risk_category(risk)
    n_cases, n_records, n_stories = drifts.shape
    if len(unacceptable) != n_cases or any(len(row) != n_records for row in unacceptable) or len(cases) != n_cases:
        raise ValueError(f"unacceptable and cases must match peak_drift_ratio's {n_cases} cases x {n_records} records")
    names = list(records) if records is not None else [f"record {i + 1}" for i in range(n_records)]
    allowable = ALLOWABLE_DRIFT[category] if allowable_drift_ratio is None else \
        positive("allowable_drift_ratio", allowable_drift_ratio)
    limit = DRIFT_FACTOR * allowable
    allowed = ALLOWED_UNACCEPTABLE[category]
    criteria = []
    statistic = np.zeros((n_cases, n_stories))
    for c, case in enumerate(cases):
        bad = [r for r in range(n_records) if unacceptable[c][r]]
        count_text = "; ".join(names[r] for r in bad) or "none"
        criteria.append(Criterion(
            name=f"unacceptable responses ({case})", clause=UNACCEPTABLE_CLAUSE[category], passed=len(bad) <= allowed,
            value=float(len(bad)), limit=float(allowed), governing=f"{case}: {count_text}",
            text=f"{len(bad)} of {n_records} unacceptable, {allowed} allowed for Risk Category {category} ({case}: "
                 f"{count_text})"))
        good = np.array([r for r in range(n_records) if r not in bad], dtype=int)
        if good.size == 0:  # nothing acceptable to take a statistic of: the mean of all, stated in the text
            statistic[c] = drifts[c].mean(axis=0)
        elif bad:
            statistic[c] = np.maximum(drifts[c, good].mean(axis=0), MEDIAN_FACTOR * np.median(drifts[c, good], axis=0))
        else:
            statistic[c] = drifts[c].mean(axis=0)
        story = int(np.argmax(statistic[c]))
        worst = float(statistic[c, story])
        record = names[int(np.argmax(drifts[c, :, story]))]
        how = drift_statistic_basis(int(good.size), n_records)
        criteria.append(Criterion(
            name=f"story drift ratio, {how} ({case})", clause=DRIFT_CLAUSE,
            passed=bool(worst <= limit * (1 + 1e-12)), value=worst, limit=limit,
            governing=f"{case}, story {story + 1}, largest single record {record}",
            text=f"{worst:.4f} in story {story + 1} vs {DRIFT_FACTOR:g} x {allowable:g} = {limit:.4f} "
                 f"({case}; largest single record there: {record})"))
    return tuple(criteria), statistic, limit, allowed


# ----------------------------------------------------------------------------------------------- test spec
def prototype_test_specification(walls: Sequence[WallDemand], frequency: float,
                                 devices: Sequence[DeviceDemand] = ()) -> str:
    """The prototype test specification (ASCE 7-16 Sec. 18.6; the clause's sequence and tolerances were NOT
    read, so this is this package's rule, stated in the text): per wall, sinusoidal cycles at ``frequency``
    (Hz, 1 / T_1 with the walls and linear devices, as :func:`~vdw_frames.verification.suite.period_range` takes
    it; the text says so when there are other devices) at the largest deformation; the number of cycles the
    energy-equivalent one, ceil(cumulative / largest cycle energy), but not fewer than 5; where the largest
    velocity exceeds the sine's 2 pi f A, a second frequency v_max / (2 pi A) that reaches it; the temperature
    rise to be reached or accounted for where the walls heat (said adiabatic where the wall does not cool).  Per
    other device (``devices``), the largest deformation, velocity and force over both bounds, which its tests
    are to reach."""
    frequency = positive("frequency", frequency)
    lines = [f"Prototype tests (ASCE 7-16 Sec. 18.6 as this package reads it; the clause's own sequence was not "
             f"available): sinusoidal cycles at f1 = {frequency:.3f} Hz (1/T1 with the walls) unless stated."]
    if devices:  # T1 as the suite's period range takes it (period_range): no assumed amplitude in it
        lines[0] = lines[0].replace("(1/T1 with the walls)", "(1/T1 with the walls and linear devices; nonlinear "
                                    "FVDs and friction dampers left out)")
    for demand in walls:
        if demand.deformation <= 0:
            lines.append(f"- wall {demand.wall + 1} (story {demand.story}): no deformation")
            continue
        cycles = 5 if demand.cycle_energy <= 0 else max(5, math.ceil(demand.cumulative_energy / demand.cycle_energy))
        sine_velocity = 2 * math.pi * frequency * demand.deformation
        text = (f"- wall {demand.wall + 1} (story {demand.story}): {cycles} cycles of +/- {demand.deformation:.1f} mm "
                f"(strain {100 * demand.strain:.0f} %) at {frequency:.3f} Hz, force up to {demand.force / 1e3:.1f} kN")
        if demand.velocity > sine_velocity:
            text += (f"; and cycles at {demand.velocity / (2 * math.pi * demand.deformation):.3f} Hz to reach the "
                     f"velocity {demand.velocity:.0f} mm/s")
        if demand.temperature_rise is not None and np.isfinite(demand.temperature_rise):
            text += f"; temperature rise {demand.temperature_rise:.1f} K{_heating(demand.cooling_time)} to be " \
                    "reached or accounted for"
        lines.append(text)
    for other in devices:
        lines.append(f"- device {other.device + 1} (story {other.story}, {other.description}): deformation +/- "
                     f"{max(other.deformation.values()):.1f} mm, velocity up to {max(other.velocity.values()):.0f} "
                     f"mm/s, force up to {max(other.force.values()) / 1e3:.1f} kN (largest of the bounds)")
    return "\n".join(lines)


def _heating(cooling_time: float | None) -> str:
    """" (adiabatic: ...)" or " (cooling ...)": how a wall's temperature rise was computed, from its thermal
    description's cooling time (s; inf: adiabatic); "" when not known (None)."""
    if cooling_time is None:
        return ""
    if math.isinf(cooling_time):
        return " (adiabatic: no cooling)"
    return f" (cooling with time constant {cooling_time:.3g} s)"


# ----------------------------------------------------------------------------------------------- verify
def verify(building: ShearBuilding, site: Site, records: Iterable[GroundMotion] | None = None, *,
           bounds: PropertyBounds | tuple[float, float] | None = None, risk_category: str | None = None,
           count: int = MIN_RECORDS, collapse_drift_ratio: float = 0.10, valid_drift_ratio: float | None = None,
           allowable_drift_ratio: float | None = None, executor: concurrent.futures.Executor | str | None = None,
           progress: bool = True) -> VerificationResult:
    """Verify ``building`` (with story heights) on ``site`` as ASCE 7-16 Chapters 16 and 18 ask (module
    docstring: each clause, and what was read from secondary sources only).

    ``records``: GroundMotion objects (mm/s^2) to select and scale ``count`` (>= 11) from (:func:`scaled_suite`);
    None: the FEMA P695 far-field components (needs the ``[p695]`` extra).  ``bounds``: the property
    modification factors (:class:`PropertyBounds` or (lambda_min, lambda_max)) -- required: the standard's
    values depend on the device's tests.  ``risk_category``: overrides ``site.risk_category``.
    ``collapse_drift_ratio`` (-): an analysis stops as collapsed beyond it; ``valid_drift_ratio`` (-): the
    largest drift ratio the story models are valid for (None: not checked).  ``allowable_drift_ratio``: Table
    12.12-1's Delta_a / h_sx if not the "all other structures" row.  ``executor``: any
    ``concurrent.futures.Executor``, or "threads" (the default, None) or "processes" for an own pool over all
    cores; ``progress``: a progress bar on standard error when it is a terminal.  Every analysis is that of
    :func:`vdw_frames.simulate` of the bound's building (:meth:`PropertyBounds.building`: walls at the bound's
    ambient temperature, if any, times lambda) under the scaled record, run as a lane
    (:func:`~vdw_frames.frame.lanes.run_lanes`: each bound's records in a few compiled calls, a task each on
    ``executor``; every peak, reason and demand equal to the bit to those
    :func:`wall_peaks`, :func:`device_peaks` and :func:`unacceptable_reasons` take from simulate's result); the
    package's warnings of each analysis are re-issued once, naming the case and record.  Returns a
    :class:`VerificationResult`.
    """
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    if building.story_heights is None:
        raise ValueError("the building has no story heights: ASCE 7-16 Sec. 16.4 checks story drift ratios; give "
                         "story_heights (mm)")
    if not isinstance(site, Site):
        raise ValueError(f"site must be a Site, got {type(site).__name__}")
    if bounds is None:
        raise ValueError("bounds are required: ASCE 7-16 Sec. 18.2.4.5 asks for the analyses at upper- and "
                         "lower-bound device properties; give bounds=(lambda_min, lambda_max) from the walls' tests "
                         "and specification")
    if not isinstance(bounds, PropertyBounds):
        if not isinstance(bounds, (tuple, list)) or len(bounds) != 2:
            raise ValueError(f"bounds must be PropertyBounds or (lambda_min, lambda_max), got {show(bounds)}")
        bounds = PropertyBounds(*bounds)
    if not building.devices:
        raise ValueError("the building has no walls and no other damping devices: there are no device properties "
                         "to bound")
    category = site.risk_category if risk_category is None else spectrum.risk_category(risk_category)
    collapse = positive("collapse_drift_ratio", collapse_drift_ratio)
    valid = None if valid_drift_ratio is None else positive("valid_drift_ratio", valid_drift_ratio)
    if records is None:
        from ..motion.p695 import fema_p695_records

        records = fema_p695_records("far-field")
    suite = scaled_suite(building, site, records, count)
    check_executor(executor)

    cases = bounds.cases
    first = suite.range.first_period
    variants = [bounds.building(building, case, 1.0 / first) for case, _ in cases]
    discordant = [f"story {story}" for story, wall in building.wall_list if bounds.discordant(wall, 1.0 / first)]
    if discordant:
        _warnings.warn(f"property bounds: for the walls of {', '.join(discordant)} no one end of the ambient range "
                       f"{bounds.ambient} degC bounds both K' and K'' at {1.0 / first:.3f} Hz (the lower bound takes "
                       "the end of the smaller K''; the other end has the smaller K'): the lower-bound displacements "
                       "may not be bounded -- verify at both ends", UserWarning, stacklevel=2)
    summaries = _run_all(variants, suite, collapse_drift_ratio=collapse, valid_drift_ratio=valid, executor=executor,
                         progress=progress, cases=cases)

    n_cases, n_records = len(cases), len(suite.motions)
    drifts = np.array([[summaries[(c, r)]["peak_drift_ratio"] for r in range(n_records)] for c in range(n_cases)])
    unacceptable = tuple(tuple(summaries[(c, r)]["reasons"] for r in range(n_records)) for c in range(n_cases))
    names = _record_names(suite.motions)
    criteria, statistic, limit, allowed = acceptance(
        drifts, unacceptable, category, cases=[c[0] for c in cases],
        records=names, allowable_drift_ratio=allowable_drift_ratio)
    peaks = {name: np.array([[summaries[(c, r)][name] for r in range(n_records)] for c in range(n_cases)])
             for name in WALL_PEAKS}
    walls = _wall_demands(building, peaks, cases, names)
    others = {name: np.array([[summaries[(c, r)][f"device_{name}"] for r in range(n_records)]
                              for c in range(n_cases)]).reshape(n_cases, n_records, len(building.other_device_list))
              for name in DEVICE_PEAKS}
    devices = tuple(
        DeviceDemand(story=story, device=j, description=device.describe(),
                     velocity_dependent=isinstance(device, FluidViscousDamper),
                     **{name: {case: float(others[name][c, :, j].max()) for c, (case, _) in enumerate(cases)}
                        for name in DEVICE_PEAKS})
        for j, (story, device) in enumerate(building.other_device_list))
    factors = stiffness_factors(building, bounds, 1.0 / first)
    return VerificationResult(
        site=site, suite=suite, bounds=bounds, cases=cases, peak_drift_ratio=drifts,
        collapsed=np.array([[summaries[(c, r)]["collapsed"] for r in range(n_records)] for c in range(n_cases)]),
        converged=np.array([[summaries[(c, r)]["converged"] for r in range(n_records)] for c in range(n_cases)]),
        unacceptable=unacceptable, drift_statistic=statistic, drift_limit=limit, allowed_unacceptable=allowed,
        criteria=criteria, walls=walls, wall_peaks=peaks,
        specification=prototype_test_specification(walls, 1.0 / first, devices), first_period=first,
        stiffness_factors=factors,
        ambient_ends=tuple(tuple(bounds.ambient_end(wall, case, 1.0 / first) for _, wall in building.wall_list)
                           for case, _ in cases),
        devices=devices, device_peaks=others)


def _wall_demands(building: ShearBuilding, peaks: dict[str, np.ndarray], cases: Sequence[tuple[str, float]],
                  names: Sequence[str]) -> tuple[WallDemand, ...]:
    demands = []
    for j, (story, wall) in enumerate(building.wall_list):
        rise = peaks["temperature_rise"][:, :, j]
        demands.append(WallDemand(
            story=story, wall=j, **{name: float(peaks[name][:, :, j].max()) for name in WALL_PEAKS[:-1]},
            temperature_rise=float(np.nanmax(rise)) if np.isfinite(rise).any() else None,
            governing=_governing(peaks["deformation"][:, :, j], cases, names),
            cooling_time=None if wall.thermal is None else float(wall.thermal.cooling_time)))
    return tuple(demands)


def _record_names(motions: Sequence[GroundMotion]) -> list[str]:
    """How the outputs name the suite's records: each record's name, else "record r" (1-based)."""
    return [motion.name or f"record {r + 1}" for r, motion in enumerate(motions)]


def _governing(values: np.ndarray, cases: Sequence[tuple[str, float]], names: Sequence[str]) -> str:
    """"case, record" of the analysis that gave the largest of ``values`` (cases, records), the first in case
    order; NaNs (a wall that does not heat) left out; "" when there is no number."""
    if not np.isfinite(values).any():
        return ""
    c, r = np.unravel_index(int(np.nanargmax(values)), values.shape)
    return f"{cases[int(c)][0]}, {names[int(r)]}"


def _run_all(variants: Sequence[ShearBuilding], suite: ScaledSuite, *, collapse_drift_ratio: float,
             valid_drift_ratio: float | None, executor: concurrent.futures.Executor | str | None, progress: bool,
             cases: Sequence[tuple[str, float]]) -> dict[tuple[int, int], dict]:
    """Every analysis (case c's building ``variants[c]`` under record r of the suite, scaled), keyed (c, r): each
    case's records in batches of lanes (:func:`~vdw_frames.frame.lanes.lane_batches`: one dt, one side of the
    walls' exact memory, a few a worker), each batch one task of :func:`vdw_frames._parallel.fan_out` (its
    progress bar counts analyses); their warnings re-issued once each, naming the record and the case."""
    motions = suite.motions

    def label(key: tuple[int, int]) -> str:
        return f"{motions[key[1]].name or key[1]} ({cases[key[0]][0]})"

    keys = [(c, r) for c in range(len(variants)) for r in range(len(motions))]
    chunks = lane_batches(variants[0], [motions[r] for _, r in keys], keys, workers=os.cpu_count() or 1,
                          apart=[c for c, _ in keys])  # every variant has the walls of the building
    tasks = {b: _Batch(variants[chunk[0][0]], tuple(motions[r] for _, r in chunk),
                       tuple(float(suite.factors[r]) for _, r in chunk), tuple(label(key) for key in chunk),
                       collapse_drift_ratio, valid_drift_ratio)
             for b, chunk in enumerate(chunks)}
    with executor_for(executor) as pool:
        done = fan_out(_run, tasks, pool, progress=progress, unit="analyses", where=lambda _: "verify",
                       sizes={b: len(chunk) for b, chunk in enumerate(chunks)})
    collected = spread(chunks, done)
    reissue(collected, label, stacklevel=3)
    return {key: each.value for key, each in collected.items()}
