"""Story materials (vdw_frames.frame.hysteresis): Bilinear against values worked by hand, Bouc-Wen against
solve_ivp of its evolution equation, consistent tangents and the trial/commit contract."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from vdw_frames import Bilinear, BoucWen
from vdw_frames.frame.hysteresis import StoryState


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

        def rate(d, y, direction):
            return [(1 - abs(y[0]) ** exponent * (beta * np.sign(direction * y[0]) + gamma)) / yield_drift]

        solution = solve_ivp(rate, (start, end), [z], rtol=1e-11, atol=1e-13, dense_output=True, args=(direction,))
        drifts = np.linspace(start, end, 401)[1:]  # 0.05 d_y steps or less
        for drift in drifts:
            force, _tangent = state.trial(drift)
            state.commit()
            z_reference = solution.sol(drift)[0]
            assert force == pytest.approx(b * k0 * drift + (1 - b) * yield_force * z_reference, rel=2e-4,
                                          abs=2e-4 * yield_force)
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

        def rate(t, y, direction, n, beta, gamma):
            z = min(abs(y[0]), 2.0)  # (the solver's probes far outside would overflow |z|^100)
            return [1.0 - z**n * (beta * np.sign(direction * y[0]) + gamma)]

        exact = solve_ivp(rate, (0.0, x), [z0], rtol=1e-11, atol=1e-13, method="LSODA",
                          args=(np.sign(x), n, beta, gamma)).y[0, -1]
        assert z == pytest.approx(exact, abs=0.02)
        step = 1e-7 * max(1.0, abs(x))
        numerical = (_bouc_wen_update(z0, x + step, n, beta, gamma)[0]
                     - _bouc_wen_update(z0, x - step, n, beta, gamma)[0]) / (2 * step)
        if abs(abs(z) - bound) > 1e-6:  # (clamped on the bound: dz/dx = 0 there, a kink)
            assert tangent == pytest.approx(numerical, rel=1e-4, abs=1e-6)


def test_bouc_wen_update_is_exact_on_the_asymptote_and_capped_below_it():
    # n = 1 from z = 0 has the closed form z = B (1 - exp(-x / B)), B = 1 / (beta + gamma).  With
    # beta + gamma = 0.01 (B = 100) increments of 100 ... 4000 yield drifts take the capped number of
    # steps (each longer than 0.1 yield drift): still within 1e-7 of B (measured 3.4e-8).  From 40 B on
    # the update returns the bound itself, and the last stepped value below 40 B differs from it only by
    # rounding (measured 8e-14 B): no jump Newton would see.
    from vdw_frames.frame.hysteresis import _bouc_wen_update

    bound = 100.0
    for x in (50.0, 101.0, 500.0, 3000.0):
        z, tangent = _bouc_wen_update(0.0, x, 1.0, 0.005, 0.005)
        assert z == pytest.approx(bound * -np.expm1(-x / bound), abs=1e-7 * bound)
        assert tangent == pytest.approx(np.exp(-x / bound), abs=1e-7)
    for n, beta, gamma in [(1.0, 0.5, 0.5), (100.0, 0.9, 0.1), (3.0, 0.02, 0.0)]:
        bound = (beta + gamma) ** (-1.0 / n)
        for z0 in (-bound, 0.0, 0.5 * bound):
            assert _bouc_wen_update(z0, -40.0 * bound, n, beta, gamma) == (-bound, 0.0)
            below, _ = _bouc_wen_update(z0, -40.0 * bound * (1 - 1e-12), n, beta, gamma)
            assert below == pytest.approx(-bound, rel=1e-12)


def test_bouc_wen_work_does_not_grow_with_the_increment_over_the_yield_drift():
    # A trial of 1e4 mm on a story whose yield drift is 1e-5 mm (1e9 yield drifts: 1e10 sub-steps before),
    # 200 steps of a frame whose stories yield at 1e-6 mm (over 120 s before) and a frame running away under
    # P-Delta with collapse detection off (it hung where Bilinear stories end at once): in a separate process,
    # so that a regression fails on its time limit instead of hanging the tests.  The frame then carries
    # only the tiny yield force: the same response as with Bilinear stories of that strength.
    program = """if True:
        import json, time, warnings
        import numpy as np
        from vdw_frames import Bilinear, BoucWen, GroundMotion, ShearBuilding, simulate
        # compiled (or loaded from the cache) first: the time limit is on the updates, not on numba
        simulate(ShearBuilding([1.0], [1.0], hysteresis=[BoucWen(1.0)]), GroundMotion(np.zeros(3), 0.01))
        start = time.perf_counter()
        force, tangent = BoucWen(1.0).new_state(1e5).trial(1e4)
        k = [8e5, 6e5, 4e5]
        motion = GroundMotion(2000.0 * np.sin(0.05 * np.arange(200)), 0.01, "sine")
        peaks, runaway = [], []
        strong = GroundMotion(5000.0 * np.sin(0.05 * np.arange(2000)), 0.01, "strong")
        for model in (BoucWen, Bilinear):
            frame = ShearBuilding([500.0] * 3, k, hysteresis=[model(1e-6 * s) for s in k])
            weak = ShearBuilding([500.0] * 3, k, story_heights=[3000.0] * 3, gravity_loads=[3e6, 2e6, 1e6],
                                 hysteresis=[model(1e3)] * 3)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                peaks.append(float(np.abs(simulate(frame, motion).drift).max()))
                runaway.append(float(np.abs(simulate(weak, strong, collapse_drift_ratio=None).drift).max()))
        print(json.dumps([force, tangent, peaks, runaway, time.perf_counter() - start]))
    """
    try:
        run = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, timeout=300, check=False)
    except subprocess.TimeoutExpired:
        pytest.fail("Bouc-Wen updates did not finish in 300 s")
    assert run.returncode == 0, run.stderr
    force, tangent, (bouc_wen, bilinear), runaway, seconds = json.loads(run.stdout)
    assert (force, tangent) == (1.0, 0.0)  # on the strength bound F_y, hardening 0
    assert bouc_wen == pytest.approx(bilinear, rel=1e-6)
    # A frame running away under P-Delta (collapse detection off): drifts of kilometres, as Bilinear's.
    assert runaway[0] > 1e6 and runaway[0] == pytest.approx(runaway[1], rel=1e-4)
    assert seconds < 60.0  # measured 0.4 s (compilation excluded)


@pytest.mark.parametrize("model", [Bilinear(5000.0, 0.1), BoucWen(5000.0, 0.1, 2.0, 0.6, 0.4)])
def test_story_tangent_is_consistent(model):
    state = model.new_state(1000.0)
    for drift in (3.0, 9.0, 2.0):
        state.trial(drift)
        state.commit()
    # (-1.0 would sit exactly on the Bilinear's yield bound, and increments of whole 0.5 mm (d_y / 10) on
    # a whole number of the Bouc-Wen update's sub-increments: small kinks where no tangent is the derivative)
    for trial in (4.03, -0.53, 12.07, 2.1):
        _force, tangent = state.trial(trial)
        step = 1e-6
        numerical = (state.trial(trial + step)[0] - state.trial(trial - step)[0]) / (2 * step)
        assert tangent == pytest.approx(numerical, rel=1e-5)
        state.revert_to_last_commit()
    assert state.committed_drift == 2.0  # trials never touched the committed state


def test_story_state_contract_refuses_bad_use():
    state = StoryState(None, 100.0)
    with pytest.raises(ValueError, match=r"commit\(\) needs a trial"):
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
