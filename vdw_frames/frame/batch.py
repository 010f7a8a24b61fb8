"""Batch analyses (incremental dynamic analysis, parameter studies) on any concurrent.futures executor.

The (motion, scale) analyses run as lanes (:mod:`vdw_frames.frame.lanes`): a picklable :class:`LaneTask` holds
up to :data:`~vdw_frames.frame.lanes.LANES_PER_TASK` of them on records of one dt -- the building, the records and the
factors -- and runs them in one compiled call in whichever process the executor chooses, on that worker's reused
workspace, returning only the peak responses (each equal to :func:`vdw_frames.simulate`'s to the bit) and the warnings
simulate would have issued.  Strain-compatible batches run one :func:`~vdw_frames.simulate` a task
(:class:`BatchTask`).  The default executor is a thread pool over all cores (the compiled analyses release the GIL);
``executor="processes"`` gives a process pool whose workers never outlive the call; a Dask cluster works through a
``distributed.Client`` (install the ``dask`` extra).  The fan-out, its
cancellation, warnings and progress bar are :mod:`vdw_frames._parallel`'s.
"""

from __future__ import annotations

import concurrent.futures
import csv
import dataclasses
import io
import os
from collections.abc import Callable, Iterable, Sequence
from contextlib import AbstractContextManager
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import ArrayLike

from .._files import write_text
from .._parallel import POOLS, Collected, check_executor, executor_for, fan_out, reissue, spread
from .._validation import check_memory, finite_array, show
from .._warnings import keyword_only_since_0_3
from ..element.bank import group_walls, wall_order
from ..element.damper import DEFAULT_MEMORY
from ..element.fast_memory import FastMemory
from ..element.fractional import DEFAULT_METHOD, Discretisation
from ..motion.record import GroundMotion, target_acceleration
from .building import ShearBuilding, is_wall
from .lanes import LaneResult, lane_batches, run_lanes
from .results import SimulationResult
from .simulation import simulate
from .strain_compatible import StrainCompatibleOptions, strain_compatible_options

if TYPE_CHECKING:
    from ..element.wall import Wall


@dataclass(frozen=True)
class BatchTask:
    """One analysis of a batch: ``building`` under ``motion.scaled(scale)``."""

    building: ShearBuilding
    motion: GroundMotion
    scale: float
    memory: str | FastMemory
    method: str | Discretisation
    strain_compatible: bool | StrainCompatibleOptions = False  # simulate()'s option: False, True or the options
    options: tuple[tuple[str, Any], ...] = ()  # further simulate() keywords, as (name, value) pairs

    def run(self) -> dict[str, Any]:
        """Peak responses of this analysis (units of :class:`~vdw_frames.frame.simulation.SimulationResult`).

        The package's warnings raised by the analysis (e.g. strain outside the identified range) are
        collected per task by :func:`vdw_frames._parallel.fan_out` and re-issued by :func:`run_batch`, once per
        message and naming the analysis (a worker process could not warn the caller; a thread's would not say which).
        """
        result = simulate(self.building, self.motion.scaled(self.scale), method=self.method, memory=self.memory,
                          strain_compatible=self.strain_compatible, **dict(self.options))
        return {
            "collapsed": result.collapsed,
            "converged": result.converged,
            "residual_drift": result.residual_drift,
            "peak_drift": result.peak_drift,
            "peak_drift_ratio": result.peak_drift_ratio,
            "peak_absolute_acceleration": result.peak_absolute_acceleration,
            "peak_base_shear": np.array([result.peak_base_shear]),
            "peak_story_wall_force": result.peak_story_wall_force,
            "peak_temperature_rise": _story_temperature_rise(result),
            "wall_failed": result.wall_failed,
            "wall_failure_time": np.array([np.inf if t is None else t for t in result.wall_failure_time]),
            **{f"peak_device_{name}": np.abs(getattr(result, f"device_{name}")).max(axis=0, initial=0.0)
               for name in ("force", "deformation", "velocity")},
        }


def _story_temperature_rise(result: SimulationResult) -> np.ndarray | None:
    """The largest temperature rise (K) of the walls of each story (0 where none has a thermal description);
    None when no wall's heat is followed (a thermal description or limits)."""
    rise = result.peak_temperature_rise
    if rise is None:
        return None
    per_story = np.zeros(result.building.stories)
    for (story, _), value in zip(result.building.wall_list, rise, strict=True):
        if np.isfinite(value):
            per_story[story - 1] = max(per_story[story - 1], value)
    return per_story


