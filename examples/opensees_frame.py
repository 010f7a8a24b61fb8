"""A 2-D steel moment frame in OpenSees with FDMK walls, exactly (vdw_frames.interop.opensees.WallBridge), and
with each wall as its Prony series (a native OpenSees material), against the bare frame.

Frame (N-mm-s-tonne): 4 stories x 3 bays of 6 m, story heights 4.2 m (first) and 3.6 m; columns and
beams are ``forceBeamColumn`` elements with five Lobatto points of fibre wide-flange sections
(``WFSection2d``; columns 400 x 400 mm, web 25 mm, flanges 40 mm, about a W14x283; beams 610 x 230 mm, web
13 mm, flanges 22 mm, about a W24x104) of Steel02 (F_y = 345 MPa, E = 200 GPa, b = 0.01), so that they
yield where the moments are largest (distributed plasticity); P-Delta transformation on the columns.
Masses 180 t per floor (roof 150 t), lumped at the four column joints.  Gravity: the weight of those
masses, 30 N/mm uniformly on every beam and the rest at the column joints, applied first (10 static
steps) and then held.  Inherent damping: 2 % Rayleigh on the initial stiffness in modes 1 and 3.
Newmark average acceleration, Newton (fallbacks KrylovNewton, NewtonLineSearch), at half the record's
step.

Walls: one per story, in the middle bay, from the midspan of the beam below (the ground, for the
first story) to the midspan of the beam above, acting horizontally: the package's recommended FDMK
parameters for 300 % strain (r = 0.59; 0.08 m^2 of shear area, 10 mm layers) on a support of
200 kN/mm in series (connection and beam flexibility; ``SupportedDamper``).  They are added after the
gravity analysis, so that they carry no gravity force.

    python examples/opensees_frame.py [--record PATH.AT2] [--pga PGA_g | --factor F] [--duration S] [--out DIR]

Without --record it runs El Centro 1940 (N-S) from ../shared/ground_motions next to the repository,
or the synthetic record shipped with the package when that folder is absent.  Prints peak drift
ratios, wall forces and strains (bare frame, bridge, Prony material) and how far the Prony material
is from the exact bridge; writes drift_envelope.png and wall_hysteresis.png to --out.  Needs OpenSeesPy
(``pip install 'vdw-frames[opensees]'``).
"""

from __future__ import annotations

import argparse
import itertools
import sys
import time
from pathlib import Path

import numpy as np

import vdw_frames as vdw
from vdw_frames import motion as ground_motion
from vdw_frames.cli import plain_warnings
from vdw_frames.interop.opensees import WallBridge, opensees_module, prony_material
from vdw_frames.paper import fitted

SHARED = Path(__file__).resolve().parents[1].parent / "shared" / "ground_motions"
DEFAULT_RECORD = "elCentro.AT2"

STORIES, BAYS, BAY = 4, 3, 6000.0  # mm
HEIGHTS = (4200.0, 3600.0, 3600.0, 3600.0)  # mm
MASSES = (180.0, 180.0, 180.0, 150.0)  # tonne per floor
BEAM_LOAD = 30.0  # N/mm on every beam
STEEL = (345.0, 200000.0, 0.01)  # F_y (MPa), E (MPa), b
COLUMN = (400.0, 25.0, 400.0, 40.0)  # depth, web, flange width, flange thickness (mm)
BEAM = (610.0, 13.0, 230.0, 22.0)
DAMPING = 0.02
WALL = vdw.SupportedDamper(fitted(300, area=0.8e5), support_stiffness=2.0e5)
WALL_BAY = 2  # the middle bay
PRONY_BAND = (0.1, 10.0)  # Hz
ALGORITHM, FALLBACKS = "Newton", ("KrylovNewton", "NewtonLineSearch")


def joint(floor: int, column: int) -> int:
    """Node tag of a beam-column joint (floor 0 is the ground, columns 1-4 from the left)."""
    return 100 * floor + column


def midspan(floor: int) -> int:
    """Node tag at the midspan of the wall bay's beam (on the ground for floor 0)."""
    return 100 * floor + 50


def column_tag(floor: int, column: int) -> int:
    """Element tag of the column below a joint."""
    return 1000 + 10 * floor + column


