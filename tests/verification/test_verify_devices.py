"""verify with fluid viscous and friction dampers: each bound scales every device's force-defining property by
its lambda, and the device demands are the maxima of the histories of the same analyses, run here one by one
from buildings written out by their constructors."""

import concurrent.futures
import csv
import io

import numpy as np
import pytest
from verification_cases import r1_wall, synthetic_records

from vdw_frames import FluidViscousDamper, FrictionDamper, ShearBuilding, simulate
from vdw_frames.cli import main
from vdw_frames.config import load_building
from vdw_frames.motion import read_at2, write_at2
from vdw_frames.verification import Site
from vdw_frames.verification import report as verification_report
from vdw_frames.verification.verify import PropertyBounds, verify

SITE = Site(1.5, 0.9, 8.0)
FRAME = dict(masses=(100.0, 100.0, 80.0), stiffnesses=(1.2e5, 1.0e5, 0.8e5), damping_ratio=0.03,
             story_heights=(3500.0, 3200.0, 3200.0))


def fvd_frame(factor=1.0):
    """The verification tests' three-story frame with linear FVDs (C x ``factor``; a diagonal one in story 2)
    and a wall in story 3 (its moduli and viscosities x ``factor``)."""
    return ShearBuilding(**FRAME, devices={1: FluidViscousDamper(300.0 * factor, 1.0),
                                           2: FluidViscousDamper(250.0 * factor, 1.0, magnification=0.9),
                                           3: r1_wall(factor)})


def test_each_bound_scales_every_device_s_force_property_and_keeps_the_rest():
    building = ShearBuilding(**FRAME, devices={
        1: [r1_wall(), FluidViscousDamper(500.0, 0.4, stiffness=9e4, magnification=0.8)],
        2: FrictionDamper(3e4, 7e4), 3: [FrictionDamper(2e4, 5e4, magnification=1.2), r1_wall(0.8)]})
    bounds = PropertyBounds(0.7, 1.3)
    for case, factor in (("nominal", 1.0), ("upper", 1.3), ("lower", 0.7)):
        expected = {1: (r1_wall(factor), FluidViscousDamper(500.0 * factor, 0.4, stiffness=9e4, magnification=0.8)),
                    2: (FrictionDamper(3e4 * factor, 7e4),),
                    3: (FrictionDamper(2e4 * factor, 5e4, magnification=1.2), r1_wall(0.8 * factor))}
        bounded = bounds.building(building, case).devices
        assert bounded.keys() == expected.keys()
        for story, devices in expected.items():
            assert len(bounded[story]) == len(devices)
            for got, want in zip(bounded[story], devices, strict=True):
                assert type(got) is type(want)
                for name, value in vars(want).items():
                    if isinstance(value, float):
                        assert getattr(got, name) == pytest.approx(value, rel=1e-14), (case, story, name)
                    else:
                        assert getattr(got, name) == value, (case, story, name)


@pytest.fixture(scope="module")
def verified():
    records = synthetic_records(12, 5.0)
    with concurrent.futures.ThreadPoolExecutor(2) as executor:
        return verify(fvd_frame(), SITE, records, bounds=(0.8, 1.25), executor=executor, progress=False)


def test_device_demands_are_the_maxima_of_the_histories_at_each_bound(verified):
    result = verified
    assert [(d.story, d.device, d.velocity_dependent) for d in result.devices] == [(1, 0, True), (2, 1, True)]
    assert result.devices[1].description == "FVD C=250.0, alpha=1.0, f=0.9"
    records = len(result.suite.motions)
    for c, (case, factor) in enumerate(result.cases):
        building = fvd_frame(factor)  # the bound written out: every C and every wall property times lambda
        peaks = {name: np.zeros((records, 2)) for name in ("force", "deformation", "velocity")}
        for r in range(records):
            history = simulate(building, result.suite.motions[r].scaled(float(result.suite.factors[r])))
            drift = np.abs(history.drift[:, :2]).max(axis=0)
            for name, values in peaks.items():
                values[r] = np.abs(getattr(history, f"device_{name}")).max(axis=0)
            # The device demands mean what they say: the deformation is f x the drift, and a linear dashpot's
            # force is C x its velocity.
            np.testing.assert_allclose(peaks["deformation"][r], [1.0, 0.9] * drift, rtol=1e-12)
            np.testing.assert_allclose(peaks["force"][r], factor * np.array([300.0, 250.0]) * peaks["velocity"][r],
                                       rtol=1e-12)
            for name in peaks:
                np.testing.assert_allclose(result.device_peaks[name][c, r], peaks[name][r], rtol=1e-12)
        for j, demand in enumerate(result.devices):
            for name in peaks:
                assert getattr(demand, name)[case] == pytest.approx(peaks[name][:, j].max(), rel=1e-12)
    # the upper bound (more C) gives larger forces and smaller deformations than the lower bound
    for demand in result.devices:
        assert demand.force["upper"] > demand.force["lower"]
        assert demand.deformation["upper"] < demand.deformation["lower"]


