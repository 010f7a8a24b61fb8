"""The design note of a code design: :func:`write_design_report` writes, into one folder,

- ``building.toml``: the designed building (frame and devices) with its ``[site]`` and, for a damped design (or
  when bounds are given), its ``[verification]`` bounds: ``vdw-frames simulate``, ``verify`` and ``collapse``
  read it (:func:`vdw_frames.config.save_building`);
- ``design.md``: the ELF table (ASCE 7-16 Sec. 12.8), the Chapter 18 reduction, the device schedule with the
  verification's peak demands, every verification round, the FEMA P695 result (with the statement that one
  archetype is not a system qualification), the times and every assumption;
- CSV tables: ``elf.csv`` (one row a story), ``devices.csv`` (one row a device, if any) and ``rounds.csv`` (one row a
  verification round); the final verification's ``verification_suite.csv``, ``verification_drifts.csv``,
  ``verification_walls.csv`` and ``verification_devices.csv`` (the tables ``vdw-frames verify`` writes as
  ``suite.csv``, ``drifts.csv``, ...);
- figures: ``design_profiles.png`` (story shears and drifts against their limits) and, with a verification,
  ``drift_spread.png`` (each bound's peak drift ratios over the records against the limit) and
  ``story_drifts.png``.

Every file is written atomically (:mod:`vdw_frames._files`); files of other names in the folder are left alone.
Units: N, mm, s, tonne (kN in the figures).

This module sits above :mod:`vdw_frames.design`, :mod:`vdw_frames.config` and :mod:`vdw_frames.plotting`, beside
the command line that calls it: the design note needs the building-file writer and the figures, which themselves
read the design's records.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ._files import output_folder, write_csv, write_text
from .config import save_building
from .design.damped import DampedDesign, p695_basis
from .design.elf import FrameDesign
from .frame.building import ShearBuilding, is_wall
from .plotting.design import plot_design_profiles, plot_drift_spread
from .plotting.verification import plot_story_drifts
from .verification import report as verification_report

if TYPE_CHECKING:
    from .assessment.collapse import CollapseAssessment
    from .verification.verify import PropertyBounds, VerificationResult

BUILDING_FILE = "building.toml"
"""The designed building's file name in the report folder."""

P695_STATEMENT = ("One archetype is not a FEMA P695 system qualification: P695 (Chapter 7) qualifies a system by "
                  "performance groups of archetypes; this is the collapse assessment of this one design.")


SCHEDULE_UNITS = ("Units of the devices' parameters: walls G1, G2 MPa, eta1, eta2 MPa s^r, A mm^2, t mm; FVD C "
                  "N (s/mm)^alpha, K_b N/mm; friction F_s N, k N/mm; f the magnification (device deformation / "
                  "story drift, -); each to 4 significant digits (devices.csv and building.toml hold them "
                  "exactly).")
"""The line under the device schedule that gives its parameters' units (the descriptions print bare numbers)."""


def write_design_report(design: FrameDesign | DampedDesign, out_dir: str | os.PathLike[str], *,
                        title: str | None = None, bounds: PropertyBounds | None = None,
                        collapse: CollapseAssessment | None = None, records: str | None = None) -> Path:
    """Write the design note of ``design`` (a :class:`~vdw_frames.design.elf.FrameDesign`, the bare frame, or a
    :class:`~vdw_frames.design.damped.DampedDesign`) into the folder ``out_dir`` (module docstring: the files);
    returns the path of ``design.md``.

    ``bounds``: for a bare design, ``[verification]`` bounds for the building file, should devices be added to
    it later (a damped design's come from its verification).  ``collapse``: for a bare design, its FEMA P695
    assessment (a damped design carries its own).  ``records``: how the verification's records were given (a
    P695 set name or a folder), for the command that repeats it.  ValueError for a design of another type or a
    folder that cannot be written.
    """
    if not isinstance(design, (FrameDesign, DampedDesign)):
        raise ValueError(f"design must be a FrameDesign or a DampedDesign, got {type(design).__name__}")
    folder = output_folder(out_dir, "design report folder")
    damped = isinstance(design, DampedDesign)
    frame = design.frame if isinstance(design, DampedDesign) else design
    verification = design.verification if isinstance(design, DampedDesign) else None
    building = design.building
    if verification is not None:
        bounds = verification.bounds

    heading = title or (f"Design of a {frame.building.stories}-story frame ({frame.system.name.lower()}) "
                        + ("with damping devices by ASCE 7-16 Chapters 12 and 18" if damped else
                           "by ASCE 7-16 Chapter 12"))
    save_building(building, folder / BUILDING_FILE, site=frame.site, bounds=bounds,
                  comment=f"{heading}\nWritten by vdw_frames.design_report (vdw-frames design-building); units N, "
                          "mm, s, tonne.\nFormat: vdw_frames.config.")
    frame.save(folder / "elf.csv")
    schedule = device_rows(building, verification)
    if schedule:  # a bare frame has none
        write_csv(folder / "devices.csv", schedule, "device schedule")
    figures = {"design_profiles.png": "Story shears and strengths; design drifts against Delta_a / rho"}
    plot_design_profiles(frame, folder / "design_profiles.png")
    if isinstance(design, DampedDesign) and verification is not None:
        write_csv(folder / "rounds.csv", round_rows(design), "rounds table")
        tables = {"verification_suite.csv": verification_report.suite_csv(verification),
                  "verification_drifts.csv": verification_report.drifts_csv(verification)}
        if verification.walls:
            tables["verification_walls.csv"] = verification_report.walls_csv(verification)
        if verification.devices:
            tables["verification_devices.csv"] = verification_report.devices_csv(verification)
        for name, table in tables.items():  # as `vdw-frames verify` writes them (suite.csv, drifts.csv, ...)
            write_text(folder / name, table, "CSV file")
        plot_drift_spread(verification, folder / "drift_spread.png")
        plot_story_drifts(verification, folder / "story_drifts.png")
        figures["drift_spread.png"] = "Each bound's peak story drift ratios over the records against the limit"
        figures["story_drifts.png"] = "Peak story drift ratios per record and story, per bound"
    text = _markdown(design, frame, building, verification, heading, figures, bounds, collapse, records)
    return write_text(folder / "design.md", text, "design note")


