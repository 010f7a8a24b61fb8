"""Benchmark of vdw_frames (issue 5): memory strategies, scaling, OpenSees comparison, compile time.

    python examples/benchmark.py [--quick]

Everything is measured in this one run, on this machine, with ``time.perf_counter`` (best of a few
repeats for runs under a second; numba compilation is excluded except in (d)):

(a) ``memory="fast"`` against ``memory="exact"``: time and deviation of the drifts at 2 000, 20 000 and
    200 000 steps (a 2 000-sample window around the peak of the record, the whole record, the whole
    record at dt / 10).  The exact memory costs O(N^2); when the 200 000-step run would take more than
    two minutes (estimated from the 20 000-step time by N^2 scaling) it is not run and the estimate is
    printed, labelled as extrapolated.
(b) the fast mode's scaling exponent: the least-squares slope of log(time) against log(steps).
(c) the *inelastic* 10-story frame (Bilinear stories, strengths by the example's rule: 0.125 W at the base,
    3 % hardening, P-Delta) with two fractional FDMK walls a story on HWA002-N x 4 (Chi-Chi 1999; 20 000
    steps, dt 0.004 s; stories yield) against OpenSeesPy running the same inelastic frame with classical
    r = 1 walls, set up the way its users would for speed: ``Steel01`` stories, each story's walls as one
    ``Parallel(Elastic, Maxwell)`` with summed constants, Newton, ``NormDispIncr 1e-10 20``,
    ``BandGeneral``, one ``analyze(N)`` call with a Node recorder.  The whole ``simulate()`` call (result
    assembly included) against OpenSees's, best of three each: target vdw_frames at most 1/20 of
    OpenSees.  Then the linear frame (the same frame, elastic) and the fast mode's "10x the steps in at
    most 11x the time" ratio, and the throughput of an incremental dynamic analysis (analyses per second
    of ``run_batch`` on the example frame of examples/ten_story.toml, all cores).
(d) numba compilation: ``import vdw_frames`` + a first ``simulate`` in a fresh subprocess with an empty
    cache (``NUMBA_CACHE_DIR`` a new temporary folder), then again in a fresh subprocess with that cache
    warm.
(e) the OpenSees bridge (``vdw_frames.interop.opensees``) on the same frame and record: its overhead per wall per
    step on top of OpenSees's own step (target <= 2 us), the bridged fractional frame against OpenSees
    running the frame with its own classical (r = 1) Elastic + Maxwell dampers (target: no slower), with
    one element per wall and with each story's walls combined into one, and the Prony material's cost
    per step against the bridge.  All with Newton to NormDispIncr 1e-9 mm; model building is not timed;
    the variants take turns, best of at least three rounds.

(f) the FEMA P695 collapse assessment (``vdw_frames.assessment.collapse_assessment``) of the example frame
    of examples/ten_story.toml, bare and with its walls, on the far-field set (44 records, hunt-and-fill to
    2 %), on the default executor (a thread pool over all cores, made by each call) and on a process pool whose
    workers are warmed first: time (target <= 60 s for both; issue 32's <= 1.5 s),
    analyses per second and per record, and where the time goes: the fixed cost of one ``simulate`` call
    (a 20-step record) and the cost per step (a long record) measured on one core, against the total.
    Skipped without the [p695] extra.

(h) fluid viscous dampers against OpenSees: the inelastic frame of (c) with its walls replaced by 20
    nonlinear FVDs (two a story, ``FVD``: alpha = 0.5, a brace K_b in series), HWA002-N x 4, against
    OpenSeesPy running the same frame with its ``ViscousDamper`` material (one ``zeroLength`` element per
    damper, ``vdw_frames.interop.opensees.device_element``; Steel01 stories, Newton, ``NormDispIncr 1e-10
    20``, one ``analyze(N)`` call with a Node recorder, as in (c)): the whole ``simulate()`` call against
    OpenSees's, taking turns, best of five each (three with --quick); target vdw_frames at most 1/20 of
    OpenSees.  The machine's load is printed before and after.  Twice: at alpha = 0.5, whose trial the
    package solves in closed form, and at alpha = 0.4 (C for the same force at 100 mm/s), solved by
    iteration (a power an iterate).

(i) lanes (issue 32, ``vdw_frames.frame.lanes.run_lanes``): the example frame of examples/ten_story.toml, bare
    (yielding, P-Delta), with walls of fixed parameters (each wall's table at its middle node: what the walls'
    fast memory and FDMK stress cost) and with its walls (amplitude-following, heating, limits), on the shipped
    record at 44 scales (0.2 ... 1.0) as one batch of 44 lanes: the time per analysis step amortised over the batch
    (targets <= 0.2 us bare, <= 0.6 us with walls) beside one ``simulate`` call's, and the page faults
    per analysis of a second batch (``resource.getrusage``; target <= 10).  Then part (c)'s inelastic frame with
    fractional walls on its record x 4 as 44 lanes, per analysis, against one OpenSeesPy analysis of it with
    classical r = 1 walls (as in (c)): target at most 1/100.  The load is printed beside each.

(j) lanes innermost, projected (issue 32): two compiled prototypes in this file, not in the package, with every
    array's last axis the lanes so that each pass over stories, modes or window does all lanes in SIMD
    instructions: the bare example frame's step (Bilinear stories, Rayleigh C, P-Delta; Newton in lockstep with
    converged or collapsed lanes masked, the package's convergence test, energies and peaks; no walls, devices or
    fallbacks) on the batch of (i), its peak drifts checked against the package's, and the fast memory of 10 walls
    (the example's r and dt) in 44 lanes, each timed against the package in turn (thread CPU time, median of the
    ratios).  With (i)'s figures of the same run it projects what a rewrite of the one integrator in that layout
    would reach, assuming the walls' whole commit gains as their memory does.

``--part X`` (repeatable) runs only the named parts (``--part h``: (h) alone).
``--quick``: 2 000 and 20 000 steps only (no 200 000-step runs), single repeats; (e) on 4 000 steps.  Without the
../shared/ground_motions folder (a fresh clone) a synthetic 80 s record at 0.004 s stands in for
HWA002-N; without OpenSeesPy part (c) prints the vdw_frames times only and part (e) is skipped.  Units: N, mm, s, tonne.
"""

from __future__ import annotations

import argparse
import dataclasses
import itertools
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np
from numba import njit

ROOT = Path(__file__).resolve().parents[1]
RECORD = ROOT.parent / "shared" / "ground_motions" / "HWA002-N.AT2"
EXACT_BUDGET = 120.0  # s: longest exact-memory run attempted (estimated by N^2 scaling)
SHORT_RUN = 5.0  # s: runs shorter than this are repeated and the best time kept

try:
    import vdw_frames  # noqa: F401
except ImportError:  # run from a checkout without an install
    sys.path.insert(0, str(ROOT))
# After the fallback above, which may put the checkout on the path first.
from vdw_frames import Bilinear, FDMKDamper, FluidViscousDamper, ShearBuilding, run_batch, simulate  # noqa: E402
from vdw_frames.element import FastMemory  # noqa: E402
from vdw_frames.element.kernel import memory_advance  # noqa: E402
from vdw_frames.motion import G, GroundMotion, read_at2  # noqa: E402

# The fast memory on every record length (by default records under 2 048 steps use the exact memory).
FAST = FastMemory(exact_below=0)

# The frame of examples/ten_story.toml (600 t floors, 450 t roof, 900 -> 450 kN/mm, 5 % Rayleigh on
# modes 1 and 2) with two paper-size walls (A = 1e6 mm^2, h = 10 mm) a story; the README's damper.
WALL = FDMKDamper(G1=0.0, G2=3.0, eta1=0.3, eta2=2.0, r=0.5, area=1.0e6, thickness=10.0)

# The dampers of part (h): C = 20 kN (s/mm)^0.5 (100 mm/s -> 200 kN), alpha = 0.5, a 200 kN/mm brace; two a
# story (sizes chosen for the timing, not matched to the walls' damping).
FVD = FluidViscousDamper(C=2.0e4, alpha=0.5, stiffness=2.0e5)
# The same at alpha = 0.4 (C for the same 200 kN at 100 mm/s): an exponent the trial solves by iteration.
FVD_GENERAL = FluidViscousDamper(C=2.0e4 * 100.0**0.1, alpha=0.4, stiffness=2.0e5)

