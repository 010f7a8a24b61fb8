"""The compiled run of analyses: one analysis (a lane) step after step, and many lanes of one building in one
call, with what each lane records besides its histories (peaks, outcome, the walls' test demands).

:func:`run_lane` is the one compiled time loop: :func:`~vdw_frames.frame.time_history.time_history` (every
``simulate``) runs it on one lane of full histories, :func:`integrate_lanes` (the batches of
:mod:`vdw_frames.frame.lanes`) on every lane's views (:func:`take`), its histories in a ring of two rows when
only peaks are kept.  Its step is :func:`vdw_frames.frame.integrator.advance`, so a lane's results are those
of the single analysis to the bit, and the loop compiles once for both.

Units: N, mm, s, tonne; ground acceleration mm/s^2.
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np
from numba import types
from numba.extending import overload

from .._jit import njit
from .integrator import COLLAPSED, FAILED, FINISHED, STOPPED, DeviceArrays, Histories, advance, prepare


class LaneArrays(NamedTuple):
    """Every lane's state, each array stacked along a first axis of lanes (L)."""

    stories: Any  # StoryArrays, (L, n, ...)
    walls: DeviceArrays  # its arrays (L, ...); group_story and magnification too (the same in every lane)
    out: Histories  # (L, rows, ...): rows = 2 (a ring) for peaks only, else the longest record
    work: Any  # Scratch, (L, ...)


class LaneExcitation(NamedTuple):
    """Every lane's ground motion, padded with zeros to the longest record (L lanes, N values)."""

    acceleration: np.ndarray  # (L, N) mm/s^2
    lengths: np.ndarray  # (L,) int64: values of each lane's record (0: the lane is idle)
    dt: float  # s, the step of every lane
    first_step: int  # steps the walls committed before row 0 (0 from rest; a restart's state, simulate only)
    stop: np.ndarray  # (1,) int64, read every step: nonzero stops every lane (vdw_frames._parallel.stop_flag)


class LanePeaks(NamedTuple):
    """What every lane recorded besides histories (L lanes, n stories, G wall groups, D other devices)."""

    peak_drift: np.ndarray  # (L, n) mm, max |drift|
    peak_absolute_acceleration: np.ndarray  # (L, n) mm/s^2, max |relative + ground acceleration|
    peak_base_shear: np.ndarray  # (L,) N
    peak_story_wall_force: np.ndarray  # (L, n) N
    residual_drift: np.ndarray  # (L, n) mm, the drift of the last row filled
    peak_group_temperature: np.ndarray  # (L, G) degC (NaN without a thermal description or unfollowed)
    peak_group_amplitude: np.ndarray  # (L, G) -, the largest strain amplitude followed (0 where none is)
    peak_input: np.ndarray  # (L,) N*mm, max |input energy|
    peak_balance_error: np.ndarray  # (L,) N*mm, max |energy balance error| (EnergyHistory.balance_error)
    overflow: np.ndarray  # (L,) int64: 1 a displacement, 2 an energy not finite (simulate refuses either)
    peak_device_force: np.ndarray  # (L, D) N, max |force| along each other device
    peak_device_deformation: np.ndarray  # (L, D) mm
    peak_device_velocity: np.ndarray  # (L, D) mm/s
    outcome: np.ndarray  # (L, 4) int64: status, failed or collapsed story, Newton corrections, rows filled
    # Each wall's test demands (run_lanes(wall_demands=True); else W = 0 and none is followed), per wall of
    # building.wall_list, up to the row its group failed at (verification.verify.wall_peaks' definitions):
    wall_group: np.ndarray  # (W,) int64: the wall's group (constant)
    wall_thickness: np.ndarray  # (W,) mm (constant): deformation = strain x thickness
    wall_share: np.ndarray  # (W,) - (constant): force = the group's force x the wall's share of its area
    peak_wall_strain: np.ndarray  # (L, W) -, max |strain|
    peak_wall_deformation: np.ndarray  # (L, W) mm, max |deformation|
    peak_wall_velocity: np.ndarray  # (L, W) mm/s, max |numpy.gradient of the deformation|
    peak_wall_force: np.ndarray  # (L, W) N, max |force|
    wall_cycle_energy: np.ndarray  # (L, W) N*mm, the largest work between upward zero crossings (2 or more)
    wall_work: np.ndarray  # (L, W) N*mm, the trapezoidal work f d(deformation) so far
    # (L, W, 5): the deformation of the row before the last (mm) and of the last (mm), the force of the last (N),
    # the work at the last upward zero crossing (N*mm), the crossings so far (0, 1, or 2 for two or more)
    wall_trace: np.ndarray


