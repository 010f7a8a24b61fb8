"""design_frame (issue 31, ASCE 7-16 Chapter 12 ELF): three buildings and sites designed, then every quantity
recomputed here by hand from the clauses written out again (C_s and its equation, T_a, C_u, T, k, C_vx, story
shears, delta_x, theta), at 1e-9.  The independent references: the clauses as written below (ASCE 7-16 Eqs.
12.8-1 ... 12.8-17, Tables 1.5-2, 11.6-1/2, 12.2-1, 12.8-1, 12.8-2, 12.12-1), T_1 from numpy's general
eigenvalue solver on the full M^-1 K (the package uses a tridiagonal solver), and for one story T_1 = 2 pi
sqrt(m / k).  Every designed building is checked again: drift <= limit, theta <= theta_max, strength = story shear
x P-Delta factor x overstrength x scale, and each story's stiffness the least that meets what governs it.
Units N-mm-s-tonne; g = 9806.65 mm/s^2."""

from __future__ import annotations

import math

import numpy as np
import pytest
from elf_by_hand import hand_cs

from vdw_frames import Bilinear, BoucWen
from vdw_frames.design import FrameDesign, design_frame, elf
from vdw_frames.verification import Site

G = 9806.65
FT = 304.8
# ASCE 7-16 Table 12.2-1 (R, Omega_0, C_d) and Table 12.8-2 (C_t, x), written out again
SYSTEM_VALUES = {"steel-smf": (8.0, 3.0, 5.5, 0.028, 0.8), "steel-imf": (4.5, 3.0, 4.0, 0.028, 0.8),
                 "steel-omf": (3.5, 3.0, 3.0, 0.028, 0.8), "rc-smf": (8.0, 3.0, 5.5, 0.016, 0.9)}
TOL = 1e-9


def hand_k(period):
    return 1.0 if period <= 0.5 else 2.0 if period >= 2.5 else 1.0 + (period - 0.5) / 2.0


def hand_shears(weights, heights, k, base_shear):
    levels = np.cumsum(heights)
    cvx = weights * levels**k / np.sum(weights * levels**k)
    forces = cvx * base_shear
    return cvx, forces, np.array([forces[i:].sum() for i in range(forces.size)])


def first_period_full(masses, stiffnesses):
    n = len(masses)
    stiffness = np.zeros((n, n))
    for i, k in enumerate(stiffnesses):
        stiffness[i, i] += k
        if i > 0:
            stiffness[i - 1, i - 1] += k
            stiffness[i - 1, i] -= k
            stiffness[i, i - 1] -= k
    omega2 = np.linalg.eigvals(np.linalg.solve(np.diag(masses), stiffness)).real
    return 2.0 * math.pi / math.sqrt(omega2.min())


