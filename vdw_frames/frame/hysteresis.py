"""Story hysteresis: the second kind of "material", with the walls' trial/commit contract.

A story model maps the story drift d (mm) to the force in the story's frame spring (N).  Its initial
stiffness k0 (N/mm) is the story's entry in :attr:`ShearBuilding.stiffnesses`; the model adds the
strength.  Like :class:`~vdw_frames.element.WallState` (and OpenSees's ``UniaxialMaterial``), a
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
  second-order TR-BDF2 rule (a trapezoidal stage to 2 - sqrt(2) of the increment, then BDF2), over
  sub-increments of at most a tenth of the yield drift (one step over a larger increment would
  overshoot the knee and the strength bound), each stage solved by safeguarded Newton, with the
  consistent tangent dF/dd of the whole update, so that a global Newton iteration converges
  quadratically and the frame keeps Newmark's second order.  OpenSees integrates the same equation by
  backward Euler (first order); both converge to the same response.

Units: drift mm, force N, stiffness N/mm.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from .._jit import njit
from .._validation import finite_scalar, non_negative, positive

LINEAR, BILINEAR, BOUC_WEN = 0, 1, 2
PARAMETERS = 6  # row of story_trial's parameters: k0, F_y, hardening, exponent, beta, gamma
STATE = 2  # row of its committed state: drift, then force (Bilinear) or z (Bouc-Wen)

_TR_FRACTION = 2.0 - math.sqrt(2.0)  # TR-BDF2's intermediate point (L-stable, second order)
_LOCAL_TOLERANCE = 1e-13  # on the stage residual, which bounds the error of z (|z| <= about 1)
_LOCAL_ITERATIONS = 200  # Newton, or bisection of a bracket as wide as the increment (2^-200 of it)
_SUB_INCREMENT = 0.1  # largest drift increment of one TR-BDF2 step, in yield drifts
# An increment of 40 strength bounds (in yield drifts) ends on the bound to rounding, whatever z started
# from inside it (see _bouc_wen_update); beyond, no sub-increment is taken at all.
_ASYMPTOTE = 40.0
_MAX_PIECES = 1000  # at most this many sub-increments (longer ones beyond): the work of a trial is bounded


@dataclass(frozen=True)
class Bilinear:
    """Elastoplastic story with kinematic hardening (OpenSees ``Steel01`` without isotropic hardening).

    ``yield_force`` F_y (N, > 0); ``hardening`` b: the post-yield stiffness is b k0, 0 <= b < 1, with k0
    the story's initial stiffness (N/mm).  The yield drift is F_y / k0 (mm).
    """

    yield_force: float
    hardening: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "yield_force", positive("yield_force", self.yield_force))
        object.__setattr__(self, "hardening", _hardening(self.hardening))

    def parameters(self, stiffness: float) -> np.ndarray:
        """The compiled model's parameter row for a story of initial stiffness ``stiffness`` (N/mm)."""
        return np.array([stiffness, self.yield_force, self.hardening, 0.0, 0.0, 0.0])

    kind = BILINEAR

    def new_state(self, stiffness: float) -> StoryState:
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

    def __post_init__(self) -> None:
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

    def new_state(self, stiffness: float) -> StoryState:
        """A trial/commit state at rest for a story of initial stiffness ``stiffness`` (N/mm)."""
        return StoryState(self, stiffness)


STORY_MODELS = (Bilinear, BoucWen)


class StoryArrays(NamedTuple):
    """The story models of n stories as :func:`story_trial` takes them."""

    kinds: np.ndarray  # (n,) int64: LINEAR, BILINEAR or BOUC_WEN
    parameters: np.ndarray  # (n, PARAMETERS): k0 (N/mm), F_y (N), hardening, exponent, beta, gamma
    committed: np.ndarray  # (n, STATE): committed drift (mm), then force (N, Bilinear) or z (Bouc-Wen)


def story_arrays(models: Sequence[Bilinear | BoucWen | None], stiffnesses: Sequence[float]) -> StoryArrays:
    """:class:`StoryArrays` at rest of ``models`` (None: linear) with initial stiffnesses (N/mm)."""
    kinds = np.array([LINEAR if model is None else model.kind for model in models], dtype=np.int64)
    parameters = np.array([[k, 0.0, 0.0, 0.0, 0.0, 0.0] if model is None else model.parameters(k)
                           for model, k in zip(models, stiffnesses, strict=True)], dtype=float)
    return StoryArrays(kinds, parameters.reshape(len(kinds), PARAMETERS), np.zeros((len(kinds), STATE)))


def _hardening(value: object) -> float:
    hardening = non_negative("hardening", value)
    if hardening >= 1.0:
        raise ValueError(f"hardening must lie in [0, 1), got {value!r}")
    return hardening


