"""ASCE 7 in one place: the standard's tables and formulas used by design and assessment, pure functions.

- :mod:`.systems`: seismic force-resisting systems (:class:`SeismicSystem`, :data:`SYSTEMS`: ASCE 7-16
  Table 12.2-1 R, Omega_0, C_d, height limits; Table 12.8-2 C_t, x);
- :mod:`.elf`: the equivalent lateral force procedure of ASCE 7-16 Chapter 12 (Sec. 12.8) with Tables 1.5-2,
  11.6-1/2, 12.8-1 and 12.12-1;
- :mod:`.damping` (Chapter 18): :func:`damping_coefficient` (B, Table 18.7-1), :func:`minimum_base_shear`
  (V_min, Sec. 18.2.1.1).

Every value carries its table, row or equation.  Units: g, s, N, mm (ft only inside Eq. 12.8-7).
"""

from .damping import DAMPING_TABLE, MINIMUM_SHEAR_FRACTION, V_MIN_RULES, damping_coefficient, minimum_base_shear
from .elf import (
    ALLOWABLE_DRIFT_RATIOS,
    FT,
    IMPORTANCE_FACTORS,
    RISK_CATEGORIES,
    THETA_AMPLIFY,
    UPPER_LIMIT_COEFFICIENTS,
    allowable_story_drift_ratio,
    approximate_period,
    check_stability,
    default_redundancy_factor,
    design_displacement,
    design_drift_limit_divisor,
    distribution_exponent,
    importance_factor,
    p_delta_amplification,
    risk_category,
    seismic_design_category,
    seismic_response_coefficient,
    stability_coefficient,
    theta_max,
    upper_limit_coefficient,
    vertical_distribution,
)
from .systems import PERIOD_PARAMETERS, PERIOD_ROWS, SDC_LETTERS, SYSTEMS, SeismicSystem, seismic_system

__all__ = [
    "ALLOWABLE_DRIFT_RATIOS",
    "DAMPING_TABLE",
    "FT",
    "IMPORTANCE_FACTORS",
    "MINIMUM_SHEAR_FRACTION",
    "PERIOD_PARAMETERS",
    "PERIOD_ROWS",
    "RISK_CATEGORIES",
    "SDC_LETTERS",
    "SYSTEMS",
    "THETA_AMPLIFY",
    "UPPER_LIMIT_COEFFICIENTS",
    "V_MIN_RULES",
    "SeismicSystem",
    "allowable_story_drift_ratio",
    "approximate_period",
    "check_stability",
    "damping_coefficient",
    "default_redundancy_factor",
    "design_displacement",
    "design_drift_limit_divisor",
    "distribution_exponent",
    "importance_factor",
    "minimum_base_shear",
    "p_delta_amplification",
    "risk_category",
    "seismic_design_category",
    "seismic_response_coefficient",
    "seismic_system",
    "stability_coefficient",
    "theta_max",
    "upper_limit_coefficient",
    "vertical_distribution",
]
