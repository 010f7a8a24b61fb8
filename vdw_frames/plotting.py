"""Figures (matplotlib, Agg backend: no display needed).  Forces are drawn in kN, displacements in mm.

Every function writes one figure to ``path`` and returns the path it wrote: the format follows the
suffix (``.png``, ``.pdf``, ``.svg``, ...); a path without one gets ``.png`` added; an existing folder
(or a path ending in a separator) gets the function's default file name inside it.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from ._validation import file_path, show, whole_number

_FORMATS = {"eps", "jpeg", "jpg", "pdf", "pgf", "png", "ps", "raw", "rgba", "svg", "svgz", "tif", "tiff", "webp"}


def _pyplot():
    # Imported on first use: matplotlib costs ~0.3 s, which `import vdw_frames` should not pay.
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_loops(results, path, labels=None, title=None) -> Path:
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
    path = _figure_path(path, "loops.png")
    plt = _pyplot()
    figure, axes = plt.subplots(figsize=(6.4, 4.8))
    for res, label in zip(results, labels):
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
    return _save(figure, path)


def _figure_path(path, default_name: str) -> Path:
    """Where a figure for ``path`` goes (see the module docstring); the folder is created."""
    text = os.fspath(path) if isinstance(path, (str, os.PathLike)) else path
    path = file_path(path, "figure path")
    if path.is_dir() or (isinstance(text, str) and text.endswith(("/", os.sep))):
        path = path / default_name
    if path.suffix.lower().lstrip(".") not in _FORMATS:
        path = path.with_name(path.name + ".png")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise ValueError(f"{path}: cannot create the folder {path.parent} ({error.strerror or error})") from None
    if path.is_dir():
        raise ValueError(f"{path}: is a folder")
    return path


def _save(figure, path: Path) -> Path:
    figure.tight_layout()
    try:
        figure.savefig(path, dpi=120)
    except OSError as error:
        raise ValueError(f"{path}: cannot write the figure ({error.strerror or error})") from None
    finally:
        _pyplot().close(figure)
    return path


def plot_drift_envelope(results: dict, path) -> Path:
    """Peak interstory drift ratio (or drift in mm without story heights) per story, one line per result.

    ``results`` maps a label to a :class:`~vdw_frames.frame.simulation.SimulationResult`.
    """
    path = _figure_path(path, "drift_envelope.png")
    plt = _pyplot()
    figure, axes = plt.subplots(figsize=(5.0, 5.6))
    for label, result in results.items():
        stories = np.arange(1, result.building.stories + 1)
        ratio = result.peak_drift_ratio
        values = 100.0 * ratio if ratio is not None else result.peak_drift
        axes.step(np.r_[values, values[-1]], np.r_[stories - 0.5, stories[-1] + 0.5], where="pre", label=label)
        axes.plot(values, stories, "o", ms=3, color=axes.lines[-1].get_color())
    ratio_known = all(r.drift_ratio is not None for r in results.values())
    axes.set_xlabel("peak interstory drift ratio (%)" if ratio_known else "peak interstory drift (mm)")
    axes.set_ylabel("story")
    axes.set_xlim(left=0.0)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small")
    return _save(figure, path)


def plot_roof_displacement(results: dict, path) -> Path:
    """Roof displacement relative to the ground (mm) against time (s), one line per result."""
    path = _figure_path(path, "roof_displacement.png")
    plt = _pyplot()
    figure, axes = plt.subplots(figsize=(8.0, 3.6))
    for label, result in results.items():
        axes.plot(result.time, result.displacement[:, -1], lw=0.9, label=label)
    axes.set_xlabel("time (s)")
    axes.set_ylabel("roof displacement (mm)")
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small")
    return _save(figure, path)


def plot_damper_hysteresis(result, story: int, path, title=None) -> Path:
    """Total damper force (kN) against drift (mm) of one story (1-based) of a simulation result."""
    message = f"story must be a story number in 1 ... {result.building.stories}, got {show(story)}"
    try:
        story = whole_number("story", story, 1)
    except ValueError:
        raise ValueError(message) from None
    if story > result.building.stories:
        raise ValueError(message)
    path = _figure_path(path, "damper_hysteresis.png")
    plt = _pyplot()
    figure, axes = plt.subplots(figsize=(5.6, 4.6))
    axes.plot(result.drift[:, story - 1], result.damper_force[:, story - 1] / 1e3, lw=0.6)
    axes.set_xlabel(f"story {story} drift (mm)")
    axes.set_ylabel(f"story {story} damper force (kN)")
    axes.grid(True, alpha=0.3)
    if title:
        axes.set_title(title)
    return _save(figure, path)


def plot_energy(result, path, title=None) -> Path:
    """Stacked energy histories (kN*m = 1e6 N*mm) with the input energy on top."""
    path = _figure_path(path, "energy.png")
    plt = _pyplot()
    energy = result.energy
    figure, axes = plt.subplots(figsize=(8.0, 4.0))
    parts = [("damper work", energy.damper_work), ("inherent damping", energy.inherent_damping),
             ("frame strain", energy.frame_strain), ("kinetic", energy.kinetic)]
    axes.stackplot(result.time, *[values / 1e6 for _, values in parts], labels=[name for name, _ in parts], alpha=0.8)
    axes.plot(result.time, energy.input / 1e6, "k", lw=1.0, label="input")
    axes.set_xlabel("time (s)")
    axes.set_ylabel("energy (kN m)")
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small", loc="upper left")
    if title:
        axes.set_title(title)
    return _save(figure, path)


def plot_ida_curves(results: dict, path, title=None) -> Path:
    """IDA curves: PGA (g) against the peak interstory drift ratio (%) of each record.

    ``results`` maps a label to a :class:`~vdw_frames.frame.batch.BatchResult` with story heights; the
    first label is drawn dashed, the others solid, one colour per record.
    """
    from .motion.record import G

    path = _figure_path(path, "ida_curves.png")
    plt = _pyplot()
    figure, axes = plt.subplots(figsize=(6.4, 4.8))
    for (label, result), style in zip(results.items(), ("--", "-", ":", "-.")):
        drift = 100.0 * result.peak_drift_ratio.max(axis=2)
        for m, name in enumerate(result.motion_names):
            axes.plot(drift[m], result.pga[m] / G, style, marker="o", ms=3, lw=1.0,
                      label=f"{name} ({label})", color=f"C{m}")
    axes.set_xlabel("peak interstory drift ratio (%)")
    axes.set_ylabel("PGA (g)")
    if title:
        axes.set_title(title)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="x-small", ncol=2)
    return _save(figure, path)
