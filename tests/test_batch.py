"""Batch analyses: identical to simulate, on thread, process and Dask executors."""

import concurrent.futures
import csv
import dataclasses

import numpy as np
import pytest
from reference import tapered_sine

from vdw_frames import FDMKDamper, GroundMotion, ShearBuilding, simulate
from vdw_frames.frame.batch import run_batch, scale_factors_to_pga, scale_factors_to_spectral_acceleration

WALL = FDMKDamper(G1=0.0, G2=3.0, eta1=0.3, eta2=2.0, r=0.5, area=2.0e5)


def building(heights=True):
    return ShearBuilding([300.0, 300.0, 250.0], [2e5, 1.8e5, 1.5e5], walls={1: [WALL, WALL], 3: WALL},
                         story_heights=[3500.0] * 3 if heights else None)


def motions():
    t = np.arange(801) * 0.01
    return [GroundMotion(tapered_sine(t, f, 1500.0, 2.0, 8.0), 0.01, name=f"sine {f} Hz") for f in (1.1, 2.7)]


def test_batch_peaks_equal_simulate():
    records = motions()
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        result = run_batch(building(), records, [0.5, 2.0], executor=pool, progress=False)
    assert result.peak_drift.shape == (2, 2, 3) and result.peak_base_shear.shape == (2, 2, 1)
    for m, motion in enumerate(records):
        for s, scale in enumerate((0.5, 2.0)):
            single = simulate(building(), motion.scaled(scale))
            np.testing.assert_array_equal(result.peak_drift[m, s], single.peak_drift)
            np.testing.assert_array_equal(result.peak_drift_ratio[m, s], single.peak_drift_ratio)
            np.testing.assert_array_equal(result.peak_absolute_acceleration[m, s], single.peak_absolute_acceleration)
            np.testing.assert_array_equal(result.peak_story_wall_force[m, s], single.peak_story_wall_force)
            assert result.peak_base_shear[m, s, 0] == single.peak_base_shear
            assert result.pga[m, s] == pytest.approx(scale * motion.pga)


def test_default_process_pool_and_per_motion_scales(tmp_path):
    records = motions()
    factors = scale_factors_to_pga(records, [1000.0, 3000.0])
    result = run_batch(building(heights=False), records, factors, progress=False)
    np.testing.assert_allclose(result.pga, [[1000.0, 3000.0]] * 2, rtol=1e-12)
    assert result.peak_drift_ratio is None
    # Linear frame: peaks scale with the record.
    np.testing.assert_allclose(result.peak_drift[:, 1], 3 * result.peak_drift[:, 0], rtol=1e-10)
    path = tmp_path / "peaks.csv"
    result.to_csv(path)
    rows = list(csv.DictReader(path.open()))
    assert len(rows) == 2 * 2 * 3
    assert float(rows[4]["peak_drift_mm"]) == result.peak_drift[0, 1, 1]
    assert rows[0]["peak_drift_ratio_-"] == ""


def test_spectral_scale_factors_hit_the_target():
    records = motions()
    factors = scale_factors_to_spectral_acceleration(records, [2000.0], period=0.5)
    for motion, (factor,) in zip(records, factors):
        assert motion.scaled(factor).scale_factor_to_spectral_acceleration(2000.0, 0.5) == pytest.approx(1.0)


def test_batch_on_a_dask_local_cluster():
    distributed = pytest.importorskip("distributed", reason="dask[distributed] not installed (extra 'dask')")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        result = run_batch(building(), motions()[:1], [1.0, 1.5], executor=client.get_executor(), progress=False)
    single = simulate(building(), motions()[0].scaled(1.5))
    np.testing.assert_array_equal(result.peak_drift[0, 1], single.peak_drift)


def test_batch_reports_worker_warnings_and_failures():
    bounded = FDMKDamper(G1=0.0, G2=3.0, eta1=0.3, eta2=2.0, r=0.5, area=2.0e5, strain_range=(2.0, 3.0))
    frame = ShearBuilding([300.0], [2e5], walls={1: bounded})
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        with pytest.warns(UserWarning, match=r"sine 1.1 Hz x 0.5: wall peak strain outside"):
            run_batch(frame, motions()[:1], [0.5], executor=pool, progress=False)
        with pytest.raises(ValueError, match="overflowed"):
            run_batch(frame, motions()[:1], [1.0, 1e200], executor=pool, progress=False)


@pytest.mark.parametrize("args, match", [
    (dict(motions=[]), "motions"), (dict(scales=[[1.0, 2.0]] * 3), "scales must have shape"),
    (dict(scales=[1.0, np.nan]), "scales must be finite"), (dict(scales=[]), "scales must have shape"),
])
def test_batch_validation(args, match):
    arguments = dict(motions=motions(), scales=[1.0]) | args
    with concurrent.futures.ThreadPoolExecutor(1) as pool, pytest.raises(ValueError, match=match):
        run_batch(building(), arguments["motions"], arguments["scales"], executor=pool)


def test_fragility_when_every_record_collapsed_and_the_mask_is_nomask():
    """An IDAResult whose collapse intensities carry no mask (``np.ma.nomask``: every record collapsed,
    built without an explicit mask) still fits its fragility; reading ``.mask[m]`` indexed a scalar."""
    from vdw_frames.frame.ida import IDAResult

    intensities = (np.array([1.0, 2.0]), np.array([1.0, 2.0, 3.0]), np.array([1.0]))
    collapse = np.ma.masked_array([2.0, 3.0, 1.0])
    assert collapse.mask is np.ma.nomask
    result = IDAResult(("a", "b", "c"), 1.0, np.array([1.0, 2.0, 3.0]), intensities,
                       tuple(np.zeros(x.size) for x in intensities),
                       tuple(np.arange(x.size) == x.size - 1 for x in intensities), collapse, ())
    fit = result.fragility()
    masked = dataclasses.replace(result, collapse_intensity=np.ma.masked_array([2.0, 3.0, 1.0], mask=[False] * 3))
    assert (fit.median, fit.dispersion) == (masked.fragility().median, masked.fragility().dispersion)
