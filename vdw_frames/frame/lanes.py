"""Many analyses of one building in one compiled call: lanes, over a workspace allocated once and reused.

IDA, FEMA P695, the ASCE 7 verification and the design loop run the same building under many records or
intensities.  :func:`run_lanes` runs L of them (one lane a record) in one call of the compiled
:func:`~vdw_frames.frame.lane_kernel.integrate_lanes`, on a :class:`LaneWorkspace` that is sized once and
reused by every later batch that fits it (no allocation, hence no page faults, per analysis).

Design (issue 32):

* **One integrator.**  A lane is :func:`vdw_frames.frame.lane_kernel.run_lane`, the very compiled loop of
  the single analysis (``simulate`` runs it on one lane of full histories), called with the lane's views: the
  same compiled arithmetic in the same order, so every lane's peaks, collapse time and histories equal
  those of :func:`~vdw_frames.frame.simulation.simulate` of its record *to the bit* (``np.array_equal``;
  tests/frame/test_lanes.py).  The exceptions: walls on records of different lengths when the shorter
  one is within the exact memory's length (``FastMemory.exact_below``, 2048 steps) and the batch's longest
  is not, or the longest is beyond ``FastMemory.max_steps``: the batch's walls keep the fast memory built for
  its longest record (within 3e-9 of the exact one, :mod:`vdw_frames.element.fast_memory`); :func:`lane_batches`
  keeps such records apart.
* **State shaped (lanes, ...).**  Every array of the single analysis (the stories' committed state, the
  walls' bank, the other devices' states, the histories, the scratch) is stacked along a first axis of
  lanes; the compiled loop takes lane l's view of each (:func:`~vdw_frames.frame.lane_kernel.take`), which
  has the very type of the single analysis's array, so the loop compiles once for both.
* **Lanes in turn.**  The lanes run one after the other inside the call, each to its own end: a lane's state
  then stays in the cache over its whole record.  A lane that collapses or fails stops; the others go on
  (their results are independent of it).  Records of different lengths are padded to the longest (a lane
  stops at its own end); records of different dt are refused.  The lanes do not step in lockstep, and no
  arithmetic is vectorised across them: each lane's Newton iterations (their number, the stories' branches)
  depend on its own state, and the step was kept the single analysis's so that the results are too.
* **The workspace.**  One per thread (thread executors run batches side by side), kept after a batch and
  reused by the next when it fits (:func:`_fits`: the same building -- or a copy, an equal pickle: a worker
  unpickles the building for every task --, dt and settings, no more lanes, and walls
  whose memory is the same), its arrays copied back to rest in place: no allocation per analysis (the results'
  peaks are small copies; histories are asked for by name and copied out of the workspace, so no kept array
  holds the batch's memory).
* **What to record.**  ``record``: "peaks" (the default) keeps two rows of histories a lane (a ring: the
  state a step needs) and the peaks the batch callers need (:class:`~vdw_frames.frame.lane_kernel.LanePeaks`);
  a list of history names (those of :class:`~vdw_frames.frame.integrator.Histories`) keeps every row of those,
  copied out per lane.  ``wall_demands=True`` (verify's) also follows each wall's test demands step by step
  (``lane_kernel._note_walls``: the operations :func:`vdw_frames.verification.verify.wall_peaks` applies to the
  full histories, in their order, so to the bit); :func:`lane_batches` cuts many analyses into batches whose
  lanes equal simulate.

Units: N, mm, s, tonne; ground acceleration mm/s^2.
"""

from __future__ import annotations

import dataclasses
import math
import pickle
import threading
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from .. import _validation, _warnings
from .._parallel import raise_if_stopped, stop_flag
from .._validation import check_memory, non_negative, show
from ..element import kernel
from ..element.bank import DEFAULT_MEMORY, WallBank, group_walls, memory_strategy
from ..element.fast_memory import FastMemory
from ..element.fractional import DEFAULT_METHOD, Discretisation, get_method
from ..motion.record import G, GroundMotion
from .building import ShearBuilding
from .hysteresis import story_arrays
from .integrator import COLLAPSED, FAILED, NewtonRaphson, scratch
from .lane_kernel import WALL_CONSTANTS, LaneArrays, LaneExcitation, LanePeaks, integrate_lanes, lane_peaks
from .results import ENERGY_BALANCE_TOLERANCE
from .time_history import (
    _check_model,
    _histories,
    _warn_strain_range,
    _warn_temperature_range,
    check_masses,
    checked_settings,
    devices_of,
    frame_arrays,
    rest_steps,
    row_bytes,
)

