"""Fast fractional memory: the weights beyond a short window as a sum of geometric modes.

The exact convolution-quadrature memory of D^r (:mod:`vdw_frames.element.fractional`) keeps every past value,
O(n) work at step n.  Here only the last ``window`` = L values are kept exactly; the weights beyond the
window are replaced by K geometric (exponential) modes,

    w_j  ~=  sum_k c_k rho_k^j        for L < j <= max_steps,

which the step kernel (:mod:`vdw_frames.element.kernel`) carries as ``mode_ratio`` = rho_k and
``mode_weight`` = c_k rho_k^(L+1).  The work per step is O(L + K) whatever the record length, and K
grows only like log(max_steps) (see the table below).

Where the modes come from
-------------------------
The weights are the Taylor coefficients of W(zeta) = delta(zeta)^r, analytic in the unit disc.  Deforming
``w_j = (1 / 2 pi i) \\oint W(zeta) zeta^(-j-1) dzeta`` onto the branch cuts of W (real axis, |zeta| >= 1) and
writing rho = 1/|zeta| = exp(-u) gives, with s = sin(pi r),

* trapezoidal, W = 2^r (1 - zeta)^r (1 + zeta)^(-r), for j >= 1::

      w_j = -(2^r s / pi) \\int_0^oo e^{-j u} tanh(u/2)^r du
            + (-1)^j (2^r s / pi) \\int_0^oo e^{-j u} coth(u/2)^r du;

  the second (alternating) term is the (-1)^j j^(r-1) tail; at r = 1 it is the pole at zeta = -1,
  w_j = 4 (-1)^j exactly (one mode at rho = -1).
* Grunwald-Letnikov, W = (1 - zeta)^r, for j >= 1::

      w_j = -(s / pi) \\int_0^oo e^{-j u} (e^u - 1)^r du.

* BDF2, W = 2^-r (1 - zeta)^r (3 - zeta)^r, for j >= 3 (W grows like |zeta|^(2r))::

      w_j = -(2^-r / pi) [ s \\int_0^ln3 e^{-j u} ((e^u - 1)(3 - e^u))^r du
                           + sin(2 pi r) \\int_ln3^oo e^{-j u} ((e^u - 1)(e^u - 3))^r du ].

  (The cut runs to infinity, not only over (1, 3): going once round both branch points multiplies
  W by exp(4 pi i r).)  At r = 1 every term vanishes: the tail is exactly zero.

* damped two-step (rho_infinity = rho in (0, 1)), W = (1 - zeta)^r P^r Q^-r, P = a0 + a1 zeta,
  Q = b0 + b1 zeta (see :class:`vdw_frames.element.fractional.DampedTwoStep`), for j >= 1 (W grows like |zeta|^r),
  with z_a = -a0/a1 (= 7 at rho = 1/2) and ln(1/rho) the start of the alternating cut (zeta < -1/rho)::

      w_j = -(1 / pi) [ s \\int_0^ln(z_a) e^{-j u} ((e^u - 1)(a0 + a1 e^u) / (b0 + b1 e^u))^r du
                        + sin(2 pi r) \\int_ln(z_a)^oo e^{-j u} ((e^u - 1)(-a1 e^u - a0) / (b0 + b1 e^u))^r du ]
            + (-1)^j (s / pi) \\int_ln(1/rho)^oo e^{-j u} ((1 + e^u)(a0 - a1 e^u) / (b1 e^u - b0))^r du.

  The last density is ~ (u - ln(1/rho))^-r at its start (offsets passed separately: u itself cannot
  resolve them below 1e-16), its left tail summed in closed form as for the trapezoidal rule; at r = 1
  it is the pole of W at -1/rho, exactly one mode of ratio -rho.  rho = 0 is BDF2 (no alternating cut).

Each integral is discretised by the trapezoidal (sinc) rule in t = log u (u = ln3 / (1 + e^-t) on
(0, ln 3), u = ln 3 + e^t on (ln 3, oo)), step 0.25, which is uniformly accurate (~1e-15) for every decay
from one step to ``max_steps`` steps; the rule's infinite left tail (u -> 0, the slowest modes, where the
alternating density ~ u^-r carries the whole mass 4 as r -> 1) is summed in closed form and lumped into
one mode with the same zeroth and first moments (error ~ (j u)^2, kept below 1e-3 of the tolerance for
j <= max_steps).  That gives ~100-150 modes per branch.  Each branch (and sign) is then compressed by
square-root balanced truncation over the horizon 0 <= j - L - 1 < max_steps - L (Gramian factor sampled
on lags 0..63 and 8 Gauss points per octave beyond): the realisation A = diag(rho), B = C^T =
sqrt(|c rho^(L+1)|) is symmetric, so the reduced model, diagonalised, again has real ratios inside the
original range and residues of one sign -- no cancellation between modes.  K is the smallest order (by
bisection) whose error on that lag grid is within the branch's share of ``tolerance``.

Error measure and float64 floor
-------------------------------
For the positive-ratio branches the measure is the l1 error sum_{L<j<=max_steps} |w_j - tail_j| / |w_0|.
For the alternating branch (trapezoidal, ratios near -1) it is the l1 error of the two-tap average
(e_j + e_{j+1}) / 2: the weight error seen by every history without a Nyquist (period-2) component,
i.e. by anything the scheme resolves.  The plain l1 norm of an alternating error is not a useful target:
the kernel stores rho_k in float64, and half an ulp (~6e-17) on a ratio near -1 shifts w_j by
~ j * 6e-17 * c_k -- summed over 1e5 steps ~1e-7 |w_0| at r -> 1, at the Nyquist frequency only.  The
float64 recurrence of the exact trapezoidal weights has errors of the same kind (~1e-9 |w_0| summed at
r = 0.99).  Below ~eps * max_steps * (slow residues) the error is rounding noise; smaller tolerances
are raised to 4x that floor.

Measured at the defaults (tests/element/test_fast_memory.py), 1e5 steps, dt-independent (the weights all scale
with dt^-r): filtered l1 error <= 7e-11 |w_0| against extended-precision weights (<= 3e-10 against the
float64 recurrence), plain l1 <= 6.1e-11 for BDF2 / Grunwald, <= 3.5e-11 for the damped method (its
alternating ratios near -rho decay geometrically: plain l1 measure) and <= 3.3e-7 (Nyquist) for the
trapezoidal rule.  Kernel force histories, 1e5 steps of a smooth 0.1-10 Hz strain history, r in
{0.05 .. 1}, dt = 0.001 and 0.02, Table-4 and G1 = 0 dampers: max |F_fast - F_exact| / max |F_exact|
<= 2.6e-9 (trapezoidal, r = 0.99, dt = 0.001; damped: <= 7.2e-10, r = 0.9, dt = 0.001, G1 = 0), peak
responses within 1.1e-9.

Defaults and cost
-----------------
``window`` L = 16, ``tolerance`` = 1e-10, ``max_steps`` = 2^20 (~1.05e6 steps): K below.  Cost per step
and channel ~ L + 2K multiply-adds (a mode is updated and read).  L + 2K is flat for L = 4..16 (each
doubling of L saves ~1-2 modes) and grows beyond, so L = 16.  K grows ~6 (BDF2, Grunwald) or ~12
(trapezoidal) per decade of max_steps and ~3-6 per decade of 1/tolerance; at max_steps = 1e5 it is
~20 % smaller.

    ============  ========  =======  =======  =======  ========  =====
    K             r = 0.05  r = 0.3  r = 0.6  r = 0.9  r = 0.99  r = 1
    ============  ========  =======  =======  =======  ========  =====
    trapezoidal   64        68       68       65       58        1
    bdf2          33        33       32       28       24        0
    grunwald      33        33       31       27       22        0
    damped        36        36       35       30       26        1
    ============  ========  =======  =======  =======  ========  =====

(damped: rho_infinity = 1/2, two of the modes alternating, near -1/2; 44-47 modes at max_steps = 1e8.)

The modes are built for records of at most ``max_steps`` steps: beyond, the error grows quickly (the
slowest modes are only moment-matched), so pass ``max_steps`` >= the record length.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray
from scipy import linalg

from .._validation import fractional_order, positive, show, whole_number
from .fractional import DampedTwoStep, Discretisation, get_method

DEFAULT_WINDOW = 16
DEFAULT_TOLERANCE = 1e-10
MAX_TOLERANCE = 1e-4
"""Largest ``tolerance`` accepted.  At 1e-4 the force histories stay within 4e-4 of the exact memory's
peak (measured: 20 000 steps, r 0.3-0.9, trapezoidal and BDF2, dt 0.005 s, with and without the
equilibrium spring); at 1e-2 they are up to 8 % off and at 1 the trapezoidal rule gives NaN."""
DEFAULT_MAX_STEPS = 2**20
MAX_STEPS = 2**40  # the longest horizon the modes are built for (~1.1e12 steps)

_LN3 = math.log(3.0)
_STEP = 0.25  # sinc step in t = log u: discretisation error ~exp(-pi^2 / h) ~ 1e-17
_NEGLIGIBLE = 1e-20  # fine modes with |residue| below this (relative to |w_0|) are dropped
_EXACT_LAGS = 64  # the time grid of the compression: lags 0..63 exactly, then Gauss points
_GAUSS_PER_OCTAVE = 8

_Tail = Callable[[float, float], tuple[float, float]]
"""(t0, h) -> (mass, first moment) of a segment's sinc nodes left of t0 (see :class:`_Segment`)."""
_Modes = tuple[NDArray[np.float64], NDArray[np.float64]]


