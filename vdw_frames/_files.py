"""Files: paths checked at the boundary, text read with clear refusals, every write atomic.

Reading (:func:`read_text`): a missing file, a folder, a FIFO or device, a file above
:data:`MAX_TEXT_BYTES`, an archive, UTF-16 and other binary data each get a ``ValueError`` that names the
file and says what it is.

Writing (:func:`replace_file`, :func:`write_text`, :func:`write_via`): every file the package writes
(records, figures, CSV tables, reports, result archives) goes to a temporary file beside the target,
named ``.<name>.vdw-tmp-<pid>-<token>``, and is renamed over the target only when complete (atomic on
POSIX and Windows), so a failed write (a full disk, an interrupted process) never destroys the old file.
A target must be a new path or a regular file: a symbolic link (which would have the write replace whatever
it points to, or create a file in another folder), a folder, a FIFO or a device is refused.
A temporary file left by a process that was killed (its pid no longer runs) is removed by the next write
of the same target.  Every failure is one ``ValueError`` naming the path.
"""

from __future__ import annotations

import csv
import io
import os
import secrets
import stat
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

from ._validation import show

MAX_TEXT_BYTES = 256 * 1024**2
"""Largest text file read (bytes): 256 MiB, far above any record or building file (a 100 000-point AT2 file
is ~2 MB); a larger one (or an endless device) is refused before it is read."""

_TEMPORARY = ".vdw-tmp-"


def file_path(path: str | os.PathLike[str], what: str = "file") -> Path:
    """``path`` (str or os.PathLike) as a :class:`pathlib.Path`; '' and None are refused."""
    if isinstance(path, bytes) or not isinstance(path, (str, os.PathLike)):
        raise ValueError(f"{what} must be a path (str or pathlib.Path), got {show(path)}")
    if str(path) == "":
        raise ValueError(f"{what} must be a path, got ''")
    return Path(path)


def read_text(path: str | os.PathLike[str], what: str = "file", strict: bool = True) -> tuple[Path, str]:
    """(Path, text) of a text file; every failure is a ValueError naming the file.

    A missing file, a folder, a FIFO or device (not a regular file), a file above :data:`MAX_TEXT_BYTES`,
    a gzip or zip archive, UTF-16 text and other binary data each get a message that says so.  A UTF-8
    byte-order mark is dropped.  ``strict``: bytes that are not UTF-8 are an error naming the file and the
    position; otherwise they become U+FFFD (for free-text headers, e.g. Latin-1 station names).
    """
    path = file_path(path, what)
    try:
        info = path.stat()
    except FileNotFoundError:
        raise ValueError(f"{path}: no such {what}") from None
    except OSError as error:
        raise ValueError(f"{path}: cannot read the {what} ({error.strerror or error})") from None
    if stat.S_ISDIR(info.st_mode):
        raise ValueError(f"{path}: is a folder, not a {what}")
    if not stat.S_ISREG(info.st_mode):
        raise ValueError(f"{path}: not a regular file (a FIFO, socket or device); give the {what} itself")
    if info.st_size > MAX_TEXT_BYTES:
        raise ValueError(f"{path}: {info.st_size:,} bytes; {what}s above {MAX_TEXT_BYTES:,} bytes are refused")
    try:
        with open(path, "rb") as handle:
            data = handle.read(MAX_TEXT_BYTES + 1)
    except OSError as error:
        raise ValueError(f"{path}: cannot read the {what} ({error.strerror or error})") from None
    if len(data) > MAX_TEXT_BYTES:
        raise ValueError(f"{path}: grew beyond {MAX_TEXT_BYTES:,} bytes while it was read; {what}s above that "
                         "are refused")
    if data.startswith(b"\x1f\x8b"):
        raise ValueError(f"{path}: a gzip-compressed file; decompress it first (e.g. gunzip)")
    if data.startswith(b"PK\x03\x04"):
        raise ValueError(f"{path}: a zip archive; extract the {what} from it first")
    if data.startswith((b"\xff\xfe", b"\xfe\xff")) or _looks_utf16(data):
        raise ValueError(f"{path}: UTF-16 text; save it as UTF-8 or ASCII")
    nul = data.find(0)
    if nul >= 0:
        raise ValueError(f"{path}: binary data (a NUL byte at position {nul}), not a text {what}")
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        if strict:
            raise ValueError(f"{path}: not UTF-8 text (byte {data[error.start]:#04x} at position "
                             f"{error.start}); save it as UTF-8") from None
        text = data.decode("utf-8", errors="replace")
    return path, text


# Bytes of text: not NUL nor a control character other than tab, line feed, form feed and carriage return.
_TEXT_BYTES = frozenset({9, 10, 12, 13, *range(0x20, 0x7F), *range(0x80, 0x100)})


def _looks_utf16(data: bytes) -> bool:
    # Mostly-ASCII text in UTF-16 without a byte-order mark: every other byte of the start is NUL (one may not
    # be: a character beyond Latin-1), the others are text.  Binary data with a few NULs (00 01 02 ff) is not.
    head = data[:200]
    if len(head) < 4:
        return False
    return any(zeros.count(0) >= len(zeros) - 1 and all(byte in _TEXT_BYTES for byte in chars)
               for zeros, chars in ((head[1::2], head[0::2]), (head[0::2], head[1::2])))


