"""Incremental dynamic analysis (Vamvatsikos & Cornell 2002) and a lognormal collapse fragility.

Every record is scaled to a spectral acceleration Sa(T, 5 %) that steps up from ``step`` by ``step``
until the building collapses or ``cap`` is reached.  Sa is the peak at the record's samples
(:func:`~vdw_frames.motion.spectrum.response_spectrum`), a little below the continuous response's when a
period holds few record steps (measured on El Centro, dt = 0.02 s: 0.3 % at T = 0.5 s, 1.9 % at 0.3 s,
3.4 % at 0.2 s): the scale factors are that much high, each run shakes the building that much harder than its
nominal Sa, and the collapse intensities come out that much low.  Each level is one :func:`simulate` run (through
:func:`run_batch`, so the records of one level run in parallel on any executor).  A run *collapses*
when a story's drift ratio exceeds ``collapse_drift_ratio`` (the building's P-Delta instability, or
simply a drift beyond which the model means nothing) or when the analysis stops converging (numerical
instability near collapse is collapse, as is usual in IDA practice); the record's collapse intensity is
the first level that collapses.  Records that reach ``cap`` standing are right-censored.

Walls with limits (:class:`~vdw_frames.element.limits.WallLimits`) can fail before the frame collapses.
Each record's first wall-failure intensity -- the first level at which any wall failed -- is reported
beside its collapse intensity, with a fragility of its own; a record whose walls stood up to its last
level is censored there.  Wall failure is not collapse (the frame goes on without the wall) unless
``wall_failure_collapse=True``; :attr:`IDAResult.limit_states` says which limit states the collapse
intensities include.

The collapse fragility P(collapse | Sa) = Phi(ln(Sa / theta) / beta) is fitted to the collapse
intensities by maximum likelihood (``scipy.stats.lognorm`` on ``scipy.stats.CensoredData``, so that
records standing at the cap count as "above the cap"): theta is the median collapse intensity and beta
the record-to-record dispersion (FEMA P-695 fits the same form).

Units: spectral acceleration mm/s^2 (divide by :data:`vdw_frames.G` for g), period s, drift ratio -.
"""

from __future__ import annotations

import concurrent.futures
import math
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .._parallel import executor_for
from .._validation import finite_array, positive, show
from .._warnings import keyword_only_since_0_3
from ..motion.record import G, GroundMotion
from .batch import run_batch, scale_factors_to_spectral_acceleration
from .building import ShearBuilding
from .time_history import is_strain_range_warning

MAX_LEVELS = 1000
"""Most intensity levels (cap / step) one IDA may ask for: 0.01 g steps up to 10 g, finer and higher than any
IDA needs (the example takes 0.1 g to 4 g: 40 levels); each level is one analysis of every standing record."""

COLLAPSE_LIMIT_STATES = "a story drift ratio beyond collapse_drift_ratio, or an analysis that stops converging"


@dataclass(frozen=True)
class Fragility:
    """A lognormal fragility: P(collapse | Sa) = Phi(ln(Sa / median) / dispersion); ``median`` mm/s^2 (> 0),
    ``dispersion`` (-, > 0)."""

    median: float
    dispersion: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "median", positive("median", self.median))
        object.__setattr__(self, "dispersion", positive("dispersion", self.dispersion))

    def probability(self, intensity: ArrayLike) -> np.ndarray:
        """P(collapse) at spectral accelerations ``intensity`` (mm/s^2, finite, >= 0; 0 gives 0)."""
        from scipy import stats

        intensity = finite_array("intensity", intensity, ndim=None)
        if (intensity < 0.0).any():
            raise ValueError(f"intensity must be >= 0 mm/s^2, got {show(intensity[intensity < 0.0].flat[0])}")
        with np.errstate(divide="ignore"):  # ln 0 = -inf: probability 0
            return stats.norm.cdf(np.log(intensity / self.median) / self.dispersion)


