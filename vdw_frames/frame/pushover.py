"""Nonlinear static (pushover) analysis of a shear building: FEMA P695 (2009) Section 6.3.

The lateral loads are lambda p on the floors, p a fixed pattern summing to 1, so that the load factor lambda
is the base shear.  In a shear building the story shears follow from statics alone: story k carries
V_k = lambda S_k, S_k = sum_{j >= k} p_j, whatever the drifts, and its drift d_k answers V_k alone through
its own force-drift law: the story model (trial/commit from its committed state,
:class:`~vdw_frames.frame.hysteresis.StoryState`), P-Delta -P_k/h_k d_k and the walls at their static
(zero-frequency) stiffness.  The roof displacement is U = sum d_k.  The path is followed in equal
increments of U up to ``target_drift_ratio`` x the building height; every equation solved is scalar
(Newton's method kept inside a bracket), so no iterate can jump to another branch.

**Branch rule.**  While every story's tangent is positive the path is unique: U rises with lambda and
each U is solved for lambda, every story on its rising branch.  The limit point is where the first story
reaches its strength under the pattern -- the story with the smallest peak of V_k(d) / S_k along its
backbone (for a Bilinear story with P-Delta whose post-yield tangent b k0 - P/h is not positive, at its
yield: F_y (1 - P/(h k0)) / S_k); should several reach it at the same load factor to rounding, the
lowest of them.  Past the limit point lambda falls, so every other story unloads from where it stood
along its own law (a Bilinear story elastically, with its walls and P-Delta, until one that hardened
before the peak meets its kinematic-hardening bound and yields in reverse) and cannot reach its strength
again, while that one story localises: it follows its own backbone, and the path is controlled by its drift
d_c (which only grows), lambda = V_c(d_c) / S_c, U = d_c + sum_{k != c} d_k(lambda).  Two stories
softening at once is an equilibrium too, but not the one a loaded frame follows: the story that reaches
its peak first sheds load, which unloads the others before they reach theirs.  The roof displacement
moves forward only while dU/dd_c = 1 + (k_t,c / S_c) sum_{k != c} S_k / k_t,k > 0; where the localising
story softens faster than the stories in series with it unload, the curve snaps back, which roof
displacement cannot describe, and the analysis stops saying so.  (A story whose tangent is positive but so
small that one unit in the last place of lambda moves the roof by more than an increment, a near plateau,
is followed the same way, by its drift: the path is unique there, whatever controls it.)  The analysis
ends at the target, or earlier where the base shear has fallen to zero: the building has lost all its
lateral strength to P-Delta and would need pulling back to stand (static collapse).

A wall's static stiffness is its stiffness K(s) at s = 0: G1 A / h for an :class:`~vdw_frames.FDMKDamper`
(eqs. (3)-(5) of the paper: the Kelvin branch's spring; the Maxwell branch relaxes to zero), zero for a
Maxwell-only wall (G1 = 0), and in series with the support for a :class:`~vdw_frames.SupportedDamper`.
A friction damper is an elastic-perfectly-plastic spring in parallel with its story (its stiffness until it
slips, then its slip force; magnification f: f^2 k and f F_s in the story), stepped by its own
:class:`~vdw_frames.element.devices.DeviceState`; a fluid viscous damper carries no static force.

From the capacity curve (base shear V against roof displacement delta), FEMA P695 Section 6.3:

* V_max, the largest base shear;
* the effective yield roof displacement, eq. (6-7): delta_y,eff = C0 (V_max / W) (g / 4 pi^2) max(T, T1)^2,
  with C0 from eq. (6-8): C0 = phi_1,r sum(m_x phi_1,x) / sum(m_x phi_1,x^2) (phi_1 the fundamental mode,
  r the roof) and W the seismic weight sum(m_x) g.  T1 and phi_1 are both those of the elastic static
  model whose capacity curve this is (:func:`elastic_mode`: initial story stiffness, the walls' static
  stiffness, P-Delta), so that eqs. (6-7) and (6-8) describe the curve they are applied to; a dynamic T1
  with the walls' stiffness at the first mode's frequency would belong to another model;
* the ultimate roof displacement delta_u at 20 % strength loss (V = 0.8 V_max after the peak);
* the period-based ductility, eq. (6-6): mu_T = delta_u / delta_y,eff.

Units: N, mm, s, tonne; g = 9806.65 mm/s^2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import eigh

from .._validation import finite_array, positive, show, whole_number
from ..element.devices import DeviceState
from ..element.friction import FrictionDamper
from ..motion.record import G
from .building import ShearBuilding, static_wall_stiffness, story_matrix
from .hysteresis import StoryState

PATTERNS = ("modal", "triangular")
STRENGTH_LOSS = 0.2  # FEMA P695 Section 6.3: delta_u at 20 % loss of V_max
MAX_STEPS = 100_000  # increments a pushover may take (a bound on the work a small input can ask for)
# A scalar search (Newton kept in a bracket, bisecting where it leaves it) ends within this many iterations:
# bisection alone closes a bracket of 1e6 mm to floating-point resolution in about 75.
_SEARCH_ITERATIONS = 400
_FORCE_TOLERANCE = 1e-13  # of the story shear sought (a few hundred times the rounding)
_DISPLACEMENT_TOLERANCE = 1e-12  # of the roof displacement sought (at least 1 mm)
_EVENT_PRECISION = 1e-9  # a kink (a story yielding) is located to this fraction of an increment
# The smallest roof-displacement increment (mm): a thousand times the equilibrium tolerance of a roof below 1 mm
# (_DISPLACEMENT_TOLERANCE), which a smaller one would not move past (the path stood still, for ever).
MIN_INCREMENT = 1e-9


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
    ``elastic_period`` (s): T1 of the elastic static model (:func:`elastic_mode`), the model of ``mode_shape``
    and of the capacity curve's elastic branch; ``period`` is max(T, this) when a code period T is given.
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
    elastic_period: float | None = None

    @property
    def roof_drift_ratio(self) -> np.ndarray:
        """Roof displacement / building height (-)."""
        return self.roof_displacement / self.height

    @property
    def normalized_base_shear(self) -> np.ndarray:
        """V / W (-)."""
        return self.base_shear / self.weight


def stuck_friction_stiffness(building: ShearBuilding) -> np.ndarray:
    """The friction dampers' elastic stiffness before they slip, magnification^2 k, summed per story (N/mm)."""
    stiffness = np.zeros(building.stories)
    for story, device in building.other_device_list:
        if isinstance(device, FrictionDamper):
            stiffness[story - 1] += device.magnification**2 * device.stiffness
    return stiffness


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


