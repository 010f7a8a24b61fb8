"""The shear building (vdw_frames.frame.building): its arguments, modes and inherent damping, and its
frequency-domain responses, against closed forms."""

from __future__ import annotations

import numpy as np
import pytest
from builders import (
    README_WALL,
    SMALL_README_WALL,
    TEN_STORY_HEIGHTS,
    TEN_STORY_MASSES,
    TEN_STORY_STIFFNESSES,
)
from reference import fdmk_modulus

from vdw_frames import Bilinear, FDMKDamper, ShearBuilding, modal_analysis


# ---------------------------------------------------------------------------------------------- arguments
@pytest.mark.parametrize("kwargs, match", [
    (dict(masses=[1.0, -2.0]), "masses must be > 0"), (dict(masses=[1.0, np.nan]), "masses must be finite"),
    (dict(stiffnesses=[1.0, 0.0]), "stiffnesses must be > 0"), (dict(stiffnesses=[1.0]), "stiffnesses has 1"),
    (dict(damping_ratio=1.0), "damping_ratio"), (dict(damping_ratio=-0.1), "damping_ratio"),
    (dict(damping_modes=(1, 3)), "damping_modes"), (dict(devices={3: SMALL_README_WALL}), "story"),
    (dict(devices={0: SMALL_README_WALL}), "story"), (dict(devices={1: "wall"}), "FDMKDamper"),
    (dict(story_heights=[3000.0]), "story_heights"), (dict(story_heights=[3000.0, -1.0]), "story_heights"),
    (dict(damping_modes=(1, None)), "damping_modes"), (dict(damping_modes=(1, np.inf)), "damping_modes"),
    (dict(damping_modes=2), "damping_modes"), (dict(devices=[SMALL_README_WALL]), "devices must be a dict"),
])
def test_masses_stiffnesses_damping_walls_and_heights_are_validated(kwargs, match):
    arguments = dict(masses=[1.0, 1.0], stiffnesses=[1.0, 1.0]) | kwargs
    with pytest.raises(ValueError, match=match):
        ShearBuilding(**arguments)


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
def test_hysteresis_gravity_loads_and_damping_model_are_validated(kwargs, match):
    with pytest.raises(ValueError, match=match):
        ShearBuilding(TEN_STORY_MASSES, TEN_STORY_STIFFNESSES, **(dict(story_heights=TEN_STORY_HEIGHTS) | kwargs))


# ---------------------------------------------------------------------------------------------- modes, damping
def test_rayleigh_damping_gives_the_ratio_in_the_named_modes():
    building = ShearBuilding([200.0, 150.0, 100.0], [2e5, 1.5e5, 1e5], damping_ratio=0.04, damping_modes=(1, 3))
    phi, omega = building.mode_shapes, building.circular_frequencies
    modal = phi.T @ building.damping_matrix @ phi
    assert modal[0, 0] / (2 * omega[0]) == pytest.approx(0.04, rel=1e-12)
    assert modal[2, 2] / (2 * omega[2]) == pytest.approx(0.04, rel=1e-12)
    # Two-story check of the eigenvalues: m = 1, k = 1 chain gives w^2 = (3 -+ sqrt 5) / 2.
    two = ShearBuilding([1.0, 1.0], [1.0, 1.0])
    np.testing.assert_allclose(two.circular_frequencies**2, [(3 - 5**0.5) / 2, (3 + 5**0.5) / 2], rtol=1e-12)