def _run(task: BatchTask) -> dict[str, Any]:
    # A module-level function: executors pickle it by name.
    return task.run()


@dataclass(frozen=True)
class LaneTask:
    """Analyses of one building on records of one dt, each under ``motions[i].scaled(scales[i])``, run as lanes
    (:func:`~vdw_frames.frame.lanes.run_lanes`); ``labels`` name them in errors."""

    building: ShearBuilding
    motions: tuple[GroundMotion, ...]
    scales: tuple[float, ...]
    labels: tuple[str, ...]
    memory: str | FastMemory
    method: str | Discretisation
    options: tuple[tuple[str, Any], ...] = ()

    def run(self) -> list[tuple[dict[str, Any], tuple[Any, ...]]]:
        """Each analysis's peaks (those of :meth:`BatchTask.run`, equal to the bit) and the warnings simulate
        would have issued for it; the first analysis that cannot run raises its ValueError, named by its label."""
        lanes = run_lanes(self.building, self.motions, self.scales, memory=self.memory, method=self.method,
                          **dict(self.options))
        out = []
        for lane, motion, label in zip(lanes, self.motions, self.labels, strict=True):
            if lane.error is not None:
                raise ValueError(f"the analysis of {label} failed: {lane.error}")
            out.append((_lane_peaks(self.building, lane, motion.dt), lane.warnings))
        return out


def _lane_peaks(building: ShearBuilding, lane: LaneResult, dt: float) -> dict[str, Any]:
    """:meth:`BatchTask.run`'s peaks from a lane (the same values: SimulationResult's definitions)."""
    wall_group = _wall_groups(building)
    rise = lane.peak_temperature_rise
    per_story = None
    if rise is not None:
        per_story = np.zeros(building.stories)
        for (story, _), value in zip(building.wall_list, rise[wall_group], strict=True):
            if np.isfinite(value):
                per_story[story - 1] = max(per_story[story - 1], value)
    failure_step = lane.group_failure_step[wall_group]
    step_dt = dt if lane.steps > 1 else 0.0  # SimulationResult.wall_failure_time's time[1] - time[0]
    return {
        "collapsed": lane.collapsed,
        "converged": lane.converged,
        "residual_drift": lane.residual_drift,
        "peak_drift": lane.peak_drift,
        "peak_drift_ratio": lane.peak_drift_ratio,
        "peak_absolute_acceleration": lane.peak_absolute_acceleration,
        "peak_base_shear": np.array([lane.peak_base_shear]),
        "peak_story_wall_force": lane.peak_story_wall_force,
        "peak_temperature_rise": per_story,
        "wall_failed": failure_step >= 0,
        "wall_failure_time": np.array([np.inf if step < 0 else step * step_dt for step in failure_step.tolist()]),
        "peak_device_force": lane.peak_device_force,
        "peak_device_deformation": lane.peak_device_deformation,
        "peak_device_velocity": lane.peak_device_velocity,
    }


def _wall_groups(building: ShearBuilding) -> np.ndarray:
    """The wall group of each wall (``building.wall_list`` order), as the analyses group them."""
    return np.asarray(group_walls(cast("list[tuple[int, Wall]]", building.wall_list))[1], dtype=np.int64)


def _run_lanes(task: LaneTask) -> list[tuple[dict[str, Any], tuple[Any, ...]]]:
    # A module-level function: executors pickle it by name.
    return task.run()


DEVICE_PEAKS = ("peak_device_force", "peak_device_deformation", "peak_device_velocity")
"""The peaks of each device that is not a wall (N, mm, mm/s along the device), (motions, scales, devices)."""
PEAKS = ("peak_drift", "peak_drift_ratio", "peak_absolute_acceleration", "peak_base_shear", "peak_story_wall_force",
         "residual_drift", "peak_temperature_rise")
_UNITS = {"peak_drift": "mm", "peak_drift_ratio": "-", "peak_absolute_acceleration": "mm/s2",
          "peak_base_shear": "N", "peak_story_wall_force": "N", "residual_drift": "mm", "peak_temperature_rise": "K"}
OUTCOMES = ("collapsed", "converged")
_SIMULATE_OPTIONS = {"collapse_drift_ratio", "free_vibration", "newton"}


