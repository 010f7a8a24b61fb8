"""Seismic time-history analysis of a shear building with FDMK walls: Newmark average acceleration with
Newton-Raphson iterations through the walls' and the stories' trial/commit.

Equation of motion, relative to the ground, at every step n+1:

    M u'' + C u' + B^T [ f_s(d) + k_G d + f_w(d) ] = -M 1 a_g,        d = B u (story drifts),

with f_s the story springs (:mod:`vdw_frames.frame.hysteresis`; linear, Bilinear or Bouc-Wen), k_G = -P/h
the P-Delta stiffness, f_w the walls and C the inherent damping.  Newmark's method with gamma = 1/2,
beta = 1/4 (unconditionally stable for linear systems, second order, no numerical damping).

Per step (the trial/commit contract of OpenSees's ``UniaxialMaterial``, compiled):

1. walls: their history is evaluated once from the committed memory (:func:`kernel.bank_affine`); within
   the step a wall's trial force is exactly K_t d + H_n (the element is linear), K_t constant;
2. Newton-Raphson on the unbalanced force R(u) with the consistent tangent
   K_T = (4/dt^2) M + (2/dt) C + B^T diag(k_s + k_G + K_t) B, each story's force and tangent from its
   model's trial at the current drift (state untouched); the building's tangent is tridiagonal with
   Rayleigh damping (solved in O(n)) and dense with modal damping.  Converged when
   ||R||_inf <= ``force_tolerance`` x the step's largest force term and either ||du||_inf <=
   ``displacement_tolerance`` (mm) or no story's tangent changed since the last correction (that
   correction then solved the piecewise-linear model exactly: a Bilinear step that stays on its branches
   takes one solve); see :class:`NewtonRaphson`.  A linear building takes exactly one solve a step;
3. on convergence the stories and the walls commit (the walls' memory advances only now);
4. when Newton fails, the same step is retried, at the same dt (the walls' memory is built for one
   dt: never sub-step), with a backtracking line search, then with initial-stiffness iterations; if
   those fail too, the analysis stops, reports ``converged = False`` and warns with the time and story.

Energies (N*mm) are accumulated in the same pass with trapezoidal work increments, the rule under which
average acceleration balances energy to the iteration tolerance.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from .._jit import njit
from .. import _warnings
from .._validation import (SIMULATION_STEP_RANGE, check_memory, non_negative, positive,
                           require_finite, show, whole_number)
from ..element import kernel
from ..element.bank import DEFAULT_MEMORY, WallBank, kernel_constants, memory_strategy
from ..element.fractional import DEFAULT_METHOD, get_method
from ..motion.record import GroundMotion
from .building import ShearBuilding, require_fixed_walls
from .hysteresis import LINEAR, PARAMETERS, STATE, story_trial

# Status codes of the compiled integrator.
_RUNNING, _FINISHED, _COLLAPSED, _FAILED = 0, 1, 2, 3
# Energy columns: input, kinetic, frame strain (recoverable), story work, inherent damping, wall work, P-Delta.
_ENERGIES = 7
# Solution strategies tried in turn on a step: Newton, Newton with line search, initial stiffness.
_NEWTON, _LINE_SEARCH, _INITIAL = 0, 1, 2
# Self-check: Newmark's average acceleration with trapezoidal work increments balances energy to the Newton
# tolerance (1e-13 ... 1e-9 of the input in the tests); a larger gap means the wrong equations were solved.
ENERGY_BALANCE_TOLERANCE = 1e-4


@dataclass(frozen=True)
class NewtonRaphson:
    """Convergence settings of the inelastic integration (all per time step).

    ``force_tolerance`` (-): bound on ||R||_inf relative to the step's largest force term (inertia,
    damping, story, P-Delta or wall force of any floor, at least 1 N); required for convergence.
    ``displacement_tolerance`` (mm): bound on ||du||_inf, the last Newton correction; required too,
    unless no story's tangent changed since that correction (it then solved the model exactly).
    ``max_iterations``: Newton iterations before the fallbacks (line search, then initial stiffness with
    ``fallback_iterations``) are tried at the same dt.
    """

    displacement_tolerance: float = 1e-8
    force_tolerance: float = 1e-9
    max_iterations: int = 25
    fallback_iterations: int = 200

    def __post_init__(self):
        object.__setattr__(self, "displacement_tolerance", positive("displacement_tolerance", self.displacement_tolerance))
        object.__setattr__(self, "force_tolerance", positive("force_tolerance", self.force_tolerance))
        object.__setattr__(self, "max_iterations", whole_number("max_iterations", self.max_iterations, 1))
        object.__setattr__(self, "fallback_iterations", whole_number("fallback_iterations", self.fallback_iterations, 1))


# ---------------------------------------------------------------------------------------------- compiled
@njit(cache=True, inline="always")
def _story_state(kinds, parameters, committed, drift, force, tangent, trial_state):
    """Every story's trial: force and tangent at ``drift``, the state value to commit."""
    for s in range(drift.shape[0]):
        force[s], tangent[s], trial_state[s] = story_trial(
            kinds[s], parameters[s, 0], parameters[s, 1], parameters[s, 2], parameters[s, 3], parameters[s, 4],
            parameters[s, 5], committed[s, 0], committed[s, 1], drift[s])


