"""FDMK walls inside OpenSeesPy models through vdw_frames.interop.opensees.WallBridge.

References: :func:`vdw_frames.simulate` on the same shear building (an independent integrator: the
package's own Newmark-Newton loop against OpenSees's, sharing only the wall kernel), OpenSees's own
``Elastic`` (with eta) and ``Maxwell`` materials for classical r = 1 walls, and linear superposition.
The bridged frames use Newmark average acceleration with Newton to a displacement-increment norm of
1e-12 mm, so "exact" here means equal to that tolerance.
"""

import dataclasses
import subprocess
import sys
import warnings

import numpy as np
import opensees_frame
import pytest
from builders import (
    CLASSICAL_WALL_A,
    FRACTIONAL_WALL_A,
    FRACTIONAL_WALL_B,
    classical_ten_story,
    fractional_ten_story,
)
from reference import history_deviation, peak_deviation

from vdw_frames import Bilinear, FDMKDamper, SupportedDamper, simulate
from vdw_frames.element import FastMemory
from vdw_frames.element.limits import WallLimits
from vdw_frames.frame import NewtonRaphson
from vdw_frames.interop.opensees import WallBridge, opensees_module
from vdw_frames.paper import strain_dependent

TIGHT = NewtonRaphson(displacement_tolerance=1e-12, force_tolerance=1e-13, max_iterations=50)

pytestmark = pytest.mark.opensees


def quiet_simulate(*args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # strain-range warnings: not what is tested
        return simulate(*args, **kwargs)


def newmark_newton(ops):
    """Newmark average acceleration, Newton to 1e-12 mm (the analysis objects short of ``analysis``)."""
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-12, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)


# ---------------------------------------------------------------------------------------------- exactness
@pytest.mark.parametrize("bridge_memory, simulate_memory", [
    ("exact", "exact"),
    (FastMemory(exact_below=0), FastMemory(exact_below=0)),  # the same modes on both sides
    ("fast", "fast"),  # the bridge's modes against simulate's exact memory (a record under 2 048 steps)
])
@pytest.mark.records
def test_bridged_shear_building_equals_simulate(ops, record, bridge_memory, simulate_memory):
    building = fractional_ten_story()
    expected = quiet_simulate(building, record, memory=simulate_memory)
    displacement, bridge = opensees_frame.run_bridged(building, record.acceleration, record.dt, memory=bridge_memory,
                                                      step_by_step=True)
    drift = opensees_frame.drifts(displacement)  # read from the OpenSees nodes every step
    assert bridge.steps == record.acceleration.size - 1 and bridge.failed_step is None
    assert peak_deviation(drift, expected.drift) < 1e-9  # measured 1e-14; 2e-12 (modes vs exact memory)
    assert history_deviation(drift, expected.drift) < 1e-9
    scale = np.abs(expected.wall_force).max()
    assert np.abs(bridge.force - expected.wall_force).max() < 1e-9 * scale
    assert np.abs(bridge.strain - expected.wall_strain).max() < 1e-9 * np.abs(expected.wall_strain).max()
    np.testing.assert_allclose(bridge.time, expected.time, atol=1e-9)
    # The walls matter: every story's walls carry more than a fifth of its frame spring's peak force.
    assert (expected.peak_story_wall_force > np.abs(expected.story_shear).max(axis=0) / 5).all()


@pytest.mark.records
def test_wall_elements_carry_the_full_wall_force(ops, record):
    # The element's own force (K_t d + sig0) is the wall's: recorders on bridge.element_tags are right.
    floors, bridge = opensees_frame.build_bridged(fractional_ten_story(), record.dt)
    opensees_frame._ground(record.acceleration, record.dt, floors)
    element_force = []
    for _ in range(300):
        assert bridge.analyze(1) == 0
        element_force.append([ops.eleResponse(tag, "basicForce")[0] for tag in bridge.element_tags])
    ops.wipe()
    np.testing.assert_allclose(element_force, bridge.force[1:], rtol=0, atol=1e-9 * np.abs(bridge.force).max())


