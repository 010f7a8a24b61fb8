"""Inelastic shear buildings: story materials, Newton-Raphson integration, P-Delta, collapse, OpenSees checks."""

from __future__ import annotations

import concurrent.futures
import warnings

import numpy as np
import opensees_frame
import pytest
from scipy.integrate import solve_ivp
from shared_data import SHARED, shared_record

from vdw_frames import (
    Bilinear,
    BoucWen,
    FDMKDamper,
    G,
    GroundMotion,
    ShearBuilding,
    incremental_dynamic_analysis,
    read_at2,
    run_batch,
    simulate,
)
from vdw_frames.frame import NewtonRaphson
from vdw_frames.frame.hysteresis import StoryState

MASSES = [600.0] * 9 + [450.0]  # tonne
STIFFNESSES = [300e3 - 15e3 * k for k in range(10)]  # N/mm
HEIGHTS = [4000.0] + [3500.0] * 9  # mm
GRAVITY = np.cumsum((9.80665e3 * np.array(MASSES))[::-1])[::-1]  # N: the weight above each story
R1_WALL = FDMKDamper(G1=0.0, G2=3.0, eta1=0.3, eta2=2.0, r=1.0, area=0.3e6, thickness=10.0)
FRACTIONAL_WALL = FDMKDamper(G1=0.0, G2=3.0, eta1=0.3, eta2=2.0, r=0.5, area=0.3e6, thickness=10.0)


def frame(model=Bilinear, strength=0.08, hardening=0.03, walls=R1_WALL, gravity=True, **options):
    """The 10-story frame, story strengths ``strength`` x the weight above story 1, tapered with height."""
    yield_forces = [strength * GRAVITY[0] * (1 - k / 12) for k in range(10)]
    return ShearBuilding(MASSES, STIFFNESSES, story_heights=HEIGHTS,
                         hysteresis=[model(f, hardening) for f in yield_forces],
                         gravity_loads=GRAVITY if gravity else None,
                         walls={story: walls for story in range(1, 7)} if walls else None, **options)


def peak_deviation(drift, reference):
    return np.abs(np.abs(drift).max(axis=0) / np.abs(reference).max(axis=0) - 1.0).max()


# --------------------------------------------------------------------------------------- story materials
def test_bilinear_follows_the_kinematic_hardening_bounds():
    # k0 = 1000 N/mm, F_y = 5000 N (yield drift 5 mm), b = 0.1: bounds 0.1 k0 d +- 4500 N.  Values by hand:
    # elastic to 2 mm; yielded at 8 mm (5000 + 100 x 3); 20 mm on the upper bound (2000 + 4500); elastic
    # unloading from (20, 6500) by k0 to 10 mm (-3500) and on to -5 mm, where it meets the lower bound
    # (-500 - 4500 = -5000 < 6500 - 25000); on the lower bound to -20 mm (-6500); elastic back to 0 (13500
    # above -6500 reaches the upper bound 4500 first: 4500).
    state = Bilinear(5000.0, 0.1).new_state(1000.0)
    path = [2.0, 8.0, 20.0, 10.0, -5.0, -20.0, 0.0]
    expected = [2000.0, 5300.0, 6500.0, -3500.0, -5000.0, -6500.0, 4500.0]
    forces = []
    for drift in path:
        force, _ = state.trial(drift)
        state.commit()
        forces.append(force)
    assert forces == pytest.approx(expected, rel=1e-15)


