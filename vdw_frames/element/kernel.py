"""The FDMK step kernel: the one compiled implementation of the element's time stepping.

Everything that advances an FDMK wall in time -- :meth:`FDMKDamper.force`, :class:`WallState`
(trial/commit), the frame integrator and the OpenSees bridge -- calls these functions, on a *bank* of
W walls (W = 1 for one wall).

Memory of a bank (one row per wall, each wall's values contiguous):

``window_weights`` (W, L)     the convolution weights w_L, ..., w_1 of D^r in that (reversed) order,
                              scaled by dt^-r (s^-r); w_0 is passed separately, ``w0`` (W,)

``window``         (W, 2, 2L) the last L committed values of the two channels that carry memory, [:, 0] the
                              strain, [:, 1] the Maxwell-branch stress (MPa); each value is written twice,
                              at slot n mod L and n mod L + L, so that the last L values always lie
                              contiguous, oldest first, at [n mod L, n mod L + L)

``mode_weight`` (W, K), ``mode_ratio`` (W, K), ``mode_state`` (W, 2, K)
                              an optional exponential (geometric) representation of the weights beyond the
                              window, w_j ~= sum_k c_k rho_k^j for j > L, with mode_weight = c_k rho_k^(L+1);
                              a wall with fewer modes is padded with inert zero modes.  K = 0 and L >= the
                              number of steps gives the exact full-history convolution;
                              :mod:`vdw_frames.element.fast_memory` builds L = 16 and K = 24-68 modes.

``history``        (2, W)     the history sums of the coming step

The history at step n (``count`` = n committed steps) of channel c is
``sum_{j=1}^{min(n, L)} w_j x_c[n-j] + sum_k mode_weight_k * mode_state_c,k``; a value leaving the window
is absorbed into the modes as S_k <- rho_k S_k + x_{n-L}.

Wall constants (``constants``, one row of 7 per wall): G1, G2 (MPa), eta1, eta2 (MPa*s^r), area (mm^2),
thickness (mm) and the flexibility 1/k_s (mm/N) of a support in series with the wall (0: rigid).

Within one step a wall's force is affine in its deformation, F = K_t d + H_n: the tangent K_t is
constant and H_n is fixed by the committed memory.  A support in series keeps it affine: the wall's
own deformation d_w solves K_w d_w + H_w = (d - d_w) / f_s, so d_w = (d - f_s H_w) / (1 + f_s K_w) in
closed form, and the wall's memory sees d_w, not d.

The wall's state beyond its memory (:class:`WallStates`: temperature, dissipated heat, stored energy,
amplitude, failure) changes only at commit, in :func:`update_walls`, after the memory has advanced: the
step's heat from the diffusive representation of :mod:`vdw_frames.element.thermal`, the temperature, the
limits, the amplitude, and the coefficients of the *next* step (those at the followed amplitude, eta1 and
eta2 times a_T(T)^r at the committed temperature: an explicit coupling with a one-step lag).  The
convolution weights depend only on r and dt, so the memory is the same whatever the coefficients do; a
wall that follows neither temperature nor amplitude keeps its coefficients and runs the same code.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from .._jit import njit

# Reassociation lets LLVM vectorise the sums over the memory; results change by rounding only.  The
# functions a step runs are compiled without numba's reference counting (allocates=False, _jit.njit): an
# array an inlined helper takes would otherwise cost two atomic operations a call, more than the
# arithmetic of a short memory.  The commit is inlined into the integrators that call it every step, as
# are the small per-wall functions into the bank loops.
_FAST = {"reassoc", "contract"}


def _group(fields: dict[str, str]) -> np.dtype:
    """The record of a state group: one float64 a field, in the order of ``fields`` (name: what it is)."""
    return np.dtype([(name, np.float64) for name in fields], align=True)


# The state groups of a wall, by concept (what the wall is, its temperature, its energies, its limits, its amplitude):
# each a record of named floats, the five together one record a wall (WALL).  Compiled code reads a field of wall w as
# walls[w].thermal.temperature, a load at a fixed offset as a column of one table was; Python reads
# WallStates.thermal.temperature, (W,).  One record array, not a NamedTuple of (W,) arrays: a compiled call from
# Python unboxes every array it is given (about 0.2 us each; WallBank.commit calls once a step), and the update
# reading five separate arrays measured up to ~10 % slower than one.
BASE_FIELDS = {
    "tracked": "1 when the wall's state is followed (a thermal description, limits or amplitude following)",
    "energy_followed": "1 when its heat and stored energy are (a thermal description or limits: the diffusive nodes)",
    "limited": "1 when the wall has limits",
    "heating_only": "1 when its temperature is all that is followed (a thermal description, no limits, fixed "
                    "parameters otherwise): the update takes it straight through",
    "g1": "G1 (MPa) at the reference temperature (a wall of fixed parameters)",
    "g2": "G2 (MPa) at the reference temperature",
    "eta1": "eta1 (MPa s^r) at the reference temperature",
    "eta2": "eta2 (MPa s^r) at the reference temperature",
    "order": "r (-)",
    "node_set": "the wall's set of diffusive nodes (WallStates.nodes: one set for every order r of the bank's "
                "followed walls)",
}
THERMAL_FIELDS = {
    "law_kind": "the shift law's kind (0: none; thermal.thermal_row)",
    "law_slope": "its slope (1/K): log10 a_T = -slope (T - T_ref) / (1 + curvature (T - T_ref))",
    "law_curvature": "its curvature (1/K)",
    "law_reference": "its reference temperature T_ref (degC)",
    "capacity": "rho c V (N*mm/K)",
    "ambient": "the ambient temperature (degC)",
    "decay": "exp(-dt / tau) (-)",
    "gain": "(tau / dt)(1 - exp(-dt / tau)) / (rho c V) (K per N*mm)",
    "valid_low": "the low end of the shift law's validity range (degC)",
    "valid_high": "its high end (degC)",
    "shift_rate": "ln(10) r slope (1/K): -d(ln a_T^r)/dT at T_ref",
    "temperature": "the wall's temperature (degC; NaN without a thermal description)",
    "outside": "the first step outside the shift law's range (-1: none)",
    "shift_anchor": "an exponent ln a_T^r from which nearby factors are found (NaN: none yet)",
    "shift_factor": "its exp",
}
ENERGY_FIELDS = {
    "heat": "N*mm dissipated since rest",
    "stored": "N*mm stored",
    "released": "N*mm lost at failure",
    "released_work": "N*mm: the work done on a failed wall's failing share over the step after its failing commit, "
                     "as its force fell to the residual (booked at that step: update_walls)",
    "parameter_loss": "N*mm of the wall's stored energy lost, at no work, as its parameters changed with temperature "
                      "or amplitude: positive as it softens",
    "springpot_heat_1": "the Kelvin springpot's heat over the last committed step, per unit volume and unit "
                        "viscosity (MPa; _springpots)",
    "springpot_heat_2": "the Maxwell springpot's",
    "springpot_stored_1": "the Kelvin springpot's stored energy after it, per unit volume and unit viscosity (MPa)",
    "springpot_stored_2": "the Maxwell springpot's",
    "previous_strain": "the Kelvin springpot's input eps at the last commit",
    "previous_dashpot_strain": "the Maxwell springpot's input eps_v at the last commit",
    "tail_dashpot": "the diffusive representation's dashpot tail (s^(1-r)) over dt",
    "tail_spring": "its spring tail (s^-r)",
    "node_work_sum": "sum_k c_k D_k of the diffusive nodes (WallStates.nodes)",
    "node_square_1": "sum_k c_k phi_k^2 of the Kelvin springpot at the last commit",
    "node_square_2": "the same of the Maxwell springpot",
}
LIMITS_FIELDS = {
    "limit_strain": "the strain limit (-; inf: none)",
    "limit_stress": "the stress limit (MPa; inf: none)",
    "limit_temperature": "the temperature limit (degC; inf: none)",
    "residual": "the force factor after failure",
    "failure_step": "the step from which the wall has failed (-1: intact)",
    "failure_mode": "FAILURE_MODES index",
    "failure_force": "the wall's force (N) at its failing commit",
    "failure_deformation": "its deformation (mm) at its failing commit",
    "scale": "the force factor now (1 unless the wall has failed)",
}
TRACKER_FIELDS = {
    "amplitude_nodes": "K, the amplitude table's nodes (0 for fixed parameters)",
    "turn": "the strain at the last reversal",
    "extreme": "the extreme of the current half-cycle",
    "direction": "+1, -1, 0 at rest",
    "last_amplitude": "the amplitude of the last completed half-cycle",
    "amplitude": "the one the parameters follow",
    "below_range": "steps spent below the table's range",
    "above_range": "steps spent above it",
    "followed_at_turn": "the amplitude followed when the last reversal was confirmed",
    "confirmed_at": "the step at which it was confirmed",
    "half_steps": "the steps between the last two confirmed reversals (0: none yet)",
    "extended_at": "the step the current half-cycle's extreme was last reached",
    "amplitude_low": "the amplitude table's range (-): its low end",
    "amplitude_high": "its high end",
    "amplitude_used": "the amplitude the coefficients were last interpolated at (reused while the amplitude stays)",
    "at_g1": "G1 there (MPa)",
    "at_g2": "G2 there (MPa)",
    "at_eta1": "eta1 there (MPa s^r)",
    "at_eta2": "eta2 there (MPa s^r)",
}
BASE = _group(BASE_FIELDS)
"""What a wall is: its followed aspects and its base parameters (:data:`BASE_FIELDS`)."""
THERMAL = _group(THERMAL_FIELDS)
"""A wall's temperature and its shift law (:data:`THERMAL_FIELDS`, :func:`vdw_frames.element.thermal.thermal_row`)."""
ENERGY = _group(ENERGY_FIELDS)
"""A wall's heat and stored energy, and the diffusive representation's sums they come from (:data:`ENERGY_FIELDS`)."""
LIMITS = _group(LIMITS_FIELDS)
"""A wall's limits and its failure (:data:`LIMITS_FIELDS`)."""
TRACKER = _group(TRACKER_FIELDS)
"""The amplitude tracker of an amplitude-following wall (:data:`TRACKER_FIELDS`, :func:`track_amplitude`)."""
FAILURE_MODES = ("", "strain", "stress", "temperature")
"""Names of the failure_mode field (LIMITS)."""


