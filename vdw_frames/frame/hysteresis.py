"""Story hysteresis: the second kind of "material", with the walls' trial/commit contract.

A story model maps the story drift d (mm) to the force in the story's frame spring (N).  Its initial
stiffness k0 (N/mm) is the story's entry in :attr:`ShearBuilding.stiffnesses`; the model adds the
strength.  Like :class:`~vdw_frames.DamperState` (and OpenSees's ``UniaxialMaterial``), a
:class:`StoryState` gives the force and tangent for a trial drift without touching its state
(``trial``), accepts the last trial (``commit``) or discards it (``revert_to_last_commit``), so that an
iterating (Newton) integrator can drive it.  :func:`story_trial` is the one compiled implementation;
the frame integrator calls it directly.

Models:

* :class:`Bilinear` -- elastoplastic with kinematic hardening: OpenSees ``Steel01`` with no isotropic
  hardening (a1 = a3 = 0), SRC/material/uniaxial/Steel01.cpp ``determineTrialState``:
  F = max(b k0 d - (1 - b) F_y, min(b k0 d + (1 - b) F_y, F_c + k0 (d - d_c))), tangent k0 inside the
  bounds and b k0 on them.  Exact for any drift increment (the return map of a piecewise-linear law).
* :class:`BoucWen` -- smooth hysteresis (see its docstring for the form and the mapping to OpenSees's
  ``BoucWen``).  The evolution equation is integrated in the drift increment by the L-stable,
  second-order TR-BDF2 rule (a trapezoidal stage to 2 - sqrt(2) of the increment, then BDF2), each
  stage solved by safeguarded Newton, with the consistent tangent dF/dd of the whole update, so that a
  global Newton iteration converges quadratically and the frame keeps Newmark's second order.  OpenSees
  integrates the same equation by backward Euler (first order); both converge to the same response.

Units: drift mm, force N, stiffness N/mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._jit import njit
from .._validation import finite_scalar, non_negative, positive

LINEAR, BILINEAR, BOUC_WEN = 0, 1, 2
PARAMETERS = 6  # row of story_trial's parameters: k0, F_y, hardening, exponent, beta, gamma
STATE = 2  # row of its committed state: drift, then force (Bilinear) or z (Bouc-Wen)

_TR_FRACTION = 2.0 - math.sqrt(2.0)  # TR-BDF2's intermediate point (L-stable, second order)
_LOCAL_TOLERANCE = 1e-13  # relative Newton tolerance on z (|z| <= about 1)
_LOCAL_ITERATIONS = 60


@dataclass(frozen=True)
class Bilinear:
    """Elastoplastic story with kinematic hardening (OpenSees ``Steel01`` without isotropic hardening).

    ``yield_force`` F_y (N, > 0); ``hardening`` b: the post-yield stiffness is b k0, 0 <= b < 1, with k0
    the story's initial stiffness (N/mm).  The yield drift is F_y / k0 (mm).
    """

    yield_force: float
    hardening: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "yield_force", positive("yield_force", self.yield_force))
        object.__setattr__(self, "hardening", _hardening(self.hardening))

    def parameters(self, stiffness: float) -> np.ndarray:
        """The compiled model's parameter row for a story of initial stiffness ``stiffness`` (N/mm)."""
        return np.array([stiffness, self.yield_force, self.hardening, 0.0, 0.0, 0.0])

    kind = BILINEAR

    def new_state(self, stiffness: float) -> "StoryState":
        """A trial/commit state at rest for a story of initial stiffness ``stiffness`` (N/mm)."""
        return StoryState(self, stiffness)


