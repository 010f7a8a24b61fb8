"""Identification of FDMK parameters from storage and loss moduli (the paper's objective (12)).

Objective
---------
For test frequencies f_i (Hz) with measured G'_i and G''_i (MPa), minimise over G1, G2, eta1, eta2 >= 0
and 0 < r <= 1

    residual="absolute":  S = sum_i (G'(f_i) - G'_i)^2 + (G''(f_i) - G''_i)^2                (MPa^2)
    residual="relative":  S = sum_i ((G'(f_i) - G'_i) / G'_i)^2 + ((G''(f_i) - G''_i) / G''_i)^2   (-)

with G' + i G'' the complex modulus of :class:`~vdw_frames.element.damper.FDMKDamper` (eqs. (3)-(5)).  This
is the paper's (12), "the error between the model and the experimental complex modulus", written
out for the real and imaginary parts.

Why a global method, and which one
----------------------------------
The problem is badly conditioned: on the paper's data the optima sit on bounds (G1 = 0, r = 1), the
surface is flat along r, and several local minima exist.  Local least squares from a guess (the
paper's MATLAB route) lands wherever the guess lies.  The model, however, is linear in most of its
parameters.  Write the Maxwell branch with its ratio lambda = eta2 / G2 (s^r):

    G*(s) = G1 * 1  +  eta1 * s^r  +  G2 * lambda s^r / (1 + lambda s^r).

For fixed (r, lambda) the moduli G1, eta1, G2 enter linearly with non-negativity bounds: a
non-negative least-squares problem in three unknowns, solved *exactly* here by enumerating its
seven active sets (variable projection).  What remains is a two-dimensional search over (r, lambda),
done on a fixed grid (r on [R_MIN, 1], lambda over LOG_LAMBDA_SPAN decades either side of the data's
geometric-mean frequency), so every basin of the surface is sampled; the best grid points that are
local minima of the grid are then polished with ``scipy.optimize.least_squares`` (trust-region
reflective, bounds) in all free parameters.  Nothing is random: the result is a deterministic
function of the data, and it does not depend on the grid (``tests/paper/test_identification.py`` checks several
grids and a much denser independent search).

The ends of the lambda range are not lost optima: lambda -> infinity turns the Maxwell branch into
a spring (G1 + G2 appear only as a sum) and lambda -> 0 into an Abel dashpot (eta1 + eta2 as a sum);
both limits are the fractional Kelvin model, i.e. G2 = eta2 = 0, which the active-set enumeration
includes at every grid point.  When the optimum is that degenerate model it is returned with
G2 = eta2 = 0.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Collection
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import least_squares

from .._validation import check_memory, finite_array, finite_scalar, show, whole_number
from ..element.damper import FDMKDamper

PARAMETERS = ("G1", "G2", "eta1", "eta2", "r")
RESIDUALS = ("absolute", "relative")
R_MIN = 1.0e-3  # lowest order searched; the bound itself is r > 0 (r -> 0 makes G* real: G'' -> 0)
LOG_LAMBDA_SPAN = 6.0  # decades of |lambda s^r| at the reference frequency searched either side of 1
DEFAULT_GRID = (41, 49)  # (orders r, values of log lambda)
START_BAND = 0.05  # polish every refined grid minimum within 5 % of the best one ...
MAX_PROFILE_MINIMA = 8  # ... and the best points of up to 8 local minima of the profile over r
MAX_STARTS = 40  # at most this many starts from the band (thinned evenly in r)
# Bytes the grid search holds per grid point and datum (G' or G''): measured ~180 (peak traced memory of
# identify on 6 and 60 frequencies), rounded up.  A grid whose arrays would pass the 2 GiB limit is refused.
_BYTES_PER_POINT_AND_DATUM = 256
_GOLDEN_STEPS = 40  # golden-section steps refining u between grid neighbours (0.618^40 ~ 5e-9)
_LINEAR = ("G1", "eta1", "G2")  # the coefficients solved by non-negative least squares
_BOUND_FACES = ({"G2": 0.0, "eta2": 0.0}, {"G1": 0.0}, {"eta1": 0.0}, {"r": 1.0})
_SUBSETS = {k: [s for n in range(1, k + 1) for s in itertools.combinations(range(k), n)] for k in range(4)}


@dataclass(frozen=True)
class IdentificationResult:
    """Result of :func:`identify`.

    params : dict
        G1, G2 (MPa), eta1, eta2 (MPa*s^r), r (-) at the global minimum.
    sse : float
        The minimised sum of squares (MPa^2 for "absolute", dimensionless for "relative").
    residuals : ndarray
        The 2n terms whose squares sum to ``sse``: model minus test, G' terms at every frequency
        then G'' terms, divided by the test values when ``residual == "relative"``.
    at_bound : tuple of str
        Parameters on a bound: G1, G2, eta1 or eta2 equal to 0, r equal to 1 (or to the search floor
        R_MIN).  When G2 = 0 the Maxwell branch is absent and eta2 is returned as 0 (on its bound).
    standard_errors : dict
        Approximate standard errors, sqrt(diag(s^2 (J^T J)^-1)) with s^2 = sse / (2n - p), J the
        Jacobian of the residuals with respect to the p free parameters off their bounds.  ``None``
        for a parameter that is fixed, on a bound, or where J^T J is singular or 2n <= p.
    residual, fixed
        The objective and pinned parameters used.
    frequency, storage_modulus, loss_modulus
        The data (Hz, MPa, MPa).
    """

    params: dict[str, float]
    sse: float
    residuals: np.ndarray
    at_bound: tuple[str, ...]
    standard_errors: dict[str, float | None]
    residual: str
    fixed: dict[str, float]
    frequency: np.ndarray = field(repr=False)
    storage_modulus: np.ndarray = field(repr=False)
    loss_modulus: np.ndarray = field(repr=False)

    def damper(self, area: float = 1.0e6, thickness: float = 10.0,
               strain_range: tuple[float, float] | None = None) -> FDMKDamper:
        """The identified damper with shear area ``area`` (mm^2) and layer thickness ``thickness`` (mm).

        Defaults are the paper's A = 1e6 mm^2 and h = 10 mm.
        """
        p = self.params
        return FDMKDamper(G1=p["G1"], G2=p["G2"], eta1=p["eta1"], eta2=p["eta2"], r=p["r"], area=area,
                          thickness=thickness, strain_range=strain_range)

    def relative_errors(self) -> tuple[np.ndarray, np.ndarray]:
        """(model - test) / test for G' and for G'' at every frequency: two arrays."""
        modulus = self.damper().complex_modulus(self.frequency)
        return (modulus.real / self.storage_modulus - 1.0, modulus.imag / self.loss_modulus - 1.0)

    def max_relative_errors(self) -> tuple[float, float]:
        """(max |relative error| in G', max |relative error| in G'') over the data."""
        storage, loss = self.relative_errors()
        return float(np.max(np.abs(storage))), float(np.max(np.abs(loss)))


