"""The report of a design verification: Markdown text and CSV tables of a
:class:`~vdw_frames.verification.verify.VerificationResult` (the CLI writes them with the package's atomic writer
and draws the figures with :mod:`vdw_frames.plotting.verification`).

Units in the tables' headers: s, g, -, mm, mm/s, N, N mm, K.
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Mapping

import numpy as np

from ..motion.record import G
from .suite import MEAN_FRACTION
from .verify import ALLOWABLE_DRIFT, DRIFT_CLAUSE, DRIFT_FACTOR, MEDIAN_FACTOR, WALL_PEAKS, VerificationResult


def _csv(rows: list[list[object]]) -> str:
    handle = io.StringIO(newline="")
    csv.writer(handle).writerows(rows)
    return handle.getvalue()


def suite_csv(result: VerificationResult) -> str:
    """One row per record: name, amplitude factor, shape misfit, PGA of the scaled record (g)."""
    suite = result.suite
    rows: list[list[object]] = [["record", "factor", "shape_misfit", "scaled_pga_g"]]
    for motion, factor, misfit in zip(suite.motions, suite.factors, suite.misfits, strict=True):
        rows.append([motion.name, repr(float(factor)), repr(float(misfit)), repr(float(factor) * motion.pga / G)])
    return _csv(rows)


def spectra_csv(result: VerificationResult) -> str:
    """One row per period of the grid: target, suite mean (g) and their ratio."""
    suite = result.suite
    rows: list[list[object]] = [["period_s", "target_g", "mean_g", "mean_over_target"]]
    for t, target, mean in zip(suite.periods, suite.target, suite.mean_spectrum, strict=True):
        rows.append([repr(float(t)), repr(float(target / G)), repr(float(mean / G)), repr(float(mean / target))])
    return _csv(rows)


def drifts_csv(result: VerificationResult) -> str:
    """One row per case, record and story: peak drift ratio, outcome and the reasons it is unacceptable."""
    rows: list[list[object]] = [["case", "lambda", "record", "story", "peak_drift_ratio", "collapsed", "converged",
                                 "unacceptable"]]
    for c, (case, factor) in enumerate(result.cases):
        for r, motion in enumerate(result.suite.motions):
            for k, ratio in enumerate(result.peak_drift_ratio[c, r]):
                rows.append([case, repr(factor), motion.name, k + 1, repr(float(ratio)), int(result.collapsed[c, r]),
                             int(result.converged[c, r]), result.unacceptable[c][r]])
    return _csv(rows)


def walls_csv(result: VerificationResult) -> str:
    """One row per wall: the test demands over the suite and the bounds (Sec. 18.6), each the largest over every
    case and record; ``strain_fraction``: the shear strain as a fraction (mm/mm; 5.44 is 544 %); then, per
    quantity, ``governing_<quantity>``: the "case, record" it came from (``governing_deformation`` is
    :attr:`~vdw_frames.verification.verify.WallDemand.governing`; empty where the wall does not heat)."""
    rows: list[list[object]] = [["wall", "story", "deformation_mm", "strain_fraction", "velocity_mm_s", "force_N",
                                 "cycle_energy_Nmm", "cumulative_energy_Nmm", "temperature_rise_K",
                                 *(f"governing_{name}" for name in WALL_PEAKS)]]
    for w in result.walls:
        rows.append([w.wall + 1, w.story, repr(w.deformation), repr(w.strain), repr(w.velocity), repr(w.force),
                     repr(w.cycle_energy), repr(w.cumulative_energy),
                     "" if w.temperature_rise is None else repr(w.temperature_rise),
                     *(result.wall_governing(name, w.wall) for name in WALL_PEAKS)])
    return _csv(rows)


def devices_csv(result: VerificationResult) -> str:
    """One row per device that is not a wall and per case: its largest force, deformation and velocity over the
    suite at that bound (:class:`~vdw_frames.verification.verify.DeviceDemand`)."""
    rows: list[list[object]] = [["device", "story", "description", "velocity_dependent", "case", "lambda", "force_N",
                                 "deformation_mm", "velocity_mm_s"]]
    for d in result.devices:
        for case, factor in result.cases:
            rows.append([d.device + 1, d.story, d.description, int(d.velocity_dependent), case, repr(factor),
                         repr(d.force[case]), repr(d.deformation[case]), repr(d.velocity[case])])
    return _csv(rows)


def device_rows(result: VerificationResult) -> list[str]:
    """The devices' demands as the CLI prints them: one line per device and case (kN, mm, mm/s)."""
    lines = [f"{'device':>6s} {'story':>5s} {'case':>8s} {'force kN':>9s} {'deform. mm':>10s} {'vel. mm/s':>9s}  "
             "device (nominal)"]
    for d in result.devices:
        for case, _ in result.cases:
            lines.append(f"{d.device + 1:6d} {d.story:5d} {case:>8s} {d.force[case] / 1e3:9.1f} "
                         f"{d.deformation[case]:10.2f} {d.velocity[case]:9.1f}  {d.description}")
    return lines


