"""The examples end to end: the seismic simulation (examples/seismic_simulation.py), the example building file,
the IDA (examples/ida.py) and the OpenSees frame (examples/opensees_frame.py)."""

import csv
import runpy
import warnings

import numpy as np
import pytest
from shared_data import EXAMPLE_BUILDING, REPO, shared_record

from vdw_frames import Bilinear, modal_analysis, paper, simulate, size_walls
from vdw_frames.config import load_building
from vdw_frames.motion import G, default_record_path, read_at2

FIGURES = ("drift_envelope.png", "roof_displacement.png", "story_hysteresis.png", "damper_hysteresis.png",
           "energy.png")


def _example():
    return runpy.run_path(str(REPO / "examples" / "seismic_simulation.py"), run_name="example")


def test_seismic_example_runs_on_the_shipped_record_without_warnings(tmp_path, capsys):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the main job must not warn: its walls stay in their strain range
        assert _example()["main"](["--out", str(tmp_path)]) == 0
    printed = capsys.readouterr().out
    for name in FIGURES:
        assert (tmp_path / name).stat().st_size > 10_000
    # The printed changes are the package's own results for the same analyses.
    building = _example()["example_building"]()
    motion = read_at2(default_record_path())
    bare = simulate(building.without_walls(), motion, free_vibration=10.0)
    walls = simulate(building, motion, free_vibration=10.0)
    rows = {line[:34].strip(): line.split() for line in printed.splitlines() if line[:34].strip()}
    assert float(rows["peak drift ratio (%)"][-3]) == pytest.approx(100 * bare.peak_drift_ratio.max(), abs=6e-4)
    assert float(rows["peak drift ratio (%)"][-2]) == pytest.approx(100 * walls.peak_drift_ratio.max(), abs=6e-4)
    assert float(rows["peak story ductility (-)"][-2]) == pytest.approx(walls.peak_ductility.max(), abs=6e-4)
    residual = 100 * np.abs(walls.residual_drift / np.asarray(building.story_heights)).max()
    assert float(rows["residual drift ratio (%)"][-2]) == pytest.approx(residual, abs=6e-4)
    story1_walls = np.abs(walls.story_wall_force[:, 0]).max() / 1e3
    assert float(rows["story-1 walls (kN)"][-2]) == pytest.approx(story1_walls, abs=6e-4)
    # The walls earn their place: less drift, less yielding, less residual drift; the frame yields without them.
    assert bare.peak_ductility.max() > 2.0
    assert walls.peak_drift_ratio.max() < 0.7 * bare.peak_drift_ratio.max()
    assert walls.peak_ductility.max() < 0.8 * bare.peak_ductility.max()
    assert np.abs(walls.residual_drift).max() < 0.5 * np.abs(bare.residual_drift).max()


@pytest.mark.records
def test_seismic_example_on_a_shared_record_scaled(tmp_path, capsys):
    rio = shared_record("RIO270.AT2")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # other records take the walls outside their range
        _example()["main"](["--record", str(rio), "--scale", "0.3", "--out", str(tmp_path)])
    assert "PGA = 0.300 g" in capsys.readouterr().out
    assert all((tmp_path / name).exists() for name in FIGURES)