@pytest.mark.parametrize("exponent, beta, gamma", [(1.0, 0.5, 0.5), (2.0, 0.7, 0.3), (5.0, 0.9, 0.1), (1.0, 0.5, -0.2)])
def test_bouc_wen_integrates_its_evolution_equation(exponent, beta, gamma):
    # Reference: dz/dd = (1/d_y)(1 - |z|^n (beta sgn(dd z) + gamma)) by solve_ivp at tight tolerance, leg by leg.
    k0, yield_force, b = 2000.0, 10000.0, 0.05
    yield_drift = yield_force / k0
    legs = [(0.0, 20.0), (20.0, -15.0), (-15.0, 8.0)]
    state = BoucWen(yield_force, b, exponent, beta, gamma).new_state(k0)
    z = 0.0
    for start, end in legs:
        direction = np.sign(end - start)

        def rate(d, y):
            return [(1 - abs(y[0]) ** exponent * (beta * np.sign(direction * y[0]) + gamma)) / yield_drift]

        solution = solve_ivp(rate, (start, end), [z], rtol=1e-11, atol=1e-13, dense_output=True)
        drifts = np.linspace(start, end, 401)[1:]  # 0.05 d_y steps or less
        for drift in drifts:
            force, tangent = state.trial(drift)
            state.commit()
            z_reference = solution.sol(drift)[0]
            assert force == pytest.approx(b * k0 * drift + (1 - b) * yield_force * z_reference, rel=2e-4, abs=2e-4 * yield_force)
        z = solution.sol(end)[0]


def test_bouc_wen_update_is_bounded_and_accurate_for_any_increment():
    # Against the exact solution of dz/dx = 1 - |z|^n (beta sgn(dx z) + gamma) (solve_ivp), for sharp
    # knees (n up to 100) and increments up to 50 yield drifts in one call: never NaN, never beyond the
    # strength bound (beta + gamma)^(-1/n), within 2 % of z (measured: 0.4e-3 for n = 1, 1.9e-2 for
    # n = 100 over 50 yield drifts), and the tangent equals a finite difference of the update.
    from vdw_frames.frame.hysteresis import _bouc_wen_update

    rng = np.random.default_rng(5)
    for _ in range(300):
        n = float(rng.choice([1.0, 2.0, 10.0, 100.0]))
        beta, gamma = [(0.5, 0.5), (0.7, 0.3), (0.9, -0.1)][rng.integers(3)]
        bound = (beta + gamma) ** (-1.0 / n)
        z0 = rng.uniform(-1.0, 1.0) * bound
        x = rng.choice([-1.0, 1.0]) * 10 ** rng.uniform(-2.0, 1.7)
        z, tangent = _bouc_wen_update(z0, x, n, beta, gamma)
        assert np.isfinite(z) and np.isfinite(tangent) and abs(z) <= bound * (1 + 1e-12)

        def rate(t, y, direction=np.sign(x)):
            z = min(abs(y[0]), 2.0)  # (the solver's probes far outside would overflow |z|^100)
            return [1.0 - z**n * (beta * np.sign(direction * y[0]) + gamma)]

        exact = solve_ivp(rate, (0.0, x), [z0], rtol=1e-11, atol=1e-13, method="LSODA").y[0, -1]
        assert z == pytest.approx(exact, abs=0.02)
        step = 1e-7 * max(1.0, abs(x))
        numerical = (_bouc_wen_update(z0, x + step, n, beta, gamma)[0]
                     - _bouc_wen_update(z0, x - step, n, beta, gamma)[0]) / (2 * step)
        if abs(abs(z) - bound) > 1e-6:  # (clamped on the bound: dz/dx = 0 there, a kink)
            assert tangent == pytest.approx(numerical, rel=1e-4, abs=1e-6)


@pytest.mark.parametrize("model", [Bilinear(5000.0, 0.1), BoucWen(5000.0, 0.1, 2.0, 0.6, 0.4)])
def test_story_tangent_is_consistent(model):
    state = model.new_state(1000.0)
    for drift in (3.0, 9.0, 2.0):
        state.trial(drift)
        state.commit()
    # (-1.0 would sit exactly on the Bilinear's yield bound, and increments of whole 0.5 mm (d_y / 10) on
    # a whole number of the Bouc-Wen update's sub-increments: small kinks where no tangent is the derivative)
    for trial in (4.03, -0.53, 12.07, 2.1):
        force, tangent = state.trial(trial)
        step = 1e-6
        numerical = (state.trial(trial + step)[0] - state.trial(trial - step)[0]) / (2 * step)
        assert tangent == pytest.approx(numerical, rel=1e-5)
        state.revert_to_last_commit()
    assert state.committed_drift == 2.0  # trials never touched the committed state


