"""The fluid viscous damper's trial at alpha = 0.5, solved in closed form (a quadratic), against the general
Newton iteration of the same implicit-trapezoid equation (vdw_frames.element.viscous.viscous_trial).

Reference: the iteration, run at alpha = 0.5 (1 +- 1e-12), whose answer differs from alpha = 0.5's by
O(1e-12) (the exponent's own change); both solve F + K dt/2 g(F) = F_n + K (u - u_n) - K dt/2 g(F_n).
"""

import numpy as np
import pytest

from vdw_frames import FluidViscousDamper
from vdw_frames.element.devices import device_response


@pytest.mark.parametrize("stiffness, magnification", [(2.0e5, 1.0), (5.0e3, 0.7)])
def test_closed_form_at_alpha_half_equals_the_iteration(stiffness, magnification):
    dt = 0.004
    t = np.arange(5001) * dt
    drift = 30.0 * np.sin(2.0 * np.pi * 0.7 * t) * np.sin(2.0 * np.pi * 0.05 * t)  # reversals, rest at t = 0
    closed = device_response(FluidViscousDamper(2.0e4, 0.5, stiffness, magnification), drift, dt)
    scale = np.abs(closed["force"]).max()
    assert scale > 1e4  # N: a real force
    for alpha in (0.5 * (1.0 - 1e-12), 0.5 * (1.0 + 1e-12)):
        iterated = device_response(FluidViscousDamper(2.0e4, alpha, stiffness, magnification), drift, dt)
        assert np.abs(closed["force"] - iterated["force"]).max() < 1e-10 * scale  # measured 1e-12 to 2.4e-12
        assert np.abs(closed["heat"] - iterated["heat"]).max() < 1e-10 * closed["heat"][-1]
        assert np.abs(closed["stored"] - iterated["stored"]).max() < 1e-10 * closed["heat"][-1]
