"""FDMK walls inside any OpenSeesPy model, exactly (:class:`WallBridge`), the Prony material
(:func:`prony_material`), an approximation for OpenSees scripts that cannot host the bridge, and the other
device kinds as OpenSees's own materials (:func:`device_material`, :func:`device_element`).

OpenSees has no fractional material and OpenSeesPy cannot run a material written in Python.  The bridge
makes the walls exact anyway, because within one time step a wall's force is affine in its
deformation (:mod:`vdw_frames.element.kernel`):

    F_{n+1} = K_t d_{n+1} + H_n,

with K_t constant over the run and H_n fixed by the wall's committed memory.  Each wall is therefore,
in the OpenSees domain, a ``zeroLength`` element between its two nodes, acting in the wall's degree of
freedom, whose material is ``InitStressMaterial(Elastic(K_t), sig0)``, and per step:

1. before ``ops.analyze(1, dt)``: sig0 = H_n (through ``parameter`` / ``updateParameter``), so that the
   element's force is K_t d + H_n for any trial deformation d, and its tangent K_t is exact: Newton
   converges as it would without walls;
2. after a successful step: the two nodes' displacements give d_{n+1}; all walls commit in one compiled
   call (:meth:`vdw_frames.element.WallBank.commit`), which also evaluates every wall's next H.

The result equals :func:`vdw_frames.simulate` on a shear building to the solver's tolerance (the tests:
1e-9 relative in peak drifts, linear and Steel01 stories).

OpenSees semantics relied on (OpenSees/OpenSees, SRC/; OpenSeesPy 3.7):

* ``material/uniaxial/InitStressMaterial.cpp``: stress = stress of the wrapped material at strain +
  epsInit, epsInit solving wrapped(epsInit) = sig0 (for ``Elastic``: sig0 / E, one iteration);
  ``updateParameter`` of its ``sig0`` re-solves it; the tangent is the wrapped material's, E.  Up to
  OpenSees 3.7.1 it prints a warning for sig0 = 0 exactly (its tolerance is |sig0| 1e-12 = 0), so a zero
  history force is sent as 1e-200 N.
* ``element/zeroLength/ZeroLength.cpp``: basic deformation = u_j - u_i along the material's direction
  (global axes without ``-orient``), counted from the nodes' displacements when the element joined the
  domain (``setDomain`` stores them as d0, and the velocities as v0), as the wall's own is.  With
  ``-doRayleigh 0`` (the default, given explicitly) the element takes no Rayleigh damping whatever
  ``rayleigh`` or ``region`` set (Rayleigh on K_t would add a damper the wall does not have: about 4 %
  error), only its material's damping tangent, here 0.  Between nodes that do not coincide (a wall
  from one floor to the next) OpenSees prints "WARNING ZeroLength::setDomain(): Element ... has L= ...,
  which is greater than the tolerance" once; the element still acts along the global direction,
  independent of its length, as the wall should.
* ``analysis/integrator/Newmark.cpp``: ``newStep`` applies the loads at t_{n+1} and equilibrium is
  enforced there, so H_n set before the step is the right one.  ``HHT.cpp`` (and generalized-alpha,
  Wilson-theta, ...) evaluate forces at t_n + alpha dt: H_n is then wrong, so every integrator other
  than Newmark average acceleration is refused.  The bridge identifies it itself on the first steps
  (:meth:`WallBridge.analyze`): the domain time advances by dt; an empty probe load pattern on a
  ``Linear`` time series reports the time the loads were applied at (t_{n+1} under Newmark, t_n + alpha dt
  under HHT); and the Newmark relations v_{n+1} = v_n + dt [(1 - gamma) a_n + gamma a_{n+1}],
  u_{n+1} = u_n + dt v_n + dt^2 [(1/2 - beta) a_n + beta a_{n+1}] at the wall nodes give gamma = 1/2 and
  beta = 1/4, on the first four steps whose accelerations change enough to tell (TRBDF2 alternates
  trapezoidal steps, which are Newmark's, with BDF2 steps).
* ``analysis/analysis/DirectIntegrationAnalysis.cpp``: a failed ``analyze`` reverts the domain to the
  last committed step; the walls then have not committed either, and the step is retried at the same dt
  with the fallback algorithms (never sub-stepped: the walls' memory is built for one dt).

Requirements (checked where possible): Newmark's average acceleration (gamma = 1/2, beta = 1/4); a
transient analysis stepped only through :meth:`WallBridge.analyze` (uniform dt, the bridge's own);
walls added after the model's nodes exist and before the first :meth:`WallBridge.analyze`.

Units: the model's.  The walls' parameters are in N, mm, s (MPa, MPa*s^r, mm^2, mm): the OpenSees
model must use N, mm, s too (and tonne for masses), the package's units.

Other devices (:func:`device_material_arguments`, :func:`device_material`, :func:`device_element`)
--------------------------------------------------------------------------------------------------
Fluid viscous and friction dampers need no bridge: OpenSees has their laws as uniaxial materials.  The
material is built *in story units*: its strain is the story drift d (the element's deformation, between
the floors) and its stress the force the device adds to the story, f F, so that a ``zeroLength`` element
between the two floors carries a device of any ``magnification`` f.  The device itself deforms by f d and
carries F (the element's force / f).  Scaling the parameters does this exactly:

* :class:`~vdw_frames.FluidViscousDamper` with a brace K_b: ``ViscousDamper`` (K, Cd, alpha) =
  (f^2 K_b, f^(1 + alpha) C, alpha).  The device's force obeys the Maxwell law dF/dt = K_b (u' - g_C(F)),
  u = f d, g_C(F) = sgn(F) (|F| / C)^(1/alpha).  The story force G = f F then obeys
  dG/dt = f dF/dt = f^2 K_b (d' - g_C(G / f) / f), and g_C(G / f) / f = sgn(G) (|G| / (f C))^(1/alpha) / f
  = sgn(G) (|G| / (f^(1 + alpha) C))^(1/alpha) = g_(f^(1 + alpha) C)(G): the same law with K = f^2 K_b and
  Cd = f^(1 + alpha) C.  OpenSees's material (SRC/material/uniaxial/ViscousDamper.cpp, Akcelyan and Lignos)
  integrates that law over the step by adaptive Dormand-Prince with the strain rate varying linearly
  from the last committed one (Newmark's average acceleration), its arguments ``K C Alpha <LGap> <NM RelTol
  AbsTol MaxHalf>`` (defaults: no gap, Dormand-Prince, RelTol 1e-6, AbsTol 1e-10, MaxHalf 15), only the
  first three given.  Its tangent is 0 (``getTangent``): Newton then iterates on the rest of the stiffness,
  converging where the brace is soft against 4 M / dt^2.  The package's own stepping (the implicit
  trapezoid, :mod:`vdw_frames.element.viscous`) differs from it at O(dt^2).
* a pure linear dashpot (no brace, alpha = 1): ``Viscous`` (C, alpha) = (f^2 C, 1) (ViscousMaterial.cpp:
  stress = C |rate|^alpha sgn(rate), damping tangent C at alpha = 1): F = C f d', G = f^2 C d'.
* :class:`~vdw_frames.FrictionDamper`: ``ElasticPP`` (E, epsyP) = (f^2 k, F_s / (f k)) (epsyN = -epsyP, by
  default).  The device is elastic, F = k f d, until |F| = F_s; the story force G = f F = f^2 k d until
  |G| = f F_s, at d = f F_s / (f^2 k) = F_s / (f k).  ElasticPP (ElasticPPMaterial.cpp) is that law by its
  return mapping, trial stress E (strain - committed plastic strain) held at +-E epsyP, the tangent E or
  0: the package's own rule (:func:`vdw_frames.element.friction.friction_trial`), exact for any step.
  ``Steel01`` with b = 0 is the same law reached through its kinematic-hardening bookkeeping (and
  optional isotropic parameters); ElasticPP states it with the device's two parameters and nothing to
  set to zero, so it is the one used.

Both sides step with Newmark's average acceleration: a friction frame equals :func:`vdw_frames.simulate`
to the Newton tolerance, an FVD frame to the two integrators' O(dt^2) difference
(tests/interop/test_devices_opensees.py).  The walls go through :class:`WallBridge` (or
:func:`prony_material`); :func:`device_material` refuses them.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, NoReturn

import numpy as np
from numpy.typing import NDArray

from .. import _warnings
from .._validation import positive, whole_number
from ..element.bank import DEFAULT_MEMORY, WallBank, kernel_constants, memory_strategy
from ..element.fast_memory import FastMemory
from ..element.fractional import DEFAULT_METHOD, Discretisation, get_method
from ..element.friction import FrictionDamper
from ..element.prony import PronySeries
from ..element.viscous import FluidViscousDamper

if TYPE_CHECKING:
    from ..element.device import Device
    from ..element.wall import Wall

__all__ = ["WallBridge", "device_element", "device_material", "device_material_arguments", "opensees_module",
           "prony_material"]

# A zero history force sent as this (N): OpenSees <= 3.7.1 warns on sig0 = 0 (see the module docstring).
_QUIET_ZERO = 1e-200
# Identification of the integrator from the Newmark relations (see WallBridge._identify).
_PARAMETER_TOLERANCE = 1e-6
_IDENTIFIABLE = 1e-3
_IDENTIFYING_STEPS = 4  # TRBDF2 alternates trapezoidal (= Newmark average acceleration) and BDF2 steps
_COMMANDS = ("analyze", "algorithm", "element", "uniaxialMaterial", "parameter", "updateParameter", "nodeDisp",
             "nodeVel", "nodeAccel", "getTime", "getNodeTags", "getEleTags", "getParamTags", "getPatterns",
             "getNDM", "getNDF", "timeSeries", "pattern", "getLoadFactor", "remove")


def opensees_module(ops: Any = None) -> Any:
    """The OpenSeesPy module to drive: ``ops`` itself (checked), or ``openseespy.opensees`` imported now.

    ImportError with the way to install it when OpenSeesPy is missing; ValueError when ``ops`` lacks
    the commands the bridge needs.
    """
    if ops is None:
        try:
            from openseespy import opensees
        except (ImportError, RuntimeError) as error:  # RuntimeError: OpenSeesPy without its BLAS/LAPACK libraries
            raise ImportError(f"vdw_frames.interop.opensees needs OpenSeesPy ({error}): pip install "
                              "'vdw-frames[opensees]' (on Debian/Ubuntu it also needs the libblas3 and liblapack3 "
                              "packages)") from error
        ops = opensees
    missing = [name for name in _COMMANDS if not callable(getattr(ops, name, None))]
    if missing:
        raise ValueError(f"ops must be the openseespy.opensees module (OpenSeesPy >= 3.5); "
                         f"{type(ops).__name__} lacks {', '.join(missing)}")
    return ops


def _algorithm(spec: str | Sequence[Any], name: str) -> tuple[Any, ...]:
    """An ``ops.algorithm`` call's arguments from a name or a sequence of arguments."""
    if isinstance(spec, str):
        spec = (spec,)
    if not isinstance(spec, (tuple, list)) or not spec or not isinstance(spec[0], str):
        raise ValueError(f"{name} must be an algorithm name or a tuple of ops.algorithm arguments, got {spec!r}")
    return tuple(spec)


