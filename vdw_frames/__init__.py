"""vdw_frames: FDMK viscoelastic damping walls and shear buildings fitted with them.

Units throughout: N, mm, s, tonne; moduli MPa (N/mm^2), viscosities MPa*s^r, stiffness N/mm,
energy N*mm, frequency Hz.
"""

from .damper import DamperState, FDMKDamper
from .fractional import BDF2, Discretisation, GrunwaldLetnikov, Trapezoidal
from .plotting import plot_loops
from .sine import SineTestResult, sine_test

__all__ = [
    "BDF2",
    "DamperState",
    "Discretisation",
    "FDMKDamper",
    "GrunwaldLetnikov",
    "SineTestResult",
    "Trapezoidal",
    "plot_loops",
    "sine_test",
]