MASSES = np.array([600.0] * 9 + [450.0])  # tonne
HEIGHTS = np.array([4000.0] + [3500.0] * 9)  # mm


def ten_story(wall=WALL) -> ShearBuilding:
    return ShearBuilding(MASSES, np.linspace(900e3, 450e3, 10), devices={story: [wall, wall] for story in range(1, 11)})


def inelastic(building: ShearBuilding) -> ShearBuilding:
    """``building`` with Bilinear stories (the example's strength rule: ASCE 7-like vertical distribution
    of 0.05 W, times an overstrength of 2.5; 3 % hardening) and P-Delta (the weight above each story)."""
    weight = MASSES * 9806.65  # N
    elevation = np.cumsum(HEIGHTS)
    exponent = min(2.0, max(1.0, 1.0 + (building.periods[0] - 0.5) / 2.0))
    forces = 0.05 * weight.sum() * weight * elevation**exponent / np.sum(weight * elevation**exponent)
    strengths = 2.5 * np.cumsum(forces[::-1])[::-1]
    return ShearBuilding(building.masses, building.stiffnesses, building.damping_ratio, building.damping_modes,
                         building.walls, HEIGHTS, hysteresis=[Bilinear(f, 0.03) for f in strengths],
                         gravity_loads=np.cumsum(weight[::-1])[::-1])


def load_record():
    """HWA002-N from ../shared, else a seeded synthetic stand-in of the same length and step."""
    if RECORD.is_file():
        return read_at2(RECORD), f"{RECORD.name} (Chi-Chi 1999, HWA002 N)"
    from vdw_frames.motion import synthetic_ground_motion

    motion = synthetic_ground_motion(duration=19999 * 0.004, dt=0.004, pga=0.1 * G, name="synthetic")
    return motion, f"synthetic stand-in ({RECORD} is absent)"


def timed(function, repeats):
    """(best time in s, result of the last call); repeats only while a run is shorter than SHORT_RUN."""
    best, result = math.inf, None
    for _ in range(repeats):
        started = time.perf_counter()
        result = function()
        elapsed = time.perf_counter() - started
        best = min(best, elapsed)
        if elapsed > SHORT_RUN:
            break
    return best, result


def fast_memory_available(building) -> bool:
    try:
        simulate(building, GroundMotion(np.zeros(8), 0.01), memory=FAST)
    except ValueError:
        return False
    return True


def deviations(drift, reference):
    """(max over stories of |peak / reference peak - 1|, max |difference| / max |reference|)."""
    peaks = np.abs(drift).max(axis=0) / np.abs(reference).max(axis=0)
    return float(np.abs(peaks - 1.0).max()), float(np.abs(drift - reference).max() / np.abs(reference).max())


def cases(motion, quick):
    """(label, GroundMotion, dt) for 2 000, 20 000 and (unless quick) 200 000 steps."""
    peak = int(np.argmax(np.abs(motion.acceleration)))
    start = min(max(peak - 1000, 0), max(motion.acceleration.size - 2000, 0))
    window = GroundMotion(motion.acceleration[start:start + 2000], motion.dt, motion.name)
    rows = [(f"window {start * motion.dt:.0f}-{(start + 2000) * motion.dt:.0f} s", window, motion.dt),
            ("whole record", motion, motion.dt)]
    if not quick:
        rows.append(("whole record, dt / 10", motion, motion.dt / 10))
    return rows


def part_a(building, motion, fast, quick, repeats):
    print("\n(a) fast vs exact memory: 10-story frame, 2 walls a story (r = 0.5), default discretisation")
    if not fast:
        print("    fast memory not available (simulate(..., memory='fast') is refused): exact memory only")
    header = f"    {'steps':>7}  {'dt (s)':>7}  {'input':<24} {'exact (s)':>16}  {'fast (s)':>9}  " \
             f"{'fast/exact':>10}  {'peak dev':>9}  {'hist dev':>9}"
    print(header)
    print("    " + "-" * (len(header) - 4))
    timings = {"exact": {}, "fast": {}}
    extrapolated = False
    for label, record, dt in cases(motion, quick):
        steps = record.acceleration_at(dt).size
        exact_time = exact = None
        estimate = None
        measured = timings["exact"]
        if measured:
            known = max(measured)
            estimate = measured[known] * (steps / known) ** 2
        if estimate is None or estimate <= EXACT_BUDGET:
            exact_time, exact = timed(lambda record=record, dt=dt: simulate(building, record, dt=dt, memory="exact"),
                                      repeats)
            timings["exact"][steps] = exact_time
            exact_cell = f"{exact_time:.3f}"
        else:
            exact_cell = f"~{estimate:.0f} extrap.*"
            extrapolated = True
        fast_cell = ratio_cell = peak_cell = history_cell = "-"
        if fast:
            fast_time, result = timed(lambda record=record, dt=dt: simulate(building, record, dt=dt, memory=FAST),
                                      repeats)
            timings["fast"][steps] = fast_time
            fast_cell = f"{fast_time:.3f}"
            reference_time = exact_time if exact_time is not None else estimate
            ratio_cell = f"{fast_time / reference_time:.4f}" + ("" if exact_time is not None else "*")
            if exact is not None:
                peak_dev, history_dev = deviations(result.drift, exact.drift)
                peak_cell, history_cell = f"{peak_dev:.2e}", f"{history_dev:.2e}"
            else:
                peak_cell = history_cell = "n/a*"
        print(f"    {steps:>7}  {dt:>7.4g}  {label:<24} {exact_cell:>16}  {fast_cell:>9}  {ratio_cell:>10}  "
              f"{peak_cell:>9}  {history_cell:>9}")
    if extrapolated:
        print(f"    * extrapolated, not measured: the exact run would exceed {EXACT_BUDGET:.0f} s, so its time is"
              " the 20 000-step time x (N / 20 000)^2 and there is no deviation to report")
    print("    peak dev = max over stories |peak drift fast / exact - 1|; "
          "hist dev = max |drift fast - exact| / max |drift exact|")
    return timings


def slope(timings):
    steps = np.array(sorted(timings), dtype=float)
    if steps.size < 2:
        return math.nan
    seconds = np.array([timings[int(n)] for n in steps])
    return float(np.polyfit(np.log(steps), np.log(seconds), 1)[0])


def part_b(timings):
    print("\n(b) scaling exponent p in time ~ steps^p (least-squares slope on log-log, measured points only)")
    if timings["fast"]:
        print(f"    fast memory:  p = {slope(timings['fast']):.3f}   (target ~1)")
    else:
        print("    fast memory not available")
    print(f"    exact memory: p = {slope(timings['exact']):.3f}   (O(N^2) convolution)")


def opensees_time(building, acceleration, dt, repeats, **options):
    sys.path.insert(0, str(ROOT / "tests"))
    try:
        import opensees_frame

        opensees_frame.opensees()
    except ImportError as error:
        return None, f"OpenSeesPy not available ({error})"
    seconds, displacement = timed(
        lambda: opensees_frame.run_recorded(building, acceleration, dt, **options), repeats)
    return (seconds, opensees_frame.drifts(displacement)), None


def classical_walls(frame: ShearBuilding) -> ShearBuilding:
    """``frame`` with every wall made classical (r = 1): the walls OpenSees can run (Parallel(Elastic, Maxwell))."""
    return ShearBuilding(frame.masses, frame.stiffnesses, frame.damping_ratio, frame.damping_modes,
                         {story: [dataclasses.replace(wall, r=1.0) for wall in walls]
                          for story, walls in frame.walls.items()},
                         frame.story_heights, frame.hysteresis, frame.gravity_loads)


