"""Complex modal analysis of a shear building with damping devices: poles, periods, damping ratios, shapes.

The linear (initial-stiffness) building with its devices has the characteristic matrix

    T(s) = s^2 M + s C + K + K_G + sum_devices B^T f^2 k(s) B,

M the floor masses (tonne), C the inherent damping (N*s/mm, Rayleigh or modal), K the initial elastic
story stiffness and K_G the P-Delta stiffness -P/h (N/mm), f each device's magnification (its deformation
/ the story drift, :mod:`vdw_frames.element.device`) and k(s) its Laplace-domain stiffness along it (N/mm):
a wall's ``wall.stiffness_transfer(s)`` (paper eqs. (3)-(5) times area/thickness, in series with the
support of a :class:`~vdw_frames.SupportedDamper`), a linear fluid viscous damper's C s (in series with its
brace K_b: K_b C s / (K_b + C s)).  A device whose stiffness depends on its amplitude (a nonlinear FVD, a
friction damper, a strain-dependent wall) is linearised at a stated story drift amplitude
(:func:`modal_analysis`); the first two enter as k(s) = K'(omega) + s K''(omega) / omega with K' + i K'' their
equivalent complex stiffness at omega, frozen while the roots are found and iterated, mode by mode, until
omega = |s| of that mode (the secant method on omega -> |s_j(omega)|, to 1e-12).

The modes are the roots of det T(s) = 0 with Im s > 0 on the principal branch of s^r: a *nonlinear*
eigenproblem, since k(s) contains s^r.

Method
------
1. Start: the frame's undamped modes phi, omega with every wall at its storage stiffness at the mode's
   own frequency (iterated), and s from the mode's Rayleigh quotient phi^T T(s) phi = 0 with k frozen
   at i omega (first-order perturbation theory: close for light and moderate damping).
2. Refine: Newton on the augmented system T(s) x = 0, v^H x = 1 (quadratic convergence; T'(s) from
   k'(s) by a Cauchy integral on a small circle, accurate to ~1e-13 since k is analytic there).
   A root is kept only if its backward error is at rounding level, ||T(s) x|| <= 1e-10 x (the largest
   entry of |s|^2 M, |s| C and K + K_G + walls) x ||x||, and it is distinct from those found.
3. Completeness (no mode missed, none spurious): the argument principle.  T is analytic in the open
   upper half plane (Im k(s) > 0 there for a passive wall, so a support's K_wall + k_s never vanishes),
   so the winding number of det T along the boundary of the sector
   Omega = {rho0 < |s| < rho1, pi/2 - 0.1 < arg s < pi - 0.05} is the number of its roots in Omega.
   The phase of det T (``slogdet``) is tracked along the boundary, from steps of a quarter of the
   distance to the real or imaginary axis beside each edge, bisecting every step where it turns by
   more than pi/4 or |det T| changes by more than a factor e^(1/2), then halving every step once more
   to check that the total does not change; the count is an exact integer, read without a quadrature
   error.  When it exceeds the roots found, the sector is split in four,
   each part counted, and the search recurses into the parts with roots missing, trying Newton from
   each part's centre, until every counted root is found (e.g. a heavily damped root that a relaxation
   root of the Maxwell branches became for r < 1, which no undamped mode leads to).  A count that still
   disagrees is an error, never a silent result.  Why the sector holds every mode: roots need
   Re s <= 0 for passive walls and a stable frame (x^H T(s) x / s has a positive real part for
   Re s > 0), so the edge at pi/2 - 0.1 loses none; rho0 = 1e-3 x the bare frame's first frequency:
   near s = 0, T(s) -> K + K_G + sum k(0) B^T B, positive definite (checked), so no root lies below;
   rho1 is doubled until the walls and damping are a small perturbation of s^2 M along the arc,
   ||M^-1 (T(s) - s^2 M)|| <= |s|^2 / 2 (k(s) grows no faster than |s|, so T(s) / s^2 -> M and no root
   lies further out).  Roots with damping ratios above cos(0.05) = 0.9988 (angles beyond pi - 0.05)
   are practically overdamped and are not reported; with heavy walls a building can have fewer
   oscillatory modes than floors (tests/frame/test_modal.py has one), and fractional walls can add a heavily
   damped one.  Modes are ordered by |s|; the count over the whole sector guarantees that mode j is
   the j-th.

Energy estimate
---------------
Beside the exact ratio, the design-code estimate (FEMA 356 eq. 9-36, JGJ 297-2013, ASCE 7-16 Ch. 18):

    xi_E = xi_inherent + sum_walls W_c / (4 pi W_s),

evaluated in the *real* mode phi, omega of the frame with every wall at its storage stiffness K'(omega)
at that mode's own frequency (the stiffened undamped mode, iterated to consistency): W_c = pi K''(omega)
d^2 with d the wall's drift amplitude in phi; W_s = phi^T (K + K_G + sum B^T K'(omega) B) phi / 2 =
omega^2 phi^T M phi / 2, the mode's maximum strain energy including the walls' storage; xi_inherent =
phi^T C phi / (2 omega phi^T M phi), the same energy ratio for the inherent dashpots (the frame's ratio
exactly for a bare frame with Rayleigh or modal damping).
It is first-order perturbation theory: exact as the damping goes to zero and for classical viscous
damping (tests/frame/test_modal.py), and it differs from the complex-mode value (measured):

(a) through the walls' frequency dependence: the damped pole sits at complex s, where k(s) is not
    k(i omega).  On examples/ten_story.toml, mode 1: 8.52 % complex, 8.34 % energy; Kelvin walls with
    the same K*(omega_1) (frequency-independent) give 8.345 % and 8.342 %, so this is nearly all of the
    gap.  The gap grows with the damping: a one-story frame with fitted-300 walls, relative gap 0.4 %
    at xi = 0.8 %, 2 % at 4.8 %, 3.3 % at 9.4 % (the estimate is low);
(b) with non-proportional, strong damping: dashpots in stories 1-2 of ten that are strong enough to
    lock those stories; the real mode ignores the locking, so the estimate keeps growing with c while
    the true ratio has passed its maximum: c = 1e5 N*s/mm, mode 1 22.5 % estimated vs 14.8 % exact;
    c = 3e5, 57 % vs 9.4 %;
(c) through xi_inherent, which follows the stiffened mode (a fixed C gives a stiffer mode a smaller
    ratio: 4.46 % instead of the bare 5 % in the example's mode 1).

Units: s in rad/s, periods s, damping ratios dimensionless, mode shapes dimensionless (largest entry 1).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, cast

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import eigh

from .. import _warnings
from .._validation import finite_array, show, whole_number
from ..element.strain_dependent import StrainDependentDamper
from ..element.viscous import FluidViscousDamper
from .building import ShearBuilding, is_wall, require_fixed_walls, require_stable_under_gravity, story_matrix

if TYPE_CHECKING:
    from ..element.device import Device
    from ..element.wall import Wall

MAX_STORIES = 100
"""Largest building (stories) the complex modal analysis takes; a larger one is refused before any work.
The search's cost grows faster than n^3 (dense n x n determinants along a contour that winds once per
mode): measured on the development machine under load, all modes 0.13 s at 20 stories, 3.3 s at 40,
111 s (one mode) at 100; 3000 stories would take days."""

# The sector Omega of the argument principle (module docstring).
_EDGE_RIGHT_GAP = 0.1
_EDGE_RIGHT = np.pi / 2 - _EDGE_RIGHT_GAP
_EDGE_LEFT = np.pi - 0.05
_CAUCHY_POINTS = 8  # points on the circle for k'(s)
_CAUCHY_RADIUS = 1e-3  # relative to |s|

# A sector of an annulus: (rho_a, rho_b, theta_a, theta_b), radii rad/s, angles rad.
_Box = tuple[float, float, float, float]


@dataclass(frozen=True)
class ModalResult:
    """Complex modes of a building with its devices (:func:`modal_analysis`), arrays over ``modes``.

    ``modes``: mode numbers (1-based, ordered by |s|).  ``poles``: s (rad/s, Im s > 0);
    ``periods``: 2 pi / |s| (s); ``damping_ratios``: -Re s / |s| (-); ``mode_shapes``: complex
    floor displacements, one column per mode, scaled so the entry of largest modulus is 1.
    ``bare_poles``, ``bare_periods``, ``bare_damping_ratios``: the same frame without devices (inherent
    damping and P-Delta kept); ``added_damping`` = damping_ratios - bare_damping_ratios.
    ``energy_damping_ratios``: the energy estimate xi_inherent + sum W_c / (4 pi W_s) (module
    docstring), with ``energy_inherent`` its inherent part and ``effective_periods`` (s) the periods of
    the real modes it uses (walls at their storage stiffness); mode j of the bare frame and of the real
    modes is paired with complex mode j (NaN where there is none: see :func:`modal_analysis`).
    ``pole_count``: the number of roots of det T in the search sector by the argument principle (= the
    number of modes found; with devices; with amplitude-dependent devices, that of the building linearised
    at mode 1's frequency).  ``drift_amplitudes`` (mm, one a story): the story drift amplitudes the
    amplitude-dependent devices were linearised at (None when there is none), ``linearisation`` one line per
    such device saying how and at what amplitude, ``linearisation_frequencies`` (Hz) the frequency |s| / 2 pi
    each mode's linearisation converged to (NaN without such devices).
    """

    modes: np.ndarray
    poles: np.ndarray
    periods: np.ndarray
    damping_ratios: np.ndarray
    mode_shapes: np.ndarray
    bare_poles: np.ndarray
    bare_periods: np.ndarray
    bare_damping_ratios: np.ndarray
    added_damping: np.ndarray
    energy_damping_ratios: np.ndarray
    energy_inherent: np.ndarray
    effective_periods: np.ndarray
    pole_count: int
    drift_amplitudes: np.ndarray | None = None
    linearisation: tuple[str, ...] = ()
    linearisation_frequencies: np.ndarray | None = None

    @property
    def frequencies(self) -> np.ndarray:
        """|s| / (2 pi), Hz."""
        return np.abs(self.poles) / (2.0 * np.pi)

    @property
    def energy_added_damping(self) -> np.ndarray:
        """The devices' part of the energy estimate, sum W_c / (4 pi W_s) (-)."""
        return self.energy_damping_ratios - self.energy_inherent


# ---------------------------------------------------------------------------------------------- T(s)
class _System:
    """T(s) of a building (with or without its devices), vectorised over many s.

    Walls and linear fluid viscous dampers enter with their exact Laplace-domain stiffness
    (:func:`device_transfer`); a nonlinear device (a nonlinear FVD, a friction damper) with its equivalent
    linear one at the story drift amplitude ``amplitudes[story]`` (mm) and the circular frequency ``frozen``
    (rad/s): k(s) = K'(omega) + s K''(omega) / omega (a spring and a dashpot with K*(i omega) = K' + i K''),
    which :func:`modal_analysis` iterates to omega = |s| (module docstring)."""

    def __init__(self, building: ShearBuilding, devices: bool = True, amplitudes: np.ndarray | None = None,
                 frozen: float | None = None) -> None:
        self.n = building.stories
        self.mass = np.asarray(building.masses, dtype=float)
        self.damping = np.asarray(building.damping_matrix, dtype=float)
        self.stiffness = np.asarray(building.stiffness_matrix) + story_matrix(np.asarray(building.geometric_stiffness))
        # Fixed walls only (modal_analysis checked): no strain-dependent wall.
        listed = building.device_list if devices else []
        self.has_devices = bool(listed)
        # Equal linear devices are evaluated once: (device, how many of it each story holds).
        counts: dict[Device, np.ndarray] = {}
        self.frozen_storage = np.zeros(self.n)  # K'(omega) of the nonlinear devices per story, N/mm
        self.frozen_dashpot = np.zeros(self.n)  # K''(omega) / omega, N*s/mm
        for story, device in listed:
            if is_linear_device(device):
                counts.setdefault(device, np.zeros(self.n))[story - 1] += 1.0
                continue
            if amplitudes is None or frozen is None:
                raise ValueError(f"story {story}'s {device.describe()} is nonlinear: its equivalent linear stiffness "
                                 "needs a drift amplitude (drift_amplitude=..., mm)")
            value = complex(device.story_stiffness(frozen / (2.0 * np.pi), float(amplitudes[story - 1]))[()])
            self.frozen_storage[story - 1] += value.real
            self.frozen_dashpot[story - 1] += value.imag / frozen
        self.groups = list(counts.items())

    def wall_stiffness(self, s: ArrayLike) -> np.ndarray:
        """Sum of the devices' k(s) per story (N/mm), shape (len(s), stories)."""
        s = np.atleast_1d(np.asarray(s, dtype=complex))
        per_story = np.zeros((s.size, self.n), dtype=complex)
        for device, count in self.groups:
            per_story += np.multiply.outer(device_transfer(device, s), count)
        per_story += self.frozen_storage + np.multiply.outer(s, self.frozen_dashpot)
        return per_story

    def matrices(self, s: ArrayLike, per_story: np.ndarray | None = None) -> np.ndarray:
        """T(s) for every s, shape (len(s), n, n); ``per_story`` overrides the walls' k (frozen)."""
        s = np.atleast_1d(np.asarray(s, dtype=complex))
        if per_story is None:
            per_story = self.wall_stiffness(s)
        matrix = (s[:, None, None] ** 2 * np.diag(self.mass) + s[:, None, None] * self.damping
                  + self.stiffness).astype(complex)
        _add_stories(matrix, np.broadcast_to(per_story, (s.size, self.n)))
        return matrix

    def derivative(self, s: complex) -> np.ndarray:
        """T'(s) = 2 s M + C + sum B^T k'(s) B (k' by the Cauchy integral on a small circle)."""
        matrix = (2.0 * s * np.diag(self.mass) + self.damping).astype(complex)
        if self.has_devices:
            radius = _CAUCHY_RADIUS * abs(s)
            turns = np.exp(2j * np.pi * np.arange(_CAUCHY_POINTS) / _CAUCHY_POINTS)
            values = self.wall_stiffness(s + radius * turns)
            slope = (values * turns.conj()[:, None]).sum(axis=0) / (_CAUCHY_POINTS * radius)
            _add_stories(matrix[None], slope[None])
        return matrix


def is_linear_device(device: Device) -> bool:
    """Whether ``device``'s force is linear in its motion: a wall of fixed parameters (strain-dependent walls are
    fixed before: :func:`modal_analysis`) or a linear fluid viscous damper."""
    return is_wall(device) or device.linear


def device_transfer(device: Device, s: ArrayLike) -> np.ndarray:
    """magnification^2 k(s) (N/mm) of a linear device at complex s (rad/s): a wall's ``stiffness_transfer``; a
    linear fluid viscous damper's C s, in series with its brace K_b: K_b C s / (K_b + C s)."""
    s = np.asarray(s, dtype=complex)
    if isinstance(device, FluidViscousDamper):
        dashpot = device.C * s
        along = dashpot if device.stiffness is None else device.stiffness * dashpot / (device.stiffness + dashpot)
    else:
        along = cast("Wall", device).stiffness_transfer(s)
    return device.magnification**2 * along


def _add_stories(matrix: np.ndarray, per_story: np.ndarray) -> None:
    """Add story springs (P, n) to matrices (P, n, n) in place: story k between floors k-1 and k."""
    n = per_story.shape[1]
    index = np.arange(n)
    matrix[:, index, index] += per_story
    if n > 1:
        upper = per_story[:, 1:]
        matrix[:, index[:-1], index[:-1]] += upper
        matrix[:, index[:-1], index[1:]] -= upper
        matrix[:, index[1:], index[:-1]] -= upper


# ---------------------------------------------------------------------------------------------- roots
def _newton(system: _System, s: complex, x: np.ndarray,
            max_iterations: int = 60) -> tuple[complex, np.ndarray] | None:
    """Newton on T(s) x = 0, v^H x = 1 from (s, x); returns (s, x) or None when it does not converge."""
    v = x / np.linalg.norm(x)
    x = x / (v.conj() @ x)
    n = system.n
    scale = np.abs(system.stiffness).max()
    for _ in range(max_iterations):
        matrix = system.matrices(s)[0] / scale
        jacobian = np.zeros((n + 1, n + 1), dtype=complex)
        jacobian[:n, :n] = matrix
        jacobian[:n, n] = system.derivative(s) @ x / scale
        jacobian[n, :n] = v.conj()
        residual = np.concatenate([matrix @ x, [v.conj() @ x - 1.0]])
        try:
            step = np.linalg.solve(jacobian, -residual)
        except np.linalg.LinAlgError:
            return None
        x = x + step[:n]
        s = s + step[n]
        if not np.isfinite(s) or s.imag <= 0.0:
            return None
        if abs(step[n]) <= 1e-14 * abs(s) and np.linalg.norm(step[:n]) <= 1e-12 * np.linalg.norm(x):
            break
    else:
        return None
    # Backward error: T(s) x must vanish relative to the size of its terms (a genuine root, not a stall).
    terms = (abs(s) ** 2 * system.mass.max() + abs(s) * np.abs(system.damping).max()
             + np.abs(system.matrices(0.0, system.wall_stiffness(s))[0]).max())
    if np.linalg.norm(system.matrices(s)[0] @ x) > 1e-10 * terms * np.linalg.norm(x):
        return None
    return s, x


def _start_guesses(system: _System) -> list[tuple[complex, np.ndarray]]:
    """(s, x) per mode: the stiffened undamped mode phi, omega (walls at their storage stiffness at the
    mode's own frequency), and s from its Rayleigh quotient phi^T T(s) phi = 0 with k frozen at i omega."""
    n = system.n
    mass = np.diag(system.mass)
    starts = []
    omega_bare = np.sqrt(np.abs(eigh(system.stiffness, mass, eigvals_only=True)))
    for j in range(n):
        omega = omega_bare[j]
        for _ in range(3):
            stiffness = system.stiffness + story_matrix(system.wall_stiffness(1j * omega)[0].real)
            values, shapes = eigh(stiffness, mass)
            omega = np.sqrt(abs(values[j]))
        shape = shapes[:, j]
        stiffness = system.matrices(0.0, system.wall_stiffness(1j * omega))[0]
        m, c, k = shape @ mass @ shape, shape @ system.damping @ shape, shape @ stiffness @ shape
        root = np.sqrt(c * c - 4.0 * m * k + 0j)
        guess = (-c + root) / (2.0 * m)
        starts.append((guess if guess.imag > 0.0 else (-c - root) / (2.0 * m), shape.astype(complex)))
    return starts


def complex_modes(building: ShearBuilding, devices: bool = True, amplitudes: np.ndarray | None = None,
                  frozen: float | None = None, *, walls: bool | None = None) -> tuple[np.ndarray, np.ndarray, int]:
    """(poles ascending in |s|, shapes as columns, argument-principle count) of the linear building: with its
    devices (``devices``; nonlinear ones linearised at the story drift ``amplitudes`` (mm) and the circular
    frequency ``frozen`` (rad/s): :class:`_System`), or the bare frame.  ``walls=`` (the keyword before 0.3)
    still works as ``devices=``, with a DeprecationWarning."""
    if walls is not None:
        _warnings.warn("complex_modes(walls=...) is deprecated since 0.3 and will be removed in 0.4: give devices=",
                       DeprecationWarning, stacklevel=2)
        devices = walls
    require_modal_size(building, "a complex modal analysis")
    require_stable_under_gravity(building if devices else building.without_devices(), "the complex modal analysis")
    return _modes_of(_System(building, devices, amplitudes, frozen))


def _modes_of(system: _System) -> tuple[np.ndarray, np.ndarray, int]:
    roots: list[tuple[complex, np.ndarray]] = []
    for guess, vector in _start_guesses(system):
        _add_root(roots, _newton(system, guess, vector))
    omega_first = np.sqrt(np.abs(eigh(system.stiffness, np.diag(system.mass), eigvals_only=True)[0]))
    sector = (1e-3 * omega_first, _outer_radius(system, max((abs(s) for s, _ in roots), default=omega_first)),
              _EDGE_RIGHT, _EDGE_LEFT)
    count = _root_count(system, sector)
    _find_missing(system, sector, count, roots)
    roots = _inside(roots, sector)
    if len(roots) != count:
        raise RuntimeError(f"modal analysis: the argument principle counts {count} poles in the search sector "
                           f"but {len(roots)} were found; please report this building")
    roots.sort(key=lambda root: abs(root[0]))
    poles = np.array([s for s, _ in roots], dtype=complex)
    shapes = np.column_stack([x for _, x in roots]) if roots else np.zeros((system.n, 0), dtype=complex)
    largest = shapes[np.argmax(np.abs(shapes), axis=0), np.arange(shapes.shape[1])]
    return poles, shapes / largest, count


def require_modal_size(building: ShearBuilding, analysis: str, limit: int = MAX_STORIES) -> None:
    """ValueError, before any work, when ``building`` has more than ``limit`` stories."""
    if building.stories > limit:
        raise ValueError(f"{analysis} takes buildings of at most {limit} stories, got {building.stories} stories "
                         f"(masses and stiffnesses of {building.stories} entries): its cost grows faster than "
                         "the cube of the story count")


def _add_root(roots: list[tuple[complex, np.ndarray]], root: tuple[complex, np.ndarray] | None) -> None:
    if root is not None and all(abs(root[0] - s) > 1e-7 * abs(s) for s, _ in roots):
        roots.append(root)


def _inside(roots: list[tuple[complex, np.ndarray]], box: _Box) -> list[tuple[complex, np.ndarray]]:
    inner, outer, right, left = box
    return [root for root in roots if inner < abs(root[0]) < outer and right < np.angle(root[0]) < left]


def _find_missing(system: _System, box: _Box, count: int, roots: list[tuple[complex, np.ndarray]],
                  depth: int = 0) -> None:
    """Add the roots of det T in ``box`` (rho_a, rho_b, theta_a, theta_b) that ``roots`` lacks.

    ``count`` roots lie in the box (argument principle).  While some are missing, Newton is tried from
    the box's centre (with the singular vector of T there); what it cannot reach is found by splitting
    the box in four, counting in each, and recursing into those with roots missing: a box small enough
    holds one root, which Newton from its centre finds.
    """
    inner, outer, right, left = box
    for _ in range(2):
        if len(_inside(roots, box)) >= count:
            return
        centre = np.sqrt(inner * outer) * np.exp(0.5j * (right + left))
        vector = np.linalg.svd(system.matrices(centre)[0])[2][-1].conj()
        _add_root(roots, _newton(system, centre, vector))
    if depth >= 40:
        return
    # Split slightly off the middle: a known root on a dividing line would stall the phase tracking.
    radius = inner * (outer / inner) ** 0.4913
    angle = right + 0.4913 * (left - right)
    for sub in ((inner, radius, right, angle), (radius, outer, right, angle), (inner, radius, angle, left),
                (radius, outer, angle, left)):
        _find_missing(system, sub, _root_count(system, sub), roots, depth + 1)


def _outer_radius(system: _System, largest: float) -> float:
    """rho1 >= 2 x the largest root found, doubled until ||M^-1 (T - s^2 M)|| <= |s|^2 / 2 on the arc."""
    radius = 2.0 * largest
    angles = np.linspace(_EDGE_RIGHT, _EDGE_LEFT, 64)
    for _ in range(40):
        s = radius * np.exp(1j * angles)
        perturbation = system.matrices(s) - s[:, None, None] ** 2 * np.diag(system.mass)
        scaled = perturbation / system.mass[None, :, None]
        if np.linalg.norm(scaled, ord=2, axis=(1, 2)).max() <= 0.5 * radius**2:
            return radius
        radius *= 2.0
    raise RuntimeError("modal analysis: the walls do not become a small perturbation of the inertia at any "
                       "radius tried; please report this building")


def _root_count(system: _System, box: _Box) -> int:
    """Roots of det T inside ``box`` = (rho_a, rho_b, theta_a, theta_b), a sector of an annulus, by the
    argument principle with the phase tracked along its boundary (counter-clockwise)."""
    inner, outer, right, left = box
    ratio = np.log(outer / inner)
    # Along a ray, singularities beside it (the real axis beside the edge at pi - 0.05, the imaginary axis
    # beside the one at pi/2 - 0.1) lie at distances ~ gap x |s|: start with steps of a quarter of that.
    gap = min(left - right, _EDGE_RIGHT_GAP, np.pi - _EDGE_LEFT)
    ray_points = int(np.ceil(4.0 * ratio / gap)) + 1
    pieces = (
        (lambda t: inner * np.exp(ratio * t) * np.exp(1j * right), ray_points),
        (lambda t: outer * np.exp(1j * (right + (left - right) * t)), 257),
        (lambda t: inner * np.exp(ratio * (1.0 - t)) * np.exp(1j * left), ray_points),
        (lambda t: inner * np.exp(1j * (left - (left - right) * t)), 257),
    )
    winding = sum(_phase_change(system, piece, points) for piece, points in pieces) / (2.0 * np.pi)
    count = round(winding)
    if abs(winding - count) > 1e-6:
        raise RuntimeError(f"modal analysis: the argument principle gave a non-integer winding {winding!r}")
    return count


def _phase_change(system: _System, path: Callable[[np.ndarray], np.ndarray], points: int,
                  max_points: int = 400_000) -> float:
    """Total change of arg det T(path(t)) for t from 0 to 1, from ``points`` samples on.

    Steps are bisected until arg det T turns by less than pi/4 and log |det T| changes by less than 1/2
    across each; then every step is halved once more and the total must not change (else the bisection
    goes on): a cluster of zeros and poles of det T beside the path (e.g. the Maxwell branches'
    relaxation poles and the overdamped roots next to them on the negative real axis, for r = 1) can turn
    the phase by 2 pi within one step while both ends agree.
    """
    t = np.linspace(0.0, 1.0, points)
    phase, size = _phase(system, path(t))
    previous = None
    while True:
        step = np.angle(np.exp(1j * np.diff(phase)))
        coarse = np.flatnonzero((np.abs(step) > np.pi / 4) | (np.abs(np.diff(size)) > 0.5))
        if coarse.size == 0:
            total = float(step.sum())
            if previous is not None and abs(total - previous) < 1e-6:
                return total
            previous = total
            coarse = np.arange(t.size - 1)  # the check: halve every step
        if t.size + coarse.size > max_points or np.min(np.diff(t)[coarse]) < 1e-14:
            raise RuntimeError("modal analysis: a pole lies on the search contour; please report this building")
        middle = 0.5 * (t[coarse] + t[coarse + 1])
        new_phase, new_size = _phase(system, path(middle))
        t = np.insert(t, coarse + 1, middle)
        phase = np.insert(phase, coarse + 1, new_phase)
        size = np.insert(size, coarse + 1, new_size)


def _phase(system: _System, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(arg det T(s), log |det T(s)|) for every s."""
    sign, size = np.linalg.slogdet(system.matrices(s))
    return np.angle(sign), size


# ---------------------------------------------------------------------------------------------- energy
def _energy_estimate(systems: Callable[[float], _System], count: int,
                     starts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(xi_E, xi_inherent, omega) of the first ``count`` stiffened real modes (module docstring); ``systems(omega)``
    is T with its nonlinear devices linearised at omega (rad/s; the same system at every omega without them),
    ``starts`` the frequencies (rad/s) the iteration starts from."""
    ratios, inherent, frequencies = [], [], []
    for j in range(count):
        omega = starts[j]
        for _ in range(100):
            system = systems(omega)
            mass = np.diag(system.mass)
            storage = system.wall_stiffness(1j * omega)[0]
            values, shapes = eigh(system.stiffness + story_matrix(storage.real), mass)
            updated = np.sqrt(abs(values[j]))
            converged = abs(updated - omega) <= 1e-13 * omega
            omega = updated
            if converged:
                break
        system = systems(omega)
        mass = np.diag(system.mass)
        storage = system.wall_stiffness(1j * omega)[0]
        shape = shapes[:, j] / np.abs(shapes[:, j]).max()  # mass-normalised shapes of huge masses underflow
        drift = np.diff(shape, prepend=0.0)
        strain_energy = 0.5 * omega**2 * shape @ mass @ shape
        wall_work = np.pi * np.sum(storage.imag * drift**2)
        inherent_work = np.pi * omega * shape @ system.damping @ shape
        inherent.append(inherent_work / (4.0 * np.pi * strain_energy))
        ratios.append((inherent_work + wall_work) / (4.0 * np.pi * strain_energy))
        frequencies.append(omega)
    return np.array(ratios), np.array(inherent), np.array(frequencies)


# ---------------------------------------------------------------------------------------------- linearisation
def drift_amplitudes(building: ShearBuilding, drift_amplitude: float | ArrayLike | None) -> np.ndarray | None:
    """The story drift amplitudes (mm, one a story) a nonlinear device is linearised at: ``drift_amplitude`` a
    number (every story) or a sequence of one a story, each finite and > 0; None stays None."""
    if drift_amplitude is None:
        return None
    values = finite_array("drift_amplitude", drift_amplitude, ndim=None)
    if values.ndim > 1 or (values.ndim == 1 and values.size != building.stories):
        raise ValueError(f"drift_amplitude must be one amplitude (mm) or one a story ({building.stories}), got "
                         f"shape {values.shape}")
    if (values <= 0.0).any():
        raise ValueError(f"drift_amplitude must be > 0 mm, got {show(values[values <= 0.0].flat[0])}")
    return np.broadcast_to(values, (building.stories,)).astype(float)


def require_amplitude(building: ShearBuilding, amplitudes: np.ndarray | None, analysis: str) -> None:
    """ValueError naming the first device whose stiffness depends on its amplitude when ``analysis`` was given
    no drift amplitude (mm) to linearise it at."""
    nonlinear = nonlinear_devices(building)
    if nonlinear and amplitudes is None:
        story, device = nonlinear[0]
        raise ValueError(f"{analysis}: story {story}'s {device.describe()} depends on its amplitude: give "
                         "drift_amplitude (mm, the story drift amplitude it is linearised at: one number, or one a "
                         "story)")


def nonlinear_devices(building: ShearBuilding) -> list[tuple[int, Device]]:
    """(story, device) of every device whose stiffness depends on its amplitude: nonlinear fluid viscous dampers,
    friction dampers and strain-dependent walls."""
    return [(story, device) for story, device in building.device_list
            if isinstance(device, StrainDependentDamper) or not is_linear_device(device)]


def linearisation_notes(building: ShearBuilding, amplitudes: np.ndarray | None) -> tuple[str, ...]:
    """One line per amplitude-dependent device: what it is and the amplitude it is linearised at."""
    notes = []
    for story, device in nonlinear_devices(building):
        if amplitudes is None:
            continue
        drift = float(amplitudes[story - 1])
        along = device.magnification * drift
        how = ("its parameters at the strain amplitude " f"{along / device.thickness:.4g}"
               if isinstance(device, StrainDependentDamper) else
               "equivalent linear stiffness K_eff + i K'' of the same energy per cycle, at each mode's own "
               "frequency |s|")
        notes.append(f"story {story}: {device.describe()} linearised at story drift amplitude {drift:.4g} mm "
                     f"(device {along:.4g} mm): {how}")
    return tuple(notes)


def _fixed_walls(building: ShearBuilding, amplitudes: np.ndarray | None) -> ShearBuilding:
    """The building with each strain-dependent wall at the strain amplitude of its story's drift amplitude
    (magnification x drift / thickness; clamped to its range with a warning); unchanged without amplitudes."""
    if amplitudes is None or not building.strain_dependent:
        return building
    walls = {story: tuple(wall.at(wall.magnification * amplitudes[story - 1] / wall.thickness)
                          if isinstance(wall, StrainDependentDamper) else wall for wall in group)
             for story, group in building.walls.items()}
    return building.with_walls(cast("dict[int, tuple[Wall | StrainDependentDamper, ...]]", walls))


def linearised_modes(building: ShearBuilding, amplitudes: np.ndarray | None,
                     wanted: int | None = None) -> tuple[np.ndarray, np.ndarray, int, np.ndarray]:
    """(poles, shapes, count, frozen omega per mode (rad/s; NaN without nonlinear devices)) of the building with
    every device, nonlinear ones linearised at ``amplitudes`` (mm) and, mode by mode, at the mode's own
    frequency omega = |s|: the fixed point of omega -> |s_j(omega)|, found by the secant method to 1e-12
    (module docstring).  ``wanted``: the modes to find (default all the first system has)."""
    if not nonlinear_devices(building):
        poles, shapes, count = complex_modes(building)
        return poles, shapes, count, np.full(poles.size, np.nan)
    require_modal_size(building, "a complex modal analysis")
    require_stable_under_gravity(building, "the complex modal analysis")
    bare = np.sqrt(np.abs(eigh(np.asarray(building.stiffness_matrix), np.asarray(building.mass_matrix),
                               eigvals_only=True)))
    first, _, first_count = _modes_of(_System(building, True, amplitudes, float(bare[0])))
    available = first.size if wanted is None else min(wanted, max(first.size, 1))
    poles = np.full(available, complex(np.nan, np.nan))
    shapes = np.full((building.stories, available), complex(np.nan, np.nan))
    frozen = np.full(available, np.nan)
    count = first_count
    for j in range(available):
        start = abs(first[j]) if j < first.size else bare[min(j, bare.size - 1)]
        found = _fixed_point(building, amplitudes, j, float(start))
        if found is None:
            continue
        poles[j], shapes[:, j], frozen[j], mode_count = found
        if j == 0:
            count = mode_count
    return poles, shapes, count, frozen


def _fixed_point(building: ShearBuilding, amplitudes: np.ndarray | None, j: int,
                 omega: float) -> tuple[complex, np.ndarray, float, int] | None:
    """Mode j (0-based) of the building linearised at omega = |s_j|: (s, shape, omega, count), or None when the
    linearised building has no mode j.  Secant iteration on g(omega) = |s_j(omega)| - omega."""
    def residual(frequency: float) -> tuple[float, complex, np.ndarray, int] | None:
        poles, shapes, count = _modes_of(_System(building, True, amplitudes, frequency))
        if poles.size <= j:
            return None
        return abs(poles[j]) - frequency, poles[j], shapes[:, j], count

    previous = residual(omega)
    if previous is None:
        return None
    omega_previous, omega = omega, omega + previous[0]
    for _ in range(60):
        current = residual(omega)
        if current is None:
            return None
        if abs(current[0]) <= 1e-12 * omega:
            return current[1], current[2], omega, current[3]
        slope = (current[0] - previous[0]) / (omega - omega_previous)
        step = -current[0] / slope if slope != 0.0 and np.isfinite(slope) else current[0]
        if not 0.5 * omega < omega + step < 2.0 * omega:  # a wild secant step: fall back to the fixed point
            step = current[0]
        omega_previous, previous, omega = omega, current, omega + step
    raise RuntimeError(f"modal analysis: the equivalent linearisation of mode {j + 1} did not converge "
                       f"(omega = {omega!r} rad/s); please report this building")


# ---------------------------------------------------------------------------------------------- public
def modal_analysis(building: ShearBuilding, modes: int | Sequence[int] | None = None,
                   drift_amplitude: float | ArrayLike | None = None) -> ModalResult:
    """Complex modal analysis of the linear ``building`` with all its devices (module docstring for the method).

    ``modes``: None (every oscillatory mode: normally one per floor; heavy devices can overdamp some, and
    fractional walls can add a heavily damped one), a mode number or a sequence of them (1-based, in
    order of |s|).  Bare-frame values of a mode the bare frame lacks, and energy estimates beyond the
    number of floors, are NaN.  The building is taken at its initial stiffness with P-Delta
    (``stiffnesses`` and ``geometric_stiffness``; story hysteresis is ignored) and its inherent
    damping (``damping_model``).

    Devices: walls (:class:`~vdw_frames.FDMKDamper`, :class:`~vdw_frames.SupportedDamper`) and linear fluid
    viscous dampers (alpha = 1) exactly, through their Laplace-domain stiffness times magnification^2.
    Devices whose stiffness depends on their amplitude are linearised at the story drift amplitude
    ``drift_amplitude`` (mm: one number for every story, or one a story; the device's own amplitude is
    magnification x drift), the result's ``linearisation`` says which device at which amplitude:

    * a nonlinear fluid viscous damper: the dashpot of the same energy per cycle,
      C_eq = lambda C (omega u_0)^(alpha - 1) / pi (FEMA 356, 2000, Sec. 9.3.4.3; with a brace, at the
      dashpot's own amplitude: :meth:`~vdw_frames.FluidViscousDamper.complex_stiffness`);
    * a friction damper: K_eff = F_s / u_0 and K'' = 4 F_s (u_0 - F_s / k) / (pi u_0^2) (FEMA 356 Sec. 9.3.3 and
      eq. 9-36: the secant stiffness and the damping W_D / (4 pi W_S));
    * a strain-dependent wall: its parameters at the strain amplitude magnification x drift / thickness
      (:meth:`~vdw_frames.StrainDependentDamper.at`).

    ASCE 7-16 Sec. 18.1 names both families (displacement-dependent: hysteretic or friction; velocity-dependent:
    viscous or viscoelastic) and its alternative (linear) procedures use an effective damping of each mode from
    such devices; the equations implemented are FEMA 356's.  A nonlinear device enters T(s) as a spring K'(omega)
    and a dashpot K''(omega) / omega, frozen at omega and iterated, mode by mode, to omega = |s| of that mode
    (the undamped natural frequency of the damped pole), as the walls' storage stiffness is iterated for the
    start and the energy estimate.  For one story, the ratio is then W_D / (4 pi W_S) exactly.
    Without ``drift_amplitude``, a nonlinear device is a ValueError naming it.

    Buildings of more than :data:`MAX_STORIES` (100) stories are refused before any work.  Returns a
    :class:`ModalResult` (rad/s, s, -).
    """
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    amplitudes = drift_amplitudes(building, drift_amplitude)
    require_amplitude(building, amplitudes, "modal_analysis()")
    nonlinear = nonlinear_devices(building)
    notes = linearisation_notes(building, amplitudes)
    building = _fixed_walls(building, amplitudes)
    require_fixed_walls(building, "modal_analysis()")
    poles, shapes, count, frozen = linearised_modes(building, amplitudes)
    bare_poles, _, _ = complex_modes(building, devices=False)
    selected = _mode_numbers(modes, poles.size)
    index = selected - 1
    # Mode j of the bare frame and of the real-mode estimate, where they exist (NaN beyond).
    bare = np.full(poles.size, complex(np.nan, np.nan))
    bare[: min(bare_poles.size, poles.size)] = bare_poles[: poles.size]
    real_modes = min(int(selected.max(initial=0)), building.stories)
    energy, inherent, omega = (np.full(poles.size, np.nan) for _ in range(3))
    if nonlinear:
        def systems(frequency: float) -> _System:
            return _System(building, True, amplitudes, frequency)
        starts = np.where(np.isfinite(poles[:real_modes]), np.abs(poles[:real_modes]), np.abs(bare[:real_modes]))
    else:
        plain = _System(building)

        def systems(frequency: float) -> _System:
            return plain
        starts = np.sqrt(np.abs(eigh(plain.stiffness, np.diag(plain.mass), eigvals_only=True)))[:real_modes]
    energy[:real_modes], inherent[:real_modes], omega[:real_modes] = _energy_estimate(systems, real_modes, starts)
    damping = -poles.real / np.abs(poles)
    bare_damping = -bare.real / np.abs(bare)
    return ModalResult(
        modes=selected,
        poles=poles[index],
        periods=2.0 * np.pi / np.abs(poles[index]),
        damping_ratios=damping[index],
        mode_shapes=shapes[:, index],
        bare_poles=bare[index],
        bare_periods=2.0 * np.pi / np.abs(bare[index]),
        bare_damping_ratios=bare_damping[index],
        added_damping=damping[index] - bare_damping[index],
        energy_damping_ratios=energy[index],
        energy_inherent=inherent[index],
        effective_periods=2.0 * np.pi / omega[index],
        pole_count=count,
        drift_amplitudes=amplitudes if nonlinear else None,
        linearisation=notes,
        linearisation_frequencies=frozen[index] / (2.0 * np.pi),
    )


def _mode_numbers(modes: int | Sequence[int] | None, available: int) -> np.ndarray:
    if modes is None:
        return np.arange(1, available + 1)
    if available == 0:
        raise ValueError("the building has no oscillatory mode: every pole is overdamped")
    items = [modes] if isinstance(modes, int) or np.ndim(modes) == 0 else list(modes)
    if not items:
        raise ValueError("modes must name at least one mode")
    numbers = np.array([whole_number("modes", m, 1) for m in items])
    if numbers.max() > available:
        raise ValueError(f"modes must be mode numbers in 1 ... {available}, got {modes!r}")
    return numbers