@pytest.mark.records
def test_bridged_steel01_frame_equals_simulate_bilinear(ops, record):
    # Yielding stories: OpenSees Steel01 (b = 0.05, no isotropic hardening) against vdw_frames' Bilinear, the
    # same law; both Newmark + Newton to 1e-12 mm.  Yield forces at 60 % of the elastic frame's peak shears.
    elastic = quiet_simulate(fractional_ten_story(), record)
    shears = np.abs(elastic.story_shear).max(axis=0)
    building = fractional_ten_story([Bilinear(0.6 * shear, 0.05) for shear in shears])
    expected = quiet_simulate(building, record, newton=TIGHT)
    assert (expected.peak_ductility > 1.2).all()  # every story yields
    displacement, bridge = opensees_frame.run_bridged(building, record.acceleration, record.dt, step_by_step=True)
    drift = opensees_frame.drifts(displacement)
    assert peak_deviation(drift, expected.drift) < 1e-9  # measured 3e-12
    assert history_deviation(drift, expected.drift) < 1e-9
    assert np.abs(bridge.force - expected.wall_force).max() < 1e-9 * np.abs(expected.wall_force).max()


@pytest.mark.records
def test_walls_added_after_a_static_load_count_from_there(ops, record):
    # Linear superposition: a constant lateral load applied (static analysis) before the walls are added
    # holds the frame at u_s; the walls then see only the dynamic part, which is the at-rest response.
    building = fractional_ten_story()
    floors = opensees_frame.build_bare(building)
    ops.timeSeries("Constant", 7)
    ops.pattern("Plain", 7, 7)
    for node in floors:
        ops.load(node, 2.0e4 * node)
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    assert ops.analyze(1) == 0
    static = np.array([ops.nodeDisp(node, 1) for node in floors])
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()
    newmark_newton(ops)
    bridge = WallBridge(ops, record.dt)
    for story, wall in building.wall_list:
        bridge.add_wall(story - 1, story, 1, wall)
    opensees_frame._ground(record.acceleration, record.dt, floors)
    displacement = np.zeros((record.acceleration.size, len(floors)))
    for n in range(1, record.acceleration.size):
        assert bridge.analyze(1) == 0
        displacement[n] = [ops.nodeDisp(node, 1) for node in floors]
    ops.wipe()
    assert np.abs(static).max() > 10.0  # mm: a real offset
    dynamic = opensees_frame.drifts(displacement - static)
    dynamic[0] = 0.0
    expected = quiet_simulate(building, record)
    assert history_deviation(dynamic, expected.drift) < 1e-9
    assert np.abs(bridge.force - expected.wall_force).max() < 1e-9 * np.abs(expected.wall_force).max()


@pytest.mark.records
def test_r1_walls_through_the_bridge_match_opensees_own_maxwell(ops, record):
    # Classical walls: the bridge (the package's discretisation, trapezoidal here) against OpenSees's Elastic
    # + Maxwell materials (its exponential integrator): they differ by the two discretisations, O(dt^2).
    building = classical_ten_story()
    native = opensees_frame.drifts(opensees_frame.run(building, record.acceleration, record.dt))
    for method, bar in (("trapezoidal", 1e-3), ("damped", 0.01)):
        displacement, _ = opensees_frame.run_bridged(building, record.acceleration, record.dt, method=method)
        deviation = peak_deviation(opensees_frame.drifts(displacement), native)
        assert deviation < bar, (method, deviation)  # measured 1.1e-4 and 1.3e-3


# ---------------------------------------------------------------------------------------------- 2-D frame
FRAME_STORIES, BAY, HEIGHT = 3, 6000.0, 3500.0


