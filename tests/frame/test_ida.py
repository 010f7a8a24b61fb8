"""Incremental dynamic analysis (vdw_frames.frame.ida): what it needs of the building, and the fragility of its
collapse intensities."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from builders import TEN_STORY_MASSES, TEN_STORY_STIFFNESSES, tapered_pulse, three_story
from scipy import stats
from shared_data import shared_record

from vdw_frames import Bilinear, G, ShearBuilding, incremental_dynamic_analysis, read_at2
from vdw_frames.frame.batch import scale_factors_to_spectral_acceleration
from vdw_frames.frame.ida import Fragility, IDAResult


@pytest.mark.records
def test_ida_refuses_a_building_without_story_heights():
    building = ShearBuilding(TEN_STORY_MASSES, TEN_STORY_STIFFNESSES, hysteresis=[Bilinear(1e6)] * 10)
    with pytest.raises(ValueError, match="needs story_heights"):
        incremental_dynamic_analysis(building, [read_at2(shared_record("RIO270.AT2"))], 0.1 * G, 1.0 * G)


@pytest.mark.parametrize("step, cap, count", [
    (1e-12, 2.0, "2,000,000,000,000"),  # numpy's MemoryError building the levels
    (1.0, 1e300, "1e+300"),  # numpy's "Maximum allowed size exceeded"
    (1e-300, 1e300, "more than any float"),  # cap / step overflows
    (1.0, 1001.0, "1,001"),  # one past the bound
])
def test_ida_refuses_more_intensity_levels_than_the_bound_before_building_them(step, cap, count):
    with pytest.raises(ValueError) as error:
        incremental_dynamic_analysis(three_story(), [tapered_pulse()], step, cap)
    assert str(error.value).startswith(f"step = {step!r} mm/s^2 up to cap = {cap!r} mm/s^2 is {count} intensity "
                                       "levels, more than 1000")


def test_fragility_when_every_record_collapsed_and_the_mask_is_nomask():
    """An IDAResult whose collapse intensities carry no mask (``np.ma.nomask``: every record collapsed,
    built without an explicit mask) still fits its fragility; reading ``.mask[m]`` indexed a scalar."""
    intensities = (np.array([1.0, 2.0]), np.array([1.0, 2.0, 3.0]), np.array([1.0]))
    collapse = np.ma.masked_array([2.0, 3.0, 1.0])
    assert collapse.mask is np.ma.nomask
    result = IDAResult(("a", "b", "c"), 1.0, np.array([1.0, 2.0, 3.0]), intensities,
                       tuple(np.zeros(x.size) for x in intensities),
                       tuple(np.arange(x.size) == x.size - 1 for x in intensities), collapse, ())
    fit = result.fragility()
    masked = dataclasses.replace(result, collapse_intensity=np.ma.masked_array([2.0, 3.0, 1.0], mask=[False] * 3))
    assert (fit.median, fit.dispersion) == (masked.fragility().median, masked.fragility().dispersion)


def _ida_result(levels_per_record: list[int], collapsed_at: list[float | None]) -> IDAResult:
    """An IDAResult of records stepped 1, 2, ... g; a record collapses at ``collapsed_at`` or stands (None)."""
    intensities = tuple(G * np.arange(1.0, n + 1.0) for n in levels_per_record)
    collapse = np.ma.masked_invalid([np.nan if c is None else c * G for c in collapsed_at])
    names = tuple(f"record {m}" for m in range(len(levels_per_record)))
    return IDAResult(names, 1.0, G * np.arange(1.0, max(levels_per_record) + 1.0), intensities,
                     tuple(np.zeros(x.size) for x in intensities),
                     tuple(np.isclose(x, c * G) if c is not None else np.zeros(x.size, bool)
                           for x, c in zip(intensities, collapsed_at, strict=True)), collapse, ())


def test_a_fragility_of_one_record_asks_for_records_not_a_higher_cap():
    """One record gives one intensity at most: raising the cap cannot make two collapses."""
    with pytest.raises(ValueError, match=r"got 1 \(run at least two records, got 1\)$"):
        _ida_result([3], [3.0]).fragility()


def test_a_fragility_with_records_standing_at_the_cap_names_them_and_the_cap_in_g():
    with pytest.raises(ValueError, match=r"got 1 \(2 of 3 records still stand at the cap, Sa\(T1\) = 4 g: raise "
                                         r"the cap\)$"):
        _ida_result([2, 4, 4], [2.0, None, None]).fragility()


def test_fragility_refuses_parameters_and_intensities_that_would_give_nan():
    for median, dispersion, match in ((0.0, 0.4, "median must be > 0"), (-1.0, 0.4, "median must be > 0"),
                                      (1.0, 0.0, "dispersion must be > 0"), (np.nan, 0.4, "median must be finite")):
        with pytest.raises(ValueError, match=match):
            Fragility(median, dispersion)
    fragility = Fragility(4000.0, 0.4)
    with pytest.raises(ValueError, match=r"intensity must be >= 0 mm/s\^2, got -1.0"):
        fragility.probability([1000.0, -1.0])
    with pytest.raises(ValueError, match="intensity must be finite, got nan"):
        fragility.probability(np.nan)
    # Zero intensity: no collapse; elsewhere the lognormal CDF written out here.
    probability = fragility.probability([0.0, 2000.0, 4000.0])
    np.testing.assert_allclose(probability, [0.0, stats.norm.cdf(np.log(0.5) / 0.4), 0.5], rtol=1e-14)


@pytest.mark.records
def test_ida_keeps_the_warnings_besides_strain_that_its_runs_gave():
    # A wall whose shift law holds over 20-21.5 degC only, starting at 21.2 degC: the stronger run heats it past
    # the range, which simulate of that run says.  IDA collected its runs' warnings and kept only the strain ones.
    from vdw_frames import simulate
    from vdw_frames.element import catalogue
    from vdw_frames.element.thermal import LogLinear, ThermalProperties

    narrow = LogLinear(degrees_per_decade=19.45, reference=21.2, valid=(20.0, 21.5))
    wall = dataclasses.replace(catalogue.fitted(300, area=2e4, thickness=10.0),
                               thermal=ThermalProperties(narrow, 1.8, 21.2))
    building = ShearBuilding([200.0, 150.0], [2e5, 1.5e5], story_heights=[3500.0, 3500.0],
                             devices={1: [wall], 2: [wall]})
    record = read_at2(shared_record("elCentro.AT2"))
    with pytest.warns(UserWarning, match=r"2 warning\(s\) of 2 analyses besides wall strain .*shift law's range"):
        result = incremental_dynamic_analysis(building, [record], 0.5 * G, 1.0 * G)
    assert len(result.other_warnings) == 2
    factors = scale_factors_to_spectral_acceleration([record], result.levels, result.period)[0]
    for factor, message, peak in zip(factors, result.other_warnings, result.peak_drift_ratio[0], strict=True):
        with pytest.warns(UserWarning, match="shift law's range") as caught:
            alone = simulate(building, record.scaled(float(factor)))
        said = [str(w.message) for w in caught if "shift law's range" in str(w.message)]
        assert message.endswith(said[0])
        assert peak == np.abs(alone.drift).max() / 3500.0  # the run is simulate's, to the bit