def check_by_hand(design: FrameDesign, site, system, weights, heights, *, risk, importance, sdc, cu, rho,
                  divisor, drift_ratio, overstrength=1.0, scale=1.0, minimum=0.0):
    """Every quantity of ``design`` again from the clauses; the hand values of the case (I_e, SDC, C_u, rho,
    the divisor of Sec. 12.12.1.1, Delta_a / h of Table 12.12-1) are given by the caller."""
    r, omega0, cd, ct, x = SYSTEM_VALUES[system]
    w, h = np.asarray(weights, float), np.asarray(heights, float)
    loads = np.array([w[i:].sum() for i in range(w.size)])
    assert (design.risk_category, design.importance, design.sdc, design.rho) == (risk, importance, sdc, rho)
    assert design.system.omega0 == omega0
    # the building
    np.testing.assert_allclose(design.building.masses, w / G, rtol=1e-15)
    np.testing.assert_allclose(design.building.gravity_loads, loads, rtol=1e-12)
    np.testing.assert_array_equal(design.building.story_heights, h)
    np.testing.assert_array_equal(design.building.stiffnesses, design.stiffnesses)
    # periods (Eq. 12.8-7, Table 12.8-1, Sec. 12.8.2)
    height_ft = h.sum() / FT
    ta = ct * height_ft**x
    assert design.ta == pytest.approx(ta, rel=TOL) and design.cu == pytest.approx(cu, rel=TOL)
    t1 = first_period_full(w / G, design.stiffnesses)
    assert design.analytical_period == pytest.approx(t1, rel=TOL)
    assert design.drift_period == pytest.approx(t1, rel=TOL)  # the fixed point, to 1e-10
    period = min(t1, cu * ta)
    assert design.period == pytest.approx(period, rel=TOL)
    # strength: C_s, V, k, C_vx, F_x, V_x (Eqs. 12.8-1 ... 12.8-13)
    cs, equation = hand_cs((site.sds, site.sd1, site.s1, site.tl), period, r, importance)
    assert design.cs == pytest.approx(cs, rel=TOL) and design.cs_equation == equation
    assert design.weight == pytest.approx(w.sum(), rel=1e-15)
    assert design.base_shear == pytest.approx(cs * w.sum(), rel=TOL)
    k = hand_k(period)
    assert design.k == pytest.approx(k, rel=TOL)
    cvx, forces, shears = hand_shears(w, h, k, cs * w.sum())
    np.testing.assert_allclose(design.cvx, cvx, rtol=TOL)
    np.testing.assert_allclose(design.forces, forces, rtol=TOL)
    np.testing.assert_allclose(design.story_shears, shears, rtol=TOL)
    # drift forces (Sec. 12.8.6.1, 12.8.6.2): C_s at T_1, no Eq. 12.8-5
    cs_drift, drift_equation = hand_cs((site.sds, site.sd1, site.s1, site.tl), design.drift_period, r,
                                       importance, minimum=False)
    assert design.cs_drift == pytest.approx(cs_drift, rel=TOL) and design.drift_equation == drift_equation
    _, _, drift_shears = hand_shears(w, h, hand_k(design.drift_period), cs_drift * w.sum())
    np.testing.assert_allclose(design.drift_story_shears, drift_shears, rtol=TOL)
    # drifts (Eq. 12.8-15), theta (Eq. 12.8-16), theta_max (Eq. 12.8-17), Delta_a / rho (Table 12.12-1)
    stiffness = design.stiffnesses
    elastic = drift_shears / stiffness
    np.testing.assert_allclose(design.elastic_drifts, elastic, rtol=TOL)
    delta = cd * elastic / importance
    theta = loads * delta * importance / (drift_shears * h * cd)
    np.testing.assert_allclose(design.theta, theta, rtol=TOL)
    np.testing.assert_allclose(theta, loads / (stiffness * h), rtol=1e-12)  # a shear story: P / (k h)
    limit_theta = min(0.5 / cd, 0.25)
    assert design.theta_max == pytest.approx(limit_theta, rel=1e-15)
    factor = np.where(theta > 0.10, 1.0 / (1.0 - theta), 1.0)
    np.testing.assert_allclose(design.design_drifts, delta * factor, rtol=TOL)
    allowable = drift_ratio * h / divisor
    np.testing.assert_allclose(design.allowable_drifts, allowable, rtol=1e-15)
    # the design meets its limits ...
    assert (delta * factor <= allowable * (1 + 1e-9)).all()
    assert (theta <= limit_theta * (1 + 1e-9)).all()
    assert (stiffness >= np.broadcast_to(minimum, stiffness.shape) * (1 - 1e-12)).all()
    # ... and each story is the least that does: what governs it is met with equality
    for i, governing in enumerate(design.governing):
        if governing == "drift":
            at_limit = math.isclose(delta[i] * factor[i], allowable[i], rel_tol=1e-9)
            at_threshold = math.isclose(theta[i], 0.10, rel_tol=1e-9)  # theta = 0.10: not amplified, just stiff enough
            assert at_limit or at_threshold, (i, delta[i] * factor[i], allowable[i], theta[i])
        elif governing == "stability":
            assert theta[i] == pytest.approx(limit_theta, rel=1e-9)
        else:
            assert stiffness[i] == pytest.approx(np.broadcast_to(minimum, stiffness.shape)[i], rel=1e-12)
    # strengths: V_x x P-Delta factor x overstrength x scale, in the story models
    strengths = shears * factor * overstrength * scale
    np.testing.assert_allclose(design.strengths, strengths, rtol=TOL)
    np.testing.assert_allclose([model.yield_force for model in design.building.hysteresis], strengths, rtol=1e-15)


def test_one_story_steel_omf_risk_category_iii_in_sdc_b():
    # S_DS = 0.2 g, S_D1 = 0.1 g: SDC B (Tables 11.6-1/2, Risk Category III); C_u = 1.7 (Table 12.8-1)
    site = Site(0.3, 0.15, 6.0, "III")
    weights, heights = [2.0e6], [4000.0]
    design = design_frame(site, "steel-omf", weights, heights, hardening=0.02)
    check_by_hand(design, site, "steel-omf", weights, heights, risk="III", importance=1.25, sdc="B", cu=1.7,
                  rho=1.0, divisor=1.0, drift_ratio=0.015)
    # one story: T_1 = 2 pi sqrt(m / k) in closed form
    mass = 2.0e6 / G
    assert design.analytical_period == pytest.approx(2 * math.pi * math.sqrt(mass / design.stiffnesses[0]),
                                                     rel=1e-12)
    # theta_max = 0.5 / 3 governs here: theta > 0.10, so the drift and the strength carry 1 / (1 - theta) = 1.2
    assert design.governing == ("stability",)
    assert design.p_delta_factors[0] == pytest.approx(1.2, rel=1e-12)
    assert design.building.hysteresis[0] == Bilinear(design.strengths[0], 0.02)


