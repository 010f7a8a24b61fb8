"""The collapse intensity of one record by hunt-and-fill (Vamvatsikos & Cornell 2004, "Applied incremental
dynamic analysis", Earthquake Spectra 20(2)).

*Hunt*: from ``start`` the intensity grows geometrically (x ``growth``) until the first collapse, or
shrinks (/ ``growth``) until the first run that stands when the start already collapses.  *Bisect*: the
interval between the lowest collapsing intensity and the highest standing one below it is bisected
(geometric midpoints) until their ratio is at most 1 + ``tolerance``.  *Fill*: an IDA curve need not be
monotonic -- a record can collapse, then stand again at a higher intensity ("structural resurrection",
Vamvatsikos & Cornell 2002) -- so the largest gaps between the standing runs below that interval are
filled (geometric midpoints), while any is wider than ``fill_ratio`` and the record has used fewer than
``max_runs`` analyses; a fill run that collapses gives a lower interval, bisected in turn.  The collapse
intensity reported is the geometric midpoint of the final interval (within sqrt(1 + tolerance) of both
ends): the lowest standing-to-collapse transition the runs resolved.  A record still standing at ``cap``
is right-censored (no collapse intensity).

Every run is one call of ``run(intensity)``; the number of runs is bounded by the settings alone:
hunting up at most ceil(ln(cap / start) / ln(growth)) + 1 runs, down at most ``MAX_HALVINGS`` (a record
that still collapses there is an error: the model fails at almost no shaking), each bisection at most
ceil(log2(ln(growth) / ln(1 + tolerance))) runs, fill runs only while fewer than ``max_runs`` were made.
A transition inside a gap narrower than ``fill_ratio``, or left unfilled when the budget ran out, is
not seen: :attr:`SearchResult.resolution` reports the widest gap left.
The search is written once, as the generator :func:`search_steps` (it yields each intensity and is sent its
run), so that many records' searches can advance together, one lane of the lanes engine a record
(:class:`~vdw_frames.assessment.collapse.SearchGroup`); :func:`hunt_and_fill` drives it with ``run``.
Units: whatever ``run`` takes (the assessment uses spectral accelerations in mm/s^2).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Generator, Sequence
from dataclasses import dataclass
from typing import cast

import numpy as np
from numpy.typing import NDArray

from .._validation import positive, show, whole_number

MAX_HALVINGS = 12  # hunting down: at most start / growth^12

MIN_TOLERANCE = 1e-6
"""Finest ``tolerance`` accepted: 1e-6 of the intensity, far below the record-to-record dispersion of collapse
intensities (beta about 0.4 in ln Sa, FEMA P695) and below what one analysis resolves (its collapse criterion
is a drift threshold on a numerical time history).  Each decade finer adds ~3.3 runs to every bisection: with
the defaults and cap = 20 start, :meth:`HuntAndFill.bound` is 84 runs a record at 0.02, 264 at 1e-6 and
11 976 at 1e-300."""


@dataclass(frozen=True)
class HuntAndFill:
    """Settings of the hunt-and-fill search (module docstring).

    ``start`` and ``cap``: the first and the highest intensity (mm/s^2 in the assessment); None lets
    :func:`~vdw_frames.assessment.collapse_assessment` choose them (S_MT and 20 S_MT).  ``growth`` (> 1,
    at most 10): the hunt's factor; ``tolerance`` (in [1e-6, 0.5)): the fill stops when collapsing /
    standing intensity <= 1 + tolerance (default 0.02: 2 % in Sa).  With the defaults (growth 1.8) the
    fill takes 5 runs (1.8^(1/32) = 1.0185).  ``fill_ratio`` (> 1 + tolerance): gaps between standing runs
    below the collapse wider than this are filled while the record has made fewer than ``max_runs``
    (1 ... 1000) analyses.
    """

    start: float | None = None
    cap: float | None = None
    growth: float = 1.8
    tolerance: float = 0.02
    fill_ratio: float = 1.1
    max_runs: int = 12

    def __post_init__(self) -> None:
        if self.start is not None:
            object.__setattr__(self, "start", positive("start", self.start))
        if self.cap is not None:
            object.__setattr__(self, "cap", positive("cap", self.cap))
        if self.start is not None and self.cap is not None and self.cap < self.start:
            raise ValueError(f"cap = {show(self.cap)} must be at least start = {show(self.start)}")
        growth = positive("growth", self.growth)
        if not 1.0 < growth <= 10.0:
            raise ValueError(f"growth must lie in (1, 10], got {show(self.growth)}")
        object.__setattr__(self, "growth", growth)
        tolerance = positive("tolerance", self.tolerance)
        if not tolerance < 0.5:
            raise ValueError(f"tolerance must lie in (0, 0.5), got {show(self.tolerance)}")
        if tolerance < MIN_TOLERANCE:
            raise ValueError(f"tolerance = {show(self.tolerance)} is below {MIN_TOLERANCE:g} of the intensity: no "
                             "collapse intensity is resolved that finely (record-to-record dispersion is about 0.4 "
                             "in ln Sa), and each finer decade only adds runs")
        if growth <= 1.0 + tolerance:
            raise ValueError(f"growth = {show(growth)} must exceed 1 + tolerance = {show(1.0 + tolerance)}")
        object.__setattr__(self, "tolerance", tolerance)
        fill = positive("fill_ratio", self.fill_ratio)
        if not fill > 1.0 + tolerance:
            raise ValueError(f"fill_ratio = {show(self.fill_ratio)} must exceed 1 + tolerance = "
                             f"{show(1.0 + tolerance)}")
        object.__setattr__(self, "fill_ratio", fill)
        object.__setattr__(self, "max_runs", whole_number("max_runs", self.max_runs, 1))
        if self.max_runs > 1000:
            raise ValueError(f"max_runs must be at most 1000, got {self.max_runs}")

    def with_range(self, start: float, cap: float) -> HuntAndFill:
        """These settings with ``start`` and ``cap`` filled in where they are None."""
        return HuntAndFill(self.start if self.start is not None else start,
                           self.cap if self.cap is not None else max(cap, self.start or start),
                           self.growth, self.tolerance, self.fill_ratio, self.max_runs)

    def bound(self) -> int:
        """The most runs one record can take with these settings (start and cap set)."""
        if self.start is None or self.cap is None:
            raise ValueError("bound() needs start and cap (HuntAndFill.filled)")
        hunt = max(math.ceil(math.log(self.cap / self.start) / math.log(self.growth) - 1e-12) + 1, MAX_HALVINGS + 1)
        bisection = max(math.ceil(math.log2(math.log(self.growth) / math.log1p(self.tolerance)) - 1e-12), 0)
        fills = max(self.max_runs - 1, 0)  # each fill run, and each lower interval one finds, is bounded too
        return hunt + bisection + fills * (1 + bisection)


@dataclass(frozen=True)
class Run:
    """One analysis: ``intensity``, ``collapsed`` (by the criterion), ``converged``, the largest story
    ``peak_drift_ratio`` (-) reached before it stopped and the time ``steps`` it integrated."""

    intensity: float
    collapsed: bool
    converged: bool
    peak_drift_ratio: float
    steps: int = 0


@dataclass(frozen=True)
class SearchResult:
    """The runs of one record (in the order run) and the bracket found.

    ``standing`` / ``collapsing``: the lowest collapsing intensity and the highest standing one below it
    (``collapsing`` None when the record stood at the cap); ``collapse_intensity``: their geometric mean
    (None when censored); ``resolution``: the widest ratio left between consecutive standing runs below
    the bracket (1.0 when there are fewer than two).
    """

    runs: tuple[Run, ...]
    standing: float
    collapsing: float | None
    resolution: float = 1.0

    @property
    def collapse_intensity(self) -> float | None:
        return None if self.collapsing is None else math.sqrt(self.standing * self.collapsing)

    @property
    def censored(self) -> bool:
        return self.collapsing is None

    def curve(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
        """(intensity, peak drift ratio, collapsed) of every run, sorted by intensity: the IDA curve."""
        order = sorted(range(len(self.runs)), key=lambda k: self.runs[k].intensity)
        runs = [self.runs[k] for k in order]
        return (np.array([r.intensity for r in runs]), np.array([r.peak_drift_ratio for r in runs]),
                np.array([r.collapsed for r in runs], dtype=bool))


def hunt_and_fill(run: Callable[[float], Run], settings: HuntAndFill, label: str = "the record") -> SearchResult:
    """Search the collapse intensity with ``run(intensity) -> Run`` (module docstring); ``settings`` with
    ``start`` and ``cap`` set.  ValueError when the record collapses even at start / growth^12.  Drives
    :func:`search_steps`, the search itself (an error of ``run`` passes through)."""
    steps = search_steps(settings, label)
    intensity = next(steps)
    while True:
        try:
            intensity = steps.send(run(intensity))
        except StopIteration as done:
            return cast(SearchResult, done.value)


def search_steps(settings: HuntAndFill, label: str = "the record") -> Generator[float, Run, SearchResult]:
    """The search of :func:`hunt_and_fill` as a generator, so that a driver can advance many records' searches
    together (:class:`vdw_frames.assessment.collapse.SearchGroup`: one lane a record, in rounds): it yields the
    next intensity to run (the unit of ``settings``: mm/s^2 in the assessment), is sent that run's :class:`Run`,
    and returns the :class:`SearchResult` (``StopIteration.value``).  The intensities, their order and the result
    are those of :func:`hunt_and_fill` for the same runs (it drives this generator).  ValueError at once for
    settings without ``start`` and ``cap``, and from ``send`` when the record collapses even at start /
    growth^12 (``label`` names it)."""
    if settings.start is None or settings.cap is None:
        raise ValueError("hunt_and_fill needs settings with start and cap")
    return _search(settings, settings.start, settings.cap, label)


def _search(settings: HuntAndFill, start: float, cap: float, label: str) -> Generator[float, Run, SearchResult]:
    """The search (module docstring) from ``start`` to ``cap``: yields intensities, is sent their runs."""
    runs: list[Run] = []

    def bracket() -> tuple[float, float]:
        """(highest standing intensity below the lowest collapse, lowest collapse).  Called only once the
        hunt has found both, and every later run keeps a standing one below the lowest collapse."""
        lowest = min(r.intensity for r in runs if r.collapsed)
        return max(r.intensity for r in runs if not r.collapsed and r.intensity < lowest), lowest

    growth = settings.growth
    intensity = start
    runs.append((yield intensity))
    if runs[-1].collapsed:  # hunt down
        for _ in range(MAX_HALVINGS):
            intensity /= growth
            runs.append((yield intensity))
            if not runs[-1].collapsed:
                break
        else:
            raise ValueError(f"{label} collapses even at {intensity:.6g} (start / {growth:g}^{MAX_HALVINGS}): the "
                             "model fails under almost no shaking")
    else:  # hunt up
        while intensity < cap:
            intensity = min(intensity * growth, cap)
            runs.append((yield intensity))
            if runs[-1].collapsed:
                break
        else:
            return SearchResult(tuple(runs), intensity, None, _widest_gap(runs, intensity))
    while True:
        standing, collapsing = bracket()
        if collapsing / standing > 1.0 + settings.tolerance:  # bisect
            runs.append((yield math.sqrt(standing * collapsing)))
            continue
        if len(runs) >= settings.max_runs:
            break
        below = sorted(r.intensity for r in runs if r.intensity <= standing)
        ratios = [high / low for low, high in itertools.pairwise(below)]
        if not ratios or max(ratios) <= settings.fill_ratio:
            break
        k = int(np.argmax(ratios))  # fill the widest gap
        runs.append((yield math.sqrt(below[k] * below[k + 1])))
    standing, collapsing = bracket()
    return SearchResult(tuple(runs), standing, collapsing, _widest_gap(runs, standing))


def _widest_gap(runs: Sequence[Run], top: float) -> float:
    below = sorted(r.intensity for r in runs if not r.collapsed and r.intensity <= top)
    return max((high / low for low, high in itertools.pairwise(below)), default=1.0)
