"""The frame: shear buildings fitted with walls, their time-history integration and batches of analyses.

- :mod:`.building`: :class:`ShearBuilding` (masses, story springs, P-Delta, inherent damping, walls)
  and its exact frequency-domain response;
- :mod:`.hysteresis`: the story models :class:`Bilinear` and :class:`BoucWen` (trial/commit materials);
- :mod:`.simulation`: :func:`simulate`, Newmark's average acceleration with Newton-Raphson through the
  walls' and stories' trial/commit;
- :mod:`.strain_compatible`: the equivalent-linear iteration for strain-dependent walls
  (``simulate(..., strain_compatible=True)``, :class:`StrainCompatibleOptions`);
- :mod:`.batch`: :func:`run_batch`, many analyses on any ``concurrent.futures`` executor;
- :mod:`.ida`: :func:`incremental_dynamic_analysis` and its lognormal collapse fragility.

Units: N, mm, s, tonne.
"""

from .batch import BatchResult, run_batch, scale_factors_to_pga, scale_factors_to_spectral_acceleration
from .building import ShearBuilding
from .hysteresis import Bilinear, BoucWen, StoryState
from .ida import Fragility, IDAResult, incremental_dynamic_analysis
from .simulation import EnergyHistory, NewtonRaphson, SimulationResult, simulate
from .strain_compatible import StrainCompatibleOptions, energy_weighted_amplitude, strain_compatible_simulation

__all__ = ["BatchResult", "Bilinear", "BoucWen", "EnergyHistory", "Fragility", "IDAResult", "NewtonRaphson",
           "ShearBuilding", "incremental_dynamic_analysis",
           "SimulationResult", "StoryState", "StrainCompatibleOptions", "energy_weighted_amplitude", "run_batch",
           "scale_factors_to_pga", "scale_factors_to_spectral_acceleration", "simulate",
           "strain_compatible_simulation"]
