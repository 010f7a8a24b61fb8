"""ASCE 7-16 Sec. 11.4 MCE_R spectrum and site coefficients against the closed-form branches and table cells
written here (Tables 11.4-1/11.4-2 as transcribed by the USGS design-maps code; secondary sources)."""

import numpy as np
import pytest

from vdw_frames import G
from vdw_frames.verification import Site, mce_spectrum, site_coefficients, site_from_values


def closed_form(t, sms, sm1, tl):
    """The branches of ASCE 7-16 Sec. 11.4.6/11.4.7 written out one period at a time."""
    ts = sm1 / sms
    t0 = 0.2 * ts
    if t < t0:
        return sms * (0.4 + 0.6 * t / t0)
    if t <= ts:
        return sms
    if t <= tl:
        return sm1 / t
    return sm1 * tl / t**2


@pytest.mark.parametrize("sms, sm1, tl", [(1.5, 0.9, 8.0), (0.75, 0.3, 4.0), (1.0, 1.2, 6.0)])
def test_spectrum_matches_closed_form_branches(sms, sm1, tl):
    ts, t0 = sm1 / sms, 0.2 * sm1 / sms
    periods = np.concatenate([[0.0, t0, ts, tl], np.linspace(0.0, 2.0 * tl, 401),
                              [t0 * (1 - 1e-9), ts * (1 + 1e-9), tl * (1 + 1e-9)]])
    computed = mce_spectrum(periods, sms, sm1, tl)
    expected = np.array([closed_form(t, sms, sm1, tl) for t in periods])
    np.testing.assert_allclose(computed, expected, rtol=1e-12)
    # the corners: 0.4 S_MS at T = 0, S_MS at T_0 and T_S, S_M1 / T_L at T_L, continuous there
    assert computed[0] == pytest.approx(0.4 * sms)
    assert computed[1] == pytest.approx(sms) and computed[2] == pytest.approx(sms)
    assert computed[3] == pytest.approx(sm1 / tl)
    np.testing.assert_allclose(computed[-3:], [sms, sms, sm1 / tl], rtol=1e-8)
    site = Site(sms, sm1, tl)
    assert (site.t0, site.ts) == (pytest.approx(t0), pytest.approx(ts))
    assert site.sds == pytest.approx(2 / 3 * sms) and site.sd1 == pytest.approx(2 / 3 * sm1)
    np.testing.assert_allclose(site.spectral_acceleration(periods), expected * 9806.65, rtol=1e-12)
    assert G == 9806.65


@pytest.mark.parametrize("ss, s1, cls, fa, fv", [
    (0.25, 0.1, "D", 1.6, 2.4),      # first columns
    (1.5, 0.5, "C", 1.2, 1.5),       # tabulated cells
    (2.0, 0.9, "B", 0.9, 0.8),       # beyond the last column: constant
    (0.1, 0.05, "A", 0.8, 0.8),      # below the first column: constant
    (0.6, 0.15, "D", 1.4 + (1.2 - 1.4) * 0.4, 2.4 + (2.2 - 2.4) * 0.5),   # straight-line interpolation
    (1.1, 0.55, "C", 1.2, 1.5 + (1.4 - 1.5) * 0.5),
    (0.6, 0.1, "E", 1.7 + (1.3 - 1.7) * 0.4, 4.2),
])
def test_site_coefficients_table_cells(ss, s1, cls, fa, fv):
    assert site_coefficients(ss, s1, cls) == (pytest.approx(fa), pytest.approx(fv))


def test_from_mapped_applies_eqs_11_4_1_and_2():
    site = Site.from_mapped(1.0, 0.15, "d", 8.0)
    fv = 2.4 + (2.2 - 2.4) * 0.5
    assert site.sms == pytest.approx(1.1 * 1.0) and site.sm1 == pytest.approx(fv * 0.15)
    assert site.site_class == "D" and site.fa == pytest.approx(1.1)
    assert site_from_values({"ss": 1.0, "s1": 0.15, "site_class": "D", "tl": 8}) == site
    assert site_from_values({"sms": 1.5, "sm1": 0.9, "tl": 8, "risk_category": 3}) == Site(1.5, 0.9, 8, "III")


