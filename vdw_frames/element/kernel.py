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


# Columns of WallStates.table: every per-wall scalar of a wall's state, in one row.
(TRACKED, BASE_G1, BASE_G2, BASE_ETA1, BASE_ETA2, ORDER,
 T_KIND, T_SLOPE, T_CURVATURE, T_REFERENCE, T_CAPACITY, T_AMBIENT, T_DECAY, T_GAIN, T_LOW, T_HIGH,
 TEMPERATURE, HEAT, STORED, RELEASED, PARAMETER_LOSS,
 LIMIT_STRAIN, LIMIT_STRESS, LIMIT_TEMPERATURE, RESIDUAL, FAILURE_STEP, FAILURE_MODE, SCALE, OUTSIDE,
 PREVIOUS_STRAIN, PREVIOUS_DASHPOT_STRAIN, TAIL_DASHPOT, TAIL_SPRING,
 AMPLITUDE_NODES, TURN, EXTREME, DIRECTION, LAST_AMPLITUDE, AMPLITUDE, BELOW_RANGE, ABOVE_RANGE,
 NODE_WORK_SUM, FOLLOWED_AT_TURN, CONFIRMED_AT, ENERGY, AMPLITUDE_LOW, AMPLITUDE_HIGH,
 AMPLITUDE_USED, AT_G1, AT_G2, AT_ETA1, AT_ETA2, SHIFT_ANCHOR, SHIFT_FACTOR, NODE_SQUARE_1, NODE_SQUARE_2,
 FAILURE_FORCE, FAILURE_DEFORMATION, RELEASED_WORK, SPRINGPOT_HEAT_1, SPRINGPOT_HEAT_2, SPRINGPOT_STORED_1,
 SPRINGPOT_STORED_2, NODE_SET, SHIFT_RATE, LIMITED, HEATING_ONLY, HALF_STEPS, EXTENDED_AT) = range(69)
STATE_FIELDS = 69
"""TRACKED: 1 when the wall's state is followed (a thermal description, limits or amplitude following);
ENERGY: 1 when its heat and stored energy are (a thermal description or limits: the diffusive nodes);
BASE_*: G1, G2 (MPa), eta1, eta2 (MPa s^r) at the reference temperature (fixed walls); ORDER: r;
T_*: the thermal row (thermal.thermal_row: law kind (0: none), its slope (1/K) and curvature (1/K),
log10 a_T = -slope (T - T_ref) / (1 + curvature (T - T_ref)), and reference T_ref (degC), rho c V
(N*mm/K), ambient (degC), exp(-dt / tau), (tau / dt)(1 - exp(-dt / tau)) / (rho c V) (K per N*mm),
validity range (degC)); SHIFT_RATE (1/K): ln(10) r slope, -d(ln a_T^r)/dT at T_ref;
TEMPERATURE (degC), HEAT (N*mm dissipated since rest), STORED (N*mm), RELEASED (N*mm lost at failure),
PARAMETER_LOSS (N*mm the wall's stored energy lost, at no work, as its parameters changed with
temperature or amplitude: positive as it softens); LIMIT_* (strain -, stress
MPa, temperature degC; inf: none), RESIDUAL (force factor after failure), FAILURE_STEP (-1 intact),
FAILURE_MODE (FAILURE_MODES index), SCALE (force factor now), OUTSIDE (first step outside the shift law's
range, -1); PREVIOUS_*: the springpots' inputs eps, eps_v at the last commit; TAIL_*: the diffusive tails
(dashpot s^(1-r) over dt, spring s^-r); amplitude tracking (amplitude-dependent walls): AMPLITUDE_NODES (K, 0 for
fixed parameters), TURN and EXTREME (strain at the last reversal, extreme of the current half-cycle),
DIRECTION (+1, -1, 0 at rest), LAST_AMPLITUDE (of the last completed half-cycle), AMPLITUDE (the one the
parameters follow), BELOW_RANGE and ABOVE_RANGE (steps spent outside the table's range); NODE_WORK_SUM:
sum_k c_k D_k of the diffusive nodes (WallStates.nodes), NODE_SQUARE_1 and NODE_SQUARE_2: sum_k c_k phi_k^2
of the Kelvin and the Maxwell springpot at the last commit; FOLLOWED_AT_TURN and CONFIRMED_AT: the amplitude
followed, and the step, when the last reversal was confirmed; HALF_STEPS: the steps between the last two
confirmed reversals (0: none yet); EXTENDED_AT: the step the current half-cycle's extreme was last reached;
AMPLITUDE_LOW and AMPLITUDE_HIGH: the amplitude table's range (-); AMPLITUDE_USED and AT_*: the amplitude
the coefficients were last interpolated at and G1, G2, eta1, eta2 there (reused while the amplitude stays);
SHIFT_ANCHOR and SHIFT_FACTOR: an exponent ln a_T^r and its exp (NaN: none yet), from which nearby factors are found;
FAILURE_FORCE (N) and FAILURE_DEFORMATION (mm): the wall's force and deformation at its failing commit;
RELEASED_WORK (N*mm): the work done on its failing share over the next step, as its force fell to the
residual (booked at that step: :func:`update_walls`); SPRINGPOT_HEAT_1 and SPRINGPOT_HEAT_2, SPRINGPOT_STORED_1
and SPRINGPOT_STORED_2: the Kelvin and the Maxwell springpot's heat over the last committed step and their
stored energy after it, per unit volume and unit viscosity (MPa; :func:`_springpots`); NODE_SET: the wall's
set of diffusive nodes (WallStates.nodes: one set for every order r of the bank's followed walls); LIMITED:
1 when the wall has limits; HEATING_ONLY: 1 when its temperature is all that is followed (a thermal
description, no limits, fixed parameters otherwise): the update takes it straight through."""
FAILURE_MODES = ("", "strain", "stress", "temperature")
"""Names of the FAILURE_MODE column."""


