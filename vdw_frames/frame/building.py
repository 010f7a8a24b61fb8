"""Shear building: lumped floor masses, story springs (elastic or yielding), P-Delta, inherent damping,
damping devices across stories (FDMK walls, fluid viscous and friction dampers)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import eigh, eigh_tridiagonal

from .. import _warnings
from .._validation import check_memory, damping_ratio, finite_array, positive, show, whole_number
from ..element.devices import KINDS, is_stepped_device
from ..element.strain_dependent import StrainDependentDamper
from ..element.supported import WALL_TYPES
from .hysteresis import STORY_MODELS, Bilinear, BoucWen

if TYPE_CHECKING:
    from ..element.device import Device
    from ..element.wall import Wall

DAMPING_MODELS = ("rayleigh", "modal")


_FREQUENCY_CHUNK = 2048  # frequencies solved at once by frequency_response

# The widest spread of story stiffnesses (largest / smallest) a building may have: a validation bound of
# double-precision arithmetic, not a model constant.  The lowest frequency of K phi = w^2 M phi loses
# about eps (2.2e-16) times the spread of its digits (2-story frames against a 60-digit closed form: <= 3e-6
# relative at 1e10, 1e-4 at 1e12; at 2e16 the eigenvalue comes out negative and the period NaN); real story
# stiffnesses, a soft or an isolation story included, span less than 1e4.
MAX_STIFFNESS_RATIO = 1e10
# The largest circular frequency squared (rad^2/s^2) accepted: the complex-mode search (modal_analysis) works with
# norms of s^2 M + K and overflows above about 1e170 (measured, 2 and 10 stories); real buildings stay below 1e7.
MAX_FREQUENCY_SQUARED = 1e150


@dataclass(frozen=True, eq=False, init=False)
class ShearBuilding:
    """A shear building with optional damping devices (FDMK walls, fluid viscous and friction dampers),
    yielding stories and P-Delta.

    Parameters
    ----------
    masses : sequence of float
        Floor masses, tonne, from the first floor up.
    stiffnesses : sequence of float
        Initial (elastic) story stiffnesses k0, N/mm; story 1 connects the ground to floor 1, story k
        floor k-1 to floor k.  The largest at most :data:`MAX_STIFFNESS_RATIO` (1e10) times the smallest,
        and k/m at most :data:`MAX_FREQUENCY_SQUARED` (1e150 rad^2/s^2) and above the smallest normal double: what
        double precision and the complex-mode search resolve (validation bounds).
    damping_ratio : float
        Inherent damping ratio of the bare frame, in [0, 1).
    damping_modes : (int, int), optional
        Rayleigh damping: the two modes (1-based) given ``damping_ratio`` by C = a0 M + a1 K_frame; the
        same mode twice splits the ratio equally between the mass and stiffness terms.  Default (1, 2),
        or (1, 1) for a one-story building.
    devices : dict {story: device or list of devices}
        Damping devices across stories (1 ... n), of any kind and mixed: walls
        (:class:`~vdw_frames.FDMKDamper`, :class:`~vdw_frames.SupportedDamper`,
        :class:`~vdw_frames.StrainDependentDamper`), :class:`~vdw_frames.FluidViscousDamper` and
        :class:`~vdw_frames.FrictionDamper`; several on one story act in parallel.  A device's deformation
        is its magnification (1 for walls) times the interstory drift (:mod:`vdw_frames.element.device`).
        ``walls=`` (the keyword before 0.3) still works, with a DeprecationWarning
        (``dataclasses.replace(building, walls=...)`` replaces its walls and keeps its other devices).
    story_heights : sequence of float, optional
        Story heights, mm, for drift ratios, P-Delta and the collapse check.
    hysteresis : sequence or dict, optional
        The story models: one per story (:class:`~vdw_frames.Bilinear`, :class:`~vdw_frames.BoucWen`,
        or None for a linear story), or a dict {story: model} (stories left out are linear).  The
        initial stiffness of each model is the story's entry in ``stiffnesses``.  Default: all linear.
    gravity_loads : sequence of float, optional
        The vertical load P each story carries (N, >= 0: the weight of everything above it).  With
        ``story_heights`` it adds P-Delta as a geometric stiffness -P/h to the story, in the restoring
        force and in the tangent (the linearised leaning-column model).  Needs ``story_heights``.
    damping_model : "rayleigh" or "modal"
        Inherent damping.  "rayleigh" (default): C = a0 M + a1 K_frame with K_frame the *initial* elastic
        story stiffness (walls and P-Delta excluded), fitted to ``damping_ratio`` in ``damping_modes``.
        Once stories yield, an initial-stiffness term keeps producing viscous forces the softened frame
        would not, which can overstate damping forces and understate displacements (Charney 2008, "Unintended
        consequences of modeling damping in structures", J. Struct. Eng. 134(4)); compare with
        "modal": the same ``damping_ratio`` in every mode of the bare elastic frame,
        C = M Phi diag(2 zeta omega) Phi^T M (mass-normalised Phi).  Rayleigh on modes 1 and 2 over-damps
        the higher modes (7-17 % in modes 3-10 of the 10-story example), which lowers floor accelerations.

    Notes
    -----
    ``masses``, ``stiffnesses`` and the periods and modes are those of the bare elastic frame (no walls,
    no P-Delta).
    """

    masses: tuple[float, ...]
    stiffnesses: tuple[float, ...]
    damping_ratio: float = 0.05
    # None (the default) becomes (1, 2), or (1, 1) for one story, in __post_init__.
    damping_modes: tuple[int, int] = cast("tuple[int, int]", None)
    devices: dict[int, tuple[Device, ...]] = field(default_factory=dict)
    story_heights: tuple[float, ...] | None = None
    hysteresis: tuple[Bilinear | BoucWen | None, ...] | None = None
    gravity_loads: tuple[float, ...] | None = None
    damping_model: str = "rayleigh"

    # The dataclass's own positional signature since 0.1, and walls=, the devices' keyword before 0.3.
    def __init__(self, masses: ArrayLike, stiffnesses: ArrayLike, damping_ratio: float = 0.05,  # noqa: PLR0917
                 damping_modes: tuple[int, int] | None = None, devices: dict[Any, Any] | None = None,
                 story_heights: ArrayLike | None = None, hysteresis: object = None,
                 gravity_loads: ArrayLike | None = None, damping_model: str = "rayleigh", *,
                 walls: dict[Any, Any] | None = None) -> None:
        if walls is not None:
            _warnings.warn("ShearBuilding(walls=...) is deprecated since 0.3 and will be removed in 0.4: give every "
                           "device, walls included, through devices=", DeprecationWarning, stacklevel=2)
            if devices is not None and not isinstance(devices, _OwnDevices):
                raise ValueError("give the devices through devices= only (walls= is its deprecated name), not both")
            # dataclasses.replace(building, walls=...) passes the building's own devices back: walls replace its walls
            devices = _walls_replaced({} if devices is None else devices, walls)
        for name, value in (("masses", masses), ("stiffnesses", stiffnesses), ("damping_ratio", damping_ratio),
                            ("damping_modes", damping_modes), ("devices", {} if devices is None else devices),
                            ("story_heights", story_heights), ("hysteresis", hysteresis),
                            ("gravity_loads", gravity_loads), ("damping_model", damping_model)):
            object.__setattr__(self, name, value)
        self.__post_init__()

    def __post_init__(self) -> None:
        stories = self._check_masses_and_stiffnesses()
        object.__setattr__(self, "damping_ratio", damping_ratio(self.damping_ratio))
        object.__setattr__(self, "damping_modes", self._check_damping_modes(stories))
        object.__setattr__(self, "devices", self._normalise_devices(self.devices, stories))
        if self.story_heights is not None:
            object.__setattr__(self, "story_heights", self._check_story_heights(self.story_heights, stories))
        object.__setattr__(self, "hysteresis", self._normalise_hysteresis(self.hysteresis, stories))
        if self.gravity_loads is not None:
            if self.story_heights is None:
                raise ValueError("gravity_loads need story_heights (P-Delta is -P/h per story)")
            object.__setattr__(self, "gravity_loads", self._check_gravity_loads(self.gravity_loads, stories))
        if not isinstance(self.damping_model, str) or self.damping_model not in DAMPING_MODELS:
            raise ValueError(f"damping_model must be one of {DAMPING_MODELS}, got {self.damping_model!r}")

    def _check_masses_and_stiffnesses(self) -> int:
        """Check and store masses (tonne) and story stiffnesses (N/mm) as tuples; returns the number of stories."""
        masses = finite_array("masses", self.masses)
        stiffnesses = finite_array("stiffnesses", self.stiffnesses)
        if masses.size == 0:
            raise ValueError("masses must hold at least one floor")
        if (masses <= 0).any():
            raise ValueError(f"masses must be > 0 tonne, got {show(masses[masses <= 0][0])}")
        if (stiffnesses <= 0).any():
            raise ValueError(f"stiffnesses must be > 0 N/mm, got {show(stiffnesses[stiffnesses <= 0][0])}")
        if stiffnesses.size != masses.size:
            raise ValueError(f"stiffnesses has {stiffnesses.size} stories for {masses.size} floors (masses)")
        with np.errstate(over="ignore"):
            assembled = stiffnesses[:-1] + stiffnesses[1:]  # the floors' diagonal terms of K
        if not np.isfinite(assembled).all():
            story = int(np.argmax(~np.isfinite(assembled)))
            raise ValueError(f"stiffnesses of stories {story + 1} and {story + 2} ({show(stiffnesses[story])} and "
                             f"{show(stiffnesses[story + 1])} N/mm) overflow when added into the stiffness matrix")
        _check_eigenproblem(masses, stiffnesses)
        object.__setattr__(self, "masses", tuple(masses.tolist()))
        object.__setattr__(self, "stiffnesses", tuple(stiffnesses.tolist()))
        return int(masses.size)

    def _check_damping_modes(self, stories: int) -> tuple[int, ...]:
        """The two mode numbers of the damping (default the first two, or the only mode of one story)."""
        if self.damping_modes is None:
            return (1, min(2, stories))
        modes: object = self.damping_modes
        if isinstance(modes, np.ndarray):
            modes = tuple(modes.tolist()) if modes.ndim == 1 else None
        if not isinstance(modes, (tuple, list)) or len(modes) != 2:
            raise ValueError(f"damping_modes must be two mode numbers in 1 ... {stories}, "
                             f"got {show(self.damping_modes)}")
        numbers = tuple(whole_number("damping_modes", m, 1) for m in modes)
        if max(numbers) > stories:
            raise ValueError(f"damping_modes must be two mode numbers in 1 ... {stories}, got {numbers}")
        return numbers

    @staticmethod
    def _check_story_heights(story_heights: ArrayLike, stories: int) -> tuple[float, ...]:
        """The story heights (mm), one a story, each > 0."""
        heights = finite_array("story_heights", story_heights)
        if heights.size != stories:
            raise ValueError(f"story_heights has {heights.size} entries for {stories} stories")
        if (heights <= 0).any():
            raise ValueError(f"story_heights must be > 0 mm, got {show(heights[heights <= 0][0])}")
        return tuple(heights.tolist())

    @staticmethod
    def _check_gravity_loads(gravity_loads: ArrayLike, stories: int) -> tuple[float, ...]:
        """The gravity loads (N) on each story, each >= 0."""
        loads = finite_array("gravity_loads", gravity_loads)
        if loads.size != stories:
            raise ValueError(f"gravity_loads has {loads.size} entries for {stories} stories")
        if (loads < 0).any():
            raise ValueError(f"gravity_loads must be >= 0 N, got {loads[loads < 0][0]!r}")
        return tuple(loads.tolist())

    @staticmethod
    def _normalise_devices(devices_by_story: dict[Any, Any] | None, stories: int) -> dict[int, tuple[Device, ...]]:
        if devices_by_story is not None and not isinstance(devices_by_story, dict):
            raise ValueError(f"devices must be a dict {{story: device or list}}, got {type(devices_by_story).__name__}")
        normalised: dict[int, tuple[Device, ...]] = {}
        seen: set[int] = set()  # stories after normalisation: {1: w, 1.0: w} is one story twice
        given = devices_by_story or {}
        kinds = ", ".join(cls.__name__ for cls in (*WALL_TYPES, StrainDependentDamper, *KINDS.values()))
        for key, entry in given.items():
            message = f"device story must be a story number in 1 ... {stories}, got {show(key)}"
            try:
                story = whole_number("device story", key, 1)
            except ValueError:
                raise ValueError(message) from None
            if story > stories:
                raise ValueError(message)
            devices = tuple(entry) if isinstance(entry, (list, tuple)) else (entry,)
            for device in devices:
                if not (is_wall(device) or is_stepped_device(device)):
                    raise ValueError(f"devices[{story}] must be {kinds} objects, got {type(device).__name__}")
            if story in seen:
                raise ValueError(f"devices has story {story} twice (keys {show(list(given))}); give each "
                                 "story once, with a list of its devices")
            seen.add(story)
            if devices:
                normalised[story] = devices
        return _OwnDevices(sorted(normalised.items()))

    @staticmethod
    def _normalise_hysteresis(hysteresis: object, stories: int) -> tuple[Bilinear | BoucWen | None, ...] | None:
        if hysteresis is None:
            return None
        models: list[Bilinear | BoucWen | None]
        if isinstance(hysteresis, dict):
            models = [None] * stories
            given: set[int] = set()
            for story, model in hysteresis.items():
                if isinstance(story, bool) or not isinstance(story, (int, np.integer)) or not 1 <= story <= stories:
                    raise ValueError(f"hysteresis story must be a story number in 1 ... {stories}, got {story!r}")
                if int(story) in given:
                    raise ValueError(f"hysteresis has story {int(story)} twice (keys {show(list(hysteresis))}); "
                                     "give each story once")
                given.add(int(story))
                models[int(story) - 1] = model
        elif isinstance(hysteresis, (list, tuple)):
            if len(hysteresis) != stories:
                raise ValueError(f"hysteresis has {len(hysteresis)} entries for {stories} stories")
            models = list(hysteresis)
        else:
            raise ValueError("hysteresis must be a sequence with one model (or None) per story, or a dict "
                             f"{{story: model}}, got {type(hysteresis).__name__}")
        for story, model in enumerate(models, start=1):
            if model is not None and not isinstance(model, STORY_MODELS):
                raise ValueError(f"hysteresis of story {story} must be Bilinear, BoucWen or None, "
                                 f"got {type(model).__name__}")
        return None if all(model is None for model in models) else tuple(models)

    @property
    def is_linear(self) -> bool:
        """True when every story is elastic (its devices aside: :attr:`devices_linear`)."""
        return self.hysteresis is None

    @property
    def devices_linear(self) -> bool:
        """True when every device's force is linear in its motion: walls of fixed parameters and linear fluid
        viscous dampers (a wall that heats, follows its amplitude or fails is stepped as linear within each
        step, its coefficients changing between steps)."""
        return all(device.linear for _, device in self.other_device_list)

    @property
    def story_models(self) -> tuple[Bilinear | BoucWen | None, ...]:
        """The story model of every story (None: linear)."""
        return self.hysteresis if self.hysteresis is not None else (None,) * self.stories

    @cached_property
    def geometric_stiffness(self) -> np.ndarray:
        """-P/h per story (N/mm): the linearised P-Delta stiffness (zeros without gravity loads)."""
        if self.gravity_loads is None:
            return _read_only(np.zeros(self.stories))
        return _read_only(-np.asarray(self.gravity_loads) / np.asarray(self.story_heights))

    @cached_property
    def yield_drifts(self) -> np.ndarray:
        """F_y / k0 per story (mm); 0 for a linear story."""
        return _read_only(np.array([0.0 if model is None else model.yield_force / k
                                    for model, k in zip(self.story_models, self.stiffnesses, strict=True)]))

    # ------------------------------------------------------------------ matrices (tonne, N/mm, N*s/mm)
    @property
    def stories(self) -> int:
        return len(self.masses)

    @cached_property
    def mass_matrix(self) -> np.ndarray:
        """Diagonal mass matrix, tonne."""
        return _read_only(np.diag(self.masses))

    @cached_property
    def stiffness_matrix(self) -> np.ndarray:
        """Bare-frame stiffness matrix, N/mm."""
        return _read_only(story_matrix(np.asarray(self.stiffnesses)))

    @cached_property
    def _modes(self) -> tuple[np.ndarray, np.ndarray]:
        eigenvalues, shapes = eigh(self.stiffness_matrix, self.mass_matrix)
        return _read_only(np.sqrt(self._checked_squares(eigenvalues))), _read_only(shapes)

    def _checked_squares(self, squares: np.ndarray) -> np.ndarray:
        """``squares`` (w^2, rad^2/s^2), or a ValueError naming the masses and stiffnesses if one is not finite
        and > 0 (a rounding eigenvalue of an ill-conditioned frame: its period would be NaN)."""
        bad = ~(np.isfinite(squares) & (squares > 0.0))
        if bad.any():
            raise ValueError(f"the frame's eigenproblem K phi = w^2 M phi gave w^2 = {show(squares[bad][0])} rad^2/s^2 "
                             f"(not finite and > 0) for masses {_span(self.masses, 't')} and stiffnesses "
                             f"{_span(self.stiffnesses, 'N/mm')}: double precision cannot resolve it")
        return squares

    @property
    def circular_frequencies(self) -> np.ndarray:
        """Bare-frame circular frequencies, rad/s, ascending."""
        return self._modes[0]

    @property
    def periods(self) -> np.ndarray:
        """Bare-frame periods, s, longest first."""
        return 2.0 * np.pi / self._modes[0]

    @property
    def mode_shapes(self) -> np.ndarray:
        """Bare-frame mode shapes as columns, mass-normalised (phi^T M phi = I), 1/sqrt(tonne)."""
        return self._modes[1]

    def lowest_circular_frequencies(self, count: int) -> np.ndarray:
        """The ``count`` lowest bare-frame circular frequencies, rad/s, ascending, without the full
        eigendecomposition: with M diagonal, K_frame phi = w^2 M phi is the symmetric tridiagonal problem
        M^-1/2 K_frame M^-1/2 psi = w^2 psi, whose lowest eigenvalues bisection finds (LAPACK stebz through
        scipy.linalg.eigh_tridiagonal) in O(n) memory and O(n count) work.  The tolerance is the smallest
        float's, so the bisection runs to the Sturm counts' own accuracy (agrees with the dense
        :attr:`circular_frequencies` to about 1e-14 at 10 stories, 1e-10 at 1 000)."""
        count = whole_number("count", count, 1)
        if count > self.stories:
            raise ValueError(f"count must be at most the {self.stories} modes, got {count}")
        # Masses and stiffnesses taken relative to their largest, the squares scaled back after: the
        # bisection's tolerance and Sturm counts work on numbers near 1 (masses of 1e308 t made its entries
        # 1e-303, where they lost their digits).
        masses, k = np.asarray(self.masses), np.asarray(self.stiffnesses)
        mass_unit, stiffness_unit = float(masses.max()), float(k.max())
        scale = 1.0 / np.sqrt(masses / mass_unit)
        k = k / stiffness_unit
        diagonal = (k + np.append(k[1:], 0.0)) * scale**2
        off = -k[1:] * scale[:-1] * scale[1:]
        squares = eigh_tridiagonal(diagonal, off, eigvals_only=True, select="i", select_range=(0, count - 1),
                                   tol=np.finfo(float).tiny)
        squares = self._checked_squares(np.asarray(squares))
        return _read_only(np.sqrt(squares) * np.sqrt(stiffness_unit / mass_unit))

    @cached_property
    def rayleigh_coefficients(self) -> tuple[float, float]:
        """(a0 in 1/s, a1 in s) of C = a0 M + a1 K_frame (the two damping modes' frequencies from
        :meth:`lowest_circular_frequencies`: no dense eigendecomposition)."""
        i, j = self.damping_modes
        lowest = self.lowest_circular_frequencies(max(i, j))
        wi, wj = lowest[i - 1], lowest[j - 1]
        zeta = self.damping_ratio
        return 2.0 * zeta * wi * wj / (wi + wj), 2.0 * zeta / (wi + wj)

    @cached_property
    def damping_matrix(self) -> np.ndarray:
        """Inherent damping matrix, N*s/mm: Rayleigh a0 M + a1 K_frame, or modal M Phi diag(2 zeta omega) Phi^T M."""
        if self.damping_model == "modal":
            shapes = self.mode_shapes
            modal = self.mass_matrix @ shapes
            return _read_only(modal @ np.diag(2.0 * self.damping_ratio * self.circular_frequencies) @ modal.T)
        a0, a1 = self.rayleigh_coefficients
        # Filled by its three diagonals: one n x n array, no dense M or K beside it.
        n, k = self.stories, np.asarray(self.stiffnesses)
        matrix = np.zeros((n, n))
        index = np.arange(n)
        matrix[index, index] = a0 * np.asarray(self.masses) + a1 * (k + np.append(k[1:], 0.0))
        matrix[index[:-1], index[1:]] = matrix[index[1:], index[:-1]] = -a1 * k[1:]
        return _read_only(matrix)

    @cached_property
    def story_damping_matrix(self) -> np.ndarray:
        """The part of the damping matrix whose forces pass through the stories, N*s/mm: a1 K_frame for
        Rayleigh damping (a0 M acts between the floors and the ground), all of C for modal damping.
        Its story forces are resolved as B^-T C_s v, so that story 1's is the damping force in the base."""
        if self.damping_model == "modal":
            return self.damping_matrix
        return _read_only(self.rayleigh_coefficients[1] * self.stiffness_matrix)

    @property
    def damping_description(self) -> str:
        """The inherent damping in words, e.g. "5 % Rayleigh on modes 1 and 2, with the initial story stiffness
        (walls and P-Delta excluded)": an assumption of every analysis, for outputs to state."""
        percent = f"{100 * self.damping_ratio:g} %"
        if self.damping_model == "modal":
            return f"{percent} in every mode of the bare elastic frame (modal)"
        first, second = self.damping_modes
        modes = f"mode {first}" if first == second else f"modes {first} and {second}"
        return f"{percent} Rayleigh on {modes}, with the initial story stiffness (walls and P-Delta excluded)"

    @cached_property
    def story_damping_row(self) -> np.ndarray:
        """1^T C_s, N*s/mm per mm/s of each floor's velocity: the damping force through story 1
        (:attr:`story_damping_matrix`'s column sums), found from the diagonals for Rayleigh damping."""
        if self.damping_model == "modal":
            return _read_only(self.story_damping_matrix.sum(axis=0))
        a1, k = self.rayleigh_coefficients[1], np.asarray(self.stiffnesses)
        upper = -a1 * k[1:]  # C_s[j - 1, j] = C_s[j, j - 1]
        row = a1 * (k + np.append(k[1:], 0.0))
        row[1:] += upper
        row[:-1] += upper
        return _read_only(row)

    @property
    def damping_ratios(self) -> np.ndarray:
        """Inherent damping ratio of every bare-frame mode (-), from C: a0 / (2 w) + a1 w / 2 for Rayleigh."""
        if self.damping_model == "modal":
            return np.full(self.stories, self.damping_ratio)
        a0, a1 = self.rayleigh_coefficients
        w = self.circular_frequencies
        return a0 / (2.0 * w) + a1 * w / 2.0

    @cached_property  # once a building: read in per-story loops (a 10 000-story table was O(n^2))
    def walls(self) -> dict[int, tuple[Wall | StrainDependentDamper, ...]]:
        """{story: its walls} (FDMK walls among :attr:`devices`), stories ascending."""
        walls = {story: tuple(cast("Wall | StrainDependentDamper", d) for d in devices if is_wall(d))
                 for story, devices in self.devices.items()}
        return {story: group for story, group in walls.items() if group}

    @property
    def wall_list(self) -> list[tuple[int, Wall | StrainDependentDamper]]:
        """(story, wall) for every wall, stories ascending."""
        return [(story, wall) for story, walls in self.walls.items() for wall in walls]

    @property
    def device_list(self) -> list[tuple[int, Device]]:
        """(story, device) for every device, walls included, stories ascending."""
        return [(story, device) for story, devices in self.devices.items() for device in devices]

    @property
    def other_device_list(self) -> list[tuple[int, Device]]:
        """(story, device) for every device that is not a wall (fluid viscous, friction: the kinds of
        :mod:`vdw_frames.element.devices`), stories ascending: the columns of a result's device histories."""
        return [(story, device) for story, device in self.device_list if not is_wall(device)]

    @property
    def strain_dependent(self) -> bool:
        """True when some wall is a :class:`StrainDependentDamper` (parameters that follow its strain amplitude)."""
        return any(isinstance(wall, StrainDependentDamper) for _, wall in self.wall_list)

    def walls_at(self, strain: float | None = None) -> ShearBuilding:
        """This building with each strain-dependent wall fixed at the amplitude ``strain`` (dimensionless;
        3.0 = 300 %), or with None at the centre, in logarithm, of its own identified range
        (:attr:`~vdw_frames.StrainDependentDamper.centre_strain`); thermal description and limits kept,
        other walls unchanged.

        What a frequency-domain analysis (modal damping, sizing, a period) of amplitude-following walls
        needs: one amplitude.  Clamped to each wall's identified range with a ``UserWarning``.
        """
        def fixed(wall: Wall | StrainDependentDamper) -> Wall:
            if not isinstance(wall, StrainDependentDamper):
                return wall
            return wall.at(wall.centre_strain if strain is None else strain)

        return self.with_walls({story: tuple(fixed(wall) for wall in walls) for story, walls in self.walls.items()})

    def without_devices(self) -> ShearBuilding:
        """The bare frame: the same stories, P-Delta and damping, with no device."""
        return dataclasses.replace(self, devices={})

    def without_walls(self) -> ShearBuilding:
        """The same frame with its walls removed (its other devices kept: :meth:`without_devices` is the bare
        frame)."""
        return self.with_walls({})

    def with_walls(self, walls: dict[int, tuple[Wall | StrainDependentDamper, ...]]) -> ShearBuilding:
        """The same frame with ``walls`` (a dict as for the constructor) instead of its own walls; its other
        devices are kept, on their stories, after the walls."""
        return dataclasses.replace(self, devices=_walls_replaced(self.devices, walls))

    def without_nonlinear_devices(self) -> ShearBuilding:
        """The same building without its devices whose stiffness depends on their amplitude (nonlinear fluid
        viscous dampers, friction dampers): what a period that must not depend on an amplitude is computed with
        (an FVD adds no static stiffness; a friction damper's elastic stiffness before it slips is left out, so
        the period is that of the frame while they slip)."""
        kept = {story: tuple(d for d in devices if is_wall(d) or d.linear)
                for story, devices in self.devices.items()}
        return dataclasses.replace(self, devices={story: group for story, group in kept.items() if group})

    def with_devices(self, devices: dict[int, tuple[Device, ...]]) -> ShearBuilding:
        """The same frame with ``devices`` (a dict as for the constructor) instead of all of its own."""
        return dataclasses.replace(self, devices=devices)

    def frequency_response(self, frequency: ArrayLike) -> np.ndarray:
        """Relative floor displacement per unit ground acceleration, mm/(mm/s^2), shape (len(f), floors).

        Solves (-w^2 M + i w C + K + K_G + K_d(w)) U = -M 1 at w = 2 pi f for frequencies f in Hz (a
        scalar or a 1-D array, finite, >= 0), with each wall's exact complex stiffness (G*(i w) area /
        thickness, eqs. (3)-(5), in series with its support if any) times its magnification^2, each
        linear device's ``story_stiffness(f)`` and the P-Delta stiffness K_G: the linear
        (initial-stiffness) building.
        Strain-dependent walls are refused (their stiffness depends on the amplitude): use the
        equivalent-linear building ``simulate(..., strain_compatible=True).building`` or walls
        ``wall.at(strain)``.  ValueError, naming the frequency, where the system is singular (an
        undamped frame at a natural frequency: the response is unbounded) or the result overflows; and,
        naming the story, when the frame is unstable under its gravity loads (P/h at or above a story's
        stiffness at rest: no steady response exists, as :func:`~vdw_frames.modal_analysis` refuses too).
        """
        require_fixed_walls(self, "frequency_response()")
        require_linear_devices(self, "frequency_response()")
        require_stable_under_gravity(self, "frequency_response()")
        frequency = finite_array("frequency", frequency, ndim=None)
        if frequency.ndim > 1:
            raise ValueError(f"frequency must be a scalar or 1-dimensional, got shape {frequency.shape}")
        frequency = np.atleast_1d(frequency)
        if (frequency < 0).any():
            raise ValueError(f"frequency must be >= 0 Hz, got {show(frequency[frequency < 0][0])}")
        response = np.empty((frequency.size, self.stories), dtype=complex)
        for start in range(0, frequency.size, _FREQUENCY_CHUNK):  # chunks bound the (f, n, n) stack
            chunk = slice(start, start + _FREQUENCY_CHUNK)
            response[chunk] = self._solve_dynamic(frequency[chunk])
        return response

    def _solve_dynamic(self, frequency: np.ndarray) -> np.ndarray:
        with np.errstate(over="ignore", invalid="ignore"):
            omega = 2.0 * np.pi * frequency
            if not np.isfinite(omega).all():
                raise ValueError(f"the dynamic stiffness overflows at f = {show(frequency[~np.isfinite(omega)][0])} Hz")
            per_story = np.zeros((omega.size, self.stories), dtype=complex)
            # Fixed walls only (frequency_response checked): no strain-dependent wall.
            for story, wall in cast("list[tuple[int, Wall]]", self.wall_list):  # magnification^2 K(i omega)
                per_story[:, story - 1] += wall.magnification**2 * wall.stiffness_transfer(1j * omega)
            for story, device in self.other_device_list:  # linear (frequency_response checked)
                per_story[:, story - 1] += device.story_stiffness(frequency)
            base = self.stiffness_matrix + story_matrix(np.asarray(self.geometric_stiffness, dtype=float))
            dynamic = (story_matrix(per_story) + base - (omega**2)[:, None, None] * self.mass_matrix
                       + (1j * omega)[:, None, None] * self.damping_matrix)
        finite = np.isfinite(dynamic).all(axis=(1, 2))
        if not finite.all():
            raise ValueError(f"the dynamic stiffness overflows at f = {show(frequency[~finite][0])} Hz")
        # Only a frame without damping (no imaginary part) can be singular, at a natural frequency;
        # there the result has no correct digit once cond * eps reaches 1e-2.
        undamped = np.flatnonzero(~np.any(dynamic.imag, axis=(1, 2)))
        if undamped.size:
            with np.errstate(divide="ignore", invalid="ignore"):
                condition = np.linalg.cond(dynamic[undamped].real)
            singular = undamped[~(condition < 1e-2 / np.finfo(float).eps)]
            if singular.size:
                raise ValueError(f"the frame has no bounded steady response at f = {show(frequency[singular[0]])} Hz: "
                                 f"without damping, that is a natural frequency (the dynamic stiffness is "
                                 f"singular there)")
        load = np.broadcast_to(-np.asarray(self.masses, dtype=complex), (omega.size, self.stories))
        response = np.linalg.solve(dynamic, load[..., None])[..., 0]
        finite = np.isfinite(response).all(axis=1)
        if not finite.all():
            raise ValueError(f"the frequency response overflows at f = {show(frequency[~finite][0])} Hz")
        return response

    def stationary_response(self, ground_acceleration: ArrayLike, dt: float, pad_factor: int = 8) -> np.ndarray:
        """Relative displacements (mm, steps x floors) from the frequency-domain solution (FFT).

        ``ground_acceleration`` (mm/s^2, sampled every ``dt`` s, dt > 0) is zero padded to
        ``pad_factor`` (a whole number >= 1) times its length; the result is the exact continuous
        response of the linear frame with FDMK dampers to the band-limited input, up to the wrap-around
        of what remains of the response after the padding.  Useful for stationary (e.g. harmonic or
        long random) excitation and as a check of :func:`simulate`.  A padded length whose arrays would
        exceed the 2 GiB memory limit is refused before allocating.
        """
        ground = finite_array("ground_acceleration", ground_acceleration)
        dt = positive("dt", dt)
        pad_factor = whole_number("pad_factor", pad_factor, 1)
        size = pad_factor * ground.size
        # Per frequency: the complex dynamic stiffness (floors^2) and response; plus the real FFTs.
        check_memory(f"stationary_response (pad_factor = {pad_factor}, {ground.size} samples)", size,
                     8 * (self.stories**2 + 4 * self.stories + 4), "use a smaller pad_factor")
        spectrum = np.fft.rfft(ground, size)
        response = self.frequency_response(np.fft.rfftfreq(size, dt))
        return np.fft.irfft(response * spectrum[:, None], size, axis=0)[: ground.size]


class _OwnDevices(dict):
    """A building's normalised ``devices``: what ``dataclasses.replace(building, walls=...)`` passes back as
    ``devices=`` beside the deprecated keyword (then the walls replace its walls), told apart from devices
    a caller gives with ``walls=`` (refused)."""


def _walls_replaced(devices: dict[int, tuple[Device, ...]], walls: object) -> dict[Any, tuple[Any, ...]]:
    """``walls`` (a dict as for the constructor) in place of the walls among ``devices``; the other devices
    kept, on their stories, after the walls."""
    if not isinstance(walls, dict):
        raise ValueError(f"walls must be a dict {{story: wall or list}}, got {type(walls).__name__}")
    merged: dict[Any, list[Any]] = {}
    for story, entry in walls.items():
        merged.setdefault(story, []).extend(entry if isinstance(entry, (list, tuple)) else (entry,))
    for story, group in devices.items():
        for device in group:
            if not is_wall(device):
                key = next((k for k in merged if k == story), story)
                merged.setdefault(key, []).append(device)
    return {story: tuple(group) for story, group in merged.items()}


def static_wall_stiffness(building: ShearBuilding) -> np.ndarray:
    """The walls' static (zero-frequency) stiffness summed per story, N/mm: magnification^2 K(s = 0) of every
    wall (G1 A / h, in series with its support for a SupportedDamper; 0 for a Maxwell-only wall).  A wall that
    follows its strain amplitude counts as at rest, with the G1 of its lowest amplitude node (where a
    time-history analysis starts it): its static stiffness at larger strains is not part of the model."""
    stiffness = np.zeros(building.stories)
    for story, wall in building.wall_list:
        if isinstance(wall, StrainDependentDamper):
            along = wall.G1[0] * wall.stiffness_scale
        else:
            along = float(np.real(wall.stiffness_transfer(0.0)))
        stiffness[story - 1] += wall.magnification**2 * along  # the story sees magnification^2 x the wall's
    return stiffness


def is_wall(device: object) -> bool:
    """Whether ``device`` is an FDMK wall (stepped by the walls' bank)."""
    return isinstance(device, (*WALL_TYPES, StrainDependentDamper))


def require_stable_under_gravity(building: ShearBuilding, analysis: str) -> None:
    """ValueError naming the story when a story's P-Delta stiffness -P/h cancels its stiffness at rest
    (k0 plus its walls' K(s = 0), :func:`static_wall_stiffness`): the linear frame is then unstable under its
    own gravity loads, with no modes and no bounded response, whatever the record.  (Per story suffices:
    K + K_G + walls = B^T diag(story totals) B with B the invertible difference matrix, positive definite
    exactly when every story total is positive.)"""
    if building.gravity_loads is None:
        return
    at_rest = np.array(building.stiffnesses, dtype=float) + static_wall_stiffness(building)
    unstable = np.flatnonzero(at_rest + np.asarray(building.geometric_stiffness) <= 0.0)
    if unstable.size:
        story = int(unstable[0])
        raise ValueError(f"{analysis}: the frame is unstable under its gravity loads: story {story + 1}'s P/h = "
                         f"{-building.geometric_stiffness[story]:.6g} N/mm is not below its stiffness at rest "
                         f"(k0 and walls) {at_rest[story]:.6g} N/mm (P-Delta exceeds the story stiffness)")


def require_fixed_walls(building: ShearBuilding | None, analysis: str) -> None:
    """ValueError when ``building`` has strain-dependent walls, which ``analysis`` cannot take."""
    if isinstance(building, ShearBuilding) and building.strain_dependent:
        raise ValueError(f"{analysis} needs fixed wall parameters, but this building has strain-dependent walls "
                         "(StrainDependentDamper), whose parameters follow their amplitude: give each wall its "
                         "parameters at one strain amplitude with wall.at(strain), or analyse in time (simulate "
                         "follows the amplitude; strain_compatible=True iterates an equivalent-linear building)")


def require_linear_devices(building: ShearBuilding, analysis: str) -> None:
    """ValueError naming the first device that is not linear (a nonlinear FVD, a friction damper), which
    ``analysis`` cannot take without an amplitude to linearise it at."""
    for story, device in building.other_device_list:
        if not device.linear:
            raise ValueError(f"{analysis} needs linear devices, but story {story} has a {device.describe()}, whose "
                             "stiffness depends on its amplitude: analyse in time (simulate), or linearise it at an "
                             "amplitude (modal_analysis(..., drift_amplitude=...))")


def _span(values: ArrayLike, unit: str) -> str:
    """'a ... b unit' (smallest ... largest), or 'a unit' when all are equal: for messages."""
    array = np.asarray(values, dtype=float)
    low, high = float(array.min()), float(array.max())
    return f"{show(low)} {unit}" if low == high else f"{show(low)} ... {show(high)} {unit}"


def _check_eigenproblem(masses: np.ndarray, stiffnesses: np.ndarray) -> None:
    """Refuse story ``stiffnesses`` (N/mm) the double-precision eigenproblem K phi = w^2 M phi cannot resolve:
    a spread (largest / smallest) above :data:`MAX_STIFFNESS_RATIO`, or, with the ``masses`` (tonne), circular
    frequencies squared above :data:`MAX_FREQUENCY_SQUARED` or below the float range (bounded above by
    Gershgorin's circles of M^-1/2 K M^-1/2, a few times the largest w^2, and below by Dunkerley's
    1 / trace(K^-1 M), at least 1/n times the smallest)."""
    k, m = stiffnesses, masses
    softest, stiffest = int(np.argmin(k)), int(np.argmax(k))
    with np.errstate(over="ignore"):
        ratio = k[stiffest] / k[softest]
    if not ratio <= MAX_STIFFNESS_RATIO:
        raise ValueError(
            f"stiffnesses span a ratio of {ratio:.3g} (story {softest + 1}: {show(k[softest])} N/mm, story "
            f"{stiffest + 1}: {show(k[stiffest])} N/mm), more than {MAX_STIFFNESS_RATIO:.0e}: double precision "
            "cannot resolve the frame's lowest frequencies (they lose about 2.2e-16 times the ratio of their digits; "
            "real story stiffnesses span less than 1e4)")
    with np.errstate(over="ignore", under="ignore", divide="ignore"):
        coupling = k[1:] / np.sqrt(m[:-1]) / np.sqrt(m[1:])  # |off-diagonal| of M^-1/2 K M^-1/2
        circles = (k + np.append(k[1:], 0.0)) / m + np.append(coupling, 0.0) + np.append(0.0, coupling)
        highest = float(circles.max())
        flexibility = np.cumsum(1.0 / k)  # floor j's deflection under a unit load there, mm/N
        lowest = float(1.0 / np.sum(m * flexibility))
    if not highest <= MAX_FREQUENCY_SQUARED:
        raise ValueError(f"masses {_span(m, 't')} and stiffnesses {_span(k, 'N/mm')} give circular frequencies "
                         f"squared (k/m) up to {highest:.3g} rad^2/s^2, beyond the {MAX_FREQUENCY_SQUARED:.0e} the "
                         "complex-mode search resolves (a validation bound: real buildings stay below 1e7)")
    if not lowest >= np.finfo(float).tiny:
        raise ValueError(f"masses {_span(m, 't')} and stiffnesses {_span(k, 'N/mm')} give circular frequencies "
                         "squared (k/m) below the smallest normal double (2.2e-308 rad^2/s^2)")


def _read_only(array: np.ndarray) -> np.ndarray:
    # Cached once per building: nobody may change them behind the validated inputs.
    array.flags.writeable = False
    return array


def story_matrix(per_story: np.ndarray) -> np.ndarray:
    """Assemble story springs (story k between floors k-1 and k, floor 0 the ground) into a matrix
    (a stack of matrices for leading axes: (..., n) -> (..., n, n))."""
    n = per_story.shape[-1]
    matrix = np.zeros((*per_story.shape, n), dtype=per_story.dtype)
    diagonal, upper = np.arange(n), np.arange(n - 1)
    matrix[..., diagonal, diagonal] = per_story
    matrix[..., upper, upper] += per_story[..., 1:]
    matrix[..., upper, upper + 1] = -per_story[..., 1:]
    matrix[..., upper + 1, upper] = -per_story[..., 1:]
    return matrix
