"""The results of a time-history analysis: response histories, energies, outcome; their self-checks.

Units: N, mm, s; energies N*mm.
"""

from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import _warnings
from .._validation import finite_array, positive, require_finite, show, whole_number
from ..element.kernel import FAILURE_MODES
from .archive import read_archive, write_archive
from .building import ShearBuilding

if TYPE_CHECKING:
    from ..element.wall import Wall

# Self-check: Newmark's average acceleration with trapezoidal work increments balances energy to the Newton
# tolerance (1e-13 ... 1e-9 of the input in the tests); a larger gap means the wrong equations were solved.
ENERGY_BALANCE_TOLERANCE = 1e-4
_ARCHIVE = "vdw_frames.SimulationResult/1"  # the format save writes and load reads


@dataclass(frozen=True)
class EnergyHistory:
    """Energy histories, N*mm, relative-motion formulation, trapezoidal work increments.

    ``input`` = -int (1^T M a_g) du; ``kinetic`` = v^T M v / 2; ``frame_strain`` = sum F_s^2 / (2 k0), the
    recoverable elastic energy of the story springs; ``hysteretic`` = int F_s dd - frame_strain, the energy
    the story springs have dissipated by yielding (and, with kinematic hardening, stored in their
    hardening); ``inherent_damping`` = int (C v) . du; ``wall_work`` = int f_w . dd (the walls: stored and
    dissipated); ``p_delta`` = int k_G d dd = -sum P d^2 / (2 h) (<= 0: gravity does work as the frame
    sways).  With Newmark's average acceleration they balance to the iteration tolerance:
    input = kinetic + frame_strain + hysteretic + inherent_damping + wall_work + p_delta.

    When every wall's heat is followed (walls with a thermal description or limits), the walls' work is
    split by their own states: ``wall_heat`` (dissipated since rest: the heat that warms them),
    ``wall_stored`` (in their springs and springpots now), ``wall_released`` (lost when a wall failed: the
    share of its stored energy it lost, and the work on that share over the next step, as its force fell
    to the residual's; :func:`vdw_frames.element.kernel.update_walls`) and ``wall_parameter_loss`` (stored
    energy the walls' states lost as their parameters changed with temperature or amplitude: the
    parameters are coefficients, so a fall of eta or G scales the energy the same state stores down, at no
    work -- a property of the coupling, measured rather than hidden in the heat; negative when a wall
    stiffens);
    :attr:`heat_balance_error` is the balance with them in place of ``wall_work``.  None otherwise.

    ``wall_work`` is the work of every device (the name is that of the walls-only releases); with fluid
    viscous or friction dampers, ``device_heat`` (dissipated since rest) and ``device_stored`` (in their
    braces and elastic stiffness now) split their share (:mod:`vdw_frames.element.devices`); None without
    such a device.  A building of those devices only has wall parts of 0.
    """

    input: np.ndarray
    kinetic: np.ndarray
    frame_strain: np.ndarray
    hysteretic: np.ndarray
    inherent_damping: np.ndarray
    wall_work: np.ndarray
    p_delta: np.ndarray
    wall_heat: np.ndarray | None = None
    wall_stored: np.ndarray | None = None
    wall_released: np.ndarray | None = None
    wall_parameter_loss: np.ndarray | None = None
    device_heat: np.ndarray | None = None
    device_stored: np.ndarray | None = None

    @property
    def heat_balance_error(self) -> np.ndarray | None:
        """input - (kinetic + frame_strain + hysteretic + inherent_damping + wall_heat + wall_stored +
        wall_released + wall_parameter_loss + p_delta), N*mm; None unless every wall's heat is followed.  It
        closes up to the difference between the walls' force (convolution quadrature) and the diffusive
        representation that splits their work (:mod:`vdw_frames.element.thermal`)."""
        if self.wall_heat is None or self.wall_stored is None or self.wall_released is None \
                or self.wall_parameter_loss is None:
            return None
        devices = 0.0
        if self.device_heat is not None and self.device_stored is not None:
            devices = self.device_heat + self.device_stored
        return self.input - (self.kinetic + self.frame_strain + self.hysteretic + self.inherent_damping
                             + self.wall_heat + self.wall_stored + self.wall_released + self.wall_parameter_loss
                             + devices + self.p_delta)

    @property
    def balance_error(self) -> np.ndarray:
        """input - (kinetic + frame_strain + hysteretic + inherent_damping + wall_work + p_delta), N*mm."""
        return self.input - (self.kinetic + self.frame_strain + self.hysteretic + self.inherent_damping
                             + self.wall_work + self.p_delta)

    def shares(self) -> dict[str, float]:
        """The terms of :attr:`balance_error`'s balance at the last step, each over the input energy (-): "walls"
        (the work done on the walls: the heat they dissipated plus what they store, gain or lose; the work of
        every device without fluid viscous or friction dampers), "other devices" (the work done on those),
        "inherent damping", "story yielding" (``hysteretic``), "frame strain and motion" (``frame_strain`` +
        ``kinetic``, still in the frame), "gravity (P-Delta)" (``p_delta``, <= 0).  Together they are 1 up to
        the balance error.  Empty when the input energy is not positive (nothing to take a share of).

        The walls' heat is not one of them: where their coefficients follow amplitude or temperature, their
        stored energy changes at no work (``wall_parameter_loss``), so their heat can exceed the work done on
        them."""
        total = float(self.input[-1])
        if not total > 0.0:
            return {}
        devices = 0.0
        if self.device_heat is not None and self.device_stored is not None:
            devices = float(self.device_heat[-1] + self.device_stored[-1])
        terms = {"walls": float(self.wall_work[-1]) - devices, "other devices": devices,
                 "inherent damping": float(self.inherent_damping[-1]), "story yielding": float(self.hysteretic[-1]),
                 "frame strain and motion": float(self.frame_strain[-1] + self.kinetic[-1]),
                 "gravity (P-Delta)": float(self.p_delta[-1])}
        return {name: value / total for name, value in terms.items()}