if TYPE_CHECKING:
    from ..element.wall import Wall

PEAKS_ONLY = "peaks"
HISTORY_NAMES = ("displacement", "velocity", "acceleration", "drift", "story_shear", "story_wall_force", "base_shear",
                 "group_force", "group_strain", "energy", "group_temperature", "group_amplitude", "device_force",
                 "device_deformation", "device_velocity")
"""The histories a batch may keep (``record``), those of :class:`~vdw_frames.frame.integrator.Histories`."""


# ------------------------------------------------------------------------------------------------ workspace
def _stack(tree: Any, lanes: int) -> Any:
    """``tree`` (a named tuple of arrays, nested) with each array repeated along a new first axis of ``lanes``."""
    if isinstance(tree, np.ndarray):
        return np.repeat(tree[None], lanes, axis=0)
    if isinstance(tree, tuple) and hasattr(tree, "_fields"):
        return type(tree)(*(_stack(field, lanes) for field in tree))
    return tree


def _reset(stacked: Any, template: Any) -> None:
    """Every array of ``stacked`` back to ``template``'s (broadcast along the lanes), in place: no allocation."""
    if isinstance(stacked, np.ndarray):
        np.copyto(stacked, template[None])
    elif isinstance(stacked, tuple) and hasattr(stacked, "_fields"):
        for field, original in zip(stacked, template, strict=True):
            _reset(field, original)


@dataclass(frozen=True)
class _Layout:
    """What fixes a workspace's arrays: the building, the step, the lanes, the rows, the walls' memory."""

    building: ShearBuilding = field(compare=False)
    building_id: int  # the building itself (held by the layout, so its id stays its own)
    dt: float
    lanes: int
    rows: int
    memory_steps: int
    method: Discretisation
    memory: str | FastMemory
    collapse_ratio: float
    wall_demands: bool = False  # each wall's test demands followed (LanePeaks)


class LaneWorkspace:
    """The arrays of :func:`~vdw_frames.frame.lane_kernel.integrate_lanes` for ``layout``: allocated once, reset
    (copied back to rest) by every batch that uses them.  A batch's histories are views of these arrays until the
    next batch: :func:`run_lanes` copies out what it returns."""

    def __init__(self, layout: _Layout) -> None:
        building = layout.building
        self.layout = layout
        floors = building.stories
        walls = cast("list[tuple[int, Wall]]", building.wall_list)  # fixed walls, as time_history takes them
        others = building.other_device_list
        groups, self.group_of_wall = group_walls(walls)
        self.walls, self.groups = walls, groups
        bank = WallBank(tuple(wall for _, wall in groups), layout.dt, layout.memory_steps, layout.method,
                        layout.memory)
        self.bank = bank
        energy_followed = bank.state("energy_followed")
        heated = layout.rows if energy_followed.any() else 0
        heat_rows = heated if np.any((energy_followed > 0.0) & (bank.state("capacity") <= 0.0)) else 0
        amplitudes = layout.rows if bank.state("amplitude_nodes").any() else 0
        out = _histories(layout.rows, floors, len(groups), len(others), heated=heated, heat_rows=heat_rows,
                         amplitudes=amplitudes)
        if heated:
            out.group_temperature[0] = bank.state("temperature")
            out.group_heat[:1] = bank.state("heat")
            out.wall_heat[0] = bank.state("heat").sum()
            out.wall_stored[0] = bank.state("stored").sum()
            out.wall_parameter_loss[0] = bank.state("parameter_loss").sum()
        if amplitudes:
            out.group_amplitude[0] = bank.state("amplitude")
        stories = story_arrays(building.story_models, building.stiffnesses)
        devices = devices_of(groups, bank, others, layout.dt)
        self.template = LaneArrays(stories, devices, out, scratch(floors, len(groups)))
        self.arrays = LaneArrays(*(_stack(part, layout.lanes) for part in self.template))
        self.frame = frame_arrays(building, layout.collapse_ratio)
        lanes, others_count = layout.lanes, len(others)
        demands = len(walls) if layout.wall_demands else 0  # walls whose test demands are followed
        followed = walls if demands else []
        # each followed wall's group, thickness and share of its group's area (as SimulationResult.wall_share)
        wall_demands = (np.asarray(self.group_of_wall, dtype=np.int64)[:demands],
                        np.array([wall.thickness for _, wall in followed], dtype=float),
                        np.array([wall.area / groups[group][1].area for (_, wall), group
                                  in zip(walls, self.group_of_wall, strict=True)][:demands], dtype=float))
        self.peaks = lane_peaks(lanes, floors, len(groups), others_count, wall_demands)
        self.ground = np.zeros((lanes, layout.memory_steps))
        self.lengths = np.zeros(lanes, dtype=np.int64)
        self.batches = 0
        self.fingerprint = b""  # the building's pickle when the workspace was made (set by :func:`workspace`)

    def reset(self) -> None:
        """Every lane back at rest (the arrays of the first batch, rewritten in place)."""
        _reset(self.arrays, self.template)
        for name, peak in zip(LanePeaks._fields, self.peaks, strict=True):
            if name not in WALL_CONSTANTS:
                peak.fill(0)
        at_rest = self.template.out.group_temperature
        self.peaks.peak_group_temperature[:] = at_rest[0] if at_rest.shape[0] else np.nan