def test_eight_story_rc_smf_in_sdc_e_with_s1_above_0_75g():
    # S_S = 1.5, S_1 = 0.8, Site Class C: F_a = 1.2, F_v = 1.4 (Tables 11.4-1/2) -> S_DS = 1.2 g, S_D1 = 0.7467 g;
    # S_1 >= 0.75 g: SDC E (Sec. 11.6); rho = 1.3 by default in SDC D-F (Sec. 12.3.4.2); C_u = 1.4
    site = Site.from_mapped(1.5, 0.8, "C", 8.0, "II", damping_system=False)
    weights, heights = [3.0e6] * 7 + [2.2e6], [4500.0] + [3800.0] * 7
    design = design_frame(site, "rc-smf", weights, heights, overstrength=1.5)
    check_by_hand(design, site, "rc-smf", weights, heights, risk="II", importance=1.0, sdc="E", cu=1.4,
                  rho=1.3, divisor=1.3, drift_ratio=0.02, overstrength=1.5)
    # T_1 = 1.90 s: S_D1 / (T_1 R) = 0.049 < 0.5 S_1 / R = 0.05, so Eq. 12.8-6 sets the drift forces; strength at
    # T = C_u T_a = 1.44 s: S_D1 / (T R) = 0.065 (Eq. 12.8-3)
    assert design.drift_equation == "12.8-6" and design.cs_equation == "12.8-3"
    assert design.governing == ("drift",) * 8


def test_ten_story_steel_smf_at_the_example_site_in_sdc_d():
    # The examples' site: S_S = 0.75, S_1 = 0.3, Site Class C -> S_DS = 0.6 g, S_D1 = 0.3 g: SDC D; C_u = 1.4
    site = Site.from_mapped(0.75, 0.3, "C", 8.0, "II")
    weights = [600.0 * G] * 9 + [450.0 * G]
    heights = [4000.0] + [3500.0] * 9
    design = design_frame(site, "steel-smf", weights, heights, rho=1.0, strength_scale=0.8, overstrength=2.0)
    check_by_hand(design, site, "steel-smf", weights, heights, risk="II", importance=1.0, sdc="D", cu=1.4,
                  rho=1.0, divisor=1.0, drift_ratio=0.02, overstrength=2.0, scale=0.8)
    assert design.cs_equation == "12.8-5"  # 0.044 S_DS I_e = 0.0264 > S_D1 / (C_u T_a R)
    # T >= 3.5 T_S, but h_n = 116 ft <= 160 ft: ASCE 7-16 Table 12.6-1 permits ELF for a regular structure of this
    # height at any period, so no statement that it does not
    assert design.period >= 3.5 * site.ts and design.height / FT <= 160.0
    assert not any("Table 12.6-1" in text for text in design.assumptions)


def test_elf_beyond_its_table_12_6_1_scope_is_stated_only_above_160_ft():
    # ASCE 7-16 Table 12.6-1, SDC D-F: ELF is permitted for regular structures not exceeding 160 ft at any period,
    # and above 160 ft only with T < 3.5 T_S.  15 stories of 3.5 m: h_n = 52.5 m = 172 ft, T = C_u T_a = 2.17 s
    # >= 3.5 T_S = 1.75 s.
    site = Site.from_mapped(0.75, 0.3, "C", 8.0, "II")
    tall = design_frame(site, "steel-smf", [600.0 * G] * 15, [3500.0] * 15)
    assert tall.height / FT > 160.0 and tall.period >= 3.5 * site.ts
    assert any("Table 12.6-1" in text for text in tall.assumptions)


