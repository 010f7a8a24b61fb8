"""Issue 11's defects and usability problems, one test (or more) each, against independent references
where a value is computed (analytic formulas, scipy, the paper's data, the text written).

Reader fuzzing lives in test_readers_fuzz.py, the README in test_readme.py, the installed wheel and the
numba cache fallback in test_install.py.
"""

from __future__ import annotations

import concurrent.futures
import gzip
import json
import math
import os
import re
import runpy
import stat
import tracemalloc
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from reference import tapered_sine
from scipy import optimize, signal
from shared_data import REPO

import vdw_frames as vdw
from vdw_frames import (
    FDMKDamper,
    GroundMotion,
    ShearBuilding,
    cli,
    paper,
    read_at2,
    read_two_column,
    run_batch,
    simulate,
    sine_test,
)
from vdw_frames.config import building_from_dict, load_building
from vdw_frames.element import WallState
from vdw_frames.motion import G, default_record, default_record_path, write_at2
from vdw_frames.plotting import plot_loops

WALL = dict(G1=0.0, G2=3.0, eta1=0.3, eta2=2.0, r=0.5)
VALUES_G = [0.1, -0.25, 0.3125, 0.0, -0.5, 0.125, 0.0625]


def write(tmp_path, name: str, data) -> Path:
    path = tmp_path / name
    path.write_bytes(data.encode("ascii") if isinstance(data, str) else data)
    return path


def at2(count_line: str, rows: list[str], header=("PEER STRONG MOTION DATABASE RECORD.",
                                                     "IMPERIAL VALLEY 10/15/79 2316, EL CENTRO ARRAY #6, 230",
                                                     "ACCELEROGRAM IN G.  FILTER POINTS:  HP=0.1 Hz LP=40.0 Hz")) -> str:
    return "\n".join([*header, count_line, *rows]) + "\n"


def sdof_complex_modulus(params, f):
    """G* of eqs. (3)-(5), written out here for the references."""
    s_r = (2j * np.pi * np.asarray(f, dtype=float)) ** params["r"]
    maxwell = params["G2"] * params["eta2"] * s_r / (params["G2"] + params["eta2"] * s_r)
    return params["G1"] + params["eta1"] * s_r + maxwell


# ------------------------------------------------------------------------------------------------ 1
@pytest.mark.parametrize("count_line, dt", [
    ("    7   0.01000    NPTS, DT", 0.01),      # legacy PEER, FEMA P695
    ("7 0.0050 NPTS, DT", 0.005),                # NGA-West1
    ("   7,  .0050,  NPTS, DT", 0.005),
    ("NPTS=      7, DT=   .0050 SEC", 0.005),    # still: NGA-West2
])
def test_defect1_legacy_count_line(tmp_path, count_line, dt):
    rows = [" ".join(f"{v:.7E}" for v in VALUES_G[:5]), " ".join(f"{v:.7E}" for v in VALUES_G[5:])]
    motion = read_at2(write(tmp_path, "legacy.AT2", at2(count_line, rows)))
    np.testing.assert_array_equal(motion.acceleration, np.array(VALUES_G) * G)
    assert motion.dt == dt


def test_defect1_messages_and_dt_only_from_the_count_line(tmp_path):
    rows = [" ".join(str(v) for v in VALUES_G)]
    with pytest.raises(ValueError, match=r"missing NPTS \(no 'NPTS= n, DT= dt' line and no legacy 'n dt NPTS, DT'"):
        read_at2(write(tmp_path, "none.AT2", at2("7 points at 0.01 s", rows)))
    decoy = at2("NPTS= 7", rows, header=("RECORDED AT DT= 0.005 SEC", "STATION"))
    with pytest.raises(ValueError, match=r"missing DT \(no 'DT=' on the NPTS line, line 3\)"):
        read_at2(write(tmp_path, "decoy.AT2", decoy))
    decoy = at2("NPTS= 7, DT= 0.02", rows, header=("RECORDED AT DT= 0.005 SEC", "STATION"))
    assert read_at2(write(tmp_path, "decoy2.AT2", decoy)).dt == 0.02


# ------------------------------------------------------------------------------------------------ 2
def pulse(name="pulse"):
    t = np.arange(601) * 0.01
    return GroundMotion(tapered_sine(t, 1.5, 2000.0, 1.0, 6.0), 0.01, name)