@njit(cache=True, inline="always")
def _residual(u, u_n, v_n, a_n, ground, dt, masses, damping, tridiagonal, kinds, parameters, committed,
              geometric, wall_tangent, wall_history, drift, story_force, story_tangent, trial_state,
              story_total, damping_force, residual):
    """Unbalanced force R = -M a_g - (M a + C v + B^T f)(u) at trial displacements u; returns the force scale.

    Fills the drifts, the stories' trial forces/tangents/states, the total story forces (spring +
    P-Delta + walls) and the damping forces C v.
    """
    n = u.shape[0]
    a0, v1 = 4.0 / dt**2, 2.0 / dt
    for s in range(n):
        drift[s] = u[s] - (u[s - 1] if s > 0 else 0.0)
    _story_state(kinds, parameters, committed, drift, story_force, story_tangent, trial_state)
    for s in range(n):
        story_total[s] = story_force[s] + geometric[s] * drift[s] + wall_tangent[s] * drift[s] + wall_history[s]
    scale = 1.0
    for i in range(n):
        increment = u[i] - u_n[i]
        inertia = masses[i] * (a0 * increment - (4.0 / dt) * v_n[i] - a_n[i])
        viscous = 0.0
        if tridiagonal:
            for j in range(max(i - 1, 0), min(i + 2, n)):
                viscous += damping[i, j] * (v1 * (u[j] - u_n[j]) - v_n[j])
        else:
            for j in range(n):
                viscous += damping[i, j] * (v1 * (u[j] - u_n[j]) - v_n[j])
        damping_force[i] = viscous
        above = story_total[i + 1] if i + 1 < n else 0.0
        external = masses[i] * ground
        residual[i] = -external - inertia - viscous - (story_total[i] - above)
        # The residual's round-off is relative to its largest terms, including the inertia terms before
        # they cancel (m a0 |u| for the increment u - u_n): the force tolerance is relative to them all.
        inertia_terms = masses[i] * (a0 * abs(u[i]) + (4.0 / dt) * abs(v_n[i]) + abs(a_n[i]))
        scale = max(scale, abs(external), inertia_terms, abs(viscous), abs(story_force[i]), abs(story_total[i]))
    return scale


@njit(cache=True, inline="always")
def _largest(values):
    """max |value| (a NaN anywhere gives NaN: it must fail the step, not vanish as numba's max would)."""
    largest = 0.0
    for value in values:
        if not abs(value) <= largest:
            largest = abs(value)
    return largest


@njit(cache=True, inline="always")
def _solve(stiffness_diagonal, masses, damping, tridiagonal, dt, rhs, work, matrix, out):
    """Solve ((4/dt^2) M + (2/dt) C + B^T diag(k) B) x = rhs; Thomas algorithm when tridiagonal, else LU."""
    n = rhs.shape[0]
    a0, v1 = 4.0 / dt**2, 2.0 / dt
    if tridiagonal:
        # diagonal in work[0], super-diagonal in work[1]
        for i in range(n):
            above = stiffness_diagonal[i + 1] if i + 1 < n else 0.0
            work[0, i] = a0 * masses[i] + v1 * damping[i, i] + stiffness_diagonal[i] + above
            work[1, i] = (v1 * damping[i, i + 1] - stiffness_diagonal[i + 1]) if i + 1 < n else 0.0
        # forward elimination (symmetric tridiagonal), in place
        out[0] = rhs[0]
        for i in range(1, n):
            factor = work[1, i - 1] / work[0, i - 1]
            work[0, i] -= factor * work[1, i - 1]
            out[i] = rhs[i] - factor * out[i - 1]
        out[n - 1] /= work[0, n - 1]
        for i in range(n - 2, -1, -1):
            out[i] = (out[i] - work[1, i] * out[i + 1]) / work[0, i]
        return
    # Every row's damping first: the stiffness couples row i to i + 1, which a later row must not overwrite.
    for i in range(n):
        for j in range(n):
            matrix[i, j] = v1 * damping[i, j]
        out[i] = rhs[i]
    for i in range(n):
        matrix[i, i] += a0 * masses[i] + stiffness_diagonal[i] + (stiffness_diagonal[i + 1] if i + 1 < n else 0.0)
        if i + 1 < n:
            matrix[i, i + 1] -= stiffness_diagonal[i + 1]
            matrix[i + 1, i] -= stiffness_diagonal[i + 1]
    # Gaussian elimination with partial pivoting
    for k in range(n):
        pivot = k
        for i in range(k + 1, n):
            if abs(matrix[i, k]) > abs(matrix[pivot, k]):
                pivot = i
        if pivot != k:
            for j in range(n):
                matrix[k, j], matrix[pivot, j] = matrix[pivot, j], matrix[k, j]
            out[k], out[pivot] = out[pivot], out[k]
        for i in range(k + 1, n):
            factor = matrix[i, k] / matrix[k, k]
            for j in range(k, n):
                matrix[i, j] -= factor * matrix[k, j]
            out[i] -= factor * out[k]
    for i in range(n - 1, -1, -1):
        total = out[i]
        for j in range(i + 1, n):
            total -= matrix[i, j] * out[j]
        out[i] = total / matrix[i, i]


