"""The compiled Newmark-Newton integrator of a shear building with FDMK walls: average acceleration with
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

The compiled functions take their arrays as named tuples (:class:`FrameArrays`, :class:`StoryArrays`,
:class:`~vdw_frames.element.kernel.BankArrays`, :class:`Histories`, :class:`Scratch`), whose fields
give every array's shape; nothing here imports the drivers above it
(:mod:`vdw_frames.frame.time_history`, :mod:`vdw_frames.frame.simulation`).  The step loops allocate
nothing (their work arrays come from :func:`scratch`): they are compiled without numba's reference
counting, which cost more than the step's arithmetic (``allocates=False`` in :mod:`vdw_frames._jit`).
Newmark's velocity and acceleration are affine in the trial displacements, so the parts of the residual
that depend only on the committed state are formed once a step (:func:`_step_constants`) and the
dynamic stiffness (4/dt^2) M + (2/dt) C once a run.

Units: N, mm, s, tonne.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from .._jit import njit
from .._validation import positive, whole_number
from ..element import kernel
from ..element.devices import DeviceStates, devices_commit, devices_trial, record_devices
from ..element.kernel import BankArrays
from .hysteresis import story_trial

# Status codes of a step (advance) and of a run (lane_kernel.LanePeaks.outcome[:, 0]; STOPPED: a run cancelled).
RUNNING, FINISHED, COLLAPSED, FAILED, STOPPED = 0, 1, 2, 3, 4
# Energy columns: input, kinetic, frame strain (recoverable), story work, inherent damping, wall work, P-Delta.
ENERGIES = 7
# Solution strategies tried in turn on a step: Newton, Newton with line search, initial stiffness.
_NEWTON, _LINE_SEARCH, _INITIAL = 0, 1, 2


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

    def __post_init__(self) -> None:
        object.__setattr__(self, "displacement_tolerance",
                           positive("displacement_tolerance", self.displacement_tolerance))
        object.__setattr__(self, "force_tolerance", positive("force_tolerance", self.force_tolerance))
        object.__setattr__(self, "max_iterations", whole_number("max_iterations", self.max_iterations, 1))
        object.__setattr__(self, "fallback_iterations",
                           whole_number("fallback_iterations", self.fallback_iterations, 1))

    def arrays(self) -> NewtonSettings:
        """The settings as the compiled integrator takes them."""
        return NewtonSettings(self.displacement_tolerance, self.force_tolerance, self.max_iterations,
                              self.fallback_iterations)


class NewtonSettings(NamedTuple):
    """:class:`NewtonRaphson` for the compiled integrator."""

    displacement_tolerance: float  # mm
    force_tolerance: float  # -
    max_iterations: int
    fallback_iterations: int


class FrameArrays(NamedTuple):
    """The building as the integrator sees it (n stories)."""

    masses: np.ndarray  # (n,) tonne
    damping: np.ndarray  # (n, n) N*s/mm
    story_damping_row: np.ndarray  # (n,): 1^T C_s, the damping force through story 1 per unit velocity
    geometric: np.ndarray  # (n,) -P/h, N/mm
    heights: np.ndarray  # (n,) mm (ones without story heights)
    tridiagonal: bool  # Rayleigh damping: a tridiagonal tangent
    linear: bool  # every story elastic: one solve a step
    collapse_ratio: float  # drift ratio that stops the run (0: never)


class DeviceArrays(NamedTuple):
    """The devices: one bank of wall groups (G groups), their stories and magnifications, and every other
    device kind's states (:class:`~vdw_frames.element.devices.DeviceStates`)."""

    group_story: np.ndarray  # (G,) int64, 0-based
    group_magnification: np.ndarray  # (G,) -: wall deformation / story drift
    bank: BankArrays
    others: DeviceStates  # empty (total 0) without any: skipped at run time, one compiled step for every building


