"""The wall contract: what every wall assembly is, and the stiffness methods derived from K*(f).

A *wall* is anything the frame, the design tools and the OpenSees bridge can hold in a story:
:class:`~vdw_frames.FDMKDamper` (the material of paper eqs. (3)-(5) over an area and a layer thickness)
and :class:`~vdw_frames.SupportedDamper` (a wall in series with its support).  :class:`Wall` states the
contract as a type; :class:`StiffnessMethods` derives K', K'', C_d and the loss factor from one
``complex_stiffness``, so that no wall type writes them again (:class:`~vdw_frames.element.prony.PronySeries`
uses it too).

Units: frequency Hz, s in rad/s, stiffness N/mm, damping coefficient N*s/mm.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar, Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike

from .._validation import positive_frequencies, require_finite, show

if TYPE_CHECKING:
    from .limits import WallLimits
    from .thermal import ThermalProperties

# The openings of the warnings a wall outside its identified range gives, on every path that steps walls
# (simulate, the batches, a wall's own force history): one text, so that callers can tell them apart
# (vdw_frames.frame.time_history.is_strain_range_warning).
PEAK_OUTSIDE = "wall peak strain outside the range its parameters were identified for: "
AMPLITUDE_OUTSIDE = "wall strain amplitude outside the amplitudes its parameters were identified at"
TEMPERATURE_OUTSIDE = ("wall temperature outside its shift law's range (the law is evaluated at the nearest end of "
                       "the range)")


@runtime_checkable
class SteppedWall(Protocol):
    """What the time-stepping kernel (:class:`~vdw_frames.element.bank.WallBank`) reads of a wall (a
    :class:`Wall`, or a strain-dependent wall that follows its amplitude), all of it: its layers' ``area``
    (mm^2) and ``thickness`` (mm), its kernel constants, its thermal description and limits (None: none),
    whether it follows its own strain amplitude (``follows_amplitude``, then its ``common_order`` r and its
    ``amplitude_table()``, (nodes, 5); (0, 5) for a wall of fixed parameters, whose order is ``r``)."""

    @property
    def area(self) -> float: ...

    @property
    def thickness(self) -> float: ...

    @property
    def thermal(self) -> ThermalProperties | None: ...

    @property
    def limits(self) -> WallLimits | None: ...

    @property
    def follows_amplitude(self) -> bool: ...

    def kernel_constants(self) -> tuple:
        """The step kernel's row of 7 constants (:mod:`vdw_frames.element.kernel`)."""
        ...

    def amplitude_table(self) -> np.ndarray:
        """(nodes, 5): log strain, G1, G2, eta1, eta2 at its amplitude nodes; (0, 5) for fixed parameters."""
        ...


@runtime_checkable
class Wall(SteppedWall, Protocol):
    """A wall assembly: frequency response, kernel constants for time stepping, scaling and resizing.

    ``r`` (-) its fractional order, ``area`` (mm^2) and ``thickness`` (mm) its viscoelastic layers,
    ``strain_range`` ((low, high), dimensionless, or None) where its parameters were identified,
    ``magnification`` (-) its geometry in the frame.
    """

    # Read-only: the wall types are frozen dataclasses (a SupportedDamper reads them off its wall).
    @property
    def r(self) -> float: ...

    @property
    def strain_range(self) -> tuple[float, float] | None: ...

    @property
    def magnification(self) -> float:
        """Its deformation / the interstory drift (-): its geometry (:mod:`vdw_frames.element.device`)."""
        ...

    kind: ClassVar[str]  # "wall": its type in building files (the Device protocol)

    @property
    def linear(self) -> bool:
        """Whether its force is linear in its motion (True: fixed parameters; the Device protocol)."""
        ...

    def complex_stiffness(self, f: ArrayLike) -> np.ndarray:
        """K*(f) = K' + i K'' (N/mm) at frequencies f (Hz)."""
        ...

    def stiffness_transfer(self, s: ArrayLike) -> np.ndarray:
        """K(s) (N/mm) for complex s (rad/s)."""
        ...

    def kernel_constants(self) -> tuple[float, ...]:
        """The step kernel's row of 7 constants (:mod:`vdw_frames.element.kernel`)."""
        ...

    def story_stiffness(self, f: ArrayLike, drift_amplitude: float | None = None) -> np.ndarray:
        """magnification^2 K(i 2 pi f) (N/mm) at frequencies f (Hz): what the story sees (the Device protocol)."""
        ...

    def describe(self) -> str:
        """Its kind and parameters, for tables."""
        ...

    def scaled(self, factor: float) -> Wall:
        """Moduli and viscosities times ``factor`` (property-modification factors; supports unchanged)."""
        ...

    def resized(self, factor: float) -> Wall:
        """``factor`` walls' worth: area times ``factor`` (a support too)."""
        ...


class StiffnessMethods:
    """K', K'', C_d and the loss factor of anything with ``complex_stiffness(f)`` (N/mm at f Hz)."""

    def complex_stiffness(self, f: ArrayLike) -> np.ndarray:  # pragma: no cover - supplied by the class
        raise NotImplementedError

    def storage_stiffness(self, f: ArrayLike) -> np.ndarray:
        """K' = Re K*(f) (N/mm) at f (Hz)."""
        return self.complex_stiffness(f).real

    def loss_stiffness(self, f: ArrayLike) -> np.ndarray:
        """K'' = Im K*(f) (N/mm) at f (Hz)."""
        return self.complex_stiffness(f).imag

    def damping_coefficient(self, f: ArrayLike) -> np.ndarray:
        """C_d = K'' / omega (N*s/mm) at f (Hz)."""
        f = positive_frequencies("f", f)
        with np.errstate(over="ignore"):
            coefficient = self.loss_stiffness(f) / (2.0 * np.pi * f)
        require_finite("C_d", coefficient)
        return coefficient

    def loss_factor(self, f: ArrayLike) -> np.ndarray:
        """K''/K' = G''/G' (-) at f (Hz); 0 where the wall has no stiffness at all (K* = 0).

        Where K' = 0 but K'' > 0 (a pure dashpot) the loss factor is unbounded: a ValueError naming the
        frequency."""
        stiffness = self.complex_stiffness(f)
        silent = stiffness == 0.0
        unbounded = (stiffness.real == 0.0) & ~silent
        if np.any(unbounded):
            where = np.broadcast_to(np.asarray(f), np.shape(unbounded))[np.asarray(unbounded)].flat[0]
            raise ValueError(f"the loss factor is unbounded at f = {show(where)} Hz: K' = 0 there (K'' = "
                             f"{show(np.asarray(stiffness.imag)[np.asarray(unbounded)].flat[0])} N/mm)")
        with np.errstate(over="ignore"):
            ratio = np.where(silent, 0.0, stiffness.imag / np.where(silent, 1.0, stiffness.real))
        require_finite("the loss factor", ratio)
        return ratio