def yield_curvature(section) -> float:
    """2 eps_y / depth (1/mm): the curvature at which the flanges of a section yield."""
    return 2.0 * STEEL[0] / STEEL[1] / section[0]


def build_frame(ops) -> np.ndarray:
    """The frame in a fresh domain, gravity applied and held; returns the periods of modes 1-3 (s)."""
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    levels = np.concatenate([[0.0], np.cumsum(HEIGHTS)])
    for floor in range(STORIES + 1):
        for column in range(1, BAYS + 2):
            ops.node(joint(floor, column), (column - 1) * BAY, levels[floor])
            if floor == 0:
                ops.fix(joint(floor, column), 1, 1, 1)
            else:
                share = MASSES[floor - 1] / (BAYS + 1)
                ops.mass(joint(floor, column), share, share, 0.0)
        ops.node(midspan(floor), (WALL_BAY - 0.5) * BAY, levels[floor])
    ops.fix(midspan(0), 1, 1, 1)
    ops.uniaxialMaterial("Steel02", 1, *STEEL, 20.0, 0.925, 0.15)
    ops.section("WFSection2d", 1, 1, *COLUMN, 10, 4)
    ops.section("WFSection2d", 2, 1, *BEAM, 10, 4)
    ops.beamIntegration("Lobatto", 1, 1, 5)
    ops.beamIntegration("Lobatto", 2, 2, 5)
    ops.geomTransf("PDelta", 1)
    ops.geomTransf("Linear", 2)
    beams = []
    for floor in range(1, STORIES + 1):
        for column in range(1, BAYS + 2):
            ops.element("forceBeamColumn", column_tag(floor, column), joint(floor - 1, column), joint(floor, column),
                        1, 1)
        for bay in range(1, BAYS + 1):
            ends = [joint(floor, bay), joint(floor, bay + 1)]
            if bay == WALL_BAY:
                ends.insert(1, midspan(floor))
            for start, end in itertools.pairwise(ends):
                tag = 2000 + 100 * floor + len(beams)
                ops.element("forceBeamColumn", tag, start, end, 2, 2)
                beams.append(tag)
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    for floor in range(1, STORIES + 1):
        weight = MASSES[floor - 1] * vdw.G  # N (tonne * mm/s^2)
        on_beams = BEAM_LOAD * BAY * BAYS
        for column in range(1, BAYS + 2):
            ops.load(joint(floor, column), 0.0, -(weight - on_beams) / (BAYS + 1), 0.0)
    for tag in beams:
        ops.eleLoad("-ele", tag, "-type", "-beamUniform", -BEAM_LOAD)
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-8, 30)
    ops.algorithm(ALGORITHM)
    ops.integrator("LoadControl", 0.1)
    ops.analysis("Static")
    if ops.analyze(10) != 0:
        raise RuntimeError("the gravity analysis failed")
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()
    omega = np.sqrt(ops.eigen(3))
    a0, a1 = 2 * DAMPING * omega[0] * omega[2] / (omega[0] + omega[2]), 2 * DAMPING / (omega[0] + omega[2])
    ops.rayleigh(a0, 0.0, a1, 0.0)  # alphaM, betaK, betaKinit, betaKcomm: the initial stiffness
    return 2 * np.pi / omega


def start_transient(ops, motion, dt):
    """Ground motion (UniformExcitation in x) and the transient analysis."""
    values = motion.acceleration_at(dt).tolist()
    ops.timeSeries("Path", 2, "-dt", dt, "-values", *values, values[-1])  # 0 past its end: repeat the last
    ops.pattern("UniformExcitation", 2, 1, "-accel", 2)
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-8, 30)
    ops.algorithm(ALGORITHM)
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    return len(values)


def analyze_with_fallbacks(ops, dt) -> int:
    """One step of the frames without the bridge, with the bridge's fallbacks."""
    status = ops.analyze(1, dt)
    for algorithm in FALLBACKS:
        if status == 0:
            break
        ops.algorithm(algorithm)
        status = ops.analyze(1, dt)
        ops.algorithm(ALGORITHM)
    return status