def test_defect2_thread_batch_delivers_every_warning_and_leaves_the_filters_alone(monkeypatch):
    bounded = FDMKDamper(**WALL, area=2.0e5, strain_range=(50.0, 60.0))  # every run stays below 5000 %
    frame = ShearBuilding([300.0], [2e5], walls={1: bounded})
    scales = np.linspace(0.5, 2.0, 16)
    shown = []

    def record(message, category, *args, **kwargs):
        shown.append((category, str(message)))

    monkeypatch.setattr(warnings, "showwarning", record)
    filters = list(warnings.filters)
    with concurrent.futures.ThreadPoolExecutor(8) as pool:
        result = run_batch(frame, [pulse()], scales, executor=pool, progress=False)
    assert warnings.filters == filters and warnings.showwarning is record
    strain = [message for category, message in shown if "wall peak strain" in message]
    assert len(strain) == 16
    for s, scale in enumerate(scales):
        peak = 100 * result.peak_drift[0, s, 0] / bounded.thickness  # the batch's own peak, as a strain
        assert f"pulse x {scale:g}: wall peak strain outside the range its parameters were identified for: " \
               f"story 1: {peak:.0f} % (range 5000-6000 %)" in strain
    warnings.warn("a later warning", UserWarning)
    assert shown[-1] == (UserWarning, "a later warning")


def test_defect2_simulate_outside_a_batch_still_warns_normally():
    bounded = FDMKDamper(**WALL, area=2.0e5, strain_range=(50.0, 60.0))
    with pytest.warns(UserWarning, match="wall peak strain outside"):
        simulate(ShearBuilding([300.0], [2e5], walls={1: bounded}), pulse())


def test_run_batch_reports_the_failing_run_by_motion_and_scale():
    frame = ShearBuilding([300.0], [2e5], walls={1: FDMKDamper(**WALL)})
    with concurrent.futures.ThreadPoolExecutor(2) as pool, \
            pytest.raises(ValueError, match=r"the analysis of quake x 1e\+200 failed: .*overflowed"):
        run_batch(frame, [pulse("quake")], [1.0, 1e200], executor=pool, progress=False)


# ------------------------------------------------------------------------------------------------ 3
def test_defect3_write_at2_non_ascii_name_over_an_existing_file(tmp_path):
    path = write(tmp_path, "record.AT2", "OLD")
    motion = GroundMotion(np.array(VALUES_G) * G, 0.01, "Tōhoku")
    assert write_at2(motion, path) == path
    assert path.read_text(encoding="utf-8").splitlines()[0] == "GROUND MOTION Tōhoku"
    back = read_at2(path)
    np.testing.assert_allclose(back.acceleration, motion.acceleration, rtol=5e-8)
    assert list(tmp_path.iterdir()) == [path]


def test_defect3_a_refused_or_failed_write_never_destroys_the_target(tmp_path, monkeypatch):
    path = write(tmp_path, "record.AT2", "OLD CONTENT")
    for name in ("quake NPTS= 5, DT= 0.1", "two\nlines"):
        with pytest.raises(ValueError, match="rename the record"):
            write_at2(GroundMotion([1.0, 2.0], 0.01, name), path)
        assert path.read_bytes() == b"OLD CONTENT"
    with pytest.raises(ValueError, match="header line '12 0.01 NPTS, DT' would be read as the NPTS/DT line"):
        write_at2(GroundMotion([1.0, 2.0], 0.01, "x"), path, header=["12 0.01 NPTS, DT"])
    assert path.read_bytes() == b"OLD CONTENT"

    def fail(source, target):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "replace", fail)
    with pytest.raises(ValueError, match="record.AT2: cannot write .No space left on device"):
        write_at2(GroundMotion([1.0, 2.0], 0.01, "x"), path)
    assert path.read_bytes() == b"OLD CONTENT" and list(tmp_path.iterdir()) == [path]


def test_defect3_write_at2_keeps_permissions_and_links(tmp_path):
    motion = GroundMotion([1.0, 2.0, 3.0], 0.01, "x")
    kept = write(tmp_path, "kept.AT2", "OLD")
    kept.chmod(0o640)
    write_at2(motion, kept)
    assert stat.S_IMODE(kept.stat().st_mode) == 0o640
    umask = os.umask(0)
    os.umask(umask)
    fresh = write_at2(motion, tmp_path / "fresh.AT2")
    assert stat.S_IMODE(fresh.stat().st_mode) == 0o666 & ~umask
    link = tmp_path / "link.AT2"
    link.symlink_to(kept)
    write_at2(GroundMotion([4.0, 5.0], 0.02, "y"), link)
    assert link.is_symlink() and read_at2(kept).dt == 0.02
    for bad, match in ((tmp_path, "is a folder"), (tmp_path / "missing" / "x.AT2", "does not exist"),
                       ("", "must be a path"), (None, "must be a path")):
        with pytest.raises(ValueError, match=match):
            write_at2(motion, bad)


# ------------------------------------------------------------------------------------------------ 4
def test_defect4_response_spectrum_period_range():
    motion = default_record()
    for period in (1e-160, 1e300, -0.0 + 1e-9):
        with pytest.raises(ValueError, match=re.escape(f"period {period!r} s is outside the range")):
            motion.spectrum(period)
    # The ends of the accepted range (1e-6 and 1e5 record steps) against scipy's exact linear simulation.
    rigid, longest = 1e-6 * motion.dt, 1e5 * motion.dt
    assert float(motion.spectrum(rigid)) == pytest.approx(motion.pga, rel=1e-8)
    omega = 2 * np.pi / longest
    system = signal.StateSpace([[0, 1], [-omega**2, -2 * 0.05 * omega]], [[0], [-1]], [[1, 0]], [[0]])
    _, u, _ = signal.lsim(system, motion.acceleration, motion.time)
    assert float(motion.spectrum(longest)) == pytest.approx(omega**2 * np.abs(u).max(), rel=1e-6)
    assert float(motion.spectrum(0.0)) == motion.pga