WALL = np.dtype([("base", BASE), ("thermal", THERMAL), ("energy", ENERGY), ("limits", LIMITS), ("tracker", TRACKER)],
                align=True)
"""A wall's state beyond its memory: its five state groups, each a record of named fields."""
GROUPS = {"base": BASE_FIELDS, "thermal": THERMAL_FIELDS, "energy": ENERGY_FIELDS, "limits": LIMITS_FIELDS,
          "tracker": TRACKER_FIELDS}
"""The fields of every state group, by group: name -> what it is."""


def wall_records(walls: int) -> np.ndarray:
    """The states of ``walls`` walls, every field 0: a (W,) array of :data:`WALL` records.  A plain ndarray, not a
    np.recarray: numba types a subclass the slow way, about a microsecond more a call from Python."""
    return np.zeros(walls, WALL)


class WallStates(NamedTuple):
    """Every wall's state beyond its memory (W walls, N diffusive nodes, K amplitude nodes), changed only by
    :func:`update_walls`.  ``walls[w].thermal.temperature`` in compiled code; ``states.thermal.temperature``
    (W,) in Python (the properties below: views of ``walls``, not copies)."""

    walls: np.ndarray  # (W,) of WALL: the state groups of every wall
    # (S, 4, N): e, g, c_k g, c_k of every node (thermal.node_coefficients, diffusive_weights), one set for each
    # order r (base.node_set): walls of one order share theirs, which keeps the update's data small
    nodes: np.ndarray
    node_state: np.ndarray  # (W, 2, N): phi of the Kelvin (eps) and Maxwell (eps_v) springpots
    amplitude_table: np.ndarray  # (W, K, 5): log strain, G1, G2, eta1, eta2 at the amplitude nodes

    @property
    def base(self) -> np.recarray:
        """What each wall is (:data:`BASE_FIELDS`), (W,)."""
        return self.walls["base"].view(np.recarray)

    @property
    def thermal(self) -> np.recarray:
        """Each wall's temperature and shift law (:data:`THERMAL_FIELDS`), (W,)."""
        return self.walls["thermal"].view(np.recarray)

    @property
    def energy(self) -> np.recarray:
        """Each wall's heat and stored energy (:data:`ENERGY_FIELDS`), (W,)."""
        return self.walls["energy"].view(np.recarray)

    @property
    def limits(self) -> np.recarray:
        """Each wall's limits and failure (:data:`LIMITS_FIELDS`), (W,)."""
        return self.walls["limits"].view(np.recarray)

    @property
    def tracker(self) -> np.recarray:
        """Each wall's amplitude tracker (:data:`TRACKER_FIELDS`), (W,)."""
        return self.walls["tracker"].view(np.recarray)