def test_story_state_contract_refuses_bad_use():
    state = StoryState(None, 100.0)
    with pytest.raises(ValueError, match="commit.. needs a trial"):
        state.commit()
    with pytest.raises(ValueError, match="must be Bilinear, BoucWen or None"):
        StoryState("steel", 100.0)


@pytest.mark.parametrize("kwargs, match", [
    (dict(yield_force=0.0), "yield_force must be > 0"), (dict(yield_force=1.0, hardening=1.0), "hardening"),
    (dict(yield_force=1.0, hardening=-0.1), "hardening"), (dict(yield_force=True), "yield_force"),
])
def test_bilinear_validation(kwargs, match):
    with pytest.raises(ValueError, match=match):
        Bilinear(**kwargs)


@pytest.mark.parametrize("kwargs, match", [
    (dict(exponent=0.5), "exponent"), (dict(beta=0.2, gamma=0.5), "beta >= gamma"),
    (dict(beta=-0.5, gamma=-0.6), "beta . gamma > 0"), (dict(exponent=np.nan), "exponent"),
])
def test_bouc_wen_validation(kwargs, match):
    with pytest.raises(ValueError, match=match):
        BoucWen(1000.0, **kwargs)


# --------------------------------------------------------------------------------------- the building
@pytest.mark.parametrize("kwargs, match", [
    (dict(hysteresis=[Bilinear(1.0)] * 3), "hysteresis has 3 entries for 10 stories"),
    (dict(hysteresis={11: Bilinear(1.0)}), "hysteresis story must be a story number"),
    (dict(hysteresis=["steel"] * 10), "hysteresis of story 1 must be Bilinear, BoucWen or None"),
    (dict(hysteresis=Bilinear(1.0)), "hysteresis must be a sequence"),
    (dict(gravity_loads=[1.0] * 10, story_heights=None), "gravity_loads need story_heights"),
    (dict(gravity_loads=[-1.0] * 10), "gravity_loads must be >= 0 N"),
    (dict(gravity_loads=[1.0] * 9), "gravity_loads has 9 entries"),
    (dict(damping_model="caughey"), "damping_model must be one of"),
])
def test_building_validation(kwargs, match):
    with pytest.raises(ValueError, match=match):
        ShearBuilding(MASSES, STIFFNESSES, **(dict(story_heights=HEIGHTS) | kwargs))


def test_modal_damping_gives_the_same_ratio_in_every_mode():
    building = ShearBuilding(MASSES, STIFFNESSES, damping_ratio=0.03, damping_model="modal")
    shapes, omega = building.mode_shapes, building.circular_frequencies
    modal = shapes.T @ building.damping_matrix @ shapes
    np.testing.assert_allclose(modal, np.diag(2 * 0.03 * omega), atol=1e-12 * modal.max())
    assert building.damping_ratios == pytest.approx([0.03] * 10)
    rayleigh = ShearBuilding(MASSES, STIFFNESSES, damping_ratio=0.05)
    ratios = np.diag(shapes.T @ rayleigh.damping_matrix @ shapes) / (2 * omega)
    np.testing.assert_allclose(rayleigh.damping_ratios, ratios, rtol=1e-12)
    # 5 % in modes 1 and 2, then 6.8 % (mode 3) rising to 17.2 % (mode 10): too much for floor accelerations
    assert ratios[:2] == pytest.approx([0.05, 0.05]) and ratios[2] == pytest.approx(0.068, abs=5e-4)
    assert ratios[-1] == pytest.approx(0.172, abs=5e-4)


