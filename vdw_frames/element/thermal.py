"""Temperature: time-temperature superposition of the FDMK model, shift laws, and what a wall needs to heat.

Time-temperature superposition (thermorheologically simple material)
--------------------------------------------------------------------
A thermorheologically simple polymer at temperature T behaves as at the reference temperature T_ref
with its clock sped up by 1 / a_T: G*(omega, T) = G*(a_T(T) omega, T_ref), a_T(T_ref) = 1, a_T < 1 above
T_ref (softer, less viscous).  For the FDMK model of paper eqs. (3)-(5),

    G*(omega, T_ref) = G1 + eta1 (i omega)^r + G2 eta2 (i omega)^r / (G2 + eta2 (i omega)^r),

every frequency enters through (i omega)^r, and (i a_T omega)^r = a_T^r (i omega)^r, so

    G*(omega, T) = G1 + [eta1 a_T^r] (i omega)^r + G2 [eta2 a_T^r] (i omega)^r / (G2 + [eta2 a_T^r] (i omega)^r):

the wall at T is the same model with eta1 and eta2 multiplied by a_T(T)^r and G1, G2, r unchanged --
exactly, at every frequency (:meth:`~vdw_frames.FDMKDamper.at_temperature`).  The loss factor is not
preserved (a frequency shift moves the wall along its own curve), which is why temperature bounds need
separate factors for K' and K'' (:meth:`~vdw_frames.FDMKDamper.property_factors`).

Shift laws
----------
:class:`WLF` (Williams, Landel & Ferry 1955): log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref), undefined at
T <= T_ref - C2.  :class:`Arrhenius`: ln a_T = (E_a / R) (1 / T - 1 / T_ref), T in kelvin.  Each carries
the temperature range of the data it was fitted to; outside it every path -- the time domain's update and
the frequency domain's ``at_temperature``, ``complex_stiffness`` of a wall at rest there, ``property_factors``
and the property bounds -- evaluates the law at the nearest end of the range and warns (:func:`held_temperature`).
Temperatures are degC; below absolute zero or above :data:`MAX_SERVICE_TEMPERATURE` (200 degC) they are
refused (:func:`service_temperature`: a kelvin value typed as degC lands above it).  The paper (Xu, Li &
Shen 2016) gives no temperature data -- its Tables 1-3 are at 21.2 degC -- so the package ships no shift
law as the paper's; the examples use a published law for a viscoelastic damper polymer and name its source.

Self-heating: the dissipated energy, not the absorbed work
----------------------------------------------------------
A wall's layers heat by the energy they *dissipate*.  The work int sigma d(eps) is not it: within a cycle
stored energy comes back, and a temperature driven by the work would fall.  The dissipation of a
fractional element is not local in time; its diffusive representation makes it a sum of non-negative
terms.  For 0 < r < 1 and a history from rest,

    D^r x(t) = int_0^oo mu(xi) phi(xi, t) d xi,   d phi / dt = -xi phi + dx/dt,   mu(xi) = sin(r pi) / pi xi^(r - 1),

(the Laplace transform of the right side is s x(s) int mu(xi) / (s + xi) d xi = s^r x(s)): a springpot
eta D^r x is a continuum of Maxwell elements, spring eta mu(xi) d xi and relaxation rate xi.  The power
eta x' D^r x splits into d/dt [eta int mu phi^2 / 2 d xi] (stored) plus eta int mu xi phi^2 d xi >= 0
(dissipated).  The Kelvin branch's springpot has x = eps; the Maxwell branch's has x = eps_v =
eps - sigma2 / G2, the strain of its dashpot (sigma2 = G2 (eps - eps_v) = eta2 D^r eps_v).

Discretisation (:func:`diffusive_nodes`, :func:`diffusive_weights`): the trapezoidal rule in log xi on
nodes spaced ``1 / NODES_PER_DECADE`` decades apart from ``XI_LOW`` to ``XI_HIGH_STEPS / dt`` (c_k =
sin(r pi) / pi xi_k^r h), continued beyond both ends as geometric series: the modes above the last node
relax within a step and act as one dashpot (a unit dashpot at r = 1, where the springpot is one); those
below the first act as one spring (they store, never dissipate).
For a strain linear within each step, each node's state and its dissipation over the step are exact:
phi_(n+1) = e phi_n + g dx with z = xi dt, e = exp(-z), g = (1 - e) / z, and int xi phi^2 dt = (its work)
- (the change of its stored energy) = g phi_n dx + D dx^2 - (phi_(n+1)^2 - phi_n^2) / 2, D = (1 - g) / z
(:func:`node_coefficients`; a positive semi-definite form of (phi_n, dx), so the heat of every step is
>= 0 and an adiabatic wall never cools; summed over the nodes it takes two sums a node, sum c g phi_n and
sum c phi_(n+1)^2, the previous step's sum c phi_n^2 being kept).

With 1.5 nodes a decade (12 nodes at dt = 0.004 s, 11 to 13 from dt = 0.02 to 0.001 s) the representation
reproduces (i omega)^r within 3.5e-3 (relative) from 0.01 Hz to the Nyquist frequency, for r from 0.05 to 1
and dt from 0.001 to 0.02 s (the tests check six steps; a dense sweep gives 3.49e-3 at worst, near
0.015 Hz and r ~ 0.5).  That is the trapezoidal rule's ripple, periodic in log omega and at most 3.2e-3,
plus the tails: the modes below the first node taken as a spring are off by up to 1.5e-3 of s^r at
0.01 Hz (most at small r), those above the last taken as a dashpot by up to 9e-4 at the Nyquist frequency
(most at r ~ 0.9).  The wider range of 14 nodes, 1e-3 to 1000 / dt rad/s, gave 3.2e-3; 2 nodes a decade
on that range give 7e-4 with 18 nodes.
The heat per steady cycle equals the loop area of the convolution-quadrature force within the same error:
1.4e-3, 6e-4 and 2e-5 for r = 0.3, 0.6 and 1 at omega dt = 0.016 (the test's tolerance is 5e-3 of
pi K'' d0^2).

Units: temperature degC (kelvin only inside Arrhenius), activation energy J/mol, volumetric heat
capacity MPa/K (= J/(cm^3 K)), time s, heat N*mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, NamedTuple, Protocol, cast, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike

from .. import _warnings
from .._validation import finite_scalar, positive, show, text

ABSOLUTE_ZERO = -273.15
"""degC."""

MAX_SERVICE_TEMPERATURE = 200.0
"""degC: the highest temperature the package takes for a viscoelastic damper's layers, an initial or ambient
temperature, a shift law's reference or range, or a temperature limit.  Above it is no service temperature
of a viscoelastic polymer: the acrylic and rubber-like damper polymers soften into flow or decompose well
below it (the ISD-110 law the examples use is measured to 65.6 degC).  Its purpose is to catch kelvin typed
where degC is meant (294.15 for 21 degC): any plausible kelvin value lies above it.  This package's bound,
not a code's."""