class Histories(NamedTuple):
    """The integrator's output (N steps, n stories, G wall groups); row 0 is rest."""

    displacement: np.ndarray  # (N, n) mm
    velocity: np.ndarray  # (N, n) mm/s
    acceleration: np.ndarray  # (N, n) mm/s^2, relative
    drift: np.ndarray  # (N, n) mm
    story_shear: np.ndarray  # (N, n) N, frame springs
    story_wall_force: np.ndarray  # (N, n) N, all walls of each story
    base_shear: np.ndarray  # (N,) N
    group_force: np.ndarray  # (N, G) N
    group_strain: np.ndarray  # (N, G) -
    peak_group_strain: np.ndarray  # (G,) -
    energy: np.ndarray  # (N, ENERGIES) N*mm
    # Walls whose heat is followed (thermal description or limits); (0, G) when none is:
    group_temperature: np.ndarray  # (N, G) degC (NaN for a group without a thermal description)
    group_heat: np.ndarray  # (N, G) N*mm dissipated since rest; (0, G) when every followed group has a temperature
    wall_heat: np.ndarray  # (N,) N*mm dissipated in all walls since rest
    wall_stored: np.ndarray  # (N,) N*mm stored in all walls
    wall_parameter_loss: np.ndarray  # (N,) N*mm the walls' stored energy lost as their parameters changed
    group_amplitude: np.ndarray  # (N, G) strain amplitude followed; (0, G) without amplitude-following walls
    # The other devices (D, the building's order; (N, 0) without any), along each device:
    device_force: np.ndarray  # (N, D) N
    device_deformation: np.ndarray  # (N, D) mm
    device_velocity: np.ndarray  # (N, D) mm/s
    device_heat: np.ndarray  # (N, D) N*mm dissipated since rest
    device_stored: np.ndarray  # (N, D) N*mm stored


class Scratch(NamedTuple):
    """Work arrays of the integration (n stories, G wall groups)."""

    displacement: np.ndarray  # (n,) trial displacements, mm
    drift: np.ndarray  # (n,) trial drifts, mm
    story_force: np.ndarray  # (n,) trial frame-spring forces, N
    story_tangent: np.ndarray  # (n,) N/mm
    trial_state: np.ndarray  # (n,) the story models' state values to commit
    story_total: np.ndarray  # (n,) spring + P-Delta + walls, N
    damping_force: np.ndarray  # (n,) C v, N
    residual: np.ndarray  # (n,) N
    correction: np.ndarray  # (n,) mm
    stiffness_diagonal: np.ndarray  # (n,) story tangents in the solve, N/mm
    wall_tangent: np.ndarray  # (n,) walls' K_t per story, N/mm
    wall_history: np.ndarray  # (n,) walls' H_n per story, N
    device_force: np.ndarray  # (n,) the other devices' trial force per story, N
    device_tangent: np.ndarray  # (n,) their tangent per story, N/mm
    work: np.ndarray  # (3, n) tridiagonal factors: pivots, super-diagonal, elimination factors
    factored: np.ndarray  # (n,) the story tangents work was factored for, N/mm (NaN: none yet)
    matrix: np.ndarray  # (n, n) dense tangent
    wall_deformation: np.ndarray  # (G,) mm
    wall_force: np.ndarray  # (G,) N
    wall_strain: np.ndarray  # (G,) -
    line_search: np.ndarray  # (n,) displacements tried by the line search, mm
    old_damping_force: np.ndarray  # (n,) C v of the last committed step, N
    # Constant over the run:
    dynamic_mass: np.ndarray  # (n,) (4/dt^2) m, N/mm
    dynamic_band: np.ndarray  # (2, n) (4/dt^2) M + (2/dt) C: diagonal, super-diagonal (tridiagonal only), N/mm
    initial_stiffness: np.ndarray  # (n,) k_0 + k_G, N/mm
    # Constant over a step (from the committed state of row n):
    step_force: np.ndarray  # (n,) m (a0 u_n + (4/dt) v_n + a_n) + C ((2/dt) u_n + v_n) - m a_g, N
    damping_offset: np.ndarray  # (n,) C ((2/dt) u_n + v_n), N
    inertia_scale: np.ndarray  # (n,) m ((4/dt) |v_n| + |a_n|), N