def test_linear_limit_equals_the_linear_path():
    motion = read_at2(shared_record("RIO270.AT2")).scaled_to_pga(0.4 * G)
    linear = ShearBuilding(MASSES, STIFFNESSES, story_heights=HEIGHTS, walls={s: FRACTIONAL_WALL for s in range(1, 7)})
    strong = frame(strength=1e3, walls=FRACTIONAL_WALL, gravity=False)  # never yields
    expected, result = simulate(linear, motion), simulate(strong, motion)
    scale = np.abs(expected.displacement).max()
    assert np.abs(result.displacement - expected.displacement).max() <= 1e-12 * scale
    assert np.abs(result.wall_force - expected.wall_force).max() <= 1e-12 * np.abs(expected.wall_force).max()
    assert result.energy.hysteretic[-1] == pytest.approx(0.0, abs=1e-9 * result.energy.input[-1])


def test_bilinear_frame_matches_opensees_steel01(ops):
    # Steel01 springs (b = hardening), P-Delta as negative-stiffness zeroLengths, rayleigh(a0, 0, a1, 0) on the
    # springs, r = 1 walls as Elastic + Maxwell; El Centro scaled so that stories reach ductility >= 4.
    motion = read_at2(shared_record("elCentro.AT2"))
    building = frame()
    result = simulate(building, motion)
    displacement, reaction, spring_force = opensees_frame.run(building, motion.acceleration, motion.dt, reactions=True,
                                                              tolerance=1e-10)
    drift = opensees_frame.drifts(displacement)
    assert result.peak_ductility.max() >= 4.0
    assert peak_deviation(result.drift, drift) < 0.01  # measured 0.13 % (the r = 1 walls' discretisations differ)
    peak = np.abs(drift).max(axis=0)
    assert (np.abs(result.residual_drift - drift[-1]) / peak).max() < 0.02  # measured 0.14 %
    story1 = spring_force[:, 0]
    assert np.abs(result.story_shear[:, 0] - story1).max() < 0.01 * np.abs(story1).max()  # measured 0.18 %
    # Base shear is the force through story 1: the ground's reaction (opposite sign), within 0.6 % of its peak.
    assert np.abs(result.base_shear + reaction).max() < 0.006 * np.abs(reaction).max()


def test_opensees_and_vdw_frames_converge_together_under_dt_refinement(ops):
    # At a quarter of the record step the two discretisations of the walls agree 15x more closely.
    motion = read_at2(shared_record("elCentro.AT2"))
    building = frame()
    dt = motion.dt / 4
    result = simulate(building, motion, dt=dt)
    displacement, reaction, spring_force = opensees_frame.run(building, motion.acceleration_at(dt), dt, reactions=True,
                                                              tolerance=1e-10)
    assert peak_deviation(result.drift, opensees_frame.drifts(displacement)) < 2e-4  # measured 0.009 %
    assert np.abs(result.base_shear + reaction).max() < 1e-3 * np.abs(reaction).max()


def test_bouc_wen_frame_matches_opensees_bouc_wen(ops):
    # OpenSees integrates z by backward Euler (first order), vdw_frames by TR-BDF2 (second order); at dt / 16
    # both have converged to 0.25 % (measured deviation 3.4 %, 0.94 %, 0.24 % at dt, dt / 4, dt / 16).
    motion = read_at2(shared_record("elCentro.AT2")).scaled(1.2)
    building = frame(model=BoucWen)
    dt = motion.dt / 16
    result = simulate(building, motion, dt=dt)
    displacement, _, spring_force = opensees_frame.run(building, motion.acceleration_at(dt), dt, reactions=True,
                                                       tolerance=1e-10)
    drift = opensees_frame.drifts(displacement)
    assert result.peak_ductility.max() >= 4.0
    assert peak_deviation(result.drift, drift) < 0.01
    assert np.abs(result.story_shear[:, 0] - spring_force[:, 0]).max() < 0.01 * np.abs(spring_force[:, 0]).max()