def output_folder(path: str | os.PathLike[str], what: str = "output folder") -> Path:
    """``path`` as a folder, created with its parents if missing, checked writable before any work; a
    ValueError naming it when it is a file, a symbolic link that loops, cannot be created or is not
    writable."""
    folder = file_path(path, what)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise ValueError(f"{folder}: exists and is not a folder (a file, or a symbolic link that loops); give "
                         f"the {what}") from None
    except OSError as error:
        raise ValueError(f"{folder}: cannot create the {what} ({error.strerror or error})") from None
    if not os.access(folder, os.W_OK | os.X_OK):
        raise ValueError(f"{folder}: the {what} is not writable")
    return folder


def write_text(path: str | os.PathLike[str], text: str, what: str = "file") -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically (:func:`replace_file`); returns the path."""
    path = file_path(path, what)
    replace_file(path, text.encode("utf-8"))
    return path


def write_csv(path: str | os.PathLike[str], rows: Sequence[Mapping[str, object]], what: str = "CSV file") -> Path:
    """Write ``rows`` (one mapping a row; the first row's keys are the header) as CSV to ``path`` atomically
    (:func:`write_text`); an empty file for no rows; returns the path."""
    handle = io.StringIO()
    if rows:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]), lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)
    return write_text(path, handle.getvalue(), what)


def replace_file(path: Path, data: bytes) -> None:
    """Write ``data`` to a temporary file beside ``path`` and rename it over ``path``: the old file stays
    whole until the new one is complete (see the module docstring)."""
    write_via(path, lambda temporary: temporary.write_bytes(data))


def write_via(path: Path, write: Callable[[Path], object]) -> None:
    """Let ``write(temporary)`` write the new file (a library's own writer, e.g. matplotlib's savefig,
    given a path with ``path``'s suffix), then rename it over ``path``; removes it on any failure."""
    target = _target(path)
    folder = target.parent
    _remove_stale(folder, target.name)
    while True:
        temporary = folder / f".{target.name}{_TEMPORARY}{os.getpid()}-{secrets.token_hex(4)}{target.suffix}"
        try:
            # 0o666 minus the umask: the permissions a plainly created file would get.
            # O_EXCL: never through a link (nor over a file) planted at the temporary's name.
            os.close(os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0), 0o666))
            break
        except FileExistsError:
            continue
        except OSError as error:
            raise ValueError(f"{path}: cannot write in {folder} ({error.strerror or error})") from None
    try:
        write(temporary)
        _keep_mode(target, temporary)
        os.replace(temporary, target)  # over the name itself: a link put there meanwhile is replaced, not followed
    except BaseException as error:
        temporary.unlink(missing_ok=True)
        if isinstance(error, OSError):
            raise ValueError(f"{path}: cannot write ({error.strerror or error})") from None
        raise


def writable_file(path: str | os.PathLike[str]) -> Path:
    """``path`` checked as a file the package may write (a new path or a regular writable file in an existing
    folder), before the work whose result goes there: a command writing several files checks them all first,
    so that none is written when another would be refused."""
    return _target(Path(path))


def _target(path: Path) -> Path:
    """``path``, checked to be a new path or a regular writable file in an existing folder: a symbolic link
    (followed or dangling, it would have the write land wherever it points), a folder, a FIFO or device is
    refused."""
    try:
        info = path.lstat()
    except FileNotFoundError:
        info = None
    except OSError as error:
        raise ValueError(f"{path}: cannot write ({error.strerror or error})") from None
    try:
        if info is not None and stat.S_ISLNK(info.st_mode):
            raise ValueError(f"{path}: a symbolic link; the package writes no file through a link (it would replace "
                             "whatever the link points to): give the file's own path")
        if info is not None and stat.S_ISDIR(info.st_mode):
            raise ValueError(f"{path}: is a folder; give a file name")
        if info is not None and not stat.S_ISREG(info.st_mode):
            raise ValueError(f"{path}: not a regular file (a FIFO, socket or device); give a file name")
        if not path.parent.is_dir():
            raise ValueError(f"{path}: folder {path.parent} does not exist")
        if info is not None and not os.access(path, os.W_OK):
            raise ValueError(f"{path}: not writable")
    except OSError as error:
        raise ValueError(f"{path}: cannot write ({error.strerror or error})") from None
    return path


def _keep_mode(target: Path, temporary: Path) -> None:
    """Give the new file the permissions of the regular file it replaces (none for a new path)."""
    try:
        info = target.lstat()
    except FileNotFoundError:
        return
    if stat.S_ISREG(info.st_mode):
        os.chmod(temporary, stat.S_IMODE(info.st_mode))


def _remove_stale(folder: Path, name: str) -> None:
    """Remove temporary files of ``name`` left by processes that no longer run (killed mid-write)."""
    prefix = f".{name}{_TEMPORARY}"
    try:
        candidates = [entry for entry in folder.iterdir() if entry.name.startswith(prefix)]
    except OSError:
        return
    for entry in candidates:
        pid = entry.name[len(prefix):].split("-", 1)[0]
        if pid.isdigit() and int(pid) != os.getpid() and not _running(int(pid)):
            entry.unlink(missing_ok=True)


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # another user's process, or no permission to ask: assume it runs
        return True
    return True
