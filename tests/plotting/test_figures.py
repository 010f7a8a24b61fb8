"""Figures (vdw_frames.plotting): where they are written, what they hold."""

from __future__ import annotations

import os

import pytest
from builders import README_WALL, TABLE4

from vdw_frames import FDMKDamper, sine_test
from vdw_frames.plotting import plot_loops


def test_figure_paths_get_a_suffix_a_file_name_in_a_folder_and_their_folders(tmp_path):
    result = sine_test(FDMKDamper(**README_WALL), 10.0, 1.0, cycles=2)
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


def test_loop_figure_is_written(tmp_path):
    damper = FDMKDamper(**TABLE4)
    results = [sine_test(damper, 22.5, f) for f in (0.5, 1.5)]
    path = plot_loops(results, tmp_path / "loops.png", title="Table 4")
    assert path.stat().st_size > 10_000
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(ValueError, match="labels"):
        plot_loops(results, tmp_path / "x.png", labels=["one"])


def test_response_figures_of_a_run_at_rest_or_stopped_at_its_first_step(tmp_path):
    # The energy figure raised numpy's "need at least one array to concatenate" when no energy part moved.
    import warnings

    import numpy as np

    from vdw_frames import BoucWen, GroundMotion, ShearBuilding, simulate
    from vdw_frames.frame import NewtonRaphson
    from vdw_frames.plotting import plot_drift_envelope, plot_energy, plot_roof_displacement, plot_story_hysteresis

    frame = ShearBuilding([500.0] * 2, [8e5, 6e5], story_heights=[3000.0] * 2,
                          hysteresis=[BoucWen(1e5, exponent=100.0)] * 2)
    at_rest = simulate(frame, GroundMotion(np.zeros(20), 0.01, "zero"))
    strict = NewtonRaphson(displacement_tolerance=1e-300, force_tolerance=1e-300, max_iterations=1,
                           fallback_iterations=1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the non-convergence warning: the point of this run
        stopped = simulate(frame, GroundMotion([0.0, 3e6, -3e6, 0.0], 0.01, "pulse"), newton=strict,
                           collapse_drift_ratio=None)
    assert stopped.time.size == 1 and not stopped.converged
    for result in (at_rest, stopped):
        runs = {"run": result}
        for plot, arguments in ((plot_energy, (result,)), (plot_story_hysteresis, (result, 1)),
                                (plot_drift_envelope, (runs,)), (plot_roof_displacement, (runs,))):
            path = plot(*arguments, tmp_path / f"{plot.__name__}.png")
            assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_wall_amplitude_figure_names_its_traces_and_the_wall_and_story(tmp_path, monkeypatch):
    # The wall of story 2 is wall 1 (the first story has none): the axis says so, and the |strain| trace is in
    # the legend with the followed amplitude and the identified range.
    import warnings

    import numpy as np

    import vdw_frames as vdw
    from vdw_frames.motion import default_record
    from vdw_frames.plotting import plot_wall_amplitude, walls

    building = vdw.ShearBuilding(masses=[400.0, 380.0], stiffnesses=[3.0e5, 2.7e5],
                                 devices={2: [vdw.paper.strain_dependent(area=0.3e6, thickness=8.0)]})
    with warnings.catch_warnings():  # (whether the wall leaves its tested range is not this test's subject)
        warnings.simplefilter("ignore", UserWarning)
        result = vdw.simulate(building, default_record())
    figures = []
    real_save = walls.save
    monkeypatch.setattr(walls, "save", lambda figure, path: (figures.append(figure), real_save(figure, path))[1])
    path = plot_wall_amplitude({"model": result}, 1, tmp_path / "amplitude.png", strain_range=(2.25, 4.5))
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    axes = figures[0].axes[0]
    assert axes.get_ylabel() == "wall 1 (story 2) strain (%)"
    assert [text.get_text() for text in axes.get_legend().get_texts()] == [
        "model: |strain|", "model: followed amplitude", "identified range"]
    strain_line = axes.get_lines()[0]
    np.testing.assert_array_equal(strain_line.get_ydata(), 100.0 * np.abs(result.wall_strain[:, 0]))