def scratch(stories: int, groups: int) -> Scratch:
    """Zeroed work arrays for :func:`advance` of a building of ``stories`` stories and ``groups`` wall
    groups (the integrator allocates nothing: it is compiled without numba's reference counting)."""
    n = stories
    shapes = {"work": (3, n), "matrix": (n, n), "wall_deformation": (groups,), "wall_force": (groups,),
              "wall_strain": (groups,), "dynamic_band": (2, n)}
    work = Scratch(*(np.zeros(shapes.get(name, (n,))) for name in Scratch._fields))
    work.factored[:] = np.nan  # nothing factored yet
    return work


# ---------------------------------------------------------------------------------------------- compiled
# The devices beyond the walls: a building without any has an empty DeviceStates (total 0), skipped at run
# time, so that every building compiles the same step (one specialisation, not one with and one without).
@njit(cache=True, inline="always")
def _add_device_forces(devices, dt, work):
    """Every device's trial at ``work.drift``; their forces into ``work.story_total``."""
    if devices.total == 0:
        return
    devices_trial(devices, work.drift, dt, work.device_force, work.device_tangent)
    for s in range(work.drift.shape[0]):
        work.story_total[s] += work.device_force[s]


@njit(cache=True, inline="always")
def _add_device_tangents(devices, work):
    """Their tangents into ``work.stiffness_diagonal``."""
    if devices.total == 0:
        return
    for s in range(work.stiffness_diagonal.shape[0]):
        work.stiffness_diagonal[s] += work.device_tangent[s]


@njit(cache=True, inline="always")
def _with_device_tangent(devices, work, s, tangent):
    """``tangent`` of story ``s`` with its devices' tangent."""
    if devices.total == 0:
        return tangent
    return tangent + work.device_tangent[s]


@njit(cache=True, inline="always")
def _record_devices(row, devices, out):
    """Row ``row`` of their histories from their committed states."""
    if devices.total == 0:
        return
    record_devices(devices.viscous.kinematics, row, out.device_force, out.device_deformation,
                   out.device_velocity, out.device_heat, out.device_stored)
    record_devices(devices.friction.kinematics, row, out.device_force, out.device_deformation,
                   out.device_velocity, out.device_heat, out.device_stored)


@njit(cache=True, inline="always")
def _commit_devices(row, devices, out):
    """Accept their last trials and record them in row ``row`` of the histories."""
    if devices.total == 0:
        return
    devices_commit(devices)
    _record_devices(row, devices, out)


@njit(cache=True, inline="always")
def _replay_devices(devices, drift, dt, work):
    """Commit them at the story drifts ``drift`` (replay); their story forces added to ``work.story_total``."""
    if devices.total == 0:
        return
    devices_trial(devices, drift, dt, work.device_force, work.device_tangent)
    devices_commit(devices)
    for s in range(drift.shape[0]):
        work.story_total[s] += work.device_force[s]


@njit(cache=True, inline="always")
def _story_state(stories, work):
    """Every story's trial at ``work.drift``: force, tangent and the state value to commit."""
    for s in range(work.drift.shape[0]):
        work.story_force[s], work.story_tangent[s], work.trial_state[s] = story_trial(stories, s, work.drift[s])


@njit(cache=True, inline="always")
def _damped_floors(frame, i, n):
    """The floors j (low <= j < high) whose velocities enter floor i's damping force (C's nonzero columns)."""
    return (max(i - 1, 0), min(i + 2, n)) if frame.tridiagonal else (0, n)


@njit(cache=True, inline="always")
def _step_constants(row, ground, dt, frame, out, work):
    """The parts of the residual fixed by the committed state of row ``row`` and the ground acceleration
    ``ground`` (mm/s^2) of the coming step, into ``work``; returns the step's least force scale (N)."""
    displacement, velocity, acceleration = out.displacement, out.velocity, out.acceleration
    masses, damping = frame.masses, frame.damping
    n = masses.shape[0]
    v1, a1 = 2.0 / dt, 4.0 / dt
    least = 1.0
    for i in range(n):
        offset = 0.0
        low, high = _damped_floors(frame, i, n)
        for j in range(low, high):
            offset += damping[i, j] * (v1 * displacement[row, j] + velocity[row, j])
        work.damping_offset[i] = offset
        external = masses[i] * ground
        work.step_force[i] = (work.dynamic_mass[i] * displacement[row, i]
                              + masses[i] * (a1 * velocity[row, i] + acceleration[row, i]) + offset - external)
        work.inertia_scale[i] = masses[i] * (a1 * abs(velocity[row, i]) + abs(acceleration[row, i]))
        least = max(least, abs(external))
    return least