# ------------------------------------------------------------------------------------------------ 5, 12
def valid_spec():
    return {"masses": [300.0, 300.0, 250.0], "stiffnesses": [2e5, 1.8e5, 1.5e5], "story_heights": [3500.0] * 3,
            "walls": [{"stories": [1, 2], "per_story": 2, "parameters": dict(WALL)},
                      {"stories": "all", "parameters": "fitted-300", "area": 5e5}]}


def test_defect5_malformed_building_file_is_one_error_line(tmp_path, capsys):
    spec = valid_spec()
    spec["walls"][0]["stories"] = [[1]]
    path = write(tmp_path, "nested.json", json.dumps(spec))
    assert cli.main(["simulate", str(path), "--record", str(default_record_path())]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and error.startswith("vdw-frames: error: ")
    assert "nested.json: walls stories must be story numbers in 1 ... 3, got [1] in [[1]]" in error


def test_defect12_story_numbers_are_whole_numbers_once_each():
    spec = valid_spec()
    spec["walls"] = [{"stories": [1, 1.0], "parameters": dict(WALL)}]
    with pytest.raises(ValueError, match=r"distinct story numbers, got \[1, 1.0\]"):
        building_from_dict(spec)
    spec["walls"] = [{"stories": [1.0], "parameters": dict(WALL)}]
    as_float = building_from_dict(spec)
    spec["walls"] = [{"stories": [1], "parameters": dict(WALL)}]
    assert as_float.wall_list == building_from_dict(spec).wall_list == [(1, FDMKDamper(**WALL))]
    spec["walls"] = [{"stories": [1], "per_story": 10**18, "parameters": dict(WALL)}]
    with pytest.raises(ValueError, match="per_story must be at most 1000, got 1000000000000000000"):
        building_from_dict(spec)  # refused, not a list of 10^18 walls
    for stories in ([1.5], [True], ["1"], [0], [4], {"1": 1}, 1):
        spec["walls"] = [{"stories": stories, "parameters": dict(WALL)}]
        with pytest.raises(ValueError, match="stor"):
            building_from_dict(spec)


json_values = st.recursive(st.none() | st.booleans() | st.floats() | st.integers() | st.text(max_size=5),
                           lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=5), inner,
                                                                                         max_size=3), max_leaves=8)


def replace_somewhere(spec, path, value):
    """``spec`` with the item at ``path`` (keys/indices, followed as far as they go) replaced by ``value``."""
    node = spec
    for step in path[:-1]:
        items = list(node) if isinstance(node, dict) else range(len(node)) if isinstance(node, list) else []
        if not items or not isinstance(node[items[step % len(items)]], (dict, list)):
            break
        node = node[items[step % len(items)]]
    items = list(node) if isinstance(node, dict) else list(range(len(node)))
    if items:
        node[items[path[-1] % len(items)]] = value
    return spec


@settings(max_examples=300, deadline=None)
@given(path=st.lists(st.integers(0, 10), min_size=1, max_size=4), value=json_values)
def test_defect5_any_malformed_building_is_a_value_error(path, value):
    spec = replace_somewhere(valid_spec(), path, value)
    try:
        building = building_from_dict(spec)
    except ValueError:
        return
    assert isinstance(building, ShearBuilding)


@settings(max_examples=100, deadline=None)
@given(text=st.one_of(json_values.map(json.dumps), st.text(max_size=40)), suffix=st.sampled_from([".json", ".toml"]))
def test_defect5_any_building_file_text_is_a_value_error_or_a_building(tmp_path_factory, text, suffix):
    path = tmp_path_factory.mktemp("building") / f"b{suffix}"
    path.write_text(text, encoding="utf-8")
    try:
        assert isinstance(load_building(path), ShearBuilding)
    except ValueError as error:
        assert str(error).startswith(str(path))


