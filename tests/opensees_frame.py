"""The shear building of :mod:`vdw_frames` as an OpenSeesPy model (independent cross-check).

Shared by the OpenSees tests (tests/frame/test_against_opensees.py, tests/interop/, ...) and
``examples/benchmark.py``.  Only classical (r = 1) dampers can be translated: OpenSees has no fractional
element.  Units are the package's (N, mm, s, tonne).

The model (ndm = 1, ndf = 1): node 0 (ground, fixed) and nodes 1 .. n (floors, lumped masses), and per
story k, between nodes k-1 and k,

* a ``zeroLength`` frame spring, ``-doRayleigh 1``: ``Elastic`` E = story stiffness for a linear story,
  ``Steel01`` (F_y, E0 = k0, b = hardening) for :class:`vdw_frames.Bilinear`, ``BoucWen`` (alpha = b,
  ko = k0, n, gamma / d_y^n, beta / d_y^n, Ao = 1, no degradation) for :class:`vdw_frames.BoucWen`;
* with gravity loads, a ``zeroLength`` P-Delta spring, ``Elastic`` E = -P/h, no Rayleigh (the
  linearised leaning column);
* per wall, a ``zeroLength`` Kelvin branch: ``Elastic`` E = k1 = G1 A/h, eta = c1 = eta1 A/h (N*s/mm);
* per wall, a ``zeroLength`` Maxwell branch: ``Maxwell`` K = k2 = G2 A/h, C = c2 = eta2 A/h, alpha = 1,
  L = 1 (omitted when G2 = 0 or eta2 = 0, which carries no stress in the FDMK model either);
* per other device (fluid viscous, friction), a ``zeroLength`` element of its native material in story
  units (``ViscousDamper``, ``Viscous`` or ``ElasticPP``, the magnification folded in):
  :func:`vdw_frames.interop.opensees.device_element`, no Rayleigh.

OpenSees semantics this relies on (source: OpenSees/OpenSees, SRC/):

* ``element/zeroLength/ZeroLength.cpp``: strain = displacement difference, strain rate = velocity
  difference, stress = force.  ``getDamp`` returns the Rayleigh matrix of the element (its alphaM, betaK,
  ...) when ``-doRayleigh 1``, otherwise (default 0) the materials' damping tangents (``eta`` of
  ``Elastic``) and never both; the damper elements therefore keep the default 0 and get no Rayleigh term.
* ``material/uniaxial/ElasticMaterial.cpp``: stress = E strain + eta strainRate (tangent E, damping
  tangent eta).
* ``material/uniaxial/Maxwell.cpp``: tau = (C / L^alpha) / K, and per step
  ``stress += stress (exp(-dt/tau) - 1) + K/2 (1 + exp(-dt/tau)) d(strain)``: an exponential
  integrator of stress' + stress/tau = K strain' (alpha only enters tau, the dashpot is always linear).
  Its ``getTangent`` returns K, not the consistent K (1 + exp(-dt/tau))/2, so ``algorithm('Linear')``
  leaves an out-of-balance force every step; the analysis here iterates (Newton) to a tight tolerance.
* ``domain/region/MeshRegion.cpp``: ``region -ele`` also puts the elements' nodes in the region and
  ``region -node`` also every element whose nodes are all in it, and ``-rayleigh`` then sets the factors
  of both (a later region would overwrite an earlier one's betaK or alphaM).  ``-eleOnly`` and
  ``-nodeOnly`` avoid that: Rayleigh is a1 K on the frame springs only and a0 M on the floor nodes.
* ``UniformExcitation`` loads -M 1 a_g and the nodal responses are relative to the ground.  The domain
  starts with zero acceleration; :func:`vdw_frames.simulate` starts from rest in equilibrium with the
  first sample (relative acceleration -a_g(0)), so the floors' initial acceleration is set to match
  (without it the bare frame differs by 4e-4 on El Centro, whose a_g(0) = 0.0063 g).
* ``timeSeries Path`` is 0 after its last point, and N steps of dt can land just past (N - 1) dt: the
  last value is repeated once.

Measured on the El Centro frame of tests/frame/test_against_opensees.py: the bare frame equals vdw_frames to
rounding; Newton takes 4 iterations a step; ``algorithm('Linear')`` is off by about 0.3 % on the
peak drifts at dt = 0.02 s (0.01 % at 0.004 s).
"""

from __future__ import annotations

import os
import tempfile

import numpy as np

_TIME_SERIES = 1
_PATTERN = 1


