"""``vdw-frames design-building`` end to end on a three-story input (issue 31, part 3): the bare design writes its
files and its building file is the one design_frame gives; the damped design's final verification is repeated
by a second, independent run of ``vdw-frames verify`` on the saved building file, which gives the same numbers
(the same CSV text, every digit); a device limit below any reachable demand is printed as the reason and exits
1; bad input is one error line and exit code 2.  Records: 12 synthetic 20 s records written as AT2 files
(the suite takes 11).  Units N-mm-s-tonne."""

from __future__ import annotations

import csv

import numpy as np
import pytest
from verification_cases import synthetic_records

from vdw_frames import ShearBuilding
from vdw_frames.cli import main
from vdw_frames.config import load_building, load_design_input, load_verification
from vdw_frames.design import design_frame
from vdw_frames.design_report import write_design_report
from vdw_frames.motion import G, write_at2

INPUT = """
[site]                  # examples/verify.py's site: S_MS = 0.9 g, S_M1 = 0.45 g
ss = 0.75
s1 = {s1}
site_class = "C"
tl = 8.0
risk_category = "{risk}"

[building]
masses = [600.0, 600.0, 450.0]
story_heights = [4000.0, 3500.0, {top}]

[design]
overstrength = 3.0      # the steel SMF's Omega_0 (Table 12.2-1), the stated expected overstrength
target_damping = 0.20
rounds = 1
bounds = [0.8, 1.2]
bounds_source = "assumed for the test"
records = "records"
{extra}

[design.prototype]      # a linear FVD with a stiff brace
type = "fluid_viscous"
C = 1.0e4
alpha = 1.0
stiffness = 1.0e6
"""


def write_input(folder, name="site.toml", risk="II", top="3500.0", extra="", s1="0.3"):
    path = folder / name
    path.write_text(INPUT.format(risk=risk, top=top, extra=extra, s1=s1))
    return path


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    folder = tmp_path_factory.mktemp("design_building")
    records = folder / "records"
    records.mkdir()
    for motion in synthetic_records(12, 20.0):  # 20 s: longer than 5 x the period range's upper end
        write_at2(motion, records / f"{motion.name.replace(' ', '_')}.AT2")
    write_input(folder)
    return folder


