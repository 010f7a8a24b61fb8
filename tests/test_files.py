"""Reading and writing files (vdw_frames._files): every reader says what a file is when it is not text it can
read (FIFOs, devices and oversized files refused before reading), and a write goes through a recognisable
temporary file, keeps the target's permissions and links, cleans up after killed writers, refuses
symbolic-link loops and keeps the old file when it fails."""

from __future__ import annotations

import gzip
import os
import re
import stat
import subprocess
import sys

import numpy as np
import pytest
from builders import VALUES_G, peer_at2, write_file

from vdw_frames import GroundMotion, _files, read_at2, read_two_column
from vdw_frames import collapse_report as report
from vdw_frames.config import load_building
from vdw_frames.motion import write_at2
from vdw_frames.plotting import plot_loops


def test_readers_name_compressed_utf16_binary_missing_and_folder_inputs(tmp_path):
    good = peer_at2("NPTS= 7, DT= 0.01", [" ".join(map(str, VALUES_G))])
    cases = [
        (gzip.compress(good.encode()), "a gzip-compressed file; decompress it first"),
        (good.encode("utf-16"), "UTF-16 text; save it as UTF-8 or ASCII"),
        (good.encode("utf-16-le"), "UTF-16 text"),
        (b"PK\x03\x04" + b"\x00" * 20, "a zip archive"),
        (b"NPTS= 7\x00\x01", "binary data"),
        # Short binary data with NULs in every other byte was called "UTF-16 text"
        (b"\x00\x01\x02\xff", r"binary data \(a NUL byte at position 0\), not a text"),
        (b"\x00\x01\x02\xc3\xbf", r"binary data \(a NUL byte at position 0\), not a text"),
        ("NPTS= 7, DT= 0.01 \u2265".encode("utf-16-be"), "UTF-16 text"),  # one character beyond Latin-1
    ]
    for data, match in cases:
        for reader in (read_at2, read_two_column):
            path = write_file(tmp_path, "odd.AT2", data)
            with pytest.raises(ValueError, match=re.escape(str(path)) + ": " + match):
                reader(path)
    binary = write_file(tmp_path, "binary.toml", b"\x00\x01\x02\xff")
    with pytest.raises(ValueError, match=r"binary.toml: binary data \(a NUL byte at position 0\), not a text building"):
        load_building(binary)
    for bad, match in ((tmp_path, "is a folder, not a"), (tmp_path / "missing.AT2", "missing.AT2: no such"),
                       ("", "must be a path, got ''"), (None, "must be a path .* got None")):
        for reader in (read_at2, read_two_column, load_building):
            with pytest.raises(ValueError, match=match):
                reader(bad)


def test_a_write_keeps_permissions(tmp_path):
    motion = GroundMotion([1.0, 2.0, 3.0], 0.01, "x")
    kept = write_file(tmp_path, "kept.AT2", "OLD")
    kept.chmod(0o640)
    write_at2(motion, kept)
    assert stat.S_IMODE(kept.stat().st_mode) == 0o640
    umask = os.umask(0)
    os.umask(umask)
    fresh = write_at2(motion, tmp_path / "fresh.AT2")
    assert stat.S_IMODE(fresh.stat().st_mode) == 0o666 & ~umask
    for bad, match in ((tmp_path, "is a folder"), (tmp_path / "missing" / "x.AT2", "does not exist"),
                       ("", "must be a path"), (None, "must be a path")):
        with pytest.raises(ValueError, match=match):
            write_at2(motion, bad)


AT2 = "HEADER\nHEADER\nACCELERATION TIME HISTORY IN UNITS OF G\nNPTS= 3, DT= 0.01 SEC\n0.1 0.2 0.3\n"


def motion() -> GroundMotion:
    return GroundMotion(np.array([1.0, -2.0, 3.0]), 0.01, "m")


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this platform")
def test_a_fifo_is_refused_without_reading(tmp_path):
    fifo = tmp_path / "pipe.AT2"
    os.mkfifo(fifo)  # reading it would block until a writer came
    with pytest.raises(ValueError, match=r"pipe.AT2: not a regular file \(a FIFO, socket or device\)"):
        read_at2(fifo)


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="no /dev/zero")
def test_an_endless_device_is_refused():
    with pytest.raises(ValueError, match="/dev/zero: not a regular file"):
        read_at2("/dev/zero")


def test_a_file_above_the_size_cap_is_refused_before_reading(tmp_path, monkeypatch):
    path = tmp_path / "big.AT2"
    path.write_text(AT2)
    assert read_at2(path).acceleration.size == 3
    monkeypatch.setattr(_files, "MAX_TEXT_BYTES", len(AT2) - 1)
    refused = rf"big.AT2: {len(AT2)} bytes; AT2 files above {len(AT2) - 1} bytes are refused"
    with pytest.raises(ValueError, match=refused):
        read_at2(path)


def test_temporary_files_are_named_and_removed(tmp_path):
    target = tmp_path / "record.AT2"
    seen = []

    def write(temporary):
        seen.append(temporary)
        temporary.write_text(AT2)

    _files.write_via(target, write)
    assert re.fullmatch(rf"\.record\.AT2\.vdw-tmp-{os.getpid()}-[0-9a-f]{{8}}\.AT2", seen[0].name)
    assert sorted(tmp_path.iterdir()) == [target] and read_at2(target).acceleration.size == 3


def dead_pid() -> int:
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait()
    return process.pid