@njit(cache=True)
def _integrate(ground, dt, masses, damping, story_damping_row, tridiagonal, kinds, parameters, committed, geometric,
               heights, collapse_ratio, linear, displacement_tolerance, force_tolerance, max_iterations,
               fallback_iterations, group_story, constants, w0, window_weights, window, mode_weight,
               mode_ratio, mode_state, history, values, wall_tangent_group, wall_history_group,
               displacement, velocity, acceleration, drift_out, story_shear, damper_force, base_shear,
               group_force, group_strain, peak_group_strain, energy, outcome):
    """Newmark average acceleration with Newton-Raphson, steps 1 .. N-1 (step 0 is rest), in place.

    Returns the number of steps filled; ``outcome`` receives (status, failed story, iterations used).
    """
    steps, n = displacement.shape
    groups = group_story.shape[0]
    a0, v1 = 4.0 / dt**2, 2.0 / dt
    initial_stiffness = np.empty(n)
    for s in range(n):
        initial_stiffness[s] = parameters[s, 0] + geometric[s]
    drift = np.zeros(n)
    story_force = np.zeros(n)
    story_tangent = np.zeros(n)
    trial_state = np.zeros(n)
    story_total = np.zeros(n)
    residual = np.zeros(n)
    correction = np.zeros(n)
    trial = np.zeros(n)
    stiffness_diagonal = np.zeros(n)
    work = np.zeros((2, n))
    matrix = np.zeros((n, n))
    wall_tangent = np.zeros(n)
    wall_history = np.zeros(n)
    wall_deformation = np.zeros(groups)
    force_out = np.zeros(groups)
    strain_out = np.zeros(groups)
    damping_force = np.zeros(n)
    old_damping_force = np.zeros(n)
    for i in range(n):  # (loops, not slice assignments: those compile numba's shape-error machinery)
        acceleration[0, i] = -ground[0]
        energy[0, 1] += 0.5 * masses[i] * velocity[0, i] ** 2
    total_iterations = 0
    for step in range(steps - 1):
        u_n, v_n, a_n = displacement[step], velocity[step], acceleration[step]
        # 1. walls: their history for this step came with the last commit; their trial force is K_t d + H_n
        for s in range(n):
            wall_tangent[s] = 0.0
            wall_history[s] = 0.0
        for g in range(groups):
            wall_tangent[group_story[g]] += wall_tangent_group[g]
            wall_history[group_story[g]] += wall_history_group[g]
        # 2. Newton-Raphson from u_n; strategies in turn, each from u_n again
        u = displacement[step + 1]
        converged = False
        for strategy in range(3):
            if linear and strategy > 0:
                break
            for i in range(n):
                u[i] = u_n[i]
            limit = max_iterations if strategy < _INITIAL else fallback_iterations
            if linear:
                limit = 1
            last_correction = np.inf
            exact_solve = False  # the last correction solved the model itself (no tangent changed since)
            for iteration in range(limit + 1):
                scale = _residual(u, u_n, v_n, a_n, ground[step + 1], dt, masses, damping, tridiagonal, kinds,
                                  parameters, committed, geometric, wall_tangent, wall_history, drift,
                                  story_force, story_tangent, trial_state, story_total, damping_force, residual)
                norm = _largest(residual)
                if exact_solve:
                    for s in range(n):
                        if story_tangent[s] + geometric[s] + wall_tangent[s] != stiffness_diagonal[s]:
                            exact_solve = False
                            break
                if iteration > 0 and (linear or (norm <= force_tolerance * scale
                                                 and (exact_solve or last_correction <= displacement_tolerance))):
                    converged = True
                    break
                if iteration == limit or not math.isfinite(norm):
                    break
                for s in range(n):
                    if strategy == _INITIAL:
                        stiffness_diagonal[s] = initial_stiffness[s] + wall_tangent[s]
                    else:
                        stiffness_diagonal[s] = story_tangent[s] + geometric[s] + wall_tangent[s]
                _solve(stiffness_diagonal, masses, damping, tridiagonal, dt, residual, work, matrix, correction)
                total_iterations += 1
                step_length = 1.0
                if strategy == _LINE_SEARCH:
                    # Backtrack until the unbalanced force drops (at most 8 halvings).
                    for _ in range(8):
                        for i in range(n):
                            trial[i] = u[i] + step_length * correction[i]
                        _residual(trial, u_n, v_n, a_n, ground[step + 1], dt, masses, damping, tridiagonal,
                                  kinds, parameters, committed, geometric, wall_tangent, wall_history, drift,
                                  story_force, story_tangent, trial_state, story_total, damping_force, residual)
                        if _largest(residual) < norm:
                            break
                        step_length *= 0.5  # (after 8 halvings the 1/256 step is taken; the next residual judges it)
                exact_solve = strategy != _INITIAL and step_length == 1.0
                last_correction = step_length * _largest(correction)
                for i in range(n):
                    u[i] += step_length * correction[i]
            if converged:
                break
        if not converged:
            failed_story, largest = 0, 0.0  # the story the last correction moved most
            for s in range(n):
                story_drift = abs(correction[s] - (correction[s - 1] if s > 0 else 0.0))
                if story_drift > largest:
                    failed_story, largest = s, story_drift
            outcome[0], outcome[1], outcome[2] = _FAILED, failed_story, total_iterations
            return step + 1
        # 3. commit: stories, then the walls with their drifts (memory advances only now)
        for s in range(n):
            committed[s, 0] = drift[s]
            committed[s, 1] = trial_state[s]
        for g in range(groups):
            wall_deformation[g] = drift[group_story[g]]
        kernel.bank_commit(constants, w0, window_weights, window, step, mode_weight, mode_ratio, mode_state,
                           history, values, wall_deformation, force_out, strain_out, wall_tangent_group,
                           wall_history_group)
        for g in range(groups):
            group_force[step + 1, g] = force_out[g]
            group_strain[step + 1, g] = strain_out[g]
            peak_group_strain[g] = max(peak_group_strain[g], abs(strain_out[g]))
        for i in range(n):
            increment = u[i] - u_n[i]
            velocity[step + 1, i] = v1 * increment - v_n[i]
            acceleration[step + 1, i] = a0 * increment - (4.0 / dt) * v_n[i] - a_n[i]
        # outputs and energies (trapezoidal work increments)
        kinetic = 0.0
        recoverable = 0.0
        input_work = 0.0
        story_work = 0.0
        damping_work = 0.0
        wall_work = 0.0
        geometric_work = 0.0
        story1_damping = 0.0  # the damping force through story 1: 1^T C_s v
        for i in range(n):
            story1_damping += story_damping_row[i] * velocity[step + 1, i]
        for s in range(n):  # (row ``step`` of the outputs holds the previous step's values; row 0 is rest)
            wall_force = story_total[s] - story_force[s] - geometric[s] * drift[s]
            change = drift[s] - drift_out[step, s]
            story_work += 0.5 * (story_force[s] + story_shear[step, s]) * change
            wall_work += 0.5 * (wall_force + damper_force[step, s]) * change
            geometric_work += 0.5 * geometric[s] * (drift[s] + drift_out[step, s]) * change
            recoverable += 0.5 * story_force[s] ** 2 / parameters[s, 0]
            story_shear[step + 1, s] = story_force[s]
            damper_force[step + 1, s] = wall_force
            drift_out[step + 1, s] = drift[s]
        for i in range(n):
            change = u[i] - u_n[i]
            kinetic += 0.5 * masses[i] * velocity[step + 1, i] ** 2
            input_work -= 0.5 * masses[i] * (ground[step + 1] + ground[step]) * change
            damping_work += 0.5 * (damping_force[i] + old_damping_force[i]) * change
            old_damping_force[i] = damping_force[i]
        base_shear[step + 1] = story_total[0] + story1_damping
        energy[step + 1, 0] = energy[step, 0] + input_work
        energy[step + 1, 1] = kinetic
        energy[step + 1, 2] = recoverable
        energy[step + 1, 3] = energy[step, 3] + story_work
        energy[step + 1, 4] = energy[step, 4] + damping_work
        energy[step + 1, 5] = energy[step, 5] + wall_work
        energy[step + 1, 6] = energy[step, 6] + geometric_work
        # 4. collapse
        if collapse_ratio > 0.0:
            for s in range(n):
                if abs(drift[s]) > collapse_ratio * heights[s]:
                    outcome[0], outcome[1], outcome[2] = _COLLAPSED, s, total_iterations
                    return step + 2
    outcome[0], outcome[1], outcome[2] = _FINISHED, 0, total_iterations
    return steps


