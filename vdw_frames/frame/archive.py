"""One ``.npz`` file of numpy arrays and a JSON text: how a result is saved and loaded back
(:meth:`vdw_frames.frame.results.SimulationResult.save` and ``load``).

The JSON names each object by its class, from a fixed list of the package's frozen dataclasses (the
walls, their thermal descriptions and limits, the story models, the building) and any the caller adds,
and gives its constructor arguments: reading rebuilds them through their constructors (which check them
again) and never unpickles anything, so a file from elsewhere cannot run code.
"""

from __future__ import annotations

import dataclasses
import json
import os
import zipfile
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from .._files import file_path, write_via
from ..element.damper import FDMKDamper
from ..element.limits import WallLimits
from ..element.strain_dependent import StrainDependentDamper
from ..element.supported import SupportedDamper
from ..element.thermal import WLF, Arrhenius, LogLinear, ThermalProperties
from .building import ShearBuilding
from .hysteresis import Bilinear, BoucWen

# The classes an archive may hold; nothing else is built on reading.
_CLASSES: tuple[type, ...] = (ShearBuilding, FDMKDamper, SupportedDamper, StrainDependentDamper, ThermalProperties,
                              WLF, Arrhenius, LogLinear, WallLimits, Bilinear, BoucWen)


def write_archive(path: str | os.PathLike[str], arrays: Mapping[str, np.ndarray], metadata: Mapping[str, object],
                  kind: str, classes: Iterable[type] = ()) -> Path:
    """Write ``arrays`` and ``metadata`` (JSON-encoded, objects of the known ``classes`` by constructor
    arguments) to ``path``, a ``.npz`` file, atomically: an existing file stays whole until the new one is
    complete.  ``kind`` names the format, checked on reading.  Returns the path."""
    target = file_path(path, "file")
    if target.suffix != ".npz":
        raise ValueError(f"{path}: give a file name ending in .npz")
    if "metadata" in arrays:
        raise ValueError("an array may not be called 'metadata'")
    known = _known(classes)
    text = json.dumps({"format": kind, **{name: _encode(value, known) for name, value in metadata.items()}})
    contents = {**arrays, "metadata": np.array(text)}

    def write(temporary: Path) -> None:
        with open(temporary, "wb") as file:
            np.savez_compressed(file, **contents)  # type: ignore[arg-type]

    write_via(target, write)
    return target


def read_archive(path: str | os.PathLike[str], kind: str,
                 classes: Iterable[type] = ()) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
    """The arrays and the decoded metadata of a file :func:`write_archive` wrote with this ``kind``."""
    target = file_path(path, "file")
    try:
        with np.load(target, allow_pickle=False) as data:
            arrays = {name: data[name] for name in data.files}
        metadata = json.loads(str(arrays.pop("metadata")))
    except (OSError, ValueError, KeyError, zipfile.BadZipFile, EOFError):
        raise ValueError(f"{path}: not a {kind} file (a saved result)") from None
    if not isinstance(metadata, dict) or metadata.pop("format", None) != kind:
        raise ValueError(f"{path}: not a {kind} file (written by another version, or not a saved result)")
    known = _known(classes)
    try:
        return arrays, {name: _decode(value, known) for name, value in metadata.items()}
    except (TypeError, KeyError) as error:
        raise ValueError(f"{path}: an entry that cannot be read ({error})") from None


def _known(classes: Iterable[type]) -> dict[str, type]:
    return {cls.__name__: cls for cls in (*_CLASSES, *classes)}


def _encode(value: object, known: dict[str, type]) -> Any:
    """A JSON value for ``value``: the known dataclasses by class name and constructor arguments."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        name = type(value).__name__
        if known.get(name) is not type(value):
            raise TypeError(f"cannot save a {name}")
        return {"class": name, "arguments": {item.name: _encode(getattr(value, item.name), known)
                                             for item in dataclasses.fields(value) if item.init}}
    if isinstance(value, dict):
        return {"items": [[_encode(key, known), _encode(item, known)] for key, item in value.items()]}
    if isinstance(value, (tuple, list)):
        return {"tuple": [_encode(item, known) for item in value]}
    if isinstance(value, np.ndarray):
        return {"array": value.tolist(), "dtype": value.dtype.str}
    if isinstance(value, np.generic):
        return value.item()
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    raise TypeError(f"cannot save a {type(value).__name__}")


def _decode(value: Any, known: dict[str, type]) -> Any:
    if isinstance(value, list):
        raise TypeError("a bare list")
    if not isinstance(value, dict):
        return value
    if set(value) == {"class", "arguments"} and isinstance(value["arguments"], dict):
        cls = known.get(value["class"])
        if cls is None:
            raise KeyError(f"class {value['class']!r}")
        return cls(**{name: _decode(item, known) for name, item in value["arguments"].items()})
    if set(value) == {"items"}:
        return {_decode(key, known): _decode(item, known) for key, item in value["items"]}
    if set(value) == {"tuple"}:
        return tuple(_decode(item, known) for item in value["tuple"])
    if set(value) == {"array", "dtype"}:
        return np.array(value["array"], dtype=np.dtype(value["dtype"]))
    raise KeyError(f"entry {sorted(value)}")
