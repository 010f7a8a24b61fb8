"""Closed forms of the pushover of a shear building with Bilinear stories and P-Delta, written without the package
(tests/frame/test_pushover.py, tests/assessment/test_collapse_ductility.py).

Walls of static stiffness k_w enter as a negative P-Delta: a story's force is F(d) - (P/h - k_w) d, so pass
``gravity`` = (P/h - k_w) h.
"""

from __future__ import annotations

import math

import numpy as np

import vdw_frames as vdw


def bilinear_frame(masses, k, h, yield_forces, hardening, gravity):
    return vdw.ShearBuilding(masses, k, story_heights=h, gravity_loads=gravity,
                             hysteresis=[vdw.Bilinear(f, b) for f, b in zip(yield_forces, hardening, strict=True)])


def physical_path(k, yield_forces, hardening, gravity, h, pattern):
    """The closed-form capacity path of a shear building of Bilinear stories with P-Delta, written here without
    the package: a function of (load factor lambda, past the peak or not) giving the story drifts, with lambda*
    and the localising story.

    Story j carries V_j = lambda S_j, S_j the pattern's share above it.  With theta = P/h its backbone is
    V = (k - theta) d up to the yield drift F_y / k, i.e. V_y = F_y (1 - theta / k), then V_y + (b k - theta)
    (d - d_y).  A story whose post-yield tangent b k - theta is not positive peaks at its yield, at
    lambda_j = V_y / S_j; the first of them (smallest lambda_j) localises and follows its backbone down, every
    other story unloads from its drift at lambda* along its elastic line minus P-Delta, slope k - theta (until a
    story that hardened before the peak yields in reverse)."""
    k, fy, b, theta, s = (np.asarray(a, dtype=float) for a in (k, yield_forces, hardening, np.asarray(gravity) / h,
                                                                np.cumsum(pattern[::-1])[::-1] / np.sum(pattern)))
    elastic, plastic = k - theta, b * k - theta
    v_yield, d_yield = fy * (1.0 - theta / k), fy / k
    peaks = np.where(plastic <= 0.0, v_yield / s, np.inf)
    c = int(np.argmin(peaks))
    peak = float(peaks[c])

    def loading(shear):
        hardening_slope = np.where(plastic > 0, plastic, 1.0)  # (a softening story is not loaded past its yield)
        return np.where(shear <= v_yield, shear / elastic, d_yield + (shear - v_yield) / hardening_slope)

    def drifts(load, past_peak):
        if not past_peak:
            return loading(load * s)
        d = loading(peak * s) - (peak - load) * s / elastic
        # Steel01's kinematic hardening: a story that yielded and hardened before the peak yields in reverse
        # once its frame force F = V + theta d falls to b k d - (1 - b) F_y; then V = (b k - theta) d - (1 - b) F_y
        reverse = load * s + theta * d < b * k * d - (1.0 - b) * fy
        d = np.where(reverse, (load * s + (1.0 - b) * fy) / np.where(reverse, plastic, 1.0), d)
        d[c] = d_yield[c] + (load * s[c] - v_yield[c]) / plastic[c]
        return d

    return drifts, peak, c


def modal_pattern(masses, k, gravity, h):
    """phi_1 (roof 1) and T1 of K + K_G (story stiffness k - P/h) and M by numpy's eigen-solver, loads m phi."""
    stories = np.asarray(k, dtype=float) - np.asarray(gravity) / np.asarray(h)
    n = stories.size
    stiffness = np.zeros((n, n))
    for j in range(n):  # story j joins floors j - 1 and j
        stiffness[j, j] += stories[j]
        if j:
            stiffness[j - 1, j - 1] += stories[j]
            stiffness[j - 1, j] -= stories[j]
            stiffness[j, j - 1] -= stories[j]
    values, vectors = np.linalg.eig(np.linalg.solve(np.diag(masses), stiffness))
    first = int(np.argmin(values.real))
    shape = vectors[:, first].real / vectors[-1, first].real
    return shape, 2.0 * math.pi / math.sqrt(values[first].real)