def test_seismic_example_reports_a_missing_record_in_one_line(tmp_path, capsys):
    assert _example()["main"](["--record", str(tmp_path / "missing.AT2"), "--out", str(tmp_path)]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "missing.AT2" in error


@pytest.mark.slow
def test_example_building_file_matches_its_description():
    building = load_building(EXAMPLE_BUILDING)
    np.testing.assert_allclose(building.periods[:4], [1.984, 0.708, 0.435, 0.319], atol=5e-4)
    # P-Delta: each story carries the weight above it.
    weight = np.asarray(building.masses) * 9806.65
    np.testing.assert_allclose(building.gravity_loads, np.cumsum(weight[::-1])[::-1], atol=1.0)  # N, rounded
    # Strengths: 0.05 W distributed as ASCE 7-16 12.8.3 (k = 1 + (T1 - 0.5) / 2), story shears x 2.5.
    k = 1.0 + (building.periods[0] - 0.5) / 2.0
    elevation = np.cumsum(building.story_heights)
    forces = 0.05 * weight.sum() * weight * elevation**k / np.sum(weight * elevation**k)
    strengths = 2.5 * np.cumsum(forces[::-1])[::-1]
    np.testing.assert_allclose([m.yield_force for m in building.story_models], strengths, rtol=1e-6)
    assert all(isinstance(m, Bilinear) and m.hardening == 0.03 for m in building.story_models)
    # Walls: one a story, the 300 % set, A / h as size_walls gives for 10 % damping in mode 1 (to the
    # rounding of the file: areas to 1000 mm^2, thicknesses to 0.1 mm).
    assert [story for story, _ in building.wall_list] == list(range(1, 11))
    assert all(w == paper.fitted(300, area=w.area, thickness=w.thickness) for _, w in building.wall_list)
    sized = size_walls(building.without_walls(), paper.fitted(300, area=0.5e6, thickness=10.0), 0.10,
                       distribution="drift", stories=range(1, 11))
    for (_, wall), (_, reference) in zip(building.wall_list, sized.wall_list, strict=True):
        assert wall.area / wall.thickness == pytest.approx(reference.area / reference.thickness, rel=0.012)
    assert modal_analysis(building, modes=[1]).damping_ratios[0] == pytest.approx(0.10, abs=1e-3)
    # Thicknesses: the shipped record's peak strains lie inside the 300 % set's identified range.
    walls = simulate(building, read_at2(default_record_path()), free_vibration=10.0)
    low, high = paper.fitted(300).strain_range
    assert np.all((low < walls.peak_wall_strain) & (walls.peak_wall_strain < high))


def test_ida_example_steps_records_to_collapse(tmp_path, capsys):
    records = tmp_path / "records"
    records.mkdir()
    (records / "synthetic.AT2").write_bytes(default_record_path().read_bytes())
    ida = runpy.run_path(str(REPO / "examples" / "ida.py"), run_name="ida")
    assert ida["main"](["--out", str(tmp_path), "--records", str(records), "--step", "0.5", "--cap", "4.0"]) == 0
    printed = capsys.readouterr().out
    building = load_building(EXAMPLE_BUILDING)
    period = building.without_walls().periods[0]
    for label, frame in (("bare_frame", building.without_walls()), ("with_VDW", building)):
        rows = list(csv.DictReader((tmp_path / f"ida_{label}.csv").open()))
        assert {row["record"] for row in rows} == {"synthetic", "synthetic_kt_035g"}  # the folder's and the shipped one
        # Each row is the package's own analysis at that Sa(T1); the last level of each record collapsed.
        first = rows[0]
        motion = read_at2(default_record_path())
        scaled = motion.scaled_to_spectral_acceleration(float(first["sa_g"]) * G, period)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)
            expected = simulate(frame, scaled).peak_drift_ratio.max()
        assert float(first["largest_drift_ratio"]) == pytest.approx(expected, rel=1e-9)
        for record in {row["record"] for row in rows}:  # stepped up until the first collapse or the cap
            runs = [row for row in rows if row["record"] == record]
            outcome = [row["collapsed"] for row in runs]
            standing = float(runs[-1]["sa_g"]) == pytest.approx(4.0) and outcome == ["0"] * len(runs)
            assert standing or outcome == ["0"] * (len(outcome) - 1) + ["1"]
            assert [float(row["sa_g"]) for row in runs] == pytest.approx(0.5 * np.arange(1, len(runs) + 1))
    assert "median collapse Sa(T1)" in printed and "collapse-margin gain" in printed
    assert "strain-dependent walls" in printed
    for name in ("ida_curves.png", "fragility.png"):
        assert (tmp_path / name).stat().st_size > 10_000


def test_example_script_reports_a_missing_record(tmp_path, capsys):
    example = runpy.run_path(str(REPO / "examples" / "seismic_simulation.py"), run_name="example")
    missing = tmp_path / "missing.AT2"
    assert example["main"](["--record", str(missing), "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err == f"seismic_simulation.py: error: {missing}: no such AT2 file\n"


@pytest.mark.slow
@pytest.mark.opensees
def test_opensees_frame_example_runs_and_its_prony_frame_follows_the_bridge(tmp_path, capsys):
    example = runpy.run_path(str(REPO / "examples" / "opensees_frame.py"), run_name="example")
    assert example["main"](["--duration", "3", "--out", str(tmp_path)]) == 0
    printed = capsys.readouterr().out
    rows = [line.split() for line in printed.splitlines() if line[:3].strip().isdigit() and "%" in line]
    assert len(rows) == 4  # one row per story
    bare, bridge, prony = (np.array([float(row[k]) for row in rows]) for k in (1, 2, 3))
    # The Prony frame (OpenSees's own Maxwell materials) is an independent model of the same walls: within
    # 2 % of the exact bridge in peak drifts; both below the bare frame.
    np.testing.assert_allclose(prony, bridge, rtol=0.02)
    assert (bridge < bare).all()
    assert "Maxwell branches" in printed and "Damper - Exponential" in printed
    for name in ("drift_envelope.png", "wall_hysteresis.png"):
        assert (tmp_path / name).stat().st_size > 10_000
