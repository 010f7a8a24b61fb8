"""A result saved to a .npz file and loaded back: every history, the outcome and the building (walls with
their thermal descriptions and limits, story models, P-Delta) come back equal, and so does every derived
quantity; files that are not saved results are refused."""

import dataclasses
import os
import warnings

import numpy as np
import pytest
from builders import TEN_STORY_GRAVITY, TEN_STORY_HEIGHTS, TEN_STORY_MASSES, TEN_STORY_STIFFNESSES, tapered_pulse

import vdw_frames as vdw
from vdw_frames.element.limits import WallLimits
from vdw_frames.element.thermal import ISD110_LOSS_PEAK, ThermalProperties
from vdw_frames.frame.results import SimulationResult

HEATED = vdw.FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5, area=3e5, thickness=8.0,
                        thermal=ThermalProperties(ISD110_LOSS_PEAK, 1.8, 15.0),
                        limits=WallLimits(strain=0.02, residual=0.1, source="a test limit"))


def _yielding_frame() -> vdw.ShearBuilding:
    """The README frame, Bilinear and Bouc-Wen stories, P-Delta, a heated wall that fails, a plain one and a
    wall on a support (every kind of object a result holds)."""
    strengths = [0.05 * TEN_STORY_GRAVITY[0] * (1 - k / 12) for k in range(10)]
    models = [vdw.Bilinear(f, 0.03) if k % 2 else vdw.BoucWen(f, 0.03) for k, f in enumerate(strengths)]
    plain = vdw.paper.fitted(300, area=0.4e6)
    return vdw.ShearBuilding(TEN_STORY_MASSES, TEN_STORY_STIFFNESSES, story_heights=TEN_STORY_HEIGHTS,
                             gravity_loads=TEN_STORY_GRAVITY, hysteresis=models,
                             walls={1: [HEATED, plain], 2: vdw.SupportedDamper(plain, 2e5), 5: plain})


@pytest.fixture(scope="module")
def result() -> SimulationResult:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return vdw.simulate(_yielding_frame(), tapered_pulse().scaled(3.0))


def _same(loaded, saved):
    if saved is None:
        assert loaded is None
    else:
        np.testing.assert_array_equal(loaded, saved)


def test_a_saved_result_loads_back_equal_in_every_history_and_the_building(result, tmp_path):
    assert result.wall_failed.any() and result.wall_temperature is not None  # the case the file must hold
    path = result.save(tmp_path / "run.npz")
    loaded = SimulationResult.load(path)
    for item in dataclasses.fields(SimulationResult):
        saved = getattr(result, item.name)
        if isinstance(saved, np.ndarray):
            np.testing.assert_array_equal(getattr(loaded, item.name), saved)
            assert getattr(loaded, item.name).dtype == saved.dtype
    for item in dataclasses.fields(result.energy):
        _same(getattr(loaded.energy, item.name), getattr(result.energy, item.name))
    assert (loaded.converged, loaded.collapsed, loaded.collapse_time, loaded.newton_iterations) == \
        (result.converged, result.collapsed, result.collapse_time, result.newton_iterations)
    # The building, rebuilt through its constructors: same walls (thermal, limits, support), models, loads.
    assert loaded.building.wall_list == result.building.wall_list
    assert loaded.building.hysteresis == result.building.hysteresis
    assert loaded.building.gravity_loads == result.building.gravity_loads
    assert loaded.building.story_heights == result.building.story_heights
    np.testing.assert_array_equal(loaded.building.periods, result.building.periods)
    # Derived quantities need the building: ratios (heights), ductilities (yield drifts), per-wall histories.
    _same(loaded.drift_ratio, result.drift_ratio)
    np.testing.assert_array_equal(loaded.peak_ductility.filled(np.nan), result.peak_ductility.filled(np.nan))
    np.testing.assert_array_equal(loaded.wall_force, result.wall_force)
    assert loaded.wall_failure_mode == result.wall_failure_mode
    assert loaded.wall_failure_time == result.wall_failure_time
    _same(loaded.peak_temperature_rise, result.peak_temperature_rise)
    _same(loaded.wall_heat, result.wall_heat)  # (found from the temperatures: the terms come back too)