class WallStates(NamedTuple):
    """Every wall's state beyond its memory (W walls, N diffusive nodes, K amplitude nodes), changed only by
    :func:`update_walls`."""

    table: np.ndarray  # (W, STATE_FIELDS): the columns above
    # (S, 4, N): e, g, c_k g, c_k of every node (thermal.node_coefficients, diffusive_weights), one set for each
    # order r (table NODE_SET): walls of one order share theirs, which keeps the update's data small
    nodes: np.ndarray
    node_state: np.ndarray  # (W, 2, N): phi of the Kelvin (eps) and Maxwell (eps_v) springpots
    amplitude_table: np.ndarray  # (W, K, 5): log strain, G1, G2, eta1, eta2 at the amplitude nodes


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
    followed: bool  # some wall's state is followed (WallStates.tracked): only then is there any to update


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
    factor = bank.states.table[w, SCALE]  # 1 unless the wall has failed
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
    factor = bank.states.table[w, SCALE]  # 1 unless the wall has failed
    wall_deformation = deformation
    if flexibility > 0.0:
        history_stress, _, modulus = fdmk_stress(0.0, strain_history, maxwell_history, G1, G2, eta1, eta2, w0)
        wall_deformation = ((deformation - flexibility * factor * history_stress * area)
                            / (1.0 + flexibility * factor * modulus * area / thickness))
    strain = wall_deformation / thickness
    stress, maxwell, _ = fdmk_stress(strain, strain_history, maxwell_history, G1, G2, eta1, eta2, w0)
    return factor * stress * area, strain, maxwell


@njit(cache=True, inline="always")
def _springpots(nodes, node_state, table, w, strain, strain_v):
    """(heat of the Kelvin springpot, of the Maxwell one, their stored energies), each per unit volume and
    unit viscosity (times eta: MPa = N*mm/mm^3), over the step that took their inputs to ``strain`` (eps)
    and ``strain_v`` (eps_v), from the diffusive nodes of wall ``w`` (nodes (S, 4, N): its set
    table[w, NODE_SET]; node_state (W, 2, N), table (W, STATE_FIELDS)), each node exactly for an input
    linear over the step (thermal.node_coefficients), the tails in closed form.  Advances the nodes.

    A node's heat over the step is its work less the change of its stored energy,
    c (g phi dx + D dx^2) - c (phi'^2 - phi^2) / 2 (thermal module docstring): two sums a node, the stored
    energy before the step kept from the last (NODE_SQUARE_*).  It is a positive semi-definite form of
    (phi, dx); the sums are clipped at 0 against rounding: an adiabatic wall never cools."""
    dx = strain - table[w, PREVIOUS_STRAIN]
    dv = strain_v - table[w, PREVIOUS_DASHPOT_STRAIN]
    work_1 = 0.0
    work_2 = 0.0
    square_1 = 0.0
    square_2 = 0.0
    # Separate passes (reads, then updates, then reads): measured faster than one fused pass.
    count = nodes.shape[2]
    n = int(table[w, NODE_SET])
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
    heat_1 = dx * (work_1 + dx * table[w, NODE_WORK_SUM]) - 0.5 * (square_1 - table[w, NODE_SQUARE_1])
    heat_2 = dv * (work_2 + dv * table[w, NODE_WORK_SUM]) - 0.5 * (square_2 - table[w, NODE_SQUARE_2])
    dashpot, spring = table[w, TAIL_DASHPOT], table[w, TAIL_SPRING]
    table[w, PREVIOUS_STRAIN] = strain
    table[w, PREVIOUS_DASHPOT_STRAIN] = strain_v
    table[w, NODE_SQUARE_1] = square_1
    table[w, NODE_SQUARE_2] = square_2
    return (max(heat_1, 0.0) + dashpot * dx * dx, max(heat_2, 0.0) + dashpot * dv * dv,
            0.5 * (square_1 + spring * strain * strain), 0.5 * (square_2 + spring * strain_v * strain_v))