class MemoryArrays(NamedTuple):
    """The fractional memory of a bank of W walls (shapes in the module docstring): a window of L steps, K modes."""

    w0: np.ndarray  # (W,): w_0 dt^-r
    window_weights: np.ndarray  # (W, L): w_L .. w_1, dt^-r
    window: np.ndarray  # (W, 2, 2L): strain and Maxwell stress, each written twice
    mode_weight: np.ndarray  # (W, K)
    mode_ratio: np.ndarray  # (W, K)
    mode_state: np.ndarray  # (W, 2, K)
    history: np.ndarray  # (2, W): the coming step's history sums
    values: np.ndarray  # (2, W): the committed step's strain and Maxwell stress


class BankArrays(NamedTuple):
    """The arrays of a bank of W walls, as the compiled functions take them."""

    constants: np.ndarray  # (W, 7): G1, G2, eta1, eta2, area, thickness, support flexibility
    memory: MemoryArrays
    tangent: np.ndarray  # (W,): K_t of the coming step, N/mm
    history_force: np.ndarray  # (W,): H_n of the coming step, N
    states: WallStates
    followed: bool  # some wall's state is followed (walls.base.tracked): only then is there any to update


@njit(cache=True, fastmath=_FAST, allocates=False)
def memory_history(memory, count):
    """The history sums of every wall at step ``count`` into ``memory.history`` (2, W); the memory is untouched."""
    walls, size = memory.window_weights.shape
    modes = memory.mode_weight.shape[1]
    filled = min(count, size)
    start = count % size + size - filled  # the oldest value still in the window
    first = size - filled
    for w in range(walls):
        for c in range(2):
            total = 0.0
            for k in range(modes):
                total += memory.mode_weight[w, k] * memory.mode_state[w, c, k]
            for i in range(filled):
                total += memory.window_weights[w, first + i] * memory.window[w, c, start + i]
            memory.history[c, w] = total


@njit(cache=True, fastmath=_FAST, allocates=False)
def memory_advance(memory, count):
    """Commit step ``count``'s ``memory.values`` (2, W: strain, Maxwell stress) and put the next step's history
    sums into ``memory.history``, in one pass over the modes.  The value leaving the window enters the modes."""
    walls, size = memory.window_weights.shape
    modes = memory.mode_weight.shape[1]
    slot = count % size
    absorb = count >= size
    filled = min(count + 1, size)
    start = (count + 1) % size + size - filled
    first = size - filled
    window, mode_state = memory.window, memory.mode_state
    for w in range(walls):
        for c in range(2):
            leaving = window[w, c, slot]
            total = 0.0
            if absorb:
                for k in range(modes):
                    state = memory.mode_ratio[w, k] * mode_state[w, c, k] + leaving
                    mode_state[w, c, k] = state
                    total += memory.mode_weight[w, k] * state
            window[w, c, slot] = memory.values[c, w]
            window[w, c, slot + size] = memory.values[c, w]
            for i in range(filled):
                total += memory.window_weights[w, first + i] * window[w, c, start + i]
            memory.history[c, w] = total


