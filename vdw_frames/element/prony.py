"""A Prony series (generalized Maxwell model) fitted to a wall's complex stiffness over a frequency band.

For programs that cannot host the exact wall (OpenSees without :mod:`vdw_frames.interop.opensees`, SAP2000,
ETABS): an equilibrium spring k_0 in parallel with n Maxwell branches, branch i a linear spring k_i in
series with a linear dashpot c_i (relaxation time tau_i = c_i / k_i), whose complex stiffness is

    K*(omega) = k_0 + sum_i k_i i omega c_i / (k_i + i omega c_i).

The fit (:func:`fit_prony`) is approximate, within a stated tolerance on a stated band, and passive by
construction (k_0, k_i, c_i >= 0: every branch dissipates, none creates energy).

Method, for n = 1, 2, ... branches in turn, until the tolerance is met:

1. relaxation times start log-spaced across the band, tau in [1 / (2 pi f_max), 1 / (2 pi f_min)];
2. for given relaxation times the model is linear in (k_0, k_1 .. k_n): they solve a non-negative least
   squares problem (scipy ``nnls``) on the relative error (K - K*) / |K*| (real and imaginary parts) at
   ``FIT_POINTS_PER_DECADE`` log-spaced frequencies; the log relaxation times are optimised around it
   (variable projection, scipy ``least_squares``), within [1e-3 / omega_max, 10 / omega_min];
3. Lawson's iteratively reweighted least squares (weights multiplied by the square root of the relative
   error, a few tens of rounds) moves the fit towards the minimax (Chebyshev) one, the criterion here;
4. the fit is accepted when its largest relative error |K - K*| / |K*| on a dense grid (``CHECK_POINTS_PER_DECADE``
   log-spaced points, both band edges included) is within the tolerance.

An n whose least-squares fit already has an RMS relative error above the tolerance cannot reach it
(the maximum is at least the RMS of the best least-squares fit) and is skipped without step 3.  The
result is the fewest branches for which this procedure reaches the tolerance (a local optimiser: not a
proof that fewer cannot).

Short relaxation times: a branch with tau << 1 / omega_max acts as a dashpot in the band (how a classical
r = 1 Kelvin dashpot is represented); time-stepping programs must resolve it (OpenSees's ``Maxwell``
needs dt well below tau; see :func:`vdw_frames.interop.opensees.prony_material`).

Units: stiffness N/mm, damping coefficient N*s/mm, relaxation time s, frequency Hz.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from .._validation import finite_array, non_negative, positive, positive_frequencies, show, whole_number
from .wall import StiffnessMethods

if TYPE_CHECKING:
    from .wall import Wall

FIT_POINTS_PER_DECADE = 24
CHECK_POINTS_PER_DECADE = 1000
MAX_BAND = 1e6
"""Widest band accepted, f_max / f_min (6 decades: 0.01-10 000 Hz holds any seismic analysis).  The
relaxation times tried then span 10 decades, already more than one time step resolves in a host program,
and the fit's cost grows steeply beyond: measured <= 5 s at 6 decades for any tolerance, up to 26 s at 8,
240 s at 10 (tolerance 1e-4) and endless at 1e12."""
_LAWSON_ROUNDS = 40
_SHORTEST = 1e-3  # x 1 / omega_max: the shortest relaxation time tried (a dashpot to 0.1 % in the band)
_LONGEST = 10.0  # x 1 / omega_min: the longest (a spring to 10 % at f_min)


def _band(f_min: object, f_max: object) -> tuple[float, float]:
    """(f_min, f_max) in Hz: both finite and > 0, f_max above f_min."""
    low, high = positive("f_min", f_min), positive("f_max", f_max)
    if not high > low:
        raise ValueError(f"f_max must exceed f_min, got f_min = {show(f_min)} Hz, f_max = {show(f_max)} Hz")
    return low, high


@dataclass(frozen=True, eq=False)
class PronySeries(StiffnessMethods):
    """An equilibrium spring and Maxwell branches fitted to a wall's complex stiffness (see the module).

    ``equilibrium_stiffness`` k_0 (N/mm); ``branches`` (n, 2): one row (k_i in N/mm, c_i in N*s/mm) per
    spring-dashpot branch, relaxation times ascending; ``f_min``, ``f_max`` (Hz): the band of the fit;
    ``tolerance``: the bound asked for and ``error`` the one achieved, both the largest relative error
    |K - K*| / |K*| over the band (dense grid).
    """

    equilibrium_stiffness: float
    branches: np.ndarray
    f_min: float
    f_max: float
    tolerance: float
    error: float

    def __post_init__(self) -> None:
        equilibrium = non_negative("equilibrium_stiffness", self.equilibrium_stiffness)
        branches = finite_array("branches", self.branches, ndim=None).copy()
        if branches.size == 0:
            branches = branches.reshape(0, 2)
        if branches.ndim != 2 or branches.shape[1] != 2:
            raise ValueError(f"branches must be an (n, 2) array, one row (k_i N/mm, c_i N*s/mm) per branch, got "
                             f"shape {branches.shape}")
        bad = (branches[:, 0] <= 0.0) | (branches[:, 1] < 0.0)
        if bad.any():  # k_i = 0 would make tau_i = c_i / k_i infinite, and K*(f) NaN
            row = int(np.argmax(bad))
            raise ValueError(f"a Prony series needs k_i > 0 and c_i >= 0 in every branch (passive), got branch "
                             f"{row + 1} = {show(tuple(branches[row].tolist()))}")
        branches.setflags(write=False)
        object.__setattr__(self, "equilibrium_stiffness", equilibrium)
        object.__setattr__(self, "branches", branches)
        f_min, f_max = _band(self.f_min, self.f_max)
        object.__setattr__(self, "f_min", f_min)
        object.__setattr__(self, "f_max", f_max)
        object.__setattr__(self, "tolerance", positive("tolerance", self.tolerance))
        object.__setattr__(self, "error", non_negative("error", self.error))

    def __len__(self) -> int:
        """The number of Maxwell branches."""
        return self.branches.shape[0]

    @property
    def relaxation_times(self) -> np.ndarray:
        """tau_i = c_i / k_i (s) of every branch."""
        return self.branches[:, 1] / self.branches[:, 0]

    def complex_stiffness(self, f: ArrayLike) -> np.ndarray:
        """K*(f) = k_0 + sum_i k_i i omega c_i / (k_i + i omega c_i) (N/mm) at frequencies f (Hz)."""
        f = positive_frequencies("f", f)
        x = 1j * 2.0 * np.pi * f[..., None] * self.relaxation_times
        return self.equilibrium_stiffness + (self.branches[:, 0] * x / (1.0 + x)).sum(axis=-1)

    def to_table(self) -> list[dict[str, Any]]:
        """The series as rows of parallel links for SAP2000 / ETABS (units N, mm, s).

        One row per link, all links between the same two joints, in parallel:

        * ``"K0"``: a *Linear* link of stiffness k_0 (N/mm) (omitted when k_0 = 0);
        * ``"M1"``, ``"M2"``, ...: a *Damper - Exponential* link each (the Maxwell damper of SAP2000 /
          ETABS: a linear spring in series with a dashpot whose force is c |v|^exponent), with
          ``stiffness`` k_i (N/mm), ``damping_coefficient`` c_i (N*s/mm, i.e. N (s/mm)^1) and
          ``damping_exponent`` 1 (a linear dashpot), in the link's direction of deformation (U1 for an
          axial link, U2 for a shear link).

        Every row also lists the relaxation time c / k (s).  With the model's units set to N, mm, s the
        numbers are typed as they are.  The nonlinear properties act in nonlinear time-history cases
        (fast nonlinear analysis or direct integration); linear load cases use the links' effective
        stiffness and damping, which the table does not set (K'(f) and K''(f) / omega at a chosen f
        from :meth:`complex_stiffness` are the consistent choice).
        """
        rows: list[dict[str, Any]] = []
        if self.equilibrium_stiffness > 0.0:
            rows.append({"link": "K0", "type": "Linear", "stiffness": self.equilibrium_stiffness,
                         "damping_coefficient": 0.0, "damping_exponent": None, "relaxation_time": None})
        for index, (stiffness, damping) in enumerate(self.branches, start=1):
            rows.append({"link": f"M{index}", "type": "Damper - Exponential", "stiffness": float(stiffness),
                         "damping_coefficient": float(damping), "damping_exponent": 1.0,
                         "relaxation_time": float(damping / stiffness)})
        return rows


# A fit: (largest relative error on the dense grid, relaxation times (s), stiffnesses k_0, k_i (N/mm));
# (inf, None, None) before any.
_Fit = tuple[float, np.ndarray | None, np.ndarray | None]


def _grid(f_min: float, f_max: float, per_decade: int) -> np.ndarray:
    count = int(np.ceil(np.log10(f_max / f_min) * per_decade)) + 1
    return np.logspace(np.log10(f_min), np.log10(f_max), max(count, 2))


def _basis(omega: np.ndarray, tau: np.ndarray) -> np.ndarray:
    """(points, n + 1) complex: the equilibrium spring and each unit Maxwell branch."""
    x = 1j * np.outer(omega, tau)
    return np.hstack([np.ones((omega.size, 1)), x / (1.0 + x)])


def _stiffnesses(basis: np.ndarray, target: np.ndarray, weight: np.ndarray) -> np.ndarray:
    """Non-negative (k_0, k_i) minimising the weighted relative error."""
    from scipy.optimize import nnls

    scale = weight / np.abs(target)
    matrix = basis * scale[:, None]
    rhs = target * scale
    stiffness, _ = nnls(np.vstack([matrix.real, matrix.imag]), np.concatenate([rhs.real, rhs.imag]),
                        maxiter=100 * basis.shape[1])
    return stiffness


def _relative_error(omega: np.ndarray, target: np.ndarray, tau: np.ndarray, stiffness: np.ndarray) -> np.ndarray:
    return np.abs(_basis(omega, tau) @ stiffness - target) / np.abs(target)


def _fit_branches(count: int, omega: np.ndarray, target: np.ndarray, check_omega: np.ndarray, check_target: np.ndarray,
                  *, tolerance: float, bounds: tuple[float, float]) -> _Fit:
    """(dense max error, tau, stiffness) of the best fit with ``count`` branches found; stops early once
    the tolerance is met."""
    from scipy.optimize import least_squares

    low, high = bounds
    start, end = np.log(1.0 / omega[-1]), np.log(1.0 / omega[0])
    log_tau = np.linspace(start, end, count + 2)[1:-1]
    weight = np.ones(omega.size)

    def residual(x: np.ndarray) -> np.ndarray:
        basis = _basis(omega, np.exp(x))
        error = (basis @ _stiffnesses(basis, target, weight) - target) * (weight / np.abs(target))
        return np.concatenate([error.real, error.imag])

    best: _Fit = (np.inf, None, None)
    for round_ in range(_LAWSON_ROUNDS):
        log_tau = least_squares(residual, log_tau, bounds=(low, high), xtol=1e-10).x
        tau = np.exp(log_tau)
        stiffness = _stiffnesses(_basis(omega, tau), target, weight)
        error = _relative_error(omega, target, tau, stiffness)
        if round_ == 0 and np.sqrt(np.mean(error**2)) > tolerance:
            break  # even the least-squares fit's RMS exceeds the tolerance: its maximum cannot meet it
        dense = _relative_error(check_omega, check_target, tau, stiffness).max()
        if dense < best[0]:
            best = (dense, tau, stiffness)
        if dense <= tolerance:
            break
        weight = weight * np.sqrt(error / error.max())
        weight /= weight.max()
    return best


def fit_prony(wall: Wall, f_min: float, f_max: float, tolerance: float = 0.01, max_branches: int = 30) -> PronySeries:
    """The Prony series with the fewest branches that matches ``wall``'s complex stiffness within
    ``tolerance`` (relative, on |K*|) over [``f_min``, ``f_max``] Hz (see the module for the method).

    ``wall``: anything with ``complex_stiffness(f)`` in N/mm (an :class:`~vdw_frames.FDMKDamper` or a
    :class:`~vdw_frames.SupportedDamper`).  The band may span at most :data:`MAX_BAND` (6 decades).
    ``tolerance`` in (0, 0.5]; ``max_branches``: the most
    branches tried before giving up with a ValueError.  Returns a :class:`PronySeries`.
    """
    f_min, f_max = _band(f_min, f_max)
    if f_max > MAX_BAND * f_min:
        raise ValueError(f"the band f_min = {f_min!r} ... f_max = {f_max!r} Hz spans {math.log10(f_max / f_min):.3g} "
                         f"decades; a Prony series is fitted over at most {math.log10(MAX_BAND):g} "
                         "(f_max <= 1e6 f_min): narrow the band to the frequencies the analysis excites")
    tolerance = positive("tolerance", tolerance)
    if tolerance > 0.5:
        raise ValueError(f"tolerance must lie in (0, 0.5], got {tolerance!r}")
    max_branches = whole_number("max_branches", max_branches, 1)
    frequencies = _grid(f_min, f_max, FIT_POINTS_PER_DECADE)
    check = _grid(f_min, f_max, CHECK_POINTS_PER_DECADE)
    target = np.asarray(wall.complex_stiffness(frequencies), dtype=complex)
    check_target = np.asarray(wall.complex_stiffness(check), dtype=complex)
    if (np.abs(check_target) == 0.0).any():
        raise ValueError("the wall has no stiffness (K* = 0) in the band: nothing to fit")
    omega, check_omega = 2.0 * np.pi * frequencies, 2.0 * np.pi * check
    bounds = (np.log(_SHORTEST / omega[-1]), np.log(_LONGEST / omega[0]))
    best: _Fit = (np.inf, None, None)
    for count in range(1, max_branches + 1):
        error, tau, stiffness = _fit_branches(count, omega, target, check_omega, check_target, tolerance=tolerance,
                                              bounds=bounds)
        if error < best[0]:
            best = (error, tau, stiffness)
        if error <= tolerance:
            break
    else:
        raise ValueError(f"no Prony series of at most {max_branches} branches reached tolerance {tolerance:g} over "
                         f"{f_min:g}-{f_max:g} Hz (best: {best[0]:.3g}); widen the tolerance or narrow the band")
    error, tau, stiffness = best
    assert tau is not None and stiffness is not None  # the loop stopped at a fit within the tolerance
    keep = stiffness[1:] > 0.0  # a branch the fit switched off is no branch
    order = np.argsort(tau[keep])
    branch_stiffness = stiffness[1:][keep][order]
    branches = np.column_stack([branch_stiffness, branch_stiffness * tau[keep][order]])
    return PronySeries(float(stiffness[0]), branches, f_min, f_max, tolerance, float(error))
