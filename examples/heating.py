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

Heating may be counted twice.  The paper's Tables 1-3 are "at 21.2 degC", but they were measured in
sinusoidal tests of several cycles, and each cycle heated the layers: one 300 % cycle dissipates
pi G'' gamma^2 per unit volume, 7.9-10.5 K at 0.5-10 Hz with the measured G'' (0.50-0.67 MPa) and
rho c = 1.8 J/(cm^3 K) -- 9.9 K at 1 Hz.  The identified parameters hold, then, at the test's mean
temperature, not at 21.2 degC, and a model that starts them at 21.2 degC and heats them again counts part of
the heating twice.  The paper does not say how many cycles (its reference [29] has the test details), so
the sensitivity is shown for two assumptions: the identified parameters taken at the mean temperature of
an adiabatic test of 1 and of 3 cycles at 300 % and 1 Hz, 21.2 + n x 9.9 / 2 degC (26.1 and 36.0 degC),
the walls heating from 21.2 degC as before (two more runs per record: the shift law's reference moved there,
:func:`at_test_temperature`).

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
TEST_TEMPERATURE = 21.2  # degC, the paper's Tables 1-3
TEST_CYCLES = (1, 3)  # cycles of the paper's tests, assumed (the paper does not say)
PERIOD_RANGE = (0.2, 2.0)  # x T1, as examples/wall_sizing.py scales the suite


def isothermal(building: vdw.ShearBuilding) -> vdw.ShearBuilding:
    """``building`` with walls that do not heat (no thermal description; parameters of 21.2 degC)."""
    return building.with_walls({story: tuple(dataclasses.replace(wall, thermal=None) for wall in walls)
                                for story, walls in building.walls.items()})


def from_ambient(building: vdw.ShearBuilding, temperature: float) -> vdw.ShearBuilding:
    """``building`` with walls that heat from ``temperature`` (degC, also their ambient)."""
    return building.with_walls({story: tuple(wall.at_ambient(temperature) for wall in walls)
                                for story, walls in building.walls.items()})


def cycle_rise(heat_capacity: float, strain: float = 3.0, frequency: float = 1.0) -> float:
    """The adiabatic temperature rise (K) of one test cycle at ``strain`` (-) and ``frequency`` (Hz):
    pi G'' gamma^2 / (rho c), G'' the paper's measured loss modulus (MPa, Tables 1-3), ``heat_capacity`` rho c
    in MPa/K."""
    frequencies, _, loss = vdw.paper.data.table_moduli(100.0 * strain)
    return float(np.pi * loss[list(frequencies).index(frequency)] * strain**2 / heat_capacity)


def at_test_temperature(building: vdw.ShearBuilding, temperature: float) -> vdw.ShearBuilding:
    """``building`` with every wall's parameters taken to hold at ``temperature`` (degC; its shift law's
    reference moved there) rather than at the paper's 21.2 degC; the walls still start at, and cool towards,
    their own temperature."""
    def moved(wall):
        law = dataclasses.replace(wall.thermal.shift, reference=temperature,
                                  source=f"{wall.thermal.shift.source}; reference moved to {temperature:g} degC, the "
                                         "assumed mean temperature of the paper's tests (examples/heating.py)")
        return dataclasses.replace(wall, thermal=dataclasses.replace(wall.thermal, shift=law))

    return building.with_walls({story: tuple(moved(wall) for wall in walls)
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
    rise = cycle_rise(building.wall_list[0][1].thermal.heat_capacity)
    for cycles in TEST_CYCLES:
        mean = TEST_TEMPERATURE + cycles * rise / 2.0
        variants[f"parameters at {mean:.1f} degC"] = at_test_temperature(building, mean)
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
            heats = not label.startswith("isothermal")
            hot = f"{np.max(result.peak_temperature_rise):22.1f}" if heats else "-"
            end = f"{np.max(result.wall_temperature[-1]):24.1f}" if heats else "-"
            print(f"{label:24s} {100 * result.peak_drift_ratio.max():12.3f} "
                  f"{np.abs(result.wall_force).max() / 1e3:18.0f} {hot:>22s} {end:>24s}")
        rise = cycle_rise(load_building(BUILDING_FILE).wall_list[0][1].thermal.heat_capacity)
        print(f"(parameters at T: the paper's sets taken at the mean temperature of an adiabatic test of "
              f"{' or '.join(str(n) for n in TEST_CYCLES)} cycles at 300 % and 1 Hz, {rise:.1f} K a cycle, instead "
              "of 21.2 degC; walls heating from 21.2 degC)")
        sensitivity = [label for label in runs if label.startswith("parameters at")]
        base = runs["heating from 21.2 degC"]
        for label in sensitivity:
            print(f"  {label}: peak drift x {runs[label].peak_drift_ratio.max() / base.peak_drift_ratio.max():.3f}, "
                  f"largest wall force x {np.abs(runs[label].wall_force).max() / np.abs(base.wall_force).max():.3f} "
                  "against heating from 21.2 degC with the parameters at 21.2 degC")
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