def run(ops, motion, dt, walls=None):
    """The frame under ``motion`` at step ``dt``: walls None (bare), "bridge" or "prony".

    Returns a dict: time (s), drift (mm, steps x stories, from the mean of each floor's joints),
    curvature_ductility (peak end-section curvature / yield curvature of the beams and of the columns), and
    with walls wall_force (N) and wall_deformation (mm), steps x stories; "bridge" also wall_strain (-),
    "prony" the series.  Stops early (with a message) if a step fails even with the fallbacks.
    """
    build_frame(ops)
    columns = [column_tag(floor, column) for floor in range(1, STORIES + 1) for column in range(1, BAYS + 2)]
    beams = [tag for tag in ops.getEleTags() if 2000 <= tag < 3000]
    ductility = np.zeros(2)
    bridge = series = None
    wall_elements = []
    if walls == "bridge":
        bridge = WallBridge(ops, dt, fallback_algorithms=FALLBACKS, algorithm=ALGORITHM)
        for story in range(1, STORIES + 1):
            bridge.add_wall(midspan(story - 1), midspan(story), 1, WALL)
    elif walls == "prony":
        series = WALL.prony(*PRONY_BAND, tolerance=0.01)
        for story in range(1, STORIES + 1):
            material = prony_material(ops, 100 * story, series)
            tag = 3000 + story
            ops.element("zeroLength", tag, midspan(story - 1), midspan(story), "-mat", material, "-dir", 1)
            wall_elements.append(tag)
    steps = start_transient(ops, motion, dt)
    floors = [[joint(floor, column) for column in range(1, BAYS + 2)] for floor in range(1, STORIES + 1)]
    displacement = np.zeros((steps, STORIES))
    force = np.zeros((steps, STORIES))
    deformation = np.zeros((steps, STORIES))
    done = steps
    for n in range(1, steps):
        status = bridge.analyze(1) if bridge is not None else analyze_with_fallbacks(ops, dt)
        if status != 0:
            print(f"    ({walls or 'bare'}: the step to t = {n * dt:.3f} s failed even with the fallbacks; stopped)")
            done = n
            break
        displacement[n] = [np.mean([ops.nodeDisp(node, 1) for node in nodes]) for nodes in floors]
        for index, (tags, section) in enumerate(((beams, BEAM), (columns, COLUMN))):
            curvature = max(abs(ops.sectionDeformation(tag, point)[1]) for tag in tags for point in (1, 5))
            ductility[index] = max(ductility[index], curvature / yield_curvature(section))
        if wall_elements:
            force[n] = [ops.eleResponse(tag, "basicForce")[0] for tag in wall_elements]
            deformation[n] = [ops.eleResponse(tag, "basicDeformation")[0] for tag in wall_elements]
    ops.wipe()
    result = {"time": dt * np.arange(done), "drift": np.diff(displacement[:done], axis=1, prepend=0.0),
              "curvature_ductility": ductility}
    if bridge is not None:
        result.update(wall_force=bridge.force[:done], wall_deformation=bridge.deformation[:done],
                      wall_strain=bridge.strain[:done], fallback_steps=len(bridge.fallback_steps))
    if series is not None:
        result.update(wall_force=force[:done], wall_deformation=deformation[:done], series=series)
    return result


def load_motion(record, pga=None, duration=None, factor=None):
    """The record (El Centro from the shared folder, else the shipped one), scaled to ``pga`` (g) or by
    ``factor``, cut to ``duration`` (s); errors name the flag as typed, in g."""
    if record is None and (SHARED / DEFAULT_RECORD).is_file():
        record = SHARED / DEFAULT_RECORD
    if pga is not None and not (np.isfinite(pga) and pga > 0.0):
        raise ValueError(f"--pga must be a PGA > 0 in g, got {pga:g}")
    if factor is not None and not (np.isfinite(factor) and factor > 0.0):
        raise ValueError(f"--factor must be a scale factor > 0, got {factor:g}")
    if duration is not None and not (np.isfinite(duration) and duration > 0.0):
        raise ValueError(f"--duration must be > 0 s, got {duration:g}")
    motion = ground_motion.read_at2(record) if record is not None else ground_motion.default_record()
    try:
        if pga is not None:
            motion = motion.scaled_to_pga(pga * ground_motion.G)
        elif factor is not None:
            motion = motion.scaled(factor)
    except ValueError as error:
        raise ValueError(f"--pga {pga:g}: {error}" if pga is not None else f"--factor {factor:g}: {error}") from None
    if duration is not None:
        points = min(motion.acceleration.size, round(duration / motion.dt) + 1)
        motion = ground_motion.GroundMotion(motion.acceleration[:points], motion.dt, motion.name)
    return motion


