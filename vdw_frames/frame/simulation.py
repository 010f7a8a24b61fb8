"""Seismic time-history analysis of a shear building with FDMK dampers (Newmark average acceleration).

Equation of motion, relative to the ground:  M u'' + C u' + K u + B^T f_d = -M 1 a_g,  with B the
drift operator (drift_k = u_k - u_{k-1}) and f_d the damper forces.  Newmark's method with
gamma = 1/2, beta = 1/4 (unconditionally stable, second order, no numerical damping).  Each damper is
advanced by the shared kernel of :mod:`vdw_frames.element.kernel` with the trial/commit contract: its history
force is evaluated from the committed memory, the new displacements are solved, the trial force is
evaluated at the new drift and committed.  The element is linear, so its tangent is constant and the
effective stiffness is factorised once; no iteration is needed.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from .._jit import njit

from ..element import kernel
from .._validation import positive, require_finite
from .building import ShearBuilding, story_matrix
from ..element.damper import DEFAULT_MEMORY, Memory
from ..element.fractional import DEFAULT_METHOD
from ..motion.record import GroundMotion


@njit(cache=True)
def _newmark(ground_acceleration, dt, masses, damping, stiffness, effective_inverse, damper_story,
             damper_constants, weights, past, mode_weight, mode_ratio, mode_state,
             displacement, velocity, acceleration, damper_force):
    """Average-acceleration Newmark steps 1 .. N-1 (step 0 is rest), filling the output arrays in place.

    damper_constants[d] = (G1, G2, eta1, eta2, area, thickness); damper_story[d] is 0-based.
    """
    steps, floors = displacement.shape
    dampers = damper_story.shape[0]
    history = np.empty((dampers, 2))
    story_force = np.zeros(floors)
    rhs = np.empty(floors)
    a0, a1, v1 = 4.0 / dt**2, 4.0 / dt, 2.0 / dt
    acceleration[0, :] = -ground_acceleration[0]
    for n in range(steps - 1):
        count = n + 1  # committed damper steps: 0 .. n
        u, v, a = displacement[n], velocity[n], acceleration[n]
        # The element's trial/commit contract, compiled: a trial at zero drift gives each damper's
        # history force (memory untouched); being linear, the rest is the constant tangent x drift,
        # already in the factorised effective stiffness.  A nonlinear frame would iterate trials here.
        story_force[:] = 0.0
        for d in range(dampers):
            G1, G2, eta1, eta2, area, thickness = damper_constants[d]
            history[d, 0], history[d, 1] = kernel.memory_history(
                weights[d], past[d], count, mode_weight[d], mode_state[d])
            stress, _, _ = kernel.fdmk_stress(0.0, history[d, 0], history[d, 1], G1, G2, eta1, eta2, weights[d, 0])
            story_force[damper_story[d]] += stress * area
        for i in range(floors):
            inertia = masses[i] * (a0 * u[i] + a1 * v[i] + a[i])
            viscous = 0.0
            for j in range(floors):
                viscous += damping[i, j] * (v1 * u[j] + v[j])
            # B^T f: a story force pushes its top floor back and its bottom floor forward.
            transmitted = story_force[i] - (story_force[i + 1] if i + 1 < floors else 0.0)
            rhs[i] = -masses[i] * ground_acceleration[n + 1] - transmitted + inertia + viscous
        new = displacement[n + 1]
        for i in range(floors):
            total = 0.0
            for j in range(floors):
                total += effective_inverse[i, j] * rhs[j]
            new[i] = total
        for d in range(dampers):
            G1, G2, eta1, eta2, area, thickness = damper_constants[d]
            s = damper_story[d]
            drift = new[s] - (new[s - 1] if s > 0 else 0.0)
            stress, maxwell, _ = kernel.fdmk_stress(drift / thickness, history[d, 0], history[d, 1],
                                                     G1, G2, eta1, eta2, weights[d, 0])
            damper_force[n + 1, d] = stress * area
            # Commit the accepted trial: only now does the memory advance.
            kernel.memory_push(past[d], count, mode_ratio[d], mode_state[d], drift / thickness, maxwell)
        for i in range(floors):
            increment = new[i] - u[i]
            velocity[n + 1, i] = v1 * increment - v[i]
            acceleration[n + 1, i] = a0 * increment - a1 * v[i] - a[i]


@dataclass(frozen=True)
class EnergyHistory:
    """Energy histories, N*mm, relative-motion formulation, trapezoidal work increments.

    ``input`` = -int (1^T M a_g) du; ``kinetic`` = v^T M v / 2; ``frame_strain`` = u^T K u / 2;
    ``inherent_damping`` = int (C v) . du; ``damper_work`` = int f_d . d(drift) (stored + dissipated).
    With Newmark's average acceleration these close to rounding: input = the sum of the other four.
    """

    input: np.ndarray
    kinetic: np.ndarray
    frame_strain: np.ndarray
    inherent_damping: np.ndarray
    damper_work: np.ndarray

    @property
    def balance_error(self) -> np.ndarray:
        """input - (kinetic + frame_strain + inherent_damping + damper_work), N*mm."""
        return self.input - (self.kinetic + self.frame_strain + self.inherent_damping + self.damper_work)


@dataclass(frozen=True)
class SimulationResult:
    """Response histories of :func:`simulate` (rows: time steps).

    time (s); displacement (mm), velocity (mm/s), acceleration (mm/s^2) relative to the ground, and
    absolute_acceleration (mm/s^2), each (steps, floors); drift (mm) and drift_ratio (-, None without
    story heights), (steps, stories); damper_force (N, total per story) and damper_strain (-, drift /
    thinnest wall's thickness; 0 where a story has no damper), (steps, stories); base_shear (N,
    = sum of floor masses x absolute accelerations, opposite sign: the shear the foundation takes);
    ground_acceleration (mm/s^2); energy (:class:`EnergyHistory`).
    """

    building: ShearBuilding
    time: np.ndarray
    ground_acceleration: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    absolute_acceleration: np.ndarray
    drift: np.ndarray
    drift_ratio: np.ndarray | None
    damper_force: np.ndarray
    damper_strain: np.ndarray
    base_shear: np.ndarray
    energy: EnergyHistory
    wall_force: np.ndarray  # (steps, dampers): each wall, in building.damper_list order

    @property
    def peak_drift(self) -> np.ndarray:
        """max |drift| per story, mm."""
        return np.abs(self.drift).max(axis=0)

    @property
    def peak_drift_ratio(self) -> np.ndarray | None:
        """max |drift ratio| per story (-), None without story heights."""
        return None if self.drift_ratio is None else np.abs(self.drift_ratio).max(axis=0)

    @property
    def peak_absolute_acceleration(self) -> np.ndarray:
        """max |absolute acceleration| per floor, mm/s^2."""
        return np.abs(self.absolute_acceleration).max(axis=0)

    @property
    def peak_base_shear(self) -> float:
        """max |base shear|, N."""
        return float(np.abs(self.base_shear).max())

    @property
    def peak_damper_force(self) -> np.ndarray:
        """max |total damper force| per story, N."""
        return np.abs(self.damper_force).max(axis=0)


def simulate(building: ShearBuilding, ground_motion, dt: float | None = None, method=DEFAULT_METHOD,
             memory=DEFAULT_MEMORY) -> SimulationResult:
    """Integrate ``building`` under ``ground_motion`` (a :class:`~vdw_frames.GroundMotion`, mm/s^2).

    ``dt`` (s) defaults to the record's step; a smaller step must divide it to a relative 1e-6 (the
    ground acceleration is interpolated linearly; the step used is the record step / the whole number of
    sub-steps, so a float32 dt works); a larger or non-dividing step, or one outside
    ``vdw_frames._validation.SIMULATION_STEP_RANGE`` (1e-9 ... 1e3 s), is a ValueError.  So is a run
    whose result arrays would exceed the 2 GiB memory limit, refused before allocating with its step
    count and memory.  ``method`` and ``memory`` (validated even for a frame without walls) select the
    dampers' discretisation and memory strategy ("fast", the default, costs the same at every step and
    stays within 3e-9 of "exact"; see :meth:`FDMKDamper.force`).  Warns (``UserWarning``) when a
    damper's peak strain leaves its ``strain_range``.  An overflowed response (absurd inputs) is a
    ValueError, never inf or NaN.  Returns a :class:`SimulationResult`.
    """
    from .._validation import SIMULATION_STEP_RANGE, check_memory, show
    from ..element.damper import memory_strategy
    from ..element.fractional import get_method

    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    if not isinstance(ground_motion, GroundMotion):
        raise ValueError(f"ground_motion must be a GroundMotion (see read_at2), got {type(ground_motion).__name__}")
    get_method(method)
    memory_strategy(memory)
    dt = positive("dt", ground_motion.dt if dt is None else dt)
    if not SIMULATION_STEP_RANGE[0] <= dt <= SIMULATION_STEP_RANGE[1]:
        raise ValueError(f"time step dt = {show(dt)} s is outside the range simulate accepts "
                         f"({SIMULATION_STEP_RANGE[0]:g} ... {SIMULATION_STEP_RANGE[1]:g} s)")
    substeps = ground_motion.substeps(dt)
    dt = ground_motion.dt / substeps
    # Result histories (about 12 per floor), wall forces and exact memories, energies: float64 a step.
    check_memory(f"simulate (dt = {dt!r} s, {building.stories} floors, {len(building.damper_list)} walls)",
                 (ground_motion.acceleration.size - 1) * substeps + 1,
                 8 * (12 * building.stories + 5 * len(building.damper_list) + 10), "use a larger dt")
    ground = ground_motion.acceleration_at(dt)
    steps, floors = ground.size, building.stories
    time = np.arange(steps) * dt

    # Identical walls on one story see the same drift: step each group once, with the summed area.
    walls = building.damper_list
    groups: dict[tuple, list[int]] = {}
    for index, (story, wall) in enumerate(walls):
        key = (story, wall.G1, wall.G2, wall.eta1, wall.eta2, wall.r, wall.thickness)
        groups.setdefault(key, []).append(index)
    members = list(groups.values())
    group_area = np.array([sum(walls[i][1].area for i in group) for group in members])
    representatives = [walls[group[0]] for group in members]
    memories = [Memory.allocate(wall, dt, steps, method, memory) for _, wall in representatives]
    stacked = _stack(memories)
    damper_story = np.array([story - 1 for story, _ in representatives], dtype=np.int64)
    constants = np.array([[w.G1, w.G2, w.eta1, w.eta2, area, w.thickness]
                          for (_, w), area in zip(representatives, group_area)]).reshape(-1, 6)

    tangent = np.zeros(floors)
    for (story, wall), area, mem in zip(representatives, group_area, memories):
        _, _, modulus = kernel.fdmk_stress(0.0, 0.0, 0.0, wall.G1, wall.G2, wall.eta1, wall.eta2, mem.weights[0])
        tangent[story - 1] += modulus * area / wall.thickness
    masses = np.asarray(building.masses)
    effective = (building.stiffness_matrix + story_matrix(tangent) + (4.0 / dt**2) * building.mass_matrix
                 + (2.0 / dt) * building.damping_matrix)

    displacement = np.zeros((steps, floors))
    velocity = np.zeros((steps, floors))
    acceleration = np.zeros((steps, floors))
    group_force = np.zeros((steps, len(members)))
    _newmark(ground, dt, masses, building.damping_matrix, building.stiffness_matrix, np.linalg.inv(effective),
             damper_story, constants, *stacked, displacement, velocity, acceleration, group_force)
    require_finite("the response", displacement)
    # Each wall carries its area's share of its group's force; stories sum their groups.
    share = np.zeros((len(members), len(walls)))
    to_story = np.zeros((len(members), floors))
    for g, group in enumerate(members):
        to_story[g, damper_story[g]] = 1.0
        for i in group:
            share[g, i] = walls[i][1].area / group_area[g]
    return _result(building, time, ground, displacement, velocity, acceleration,
                   group_force @ share, group_force @ to_story)


def _stack(memories):
    """Stack per-damper memories into (dampers, ...) arrays; modes padded with inert zeros."""
    if not memories:
        return (np.zeros((0, 1)), np.zeros((0, 1, 2)), np.zeros((0, 0)), np.zeros((0, 0)), np.zeros((0, 0, 2)))
    modes = max(m.mode_ratio.size for m in memories)
    weights = np.stack([m.weights for m in memories])
    past = np.stack([m.past for m in memories])
    mode_weight = np.zeros((len(memories), modes))
    mode_ratio = np.zeros((len(memories), modes))
    for d, m in enumerate(memories):
        mode_weight[d, : m.mode_weight.size] = m.mode_weight
        mode_ratio[d, : m.mode_ratio.size] = m.mode_ratio
    return weights, past, mode_weight, mode_ratio, np.zeros((len(memories), modes, 2))


def _result(building, time, ground, displacement, velocity, acceleration, wall_force, damper_force):
    floors = building.stories
    drift = np.diff(displacement, axis=1, prepend=0.0)
    heights = building.story_heights
    drift_ratio = None if heights is None else drift / np.asarray(heights)
    thinnest = np.full(floors, np.inf)
    for story, wall in building.damper_list:
        thinnest[story - 1] = min(thinnest[story - 1], wall.thickness)
    damper_strain = drift / thinnest
    masses = np.asarray(building.masses)
    absolute = acceleration + ground[:, None]
    base_shear = -(absolute @ masses)
    energy = _energy(building, ground, displacement, velocity, drift, damper_force)
    require_finite("the energy histories", np.concatenate([energy.input, energy.kinetic, energy.frame_strain,
                                                           energy.inherent_damping, energy.damper_work]))
    _warn_strain_range(building, np.abs(drift).max(axis=0))
    return SimulationResult(building, time, ground, displacement, velocity, acceleration, absolute, drift,
                            drift_ratio, damper_force, damper_strain, base_shear, energy, wall_force)


@njit(cache=True)
def _energy_histories(ground, masses, stiffness, damping, displacement, velocity, drift, damper_force):
    """One pass over the steps: (input, kinetic, frame strain, inherent damping, damper work), N*mm.

    Work terms use trapezoidal increments 0.5 (f_n + f_{n+1}) . (x_{n+1} - x_n), the rule under which
    Newmark's average acceleration conserves energy exactly.
    """
    steps, floors = displacement.shape
    energy = np.zeros((5, steps))
    damping_force = np.zeros((2, floors))
    for n in range(steps):
        now = n % 2
        kinetic = 0.0
        strain = 0.0
        for i in range(floors):
            kinetic += 0.5 * masses[i] * velocity[n, i] ** 2
            restoring = 0.0
            viscous = 0.0
            for j in range(floors):
                restoring += stiffness[i, j] * displacement[n, j]
                viscous += damping[i, j] * velocity[n, j]
            strain += 0.5 * displacement[n, i] * restoring
            damping_force[now, i] = viscous
        energy[1, n] = kinetic
        energy[2, n] = strain
        if n == 0:
            continue
        work_input = 0.0
        work_damping = 0.0
        work_damper = 0.0
        for i in range(floors):
            step = displacement[n, i] - displacement[n - 1, i]
            work_input -= 0.5 * masses[i] * (ground[n] + ground[n - 1]) * step
            work_damping += 0.5 * (damping_force[now, i] + damping_force[1 - now, i]) * step
            work_damper += 0.5 * (damper_force[n, i] + damper_force[n - 1, i]) * (drift[n, i] - drift[n - 1, i])
        energy[0, n] = energy[0, n - 1] + work_input
        energy[3, n] = energy[3, n - 1] + work_damping
        energy[4, n] = energy[4, n - 1] + work_damper
    return energy


def _energy(building, ground, displacement, velocity, drift, damper_force):
    energy = _energy_histories(ground, np.asarray(building.masses), building.stiffness_matrix,
                               building.damping_matrix, displacement, velocity, drift, damper_force)
    return EnergyHistory(*energy)


def _warn_strain_range(building, peak_drift):
    outside = []
    for story, wall in building.damper_list:
        if wall.strain_range is None:
            continue
        peak = peak_drift[story - 1] / wall.thickness
        low, high = wall.strain_range
        if not low <= peak <= high:
            outside.append(f"story {story}: {100 * peak:.0f} % (range {100 * low:.0f}-{100 * high:.0f} %)")
    if outside:
        from .._warnings import warn  # collected per task by run_batch (thread-safe)

        warn("damper peak strain outside the range its parameters were identified for: "
             + "; ".join(dict.fromkeys(outside)), UserWarning, stacklevel=4)
