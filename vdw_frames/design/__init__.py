"""Design with damping devices: how many are needed for a target damping ratio.

- :mod:`.sizing`: :func:`size_devices` (:class:`DeviceSizing`: devices of any kind for a target damping
  ratio of one mode, nonlinear ones linearised at a design drift amplitude), :func:`size_walls` (walls),
  :func:`damping_curve` (:class:`SizingCurve`: period and damping ratio against the wall size), both
  from the complex modes of :func:`vdw_frames.frame.modal_analysis`;
- :mod:`.layers`: :func:`size_layers` (:class:`LayerSizing`: layer thicknesses that keep strain-dependent
  walls inside their identified amplitudes over a suite of records).

Units: N, mm, s, tonne; periods s, areas mm^2.
"""

from .layers import LayerSizing, size_layers
from .sizing import DISTRIBUTIONS, DeviceSizing, SizingCurve, damping_curve, size_devices, size_walls

__all__ = ["DISTRIBUTIONS", "DeviceSizing", "LayerSizing", "SizingCurve", "damping_curve", "size_devices",
           "size_layers", "size_walls"]