def markdown(result: VerificationResult, figures: Mapping[str, str], title: str) -> str:
    """The report: site, suite, bounds, each criterion with pass/fail, the drift table, the wall demands and the
    prototype test specification; ``figures`` maps a caption to a file name relative to the report."""
    site, suite = result.site, result.suite
    category = site.risk_category
    lines = [f"# {title}", "",
             f"**Result: {'PASS' if result.passed else 'FAIL'}** "
             f"({sum(c.passed for c in result.criteria)} of {len(result.criteria)} criteria pass)", "",
             "ASCE 7-16 was not at hand: every clause below was read from secondary sources (transcriptions, "
             "implementers' code, the committee chair's slides); Table 12.12-1 and the Chapter 18 provisions were "
             "not read at all (see the package documentation, `vdw_frames.verification`).  Sec. 16.2.3.1, "
             "16.2.3.2 and 16.4.1.2 were read in a transcription of their ASCE 7-22 wording (believed the same in "
             "substance for 7-16, not verified) and are cited so; Sec. 16.4.1.1's count for Risk Category I-II in the "
             "ASCE 7-16 chair's slides (Hamburger 2014), for III-IV recalled.", "",
             "## Site and target (Sec. 11.4)", "", f"- {site.describe()}", "",
             "## Suite (Sec. 16.2)", "",
             f"- {suite.range.describe()}",
             f"- {len(suite.motions)} records chosen from {suite.candidates} by the smallest misfit of spectral shape; "
             f"each scaled by its own best-fit factor times one common factor, the smallest for which the mean is "
             f">= {100 * MEAN_FRACTION:.0f} % of the target at every one of {suite.periods.size} periods of the range "
             f"(Sec. 16.2.3.2, read in ASCE 7-22 wording; governing at T = {suite.governing_period:.3f} s; smallest "
             f"ratio {suite.ratio.min():.4f})",
             f"- {suite.component_note}", "",
             "| record | factor | misfit | scaled PGA (g) |", "|---|---|---|---|"]
    for motion, factor, misfit in zip(suite.motions, suite.factors, suite.misfits, strict=True):
        lines.append(f"| {motion.name} | {factor:.3f} | {misfit:.3f} | {factor * motion.pga / G:.3f} |")
    lines += ["", "## Property bounds (Sec. 18.2.4.5)", "",
              f"- lambda_min = {result.bounds.lower:g}, lambda_max = {result.bounds.upper:g} ({result.bounds.source}); "
              "every wall's moduli and viscosities times lambda (`wall.scaled`)"
              + ("; every fluid viscous damper's C and every friction damper's slip force times lambda "
                 "(`device.scaled`: the upper bound gives the largest device forces, the lower usually the "
                 "largest displacements)" if result.devices else "")]
    included = {True: "include", False: "do not include", None: "are not stated to include or exclude"}
    lines.append(f"- the lambdas {included[result.bounds.lambda_includes_temperature]} the effect of temperature")
    if result.bounds.ambient is not None:
        cold, hot = result.bounds.ambient
        lines.append(f"- ambient {cold:g} to {hot:g} degC: each bound starts every wall (and heats it from there) at "
                     f"the end of the range that bounds its quantity at {1.0 / result.first_period:.3f} Hz -- the "
                     f"upper bound (forces) at the larger |K*|, here {result.ambient_range('upper')}; the lower bound "
                     f"(displacements) at the smaller K'', here {result.ambient_range('lower')}; a temperature changes "
                     "K' and K'' by different factors")
    frequency = 1.0 / result.first_period
    lines += ["", f"| case | lambda | K' factor at {frequency:.3f} Hz | K'' factor at {frequency:.3f} Hz |",
              "|---|---|---|---|"]
    for c, (case, factor) in enumerate(result.cases):
        storage, loss = result.stiffness_factors[c, :, 0], result.stiffness_factors[c, :, 1]
        lines.append(f"| {case} | {factor:g} | {_span(storage)} | {_span(loss)} |")
    lines += ["",
              "## Acceptance (Sec. 16.4)", "",
              f"- Drift limit {DRIFT_FACTOR:g} x {ALLOWABLE_DRIFT[category]:g} h_sx = {result.drift_limit:.4f} "
              f"(all other structures, Risk Category {category}): {DRIFT_CLAUSE}; "
              f"{result.allowed_unacceptable} unacceptable response(s) allowed per suite",
              f"- Drift statistic per story (Sec. 16.4.1.2, read in ASCE 7-22 wording): the mean of the suite's "
              f"peak drift ratios where every response is acceptable; where some are not, max(mean, "
              f"{MEDIAN_FACTOR:g} x median) of the acceptable records only; where none is, the mean of all, the "
              "unacceptable ones included (this package's fallback, not read in the clause's transcription). "
              "Here: " + "; ".join(f"{case}, {result.drift_statistic_basis(case)}" for case, _ in result.cases),
              "",
              "| criterion | clause | result | value | limit | governing |", "|---|---|---|---|---|---|"]
    for criterion in result.criteria:
        lines.append(f"| {criterion.name} | {criterion.clause} | {'pass' if criterion.passed else 'FAIL'} | "
                     f"{criterion.value:.4g} | {criterion.limit:.4g} | {criterion.governing} |")
    lines += ["", "| story | " + " | ".join(f"{case}: {result.drift_statistic_basis(case)} (%)"
                                           for case, _ in result.cases) + " |",
              "|---" * (len(result.cases) + 1) + "|"]
    for k in range(result.drift_statistic.shape[1]):
        lines.append(f"| {k + 1} | " + " | ".join(f"{100 * v:.3f}" for v in result.drift_statistic[:, k]) + " |")
    lines += ["", "## Device test demands (Sec. 18.6)", "", *_wall_lines(result)]
    if result.devices:
        lines += ["", "Other devices: the largest force, deformation and velocity along each device over the suite, "
                  "at each bound (velocity-dependent: force a function of the velocity, ASCE 7-16 Sec. 18.1).", "",
                  "| device | story | description | case | force (kN) | deformation (mm) | velocity (mm/s) |",
                  "|---" * 7 + "|"]
        for d in result.devices:
            for case, _ in result.cases:
                lines.append(f"| {d.device + 1} | {d.story} | {d.description} | {case} | {d.force[case] / 1e3:.1f} | "
                             f"{d.deformation[case]:.2f} | {d.velocity[case]:.1f} |")
    lines += ["", result.specification, ""]
    if any(any(row) for row in result.unacceptable):
        lines += ["## Unacceptable responses", ""]
        for index, (case, _) in enumerate(result.cases):
            for r, reason in enumerate(result.unacceptable[index]):
                if reason:
                    lines.append(f"- {case}, {suite.motions[r].name}: {reason}")
        lines.append("")
    for caption, name in figures.items():
        lines += [f"![{caption}]({name})", "", f"*{caption}*", ""]
    lines += [f"Files: suite.csv, spectra.csv, drifts.csv, walls.csv{', devices.csv' if result.devices else ''}.",
              f"Largest single peak drift ratio: {100 * float(np.max(result.peak_drift_ratio)):.3f} %.", ""]
    return "\n".join(lines)


