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
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .._jit import njit

# Reassociation lets LLVM vectorise the sums over the memory; results change by rounding only.  The
# loops index the bank's arrays directly (no views, no calls): in numba a view or an array passed to a
# call costs reference counting, more than the arithmetic of a short memory.  The small per-wall
# functions are inlined into the bank loops for the same reason.
_FAST = {"reassoc", "contract"}


class BankArrays(NamedTuple):
    """The arrays of a bank of W walls, as the compiled functions take them (shapes in the module docstring):
    W walls, a window of L steps, K modes."""

    constants: np.ndarray  # (W, 7): G1, G2, eta1, eta2, area, thickness, support flexibility
    w0: np.ndarray  # (W,): w_0 dt^-r
    window_weights: np.ndarray  # (W, L): w_L .. w_1, dt^-r
    window: np.ndarray  # (W, 2, 2L): strain and Maxwell stress, each written twice
    mode_weight: np.ndarray  # (W, K)
    mode_ratio: np.ndarray  # (W, K)
    mode_state: np.ndarray  # (W, 2, K)
    history: np.ndarray  # (2, W): the coming step's history sums
    values: np.ndarray  # (2, W): scratch of the commit
    tangent: np.ndarray  # (W,): K_t of the coming step, N/mm
    history_force: np.ndarray  # (W,): H_n of the coming step, N


@njit(cache=True, fastmath=_FAST)
def memory_history(bank, count):
    """The history sums of every wall at step ``count`` into ``bank.history`` (2, W); the memory is untouched."""
    walls, size = bank.window_weights.shape
    modes = bank.mode_weight.shape[1]
    filled = min(count, size)
    start = count % size + size - filled  # the oldest value still in the window
    first = size - filled
    for w in range(walls):
        for c in range(2):
            total = 0.0
            for k in range(modes):
                total += bank.mode_weight[w, k] * bank.mode_state[w, c, k]
            for i in range(filled):
                total += bank.window_weights[w, first + i] * bank.window[w, c, start + i]
            bank.history[c, w] = total


@njit(cache=True, fastmath=_FAST)
def memory_advance(bank, count):
    """Commit step ``count``'s ``bank.values`` (2, W: strain, Maxwell stress) and put the next step's history
    sums into ``bank.history``, in one pass over the modes.  The value leaving the window enters the modes."""
    walls, size = bank.window_weights.shape
    modes = bank.mode_weight.shape[1]
    slot = count % size
    absorb = count >= size
    filled = min(count + 1, size)
    start = (count + 1) % size + size - filled
    first = size - filled
    window, mode_state = bank.window, bank.mode_state
    for w in range(walls):
        for c in range(2):
            leaving = window[w, c, slot]
            total = 0.0
            if absorb:
                for k in range(modes):
                    state = bank.mode_ratio[w, k] * mode_state[w, c, k] + leaving
                    mode_state[w, c, k] = state
                    total += bank.mode_weight[w, k] * state
            window[w, c, slot] = bank.values[c, w]
            window[w, c, slot + size] = bank.values[c, w]
            for i in range(filled):
                total += bank.window_weights[w, first + i] * window[w, c, start + i]
            bank.history[c, w] = total


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
    stress, _, modulus = fdmk_stress(0.0, bank.history[0, w], bank.history[1, w], c[0], c[1], c[2], c[3],
                                     bank.w0[w])
    wall_tangent = modulus * area / thickness
    scale = 1.0 / (1.0 + flexibility * wall_tangent)
    return wall_tangent * scale, stress * area * scale


@njit(cache=True, inline="always")
def wall_response(bank, w, deformation):
    """(force N, wall strain, Maxwell stress MPa) of wall ``w`` at ``deformation`` (mm) this step.

    The wall's own deformation is the assembly's minus the support's: d_w = (d - f_s H_w) / (1 + f_s K_w).
    """
    c = bank.constants[w]
    G1, G2, eta1, eta2, area, thickness, flexibility = c[0], c[1], c[2], c[3], c[4], c[5], c[6]
    strain_history, maxwell_history, w0 = bank.history[0, w], bank.history[1, w], bank.w0[w]
    wall_deformation = deformation
    if flexibility > 0.0:
        history_stress, _, modulus = fdmk_stress(0.0, strain_history, maxwell_history, G1, G2, eta1, eta2, w0)
        wall_deformation = ((deformation - flexibility * history_stress * area)
                            / (1.0 + flexibility * modulus * area / thickness))
    strain = wall_deformation / thickness
    stress, maxwell, _ = fdmk_stress(strain, strain_history, maxwell_history, G1, G2, eta1, eta2, w0)
    return stress * area, strain, maxwell


@njit(cache=True)
def bank_affine(bank, count):
    """Every wall of ``bank`` at the start of step ``count``: history sums, K_t (N/mm) and H_n (N) into
    ``bank.history``, ``bank.tangent`` and ``bank.history_force``."""
    memory_history(bank, count)
    for w in range(bank.constants.shape[0]):
        bank.tangent[w], bank.history_force[w] = wall_affine(bank, w)


@njit(cache=True)
def bank_commit(bank, count, deformation, force, strain):
    """Accept ``deformation`` (mm, (W,)) for step ``count``: forces (N, (W,)) and wall strains (-, (W,)) into
    ``force`` and ``strain``, the memory advanced, and the next step's history sums, K_t and H_n (as
    :func:`bank_affine` would give them)."""
    for w in range(bank.constants.shape[0]):
        force[w], strain[w], bank.values[1, w] = wall_response(bank, w, deformation[w])
        bank.values[0, w] = strain[w]
    memory_advance(bank, count)
    for w in range(bank.constants.shape[0]):
        bank.tangent[w], bank.history_force[w] = wall_affine(bank, w)


@njit(cache=True)
def displacement_driven(bank, displacement):
    """(force N, wall strain) histories (steps,) of a one-wall bank at rest for a displacement history
    (mm, (steps,)): :func:`bank_commit` step after step."""
    steps = displacement.shape[0]
    force = np.empty(steps)
    strain = np.empty(steps)
    for n in range(steps):
        bank_commit(bank, n, displacement[n:n + 1], force[n:n + 1], strain[n:n + 1])
    return force, strain
