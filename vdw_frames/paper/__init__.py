"""The paper (Xu, Li & Shen 2016): its printed data, parameter identification, and the reproduction report.

- :mod:`.data`: Tables 1-5 as printed, the printed closed forms (not the model), and the recommended
  parameter sets :func:`fitted` identified from Tables 1-3;
- :mod:`.identification`: :func:`identify`, the global fit of eqs. (3)-(5) to measured moduli;
- :mod:`.strain_dependence`: :func:`strain_dependent`, one strain-dependent model from Tables 1-3 jointly;
- :mod:`.errata`: the errata and every number of the reproduction report, computed;
- :mod:`.report`: :func:`write_paper_report`, the reproduction report (rendering).

Units: moduli MPa, viscosities MPa*s^r, frequencies Hz, strains in % where the paper uses %.
"""

from .data import (
    AREA,
    COLUMN_UNITS,
    FIT_QUALITY,
    FIT_RANGE,
    FITTED,
    FREQUENCIES,
    RECOMMENDED_RESIDUAL,
    STRAINS,
    TABLE4,
    TABLE5,
    TABLES,
    TEMPERATURE,
    THICKNESS,
    fitted,
    printed_eq7_modulus,
    printed_eq8_moduli,
    printed_eq9_loss_factor,
    printed_eq10_stiffness,
    printed_eq11_damping_coefficient,
    table_moduli,
)
from .identification import IdentificationResult, identify
from .report import write_paper_report
from .strain_dependence import (
    STRAIN_DEPENDENT,
    STRAIN_DEPENDENT_QUALITY,
    StrainDependenceResult,
    identify_strain_dependent,
    interpolated_moduli,
    strain_dependent,
)

__all__ = [
    "AREA", "COLUMN_UNITS", "FITTED", "FIT_QUALITY", "FIT_RANGE", "FREQUENCIES", "RECOMMENDED_RESIDUAL",
    "STRAINS", "STRAIN_DEPENDENT", "STRAIN_DEPENDENT_QUALITY", "TABLE4", "TABLE5", "TABLES", "TEMPERATURE",
    "THICKNESS", "IdentificationResult", "StrainDependenceResult", "fitted", "identify",
    "identify_strain_dependent", "interpolated_moduli", "printed_eq7_modulus", "printed_eq8_moduli",
    "printed_eq9_loss_factor", "printed_eq10_stiffness", "printed_eq11_damping_coefficient",
    "strain_dependent", "table_moduli", "write_paper_report",
]
