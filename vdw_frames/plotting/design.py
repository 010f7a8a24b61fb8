"""Figures of design: a mode's damping ratio and period against the wall size; a code design's story shears
and drifts against their limits (ASCE 7-16 Sec. 12.8); a verification's peak drift ratios per bound."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..asce7.elf import design_drift_limit_divisor
from ._figure import figure_path, pyplot, save

if TYPE_CHECKING:  # types only: the figures sit below the design and verification that draw them in their reports
    from ..design.elf import FrameDesign
    from ..design.sizing import SizingCurve
    from ..verification.verify import VerificationResult


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
        bottom.set_xlabel(f"area factor on its own walls (1 = as they are; {curve.stories_text})")
    else:
        per = "per story" if curve.distribution == "uniform" else "largest story"
        bottom.set_xlabel(f"wall shear area, m$^2$ ({per}; {curve.distribution} over {curve.stories_text})")
    for axes in (top, bottom):
        axes.grid(True, which="both", alpha=0.3)
        axes.legend(fontsize="small")
    if title:
        top.set_title(title)
    return save(figure, path)


def plot_design_profiles(design: FrameDesign, path: str | os.PathLike[str], title: str | None = None) -> Path:
    """The story-shear and drift profiles of a frame designed by ASCE 7-16 Sec. 12.8 (:func:`design_frame`) to a
    PNG; returns the path.

    Left: the design story shears V_x of Chapter 12 (Eq. 12.8-13, kN), the same times ``strength_scale`` where
    it is below 1 (Chapter 18's V_min / V, Sec. 18.2.1.1), and the story yield strengths (V_x x the P-Delta
    factor x overstrength x strength_scale).  Right: the design story drift delta_x (Eq. 12.8-15 with the
    P-Delta factor, mm) against its limit Delta_a / rho (Table 12.12-1, Sec. 12.12.1.1), dashed.
    """
    path = figure_path(path, "design_profiles.png")
    plt = pyplot()
    stories = np.arange(1, design.strengths.size + 1)
    figure, (shear, drift) = plt.subplots(1, 2, figsize=(9.6, 5.2), sharey=True)
    shear.plot(design.story_shears / 1e3, stories, "C0-", lw=1.8,
               label=f"V_x, Chapter 12 (V = {design.base_shear / 1e3:.4g} kN)")
    if design.strength_scale < 1.0:
        shear.plot(design.strength_scale * design.story_shears / 1e3, stories, "C2--", lw=1.6,
                   label=f"V_x x {design.strength_scale:.3g} (Chapter 18: V_min / V)")
    shear.plot(design.strengths / 1e3, stories, "C3o", ms=5,
               label=f"yield strength (overstrength {design.overstrength:g}, P-Delta factor)")
    shear.set_xlabel("story shear (kN)")
    shear.set_ylabel("story")
    shear.set_xlim(left=0.0)
    shear.legend(fontsize="small", loc="best")
    drift.plot(design.design_drifts, stories, "C0-o", ms=4, lw=1.8, label="delta_x = C_d delta_xe / I_e (P-Delta)")
    divided = design_drift_limit_divisor(design.system, design.sdc, design.rho) != 1.0  # Sec. 12.12.1.1
    drift.plot(design.allowable_drifts, stories, "C3--", lw=1.4,
               label=f"limit Delta_a / rho (rho = {design.rho:g})" if divided else "limit Delta_a (Table 12.12-1)")
    drift.set_xlabel("design story drift (mm)")
    drift.set_xlim(left=0.0)
    drift.legend(fontsize="small", loc="best")
    for axes in (shear, drift):
        axes.set_yticks(stories)
        axes.grid(True, alpha=0.3)
    figure.suptitle(title or f"ASCE 7-16 ELF design: {design.system.name}, SDC {design.sdc}, T = "
                    f"{design.period:.3f} s, C_s = {design.cs:.4g} (Eq. {design.cs_equation})", fontsize="medium")
    return save(figure, path)


def plot_drift_spread(result: VerificationResult, path: str | os.PathLike[str], title: str | None = None) -> Path:
    """The spread of a verification's peak story drift ratios per bound (ASCE 7-16 Sec. 16.4.1.2) to a PNG;
    returns the path.

    One column per case (nominal, upper and lower bound): each record's largest peak story drift ratio over the
    stories (%, a dot; an unacceptable response a red cross, at the top of the axes where its drift is not finite),
    the suite statistic of the story that governs (a black bar: the mean, or Sec. 16.4.1.2's statistic with
    unacceptable responses), and the limit (2 x Table 12.12-1 for Risk Category I-II, dashed).
    """
    path = figure_path(path, "drift_spread.png")
    plt = pyplot()
    peaks = 100.0 * np.max(result.peak_drift_ratio, axis=2)  # (cases, records)
    statistic = 100.0 * np.max(result.drift_statistic, axis=1)
    limit = 100.0 * result.drift_limit
    finite = peaks[np.isfinite(peaks)]
    top = 1.15 * max(limit, float(statistic.max()), float(finite.max()) if finite.size else 0.0)
    figure, axes = plt.subplots(figsize=(2.4 + 1.6 * len(result.cases), 5.4))
    spread = np.linspace(-0.18, 0.18, peaks.shape[1]) if peaks.shape[1] > 1 else np.zeros(1)
    for c in range(len(result.cases)):
        bad = np.array([bool(reason) for reason in result.unacceptable[c]])
        shown = np.minimum(np.nan_to_num(peaks[c], nan=top, posinf=top), top)
        axes.plot(c + spread[~bad], shown[~bad], "o", color="C0", ms=5, alpha=0.8,
                  label="a record's largest story" if c == 0 else None)
        if bad.any():
            labelled = "unacceptable response" in axes.get_legend_handles_labels()[1]
            axes.plot(c + spread[bad], shown[bad], "x", color="C3", ms=7, mew=2,
                      label=None if labelled else "unacceptable response")
        axes.plot([c - 0.3, c + 0.3], [statistic[c]] * 2, "k-", lw=2.5,
                  label="suite statistic, governing story" if c == 0 else None)
    axes.axhline(limit, color="C3", ls="--", lw=1.2, label=f"limit {limit:.3g} %")
    axes.set_xticks(range(len(result.cases)))
    axes.set_xticklabels([f"{case}\n(lambda = {factor:g})" for case, factor in result.cases])
    axes.set_xlim(-0.6, len(result.cases) - 0.4)
    axes.set_ylim(0.0, top)
    axes.set_ylabel("peak story drift ratio (%)")
    axes.grid(True, axis="y", alpha=0.3)
    axes.legend(fontsize="small", loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)  # below: no point hidden
    verdict = "PASS" if result.passed else "FAIL"
    axes.set_title(title or f"Peak drift ratios per bound, {peaks.shape[1]} records: {verdict}", fontsize="medium")
    return save(figure, path)