@njit(cache=True, inline="always")
def _residual(u, dt, least, frame, stories, devices, work):
    """Unbalanced force R = -M a_g - (M a + C v + B^T f)(u) at trial displacements u (n,) of the step whose
    constants :func:`_step_constants` put in ``work`` (its least force scale ``least``, N), into
    ``work.residual``; returns the force scale.

    Newmark's a and v are affine in u: R = step_force - (4/dt^2) M u - (2/dt) C u - B^T f(u).  Fills the
    drifts, the stories' trial forces/tangents/states, the total story forces (spring + P-Delta + walls)
    and the damping forces C v.
    """
    damping, geometric = frame.damping, frame.geometric
    n = u.shape[0]
    v1 = 2.0 / dt
    for s in range(n):
        work.drift[s] = u[s] - (u[s - 1] if s > 0 else 0.0)
    _story_state(stories, work)
    for s in range(n):
        work.story_total[s] = (work.story_force[s] + geometric[s] * work.drift[s]
                               + work.wall_tangent[s] * work.drift[s] + work.wall_history[s])
    _add_device_forces(devices, dt, work)
    scale = least
    for i in range(n):
        damped = 0.0
        low, high = _damped_floors(frame, i, n)
        for j in range(low, high):
            damped += damping[i, j] * u[j]
        viscous = v1 * damped - work.damping_offset[i]
        work.damping_force[i] = viscous
        above = work.story_total[i + 1] if i + 1 < n else 0.0
        work.residual[i] = (work.step_force[i] - work.dynamic_mass[i] * u[i] - v1 * damped
                            - (work.story_total[i] - above))
        # The residual's round-off is relative to its largest terms, including the inertia terms before
        # they cancel (m a0 |u| for the increment u - u_n): the force tolerance is relative to them all.
        scale = max(scale, work.dynamic_mass[i] * abs(u[i]) + work.inertia_scale[i], abs(viscous),
                    abs(work.story_force[i]), abs(work.story_total[i]))
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
def _solve(frame, dt, work):
    """Solve ((4/dt^2) M + (2/dt) C + B^T diag(k) B) x = R for the correction x (n,), k =
    ``work.stiffness_diagonal``, R = ``work.residual``: the Thomas algorithm when tridiagonal, else LU."""
    if frame.tridiagonal:
        _solve_tridiagonal(work)
    else:
        _solve_dense(frame, dt, work)


@njit(cache=True, inline="always")
def _solve_tridiagonal(work):
    """:func:`_solve` when C is tridiagonal (Rayleigh damping): the Thomas algorithm on the symmetric band.

    The elimination (pivots, factors) depends only on the story tangents k (the dynamic band is fixed for the
    run): it is kept in ``work.work`` with the k it was made for (``work.factored``) and reused while k is
    the same -- a Bilinear frame on its branches, walls' constant K_t --, the same operations on the same
    values (bit-identical), without the chain of divisions that dominated the solve."""
    k, rhs, out, band, factored = work.stiffness_diagonal, work.residual, work.correction, work.work, work.factored
    n = rhs.shape[0]
    same = True
    for i in range(n):
        if k[i] != factored[i]:  # (NaN after prepare: never equal)
            same = False
            break
    if not same:
        # diagonal in band[0], super-diagonal in band[1], elimination factors in band[2] (symmetric tridiagonal)
        diagonal = work.dynamic_band[0, 0] + k[0] + (k[1] if n > 1 else 0.0)
        band[0, 0] = diagonal
        for i in range(1, n):
            upper = work.dynamic_band[1, i - 1] - k[i]
            band[1, i - 1] = upper
            factor = upper / diagonal
            band[2, i] = factor
            diagonal = work.dynamic_band[0, i] + k[i] + (k[i + 1] if i + 1 < n else 0.0) - factor * upper
            band[0, i] = diagonal
        for i in range(n):
            factored[i] = k[i]
    out[0] = rhs[0]
    for i in range(1, n):
        out[i] = rhs[i] - band[2, i] * out[i - 1]
    out[n - 1] /= band[0, n - 1]
    for i in range(n - 2, -1, -1):
        out[i] = (out[i] - band[1, i] * out[i + 1]) / band[0, i]


