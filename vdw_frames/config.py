"""Buildings described in small TOML or JSON files (for the ``vdw-frames simulate`` command).

Keys (units N-mm-s-tonne)::

    masses = [600, 600, 450]            # tonne, first floor up
    stiffnesses = [9e5, 7e5, 5e5]       # N/mm, story 1 first
    story_heights = [4000, 3500, 3500]  # mm, optional
    damping_ratio = 0.05                # optional (default 0.05)
    damping_modes = [1, 2]              # optional (default [1, 2]; [1, 1] for one story)
    damping_model = "rayleigh"          # optional: "rayleigh" (default) or "modal"
    gravity_loads = [1.6e7, 1.0e7, 4.4e6]  # N per story, optional: P-Delta (needs story_heights)
    strain_compatible = true            # optional (default false): equivalent-linear analysis, see below

    [site]                              # optional, for ``vdw-frames verify`` (ASCE 7-16 Sec. 11.4)
    sms = 1.5                           # g; or ss, s1 (g) and site_class = "D"
    sm1 = 0.9                           # g
    tl = 8.0                            # s
    risk_category = "II"                # optional (default "II")

    [verification]                      # optional, for ``vdw-frames verify``
    bounds = [0.8, 1.2]                 # the devices' lambda_min, lambda_max (ASCE 7-16 Sec. 18.2.4.5)
    bounds_source = "..."               # where they come from (optional)
    ambient = [0.0, 40.0]               # degC, the walls' service temperatures (optional; walls with thermal)
    lambda_includes_temperature = false # whether bounds already include temperature (optional; not with ambient)

    [hysteresis]                        # optional: yielding stories (default: all linear)
    model = "bilinear"                  # "bilinear" (Steel01-like) or "bouc-wen"
    yield_forces = [2e6, 1.6e6, 1e6]    # N, one per story
    hardening = 0.03                    # post-yield stiffness / initial (optional, default 0)
    # bouc-wen only, optional: exponent = 1.0, beta = 0.5, gamma = 0.5

    [[walls]]                           # any number of wall groups, optional
    stories = "all"                     # or a list of story numbers
    per_story = 2                       # walls in parallel in each of those stories (1 ... 1000)
    parameters = "fitted-300"           # recommended set for 225, 300 or 450 % strain ...
    # parameters = {G1 = 0.0, G2 = 3.0, eta1 = 0.3, eta2 = 2.0, r = 0.5}   # ... or explicit (MPa, MPa*s^r)
    # parameters = "strain-dependent"   # ... or the paper's strain-dependent model (225-450 %)
    area = 1.0e6                        # mm^2, optional (default: the paper's 1e6); or one per listed story
    thickness = 10.0                    # mm, optional (default: the paper's 10); or one per listed story
    magnification = 1.0                 # optional: wall deformation / story drift (default 1)

    [walls.thermal]                     # optional: walls that heat (vdw_frames.element.thermal)
    shift = "isd110-loss-peak"          # the examples' shift law (its source: ISD110_LOSS_PEAK.source), or
    # shift = {law = "wlf", C1 = 8.0, C2 = 120.0, reference = 21.2, valid = [0, 60], source = "..."}
    # shift = {law = "arrhenius", activation_energy = 2.0e5, reference = 21.2, valid = [0, 60], source = "..."}
    # shift = {law = "log-linear", degrees_per_decade = 19.45, reference = 21.2, valid = [0, 70], source = "..."}
    heat_capacity = 1.8                 # MPa/K = J/(cm^3 K), volumetric
    temperature = 21.2                  # degC, initial and ambient (optional: the law's reference)
    cooling_time = 600.0                # s, or "conduction" (each wall's h^2 / (pi^2 kappa)); optional (adiabatic)

    [walls.limits]                      # optional: walls that fail (vdw_frames.element.limits); any subset
    strain = 8.5                        # -, shear strain of rupture or debonding (8.5 = 850 %)
    stress = 2.0                        # MPa, bond shear strength
    temperature = 80.0                  # degC, the material's limit (walls with a thermal table)
    residual = 0.0                      # share of its force a failed wall keeps, in [0, 1)
    source = "..."                      # where the limits come from (the paper gives none)

    [[devices]]                         # any number of device groups, optional: any kind of damping device
    type = "fluid_viscous"              # "fluid_viscous" or "friction" (vdw_frames.element.devices.KINDS), or "wall"
    stories = [1, 2]                    # or "all" (default)
    per_story = 2                       # devices in parallel in each of those stories (1 ... 1000, default 1)
    C = 2.0e3                           # fluid_viscous: N (s/mm)^alpha; F = C |v|^alpha sgn(v)
    alpha = 0.5                         # fluid_viscous: velocity exponent in (0, 1]
    stiffness = 2.0e5                   # fluid_viscous: K_b, N/mm, the brace in series (optional for alpha = 1)
    # slip_force = 5.0e5                # friction: N, and stiffness (N/mm) until it slips
    magnification = 1.0                 # optional: device deformation / story drift (1 chevron, cos(theta) diagonal)

A device group's parameters are its class's arguments by name (:class:`~vdw_frames.FluidViscousDamper`,
:class:`~vdw_frames.FrictionDamper`), each one number or one per listed story.  ``type = "wall"`` takes the
keys of a ``[[walls]]`` group (and its ``thermal`` and ``limits`` tables) instead.  A story's devices are
its walls of ``[[walls]]`` first, then those of ``[[devices]]`` in the file's order; they act in parallel.

In TOML a wall group's ``[walls.thermal]`` and ``[walls.limits]`` tables follow its ``[[walls]]`` entry (a
``type = "wall"`` device group's, ``[devices.thermal]`` and ``[devices.limits]``).
JSON files use the same keys ("walls" and "devices" lists of objects).  TOML is read by tomllib (tomli before
Python 3.11).

Strain-dependent walls
----------------------
``parameters = "strain-dependent"`` gives the group :func:`vdw_frames.paper.strain_dependent` walls (one
common fractional order), whose FDMK parameters follow their own strain amplitude step by step in the
time-history analysis (:func:`vdw_frames.element.kernel.track_amplitude`).  The strain-compatible
(equivalent-linear) iteration of :mod:`vdw_frames.frame.strain_compatible` runs instead when the file
asks for it with the top-level ``strain_compatible = true`` (before any ``[[walls]]`` in TOML), or with a
table of the iteration's settings (:class:`~vdw_frames.frame.strain_compatible.StrainCompatibleOptions`;
any of them, the rest default)::

    [strain_compatible]
    effective_strain_ratio = 0.65       # effective / peak strain, in (0, 1]
    initial_strain = 3.0                # starting amplitude (3.0 = 300 %); default: the middle of the range
    tolerance = 0.01                    # converged when every effective strain changes by less than 1 %
                                        # (at least 1e-12: double precision cannot meet a tighter one)
    max_iterations = 20                 # at most 200: each iteration is a whole analysis

:func:`load_analysis` returns the building and the keyword arguments for
:func:`~vdw_frames.frame.simulation.simulate` that the file asks for (``vdw-frames simulate`` uses it);
:func:`load_building` returns the building alone.

:func:`save_building` writes a building (with a ``[site]`` and ``[verification]`` table when given) to a
file that :func:`load_building` reads back to an equal building, every float the same bits
(:func:`building_to_dict` gives the dict); what a file cannot say is refused (module functions' docstrings).

Files are UTF-8 (a byte-order mark is allowed).  Story numbers are whole numbers (``2`` or ``2.0``),
each at most once in a group.  Anything malformed is a ValueError naming the file and the key: an unknown
key in any table (``[site]`` and ``[verification]`` are checked whichever command reads the file), a key
given twice in a JSON object (``json`` alone would keep the last), a per-story list of another length
than ``masses``.  A group's walls are built once per distinct size (a 10 000-story group is one wall object).
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import sys
from pathlib import Path
from typing import Any, cast

import numpy as np

if sys.version_info >= (3, 11):
    import tomllib
else:  # Python 3.10: the same parser, as a package
    import tomli as tomllib

from ._files import read_text
from ._validation import show, whole_number
from .element.catalogue import STRAINS, fitted, strain_dependent
from .element.damper import FDMKDamper
from .element.device import Device
from .element.devices import KINDS
from .element.limits import WallLimits
from .element.strain_dependent import StrainDependentDamper
from .element.thermal import ISD110_LOSS_PEAK, WLF, Arrhenius, LogLinear, ThermalProperties, conduction_time
from .frame.building import ShearBuilding
from .frame.hysteresis import Bilinear, BoucWen
from .frame.strain_compatible import StrainCompatibleOptions
from .verification.spectrum import SITE_KEYS, Site, site_from_values
from .verification.verify import PropertyBounds

_BUILDING_KEYS = {"masses", "stiffnesses", "story_heights", "damping_ratio", "damping_modes", "damping_model",
                  "gravity_loads", "hysteresis", "walls", "devices", "strain_compatible", "site", "verification"}
_VERIFICATION_KEYS = {"ambient", "bounds", "bounds_source", "lambda_includes_temperature"}
_HYSTERESIS_KEYS = {"bilinear": {"model", "yield_forces", "hardening"},
                    "bouc-wen": {"model", "yield_forces", "hardening", "exponent", "beta", "gamma"}}
_STRAIN_COMPATIBLE_KEYS = {"effective_strain_ratio", "initial_strain", "tolerance", "max_iterations"}
_WALL_KEYS = {"stories", "per_story", "parameters", "area", "thickness", "thermal", "limits", "magnification"}
_GROUP_KEYS = {"type", "stories", "per_story"}
_ALL_DEVICE_KEYS = {item.name for kind in KINDS.values() for item in dataclasses.fields(kind)}
WALL_TYPE = "wall"
"""A ``[[devices]]`` group's ``type`` for FDMK walls (the keys of a ``[[walls]]`` group)."""
_THERMAL_KEYS = {"shift", "heat_capacity", "temperature", "cooling_time"}
_LIMIT_KEYS = {"strain", "stress", "temperature", "residual", "source"}
_SHIFT_LAWS: dict[str, tuple[type[WLF] | type[Arrhenius] | type[LogLinear], set[str]]] = {
    "wlf": (WLF, {"C1", "C2"}), "arrhenius": (Arrhenius, {"activation_energy"}),
    "log-linear": (LogLinear, {"degrees_per_decade"})}
