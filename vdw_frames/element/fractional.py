"""Discretisations of the Riemann-Liouville derivative D^r on a uniform grid.

Every method here is a convolution quadrature (Lubich, 1988): with a generating function
delta(zeta) of a linear multistep method, the discrete operator

    (D^r x)_n  ~=  dt^(-r) * sum_{j=0}^{n} w_j x_{n-j},      sum_j w_j zeta^j = delta(zeta)^r,

applied to a history that is zero before t = 0 (the paper's eq. (1), fractional derivative from rest).
Because convolution quadrature is an algebra homomorphism, applying it to the whole FDMK transfer
function of eqs. (3)-(5) gives the same scheme as applying it to each D^r in (3) and (4): the discrete
element is the model's transfer function evaluated at ``s = delta(zeta) / dt``.  Its steady state under
``x_n = exp(i omega n dt)`` is therefore the exact complex modulus evaluated at
``s = symbol(omega, dt) = delta(exp(-i omega dt)) / dt`` (see :meth:`Discretisation.symbol`).

Methods
-------
``DampedTwoStep`` (default; name ``"damped"``, field ``rho_infinity`` = 1/2 by default, in [0, 1))
    delta(zeta) = (1 - zeta)(a0 + a1 zeta) / (b0 + b1 zeta), a1 = (rho - 1) / (2 (1 + rho)), a0 = 1 - a1,
    b1 = rho / (1 + rho), b0 = 1 / (1 + rho): the second-order two-step family from BDF2 (rho = 0) to the
    trapezoidal rule (rho -> 1).  delta(e^-z) = z + (a1/2 - 1/12) z^3 + ..., so s^r is off by about
    r (1/12 - a1/2) (omega dt)^2 = r (omega dt)^2 / 6 at rho = 1/2, half BDF2's: 0.40 % for r = 0.6 and
    0.67 % for r = 1 at omega dt = 0.2.  A-stable (Re delta(e^{i phi}) >= 0), with delta(-1) = 8 finite
    and parasitic (Nyquist) content decaying like rho^n.  The weights are the Taylor coefficients of
    (1 - zeta)^r P^r Q^-r (P = a0 + a1 zeta, Q = b0 + b1 zeta), by Miller's recurrence (stable: the
    singularities 1, -a0/a1 = 7 and -1/rho = -2 lie on or outside the unit circle; l1 deviation from the
    same recurrence in extended precision <= 2e-14 |w_0| over 1e5 weights); at r = 1 they are
    7/4, -23/8, 27/4 (-1/2)^j.  Measured (tests/element/test_damped_two_step.py), force error on a tapered 1 Hz
    sine at omega dt = 0.2, this method / BDF2: Table-4 damper 0.11 % / 0.22 % (r = 0.6), 0.25 % / 0.51 %
    (r = 1); pure Abel dashpot (G1 = G2 = eta2 = 0) 0.21 / 0.42 % (r = 0.3), 0.44 / 0.87 % (r = 0.6),
    0.69 / 1.36 % (r = 0.9), 0.77 / 1.54 % (r = 1): within 1 % for every r, which BDF2 is not.  On a
    sine from rest (kink at t = 0, 200 steps per cycle, Table 4, r = 0.6, against a 32x finer BDF2
    solution): 1.3 % error in the first cycle (BDF2 0.7 %, trapezoidal 1.8 %), dominated by the first
    steps after the kink, and 2.6e-5 in the second cycle (BDF2 5.2e-5, trapezoidal 2.2e-3).
    Why the default: it meets "within 1 % at omega dt <= 0.2" for every r in (0, 1] with the damping
    at the Nyquist frequency that the trapezoidal rule lacks; the price is a larger error in the few
    steps right after a kink in the input, which dies out like 2^-n.
``BDF2``
    delta(zeta) = 3/2 - 2 zeta + zeta^2 / 2 (rho_infinity = 0).  Second order and L-stable: the
    strongest damping of the family, weights decaying smoothly like j^(-1-r).  Its symbol is
    i omega (1 + (omega dt)^2 / 3 + ...), so s^r is off by about r (omega dt)^2 / 3: 0.8 % for r = 0.6
    and 1.3 % for r = 1 at omega dt = 0.2 (omega dt <= 0.15 keeps every r within 1 %).
``Trapezoidal``
    delta(zeta) = 2 (1 - zeta) / (1 + zeta) (Tustin, rho_infinity = 1).  Second order with a four times
    smaller error than BDF2 ((omega dt)^2 / 12 in |s|, exact phase) but only A-stable: delta^r is
    singular at zeta = -1, the weights carry an alternating tail (-1)^j j^(r-1), and any kink in the
    input -- the start of a sine test, u'(0+) != 0 -- excites a Nyquist-frequency oscillation that
    decays like a power law and, at r = 1, not at all (the trapezoidal velocity's well-known ringing).
    Measured on a sine from rest with 200 steps per cycle and r = 0.6: 1.8 % error in the first quarter
    cycle and 0.2 % a cycle later.  Selectable for inputs that start smoothly.
``GrunwaldLetnikov``
    delta(zeta) = 1 - zeta (backward Euler).  First order: symbol i omega (1 - i omega dt / 2 + ...), about
    6 % error in s^0.6 at omega dt = 0.2.  Kept for comparison with the literature.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .._jit import njit
from .._validation import check_memory, finite_array, finite_scalar, fractional_order, time_step, whole_number


@njit(cache=True)
def _trapezoidal_weights(r, count):
    # Coefficients of ((1 - z) / (1 + z))^r from (1 - z^2) g' = -2 r g, an O(n) recurrence.
    g = np.empty(count)
    g[0] = 1.0
    if count > 1:
        g[1] = -2.0 * r
    for n in range(1, count - 1):
        g[n + 1] = ((n - 1) * g[n - 1] - 2.0 * r * g[n]) / (n + 1)
    return g * 2.0**r


@njit(cache=True)
def _bdf2_weights(r, count):
    # Coefficients of p(z)^r, p(z) = 3/2 - 2 z + z^2 / 2, by J.C.P. Miller's recurrence p g' = r p' g.
    p = np.array([1.5, -2.0, 0.5])
    g = np.empty(count)
    g[0] = 1.5**r
    for n in range(1, count):
        total = 0.0
        for k in range(1, min(n, 2) + 1):
            total += (r * k - (n - k)) * p[k] * g[n - k]
        g[n] = total / (n * p[0])
    return g


@njit(cache=True)
def _grunwald_weights(r, count):
    # Coefficients of (1 - z)^r: the Grunwald-Letnikov binomial weights.
    g = np.empty(count)
    g[0] = 1.0
    for n in range(1, count):
        g[n] = g[n - 1] * (1.0 - (r + 1.0) / n)
    return g


@njit(cache=True)
def _damped_weights(r, a0, a1, b0, b1, count):
    # Coefficients of W = F^r, F(z) = (1 - z)(a0 + a1 z) / (b0 + b1 z), by Miller's recurrence D W' = r N W
    # with D = (1 - z)(a0 + a1 z)(b0 + b1 z) (cubic) and N = D F'/F = -P Q + a1 E Q - b1 E P (quadratic),
    # E = 1 - z, P = a0 + a1 z, Q = b0 + b1 z.  Every root of D lies on or outside the unit circle
    # (1, -a0/a1 > 1, -b0/b1 < -1), so the forward recurrence is stable.
    d = np.array([a0 * b0, a0 * b1 + a1 * b0 - a0 * b0, a1 * b1 - a0 * b1 - a1 * b0, -a1 * b1])
    n = np.array([-a0 * b0 + a1 * b0 - b1 * a0,
                  -(a0 * b1 + a1 * b0) + a1 * (b1 - b0) - b1 * (a1 - a0),
                  -a1 * b1 - a1 * b1 + b1 * a1])
    g = np.empty(count)
    g[0] = (a0 / b0) ** r
    for m in range(count - 1):
        total = 0.0
        for k in range(min(m, 2) + 1):
            total += r * n[k] * g[m - k]
        for k in range(1, min(m + 1, 3) + 1):
            total -= d[k] * (m + 1 - k) * g[m + 1 - k]
        g[m + 1] = total / (d[0] * (m + 1))
    return g


@dataclass(frozen=True)
class Discretisation:
    """A convolution-quadrature discretisation of D^r (see the module docstring)."""

    name: str
    order: int

    def generating_function(self, zeta: complex | np.ndarray) -> complex | np.ndarray:
        """delta(zeta) of the underlying multistep method (dimensionless)."""
        raise NotImplementedError

    def _weights(self, r: float, count: int) -> np.ndarray:
        raise NotImplementedError

    def weights(self, r: float, count: int, dt: float = 1.0) -> np.ndarray:
        """The first ``count`` weights w_j of ``(D^r x)_n ~= sum_j w_j x_{n-j}``, in s^-r.

        ``count``: a whole number >= 1 (bools and text refused; more weights than fit in the memory limit
        refused before allocating).  ``dt`` (s, within ``SIMULATION_STEP_RANGE``, 1e-9 ... 1e3 s) is the
        step; the weights are those of delta(zeta)^r scaled by dt^-r.
        """
        r = fractional_order(r)
        dt = time_step(dt)
        count = whole_number("count", count, 1)
        check_memory(f"weights(count = {count})", count, 8 * 4)  # the weights and the recurrence's arrays
        return self._weights(r, count) * dt ** (-r)

    def symbol(self, omega: ArrayLike, dt: float) -> complex | np.ndarray:
        """delta(exp(-i omega dt)) / dt (rad/s, complex): the scheme's stand-in for i*omega.

        omega in rad/s (finite), dt in s (within ``SIMULATION_STEP_RANGE``, 1e-9 ... 1e3 s).  The discrete
        steady state of a transfer function H(s) under a sampled sinusoid of circular frequency omega is
        H(symbol(omega, dt)).
        """
        omega = finite_array("omega", omega, ndim=None)
        dt = time_step(dt)
        zeta = np.exp(-1j * omega * dt)
        return self.generating_function(zeta) / dt


@dataclass(frozen=True)
class Trapezoidal(Discretisation):
    """Trapezoidal-rule (Tustin) convolution quadrature: second order, exact phase, rings after kinks."""

    name: str = "trapezoidal"
    order: int = 2

    def generating_function(self, zeta: complex | np.ndarray) -> complex | np.ndarray:
        return 2.0 * (1.0 - zeta) / (1.0 + zeta)

    def _weights(self, r: float, count: int) -> np.ndarray:
        return _trapezoidal_weights(r, count)


@dataclass(frozen=True)
class BDF2(Discretisation):
    """Second-order backward-difference convolution quadrature: L-stable, twice the default's error."""

    name: str = "bdf2"
    order: int = 2

    def generating_function(self, zeta: complex | np.ndarray) -> complex | np.ndarray:
        return 1.5 - 2.0 * zeta + 0.5 * zeta**2

    def _weights(self, r: float, count: int) -> np.ndarray:
        return _bdf2_weights(r, count)