@njit(cache=True, inline="always")
def _solve_dense(frame, dt, work):
    """:func:`_solve` for a full C (modal damping): Gaussian elimination with partial pivoting."""
    damping, k = frame.damping, work.stiffness_diagonal
    rhs, out, matrix = work.residual, work.correction, work.matrix
    n = rhs.shape[0]
    v1 = 2.0 / dt
    # Every row's damping first: the stiffness couples row i to i + 1, which a later row must not overwrite.
    for i in range(n):
        for j in range(n):
            matrix[i, j] = v1 * damping[i, j]
        out[i] = rhs[i]
    for i in range(n):
        matrix[i, i] += work.dynamic_mass[i] + k[i] + (k[i + 1] if i + 1 < n else 0.0)
        if i + 1 < n:
            matrix[i, i + 1] -= k[i + 1]
            matrix[i + 1, i] -= k[i + 1]
    # Gaussian elimination with partial pivoting
    for c in range(n):
        pivot = c
        for i in range(c + 1, n):
            if abs(matrix[i, c]) > abs(matrix[pivot, c]):
                pivot = i
        if pivot != c:
            for j in range(n):
                matrix[c, j], matrix[pivot, j] = matrix[pivot, j], matrix[c, j]
            out[c], out[pivot] = out[pivot], out[c]
        for i in range(c + 1, n):
            factor = matrix[i, c] / matrix[c, c]
            for j in range(c, n):
                matrix[i, j] -= factor * matrix[c, j]
            out[i] -= factor * out[c]
    for i in range(n - 1, -1, -1):
        total = out[i]
        for j in range(i + 1, n):
            total -= matrix[i, j] * out[j]
        out[i] = total / matrix[i, i]


@njit(cache=True, inline="always")
def _newton(row, ground_next, dt, frame, stories, devices, newton, out, work):
    """Newton-Raphson for the step from row ``row`` (u_n) into ``work.displacement``: the strategies in turn
    (full tangent, with a line search, initial stiffness), each from u_n again.  Returns (converged,
    corrections made)."""
    least = _step_constants(row, ground_next, dt, frame, out, work)
    u = work.displacement
    made = 0
    for strategy in range(3):
        if frame.linear and strategy > 0:
            break
        for i in range(u.shape[0]):
            u[i] = out.displacement[row, i]
        limit = newton.max_iterations if strategy < _INITIAL else newton.fallback_iterations
        if frame.linear:
            limit = 1
        converged, corrections = _iterate(strategy, limit, least, dt, frame, stories, devices, newton, work)
        made += corrections
        if converged:
            return True, made
    return False, made


@njit(cache=True, inline="always")
def _iterate(strategy, limit, least, dt, frame, stories, devices, newton, work):
    """At most ``limit`` Newton corrections of ``work.displacement`` with one strategy; returns (converged,
    corrections made)."""
    u, geometric = work.displacement, frame.geometric
    n = u.shape[0]
    last_correction = np.inf
    exact_solve = False  # the last correction solved the model itself (no tangent changed since)
    made = 0
    for iteration in range(limit + 1):
        scale = _residual(u, dt, least, frame, stories, devices, work)
        norm = _largest(work.residual)
        if exact_solve and _tangent_changed(frame, devices, work):
            exact_solve = False
        if iteration > 0 and (frame.linear or (
                norm <= newton.force_tolerance * scale
                and (exact_solve or last_correction <= newton.displacement_tolerance))):
            return True, made
        if iteration == limit or not math.isfinite(norm):
            return False, made
        for s in range(n):
            if strategy == _INITIAL:
                work.stiffness_diagonal[s] = work.initial_stiffness[s] + work.wall_tangent[s]
            else:
                work.stiffness_diagonal[s] = work.story_tangent[s] + geometric[s] + work.wall_tangent[s]
        _add_device_tangents(devices, work)
        _solve(frame, dt, work)
        made += 1
        step_length = 1.0
        if strategy == _LINE_SEARCH:
            step_length = _line_search(norm, dt, least, frame, stories, devices, work)
        exact_solve = strategy != _INITIAL and step_length == 1.0
        last_correction = step_length * _largest(work.correction)
        for i in range(n):
            u[i] += step_length * work.correction[i]
    return False, made