def test_the_report_and_its_table_carry_the_device_demands(verified):
    result = verified
    table = list(csv.reader(io.StringIO(verification_report.devices_csv(result))))
    assert table[0] == ["device", "story", "description", "velocity_dependent", "case", "lambda", "force_N",
                        "deformation_mm", "velocity_mm_s"]
    assert len(table) == 1 + 2 * 3
    assert table[2][:6] == ["1", "1", "FVD C=300.0, alpha=1.0", "1", "upper", "1.25"]
    assert [float(value) for value in table[2][6:]] == [result.devices[0].force["upper"],
                                                        result.devices[0].deformation["upper"],
                                                        result.devices[0].velocity["upper"]]
    text = verification_report.markdown(result, {}, "check")
    assert "| 2 | 2 | FVD C=250.0, alpha=1.0, f=0.9 | lower |" in text
    assert "C and every friction damper's slip force times lambda" in text
    printed = "\n".join(verification_report.device_rows(result))
    assert f"{result.devices[0].force['lower'] / 1e3:9.1f}" in printed
    assert "device 2 (story 2, FVD C=250.0, alpha=1.0, f=0.9)" in result.specification


def test_a_building_with_devices_but_no_walls_is_verified():
    records = synthetic_records(11, 5.0)
    building = ShearBuilding(**FRAME, devices={1: FluidViscousDamper(300.0, 1.0)})
    with concurrent.futures.ThreadPoolExecutor(2) as executor:
        result = verify(building, SITE, records, bounds=(0.8, 1.25), executor=executor, progress=False)
    assert result.walls == () and len(result.devices) == 1
    assert "| upper | 1.25 | - | - |" in verification_report.markdown(result, {}, "check")


FVD_BUILDING = """
masses = [100.0, 100.0, 80.0]
stiffnesses = [1.2e5, 1.0e5, 0.8e5]
story_heights = [3500.0, 3200.0, 3200.0]
damping_ratio = 0.03

[[devices]]
type = "fluid_viscous"
stories = [1]
C = 300.0
alpha = 1.0

[[devices]]
type = "friction"
stories = [2, 3]
slip_force = 4.0e4
stiffness = 6.0e4
"""


def test_the_verify_command_prints_and_writes_the_device_demands(tmp_path, capsys):
    (tmp_path / "building.toml").write_text(FVD_BUILDING)
    folder = tmp_path / "records"
    folder.mkdir()
    for motion in synthetic_records(11, 5.0):
        write_at2(motion, folder / f"{motion.name.replace(' ', '_')}.AT2")
    out = tmp_path / "out"
    code = main(["verify", str(tmp_path / "building.toml"), "--sms", "1.5", "--sm1", "0.9", "--tl", "8",
                 "--bounds", "0.8", "1.25", "--records", str(folder), "--out", str(out)])
    printed = capsys.readouterr().out
    assert code in (0, 1), printed
    records = [read_at2(path) for path in sorted(folder.glob("*.AT2"))]
    with concurrent.futures.ThreadPoolExecutor(2) as executor:
        expected = verify(load_building(tmp_path / "building.toml"), SITE, records, bounds=(0.8, 1.25),
                          executor=executor, progress=False)
    assert "upper bound: lambda 1.25; other devices' C or slip force x lambda" in printed
    for line in verification_report.device_rows(expected):
        assert line in printed
    assert [d.description for d in expected.devices] == ["FVD C=300.0, alpha=1.0", "friction F_s=40000.0, k=60000.0",
                                                         "friction F_s=40000.0, k=60000.0"]
    written = list(csv.reader(io.StringIO((out / "devices.csv").read_text())))
    assert written == list(csv.reader(io.StringIO(verification_report.devices_csv(expected))))
    # a friction damper's force never exceeds its (bounded) slip force
    assert expected.devices[1].force["upper"] <= 1.25 * 4.0e4 * (1 + 1e-12)
    assert expected.devices[1].force["lower"] <= 0.8 * 4.0e4 * (1 + 1e-12)


def test_the_prototype_specification_says_which_period_its_frequency_comes_from_with_other_devices():
    """f1 is 1/T1 of period_range, which leaves the nonlinear FVDs and friction dampers out: the printed line says
    so when the building has such devices (it said "with the walls" only)."""
    from vdw_frames.verification.verify import DeviceDemand, prototype_test_specification

    demand = DeviceDemand(story=1, device=0, description="friction F_s=1e5, k=1e4", velocity_dependent=False,
                          force={"upper": 1e5}, deformation={"upper": 20.0}, velocity={"upper": 300.0})
    text = prototype_test_specification([], 0.8, [demand])
    assert "1/T1 with the walls and linear devices; nonlinear FVDs and friction dampers left out" in text
    assert "force up to 100.0 kN" in text
    assert "(1/T1 with the walls)" in prototype_test_specification([], 0.8)