# ------------------------------------------------------------------------------------------------ 6
@pytest.mark.parametrize("free", ["G1", "G2", "eta1", "eta2", "r", None])
def test_defect6_identify_with_four_or_five_parameters_fixed(free):
    f, storage, loss = paper.data.table_moduli(300)
    start = paper.fitted(300)
    params = {name: getattr(start, name) for name in ("G1", "G2", "eta1", "eta2", "r")}
    params["G1"] = 0.4  # off the fitted optimum, so the free parameter has something to do

    def objective(x):
        trial = dict(params, **({free: x} if free else {}))
        g = sdof_complex_modulus(trial, f)
        return float(np.sum(((g.real - storage) / storage) ** 2 + ((g.imag - loss) / loss) ** 2))

    fixed = {name: value for name, value in params.items() if name != free}
    result = vdw.identify(f, storage, loss, residual="relative", fixed=fixed)
    assert {name: result.params[name] for name in fixed} == fixed
    if free is None:
        assert result.sse == pytest.approx(objective(None), rel=1e-12)
        return
    # Independent 1-D global search: a dense grid, then scipy's bounded Brent around its best point.
    upper = 1.0 if free == "r" else 20.0 * max(params[free], 1.0)
    grid = np.linspace(1e-3 if free == "r" else 0.0, upper, 4001)
    best = grid[np.argmin([objective(x) for x in grid])]
    step = grid[1] - grid[0]
    polished = optimize.minimize_scalar(objective, bounds=(max(best - step, grid[0]), min(best + step, upper)),
                                        method="bounded", options={"xatol": 1e-12})
    reference = min(objective(best), polished.fun)
    assert result.sse <= reference * (1 + 1e-9)
    assert result.sse == pytest.approx(reference, rel=1e-6)


# ------------------------------------------------------------------------------------------------ 7, 8
def test_defect7_stationary_response_arguments():
    frame = ShearBuilding([100.0, 100.0], [4e4, 4e4])
    ground = np.ones(16)
    for dt, pad, match in [(0.0, 8, "dt must be > 0, got 0.0"), (-0.01, 8, "dt must be > 0, got -0.01"),
                           (0.01, 0, "pad_factor must be a whole number >= 1, got 0"),
                           (0.01, 1.5, "pad_factor must be a whole number >= 1, got 1.5"),
                           (0.01, True, "pad_factor must be a whole number >= 1, got True"),
                           (0.01, 10**12, r"needs 16,000,000,000,000 steps, whose arrays would take .* TiB")]:
        with pytest.raises(ValueError, match=match):
            frame.stationary_response(ground, dt, pad)
    assert frame.stationary_response(ground, 0.01, np.int64(2)).shape == (16, 2)


def test_defect8_frequency_response_against_the_closed_form():
    mass, stiffness = 100.0, 4e4
    wall = FDMKDamper(**WALL, area=2e4)
    frame = ShearBuilding([mass], [stiffness], damping_ratio=0.02, walls={1: wall})
    f = np.linspace(0.0, 40.0, 5000)  # more than one chunk of the batched solve
    a0, a1 = frame.rayleigh_coefficients
    omega = 2 * np.pi * f
    wall_stiffness = sdof_complex_modulus(WALL, np.where(f > 0, f, 1.0)) * wall.area / wall.thickness
    wall_stiffness[f == 0] = WALL["G1"] * wall.area / wall.thickness
    expected = -mass / (stiffness + wall_stiffness - mass * omega**2 + 1j * omega * (a0 * mass + a1 * stiffness))
    np.testing.assert_allclose(frame.frequency_response(f)[:, 0], expected, rtol=1e-12)


def test_defect8_frequency_response_bad_cases():
    undamped = ShearBuilding([1.0], [(2 * np.pi) ** 2], damping_ratio=0.0)  # f_n = 1 Hz exactly
    with pytest.raises(ValueError, match=r"no bounded steady response at f = 1.0 Hz"):
        undamped.frequency_response([0.5, 1.0])
    assert undamped.frequency_response(0.5)[0, 0] == pytest.approx(-1.0 / ((2 * np.pi) ** 2 * 0.75), rel=1e-12)
    frame = ShearBuilding([100.0, 100.0], [4e4, 4e4])
    with pytest.raises(ValueError, match=r"scalar or 1-dimensional, got shape \(1, 2\)"):
        frame.frequency_response([[1.0, 2.0]])
    with pytest.raises(ValueError, match=r"overflows at f = 1e\+200 Hz"):
        frame.frequency_response([1.0, 1e200])
    with pytest.raises(ValueError, match=r"frequency must be >= 0 Hz, got -1.0"):
        frame.frequency_response(np.array([1.0, -1.0]))


# ------------------------------------------------------------------------------------------------ 9
def test_defect9_damper_results_are_checked():
    damper = FDMKDamper(**WALL)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no RuntimeWarning may stand in for an error
        with pytest.raises(ValueError, match="s must be finite, got"):
            damper.transfer(np.nan)
        with pytest.raises(ValueError, match=r"overflowed \(inf or NaN\) at f = 1e\+308 Hz"):
            damper.complex_modulus([1.0, 1e308])
        with pytest.raises(ValueError, match=r"K\*\(f\) overflowed \(inf or NaN\) at f = 1.0 Hz for G1 = 1e\+308"):
            FDMKDamper(**dict(WALL, G1=1e308)).storage_stiffness(1.0)
        with pytest.raises(ValueError, match=r"loss factor is unbounded at f = 1e-320 Hz"):
            FDMKDamper(**dict(WALL, r=1.0)).loss_factor(1e-320)
        with pytest.raises(ValueError, match=r"unbounded at f = 0.5 Hz"):
            FDMKDamper(G1=0.0, G2=0.0, eta1=1.0, eta2=0.0, r=1.0).loss_factor([0.5, 1.0])  # a pure dashpot
        # Limits that are finite stay finite: G* -> (eta1 + eta2)(i w)^r as w -> 0 (loss factor tan(r pi/2)),
        # and the Maxwell branch -> G2 + eta1 (i w)^r as w -> infinity.
        assert float(damper.loss_factor(1e-320)) == pytest.approx(math.tan(0.5 * math.pi / 2), rel=1e-9)
        huge = complex(damper.complex_modulus(1e300))
        s_r = (2j * math.pi * 1e300) ** 0.5
        assert huge == pytest.approx(WALL["G2"] + WALL["eta1"] * s_r, rel=1e-12)
        assert damper.damping_coefficient(1.0) == pytest.approx(
            sdof_complex_modulus(WALL, 1.0).imag * 1e5 / (2 * math.pi), rel=1e-12)