def _direction(ndm: int, ndf: int, dof: int) -> int:
    """The zeroLength direction (1-6) acting on node dof ``dof`` (ZeroLength.cpp ``setTran1d``)."""
    if ndm == 2 and ndf == 3 and dof == 3:
        return 6  # the in-plane rotation is the rotation about z
    if (ndm, ndf) in ((1, 1), (2, 2), (2, 3), (3, 3), (3, 6)) and dof <= ndf:
        return dof
    raise ValueError(f"dof {dof} is no translation or rotation of a node with ndm = {ndm}, ndf = {ndf}")


class WallBridge:
    """FDMK walls in an OpenSeesPy model, stepped exactly with it (see :mod:`vdw_frames.interop.opensees`).

    ``ops``: the ``openseespy.opensees`` module the model lives in (None: imported here).  ``dt`` (s): the
    analysis step (every step is ``ops.analyze(1, dt)``).  ``method``, ``memory``: the walls'
    discretisation and memory, as for :func:`vdw_frames.simulate` (``"fast"`` here always uses the modes,
    since the length of the run is not known in advance: within 1e-10 of ``"exact"`` in peak drifts;
    ``"exact"`` keeps the whole history and grows as needed).

    ``fallback_algorithms``: algorithms tried in turn, at the same dt, when a step fails (names, e.g.
    ``("KrylovNewton", "NewtonLineSearch")``, or tuples of ``ops.algorithm`` arguments); then
    ``algorithm``, the analysis's own algorithm (required with fallbacks), is set again.

    ``tags``: the first tag of the bridge's objects (per wall an ``Elastic`` and an ``InitStressMaterial``
    material, a ``zeroLength`` element and a parameter; once a ``Linear`` time series and an empty
    ``Plain`` load pattern, the integrator probe, removed once the integrator is identified); they take
    consecutive numbers from there.  None
    (default): from the first power of ten above every node, element, parameter and pattern tag in
    the domain, skipping numbers OpenSees refuses (it cannot list material and time-series tags).
    ``bridge.tags`` lists what was created.

    Use::

        bridge = WallBridge(ops, dt)                       # after the model (and any gravity analysis)
        bridge.add_wall(node_i, node_j, 1, damper)          # per wall: deformation u_j - u_i in dof 1
        ...                                                 # ground motion pattern, Newmark(0.5, 0.25)
        status = bridge.analyze(steps)                      # 0 on success, like ops.analyze
        bridge.force, bridge.deformation, bridge.strain     # (steps + 1, walls): N, mm, -

    Results (rows: the start, then every completed step): ``force`` (N), ``deformation`` (mm), ``strain`` (-,
    the wall's own deformation / thickness), ``time`` (s); ``steps`` completed, ``failed_step`` (None, or
    the step the last :meth:`analyze` stopped at), ``fallback_steps`` (the steps a fallback rescued).
    A wall whose strain goes above the range its parameters were identified for (``strain_range``) is said
    once, in a ``UserWarning`` at the end of the :meth:`analyze` call where it first did (as
    :func:`~vdw_frames.simulate` warns); one that stays below its range is not (compare ``peak_strain``).

    Requirements: Newmark's average acceleration (gamma = 1/2, beta = 1/4: any other integrator is refused
    with a ValueError on the first steps that identify it), a transient analysis, a uniform dt (the
    bridge's), and no ``ops.analyze`` outside the bridge once it has started.  The wall elements show the
    walls' full force (``eleResponse(tag, "force")``, element recorders on ``bridge.element_tags``).
    """

    def __init__(self, ops: Any, dt: float, method: str | Discretisation = DEFAULT_METHOD,
                 memory: str | FastMemory = DEFAULT_MEMORY, *, fallback_algorithms: str | Sequence[Any] = (),
                 algorithm: str | Sequence[Any] | None = None, tags: int | None = None) -> None:
        self.ops = opensees_module(ops)
        self.dt = positive("dt", dt)
        self.method = get_method(method)
        self._strategy = memory_strategy(memory)
        self.memory = memory
        if isinstance(fallback_algorithms, str):
            fallback_algorithms = (fallback_algorithms,)
        self.fallback_algorithms = tuple(_algorithm(spec, "fallback_algorithms") for spec in fallback_algorithms)
        self.algorithm = None if algorithm is None else _algorithm(algorithm, "algorithm")
        if self.fallback_algorithms and self.algorithm is None:
            raise ValueError("with fallback_algorithms, name the analysis's own algorithm (algorithm='Newton', say): "
                             "the bridge sets it again after a step that needed a fallback")
        self._explicit_tags = tags is not None
        self._next_tag = None if tags is None else whole_number("tags", tags, 1)
        self.tags: dict[str, list[int]] = {"material": [], "element": [], "parameter": [], "time_series": [],
                                           "pattern": []}
        self._walls: list[tuple[int, int, int, Wall]] = []  # (node_i, node_j, dof, damper)
        self._tangent: list[float] = []  # K_t of every wall's element, N/mm
        self._reference: list[float] = []  # u_j - u_i when the wall was added, mm
        self.bank: WallBank | None = None
        self.failed_step: int | None = None
        self.fallback_steps: list[int] = []
        self._rows: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
        self._time: float | None = None  # the domain time after the last committed step, s
        self._refused: str | None = None
        self._identified = False
        self._identifying_steps = 0
        self._probe: int | None = None
        self._warned_above: set[int] = set()  # walls already said to be above their identified strains

    # ------------------------------------------------------------------ set-up
    def __len__(self) -> int:
        return len(self._walls)

    @property
    def walls(self) -> tuple[tuple[int, int, int, Wall], ...]:
        """(node_i, node_j, dof, damper) of every wall, in order."""
        return tuple(self._walls)

    @property
    def element_tags(self) -> list[int]:
        """The walls' zeroLength element tags, in wall order (for recorders)."""
        return list(self.tags["element"])

    def _claim(self, kind: str, create: Callable[[int], object]) -> int:
        """Create an OpenSees object with the next free tag: ``create(tag)``; returns the tag.

        Element, parameter and pattern tags in use are skipped (OpenSees lists them); material and time
        series tags cannot be listed, so a number OpenSees refuses is skipped, in the default range only.
        """
        ops = self.ops
        if self._next_tag is None:
            existing = [max(list(tags), default=0) for tags in (ops.getNodeTags(), ops.getEleTags(),
                                                                 ops.getParamTags(), ops.getPatterns())]
            self._next_tag = 10 ** (len(str(max(existing))))
        listed = {"element": ops.getEleTags, "parameter": ops.getParamTags, "pattern": ops.getPatterns}.get(kind)
        taken = set(listed()) if listed is not None else set()
        for _ in range(100):
            tag = self._next_tag
            self._next_tag += 1
            if tag in taken:
                if self._explicit_tags:
                    raise ValueError(f"{kind} tag {tag} is taken: the bridge numbers its objects consecutively from "
                                     f"tags = {self.tags_start}; choose a free range")
                continue
            try:
                create(tag)
            except Exception as error:  # OpenSeesError: the tag is taken
                if self._explicit_tags or listed is not None:
                    raise ValueError(f"OpenSees refused {kind} tag {tag} ({error}): is it taken? The bridge numbers "
                                     f"its objects consecutively from tags = {self.tags_start}; choose a free "
                                     "range") from error
                continue
            self.tags[kind].append(tag)
            return tag
        raise ValueError(f"no free {kind} tag found below {self._next_tag}; pass tags= the start of a free range")

    @property
    def tags_start(self) -> int | None:
        """The first tag of the bridge's objects (None before the first)."""
        created = [tag for tags in self.tags.values() for tag in tags]
        return min(created, default=self._next_tag)

    def add_wall(self, node_i: int, node_j: int, dof: int, damper: Wall) -> int:
        """Add a wall between existing nodes ``node_i`` and ``node_j``; returns its index.

        The wall's deformation is u_j - u_i (mm) in node degree of freedom ``dof`` (1-based, a translation
        or rotation of the nodes), counted from the nodes' displacements now: a wall added after a
        gravity analysis carries no gravity force, as one installed after the dead load.  ``damper``: an
        :class:`~vdw_frames.FDMKDamper` or :class:`~vdw_frames.SupportedDamper` (a wall with its support
        in series).  Before the first :meth:`analyze` only.
        """
        if self.bank is not None:
            raise ValueError("add every wall before the first analyze(): the walls are stepped together")
        kernel_constants(damper)  # refuses anything that is not a wall assembly
        if damper.follows_amplitude or damper.thermal is not None or damper.limits is not None:
            raise ValueError("the bridge holds each wall's tangent K_t in an OpenSees Elastic material for the whole "
                             "analysis, so it takes walls of fixed parameters only: no strain-dependent "
                             "(amplitude-following), heating (thermal=...) or failing (limits=...) walls; run such "
                             "walls with vdw_frames.simulate, or give the bridge wall.at(strain) at one amplitude")
        ops = self.ops
        nodes = set(ops.getNodeTags())
        for name, node in (("node_i", node_i), ("node_j", node_j)):
            if isinstance(node, bool) or not isinstance(node, (int, np.integer)) or int(node) not in nodes:
                raise ValueError(f"{name} must be the tag of an existing node, got {node!r}")
        node_i, node_j = int(node_i), int(node_j)
        if node_i == node_j:
            raise ValueError(f"a wall needs two different nodes, got node_i = node_j = {node_i}")
        dof = whole_number("dof", dof, 1)
        ndm = int(_first(ops.getNDM(node_j)))
        ndf_i, ndf_j = int(_first(ops.getNDF(node_i))), int(_first(ops.getNDF(node_j)))
        if ndf_i != ndf_j:
            raise ValueError(f"nodes {node_i} and {node_j} have different numbers of dofs ({ndf_i}, {ndf_j})")
        direction = _direction(ndm, ndf_j, dof)
        # K_t exactly as the bank will have it: the same kernel call on the same first weight.
        tangent = float(WallBank((damper,), self.dt, 1, self.method, "exact").tangent[0])
        reference = ops.nodeDisp(node_j, dof) - ops.nodeDisp(node_i, dof)
        elastic = self._claim("material", lambda tag: ops.uniaxialMaterial("Elastic", tag, tangent))
        stressed = self._claim("material", lambda tag: ops.uniaxialMaterial("InitStressMaterial", tag, elastic,
                                                                            _QUIET_ZERO))
        element = self._claim("element", lambda tag: ops.element("zeroLength", tag, node_i, node_j, "-mat", stressed,
                                                                 "-dir", direction, "-doRayleigh", 0))
        self._claim("parameter", lambda tag: ops.parameter(tag, "element", element, "sig0"))
        self._walls.append((node_i, node_j, dof, damper))
        self._tangent.append(tangent)
        self._reference.append(reference)
        return len(self._walls) - 1

    # ------------------------------------------------------------------ results
    def _stacked(self, column: int) -> np.ndarray:
        if not self._rows:
            return np.zeros((1, len(self._walls)))
        return np.vstack([np.zeros((1, len(self._walls)))] + [rows[column] for rows in self._rows])

    @property
    def steps(self) -> int:
        """Completed (committed) steps."""
        return 0 if self.bank is None else self.bank.count

    @property
    def time(self) -> np.ndarray:
        """Domain time (s) of every row of the results: the start, then every completed step."""
        start = self._time - self.steps * self.dt if self._time is not None else 0.0
        return start + self.dt * np.arange(self.steps + 1)

    @property
    def force(self) -> np.ndarray:
        """Wall forces, N: (completed steps + 1, walls), row 0 the start (0)."""
        return self._stacked(0)

    @property
    def deformation(self) -> np.ndarray:
        """Wall deformations u_j - u_i from where the walls were added, mm: (completed steps + 1, walls)."""
        return self._stacked(1)

    @property
    def strain(self) -> np.ndarray:
        """Wall strains (the wall's own deformation / thickness, -): (completed steps + 1, walls)."""
        return self._stacked(2)

    @property
    def peak_strain(self) -> np.ndarray:
        """max |strain| of every wall (-)."""
        return np.abs(self.strain).max(axis=0)

    # ------------------------------------------------------------------ analysis
    def _start(self, steps: int) -> None:
        """The bank, the node index, the integrator probe: at the first analyze()."""
        ops = self.ops
        if not self._walls:
            raise ValueError("add at least one wall (add_wall) before analyze()")
        capacity = 0 if self._strategy is not None else max(steps, 1)
        bank = WallBank(tuple(wall for *_, wall in self._walls), self.dt, capacity, self.method, self.memory)
        if not np.array_equal(bank.tangent, self._tangent):
            raise RuntimeError("internal error: the walls' elements and memory disagree on K_t")
        self.bank = bank
        keys = list(dict.fromkeys(key for node_i, node_j, dof, _ in self._walls
                                  for key in ((node_i, dof), (node_j, dof))))
        self._node_dofs = keys
        self._index_i = np.array([keys.index((node_i, dof)) for node_i, _, dof, _ in self._walls])
        self._index_j = np.array([keys.index((node_j, dof)) for _, node_j, dof, _ in self._walls])
        self._reference_array = np.array(self._reference)
        self._parameters = list(self.tags["parameter"])
        self._time = ops.getTime()
        series = self._claim("time_series", lambda tag: ops.timeSeries("Linear", tag))
        self._probe = self._claim("pattern", lambda tag: ops.pattern("Plain", tag, series))
        self._kinematics = self._read_kinematics()

    def _read_kinematics(self) -> NDArray[np.float64]:
        ops = self.ops
        return np.array([[ops.nodeDisp(n, d), ops.nodeVel(n, d), ops.nodeAccel(n, d)] for n, d in self._node_dofs])

    def _refuse(self, reason: str) -> NoReturn:
        self._refused = (f"WallBridge: {reason}.  The walls' history force is exact only under Newmark's average "
                         "acceleration (ops.integrator('Newmark', 0.5, 0.25)) in a transient analysis stepped by "
                         "the bridge alone; HHT, generalized-alpha and similar integrators evaluate forces at "
                         "t_n + alpha dt and are refused.  Rebuild the analysis and the bridge.")
        raise ValueError(self._refused)

    def _check_time(self) -> float:
        time = self.ops.getTime()
        assert self._time is not None  # set by _start
        expected = self._time + self.dt
        if abs(time - expected) > 1e-9 * self.dt + 4e-16 * abs(expected):
            self._refuse(f"the step moved the domain time from {self._time!r} s to {time!r} s, not by dt = "
                         f"{self.dt!r} s (a static or variable-step analysis?)")
        self._time = time
        return time

    def _identify(self, time: float) -> None:
        """Check, on the first steps, that the step just taken was Newmark average acceleration."""
        ops = self.ops
        if self._probe is not None:
            factor = ops.getLoadFactor(self._probe)
            if abs(factor - time) > 1e-9 * self.dt + 4e-16 * abs(time):
                self._refuse(f"the loads of this step were applied at t = {factor!r} s, not at the step's end "
                             f"t = {time!r} s: an HHT-type integrator")
            ops.remove("loadPattern", self._probe)
            self._probe = None
        before, after = self._kinematics, self._read_kinematics()
        self._kinematics = after
        dt, eps = self.dt, np.finfo(float).eps
        (u0, v0, a0), (u1, v1, a1) = before.T, after.T
        moved = np.abs(u1 - u0) > 1e3 * eps * (np.abs(u0) + np.abs(u1)) + 1e-300
        if np.any(moved) and not (np.any(v1) or np.any(a1)):
            self._refuse("the nodes moved but have no velocity or acceleration: not a transient analysis")
        change = a1 - a0
        with np.errstate(divide="ignore", invalid="ignore"):
            gamma = (v1 - v0 - dt * a0) / (dt * change)
            beta = (u1 - u0 - dt * v0 - 0.5 * dt * dt * a0) / (dt * dt * change)
            gamma_error = (_PARAMETER_TOLERANCE
                           + 100 * eps * (np.abs(v0) + np.abs(v1) + dt * np.abs(a0)) / (dt * np.abs(change)))
            beta_error = _PARAMETER_TOLERANCE + 100 * eps * (np.abs(u0) + np.abs(u1) + dt * np.abs(v0)
                                                             + dt * dt * np.abs(a0)) / (dt * dt * np.abs(change))
        usable = (np.abs(change) > 0) & (gamma_error < _IDENTIFIABLE) & (beta_error < _IDENTIFIABLE)
        if not usable.any():
            return  # no acceleration change yet to tell the integrator by: the next step
        k = int(np.argmax(np.where(usable, np.abs(change), -1.0)))
        if abs(gamma[k] - 0.5) > gamma_error[k] or abs(beta[k] - 0.25) > beta_error[k]:
            node, dof = self._node_dofs[k]
            self._refuse(f"the step satisfies the Newmark relations with gamma = {gamma[k]:.6g}, beta = {beta[k]:.6g} "
                         f"(node {node}, dof {dof}), not gamma = 1/2, beta = 1/4")
        self._identifying_steps += 1
        self._identified = self._identifying_steps >= _IDENTIFYING_STEPS

    def _retry(self) -> int:
        """The failed step again with each fallback algorithm; the analysis's own algorithm set back."""
        ops = self.ops
        assert self.algorithm is not None  # required with fallback algorithms (checked in __init__)
        for spec in self.fallback_algorithms:
            ops.algorithm(*spec)
            status = ops.analyze(1, self.dt)
            if status == 0:
                break
        ops.algorithm(*self.algorithm)
        return status

    def analyze(self, steps: int) -> int:
        """Run ``steps`` steps of ``dt`` (``ops.analyze(1, dt)`` each), the walls updated and committed.

        Returns 0 when every step converged.  A failed step is retried with ``fallback_algorithms`` at
        the same dt; when they fail too the analysis stops there, the walls stay at the last converged
        step, ``failed_step`` records the failed step (1-based, counted from the bridge's first step) and
        the (negative) status is returned.  ValueError when the analysis is not Newmark average
        acceleration (identified on the first steps; see the module docstring).
        """
        steps = whole_number("steps", steps, 0)
        if self._refused is not None:
            raise ValueError(self._refused)
        ops = self.ops
        if self.bank is None:
            self._start(steps)
        else:
            assert self._time is not None  # set by _start, and after every step
            if abs(ops.getTime() - self._time) > 1e-9 * self.dt + 4e-16 * abs(self._time):
                raise ValueError(f"the domain time is {ops.getTime()!r} s, not {self._time!r} s where the bridge left "
                                 "it: step the analysis only through bridge.analyze()")
        bank = self.bank
        assert bank is not None  # _start built it
        bank.reserve(steps)  # an exact memory grows; a fast one refuses steps past its horizon
        self.failed_step = None
        count = len(self._walls)
        forces, deformations, strains = np.zeros((steps, count)), np.zeros((steps, count)), np.zeros((steps, count))
        update, analyze, node_disp = ops.updateParameter, ops.analyze, ops.nodeDisp
        parameters, node_dofs, dt = self._parameters, self._node_dofs, self.dt
        index_i, index_j, reference = self._index_i, self._index_j, self._reference_array
        history = bank.history_force  # updated in place by every commit
        status = 0
        done = 0
        try:
            for step in range(steps):
                # 1. the step's history force: the element's force is K_t d + H_n
                for tag, value in zip(parameters, history.tolist(), strict=True):
                    update(tag, value or _QUIET_ZERO)
                status = analyze(1, dt)
                if status != 0 and self.fallback_algorithms:
                    status = self._retry()
                    if status == 0:
                        self.fallback_steps.append(bank.count + 1)
                if status != 0:
                    self.failed_step = bank.count + 1
                    status = status if status < 0 else -1
                    break
                if not self._identified:
                    self._identify(self._check_time())
                # 2. the converged displacements (read after analyze returned), then all walls commit
                displacement = np.array([node_disp(node, dof) for node, dof in node_dofs])
                deformation = displacement[index_j] - displacement[index_i] - reference
                forces[step], strains[step] = bank.commit(deformation)
                deformations[step] = deformation
                done = step + 1
        finally:
            if done:
                self._rows.append((forces[:done], deformations[:done], strains[:done]))
            self._time = ops.getTime()
        self._warn_above_range(np.abs(strains[:done]).max(axis=0, initial=0.0))
        return status

    def _warn_above_range(self, peak: np.ndarray) -> None:
        """One warning naming the walls whose strain (``peak``, -, of the last call) went above their identified
        range for the first time."""
        above = []
        for index, (node_i, node_j, _, wall) in enumerate(self._walls):
            strain_range = wall.strain_range
            if index in self._warned_above or strain_range is None or not peak[index] > strain_range[1]:
                continue
            self._warned_above.add(index)
            above.append(f"wall {index} (nodes {node_i}-{node_j}): {100 * peak[index]:.0f} % (range "
                         f"{100 * strain_range[0]:.4g}-{100 * strain_range[1]:.4g} %)")
        if above:
            _warnings.warn("WallBridge: wall strain above the range its parameters were identified for (the model "
                           "is extrapolated there): " + "; ".join(above), UserWarning, stacklevel=3)