def identify(frequency: ArrayLike, storage_modulus: ArrayLike, loss_modulus: ArrayLike, residual: str = "absolute",
             fixed: dict[str, float] | None = None, grid: tuple[int, int] = DEFAULT_GRID) -> IdentificationResult:
    """Global least-squares FDMK parameters for measured G' and G'' (objective (12); see module doc).

    frequency in Hz (> 0; repeated frequencies allowed, e.g. several strain levels pooled),
    storage_modulus and loss_modulus in MPa; ``residual`` is "absolute" or "relative"; ``fixed``
    pins parameters, e.g. ``{"r": 0.6}``; ``grid`` = (number of orders r, number of log lambda
    values) of the global search, whole numbers >= 3 (a grid whose search would hold more than 2 GiB is
    refused before allocating).  Raises ValueError naming the offending value.
    """
    problem = _Problem(frequency, storage_modulus, loss_modulus, residual, fixed)
    n_r, n_u = _grid_size(grid)
    points = (1 if "r" in problem.fixed else n_r) * (n_u if problem.searches_lambda else 1)
    check_memory(f"identify(grid = {show(grid)}, {problem.frequency.size} frequencies)", points,
                 _BYTES_PER_POINT_AND_DATUM * 2 * problem.frequency.size, "use a coarser grid (the default is "
                 f"{DEFAULT_GRID}; the result does not depend on it)", unit="grid points")
    r_values = np.array([problem.fixed["r"]]) if "r" in problem.fixed else np.linspace(R_MIN, 1.0, n_r)
    u_values = np.linspace(-LOG_LAMBDA_SPAN, LOG_LAMBDA_SPAN, n_u) if problem.searches_lambda else np.zeros(1)

    starts = [problem.full_parameters(r, u, c) for r, u, c in problem.starts(r_values, u_values)]
    candidates = [problem.polish(start) for start in starts] + starts
    best = min(candidates, key=problem.sse)
    # An optimum on a bound is approached only slowly from inside: polish again with each bound imposed.
    on_bound = [problem.polish(dict(best, **pins), pinned=pins) for pins in _BOUND_FACES
                if not set(pins) & set(problem.fixed)]
    best = min([best, *on_bound], key=problem.sse)
    return problem.result(problem.snap(best))


