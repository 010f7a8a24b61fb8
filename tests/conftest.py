"""Fixtures shared by the test modules.

The test folders mirror the package (tests/element, tests/motion, tests/frame, tests/design, tests/paper,
tests/interop, tests/assessment, tests/plotting; tests/integration for the README, the examples, the installed
wheel and the command line; tests/test_config.py, test_files.py, test_parallel.py and test_validation.py for
the top-level modules).  pytest runs in importlib mode with tests/ on sys.path (pyproject.toml): test files of
the same name may sit in different folders, test modules never import each other, and the shared modules are
imported by name from any folder: ``builders`` (parameter sets, frames, motions, files), ``reference`` (independent
solutions and measures of agreement), ``shared_data`` (the repository and ../shared) and ``opensees_frame``
(the OpenSeesPy models, also used by examples/benchmark.py).

Markers: ``slow`` (more than about 2 s on 2 cores; ``pytest -m "not slow"`` is the developer subset),
``opensees`` (needs OpenSeesPy), ``records`` (needs recorded accelerograms: ../shared/ground_motions or the
[p695] extra).
"""

import opensees_frame
import pytest
from shared_data import shared_record

from vdw_frames import read_at2


@pytest.fixture(scope="module")
def ops():
    """The ``openseespy.opensees`` module.  A test dependency (the test extra; .ci/run installs libblas3 and
    liblapack3): a test that needs it fails, never skips, when it cannot be loaded."""
    try:
        return opensees_frame.opensees()
    except ImportError as error:
        pytest.fail(str(error))


@pytest.fixture(scope="module")
def record():
    """El Centro 1940 N-S (elCentro.AT2: 1559 points at 0.02 s, PGA 0.32 g) from ../shared, or a skip."""
    return read_at2(shared_record("elCentro.AT2"))
