"""Where the tests find things outside the package: the repository and the shared records beside it.

The package knows nothing of ``../shared``; tests that need the recorded accelerograms call
:func:`shared_record`, which skips (saying where it looked) when the folder is absent.
"""

from __future__ import annotations

from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
SHARED = REPO.parent / "shared" / "ground_motions"
PAPER_TEXT = REPO.parent / "shared" / "seed" / "fdmk_5plus4_vdw_paper.txt"
EXAMPLE_BUILDING = REPO / "examples" / "ten_story.toml"


def shared_record(file_name: str) -> Path:
    """Path of a record in ../shared/ground_motions, or a skip when that folder is absent."""
    if not SHARED.is_dir():
        pytest.skip(f"shared ground motions not found at {SHARED}")
    return SHARED / file_name