def test_modal_damping_gives_the_same_ratio_in_every_mode():
    building = ShearBuilding(TEN_STORY_MASSES, TEN_STORY_STIFFNESSES, damping_ratio=0.03, damping_model="modal")
    shapes, omega = building.mode_shapes, building.circular_frequencies
    modal = shapes.T @ building.damping_matrix @ shapes
    np.testing.assert_allclose(modal, np.diag(2 * 0.03 * omega), atol=1e-12 * modal.max())
    assert building.damping_ratios == pytest.approx([0.03] * 10)
    rayleigh = ShearBuilding(TEN_STORY_MASSES, TEN_STORY_STIFFNESSES, damping_ratio=0.05)
    ratios = np.diag(shapes.T @ rayleigh.damping_matrix @ shapes) / (2 * omega)
    np.testing.assert_allclose(rayleigh.damping_ratios, ratios, rtol=1e-12)
    # 5 % in modes 1 and 2, then 6.8 % (mode 3) rising to 17.2 % (mode 10): too much for floor accelerations
    assert ratios[:2] == pytest.approx([0.05, 0.05]) and ratios[2] == pytest.approx(0.068, abs=5e-4)
    assert ratios[-1] == pytest.approx(0.172, abs=5e-4)


# ---------------------------------------------------------------------------------------------- frequency domain
def test_frequency_response_equals_the_one_story_closed_form():
    mass, stiffness = 100.0, 4e4
    wall = FDMKDamper(**README_WALL, area=2e4)
    frame = ShearBuilding([mass], [stiffness], damping_ratio=0.02, devices={1: wall})
    f = np.linspace(0.0, 40.0, 5000)  # more than one chunk of the batched solve
    a0, a1 = frame.rayleigh_coefficients
    omega = 2 * np.pi * f
    wall_stiffness = fdmk_modulus(README_WALL, np.where(f > 0, f, 1.0)) * wall.area / wall.thickness
    wall_stiffness[f == 0] = README_WALL["G1"] * wall.area / wall.thickness
    expected = -mass / (stiffness + wall_stiffness - mass * omega**2 + 1j * omega * (a0 * mass + a1 * stiffness))
    np.testing.assert_allclose(frame.frequency_response(f)[:, 0], expected, rtol=1e-12)


def test_frequency_response_refuses_resonance_bad_shapes_overflow_and_negative_frequencies():
    undamped = ShearBuilding([1.0], [(2 * np.pi) ** 2], damping_ratio=0.0)  # f_n = 1 Hz exactly
    with pytest.raises(ValueError, match=r"no bounded steady response at f = 1.0 Hz"):
        undamped.frequency_response([0.5, 1.0])
    assert undamped.frequency_response(0.5)[0, 0] == pytest.approx(-1.0 / ((2 * np.pi) ** 2 * 0.75), rel=1e-12)
    frame = ShearBuilding([100.0, 100.0], [4e4, 4e4])
    with pytest.raises(ValueError, match=r"scalar or 1-dimensional, got shape \(1, 2\)"):
        frame.frequency_response([[1.0, 2.0]])
    with pytest.raises(ValueError, match=r"overflows at f = 1e\+200 Hz"):
        frame.frequency_response([1.0, 1e200])
    with pytest.raises(ValueError, match=r"frequency must be >= 0 Hz, got -1.0"):
        frame.frequency_response(np.array([1.0, -1.0]))


def test_stationary_response_validates_its_step_and_padding():
    frame = ShearBuilding([100.0, 100.0], [4e4, 4e4])
    ground = np.ones(16)
    for dt, pad, match in [(0.0, 8, "dt must be > 0, got 0.0"), (-0.01, 8, "dt must be > 0, got -0.01"),
                           (0.01, 0, "pad_factor must be a whole number >= 1, got 0"),
                           (0.01, 1.5, "pad_factor must be a whole number >= 1, got 1.5"),
                           (0.01, True, "pad_factor must be a whole number >= 1, got True"),
                           (0.01, 10**12, r"needs 16,000,000,000,000 steps, whose arrays would take .* TiB")]:
        with pytest.raises(ValueError, match=match):
            frame.stationary_response(ground, dt, pad)
    assert frame.stationary_response(ground, 0.01, np.int64(2)).shape == (16, 2)


class StoryNumber(int):
    """A story number equal to its int but hashed apart from it, so that a dict keeps both keys (Python
    merges 1, 1.0 and np.int64(1) into one key before the building sees them)."""

    def __hash__(self) -> int:
        return hash(("story", int(self)))


