"""Sizing walls (and any damping device) to a target damping ratio of one mode, from the complex modal analysis.

:func:`size_devices` takes any device as the template (a wall, a linear or nonlinear fluid viscous damper, a
friction damper: :class:`~vdw_frames.element.device.Device`), scaled by ``device.resized`` (a wall's area, an
FVD's C and K_b, a friction damper's slip force and stiffness), with nonlinear devices linearised at a stated
design story drift amplitude (:func:`~vdw_frames.modal_analysis`); :func:`size_walls` and
:func:`damping_curve` are its walls-only forms, as before.

The walls are one template wall per story, its shear area scaled by ``factor x weight[story]``:

- ``distribution = "uniform"``: weight 1 on every walled story;
- ``"stiffness"``: weight proportional to the story's initial stiffness k0 (largest 1);
- ``"drift"``: weight proportional to the story's drift in the mode, from the bare frame's undamped
  mode shape (largest 1);
- ``"existing"``: no template (``wall=None``): the building's own walls, every one's area scaled by the
  same ``factor`` (1 = the building as it is), on the stories that have them; the layout the engineer
  chose (areas and thicknesses that differ by story) is kept.

So ``factor x wall.area`` is the wall area of the story with the largest weight (``"existing"``: ``factor x``
each wall's own area).  A
:class:`~vdw_frames.SupportedDamper` scales with its support (``factor`` walls' worth, each with its
own connection: k_s scales with the area), so the support's share of the deformation is unchanged.

The walled stories: ``stories`` (a list of story numbers or "all"); by default those of the building's
existing walls, or every story when it has none.  The building's existing walls are *replaced*.

Added damping does not grow without bound: the walls stiffen the frame as they damp it, the mode
shortens and, with walls in some stories only, concentrates its drift in the stories without walls,
so the mode's damping ratio reaches a maximum and then falls (measured in the README, section "What
the walls add, and sizing them").  :func:`size_walls` finds that maximum first and refuses a target
above it.

Units: areas mm^2, periods s, damping ratios dimensionless.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, cast

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import eigh

from .._validation import damping_ratio as check_damping_ratio
from .._validation import finite_array, whole_number
from ..element.device import Device
from ..element.devices import is_stepped_device
from ..element.strain_dependent import StrainDependentDamper
from ..element.supported import WALL_TYPES
from ..frame.building import ShearBuilding, is_wall, require_fixed_walls, story_matrix
from ..frame.modal import (
    complex_modes,
    drift_amplitudes,
    linearisation_notes,
    linearised_modes,
    modal_analysis,
    nonlinear_devices,
    require_amplitude,
    require_modal_size,
)

if TYPE_CHECKING:
    from ..element.wall import Wall

DISTRIBUTIONS = ("uniform", "stiffness", "drift", "existing")
MAX_STORIES = 30
"""Largest building (stories) :func:`size_walls` and :func:`damping_curve` take, refused before any work:
they repeat the complex modal analysis some 50-100 times (:data:`vdw_frames.frame.modal.MAX_STORIES` is
its own limit).  Measured on the development machine under load, damping_curve 7 s at 20 stories, 24 s at
30, 51 s at 35 and 198 s at 40; ``vdw-frames design`` runs both."""
MAX_FACTORS = 1000  # damping_curve's factors: each is a complex modal analysis
# Default factors of the damping-versus-size curve: 1/50 to 50 times the template wall's area.
DEFAULT_FACTORS = np.geomspace(0.02, 50.0, 41)
SEARCH_FACTORS = (1e-3, 1e3)
"""The area factors searched for the largest damping ratio (:attr:`SizingCurve.best_factor`): a best factor at
an end means the ratio still grows there (no interior maximum within a million-fold range of sizes)."""


@dataclass(frozen=True)
class SizingCurve:
    """A mode's period and damping ratio against the wall size (:func:`damping_curve`).

    ``factors``: area factors (-); ``areas``: wall area per story (mm^2, shape (factors, stories), 0
    where a story has no wall; all of a story's walls); ``damping_ratios`` (-) and ``periods`` (s) of mode
    ``mode`` (NaN where that mode is no longer oscillatory); ``bare_damping_ratio`` and ``bare_period``: the
    frame without walls; ``best_factor`` and ``best_damping_ratio``: the largest ratio over factors 1e-3 ... 1e3 and
    the factor that gives it (``best_factor`` = 1e3 means it was still growing there), with ``best_period`` (s).
    ``weights``: the distribution over the stories (largest 1); ``wall``: the template (None for the
    ``"existing"`` distribution, which scales the building's own walls).  ``drift_amplitudes`` (mm, one a
    story): the story drift amplitudes the building's amplitude-dependent devices (nonlinear FVDs, friction
    dampers, kept as they are) were linearised at, and ``linearisation`` one line per such device (None and
    () when the building has none): the curve holds at those amplitudes only.
    """

    mode: int
    distribution: str
    stories: tuple[int, ...]
    wall: Wall | None
    weights: np.ndarray
    factors: np.ndarray
    areas: np.ndarray
    damping_ratios: np.ndarray
    periods: np.ndarray
    bare_damping_ratio: float
    bare_period: float
    best_factor: float
    best_damping_ratio: float
    best_period: float
    drift_amplitudes: np.ndarray | None = None
    linearisation: tuple[str, ...] = ()

    @property
    def stories_text(self) -> str:
        """The walled stories in words ("stories 1-10", "story 3")."""
        return story_text(self.stories)


def _check_wall(wall: object) -> None:
    if not isinstance(wall, WALL_TYPES):
        raise ValueError(f"wall must be an FDMKDamper or a SupportedDamper (strain-dependent walls: pick the "
                         f"parameters at one amplitude with wall.at(strain)), got {type(wall).__name__}")


def _check_device(device: object) -> None:
    """A template :func:`size_devices` can scale: any device of the :class:`~vdw_frames.element.device.Device`
    protocol with a fixed linearisation (a strain-dependent wall: pick it at one amplitude first)."""
    if isinstance(device, StrainDependentDamper):
        _check_wall(device)
    if not isinstance(device, Device) or not (is_wall(device) or is_stepped_device(device)):
        raise ValueError(f"device must be a damping device (FDMKDamper, SupportedDamper, FluidViscousDamper, "
                         f"FrictionDamper), got {type(device).__name__}")


class _Sizer:
    """The mode's complex pole as a function of the size factor, for one building, template and distribution.

    ``walls_only``: the template and the building's scaled devices must be walls (:func:`size_walls`,
    :func:`damping_curve`); otherwise any device (:func:`size_devices`).  ``amplitudes``: the story drift
    amplitudes (mm) amplitude-dependent devices are linearised at (None: none may be present)."""

    def __init__(self, building: ShearBuilding, wall: Device | None, mode: int, distribution: str,
                 stories: int | Sequence[int] | str | None, *, walls_only: bool = True,
                 amplitudes: np.ndarray | None = None) -> None:
        if not isinstance(building, ShearBuilding):
            raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
        what = "wall sizing (size_walls, damping_curve)" if walls_only else "device sizing (size_devices)"
        require_modal_size(building, what, MAX_STORIES)
        require_fixed_walls(building, "wall sizing" if walls_only else "device sizing")
        if not isinstance(distribution, str) or distribution not in DISTRIBUTIONS:
            raise ValueError(f"distribution must be one of {DISTRIBUTIONS}, got {distribution!r}")
        check = _check_wall if walls_only else _check_device
        own = building.wall_list if walls_only else building.device_list
        kind = "walls" if walls_only else "devices"
        if distribution == "existing":
            if wall is not None:
                raise ValueError(f"the 'existing' distribution scales the building's own {kind}: give "
                                 f"{'wall' if walls_only else 'device'}=None")
            if not own:
                raise ValueError(f"the 'existing' distribution scales the building's own {kind}, but it has none")
            occupied = sorted({story for story, _ in own})
            if stories is not None and _stories(building, stories) != tuple(occupied):
                held = "walled stories" if walls_only else "stories of its devices"
                raise ValueError(f"the 'existing' distribution keeps the {held} {occupied}; got stories={stories!r}")
            for _, existing in own:
                check(existing)
        else:
            check(wall)
        self.mode = whole_number("mode", mode, 1)
        if self.mode > building.stories:
            raise ValueError(f"mode must be a mode number in 1 ... {building.stories}, got {mode!r}")
        self.building, self.wall, self.distribution = building, wall, distribution
        self.walls_only, self.amplitudes = walls_only, amplitudes
        self.stories = _stories(building, stories, walls_only)
        self.weights = _weights(building, distribution, self.stories, self.mode)
        poles, _, _ = complex_modes(building, devices=False)
        self.bare = poles[self.mode - 1]
        self._cache: dict[float, complex] = {}

    def building_for(self, factor: float) -> ShearBuilding:
        if self.wall is None:  # "existing": every wall (every device) of the building scaled alike
            if self.walls_only:
                return self.building.with_walls({story: tuple(wall.resized(factor) for wall in walls)
                                                 for story, walls in self.building.walls.items()})
            return self.building.with_devices({story: tuple(device.resized(factor) for device in devices)
                                               for story, devices in self.building.devices.items()})
        sized = {story: (self.wall.resized(factor * self.weights[story - 1]),)
                 for story in self.stories if self.weights[story - 1] > 0.0}
        if is_wall(self.wall):
            return self.building.with_walls(cast("dict[int, tuple[Wall | StrainDependentDamper, ...]]", sized))
        # Devices of the template's kind are replaced; every other device is kept, before the sized ones.
        merged: dict[int, list[Device]] = {}
        for story, device in self.building.device_list:
            if type(device) is not type(self.wall):
                merged.setdefault(story, []).append(device)
        for story, group in sized.items():
            merged.setdefault(story, []).extend(group)
        return self.building.with_devices({story: tuple(group) for story, group in merged.items()})

    def story_areas(self) -> np.ndarray:
        """Wall area per story at factor 1 (mm^2; 0 where a story has no wall)."""
        if self.wall is None:
            return np.array([sum(wall.area for wall in self.building.walls.get(story, ()))
                             for story in range(1, self.building.stories + 1)])
        return self.weights * cast("Wall", self.wall).area

    def pole(self, factor: float) -> complex:
        """The mode's pole with devices of ``factor`` (NaN when the mode is no longer oscillatory)."""
        if factor not in self._cache:
            building = self.building_for(factor)
            if self.amplitudes is not None and nonlinear_devices(building):
                poles, _, _, _ = linearised_modes(building, self.amplitudes, self.mode)
            else:
                poles, _, _ = complex_modes(building)
            self._cache[factor] = poles[self.mode - 1] if poles.size >= self.mode else complex(np.nan, np.nan)
        return self._cache[factor]

    def damping(self, factor: float) -> float:
        s = self.pole(factor)
        return float(-s.real / abs(s))

    def best(self) -> tuple[float, float]:
        """(factor, damping ratio) of the largest damping ratio over the factors of SEARCH_FACTORS."""
        grid = np.geomspace(*SEARCH_FACTORS, 49)
        values = np.array([self.damping(f) for f in grid])
        values = np.where(np.isfinite(values), values, -np.inf)
        from scipy.optimize import minimize_scalar  # imported on use: `import vdw_frames` need not pay for it

        k = int(np.argmax(values))
        if k in (0, grid.size - 1):
            return float(grid[k]), float(values[k])
        low, high = np.log(grid[k - 1]), np.log(grid[k + 1])
        found = minimize_scalar(lambda x: -self.damping(float(np.exp(x))), bounds=(low, high), method="bounded",
                                options={"xatol": 1e-6})
        factor = float(np.exp(found.x))
        return (factor, self.damping(factor)) if self.damping(factor) >= values[k] else (float(grid[k]), values[k])

    def describe(self, factor: float) -> str:
        stories = story_text(self.stories)
        if self.wall is None:
            kind = "the areas of the building's own walls (every wall" if self.walls_only else \
                "the building's own devices (every device"
            return f"{factor:.3g} x {kind} alike, {stories})"
        per = "per story" if self.distribution == "uniform" else "in the story with the largest weight"
        if not self.walls_only:
            return (f"{factor:.3g} x {self.wall.describe()} ({per}; {self.distribution} distribution over "
                    f"{stories})")
        area = factor * cast("Wall", self.wall).area
        return (f"{factor:.3g} x the wall's area ({area:.4g} mm^2 {per}; {self.distribution} distribution over "
                f"{stories})")