# ---------------------------------------------------------------------------------------------- results
@dataclass(frozen=True)
class EnergyHistory:
    """Energy histories, N*mm, relative-motion formulation, trapezoidal work increments.

    ``input`` = -int (1^T M a_g) du; ``kinetic`` = v^T M v / 2; ``frame_strain`` = sum F_s^2 / (2 k0), the
    recoverable elastic energy of the story springs; ``hysteretic`` = int F_s dd - frame_strain, the energy
    the story springs have dissipated by yielding (and, with kinematic hardening, stored in their
    hardening); ``inherent_damping`` = int (C v) . du; ``damper_work`` = int f_w . dd (the walls: stored and
    dissipated); ``p_delta`` = int k_G d dd = -sum P d^2 / (2 h) (<= 0: gravity does work as the frame
    sways).  With Newmark's average acceleration they balance to the iteration tolerance:
    input = kinetic + frame_strain + hysteretic + inherent_damping + damper_work + p_delta.
    """

    input: np.ndarray
    kinetic: np.ndarray
    frame_strain: np.ndarray
    hysteretic: np.ndarray
    inherent_damping: np.ndarray
    damper_work: np.ndarray
    p_delta: np.ndarray

    @property
    def balance_error(self) -> np.ndarray:
        """input - (kinetic + frame_strain + hysteretic + inherent_damping + damper_work + p_delta), N*mm."""
        return self.input - (self.kinetic + self.frame_strain + self.hysteretic + self.inherent_damping
                             + self.damper_work + self.p_delta)


