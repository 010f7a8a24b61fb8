"""The trial/commit contract of a wall's state (vdw_frames.element.damper.WallState): stepping reproduces the
element's force, trials leave no trace, the tangent is the derivative, revert and the fast memory's horizon."""

import warnings

import numpy as np
import pytest
from builders import TABLE4

from vdw_frames import FDMKDamper
from vdw_frames.element import WallState
from vdw_frames.element.fast_memory import FastMemory


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


def test_a_state_of_anything_but_a_wall_is_refused_naming_its_type():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match="a wall must be an FDMKDamper or a SupportedDamper, got str"):
            WallState("x", 0.01)


def test_a_trial_whose_force_overflows_is_refused_naming_the_displacement_and_leaves_no_trace():
    state = FDMKDamper(**TABLE4).new_state(0.01)
    with pytest.raises(ValueError, match=r"force overflowed \(inf or NaN\) at displacement = 1e\+308 mm"):
        state.trial(1e308)
    with pytest.raises(ValueError, match=r"force overflowed \(inf or NaN\) at displacement = 1e\+305 mm"):
        state.trial(1e305)
    with pytest.raises(ValueError, match="commit\\(\\) needs a trial"):
        state.commit()
    # Nothing reached the memory: the state is still at rest, and steps on as a fresh one does.
    assert state.steps == 0
    fresh = FDMKDamper(**TABLE4).new_state(0.01)
    for displacement in (1.0, -0.5, 0.25):
        expected = fresh.trial(displacement)
        fresh.commit()
        assert state.trial(displacement) == expected
        state.commit()


def test_a_state_says_once_when_its_strain_goes_above_the_identified_ones():
    # The 450 % set: a 600 % sine passes 450 % first at the commit where 60 sin(2 pi n / 200) / 10 > 4.5 (n = 27);
    # FDMKDamper.force and simulate say so, WallState said nothing.
    from vdw_frames.element.catalogue import fitted

    state = fitted(450, area=1e4, thickness=10.0).new_state(0.005)
    displacement = 60.0 * np.sin(2 * np.pi * np.arange(1, 401) / 200)
    first = int(np.flatnonzero(np.abs(displacement) / 10.0 > 4.5)[0]) + 1
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for value in displacement:
            state.trial(float(value))
            state.commit()
    said = [str(w.message) for w in caught if "WallState" in str(w.message)]
    strain = 100 * abs(displacement[first - 1]) / 10.0
    assert said == [f"WallState: wall strain {strain:.4g} % at commit {first}, above the 450 % its parameters were "
                    "identified at (the model is extrapolated there; said once)"]
