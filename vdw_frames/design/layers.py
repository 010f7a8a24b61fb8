"""Layer thicknesses that keep walls inside the strain amplitudes their parameters were identified at.

A strain-dependent wall (:class:`~vdw_frames.StrainDependentDamper`) follows its own amplitude in the
time domain, but its parameters mean something only between the amplitudes of the tests it was
identified from (the paper's sets: 225-450 %); outside them they are clamped (the 225 % set behaves as
a viscoelastic fluid below it) and nothing is known.  The layer thickness t sets the strain a story
drift gives, so it is the design variable that places a wall's amplitudes in that range.

:func:`size_layers` applies one rule to every amplitude-following wall: *over a suite of ground motions
at the design intensity, the smallest and the largest peak amplitude the wall follows lie symmetric, in
logarithm, about the centre of its identified range* (sqrt(225 x 450) = 318 % for the paper's sets).
Area and thickness change together (A / t fixed), so the wall's stiffness at a given strain, and so the
frame's linear properties, are those of the design that fixed A / t (e.g. :func:`size_walls` for a
damping ratio).  A fixed point: every pass runs the suite, then scales each wall's t by
sqrt(lowest x highest) / centre; it stops when no thickness changes by more than ``tolerance``.
Whether the rule can succeed is then a property of the suite: a wall fits when its highest / lowest
ratio is at most the range's (2 for 225-450 %); :class:`LayerSizing` reports both.

Units: thickness mm, area mm^2, strain dimensionless (3.0 = 300 %).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .. import _warnings
from .._validation import positive, whole_number
from ..element.bank import DEFAULT_MEMORY, group_walls
from ..element.strain_dependent import StrainDependentDamper
from ..frame.building import ShearBuilding
from ..frame.lanes import lane_batches, run_lanes
from ..frame.simulation import simulate
from ..motion.record import GroundMotion

MAX_ITERATIONS = 100
"""The most passes :func:`size_layers` takes (each runs the whole suite), refused above before any work."""

_LANE_OPTIONS = {"method", "memory", "collapse_drift_ratio", "free_vibration", "newton"}
"""The options of :func:`~vdw_frames.simulate` that :func:`~vdw_frames.frame.lanes.run_lanes` takes too."""


@dataclass(frozen=True)
class LayerSizing:
    """The outcome of :func:`size_layers`.

    ``building``: the building with its amplitude-following walls re-layered; ``walls``: the index of each
    such wall in ``building.wall_list``; ``lowest`` and ``highest`` (-, one per such wall): the smallest
    and largest peak followed amplitude over the suite, from the last pass (run with the returned
    building); ``strain_range`` (-, (walls, 2)): each wall's identified range; ``iterations`` and
    ``converged``.
    """

    building: ShearBuilding
    walls: tuple[int, ...]
    lowest: np.ndarray
    highest: np.ndarray
    strain_range: np.ndarray
    iterations: int
    converged: bool

    @property
    def inside(self) -> np.ndarray:
        """Whether every suite amplitude of each wall lies in its identified range, (walls,) bool."""
        return (self.lowest >= self.strain_range[:, 0]) & (self.highest <= self.strain_range[:, 1])

    @property
    def margin(self) -> float:
        """The smallest factor by which any amplitude stays inside its range (< 1: outside), -."""
        return float(min(np.min(self.lowest / self.strain_range[:, 0]),
                         np.min(self.strain_range[:, 1] / self.highest)))


def size_layers(building: ShearBuilding, motions: Sequence[GroundMotion], tolerance: float = 0.002,
                max_iterations: int = 20, **simulate_options: Any) -> LayerSizing:
    """Re-layer ``building``'s amplitude-following walls by the rule of the module docstring.

    ``motions``: the suite (GroundMotion, mm/s^2), each already scaled to the design intensity;
    ``tolerance`` (-): the largest relative change of a thickness at convergence; ``max_iterations``:
    passes at most (each runs the suite once; 1 ... :data:`MAX_ITERATIONS`).  ``simulate_options`` go to every
    :func:`~vdw_frames.simulate` (e.g. ``free_vibration``).  Walls of fixed parameters are left as they
    are.  Returns a :class:`LayerSizing` (not converged after ``max_iterations``: ``converged`` False).
    Each pass runs the suite as lanes (:func:`~vdw_frames.frame.lanes.run_lanes`: the same analyses as
    simulate's, to the bit, a few compiled calls a pass), unless ``simulate_options`` hold one that lanes do
    not take (``dt``, ``strain_compatible``, ``initial_state``): then one simulate a record.
    """
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    motions = list(motions)
    if not motions or not all(isinstance(m, GroundMotion) for m in motions):
        raise ValueError("motions must be a non-empty sequence of GroundMotion objects")
    tolerance = positive("tolerance", tolerance)
    if tolerance >= 0.5:
        raise ValueError(f"tolerance must be below 0.5 (a relative change of thickness), got {tolerance!r}")
    max_iterations = whole_number("max_iterations", max_iterations, 1)
    if max_iterations > MAX_ITERATIONS:
        raise ValueError(f"max_iterations must be at most {MAX_ITERATIONS} (each pass runs the whole suite), got "
                         f"{max_iterations}")
    walls = tuple(i for i, (_, wall) in enumerate(building.wall_list) if isinstance(wall, StrainDependentDamper))
    if not walls:
        raise ValueError("size_layers needs walls that follow their amplitude (StrainDependentDamper); "
                         "this building has none")
    ranges = np.array([building.wall_list[i][1].strain_range for i in walls], dtype=float)
    centre = np.sqrt(ranges[:, 0] * ranges[:, 1])
    scale = np.ones(len(walls))
    current = building
    for iteration in range(1, max_iterations + 1):
        current = _relayered(building, walls, scale)
        peaks = _suite_amplitudes(current, motions, walls, simulate_options)
        lowest, highest = peaks.min(axis=0), peaks.max(axis=0)
        if not np.all(lowest > 0.0):
            raise ValueError("a wall followed no amplitude under some motion of the suite (the motion is zero at "
                             "that wall's story); scale the suite to the design intensity first")
        change = np.sqrt(lowest * highest) / centre
        if np.max(np.abs(change - 1.0)) <= tolerance:
            return LayerSizing(current, walls, lowest, highest, ranges, iteration, True)
        scale = scale * change
    return LayerSizing(current, walls, lowest, highest, ranges, max_iterations, False)


def _relayered(building: ShearBuilding, walls: tuple[int, ...], scale: np.ndarray) -> ShearBuilding:
    """``building`` with wall ``walls[k]``'s thickness and area both times ``scale[k]``."""
    factors = dict(zip(walls, scale.tolist(), strict=True))
    by_story: dict[int, list[Any]] = {}
    for index, (story, wall) in enumerate(building.wall_list):
        if index in factors and isinstance(wall, StrainDependentDamper):
            factor = factors[index]
            by_story.setdefault(story, []).append(
                dataclasses.replace(wall, thickness=wall.thickness * factor, area=wall.area * factor))
        else:
            by_story.setdefault(story, []).append(wall)
    return building.with_walls({story: tuple(group) for story, group in by_story.items()})


def _suite_amplitudes(building: ShearBuilding, motions: Sequence[GroundMotion], walls: tuple[int, ...],
                      options: dict[str, Any]) -> np.ndarray:
    """The peak amplitude (-) each wall of ``walls`` (indices in ``building.wall_list``) followed under each
    record, (records, walls): the records as lanes in batches of one dt and memory
    (:func:`~vdw_frames.frame.lanes.lane_batches`), each lane's warnings issued as its simulate would have, in
    the records' order; an analysis that cannot run raises simulate's ValueError."""
    if set(options) - _LANE_OPTIONS:
        return np.array([_peak_amplitudes(building, motion, walls, options) for motion in motions])
    lanes: dict[int, Any] = {}
    for batch in lane_batches(building, motions, range(len(motions)), memory=options.get("memory", DEFAULT_MEMORY),
                              free_vibration=options.get("free_vibration", 0.0), workers=None):
        lanes.update(zip(batch, run_lanes(building, [motions[i] for i in batch], **options), strict=True))
    group = group_walls(building.wall_list)[1][list(walls)]  # type: ignore[arg-type]  # fixed-order walls
    peaks = []
    for i in range(len(motions)):
        lane = lanes[i]
        for caught in lane.warnings:
            _warnings.warn(caught.message, caught.category, stacklevel=3)  # the caller of size_layers
        if lane.error is not None:
            raise ValueError(lane.error)
        if lane.peak_group_amplitude is None:  # pragma: no cover - the walls follow their amplitude (checked above)
            raise ValueError("the analysis followed no wall amplitude")
        peaks.append(lane.peak_group_amplitude[group])
    return np.array(peaks)


def _peak_amplitudes(building: ShearBuilding, motion: GroundMotion, walls: tuple[int, ...],
                     options: dict[str, Any]) -> np.ndarray:
    result = simulate(building, motion, **options)
    amplitude = result.wall_amplitude
    if amplitude is None:  # pragma: no cover - the walls follow their amplitude (checked above)
        raise ValueError("the analysis followed no wall amplitude")
    return amplitude[:, list(walls)].max(axis=0)