def _walls_sizer(building: ShearBuilding, wall: Wall | None, mode: int, distribution: str,
                 stories: int | Sequence[int] | str | None, *, drift_amplitude: float | ArrayLike | None,
                 analysis: str) -> _Sizer:
    """The :class:`_Sizer` of walls, the building's amplitude-dependent devices (kept as they are) linearised at
    ``drift_amplitude`` (mm): a ValueError naming the first such device when it is None."""
    amplitudes = drift_amplitudes(building, drift_amplitude) if isinstance(building, ShearBuilding) else None
    sizer = _Sizer(building, wall, mode, distribution, stories, amplitudes=amplitudes)
    require_amplitude(sizer.building_for(1.0), amplitudes, analysis)
    return sizer


def damping_curve(building: ShearBuilding, wall: Wall | None, mode: int = 1, distribution: str = "uniform",
                  stories: int | Sequence[int] | str | None = None, factors: ArrayLike | None = None, *,
                  drift_amplitude: float | ArrayLike | None = None) -> SizingCurve:
    """Period and damping ratio of ``mode`` against the walls' size (see the module docstring).

    ``factors``: area factors (> 0) to evaluate (default 0.02 ... 50, 41 points, geometric; at most
    :data:`MAX_FACTORS`).  ``drift_amplitude`` (mm, one number or one a story): the story drift amplitude at
    which the building's devices whose stiffness depends on their amplitude (nonlinear FVDs, friction dampers:
    kept as they are beside the walls) are linearised (:func:`~vdw_frames.modal_analysis`); needed (a
    ValueError otherwise) when the building has such a device, and stated in the result.  Buildings above
    :data:`MAX_STORIES` (30) stories are refused before any work.  Returns a :class:`SizingCurve` (mm^2, s, -).
    """
    sizer = _walls_sizer(building, wall, mode, distribution, stories, drift_amplitude=drift_amplitude,
                         analysis="damping_curve()")
    factors = DEFAULT_FACTORS if factors is None else finite_array("factors", factors)
    if factors.size == 0 or (factors <= 0).any():
        raise ValueError("factors must be one or more area factors > 0")
    if factors.size > MAX_FACTORS:
        raise ValueError(f"factors holds {factors.size} area factors; at most {MAX_FACTORS} are evaluated (each "
                         "is a complex modal analysis)")
    poles = np.array([sizer.pole(float(f)) for f in factors])
    best_factor, best_ratio = sizer.best()
    areas = np.outer(factors, sizer.story_areas())
    return SizingCurve(sizer.mode, distribution, sizer.stories, wall, sizer.weights, factors, areas,
                       -poles.real / np.abs(poles), 2.0 * np.pi / np.abs(poles),
                       float(-sizer.bare.real / abs(sizer.bare)), float(2.0 * np.pi / abs(sizer.bare)),
                       best_factor, best_ratio, float(2.0 * np.pi / abs(sizer.pole(best_factor))),
                       *_linearisation(sizer))


