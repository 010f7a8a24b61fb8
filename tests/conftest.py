"""Fixtures shared by the test modules."""

import pytest

import opensees_frame


@pytest.fixture(scope="module")
def ops():
    """The ``openseespy.opensees`` module.  A test dependency (the test extra; .ci/run installs libblas3 and
    liblapack3): a test that needs it fails, never skips, when it cannot be loaded."""
    try:
        return opensees_frame.opensees()
    except ImportError as error:
        pytest.fail(str(error))