def test_a_loaded_result_goes_on_from_its_state_as_the_saved_one_does(result, tmp_path):
    """The initial state (a restart) is part of the file too."""
    building = result.building
    start = result.state_at(150)
    motion = tapered_pulse().scaled(3.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        restarted = vdw.simulate(building.without_walls(), motion, initial_state=start)
    loaded = SimulationResult.load(restarted.save(tmp_path / "restart.npz"))
    assert loaded.first_step == restarted.first_step == 150
    np.testing.assert_array_equal(loaded.state_at(-1).drift, restarted.state_at(-1).drift)


def test_saving_replaces_the_old_file_only_when_the_new_one_is_complete(result, tmp_path, monkeypatch):
    path = result.save(tmp_path / "run.npz")
    before = path.read_bytes()

    def fail(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(np, "savez_compressed", fail)
    with pytest.raises(ValueError, match="run.npz: cannot write"):
        result.save(path)
    assert path.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["run.npz"]


@pytest.mark.parametrize("content", [b"", b"not a zip", None])
def test_a_file_that_is_not_a_saved_result_is_refused_naming_it(tmp_path, content):
    path = tmp_path / "other.npz"
    if content is None:
        np.savez(path, x=np.zeros(3))  # an npz without the result's metadata
    else:
        path.write_bytes(content)
    with pytest.raises(ValueError, match="other.npz: not a vdw_frames.SimulationResult"):
        SimulationResult.load(path)


def test_a_saved_result_must_be_named_npz(result, tmp_path):
    with pytest.raises(ValueError, match=r"run.csv: give a file name ending in .npz"):
        result.save(tmp_path / "run.csv")


def test_walls_that_follow_their_amplitude_come_back_with_their_histories(tmp_path):
    wall = vdw.paper.strain_dependent(area=2e5, thickness=8.0)
    building = vdw.ShearBuilding([300.0, 250.0], [2e5, 1.5e5], walls={1: wall, 2: wall}, story_heights=[3500.0] * 2)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = vdw.simulate(building, tapered_pulse().scaled(2.0))
    assert result.wall_amplitude is not None
    loaded = SimulationResult.load(result.save(tmp_path / "amplitude.npz"))
    assert loaded.building.wall_list == building.wall_list
    np.testing.assert_array_equal(loaded.wall_amplitude, result.wall_amplitude)
    np.testing.assert_array_equal(loaded.wall_time_outside_range, result.wall_time_outside_range)


def test_save_refuses_a_link_a_folder_or_a_fifo_and_leaves_what_it_points_to(result, tmp_path):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    victim = elsewhere / "passwd"  # no .npz suffix: before, a link named run.npz replaced it all the same
    victim.write_text("keep me")
    linked, dangling, folder = tmp_path / "linked.npz", tmp_path / "dangling.npz", tmp_path / "folder.npz"
    linked.symlink_to(victim)
    dangling.symlink_to(elsewhere / "new.npz")  # before: created elsewhere/new.npz
    folder.mkdir()
    for path, message in ((linked, "a symbolic link; the package writes no file through a link"),
                          (dangling, "a symbolic link; the package writes no file through a link"),
                          (folder, "is a folder; give a file name")):
        with pytest.raises(ValueError, match=f"{path.name}: {message}"):
            result.save(path)
    if hasattr(os, "mkfifo"):
        fifo = tmp_path / "pipe.npz"
        os.mkfifo(fifo)
        with pytest.raises(ValueError, match=r"pipe.npz: not a regular file \(a FIFO, socket or device\)"):
            result.save(fifo)
    assert victim.read_text() == "keep me" and [p.name for p in elsewhere.iterdir()] == ["passwd"]
    assert linked.is_symlink() and dangling.is_symlink()
    # A new path and a regular .npz file are written.
    assert SimulationResult.load(result.save(tmp_path / "new.npz")).time.size == result.time.size