_NAMED_SHIFT_LAWS = {"isd110-loss-peak": ISD110_LOSS_PEAK}
_PARAMETER_KEYS = {"G1", "G2", "eta1", "eta2", "r"}
MAX_PER_STORY = 1000
"""Most walls one group may put in parallel on a story (a bound, so a typo cannot exhaust memory)."""


def load_building(path: str | os.PathLike[str]) -> ShearBuilding:
    """Read a :class:`ShearBuilding` from a ``.toml`` or ``.json`` file (format in the module docstring)."""
    return load_analysis(path)[0]


def load_analysis(path: str | os.PathLike[str]) -> tuple[ShearBuilding, dict[str, Any]]:
    """(building, keyword arguments for ``simulate``) from a ``.toml`` or ``.json`` building file.

    The keywords are ``{"strain_compatible": True or StrainCompatibleOptions}`` when the file asks for a
    strain-compatible analysis, else empty.
    """
    path, data = _read_data(path)
    try:
        return building_from_dict(data), simulate_options(data)
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from None


def load_verification(path: str | os.PathLike[str]) -> tuple[ShearBuilding, Site | None, PropertyBounds | None]:
    """(building, site, property bounds) from a building file for ``vdw-frames verify``: its ``[site]`` table
    (keys of :func:`vdw_frames.verification.spectrum.site_from_values`: ``sms``, ``sm1`` or ``ss``, ``s1``,
    ``site_class``; ``tl``; ``risk_category``) and its ``[verification]`` table (``bounds = [lambda_min,
    lambda_max]``, the devices' property modification factors of ASCE 7-16 Sec. 18.2.4.5, ``bounds_source``,
    where they come from, and optionally ``ambient = [coldest, hottest]``, degC, the walls' service temperatures:
    :class:`~vdw_frames.verification.PropertyBounds`); None for a table the file does not have."""
    path, data = _read_data(path)
    try:
        return (building_from_dict(data), *site_and_bounds(data))
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from None


def site_and_bounds(data: dict[str, Any]) -> tuple[Site | None, PropertyBounds | None]:
    """(site, property bounds) of a building dict's ``[site]`` and ``[verification]`` tables (None for a table
    it does not have); :func:`building_from_dict` checks them too, so that every command that reads a building
    file refuses a typo in them, not only ``verify``."""
    site = None if "site" not in data else site_from_values(_table("site", data["site"], set(SITE_KEYS)))
    bounds = None
    if "verification" in data:
        table = _table("verification", data["verification"], _VERIFICATION_KEYS)
        values = table.get("bounds")
        if not isinstance(values, list) or len(values) != 2:
            raise ValueError(f"verification bounds must be [lambda_min, lambda_max], got {show(values)}")
        source = table.get("bounds_source", "stated in the building file")
        if not isinstance(source, str):
            raise ValueError(f"verification bounds_source must be text, got {show(source)}")
        ambient = table.get("ambient")
        if ambient is not None and (not isinstance(ambient, list) or len(ambient) != 2):
            raise ValueError(f"verification ambient must be [coldest, hottest] in degC, got {show(ambient)}")
        included = table.get("lambda_includes_temperature")
        if included is not None and not isinstance(included, bool):
            raise ValueError(f"verification lambda_includes_temperature must be true or false, got "
                             f"{show(included)}")
        bounds = PropertyBounds(values[0], values[1], source, None if ambient is None else tuple(ambient),
                                included)
    return site, bounds


def _read_data(path: str | os.PathLike[str]) -> tuple[Any, Any]:
    """(path, parsed contents) of a .toml or .json building file."""
    path, text = read_text(path, "building file")
    try:
        if path.suffix.lower() == ".toml":
            data = tomllib.loads(text)
        elif path.suffix.lower() == ".json":
            data = json.loads(text, object_pairs_hook=_unique_keys)
        else:
            raise ValueError(f"{path}: building files must end in .toml or .json")
    except (ValueError, RecursionError) as error:  # JSONDecodeError and TOMLDecodeError are ValueErrors
        if str(error).startswith(str(path)):
            raise
        if isinstance(error, _DuplicateKeyError):
            raise ValueError(f"{path}: {error}") from None
        raise ValueError(f"{path}: not valid {path.suffix[1:].upper()}: {error}") from None
    return path, data


