"""Buildings whose walls heat: energy accounts with the walls' own heat, temperatures, batch envelopes over
ambient temperatures -- each against an independent computation."""

import dataclasses
import re
import warnings

import numpy as np
import pytest

import vdw_frames as vdw
from vdw_frames.element.thermal import ISD110_LOSS_PEAK, LogLinear, ThermalProperties, thermal_row
from vdw_frames.frame.results import _heat_from_temperature
from vdw_frames.motion import default_record


def heated(wall, heat_capacity=1.8, temperature=21.2):
    return dataclasses.replace(wall, thermal=ThermalProperties(ISD110_LOSS_PEAK, heat_capacity, temperature))


def five_story(walls):
    masses = np.array([400.0, 400.0, 380.0, 360.0, 300.0])
    weight = np.cumsum((masses * vdw.G)[::-1])[::-1]
    return vdw.ShearBuilding(masses=masses, stiffnesses=[3.0e5, 2.7e5, 2.4e5, 2.0e5, 1.6e5],
                             story_heights=[3500.0] * 5, gravity_loads=weight,
                             hysteresis=[vdw.Bilinear(0.12 * w, 0.03) for w in weight],
                             devices={story: walls for story in range(1, 6)})


WALL = vdw.FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5, area=3e5, thickness=8.0)


def test_the_energy_balance_closes_with_the_walls_heat_as_their_dissipation():
    building = five_story([heated(WALL)])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = vdw.simulate(building, default_record().scaled(1.5))
    energy = result.energy
    assert np.nanmax(result.peak_temperature_rise) > 5.0
    assert np.all(np.diff(energy.wall_heat) >= 0.0)
    assert np.abs(energy.heat_balance_error).max() <= 5e-3 * energy.input.max()
    # The split is the walls' work: heat + stored + parameter loss (no wall failed) equals int F dd.
    split = energy.wall_heat + energy.wall_stored + energy.wall_released + energy.wall_parameter_loss
    assert np.abs(split - energy.wall_work).max() <= 5e-3 * energy.input.max()
    # The walls' heat is the sum of their own (found from their temperatures: rounding of T times rho c V).
    np.testing.assert_allclose(result.wall_heat.sum(axis=1), energy.wall_heat, rtol=1e-12,
                               atol=1e-12 * energy.wall_heat[-1])


def test_a_wall_heat_found_from_its_cooling_temperature_is_the_heat_the_kernel_summed():
    # One wall with limits and no heat capacity makes the analysis record every group's heat as the kernel
    # sums it; the heated groups' heat found from their temperatures (cooling: the update inverted) must equal it.
    cooling = dataclasses.replace(WALL, thermal=ThermalProperties(ISD110_LOSS_PEAK, 1.5, 15.0, cooling_time=4.0))
    limits_only = dataclasses.replace(WALL, area=1e5, limits=vdw.WallLimits(strain=50.0))
    building = five_story([cooling])
    recorded = vdw.ShearBuilding(building.masses, building.stiffnesses, building.damping_ratio,
                                 building.damping_modes, {**building.walls, 1: [cooling, limits_only]},
                                 building.story_heights, building.hysteresis, building.gravity_loads)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        derived, summed = vdw.simulate(building, default_record()), vdw.simulate(recorded, default_record())
    assert derived.group_heat.shape[0] == 0 and summed.group_heat.shape[0] == derived.time.size
    # The heated groups' temperatures fall while they cool (a decay really is inverted).
    assert np.any(np.diff(derived.wall_temperature[:, 0]) < 0.0)
    dt = float(summed.time[1] - summed.time[0])
    heated = np.isfinite(summed.group_temperature[0])  # every group but the one without a heat capacity
    assert heated.sum() == 5
    row = thermal_row(cooling.thermal, WALL.area * WALL.thickness, dt)  # each heated group: one wall
    # (row[7]: the update's gain, K per N*mm, in thermal_row's order kind, slope, curvature, T_ref, rho c V, T_0,
    # decay, gain)
    terms = np.zeros((heated.size, 4))
    terms[heated] = (0.0, 15.0, np.exp(-dt / 4.0), row[7])
    found = _heat_from_temperature(summed.group_temperature, terms)
    np.testing.assert_allclose(found[:, heated], summed.group_heat[:, heated], rtol=1e-12,
                               atol=1e-11 * summed.group_heat.max())


def test_a_wall_temperature_is_its_heat_over_its_heat_capacity():
    building = five_story([heated(WALL, heat_capacity=1.5, temperature=10.0)])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = vdw.simulate(building, default_record())
    volume = WALL.area * WALL.thickness  # mm^3
    np.testing.assert_allclose(result.wall_temperature - 10.0, result.wall_heat / (1.5 * volume), atol=1e-9)


def test_walls_without_a_thermal_description_report_no_temperature():
    result = vdw.simulate(five_story([WALL]), default_record())
    assert result.wall_temperature is None and result.peak_temperature_rise is None
    assert result.energy.wall_heat is None and result.energy.heat_balance_error is None