def frame_2d(ops, walls, dt, acceleration, native=False, method="damped"):
    """A 3-story, 1-bay elastic steel frame (ndm 2, ndf 3) with a wall per story on the left column line,
    between the floor nodes (dof 1).  ``native``: the r = 1 walls as OpenSees Elastic(k1, c1) + Maxwell
    zeroLength elements instead of the bridge.  Returns the left floor nodes' displacement histories (mm)."""
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    for floor in range(FRAME_STORIES + 1):
        for column in (1, 2):
            ops.node(10 * floor + column, (column - 1) * BAY, floor * HEIGHT)
            if floor == 0:
                ops.fix(10 * floor + column, 1, 1, 1)
            else:
                ops.mass(10 * floor + column, 60.0, 60.0, 0.0)
    ops.geomTransf("Linear", 1)
    tag = 0
    for floor in range(1, FRAME_STORIES + 1):
        for column in (1, 2):  # columns: E = 200 GPa, A = 2e4 mm^2, I = 6e8 mm^4
            tag += 1
            ops.element("elasticBeamColumn", tag, 10 * (floor - 1) + column, 10 * floor + column, 2.0e4, 2.0e5,
                        6.0e8, 1)
        tag += 1  # beam: A = 1.2e4 mm^2, I = 9e8 mm^4
        ops.element("elasticBeamColumn", tag, 10 * floor + 1, 10 * floor + 2, 1.2e4, 2.0e5, 9.0e8, 1)
    w1, w2 = (np.sqrt(value) for value in ops.eigen("-fullGenLapack", 2))
    ops.rayleigh(2 * 0.03 * w1 * w2 / (w1 + w2), 0.0, 2 * 0.03 / (w1 + w2), 0.0)
    bridge = None
    if native:
        material = 100
        for story, wall in enumerate(walls, start=1):
            k1, c1, k2, c2 = opensees_frame.damper_constants(wall)
            ops.uniaxialMaterial("Elastic", material, k1, c1)
            ops.element("zeroLength", 100 + story, 10 * (story - 1) + 1, 10 * story + 1, "-mat", material, "-dir", 1)
            if k2 > 0.0 and c2 > 0.0:
                ops.uniaxialMaterial("Maxwell", material + 1, k2, c2, 1.0, 1.0)
                ops.element("zeroLength", 200 + story, 10 * (story - 1) + 1, 10 * story + 1, "-mat", material + 1,
                            "-dir", 1)
            material += 2
    else:
        bridge = WallBridge(ops, dt, method=method)
        for story, wall in enumerate(walls, start=1):
            assert bridge.add_wall(10 * (story - 1) + 1, 10 * story + 1, 1, wall) == story - 1
    values = list(acceleration)
    ops.timeSeries("Path", 1, "-dt", dt, "-values", *values, values[-1])
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
    newmark_newton(ops)
    ops.analysis("Transient")
    nodes = [10 * floor + 1 for floor in range(1, FRAME_STORIES + 1)]
    displacement = np.zeros((len(values), len(nodes)))
    for n in range(1, len(values)):
        status = bridge.analyze(1) if bridge is not None else ops.analyze(1, dt)
        assert status == 0
        displacement[n] = [ops.nodeDisp(node, 1) for node in nodes]
    ops.wipe()
    return displacement, bridge


@pytest.mark.records
def test_2d_frame_kelvin_walls_equal_opensees_elastic_with_eta(ops, record):
    # r = 1 Kelvin walls (G2 = 0) with the trapezoidal rule: D^1 discretised as Newmark's own velocity
    # (v_{n+1} = 2 (u_{n+1} - u_n) / dt - v_n from rest), so the bridge and OpenSees's Elastic(k1, eta = c1)
    # solve the same equations: equal to the Newton tolerance.
    walls = [FDMKDamper(G1=0.8, G2=0.0, eta1=0.08, eta2=0.0, r=1.0, area=a, thickness=10.0)
             for a in (3.0e5, 2.5e5, 2.0e5)]
    acceleration = record.acceleration[:800]
    native, _ = frame_2d(ops, walls, record.dt, acceleration, native=True)
    bridged, bridge = frame_2d(ops, walls, record.dt, acceleration, method="trapezoidal")
    assert history_deviation(bridged, native) < 1e-9  # measured 1e-15
    assert np.abs(bridge.deformation[:, 0] - bridged[:, 0]).max() < 1e-9 * np.abs(bridged).max()


@pytest.mark.records
def test_2d_frame_r1_walls_match_opensees_elastic_plus_maxwell(ops, record):
    walls = [dataclasses.replace(CLASSICAL_WALL_A, area=a) for a in (3.0e5, 2.5e5, 2.0e5)]
    acceleration = record.acceleration[:800]
    native, _ = frame_2d(ops, walls, record.dt, acceleration, native=True)
    bridged, _ = frame_2d(ops, walls, record.dt, acceleration)
    # The default discretisation against OpenSees's exponential Maxwell integrator: measured 0.26 %.
    assert peak_deviation(np.diff(bridged, axis=1, prepend=0.0), np.diff(native, axis=1, prepend=0.0)) < 0.01
    bare, _ = frame_2d(ops, [], record.dt, acceleration, native=True)
    assert (np.abs(native).max(axis=0) < 0.8 * np.abs(bare).max(axis=0)).all()  # the walls matter


