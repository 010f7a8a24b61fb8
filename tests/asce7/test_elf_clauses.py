"""vdw_frames.asce7: the tables and equations of ASCE 7-16 Chapters 1, 11 and 12 against hand values written out
here, and the ELF of a published calculation.

Published example: an ASCE 7-16 "Seismic Base Shear" calculation printed by ENERCALC (Structural Engineering
Library, build 20.24.09.03) for a two-story building, filed with the City of Santa Ana building records:
https://publicdocs.santa-ana.org/BuildingWeblink/0/doc/548648/Page109.aspx (read through the project's search
tool).  Its printed numbers: R = 6.5, I_e = 1, C_s from Eq. 12.8-2 = 0.154 (0.1538; the calculation takes S_S <= 1.5
under ASCE 7-16 Sec. 12.8.1.3, i.e. S_DS = 1.0 for C_s although the site's S_DS is 1.064), Eq. 12.8-3 bound 0.401,
Eq. 12.8-5 minimum 0.044, W = 62.30 k, V = 9.58 k, k = 1.00; level 2: w = 20.90 k, h = 17.00 ft, w h^k = 355.30,
C_vx = 0.517, F_x = 4.96 k, story shear 4.96 k; level 1: w = 41.40 k, h = 8.00 ft, w h^k = 331.20, C_vx = 0.482,
F_x = 4.62 k, story shear 9.58 k; sum w h^k = 686.50.  Differences, explained: C_vx of level 2 is 355.30 / 686.50
= 0.51755, printed 0.517 (the print truncates to three decimals: 0.482 is 0.48245 truncated too), so C_vx is
compared with the printed value truncated; the package does not apply Sec. 12.8.1.3 by itself, so the test passes
S_DS = 1.0 as the calculation did.  The calculation prints neither S_D1 nor T: the Eq. 12.8-3 bound is checked as
S_D1 / (T R / I_e) with S_D1 / T = 0.401 x 6.5 taken from the print (any T <= 0.5 s, k = 1).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from elf_by_hand import hand_cs

from vdw_frames import asce7
from vdw_frames.asce7 import (
    SYSTEMS,
    allowable_story_drift_ratio,
    approximate_period,
    check_stability,
    distribution_exponent,
    importance_factor,
    seismic_design_category,
    seismic_response_coefficient,
    seismic_system,
    stability_coefficient,
    theta_max,
    upper_limit_coefficient,
    vertical_distribution,
)
from vdw_frames.assessment import STRUCTURAL_SYSTEMS

FT = 304.8  # mm per ft


def test_published_enercalc_two_story_elf_at_its_printed_precision():
    r, ie, sds = 6.5, 1.0, 1.0
    period = 0.2  # any T <= 0.5 s gives k = 1; the print gives S_D1 / T through its Eq. 12.8-3 bound
    sd1 = 0.401 * r / ie * period
    cs, equation = seismic_response_coefficient(sds, sd1, None, 8.0, period, r, ie)
    assert equation == "12.8-2"
    assert round(cs, 4) == 0.1538 and round(cs, 3) == 0.154
    assert round(sd1 / (period * r / ie), 3) == 0.401  # the Eq. 12.8-3 bound it prints
    assert round(max(0.044 * sds * ie, 0.01), 3) == 0.044  # Eq. 12.8-5 as printed
    weights_kip = np.array([41.40, 20.90])  # level 1, level 2
    heights_ft = np.array([8.00, 17.00])
    weight = weights_kip.sum()
    assert round(weight, 2) == 62.30
    base_shear = cs * weight
    assert round(base_shear, 2) == 9.58
    k = distribution_exponent(period)
    assert k == 1.0
    cvx = vertical_distribution(weights_kip, heights_ft * FT, k)  # the same C_vx in ft or mm
    products = weights_kip * heights_ft**k
    np.testing.assert_allclose(np.round(products, 2), [331.20, 355.30], rtol=0, atol=1e-12)
    assert round(products.sum(), 2) == 686.50
    np.testing.assert_allclose(np.floor(cvx * 1000) / 1000, [0.482, 0.517], rtol=0, atol=1e-12)
    forces = cvx * base_shear
    np.testing.assert_allclose(np.round(forces, 2), [4.62, 4.96], rtol=0, atol=1e-12)
    shears = np.cumsum(forces[::-1])[::-1]
    np.testing.assert_allclose(np.round(shears, 2), [9.58, 4.96], rtol=0, atol=1e-12)


def test_stability_coefficients_of_a_published_forum_example():
    # Eng-Tips thread "P-Delta Effect ASCE 12.8.7" (http://www.eng-tips.com/viewthread.cfm?qid=396421), read through
    # the project's search tool: with Eq. 12.8-16 as theta = P_x Delta / (V_x h_sx C_d) (I_e = 1), C_d = 5.5, beta = 1:
    # level 30: P = 140 746 kN, V = 3758 kN, Delta = 6.653 mm, h = 3200 mm -> theta = 0.0142; level 20: P = 257 772
    # kN, V = 4579 kN, Delta = 6.659 mm -> theta = 0.0213; theta_max = 0.091.  (The thread's dispute is whether its
    # Delta already holds C_d; the equation is the same either way.)
    theta = stability_coefficient([140746e3, 257772e3], [6.653, 6.659], 1.0, [3758e3, 4579e3], [3200.0, 3200.0], 5.5)
    np.testing.assert_allclose(np.round(theta, 4), [0.0142, 0.0213], rtol=0, atol=1e-12)
    assert round(theta_max(1.0, 5.5), 3) == 0.091


@pytest.mark.parametrize(("spectrum", "period", "r", "ie", "expected"), [
    ((1.0, 0.6, 0.6, 8.0), 0.4, 8.0, 1.0, "12.8-2"),  # T < T_S: the plateau
    ((1.0, 0.6, 0.6, 8.0), 1.5, 8.0, 1.0, "12.8-3"),  # 0.6 / 12 = 0.05 > 0.5 x 0.6 / 8 = 0.0375
    ((1.0, 0.6, 0.9, 8.0), 1.5, 8.0, 1.0, "12.8-6"),  # 0.5 x 0.9 / 8 = 0.05625 > 0.05
    ((0.5, 0.3, None, 4.0), 6.0, 8.0, 1.0, "12.8-5"),  # 0.3 x 4 / 288 = 0.00417 < 0.044 x 0.5 = 0.022
    ((1.2, 0.9, None, 4.0), 5.0, 3.5, 1.5, "12.8-5"),  # Eq. 12.8-4: 0.0617 < 0.044 x 1.2 x 1.5 = 0.0792
    ((1.2, 0.9, None, 4.0), 5.0, 2.0, 1.5, "12.8-4"),  # Eq. 12.8-4: 0.9 x 4 x 1.5 / (25 x 2) = 0.108 > 0.0792
])
def test_seismic_response_coefficient_each_equation(spectrum, period, r, ie, expected):
    sds, sd1, s1, tl = spectrum
    cs, equation = seismic_response_coefficient(sds, sd1, s1, tl, period, r, ie)
    hand, hand_equation = hand_cs(spectrum, period, r, ie)
    assert cs == pytest.approx(hand, rel=1e-12)
    assert equation == hand_equation == expected


def test_the_governing_equations_are_the_ones_named_by_hand():
    # Eq. 12.8-2: 1.0 / 8 = 0.125
    assert seismic_response_coefficient(1.0, 0.6, 0.6, 8.0, 0.4, 8.0, 1.0) == (0.125, "12.8-2")
    # Eq. 12.8-3: 0.6 / (1.5 x 8) = 0.05
    assert seismic_response_coefficient(1.0, 0.6, 0.6, 8.0, 1.5, 8.0, 1.0) == (pytest.approx(0.05, rel=1e-12),
                                                                                 "12.8-3")
    # Eq. 12.8-6: 0.5 x 0.9 / 8 = 0.05625
    assert seismic_response_coefficient(1.0, 0.6, 0.9, 8.0, 1.5, 8.0, 1.0) == (pytest.approx(0.05625, rel=1e-12),
                                                                                 "12.8-6")
    # Eq. 12.8-5: 0.044 x 0.5 = 0.022 > 0.3 x 4 / (36 x 8) = 0.004167
    assert seismic_response_coefficient(0.5, 0.3, None, 4.0, 6.0, 8.0, 1.0) == (pytest.approx(0.022, rel=1e-12),
                                                                                 "12.8-5")
    # Eq. 12.8-5's floor 0.01: 0.044 x 0.2 = 0.0088 < 0.01
    assert seismic_response_coefficient(0.2, 0.05, None, 4.0, 6.0, 8.0, 1.0) == (0.01, "12.8-5")
    # Eq. 12.8-4: T = 5 s > T_L = 4 s: 0.9 x 4 / (25 x 2) = 0.072 (R / I_e = 2); Eq. 12.8-5 left out
    cs, equation = seismic_response_coefficient(1.2, 0.9, None, 4.0, 5.0, 3.0, 1.5, minimum=False)
    assert (cs, equation) == (pytest.approx(0.9 * 4.0 / (25.0 * 2.0), rel=1e-12), "12.8-4")
    # Eq. 12.8-5 left out for drift (Sec. 12.8.6.1), Eq. 12.8-6 kept
    assert seismic_response_coefficient(0.5, 0.3, None, 4.0, 6.0, 8.0, 1.0, minimum=False)[1] == "12.8-4"
    assert seismic_response_coefficient(1.0, 0.6, 0.9, 8.0, 3.0, 8.0, 1.0, minimum=False) == (
        pytest.approx(0.05625, rel=1e-12), "12.8-6")


def test_upper_limit_coefficient_at_the_printed_values_and_between():
    # ASCE 7-16 Table 12.8-1
    for sd1, cu in ((0.05, 1.7), (0.1, 1.7), (0.15, 1.6), (0.2, 1.5), (0.3, 1.4), (0.4, 1.4), (0.9, 1.4)):
        assert upper_limit_coefficient(sd1) == pytest.approx(cu, abs=1e-15)
    assert upper_limit_coefficient(0.25) == pytest.approx(1.45, abs=1e-12)
    assert upper_limit_coefficient(0.125) == pytest.approx(1.65, abs=1e-12)


def test_approximate_period_eq_12_8_7_in_feet():
    h_mm = 120.0 * FT
    assert approximate_period(h_mm, SYSTEMS["steel-smf"]) == pytest.approx(0.028 * 120.0**0.8, rel=1e-12)
    assert approximate_period(h_mm, SYSTEMS["rc-smf"]) == pytest.approx(0.016 * 120.0**0.9, rel=1e-12)


def test_distribution_exponent_section_12_8_3():
    assert distribution_exponent(0.3) == 1.0 and distribution_exponent(0.5) == 1.0
    assert distribution_exponent(1.5) == pytest.approx(1.5, abs=1e-15)
    assert distribution_exponent(2.5) == 2.0 and distribution_exponent(4.0) == 2.0


def test_importance_sdc_and_drift_tables():
    assert [importance_factor(c) for c in ("I", "II", "III", "IV")] == [1.0, 1.0, 1.25, 1.5]  # Table 1.5-2
    assert [allowable_story_drift_ratio(c) for c in ("I", "II", "III", "IV")] == [0.02, 0.02, 0.015, 0.01]
    # Tables 11.6-1/2: (S_DS, S_D1, S_1, risk) -> SDC
    cases = [((0.1, 0.05, 0.05, "II"), "A"), ((0.2, 0.05, 0.05, "II"), "B"), ((0.2, 0.05, 0.05, "IV"), "C"),
             ((0.4, 0.1, 0.1, "II"), "C"), ((0.4, 0.1, 0.1, "IV"), "D"), ((0.1, 0.15, 0.15, "II"), "C"),
             ((0.1, 0.25, 0.25, "I"), "D"), ((0.6, 0.1, 0.1, "III"), "D"), ((1.0, 0.6, 0.75, "II"), "E"),
             ((1.0, 0.6, 0.75, "IV"), "F"), ((1.0, 0.6, 0.74, "IV"), "D"), ((0.167, 0.067, None, "II"), "B"),
             # on a boundary after 2/3 in floating point: S_D1 = 2/3 x 0.3 = 0.19999999999999998 is the 0.20 row
             ((2.0 / 3.0 * 0.45, 2.0 / 3.0 * 0.3, 0.2, "II"), "D"), ((2.0 / 3.0 * 0.75, 0.1, 0.1, "II"), "D")]
    for (sds, sd1, s1, risk), sdc in cases:
        assert seismic_design_category(sds, sd1, s1, risk) == sdc, (sds, sd1, s1, risk)


def test_systems_table_12_2_1_and_12_8_2():
    expected = {"steel-smf": (8.0, 3.0, 5.5, 0.028, 0.8, "C.1"), "steel-imf": (4.5, 3.0, 4.0, 0.028, 0.8, "C.3"),
                "steel-omf": (3.5, 3.0, 3.0, 0.028, 0.8, "C.4"), "rc-smf": (8.0, 3.0, 5.5, 0.016, 0.9, "C.5")}
    for key, (r, omega0, cd, ct, x, row) in expected.items():
        system = seismic_system(key)
        assert (system.r, system.omega0, system.cd, system.ct, system.x) == (r, omega0, cd, ct, x)
        assert system.table_row.endswith(row) and system.moment_frame
    assert SYSTEMS["steel-imf"].height_limit_ft("D") == 35.0
    assert SYSTEMS["steel-imf"].height_limit_ft("E") == 0.0
    assert SYSTEMS["steel-omf"].height_limit_ft("D") == 0.0
    assert SYSTEMS["steel-smf"].height_limit_ft("F") is None
    assert seismic_system(SYSTEMS["rc-smf"]) is SYSTEMS["rc-smf"]


def test_collapse_structural_systems_come_from_asce7():
    assert STRUCTURAL_SYSTEMS is asce7.PERIOD_PARAMETERS
    assert STRUCTURAL_SYSTEMS["steel-moment-frame"] == (0.028, 0.8)
    assert STRUCTURAL_SYSTEMS["concrete-moment-frame"] == (0.016, 0.9)
    assert STRUCTURAL_SYSTEMS["other"] == (0.02, 0.75)


def test_stability_coefficient_and_theta_max():
    # Eq. 12.8-16 with the numbers of a hand case: P = 1000 kN, Delta = 22 mm, I_e = 1, V = 100 kN, h = 4000, C_d = 5.5
    theta = stability_coefficient([1.0e6], [22.0], 1.0, [1.0e5], [4000.0], 5.5)
    assert theta[0] == pytest.approx(1.0e6 * 22.0 / (1.0e5 * 4000.0 * 5.5), rel=1e-12)
    assert theta_max(1.0, 5.5) == pytest.approx(0.5 / 5.5, rel=1e-15)
    assert theta_max(1.0, 1.5) == 0.25  # the cap of Eq. 12.8-17
    assert asce7.p_delta_amplification(0.08) == 1.0
    assert asce7.p_delta_amplification(0.15) == pytest.approx(1.0 / 0.85, rel=1e-15)
    check_stability(0.09, 0.5 / 5.5, 3)
    with pytest.raises(ValueError, match=r"story 3: theta = 0\.095 exceeds theta_max = 0\.09091"):
        check_stability(0.095, 0.5 / 5.5, 3)


@pytest.mark.parametrize(("call", "message"), [
    (lambda: seismic_system("steel-xyz"), r"system must be one of steel-smf, steel-imf, steel-omf, rc-smf.*steel-xyz"),
    (lambda: importance_factor("V"), r"risk_category must be one of I, II, III, IV .*'V'"),
    (lambda: seismic_design_category(-0.1, 0.3, None, "II"), r"sds"),
    (lambda: vertical_distribution([1.0, 2.0], [1.0], 1.0), r"same, non-zero length"),
    (lambda: vertical_distribution([1.0], [1.0], 2.5), r"k must lie in \[1, 2\]"),
    (lambda: upper_limit_coefficient(math.nan), r"sd1"),
])
def test_bad_input_is_refused_with_the_value_named(call, message):
    with pytest.raises(ValueError, match=message):
        call()


HOSTILE = [math.nan, math.inf, -1.0, 0.0, 1e308, 5e-324, 10**400, "", "II", None, [1.0, "x"], np.array([[1.0]]),
           True, 1j, object()]
CALLS = {
    "seismic_response_coefficient": (seismic_response_coefficient, (1.0, 0.6, 0.6, 8.0, 1.0, 8.0, 1.0)),
    "seismic_design_category": (seismic_design_category, (1.0, 0.6, 0.6, "II")),
    "vertical_distribution": (vertical_distribution, ([1.0e6, 2.0e6], [3000.0, 6000.0], 1.5)),
    "stability_coefficient": (stability_coefficient, ([1e6], [20.0], 1.0, [1e5], [3000.0], 5.5)),
    "theta_max": (theta_max, (1.0, 5.5)),
    "upper_limit_coefficient": (upper_limit_coefficient, (0.3,)),
    "approximate_period": (approximate_period, (30000.0, SYSTEMS["steel-smf"])),
    "distribution_exponent": (distribution_exponent, (1.0,)),
}


@pytest.mark.parametrize("name", sorted(CALLS))
@pytest.mark.parametrize("value", HOSTILE, ids=lambda value: "object" if type(value) is object else repr(value))
def test_hostile_arguments_give_finite_values_or_a_value_error(name, value):
    function, arguments = CALLS[name]
    for position in range(len(arguments)):
        hostile = list(arguments)
        hostile[position] = value
        try:
            result = function(*hostile)
        except ValueError:
            continue
        numbers = [part for part in (result if isinstance(result, tuple) else (result,)) if not isinstance(part, str)]
        assert all(np.isfinite(np.asarray(part, dtype=float)).all() for part in numbers), (name, position, result)
