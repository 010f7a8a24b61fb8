"""Seismic time-history analysis of a shear building with FDMK walls: :func:`simulate`, the one entry.

A thin dispatcher above the two analyses: the time-history analysis of walls with fixed parameters
(:func:`vdw_frames.frame.time_history.time_history`, the compiled Newmark-Newton integrator of
:mod:`vdw_frames.frame.integrator`) and the strain-compatible (equivalent-linear) iteration of
:mod:`vdw_frames.frame.strain_compatible`, which runs the first as often as it needs.  Neither imports
this module.

Units: N, mm, s, tonne; ground acceleration mm/s^2.
"""

from __future__ import annotations

from typing import Any

from ..element.bank import DEFAULT_MEMORY
from ..element.fast_memory import FastMemory
from ..element.fractional import DEFAULT_METHOD, Discretisation
from ..motion.record import GroundMotion
from .building import ShearBuilding
from .integrator import NewtonRaphson
from .results import FrameState, SimulationResult
from .strain_compatible import StrainCompatibleOptions, strain_compatible_simulation
from .time_history import time_history


def simulate(building: ShearBuilding, ground_motion: GroundMotion, dt: float | None = None,
             method: str | Discretisation = DEFAULT_METHOD, memory: str | FastMemory = DEFAULT_MEMORY,
             strain_compatible: bool | StrainCompatibleOptions = False, *, collapse_drift_ratio: float | None = 0.10,
             free_vibration: float = 0.0, newton: NewtonRaphson | None = None,
             initial_state: FrameState | None = None) -> SimulationResult:
    """Integrate ``building`` under ``ground_motion`` (a :class:`~vdw_frames.GroundMotion`, mm/s^2).

    ``dt`` (s) defaults to the record's step; a smaller step must divide it to a relative 1e-6 (the
    ground acceleration is interpolated linearly; the step used is the record step / the whole number of
    sub-steps, so a float32 dt works); a larger or non-dividing step, or one outside
    ``vdw_frames._validation.SIMULATION_STEP_RANGE`` (1e-9 ... 1e3 s), is a ValueError.  So is a run
    whose result arrays would exceed the 2 GiB memory limit, refused before allocating with its step
    count and memory, and so is a building unstable at rest under its gravity loads (a story's P/h at or
    above its initial stiffness plus its walls' static stiffness), naming the story.  ``method`` and
    ``memory`` (validated even for a frame without walls) select the walls' discretisation and memory
    strategy ("fast", the default, costs the same at every step and stays within 3e-9 of "exact"; see
    :meth:`FDMKDamper.force`).

    ``collapse_drift_ratio`` (-, default 0.10; None disables it; needs story heights): when any story's
    drift ratio exceeds it, the analysis stops there with ``result.collapsed`` and
    ``result.collapse_time``.  ``free_vibration`` (s, >= 0): seconds of zero ground acceleration appended
    to the record, so that residual drifts are measured at rest.  ``newton``: the convergence settings
    (:class:`NewtonRaphson`); a linear building takes one solve per step whatever they are.

    Walls may carry a thermal description (they heat, :mod:`vdw_frames.element.thermal`) and limits (they
    fail, :mod:`vdw_frames.element.limits`); :class:`~vdw_frames.StrainDependentDamper` walls with one
    common r follow their own strain amplitude step by step (:func:`vdw_frames.element.kernel.track_amplitude`).
    ``strain_compatible``: ``True`` (or a :class:`~vdw_frames.frame.StrainCompatibleOptions`) runs the
    equivalent-linear iteration of :mod:`vdw_frames.frame.strain_compatible` instead, for buildings with
    strain-dependent walls; its result is the response of the equivalent-linear building
    (``result.building``).

    ``initial_state``: a :class:`~vdw_frames.frame.results.FrameState` (``result.state_at(step)`` of an
    earlier analysis at the same dt) to start from instead of rest: the stories and walls of ``building``
    are committed through the state's drift history, then the analysis goes on under the record from the
    state's time (the result's rows start there; its energies count from the state).

    A step that fails to converge even with the fallbacks stops the analysis with
    ``result.converged = False`` and a ``RuntimeWarning`` naming the time and story; never NaN.  A run
    whose energy balance misses by more than ``vdw_frames.frame.results.ENERGY_BALANCE_TOLERANCE`` (1e-4)
    of its peak input energy warns (``RuntimeWarning``, a self-check: the equations were not solved).  Warns
    (``UserWarning``) when a wall's peak strain lies above its ``strain_range`` (every wall model, naming the
    story and the model; a fixed-parameter wall's also below it), and when an amplitude-following wall's
    amplitude lies above its range or never reaches it.  Returns a
    :class:`SimulationResult`.
    """
    options: dict[str, Any] = dict(dt=dt, method=method, memory=memory, collapse_drift_ratio=collapse_drift_ratio,
                                   free_vibration=free_vibration, newton=newton)
    if strain_compatible is not False:
        if initial_state is not None:
            raise ValueError("initial_state is for time-history analyses: the strain-compatible iteration reruns "
                             "the whole record (strain_compatible=False)")
        return strain_compatible_simulation(building, ground_motion, strain_compatible, **options)
    return time_history(building, ground_motion, initial_state=initial_state, **options)