# ------------------------------------------------------------------------------------------------ 10
def test_defect10_value_errors_that_name_the_value():
    damper = FDMKDamper(**WALL)
    frame = ShearBuilding([300.0], [2e5], walls={1: damper})
    motion = pulse()
    cases = [
        (lambda: WallState("x", 0.01), "a wall must be an FDMKDamper or a SupportedDamper, got str"),
        (lambda: run_batch(frame, motion, [1]), "got one GroundMotion .'pulse'.; pass \\[motion\\]"),
        (lambda: run_batch(frame, [motion, 3], [1]), "got int 3"),
        (lambda: run_batch(frame, [motion], [1], executor="x"), "executor must be a concurrent.futures.Executor"),
        (lambda: run_batch(frame, [motion], [1], method="x"), "method must be one of"),
        (lambda: sine_test(damper, 1e300, 1), r"overflowed .* amplitude = 1e\+300 mm"),
        (lambda: simulate(frame, GroundMotion([0.0, 1.0, 0.0], 1e-300)), r"dt = 1e-300 s is outside the range"),
        (lambda: simulate(frame, GroundMotion([0.0, 1.0, 0.0], 1e300)), r"dt = 1e\+300 s is outside the range"),
        (lambda: simulate(frame.without_walls(), motion, method="x"), "method must be one of .*got 'x'"),
        (lambda: simulate(frame.without_walls(), motion, memory="x"), "memory must be one of .*got 'x'"),
    ]
    for call, match in cases:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            with pytest.raises(ValueError, match=match):
                call()


# ------------------------------------------------------------------------------------------------ 11
def test_defect11_plot_paths(tmp_path):
    result = sine_test(FDMKDamper(**WALL), 10.0, 1.0, cycles=2)
    path = plot_loops(result, tmp_path / "dir" / "loops")
    assert path == tmp_path / "dir" / "loops.png" and path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    folder = tmp_path / "figures"
    folder.mkdir()
    path = plot_loops(result, folder)
    assert path == folder / "loops.png" and path.is_file()
    assert not (tmp_path / "figures.png").exists()
    path = plot_loops(result, str(tmp_path / "new") + os.sep)
    assert path == tmp_path / "new" / "loops.png" and path.is_file()
    path = plot_loops(result, tmp_path / "loops.pdf")
    assert path.read_bytes()[:5] == b"%PDF-"
    (tmp_path / "file").write_text("x")
    with pytest.raises(ValueError, match="cannot create the folder"):
        plot_loops(result, tmp_path / "file" / "loops.png")


# ------------------------------------------------------------------------------------------------ readers
def test_readers_fortran_numbers(tmp_path):
    rows = ["  .1000D+00 -.2500D+00  .3125D+00  .0000D+00-.5000D+00", " 1.25D-01-6.25D-02"]
    motion = read_at2(write(tmp_path, "fortran.AT2", at2("    7   0.01000    NPTS, DT", rows)))
    np.testing.assert_array_equal(motion.acceleration, np.array([0.1, -0.25, 0.3125, 0.0, -0.5, 0.125, -0.0625]) * G)
    text = "0.00 1.0D-03\n0.01-.39E-02\n0.02 -.33E-02\n"
    motion = read_two_column(write(tmp_path, "fortran.txt", text), unit="m/s2")
    np.testing.assert_array_equal(motion.acceleration, np.array([1.0e-3, -0.39e-2, -0.33e-2]) * 1000.0)
    for token in ("1.0-2", "12.34512.345", "-.39E-02.33E-02x"):  # no unique reading: refused, not guessed
        with pytest.raises(ValueError, match=f"non-numeric value '{re.escape(token)}' on line 5"):
            read_at2(write(tmp_path, "ambiguous.AT2", at2("NPTS= 2, DT= 0.01", [f"0.1 {token}"])))


