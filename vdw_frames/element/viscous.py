"""The fluid viscous damper (FVD): F = C |v|^alpha sgn(v), alone or in series with a brace.

:class:`FluidViscousDamper` (C, alpha, stiffness K_b, magnification).  With a finite ``stiffness`` the
device is the Maxwell form of OpenSees's ``ViscousDamper`` material (K, Cd, alpha; Akcelyan, Lignos and
Hikino 2018, "Adaptive numerical method algorithms for nonlinear viscous and bilinear oil damper models
subjected to dynamic loading", Soil Dyn. Earthq. Eng. 113): the brace (and the oil column) of stiffness K_b
carries the force F = K_b (u - u_d) of the dashpot, whose deformation u_d moves at
v_d = sgn(F) (|F| / C)^(1/alpha).  Without a stiffness it is a pure dashpot, allowed only for alpha = 1
(a nonlinear dashpot alone has an infinite tangent at v = 0).

Time stepping (compiled, :func:`viscous_trial`): the implicit trapezoidal rule on the dashpot's
deformation, u_d,n+1 = u_d,n + dt/2 (v_d,n + v_d,n+1) -- the rule of Newmark's average acceleration,
which the frame uses for its own velocities, so a linear FVD (alpha = 1) in a linear frame is the
bilinear (Tustin) transform of the continuous system, exactly.  Each trial solves the scalar equation
F + K_b dt/2 g(F) = F_n + K_b (u - u_n) - K_b dt/2 g(F_n), g(F) = sgn(F)(|F|/C)^(1/alpha), strictly
increasing in F (one root), by Newton's method from the last trial's force, any iterate above the root
of K_b dt/2 g(F) = |target| moved there once (g is convex for F > 0 when alpha <= 1: from above the root
the iterates fall monotonically onto it), or in closed form where it is linear (alpha = 1) or quadratic
(alpha = 0.5, the common exponent: 13 times faster a trial than the iteration); the consistent tangent is
dF/du = K_b / (1 + K_b dt/2 g'(F)).  The rule is unconditionally stable; a brace much stiffer than the
oil over a step (K_b dt/2 g'(F) >> 1) makes the force of a sudden change alternate about the true one,
decaying as (1 - x)/(1 + x) a step with x = K_b dt/2 g'(F), as the trapezoidal rule does.  A pure dashpot
takes Newmark's velocity v = 2/dt (u - u_n) - v_n: F = C v, dF/du = 2 C / dt.

Energies (N*mm): the dashpot's heat over a step is the trapezoidal work on it, (F_n + F)/2 (u_d,n+1 - u_d,n),
the brace stores F^2 / (2 K_b); with the frame's trapezoidal work (F_n + F)/2 (u_n+1 - u_n) they balance
exactly.

Equivalent linearisation (:meth:`FluidViscousDamper.complex_stiffness`): a dashpot of the same energy per
cycle at amplitude u_0 and circular frequency omega, C_eq = lambda C (omega u_0)^(alpha - 1) / pi with
lambda = 2^(2 + alpha) Gamma^2(1 + alpha/2) / Gamma(2 + alpha) (FEMA 356, 2000, Sec. 9.3.4.3 and its
commentary; the energy per cycle of F = C |v|^alpha under u_0 sin(omega t) is lambda C omega^alpha
u_0^(1 + alpha), Soong and Dargush 1997, "Passive energy dissipation systems in structural engineering",
Sec. 6.2).  With a brace, the dashpot's own amplitude is solved for (:func:`dashpot_amplitude_ratio`), its
motion taken as a sine -- an approximation for alpha < 1: against the steady state of the Maxwell equation under
u_0 sin(omega t) (solved in tests/element/test_devices.py), pi K'' u_0^2 is within 1.5 % of the energy per cycle
for q = omega C_eq(u_0) / K_b <= 0.15 (alpha = 0.3 and 0.5, a stiff brace), 3-4 % high at q ~ 0.3, and at
alpha = 0.3 11 % high at q = 0.66 and 17 % low at q = 2.2 (measured); the stiffness K' of a stiff brace's damper
is low by 20-50 % there, a few per cent of |K*|.

Units: force N, deformation mm, velocity mm/s, C in N (s/mm)^alpha, stiffness N/mm, frequency Hz.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import ClassVar, NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._jit import njit
from .._validation import finite_array, finite_scalar, positive, scaled_value, show
from .device import (
    Kinematics,
    describe_number,
    device_amplitude,
    kinematics,
    magnification_factor,
    require_own_amplitude,
    story_share,
)


def energy_factor(alpha: float) -> float:
    """lambda(alpha) = 2^(2 + alpha) Gamma^2(1 + alpha/2) / Gamma(2 + alpha) (-): the energy per cycle of
    F = C |v|^alpha under u_0 sin(omega t) is lambda C omega^alpha u_0^(1 + alpha) (FEMA 356 Sec. 9.3.4.3
    commentary); lambda(1) = pi."""
    return 2.0 ** (2.0 + alpha) * math.gamma(1.0 + alpha / 2.0) ** 2 / math.gamma(2.0 + alpha)


@dataclass(frozen=True)
class FluidViscousDamper:
    """A fluid viscous damper: F = C |v|^alpha sgn(v) (N), v the dashpot's velocity (mm/s).

    Parameters
    ----------
    C : float
        Damping coefficient, N (s/mm)^alpha, finite and > 0.
    alpha : float
        Velocity exponent, 0 < alpha <= 1 (0.3-1 in practice; 1: a linear dashpot).
    stiffness : float, optional
        K_b (N/mm), the brace and oil column in series with the dashpot (OpenSees's ``ViscousDamper`` K).
        None: a pure dashpot, allowed only for alpha = 1.
    magnification : float
        Device deformation / story drift (-), > 0: 1 for a chevron, cos(theta) for a diagonal
        (:mod:`vdw_frames.element.device`).
    """

    C: float
    alpha: float
    stiffness: float | None = None
    magnification: float = 1.0
    kind: ClassVar[str] = "fluid_viscous"

    def __post_init__(self) -> None:
        object.__setattr__(self, "C", positive("C", self.C))
        alpha = finite_scalar("alpha", self.alpha)
        if not 0.0 < alpha <= 1.0:
            raise ValueError(f"alpha must be in (0, 1], got {show(self.alpha)}")
        object.__setattr__(self, "alpha", alpha)
        if self.stiffness is None:
            if alpha != 1.0:
                raise ValueError(f"a nonlinear FluidViscousDamper (alpha = {show(alpha)} < 1) needs a stiffness "
                                 "(K_b, N/mm, the brace in series): a nonlinear dashpot alone has an infinite "
                                 "tangent at zero velocity")
        else:
            object.__setattr__(self, "stiffness", positive("stiffness", self.stiffness))
        object.__setattr__(self, "magnification", magnification_factor(self.magnification))

    @property
    def linear(self) -> bool:
        """Whether its force is linear in its motion (alpha = 1)."""
        return self.alpha == 1.0

    def describe(self) -> str:
        """'FVD C=..., alpha=..., K_b=...' for tables."""
        brace = f", K_b={describe_number(self.stiffness)}" if self.stiffness is not None else ""
        geometry = f", f={describe_number(self.magnification)}" if self.magnification != 1.0 else ""
        return f"FVD C={describe_number(self.C)}, alpha={describe_number(self.alpha)}{brace}{geometry}"

    def energy_per_cycle(self, amplitude: float, frequency: float) -> float:
        """lambda C omega^alpha u_0^(1 + alpha) (N*mm): the dashpot's energy per cycle of a steady sine of
        ``amplitude`` u_0 (mm) across the dashpot at ``frequency`` (Hz) (FEMA 356 Sec. 9.3.4.3 commentary)."""
        amplitude = positive("amplitude", amplitude)
        omega = 2.0 * math.pi * positive("frequency", frequency)
        try:  # a Python float's ** raises OverflowError rather than giving inf
            energy = energy_factor(self.alpha) * self.C * omega**self.alpha * amplitude ** (1.0 + self.alpha)
        except OverflowError:
            energy = math.inf
        if not math.isfinite(energy):
            raise ValueError(f"the FVD's energy per cycle at amplitude = {show(amplitude)} mm and frequency = "
                             f"{show(frequency)} Hz (C = {show(self.C)}) exceeds the double-precision range")
        return energy

    def equivalent_coefficient(self, frequency: ArrayLike, amplitude: float) -> np.ndarray:
        """C_eq = lambda C (omega u_0)^(alpha - 1) / pi (N*s/mm) of the dashpot at its own amplitude u_0 (mm)
        and ``frequency`` (Hz, > 0): the linear dashpot of the same energy per cycle."""
        given = finite_array("frequency", frequency, ndim=None)
        if (given <= 0.0).any():
            raise ValueError(f"frequency must be > 0 Hz for an equivalent coefficient, got "
                             f"{show(given[given <= 0.0].flat[0])}")
        with np.errstate(over="ignore"):
            omega = 2.0 * math.pi * given
        amplitude = positive("amplitude", amplitude)
        with np.errstate(over="ignore", divide="ignore"):
            coefficient = energy_factor(self.alpha) * self.C * (omega * amplitude) ** (self.alpha - 1.0) / math.pi
        if not np.isfinite(coefficient).all():
            where = given[~np.isfinite(coefficient)].flat[0] if given.ndim else float(given)
            raise ValueError(f"the FVD's equivalent coefficient overflowed (inf) at frequency = {show(where)} Hz and "
                             f"amplitude = {show(amplitude)} mm (C = {show(self.C)}, alpha = {show(self.alpha)})")
        return coefficient

    def complex_stiffness(self, f: ArrayLike, amplitude: float | None = None) -> np.ndarray:
        """K*(f) (N/mm) along the device at frequencies f (Hz, >= 0): exact for alpha = 1 (i omega C, in series
        with K_b), else the equivalent linear one at the device's deformation ``amplitude`` (mm): the dashpot
        of :meth:`equivalent_coefficient` at the dashpot's own amplitude (with a brace,
        :func:`dashpot_amplitude_ratio` of the device's)."""
        frequency = finite_array("f", f, ndim=None)
        if (frequency < 0.0).any():
            raise ValueError(f"f must be >= 0 Hz, got {show(frequency[frequency < 0.0].flat[0])}")
        with np.errstate(over="ignore"):
            omega = 2.0 * math.pi * frequency
        u0 = None if self.linear else require_own_amplitude(amplitude, "nonlinear FVD")
        # omega C_eq (N/mm); inf where it overflows (the brace then carries the whole motion: K* -> K_b)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            if u0 is None:
                loss = omega * self.C
            else:
                # omega C_eq at the device's amplitude, then at the dashpot's (x u0): omega C_eq ~ x^(alpha - 1)
                loss = energy_factor(self.alpha) * self.C * omega**self.alpha * u0 ** (self.alpha - 1.0) / math.pi
                if self.stiffness is not None:
                    ratio = dashpot_amplitude_ratio(loss / self.stiffness, self.alpha)
                    loss = loss * ratio ** (self.alpha - 1.0)
            loss = np.where(omega == 0.0, 0.0, loss)  # no rate, no force: 0 even where C (omega u0)^alpha overflows
            if self.stiffness is None:
                value = loss * 1j
            else:
                # K_b i q / (1 + i q), q = omega C_eq / K_b; for q > 1 as K_b / (1 - i / q): finite for any q
                q = loss / self.stiffness
                large = q > 1.0
                value = np.where(large, self.stiffness / (1.0 - 1j / np.where(large, q, 1.0)),
                                 self.stiffness * 1j * q / (1.0 + 1j * q))
        value = np.asarray(value, dtype=complex)
        if not np.isfinite(value).all():
            where = frequency[~np.isfinite(value)].flat[0] if frequency.ndim else float(frequency)
            raise ValueError(f"the FVD's K*(f) overflowed (inf) at f = {show(where)} Hz (C = {show(self.C)}, alpha = "
                             f"{show(self.alpha)}, no brace): a pure dashpot's force grows without bound with f")
        return value

    def story_stiffness(self, f: ArrayLike, drift_amplitude: float | None = None) -> np.ndarray:
        """magnification^2 K*(f) (N/mm): what the story sees at f (Hz); a nonlinear damper's at the story
        drift amplitude ``drift_amplitude`` (mm: the device's is magnification x drift)."""
        amplitude = None
        if not self.linear:
            amplitude = device_amplitude(drift_amplitude, self.magnification, "nonlinear FVD")
        return story_share(self.magnification, self.complex_stiffness(f, amplitude), "FVD")

    def scaled(self, factor: float) -> FluidViscousDamper:
        """C times ``factor`` (> 0): the property-modification factors of the damping constant (ASCE 7-16
        Sec. 18.2.4.5 applies them to the device's force-velocity properties); alpha, K_b kept."""
        factor = positive("factor", factor)
        return dataclasses.replace(self, C=scaled_value("C", self.C, factor))

    def resized(self, factor: float) -> FluidViscousDamper:
        """``factor`` dampers in parallel (> 0): C and K_b times ``factor``."""
        factor = positive("factor", factor)
        stiffness = scaled_value("stiffness", self.stiffness, factor) if self.stiffness is not None else None
        return dataclasses.replace(self, C=scaled_value("C", self.C, factor), stiffness=stiffness)


def dashpot_amplitude_ratio(loss_ratio: ArrayLike, alpha: float) -> np.ndarray:
    """x = u_d0 / u_0 (-): the dashpot's share of the amplitude of a damper in series with a brace, where
    ``loss_ratio`` q = omega C_eq(u_0) / K_b is that of a dashpot at the whole amplitude.  The dashpot's
    force is K_b times the brace's deformation, so |u_d0| = u_0 / |1 + i omega C_eq(x u_0) / K_b| with
    C_eq(x u_0) = C_eq(u_0) x^(alpha - 1): x^2 + q^2 x^(2 alpha) = 1, increasing in x (one root in (0, 1]),
    solved by bisection to 1e-15."""
    q = np.asarray(loss_ratio, dtype=float)
    low, high = np.zeros(q.shape), np.ones(q.shape)
    for _ in range(60):
        middle = 0.5 * (low + high)
        with np.errstate(over="ignore"):  # a q^2 x^(2 alpha) that overflows is above 1 all the same
            above = middle**2 + q**2 * middle ** (2.0 * alpha) > 1.0
        high = np.where(above, middle, high)
        low = np.where(above, low, middle)
    return 0.5 * (low + high)


# ---------------------------------------------------------------------------------------------- compiled
class ViscousStates(NamedTuple):
    """A kind's state group: V fluid viscous dampers of one analysis."""

    kinematics: Kinematics
    coefficient: np.ndarray  # (V,) C, N (s/mm)^alpha
    exponent: np.ndarray  # (V,) alpha
    flexibility: np.ndarray  # (V,) 1/K_b, mm/N (0: a pure dashpot)
    dashpot_velocity: np.ndarray  # (V,) v_d, mm/s, committed
    trial_dashpot_velocity: np.ndarray  # (V,) mm/s
    dt: float  # s


def viscous_states(dampers: list[tuple[int, int, FluidViscousDamper]], dt: float) -> ViscousStates:
    """The compiled states of ``dampers`` ((story 0-based, history column, damper)) at rest, step ``dt`` s."""
    count = len(dampers)
    return ViscousStates(
        kinematics=kinematics([s for s, _, _ in dampers], [c for _, c, _ in dampers],
                              [d.magnification for _, _, d in dampers]),
        coefficient=np.array([d.C for _, _, d in dampers], dtype=float).reshape(count),
        exponent=np.array([d.alpha for _, _, d in dampers], dtype=float).reshape(count),
        flexibility=np.array([1.0 / d.stiffness if d.stiffness is not None else 0.0 for _, _, d in dampers],
                             dtype=float).reshape(count),
        dashpot_velocity=np.zeros(count), trial_dashpot_velocity=np.zeros(count), dt=float(dt))


@njit(cache=True, inline="always")
def _dashpot_velocity(force, coefficient, exponent):
    """g(F) = sgn(F) (|F| / C)^(1/alpha) (mm/s) and its derivative g'(F) (mm/s/N)."""
    if force == 0.0:
        return 0.0, (1.0 / coefficient if exponent == 1.0 else 0.0)
    ratio = abs(force) / coefficient
    speed = ratio ** (1.0 / exponent)
    return math.copysign(speed, force), speed / (exponent * abs(force))


@njit(cache=True, inline="always")
def viscous_trial(states, i, deformation, velocity):
    """Damper ``i`` at the trial ``deformation`` (mm) and Newmark ``velocity`` (mm/s): its force (N),
    consistent tangent dF/du (N/mm), dashpot velocity, heat and stored energy (N*mm) into the trial fields."""
    motion = states.kinematics
    C, alpha, flexibility, dt = states.coefficient[i], states.exponent[i], states.flexibility[i], states.dt
    previous = motion.force[i]
    if flexibility == 0.0:  # a pure linear dashpot: F = C v
        force = C * velocity
        tangent = 2.0 * C / dt
        dashpot_velocity = velocity
        heat = motion.heat[i] + 0.5 * (previous + force) * (deformation - motion.deformation[i])
        stored = 0.0
    else:
        stiffness, half = 1.0 / flexibility, 0.5 * dt
        committed_velocity = states.dashpot_velocity[i]
        target = previous + stiffness * (deformation - motion.deformation[i]) - stiffness * half * committed_velocity
        if alpha == 1.0:
            force = target / (1.0 + stiffness * half / C)
            tangent = stiffness / (1.0 + stiffness * half / C)
            dashpot_velocity = force / C
        elif alpha == 0.5:
            # g(F) = F |F| / C^2: F + a F^2 = |target| with a = K dt/2 / C^2, a quadratic; its positive root in
            # the form without cancellation, 2 |target| / (1 + sqrt(1 + 4 a |target|)) (the common exponent, in
            # closed form: no iteration, no power)
            size, a = abs(target), stiffness * half / (C * C)
            root = math.sqrt(1.0 + 4.0 * a * size)
            force = 2.0 * size / (1.0 + root)
            tangent = stiffness / root  # K / (1 + 2 a F), = K / root exactly: finite where a overflows
            ratio = force / C
            force = math.copysign(force, target)
            dashpot_velocity = math.copysign(ratio * ratio, target)
        else:
            # F + K dt/2 g(F) = target, from the last trial's force (an earlier Newton iterate of this step, or the
            # committed force: near the root) when it has the target's sign and is below |target|, else from
            # |target|.  Any iterate above U, the root of K dt/2 g(F) = |target| (itself above the root, and near
            # it where the dashpot takes most of the step), is moved to U once: from there the iterates fall
            # monotonically onto the root (r is convex).  Without it, Newton from far above (a warm start far
            # from the root, or the first step from below, which overshoots) falls by only (1 - alpha) an
            # iteration -- 100 iterations short of the root at alpha = 0.05 -- and g may overflow there.
            size = abs(target)
            last = motion.trial_force[i] if target > 0.0 else -motion.trial_force[i]
            force = last if 0.0 < last < size else size
            bounded = False
            for _ in range(100):
                speed, slope = _dashpot_velocity(force, C, alpha)
                if not bounded and not stiffness * half * speed <= size:
                    bounded = True
                    force = C * (size / (stiffness * half)) ** alpha
                    speed, slope = _dashpot_velocity(force, C, alpha)
                step = (force + stiffness * half * speed - size) / (1.0 + stiffness * half * slope)
                force -= step
                if not abs(step) > 1e-15 * size:
                    break
            force = max(force, 0.0)
            speed, slope = _dashpot_velocity(force, C, alpha)
            tangent = stiffness / (1.0 + stiffness * half * slope)
            force = math.copysign(force, target)
            dashpot_velocity = math.copysign(speed, target)
        heat = motion.heat[i] + 0.5 * (previous + force) * half * (committed_velocity + dashpot_velocity)
        stored = 0.5 * force * force * flexibility
    motion.trial_force[i], motion.trial_tangent[i] = force, tangent
    motion.trial_heat[i], motion.trial_stored[i] = heat, stored
    states.trial_dashpot_velocity[i] = dashpot_velocity


@njit(cache=True, inline="always")
def viscous_commit(states, i):
    """Accept damper ``i``'s trial (its kinematics are committed by the caller)."""
    states.dashpot_velocity[i] = states.trial_dashpot_velocity[i]