# ---------------------------------------------------------------------------------------------- failures
@pytest.mark.records
def test_a_failed_step_is_retried_with_the_fallback_and_the_run_continues(ops, record):
    # Initial-stiffness iterations (6 at most) cannot follow yielding; Newton can.  Without a fallback the
    # run stops at the first yielding step; with Newton as fallback it completes and equals simulate.
    building = fractional_ten_story([Bilinear(3.0e6 * (1.0 - 0.06 * s), 0.05) for s in range(10)])
    expected = quiet_simulate(building, record, newton=TIGHT)
    steps = record.acceleration.size - 1
    outcomes = {}
    for fallback in ((), ("KrylovNewton", "Newton")):
        options = {"fallback_algorithms": fallback, "algorithm": ("ModifiedNewton", "-initial")} if fallback else {}
        floors, bridge = opensees_frame.build_bridged(building, record.dt, options, max_iterations=6,
                                                      algorithm=("ModifiedNewton", "-initial"))
        opensees_frame._ground(record.acceleration, record.dt, floors)
        status = bridge.analyze(steps)
        outcomes[fallback] = (status, bridge, ops.getTime())
        ops.wipe()
    status, bridge, time = outcomes[()]
    assert status < 0 and bridge.failed_step is not None
    assert bridge.steps == bridge.failed_step - 1 and bridge.force.shape == (bridge.failed_step, 20)
    assert time == pytest.approx(bridge.steps * record.dt)  # OpenSees reverted the failed step
    scale = np.abs(expected.wall_force).max()
    assert np.abs(bridge.force - expected.wall_force[:bridge.failed_step]).max() < 1e-9 * scale
    status, bridge, _ = outcomes[("KrylovNewton", "Newton")]
    assert status == 0 and bridge.failed_step is None and bridge.steps == steps
    assert outcomes[()][1].failed_step in bridge.fallback_steps and len(bridge.fallback_steps) > 10
    drift = bridge.deformation[:, ::2]  # story k's first wall is wall 2 (k - 1)
    assert peak_deviation(drift, expected.drift) < 1e-9


@pytest.mark.records
def test_the_run_can_continue_after_a_failure(ops, record):
    # A failed analyze() leaves bridge and domain at the last converged step; loosening the test lets the
    # same bridge carry on, and the result is the uninterrupted one.
    building = fractional_ten_story([Bilinear(3.0e6 * (1.0 - 0.06 * s), 0.05) for s in range(10)])
    floors, bridge = opensees_frame.build_bridged(building, record.dt, max_iterations=6,
                                                  algorithm=("ModifiedNewton", "-initial"))
    opensees_frame._ground(record.acceleration, record.dt, floors)
    steps = record.acceleration.size - 1
    assert bridge.analyze(steps) < 0
    ops.algorithm("Newton")
    assert bridge.analyze(steps - bridge.steps) == 0 and bridge.failed_step is None
    ops.wipe()
    expected = quiet_simulate(building, record, newton=TIGHT)
    assert np.abs(bridge.force - expected.wall_force).max() < 1e-9 * np.abs(expected.wall_force).max()


@pytest.mark.parametrize("integrator, message", [
    (("HHT", 0.9), "applied at t = 0.018"),  # gamma = 0.6, beta = 0.3025, loads at t_n + 0.9 dt
    (("HHT", 0.9, 0.5, 0.25), "applied at t = 0.018"),  # Newmark's kinematics, HHT's equilibrium
    (("GeneralizedAlpha", 1.0, 0.8), "applied at t = 0.016"),
    (("Newmark", 0.5, 1.0 / 6.0), "beta = 0.166667"),  # linear acceleration
    (("Newmark", 0.6, 0.3025), "gamma = 0.6"),
    (("TRBDF2",), "not gamma = 1/2, beta = 1/4"),  # its second step is BDF2
    (("LoadControl", 0.1), "not by dt"),  # a static analysis
])
@pytest.mark.records
def test_other_integrators_are_refused(ops, record, integrator, message):
    floors, bridge = opensees_frame.build_bridged(fractional_ten_story(), record.dt)
    if integrator[0] == "LoadControl":
        ops.timeSeries("Linear", 1)
        ops.pattern("Plain", 1, 1)
        ops.load(floors[-1], 1.0e5)
        ops.integrator(*integrator)
        ops.analysis("Static")
    else:
        opensees_frame._ground(record.acceleration, record.dt, floors)
        ops.integrator(*integrator)
    with pytest.raises(ValueError, match="Newmark's average acceleration") as refused:
        bridge.analyze(50)
    assert message in str(refused.value)
    assert bridge.steps <= 1
    with pytest.raises(ValueError, match="Newmark"):  # and it stays refused
        bridge.analyze(1)
    ops.wipe()


