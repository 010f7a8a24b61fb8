"""FDMK walls in OpenSeesPy models: :class:`WallBridge` (exact) and :func:`prony_material` (approximate).

The short name of :mod:`vdw_frames.interop.opensees`, where everything is documented.  OpenSeesPy is an
optional dependency (``pip install 'vdw-frames[opensees]'``).
"""

from .interop.opensees import WallBridge, opensees_module, prony_material

__all__ = ["WallBridge", "opensees_module", "prony_material"]