@dataclass(frozen=True)
class SimulationResult:
    """Response histories of :func:`simulate` (rows: time steps; they end where the analysis stopped).

    time (s); displacement (mm), velocity (mm/s), acceleration (mm/s^2) relative to the ground, and
    absolute_acceleration (mm/s^2), each (steps, floors); drift (mm) and drift_ratio (-, None without
    story heights), (steps, stories); story_shear (N, the force in each story's frame spring only,
    (steps, stories)); damper_force (N, total of the walls of each story, (steps, stories)) and
    damper_strain (-, the strain of each story's most strained wall group, 0 where a story has no
    wall); wall_force (N) and wall_strain (-, the wall's own deformation / thickness: with a support
    in series it is not drift / thickness), (steps, walls) in ``building.damper_list`` order;
    base_shear (N): the force transmitted through story 1 -- its frame spring, walls, P-Delta force
    and inherent damping force through the story (a1 k1 v1 with Rayleigh damping: the mass-proportional
    term acts between the floors and the ground) -- the horizontal reaction of the ground (with P-Delta
    it is less than the story-1 frame and wall shears, story_shear + damper_force, which are what the
    structure must resist); ground_acceleration (mm/s^2); energy (:class:`EnergyHistory`).  absolute_acceleration, drift_ratio,
    damper_strain, wall_force and wall_strain are computed on first use (from the stored histories and
    the wall groups: identical walls of a story are stepped once, as one of their summed area).

    ``converged``: False when a step failed to converge (the histories end at the last converged step);
    ``collapsed`` and ``collapse_time`` (s): a story's drift ratio exceeded ``collapse_drift_ratio``
    (the histories end at that step); ``newton_iterations``: the total number of Newton corrections.

    Strain-compatible analyses (``simulate(..., strain_compatible=True)``) also report, per wall in
    ``building.damper_list`` order, ``wall_effective_strain`` (-, the final effective strains) and
    ``wall_dampers`` (the FDMKDamper each wall ended with), with ``strain_iterations`` and
    ``strain_converged``; ``building`` is then the equivalent-linear building.  None otherwise.
    """

    building: ShearBuilding
    time: np.ndarray
    ground_acceleration: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    drift: np.ndarray
    story_shear: np.ndarray
    damper_force: np.ndarray
    base_shear: np.ndarray
    energy: EnergyHistory
    # Walls stepped together (identical walls of a story: one group of their summed area); the per-wall and
    # derived histories are computed from these on first use, not stored by every analysis.
    group_force: np.ndarray = field(repr=False)  # (steps, groups), N
    group_strain: np.ndarray = field(repr=False)  # (steps, groups), -
    wall_group: np.ndarray = field(repr=False)  # (walls,): the group of each wall of building.damper_list
    wall_share: np.ndarray = field(repr=False)  # (walls,): each wall's share of its group's area
    converged: bool = True
    collapsed: bool = False
    collapse_time: float | None = None
    newton_iterations: int = 0
    wall_effective_strain: np.ndarray | None = None
    wall_dampers: tuple | None = None
    strain_iterations: int | None = None
    strain_converged: bool | None = None

    @cached_property
    def absolute_acceleration(self) -> np.ndarray:
        """Relative acceleration + ground acceleration, mm/s^2, (steps, floors)."""
        return self.acceleration + self.ground_acceleration[:, None]

    @cached_property
    def drift_ratio(self) -> np.ndarray | None:
        """Drift / story height (-), (steps, stories); None without story heights."""
        heights = self.building.story_heights
        return None if heights is None else self.drift / np.asarray(heights)

    @cached_property
    def wall_force(self) -> np.ndarray:
        """Force of every wall (N), (steps, walls) in ``building.damper_list`` order."""
        return np.take(self.group_force, self.wall_group, axis=1) * self.wall_share

    @cached_property
    def wall_strain(self) -> np.ndarray:
        """Strain of every wall (-: its own deformation / thickness), (steps, walls)."""
        return np.take(self.group_strain, self.wall_group, axis=1)

    @cached_property
    def damper_strain(self) -> np.ndarray:
        """The strain of each story's most strained wall group (-), (steps, stories); 0 without walls."""
        strain = np.zeros((self.time.size, self.building.stories))
        peaks = np.abs(self.group_strain).max(axis=0, initial=0.0)
        stories = np.array([story - 1 for story, _ in self.building.damper_list], dtype=int)
        most = {}
        for wall, group in enumerate(self.wall_group):
            story = stories[wall]
            if story not in most or peaks[group] > peaks[most[story]]:
                most[story] = group
        for story, group in most.items():
            strain[:, story] = self.group_strain[:, group]
        return strain

    @property
    def peak_drift(self) -> np.ndarray:
        """max |drift| per story, mm."""
        return np.abs(self.drift).max(axis=0)

    @property
    def peak_drift_ratio(self) -> np.ndarray | None:
        """max |drift ratio| per story (-), None without story heights."""
        return None if self.drift_ratio is None else np.abs(self.drift_ratio).max(axis=0)

    @property
    def residual_drift(self) -> np.ndarray:
        """Drift at the last step, per story, mm (append ``free_vibration`` to measure it at rest).  For an
        analysis that collapsed or stopped converging it is the drift where it stopped, not a residual."""
        return self.drift[-1].copy()

    @property
    def peak_ductility(self) -> np.ma.MaskedArray:
        """Peak |drift| / yield drift per story (-); masked for stories without a hysteresis model."""
        yield_drifts = self.building.yield_drifts
        elastic = yield_drifts == 0.0
        ratio = self.peak_drift / np.where(elastic, 1.0, yield_drifts)
        return np.ma.masked_array(ratio, mask=elastic)

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
        """max |total wall force| per story, N."""
        return np.abs(self.damper_force).max(axis=0)

    @property
    def peak_wall_strain(self) -> np.ndarray:
        """max |strain| of every wall (-), in ``building.damper_list`` order."""
        return np.abs(self.group_strain).max(axis=0, initial=0.0)[self.wall_group]


