"""One nonlinear time-history analysis of a shear building with walls of fixed parameters.

:func:`time_history` validates the inputs, lays the building, its story models and its walls out as the
compiled integrator's arrays (:mod:`vdw_frames.frame.integrator`), runs it, and assembles the
:class:`~vdw_frames.frame.results.SimulationResult`.  :func:`vdw_frames.simulate` calls it directly, or
through the strain-compatible iteration (:mod:`vdw_frames.frame.strain_compatible`).

Units: N, mm, s, tonne.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from .. import _warnings
from .._parallel import raise_if_stopped, stop_flag
from .._validation import check_memory, non_negative, positive, require_finite, show, time_step
from ..element.bank import DEFAULT_MEMORY, WallBank, group_walls, memory_strategy, wall_order
from ..element.devices import device_states
from ..element.fast_memory import FastMemory
from ..element.fractional import DEFAULT_METHOD, Discretisation, get_method
from ..element.wall import AMPLITUDE_OUTSIDE, PEAK_OUTSIDE, TEMPERATURE_OUTSIDE
from ..motion.record import G, GroundMotion
from .building import ShearBuilding, require_stable_under_gravity
from .hysteresis import StoryArrays, story_arrays
from .integrator import (
    COLLAPSED,
    ENERGIES,
    FAILED,
    DeviceArrays,
    FrameArrays,
    Histories,
    NewtonRaphson,
    Scratch,
    replay,
    scratch,
)
from .lane_kernel import LaneExcitation, lane_peaks, run_lane
from .results import FrameState, SimulationResult, energy_history

if TYPE_CHECKING:
    from ..element.device import Device
    from ..element.strain_dependent import StrainDependentDamper
    from ..element.wall import Wall

MAX_MODAL_DAMPING_STORIES = 300
"""Largest building (stories) :func:`time_history` integrates with ``damping_model="modal"``, refused before any
work: the modal damping matrix is dense (a full eigendecomposition), so every step solves a dense n x n system,
O(n^3).  Measured on the development machine under load, 300 steps took 1.0 s at 100 stories, 7 s at 300 and
234 s at 1 000.  Rayleigh damping is tridiagonal (O(n) a step; 300 steps of 10 000 stories in 2-13 s), bounded
only by the memory of its damping matrix (n x n floats within the 2 GiB limit: at most 16 384 stories)."""


def _require_size(building: ShearBuilding) -> None:
    """ValueError, before any work, for a building beyond :data:`MAX_MODAL_DAMPING_STORIES` with modal damping or
    whose damping matrix exceeds the memory limit."""
    floors = building.stories
    if building.damping_model == "modal" and floors > MAX_MODAL_DAMPING_STORIES:
        raise ValueError(f"simulate takes buildings of at most {MAX_MODAL_DAMPING_STORIES} stories with modal damping, "
                         f"got {floors} stories: its dense damping matrix makes every step a dense solve, O(n^3); "
                         "use damping_model='rayleigh' (O(n) a step)")
    # The integrator takes C as an n x n array (only its band is read with Rayleigh damping).
    check_memory(f"simulate's damping matrix ({floors} x {floors} floors)", float(floors) ** 2, 8.0,
                 "fewer stories", unit="entries")


def time_history(building: ShearBuilding, ground_motion: GroundMotion, dt: float | None = None,
                 method: str | Discretisation = DEFAULT_METHOD, memory: str | FastMemory = DEFAULT_MEMORY, *,
                 collapse_drift_ratio: float | None = 0.10, free_vibration: float = 0.0,
                 newton: NewtonRaphson | None = None, initial_state: FrameState | None = None) -> SimulationResult:
    """Integrate ``building`` under ``ground_motion`` (mm/s^2): walls of fixed parameters, walls that heat
    (a thermal description), walls that follow their own strain amplitude (strain-dependent walls with a
    common r), walls that fail (limits), fluid viscous and friction dampers.

    The arguments are those of :func:`vdw_frames.simulate` (units there); this is its analysis whenever
    the strain-compatible iteration is not asked for.
    """
    _check_model(building, ground_motion)
    method = get_method(method)
    memory_strategy(memory)
    newton, collapse_drift_ratio = checked_settings(newton, collapse_drift_ratio)
    free_vibration = non_negative("free_vibration", free_vibration)
    dt = time_step(ground_motion.dt if dt is None else dt)
    substeps = ground_motion.substeps(dt)  # the one check of the step against the record
    dt = ground_motion.dt / substeps
    check_masses(building, dt)
    floors, walls = building.stories, cast("list[tuple[int, Wall]]", building.wall_list)  # fixed walls only
    # Response and result histories (about 14 per floor), each wall's force, strain and exact memory,
    # energies: float64 a step.
    others = building.other_device_list
    step_bytes = row_bytes(floors, len(walls), len(others))
    record_steps = (ground_motion.acceleration.size - 1) * substeps + 1
    if free_vibration > 0.0:  # named first: its steps may not even be a number (1e308 s / dt = inf)
        check_memory(f"simulate with free_vibration = {show(free_vibration)} s (dt = {dt!r} s, {floors} floors, "
                     f"{len(walls)} walls)", record_steps + free_vibration / dt, step_bytes,
                     "use a shorter free_vibration")
    rest = rest_steps(free_vibration, dt)
    steps = record_steps + rest
    start = 0 if initial_state is None else _check_state(initial_state, dt, steps, floors)
    check_memory(f"simulate (dt = {dt!r} s, {floors} floors, {len(walls)} walls)", steps, step_bytes,
                 "use a larger dt")
    ground = ground_motion.interpolated(substeps)
    if rest:
        ground = np.concatenate([ground, np.zeros(rest)])
    ground = ground[start:]
    rows = steps - start

    stop = stop_flag()
    raise_if_stopped(stop)  # before the walls' memory is built, not only within the loop
    groups, group_of_wall = group_walls(walls)
    bank = WallBank(tuple(wall for _, wall in groups), dt, steps, method, memory)
    energy_followed = bank.state("energy_followed")  # walls whose heat and stored energy are followed
    heated = rows if energy_followed.any() else 0
    # A group with a heat capacity keeps its heat in its temperature (SimulationResult.wall_heat finds it from
    # there); the heat itself is recorded only when some followed group has none (limits only).
    heat_rows = heated if np.any((energy_followed > 0.0) & (bank.state("capacity") <= 0.0)) else 0
    amplitudes = rows if bank.state("amplitude_nodes").any() else 0
    collapse_ratio = collapse_drift_ratio if (collapse_drift_ratio and building.story_heights) else 0.0
    frame = frame_arrays(building, collapse_ratio)
    out = _histories(rows, floors, len(groups), len(others), heated=heated, heat_rows=heat_rows,
                     amplitudes=amplitudes)
    stories = story_arrays(building.story_models, building.stiffnesses)
    device_arrays = devices_of(groups, bank, others, dt)
    work = scratch(floors, len(groups))
    if initial_state is None:
        out.acceleration[0] = -ground[0]
    else:
        _start_from(initial_state, frame, stories, device_arrays, out, work)
    if heated:
        out.group_temperature[0] = bank.state("temperature")
        out.group_heat[:1] = initial_heat = bank.state("heat")
        out.wall_heat[0] = initial_heat.sum()
        out.wall_stored[0] = bank.state("stored").sum()
        out.wall_parameter_loss[0] = bank.state("parameter_loss").sum()
    if amplitudes:
        out.group_amplitude[0] = bank.state("amplitude")
    outcome = lane_peaks(1, 0, 0, 0)  # a single analysis keeps its histories: of the peaks, only the outcome
    excitation = LaneExcitation(np.ascontiguousarray(ground[None]), np.array([ground.size], dtype=np.int64),
                                float(dt), int(start), stop)
    run_lane(0, excitation, frame, stories, device_arrays, out, work, newton.arrays(), outcome)
    raise_if_stopped(stop)
    status, story_index, iterations, filled = (int(x) for x in outcome.outcome[0])
    if status == FAILED:
        _warnings.warn(f"simulate: the step to t = {(start + filled) * dt:.6g} s did not converge "
                       f"(story {story_index + 1} moved most in the last correction), even with a line search "
                       "and initial-stiffness iterations; the analysis stops there (result.converged is False)",
                       RuntimeWarning,
                       stacklevel=3)
    keep = slice(0, filled)
    try:
        require_finite("the response", out.displacement[keep])
    except ValueError as error:
        raise ValueError(f"{error} {_record_text(ground_motion)}") from None
    time = np.arange(start, start + filled) * dt
    share = np.array([walls[i][1].area / groups[g][1].area for i, g in enumerate(group_of_wall)])
    above = bank.state("above_range")[group_of_wall] * dt
    amplitude = out.group_amplitude[keep].max(axis=0, initial=0.0)[group_of_wall] if out.group_amplitude.size else None
    _warn_strain_range(walls, out.peak_group_strain[group_of_wall], above, amplitude)
    _warn_temperature_range(groups, bank, dt)
    failure = np.stack([bank.state("failure_step"), bank.state("failure_mode")], axis=1).astype(np.int64)
    wall_energies = None
    if heated and energy_followed.all():
        wall_energies = (out.wall_heat[keep], out.wall_stored[keep], _released_energy(bank, failure, start, filled),
                         out.wall_parameter_loss[keep])
    try:
        energies = energy_history(out.energy[keep], wall_energies, _device_energies(out, keep, walls=bool(walls)))
    except ValueError as error:
        raise ValueError(f"{error} {_record_text(ground_motion)}") from None
    return SimulationResult(
        building=building, time=time, ground_acceleration=ground[keep], displacement=out.displacement[keep],
        velocity=out.velocity[keep], acceleration=out.acceleration[keep], drift=out.drift[keep],
        story_shear=out.story_shear[keep], story_wall_force=out.story_wall_force[keep], base_shear=out.base_shear[keep],
        energy=energies, group_force=out.group_force[keep],
        group_strain=out.group_strain[keep], wall_group=group_of_wall, wall_share=share,
        converged=status != FAILED, collapsed=status == COLLAPSED,
        collapse_time=float(time[-1]) if status == COLLAPSED else None, newton_iterations=iterations,
        group_temperature=out.group_temperature[keep], group_heat=out.group_heat[keep],
        group_heat_terms=(np.stack([initial_heat, bank.state("ambient"), bank.state("decay"),
                                    bank.state("gain")], axis=1) if heated and not heat_rows
                          else np.zeros((0, 4))),
        group_failure=failure, group_amplitude=out.group_amplitude[keep],
        group_outside_range=np.stack([bank.state("below_range"), bank.state("above_range")], axis=1) * dt,
        initial_state=initial_state, device_force=out.device_force[keep],
        device_deformation=out.device_deformation[keep], device_velocity=out.device_velocity[keep],
        device_heat=out.device_heat[keep], device_stored=out.device_stored[keep])


def _device_energies(out: Histories, keep: slice, *, walls: bool) -> tuple | None:
    """(heat, stored) of the devices that are not walls, summed (rows,) N*mm; None without any.  A building
    without walls gets wall parts of 0 (:func:`~vdw_frames.frame.results.energy_history` adds them)."""
    if out.device_heat.shape[1] == 0:
        return None
    return out.device_heat[keep].sum(axis=1), out.device_stored[keep].sum(axis=1), walls


def checked_settings(newton: NewtonRaphson | None, collapse_drift_ratio: float | None
                     ) -> tuple[NewtonRaphson, float | None]:
    """``newton`` (None: the defaults) and ``collapse_drift_ratio`` (-, None: never) as every analysis checks them:
    0, a negative or a NaN limit is refused, not taken as "never"."""
    newton = NewtonRaphson() if newton is None else newton
    if not isinstance(newton, NewtonRaphson):
        raise ValueError(f"newton must be a NewtonRaphson, got {type(newton).__name__}")
    if collapse_drift_ratio is not None:
        collapse_drift_ratio = positive("collapse_drift_ratio", collapse_drift_ratio)
    return newton, collapse_drift_ratio


def check_masses(building: ShearBuilding, dt: float) -> None:
    """ValueError when Newmark's inertia term of the effective stiffness, 4 m / dt^2 (m tonne, dt s), overflows."""
    heaviest = max(building.masses)
    if not math.isfinite(4.0 / dt**2 * heaviest):
        raise ValueError(f"masses up to {heaviest:.6g} t with dt = {dt!r} s overflow Newmark's 4 m / dt^2 (inf): "
                         "the masses are too large to integrate")


