"""The same added damping by four devices: VDW walls, linear and nonlinear fluid viscous dampers, friction dampers.

The 10-story example frame (examples/ten_story.toml without its walls: yielding Bilinear stories, P-Delta,
5 % Rayleigh damping) gets, in turn, four alternatives, each sized by ``vdw_frames.design.size_devices`` so
that mode 1 has the same added damping ratio above the bare frame's (the complex-mode ratio -Re s / |s| of
``modal_analysis``), one device a story, scaled in proportion to the story stiffness.  The target is
15 %; the walls cannot add that much to this frame (at most 10.1 %: they stiffen it as they damp it, and their
damping ratio peaks), so every alternative gets 80 % of the walls' most, 8 %, and the example says so:

- "VDW walls": the paper's 300 % set (fixed parameters, neither heating nor failing: the classical walls);
- "linear FVD": fluid viscous dampers, alpha = 1, with a brace in series (template C = 10 kN s/mm,
  K_b = 1 000 kN/mm; sizing scales both);
- "nonlinear FVD": alpha = 0.5 (template C = 100 kN (s/mm)^0.5, the same brace);
- "friction": slip force and elastic stiffness in a fixed ratio (slip deformation 2 mm).

The walls and the linear FVDs are linear: their damping ratio holds at every amplitude.  The nonlinear FVDs
and the friction dampers are linearised at a stated story drift amplitude, DESIGN_DRIFT_RATIO (1 %) of each
story height (FEMA 356 Sec. 9.3.4.3 and 9.3.3): their added damping holds at that amplitude only.  After
the analyses the example says what their equivalent damping is at the drifts the records actually reached.

Each is run on the synthetic record that ships with the package (0.35 g) and on three shared records
(../shared/ground_motions, when present), scaled to the shipped record's spectrum over 0.2-2 T1 of the bare
frame, each followed by 10 s of free vibration (residual drift at rest).  Printed per alternative and
record: peak and residual drift ratio, peak absolute floor acceleration, peak base shear, the devices'
largest force and velocity, and the shares of the input energy the devices, the inherent damping and the
yielding stories dissipated.  Figures in --out: each alternative's story-1 loop under the shipped record.

    python examples/devices.py [--records DIR] [--out DIR]
"""

from __future__ import annotations

import argparse
import math
import sys
import textwrap
import time
import warnings
from pathlib import Path

import matplotlib as mpl

mpl.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import vdw_frames as vdw
from vdw_frames.cli import plain_warnings
from vdw_frames.config import load_building
from vdw_frames.design import damping_curve, size_devices
from vdw_frames.motion import G, default_record, read_at2

ROOT = Path(__file__).resolve().parents[1]
BUILDING_FILE = Path(__file__).with_name("ten_story.toml")
DEFAULT_RECORDS = ROOT.parent / "shared" / "ground_motions"
SHARED_RECORDS = ("elCentro.AT2", "RIO270.AT2", "ARL360.at2")
ADDED_DAMPING = 0.15
DESIGN_DRIFT_RATIO = 0.01  # story drift amplitude / height at which the nonlinear devices are linearised
FREE_VIBRATION = 10.0  # s after each record
PERIOD_RANGE = (0.2, 2.0)  # x T1 of the bare frame: the records are scaled to the shipped one's spectrum there
TEMPLATES = {
    "VDW walls": vdw.paper.fitted(300, area=1.0e6, thickness=10.0),
    "linear FVD": vdw.FluidViscousDamper(1.0e4, 1.0, stiffness=1.0e6),
    "nonlinear FVD": vdw.FluidViscousDamper(1.0e5, 0.5, stiffness=1.0e6),
    "friction": vdw.FrictionDamper(2.0e5, 1.0e5),
}


def example_frame() -> vdw.ShearBuilding:
    """The bare example frame (examples/ten_story.toml without its walls)."""
    return load_building(BUILDING_FILE).without_devices()


def design_drifts(frame: vdw.ShearBuilding) -> np.ndarray:
    """The story drift amplitudes (mm) the nonlinear devices are linearised at: DESIGN_DRIFT_RATIO x heights."""
    return DESIGN_DRIFT_RATIO * np.asarray(frame.story_heights)