@pytest.mark.parametrize("args, words", [
    ((0.0, 0.9, 8.0), "S_MS"), ((1.5, -0.1, 8.0), "S_M1"), ((1.5, 0.9, 0.0), "T_L"),
    ((1.5, float("nan"), 8.0), "S_M1"), ((0.1, 0.9, 8.0), "larger than S_MS x T_L"),
])
def test_bad_spectral_parameters_are_refused(args, words):
    with pytest.raises(ValueError, match=words):
        Site(*args)
    with pytest.raises(ValueError, match=words):
        mce_spectrum(1.0, *args)


@pytest.mark.parametrize("ss, s1, cls, words", [
    (1.0, 0.1, "F", "Site Class F"), (1.2, 0.1, "E", "11.4.8"), (1.0, 0.3, "D", "S_1 = 0.3"),
    (1.0, 0.7, "C", "damping system"), (1.0, 0.1, "G", "site_class"), (0.0, 0.1, "C", "S_S"),
])
def test_sites_needing_a_hazard_analysis_are_refused(ss, s1, cls, words):
    with pytest.raises(ValueError, match=words):
        Site.from_mapped(ss, s1, cls, 8.0)


def test_site_table_errors_name_the_key():
    with pytest.raises(ValueError, match="tl"):
        site_from_values({"sms": 1.5, "sm1": 0.9})
    with pytest.raises(ValueError, match="unknown site keys"):
        site_from_values({"sms": 1.5, "sm1": 0.9, "tl": 8, "sds": 1.0})
    with pytest.raises(ValueError, match="not both"):
        site_from_values({"sms": 1.5, "sm1": 0.9, "tl": 8, "ss": 1.0})


@pytest.mark.parametrize("changes, message", [
    ({"ss": -5}, r"ss \(S_S, g\) must be > 0, got -5"),
    ({"s1": 0.0}, r"s1 \(S_1, g\) must be > 0, got 0"),
    ({"fa": -1}, r"fa \(F_a, -\) must be > 0, got -1"),
    ({"fv": float("inf")}, r"fv \(F_v, -\) must be finite, got inf"),
    # 1.5 g x 1.0 is S_MS; 1.2 x 1.5 g = 1.8 g is not (1.8 is 20 % above 1.5)
    ({"ss": 1.5, "fa": 1.2}, r"sms = 1.5 g disagrees with fa x ss = 1.2 x 1.5 = 1.8 g \(ASCE 7-16 Eq. 11.4-1; "
                             r"tolerance 0.5% of sms\)"),
    ({"s1": 0.6, "fv": 1.4}, r"sm1 = 0.9 g disagrees with fv x s1 = 1.4 x 0.6 = 0.84 g \(ASCE 7-16 Eq. 11.4-2"),
])
def test_site_refuses_impossible_or_inconsistent_mapped_values(changes, message):
    with pytest.raises(ValueError, match=message):
        Site(1.5, 0.9, 8.0, **changes)


def test_site_accepts_mapped_values_within_the_rounding_tolerance():
    # S_MS printed to three figures: 1.0 x 1.504 = 1.504 against 1.50 (0.27 %) is accepted, 1.51 (0.67 %) is not
    assert Site(1.50, 0.9, 8.0, ss=1.504, fa=1.0, s1=0.6, fv=1.5).fa == 1.0
    with pytest.raises(ValueError, match=r"sms = 1\.5 g disagrees with fa x ss = 1\.0 x 1\.51 = 1\.51 g"):
        Site(1.50, 0.9, 8.0, ss=1.51, fa=1.0)
    mapped = Site.from_mapped(1.0, 0.15, "D", 8.0)  # F_a S_S = S_MS exactly: still accepted
    assert mapped.sms == pytest.approx(1.1)
