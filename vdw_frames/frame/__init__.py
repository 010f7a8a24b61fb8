"""The frame: shear buildings fitted with walls, their time-history integration and batches of analyses.

- :mod:`.building`: :class:`ShearBuilding` (masses, story springs, inherent damping, walls) and its
  exact frequency-domain response;
- :mod:`.simulation`: :func:`simulate`, Newmark's average acceleration with the walls' trial/commit;
- :mod:`.batch`: :func:`run_batch`, many analyses on any ``concurrent.futures`` executor.

Units: N, mm, s, tonne.
"""

from .batch import BatchResult, run_batch, scale_factors_to_pga, scale_factors_to_spectral_acceleration
from .building import ShearBuilding
from .simulation import EnergyHistory, SimulationResult, simulate

__all__ = ["BatchResult", "EnergyHistory", "ShearBuilding", "SimulationResult", "run_batch",
           "scale_factors_to_pga", "scale_factors_to_spectral_acceleration", "simulate"]
