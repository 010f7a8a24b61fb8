"""The device contract: what every damping device in a story provides, and the geometry they share.

A *device* is anything a story of a :class:`~vdw_frames.ShearBuilding` can hold: the FDMK walls
(:class:`~vdw_frames.FDMKDamper`, :class:`~vdw_frames.SupportedDamper`,
:class:`~vdw_frames.StrainDependentDamper`), fluid viscous dampers (:class:`~vdw_frames.FluidViscousDamper`)
and friction dampers (:class:`~vdw_frames.FrictionDamper`).  :class:`Device` states the contract as a type;
the model followed is OpenSees's ``UniaxialMaterial`` (``setTrialStrain(strain, strainRate)`` ->
``getStress``/``getTangent`` -> ``commitState``/``revertToLastCommit``), whose compiled side every kind
provides in its own module (:mod:`vdw_frames.element.devices` lists them).

Geometry (every device): its deformation is ``magnification`` x the interstory drift and its force adds
``magnification`` x its force to the story shear, so the story sees magnification^2 x its stiffness:
1 for a chevron brace, cos(theta) for a diagonal brace at angle theta to the floor, larger for toggle and
scissor-jack layouts (Constantinou et al. 2001, "Toggle-brace-damper seismic energy dissipation systems",
J. Struct. Eng. 127(2)).

Units: frequency Hz, deformation mm, force N, stiffness N/mm.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence
from typing import ClassVar, NamedTuple, Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike

from .._validation import positive, show


@runtime_checkable
class Device(Protocol):
    """A damping device across a story.

    A subclass (a frozen dataclass) provides:

    * ``kind`` (class attribute): its name in building files (``"wall"`` for every wall; the other kinds'
      are registered in :data:`vdw_frames.element.devices.KINDS`);
    * ``magnification`` (-): the geometry factor above, > 0;
    * ``linear``: whether its force is linear in its motion (a wall of fixed parameters, a linear FVD);
    * :meth:`story_stiffness`: the complex stiffness f^2 K*(f) the story sees (N/mm), exact for a linear
      device, the equivalent linear one at a stated drift amplitude for a nonlinear one;
    * :meth:`scaled`: its force-defining properties times a property-modification factor;
    * :meth:`resized`: ``factor`` devices' worth in parallel;
    * :meth:`describe`: a short text for tables (its kind and parameters).

    Time stepping, energies (dissipated and stored) and the trial/commit/revert of the compiled side are
    the kind's module's (:mod:`vdw_frames.element.devices`; the walls keep their own bank,
    :mod:`vdw_frames.element.bank`).
    """

    kind: ClassVar[str]

    @property
    def magnification(self) -> float: ...

    @property
    def linear(self) -> bool:
        """Whether its force is linear in its motion (then :meth:`story_stiffness` needs no amplitude)."""
        ...

    def story_stiffness(self, f: ArrayLike, drift_amplitude: float | None = None) -> np.ndarray:
        """magnification^2 K*(f) (N/mm) at frequencies f (Hz); a nonlinear device's at ``drift_amplitude`` (mm)."""
        ...

    def scaled(self, factor: float) -> Device:
        """Its force-defining properties times ``factor`` (property-modification factors)."""
        ...

    def resized(self, factor: float) -> Device:
        """``factor`` devices' worth in parallel."""
        ...

    def describe(self) -> str:
        """Its kind and parameters, for tables."""
        ...


def magnification_factor(value: object) -> float:
    """A device's magnification (-): finite and > 0, with its square (the story's share of the device's stiffness)
    a normal double, else a ValueError naming it."""
    magnification = positive("magnification", value)
    if not sys.float_info.min <= magnification * magnification < math.inf:
        raise ValueError(f"magnification = {show(value)}: its square, the story's share of the device's stiffness, "
                         "lies outside the double-precision range")
    return magnification


def story_share(magnification: float, stiffness: np.ndarray, kind: str) -> np.ndarray:
    """magnification^2 x ``stiffness`` (N/mm): what the story sees of a device's K*; a ValueError naming the
    magnification where the product overflows."""
    with np.errstate(over="ignore", invalid="ignore"):
        share = magnification * magnification * np.asarray(stiffness)
    if not np.isfinite(share).all():
        raise ValueError(f"the {kind}'s stiffness times its magnification^2 ({show(magnification)}^2) exceeds the "
                         "double-precision range")
    return share


def device_amplitude(drift_amplitude: float | None, magnification: float, kind: str) -> float:
    """The device's deformation amplitude (mm) at a story drift amplitude (mm): magnification x drift; a
    ValueError when a nonlinear device's equivalent stiffness is asked for without an amplitude."""
    if drift_amplitude is None:
        raise ValueError(f"a {kind}'s equivalent linear stiffness depends on its amplitude: give drift_amplitude "
                         "(mm), the story drift amplitude it is linearised at")
    amplitude = positive("drift_amplitude", drift_amplitude)
    if not math.isfinite(magnification * amplitude):
        raise ValueError(f"drift_amplitude = {show(drift_amplitude)} mm times the {kind}'s magnification "
                         f"{show(magnification)} exceeds the double-precision range")
    return magnification * amplitude


def require_own_amplitude(amplitude: float | None, kind: str) -> float:
    """A device's own deformation amplitude (mm, finite and > 0) for its ``complex_stiffness``: a ValueError naming
    ``amplitude`` when it is None (its K* depends on it)."""
    if amplitude is None:
        raise ValueError(f"a {kind}'s K* depends on its amplitude: give amplitude (mm, the device's own deformation "
                         "amplitude; story_stiffness takes the story's, drift_amplitude)")
    return positive("amplitude", amplitude)


def describe_number(value: float) -> str:
    """A parameter as tables print it (4 significant digits)."""
    return show(float(f"{value:.4g}"))


class Kinematics(NamedTuple):
    """Where each of one kind's D devices sits and how it moved: the state group every kind's compiled
    states start with (:mod:`vdw_frames.element.devices`).  Committed values are those of the last
    accepted step; ``trial_*`` those of the last trial, which a commit accepts and a revert discards."""

    story: np.ndarray  # (D,) int64: the story (0-based) it spans
    column: np.ndarray  # (D,) int64: its column in the building's device histories
    magnification: np.ndarray  # (D,) -: device deformation / story drift
    deformation: np.ndarray  # (D,) mm, committed
    velocity: np.ndarray  # (D,) mm/s, committed (Newmark's, of the deformation)
    force: np.ndarray  # (D,) N, committed
    heat: np.ndarray  # (D,) N*mm dissipated since rest, committed
    stored: np.ndarray  # (D,) N*mm stored now, committed
    trial_deformation: np.ndarray  # (D,) mm
    trial_velocity: np.ndarray  # (D,) mm/s
    trial_force: np.ndarray  # (D,) N
    trial_tangent: np.ndarray  # (D,) N/mm: dF/dd including Newmark's 2/dt dF/dv
    trial_heat: np.ndarray  # (D,) N*mm
    trial_stored: np.ndarray  # (D,) N*mm


def kinematics(stories: Sequence[int], columns: Sequence[int], magnifications: Sequence[float]) -> Kinematics:
    """The :class:`Kinematics` of devices at rest on ``stories`` (0-based), history ``columns`` and
    ``magnifications``."""
    count = len(stories)
    zeros = [np.zeros(count) for _ in range(11)]
    return Kinematics(np.asarray(stories, dtype=np.int64).reshape(count),
                      np.asarray(columns, dtype=np.int64).reshape(count),
                      np.asarray(magnifications, dtype=float).reshape(count), *zeros)