def _first(value: Any) -> Any:
    """OpenSeesPy returns some scalars as one-element lists."""
    return value[0] if isinstance(value, (list, tuple)) else value


def prony_material(ops: Any, tag: int, prony: PronySeries) -> int:
    """Build ``prony`` as a native OpenSees uniaxial material; returns ``tag``.

    ``uniaxialMaterial Parallel tag`` of ``Elastic`` k_0 (tag + 1; omitted when k_0 = 0) and one ``Maxwell``
    per branch (K = k_i, C = c_i, alpha = 1, L = 1: tau = C / K; the following tags), so it uses tags
    ``tag`` to ``tag + len(prony) + 1``.  Use it in a ``zeroLength`` element between the wall's nodes.

    OpenSees's ``Maxwell`` (SRC/material/uniaxial/Maxwell.cpp) advances each branch by
    stress += stress (e^(-dt/tau) - 1) + K/2 (1 + e^(-dt/tau)) d(strain), second order in dt/tau, with the
    tangent K (not the consistent K (1 + e^(-dt/tau)) / 2: Newton iterates, ``Linear`` is off).  A branch
    with tau << dt acts as a spring K/2 instead of the dashpot it represents: run at dt well below the
    shortest relaxation time (``prony.relaxation_times.min()``), or narrow the band's upper frequency.
    Units: N, mm, s.
    """
    ops = opensees_module(ops)
    if not isinstance(prony, PronySeries):
        raise ValueError(f"prony must be a PronySeries (damper.prony(...)), got {type(prony).__name__}")
    tag = whole_number("tag", tag, 1)
    components = []
    next_tag = tag + 1
    commands: list[tuple[str | float, ...]] = []
    if prony.equilibrium_stiffness > 0.0:
        commands.append(("Elastic", prony.equilibrium_stiffness))
    commands += [("Maxwell", float(k), float(c), 1.0, 1.0) for k, c in prony.branches]
    for command in commands:
        _material(ops, command[0], next_tag, *command[1:])
        components.append(next_tag)
        next_tag += 1
    _material(ops, "Parallel", tag, *components)
    return tag