class StoryState:
    """Trial/commit state (a :class:`~vdw_frames.element.material.Material`) of one story model (``model``
    None: linear) of initial stiffness ``stiffness`` N/mm."""

    def __init__(self, model: Bilinear | BoucWen | None, stiffness: float) -> None:
        if model is not None and not isinstance(model, STORY_MODELS):
            raise ValueError(f"a story model must be Bilinear, BoucWen or None, got {type(model).__name__}")
        self.model = model
        self._arrays = story_arrays([model], [positive("stiffness", stiffness)])
        self._trial: tuple[float, float] | None = None

    def trial(self, drift: float) -> tuple[float, float]:
        """(force N, tangent N/mm) at ``drift`` (mm) from the committed state; the state is untouched."""
        drift = finite_scalar("drift", drift)
        force, tangent, state_value = story_trial(self._arrays, 0, drift)
        self._trial = (drift, state_value)
        return force, tangent

    def commit(self) -> None:
        """Accept the last trial."""
        if self._trial is None:
            raise ValueError("commit() needs a trial() first")
        self._arrays.committed[0] = self._trial
        self._trial = None

    def revert_to_last_commit(self) -> None:
        """Discard the pending trial."""
        self._trial = None

    @property
    def committed_drift(self) -> float:
        """The committed drift, mm."""
        return float(self._arrays.committed[0, 0])


@njit(cache=True, inline="always")
def story_trial(stories, s, drift):
    """(force N, tangent N/mm, new state value) of story ``s`` of ``stories`` (:class:`StoryArrays`) at
    ``drift`` (mm) from its committed state; the state is untouched.  The state value is the force (Bilinear)
    or z (Bouc-Wen) to commit."""
    kind = stories.kinds[s]
    k0, yield_force, hardening = stories.parameters[s, 0], stories.parameters[s, 1], stories.parameters[s, 2]
    committed_drift, committed_value = stories.committed[s, 0], stories.committed[s, 1]
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
    exponent, beta, gamma = stories.parameters[s, 3], stories.parameters[s, 4], stories.parameters[s, 5]
    yield_drift = yield_force / k0
    z, dz_dd = _bouc_wen_update(committed_value, (drift - committed_drift) / yield_drift, exponent, beta, gamma)
    force = hardening * k0 * drift + (1.0 - hardening) * yield_force * z
    tangent = hardening * k0 + (1.0 - hardening) * k0 * dz_dd
    return force, tangent, z


@njit(cache=True)
def _rate(z, direction, exponent, beta, gamma):
    """(Phi, dPhi/dz) of dz/dx = Phi(z) = 1 - |z|^n (beta sgn(dx z) + gamma), x = d / d_y."""
    magnitude = abs(z)
    psi = gamma + beta if direction * z > 0.0 else gamma - beta
    if magnitude == 0.0 or psi == 0.0:  # (psi = 0: no |z|^n at all, which could overflow to inf * 0)
        return 1.0, 0.0
    power = magnitude**exponent
    return 1.0 - power * psi, -exponent * power / magnitude * (1.0 if z > 0.0 else -1.0) * psi


@njit(cache=True)
def _solve_stage(start, step, exponent, beta, gamma, direction):
    """Root z of g(z) = z - start - step Phi(z), with 1 - step Phi'(z) there; NaN if not found.

    g' >= 1 (beta >= gamma), so the root is unique, |z - root| <= |g(z)| for any z, and it lies within
    |g(start)| of ``start``: safeguarded Newton, bisecting whenever Newton leaves the bracket, stopped on
    the residual itself.
    """
    z = start
    phi, slope = _rate(z, direction, exponent, beta, gamma)
    residual = z - start - step * phi
    low, high = start - abs(residual), start + abs(residual)
    for _ in range(_LOCAL_ITERATIONS):
        derivative = 1.0 - step * slope
        if abs(residual) <= _LOCAL_TOLERANCE * (1.0 + abs(z)):
            return z, derivative
        if residual > 0.0:
            high = z
        else:
            low = z
        candidate = z - residual / derivative
        if not low <= candidate <= high:  # (also NaN)
            candidate = 0.5 * (low + high)
        z = candidate
        phi, slope = _rate(z, direction, exponent, beta, gamma)
        residual = z - start - step * phi
    return np.nan, np.nan


