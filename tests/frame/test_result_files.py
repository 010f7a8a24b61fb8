"""A result saved to a .npz file and loaded back: every history, the outcome and the building (walls with
their thermal descriptions and limits, story models, P-Delta) come back equal, and so does every derived
quantity; files that are not saved results are refused."""

import dataclasses
import io
import json
import os
import warnings
import zipfile

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
                             devices={1: [HEATED, plain], 2: vdw.SupportedDamper(plain, 2e5), 5: plain})


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
    with pytest.raises(ValueError, match=r"run\.npz: cannot write"):
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
    with pytest.raises(ValueError, match=r"other\.npz: not a vdw_frames\.SimulationResult"):
        SimulationResult.load(path)


def test_a_saved_result_must_be_named_npz(result, tmp_path):
    with pytest.raises(ValueError, match=r"run.csv: give a file name ending in .npz"):
        result.save(tmp_path / "run.csv")


def test_walls_that_follow_their_amplitude_come_back_with_their_histories(tmp_path):
    wall = vdw.paper.strain_dependent(area=2e5, thickness=8.0)
    building = vdw.ShearBuilding([300.0, 250.0], [2e5, 1.5e5], devices={1: wall, 2: wall}, story_heights=[3500.0] * 2)
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


# ------------------------------------------------------------------------------------- hostile files
def rewrite(source, target, arrays=None, metadata=None, building=None):
    """``source`` (a saved result) written again to ``target`` with some arrays, metadata entries or building
    arguments replaced, as a hostile or broken writer would (numpy and json only, no package code)."""
    with np.load(source) as data:
        contents = {name: data[name] for name in data.files}
    meta = json.loads(str(contents["metadata"]))
    meta.update(metadata or {})
    meta["building"]["arguments"].update(building or {})
    contents.update(arrays or {})
    contents["metadata"] = np.array(json.dumps(meta))
    np.savez(target, **contents)
    return target


@pytest.fixture(scope="module")
def saved(result, tmp_path_factory):
    return result.save(tmp_path_factory.mktemp("saved") / "run.npz")


HEIGHTS_X1000 = {"story_heights": {"tuple": [1000.0 * h for h in TEN_STORY_HEIGHTS]}}


@pytest.mark.parametrize("change, message", [
    ({"metadata": {"converged": "yes"}}, "converged must be True or False, got 'yes'"),
    ({"metadata": {"newton_iterations": -5}}, "newton_iterations must be a whole number >= 0, got -5"),
    ({"metadata": {"newton_iterations": "many"}}, "newton_iterations must be a whole number >= 0, got 'many'"),
    ({"metadata": {"collapse_time": {"array": [1.0], "dtype": "|O"}}},
     r"collapse_time: an entry that cannot be read \(an array of dtype object\)"),
    ({"metadata": {"collapse_time": float("nan")}}, "collapse_time must be the last time, .* got nan"),
    ({"arrays": {"result.time": np.arange(3).astype("datetime64[s]")}}, "time must be a float64 array, got datetime64"),
    ({"arrays": {"result.displacement": np.zeros(5)}}, r"displacement must have shape \(\d+, 10\), got \(5,\)"),
    ({"arrays": {"result.group_strain": np.zeros((3, 2))}}, r"group_strain must have shape \(\d+, 4\), got \(3, 2\)"),
    ({"arrays": {"result.group_failure": np.array([[10**9, 1], [-1, 0], [-1, 0], [-1, 0]])}},
     r"group_failure must hold, per wall group, a failure step in 0 ... \d+ \(-1: intact\)"),
    ({"arrays": {"result.wall_group": np.array([0, 1, 2, 7])}},
     r"wall_group must give each of the building's 4 walls one of the 4 wall groups"),
    ({"arrays": {"result.wall_share": np.array([1.0, 1.0, 1.0, 0.5])}}, "wall_share must give each wall a share"),
    ({"building": HEIGHTS_X1000}, r"base_shear disagrees with story 1's frame, wall, P-Delta and damping forces"),
    ({"building": {"masses": {"tuple": [600.0] * 9 + [451.0]}}},
     "energy.kinetic disagrees with v\\^T M v / 2 with the building's masses"),
    ({"building": {"stiffnesses": {"tuple": [3e5] * 10}}}, "energy.frame_strain disagrees with sum F_s"),
])
def test_load_refuses_a_file_whose_entries_are_wrong_naming_the_entry(saved, tmp_path, change, message):
    path = rewrite(saved, tmp_path / "bad.npz", **change)
    with pytest.raises(ValueError, match=f"bad.npz: {message}"):
        SimulationResult.load(path)