@njit(cache=True, inline="always")
def fdmk_stress(strain, strain_history, maxwell_history, G1, G2, eta1, eta2, w0):
    """Stress (MPa), Maxwell-branch stress (MPa) and tangent modulus d(stress)/d(strain) (MPa).

    Eq. (3): sigma1 = G1 eps + eta1 D^r eps.  Eq. (4), multiplied by G2:
    G2 sigma2 + eta2 D^r sigma2 = G2 eta2 D^r eps, solved for the current sigma2 with
    D^r x = w0 x_n + history.  Eq. (5): sigma = sigma1 + sigma2.  A Maxwell branch with G2 = 0 or
    eta2 = 0 carries no stress.  (Scalars: the innermost function of every path.)
    """
    rate = w0 * strain + strain_history  # discrete D^r eps at this step
    stress = G1 * strain + eta1 * rate
    tangent = G1 + eta1 * w0
    maxwell = 0.0
    if G2 > 0.0 and eta2 > 0.0:
        denominator = G2 + eta2 * w0
        maxwell = (G2 * eta2 * rate - eta2 * maxwell_history) / denominator
        tangent += G2 * eta2 * w0 / denominator
    return stress + maxwell, maxwell, tangent


@njit(cache=True, inline="always")
def wall_affine(bank, w):
    """(K_t in N/mm, H_n in N) of wall ``w``: its force this step is K_t d + H_n for deformation d (mm).

    A trial at zero deformation; the memory is untouched.  With a support (flexibility f_s > 0) in
    series: K_t = K_w / (1 + f_s K_w), H_n = H_w / (1 + f_s K_w).
    """
    c = bank.constants[w]
    area, thickness, flexibility = c[4], c[5], c[6]
    stress, _, modulus = fdmk_stress(0.0, bank.memory.history[0, w], bank.memory.history[1, w], c[0], c[1], c[2], c[3],
                                     bank.memory.w0[w])
    factor = bank.states.walls[w].limits.scale  # 1 unless the wall has failed
    stress *= factor
    wall_tangent = factor * modulus * area / thickness
    scale = 1.0 / (1.0 + flexibility * wall_tangent)
    return wall_tangent * scale, stress * area * scale


@njit(cache=True, inline="always")
def wall_response(bank, w, deformation):
    """(force N, wall strain, Maxwell stress MPa) of wall ``w`` at ``deformation`` (mm) this step.

    The wall's own deformation is the assembly's minus the support's: d_w = (d - f_s H_w) / (1 + f_s K_w).
    """
    c = bank.constants[w]
    G1, G2, eta1, eta2, area, thickness, flexibility = c[0], c[1], c[2], c[3], c[4], c[5], c[6]
    strain_history, maxwell_history, w0 = bank.memory.history[0, w], bank.memory.history[1, w], bank.memory.w0[w]
    factor = bank.states.walls[w].limits.scale  # 1 unless the wall has failed
    wall_deformation = deformation
    if flexibility > 0.0:
        history_stress, _, modulus = fdmk_stress(0.0, strain_history, maxwell_history, G1, G2, eta1, eta2, w0)
        wall_deformation = ((deformation - flexibility * factor * history_stress * area)
                            / (1.0 + flexibility * factor * modulus * area / thickness))
    strain = wall_deformation / thickness
    stress, maxwell, _ = fdmk_stress(strain, strain_history, maxwell_history, G1, G2, eta1, eta2, w0)
    return factor * stress * area, strain, maxwell


