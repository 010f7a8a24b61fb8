"""Fixtures shared by the test modules."""

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
