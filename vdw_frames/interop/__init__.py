"""Interoperability with other structural programs.

- :mod:`.opensees`: FDMK walls inside any OpenSeesPy model, exactly (:class:`~.opensees.WallBridge`), and
  a wall's Prony series as a native OpenSees material (:func:`~.opensees.prony_material`).  OpenSeesPy is an
  optional dependency (``pip install 'vdw-frames[opensees]'``), imported only when a bridge is built without an ``ops``.
"""