class _DuplicateKeyError(ValueError):
    """A JSON object that gives one key twice."""


def _unique_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """A JSON object as a dict, refusing a key given twice (``json`` would keep the last one silently; TOML
    refuses it by itself)."""
    table: dict[str, Any] = {}
    for key, value in pairs:
        if key in table:
            raise _DuplicateKeyError(f"the key {key!r} is given twice in one JSON object (which one is meant? json "
                                     "would keep the last silently)")
        table[key] = value
    return table


def building_from_dict(data: dict[str, Any]) -> ShearBuilding:
    """A :class:`ShearBuilding` from a dict with the keys of the module docstring."""
    if not isinstance(data, dict):
        raise ValueError("a building must be a table of keys")
    unknown = set(data) - _BUILDING_KEYS
    if unknown:
        raise ValueError(f"unknown building keys {sorted(unknown)}; expected some of {sorted(_BUILDING_KEYS)}")
    for key in ("masses", "stiffnesses"):
        if key not in data:
            raise ValueError(f"missing key {key!r}")
        if not isinstance(data[key], list):
            raise ValueError(f"{key} must be a list of numbers, got {data[key]!r}")
    if not isinstance(data.get("damping_modes", []), list):
        raise ValueError(f"damping_modes must be a list of two mode numbers, got {data['damping_modes']!r}")
    if not isinstance(data.get("walls", []), list):
        raise ValueError(f"walls must be a list of wall groups, got {data['walls']!r}")
    if not isinstance(data.get("devices", []), list):
        raise ValueError(f"devices must be a list of device groups, got {show(data['devices'])}")
    stories = len(data["masses"])
    # One value per story in every list, checked before the walls, whose per-story lists would otherwise be
    # blamed for a masses or stiffnesses list of the wrong length.
    for key in ("stiffnesses", "story_heights", "gravity_loads"):
        if isinstance(data.get(key), list) and len(data[key]) != stories:
            raise ValueError(f"{key} must give one value per story: masses gives {stories} stories, {key} "
                             f"{len(data[key])} values")
    simulate_options(data)  # validated here too; load_analysis returns it
    site_and_bounds(data)  # likewise: a typo in [site] or [verification] is refused by every command
    dampers: dict[int, list[object]] = {}  # walls and the registered kinds
    groups = [(None, group) for group in data.get("walls", [])] + \
        [(_device_type(group), group) for group in data.get("devices", [])]
    for kind, group in groups:
        members: list[tuple[int, object]]
        if kind is None or kind == WALL_TYPE:
            walls, per_story = _wall_group(group if kind is None else _without_type(group), stories)
            members = list(walls)
        else:
            devices, per_story = _device_group(kind, group, stories)
            members = list(devices)
        for story, device in members:
            dampers.setdefault(story, []).extend([device] * per_story)
    # damping_modes only when the file gives them: else the building picks its default.
    modes = tuple(data["damping_modes"]) if "damping_modes" in data else None
    return ShearBuilding(
        data["masses"], data["stiffnesses"],
        damping_ratio=data.get("damping_ratio", 0.05),
        damping_modes=modes,
        devices={story: tuple(devices) for story, devices in sorted(dampers.items())},
        story_heights=data.get("story_heights"),
        hysteresis=_hysteresis(data.get("hysteresis"), stories),
        gravity_loads=data.get("gravity_loads"),
        damping_model=data.get("damping_model", "rayleigh"),
    )


def _hysteresis(table: object, stories: int) -> tuple[Bilinear | BoucWen, ...] | None:
    """The story models of a ``[hysteresis]`` table (module docstring), or None."""
    if table is None:
        return None
    if not isinstance(table, dict) or not isinstance(table.get("model"), str) or table["model"] not in _HYSTERESIS_KEYS:
        raise ValueError(f"hysteresis must be a table with model = 'bilinear' or 'bouc-wen', got {table!r}")
    keys = _HYSTERESIS_KEYS[table["model"]]
    unknown = set(table) - keys
    if unknown:
        raise ValueError(f"unknown hysteresis keys {sorted(unknown)}; expected some of {sorted(keys)}")
    forces = table.get("yield_forces")
    if not isinstance(forces, list) or len(forces) != stories:
        raise ValueError(f"hysteresis yield_forces must be a list of {stories} forces (N), got {forces!r}")
    options = {key: table[key] for key in keys - {"model", "yield_forces"} if key in table}
    model = Bilinear if table["model"] == "bilinear" else BoucWen
    return tuple(model(force, **options) for force in forces)


def simulate_options(data: dict[str, Any]) -> dict[str, Any]:
    """The keyword arguments for ``simulate`` that a building dict's ``strain_compatible`` key asks for."""
    value = data.get("strain_compatible", False)
    if isinstance(value, dict):
        unknown = set(value) - _STRAIN_COMPATIBLE_KEYS
        if unknown:
            raise ValueError(f"unknown strain_compatible keys {sorted(unknown)}; expected some of "
                             f"{sorted(_STRAIN_COMPATIBLE_KEYS)}")
        value = StrainCompatibleOptions(**value)
    elif not isinstance(value, bool):
        raise ValueError(f"strain_compatible must be true, false or a table of "
                         f"{sorted(_STRAIN_COMPATIBLE_KEYS)}, got {value!r}")
    return {"strain_compatible": value} if value is not False else {}


def _wall_group(group: object, stories: int) -> tuple[list[tuple[int, FDMKDamper | StrainDependentDamper]], int]:
    """([(story, wall)], walls per story) of one ``[[walls]]`` entry; area and thickness may be lists, one
    value per listed story."""
    if not isinstance(group, dict):
        raise ValueError(f"each walls entry must be a table, got {group!r}")
    unknown = set(group) - _WALL_KEYS
    if unknown:
        raise ValueError(f"unknown walls keys {sorted(unknown)}; expected some of {sorted(_WALL_KEYS)}")
    story_numbers = _story_numbers(group.get("stories", "all"), stories)
    per_story = whole_number("walls per_story", group.get("per_story", 1), 1)
    if per_story > MAX_PER_STORY:
        raise ValueError(f"walls per_story must be at most {MAX_PER_STORY}, got {per_story}")
    sizes = {key: group[key] for key in ("area", "thickness") if isinstance(group.get(key), list)}
    for key, values in sizes.items():
        if len(values) != len(story_numbers):
            raise ValueError(f"walls {key} must be one number or one per listed story ({len(story_numbers)} "
                             f"stories), got {len(values)} values")
    walls = []
    made: dict[str, FDMKDamper | StrainDependentDamper] = {}  # one wall per distinct size: the rest are the same
    for index, story in enumerate(story_numbers):
        each = {key: values[index] for key, values in sizes.items()}
        size = repr(sorted(each.items()))  # repr: 1 and 1.0 are one key to a dict, not to the constructor
        if size not in made:
            made[size] = _wall(dict(group, **each))
        walls.append((story, made[size]))
    return walls, per_story


