"""Interoperability with other structural programs.

- :mod:`.opensees`: FDMK walls inside any OpenSeesPy model, exactly (:class:`~.opensees.WallBridge`), and
  a wall's Prony series as a native OpenSees material (:func:`~.opensees.prony_material`), fluid viscous and
  friction dampers as OpenSees's own ``ViscousDamper`` / ``Viscous`` / ``ElasticPP`` materials
  (:func:`~.opensees.device_material`, :func:`~.opensees.device_element`).  OpenSeesPy is an
  optional dependency (``pip install 'vdw-frames[opensees]'``), imported only when a bridge is built without an ``ops``.
"""
