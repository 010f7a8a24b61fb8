"""The fractional-derivative Maxwell-Kelvin (FDMK) damper: parameters, frequency response, time stepping.

The model is the paper's eqs. (3)-(5) (Xu, Li & Shen 2016): a fractional Kelvin branch

    sigma1 = G1 eps + eta1 D^r eps                                   (3)

in parallel (same strain, stresses add, eq. (5)) with a fractional Maxwell branch

    sigma2 + (eta2 / G2) D^r sigma2 = eta2 D^r eps                   (4)

Laplace-transforming (3)-(5) from rest gives the complex modulus (s = i omega)

    G*(s) = G1 + eta1 s^r + G2 eta2 s^r / (G2 + eta2 s^r).

With a = omega^r, c = cos(r pi/2), q = sin(r pi/2) and D = G2^2 + 2 G2 eta2 a c + eta2^2 a^2:

    G'  = G1 + eta1 a c + G2 eta2 a (G2 c + eta2 a) / D
    G'' = eta1 a q + G2^2 eta2 a q / D

This is *not* the paper's printed (6b)-(11); see :mod:`vdw_frames.paper` for those and how they differ.

Units: moduli MPa, viscosities MPa*s^r, area mm^2, thickness mm, displacement mm, force N,
frequency Hz, stiffness N/mm, damping coefficient N*s/mm, time s.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from functools import cached_property
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike

from .. import _warnings
from .._validation import (
    finite_array,
    finite_complex_array,
    fractional_order,
    non_negative,
    positive,
    positive_frequencies,
    require_finite,
    scaled_value,
    show,
    wall_geometry,
)
from .bank import DEFAULT_MEMORY, MEMORY_STRATEGIES, WallBank, kernel_constants, memory_strategy
from .device import describe_number, magnification_factor
from .fast_memory import FastMemory
from .fractional import DEFAULT_METHOD, Discretisation, get_method
from .kernel import FAILURE_MODES
from .limits import WallLimits, check_temperature_limit
from .prony import PronySeries, fit_prony
from .thermal import SHIFT_LAWS, PropertyFactors, ShiftLaw, ThermalProperties, property_factors, shift_factor
from .wall import AMPLITUDE_OUTSIDE, PEAK_OUTSIDE, TEMPERATURE_OUTSIDE, SteppedWall, StiffnessMethods, Wall

__all__ = ["DEFAULT_MEMORY", "MEMORY_STRATEGIES", "FDMKDamper", "WallState", "driven_force"]


@dataclass(frozen=True)
class FDMKDamper(StiffnessMethods):
    """An FDMK viscoelastic damper (paper eqs. (3)-(5)) of shear area ``area`` and layer thickness ``thickness``.

    Parameters
    ----------
    G1, G2 : float
        Elastic moduli of the Kelvin and Maxwell branches, MPa (>= 0).
    eta1, eta2 : float
        Viscosities of the Abel dashpots, MPa*s^r (>= 0).
    r : float
        Fractional order, 0 < r <= 1 (r = 1: classical Kelvin + Maxwell).
    area : float
        Total shear area of the viscoelastic layers, mm^2 (the paper's A = 1e6 mm^2).
    thickness : float
        Thickness of one viscoelastic layer, mm (the paper's h = 10 mm); strain = displacement / thickness.
    strain_range : (float, float), optional
        Shear-strain amplitudes (dimensionless: 3.0 is 300 %) the parameters were identified for;
        :func:`vdw_frames.simulate` warns when a damper's peak strain leaves it.  Not part of the model.
    thermal : ThermalProperties, optional
        Temperature dependence and self-heating (:mod:`vdw_frames.element.thermal`): the parameters above
        are those at ``thermal.shift.reference``; the wall starts at ``thermal.temperature`` and heats by
        the energy it dissipates.  Its frequency response is that at ``thermal.temperature``.  None
        (default): the parameters hold at every temperature and the wall never heats.
    limits : WallLimits, optional
        Strain, stress and temperature at which the wall fails (:mod:`vdw_frames.element.limits`); None
        (default): it never fails.
    magnification : float
        The wall's deformation / the interstory drift (-, > 0; default 1): its geometry in the frame, as for
        every device (:mod:`vdw_frames.element.device`).  Not part of the material: the wall's own
        stiffness methods (``complex_stiffness``, ``stiffness_transfer``) are along the wall; the story sees
        magnification^2 times them (:meth:`story_stiffness`).
    """

    G1: float
    G2: float
    eta1: float
    eta2: float
    r: float
    area: float = 1.0e6
    thickness: float = 10.0
    strain_range: tuple[float, float] | None = field(default=None, compare=False)
    thermal: ThermalProperties | None = None
    limits: WallLimits | None = None
    magnification: float = 1.0

    # A wall of fixed parameters: linear viscoelastic (eqs. (3)-(5)) at a fixed temperature; no amplitude table.
    kind: ClassVar[str] = "wall"  # building files' type
    follows_amplitude: ClassVar[bool] = False
    linear: ClassVar[bool] = True

    def amplitude_table(self) -> np.ndarray:
        """The kernel's amplitude table, (0, 5): a wall of fixed parameters follows no amplitude."""
        return np.zeros((0, 5))

    def __post_init__(self) -> None:
        object.__setattr__(self, "magnification", magnification_factor(self.magnification))
        for name in ("G1", "G2", "eta1", "eta2"):
            object.__setattr__(self, name, non_negative(name, getattr(self, name)))
        object.__setattr__(self, "r", fractional_order(self.r))
        area, thickness = wall_geometry(self.area, self.thickness)
        object.__setattr__(self, "area", area)
        object.__setattr__(self, "thickness", thickness)
        if self.strain_range is not None:
            bounds = self.strain_range if isinstance(self.strain_range, (tuple, list)) else ()
            if len(bounds) != 2:
                raise ValueError(f"strain_range must be two numbers (low, high), got {show(self.strain_range)}")
            low, high = (non_negative("strain_range", value) for value in bounds)
            if low > high:
                raise ValueError(f"strain_range must have low <= high, got {show(self.strain_range)}")
            object.__setattr__(self, "strain_range", (low, high))
        if self.thermal is not None and not isinstance(self.thermal, ThermalProperties):
            raise ValueError(f"thermal must be ThermalProperties (or None), got {type(self.thermal).__name__}")
        if self.limits is not None and not isinstance(self.limits, WallLimits):
            raise ValueError(f"limits must be WallLimits (or None), got {type(self.limits).__name__}")
        check_temperature_limit(self.limits, self.thermal)

    # ------------------------------------------------------------------ temperature
    @cached_property
    def viscosities(self) -> tuple[float, float]:
        """(eta1, eta2) (MPa*s^r) at the wall's temperature at rest: times a_T^r with a thermal description
        (time-temperature superposition: :mod:`vdw_frames.element.thermal`), as given otherwise.  Kept once
        found (the wall is frozen): an analysis asks for it several times a wall."""
        if self.thermal is None:
            return self.eta1, self.eta2
        factor = self.thermal.viscosity_factor(self.thermal.temperature, self.r)  # held at the law's range
        return self.eta1 * factor, self.eta2 * factor

    def at_temperature(self, temperature: float, shift: ShiftLaw | None = None) -> FDMKDamper:
        """The isothermal wall at ``temperature`` (degC): eta1 and eta2 times a_T(temperature)^r, G1, G2, r
        kept -- exact time-temperature superposition for this model (:mod:`vdw_frames.element.thermal`).
        Outside the law's valid range the law is held at the range's end, with a warning, as the time domain
        does (:func:`~vdw_frames.element.thermal.held_temperature`); ``temperature`` must be a service
        temperature (above absolute zero, at most 200 degC).

        ``shift``: the law to use (default: this wall's ``thermal.shift``; one of them is needed).  The
        result has no thermal description: its parameters hold at every temperature, and a temperature limit
        (``limits.temperature``) is dropped with it (the isothermal wall does not heat)."""
        law = shift if shift is not None else (self.thermal.shift if self.thermal is not None else None)
        if law is None:
            raise ValueError("at_temperature needs a shift law: give shift=..., or a wall with a thermal description")
        if not isinstance(law, SHIFT_LAWS):
            raise ValueError(f"shift must be a WLF, Arrhenius or LogLinear law, got {type(law).__name__}")
        factor = shift_factor(law, temperature, self.r)
        return dataclasses.replace(self, eta1=scaled_value("eta1", self.eta1, factor, "a_T^r"),
                                   eta2=scaled_value("eta2", self.eta2, factor, "a_T^r"), thermal=None,
                                   limits=self.limits.without_temperature() if self.limits is not None else None)

    def at_ambient(self, temperature: float) -> FDMKDamper:
        """This wall starting at, and cooling towards, ``temperature`` (degC), its heating kept; a ValueError
        without a thermal description."""
        if self.thermal is None:
            raise ValueError("at_ambient needs a wall with a thermal description (thermal=ThermalProperties(...))")
        return dataclasses.replace(self, thermal=self.thermal.at(temperature))

    def property_factors(self, temperatures: ArrayLike, frequency: float) -> PropertyFactors:
        """Property-modification factors of K' and K'' (separately) at ``frequency`` (Hz) over ambient
        ``temperatures`` (degC), relative to the parameters as given (the shift law's reference): see
        :func:`vdw_frames.element.thermal.property_factors`."""
        return property_factors(self, temperatures, frequency)

    def resized(self, factor: float) -> FDMKDamper:
        """``factor`` walls' worth (> 0, -): the shear area times ``factor``; material and thickness kept."""
        factor = positive("factor", factor)
        return dataclasses.replace(self, area=scaled_value("area", self.area, factor))

    def scaled(self, factor: float) -> FDMKDamper:
        """This wall with its moduli and viscosities (G1, G2, eta1, eta2) times ``factor`` (> 0, -).

        The property-modification factors of ASCE 7-16 Sec. 18.2.4.5 (upper- and lower-bound damper
        properties, e.g. 1.2 and 0.8): K*(f) scales by ``factor`` at every frequency, the loss factor
        G''/G' does not change.  r, area, thickness and strain_range are kept.
        """
        factor = positive("factor", factor)
        return dataclasses.replace(self, G1=scaled_value("G1", self.G1, factor), G2=scaled_value("G2", self.G2, factor),
                                   eta1=scaled_value("eta1", self.eta1, factor),
                                   eta2=scaled_value("eta2", self.eta2, factor))

    # ------------------------------------------------------------------ frequency domain
    @property
    def stiffness_scale(self) -> float:
        """area / thickness (mm): converts a modulus in MPa to a stiffness in N/mm."""
        return self.area / self.thickness

    def transfer(self, s: ArrayLike) -> np.ndarray:
        """G*(s) = G1 + eta1 s^r + G2 eta2 s^r / (G2 + eta2 s^r) (MPa) for complex s (rad/s).

        The Laplace transform of eqs. (3)-(5); principal branch of s^r.  ``s`` must be finite; a
        result that overflows is a ValueError naming the s where it does.
        """
        s = finite_complex_array("s", s)
        return self._checked("G*(s)", self._transfer(s), s, "s", "rad/s")

    def _transfer(self, s: ArrayLike) -> np.ndarray:
        with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
            eta1, eta2 = self.viscosities
            s_r = np.asarray(s, dtype=complex) ** self.r
            modulus = self.G1 + eta1 * s_r
            if self.G2 > 0.0 and eta2 > 0.0:
                viscous = eta2 * s_r
                # G2 x / (G2 + x) written so that neither G2 x nor G2 + x overflows for large |x|.
                large = np.abs(viscous) > self.G2
                safe = np.where(large, viscous, 1.0)
                modulus = modulus + np.where(large, self.G2 / (1.0 + self.G2 / safe),
                                             self.G2 * viscous / (self.G2 + viscous))
        return modulus

    def _checked(self, name: str, values: np.ndarray, inputs: ArrayLike, label: str = "f",
                 unit: str = "Hz") -> np.ndarray:
        """``values`` if all finite, else a ValueError naming the first input where they are not."""
        if not np.all(np.isfinite(values)):
            bad = ~np.isfinite(np.asarray(values))
            where = np.broadcast_to(np.asarray(inputs), bad.shape)[bad].flat[0]
            raise ValueError(f"{name} overflowed (inf or NaN) at {label} = {show(where)} {unit} for G1 = {self.G1!r}, "
                             f"G2 = {self.G2!r}, eta1 = {self.eta1!r}, eta2 = {self.eta2!r}, r = {self.r!r}: "
                             f"the {'frequency' if label == 'f' else label} or the parameters are too large")
        return values

    def complex_modulus(self, f: ArrayLike) -> np.ndarray:
        """G*(i 2 pi f) = G' + i G'' in MPa for frequencies f in Hz (scalar or array, finite, > 0).

        ValueError naming the frequency where the result overflows (e.g. f = 1e308 Hz)."""
        f = positive_frequencies("f", f)
        with np.errstate(over="ignore"):
            s = 2j * np.pi * f
        return self._checked("G*(i 2 pi f)", self._transfer(s), f)

    def storage_modulus(self, f: ArrayLike) -> np.ndarray:
        """G' (MPa) at f (Hz)."""
        return self.complex_modulus(f).real

    def loss_modulus(self, f: ArrayLike) -> np.ndarray:
        """G'' (MPa) at f (Hz)."""
        return self.complex_modulus(f).imag

    def stiffness_transfer(self, s: ArrayLike) -> np.ndarray:
        """K(s) = G*(s) area / thickness (N/mm) for complex s (rad/s): the wall's Laplace-domain stiffness."""
        s = finite_complex_array("s", s)
        with np.errstate(over="ignore", invalid="ignore"):
            return self._checked("K(s)", self._transfer(s) * self.stiffness_scale, s, "s", "rad/s")

    def complex_stiffness(self, f: ArrayLike) -> np.ndarray:
        """K*(f) = K' + i K'' (N/mm) at frequencies f (Hz)."""
        f = positive_frequencies("f", f)
        with np.errstate(over="ignore", invalid="ignore"):
            return self._checked("K*(f)", self.complex_modulus(f) * self.stiffness_scale, f)

    def story_stiffness(self, f: ArrayLike, drift_amplitude: float | None = None) -> np.ndarray:
        """magnification^2 K(i 2 pi f) (N/mm): what the story sees at frequencies f (Hz, >= 0; 0 is the static
        stiffness G1 area / thickness).  ``drift_amplitude`` (mm) is accepted for the :class:`Device` protocol
        and not used: the wall is linear."""
        return story_stiffness_of(self, f)

    def describe(self) -> str:
        """'FDMK wall G1=..., G2=..., eta1=..., eta2=..., r=..., A=..., t=...' for tables."""
        return f"FDMK wall {wall_parameters(self)}"

    def prony(self, f_min: float, f_max: float, tolerance: float = 0.01) -> PronySeries:
        """A generalized Maxwell model (:class:`~vdw_frames.element.prony.PronySeries`) matching K*(f) within
        ``tolerance`` (relative, on |K*|) over [``f_min``, ``f_max``] Hz (at most 6 decades) with the fewest
        branches; passive.
        For programs that cannot host the exact wall; see :mod:`vdw_frames.element.prony`."""
        return fit_prony(self, f_min, f_max, tolerance)

    # ------------------------------------------------------------------ time domain
    def kernel_constants(self) -> tuple[float, ...]:
        """(G1, G2, eta1, eta2, area, thickness, support flexibility = 0): the kernel's constants of this wall."""
        return (self.G1, self.G2, self.eta1, self.eta2, self.area, self.thickness, 0.0)

    def new_state(self, dt: float, method: str | Discretisation = DEFAULT_METHOD,
                  memory: str | FastMemory = DEFAULT_MEMORY) -> WallState:
        """A fresh (at-rest) time-stepping state with step ``dt`` (s); see :class:`WallState`."""
        return WallState(self, dt, method=method, memory=memory)

    def force(self, displacement: ArrayLike, dt: float, method: str | Discretisation = DEFAULT_METHOD,
              memory: str | FastMemory = DEFAULT_MEMORY) -> np.ndarray:
        """Force history (N) for a displacement history (mm) sampled every ``dt`` s, starting from rest.

        ``displacement[n]`` is the displacement at t = n dt; the history before t = 0 is zero
        (Riemann-Liouville derivatives from rest).  ``method`` selects the discretisation of D^r
        (:mod:`vdw_frames.element.fractional`; default: the damped two-step convolution quadrature, second order).
        ``memory``: "fast" (default; O(1) work per step, within 3e-9 of "exact"; see
        :mod:`vdw_frames.element.fast_memory`), "exact" (the full history, O(n) at step n) or a
        :class:`~vdw_frames.element.fast_memory.FastMemory` with its own tolerance.  A ``UserWarning`` when the
        peak strain lies outside ``strain_range`` (or the wall heats past its shift law's range).
        """
        return driven_force(self, displacement, dt, method, memory, strain_range=self.strain_range)


def story_stiffness_of(wall: Wall, f: ArrayLike) -> np.ndarray:
    """magnification^2 K(i 2 pi f) (N/mm) of a wall of fixed parameters (an FDMKDamper or a SupportedDamper)
    at frequencies f (Hz, finite, >= 0)."""
    frequency = finite_array("f", f, ndim=None)
    if (frequency < 0.0).any():
        raise ValueError(f"f must be >= 0 Hz, got {show(frequency[frequency < 0.0].flat[0])}")
    with np.errstate(over="ignore"):
        s = 2j * np.pi * frequency
    return wall.magnification**2 * wall.stiffness_transfer(s)


def wall_parameters(wall: FDMKDamper) -> str:
    """'G1=..., G2=..., eta1=..., eta2=..., r=..., A=..., t=...' (and its magnification when not 1)."""
    text = ", ".join(f"{name}={describe_number(getattr(wall, name))}" for name in ("G1", "G2", "eta1", "eta2", "r"))
    geometry = f", f={describe_number(wall.magnification)}" if wall.magnification != 1.0 else ""
    return f"{text}, A={describe_number(wall.area)}, t={describe_number(wall.thickness)}{geometry}"


def driven_force(wall: SteppedWall, displacement: ArrayLike, dt: float, method: str | Discretisation = DEFAULT_METHOD,
                 memory: str | FastMemory = DEFAULT_MEMORY, *,
                 strain_range: tuple[float, float] | None = None) -> np.ndarray:
    """Force history (N) of a wall assembly for a displacement history (mm) from rest (see ``force``).  A heating
    wall whose temperature leaves its shift law's range is warned about, as :func:`~vdw_frames.simulate` does
    (the law is then evaluated at the nearest end of the range), and so is a wall following its amplitude that
    followed one above its identified strains, or never reached them (the nearest end's parameters are used),
    and a wall of fixed parameters identified for ``strain_range`` (-, low, high) whose peak strain (its own
    deformation / thickness) lies outside it."""
    displacement = finite_array("displacement", displacement)
    dt = positive("dt", dt)
    bank = WallBank((wall,), dt, displacement.size, get_method(method), memory)
    force, strain = bank.drive(displacement)
    require_finite("force", force)
    first = float(bank.state("outside")[0])
    if first >= 0.0:
        low, high = float(bank.state("valid_low")[0]), float(bank.state("valid_high")[0])
        _warnings.warn(f"{TEMPERATURE_OUTSIDE} from t = {first * dt:.4g} s: "
                       f"{float(bank.state('temperature')[0]):.1f} degC at the end; range {low:g} ... {high:g} degC",
                       UserWarning, stacklevel=3)
    if wall.follows_amplitude:
        low, high = np.exp(wall.amplitude_table()[[0, -1], 0])  # the identified strains the kernel follows
        above, peak = float(bank.state("above_range")[0]) * dt, float(bank.state("amplitude")[0])
        never = float(bank.state("below_range")[0]) >= displacement.size  # every step below: never reached
        if above > 0.0 or never:
            where = (f"above the range for {above:.3g} s" if above > 0.0 else
                     f"below the range throughout (its strain at most {100 * np.max(np.abs(strain)):.0f} %)")
            _warnings.warn(f"{AMPLITUDE_OUTSIDE} ({100 * low:.4g}-{100 * high:.4g} %; those of the nearest are used): "
                           f"{where} (followed {100 * peak:.0f} % at the end)", UserWarning, stacklevel=3)
    elif strain_range is not None:
        low, high = strain_range
        peak = float(np.max(np.abs(strain), initial=0.0))
        if not low <= peak <= high:
            _warnings.warn(f"{PEAK_OUTSIDE}{100 * peak:.0f} % "
                           f"(range {100 * low:.4g}-{100 * high:.4g} %)", UserWarning, stacklevel=3)
    return force


class WallState:
    """Time-stepping state of one wall, with OpenSees ``UniaxialMaterial``-like trial/commit semantics.

    ``force, tangent = state.trial(displacement)`` gives the force (N) at the next step for the given
    displacement (mm) and its derivative d(force)/d(displacement) (N/mm) without changing the memory;
    any number of trials may precede ``state.commit()``, which accepts the last trial and advances the
    memory by one step of ``dt`` seconds; ``revert_to_last_commit()`` discards the trial.  Stepping
    trial/commit reproduces :meth:`FDMKDamper.force`.  ``damper`` is an :class:`FDMKDamper` or a
    :class:`~vdw_frames.SupportedDamper`.  The first commit whose strain goes above the strains the wall's
    parameters were identified at, and the first whose temperature leaves its shift law's range, are said once
    each in a ``UserWarning``.  The exact memory grows as needed; the fast memory serves
    ``FastMemory.max_steps`` steps (2^20 by default).
    """

    _INITIAL_CAPACITY = 1024

    def __init__(self, damper: SteppedWall, dt: float, method: str | Discretisation = DEFAULT_METHOD,
                 memory: str | FastMemory = DEFAULT_MEMORY) -> None:
        kernel_constants(damper)  # refuses anything that is not a wall
        self.damper = damper
        self.dt = positive("dt", dt)
        self.method = get_method(method)
        self.memory = memory
        self._fast = memory_strategy(memory) is not None
        self._bank = WallBank((damper,), self.dt, 0 if self._fast else self._INITIAL_CAPACITY, self.method, memory)
        self._trial: float | None = None
        self.committed_displacement = 0.0
        self.committed_force = 0.0
        # The largest strain its parameters were identified at (-), said once when a commit goes above it.
        self._identified_high: float | None = None
        if damper.follows_amplitude:  # its amplitude nodes
            self._identified_high = float(np.exp(damper.amplitude_table()[-1, 0]))
        elif isinstance(damper, Wall) and damper.strain_range is not None:
            self._identified_high = float(damper.strain_range[1])
        self._said: set[str] = set()
        self._heats = damper.thermal is not None

    def __repr__(self) -> str:
        return f"WallState(damper={self.damper!r}, dt={self.dt!r}, steps={self.steps})"

    @property
    def steps(self) -> int:
        """Committed steps."""
        return self._bank.count

    @property
    def temperature(self) -> float:
        """Temperature of the wall's layers after the last commit (degC); NaN without a thermal description."""
        return float(self._bank.states.thermal.temperature[0])

    @property
    def heat(self) -> float:
        """Energy the wall has dissipated since rest (N*mm); 0 unless its heat is followed (a thermal
        description or limits)."""
        return float(self._bank.states.energy.heat[0])

    @property
    def amplitude(self) -> float:
        """The strain amplitude an amplitude-following wall follows after the last commit (-); 0 otherwise."""
        return float(self._bank.states.tracker.amplitude[0])

    @property
    def failure_step(self) -> int | None:
        """The commit (counted from 0, as the samples of :meth:`FDMKDamper.force`) at which the wall failed
        (a limit exceeded), None while intact; its force is the residual share from the next commit on."""
        step = int(self._bank.states.limits.failure_step[0])
        return None if step < 0 else step - 1

    @property
    def failure_mode(self) -> str:
        """How the wall failed ("strain", "stress", "temperature"), "" while intact."""
        return FAILURE_MODES[int(self._bank.states.limits.failure_mode[0])]

    def trial(self, displacement: float) -> tuple[float, float]:
        """(force in N, tangent in N/mm) at the next step for ``displacement`` (mm); memory untouched."""
        displacement = finite_array("displacement", [displacement])[0]
        force = float(self._bank.trial_forces([displacement], name="displacement")[0])
        self._trial = displacement
        return force, float(self._bank.tangent[0])

    def commit(self) -> None:
        """Accept the last trial and advance the memory one step."""
        if self._trial is None:
            raise ValueError("commit() needs a trial() first")
        force, strain = self._bank.commit([self._trial], name="displacement")
        self.committed_displacement, self.committed_force = self._trial, float(force[0])
        self._trial = None
        high, now = self._identified_high, abs(float(strain[0]))
        if high is not None and now > high and "strain" not in self._said:
            self._said.add("strain")
            _warnings.warn(f"WallState: wall strain {100 * now:.4g} % at commit {self.steps}, above the "
                           f"{100 * high:.4g} % its parameters were identified at (the model is extrapolated there; "
                           "said once)", UserWarning, stacklevel=2)
        if self._heats and "temperature" not in self._said and self._bank.states.thermal.outside[0] >= 0.0:
            self._said.add("temperature")
            _warnings.warn(f"WallState: wall temperature {self.temperature:.1f} degC at commit {self.steps}, outside "
                           "its shift law's range (the law is evaluated at the nearest end of the range; said once)",
                           UserWarning, stacklevel=2)

    def revert_to_last_commit(self) -> None:
        """Discard the pending trial."""
        self._trial = None
