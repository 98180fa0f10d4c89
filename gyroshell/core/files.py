"""Output files: checked before any work, written whole or not at all, together.

* :func:`check_output` / :func:`check_outputs` refuse, before anything is computed, an output
  that could never be written: a missing or read-only folder, a parent that is a file, a path
  that is a folder or an existing read-only file, a plot format matplotlib cannot write, or
  one file named for two outputs. Messages name the path as the user gave it.
* :func:`atomic_path` writes to a hidden temporary file beside the real target (through
  symlinks, so the link is kept and its target updated) and moves it into place only on
  success; a replaced file keeps its permission bits.
* Inside :func:`transaction` every :func:`atomic_path` is staged and moved into place only
  when the whole block succeeds: a run with several outputs leaves none of them (and no
  temporary file) if any step fails or is interrupted.
* :func:`termination_signals` turns SIGTERM and SIGHUP into :class:`Terminated` (a
  ``KeyboardInterrupt``), so they clean up temporary files exactly like Ctrl-C.
"""

from __future__ import annotations

import contextvars
import os
import shutil
import signal
import stat
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

from .context import outermost
from .errors import InputFileError, MissingFileError, ParameterError

#: Kinds of output whose format is checked from the file name's suffix.
PLOT = "plot"
#: Plot formats (file suffixes) every supported matplotlib (>= 3.7) writes without extra
#: packages; checked without importing matplotlib, so a refusal stays fast.
PLOT_FORMATS: tuple[str, ...] = ("eps", "jpeg", "jpg", "pdf", "pgf", "png", "ps", "raw",
                                 "rgba", "svg", "svgz", "tif", "tiff", "webp")


class OutputPathError(ParameterError):
    """An output path that cannot be written; the message names the path."""