def _material(ops: Any, kind: str | float, tag: int, *arguments: str | float | int) -> None:
    try:
        ops.uniaxialMaterial(kind, tag, *arguments)
    except Exception as error:  # OpenSeesError
        raise ValueError(f"OpenSees refused uniaxialMaterial {kind} {tag} ({error}): is the tag taken?") from error


def device_material_arguments(device: Device) -> tuple[str | float, ...]:
    """The ``uniaxialMaterial`` type and parameters (without the tag) of ``device`` in story units: strain
    the story drift (mm), stress the force the device adds to the story (N), its magnification f folded
    into the parameters (see the module docstring for the proof):

    * :class:`~vdw_frames.FluidViscousDamper` with a stiffness: ``("ViscousDamper", f^2 K_b, f^(1 + alpha) C,
      alpha)`` (N/mm, N (s/mm)^alpha, -);
    * a pure (linear) dashpot: ``("Viscous", f^2 C, 1.0)`` (N s/mm);
    * :class:`~vdw_frames.FrictionDamper`: ``("ElasticPP", f^2 k, F_s / (f k))`` (N/mm, mm).

    ValueError for anything else (the walls go through :class:`WallBridge`)."""
    if isinstance(device, FluidViscousDamper):
        f, alpha = device.magnification, device.alpha
        if device.stiffness is None:
            return ("Viscous", f * f * device.C, 1.0)
        return ("ViscousDamper", f * f * device.stiffness, f ** (1.0 + alpha) * device.C, alpha)
    if isinstance(device, FrictionDamper):
        f = device.magnification
        return ("ElasticPP", f * f * device.stiffness, device.slip_force / (f * device.stiffness))
    raise ValueError(f"no native OpenSees material for a {device.kind} device ({device!r}): fluid viscous and friction "
                     "dampers only; FDMK walls go through WallBridge (or prony_material)")