def opensees():
    """The ``openseespy.opensees`` module (ImportError with a hint when it cannot be loaded)."""
    try:
        import openseespy.opensees as ops
    except ImportError as error:  # the extension needs the system libblas3 / liblapack3
        raise ImportError(
            f"openseespy is needed for the OpenSees cross-check ({error}); install the test extra "
            "(pip install -e '.[test]') and the Debian packages libblas3 liblapack3") from error
    return ops


def damper_constants(wall):
    """(k1, c1, k2, c2) in N/mm and N*s/mm of a classical (r = 1) FDMK wall."""
    if wall.r != 1.0:
        raise ValueError(f"OpenSees has no fractional element: only r = 1 walls translate, got r = {wall.r}")
    scale = wall.area / wall.thickness
    return wall.G1 * scale, wall.eta1 * scale, wall.G2 * scale, wall.eta2 * scale


def imposed_force(ops, material, displacement, dt):
    """Force history (N) of one zeroLength element whose free end follows ``displacement`` (mm).

    ``material``: the ``uniaxialMaterial`` arguments, or a function defining the material that returns its tag.
    """
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(0, 0.0)
    ops.fix(0, 1)
    ops.node(1, 0.0)
    ops.mass(1, 1.0)
    if callable(material):
        tag = material(ops)
    else:
        ops.uniaxialMaterial(*material)
        tag = material[1]
    ops.element("zeroLength", 1, 0, 1, "-mat", tag, "-dir", 1)
    values = list(displacement)
    ops.timeSeries("Path", 1, "-dt", dt, "-values", *values, values[-1])
    ops.pattern("Plain", 1, 1)
    ops.sp(1, 1, 1.0)
    # Penalty, not Transformation: the Transformation handler leaves the velocity of an imposed DOF at
    # zero, which the Elastic material's eta term needs.
    ops.constraints("Penalty", 1e16, 1e16)
    ops.numberer("Plain")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-12, 20)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    force = [0.0]
    for _ in range(len(values) - 1):
        assert ops.analyze(1, dt) == 0
        force.append(ops.eleResponse(1, "basicForce")[0])
    ops.wipe()
    return np.array(force)


def build(building, tolerance=1e-9, max_iterations=50, algorithm="Newton", parallel_walls=False):
    """Build ``building`` (a :class:`vdw_frames.ShearBuilding` with r = 1 walls and any fluid viscous or
    friction dampers) in a fresh OpenSees domain.

    The analysis is transient Newmark (gamma = 1/2, beta = 1/4, average acceleration, as in
    :func:`vdw_frames.simulate`), Newton iterations to a displacement-increment norm of ``tolerance`` mm
    (needed for the Maxwell material's non-consistent tangent; see the module docstring);
    ``algorithm="Linear"`` takes one solve a step instead (faster, not converged with Maxwell walls); a
    tuple gives ``ops.algorithm`` arguments.
    ``parallel_walls=True`` models each story's walls as one ``Parallel(Elastic, Maxwell)`` material with
    the summed constants (fewer elements: how one would set OpenSees up for speed).  The ground
    motion is added by :func:`run` / :func:`run_recorded`.  Returns the floor node tags.
    """
    ops = opensees()
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    floors = list(range(1, building.stories + 1))
    ops.node(0, 0.0)
    ops.fix(0, 1)
    for node, mass in zip(floors, building.masses, strict=True):
        ops.node(node, 0.0)
        ops.mass(node, mass)

    tag = 0
    frame_springs = []
    for story, (stiffness, model) in enumerate(zip(building.stiffnesses, building.story_models, strict=True), start=1):
        tag += 1
        story_material(tag, stiffness, model)
        ops.element("zeroLength", tag, story - 1, story, "-mat", tag, "-dir", 1, "-doRayleigh", 1)
        frame_springs.append(tag)
    for story, geometric in enumerate(building.geometric_stiffness, start=1):
        if geometric != 0.0:
            tag += 1
            ops.uniaxialMaterial("Elastic", tag, geometric)
            ops.element("zeroLength", tag, story - 1, story, "-mat", tag, "-dir", 1)
    if parallel_walls:
        for story, walls in building.walls.items():
            k1, c1, k2, c2 = np.sum([damper_constants(wall) for wall in walls], axis=0)
            elastic, maxwell, tag = tag + 1, tag + 2, tag + 3
            ops.uniaxialMaterial("Elastic", elastic, k1, c1)
            ops.uniaxialMaterial("Maxwell", maxwell, k2, c2, 1.0, 1.0)
            ops.uniaxialMaterial("Parallel", tag, elastic, maxwell)
            ops.element("zeroLength", tag, story - 1, story, "-mat", tag, "-dir", 1)
    for story, wall in [] if parallel_walls else building.wall_list:
        k1, c1, k2, c2 = damper_constants(wall)
        tag += 1
        ops.uniaxialMaterial("Elastic", tag, k1, c1)  # E, eta: stress = E strain + eta strain rate
        ops.element("zeroLength", tag, story - 1, story, "-mat", tag, "-dir", 1)
        if k2 > 0.0 and c2 > 0.0:
            tag += 1
            ops.uniaxialMaterial("Maxwell", tag, k2, c2, 1.0, 1.0)  # K, C, alpha, L
            ops.element("zeroLength", tag, story - 1, story, "-mat", tag, "-dir", 1)

    if building.other_device_list:
        from vdw_frames.interop.opensees import device_element

        for story, device in building.other_device_list:
            tag += 1
            device_element(ops, tag, story - 1, story, device)

    a0, a1 = building.rayleigh_coefficients
    # rayleigh(alphaM, betaK, betaKinit, betaKcomm): a1 on the springs' *initial* stiffness, as vdw_frames.
    ops.region(1, "-eleOnly", *frame_springs, "-rayleigh", 0.0, 0.0, a1, 0.0)
    ops.region(2, "-nodeOnly", *floors, "-rayleigh", a0, 0.0, 0.0, 0.0)

    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", tolerance, max_iterations)
    ops.algorithm(*((algorithm,) if isinstance(algorithm, str) else algorithm))
    ops.integrator("Newmark", 0.5, 0.25)
    return floors


