"""The reproduction report (vdw_frames.paper.report) end to end: its sections, numbers and figures."""

from __future__ import annotations

import pytest

from vdw_frames.paper.report import write_paper_report

pytestmark = pytest.mark.slow  # the report re-runs every identification: ~15 s each


def test_report_has_its_sections_errata_numbers_and_figures(tmp_path):
    path = write_paper_report(tmp_path / "out")
    assert path == tmp_path / "out" / "report.md"
    text = path.read_text()
    for heading in ("## 1. Parameter sets", "## 2. Tables 1-3", "## 3. Table 5", "## 4. Errata", "## 5. Figures",
                    "## 6. Strain dependence"):
        assert heading in text
    assert "Table 4 gives G'(0.5 Hz) = 10.71 MPa" in text
    assert "No candidate reproduces the printed theoretical areas" in text
    assert "-0.3090" in text  # cos(0.6 pi)
    pngs = sorted(p.name for p in (tmp_path / "out").glob("*.png"))
    assert len(pngs) == 11
    for name in pngs:
        assert f"({name})" in text
        data = (tmp_path / "out" / name).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 20_000


def test_quick_report_has_no_figures(tmp_path):
    path = write_paper_report(tmp_path, quick=True)
    assert "quick run" in path.read_text()
    assert not list(tmp_path.glob("*.png"))


def test_the_report_states_the_heating_of_the_tests_themselves():
    # Reference: pi G'' gamma^2 / (rho c) by hand from Table 2's printed G'' (0.67 MPa at 0.5 Hz, 0.50 at 10 Hz),
    # gamma = 3, rho c = 1.8 J/(cm^3 K): 10.52 and 7.85 K a cycle.
    from vdw_frames.paper.report import _self_heating_note

    note = _self_heating_note()
    assert f"| 300 % | {3.14159265 * 0.50 * 9 / 1.8:.1f}-{3.14159265 * 0.67 * 9 / 1.8:.1f} |" in note
    assert "| 300 % | 7.9-10.5 |" in note and "counts part of the heating twice" in note