@dataclass(frozen=True)
class FrameState:
    """The state of a frame at one committed step of an analysis, to start another from
    (``simulate(..., initial_state=state)``; :meth:`SimulationResult.state_at` gives it).

    A frame with fractional walls and hysteretic stories is hereditary: its state is its history.  So the
    state holds every story's ``drift`` (mm, (step + 1, stories)) from rest to the step, and an analysis
    started from it commits its own stories and walls through that history, as the analysis that made it
    did, before going on: the stories' and walls' memory, temperature, amplitude and failure are those
    their own history gives.  That is what lets a state start a frame whose walls differ -- the frame
    without a wall that failed, a retrofit, an aftershock on the damaged frame.  ``displacement`` (mm),
    ``velocity`` (mm/s) and ``acceleration`` (mm/s^2, relative to the ground) of every floor at the step,
    (stories,); ``step``: the step's index from rest; ``dt`` (s): the step of the analysis.
    """

    step: int
    dt: float
    displacement: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    drift: np.ndarray

    def __post_init__(self) -> None:
        step = whole_number("step", self.step, 0)
        object.__setattr__(self, "step", step)
        object.__setattr__(self, "dt", positive("dt", self.dt))
        drift = finite_array("drift", self.drift, ndim=2)
        if drift.shape[0] != step + 1 or drift.shape[1] == 0:
            raise ValueError(f"drift must hold step + 1 = {step + 1} rows (rest to the step) of at least one story, "
                             f"got shape {drift.shape}")
        for name in ("displacement", "velocity", "acceleration", "drift"):
            values = drift if name == "drift" else finite_array(name, getattr(self, name))
            if name != "drift" and values.shape != (drift.shape[1],):
                raise ValueError(f"{name} must hold one value per floor ({drift.shape[1]}), got shape {values.shape}")
            values = values.copy()
            values.flags.writeable = False
            object.__setattr__(self, name, values)
        if np.any(self.drift[0] != 0.0):
            raise ValueError(f"drift must start from rest: row 0 is {show(self.drift[0].tolist())}")

    @property
    def stories(self) -> int:
        """The number of stories."""
        return int(self.drift.shape[1])

    @property
    def time(self) -> float:
        """The time of the state, s."""
        return self.step * self.dt


