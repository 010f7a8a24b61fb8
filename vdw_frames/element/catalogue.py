"""The catalogue of identified wall parameters: the recommended FDMK sets of the paper's three strain levels
and the strain-dependent family, as numbers, and the walls they make.

The numbers were identified from the paper's Tables 1-3 (Xu, Li & Shen 2016) by
:mod:`vdw_frames.paper.identification` and :mod:`vdw_frames.paper.strain_dependence`, which document how and
re-export everything here under their old names (``vdw_frames.paper.fitted``,
``vdw_frames.paper.strain_dependence.strain_dependent``, ...).  They live here, with the element, so that
reading a building file (:mod:`vdw_frames.config`) needs neither the identification nor scipy.optimize;
``tests/paper`` re-run the identification and check that it reproduces them.

Units: moduli MPa, viscosities MPa*s^r, areas mm^2, thicknesses mm; strains in % in ``STRAINS`` and
``FIT_RANGE``, dimensionless (3.0 = 300 %) in the strain-dependent nodes.
"""

from __future__ import annotations

from typing import Any

from .damper import FDMKDamper
from .strain_dependent import StrainDependentDamper

STRAINS = (225, 300, 450)  # the paper's test strain amplitudes, %
AREA = 1.0e6  # total shear area A, mm^2 (the paper, after its eq. (10))
THICKNESS = 10.0  # thickness h of one viscoelastic layer, mm (the paper)

FITTED = {  # identify(*table_moduli(strain), residual="relative").params, to full precision
    225: {"G1": 0.0, "G2": 1.345063289561554, "eta1": 0.017660063643352687, "eta2": 0.365874967763888,
          "r": 1.0},
    300: {"G1": 0.0, "G2": 2.629620360282735, "eta1": 0.03553163240054065, "eta2": 1.9554766033255833,
          "r": 0.5891742702867667},
    450: {"G1": 1.873862947265929, "G2": 1.2119939259478345, "eta1": 0.052314549243817524,
          "eta2": 0.7978350638064874, "r": 0.46424699522808816},
}

FIT_RANGE = {225: (225.0, 262.5), 300: (262.5, 375.0), 450: (375.0, 450.0)}  # shear strain, %

STRAIN_DEPENDENT = {  # identify_strain_dependent().nodes, to full precision; strains dimensionless
    "strains": (2.25, 3.0, 4.5),
    "G1": (0.0, 0.48474795816470173, 2.089158947418294),
    "G2": (1.3164522510416001, 2.0540349707987264, 1.0221180408839328),
    "eta1": (0.01779753897235117, 0.023724302048879913, 0.031172868351328663),
    "eta2": (0.3121840162436633, 1.0428713796296716, 0.4900621894880103),
    "r": (1.0, 0.6839119697160516, 0.5528706313617792),
}

STRAIN_DEPENDENT_COMMON = {  # identify_strain_dependent(common_order=True).nodes: one r for every amplitude
    "strains": (2.25, 3.0, 4.5),
    "G1": (0.0, 0.8969052081005391, 2.3590971351601246),
    "G2": (1.3380785350046127, 1.6163068776846077, 0.6926273736286789),
    "eta1": (0.032287150788946825, 0.01353131459927258, 0.01026816739961604),
    "eta2": (0.44201165724089975, 0.5147667815855544, 0.16433035190061754),
    "r": (0.8222114475469737, 0.8222114475469737, 0.8222114475469737),
}


def strain_key(strain: float) -> int:
    """The paper's strain level (225, 300 or 450, %) that ``strain`` names; ValueError otherwise."""
    for key in STRAINS:
        try:
            if float(strain) == key:
                return key
        except (TypeError, ValueError):
            break
    raise ValueError(f"strain must be one of the paper's strain levels {STRAINS} (%), got {strain!r}")


def fitted(strain: float, area: float = AREA, thickness: float = THICKNESS) -> FDMKDamper:
    """The recommended FDMK damper for the paper's strain level ``strain`` (225, 300 or 450 %).

    Parameters from ``FITTED``: the global minimum of objective (12) with relative residuals,
    sum of ((G'_model - G'_test)/G'_test)^2 + ((G''_model - G''_test)/G''_test)^2 over that strain's
    six frequencies (why relative: :mod:`vdw_frames.paper.data`).  Fit quality
    (``vdw_frames.paper.FIT_QUALITY``): SSE 1.520 / 0.3213 / 0.1579 and max |relative error| in G'
    78.6 / 29.6 / 27.0 % and in G'' 34.3 / 15.7 / 6.0 % at 225 / 300 / 450 %.  Shear area ``area`` (mm^2)
    and layer thickness ``thickness`` (mm) default to the paper's.  The damper's ``strain_range`` is
    ``FIT_RANGE[strain]`` as fractions (3.0 = 300 %), so simulations warn outside it.
    """
    key = strain_key(strain)
    low, high = FIT_RANGE[key]
    p = FITTED[key]
    return FDMKDamper(G1=p["G1"], G2=p["G2"], eta1=p["eta1"], eta2=p["eta2"], r=p["r"], area=area, thickness=thickness,
                      strain_range=(low / 100.0, high / 100.0))


def strain_dependent(area: float = AREA, thickness: float = THICKNESS, common_order: bool = True,
                     **wall_options: Any) -> StrainDependentDamper:
    """The paper's wall as a strain-dependent FDMK model over 225-450 %.

    Parameters piecewise linear in log(strain) between the tested strains 225, 300 and 450 %, from the
    joint identification of Tables 1-3 (:mod:`vdw_frames.paper.strain_dependence`).  ``common_order``
    (default): one r = 0.822 for every amplitude (``STRAIN_DEPENDENT_COMMON``), what a time-domain analysis
    that follows the amplitude needs; its objective is 1.22 / 1.05 / 1.08 times the free-r family's at
    225 / 300 / 450 % (``vdw_frames.paper.strain_dependence.COMMON_ORDER_COST``).  ``common_order=False``:
    r free at each node (``STRAIN_DEPENDENT``, r = 1.0 / 0.68 / 0.55), for the strain-compatible
    (equivalent-linear) analysis only.  Shear area ``area`` (mm^2) and layer thickness ``thickness`` (mm)
    default to the paper's; ``wall_options`` (``thermal``, ``limits``) go to the wall.  Amplitudes outside
    225-450 % are clamped.
    """
    nodes = STRAIN_DEPENDENT_COMMON if common_order else STRAIN_DEPENDENT
    return StrainDependentDamper.from_nodes(nodes, area=area, thickness=thickness, **wall_options)