# ----------------------------------------------------------------------------- densities
def _sin_pi(r: float) -> float:
    """sin(pi r) for 0 < r <= 1, exact zero at r = 1."""
    return math.sin(math.pi * min(r, 1.0 - r))


def _sin_2pi(r: float) -> float:
    """sin(2 pi r) for 0 < r <= 1, exact zeros at r = 1/2 and r = 1."""
    x = r if r <= 0.5 else r - 1.0
    return math.sin(2.0 * math.pi * x)


def _phi(x: float) -> float:
    """x / (1 - exp(-x)), with phi(0) = 1."""
    return 1.0 if x == 0.0 else x / -math.expm1(-x)


class _Segment:
    """One piece of a branch cut: w_j gets sigma^j \\int e^{-j u} F(u) du over the segment."""

    def __init__(self, sigma: int, density: Callable[..., NDArray[np.float64]], kind: str, end: float = 0.0,
                 small: _Tail | None = None) -> None:
        self.sigma = sigma  # +1: ratio rho = e^-u, -1: rho = -e^-u
        self.density = density  # F(u), vectorised; F(u, u - end) for kind 'shift'
        self.kind = kind  # 'log' (0, oo), 'logistic' (0, end), 'shift' (end, oo)
        self.end = end
        # (mass, first moment) of the sinc rule's nodes left of t0, F(u) ~ C u^alpha as u -> 0:
        # a function (t0, h) -> (m0, m1), or None when the segment does not reach u = 0.
        self.small = small