def part_c(building, motion, source, fast, timings, *, quick, repeats):
    steps = motion.acceleration.size
    memory = FAST if fast else "exact"
    label = "fast" if fast else "exact"
    strong = motion.scaled(4.0)
    frame = inelastic(building)
    print(f"\n(c) inelastic 10-story frame (Bilinear stories, P-Delta), 2 walls a story, {source} x 4: {steps} steps, "
          f"dt = {motion.dt:g} s, PGA = {strong.pga / G:.3f} g")
    vdw_time, result = timed(lambda: simulate(frame, strong, memory=memory), 3)
    classical = classical_walls(frame)
    opensees, problem = opensees_time(classical, strong.acceleration, strong.dt, 3, tolerance=1e-10,
                                      max_iterations=20, parallel_walls=True)
    print(f"    peak story ductility {result.peak_ductility.max():.2f}, {result.newton_iterations / steps:.2f} Newton "
          f"corrections a step")
    rows = [(f"vdw_frames simulate(), fractional r = {WALL.r:g}, memory='{label}'", vdw_time)]
    if opensees is not None:
        os_time, os_drift = opensees
        rows.append(("OpenSeesPy, classical r = 1 (Steel01, Parallel(Elastic, Maxwell), Newton)", os_time))
        r1_time, r1 = timed(lambda: simulate(classical, strong, memory=memory), 3)
        peak_dev, _ = deviations(r1.drift, os_drift)
        rows.append(("vdw_frames simulate(), same r = 1 frame", r1_time))
    linear_time, _ = timed(lambda: simulate(building, motion, memory=memory), 3)
    rows.append(("vdw_frames simulate(), the frame kept elastic (linear path)", linear_time))
    for name, seconds in rows:
        print(f"    {name:<78} {seconds:8.3f} s")
    if opensees is None:
        print(f"    {problem}")
    else:
        ratio = vdw_time / os_time
        verdict = "meets" if ratio <= 1 / 20 else "misses"
        print(f"    vdw_frames (fractional, inelastic) / OpenSees (classical, inelastic) = {ratio:.4f}  "
              f"(= 1/{1 / ratio:.1f}; target <= 1/20 = 0.05: {verdict})")
        print(f"    (the r = 1 frame, vdw_frames' default discretisation vs OpenSees: peak drifts within "
              f"{100 * peak_dev:.2f} %)")
        print(f"    linear path / OpenSees inelastic = 1/{os_time / linear_time:.1f}")
    if fast:
        fast_times = timings["fast"]
        ordered = sorted(fast_times)
        for low, high in itertools.pairwise(ordered):
            growth = fast_times[high] / fast_times[low]
            verdict = "meets" if growth <= 11.0 * high / low / 10.0 else "misses"
            print(f"    fast memory, {high / low:.0f}x the steps ({low} -> {high}): {growth:.2f}x the time "
                  f"(target <= {11.0 * high / low / 10.0:.0f}x: {verdict})")
    else:
        print("    fast memory not available: no 10x-steps / 11x-time ratio")
    ida_throughput(quick)
    return None if opensees is None else opensees[0]


def part_walls(motion, source, opensees_seconds, repeats):
    """(g) Walls that heat, follow their amplitude and fail, against walls of fixed parameters."""
    from vdw_frames import ThermalProperties, WallLimits, paper
    from vdw_frames.element import ISD110_LOSS_PEAK

    heat = ThermalProperties(ISD110_LOSS_PEAK, 1.8, 21.2)
    limits = WallLimits(strain=8.5)
    family = paper.strain_dependent(area=1.0e6, thickness=10.0)
    fixed = family.at(3.0)
    walls = {
        "fixed parameters (the family at 300 %)": fixed,
        "fixed, self-heating": dataclasses.replace(fixed, thermal=heat),
        "fixed, limits (energy followed for the release)": dataclasses.replace(fixed, limits=limits),
        "amplitude-dependent": family,
        "amplitude-dependent, self-heating": dataclasses.replace(family, thermal=heat),
        "amplitude-dependent, self-heating, limits": dataclasses.replace(family, thermal=heat, limits=limits),
    }
    strong = motion.scaled(4.0)
    frames = {label: inelastic(ten_story(wall)) for label, wall in walls.items()}
    steps = strong.acceleration.size
    print(f"\n(g) walls as devices: inelastic 10-story frame, 2 walls a story (r = {family.common_order:.3f}), "
          f"{source} x 4: {steps} steps")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for frame in frames.values():
            simulate(frame, GroundMotion(strong.acceleration[:50], strong.dt))  # compile
        best = {label: math.inf for label in frames}
        labels = list(frames)
        # Interleaved, so that a load change touches every case alike, and each round in another order, so that
        # every case runs in every position once (a run's time depends a little on the run before it).
        for round_ in range(max(repeats, len(labels))):
            for label in labels[round_ % len(labels):] + labels[:round_ % len(labels)]:
                started = time.perf_counter()
                simulate(frames[label], strong)
                best[label] = min(best[label], time.perf_counter() - started)
    base = best["fixed parameters (the family at 300 %)"]
    targets = {"fixed, self-heating": 1.3, "amplitude-dependent": 1.3, "amplitude-dependent, self-heating": 1.5}
    for label, seconds in best.items():
        target = targets.get(label)
        meets = target is not None and seconds / base <= target
        verdict = "" if target is None else f"  (target <= {target:g}: {'meets' if meets else 'misses'})"
        line = f"    {label:<50} {seconds:7.3f} s  {seconds / base:5.2f} x fixed{verdict}"
        if opensees_seconds is not None:
            line += f"   1/{opensees_seconds / seconds:.1f} of OpenSees"
        print(line)
    if opensees_seconds is not None:
        print("    (OpenSees: the same frame with classical r = 1 walls, part (c); target <= 1/20 for every case)")


def part_fvd(motion, source, quick, repeats):
    """(h): the inelastic frame with 20 nonlinear FVDs, vdw_frames against OpenSees's ViscousDamper (module
    docstring), at alpha = 0.5 (solved in closed form) and at alpha = 0.4 (the general iteration).  All runs
    take turns, round after round, so that a change of the machine's load touches them alike."""
    sys.path.insert(0, str(ROOT / "tests"))
    if quick:
        motion = GroundMotion(motion.acceleration[:4000], motion.dt, motion.name)
    strong = motion.scaled(4.0)
    steps = strong.acceleration.size
    base = inelastic(ten_story())
    frames = {damper.alpha: base.with_devices({story: (damper, damper) for story in range(1, 11)})
              for damper in (FVD, FVD_GENERAL)}
    load = os.getloadavg() if hasattr(os, "getloadavg") else (math.nan,) * 3
    print(f"\n(h) fluid viscous dampers: inelastic 10-story frame (Bilinear stories, P-Delta), 20 FVDs (2 a story), "
          f"{source} x 4: {steps} steps, dt = {strong.dt:g} s; load {load[0]:.2f} before")
    for frame in frames.values():
        simulate(frame, GroundMotion(strong.acceleration[:50], strong.dt))  # compile (or load from the cache)
    try:
        import opensees_frame

        opensees_frame.opensees()
    except ImportError as error:
        for alpha, frame in frames.items():
            seconds, _ = timed(lambda frame=frame: simulate(frame, strong), max(repeats, 3))
            print(f"    alpha = {alpha:g}: vdw_frames simulate() {seconds:.3f} s")
        print(f"    OpenSees not available ({error})")
        return
    runs = {}
    for alpha, frame in frames.items():
        runs["vdw_frames", alpha] = lambda frame=frame: simulate(frame, strong)
        runs["OpenSees", alpha] = lambda frame=frame: opensees_frame.run_recorded(
            frame, strong.acceleration, strong.dt, tolerance=1e-10, max_iterations=20)
    best, results = {key: math.inf for key in runs}, {}
    rounds = 3 if quick else max(repeats, 3)
    for _ in range(rounds):
        for key, run in runs.items():
            started = time.perf_counter()
            results[key] = run()
            best[key] = min(best[key], time.perf_counter() - started)
    after = os.getloadavg() if hasattr(os, "getloadavg") else (math.nan,) * 3
    for alpha, frame in frames.items():
        result = results["vdw_frames", alpha]
        peak_dev, _ = deviations(result.drift, opensees_frame.drifts(results["OpenSees", alpha]))
        pairs = result.device_force.reshape(steps, 10, 2).sum(axis=2)  # columns: two dampers a story, in order
        share = np.abs(pairs).max(axis=0) / np.abs(result.story_shear).max(axis=0)
        damper = frame.other_device_list[0][1]
        solved = "closed form (a quadratic)" if alpha == 0.5 else "Newton iteration, a power each"
        print(f"    {damper.describe()}: peak story ductility {result.peak_ductility.max():.2f}, "
              f"{result.newton_iterations / steps:.2f} Newton corrections a step, a story's dampers reach "
              f"{100 * share.min():.0f}-{100 * share.max():.0f} % of its frame spring's peak force")
        print(f"      {'vdw_frames simulate(), implicit trapezoid FVDs: ' + solved:<76} "
              f"{best['vdw_frames', alpha]:8.3f} s")
        print(f"      {'OpenSeesPy, ViscousDamper (Dormand-Prince), Steel01, Newton, one analyze(N)':<76} "
              f"{best['OpenSees', alpha]:8.3f} s")
        ratio = best["vdw_frames", alpha] / best["OpenSees", alpha]
        print(f"      vdw_frames / OpenSees = {ratio:.4f} (= 1/{1 / ratio:.1f}; target <= 1/20 = 0.05: "
              f"{'meets' if ratio <= 1 / 20 else 'misses'}); peak drifts within {100 * peak_dev:.2f} % (the two FVD "
              "integrators' O(dt^2) difference)")
    print(f"    best of {rounds} turns each; load {after[0]:.2f} after (1-min average, {os.cpu_count()} CPUs)")


