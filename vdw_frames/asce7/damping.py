"""ASCE 7-16 Chapter 18 (structures with damping systems): the damping coefficient B and the SFRS's minimum base shear.

Sources, and what was read (searched in stored copies of the standard and its extracts; never the
standard's own printed table):

* **Table 18.7-1**, the damping coefficient B_V+I, B_1D, B_1E, B_R, B_1M, B_mD, B_mM "(where period of the
  structure >= T_0)".  READ (ASCE 7-16 Sec. 18.1.3 notation, a copy of the 2016 Chapter 18): "B_V+I = numerical
  coefficient as set forth in Table 18.7-1 for effective damping equal to the sum of viscous damping in the
  fundamental mode of vibration of the structure in the direction of interest, beta_Vm (m = 1), plus inherent
  damping, beta_I, and period of structure equal to T_1".  NOT READ: the table's cells and its interpolation
  note; the values below are as RECALLED from ASCE 7-05 Table 18.6-1 / ASCE 7-10 and 7-16 Table 18.7-1 (the same
  cells in the three editions, as recalled): effective damping (percent of critical) <= 2: 0.8; 5: 1.0;
  10: 1.2; 20: 1.5; 30: 1.8; 40: 2.1; 50: 2.4; 60: 2.7; 70: 3.0; 80: 3.3; 90: 3.6; >= 100: 4.0, with linear
  interpolation between the printed damping values (as recalled: "interpolation shall be used for intermediate
  values").  Check the cells against the standard before relying on them.
* **Sec. 18.2.1.1** (minimum base shear of the seismic force-resisting system).  READ: the 2016 extract's Sec.
  18.2.1, "The seismic force-resisting system shall have the required strength to meet the forces defined in
  Section 18.2.1.1", and the ASCE 7-22 commentary C18.2.1: the SFRS without the damping system "must be designed
  to have not less than 75% of the strength required for structures without a DS that have that type of SFRS
  (and not less than 100% if the structure is horizontally or vertically irregular)".  NOT READ (recalled from
  ASCE 7-16): Eq. 18.2-1 V_min = max(V / B_V+I, 0.75 V), and its exception -- V_min not less than 1.0 V where, in
  the direction of interest, the damping system has fewer than two damping devices on each floor level
  configured to resist torsion, or the SFRS has horizontal irregularity Type 1b (Table 12.3-1) or vertical
  irregularity Type 1b (Table 12.3-2).  Which of these applies is the user's statement (``irregular=True``).

Units: damping ratios dimensionless (0.2 = 20 % of critical), base shears in any one force unit (N in this
package).
"""

from __future__ import annotations

import numpy as np

from .._validation import finite_scalar, non_negative, show

DAMPING_TABLE = (
    (0.02, 0.8), (0.05, 1.0), (0.10, 1.2), (0.20, 1.5), (0.30, 1.8), (0.40, 2.1), (0.50, 2.4), (0.60, 2.7),
    (0.70, 3.0), (0.80, 3.3), (0.90, 3.6), (1.00, 4.0),
)
"""ASCE 7-16 Table 18.7-1 (effective damping as a ratio, B): the first row is "<= 2 %", the last ">= 100 %".
The cells are as RECALLED, not read from the standard (module docstring)."""

MINIMUM_SHEAR_FRACTION = 0.75
"""ASCE 7-16 Sec. 18.2.1.1 (Eq. 18.2-1 as recalled; 75 % confirmed by the ASCE 7-22 commentary C18.2.1): the
reduced SFRS keeps at least 0.75 V."""

V_MIN_RULES = ("V / B_V+I", "0.75 V", "1.0 V (irregular)")
"""The three cases of :func:`minimum_base_shear`'s rule, as it names them."""


def damping_coefficient(effective_damping: float) -> float:
    """B of ASCE 7-16 Table 18.7-1 at ``effective_damping`` (-, a ratio of critical: 0.20 = 20 %).

    <= 0.02 gives 0.8 and >= 1.0 gives 4.0 (the table's first and last rows); between printed values B is
    interpolated linearly in the damping ratio (the table's note, as recalled).  The cells are as recalled,
    not read (module docstring).  ValueError for a negative or non-finite value.
    """
    beta = non_negative("effective_damping", effective_damping)
    dampings, coefficients = zip(*DAMPING_TABLE, strict=True)
    return float(np.interp(beta, dampings, coefficients))


def minimum_base_shear(v: float, b_v_plus_i: float, irregular: bool = False) -> tuple[float, str]:
    """(V_min, rule): the SFRS's minimum base shear, ASCE 7-16 Sec. 18.2.1.1 (module docstring for what was read).

    ``v``: the Chapter 12 seismic base shear V of the structure without the damping system (N, > 0);
    ``b_v_plus_i``: B_V+I (Table 18.7-1, :func:`damping_coefficient`, >= 0.8); ``irregular``: True where the
    clause's exception applies (stated by the user: fewer than two devices a floor configured to resist torsion,
    or horizontal irregularity Type 1b / vertical irregularity Type 1b, as recalled).  V_min = max(V / B_V+I,
    0.75 V), or 1.0 V when irregular.  ``rule`` names the case: one of :data:`V_MIN_RULES`.
    """
    shear = finite_scalar("v", v)
    if shear <= 0.0:
        raise ValueError(f"v (the seismic base shear V) must be > 0, got {show(v)}")
    b = finite_scalar("b_v_plus_i", b_v_plus_i)
    if b < DAMPING_TABLE[0][1]:
        raise ValueError(f"b_v_plus_i must be a Table 18.7-1 coefficient (>= {DAMPING_TABLE[0][1]}), got "
                         f"{show(b_v_plus_i)}")
    if not isinstance(irregular, (bool, np.bool_)):
        raise ValueError(f"irregular must be True or False, got {show(irregular)}")
    if irregular:
        return shear, V_MIN_RULES[2]
    reduced, floor = shear / b, MINIMUM_SHEAR_FRACTION * shear
    return (reduced, V_MIN_RULES[0]) if reduced >= floor else (floor, V_MIN_RULES[1])
