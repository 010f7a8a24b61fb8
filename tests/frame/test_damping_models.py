"""Every inherent-damping model, linear and yielding, against an independent integrator written here.

The reference is a plain Newmark average-acceleration / Newton-Raphson loop on dense numpy matrices
(M, C from ``building.damping_matrix``, story springs assembled here), with its own elastoplastic
kinematic-hardening story model, so that it shares no code with :func:`vdw_frames.simulate`.  The linear
building is also checked against the exact frequency-domain solution.  A modal-damping defect (the dense
tangent assembled row by row overwrote its coupling terms) once gave 41-57 % errors here, silently.
"""

import warnings

import numpy as np
import pytest

import vdw_frames as vdw
from vdw_frames.frame.integrator import NewtonRaphson

DAMPING_MODELS = ("rayleigh", "modal")


def reference_newmark(masses, damping, k0, yield_force, hardening, geometric, *, ground, dt):
    """Newmark (gamma 1/2, beta 1/4) with Newton on dense matrices; stories elastoplastic with kinematic
    hardening (yield_force inf: linear) and a P-Delta stiffness ``geometric`` per story.  Returns drifts."""
    n = masses.size
    B = np.eye(n) - np.eye(n, k=-1)  # drift = B u
    M = np.diag(masses)
    u, v = np.zeros(n), np.zeros(n)
    a = -ground[0] * np.ones(n)
    committed_drift, committed_force = np.zeros(n), np.zeros(n)
    drifts = [np.zeros(n)]

    def story(d):
        trial = committed_force + k0 * (d - committed_drift)
        upper = hardening * k0 * d + (1 - hardening) * yield_force
        lower = hardening * k0 * d - (1 - hardening) * yield_force
        force = np.clip(trial, lower, upper)
        tangent = np.where((trial > upper) | (trial < lower), hardening * k0, k0)
        return force, tangent

    for step in range(1, ground.size):
        x = u.copy()
        for _ in range(50):
            acc = 4 / dt**2 * (x - u) - 4 / dt * v - a
            vel = 2 / dt * (x - u) - v
            d = B @ x
            force, tangent = story(d)
            residual = -M @ np.ones(n) * ground[step] - M @ acc - damping @ vel - B.T @ (force + geometric * d)
            K = 4 / dt**2 * M + 2 / dt * damping + B.T @ np.diag(tangent + geometric) @ B
            correction = np.linalg.solve(K, residual)
            x = x + correction
            if np.abs(correction).max() < 1e-10:
                break
        d = B @ x
        committed_force, _ = story(d)
        committed_drift = d
        v_new = 2 / dt * (x - u) - v
        a = 4 / dt**2 * (x - u) - 4 / dt * v - a
        u, v = x, v_new
        drifts.append(d)
    return np.array(drifts)


def frame(stories, damping_model, yielding, p_delta=False):
    masses = np.linspace(120.0, 90.0, stories)
    stiffnesses = np.linspace(9e4, 6e4, stories)
    heights = [3500.0] * stories
    weight_above = np.cumsum((masses * vdw.G)[::-1])[::-1]
    hysteresis = [vdw.Bilinear(0.12 * weight_above[k], 0.05) for k in range(stories)] if yielding else None
    return vdw.ShearBuilding(masses=masses, stiffnesses=stiffnesses, damping_model=damping_model,
                             damping_ratio=0.05, story_heights=heights, hysteresis=hysteresis,
                             gravity_loads=weight_above if p_delta else None)


def run_reference(building, ground, dt):
    n = building.stories
    if building.hysteresis is None:
        yield_force, hardening = np.full(n, np.inf), np.zeros(n)
    else:
        yield_force = np.array([m.yield_force for m in building.hysteresis])
        hardening = np.array([m.hardening for m in building.hysteresis])
    return reference_newmark(np.asarray(building.masses), np.asarray(building.damping_matrix),
                             np.asarray(building.stiffnesses), yield_force, hardening,
                             np.asarray(building.geometric_stiffness), ground=ground, dt=dt)


