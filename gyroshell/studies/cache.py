"""The cache of a parameter study: finished points in a JSON Lines file.

Each line is one ``{"key": ..., "row": ...}`` object (``key``: :data:`KEY_LENGTH`
hexadecimal digits, :func:`point_key`; ``row``: the point's computed columns), written and
flushed as soon as its chunk of points finishes, so that an interrupted study keeps what it
computed. JSON keeps a float64 exactly, so a row read back is the row computed, bit for bit.

What is read back is checked as strictly as what is computed: a file that is not UTF-8
text, a line that is not such an object, or a row of this study whose columns or values are
not what the study computes (``"critical_speed": "fast"``) is refused, naming the file and
the line, and the file is left as it was. Only a last line cut short by an interruption
(no newline, not JSON) is skipped: its point runs again, and the cut line is dropped before
new lines are appended.

Several studies may share one cache, at once: each appends whole lines in one write under
an exclusive lock of the file (``fcntl.flock``; where there is none, on Windows, one
writer at a time) and reads it under a shared one, and a cut last line is dropped only as
found at the moment of writing, under that lock, so that what another study appended
since this one read the file is kept. A write that fails (a full disk) is undone to the
last whole line and reported as an OSError naming the file.
"""

from __future__ import annotations

import errno
import hashlib
import json
import os
import re
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows: no advisory locks
    fcntl = None

from ..core.errors import ParameterError

__all__ = ["KEY_LENGTH", "PointCache", "file_digest", "point_key"]

#: Hexadecimal digits of a point's key (128 bits of SHA-256: collisions are out of reach).
KEY_LENGTH = 32
_KEY = re.compile(f"^[0-9a-f]{{{KEY_LENGTH}}}$")
#: What the user can do about a refused cache line, and about a refused cache file.
_REMEDY = "remove that line (or the file) or give another cache path"
_FILE_REMEDY = "remove it or give another cache path"
#: What a study that could not write its cache may do: on a full disk, and otherwise.
_FULL_REMEDY = ("the points it holds are kept: free some space and run the study again to "
                "resume")
_WRITE_REMEDY = "the points it holds are kept: run the study again to resume"
#: Errors of a lock the file system does not keep (some network file systems): go on
#: without it, as where there are no locks at all.
_NO_LOCKS = (errno.ENOLCK, errno.EOPNOTSUPP, errno.ENOSYS, errno.EINVAL)
#: Bytes read at a time looking back for the last line's start.
_TAIL_CHUNK = 4096


def point_key(spec: str, point: dict) -> str:
    """The cache key of ``point`` in the study described by ``spec`` (a JSON text of
    everything else that decides the point's row).

    Examples
    --------
    >>> len(point_key("[]", {"tension": 80.0}))
    32
    >>> point_key("[]", {"a": 1, "b": 2}) == point_key("[]", {"b": 2, "a": 1})
    True
    """
    text = spec + json.dumps(point, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:KEY_LENGTH]


def file_digest(path: str | os.PathLike[str]) -> str:
    """The SHA-256 of a file's content (hexadecimal): an input file's part of a cache key,
    so that a file edited in place is not taken for the one the cached rows were computed
    from.

    Raises
    ------
    ParameterError
        Naming the file, if it cannot be read.
    """
    digest = hashlib.sha256()
    try:
        with open(path, "rb") as fh:
            for block in iter(lambda: fh.read(1 << 20), b""):
                digest.update(block)
    except OSError as exc:
        raise ParameterError(f"{os.fspath(path)}: cannot read it to key the study's cache "
                             f"({exc.strerror or exc})") from None
    return digest.hexdigest()