def test_heating_softens_the_walls_and_the_frame_drifts_more():
    cold = five_story([WALL])
    hot = five_story([heated(WALL, heat_capacity=0.5)])
    motion = default_record().scaled(1.5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        plain, heating = vdw.simulate(cold, motion), vdw.simulate(hot, motion)
    assert heating.peak_drift.max() > plain.peak_drift.max()


def test_a_batch_over_ambient_temperatures_is_the_envelope_of_the_separate_runs():
    building = five_story([heated(WALL)])
    motion = default_record()
    temperatures = (0.0, 21.2, 40.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        batch = vdw.run_batch(building, [motion], [1.0], executor=_Serial(), progress=False,
                              ambient_temperatures=temperatures)
        separate = [vdw.simulate(building.with_walls({s: [w.at_ambient(t) for w in ws]
                                                      for s, ws in building.walls.items()}), motion)
                    for t in temperatures]
    drifts = np.array([run.peak_drift for run in separate])  # (temperatures, stories)
    np.testing.assert_allclose(batch.peak_drift[0, 0], drifts.max(axis=0), rtol=1e-12)
    np.testing.assert_array_equal(batch.governing_temperature["peak_drift"][0, 0],
                                  np.array(temperatures)[drifts.argmax(axis=0)])
    rises = np.array([[np.nanmax(run.peak_temperature_rise[[k]]) for k in range(5)] for run in separate])
    np.testing.assert_allclose(batch.peak_temperature_rise[0, 0], rises.max(axis=0), rtol=1e-12)
    assert batch.ambient_temperatures == temperatures


def test_ambient_temperatures_need_walls_that_can_feel_them():
    with pytest.raises(ValueError, match=r"ambient_temperatures needs .* thermal description"):
        vdw.run_batch(five_story([WALL]), [default_record()], [1.0], executor=_Serial(), progress=False,
                      ambient_temperatures=(0.0, 40.0))


class _Serial:
    """A concurrent.futures-like executor that runs each task at once (no processes in the test)."""

    def submit(self, function, *args):
        from concurrent.futures import Future

        future = Future()
        future.set_result(function(*args))
        return future

    def shutdown(self, *args, **kwargs):
        pass


def test_walls_that_only_follow_their_amplitude_record_it_and_no_temperature_or_heat():
    # The same family heating at an enormous heat capacity from its law's reference (coefficients as given,
    # temperature still): its amplitudes come through the heated walls' recording, which the amplitude-only
    # walls no longer share.
    family = vdw.paper.strain_dependent(area=3e5, thickness=8.0)
    still = heated(family, heat_capacity=1e12, temperature=ISD110_LOSS_PEAK.reference)
    motion = default_record().scaled(1.5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        following, reference = (vdw.simulate(five_story([wall]), motion) for wall in (family, still))
    assert following.wall_temperature is None and following.wall_heat is None
    assert following.peak_temperature_rise is None
    assert reference.wall_temperature is not None and np.ptp(reference.wall_temperature) < 1e-6
    assert following.wall_amplitude is not None and following.wall_amplitude.shape == (following.time.size, 5)
    assert np.all(following.wall_amplitude[0] == 0.0) and following.wall_amplitude.max() > 1.0
    np.testing.assert_allclose(following.wall_amplitude, reference.wall_amplitude, rtol=0.0, atol=1e-9)


def test_a_warning_names_each_wall_whose_temperature_left_its_law_s_range_and_when():
    # Reference: the recorded temperature histories -- the first time each group is above the range's end.
    narrow = LogLinear(degrees_per_decade=19.45, reference=21.2, valid=(15.0, 40.0))
    building = five_story([dataclasses.replace(WALL, thermal=ThermalProperties(narrow, 1.8, 21.2))])
    with pytest.warns(UserWarning, match="wall temperature outside its shift law's range") as caught:
        result = vdw.simulate(building, default_record().scaled(1.5))
    message = next(str(w.message) for w in caught if "shift law's range" in str(w.message))
    named = {int(story): float(time) for story, time in re.findall(r"story (\d+) at t = ([\d.e+-]+) s", message)}
    above = result.wall_temperature > 40.0
    expected = {story + 1: float(result.time[np.argmax(above[:, story])])
                for story in range(5) if above[:, story].any()}
    assert 0 < len(expected) < 5  # some walls leave the range, some do not
    assert named.keys() == expected.keys()
    for story, time in expected.items():
        assert named[story] == pytest.approx(time, rel=1e-3)


def test_the_modes_of_walls_at_rest_beyond_their_law_s_range_take_the_law_at_the_range_s_end():
    # The measurement: walls at rest at 100 degC gave mode-1 damping 5.20 % (the law extrapolated) against
    # 6.45 % in the time domain (the law held at 70 degC).  Reference: walls written out with eta x a_T^r at the
    # range's end, a_T = 10^(-(70 - 21.2) / 19.45) by the law's printed formula.
    held = 10.0 ** (WALL.r * -(70.0 - 21.2) / ((65.6 - 26.7) / 2.0))
    at_end = dataclasses.replace(WALL, eta1=WALL.eta1 * held, eta2=WALL.eta2 * held)
    with pytest.warns(UserWarning, match="temperature 100 degC is outside the shift law's range 0 ... 70 degC"):
        hot = vdw.modal_analysis(five_story([heated(WALL, temperature=100.0)]))
    reference = vdw.modal_analysis(five_story([at_end]))
    np.testing.assert_allclose(hot.damping_ratios, reference.damping_ratios, rtol=1e-10)
    np.testing.assert_allclose(hot.periods, reference.periods, rtol=1e-10)