def test_a_killed_writers_temporary_file_is_removed_by_the_next_write(tmp_path):
    target = tmp_path / "record.AT2"
    stale = tmp_path / f".record.AT2.vdw-tmp-{dead_pid()}-0badc0de.AT2"
    stale.write_text("half a file")
    live = tmp_path / ".record.AT2.vdw-tmp-1-0badc0de.AT2"  # pid 1 runs: its write may be under way
    live.write_text("being written")
    other = tmp_path / f".other.AT2.vdw-tmp-{dead_pid()}-0badc0de.AT2"  # another target's: not ours to remove
    other.write_text("x")
    write_at2(motion(), target)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([target.name, live.name, other.name])


LINK_REFUSED = "a symbolic link; the package writes no file through a link"


def test_no_writer_writes_through_a_symbolic_link(tmp_path):
    """A link to a file elsewhere (before: replaced wherever it pointed), a dangling one (before: created a
    file in another folder) and a loop are refused by every writer; the linked file and the folders stay."""
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    victim = write_file(elsewhere, "system.conf", "keep me")
    live, dangling, first, second = (tmp_path / name for name in ("live.AT2", "dangling.AT2", "a.AT2", "b.AT2"))
    live.symlink_to(victim)
    dangling.symlink_to(elsewhere / "new.AT2")
    first.symlink_to(second)
    second.symlink_to(first)
    for link in (live, dangling, first):
        with pytest.raises(ValueError, match=rf"{link.name}: {LINK_REFUSED}"):
            write_at2(motion(), link)
        with pytest.raises(ValueError, match=rf"{link.name}: {LINK_REFUSED}"):
            _files.write_text(link, "text")
        with pytest.raises(ValueError, match=rf"{link.name}: {LINK_REFUSED}"):
            _files.write_via(link, lambda temporary: temporary.write_text("text"))
        assert link.is_symlink()
    assert victim.read_text() == "keep me" and sorted(p.name for p in elsewhere.iterdir()) == ["system.conf"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.AT2", "b.AT2", "dangling.AT2", "elsewhere", "live.AT2"]


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this platform")
def test_no_writer_replaces_a_fifo(tmp_path):
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    with pytest.raises(ValueError, match=r"pipe.csv: not a regular file \(a FIFO, socket or device\)"):
        _files.write_text(fifo, "a,b\n")
    assert stat.S_ISFIFO(fifo.lstat().st_mode)


def test_the_rename_replaces_a_link_planted_after_the_check_not_its_target(tmp_path, monkeypatch):
    """Between the check and the rename a link may appear at the target's name: os.replace renames over the
    name itself, so the link goes and the file it points to stays."""
    victim = write_file(tmp_path, "victim.txt", "keep me")
    target = tmp_path / "table.csv"

    def write(temporary):
        temporary.write_text("new")
        target.symlink_to(victim)

    _files.write_via(target, write)
    assert not target.is_symlink() and target.read_text() == "new" and victim.read_text() == "keep me"


def failing_replace(source, target):
    raise OSError(28, "No space left on device")


def test_a_failed_figure_or_csv_write_keeps_the_old_file(tmp_path, monkeypatch):
    from vdw_frames.element.sine import sine_test
    from vdw_frames.paper import fitted

    figure = plot_loops(sine_test(fitted(300), 3.0, 1.0, cycles=1), tmp_path / "loops.png")
    old = figure.read_bytes()
    table = _files.write_text(tmp_path / "table.csv", "a,b\n1,2\n")
    monkeypatch.setattr(os, "replace", failing_replace)
    with pytest.raises(ValueError, match=r"loops.png: cannot write \(No space left on device\)"):
        plot_loops(sine_test(fitted(300), 6.0, 1.0, cycles=1), figure)
    with pytest.raises(ValueError, match=r"table.csv: cannot write \(No space left on device\)"):
        _files.write_text(table, "c,d\n")
    assert figure.read_bytes() == old and table.read_text() == "a,b\n1,2\n"
    assert sorted(tmp_path.iterdir()) == [figure, table]


def test_the_collapse_report_writes_through_a_temporary_file(tmp_path, monkeypatch):
    path = tmp_path / "report.md"
    path.write_text("old report")
    monkeypatch.setattr(os, "replace", failing_replace)
    with pytest.raises(ValueError, match=r"report.md: cannot write \(No space left on device\)"):
        report._write_text(path, "new report")
    assert path.read_text() == "old report" and sorted(tmp_path.iterdir()) == [path]


def test_the_paper_report_refuses_a_file_or_a_looping_link_as_its_folder(tmp_path):
    # Both raised a FileExistsError traceback from mkdir before.
    from vdw_frames.paper import write_paper_report

    afile = write_file(tmp_path, "afile", "x")
    loop = tmp_path / "loop"
    loop.symlink_to(loop)
    for bad in (afile, loop):
        with pytest.raises(ValueError, match=rf"{bad.name}: exists and is not a folder \(a file, or a symbolic link "
                                             r"that loops\); give the report folder"):
            write_paper_report(bad, quick=True)
    with pytest.raises(ValueError, match="report folder must be a path"):
        write_paper_report(None, quick=True)


@pytest.mark.slow
def test_a_failed_paper_report_write_keeps_the_old_report(tmp_path, monkeypatch):
    from vdw_frames.paper import write_paper_report

    old = write_file(tmp_path, "report.md", "old report")
    monkeypatch.setattr(os, "replace", failing_replace)
    with pytest.raises(ValueError, match=r"report.md: cannot write \(No space left on device\)"):
        write_paper_report(tmp_path, quick=True)
    assert old.read_text() == "old report" and sorted(tmp_path.iterdir()) == [old]
