"""Fixtures of the verification tests: a three-story frame with r = 1 walls and 14 short synthetic records."""

import pytest
from verification_cases import synthetic_records, three_story


@pytest.fixture(scope="session")
def building():
    return three_story()


@pytest.fixture(scope="session")
def records():
    return synthetic_records()
