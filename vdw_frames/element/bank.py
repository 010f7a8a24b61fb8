"""Walls stepped together: their memories stacked into the arrays of :mod:`vdw_frames.element.kernel`.

A :class:`WallBank` holds any number of wall assemblies (:class:`~vdw_frames.FDMKDamper`, or
:class:`~vdw_frames.SupportedDamper` with its support in series) on one time step.  Each step has two
compiled calls, whatever the number of walls:

1. the history, once per step: every wall's force this step is ``tangent * d + history_force`` for a
   trial deformation d (the element's trial, affine in d): :meth:`WallBank.trial_forces`;
2. :meth:`WallBank.commit` -- the accepted deformations: forces and wall strains, memory advanced,
   and the next step's history evaluated in the same pass over the memory.

This is the trial/commit contract of :class:`~vdw_frames.element.damper.WallState`, for many walls at
once; the frame integrator and the OpenSees bridge use the same compiled calls inside their own loops
(:attr:`WallBank.arrays`, a :class:`~vdw_frames.element.kernel.BankArrays`).  Walls of one story that see
the same strain history are stepped once, as one wall of their summed area (:func:`group_walls`).

Units: deformation mm, force N, stiffness N/mm, time s.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from .._validation import check_memory, finite_array, show, time_step, whole_number
from . import kernel, thermal
from .fast_memory import MAX_STEPS as MAX_FAST_STEPS
from .fast_memory import FastMemory
from .fractional import DEFAULT_METHOD, METHODS, Discretisation, get_method

if TYPE_CHECKING:
    from .limits import WallLimits
    from .thermal import ThermalProperties
    from .wall import SteppedWall, Wall

MEMORY_STRATEGIES = ("fast", "exact")
DEFAULT_MEMORY = "fast"


def memory_strategy(memory: str | FastMemory) -> FastMemory | None:
    """``None`` for the exact full-history memory, else the :class:`FastMemory` to use."""
    if isinstance(memory, FastMemory):
        return memory
    if isinstance(memory, str) and memory == "fast":
        return FastMemory()
    if isinstance(memory, str) and memory == "exact":
        return None
    raise ValueError(f"memory must be one of {MEMORY_STRATEGIES} or a FastMemory, got {memory!r}")


def wall_order(wall: Any) -> float:
    """A wall's fractional order r (-): its own, or the common r of an amplitude-following wall
    (:attr:`vdw_frames.element.strain_dependent.StrainDependentDamper.common_order`, a ValueError if none)."""
    return float(wall.common_order) if wall.follows_amplitude else float(wall.r)


def amplitude_key(wall: Any) -> tuple | None:
    """What makes two amplitude-following walls behave alike (their node table), None for fixed walls."""
    return tuple(map(tuple, wall.amplitude_table())) if wall.follows_amplitude else None


def kernel_constants(wall: SteppedWall) -> np.ndarray:
    """The kernel's row of 7 constants of a wall assembly (see :mod:`vdw_frames.element.kernel`)."""
    try:
        return np.asarray(wall.kernel_constants(), dtype=float)
    except AttributeError:
        raise ValueError(f"a wall must be an FDMKDamper or a SupportedDamper, got {type(wall).__name__}") from None


@dataclass
class _Memory:
    """The fractional memory of one wall at rest: its weights and modes (the bank stacks them)."""

    w0: float
    window_weights: np.ndarray  # (L,): w_L .. w_1
    mode_weight: np.ndarray  # (K,)
    mode_ratio: np.ndarray  # (K,)
    max_steps: int

    @classmethod
    def allocate(cls, r: float, dt: float, steps: int, method: str | Discretisation = DEFAULT_METHOD,
                 memory: str | FastMemory = DEFAULT_MEMORY) -> _Memory:
        """Memory for ``steps`` steps of ``dt`` s of order ``r``: exact (a window of all steps) or fast."""
        strategy = memory_strategy(memory)
        if strategy is not None and not 0 < steps <= strategy.exact_below:
            weights, mode_weight, mode_ratio = strategy.arrays(method, r, dt, steps)
            max_steps = max(int(steps), strategy.max_steps)
        else:
            weights = get_method(method).weights(r, max(int(steps), 1) + 1, dt)
            mode_weight = mode_ratio = np.zeros(0)
            max_steps = weights.size - 1
        return cls(float(weights[0]), np.ascontiguousarray(weights[:0:-1]), mode_weight, mode_ratio, max_steps)