@njit(cache=True, inline="always")
def _tangent_changed(frame, devices, work):
    """Whether a story's tangent differs from the one the last correction was solved with."""
    for s in range(work.stiffness_diagonal.shape[0]):
        tangent = _with_device_tangent(devices, work, s,
                                       work.story_tangent[s] + frame.geometric[s] + work.wall_tangent[s])
        if tangent != work.stiffness_diagonal[s]:
            return True
    return False


@njit(cache=True, inline="always")
def _line_search(norm, dt, least, frame, stories, devices, work):
    """The length of ``work.correction`` to take from ``work.displacement``: halved until the unbalanced force
    drops below ``norm`` (at most 8 halvings; after them the 1/256 step is taken and the next residual judges
    it)."""
    u, trial = work.displacement, work.line_search
    step_length = 1.0
    for _ in range(8):
        for i in range(u.shape[0]):
            trial[i] = u[i] + step_length * work.correction[i]
        _residual(trial, dt, least, frame, stories, devices, work)
        if _largest(work.residual) < norm:
            break
        step_length *= 0.5
    return step_length


@njit(cache=True, inline="always")
def _moved_most(correction):
    """The story (0-based) whose drift the correction ``correction`` (floors) changed most."""
    story, largest = 0, 0.0
    for s in range(correction.shape[0]):
        story_drift = abs(correction[s] - (correction[s - 1] if s > 0 else 0.0))
        if story_drift > largest:
            story, largest = s, story_drift
    return story


@njit(cache=True, inline="always")
def _record_walls(next_row, states, out, work):
    """Row ``next_row`` of the wall groups' histories from the committed walls (``states``: their WallStates)."""
    groups = work.wall_force.shape[0]
    for g in range(groups):
        out.group_force[next_row, g] = work.wall_force[g]
        out.group_strain[next_row, g] = work.wall_strain[g]
        out.peak_group_strain[g] = max(out.peak_group_strain[g], abs(work.wall_strain[g]))
    if out.group_temperature.shape[0] > 0:
        heat, stored, parameter_loss = 0.0, 0.0, 0.0
        for g in range(groups):
            energy = states.walls[g].energy
            out.group_temperature[next_row, g] = states.walls[g].thermal.temperature
            if out.group_heat.shape[0] > 0:
                out.group_heat[next_row, g] = energy.heat
            heat += energy.heat
            stored += energy.stored
            parameter_loss += energy.parameter_loss
        out.wall_heat[next_row] = heat
        out.wall_stored[next_row] = stored
        out.wall_parameter_loss[next_row] = parameter_loss
    if out.group_amplitude.shape[0] > 0:
        for g in range(groups):
            out.group_amplitude[next_row, g] = states.walls[g].tracker.amplitude


@njit(cache=True, inline="always")
def prepare(dt, row, frame, stories, out, work):
    """The run's constants into ``work`` (the dynamic stiffness, the initial tangents) and C v of the state in
    row ``row`` of ``out`` (``work.old_damping_force``): what :func:`advance` needs before its first step."""
    n = frame.masses.shape[0]
    a0, v1 = 4.0 / dt**2, 2.0 / dt
    for i in range(n):
        work.dynamic_mass[i] = a0 * frame.masses[i]
        work.dynamic_band[0, i] = work.dynamic_mass[i] + v1 * frame.damping[i, i]
        work.dynamic_band[1, i] = v1 * frame.damping[i, i + 1] if i + 1 < n else 0.0
        work.initial_stiffness[i] = stories.parameters[i, 0] + frame.geometric[i]
    work.factored[0] = np.nan  # the dynamic band may have changed: factor anew
    old_damping_force = work.old_damping_force
    for i in range(n):  # C v of row 0 (loops, not slice operations: those compile numba's shape-error machinery)
        old_damping_force[i] = 0.0
        for j in range(n):
            old_damping_force[i] += frame.damping[i, j] * out.velocity[row, j]