@pytest.mark.parametrize("model", [Bilinear, BoucWen])
def test_inelastic_frame_with_fractional_walls_converges_at_second_order(model):
    # Errors against a 16x finer solution; sub-steps of the record (linear interpolation of the ground motion).
    motion = read_at2(shared_record("elCentro.AT2")).scaled(1.2)
    motion = GroundMotion(motion.acceleration[:600], motion.dt, motion.name)  # the first 12 s: the strong part
    building = frame(model=model, walls=FRACTIONAL_WALL)
    reference = simulate(building, motion, dt=motion.dt / 32, memory="exact")
    errors = []
    for sub in (2, 4, 8):
        result = simulate(building, motion, dt=motion.dt / sub, memory="exact")
        every = 32 // sub
        errors.append(np.abs(result.drift - reference.drift[::every]).max())
    assert result.peak_ductility.max() > 3.0
    ratios = [errors[0] / errors[1], errors[1] / errors[2]]
    assert min(ratios) > 3.0, ratios  # second order: 4 per halving


@pytest.mark.parametrize("name", sorted(p.name for p in SHARED.glob("*.[aA][tT]2")) if SHARED.is_dir() else ["(none)"])
def test_energy_balance_closes_at_ductility_four_on_every_shared_record(name):
    motion = read_at2(shared_record(name))
    building = frame(walls=FRACTIONAL_WALL)
    # Scale each record to the smallest of a few intensities that takes some story to ductility 4.
    for sa in (0.2, 0.4, 0.7, 1.0, 1.5):
        result = simulate(building, motion.scaled_to_spectral_acceleration(sa * G, building.periods[0]))
        if result.peak_ductility.max() >= 4.0 or result.collapsed:
            break
    assert result.peak_ductility.max() >= 4.0 and result.converged
    energy = result.energy
    assert np.abs(energy.balance_error).max() < 0.005 * np.abs(energy.input).max()  # measured ~1e-13
    assert energy.hysteretic[-1] > 0.05 * energy.input[-1]  # the stories dissipate
    assert energy.p_delta[-1] <= 0.0


def test_weak_frame_with_p_delta_collapses_cleanly():
    motion = read_at2(shared_record("RIO270.AT2")).scaled_to_pga(1.0 * G)
    building = frame(strength=0.03, hardening=0.0, walls=None)
    result = simulate(building, motion, collapse_drift_ratio=0.10)
    assert result.collapsed and result.converged
    assert result.collapse_time == pytest.approx(result.time[-1])
    assert result.time[-1] < motion.duration
    assert np.abs(result.drift_ratio[-1]).max() > 0.10 >= np.abs(result.drift_ratio[:-1]).max()
    for history in (result.displacement, result.story_shear, result.base_shear, result.energy.input):
        assert np.isfinite(history).all() and history.shape[0] == result.time.size
    # Without the check the leaning frame runs away (the linearised P-Delta grows without bound): the analysis
    # goes on past the collapse time (or stops where Newton gives up), never raises, and stays finite.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        free = simulate(building, motion, collapse_drift_ratio=None)
    assert not free.collapsed and free.time[-1] > result.collapse_time
    assert np.abs(free.drift_ratio).max() > 1.0 and np.isfinite(free.displacement).all()


def test_sharp_bouc_wen_story_at_the_record_step_converges():
    # Increments of several yield drifts a step through a knee of exponent 50 (a near-bilinear story): the
    # update once returned a non-root there, and a NaN state passed Newton's norm.
    motion = read_at2(shared_record("elCentro.AT2"))
    weight = 100.0 * 9806.65
    building = ShearBuilding([100.0], [1e5], story_heights=[3000.0], hysteresis=[BoucWen(0.1 * weight, 0.02, 50.0)])
    result = simulate(building, motion)
    assert result.converged and not result.collapsed and np.isfinite(result.displacement).all()
    assert result.peak_ductility[0] > 2.0
    assert np.abs(result.energy.balance_error).max() < 1e-6 * result.energy.input.max()