def lane_peaks(lanes: int, floors: int, groups: int, devices: int,
               walls: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None) -> LanePeaks:
    """Zeroed :class:`LanePeaks` of ``lanes`` lanes, ``floors`` stories, ``groups`` wall groups and ``devices``
    other devices; ``walls``: the (group, thickness mm, share -) of each wall whose test demands are followed
    (None: none is).  A single analysis, which keeps its histories, takes one lane of nothing but its outcome
    (``lane_peaks(1, 0, 0, 0)``): every lane run compiles to the same code."""
    group, thickness, share = walls if walls is not None else (np.zeros(0, dtype=np.int64), np.zeros(0), np.zeros(0))
    followed = group.size
    return LanePeaks(np.zeros((lanes, floors)), np.zeros((lanes, floors)), np.zeros(lanes),
                     np.zeros((lanes, floors)), np.zeros((lanes, floors)), np.zeros((lanes, groups)),
                     np.zeros((lanes, groups)), np.zeros(lanes), np.zeros(lanes), np.zeros(lanes, dtype=np.int64),
                     np.zeros((lanes, devices)), np.zeros((lanes, devices)), np.zeros((lanes, devices)),
                     np.zeros((lanes, 4), dtype=np.int64),
                     wall_group=np.asarray(group, dtype=np.int64), wall_thickness=np.asarray(thickness, dtype=float),
                     wall_share=np.asarray(share, dtype=float),
                     **{name: np.zeros((lanes, followed)) for name in (
                         "peak_wall_strain", "peak_wall_deformation", "peak_wall_velocity", "peak_wall_force",
                         "wall_cycle_energy", "wall_work")},
                     wall_trace=np.zeros((lanes, followed, 5)))


WALL_CONSTANTS = ("wall_group", "wall_thickness", "wall_share")
"""The fields of :class:`LanePeaks` that describe the walls and stay through every batch (the others are reset)."""


# -------------------------------------------------------------------------------------------------- compiled
def take(tree, lane):  # pragma: no cover - compiled only (the overload below)
    """Lane ``lane``'s view of the named tuple ``tree``: each array indexed on its first axis, named tuples
    field by field, anything else (flags, counts, None) as it is."""


@overload(take)  # not inline="always": numba 0.6x's IR inlining of it lost writes through the views it made
def _take_typed(tree, lane):
    if isinstance(tree, types.BaseNamedTuple):
        named: Any = tree  # numba's type of the argument (its fields' types, its class)
        # Arrays indexed here, not through take: a function compiled without numba's runtime may return no
        # array it was not given (a named tuple of views is fine).
        fields = ", ".join(f"tree[{i}][lane]" if isinstance(kind, types.Array) else f"take(tree[{i}], lane)"
                           for i, kind in enumerate(named.types))
        scope: dict[str, Any] = {"build": named.instance_class, "take": take}
        exec(f"def view(tree, lane):\n    return build({fields})\n", scope)
        return scope["view"]
    return lambda tree, lane: tree


@njit(cache=True, inline="always")
def _note_peaks(lane, row, ground, out, peaks):
    """Lane ``lane``'s peaks with row ``row`` of its histories (ground acceleration ``ground``, mm/s^2)."""
    n = out.displacement.shape[1]
    for s in range(n):
        peaks.peak_drift[lane, s] = max(peaks.peak_drift[lane, s], abs(out.drift[row, s]))
        peaks.peak_absolute_acceleration[lane, s] = max(peaks.peak_absolute_acceleration[lane, s],
                                                     abs(out.acceleration[row, s] + ground))
        peaks.peak_story_wall_force[lane, s] = max(peaks.peak_story_wall_force[lane, s],
                                                   abs(out.story_wall_force[row, s]))
        peaks.residual_drift[lane, s] = out.drift[row, s]
    peaks.peak_base_shear[lane] = max(peaks.peak_base_shear[lane], abs(out.base_shear[row]))
    if out.group_temperature.shape[0] > 0:
        for g in range(out.group_temperature.shape[1]):
            value = out.group_temperature[row, g]
            if not peaks.peak_group_temperature[lane, g] >= value:  # NaN (not followed) stays NaN
                peaks.peak_group_temperature[lane, g] = value
    if out.group_amplitude.shape[0] > 0:
        for g in range(out.group_amplitude.shape[1]):
            peaks.peak_group_amplitude[lane, g] = max(peaks.peak_group_amplitude[lane, g], out.group_amplitude[row, g])
    for s in range(n):
        if not math.isfinite(out.displacement[row, s]):
            peaks.overflow[lane] |= 1
    energy = out.energy
    for column in range(energy.shape[1]):
        if not math.isfinite(energy[row, column]):
            peaks.overflow[lane] |= 2
    # EnergyHistory.balance_error, term by term in its order (hysteretic = strain work - frame strain first)
    error = energy[row, 0] - (energy[row, 1] + energy[row, 2] + (energy[row, 3] - energy[row, 2]) + energy[row, 4]
                              + energy[row, 5] + energy[row, 6])
    peaks.peak_input[lane] = max(peaks.peak_input[lane], abs(energy[row, 0]))
    peaks.peak_balance_error[lane] = max(peaks.peak_balance_error[lane], abs(error))
    for d in range(out.device_force.shape[1]):
        peaks.peak_device_force[lane, d] = max(peaks.peak_device_force[lane, d], abs(out.device_force[row, d]))
        peaks.peak_device_deformation[lane, d] = max(peaks.peak_device_deformation[lane, d],
                                                  abs(out.device_deformation[row, d]))
        peaks.peak_device_velocity[lane, d] = max(peaks.peak_device_velocity[lane, d], abs(out.device_velocity[row, d]))