@dataclass(frozen=True)
class IDAResult:
    """The IDA curves of every record.

    ``motion_names``; ``period`` (s) and ``levels`` (mm/s^2, the Sa steps); per record (tuples, one entry a
    record): ``intensities`` (the levels run, mm/s^2), ``peak_drift_ratio`` (the largest story drift ratio
    of each run, -), ``collapsed`` (bool per run, by the limit states of ``limit_states``);
    ``collapse_intensity`` (mm/s^2, masked where the record stood at the cap); ``strain_warnings``: the
    strain-range warnings of the runs (text), counted, not silenced.  ``wall_failed`` (bool per run: any
    wall failed) and ``wall_failure_intensity`` (mm/s^2, the first level with a failed wall, masked where
    no wall failed up to the record's last level); ``limit_states``: what a collapse is, in words.
    ``other_warnings``: every other warning of the runs (a wall's temperature outside its shift law's range,
    a step that did not converge, ...), each naming its run; the analysis warns once when there are any.
    """

    motion_names: tuple[str, ...]
    period: float
    levels: np.ndarray
    intensities: tuple[np.ndarray, ...]
    peak_drift_ratio: tuple[np.ndarray, ...]
    collapsed: tuple[np.ndarray, ...]
    collapse_intensity: np.ma.MaskedArray
    strain_warnings: tuple[str, ...]
    wall_failed: tuple[np.ndarray, ...] = ()
    wall_failure_intensity: np.ma.MaskedArray = field(default_factory=lambda: np.ma.masked_array([]))
    limit_states: str = COLLAPSE_LIMIT_STATES
    other_warnings: tuple[str, ...] = ()

    @property
    def analyses(self) -> int:
        return sum(len(runs) for runs in self.intensities)

    def fragility(self, limit_state: str = "collapse") -> Fragility:
        """Maximum-likelihood lognormal fit of the collapse intensities (``limit_state="collapse"``) or of
        the first wall-failure intensities (``"wall failure"``), each censored at the record's last level."""
        from scipy import stats

        if limit_state not in ("collapse", "wall failure"):
            raise ValueError(f"limit_state must be 'collapse' or 'wall failure', got {limit_state!r}")
        observed = self.collapse_intensity if limit_state == "collapse" else self.wall_failure_intensity
        collapsed = observed.compressed()
        standing = np.array([self.intensities[m][-1] for m in range(len(self.motion_names))
                             if np.ma.getmaskarray(observed)[m]])
        if collapsed.size < 2:
            what = "collapses" if limit_state == "collapse" else "wall failures"
            records = len(self.motion_names)
            if records < 2:  # no cap helps: one record gives one intensity at most
                advice = f"run at least two records, got {records}"
            else:
                advice = (f"{standing.size} of {records} records still stand at the cap, Sa(T1) = "
                          f"{self.levels[-1] / G:.4g} g: raise the cap")
            raise ValueError(f"a fragility needs at least two {what}, got {collapsed.size} ({advice})")
        data = stats.CensoredData(uncensored=collapsed, right=standing) if standing.size else collapsed
        shape, _, scale = stats.lognorm.fit(data, floc=0.0)
        return Fragility(float(scale), float(shape))