@dataclass(frozen=True)
class BoucWen:
    """Smooth Bouc-Wen story hysteresis, no degradation.

    F = b k0 d + (1 - b) F_y z,   dz/dd = (1 / d_y) [1 - |z|^n (beta sgn(dd z) + gamma)],   d_y = F_y / k0,

    with ``yield_force`` F_y (N, > 0), ``hardening`` b (0 <= b < 1), ``exponent`` n (>= 1: the larger, the
    sharper the knee), ``beta`` and ``gamma``; k0 is the story's initial stiffness (N/mm).  On loading z
    tends to (beta + gamma)^(-1/n) (1 with the defaults, so F_y is the strength of the hysteretic part).
    Accepted: beta + gamma > 0 (bounded z) and beta >= gamma (passive: unloading is at least as stiff as
    elastic; it also makes the implicit update a monotone equation with one root).

    The same as OpenSees's ``uniaxialMaterial BoucWen alpha ko n gamma beta Ao deltaA deltaNu deltaEta``
    with alpha = b, ko = k0, n = n, Ao = 1, deltaA = deltaNu = deltaEta = 0 and
    gamma_OpenSees = gamma / d_y^n, beta_OpenSees = beta / d_y^n (its z is d_y z, its sigma
    alpha ko eps + (1 - alpha) ko z_OpenSees).
    """

    yield_force: float
    hardening: float = 0.0
    exponent: float = 1.0
    beta: float = 0.5
    gamma: float = 0.5

    def __post_init__(self):
        object.__setattr__(self, "yield_force", positive("yield_force", self.yield_force))
        object.__setattr__(self, "hardening", _hardening(self.hardening))
        exponent = finite_scalar("exponent", self.exponent)
        if not 1.0 <= exponent <= 100.0:
            raise ValueError(f"exponent must lie in [1, 100], got {self.exponent!r}")
        object.__setattr__(self, "exponent", exponent)
        beta, gamma = finite_scalar("beta", self.beta), finite_scalar("gamma", self.gamma)
        if not beta + gamma > 0.0 or beta < gamma:
            raise ValueError(f"Bouc-Wen needs beta + gamma > 0 and beta >= gamma, got beta = {self.beta!r}, "
                             f"gamma = {self.gamma!r}")
        object.__setattr__(self, "beta", beta)
        object.__setattr__(self, "gamma", gamma)

    kind = BOUC_WEN

    def parameters(self, stiffness: float) -> np.ndarray:
        """The compiled model's parameter row for a story of initial stiffness ``stiffness`` (N/mm)."""
        return np.array([stiffness, self.yield_force, self.hardening, self.exponent, self.beta, self.gamma])

    def new_state(self, stiffness: float) -> "StoryState":
        """A trial/commit state at rest for a story of initial stiffness ``stiffness`` (N/mm)."""
        return StoryState(self, stiffness)


STORY_MODELS = (Bilinear, BoucWen)


def _hardening(value) -> float:
    hardening = non_negative("hardening", value)
    if hardening >= 1.0:
        raise ValueError(f"hardening must lie in [0, 1), got {value!r}")
    return hardening


class StoryState:
    """Trial/commit state of one story model (``model`` None: linear) of initial stiffness ``stiffness`` N/mm."""

    def __init__(self, model, stiffness: float):
        if model is not None and not isinstance(model, STORY_MODELS):
            raise ValueError(f"a story model must be Bilinear, BoucWen or None, got {type(model).__name__}")
        stiffness = positive("stiffness", stiffness)
        self.model = model
        self.kind = LINEAR if model is None else model.kind
        self.parameters = (np.array([stiffness, 0.0, 0.0, 0.0, 0.0, 0.0]) if model is None
                           else model.parameters(stiffness))
        self.committed = np.zeros(STATE)
        self._trial = None

    def trial(self, drift: float):
        """(force N, tangent N/mm) at ``drift`` (mm) from the committed state; the state is untouched."""
        drift = finite_scalar("drift", drift)
        force, tangent, state_value = story_trial(self.kind, *self.parameters, *self.committed, drift)
        self._trial = (drift, force if self.kind != BOUC_WEN else state_value)
        return force, tangent

    def commit(self) -> None:
        """Accept the last trial."""
        if self._trial is None:
            raise ValueError("commit() needs a trial() first")
        self.committed[:] = self._trial
        self._trial = None

    def revert_to_last_commit(self) -> None:
        """Discard the pending trial."""
        self._trial = None

    @property
    def committed_drift(self) -> float:
        return float(self.committed[0])


