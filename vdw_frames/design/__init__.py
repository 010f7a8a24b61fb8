"""Design with damping devices: how many are needed for a target damping ratio.

- :mod:`.sizing`: :func:`size_devices` (:class:`DeviceSizing`: devices of any kind for a target damping
  ratio of one mode, nonlinear ones linearised at a design drift amplitude), :func:`size_walls` (walls),
  :func:`damping_curve` (:class:`SizingCurve`: period and damping ratio against the wall size), both
  from the complex modes of :func:`vdw_frames.frame.modal_analysis`;
- :mod:`.damped`: :func:`design_damped` (:class:`DampedDesign`, :class:`DesignRound`): a frame with damping
  devices by ASCE 7-16 Chapters 12 and 18 (V_min, devices sized at the MCE_R amplitude), verified and iterated;
- :mod:`.layers`: :func:`size_layers` (:class:`LayerSizing`: layer thicknesses that keep strain-dependent
  walls inside their identified amplitudes over a suite of records);
- :mod:`.elf`: :func:`design_frame` (:class:`FrameDesign`): the frame by ASCE 7-16 Chapter 12 (the equivalent
  lateral force procedure, Sec. 12.8): strengths and stiffnesses of a shear building for a site and a system.

Units: N, mm, s, tonne; periods s, areas mm^2.
"""

from .damped import DampedDesign, DesignRound, LimitCheck, design_damped
from .elf import FrameDesign, design_frame
from .layers import LayerSizing, size_layers
from .sizing import DISTRIBUTIONS, DeviceSizing, SizingCurve, damping_curve, size_devices, size_walls

__all__ = ["DISTRIBUTIONS", "DampedDesign", "DesignRound", "DeviceSizing", "FrameDesign", "LayerSizing", "LimitCheck",
           "SizingCurve", "damping_curve", "design_damped", "design_frame", "size_devices", "size_layers", "size_walls"]