@pytest.mark.parametrize(("system", "stories", "governing"), [
    # theta_max = 0.5 / 3 = 0.167 at the first story; above, drift with 1 / (1 - theta) (0.10 < theta < theta_max)
    ("steel-omf", 4, ("stability", "drift", "drift", "drift")),
    # theta_max = 0.5 / 4 = 0.125 at the first story; the second is stiffened to theta = 0.10 exactly, where the
    # drift no longer needs the P-Delta factor (smaller than the amplified requirement)
    ("steel-imf", 2, ("stability", "drift")),
])
def test_p_delta_amplified_and_threshold_stories_in_sdc_c(system, stories, governing):
    # S_DS = 0.4 g, S_D1 = 0.1867 g, Risk Category III: SDC C (Tables 11.6-1/2); C_u interpolated in Table 12.8-1
    site = Site(0.6, 0.28, 8.0, "III")
    weights, heights = [3.0e6] * stories, [4000.0] * stories
    design = design_frame(site, system, weights, heights)
    cu = 1.6 + (site.sd1 - 0.15) / (0.2 - 0.15) * (1.5 - 1.6)
    check_by_hand(design, site, system, weights, heights, risk="III", importance=1.25, sdc="C", cu=cu, rho=1.0,
                  divisor=1.0, drift_ratio=0.015)
    assert design.governing == governing
    amplified = design.theta > 0.10
    assert amplified.any()
    np.testing.assert_allclose(design.p_delta_factors[amplified], 1.0 / (1.0 - design.theta[amplified]), rtol=1e-15)


def test_a_minimum_stiffness_governs_where_it_is_larger():
    site = Site(0.9, 0.45, 8.0, "II")
    weights, heights = [3.0e6] * 4, [3600.0] * 4
    minimum = [2.0e5, 1.0, 1.0, 1.0]
    design = design_frame(site, "steel-smf", weights, heights, minimum_stiffness=minimum, rho=1.0)
    check_by_hand(design, site, "steel-smf", weights, heights, risk="II", importance=1.0, sdc="D", cu=1.4,
                  rho=1.0, divisor=1.0, drift_ratio=0.02, minimum=np.array(minimum))
    assert design.governing[0] == "minimum" and "minimum" not in design.governing[1:]


def test_a_user_story_model_and_the_table_and_csv(tmp_path):
    site = Site(0.9, 0.45, 8.0, "II")
    design = design_frame(site, "steel-smf", [3.0e6] * 3, [3600.0] * 3,
                          story_model=lambda force: BoucWen(force, 0.05, exponent=2.0))
    assert all(isinstance(model, BoucWen) and model.exponent == 2.0 for model in design.building.hysteresis)
    text = design.table()
    for needle in ("T_a = C_t h_n^x", "Table 12.8-1", f"Eq. {design.cs_equation}", "Delta_a/rho", "theta",
                   "Assumptions:", "beta = 1", "footnotes of Table 12.2-1"):
        assert needle in text
    path = design.save(tmp_path / "elf.csv")
    lines = path.read_text().splitlines()
    assert len(lines) == 4 and lines[0].startswith("story,height_mm,weight_n,cvx,force_n,story_shear_n")
    first = dict(zip(lines[0].split(","), lines[1].split(","), strict=True))
    assert float(first["strength_n"]) == pytest.approx(design.strengths[0], rel=1e-15)
    assert float(first["theta"]) == pytest.approx(design.theta[0], rel=1e-15)
    summary = design.summary()
    assert summary["cs_equation"] == design.cs_equation and summary["base_shear_n"] == design.base_shear


EXAMPLE_SITE = Site.from_mapped(0.75, 0.3, "C", 8.0, "II")  # SDC D


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"system": "steel-xyz"}, r"system must be one of steel-smf, steel-imf, steel-omf, rc-smf .*'steel-xyz'"),
    ({"risk_category": "V"}, r"risk_category must be one of I, II, III, IV .*'V'"),
    ({"system": "steel-imf"}, r"h_n = 35500 mm = 116\.5 ft exceeds the 35 ft limit of Steel intermediate moment "
                              r"frames in Seismic Design Category D"),
    ({"system": "steel-omf"}, r"Steel ordinary moment frames are not permitted \(NP\) in Seismic Design Category D"),
    ({"weights": [1.0e6] * 3}, r"weights has 3 values and story_heights 10"),
    ({"weights": [1.0e6] * 9 + [-1.0]}, r"weights must be > 0 \(N\), got \[-1\.0\] at floor\(s\) \[10\]"),
    ({"strength_scale": 0.0}, r"strength_scale must lie in \(0, 1\], got 0\.0"),
    ({"strength_scale": 1.5}, r"strength_scale must lie in \(0, 1\], got 1\.5"),
    ({"overstrength": 0.9}, r"overstrength must be >= 1"),
    ({"rho": 1.1}, r"rho must be 1\.0 or 1\.3 .*1\.1"),
    ({"minimum_stiffness": -1.0}, r"minimum_stiffness must be one value >= 0"),
    ({"site": {"sms": 0.9}}, r"site must be a vdw_frames\.verification\.Site"),
    ({"site": Site(0.2, 0.08, 8.0)}, r"Seismic Design Category A .*Sec\. 11\.7"),
    ({"story_model": 3.0}, r"story_model must be a function of the yield force"),
])
def test_bad_input_gets_one_clear_error(kwargs, message):
    arguments = {"site": EXAMPLE_SITE, "system": "steel-smf", "weights": [600.0 * G] * 10,
                 "story_heights": [4000.0] + [3500.0] * 9}
    options = {key: kwargs.pop(key) for key in list(kwargs) if key not in arguments}
    arguments.update(kwargs)
    with pytest.raises(ValueError, match=message):
        design_frame(arguments["site"], arguments["system"], arguments["weights"], arguments["story_heights"],
                     **options)


