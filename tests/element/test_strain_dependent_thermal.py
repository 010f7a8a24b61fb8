"""Strain-dependent walls at other temperatures: time-temperature superposition at every node amplitude,
checked against G*(omega, T) = G*(a_T omega, T_ref) computed in the test."""

import dataclasses

import numpy as np
import pytest

from vdw_frames import paper
from vdw_frames.element.thermal import ISD110_LOSS_PEAK, WLF, ThermalProperties

HEAT = ThermalProperties(ISD110_LOSS_PEAK, 1.8)


@pytest.mark.parametrize("temperature", [0.0, 10.0, 35.0, 60.0])
@pytest.mark.parametrize("strain", [2.25, 3.0, 3.6, 4.5])
def test_a_strain_dependent_wall_at_a_temperature_obeys_time_temperature_superposition(temperature, strain):
    wall = dataclasses.replace(paper.strain_dependent(), thermal=HEAT)
    shifted = wall.at_temperature(temperature)
    assert shifted.thermal is None
    a_t = 10.0 ** ISD110_LOSS_PEAK.log10_shift(temperature)
    f = np.geomspace(0.05, 20.0, 30)
    expected = wall.complex_modulus(a_t * f, strain)
    np.testing.assert_allclose(shifted.complex_modulus(f, strain), expected, rtol=1e-12)


def test_a_family_with_free_orders_shifts_node_by_node():
    family = paper.strain_dependent(common_order=False)
    law = WLF(8.0, 120.0, 21.2, (0.0, 60.0))
    shifted = family.at_temperature(5.0, law)
    a_t = 10.0 ** law.log10_shift(5.0)
    for strain in family.strains:
        np.testing.assert_allclose(shifted.complex_modulus(0.7, strain), family.complex_modulus(0.7 * a_t, strain),
                                   rtol=1e-12)


def test_ambient_and_property_factors_of_a_strain_dependent_wall():
    wall = dataclasses.replace(paper.strain_dependent(), thermal=HEAT)
    assert wall.at_ambient(5.0).thermal.temperature == 5.0
    factors = wall.property_factors([0.0, 21.2, 40.0], 0.6, 3.0)
    reference = wall.at(3.0).property_factors([0.0, 21.2, 40.0], 0.6)
    np.testing.assert_array_equal(factors.storage, reference.storage)
    np.testing.assert_array_equal(factors.loss, reference.loss)
    with pytest.raises(ValueError, match="at_ambient needs a wall with a thermal description"):
        paper.strain_dependent().at_ambient(5.0)
    with pytest.raises(ValueError, match="at_temperature needs a shift law"):
        paper.strain_dependent().at_temperature(5.0)