@njit(cache=True, inline="always")
def _shift_factor(table, w, count):
    """a_T^r (-) of wall ``w`` at its committed temperature, clamped to its shift law's range (the first step
    outside it is noted, OUTSIDE), found from the last exp taken where the exponent has moved little.

    The exponent ln a_T^r = -(ln 10 r slope) d / (1 + curvature d), d = T - T_ref, is every law of
    :mod:`~vdw_frames.element.thermal` (thermal.log10_shift); a log-linear law has no curvature and so no
    division.  Near the anchor, exp(anchor + x) = exp(anchor) exp(x) with the series of exp(x) to x^4 (|x| <=
    1e-3: x^5 / 120 < 1e-17, within an ulp; Estrin's grouping, a shorter chain than Horner's)."""
    temperature = table[w, TEMPERATURE]
    clamped = min(max(temperature, table[w, T_LOW]), table[w, T_HIGH])
    if clamped != temperature and table[w, OUTSIDE] < 0.0:
        table[w, OUTSIDE] = count + 1
    difference = clamped - table[w, T_REFERENCE]
    exponent = -table[w, SHIFT_RATE] * difference
    curvature = table[w, T_CURVATURE]
    if curvature != 0.0:
        exponent /= 1.0 + curvature * difference
    x = exponent - table[w, SHIFT_ANCHOR]
    if abs(x) <= 1e-3:
        x2 = x * x
        return table[w, SHIFT_FACTOR] * ((1.0 + x) + x2 * ((0.5 + x * (1.0 / 6.0)) + x2 * (1.0 / 24.0)))
    factor = math.exp(exponent)  # (the first call too: the anchor starts as NaN)
    table[w, SHIFT_ANCHOR] = exponent
    table[w, SHIFT_FACTOR] = factor
    return factor


@njit(cache=True, fastmath=_FAST, allocates=False)
def _interpolate_amplitude(table, amplitude_table, w):
    """G1, G2, eta1, eta2 of amplitude-following wall ``w`` at its amplitude into AT_* (``amplitude_table``
    (W, K, 5): linear in log strain between the nodes, the end node's outside them).  Not inlined: it runs
    only when the followed amplitude has moved, and the update's loop stays short without it (compiled with the
    update's own floating-point flags, as it was when inlined)."""
    count = int(table[w, AMPLITUDE_NODES])
    amplitude = table[w, AMPLITUDE]
    x = math.log(max(amplitude, 1e-300))
    k = 0
    while k < count - 2 and x > amplitude_table[w, k + 1, 0]:
        k += 1
    low, high = amplitude_table[w, k, 0], amplitude_table[w, k + 1, 0]
    t = min(max((x - low) / (high - low), 0.0), 1.0)
    for column, field in ((1, AT_G1), (2, AT_G2), (3, AT_ETA1), (4, AT_ETA2)):
        table[w, field] = (amplitude_table[w, k, column]
                           + t * (amplitude_table[w, k + 1, column] - amplitude_table[w, k, column]))
    table[w, AMPLITUDE_USED] = amplitude