@dataclass(frozen=True)
class GrunwaldLetnikov(Discretisation):
    """Grunwald-Letnikov (backward-Euler) convolution quadrature: first order, for comparison."""

    name: str = "grunwald"
    order: int = 1

    def generating_function(self, zeta: complex | np.ndarray) -> complex | np.ndarray:
        return 1.0 - zeta

    def _weights(self, r: float, count: int) -> np.ndarray:
        return _grunwald_weights(r, count)


@dataclass(frozen=True)
class DampedTwoStep(Discretisation):
    """Two-step second-order family between BDF2 and the trapezoidal rule with damping rho_infinity.

    delta(zeta) = (1 - zeta)(a0 + a1 zeta) / (b0 + b1 zeta), a1 = (rho - 1) / (2 (1 + rho)), a0 = 1 - a1,
    b1 = a1 + 1/2 = rho / (1 + rho), b0 = 1/2 - a1 = 1 / (1 + rho): rho_infinity = 0 is BDF2, the limit
    rho_infinity -> 1 the trapezoidal rule.  See the module docstring.
    """

    name: str = "damped"
    order: int = 2
    rho_infinity: float = 0.5

    def __post_init__(self) -> None:
        rho = finite_scalar("rho_infinity", self.rho_infinity)
        if not 0.0 <= rho < 1.0:
            raise ValueError(f"rho_infinity must lie in [0, 1), got {self.rho_infinity!r}")
        object.__setattr__(self, "rho_infinity", rho)

    @property
    def coefficients(self) -> tuple[float, float, float, float]:
        """(a0, a1, b0, b1) of delta(zeta) = (1 - zeta)(a0 + a1 zeta) / (b0 + b1 zeta)."""
        rho = self.rho_infinity
        a1 = (rho - 1.0) / (2.0 * (1.0 + rho))
        return 1.0 - a1, a1, 1.0 / (1.0 + rho), rho / (1.0 + rho)

    def generating_function(self, zeta: complex | np.ndarray) -> complex | np.ndarray:
        a0, a1, b0, b1 = self.coefficients
        return (1.0 - zeta) * (a0 + a1 * zeta) / (b0 + b1 * zeta)

    def _weights(self, r: float, count: int) -> np.ndarray:
        return _damped_weights(r, *self.coefficients, count)


METHODS = {m.name: m for m in (BDF2(), Trapezoidal(), GrunwaldLetnikov(), DampedTwoStep())}
DEFAULT_METHOD = "damped"


def get_method(method: str | Discretisation) -> Discretisation:
    """A :class:`Discretisation` from itself or from its name ('trapezoidal', 'bdf2', 'grunwald', 'damped')."""
    if isinstance(method, Discretisation):
        return method
    try:
        return METHODS[method]
    except (KeyError, TypeError):
        raise ValueError(f"method must be one of {sorted(METHODS)}, got {method!r}") from None


