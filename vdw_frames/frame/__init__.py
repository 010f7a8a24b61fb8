"""The frame: shear buildings fitted with walls, their analyses in time and frequency, batches of analyses.

- :mod:`.building`: :class:`ShearBuilding` (masses, story springs, P-Delta, inherent damping, walls)
  and its exact frequency-domain response;
- :mod:`.modal`: :func:`modal_analysis`, the complex modes of the linear building with its walls;
- :mod:`.hysteresis`: the story models :class:`Bilinear` and :class:`BoucWen` (trial/commit materials);
- :mod:`.simulation`: :func:`simulate`, the one entry to a time-history analysis, dispatching to
  :mod:`.time_history` (walls of fixed parameters; the compiled loop in :mod:`.integrator`, the results
  in :mod:`.results`) or :mod:`.strain_compatible` (the equivalent-linear iteration);
- :mod:`.batch`: :func:`run_batch`, many analyses on any ``concurrent.futures`` executor, and
  :func:`worker_pool`, the default pool (threads) kept for several calls;
- :mod:`.ida`: :func:`incremental_dynamic_analysis` and its lognormal collapse fragility.

Units: N, mm, s, tonne.
"""

from .batch import (
    BatchResult,
    run_batch,
    scale_factors_to_pga,
    scale_factors_to_spectral_acceleration,
    worker_pool,
)
from .building import ShearBuilding
from .hysteresis import Bilinear, BoucWen, StoryState
from .ida import Fragility, IDAResult, incremental_dynamic_analysis
from .integrator import NewtonRaphson
from .modal import ModalResult, modal_analysis
from .results import EnergyHistory, SimulationResult
from .simulation import simulate
from .strain_compatible import StrainCompatibleOptions, energy_weighted_amplitude

__all__ = ["BatchResult", "Bilinear", "BoucWen", "EnergyHistory", "Fragility", "IDAResult", "ModalResult",
           "NewtonRaphson", "ShearBuilding", "SimulationResult", "StoryState", "StrainCompatibleOptions",
           "energy_weighted_amplitude", "incremental_dynamic_analysis", "modal_analysis", "run_batch",
           "scale_factors_to_pga", "scale_factors_to_spectral_acceleration", "simulate", "worker_pool"]