def pushover(building: ShearBuilding, pattern: str | ArrayLike = "modal", target_drift_ratio: float = 0.05, *,
             period: float | None = None, steps: int = 500) -> PushoverResult:
    """Pushover of ``building`` to a roof displacement of ``target_drift_ratio`` x its height (FEMA P695 Sec. 6.3).

    ``pattern``: "modal" (FEMA P695 Sec. 6.3: loads m_x phi_1,x, phi_1 the fundamental mode of the elastic
    static model), "triangular" (m_x h_x, h_x the floor's elevation: ASCE 7-16 Sec. 12.8.3 with k = 1) or
    an array with one non-negative load per floor (not all zero); normalised to sum 1.
    ``target_drift_ratio`` (-, > 0, at most 1): roof displacement / height at the end.  ``period`` (s):
    the period of eq. (6-7), max(T, T1) with T = C_u T_a (Sec. 5.2.5); default the elastic static model's T1
    (:func:`elastic_mode`), the T1 consistent with this curve and with C0 (eq. 6-8), which comes from that
    model's phi_1 (:attr:`PushoverResult.elastic_period`; module docstring).  ``steps``: equal
    roof-displacement increments (1 ... 100 000, each at least :data:`MIN_INCREMENT` = 1e-9 mm); an increment
    over which a story's tangent jumps (a Bilinear story yielding or unloading) is cut so that the curve has a
    point just past the corner (within 1e-9 of an increment), and the peak (the limit point) is a point of the
    curve, so V_max is exact.  The building needs ``story_heights``.

    Branch rule (the module docstring): the load factor rises until the first story reaches its strength
    under the pattern -- the story k with the smallest peak of V_k(d) / S_k, S_k the share of the pattern
    above it (ties to rounding: the lowest such story); past that limit point that story alone follows its
    backbone (it localises; the path is controlled by its drift) and every other story unloads from its
    state at the peak along its own law (a Bilinear story elastically, with its walls and P-Delta, until its
    kinematic-hardening bound makes it yield in reverse).

    The analysis goes past the peak into the negative-stiffness branch, and ends at the target or at the
    first increment whose base shear is zero or less (after a peak: no lateral strength left).  ValueError,
    saying where it stopped (roof displacement, base shear) and why, when it cannot reach the target: the
    capacity curve snaps back (the roof would have to move back: the localising story softens faster than
    the stories in series with it unload), a second story reaches its strength past the peak, or the
    equilibrium search fails.  Returns a :class:`PushoverResult`.
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
    t1, shape = elastic_mode(building, walls + stuck_friction_stiffness(building))
    period = t1 if period is None else positive("period", period)
    masses = np.asarray(building.masses)
    loads = _pattern(pattern, building, shape)
    height = float(np.sum(building.story_heights))
    weight = float(masses.sum() * G)
    c0 = float(shape[-1] * np.sum(masses * shape) / np.sum(masses * shape**2))  # eq. (6-8)

    path = _Path(building, loads, walls)
    target = target_drift_ratio * height
    increment = target / steps
    if not increment >= MIN_INCREMENT:
        raise ValueError(f"target_drift_ratio = {show(target_drift_ratio)} of a {height:g} mm height in {steps} steps "
                         f"is increments of {increment:.3g} mm, below the {MIN_INCREMENT:g} mm a pushover resolves; "
                         "take a larger target or fewer steps")
    roof, shear, drift = [0.0], [0.0], [np.zeros(building.stories)]
    end = "target"
    stood = 0  # commits in a row that did not move the path (a turn to drift control moves on at the next)
    while roof[-1] < target * (1.0 - 1e-12):
        if shear[-1] <= 0.0 < max(shear):
            end = "no strength left"
            break
        try:
            trial = path.solve(min(roof[-1] + increment, target))
            if path.kinked(trial):
                trial = _land_on_kink(path, trial, _EVENT_PRECISION * increment)
        except _Stop as stop:
            raise ValueError(f"pushover stopped at a roof displacement of {path.roof:.6g} mm (roof drift ratio "
                             f"{path.roof / height:.4g}, base shear {path.load / 1e3:.6g} kN) short of the target "
                             f"{target:.6g} mm: {stop}") from None
        moved = trial.roof != path.roof or trial.load != path.load
        path.commit(trial)
        if not moved:  # a turn to drift control where the path stood (a limit point at the last point)
            stood += 1
            if stood > 2:  # a turn happens once; a path that keeps standing would loop for ever
                raise ValueError(f"pushover stopped at a roof displacement of {path.roof:.6g} mm (base shear "
                                 f"{path.load / 1e3:.6g} kN) short of the target {target:.6g} mm: the path does not "
                                 "move forward")
            continue
        stood = 0
        roof.append(path.roof)
        shear.append(path.load)
        drift.append(path.drift.copy())
    return _result(np.array(roof), np.array(shear), np.array(drift), loads, height=height, weight=weight, period=period,
                   c0=c0, shape=shape, walls=walls, end=end, t1=t1)


def _land_on_kink(path: _Path, trial: _Trial, precision: float) -> _Trial:
    """The trial just past the first kink between the committed state and ``trial`` (bisection of the roof
    displacement to ``precision`` mm), so that a piecewise-linear capacity curve keeps its corners."""
    start = path.roof
    low, high = 0.0, trial.roof - start
    while high - low > precision:
        middle = 0.5 * (low + high)
        candidate = path.solve(start + middle)
        if path.kinked(candidate) or candidate.peak:
            high, trial = middle, candidate
        else:
            low = middle
    return trial


def _pattern(pattern: str | ArrayLike, building: ShearBuilding, shape: np.ndarray) -> np.ndarray:
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


class _Stop(Exception):
    """Why the path cannot be followed further (becomes the ValueError saying where)."""


@dataclass(frozen=True)
class _Trial:
    """An equilibrium point not yet committed: story drifts (mm), story shears and tangents (N, N/mm: frame,
    walls, P-Delta), load factor (N) and whether the path turns to the drift control of story ``localising``
    there (``peak``: the limit point, or a plateau that the load factor cannot resolve)."""

    drift: np.ndarray
    shear: np.ndarray
    tangent: np.ndarray
    load: float
    peak: bool = False
    localising: int | None = None

    @property
    def roof(self) -> float:
        return float(np.sum(self.drift))


def _bracketed(step: float, low: float, high: float, iteration: int) -> bool:
    """Whether a Newton step may be taken: inside the bracket, and not on every third iteration of a finite
    bracket, which is bisected instead (near a corner Newton may creep by units in the last place; this
    bounds the search by bisection's)."""
    return low < step < high and not (iteration % 3 == 2 and math.isfinite(high - low))


def _collapsed(low: float, high: float) -> bool:
    """Whether a bracket has shrunk to adjacent floating-point numbers (or nothing)."""
    middle = 0.5 * (low + high)
    return not low < middle < high


class _Path:
    """The equilibrium path of a pushover, solved one story at a time.

    In a shear building under the floor loads lambda p, story k carries the shear V_k = lambda S_k with
    S_k = sum_{j >= k} p_j whatever the drifts (statics alone), so that, given lambda, each story's drift
    solves its own equation V_k(d_k) = lambda S_k, V_k its frame spring (trial from its committed state),
    walls and P-Delta.  Before the limit point the roof displacement U(lambda) = sum d_k(lambda) is solved
    for lambda, every story on its rising branch; past it the localising story c's drift d_c is solved for,
    lambda = V_c(d_c) / S_c and every other story on its own (unloading) branch.  Each scalar equation is
    solved by Newton's method kept inside a bracket (bisection where Newton leaves it), so no iterate can
    jump to another branch.
    """

    def __init__(self, building: ShearBuilding, loads: np.ndarray, walls: np.ndarray):
        self.above = np.cumsum(loads[::-1])[::-1]  # S_k
        self.linear = walls + np.asarray(building.geometric_stiffness)  # walls and P-Delta, per story
        self.initial = np.asarray(building.stiffnesses, dtype=float)
        self.states = [StoryState(model, k)
                       for model, k in zip(building.story_models, building.stiffnesses, strict=True)]
        # Friction dampers: elastic-perfectly-plastic springs in parallel with their stories (their rate does
        # not enter); fluid viscous dampers carry no static force.
        self.friction: list[list[DeviceState]] = [[] for _ in range(building.stories)]
        for story, device in building.other_device_list:
            if isinstance(device, FrictionDamper):
                self.friction[story - 1].append(DeviceState(device, 1.0))
        n = building.stories
        self.drift = np.zeros(n)
        self.shear = np.zeros(n)
        self.tangent = self.initial + self.linear
        self.load = 0.0
        self.localising: int | None = None

    @property
    def roof(self) -> float:
        return float(np.sum(self.drift))

    def _story(self, k: int, drift: float) -> tuple[float, float]:
        if not math.isfinite(drift):
            raise _Stop(f"story {k + 1}'s drift is not finite")
        force, tangent = self.states[k].trial(drift)
        for damper in self.friction[k]:
            extra_force, extra_tangent = damper.trial(drift)
            force, tangent = force + extra_force, tangent + extra_tangent
        return force + self.linear[k] * drift, tangent + self.linear[k]

    def _story_drift(self, k: int, shear: float) -> tuple[float, float, float] | None:
        """(drift mm, shear N, tangent N/mm) of story k carrying ``shear`` (N), reached from its committed state
        along its own branch (where its tangent stays positive), or None when it cannot carry it there (its
        strength on that branch is below ``shear``)."""
        x = float(self.drift[k])
        value, slope = self._story(k, x)
        value -= shear
        forward = value < 0.0
        low, high = (x, math.inf) if forward else (-math.inf, x)
        # the rounding of a story force is about that of k0 d and of the shears themselves (1 N at least)
        tolerance = _FORCE_TOLERANCE * max(abs(shear), abs(float(self.shear[k])), self.initial[k] * abs(x), 1.0)
        for iteration in range(_SEARCH_ITERATIONS):
            if slope <= 0.0:  # beyond the branch's end (a peak) in the direction of motion
                if forward:
                    high = x
                else:
                    low = x
            elif abs(value) <= tolerance:
                return x, value + shear, slope
            elif value < 0.0:
                low = x
            else:
                high = x
            step = x - value / slope if slope > 0.0 else math.nan
            if step == x:  # a correction below the resolution of x: the root, to rounding
                return x, value + shear, slope
            if not _bracketed(step, low, high, iteration):
                if _collapsed(low, high):
                    return None
                step = 0.5 * (low + high)
            x = step
            value, slope = self._story(k, x)
            value -= shear
        raise _Stop(f"story {k + 1}'s drift under a shear of {shear / 1e3:.6g} kN was not found in "
                    f"{_SEARCH_ITERATIONS} iterations")

    def _at_load(self, load: float, skip: int | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray] | list[int]:
        """(drifts, shears, tangents) of every story (but ``skip``, left as committed) under the load factor
        ``load`` from its committed state, or the stories that cannot carry it."""
        drift, shear, tangent = self.drift.copy(), self.shear.copy(), self.tangent.copy()
        failed = []
        for k in range(drift.size):
            if k == skip:
                continue
            found = self._story_drift(k, load * float(self.above[k]))
            if found is None:
                failed.append(k)
            else:
                drift[k], shear[k], tangent[k] = found
        return failed or (drift, shear, tangent)

    def solve(self, roof: float) -> _Trial:
        """The equilibrium at roof displacement ``roof`` (mm) on the physical branch, from the committed state;
        before the limit point, the limit point itself when ``roof`` lies beyond it (``peak``)."""
        return self._rising(roof) if self.localising is None else self._softening(roof)

    def _rising(self, roof: float) -> _Trial:
        # Every story on its rising branch: U(lambda) increases with lambda, dU/dlambda = sum S_k / k_t,k.
        low, high = self.load, math.inf
        below = _Trial(self.drift, self.shear, self.tangent, self.load)  # at low
        above: _Trial | None = None  # at high when it is an equilibrium beyond the roof displacement sought
        failed: list[int] = []  # the stories that cannot carry the load factor high
        value = self.roof - roof
        slope = float(np.sum(self.above / self.tangent))
        tangent = self.tangent  # of the last equilibrium found
        load = self.load
        tolerance = _DISPLACEMENT_TOLERANCE * max(1.0, abs(roof))
        for iteration in range(_SEARCH_ITERATIONS):
            step = load - value / slope if slope > 0.0 else math.nan
            if step == load or (not _bracketed(step, low, high, iteration) and _collapsed(low, high)):
                if failed:
                    # The limit point: no larger load factor can be carried; the first story that cannot carry
                    # one is the one that localises (the lowest, should several at once).
                    return _Trial(below.drift, below.shear, below.tangent, below.load, True, failed[0])
                # No load factor resolves the roof displacement to the tolerance: a story's tangent is so
                # small (a near plateau, or a corner into one) that one unit in the last place of lambda
                # moves the roof by more.  The nearer equilibrium is the point, if the roof moves forward;
                # if not, the path (unique here) is followed by that story's drift from now on.
                nearest = below if above is None or roof - below.roof <= above.roof - roof else above
                if nearest.roof > self.roof:
                    return nearest
                flexible = int(np.argmax(self.above / np.where(tangent > 0.0, tangent, np.inf)))
                return _Trial(below.drift, below.shear, below.tangent, below.load, True, flexible)
            if not _bracketed(step, low, high, iteration):
                step = 0.5 * (low + high)
            load = step
            found = self._at_load(load)
            if isinstance(found, list):
                failed, high, above, slope = found, load, None, math.nan
                continue
            trial = _Trial(*found, load)
            tangent = trial.tangent
            value = trial.roof - roof
            if abs(value) <= tolerance:
                return trial
            if value < 0.0:
                low, below = load, trial
            else:
                high, above, failed = load, trial, []
            slope = float(np.sum(self.above / trial.tangent))
        raise _Stop(f"the load factor for this roof displacement was not found in {_SEARCH_ITERATIONS} iterations")

    def _softening(self, roof: float) -> _Trial:
        # Story c localises: d_c controls; lambda = V_c(d_c) / S_c; dU/dd_c = 1 + k_t,c / S_c sum_{k != c} S_k / k_t,k.
        c = self.localising
        assert c is not None
        share = float(self.above[c])
        others = np.arange(self.drift.size) != c
        low, high = float(self.drift[c]), math.inf
        x = low
        tolerance = _DISPLACEMENT_TOLERANCE * max(1.0, abs(roof))
        for iteration in range(_SEARCH_ITERATIONS):
            shear_c, tangent_c = self._story(c, x)
            load = shear_c / share
            found = self._at_load(load, skip=c)
            if isinstance(found, list):
                raise _Stop(f"story {found[0] + 1} reaches a limit of its own too (its strength, or in reverse "
                            f"yielding a tangent that is not positive): a second limit point after story {c + 1}'s, "
                            "which the branch rule does not cover")
            drift, shear, tangent = found
            drift[c], shear[c], tangent[c] = x, shear_c, tangent_c
            trial = _Trial(drift, shear, tangent, load)
            value = trial.roof - roof
            if abs(value) <= tolerance:
                return trial
            if value < 0.0:
                low = x
            else:
                high = x
            slope = 1.0 + tangent_c / share * float(np.sum(self.above[others] / tangent[others]))
            if not slope > 0.0:
                raise _Stop(f"the capacity curve snaps back (story {c + 1} softens at {show(tangent_c)} N/mm, faster "
                            "than the stories in series with it unload); roof displacement control cannot follow it")
            step = x - value / slope
            if step == x:  # a correction below the resolution of d_c: the root, to rounding
                return trial
            if not _bracketed(step, low, high, iteration):
                if _collapsed(low, high):
                    raise _Stop("the localising story's drift for this roof displacement was not found (the "
                                "bracket closed)")
                step = 0.5 * (low + high)
            x = step
        raise _Stop(f"the localising story's drift for this roof displacement was not found in "
                    f"{_SEARCH_ITERATIONS} iterations")

    def kinked(self, trial: _Trial) -> bool:
        """Whether a story's own tangent jumped (by over half its initial stiffness) between the committed
        state and ``trial``: a corner of a piecewise-linear model (Bilinear yielding or unloading)."""
        return bool((np.abs(trial.tangent - self.tangent) > 0.5 * self.initial).any())

    def commit(self, trial: _Trial) -> None:
        for k, state in enumerate(self.states):
            state.trial(float(trial.drift[k]))  # the trial's drift, then commit it
            state.commit()
            for damper in self.friction[k]:
                damper.trial(float(trial.drift[k]))
                damper.commit()
        self.drift, self.shear, self.tangent, self.load = trial.drift.copy(), trial.shear, trial.tangent, trial.load
        if trial.peak:
            # Past the limit point: the tangents of the branch about to be followed (the localising story past
            # its peak, the others unloading), so that the turn itself is not taken for a kink.
            c = self.localising = trial.localising
            assert c is not None
            nudge = 1e-9 * max(1.0, float(np.abs(self.drift).max()))
            self.tangent = np.array([self._story(k, float(self.drift[k]) + (nudge if k == c else -nudge))[1]
                                     for k in range(self.drift.size)])


def _result(roof: np.ndarray, shear: np.ndarray, drift: np.ndarray, loads: np.ndarray, *, height: float, weight: float,
            period: float, c0: float, shape: np.ndarray, walls: np.ndarray, end: str, t1: float) -> PushoverResult:
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
                          None if ultimate is None else ultimate / float(yield_roof), end, float(t1))