_cache = threading.local()  # each thread its own workspace (thread executors run batches side by side)


def _fits(held: _Layout, wanted: _Layout) -> bool:
    """Whether a workspace laid out as ``held`` serves a batch laid out as ``wanted``: the same building, step,
    settings and rows, at least as many lanes and steps, and walls whose memory is the same for both lengths
    (none, or the fast memory for both: built for at least ``FastMemory.max_steps`` steps whatever the record)."""
    if (held.building_id, held.dt, held.method, held.memory, held.collapse_ratio, held.rows, held.wall_demands) != (
            wanted.building_id, wanted.dt, wanted.method, wanted.memory, wanted.collapse_ratio, wanted.rows,
            wanted.wall_demands):
        return False
    if held.lanes < wanted.lanes or held.memory_steps < wanted.memory_steps:
        return False
    if held.memory_steps == wanted.memory_steps or not held.building.wall_list:
        return True
    strategy = memory_strategy(held.memory)
    return strategy is not None and wanted.memory_steps > strategy.exact_below and (
        held.memory_steps <= strategy.max_steps)


def _fingerprint(building: ShearBuilding) -> bytes:
    """The building's pickle: equal for a building and its copies (a worker unpickles the same building for each
    of its tasks), whose workspaces would be equal too."""
    return pickle.dumps(building, protocol=pickle.HIGHEST_PROTOCOL)


def workspace(layout: _Layout) -> LaneWorkspace:
    """This thread's workspace for ``layout``: the last one when it fits (:func:`_fits`: its idle lanes stay
    idle), else a new one (which replaces it).  A copy of the workspace's building (an equal pickle, taken at
    the same point of :func:`run_lanes`: a process pool's worker unpickles the building anew for every task)
    takes the workspace over, as the building itself would."""
    held = getattr(_cache, "workspace", None)
    fingerprint = None
    if held is not None and held.layout.building_id != layout.building_id:
        fingerprint = _fingerprint(layout.building)
        if fingerprint == held.fingerprint:
            held.layout = dataclasses.replace(held.layout, building=layout.building, building_id=layout.building_id)
    if held is None or not _fits(held.layout, layout):
        fingerprint = _fingerprint(layout.building) if fingerprint is None else fingerprint
        _cache.workspace = None  # the old arrays freed before the new ones are allocated
        held = LaneWorkspace(layout)
        held.fingerprint = fingerprint
        _cache.workspace = held
    return held