@njit(cache=True, inline="always")
def _note_walls(lane, k, row, dt, out, walls, peaks):
    """Lane ``lane``'s wall demands with row ``row`` of its histories, row ``k`` from rest (dt s), as
    :func:`vdw_frames.verification.verify.wall_peaks` takes them from the whole histories, in the same
    operations: each wall's deformation strain x thickness and force its group's x its share; its rows up to
    the one its group failed at (``walls``: the lane's bank, whose failure step is set at the failing commit);
    the trapezoidal work 0.5 (f_k + f_k-1) (d_k - d_k-1) summed in order (``numpy.cumsum``), its cycles between
    upward zero crossings (d_k-1 < 0 <= d_k); the velocity of row k - 1 by ``numpy.gradient``'s differences
    (central, one-sided at row 0; that of the last row: :func:`_finish_walls`)."""
    states = walls.bank.states.walls
    trace = peaks.wall_trace
    for w in range(peaks.wall_group.shape[0]):
        group = peaks.wall_group[w]
        failed_at = states[group].limits.failure_step  # -1: standing
        strain = out.group_strain[row, group]
        deformation = strain * peaks.wall_thickness[w]
        force = out.group_force[row, group] * peaks.wall_share[w]
        if k > 0 and (failed_at < 0.0 or k - 1 <= failed_at):
            if k == 1:
                velocity = (deformation - trace[lane, w, 1]) / dt
            else:
                velocity = (deformation - trace[lane, w, 0]) / (2.0 * dt)
            peaks.peak_wall_velocity[lane, w] = max(peaks.peak_wall_velocity[lane, w], abs(velocity))
        if failed_at < 0.0 or k <= failed_at:
            peaks.peak_wall_strain[lane, w] = max(peaks.peak_wall_strain[lane, w], abs(strain))
            peaks.peak_wall_deformation[lane, w] = max(peaks.peak_wall_deformation[lane, w], abs(deformation))
            peaks.peak_wall_force[lane, w] = max(peaks.peak_wall_force[lane, w], abs(force))
            if k > 0:
                previous = trace[lane, w, 1]
                work = peaks.wall_work[lane, w] + 0.5 * (force + trace[lane, w, 2]) * (deformation - previous)
                peaks.wall_work[lane, w] = work
                if previous < 0.0 and deformation >= 0.0:
                    if trace[lane, w, 4] > 0.0:
                        cycle = work - trace[lane, w, 3]
                        if trace[lane, w, 4] < 2.0 or cycle > peaks.wall_cycle_energy[lane, w]:
                            peaks.wall_cycle_energy[lane, w] = cycle
                        trace[lane, w, 4] = 2.0
                    else:
                        trace[lane, w, 4] = 1.0
                    trace[lane, w, 3] = work
        trace[lane, w, 0] = trace[lane, w, 1] if k > 0 else deformation
        trace[lane, w, 1] = deformation
        trace[lane, w, 2] = force


