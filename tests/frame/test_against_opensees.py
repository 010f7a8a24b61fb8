"""Cross-check against OpenSeesPy: the same shear building, r = 1 walls, a recorded accelerogram.

OpenSees has no fractional element, so the check uses classical walls (r = 1): the Kelvin branch is an
``Elastic`` material with its ``eta`` (k1 = G1 A/h, c1 = eta1 A/h), the Maxwell branch a ``Maxwell``
material (K = G2 A/h, C = eta2 A/h, alpha = 1, L = 1), Rayleigh damping a0 M on the floor nodes and
a1 K on the story springs only; see ``tests/opensees_frame.py`` for the model and the OpenSees semantics it
relies on.  Both sides integrate with Newmark's average acceleration, so the bare frame agrees to
rounding; with walls the only differences are the dampers' own time discretisations.  The frame and its walls:
``tests/builders.py`` (``classical_ten_story``).
"""


import numpy as np
import opensees_frame
import pytest
from builders import classical_ten_story
from opensees_frame import imposed_force
from reference import history_deviation, peak_deviation

from vdw_frames import simulate

pytestmark = pytest.mark.opensees


def test_opensees_materials_are_the_r1_branches_in_force_and_displacement(ops):
    # Imposed u = U (1 - cos w t) (smooth start: Newmark's velocity is then second order).  Analytic:
    # Kelvin f = k u + c u'; Maxwell f' + f k/c = k u' from rest, f = k U w (a sin wt - w cos wt + w e^-at)
    # / (a^2 + w^2) with a = k/c.  So zeroLength strain/stress are displacement/force, Maxwell's C is
    # the dashpot N*s/mm with alpha = 1, L = 1, and Elastic's eta is a parallel dashpot.
    k, c, amplitude, w = 1.0e5, 2.0e4, 10.0, 2.0 * np.pi * 1.5
    a = k / c
    errors = {}
    for dt in (0.01, 0.005):
        t = np.arange(round(3.0 / dt) + 1) * dt
        u = amplitude * (1.0 - np.cos(w * t))
        kelvin = k * u + c * amplitude * w * np.sin(w * t)
        maxwell = k * amplitude * w * (a * np.sin(w * t) - w * np.cos(w * t) + w * np.exp(-a * t)) / (a * a + w * w)
        for name, material, exact in (("Elastic", ("Elastic", 1, k, c), kelvin),
                                      ("Maxwell", ("Maxwell", 1, k, c, 1.0, 1.0), maxwell)):
            errors[name, dt] = history_deviation(imposed_force(ops, material, u, dt), exact)
    for name in ("Elastic", "Maxwell"):
        assert errors[name, 0.01] < 1e-3, errors  # measured 4.5e-4 (Elastic), 4.1e-4 (Maxwell)
        assert 3.5 < errors[name, 0.01] / errors[name, 0.005] < 4.5, errors  # second order


@pytest.mark.records
def test_bare_frame_equals_opensees(ops, record):
    # Same Newmark, same Rayleigh matrix (a0 M on nodes, a1 K on the story springs), same initial state:
    # equal to rounding (measured 3e-14 on the peaks, 2e-12 on the histories).  This pins down the
    # region/Rayleigh set-up of the OpenSees model.
    building = classical_ten_story(walls=False)
    expected = opensees_frame.drifts(opensees_frame.run(building, record.acceleration, record.dt))
    result = simulate(building, record)
    assert peak_deviation(result.drift, expected) < 1e-3  # the "tighter" bar: 0.1 %
    assert history_deviation(result.drift, expected) < 1e-8


@pytest.mark.parametrize("method, bar, measured", [
    # Trapezoidal convolution quadrature at r = 1 is exactly Newmark's velocity, so the Kelvin branch is
    # identical; the Maxwell branch differs by OpenSees' exponential integrator (O(dt^2)).
    ("trapezoidal", 1e-3, 1.1e-4),
    # The default damped two-step and BDF2 quadratures differ from the trapezoidal rule at O(dt^2)
    # (omega_1 dt = 0.11 here); the default halves BDF2's error.
    ("damped", 1e-2, 1.3e-3),
    ("bdf2", 1e-2, 3.3e-3),
])
@pytest.mark.records
def test_frame_with_r1_walls_matches_opensees_within_one_percent(ops, record, method, bar, measured):
    building = classical_ten_story()
    expected = opensees_frame.drifts(opensees_frame.run(building, record.acceleration, record.dt))
    result = simulate(building, record, method=method)
    deviation = peak_deviation(result.drift, expected)
    assert deviation < bar, (method, deviation, measured)
    assert deviation < 0.01  # the bar: peak drifts per story within 1 %
    # The walls matter: they cut the peak drifts by 26-52 % against the bare frame.
    bare = simulate(building.without_walls(), record)
    assert (result.peak_drift < 0.85 * bare.peak_drift).all()


@pytest.mark.records
def test_one_analyze_call_with_a_recorder_equals_stepping(ops, record):
    # The benchmark times OpenSees with one analyze(N) call and a recorder: the same answer.
    building = classical_ten_story()
    acceleration = record.acceleration[:400]
    stepped = opensees_frame.run(building, acceleration, record.dt)
    recorded = opensees_frame.run_recorded(building, acceleration, record.dt)
    assert recorded.shape == stepped.shape
    assert np.abs(recorded - stepped).max() <= 1e-12 * np.abs(stepped).max()
