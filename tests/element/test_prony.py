"""Prony series (generalized Maxwell) export of FDMK walls (vdw_frames.element.prony): the bound, passivity
and the SAP2000/ETABS table.  The native OpenSees material and a frame built from it:
tests/interop/test_prony_material.py.

References: the FDMK complex stiffness in closed form (tests/reference.py, independent of the package's
``transfer``) and the generalized Maxwell stiffness written out here from the branches.
"""

import numpy as np
import pytest
from builders import BOTH_BRANCHES
from reference import closed_form_moduli

from vdw_frames import FDMKDamper, SupportedDamper
from vdw_frames.element.prony import MAX_BAND, PronySeries, fit_prony
from vdw_frames.paper import fitted

BAND = (0.1, 10.0)  # Hz: the band of a building's first few modes


def order_walls():
    """One wall per fractional order asked for, Kelvin and Maxwell branches both active."""
    return {r: FDMKDamper(**BOTH_BRANCHES, r=r, area=1.0e6, thickness=10.0)
            for r in (0.2, 0.5, 0.8, 1.0)}


def maxwell_stiffness(f, k0, branches):
    """k_0 + sum k_i i w c_i / (k_i + i w c_i), written out from the branches (N/mm)."""
    omega = 2.0 * np.pi * np.asarray(f)[:, None]
    k, c = branches[:, 0], branches[:, 1]
    return k0 + (k * 1j * omega * c / (k + 1j * omega * c)).sum(axis=1)


def check_frequencies(f_min, f_max, count=20000, seed=3):
    """Log-uniform random frequencies in the band plus its edges: a grid the fit never saw."""
    draws = np.random.default_rng(seed).uniform(np.log(f_min), np.log(f_max), count)
    return np.concatenate([[f_min, f_max], np.exp(draws)])


@pytest.fixture(scope="module")
def series():
    return {r: wall.prony(*BAND, tolerance=0.01) for r, wall in order_walls().items()}


@pytest.mark.parametrize("r", [0.2, 0.5, 0.8, 1.0])
def test_the_bound_holds_on_a_dense_grid_and_the_series_is_passive(series, r):
    wall, prony = order_walls()[r], series[r]
    f = check_frequencies(*BAND)
    parameters = {name: getattr(wall, name) for name in ("G1", "G2", "eta1", "eta2", "r")}
    storage, loss = closed_form_moduli(parameters, f)
    exact = (storage + 1j * loss) * wall.area / wall.thickness
    fitted_stiffness = maxwell_stiffness(f, prony.equilibrium_stiffness, prony.branches)
    error = np.abs(fitted_stiffness - exact) / np.abs(exact)
    assert error.max() <= 0.01
    assert error.max() == pytest.approx(prony.error, rel=0.02)  # the reported error is the achieved one
    # Passive: every stiffness and damping coefficient >= 0 (so K'' >= 0 at every frequency).
    assert prony.equilibrium_stiffness >= 0.0 and (prony.branches >= 0.0).all()
    assert (maxwell_stiffness(np.logspace(-3, 3, 200), prony.equilibrium_stiffness, prony.branches).imag >= 0).all()
    # Few branches, relaxation times ascending: measured 3, 4, 4, 2 for r = 0.2, 0.5, 0.8, 1 (errors 0.95,
    # 0.96, 0.74, 0.09 %).
    assert 1 <= len(prony) <= 5
    assert (np.diff(prony.relaxation_times) > 0).all()
    np.testing.assert_allclose(prony.complex_stiffness(f), fitted_stiffness, rtol=1e-12)


def test_a_tighter_tolerance_takes_more_branches_and_meets_its_bound():
    wall = order_walls()[0.5]
    loose, tight = wall.prony(*BAND, tolerance=0.05), wall.prony(*BAND, tolerance=0.002)
    assert len(loose) < len(tight)
    f = check_frequencies(*BAND)
    for prony, tolerance in ((loose, 0.05), (tight, 0.002)):
        exact = wall.complex_stiffness(f)
        assert (np.abs(prony.complex_stiffness(f) - exact) / np.abs(exact)).max() <= tolerance


def test_a_supported_wall_is_fitted_as_the_assembly():
    wall = SupportedDamper(fitted(300, area=0.4e6), 2.0e5)
    prony = wall.prony(0.2, 5.0, tolerance=0.01)
    f = check_frequencies(0.2, 5.0)
    bare = wall.damper.complex_stiffness(f)
    assembly = bare * 2.0e5 / (bare + 2.0e5)  # springs in series, written out
    assert (np.abs(prony.complex_stiffness(f) - assembly) / np.abs(assembly)).max() <= 0.01