@njit(cache=True)
def story_trial(kind, k0, yield_force, hardening, exponent, beta, gamma, committed_drift, committed_value, drift):
    """(force N, tangent N/mm, new state value) of a story model at ``drift`` (mm) from its committed state.

    ``kind``: LINEAR, BILINEAR or BOUC_WEN; then the parameter row (k0, F_y, b, n, beta, gamma) and the
    committed state (drift, force) for Bilinear, (drift, z) for Bouc-Wen.  The state value is the force or
    z to commit.  (Scalars, not rows: numba passes arrays to a call as whole structures.)
    """
    if kind == LINEAR:
        return k0 * drift, k0, k0 * drift
    if kind == BILINEAR:
        elastic = committed_value + k0 * (drift - committed_drift)
        bound = (1.0 - hardening) * yield_force
        upper = hardening * k0 * drift + bound
        lower = hardening * k0 * drift - bound
        if elastic > upper:
            return upper, hardening * k0, upper
        if elastic < lower:
            return lower, hardening * k0, lower
        return elastic, k0, elastic
    # Bouc-Wen
    yield_drift = yield_force / k0
    z, dz_dd = _bouc_wen_update(committed_value, (drift - committed_drift) / yield_drift, exponent, beta, gamma)
    force = hardening * k0 * drift + (1.0 - hardening) * yield_force * z
    tangent = hardening * k0 + (1.0 - hardening) * k0 * dz_dd
    return force, tangent, z


@njit(cache=True)
def _rate(z, direction, exponent, beta, gamma):
    """(Phi, dPhi/dz) of dz/dx = Phi(z) = 1 - |z|^n (beta sgn(dx z) + gamma), x = d / d_y."""
    magnitude = abs(z)
    if magnitude == 0.0:
        return 1.0, 0.0
    psi = gamma + beta if direction * z > 0.0 else gamma - beta
    power = magnitude**exponent
    return 1.0 - power * psi, -exponent * power / magnitude * (1.0 if z > 0.0 else -1.0) * psi


@njit(cache=True)
def _solve_stage(start, step, exponent, beta, gamma, direction):
    """Root z of g(z) = z - start - step Phi(z), and 1 - step Phi'(z) there (g' >= 1: one root).

    Safeguarded Newton: |g(z) - g(y)| >= |z - y| brackets the root within |g(start)| of ``start``.
    """
    z = start
    phi, slope = _rate(z, direction, exponent, beta, gamma)
    residual = z - start - step * phi
    low, high = start - abs(residual), start + abs(residual)
    for _ in range(_LOCAL_ITERATIONS):
        derivative = 1.0 - step * slope
        if residual > 0.0:
            high = z
        elif residual < 0.0:
            low = z
        else:
            return z, derivative
        candidate = z - residual / derivative
        if not low < candidate < high:
            candidate = 0.5 * (low + high)
        change = abs(candidate - z)
        z = candidate
        phi, slope = _rate(z, direction, exponent, beta, gamma)
        residual = z - start - step * phi
        if change <= _LOCAL_TOLERANCE * max(1.0, abs(z)):
            break
    return z, 1.0 - step * slope


@njit(cache=True)
def _bouc_wen_update(z_committed, increment, exponent, beta, gamma):
    """(z, dz/dd * d_y) after a drift increment of ``increment`` yield drifts, by TR-BDF2.

    Stage 1, trapezoidal over g x: z_g = z_n + (g x / 2)(Phi(z_n) + Phi(z_g)).
    Stage 2, BDF2: z = c1 z_g - c2 z_n + c3 x Phi(z), c1 = 1 / (g (2 - g)), c2 = (1 - g)^2 / (g (2 - g)),
    c3 = (1 - g) / (2 - g); the tangent follows both stages by implicit differentiation.
    """
    if increment == 0.0:
        # No increment: the unloading branch's slope, the stiffer one (direction opposite to z).
        phi, _ = _rate(z_committed, -1.0 if z_committed > 0.0 else 1.0, exponent, beta, gamma)
        return z_committed, phi
    direction = 1.0 if increment > 0.0 else -1.0
    g = _TR_FRACTION
    phi_n, _ = _rate(z_committed, direction, exponent, beta, gamma)
    half = 0.5 * g * increment
    z_g, stage1_derivative = _solve_stage(z_committed + half * phi_n, half, exponent, beta, gamma, direction)
    phi_g, _ = _rate(z_g, direction, exponent, beta, gamma)
    dzg_dx = 0.5 * g * (phi_n + phi_g) / stage1_derivative
    c1 = 1.0 / (g * (2.0 - g))
    c2 = (1.0 - g) ** 2 / (g * (2.0 - g))
    c3 = (1.0 - g) / (2.0 - g)
    z, stage2_derivative = _solve_stage(c1 * z_g - c2 * z_committed, c3 * increment, exponent, beta, gamma,
                                        direction)
    phi, _ = _rate(z, direction, exponent, beta, gamma)
    dz_dx = (c1 * dzg_dx + c3 * phi) / stage2_derivative
    return z, dz_dx