THERMAL_DIFFUSIVITY = 0.1
"""mm^2/s (1e-7 m^2/s): the thermal diffusivity kappa the package takes for the viscoelastic layers, the order
of unfilled and filled polymers (about 0.08-0.15 mm^2/s; an assumption for the paper's material, which the
paper does not characterise).  Used by :func:`conduction_time`."""

MIN_HEAT_CAPACITY = 1e-3
"""MPa/K = J/(cm^3 K): the smallest volumetric heat capacity rho c :class:`ThermalProperties` takes, a
validation floor (this package's), not a model constant.  Air is about 1.2e-3 (at 300 K, rho = 1.16 kg/m^3
and c_p = 1.007 kJ/(kg K): Incropera and DeWitt, Fundamentals of Heat and Mass Transfer, Table A.4); every
solid, foams included, holds more (polymers 1.5-2.0, steel 3.5), so no layer lies below it; a rho c of
5e-324 made the temperatures inf and 1e-300 rises of 1e210 K."""

GAS_CONSTANT = 8.314462618
"""J/(mol K) (CODATA 2018)."""

NODES_PER_DECADE = 1.5
"""Nodes of the diffusive representation per decade of relaxation rate."""
XI_LOW = 3e-3
"""rad/s: the slowest node (periods up to ~2 000 s are represented; slower modes act as one spring: up to
1.5e-3 of s^r at 0.01 Hz, the band's low end; module docstring)."""
XI_HIGH_STEPS = 100.0
"""The fastest node is XI_HIGH_STEPS / dt rad/s: it relaxes within a step (exp(-100) ~ 4e-44), as the modes
beyond it, summed into the tail dashpot, do (their departure from a dashpot is up to 9e-4 of s^r at the
Nyquist frequency, most at r ~ 0.9; module docstring)."""