@dataclass(frozen=True)
class BatchResult:
    """Peaks of every (motion, scale) analysis, arrays shaped (motions, scales, stories or 1).

    ``scales`` is (motions, scales): the factor each record was multiplied by.  Units: peak_drift mm,
    peak_drift_ratio - (None without story heights), peak_absolute_acceleration mm/s^2 (per floor),
    peak_base_shear N, peak_story_wall_force N (total per story), residual_drift mm (the drift at the last
    step, per story; for a collapsed or non-converged run, the drift where it stopped).  ``collapsed`` and
    ``converged`` (motions, scales) are each analysis's outcome
    (:class:`~vdw_frames.frame.SimulationResult`): a collapsed or non-converged run is recorded, its peaks
    being those reached before it stopped.  With ``run_batch(..., property_factors=...)`` the peaks are
    the envelope over the factors (residual drifts: the largest in magnitude; collapsed: any;
    converged: all): ``property_factors`` lists them and ``governing_factor`` maps each peak's name to
    an array of its shape holding the factor that gave each value (None otherwise); with
    ``ambient_temperatures``, likewise ``ambient_temperatures`` and ``governing_temperature`` (degC).
    ``peak_temperature_rise`` (K): the largest temperature rise of the walls of each story (0 where no wall
    has a thermal description; None when no wall's heat is followed).  ``wall_failed`` (motions, scales,
    walls) bool: which walls failed in each run (walls with :class:`~vdw_frames.element.limits.WallLimits`;
    ``building.wall_list`` order, their stories in ``wall_stories``); ``wall_failure_time`` (s, same
    shape, masked where the wall stood); with property factors or temperatures: failed in any variant, at
    the earliest time.  ``peak_device_force`` (N), ``peak_device_deformation`` (mm), ``peak_device_velocity``
    (mm/s): (motions, scales, devices), the peaks along each device that is not a wall (fluid viscous,
    friction), ``building.other_device_list`` order; with property factors, their envelope too.
    """

    motion_names: tuple[str, ...]
    scales: np.ndarray
    pga: np.ndarray  # (motions, scales): PGA of each scaled record, mm/s^2
    peak_drift: np.ndarray
    peak_drift_ratio: np.ndarray | None
    peak_absolute_acceleration: np.ndarray
    peak_base_shear: np.ndarray
    peak_story_wall_force: np.ndarray
    residual_drift: np.ndarray
    collapsed: np.ndarray
    converged: np.ndarray
    peak_temperature_rise: np.ndarray | None = None
    wall_stories: tuple[int, ...] = ()
    wall_failed: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((0, 0, 0), dtype=bool))
    wall_failure_time: np.ma.MaskedArray = dataclasses.field(default_factory=lambda: np.ma.zeros((0, 0, 0)))
    property_factors: tuple[float, ...] | None = None
    governing_factor: dict[str, np.ndarray] | None = None
    ambient_temperatures: tuple[float, ...] | None = None
    governing_temperature: dict[str, np.ndarray] | None = None
    peak_device_force: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((0, 0, 0)))
    peak_device_deformation: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((0, 0, 0)))
    peak_device_velocity: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((0, 0, 0)))

    def to_csv(self, path: str | os.PathLike[str]) -> Path:
        """Write one row per (motion, scale, story) with every peak and the outcome (``None`` ratios left
        empty) to ``path``, atomically; returns the path."""
        stories = self.peak_drift.shape[2]
        handle = io.StringIO(newline="")
        writer = csv.writer(handle)
        writer.writerow(["motion", "scale", "pga_mm_s2", "story"]
                        + [f"{name}_{_UNITS[name]}" for name in PEAKS] + list(OUTCOMES) + ["walls_failed"])
        wall_stories = np.array(self.wall_stories, dtype=int)
        for m, name in enumerate(self.motion_names):
            for s in range(self.scales.shape[1]):
                for k in range(stories):
                    row = [name, repr(float(self.scales[m, s])), repr(float(self.pga[m, s])), k + 1]
                    for peak in PEAKS:
                        values = getattr(self, peak)
                        row.append("" if values is None else repr(float(values[m, s, k if values.shape[2] > 1 else 0])))
                    failed = int(self.wall_failed[m, s, wall_stories == k + 1].sum()) if wall_stories.size else 0
                    writer.writerow(row + [int(getattr(self, outcome)[m, s]) for outcome in OUTCOMES] + [failed])
        return write_text(path, handle.getvalue(), "CSV file")