def test_a_story_given_twice_after_normalisation_is_refused():
    wall = FDMKDamper(**README_WALL)
    with pytest.raises(ValueError, match=r"devices has story 1 twice \(keys \[1, 1\]\); give each story once"):
        ShearBuilding([1.0, 1.0], [1.0, 1.0], devices={1: wall, StoryNumber(1): wall})
    with pytest.raises(ValueError, match=r"hysteresis has story 2 twice"):
        ShearBuilding([1.0, 1.0], [1.0, 1.0], hysteresis={2: Bilinear(1.0), StoryNumber(2): Bilinear(2.0)})


def test_stiffnesses_whose_sum_overflows_are_refused_naming_the_stories():
    # Before: scipy's "array must not contain infs or NaNs" from the first eigen-analysis.
    with pytest.raises(ValueError, match=r"stiffnesses of stories 2 and 3 \(1e\+308 and 1e\+308 N/mm\) overflow"):
        ShearBuilding([1.0] * 3, [1.0, 1e308, 1e308])
    # its sum is finite (masses that keep k/m within MAX_FREQUENCY_SQUARED)
    assert ShearBuilding([1e300] * 2, [1e308, 1e299]).stiffness_matrix[0, 0] == 1e308 + 1e299


def _two_story_lowest_frequency(masses, stiffnesses):
    """w1 (rad/s) of a 2-story shear frame in 60-digit decimal arithmetic: w^2 = 2 det / (tr + sqrt(tr^2 - 4 det))
    of M^-1 K (the smaller root of its characteristic quadratic, in the form without cancellation)."""
    from decimal import Decimal, localcontext

    with localcontext() as context:
        context.prec = 60
        (m1, m2), (k1, k2) = (Decimal(x) for x in masses), (Decimal(x) for x in stiffnesses)
        trace = (k1 + k2) / m1 + k2 / m2
        determinant = k1 * k2 / (m1 * m2)
        return float((2 * determinant / (trace + (trace * trace - 4 * determinant).sqrt())).sqrt())


@pytest.mark.parametrize(("stiffnesses", "named"), [
    ([1e-12, 2e4], r"ratio of 2e\+16 \(story 1: 1e-12 N/mm, story 2: 20000.0 N/mm\), more than 1e\+10"),
    ([1e300, 2e4], r"ratio of 5e\+295 \(story 2: 20000.0 N/mm, story 1: 1e\+300 N/mm\), more than 1e\+10"),
    ([2e4, 1.9e-6], r"ratio of 1.05e\+10 \(story 2: 1.9e-06 N/mm, story 1: 20000.0 N/mm\)"),
])
def test_story_stiffnesses_the_eigenproblem_cannot_resolve_are_refused_naming_them(stiffnesses, named):
    """A spread of stiffnesses above 1e10: the lowest eigenvalue came out negative (1e-12 next to 2e4: period NaN,
    simulate "did not converge", modal_analysis "SVD did not converge")."""
    with pytest.raises(ValueError, match=named + ".*double precision cannot resolve"):
        ShearBuilding([10.0, 10.0], stiffnesses)


def test_the_widest_stiffness_spread_allowed_still_gives_the_lowest_frequency_to_6_digits():
    """At the bound (1e10) both solvers agree with the 60-digit closed form within 1e-5 (measured <= 3e-6)."""
    for masses, stiffnesses in (([10.0, 10.0], [2e-6, 2e4]), ([1e-12, 1e4], [2e-6, 2e4]), ([10.0, 10.0], [2e4, 2e-6])):
        frame = ShearBuilding(masses, stiffnesses)
        exact = _two_story_lowest_frequency(masses, stiffnesses)
        assert frame.lowest_circular_frequencies(1)[0] == pytest.approx(exact, rel=1e-5)
        assert frame.circular_frequencies[0] == pytest.approx(exact, rel=1e-5)