def plot(results, out: Path) -> list[Path]:
    from vdw_frames.plotting._figure import pyplot as _pyplot

    plt = _pyplot()
    out.mkdir(parents=True, exist_ok=True)
    heights = np.array(HEIGHTS)
    figure, axis = plt.subplots(figsize=(5.5, 5.0))
    levels = np.arange(1, STORIES + 1)
    for label, style in (("bare", "k--o"), ("walls (bridge)", "b-s"), ("walls (Prony)", "r:^")):
        if label in results:
            ratio = 100 * np.abs(results[label]["drift"]).max(axis=0) / heights
            axis.plot(ratio, levels, style, label=label)
    axis.set_xlabel("peak drift ratio (%)")
    axis.set_ylabel("story")
    axis.set_yticks(levels)
    axis.set_xlim(left=0.0)
    axis.set_title("Drift envelope, 4-story steel frame")
    axis.grid(True, alpha=0.3)
    axis.legend()
    paths = [out / "drift_envelope.png"]
    figure.tight_layout()
    figure.savefig(paths[0], dpi=130)
    plt.close(figure)

    figure, axis = plt.subplots(figsize=(6.0, 4.5))
    for label, style in (("walls (bridge)", "b-"), ("walls (Prony)", "r:")):
        if label in results:
            axis.plot(results[label]["wall_deformation"][:, 0], results[label]["wall_force"][:, 0] / 1e3, style,
                      lw=0.8, label=label)
    axis.set_xlabel("deformation across wall and support, u_j - u_i (mm)")
    axis.set_ylabel("wall force (kN)")
    axis.set_title("Story 1 wall on its support")
    axis.grid(True, alpha=0.3)
    axis.legend()
    paths.append(out / "wall_hysteresis.png")
    figure.tight_layout()
    figure.savefig(paths[1], dpi=130)
    plt.close(figure)
    return paths


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], allow_abbrev=False)
    parser.add_argument("--record", type=Path, help=f"PEER AT2 record (default: ../shared/ground_motions/"
                                                    f"{DEFAULT_RECORD}, else the shipped synthetic record)")
    scale = parser.add_mutually_exclusive_group()
    scale.add_argument("--pga", type=float, help="scale the record to this PGA, in g")
    scale.add_argument("--factor", type=float, help="multiply the record by this factor")
    parser.add_argument("--duration", type=float, help="use only the first DURATION seconds of the record")
    parser.add_argument("--out", type=Path, default=Path("opensees_frame"),
                        help="folder for the figures (default ./opensees_frame)")
    args = parser.parse_args(argv)
    try:  # one error line, as the vdw-frames command gives
        motion = load_motion(args.record, args.pga, args.duration, args.factor)
        ops = opensees_module()
        return run_frames(ops, motion, args.out)
    except (ValueError, OSError, ImportError) as error:
        print(f"opensees_frame.py: error: {error}", file=sys.stderr)
        return 2