def test_a_bare_design_writes_the_building_design_frame_gives(folder, capsys):
    out = folder / "bare"
    out.mkdir()
    (out / "notes.txt").write_text("mine")  # an unrelated file in the output folder is left alone
    assert main(["design-building", str(folder / "site.toml"), "--device", "none", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "SDC D" in printed and "report:" in printed and "[design.prototype] is not used" in printed
    for name in ("building.toml", "design.md", "elf.csv", "design_profiles.png"):
        assert (out / name).stat().st_size > 0, name
    assert (out / "notes.txt").read_text() == "mine"
    assert not (out / "devices.csv").exists()
    # The file's building is design_frame's, called here with the input's values, every float the same bits.
    given = load_design_input(folder / "site.toml")
    assert np.array_equal(given.weights, np.array([600.0, 600.0, 450.0]) * G)
    expected = design_frame(given.site, "steel-smf", given.weights, given.story_heights, overstrength=3.0)
    building, site, bounds = load_verification(out / "building.toml")
    assert building.stiffnesses == expected.building.stiffnesses
    assert building.masses == expected.building.masses
    assert building.gravity_loads == expected.building.gravity_loads
    assert building.hysteresis == expected.building.hysteresis
    assert not building.devices
    assert (site.sms, site.sm1, site.tl) == (given.site.sms, given.site.sm1, given.site.tl)
    assert bounds is None  # a bare frame has no device properties to bound
    # elf.csv holds the design's rows
    with (out / "elf.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    assert [float(row["strength_n"]) for row in rows] == [float(v) for v in expected.strengths]
    text = (out / "design.md").read_text()
    assert "ELF" in text and "Eq. 12.8-" in text and "No devices" in text


@pytest.mark.slow
def test_the_damped_design_s_verification_is_repeated_by_verify_on_the_saved_file(folder, capsys):
    out = folder / "fvd"
    code = main(["design-building", str(folder / "site.toml"), "--out", str(out)])  # fvd: the prototype's type
    printed = capsys.readouterr().out
    assert code == 0, printed
    assert "design: PASS" in printed
    for name in ("building.toml", "design.md", "elf.csv", "devices.csv", "rounds.csv", "design_profiles.png",
                 "drift_spread.png", "verification_drifts.csv", "verification_devices.csv"):
        assert (out / name).stat().st_size > 0, name
    building = load_building(out / "building.toml")
    assert [story for story, _ in building.device_list] == [1, 2, 3]
    # A second, independent run: the verify command on the saved building file (its [site] and [verification]).
    again = folder / "verify_again"
    code = main(["verify", str(out / "building.toml"), "--records", str(folder / "records"), "--out", str(again)])
    printed = capsys.readouterr().out
    assert code == 0 and "verification: PASS" in printed
    # The same numbers: every peak drift ratio and device demand, to the last digit written (repr of the float).
    assert (again / "drifts.csv").read_text() == (out / "verification_drifts.csv").read_text()
    assert (again / "devices.csv").read_text() == (out / "verification_devices.csv").read_text()
    assert (again / "suite.csv").read_text() == (out / "verification_suite.csv").read_text()
    text = (out / "design.md").read_text()
    assert "**Verdict: PASS**" in text and "Device schedule" in text and "### Rounds" in text
    # The schedule's demands are the verification's largest over the bounds, device by device.
    with (out / "devices.csv").open() as handle:
        schedule = list(csv.DictReader(handle))
    with (again / "devices.csv").open() as handle:
        per_case = list(csv.DictReader(handle))
    for index, row in enumerate(schedule, start=1):
        cases = [case for case in per_case if int(case["device"]) == index]
        assert len(cases) == 3
        assert float(row["deformation_mm"]) == max(float(case["deformation_mm"]) for case in cases)
        assert float(row["force_n"]) == max(float(case["force_N"]) for case in cases)
        assert float(row["c"]) == building.device_list[index - 1][1].C


@pytest.mark.slow
def test_a_device_limit_below_any_reachable_demand_is_the_reason_and_exits_1(folder, capsys):
    # 1 micrometre of stroke: no damper of any size stays under it at MCE_R
    site = write_input(folder, "limited.toml", extra="\n[design.device_limits]\nstroke = 1.0e-3")
    out = folder / "limited"
    code = main(["design-building", str(site), "--device", "fvd", "--out", str(out)])
    printed = capsys.readouterr().out
    assert code == 1
    assert "design: FAIL" in printed and "stroke of device" in printed and "limit 0.001 mm" in printed
    assert "**Verdict: FAIL**" in (out / "design.md").read_text()


@pytest.mark.parametrize(("arguments", "input_options", "words"), [
    (["--system", "steel-xyz"], {}, "steel-xyz"),
    ([], {"risk": "V"}, "risk"),
    # Steel IMF in SDC D: 35 ft (Table 12.2-1 row C.3); 4000 + 3500 + 3500 mm = 36.1 ft
    (["--system", "steel-imf"], {}, "exceeds the 35 ft limit"),
    (["--target-damping", "0"], {}, "--target-damping must be a damping ratio in (0, 1)"),
    (["--target-damping", "1"], {}, "--target-damping must be a damping ratio in (0, 1)"),
    (["--target-damping", "-0.2", "--device", "fvd"], {}, "--target-damping must be a damping ratio in (0, 1)"),
    (["--device", "walls"], {}, "[design.prototype] is of type 'fluid_viscous', not 'wall'"),
    ([], {"top": "3500.0, 3500.0"}, "weights and story heights of different lengths"),
    # a site outside the spectrum's rules: S_1 >= 0.6 g needs a site-specific hazard analysis (Sec. 11.4.8)
    ([], {"s1": "0.6"}, "Sec. 11.4.8 requires a ground motion hazard analysis"),
    (["--bounds", "1.2", "0.8"], {}, "lambda"),
    (["--rounds", "0"], {}, "rounds"),
    (["--rounds", "11"], {}, "rounds"),
    ([], {"extra": 'distribution = "foo"'}, "distribution"),
    ([], {"extra": "\n[design.device_limits]\nstroke = -1.0"}, "device_limits['stroke'] must be > 0"),
])
def test_bad_input_is_one_error_line_and_exit_2(folder, tmp_path, capsys, arguments, input_options, words):
    site = write_input(tmp_path, **input_options)
    code = main(["design-building", str(site), *arguments, "--out", str(tmp_path / "out")])
    error = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(error) == 1 and error[0].startswith("vdw-frames: error:"), error
    assert words in error[0]
    assert not (tmp_path / "out").exists()  # checked before the output folder is made


def test_the_report_refuses_what_is_not_a_design_and_makes_no_folder(tmp_path):
    with pytest.raises(ValueError, match="design must be a FrameDesign or a DampedDesign, got ShearBuilding"):
        write_design_report(ShearBuilding([1.0], [1.0]), tmp_path / "report")
    assert not (tmp_path / "report").exists()


@pytest.mark.slow
def test_records_left_out_of_the_design_are_named_and_the_repeat_is_not_claimed(tmp_path, capsys):
    # A record too short for the building's period range is left out of the design's selection; `vdw-frames verify`
    # with the same set refuses it (scaled_suite's rule), so design.md must not claim that command repeats the
    # verification, and must name what was left out.
    records = tmp_path / "records"
    records.mkdir()
    for motion in [*synthetic_records(12, 20.0), *synthetic_records(1, 3.0)]:
        name = motion.name.replace(" ", "_") + ("_short" if motion.duration < 10.0 else "")
        write_at2(motion, records / f"{name}.AT2")
    site = write_input(tmp_path)
    out = tmp_path / "fvd"
    assert main(["design-building", str(site), "--out", str(out)]) == 0, capsys.readouterr().out
    capsys.readouterr()
    code = main(["verify", str(out / "building.toml"), "--records", str(records), "--out", str(tmp_path / "again")])
    error = capsys.readouterr().err
    assert code == 2 and "too short" in error  # the same set cannot repeat it
    text = (out / "design.md").read_text()
    assert "is repeated, independently, by `vdw-frames verify" not in text
    assert "The final verification left out 1 candidate record(s) too short" in text
    assert "refuses them" in text


def test_a_bare_design_s_p695_result_states_the_spectrum_it_is_measured_against(tmp_path):
    # The ACMR is S_CT / S_MT: its value depends on the P695 seismic design category whose MCE S_MT it divides by
    # (collapse_assessment's default is SDC Dmax, not the design's site), so the report must say which.
    from types import SimpleNamespace

    given = load_design_input(write_input(tmp_path))
    frame = design_frame(given.site, "steel-smf", given.weights, given.story_heights, overstrength=3.0)
    collapse = SimpleNamespace(acmr=1.8, acmr20=1.56, acmr10=1.96, passes_acmr20=True, passes_acmr10=False,
                               sdc="Dmax", smt=1.2 * G, period=0.9)
    write_design_report(frame, tmp_path / "out", collapse=collapse)
    text = (tmp_path / "out" / "design.md").read_text()
    assert "ACMR 1.800 vs ACMR20% 1.560" in text
    assert "SDC Dmax" in text and "S_MT = 1.2 g at T = 0.9 s" in text


def test_a_bare_design_on_a_site_with_s1_at_least_0_6g_is_not_refused(tmp_path, capsys):
    # ASCE 7-16 Sec. 11.4.8 asks for a ground motion hazard analysis on sites with S_1 >= 0.6 g for seismically
    # isolated structures and structures with damping systems only: a bare frame on Site Class C with S_1 = 0.75 g
    # uses the tabulated coefficients (F_v = 1.4) and lands in SDC E (Sec. 11.6), where Eq. 12.8-6 applies.
    site = write_input(tmp_path, s1="0.75")
    code = main(["design-building", str(site), "--device", "none", "--out", str(tmp_path / "out")])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert "SDC E" in captured.out
    # with the devices the same site is refused (the damped case of Sec. 11.4.8)
    code = main(["design-building", str(site), "--out", str(tmp_path / "damped")])
    assert code == 2 and "Sec. 11.4.8" in capsys.readouterr().err


@pytest.mark.parametrize("existing", [False, True])
def test_a_target_below_the_bare_frame_s_damping_leaves_no_folder_behind(folder, tmp_path, capsys, existing):
    # The refusal comes from the sizing, after the output folder is made: a folder this command made is removed
    # again (it is empty); one the user had is left as it was.  The bare frame's mode-1 damping is its 5 %.
    out = tmp_path / "out"
    if existing:
        out.mkdir()
    code = main(["design-building", str(folder / "site.toml"), "--target-damping", "0.02", "--out", str(out)])
    error = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(error) == 1 and "is not above the bare frame's mode-1 damping ratio" in error[0], error
    assert out.exists() == existing
    assert not existing or not any(out.iterdir())


def test_the_device_schedule_states_the_units_of_the_parameters_it_prints():
    """The schedule's descriptions print bare numbers ("FVD C=1000.0, alpha=0.5, K_b=100000.0"): a line under it
    gives their units (before, the note left C's unit, N (s/mm)^alpha, to be guessed)."""
    from vdw_frames import FDMKDamper, FluidViscousDamper, FrictionDamper
    from vdw_frames.design_report import _schedule, device_rows

    building = ShearBuilding([100.0, 100.0], [1e5, 1e5], devices={
        1: [FDMKDamper(0.0, 3.0, 0.3, 2.0, 0.5)], 2: [FluidViscousDamper(1e3, 0.5, 1e5, magnification=0.8),
                                                     FrictionDamper(2e4, 5e4)]})
    lines = _schedule(device_rows(building))
    assert "| 2 | FVD C=1000.0, alpha=0.5, K_b=100000.0, f=0.8 | - | - | - | - | - |" in lines
    assert lines[-2] == ("Units of the devices' parameters: walls G1, G2 MPa, eta1, eta2 MPa s^r, A mm^2, t mm; FVD "
                         "C N (s/mm)^alpha, K_b N/mm; friction F_s N, k N/mm; f the magnification (device deformation "
                         "/ story drift, -); each to 4 significant digits (devices.csv and building.toml hold them "
                         "exactly).")
    rounded = _schedule(device_rows(ShearBuilding([100.0], [1e5], devices={1: [FrictionDamper(12345.678, 5e4)]})))
    assert "| 1 | friction F_s=12350.0, k=50000.0 | - | - | - | - | - |" in rounded  # 4 digits, as stated