def test_frequencies_squared_beyond_the_float_range_are_refused_naming_masses_and_stiffnesses():
    with pytest.raises(ValueError, match=r"masses 1e-300 t and stiffnesses 1e\+300 N/mm .* up to inf rad\^2/s\^2"):
        ShearBuilding([1e-300, 1e-300], [1e300, 1e300])
    with pytest.raises(ValueError, match=r"masses 1e\+300 t and stiffnesses 1e-300 N/mm .* below the smallest normal"):
        ShearBuilding([1e300, 1e300], [1e-300, 1e-300])


def test_frequencies_squared_the_complex_mode_search_cannot_resolve_are_refused_and_those_below_computed():
    """k/m = 1e200 rad^2/s^2 (finite): modal_analysis's complex-mode search overflowed and raised "the argument
    principle counts 2 poles ... but 0 were found; please report this building" (the CLI: exit 3).  Refused above
    1e150 (Gershgorin's bound on w^2, 3 k/m for two equal stories); just below it, modal_analysis's first period
    against the closed form of the two-story frame."""
    from vdw_frames import modal_analysis

    with pytest.raises(ValueError, match=r"masses 1.0 t and stiffnesses 1e\+200 N/mm give circular frequencies squared "
                                         r"\(k/m\) up to 3e\+200 rad\^2/s\^2, beyond the 1e\+150 the complex-mode"):
        ShearBuilding([1.0, 1.0], [1e200, 1e200])
    masses, stiffnesses = [1.0, 1.0], [3e149, 3e149]  # Gershgorin's bound 9e149: accepted
    exact = _two_story_lowest_frequency(masses, stiffnesses)
    assert modal_analysis(ShearBuilding(masses, stiffnesses)).periods[0] == pytest.approx(2 * np.pi / exact, rel=1e-9)


def test_frequencies_and_periods_are_never_nan(monkeypatch):
    """Masses spread 1e34 over a stiffness spread of 1e10: the dense solver's w1^2 comes out -1.2e-10 (NaN periods
    before): a ValueError naming the masses and stiffnesses.  The tridiagonal bisection, on masses and stiffnesses
    scaled to their largest, resolves it (no frame found where it does not); given the dense solver's eigenvalue
    it raises the same."""
    from vdw_frames.frame import building

    frame = ShearBuilding([1e4, 1e-30, 1e4], [2e-6, 2e4, 2e-6])
    named = r"w\^2 = .* \(not finite and > 0\) for masses 1e-30 ... 10000.0 t and stiffnesses 2e-06 ... 20000.0 N/mm"
    with pytest.raises(ValueError, match=named):
        frame.periods  # noqa: B018
    assert frame.lowest_circular_frequencies(1)[0] > 0.0
    monkeypatch.setattr(building, "eigh_tridiagonal", lambda *args, **kwargs: np.array([-1.2e-10]))
    with pytest.raises(ValueError, match=named):
        ShearBuilding([1e4, 1e-30, 1e4], [2e-6, 2e4, 2e-6]).lowest_circular_frequencies(1)


def test_frequency_domain_refuses_a_frame_unstable_under_its_gravity_loads():
    # Story 2: P/h = 8e6 / 10 = 8e5 N/mm against k0 = 6e5 plus a wall whose K(0) = G1 A / t = 8.69e4 N/mm.
    # It returned a bounded stationary_response before; modal_analysis already refused the frame.
    wall = FDMKDamper(G1=8.69, G2=3.58, eta1=0.75, eta2=0.98, r=0.6, area=1e5, thickness=10.0)
    unstable = ShearBuilding([500.0] * 3, [8e5, 6e5, 4e5], devices={2: wall}, story_heights=[10.0] * 3,
                             gravity_loads=[3e6, 8e6, 1e6])
    message = (r"the frame is unstable under its gravity loads: story 2's P/h = 800000 N/mm is not below its "
               r"stiffness at rest \(k0 and walls\) 686900 N/mm")
    with pytest.raises(ValueError, match=r"frequency_response\(\): " + message):
        unstable.stationary_response(np.sin(0.1 * np.arange(200)), 0.01)
    with pytest.raises(ValueError, match=message):
        unstable.frequency_response([0.5, 1.0])
    with pytest.raises(ValueError, match=message):
        modal_analysis(unstable)
    # The walls hold the story at rest once their static stiffness closes the gap.
    held = unstable.with_walls({2: (wall.resized(3.0),)})  # 6e5 + 2.607e5 > 8e5 N/mm
    assert np.isfinite(held.stationary_response(np.sin(0.1 * np.arange(200)), 0.01)).all()