def rest_steps(free_vibration: float, dt: float) -> int:
    """The steps of ``free_vibration`` s of rest at ``dt`` s, rounded up (a hair below a whole step: that step)."""
    return math.ceil(free_vibration / dt - 1e-9) if free_vibration > 0.0 else 0


def row_bytes(floors: int, walls: int, devices: int, *, wall_memory: bool = True, histories: bool = True) -> int:
    """Bytes an analysis keeps a step (float64): each wall's force, strain and exact memory (``wall_memory``) and
    every history row (``histories``: about 14 a floor, 5 a device, the energies)."""
    return 8 * ((6 * walls if wall_memory else 0) + (14 * floors + 5 * devices + 12 if histories else 0))


def frame_arrays(building: ShearBuilding, collapse_ratio: float) -> FrameArrays:
    """The building as the integrator sees it: fresh writable float64 copies, but for the n x n damping matrix, a
    read-only view of the building's (not a second n^2 floats; read-only whatever the building's flags), so that
    every building gives one array type and the step compiles once; stopping at a drift ratio of
    ``collapse_ratio`` (-, 0: never)."""
    heights = building.story_heights if building.story_heights is not None else np.ones(building.stories)
    damping = np.ascontiguousarray(building.damping_matrix, dtype=float).view()
    damping.flags.writeable = False
    return FrameArrays(
        masses=np.array(building.masses, dtype=float), damping=damping,
        story_damping_row=np.array(building.story_damping_row, dtype=float),
        geometric=np.array(building.geometric_stiffness, dtype=float), heights=np.array(heights, dtype=float),
        tridiagonal=building.damping_model == "rayleigh", linear=building.is_linear and building.devices_linear,
        collapse_ratio=float(collapse_ratio))