@njit(cache=True, inline="always")
def set_coefficients(table, amplitude_table, constants, w, count):
    """Wall ``w``'s G1, G2, eta1, eta2 (``constants`` (W, 7)) for the step after commit ``count``, at its
    committed amplitude and temperature: the parameters at the amplitude (``amplitude_table`` (W, K, 5); the
    base parameters of ``table`` for a wall of fixed parameters), eta times a_T^r at the temperature
    (:func:`_shift_factor`).  G1 and G2 are written only for a wall that follows its amplitude (nothing else
    changes them).  Returns whether the coefficients follow anything (False: the base parameters, as before)."""
    eta1, eta2 = table[w, BASE_ETA1], table[w, BASE_ETA2]
    follows = False
    if table[w, AMPLITUDE_NODES] > 0.0:
        if table[w, AMPLITUDE] != table[w, AMPLITUDE_USED]:  # (held within much of a half-cycle: reuse the last)
            _interpolate_amplitude(table, amplitude_table, w)
        constants[w, 0] = table[w, AT_G1]
        constants[w, 1] = table[w, AT_G2]
        eta1, eta2 = table[w, AT_ETA1], table[w, AT_ETA2]
        follows = True
    if table[w, T_KIND] != 0.0:
        factor = _shift_factor(table, w, count)
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
def track_amplitude(table, w, strain, count):
    """Follow wall ``w``'s strain amplitude after commit ``count`` (``strain`` -): the ENVELOPE of the total
    strain, not its ripples.

    Half-cycles run between reversals, a = |extreme - turn| / 2 (an offset of the strain, a residual drift,
    is not amplitude); the first excursion from rest is a quarter cycle, a = |extreme|.  A reversal is
    confirmed only when the strain has come back across the centre of the half-cycle in progress, by more
    than a = |extreme - turn| / 2 from its extreme: the reversals of a faster component riding on a slower
    one (a higher mode's ripple, smaller than the slow motion's amplitude) do not end half-cycles, so the
    amplitude followed is that of the total strain's envelope, half its peak-to-peak over the slow cycle.
    Decay release: once the extreme has stood longer than a whole cycle, twice the last half-cycle
    (``held`` steps against 2 HALF_STEPS), the return needed shrinks as 2 HALF_STEPS / held, to
    REVERSAL_GATE a at the least, so a motion that loses more than half its amplitude within a half-cycle
    (or settles about an offset) is still followed down, two to five cycles late.  Where it holds: two
    harmonics a1 sin(w1 t) + a2 sin(w2 t + phi), a2 < a1, are followed by their envelope for every phase
    while the faster one's velocity amplitude is at most three times the slower one's, a2 w2 <= 3 a1 w1
    (checked over 448 cases, phases and steps included); beyond that the strain's own reversals are the
    faster component's, and the tracker may follow them.

    The wall follows the larger of the current half-cycle's amplitude so far and that of the last completed
    one, reached continuously: from the confirmed reversal on, the followed amplitude moves from where it
    was to the completed half-cycle's linearly in time, over as many steps as that half-cycle's confirmation
    took after the one before (HALF_STEPS).  So a steady sine of amplitude A gives A at every step after
    its first quarter cycle (the parameters are those of the test at A), a growing motion is followed at
    once, a decaying one about a cycle late, and the parameters never jump (a jump would make the force
    jump: a spurious oscillation).

    Physical reading: the amplitude dependence of a filled elastomer (the Payne effect: the filler network
    breaks down with strain) is governed by the total strain amplitude of the cycle, not by the components
    of a spectral decomposition of the strain; the paper's sets were measured under single sines, where
    the two coincide."""
    direction, turn, extreme = table[w, DIRECTION], table[w, TURN], table[w, EXTREME]
    if direction == 0.0:
        if strain != turn:
            direction = 1.0 if strain > turn else -1.0
            extreme = strain
            table[w, EXTENDED_AT] = count
    elif direction * (strain - extreme) > 0.0:
        extreme = strain
        table[w, EXTENDED_AT] = count
    else:
        span = 0.5 * abs(extreme - turn)  # the half-cycle's amplitude so far: the return that confirms it
        gate = span
        # The extreme has stood longer than a whole cycle (twice the last half-cycle): a decay.  One
        # half-cycle was too short a wait: a ripple's reversal at start-up shortened it, and the release
        # then ended half-cycles at every ripple (tests/element/test_amplitude.py, the phase sweep).
        held, cycle = count - table[w, EXTENDED_AT], 2.0 * table[w, HALF_STEPS]
        if held > cycle > 0.0:
            gate *= max(cycle / held, REVERSAL_GATE)
        if direction * (extreme - strain) > gate:
            first = table[w, LAST_AMPLITUDE] == 0.0  # the excursion from rest: a quarter cycle
            table[w, LAST_AMPLITUDE] = 2.0 * span if first else span
            table[w, FOLLOWED_AT_TURN] = table[w, AMPLITUDE]
            table[w, HALF_STEPS] = count - table[w, CONFIRMED_AT]  # >= 1: the turn was set at an earlier step
            table[w, CONFIRMED_AT] = count
            table[w, EXTENDED_AT] = count
            turn, extreme, direction = extreme, strain, -direction
    table[w, DIRECTION], table[w, TURN], table[w, EXTREME] = direction, turn, extreme
    completed, before = table[w, LAST_AMPLITUDE], table[w, FOLLOWED_AT_TURN]
    if completed == 0.0:  # no reversal yet: a quarter cycle from rest
        table[w, AMPLITUDE] = abs(extreme)
        return
    progress = min((count - table[w, CONFIRMED_AT]) / table[w, HALF_STEPS], 1.0)
    table[w, AMPLITUDE] = max(0.5 * abs(extreme - turn), before + (completed - before) * progress)


