"""ASCE 7-16 Table 18.7-1 (B) and Sec. 18.2.1.1 (V_min), against the table's printed cells (as recalled: see
vdw_frames.asce7.damping) and the rule worked by hand."""

from __future__ import annotations

import math

import pytest

from vdw_frames.asce7 import damping_coefficient, minimum_base_shear

# The printed rows of Table 18.7-1: effective damping in percent of critical -> B, typed in from the table as
# recalled (the first row is "<= 2", the last ">= 100").
PRINTED = {2: 0.8, 5: 1.0, 10: 1.2, 20: 1.5, 30: 1.8, 40: 2.1, 50: 2.4, 60: 2.7, 70: 3.0, 80: 3.3, 90: 3.6,
           100: 4.0}


@pytest.mark.parametrize(("percent", "b"), sorted(PRINTED.items()))
def test_b_at_the_printed_damping_values(percent: int, b: float) -> None:
    assert damping_coefficient(percent / 100) == pytest.approx(b, abs=1e-12)


def test_b_beyond_the_table_ends_is_the_end_rows() -> None:
    assert damping_coefficient(0.0) == 0.8  # "<= 2 %"
    assert damping_coefficient(0.01) == 0.8
    assert damping_coefficient(1.5) == 4.0  # ">= 100 %"


@pytest.mark.parametrize(("beta", "expected"), [
    (0.035, 0.8 + (1.0 - 0.8) * (3.5 - 2) / (5 - 2)),   # 0.9
    (0.15, 1.2 + (1.5 - 1.2) * (15 - 10) / (20 - 10)),  # 1.35
    (0.25, 1.5 + (1.8 - 1.5) * 0.5),                    # 1.65
    (0.95, 3.6 + (4.0 - 3.6) * 0.5),                    # 3.8
])
def test_b_between_printed_values_is_linear(beta: float, expected: float) -> None:
    assert damping_coefficient(beta) == pytest.approx(expected, rel=1e-12)


def test_v_min_is_v_over_b_when_that_exceeds_three_quarters() -> None:
    v_min, rule = minimum_base_shear(1000.0, 1.2)   # 1000 / 1.2 = 833.3 > 750
    assert v_min == pytest.approx(1000.0 / 1.2, rel=1e-12)
    assert rule == "V / B_V+I"


def test_v_min_is_three_quarters_of_v_when_b_is_large() -> None:
    v_min, rule = minimum_base_shear(1000.0, 1.5)   # 1000 / 1.5 = 666.7 < 750
    assert v_min == pytest.approx(750.0, rel=1e-12)
    assert rule == "0.75 V"
    # The crossover: B = 4/3 gives both 750.
    assert minimum_base_shear(1000.0, 4 / 3)[0] == pytest.approx(750.0, rel=1e-12)


def test_v_min_is_v_when_irregular() -> None:
    v_min, rule = minimum_base_shear(1000.0, 2.4, irregular=True)
    assert v_min == 1000.0
    assert rule == "1.0 V (irregular)"


@pytest.mark.parametrize("bad", [-0.01, math.nan, math.inf, "0.2", None])
def test_bad_effective_damping_is_refused(bad: object) -> None:
    with pytest.raises(ValueError, match="effective_damping"):
        damping_coefficient(bad)  # type: ignore[arg-type]


@pytest.mark.parametrize(("v", "b", "irregular", "name"), [
    (0.0, 1.2, False, "v"), (-5.0, 1.2, False, "v"), (math.nan, 1.2, False, "v"),
    (100.0, 0.5, False, "b_v_plus_i"), (100.0, math.inf, False, "b_v_plus_i"), (100.0, 1.2, "yes", "irregular"),
])
def test_bad_minimum_base_shear_input_is_refused(v: float, b: float, irregular: object, name: str) -> None:
    with pytest.raises(ValueError, match=name):
        minimum_base_shear(v, b, irregular)  # type: ignore[arg-type]