class Terminated(KeyboardInterrupt):
    """SIGTERM or SIGHUP, raised in the main thread so that cleanup runs as for Ctrl-C."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def read_csv_exact(path: str | os.PathLike[str], **kwargs):
    """pandas.read_csv that gives back every float bit for bit (floats written with 17
    significant digits): pandas 2 needs ``float_precision="round_trip"`` for that, pandas 3
    parses exactly by default and deprecates the option."""
    import pandas as pd

    if int(pd.__version__.split(".")[0]) < 3:
        kwargs.setdefault("float_precision", "round_trip")
    return pd.read_csv(path, **kwargs)


def _read_only(st: os.stat_result, path: str) -> bool:
    # Mode bits as well as access(): the superuser may write anywhere, but a file or folder
    # someone made read-only is meant to be left alone.
    return not (st.st_mode & 0o222) or not os.access(path, os.W_OK)


def check_output(path: str | os.PathLike[str], *, option: str = "output",
                 kind: str | None = None) -> Path:
    """Refuse an output path that could never be written; returns the file to write
    (symlinks resolved).

    Parameters
    ----------
    path : str or os.PathLike
        The path as the user gave it.
    option : str
        How the user named it (e.g. ``--plot``), for the message.
    kind : {None, "plot"} or tuple of str
        ``"plot"`` also checks that matplotlib can write the suffix's format; a tuple
        holds the suffixes allowed (``(".csv", ".parquet")``), any other is refused.

    Raises
    ------
    OutputPathError
        Naming ``option`` and ``path`` and why it cannot be written.
    """
    if not isinstance(path, (str, os.PathLike)) or not os.fspath(path):
        raise OutputPathError(f"{option} must be a file path, got {path!r}")
    shown = os.fspath(path)
    real = os.path.realpath(shown)
    folder = os.path.dirname(real) or "."

    def fail(reason: str) -> OutputPathError:
        return OutputPathError(f"{option} {shown}: {reason}")

    if os.path.isdir(real):
        raise fail("is a folder, not a file")
    if isinstance(kind, tuple) and Path(shown).suffix.lower() not in kind:
        raise OutputPathError(f"{option}: use a {' or '.join(kind)} file, got {shown}")
    if not os.path.exists(folder):
        raise fail(f"folder {os.path.dirname(shown) or '.'} does not exist")
    if not os.path.isdir(folder):
        raise fail(f"{os.path.dirname(shown)} is a file, not a folder")
    if _read_only(os.stat(folder), folder):
        raise fail(f"folder {os.path.dirname(shown) or '.'} is read-only")
    if os.path.lexists(real):
        st = os.stat(real)
        if not stat.S_ISREG(st.st_mode):
            raise fail("exists and is not a regular file; not replaced")
        if _read_only(st, real):
            raise fail("exists and is read-only; not replaced")
    if kind == PLOT:
        suffix = Path(shown).suffix.lower().lstrip(".")
        if suffix not in PLOT_FORMATS:
            raise fail(f"unsupported plot format {suffix!r} (use one of "
                       f"{', '.join(PLOT_FORMATS)})")
    return Path(real)


def check_output_folder(path: str | os.PathLike[str], *, option: str = "output folder"
                        ) -> Path:
    """Refuse an output folder that is a file, is read-only, or whose parent is missing or
    not a folder; returns it as a Path (created later, when the first file is written)."""
    if not isinstance(path, (str, os.PathLike)) or not os.fspath(path):
        raise OutputPathError(f"{option} must be a folder path, got {path!r}")
    shown = os.fspath(path)
    real = os.path.realpath(shown)
    if os.path.exists(real):
        if not os.path.isdir(real):
            raise OutputPathError(f"{option} {shown}: is a file, not a folder")
        if _read_only(os.stat(real), real):
            raise OutputPathError(f"{option} {shown}: folder is read-only")
        return Path(shown)
    parent = os.path.dirname(real) or "."
    while not os.path.exists(parent):
        parent = os.path.dirname(parent)
    if not os.path.isdir(parent):
        raise OutputPathError(f"{option} {shown}: {parent} is a file, not a folder")
    if _read_only(os.stat(parent), parent):
        raise OutputPathError(f"{option} {shown}: cannot create it, {parent} is read-only")
    return Path(shown)


def check_outputs(outputs: dict[str, tuple[str | os.PathLike[str] | None, str | None]]
                  ) -> dict[str, Path]:
    """Check several outputs {option: (path or None, kind)} (``kind`` as in
    :func:`check_output`); also refuse one file named twice.

    Returns {option: file to write} for the paths given.
    """
    checked: dict[str, Path] = {}
    for option, (path, kind) in outputs.items():
        if path is not None:
            checked[option] = check_output(path, option=option, kind=kind)
    seen: dict[Path, str] = {}
    for option, real in checked.items():
        if real in seen:
            raise OutputPathError(f"{seen[real]} and {option} name the same file "
                                  f"{os.fspath(outputs[option][0])}; give each its own")
        seen[real] = option
    return checked


def check_input(path: str | os.PathLike[str], *, what: str = "file") -> Path:
    """Refuse an input path that cannot be read as a file, before it is opened; returns it.

    Parameters
    ----------
    path : str or os.PathLike
        The path as the user gave it.
    what : str
        What the file should be (e.g. ``"TOML file"``, ``"NetCDF file"``), for the messages.

    Raises
    ------
    MissingFileError
        ``no such <what>: <path>`` (also a ``FileNotFoundError``).
    InputFileError
        A path that is not text, a folder (``<path> is a directory, not a <what>``) or
        something else that is not a regular file.
    """
    if not isinstance(path, (str, os.PathLike)) or not os.fspath(path):
        raise InputFileError(f"the {what} must be given as a file path, got {path!r}")
    shown = os.fspath(path)
    if isinstance(shown, bytes):
        shown = os.fsdecode(shown)
    if os.path.isdir(shown):
        raise InputFileError(f"{shown} is a directory, not a {what}")
    if not os.path.exists(shown):
        raise MissingFileError(f"no such {what}: {shown}")
    if not os.path.isfile(shown):
        raise InputFileError(f"{shown} is not a regular file, so not a {what}")
    return Path(shown)


def read_input(path: str | os.PathLike[str], *, what: str = "file") -> bytes:
    """The bytes of an input file, checked by :func:`check_input`; a file that cannot be
    read raises :class:`~gyroshell.core.errors.InputFileError` naming it."""
    checked = check_input(path, what=what)
    try:
        return checked.read_bytes()
    except OSError as exc:  # unreadable (permissions), or removed meanwhile
        raise InputFileError(f"{checked}: cannot read the {what} "
                             f"({exc.strerror or exc})") from None


def _default_mode() -> int:
    umask = os.umask(0)
    os.umask(umask)
    return 0o666 & ~umask


def _match_permissions(tmp: str, target: Path) -> None:
    """Give ``tmp`` the permissions (and owner, if allowed) of the file it replaces, or the
    usual ones for a new file (mkstemp makes 0600)."""
    try:
        st = os.stat(target)
    except FileNotFoundError:
        os.chmod(tmp, _default_mode())
        return
    os.chmod(tmp, stat.S_IMODE(st.st_mode))
    if hasattr(os, "chown"):
        try:
            os.chown(tmp, st.st_uid, st.st_gid)
        except OSError:
            pass


def _remove(path: str | None) -> None:
    if path is not None:
        try:
            os.remove(path)
        except FileNotFoundError:
            pass


class Transaction:
    """Staged outputs moved into place together by :meth:`commit` (see :func:`transaction`).
    """

    def __init__(self) -> None:
        self._staged: list[tuple[str, Path, str]] = []  # (temporary, target, user's path)

    def stage(self, tmp: str, target: Path, shown: str) -> None:
        for i, (old_tmp, old_target, _) in enumerate(self._staged):
            if old_target == target:  # written twice: the last version wins
                _remove(old_tmp)
                del self._staged[i]
                break
        self._staged.append((tmp, target, shown))

    def rollback(self) -> None:
        """Remove every staged temporary file."""
        staged, self._staged = self._staged, []
        for tmp, _, _ in staged:
            _remove(tmp)

    def commit(self) -> list[Path]:
        """Move every staged file into place; on any failure put back what was there."""
        done: list[tuple[Path, str | None]] = []  # (target, backup of the old file or None)
        staged, self._staged = self._staged, []
        try:
            for tmp, target, shown in staged:
                backup = None
                if os.path.lexists(target):
                    backup = _hidden_name(target, "old")
                    try:
                        os.link(target, backup)
                    except OSError:  # a file system without hard links
                        shutil.copy2(target, backup)
                try:
                    os.replace(tmp, target)
                except OSError as exc:
                    _remove(backup)
                    raise OSError(exc.errno, f"cannot write {shown}: {exc.strerror}"
                                  ) from None
                done.append((target, backup))
        except BaseException:
            for target, backup in reversed(done):
                if backup is None:
                    _remove(os.fspath(target))
                else:
                    os.replace(backup, target)
            for tmp, _, _ in staged:
                _remove(tmp)
            raise
        for _, backup in done:
            _remove(backup)
        return [target for _, target, _ in staged]


_ACTIVE: contextvars.ContextVar[Transaction | None] = contextvars.ContextVar(
    "gyroshell_output_transaction", default=None)


def _hidden_name(target: Path, tag: str) -> str:
    fd, name = tempfile.mkstemp(prefix=f".{target.name}.{tag}.", dir=target.parent)
    os.close(fd)
    os.remove(name)
    return name


@contextmanager
def transaction() -> Iterator[Transaction]:
    """Stage every :func:`atomic_path` write inside the block; move them all into place at
    its end, or none if it raises (including KeyboardInterrupt and :class:`Terminated`).

    Nested blocks join the outermost one.
    """
    with outermost(_ACTIVE, Transaction) as (current, owner):
        if not owner:
            yield current
            return
        try:
            yield current
        except BaseException:
            current.rollback()
            raise
    current.commit()


@contextmanager
def atomic_path(path: str | os.PathLike[str], *, option: str = "output",
                kind: str | None = None) -> Iterator[Path]:
    """Yield a temporary path beside ``path``'s real file; move it there only on success.

    The path is checked first (:func:`check_output`). Inside :func:`transaction` the file is
    staged and moved with the others when the transaction ends. An ``OSError`` while writing
    names ``path``, not the temporary file.
    """
    shown = os.fspath(path) if isinstance(path, (str, os.PathLike)) else str(path)
    target = check_output(path, option=option, kind=kind)
    tmp = None
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=target.suffix,
                                   dir=target.parent)
        os.close(fd)
        try:
            yield Path(tmp)
        except OSError as exc:  # name the user's file, not the hidden temporary one
            raise OSError(exc.errno, f"cannot write {shown}: {exc.strerror or exc}"
                          ) from None
        _match_permissions(tmp, target)
        active = _ACTIVE.get()
        if active is not None:
            active.stage(tmp, target, shown)
            tmp = None
        else:
            try:
                os.replace(tmp, target)
            except OSError as exc:
                raise OSError(exc.errno, f"cannot write {shown}: {exc.strerror}") from None
            tmp = None
    finally:
        _remove(tmp)


def write_atomic(path: str | os.PathLike[str], writer: Callable[[Path], object], *,
                 option: str = "output", kind: str | None = None) -> Path:
    """Call ``writer(tmp_path)`` and move the result onto ``path`` (whole or nothing)."""
    with atomic_path(path, option=option, kind=kind) as tmp:
        writer(tmp)
    return Path(path)


@contextmanager
def termination_signals() -> Iterator[None]:
    """Within the block, SIGTERM and SIGHUP raise :class:`Terminated` in the main thread
    (like SIGINT raises KeyboardInterrupt), so ``finally`` blocks remove temporary files.
    Does nothing outside the main thread."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def raise_terminated(signum, frame):
        raise Terminated(signum)

    previous = {}
    for name in ("SIGTERM", "SIGHUP"):
        signum = getattr(signal, name, None)
        if signum is not None:
            previous[signum] = signal.signal(signum, raise_terminated)
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)