@runtime_checkable
class ShiftLaw(Protocol):
    """A time-temperature shift law: a_T(T) (-) for temperatures T in degC, a_T(reference) = 1."""

    reference: float
    valid: tuple[float, float]

    def log10_shift(self, temperature: ArrayLike) -> np.ndarray:
        """log10 a_T at ``temperature`` (degC), evaluated where the law is defined."""
        ...

    def kernel_row(self) -> tuple[float, float, float, float]:
        """(kind, slope 1/K, curvature 1/K, reference degC) for the compiled update: log10 a_T =
        -slope d / (1 + curvature d), d = T - reference (:func:`log10_shift`)."""
        ...


def _check_range(name: str, valid: object, reference: float, lowest: float) -> tuple[float, float]:
    if not isinstance(valid, (tuple, list)) or len(valid) != 2:
        raise ValueError(f"{name} must be two temperatures (low, high) in degC, got {show(valid)}")
    low, high = (finite_scalar(name, value) for value in valid)
    if not lowest < low <= reference <= high:
        raise ValueError(f"{name} must hold the reference temperature {reference:g} degC and lie above "
                         f"{lowest:g} degC, with low <= high; got {show(valid)}")
    service_temperature(f"{name} high end", high)
    return low, high


def service_temperature(name: str, value: object) -> float:
    """``value`` (degC) as a float if it can be a viscoelastic layer's temperature: finite, above absolute
    zero and at most :data:`MAX_SERVICE_TEMPERATURE`; a ValueError naming it (and, above the bound, the
    value less 273.15, in case kelvin was typed) otherwise."""
    temperature = finite_scalar(name, value)
    if temperature <= ABSOLUTE_ZERO:
        raise ValueError(f"{name} must be above absolute zero ({ABSOLUTE_ZERO} degC), got {show(value)}")
    if temperature > MAX_SERVICE_TEMPERATURE:
        raise ValueError(f"{name} {show(value)} degC is above {MAX_SERVICE_TEMPERATURE:g} degC, no service "
                         "temperature of a viscoelastic damper polymer; temperatures are in degC -- if this is "
                         f"kelvin, subtract 273.15 ({temperature - 273.15:.4g} degC)")
    return temperature


def held_temperature(law: WLF | Arrhenius | LogLinear, temperature: object, warn: bool = True) -> float:
    """The temperature (degC) at which the frequency domain evaluates ``law`` for a wall at ``temperature``:
    ``temperature`` inside the law's valid range, the range's nearer end outside it, with a warning (none
    with ``warn=False``) -- the rule of the time domain, whose update holds the law at the range's end too
    (kernel ``_shift_factor``).  ``temperature`` must be a service temperature (:func:`service_temperature`)."""
    value = service_temperature("temperature", temperature)
    low, high = law.valid
    held = min(max(value, low), high)
    if warn and held != value:
        _warnings.warn(f"temperature {value:g} degC is outside the shift law's range {low:g} ... {high:g} degC: "
                       f"the law is evaluated at {held:g} degC, the range's end (as the time domain does)",
                       UserWarning, stacklevel=3)
    return held