def devices_of(groups: Sequence[tuple[int, Any]], bank: WallBank, others: Sequence[tuple[int, Device]],
               dt: float) -> DeviceArrays:
    """The devices as the integrator sees them: the wall groups ((story 1-based, combined wall)) of ``bank``
    and the other devices ((story 1-based, device); none: an empty state), at rest on a step of ``dt`` s."""
    return DeviceArrays(np.array([story - 1 for story, _ in groups], dtype=np.int64),
                        np.array([combined.wall.magnification for _, combined in groups], dtype=float),
                        bank.arrays, device_states(others, dt))


def _histories(rows: int, floors: int, groups: int, devices: int, *, heated: int, heat_rows: int,
               amplitudes: int) -> Histories:
    """Zeroed histories of ``rows`` rows: the walls' heat (``heated``, ``heat_rows`` rows) and amplitude
    (``amplitudes`` rows) only where followed."""
    return Histories(
        displacement=np.zeros((rows, floors)), velocity=np.zeros((rows, floors)),
        acceleration=np.zeros((rows, floors)), drift=np.zeros((rows, floors)),
        story_shear=np.zeros((rows, floors)), story_wall_force=np.zeros((rows, floors)),
        base_shear=np.zeros(rows), group_force=np.zeros((rows, groups)),
        group_strain=np.zeros((rows, groups)), peak_group_strain=np.zeros(groups),
        energy=np.zeros((rows, ENERGIES)),
        group_temperature=np.zeros((heated, groups)), group_heat=np.zeros((heat_rows, groups)),
        wall_heat=np.zeros(heated), wall_stored=np.zeros(heated), wall_parameter_loss=np.zeros(heated),
        group_amplitude=np.zeros((amplitudes, groups)), device_force=np.zeros((rows, devices)),
        device_deformation=np.zeros((rows, devices)), device_velocity=np.zeros((rows, devices)),
        device_heat=np.zeros((rows, devices)), device_stored=np.zeros((rows, devices)))


