"""The FDMK step kernel: the one compiled implementation of the element's time stepping.

Everything that advances an FDMK wall in time -- :meth:`FDMKDamper.force`, :class:`DamperState`
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
"""

from __future__ import annotations

import numpy as np

from .._jit import njit

# Reassociation lets LLVM vectorise the sums over the memory; results change by rounding only.  The
# loops index the bank's arrays directly (no views, no calls): in numba a view or an array passed to a
# call costs reference counting, more than the arithmetic of a short memory.  The small per-wall
# functions are inlined into the bank loops for the same reason.
_FAST = {"reassoc", "contract"}


@njit(cache=True, fastmath=_FAST)
def memory_history(window_weights, window, count, mode_weight, mode_state, history):
    """The history sums (2, W) of every wall at step ``count`` into ``history``; the memory is untouched."""
    walls, size = window_weights.shape
    modes = mode_weight.shape[1]
    filled = min(count, size)
    start = count % size + size - filled  # the oldest value still in the window
    first = size - filled
    for w in range(walls):
        for c in range(2):
            total = 0.0
            for k in range(modes):
                total += mode_weight[w, k] * mode_state[w, c, k]
            for i in range(filled):
                total += window_weights[w, first + i] * window[w, c, start + i]
            history[c, w] = total


@njit(cache=True, fastmath=_FAST)
def memory_advance(window_weights, window, count, mode_weight, mode_ratio, mode_state, values, history):
    """Commit step ``count``'s ``values`` (2, W: strain, Maxwell stress) and put the next step's history
    sums into ``history``, in one pass over the modes.  The value leaving the window enters the modes."""
    walls, size = window_weights.shape
    modes = mode_weight.shape[1]
    slot = count % size
    absorb = count >= size
    filled = min(count + 1, size)
    start = (count + 1) % size + size - filled
    first = size - filled
    for w in range(walls):
        for c in range(2):
            leaving = window[w, c, slot]
            total = 0.0
            if absorb:
                for k in range(modes):
                    state = mode_ratio[w, k] * mode_state[w, c, k] + leaving
                    mode_state[w, c, k] = state
                    total += mode_weight[w, k] * state
            window[w, c, slot] = values[c, w]
            window[w, c, slot + size] = values[c, w]
            for i in range(filled):
                total += window_weights[w, first + i] * window[w, c, start + i]
            history[c, w] = total


@njit(cache=True, inline="always")
def fdmk_stress(strain, strain_history, maxwell_history, G1, G2, eta1, eta2, w0):
    """Stress (MPa), Maxwell-branch stress (MPa) and tangent modulus d(stress)/d(strain) (MPa).

    Eq. (3): sigma1 = G1 eps + eta1 D^r eps.  Eq. (4), multiplied by G2:
    G2 sigma2 + eta2 D^r sigma2 = G2 eta2 D^r eps, solved for the current sigma2 with
    D^r x = w0 x_n + history.  Eq. (5): sigma = sigma1 + sigma2.  A Maxwell branch with G2 = 0 or
    eta2 = 0 carries no stress.
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
def wall_affine(constants, w0, strain_history, maxwell_history):
    """(K_t in N/mm, H_n in N): the wall assembly's force this step is K_t d + H_n for deformation d (mm).

    A trial at zero deformation; the memory is untouched.  With a support (flexibility f_s > 0) in
    series: K_t = K_w / (1 + f_s K_w), H_n = H_w / (1 + f_s K_w).
    """
    G1, G2, eta1, eta2, area, thickness, flexibility = (constants[0], constants[1], constants[2], constants[3],
                                                       constants[4], constants[5], constants[6])
    stress, _, modulus = fdmk_stress(0.0, strain_history, maxwell_history, G1, G2, eta1, eta2, w0)
    wall_tangent = modulus * area / thickness
    scale = 1.0 / (1.0 + flexibility * wall_tangent)
    return wall_tangent * scale, stress * area * scale


@njit(cache=True, inline="always")
def wall_response(constants, w0, strain_history, maxwell_history, deformation):
    """(force N, wall strain, Maxwell stress MPa) of a wall assembly at ``deformation`` (mm) this step.

    The wall's own deformation is the assembly's minus the support's: d_w = (d - f_s H_w) / (1 + f_s K_w).
    """
    G1, G2, eta1, eta2, area, thickness, flexibility = (constants[0], constants[1], constants[2], constants[3],
                                                       constants[4], constants[5], constants[6])
    wall_deformation = deformation
    if flexibility > 0.0:
        history_stress, _, modulus = fdmk_stress(0.0, strain_history, maxwell_history, G1, G2, eta1, eta2, w0)
        wall_deformation = ((deformation - flexibility * history_stress * area)
                            / (1.0 + flexibility * modulus * area / thickness))
    strain = wall_deformation / thickness
    stress, maxwell, _ = fdmk_stress(strain, strain_history, maxwell_history, G1, G2, eta1, eta2, w0)
    return stress * area, strain, maxwell


@njit(cache=True)
def bank_affine(constants, w0, window_weights, window, count, mode_weight, mode_state, history, tangent,
                history_force):
    """Every wall of a bank at the start of step ``count``: history sums (2, W), K_t (N/mm), H_n (N)."""
    memory_history(window_weights, window, count, mode_weight, mode_state, history)
    for d in range(constants.shape[0]):
        tangent[d], history_force[d] = wall_affine(constants[d], w0[d], history[0, d], history[1, d])


@njit(cache=True)
def bank_commit(constants, w0, window_weights, window, count, mode_weight, mode_ratio, mode_state, history,
                values, deformation, force, strain, tangent, history_force):
    """Accept ``deformation`` (mm, per wall) for step ``count``: forces (N) and wall strains out, memory
    advanced, and the next step's history sums, K_t and H_n (as :func:`bank_affine` would give them).
    ``values`` (2, W) is scratch space."""
    for d in range(constants.shape[0]):
        force[d], strain[d], values[1, d] = wall_response(constants[d], w0[d], history[0, d], history[1, d],
                                                          deformation[d])
        values[0, d] = strain[d]
    memory_advance(window_weights, window, count, mode_weight, mode_ratio, mode_state, values, history)
    for d in range(constants.shape[0]):
        tangent[d], history_force[d] = wall_affine(constants[d], w0[d], history[0, d], history[1, d])


@njit(cache=True)
def displacement_driven(constants, w0, window_weights, window, mode_weight, mode_ratio, mode_state, displacement):
    """(force N, wall strain) histories of one wall assembly (a bank of W = 1) for a displacement history
    (mm) from rest: :func:`bank_commit` step after step."""
    steps = displacement.shape[0]
    force = np.empty(steps)
    strain = np.empty(steps)
    history = np.zeros((2, 1))  # at rest
    values = np.zeros((2, 1))
    tangent = np.zeros(1)
    history_force = np.zeros(1)
    for n in range(steps):
        bank_commit(constants, w0, window_weights, window, n, mode_weight, mode_ratio, mode_state, history, values,
                    displacement[n:n + 1], force[n:n + 1], strain[n:n + 1], tangent, history_force)
    return force, strain