def shift_factor(law: WLF | Arrhenius | LogLinear, temperature: object, r: float, warn: bool = True) -> float:
    """a_T^r (-) of ``law`` at ``temperature`` (degC), held at the law's valid range (:func:`held_temperature`;
    ``warn=False``: without the warning, for callers that report it themselves)."""
    return float(10.0 ** (r * float(law.log10_shift(held_temperature(law, temperature, warn)))))


def conduction_time(thickness: float, diffusivity: float = THERMAL_DIFFUSIVITY) -> float:
    """h^2 / (pi^2 kappa) (s): the time constant of the slowest mode of heat conduction across a layer of
    ``thickness`` h (mm) whose faces are held at the steel plates' temperature, ``diffusivity`` kappa in mm^2/s
    (default :data:`THERMAL_DIFFUSIVITY`): the layer's excess temperature sin(pi x / h) decays as
    exp(-pi^2 kappa t / h^2).  A first value of :attr:`ThermalProperties.cooling_time`; it takes the plates
    as staying at ambient (they warm too, so the layer cools more slowly than this)."""
    return positive("thickness", thickness) ** 2 / (math.pi**2 * positive("diffusivity", diffusivity))


@dataclass(frozen=True)
class WLF:
    """The Williams-Landel-Ferry shift law log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref).

    ``C1`` (-, > 0: the wall softens as it heats) and ``C2`` (K, > 0), ``reference`` T_ref (degC), ``valid``
    (low, high) degC: the range of the data the constants were fitted to (it must hold T_ref and lie above
    T_ref - C2, where the law is undefined).  ``source``: where the constants come from (printed by the
    examples and reports).
    """

    C1: float
    C2: float
    reference: float
    valid: tuple[float, float]
    source: str = ""

    def __post_init__(self) -> None:
        if finite_scalar("C1", self.C1) <= 0.0:
            raise ValueError(f"C1 must be > 0 (with C1 <= 0 the wall would stiffen, its relaxation slow down, as "
                             f"it heats), got {show(self.C1)}")
        object.__setattr__(self, "C1", finite_scalar("C1", self.C1))
        object.__setattr__(self, "C2", positive("C2", self.C2))
        reference = service_temperature("reference", self.reference)
        object.__setattr__(self, "reference", reference)
        text("source", self.source)
        object.__setattr__(self, "valid", _check_range("valid", self.valid, reference,
                                                      max(ABSOLUTE_ZERO, reference - self.C2)))

    @property
    def lowest(self) -> float:
        """T_ref - C2 (degC): the law is undefined at and below it."""
        return self.reference - self.C2

    def log10_shift(self, temperature: ArrayLike) -> np.ndarray:
        """log10 a_T at ``temperature`` (degC, > T_ref - C2; a ValueError naming it otherwise)."""
        temperature = np.asarray(temperature, dtype=float)
        if not np.all(np.isfinite(temperature)) or np.any(temperature <= self.lowest):
            bad = temperature[~(np.isfinite(temperature) & (temperature > self.lowest))].flat[0]
            raise ValueError(f"temperature {show(bad)} degC is at or below T_ref - C2 = {self.lowest:g} degC, "
                             "where the WLF law is undefined")
        difference = temperature - self.reference
        return -self.C1 * difference / (self.C2 + difference)

    def kernel_row(self) -> tuple[float, float, float, float]:
        return (float(WLF_KIND), self.C1 / self.C2, 1.0 / self.C2, self.reference)


