"""The friction damper: elastic until it slips, then a constant slip force.

:class:`FrictionDamper` (slip force F_s, stiffness k, magnification) models a Pall-type or slotted-bolted
friction device: displacement-dependent and rate-independent, the elastic-perfectly-plastic law of
OpenSees's ``ElasticPP`` material (E = k, epsyP = F_s / k) or ``Steel01`` with b = 0.

Time stepping (compiled, :func:`friction_trial`): the return mapping of that law, exact for any step: the
trial force F_n + k (u - u_n), held at +-F_s while it slips; the tangent is k while stuck, 0 while slipping.

Energies (N*mm): the slip's heat over a step is the frame's trapezoidal work on the device,
(F_n + F)/2 (u_n+1 - u_n), less the change of the elastic energy F^2 / (2 k) it stores, which is
(F_n + F)/2 times the step's slip: exact at full slip (F_s times the slip), and off by half the step's
force change times its slip on the one step that starts to slip (the trapezoidal rule's own error there).

Equivalent linearisation (:meth:`FrictionDamper.complex_stiffness`) at a deformation amplitude u_0 above
the slip deformation u_y = F_s / k: the secant (effective) stiffness K_eff = F_s / u_0 and the loss
stiffness of the same energy per cycle, K'' = E / (pi u_0^2) with E = 4 F_s (u_0 - u_y), the area of the
rigid-plastic loop less the elastic part (FEMA 356, 2000, Sec. 9.3.3 (displacement-dependent devices:
effective stiffness) and eq. 9-36 (the effective damping W_D / (4 pi W_S))).  Below u_y it is elastic, k.

Units: force N, deformation mm, stiffness N/mm, frequency Hz.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import ClassVar, NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._jit import njit
from .._validation import finite_array, positive, scaled_value, show
from .device import (
    Kinematics,
    describe_number,
    device_amplitude,
    kinematics,
    magnification_factor,
    require_own_amplitude,
    story_share,
)


@dataclass(frozen=True)
class FrictionDamper:
    """A friction damper: elastic of ``stiffness`` k (N/mm) until the force reaches ``slip_force`` F_s (N),
    then slipping at F_s.  Both finite and > 0; ``magnification`` (-, > 0) as for every device
    (:mod:`vdw_frames.element.device`)."""

    slip_force: float
    stiffness: float
    magnification: float = 1.0
    kind: ClassVar[str] = "friction"

    def __post_init__(self) -> None:
        object.__setattr__(self, "slip_force", positive("slip_force", self.slip_force))
        object.__setattr__(self, "stiffness", positive("stiffness", self.stiffness))
        object.__setattr__(self, "magnification", magnification_factor(self.magnification))

    linear: ClassVar[bool] = False

    @property
    def slip_deformation(self) -> float:
        """u_y = F_s / k (mm): the deformation at which it starts to slip."""
        return self.slip_force / self.stiffness

    def describe(self) -> str:
        """'friction F_s=..., k=...' for tables."""
        geometry = f", f={describe_number(self.magnification)}" if self.magnification != 1.0 else ""
        return f"friction F_s={describe_number(self.slip_force)}, k={describe_number(self.stiffness)}{geometry}"

    def energy_per_cycle(self, amplitude: float) -> float:
        """4 F_s (u_0 - F_s / k) (N*mm): the loop area of one cycle of deformation amplitude u_0 (mm); 0 below
        the slip deformation."""
        amplitude = positive("amplitude", amplitude)
        energy = 4.0 * self.slip_force * max(amplitude - self.slip_deformation, 0.0)
        if not math.isfinite(energy):
            raise ValueError(f"the friction damper's energy per cycle at amplitude = {show(amplitude)} mm "
                             f"(slip_force = {show(self.slip_force)} N) exceeds the double-precision range")
        return energy

    def complex_stiffness(self, f: ArrayLike, amplitude: float | None = None) -> np.ndarray:
        """K_eff + i K'' (N/mm) at frequencies f (Hz, >= 0; rate-independent: the same at every f) and the
        device's deformation ``amplitude`` u_0 (mm): K_eff = F_s / u_0, K'' = 4 F_s (u_0 - u_y) / (pi u_0^2)
        above u_y = F_s / k (FEMA 356 Sec. 9.3.3, eq. 9-36); k below."""
        frequency = finite_array("f", f, ndim=None)
        if (frequency < 0.0).any():
            raise ValueError(f"f must be >= 0 Hz, got {show(frequency[frequency < 0.0].flat[0])}")
        u0 = require_own_amplitude(amplitude, "friction damper")
        if u0 <= self.slip_deformation:
            value = complex(self.stiffness)
        else:
            # K'' = 4 F_s (u0 - u_y) / (pi u0^2) as (F_s / u0) (4 / pi) (1 - u_y / u0): every factor bounded
            # (F_s / u0 < k), where u0^2 or the loop area would overflow for a huge amplitude
            secant = self.slip_force / u0
            value = complex(secant, secant * (4.0 / math.pi) * (1.0 - self.slip_deformation / u0))
        return np.full(frequency.shape, value)

    def story_stiffness(self, f: ArrayLike, drift_amplitude: float | None = None) -> np.ndarray:
        """magnification^2 K*(f) (N/mm) at the story drift amplitude ``drift_amplitude`` (mm)."""
        amplitude = device_amplitude(drift_amplitude, self.magnification, "friction damper")
        return story_share(self.magnification, self.complex_stiffness(f, amplitude), "friction damper")

    def scaled(self, factor: float) -> FrictionDamper:
        """The slip force times ``factor`` (> 0): the property-modification factors of the friction force
        (ASCE 7-16 Sec. 18.2.4.5); the stiffness kept."""
        factor = positive("factor", factor)
        return dataclasses.replace(self, slip_force=scaled_value("slip_force", self.slip_force, factor))

    def resized(self, factor: float) -> FrictionDamper:
        """``factor`` dampers in parallel (> 0): slip force and stiffness times ``factor``."""
        factor = positive("factor", factor)
        return dataclasses.replace(self, slip_force=scaled_value("slip_force", self.slip_force, factor),
                                   stiffness=scaled_value("stiffness", self.stiffness, factor))


# ---------------------------------------------------------------------------------------------- compiled
class FrictionStates(NamedTuple):
    """A kind's state group: R friction dampers of one analysis."""

    kinematics: Kinematics
    slip_force: np.ndarray  # (R,) N
    stiffness: np.ndarray  # (R,) N/mm