def _check_model(building: ShearBuilding, ground_motion: GroundMotion) -> None:
    """Refuse what is not a building and a record, a building too large, or one unstable under its gravity
    loads (before any array is built)."""
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    for _, wall in building.wall_list:  # an amplitude-following wall needs one r (its memory's)
        wall_order(wall)
    if not isinstance(ground_motion, GroundMotion):
        raise ValueError(f"ground_motion must be a GroundMotion (see read_at2), got {type(ground_motion).__name__}")
    _require_size(building)
    require_stable_under_gravity(building, "simulate")


def _released_energy(bank: WallBank, failure: np.ndarray, start: int, filled: int) -> np.ndarray:
    """The walls' energy (N*mm) released by their failures, row by row: from each failure's row on, the stored
    energy it released; from the next row on, the work on its lost share as its force fell."""
    released = np.zeros(filled)
    for step, energy, falling_work in zip(failure[:, 0], bank.state("released"),
                                          bank.state("released_work"), strict=True):
        if step >= 0:
            released[max(int(step) - start, 0):] += energy
            released[max(int(step) + 1 - start, 0):] += falling_work
    return released


def _record_text(ground_motion: GroundMotion) -> str:
    """The record and its PGA, in g as well (the unit of a CLI's scale), for an overflow's message: formed
    only when one is raised (the PGA is a pass over the record)."""
    name = f"ground motion {ground_motion.name!r}, " if ground_motion.name else ""
    return f"({name}PGA {ground_motion.pga:.6g} mm/s^2 = {ground_motion.pga / G:.4g} g)"