def test_load_checks_the_damping_force_from_the_diagonals_not_dense_matrices(saved, tmp_path, monkeypatch):
    # With Rayleigh damping story 1's damping force is a1 k1 v1 (the column sums of a1 K vanish but the first):
    # load checks it without any n x n matrix (with them a 4 000-story result took 3.0 s and 271 MB to load, now
    # 0.1 s and 15 MB), and still refuses a building whose damping is not the analysis's.
    def dense(self):
        raise AssertionError("a dense n x n matrix built at load")

    monkeypatch.setattr(vdw.ShearBuilding, "stiffness_matrix", property(dense))
    monkeypatch.setattr(vdw.ShearBuilding, "mass_matrix", property(dense))
    loaded = SimulationResult.load(saved)
    a1 = loaded.building.rayleigh_coefficients[1]
    row = np.asarray(loaded.building.story_damping_row)
    assert row[0] == pytest.approx(a1 * TEN_STORY_STIFFNESSES[0], rel=1e-12)
    np.testing.assert_allclose(row[1:], 0.0, atol=1e-12 * a1 * max(TEN_STORY_STIFFNESSES))
    path = rewrite(saved, tmp_path / "bad.npz", building={"damping_ratio": 0.10})
    with pytest.raises(ValueError, match=r"bad\.npz: base_shear disagrees with story 1's frame, wall, P-Delta"):
        SimulationResult.load(path)


def test_load_refuses_a_reversed_time_non_finite_histories_and_a_drift_not_of_the_displacements(result, saved,
                                                                                                 tmp_path):
    velocity = result.velocity.copy()
    velocity[5, 3] = np.nan
    cases = [({"result.time": result.time[::-1].copy()}, r"time must be \(first step \+ k\) dt"),
             ({"result.velocity": velocity}, r"velocity must be finite, got nan at index \(5, 3\)"),
             ({"energy.input": np.full(result.time.size, np.inf)},
              r"energy.input must be finite, got inf at index \(0,\)"),
             ({"result.drift": result.drift * 1.001}, "drift disagrees with the displacement differences")]
    for arrays, message in cases:
        path = rewrite(saved, tmp_path / "bad.npz", arrays=arrays)
        with pytest.raises(ValueError, match=f"bad.npz: {message}"):
            SimulationResult.load(path)


def test_load_refuses_a_time_with_a_nan_and_names_time_when_it_is_the_one_cut_short(result, saved, tmp_path):
    """A NaN in time passed every comparison of its uniform-step check (the result loaded); a time one step short
    of the histories was reported as "displacement must have shape (n - 1, 10)"."""
    time = result.time.copy()
    time[4] = np.nan
    steps = result.time.size
    cases = [({"result.time": time}, r"time must be finite, got nan at index \(4,\)"),
             ({"result.time": result.time[:-1].copy()},
              rf"time has {steps - 1} steps but every history \(displacement, .*, base_shear\) has {steps} rows"),
             ({"result.time": np.append(result.time, result.time[-1] + result.time[1])},
              rf"time has {steps + 1} steps but every history .* has {steps} rows")]
    for arrays, message in cases:
        path = rewrite(saved, tmp_path / "bad.npz", arrays=arrays)
        with pytest.raises(ValueError, match=f"bad.npz: {message}"):
            SimulationResult.load(path)


def test_load_refuses_raw_members_deep_metadata_and_a_fifo(saved, tmp_path):
    raw = tmp_path / "raw.npz"
    raw.write_bytes(saved.read_bytes())
    with zipfile.ZipFile(raw, "a") as archive:
        archive.writestr("notes.txt", "not an array")
    with pytest.raises(ValueError, match=r"raw.npz: entries \['notes.txt'\] are not numpy arrays"):
        SimulationResult.load(raw)
    nested: object = 0.0
    for _ in range(800):
        nested = [nested]
    deep = rewrite(saved, tmp_path / "deep.npz", metadata={"collapse_time": nested})
    with pytest.raises(ValueError, match=r"deep.npz: metadata nested more than 32 deep"):
        SimulationResult.load(deep)
    if hasattr(os, "mkfifo"):
        fifo = tmp_path / "pipe.npz"
        os.mkfifo(fifo)  # np.load would wait for a writer forever
        with pytest.raises(ValueError, match=r"pipe.npz: not a regular file"):
            SimulationResult.load(fifo)


