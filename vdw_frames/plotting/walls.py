"""Figures of the walls of time-history analyses: temperature, followed amplitude, loops in time windows.

Wall numbers are 1-based positions in ``result.building.wall_list``.  Forces are drawn in kN, strains
in %, temperatures in degC.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .._validation import finite_scalar, show, whole_number
from ._figure import figure_path, pyplot, save

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from ..frame.results import SimulationResult


def _wall_index(result: SimulationResult, wall: int) -> int:
    """``wall`` (1-based) checked against ``result.building.wall_list``; its 0-based index."""
    count = len(result.building.wall_list)
    message = f"wall must be a wall number in 1 ... {count} (building.wall_list order), got {show(wall)}"
    try:
        number = whole_number("wall", wall, 1)
    except ValueError:
        raise ValueError(message) from None
    if number > count:
        raise ValueError(message)
    return number - 1


def _wall_name(result: SimulationResult, index: int) -> str:
    """"wall N (story S)": the wall at 0-based ``index`` of ``result.building.wall_list``, and its story."""
    return f"wall {index + 1} (story {result.building.wall_list[index][0]})"


def _finish_history(figure: Figure, axes: Axes, ylabel: str, title: str | None, path: Path) -> Path:
    """Label a history against time (s), grid, legend and title; save the figure to ``path``."""
    axes.set_xlabel("time (s)")
    axes.set_ylabel(ylabel)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small", loc="best")
    if title:
        axes.set_title(title)
    return save(figure, path)


def plot_wall_temperature(results: Mapping[str, SimulationResult], wall: int, path: str | os.PathLike[str],
                          title: str | None = None) -> Path:
    """Temperature of wall ``wall``'s layers (degC) against time (s), one line per result (each wall must
    carry a thermal description)."""
    path = figure_path(path, "wall_temperature.png")
    plt = pyplot()
    figure, axes = plt.subplots(figsize=(8.0, 3.8))
    name = f"wall {wall}"
    for label, result in results.items():
        index = _wall_index(result, wall)
        name = _wall_name(result, index)
        temperature = result.wall_temperature
        if temperature is None or not np.isfinite(temperature[:, index]).all():
            raise ValueError(f"{label}: wall {wall} has no temperature (no thermal description)")
        axes.plot(result.time, temperature[:, index], lw=1.0, label=label)
    return _finish_history(figure, axes, f"{name} temperature (degC)", title, path)


def plot_wall_loops(result: SimulationResult, wall: int, windows: Sequence[tuple[float, float]],
                    path: str | os.PathLike[str], title: str | None = None) -> Path:
    """Force (kN) against strain (%) of wall ``wall`` within each time window (start, end) s, one loop per
    window -- e.g. the start and the end of a record, to see a wall soften as it heats."""
    index = _wall_index(result, wall)
    if not windows:
        raise ValueError("windows must hold at least one (start, end) time window (s)")
    spans = []
    for window in windows:
        if not isinstance(window, (tuple, list)) or len(window) != 2:
            raise ValueError(f"each window must be (start, end) in s, got {show(window)}")
        start, end = finite_scalar("window start", window[0]), finite_scalar("window end", window[1])
        if not start < end:
            raise ValueError(f"a window must end after it starts, got {show(window)}")
        mask = (result.time >= start) & (result.time <= end)
        if not mask.any():
            raise ValueError(f"window {show(window)} s holds no step of the analysis "
                             f"({result.time[0]:g} ... {result.time[-1]:g} s)")
        spans.append((start, end, mask))
    path = figure_path(path, "wall_loops.png")
    plt = pyplot()
    figure, axes = plt.subplots(figsize=(5.8, 4.8))
    for start, end, mask in spans:
        axes.plot(100.0 * result.wall_strain[mask, index], result.wall_force[mask, index] / 1e3, lw=0.8,
                  label=f"{start:.1f}-{end:.1f} s")
    axes.axhline(0.0, color="0.7", lw=0.5)
    axes.axvline(0.0, color="0.7", lw=0.5)
    axes.set_xlabel(f"{_wall_name(result, index)} strain (%)")
    axes.set_ylabel(f"{_wall_name(result, index)} force (kN)")
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small", loc="best")
    if title:
        axes.set_title(title)
    return save(figure, path)


def plot_wall_amplitude(results: Mapping[str, SimulationResult], wall: int, path: str | os.PathLike[str],
                        strain_range: tuple[float, float] | None = None, title: str | None = None) -> Path:
    """The strain amplitude (%) wall ``wall`` followed against time (s), one line per result, with the
    wall's |strain| (grey, one trace per result, in the legend) and its identified ``strain_range`` (-, e.g.
    (2.25, 4.5)) shaded.  The axis names the wall and its story (of the first result's building)."""
    path = figure_path(path, "wall_amplitude.png")
    plt = pyplot()
    figure, axes = plt.subplots(figsize=(8.0, 3.8))
    name = f"wall {wall}"
    for number, (label, result) in enumerate(results.items()):
        index = _wall_index(result, wall)
        if number == 0:
            name = _wall_name(result, index)
        amplitude = result.wall_amplitude
        if amplitude is None:
            raise ValueError(f"{label}: no wall follows its amplitude")
        axes.plot(result.time, 100.0 * np.abs(result.wall_strain[:, index]), color=str(0.75 - 0.15 * (number % 3)),
                  lw=0.5, label=f"{label}: |strain|")
        axes.plot(result.time, 100.0 * amplitude[:, index], lw=1.1, label=f"{label}: followed amplitude")
    if strain_range is not None:
        axes.axhspan(100.0 * strain_range[0], 100.0 * strain_range[1], color="tab:green", alpha=0.12,
                     label="identified range")
    return _finish_history(figure, axes, f"{name} strain (%)", title, path)