@dataclass(frozen=True)
class Arrhenius:
    """The Arrhenius shift law ln a_T = (E_a / R) (1 / T - 1 / T_ref), temperatures in kelvin inside.

    ``activation_energy`` E_a (J/mol, > 0), ``reference`` T_ref (degC), ``valid`` (low, high) degC, ``source``.
    """

    activation_energy: float
    reference: float
    valid: tuple[float, float]
    source: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "activation_energy", positive("activation_energy", self.activation_energy))
        reference = service_temperature("reference", self.reference)
        object.__setattr__(self, "reference", reference)
        text("source", self.source)
        object.__setattr__(self, "valid", _check_range("valid", self.valid, reference, ABSOLUTE_ZERO))

    def log10_shift(self, temperature: ArrayLike) -> np.ndarray:
        """log10 a_T at ``temperature`` (degC, above absolute zero)."""
        temperature = np.asarray(temperature, dtype=float)
        if not np.all(np.isfinite(temperature)) or np.any(temperature <= ABSOLUTE_ZERO):
            bad = temperature[~(np.isfinite(temperature) & (temperature > ABSOLUTE_ZERO))].flat[0]
            raise ValueError(f"temperature {show(bad)} degC is at or below absolute zero")
        kelvin = temperature - ABSOLUTE_ZERO
        return self.activation_energy / GAS_CONSTANT * (1.0 / kelvin - 1.0 / (self.reference - ABSOLUTE_ZERO)) \
            / math.log(10.0)

    def kernel_row(self) -> tuple[float, float, float, float]:
        kelvin = self.reference - ABSOLUTE_ZERO  # 1/T - 1/T_ref = -(d / T_ref^2) / (1 + d / T_ref)
        return (float(ARRHENIUS_KIND), self.activation_energy / GAS_CONSTANT / math.log(10.0) / kelvin**2, 1.0 / kelvin,
                self.reference)


@dataclass(frozen=True)
class LogLinear:
    """A shift law linear in log: log10 a_T = -(T - T_ref) / ``degrees_per_decade``: one decade of frequency
    per ``degrees_per_decade`` K (> 0) -- the limit of WLF for C2 >> T - T_ref, and what a material's loss-peak
    temperatures at several frequencies measure directly.

    ``reference`` T_ref (degC), ``valid`` (low, high) degC (it must hold T_ref), ``source``.
    """

    degrees_per_decade: float
    reference: float
    valid: tuple[float, float]
    source: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "degrees_per_decade", positive("degrees_per_decade", self.degrees_per_decade))
        reference = service_temperature("reference", self.reference)
        object.__setattr__(self, "reference", reference)
        text("source", self.source)
        object.__setattr__(self, "valid", _check_range("valid", self.valid, reference, ABSOLUTE_ZERO))

    def log10_shift(self, temperature: ArrayLike) -> np.ndarray:
        """log10 a_T at ``temperature`` (degC, above absolute zero: a ValueError naming it otherwise, as
        :class:`WLF` and :class:`Arrhenius` give)."""
        temperature = np.asarray(temperature, dtype=float)
        if not np.all(np.isfinite(temperature)) or np.any(temperature <= ABSOLUTE_ZERO):
            bad = temperature[~(np.isfinite(temperature) & (temperature > ABSOLUTE_ZERO))].flat[0]
            raise ValueError(f"temperature {show(bad)} degC is at or below absolute zero")
        return -(temperature - self.reference) / self.degrees_per_decade

    def kernel_row(self) -> tuple[float, float, float, float]:
        return (float(LOG_LINEAR_KIND), 1.0 / self.degrees_per_decade, 0.0, self.reference)


ISD110_LOSS_PEAK = LogLinear(
    degrees_per_decade=(65.6 - 26.7) / 2.0, reference=21.2, valid=(0.0, 70.0),
    source="fitted to the loss-peak temperatures of 3M ISD-110 (80, 115, 150 degF = 26.7, 46.1, 65.6 degC at "
           "10, 100, 1000 Hz) in Ver & Beranek, Noise and Vibration Control Engineering, 2nd ed. (Wiley 2006), "
           "Table 14.1, p. 598; measured 26.7-65.6 degC, extended to 0-70 degC at the same slope (an "
           "assumption), and applied to the paper's material, whose temperature data the paper does not give "
           "(a second assumption)")
"""The examples' shift law: one frequency decade per 19.45 K, the ISD-110 loss peak's own shift.  No
published WLF or Arrhenius constants of a structural damper polymer were within reach; this law is fitted
to published measurements, and its source says where it is an assumption."""

NO_SHIFT, WLF_KIND, ARRHENIUS_KIND, LOG_LINEAR_KIND = 0, 1, 2, 3