def common_added_damping(frame: vdw.ShearBuilding) -> float:
    """ADDED_DAMPING, or, when the walls cannot reach it, 80 % of the most they can add to this frame, to the
    percent below (they stiffen the frame as they damp it: their damping ratio peaks, :func:`damping_curve`)."""
    curve = damping_curve(frame, TEMPLATES["VDW walls"], distribution="stiffness", factors=[1.0])
    most = curve.best_damping_ratio - curve.bare_damping_ratio
    if most > ADDED_DAMPING:
        return ADDED_DAMPING
    added = math.floor(80.0 * most) / 100.0
    print(f"{100 * ADDED_DAMPING:.0f} % added is out of the walls' reach in this frame: at most {100 * most:.1f} % "
          f"(with {curve.best_factor:.3g} x the template wall); every alternative is sized to {100 * added:.0f} % "
          "added instead")
    return added


def alternatives(frame: vdw.ShearBuilding, added: float) -> dict[str, vdw.ShearBuilding]:
    """Each alternative sized to the bare frame's mode-1 damping ratio + ``added``; prints each sizing."""
    bare = float(vdw.modal_analysis(frame, 1).damping_ratios[0])
    sized = {}
    for name, template in TEMPLATES.items():
        started = time.perf_counter()
        sizing = size_devices(frame, template, bare + added, distribution="stiffness",
                              drift_amplitude=design_drifts(frame))
        sized[name] = sizing.building
        print(f"\n{name} (sized in {time.perf_counter() - started:.0f} s): {sizing.report()}")
    return sized


def records(folder: Path, period: float) -> list[vdw.GroundMotion]:
    """The shipped record and the shared ones present in ``folder``, scaled to its spectrum (module docstring)."""
    shipped = default_record()
    suite = [shipped]
    periods = np.geomspace(PERIOD_RANGE[0] * period, PERIOD_RANGE[1] * period, 60)
    target = shipped.spectrum(periods)
    for name in SHARED_RECORDS:
        if (folder / name).is_file():
            record = read_at2(folder / name)
            suite.append(record.scaled(float(np.exp(np.mean(np.log(target / record.spectrum(periods)))))))
    return suite


def device_histories(result: vdw.SimulationResult) -> list[tuple[int, str, np.ndarray, np.ndarray, np.ndarray]]:
    """(story, description, force N, deformation mm, velocity mm/s) of every device, walls included: a wall's
    deformation and velocity are its story's (magnification 1), from Newmark's floor velocities."""
    building = result.building
    drift_velocity = np.diff(result.velocity, axis=1, prepend=0.0)
    out = [(story, wall.describe(), result.wall_force[:, w], wall.magnification * result.drift[:, story - 1],
            wall.magnification * drift_velocity[:, story - 1])
           for w, (story, wall) in enumerate(building.wall_list)]
    out += [(story, device.describe(), result.device_force[:, d], result.device_deformation[:, d],
             result.device_velocity[:, d]) for d, (story, device) in enumerate(building.other_device_list)]
    return out


def summary(result: vdw.SimulationResult) -> dict[str, float]:
    """The printed quantities of one analysis."""
    devices = device_histories(result)
    energy = result.energy
    total = float(energy.input[-1])
    return {
        "drift %": 100 * float(result.peak_drift_ratio.max()),
        "residual %": 100 * float(np.max(np.abs(result.residual_drift) / np.asarray(result.building.story_heights))),
        "accel g": float(result.peak_absolute_acceleration.max()) / G,
        "base kN": result.peak_base_shear / 1e3,
        "force kN": max(float(np.abs(force).max()) for _, _, force, _, _ in devices) / 1e3,
        "velocity mm/s": max(float(np.abs(velocity).max()) for _, _, _, _, velocity in devices),
        "devices %": 100 * float(energy.wall_work[-1]) / total,
        "inherent %": 100 * float(energy.inherent_damping[-1]) / total,
        "yielding %": 100 * float(energy.hysteretic[-1]) / total,
    }


def plot_loops(results: dict[str, vdw.SimulationResult], path: Path) -> None:
    """Story 1's device loop (force against deformation) of every alternative, one panel each."""
    figure, axes = plt.subplots(2, 2, figsize=(10, 8), constrained_layout=True)
    for axis, (name, result) in zip(axes.flat, results.items(), strict=True):
        story, description, force, deformation, _ = next(item for item in device_histories(result) if item[0] == 1)
        axis.plot(deformation, force / 1e3, lw=0.7)
        axis.set_title(f"{name}: story {story}\n{textwrap.fill(description, 70)}", fontsize=8)
        axis.set_xlabel("device deformation (mm)")
        axis.set_ylabel("device force (kN)")
        axis.grid(alpha=0.3)
    figure.savefig(path, dpi=120)
    plt.close(figure)


