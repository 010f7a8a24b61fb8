"""The ``vdw-frames verify`` command on a three-story building file and a folder of short synthetic records:
the report, CSV files and figures it writes agree with :func:`verify` run here; bad input is one error line."""

import concurrent.futures
import csv

import numpy as np
import pytest
from verification_cases import synthetic_records

from vdw_frames.cli import main
from vdw_frames.config import load_building
from vdw_frames.motion import read_at2, write_at2
from vdw_frames.verification import Site, verify

BUILDING = """
masses = [100.0, 100.0, 80.0]
stiffnesses = [1.2e5, 1.0e5, 0.8e5]
story_heights = [3500.0, 3200.0, 3200.0]
damping_ratio = 0.03

[[walls]]
stories = [1, 2]
area = 2.0e5
thickness = 10.0
parameters = {G1 = 0.5, G2 = 1.0, eta1 = 0.05, eta2 = 0.2, r = 1.0}

[[walls]]
stories = [3]
area = 2.0e5
thickness = 10.0
parameters = {G1 = 0.4, G2 = 0.8, eta1 = 0.04, eta2 = 0.16, r = 1.0}
"""


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("verify_cli")
    (folder / "building.toml").write_text(BUILDING)
    records = folder / "records"
    records.mkdir()
    for motion in synthetic_records(12, 5.0):
        write_at2(motion, records / f"{motion.name.replace(' ', '_')}.AT2")
    return folder


def test_verify_command_writes_the_report(inputs, capsys):
    out = inputs / "out"
    code = main(["verify", str(inputs / "building.toml"), "--sms", "1.5", "--sm1", "0.9", "--tl", "8",
                 "--bounds", "0.8", "1.25", "--records", str(inputs / "records"), "--out", str(out)])
    printed = capsys.readouterr().out
    assert code == 0, printed
    assert "verification: PASS" in printed and "report:" in printed
    for name in ("report.md", "suite.csv", "spectra.csv", "drifts.csv", "walls.csv", "suite_spectra.png",
                 "story_drifts.png"):
        assert (out / name).stat().st_size > 0, name
    # the same verification run here
    building = load_building(inputs / "building.toml")
    records = [read_at2(p) for p in sorted((inputs / "records").glob("*.AT2"))]
    with concurrent.futures.ThreadPoolExecutor(2) as executor:
        expected = verify(building, Site(1.5, 0.9, 8.0), records, bounds=(0.8, 1.25), executor=executor,
                          progress=False)
    with open(out / "walls.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert [float(row["deformation_mm"]) for row in rows] == pytest.approx([w.deformation for w in expected.walls],
                                                                          rel=1e-12)
    with open(out / "drifts.csv", newline="") as handle:
        drifts = np.array([float(row["peak_drift_ratio"]) for row in csv.DictReader(handle)])
    np.testing.assert_allclose(drifts, expected.peak_drift_ratio.ravel(), rtol=1e-12)
    with open(out / "spectra.csv", newline="") as handle:
        ratio = np.array([float(row["mean_over_target"]) for row in csv.DictReader(handle)])
    assert ratio.min() == pytest.approx(0.9, rel=1e-9)
    report = (out / "report.md").read_text()
    assert "**Result: PASS**" in report and "![" in report and "Prototype tests" in report
    assert "| story drift ratio, mean of all 11 records (lower) |" in report and "mean story drift" not in report
    assert "Sec. 16.4.1.2 (read in ASCE 7-22 wording)" in report and "stands in for the maximum-direction" in report
    assert "Sec. 16.2.3.1, read in ASCE 7-22 wording" in printed  # the period range, on the console too
    assert "stands in for the maximum-direction spectrum" in printed  # and what the spectra are
    # walls.csv names the strain a fraction, and the case and record of each column's largest
    assert [float(row["strain_fraction"]) for row in rows] == pytest.approx([w.strain for w in expected.walls],
                                                                            rel=1e-12)
    assert [row["governing_deformation"] for row in rows] == [w.governing for w in expected.walls]