def _device_type(group: object) -> str:
    """The ``type`` of a ``[[devices]]`` group: a registered kind (:data:`vdw_frames.element.devices.KINDS`) or
    ``"wall"``; a ValueError naming an unknown one and listing the known."""
    known = sorted([*KINDS, WALL_TYPE])
    if not isinstance(group, dict):
        raise ValueError(f"each devices entry must be a table, got {show(group)}")
    if "type" not in group:
        raise ValueError(f"each devices entry needs a type, one of {known}")
    kind = group["type"]
    if not isinstance(kind, str) or kind not in known:
        raise ValueError(f"unknown device type {show(kind)}; the known types are {known}")
    return kind


def _without_type(group: dict[str, Any]) -> dict[str, Any]:
    return {key: value for key, value in group.items() if key != "type"}


def _device_group(kind: str, group: dict[str, Any], stories: int) -> tuple[list[tuple[int, Device]], int]:
    """([(story, device)], devices per story) of one ``[[devices]]`` entry of a registered ``kind``: its
    class's arguments by name, each one number or one per listed story."""
    cls = KINDS[kind]
    parameters = {item.name for item in dataclasses.fields(cls)}
    unknown = set(group) - parameters - _GROUP_KEYS
    if unknown:
        raise ValueError(f"unknown {kind} device keys {sorted(unknown)}; expected some of "
                         f"{sorted(parameters | _GROUP_KEYS)}")
    story_numbers = _story_numbers(group.get("stories", "all"), stories, f"{kind} devices")
    per_story = whole_number(f"{kind} devices per_story", group.get("per_story", 1), 1)
    if per_story > MAX_PER_STORY:
        raise ValueError(f"{kind} devices per_story must be at most {MAX_PER_STORY}, got {per_story}")
    given = {key: group[key] for key in parameters if key in group}
    for key, values in given.items():
        if isinstance(values, list) and len(values) != len(story_numbers):
            raise ValueError(f"{kind} devices {key} must be one number or one per listed story "
                             f"({len(story_numbers)} stories), got {len(values)} values")
    devices: list[tuple[int, Device]] = []
    made: dict[str, Device] = {}  # one device per distinct set of values: the rest are the same
    for index, story in enumerate(story_numbers):
        each = {key: values[index] if isinstance(values, list) else values for key, values in given.items()}
        key = repr(sorted(each.items()))
        if key not in made:
            try:
                made[key] = cls(**each)
            except TypeError as error:  # a required parameter missing
                raise ValueError(f"{kind} devices: {error}; give {sorted(parameters)}") from None
            except ValueError as error:
                raise ValueError(f"{kind} devices (story {story}): {error}") from None
        devices.append((story, made[key]))
    return devices, per_story


def _wall(group: dict[str, Any]) -> FDMKDamper | StrainDependentDamper:
    """One wall of a ``[[walls]]`` entry whose area and thickness are numbers."""
    geometry = {key: group[key] for key in ("area", "thickness") if key in group}
    parameters = group.get("parameters")
    if isinstance(parameters, str) and parameters.startswith("fitted-"):
        try:
            strain = float(parameters.removeprefix("fitted-"))
        except ValueError:
            raise ValueError(f"walls parameters {parameters!r}: expected e.g. 'fitted-300'") from None
        wall: FDMKDamper | StrainDependentDamper = fitted(strain, **geometry)
    elif parameters == "strain-dependent":
        wall = strain_dependent(**geometry)
    elif isinstance(parameters, dict) and set(parameters) == _PARAMETER_KEYS:
        wall = FDMKDamper(**parameters, **geometry)
    else:
        raise ValueError(f"walls parameters must be 'fitted-225', 'fitted-300', 'fitted-450', 'strain-dependent' "
                         f"or a table with exactly {sorted(_PARAMETER_KEYS)}, got {parameters!r}")
    extras: dict[str, Any] = {}
    if "thermal" in group:
        extras["thermal"] = _thermal(group["thermal"], wall.thickness)
    if "limits" in group:
        extras["limits"] = _limits(group["limits"])
    if "magnification" in group:
        extras["magnification"] = group["magnification"]
    if extras:
        wall = dataclasses.replace(wall, **extras)
    return wall


def _story_numbers(story_numbers: object, stories: int, what: str = "walls") -> list[int]:
    """The story numbers of a ``stories`` key ("all" or a list of distinct story numbers) of a group of ``what``
    (for the messages: "walls", "friction devices", ...)."""
    if story_numbers == "all":
        return list(range(1, stories + 1))
    if isinstance(story_numbers, list):
        numbers = []
        for given in story_numbers:
            try:
                number = whole_number("story", given, 1)
            except ValueError:
                raise ValueError(f"{what} stories must be story numbers in 1 ... {stories}, got {show(given)} "
                                 f"in {show(story_numbers)}") from None
            if number > stories:
                # singular: "wall story", "friction device story"
                raise ValueError(f"{what.removesuffix('s')} story must be a story number in 1 ... {stories}, got "
                                 f"{number}")
            numbers.append(number)
        if not numbers:  # a group for no story is a mistake, not a building without those devices
            raise ValueError(f"{what} stories must be 'all' or a list of distinct story numbers, got [] (no story)")
        if len(set(numbers)) != len(numbers):
            raise ValueError(f"{what} stories must be 'all' or a list of distinct story numbers, got "
                             f"{show(story_numbers)}")
        return numbers
    raise ValueError(f"{what} stories must be 'all' or a list of distinct story numbers, got {show(story_numbers)}")


def _table(name: str, value: object, keys: set[str]) -> dict[str, Any]:
    """A table with only ``keys``."""
    if not isinstance(value, dict):
        raise ValueError(f"{name} must be a table of {sorted(keys)}, got {show(value)}")
    unknown = set(value) - keys
    if unknown:
        raise ValueError(f"unknown {name} keys {sorted(unknown)}; expected some of {sorted(keys)}")
    return value