@pytest.mark.records
def test_newmark_average_acceleration_alone_is_accepted(ops, record):
    # The same set-up with Newmark(1/2, 1/4), and with HHT(alpha = 1), which is that integrator.
    for integrator in (("Newmark", 0.5, 0.25), ("HHT", 1.0)):
        floors, bridge = opensees_frame.build_bridged(fractional_ten_story(), record.dt)
        opensees_frame._ground(record.acceleration, record.dt, floors)
        ops.integrator(*integrator)
        assert bridge.analyze(50) == 0 and bridge._identified
        ops.wipe()


@pytest.mark.records
def test_stepping_outside_the_bridge_is_refused(ops, record):
    building = fractional_ten_story()
    floors = opensees_frame.build_bare(building)
    bridge = WallBridge(ops, record.dt)
    bridge.add_wall(0, 1, 1, FRACTIONAL_WALL_A)
    opensees_frame._ground(record.acceleration, record.dt, floors)
    assert bridge.analyze(10) == 0
    ops.analyze(1, record.dt)
    with pytest.raises(ValueError, match=r"only through bridge\.analyze"):
        bridge.analyze(1)
    ops.wipe()


# ---------------------------------------------------------------------------------------------- tags, inputs
def test_tags_never_collide_with_the_models(ops):
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    for node in (1, 2, 3):
        ops.node(node, 0.0)
    ops.fix(1, 1)
    for tag in (1, 100, 101, 102, 250):  # materials the bridge cannot list, in its default range too
        ops.uniaxialMaterial("Elastic", tag, 1.0e3)
    ops.element("zeroLength", 42, 1, 2, "-mat", 1, "-dir", 1)
    bridge = WallBridge(ops, 0.01)
    bridge.add_wall(1, 2, 1, FRACTIONAL_WALL_A)
    bridge.add_wall(2, 3, 1, FRACTIONAL_WALL_B)
    assert min(bridge.tags["element"]) >= 100  # above every node, element, parameter, pattern tag
    assert not {100, 101, 102, 250} & set(bridge.tags["material"])  # taken material tags skipped
    assert len(set(bridge.tags["material"])) == 4 and len(bridge.element_tags) == 2
    assert set(ops.getEleTags()) == {42, *bridge.element_tags}
    explicit = WallBridge(ops, 0.01, tags=100)
    with pytest.raises(ValueError, match="tag 100"):
        explicit.add_wall(1, 2, 1, FRACTIONAL_WALL_A)
    ops.wipe()


def test_bad_nodes_dofs_walls_steps_algorithms_and_memories_are_refused(ops):
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 3000.0)
    ops.fix(1, 1, 1, 1)
    bridge = WallBridge(ops, 0.01)
    with pytest.raises(ValueError, match="node_j"):
        bridge.add_wall(1, 7, 1, FRACTIONAL_WALL_A)
    with pytest.raises(ValueError, match="node_i"):
        bridge.add_wall(True, 2, 1, FRACTIONAL_WALL_A)
    with pytest.raises(ValueError, match="two different nodes"):
        bridge.add_wall(2, 2, 1, FRACTIONAL_WALL_A)
    with pytest.raises(ValueError, match="dof 4"):
        bridge.add_wall(1, 2, 4, FRACTIONAL_WALL_A)
    with pytest.raises(ValueError, match="dof"):
        bridge.add_wall(1, 2, 0, FRACTIONAL_WALL_A)
    with pytest.raises(ValueError, match="FDMKDamper or a SupportedDamper"):
        bridge.add_wall(1, 2, 1, "wall")
    with pytest.raises(ValueError, match="fixed parameters only: no strain-dependent"):
        bridge.add_wall(1, 2, 1, strain_dependent())
    with pytest.raises(ValueError, match="fixed parameters only"):
        limited = FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5, limits=WallLimits(strain=8.5))
        bridge.add_wall(1, 2, 1, SupportedDamper(limited, 1e5))
    with pytest.raises(ValueError, match="add at least one wall"):
        bridge.analyze(1)
    with pytest.raises(ValueError, match="dt"):
        WallBridge(ops, 0.0)
    with pytest.raises(ValueError, match="name the analysis's own algorithm"):
        WallBridge(ops, 0.01, fallback_algorithms=("Newton",))
    with pytest.raises(ValueError, match="fallback_algorithms"):
        WallBridge(ops, 0.01, fallback_algorithms=(3,), algorithm="Newton")
    with pytest.raises(ValueError, match="memory"):
        WallBridge(ops, 0.01, memory="approximate")
    with pytest.raises(ValueError, match=r"openseespy\.opensees module"):
        WallBridge(np, 0.01)
    assert bridge.add_wall(1, 2, 3, FRACTIONAL_WALL_A) == 0  # the rotation of an ndm 2, ndf 3 node: zeroLength dir 6
    assert bridge.force.shape == (1, 1) and bridge.steps == 0
    ops.wipe()