@pytest.mark.parametrize("extra, words", [
    ([], "--bounds LAMBDA_MIN LAMBDA_MAX"),
    (["--bounds", "1.1", "1.2"], "lambda_min must be <= 1"),
    (["--bounds", "0.8", "1.2", "--sm1", "20"], "S_M1 = 20.0 g is larger than S_MS x T_L"),
    (["--bounds", "0.8", "1.2", "--count", "10"], "count = 10"),
    (["--bounds", "0.8", "1.2", "--records", "nowhere"], "--records nowhere"),
])
def test_verify_command_errors_are_one_line(inputs, capsys, extra, words):
    args = ["verify", str(inputs / "building.toml"), "--sms", "1.5", "--sm1", "0.9", "--tl", "8",
            "--records", str(inputs / "records"), "--out", str(inputs / "bad")]
    # a later --sm1 or --records overrides the earlier one (argparse keeps the last)
    code = main(args + extra)
    error = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(error) == 1 and error[0].startswith("vdw-frames: error:") and words in error[0]


def test_site_and_bounds_from_the_building_file(inputs, capsys):
    path = inputs / "with_site.toml"
    path.write_text(BUILDING.replace("[[walls]]", """[site]
ss = 1.0
s1 = 0.15
site_class = "D"
tl = 8.0
risk_category = "III"

[verification]
bounds = [0.85, 1.2]
bounds_source = "manufacturer's data sheet (example)"

[[walls]]""", 1))
    out = inputs / "out_file"
    code = main(["verify", str(path), "--records", str(inputs / "records"), "--out", str(out)])
    printed = capsys.readouterr().out
    assert code == 0, printed
    # F_a = 1.1 at S_S = 1.0 and F_v = 2.3 at S_1 = 0.15 on Site Class D (Tables 11.4-1, 11.4-2)
    assert "S_MS = 1.1 g, S_M1 = 0.345 g" in printed and "Risk Category III" in printed
    report = (out / "report.md").read_text()
    assert "lambda_min = 0.85, lambda_max = 1.2 (manufacturer's data sheet (example))" in report
    assert "2 x 0.015 h_sx" in report
    with open(out / "drifts.csv", newline="") as handle:
        assert {row["lambda"] for row in csv.DictReader(handle)} == {"1.0", "1.2", "0.85"}


@pytest.mark.parametrize("table, words", [
    ("[verification]\nbounds = [0.8]\n", "bounds must be [lambda_min, lambda_max]"),
    ("[verification]\nbounds = [0.8, 1.2]\nsource = 'x'\n", "unknown verification keys"),
    ("[verification]\nbounds = [0.8, 1.2]\nambient = [40.0]\n", "ambient must be [coldest, hottest] in degC"),
    # Kelvin typed where degC is meant, and temperature counted twice.
    ("[verification]\nbounds = [0.8, 1.2]\nambient = [283.15, 303.15]\n", "subtract 273.15 (10 degC)"),
    ("[verification]\nbounds = [0.8, 1.2]\nambient = [10.0, 30.0]\nlambda_includes_temperature = true\n",
     "count temperature twice"),
    ("[verification]\nbounds = [0.8, 1.2]\nlambda_includes_temperature = 'yes'\n", "must be true or false"),
    ("[site]\nsms = 1.5\ntl = 8.0\n", "only ['sms']"),
    ("[site]\nsms = 1.5\nsm1 = 0.9\n", "the site needs tl"),
])
def test_bad_verification_tables_name_the_key(inputs, capsys, table, words):
    path = inputs / "bad_table.toml"
    path.write_text(BUILDING.replace("[[walls]]", table + "\n[[walls]]", 1))
    code = main(["verify", str(path), "--records", str(inputs / "records"), "--out", str(inputs / "bad2")])
    error = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(error) == 1 and words in error[0] and "bad_table.toml" in error[0]


HEATED = BUILDING.replace("r = 1.0}\n", 'r = 1.0}\nthermal = {shift = "isd110-loss-peak", heat_capacity = 1.8, '
                                          'temperature = 21.2}\n')