@pytest.mark.parametrize("divisions, free_vibration, gravity", [(128, 0.0, True), (1, 60.0, False)])
def test_small_steps_and_long_rest_converge(divisions, free_vibration, gravity):
    # The force test's scale includes the inertia terms before they cancel (m 4/dt^2 |u|): at dt / 128, and
    # at rest after a record without P-Delta, the tolerance stays above the residual's round-off.
    motion = read_at2(shared_record("elCentro.AT2")).scaled(1.2)
    motion = GroundMotion(motion.acceleration[:400], motion.dt, motion.name)  # 8 s
    building = frame(walls=FRACTIONAL_WALL, gravity=gravity)
    result = simulate(building, motion, dt=motion.dt / divisions, free_vibration=free_vibration)
    assert result.converged and result.peak_ductility.max() > 1.0
    assert result.time[-1] == pytest.approx(motion.duration + free_vibration)


def test_free_vibration_appends_rest_and_residual_drift_is_measured_at_rest():
    motion = read_at2(shared_record("RIO270.AT2")).scaled_to_pga(0.6 * G)
    building = frame(walls=FRACTIONAL_WALL)
    result = simulate(building, motion, free_vibration=10.0)
    assert result.time[-1] == pytest.approx(motion.duration + 10.0)
    assert not result.ground_acceleration[-int(10.0 / motion.dt):].any()
    assert np.abs(result.velocity[-1]).max() < 0.02 * np.abs(result.velocity).max()  # at rest
    np.testing.assert_array_equal(result.residual_drift, result.drift[-1])
    assert np.abs(result.residual_drift).max() > 1.0  # mm: the frame yielded and kept a permanent set


def test_nonconvergence_is_reported_not_raised():
    motion = read_at2(shared_record("RIO270.AT2")).scaled_to_pga(0.6 * G)
    building = frame(model=BoucWen, walls=FRACTIONAL_WALL)
    hopeless = NewtonRaphson(displacement_tolerance=1e-300, force_tolerance=1e-300, max_iterations=1,
                             fallback_iterations=1)
    with pytest.warns(RuntimeWarning, match=r"did not converge \(story \d+"):
        result = simulate(building, motion, newton=hopeless)
    assert not result.converged and not result.collapsed
    assert np.isfinite(result.displacement).all() and result.time[-1] < motion.duration
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with concurrent.futures.ThreadPoolExecutor(1) as pool:
            batch = run_batch(building, [motion], [0.5, 1.0], executor=pool, progress=False, newton=hopeless)
    assert batch.converged.tolist() == [[False, False]]


def test_ida_refuses_a_building_without_story_heights():
    building = ShearBuilding(MASSES, STIFFNESSES, hysteresis=[Bilinear(1e6)] * 10)
    with pytest.raises(ValueError, match="needs story_heights"):
        incremental_dynamic_analysis(building, [read_at2(shared_record("RIO270.AT2"))], 0.1 * G, 1.0 * G)


def test_run_batch_reports_collapse_convergence_and_residual_drift():
    motion = read_at2(shared_record("RIO270.AT2"))
    building = frame(strength=0.03, hardening=0.0, walls=None)
    factors = [0.1 * G / motion.pga, 1.0 * G / motion.pga]
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        batch = run_batch(building, [motion], factors, executor=pool, progress=False)
    assert batch.collapsed.tolist() == [[False, True]]
    assert batch.converged.tolist() == [[True, True]]
    expected = simulate(building, motion.scaled(factors[0]))
    np.testing.assert_allclose(batch.residual_drift[0, 0], expected.residual_drift, rtol=1e-12)