def analysis_bytes(building: ShearBuilding) -> int:
    """Bytes one analysis of :func:`run_batch` keeps until the batch returns: its peaks, outcome and warnings (a
    wall's warning names its story and strain, per analysis) and its rows of the :class:`BatchResult` (the lanes'
    workspaces, at most :data:`~vdw_frames.frame.lanes.LANES_PER_TASK` analyses a task, are reused).  Measured
    (tracemalloc, 300-1500 scales of a 41-step record): 2.1 KB an analysis of a 2-story frame, 2.5 KB of a 10-story
    one with or without 10 quiet walls, 4.5 KB of the 10-story example whose 10 walls warn, 3.6 KB of a 40-story
    frame, 2.8 KB of a 4-story frame with 4 other devices; this count is about 1.7-3 times those."""
    return 4096 + 128 * building.stories + 256 * (len(building.wall_list) + len(building.other_device_list))


def variant_bytes(building: ShearBuilding) -> int:
    """Bytes one device variant of :func:`run_batch` (a property factor at an ambient temperature) keeps besides its
    analyses: its building.  Measured (tracemalloc, 100 and 300 property factors, one analysis each): about 17 KB
    for the 10-story example frame with 10 walls, 5 KB for a 4-story frame with 5 devices; this count is
    1.1-2 times those."""
    floors = building.stories
    return 4096 + 1024 * floors + 16 * floors**2 + 512 * (len(building.wall_list) + len(building.other_device_list))


def _check_analyses(building: ShearBuilding, motions: int, scales: int, variants: int = 1) -> None:
    """Refuse, before any work, a batch whose results would exceed the memory limit (a small input -- np.ones(10**8)
    as scales, 10**6 property factors -- asking for gigabytes of them)."""
    analyses = motions * scales
    what = f"run_batch ({motions} records x {scales} scales"
    if variants == 1:
        check_memory(f"{what} = {analyses:,} analyses, {building.stories} floors)", analyses,
                     analysis_bytes(building), "use fewer records or scales, or split the batch", unit="analyses")
    else:
        check_memory(f"{what} x {variants:,} device variants, {building.stories} floors)", variants,
                     analyses * analysis_bytes(building) + variant_bytes(building),
                     "use fewer property factors or ambient temperatures", unit="device variants")


