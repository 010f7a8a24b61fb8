"""Nonlinear static (pushover) analysis of a shear building: FEMA P695 (2009) Section 6.3.

The lateral loads are lambda p on the floors, p a fixed pattern; the roof displacement is prescribed in
equal increments up to ``target_drift_ratio`` x the building height (displacement control), and at each
increment Newton's method solves the bordered system

    [ K_T   -p ] [du     ]   [ lambda p - B^T f(B u) ]
    [ e_n^T  0 ] [dlambda] = [ U - u_n               ]

for the floor displacements u and the load factor lambda, with f the story forces: the story model
(trial/commit, :class:`~vdw_frames.frame.hysteresis.StoryState`), P-Delta -P/h d and the walls at their
static (zero-frequency) stiffness.  Displacement control follows the capacity curve past its peak into
the negative-stiffness branch that P-Delta gives a yielding story; only a curve that snaps back (a story
softening faster than the stories in series with it unload) defeats it, and that is reported.  The
analysis ends at the target, or earlier where the base shear has fallen to zero: the building has lost
all its lateral strength to P-Delta and would need pulling back to stand (static collapse).

A wall's static stiffness is its stiffness K(s) at s = 0: G1 A / h for an :class:`~vdw_frames.FDMKDamper`
(eqs. (3)-(5) of the paper: the Kelvin branch's spring; the Maxwell branch relaxes to zero), zero for a
Maxwell-only wall (G1 = 0), and in series with the support for a :class:`~vdw_frames.SupportedDamper`.

From the capacity curve (base shear V against roof displacement delta), FEMA P695 Section 6.3:

* V_max, the largest base shear;
* the effective yield roof displacement, eq. (6-7): delta_y,eff = C0 (V_max / W) (g / 4 pi^2) max(T, T1)^2,
  with C0 from eq. (6-8): C0 = phi_1,r sum(m_x phi_1,x) / sum(m_x phi_1,x^2) (phi_1 the fundamental mode,
  r the roof) and W the seismic weight sum(m_x) g;
* the ultimate roof displacement delta_u at 20 % strength loss (V = 0.8 V_max after the peak);
* the period-based ductility, eq. (6-6): mu_T = delta_u / delta_y,eff.

Units: N, mm, s, tonne; g = 9806.65 mm/s^2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import eigh

from .._validation import finite_array, positive, show, whole_number
from ..motion.record import G
from .building import ShearBuilding, static_wall_stiffness, story_matrix
from .hysteresis import StoryState

PATTERNS = ("modal", "triangular")
STRENGTH_LOSS = 0.2  # FEMA P695 Section 6.3: delta_u at 20 % loss of V_max
MAX_STEPS = 100_000  # increments a pushover may take (a bound on the work a small input can ask for)
_HALVINGS = 10  # an increment Newton cannot solve is cut in half up to this many times
_ITERATIONS = 50
_FORCE_TOLERANCE = 1e-10  # of the largest force in the step
_DISPLACEMENT_TOLERANCE = 1e-10  # mm
_EVENT_PRECISION = 1e-9  # a kink (a story yielding) is located to this fraction of an increment


@dataclass(frozen=True)
class PushoverResult:
    """A capacity curve and its FEMA P695 Section 6.3 quantities.

    Histories, one entry per converged increment from rest: ``roof_displacement`` (mm),
    ``base_shear`` (N: the sum of the lateral loads, which equals story 1's shear including P-Delta and
    walls), ``story_drift`` (mm, (points, stories)).  ``pattern``: the lateral load shape (sums to 1,
    so that the load factor is the base shear).  ``height`` (mm) and ``weight`` W (N, sum of the floor
    masses x g).  ``period`` (s): the period in eq. (6-7), max(T, T1); ``c0`` (-) from eq. (6-8);
    ``mode_shape``: phi_1 of the elastic static model (frame, walls' static stiffness, P-Delta),
    roof = 1.  ``max_base_shear`` V_max (N) and ``peak_roof_displacement`` (mm, where it occurs);
    ``yield_roof_displacement`` delta_y,eff (mm, eq. 6-7); ``ultimate_roof_displacement`` delta_u (mm,
    V = 0.8 V_max past the peak, interpolated linearly between increments; None when the curve does not
    lose 20 % of its strength before the target); ``period_based_ductility`` mu_T (-, eq. 6-6; None
    with delta_u).  ``wall_stiffness`` (N/mm per story): the walls' static stiffness used.
    ``end``: "target" or "no strength left" (the base shear fell to zero or below before the target).
    """

    roof_displacement: np.ndarray
    base_shear: np.ndarray
    story_drift: np.ndarray
    pattern: np.ndarray
    height: float
    weight: float
    period: float
    c0: float
    mode_shape: np.ndarray
    wall_stiffness: np.ndarray
    max_base_shear: float
    peak_roof_displacement: float
    yield_roof_displacement: float
    ultimate_roof_displacement: float | None
    period_based_ductility: float | None
    end: str = "target"

    @property
    def roof_drift_ratio(self) -> np.ndarray:
        """Roof displacement / building height (-)."""
        return self.roof_displacement / self.height

    @property
    def normalized_base_shear(self) -> np.ndarray:
        """V / W (-)."""
        return self.base_shear / self.weight


def elastic_mode(building: ShearBuilding, wall_stiffness: np.ndarray) -> tuple[float, np.ndarray]:
    """(T1 in s, phi_1 with roof ordinate 1) of the elastic static model: initial story stiffness, the walls'
    static stiffness and the P-Delta stiffness -P/h.  ValueError when that model is unstable."""
    stiffness = story_matrix(np.asarray(building.stiffnesses) + wall_stiffness
                             + np.asarray(building.geometric_stiffness))
    eigenvalues, shapes = eigh(stiffness, np.diag(building.masses))
    if not eigenvalues[0] > 0.0:
        raise ValueError("the building is unstable under its gravity loads (P-Delta stiffness exceeds the "
                         "elastic stiffness): no pushover")
    shape = shapes[:, 0] / shapes[-1, 0]
    return 2.0 * math.pi / math.sqrt(eigenvalues[0]), shape


def pushover(building: ShearBuilding, pattern="modal", target_drift_ratio: float = 0.05, *,
             period: float | None = None, steps: int = 500) -> PushoverResult:
    """Pushover of ``building`` to a roof displacement of ``target_drift_ratio`` x its height (FEMA P695 Sec. 6.3).

    ``pattern``: "modal" (FEMA P695 Sec. 6.3: loads m_x phi_1,x, phi_1 the fundamental mode of the elastic
    static model), "triangular" (m_x h_x, h_x the floor's elevation: ASCE 7-16 Sec. 12.8.3 with k = 1) or
    an array with one non-negative load per floor (not all zero); normalised to sum 1.
    ``target_drift_ratio`` (-, > 0, at most 1): roof displacement / height at the end.  ``period`` (s):
    the period of eq. (6-7), max(T, T1) with T = C_u T_a (Sec. 5.2.5) and T1 the analytical one; default
    the elastic static model's T1.  ``steps``: equal roof-displacement increments (1 ... 100 000); an
    increment Newton cannot solve is halved up to 10 times; an increment over which a story's tangent jumps
    (a Bilinear story yielding) is bisected so that the curve has a point just past the corner (within 1e-9
    of an increment), keeping V_max exact.  The building needs ``story_heights``.

    The analysis goes past the peak into the negative-stiffness branch, and ends at the target or at the
    first increment whose base shear is zero or less (after a peak: no lateral strength left).  ValueError,
    saying where it stopped (roof displacement, base shear) and why, when it cannot reach the target:
    Newton fails even on the smallest increment, or the capacity curve snaps back (roof displacement
    control cannot follow it).  Returns a :class:`PushoverResult`.
    """
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    if building.story_heights is None:
        raise ValueError("a pushover needs story_heights (the target is a roof drift ratio)")
    target_drift_ratio = positive("target_drift_ratio", target_drift_ratio)
    if target_drift_ratio > 1.0:
        raise ValueError(f"target_drift_ratio must be at most 1 (a roof displacement of the whole height), "
                         f"got {show(target_drift_ratio)}")
    steps = whole_number("steps", steps, 1)
    if steps > MAX_STEPS:
        raise ValueError(f"steps must be at most {MAX_STEPS}, got {steps}")
    walls = static_wall_stiffness(building)
    t1, shape = elastic_mode(building, walls)
    period = t1 if period is None else positive("period", period)
    masses = np.asarray(building.masses)
    loads = _pattern(pattern, building, shape)
    height = float(np.sum(building.story_heights))
    weight = float(masses.sum() * G)
    c0 = float(shape[-1] * np.sum(masses * shape) / np.sum(masses * shape**2))  # eq. (6-8)

    curve = _Curve(building, loads, walls)
    target = target_drift_ratio * height
    increment = target / steps
    roof, shear, drift = [0.0], [0.0], [np.zeros(building.stories)]
    end = "target"
    while roof[-1] < target * (1.0 - 1e-12):
        if shear[-1] <= 0.0 < max(shear):
            end = "no strength left"
            break
        size = min(increment, target - roof[-1])
        for _ in range(_HALVINGS + 1):
            if curve.advance(roof[-1] + size):
                break
            size /= 2.0
        else:
            snap = curve.snaps_back(curve.last_tangent)
            why = (f"the capacity curve snaps back ({snap}); roof displacement control cannot follow it" if snap else
                   f"Newton did not converge on the next increment, even at 1/{2 ** _HALVINGS} of it ({curve.failure})")
            raise ValueError(f"pushover stopped at a roof displacement of {roof[-1]:.6g} mm (roof drift ratio "
                             f"{roof[-1] / height:.4g}, base shear {shear[-1] / 1e3:.6g} kN) short of the target "
                             f"{target:.6g} mm: {why}")
        if curve.kinked() and size > _EVENT_PRECISION * increment:
            _land_on_kink(curve, roof[-1], size, _EVENT_PRECISION * increment)
        curve.commit()
        snap = curve.snaps_back()
        if snap is not None:
            raise ValueError(f"pushover stopped at a roof displacement of {curve.roof:.6g} mm (roof drift ratio "
                             f"{curve.roof / height:.4g}, base shear {curve.load / 1e3:.6g} kN) short of the target "
                             f"{target:.6g} mm: the capacity curve snaps back ({snap}); roof displacement "
                             "control cannot follow it")
        roof.append(curve.roof)
        shear.append(curve.load)
        drift.append(curve.drift.copy())
    return _result(np.array(roof), np.array(shear), np.array(drift), loads, height, weight, period, c0, shape, walls,
                   end)


def _land_on_kink(curve: _Curve, start: float, size: float, precision: float) -> None:
    """Leave ``curve`` at the trial just past the first kink within ``start + (0, size]`` (bisection to
    ``precision`` mm), so that a piecewise-linear capacity curve keeps its corners (V_max at a story's
    yield is then exact, not the nearest increment's)."""
    low, high = 0.0, size
    while high - low > precision:
        middle = 0.5 * (low + high)
        if curve.advance(start + middle) and not curve.kinked():
            low = middle
        else:
            high = middle
    if not curve.advance(start + high):  # converged before at this or a larger increment
        raise ValueError(f"pushover: Newton failed just past a kink at a roof displacement of {start + high:.6g} mm "
                         f"({curve.failure})")


def _pattern(pattern, building: ShearBuilding, shape: np.ndarray) -> np.ndarray:
    masses = np.asarray(building.masses)
    if isinstance(pattern, str):
        if pattern == "modal":
            loads = masses * shape
        elif pattern == "triangular":
            if building.story_heights is None:
                raise ValueError("a triangular pattern needs story heights")
            loads = masses * np.cumsum(building.story_heights)
        else:
            raise ValueError(f"pattern must be one of {PATTERNS} or one load per floor, got {pattern!r}")
        if (loads < 0).any():
            raise ValueError("the fundamental mode of this building changes sign over the height; give the "
                             "pattern as loads")
    else:
        loads = finite_array("pattern", pattern)
        if loads.size != building.stories:
            raise ValueError(f"pattern has {loads.size} loads for {building.stories} floors")
        if (loads < 0).any() or not loads.sum() > 0:
            raise ValueError(f"pattern loads must be >= 0 and not all zero, got {show(loads.tolist())}")
    return loads / loads.sum()


class _Curve:
    """The equilibrium state of a pushover: committed story states, trial displacements and load factor."""

    def __init__(self, building: ShearBuilding, loads: np.ndarray, walls: np.ndarray):
        self.loads = loads
        self.linear = walls + np.asarray(building.geometric_stiffness)  # walls and P-Delta, per story
        self.states = [StoryState(model, k)
                       for model, k in zip(building.story_models, building.stiffnesses, strict=True)]
        n = building.stories
        self.u = np.zeros(n)
        self.load = 0.0
        self._trial: tuple[np.ndarray, float, np.ndarray, np.ndarray] | None = None
        self.failure = ""
        self.initial = np.asarray(building.stiffnesses, dtype=float)
        self.tangent = self.initial + self.linear
        self.last_tangent = self.tangent

    @property
    def roof(self) -> float:
        return float(self.u[-1])

    @property
    def drift(self) -> np.ndarray:
        return np.diff(self.u, prepend=0.0)

    def _forces(self, u):
        drift = np.diff(u, prepend=0.0)
        force, tangent = np.empty(drift.size), np.empty(drift.size)
        for k, state in enumerate(self.states):
            force[k], tangent[k] = state.trial(float(drift[k]))
        return force + self.linear * drift, tangent + self.linear

    def advance(self, roof: float) -> bool:
        """Newton from the committed state to equilibrium at roof displacement ``roof``; False if it fails."""
        n = self.u.size
        u, load = self.u.copy(), self.load
        matrix = np.zeros((n + 1, n + 1))
        matrix[n, n - 1] = 1.0
        matrix[:n, n] = -self.loads
        correction = np.zeros(n + 1)
        for iteration in range(_ITERATIONS):
            force, tangent = self._forces(u)
            shear_from_above = np.append(force[1:], 0.0)
            residual = load * self.loads - (force - shear_from_above)
            scale = max(1.0, float(np.abs(force).max()), abs(load))
            correction_norm = math.inf if iteration == 0 else float(np.abs(correction[:n]).max())
            if (iteration > 0 and float(np.abs(residual).max()) <= _FORCE_TOLERANCE * scale
                    and abs(u[-1] - roof) <= _DISPLACEMENT_TOLERANCE and correction_norm <= 1e-6 * (1.0 + abs(roof))):
                self._trial = (u, load, force, tangent)
                return True
            self.last_tangent = tangent
            matrix[:n, :n] = story_matrix(tangent)
            rhs = np.append(residual, roof - u[-1])
            try:
                correction = np.linalg.solve(matrix, rhs)
            except np.linalg.LinAlgError:
                self.failure = "the tangent is singular: two or more stories have no stiffness left at once"
                return False
            if not np.isfinite(correction).all():
                self.failure = "the Newton correction is not finite"
                return False
            u = u + correction[:n]
            load += float(correction[n])
        self.failure = f"the unbalanced force stayed above {_FORCE_TOLERANCE:g} of the story forces after " \
                       f"{_ITERATIONS} iterations"
        return False

    def kinked(self) -> bool:
        """Whether a story's own tangent jumped (by over half its initial stiffness) between the committed
        state and the pending trial: a corner of a piecewise-linear model (Bilinear yielding or unloading)."""
        assert self._trial is not None, "kinked() needs a converged trial"
        tangent = self._trial[3]
        return bool((np.abs(tangent - self.tangent) > 0.5 * self.initial).any())

    def commit(self) -> None:
        assert self._trial is not None, "commit() needs a converged trial"
        u, load, force, tangent = self._trial
        for k, state in enumerate(self.states):
            state.trial(float(u[k] - (u[k - 1] if k else 0.0)))  # the converged trial, then commit it
            state.commit()
        self.u, self.load, self.tangent = u, load, tangent
        self._trial = None

    def snaps_back(self, tangent=None) -> str | None:
        """Why the curve snaps back with the story tangents ``tangent`` (default: the committed state's), or None.

        In a shear building story k carries lambda P_k (P_k the loads above it), so the roof moves by
        dU = dlambda sum_k P_k / k_t,k.  Past the peak (a story with negative tangent, dlambda < 0) the
        roof must keep moving forward: when sum_k P_k / k_t,k > 0 instead, the path turns back in U.
        """
        tangent = self.tangent if tangent is None else tangent
        if not (tangent < 0).any() or (tangent == 0).any():
            return None
        above = np.cumsum(self.loads[::-1])[::-1]
        flexibility = float(np.sum(above / tangent))
        if flexibility <= 0.0:
            return None
        soft = [k + 1 for k in np.flatnonzero(tangent < 0)]
        return (f"story {', '.join(map(str, soft))} softens at {show(float(tangent[soft[0] - 1]))} N/mm, faster than "
                f"the stories in series with it unload")


def _result(roof, shear, drift, loads, height, weight, period, c0, shape, walls, end) -> PushoverResult:
    peak = int(np.argmax(shear))
    max_shear = float(shear[peak])
    if not max_shear > 0.0:
        raise ValueError("the pushover found no positive base shear")
    yield_roof = c0 * (max_shear / weight) * (G / (4.0 * math.pi**2)) * period**2  # eq. (6-7)
    ultimate = None
    residual = (1.0 - STRENGTH_LOSS) * max_shear
    below = np.flatnonzero(shear[peak:] <= residual)
    if below.size:
        j = peak + int(below[0])
        # linear between the last point above 0.8 V_max and the first at or below it
        fraction = (shear[j - 1] - residual) / (shear[j - 1] - shear[j])
        ultimate = float(roof[j - 1] + fraction * (roof[j] - roof[j - 1]))
    return PushoverResult(roof, shear, drift, loads, height, weight, float(period), c0, shape, walls, max_shear,
                          float(roof[peak]), float(yield_roof), ultimate,
                          None if ultimate is None else ultimate / float(yield_roof), end)