# ---------------------------------------------------------------------------------------------- the driver
@dataclass(frozen=True)
class LaneResult:
    """One lane's analysis: its peaks (copies, units of :class:`LanePeaks`), outcome and the histories asked
    for (``histories``: name -> (rows filled, ...) array, copies owned by the result)."""

    peak_drift: np.ndarray
    peak_drift_ratio: np.ndarray | None
    peak_absolute_acceleration: np.ndarray
    peak_base_shear: float
    peak_story_wall_force: np.ndarray
    residual_drift: np.ndarray
    peak_group_strain: np.ndarray  # (G,) -
    peak_group_temperature: np.ndarray  # (G,) degC
    peak_temperature_rise: np.ndarray | None  # (G,) K over the temperature at rest; None: no wall's heat followed
    group_failure_step: np.ndarray  # (G,) the step each wall group failed at (-1: it stood)
    peak_device_force: np.ndarray
    peak_device_deformation: np.ndarray
    peak_device_velocity: np.ndarray
    converged: bool
    collapsed: bool
    collapse_time: float | None  # s
    newton_iterations: int
    steps: int  # rows filled (the last at t = (steps - 1) dt)
    histories: dict[str, np.ndarray]
    error: str | None = None  # why the lane did not run (its input held a non-finite value)
    # The warnings simulate would have issued for this analysis (not issued: the caller says which lane gave them)
    warnings: tuple[_warnings.CollectedWarning, ...] = ()
    peak_group_amplitude: np.ndarray | None = None  # (G,) -, the largest amplitude followed; None: none followed
    group_failure_mode: np.ndarray | None = None  # (G,) int64, kernel.FAILURE_MODES index (0: it stood)
    # run_lanes(wall_demands=True): per wall of building.wall_list, name -> (W,): "deformation" (mm), "strain" (-),
    # "velocity" (mm/s), "force" (N), "cycle_energy" and "cumulative_energy" (N*mm), each up to the wall's failure,
    # as vdw_frames.verification.verify.wall_peaks defines them; None otherwise
    wall_demands: dict[str, np.ndarray] | None = None


LANES_PER_TASK = 44
"""At most this many analyses of one task of a fanned-out batch (one compiled call of the lanes engine): a FEMA P695
record set; with fewer tasks than about four a worker, a batch is cut finer so that every worker has some
(:func:`lane_batches`)."""


def lane_batches(building: ShearBuilding, motions: Sequence[GroundMotion], analyses: Sequence[Any], *,
                 memory: str | FastMemory = DEFAULT_MEMORY, free_vibration: float = 0.0, workers: int | None = 1,
                 apart: Sequence[Any] | None = None) -> list[list[Any]]:
    """``analyses`` (any keys; ``motions[i]`` the record of ``analyses[i]``) cut into batches that may run as the
    lanes of one :func:`run_lanes` call with every lane equal to simulate's analysis: one dt (exactly) a batch
    and, with walls, one side of the exact memory's length (``FastMemory.exact_below`` steps: simulate takes the
    exact memory below it, the fast one above; ``free_vibration`` s of rest counted as simulate rounds them) and,
    above it, one horizon of the fast memory's modes (built for the record's steps, at least ``FastMemory.max_steps``:
    a record longer than that shares a batch only with records of its own length), at most :data:`LANES_PER_TASK`
    analyses each, and at most about a quarter of a worker's share (``workers``
    processes or threads: finer tasks balance the pool; None: no pool, the batches as large as they may be), and
    within the memory limit of a peaks-only :func:`run_lanes` call (:func:`lane_bytes` a step and
    :func:`lane_state_bytes` a lane), so that a batch runs
    whenever each of its records alone would.
    Analyses whose ``apart`` (one hashable key an analysis, e.g. the building's variant; ``building`` then stands
    for all: walls or none) differ never share a batch.  In the order of ``analyses`` within each batch."""
    apart = [None] * len(analyses) if apart is None else list(apart)
    if not len(motions) == len(apart) == len(analyses):
        raise ValueError(f"lane_batches needs one record (and one key apart, if any) an analysis, got {len(motions)} "
                         f"records and {len(apart)} keys for {len(analyses)} analyses")
    share = len(analyses) if workers is None else math.ceil(len(analyses) / (4 * max(1, workers)))
    size = max(1, min(LANES_PER_TASK, share))
    strategy = memory_strategy(memory) if building.wall_list else None
    free_vibration = non_negative("free_vibration", free_vibration)

    def steps_of(motion: GroundMotion) -> float:
        """The record's steps and its rest, rounded as simulate rounds them (inf for a rest too long to count)."""
        if not math.isfinite(free_vibration / motion.dt):
            return math.inf
        return motion.acceleration.size + rest_steps(free_vibration, motion.dt)

    def horizon(steps: float) -> float:
        """The walls' memory of an analysis of ``steps`` steps: -1 exact (or no walls), else the steps the fast
        memory's modes are built for (FastMemory.arrays: the record's steps, at least max_steps), which a batch
        builds for its longest record: records beyond max_steps would otherwise take another record's modes."""
        if strategy is None or steps <= strategy.exact_below:
            return -1.0
        return float(max(steps, strategy.max_steps))

    state = lane_state_bytes(building)
    by_key: dict[tuple[Any, float, float], list[tuple[Any, float]]] = {}
    for motion, analysis, key in zip(motions, analyses, apart, strict=True):
        steps = steps_of(motion)
        by_key.setdefault((key, motion.dt, horizon(steps)), []).append((analysis, steps))
    batches: list[list[Any]] = []
    for group in by_key.values():
        for first in range(0, len(group), size):
            batch: list[Any] = []
            longest = 0.0
            for analysis, steps in group[first:first + size]:
                longest_then = max(longest, steps)
                if batch and (len(batch) + 1) * (longest_then * lane_bytes(building, longest_then, memory) + state) > \
                        _validation.MEMORY_LIMIT_BYTES:  # (read now: tests lower it)
                    batches.append(batch)
                    batch, longest_then = [], steps
                batch.append(analysis)
                longest = longest_then
            batches.append(batch)
    return batches