@njit(cache=True, inline="always")
def _springpots(nodes, node_state, energy, n, w, strain, strain_v):
    """(heat of the Kelvin springpot, of the Maxwell one, their stored energies), each per unit volume and
    unit viscosity (times eta: MPa = N*mm/mm^3), over the step that took their inputs to ``strain`` (eps)
    and ``strain_v`` (eps_v), from the diffusive nodes of wall ``w`` (nodes (S, 4, N): its set ``n``,
    base.node_set; node_state (W, 2, N); ``energy``: the wall's ENERGY record), each node exactly for an input
    linear over the step (thermal.node_coefficients), the tails in closed form.  Advances the nodes.

    A node's heat over the step is its work less the change of its stored energy,
    c (g phi dx + D dx^2) - c (phi'^2 - phi^2) / 2 (thermal module docstring): two sums a node, the stored
    energy before the step kept from the last (node_square_*).  It is a positive semi-definite form of
    (phi, dx); the sums are clipped at 0 against rounding: an adiabatic wall never cools."""
    dx = strain - energy.previous_strain
    dv = strain_v - energy.previous_dashpot_strain
    work_1 = 0.0
    work_2 = 0.0
    square_1 = 0.0
    square_2 = 0.0
    # Separate passes (reads, then updates, then reads): measured faster than one fused pass.
    count = nodes.shape[2]
    for k in range(count):
        work_1 += nodes[n, 2, k] * node_state[w, 0, k]
        work_2 += nodes[n, 2, k] * node_state[w, 1, k]
    for k in range(count):
        node_state[w, 0, k] = nodes[n, 0, k] * node_state[w, 0, k] + nodes[n, 1, k] * dx
    for k in range(count):
        node_state[w, 1, k] = nodes[n, 0, k] * node_state[w, 1, k] + nodes[n, 1, k] * dv
    for k in range(count):
        square_1 += nodes[n, 3, k] * node_state[w, 0, k] * node_state[w, 0, k]
        square_2 += nodes[n, 3, k] * node_state[w, 1, k] * node_state[w, 1, k]
    heat_1 = dx * (work_1 + dx * energy.node_work_sum) - 0.5 * (square_1 - energy.node_square_1)
    heat_2 = dv * (work_2 + dv * energy.node_work_sum) - 0.5 * (square_2 - energy.node_square_2)
    dashpot, spring = energy.tail_dashpot, energy.tail_spring
    energy.previous_strain = strain
    energy.previous_dashpot_strain = strain_v
    energy.node_square_1 = square_1
    energy.node_square_2 = square_2
    return (max(heat_1, 0.0) + dashpot * dx * dx, max(heat_2, 0.0) + dashpot * dv * dv,
            0.5 * (square_1 + spring * strain * strain), 0.5 * (square_2 + spring * strain_v * strain_v))


@njit(cache=True, inline="always")
def _shift_factor(thermal, count):
    """a_T^r (-) of a wall (``thermal``: its THERMAL record) at its committed temperature, clamped to its shift law's
    range (the first step outside it is noted, ``outside``), found from the last exp taken where the exponent has
    moved little.

    The exponent ln a_T^r = -(ln 10 r slope) d / (1 + curvature d), d = T - T_ref, is every law of
    :mod:`~vdw_frames.element.thermal` (thermal.log10_shift); a log-linear law has no curvature and so no
    division.  Near the anchor, exp(anchor + x) = exp(anchor) exp(x) with the series of exp(x) to x^4 (|x| <=
    1e-3: x^5 / 120 < 1e-17, within an ulp; Estrin's grouping, a shorter chain than Horner's)."""
    temperature = thermal.temperature
    clamped = min(max(temperature, thermal.valid_low), thermal.valid_high)
    if clamped != temperature and thermal.outside < 0.0:
        thermal.outside = count + 1
    difference = clamped - thermal.law_reference
    exponent = -thermal.shift_rate * difference
    curvature = thermal.law_curvature
    if curvature != 0.0:
        exponent /= 1.0 + curvature * difference
    x = exponent - thermal.shift_anchor
    if abs(x) <= 1e-3:
        x2 = x * x
        return thermal.shift_factor * ((1.0 + x) + x2 * ((0.5 + x * (1.0 / 6.0)) + x2 * (1.0 / 24.0)))
    factor = math.exp(exponent)  # (the first call too: the anchor starts as NaN)
    thermal.shift_anchor = exponent
    thermal.shift_factor = factor
    return factor


@njit(cache=True, fastmath=_FAST, allocates=False)
def _interpolate_amplitude(tracker, amplitude_table, w):
    """G1, G2, eta1, eta2 of amplitude-following wall ``w`` at its amplitude into at_* of ``tracker`` (its TRACKER
    record; ``amplitude_table`` (W, K, 5): linear in log strain between the nodes, the end node's outside them).  Not
    inlined: it runs only when the followed amplitude has moved, and the update's loop stays short without it
    (compiled with the update's own floating-point flags, as it was when inlined)."""
    count = int(tracker.amplitude_nodes)
    amplitude = tracker.amplitude
    x = math.log(max(amplitude, 1e-300))
    k = 0
    while k < count - 2 and x > amplitude_table[w, k + 1, 0]:
        k += 1
    low, high = amplitude_table[w, k, 0], amplitude_table[w, k + 1, 0]
    t = min(max((x - low) / (high - low), 0.0), 1.0)
    tracker.at_g1 = amplitude_table[w, k, 1] + t * (amplitude_table[w, k + 1, 1] - amplitude_table[w, k, 1])
    tracker.at_g2 = amplitude_table[w, k, 2] + t * (amplitude_table[w, k + 1, 2] - amplitude_table[w, k, 2])
    tracker.at_eta1 = amplitude_table[w, k, 3] + t * (amplitude_table[w, k + 1, 3] - amplitude_table[w, k, 3])
    tracker.at_eta2 = amplitude_table[w, k, 4] + t * (amplitude_table[w, k + 1, 4] - amplitude_table[w, k, 4])
    tracker.amplitude_used = amplitude