def _size(device: object) -> dict[str, float | None]:
    """A device's sizes (units in the keys); None where the kind has no such size."""
    names = {"area_mm2": "area", "thickness_mm": "thickness", "c": "C", "alpha": "alpha", "slip_force_n": "slip_force",
             "stiffness_n_per_mm": "stiffness", "magnification": "magnification"}
    sizes: dict[str, float | None] = {}
    for key, name in names.items():
        value = getattr(device, name, None)
        sizes[key] = float(value) if isinstance(value, (int, float, np.floating)) else None
    return sizes


def device_rows(building: ShearBuilding, verification: VerificationResult | None = None) -> list[dict[str, Any]]:
    """The device schedule: one dict per device (story 1 first, in each story's order) with its kind, its sizes
    (wall area mm^2 and layer thickness mm; FVD C N (s/mm)^alpha, alpha and brace stiffness N/mm; friction
    slip force N and stiffness N/mm; magnification) and, with ``verification``, its largest demands over the
    suite and the bounds: deformation along the device (mm), velocity (mm/s), force (N), and for walls the
    shear strain (-) and temperature rise (K)."""
    walls = {demand.wall: demand for demand in verification.walls} if verification else {}
    others = {demand.device: demand for demand in verification.devices} if verification else {}
    rows = []
    wall_index = other_index = 0
    for story, device in building.device_list:
        row: dict[str, Any] = {"story": story, "kind": getattr(device, "kind", type(device).__name__),
                               "description": device.describe(), **_size(device)}
        demand: dict[str, float | None] = {"deformation_mm": None, "velocity_mm_s": None, "force_n": None,
                                           "strain": None, "temperature_rise_k": None}
        if is_wall(device):
            found = walls.get(wall_index)
            wall_index += 1
            if found is not None:
                demand.update(deformation_mm=found.deformation, velocity_mm_s=found.velocity, force_n=found.force,
                              strain=found.strain, temperature_rise_k=found.temperature_rise)
        else:
            other = others.get(other_index)
            other_index += 1
            if other is not None:
                demand.update(deformation_mm=max(other.deformation.values()),
                              velocity_mm_s=max(other.velocity.values()), force_n=max(other.force.values()))
        rows.append({**row, **demand})
    return rows


def round_rows(design: DampedDesign) -> list[dict[str, Any]]:
    """One dict per verification round of a damped design (units in the keys)."""
    rows = []
    for item in design.rounds:
        rows.append({
            "round": item.number, "target_damping": item.target_damping, "stiffness_factor": item.stiffness_factor,
            "effective_damping": item.effective_damping, "b_v_plus_i": item.b_v_plus_i, "v_n": item.v,
            "v_min_n": item.v_min, "v_min_rule": item.v_min_rule, "drift_statistic": item.drift_statistic,
            "drift_limit": item.drift_limit,
            **{f"unacceptable_{case}": count for case, count in item.unacceptable.items()},
            "allowed_unacceptable": item.allowed_unacceptable,
            "largest_limit_ratio": max((check.ratio for check in item.limits), default=None),
            "passed": item.passed, "seconds": item.seconds, "change": item.change, "failed": "; ".join(item.failed),
        })
    return rows


