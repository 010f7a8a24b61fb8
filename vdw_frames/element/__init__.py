"""The FDMK element: the model (paper eqs. (3)-(5)), its time stepping and the sinusoidal test.

- :mod:`.wall`: the :class:`Wall` contract and the stiffness methods every wall derives from K*(f);
  :mod:`.material`: the trial/commit :class:`Material` contract (after OpenSees's ``UniaxialMaterial``);
- :mod:`.damper`: :class:`FDMKDamper` (parameters, complex modulus and stiffness) and
  :class:`WallState` (one wall's trial/commit stepping); :mod:`.supported`: :class:`SupportedDamper`,
  a wall in series with its support; :mod:`.bank`: :class:`WallBank`, many walls stepped together;
- :mod:`.kernel`: the one compiled step kernel every time-domain path calls;
- :mod:`.fractional`: convolution quadratures of D^r; :mod:`.fast_memory`: the O(1)-per-step memory;
- :mod:`.sine`: the sinusoidal test of one wall;
- :mod:`.prony`: :class:`PronySeries`, a generalized Maxwell model fitted to a wall over a band
  (``wall.prony(f_min, f_max)``), for programs that cannot host the exact wall;
- :mod:`.strain_dependent`: :class:`StrainDependentDamper`, FDMK parameters as functions of the
  strain amplitude (followed step by step in the time domain);
- :mod:`.device`: the :class:`Device` contract every damping device satisfies; :mod:`.devices`: the
  compiled trial/commit of the kinds beyond the walls and their registry; :mod:`.viscous`:
  :class:`FluidViscousDamper`; :mod:`.friction`: :class:`FrictionDamper`;
- :mod:`.thermal`: temperature -- shift laws (:class:`WLF`, :class:`Arrhenius`, :class:`LogLinear`),
  :class:`ThermalProperties`, self-heating; :mod:`.limits`: :class:`WallLimits`, walls that fail.

Units: N, mm, s; moduli MPa, viscosities MPa*s^r.
"""

from .bank import WallBank
from .damper import FDMKDamper, WallState
from .device import Device
from .devices import DeviceState, device_response
from .fast_memory import FastMemory
from .fractional import BDF2, DampedTwoStep, Discretisation, GrunwaldLetnikov, Trapezoidal
from .friction import FrictionDamper
from .limits import WallLimits
from .material import Material
from .prony import PronySeries
from .sine import SineTestResult, sine_test
from .strain_dependent import StrainDependentDamper
from .supported import SupportedDamper
from .thermal import ISD110_LOSS_PEAK, WLF, Arrhenius, LogLinear, ThermalProperties
from .viscous import FluidViscousDamper
from .wall import Wall

__all__ = ["BDF2", "ISD110_LOSS_PEAK", "WLF", "Arrhenius", "DampedTwoStep", "Device", "DeviceState", "Discretisation",
           "FDMKDamper", "FastMemory", "FluidViscousDamper", "FrictionDamper", "GrunwaldLetnikov", "LogLinear",
           "Material", "PronySeries", "SineTestResult", "StrainDependentDamper", "SupportedDamper",
           "ThermalProperties", "Trapezoidal", "Wall", "WallBank", "WallLimits", "WallState", "device_response",
           "sine_test"]
