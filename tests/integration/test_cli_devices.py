"""The command line with fluid viscous and friction dampers beside the walls: the story table names each
device on its story, the device table prints the peaks of the package's own histories, and each device's loop
is drawn (the loop's data checked against the histories, not only that a file exists)."""

from __future__ import annotations

import dataclasses

import matplotlib.axes
import numpy as np
import pytest
from builders import MIXED_DEVICES_TOML, tapered_pulse, write_file

from vdw_frames import FluidViscousDamper, ShearBuilding, cli, simulate
from vdw_frames.config import load_building
from vdw_frames.motion import default_record_path, read_at2
from vdw_frames.plotting import plot_device_loops
from vdw_frames.plotting.devices import MAX_PANELS, distinct_devices, largest_devices


@pytest.mark.filterwarnings("ignore:wall peak strain outside the range")  # the shipped record strains it 105 %
def test_simulate_names_every_device_and_prints_their_peaks(tmp_path, capsys):
    path = write_file(tmp_path, "mixed.toml", MIXED_DEVICES_TOML)
    code = cli.main(["simulate", str(path), "--record", str(default_record_path()), "--out", str(tmp_path)])
    assert code == 0
    out = capsys.readouterr().out
    assert "1 FDMK walls, 4 other devices" in out
    lines = out.splitlines()
    listing = lines.index("devices per story (in parallel; their total force in the story table's devices kN):")
    assert lines[listing + 1:listing + 5] == ["    1  1 x FDMKDamper A=0.3 m^2, t=20 mm",
                                              "    2  1 x FVD C=150.0, alpha=1.0",
                                              "    3  1 x FVD C=1500.0, alpha=0.5, K_b=80000.0, f=0.8",
                                              "    4  2 x friction F_s=20000.0, k=60000.0"]
    expected = simulate(load_building(path), read_at2(default_record_path()))
    rows = [line.split(None, 5) for line in lines[listing + 6:listing + 10]]
    for j, row in enumerate(rows):
        assert int(row[0]) == j + 1 and int(row[1]) == [2, 3, 4, 4][j]
        assert float(row[2]) == pytest.approx(np.abs(expected.device_force[:, j]).max() / 1e3, abs=0.051)
        assert float(row[3]) == pytest.approx(np.abs(expected.device_deformation[:, j]).max(), abs=0.0051)
        assert float(row[4]) == pytest.approx(np.abs(expected.device_velocity[:, j]).max(), abs=0.051)
    # the story table's device force of story 3 is f x the FVD's force (magnification 0.8), of story 4 two slip forces
    heading = next(i for i, line in enumerate(lines) if "devices kN" in line)  # the story table's heading
    table = {int(line.split()[0]): line.split() for line in lines[heading + 1:heading + 5]}
    assert float(table[3][6]) == pytest.approx(0.8 * np.abs(expected.device_force[:, 1]).max() / 1e3, abs=0.06)
    assert float(table[4][6]) == pytest.approx(2 * 20.0, abs=0.051)
    assert table[2][7] == "-"  # no wall: no strain
    energy = expected.energy
    share = (energy.device_heat[-1] + energy.device_stored[-1]) / energy.input[-1]
    assert f"other devices (work done on them) {round(100 * share)} %" in out
    assert (tmp_path / "device_loops.png").stat().st_size > 10_000


def test_the_device_loops_are_the_histories(tmp_path, monkeypatch):
    building = load_building(write_file(tmp_path, "mixed.toml", MIXED_DEVICES_TOML))
    result = simulate(building, tapered_pulse())
    assert distinct_devices(result) == [1, 2, 3]  # the two equal friction dampers of story 4 are one loop
    drawn = []
    original = matplotlib.axes.Axes.plot

    def record(self, *args, **kwargs):
        if len(args) >= 2:
            drawn.append((np.asarray(args[0]), np.asarray(args[1])))
        return original(self, *args, **kwargs)

    monkeypatch.setattr(matplotlib.axes.Axes, "plot", record)
    path = plot_device_loops(result, tmp_path / "loops", title="pulse")
    assert path.name == "loops.png" and path.stat().st_size > 10_000
    assert len(drawn) == 3
    for (x, y), j in zip(drawn, (0, 1, 2), strict=True):
        np.testing.assert_array_equal(x, result.device_deformation[:, j])
        np.testing.assert_array_equal(y, result.device_force[:, j] / 1e3)


def test_device_loops_are_bounded_and_checked(tmp_path):
    many = ShearBuilding([100.0] * 2, [1e5] * 2, devices={
        1: [FluidViscousDamper(10.0 + k, 1.0) for k in range(10)], 2: [FluidViscousDamper(50.0 + k, 1.0)
                                                                      for k in range(5)]})
    result = simulate(many, dataclasses.replace(tapered_pulse(), acceleration=tapered_pulse().acceleration[:200]))
    assert len(distinct_devices(result)) == 15
    with pytest.raises(ValueError, match=f"15 devices asked for: one figure draws at most {MAX_PANELS}"):
        plot_device_loops(result, tmp_path)
    chosen = largest_devices(result)
    peaks = np.abs(result.device_force).max(axis=0)
    assert len(chosen) == MAX_PANELS and set(chosen) == set(np.argsort(-peaks)[:MAX_PANELS] + 1)
    assert plot_device_loops(result, tmp_path, chosen).name == "device_loops.png"
    for bad in (0, 16, 1.5, "1"):
        with pytest.raises(ValueError, match=r"device numbers in 1 \.\.\. 15"):
            plot_device_loops(result, tmp_path, [bad])
    with pytest.raises(ValueError, match="no device other than walls"):
        plot_device_loops(simulate(ShearBuilding([100.0], [1e5]), tapered_pulse()), tmp_path)


