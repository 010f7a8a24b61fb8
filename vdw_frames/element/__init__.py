"""The FDMK element: the model (paper eqs. (3)-(5)), its time stepping and the sinusoidal test.

- :mod:`.damper`: :class:`FDMKDamper` (parameters, complex modulus and stiffness) and
  :class:`DamperState` (trial/commit stepping); :mod:`.supported`: :class:`SupportedDamper`, a wall
  in series with its support; :mod:`.bank`: :class:`WallBank`, many walls stepped together;
- :mod:`.kernel`: the one compiled step kernel every time-domain path calls;
- :mod:`.fractional`: convolution quadratures of D^r; :mod:`.fast_memory`: the O(1)-per-step memory;
- :mod:`.sine`: the sinusoidal test of one damper;
- :mod:`.prony`: :class:`PronySeries`, a generalized Maxwell model fitted to a wall over a band
  (``damper.prony(f_min, f_max)``), for programs that cannot host the exact wall;
- :mod:`.strain_dependent`: :class:`StrainDependentDamper`, FDMK parameters as functions of the
  strain amplitude.

Units: N, mm, s; moduli MPa, viscosities MPa*s^r.
"""

from .damper import DEFAULT_MEMORY, DamperState, FDMKDamper
from .fast_memory import FastMemory
from .fractional import BDF2, DEFAULT_METHOD, DampedTwoStep, Discretisation, GrunwaldLetnikov, Trapezoidal
from .bank import WallBank
from .prony import PronySeries
from .sine import SineTestResult, sine_test
from .strain_dependent import StrainDependentDamper
from .supported import WALL_TYPES, SupportedDamper

__all__ = ["BDF2", "DEFAULT_MEMORY", "DEFAULT_METHOD", "DampedTwoStep", "DamperState", "Discretisation",
           "FDMKDamper", "FastMemory", "GrunwaldLetnikov", "PronySeries", "SineTestResult",
           "StrainDependentDamper", "SupportedDamper", "Trapezoidal", "WALL_TYPES", "WallBank", "sine_test"]