def friction_states(dampers: list[tuple[int, int, FrictionDamper]]) -> FrictionStates:
    """The compiled states of ``dampers`` ((story 0-based, history column, damper)) at rest."""
    count = len(dampers)
    return FrictionStates(
        kinematics=kinematics([s for s, _, _ in dampers], [c for _, c, _ in dampers],
                              [d.magnification for _, _, d in dampers]),
        slip_force=np.array([d.slip_force for _, _, d in dampers], dtype=float).reshape(count),
        stiffness=np.array([d.stiffness for _, _, d in dampers], dtype=float).reshape(count))


@njit(cache=True, inline="always")
def friction_trial(states, i, deformation, velocity):
    """Damper ``i`` at the trial ``deformation`` (mm): force (N), tangent (N/mm), heat and stored energy (N*mm)
    into the trial fields (the return mapping of an elastic-perfectly-plastic law)."""
    motion = states.kinematics
    slip, stiffness = states.slip_force[i], states.stiffness[i]
    previous = motion.force[i]
    force = previous + stiffness * (deformation - motion.deformation[i])
    tangent = stiffness
    if abs(force) > slip:
        force = math.copysign(slip, force)
        tangent = 0.0
    stored = 0.5 * force * force / stiffness
    work = 0.5 * (previous + force) * (deformation - motion.deformation[i])
    motion.trial_force[i], motion.trial_tangent[i] = force, tangent
    motion.trial_heat[i] = motion.heat[i] + work - (stored - motion.stored[i])
    motion.trial_stored[i] = stored


@njit(cache=True, inline="always")
def friction_commit(states, i):
    """Accept damper ``i``'s trial (its kinematics are committed by the caller)."""
