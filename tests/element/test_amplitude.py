"""Walls that follow their own strain amplitude in the time domain, against the fixed-parameter walls of the
frequency domain at each amplitude (each exact there), and their failure limits."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vdw_frames import FDMKDamper, StrainDependentDamper, paper
from vdw_frames.element.limits import WallLimits
from vdw_frames.element.thermal import ISD110_LOSS_PEAK, ThermalProperties

THICKNESS = 10.0
SYNTHETIC = StrainDependentDamper(  # a made-up family with one r and parameters that change a lot
    strains=(1.0, 2.0, 4.0), G1=(3.0, 1.0, 0.2), G2=(4.0, 2.0, 0.5), eta1=(0.5, 0.2, 0.05), eta2=(3.0, 1.0, 0.3),
    r=(0.5, 0.5, 0.5), area=1e5, thickness=THICKNESS)
FAMILIES = {"paper": paper.strain_dependent(area=1e5, thickness=THICKNESS), "synthetic": SYNTHETIC}
MILD = StrainDependentDamper(  # a made-up family with one r, softening by a factor of two over its range
    strains=(1.0, 2.0, 4.0), G1=(1.6, 1.2, 0.8), G2=(2.0, 1.5, 1.0), eta1=(0.3, 0.25, 0.2), eta2=(1.6, 1.2, 0.8),
    r=(0.5, 0.5, 0.5), area=1e5, thickness=THICKNESS)
PER_CYCLE = 400


def loops(wall, amplitudes, cycles, frequency=1.0):
    """(displacement, force) of a sine whose amplitude (strain, -) steps through ``amplitudes``, ``cycles``
    cycles each, with the last cycle of each level's slice."""
    dt = 1.0 / (frequency * PER_CYCLE)
    time = np.arange(len(amplitudes) * cycles * PER_CYCLE + 1) * dt
    level = np.minimum(time * frequency // cycles, len(amplitudes) - 1).astype(int)
    displacement = np.asarray(amplitudes)[level] * THICKNESS * np.sin(2 * np.pi * frequency * time)
    return displacement, wall.force(displacement, dt), dt


def cycle_measures(displacement, force, cycle):
    """(loop area N*mm, peak force N) of cycle number ``cycle`` (0-based)."""
    part = slice(cycle * PER_CYCLE, (cycle + 1) * PER_CYCLE + 1)
    return abs(np.trapezoid(force[part], displacement[part])), np.abs(force[part]).max()


@pytest.mark.parametrize("family", FAMILIES, ids=list(FAMILIES))
def test_a_steady_sine_gives_the_loop_of_the_wall_at_that_amplitude(family):
    wall = FAMILIES[family]
    for amplitude in (*wall.strains, float(np.sqrt(wall.strains[0] * wall.strains[1]))):
        displacement, force, dt = loops(wall, [amplitude], 6)
        fixed = wall.at(amplitude).force(displacement, dt)
        area, peak = cycle_measures(displacement, force, 5)
        fixed_area, fixed_peak = cycle_measures(displacement, fixed, 5)
        assert area == pytest.approx(fixed_area, rel=0.02)
        assert peak == pytest.approx(fixed_peak, rel=0.02)
        exact_area = np.pi * float(wall.at(amplitude).loss_stiffness(1.0)) * (amplitude * THICKNESS) ** 2
        assert fixed_area == pytest.approx(exact_area, rel=2e-3)  # the fixed wall itself is exact


@pytest.mark.parametrize("family", FAMILIES, ids=list(FAMILIES))
def test_a_stepped_sine_reaches_the_other_level_loop_within_three_cycles(family):
    # A step up is followed at once; the loop is the new level's after two cycles (the Maxwell memory was
    # built under the other level's parameters).  A step down is followed by the envelope rule only once the
    # smaller motion has persisted: a fall to half the amplitude or less within one half-cycle looks, at
    # first, like a higher mode's ripple at a peak (kernel.track_amplitude, decay release): the synthetic
    # family's 400 -> 100 % is the new level's after three cycles.
    wall = FAMILIES[family]
    low, high = wall.strains[0], wall.strains[-1]
    displacement, force, _dt = loops(wall, [low, high, low], 6)
    for level, amplitude, after in ((1, high, 2), (2, low, 3)):
        start = level * 6
        steady_displacement, steady_force, _ = loops(wall.at(amplitude), [amplitude], 6)
        steady = cycle_measures(steady_displacement, steady_force, 5)
        reached = cycle_measures(displacement, force, start + after)  # the cycle after those at the new level
        assert reached[0] == pytest.approx(steady[0], rel=0.02)
        assert reached[1] == pytest.approx(steady[1], rel=0.02)


def test_the_followed_amplitude_of_a_sine_is_its_amplitude():
    wall = SYNTHETIC
    state = wall.new_state(0.0025)
    amplitudes = []
    for n in range(1, 3 * PER_CYCLE):
        state.trial(2.5 * THICKNESS * np.sin(2 * np.pi * n / PER_CYCLE))
        state.commit()
        amplitudes.append(state.amplitude)
    # From the first peak on (the quarter cycle from rest), at every step: the envelope rule holds A through
    # each reversal (it confirms at the centre, where the completed half-cycle's amplitude is A again).
    np.testing.assert_allclose(amplitudes[PER_CYCLE // 4 - 1:], 2.5, rtol=1e-12)


def followed(wall, strain, dt):
    """The amplitude (-) ``wall`` follows at each step of a strain history (-) from rest, step by step."""
    state = wall.new_state(dt)
    amplitude = []
    for value in strain[1:]:
        state.trial(value * wall.thickness)
        state.commit()
        amplitude.append(state.amplitude)
    return np.array([0.0, *amplitude])


TWO_HARMONICS = [  # (a1, f1 Hz, a2, f2 Hz): a slow motion and a faster, smaller one (a higher mode's ripple)
    (3.0, 0.6, 0.8, 2.5),  # the issue's: peak 379 %
    (3.0, 0.6, 0.4, 2.5), (3.0, 0.6, 1.2, 2.5), (3.0, 0.6, 0.8, 4.1), (2.5, 1.0, 0.5, 3.7), (3.0, 0.6, 0.3, 6.3),
    # An independent review's sweep found these locked onto the ripple at some phases (down to 0.25 a1):
    (3.0, 0.6, 1.2, 4.4), (3.0, 0.6, 0.8, 6.0),
]
"""Each with a2 w2 <= 3 a1 w1: the faster component's velocity at most three times the slower one's, the
range where the envelope rule is stated to hold (kernel.track_amplitude)."""


def envelope_bounds(strain, a1, steps_per_slow_cycle):
    """(lower, upper) bounds of the envelope's amplitude, from the strain alone: the larger harmonic's
    amplitude, or half the strain's range over the slow cycle that ends at each step where that is smaller
    (with a non-integer frequency ratio the slow cycle's range can dip below 2 a1); and the peak |strain|."""
    windows = np.lib.stride_tricks.sliding_window_view(strain, steps_per_slow_cycle + 1)
    half_range = 0.5 * (windows.max(axis=1) - windows.min(axis=1))
    return np.minimum(a1, half_range), np.abs(strain).max()


# Some of the pairs reach past the identified amplitudes, on purpose (the tracker's range is what is tested).
@pytest.mark.filterwarnings("ignore:WallState. wall strain:UserWarning")
@pytest.mark.parametrize("a1, f1, a2, f2", TWO_HARMONICS)
@pytest.mark.parametrize("phase", [0.0, 0.5 * np.pi, np.pi, 1.5 * np.pi])
def test_two_harmonics_are_followed_by_their_envelope_not_their_ripples(a1, f1, a2, f2, phase):
    # Reference: the closed form of the strain itself.  The envelope of a1 sin(2 pi f1 t) + a2 sin(2 pi f2 t
    # + phase) (half its peak-to-peak over a slow cycle) lies between a1 and the peak |strain|; the
    # half-cycles between the fast component's reversals (what was followed before, down to 5 % on the
    # first case) do not.
    assert a2 * f2 <= 3.0 * a1 * f1
    dt = 0.004 if phase != np.pi else 0.01
    time = np.arange(0.0, 12.0 / f1, dt)
    strain = a1 * np.sin(2 * np.pi * f1 * time) + a2 * np.sin(2 * np.pi * f2 * time + phase)
    cycle = round(1.0 / (f1 * dt))
    lower, upper = envelope_bounds(strain, a1, cycle)
    amplitude = followed(SYNTHETIC, strain, dt)[cycle:]  # after the first slow cycle
    assert np.all(amplitude >= lower - 1e-12) and amplitude.max() <= upper + 1e-12


def test_a_growing_motion_is_followed_at_once():
    # A sine whose amplitude grows 1 % a step at 400 steps a cycle, then jumps from 1.0 to 4.0: at every step
    # the followed amplitude is at least the half-cycle's so far, |strain - last extreme| / 2, found from the
    # strain history alone (its extremes), and at the jump's first peak it is the new half-cycle's, 2.5.
    dt = 1.0 / PER_CYCLE
    time = np.arange(6 * PER_CYCLE + 1) * dt
    growing = np.minimum(0.2 * 1.01 ** np.arange(time.size), 3.0) * np.sin(2 * np.pi * time)
    jump = np.where(time < 3.0, 1.0, 4.0) * np.sin(2 * np.pi * time)
    for strain in (growing, jump):
        amplitude = followed(SYNTHETIC, strain, dt)
        last_extreme = np.zeros_like(strain)
        peaks = extrema(strain)
        for start, end in zip(peaks, [*peaks[1:], strain.size], strict=True):
            last_extreme[start + 1:end + 1] = strain[start]
        so_far = 0.5 * np.abs(strain - last_extreme)
        assert np.all(amplitude[peaks[0]:] >= so_far[peaks[0]:] - 1e-12)
    first_new = int(3.25 * PER_CYCLE)  # the first peak at 4.0: the half-cycle from -1.0
    assert amplitude[first_new] == pytest.approx(2.5, rel=1e-12)


@pytest.mark.parametrize("decay", [0.3, 0.8])
def test_a_decaying_motion_is_followed_within_about_a_cycle(decay):
    # A free decay a0 exp(-decay t) sin(2 pi t) (0.86 and 0.67 of the amplitude a half-cycle): after the first
    # cycle the followed amplitude lies between the envelope now and the envelope 1.25 cycles earlier (the
    # half-cycle's reversal is confirmed at its centre, a quarter cycle late, and the followed amplitude moves
    # to it over a half-cycle).
    dt = 1.0 / PER_CYCLE
    time = np.arange(5 * PER_CYCLE + 1) * dt
    envelope = 4.0 * np.exp(-decay * time)
    amplitude = followed(SYNTHETIC, envelope * np.sin(2 * np.pi * time), dt)
    later = time >= 1.25
    assert np.all(amplitude[later] >= envelope[later])
    assert np.all(amplitude[later] <= 4.0 * np.exp(-decay * (time[later] - 1.25)))


@pytest.mark.parametrize("low", [0.3, 1.0])
def test_a_sudden_drop_is_followed_once_it_persists(low):
    # 400 % then 30 % or 100 %: a fall to less than half within one half-cycle is what a ripple at a peak
    # looks like at first, so the half-cycle stalls; the decay release ends it once its extreme has stood
    # longer than a whole cycle (1 s here), and two to five cycles after the drop the wall follows the new
    # amplitude (measured: from 8.4 s and 5.4 s on).
    dt = 1.0 / PER_CYCLE
    time = np.arange(9 * PER_CYCLE + 1) * dt
    amplitude = followed(SYNTHETIC, np.where(time < 3.0, 4.0, low) * np.sin(2 * np.pi * time), dt)
    held = (time >= 1.0) & (time < 4.0)
    assert amplitude[held].min() == pytest.approx(4.0, rel=1e-9)  # 400 % held through the first cycle after it
    np.testing.assert_allclose(amplitude[time >= 8.5], low, rtol=1e-9)


def free_vibration(wall, initial_velocity, spring, mass, dt=0.002, steps=4000):
    """(wall force N, followed amplitude -, displacement mm) of a mass (tonne) on a linear ``spring`` (N/mm)
    with ``wall`` in parallel (a story), set moving from rest with ``initial_velocity`` (mm/s): Newmark's
    average acceleration; the wall is affine within a step, so one Newton correction solves it."""
    state = wall.new_state(dt)
    u, v, a = 0.0, initial_velocity, 0.0
    force, amplitude, displacement = [], [], []
    for _ in range(steps):
        f, k = state.trial(u)
        a_guess = -4 / dt * v - a  # the Newmark acceleration at u_new = u
        u_new = u + (-mass * a_guess - f - spring * u) / (4 * mass / dt**2 + k + spring)
        f, _ = state.trial(u_new)
        state.commit()
        a_new = 4 / dt**2 * (u_new - u) - 4 / dt * v - a
        v, u, a = 2 / dt * (u_new - u) - v, u_new, a_new
        force.append(f)
        amplitude.append(state.amplitude)
        displacement.append(u)
    return np.array(force), np.array(amplitude), np.array(displacement)


def extrema(values):
    step = np.sign(np.diff(values))
    return np.flatnonzero((step[1:] != step[:-1]) & (step[1:] != 0)) + 1


# The free vibration starts beyond the identified amplitudes, on purpose (said by WallState and .force).
@pytest.mark.filterwarnings("ignore:WallState. wall strain:UserWarning")
@pytest.mark.filterwarnings("ignore:wall peak strain outside:UserWarning")
@pytest.mark.slow
@pytest.mark.parametrize("family", ["paper", "mild"])
def test_a_free_vibration_has_no_spurious_force_oscillation_at_reversals(family):
    # A story: a spring 10 or 20 times stiffer than the wall, so that the motion decays slowly through the
    # wall's identified amplitudes.  (1) A spurious oscillation (parameters jumping at reversals) would add
    # force extrema: the wall's force has one extremum per half-cycle of the motion.  (2) Over each cycle
    # inside the range the wall's loop is that of the fixed-parameter wall at the amplitude it reached (its
    # mean over the cycle), the closer the slower the decay: halving the decay per cycle halves the
    # difference.  (SYNTHETIC's stiffness falls faster than 1 / amplitude: it has genuine force peaks
    # before the strain's, so it is left out.)
    wall = {"paper": FAMILIES["paper"], "mild": MILD}[family]
    errors = {}
    for ratio in (10.0, 20.0):
        spring = ratio * float(np.abs(wall.at(wall.strains[-1]).complex_stiffness(1.0)))
        mass = spring / (2 * np.pi) ** 2  # about 1 Hz, where the walls were tested
        force, amplitude, displacement = free_vibration(wall, 1.2 * wall.strains[-1] * THICKNESS * 2 * np.pi,
                                                        spring, mass, steps=20000)
        assert amplitude.max() > wall.strains[-1]
        half_cycles = extrema(displacement)
        significant = half_cycles[np.abs(displacement[half_cycles]) > 1e-3 * np.abs(displacement).max()]
        # Between mid-half-cycles (the force leads the motion), from the first reversal on (the first loading
        # from rest crosses the whole range at once).
        window = slice(int(significant[0] + significant[1]) // 2, int(significant[-2] + significant[-1]) // 2)
        assert extrema(force[window]).size == extrema(displacement[window]).size
        inside = half_cycles[(amplitude[half_cycles] >= wall.strains[0]) & (amplitude[half_cycles] <= wall.strains[-1])]
        assert inside.size >= 20
        errors[ratio] = []
        for start, end in zip(inside[:-2:2], inside[2::2], strict=True):
            reached = float(amplitude[start:end + 1].mean())
            fixed = wall.at(reached).force(displacement, 0.002)
            loop = abs(np.trapezoid(force[start:end + 1], displacement[start:end + 1]))
            errors[ratio].append(loop / abs(np.trapezoid(fixed[start:end + 1], displacement[start:end + 1])) - 1)
    assert np.abs(errors[20.0]).max() <= 0.03
    assert np.abs(errors[20.0]).max() <= 0.6 * np.abs(errors[10.0]).max()


# Random drives go beyond the identified amplitudes, on purpose: WallState says so once a run.
@pytest.mark.filterwarnings("ignore:WallState. wall strain:UserWarning")
@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**16), harmonic=st.booleans())
def test_an_amplitude_following_wall_is_passive(seed, harmonic):
    rng = np.random.default_rng(seed)
    dt, steps = 0.005, 800
    if harmonic:
        displacement = rng.uniform(5, 50) * np.sin(2 * np.pi * rng.uniform(0.2, 4.0) * np.arange(steps) * dt)
    else:
        displacement = np.cumsum(rng.normal(0.0, 3.0, steps))
    wall = StrainDependentDamper.from_nodes(
        {name: getattr(SYNTHETIC, name) for name in ("strains", "G1", "G2", "eta1", "eta2", "r")}, area=1e5,
        thickness=THICKNESS, thermal=ThermalProperties(ISD110_LOSS_PEAK, 1e12))
    state = wall.new_state(dt)
    heat = [0.0]
    for value in displacement[1:]:
        state.trial(value)
        state.commit()
        heat.append(state.heat)
    assert np.all(np.diff(heat) >= 0.0)


def test_a_family_without_a_common_order_is_refused_in_the_time_domain():
    free = paper.strain_dependent(common_order=False)
    with pytest.raises(ValueError,
                       match=r"needs one fractional order r at every amplitude, got r = 1, 0\.6839, 0\.5529"):
        free.force(np.zeros(10), 0.01)
    with pytest.raises(ValueError, match="one fractional order r"):
        free.new_state(0.01)


# ------------------------------------------------------------------------------- failure
def test_a_wall_fails_at_the_first_committed_step_beyond_its_limit():
    limits = WallLimits(strain=2.0, residual=0.0)
    wall = FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5, area=1e5, thickness=THICKNESS, limits=limits)
    dt = 0.005
    time = np.arange(2001) * dt
    displacement = 30.0 * np.sin(2 * np.pi * time) * np.minimum(time / 5.0, 1.0)  # to 300 %, slowly
    force = {}
    intact = FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5, area=1e5, thickness=THICKNESS)
    for name, model in (("limited", wall), ("intact", intact)):
        state = model.new_state(dt)
        force[name] = []
        for value in displacement:
            force[name].append(state.trial(value)[0])
            state.commit()
        if name == "limited":
            limited_state = state
    beyond = int(np.argmax(np.abs(displacement / THICKNESS) > 2.0))  # found from the strain history itself
    assert limited_state.failure_step == beyond and limited_state.failure_mode == "strain"
    assert np.all(np.array(force["limited"])[beyond + 1:] == 0.0)
    assert np.all(np.array(force["limited"])[:beyond + 1] == np.array(force["intact"])[:beyond + 1])


@pytest.mark.parametrize("make, match", [
    (lambda: WallLimits(strain=0.0), "strain must be > 0, got 0.0"),
    (lambda: WallLimits(strain=-8.5), "strain must be > 0, got -8.5"),
    (lambda: WallLimits(stress=0.0), "stress must be > 0, got 0.0"),
    (lambda: WallLimits(residual=1.0), r"residual must lie in \[0, 1\) .* got 1.0"),
    (lambda: WallLimits(residual=-0.1), r"residual must lie in \[0, 1\) .* got -0.1"),
    (lambda: WallLimits(temperature=-300.0), r"temperature limit must be above absolute zero .* got -300.0"),
    (lambda: FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5, limits=8.5), "limits must be WallLimits"),
])
def test_non_physical_limits_are_refused_naming_the_value(make, match):
    with pytest.raises(ValueError, match=match):
        make()