def story_material(tag, stiffness, model):
    """The OpenSees uniaxial material of a story spring (see the module docstring)."""
    ops = opensees()
    if model is None:
        ops.uniaxialMaterial("Elastic", tag, stiffness)
    elif type(model).__name__ == "Bilinear":
        ops.uniaxialMaterial("Steel01", tag, model.yield_force, stiffness, model.hardening)
    elif type(model).__name__ == "BoucWen":
        scale = (model.yield_force / stiffness) ** model.exponent  # d_y^n
        # alpha ko n gamma beta Ao deltaA deltaNu deltaEta tolerance maxNumIter
        ops.uniaxialMaterial("BoucWen", tag, model.hardening, stiffness, model.exponent, model.gamma / scale,
                             model.beta / scale, 1.0, 0.0, 0.0, 0.0, 1e-12, 100)
    else:
        raise ValueError(f"no OpenSees material for {model!r}")


def _ground(acceleration, dt, floors):
    ops = opensees()
    values = np.asarray(acceleration, dtype=float).tolist()
    # Repeat the last value: a Path series is 0 beyond its last point (see the module docstring).
    ops.timeSeries("Path", _TIME_SERIES, "-dt", dt, "-values", *values, values[-1])
    ops.pattern("UniformExcitation", _PATTERN, 1, "-accel", _TIME_SERIES)
    # Start from rest in equilibrium, as vdw_frames.simulate does: relative acceleration -a_g(0) (OpenSees
    # would otherwise start from zero acceleration, a small initial-condition difference when a_g(0) != 0).
    for node in floors:
        ops.setNodeAccel(node, 1, -values[0], "-commit")
    ops.analysis("Transient")


def _drifts(displacement):
    return np.diff(np.hstack([np.zeros((displacement.shape[0], 1)), displacement]), axis=1)


def run(building, acceleration, dt, reactions=False, **options):
    """Relative floor displacements (mm, steps x floors) under the ground acceleration (mm/s^2, every dt s).

    Row n is t = n dt (row 0: rest), as in :func:`vdw_frames.simulate`.  Steps one ``analyze(1, dt)`` at
    a time and reads the nodes.  ``reactions=True`` also returns the ground node's reaction (N, steps)
    and the story springs' forces (N, steps x stories).
    """
    floors = build(building, **options)
    _ground(acceleration, dt, floors)
    ops = opensees()
    steps = len(acceleration)
    displacement = np.zeros((steps, len(floors)))
    reaction = np.zeros(steps)
    spring_force = np.zeros((steps, len(floors)))
    for n in range(1, steps):
        if ops.analyze(1, dt) != 0:
            raise RuntimeError(f"OpenSees analysis failed at step {n}")
        displacement[n] = [ops.nodeDisp(node, 1) for node in floors]
        if reactions:
            ops.reactions("-dynamic")
            reaction[n] = ops.nodeReaction(0, 1)
            # zeroLength "basicForce" is the material's force (without Rayleigh); tags 1 .. n are the springs
            spring_force[n] = [ops.eleResponse(story, "basicForce")[0] for story in floors]
    ops.wipe()
    return (displacement, reaction, spring_force) if reactions else displacement


