"""Reading and writing files (vdw_frames._files): every reader says what a file is when it is not text it can
read, and a write keeps the target's permissions and links."""

from __future__ import annotations

import gzip
import os
import re
import stat

import pytest
from builders import VALUES_G, peer_at2, write_file

from vdw_frames import GroundMotion, read_at2, read_two_column
from vdw_frames.config import load_building
from vdw_frames.motion import write_at2


def test_readers_name_compressed_utf16_binary_missing_and_folder_inputs(tmp_path):
    good = peer_at2("NPTS= 7, DT= 0.01", [" ".join(map(str, VALUES_G))])
    cases = [
        (gzip.compress(good.encode()), "a gzip-compressed file; decompress it first"),
        (good.encode("utf-16"), "UTF-16 text; save it as UTF-8 or ASCII"),
        (good.encode("utf-16-le"), "UTF-16 text"),
        (b"PK\x03\x04" + b"\x00" * 20, "a zip archive"),
        (b"NPTS= 7\x00\x01", "binary data"),
    ]
    for data, match in cases:
        for reader in (read_at2, read_two_column):
            path = write_file(tmp_path, "odd.AT2", data)
            with pytest.raises(ValueError, match=re.escape(str(path)) + ": " + match):
                reader(path)
    for bad, match in ((tmp_path, "is a folder, not a"), (tmp_path / "missing.AT2", "missing.AT2: no such"),
                       ("", "must be a path, got ''"), (None, "must be a path .* got None")):
        for reader in (read_at2, read_two_column, load_building):
            with pytest.raises(ValueError, match=match):
                reader(bad)


def test_a_write_keeps_permissions_and_follows_links(tmp_path):
    motion = GroundMotion([1.0, 2.0, 3.0], 0.01, "x")
    kept = write_file(tmp_path, "kept.AT2", "OLD")
    kept.chmod(0o640)
    write_at2(motion, kept)
    assert stat.S_IMODE(kept.stat().st_mode) == 0o640
    umask = os.umask(0)
    os.umask(umask)
    fresh = write_at2(motion, tmp_path / "fresh.AT2")
    assert stat.S_IMODE(fresh.stat().st_mode) == 0o666 & ~umask
    link = tmp_path / "link.AT2"
    link.symlink_to(kept)
    write_at2(GroundMotion([4.0, 5.0], 0.02, "y"), link)
    assert link.is_symlink() and read_at2(kept).dt == 0.02
    for bad, match in ((tmp_path, "is a folder"), (tmp_path / "missing" / "x.AT2", "does not exist"),
                       ("", "must be a path"), (None, "must be a path")):
        with pytest.raises(ValueError, match=match):
            write_at2(motion, bad)