def _thermal(value: object, thickness: float) -> ThermalProperties:
    """The :class:`ThermalProperties` of a ``[walls.thermal]`` table (module docstring) for walls of layers
    ``thickness`` mm thick (``cooling_time = "conduction"``: their conduction time)."""
    table = _table("walls thermal", value, _THERMAL_KEYS)
    if "shift" not in table or "heat_capacity" not in table:
        raise ValueError("walls thermal needs shift and heat_capacity (MPa/K = J/(cm^3 K))")
    shift = table["shift"]
    if isinstance(shift, str):
        if shift not in _NAMED_SHIFT_LAWS:
            raise ValueError(f"walls thermal shift must be one of {sorted(_NAMED_SHIFT_LAWS)} or a table with law = "
                             f"{' / '.join(repr(law) for law in _SHIFT_LAWS)}, got {shift!r}")
        law: WLF | Arrhenius | LogLinear = _NAMED_SHIFT_LAWS[shift]
    else:
        if not isinstance(shift, dict) or not isinstance(shift.get("law"), str) or shift["law"] not in _SHIFT_LAWS:
            raise ValueError(f"walls thermal shift must be one of {sorted(_NAMED_SHIFT_LAWS)} or a table with law = "
                             f"{' / '.join(repr(law) for law in _SHIFT_LAWS)}, got {show(shift)}")
        kind, constants = _SHIFT_LAWS[shift["law"]]
        fields = _table(f"walls thermal shift ({shift['law']})", shift,
                        constants | {"law", "reference", "valid", "source"})
        missing = (constants | {"reference", "valid"}) - set(fields)
        if missing:
            raise ValueError(f"walls thermal shift ({shift['law']}) needs {sorted(missing)}")
        valid = fields["valid"]
        if not isinstance(valid, list) or len(valid) != 2:
            raise ValueError(f"walls thermal shift valid must be [low, high] (degC), got {show(valid)}")
        arguments = {key: item for key, item in fields.items() if key != "law"}
        law = kind(**{**arguments, "valid": tuple(valid)})
    options = {key: table[key] for key in ("temperature", "cooling_time") if key in table}
    if isinstance(options.get("cooling_time"), str):
        if options["cooling_time"] != "conduction":
            raise ValueError(f"walls thermal cooling_time must be a time in s or \"conduction\", got "
                             f"{show(options['cooling_time'])}")
        options["cooling_time"] = conduction_time(thickness)
    return ThermalProperties(law, table["heat_capacity"], **options)


def _limits(value: object) -> WallLimits:
    """The :class:`WallLimits` of a ``[walls.limits]`` table (module docstring)."""
    return WallLimits(**_table("walls limits", value, _LIMIT_KEYS))


# ------------------------------------------------------------------------------------------ writing buildings
_FORMATS = (".toml", ".json")
_INLINE = {"parameters", "shift"}  # tables written inline (``parameters = {G1 = ...}``), as the docstring shows


def building_to_dict(building: ShearBuilding, *, site: Site | None = None,
                     bounds: PropertyBounds | None = None) -> dict[str, Any]:
    """The building file's dict (keys of the module docstring) of ``building``, from which
    :func:`building_from_dict` builds an equal building (every float the same bits); with ``site`` and
    ``bounds`` its ``[site]`` and ``[verification]`` tables, for ``vdw-frames verify``.

    Devices are written as ``[[devices]]`` groups (walls with ``type = "wall"``), one per position in the
    stories' device lists, so that every story gets its devices back in their order; a group covers the
    stories whose device at that position is of one kind and form (per-story values as lists).  ValueError
    naming what a building file cannot say: story models that differ in kind or in a parameter other than
    the yield force, linear stories among yielding ones, a wall of another kind than the catalogue's
    (``fitted-225/300/450``, ``strain-dependent``) or explicit FDMK parameters (a strain-dependent wall of
    other tables, a wall on a support), a device kind without a building-file type.
    """
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    data: dict[str, Any] = {"masses": _floats(building.masses), "stiffnesses": _floats(building.stiffnesses)}
    if building.story_heights is not None:
        data["story_heights"] = _floats(building.story_heights)
    if building.gravity_loads is not None:
        data["gravity_loads"] = _floats(building.gravity_loads)
    data["damping_ratio"] = float(building.damping_ratio)
    data["damping_modes"] = [int(mode) for mode in building.damping_modes]
    data["damping_model"] = building.damping_model
    hysteresis = _hysteresis_table(building)
    if hysteresis is not None:
        data["hysteresis"] = hysteresis
    groups = _device_groups(building)
    if groups:
        data["devices"] = groups
    if site is not None:
        data["site"] = _site_table(site)
    if bounds is not None:
        data["verification"] = _bounds_table(bounds)
    return data


def save_building(building: ShearBuilding, path: str | os.PathLike[str], *, site: Site | None = None,
                  bounds: PropertyBounds | None = None, comment: str | None = None) -> Path:
    """Write ``building`` (and ``site``, ``bounds``: :func:`building_to_dict`) to a ``.toml`` or ``.json``
    building file that :func:`load_building` (``vdw-frames simulate``, ``verify``, ``collapse``) reads back to an
    equal building; returns the path.

    TOML is written by this module's own writer for the few value kinds a building file holds (numbers,
    text, booleans, lists and tables; floats as Python's shortest round-trip ``repr``); JSON by ``json``.
    Before anything is written the text is read back (tomllib or json) and the building rebuilt from it: a
    building that would not come back equal is refused with a ValueError, and an existing file is left as
    it was (the write is atomic: :func:`vdw_frames._files.write_text`).  ``comment``: lines put at the head of
    a TOML file as ``#`` comments (JSON has none).
    """
    from ._files import file_path, write_text

    target = file_path(path, "building file")
    suffix = target.suffix.lower()
    if suffix not in _FORMATS:
        raise ValueError(f"{target}: building files must end in .toml or .json")
    data = building_to_dict(building, site=site, bounds=bounds)
    if suffix == ".json":
        text = json.dumps(data, indent=2, allow_nan=False, ensure_ascii=False) + "\n"
        parsed = json.loads(text)
    else:
        head = "".join(f"# {line}\n".replace("# \n", "#\n") for line in (comment or "").splitlines())
        text = head + _toml_document(data)
        parsed = tomllib.loads(text)
    try:
        again = building_from_dict(parsed)
        site_again, bounds_again = site_and_bounds(parsed)
    except ValueError as error:  # a defect of the writer: say so rather than write a file that cannot be read
        raise ValueError(f"{target}: the building cannot be written as a building file ({error})") from None
    if not _same_building(again, building) or (site is not None and not _same_spectrum(site_again, site)) or \
            (bounds is not None and bounds_again != bounds):
        raise ValueError(f"{target}: the building cannot be written exactly as a building file (read back, it "
                         "differs)")
    return write_text(target, text, "building file")


def _same_building(one: ShearBuilding, other: ShearBuilding) -> bool:
    """Whether two buildings are equal field by field (a ShearBuilding compares by identity)."""
    return all(getattr(one, item.name) == getattr(other, item.name) for item in dataclasses.fields(one))


def _same_spectrum(one: Site | None, other: Site) -> bool:
    """Whether two sites give the same MCE_R spectrum and risk category (how S_MS and S_M1 were found aside)."""
    return one is not None and all(getattr(one, name) == getattr(other, name)
                                   for name in ("sms", "sm1", "tl", "risk_category"))


def _floats(values: Any) -> list[float]:
    return [_number(value) for value in values]


def _number(value: Any) -> float:
    """A finite float (a building file holds no NaN or infinity)."""
    number = float(value)
    if not math.isfinite(number):
        raise ValueError(f"a building file holds finite numbers only, got {show(value)}")
    return number


