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
import math
import os
import stat
import zipfile
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from .._files import file_path, write_via
from .._validation import MEMORY_LIMIT_BYTES
from ..element.damper import FDMKDamper
from ..element.friction import FrictionDamper
from ..element.limits import WallLimits
from ..element.strain_dependent import StrainDependentDamper
from ..element.supported import SupportedDamper
from ..element.thermal import WLF, Arrhenius, LogLinear, ThermalProperties
from ..element.viscous import FluidViscousDamper
from .building import ShearBuilding
from .hysteresis import Bilinear, BoucWen

# The classes an archive may hold; nothing else is built on reading.
_CLASSES: tuple[type, ...] = (ShearBuilding, FDMKDamper, SupportedDamper, StrainDependentDamper, FluidViscousDamper,
                              FrictionDamper, ThermalProperties,
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
        info = target.stat()
    except OSError as error:
        raise ValueError(f"{path}: cannot read the {kind} file ({error.strerror or error})") from None
    if not stat.S_ISREG(info.st_mode):  # a FIFO would block np.load forever
        raise ValueError(f"{path}: not a regular file (a folder, FIFO, socket or device); give a saved result")
    try:
        with zipfile.ZipFile(target) as archive:
            members = archive.infolist()
        size = sum(member.file_size for member in members)
        if size > MEMORY_LIMIT_BYTES:
            raise ValueError(f"{path}: its arrays would take {size:,} bytes, above the {MEMORY_LIMIT_BYTES:,} bytes "
                             "a saved result is read to")
        raw = sorted(member.filename for member in members if not member.filename.endswith(".npy"))
        if raw:
            raise ValueError(f"{path}: entries {raw} are not numpy arrays; not a {kind} file")
        for member in members:
            _declared_size_fits(target, member, path)
        with np.load(target, allow_pickle=False) as data:
            arrays = {name: data[name] for name in data.files}
        metadata = json.loads(str(arrays.pop("metadata")))
    except ValueError as error:
        if str(error).startswith(f"{path}: "):
            raise
        raise ValueError(f"{path}: not a {kind} file (a saved result)") from None
    except (OSError, KeyError, zipfile.BadZipFile, EOFError, RecursionError):
        raise ValueError(f"{path}: not a {kind} file (a saved result)") from None
    if not isinstance(metadata, dict) or metadata.pop("format", None) != kind:
        raise ValueError(f"{path}: not a {kind} file (written by another version, or not a saved result)")
    if _depth(metadata) > MAX_DEPTH:
        raise ValueError(f"{path}: metadata nested more than {MAX_DEPTH} deep, beyond what a saved result needs")
    known = _known(classes)
    decoded = {}
    for name, value in metadata.items():
        try:
            decoded[name] = _decode(value, known)
        except (TypeError, KeyError, ValueError) as error:
            raise ValueError(f"{path}: {name}: an entry that cannot be read ({error})") from None
    return arrays, decoded


def _declared_size_fits(target: Path, member: zipfile.ZipInfo, path: object) -> None:
    """Refuse an entry whose .npy header declares more data than the entry holds: numpy allocates the
    declared shape before it reads (a crafted 100-byte entry declaring 10^11 values would be a MemoryError)."""
    with zipfile.ZipFile(target) as archive, archive.open(member) as entry:
        version = np.lib.format.read_magic(entry)
        if version == (1, 0):
            shape, _, dtype = np.lib.format.read_array_header_1_0(entry)
        elif version == (2, 0):
            shape, _, dtype = np.lib.format.read_array_header_2_0(entry)
        else:
            raise ValueError(f"{path}: entry {member.filename!r}: .npy format {version} not read")
        declared = math.prod(shape) * dtype.itemsize
        if declared > member.file_size:
            raise ValueError(f"{path}: entry {member.filename!r} declares {shape} {dtype} ({declared:,} bytes) but "
                             f"holds {member.file_size:,} bytes; not a saved result")


MAX_DEPTH = 32
"""Deepest nesting of a saved result's JSON metadata read (a building with walls, their thermal description
and limits is ~8 deep); deeper is refused before it is decoded (it would exhaust Python's recursion)."""


def _depth(value: Any) -> int:
    """How deep ``value`` (decoded JSON) nests dicts and lists (counted without recursion, up to MAX_DEPTH + 1)."""
    deepest, stack = 0, [(value, 1)]
    while stack:
        item, level = stack.pop()
        if isinstance(item, (dict, list)):
            deepest = max(deepest, level)
            if level <= MAX_DEPTH:
                stack.extend((child, level + 1) for child in (item.values() if isinstance(item, dict) else item))
    return deepest


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
        dtype = np.dtype(value["dtype"])
        if dtype.kind not in "biuf":  # no object, datetime, text or structured arrays
            raise TypeError(f"an array of dtype {dtype}")
        return np.array(value["array"], dtype=dtype)
    raise KeyError(f"entry {sorted(value)}")