@keyword_only_since_0_3
def run_batch(building: ShearBuilding, motions: Iterable[GroundMotion], scales: ArrayLike,
              executor: concurrent.futures.Executor | str | None = None, *, progress: bool = True,
              memory: str | FastMemory = DEFAULT_MEMORY, method: str | Discretisation = DEFAULT_METHOD,
              strain_compatible: bool | StrainCompatibleOptions = False, property_factors: ArrayLike | None = None,
              ambient_temperatures: ArrayLike | None = None, **simulate_options: Any) -> BatchResult:
    """Run ``building`` under every motion at every scale factor.

    ``motions``: GroundMotion objects (mm/s^2).  ``scales``: factors (dimensionless) applied as
    :meth:`GroundMotion.scaled` does, either one sequence for all motions (shape (scales,)) or one row
    per motion (shape (motions, scales)), e.g. from :func:`scale_factors_to_pga`.  ``executor``: any
    :class:`concurrent.futures.Executor` or Dask ``distributed.Client``, or an own pool over all cores, shut down
    after: None or "threads" (the default) a thread pool, whose running analyses stop within a step on an error,
    Ctrl-C or SIGTERM; "processes" a process pool, whose workers are terminated then and die with the process.
    ``progress``: a progress bar (tqdm) on standard error, only when it is a terminal.  The peaks equal those
    of :func:`simulate` for the same run; the package's warnings of every analysis are re-issued here,
    once per message, naming the motion and scale (collected per task, safe with thread executors).
    The first failing analysis cancels the rest and raises, its message naming the motion and scale.
    ``strain_compatible`` (False, True or a :class:`~vdw_frames.frame.strain_compatible.StrainCompatibleOptions`)
    is passed to every :func:`simulate`: True runs each analysis strain-compatible (buildings with
    strain-dependent walls need it).  ``simulate_options`` (``collapse_drift_ratio``,
    ``free_vibration``, ``newton``) go to every :func:`simulate` too.  Collapse and non-convergence
    are outcomes, recorded in ``collapsed`` and ``converged``, not failures.  ``method`` and ``memory``
    are checked before anything is submitted.
    ``property_factors`` (e.g. (0.8, 1.0, 1.2)): property-modification factors of the devices (ASCE 7-16
    Sec. 18.2.4.5) other than temperature (aging, environment, testing, specification): the batch runs once
    per factor with every wall's moduli and viscosities scaled (``wall.scaled(factor)``; supports
    unchanged) and every other device's force-defining property (``device.scaled(factor)``: a fluid viscous
    damper's C, a friction damper's slip force) and returns the envelope of the peaks, with the governing
    factor of each (:class:`BatchResult`).
    ``ambient_temperatures`` (e.g. (0.0, 21.2, 40.0), degC): the same over ambient temperatures, every wall
    with a thermal description starting at (and cooling towards) each (``wall.at_ambient(T)``) and heating
    itself; the envelope names the governing temperature of each peak.  Both together: every combination.
    """
    from ..element.damper import memory_strategy
    from ..element.fractional import get_method

    unknown = set(simulate_options) - _SIMULATE_OPTIONS
    if unknown:
        raise ValueError(f"unknown run_batch options {sorted(unknown)}; expected some of {sorted(_SIMULATE_OPTIONS)}")
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    if isinstance(motions, GroundMotion):
        raise ValueError(f"motions must be a list of GroundMotion objects, got one GroundMotion ({motions.name!r}); "
                         f"pass [motion]")
    try:
        motions = list(motions)
    except TypeError:
        raise ValueError(f"motions must be a list of GroundMotion objects, got {show(motions)}") from None
    if property_factors is not None or ambient_temperatures is not None:  # motions: listed, iterated per variant
        try:
            shape = np.shape(scales)
        except ValueError:  # ragged: refused, named, by the variant's run
            shape = ()
        scale_count = shape[-1] if len(shape) in (1, 2) else 1  # a bad shape: refused by the variant's run
        return _property_envelope(building, property_factors, ambient_temperatures, executor,
                                  (len(motions), scale_count),
                                  lambda variant, pool: run_batch(variant, motions, scales, pool, progress=progress,
                                                                  memory=memory, method=method,
                                                                  strain_compatible=strain_compatible,
                                                                  **simulate_options))
    if not motions or not all(isinstance(m, GroundMotion) for m in motions):
        bad = next((m for m in motions if not isinstance(m, GroundMotion)), None)
        raise ValueError("motions must be a non-empty sequence of GroundMotion objects"
                         + (f", got {type(bad).__name__} {show(bad)}" if motions else ", got none"))
    check_executor(executor)
    get_method(method)
    memory_strategy(memory)
    factors = finite_array("scales", scales, ndim=None)
    if factors.ndim == 1:
        factors = np.broadcast_to(factors, (len(motions), factors.size))
    if factors.ndim != 2 or factors.shape[0] != len(motions) or factors.shape[1] == 0:
        raise ValueError(f"scales must have shape (scales,) or ({len(motions)}, scales), got {np.shape(scales)}")
    _check_analyses(building, len(motions), factors.shape[1])
    if strain_compatible is not False:
        strain_compatible_options(strain_compatible)  # a bad value fails here, not in every worker
    else:
        for _, wall in building.wall_list:  # an amplitude-following wall needs one r: refused before any work
            wall_order(wall)
    options = tuple(sorted(simulate_options.items()))
    if strain_compatible is False:  # the lanes engine: many analyses a task, in one compiled call
        collected = _fan_out_lanes(building, motions, factors, memory=memory, method=method, options=options,
                                   executor=executor, progress=progress)
    else:
        tasks = {(m, s): BatchTask(building, motion, float(factors[m, s]), memory, method, strain_compatible, options)
                 for m, motion in enumerate(motions) for s in range(factors.shape[1])}
        with executor_for(executor) as pool:
            collected = fan_out(_run, tasks, pool, progress=progress, unit="analyses",
                                where=lambda key: f"run_batch: the analysis of {_label(motions, key[0])} x "
                                                  f"{factors[key]:g} failed")
    reissue(collected, lambda key: f"{_label(motions, key[0])} x {factors[key]:g}", stacklevel=2)
    peaks = {key: each.value for key, each in collected.items()}

    def stack(name: str) -> np.ndarray:
        return np.array([[peaks[(m, s)][name] for s in range(factors.shape[1])] for m in range(len(motions))])

    # A peak that an analysis does not give (drift ratios without story heights, temperatures without a
    # thermal description) is None in every analysis of the batch.
    stacked: dict[str, Any] = {name: None if peaks[(0, 0)][name] is None else stack(name) for name in PEAKS}
    stacked.update({name: stack(name).astype(bool) for name in OUTCOMES})
    pga = np.array([[abs(f) * motion.pga for f in row] for row, motion in zip(factors, motions, strict=True)])
    walls = len(building.wall_list)
    failed = stack("wall_failed").reshape(len(motions), factors.shape[1], walls).astype(bool)
    failure_time = stack("wall_failure_time").reshape(failed.shape)
    others = len(building.other_device_list)
    stacked.update({name: stack(name).reshape(len(motions), factors.shape[1], others) for name in DEVICE_PEAKS})
    return BatchResult(motion_names=tuple(m.name for m in motions), scales=np.array(factors), pga=pga, **stacked,
                       wall_stories=tuple(story for story, _ in building.wall_list), wall_failed=failed,
                       wall_failure_time=np.ma.masked_array(np.where(failed, failure_time, 0.0), mask=~failed))


