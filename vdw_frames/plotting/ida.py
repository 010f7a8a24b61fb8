"""Figures of incremental dynamic analyses: IDA curves and collapse fragilities (intensities in g)."""

from __future__ import annotations

import os
from collections.abc import Mapping
from itertools import cycle
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..motion.record import G
from ._figure import figure_path, pyplot, save

if TYPE_CHECKING:
    from ..frame.ida import IDAResult


def plot_ida_curves(results: Mapping[str, IDAResult], path: str | os.PathLike[str], title: str | None = None) -> Path:
    """IDA curves: Sa(T1) (g) against the largest story drift ratio (%) of every record, collapses marked x.

    ``results`` maps a label to an :class:`~vdw_frames.frame.ida.IDAResult`; the first label is drawn
    dashed, the others solid, one colour per record.
    """
    path = figure_path(path, "ida_curves.png")
    plt = pyplot()
    figure, axes = plt.subplots(figsize=(7.0, 5.0))
    for (label, result), style in zip(results.items(), cycle(("--", "-", ":", "-.")), strict=False):
        for m, name in enumerate(result.motion_names):
            sa, drift, collapsed = result.intensities[m] / G, 100.0 * result.peak_drift_ratio[m], result.collapsed[m]
            standing = ~collapsed
            axes.plot(drift[standing], sa[standing], style, marker="o", ms=2.5, lw=1.0, color=f"C{m}",
                      label=f"{name} ({label})")
            if collapsed.any():
                last = np.flatnonzero(standing)[-1] if standing.any() else None
                x0 = drift[last] if last is not None else 0.0
                y0 = sa[last] if last is not None else 0.0
                axes.plot([x0, 10.0 * max(1.0, x0 / 10.0)], [y0, sa[collapsed][0]], style, lw=0.8, color=f"C{m}")
                axes.plot([10.0 * max(1.0, x0 / 10.0)], [sa[collapsed][0]], "x", ms=7, mew=2, color=f"C{m}")
    if any(collapsed.any() for result in results.values() for collapsed in result.collapsed):
        # One legend entry for the marks drawn at the cut-off (not a drift the frame reached).
        axes.plot([], [], "x", ms=7, mew=2, color="0.3", label="collapse (drawn at the 10 % cut-off)")
    axes.set_xlabel("largest story drift ratio (%)")
    axes.set_ylabel("Sa(T1, 5 %) (g)")
    axes.set_xlim(0.0, 11.0)
    if title:
        axes.set_title(title)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="x-small", ncol=2)
    return save(figure, path)


def plot_fragility(results: Mapping[str, IDAResult], path: str | os.PathLike[str], title: str | None = None) -> Path:
    """Collapse fragility curves (lognormal fits) with the records' collapse intensities as steps.

    ``results`` maps a label to an :class:`~vdw_frames.frame.ida.IDAResult` with at least two collapses.
    """
    path = figure_path(path, "fragility.png")
    plt = pyplot()
    figure, axes = plt.subplots(figsize=(6.4, 4.6))
    top = max(result.levels[-1] for result in results.values()) / G
    sa = np.linspace(1e-3, top, 300)
    for k, (label, result) in enumerate(results.items()):
        fit = result.fragility()
        axes.plot(sa, fit.probability(sa * G), color=f"C{k}",
                  label=f"{label}: median {fit.median / G:.2f} g, beta {fit.dispersion:.2f}")
        points = np.sort(result.collapse_intensity.compressed()) / G
        count = len(result.motion_names)
        axes.plot(points, np.arange(1, points.size + 1) / count, "o", color=f"C{k}", ms=4)
    axes.set_xlabel("Sa(T1, 5 %) (g)")
    axes.set_ylabel("probability of collapse")
    axes.set_ylim(0.0, 1.0)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small", loc="lower right")
    if title:
        axes.set_title(title)
    return save(figure, path)