# ---------------------------------------------------------------------------------------------- large frames
def _uniform_chain_frequencies(n: int, mass: float, stiffness: float, count: int) -> np.ndarray:
    """Closed form of a uniform fixed-free spring-mass chain: w_j = 2 sqrt(k/m) sin((2j - 1) pi / (2 (2n + 1)))."""
    j = np.arange(1, count + 1)
    return 2.0 * np.sqrt(stiffness / mass) * np.sin((2 * j - 1) * np.pi / (2 * (2 * n + 1)))


def test_lowest_frequencies_from_the_tridiagonal_problem_match_the_dense_solver():
    rng = np.random.default_rng(29)
    frame = ShearBuilding(rng.uniform(50.0, 600.0, 10), rng.uniform(1e4, 5e5, 10))
    np.testing.assert_allclose(frame.lowest_circular_frequencies(3), frame.circular_frequencies[:3], rtol=1e-10)
    np.testing.assert_allclose(ShearBuilding(TEN_STORY_MASSES, TEN_STORY_STIFFNESSES).lowest_circular_frequencies(2),
                               ShearBuilding(TEN_STORY_MASSES, TEN_STORY_STIFFNESSES).circular_frequencies[:2],
                               rtol=1e-10)
    # and the closed form of a uniform chain, at 10 and at 10 000 stories (no dense solver there).  Bisection
    # is accurate to eps ||T|| = eps 4 k / m absolutely: relative to w1^2 that is 3.6e-8 at 10 000 stories.
    for n, rtol in ((10, 1e-13), (10_000, 3e-8)):
        chain = ShearBuilding([100.0] * n, [1e5] * n)
        exact = _uniform_chain_frequencies(n, 100.0, 1e5, 2)
        np.testing.assert_allclose(chain.lowest_circular_frequencies(2) ** 2, exact**2, rtol=rtol)
    with pytest.raises(ValueError, match="count must be at most the 10 modes, got 11"):
        frame.lowest_circular_frequencies(11)


def test_rayleigh_damping_without_the_dense_eigendecomposition(monkeypatch):
    """Rayleigh's coefficients, damping matrix and story-1 damping row: the dense formulas' values, from the
    two lowest frequencies alone."""
    rng = np.random.default_rng(7)
    masses, stiffnesses = rng.uniform(50.0, 600.0, 12), rng.uniform(1e4, 5e5, 12)
    dense = ShearBuilding(masses, stiffnesses, damping_modes=(1, 3), damping_ratio=0.04)
    w = dense.circular_frequencies  # the dense solver's, computed first
    a0, a1 = 2 * 0.04 * w[0] * w[2] / (w[0] + w[2]), 2 * 0.04 / (w[0] + w[2])
    monkeypatch.setattr("vdw_frames.frame.building.eigh", None)  # no dense solver from here on
    frame = ShearBuilding(masses, stiffnesses, damping_modes=(1, 3), damping_ratio=0.04)
    np.testing.assert_allclose(frame.rayleigh_coefficients, (a0, a1), rtol=1e-12)
    np.testing.assert_allclose(frame.damping_matrix, a0 * frame.mass_matrix + a1 * frame.stiffness_matrix,
                               rtol=1e-12, atol=0.0)
    np.testing.assert_allclose(frame.story_damping_row, (a1 * frame.stiffness_matrix).sum(axis=0), rtol=1e-12,
                               atol=1e-9 * a1 * stiffnesses.max())
