"""The package as a user gets it: a wheel built from this tree, installed into a fresh virtual
environment, runs the default seismic simulation from outside the repository (no ../shared, no
source tree: the synthetic record must come from the installed package data)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest
from shared_data import REPO

pytestmark = pytest.mark.slow  # a wheel build and fresh interpreters that compile everything: ~20 s each


def _run(command, cwd, **options):
    env = {key: value for key, value in os.environ.items() if key not in ("PYTHONPATH", "PYTHONHOME")}
    return subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True, timeout=300, check=False,
                          **options)


def _build_wheel(folder: Path) -> Path:
    """``pip wheel --no-deps`` of the repository; without network or a local index, pip's isolated
    build cannot fetch setuptools, so the build falls back to the running environment's."""
    errors = []
    for extra in ([], ["--no-build-isolation"]):
        build = _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", *extra, "-w", str(folder), str(REPO)],
                     cwd=folder)
        wheels = sorted(folder.glob("vdw_frames-*.whl"))
        if build.returncode == 0 and wheels:
            return wheels[-1]
        errors.append(build.stderr[-2000:])
    pytest.fail("could not build a wheel:\n" + "\n".join(errors))


def test_wheel_installs_and_runs_the_default_simulation(tmp_path):
    wheel = _build_wheel(tmp_path)
    venv = tmp_path / "venv"
    assert _run([sys.executable, "-m", "venv", "--without-pip", str(venv)], cwd=tmp_path).returncode == 0
    python = venv / "bin" / "python"
    # numpy, scipy, numba, matplotlib come from this environment (no network needed); a path listed in
    # a .pth file is only appended to sys.path, so the editable install here stays inactive.
    site_packages = Path(_run([str(python), "-c", "import sysconfig; print(sysconfig.get_path('purelib'))"],
                              cwd=tmp_path).stdout.strip())
    (site_packages / "dependencies.pth").write_text(sysconfig.get_path("purelib") + "\n")
    install = _run([sys.executable, "-m", "pip", "--python", str(python), "install", "--no-deps", "--no-index", "-q",
                    str(wheel)], cwd=tmp_path)
    assert install.returncode == 0, install.stderr

    where = _run([str(python), "-c", "import vdw_frames, vdw_frames.motion as m; print(vdw_frames.__file__); "
                  "print(m.default_record_path())"], cwd=tmp_path)
    assert where.returncode == 0, where.stderr
    package, record = (Path(line) for line in where.stdout.splitlines())
    # Resolved paths: a symlinked temporary folder must not make the comparison fail.
    assert package.resolve().is_relative_to(site_packages.resolve())
    assert record.resolve().is_relative_to(site_packages.resolve())
    assert record.is_file() and record.name == "synthetic_kt_035g.AT2"

    # The main job, the example script, run from a folder outside the repository.
    example = _run([str(python), str(REPO / "examples" / "seismic_simulation.py"), "--out", "figures"], cwd=tmp_path)
    assert example.returncode == 0, example.stderr
    assert "record synthetic_kt_035g: 2501 points, dt = 0.01 s, PGA = 0.350 g" in example.stdout
    assert "peak drift ratio (%)" in example.stdout
    for name in ("drift_envelope.png", "roof_displacement.png", "wall_hysteresis.png", "energy.png"):
        assert (tmp_path / "figures" / name).stat().st_size > 10_000

    # The installed console script, on the installed record.
    command = _run([str(venv / "bin" / "vdw-frames"), "simulate", str(REPO / "examples" / "ten_story.toml"),
                    "--record", str(record)], cwd=tmp_path)
    assert command.returncode == 0, command.stderr
    assert "10 stories" in command.stdout and "record synthetic_kt_035g: PGA = 0.350 g" in command.stdout


NO_CACHE_SCRIPT = r"""
import json, warnings
import numpy as np
from numba.core import caching
from numba.core.registry import CPUDispatcher
from scipy import signal


def unwritable(locator):
    raise PermissionError(13, "Permission denied", locator.get_cache_path())


# Every cache folder refuses writes, as on a read-only install with an unwritable HOME (as root, file
# permissions cannot simulate that): numba then finds no locator and refuses "cannot cache function".
caching._CacheLocator.ensure_cache_path = unwritable
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    import vdw_frames as vdw

    wall = vdw.FDMKDamper(G1=0.0, G2=3.0, eta1=0.3, eta2=2.0, r=0.5)
    loop = vdw.sine_test(wall, 10.0, 1.0)
    frame = vdw.ShearBuilding([100.0], [4.0e4], damping_ratio=0.05)
    dt = 0.002
    t = np.arange(2001) * dt
    motion = vdw.GroundMotion(1000.0 * np.sin(2 * np.pi * 1.5 * t) * np.minimum(t, 1.0), dt)
    result = vdw.simulate(frame, motion)
omega = frame.circular_frequencies[0]
system = signal.StateSpace([[0, 1], [-omega**2, -2 * 0.05 * omega]], [[0], [-1]], [[1, 0]], [[0]])
_, reference, _ = signal.lsim(system, motion.acceleration, t)
print(json.dumps({
    "warnings": [f"{w.category.__name__}: {w.message}" for w in caught],
    "storage": [loop.storage_stiffness, float(wall.storage_stiffness(1.0))],
    "loss": [loop.loss_stiffness, float(wall.loss_stiffness(1.0))],
    "peak": [float(np.abs(result.displacement[:, 0]).max()), float(np.abs(reference).max())],
    "caches": sorted({type(f._cache).__name__ for module in (vdw.element.kernel, vdw.frame.simulation)
                      for f in vars(module).values() if isinstance(f, CPUDispatcher)}),
}))
"""


def test_import_without_a_writable_numba_cache_warns_once_and_computes(tmp_path):
    run = _run([sys.executable, "-c", NO_CACHE_SCRIPT], cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    report = json.loads(run.stdout)
    cache_warnings = [w for w in report["warnings"] if "cache" in w]
    assert len(cache_warnings) == 1, report["warnings"]
    assert cache_warnings[0].startswith("RuntimeWarning: vdw_frames: numba cannot write a compilation cache")
    assert report["caches"] == ["NullCache"]  # every compiled function of the kernel and the integrator
    # Right answers without the cache: the element against its complex modulus (200 steps a cycle: the
    # discretisation error is below 2e-4), the frame against scipy's exact linear simulation.
    for computed, reference in (report["storage"], report["loss"]):
        assert computed == pytest.approx(reference, rel=1e-3)
    assert report["peak"][0] == pytest.approx(report["peak"][1], rel=1e-3)
