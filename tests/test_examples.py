"""The example seismic simulation and the command line, end to end."""

import csv
import json
import runpy
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from vdw_frames import cli, paper, simulate
from vdw_frames.config import building_from_dict, load_building
from vdw_frames.motion import G, default_record_path, read_at2

from shared_data import REPO as ROOT
from shared_data import shared_record
FIGURES = ("drift_envelope.png", "roof_displacement.png", "damper_hysteresis.png", "energy.png")


def _example():
    return runpy.run_path(str(ROOT / "examples" / "seismic_simulation.py"), run_name="example")


def test_seismic_example_runs_on_the_shipped_record(tmp_path, capsys):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # strain-range warnings are expected output
        assert _example()["main"](["--out", str(tmp_path)]) == 0
    printed = capsys.readouterr().out
    assert "peak drift ratio (%)" in printed and "reduction" in printed
    for name in FIGURES:
        assert (tmp_path / name).stat().st_size > 10_000
    # The printed reduction is the one the package computes.
    building = _example()["example_building"]()
    motion = read_at2(default_record_path())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        bare = simulate(building.without_dampers(), motion).peak_drift_ratio.max()
        walls = simulate(building, motion).peak_drift_ratio.max()
    line = next(row for row in printed.splitlines() if row.startswith("peak drift ratio"))
    assert float(line.split()[-2]) == pytest.approx(100 * (1 - walls / bare), abs=0.06)
    assert walls < 0.7 * bare


def test_seismic_example_on_a_shared_record_scaled(tmp_path, capsys):
    rio = shared_record("RIO270.AT2")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        _example()["main"](["--record", str(rio), "--scale", "0.3", "--out", str(tmp_path)])
    assert "PGA = 0.300 g" in capsys.readouterr().out
    assert all((tmp_path / name).exists() for name in FIGURES)


def test_example_building_file_matches_its_description():
    building = load_building(ROOT / "examples" / "ten_story.toml")
    np.testing.assert_allclose(building.periods[:4], [1.984, 0.708, 0.435, 0.319], atol=5e-4)
    assert [story for story, _ in building.damper_list] == [1, 2, 3, 4, 5, 6]
    assert building.damper_list[0][1] == paper.fitted(300, area=0.5e6)
    assert 0.0 < building.damper_list[0][1].r < 1.0  # the example exercises the fractional memory


def test_cli_simulate_with_a_json_building(tmp_path, capsys):
    spec = {"masses": [300.0, 300.0], "stiffnesses": [2e5, 1.5e5], "story_heights": [3500.0, 3500.0],
            "walls": [{"stories": [1], "per_story": 2,
                       "parameters": {"G1": 0.0, "G2": 3.0, "eta1": 0.3, "eta2": 2.0, "r": 0.5}}]}
    path = tmp_path / "two.json"
    path.write_text(json.dumps(spec))
    assert cli.main(["simulate", str(path), "--record", str(default_record_path()), "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "2 stories" in out and "2 FDMK dampers" in out
    assert (tmp_path / "damper_hysteresis.png").exists()
    # The printed table is the package's own result for the same building and record.
    expected = simulate(building_from_dict(spec), read_at2(default_record_path()))
    row = next(line.split() for line in out.splitlines() if line.strip().startswith("1 "))
    assert float(row[1]) == pytest.approx(expected.peak_drift[0], abs=0.006)
    assert float(row[4]) == pytest.approx(expected.peak_damper_force[0] / 1e3, abs=0.06)


def test_cli_sine_test_prints_stiffness_and_writes_the_loop(tmp_path, capsys):
    assert cli.main(["sine-test", "--strain", "300", "--frequency", "1.5", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    damper = paper.fitted(300)
    expected = damper.storage_stiffness(1.5) / 1e3
    line = next(row for row in out.splitlines() if "storage stiffness" in row)
    assert float(line.split("=")[1].split()[0]) == pytest.approx(expected, rel=2e-3)
    assert (tmp_path / "sine_test_loop.png").stat().st_size > 10_000


def test_cli_reports_bad_input_as_an_error(tmp_path, capsys):
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"masses": [1.0, 1.0], "stiffnesses": [1.0, 1.0],
                               "walls": [{"stories": [3], "parameters": "fitted-300"}]}))
    assert cli.main(["simulate", str(bad), "--record", str(default_record_path())]) == 2
    assert "bad.json: damper story must be a story number in 1 ... 2, got 3" in capsys.readouterr().err


@pytest.mark.parametrize("command", ["simulate", "sine-test", "paper-report"])
def test_cli_help(command):
    run = subprocess.run([sys.executable, "-m", "vdw_frames.cli", command, "--help"], capture_output=True, text=True)
    assert run.returncode == 0 and "usage: vdw-frames" in run.stdout


def test_cli_reports_a_missing_record(tmp_path, capsys):
    assert cli.main(["simulate", str(ROOT / "examples" / "ten_story.toml"), "--record", str(tmp_path / "none.AT2")]) == 2
    assert "none.AT2" in capsys.readouterr().err


@pytest.mark.parametrize("data, match", [
    ({"masses": 5, "stiffnesses": [1.0]}, "masses must be a list"),
    ({"masses": [1.0], "stiffnesses": [1.0], "walls": 5}, "walls must be a list"),
    ({"masses": [1.0], "stiffnesses": [1.0], "damping_modes": 5}, "damping_modes must be a list"),
    ({"masses": [1.0, 1.0], "stiffnesses": [1.0, 1.0], "walls": [{"stories": [1, 1], "parameters": "fitted-300"}]},
     "distinct story numbers"),
    ({"masses": [1.0]}, "missing key 'stiffnesses'"),
    ({"masses": [1.0], "stiffnesses": [1.0], "floors": 1}, "unknown building keys"),
    ({"masses": [1.0], "stiffnesses": [1.0], "walls": [{"parameters": "fitted-999"}]}, "strain must be one of"),
    ({"masses": [1.0], "stiffnesses": [1.0], "walls": [{"parameters": {"G1": 1.0}}]}, "walls parameters"),
    ({"masses": [1.0], "stiffnesses": [1.0], "walls": [{"parameters": "fitted-300", "per_story": 0}]}, "per_story"),
])
def test_building_file_validation(data, match):
    with pytest.raises(ValueError, match=match):
        building_from_dict(data)


def test_ida_example_writes_curves_and_csv(tmp_path, capsys):
    records = tmp_path / "records"
    records.mkdir()
    (records / "synthetic.AT2").write_bytes(default_record_path().read_bytes())
    ida = runpy.run_path(str(ROOT / "examples" / "ida.py"), run_name="ida")
    assert ida["main"](["--out", str(tmp_path), "--records", str(records), "--levels", "2"]) == 0
    rows = list(csv.DictReader((tmp_path / "ida_with_VDW.csv").open()))
    assert len(rows) == 1 * 2 * 10
    assert float(rows[10]["pga_mm_s2"]) == pytest.approx(0.2 * G)
    # A linear frame: doubling the PGA doubles every peak.
    first, second = float(rows[0]["peak_drift_mm"]), float(rows[10]["peak_drift_mm"])
    assert second == pytest.approx(2 * first, rel=1e-9)
    assert (tmp_path / "ida_curves.png").stat().st_size > 10_000
    assert "median peak drift ratio" in capsys.readouterr().out