def _check_state(state: FrameState, dt: float, steps: int, floors: int) -> int:
    """The step an analysis starts from ``state``, after checking that the state fits it."""
    if not isinstance(state, FrameState):
        raise ValueError(f"initial_state must be a FrameState (see SimulationResult.state_at), got "
                         f"{type(state).__name__}")
    if abs(state.dt - dt) > 1e-9 * dt:
        raise ValueError(f"initial_state was reached with dt = {state.dt!r} s, this analysis steps dt = {dt!r} s: "
                         "a fractional wall's memory is built for one step")
    if state.stories != floors:
        raise ValueError(f"initial_state holds {state.stories} stories, the building has {floors}")
    if state.step >= steps - 1:
        raise ValueError(f"initial_state is at step {state.step} (t = {state.time:.6g} s), at or past the last "
                         f"step of the record ({steps - 1}): nothing is left to integrate")
    return state.step


def _start_from(state: FrameState, frame: FrameArrays, stories: StoryArrays, walls: DeviceArrays,
                out: Histories, work: Scratch) -> None:
    """Row 0 of ``out`` at ``state``: the stories and walls committed through its drift history
    (:func:`~vdw_frames.frame.integrator.replay`), the floors' motion, and the energy the state holds.

    The energies of the new analysis count from the state: kinetic, recoverable and P-Delta energy are
    those of the state, the walls' work that of their history (their stored and dissipated energy), the
    dissipation of the stories and of the inherent damping starts at 0, and the input starts at their
    sum -- the balance closes from row 0 on.
    """
    wall_work = replay(np.ascontiguousarray(state.drift), state.dt, stories, walls, out, work)
    drift = state.drift[-1]
    out.displacement[0], out.velocity[0], out.acceleration[0], out.drift[0] = (
        state.displacement, state.velocity, state.acceleration, drift)
    kinetic = 0.5 * float(np.dot(frame.masses, state.velocity ** 2))
    recoverable = float(np.sum(0.5 * out.story_shear[0] ** 2 / stories.parameters[:, 0]))
    p_delta = float(np.sum(0.5 * frame.geometric * drift ** 2))
    out.energy[0, 1:] = (kinetic, recoverable, recoverable, 0.0, wall_work, p_delta)
    out.energy[0, 0] = kinetic + recoverable + wall_work + p_delta
    out.base_shear[0] = (out.story_shear[0, 0] + frame.geometric[0] * drift[0] + out.story_wall_force[0, 0]
                         + float(np.dot(frame.story_damping_row, state.velocity)))