def _power_tail(scale: float, alpha: float, length: float = 1.0) -> _Tail:
    """Closed-form sums h sum_{t_k <= t0} C (length e^t_k)^(alpha+1) (and alpha+2) over t_k = t0 - m h."""

    def tail(t0: float, h: float) -> tuple[float, float]:
        a1, a2 = alpha + 1.0, alpha + 2.0
        u0 = length * math.exp(t0)
        m0 = scale * h * u0**a1 / -math.expm1(-a1 * h)
        m1 = scale * h * u0**a2 / -math.expm1(-a2 * h)
        return m0, m1

    return tail


def _segments(method: Discretisation, r: float) -> list[_Segment]:
    name = method.name
    s = _sin_pi(r)
    if name == "trapezoidal":
        k = 2.0**r * s / math.pi

        def positive_density(u: NDArray[np.float64]) -> NDArray[np.float64]:
            return -k * np.tanh(0.5 * u) ** r

        def alternating_density(u: NDArray[np.float64]) -> NDArray[np.float64]:
            return k / np.tanh(0.5 * u) ** r

        def alternating_tail(t0: float, h: float) -> tuple[float, float]:
            # C u^(-r) with C = 4^r s / pi; s / (1 - r) = pi sinc(1 - r) keeps r -> 1 finite (mass -> 4).
            u0 = math.exp(t0)
            m0 = 4.0**r * float(np.sinc(1.0 - r)) * u0 ** (1.0 - r) * _phi((1.0 - r) * h)
            m1 = 4.0**r * s / math.pi * h * u0 ** (2.0 - r) / -math.expm1(-(2.0 - r) * h)
            return m0, m1

        return [
            _Segment(+1, positive_density, "log", small=_power_tail(-s / math.pi, r)),
            _Segment(-1, alternating_density, "log", small=alternating_tail),
        ]
    if name == "grunwald":

        def density(u: NDArray[np.float64]) -> NDArray[np.float64]:
            return -(s / math.pi) * np.expm1(u) ** r

        return [_Segment(+1, density, "log", small=_power_tail(-s / math.pi, r))]
    if name == "bdf2":
        s2 = _sin_2pi(r)
        k = 2.0**-r / math.pi

        def inner(u: NDArray[np.float64]) -> NDArray[np.float64]:  # (0, ln 3): (e^u - 1)(3 - e^u) >= 0
            return -k * s * np.maximum(np.expm1(u) * (3.0 - np.exp(u)), 0.0) ** r

        def outer(u: NDArray[np.float64], delta: NDArray[np.float64]) -> NDArray[np.float64]:  # (ln 3, oo)
            return -k * s2 * np.maximum(np.expm1(u) * (np.exp(u) - 3.0), 0.0) ** r

        # inner ~ -k s (2u)^r = -(s / pi) u^r as u -> 0
        return [
            _Segment(+1, inner, "logistic", end=_LN3, small=_power_tail(-s / math.pi, r, _LN3)),
            _Segment(+1, outer, "shift", end=_LN3),
        ]
    if name == "damped" and isinstance(method, DampedTwoStep):
        return _damped_segments(method, r, s)
    raise ValueError(f"unknown method {name!r}")