@njit(cache=True, inline="always")
def set_coefficients(states, constants, w, count):
    """Wall ``w``'s G1, G2, eta1, eta2 (``constants`` (W, 7)) for the step after commit ``count``, at its
    committed amplitude and temperature: the parameters at the amplitude (``states.amplitude_table`` (W, K, 5);
    the base parameters, its BASE record, for a wall of fixed parameters), eta times a_T^r at the temperature
    (:func:`_shift_factor`).  G1 and G2 are written only for a wall that follows its amplitude (nothing else
    changes them).  Returns whether the coefficients follow anything (False: the base parameters, as before)."""
    wall = states.walls[w]
    tracker = wall.tracker
    eta1, eta2 = wall.base.eta1, wall.base.eta2
    follows = False
    if tracker.amplitude_nodes > 0.0:
        if tracker.amplitude != tracker.amplitude_used:  # (held within much of a half-cycle: reuse the last)
            _interpolate_amplitude(tracker, states.amplitude_table, w)
        constants[w, 0] = tracker.at_g1
        constants[w, 1] = tracker.at_g2
        eta1, eta2 = tracker.at_eta1, tracker.at_eta2
        follows = True
    if wall.thermal.law_kind != 0.0:
        factor = _shift_factor(wall.thermal, count)
        eta1 *= factor
        eta2 *= factor
        follows = True
    constants[w, 2] = eta1
    constants[w, 3] = eta2
    return follows


REVERSAL_GATE = 0.05
"""The smallest return, as a share of the half-cycle's amplitude, that can end a half-cycle (the floor of the
decay release in :func:`track_amplitude`): smaller wiggles of the strain are never reversals."""


@njit(cache=True, inline="always")
def track_amplitude(tracker, strain, count):
    """Follow a wall's strain amplitude after commit ``count`` (``strain`` -; ``tracker``: the wall's TRACKER
    record): the ENVELOPE of the total strain, not its ripples.

    Half-cycles run between reversals, a = |extreme - turn| / 2 (an offset of the strain, a residual drift,
    is not amplitude); the first excursion from rest is a quarter cycle, a = |extreme|.  A reversal is
    confirmed only when the strain has come back across the centre of the half-cycle in progress, by more
    than a = |extreme - turn| / 2 from its extreme: the reversals of a faster component riding on a slower
    one (a higher mode's ripple, smaller than the slow motion's amplitude) do not end half-cycles, so the
    amplitude followed is that of the total strain's envelope, half its peak-to-peak over the slow cycle.
    Decay release: once the extreme has stood longer than a whole cycle, twice the last half-cycle
    (``held`` steps against 2 half_steps), the return needed shrinks as 2 half_steps / held, to
    REVERSAL_GATE a at the least, so a motion that loses more than half its amplitude within a half-cycle
    (or settles about an offset) is still followed down, two to five cycles late.  Where it holds: two
    harmonics a1 sin(w1 t) + a2 sin(w2 t + phi), a2 < a1, are followed by their envelope for every phase
    while the faster one's velocity amplitude is at most three times the slower one's, a2 w2 <= 3 a1 w1
    (checked over 448 cases, phases and steps included); beyond that the strain's own reversals are the
    faster component's, and the tracker may follow them.

    The wall follows the larger of the current half-cycle's amplitude so far and that of the last completed
    one, reached continuously: from the confirmed reversal on, the followed amplitude moves from where it
    was to the completed half-cycle's linearly in time, over as many steps as that half-cycle's confirmation
    took after the one before (half_steps).  So a steady sine of amplitude A gives A at every step after
    its first quarter cycle (the parameters are those of the test at A), a growing motion is followed at
    once, a decaying one about a cycle late, and the parameters never jump (a jump would make the force
    jump: a spurious oscillation).

    Physical reading: the amplitude dependence of a filled elastomer (the Payne effect: the filler network
    breaks down with strain) is governed by the total strain amplitude of the cycle, not by the components
    of a spectral decomposition of the strain; the paper's sets were measured under single sines, where
    the two coincide."""
    direction, turn, extreme = tracker.direction, tracker.turn, tracker.extreme
    if direction == 0.0:
        if strain != turn:
            direction = 1.0 if strain > turn else -1.0
            extreme = strain
            tracker.extended_at = count
    elif direction * (strain - extreme) > 0.0:
        extreme = strain
        tracker.extended_at = count
    else:
        span = 0.5 * abs(extreme - turn)  # the half-cycle's amplitude so far: the return that confirms it
        gate = span
        # The extreme has stood longer than a whole cycle (twice the last half-cycle): a decay.  One
        # half-cycle was too short a wait: a ripple's reversal at start-up shortened it, and the release
        # then ended half-cycles at every ripple (tests/element/test_amplitude.py, the phase sweep).
        held, cycle = count - tracker.extended_at, 2.0 * tracker.half_steps
        if held > cycle > 0.0:
            gate *= max(cycle / held, REVERSAL_GATE)
        if direction * (extreme - strain) > gate:
            first = tracker.last_amplitude == 0.0  # the excursion from rest: a quarter cycle
            tracker.last_amplitude = 2.0 * span if first else span
            tracker.followed_at_turn = tracker.amplitude
            tracker.half_steps = count - tracker.confirmed_at  # >= 1: the turn was set at an earlier step
            tracker.confirmed_at = count
            tracker.extended_at = count
            turn, extreme, direction = extreme, strain, -direction
    tracker.direction, tracker.turn, tracker.extreme = direction, turn, extreme
    completed, before = tracker.last_amplitude, tracker.followed_at_turn
    if completed == 0.0:  # no reversal yet: a quarter cycle from rest
        tracker.amplitude = abs(extreme)
        return
    progress = min((count - tracker.confirmed_at) / tracker.half_steps, 1.0)
    tracker.amplitude = max(0.5 * abs(extreme - turn), before + (completed - before) * progress)


