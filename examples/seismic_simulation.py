"""Seismic simulation of a yielding 10-story shear building with and without "5+4" viscoelastic damping walls.

Building (examples/ten_story.toml; N-mm-s-tonne): floor masses 600 t (roof 450 t); story stiffnesses
300 kN/mm at the base falling by 15 kN/mm a story; story heights 4.0 m (first) and 3.5 m; 5 % Rayleigh
damping in modes 1 and 2 (bare elastic frame: T1 = 1.98 s).  Stories yield (Bilinear, OpenSees Steel01
without isotropic hardening, 3 % post-yield stiffness) at strengths set by a stated code-like rule:
a design base shear of 0.05 W (W the seismic weight, 57.4 MN) distributed over the height as
ASCE 7-16 §12.8.3 does (F_x proportional to w_x h_x^k, k = 1.74 for T1 = 1.98 s), times an overstrength
of 2.5 -- story 1 yields at 0.125 W.  P-Delta: each story carries the weight above it (leaning column).

Walls (one a story): the paper's three sets (225, 300, 450 %) as one strain-dependent family with one
fractional order, each wall following its own strain amplitude step by step, heating itself (from
21.2 degC, the paper's test temperature) and failing at a stated strain; sized by the rule of
examples/wall_sizing.py so that at this example's intensity their amplitudes stay inside 225-450 %.
The building file states the assumptions (shift law, heat capacity, failure strain) and their sources.
Here the walls also cool: each layer towards the plates with its conduction time h^2 / (pi^2 kappa)
(vdw_frames.element.thermal.conduction_time, kappa = 0.1 mm^2/s, an assumption): 6.5 s for the roof wall's
2.53 mm layers, 67 s for story 1's 8.12 mm -- the thin roof layers would not stay adiabatic over the record.

The same frame is run with three wall models, each named by what it includes, to show what the choice
does: "amplitude, heating" -- the walls follow their amplitude in the time domain, heat, cool and can fail
(the model); "equiv.-linear, heating" -- each wall fixed at an effective amplitude, 0.65 x its peak,
iterated, heating, cooling and able to fail as the model; "fixed 300 %, no heat" -- every wall the 300 % set,
neither heating nor failing (classical linear viscoelastic walls, as another program such as OpenSees takes
them).

    python examples/seismic_simulation.py [--record PATH.AT2] [--pga PGA_g | --factor F] [--out DIR]

Without --record it runs the synthetic record that ships with the package (0.35 g).  Prints peak and
residual drift ratio, story ductility, peak floor acceleration and base shear for the bare frame and
the three wall models, then per story the walls' peak strain, the amplitude they followed, the time
outside their tested amplitudes, their temperature rise and failures; writes figures to --out.  Ten
seconds of free vibration follow the record, so that residual drifts are measured at rest.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import vdw_frames as vdw
from vdw_frames import plotting
from vdw_frames.cli import plain_warnings
from vdw_frames.config import load_building
from vdw_frames.element.thermal import conduction_time
from vdw_frames.motion import G, default_record, read_at2

BUILDING_FILE = Path(__file__).with_name("ten_story.toml")
FREE_VIBRATION = 10.0  # s after the record, for residual drifts at rest
MODELS = ("amplitude, heating", "equiv.-linear, heating", "fixed 300 %, no heat")


def example_building() -> vdw.ShearBuilding:
    """The 10-story example frame with its walls (examples/ten_story.toml), each cooling with its layers'
    conduction time (:func:`conduction_cooled`)."""
    return conduction_cooled(load_building(BUILDING_FILE))


def conduction_cooled(building: vdw.ShearBuilding) -> vdw.ShearBuilding:
    """``building`` with every heating wall cooling towards its ambient with the conduction time of its own
    layers, h^2 / (pi^2 kappa) (s; :func:`vdw_frames.element.thermal.conduction_time`)."""
    return building.with_walls({story: tuple(
        dataclasses.replace(wall, thermal=dataclasses.replace(wall.thermal,
                                                              cooling_time=conduction_time(wall.thickness)))
        if getattr(wall, "thermal", None) is not None else wall for wall in walls)
        for story, walls in building.walls.items()})


def classical_walls(building: vdw.ShearBuilding, strain: float = 3.0) -> vdw.ShearBuilding:
    """``building`` with walls of fixed parameters at ``strain`` that neither heat nor fail: the classical
    linear viscoelastic walls another program (OpenSees) can take."""
    return building.with_walls({story: tuple(dataclasses.replace(wall, thermal=None, limits=None) for wall in walls)
                                for story, walls in building.walls_at(strain).walls.items()})


def run_models(building: vdw.ShearBuilding, motion: vdw.GroundMotion) -> dict[str, vdw.SimulationResult]:
    """The bare frame and the three wall models (module docstring) under ``motion``."""
    options = dict(free_vibration=FREE_VIBRATION)
    return {
        "bare frame": vdw.simulate(building.without_devices(), motion, **options),
        MODELS[0]: vdw.simulate(building, motion, **options),
        MODELS[1]: vdw.simulate(building, motion, strain_compatible=True, **options),
        MODELS[2]: vdw.simulate(classical_walls(building, 3.0), motion, **options),
    }


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], allow_abbrev=False)
    parser.add_argument("--record", type=Path, help="PEER AT2 record (default: the shipped synthetic record)")
    scale = parser.add_mutually_exclusive_group()
    scale.add_argument("--pga", type=float, help="scale the record to this PGA, in g")
    scale.add_argument("--factor", type=float, help="multiply the record by this factor")
    parser.add_argument("--out", type=Path, default=Path("out"), help="folder for the figures (default ./out)")
    args = parser.parse_args(argv)
    try:
        return run(args)
    except (ValueError, OSError) as error:  # one error line, as the vdw-frames command gives
        print(f"seismic_simulation.py: error: {error}", file=sys.stderr)
        return 2


def run(args) -> int:
    motion = read_at2(args.record) if args.record else default_record()
    if args.pga is not None:
        if not args.pga > 0.0:
            raise ValueError(f"--pga must be a PGA > 0 in g, got {args.pga:g}")
        motion = motion.scaled_to_pga(args.pga * G)
    if args.factor is not None:
        motion = motion.scaled(args.factor)
    walled = example_building()
    print(f"record {motion.name}: {motion.acceleration.size} points, dt = {motion.dt:g} s, "
          f"PGA = {motion.pga / G:.3f} g")
    weight = float(np.sum(walled.masses)) * G
    strengths = np.array([model.yield_force for model in walled.story_models])
    print(f"frame: T1 = {walled.without_devices().periods[0]:.2f} s (bare, elastic), story strengths "
          f"{strengths[0] / weight:.3f} W at the base to {strengths[-1] / weight:.3f} W at the top "
          f"(W = {weight / 1e6:.1f} MN), 3 % hardening, P-Delta; inherent damping {walled.damping_description}")
    walls = walled.wall_list
    wall = walls[0][1]
    print(f"walls: {len(walls)} in stories {walls[0][0]}-{walls[-1][0]}, one family this package fitted to the paper's "
          f"three sets, Tables 1-3 (its common r = {wall.common_order:.3f}, not a value of the paper; "
          f"{100 * wall.strain_range[0]:.0f}-{100 * wall.strain_range[1]:.0f} %); "
          f"areas {min(w.area for _, w in walls) / 1e6:.2f}-{max(w.area for _, w in walls) / 1e6:.2f} m^2, "
          f"layers {min(w.thickness for _, w in walls):g}-{max(w.thickness for _, w in walls):g} mm")
    print(f"  heating: from {wall.thermal.temperature:g} degC, rho c = {wall.thermal.heat_capacity:g} J/(cm^3 K) "
          "(assumed: the middle of 1.5-2.0 for filled polymers, ten_story.toml), "
          f"shift law {type(wall.thermal.shift).__name__}: {wall.thermal.shift.source}")
    cooling = [w.thermal.cooling_time for _, w in walls]
    print(f"  cooling: each wall with its layers' conduction time h^2 / (pi^2 kappa), kappa = 0.1 mm^2/s (assumed): "
          f"{min(cooling):.1f}-{max(cooling):.0f} s (roof {cooling[-1]:.1f} s); the plates taken at ambient")
    print(f"  failure: at {100 * wall.limits.strain:.0f} % shear strain: {wall.limits.source}")

    started = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        results = run_models(walled, motion)
    elapsed = time.perf_counter() - started
    for warning in dict.fromkeys(str(w.message) for w in caught):
        print(f"warning: {warning}")
    for label, result in results.items():
        if result.collapsed or not result.converged:
            print(f"{label}: {'collapsed' if result.collapsed else 'did not converge'} at t = {result.time[-1]:.2f} s")

    print_summary(results)
    print_walls(results)
    print(f"(four analyses took {elapsed:.2f} s)")
    print_figures(results, args.out)
    return 0


def print_summary(results: dict[str, vdw.SimulationResult]) -> None:
    """The frame's peaks under each model, and how far they move with the wall model."""
    rows = [
        ("peak drift ratio (%)", lambda r: 100 * r.peak_drift_ratio.max()),
        (f"resid. drift ratio, {FREE_VIBRATION:g} s after (%)", _residual),
        ("peak story ductility (-)", lambda r: r.peak_ductility.max()),
        ("peak abs. floor acceleration (g)", lambda r: r.peak_absolute_acceleration.max() / G),
        ("peak base shear, story 1 (kN)", lambda r: r.peak_base_shear / 1e3),
        ("  story-1 frame shear (kN)", lambda r: np.abs(r.story_shear[:, 0]).max() / 1e3),
        ("  story-1 walls (kN)", lambda r: np.abs(r.story_wall_force[:, 0]).max() / 1e3),
        ("peak roof displacement (mm)", lambda r: np.abs(r.displacement[:, -1]).max()),
    ]
    labels = list(results)
    print(f"\n{'response':34s} " + " ".join(f"{label:>22s}" for label in labels))
    for name, value in rows:
        print(f"{name:34s} " + " ".join(f"{value(results[label]):22.3f}" for label in labels))
    drifts = [100 * results[model].peak_drift_ratio.max() for model in MODELS]
    print(f"the wall model moves the peak drift ratio between {min(drifts):.2f} and {max(drifts):.2f} % "
          f"(bare frame {100 * results['bare frame'].peak_drift_ratio.max():.2f} %): the time-domain model is the "
          "package's; the other two fix each wall at one amplitude")
    print("(peak base shear: through story 1 -- its spring, walls, P-Delta and the inherent damping through it; "
          "Rayleigh's mass-proportional forces act between the floors and the ground and are not in it)")
    print("shares of the input energy at the end (walls: the work done on them):")
    for label in labels:
        shares = results[label].energy.shares()
        # round() to an int: a frame that never yields has a hysteretic energy of a rounding's size, which .0f
        # would print as "-0".
        print(f"  {label}: " + ", ".join(f"{name} {round(100 * shares[name])} %"
                                         for name in ("walls", "inherent damping", "story yielding")
                                         if name != "walls" or label != "bare frame"))
    energy = results[MODELS[0]].energy
    if energy.wall_parameter_loss is not None:
        change = -energy.wall_parameter_loss[-1]
        share = 100 * abs(change) / energy.input[-1]
        print(f"  {MODELS[0]}: as the walls' coefficients followed their amplitude and temperature, their stored "
              f"energy {'rose' if change > 0 else 'fell'} by {abs(change) / 1e6:.0f} kN m ({share:.1f} % "
              "of the input) at no work -- a secant amplitude model is not passive where the moduli rise with "
              "amplitude (the paper's sets stiffen from 225 to 450 %); the energy balance accounts for it, and the "
              f"walls' heat, {energy.wall_heat[-1] / 1e6:.0f} kN m, includes it (dT below comes from that heat)")


