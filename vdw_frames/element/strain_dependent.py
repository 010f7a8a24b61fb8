"""A strain-amplitude-dependent FDMK wall: FDMK parameters as functions of the shear-strain amplitude.

The "5+4" wall's moduli change strongly with the strain amplitude of the test (the paper's Tables 1-3
at 225, 300 and 450 %).  A :class:`StrainDependentDamper` holds one FDMK parameter set (paper eqs.
(3)-(5)) at each of a few *node* amplitudes gamma_1 < ... < gamma_n and takes every parameter
(G1, G2, eta1, eta2, r) piecewise linear in log(gamma) between them:

    p(gamma) = p_k + (p_{k+1} - p_k) * log(gamma / gamma_k) / log(gamma_{k+1} / gamma_k),
    gamma_k <= gamma <= gamma_{k+1}.

Between two nodes every parameter is a convex combination of two valid values, so G1, G2, eta1,
eta2 >= 0 and 0 < r <= 1 hold at every amplitude of the range by construction; with them every term
of G' and G'' (see :mod:`vdw_frames.element.damper`) is non-negative: the wall is passive at every
(f, gamma).  Outside [gamma_1, gamma_n] (``strain_range``) nothing is known: the parameters are
clamped to the nearest end and a ``UserWarning`` names the amplitude reached.  The clamp is the rule below
the range too, not the family's trend: for the paper's sets that trend falls to G1 = 0 at 225 % (continued,
G1 < 0: an active wall) while the Payne effect stiffens a filled elastomer at small amplitudes; the time an
analysis spends below the range is reported (``SimulationResult.wall_time_below_range``; docs/theory.rst).

This is a model of *amplitude* dependence for steady harmonic cycles, the way the tests measured it.
In a time-history analysis (:func:`vdw_frames.simulate`) such a wall follows the amplitude of the envelope
of its own total strain at every committed step (a higher mode's ripple does not end a half-cycle: the Payne
effect is governed by the total strain amplitude), with one fractional order r for the whole wall (the
convolution weights depend on r: a family with different r per node is refused there;
:func:`vdw_frames.paper.strain_dependent` is the paper's sets with one common r); the coefficients at the
amplitude come from the same interpolation (:func:`vdw_frames.element.kernel.track_amplitude`,
:func:`vdw_frames.element.kernel.set_coefficients`).
``simulate(..., strain_compatible=True)`` instead runs the equivalent-linear iteration of
:mod:`vdw_frames.frame.strain_compatible`, which gives each wall one fixed parameter set per analysis.

Units: strain amplitude dimensionless (3.0 = 300 %), moduli MPa, viscosities MPa*s^r, area mm^2,
thickness mm, frequency Hz, stiffness N/mm.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import ClassVar, overload

import numpy as np
from numpy.typing import ArrayLike

from .. import _warnings
from .._validation import (
    finite_array,
    fractional_order,
    non_negative,
    positive,
    positive_frequencies,
    refuse_non_numbers,
    scaled_value,
    wall_geometry,
)
from .damper import DEFAULT_MEMORY, FDMKDamper, WallState, driven_force
from .device import describe_number, device_amplitude, magnification_factor
from .fast_memory import FastMemory
from .fractional import DEFAULT_METHOD, Discretisation
from .limits import WallLimits, check_temperature_limit
from .thermal import SHIFT_LAWS, PropertyFactors, ShiftLaw, ThermalProperties, held_temperature, property_factors

PARAMETERS = ("G1", "G2", "eta1", "eta2", "r")


def _strain_amplitudes(name: str, values: ArrayLike) -> np.ndarray:
    """Strain amplitudes (dimensionless, finite, >= 0), scalar or array."""
    refuse_non_numbers(name, values)
    array = finite_array(name, values, ndim=None)
    if (array < 0.0).any():
        raise ValueError(f"{name} must be >= 0 (an amplitude), got {array[array < 0.0].flat[0]!r}")
    return array


@dataclass(frozen=True)
class StrainDependentDamper:
    """An FDMK wall whose parameters depend on the shear-strain amplitude (see the module docstring).

    Parameters
    ----------
    strains : sequence of float
        Node strain amplitudes, dimensionless (3.0 = 300 %), > 0 and strictly increasing, at least two.
        The identified range is [strains[0], strains[-1]].
    G1, G2 : sequence of float
        Elastic moduli at the nodes, MPa (>= 0), one per node.
    eta1, eta2 : sequence of float
        Viscosities at the nodes, MPa*s^r (>= 0).
    r : sequence of float
        Fractional orders at the nodes, 0 < r <= 1.
    area : float
        Total shear area of the viscoelastic layers, mm^2.
    thickness : float
        Thickness of one viscoelastic layer, mm; strain = displacement / thickness.
    magnification : float
        The wall's deformation / the interstory drift (-, > 0; default 1), as for every device
        (:mod:`vdw_frames.element.device`): geometry, not material; :meth:`at` keeps it.

    Notes
    -----
    Every parameter is piecewise linear in log(strain) between the nodes.
    :meth:`constant` makes a wall whose parameters do not vary.
    """

    strains: tuple[float, ...]
    G1: tuple[float, ...]
    G2: tuple[float, ...]
    eta1: tuple[float, ...]
    eta2: tuple[float, ...]
    r: tuple[float, ...]
    area: float = 1.0e6
    thickness: float = 10.0
    thermal: ThermalProperties | None = None
    limits: WallLimits | None = None
    magnification: float = 1.0

    # Its parameters follow its own strain amplitude: nonlinear, stepped with its amplitude table.
    kind: ClassVar[str] = "wall"  # building files' type
    follows_amplitude: ClassVar[bool] = True
    linear: ClassVar[bool] = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "magnification", magnification_factor(self.magnification))
        refuse_non_numbers("strains", self.strains)
        strains = finite_array("strains", self.strains)
        if strains.size < 2:
            raise ValueError(f"strains must hold at least two node amplitudes, got {self.strains!r}")
        if (strains <= 0.0).any():
            raise ValueError(f"strains must be > 0 (they are interpolated in log strain), got {self.strains!r}")
        if (np.diff(strains) <= 0.0).any():
            raise ValueError(f"strains must be strictly increasing, got {self.strains!r}")
        object.__setattr__(self, "strains", tuple(strains.tolist()))
        for name in PARAMETERS:
            values = getattr(self, name)
            refuse_non_numbers(name, values)
            array = finite_array(name, values)
            if array.size != strains.size:
                raise ValueError(f"{name} has {array.size} values for {strains.size} strains")
            check = fractional_order if name == "r" else (lambda v, n=name: non_negative(n, v))
            object.__setattr__(self, name, tuple(check(v) for v in array.tolist()))
        area, thickness = wall_geometry(self.area, self.thickness)
        object.__setattr__(self, "area", area)
        object.__setattr__(self, "thickness", thickness)
        if self.thermal is not None and not isinstance(self.thermal, ThermalProperties):
            raise ValueError(f"thermal must be ThermalProperties (or None), got {type(self.thermal).__name__}")
        if self.limits is not None and not isinstance(self.limits, WallLimits):
            raise ValueError(f"limits must be WallLimits (or None), got {type(self.limits).__name__}")
        check_temperature_limit(self.limits, self.thermal)

    # ------------------------------------------------------------------ time domain (amplitude followed)
    @property
    def common_order(self) -> float:
        """The fractional order r shared by every node (-): what a time-domain analysis that follows the
        amplitude needs (the convolution weights depend on r, so within an analysis a wall's r is fixed).
        A ValueError when the nodes' r differ."""
        if len(set(self.r)) != 1:
            raise ValueError(f"a strain-dependent wall followed in the time domain needs one fractional order r "
                             f"at every amplitude, got r = {', '.join(f'{r:.4g}' for r in self.r)} at "
                             f"{', '.join(f'{100 * s:.4g} %' for s in self.strains)}; use a family identified with a "
                             "common r (paper.strain_dependent(), the default), or strain_compatible=True")
        return self.r[0]

    def kernel_constants(self) -> tuple[float, ...]:
        """The kernel's constants at the lowest node (where a wall at rest starts): G1, G2, eta1, eta2, area,
        thickness, support flexibility 0."""
        return (self.G1[0], self.G2[0], self.eta1[0], self.eta2[0], self.area, self.thickness, 0.0)

    def amplitude_table(self) -> np.ndarray:
        """(nodes, 5): log(strain), G1, G2 (MPa), eta1, eta2 (MPa*s^r) at every node, for the kernel."""
        return np.column_stack([np.log(self.strains), self.G1, self.G2, self.eta1, self.eta2])

    def new_state(self, dt: float, method: str | Discretisation = DEFAULT_METHOD,
                  memory: str | FastMemory = DEFAULT_MEMORY) -> WallState:
        """A fresh trial/commit state on steps of ``dt`` s, following its own amplitude (see
        :func:`vdw_frames.element.kernel.track_amplitude`); displacement mm, force N."""
        _ = self.common_order  # refuses a family without one r
        return WallState(self, dt, method=method, memory=memory)

    def force(self, displacement: ArrayLike, dt: float, method: str | Discretisation = DEFAULT_METHOD,
              memory: str | FastMemory = DEFAULT_MEMORY) -> np.ndarray:
        """Force history (N) for a displacement history (mm) every ``dt`` s from rest, the parameters following
        the wall's own strain amplitude step by step (:func:`vdw_frames.element.kernel.track_amplitude`)."""
        _ = self.common_order  # refuses a family without one r
        return driven_force(self, displacement, dt, method, memory)

    @classmethod
    def from_nodes(cls, nodes: Mapping[str, Sequence[float] | np.ndarray], area: float = 1.0e6,
                   thickness: float = 10.0, thermal: ThermalProperties | None = None,
                   limits: WallLimits | None = None, magnification: float = 1.0) -> StrainDependentDamper:
        """A wall from a mapping of node values {"strains", "G1", "G2", "eta1", "eta2", "r"} (units as for the
        constructor; e.g. :data:`vdw_frames.paper.strain_dependence.STRAIN_DEPENDENT_COMMON`)."""
        missing = {"strains", *PARAMETERS} - set(nodes)
        if missing:
            raise ValueError(f"nodes lacks {sorted(missing)}")
        return cls(strains=tuple(nodes["strains"]), G1=tuple(nodes["G1"]), G2=tuple(nodes["G2"]),
                   eta1=tuple(nodes["eta1"]), eta2=tuple(nodes["eta2"]), r=tuple(nodes["r"]), area=area,
                   thickness=thickness, thermal=thermal, limits=limits, magnification=magnification)

    @classmethod
    def constant(cls, damper: FDMKDamper, strain_range: tuple[float, float] | list[float]) -> StrainDependentDamper:
        """A wall with ``damper``'s parameters at every amplitude of ``strain_range`` (low, high), dimensionless."""
        if not isinstance(damper, FDMKDamper):
            raise ValueError(f"damper must be an FDMKDamper, got {type(damper).__name__}")
        if not isinstance(strain_range, (tuple, list)) or len(strain_range) != 2:
            raise ValueError(f"strain_range must be two amplitudes (low, high), got {strain_range!r}")
        nodes = {name: (getattr(damper, name),) * 2 for name in PARAMETERS}
        return cls.from_nodes({"strains": tuple(strain_range), **nodes}, damper.area, damper.thickness,
                              damper.thermal, damper.limits, damper.magnification)

    def scaled(self, factor: float) -> StrainDependentDamper:
        """This wall with its moduli and viscosities (G1, G2, eta1, eta2) times ``factor`` (> 0) at every node
        amplitude: the property-modification factors of ASCE 7-16 Sec. 18.2.4.5 (see :meth:`FDMKDamper.scaled`)."""
        factor = positive("factor", factor)

        def times(name: str, values: tuple[float, ...]) -> tuple[float, ...]:
            return tuple(scaled_value(name, v, factor) for v in values)

        return dataclasses.replace(self, G1=times("G1", self.G1), G2=times("G2", self.G2),
                                   eta1=times("eta1", self.eta1), eta2=times("eta2", self.eta2))

    def at_temperature(self, temperature: float, shift: ShiftLaw | None = None) -> StrainDependentDamper:
        """The isothermal wall at ``temperature`` (degC): at every node amplitude eta1 and eta2 times
        a_T(temperature)^r, G1, G2, r kept (:meth:`FDMKDamper.at_temperature`, node by node: the law held at
        its valid range's end beyond it, with a warning).  ``shift``: the law (default: this wall's
        ``thermal.shift``).  The result has no thermal description and no temperature limit."""
        law = shift if shift is not None else (self.thermal.shift if self.thermal is not None else None)
        if law is None:
            raise ValueError("at_temperature needs a shift law: give shift=..., or a wall with a thermal description")
        if not isinstance(law, SHIFT_LAWS):
            raise ValueError(f"shift must be a WLF, Arrhenius or LogLinear law, got {type(law).__name__}")
        log10_shift = float(law.log10_shift(held_temperature(law, temperature)))
        factors = [float(10.0 ** (r * log10_shift)) for r in self.r]

        def times(name: str, values: tuple[float, ...]) -> tuple[float, ...]:
            return tuple(scaled_value(name, v, f, "a_T^r") for v, f in zip(values, factors, strict=True))

        return dataclasses.replace(self, eta1=times("eta1", self.eta1), eta2=times("eta2", self.eta2), thermal=None,
                                   limits=self.limits.without_temperature() if self.limits is not None else None)

    def at_ambient(self, temperature: float) -> StrainDependentDamper:
        """This wall starting at, and cooling towards, ``temperature`` (degC), its heating kept; a ValueError
        without a thermal description."""
        if self.thermal is None:
            raise ValueError("at_ambient needs a wall with a thermal description (thermal=ThermalProperties(...))")
        return dataclasses.replace(self, thermal=self.thermal.at(temperature))

    def property_factors(self, temperatures: ArrayLike, frequency: float, strain: float) -> PropertyFactors:
        """Property-modification factors of K' and K'' (separately) at ``frequency`` (Hz) and amplitude
        ``strain`` (-) over ambient ``temperatures`` (degC): those of :meth:`at` ``(strain)``
        (:func:`vdw_frames.element.thermal.property_factors`)."""
        return property_factors(self.at(strain), temperatures, frequency)

    def resized(self, factor: float) -> StrainDependentDamper:
        """``factor`` walls' worth (> 0, -): the shear area times ``factor``; material and thickness kept."""
        factor = positive("factor", factor)
        return dataclasses.replace(self, area=scaled_value("area", self.area, factor))

    @property
    def strain_range(self) -> tuple[float, float]:
        """(lowest, highest) node amplitude, dimensionless: where the parameters were identified."""
        return self.strains[0], self.strains[-1]

    @property
    def centre_strain(self) -> float:
        """sqrt(lowest x highest) node amplitude, dimensionless: the centre, in logarithm, of
        :attr:`strain_range` (3.18 for the paper's 225-450 %), the one amplitude a frequency-domain analysis
        of the wall uses by default."""
        low, high = self.strain_range
        return math.sqrt(low * high)

    @property
    def stiffness_scale(self) -> float:
        """area / thickness (mm): converts a modulus in MPa to a stiffness in N/mm."""
        return self.area / self.thickness

    @overload
    def clamped(self, strain: float) -> float: ...

    @overload
    def clamped(self, strain: ArrayLike) -> float | np.ndarray: ...

    def clamped(self, strain: ArrayLike) -> float | np.ndarray:
        """``strain`` (dimensionless, scalar or array, >= 0) clamped into :attr:`strain_range`; no warning."""
        low, high = self.strain_range
        clamped = np.clip(_strain_amplitudes("strain", strain), low, high)
        return float(clamped) if clamped.ndim == 0 else clamped

    def parameters(self, strain: float) -> dict[str, float]:
        """{G1, G2, eta1, eta2, r} (MPa, MPa*s^r, -) at the amplitude ``strain`` (dimensionless).

        Outside :attr:`strain_range` the parameters of the nearest end, with a ``UserWarning``.
        """
        value = self._one_amplitude(strain)
        self._warn_outside(value)
        return self._parameters(float(value))

    def at(self, strain: float) -> FDMKDamper:
        """The :class:`FDMKDamper` for the amplitude ``strain`` (dimensionless; 3.0 = 300 %).

        Clamped to :attr:`strain_range` with a ``UserWarning`` naming the amplitude when outside it.
        The damper keeps this wall's area and thickness, and its ``strain_range`` is this wall's.
        """
        value = self._one_amplitude(strain)
        self._warn_outside(value)
        return self._damper(self._parameters(float(value)))

    def complex_modulus(self, f: ArrayLike, strain: ArrayLike) -> np.ndarray | complex:
        """G*(i 2 pi f) = G' + i G'' (MPa) at frequencies ``f`` (Hz, > 0) and amplitudes ``strain``.

        ``f`` and ``strain`` are scalars or arrays that broadcast together; amplitudes outside
        :attr:`strain_range` are clamped, with one ``UserWarning``.
        """
        f = positive_frequencies("f", f)
        strain = _strain_amplitudes("strain", strain)
        f, strain = np.broadcast_arrays(f, strain)
        self._warn_outside(strain)
        clamped = np.clip(strain, *self.strain_range)
        modulus = np.empty(f.shape, dtype=complex)
        for value in np.unique(clamped):
            where = clamped == value
            modulus[where] = self._damper(self._parameters(float(value))).complex_modulus(f[where])
        return modulus if modulus.ndim else complex(modulus)

    def complex_stiffness(self, f: ArrayLike, strain: ArrayLike) -> np.ndarray | complex:
        """K* = G* area / thickness (N/mm) at frequencies ``f`` (Hz) and amplitudes ``strain`` (see
        :meth:`complex_modulus`)."""
        return self.complex_modulus(f, strain) * self.stiffness_scale

    def story_stiffness(self, f: ArrayLike, drift_amplitude: float | None = None) -> np.ndarray:
        """magnification^2 K(i 2 pi f) (N/mm) at frequencies f (Hz, >= 0) of the wall at the strain amplitude
        of the story drift amplitude ``drift_amplitude`` (mm): magnification x drift / thickness, :meth:`at`
        that amplitude (clamped to the range with a warning).  A ValueError without an amplitude: its
        stiffness depends on it."""
        amplitude = device_amplitude(drift_amplitude, self.magnification, "strain-dependent wall")
        return self.at(amplitude / self.thickness).story_stiffness(f)

    def describe(self) -> str:
        """'strain-dependent FDMK wall (n nodes, 225-450 %), A=..., t=...' for tables."""
        low, high = self.strain_range
        geometry = f", f={describe_number(self.magnification)}" if self.magnification != 1.0 else ""
        return (f"strain-dependent FDMK wall ({len(self.strains)} nodes, {100 * low:.4g}-{100 * high:.4g} %), "
                f"A={describe_number(self.area)}, t={describe_number(self.thickness)}{geometry}")

    # ---------------------------------------------------------------------------------------- internals
    @staticmethod
    def _one_amplitude(strain: ArrayLike) -> np.ndarray:
        value = _strain_amplitudes("strain", strain)
        if value.ndim != 0:
            raise ValueError(f"strain must be one amplitude, got shape {value.shape}")
        return value

    def _parameters(self, strain: float) -> dict[str, float]:
        """Parameters at ``strain`` clamped to the range, interpolated linearly in log strain."""
        x = np.log(np.clip(strain, *self.strain_range))
        nodes = np.log(self.strains)
        return {name: float(np.interp(x, nodes, getattr(self, name))) for name in PARAMETERS}

    def _damper(self, parameters: dict[str, float]) -> FDMKDamper:
        return FDMKDamper(G1=parameters["G1"], G2=parameters["G2"], eta1=parameters["eta1"], eta2=parameters["eta2"],
                          r=parameters["r"], area=self.area, thickness=self.thickness, strain_range=self.strain_range,
                          thermal=self.thermal, limits=self.limits, magnification=self.magnification)

    def _warn_outside(self, strain: np.ndarray) -> None:
        low, high = self.strain_range
        outside = strain[(strain < low) | (strain > high)]
        if outside.size:
            reached = ", ".join(f"{100 * s:.4g} %" for s in np.unique(outside)[:5])
            more = f" (and {np.unique(outside).size - 5} more)" if np.unique(outside).size > 5 else ""
            _warnings.warn(f"strain amplitude {reached}{more} outside the identified range "
                           f"{100 * low:.4g}-{100 * high:.4g} %: the parameters of the nearest end are used",
                           UserWarning, stacklevel=3)
