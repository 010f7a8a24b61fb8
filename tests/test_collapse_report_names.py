"""The collapse report's old names (vdw_frames.assessment.report, .write_collapse_report) still work, deprecated."""

import pytest

from vdw_frames import assessment, collapse_report


def test_the_old_names_give_the_new_objects_with_a_deprecation_warning():
    with pytest.warns(DeprecationWarning, match=r"vdw_frames.collapse_report.write_collapse_report"):
        assert assessment.write_collapse_report is collapse_report.write_collapse_report
    with pytest.warns(DeprecationWarning, match=r"use vdw_frames.collapse_report"):
        assert assessment.report is collapse_report
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        assessment.nothing  # noqa: B018