# ---------------------------------------------------------------------------------------------- driver
def simulate(building: ShearBuilding, ground_motion, dt: float | None = None, method=DEFAULT_METHOD,
             memory=DEFAULT_MEMORY, strain_compatible=False, *, collapse_drift_ratio: float | None = 0.10,
             free_vibration: float = 0.0, newton: NewtonRaphson | None = None) -> SimulationResult:
    """Integrate ``building`` under ``ground_motion`` (a :class:`~vdw_frames.GroundMotion`, mm/s^2).

    ``dt`` (s) defaults to the record's step; a smaller step must divide it to a relative 1e-6 (the
    ground acceleration is interpolated linearly; the step used is the record step / the whole number of
    sub-steps, so a float32 dt works); a larger or non-dividing step, or one outside
    ``vdw_frames._validation.SIMULATION_STEP_RANGE`` (1e-9 ... 1e3 s), is a ValueError.  So is a run
    whose result arrays would exceed the 2 GiB memory limit, refused before allocating with its step
    count and memory.  ``method`` and ``memory`` (validated even for a frame without walls) select the
    walls' discretisation and memory strategy ("fast", the default, costs the same at every step and
    stays within 3e-9 of "exact"; see :meth:`FDMKDamper.force`).

    ``collapse_drift_ratio`` (-, default 0.10; None disables it; needs story heights): when any story's
    drift ratio exceeds it, the analysis stops there with ``result.collapsed`` and
    ``result.collapse_time``.  ``free_vibration`` (s, >= 0): seconds of zero ground acceleration appended
    to the record, so that residual drifts are measured at rest.  ``newton``: the convergence settings
    (:class:`NewtonRaphson`); a linear building takes one solve per step whatever they are.

    ``strain_compatible``: ``True`` (or a :class:`~vdw_frames.StrainCompatibleOptions`) runs the
    equivalent-linear iteration of :mod:`vdw_frames.frame.strain_compatible` for buildings with
    :class:`~vdw_frames.StrainDependentDamper` walls, which a plain run (``False``, the default) refuses;
    its result is the response of the equivalent-linear building (``result.building``).

    A step that fails to converge even with the fallbacks stops the analysis with
    ``result.converged = False`` and a ``RuntimeWarning`` naming the time and story; never NaN.  Warns
    (``UserWarning``) when a wall's peak strain leaves its ``strain_range``.  Returns a
    :class:`SimulationResult`.
    """
    if strain_compatible is not False:
        from .strain_compatible import strain_compatible_simulation  # it calls simulate() back

        return strain_compatible_simulation(building, ground_motion, strain_compatible, dt=dt, method=method,
                                            memory=memory, collapse_drift_ratio=collapse_drift_ratio,
                                            free_vibration=free_vibration, newton=newton)
    require_fixed_walls(building, "simulate()")
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    if not isinstance(ground_motion, GroundMotion):
        raise ValueError(f"ground_motion must be a GroundMotion (see read_at2), got {type(ground_motion).__name__}")
    method = get_method(method)
    memory_strategy(memory)
    newton = NewtonRaphson() if newton is None else newton
    if not isinstance(newton, NewtonRaphson):
        raise ValueError(f"newton must be a NewtonRaphson, got {type(newton).__name__}")
    if collapse_drift_ratio is not None:
        collapse_drift_ratio = positive("collapse_drift_ratio", collapse_drift_ratio)
    free_vibration = non_negative("free_vibration", free_vibration)
    dt = positive("dt", ground_motion.dt if dt is None else dt)
    if not SIMULATION_STEP_RANGE[0] <= dt <= SIMULATION_STEP_RANGE[1]:
        raise ValueError(f"time step dt = {show(dt)} s is outside the range simulate accepts "
                         f"({SIMULATION_STEP_RANGE[0]:g} ... {SIMULATION_STEP_RANGE[1]:g} s)")
    substeps = ground_motion.substeps(dt)
    dt = ground_motion.dt / substeps
    # Response and result histories (about 14 per floor), each wall's force, strain and exact memory,
    # energies: float64 a step.
    check_memory(f"simulate (dt = {dt!r} s, {building.stories} floors, {len(building.damper_list)} walls)",
                 (ground_motion.acceleration.size - 1) * substeps + 1 + math.ceil(free_vibration / dt),
                 8 * (14 * building.stories + 6 * len(building.damper_list) + 12), "use a larger dt")
    ground = ground_motion.acceleration_at(dt)
    if free_vibration > 0.0:
        ground = np.concatenate([ground, np.zeros(int(math.ceil(free_vibration / dt - 1e-9)))])
    steps, floors = ground.size, building.stories

    walls = building.damper_list
    groups, group_of_wall = _wall_groups(walls)
    bank = WallBank([wall for _, wall in groups], dt, steps, method, memory)
    group_story = np.array([story - 1 for story, _ in groups], dtype=np.int64)

    models = building.story_models
    kinds = np.array([LINEAR if model is None else model.kind for model in models], dtype=np.int64)
    parameters = np.array([[k, 0.0, 0.0, 0.0, 0.0, 0.0] if model is None else model.parameters(k)
                           for model, k in zip(models, building.stiffnesses)]).reshape(floors, PARAMETERS)
    committed = np.zeros((floors, STATE))
    heights = np.asarray(building.story_heights) if building.story_heights is not None else np.ones(floors)
    collapse_ratio = collapse_drift_ratio if (collapse_drift_ratio and building.story_heights) else 0.0
    damping = np.ascontiguousarray(building.damping_matrix)
    tridiagonal = building.damping_model == "rayleigh"

    displacement = np.zeros((steps, floors))
    velocity = np.zeros((steps, floors))
    acceleration = np.zeros((steps, floors))
    drift = np.zeros((steps, floors))
    story_shear = np.zeros((steps, floors))
    damper_force = np.zeros((steps, floors))
    base_shear = np.zeros(steps)
    group_force = np.zeros((steps, len(groups)))
    group_strain = np.zeros((steps, len(groups)))
    peak_group_strain = np.zeros(len(groups))
    energy = np.zeros((steps, _ENERGIES))
    outcome = np.zeros(3, dtype=np.int64)
    (constants, w0, window_weights, window, mode_weight, mode_ratio, mode_state, history, values, wall_tangent,
     wall_history) = bank.kernel_arrays()
    filled = _integrate(
        ground, dt, np.asarray(building.masses), damping, building.story_damping_matrix.sum(axis=0),
        tridiagonal, kinds, parameters, committed, np.asarray(building.geometric_stiffness), heights,
        collapse_ratio, building.is_linear, newton.displacement_tolerance, newton.force_tolerance,
        newton.max_iterations, newton.fallback_iterations, group_story, constants, w0, window_weights, window,
        mode_weight, mode_ratio, mode_state, history, values, wall_tangent, wall_history,
        displacement, velocity, acceleration, drift, story_shear, damper_force, base_shear, group_force,
        group_strain, peak_group_strain, energy, outcome)
    status, story_index, iterations = (int(x) for x in outcome)
    keep = slice(0, filled)
    time = np.arange(filled) * dt
    if status == _FAILED:
        _warnings.warn(f"simulate: the step to t = {filled * dt:.6g} s did not converge (story {story_index + 1} "
                       "moved most in the last correction), even with a line search and initial-stiffness "
                       "iterations; the analysis stops there (result.converged is False)", RuntimeWarning,
                       stacklevel=2)
    require_finite("the response", displacement[keep])
    return _result(building, walls, groups, group_of_wall, time, ground[keep], displacement[keep],
                   velocity[keep], acceleration[keep], drift[keep], story_shear[keep],
                   damper_force[keep], base_shear[keep], group_force[keep], group_strain[keep], peak_group_strain,
                   energy[keep], converged=status != _FAILED, collapsed=status == _COLLAPSED,
                   collapse_time=float(time[-1]) if status == _COLLAPSED else None, iterations=iterations)


