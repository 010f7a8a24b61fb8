"""The FDMK step kernel: the one compiled implementation of the element's time stepping.

Everything that advances an FDMK damper in time -- :meth:`FDMKDamper.force`, :class:`DamperState`
(trial/commit) and the shear-building integrator -- calls these functions.

Memory layout of one damper (arrays, so that many dampers stack into higher-dimensional arrays):

``weights``  (L+1,)  convolution weights w_0 .. w_L of D^r, already scaled by dt^-r (s^-r)
``past``     (L, 2)  ring buffer of the last L committed values of the two channels that carry
                     memory: column 0 the strain, column 1 the Maxwell-branch stress (MPa)
``mode_weight`` (K,), ``mode_ratio`` (K,), ``mode_state`` (K, 2)
                     an optional exponential (geometric) representation of the weights beyond the
                     window, w_j ~= sum_k c_k rho_k^j for j > L, with mode_weight = c_k rho_k^(L+1).
                     K = 0 and L >= the number of steps gives the exact full-history convolution;
                     :mod:`vdw_frames.element.fast_memory` builds L = 16 and K = 24-68 modes (the fast memory).

The history at step n (``count`` = n committed steps) of channel c is
``sum_{j=1}^{min(n, L)} w_j past_c[n-j] + sum_k mode_weight_k * mode_state_k,c``; values leaving the
window are absorbed into ``mode_state`` as S_k <- rho_k S_k + x_{n-L}.
"""

from __future__ import annotations

import numpy as np
from .._jit import njit


@njit(cache=True)
def memory_history(weights, past, count, mode_weight, mode_state):
    """History sums (strain channel, Maxwell channel) of D^r at step ``count``, without w_0 x_n."""
    window = past.shape[0]
    newest = count % window  # the slot the next value goes to
    filled = min(count, window)
    strain_sum = 0.0
    maxwell_sum = 0.0
    # Two contiguous runs of the ring buffer: slots newest-1 .. 0, then window-1 downwards.
    first = min(filled, newest)
    for j in range(1, first + 1):
        w = weights[j]
        strain_sum += w * past[newest - j, 0]
        maxwell_sum += w * past[newest - j, 1]
    for j in range(first + 1, filled + 1):
        w = weights[j]
        strain_sum += w * past[newest - j + window, 0]
        maxwell_sum += w * past[newest - j + window, 1]
    for k in range(mode_weight.shape[0]):
        strain_sum += mode_weight[k] * mode_state[k, 0]
        maxwell_sum += mode_weight[k] * mode_state[k, 1]
    return strain_sum, maxwell_sum


@njit(cache=True)
def memory_push(past, count, mode_ratio, mode_state, strain, maxwell_stress):
    """Commit step ``count``'s values; returns the new count.  The oldest value moves into the modes."""
    window = past.shape[0]
    slot = count % window
    if count >= window:
        for k in range(mode_ratio.shape[0]):
            mode_state[k, 0] = mode_ratio[k] * mode_state[k, 0] + past[slot, 0]
            mode_state[k, 1] = mode_ratio[k] * mode_state[k, 1] + past[slot, 1]
    past[slot, 0] = strain
    past[slot, 1] = maxwell_stress
    return count + 1


@njit(cache=True)
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


@njit(cache=True)
def strain_driven(strain, G1, G2, eta1, eta2, weights, past, mode_weight, mode_ratio, mode_state):
    """Stress history (MPa) for a strain history from rest, stepping the memory in place."""
    stress = np.empty(strain.shape[0])
    count = 0
    for n in range(strain.shape[0]):
        strain_sum, maxwell_sum = memory_history(weights, past, count, mode_weight, mode_state)
        stress[n], maxwell, _ = fdmk_stress(
            strain[n], strain_sum, maxwell_sum, G1, G2, eta1, eta2, weights[0]
        )
        count = memory_push(past, count, mode_ratio, mode_state, strain[n], maxwell)
    return stress