def lane_bytes(building: ShearBuilding, steps: float, memory: str | FastMemory, *, histories: bool = False) -> int:
    """Bytes a lane of a :func:`run_lanes` call whose longest record (rest included) has ``steps`` steps takes a
    step: its ground acceleration, its walls' exact memory (as simulate counts it) where the walls keep one (the
    exact strategy, or a record within the fast one's exact length) and, with ``histories`` asked for by name,
    every row of them (simulate's count of a row)."""
    strategy = memory_strategy(memory)
    exact = strategy is None or steps <= strategy.exact_below
    return 8 + row_bytes(building.stories, len(building.wall_list), len(building.other_device_list),
                         wall_memory=exact, histories=histories)


def lane_state_bytes(building: ShearBuilding) -> int:
    """Bytes a lane of a :func:`run_lanes` call takes whatever its length: its state in the workspace (the frame's,
    each wall group's and device's), its peaks and its :class:`LaneResult`.  Measured (tracemalloc, peaks only,
    41-step records, 200-1500 lanes): 3.2 KB a lane of a bare 2-story frame, 7.7-10.5 KB of a bare 10-story one
    (10.5 with hysteresis and gravity), 33 KB of a bare 40-story one (a floors^2 term), 34 KB of state besides the
    walls' exact memory a step in the 10-story example with 10 walls, 63 KB with 20 stories and 20 wall groups; this
    count is 1.2-1.9 times those, so that a number of lanes cannot ask for unbounded memory unseen (the per-step
    arrays are :func:`lane_bytes`)."""
    floors = building.stories
    walls = cast("list[tuple[int, Wall]]", building.wall_list)  # as the workspace groups them
    groups = len(group_walls(walls)[0]) if walls else 0
    return 4096 + 1024 * floors + 8 * floors**2 + 3072 * groups + 512 * len(building.other_device_list)


def _record_names(record: str | Sequence[str]) -> tuple[str, ...]:
    if isinstance(record, str):
        if record != PEAKS_ONLY:
            raise ValueError(f"record must be {PEAKS_ONLY!r} or a list of history names from {HISTORY_NAMES}, "
                             f"got {record!r}")
        return ()
    names = tuple(record)
    unknown = [name for name in names if name not in HISTORY_NAMES]
    if unknown or not names:
        raise ValueError(f"record must be {PEAKS_ONLY!r} or a non-empty list of history names from {HISTORY_NAMES}, "
                         f"got {list(names)!r}")
    return names