def run_recorded(building, acceleration, dt, **options):
    """As :func:`run` with one ``analyze(N - 1, dt)`` call and a node recorder to a temporary file.

    The way one would time OpenSees: the whole history in one call.
    """
    ops = opensees()
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "disp.out")
        floors = build(building, **options)
        ops.recorder("Node", "-file", path, "-precision", 17, "-node", *floors, "-dof", 1, "disp")
        _ground(acceleration, dt, floors)
        status = ops.analyze(len(acceleration) - 1, dt)
        ops.wipe()  # closes (flushes) the recorder
        if status != 0:
            raise RuntimeError("OpenSees analysis failed")
        recorded = np.loadtxt(path, ndmin=2)
    return np.vstack([np.zeros((1, len(floors))), recorded])


def drifts(displacement):
    """Interstory drifts (mm, steps x stories) from floor displacements."""
    return _drifts(np.asarray(displacement))


# ---------------------------------------------------------------------------------------------- walls bridged
def build_bare(building, tolerance=1e-12, max_iterations=50, algorithm="Newton"):
    """The frame of ``building`` without its walls (:func:`build` of ``building.without_walls()``: its other
    devices as native elements) in a fresh domain, for walls added afterwards.  Returns the floor node tags
    (story k between nodes k-1 and k; node 0 the ground)."""
    return build(building.without_walls(), tolerance, max_iterations, algorithm)


def build_bridged(building, dt, bridge_options=None, **options):
    """The bare frame (:func:`build_bare`, ``options``) with the building's walls through a
    :class:`vdw_frames.opensees.WallBridge` (``bridge_options``: its keyword arguments) on steps of ``dt``
    s: (floor node tags, the bridge)."""
    from vdw_frames.interop.opensees import WallBridge

    floors = build_bare(building, **options)
    bridge = WallBridge(opensees(), dt, **(bridge_options or {}))
    for story, wall in building.wall_list:
        bridge.add_wall(story - 1, story, 1, wall)
    return floors, bridge


def run_bridged(building, acceleration, dt, method="damped", memory="fast", step_by_step=False, **options):
    """``building`` with its walls through :class:`vdw_frames.opensees.WallBridge`: (floor displacements
    (mm, steps x floors), the bridge).  ``options`` go to :func:`build_bare`; ``step_by_step`` reads the
    floors after every ``bridge.analyze(1)`` (otherwise they are the cumulative sum of the walls' drifts,
    which needs a wall on every story)."""
    ops = opensees()
    floors, bridge = build_bridged(building, dt, {"method": method, "memory": memory}, **options)
    _ground(acceleration, dt, floors)
    steps = len(acceleration)
    if step_by_step:
        displacement = np.zeros((steps, len(floors)))
        for n in range(1, steps):
            if bridge.analyze(1) != 0:
                break
            displacement[n] = [ops.nodeDisp(node, 1) for node in floors]
    else:
        bridge.analyze(steps - 1)
        first = {story: index for index, (story, _) in reversed(list(enumerate(building.wall_list)))}
        displacement = np.cumsum(bridge.deformation[:, [first[s] for s in range(1, len(floors) + 1)]], axis=1)
    ops.wipe()
    return displacement, bridge


def build_prony(building, f_min, f_max, prony_tolerance=0.01, **options):
    """The bare frame (:func:`build_bare`, ``options``) with every wall as its Prony series over
    [f_min, f_max] Hz (within ``prony_tolerance``), a native ``Parallel`` of ``Elastic`` and ``Maxwell`` materials
    (:func:`vdw_frames.opensees.prony_material`) in a ``zeroLength`` element: (floor node tags, {wall: series})."""
    from vdw_frames.interop.opensees import prony_material

    ops = opensees()
    floors = build_bare(building, **options)
    series = {}
    tag = 1000
    for index, (story, wall) in enumerate(building.wall_list):
        if wall not in series:
            series[wall] = wall.prony(f_min, f_max, prony_tolerance)
        prony_material(ops, tag, series[wall])
        ops.element("zeroLength", 1000 + index, story - 1, story, "-mat", tag, "-dir", 1)
        tag += len(series[wall]) + 2
    return floors, series


def run_prony(building, acceleration, dt, f_min, f_max, prony_tolerance=0.01, **options):
    """``building`` with every wall as its Prony series (:func:`build_prony`): (floor displacements (mm,
    steps x floors), {wall: series}).  Stepped one ``analyze(1, dt)`` at a time."""
    ops = opensees()
    floors, series = build_prony(building, f_min, f_max, prony_tolerance, **options)
    _ground(acceleration, dt, floors)
    steps = len(acceleration)
    displacement = np.zeros((steps, len(floors)))
    for n in range(1, steps):
        if ops.analyze(1, dt) != 0:
            raise RuntimeError(f"OpenSees analysis failed at step {n}")
        displacement[n] = [ops.nodeDisp(node, 1) for node in floors]
    ops.wipe()
    return displacement, series
