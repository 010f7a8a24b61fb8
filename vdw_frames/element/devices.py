"""Every device kind behind one compiled contract, and the registry of kinds.

The FDMK walls are stepped by their own bank (:mod:`vdw_frames.element.bank`): within a step a wall's force
is affine in its deformation, F = K_t d + H_n, which the integrator uses as it is (the walls' fast path).
Every other kind is registered here (:data:`KINDS`) and stepped through :class:`DeviceStates`, one state
group a kind, each owned by its kind's module (named fields, no shared table):

* ``trial`` -- every device at the story drifts of a Newton iterate: deformation = magnification x drift,
  Newmark's velocity v = 2/dt (u - u_n) - v_n, and the kind's trial function gives force and consistent
  tangent (the ``setTrialStrain`` / ``getStress`` / ``getTangent`` of OpenSees's ``UniaxialMaterial``);
  :func:`devices_trial` sums magnification x force and magnification^2 x tangent into each story;
* ``commit`` -- :func:`devices_commit` accepts the last trial (``commitState``); a new trial simply
  overwrites an unaccepted one (``revertToLastCommit``).

Adding a kind: one module with its frozen-dataclass device (:class:`~vdw_frames.element.device.Device`), its
state group (a NamedTuple starting with :class:`~vdw_frames.element.device.Kinematics`), its ``*_states``
builder and compiled ``*_trial`` / ``*_commit``; then its entry in :data:`KINDS`, a field of
:class:`DeviceStates` and a line in :func:`devices_trial`, :func:`devices_commit` and :func:`device_states`.

Units: deformation mm, velocity mm/s, force N, stiffness N/mm, energy N*mm, time s.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._jit import njit
from .._validation import finite_array, show, time_step
from .device import Device
from .friction import FrictionDamper, FrictionStates, friction_commit, friction_states, friction_trial
from .viscous import FluidViscousDamper, ViscousStates, viscous_commit, viscous_states, viscous_trial

KINDS: dict[str, type] = {FluidViscousDamper.kind: FluidViscousDamper, FrictionDamper.kind: FrictionDamper}
"""The registered device kinds other than the walls: name (building files' ``type``) -> class."""


class DeviceStates(NamedTuple):
    """Every registered kind's state group, for one analysis."""

    viscous: ViscousStates
    friction: FrictionStates
    total: int  # devices of every kind


def is_stepped_device(device: object) -> bool:
    """Whether ``device`` is one of the registered kinds stepped here (not a wall)."""
    return isinstance(device, tuple(KINDS.values()))


def device_states(devices: Sequence[tuple[int, Device]], dt: float) -> DeviceStates:
    """The compiled states of ``devices`` ((story 1-based, device), the building's order: their history
    columns) at rest, on a step of ``dt`` s."""
    dt = time_step(dt)
    viscous: list[tuple[int, int, FluidViscousDamper]] = []
    friction: list[tuple[int, int, FrictionDamper]] = []
    for column, (story, device) in enumerate(devices):
        if isinstance(device, FluidViscousDamper):
            viscous.append((story - 1, column, device))
        elif isinstance(device, FrictionDamper):
            friction.append((story - 1, column, device))
        else:
            raise ValueError(f"a device must be one of {sorted(KINDS)} here, got {type(device).__name__}")
    return DeviceStates(viscous=viscous_states(viscous, dt), friction=friction_states(friction), total=len(devices))


@njit(cache=True, inline="always")
def _kinematic_trial(motion, i, drift, dt):
    """Device ``i``'s trial deformation (mm) and Newmark velocity (mm/s) at the story ``drift`` (mm)."""
    deformation = motion.magnification[i] * drift
    velocity = 2.0 / dt * (deformation - motion.deformation[i]) - motion.velocity[i]
    motion.trial_deformation[i], motion.trial_velocity[i] = deformation, velocity
    return deformation, velocity


@njit(cache=True, inline="always")
def _add_to_stories(motion, i, force, tangent):
    """Device ``i``'s trial force and tangent into its story's totals."""
    s, factor = motion.story[i], motion.magnification[i]
    force[s] += factor * motion.trial_force[i]
    tangent[s] += factor * factor * motion.trial_tangent[i]


@njit(cache=True, allocates=False)  # called: inlined into the integrator's overloads, numba's SSA pass warns
def devices_trial(states, drift, dt, force, tangent):
    """Every device at the story drifts ``drift`` (n,) mm of a step of ``dt`` s: the stories' device forces
    (N) and tangents (N/mm) into ``force`` and ``tangent`` (n,), the devices' trials into their states."""
    for s in range(force.shape[0]):
        force[s] = 0.0
        tangent[s] = 0.0
    viscous = states.viscous
    for i in range(viscous.kinematics.story.shape[0]):
        d, v = _kinematic_trial(viscous.kinematics, i, drift[viscous.kinematics.story[i]], dt)
        viscous_trial(viscous, i, d, v)
        _add_to_stories(viscous.kinematics, i, force, tangent)
    friction = states.friction
    for i in range(friction.kinematics.story.shape[0]):
        d, v = _kinematic_trial(friction.kinematics, i, drift[friction.kinematics.story[i]], dt)
        friction_trial(friction, i, d, v)
        _add_to_stories(friction.kinematics, i, force, tangent)


@njit(cache=True, inline="always")
def _commit_kinematics(motion, i):
    motion.deformation[i], motion.velocity[i] = motion.trial_deformation[i], motion.trial_velocity[i]
    motion.force[i] = motion.trial_force[i]
    motion.heat[i], motion.stored[i] = motion.trial_heat[i], motion.trial_stored[i]


@njit(cache=True, allocates=False)  # called: inlined into the integrator's overloads, numba's SSA pass warns
def devices_commit(states):
    """Accept every device's last trial."""
    viscous = states.viscous
    for i in range(viscous.kinematics.story.shape[0]):
        viscous_commit(viscous, i)
        _commit_kinematics(viscous.kinematics, i)
    friction = states.friction
    for i in range(friction.kinematics.story.shape[0]):
        friction_commit(friction, i)
        _commit_kinematics(friction.kinematics, i)


@njit(cache=True, inline="always")
def record_devices(motion, row, force, deformation, velocity, heat, stored):
    """A kind's committed devices into row ``row`` of the histories (rows, devices), at their columns."""
    for i in range(motion.story.shape[0]):
        c = motion.column[i]
        force[row, c], deformation[row, c] = motion.force[i], motion.deformation[i]
        velocity[row, c] = motion.velocity[i]
        heat[row, c], stored[row, c] = motion.heat[i], motion.stored[i]


@njit(cache=True)
def _drive(states, motion, deformation, dt, force, heat, stored):
    """One device (``motion``: its kinematics) driven from rest through a deformation history (mm, (steps,))."""
    drift = np.zeros(1)
    story_force, story_tangent = np.zeros(1), np.zeros(1)
    for n in range(1, deformation.shape[0]):
        drift[0] = deformation[n]
        devices_trial(states, drift, dt, story_force, story_tangent)
        devices_commit(states)
        force[n], heat[n], stored[n] = story_force[0], motion.heat[0], motion.stored[0]


def device_response(device: Device, deformation: ArrayLike, dt: float) -> dict[str, np.ndarray]:
    """A device alone driven through a deformation history (mm, (steps,), starting at rest: 0) on a step of
    ``dt`` s, as the frame integrator steps it (a story drift of ``deformation``): {"force": N (along the
    story, magnification x the device's), "heat": N*mm dissipated since rest, "stored": N*mm} histories.
    For loops and the closed-form checks."""
    history = finite_array("deformation", deformation)
    if history.size < 2 or history[0] != 0.0:
        raise ValueError("deformation must start at rest (0 mm) and hold at least two steps")
    states = device_states([(1, device)], dt)
    motion = states.viscous.kinematics if states.viscous.coefficient.size else states.friction.kinematics
    force, heat, stored = np.zeros(history.size), np.zeros(history.size), np.zeros(history.size)
    _drive(states, motion, history, float(dt), force, heat, stored)
    for name, values in (("force", force), ("heat", heat), ("stored", stored)):
        if not np.isfinite(values).all():
            step = int(np.flatnonzero(~np.isfinite(values))[0])
            raise ValueError(f"the {device.describe()}'s {name} overflowed (inf) at step {step}, deformation "
                             f"{show(float(history[step]))} mm: outside the double-precision range")
    return {"force": force, "heat": heat, "stored": stored}


class DeviceState:
    """Time-stepping state of one device that is not a wall, with OpenSees ``UniaxialMaterial``-like
    trial/commit semantics (the walls' is :class:`~vdw_frames.element.damper.WallState`).

    ``force, tangent = state.trial(deformation)`` gives the force (N, along the story: magnification x the
    device's) at the next step for a story drift ``deformation`` (mm) and its derivative (N/mm, Newmark's
    velocity term included), the committed state untouched; any number of trials may precede
    :meth:`commit`, which accepts the last one and advances a step of ``dt`` s; :meth:`revert_to_last_commit`
    discards it.  The device's velocity is Newmark's, v = 2/dt (u - u_n) - v_n, as in the frame.
    """

    def __init__(self, device: Device, dt: float) -> None:
        self.device = device
        self.dt = time_step(dt)
        self._states = device_states([(1, device)], self.dt)
        viscous = self._states.viscous
        self._motion = viscous.kinematics if viscous.coefficient.size else self._states.friction.kinematics
        self._drift, self._force, self._tangent = np.zeros(1), np.zeros(1), np.zeros(1)
        self._tried = False

    def trial(self, deformation: float) -> tuple[float, float]:
        """(force N, tangent N/mm) at the story drift ``deformation`` (mm) this step; nothing committed."""
        self._drift[0] = finite_array("deformation", [deformation])[0]
        devices_trial(self._states, self._drift, self.dt, self._force, self._tangent)
        if not (math.isfinite(self._force[0]) and math.isfinite(self._tangent[0])
                and math.isfinite(self._motion.trial_heat[0]) and math.isfinite(self._motion.trial_stored[0])):
            self._tried = False  # nothing to commit
            raise ValueError(f"the {self.device.describe()}'s trial at deformation {show(float(deformation))} mm "
                             "overflowed (inf): outside the double-precision range")
        self._tried = True
        return float(self._force[0]), float(self._tangent[0])

    def commit(self) -> None:
        """Accept the last trial (a ValueError without one)."""
        if not self._tried:
            raise ValueError("commit needs a trial first")
        devices_commit(self._states)
        self._tried = False

    def revert_to_last_commit(self) -> None:
        """Discard the last trial."""
        self._tried = False

    @property
    def committed_force(self) -> float:
        """The device's own force at the last commit (N)."""
        return float(self._motion.force[0])

    @property
    def heat(self) -> float:
        """Energy dissipated since rest at the last commit (N*mm)."""
        return float(self._motion.heat[0])

    @property
    def stored(self) -> float:
        """Energy stored at the last commit (N*mm)."""
        return float(self._motion.stored[0])
