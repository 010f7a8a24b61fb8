"""Figures of an ASCE 7-16 design verification (:func:`vdw_frames.verification.verify`): the target and the
scaled suite's spectra with the period range, and the story drift ratios per record with each case's drift
statistic and the limit.  Accelerations in g, drift ratios in %.

The functions take a :class:`~vdw_frames.verification.VerificationResult` read by attribute (plotting sits beside
the verification layer and imports it for type checking only).
"""

from __future__ import annotations

import os
import textwrap
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..motion.record import G
from ._figure import figure_path, pyplot, save

if TYPE_CHECKING:
    from ..verification.verify import VerificationResult


def plot_suite_spectra(result: VerificationResult, path: str | os.PathLike[str], title: str | None = None) -> Path:
    """The MCE_R target, 90 % of it, every scaled record's 5 %-damped spectrum (thin; one component, standing in
    for the maximum-direction spectrum of Sec. 16.2.3.2) and the suite's mean over the period range T_lower ...
    T_upper (shaded), with T_1 marked; periods s (log), S_a g (log).  The legend cites the clauses as read."""
    path = figure_path(path, "suite_spectra.png")
    plt = pyplot()
    suite = result.suite
    figure, axes = plt.subplots(figsize=(7.5, 5.0))
    periods = np.geomspace(min(0.05, suite.periods[0]), max(2.0 * suite.periods[-1], 4.0), 300)
    axes.axvspan(suite.range.lower, suite.range.upper, color="0.9",
                 label="period range (Sec. 16.2.3.1, read in ASCE 7-22 wording)")
    for k, spectrum in enumerate(suite.scaled_spectra):
        axes.plot(suite.periods, spectrum / G, lw=0.5, color="0.55",
                  label="scaled records (one component each)" if k == 0 else None)
    axes.plot(periods, result.site.spectrum(periods), "k-", lw=1.6, label="MCE_R target (Sec. 11.4.7)")
    axes.plot(periods, 0.9 * result.site.spectrum(periods), "k--", lw=1.0,
              label="90 % of the target (Sec. 16.2.3.2, read in ASCE 7-22 wording)")
    axes.plot(suite.periods, suite.mean_spectrum / G, "C3-", lw=1.8, label="suite mean")
    axes.axvline(suite.range.first_period, color="C0", lw=0.8, ls=":", label=f"T_1 = {suite.range.first_period:.2f} s")
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("period T (s)")
    axes.set_ylabel("S_a (g), 5 % damping")
    axes.set_title(title or f"{len(suite.motions)} records scaled to the MCE_R spectrum", fontsize="medium")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize="small", loc="lower left")
    return save(figure, path)


def plot_story_drifts(result: VerificationResult, path: str | os.PathLike[str], title: str | None = None) -> Path:
    """Peak story drift ratio (%) of every record (thin lines: acceptable ones solid grey, collapsed or otherwise
    unacceptable ones dotted red) and the case's drift statistic of Sec. 16.4.1.2 (thick: the mean, or max(mean,
    1.2 x median) of the acceptable records, as its legend says with how many records stand behind it) against
    the story, one panel per case (nominal, upper, lower bound), with the limit 2 x Table 12.12-1 dashed; each
    panel's legend explains every line style drawn in it."""
    path = figure_path(path, "story_drifts.png")
    plt = pyplot()
    count = len(result.cases)
    figure, axes = plt.subplots(1, count, figsize=(4.2 * count, 5.0), squeeze=False, sharey=True, sharex=True)
    stories = np.arange(1, result.peak_drift_ratio.shape[2] + 1)
    top = 100.0 * max(float(np.max(result.peak_drift_ratio)), result.drift_limit) * 1.1
    for c, (panel, (case, factor)) in enumerate(zip(axes[0], result.cases, strict=True)):
        labelled: set[bool] = set()
        for r in range(result.peak_drift_ratio.shape[1]):
            bad = bool(result.unacceptable[c][r])
            label = None if bad in labelled else "unacceptable record (Sec. 16.4.1.1)" if bad else "acceptable record"
            labelled.add(bad)
            panel.plot(100.0 * np.minimum(result.peak_drift_ratio[c, r], top / 100.0), stories,
                       ":" if bad else "-", color="C3" if bad else "0.6", lw=0.8, label=label)
        basis = textwrap.fill(result.drift_statistic_basis(case), 34)
        panel.plot(100.0 * result.drift_statistic[c], stories, "k-o", lw=2.0, ms=3,
                   label=f"{basis}\n(Sec. 16.4.1.2, ASCE 7-22 wording)")
        panel.axvline(100.0 * result.drift_limit, color="C3", ls="--", lw=1.2,
                      label=f"limit {100 * result.drift_limit:.1f} % (2 x Table 12.12-1)")
        panel.set_title(f"{case} (lambda = {factor:g})", fontsize="medium")
        panel.set_xlabel("peak story drift ratio (%)")
        panel.set_xlim(0.0, top)
        panel.grid(True, alpha=0.3)
        panel.legend(fontsize="x-small", loc="best")
    axes[0][0].set_ylabel("story")
    axes[0][0].set_yticks(stories)
    if title:
        figure.suptitle(title)
    return save(figure, path)
