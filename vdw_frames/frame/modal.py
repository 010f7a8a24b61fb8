"""Complex modal analysis of a shear building with FDMK walls: poles, periods, damping ratios, shapes.

The linear (initial-stiffness) building with its walls has the characteristic matrix

    T(s) = s^2 M + s C + K + K_G + sum_walls B^T k(s) B,

M the floor masses (tonne), C the inherent damping (N*s/mm, Rayleigh or modal), K the initial elastic
story stiffness and K_G the P-Delta stiffness -P/h (N/mm), and k(s) each wall's Laplace-domain stiffness
``wall.stiffness_transfer(s)`` (N/mm; paper eqs. (3)-(5) times area/thickness, in series with the
support of a :class:`~vdw_frames.SupportedDamper`).  The modes are the roots of det T(s) = 0 with
Im s > 0 on the principal branch of s^r: a *nonlinear* eigenproblem, since k(s) contains s^r.

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

from .._validation import whole_number
from .building import ShearBuilding, require_fixed_walls, require_stable_under_gravity, story_matrix

if TYPE_CHECKING:
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
    """Complex modes of a building with walls (:func:`modal_analysis`), arrays over ``modes``.

    ``modes``: mode numbers (1-based, ordered by |s|).  ``poles``: s (rad/s, Im s > 0);
    ``periods``: 2 pi / |s| (s); ``damping_ratios``: -Re s / |s| (-); ``mode_shapes``: complex
    floor displacements, one column per mode, scaled so the entry of largest modulus is 1.
    ``bare_poles``, ``bare_periods``, ``bare_damping_ratios``: the same frame without walls (inherent
    damping and P-Delta kept); ``added_damping`` = damping_ratios - bare_damping_ratios.
    ``energy_damping_ratios``: the energy estimate xi_inherent + sum W_c / (4 pi W_s) (module
    docstring), with ``energy_inherent`` its inherent part and ``effective_periods`` (s) the periods of
    the real modes it uses (walls at their storage stiffness); mode j of the bare frame and of the real
    modes is paired with complex mode j (NaN where there is none: see :func:`modal_analysis`).
    ``pole_count``: the number of roots of det T in the search sector by the argument principle (= the
    number of modes found; with walls).
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

    @property
    def frequencies(self) -> np.ndarray:
        """|s| / (2 pi), Hz."""
        return np.abs(self.poles) / (2.0 * np.pi)

    @property
    def energy_added_damping(self) -> np.ndarray:
        """The walls' part of the energy estimate, sum W_c / (4 pi W_s) (-)."""
        return self.energy_damping_ratios - self.energy_inherent


# ---------------------------------------------------------------------------------------------- T(s)
class _System:
    """T(s) of a building (with or without its walls), vectorised over many s."""

    def __init__(self, building: ShearBuilding, walls: bool = True) -> None:
        self.n = building.stories
        self.mass = np.asarray(building.masses, dtype=float)
        self.damping = np.asarray(building.damping_matrix, dtype=float)
        self.stiffness = np.asarray(building.stiffness_matrix) + story_matrix(np.asarray(building.geometric_stiffness))
        # Fixed walls only (modal_analysis checked): no strain-dependent wall.
        self.walls = cast("list[tuple[int, Wall]]", building.wall_list) if walls else []
        # Equal walls are evaluated once: (wall, how many of it each story holds).
        counts: dict[Wall, np.ndarray] = {}
        for story, wall in self.walls:
            counts.setdefault(wall, np.zeros(self.n))[story - 1] += 1.0
        self.wall_groups = list(counts.items())

    def wall_stiffness(self, s: ArrayLike) -> np.ndarray:
        """Sum of the walls' k(s) per story (N/mm), shape (len(s), stories)."""
        s = np.atleast_1d(np.asarray(s, dtype=complex))
        per_story = np.zeros((s.size, self.n), dtype=complex)
        for wall, count in self.wall_groups:
            per_story += np.multiply.outer(wall.stiffness_transfer(s), count)
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
        if self.walls:
            radius = _CAUCHY_RADIUS * abs(s)
            turns = np.exp(2j * np.pi * np.arange(_CAUCHY_POINTS) / _CAUCHY_POINTS)
            values = self.wall_stiffness(s + radius * turns)
            slope = (values * turns.conj()[:, None]).sum(axis=0) / (_CAUCHY_POINTS * radius)
            _add_stories(matrix[None], slope[None])
        return matrix


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


def complex_modes(building: ShearBuilding, walls: bool = True) -> tuple[np.ndarray, np.ndarray, int]:
    """(poles ascending in |s|, shapes as columns, argument-principle count) of the linear building."""
    require_modal_size(building, "a complex modal analysis")
    require_stable_under_gravity(building if walls else building.without_walls(), "the complex modal analysis")
    system = _System(building, walls)
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
def _energy_estimate(building: ShearBuilding, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(xi_E, xi_inherent, omega) of the first ``count`` stiffened real modes (module docstring)."""
    system = _System(building)
    mass = np.diag(system.mass)
    omega_bare = np.sqrt(np.abs(eigh(system.stiffness, mass, eigvals_only=True)))
    ratios, inherent, frequencies = [], [], []
    for j in range(count):
        omega = omega_bare[j]
        for _ in range(100):
            storage = system.wall_stiffness(1j * omega)[0]
            values, shapes = eigh(system.stiffness + story_matrix(storage.real), mass)
            updated = np.sqrt(abs(values[j]))
            converged = abs(updated - omega) <= 1e-13 * omega
            omega = updated
            if converged:
                break
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


# ---------------------------------------------------------------------------------------------- public
def modal_analysis(building: ShearBuilding, modes: int | Sequence[int] | None = None) -> ModalResult:
    """Complex modal analysis of the linear ``building`` with its walls (module docstring for the method).

    ``modes``: None (every oscillatory mode: normally one per floor; heavy walls can overdamp some, and
    fractional walls can add a heavily damped one), a mode number or a sequence of them (1-based, in
    order of |s|).  Bare-frame values of a mode the bare frame lacks, and energy estimates beyond the
    number of floors, are NaN.  The building is taken at its initial stiffness with P-Delta
    (``stiffnesses`` and ``geometric_stiffness``; story hysteresis is ignored) and its inherent
    damping (``damping_model``).  Walls may be :class:`~vdw_frames.FDMKDamper` or
    :class:`~vdw_frames.SupportedDamper`; strain-dependent walls are refused (give them parameters at
    one amplitude with ``wall.at(strain)``).  Buildings of more than :data:`MAX_STORIES` (100) stories are
    refused before any work.  Returns a :class:`ModalResult` (rad/s, s, -).
    """
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    require_fixed_walls(building, "modal_analysis()")
    poles, shapes, count = complex_modes(building)
    bare_poles, _, _ = complex_modes(building, walls=False)
    selected = _mode_numbers(modes, poles.size)
    index = selected - 1
    # Mode j of the bare frame and of the real-mode estimate, where they exist (NaN beyond).
    bare = np.full(poles.size, complex(np.nan, np.nan))
    bare[: min(bare_poles.size, poles.size)] = bare_poles[: poles.size]
    real_modes = min(int(selected.max(initial=0)), building.stories)
    energy, inherent, omega = (np.full(poles.size, np.nan) for _ in range(3))
    energy[:real_modes], inherent[:real_modes], omega[:real_modes] = _energy_estimate(building, real_modes)
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