def ida_throughput(quick):
    """Analyses per second of run_batch on the example frame (the default pool: threads over all cores, warmed up)."""
    from vdw_frames.config import load_building
    from vdw_frames.frame import worker_pool
    from vdw_frames.motion import default_record

    building = load_building(ROOT / "examples" / "ten_story.toml")
    record = default_record()
    levels = np.linspace(0.2, 1.0, 8 if quick else 24)
    factors = levels * G / record.pga
    with worker_pool() as pool, warnings.catch_warnings():
        warnings.simplefilter("ignore")  # strain-range warnings: counted by examples/ida.py, not timed here
        run_batch(building, [record], factors[:2 * (os.cpu_count() or 1)], executor=pool, progress=False)  # warm
        started = time.perf_counter()
        run_batch(building, [record], factors, executor=pool, progress=False)
        seconds = time.perf_counter() - started
    kind = "elastic" if building.is_linear else "inelastic"
    print(f"    IDA throughput: {factors.size} analyses of the example frame ({record.acceleration.size} steps, "
          f"{len(building.wall_list)} walls, {kind} stories) in {seconds:.2f} s = {factors.size / seconds:.1f} "
          f"analyses/s on {os.cpu_count()} cores")


_PROBE = r"""
import json, time
started = time.perf_counter()
import numpy as np
import vdw_frames
from vdw_frames import FDMKDamper, ShearBuilding, simulate
from vdw_frames.motion import GroundMotion
imported = time.perf_counter()
wall = FDMKDamper(G1=0.0, G2=3.0, eta1=0.3, eta2=2.0, r=0.5)
building = ShearBuilding([600.0] * 9 + [450.0], np.linspace(900e3, 450e3, 10),
                         walls={story: [wall, wall] for story in range(1, 11)})
t = np.arange(500) * 0.01
simulate(building, GroundMotion(1000.0 * np.sin(2 * np.pi * t), 0.01))
done = time.perf_counter()
print(json.dumps({"import": imported - started, "simulate": done - imported}))
"""


def probe(cache_dir):
    environment = dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir))
    environment["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")]))
    started = time.perf_counter()
    completed = subprocess.run([sys.executable, "-c", _PROBE], env=environment, capture_output=True, text=True,
                               check=True)
    wall_time = time.perf_counter() - started
    timings = json.loads(completed.stdout.strip().splitlines()[-1])
    return timings["import"], timings["simulate"], wall_time


def part_d():
    print("\n(d) numba compilation: fresh subprocess, import vdw_frames + first simulate "
          "(10-story frame, 2 walls a story, 500 steps)")
    print(f"    {'cache':<30} {'import (s)':>10}  {'1st simulate (s)':>16}  {'process total (s)':>17}")
    with tempfile.TemporaryDirectory(prefix="vdw-numba-cache-") as cache_dir:
        for label in ("cold (empty NUMBA_CACHE_DIR)", "warm (same cache, new process)"):
            imported, first, total = probe(cache_dir)
            print(f"    {label:<30} {imported:>10.3f}  {first:>16.3f}  {total:>17.3f}")


def part_bridge(building, motion, source, quick, repeats):
    """(e): the OpenSees bridge's three numbers (see the module docstring).

    Two set-ups of the same frame: one OpenSees element per wall (and per branch of a classical wall), and
    the walls of a story as one wall of their summed area (identical walls in parallel see the same drift:
    the same model, as fast as OpenSees users set it up).  The variants run in turn, round after round,
    so that the machine's load varies alike for all; each keeps its best round.
    """
    sys.path.insert(0, str(ROOT / "tests"))
    try:
        import opensees_frame

        ops = opensees_frame.opensees()
    except ImportError as error:
        print(f"\n(e) OpenSees bridge: skipped, OpenSeesPy not available ({error})")
        return
    if quick:
        motion = GroundMotion(motion.acceleration[:4000], motion.dt, motion.name)
    steps, dt = motion.acceleration.size - 1, motion.dt
    walls = len(building.wall_list)
    print(f"\n(e) OpenSees bridge: 10-story frame, {walls} fractional walls (r = {WALL.r:g}), {source}: {steps} steps, "
          f"dt = {dt:g} s; Newton, NormDispIncr 1e-9 mm; time per step, best of {max(repeats, 3)} rounds")
    combined = dataclasses.replace(building, devices={story: dataclasses.replace(ws[0], area=sum(w.area for w in ws))
                                                      for story, ws in building.walls.items()})

    def classical(frame):
        return dataclasses.replace(frame, devices={story: [dataclasses.replace(w, r=1.0) for w in ws]
                                                   for story, ws in frame.walls.items()})

    def own_steps(model):  # the bridge's model, its history forces never updated: OpenSees's own step
        for _ in range(steps):
            ops.analyze(1, dt)

    def bridge_run(model):
        return model[1].analyze(steps)

    def one_call(model):
        return ops.analyze(steps, dt)

    variants = {  # name: (build the model -> (floor nodes, anything), run it)
        "bridge": (lambda: opensees_frame.build_bridged(building, dt, tolerance=1e-9), bridge_run),
        "own": (lambda: opensees_frame.build_bridged(building, dt, tolerance=1e-9), own_steps),
        "classical": (lambda: (opensees_frame.build(classical(building), tolerance=1e-9), None), one_call),
        "prony": (lambda: opensees_frame.build_prony(building, 0.1, 10.0, tolerance=1e-9), one_call),
        "bridge, combined": (lambda: opensees_frame.build_bridged(combined, dt, tolerance=1e-9), bridge_run),
        "bridge, combined, Linear": (lambda: opensees_frame.build_bridged(combined, dt, tolerance=1e-9,
                                                                          algorithm="Linear"), bridge_run),
        "classical, combined": (lambda: (opensees_frame.build(classical(combined), tolerance=1e-9), None), one_call),
    }
    opensees_frame.run_bridged(building, motion.acceleration[:50], dt)  # compile, build the fast memory's modes
    seconds = {name: math.inf for name in variants}
    models = {}
    for _ in range(max(repeats, 3)):
        for name, (build, run) in variants.items():
            model = build()
            opensees_frame._ground(motion.acceleration, dt, model[0])
            started = time.perf_counter()
            status = run(model)
            seconds[name] = min(seconds[name], time.perf_counter() - started)
            ops.wipe()
            if status not in (0, None):
                raise RuntimeError(f"the OpenSees analysis '{name}' of the benchmark failed")
            models[name] = model[1]
    per_step = {name: 1e6 * value / steps for name, value in seconds.items()}
    reference = simulate(building, motion, memory=FAST)
    peak_dev, _ = deviations(models["bridge"].deformation[:, ::2], reference.drift)  # wall 2 (k - 1): story k's
    linear_dev, _ = deviations(models["bridge, combined, Linear"].deformation, reference.drift)
    series = next(iter(models["prony"].values()))
    rows = [(f"one element per wall ({walls} walls):", None),
            ("bridge: bridge.analyze(N)", "bridge"),
            ("the same OpenSees model, analyze(1, dt) N times, no wall update", "own"),
            ("OpenSees, classical r = 1 walls: Elastic + Maxwell elements, one call", "classical"),
            (f"OpenSees, Prony material ({len(series)} branches, 0.1-10 Hz, 1 %), one call", "prony"),
            (f"each story's walls as one of their summed area ({len(combined.wall_list)} walls):", None),
            ("bridge", "bridge, combined"),
            ("bridge, algorithm Linear (one solve a step: exact on a linear frame)", "bridge, combined, Linear"),
            ("OpenSees, classical r = 1 walls, one call", "classical, combined")]
    for label, name in rows:
        print(f"    {label}" if name is None else f"      {label:<72} {per_step[name]:7.1f} us")
    overhead = (seconds["bridge"] - seconds["own"]) / (steps * walls)
    print(f"    1. bridge overhead per wall per step: {1e6 * overhead:.2f} us (target <= 2 us: "
          f"{'meets' if overhead <= 2e-6 else 'misses'}); all walls together "
          f"{(seconds['bridge'] - seconds['own']) / seconds['own']:.2f} x OpenSees's own step")
    for key, label in (("", "one element per wall"), (", combined", "walls combined per story")):
        ratio = seconds["bridge" + key] / seconds["classical" + key]
        print(f"    2. bridged fractional frame / OpenSees classical Maxwell frame, {label}: {ratio:.2f} (target <= 1: "
              f"{'meets' if ratio <= 1.0 else 'misses'})")
    print(f"       with algorithm Linear: {seconds['bridge, combined, Linear'] / seconds['classical, combined']:.2f}")
    print(f"    3. Prony material / bridge, time per step: {seconds['prony'] / seconds['bridge']:.2f}")
    print(f"    (bridge vs simulate on the same frame: peak drifts within {peak_dev:.1e}; Linear: {linear_dev:.1e})")