# ---------------------------------------------------------------------------------------------- internals
def _grid_size(grid: object) -> tuple[int, int]:
    message = f"grid must be two whole numbers >= 3 (orders, log lambda values), got {show(grid)}"
    if isinstance(grid, (str, bytes)) or not isinstance(grid, (tuple, list, np.ndarray)) or len(grid) != 2:
        raise ValueError(message)
    try:
        n_r, n_u = (whole_number("grid", n, 3) for n in grid)
    except ValueError:
        raise ValueError(message) from None
    return n_r, n_u


def _nonnegative_least_squares(columns: NDArray[np.float64],
                               target: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Exact NNLS for up to three columns, batched over leading axes of ``columns`` (..., m, k).

    The minimiser is the unconstrained least-squares solution on its support; enumerating every
    support and keeping the best one with non-negative coefficients is exact for k <= 3.
    Returns (sum of squares, coefficients).
    """
    shape, k = columns.shape[:-2], columns.shape[-1]
    best = np.broadcast_to(np.sum(target**2, axis=-1), shape).copy()
    coefficients = np.zeros((*shape, k))
    for subset in _SUBSETS[k]:
        sub = columns[..., list(subset)]
        solution = np.einsum("...im,...m->...i", np.linalg.pinv(sub), target)
        fit = np.sum((np.einsum("...mi,...i->...m", sub, solution) - target) ** 2, axis=-1)
        better = np.all(solution >= 0.0, axis=-1) & (fit < best)
        best = np.where(better, fit, best)
        full = np.zeros_like(coefficients)
        full[..., list(subset)] = solution
        coefficients = np.where(better[..., None], full, coefficients)
    return best, coefficients


def _golden_section(function: Callable[[NDArray[np.float64]], NDArray[np.float64]], low: ArrayLike, high: ArrayLike,
                    steps: int = _GOLDEN_STEPS) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Vectorised golden-section minimisation of ``function`` (array -> array) on [low, high] elementwise.

    Returns (argmin, min) per element, the better of the two final interior points.
    """
    ratio = (np.sqrt(5.0) - 1.0) / 2.0
    a, b = np.array(low, dtype=float), np.array(high, dtype=float)
    c, d = b - ratio * (b - a), a + ratio * (b - a)
    fc, fd = function(c), function(d)
    for _ in range(steps):
        left = fc <= fd  # the minimum lies in [a, d]
        a, b = np.where(left, a, c), np.where(left, d, b)
        new = np.where(left, b - ratio * (b - a), a + ratio * (b - a))
        value = function(new)
        c, d, fc, fd = (np.where(left, new, d), np.where(left, c, new),
                        np.where(left, value, fd), np.where(left, fc, value))
    better = fc <= fd
    return np.where(better, c, d), np.where(better, fc, fd)


class _Problem:
    """Validated data, weights and pinned parameters of one identification."""

    def __init__(self, frequency: ArrayLike, storage_modulus: ArrayLike, loss_modulus: ArrayLike, residual: str,
                 fixed: dict[str, float] | None) -> None:
        f = finite_array("frequency", frequency)
        storage = finite_array("storage_modulus", storage_modulus)
        loss = finite_array("loss_modulus", loss_modulus)
        if not (f.size == storage.size == loss.size):
            raise ValueError(f"frequency, storage_modulus and loss_modulus must have equal lengths, got "
                             f"{f.size}, {storage.size} and {loss.size}")
        if (f <= 0.0).any():
            raise ValueError(f"frequency must be > 0 Hz, got {show(f[f <= 0.0][0])}")
        for name, values in (("storage_modulus", storage), ("loss_modulus", loss)):
            if (values < 0.0).any():  # a passive material stores and dissipates: G' >= 0 and G'' >= 0
                index = int(np.argmax(values < 0.0))
                raise ValueError(f"{name} must be >= 0 MPa (a passive material), got {show(values[index])} "
                                 f"at index {index} (f = {show(f[index])} Hz)")
        if residual not in RESIDUALS:
            raise ValueError(f"residual must be one of {RESIDUALS}, got {residual!r}")
        if residual == "relative":
            for name, values in (("storage_modulus", storage), ("loss_modulus", loss)):
                if (values == 0.0).any():
                    raise ValueError(f"residual='relative' divides by {name}, which contains 0.0")
        self.fixed = self._check_fixed(fixed)
        free = [name for name in PARAMETERS if name not in self.fixed]
        if 2 * f.size < len(free):
            raise ValueError(f"{2 * f.size} data (G' and G'' at {f.size} frequencies) cannot determine "
                             f"{len(free)} free parameters {free}")
        self.free = free
        self.residual = residual
        self.frequency, self.storage, self.loss = f, storage, loss
        self.weights = (np.concatenate([1.0 / storage, 1.0 / loss]) if residual == "relative"
                        else np.ones(2 * f.size))
        self.target = np.concatenate([storage, loss]) * self.weights
        s = 2j * np.pi * f
        self.log_s = np.log(s)
        self.log_reference = np.mean(np.log(2.0 * np.pi * f))  # log of the geometric-mean omega
        fixed_g2, fixed_eta2 = self.fixed.get("G2"), self.fixed.get("eta2")
        self.maxwell_off = fixed_g2 == 0.0 or fixed_eta2 == 0.0
        self.searches_lambda = not self.maxwell_off and not (fixed_g2 is not None and fixed_eta2 is not None)
        self.linear = [name for name in _LINEAR if name not in self.fixed
                       and not (name == "G2" and (fixed_eta2 is not None or self.maxwell_off))]

    @staticmethod
    def _check_fixed(fixed: dict[str, float] | None) -> dict[str, float]:
        if fixed is None:
            return {}
        if not isinstance(fixed, dict):
            raise ValueError(f"fixed must be a dict of parameter values, got {fixed!r}")
        checked = {}
        for name, given in fixed.items():
            if name not in PARAMETERS:
                raise ValueError(f"fixed has unknown parameter {name!r}; expected some of {PARAMETERS}")
            value = finite_scalar(f"fixed[{name!r}]", given)
            if name == "r" and not 0.0 < value <= 1.0:
                raise ValueError(f"fixed['r'] must lie in (0, 1], got {value!r}")
            if name != "r" and value < 0.0:
                raise ValueError(f"fixed[{name!r}] must be >= 0, got {value!r}")
            checked[name] = value
        return checked

    # -- the model, through FDMKDamper -------------------------------------------------------------
    def weighted_residuals(self, params: dict[str, float]) -> NDArray[np.float64]:
        modulus = FDMKDamper(G1=params["G1"], G2=params["G2"], eta1=params["eta1"], eta2=params["eta2"],
                             r=params["r"]).complex_modulus(self.frequency)
        return np.concatenate([modulus.real, modulus.imag]) * self.weights - self.target

    def sse(self, params: dict[str, float]) -> float:
        return float(np.sum(self.weighted_residuals(params) ** 2))

    def _lambda(self, r: NDArray[np.float64] | float, u: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """eta2 / G2 (s^r) for the search variable u = log10 |lambda (i omega_ref)^r| (arrays broadcast)."""
        if not self.searches_lambda:
            g2, eta2 = self.fixed.get("G2", 0.0), self.fixed.get("eta2", 0.0)
            return np.broadcast_to(eta2 / g2 if g2 > 0.0 else 0.0, np.shape(u)).astype(float)
        return 10.0**u * np.exp(-r * self.log_reference)

    def projected_points(self, r: ArrayLike, u: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Variable projection at the points (r[k], u[k]): (sse of shape (n,), linear coefficients (n, k)).

        For each point the coefficients in ``self.linear`` (among G1, eta1, G2) are the exact
        non-negative least-squares solution for that order r and ratio lambda = eta2 / G2.
        """
        r, u = (np.ravel(x) for x in np.broadcast_arrays(np.asarray(r, dtype=float), np.asarray(u, dtype=float)))
        s_r = np.exp(r[:, None] * self.log_s[None, :])  # (i omega)^r, principal branch, (n, m)
        lam = self._lambda(r, u)[:, None]
        maxwell = lam * s_r / (1.0 + lam * s_r)  # G* of a Maxwell branch with G2 = 1, eta2 = lam
        columns = {"G1": np.ones_like(s_r), "eta1": s_r, "G2": maxwell}
        offset = np.zeros_like(s_r)
        for name in ("G1", "eta1"):
            if name in self.fixed:
                offset = offset + self.fixed[name] * columns[name]
        if not self.maxwell_off and "G2" not in self.linear:
            with np.errstate(divide="ignore"):
                g2 = self.fixed["G2"] if "G2" in self.fixed else self.fixed["eta2"] / lam
            offset = offset + g2 * maxwell
        rest = self.target - np.concatenate([offset.real, offset.imag], axis=-1) * self.weights
        if not self.linear:
            return np.sum(rest**2, axis=-1), np.zeros((r.size, 0))
        design = np.stack([np.concatenate([columns[name].real, columns[name].imag], axis=-1)
                           for name in self.linear], axis=-1) * self.weights[:, None]
        return _nonnegative_least_squares(design, rest)

    def projected(self, r_values: NDArray[np.float64],
                  u_values: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Variable projection on the grid: (sse, linear coefficients) of shape (len(r), len(u)[, k])."""
        r_grid, u_grid = np.meshgrid(r_values, u_values, indexing="ij")
        sse, coefficients = self.projected_points(r_grid, u_grid)
        return sse.reshape(r_grid.shape), coefficients.reshape((*r_grid.shape, len(self.linear)))

    def starts(self, r_values: NDArray[np.float64],
               u_values: NDArray[np.float64]) -> list[tuple[float, float, NDArray[np.float64]]]:
        """Starting points (r, u, linear coefficients) for the local polish, from the grid.

        1. The projected sum on the (r, u) grid.
        2. Along every row (fixed r), each local minimum in u is refined by golden-section search
           between its neighbours, so each row gives the profile value min over u of the sum at that
           r to within round-off, whatever the spacing of the u grid.
        3. Starts: every refined row minimum within START_BAND (relative) of the best one, plus the
           best point of every local minimum of the profile over r (at most MAX_PROFILE_MINIMA); when
           more than MAX_STARTS lie in the band they are thinned evenly in r.
        """
        sse, _ = self.projected(r_values, u_values)
        n_u = u_values.size
        padded = np.pad(sse, ((0, 0), (1, 1)), constant_values=np.inf)
        is_min = (sse <= padded[:, :-2]) & (sse <= padded[:, 2:])
        row_list: list[int] = []
        col_list: list[int] = []
        for i in range(r_values.size):  # the best 3 local minima in u of each row (a plateau counts many)
            js = np.flatnonzero(is_min[i])
            js = js[np.argsort(sse[i, js], kind="stable")][:3]
            row_list.extend([i] * js.size)
            col_list.extend(js)
        rows, cols = np.array(row_list), np.array(col_list)
        r = r_values[rows]
        if n_u > 1 and self.searches_lambda:
            low = u_values[np.maximum(cols - 1, 0)]
            high = u_values[np.minimum(cols + 1, n_u - 1)]
            u, value = _golden_section(lambda x: self.projected_points(r, x)[0], low, high)
            grid_value = sse[rows, cols]
            keep_grid = grid_value <= value
            u = np.where(keep_grid, u_values[cols], u)
            value = np.where(keep_grid, grid_value, value)
        else:
            u, value = u_values[cols], sse[rows, cols]
        # Per row: distinct refined minima (a plateau in u refines to one value), best first, at most 3.
        kept_list: list[np.intp] = []
        for i in np.unique(rows):
            members = np.flatnonzero(rows == i)
            members = members[np.argsort(value[members], kind="stable")]
            distinct: list[np.intp] = []
            for k in members:
                if all(abs(value[k] - value[m]) > 1e-9 * max(value[m], 1e-300) for m in distinct):
                    distinct.append(k)
            kept_list.extend(distinct[:3])
        kept = np.array(kept_list)
        best = float(value[kept].min())
        band = kept[value[kept] <= best * (1.0 + START_BAND) + 1e-300]
        band = band[np.argsort(r[band], kind="stable")]
        if band.size > MAX_STARTS:
            band = band[np.unique(np.round(np.linspace(0, band.size - 1, MAX_STARTS)).astype(int))]
        # Local minima of the profile over r (the best refined value of each row).
        profile_rows = np.unique(rows[kept])
        profile = np.array([value[kept][rows[kept] == i].min() for i in profile_rows])
        left = np.r_[np.inf, profile[:-1]]
        right = np.r_[profile[1:], np.inf]
        minima_rows = profile_rows[(profile <= left) & (profile <= right)]
        minima = [kept[rows[kept] == i][np.argmin(value[kept][rows[kept] == i])] for i in minima_rows]
        minima = sorted(minima, key=lambda k: value[k])[:MAX_PROFILE_MINIMA]
        chosen = list(dict.fromkeys(list(band) + list(minima)))
        _chosen_sse, coefficients = self.projected_points(r[chosen], u[chosen])
        return [(float(r[k]), float(u[k]), coefficients[n]) for n, k in enumerate(chosen)]

    def full_parameters(self, r: float, u: float, coefficients: NDArray[np.float64]) -> dict[str, float]:
        """All five parameters from a grid point (r, u) and its linear coefficients."""
        params = dict(self.fixed)
        params.update(zip(self.linear, (float(c) for c in coefficients), strict=True))
        params["r"] = float(r)
        if self.maxwell_off:
            params.setdefault("G2", 0.0)
            params.setdefault("eta2", 0.0)
        elif self.searches_lambda:
            lam = float(self._lambda(r, u))
            if "eta2" in self.fixed:
                params["G2"] = self.fixed["eta2"] / lam
            else:
                params["eta2"] = params["G2"] * lam
        return {name: params[name] for name in PARAMETERS}

    # -- local polishing ----------------------------------------------------------------------------
    def polish(self, start: dict[str, float], pinned: Collection[str] = ()) -> dict[str, float]:
        """least_squares (trf, bounds) in the free parameters not in ``pinned`` from ``start``."""
        free = [name for name in self.free if name not in pinned]
        if not free:  # a bound face pinning the only free parameter: nothing to polish (scipy 1.15 refuses x0 = [])
            return dict(start)
        lower = np.array([R_MIN if name == "r" else 0.0 for name in free])
        upper = np.array([1.0 if name == "r" else np.inf for name in free])
        x0 = np.clip([start[name] for name in free], lower, upper)

        def params_of(x: NDArray[np.float64]) -> dict[str, float]:
            params = dict(start)
            params.update(zip(free, np.clip(x, lower, upper), strict=True))
            return params

        solution = least_squares(lambda x: self.weighted_residuals(params_of(x)), x0, bounds=(lower, upper),
                                 method="trf", x_scale="jac", ftol=1e-14, xtol=1e-14, gtol=1e-14, max_nfev=3000)
        return params_of(solution.x)

    def snap(self, params: dict[str, float]) -> dict[str, float]:
        """Put parameters within round-off of a bound onto it (kept only if the sum does not rise)."""
        params = dict(params)
        scale = float(np.max(np.abs(np.concatenate([self.storage, self.loss]))))
        if params["G2"] <= 1e-9 * scale and "G2" not in self.fixed:
            params.update(G2=0.0, eta2=0.0 if "eta2" not in self.fixed else params["eta2"])
        for name in ("G1", "G2", "eta1", "eta2"):
            if name not in self.fixed and 0.0 < params[name] <= 1e-9 * scale:
                trial = dict(params, **{name: 0.0})
                if self.sse(trial) <= self.sse(params) * (1.0 + 1e-9) + 1e-20:
                    params = trial
        if "r" not in self.fixed and params["r"] >= 1.0 - 1e-9:
            params["r"] = 1.0
        return params

    def result(self, params: dict[str, float]) -> IdentificationResult:
        params = {name: float(value) for name, value in params.items()}
        residuals = self.weighted_residuals(params)
        at_bound = tuple(name for name in PARAMETERS if
                         (name != "r" and params[name] == 0.0) or (name == "r" and params[name] in (1.0, R_MIN)))
        return IdentificationResult(
            params=params, sse=float(np.sum(residuals**2)), residuals=residuals, at_bound=at_bound,
            standard_errors=self._standard_errors(params, at_bound), residual=self.residual,
            fixed=dict(self.fixed), frequency=self.frequency, storage_modulus=self.storage, loss_modulus=self.loss)

    def _standard_errors(self, params: dict[str, float], at_bound: tuple[str, ...]) -> dict[str, float | None]:
        errors: dict[str, float | None] = {name: None for name in PARAMETERS}
        names = [name for name in self.free if name not in at_bound]
        dof = self.target.size - len(names)
        if not names or dof <= 0:
            return errors
        columns = []
        for name in names:  # central differences, steps relative to the value
            step = 1e-6 * max(abs(params[name]), 1e-6)
            up, down = dict(params), dict(params)
            up[name] += step
            down[name] -= step
            if name == "r" and up["r"] > 1.0:
                up["r"], step = 1.0, 0.5 * (1.0 - down["r"])
            columns.append((self.weighted_residuals(up) - self.weighted_residuals(down)) / (2.0 * step))
        jacobian = np.column_stack(columns)
        normal = jacobian.T @ jacobian
        if np.linalg.cond(normal) > 1e12:
            return errors
        variance = float(np.sum(self.weighted_residuals(params) ** 2)) / dof
        covariance = variance * np.linalg.inv(normal)
        errors.update({name: float(np.sqrt(covariance[k, k])) for k, name in enumerate(names)})
        return errors
