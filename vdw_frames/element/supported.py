"""A wall in series with the flexibility of its support (connection, beam, brace).

A wall is never attached rigidly: the beams, the connection plates and the wall's own frame deform too.
With a support of stiffness k_s (N/mm) in series, the assembly's Laplace-domain stiffness is

    K_assembly(s) = K_wall(s) k_s / (K_wall(s) + k_s),

which is softer and, when k_s is comparable to |K_wall|, dissipates less: part of the deformation goes
into the support, which stores energy but dissipates none.

Time domain: exact.  Within one step the wall's force is affine in its own deformation, so the internal
node between wall and support is eliminated in closed form (:func:`vdw_frames.element.kernel.wall_response`);
the wall's memory sees the wall's deformation, not the assembly's.

Units: stiffness N/mm, frequency Hz, s in rad/s, displacement mm, force N.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike

from .._validation import positive, positive_frequencies, require_finite, scaled_value
from .damper import DEFAULT_MEMORY, FDMKDamper, WallState, driven_force, story_stiffness_of, wall_parameters
from .device import describe_number
from .fast_memory import FastMemory
from .fractional import DEFAULT_METHOD, Discretisation
from .limits import WallLimits
from .prony import PronySeries, fit_prony
from .thermal import PropertyFactors, ShiftLaw, ThermalProperties, property_factors
from .wall import StiffnessMethods


@dataclass(frozen=True)
class SupportedDamper(StiffnessMethods):
    """An :class:`FDMKDamper` ``damper`` in series with a support of stiffness ``support_stiffness`` (N/mm, > 0).

    Accepted wherever a wall is: :class:`~vdw_frames.ShearBuilding` dampers, :func:`~vdw_frames.sine_test`,
    :func:`~vdw_frames.simulate`, :func:`~vdw_frames.run_batch`.  It has the stiffness methods of a wall
    (the modulus methods belong to the material, ``damper``).  Its geometry is its wall's
    (:attr:`magnification` reads ``damper.magnification``): the assembly, wall and support in series,
    deforms by magnification x the interstory drift.
    """

    damper: FDMKDamper
    support_stiffness: float

    kind: ClassVar[str] = "wall"  # building files' type
    follows_amplitude: ClassVar[bool] = False
    linear: ClassVar[bool] = True

    def amplitude_table(self) -> np.ndarray:
        """The kernel's amplitude table, (0, 5): its wall has fixed parameters."""
        return np.zeros((0, 5))

    def __post_init__(self) -> None:
        if not isinstance(self.damper, FDMKDamper):
            raise ValueError(f"damper must be an FDMKDamper, got {type(self.damper).__name__}")
        object.__setattr__(self, "support_stiffness", positive("support_stiffness", self.support_stiffness))

    # The wall's own properties, for code that reads them off any wall assembly.
    @property
    def magnification(self) -> float:
        """The assembly's deformation / the interstory drift (-): its wall's (:class:`FDMKDamper` ``magnification``)."""
        return self.damper.magnification

    @property
    def r(self) -> float:
        return self.damper.r

    @property
    def area(self) -> float:
        """Shear area of the wall, mm^2."""
        return self.damper.area

    @property
    def thickness(self) -> float:
        """Layer thickness of the wall, mm (wall strain = wall deformation / thickness)."""
        return self.damper.thickness

    @property
    def strain_range(self) -> tuple[float, float] | None:
        return self.damper.strain_range

    @property
    def thermal(self) -> ThermalProperties | None:
        """The wall's thermal description (the support neither heats nor softens)."""
        return self.damper.thermal

    @property
    def limits(self) -> WallLimits | None:
        """The wall's limits (the support does not fail)."""
        return self.damper.limits

    def at_temperature(self, temperature: float, shift: ShiftLaw | None = None) -> SupportedDamper:
        """The assembly with its wall at ``temperature`` (degC; see :meth:`FDMKDamper.at_temperature`)."""
        return SupportedDamper(self.damper.at_temperature(temperature, shift), self.support_stiffness)

    def at_ambient(self, temperature: float) -> SupportedDamper:
        """The assembly with its wall starting at, and cooling towards, ``temperature`` (degC)."""
        return SupportedDamper(self.damper.at_ambient(temperature), self.support_stiffness)

    def property_factors(self, temperatures: ArrayLike, frequency: float) -> PropertyFactors:
        """Temperature factors of the assembly's K' and K'' at ``frequency`` (Hz) over ``temperatures`` (degC):
        :func:`vdw_frames.element.thermal.property_factors`."""
        return property_factors(self, temperatures, frequency)

    def resized(self, factor: float) -> SupportedDamper:
        """``factor`` walls' worth (> 0, -): the wall's area and the support's stiffness times ``factor``."""
        factor = positive("factor", factor)
        return SupportedDamper(self.damper.resized(factor),
                               scaled_value("support_stiffness", self.support_stiffness, factor))

    def scaled(self, factor: float) -> SupportedDamper:
        """The wall's moduli and viscosities times ``factor`` (:meth:`FDMKDamper.scaled`); the support unchanged."""
        return SupportedDamper(self.damper.scaled(factor), self.support_stiffness)

    # ------------------------------------------------------------------ frequency domain
    def stiffness_transfer(self, s: ArrayLike) -> np.ndarray:
        """K(s) = K_wall(s) k_s / (K_wall(s) + k_s) (N/mm) for complex s (rad/s)."""
        wall = self.damper.stiffness_transfer(s)
        stiffness = wall * self.support_stiffness / (wall + self.support_stiffness)
        require_finite("stiffness", stiffness)
        return stiffness

    def complex_stiffness(self, f: ArrayLike) -> np.ndarray:
        """K*(f) = K' + i K'' (N/mm) of the assembly at frequencies f (Hz)."""
        f = positive_frequencies("f", f)
        return self.stiffness_transfer(2j * np.pi * f)

    def story_stiffness(self, f: ArrayLike, drift_amplitude: float | None = None) -> np.ndarray:
        """magnification^2 K(i 2 pi f) (N/mm) of the assembly: what the story sees at f (Hz, >= 0);
        ``drift_amplitude`` (mm) is not used (the assembly is linear)."""
        return story_stiffness_of(self, f)

    def describe(self) -> str:
        """'FDMK wall ..., support k_s=...' for tables."""
        return f"FDMK wall {wall_parameters(self.damper)}, support k_s={describe_number(self.support_stiffness)}"

    def prony(self, f_min: float, f_max: float, tolerance: float = 0.01) -> PronySeries:
        """A generalized Maxwell model of the assembly (wall and support) over [``f_min``, ``f_max``] Hz;
        see :meth:`FDMKDamper.prony`."""
        return fit_prony(self, f_min, f_max, tolerance)

    # ------------------------------------------------------------------ time domain
    def kernel_constants(self) -> tuple[float, ...]:
        """The wall's kernel constants with the support's flexibility 1 / k_s (mm/N)."""
        return (*self.damper.kernel_constants()[:6], 1.0 / self.support_stiffness)

    def new_state(self, dt: float, method: str | Discretisation = DEFAULT_METHOD,
                  memory: str | FastMemory = DEFAULT_MEMORY) -> WallState:
        """A fresh trial/commit state on steps of ``dt`` s (displacement: the assembly's, mm)."""
        return WallState(self, dt, method=method, memory=memory)

    def force(self, displacement: ArrayLike, dt: float, method: str | Discretisation = DEFAULT_METHOD,
              memory: str | FastMemory = DEFAULT_MEMORY) -> np.ndarray:
        """Force history (N) for an assembly displacement history (mm) every ``dt`` s, from rest."""
        return driven_force(self, displacement, dt, method, memory, strain_range=self.strain_range)


WALL_TYPES = (FDMKDamper, SupportedDamper)
"""The wall assemblies the time-domain and frequency-domain code accepts."""