@keyword_only_since_0_3
def incremental_dynamic_analysis(building: ShearBuilding, motions: Iterable[GroundMotion], step: float, cap: float,
                                 period: float | None = None, executor: concurrent.futures.Executor | str | None = None,
                                 *, wall_failure_collapse: bool = False, **options: Any) -> IDAResult:
    """IDA of ``building`` under ``motions`` (GroundMotion, mm/s^2): Sa(``period``, 5 %) from ``step`` in steps
    of ``step`` up to ``cap`` (mm/s^2) or collapse, record by record (module docstring); at most
    :data:`MAX_LEVELS` = 1000 levels (cap / step), else a ValueError naming step, cap and the count.

    ``period`` (s): the intensity measure's period, default the bare elastic frame's T1.  ``executor``:
    as for :func:`run_batch` (the default thread pool serves every level).
    ``options`` go to :func:`run_batch` and :func:`simulate` (``collapse_drift_ratio`` (default 0.10, needs
    story heights), ``method``, ``memory``, ``strain_compatible``, ...).  ``wall_failure_collapse``: count
    the failure of any wall as collapse (default False: a failed wall leaves the frame standing).
    """
    from .. import _warnings

    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    if building.story_heights is None:
        raise ValueError("an incremental dynamic analysis needs story_heights: collapse is a story drift ratio "
                         "beyond collapse_drift_ratio, and the curves are drift ratios")
    motions = list(motions)
    if not motions or not all(isinstance(m, GroundMotion) for m in motions):
        raise ValueError("motions must be a non-empty sequence of GroundMotion objects")
    if not isinstance(wall_failure_collapse, (bool, np.bool_)):
        raise ValueError(f"wall_failure_collapse must be True or False, got {wall_failure_collapse!r}")
    step, cap = positive("step", step), positive("cap", cap)
    if cap < step:
        raise ValueError(f"cap = {cap:g} mm/s^2 must be at least one step ({step:g} mm/s^2)")
    period = building.periods[0] if period is None else positive("period", period)
    ratio = cap / step  # may overflow to inf (cap 1e300, step 1e-10): counted, never built
    if not ratio + 1e-9 < MAX_LEVELS + 1:
        count = f"{math.floor(ratio + 1e-9):,}" if ratio < 1e15 else \
            (f"{ratio:.3g}" if math.isfinite(ratio) else "more than any float")
        raise ValueError(f"step = {show(step)} mm/s^2 up to cap = {show(cap)} mm/s^2 is {count} intensity levels, "
                         f"more than {MAX_LEVELS} (0.01 g steps to 10 g; each level is an analysis of every "
                         "standing record); take a larger step or a lower cap")
    levels = step * np.arange(1, math.floor(ratio + 1e-9) + 1)
    factors = scale_factors_to_spectral_acceleration(motions, levels, period)  # (motions, levels)
    intensities: list[list[float]] = [[] for _ in motions]
    drift: list[list[float]] = [[] for _ in motions]
    collapsed: list[list[bool]] = [[] for _ in motions]
    wall_failed: list[list[bool]] = [[] for _ in motions]
    messages: list[str] = []
    standing = list(range(len(motions)))
    with executor_for(executor) as pool:  # one pool for every level (default: threads)
        for index, level in enumerate(levels):
            if not standing:
                break
            with _warnings.collect() as caught:  # run_batch's re-issued warnings, per thread
                batch = run_batch(building, [motions[m] for m in standing], factors[standing, index][:, None],
                                  executor=pool, progress=False, **options)
            messages.extend(w.message for w in caught)
            assert batch.peak_drift_ratio is not None  # the building has story heights (checked above)
            for row, m in enumerate(standing):
                intensities[m].append(level)
                drift[m].append(float(batch.peak_drift_ratio[row, 0].max()))
                wall_failed[m].append(bool(batch.wall_failed[row, 0].any()))
                collapsed[m].append(bool(batch.collapsed[row, 0] or not batch.converged[row, 0]
                                         or (wall_failure_collapse and wall_failed[m][-1])))
            standing = [m for m in standing if not collapsed[m][-1]]
    limit_states = COLLAPSE_LIMIT_STATES + (", or the failure of any wall" if wall_failure_collapse else
                                            " (wall failure not included: a failed wall leaves the frame standing)")
    # The strain-range warnings are counted in the result; the others (a wall's temperature beyond its shift law's
    # range, a step that did not converge) were collected with them and must not be lost either.
    others = tuple(message for message in messages if not is_strain_range_warning(message))
    if others:
        _warnings.warn(f"incremental_dynamic_analysis: {len(others)} warning(s) of {sum(map(len, intensities))} "
                       f"analyses besides wall strain (result.other_warnings), e.g. {others[0]}", UserWarning,
                       stacklevel=3)
    return IDAResult(tuple(m.name for m in motions), float(period), levels,
                     tuple(np.array(x) for x in intensities), tuple(np.array(x) for x in drift),
                     tuple(np.array(x, dtype=bool) for x in collapsed), _first_level(intensities, collapsed),
                     tuple(message for message in messages if is_strain_range_warning(message)),
                     tuple(np.array(x, dtype=bool) for x in wall_failed), _first_level(intensities, wall_failed),
                     limit_states, others)


def _first_level(intensities: list[list[float]], happened: list[list[bool]]) -> np.ma.MaskedArray:
    """Per record, the first level (mm/s^2) at which an event happened; masked where it never did."""
    first = [next((sa for sa, h in zip(levels, events, strict=True) if h), None)
             for levels, events in zip(intensities, happened, strict=True)]
    return np.ma.masked_array([0.0 if sa is None else sa for sa in first], mask=[sa is None for sa in first])