def _hysteresis_table(building: ShearBuilding) -> dict[str, Any] | None:
    """The ``[hysteresis]`` table: one model and one set of parameters for every story, the yield forces
    per story."""
    models = building.hysteresis
    if models is None or all(model is None for model in models):
        return None
    if any(model is None for model in models):
        linear = [s + 1 for s, model in enumerate(models) if model is None]
        raise ValueError(f"stories {linear} are linear among yielding ones: a building file's [hysteresis] gives "
                         "every story a yield force")
    kinds = {type(model) for model in models}
    if len(kinds) != 1:
        raise ValueError("the stories mix Bilinear and BoucWen models: a building file's [hysteresis] has one model")
    first = cast("Bilinear | BoucWen", models[0])
    shared = [item.name for item in dataclasses.fields(first) if item.name != "yield_force"]
    for name in shared:
        values = {getattr(model, name) for model in models}
        if len(values) != 1:
            raise ValueError(f"the stories' {name} differ ({sorted(values)}): a building file's [hysteresis] gives "
                             "one")
    table: dict[str, Any] = {"model": "bilinear" if isinstance(first, Bilinear) else "bouc-wen",
                             "yield_forces": [_number(cast(Any, model).yield_force) for model in models]}
    table.update({name: _number(getattr(first, name)) for name in shared})
    return table


def _device_groups(building: ShearBuilding) -> list[dict[str, Any]]:
    """The ``[[devices]]`` groups of ``building`` (see :func:`building_to_dict`)."""
    # Each story's devices as runs of equal devices (per_story); run j of every story goes to the groups of
    # position j, in order, so that a story's devices come back in their order.
    runs = {story: _runs(devices) for story, devices in building.devices.items()}
    groups: list[dict[str, Any]] = []
    for position in range(max((len(r) for r in runs.values()), default=0)):
        members: dict[Any, list[tuple[int, dict[str, Any]]]] = {}
        for story, story_runs in runs.items():
            if position < len(story_runs):
                device, count = story_runs[position]
                fixed, varying = _device_entry(device, story)
                key = repr((sorted(fixed.items()), count, sorted(varying)))
                members.setdefault(key, []).append((story, {"fixed": fixed, "varying": varying, "count": count}))
        for entries in members.values():
            groups.append(_group(entries, building.stories))
    return groups


def _runs(devices: tuple[Device, ...]) -> list[tuple[Device, int]]:
    runs: list[tuple[Device, int]] = []
    for device in devices:
        if runs and runs[-1][0] == device and type(runs[-1][0]) is type(device):
            runs[-1] = (device, runs[-1][1] + 1)
        else:
            runs.append((device, 1))
    return runs


def _group(entries: list[tuple[int, dict[str, Any]]], stories: int) -> dict[str, Any]:
    """One ``[[devices]]`` group of the stories in ``entries`` (their devices of one kind and form)."""
    numbers = [story for story, _ in entries]
    first = entries[0][1]
    group: dict[str, Any] = {"type": first["fixed"]["type"],
                             "stories": "all" if numbers == list(range(1, stories + 1)) else numbers}
    if first["count"] != 1:
        group["per_story"] = first["count"]
    group.update({key: value for key, value in first["fixed"].items() if key != "type"})
    for key in first["varying"]:
        values = [entry["varying"][key] for _, entry in entries]
        group[key] = values[0] if all(value == values[0] for value in values) else values
    return group


def _device_entry(device: Device, story: int) -> tuple[dict[str, Any], dict[str, float]]:
    """(keys that must be the same in a group, incl. ``type``; numbers that may differ per story) of one
    device."""
    if isinstance(device, (FDMKDamper, StrainDependentDamper)):
        return _wall_entry(device, story)
    if getattr(device, "kind", None) == WALL_TYPE:  # a wall on a support, ...: no building-file keys
        raise ValueError(f"story {story}: a {type(device).__name__} cannot be written in a building file")
    kind = getattr(device, "kind", None)
    if kind not in KINDS or type(device) is not KINDS[kind]:
        raise ValueError(f"story {story}: a {type(device).__name__} has no type in building files (the known types: "
                         f"{sorted([*KINDS, WALL_TYPE])})")
    # A None (an FVD without a brace) is left out (TOML has no null): the group key tells it from a number.
    varying = {item.name: _number(getattr(device, item.name)) for item in dataclasses.fields(cast(Any, device))
               if getattr(device, item.name) is not None}
    return {"type": kind}, varying


def _wall_entry(wall: FDMKDamper | StrainDependentDamper, story: int) -> tuple[dict[str, Any], dict[str, float]]:
    """(fixed keys, per-story numbers) of one wall: its parameters named as the reader knows them."""
    geometry = {"area": wall.area, "thickness": wall.thickness}
    parameters: str | dict[str, float]
    if isinstance(wall, StrainDependentDamper):
        plain = dataclasses.replace(wall, thermal=None, limits=None, magnification=1.0)
        if plain != strain_dependent(area=wall.area, thickness=wall.thickness):
            raise ValueError(f"story {story}: a strain-dependent wall of other tables than the paper's "
                             "(parameters = \"strain-dependent\") cannot be written in a building file")
        parameters = "strain-dependent"
    elif type(wall) is not FDMKDamper:
        raise ValueError(f"story {story}: a {type(wall).__name__} cannot be written in a building file")
    else:
        values = {name: getattr(wall, name) for name in sorted(_PARAMETER_KEYS)}
        named = [strain for strain in STRAINS
                 if all(getattr(fitted(strain), name) == value for name, value in values.items())]
        parameters = f"fitted-{named[0]}" if named else {name: _number(value) for name, value in values.items()}
    fixed: dict[str, Any] = {"type": WALL_TYPE, "parameters": parameters}
    if wall.magnification != 1.0:
        fixed["magnification"] = _number(wall.magnification)
    if wall.thermal is not None:
        fixed["thermal"] = _thermal_table(wall.thermal)
    if wall.limits is not None:
        fixed["limits"] = {item.name: getattr(wall.limits, item.name) for item in dataclasses.fields(wall.limits)
                           if getattr(wall.limits, item.name) is not None}
    return fixed, {key: _number(value) for key, value in geometry.items()}


def _thermal_table(thermal: ThermalProperties) -> dict[str, Any]:
    shift: str | dict[str, Any]
    named = [name for name, law in _NAMED_SHIFT_LAWS.items() if law == thermal.shift]
    if named:
        shift = named[0]
    else:
        law = next(name for name, (kind, _) in _SHIFT_LAWS.items() if type(thermal.shift) is kind)
        shift = {"law": law, **{item.name: getattr(thermal.shift, item.name)
                                for item in dataclasses.fields(thermal.shift)}}
        shift["valid"] = [_number(value) for value in thermal.shift.valid]
    table: dict[str, Any] = {"shift": shift, "heat_capacity": _number(thermal.heat_capacity),
                             "temperature": _number(thermal.temperature)}
    if thermal.cooling_time != math.inf:  # inf (adiabatic) is the default, and TOML's inf is no JSON
        table["cooling_time"] = _number(thermal.cooling_time)
    return table


def _site_table(site: Site) -> dict[str, Any]:
    """The ``[site]`` table: the mapped values when the site came from them and they give it back, else S_MS
    and S_M1 themselves."""
    if not isinstance(site, Site):
        raise ValueError(f"site must be a Site, got {type(site).__name__}")
    table: dict[str, Any] = {"tl": _number(site.tl), "risk_category": site.risk_category}
    if site.ss is not None and site.s1 is not None and site.site_class is not None:
        mapped = {"ss": _number(site.ss), "s1": _number(site.s1), "site_class": site.site_class, **table}
        try:
            if site_from_values(mapped) == site:
                return mapped
        except ValueError:  # e.g. Sec. 11.4.8 refuses the mapped values for a damped structure: give S_MS, S_M1
            pass
    return {"sms": _number(site.sms), "sm1": _number(site.sm1), **table}