@njit(cache=True)
def _tr_bdf2(z_start, increment, exponent, beta, gamma, direction):
    """One TR-BDF2 step of dz/dx = Phi(z) over ``increment``: (z, dz/dz_start, dz/dincrement).

    Stage 1, trapezoidal over g x: z_g = z_0 + (g x / 2)(Phi(z_0) + Phi(z_g)).
    Stage 2, BDF2: z = c1 z_g - c2 z_0 + c3 x Phi(z), c1 = 1 / (g (2 - g)), c2 = (1 - g)^2 / (g (2 - g)),
    c3 = (1 - g) / (2 - g); the derivatives follow both stages by implicit differentiation.
    """
    g = _TR_FRACTION
    phi_0, slope_0 = _rate(z_start, direction, exponent, beta, gamma)
    half = 0.5 * g * increment
    z_g, stage1 = _solve_stage(z_start + half * phi_0, half, exponent, beta, gamma, direction)
    phi_g, _ = _rate(z_g, direction, exponent, beta, gamma)
    dzg_dz0 = (1.0 + half * slope_0) / stage1
    dzg_dx = 0.5 * g * (phi_0 + phi_g) / stage1
    c1 = 1.0 / (g * (2.0 - g))
    c2 = (1.0 - g) ** 2 / (g * (2.0 - g))
    c3 = (1.0 - g) / (2.0 - g)
    z, stage2 = _solve_stage(c1 * z_g - c2 * z_start, c3 * increment, exponent, beta, gamma, direction)
    phi, _ = _rate(z, direction, exponent, beta, gamma)
    return z, (c1 * dzg_dz0 - c2) / stage2, (c1 * dzg_dx + c3 * phi) / stage2


@njit(cache=True)
def _pieces(z_committed, increment, pieces, exponent, beta, gamma, direction, bound):
    """(z, dz/dincrement) after ``pieces`` equal TR-BDF2 steps over ``increment``, the tangent chained
    through them; a step that would leave the strength bound from inside is clamped on it (dz = 0)."""
    piece = increment / pieces
    z = z_committed
    dz_dx = 0.0
    for _ in range(pieces):
        inside = abs(z) <= bound
        z_new, dz_dz0, dz_dpiece = _tr_bdf2(z, piece, exponent, beta, gamma, direction)
        if inside and abs(z_new) > bound:
            z, dz_dx = (bound if z_new > 0.0 else -bound), 0.0
        else:
            z, dz_dx = z_new, dz_dz0 * dz_dx + dz_dpiece / pieces
    return z, dz_dx


@njit(cache=True)
def _bouc_wen_update(z_committed, increment, exponent, beta, gamma):
    """(z, dz/dd * d_y) after a drift increment of ``increment`` yield drifts.

    TR-BDF2 (:func:`_tr_bdf2`) over sub-increments of about ``_SUB_INCREMENT`` yield drifts: one step up
    to it; beyond, the results of m and m + 1 equal steps (m = floor(|x| / h)) blended linearly in |x| / h
    - m, so that z stays a continuous function of the drift (a jump in the number of steps would make the
    trial force jump, which Newton cannot settle), the blend included in the consistent tangent (at a
    whole |x| / h the slope has a small kink; the tangent there is the one of larger increments).  The
    exact solution never leaves |z| <= (beta + gamma)^(-1/n) once inside; a step that would is clamped.

    The work is bounded whatever the increment (a runaway frame, a tiny yield drift).  From |z| <= bound
    B = (beta + gamma)^(-1/n), dz/dx >= 1 until z has the increment's sign (beta >= gamma), then
    dz/dx = 1 - (|z| / B)^n >= 1 - |z| / B (n >= 1), so B - |z| <= B exp(-(|x| - B) / B): an increment of
    ``_ASYMPTOTE`` B or more ends on the bound to rounding (within e^-39 B), and z = +-B, dz/dx = 0 are
    returned without stepping.  Below that, at most ``_MAX_PIECES`` equal steps are taken (longer than
    ``_SUB_INCREMENT`` only when B > _MAX_PIECES * _SUB_INCREMENT / _ASYMPTOTE = 2.5, i.e. beta + gamma
    < 0.4 for n = 1).
    """
    if increment == 0.0:
        # No increment: the unloading branch's slope, the stiffer one (direction opposite to z).
        phi, _ = _rate(z_committed, -1.0 if z_committed > 0.0 else 1.0, exponent, beta, gamma)
        return z_committed, phi
    direction = 1.0 if increment > 0.0 else -1.0
    bound = (beta + gamma) ** (-1.0 / exponent)
    if abs(z_committed) <= bound and abs(increment) >= _ASYMPTOTE * bound:
        return direction * bound, 0.0
    size = abs(increment) / _SUB_INCREMENT
    if size <= 1.0:
        return _pieces(z_committed, increment, 1, exponent, beta, gamma, direction, bound)
    if size >= _MAX_PIECES:  # (the blend below reaches _MAX_PIECES steps exactly here: z stays continuous)
        return _pieces(z_committed, increment, _MAX_PIECES, exponent, beta, gamma, direction, bound)
    fewer = int(size)
    weight = size - fewer
    z_a, dz_a = _pieces(z_committed, increment, fewer, exponent, beta, gamma, direction, bound)
    z_b, dz_b = _pieces(z_committed, increment, fewer + 1, exponent, beta, gamma, direction, bound)
    z = (1.0 - weight) * z_a + weight * z_b
    return z, (1.0 - weight) * dz_a + weight * dz_b + (z_b - z_a) * direction / _SUB_INCREMENT
