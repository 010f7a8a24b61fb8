"""Strain-compatible (equivalent-linear) analysis of buildings with strain-dependent walls.

A :class:`~vdw_frames.element.strain_dependent.StrainDependentDamper` has FDMK parameters that depend on
its strain amplitude, but one time-history analysis (:func:`~vdw_frames.frame.simulation.simulate`)
integrates walls with fixed parameters.  :func:`strain_compatible_simulation` -- what
``simulate(building, motion, strain_compatible=True)`` runs -- finds, for each wall, the parameter set
compatible with the strain the wall reaches, the way an equivalent-linear site-response analysis
finds strain-compatible soil properties (SHAKE: Schnabel, Lysmer & Seed 1972):

1. every strain-dependent wall starts at an assumed amplitude: the geometric middle of its
   identified range, sqrt(low * high) (318 % for :func:`vdw_frames.paper.strain_dependent`), unless
   ``initial_strain`` is given;
2. the building is analysed with each wall's :class:`FDMKDamper` at its amplitude (an ordinary
   :func:`simulate` run; the walls' fractional memory starts from rest in every run);
3. each wall's effective strain is ``effective_strain_ratio`` (default 0.65) times its peak strain,
   magnification x max |drift| / thickness over the record;
4. each wall takes the parameters at its effective strain (clamped to its range, with a warning
   naming the wall and the strain reached);
5. 2-4 repeat until every wall's effective strain differs by less than ``tolerance`` (1 %) from the
   one that chose the parameters of the run, or ``max_iterations`` runs have been made.  The updates
   are under-relaxed adaptively: a wall whose update reverses direction (iterates that alternate
   about the fixed point, seen with slopes near -1, and with yielding stories when two stories trade
   the yielding as their walls' parameters change) halves its relaxation factor, which recovers by
   1.5x a step while its updates keep their sign.  This changes the path, not the fixed point or the
   convergence test.

The result is the last run's :class:`SimulationResult`: the response of the equivalent-linear
building (``result.building``: the building given, with every strain-dependent wall replaced by
its final :class:`FDMKDamper`), with ``wall_effective_strain``, ``equivalent_walls``,
``strain_iterations`` and ``strain_converged`` filled in.  Walls that are plain
:class:`FDMKDamper` objects keep their parameters (their ``wall_effective_strain`` is the ratio
times their peak strain, for information).  Every other property of the building (story
hysteresis, loads, damping model, ...) is kept: each run's building is
``dataclasses.replace(building, walls=...)``.

Why 0.65 of the peak
--------------------
The parameters were identified from steady harmonic tests at amplitude gamma.  An earthquake drives a
wall through a few cycles near its peak and many smaller ones, so the harmonic amplitude that stands
for the record is that of the cycles that do the work: weighting each half-cycle amplitude a_i by
the energy it dissipates (proportional to a_i^2 for a linear wall) gives the energy-weighted amplitude
gamma_E^2 = sum a_i^4 / sum a_i^2 (:func:`energy_weighted_amplitude`).  Over the five PEER records of
the project's test set, scaled to PGA 0.4 g and 0.8 g, on the 10-story example frame with
strain-dependent walls in its six lower stories (strain-compatible runs), gamma_E / gamma_peak is
0.39-0.72 over records and walls, median 0.62, when the frame stays elastic, and 0.20-0.71, median
0.53, when its stories yield (one large excursion, smaller cycles after it)
(``tests/paper/test_strain_dependence.py`` re-measures both bands and checks that the default lies in
them).  0.65 is close to those medians, and it is the ratio
equivalent-linear site response uses for the same reason (Idriss & Sun 1992: (M - 1) / 10, 0.65 for
magnitude 7.5).  The peak itself (ratio 1, ``effective_strain_ratio
=1.0``) would give a wall the properties of one excursion it spends a fraction of a cycle at.

Limits (read before trusting a number)
--------------------------------------
* One fixed parameter set per wall per analysis: the wall does not soften or stiffen during the record;
  the small cycles before and after the strong ones see the effective-strain parameters.
* The amplitude comes from the peak strain times a fixed ratio, not from a cycle-by-cycle measure of
  this record's history.
* No rate-of-strain effects beyond the model's own frequency dependence (the parameters come from
  0.5-10 Hz harmonic tests at 21.2 degC; no heating during the record).
* No strain-history effects: no Mullins softening on first loading, no Payne-effect recovery, no
  dependence on the order in which the amplitudes occur.
* Outside a wall's identified range its parameters are clamped to the nearest end (warned), never
  extrapolated.
* The convergence of the fixed-point iteration is not guaranteed: ``strain_converged`` says whether it
  converged (a ``UserWarning`` too when it did not).

Units: strain dimensionless (3.0 = 300 %), drift and thickness mm.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from .. import _warnings
from .._validation import finite_array, positive, refuse_non_numbers, show, whole_number
from ..element.damper import FDMKDamper
from ..element.strain_dependent import StrainDependentDamper
from ..motion.record import GroundMotion
from .building import ShearBuilding
from .results import SimulationResult
from .time_history import peak_strain_warning, time_history

if TYPE_CHECKING:
    from ..element.wall import Wall

DEFAULT_EFFECTIVE_STRAIN_RATIO = 0.65

MIN_TOLERANCE = 1e-12
"""Tightest ``tolerance`` accepted: the effective strains are computed in double precision from a
time-history analysis whose rounding is far above 1e-16 of the strain, so a tighter tolerance could
never be met and would only run ``max_iterations`` analyses."""

MAX_ITERATIONS = 200
"""Largest ``max_iterations`` accepted: every iteration is a whole time-history analysis.  The project's
records converge in 3-12 (``tests/frame/test_strain_compatible.py``); 200, ten times the default 20, leaves
room for a slowly converging, heavily under-relaxed case while a small input cannot ask for unbounded work."""


@dataclass(frozen=True)
class StrainCompatibleOptions:
    """Settings of the strain-compatible iteration (see the module docstring).

    effective_strain_ratio : float
        Effective strain / peak strain of each wall, in (0, 1] (default 0.65; 1.0 uses the peak).
    initial_strain : float or None
        The amplitude every strain-dependent wall starts at (dimensionless, > 0; clamped quietly to
        each wall's range); None (default): the geometric middle of each wall's range.
    tolerance : float
        Converged when every effective strain changes by less than this fraction (default 0.01), in
        [1e-12, 1) (:data:`MIN_TOLERANCE`: double precision cannot meet a tighter one).
    max_iterations : int
        At most this many analyses (default 20), in [1, 200] (:data:`MAX_ITERATIONS`: each is a whole
        analysis).
    """

    effective_strain_ratio: float = DEFAULT_EFFECTIVE_STRAIN_RATIO
    initial_strain: float | None = None
    tolerance: float = 0.01
    max_iterations: int = 20

    def __post_init__(self) -> None:
        for name in ("effective_strain_ratio", "initial_strain", "tolerance"):
            refuse_non_numbers(name, getattr(self, name))
        ratio = positive("effective_strain_ratio", self.effective_strain_ratio)
        if ratio > 1.0:
            raise ValueError(f"effective_strain_ratio must lie in (0, 1], got {self.effective_strain_ratio!r}")
        object.__setattr__(self, "effective_strain_ratio", ratio)
        if self.initial_strain is not None:
            object.__setattr__(self, "initial_strain", positive("initial_strain", self.initial_strain))
        tolerance = positive("tolerance", self.tolerance)
        if tolerance >= 1.0:
            raise ValueError(f"tolerance must lie in (0, 1), got {self.tolerance!r}")
        if tolerance < MIN_TOLERANCE:
            raise ValueError(f"tolerance = {show(self.tolerance)} is below {MIN_TOLERANCE:g}: the effective strains "
                             "are computed in double precision and could never meet it")
        object.__setattr__(self, "tolerance", tolerance)
        iterations = whole_number("max_iterations", self.max_iterations, 1)
        if iterations > MAX_ITERATIONS:
            raise ValueError(f"max_iterations = {show(self.max_iterations)} exceeds {MAX_ITERATIONS}: each iteration "
                             "is a whole time-history analysis (the default is 20; the project's records converge "
                             "in 3-12)")
        object.__setattr__(self, "max_iterations", iterations)


def strain_compatible_options(value: bool | StrainCompatibleOptions) -> StrainCompatibleOptions:
    """``True`` -> the default options; a :class:`StrainCompatibleOptions` -> itself; else ValueError."""
    if value is True:
        return StrainCompatibleOptions()
    if isinstance(value, StrainCompatibleOptions):
        return value
    raise ValueError(f"strain_compatible must be True, False or a StrainCompatibleOptions, got {value!r}")


def strain_compatible_simulation(building: ShearBuilding, ground_motion: GroundMotion,
                                 options: bool | StrainCompatibleOptions = True,
                                 **simulate_options: Any) -> SimulationResult:
    """Equivalent-linear analysis of ``building`` under ``ground_motion`` (method: module docstring).

    ``options``: ``True`` (defaults) or a :class:`StrainCompatibleOptions`.  ``simulate_options`` go
    to every :func:`~vdw_frames.frame.simulation.simulate` run (``dt`` in s, ``method``, ``memory``, ...).
    Returns the last run's :class:`SimulationResult` with, per wall in ``building.wall_list``
    order, ``wall_effective_strain`` (dimensionless: the effective strain each wall's final
    parameters were taken at) and ``equivalent_walls`` (its final :class:`FDMKDamper`; for a
    strain-dependent wall ``wall.at(wall_effective_strain)``), plus ``strain_iterations`` (analyses
    run) and ``strain_converged``.  ``result.building`` is the equivalent-linear building.  Warns
    (``UserWarning``) naming each wall whose effective strain left its range, and when the iteration
    did not converge; the final run's own warnings are passed on.
    """
    options = strain_compatible_options(options)
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    walls = [wall for _, wall in building.wall_list]
    dependent = np.array([isinstance(wall, StrainDependentDamper) for wall in walls], dtype=bool)
    thickness = np.array([wall.thickness / wall.magnification for wall in walls])  # strain per mm of drift
    stories = np.array([story for story, _ in building.wall_list], dtype=int) - 1
    strain = np.array([_initial_strain(wall, options.initial_strain) if isinstance(wall, StrainDependentDamper)
                       else 0.0 for wall in walls])

    converged, previous_step, relaxation = False, np.zeros(len(walls)), np.ones(len(walls))
    for iteration in range(1, options.max_iterations + 1):
        final = [wall.at(wall.clamped(s)) if isinstance(wall, StrainDependentDamper) else wall  # clamped: no warning
                 for wall, s in zip(walls, strain, strict=True)]
        # The strain-compatible analysis judges the range itself (effective, not peak, strain).
        run_walls = [dataclasses.replace(d, strain_range=None) if flag and isinstance(d, FDMKDamper) else d
                     for d, flag in zip(final, dependent, strict=True)]
        with _warnings.collect() as caught:  # per thread: safe under run_batch's thread executors
            result = time_history(building.with_walls(_regroup(building, run_walls)),
                                  ground_motion, **simulate_options)
        effective = options.effective_strain_ratio * result.peak_drift[stories] / thickness
        converged = bool(np.all(np.abs(effective - strain)[dependent] <= options.tolerance * strain[dependent]))
        if converged or iteration == options.max_iterations:
            break
        step = effective - strain
        # Adaptive under-relaxation: a wall whose step reverses (iterates alternating about the fixed
        # point; with yielding stories two of them can trade the yielding back and forth) halves its
        # relaxation factor, and recovers it by 1.5x a step while its steps keep their sign -- unless
        # both strains lie beyond the same end of its range, where its parameters do not change.
        moves = np.array([flag and isinstance(wall, StrainDependentDamper) and wall.clamped(e) != wall.clamped(s)
                          for wall, flag, e, s in zip(walls, dependent, effective, strain, strict=True)], dtype=bool)
        reverses = (step * previous_step < 0.0) & moves
        relaxation = np.where(reverses, 0.5 * relaxation, np.minimum(1.0, 1.5 * relaxation))
        step = relaxation * step
        strain, previous_step = np.where(dependent, strain + step, strain), step

    for message in caught:
        _warnings.warn(message.message, message.category, stacklevel=3)
    _warn_clamped(building, walls, strain, effective / options.effective_strain_ratio)
    # The equivalent walls ran without a range (judged above by their effective strain); their peak strain
    # beyond the tested range is warned about as for every wall model.
    peaks = result.peak_wall_strain
    tested = [(index, entry) for index, (entry, flag) in enumerate(zip(building.wall_list, dependent, strict=True))
              if flag]
    peak_warning = peak_strain_warning([entry for _, entry in tested], peaks[[index for index, _ in tested]],
                                       "StrainDependentDamper, equivalent-linear")
    if peak_warning is not None:
        _warnings.warn(peak_warning, UserWarning, stacklevel=3)
    if not converged:
        change = np.max((np.abs(effective - strain) / np.where(strain > 0.0, strain, 1.0))[dependent])
        _warnings.warn(f"strain-compatible analysis did not converge in {options.max_iterations} analyses: the "
                      f"effective strains still changed by up to {100 * change:.2g} % (tolerance "
                      f"{100 * options.tolerance:g} %)", UserWarning, stacklevel=3)
    return dataclasses.replace(
        result, building=building.with_walls(_regroup(building, final)),
        wall_effective_strain=np.where(dependent, strain, effective), equivalent_walls=tuple(final),
        strain_iterations=iteration, strain_converged=converged)


def energy_weighted_amplitude(strain: ArrayLike) -> float:
    """The energy-weighted half-cycle amplitude of a strain (or drift) history, in its units.

    The history is cut at its extrema (from its first sample) into half-cycles of amplitude
    a_i = |x_{i+1} - x_i| / 2; each weighs by the energy a linear wall dissipates in it (~ a_i^2), so
    the result is sqrt(sum a_i^4 / sum a_i^2): a steady sine of amplitude A gives A, and it lies
    between the largest and the typical half-cycle.  0 for a constant history.
    """
    x = finite_array("strain", strain)
    x = x[np.r_[True, np.diff(x) != 0.0]]  # drop repeated samples (plateaus)
    if x.size < 2:
        return 0.0
    step = np.diff(x)
    turns = np.flatnonzero(np.sign(step[1:]) != np.sign(step[:-1])) + 1
    amplitude = np.abs(np.diff(x[np.r_[0, turns, x.size - 1]])) / 2.0
    return float(np.sqrt(np.sum(amplitude**4) / np.sum(amplitude**2)))


def _initial_strain(wall: StrainDependentDamper, initial: float | None) -> float:
    low, high = wall.strain_range
    return float(np.sqrt(low * high)) if initial is None else wall.clamped(initial)


def _regroup(building: ShearBuilding,
             walls: Iterable[Wall | StrainDependentDamper]) -> dict[int, tuple[Wall | StrainDependentDamper, ...]]:
    """{story: walls} in ``building.walls``' layout from one wall per entry of ``building.wall_list``."""
    remaining = iter(walls)
    return {story: tuple(next(remaining) for _ in group) for story, group in building.walls.items()}


def _warn_clamped(building: ShearBuilding, walls: Sequence[Wall | StrainDependentDamper], strain: np.ndarray,
                  peak: np.ndarray) -> None:
    outside = []
    for index, ((story, _), wall, effective, reached) in enumerate(zip(building.wall_list, walls, strain, peak,
                                                                       strict=True)):
        if isinstance(wall, StrainDependentDamper) and wall.clamped(effective) != effective:
            low, high = wall.strain_range
            outside.append(f"wall {index} (story {story}): effective strain {100 * effective:.0f} % (peak "
                           f"{100 * reached:.0f} %), outside {100 * low:.4g}-{100 * high:.4g} %: parameters of "
                           f"{100 * wall.clamped(effective):.4g} % used")
    if outside:
        _warnings.warn("strain-compatible analysis: " + "; ".join(outside), UserWarning, stacklevel=4)