def sine_motion(frequency=1.0, amplitude=3000.0, duration=12.0, dt=0.01):
    time = np.arange(0.0, duration, dt)
    return vdw.GroundMotion(amplitude * np.sin(2 * np.pi * frequency * time) * np.minimum(time / 2, 1.0), dt)


@pytest.mark.parametrize("damping_model", DAMPING_MODELS)
@pytest.mark.parametrize("stories", [2, 5])
def test_linear_building_equals_an_independent_newmark(damping_model, stories):
    building = frame(stories, damping_model, yielding=False)
    motion = sine_motion()
    result = vdw.simulate(building, motion)
    reference = run_reference(building, motion.acceleration, motion.dt)
    scale = np.abs(reference).max()
    assert np.abs(result.drift - reference).max() <= 1e-9 * scale
    assert np.abs(result.energy.balance_error).max() <= 1e-9 * np.abs(result.energy.input).max()


@pytest.mark.parametrize("damping_model", DAMPING_MODELS)
@pytest.mark.parametrize("p_delta", [False, True])
def test_yielding_building_equals_an_independent_newmark(damping_model, p_delta):
    building = frame(4, damping_model, yielding=True, p_delta=p_delta)
    motion = sine_motion(amplitude=4000.0)
    result = vdw.simulate(building, motion)
    assert result.converged and not result.collapsed
    assert result.peak_ductility.max() > 2.0  # the stories do yield
    reference = run_reference(building, motion.acceleration, motion.dt)
    # Both solve the same equations to their Newton tolerances (1e-8 mm here, 1e-10 mm in the reference).
    assert np.abs(result.drift - reference).max() <= 1e-6 * np.abs(reference).max()


@pytest.mark.parametrize("damping_model", DAMPING_MODELS)
def test_linear_building_with_walls_matches_the_frequency_domain(damping_model):
    building = frame(6, damping_model, yielding=False).with_walls(
        {1: vdw.FDMKDamper(0.0, 1.2, 0.05, 0.3, 0.6, area=2e5, thickness=10.0)})
    time = np.arange(0.0, 40.0, 0.0025)
    rng = np.random.default_rng(3)
    # A smooth band-limited input (0.3-3 Hz) tapered at both ends: Newmark's error is O((w dt)^2).
    ground = sum(np.sin(2 * np.pi * f * time + rng.uniform(0, 6)) for f in (0.3, 0.7, 1.1, 1.9, 3.0))
    ground *= 2000.0 * np.sin(np.pi * time / time[-1]) ** 2
    result = vdw.simulate(building, vdw.GroundMotion(ground, 0.0025), memory="exact")
    exact = building.stationary_response(ground, 0.0025)
    drift_exact = np.diff(exact, axis=1, prepend=0.0)
    error = np.abs(result.peak_drift - np.abs(drift_exact).max(axis=0)) / np.abs(drift_exact).max(axis=0)
    assert error.max() <= 3e-3


def test_simulate_warns_when_its_energy_balance_breaks():
    # The self-check that would have caught the modal-damping defect: a run solved far from its
    # equations (here on purpose, a Newton loop stopped at a 30 % force residual) warns, naming it.
    building = frame(4, "modal", yielding=True)
    motion = sine_motion(amplitude=4000.0)
    loose = NewtonRaphson(displacement_tolerance=50.0, force_tolerance=0.3, max_iterations=1)
    with pytest.warns(RuntimeWarning, match=r"simulate: the energy balance misses by .* of the peak input energy "
                                            r"\(self-check bound 0.0001\)"):
        result = vdw.simulate(building, motion, newton=loose)
    assert np.abs(result.energy.balance_error).max() > 1e-4 * result.energy.input.max()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # solved to its tolerances, the same run is silent
        vdw.simulate(building, motion)