def _damped_segments(method: DampedTwoStep, r: float, s: float) -> list[_Segment]:
    # W = (1 - zeta)^r P^r Q^-r, P = a0 + a1 zeta, Q = b0 + b1 zeta; branch points 1 and z_a = -a0/a1 > 1
    # (exponent r, cut (1, oo) as for BDF2) and z_b = -b0/b1 = -1/rho_infinity (exponent -r, cut
    # (-oo, z_b)); |W| grows like |zeta|^r, so the cut integrals hold for j >= 1.
    a0, a1, b0, b1 = method.coefficients
    s2 = _sin_2pi(r)
    log_za = math.log(-a0 / a1)

    def inner(u: NDArray[np.float64]) -> NDArray[np.float64]:  # (0, ln z_a): (e^u - 1)(a0 + a1 e^u) >= 0
        x = np.exp(u)
        return -(s / math.pi) * (np.maximum(np.expm1(u) * (a0 + a1 * x), 0.0) / (b0 + b1 * x)) ** r

    # (ln z_a, oo): both factors of (1 - x)(a0 + a1 x) negative, phase exp(-2 pi i r)
    def outer(u: NDArray[np.float64], delta: NDArray[np.float64]) -> NDArray[np.float64]:
        x = np.exp(u)
        return -(s2 / math.pi) * (np.maximum(np.expm1(u) * (-a1 * x - a0), 0.0) / (b0 + b1 * x)) ** r

    # inner ~ -(s / pi) u^r as u -> 0 (a0 + a1 = b0 + b1 = 1)
    segments = [
        _Segment(+1, inner, "logistic", end=log_za, small=_power_tail(-s / math.pi, r, log_za)),
        _Segment(+1, outer, "shift", end=log_za),
    ]
    if b1 > 0.0:
        rho = method.rho_infinity
        log_zb = -math.log(rho)  # zeta = -e^u, u > ln|z_b|; b1 e^u - b0 = b0 expm1(u - ln|z_b|)
        scale = ((1.0 + 1.0 / rho) * (a0 - a1 / rho) / b0) ** r  # |W| ~ scale * (u - ln|z_b|)^-r

        # delta = u - ln|z_b|, passed separately: u loses it below ~1e-16
        def alternating(u: NDArray[np.float64], delta: NDArray[np.float64]) -> NDArray[np.float64]:
            x = np.exp(u)
            return (s / math.pi) * ((1.0 + x) * (a0 - a1 * x) / (b0 * np.expm1(delta))) ** r

        def alternating_tail(t0: float, h: float) -> tuple[float, float]:
            # (s / pi) scale delta^-r summed over delta_k = e^{t_k}, t_k <= t0; s / (pi (1 - r)) = sinc(1 - r)
            # keeps r -> 1 finite: at r = 1 the cut is the simple pole, one mode (-rho)^j of mass `scale`.
            d0 = math.exp(t0)
            m0 = scale * float(np.sinc(1.0 - r)) * d0 ** (1.0 - r) * _phi((1.0 - r) * h)
            m1 = scale * s / math.pi * h * d0 ** (2.0 - r) / -math.expm1(-(2.0 - r) * h)
            return m0, m1

        segments.append(_Segment(-1, alternating, "shift", end=log_zb, small=alternating_tail))
    return segments