def _wall_groups(walls):
    """Walls of one story that see the same strain history are stepped once, as one wall of their summed area.

    Two walls in parallel on a story are one wall of the summed area when their material, order and
    thickness agree and their supports scale with their areas (equal flexibility x area).  Returns
    ([(story, combined wall)], group index of every wall).
    """
    keys: dict[tuple, int] = {}
    members: list[list[int]] = []
    for index, (story, wall) in enumerate(walls):
        G1, G2, eta1, eta2, area, thickness, flexibility = (float(x) for x in kernel_constants(wall))
        key = (story, G1, G2, eta1, eta2, wall.r, thickness, flexibility * area)
        if key not in keys:
            keys[key] = len(members)
            members.append([])
        members[keys[key]].append(index)
    groups = []
    group_of_wall = np.zeros(len(walls), dtype=np.int64)
    for g, indices in enumerate(members):
        story, first = walls[indices[0]]
        area = sum(walls[i][1].area for i in indices)
        groups.append((story, _CombinedWall(first, area)))
        group_of_wall[indices] = g
    return groups, group_of_wall


@dataclass(frozen=True)
class _CombinedWall:
    """Parallel identical walls (see :func:`_wall_groups`) as one wall of the summed area, for the kernel."""

    wall: object
    area: float
    r: float = field(init=False)

    def __post_init__(self):
        object.__setattr__(self, "r", self.wall.r)

    def kernel_constants(self):
        G1, G2, eta1, eta2, area, thickness, flexibility = kernel_constants(self.wall)
        return (G1, G2, eta1, eta2, self.area, thickness, flexibility * area / self.area)