def _number(value: float | None, spec: str = ".4g") -> str:
    return "-" if value is None else format(value, spec)


def _schedule(rows: list[dict[str, Any]]) -> list[str]:
    """The device schedule as a markdown table."""
    if not rows:
        return ["No devices: the bare frame.", ""]
    lines = ["| story | device | deformation (mm) | velocity (mm/s) | force (kN) | strain (%) | temperature rise (K) |",
             "|---|---|---|---|---|---|---|"]
    for row in rows:
        force = None if row["force_n"] is None else row["force_n"] / 1e3
        strain = None if row["strain"] is None else 100.0 * row["strain"]
        lines.append(f"| {row['story']} | {row['description']} | {_number(row['deformation_mm'])} | "
                     f"{_number(row['velocity_mm_s'])} | {_number(force)} | {_number(strain)} | "
                     f"{_number(row['temperature_rise_k'])} |")
    return [*lines, "", SCHEDULE_UNITS, ""]


def _markdown(design: Any, frame: FrameDesign, building: ShearBuilding,  # noqa: PLR0917
              verification: VerificationResult | None, heading: str, figures: dict[str, str],
              bounds: PropertyBounds | None, collapse: CollapseAssessment | None, records: str | None) -> str:
    damped = verification is not None
    lines = [f"# {heading}", ""]
    if damped:
        verdict = "PASS" if design.passed else "FAIL"
        lines += [f"**Verdict: {verdict}** after {len(design.rounds)} verification round(s)"
                  + (f": {design.failure}" if design.failure else "."), ""]
    else:
        lines += ["The frame designed by the equivalent lateral force procedure alone: no damping devices and no "
                  "response-history verification (`vdw-frames verify` is for structures with devices; "
                  "`vdw-frames simulate` and `collapse` read the building file).", ""]
    rerun = f" --records {records}" if records else ""
    files = ["`building.toml` (the designed building: `vdw-frames simulate`, `verify` and `collapse` read it)",
             "`elf.csv`"]
    files += ["`devices.csv`"] if building.devices else []
    files += ["`rounds.csv`", "`verification_*.csv` (the final verification's tables)"] if damped else []
    lines += ["Files: " + ", ".join(files) + ", the figures below.", ""]
    left_out = design.rounds[-1].left_out if damped else ()
    if damped and not left_out:
        lines += [f"The final verification is repeated, independently, by `vdw-frames verify building.toml{rerun}` "
                  "(the site and the bounds are in the file).", ""]
    elif damped:
        lines += [f"The final verification left out {len(left_out)} candidate record(s) too short for its period "
                  f"range ({', '.join(left_out)}); `vdw-frames verify building.toml{rerun}` refuses them: it repeats "
                  "the verification with a set of records without them (the site and the bounds are in the file).", ""]
    lines += ["## Figures", ""]
    for name, caption in figures.items():
        lines += [f"![{caption}]({name})", ""]
    lines += [frame.table().replace("## Frame by", "## The frame by", 1), ""]
    if damped:
        undamped = design.undamped
        lines += [f"The same frame at 1.0 V (Chapter 12 without dampers, for the record): V = "
                  f"{undamped.base_shear / 1e3:.1f} kN, T_1 = {undamped.analytical_period:.3f} s, sum of story "
                  f"strengths {np.sum(undamped.strengths) / 1e3:.1f} kN (here {np.sum(frame.strengths) / 1e3:.1f} kN).",
                  ""]
    lines += ["## Device schedule", "",
              "Each device with its largest demands over the suite and the three property bounds (the verification's)."
              if damped else "", ""]
    lines += _schedule(device_rows(building, verification))
    if verification is not None:
        lines += [design.report(), "## The final verification (ASCE 7-16 Chapters 16 and 18)", ""]
        lines += [f"- {'pass' if c.passed else 'FAIL'}: {c.name}: {c.text}" for c in verification.criteria]
        lines += ["", f"Bounds: lambda {verification.bounds.lower:g} ... {verification.bounds.upper:g} "
                  f"({verification.bounds.source}).", ""]
    elif collapse is not None:
        lines += ["## FEMA P695", "",
                  f"- ACMR {collapse.acmr:.3f} vs ACMR20% {collapse.acmr20:.3f}: "
                  f"{'pass' if collapse.passes_acmr20 else 'FAIL'} (ACMR10% {collapse.acmr10:.3f}: "
                  f"{'pass' if collapse.passes_acmr10 else 'FAIL'}; FEMA P695 Sec. 7.5); {p695_basis(collapse)}", "",
                  P695_STATEMENT, ""]
    return "\n".join(lines).rstrip("\n") + "\n"
