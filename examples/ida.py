"""Incremental dynamic analysis of the yielding 10-story example frame: bare, with its walls, and with ideal walls.

Frame and walls: examples/ten_story.toml (strengths by a code-like rule, 3 % hardening, P-Delta; the
walls follow their own strain amplitude, heat themselves and fail at 850 % shear strain -- assumptions
stated in the file; see examples/seismic_simulation.py).  Records: every record of
../shared/ground_motions (when that folder is beside the repository) plus the synthetic record shipped
with the package.  Intensity measure: Sa(T1, 5 %) with T1 = 1.98 s, the bare elastic frame's period,
for every configuration (one hazard axis).  Each record is stepped up by --step g until the frame
collapses -- a story drift ratio beyond 10 %, or an analysis that stops converging -- or the cap --cap g
is reached (vdw_frames.incremental_dynamic_analysis; the records of one level run in parallel).

Three configurations:

- the bare frame;
- the frame with its walls, which can fail: each record's first wall-failure intensity is reported
  beside its collapse intensity, each with a lognormal fragility.  A failed wall stops carrying force
  and the frame goes on without it; collapse stays a frame event, and the margin is printed both ways
  (wall failure not counted, and counted as collapse);
- "ideal walls": the same walls fixed at the 300 % set, never heating nor failing -- the linear
  viscoelastic walls the package used to assume, which near collapse work at thousands of per cent
  strain.  Their margin is printed only to show what that assumption claimed.

Outputs: the IDA curves with their collapse points (ida_curves.png), the collapse fragilities
(fragility.png), per record the collapse and first wall-failure intensities, the medians and margins
(printed, each saying which limit states it includes), and every run in a CSV per configuration.

    python examples/ida.py [--out DIR] [--records DIR] [--step G] [--cap G]
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import vdw_frames as vdw
from vdw_frames.cli import plain_warnings
from vdw_frames.config import load_building
from vdw_frames.motion import G, default_record, read_at2
from vdw_frames.plotting import plot_fragility, plot_ida_curves

BUILDING_FILE = Path(__file__).with_name("ten_story.toml")
SHARED_RECORDS = Path(__file__).resolve().parents[1].parent / "shared" / "ground_motions"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], allow_abbrev=False)
    parser.add_argument("--out", type=Path, default=Path("ida"), help="output folder (default ./ida)")
    parser.add_argument("--records", type=Path, help="folder of AT2 records (default ../shared/ground_motions)")
    parser.add_argument("--step", type=float, default=0.1, help="Sa(T1) step, g (default 0.1)")
    parser.add_argument("--cap", type=float, default=4.0, help="highest Sa(T1), g (default 4.0)")
    args = parser.parse_args(argv)
    try:
        return run(args)
    except (ValueError, OSError) as error:
        print(f"ida.py: error: {error}", file=sys.stderr)
        return 2


def run(args) -> int:
    if not (args.step > 0.0 and args.cap >= args.step):
        raise ValueError(f"--step must be > 0 and --cap >= --step, got --step {args.step:g}, --cap {args.cap:g}")
    if args.records is not None and not args.records.is_dir():
        raise ValueError(f"--records {args.records}: not a folder")
    folder = args.records or (SHARED_RECORDS if SHARED_RECORDS.is_dir() else None)
    motions = [read_at2(path) for path in sorted(folder.glob("*.[aA][tT]2"))] if folder else []
    if args.records is not None and not motions:
        raise ValueError(f"--records {args.records}: no .AT2 records in the folder")
    if folder is None:
        print(f"(no records at {SHARED_RECORDS}: the shipped synthetic record only, no fragility fit)")
    motions.append(default_record())
    walled = load_building(BUILDING_FILE)
    ideal = walled.with_walls({story: tuple(dataclasses.replace(wall.at(3.0), thermal=None, limits=None)
                                            for wall in walls) for story, walls in walled.walls.items()})
    buildings = {"bare frame": walled.without_devices(), "with VDW": walled, "ideal walls": ideal}
    period = walled.without_devices().periods[0]
    args.out.mkdir(parents=True, exist_ok=True)
    print(f"IDA: {len(motions)} records ({', '.join(m.name for m in motions)}), Sa(T1 = {period:.2f} s) from "
          f"{args.step:g} g in steps of {args.step:g} g up to {args.cap:g} g or collapse")
    limits = walled.wall_list[0][1].limits
    print(f"walls fail at {100 * limits.strain:.0f} % shear strain ({limits.source})")

    results = {}
    with vdw.frame.worker_pool() as pool, warnings.catch_warnings():  # one pool (threads) for every call
        # Counted below: a wall beyond the amplitudes its parameters were identified for.
        warnings.simplefilter("ignore", UserWarning)
        for label, building in buildings.items():
            started = time.perf_counter()
            result = vdw.incremental_dynamic_analysis(building, motions, args.step * G, args.cap * G, period,
                                                      executor=pool)
            elapsed = time.perf_counter() - started
            results[label] = result
            path = args.out / f"ida_{label.replace(' ', '_')}.csv"
            _write_csv(result, path)
            print(f"\n{label}: {result.analyses} analyses in {elapsed:.1f} s -> {path}")
            for m, name in enumerate(result.motion_names):
                print(f"  {name:20s} collapse Sa(T1): {_level(result.collapse_intensity, m, args.cap)}"
                      + (f"; first wall failure: {_level(result.wall_failure_intensity, m, args.cap)}"
                         if label == "with VDW" else ""))
            if result.strain_warnings:
                print(f"  {len(result.strain_warnings)} of {result.analyses} runs took walls outside the amplitudes "
                      f"their parameters were identified for, e.g.: {result.strain_warnings[0]}")
        print(f"\ncollapse: {COLLAPSE}")
        medians = {}
        for label, result in results.items():
            medians[label] = _median(result, "collapse", f"{label}: median collapse Sa(T1)")
        failure = _median(results["with VDW"], "wall failure", "with VDW: median first-wall-failure Sa(T1)")
        either = _either(results["with VDW"])
        medians["with VDW, wall failure counted"] = _median(
            either, "collapse", "with VDW: median Sa(T1) of collapse or first wall failure, whichever comes first")
        bare = medians["bare frame"]
        if bare is not None:
            print("collapse-margin gain of the walls (median over the bare frame's):")
            for label, text in (("with VDW", "walls that can fail, wall failure not counted as collapse"),
                                ("with VDW, wall failure counted", "walls that can fail, wall failure counted as "
                                                                   "collapse"),
                                ("ideal walls", "ideal walls (never heat, never fail; linear at any strain -- "
                                                "NOT a margin: what the old assumption claimed)")):
                if medians[label] is not None:
                    print(f"  x {medians[label] / bare:.2f}: {text}")
        if failure is not None and medians["with VDW"] is not None:
            print(f"  the walls' first failure comes at {failure / medians['with VDW']:.2f} x the walled frame's "
                  "median collapse intensity")
        figures = [plot_ida_curves(results, args.out / "ida_curves.png",
                                   title="IDA: bare frame, with VDW, ideal walls; x = collapse")]
        fitted = {label: result for label, result in {**results, "with VDW, wall failure counted": either}.items()
                  if medians[label] is not None}
        if fitted:
            figures.append(plot_fragility(fitted, args.out / "fragility.png", title="collapse fragility"))
    print("figures: " + ", ".join(str(path) for path in figures))
    return 0


COLLAPSE = ("a story drift ratio above 10 % or an analysis that stops converging (a frame event; a failed wall "
            "stops carrying force and the frame goes on)")


def _level(intensity: np.ma.MaskedArray, m: int, cap: float) -> str:
    return f"{intensity[m] / G:.2f} g" if intensity[m] is not np.ma.masked else f"none up to {cap:g} g"


def _median(result, limit_state: str, text: str) -> float | None:
    """Print and return the median of the lognormal fit for ``limit_state`` (mm/s^2), or None."""
    try:
        fit = result.fragility(limit_state)
    except ValueError as error:
        print(f"{text}: no fit ({error})")
        return None
    print(f"{text} = {fit.median / G:.3f} g, dispersion beta = {fit.dispersion:.2f} (lognormal, maximum "
          "likelihood, records standing at their last level censored)")
    return fit.median


def _either(result):
    """``result`` with each record's collapse intensity the earlier of its collapse and first wall failure."""
    collapse, failure = result.collapse_intensity, result.wall_failure_intensity
    earliest = np.ma.masked_array(np.minimum(collapse.filled(np.inf), failure.filled(np.inf)))
    earliest = np.ma.masked_invalid(earliest)
    return dataclasses.replace(result, collapse_intensity=earliest)


def _write_csv(result, path):
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["record", "sa_g", "largest_drift_ratio", "collapsed", "wall_failed"])
        for m, name in enumerate(result.motion_names):
            failed = result.wall_failed[m] if result.wall_failed else np.zeros(len(result.intensities[m]), bool)
            for sa, drift, collapsed, broke in zip(result.intensities[m], result.peak_drift_ratio[m],
                                                   result.collapsed[m], failed, strict=True):
                writer.writerow([name, repr(float(sa / G)), repr(float(drift)), int(collapsed), int(broke)])


if __name__ == "__main__":
    with plain_warnings():  # one line "warning: ...", as the vdw-frames command prints them
        sys.exit(main())
