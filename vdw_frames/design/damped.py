"""A damped structure by ASCE 7-16 Chapter 18: the reduced frame, the devices, and the verification loop.

:func:`design_damped` goes from a site to a verified design (issue 31, part 2):

1. **The undamped frame** (:func:`~vdw_frames.design.elf.design_frame` at ``strength_scale`` 1): the Chapter 12
   seismic base shear V, kept for the record (:attr:`DampedDesign.undamped`).
2. **The devices** (:func:`~vdw_frames.design.size_devices`, ``distribution`` "stiffness" by default) sized on
   the bare frame for ``target_damping`` in mode 1 at the **MCE_R amplitude estimate**: the story drift
   amplitudes of mode 1 under the site's MCE_R spectrum at T_1 reduced by B at the target damping,

       Delta_i = Gamma_1 |phi_i - phi_(i-1)| S_aM(T_1) / B(beta_target) (T_1 / 2 pi)^2      (mm)

   with phi_1 and Gamma_1 = phi^T M 1 / phi^T M phi the bare frame's undamped first mode (initial stiffness with
   P-Delta), T_1 = 2 pi / |s_1| of the damped pole (complex modal analysis) and S_aM the MCE_R spectrum
   (:meth:`~vdw_frames.verification.Site.spectral_acceleration`).  It is an ESTIMATE (one mode, the elastic
   frame, B in place of a response history); nonlinear devices are linearised at it, and sizing and amplitude
   are iterated until the amplitudes change by less than :data:`AMPLITUDE_TOLERANCE` (relative), at most
   :data:`AMPLITUDE_ITERATIONS` times (the result says if that bound stopped it).  Linear devices (walls,
   alpha = 1 FVDs) do not depend on it; it is then reported only.
3. **B_V+I and V_min.**  The effective damping beta_V+I of mode 1 is the complex-mode ratio -Re s_1 / |s_1| of
   the frame with its devices at that amplitude (:func:`~vdw_frames.modal_analysis`), the inherent damping
   included.  ASCE 7-16 defines B_V+I (Sec. 18.1.3, read) at "the sum of viscous damping in the fundamental
   mode ... beta_V1, plus inherent damping, beta_I"; its Sec. 18.7 alternative procedures compute beta_V1 from
   the devices' energy per cycle W_D / (4 pi W_S) in the fundamental mode at the design displacement (as
   recalled, not read).  The complex mode gives that ratio exactly for linear viscous and viscoelastic devices
   (for one story, W_D / (4 pi W_S) exactly) and for nonlinear ones the FEMA 356 energy-equivalent
   linearisation; taken here at the MCE_R amplitude, not the design earthquake's (2/3 of it), which for an FVD
   with alpha < 1 gives less damping, so a smaller B and a larger V_min (conservative).  The frame's
   hysteretic damping (beta_H) is not included (the modal analysis is elastic).  B_V+I from Table 18.7-1
   (:func:`~vdw_frames.asce7.damping_coefficient`; a round whose T_1 is below T_0, outside the table's heading,
   says so in the assumptions: :func:`short_period_note`), V_min = max(V / B_V+I, 0.75 V) or 1.0 V where the user
   states the structure is irregular (Sec. 18.2.1.1, :func:`~vdw_frames.asce7.minimum_base_shear`).
4. **The reduced frame**: :func:`design_frame` again with ``strength_scale = V_min / V`` (strengths scaled; the
   stiffness that the drift limit requires is the one design_frame states), the sized devices put on it.
5. **The verification**: :func:`~vdw_frames.verification.verify` (Chapters 16 and 18: the scaled suite, nominal,
   upper and lower bound) from the candidate records long enough for the round's period range (records
   shorter than 5 x T_upper, which :func:`~vdw_frames.verification.scaled_suite` refuses, are left out of the
   selection and the assumptions say how many), and the **device limits**: ``device_limits`` (below) and the walls' own
   :class:`~vdw_frames.element.limits.WallLimits` (strain, stress, temperature), each against the
   verification's largest demand over the suite and the bounds (:attr:`VerificationResult.walls`,
   :attr:`VerificationResult.devices`).
6. **The iteration** (at most ``rounds`` verifications): when the verification or a device limit fails,

   * the devices are enlarged: the next round's target damping is the last one + :data:`TARGET_STEP`;
   * the frame is stiffened too, by :data:`STIFFNESS_STEP` (every story's stiffness at least that times the
     round's, through design_frame's ``minimum_stiffness``), when devices alone cannot pass: a device limit
     failed, the last enlargement cut the largest drift statistic over its limit by less than
     :data:`STALL_FRACTION`, or the target is out of reach.  A wall's added damping has a maximum
     (:func:`~vdw_frames.design.size_devices` finds it): a target beyond it is kept as the goal, and the round's
     devices are sized for the bare ratio + :data:`REACH_FRACTION` of the largest added damping (stated in the
     round).

   Every :class:`DesignRound` records what changed, why, and the verification's numbers.  When no round
   passes, :attr:`DampedDesign.failure` names each failed criterion or limit and by how much (demand / limit).
7. **FEMA P695** (optional, ``p695``): :func:`~vdw_frames.assessment.collapse_assessment` of the final design
   with device failure counted (the walls as designed, with their :class:`WallLimits`, a wall's failure counted
   as collapse: ``CollapseCriterion(wall_failure=True)``) and without (the same walls without limits, which
   never fail).  FVDs and friction dampers have no failure model here: for them one assessment serves both and
   the report says so.  One archetype is not a P695 system qualification (the report says so).

The walls' own :class:`~vdw_frames.element.limits.WallLimits` are checked too: strain, bond stress (peak force /
area, MPa) and temperature (the peak rise against the limit less the wall's temperature at rest, K).

``device_limits``: a dict of limits, any of ``"stroke"`` (mm: every device's largest deformation along itself;
a wall's is strain x thickness), ``"velocity"`` (mm/s: every device's largest velocity), ``"strain"`` (-: walls,
in addition to their own WallLimits strain) and ``"temperature_rise"`` (K: walls that heat).  Demands are the
largest over the suite and the three property bounds.

Units: N, mm, s, tonne; damping ratios -, drift ratios -, times s.
"""