def _fan_out_lanes(building: ShearBuilding, motions: Sequence[GroundMotion], factors: np.ndarray, *,
                   memory: str | FastMemory, method: str | Discretisation, options: tuple[tuple[str, Any], ...],
                   executor: concurrent.futures.Executor | str | None,
                   progress: bool) -> dict[tuple[int, int], Collected]:
    """Every (motion, scale) analysis as lanes: :class:`LaneTask` s of records of one dt and wall memory, at most
    :data:`~vdw_frames.frame.lanes.LANES_PER_TASK` each (:func:`~vdw_frames.frame.lanes.lane_batches`), fanned out
    by :func:`~vdw_frames._parallel.fan_out`; returns each analysis's peaks and warnings keyed (motion, scale), as
    the tasks of one analysis give them."""
    pairs = [(m, s) for m in range(len(motions)) for s in range(factors.shape[1])]
    chunks = lane_batches(building, [motions[m] for m, _ in pairs], pairs, memory=memory,
                          free_vibration=dict(options).get("free_vibration", 0.0), workers=os.cpu_count() or 1)
    tasks = {c: LaneTask(building, tuple(motions[m] for m, _ in chunk), tuple(float(factors[m, s]) for m, s in chunk),
                         tuple(f"{_label(motions, m)} x {factors[m, s]:g}" for m, s in chunk), memory, method, options)
             for c, chunk in enumerate(chunks)}
    with executor_for(executor) as pool:
        done = fan_out(_run_lanes, tasks, pool, progress=progress, unit="batches of analyses",
                       where=lambda key: "run_batch")
    return spread(chunks, done)


def worker_pool(kind: str = "threads") -> AbstractContextManager[concurrent.futures.Executor]:
    """``with worker_pool() as pool:`` the default executor of :func:`run_batch`,
    :func:`~vdw_frames.incremental_dynamic_analysis`, :func:`~vdw_frames.verify` and
    :func:`~vdw_frames.collapse_assessment` -- a pool over all cores, ``kind`` "threads" (the default) or
    "processes" -- kept for several calls (``executor=pool``), with the same care (:mod:`vdw_frames._parallel`):
    an error, Ctrl-C or SIGTERM inside the block stops a thread pool's analyses within a step, and terminates a
    process pool's workers at once, which also ignore Ctrl-C and die with this process (even killed by
    SIGKILL).  A plain ``ProcessPoolExecutor`` leaves its workers running when its process is killed."""
    if kind not in POOLS:
        raise ValueError(f"kind must be one of {', '.join(POOLS)}, got {show(kind)}")
    return executor_for(kind)


def _label(motions: Sequence[GroundMotion], m: int) -> str:
    return motions[m].name or f"motion {m}"


