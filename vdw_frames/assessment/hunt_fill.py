"""The collapse intensity of one record by hunt-and-fill (Vamvatsikos & Cornell 2004, "Applied incremental
dynamic analysis", Earthquake Spectra 20(2), Section "Hunt & fill tracing").

*Hunt*: from ``start`` the intensity grows geometrically (x ``growth``) until the first collapse, or
shrinks (/ ``growth``) until the first run that stands when the start already collapses.  *Fill*: the
interval between the highest standing and the lowest collapsing intensity is bisected (geometric
midpoints) until their ratio is at most 1 + ``tolerance``.  The collapse intensity reported is the
geometric midpoint of that last interval (within sqrt(1 + tolerance) of both ends).  A record still
standing at ``cap`` is right-censored (no collapse intensity).

Every run is one call of ``run(intensity)``; the number of runs is bounded by the settings alone:
hunting up at most ceil(ln(cap / start) / ln(growth)) + 1 runs, down at most ``MAX_HALVINGS`` (a record
that still collapses there is an error: the model fails at almost no shaking), bisecting at most
ceil(log2(ln(growth) / ln(1 + tolerance))).

Like every search of a non-monotonic IDA curve, it finds *a* standing-to-collapse transition: where a
record collapses and then "resurrects" at a higher intensity (Vamvatsikos & Cornell 2002), the first
collapse found by the hunt bounds the bracket, so the transition found may not be the lowest.
Units: whatever ``run`` takes (the assessment uses spectral accelerations in mm/s^2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from .._validation import positive, show

MAX_HALVINGS = 12  # hunting down: at most start / growth^12


@dataclass(frozen=True)
class HuntAndFill:
    """Settings of the hunt-and-fill search (module docstring).

    ``start`` and ``cap``: the first and the highest intensity (mm/s^2 in the assessment); None lets
    :func:`~vdw_frames.assessment.collapse_assessment` choose them (S_MT and 20 S_MT).  ``growth`` (> 1,
    at most 10): the hunt's factor; ``tolerance`` (in (0, 0.5)): the fill stops when collapsing /
    standing intensity <= 1 + tolerance (default 0.02: 2 % in Sa).  With the defaults (growth 1.8) the
    fill takes 5 runs (1.8^(1/32) = 1.0185).
    """

    start: float | None = None
    cap: float | None = None
    growth: float = 1.8
    tolerance: float = 0.02

    def __post_init__(self):
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
        if growth <= 1.0 + tolerance:
            raise ValueError(f"growth = {show(growth)} must exceed 1 + tolerance = {show(1.0 + tolerance)}")
        object.__setattr__(self, "tolerance", tolerance)

    def with_range(self, start: float, cap: float) -> "HuntAndFill":
        """These settings with ``start`` and ``cap`` filled in where they are None."""
        return HuntAndFill(self.start if self.start is not None else start,
                           self.cap if self.cap is not None else max(cap, self.start or start),
                           self.growth, self.tolerance)

    def max_runs(self) -> int:
        """The most runs one record can take with these settings (start and cap set)."""
        up = math.ceil(math.log(self.cap / self.start) / math.log(self.growth) - 1e-12) + 1
        fill = math.ceil(math.log2(math.log(self.growth) / math.log1p(self.tolerance)) - 1e-12)
        return max(up, MAX_HALVINGS + 1) + max(fill, 0)


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

    ``standing`` / ``collapsing``: the highest standing and the lowest collapsing intensity of the final
    bracket (``collapsing`` None when the record stood at the cap); ``collapse_intensity``: their
    geometric mean (None when censored).
    """

    runs: tuple
    standing: float
    collapsing: float | None

    @property
    def collapse_intensity(self) -> float | None:
        return None if self.collapsing is None else math.sqrt(self.standing * self.collapsing)

    @property
    def censored(self) -> bool:
        return self.collapsing is None

    def curve(self):
        """(intensity, peak drift ratio, collapsed) of every run, sorted by intensity: the IDA curve."""
        order = sorted(range(len(self.runs)), key=lambda k: self.runs[k].intensity)
        runs = [self.runs[k] for k in order]
        return (np.array([r.intensity for r in runs]), np.array([r.peak_drift_ratio for r in runs]),
                np.array([r.collapsed for r in runs], dtype=bool))


def hunt_and_fill(run: Callable[[float], Run], settings: HuntAndFill, label: str = "the record") -> SearchResult:
    """Search the collapse intensity with ``run(intensity) -> Run`` (module docstring); ``settings`` with
    ``start`` and ``cap`` set.  ValueError when the record collapses even at start / growth^12."""
    if settings.start is None or settings.cap is None:
        raise ValueError("hunt_and_fill needs settings with start and cap")
    runs = []

    def analyse(intensity):
        result = run(intensity)
        runs.append(result)
        return result.collapsed

    growth = settings.growth
    intensity = settings.start
    standing, collapsing = None, None
    if analyse(intensity):
        collapsing = intensity
        for _ in range(MAX_HALVINGS):
            intensity /= growth
            if not analyse(intensity):
                standing = intensity
                break
            collapsing = intensity
        else:
            raise ValueError(f"{label} collapses even at {intensity:.6g} (start / {growth:g}^{MAX_HALVINGS}): the "
                             "model fails under almost no shaking")
    else:
        standing = intensity
        while standing < settings.cap:
            intensity = min(standing * growth, settings.cap)
            if analyse(intensity):
                collapsing = intensity
                break
            standing = intensity
        if collapsing is None:
            return SearchResult(tuple(runs), standing, None)
    while collapsing / standing > 1.0 + settings.tolerance:
        middle = math.sqrt(standing * collapsing)
        if analyse(middle):
            collapsing = middle
        else:
            standing = middle
    return SearchResult(tuple(runs), standing, collapsing)