def _fine_modes(method: Discretisation, r: float, window: int, max_steps: int,
                tolerance: float) -> list[tuple[int, float, float]]:
    """Sinc-quadrature modes: list of (sigma, u, g) with w_{L+1+i} ~= sum g sigma^i e^{-i u}."""
    h = _STEP
    first = window + 1  # smallest lag represented by the modes
    w0 = abs(method.weights(r, 1)[0])
    # Lump the rule's nodes below u_low into one moment-matched mode: its error is
    # <= j^2 var/2 * mass <= (j u_low)^2 * 2 for mass <= 4; summed over j <= max_steps it stays
    # below 1e-3 of the tolerance.
    u_low = math.sqrt(1e-3 * tolerance * w0 * 3.0 / (4.0 * float(max_steps) ** 3))
    # Beyond u_high every node's residue e^{-(L+1) u} F(u) h u is negligible (F grows <= e^{2 r u}).
    u_high = 50.0 * math.log(10.0) / max(first - 2.0 * r, 1.0)
    modes: list[tuple[int, float, float]] = []
    for segment in _segments(method, r):
        if segment.kind == "log":
            t = h * np.arange(math.ceil(math.log(u_low) / h), math.ceil(math.log(u_high) / h) + 1)
            u = np.exp(t)
            du = u
        elif segment.kind == "logistic":
            b = segment.end
            t = h * np.arange(math.ceil(math.log(u_low / b) / h), math.ceil(50.0 / h) + 1)
            sig = 0.5 * (1.0 + np.tanh(0.5 * t))
            u = b * sig
            du = b * sig * (0.5 * (1.0 - np.tanh(0.5 * t)))
        else:  # shift
            if u_high <= segment.end:
                continue
            low = math.log(u_low) if segment.small is not None else -50.0
            t = h * np.arange(math.floor(low / h), math.ceil(math.log(u_high - segment.end) / h) + 1)
            u = segment.end + np.exp(t)
            du = np.exp(t)
        with np.errstate(over="ignore", invalid="ignore"):
            c = h * (segment.density(u, du) if segment.kind == "shift" else segment.density(u)) * du
        c = np.where(np.isfinite(c), c, 0.0)
        if segment.small is not None:
            m0, m1 = segment.small(t[0] - h, h)
            if m0 != 0.0:
                start = segment.end if segment.kind == "shift" else 0.0
                u = np.append(u, start + (m1 / m0 if m1 != 0.0 else 0.0))
                c = np.append(c, m0)
        g = c * np.exp(-first * u) * segment.sigma**first
        keep = np.abs(g) > _NEGLIGIBLE * w0
        modes.extend((segment.sigma, float(uu), float(gg)) for uu, gg in zip(u[keep], g[keep], strict=True))
    return modes