def amplitude_note(frame_heights: np.ndarray, buildings: dict[str, vdw.ShearBuilding],
                   peaks: dict[str, np.ndarray], added: float) -> list[str]:
    """What the nonlinear devices' equivalent damping is at the peak drifts the records reached (mean of the
    records' per-story peaks), against the ``added`` damping they were sized for at the design drift."""
    lines = []
    for name in ("nonlinear FVD", "friction"):
        reached = peaks[name]
        bare = float(vdw.modal_analysis(buildings[name].without_devices(), 1).damping_ratios[0])
        at_reached = float(vdw.modal_analysis(buildings[name], 1, drift_amplitude=reached).damping_ratios[0]) - bare
        lines.append(f"  {name}: sized for {100 * added:.0f} % added at {100 * DESIGN_DRIFT_RATIO:.1f} % "
                     f"drift; the records' mean peak drifts ({100 * float(np.min(reached / frame_heights)):.2f}-"
                     f"{100 * float(np.max(reached / frame_heights)):.2f} %) give it {100 * at_reached:.1f} % added")
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], allow_abbrev=False)
    parser.add_argument("--records", type=Path, default=DEFAULT_RECORDS,
                        help="folder of the shared AT2 records (default ../shared/ground_motions; absent: the "
                             "shipped record only)")
    parser.add_argument("--out", type=Path, default=Path("out"), help="folder for the figure (default ./out)")
    args = parser.parse_args(argv)
    try:
        return run(args)
    except (ValueError, OSError) as error:
        print(f"devices.py: error: {error}", file=sys.stderr)
        return 2


def run(args: argparse.Namespace) -> int:
    frame = example_frame()
    bare = float(vdw.modal_analysis(frame, 1).damping_ratios[0])
    print(f"bare frame: T1 = {frame.periods[0]:.3f} s, mode-1 damping {bare:.4f}; target: {100 * ADDED_DAMPING:.0f} % "
          f"added; nonlinear devices linearised at {100 * DESIGN_DRIFT_RATIO:g} % story drift")
    added = common_added_damping(frame)
    buildings = alternatives(frame, added)
    suite = records(args.records, float(frame.periods[0]))
    print(f"\nrecords: {', '.join(f'{m.name} ({m.pga / G:.2f} g)' for m in suite)}"
          + ("" if len(suite) > 1 else f" (no shared records at {args.records})"))
    columns = ("drift %", "residual %", "accel g", "base kN", "force kN", "velocity mm/s", "devices %", "inherent %",
               "yielding %")
    print(f"\n{'alternative':14s} {'record':14s} " + " ".join(f"{c:>13s}" for c in columns))
    shipped: dict[str, vdw.SimulationResult] = {}
    peaks: dict[str, list[np.ndarray]] = {name: [] for name in buildings}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # the 300 % walls outside their strain range: stated above
        for name, building in buildings.items():
            for motion in suite:
                result = vdw.simulate(building, motion, free_vibration=FREE_VIBRATION)
                shipped.setdefault(name, result)
                peaks[name].append(result.peak_drift)
                values = summary(result)
                print(f"{name:14s} {motion.name[:14]:14s} " + " ".join(f"{values[c]:13.3g}" for c in columns))
    args.out.mkdir(parents=True, exist_ok=True)
    figure = args.out / "device_loops.png"
    plot_loops(shipped, figure)
    mean_peaks = {name: np.mean(values, axis=0) for name, values in peaks.items()}
    print(f"\nfigure: {figure}")
    print("\nWhat the table shows: with the same mode-1 damping at the design amplitude, the four alternatives are "
          "compared at the drifts the records reach.  The linear devices keep their damping at every amplitude; "
          "the nonlinear ones do not:")
    for line in amplitude_note(np.asarray(frame.story_heights), buildings, mean_peaks, added):
        print(line)
    print("A friction damper's equivalent damping falls at drifts above (and below) the one it was sized at, a "
          "nonlinear FVD's more slowly (C_eq ~ u^(alpha - 1)); a different DESIGN_DRIFT_RATIO changes their size and "
          "the comparison.  The walls are the fixed 300 % set: their own amplitude, heat and failure are in "
          "examples/seismic_simulation.py.")
    return 0


if __name__ == "__main__":
    with plain_warnings():  # one line "warning: ...", as the vdw-frames command prints them
        sys.exit(main())