NONLINEAR_DEVICES_TOML = """masses = [200.0, 200.0]
stiffnesses = [2.0e5, 1.8e5]
story_heights = [3500.0, 3500.0]
[[devices]]
type = "fluid_viscous"
C = 2.0e4
alpha = 0.5
stiffness = 2.0e5
[[devices]]
type = "friction"
slip_force = 1.0e5
stiffness = 5.0e4
stories = [2]
"""


def test_design_states_the_amplitude_its_modal_table_of_nonlinear_devices_holds_at(tmp_path, capsys):
    """The modal table of a building of nonlinear FVDs and friction dampers depends on --drift-amplitude: the
    output says at which amplitude each device is linearised, and its columns are the devices', not "walls"
    (it printed "T walls s" and "the walls' own share" for a building with no wall, and no amplitude)."""
    from vdw_frames import modal_analysis

    path = write_file(tmp_path, "nonlinear.toml", NONLINEAR_DEVICES_TOML)
    assert cli.main(["design", str(path), "--drift-amplitude", "20", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "T walls" not in out and "walls' own share" not in out
    assert "0 walls, 3 other devices" in out
    assert "equivalent linearisation (the periods and damping ratios above hold at these amplitudes only):" in out
    assert "story 2: friction F_s=100000.0, k=50000.0 linearised at story drift amplitude 20 mm (device 20 mm)" in out
    row = next(line for line in out.splitlines() if line.split()[:1] == ["1"]).split()
    expected = modal_analysis(load_building(path), drift_amplitude=20.0)
    assert float(row[4]) == pytest.approx(100 * expected.damping_ratios[0], abs=0.0051)


@pytest.mark.slow
def test_design_sizes_walls_beside_a_friction_damper_at_the_drift_amplitude(tmp_path, capsys, monkeypatch):
    """design --target on a building of walls and a friction damper: the walls are sized with the damper
    linearised at --drift-amplitude, and the output says so (it stopped with "give drift_amplitude", an argument
    that size_walls and damping_curve did not take).  Reference: the sized walls' damping ratio by
    modal_analysis at that amplitude (tests/design/test_sizing.py checks size_walls against state-space
    eigenvalues); without --drift-amplitude, one error line that names the flag."""
    from vdw_frames import modal_analysis, size_walls

    text = ('masses = [100, 100, 100, 100]\nstiffnesses = [2e5, 2e5, 2e5, 2e5]\ndamping_ratio = 0.02\n'
            '[[walls]]\nstories = "all"\nparameters = {G1 = 0.0, G2 = 3.0, eta1 = 0.3, eta2 = 2.0, r = 0.5}\n'
            'area = 2.0e5\nthickness = 10.0\n'
            '[[devices]]\ntype = "friction"\nstories = [2]\nslip_force = 2.0e4\nstiffness = 2.0e5\n')
    path = write_file(tmp_path, "walls_and_friction.toml", text)
    assert cli.main(["design", str(path), "--target", "0.2", "--out", str(tmp_path)]) == 2
    assert capsys.readouterr().err == (f"vdw-frames: error: {path}: story 2's friction F_s=20000.0, k=200000.0 "
                                       "depends on its amplitude: give --drift-amplitude (mm, the story drift "
                                       "amplitude it is linearised at)\n")
    import vdw_frames.plotting

    titles = []
    drawn = vdw_frames.plotting.plot_damping_curve
    monkeypatch.setattr(vdw_frames.plotting, "plot_damping_curve",
                        lambda *a, **k: titles.append(k.get("title")) or drawn(*a, **k))
    assert cli.main(["design", str(path), "--target", "0.2", "--drift-amplitude", "10", "--modes", "1",
                     "--out", str(tmp_path)]) == 0
    assert titles == ["walls_and_friction.toml: mode 1 against the wall size\n(other devices linearised at story "
                      "drift amplitude 10 mm)"]
    out = capsys.readouterr().out
    assert ("the other devices kept as they are, linearised at story drift amplitude 10 mm (--drift-amplitude): the "
            "damping ratios and sizes below hold at that amplitude only") in out
    building = load_building(path)
    sized = size_walls(building, None, 0.2, distribution="existing", drift_amplitude=10.0)
    result = modal_analysis(sized, 1, drift_amplitude=10.0)
    assert result.damping_ratios[0] == pytest.approx(0.2, abs=1e-6)
    factor = sized.walls[1][0].area / building.walls[1][0].area
    assert f"target 20 %: the file's walls, every area x {factor:.3f}" in out
    assert f"xi = 20.00 %, T = {result.periods[0]:.3f} s" in out
