"""What every figure shares: matplotlib loaded on first use (Agg backend), the figure path rule, saving."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .._files import file_path, write_via
from .._validation import show, whole_number

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..frame.results import SimulationResult

_FORMATS = {"eps", "jpeg", "jpg", "pdf", "pgf", "png", "ps", "raw", "rgba", "svg", "svgz", "tif", "tiff", "webp"}


def pyplot() -> Any:
    """matplotlib.pyplot on the Agg backend, imported on first use (~0.3 s that ``import vdw_frames``
    should not pay)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def figure_path(path: str | os.PathLike[str], default_name: str) -> Path:
    """Where a figure for ``path`` goes (see :mod:`vdw_frames.plotting`); the folder is created."""
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


def story_number(result: SimulationResult, story: int) -> int:
    """``story`` (1-based) checked against ``result.building``."""
    message = f"story must be a story number in 1 ... {result.building.stories}, got {show(story)}"
    try:
        story = whole_number("story", story, 1)
    except ValueError:
        raise ValueError(message) from None
    if story > result.building.stories:
        raise ValueError(message)
    return story


def save(figure: Figure, path: Path) -> Path:
    """Lay out, write and close ``figure``; returns ``path``."""
    figure.tight_layout()
    try:
        write_via(path, lambda temporary: figure.savefig(temporary, dpi=120, format=path.suffix.lstrip(".").lower()))
    finally:
        pyplot().close(figure)
    return path