def test_readers_say_what_a_file_is(tmp_path):
    good = at2("NPTS= 7, DT= 0.01", [" ".join(map(str, VALUES_G))])
    cases = [
        (gzip.compress(good.encode()), "a gzip-compressed file; decompress it first"),
        (good.encode("utf-16"), "UTF-16 text; save it as UTF-8 or ASCII"),
        (good.encode("utf-16-le"), "UTF-16 text"),
        (b"PK\x03\x04" + b"\x00" * 20, "a zip archive"),
        (b"NPTS= 7\x00\x01", "binary data"),
    ]
    for data, match in cases:
        for reader in (read_at2, read_two_column):
            path = write(tmp_path, "odd.AT2", data)
            with pytest.raises(ValueError, match=re.escape(str(path)) + ": " + match):
                reader(path)
    for bad, match in ((tmp_path, "is a folder, not a"), (tmp_path / "missing.AT2", "missing.AT2: no such"),
                       ("", "must be a path, got ''"), (None, "must be a path .* got None")):
        for reader in (read_at2, read_two_column, load_building):
            with pytest.raises(ValueError, match=match):
                reader(bad)


def test_readers_bom_padding_ctrl_z_and_float32_times(tmp_path):
    rows = [" ".join(f"{v:.4f}" for v in VALUES_G[:5]), " ".join(f"{v:.4f}" for v in VALUES_G[5:] + [0.0, 0.0, 0.0])]
    text = "\ufeff" + at2("NPTS= 7, DT= 0.01", rows).replace("\n", "\r\n") + "\x1a"
    motion = read_at2(write(tmp_path, "dos.AT2", text.encode("utf-8")))
    np.testing.assert_array_equal(motion.acceleration, np.array(VALUES_G) * G)
    extra_line = at2("NPTS= 7, DT= 0.01", rows + ["0.0 0.0"])
    with pytest.raises(ValueError, match="too many values: NPTS = 7 on line 4 but 12 values follow"):
        read_at2(write(tmp_path, "extra.AT2", extra_line))  # zeros beyond the last line of values: not padding
    nonzero = at2("NPTS= 6, DT= 0.01", rows)
    with pytest.raises(ValueError, match="too many values"):
        read_at2(write(tmp_path, "nonzero.AT2", nonzero))
    times = np.float32(np.arange(12) * 0.01)
    assert f"{times[10]:.8g}" == "0.099999994" or f"{times[10]:.8g}" == "0.1"
    lines = "".join(f"{t:.8g}, {k}\n" for k, t in enumerate(times))
    motion = read_two_column(write(tmp_path, "float32.csv", ("\ufeff" + lines).encode("utf-8")), unit="mm/s2")
    np.testing.assert_array_equal(motion.acceleration, np.arange(12.0))
    assert motion.dt == pytest.approx(0.01, rel=1e-6)
    with pytest.raises(ValueError, match="non-uniform time step at line 3"):
        read_two_column(write(tmp_path, "uneven.txt", "0 1\n0.01 2\n0.02002 3\n0.03 4\n"))


def test_building_files_bom_and_encoding(tmp_path, capsys):
    spec = json.dumps(valid_spec())
    assert load_building(write(tmp_path, "bom.json", b"\xef\xbb\xbf" + spec.encode())).stories == 3
    toml = "\ufeffmasses = [300.0]\nstiffnesses = [2e5]\n"
    assert load_building(write(tmp_path, "bom.toml", toml.encode("utf-8"))).stiffnesses == (2e5,)
    latin = write(tmp_path, "latin1.toml", "# b\xe2timent\nmasses = [300.0]\nstiffnesses = [2e5]\n".encode("latin-1"))
    assert cli.main(["simulate", str(latin), "--record", str(default_record_path())]) == 2
    assert f"{latin}: not UTF-8 text (byte 0xe2 at position 3); save it as UTF-8" in capsys.readouterr().err


# ------------------------------------------------------------------------------------------------ steps
def test_simulate_accepts_a_float32_step():
    frame = ShearBuilding([300.0, 250.0], [2e5, 1.5e5], walls={1: FDMKDamper(**WALL)})
    motion = pulse()
    for step in (0.01, 0.005):
        single = simulate(frame, motion, dt=np.float32(step))
        double = simulate(frame, motion, dt=step)
        np.testing.assert_array_equal(single.time, double.time)
        np.testing.assert_array_equal(single.displacement, double.displacement)
    np.testing.assert_array_equal(motion.resampled(np.float32(0.005)).acceleration, motion.resampled(0.005).acceleration)


def peak_allocation(call):
    tracemalloc.start()
    try:
        call()
    except ValueError as error:
        message = str(error)
    else:
        message = None
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return message, peak


def test_refuse_before_allocating():
    motion = default_record()
    message, peak = peak_allocation(lambda: motion.resampled(2e-8))
    assert "needs 1,250,000,001 steps, whose arrays would take 27.9 GiB (limit 2 GiB)" in message
    assert peak < 20e6
    building = ten_story_frame()
    message, peak = peak_allocation(lambda: simulate(building, motion, dt=1e-7))
    assert "simulate (dt = 1e-07 s, 10 floors, 6 walls) needs 250,000,001 steps" in message and peak < 20e6
    message, peak = peak_allocation(lambda: sine_test(paper.fitted(300), 30.0, 1.0, cycles=100_000_000))
    assert "sine_test(100,000,000 cycles of 200 steps) needs 20,000,000,001 steps" in message and peak < 20e6
    message, _ = peak_allocation(lambda: vdw.motion.synthetic_ground_motion(duration=1e9))
    assert "needs 100,000,000,001 steps" in message


