"""Walls stepped together: their memories stacked into the arrays of :mod:`vdw_frames.element.kernel`.

A :class:`WallBank` holds any number of wall assemblies (:class:`~vdw_frames.FDMKDamper`, or
:class:`~vdw_frames.SupportedDamper` with its support in series) on one time step.  Each step has two
compiled calls, whatever the number of walls:

1. the history, once per step: every wall's force this step is ``tangent * d + history_force`` for a
   trial deformation d (the element's trial, affine in d): :meth:`WallBank.trial_forces`;
2. :meth:`WallBank.commit` -- the accepted deformations: forces and wall strains, memory advanced,
   and the next step's history evaluated in the same pass over the memory.

This is the trial/commit contract of :class:`~vdw_frames.DamperState`, for many walls at once; the frame
integrator and the OpenSees bridge use the same compiled calls inside their own loops.

Units: deformation mm, force N, stiffness N/mm, time s.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._validation import positive, whole_number
from . import kernel
from .fast_memory import FastMemory
from .fractional import DEFAULT_METHOD, get_method

MEMORY_STRATEGIES = ("fast", "exact")
DEFAULT_MEMORY = "fast"


def memory_strategy(memory):
    """``None`` for the exact full-history memory, else the :class:`FastMemory` to use."""
    if isinstance(memory, FastMemory):
        return memory
    if isinstance(memory, str) and memory == "fast":
        return FastMemory()
    if isinstance(memory, str) and memory == "exact":
        return None
    raise ValueError(f"memory must be one of {MEMORY_STRATEGIES} or a FastMemory, got {memory!r}")


def kernel_constants(wall) -> np.ndarray:
    """The kernel's row of 7 constants of a wall assembly (see :mod:`vdw_frames.element.kernel`)."""
    try:
        return np.asarray(wall.kernel_constants(), dtype=float)
    except AttributeError:
        raise ValueError(f"a wall must be an FDMKDamper or a SupportedDamper, got {type(wall).__name__}") from None


