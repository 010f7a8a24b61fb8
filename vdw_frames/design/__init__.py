"""Design with walls: what they add to the frame's modes, and how many are needed.

- :mod:`.modal`: :func:`modal_analysis` (also ``ShearBuilding.modal_analysis``), the complex modes of the
  linear building with its frequency-dependent walls (a nonlinear eigenproblem solved by Newton and
  checked complete by the argument principle), with the design-code energy estimate beside it;
  :class:`ModalResult`;
- :mod:`.sizing`: :func:`size_walls` (walls for a target damping ratio of one mode),
  :func:`damping_curve` (:class:`SizingCurve`: period and damping ratio against the wall size).

Units: N, mm, s, tonne; poles rad/s, periods s, areas mm^2.
"""

from .modal import ModalResult, modal_analysis
from .sizing import DISTRIBUTIONS, SizingCurve, damping_curve, resized, size_walls

__all__ = ["DISTRIBUTIONS", "ModalResult", "SizingCurve", "damping_curve", "modal_analysis", "resized", "size_walls"]