def _linearisation(sizer: _Sizer) -> tuple[np.ndarray | None, tuple[str, ...]]:
    """(story drift amplitudes (mm), one line per device) of the sizer's amplitude-dependent devices; (None, ())
    when it has none."""
    probe = sizer.building_for(1.0)
    if sizer.amplitudes is None or not nonlinear_devices(probe):
        return None, ()
    return sizer.amplitudes, linearisation_notes(probe, sizer.amplitudes)


def size_walls(building: ShearBuilding, wall: Wall | None, target_damping: float, mode: int = 1,
               distribution: str = "uniform", stories: int | Sequence[int] | str | None = None, *,
               drift_amplitude: float | ArrayLike | None = None) -> ShearBuilding:
    """A copy of ``building`` whose walls give ``mode`` the total damping ratio ``target_damping``.

    ``wall``: the template (:class:`~vdw_frames.FDMKDamper` or :class:`~vdw_frames.SupportedDamper`), its
    area scaled over the ``stories`` by ``distribution`` (module docstring); the building's own walls
    are replaced.  ``distribution="existing"`` with ``wall=None`` scales the building's own walls instead,
    every one by the same factor.  The ratio is the complex-mode value -Re s / |s| (:func:`modal_analysis`),
    inherent damping included, met to 1e-6 (the issue asks 1e-3).  The smallest walls that reach it
    are returned.  ValueError when the target is below the bare frame's ratio or above the largest
    achievable one (the message states that maximum and the wall size that gives it), and for buildings
    above :data:`MAX_STORIES` (30) stories, before any work.

    ``drift_amplitude`` (mm, one number or one a story): the design story drift amplitude at which the
    building's other devices whose stiffness depends on their amplitude (nonlinear FVDs, friction dampers, kept
    as they are) are linearised, as for :func:`size_devices`; needed (a ValueError otherwise) when the building
    has such a device.  The walls found reach the target at that amplitude only.
    """
    target = check_damping_ratio(target_damping, "target_damping")
    sizer = _walls_sizer(building, wall, mode, distribution, stories, drift_amplitude=drift_amplitude,
                         analysis="size_walls()")
    return sizer.building_for(_solve(sizer, target))


