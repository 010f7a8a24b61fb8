"""Property tests (hypothesis): passivity, linearity, time invariance for any admissible parameters."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from vdw_frames import FDMKDamper, sine_test

moduli = st.floats(0.0, 20.0)
viscosities = st.floats(0.0, 5.0)
orders = st.floats(0.01, 1.0)
dampers = st.builds(FDMKDamper, G1=moduli, G2=moduli, eta1=viscosities, eta2=viscosities, r=orders)
methods = st.sampled_from(["bdf2", "trapezoidal", "grunwald"])


@settings(max_examples=40, deadline=None)
@given(damper=dampers, amplitude=st.floats(0.1, 50.0), frequency=st.floats(0.1, 20.0))
def test_loop_area_is_non_negative(damper, amplitude, frequency):
    result = sine_test(damper, amplitude, frequency, cycles=3)
    # Rounding allowance: a relative 1e-12 of the elastic energy scale.
    scale = (damper.G1 + damper.G2 + damper.eta1 + damper.eta2) * damper.area / damper.thickness * amplitude**2
    assert result.loop_area >= -1e-12 * scale


@settings(max_examples=25, deadline=None)
@given(damper=dampers, method=methods, a=st.floats(-3.0, 3.0), b=st.floats(-3.0, 3.0),
       seed=st.integers(0, 2**16))
def test_force_is_linear(damper, method, a, b, seed):
    rng = np.random.default_rng(seed)
    u1, u2 = rng.normal(size=(2, 400)).cumsum(axis=1)
    combined = damper.force(a * u1 + b * u2, 0.01, method=method)
    separate = a * damper.force(u1, 0.01, method=method) + b * damper.force(u2, 0.01, method=method)
    scale = (np.max(np.abs(damper.force(u1, 0.01, method=method)))
             + np.max(np.abs(damper.force(u2, 0.01, method=method))))
    assert np.max(np.abs(combined - separate)) <= 1e-11 * (abs(a) + abs(b) + 1) * (scale + 1e-300)


@settings(max_examples=25, deadline=None)
@given(damper=dampers, method=methods, delay=st.integers(1, 300), seed=st.integers(0, 2**16))
def test_force_is_time_invariant(damper, method, delay, seed):
    u = np.random.default_rng(seed).normal(size=300).cumsum()
    delayed = damper.force(np.concatenate([np.zeros(delay), u]), 0.005, method=method)
    assert not np.any(delayed[:delay])
    reference = damper.force(u, 0.005, method=method)
    # The kernel's history sums are vectorised (reassociated), so the delayed run rounds differently: equal
    # to rounding of the sums, i.e. relative to the force scale, not element by element near a zero crossing.
    np.testing.assert_allclose(delayed[delay:], reference, rtol=0, atol=1e-12 * np.abs(reference).max())