def _wall_lines(result: VerificationResult) -> list[str]:
    """The walls' test demands: a note on what each column is, the table, how the temperatures were computed."""
    cases, records = len(result.cases), len(result.suite.motions)
    lines = [f"Each wall's largest values over all {cases * records} analyses ({cases} cases x {records} records, "
             "unacceptable ones included), each column from the case and record that gave it: the last column "
             "names those of the largest deformation only; walls.csv names every column's (governing_*).", ""] \
        if result.walls else []
    lines += ["| wall | story | deformation (mm) | strain (%) | velocity (mm/s) | force (kN) | energy/cycle (kN m) | "
              "cumulative (kN m) | temperature rise (K) | largest deformation in (case, record) |", "|---" * 10 + "|"]
    for w in result.walls:
        rise = "-" if w.temperature_rise is None else f"{w.temperature_rise:.1f}"
        lines.append(f"| {w.wall + 1} | {w.story} | {w.deformation:.1f} | {100 * w.strain:.0f} | {w.velocity:.0f} | "
                     f"{w.force / 1e3:.1f} | {w.cycle_energy / 1e6:.2f} | {w.cumulative_energy / 1e6:.2f} | {rise} | "
                     f"{w.governing} |")
    heating = _heating_note(result)
    return lines + (["", heating] if heating else [])


def _heating_note(result: VerificationResult) -> str:
    """How the walls' temperature rises were computed: adiabatic (no cooling time) or cooling towards the ambient
    with a time constant (s), per wall that heats; "" without such walls."""
    heating = [w for w in result.walls if w.temperature_rise is not None and w.cooling_time is not None]
    if not heating:
        return ""
    adiabatic = [w for w in heating if math.isinf(w.cooling_time or 0.0)]
    cooled = [w for w in heating if not math.isinf(w.cooling_time or 0.0)]
    parts = []
    if adiabatic:
        which = "every wall" if len(adiabatic) == len(result.walls) else \
            "wall(s) " + ", ".join(str(w.wall + 1) for w in adiabatic)
        parts.append(f"adiabatic for {which} (no cooling in the thermal description: cooling time infinite), so "
                     "all the heat stays in the viscoelastic layers -- an upper bound of the rise")
    parts += [f"wall {w.wall + 1} cooling towards its ambient with time constant {w.cooling_time:.3g} s"
              for w in cooled]
    return "Temperature rises: " + "; ".join(parts) + "."


def _span(values: np.ndarray) -> str:
    """'a' or 'a-b': the range of the walls' factors ('-' without walls)."""
    if len(values) == 0:
        return "-"
    low, high = float(min(values)), float(max(values))
    return f"{low:.3f}" if abs(high - low) < 5e-4 else f"{low:.3f}-{high:.3f}"