def test_load_refuses_an_entry_whose_header_declares_more_data_than_it_holds(saved, tmp_path):
    """A crafted entry: a valid .npy header declaring 10^11 float64 values (800 GB) over 64 bytes of data.
    numpy allocates the declared shape before reading, so without the check this was a MemoryError (or, under
    memory overcommit, a large allocation), not a ValueError."""
    header = io.BytesIO()
    np.lib.format.write_array_header_1_0(header, {"descr": "<f8", "fortran_order": False, "shape": (10**11,)})
    crafted = tmp_path / "crafted.npz"
    with zipfile.ZipFile(saved) as source, zipfile.ZipFile(crafted, "w") as target:
        for name in source.namelist():
            data = header.getvalue() + bytes(64) if name == "result.time.npy" else source.read(name)
            target.writestr(name, data)
    with pytest.raises(ValueError, match=r"crafted.npz: entry 'result.time.npy' declares \(100000000000,\) float64 "
                                         r"\(800,000,000,000 bytes\) but holds \d+ bytes"):
        SimulationResult.load(crafted)


def test_the_checks_pass_a_file_as_saved_and_hold_the_analysis_identities(result, saved, tmp_path):
    """The untouched file loads bit-exact (above); rewritten by numpy without a change it loads too; and the
    identities are those of the analysis: the P-Delta energy is -sum P d^2 / (2 h) computed here."""
    same = SimulationResult.load(rewrite(saved, tmp_path / "same.npz"))
    np.testing.assert_array_equal(same.drift, result.drift)
    heights, loads = np.array(TEN_STORY_HEIGHTS), np.array(TEN_STORY_GRAVITY)
    np.testing.assert_allclose(result.energy.p_delta, -(result.drift**2 * loads / (2 * heights)).sum(axis=1),
                               rtol=1e-9, atol=1e-9 * np.abs(result.energy.p_delta).max())


def _variants():
    frame = vdw.ShearBuilding(TEN_STORY_MASSES, TEN_STORY_STIFFNESSES)  # no heights, no walls
    walled = vdw.ShearBuilding(TEN_STORY_MASSES, TEN_STORY_STIFFNESSES, story_heights=TEN_STORY_HEIGHTS,
                               devices={1: vdw.paper.fitted(300, area=0.4e6), 3: vdw.paper.fitted(450, area=0.2e6)})
    strain_dependent = vdw.paper.strain_dependent(area=0.5e6, thickness=10.0, common_order=False)
    return {
        "bare frame without heights": (frame, {}),
        "modal damping and walls": (dataclasses.replace(walled, damping_model="modal"), {}),
        "P-Delta, Bilinear stories, a collapse": (
            dataclasses.replace(walled, gravity_loads=tuple(TEN_STORY_GRAVITY),
                                hysteresis=[vdw.Bilinear(0.02 * TEN_STORY_GRAVITY[0], 0.0)] * 10),
            {"collapse_drift_ratio": 0.002}),
        "strain-compatible walls": (dataclasses.replace(frame, devices={1: strain_dependent, 2: strain_dependent}),
                                    {"strain_compatible": True}),
    }


@pytest.mark.parametrize("name", list(_variants()))
def test_every_kind_of_result_loads_back_bit_exact_through_the_checks(name, tmp_path):
    building, options = _variants()[name]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = vdw.simulate(building, tapered_pulse().scaled(3.0), **options)
    assert name != "P-Delta, Bilinear stories, a collapse" or result.collapsed  # the case the file must hold
    loaded = SimulationResult.load(result.save(tmp_path / "variant.npz"))
    for item in dataclasses.fields(SimulationResult):
        saved = getattr(result, item.name)
        if isinstance(saved, np.ndarray):
            assert getattr(loaded, item.name).dtype == saved.dtype
            np.testing.assert_array_equal(getattr(loaded, item.name), saved)
        elif item.name not in ("building", "energy", "initial_state"):
            assert getattr(loaded, item.name) == saved, item.name
    for item in dataclasses.fields(result.energy):
        _same(getattr(loaded.energy, item.name), getattr(result.energy, item.name))
    for field in ("masses", "stiffnesses", "story_heights", "gravity_loads", "hysteresis", "wall_list",
                  "damping_model"):
        assert getattr(loaded.building, field) == getattr(result.building, field), field