@dataclass(frozen=True)
class DeviceSizing:
    """The result of :func:`size_devices`.

    ``building``: the sized building; ``device``: the template (None for the ``"existing"`` distribution);
    ``factor`` (-): its size factor (``device.resized(factor x weight)`` on each story); ``weights``: the
    distribution over the stories (largest 1); ``mode``, ``target_damping`` (-) and ``damping_ratio`` (-, the
    sized building's complex-mode ratio of that mode, :func:`~vdw_frames.modal_analysis`), ``period`` (s);
    ``bare_damping_ratio`` (-): the frame without devices; ``drift_amplitudes`` (mm, one a story): the story
    drift amplitudes the amplitude-dependent devices were linearised at (None when none is present) and
    ``linearisation``: one line per such device saying how and at which amplitude.
    """

    building: ShearBuilding
    device: Device | None
    factor: float
    weights: np.ndarray
    mode: int
    target_damping: float
    damping_ratio: float
    period: float
    bare_damping_ratio: float
    drift_amplitudes: np.ndarray | None
    linearisation: tuple[str, ...]
    description: str

    def report(self) -> str:
        """A few lines for a design note: what was sized, to what damping, and the linearisation amplitudes."""
        lines = [f"mode {self.mode}: damping ratio {self.damping_ratio:.6f} (target {self.target_damping:.6f}, bare "
                 f"frame {self.bare_damping_ratio:.6f}), period {self.period:.4g} s, with {self.description}"]
        if self.linearisation:
            lines.append("equivalent linearisation (the damping ratio holds at these amplitudes only):")
            lines.extend(f"  {note}" for note in self.linearisation)
        return "\n".join(lines)