@contextmanager
def folder_transaction(folder: str | os.PathLike[str]) -> Iterator[Path]:
    """:func:`transaction` for a run that writes into ``folder``: creates it (and missing
    parents); if the block raises, no file is moved in and the folders it created are
    removed again (deepest first, while empty)."""
    folder = Path(folder)
    created = []
    probe = folder
    while not probe.exists() and probe != probe.parent:
        created.append(probe)
        probe = probe.parent
    try:
        with transaction():
            folder.mkdir(parents=True, exist_ok=True)
            yield folder
    except BaseException:
        for made in created:
            try:
                made.rmdir()
            except OSError:
                break
        raise


def check_output_folder_with_files(path: str | os.PathLike[str], files: tuple[str, ...] = (),
                                   *, option: str = "output folder") -> Path:
    """Refuse, before any work, an output folder that could not take ``files``: what
    :func:`check_output_folder` refuses, a missing parent (only the folder itself is created
    later, like ``mkdir`` without ``-p``), and, in a folder that exists, any of ``files``
    (names inside it) that :func:`check_output` refuses (read-only, a folder, not a regular
    file). Returns the folder as a Path.

    Raises
    ------
    OutputPathError
        Naming ``option`` and the folder or file as the user gave it.
    """
    folder = check_output_folder(path, option=option)
    shown = os.fspath(path)
    real = os.path.realpath(shown)
    if not os.path.isdir(real):
        parent = os.path.dirname(real) or "."
        if not os.path.isdir(parent):
            above = os.path.dirname(os.path.normpath(shown)) or "."
            raise OutputPathError(f"{option} {shown}: folder {above} does not exist")
        return folder
    for name in files:
        check_output(os.path.join(shown, name), option=option)
    return folder
