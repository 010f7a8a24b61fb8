"""vdw_frames: FDMK viscoelastic damping walls and shear buildings fitted with them.

What a user touches is here; everything else stays in its sub-package:
:mod:`~vdw_frames.element` (the wall model and its time stepping), :mod:`~vdw_frames.motion` (ground
motions), :mod:`~vdw_frames.frame` (shear buildings, their analyses, batches), :mod:`~vdw_frames.design`
(wall sizing), :mod:`~vdw_frames.paper` (the paper's data, identification, report),
:mod:`~vdw_frames.interop` (OpenSees), :mod:`~vdw_frames.plotting` (figures), and beside them
:mod:`~vdw_frames.config` (building files) and :mod:`~vdw_frames.cli`.  ``paper``, ``identify`` and
the sub-packages above the frame load on first use (they pull in scipy.optimize and matplotlib, which
``import vdw_frames`` need not pay for).

Units throughout: N, mm, s, tonne; moduli MPa (N/mm^2), viscosities MPa*s^r, stiffness N/mm,
energy N*mm, frequency Hz.
"""

from importlib import import_module
from importlib.metadata import PackageNotFoundError, version
from typing import Any

from .element import (
    FDMKDamper,
    FluidViscousDamper,
    FrictionDamper,
    StrainDependentDamper,
    SupportedDamper,
    ThermalProperties,
    WallLimits,
    sine_test,
)
from .frame import Bilinear, BoucWen, ShearBuilding, incremental_dynamic_analysis, modal_analysis, run_batch, simulate
from .motion import G, GroundMotion, read_at2, read_two_column

try:
    __version__ = version("vdw-frames")
except PackageNotFoundError:  # a source tree that was never installed
    __version__ = "0+unknown"

__all__ = [
    "Bilinear",
    "BoucWen",
    "FDMKDamper",
    "FluidViscousDamper",
    "FrictionDamper",
    "G",
    "GroundMotion",
    "ShearBuilding",
    "StrainDependentDamper",
    "SupportedDamper",
    "ThermalProperties",
    "WallLimits",
    "design_frame",
    "identify",
    "incremental_dynamic_analysis",
    "modal_analysis",
    "paper",
    "read_at2",
    "read_two_column",
    "run_batch",
    "simulate",
    "sine_test",
    "size_walls",
]

_LAZY = {"paper": ("vdw_frames.paper", None), "identify": ("vdw_frames.paper", "identify"),
         "size_walls": ("vdw_frames.design", "size_walls"),
         "design_frame": ("vdw_frames.design", "design_frame")}
_SUBPACKAGES = ("asce7", "config", "design", "element", "frame", "interop", "motion", "paper", "plotting",
                "verification")


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        module_name, attribute = _LAZY[name]
        module = import_module(module_name)
        return module if attribute is None else getattr(module, attribute)
    if name in _SUBPACKAGES:
        return import_module(f"vdw_frames.{name}")
    raise AttributeError(f"module 'vdw_frames' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(__all__) | set(_SUBPACKAGES) | {"__version__"})