def _warn_temperature_range(groups: Sequence[tuple[int, object]], bank: WallBank, dt: float) -> None:
    """One warning naming every wall group whose temperature left its shift law's range, and when."""
    first, temperature = bank.state("outside"), bank.state("temperature")
    low, high = bank.state("valid_low"), bank.state("valid_high")
    outside = [f"story {story} at t = {first[g] * dt:.4g} s ({temperature[g]:.1f} degC at the end; "
               f"range {low[g]:g} ... {high[g]:g} degC)" for g, (story, _) in enumerate(groups) if first[g] >= 0]
    if outside:
        _warnings.warn(TEMPERATURE_OUTSIDE + ": " + "; ".join(outside), UserWarning, stacklevel=4)




def is_strain_range_warning(message: str) -> bool:
    """Whether ``message`` is one of the warnings of walls outside the strains their parameters were
    identified for (peak strain of a fixed-parameter wall, or amplitude of an amplitude-following one)."""
    return PEAK_OUTSIDE in message or AMPLITUDE_OUTSIDE in message


def wall_model(wall: Wall | StrainDependentDamper) -> str:
    """A wall's model as the warnings name it: its class, and whether it follows its amplitude."""
    name = type(wall).__name__
    return f"{name}, amplitude followed" if wall.follows_amplitude else name


def peak_strain_warning(walls: Sequence[tuple[int, Wall | StrainDependentDamper]], peak_wall_strain: np.ndarray,
                        model: str | None = None) -> str | None:
    """The warning (None: none) for the walls whose peak strain (-, in ``walls`` order) lies above the range
    their parameters were identified at (``strain_range``), each named by story and model (``model``, or
    :func:`wall_model`).  For every wall model: the peak strain is what a test would have to reach, whatever
    amplitude the parameters follow.  A wall of fixed parameters whose peak stays below the range warns too
    (its parameters were identified at larger strains); an amplitude-following wall's time below the range is
    counted instead (``SimulationResult.wall_time_below_range``)."""
    outside = []
    for index, (story, wall) in enumerate(walls):
        strain_range = wall.strain_range
        if strain_range is None:
            continue
        low, high = strain_range
        peak = float(peak_wall_strain[index])
        if peak > high or (peak < low and not wall.follows_amplitude):
            outside.append(f"story {story}: {100 * peak:.0f} % (range {100 * low:.0f}-{100 * high:.0f} %), "
                           f"{model or wall_model(wall)}")
    return PEAK_OUTSIDE + "; ".join(dict.fromkeys(outside)) if outside else None


def _warn_strain_range(walls: Sequence[tuple[int, Wall]], peak_wall_strain: np.ndarray, above_seconds: np.ndarray,
                       peak_amplitude: np.ndarray | None) -> None:
    """Warn when a wall's peak strain lies beyond the range its parameters were identified for
    (:func:`peak_strain_warning`, every wall model), or an amplitude-following wall follows an amplitude above
    its identified ones, or never reaches them (its parameters are then those of the nearest end: an
    extrapolation).  The time an amplitude-following wall spends below the range as a record builds up and
    dies out is counted, not warned about (``result.wall_time_below_range``)."""
    beyond = []
    for index, (story, wall) in enumerate(walls):
        if wall.strain_range is None or not wall.follows_amplitude:
            continue
        low, high = wall.strain_range
        if peak_amplitude is None:  # pragma: no cover - amplitude-following walls are followed
            continue
        if above_seconds[index] > 0.0:
            beyond.append(f"story {story}: up to {100 * peak_amplitude[index]:.0f} % for "
                          f"{above_seconds[index]:.3g} s (range {100 * low:.0f}-{100 * high:.0f} %)")
        elif peak_amplitude[index] < low:
            beyond.append(f"story {story}: at most {100 * peak_amplitude[index]:.0f} %, below the range "
                          f"{100 * low:.0f}-{100 * high:.0f} % throughout")
    said = [peak_strain_warning(walls, peak_wall_strain)]
    if beyond:
        said.append(AMPLITUDE_OUTSIDE + " (those of the nearest are used): " + "; ".join(dict.fromkeys(beyond)))
    if any(said):  # one warning an analysis: batches count the analyses that warned (is_strain_range_warning)
        _warnings.warn(". ".join(text for text in said if text), UserWarning, stacklevel=4)