@njit(cache=True, inline="always")
def _follow_amplitude(table, w, strain, count):
    """The amplitude of an amplitude-following wall ``w`` after commit ``count``, and its steps outside its
    range."""
    if table[w, AMPLITUDE_NODES] > 0.0:
        track_amplitude(table, w, strain, count)
        if table[w, AMPLITUDE] < table[w, AMPLITUDE_LOW]:
            table[w, BELOW_RANGE] += 1.0
        elif table[w, AMPLITUDE] > table[w, AMPLITUDE_HIGH]:
            table[w, ABOVE_RANGE] += 1.0


@njit(cache=True, inline="always")
def _energies(table, w, G1, G2, eta2, strain, maxwell):
    """(springs, heat_1, heat_2, stored_1, stored_2) of wall ``w`` (``table`` (W, STATE_FIELDS)) after a commit: the
    energy in its springs (G1 at ``strain``, G2 at the Maxwell stress ``maxwell`` MPa) per unit volume (MPa), and
    its springpots' heat over the step and stored energy after it per unit volume and unit viscosity
    (SPRINGPOT_*).  A Maxwell branch without G2 or eta2 carries no stress: its terms are 0."""
    springs = 0.5 * G1 * strain * strain
    heat_2 = stored_2 = 0.0
    if G2 > 0.0 and eta2 > 0.0:
        springs += 0.5 * maxwell * maxwell / G2
        heat_2, stored_2 = table[w, SPRINGPOT_HEAT_2], table[w, SPRINGPOT_STORED_2]
    return springs, table[w, SPRINGPOT_HEAT_1], heat_2, table[w, SPRINGPOT_STORED_1], stored_2


@njit(cache=True, inline="always")
def _stored(springs, eta1, eta2, stored_1, stored_2, volume):
    """The energy (N*mm) a wall of ``volume`` mm^3 (times SCALE after a failure) stores under viscosities ``eta1``,
    ``eta2`` (MPa s^r): its springs' (``springs``, MPa) and its springpots' (per unit volume and viscosity)."""
    return (springs + eta1 * stored_1 + eta2 * stored_2) * volume


@njit(cache=True, inline="always")
def _warm(table, w, heat):
    """Wall ``w``'s temperature (degC) after a step's ``heat`` (N*mm): T' = T_a + (T - T_a) exp(-dt / tau)
    + gain heat, the exact step of rho c V dT/dt = P - rho c V (T - T_a) / tau for a power P constant over it."""
    ambient = table[w, T_AMBIENT]
    table[w, TEMPERATURE] = ambient + (table[w, TEMPERATURE] - ambient) * table[w, T_DECAY] + heat * table[w, T_GAIN]


