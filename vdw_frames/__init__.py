"""vdw_frames: FDMK viscoelastic damping walls and shear buildings fitted with them.

Sub-packages: :mod:`~vdw_frames.element` (the FDMK wall model and its time stepping),
:mod:`~vdw_frames.frame` (shear buildings, integration, batches), :mod:`~vdw_frames.design` (complex
modal analysis, wall sizing), :mod:`~vdw_frames.motion` (ground motions) and :mod:`~vdw_frames.paper`
(the paper's data, identification, report); beside them
:mod:`~vdw_frames.config` (building files), :mod:`~vdw_frames.plotting` and :mod:`~vdw_frames.cli`.
The public names are re-exported here; ``paper`` and ``identify`` load on first use (they pull in
scipy.optimize, which ``import vdw_frames`` need not pay for).

Units throughout: N, mm, s, tonne; moduli MPa (N/mm^2), viscosities MPa*s^r, stiffness N/mm,
energy N*mm, frequency Hz.
"""

from importlib import import_module

from . import design, element, frame, motion
from .design import ModalResult, SizingCurve, damping_curve, size_walls
from .element import (
    BDF2,
    DampedTwoStep,
    DamperState,
    Discretisation,
    FastMemory,
    FDMKDamper,
    GrunwaldLetnikov,
    SineTestResult,
    StrainDependentDamper,
    SupportedDamper,
    Trapezoidal,
    WallBank,
    sine_test,
)
from .frame import (
    BatchResult,
    Bilinear,
    BoucWen,
    EnergyHistory,
    IDAResult,
    NewtonRaphson,
    ShearBuilding,
    SimulationResult,
    StrainCompatibleOptions,
    incremental_dynamic_analysis,
    run_batch,
    simulate,
)
from .motion import G, GroundMotion, read_at2, read_two_column, response_spectrum, write_at2
from .plotting import plot_loops

__all__ = [
    "BDF2",
    "BatchResult",
    "Bilinear",
    "BoucWen",
    "DampedTwoStep",
    "DamperState",
    "Discretisation",
    "EnergyHistory",
    "FDMKDamper",
    "FastMemory",
    "G",
    "GroundMotion",
    "GrunwaldLetnikov",
    "IDAResult",
    "ModalResult",
    "NewtonRaphson",
    "ShearBuilding",
    "SimulationResult",
    "SineTestResult",
    "SizingCurve",
    "SupportedDamper",
    "StrainCompatibleOptions",
    "StrainDependentDamper",
    "Trapezoidal",
    "WallBank",
    "damping_curve",
    "design",
    "element",
    "frame",
    "identify",
    "incremental_dynamic_analysis",
    "motion",
    "paper",
    "plot_loops",
    "read_at2",
    "read_two_column",
    "response_spectrum",
    "run_batch",
    "simulate",
    "sine_test",
    "size_walls",
    "write_at2",
]

_LAZY = {"paper": ("vdw_frames.paper", None), "identify": ("vdw_frames.paper", "identify")}


def __getattr__(name):
    if name in _LAZY:
        module_name, attribute = _LAZY[name]
        module = import_module(module_name)
        return module if attribute is None else getattr(module, attribute)
    raise AttributeError(f"module 'vdw_frames' has no attribute {name!r}")