def size_devices(building: ShearBuilding, device: Device | None, target_damping: float, *, mode: int = 1,
                 distribution: str = "uniform", stories: int | Sequence[int] | str | None = None,
                 drift_amplitude: float | ArrayLike | None = None) -> DeviceSizing:
    """Size damping devices of any kind so that ``mode`` reaches the total damping ratio ``target_damping``.

    ``device``: the template, any device (:class:`~vdw_frames.FDMKDamper`, :class:`~vdw_frames.SupportedDamper`,
    :class:`~vdw_frames.FluidViscousDamper`, :class:`~vdw_frames.FrictionDamper`), put on the ``stories`` as
    ``device.resized(factor x weight[story])`` with the weights of ``distribution`` (module docstring): a wall's
    area (and support), an FVD's C and brace K_b, a friction damper's slip force and stiffness scale
    together, so its slip deformation F_s / k is kept.  The building's devices of the template's kind (any wall,
    for a wall) are replaced; its other devices are kept and count in the damping.  ``distribution="existing"``
    with ``device=None`` scales every device of the building by the same factor instead.

    ``drift_amplitude`` (mm, one number or one a story): the design story drift amplitude at which devices
    whose stiffness depends on their amplitude (nonlinear FVDs, friction dampers) are linearised
    (:func:`~vdw_frames.modal_analysis`), e.g. a design drift ratio times the story heights; needed (a
    ValueError otherwise) when such a device is present, and stated in the result.  The damping reached holds at
    that amplitude only: a friction damper's added damping falls at both smaller and larger drifts.

    The ratio is the complex-mode value -Re s / |s|, inherent damping included, met to 1e-6; the smallest
    devices that reach it are returned.  ValueError when the target is not above the bare frame's ratio or
    above the largest achievable one (the message states that maximum), and for buildings above
    :data:`MAX_STORIES` (30) stories, before any work.  Returns a :class:`DeviceSizing`.
    """
    target = check_damping_ratio(target_damping, "target_damping")
    amplitudes = drift_amplitudes(building, drift_amplitude) if isinstance(building, ShearBuilding) else None
    sizer = _Sizer(building, device, mode, distribution, stories, walls_only=False, amplitudes=amplitudes)
    probe = sizer.building_for(1.0)
    require_amplitude(probe, amplitudes, "size_devices()")
    nonlinear = nonlinear_devices(probe)
    factor = _solve(sizer, target)
    sized = sizer.building_for(factor)
    result = modal_analysis(sized, sizer.mode, drift_amplitude=amplitudes if nonlinear else None)
    bare = float(-sizer.bare.real / abs(sizer.bare))
    return DeviceSizing(sized, device, factor, sizer.weights, sizer.mode, target, float(result.damping_ratios[0]),
                        float(result.periods[0]), bare, amplitudes if nonlinear else None,
                        linearisation_notes(sized, amplitudes), sizer.describe(factor))