@dataclass
class Memory:
    """The fractional memory of one wall at rest: its weights and modes (the bank stacks them)."""

    w0: float
    window_weights: np.ndarray  # (L,): w_L .. w_1
    mode_weight: np.ndarray  # (K,)
    mode_ratio: np.ndarray  # (K,)
    max_steps: int

    @classmethod
    def allocate(cls, r: float, dt: float, steps: int, method=DEFAULT_METHOD, memory=DEFAULT_MEMORY) -> "Memory":
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
    the exact memory keeps that many).  ``method``, ``memory``: as for :meth:`FDMKDamper.force`.
    Attributes ``tangent`` (N/mm) and ``history_force`` (N), one per wall, always for the coming step:
    a wall's force this step is ``tangent * d + history_force`` at deformation d (mm).  The arrays are
    laid out as :mod:`vdw_frames.element.kernel` describes.
    """

    walls: tuple
    dt: float
    steps: int
    method: object = DEFAULT_METHOD
    memory: object = DEFAULT_MEMORY
    count: int = field(default=0, init=False)
    constants: np.ndarray = field(init=False, repr=False)
    tangent: np.ndarray = field(init=False, repr=False)
    history_force: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        self.walls = tuple(self.walls)
        self.dt = positive("dt", self.dt)
        self.steps = whole_number("steps", self.steps, 0)
        self.method = get_method(self.method)
        memory_strategy(self.memory)
        self.constants = np.array([kernel_constants(wall) for wall in self.walls]).reshape(-1, 7)
        memories = [Memory.allocate(wall.r, self.dt, self.steps, self.method, self.memory) for wall in self.walls]
        self.max_steps = min((m.max_steps for m in memories), default=max(self.steps, 1))
        size = max((m.window_weights.size for m in memories), default=1)
        modes = max((m.mode_ratio.size for m in memories), default=0)
        count = len(memories)
        self.w0 = np.array([m.w0 for m in memories])
        self.window_weights = np.zeros((count, size))
        self.window = np.zeros((count, 2, 2 * size))
        self.mode_weight = np.zeros((count, modes))  # fewer modes: padded with inert zero modes
        self.mode_ratio = np.zeros((count, modes))
        self.mode_state = np.zeros((count, 2, modes))
        for d, m in enumerate(memories):
            if m.window_weights.size != size:
                raise ValueError("walls of one bank must share the memory window (same memory strategy)")
            self.window_weights[d] = m.window_weights
            self.mode_weight[d, : m.mode_weight.size] = m.mode_weight
            self.mode_ratio[d, : m.mode_ratio.size] = m.mode_ratio
        self.history = np.zeros((2, count))
        self._values = np.zeros((2, count))
        self.tangent = np.zeros(count)
        self.history_force = np.zeros(count)
        self.evaluate_history()

    def __len__(self) -> int:
        return len(self.walls)

    def evaluate_history(self) -> None:
        """(Re)evaluate ``tangent`` and ``history_force`` of the coming step from the memory (commit does it)."""
        kernel.bank_affine(self.constants, self.w0, self.window_weights, self.window, self.count,
                           self.mode_weight, self.mode_state, self.history, self.tangent, self.history_force)

    def trial_forces(self, deformation) -> np.ndarray:
        """Forces (N) at trial deformations (mm, one per wall) this step; the memory is untouched."""
        return self.tangent * np.asarray(deformation, dtype=float) + self.history_force

    def commit(self, deformation):
        """Accept ``deformation`` (mm, one per wall) for this step; returns (forces N, wall strains).

        Advances every wall's memory one step and evaluates the next step's history.
        """
        if self.count >= self.max_steps:
            raise ValueError(f"the wall memory was built for {self.max_steps} steps; build the bank (or "
                             "FastMemory(max_steps=...)) for more")
        deformation = np.ascontiguousarray(deformation, dtype=float).reshape(len(self.walls))
        force = np.empty(len(self.walls))
        strain = np.empty(len(self.walls))
        kernel.bank_commit(self.constants, self.w0, self.window_weights, self.window, self.count,
                           self.mode_weight, self.mode_ratio, self.mode_state, self.history, self._values,
                           deformation, force, strain, self.tangent, self.history_force)
        self.count += 1
        return force, strain

    def resized(self, steps: int) -> "WallBank":
        """This bank with room for ``steps`` steps in all: the committed memory copied, the count kept.

        How an exact memory grows (:class:`~vdw_frames.DamperState`, the OpenSees bridge): only a memory
        without modes that still holds every committed step can be resized.
        """
        size = self.window_weights.shape[1]
        if self.mode_weight.shape[1] or self.count > size:
            raise ValueError("only an exact memory holding every committed step can be resized")
        steps = whole_number("steps", steps, max(self.count, 1))
        bigger = WallBank(self.walls, self.dt, steps, self.method, "exact")
        values = self.window[:, :, :self.count]  # x_0 .. x_{count-1}: not yet wrapped
        new_size = bigger.window_weights.shape[1]
        bigger.window[:, :, :self.count] = values
        bigger.window[:, :, new_size:new_size + self.count] = values
        bigger.count = self.count
        bigger.evaluate_history()
        return bigger

    def drive(self, displacement) -> tuple:
        """(force N, wall strain) histories of a one-wall bank at rest for a displacement history (mm)."""
        if len(self.walls) != 1 or self.count != 0:
            raise ValueError("drive() needs a one-wall bank at rest")
        return kernel.displacement_driven(self.constants, self.w0, self.window_weights, self.window,
                                          self.mode_weight, self.mode_ratio, self.mode_state, displacement)

    def kernel_arrays(self):
        """(constants, w0, window_weights, window, mode_weight, mode_ratio, mode_state, history, values,
        tangent, history_force): the arrays of :func:`kernel.bank_commit` (``values`` is its scratch), for
        integrators that loop in numba."""
        return (self.constants, self.w0, self.window_weights, self.window, self.mode_weight, self.mode_ratio,
                self.mode_state, self.history, self._values, self.tangent, self.history_force)