# ----------------------------------------------------------------------------- compression
def _time_grid(horizon: int) -> _Modes:
    """Points i and weights approximating sum_{i=0}^{horizon-1} f(i) for smooth f (lags beyond L+1)."""
    if horizon <= _EXACT_LAGS:
        return np.arange(horizon, dtype=float), np.ones(horizon)
    points = [np.arange(_EXACT_LAGS, dtype=float)]
    weights = [np.ones(_EXACT_LAGS)]
    x, wx = np.polynomial.legendre.leggauss(_GAUSS_PER_OCTAVE)
    a, end = _EXACT_LAGS - 0.5, horizon - 0.5
    while a < end:
        b = min(2.0 * a, end)
        points.append(0.5 * (a + b) + 0.5 * (b - a) * x)
        weights.append(0.5 * (b - a) * wx)
        a = b
    return np.concatenate(points), np.concatenate(weights)


def _reduce(u: NDArray[np.float64], g: NDArray[np.float64], horizon: int, budget: float, alternating: bool) -> _Modes:
    """Balanced truncation of the one-signed geometric sum h_i = sum g e^{-i u}, 0 <= i < horizon.

    Returns (u_r, g_r) of the smallest order whose error over the horizon, estimated on the time grid,
    is <= budget (or the input when no smaller order is).  The error is the l1 norm
    sum_i |e_i| of e_i = sum g_r e^{-i u_r} - h_i, or, for an ``alternating`` group (ratios -e^{-u}),
    the l1 norm of its two-tap average (e_i + e_{i+1}) / 2 carried to the alternating sequence,
    |e_0| / 2 + sum_i |e_i - e_{i+1}| / 2: the error seen by any history without a Nyquist component.
    """
    lags, lag_weights = _time_grid(horizon)
    basis = np.exp(-np.outer(u, lags))
    decay = -np.expm1(-u)  # 1 - e^{-u}, accurate for slow modes

    def error(u_r: NDArray[np.float64], g_r: NDArray[np.float64]) -> float:
        basis_r = np.exp(-np.outer(u_r, lags))
        if not alternating:
            return float(lag_weights @ np.abs(g_r @ basis_r - g @ basis))
        step = (g_r * -np.expm1(-u_r)) @ basis_r - (g * decay) @ basis
        return float(0.5 * abs(g_r.sum() - g.sum()) + 0.5 * (lag_weights @ np.abs(step)))

    sign = 1.0 if g[0] > 0 else -1.0
    b = np.sqrt(np.abs(g))
    # Square-root Gramian factor: P = Z Z^T = sum_i A^i b b^T A^i (= Q, the realisation is symmetric).
    factor = b[:, None] * basis * np.sqrt(lag_weights)[None, :]
    vectors, singular, _ = linalg.svd(factor, full_matrices=False)
    projected_b = vectors.T @ b
    projected_decay = vectors.T @ (decay[:, None] * vectors)

    def reduced(order: int) -> _Modes:
        block = projected_decay[:order, :order]
        d, rotation = linalg.eigh(0.5 * (block + block.T))
        u_r = -np.log1p(-np.clip(d, 0.0, 1.0 - 1e-16))
        g_r = sign * (rotation.T @ projected_b[:order]) ** 2
        return u_r, g_r

    # The error decreases with the order down to a rounding floor (~eps * horizon * slow residues, noisy
    # below that); estimate the floor at the numerical rank and never ask for less than 4x it.
    rank = max(int(np.count_nonzero(singular > 1e-14 * singular[0])), 1)
    best = reduced(rank) if rank < u.size else (u, g)
    budget = max(budget, 4.0 * error(*best))
    # Smallest passing order by bisection.
    low, high = 0, rank  # order `low` fails (or is 0), order `high` passes
    while high - low > 1:
        middle = (low + high) // 2
        candidate = reduced(middle)
        if error(*candidate) <= budget:
            high, best = middle, candidate
        else:
            low = middle
    return best


