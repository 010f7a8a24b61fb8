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


def _story_number(result, story) -> int:
    message = f"story must be a story number in 1 ... {result.building.stories}, got {show(story)}"
    try:
        story = whole_number("story", story, 1)
    except ValueError:
        raise ValueError(message) from None
    if story > result.building.stories:
        raise ValueError(message)
    return story


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
    return _story_loop(result, story, path, "damper_hysteresis.png", result.damper_force, "damper force", title)


def _story_loop(result, story, path, default_name, force, what, title) -> Path:
    """``force`` (N, steps x stories) of one story (1-based) against its drift (mm), drawn in kN."""
    story = _story_number(result, story)
    path = _figure_path(path, default_name)
    plt = _pyplot()
    figure, axes = plt.subplots(figsize=(5.6, 4.6))
    axes.plot(result.drift[:, story - 1], force[:, story - 1] / 1e3, lw=0.7)
    axes.axhline(0.0, color="0.7", lw=0.5)
    axes.axvline(0.0, color="0.7", lw=0.5)
    axes.set_xlabel(f"story {story} drift (mm)")
    axes.set_ylabel(f"story {story} {what} (kN)")
    axes.grid(True, alpha=0.3)
    if title:
        axes.set_title(title)
    return _save(figure, path)


def plot_energy(result, path, title=None) -> Path:
    """Stacked energy histories (kN*m = 1e6 N*mm) with the input energy on top.

    Walls, inherent damping and story yielding (hysteretic) dissipate; frame strain and kinetic energy
    are stored.  With P-Delta, gravity also does work (``energy.p_delta`` <= 0): the stack then reaches
    input - p_delta, drawn dashed.
    """
    path = _figure_path(path, "energy.png")
    plt = _pyplot()
    energy = result.energy
    figure, axes = plt.subplots(figsize=(8.0, 4.0))
    parts = [("walls", energy.damper_work), ("inherent damping", energy.inherent_damping),
             ("story yielding", energy.hysteretic), ("frame strain", energy.frame_strain),
             ("kinetic", energy.kinetic)]
    parts = [(name, values) for name, values in parts if np.abs(values).max() > 0.0]
    axes.stackplot(result.time, *[values / 1e6 for _, values in parts], labels=[name for name, _ in parts], alpha=0.8)
    axes.plot(result.time, energy.input / 1e6, "k", lw=1.0, label="input")
    if np.abs(energy.p_delta).max() > 0.0:
        axes.plot(result.time, (energy.input - energy.p_delta) / 1e6, "k--", lw=0.8, label="input + gravity (P-Delta)")
    axes.set_xlabel("time (s)")
    axes.set_ylabel("energy (kN m)")
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small", loc="upper left")
    if title:
        axes.set_title(title)
    return _save(figure, path)


def plot_ida_curves(results: dict, path, title=None) -> Path:
    """IDA curves: Sa(T1) (g) against the largest story drift ratio (%) of every record, collapses marked x.

    ``results`` maps a label to an :class:`~vdw_frames.frame.ida.IDAResult`; the first label is drawn
    dashed, the others solid, one colour per record.
    """
    from .motion.record import G

    path = _figure_path(path, "ida_curves.png")
    plt = _pyplot()
    figure, axes = plt.subplots(figsize=(7.0, 5.0))
    for (label, result), style in zip(results.items(), ("--", "-", ":", "-.")):
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
    axes.set_xlabel("largest story drift ratio (%)")
    axes.set_ylabel("Sa(T1, 5 %) (g)")
    axes.set_xlim(0.0, 11.0)
    if title:
        axes.set_title(title)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="x-small", ncol=2)
    return _save(figure, path)


def plot_fragility(results: dict, path, title=None) -> Path:
    """Collapse fragility curves (lognormal fits) with the records' collapse intensities as steps.

    ``results`` maps a label to an :class:`~vdw_frames.frame.ida.IDAResult` with at least two collapses.
    """
    from .motion.record import G

    path = _figure_path(path, "fragility.png")
    plt = _pyplot()
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
    return _save(figure, path)


def plot_story_hysteresis(result, story: int, path, title=None) -> Path:
    """Story-spring force (kN) against drift (mm) of one story (1-based): the frame's own hysteresis."""
    return _story_loop(result, story, path, "story_hysteresis.png", result.story_shear, "frame shear", title)