from __future__ import annotations

import concurrent.futures
import dataclasses
import time
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import eigh

from .._validation import finite_scalar, positive, show, whole_number
from ..asce7.damping import damping_coefficient, minimum_base_shear
from ..element.device import Device
from ..frame.building import ShearBuilding, is_wall, story_matrix
from ..frame.modal import linearisation_notes, modal_analysis, nonlinear_devices
from ..motion.record import G, GroundMotion
from ..verification.spectrum import Site
from ..verification.suite import MIN_CYCLES, period_range
from ..verification.verify import PropertyBounds, VerificationResult, verify
from .elf import FrameDesign, design_frame
from .sizing import DISTRIBUTIONS, DeviceSizing, _Sizer, _solve

TARGET_STEP = 0.05
"""Added to the target damping ratio when a round fails (this package's rule)."""
STIFFNESS_STEP = 1.5
"""Factor on every story's stiffness when devices alone cannot pass (this package's rule)."""
MAX_ROUNDS = 10
"""Most verification rounds :func:`design_damped` takes (each is 3 x 11 or more response histories)."""
STALL_FRACTION = 0.10
"""Devices alone are taken not to pass when an enlargement cut the largest drift statistic over its limit by less
than this fraction (this package's rule): the frame is stiffened too."""
REACH_FRACTION = 0.90
"""Where the target damping is out of reach, the devices are sized for the bare ratio + this fraction of the largest
achievable added damping (this package's rule; at the maximum itself the devices' size is ill-determined)."""
AMPLITUDE_TOLERANCE = 0.01
"""Sizing and the MCE_R amplitude estimate are iterated until the amplitudes change by less than this (relative)."""
AMPLITUDE_ITERATIONS = 20
"""Most sizing-amplitude iterations."""
DEVICE_LIMITS = {"stroke": "mm", "velocity": "mm/s", "strain": "-", "temperature_rise": "K"}
"""The keys of ``device_limits`` and their units (module docstring)."""
COLLAPSE_KEYS = ("with device failure", "without device failure")
"""The keys of :attr:`DampedDesign.collapse`."""


@dataclass(frozen=True)
class LimitCheck:
    """One device limit against its demand: ``limit`` (the key of :data:`DEVICE_LIMITS`, or "strain (WallLimits)"),
    ``where`` (device and story), ``demand`` and ``value`` (the limit) in the key's unit, ``ratio`` = demand /
    value (> 1: exceeded)."""

    limit: str
    where: str
    demand: float
    value: float

    @property
    def ratio(self) -> float:
        # inf where nothing is allowed (a wall at rest at or above its temperature limit)
        return self.demand / self.value if self.value > 0.0 else float("inf")

    @property
    def passed(self) -> bool:
        return self.demand <= self.value

    def text(self) -> str:
        unit = {**DEVICE_LIMITS, "stress": "MPa"}.get(self.limit.split(" ")[0], "-")
        unit = "" if unit == "-" else f" {unit}"
        return (f"{self.limit} of {self.where}: demand {self.demand:.4g} vs limit {self.value:.4g}{unit} "
                f"(ratio {self.ratio:.3f})")


@dataclass(frozen=True)
class DesignRound:
    """One round of :func:`design_damped`.

    ``number`` (1-based); ``change``: what changed from the last round and why (round 1: the starting design);
    ``target_damping`` (-), ``stiffness_factor`` (-, on every story's stiffness of the Chapter 12 design);
    ``devices``: the sized devices in words; ``drift_amplitudes`` (mm per story, the MCE_R estimate);
    ``effective_damping`` (-), ``b_v_plus_i`` (-), ``v`` and ``v_min`` (N), ``v_min_rule``; the verification's
    numbers: ``drift_statistic`` (-, the largest over stories and bounds), ``drift_limit`` (-), ``unacceptable``
    (count per case name), ``allowed_unacceptable``; ``device_peaks``: the largest demands (name -> value: walls'
    strain -, deformation mm, velocity mm/s, temperature rise K; other devices' deformation mm, velocity mm/s,
    force N); ``limits``: each :class:`LimitCheck`; ``passed``; ``seconds`` (the verification's time);
    ``failed``: each failed criterion or limit with by how much (empty when the round passed); ``left_out``: the
    names of the candidate records too short for the round's period range (left out of its selection)."""

    number: int
    change: str
    target_damping: float
    stiffness_factor: float
    devices: str
    drift_amplitudes: np.ndarray
    effective_damping: float
    b_v_plus_i: float
    v: float
    v_min: float
    v_min_rule: str
    drift_statistic: float
    drift_limit: float
    unacceptable: dict[str, int]
    allowed_unacceptable: int
    device_peaks: dict[str, float]
    limits: tuple[LimitCheck, ...]
    passed: bool
    seconds: float
    failed: tuple[str, ...] = ()
    left_out: tuple[str, ...] = ()