def _result(building, walls, groups, group_of_wall, time, ground, displacement, velocity, acceleration, drift,
            story_shear, damper_force, base_shear, group_force, group_strain, peak_group_strain, energy, *,
            converged, collapsed, collapse_time, iterations):
    share = np.array([walls[i][1].area / groups[g][1].area for i, g in enumerate(group_of_wall)])
    require_finite("the energy histories", energy)
    energy_history = EnergyHistory(energy[:, 0], energy[:, 1], energy[:, 2], energy[:, 3] - energy[:, 2],
                                   energy[:, 4], energy[:, 5], energy[:, 6])
    _check_energy_balance(energy_history)
    _warn_strain_range(walls, peak_group_strain[group_of_wall])
    return SimulationResult(building, time, ground, displacement, velocity, acceleration, drift, story_shear,
                            damper_force, base_shear, energy_history, group_force, group_strain, group_of_wall,
                            share, converged, collapsed, collapse_time, iterations)


def _check_energy_balance(energy: EnergyHistory) -> None:
    """Warn when the energy balance misses by more than ENERGY_BALANCE_TOLERANCE of the peak input energy."""
    scale = float(np.abs(energy.input).max(initial=0.0))
    if scale == 0.0:
        return
    error = float(np.abs(energy.balance_error).max()) / scale
    if error > ENERGY_BALANCE_TOLERANCE:
        _warnings.warn(f"simulate: the energy balance misses by {error:.3g} of the peak input energy (self-check "
                       f"bound {ENERGY_BALANCE_TOLERANCE:g}): the integration did not solve the equations of "
                       "motion to their tolerance; do not trust this result", RuntimeWarning, stacklevel=4)


def _warn_strain_range(walls, peak_wall_strain):
    outside = []
    for index, (story, wall) in enumerate(walls):
        if wall.strain_range is None:
            continue
        peak = float(peak_wall_strain[index])
        low, high = wall.strain_range
        if not low <= peak <= high:
            outside.append(f"story {story}: {100 * peak:.0f} % (range {100 * low:.0f}-{100 * high:.0f} %)")
    if outside:
        _warnings.warn("damper peak strain outside the range its parameters were identified for: "
                       + "; ".join(dict.fromkeys(outside)), UserWarning, stacklevel=4)