def part_p695():
    """(f): the far-field FEMA P695 assessment of the example frame, bare and with walls (module docstring)."""
    from vdw_frames.config import load_building
    from vdw_frames.frame import worker_pool

    try:
        from vdw_frames.assessment import collapse_assessment
        from vdw_frames.motion import fema_p695_records

        records = fema_p695_records("far-field")
    except ImportError as error:
        print(f"\n(f) FEMA P695 assessment: skipped ({error})")
        return
    walled = load_building(ROOT / "examples" / "ten_story.toml")
    buildings = {"bare frame": walled.without_devices(), "with walls": walled}
    cores = os.cpu_count() or 1
    print(f"\n(f) FEMA P695 collapse assessment of the example frame, far-field set ({len(records)} records), "
          f"SDC Dmax, {cores} cores")
    steps_seen = {}
    for motion in records:
        steps_seen.setdefault(motion.dt, motion)
    warm = [GroundMotion(m.acceleration[:2100], m.dt) for m in steps_seen.values()]
    kinds = {"threads": "the default executor: a thread pool made by each call, its start-up timed",
             "processes": "a process pool kept for both, its workers warmed first"}
    for kind, description in kinds.items():
        results, seconds = {}, {}
        with worker_pool(kind) as pool, warnings.catch_warnings():
            warnings.simplefilter("ignore")  # strain-range warnings: counted by examples/p695.py, not timed here
            # Compiled code loaded and the walls' fast memory built for each record step (in every worker).
            for building in buildings.values():
                run_batch(building, warm * cores, [0.1], executor=pool, progress=False)
            for label, building in buildings.items():
                started = time.perf_counter()
                results[label] = collapse_assessment(building, records, sdc="Dmax", progress=False,
                                                     executor=None if kind == "threads" else pool)
                seconds[label] = time.perf_counter() - started
        _p695_table(kind, description, results, seconds, records=records, cores=cores, buildings=buildings)


def _p695_table(kind, description, results, seconds, *, records, cores, buildings):
    """Part (f)'s table for one kind of executor."""
    print(f"  {kind} ({description}; load {os.getloadavg()[0]:.2f}):")
    total = sum(seconds.values())
    print(f"    {'':<12} {'analyses':>9} {'per record':>14} {'steps':>11} {'time (s)':>9} {'analyses/s':>11} "
          f"{'ACMR':>6}")
    for label, result in results.items():
        print(f"    {label:<12} {result.total_analyses:>9} {result.analyses.mean():>7.1f} "
              f"(<={result.analyses.max():>2}) "
              f"{int(result.steps.sum()):>11} {seconds[label]:>9.2f} {result.total_analyses / seconds[label]:>11.1f} "
              f"{result.acmr:>6.2f}")
    analyses = sum(r.total_analyses for r in results.values())
    print(f"    both: {analyses} analyses in {total:.1f} s = {analyses / total:.1f} analyses/s, "
          f"{analyses / (2 * len(records)):.1f} analyses a record (target: the whole in <= 60 s: "
          f"{'meets' if total <= 60.0 else 'misses'}, issue 32's <= 1.5 s: {'meets' if total <= 1.5 else 'misses'}; "
          "<= 12 a record on average: "
          f"{'meets' if analyses / (2 * len(records)) <= 12 else 'misses'}, at most "
          f"{max(r.analyses.max() for r in results.values())})")
    if kind != "threads":
        return
    # Where the time goes, on one core: a fixed cost per simulate() call and a cost per step.
    long = max(records, key=lambda m: m.acceleration.size)
    print("    one core:       fixed cost per analysis   cost per step   model of the run (fixed share)")
    for label, building in buildings.items():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            short = GroundMotion(long.acceleration[:20], long.dt)
            fixed, _ = timed(lambda building=building, short=short: simulate(building, short), 20)
            whole, run = timed(lambda building=building: simulate(building, long.scaled(0.5)), 3)
        per_step = (whole - fixed) / run.time.size
        result = results[label]
        model = result.total_analyses * fixed + result.steps.sum() * per_step
        print(f"    {label:<14} {1e3 * fixed:>10.2f} ms {1e6 * per_step:>18.2f} us   {model:.1f} s of work "
              f"({100 * result.total_analyses * fixed / model:.0f} % fixed) = {model / cores:.1f} s on {cores} cores; "
              f"measured: searches {result.search_seconds:.1f} s, the rest (pushover, modes, spectra, bootstrap) "
              f"{seconds[label] - result.search_seconds:.1f} s")