def log10_shift(slope: float, curvature: float, reference: float, temperature: float) -> float:
    """log10 a_T = -slope d / (1 + curvature d), d = temperature - reference (degC; slope and curvature 1/K), of a
    law's ``kernel_row``: the one form every law here takes (WLF: slope C1 / C2, curvature 1 / C2; Arrhenius:
    slope E_a / (R ln 10 T_ref^2), curvature 1 / T_ref, T_ref in kelvin; log-linear: no curvature).  The compiled
    update uses the same form, its exponent ln a_T^r with ln(10) r slope found once (kernel:
    thermal.shift_rate)."""
    difference = temperature - reference
    if curvature == 0.0:
        return -slope * difference
    return -slope * difference / (1.0 + curvature * difference)


SHIFT_LAWS = (WLF, Arrhenius, LogLinear)


@dataclass(frozen=True)
class ThermalProperties:
    """What a wall needs to change with temperature and to heat itself.

    ``shift``: its :class:`WLF`, :class:`Arrhenius` or :class:`LogLinear` law; the wall's parameters are those at
    ``shift.reference``.  ``heat_capacity`` rho c of the viscoelastic layers (MPa/K = J/(cm^3 K); polymers
    1.5-2.0; at least :data:`MIN_HEAT_CAPACITY` = 1e-3, about air's, a validation floor, not a model
    constant).  ``temperature`` (degC): the layers' temperature at rest and the ambient they cool towards;
    default ``shift.reference``.  ``cooling_time`` tau (s, > 0; default inf, adiabatic): the time
    constant of rho c V dT/dt = P - rho c V (T - T_ambient) / tau.

    Adiabatic is the default because the strong motion of most records (10-30 s) is shorter than the time a
    layer of thickness h needs to pass its heat to the steel plates, h^2 / (pi^2 kappa) with kappa ~ 1e-7
    m^2/s for polymers: ~25 s for 5 mm, ~100 s for 10 mm, ~400 s for 20 mm.  It bounds the temperature rise
    from above (the plates, whose heat capacity is comparable, would take part of the heat).  For long records
    or thin layers give ``cooling_time`` (the conduction time above is a fair first value:
    :func:`conduction_time`; 5.7 s for 2.37 mm layers).  Temperatures are service temperatures
    (:func:`service_temperature`: above absolute zero, at most 200 degC).
    """

    shift: WLF | Arrhenius | LogLinear
    heat_capacity: float
    temperature: float = cast(float, None)  # None: the shift law's reference (a float after checking)
    cooling_time: float = math.inf

    def __post_init__(self) -> None:
        if not isinstance(self.shift, SHIFT_LAWS):
            raise ValueError(f"shift must be a WLF, Arrhenius or LogLinear law, got {type(self.shift).__name__}")
        heat_capacity = positive("heat_capacity", self.heat_capacity)
        if heat_capacity < MIN_HEAT_CAPACITY:
            raise ValueError(f"heat_capacity {show(self.heat_capacity)} MPa/K = J/(cm^3 K) is below "
                             f"{MIN_HEAT_CAPACITY:g}, about air's rho c (1.2e-3): no damper layer holds so little heat "
                             "(polymers 1.5-2.0, every solid 100 times air's or more; a validation floor, not a "
                             "model constant)")
        object.__setattr__(self, "heat_capacity", heat_capacity)
        temperature = self.shift.reference if self.temperature is None else service_temperature("temperature",
                                                                                                self.temperature)
        if isinstance(self.shift, WLF) and temperature <= self.shift.lowest:
            raise ValueError(f"temperature {show(temperature)} degC is at or below T_ref - C2 = "
                             f"{self.shift.lowest:g} degC, where the WLF law is undefined")
        object.__setattr__(self, "temperature", temperature)
        if isinstance(self.cooling_time, (bool, np.bool_)) or np.ndim(self.cooling_time) != 0:  # one number
            raise ValueError(f"cooling_time must be a time in s, got {show(self.cooling_time)}")
        cooling = float(self.cooling_time) if self.cooling_time == math.inf else positive("cooling_time",
                                                                                          self.cooling_time)
        object.__setattr__(self, "cooling_time", cooling)

    def viscosity_factor(self, temperature: float, r: float, warn: bool = True) -> float:
        """a_T(temperature)^r (-): the factor on eta1 and eta2 at ``temperature`` (degC), the law held at its
        valid range's end beyond it, with a warning (:func:`shift_factor`; ``warn=False``: without it)."""
        return shift_factor(self.shift, temperature, r, warn)

    def at(self, temperature: float) -> ThermalProperties:
        """The same properties at rest at ``temperature`` (degC)."""
        return ThermalProperties(self.shift, self.heat_capacity, temperature, self.cooling_time)


