"""The design figures (vdw_frames.plotting.design): what they draw is the design's and the verification's own
numbers (kN, mm, %), read back from the figure's lines."""

from __future__ import annotations

import numpy as np
import pytest

from vdw_frames.design import design_frame
from vdw_frames.motion import G
from vdw_frames.plotting import design as figures
from vdw_frames.plotting import plot_design_profiles, plot_drift_spread
from vdw_frames.verification import Site
from vdw_frames.verification.verify import VerificationResult

SITE = Site.from_mapped(0.75, 0.3, "C", 8.0, "II")
PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture
def captured(monkeypatch):
    """The figures the module saves (their PNGs are still written)."""
    saved = []
    real = figures.save
    monkeypatch.setattr(figures, "save", lambda figure, path: (saved.append(figure), real(figure, path))[1])
    return saved


def test_the_profiles_draw_the_design_s_shears_strengths_drifts_and_limits(tmp_path, captured):
    design = design_frame(SITE, "steel-smf", np.array([600.0, 600.0, 450.0]) * G, [4000.0, 3500.0, 3500.0],
                          overstrength=2.0, strength_scale=0.8)
    path = plot_design_profiles(design, tmp_path / "profiles")
    assert path == tmp_path / "profiles.png" and path.read_bytes()[:8] == PNG
    shear, drift = captured[0].axes
    stories = [1, 2, 3]
    lines = {line.get_label(): line for line in shear.get_lines()}
    chapter12 = next(line for label, line in lines.items() if label.startswith("V_x, Chapter 12"))
    np.testing.assert_array_equal(chapter12.get_xdata(), design.story_shears / 1e3)
    reduced = next(line for label, line in lines.items() if label.startswith("V_x x 0.8"))
    np.testing.assert_allclose(reduced.get_xdata(), 0.8 * design.story_shears / 1e3, rtol=1e-15)
    strengths = next(line for label, line in lines.items() if label.startswith("yield strength"))
    np.testing.assert_array_equal(strengths.get_xdata(), design.strengths / 1e3)
    # overstrength 2 x scale 0.8 x V_x (x the P-Delta factor, 1 here where theta <= 0.10)
    np.testing.assert_allclose(strengths.get_xdata(), 1.6 * design.story_shears / 1e3, rtol=1e-12)
    for line in shear.get_lines() + drift.get_lines():
        assert list(line.get_ydata()) == stories
    delta, limit = drift.get_lines()
    np.testing.assert_array_equal(delta.get_xdata(), design.design_drifts)
    np.testing.assert_array_equal(limit.get_xdata(), design.allowable_drifts)


def test_the_drift_spread_draws_each_record_s_largest_story_per_bound(tmp_path, captured):
    rng = np.random.default_rng(3)
    peaks = rng.uniform(0.005, 0.03, size=(3, 11, 4))
    peaks[2, 4, 1] = 0.12  # a collapse: drawn as a cross
    unacceptable = tuple(tuple("collapse" if (c, r) == (2, 4) else "" for r in range(11)) for c in range(3))
    result = VerificationResult(
        site=SITE, suite=None, bounds=None, cases=(("nominal", 1.0), ("upper", 1.2), ("lower", 0.8)),
        peak_drift_ratio=peaks, collapsed=np.zeros((3, 11), bool), converged=np.ones((3, 11), bool),
        unacceptable=unacceptable, drift_statistic=peaks.mean(axis=1), drift_limit=0.04, allowed_unacceptable=1,
        criteria=(), walls=(), wall_peaks={}, specification="", first_period=1.0, stiffness_factors=np.zeros((3, 0, 2)))
    path = plot_drift_spread(result, tmp_path / "spread.png")
    assert path.read_bytes()[:8] == PNG
    axes = captured[0].axes[0]
    top = axes.get_ylim()[1]
    dots = [line for line in axes.get_lines() if line.get_marker() == "o"]
    crosses = [line for line in axes.get_lines() if line.get_marker() == "x"]
    largest = 100 * peaks.max(axis=2)
    for c, line in enumerate(dots):
        expected = np.delete(largest[c], 4) if c == 2 else largest[c]
        np.testing.assert_allclose(line.get_ydata(), expected, rtol=1e-15)
    assert len(crosses) == 1 and list(crosses[0].get_ydata()) == [12.0] and top >= 12.0
    bars = [line for line in axes.get_lines() if line.get_marker() in ("None", "") and len(line.get_xdata()) == 2
            and line.get_linestyle() == "-"]
    np.testing.assert_allclose([bar.get_ydata()[0] for bar in bars], 100 * peaks.mean(axis=1).max(axis=1), rtol=1e-15)
    assert any(line.get_linestyle() == "--" and line.get_ydata()[0] == 4.0 for line in axes.get_lines())


def test_the_drift_limit_label_says_rho_only_where_it_divides(tmp_path, captured):
    # ASCE 7-16 Sec. 12.12.1.1 divides Delta_a by rho for moment frames in SDC D-F only: in SDC C (S_DS = 0.4 g,
    # S_D1 = 0.15 g) a stated rho = 1.3 leaves the limit 0.020 h_sx, and the legend must not call it Delta_a / rho.
    site = Site(0.6, 0.225, 8.0, "II")
    design = design_frame(site, "steel-smf", [600.0 * G] * 2, [3500.0, 3500.0], rho=1.3)
    assert design.sdc == "C"
    np.testing.assert_allclose(design.allowable_drifts, 0.020 * 3500.0, rtol=1e-15)
    plot_design_profiles(design, tmp_path / "profiles")
    label = captured[0].axes[1].get_lines()[1].get_label()
    assert "/ rho" not in label and "Delta_a" in label
