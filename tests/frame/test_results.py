"""Analysis results (vdw_frames.frame.results): the energy balance is checked and a broken one is named."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from vdw_frames.frame.results import ENERGY_BALANCE_TOLERANCE, EnergyHistory, check_energy_balance


def test_a_broken_energy_balance_warns_naming_it():
    ramp = np.linspace(0.0, 1.0e6, 5)
    balanced = EnergyHistory(ramp, ramp / 2, ramp / 4, ramp / 8, ramp / 8, 0 * ramp, 0 * ramp)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_energy_balance(balanced)
    broken = EnergyHistory(ramp, ramp / 2, ramp / 4, ramp / 8, ramp / 8, ramp * 3 * ENERGY_BALANCE_TOLERANCE,
                           0 * ramp)
    with pytest.warns(RuntimeWarning, match="energy balance misses by 0.0003"):
        check_energy_balance(broken)
