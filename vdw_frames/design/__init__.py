"""Design with walls: how many are needed for a target damping ratio.

- :mod:`.sizing`: :func:`size_walls` (walls for a target damping ratio of one mode),
  :func:`damping_curve` (:class:`SizingCurve`: period and damping ratio against the wall size), both
  from the complex modes of :func:`vdw_frames.frame.modal_analysis`.

Units: N, mm, s, tonne; periods s, areas mm^2.
"""

from .sizing import DISTRIBUTIONS, SizingCurve, damping_curve, size_walls

__all__ = ["DISTRIBUTIONS", "SizingCurve", "damping_curve", "size_walls"]
