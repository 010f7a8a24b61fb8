"""Figures of one wall: force-displacement loops of sine tests."""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from ._figure import figure_path, pyplot, save

if TYPE_CHECKING:
    from ..element.sine import SineTestResult


def plot_loops(results: SineTestResult | list[SineTestResult] | tuple[SineTestResult, ...],
               path: str | os.PathLike[str], labels: Sequence[str] | None = None, title: str | None = None) -> Path:
    """Draw force-displacement loops of sine tests to a PNG at ``path``; returns the path.

    ``results`` is one :class:`~vdw_frames.element.sine.SineTestResult` or a sequence of them.  The whole
    history is drawn thin (the start-up transient shows), the last full cycle thick.
    """
    if not isinstance(results, (list, tuple)):
        results = [results]
    if labels is None:
        labels = [f"U = {res.amplitude:g} mm, f = {res.frequency:g} Hz" for res in results]
    if len(labels) != len(results):
        raise ValueError(f"labels has {len(labels)} entries for {len(results)} results")
    path = figure_path(path, "loops.png")
    plt = pyplot()
    figure, axes = plt.subplots(figsize=(6.4, 4.8))
    for res, label in zip(results, labels, strict=True):
        (line,) = axes.plot(res.displacement[res.last_cycle], res.force[res.last_cycle] / 1e3,
                            lw=1.8, label=label)
        axes.plot(res.displacement, res.force / 1e3, lw=0.5, alpha=0.4, color=line.get_color())
    axes.set_xlabel("displacement (mm)")
    axes.set_ylabel("force (kN)")
    axes.axhline(0.0, color="0.7", lw=0.5)
    axes.axvline(0.0, color="0.7", lw=0.5)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small")
    if title:
        axes.set_title(title)
    return save(figure, path)
