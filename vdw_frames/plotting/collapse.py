"""Figures of FEMA P695 collapse assessments: IDA curves with collapse points, pushover curves with
delta_y,eff and delta_u, empirical and P695 collapse fragilities.  Intensities in g, drifts in %.

The functions take :class:`~vdw_frames.assessment.CollapseAssessment` objects, read by attribute: plotting
sits below the assessment layer (whose report draws these figures), so it names what it reads in small
protocols (:class:`Assessed`) rather than importing the assessment.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Protocol

import numpy as np
from numpy.typing import ArrayLike

from ..motion.record import G
from ._figure import figure_path, pyplot, save

if TYPE_CHECKING:
    from ..frame.pushover import PushoverResult


class _Criterion(Protocol):
    @property
    def drift_ratio(self) -> float: ...  # the collapse drift ratio (-)


class _Curve(Protocol):
    """One record's runs, sorted by intensity (an assessment's IDACurve)."""

    @property
    def intensity(self) -> np.ndarray: ...  # mm/s^2
    @property
    def peak_drift_ratio(self) -> np.ndarray: ...  # (-)
    @property
    def collapsed(self) -> np.ndarray: ...  # bool


class Assessed(Protocol):
    """What the figures read of a :class:`~vdw_frames.assessment.CollapseAssessment` (intensities mm/s^2)."""

    @property
    def criterion(self) -> _Criterion: ...
    @property
    def curves(self) -> Sequence[_Curve]: ...
    @property
    def smt(self) -> float: ...
    @property
    def median_collapse_intensity(self) -> float: ...
    @property
    def cmr(self) -> float: ...
    @property
    def total_analyses(self) -> int: ...
    @property
    def period(self) -> float: ...  # s
    @property
    def collapse_intensity(self) -> np.ma.MaskedArray: ...
    @property
    def record_names(self) -> Sequence[str]: ...
    @property
    def beta_total(self) -> float: ...
    def fragility(self, intensity: ArrayLike, adjusted: bool = False) -> np.ndarray: ...


def plot_collapse_ida(assessments: Mapping[str, Assessed], path: str | os.PathLike[str],
                      title: str | None = None) -> Path:
    """IDA curves of every record: the set's intensity S_T (g) against the largest story drift ratio (%), one
    panel per assessment (``assessments`` maps a label to a CollapseAssessment); each record's first
    collapsing run is marked x at the collapse drift limit, S_MT and Ŝ_CT are drawn as lines."""
    path = figure_path(path, "collapse_ida.png")
    plt = pyplot()
    count = len(assessments)
    figure, axes = plt.subplots(1, count, figsize=(6.0 * count, 5.0), squeeze=False, sharey=True)
    for panel, (label, assessment) in zip(axes[0], assessments.items(), strict=True):
        limit = 100.0 * assessment.criterion.drift_ratio
        for k, curve in enumerate(assessment.curves):
            sa, drift, collapsed = curve.intensity / G, 100.0 * curve.peak_drift_ratio, curve.collapsed
            standing = ~collapsed
            colour = f"C{k % 10}"
            panel.plot(drift[standing], sa[standing], "-", marker="o", ms=2.0, lw=0.7, color=colour)
            if collapsed.any():
                first = int(np.flatnonzero(collapsed)[0])
                below = np.flatnonzero(standing & (sa < sa[first]))
                start = (drift[below[-1]], sa[below[-1]]) if below.size else (0.0, 0.0)
                panel.plot([start[0], limit], [start[1], sa[first]], ":", lw=0.6, color=colour)
                panel.plot([limit], [sa[first]], "x", ms=5, mew=1.2, color=colour)
        panel.axhline(assessment.smt / G, color="k", lw=1.0, ls="--", label=f"S_MT = {assessment.smt / G:.3f} g")
        panel.axhline(assessment.median_collapse_intensity / G, color="r", lw=1.0,
                      label=f"Ŝ_CT = {assessment.median_collapse_intensity / G:.3f} g (CMR {assessment.cmr:.2f})")
        panel.set_xlim(0.0, 1.1 * limit)
        panel.set_xlabel("largest story drift ratio (%)")
        panel.set_title(f"{label}: {len(assessment.curves)} records, {assessment.total_analyses} analyses",
                        fontsize="medium")
        panel.grid(True, alpha=0.3)
        panel.legend(fontsize="small", loc="upper left")
    axes[0][0].set_ylabel(f"S_T = median Sa(T = {next(iter(assessments.values())).period:.2f} s) of the set (g)")
    if title:
        figure.suptitle(title)
    return save(figure, path)


def plot_pushover(pushovers: Mapping[str, PushoverResult], path: str | os.PathLike[str],
                  title: str | None = None) -> Path:
    """Capacity curves V/W against roof drift ratio (%) with V_max, 0.8 V_max, delta_y,eff (eq. 6-7) and
    delta_u marked; ``pushovers`` maps a label to a PushoverResult."""
    path = figure_path(path, "pushover.png")
    plt = pyplot()
    figure, axes = plt.subplots(figsize=(7.0, 4.8))
    right = 0.0
    for k, (label, result) in enumerate(pushovers.items()):
        colour = f"C{k}"
        x = 100.0 * result.roof_drift_ratio
        v = result.normalized_base_shear
        right = max(right, x[-1])
        text = f"{label}: V_max/W = {result.max_base_shear / result.weight:.3f}"
        if result.period_based_ductility is not None:
            text += f", mu_T = {result.period_based_ductility:.2f}"
        axes.plot(x, v, ("-", "--", ":", "-.")[k % 4], color=colour, lw=2.2 if k == 0 else 1.4, label=text)
        vmax = result.max_base_shear / result.weight
        yield_x = 100.0 * result.yield_roof_displacement / result.height
        axes.plot([0.0, yield_x], [0.0, vmax], "--", color=colour, lw=0.9)
        axes.plot([yield_x], [vmax], "s", color=colour, ms=6, label=f"  delta_y,eff = {yield_x:.3f} %")
        if result.ultimate_roof_displacement is not None:
            ultimate_x = 100.0 * result.ultimate_roof_displacement / result.height
            axes.plot([ultimate_x], [0.8 * vmax], "D", color=colour, ms=6,
                      label=f"  delta_u = {ultimate_x:.3f} % (0.8 V_max)")
        axes.axhline(0.8 * vmax, color=colour, lw=0.6, ls=":")
    axes.axhline(0.0, color="k", lw=0.6)
    axes.set_xlim(0.0, right)
    axes.set_xlabel("roof drift ratio (%)")
    axes.set_ylabel("base shear / seismic weight V/W (-)")
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small")
    if title:
        axes.set_title(title)
    return save(figure, path)


def plot_collapse_fragility(assessments: Mapping[str, Assessed], path: str | os.PathLike[str],
                            title: str | None = None) -> Path:
    """Collapse fragilities against S_T (g): the empirical one (fraction of records collapsed) as steps and
    FEMA P695's lognormal one (median Ŝ_CT, dispersion beta_TOT) as a line, with S_MT marked."""
    path = figure_path(path, "collapse_fragility.png")
    plt = pyplot()
    figure, axes = plt.subplots(figsize=(7.0, 4.8))
    top = max(float(np.max(a.collapse_intensity.filled(0.0))) for a in assessments.values()) / G
    top = 1.15 * max(top, max(a.smt for a in assessments.values()) / G)
    sa = np.linspace(top / 400.0, top, 400)
    for k, (label, assessment) in enumerate(assessments.items()):
        colour = f"C{k}"
        points = np.sort(assessment.collapse_intensity.compressed()) / G
        count = len(assessment.record_names)
        axes.step(np.concatenate([[0.0], points]), np.arange(points.size + 1) / count, where="post", color=colour,
                  lw=1.0, label=f"{label}: records ({count})")
        axes.plot(sa, assessment.fragility(sa * G), "--", color=colour, lw=1.4,
                  label=f"{label}: P695 lognormal, Ŝ_CT {assessment.median_collapse_intensity / G:.3f} g, "
                        f"beta_TOT {assessment.beta_total:.3f}")
    smt = next(iter(assessments.values())).smt / G
    axes.axvline(smt, color="k", lw=0.8, ls=":", label=f"S_MT = {smt:.3f} g")
    axes.set_xlim(0.0, top)
    axes.set_ylim(0.0, 1.0)
    axes.set_xlabel("S_T = median Sa(T) of the set (g)")
    axes.set_ylabel("probability of collapse")
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="x-small", loc="lower right")
    if title:
        axes.set_title(title)
    return save(figure, path)
