"""vdw_frames: FDMK viscoelastic damping walls and shear buildings fitted with them.

Units throughout: N, mm, s, tonne; moduli MPa (N/mm^2), viscosities MPa*s^r, stiffness N/mm,
energy N*mm, frequency Hz.
"""

from .batch import BatchResult, run_batch
from .building import ShearBuilding
from .damper import DamperState, FDMKDamper
from .fast_memory import FastMemory
from .fractional import BDF2, DampedTwoStep, Discretisation, GrunwaldLetnikov, Trapezoidal
from .ground_motion import G, GroundMotion, read_at2, read_two_column, response_spectrum
from .plotting import plot_loops
from .simulation import EnergyHistory, SimulationResult, simulate
from .sine import SineTestResult, sine_test

__all__ = [
    "BDF2",
    "BatchResult",
    "DampedTwoStep",
    "DamperState",
    "Discretisation",
    "EnergyHistory",
    "FDMKDamper",
    "FastMemory",
    "G",
    "GroundMotion",
    "GrunwaldLetnikov",
    "ShearBuilding",
    "SimulationResult",
    "SineTestResult",
    "Trapezoidal",
    "plot_loops",
    "read_at2",
    "read_two_column",
    "response_spectrum",
    "run_batch",
    "simulate",
    "sine_test",
]
