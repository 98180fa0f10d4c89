"""The one pyplot import and the one figure saver of gyroshell, and the helpers every
drawing shares (a new Axes, mm coordinates, the table of a result)."""

from __future__ import annotations

import numpy as np


def pyplot(path=None, *, headless: bool = False):
    """matplotlib.pyplot, imported on first use (never at ``import gyroshell``).

    ``headless``: the figures are only ever written to files (``gyroshell reproduce``):
    the Agg back-end, if it can still be selected. ``path``: a figure is about to be
    written there: Agg when there is no display.
    """
    import matplotlib

    if headless:
        matplotlib.use("Agg", force=False)
    elif path is not None:
        import os

        if not os.environ.get("DISPLAY") and matplotlib.get_backend().lower() != "agg":
            matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig, path, *, dpi: int, tight: bool = False, file_format: str | None = None,
                close: bool = True, option: str = "output"):
    """Write a matplotlib figure to ``path``, whole or not at all; returns the path.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    path : str or os.PathLike
        The file; its suffix gives the format unless ``file_format`` is set.
    dpi : int
        Resolution, dots per inch (each caller keeps its own, so its files stay the same).
    tight : bool
        Crop to the drawn content (``bbox_inches="tight"``).
    file_format : str, optional
        Format regardless of the suffix (e.g. ``"png"``).
    close : bool
        Close the figure afterwards (also if writing failed), freeing its memory.
    option : str
        The option naming the file in error messages (e.g. ``"--plot"``).
    """
    from pathlib import Path

    from ..core.files import write_atomic

    options: dict = {"dpi": dpi}
    if file_format is not None:
        options["format"] = file_format
    if tight:
        options["bbox_inches"] = "tight"
    try:
        write_atomic(path, lambda tmp: fig.savefig(tmp, **options), option=option)
    finally:
        if close:
            pyplot().close(fig)
    return Path(path)


def _axes(ax, figsize=(7.0, 4.5)):
    if ax is not None:
        return ax
    plt = pyplot()
    _, ax = plt.subplots(figsize=figsize, constrained_layout=True)
    return ax


def _mm(values) -> np.ndarray:
    return 1e3 * np.asarray(values)


def _table(result):
    """The table of a result that holds one (``.table``), or the table itself."""
    return result.table if hasattr(result, "table") else result