@njit(cache=True, inline="always")
def _follow_amplitude(tracker, strain, count):
    """The amplitude of an amplitude-following wall (``tracker``: its TRACKER record) after commit ``count``, and its
    steps outside its range."""
    if tracker.amplitude_nodes > 0.0:
        track_amplitude(tracker, strain, count)
        if tracker.amplitude < tracker.amplitude_low:
            tracker.below_range += 1.0
        elif tracker.amplitude > tracker.amplitude_high:
            tracker.above_range += 1.0


@njit(cache=True, inline="always")
def _energies(energy, G1, G2, eta2, strain, maxwell):
    """(springs, heat_1, heat_2, stored_1, stored_2) of a wall (``energy``: its ENERGY record) after a commit: the
    energy in its springs (G1 at ``strain``, G2 at the Maxwell stress ``maxwell`` MPa) per unit volume (MPa), and
    its springpots' heat over the step and stored energy after it per unit volume and unit viscosity
    (springpot_*).  A Maxwell branch without G2 or eta2 carries no stress: its terms are 0."""
    springs = 0.5 * G1 * strain * strain
    heat_2 = stored_2 = 0.0
    if G2 > 0.0 and eta2 > 0.0:
        springs += 0.5 * maxwell * maxwell / G2
        heat_2, stored_2 = energy.springpot_heat_2, energy.springpot_stored_2
    return springs, energy.springpot_heat_1, heat_2, energy.springpot_stored_1, stored_2


@njit(cache=True, inline="always")
def _stored(springs, eta1, eta2, stored_1, stored_2, volume):
    """The energy (N*mm) a wall of ``volume`` mm^3 (times its scale after a failure) stores under viscosities ``eta1``,
    ``eta2`` (MPa s^r): its springs' (``springs``, MPa) and its springpots' (per unit volume and viscosity)."""
    return (springs + eta1 * stored_1 + eta2 * stored_2) * volume


@njit(cache=True, inline="always")
def _warm(thermal, heat):
    """A wall's temperature (degC; ``thermal``: its THERMAL record) after a step's ``heat`` (N*mm): T' = T_a
    + (T - T_a) exp(-dt / tau) + gain heat, the exact step of rho c V dT/dt = P - rho c V (T - T_a) / tau for a
    power P constant over it."""
    ambient = thermal.ambient
    thermal.temperature = ambient + (thermal.temperature - ambient) * thermal.decay + heat * thermal.gain


@njit(cache=True, inline="always")
def _exceeded_limit(limits, temperature, strain, force, area):
    """The failure mode of a wall (``limits``: its LIMITS record) at its committed ``strain`` (-), ``force``
    (N) over ``area`` (mm^2) and ``temperature`` (degC): 1 strain, 2 stress, 3 temperature (the first limit
    exceeded, in that order), 0 none."""
    if abs(strain) > limits.limit_strain:
        return 1.0
    if abs(force) > limits.limit_stress * area:
        return 2.0
    if temperature > limits.limit_temperature:
        return 3.0
    return 0.0