def ten_story_frame():
    """The README's linear 10-story frame with a half-size 300 % wall in each of the six lower stories."""
    wall = paper.fitted(300, area=0.5e6)
    return ShearBuilding(masses=[600.0] * 9 + [450.0], stiffnesses=[300e3 - 15e3 * k for k in range(10)],
                         walls={story: wall for story in range(1, 7)}, story_heights=[4000.0] + [3500.0] * 9)


def test_realistic_long_runs_are_not_refused():
    building = ten_story_frame()
    motion = default_record()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        long_run = simulate(building, motion, dt=motion.dt / 80)  # 200 001 steps
        coarse = simulate(building, motion)
    assert long_run.time.size == 200_001
    # Finer steps change the linear response only by Newmark's O(dt^2) error.
    assert long_run.peak_drift.max() == pytest.approx(coarse.peak_drift.max(), rel=2e-2)


def test_cli_refuses_before_allocating(tmp_path, capsys):
    building = str(REPO / "examples" / "ten_story.toml")
    assert cli.main(["simulate", building, "--record", str(default_record_path()), "--dt", "1e-7"]) == 2
    assert "needs 250,000,001 steps" in capsys.readouterr().err
    assert cli.main(["sine-test", "--cycles", "100000000", "--out", str(tmp_path)]) == 2
    assert "needs 20,000,000,001 steps, whose arrays would take 1.16 TiB" in capsys.readouterr().err


def test_sine_test_uses_the_nearest_dividing_step():
    damper = FDMKDamper(**WALL)
    result = sine_test(damper, 10.0, 1.0, dt=0.003)
    assert result.requested_dt == 0.003 and result.dt == 1.0 / 333
    assert result.time[333] == pytest.approx(1.0, rel=1e-15)  # a whole period in whole steps
    # Against the frequency domain: after 5 cycles the start-up transient leaves < 0.1 % (element.sine).
    assert result.storage_stiffness == pytest.approx(float(damper.storage_stiffness(1.0)), rel=1e-3)
    assert result.loss_stiffness == pytest.approx(float(damper.loss_stiffness(1.0)), rel=1e-3)
    exact = sine_test(damper, 10.0, 1.0, dt=0.005)
    assert exact.dt == exact.requested_dt == 0.005
    assert sine_test(damper, 10.0, 1.0).requested_dt is None


# ------------------------------------------------------------------------------------------------ numbers
@pytest.mark.parametrize("kind", [int, float, np.int32, np.int64, np.float32, np.float64])
def test_one_rule_for_numbers_accepts_numpy(kind):
    damper = FDMKDamper(G1=kind(0), G2=kind(3), eta1=0.5, eta2=kind(2), r=0.5 if kind in (int, np.int32, np.int64)
                        else kind(0.5), area=kind(100000), thickness=kind(10))
    assert damper == FDMKDamper(G1=0.0, G2=3.0, eta1=0.5, eta2=2.0, r=0.5, area=1e5, thickness=10.0)
    frame = ShearBuilding(np.array([300, 300], dtype=kind), [kind(200000)] * 2, damping_ratio=0.05,
                          damping_modes=np.array([1, 2], dtype=np.int64 if kind in (float, np.float32, np.float64)
                                                  else kind), walls={np.int64(1): damper})
    assert frame.damping_modes == (1, 2) and frame.masses == (300.0, 300.0)
    result = sine_test(damper, kind(10), kind(1), cycles=kind(3))
    assert result.cycles == 3


