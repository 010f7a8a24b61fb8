"""Figures of the devices that are not walls (fluid viscous and friction dampers): each one's loop.

Device numbers are 1-based positions in ``result.building.other_device_list`` (the columns of the result's
device histories).  Forces are drawn in kN, deformations (along the device) in mm.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .._validation import show, whole_number
from ._figure import figure_path, pyplot, save

if TYPE_CHECKING:
    from ..frame.results import SimulationResult

MAX_PANELS = 12
"""Most device loops one figure draws (a bound: a building file of 10 000 devices is not 10 000 panels)."""


def distinct_devices(result: SimulationResult) -> list[int]:
    """The device numbers (1-based, ``building.other_device_list`` order) of one device of each kind of equal
    devices on a story: equal devices side by side on a story move alike, so their loops are one."""
    first: dict[tuple[int, object], int] = {}  # devices are frozen dataclasses: equal ones hash alike
    for index, (story, device) in enumerate(result.building.other_device_list):
        first.setdefault((story, device), index + 1)
    return list(first.values())


def plot_device_loops(result: SimulationResult, path: str | os.PathLike[str], devices: Sequence[int] | None = None,
                      title: str | None = None) -> Path:
    """Force (kN) against deformation (mm), both along the device, of each device in ``devices`` (1-based
    numbers in ``result.building.other_device_list`` order; None: :func:`distinct_devices`), one panel each,
    titled by its number, story and ``describe()``; at most :data:`MAX_PANELS` panels."""
    others = result.building.other_device_list
    if not others:
        raise ValueError("the building has no device other than walls (fluid viscous or friction) to draw; its walls' "
                         "loops: plot_wall_loops")
    chosen = distinct_devices(result) if devices is None else list(devices)
    if not chosen:
        raise ValueError("devices must hold at least one device number")
    if len(chosen) > MAX_PANELS:
        raise ValueError(f"{len(chosen)} devices asked for: one figure draws at most {MAX_PANELS}; choose them "
                         "with devices=[...]")
    indices = []
    for number in chosen:
        message = f"devices must be device numbers in 1 ... {len(others)} (building.other_device_list order), got " \
                  f"{show(number)}"
        try:
            value = whole_number("device", number, 1)
        except ValueError:
            raise ValueError(message) from None
        if value > len(others):
            raise ValueError(message)
        indices.append(value - 1)
    path = figure_path(path, "device_loops.png")
    plt = pyplot()
    columns = min(len(indices), 3)
    rows = math.ceil(len(indices) / columns)
    figure, axes = plt.subplots(rows, columns, figsize=(4.2 * columns, 3.6 * rows), squeeze=False)
    for panel, index in zip(axes.flat, indices, strict=False):
        story, device = others[index]
        panel.plot(result.device_deformation[:, index], result.device_force[:, index] / 1e3, lw=0.7)
        panel.axhline(0.0, color="0.7", lw=0.5)
        panel.axvline(0.0, color="0.7", lw=0.5)
        panel.set_title(f"device {index + 1}, story {story}\n{device.describe()}", fontsize="small")
        panel.set_xlabel("deformation (mm)")
        panel.set_ylabel("force (kN)")
        panel.grid(True, alpha=0.3)
    for panel in list(axes.flat)[len(indices):]:
        panel.set_visible(False)
    if title:
        figure.suptitle(title)
    figure.tight_layout()
    return save(figure, path)


def largest_devices(result: SimulationResult, count: int = MAX_PANELS) -> list[int]:
    """Of :func:`distinct_devices`, the ``count`` of the largest peak force (device numbers, ascending)."""
    numbers = distinct_devices(result)
    peaks = np.abs(result.device_force).max(axis=0, initial=0.0)
    numbers = sorted(numbers, key=lambda number: -peaks[number - 1])[:count]
    return sorted(numbers)