def _property_envelope(building: ShearBuilding, property_factors: ArrayLike | None,
                       ambient_temperatures: ArrayLike | None, executor: concurrent.futures.Executor | str | None,
                       analyses: tuple[int, int],
                       run: Callable[[ShearBuilding, concurrent.futures.Executor], BatchResult]) -> BatchResult:
    """Envelope of ``run(variant, executor)`` over every device variant: each property factor f (``scaled(f)``
    of every device) at each ambient temperature T (``wall.at_ambient(T)`` for walls with a thermal
    description); see run_batch.  ``analyses``: (records, scales) of each variant's run, counted against the memory
    limit with the variants before any is built."""
    factors = np.array([1.0]) if property_factors is None else \
        finite_array("property_factors", property_factors, ndim=None).ravel()
    if factors.size == 0 or (factors <= 0).any():
        raise ValueError(f"property_factors must be one or more factors > 0, got {property_factors!r}")
    temperatures: list[float | None] = [None]
    if ambient_temperatures is not None:
        temperatures = [float(t) for t in finite_array("ambient_temperatures", ambient_temperatures, ndim=None).ravel()]
        if not temperatures or not any(wall.thermal is not None for _, wall in building.wall_list):
            raise ValueError("ambient_temperatures needs one or more temperatures (degC) and walls with a thermal "
                             f"description (thermal=ThermalProperties(...)), got {show(ambient_temperatures)}")

    def variant(factor: float, temperature: float | None) -> ShearBuilding:
        def wall_variant(wall: Any) -> Any:
            wall = wall.scaled(factor)
            if temperature is None or wall.thermal is None:
                return wall
            return wall.at_ambient(temperature)
        return building.with_devices({story: tuple(wall_variant(device) if is_wall(device) else device.scaled(factor)
                                                   for device in devices)
                                      for story, devices in building.devices.items()})

    _check_analyses(building, *analyses, variants=factors.size * len(temperatures))
    combinations = [(float(f), t) for f in factors for t in temperatures]
    variants = [variant(f, t) for f, t in combinations]
    with executor_for(executor) as pool:  # one pool for every variant
        results = [run(each, pool) for each in variants]
    envelope: dict[str, Any] = {}
    by_factor: dict[str, np.ndarray] = {}
    by_temperature: dict[str, np.ndarray] = {}
    for name in (*PEAKS, *DEVICE_PEAKS):
        if getattr(results[0], name) is None:
            envelope[name] = None
            continue
        stacked = np.stack([getattr(result, name) for result in results])
        worst = np.argmax(np.abs(stacked), axis=0)  # peaks are >= 0; residual drifts keep their sign
        envelope[name] = np.take_along_axis(stacked, worst[None], axis=0)[0]
        by_factor[name] = np.array([c[0] for c in combinations])[worst]
        if ambient_temperatures is not None:
            by_temperature[name] = np.array([c[1] for c in combinations])[worst]
    envelope["wall_failed"] = np.any([result.wall_failed for result in results], axis=0)
    earliest = np.min([result.wall_failure_time.filled(np.inf) for result in results], axis=0)
    envelope["wall_failure_time"] = np.ma.masked_array(np.where(envelope["wall_failed"], earliest, 0.0),
                                                       mask=~envelope["wall_failed"])
    envelope["collapsed"] = np.any([result.collapsed for result in results], axis=0)
    envelope["converged"] = np.all([result.converged for result in results], axis=0)
    return dataclasses.replace(
        results[0], **envelope,
        property_factors=None if property_factors is None else tuple(factors.tolist()),
        governing_factor=None if property_factors is None else by_factor,
        ambient_temperatures=None if ambient_temperatures is None else tuple(t for t in temperatures if t is not None),
        governing_temperature=None if ambient_temperatures is None else by_temperature)


def scale_factors_to_pga(motions: Iterable[GroundMotion], targets: ArrayLike) -> np.ndarray:
    """Factors (motions, targets) that scale each motion to each target PGA (mm/s^2)."""
    targets = finite_array("targets", targets)
    return np.array([[motion.scale_factor_to_pga(t) for t in targets] for motion in motions])


def scale_factors_to_spectral_acceleration(motions: Iterable[GroundMotion], targets: ArrayLike, period: float,
                                           damping_ratio: float = 0.05) -> np.ndarray:
    """Factors (motions, targets) that scale each motion to each target Sa(period) (mm/s^2, s).

    Sa is linear in the scale factor: one response spectrum per motion serves every target.
    """
    targets = np.array([target_acceleration("target spectral acceleration", t, 2)
                        for t in finite_array("targets", targets)])
    unit = np.array([motion.scale_factor_to_spectral_acceleration(1.0, period, damping_ratio) for motion in motions])
    return unit[:, None] * targets