@lru_cache(maxsize=256)
def _dimensionless_modes(method: Discretisation, r: float, window: int, tolerance: float, max_steps: int) -> _Modes:
    w0 = abs(method.weights(r, 1)[0])
    fine = _fine_modes(method, r, window, max_steps, tolerance)
    groups: dict[tuple[int, bool], list[tuple[float, float]]] = {}
    for sigma, rate, residue in fine:
        groups.setdefault((sigma, residue > 0), []).append((rate, residue))
    horizon = max_steps - window
    budget = tolerance * w0 / max(len(groups), 1)
    ratios, weights = [], []
    for (sigma, _), members in sorted(groups.items()):
        u = np.array([m[0] for m in members])
        g = np.array([m[1] for m in members])
        # The Nyquist-filtered measure only for ratios near -1 (trapezoidal); the damped method's
        # alternating ratios are near -rho_infinity and decay geometrically: plain l1.
        u_r, g_r = _reduce(u, g, horizon, budget, alternating=sigma < 0 and method.name == "trapezoidal")
        order = np.argsort(u_r)
        ratios.append(sigma * np.exp(-u_r[order]))
        weights.append(g_r[order])
    if not ratios:
        return np.zeros(0), np.zeros(0)
    return np.concatenate(ratios), np.concatenate(weights)


# ----------------------------------------------------------------------------- public API
def _tolerance(value: object) -> float:
    tolerance = positive("tolerance", value)
    if tolerance > MAX_TOLERANCE:
        raise ValueError(f"tolerance must lie in (0, {MAX_TOLERANCE:g}], got {show(value)}: larger ones put the "
                         "forces percents off the exact memory (and NaN near 1)")
    return tolerance