@njit(cache=True, inline="always")
def _exceeded_limit(table, w, strain, force, area):
    """The failure mode of wall ``w`` at its committed ``strain`` (-) and ``force`` (N) over ``area`` (mm^2):
    1 strain, 2 stress, 3 temperature (the first limit exceeded, in that order), 0 none."""
    if abs(strain) > table[w, LIMIT_STRAIN]:
        return 1.0
    if abs(force) > table[w, LIMIT_STRESS] * area:
        return 2.0
    if table[w, TEMPERATURE] > table[w, LIMIT_TEMPERATURE]:
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
    table, nodes, node_state = states.table, states.nodes, states.node_state
    amplitude_table = states.amplitude_table
    walls = constants.shape[0]
    # The springpots of every wall first, then the rest: the walls' node sums are independent, and in a loop of
    # their own they overlap (29.6 -> 24.6 ns a wall and step, the update timed alone; docs/validation.rst).
    for w in range(walls):
        if table[w, ENERGY] == 0.0:
            continue
        strain_v = 0.0  # the strain of the Maxwell branch's dashpot (none without G2 or eta2)
        if constants[w, 1] > 0.0 and constants[w, 3] > 0.0:
            strain_v = values[0, w] - values[1, w] * (1.0 / constants[w, 1])
        heat_1, heat_2, stored_1, stored_2 = _springpots(nodes, node_state, table, w, values[0, w], strain_v)
        table[w, SPRINGPOT_HEAT_1], table[w, SPRINGPOT_HEAT_2] = heat_1, heat_2
        table[w, SPRINGPOT_STORED_1], table[w, SPRINGPOT_STORED_2] = stored_1, stored_2
    for w in range(walls):
        if table[w, TRACKED] == 0.0:
            continue
        strain, maxwell = values[0, w], values[1, w]
        G1, G2, eta1, eta2 = constants[w, 0], constants[w, 1], constants[w, 2], constants[w, 3]
        volume = constants[w, 4] * constants[w, 5] * table[w, SCALE]  # a failed wall keeps its residual share
        # A wall that only heats (the common case) goes straight through: the same steps as the general path below,
        # without its checks (each about half a nanosecond a wall and step; docs/validation.rst, Performance).
        if table[w, HEATING_ONLY] != 0.0:
            springs, heat_1, heat_2, stored_1, stored_2 = _energies(table, w, G1, G2, eta2, strain, maxwell)
            heat = (eta1 * heat_1 + eta2 * heat_2) * volume
            stored = _stored(springs, eta1, eta2, stored_1, stored_2, volume)
            table[w, HEAT] += heat
            _warm(table, w, heat)
            factor = _shift_factor(table, w, count)
            eta1, eta2 = table[w, BASE_ETA1] * factor, table[w, BASE_ETA2] * factor
            constants[w, 2], constants[w, 3] = eta1, eta2
            renewed = _stored(springs, eta1, eta2, stored_1, stored_2, volume)
            table[w, PARAMETER_LOSS] += stored - renewed
            table[w, STORED] = renewed
            continue
        limited = table[w, LIMITED] != 0.0
        if limited and table[w, FAILURE_STEP] == count:  # the step after the failing commit
            table[w, RELEASED_WORK] = (0.5 * (1.0 - table[w, RESIDUAL]) * table[w, FAILURE_FORCE]
                                       * (deformation[w] - table[w, FAILURE_DEFORMATION]))
        if table[w, ENERGY] == 0.0:  # a wall that only follows its amplitude: no heat, no energy split
            _follow_amplitude(table, w, strain, count)
            set_coefficients(table, amplitude_table, constants, w, count)
            continue
        springs, heat_1, heat_2, stored_1, stored_2 = _energies(table, w, G1, G2, eta2, strain, maxwell)
        heat = (eta1 * heat_1 + eta2 * heat_2) * volume
        stored = _stored(springs, eta1, eta2, stored_1, stored_2, volume)
        table[w, HEAT] += heat
        if table[w, T_CAPACITY] > 0.0:
            _warm(table, w, heat)
        failing = False
        if limited and table[w, FAILURE_STEP] < 0.0:
            mode = _exceeded_limit(table, w, strain, force[w], constants[w, 4])
            if mode > 0.0:
                failing = True
                table[w, FAILURE_STEP] = count + 1
                table[w, FAILURE_MODE] = mode
                table[w, RELEASED] = (1.0 - table[w, RESIDUAL]) * stored
                table[w, FAILURE_FORCE] = force[w]
                table[w, FAILURE_DEFORMATION] = deformation[w]
                table[w, SCALE] = table[w, RESIDUAL]
                stored *= table[w, RESIDUAL]
        _follow_amplitude(table, w, strain, count)
        if not set_coefficients(table, amplitude_table, constants, w, count):  # limits only: parameters stay,
            table[w, STORED] = stored                                          # and so does the stored energy
            continue
        # The same state stores another energy under the next step's parameters (temperature, amplitude): the
        # difference does no work and warms nothing in this model; it is accounted, not hidden in the heat.
        if constants[w, 0] != G1 or constants[w, 1] != G2:  # (G1 and G2 follow the amplitude only)
            springs = _energies(table, w, constants[w, 0], constants[w, 1], constants[w, 3], strain, maxwell)[0]
        renewed = _stored(springs, constants[w, 2], constants[w, 3], stored_1, stored_2,
                          constants[w, 4] * constants[w, 5] * table[w, SCALE])
        if not failing:
            table[w, PARAMETER_LOSS] += stored - renewed
        table[w, STORED] = renewed


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
