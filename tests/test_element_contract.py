"""Trial/commit contract of WallState and every ValueError at the boundary."""

import math

import numpy as np
import pytest

from vdw_frames import FDMKDamper, sine_test
from vdw_frames.element.fast_memory import FastMemory

TABLE4 = dict(G1=8.69, G2=3.58, eta1=0.75, eta2=0.98, r=0.60)


def _history(steps=3000, dt=0.004):
    t = np.arange(steps) * dt
    return 20 * np.sin(2 * np.pi * 1.1 * t) * np.sin(0.7 * t) + 3 * np.sin(2 * np.pi * 4.3 * t), dt


@pytest.mark.parametrize("memory", ["fast", "exact"])
@pytest.mark.parametrize("method", ["bdf2", "trapezoidal", "grunwald"])
def test_trial_commit_reproduces_force(method, memory):
    damper = FDMKDamper(**TABLE4)
    displacement, dt = _history()  # 3000 steps: the exact memory grows past its first allocation
    state = damper.new_state(dt, method=method, memory=memory)
    stepped = []
    for u in displacement:
        state.trial(u + 5.0)  # a rejected iterate must leave no trace
        force, _ = state.trial(u)
        stepped.append(force)
        state.commit()
    np.testing.assert_allclose(stepped, damper.force(displacement, dt, method=method, memory=memory),
                               rtol=1e-12, atol=1e-6)
    assert state.steps == displacement.size


def test_trial_is_repeatable_and_tangent_is_the_derivative():
    damper = FDMKDamper(**TABLE4)
    displacement, dt = _history(200)
    state = damper.new_state(dt)
    for u in displacement[:150]:
        state.trial(u)
        state.commit()
    first = state.trial(4.2)
    assert state.trial(4.2) == first
    force_a, tangent = state.trial(4.0)
    force_b, _ = state.trial(5.0)
    # The element is linear: the secant over any interval equals the tangent.
    assert force_b - force_a == pytest.approx(tangent, rel=1e-10)
    # w0 of the default damped two-step method is (a0 / b0)^r dt^-r = (7/4)^r dt^-r: the tangent is the
    # modulus at that "frequency".
    w0 = 1.75**damper.r * dt**-damper.r
    expected = damper.G1 + damper.eta1 * w0 + damper.G2 * damper.eta2 * w0 / (damper.G2 + damper.eta2 * w0)
    assert tangent == pytest.approx(expected * damper.area / damper.thickness, rel=1e-12)


def test_fast_state_refuses_to_run_past_its_horizon():
    state = FDMKDamper(**TABLE4).new_state(0.01, memory=FastMemory(max_steps=20))
    for _ in range(20):
        state.trial(1.0)
        state.commit()
    state.trial(1.0)
    with pytest.raises(ValueError, match="built for 20 steps"):
        state.commit()


def test_revert_discards_the_trial():
    damper = FDMKDamper(**TABLE4)
    state = damper.new_state(0.01)
    state.trial(1.0)
    state.revert_to_last_commit()
    with pytest.raises(ValueError, match="trial"):
        state.commit()
    assert state.steps == 0


@pytest.mark.parametrize("name, value, match", [
    ("r", 0.0, "r must lie in"), ("r", 1.5, "r must lie in"), ("r", -0.2, "r must lie in"),
    ("r", math.nan, "r must be finite"), ("G1", -1.0, "G1 must be >= 0"), ("G2", -0.1, "G2"),
    ("eta1", math.inf, "eta1 must be finite"), ("eta2", -3.0, "eta2"), ("G1", "soft", "G1 must be a real"),
    ("area", 0.0, "area must be > 0"), ("thickness", -10.0, "thickness must be > 0"),
    ("thickness", math.nan, "thickness must be finite"),
])
def test_invalid_parameters_are_refused_by_name(name, value, match):
    with pytest.raises(ValueError, match=match):
        FDMKDamper(**dict(TABLE4, **{name: value}))


def test_invalid_inputs_are_refused():
    damper = FDMKDamper(**TABLE4)
    with pytest.raises(ValueError, match="displacement must be finite.*index 2"):
        damper.force([0.0, 1.0, math.nan], 0.01)
    with pytest.raises(ValueError, match="dt must be > 0"):
        damper.force([0.0, 1.0], 0.0)
    with pytest.raises(ValueError, match="dt must be > 0"):
        damper.new_state(-0.01)
    with pytest.raises(ValueError, match="method must be one of"):
        damper.force([0.0, 1.0], 0.01, method="euler")
    with pytest.raises(ValueError, match="memory must be one of"):
        damper.force([0.0, 1.0], 0.01, memory="sloppy")
    with pytest.raises(ValueError, match="displacement must be finite"):
        damper.new_state(0.01).trial(math.inf)
    with pytest.raises(ValueError, match="f must be > 0"):
        damper.storage_modulus([1.0, -2.0])
    with pytest.raises(ValueError, match="f must be finite"):
        damper.loss_factor(math.nan)
    with pytest.raises(ValueError, match="amplitude must be > 0"):
        sine_test(damper, 0.0, 1.0)
    with pytest.raises(ValueError, match="frequency must be finite"):
        sine_test(damper, 1.0, math.inf)
    with pytest.raises(ValueError, match="fewer than 8 steps"):
        sine_test(damper, 1.0, 1.5, dt=0.1)
    with pytest.raises(ValueError, match="cycles"):
        sine_test(damper, 1.0, 1.0, cycles=0)
    with pytest.raises(ValueError, match="FDMKDamper"):
        sine_test(TABLE4, 1.0, 1.0)


def test_more_boundary_cases():
    damper = FDMKDamper(**TABLE4)
    with pytest.raises(ValueError, match="displacement must be real"):
        damper.force(np.array([0.0, 1.0 + 5.0j]), 0.01)
    with pytest.raises(ValueError, match="G1 must be a real number"):
        FDMKDamper(**dict(TABLE4, G1=np.complex128(1 + 1j)))
    with pytest.raises(ValueError, match="cycles must be a whole number"):
        sine_test(damper, 1.0, 1.0, cycles=None)
    with pytest.raises(ValueError, match="cycles must be a whole number"):
        sine_test(damper, 1.0, 1.0, cycles=math.inf)
    with pytest.raises(ValueError, match="force overflowed"):
        FDMKDamper(**dict(TABLE4, G1=1e308)).force([0.0, 1e3, 2e3], 0.01)
    for bad, match in [(dict(max_steps=math.inf), "max_steps must be a whole number"),
                       (dict(window="a"), "window must be a whole number"), (dict(tolerance=0.0), "tolerance must be > 0")]:
        with pytest.raises(ValueError, match=match):
            FastMemory(**bad)
    with pytest.raises(ValueError, match="strain_range must be two numbers"):
        FDMKDamper(**TABLE4, strain_range=(1.0,))


def test_loss_factor_of_a_damper_without_modulus_is_zero():
    # G2 > 0 with eta2 = 0: the Maxwell branch carries no force, and nothing else is there.
    assert FDMKDamper(G1=0.0, G2=3.0, eta1=0.0, eta2=0.0, r=0.5).loss_factor(1.0) == 0.0
    assert FDMKDamper(G1=0.0, G2=0.0, eta1=1.0, eta2=0.0, r=0.5).loss_factor(1.0) == pytest.approx(1.0)


def test_parameters_are_immutable():
    damper = FDMKDamper(**TABLE4)
    with pytest.raises(AttributeError):
        damper.G1 = 1.0