def run_lanes(building: ShearBuilding, motions: Sequence[GroundMotion], scales: Sequence[float] | None = None, *,
              record: str | Sequence[str] = PEAKS_ONLY,
              method: str | Discretisation = DEFAULT_METHOD, memory: str | FastMemory = DEFAULT_MEMORY,
              collapse_drift_ratio: float | None = 0.10, free_vibration: float = 0.0,
              newton: NewtonRaphson | None = None, wall_demands: bool = False) -> list[LaneResult]:
    """Run ``building`` under every record of ``motions`` (mm/s^2), one lane each, in one compiled call
    (:func:`~vdw_frames.frame.lane_kernel.integrate_lanes`) on this thread's reused workspace; returns one
    :class:`LaneResult` a record, equal to :func:`~vdw_frames.frame.simulation.simulate` of that record with the
    same options (module docstring: to the bit).

    ``record``: "peaks" (peaks, outcome, wall failures only) or a list of history names
    (:data:`HISTORY_NAMES`), kept for every lane (copies).  ``scales`` (-, one a record; default 1): lane l
    runs ``motions[l].scaled(scales[l])``, scaled into the workspace (the product of ``GroundMotion.scaled``,
    without a new record).  Every record must have the same dt (s; else a ValueError naming two that differ;
    split such a batch by dt) and at least one step; a lane whose scaled acceleration holds a non-finite value
    (an overflowing scale, say) is not run: its result has ``error`` set and ``converged`` False, and the
    other lanes run; so does a lane whose response or energies overflow (``error`` says which, as simulate's
    ValueError would).  ``method``, ``memory``, ``collapse_drift_ratio`` (-, None: never), ``free_vibration``
    (s of rest after each record), ``newton``: as for ``simulate``.  ``wall_demands``: also follow every wall's
    test demands (:attr:`LaneResult.wall_demands`, those of :func:`vdw_frames.verification.verify.wall_peaks`
    to the bit), a few operations a wall and step more.
    """
    names = _record_names(record)
    motions = list(motions)
    if not motions:
        raise ValueError("run_lanes needs at least one record, got none")
    _check_model(building, motions[0])
    for motion in motions[1:]:
        if not isinstance(motion, GroundMotion):
            raise ValueError(f"motions must be GroundMotion objects (see read_at2), got {type(motion).__name__}")
    dt = motions[0].dt
    for motion in motions[1:]:
        if abs(motion.dt - dt) > 1e-12 * dt:
            raise ValueError(f"the records of one batch must share dt: {motions[0].name or 'record 0'!r} has "
                             f"dt = {dt!r} s, {motion.name or 'another'!r} dt = {motion.dt!r} s; split the batch by dt")
    lengths = np.array([motion.acceleration.size for motion in motions], dtype=np.int64)
    if (lengths < 2).any():
        short = motions[int(np.argmin(lengths))]
        raise ValueError(f"record {short.name or int(np.argmin(lengths))!r} has {int(lengths.min())} value(s): "
                         "a record needs at least 2 (one step)")
    newton, collapse_drift_ratio = checked_settings(newton, collapse_drift_ratio)
    factors = np.ones(len(motions)) if scales is None else np.asarray(scales, dtype=float)
    if factors.shape != (len(motions),) or not np.isfinite(factors).all():
        raise ValueError(f"scales must be {len(motions)} finite factors (one a record), got {show(scales)}")
    free_vibration = non_negative("free_vibration", free_vibration)
    # checked before the rest is rounded, as simulate checks it: 1e308 s / dt is inf, which ceil refuses
    check_memory(f"run_lanes ({len(motions)} lanes, free_vibration = {show(free_vibration)} s)",
                 float(len(motions)) * (float(lengths.max()) + free_vibration / dt), 8.0,
                 "use a shorter free_vibration")
    rest = rest_steps(free_vibration, dt)
    lengths = lengths + rest
    longest = int(lengths.max())
    # checked before the workspace is made
    walls = len(building.wall_list)
    check_memory(f"run_lanes ({len(motions)} lanes of up to {longest} steps, {building.stories} floors, {walls} walls"
                 f"{', histories ' + ', '.join(names) if names else ''})", float(len(motions)) * longest,
                 lane_bytes(building, longest, memory, histories=bool(names)),
                 "split the batch" + (" or keep fewer histories (record='peaks')" if names else ""))
    # and each lane's state and result besides (a million lanes of a short record: gigabytes of them)
    check_memory(f"run_lanes ({len(motions)} lanes of up to {longest} steps, {building.stories} floors, {walls} walls: "
                 "each lane's state and result with its steps)", len(motions),
                 lane_state_bytes(building) + longest * lane_bytes(building, longest, memory, histories=bool(names)),
                 "split the batch", unit="lanes")
    check_masses(building, dt)
    collapse_ratio = float(collapse_drift_ratio) if (collapse_drift_ratio and building.story_heights) else 0.0
    if not isinstance(wall_demands, bool):
        raise ValueError(f"wall_demands must be True or False, got {show(wall_demands)}")
    layout = _Layout(building, id(building), float(dt), len(motions), longest if names else 2, longest,
                     get_method(method), memory, collapse_ratio, wall_demands)
    stop = stop_flag()
    raise_if_stopped(stop)  # before the workspace (and the walls' fast memory) is made, not only within the loop
    space = workspace(layout)
    space.reset()
    space.batches += 1
    errors: list[str | None] = []
    space.ground[:, :] = 0.0
    space.lengths[:] = 0  # lanes beyond this batch's stay idle
    for lane, motion in enumerate(motions):
        size = motion.acceleration.size
        ground = space.ground[lane, :size]  # the free vibration after it: zeros
        with np.errstate(over="ignore", invalid="ignore"):
            np.multiply(motion.acceleration, factors[lane], out=ground)
        bad = np.flatnonzero(~np.isfinite(ground))
        if bad.size:
            errors.append(f"the ground acceleration of {motion.name or f'record {lane}'!r} x {show(factors[lane])} "
                          f"is {show(ground[bad[0]])} at t = {bad[0] * dt:.6g} s (not finite): this lane was not run")
            space.lengths[lane] = 0
            continue
        errors.append(None)
        space.lengths[lane] = lengths[lane]
    lanes = space.arrays
    lanes.out.acceleration[:, 0, :] = -space.ground[:, :1]
    integrate_lanes(LaneExcitation(space.ground, space.lengths, float(dt), 0, stop), space.frame, lanes,
                    newton.arrays(), space.peaks)
    raise_if_stopped(stop)
    for lane, motion in enumerate(motions):
        overflow = int(space.peaks.overflow[lane])
        if overflow and errors[lane] is None:
            what = "the response" if overflow & 1 else "the energy histories"
            name = f"ground motion {motion.name!r}, " if motion.name else ""
            pga = abs(float(factors[lane])) * motion.pga
            errors[lane] = (f"{what} overflowed (inf or NaN): the inputs or parameters are too large ({name}PGA "
                            f"{pga:.6g} mm/s^2 = {pga / G:.4g} g)")
    return [_lane_result(space, lane, names, errors[lane]) for lane in range(len(motions))]