@njit(cache=True, inline="always")
def advance(step, row, next_row, ground_now, ground_next, dt, start, frame, stories, walls, newton, out, work):
    """One step of the analysis, the step body of :func:`vdw_frames.frame.lane_kernel.run_lane` (every analysis,
    (:mod:`vdw_frames.frame.lanes`): from the committed state in row ``row`` of ``out`` (step ``step`` of the
    run, ``start`` + ``step`` of the walls' memory) to row ``next_row`` under the ground accelerations
    ``ground_now``, ``ground_next`` (mm/s^2) of both.  :func:`prepare` must have run.  Returns (status,
    story, Newton corrections): RUNNING, FAILED (the story the last correction moved most; nothing
    committed) or COLLAPSED (the story; the step committed and recorded)."""
    n = out.displacement.shape[1]
    bank = walls.bank
    groups = walls.group_story.shape[0]
    a0, v1 = 4.0 / dt**2, 2.0 / dt
    # 1. walls: their history for this step came with the last commit; their trial force is K_t d + H_n
    for s in range(n):
        work.wall_tangent[s] = 0.0
        work.wall_history[s] = 0.0
    for g in range(groups):
        factor = walls.group_magnification[g]
        work.wall_tangent[walls.group_story[g]] += factor * factor * bank.tangent[g]
        work.wall_history[walls.group_story[g]] += factor * bank.history_force[g]
    # 2. Newton-Raphson from u_n; strategies in turn, each from u_n again
    converged, iterations = _newton(row, ground_next, dt, frame, stories, walls.others, newton, out, work)
    if not converged:
        return FAILED, _moved_most(work.correction), iterations
    # 3. commit: stories, then the walls with their drifts (memory advances only now)
    for s in range(n):
        stories.committed[s, 0] = work.drift[s]
        stories.committed[s, 1] = work.trial_state[s]
    for g in range(groups):
        work.wall_deformation[g] = walls.group_magnification[g] * work.drift[walls.group_story[g]]
    kernel.bank_commit(bank, start + step, work.wall_deformation, work.wall_force, work.wall_strain)
    _record_walls(next_row, bank.states, out, work)
    _commit_devices(next_row, walls.others, out)
    u = work.displacement
    for i in range(n):
        increment = u[i] - out.displacement[row, i]
        out.displacement[next_row, i] = u[i]
        out.velocity[next_row, i] = v1 * increment - out.velocity[row, i]
        out.acceleration[next_row, i] = (a0 * increment - (4.0 / dt) * out.velocity[row, i]
                                         - out.acceleration[row, i])
    _record(row, next_row, ground_now, ground_next, frame, stories, out, work, work.old_damping_force)
    # 4. collapse
    if frame.collapse_ratio > 0.0:
        for s in range(n):
            if abs(work.drift[s]) > frame.collapse_ratio * frame.heights[s]:
                return COLLAPSED, s, iterations
    return RUNNING, 0, iterations