def print_walls(results: dict[str, vdw.SimulationResult]) -> None:
    """Per story: the walls' peak strain, followed amplitude, time outside the tested amplitudes,
    temperature rise and failure (time-domain model), with the equivalent-linear effective strain."""
    model = results[MODELS[0]]
    linear = results[MODELS[1]]
    fixed = results[MODELS[2]]
    walls = model.building.wall_list
    amplitude = model.wall_amplitude.max(axis=0)
    outside = model.wall_time_outside_range
    rise = model.peak_temperature_rise
    print(f"\nwalls, {MODELS[0]} (equivalent-linear: effective strain; fixed 300 %: peak strain):")
    print(f"{'story':>5s} {'peak strain %':>13s} {'amplitude %':>11s} {'below s':>8s} {'above s':>8s} "
          f"{'dT K':>6s} {'failed':>16s} {'eq.-lin. eff. %':>15s} {'fixed 300 % peak':>16s}")
    failure_time, failure_mode = model.wall_failure_time, model.wall_failure_mode
    for w, (story, _) in enumerate(walls):
        failed = f"{failure_mode[w]} at {failure_time[w]:.2f} s" if model.wall_failed[w] else "no"
        effective = linear.wall_effective_strain[w] if linear.wall_effective_strain is not None else np.nan
        print(f"{story:5d} {100 * model.peak_wall_strain[w]:13.0f} {100 * amplitude[w]:11.0f} {outside[w, 0]:8.2f} "
              f"{outside[w, 1]:8.2f} {rise[w]:6.1f} {failed:>16s} {100 * effective:15.0f} "
              f"{100 * fixed.peak_wall_strain[w]:16.0f}")
    print("  (amplitude: the largest half-cycle amplitude the wall followed; below/above: seconds spent below "
          "225 % or above 450 %, where the nearest set's parameters are used -- below, every record's build-up and "
          "decay; peak strain exceeds the amplitude by any drift offset; eq.-lin. eff.: 0.65 x the wall's peak strain, "
          "the effective-strain ratio of equivalent-linear site response (Idriss & Sun 1992), an assumption for walls; "
          "dT: the peak temperature rise from the walls' heat, each wall cooling with its conduction time)")


