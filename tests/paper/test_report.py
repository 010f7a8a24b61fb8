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
