"""The cache of a parameter study: finished points in a JSON Lines file.

Each line is one ``{"key": ..., "row": ...}`` object, written and flushed as soon as its
chunk of points finishes, so that an interrupted study keeps what it computed. JSON keeps a
float64 exactly, so a row read back is the row computed, bit for bit.
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path

__all__ = ["KEY_LENGTH", "PointCache", "point_key"]

#: Hexadecimal digits of a point's key (128 bits of SHA-256: collisions are out of reach).
KEY_LENGTH = 32


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


class PointCache:
    """Finished points in a JSON Lines file; ``path=None`` keeps nothing.

    Use as a context manager around the work: :meth:`add` appends while the file is open.

    Parameters
    ----------
    path : path-like or None
        The JSON Lines file (created if missing; its folder must exist).

    Raises
    ------
    FileNotFoundError
        If the folder of ``path`` does not exist.
    """

    def __init__(self, path: str | os.PathLike[str] | None) -> None:
        self.path = None if path is None else Path(path)
        self._file = None
        if self.path is not None and not self.path.parent.is_dir():
            raise FileNotFoundError(f"cache folder does not exist: {self.path.parent}")

    def done(self) -> dict[str, dict]:
        """Rows already computed, by key; a line cut short by an interruption is skipped
        (that point runs again)."""
        rows: dict[str, dict] = {}
        if self.path is None or not self.path.exists():
            return rows
        with open(self.path, encoding="utf-8") as fh:
            for line in fh:
                try:
                    entry = json.loads(line)
                    rows[entry["key"]] = entry["row"]
                except (json.JSONDecodeError, KeyError, TypeError):
                    continue
        return rows

    def __enter__(self) -> PointCache:
        if self.path is not None:
            self._file = open(self.path, "a", encoding="utf-8")
        return self

    def add(self, entries: list[tuple[str, dict]]) -> None:
        """Append ``(key, row)`` entries and flush them to the file."""
        if self._file is not None:
            for key, row in entries:
                self._file.write(json.dumps({"key": key, "row": row}) + "\n")
            self._file.flush()

    def __exit__(self, *exc) -> None:
        if self._file is not None:
            self._file.close()