def fixed_parameter_walls(walled: ShearBuilding) -> ShearBuilding:
    """``walled`` with each amplitude-following wall replaced by a wall of fixed parameters, those of its table's
    middle node (same r, area and thickness), without heat or limits: what its fast memory and FDMK stress cost."""
    walls = {}
    for story, wall in walled.wall_list:
        middle = wall.amplitude_table()[wall.amplitude_table().shape[0] // 2]
        walls.setdefault(story, []).append(FDMKDamper(G1=middle[1], G2=middle[2], eta1=middle[3], eta2=middle[4],
                                                      r=wall.common_order, area=wall.area, thickness=wall.thickness))
    return walled.with_walls({story: tuple(group) for story, group in walls.items()})


def part_lanes(benchmark_frame, motion, source, repeats):
    """(i): lanes against single analyses (module docstring); returns the three batches' times a lane and step (us)."""
    import resource

    from vdw_frames.config import load_building
    from vdw_frames.frame.lanes import run_lanes

    record = read_at2(ROOT / "vdw_frames" / "motion" / "data" / "synthetic_kt_035g.AT2")
    walled = load_building(ROOT / "examples" / "ten_story.toml")
    scales = np.linspace(0.2, 1.0, 44)
    print(f"\n(i) lanes: the example frame on the shipped record ({record.acceleration.size} points) x 44 scales "
          "(0.2 ... 1.0), one batch of 44 lanes, against one simulate() call per analysis")
    amortised = {}
    # The walls' share in two parts: their fast memory and FDMK stress (walls of fixed parameters), then what
    # following amplitude, heat and limits adds.
    for label, building, target in (("bare frame", walled.without_devices(), 0.2),
                                    ("walls of fixed parameters (no amplitude, heat or limits)",
                                     fixed_parameter_walls(walled), math.inf),
                                    ("walls (amplitude, heat, limits)", walled, 0.6)):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            run_lanes(building, [record] * 44, scales)  # compile (or load) and size the workspace
            single, result = timed(lambda building=building: simulate(building, record.scaled(0.6)), repeats)
            load_single = os.getloadavg()[0]
            batch, lanes = timed(lambda building=building: run_lanes(building, [record] * 44, scales), repeats)
            load_batch = os.getloadavg()[0]
            before = resource.getrusage(resource.RUSAGE_SELF)
            run_lanes(building, [record] * 44, scales)
            after = resource.getrusage(resource.RUSAGE_SELF)
        steps = sum(lane.steps - 1 for lane in lanes)
        per_step, single_step = 1e6 * batch / steps, 1e6 * single / (result.time.size - 1)
        faults = (after.ru_minflt - before.ru_minflt + after.ru_majflt - before.ru_majflt) / 44
        bar = f"target <= {target:g}: {'meets' if per_step <= target else 'misses'}; " if target < math.inf else ""
        amortised[label] = per_step
        print(f"    {label}: {per_step:.3f} us a step amortised over 44 lanes ({bar}load {load_batch:.2f}); "
              f"one simulate(): {single_step:.3f} us a step (load {load_single:.2f}); "
              f"ratio {single_step / per_step:.2f}; {sum(lane.collapsed for lane in lanes)} of 44 collapsed")
        print(f"        page faults per analysis of a later batch: {faults:.1f} (target <= 10: "
              f"{'meets' if faults <= 10 else 'misses'})")
    frame, plain, walls = amortised.values()
    print(f"    the walled step's shares: the frame {frame / walls:.0%}, the walls' fast memory and FDMK stress "
          f"{(plain - frame) / walls:.0%}, following amplitude, heat and limits {(walls - plain) / walls:.0%} "
          "(differences of the three, same run)")
    # Against OpenSeesPy, per analysis: part (c)'s inelastic frame with fractional walls on its record x 4, as
    # 44 lanes of one batch, against one OpenSees analysis of the same frame with classical r = 1 walls.
    frame, strong = inelastic(benchmark_frame), motion.scaled(4.0)
    memory = FAST if fast_memory_available(benchmark_frame) else "exact"
    opensees, problem = opensees_time(classical_walls(frame), strong.acceleration, strong.dt, 3, tolerance=1e-10,
                                      max_iterations=20, parallel_walls=True)
    if opensees is None:
        print(f"    against OpenSees: skipped ({problem})")
        return amortised
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run_lanes(frame, [motion] * 2, [4.0] * 2, memory=memory)  # compile (or load) before timing
        single, _ = timed(lambda: simulate(frame, strong, memory=memory), repeats)
        batch, lanes = timed(lambda: run_lanes(frame, [motion] * 44, [4.0] * 44, memory=memory), repeats)
    load = os.getloadavg()[0]
    per_analysis = batch / 44
    print(f"    against OpenSeesPy, part (c)'s frame and record ({source} x 4, {motion.acceleration.size} points, "
          f"memory '{memory if isinstance(memory, str) else 'fast'}'), per analysis: 44 lanes {per_analysis:.3f} s, "
          f"one simulate() {single:.3f} s, OpenSees (classical r = 1) {opensees[0]:.3f} s (load {load:.2f})")
    ratio = per_analysis / opensees[0]
    print(f"        lanes / OpenSees = 1/{1 / ratio:.0f} (target <= 1/100: {'meets' if ratio <= 0.01 else 'misses'}); "
          f"one simulate() / OpenSees = 1/{opensees[0] / single:.0f}; {sum(lane.collapsed for lane in lanes)} of 44 "
          "collapsed")
    return amortised


# ------------------------------------------------------------------------------------ (j): lanes innermost
# Prototypes measured against the package, not part of it: the bare frame's step and the walls' fast memory
# with every array's last axis the lanes, so that each pass over stories, modes or window does all lanes in
# SIMD instructions.  What a rewrite of the one integrator in that layout would gain (issue 32's bars).
@njit(cache=True, inline="always")
def _lanes_step_constants(step, ground, dt, frame, state, work):  # pragma: no cover - timed only
    """The parts of every lane's residual fixed by its committed state (integrator._step_constants)."""
    masses, c_diagonal, c_upper = frame[0], frame[1], frame[2]
    u, v, a = state[0], state[1], state[2]
    trial, step_force, offset, scale = work[0], work[10], work[11], work[12]
    n, lanes = u.shape
    a0, v1, a1 = 4.0 / dt**2, 2.0 / dt, 4.0 / dt
    for i in range(n):
        for lane in range(lanes):
            damped = c_diagonal[i] * (v1 * u[i, lane] + v[i, lane])
            if i > 0:
                damped += c_upper[i - 1] * (v1 * u[i - 1, lane] + v[i - 1, lane])
            if i + 1 < n:
                damped += c_upper[i] * (v1 * u[i + 1, lane] + v[i + 1, lane])
            offset[i, lane] = damped
            step_force[i, lane] = (a0 * masses[i] * u[i, lane] + masses[i] * (a1 * v[i, lane] + a[i, lane])
                                   + damped - masses[i] * ground[lane, step + 1])
            trial[i, lane] = u[i, lane]
            scale[i, lane] = 1.0


@njit(cache=True, inline="always")
def _lanes_residual(dt, frame, state, work):  # pragma: no cover - timed only
    """Every lane's Bilinear story trial (hysteresis.story_trial) and unbalanced force (integrator._residual)."""
    masses, c_diagonal, c_upper, geometric, k0, yield_force, hardening = frame[:7]
    committed_drift, committed_force = state[3], state[4]
    trial, drift, force, tangent, total, residual = work[:6]
    step_force, offset, scale, damping = work[10], work[11], work[12], work[13]
    n, lanes = trial.shape
    a0, v1 = 4.0 / dt**2, 2.0 / dt
    for i in range(n):
        bound = (1.0 - hardening) * yield_force[i]
        for lane in range(lanes):
            d = trial[i, lane] - (trial[i - 1, lane] if i > 0 else 0.0)
            drift[i, lane] = d
            elastic = committed_force[i, lane] + k0[i] * (d - committed_drift[i, lane])
            high = hardening * k0[i] * d + bound
            low = hardening * k0[i] * d - bound
            f = min(max(elastic, low), high)
            force[i, lane] = f
            tangent[i, lane] = k0[i] if low <= elastic <= high else hardening * k0[i]
            total[i, lane] = f + geometric[i] * d
    for i in range(n):
        for lane in range(lanes):
            damped = c_diagonal[i] * trial[i, lane]
            if i > 0:
                damped += c_upper[i - 1] * trial[i - 1, lane]
            if i + 1 < n:
                damped += c_upper[i] * trial[i + 1, lane]
            above = total[i + 1, lane] if i + 1 < n else 0.0
            damping[i, lane] = v1 * damped - offset[i, lane]
            residual[i, lane] = (step_force[i, lane] - a0 * masses[i] * trial[i, lane] - v1 * damped
                                 - (total[i, lane] - above))
            scale[i, lane] = max(scale[i, lane], a0 * masses[i] * abs(trial[i, lane]), abs(damping[i, lane]),
                                 abs(force[i, lane]), abs(total[i, lane]))


@njit(cache=True, inline="always")
def _lanes_converged(iteration, frame, flags, work):  # pragma: no cover - timed only
    """Mask the lanes that converged (integrator._iterate's test); returns how many still iterate."""
    geometric = frame[3]
    tangent, residual, solved, scale = work[3], work[5], work[7], work[12]
    active, last_correction = flags[0], flags[1]
    n, lanes = residual.shape
    live = 0
    for lane in range(lanes):
        if active[lane] > 0.0 and iteration > 0:
            norm, largest, exact = 0.0, 1.0, True
            for i in range(n):
                norm = max(norm, abs(residual[i, lane]))
                largest = max(largest, scale[i, lane])
                exact = exact and solved[i, lane] == tangent[i, lane] + geometric[i]
            if norm <= 1e-9 * largest and (exact or last_correction[lane] <= 1e-8):
                active[lane] = 0.0
        live += active[lane] > 0.0
    return live


@njit(cache=True, inline="always")
def _lanes_solve(dt, frame, flags, work):  # pragma: no cover - timed only
    """Every lane's Newton correction (the Thomas algorithm, integrator._solve_tridiagonal) and update."""
    masses, c_diagonal, c_upper, geometric = frame[:4]
    trial, tangent, residual, correction, solved, pivot, upper = (work[0], work[3], work[5], work[6], work[7],
                                                                  work[8], work[9])
    active, last_correction = flags[0], flags[1]
    n, lanes = trial.shape
    a0, v1 = 4.0 / dt**2, 2.0 / dt
    for i in range(n):
        for lane in range(lanes):
            solved[i, lane] = tangent[i, lane] + geometric[i]
    for lane in range(lanes):
        pivot[0, lane] = a0 * masses[0] + v1 * c_diagonal[0] + solved[0, lane] + solved[1, lane]
        correction[0, lane] = residual[0, lane]
    for i in range(1, n):
        for lane in range(lanes):
            off_diagonal = v1 * c_upper[i - 1] - solved[i, lane]
            upper[i, lane] = off_diagonal
            factor = off_diagonal / pivot[i - 1, lane]
            after = solved[i + 1, lane] if i + 1 < n else 0.0
            pivot[i, lane] = a0 * masses[i] + v1 * c_diagonal[i] + solved[i, lane] + after - factor * off_diagonal
            correction[i, lane] = residual[i, lane] - factor * correction[i - 1, lane]
    for lane in range(lanes):
        correction[n - 1, lane] /= pivot[n - 1, lane]
        last_correction[lane] = abs(correction[n - 1, lane])
    for i in range(n - 2, -1, -1):
        for lane in range(lanes):
            correction[i, lane] = (correction[i, lane] - upper[i + 1, lane] * correction[i + 1, lane]) / pivot[i, lane]
            last_correction[lane] = max(last_correction[lane], abs(correction[i, lane]))
    for i in range(n):
        for lane in range(lanes):
            if active[lane] > 0.0:
                trial[i, lane] += correction[i, lane]


# numba takes no keyword-only arguments: the compiled prototypes' arguments are positional (PLR0917).
@njit(cache=True, inline="always")
def _lanes_commit(step, ground, dt, frame, state, work, flags, peaks, energy):  # noqa: PLR0917
    """Commit every standing lane's step, its energies (integrator._record) and peaks (lane_kernel._note_peaks)."""
    masses, geometric, k0, heights, collapse_ratio = frame[0], frame[3], frame[4], frame[7], frame[8]
    u, v, a, committed_drift, committed_force, old_damping = state
    trial, drift, force, total, damping = work[0], work[1], work[2], work[4], work[13]
    collapsed = flags[2]
    n, lanes = u.shape
    a0, v1, a1 = 4.0 / dt**2, 2.0 / dt, 4.0 / dt
    for lane in range(lanes):
        if collapsed[lane] == 0.0:
            energy[1, lane] = 0.0
            energy[2, lane] = 0.0
    for i in range(n):
        for lane in range(lanes):
            if collapsed[lane] > 0.0:
                continue
            increment = trial[i, lane] - u[i, lane]
            velocity = v1 * increment - v[i, lane]
            acceleration = a0 * increment - a1 * v[i, lane] - a[i, lane]
            change = drift[i, lane] - committed_drift[i, lane]
            energy[0, lane] -= 0.5 * masses[i] * (ground[lane, step] + ground[lane, step + 1]) * increment
            energy[1, lane] += 0.5 * masses[i] * velocity * velocity
            energy[2, lane] += 0.5 * force[i, lane] ** 2 / k0[i]
            energy[3, lane] += 0.5 * (force[i, lane] + committed_force[i, lane]) * change
            energy[4, lane] += 0.5 * (damping[i, lane] + old_damping[i, lane]) * increment
            energy[6, lane] += 0.5 * geometric[i] * (drift[i, lane] + committed_drift[i, lane]) * change
            u[i, lane], v[i, lane], a[i, lane] = trial[i, lane], velocity, acceleration
            committed_drift[i, lane], committed_force[i, lane] = drift[i, lane], force[i, lane]
            old_damping[i, lane] = damping[i, lane]
            peaks[0, i, lane] = max(peaks[0, i, lane], abs(drift[i, lane]))
            peaks[1, i, lane] = max(peaks[1, i, lane], abs(acceleration + ground[lane, step + 1]))
            peaks[2, i, lane] = max(peaks[2, i, lane], abs(total[i, lane]))
            if abs(drift[i, lane]) > collapse_ratio * heights[i]:
                collapsed[lane] = 1.0


@njit(cache=True, nogil=True)
def _frame_lanes_innermost(ground, dt, frame, state, work, flags, peaks, energy):  # noqa: PLR0917
    """The bare frame of Bilinear stories, Rayleigh (tridiagonal) C and P-Delta under ``ground`` (L, N) mm/s^2,
    every lane at once, arrays (n, L): ``frame`` (masses, C's diagonal and upper diagonal, -P/h, k0, F_y, hardening,
    heights, collapse drift ratio), ``state`` (u, v, a, committed drift and force, damping force), ``work`` (14
    arrays), ``flags`` (3, L): iterating, last correction, collapsed.  Newton in lockstep, a lane that converged
    or collapsed masked; the package's convergence test (force 1e-9 x the step's force scale, and an exact solve or
    a correction <= 1e-8 mm), its energies and peaks; no walls, devices or fallbacks."""
    active, last_correction, collapsed = flags[0], flags[1], flags[2]
    for step in range(ground.shape[1] - 1):
        _lanes_step_constants(step, ground, dt, frame, state, work)
        for lane in range(active.shape[0]):
            active[lane] = 0.0 if collapsed[lane] > 0.0 else 1.0
            last_correction[lane] = np.inf
        for iteration in range(26):
            _lanes_residual(dt, frame, state, work)
            if _lanes_converged(iteration, frame, flags, work) == 0:
                break
            _lanes_solve(dt, frame, flags, work)
        _lanes_commit(step, ground, dt, frame, state, work, flags, peaks, energy)


@njit(cache=True, nogil=True)
def _memory_lanes_innermost(steps, memory, window, mode_state, history, total):  # pragma: no cover - timed only
    """``steps`` commits of the fast memory of W walls in L lanes (``memory``: the package's MemoryArrays of the
    walls, whose weights every lane shares; window (W, 2, 2 size, L), mode_state (W, 2, K, L), history (2, W, L)):
    each lane the package's kernel.memory_advance in its order of operations, lanes innermost.  The values
    committed are made from the history as the timed package loop makes them."""
    walls, size = memory.window_weights.shape
    modes, lanes = memory.mode_weight.shape[1], history.shape[2]
    for count in range(steps):
        slot, absorb = count % size, count >= size
        filled = min(count + 1, size)
        start, first = (count + 1) % size + size - filled, size - filled
        for w in range(walls):
            for c in range(2):
                for lane in range(lanes):
                    total[lane] = 0.0
                if absorb:
                    for k in range(modes):
                        ratio, weight = memory.mode_ratio[w, k], memory.mode_weight[w, k]
                        for lane in range(lanes):
                            value = ratio * mode_state[w, c, k, lane] + window[w, c, slot, lane]
                            mode_state[w, c, k, lane] = value
                            total[lane] += weight * value
                for lane in range(lanes):
                    value = 1e-3 * history[1 - c, w, lane] + (0.1 if c == 0 else -0.1)
                    window[w, c, slot, lane] = value
                    window[w, c, slot + size, lane] = value
                for i in range(filled):
                    weight = memory.window_weights[w, first + i]
                    for lane in range(lanes):
                        total[lane] += weight * window[w, c, start + i, lane]
                for lane in range(lanes):
                    history[c, w, lane] = total[lane]


@njit(cache=True, nogil=True)
def _memory_package(steps, memory):  # pragma: no cover - timed only
    """The package's kernel.memory_advance ``steps`` times on one lane, the values made as above."""
    for count in range(steps):
        for w in range(memory.values.shape[1]):
            memory.values[0, w] = 1e-3 * memory.history[1, w] + 0.1
            memory.values[1, w] = 1e-3 * memory.history[0, w] - 0.1
        memory_advance(memory, count)


def part_lanes_innermost(amortised, repeats):
    """(j): the lanes-innermost prototypes against the package, and what they project (module docstring)."""
    from vdw_frames.config import load_building
    from vdw_frames.element.bank import _Memory
    from vdw_frames.element.kernel import MemoryArrays
    from vdw_frames.frame.lanes import run_lanes
    from vdw_frames.frame.time_history import frame_arrays

    record = read_at2(ROOT / "vdw_frames" / "motion" / "data" / "synthetic_kt_035g.AT2")
    bare = load_building(ROOT / "examples" / "ten_story.toml").without_devices()
    lanes, n = 44, bare.stories
    scales = np.linspace(0.2, 1.0, lanes)
    ground = np.outer(scales, record.acceleration)
    frame = frame_arrays(bare, 0.10)
    hysteresis = bare.hysteresis
    constants = (frame.masses, np.diag(frame.damping).copy(), np.diag(frame.damping, 1).copy(), frame.geometric,
                 np.asarray(bare.stiffnesses, dtype=float), np.array([h.yield_force for h in hysteresis]),
                 hysteresis[0].hardening, frame.heights, frame.collapse_ratio)

    def prototype():
        peaks = np.zeros((3, n, lanes))
        _frame_lanes_innermost(ground, record.dt, constants, tuple(np.zeros((n, lanes)) for _ in range(6)),
                               tuple(np.zeros((n, lanes)) for _ in range(14)), np.zeros((3, lanes)), peaks,
                               np.zeros((7, lanes)))
        return peaks

    print(f"\n(j) lanes innermost (prototypes, not the package): the bare example frame on the shipped record x "
          f"{lanes} scales, and the fast memory of 10 walls in {lanes} lanes, each against the package in turn")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        results = run_lanes(bare, [record] * lanes, scales)
    peaks = prototype()
    package_drift = np.array([lane.peak_drift for lane in results]).T
    difference = np.abs(peaks[0] - package_drift).max() / package_drift.max()
    steps = sum(lane.steps - 1 for lane in results)
    frame_ratios = []
    for _ in range(repeats):
        started = time.thread_time()
        prototype()
        mine = time.thread_time() - started
        started = time.thread_time()
        run_lanes(bare, [record] * lanes, scales)
        theirs = time.thread_time() - started
        frame_ratios.append(mine / theirs)
        print(f"    frame: prototype {1e6 * mine / steps:.3f} us a lane and step, package "
              f"{1e6 * theirs / steps:.3f} us")
    frame_ratio = float(np.median(frame_ratios))
    print(f"    the frame's step lanes innermost: {frame_ratio:.2f} of the package's time (median of {repeats}); "
          f"peak drifts within {difference:.1e} of the package's (relative to the largest)")
    order = load_building(ROOT / "examples" / "ten_story.toml").wall_list[0][1].common_order
    weights = _Memory.allocate(order, record.dt, 4 * record.acceleration.size, memory=FAST)
    walls, size, modes = 10, weights.window_weights.size, weights.mode_weight.size
    memory = MemoryArrays(np.full(walls, weights.w0), np.tile(weights.window_weights, (walls, 1)),
                          np.zeros((walls, 2, 2 * size)), np.tile(weights.mode_weight, (walls, 1)),
                          np.tile(weights.mode_ratio, (walls, 1)), np.zeros((walls, 2, modes)), np.zeros((2, walls)),
                          np.zeros((2, walls)))
    memory_ratios = []
    count = max(2000, record.acceleration.size)
    _memory_lanes_innermost(1, memory, np.zeros((walls, 2, 2 * size, lanes)), np.zeros((walls, 2, modes, lanes)),
                            np.zeros((2, walls, lanes)), np.zeros(lanes))  # compile (or load) before timing
    _memory_package(1, memory._replace(window=np.zeros_like(memory.window)))
    for _ in range(repeats):
        lanes_memory = (np.zeros((walls, 2, 2 * size, lanes)), np.zeros((walls, 2, modes, lanes)),
                        np.zeros((2, walls, lanes)), np.zeros(lanes))
        started = time.thread_time()
        _memory_lanes_innermost(count, memory, *lanes_memory)
        mine = (time.thread_time() - started) / (count * walls * lanes)
        started = time.thread_time()
        _memory_package(count * 4, memory._replace(window=np.zeros_like(memory.window),
                                                    mode_state=np.zeros_like(memory.mode_state),
                                                    history=np.zeros_like(memory.history)))
        theirs = (time.thread_time() - started) / (count * 4 * walls)
        memory_ratios.append(mine / theirs)
        print(f"    fast memory ({modes} modes, a window of {size}, two channels): prototype {1e9 * mine:.1f} ns a "
              f"wall, lane and step, package {1e9 * theirs:.1f} ns a wall and step")
    memory_ratio = float(np.median(memory_ratios))
    print(f"    the fast memory lanes innermost: {memory_ratio:.2f} of the package's time (median of {repeats})")
    if amortised:
        bare_step, fixed_step, walled_step = amortised.values()
        projected_bare = bare_step * frame_ratio
        projected_walls = (projected_bare + (fixed_step - bare_step) * memory_ratio
                           + (walled_step - fixed_step) * memory_ratio)
        print(f"    projected for a rewrite of the one integrator in this layout (part (i)'s figures of this run times "
              f"these ratios; the walls' whole commit assumed to gain as their memory does): bare "
              f"{projected_bare:.2f} us a lane and step (target <= 0.2), walls {projected_walls:.2f} us (<= 0.6)")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="2 000 and 20 000 steps only, single repeats")
    parser.add_argument("--part", action="append", choices=list("abcdefghij"),
                        help="run only this part (repeatable; default: every part)")
    args = parser.parse_args(argv)
    parts = set(args.part or "abcdefghij")
    repeats = 1 if args.quick else 5

    motion, source = load_record()
    building = ten_story()
    print("vdw_frames benchmark" + (" (--quick)" if args.quick else ""))
    load = os.getloadavg() if hasattr(os, "getloadavg") else (math.nan,) * 3
    print(f"machine: {platform.machine()}, {os.cpu_count()} CPUs, load {load[0]:.2f}; Python "
          f"{platform.python_version()}, numpy {np.__version__}, numba {__import__('numba').__version__}")
    print(f"record: {source}: {motion.acceleration.size} points, dt = {motion.dt:g} s, "
          f"PGA = {motion.pga / G:.3f} g")
    fast = fast_memory_available(building)
    # Compile (or load from the cache) before timing anything.
    warm = GroundMotion(motion.acceleration[:50], motion.dt)
    for memory in ("exact", "fast") if fast else ("exact",):
        simulate(building, warm, memory=memory)

    timings: dict[str, dict[int, float]] = {"exact": {}, "fast": {}}
    if "a" in parts:
        timings = part_a(building, motion, fast, args.quick, repeats)
    if "b" in parts:
        part_b(timings)
    opensees_seconds = None
    if "c" in parts:
        opensees_seconds = part_c(building, motion, source, fast, timings, quick=args.quick, repeats=repeats)
    if "g" in parts:
        part_walls(motion, source, opensees_seconds, repeats)
    if "d" in parts:
        part_d()
    if "e" in parts:
        part_bridge(building, motion, source, args.quick, repeats)
    if "f" in parts:
        part_p695()
    if "h" in parts:
        part_fvd(motion, source, args.quick, repeats)
    amortised = None
    if "i" in parts:
        amortised = part_lanes(building, motion, source, repeats)
    if "j" in parts:
        part_lanes_innermost(amortised, repeats)
    return 0


if __name__ == "__main__":
    sys.exit(main())
