"""Strain-dependent walls (vdw_frames.element.strain_dependent): parameters interpolated in log strain, the
complex modulus against the real closed form of eqs. (3)-(5) on parameters interpolated here, clamping, scaling
and validation.  The paper's model: tests/paper/test_strain_dependence.py; strain-compatible analysis:
tests/frame/test_strain_compatible.py."""

import dataclasses
import math
import warnings

import numpy as np
import pytest
from reference import closed_form_moduli as closed_form

from vdw_frames import StrainDependentDamper, paper

NAMES = ("G1", "G2", "eta1", "eta2", "r")


# ------------------------------------------------------------------------------------------ the element
WALL = StrainDependentDamper((1.0, 2.0, 4.0), G1=(0.0, 1.0, 2.0), G2=(2.0, 2.0, 1.0), eta1=(0.1, 0.2, 0.4),
                             eta2=(1.0, 0.5, 0.5), r=(1.0, 0.6, 0.4), area=2.0e5, thickness=8.0)


def test_parameters_at_nodes_and_between_are_linear_in_log_strain():
    assert WALL.strain_range == (1.0, 4.0)
    for k, strain in enumerate(WALL.strains):
        damper = WALL.at(strain)
        assert {name: getattr(damper, name) for name in NAMES} == {name: getattr(WALL, name)[k] for name in NAMES}
    # The geometric mean of two nodes is half way in log strain: the parameters are the mean of the nodes'.
    middle = WALL.at(math.sqrt(2.0 * 4.0))
    for name in NAMES:
        halfway = 0.5 * (getattr(WALL, name)[1] + getattr(WALL, name)[2])
        assert getattr(middle, name) == pytest.approx(halfway, rel=1e-12)
    assert (middle.area, middle.thickness, middle.strain_range) == (2.0e5, 8.0, (1.0, 4.0))


def test_complex_modulus_and_stiffness_against_the_closed_form():
    f = np.geomspace(0.1, 20.0, 7)
    strain = 1.5
    t = math.log(1.5 / 1.0) / math.log(2.0)
    params = {name: (1 - t) * getattr(WALL, name)[0] + t * getattr(WALL, name)[1] for name in NAMES}
    storage, loss = closed_form(params, f)
    modulus = WALL.complex_modulus(f, strain)
    np.testing.assert_allclose(modulus.real, storage, rtol=1e-12)
    np.testing.assert_allclose(modulus.imag, loss, rtol=1e-12)
    np.testing.assert_allclose(WALL.complex_stiffness(f, strain), modulus * 2.0e5 / 8.0, rtol=1e-14)
    # f and strain broadcast: a (3, 1) x (4,) grid.
    grid = WALL.complex_modulus(f[:3, None], np.array([1.0, 1.5, 2.0, 3.0]))
    assert grid.shape == (3, 4)
    assert grid[1, 1] == pytest.approx(WALL.at(1.5).complex_modulus(f[1]), rel=1e-14)
    assert isinstance(WALL.complex_modulus(1.0, 2.0), complex)


def test_clamping_outside_the_range_warns_with_the_strain_reached():
    with pytest.warns(UserWarning, match=r"strain amplitude 50 % outside the identified range 100-400 %"):
        low = WALL.at(0.5)
    with pytest.warns(UserWarning, match=r"strain amplitude 750 % outside"):
        high = WALL.at(7.5)
    assert low == WALL.at(1.0) and high == WALL.at(4.0)
    with pytest.warns(UserWarning, match=r"750 %"):
        assert WALL.complex_modulus(2.0, 7.5) == WALL.at(4.0).complex_modulus(2.0)
    assert WALL.clamped(0.5) == 1.0 and WALL.clamped(7.5) == 4.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        WALL.at(1.0), WALL.at(4.0), WALL.at(2.5), WALL.clamped([0.1, 9.0])
    with pytest.warns(UserWarning, match="outside"):
        assert paper.strain_dependent().at(1.0) == paper.strain_dependent().at(2.25)


@pytest.mark.parametrize("changes, match", [
    ({"strains": (1.0,), "G1": (0.0,), "G2": (1.0,), "eta1": (1.0,), "eta2": (1.0,), "r": (0.5,)}, "at least two"),
    ({"strains": (2.0, 1.0, 4.0)}, "strictly increasing"),
    ({"strains": (0.0, 2.0, 4.0)}, "> 0"),
    ({"strains": (1.0, True, 4.0)}, "real numbers"),
    ({"G1": (0.0, -1.0, 2.0)}, "G1 must be >= 0"),
    ({"eta2": (1.0, 0.5)}, "eta2 has 2 values for 3 strains"),
    ({"r": (1.0, 0.0, 0.4)}, r"r must lie in \(0, 1\]"),
    ({"r": (1.0, 1.2, 0.4)}, r"r must lie in \(0, 1\]"),
    ({"G2": (1.0, "2", 1.0)}, "real numbers"),
    ({"eta1": (0.1, float("nan"), 0.4)}, "finite"),
    ({"area": 0.0}, "area must be > 0"),
])
def test_bad_strain_nodes_and_parameters_are_refused(changes, match):
    with pytest.raises(ValueError, match=match):
        dataclasses.replace(WALL, **changes)


@pytest.mark.parametrize("strain", [-0.1, True, "3", float("inf"), [1.0, 2.0]])
def test_bad_strains_are_refused(strain):
    with pytest.raises(ValueError, match="strain"):
        WALL.at(strain)


def test_constant_wall_has_the_damper_parameters_everywhere():
    damper = paper.fitted(300, area=0.5e6)
    wall = StrainDependentDamper.constant(damper, (2.0, 5.0))
    for strain in (2.0, 2.7, 3.3, 5.0):
        at = wall.at(strain)
        assert {name: getattr(at, name) for name in NAMES} == paper.FITTED[300]
        assert (at.area, at.thickness) == (damper.area, damper.thickness)
    with pytest.raises(ValueError, match="FDMKDamper"):
        StrainDependentDamper.constant(WALL, (1.0, 2.0))


def test_strain_dependent_walls_scale_at_every_amplitude():
    wall = paper.strain_dependent(area=1e5)
    for strain in (2.5, 3.0, 4.0):
        np.testing.assert_allclose(wall.scaled(0.8).at(strain).complex_stiffness(1.0),
                                   0.8 * wall.at(strain).complex_stiffness(1.0), rtol=1e-12)


def test_a_force_history_beyond_the_identified_amplitudes_is_said():
    # The paper's family was identified at 225-450 %: a 1000 % sine is followed at 1000 % with the 450 % node's
    # parameters, a 100 % one with the 225 % node's; simulate warns of both, StrainDependentDamper.force said
    # nothing.  Within the range it says nothing.
    wall = paper.strain_dependent(area=1e4, thickness=10.0)
    steps = np.arange(1001)
    for amplitude, said in ((100.0, r"above the range for 4.9\d s \(followed 1000 % at the end\)"),
                            (10.0, r"below the range throughout \(its strain at most 100 %\)")):
        with pytest.warns(UserWarning, match=r"amplitudes its parameters were identified at \(225-450 %; .*" + said):
            wall.force(amplitude * np.sin(2 * np.pi * steps / 200), 0.005)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        wall.force(30.0 * np.sin(2 * np.pi * steps / 200), 0.005)
