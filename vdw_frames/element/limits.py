"""Limit states of a wall: rupture or debonding of its viscoelastic layers, their bond strength, their
temperature limit.

A wall carrying :class:`WallLimits` fails at the first committed step where its strain, shear stress or
temperature exceeds a limit: from the next step its force (and tangent) is ``residual`` times what the
intact wall would give, for the rest of the analysis.  The analysis goes on with the frame that remains;
the wall's stored energy at failure (less the residual share) is released and accounted
(:class:`vdw_frames.frame.results.EnergyHistory`), and the result names the wall, the time and the mode
(``wall_failed``, ``wall_failure_time``, ``wall_failure_mode``).

The paper (Xu, Li & Shen 2016) reports no failure up to its largest test strain, 450 %, and gives no
strength: the package ships no limit as the paper's.  Every limit is the user's, with its source.

Units: strain dimensionless (8.5 = 850 %), stress MPa, temperature degC.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from .._validation import finite_scalar, positive, show
from .thermal import ThermalProperties, service_temperature


@dataclass(frozen=True)
class WallLimits:
    """Limits of a wall (any subset, at least one; None: no limit of that kind).

    ``strain`` (-, > 0): the shear strain of rupture or debonding of the layers; ``stress`` (MPa, > 0): the
    shear stress (force / area) of the bond; ``temperature`` (degC, a service temperature: above absolute
    zero, at most 200 degC, :func:`~vdw_frames.element.thermal.service_temperature`): the material's
    temperature limit -- walls with a thermal description only (a wall without one never heats, so the limit
    could never be reached: the wall constructors refuse it, :func:`check_temperature_limit`); ``residual``
    (-, in [0, 1)): the share of its force a failed wall keeps (0: none).  ``source``: where the limits come from
    (printed by the examples and reports).
    """

    strain: float | None = None
    stress: float | None = None
    temperature: float | None = None
    residual: float = 0.0
    source: str = ""

    def __post_init__(self) -> None:
        for name in ("strain", "stress"):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, positive(name, value))
        if self.temperature is not None:
            object.__setattr__(self, "temperature", service_temperature("temperature limit", self.temperature))
        residual = finite_scalar("residual", self.residual)
        if not 0.0 <= residual < 1.0:
            raise ValueError(f"residual must lie in [0, 1) (the share of its force a failed wall keeps), got "
                             f"{show(self.residual)}")
        object.__setattr__(self, "residual", residual)
        if not isinstance(self.source, str):
            raise ValueError(f"source must be a string, got {show(self.source)}")
        if self.strain is None and self.stress is None and self.temperature is None:
            raise ValueError("limits need a strain, stress or temperature limit, got none (a wall without limits "
                             "takes limits=None)")

    def without_temperature(self) -> WallLimits | None:
        """These limits without the temperature limit (None when no strain or stress limit is left): for a wall
        taken isothermal, which does not heat."""
        if self.strain is None and self.stress is None:
            return None
        return dataclasses.replace(self, temperature=None)

    def kernel_row(self) -> tuple[float, float, float, float]:
        """(strain, stress MPa, temperature degC, residual) for the kernel; inf where there is no limit."""
        return (math.inf if self.strain is None else self.strain, math.inf if self.stress is None else self.stress,
                math.inf if self.temperature is None else self.temperature, self.residual)


def check_temperature_limit(limits: WallLimits | None, thermal: ThermalProperties | None) -> None:
    """A ValueError when ``limits`` has a temperature limit and the wall has no thermal description
    (``thermal`` None): such a wall never heats, so it could never reach the limit and would never fail."""
    if limits is not None and limits.temperature is not None and thermal is None:
        raise ValueError(f"limits.temperature = {limits.temperature:g} degC needs a wall with a thermal description "
                         "(thermal=ThermalProperties(...)): without one the wall never heats and could never reach "
                         "its temperature limit")