def device_material(ops: Any, tag: int, device: Device) -> int:
    """Build ``device`` (a :class:`~vdw_frames.FluidViscousDamper` or :class:`~vdw_frames.FrictionDamper`)
    as the native OpenSees uniaxial material :func:`device_material_arguments` names, with tag ``tag``;
    returns ``tag``.  In story units: use it in a ``zeroLength`` element between the story's two floors
    (:func:`device_element`).  Units: N, mm, s."""
    ops = opensees_module(ops)
    tag = whole_number("tag", tag, 1)
    kind, *parameters = device_material_arguments(device)
    _material(ops, kind, tag, *parameters)
    return tag


def device_element(ops: Any, tag: int, node_i: int, node_j: int, device: Device, dof: int = 1) -> int:
    """``device`` between nodes ``node_i`` and ``node_j``: its material (:func:`device_material`, material tag
    ``tag``) in a ``zeroLength`` element (element tag ``tag``) acting in node degree of freedom ``dof``
    (1-based), deformation u_j - u_i = the story drift (mm), force the force the device adds to the story
    (N: magnification x the device's own).  ``-doRayleigh 0``: the device takes no Rayleigh damping, as in
    :func:`vdw_frames.simulate`.  Returns ``tag``."""
    ops = opensees_module(ops)
    tag = whole_number("tag", tag, 1)
    dof = whole_number("dof", dof, 1)
    nodes = set(ops.getNodeTags())
    for name, node in (("node_i", node_i), ("node_j", node_j)):
        if isinstance(node, bool) or not isinstance(node, (int, np.integer)) or int(node) not in nodes:
            raise ValueError(f"{name} must be the tag of an existing node, got {node!r}")
    if int(node_i) == int(node_j):
        raise ValueError(f"a device needs two different nodes, got node_i = node_j = {int(node_i)}")
    direction = _direction(int(_first(ops.getNDM(int(node_j)))), int(_first(ops.getNDF(int(node_j)))), dof)
    device_material(ops, tag, device)
    try:
        ops.element("zeroLength", tag, int(node_i), int(node_j), "-mat", tag, "-dir", direction, "-doRayleigh", 0)
    except Exception as error:  # OpenSeesError
        raise ValueError(f"OpenSees refused zeroLength element {tag} ({error}): is the tag taken?") from error
    return tag