@njit(cache=True, allocates=False)
def replay(drift, dt, stories, walls, out, work):
    """Commit the stories and the walls through a drift history as the integrator commits them, and write
    the state of its last row into row 0 of ``out``'s story and wall histories.

    ``drift`` (k + 1, n) mm: every story's drift from rest (row 0) to step k; ``stories``
    :class:`StoryArrays` and ``walls`` :class:`DeviceArrays` at rest (their committed states advance k
    steps); ``out`` :class:`Histories` (row 0 of story_shear, story_wall_force, group_force and
    group_strain is written); ``work`` :class:`Scratch` of the building.  A frame with fractional walls
    and hysteretic stories is hereditary: its state is its history, so committing the same drifts
    reproduces the states the analysis reached.
    ``dt`` (s): the step (the devices' Newmark velocities).  Returns the devices' work over the history (N*mm,
    trapezoidal increments, as the integrator's energy); row 0 of the other devices' histories is their state.
    """
    steps, n = drift.shape
    groups = walls.group_story.shape[0]
    deformation, force, strain = work.wall_deformation, work.wall_force, work.wall_strain
    story_wall = work.story_total
    for s in range(n):
        out.story_wall_force[0, s] = 0.0
    wall_work = 0.0
    for j in range(1, steps):
        for s in range(n):
            out.story_shear[0, s], _, value = story_trial(stories, s, drift[j, s])
            stories.committed[s, 0] = drift[j, s]
            stories.committed[s, 1] = value
        for g in range(groups):
            deformation[g] = walls.group_magnification[g] * drift[j, walls.group_story[g]]
        kernel.bank_commit(walls.bank, j - 1, deformation, force, strain)
        for s in range(n):
            story_wall[s] = 0.0
        _replay_devices(walls.others, drift[j], dt, work)
        for g in range(groups):
            story_wall[walls.group_story[g]] += walls.group_magnification[g] * force[g]
            out.group_force[0, g] = force[g]
            out.group_strain[0, g] = strain[g]
        for s in range(n):
            wall_work += 0.5 * (story_wall[s] + out.story_wall_force[0, s]) * (drift[j, s] - drift[j - 1, s])
            out.story_wall_force[0, s] = story_wall[s]
    _record_devices(0, walls.others, out)
    return wall_work


@njit(cache=True, inline="always")
def _record(row, next_row, ground_now, ground_next, frame, stories, out, work, old_damping_force):
    """Outputs and energies of the converged step into row ``next_row`` (trapezoidal work increments); row
    ``row`` of the outputs holds the previous step's values; ``ground_now``, ``ground_next`` (mm/s^2) the
    ground accelerations of both."""
    n = work.drift.shape[0]
    masses, geometric = frame.masses, frame.geometric
    kinetic = 0.0
    recoverable = 0.0
    input_work = 0.0
    story_work = 0.0
    damping_work = 0.0
    wall_work = 0.0
    geometric_work = 0.0
    story1_damping = 0.0  # the damping force through story 1: 1^T C_s v
    for i in range(n):
        story1_damping += frame.story_damping_row[i] * out.velocity[next_row, i]
    for s in range(n):
        drift = work.drift[s]
        wall_force = work.story_total[s] - work.story_force[s] - geometric[s] * drift
        change = drift - out.drift[row, s]
        story_work += 0.5 * (work.story_force[s] + out.story_shear[row, s]) * change
        wall_work += 0.5 * (wall_force + out.story_wall_force[row, s]) * change
        geometric_work += 0.5 * geometric[s] * (drift + out.drift[row, s]) * change
        recoverable += 0.5 * work.story_force[s] ** 2 / stories.parameters[s, 0]
        out.story_shear[next_row, s] = work.story_force[s]
        out.story_wall_force[next_row, s] = wall_force
        out.drift[next_row, s] = drift
    for i in range(n):
        change = out.displacement[next_row, i] - out.displacement[row, i]
        kinetic += 0.5 * masses[i] * out.velocity[next_row, i] ** 2
        input_work -= 0.5 * masses[i] * (ground_next + ground_now) * change
        damping_work += 0.5 * (work.damping_force[i] + old_damping_force[i]) * change
        old_damping_force[i] = work.damping_force[i]
    out.base_shear[next_row] = work.story_total[0] + story1_damping
    energy = out.energy
    energy[next_row, 0] = energy[row, 0] + input_work
    energy[next_row, 1] = kinetic
    energy[next_row, 2] = recoverable
    energy[next_row, 3] = energy[row, 3] + story_work
    energy[next_row, 4] = energy[row, 4] + damping_work
    energy[next_row, 5] = energy[row, 5] + wall_work
    energy[next_row, 6] = energy[row, 6] + geometric_work
