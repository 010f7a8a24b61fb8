"""Fixtures of the verification tests: a three-story frame with r = 1 walls and 14 short synthetic records."""

from verification_cases import building, records  # noqa: F401  (fixtures)