@njit(cache=True, fastmath=_FAST, allocates=False)
def update_walls(states, constants, values, force, deformation, count):
    """After the commit of step ``count`` (forces (W,) N and deformations (W,) mm, the memory advanced,
    ``values`` (2, W) the committed strain and Maxwell stress): each followed wall's heat over the step,
    stored energy, temperature, amplitude, limits (``states``: :class:`WallStates`), and the coefficients
    of the next step (``constants`` (W, 7)).  One call a step for the whole bank: a call costs more than a
    wall's update.

    A wall fails at the commit that exceeds a limit: it releases the share (1 - residual) of the energy it
    stores then, and its force is the residual share from the next step on.  Over that next step the force
    the frame sees falls from the intact wall's to the residual's; the trapezoidal work of the frame's
    energy balance counts half the lost share's force over the step's deformation, (1 - residual) F dd / 2,
    and that work goes into the tearing too: it is released, at that step."""
    walls, nodes, node_state = states.walls, states.nodes, states.node_state
    # The springpots of every wall first, then the rest: the walls' node sums are independent, and in a loop of
    # their own they overlap (29.6 -> 24.6 ns a wall and step, the update timed alone; docs/validation.rst).
    for w in range(constants.shape[0]):
        wall = walls[w]
        if wall.base.energy_followed == 0.0:
            continue
        strain_v = 0.0  # the strain of the Maxwell branch's dashpot (none without G2 or eta2)
        if constants[w, 1] > 0.0 and constants[w, 3] > 0.0:
            strain_v = values[0, w] - values[1, w] * (1.0 / constants[w, 1])
        energy = wall.energy
        heat_1, heat_2, stored_1, stored_2 = _springpots(nodes, node_state, energy, int(wall.base.node_set), w,
                                                         values[0, w], strain_v)
        energy.springpot_heat_1, energy.springpot_heat_2 = heat_1, heat_2
        energy.springpot_stored_1, energy.springpot_stored_2 = stored_1, stored_2
    for w in range(constants.shape[0]):
        wall = walls[w]
        base, thermal, energy, limits = wall.base, wall.thermal, wall.energy, wall.limits
        if base.tracked == 0.0:
            continue
        strain, maxwell = values[0, w], values[1, w]
        G1, G2, eta1, eta2 = constants[w, 0], constants[w, 1], constants[w, 2], constants[w, 3]
        volume = constants[w, 4] * constants[w, 5] * limits.scale  # a failed wall keeps its residual share
        # A wall that only heats (the common case) goes straight through: the same steps as the general path below,
        # without its checks (each about half a nanosecond a wall and step; docs/validation.rst, Performance).
        if base.heating_only != 0.0:
            springs, heat_1, heat_2, stored_1, stored_2 = _energies(energy, G1, G2, eta2, strain, maxwell)
            heat = (eta1 * heat_1 + eta2 * heat_2) * volume
            stored = _stored(springs, eta1, eta2, stored_1, stored_2, volume)
            energy.heat += heat
            _warm(thermal, heat)
            factor = _shift_factor(thermal, count)
            eta1, eta2 = base.eta1 * factor, base.eta2 * factor
            constants[w, 2], constants[w, 3] = eta1, eta2
            renewed = _stored(springs, eta1, eta2, stored_1, stored_2, volume)
            energy.parameter_loss += stored - renewed
            energy.stored = renewed
            continue
        limited = base.limited != 0.0
        if limited and limits.failure_step == count:  # the step after the failing commit
            energy.released_work = (0.5 * (1.0 - limits.residual) * limits.failure_force
                                    * (deformation[w] - limits.failure_deformation))
        if base.energy_followed == 0.0:  # a wall that only follows its amplitude: no heat, no energy split
            _follow_amplitude(wall.tracker, strain, count)
            set_coefficients(states, constants, w, count)
            continue
        springs, heat_1, heat_2, stored_1, stored_2 = _energies(energy, G1, G2, eta2, strain, maxwell)
        heat = (eta1 * heat_1 + eta2 * heat_2) * volume
        stored = _stored(springs, eta1, eta2, stored_1, stored_2, volume)
        energy.heat += heat
        if thermal.capacity > 0.0:
            _warm(thermal, heat)
        failing = False
        if limited and limits.failure_step < 0.0:
            mode = _exceeded_limit(limits, thermal.temperature, strain, force[w], constants[w, 4])
            if mode > 0.0:
                failing = True
                limits.failure_step = count + 1
                limits.failure_mode = mode
                energy.released = (1.0 - limits.residual) * stored
                limits.failure_force = force[w]
                limits.failure_deformation = deformation[w]
                limits.scale = limits.residual
                stored *= limits.residual
        _follow_amplitude(wall.tracker, strain, count)
        if not set_coefficients(states, constants, w, count):  # limits only: parameters stay,
            energy.stored = stored                             # and so does the stored energy
            continue
        # The same state stores another energy under the next step's parameters (temperature, amplitude): the
        # difference does no work and warms nothing in this model; it is accounted, not hidden in the heat.
        if constants[w, 0] != G1 or constants[w, 1] != G2:  # (G1 and G2 follow the amplitude only)
            springs = _energies(energy, constants[w, 0], constants[w, 1], constants[w, 3], strain, maxwell)[0]
        renewed = _stored(springs, constants[w, 2], constants[w, 3], stored_1, stored_2,
                          constants[w, 4] * constants[w, 5] * limits.scale)
        if not failing:
            energy.parameter_loss += stored - renewed
        energy.stored = renewed


@njit(cache=True, allocates=False)
def bank_affine(bank, count):
    """Every wall of ``bank`` at the start of step ``count``: history sums, K_t (N/mm) and H_n (N) into
    ``bank.memory.history``, ``bank.tangent`` and ``bank.history_force``."""
    memory_history(bank.memory, count)
    for w in range(bank.constants.shape[0]):
        bank.tangent[w], bank.history_force[w] = wall_affine(bank, w)


@njit(cache=True, inline="always")
def bank_commit(bank, count, deformation, force, strain):
    """Accept ``deformation`` (mm, (W,)) for step ``count``: forces (N, (W,)) and wall strains (-, (W,)) into
    ``force`` and ``strain``, the memory advanced, and the next step's history sums, K_t and H_n (as
    :func:`bank_affine` would give them)."""
    for w in range(bank.constants.shape[0]):
        force[w], strain[w], bank.memory.values[1, w] = wall_response(bank, w, deformation[w])
        bank.memory.values[0, w] = strain[w]
    memory_advance(bank.memory, count)
    if bank.followed:
        update_walls(bank.states, bank.constants, bank.memory.values, force, deformation, count)
    for w in range(bank.constants.shape[0]):
        bank.tangent[w], bank.history_force[w] = wall_affine(bank, w)


@njit(cache=True, allocates=False)
def displacement_driven(bank, displacement, force, strain):
    """The force (N) and wall strain (-) histories, into ``force`` and ``strain`` (steps,), of a one-wall bank
    at rest for a displacement history (mm, (steps,)): :func:`bank_commit` step after step."""
    for n in range(displacement.shape[0]):
        bank_commit(bank, n, displacement[n:n + 1], force[n:n + 1], strain[n:n + 1])