def run_frames(ops, motion, out: Path) -> int:
    """The bare frame, the bridged walls and the Prony walls under ``motion``; prints and plots."""
    out.mkdir(parents=True, exist_ok=True)
    # OpenSees's own messages (the Maxwell material's banner, "Process 0 Terminating" at exit, its warnings)
    # go to a log beside the figures instead of between the tables.
    ops.logFile(str(out / "opensees.log"), "-noEcho")
    print(f"OpenSees's own messages: {out / 'opensees.log'}")
    dt = motion.dt / 2
    print(f"record {motion.name}: {motion.acceleration.size} points, dt = {motion.dt:g} s, "
          f"PGA = {motion.pga / ground_motion.G:.3f} g; analysis step {dt:g} s")
    periods = build_frame(ops)
    print("frame: 4 stories x 3 bays, fibre forceBeamColumn elements, periods (s): "
          + ", ".join(f"{p:.3f}" for p in periods))
    wall = WALL.damper
    print(f"walls: one per story (middle bay), 300 % set: G1={wall.G1:.3g} MPa, G2={wall.G2:.3g} MPa, "
          f"eta1={wall.eta1:.3g}, eta2={wall.eta2:.3g} MPa*s^r, r={wall.r:.3g}, A={wall.area:g} mm^2, "
          f"h={wall.thickness:g} mm, on a {WALL.support_stiffness / 1e3:g} kN/mm support; "
          f"K'(1/T1) = {WALL.storage_stiffness(1 / periods[0]) / 1e3:.1f} kN/mm")

    results = {}
    for label, walls in (("bare", None), ("walls (bridge)", "bridge"), ("walls (Prony)", "prony")):
        started = time.perf_counter()
        results[label] = run(ops, motion, dt, walls)
        print(f"  {label:<15} {time.perf_counter() - started:6.1f} s")
    for label, result in results.items():
        beams, columns = result["curvature_ductility"]
        print(f"  {label:<15} peak end-section curvature / yield curvature: beams {beams:.2f}, columns {columns:.2f}"
              + ("  (the frame yields)" if max(beams, columns) > 1.0 else "  (elastic)"))
    bridge, prony = results["walls (bridge)"], results["walls (Prony)"]
    series = prony["series"]
    print(f"Prony series of the wall on {PRONY_BAND[0]:g}-{PRONY_BAND[1]:g} Hz: {len(series)} Maxwell branches, "
          f"|K*| within {100 * series.error:.2f} % (tolerance 1 %); shortest relaxation time "
          f"{series.relaxation_times.min():.4f} s against the step {dt:g} s.  As links (N, mm, s):")
    for row in series.to_table():
        exponent = "" if row["damping_exponent"] is None else f", exponent {row['damping_exponent']:g}"
        print(f"    {row['link']:<3} {row['type']:<21} k = {row['stiffness']:10.1f} N/mm, "
              f"c = {row['damping_coefficient']:10.1f} N*s/mm{exponent}")

    heights = np.array(HEIGHTS)
    print("\nstory   peak drift ratio (%)                 peak wall force (kN)   peak wall strain (%)")
    print("        bare   bridge  Prony  Prony-bridge      bridge   Prony          bridge")
    for story in range(STORIES):
        ratios = [100 * np.abs(results[label]["drift"][:, story]).max() / heights[story]
                  for label in ("bare", "walls (bridge)", "walls (Prony)")]
        forces = [np.abs(results[label]["wall_force"][:, story]).max() / 1e3
                  for label in ("walls (bridge)", "walls (Prony)")]
        strain = 100 * np.abs(bridge["wall_strain"][:, story]).max()
        print(f"  {story + 1}    {ratios[0]:6.3f}  {ratios[1]:6.3f}  {ratios[2]:6.3f}  "
              f"{100 * (ratios[2] / ratios[1] - 1):+6.2f} %       {forces[0]:8.1f} {forces[1]:8.1f}        "
              f"{strain:8.1f}")
    steps = min(bridge["drift"].shape[0], prony["drift"].shape[0])
    history = np.abs(prony["drift"][:steps] - bridge["drift"][:steps]).max() / np.abs(bridge["drift"]).max()
    bare_peak, bridge_peak = (np.abs(results[label]["drift"]).max(axis=0) / heights
                              for label in ("bare", "walls (bridge)"))
    print(f"walls reduce the largest peak drift ratio by {100 * (1 - bridge_peak.max() / bare_peak.max()):.1f} %; "
          f"the Prony material deviates from the exact bridge by at most "
          f"{100 * np.abs(np.abs(prony['drift']).max(axis=0) / np.abs(bridge['drift']).max(axis=0) - 1).max():.2f} % "
          f"in peak drifts ({100 * history:.2f} % of the peak in the drift histories)")
    low, high = WALL.strain_range
    outside = [story + 1 for story, peak in enumerate(np.abs(bridge["wall_strain"]).max(axis=0))
               if not low <= peak <= high]
    if outside:
        print(f"caution: the peak strain of the walls of stories {', '.join(map(str, outside))} lies outside the "
              f"{100 * low:.0f}-{100 * high:.0f} % the 300 % parameters were identified for (the walls' moduli "
              "depend on the strain amplitude; see vdw_frames.paper.strain_dependent)")
    if bridge["fallback_steps"]:
        print(f"(the bridge retried {bridge['fallback_steps']} steps with a fallback algorithm)")
    for path in plot(results, out):
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    with plain_warnings():  # one line "warning: ...", as the vdw-frames command prints them
        sys.exit(main())