def _bounds_table(bounds: PropertyBounds) -> dict[str, Any]:
    if not isinstance(bounds, PropertyBounds):
        raise ValueError(f"bounds must be PropertyBounds, got {type(bounds).__name__}")
    table: dict[str, Any] = {"bounds": [_number(bounds.lower), _number(bounds.upper)],
                             "bounds_source": bounds.source}
    if bounds.ambient is not None:
        table["ambient"] = [_number(value) for value in bounds.ambient]
    if bounds.lambda_includes_temperature is not None:
        table["lambda_includes_temperature"] = bool(bounds.lambda_includes_temperature)
    return table


# The TOML writer: the value kinds of a building file only (tomllib reads; the standard library writes none).
def _toml_document(data: dict[str, Any]) -> str:
    lines: list[str] = []
    _toml_table(data, [], lines)
    return "\n".join(lines).lstrip("\n") + "\n"


def _toml_table(table: dict[str, Any], path: list[str], lines: list[str]) -> None:
    """``table``'s plain keys, then its sub-tables ``[path.key]`` and arrays of tables ``[[path.key]]``."""
    nested: list[tuple[str, Any]] = []
    for key, value in table.items():
        is_table = isinstance(value, dict) and key not in _INLINE
        if is_table or (isinstance(value, list) and value and all(isinstance(item, dict) for item in value)):
            nested.append((key, value))
        else:
            lines.append(f"{_toml_key(key)} = {_toml_value(value)}")
    for key, value in nested:
        name = ".".join(_toml_key(part) for part in [*path, key])
        for item in value if isinstance(value, list) else [value]:
            lines.append("")
            lines.append(f"[[{name}]]" if isinstance(value, list) else f"[{name}]")
            _toml_table(item, [*path, key], lines)


def _toml_key(key: str) -> str:
    return key if key and all(c.isascii() and (c.isalnum() or c in "_-") for c in key) else _toml_string(key)


def _toml_value(value: Any) -> str:
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(_number(value))  # the shortest text that reads back to the same float: valid TOML
    if isinstance(value, str):
        return _toml_string(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(item) for item in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_toml_key(k)} = {_toml_value(v)}" for k, v in value.items()) + "}"
    raise ValueError(f"a building file cannot hold {show(value)}")


_TOML_ESCAPES = {'"': '\\"', "\\": "\\\\", "\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f", "\r": "\\r"}


def _toml_string(text: str) -> str:
    """A TOML basic string: quotes, backslashes and control characters escaped."""
    return '"' + "".join(_TOML_ESCAPES.get(c, f"\\u{ord(c):04x}" if ord(c) < 0x20 or ord(c) == 0x7F else c)
                         for c in text) + '"'


# ------------------------------------------------------------------------------- design input (site.toml)
DESIGN_DEVICES = ("none", "walls", "fvd", "friction")
"""The ``device`` choices of a design input (``vdw-frames design-building --device``)."""
DEVICE_TYPES = {"walls": WALL_TYPE, "fvd": "fluid_viscous", "friction": "friction"}
"""The building-file ``type`` of each design device choice."""
_DESIGN_INPUT_KEYS = {"site", "building", "design"}
_DESIGN_BUILDING_KEYS = {"weights", "masses", "story_heights", "damping_ratio", "damping_modes"}
_DESIGN_KEYS = {"system", "device", "target_damping", "overstrength", "hardening", "rho", "minimum_stiffness",
                "irregular", "rounds", "bounds", "bounds_source", "records", "distribution", "p695",
                "prototype", "device_limits"}
WALL_RUPTURE_SOURCE = ("monotonic ultimate shear strain ~850 % of a full-scale TPE viscoelastic damper (TRCS500T-10), "
                       "abstract at https://synapsesocial.com/ar/papers/6992652ceb1f82dc367a11cf; not the paper's "
                       "material")
"""Where the default wall prototype's rupture strain (8.5) comes from."""
DEFAULT_PROTOTYPES: dict[str, dict[str, Any]] = {
    "walls": {"type": WALL_TYPE, "parameters": "fitted-300",
              "limits": {"strain": 8.5, "source": WALL_RUPTURE_SOURCE}},
    "fvd": {"type": "fluid_viscous", "C": 1.0e3, "alpha": 0.5, "stiffness": 1.0e5},
    "friction": {"type": "friction", "slip_force": 1.0e5, "stiffness": 1.0e5},
}
"""The device prototypes a design input without ``[design.prototype]`` gets (size_devices scales them): the
paper's wall identified at 300 % (A = 1e6 mm^2, h = 10 mm), failing at 850 % shear strain
(:data:`WALL_RUPTURE_SOURCE`: another material's test, not the paper's, whose tests stop at 450 % with no failure;
the same assumption as examples/ten_story.toml); a nonlinear FVD of alpha = 0.5 with a brace of
K_b = 100 C (N/mm; resizing keeps the ratio); a friction damper slipping at 1 mm (slip force / stiffness, which
resizing keeps).  This package's choices."""


@dataclasses.dataclass(frozen=True)
class DesignInput:
    """What a design input file (``site.toml``, :func:`load_design_input`) gives: ``site``; ``weights`` (N per
    floor, floor 1 first) and ``story_heights`` (mm); ``frame_options`` (keywords of
    :func:`vdw_frames.design.elf.design_frame`: overstrength, hardening, rho, minimum_stiffness, damping_ratio,
    damping_modes); ``system`` and ``device`` (None where the file does not say); ``prototype`` (a device,
    None where the file gives no ``[design.prototype]``); ``target_damping``, ``rounds``, ``bounds``
    (PropertyBounds or None), ``records`` (a P695 set name or a folder, resolved against the file's folder;
    None where not given), ``irregular``, ``distribution``, ``p695``, ``device_limits``."""

    site: Site
    weights: tuple[float, ...]
    story_heights: tuple[float, ...]
    frame_options: dict[str, Any]
    system: str | None = None
    device: str | None = None
    prototype: Device | None = None
    target_damping: float | None = None
    rounds: int | None = None
    bounds: PropertyBounds | None = None
    records: str | None = None
    irregular: bool = False
    distribution: str | None = None
    p695: bool = False
    device_limits: dict[str, float] = dataclasses.field(default_factory=dict)