def test_non_finite_weights_and_an_unsettled_period_are_refused(monkeypatch):
    site = Site(0.9, 0.45, 8.0, "II")
    with pytest.raises(ValueError, match="weights"):
        design_frame(site, "steel-smf", [3.0e6, math.nan], [3600.0] * 2)
    monkeypatch.setattr(elf, "MAX_ITERATIONS", 1)  # one iteration cannot settle T_1 from C_u T_a
    with pytest.raises(ValueError, match=r"T_1 did not settle in 1 iterations .*give a minimum_stiffness"):
        design_frame(site, "steel-smf", [3.0e6] * 4, [3600.0] * 4)


def test_a_site_outside_the_tabulated_rules_is_refused_before_design():
    # ASCE 7-16 Sec. 11.4.8: Site Class D with S_1 >= 0.2 needs a site-specific analysis; the Site refuses it, so
    # no ELF design is ever made from tabulated coefficients there
    with pytest.raises(ValueError, match=r"Sec\. 11\.4\.8 requires a ground motion hazard analysis"):
        Site.from_mapped(1.0, 0.3, "D", 8.0, "II", damping_system=False)


HOSTILE = [math.nan, math.inf, -math.inf, 1e308, -1e308, 5e-324, -0.0, 0.0, 2**63, 10**400, np.float64("nan"),
           np.array([1.0, 2.0]), np.array([[1.0]]), np.array([]), [], (), {}, [1.0, "x"], [math.nan], "", "1.0",
           b"1", 1j, True, None, object()]
VALID = {"site": Site(0.9, 0.45, 8.0, "II"), "system": "steel-smf", "weights": [3.0e6, 2.0e6],
         "story_heights": [3600.0, 3600.0], "risk_category": "II", "rho": 1.0, "overstrength": 1.2,
         "hardening": 0.03, "minimum_stiffness": 1.0e3, "story_model": None, "strength_scale": 0.9,
         "damping_ratio": 0.05, "damping_modes": (1, 2)}


@pytest.mark.parametrize("argument", sorted(VALID))
@pytest.mark.parametrize("value", HOSTILE, ids=lambda value: "object" if type(value) is object else repr(value))
def test_hostile_values_give_a_design_or_a_value_error(argument, value):
    arguments = {**VALID, argument: value}
    try:
        design = design_frame(arguments.pop("site"), arguments.pop("system"), arguments.pop("weights"),
                              arguments.pop("story_heights"), **arguments)
    except ValueError:
        return
    for name in ("stiffnesses", "strengths", "design_drifts", "theta", "cvx"):
        assert np.isfinite(getattr(design, name)).all(), name
    assert math.isfinite(design.analytical_period) and design.analytical_period > 0


def test_strengths_without_rho_say_so():
    # ASCE 7-16 Sec. 12.4.2.1: E_h = rho Q_E.  The strengths are V_x (Q_E) alone: with rho = 1.3 (SDC D) that must
    # be stated; with rho = 1.0 there is nothing to state.
    site = Site.from_mapped(0.75, 0.3, "C", 8.0, "II")
    weights, heights = [600.0 * G] * 3, [3500.0] * 3
    stated = design_frame(site, "steel-smf", weights, heights)
    assert stated.rho == 1.3
    assert np.allclose(stated.strengths, stated.story_shears * stated.p_delta_factors, rtol=1e-12)
    assert any("12.4.2.1" in text for text in stated.assumptions)
    assert not any("12.4.2.1" in text for text in design_frame(site, "steel-smf", weights, heights,
                                                               rho=1.0).assumptions)