def _lane_result(space: LaneWorkspace, lane: int, names: tuple[str, ...], error: str | None) -> LaneResult:
    """Lane ``lane``'s result, every array a copy (the workspace's arrays serve the next batch)."""
    peaks, building, dt = space.peaks, space.layout.building, space.layout.dt
    status, _, iterations, filled = (int(x) for x in peaks.outcome[lane])
    heights = building.story_heights
    out = space.arrays.out
    limits = space.arrays.walls.bank.states.walls["limits"]
    failure_step = limits["failure_step"][lane].astype(np.int64)
    if error is not None:
        status, filled = FAILED, 0
        caught: list[_warnings.CollectedWarning] = []
    else:
        with _warnings.collect() as caught:
            _warn_as_simulate(space, lane)
    return LaneResult(
        peak_drift=peaks.peak_drift[lane].copy(),
        peak_drift_ratio=None if heights is None else peaks.peak_drift[lane] / np.asarray(heights),
        peak_absolute_acceleration=peaks.peak_absolute_acceleration[lane].copy(),
        peak_base_shear=float(peaks.peak_base_shear[lane]),
        peak_story_wall_force=peaks.peak_story_wall_force[lane].copy(),
        residual_drift=peaks.residual_drift[lane].copy(), peak_group_strain=out.peak_group_strain[lane].copy(),
        peak_group_temperature=peaks.peak_group_temperature[lane].copy(), group_failure_step=failure_step,
        peak_temperature_rise=(peaks.peak_group_temperature[lane] - space.template.out.group_temperature[0]
                               if space.template.out.group_temperature.shape[0] else None),
        peak_device_force=peaks.peak_device_force[lane].copy(),
        peak_device_deformation=peaks.peak_device_deformation[lane].copy(),
        peak_device_velocity=peaks.peak_device_velocity[lane].copy(),
        converged=status != FAILED, collapsed=status == COLLAPSED,
        collapse_time=(filled - 1) * dt if status == COLLAPSED else None, newton_iterations=iterations,
        steps=filled, histories={name: getattr(out, name)[lane, :filled].copy() for name in names}, error=error,
        warnings=tuple(caught),
        peak_group_amplitude=(peaks.peak_group_amplitude[lane].copy() if space.template.out.group_amplitude.shape[0]
                              else None),
        group_failure_mode=limits["failure_mode"][lane].astype(np.int64),
        wall_demands=_wall_demands(peaks, lane) if space.layout.wall_demands else None)