@dataclass
class WallBank:
    """The state of ``walls`` (a sequence of wall assemblies) stepped together on a step of ``dt`` s.

    ``steps``: the number of steps the bank must serve (the fast memory is built for at least that many;
    the exact memory keeps that many, and :meth:`reserve` grows it).  ``method``, ``memory``: as for
    :meth:`FDMKDamper.force`.  :attr:`tangent` (N/mm) and :attr:`history_force` (N), one per wall, are
    always those of the coming step: a wall's force this step is ``tangent * d + history_force`` at
    deformation d (mm).  :attr:`arrays` holds everything the compiled kernel steps.
    """

    walls: tuple[SteppedWall, ...]
    dt: float
    steps: int
    method: Discretisation = METHODS[DEFAULT_METHOD]
    memory: str | FastMemory = DEFAULT_MEMORY
    count: int = field(default=0, init=False)
    max_steps: int = field(default=0, init=False)
    arrays: kernel.BankArrays = field(init=False, repr=False)

    def __post_init__(self) -> None:
        if not isinstance(self.walls, (tuple, list)):
            raise ValueError(f"walls must be a sequence of walls, got {type(self.walls).__name__}")
        self.walls = tuple(self.walls)
        self.dt = time_step(self.dt)
        self.steps = whole_number("steps", self.steps, 0)
        self.method = get_method(self.method)
        memory_strategy(self.memory)
        self.arrays = self._allocate(self.steps, self._states())
        self.evaluate_history()

    def _states(self) -> kernel.WallStates:
        """Every wall at rest: base parameters, temperature, limits, the diffusive nodes of followed walls."""
        count = len(self.walls)
        constants = np.array([kernel_constants(wall) for wall in self.walls]).reshape(-1, 7)
        thermals = [wall.thermal for wall in self.walls]
        limits = [wall.limits for wall in self.walls]
        tables = [wall.amplitude_table() for wall in self.walls]
        walls = kernel.wall_records(count)
        base, thermal_group, energy, limits_group, tracker = (walls[group].view(np.recarray) for group in kernel.GROUPS)
        base["energy_followed"] = [t is not None or lim is not None for t, lim in zip(thermals, limits, strict=True)]
        base["tracked"] = [t is not None or lim is not None or nodes.size > 0
                           for t, lim, nodes in zip(thermals, limits, tables, strict=True)]
        base["g1"], base["g2"], base["eta1"], base["eta2"] = constants[:, :4].T
        base["order"] = [wall_order(wall) for wall in self.walls]
        tracker["amplitude_nodes"] = [nodes.shape[0] for nodes in tables]
        amplitude_table = np.zeros((count, max((nodes.shape[0] for nodes in tables), default=0), 5))
        for w, nodes in enumerate(tables):
            amplitude_table[w, :nodes.shape[0]] = nodes
            if nodes.shape[0]:
                tracker.amplitude_low[w], tracker.amplitude_high[w] = np.exp(nodes[[0, -1], 0])
        for w, (wall_thermal, c) in enumerate(zip(thermals, constants, strict=True)):
            for name, value in thermal.thermal_row(wall_thermal, c[4] * c[5], self.dt)._asdict().items():
                thermal_group[name][w] = value
        thermal_group["temperature"] = [t.temperature if t is not None else np.nan for t in thermals]
        thermal_group["shift_rate"] = math.log(10.0) * base.order * thermal_group.law_slope
        for name in ("limit_strain", "limit_stress", "limit_temperature"):
            limits_group[name] = np.inf
        for w, wall_limits in enumerate(limits):
            if wall_limits is not None:
                (limits_group.limit_strain[w], limits_group.limit_stress[w], limits_group.limit_temperature[w],
                 limits_group.residual[w]) = wall_limits.kernel_row()
        base["limited"] = [lim is not None for lim in limits]
        # The update's straight path calls the temperature and shift-law steps unchecked: only for a wall with both.
        heats = (thermal_group.law_kind != 0.0) & (thermal_group.capacity > 0.0)
        only = (base.limited == 0.0) & (tracker.amplitude_nodes == 0.0)
        base["heating_only"] = heats & only
        limits_group["failure_step"] = -1.0
        limits_group["scale"] = 1.0
        thermal_group["outside"] = -1.0
        tracker["amplitude_used"] = np.nan  # nothing interpolated yet
        thermal_group["shift_anchor"] = np.nan  # no exp taken yet
        tracked = np.flatnonzero(base.energy_followed)
        xi = thermal.diffusive_nodes(self.dt) if tracked.size else np.zeros(0)
        e, gain, work = thermal.node_coefficients(xi, self.dt).T
        orders = sorted({float(base.order[w]) for w in tracked.tolist()})  # one node set for each
        nodes = np.zeros((len(orders), 4, xi.size))
        tails = []
        for n, order in enumerate(orders):
            weights, dashpot, spring = thermal.diffusive_weights(order, xi)
            nodes[n] = e, gain, weights * gain, weights
            tails.append((dashpot / self.dt, spring, float(weights @ work)))  # a dashpot's heat is dashpot dx^2 / dt
        for w in tracked.tolist():
            n = orders.index(float(base.order[w]))
            base.node_set[w] = n
            energy.tail_dashpot[w], energy.tail_spring[w], energy.node_work_sum[w] = tails[n]
        return kernel.WallStates(walls=walls, nodes=nodes, node_state=np.zeros((count, 2, xi.size)),
                                 amplitude_table=amplitude_table)

    @property
    def states(self) -> kernel.WallStates:
        """Every wall's state beyond its memory, the kernel's own (changed in place by every commit): its state
        groups ``states.base``, ``.thermal``, ``.energy``, ``.limits``, ``.tracker``, each (W,) records of named
        fields (:class:`~vdw_frames.element.kernel.WallStates`).  :meth:`state` gives a copy of one field."""
        return self.arrays.states

    def state(self, field: str) -> np.ndarray:
        """One named field of every wall's state, a copy (W,): ``bank.state("temperature")``; the names are those of
        the state groups (:data:`vdw_frames.element.kernel.GROUPS`).  Units: the field's own."""
        for group, fields in kernel.GROUPS.items():
            if field in fields:
                return np.array(self.arrays.states.walls[group][field], dtype=float)
        names = ", ".join(name for fields in kernel.GROUPS.values() for name in fields)
        raise ValueError(f"no wall state field {field!r}; the fields are {names}")

    def _allocate(self, steps: int, states: kernel.WallStates) -> kernel.BankArrays:
        strategy = memory_strategy(self.memory)
        if strategy is None or 0 < steps <= strategy.exact_below:  # the exact memory: weights and values, each step
            check_memory(f"WallBank ({len(self.walls)} walls, exact memory)", steps, 40.0 * max(len(self.walls), 1),
                         "use the fast memory")
        elif steps > MAX_FAST_STEPS:
            raise ValueError(f"steps must be at most 2**40 = {MAX_FAST_STEPS:,} with the fast memory, got {steps:,}")
        memories = [_Memory.allocate(wall_order(wall), self.dt, steps, self.method, self.memory) for wall in self.walls]
        self.max_steps = min((m.max_steps for m in memories), default=max(steps, 1))
        size = max((m.window_weights.size for m in memories), default=1)
        modes = max((m.mode_ratio.size for m in memories), default=0)
        count = len(memories)
        window_weights = np.zeros((count, size))
        mode_weight = np.zeros((count, modes))  # fewer modes: padded with inert zero modes
        mode_ratio = np.zeros((count, modes))
        for d, m in enumerate(memories):
            if m.window_weights.size != size:
                raise ValueError("walls of one bank must share the memory window (same memory strategy)")
            window_weights[d] = m.window_weights
            mode_weight[d, : m.mode_weight.size] = m.mode_weight
            mode_ratio[d, : m.mode_ratio.size] = m.mode_ratio
        constants = np.array([kernel_constants(wall) for wall in self.walls]).reshape(-1, 7)
        for w, wall in enumerate(self.walls):  # the coefficients at the temperature at rest
            wall_thermal = wall.thermal
            if wall_thermal is not None:
                # held at the law's range, as every step is; the analysis warns of it itself (thermal.outside)
                constants[w, 2:4] *= wall_thermal.viscosity_factor(wall_thermal.temperature, wall_order(wall),
                                                                   warn=False)
        memory = kernel.MemoryArrays(
            w0=np.array([m.w0 for m in memories]), window_weights=window_weights, window=np.zeros((count, 2, 2 * size)),
            mode_weight=mode_weight, mode_ratio=mode_ratio, mode_state=np.zeros((count, 2, modes)),
            history=np.zeros((2, count)), values=np.zeros((2, count)))
        return kernel.BankArrays(constants=constants, memory=memory, tangent=np.zeros(count),
                                 history_force=np.zeros(count), states=states,
                                 followed=bool(states.base.tracked.any()))

    def __len__(self) -> int:
        return len(self.walls)

    @property
    def tangent(self) -> np.ndarray:
        """K_t of every wall for the coming step, N/mm (updated in place by :meth:`commit`)."""
        return self.arrays.tangent

    @property
    def history_force(self) -> np.ndarray:
        """H_n of every wall for the coming step, N (updated in place by :meth:`commit`)."""
        return self.arrays.history_force

    def evaluate_history(self) -> None:
        """(Re)evaluate ``tangent`` and ``history_force`` of the coming step from the memory (commit does it)."""
        kernel.bank_affine(self.arrays, self.count)

    def trial_forces(self, deformation: ArrayLike, *, name: str = "deformation") -> np.ndarray:
        """Forces (N) at trial deformations (mm, one per wall) this step; the memory is untouched.  A force
        that overflows (inf) is a ValueError naming the deformation (as ``name``)."""
        return self._trial(self._deformations(deformation, name), name)

    def _trial(self, deformation: np.ndarray, name: str) -> np.ndarray:
        """:meth:`trial_forces` of deformations :meth:`_deformations` already checked."""
        with np.errstate(over="ignore", invalid="ignore"):
            force = self.tangent * deformation + self.history_force
        self._require_finite(force, deformation, name)
        return force

    def _require_finite(self, force: np.ndarray, deformation: np.ndarray, name: str) -> None:
        bad = ~np.isfinite(force)
        if bad.any():
            w = int(np.argmax(bad))
            wall = f" of wall {w + 1}" if len(self.walls) > 1 else ""
            raise ValueError(f"the force{wall} overflowed (inf or NaN) at {name} = {show(deformation[w])} mm: "
                             f"the {name} or the wall's parameters are too large")

    def _deformations(self, deformation: ArrayLike, name: str = "deformation") -> np.ndarray:
        deformation = finite_array(name, deformation, ndim=None)
        if deformation.size != len(self.walls):
            raise ValueError(f"{name} has {deformation.size} values for {len(self.walls)} walls")
        return np.ascontiguousarray(deformation.reshape(len(self.walls)))

    def commit(self, deformation: ArrayLike, *, name: str = "deformation") -> tuple[np.ndarray, np.ndarray]:
        """Accept ``deformation`` (mm, one per wall) for this step; returns (forces N, wall strains).

        Advances every wall's memory one step and evaluates the next step's history.  A force that
        overflows is a ValueError naming the deformation (as ``name``), before the memory takes it.
        """
        deformation = self._deformations(deformation, name)
        self._trial(deformation, name)  # refuses an overflowing force before the memory takes it
        self.reserve(1)
        force = np.empty(len(self.walls))
        strain = np.empty(len(self.walls))
        kernel.bank_commit(self.arrays, self.count, deformation, force, strain)
        self.count += 1
        self._require_finite(force, deformation, name)
        self._require_finite(self.history_force, deformation, name)  # the next step's history
        return force, strain

    def reserve(self, steps: int) -> None:
        """Make room for ``steps`` more commits: an exact memory grows (at least doubling, the committed
        values copied); a fast memory, built for ``max_steps`` steps, is a ValueError past them."""
        steps = whole_number("steps", steps, 0)
        if self.count + steps <= self.max_steps:
            return
        arrays = self.arrays
        size = arrays.memory.window_weights.shape[1]
        if arrays.memory.mode_weight.shape[1] or self.count > size:
            raise ValueError(f"the fast memory was built for {self.max_steps} steps ({self.count} committed); build "
                             "it with memory=FastMemory(max_steps=...) for more")
        self.memory = "exact"
        bigger = self._allocate(max(2 * self.max_steps, self.count + steps), arrays.states)
        new_size = bigger.memory.window_weights.shape[1]
        values = arrays.memory.window[:, :, :self.count]  # x_0 .. x_{count-1}: not yet wrapped
        bigger.memory.window[:, :, :self.count] = values
        bigger.memory.window[:, :, new_size:new_size + self.count] = values
        bigger.constants[:] = arrays.constants  # the coefficients the states last set
        self.arrays = bigger
        self.evaluate_history()

    def drive(self, displacement: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(force N, wall strain) histories of a one-wall bank at rest for a displacement history (mm)."""
        if len(self.walls) != 1 or self.count != 0:
            raise ValueError("drive() needs a one-wall bank at rest")
        force, strain = np.empty(len(displacement)), np.empty(len(displacement))
        kernel.displacement_driven(self.arrays, displacement, force, strain)
        return force, strain


@dataclass(frozen=True)
class _CombinedWall:
    """Parallel identical walls (see :func:`group_walls`) as one wall of the summed area, for the kernel."""

    wall: Wall
    area: float
    r: float = field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "r", wall_order(self.wall))

    @property
    def thickness(self) -> float:
        return self.wall.thickness

    @property
    def thermal(self) -> ThermalProperties | None:
        return self.wall.thermal

    @property
    def limits(self) -> WallLimits | None:
        return self.wall.limits

    def amplitude_table(self) -> np.ndarray:
        """The wrapped wall's amplitude table ((0, 5) for a wall of fixed parameters)."""
        return self.wall.amplitude_table()

    @property
    def follows_amplitude(self) -> bool:
        return self.wall.follows_amplitude

    @property
    def common_order(self) -> float:
        return wall_order(self.wall)

    def kernel_constants(self) -> tuple[float, ...]:
        G1, G2, eta1, eta2, area, thickness, flexibility = kernel_constants(self.wall)
        return (G1, G2, eta1, eta2, self.area, thickness, flexibility * area / self.area)


def group_walls(walls: Sequence[tuple[int, Wall]]) -> tuple[list[tuple[int, _CombinedWall]], np.ndarray]:
    """Walls of one story that see the same strain history, stepped once as one wall of their summed area.

    ``walls``: (story, wall) pairs.  Two walls in parallel on a story are one wall of the summed area when
    their material, order, thickness and magnification agree and their supports scale with their areas
    (equal flexibility x area).  Returns ([(story, combined wall)], the group index of every wall (walls,)).
    """
    keys: dict[tuple, int] = {}
    members: list[list[int]] = []
    for index, (story, wall) in enumerate(walls):
        G1, G2, eta1, eta2, area, thickness, flexibility = (float(x) for x in kernel_constants(wall))
        key = (story, G1, G2, eta1, eta2, wall_order(wall), thickness, flexibility * area,
               wall.thermal, wall.limits, amplitude_key(wall),
               wall.magnification)
        if key not in keys:
            keys[key] = len(members)
            members.append([])
        members[keys[key]].append(index)
    groups: list[tuple[int, _CombinedWall]] = []
    group_of_wall = np.zeros(len(walls), dtype=np.int64)
    for g, indices in enumerate(members):
        story, first = walls[indices[0]]
        area = sum(walls[i][1].area for i in indices)
        groups.append((story, _CombinedWall(first, area)))
        group_of_wall[indices] = g
    return groups, group_of_wall