def test_ambient_bounds_from_the_file_and_the_command_line(inputs, capsys):
    from vdw_frames.verification import PropertyBounds

    path = inputs / "heated.toml"
    path.write_text(HEATED.replace("[[walls]]", "[verification]\nbounds = [0.8, 1.25]\nambient = [0.0, 40.0]\n\n"
                                   "[[walls]]", 1))
    out = inputs / "out_heated"
    code = main(["verify", str(path), "--sms", "1.5", "--sm1", "0.9", "--tl", "8", "--records",
                 str(inputs / "records"), "--out", str(out)])
    printed = capsys.readouterr().out
    assert code == 0, printed
    building = load_building(path)
    records = [read_at2(p) for p in sorted((inputs / "records").glob("*.AT2"))]
    with concurrent.futures.ThreadPoolExecutor(2) as executor:
        expected = verify(building, Site(1.5, 0.9, 8.0), records, executor=executor, progress=False,
                          bounds=PropertyBounds(0.8, 1.25, ambient=(0.0, 40.0)))
    frequency = 1.0 / expected.first_period
    assert expected.ambient_ends == ((None,) * 3, (0.0,) * 3, (40.0,) * 3)  # walls below their loss peak
    for c, case, at in ((1, "upper", 0.0), (2, "lower", 40.0)):
        storage, loss = expected.stiffness_factors[c, :, 0], expected.stiffness_factors[c, :, 1]
        assert (f"{case} bound: lambda {expected.cases[c][1]:g}, walls from {at:g} degC: K' x {storage.min():.3f}-"
                f"{storage.max():.3f}, K'' x {loss.min():.3f}-{loss.max():.3f} at {frequency:.3f} Hz") in printed
    with open(out / "drifts.csv", newline="") as handle:
        drifts = np.array([float(row["peak_drift_ratio"]) for row in csv.DictReader(handle)])
    np.testing.assert_allclose(drifts, expected.peak_drift_ratio.ravel(), rtol=1e-12)
    report = (out / "report.md").read_text()
    assert "the upper bound (forces) at the larger |K*|, here 0 degC; the lower bound (displacements) at the " \
           "smaller K'', here 40 degC" in report
    assert "the lambdas are not stated to include or exclude the effect of temperature" in report
    # --ambient overrides the file's range.
    code = main(["verify", str(path), "--sms", "1.5", "--sm1", "0.9", "--tl", "8", "--ambient", "10", "30",
                 "--records", str(inputs / "records"), "--out", str(inputs / "out_heated_cli")])
    printed = capsys.readouterr().out
    assert code == 0 and "upper bound: lambda 1.25, walls from 10 degC" in printed and "from 30 degC" in printed


def test_kelvin_on_the_command_line_is_refused_in_one_line(inputs, capsys):
    code = main(["verify", str(inputs / "building.toml"), "--sms", "1.5", "--sm1", "0.9", "--tl", "8", "--bounds",
                 "0.8", "1.2", "--ambient", "283.15", "303.15", "--records", str(inputs / "records"), "--out",
                 str(inputs / "bad4")])
    error = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(error) == 1 and "ambient temperature 283.15 degC is above 200 degC" in error[0]


def test_ambient_bounds_need_walls_that_heat(inputs, capsys):
    code = main(["verify", str(inputs / "building.toml"), "--sms", "1.5", "--sm1", "0.9", "--tl", "8", "--bounds",
                 "0.8", "1.2", "--ambient", "0", "40", "--records", str(inputs / "records"), "--out",
                 str(inputs / "bad3")])
    error = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(error) == 1 and "need walls with a thermal description" in error[0]


def test_a_verification_that_fails_exits_1(inputs, capsys):
    """Every run's drift ratio is beyond a story model valid to 1e-6 only (Sec. 18.3.3's "unacceptable
    response"): the verdict is FAIL, the exit code 1 (errors stay 2), the report says the same."""
    out = inputs / "out_fail"
    code = main(["verify", str(inputs / "building.toml"), "--sms", "1.5", "--sm1", "0.9", "--tl", "8", "--bounds",
                 "0.8", "1.25", "--valid-drift-ratio", "1e-6", "--records", str(inputs / "records"), "--out",
                 str(out)])
    printed = capsys.readouterr().out
    assert code == 1, printed
    assert "verification: FAIL" in printed and "**Result: FAIL**" in (out / "report.md").read_text()
    with open(out / "drifts.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    # every run is unacceptable, and its drift ratios exceed the bound that made it so
    assert rows and all(row["unacceptable"] and float(row["peak_drift_ratio"]) > 0 for row in rows)
    assert max(float(row["peak_drift_ratio"]) for row in rows) > 1e-6


def test_site_and_verification_typos_are_refused_by_every_command(inputs, capsys, tmp_path):
    path = tmp_path / "typo.toml"
    path.write_text(BUILDING.replace("[[walls]]", "[site]\nsms = 1.5\nsm1 = 0.9\ntl = 8.0\nrisk = 'II'\n\n[[walls]]",
                                     1))
    for argv in (["simulate", str(path), "--record", "none.AT2"], ["design", str(path), "--out", str(tmp_path)],
                 ["collapse", str(path), "--out", str(tmp_path / "c")]):
        assert main(argv) == 2
        error = capsys.readouterr().err.strip().splitlines()
        assert len(error) == 1 and f"{path}: unknown site keys ['risk']" in error[0], (argv, error)
