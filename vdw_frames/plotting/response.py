"""Figures of one time-history analysis: drift envelopes, roof displacement, story loops, energies.

Forces are drawn in kN, displacements in mm.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ._figure import figure_path, pyplot, save, story_number

if TYPE_CHECKING:
    from ..frame.results import SimulationResult


def plot_drift_envelope(results: Mapping[str, SimulationResult], path: str | os.PathLike[str],
                        title: str | None = None) -> Path:
    """Peak interstory drift ratio (or drift in mm without story heights) per story, one line per result.

    ``results`` maps a label to a :class:`~vdw_frames.frame.results.SimulationResult`.
    """
    path = figure_path(path, "drift_envelope.png")
    plt = pyplot()
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
    if title:
        axes.set_title(title, fontsize="medium")
    return save(figure, path)


def plot_roof_displacement(results: Mapping[str, SimulationResult], path: str | os.PathLike[str],
                           title: str | None = None) -> Path:
    """Roof displacement relative to the ground (mm) against time (s), one line per result."""
    path = figure_path(path, "roof_displacement.png")
    plt = pyplot()
    figure, axes = plt.subplots(figsize=(8.0, 3.6))
    for label, result in results.items():
        axes.plot(result.time, result.displacement[:, -1], lw=0.9, label=label)
    axes.set_xlabel("time (s)")
    axes.set_ylabel("roof displacement (mm)")
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small")
    if title:
        axes.set_title(title, fontsize="medium")
    return save(figure, path)


def plot_wall_hysteresis(result: SimulationResult, story: int, path: str | os.PathLike[str],
                         title: str | None = None) -> Path:
    """Total damper force (kN) against drift (mm) of one story (1-based) of a simulation result."""
    return _story_loop(result, story, path, "damper_hysteresis.png", result.story_wall_force, "damper force",
                       title=title)


def _story_loop(result: SimulationResult, story: int, path: str | os.PathLike[str], default_name: str,
                force: np.ndarray, what: str, *, title: str | None) -> Path:
    """``force`` (N, steps x stories) of one story (1-based) against its drift (mm), drawn in kN."""
    story = story_number(result, story)
    path = figure_path(path, default_name)
    plt = pyplot()
    figure, axes = plt.subplots(figsize=(5.6, 4.6))
    axes.plot(result.drift[:, story - 1], force[:, story - 1] / 1e3, lw=0.7)
    axes.axhline(0.0, color="0.7", lw=0.5)
    axes.axvline(0.0, color="0.7", lw=0.5)
    axes.set_xlabel(f"story {story} drift (mm)")
    axes.set_ylabel(f"story {story} {what} (kN)")
    axes.grid(True, alpha=0.3)
    if title:
        axes.set_title(title)
    return save(figure, path)


def plot_story_hysteresis(result: SimulationResult, story: int, path: str | os.PathLike[str],
                          title: str | None = None) -> Path:
    """Story-spring force (kN) against drift (mm) of one story (1-based): the frame's own hysteresis."""
    return _story_loop(result, story, path, "story_hysteresis.png", result.story_shear, "frame shear", title=title)


def plot_energy(result: SimulationResult, path: str | os.PathLike[str], title: str | None = None) -> Path:
    """Stacked energy histories (kN*m = 1e6 N*mm) with the input energy on top.

    The walls' band is the work done on them (``energy.wall_work``): the heat they dissipated plus the
    energy they store, which an amplitude-following wall can also gain or lose at no work as its moduli
    change (``energy.wall_parameter_loss``), so it is not their heat alone.  Inherent damping and story yielding
    (hysteretic) dissipate; frame strain and kinetic energy are stored.  With P-Delta, gravity also does work
    (``energy.p_delta`` <= 0): the stack then reaches input - p_delta, drawn dashed.
    """
    path = figure_path(path, "energy.png")
    plt = pyplot()
    energy = result.energy
    figure, axes = plt.subplots(figsize=(9.5, 4.0))
    parts = [("walls (work done on them)", energy.wall_work), ("inherent damping", energy.inherent_damping),
             ("story yielding", energy.hysteretic), ("frame strain", energy.frame_strain),
             ("kinetic", energy.kinetic)]
    parts = [(name, values) for name, values in parts if np.abs(values).max() > 0.0]
    if parts:  # (none at rest, or in a run that stopped at its first step)
        axes.stackplot(result.time, *[values / 1e6 for _, values in parts], labels=[name for name, _ in parts],
                       alpha=0.8)
    axes.plot(result.time, energy.input / 1e6, "k", lw=1.0, label="input")
    if np.abs(energy.p_delta).max() > 0.0:
        axes.plot(result.time, (energy.input - energy.p_delta) / 1e6, "k--", lw=0.8, label="input + gravity (P-Delta)")
    axes.set_xlabel("time (s)")
    axes.set_ylabel("energy (kN m)")
    axes.grid(True, alpha=0.3)
    # Beside the axes: inside, the legend covered the histories (they rise from the upper left corner).
    axes.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    if title:
        axes.set_title(title, fontsize="medium")
    return save(figure, path)
