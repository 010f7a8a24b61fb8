"""Figures of wall design: a mode's damping ratio and period against the wall size."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

from ..design.sizing import SizingCurve, story_text
from ._figure import figure_path, pyplot, save


def plot_damping_curve(curve: SizingCurve, path: str | os.PathLike[str], target: float | None = None,
                       marks: Mapping[str, float] | None = None, title: str | None = None,
                       own: tuple[float, float] | tuple[float, float, float] | None = None) -> Path:
    """Damping ratio (%) and period (s) of ``curve.mode`` against the wall size to a PNG; returns the path.

    The size axis (logarithmic) is the wall area (m^2) of the story with the largest weight (every walled
    story's for the uniform distribution), or, for the ``"existing"`` distribution, the factor on the
    building's own wall areas (1 = the building's walls).  Drawn: the bare frame's values (dashed), the
    largest achievable ratio (a dot), ``target`` (a horizontal line, -), ``marks`` ({label: area factor},
    e.g. the walls of the building file) as vertical lines, and ``own`` = (damping ratio -, period s) of the
    building's own walls as dotted horizontal lines, so that they show on any layout (walls laid out
    otherwise than the curve's lie off it), or (damping ratio, period, area factor) as a point on the
    curves where they lie on them.
    """
    if not isinstance(curve, SizingCurve):
        raise ValueError(f"curve must be a SizingCurve (from damping_curve), got {type(curve).__name__}")
    path = figure_path(path, "design_damping.png")
    plt = pyplot()
    scale = 1.0 if curve.wall is None else curve.wall.area / 1e6  # size-axis units per area factor
    size = curve.factors * scale
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(6.4, 6.4), sharex=True)
    top.semilogx(size, 100.0 * curve.damping_ratios, "C0", lw=1.8, label="with walls (complex modes)")
    top.axhline(100.0 * curve.bare_damping_ratio, color="0.4", ls="--", lw=1.0, label="bare frame")
    best = curve.best_factor * scale
    at = f"{best:.3g} x its own" if curve.wall is None else f"{best:.3g} m$^2$"
    top.plot([best], [100.0 * curve.best_damping_ratio], "o", color="C3",
             label=f"largest: {100 * curve.best_damping_ratio:.2f} % at {at}")
    if target is not None:
        top.axhline(100.0 * target, color="C2", lw=1.0, label=f"target {100 * target:.3g} %")
    bottom.semilogx(size, curve.periods, "C1", lw=1.8, label="with walls")
    bottom.axhline(curve.bare_period, color="0.4", ls="--", lw=1.0, label="bare frame")
    if own is not None and len(own) == 3:  # on the curves
        where = [own[2] * scale]
        top.plot(where, [100.0 * own[0]], "D", color="C4", ms=7, label=f"its own walls: {100 * own[0]:.2f} %")
        bottom.plot(where, [own[1]], "D", color="C4", ms=7, label=f"its own walls: {own[1]:.3f} s")
    elif own is not None:
        top.axhline(100.0 * own[0], color="C4", ls=":", lw=1.4, label=f"its own walls: {100 * own[0]:.2f} %")
        bottom.axhline(own[1], color="C4", ls=":", lw=1.4, label=f"its own walls: {own[1]:.3f} s")
    for label, factor in (marks or {}).items():
        for axes in (top, bottom):
            axes.axvline(factor * scale, color="0.2", lw=0.8, ls=":")
        top.annotate(label, (factor * scale, top.get_ylim()[0]), rotation=90, fontsize="x-small",
                     va="bottom", ha="right")
    top.set_ylabel(f"mode {curve.mode} damping ratio (%)")
    bottom.set_ylabel(f"mode {curve.mode} period (s)")
    if curve.wall is None:
        bottom.set_xlabel(f"area factor on its own walls (1 = as they are; {story_text(curve.stories)})")
    else:
        per = "per story" if curve.distribution == "uniform" else "largest story"
        bottom.set_xlabel(f"wall shear area, m$^2$ ({per}; {curve.distribution} over {story_text(curve.stories)})")
    for axes in (top, bottom):
        axes.grid(True, which="both", alpha=0.3)
        axes.legend(fontsize="small")
    if title:
        top.set_title(title)
    return save(figure, path)
