"""The frame: shear buildings fitted with walls, their time-history integration and batches of analyses.

- :mod:`.building`: :class:`ShearBuilding` (masses, story springs, P-Delta, inherent damping, walls)
  and its exact frequency-domain response;
- :mod:`.hysteresis`: the story models :class:`Bilinear` and :class:`BoucWen` (trial/commit materials);
- :mod:`.simulation`: :func:`simulate`, Newmark's average acceleration with Newton-Raphson through the
  walls' and stories' trial/commit;
- :mod:`.batch`: :func:`run_batch`, many analyses on any ``concurrent.futures`` executor.

Units: N, mm, s, tonne.
"""

from .batch import BatchResult, run_batch, scale_factors_to_pga, scale_factors_to_spectral_acceleration
from .building import ShearBuilding
from .hysteresis import Bilinear, BoucWen, StoryState
from .simulation import EnergyHistory, NewtonRaphson, SimulationResult, simulate

__all__ = ["BatchResult", "Bilinear", "BoucWen", "EnergyHistory", "NewtonRaphson", "ShearBuilding",
           "SimulationResult", "StoryState", "run_batch", "scale_factors_to_pga",
           "scale_factors_to_spectral_acceleration", "simulate"]