@dataclass(frozen=True)
class DampedDesign:
    """The result of :func:`design_damped` (module docstring for each step).

    ``frame``: the reduced SFRS of the final round (:class:`~vdw_frames.design.elf.FrameDesign`); ``undamped``:
    the same frame at 1.0 V (the record); ``building``: the final frame with its devices; ``sizing``: the final
    :class:`~vdw_frames.design.DeviceSizing`; ``effective_damping`` (-), ``b_v_plus_i`` (-), ``v_min`` (N),
    ``v_min_rule``; ``drift_amplitudes`` (mm per story: the MCE_R estimate of the final round); ``rounds``;
    ``verification`` (the final :class:`~vdw_frames.verification.VerificationResult`); ``passed``; ``failure``
    (None, or which criteria and limits failed and by how much); ``collapse``: None, or
    :data:`COLLAPSE_KEYS` -> :class:`~vdw_frames.assessment.CollapseAssessment` (one object under both keys where
    the devices have no failure model); ``timings`` (part -> s); ``assumptions``; ``device_limits``.
    """

    frame: FrameDesign
    undamped: FrameDesign
    building: ShearBuilding
    sizing: DeviceSizing
    effective_damping: float
    b_v_plus_i: float
    v_min: float
    v_min_rule: str
    drift_amplitudes: np.ndarray
    rounds: tuple[DesignRound, ...]
    verification: VerificationResult
    passed: bool
    failure: str | None
    collapse: dict[str, Any] | None
    timings: dict[str, float]
    assumptions: tuple[str, ...]
    device_limits: dict[str, float]

    def report(self) -> str:
        """The Chapter 18 part of a design note, markdown: the reduction, the devices, every round, P695, times."""
        undamped, frame = self.undamped, self.frame
        lines = ["## Chapter 18: the damped structure", "",
                 f"- Chapter 12 base shear of the frame without dampers V = {undamped.base_shear / 1e3:.1f} kN "
                 f"(C_s = {undamped.cs:.4f}, Eq. {undamped.cs_equation}).",
                 f"- Effective damping beta_V+I = {self.effective_damping:.4f} (mode 1, complex modal analysis with "
                 f"the devices at the MCE_R amplitude estimate, inherent damping included); B_V+I = "
                 f"{self.b_v_plus_i:.3f} (ASCE 7-16 Table 18.7-1, cells as recalled, not read).",
                 f"- V_min = {self.v_min / 1e3:.1f} kN = {self.v_min / undamped.base_shear:.3f} V, governed by "
                 f"{self.v_min_rule} (Sec. 18.2.1.1); the frame is designed with strength_scale "
                 f"{frame.strength_scale:.4f}.",
                 f"- Devices: {self.sizing.description}.",
                 "- Story drift amplitudes of mode 1 at MCE_R (estimate, mm): "
                 + ", ".join(f"{a:.1f}" for a in self.drift_amplitudes), ""]
        if self.sizing.linearisation:
            lines += ["Equivalent linearisation of the devices (holds at these amplitudes only):", ""]
            lines += [f"- {note}" for note in self.sizing.linearisation] + [""]
        lines += ["### Rounds", "",
                  "| round | change | target | stiffness x | beta_V+I | B_V+I | V_min/V | drift stat / limit | "
                  "unacceptable (nominal, upper, lower) / allowed | largest limit ratio | verdict | time s |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in self.rounds:
            worst = f"{max(c.ratio for c in r.limits):.3f}" if r.limits else "-"
            counts = ", ".join(str(v) for v in r.unacceptable.values())
            lines.append(f"| {r.number} | {r.change} | {r.target_damping:.3f} | {r.stiffness_factor:.3g} | "
                         f"{r.effective_damping:.4f} | {r.b_v_plus_i:.3f} | {r.v_min / r.v:.3f} | "
                         f"{r.drift_statistic:.4f} / {r.drift_limit:.4f} | {counts} / {r.allowed_unacceptable} | "
                         f"{worst} | {'PASS' if r.passed else 'FAIL'} | {r.seconds:.1f} |")
        lines += ["", f"**Verdict: {'PASS' if self.passed else 'FAIL'}**" + (f" -- {self.failure}" if self.failure
                                                                                else ""), ""]
        final = self.rounds[-1]
        if final.device_peaks:
            lines += ["Largest device demands of the final round (over the suite and the bounds): "
                      + ", ".join(f"{name} {value:.4g}" for name, value in final.device_peaks.items()), ""]
        if self.collapse is not None:
            lines += ["### FEMA P695", ""]
            seen: set[int] = set()
            for key, assessment in self.collapse.items():
                same = id(assessment) in seen
                seen.add(id(assessment))
                note = " (the same assessment: the devices have no failure model)" if same else ""
                lines.append(f"- {key}: ACMR {assessment.acmr:.3f} vs ACMR20% {assessment.acmr20:.3f}: "
                             f"{'pass' if assessment.passes_acmr20 else 'FAIL'}{note}; {p695_basis(assessment)}")
            lines += ["", "One archetype is not a FEMA P695 system qualification: P695 asks for performance groups "
                      "of archetypes; this is the assessment of this one design.", ""]
        lines += ["### Times", ""] + [f"- {part}: {seconds:.3g} s" for part, seconds in self.timings.items()]
        lines += ["", "### Assumptions", ""] + [f"- {text}" for text in self.assumptions]
        return "\n".join(lines) + "\n"


# ------------------------------------------------------------------------------------------------ helpers
def p695_basis(assessment: Any) -> str:
    """What a FEMA P695 ACMR is measured against, in words: the SDC of P695 Table 5-1 whose MCE S_MT (g) at the
    period T (s) divides the collapse intensity (collapse_assessment's ``sdc``: Dmax unless given, not the design's
    site)."""
    return (f"SDC {assessment.sdc}, S_MT = {assessment.smt / G:.3g} g at T = {assessment.period:.3g} s "
            "(FEMA P695 Table 5-1's MCE of that SDC, not the design site's)")


def _check_limits(device_limits: Mapping[str, float] | None) -> dict[str, float]:
    if device_limits is None:
        return {}
    if not isinstance(device_limits, Mapping):
        raise ValueError(f"device_limits must be a dict of {sorted(DEVICE_LIMITS)}, got {show(device_limits)}")
    unknown = set(device_limits) - set(DEVICE_LIMITS)
    if unknown:
        raise ValueError(f"device_limits: unknown {sorted(map(str, unknown))}; expected some of "
                         f"{', '.join(f'{k} ({u})' for k, u in DEVICE_LIMITS.items())}")
    return {key: positive(f"device_limits[{key!r}]", value) for key, value in device_limits.items()}


def _target(value: object) -> float:
    target = finite_scalar("target_damping", value)
    if not 0.0 < target < 1.0:
        raise ValueError(f"target_damping must lie in (0, 1) (a damping ratio of mode 1), got {show(value)}")
    return target


def short_period_note(period: float, site: Site, number: int) -> str | None:
    """The assumption a round states where its period T_1 (s) is below the site's T_0 (s): Table 18.7-1 is headed
    "where period of the structure >= T_0" (ASCE 7-16, the heading as read; :mod:`vdw_frames.asce7.damping`), so
    its B_V+I there is used outside the table's range; None where T_1 >= T_0."""
    if period >= site.t0:
        return None
    return (f"round {number}: T_1 = {period:.3f} s is below T_0 = {site.t0:.3f} s, outside Table 18.7-1 (headed "
            "'where period of the structure >= T_0'); its B_V+I is used there all the same, and the standard's rule "
            "for shorter periods (as recalled, not read: B interpolated towards 1.0 at T = 0) is not applied, so "
            "V_min may be low")


def mce_drift_amplitudes(frame: ShearBuilding, site: Site, period: float, damping: float) -> np.ndarray:
    """Story drift amplitudes (mm) of mode 1 at MCE_R, the estimate of the module docstring: the bare ``frame``'s
    undamped first mode (shape and Gamma_1), the site's MCE_R S_a at ``period`` (s) divided by B at ``damping``
    (-, Table 18.7-1), times (T / 2 pi)^2; floored at 1e-6 mm."""
    mass = np.asarray(frame.mass_matrix)
    stiffness = np.asarray(frame.stiffness_matrix) + story_matrix(np.asarray(frame.geometric_stiffness))
    _, shapes = eigh(stiffness, mass)
    shape = shapes[:, 0]
    gamma = float(shape @ mass @ np.ones(frame.stories) / (shape @ mass @ shape))
    spectral = float(np.asarray(site.spectral_acceleration(period))) / damping_coefficient(damping)
    displacement = spectral * (period / (2.0 * np.pi)) ** 2
    # Floored at 1 nm: a story that does not drift in the mode still needs an amplitude > 0 to linearise at.
    return np.maximum(np.abs(gamma * np.diff(shape, prepend=0.0)) * displacement, 1e-6)


@dataclass(frozen=True)
class _Sized:
    """What :func:`_size` found: the sizing, the amplitudes (mm), whether they settled, the damping ratio the devices
    were sized for (-) and, where the target was out of reach, the largest achievable ratio (-; else None)."""

    sizing: DeviceSizing
    amplitudes: np.ndarray
    converged: bool
    target: float
    largest: float | None


def _size_once(frame: ShearBuilding, device: Device, target: float, distribution: str,
               amplitudes: np.ndarray) -> tuple[DeviceSizing, float, float | None]:
    """(sizing, the ratio sized for, the largest achievable ratio or None): :func:`~vdw_frames.design.size_devices`
    for ``target``, or where it is out of reach for the bare ratio + :data:`REACH_FRACTION` of the largest added
    damping.  Done as size_devices does it, on one sizer: its complex poles are cached, so the search for the
    largest ratio (which size_devices makes too) runs once."""
    sizer = _Sizer(frame, device, 1, distribution, None, walls_only=False, amplitudes=amplitudes)
    bare = float(-sizer.bare.real / abs(sizer.bare))
    largest: float | None = None
    if target > bare:  # below: _solve's ValueError says the bare frame has that much already
        best = sizer.best()[1]
        if target > best:
            largest, target = best, bare + REACH_FRACTION * (best - bare)
    factor = _solve(sizer, target)
    sized = sizer.building_for(factor)
    nonlinear = bool(nonlinear_devices(sized))
    result = modal_analysis(sized, 1, drift_amplitude=amplitudes if nonlinear else None)
    sizing = DeviceSizing(sized, device, factor, sizer.weights, 1, target, float(result.damping_ratios[0]),
                          float(result.periods[0]), bare, amplitudes if nonlinear else None,
                          linearisation_notes(sized, amplitudes), sizer.describe(factor))
    return sizing, target, largest


def _size(frame: ShearBuilding, device: Device, target: float, site: Site, distribution: str) -> _Sized:
    """Sizing and the MCE_R amplitude iterated (module docstring); a target out of reach is capped."""
    period = float(modal_analysis(frame, 1).periods[0])
    amplitudes = mce_drift_amplitudes(frame, site, period, target)
    for _ in range(AMPLITUDE_ITERATIONS):
        sizing, used, largest = _size_once(frame, device, target, distribution, amplitudes)
        updated = mce_drift_amplitudes(frame, site, sizing.period, used)
        if sizing.drift_amplitudes is None:  # linear devices: sized independently of the amplitude
            return _Sized(sizing, updated, True, used, largest)
        change = float(np.max(np.abs(updated - amplitudes) / amplitudes))
        if change < AMPLITUDE_TOLERANCE:  # the amplitudes sized at reproduce themselves: settled
            return _Sized(sizing, amplitudes, True, used, largest)
        sized_at, amplitudes = amplitudes, updated
    return _Sized(sizing, sized_at, False, used, largest)


def _limit_checks(building: ShearBuilding, result: VerificationResult, limits: dict[str, float]
                  ) -> tuple[LimitCheck, ...]:
    checks: list[LimitCheck] = []
    walls = building.wall_list
    for demand in result.walls:
        wall = walls[demand.wall][1]
        where = f"wall {demand.wall + 1} (story {demand.story})"
        own = getattr(wall, "limits", None)
        if own is not None and own.strain is not None:
            checks.append(LimitCheck("strain (WallLimits)", where, demand.strain, own.strain))
        if own is not None and own.stress is not None:
            checks.append(LimitCheck("stress (WallLimits)", where, demand.force / wall.area, own.stress))
        if own is not None and own.temperature is not None and demand.temperature_rise is not None \
                and wall.thermal is not None:
            # the rise (K) against the rise the limit allows from the warmest temperature the wall starts at
            checks.append(LimitCheck("temperature_rise (WallLimits)", where, demand.temperature_rise,
                                     own.temperature - _warmest_start(wall, getattr(result, "bounds", None))))
        if "strain" in limits:
            checks.append(LimitCheck("strain", where, demand.strain, limits["strain"]))
        if "stroke" in limits:
            checks.append(LimitCheck("stroke", where, demand.deformation, limits["stroke"]))
        if "velocity" in limits:
            checks.append(LimitCheck("velocity", where, demand.velocity, limits["velocity"]))
        if "temperature_rise" in limits and demand.temperature_rise is not None:
            checks.append(LimitCheck("temperature_rise", where, demand.temperature_rise, limits["temperature_rise"]))
    for other in result.devices:
        where = f"device {other.device + 1} (story {other.story}, {other.description})"
        if "stroke" in limits:
            checks.append(LimitCheck("stroke", where, max(other.deformation.values()), limits["stroke"]))
        if "velocity" in limits:
            checks.append(LimitCheck("velocity", where, max(other.velocity.values()), limits["velocity"]))
    return tuple(checks)


def _warmest_start(wall: Any, bounds: PropertyBounds | None) -> float:
    """The warmest temperature (degC) a wall starts an analysis at: its own, or the hot end of the bounds' ambient
    range (:class:`~vdw_frames.verification.PropertyBounds`)."""
    own = float(wall.thermal.temperature)
    return own if bounds is None or bounds.ambient is None else max(own, float(bounds.ambient[1]))


def _check_wall_temperature(device: Any, bounds: Any) -> None:
    """ValueError where a wall prototype starts at or above its own temperature limit (no rise is allowed)."""
    limits = getattr(device, "limits", None) if is_wall(device) else None
    if limits is None or limits.temperature is None or getattr(device, "thermal", None) is None:
        return
    start = _warmest_start(device, bounds if isinstance(bounds, PropertyBounds) else None)
    if limits.temperature <= start:
        raise ValueError(f"the wall's temperature limit {limits.temperature:g} degC is not above the temperature it "
                         f"starts at, {start:g} degC: it would fail at once")


def _peaks(result: VerificationResult) -> dict[str, float]:
    peaks: dict[str, float] = {}
    if result.walls:
        peaks["wall strain (-)"] = max(w.strain for w in result.walls)
        peaks["wall deformation (mm)"] = max(w.deformation for w in result.walls)
        peaks["wall velocity (mm/s)"] = max(w.velocity for w in result.walls)
        rises = [w.temperature_rise for w in result.walls if w.temperature_rise is not None]
        if rises:
            peaks["wall temperature rise (K)"] = max(rises)
    if result.devices:
        peaks["device deformation (mm)"] = max(max(d.deformation.values()) for d in result.devices)
        peaks["device velocity (mm/s)"] = max(max(d.velocity.values()) for d in result.devices)
        peaks["device force (N)"] = max(max(d.force.values()) for d in result.devices)
    return peaks


def _failures(result: VerificationResult, checks: tuple[LimitCheck, ...]) -> list[str]:
    texts = []
    for criterion in result.criteria:
        if not criterion.passed:
            ratio = criterion.value / criterion.limit if criterion.limit > 0 else float("inf")
            texts.append(f"{criterion.name} ({criterion.clause}): {criterion.value:.4g} vs limit {criterion.limit:.4g}"
                         + (f" (ratio {ratio:.3f})" if np.isfinite(ratio) else ""))
    texts += [check.text() for check in checks if not check.passed]
    return texts


def _governing_ratio(result: VerificationResult | None) -> float:
    """The largest drift statistic over its limit (inf without a result)."""
    return float("inf") if result is None else float(np.max(result.drift_statistic)) / result.drift_limit


def _without_limits(device: Any) -> Any:
    """A wall without its :class:`WallLimits` (it never fails); any other device as it is."""
    if not is_wall(device):
        return device
    if hasattr(device, "damper"):  # SupportedDamper: the limits are its wall's
        return dataclasses.replace(device, damper=_without_limits(device.damper))
    return dataclasses.replace(device, limits=None) if device.limits is not None else device


def _has_limits(building: ShearBuilding) -> bool:
    return any(getattr(wall, "limits", None) is not None for _, wall in building.wall_list)


def _out_of_reach(error: ValueError) -> bool:
    return "out of reach" in str(error)


# ------------------------------------------------------------------------------------------------ the loop
def design_damped(site: Site, system: Any, weights: ArrayLike, story_heights: ArrayLike, device: Device,
                  target_damping: float, *, bounds: PropertyBounds | tuple[float, float],
                  records: Iterable[GroundMotion] | None = None, irregular: bool = False, rounds: int = 4,
                  device_limits: Mapping[str, float] | None = None, p695: bool | Mapping[str, Any] = False,
                  executor: concurrent.futures.Executor | str | None = None, progress: bool = True,
                  distribution: str = "stiffness", **frame_options: Any) -> DampedDesign:
    """Design a frame with damping devices by ASCE 7-16 Chapters 12 and 18 and verify it (module docstring).

    ``site`` (:class:`~vdw_frames.verification.Site`), ``system`` (a key of
    :data:`~vdw_frames.asce7.SYSTEMS` or a SeismicSystem), ``weights`` (N per floor, floor 1 first),
    ``story_heights`` (mm) and ``frame_options``: as :func:`~vdw_frames.design.elf.design_frame` takes them
    (``strength_scale`` is this function's; ``minimum_stiffness`` (N/mm) is kept as the floor of the stiffening).
    ``device``: the prototype (a wall, FluidViscousDamper or FrictionDamper)
    :func:`~vdw_frames.design.size_devices` scales over the stories by ``distribution``; ``target_damping``
    (-, in (0, 1)): the total damping ratio of mode 1 to start from.
    ``bounds`` (lambda_min, lambda_max) and ``records`` (None: the FEMA P695 far-field set, the ``[p695]`` extra):
    for :func:`~vdw_frames.verification.verify`.  ``irregular``: the structure has the irregularities of Sec.
    18.2.1.1's exception (V_min = 1.0 V).  ``rounds`` (1 ... :data:`MAX_ROUNDS`): most verifications.
    ``device_limits``: module docstring (keys of :data:`DEVICE_LIMITS`).  ``p695``: True (or a dict of
    :func:`~vdw_frames.assessment.collapse_assessment` options, e.g. ``{"sdc": "Dmax"}``) for the collapse
    assessment of the final design.  ``executor``/``progress``: for every analysis.  Returns a
    :class:`DampedDesign`; ValueError for bad input (a target damping <= 0 or >= 1, unknown limits, ...) and
    where the first target is not above the bare frame's damping.
    """
    target = _target(target_damping)
    limits = _check_limits(device_limits)
    n_rounds = _check_options(rounds, irregular, distribution, p695, bounds, frame_options)
    _check_wall_temperature(device, bounds)
    loop = _Loop(site, system, weights, story_heights, device, distribution=distribution, frame_options=frame_options)
    records = list(records) if records is not None else None
    current, history, previous = target, [], None
    change = f"start: target damping {target:.3f}, the Chapter 12 frame"
    for number in range(1, n_rounds + 1):
        undamped, sized = loop.devices(current, number)
        sizing, amplitudes = sized.sizing, sized.amplitudes
        if sized.largest is not None:
            change += (f"; target {current:.3f} out of reach (at most {sized.largest:.4f}): devices sized for "
                       f"{sized.target:.4f}")
        devices = dict(sizing.building.devices.items())
        nonlinear = sizing.drift_amplitudes is not None
        effective = float(modal_analysis(undamped.building.with_devices(devices), 1,
                                         drift_amplitude=amplitudes if nonlinear else None).damping_ratios[0])
        b = damping_coefficient(effective)
        note = short_period_note(sizing.period, site, number)
        if note is not None:
            loop.assumptions.append(note)
        v = float(undamped.base_shear)
        v_min, rule = minimum_base_shear(v, b, bool(irregular))
        if v_min > v:  # B_V+I < 1 (below 5 % damping): design_frame's strength_scale stops at 1
            loop.assumptions.append(
                f"round {number}: V_min = V / B_V+I = {v_min / v:.4f} V exceeds V (B_V+I = {b:.4f} < 1 at "
                f"{effective:.4f} damping); the frame is designed for V, not V_min")
        frame = loop.frame_design(min(1.0, v_min / v))
        building = frame.building.with_devices(devices)

        started = time.perf_counter()
        candidates = loop.candidates(building, records, number)
        result = verify(building, site, candidates, bounds=bounds, executor=executor, progress=progress)
        seconds = time.perf_counter() - started
        loop.timings[f"verification round {number}"] = seconds
        checks = _limit_checks(building, result, limits)
        failures = _failures(result, checks)
        cases = [name for name, _ in result.cases]
        history.append(DesignRound(
            number=number, change=change, target_damping=sized.target, stiffness_factor=loop.factor,
            devices=sizing.description, drift_amplitudes=amplitudes, effective_damping=effective, b_v_plus_i=b,
            v=v, v_min=v_min, v_min_rule=rule, drift_statistic=float(np.max(result.drift_statistic)),
            drift_limit=float(result.drift_limit),
            unacceptable={case: sum(1 for reason in result.unacceptable[c] if reason) for c, case in enumerate(cases)},
            allowed_unacceptable=result.allowed_unacceptable, device_peaks=_peaks(result), limits=checks,
            passed=not failures, seconds=seconds, failed=tuple(failures), left_out=loop.left_out.get(number, ())))
        final = (frame, undamped, building, sizing, effective, b, v_min, rule, amplitudes, result)
        if not failures:
            break
        current, change = loop.next_round(current, sized, number, result, previous, checks=checks, failures=failures)
        previous = result

    (frame, undamped, building, sizing, effective, b, v_min, rule, amplitudes, result) = final
    failed = history[-1].failed
    failure = None if not failed else (f"no design passed in {len(history)} round(s); the last failed: "
                                       + "; ".join(failed))
    collapse = None
    if p695:
        collapse = _collapse(building, {} if isinstance(p695, (bool, np.bool_)) else dict(p695),
                             executor, progress, loop.timings)
    return DampedDesign(
        frame=frame, undamped=undamped, building=building, sizing=sizing, effective_damping=effective,
        b_v_plus_i=b, v_min=v_min, v_min_rule=rule, drift_amplitudes=amplitudes, rounds=tuple(history),
        verification=result, passed=not failed, failure=failure, collapse=collapse, timings=loop.timings,
        assumptions=tuple(loop.assumptions), device_limits=limits)


def _check_options(rounds: object, irregular: object, distribution: object, p695: object, bounds: object,
                   frame_options: dict[str, Any]) -> int:
    """The number of rounds, after the other options of :func:`design_damped` are checked."""
    n_rounds = whole_number("rounds", rounds, 1)
    if n_rounds > MAX_ROUNDS:
        raise ValueError(f"rounds must be a whole number in 1 ... {MAX_ROUNDS}, got {rounds!r}")
    if not isinstance(irregular, (bool, np.bool_)):
        raise ValueError(f"irregular must be True or False, got {show(irregular)}")
    if distribution not in DISTRIBUTIONS or distribution == "existing":
        raise ValueError(f"distribution must be one of {[d for d in DISTRIBUTIONS if d != 'existing']}, got "
                         f"{show(distribution)}")
    if "strength_scale" in frame_options:
        raise ValueError("strength_scale is design_damped's own (V_min / V); do not give it")
    if not isinstance(p695, (bool, np.bool_, Mapping)):
        raise ValueError(f"p695 must be True, False or a dict of collapse_assessment options, got {show(p695)}")
    if bounds is None:
        raise ValueError("bounds are required: ASCE 7-16 Sec. 18.2.4.5 asks for upper- and lower-bound device "
                         "properties; give bounds=(lambda_min, lambda_max)")
    return n_rounds


class _Loop:
    """The state of :func:`design_damped` between rounds: the frame's stiffness factor, the times, the
    assumptions."""

    def __init__(self, site: Site, system: Any, weights: ArrayLike, story_heights: ArrayLike, device: Device, *,
                 distribution: str, frame_options: dict[str, Any]) -> None:
        self.site, self.system, self.weights, self.story_heights = site, system, weights, story_heights
        self.device, self.distribution = device, distribution
        self.options = dict(frame_options)
        self.minimum = self.options.pop("minimum_stiffness", 0.0)
        self.timings: dict[str, float] = {}
        self.factor = 1.0
        self._p695_records: list[GroundMotion] | None = None
        self.left_out: dict[int, tuple[str, ...]] = {}
        self.assumptions = [
            "B_V+I from the complex-mode damping ratio of mode 1 with the devices at the MCE_R amplitude estimate "
            "(inherent damping included, the frame's hysteretic damping not); ASCE 7-16 Sec. 18.7 computes beta_V1 "
            "from the devices' energy at the design displacement (as recalled): at MCE_R a nonlinear FVD's ratio "
            "is smaller, so B smaller and V_min larger (conservative).",
            "Table 18.7-1's cells and Sec. 18.2.1.1's Eq. 18.2-1 and exception are as recalled, not read from the "
            "standard (vdw_frames.asce7.damping says what was read).",
            "The MCE_R story drift amplitudes are a one-mode estimate: Gamma_1 |phi_i - phi_i-1| S_aM(T_1) / "
            "B(target) (T_1 / 2 pi)^2 with the bare frame's undamped mode and the damped T_1.",
            f"Devices distributed by the '{distribution}' rule of size_devices over every story.",
            f"Iteration (this package's rule): a failed round adds {TARGET_STEP:g} to the target damping, and "
            f"multiplies every story's stiffness by {STIFFNESS_STEP:g} when a device limit failed, the enlargement "
            f"cut the drift statistic over its limit by less than {STALL_FRACTION:.0%}, or the target is out of "
            f"reach (the devices then sized for the bare ratio + {REACH_FRACTION:.0%} of the largest added damping).",
        ]
        self.base = self.frame_design(1.0)

    def candidates(self, building: ShearBuilding, records: list[GroundMotion] | None,
                   number: int) -> list[GroundMotion]:
        """The records long enough for ``building``'s period range (Sec. 16.2 as :func:`scaled_suite` checks it:
        at least :data:`MIN_CYCLES` x T_upper); ``records`` None: the FEMA P695 far-field set, loaded once.  The
        records left out are stated in the assumptions."""
        if records is None:
            if self._p695_records is None:
                from ..motion.p695 import fema_p695_records

                self._p695_records = list(fema_p695_records("far-field"))
            records = self._p695_records
        shortest = MIN_CYCLES * period_range(building).upper
        kept = [motion for motion in records if motion.duration >= shortest]
        if len(kept) < len(records):
            self.left_out[number] = tuple(motion.name or f"record {i + 1}" for i, motion in enumerate(records)
                                          if motion.duration < shortest)
            self.assumptions.append(
                f"round {number}: {len(records) - len(kept)} of the {len(records)} candidate records left out of the "
                f"suite's selection: shorter than {MIN_CYCLES:g} x T_upper = {shortest:.3g} s (scaled_suite's rule): "
                + ", ".join(self.left_out[number]))
        return kept

    def frame_design(self, scale: float) -> FrameDesign:
        """design_frame at ``strength_scale`` ``scale``, every story at least ``factor`` x the first design's."""
        started = time.perf_counter()
        floor: Any = self.minimum if self.factor == 1.0 else \
            np.maximum(self.factor * np.asarray(self.base.stiffnesses, dtype=float), self.minimum)
        design = design_frame(self.site, self.system, self.weights, self.story_heights, strength_scale=scale,
                              minimum_stiffness=floor, **self.options)
        self.timings["ELF"] = self.timings.get("ELF", 0.0) + time.perf_counter() - started
        return design

    def devices(self, target: float, number: int) -> tuple[FrameDesign, _Sized]:
        """(the 1.0 V frame, the sizing) for ``target`` on the frame at the current stiffness factor."""
        undamped = self.base if self.factor == 1.0 else self.frame_design(1.0)
        started = time.perf_counter()
        try:
            sized = _size(undamped.building.without_devices(), self.device, target, self.site, self.distribution)
        finally:
            self.timings["sizing"] = self.timings.get("sizing", 0.0) + time.perf_counter() - started
        if not sized.converged:
            self.assumptions.append(
                f"round {number}: the sizing-amplitude iteration stopped at its bound ({AMPLITUDE_ITERATIONS}) "
                f"before the amplitudes settled to {AMPLITUDE_TOLERANCE:g}")
        return undamped, sized

    def next_round(self, target: float, sized: _Sized, number: int, result: VerificationResult,
                   previous: VerificationResult | None, *, checks: tuple[LimitCheck, ...],
                   failures: list[str]) -> tuple[float, str]:
        """(the next target, the change text) after round ``number`` failed (module docstring, step 6)."""
        limit_failed = any(not check.passed for check in checks)
        stalled = previous is not None and \
            _governing_ratio(result) > (1.0 - STALL_FRACTION) * _governing_ratio(previous)
        if sized.largest is not None:
            change = (f"target damping {target:.3f} kept (out of reach: at most {sized.largest:.4f} on this frame, "
                      f"devices sized for {sized.target:.4f})")
        elif target + TARGET_STEP < 1.0:
            target += TARGET_STEP
            change = f"target damping +{TARGET_STEP:g} to {target:.3f} (devices enlarged)"
        else:
            change = "target damping kept (no larger ratio below 1)"
        if limit_failed or stalled or sized.largest is not None:
            self.factor *= STIFFNESS_STEP
            reason = "a device limit failed" if limit_failed else "the target is out of reach" \
                if sized.largest is not None else \
                f"the last enlargement cut the drift ratio to limit by less than {STALL_FRACTION:.0%}"
            change += f", frame stiffness x{STIFFNESS_STEP:g} (to x{self.factor:g}: {reason})"
        return target, change + f", because round {number} failed: " + "; ".join(failures)


def _collapse(building: ShearBuilding, options: dict[str, Any], executor: concurrent.futures.Executor | str | None,
              progress: bool, timings: dict[str, float]) -> dict[str, Any]:
    """The P695 assessments with and without device failure counted (module docstring)."""
    from ..assessment.collapse import CollapseCriterion, collapse_assessment

    if "criterion" in options:
        raise ValueError("p695 options: the criterion is design_damped's (with and without device failure)")
    options.setdefault("executor", executor)
    options.setdefault("progress", progress)
    started = time.perf_counter()
    free = building.with_devices({story: tuple(_without_limits(d) for d in group)
                                  for story, group in building.devices.items()})
    without = collapse_assessment(free, **options)
    timings["P695 without device failure"] = time.perf_counter() - started
    if not _has_limits(building):
        return {COLLAPSE_KEYS[0]: without, COLLAPSE_KEYS[1]: without}
    started = time.perf_counter()
    counted = collapse_assessment(building, criterion=CollapseCriterion(wall_failure=True), **options)
    timings["P695 with device failure"] = time.perf_counter() - started
    return {COLLAPSE_KEYS[0]: counted, COLLAPSE_KEYS[1]: without}