@pytest.mark.parametrize("call, match", [
    (lambda: FDMKDamper(**dict(WALL, G1="1.0")), "G1 must be a real number, got '1.0'"),
    (lambda: FDMKDamper(**dict(WALL, r=True)), "r must be a real number, got True"),
    (lambda: FDMKDamper(**dict(WALL, area=np.bool_(True))), "area must be a real number, got True"),
    (lambda: ShearBuilding([1.0, True], [1.0, 1.0]), "masses must be real numbers"),
    (lambda: ShearBuilding(["1", "2"], [1.0, 1.0]), "masses must be real numbers"),
    (lambda: ShearBuilding([1.0], [1.0], damping_ratio="0.05"), "damping_ratio must be a real number"),
    (lambda: GroundMotion(np.array([True, False]), 0.01), "acceleration must be real numbers, got an array of dtype bool"),
    (lambda: sine_test(FDMKDamper(**WALL), 10.0, 1.0, cycles=True), "cycles must be a whole number >= 1, got True"),
    (lambda: read_two_column(REPO / "README.md", skip_rows=1.5), "skip_rows must be a whole number >= 0, got 1.5"),
])
def test_one_rule_for_numbers_refuses_bools_and_strings(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_messages_print_plain_numbers():
    motion = GroundMotion([0.0, 1.0, 0.0], 0.02)
    calls = [
        lambda: vdw._validation.positive("dt", np.float64(-0.01)),
        lambda: GroundMotion(np.array([1.0, np.nan]), 0.01),
        lambda: GroundMotion([1.0, 2.0], np.float64(-0.01)),
        lambda: FDMKDamper(**dict(WALL, G1=np.float64(-1.0))),
        lambda: FDMKDamper(**dict(WALL, strain_range=(np.float64(3.0), np.float64(2.0)))),
        lambda: ShearBuilding(np.array([1.0, -1.0]), [1.0, 1.0]),
        lambda: ShearBuilding([1.0], [1.0], damping_ratio=np.float32(1.5)),
        lambda: ShearBuilding([1.0, 1.0], [1.0, 1.0], damping_modes=np.array([1, 5])),
        lambda: ShearBuilding([1.0], [1.0], walls={np.int64(4): FDMKDamper(**WALL)}),
        lambda: ShearBuilding([1.0], [1.0]).frequency_response(np.array([-1.0])),
        lambda: motion.spectrum(np.array([-1.0])),
        lambda: motion.spectrum(np.float64(1e9)),
        lambda: motion.resampled(np.float64(0.015)),
        lambda: FDMKDamper(**WALL).complex_modulus(np.array([np.float64(-2.0)])),
        lambda: vdw.identify(np.array([1.0, -2.0, 3.0]), [1.0, 1.0, 1.0], [1.0, 1.0, 1.0]),
        lambda: sine_test(FDMKDamper(**WALL), np.float64(-1.0), 1.0),
    ]
    for call in calls:
        with pytest.raises(ValueError) as error:
            call()
        assert "np." not in str(error.value) and "float64" not in str(error.value), str(error.value)
        assert re.search(r"-?\d", str(error.value))  # the value itself is named


# ------------------------------------------------------------------------------------------------ CLI
def test_cli_warnings_are_one_plain_line(tmp_path, capsys):
    # A stiff one-story frame: its 300 % wall stays far below the strains it was identified for.
    spec = {"masses": [300.0], "stiffnesses": [2e5], "walls": [{"parameters": "fitted-300"}]}
    building = str(write(tmp_path, "stiff.json", json.dumps(spec)))
    assert cli.main(["simulate", building, "--record", str(default_record_path())]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err and all(line.startswith("warning: wall peak strain outside the range") for line in err)
    assert not any("UserWarning" in line or ".py:" in line for line in err)


def test_cli_scale_is_checked_in_g(capsys):
    building = str(REPO / "examples" / "ten_story.toml")
    assert cli.main(["simulate", building, "--record", str(default_record_path()), "--scale", "-0.4"]) == 2
    assert capsys.readouterr().err == "vdw-frames: error: --scale must be a PGA > 0 in g, got -0.4\n"


def test_cli_prints_dashes_for_values_that_do_not_exist(tmp_path, capsys):
    spec = {"masses": [300.0, 300.0], "stiffnesses": [2e5, 1.5e5], "walls": [{"stories": [1], "parameters": WALL}]}
    path = write(tmp_path, "no_heights.json", json.dumps(spec))
    assert cli.main(["simulate", str(path), "--record", str(default_record_path())]) == 0
    rows = [line.split() for line in capsys.readouterr().out.splitlines() if re.match(r"\s+[12] ", line)]
    expected = simulate(building_from_dict(spec), default_record())
    assert rows[0][2] == "-" and rows[1][2] == "-" and "nan" not in " ".join(rows[0] + rows[1])
    assert rows[1][4:] == ["-", "-"]  # story 2 has no wall
    assert float(rows[1][1]) == pytest.approx(expected.peak_drift[1], abs=0.006)


def test_cli_checks_out_before_the_analysis(tmp_path, capsys, monkeypatch):
    def no_analysis(*args, **kwargs):
        raise AssertionError("the analysis ran before --out was checked")

    monkeypatch.setattr(vdw.frame.simulation, "simulate", no_analysis)
    blocker = write(tmp_path, "taken", "a file")
    building = str(REPO / "examples" / "ten_story.toml")
    assert cli.main(["simulate", building, "--record", str(default_record_path()), "--out", str(blocker)]) == 2
    assert f"--out {blocker}: exists and is not a folder" in capsys.readouterr().err
    assert cli.main(["sine-test", "--out", str(blocker / "sub")]) == 2
    assert "cannot create the folder" in capsys.readouterr().err


def test_example_script_reports_a_missing_record(tmp_path, capsys):
    example = runpy.run_path(str(REPO / "examples" / "seismic_simulation.py"), run_name="example")
    missing = tmp_path / "missing.AT2"
    assert example["main"](["--record", str(missing), "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err == f"seismic_simulation.py: error: {missing}: no such AT2 file\n"