def load_design_input(path: str | os.PathLike[str], damping_system: bool | None = None) -> DesignInput:
    """The design input of ``vdw-frames design-building`` from a ``.toml`` or ``.json`` file::

        [site]                      # as a building file's (site_from_values): sms, sm1 or ss, s1, site_class;
        ss = 0.75                   #   tl; risk_category (default "II")
        s1 = 0.3
        site_class = "C"
        tl = 8.0
        risk_category = "II"

        [building]
        weights = [5.884e6, ...]    # N, seismic weight of each floor, floor 1 first (or masses = [...], tonne)
        story_heights = [4000, ...] # mm, as many
        damping_ratio = 0.05        # optional: inherent damping (default 0.05), damping_modes = [1, 2]

        [design]                    # optional, every key optional
        system = "steel-smf"        # steel-smf, steel-imf, steel-omf, rc-smf (ASCE 7-16 Table 12.2-1)
        device = "walls"            # none (default: the bare frame by Chapter 12), walls, fvd, friction
        target_damping = 0.15       # mode-1 damping ratio the devices are first sized for, in (0, 1)
        overstrength = 1.0          # story strength / design story shear (>= 1)
        hardening = 0.03            # post-yield stiffness ratio of the Bilinear stories
        rho = 1.3                   # redundancy factor (default by SDC, Sec. 12.3.4)
        minimum_stiffness = 0.0     # N/mm, one number or one a story
        irregular = false           # Sec. 18.2.1.1: V_min = 1.0 V for the irregular structures it names
        rounds = 4                  # most verification rounds
        bounds = [0.8, 1.2]         # property modification factors (Sec. 18.2.4.5), needed with devices
        bounds_source = "..."       # where they come from
        records = "far-field"       # the verification's records: a FEMA P695 set or a folder of .AT2 files
        distribution = "stiffness"  # how size_devices spreads the devices over the stories
        p695 = false                # the FEMA P695 collapse assessment of the final design

        [design.prototype]          # optional: the device size_devices scales (keys of a [[devices]] group)
        type = "wall"               # wall, fluid_viscous or friction; must agree with device
        parameters = "fitted-300"
        thickness = 12.0

        [design.device_limits]      # optional: stroke (mm), velocity (mm/s), strain (-), temperature_rise (K)
        stroke = 60.0

    ``damping_system``: whether the design has devices, for the site's ASCE 7-16 Sec. 11.4.8 rule (a ground motion
    hazard analysis for structures with damping systems on sites with S_1 >= 0.6 g); None: as the input says (its
    ``device`` other than none; without one, a ``[design.prototype]``: the command line's choice).
    A relative ``records`` folder is read from the input file's folder.  ValueError naming the file and the key
    for anything malformed: unknown keys, weights and story heights of different lengths, both or neither of
    weights and masses, a prototype of another type than ``device``, an unknown device.
    """
    file, data = _read_data(path)
    try:
        return _design_input(data, Path(file).parent, damping_system)
    except ValueError as error:
        raise ValueError(f"{file}: {error}") from None


def _design_input(data: object, folder: Path, damping_system: bool | None = None) -> DesignInput:
    table = _table("design input", data, _DESIGN_INPUT_KEYS)
    if "site" not in table or "building" not in table:
        raise ValueError("a design input needs a [site] and a [building] table")
    design = _table("design", table.get("design", {}), _DESIGN_KEYS)
    if damping_system is None:
        damping_system = design["device"] != "none" if "device" in design else "prototype" in design
    site = site_from_values(_table("site", table["site"], set(SITE_KEYS)), damping_system=bool(damping_system))
    weights, heights, options = _design_floors(_table("building", table["building"], _DESIGN_BUILDING_KEYS))
    options.update({key: design[key] for key in ("overstrength", "hardening", "rho", "minimum_stiffness")
                    if key in design})
    device = design.get("device")
    if device is not None and device not in DESIGN_DEVICES:
        raise ValueError(f"unknown design device {show(device)}; expected one of {list(DESIGN_DEVICES)}")
    bounds = None
    if "bounds" in design:
        source = design.get("bounds_source", "stated in the design input")
        bounds = site_and_bounds({"verification": {"bounds": design["bounds"], "bounds_source": source}})[1]
    elif "bounds_source" in design:
        raise ValueError("design bounds_source without bounds")
    records = design.get("records")
    if records is not None:
        if not isinstance(records, str) or not records.strip():
            raise ValueError(f"design records must be a FEMA P695 set name or a folder, got {show(records)}")
        if "/" in records or os.sep in records or (folder / records).is_dir():
            records = str(folder / records)
    flags = {}
    for key in ("irregular", "p695"):
        if key in design and not isinstance(design[key], bool):
            raise ValueError(f"design {key} must be true or false, got {show(design[key])}")
        flags[key] = bool(design.get(key, False))
    limits = _table("design device_limits", design.get("device_limits", {}),
                    {"stroke", "velocity", "strain", "temperature_rise"})
    system = design.get("system")
    if system is not None and not isinstance(system, str):
        raise ValueError(f"design system must be a name such as 'steel-smf', got {show(system)}")
    return DesignInput(site=site, weights=weights, story_heights=heights, frame_options=options, system=system,
                       device=device, prototype=_prototype(design, device), target_damping=design.get("target_damping"),
                       rounds=design.get("rounds"), bounds=bounds, records=records, irregular=flags["irregular"],
                       distribution=design.get("distribution"), p695=flags["p695"], device_limits=dict(limits))


def _design_floors(floors: dict[str, Any]) -> tuple[tuple[float, ...], tuple[float, ...], dict[str, Any]]:
    """(weights N, story heights mm, design_frame options) of a design input's ``[building]`` table."""
    if ("weights" in floors) == ("masses" in floors):
        raise ValueError("building needs either weights (N per floor) or masses (tonne per floor), not both")
    if "story_heights" not in floors:
        raise ValueError("building needs story_heights (mm, story 1 first)")
    values: dict[str, tuple[float, ...]] = {}
    for key in ("weights", "masses", "story_heights"):
        if key in floors:
            given = floors[key]
            if not isinstance(given, list) or not given or \
                    not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in given):
                raise ValueError(f"building {key} must be a list of numbers, got {show(given)}")
            values[key] = tuple(float(v) for v in given)
    from .motion.record import G

    weights = values["weights"] if "weights" in values else tuple(m * G for m in values["masses"])
    heights = values["story_heights"]
    if len(weights) != len(heights):
        raise ValueError(f"weights and story heights of different lengths: {len(weights)} "
                         f"{'weights' if 'weights' in values else 'masses'} and {len(heights)} story heights")
    options: dict[str, Any] = {key: floors[key] for key in ("damping_ratio", "damping_modes") if key in floors}
    if "damping_modes" in options:
        if not isinstance(options["damping_modes"], list):
            raise ValueError(f"building damping_modes must be a list of two mode numbers, got "
                             f"{show(options['damping_modes'])}")
        options["damping_modes"] = tuple(options["damping_modes"])
    return weights, heights, options


def _prototype(design: dict[str, Any], device: str | None) -> Device | None:
    """The device of a design input's ``[design.prototype]`` table (None without one), of ``device``'s type."""
    if "prototype" not in design:
        return None
    group = _table("design prototype", design["prototype"], _WALL_KEYS | _GROUP_KEYS | _ALL_DEVICE_KEYS)
    kind = _device_type(group)
    if device not in (None, "none") and DEVICE_TYPES[device] != kind:
        raise ValueError(f"the design prototype is of type {kind!r} but device is {device!r} "
                         f"(type {DEVICE_TYPES[device]!r})")
    if "stories" in group or "per_story" in group:
        raise ValueError("the design prototype is one device: no stories or per_story")
    return building_from_dict({"masses": [1.0], "stiffnesses": [1.0], "devices": [group]}).device_list[0][1]
