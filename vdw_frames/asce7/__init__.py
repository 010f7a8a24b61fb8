"""ASCE 7-16 tables and formulas, pure functions (each cites its clause and says what was read).

- :mod:`.damping` (Chapter 18): :func:`damping_coefficient` (B, Table 18.7-1), :func:`minimum_base_shear`
  (V_min, Sec. 18.2.1.1).
"""

from .damping import DAMPING_TABLE, MINIMUM_SHEAR_FRACTION, V_MIN_RULES, damping_coefficient, minimum_base_shear

__all__ = ["DAMPING_TABLE", "MINIMUM_SHEAR_FRACTION", "V_MIN_RULES", "damping_coefficient", "minimum_base_shear"]