def _wall_demands(peaks: LanePeaks, lane: int) -> dict[str, np.ndarray]:
    """Lane ``lane``'s wall demands (copies): the peaks of :class:`LanePeaks`, and the largest cycle's work where
    two upward zero crossings or more were seen, else the whole work (as ``cycle_energies`` takes it)."""
    work = peaks.wall_work[lane].copy()
    return {"deformation": peaks.peak_wall_deformation[lane].copy(), "strain": peaks.peak_wall_strain[lane].copy(),
            "velocity": peaks.peak_wall_velocity[lane].copy(), "force": peaks.peak_wall_force[lane].copy(),
            "cycle_energy": np.where(peaks.wall_trace[lane, :, 4] >= 2.0, peaks.wall_cycle_energy[lane], work),
            "cumulative_energy": work}


class _LaneBank:
    """One lane's wall states read as :meth:`WallBank.state` reads a bank's (copies)."""

    def __init__(self, records: np.ndarray) -> None:
        self.records = records

    def state(self, field: str) -> np.ndarray:
        for group, fields in kernel.GROUPS.items():
            if field in fields:
                return np.array(self.records[group][field], dtype=float)
        raise ValueError(f"no wall state field {field!r}")


def _warn_as_simulate(space: LaneWorkspace, lane: int) -> None:
    """The warnings :func:`~vdw_frames.frame.time_history.time_history` gives its analysis, in its order, from
    the lane's peaks and wall states: non-convergence, walls outside their strain range or amplitudes, wall
    temperatures outside their shift law's range, the energy balance's self-check."""
    peaks, dt = space.peaks, space.layout.dt
    status, story, _, filled = (int(x) for x in peaks.outcome[lane])
    if status == FAILED:
        _warnings.warn(f"simulate: the step to t = {filled * dt:.6g} s did not converge "
                       f"(story {story + 1} moved most in the last correction), even with a line search "
                       "and initial-stiffness iterations; the analysis stops there (result.converged is False)",
                       RuntimeWarning)
    bank = _LaneBank(space.arrays.walls.bank.states.walls[lane])
    group_of_wall = space.group_of_wall
    above = bank.state("above_range")[group_of_wall] * dt
    amplitude = (peaks.peak_group_amplitude[lane][group_of_wall] if space.template.out.group_amplitude.shape[0]
                 else None)
    _warn_strain_range(space.walls, space.arrays.out.peak_group_strain[lane][group_of_wall], above, amplitude)
    _warn_temperature_range(space.groups, bank, dt)  # type: ignore[arg-type]
    scale = float(peaks.peak_input[lane])
    if scale > 0.0 and float(peaks.peak_balance_error[lane]) / scale > ENERGY_BALANCE_TOLERANCE:
        error = float(peaks.peak_balance_error[lane]) / scale
        _warnings.warn(f"simulate: the energy balance misses by {error:.3g} of the peak input energy (self-check "
                       f"bound {ENERGY_BALANCE_TOLERANCE:g}): the integration did not solve the equations of "
                       "motion to their tolerance; do not trust this result", RuntimeWarning)


__all__ = ["HISTORY_NAMES", "LANES_PER_TASK", "PEAKS_ONLY", "LanePeaks", "LaneResult", "LaneWorkspace",
           "integrate_lanes", "lane_batches", "run_lanes", "workspace"]