@dataclass(frozen=True)
class SimulationResult:
    """Response histories of :func:`simulate` (rows: time steps; they end where the analysis stopped).

    time (s); displacement (mm), velocity (mm/s), acceleration (mm/s^2) relative to the ground, and
    absolute_acceleration (mm/s^2), each (steps, floors); drift (mm) and drift_ratio (-, None without
    story heights), (steps, stories); story_shear (N, the force in each story's frame spring only,
    (steps, stories)); story_wall_force (N, total of the walls of each story, (steps, stories)) and
    story_wall_strain (-, the strain of each story's most strained wall group, 0 where a story has no
    wall); wall_force (N) and wall_strain (-, the wall's own deformation / thickness: with a support
    in series it is not drift / thickness), (steps, walls) in ``building.wall_list`` order;
    base_shear (N): the force transmitted through story 1 -- its frame spring, walls, P-Delta force
    and inherent damping force through the story (a1 k1 v1 with Rayleigh damping: the mass-proportional
    term acts between the floors and the ground) -- the horizontal reaction of the ground (with P-Delta
    it is less than the story-1 frame and wall shears, story_shear + story_wall_force, which are what the
    structure must resist); ground_acceleration (mm/s^2); energy (:class:`EnergyHistory`).
    absolute_acceleration, drift_ratio, story_wall_strain, wall_force and wall_strain are computed on first
    use (from the stored histories and the wall groups: identical walls of a story are stepped once, as one
    of their summed area).

    ``converged``: False when a step failed to converge (the histories end at the last converged step);
    ``collapsed`` and ``collapse_time`` (s): a story's drift ratio exceeded ``collapse_drift_ratio``
    (the histories end at that step); ``newton_iterations``: the total number of Newton corrections.

    Strain-compatible analyses (``simulate(..., strain_compatible=True)``) also report, per wall in
    ``building.wall_list`` order, ``wall_effective_strain`` (-, the final effective strains) and
    ``equivalent_walls`` (the FDMKDamper each wall ended with), with ``strain_iterations`` and
    ``strain_converged``; ``building`` is then the equivalent-linear building.  None otherwise.
    """

    building: ShearBuilding
    time: np.ndarray
    ground_acceleration: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    drift: np.ndarray
    story_shear: np.ndarray
    story_wall_force: np.ndarray
    base_shear: np.ndarray
    energy: EnergyHistory
    # Walls stepped together (identical walls of a story: one group of their summed area); the per-wall and
    # derived histories are computed from these on first use, not stored by every analysis.
    group_force: np.ndarray = field(repr=False)  # (steps, groups), N
    group_strain: np.ndarray = field(repr=False)  # (steps, groups), -
    wall_group: np.ndarray = field(repr=False)  # (walls,): the group of each wall of building.wall_list
    wall_share: np.ndarray = field(repr=False)  # (walls,): each wall's share of its group's area
    converged: bool = True
    collapsed: bool = False
    collapse_time: float | None = None
    newton_iterations: int = 0
    wall_effective_strain: np.ndarray | None = None
    equivalent_walls: tuple[Wall, ...] | None = None
    strain_iterations: int | None = None
    strain_converged: bool | None = None
    # Followed walls (thermal description or limits): (steps, groups) histories, (0, groups) when none is.
    group_temperature: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)), repr=False)  # degC
    group_heat: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)), repr=False)  # N*mm
    # (groups, 4) when the heat is found from the temperature instead (every followed group has a heat
    # capacity): each group's heat at row 0 (N*mm), ambient (degC), decay exp(-dt/tau) and gain (K per N*mm)
    # of its temperature update (kernel.update_walls); (0, 4) otherwise.
    group_heat_terms: np.ndarray = field(default_factory=lambda: np.zeros((0, 4)), repr=False)
    group_failure: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), dtype=np.int64),
                                      repr=False)  # (groups, 2): step (-1 intact), mode
    group_amplitude: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)), repr=False)  # (steps, groups)
    group_outside_range: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)), repr=False)  # s (groups, 2)
    initial_state: FrameState | None = field(default=None, repr=False)  # where the analysis started, None: rest
    # The devices that are not walls, (steps, devices) in building.other_device_list order, along each device:
    device_force: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)), repr=False)  # N
    device_deformation: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)), repr=False)  # mm
    device_velocity: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)), repr=False)  # mm/s
    device_heat: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)), repr=False)  # N*mm since rest
    device_stored: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)), repr=False)  # N*mm

    @property
    def first_step(self) -> int:
        """The index from rest of this result's row 0 (0 unless it started from an ``initial_state``)."""
        return 0 if self.initial_state is None else self.initial_state.step

    def state_at(self, step: int) -> FrameState:
        """The frame's state at row ``step`` of this result (negative counts from the end, as in numpy), to
        start another analysis from: ``simulate(other_building, motion, initial_state=result.state_at(k))``
        goes on from t = ``time[k]`` (see :class:`FrameState`)."""
        rows = self.time.size
        index = whole_number("step", step, -rows)
        if index >= rows:
            raise ValueError(f"step must be a row of this result (-{rows} ... {rows - 1}), got {show(step)}")
        index %= rows
        if self.time.size > 1:
            dt = float(self.time[1] - self.time[0])
        elif self.initial_state is not None:
            dt = self.initial_state.dt
        else:
            raise ValueError("state_at needs a result of at least two steps (its time step)")
        prefix = self.initial_state.drift[:-1] if self.initial_state is not None else np.zeros((0, self.drift.shape[1]))
        return FrameState(step=self.first_step + index, dt=dt, displacement=self.displacement[index],
                          velocity=self.velocity[index], acceleration=self.acceleration[index],
                          drift=np.concatenate([prefix, self.drift[:index + 1]]))

    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write this result to ``path``, a ``.npz`` file: every history (numpy arrays, in their units
        above), the outcome and the building analysed, walls and story models included, so that
        :meth:`load` gives back a result equal in every history and property.  The write is atomic (an
        existing file stays whole until the new one is complete).  Returns the path."""
        arrays: dict[str, np.ndarray] = {}
        metadata: dict[str, object] = {}
        for item in dataclasses.fields(self):
            value = getattr(self, item.name)
            if isinstance(value, np.ndarray):
                arrays[f"result.{item.name}"] = value
            elif isinstance(value, EnergyHistory):
                arrays.update({f"energy.{part.name}": getattr(value, part.name) for part in dataclasses.fields(value)
                               if getattr(value, part.name) is not None})
            else:
                metadata[item.name] = value
        return write_archive(path, arrays, metadata, _ARCHIVE, classes=(FrameState,))

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> SimulationResult:
        """The result :meth:`save` wrote to ``path``; a file that is not one is refused (ValueError).

        The file is not trusted: every entry is checked before a result is made of it, and a ValueError
        names the file and the first entry that fails (:func:`check_saved_result`): its type, dtype, shape
        and finiteness, its range (a wall's group, a failure step, a time that increases uniformly), and the
        histories' agreement with each other and with the building they were computed for."""
        arrays, metadata = read_archive(path, _ARCHIVE, classes=(FrameState,))
        energy = {name.removeprefix("energy."): value for name, value in arrays.items() if name.startswith("energy.")}
        arguments: dict[str, Any] = {name.removeprefix("result."): value for name, value in arrays.items()
                                     if name.startswith("result.")}
        names = {item.name for item in dataclasses.fields(cls)}
        unknown = sorted({*arguments, *metadata} - names) + sorted(set(energy) - set(_ENERGY_FIELDS))
        missing = sorted(name for name in _REQUIRED if name not in arguments and name not in metadata) + \
            sorted(name for name in _ENERGY_FIELDS[:7] if name not in energy)
        if unknown or missing or len(arrays) != len(energy) + len(arguments):
            stray = sorted(name for name in arrays if not name.startswith(("energy.", "result.")))
            raise ValueError(f"{path}: a saved result with missing or unknown entries (missing {missing}, unknown "
                             f"{unknown + stray})")
        try:
            check_saved_result({**arguments, **metadata}, energy)
        except ValueError as error:
            raise ValueError(f"{path}: {error}") from None
        return cls(energy=EnergyHistory(**energy), **arguments, **metadata)

    @cached_property
    def wall_amplitude(self) -> np.ndarray | None:
        """The strain amplitude each amplitude-following wall followed (-), (steps, walls); 0 for walls of
        fixed parameters; None without amplitude-following walls
        (:func:`vdw_frames.element.kernel.track_amplitude`)."""
        if self.group_amplitude.shape[0] == 0:
            return None
        return np.take(self.group_amplitude, self.wall_group, axis=1)

    @property
    def wall_time_outside_range(self) -> np.ndarray | None:
        """Seconds each amplitude-following wall spent below and above its identified amplitudes (where its
        parameters are those of the nearest end), (walls, 2); None without amplitude-following walls."""
        if self.group_amplitude.shape[0] == 0:
            return None
        return self.group_outside_range[self.wall_group]

    @property
    def wall_time_below_range(self) -> np.ndarray | None:
        """Seconds (walls,) each amplitude-following wall followed an amplitude below its lowest identified one,
        where its parameters are clamped to that set's (for :func:`vdw_frames.paper.strain_dependent` the 225 %
        set, G1 = 0: a viscoelastic fluid; the rule and its reasons: docs/theory.rst); 0 for walls of fixed
        parameters; None without amplitude-following walls.  Column 0 of :attr:`wall_time_outside_range`."""
        outside = self.wall_time_outside_range
        return None if outside is None else outside[:, 0]

    @property
    def wall_time_above_range(self) -> np.ndarray | None:
        """Seconds (walls,) each amplitude-following wall followed an amplitude above its highest identified one
        (parameters clamped to that set's, with a warning); 0 for walls of fixed parameters; None without
        amplitude-following walls.  Column 1 of :attr:`wall_time_outside_range`.  A peak *strain* above the range
        warns for every wall model (:func:`vdw_frames.frame.time_history.peak_strain_warning`)."""
        outside = self.wall_time_outside_range
        return None if outside is None else outside[:, 1]

    @property
    def wall_failed(self) -> np.ndarray:
        """Whether each wall failed (a limit of its :class:`~vdw_frames.element.limits.WallLimits` exceeded),
        (walls,) bool in ``building.wall_list`` order."""
        if self.group_failure.shape[0] == 0:
            return np.zeros(self.wall_group.size, dtype=bool)
        return self.group_failure[self.wall_group, 0] >= 0

    @property
    def wall_failure_time(self) -> tuple[float | None, ...]:
        """The time (s) of each wall's failure (the first committed step beyond a limit), None if intact."""
        if self.group_failure.shape[0] == 0:
            return (None,) * self.wall_group.size
        dt = float(self.time[1] - self.time[0]) if self.time.size > 1 else 0.0
        return tuple(None if step < 0 else step * dt for step in self.group_failure[self.wall_group, 0].tolist())

    @property
    def wall_failure_mode(self) -> tuple[str, ...]:
        """How each wall failed: "strain", "stress" or "temperature"; "" if intact."""
        if self.group_failure.shape[0] == 0:
            return ("",) * self.wall_group.size
        return tuple(FAILURE_MODES[mode] for mode in self.group_failure[self.wall_group, 1].tolist())

    @cached_property
    def wall_temperature(self) -> np.ndarray | None:
        """Temperature of every wall's viscoelastic layers (degC), (steps, walls); NaN for a wall without a
        thermal description; None when no wall's heat is followed (a thermal description or limits:
        :class:`~vdw_frames.element.thermal.ThermalProperties`, :class:`~vdw_frames.WallLimits`)."""
        if self.group_temperature.shape[0] == 0:
            return None
        return np.take(self.group_temperature, self.wall_group, axis=1)

    @property
    def peak_temperature_rise(self) -> np.ndarray | None:
        """Largest temperature rise of every wall over its temperature at rest (K), (walls,); NaN without a
        thermal description; None when no wall's heat is followed."""
        temperature = self.wall_temperature
        if temperature is None:
            return None
        return np.max(temperature - temperature[:1], axis=0)

    @cached_property
    def wall_heat(self) -> np.ndarray | None:
        """Energy every wall has dissipated since rest (N*mm), (steps, walls); None when no wall's heat is followed
        (a thermal description or limits).

        Walls that all have a heat capacity keep their heat in their temperature: the heat of each step is
        found from the kernel's update, T' = T_a + (T - T_a) exp(-dt/tau) + gain * heat, inverted (exact
        up to the rounding of T: about 1e-14 K times rho c V)."""
        if self.group_heat.shape[0] > 0:
            heat = self.group_heat
        elif self.group_heat_terms.shape[0] > 0 and self.group_temperature.shape[0] > 0:
            heat = _heat_from_temperature(self.group_temperature, self.group_heat_terms)
        else:
            return None
        return np.take(heat, self.wall_group, axis=1) * self.wall_share

    @cached_property
    def absolute_acceleration(self) -> np.ndarray:
        """Relative acceleration + ground acceleration, mm/s^2, (steps, floors)."""
        return self.acceleration + self.ground_acceleration[:, None]

    @cached_property
    def drift_ratio(self) -> np.ndarray | None:
        """Drift / story height (-), (steps, stories); None without story heights."""
        heights = self.building.story_heights
        return None if heights is None else self.drift / np.asarray(heights)

    @cached_property
    def wall_force(self) -> np.ndarray:
        """Force of every wall (N), (steps, walls) in ``building.wall_list`` order."""
        return np.take(self.group_force, self.wall_group, axis=1) * self.wall_share

    @cached_property
    def wall_strain(self) -> np.ndarray:
        """Strain of every wall (-: its own deformation / thickness), (steps, walls)."""
        return np.take(self.group_strain, self.wall_group, axis=1)

    @cached_property
    def story_wall_strain(self) -> np.ndarray:
        """The strain of each story's most strained wall group (-), (steps, stories); 0 without walls."""
        strain = np.zeros((self.time.size, self.building.stories))
        peaks = np.abs(self.group_strain).max(axis=0, initial=0.0)
        stories = np.array([story - 1 for story, _ in self.building.wall_list], dtype=int)
        most: dict[int, int] = {}
        for wall, group in enumerate(self.wall_group):
            story = stories[wall]
            if story not in most or peaks[group] > peaks[most[story]]:
                most[story] = group
        for story, group in most.items():
            strain[:, story] = self.group_strain[:, group]
        return strain

    @property
    def peak_drift(self) -> np.ndarray:
        """max |drift| per story, mm."""
        return np.abs(self.drift).max(axis=0)

    @property
    def peak_drift_ratio(self) -> np.ndarray | None:
        """max |drift ratio| per story (-), None without story heights."""
        return None if self.drift_ratio is None else np.abs(self.drift_ratio).max(axis=0)

    @property
    def residual_drift(self) -> np.ndarray:
        """Drift at the last step, per story, mm (append ``free_vibration`` to measure it at rest).  For an
        analysis that collapsed or stopped converging it is the drift where it stopped, not a residual."""
        return self.drift[-1].copy()

    @property
    def peak_ductility(self) -> np.ma.MaskedArray:
        """Peak |drift| / yield drift per story (-); masked for stories without a hysteresis model."""
        yield_drifts = self.building.yield_drifts
        elastic = yield_drifts == 0.0
        ratio = self.peak_drift / np.where(elastic, 1.0, yield_drifts)
        return np.ma.masked_array(ratio, mask=elastic)

    @property
    def peak_absolute_acceleration(self) -> np.ndarray:
        """max |absolute acceleration| per floor, mm/s^2."""
        return np.abs(self.absolute_acceleration).max(axis=0)

    @property
    def peak_base_shear(self) -> float:
        """max |base shear|, N."""
        return float(np.abs(self.base_shear).max())

    @property
    def peak_story_wall_force(self) -> np.ndarray:
        """max |total wall force| per story, N."""
        return np.abs(self.story_wall_force).max(axis=0)

    @property
    def peak_wall_strain(self) -> np.ndarray:
        """max |strain| of every wall (-), in ``building.wall_list`` order."""
        return np.abs(self.group_strain).max(axis=0, initial=0.0)[self.wall_group]


_ENERGY_FIELDS = ("input", "kinetic", "frame_strain", "hysteretic", "inherent_damping", "wall_work", "p_delta",
                  "wall_heat", "wall_stored", "wall_released", "wall_parameter_loss", "device_heat", "device_stored")
_DEVICE_HISTORIES = ("device_force", "device_deformation", "device_velocity", "device_heat", "device_stored")
_REQUIRED = ("building", "time", "ground_acceleration", "displacement", "velocity", "acceleration", "drift",
             "story_shear", "story_wall_force", "base_shear", "group_force", "group_strain", "wall_group", "wall_share")
CONSISTENCY_TOLERANCE = 1e-9
"""Relative tolerance (of each quantity's largest magnitude) of the identities :func:`check_saved_result`
checks between a loaded result's histories; :func:`simulate` meets them to rounding (~1e-15), a P-Delta
energy summed over the steps to ~1e-12."""


def check_saved_result(fields: dict[str, Any], energy: dict[str, Any]) -> None:
    """Check the entries of a saved :class:`SimulationResult` (``fields``: its constructor arguments but
    ``energy``; ``energy``: the :class:`EnergyHistory` arguments); a ValueError naming the first entry that
    fails.

    Checked: every history is a float64 numpy array (no object, datetime, raw or other array) of the shape
    the building and the number of rows give, finite (a group temperature may be NaN throughout, for a wall
    without a thermal description); ``time`` is (first step + k) dt, dt > 0; ``wall_group`` maps every wall
    to a group (each group used, its walls on one story) and ``wall_share`` gives each group's walls shares
    that sum to 1; a failure step lies in the result's steps (or is -1) with a known mode; the outcome's
    flags are bools, counts whole numbers >= 0, ``collapse_time`` the last time exactly when ``collapsed``.
    Identities of the analysis (:func:`~vdw_frames.frame.integrator` and :func:`simulate`), within
    :data:`CONSISTENCY_TOLERANCE`: drift = displacement differences; kinetic energy = v^T M v / 2 (the masses);
    frame strain energy = sum F_s^2 / (2 k0) (the stiffnesses); base shear = story 1's frame, wall, P-Delta
    (-P/h d) and damping forces (the gravity loads, the story heights and the damping); P-Delta energy =
    -sum P d^2 / (2 h).  Story heights enter the histories only through P-Delta: without gravity loads they
    cannot be checked against them.
    """
    building = fields.get("building")
    if not isinstance(building, ShearBuilding):
        raise ValueError(f"building must be a ShearBuilding, got {type(building).__name__}")
    floors, walls = building.stories, len(building.wall_list)
    state = _check_outcome_flags(fields, floors)
    time, first, dt = _check_time(fields.get("time"), state)
    rows = time.size
    _check_time_rows(fields, rows)
    histories = {name: _history(name, fields.get(name), (rows, floors))
                 for name in ("displacement", "velocity", "acceleration", "drift", "story_shear", "story_wall_force")}
    for name in ("ground_acceleration", "base_shear"):
        histories[name] = _history(name, fields.get(name), (rows,))
    groups = _check_wall_groups(fields, building, rows)
    _check_group_states(fields, groups, rows, first, dt)
    devices = len(building.other_device_list)
    for name in _DEVICE_HISTORIES:
        value = _array(name, fields.get(name, np.zeros((0, 0))))
        _history(name, value, (0, 0) if devices == 0 and value.shape == (0, 0) else (rows, devices))
    _check_strain_compatible(fields, walls)
    collapse_time = fields.get("collapse_time")
    if fields.get("collapsed", False) != (collapse_time is not None) or \
            (collapse_time is not None and collapse_time != float(time[-1])):
        raise ValueError(f"collapse_time must be the last time, {float(time[-1])!r} s, when collapsed and None "
                         f"otherwise, got {show(collapse_time)}")
    for name in _ENERGY_FIELDS:
        if name in energy:
            _history(f"energy.{name}", energy[name], (rows,))
    _check_identities(building, histories, energy)


def _array(name: str, value: object, kind: str = "f") -> np.ndarray:
    """``value`` if it is a float64 (``kind`` "f") or int64 ("i") numpy array; else a ValueError."""
    if not isinstance(value, np.ndarray) or value.dtype.kind != kind or value.dtype.itemsize != 8:
        wanted = "float64" if kind == "f" else "int64"
        got = value.dtype if isinstance(value, np.ndarray) else type(value).__name__
        raise ValueError(f"{name} must be a {wanted} array, got {got}")
    return value


def _history(name: str, value: object, shape: tuple[int, ...], nan_columns: bool = False) -> np.ndarray:
    """``value`` if it is a finite float64 array of ``shape`` (with ``nan_columns``, a column may be NaN
    throughout: a wall without a temperature); else a ValueError naming the first bad entry."""
    values = _array(name, value)
    if values.shape != shape:
        raise ValueError(f"{name} must have shape {shape}, got {values.shape}")
    bad = ~np.isfinite(values)
    if nan_columns and values.ndim == 2:
        bad &= ~np.all(np.isnan(values), axis=0)
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        raise ValueError(f"{name} must be finite, got {show(values[index])} at index {index}")
    return values


def _check_outcome_flags(fields: dict[str, Any], floors: int) -> FrameState | None:
    """The outcome's flags and counts, and the initial state (returned: None for a start from rest)."""
    for name in ("converged", "collapsed"):
        if not isinstance(fields.get(name, False), bool):
            raise ValueError(f"{name} must be True or False, got {show(fields[name])}")
    for name, least in (("newton_iterations", 0), ("strain_iterations", 1)):
        value = fields.get(name, 0)
        if (value is not None or name == "newton_iterations") and \
                (isinstance(value, bool) or not isinstance(value, int) or value < least):
            raise ValueError(f"{name} must be a whole number >= {least}, got {show(value)}")
    if fields.get("strain_converged") is not None and not isinstance(fields["strain_converged"], bool):
        raise ValueError(f"strain_converged must be True, False or None, got {show(fields['strain_converged'])}")
    state = fields.get("initial_state")
    if state is not None and (not isinstance(state, FrameState) or state.stories != floors):
        raise ValueError(f"initial_state must be a FrameState of {floors} stories, got {show(state)}")
    return state


def _check_time(value: object, state: FrameState | None) -> tuple[np.ndarray, int, float]:
    """(time (s), its first step, dt (s)): ``value`` must be (first step + k) dt, dt > 0."""
    time = _array("time", value)
    rows = time.size
    if time.ndim != 1 or rows == 0:
        raise ValueError(f"time must be a 1-D array of at least one step, got shape {time.shape}")
    bad = ~np.isfinite(time)
    if bad.any():  # NaN passes the comparisons below
        index = int(np.argmax(bad))
        raise ValueError(f"time must be finite, got {show(time[index])} at index ({index},)")
    first = 0 if state is None else state.step
    dt = state.dt if state is not None else float(time[1]) if rows > 1 else 1.0
    # simulate writes (first + k) dt exactly; a restart's dt may differ from its state's by 1e-9 (_check_state)
    if not (np.isfinite(dt) and dt > 0.0) or np.any(np.diff(time) <= 0.0) or \
            np.any(np.abs(time - np.arange(first, first + rows) * dt) > 1e-8 * (first + rows) * dt):
        raise ValueError(f"time must be (first step + k) dt, increasing uniformly from {first} dt (dt > 0), got "
                         f"{show(time[:3].tolist())} ...")
    return time, first, dt


_STEP_HISTORIES = ("displacement", "velocity", "acceleration", "drift", "story_shear", "story_wall_force",
                   "ground_acceleration", "base_shear")


def _check_time_rows(fields: dict[str, Any], rows: int) -> None:
    """A ValueError naming ``time`` when the step histories agree among themselves on a number of rows that is
    not its ``rows`` (a truncated or extended time); a single history of its own length is named by its shape
    check instead."""
    counts = {name: value.shape[0] for name in _STEP_HISTORIES
              if isinstance(value := fields.get(name), np.ndarray) and value.ndim >= 1}
    if len(counts) == len(_STEP_HISTORIES) and len(set(counts.values())) == 1 and rows not in counts.values():
        raise ValueError(f"time has {rows} steps but every history ({', '.join(counts)}) has "
                         f"{next(iter(counts.values()))} rows: time must have one entry a row")


def _check_wall_groups(fields: dict[str, Any], building: ShearBuilding, rows: int) -> int:
    """The wall groups' force and strain histories, the walls' groups (each group used, its walls on one
    story) and shares (summing to 1 a group); returns the number of groups."""
    walls = len(building.wall_list)
    group_force = _array("group_force", fields.get("group_force"))
    groups = group_force.shape[1] if group_force.ndim == 2 else -1
    for name in ("group_force", "group_strain"):
        _history(name, fields.get(name), (rows, max(groups, 0)))
    wall_group = _array("wall_group", fields.get("wall_group"), "i")
    if wall_group.shape != (walls,) or np.any(wall_group < 0) or np.any(wall_group >= groups) or \
            np.unique(wall_group).size != groups:
        raise ValueError(f"wall_group must give each of the building's {walls} walls one of the {groups} wall groups "
                         f"(each group used), got {show(wall_group.tolist())}")
    stories = np.array([story for story, _ in building.wall_list], dtype=np.int64)
    for group in range(groups):
        if np.unique(stories[wall_group == group]).size != 1:
            raise ValueError(f"wall_group {group} holds walls of stories {sorted(set(stories[wall_group == group]))}: "
                             "a group is walls of one story")
    share = _history("wall_share", fields.get("wall_share"), (walls,))
    if np.any(share <= 0.0) or np.any(share > 1.0) or \
            np.any(np.abs(np.bincount(wall_group, share, groups) - 1.0) > CONSISTENCY_TOLERANCE):
        raise ValueError(f"wall_share must give each wall a share in (0, 1] of its group, the shares of a group "
                         f"summing to 1, got {show(share.tolist())}")
    return groups


def _check_group_states(fields: dict[str, Any], groups: int, rows: int, first: int, dt: float) -> None:
    """The wall groups' temperature, heat and amplitude histories, heat terms, failures and time outside
    their tested range."""
    for name in ("group_temperature", "group_heat", "group_amplitude"):
        value = _array(name, fields.get(name, np.zeros((0, 0))))
        shape = value.shape if value.shape in ((0, 0), (0, groups)) else (rows, groups)
        values = _history(name, value, shape, nan_columns=name == "group_temperature")
        if name == "group_amplitude" and np.any(values < 0.0):
            raise ValueError("group_amplitude must be >= 0")
    terms = _array("group_heat_terms", fields.get("group_heat_terms", np.zeros((0, 4))))
    terms = _history("group_heat_terms", terms, terms.shape if terms.shape == (0, 4) else (groups, 4))
    if np.any(terms[:, 2] < 0.0) or np.any(terms[:, 2] > 1.0) or np.any(terms[:, 3] < 0.0):
        raise ValueError("group_heat_terms must hold decays in [0, 1] and gains >= 0 (columns 3 and 4)")
    failure = _array("group_failure", fields.get("group_failure", np.zeros((0, 2), dtype=np.int64)), "i")
    step, mode = (failure[:, 0], failure[:, 1]) if failure.ndim == 2 and failure.shape[1] == 2 else (None, None)
    if step is None or mode is None or failure.shape[0] not in (0, groups) or np.any(step < -1) or \
            np.any(step >= first + rows) or np.any((mode < 0) | (mode >= len(FAILURE_MODES))) or \
            np.any((step < 0) != (mode == 0)):
        raise ValueError(f"group_failure must hold, per wall group, a failure step in {first} ... {first + rows - 1} "
                         f"(-1: intact) and a mode of 1 ... {len(FAILURE_MODES) - 1} (0: intact), got "
                         f"{show(failure.tolist())}")
    outside = _array("group_outside_range", fields.get("group_outside_range", np.zeros((0, 2))))
    outside = _history("group_outside_range", outside, outside.shape if outside.shape == (0, 2) else (groups, 2))
    if np.any(outside < 0.0) or np.any(outside > (first + rows) * dt):
        raise ValueError(f"group_outside_range must hold times in 0 ... {(first + rows) * dt:.6g} s, got "
                         f"{show(outside.tolist())}")


def _check_strain_compatible(fields: dict[str, Any], walls: int) -> None:
    """A strain-compatible analysis's entries: all four given or none."""
    effective, equivalent = fields.get("wall_effective_strain"), fields.get("equivalent_walls")
    strained = (effective, equivalent, fields.get("strain_iterations"), fields.get("strain_converged"))
    if any(item is None for item in strained) and any(item is not None for item in strained):
        raise ValueError("wall_effective_strain, equivalent_walls, strain_iterations and strain_converged must all be "
                         "given (a strain-compatible analysis) or all be None")
    if effective is not None and np.any(_history("wall_effective_strain", effective, (walls,)) < 0.0):
        raise ValueError("wall_effective_strain must be >= 0")
    if equivalent is not None and (not isinstance(equivalent, tuple) or len(equivalent) != walls):
        raise ValueError(f"equivalent_walls must be a tuple of the building's {walls} walls, got {show(equivalent)}")


def _check_identities(building: ShearBuilding, histories: dict[str, np.ndarray], energy: dict[str, np.ndarray]) -> None:
    """The identities :func:`check_saved_result` lists, each within CONSISTENCY_TOLERANCE of its scale."""
    displacement, velocity, drift = histories["displacement"], histories["velocity"], histories["drift"]
    shear, walls = histories["story_shear"], histories["story_wall_force"]
    geometric = np.asarray(building.geometric_stiffness)
    # the row simulate uses (from the diagonals for Rayleigh damping: no dense n x n matrix at load)
    damping = velocity @ np.asarray(building.story_damping_row)
    checks = (
        ("drift", drift, np.diff(displacement, axis=1, prepend=0.0), "the displacement differences"),
        ("energy.kinetic", energy["kinetic"], 0.5 * (velocity**2) @ np.asarray(building.masses),
         "v^T M v / 2 with the building's masses"),
        ("energy.frame_strain", energy["frame_strain"], 0.5 * (shear**2) @ (1.0 / np.asarray(building.stiffnesses)),
         "sum F_s^2 / (2 k0) with the building's stiffnesses"),
        ("base_shear", histories["base_shear"], shear[:, 0] + walls[:, 0] + geometric[0] * drift[:, 0] + damping,
         "story 1's frame, wall, P-Delta and damping forces with the building's gravity loads, heights and damping"),
        ("energy.p_delta", energy["p_delta"], 0.5 * (drift**2) @ geometric,
         "-sum P d^2 / (2 h) with the building's gravity loads and story heights"),
    )
    for name, stored, expected, what in checks:
        scale = max(float(np.abs(stored).max(initial=0.0)), float(np.abs(expected).max(initial=0.0)))
        gap = np.abs(stored - expected)
        if gap.max(initial=0.0) > CONSISTENCY_TOLERANCE * scale:
            row = int(np.argmax(gap.max(axis=1) if gap.ndim == 2 else gap))
            raise ValueError(f"{name} disagrees with {what}: off by {float(gap.max()):.3g} at row {row} (tolerance "
                             f"{CONSISTENCY_TOLERANCE:g} of {scale:.3g}); the file's histories and building do not "
                             "belong together")


def _heat_from_temperature(temperature: np.ndarray, terms: np.ndarray) -> np.ndarray:
    """Every group's heat since rest (N*mm), (steps, groups), from its temperature history (degC, (steps,
    groups)) and ``terms`` (groups, 4): heat at row 0, ambient, decay and gain of the temperature update
    (a group with gain 0 has no temperature and no heat)."""
    initial, ambient, decay, gain = terms.T
    heat = np.zeros(temperature.shape)
    heat[0] = initial
    heated = gain > 0.0
    rise = temperature[:, heated] - ambient[heated]
    steps = (rise[1:] - rise[:-1] * decay[heated]) / gain[heated]
    heat[1:, heated] = initial[heated] + np.cumsum(steps, axis=0)
    return heat


def check_energy_balance(energy: EnergyHistory) -> None:
    """Warn when the energy balance misses by more than ENERGY_BALANCE_TOLERANCE of the peak input energy."""
    scale = float(np.abs(energy.input).max(initial=0.0))
    if scale == 0.0:
        return
    error = float(np.abs(energy.balance_error).max()) / scale
    if error > ENERGY_BALANCE_TOLERANCE:
        _warnings.warn(f"simulate: the energy balance misses by {error:.3g} of the peak input energy (self-check "
                       f"bound {ENERGY_BALANCE_TOLERANCE:g}): the integration did not solve the equations of "
                       "motion to their tolerance; do not trust this result", RuntimeWarning, stacklevel=5)


def energy_history(energy: np.ndarray, wall_energies: tuple | None = None,
                   device_energies: tuple | None = None) -> EnergyHistory:
    """The integrator's energy columns (steps, 7) as an :class:`EnergyHistory`, checked finite and balanced;
    ``wall_energies``: (heat, stored, released, parameter loss) histories (steps,) N*mm when every wall's heat
    is followed; ``device_energies``: (heat, stored) of the other devices (steps,) N*mm, when there are any, and
    whether the building has walls (without, the wall parts are 0)."""
    require_finite("the energy histories", energy)
    heat, stored, released, parameter_loss = wall_energies if wall_energies is not None else (None,) * 4
    device_heat, device_stored, has_walls = device_energies if device_energies is not None else (None, None, True)
    if not has_walls:  # the devices' split stands for the whole device work
        heat = stored = released = parameter_loss = np.zeros(energy.shape[0])
    history = EnergyHistory(input=energy[:, 0], kinetic=energy[:, 1], frame_strain=energy[:, 2],
                            hysteretic=energy[:, 3] - energy[:, 2], inherent_damping=energy[:, 4],
                            wall_work=energy[:, 5], p_delta=energy[:, 6], wall_heat=heat, wall_stored=stored,
                            wall_released=released, wall_parameter_loss=parameter_loss, device_heat=device_heat,
                            device_stored=device_stored)
    check_energy_balance(history)
    return history