def test_the_table_rows_are_the_series(series):
    prony = series[0.5]
    rows = prony.to_table()
    k0 = sum(row["stiffness"] for row in rows if row["type"] == "Linear")
    links = [row for row in rows if row["type"] == "Damper - Exponential"]
    assert k0 == prony.equilibrium_stiffness and len(links) == len(prony)
    assert all(row["damping_exponent"] == 1.0 for row in links)
    branches = np.array([[row["stiffness"], row["damping_coefficient"]] for row in links])
    np.testing.assert_allclose([row["relaxation_time"] for row in links], branches[:, 1] / branches[:, 0])
    f = np.logspace(-1, 1, 50)
    np.testing.assert_allclose(maxwell_stiffness(f, k0, branches), prony.complex_stiffness(f), rtol=1e-14)


def test_bad_bands_tolerances_branch_counts_and_negative_branches_are_refused():
    wall = order_walls()[0.5]
    with pytest.raises(ValueError, match="f_max must exceed f_min"):
        wall.prony(5.0, 1.0)
    with pytest.raises(ValueError, match="f_min"):
        wall.prony(0.0, 1.0)
    with pytest.raises(ValueError, match="tolerance"):
        wall.prony(0.1, 10.0, tolerance=0.0)
    with pytest.raises(ValueError, match="tolerance"):
        wall.prony(0.1, 10.0, tolerance=0.9)
    with pytest.raises(ValueError, match="no Prony series of at most 2 branches"):
        fit_prony(wall, 0.01, 100.0, tolerance=1e-4, max_branches=2)
    with pytest.raises(ValueError, match="passive"):
        PronySeries(1.0, np.array([[1.0, -1.0]]), 0.1, 1.0, 0.01, 0.0)


@pytest.mark.parametrize("branches, match", [
    ([1.0, 2.0, 3.0], r"branches must be an \(n, 2\) array.*got shape \(3,\)"),
    ([[1.0, 2.0, 3.0]], r"branches must be an \(n, 2\) array.*got shape \(1, 3\)"),
    ("ab", "branches must be real numbers"),
    ([[1.0, np.nan]], "branches must be finite"),
    ([[0.0, 2.0]], r"k_i > 0 and c_i >= 0 in every branch \(passive\), got branch 1 = \(0.0, 2.0\)"),
])
def test_badly_shaped_or_inert_branches_are_refused_by_name(branches, match):
    # Before: numpy's "cannot reshape array of size 3 into shape (2)", and a k_i = 0 branch gave NaN stiffness.
    with pytest.raises(ValueError, match=match):
        PronySeries(1.0, branches, 0.1, 10.0, 0.01, 0.0)


@pytest.mark.parametrize("k0, match", [(np.nan, "equilibrium_stiffness must be finite"),
                                       ("1", "equilibrium_stiffness must be a real number"),
                                       (-1.0, "equilibrium_stiffness must be >= 0")])
def test_a_bad_equilibrium_stiffness_is_refused_by_name(k0, match):
    with pytest.raises(ValueError, match=match):
        PronySeries(k0, [[1.0, 2.0]], 0.1, 10.0, 0.01, 0.0)


def test_a_series_without_branches_is_a_spring():
    spring = PronySeries(5.0, [], 0.1, 10.0, 0.01, 0.0)
    np.testing.assert_array_equal(spring.complex_stiffness([0.1, 1.0]), [5.0, 5.0])


def test_a_band_beyond_six_decades_is_refused_before_fitting():
    # 0.1 Hz ... 1e12 Hz ran for minutes and 1e300 never returned; 6 decades are fitted (about 1 s).
    wall = order_walls()[0.5]
    for f_max in (1.0e12, 1.0e300, 0.1 * MAX_BAND * (1 + 1e-12)):
        with pytest.raises(ValueError, match=r"band f_min = 0.1 \.\.\. f_max = .* Hz spans .* decades; .* at most 6"):
            wall.prony(0.1, f_max)
    series = wall.prony(0.01, 0.01 * MAX_BAND, tolerance=0.01)
    f = check_frequencies(0.01, 0.01 * MAX_BAND)
    assert np.max(np.abs(series.complex_stiffness(f) / wall.complex_stiffness(f) - 1)) <= 0.01