def _solve(sizer: _Sizer, target: float) -> float:
    """The smallest size factor whose mode reaches ``target`` (ValueErrors as :func:`size_walls` states them)."""
    bare = float(-sizer.bare.real / abs(sizer.bare))
    kind = "walls" if sizer.walls_only else "devices"
    if target <= bare:
        raise ValueError(f"target_damping {target!r} is not above the bare frame's mode-{sizer.mode} damping ratio "
                         f"{bare:.4f}: no {kind} are needed")
    best_factor, best_ratio = sizer.best()
    if target > best_ratio:
        limit = " (still growing at the largest size tried)" if best_factor >= SEARCH_FACTORS[1] else ""
        raise ValueError(f"target_damping {target!r} is out of reach: the largest achievable mode-{sizer.mode} "
                         f"damping ratio is {best_ratio:.4f} ({best_ratio - bare:.4f} added to the bare frame's "
                         f"{bare:.4f}), with {sizer.describe(best_factor)}{limit}")
    # The smallest factor reaching the target: damping rises from the bare value to the maximum.
    low = SEARCH_FACTORS[0]
    while sizer.damping(low) > target:
        low *= 1e-2
        if low < 1e-12:  # only the building's devices that are not sized can hold the ratio up there
            raise ValueError(f"target_damping {target!r} is reached without {kind}: the building's other devices "
                             f"give mode {sizer.mode} the damping ratio {sizer.damping(low):.4f} with {kind} of "
                             f"{low:.0e} x the size; no {kind} are needed")
    from scipy.optimize import brentq

    return float(brentq(lambda f: sizer.damping(f) - target, low, best_factor, xtol=1e-12, rtol=1e-10))


def _stories(building: ShearBuilding, stories: int | Sequence[int] | str | None,
             walls_only: bool = True) -> tuple[int, ...]:
    if stories is None:
        stories = (sorted(building.walls) if walls_only else sorted(building.devices)) or "all"
    if isinstance(stories, str):
        if stories != "all":
            raise ValueError(f"stories must be 'all' or a list of story numbers, got {stories!r}")
        return tuple(range(1, building.stories + 1))
    items = [stories] if isinstance(stories, int) or np.ndim(stories) == 0 else list(stories)
    numbers = [whole_number("stories", s, 1) for s in items]
    if not numbers or max(numbers) > building.stories or len(set(numbers)) != len(numbers):
        raise ValueError(f"stories must be distinct story numbers in 1 ... {building.stories}, got {stories!r}")
    return tuple(sorted(numbers))


def _weights(building: ShearBuilding, distribution: str, stories: tuple[int, ...], mode: int) -> np.ndarray:
    """Area weight of every story (0 for stories without walls; largest 1)."""
    index = np.array(stories) - 1
    if distribution in ("uniform", "existing"):
        raw = np.ones(building.stories)
    elif distribution == "stiffness":
        raw = np.asarray(building.stiffnesses, dtype=float)
    else:
        stiffness = np.asarray(building.stiffness_matrix) + story_matrix(np.asarray(building.geometric_stiffness))
        _, shapes = eigh(stiffness, np.asarray(building.mass_matrix))
        raw = np.abs(np.diff(shapes[:, mode - 1], prepend=0.0))
    weights = np.zeros(building.stories)
    weights[index] = raw[index]
    if weights.max() <= 0.0:
        raise ValueError(f"the {distribution} distribution gives no wall to stories {list(stories)}")
    return weights / weights.max()


def story_text(stories: tuple[int, ...]) -> str:
    if len(stories) > 1 and stories == tuple(range(stories[0], stories[-1] + 1)):
        return f"stories {stories[0]}-{stories[-1]}"
    return "story " + ", ".join(map(str, stories)) if len(stories) == 1 else "stories " + ", ".join(map(str, stories))
