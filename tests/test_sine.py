"""Sinusoidal test of the element alone, against the frequency-domain solution."""

import numpy as np
import pytest

from vdw_frames import FDMKDamper, sine_test
from vdw_frames.plotting import plot_loops

TABLE4 = dict(G1=8.69, G2=3.58, eta1=0.75, eta2=0.98, r=0.60)
PARAMETER_SETS = [TABLE4, dict(G1=0.0, G2=3.0, eta1=0.3, eta2=2.0, r=0.3), dict(G1=1.0, G2=2.0, eta1=0.5, eta2=0.5, r=0.9),
                  dict(G1=0.5, G2=5.0, eta1=0.2, eta2=1.0, r=0.1), dict(G1=0.0, G2=1.0, eta1=0.0, eta2=1.0, r=1.0)]


@pytest.mark.parametrize("params", PARAMETER_SETS)
@pytest.mark.parametrize("frequency", [0.5, 10.0])
def test_last_loop_is_steady(params, frequency):
    # The docstring of vdw_frames.element.sine promises the default 5 cycles give the steady loop to 0.1 %.
    damper = FDMKDamper(**params)
    result = sine_test(damper, 30.0, frequency)
    assert result.loop_area == pytest.approx(np.pi * damper.loss_stiffness(frequency) * 30.0**2, rel=1e-3)
    assert result.storage_stiffness == pytest.approx(damper.storage_stiffness(frequency), rel=1e-3)
    assert result.loss_stiffness == pytest.approx(damper.loss_stiffness(frequency), rel=1e-3)


def test_effective_stiffness_and_damping_ratio_of_an_ellipse():
    damper = FDMKDamper(**TABLE4)
    result = sine_test(damper, 22.5, 1.5)
    # Steady ellipse F = K' u + K'' U cos: peak force U sqrt(K'^2 + K''^2).
    modulus = abs(damper.complex_modulus(1.5)) * damper.area / damper.thickness
    assert result.effective_stiffness == pytest.approx(modulus, rel=2e-3)
    expected = np.pi * damper.loss_stiffness(1.5) / (2 * np.pi * modulus)
    assert result.equivalent_damping_ratio == pytest.approx(expected, rel=3e-3)
    assert result.time[-1] == pytest.approx(5 / 1.5)
    assert result.last_cycle.stop - result.last_cycle.start == 201


def test_first_cycle_shows_the_transient():
    damper = FDMKDamper(**TABLE4)
    result = sine_test(damper, 30.0, 1.0, cycles=1)
    steady = np.pi * damper.loss_stiffness(1.0) * 30.0**2
    assert abs(result.loop_area / steady - 1) > 0.02  # power-law memory of the start


def test_loop_figure_is_written(tmp_path):
    damper = FDMKDamper(**TABLE4)
    results = [sine_test(damper, 22.5, f) for f in (0.5, 1.5)]
    path = plot_loops(results, tmp_path / "loops.png", title="Table 4")
    assert path.stat().st_size > 10_000
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(ValueError, match="labels"):
        plot_loops(results, tmp_path / "x.png", labels=["one"])