class ThermalRow(NamedTuple):
    """A wall's thermal constants as the kernel takes them (the fields of the same names of the kernel's THERMAL
    group, :data:`vdw_frames.element.kernel.THERMAL_FIELDS`)."""

    law_kind: float  # the shift law's kind (0: none)
    law_slope: float  # 1/K
    law_curvature: float  # 1/K
    law_reference: float  # degC
    capacity: float  # rho c V, N*mm/K
    ambient: float  # degC
    decay: float  # exp(-dt / tau)
    gain: float  # (tau / dt)(1 - exp(-dt / tau)) / (rho c V), K per N*mm
    valid_low: float  # degC
    valid_high: float  # degC


def thermal_row(thermal: ThermalProperties | None, volume: float, dt: float) -> ThermalRow:
    """The kernel's thermal constants (:class:`ThermalRow`) of a wall with ``thermal`` (None: no temperature
    dependence) and ``volume`` mm^3 of viscoelastic layers, for steps of ``dt`` s."""
    if thermal is None:
        return ThermalRow(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -math.inf, math.inf)
    kind, slope, curvature, reference = thermal.shift.kernel_row()
    decay = math.exp(-dt / thermal.cooling_time)
    gain = 1.0 if thermal.cooling_time == math.inf else -math.expm1(-dt / thermal.cooling_time) \
        * thermal.cooling_time / dt
    capacity = thermal.heat_capacity * volume
    low, high = thermal.shift.valid
    return ThermalRow(float(kind), float(slope), float(curvature), float(reference), float(capacity),
                      float(thermal.temperature), decay, gain / capacity, float(low), float(high))


def diffusive_nodes(dt: float) -> np.ndarray:
    """Relaxation rates xi_k (rad/s) of the diffusive representation for steps of ``dt`` s: log-spaced,
    ``NODES_PER_DECADE`` a decade, from XI_LOW to XI_HIGH_STEPS / dt."""
    return _diffusive_nodes(positive("dt", dt)).copy()


@lru_cache(maxsize=16)
def _diffusive_nodes(dt: float) -> np.ndarray:
    """diffusive_nodes, kept per step (every analysis of a step builds the same nodes; callers get a copy)."""
    high = XI_HIGH_STEPS / dt
    decades = max(math.log10(high / XI_LOW), 0.0)
    count = math.ceil(decades * NODES_PER_DECADE) + 1
    return np.geomspace(XI_LOW, high, count) if count > 1 else np.array([XI_LOW])


def diffusive_weights(r: float, nodes: np.ndarray) -> tuple[np.ndarray, float, float]:
    """(c_k (s^-r), tail dashpot (s^(1-r)), tail spring (s^-r)) of D^r on ``nodes`` (rad/s, log-spaced).

    The trapezoidal rule in u = log xi on the infinite grid u_k = u_0 + k h (spectrally accurate: the
    integrand is analytic in a strip), the grid points beyond the last node summed as a geometric series in
    their asymptotic form (a dashpot, xi_k >> omega), those below the first likewise (a spring).  r = 1:
    no node weight, a unit dashpot (the limit of the same formulas)."""
    if r >= 1.0:
        return np.zeros(nodes.size), 1.0, 0.0
    density = math.sin(r * math.pi) / math.pi
    h = math.log(nodes[1] / nodes[0]) if nodes.size > 1 else math.log(10.0) / NODES_PER_DECADE
    weights = density * nodes**r * h
    above = math.exp((r - 1.0) * h)  # ratio of successive xi^(r-1) beyond the last node
    dashpot = density * h * nodes[-1] ** (r - 1.0) * above / (1.0 - above)
    below = math.exp(-r * h)  # ratio of successive xi^r below the first node
    spring = density * h * nodes[0] ** r * below / (1.0 - below)
    return weights, dashpot, spring