class PointCache:
    """Finished points in a JSON Lines file; ``path=None`` keeps nothing.

    Use as a context manager around the work: :meth:`add` appends while the file is open.

    Parameters
    ----------
    path : path-like or None
        The JSON Lines file (created if missing; its folder must exist).

    Raises
    ------
    ParameterError
        If the folder of ``path`` does not exist, or ``path`` is a folder.
    """

    def __init__(self, path: str | os.PathLike[str] | None) -> None:
        self.path = None if path is None else Path(path)
        self._fd: int | None = None  # opened for appending at the first entry
        if self.path is None:
            return
        if not self.path.parent.is_dir():
            raise ParameterError(f"cache {self.path}: folder {self.path.parent} does not "
                                 "exist")
        if self.path.exists() and not self.path.is_file():
            raise ParameterError(f"cache {self.path} is not a file (a folder?); give a "
                                 "FILE.jsonl path")

    def done(self, check: Callable[[str, dict], dict] | None = None) -> dict[str, dict]:
        """Rows already computed, by key.

        ``check(key, row)`` returns the row as the study uses it or raises ParameterError
        (for the keys of this study; rows of other studies sharing the file pass through).
        A last line cut short by an interruption is skipped (that point runs again).

        Raises
        ------
        ParameterError
            Naming the file and the line: not UTF-8 text, a line that is not a
            ``{"key", "row"}`` object, or a row ``check`` refuses.
        """
        rows: dict[str, dict] = {}
        if self.path is None or not self.path.exists():
            return rows
        lines = self._lines()
        for number, line in enumerate(lines, start=1):
            if not line.strip():
                continue
            last = number == len(lines) and not line.endswith("\n")
            entry = self._entry(line, number, last)
            if entry is None:
                continue
            key, row = entry
            if check is not None:
                try:
                    row = check(key, row)
                except ParameterError as exc:
                    raise ParameterError(f"cache {self.path} line {number}: {exc}; the file "
                                         f"was edited or damaged: {_REMEDY}") from None
            rows[key] = row
        return rows

    def _lines(self) -> list[str]:
        """The file's lines (with their newlines), as text."""
        try:
            with open(self.path, "rb") as fh, _locked(fh.fileno(), shared=True):
                data = fh.read()
        except OSError as exc:
            raise ParameterError(f"cache {self.path}: cannot read it ({exc.strerror})"
                                 ) from None
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as exc:
            raise ParameterError(f"cache {self.path} is not a study cache: byte {exc.start} "
                                 f"is not UTF-8 text (a binary file?); {_FILE_REMEDY}") from None
        if "\x00" in text:
            raise ParameterError(f"cache {self.path} is not a study cache: it holds NUL "
                                 f"bytes (a binary file?); {_FILE_REMEDY}")
        parts = text.split("\n")  # JSON Lines break at "\n" only
        return [part + "\n" for part in parts[:-1]] + ([parts[-1]] if parts[-1] else [])

    def _entry(self, line: str, number: int, last: bool) -> tuple[str, dict] | None:
        """(key, row) of one line; None for a last line cut short."""
        where = f"cache {self.path} line {number}"
        try:
            entry = json.loads(line)
        except json.JSONDecodeError as exc:
            if last:  # cut short by an interruption: dropped before appending (_append)
                return None
            raise ParameterError(f"{where} is not JSON ({exc.msg}); {_REMEDY}") from None
        if not isinstance(entry, dict) or set(entry) != {"key", "row"}:
            got = sorted(entry) if isinstance(entry, dict) else type(entry).__name__
            raise ParameterError(f"{where} must be an object with the fields key and row, "
                                 f"got {got}; {_REMEDY}")
        key, row = entry["key"], entry["row"]
        if not isinstance(key, str) or not _KEY.match(key):
            raise ParameterError(f"{where}: key must be {KEY_LENGTH} hexadecimal digits, got "
                                 f"{key!r}; {_REMEDY}")
        if not isinstance(row, dict):
            raise ParameterError(f"{where}: row must be an object (column: value), got "
                                 f"{type(row).__name__}; {_REMEDY}")
        return key, row

    def __enter__(self) -> PointCache:
        return self

    def _open(self) -> None:
        """Open the file for appending, at the first entry: a study refused before it
        finishes a point leaves the file as it was."""
        try:
            self._fd = os.open(self.path, os.O_RDWR | os.O_APPEND | os.O_CREAT, 0o666)
        except OSError as exc:
            raise _write_error(self.path, exc) from None

    def add(self, entries: list[tuple[str, dict]]) -> None:
        """Append ``(key, row)`` entries to the file, whole lines in one write.

        Raises
        ------
        OSError
            The file could not be written (a full disk), naming it; the lines written
            before are kept whole.
        """
        if self.path is None or not entries:
            return
        if self._fd is None:
            self._open()
        data = "".join(json.dumps({"key": key, "row": row}) + "\n" for key, row in entries)
        try:
            with _locked(self._fd):
                _append(self._fd, data.encode("utf-8"))
        except OSError as exc:
            raise _write_error(self.path, exc) from None

    def __exit__(self, *exc) -> None:
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None


@contextmanager
def _locked(fd: int, *, shared: bool = False) -> Iterator[None]:
    """Hold an advisory lock of the open file ``fd`` (shared to read, exclusive to write)."""
    if fcntl is None:  # pragma: no cover - Windows
        yield
        return
    try:
        fcntl.flock(fd, fcntl.LOCK_SH if shared else fcntl.LOCK_EX)
    except OSError as exc:  # pragma: no cover - a file system without locks
        if exc.errno not in _NO_LOCKS:
            raise
        yield
        return
    try:
        yield
    finally:
        fcntl.flock(fd, fcntl.LOCK_UN)


def _append(fd: int, data: bytes) -> None:
    """Append ``data`` (whole lines) to the locked file ``fd``: a last line cut short is
    dropped first (one that is JSON gets its newline); a failed write is undone."""
    end = os.fstat(fd).st_size
    start, tail = _last_line(fd, end)
    if tail:
        try:
            json.loads(tail.decode("utf-8"))
        except (UnicodeDecodeError, json.JSONDecodeError):  # cut by an interruption
            os.ftruncate(fd, start)
            end = start
        else:
            data = b"\n" + data
    try:
        view = memoryview(data)
        while view:
            view = view[os.write(fd, view):]
    except OSError:
        try:
            os.ftruncate(fd, end)
        except OSError:  # pragma: no cover - the next reader skips a cut last line
            pass
        raise


def _last_line(fd: int, end: int) -> tuple[int, bytes]:
    """(offset, bytes) of what follows the last newline of the first ``end`` bytes of
    ``fd`` (empty if the file is empty or ends in a newline)."""
    tail, position = b"", end
    while position > 0:
        size = min(_TAIL_CHUNK, position)
        position -= size
        chunk = os.pread(fd, size, position)
        cut = chunk.rfind(b"\n")
        if cut >= 0:
            return position + cut + 1, chunk[cut + 1:] + tail
        tail = chunk + tail
    return 0, tail


def _write_error(path: Path, exc: OSError) -> OSError:
    """The one-line OSError of a cache that could not be written."""
    full = exc.errno in (errno.ENOSPC, errno.EDQUOT)
    return OSError(exc.errno, f"cannot write the study cache {path}: "
                              f"{exc.strerror or exc}; {_FULL_REMEDY if full else _WRITE_REMEDY}")
