"""Walls that heat: the example frame isothermal at 21.2 degC against self-heating walls from 0, 21.2 and 40 degC.

The example frame (examples/ten_story.toml) runs on the shipped record (25 s) and, when the shared
records are there, on HWA002-N (Chi-Chi 1999, 80 s), each at the example's intensity (HWA002-N scaled to
the shipped record's spectrum as examples/wall_sizing.py does).  Four runs per record:

- isothermal: the walls' parameters stay those of the paper's tests (21.2 degC) -- the package's walls
  before they could heat;
- self-heating from an ambient (and initial) temperature of 0, 21.2 and 40 degC: the viscoelastic
  layers heat with the energy they dissipate (adiabatic during the record) and their viscosities follow
  the temperature through the shift law (time-temperature superposition, eta x a_T^r).

The shift law (``ISD110_LOSS_PEAK``, fitted to Ver & Beranek 2006, Table 14.1, 3M ISD-110) and the heat
capacity (1.8 J/(cm^3 K)) are assumptions stated in the building file: the paper gives no temperature
data.  Prints the peak drift ratio, the largest wall force and the largest temperature rise of every
run; draws the hottest wall's temperature against time and its loops in the first and last strong
seconds of each record.

    python examples/heating.py [--records DIR] [--out DIR]
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import warnings
from pathlib import Path

import numpy as np

import vdw_frames as vdw
from vdw_frames import plotting
from vdw_frames.cli import plain_warnings
from vdw_frames.config import load_building
from vdw_frames.motion import G, GroundMotion, default_record, read_at2

ROOT = Path(__file__).resolve().parents[1]
BUILDING_FILE = Path(__file__).with_name("ten_story.toml")
DEFAULT_RECORDS = ROOT.parent / "shared" / "ground_motions"
AMBIENTS = (0.0, 21.2, 40.0)  # degC
PERIOD_RANGE = (0.2, 2.0)  # x T1, as examples/wall_sizing.py scales the suite


def isothermal(building: vdw.ShearBuilding) -> vdw.ShearBuilding:
    """``building`` with walls that do not heat (no thermal description; parameters of 21.2 degC)."""
    return building.with_walls({story: tuple(dataclasses.replace(wall, thermal=None) for wall in walls)
                                for story, walls in building.walls.items()})


def from_ambient(building: vdw.ShearBuilding, temperature: float) -> vdw.ShearBuilding:
    """``building`` with walls that heat from ``temperature`` (degC, also their ambient)."""
    return building.with_walls({story: tuple(wall.at_ambient(temperature) for wall in walls)
                                for story, walls in building.walls.items()})


def records(folder: Path) -> list[GroundMotion]:
    """The shipped record, and HWA002-N at the same intensity when ``folder`` holds it."""
    shipped = default_record()
    motions = [shipped]
    path = folder / "HWA002-N.AT2"
    if path.is_file():
        building = load_building(BUILDING_FILE)
        period = vdw.modal_analysis(building.walls_at()).periods[0]  # walls at the log-centre of their range
        periods = np.geomspace(PERIOD_RANGE[0] * period, PERIOD_RANGE[1] * period, 60)
        record = read_at2(path)
        motions.append(record.scaled(float(np.exp(np.mean(np.log(shipped.spectrum(periods)
                                                                 / record.spectrum(periods)))))))
    else:
        print(f"heating.py: {path} not found: running the shipped record only")
    return motions


def run(motion: GroundMotion) -> dict[str, vdw.SimulationResult]:
    """The four runs of the module docstring; the package's warnings printed, naming the run."""
    building = load_building(BUILDING_FILE)
    variants = {"isothermal 21.2 degC": isothermal(building)}
    variants.update({f"heating from {ambient:g} degC": from_ambient(building, ambient) for ambient in AMBIENTS})
    runs = {}
    for label, variant in variants.items():
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            runs[label] = vdw.simulate(variant, motion)
        for warning in dict.fromkeys(str(w.message) for w in caught):
            print(f"warning: {label}: {warning}")
    return runs


def strong_motion(motion: GroundMotion) -> tuple[float, float]:
    """The 5-95 % Arias-intensity interval (s), the record's strong motion."""
    arias = np.cumsum(motion.acceleration ** 2)
    arias /= arias[-1]
    time = np.arange(motion.acceleration.size) * motion.dt
    return float(time[np.searchsorted(arias, 0.05)]), float(time[np.searchsorted(arias, 0.95)])


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], allow_abbrev=False)
    parser.add_argument("--records", type=Path, default=DEFAULT_RECORDS,
                        help="folder of the shared AT2 records (default ../shared/ground_motions)")
    parser.add_argument("--out", type=Path, default=Path("out-heating"), help="folder for the figures")
    args = parser.parse_args(argv)
    for motion in records(args.records):
        print(f"\n{motion.name}: PGA {motion.pga / G:.3f} g, {motion.acceleration.size * motion.dt:.0f} s")
        runs = run(motion)
        print(f"{'walls':24s} {'peak drift %':>12s} {'peak wall force kN':>18s} {'max temperature rise K':>22s} "
              f"{'hottest wall at end degC':>24s}")
        for label, result in runs.items():
            heats = label.startswith("heating")
            hot = f"{np.max(result.peak_temperature_rise):22.1f}" if heats else "-"
            end = f"{np.max(result.wall_temperature[-1]):24.1f}" if heats else "-"
            print(f"{label:24s} {100 * result.peak_drift_ratio.max():12.3f} "
                  f"{np.abs(result.wall_force).max() / 1e3:18.0f} {hot:>22s} {end:>24s}")
        heated = {label: result for label, result in runs.items() if label.startswith("heating")}
        reference = heated["heating from 21.2 degC"]
        hottest = int(np.nanargmax(reference.peak_temperature_rise)) + 1
        story = reference.building.wall_list[hottest - 1][0]
        start, stop = strong_motion(motion)
        window = min(4.0, (stop - start) / 3)
        name = motion.name.replace(" ", "_")
        figures = [
            plotting.plot_wall_temperature(heated, hottest, args.out / f"{name}_wall_temperature.png",
                                           title=f"{motion.name}: story {story} wall (the hottest from 21.2 degC)"),
            plotting.plot_wall_loops(reference, hottest, [(start, start + window), (stop - window, stop)],
                                     args.out / f"{name}_wall_loops.png",
                                     title=f"{motion.name}: story {story} wall heating from 21.2 degC\n"
                                           "start and end of the strong motion (5-95 % Arias)"),
        ]
        print("figures: " + ", ".join(str(path) for path in figures))
    return 0


if __name__ == "__main__":
    with plain_warnings():  # one line "warning: ...", as the vdw-frames command prints them
        sys.exit(main())