def _opensees_module_error(setup: str) -> str:
    """What ``opensees_module()`` says, as an ImportError, in a fresh interpreter where ``setup`` (Python
    lines) has broken the import of OpenSeesPy."""
    program = (setup + "import vdw_frames.interop.opensees as bridge\n"
               "try:\n"
               "    bridge.opensees_module()\n"
               "except ImportError as error:\n"
               "    print(error)\n")
    return subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, check=True).stdout


def test_vdw_frames_opensees_imports_openseespy_lazily_and_says_how_to_install_it():
    said = _opensees_module_error("import sys; sys.modules['openseespy'] = None; sys.modules['openseespy.opensees'] "
                                  "= None\n")
    assert "pip install 'vdw-frames[opensees]'" in said
    assert opensees_module(None) is opensees_frame.opensees()


def test_openseespy_without_its_blas_libraries_is_an_import_error_with_the_fix():
    """OpenSeesPy raises RuntimeError ('Failed to import openseespy on Linux.') when libblas.so.3 is
    missing: it must reach the user as the ImportError naming the packages, not as a traceback."""
    said = _opensees_module_error("import sys\n"
                                  "class Finder:\n"
                                  "    def find_spec(self, name, path=None, target=None):\n"
                                  "        if name.startswith('openseespy'):\n"
                                  "            raise RuntimeError('Failed to import openseespy on Linux.')\n"
                                  "sys.meta_path.insert(0, Finder())\n")
    assert "Failed to import openseespy on Linux." in said
    assert "libblas3 and liblapack3" in said


@pytest.mark.records
def test_the_memory_serves_the_steps_it_was_built_for(ops, record):
    # The exact memory grows (bridge.analyze(1) at a time: 1, 2, 4, ... steps); the fast one is built for
    # FastMemory.max_steps steps and says so beyond.
    floors, bridge = opensees_frame.build_bridged(fractional_ten_story(), record.dt,
                                                  {"memory": FastMemory(max_steps=100)})
    opensees_frame._ground(record.acceleration, record.dt, floors)
    assert bridge.analyze(100) == 0
    with pytest.raises(ValueError, match="FastMemory"):
        bridge.analyze(1)
    ops.wipe()


def test_a_wall_above_its_identified_strains_is_said_once_as_simulate_says_it(ops):
    # The 450 % set was identified for 375-450 %: a one-story frame whose wall reaches about 2260 % is an
    # extrapolation, which simulate warns about; the bridge said nothing.  It now says so once, whether the
    # analysis runs in one call or step by step.
    from vdw_frames import G, GroundMotion, ShearBuilding
    from vdw_frames.element.catalogue import fitted

    building = ShearBuilding([300.0], [2e4], devices={1: [fitted(450, area=2e3, thickness=10.0)]})
    t = np.arange(0.0, 4.0, 0.01)
    motion = GroundMotion(0.5 * G * np.sin(2.0 * np.pi * t) * np.minimum(t, 1.0), 0.01, "sine")
    with pytest.warns(UserWarning, match="peak strain outside the range") as said:
        expected = simulate(building, motion)
    peak = float(np.abs(expected.wall_strain).max())
    assert 4.5 < peak < 100.0 and len(said) == 1
    for calls in (1, t.size - 1):
        floors, bridge = opensees_frame.build_bridged(building, 0.01)
        opensees_frame._ground(motion.acceleration, 0.01, floors)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            for _ in range(calls):
                assert bridge.analyze((t.size - 1) // calls) == 0
        ops.wipe()
        above = [str(w.message) for w in caught if "WallBridge: wall strain above the range" in str(w.message)]
        assert len(above) == 1 and "wall 0 (nodes 0-1)" in above[0] and "(range 375-450 %)" in above[0]
        assert bridge.peak_strain[0] == pytest.approx(peak, rel=1e-9)
