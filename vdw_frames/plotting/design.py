"""Figures of wall design: a mode's damping ratio and period against the wall size."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

from ..design.sizing import SizingCurve, story_text
from ._figure import figure_path, pyplot, save


def plot_damping_curve(curve: SizingCurve, path: str | os.PathLike[str], target: float | None = None,
                       marks: Mapping[str, float] | None = None, title: str | None = None) -> Path:
    """Damping ratio (%) and period (s) of ``curve.mode`` against the wall area (m^2) to a PNG; returns the path.

    The area axis is the wall area of the story with the largest weight (every walled story's for the
    uniform distribution), logarithmic.  Drawn: the bare frame's values (dashed), the largest
    achievable ratio (a dot), ``target`` (a horizontal line, -) and ``marks`` ({label: area factor},
    e.g. the walls of the building file) as vertical lines.
    """
    if not isinstance(curve, SizingCurve):
        raise ValueError(f"curve must be a SizingCurve (from damping_curve), got {type(curve).__name__}")
    path = figure_path(path, "design_damping.png")
    plt = pyplot()
    area = curve.factors * curve.wall.area / 1e6
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(6.4, 6.4), sharex=True)
    top.semilogx(area, 100.0 * curve.damping_ratios, "C0", lw=1.8, label="with walls (complex modes)")
    top.axhline(100.0 * curve.bare_damping_ratio, color="0.4", ls="--", lw=1.0, label="bare frame")
    best_area = curve.best_factor * curve.wall.area / 1e6
    top.plot([best_area], [100.0 * curve.best_damping_ratio], "o", color="C3",
             label=f"largest: {100 * curve.best_damping_ratio:.2f} % at {best_area:.3g} m$^2$")
    if target is not None:
        top.axhline(100.0 * target, color="C2", lw=1.0, label=f"target {100 * target:.3g} %")
    bottom.semilogx(area, curve.periods, "C1", lw=1.8, label="with walls")
    bottom.axhline(curve.bare_period, color="0.4", ls="--", lw=1.0, label="bare frame")
    for label, factor in (marks or {}).items():
        for axes in (top, bottom):
            axes.axvline(factor * curve.wall.area / 1e6, color="0.2", lw=0.8, ls=":")
        top.annotate(label, (factor * curve.wall.area / 1e6, top.get_ylim()[0]), rotation=90, fontsize="x-small",
                     va="bottom", ha="right")
    top.set_ylabel(f"mode {curve.mode} damping ratio (%)")
    bottom.set_ylabel(f"mode {curve.mode} period (s)")
    per = "per story" if curve.distribution == "uniform" else "largest story"
    bottom.set_xlabel(f"wall shear area, m$^2$ ({per}; {curve.distribution} over {story_text(curve.stories)})")
    for axes in (top, bottom):
        axes.grid(True, which="both", alpha=0.3)
        axes.legend(fontsize="small")
    if title:
        top.set_title(title)
    return save(figure, path)