def tail_modes(method: str | Discretisation, r: float, dt: float, window: int = DEFAULT_WINDOW,
               tolerance: float = DEFAULT_TOLERANCE,
               max_steps: int = DEFAULT_MAX_STEPS) -> tuple[np.ndarray, np.ndarray]:
    """Geometric modes replacing the CQ weights of D^r beyond ``window`` steps.

    Parameters
    ----------
    method : str or Discretisation
        'trapezoidal', 'bdf2', 'grunwald' or 'damped', or a :class:`~vdw_frames.element.fractional.DampedTwoStep`
        with any rho_infinity (see :mod:`vdw_frames.element.fractional`).
    r : float
        Fractional order, 0 < r <= 1.
    dt : float
        Time step (s); the modes' weights carry the weights' dt^-r scaling.
    window : int
        L >= 2, the number of past values kept exactly (weights w_1..w_L).
    tolerance : float
        Target for the relative weight error sum_{L<j<=max_steps} |w_j - sum_k c_k rho_k^j| / |w_0|, split
        evenly between the branches; for the trapezoidal rule's alternating branch the error counted is
        that of the two-tap average (e_j + e_{j+1}) / 2 (the error seen by histories without a Nyquist
        component; see the module docstring).  Values below the float64 floor (~1e-12 for 1e6 steps)
        are raised to it; values above :data:`MAX_TOLERANCE` (1e-4) are refused.
    max_steps : int
        Longest record the modes are built for (> window); K grows like log(max_steps / tolerance).
        The modes are accurate only up to it: beyond, the error grows quickly (the slowest modes are
        fitted over the horizon only), so pass at least the record length.

    Returns
    -------
    (mode_ratio, mode_weight) : float64 arrays of shape (K,)
        In the layout of :mod:`vdw_frames.element.kernel`: rho_k and c_k rho_k^(L+1) (s^-r), so that
        w_j ~= sum_k mode_weight_k * mode_ratio_k^(j - L - 1) for j > L.
    """
    method = get_method(method)
    r = fractional_order(r)
    dt = positive("dt", dt)
    window = int(window)
    max_steps = int(max_steps)
    tolerance = _tolerance(tolerance)
    if window < 2:
        raise ValueError(f"window must be >= 2, got {window}")
    if max_steps <= window:
        raise ValueError(f"max_steps must exceed window ({window}), got {max_steps}")
    ratio, weight = _dimensionless_modes(method, r, window, tolerance, max_steps)
    return ratio.copy(), weight * dt ** (-r)


def fast_memory_arrays(method: str | Discretisation, r: float, dt: float, window: int = DEFAULT_WINDOW,
                       tolerance: float = DEFAULT_TOLERANCE,
                       max_steps: int = DEFAULT_MAX_STEPS) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(weights (L+1,), mode_weight (K,), mode_ratio (K,)): the fast memory of one wall.

    The first L+1 exact CQ weights w_0..w_L (scaled by dt^-r) and the modes of :func:`tail_modes`;
    :class:`vdw_frames.element.bank.Memory` lays them out for :mod:`vdw_frames.element.kernel`.
    Parameters as for :func:`tail_modes`.
    """
    mode_ratio, mode_weight = tail_modes(method, r, dt, window, tolerance, max_steps)
    weights = get_method(method).weights(r, int(window) + 1, dt)
    return weights, mode_weight, mode_ratio


@dataclass(frozen=True)
class FastMemory:
    """The fast memory strategy with its settings (``memory="fast"`` means ``FastMemory()``).

    ``tolerance``: relative weight error beyond the window, in (0, 1e-4] (see :func:`tail_modes`); ``window``: past
    steps kept exactly; ``max_steps``: the longest record the modes serve (raised to the record length
    when a whole record is known in advance); ``exact_below``: records known to be at most this long
    use the exact memory instead, which is both exact and cheaper there than building the modes.
    """

    tolerance: float = DEFAULT_TOLERANCE
    window: int = DEFAULT_WINDOW
    max_steps: int = DEFAULT_MAX_STEPS
    exact_below: int = 2048

    def __post_init__(self) -> None:
        object.__setattr__(self, "tolerance", _tolerance(self.tolerance))
        object.__setattr__(self, "window", whole_number("window", self.window, 2))
        object.__setattr__(self, "max_steps", whole_number("max_steps", self.max_steps, self.window + 1))
        if self.max_steps > MAX_STEPS:
            raise ValueError(f"max_steps must be <= 2**40, got {self.max_steps!r}")
        object.__setattr__(self, "exact_below", whole_number("exact_below", self.exact_below, 0))

    def arrays(self, method: str | Discretisation, r: float, dt: float,
               steps: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(weights, mode_weight, mode_ratio) for a record of ``steps`` steps (see :func:`fast_memory_arrays`)."""
        return fast_memory_arrays(method, r, dt, self.window, self.tolerance, max(int(steps), self.max_steps))