def print_figures(results: dict[str, vdw.SimulationResult], out: Path) -> None:
    without, model = results["bare frame"], results[MODELS[0]]
    ductile = int(np.argmax(without.peak_ductility.filled(0.0))) + 1
    story = int(np.argmax(model.peak_story_wall_force)) + 1
    wall = 1 + [s for s, _ in model.building.wall_list].index(story)  # the wall of that story (one a story)
    hottest = int(np.nanargmax(model.peak_temperature_rise)) + 1  # a wall number
    figures = [
        plotting.plot_drift_envelope(results, out / "drift_envelope.png"),
        plotting.plot_roof_displacement({label: results[label] for label in ("bare frame", MODELS[0])},
                                        out / "roof_displacement.png"),
        plotting.plot_story_hysteresis(without, ductile, out / "story_hysteresis_bare.png",
                                       title=f"bare frame, most ductile story ({ductile}): "
                                             f"ductility {without.peak_ductility[ductile - 1]:.1f}"),
        plotting.plot_story_hysteresis(model, ductile, out / "story_hysteresis_walls.png",
                                       title=f"with walls, story {ductile}: ductility "
                                             f"{model.peak_ductility[ductile - 1]:.1f}"),
        plotting.plot_wall_hysteresis(model, story, out / "wall_hysteresis.png",
                                      title=f"most loaded story ({story}): walls, {MODELS[0]}"),
        plotting.plot_wall_amplitude({MODELS[0]: model}, wall, out / "wall_amplitude.png",
                                     strain_range=model.building.wall_list[wall - 1][1].strain_range,
                                     title=f"wall {wall} (story {story}): strain and the amplitude it follows"),
        plotting.plot_wall_temperature({MODELS[0]: model}, hottest, out / "wall_temperature.png",
                                       title=f"hottest wall (story {model.building.wall_list[hottest - 1][0]})"),
        plotting.plot_energy(model, out / "energy.png", title=f"energy, walls ({MODELS[0]})"),
    ]
    print("figures: " + ", ".join(str(path) for path in figures))


def _residual(result) -> float:
    """Largest residual drift ratio (%) at the end of the free vibration."""
    return 100 * float(np.abs(result.residual_drift / np.asarray(result.building.story_heights)).max())


if __name__ == "__main__":
    with plain_warnings():  # one line "warning: ...", as the vdw-frames command prints them
        sys.exit(main())