def node_coefficients(nodes: np.ndarray, dt: float) -> np.ndarray:
    """(nodes, 3): e, g, D of every node for a step of ``dt`` s (z = xi dt, e = exp(-z), g = (1 - e) / z,
    D = (1 - g) / z, a series below z = 0.05, where the closed form cancels).

    Over a step with the input rising linearly by dx, phi' = -xi phi + dx/dt gives phi_(n+1) = e phi_n + g dx,
    its work (dx/dt) int phi dt = g phi_n dx + D dx^2 and so its dissipation
    int xi phi^2 dt = g phi_n dx + D dx^2 - (phi_(n+1)^2 - phi_n^2) / 2.
    """
    z = np.asarray(nodes, dtype=float) * dt
    e = np.exp(-z)
    gain = np.where(z > 0.0, -np.expm1(-z) / np.where(z > 0.0, z, 1.0), 1.0)
    series = 0.5 - z / 6.0 + z**2 / 24.0 - z**3 / 120.0 + z**4 / 720.0 - z**5 / 5040.0
    closed = (1.0 - gain) / np.where(z > 0.0, z, 1.0)
    return np.ascontiguousarray(np.stack([e, gain, np.where(z < 0.05, series, closed)], axis=1))


@dataclass(frozen=True)
class PropertyFactors:
    """Temperature property-modification factors of a wall (ASCE 7-16 Sec. 18.2.4.5): at each ambient
    temperature, K' and K'' at ``frequency`` over their values for the parameters as given.

    ``temperatures`` (degC), ``storage`` and ``loss`` (-), one per temperature; ``frequency`` (Hz).  A
    temperature change shifts the wall along its own frequency curve, so K' and K'' change by different
    factors and the loss factor changes with them (a single ``wall.scaled(lambda)`` cannot represent it).
    """

    temperatures: np.ndarray
    storage: np.ndarray
    loss: np.ndarray
    frequency: float

    @property
    def loss_factor_ratio(self) -> np.ndarray:
        """(K''/K')(T) over (K''/K') as given: how much the loss factor changes (-)."""
        return self.loss / self.storage


def property_factors(wall: Any, temperatures: ArrayLike, frequency: float) -> PropertyFactors:
    """:class:`PropertyFactors` of ``wall`` (any wall with ``at_temperature`` and a thermal description)
    at ``frequency`` (Hz, > 0) over ``temperatures`` (degC, service temperatures: :func:`service_temperature`);
    outside the shift law's range the law is held at the range's end, with a warning (:func:`held_temperature`,
    as the time domain does)."""
    if wall.thermal is None:
        raise ValueError("property factors from temperature need a wall with a thermal description "
                         "(thermal=ThermalProperties(...))")
    values = np.atleast_1d(np.asarray(temperatures, dtype=float))
    if values.ndim != 1 or values.size == 0 or not np.all(np.isfinite(values)) or np.any(values <= ABSOLUTE_ZERO):
        raise ValueError(f"temperatures must be one or more finite temperatures above absolute zero (degC), "
                         f"got {show(temperatures)}")
    for value in values:
        service_temperature("temperature", value)
    frequency = positive("frequency", frequency)
    nominal = wall.at_temperature(wall.thermal.shift.reference).complex_stiffness(frequency)
    shifted = np.array([complex(wall.at_temperature(t).complex_stiffness(frequency)) for t in values])
    return PropertyFactors(values, shifted.real / nominal.real, shifted.imag / nominal.imag, frequency)
