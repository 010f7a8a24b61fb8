"""Walls stepped together (vdw_frames.element.bank.WallBank): inputs are refused by name, and no force
leaves it as inf or NaN."""

import math

import numpy as np
import pytest
from builders import TABLE4

from vdw_frames import FDMKDamper, ThermalProperties, WallLimits
from vdw_frames.element import ISD110_LOSS_PEAK, kernel
from vdw_frames.element.bank import WallBank
from vdw_frames.element.fractional import get_method


def bank(walls=1):
    return WallBank((FDMKDamper(**TABLE4),) * walls, 0.01, 10, get_method("trapezoidal"), "exact")


@pytest.mark.parametrize("bad", [math.nan, math.inf])
def test_non_finite_deformations_are_refused_by_trial_and_commit(bad):
    with pytest.raises(ValueError, match="deformation must be finite"):
        bank().trial_forces([bad])
    with pytest.raises(ValueError, match="deformation must be finite"):
        bank().commit([bad])


def test_a_wrong_number_of_deformations_is_refused_naming_both_counts():
    with pytest.raises(ValueError, match="deformation has 2 values for 1 walls"):
        bank().commit(np.array([1.0, 2.0]))
    with pytest.raises(ValueError, match="deformation has 1 values for 2 walls"):
        bank(2).trial_forces([1.0])


def test_an_overflowing_force_is_refused_before_the_memory_takes_it():
    walls = bank(2)
    with pytest.raises(ValueError, match=r"the force of wall 2 overflowed \(inf or NaN\) at deformation = 1e\+306 mm"):
        walls.commit([1.0, 1e306])
    assert walls.count == 0
    force, _ = walls.commit([1.0, 1.0])
    assert force[0] == force[1] == bank().commit([1.0])[0][0]  # as from rest


@pytest.mark.parametrize("dt", [1e-300, 5e-324, 1e300, 1e-10, 1e4])
def test_time_steps_outside_the_accepted_range_are_refused(dt):
    refused = r"dt = .* s is outside the range of time steps accepted \(1e-09 \.\.\. 1000 s\)"
    with pytest.raises(ValueError, match=refused):
        WallBank((FDMKDamper(**TABLE4),), dt, 10)


def test_the_wall_state_is_read_by_name_from_its_groups():
    # References: the walls' own inputs (temperature at rest, limits) and the state groups themselves.
    heated = FDMKDamper(**TABLE4, thermal=ThermalProperties(ISD110_LOSS_PEAK, 1.8, 25.0),
                        limits=WallLimits(strain=2.5, residual=0.2))
    walls = WallBank((heated, FDMKDamper(**TABLE4)), 0.01, 10)
    names = [name for fields in kernel.GROUPS.values() for name in fields]
    assert len(names) == len(set(names))  # WallBank.state finds a field by its name alone
    np.testing.assert_array_equal(walls.state("temperature"), [25.0, np.nan])
    np.testing.assert_array_equal(walls.state("limit_strain"), [2.5, np.inf])
    np.testing.assert_array_equal(walls.state("residual"), [0.2, 0.0])
    np.testing.assert_array_equal(walls.state("failure_step"), [-1.0, -1.0])
    np.testing.assert_array_equal(walls.state("tracked"), [1.0, 0.0])
    walls.commit([0.5, 0.5])
    for group, fields in kernel.GROUPS.items():
        for name in fields:
            np.testing.assert_array_equal(walls.state(name), getattr(getattr(walls.states, group), name))
    copy = walls.state("heat")
    assert copy[0] > 0.0
    copy[0] = -1.0  # a copy: the state is untouched
    assert walls.states.energy.heat[0] > 0.0
    with pytest.raises(ValueError, match="no wall state field 'TEMPERATURE'; the fields are tracked, "):
        walls.state("TEMPERATURE")