@njit(cache=True, inline="always")
def _finish_walls(lane, rows, dt, walls, peaks):
    """The velocity of the last of lane ``lane``'s ``rows`` rows (``numpy.gradient``'s one-sided difference at
    the end; none for a single row), for the walls standing then."""
    if rows < 2:
        return
    states = walls.bank.states.walls
    trace = peaks.wall_trace
    for w in range(peaks.wall_group.shape[0]):
        failed_at = states[peaks.wall_group[w]].limits.failure_step
        if failed_at < 0.0 or rows - 1 <= failed_at:
            velocity = (trace[lane, w, 1] - trace[lane, w, 0]) / dt
            peaks.peak_wall_velocity[lane, w] = max(peaks.peak_wall_velocity[lane, w], abs(velocity))


@njit(cache=True, allocates=False)
def integrate_lanes(excitation, frame, lanes, newton, peaks):
    """Every lane's analysis from rest, in place: lane under ``excitation`` (:class:`LaneExcitation`: ground
    acceleration ``acceleration[lane, :lengths[lane]]`` mm/s^2, a lane of length 0 idle; the step dt s), of the
    building ``frame`` (:class:`FrameArrays`, the same for every lane), with the states ``lanes``
    (:class:`LaneArrays` at rest, row 0 of the histories holding the state at rest) and the settings
    ``newton``; ``peaks`` (:class:`LanePeaks`, zeroed, the temperatures at rest) receive each lane's peaks and
    outcome.  Each lane is :func:`run_lane` on the lane's views (:func:`take`)."""
    for lane in range(excitation.acceleration.shape[0]):
        if excitation.lengths[lane] > 0:
            run_lane(lane, excitation, frame, take(lanes.stories, lane), take(lanes.walls, lane),
                     take(lanes.out, lane), take(lanes.work, lane), newton, peaks)


@njit(cache=True, allocates=False)
def run_lane(lane, excitation, frame, stories, walls, out, work, newton, peaks):
    """Lane ``lane``'s analysis, in place: :func:`~vdw_frames.frame.integrator.advance` step after step from the
    state in row 0 of ``out`` (rest, or a state :func:`~vdw_frames.frame.integrator.replay` brought the stories
    and walls to: ``excitation.first_step`` steps of the walls' memory), its rows in a ring when ``out`` holds
    fewer rows than the record.  ``excitation`` :class:`LaneExcitation`; ``frame`` :class:`FrameArrays`;
    ``stories``, ``walls`` (:class:`DeviceArrays`), ``out`` (:class:`Histories`), ``work`` (:class:`Scratch`):
    the lane's (views of a batch's arrays, or a single analysis's); ``newton`` :class:`NewtonSettings`;
    ``peaks`` follow the lane's peaks (:func:`_note_peaks`, :func:`_note_walls`) unless they hold no story (a
    single analysis's, ``lane_peaks(1, 0, 0, 0)``: it keeps its histories instead); ``peaks.outcome[lane]``
    receives (status, failed or collapsed story, Newton corrections, rows filled); a nonzero ``excitation.stop[0]``
    (a cancelled fan-out's: another task failed) ends the lane before its next step, STOPPED.  (Called once a lane, not
    inlined: numba's inlining of the step into the loop that takes the views lost the writes of :func:`prepare`,
    numba 0.6x.)"""
    ground, dt, start = excitation.acceleration, excitation.dt, excitation.first_step
    steps = excitation.lengths[lane]
    rows = out.displacement.shape[0]
    note = peaks.peak_drift.shape[1] > 0
    prepare(dt, 0, frame, stories, out, work)
    if note:
        _note_peaks(lane, 0, ground[lane, 0], out, peaks)
        _note_walls(lane, 0, 0, dt, out, walls, peaks)
    total = 0
    status, story, filled = FINISHED, 0, steps
    for step in range(steps - 1):
        if excitation.stop[0] != 0:
            status, filled = STOPPED, step + 1
            break
        row, next_row = step % rows, (step + 1) % rows
        status, story, iterations = advance(step, row, next_row, ground[lane, step], ground[lane, step + 1], dt,
                                            start, frame, stories, walls, newton, out, work)
        total += iterations
        if status == FAILED:
            filled = step + 1
            break
        if note:
            _note_peaks(lane, next_row, ground[lane, step + 1], out, peaks)
            _note_walls(lane, step + 1, next_row, dt, out, walls, peaks)
        if status == COLLAPSED:
            filled = step + 2
            break
    if status not in (FAILED, COLLAPSED, STOPPED):
        status, story = FINISHED, 0
    if note:
        _finish_walls(lane, filled, dt, walls, peaks)
    outcome = peaks.outcome
    outcome[lane, 0], outcome[lane, 1], outcome[lane, 2], outcome[lane, 3] = status, story, total, filled
