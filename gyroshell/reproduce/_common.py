"""Shared pieces of the studies: settings (full or quick), atomic CSV/PNG/Markdown output."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from .. import plot
from ..core.files import write_atomic
from ..results.base import write_table
from ..tape.parameters import TapeParameters

if TYPE_CHECKING:  # pandas loads when a study runs, not when the CLI starts
    import pandas as pd

#: Time step of the paper's runs (Table 1's "2x10^6 s" is 2e-6 s), s.
PAPER_DT = 2.0e-6
#: Intervals across the width in quick mode (the paper's grid has 41).
QUICK_INTERVALS = 12


@dataclass(frozen=True)
class Settings:
    """How a study runs.

    Parameters
    ----------
    quick : bool
        Coarse grid (12 intervals across instead of 41) and short records: the same code
        path in seconds, for tests and previews. Numbers are then not the paper's.
    progress : bool or None
        Progress bars on long runs; None: only when stderr is a terminal.
    """

    quick: bool = False
    progress: bool | None = None

    def params(self, **changes: object) -> TapeParameters:
        """Table 1 parameters with ``changes``; coarse spacing in quick mode."""
        p = TapeParameters(**changes)
        if self.quick:
            p = p.replace(spacing=p.width / QUICK_INTERVALS)
        return p

    def pick(self, full, quick):
        """``quick`` in quick mode, else ``full``."""
        return quick if self.quick else full


def save_csv(frame: pd.DataFrame, path: Path) -> Path:
    """Write ``frame`` as CSV (no index, ``NaN`` for missing), whole or not at all
    (:func:`gyroshell.results.base.write_table`)."""
    return write_table(frame, path)


def markdown_table(frame: pd.DataFrame, floatfmt: str = ".6g") -> str:
    """A GitHub Markdown table of ``frame`` (no extra dependency)."""
    def cell(v) -> str:
        if isinstance(v, float):
            return "" if v != v else format(v, floatfmt)
        return str(v)

    lines = ["| " + " | ".join(map(str, frame.columns)) + " |",
             "|" + "|".join("---" for _ in frame.columns) + "|"]
    lines += ["| " + " | ".join(cell(v) for v in row) + " |"
              for row in frame.itertuples(index=False)]
    return "\n".join(lines) + "\n"


def save_markdown(frame: pd.DataFrame, path: Path, title: str = "") -> Path:
    text = (f"{title}\n\n" if title else "") + markdown_table(frame)
    return write_atomic(path, lambda tmp: tmp.write_text(text))


#: Resolution of the studies' PNG files, dots per inch.
FIGURE_DPI = 110


def save_figure(fig, path: Path, dpi: int = FIGURE_DPI) -> Path:
    """Save a matplotlib figure as PNG cropped to its content, whole or not at all, and
    close it (:func:`gyroshell.plot.save_figure`)."""
    return plot.save_figure(fig, path, dpi=dpi, tight=True, file_format="png")


def pyplot():
    """matplotlib.pyplot for figures only written to files (:func:`gyroshell.plot.pyplot`)."""
    return plot.pyplot(headless=True)
