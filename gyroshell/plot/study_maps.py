"""Parameter studies: stability maps over two varied parameters, a quantity against one."""

from __future__ import annotations

import numpy as np

from ..core.errors import ParameterError
from ..core.units import axis_label
from .figures import _axes, _table

#: Colours of the stability classes (colour-blind safe pairs).
STABILITY_COLOURS = {"stable": "#4daf4a", "divergence": "#e41a1c", "flutter": "#377eb8",
                     "undetermined": "#bbbbbb", "": "#ffffff"}


def stability_map(study, *, x: str | None = None, y: str | None = None, ax=None,
                  title: str | None = None):
    """Stable / divergence / flutter over two varied parameters of a study.

    ``study`` is a :class:`~gyroshell.StudyResult` (or its table); ``x`` and ``y``
    default to the first two varied parameters (x: the first). Each point is a coloured
    cell; the critical speed, if computed and x or y is the velocity, is drawn over it.
    """
    table = _table(study)
    varied = list(getattr(study, "varied", ()))
    x = x or (varied[0] if varied else None)
    y = y or (varied[1] if len(varied) > 1 else None)
    if x is None or y is None or x not in table or y not in table:
        raise ParameterError("stability_map needs two varied parameters (x, y)")
    if "stability" not in table:
        raise ParameterError("stability_map needs a 'stability' column: compute modes")
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    ax = _axes(ax)
    xv, xs, xticks = _positions(table[x])
    yv, ys, yticks = _positions(table[y])
    classes = list(STABILITY_COLOURS)
    grid = np.full((len(ys), len(xs)), classes.index(""), dtype=float)
    for a, b, s in zip(xv, yv, table["stability"], strict=True):
        grid[np.searchsorted(ys, b), np.searchsorted(xs, a)] = classes.index(s)
    if xticks is not None:
        ax.set_xticks(xs, xticks)
    if yticks is not None:
        ax.set_yticks(ys, yticks)
    cmap = ListedColormap([STABILITY_COLOURS[c] for c in classes])
    ax.pcolormesh(_edges(xs), _edges(ys), grid, cmap=cmap, vmin=-0.5,
                  vmax=len(classes) - 0.5, shading="flat", edgecolors="w", linewidth=0.3)
    present = [c for c in classes if c and (table["stability"] == c).any()]
    handles = [Patch(color=STABILITY_COLOURS[c], label=c) for c in present]
    other = y if x == "velocity" else x
    if ("critical_speed" in table and "velocity" in (x, y)
            and table[other].dtype.kind in "fiu"):
        crit = table.groupby(other)["critical_speed"].first().dropna()
        if len(crit):
            cx, cy = (crit.to_numpy(), crit.index.to_numpy()) if x == "velocity" else (
                crit.index.to_numpy(), crit.to_numpy())
            (line,) = ax.plot(cx, cy, "k-", lw=1.5, label="critical speed")
            handles.append(line)
    ax.legend(handles=handles, fontsize=8, loc="best", framealpha=0.9)
    ax.set_xlabel(axis_label(x))
    ax.set_ylabel(axis_label(y))
    ax.set_title(title or "Stability of the moving tape")
    return ax


def study_lines(study, *, quantity: str | None = None, x: str | None = None, ax=None,
                title: str | None = None):
    """A computed column against a varied parameter (one line per value of any other).

    ``quantity`` defaults to the first computed number of the study."""
    table = _table(study)
    varied = list(getattr(study, "varied", ()))
    x = x or (varied[0] if varied else None)
    if x is None or x not in table:
        raise ParameterError("study_lines needs the varied parameter x")
    if quantity is None:
        numeric = _computed_columns(table, varied) if getattr(study, "compute", ()) else []
        if not numeric:
            raise ParameterError("study_lines needs a quantity column")
        quantity = numeric[0]
    if quantity not in table:
        raise ParameterError(f"no column {quantity!r} in the study")
    ax = _axes(ax)
    others = [v for v in varied if v != x]
    groups = table.groupby(others) if others else [((), table)]
    for key, group in groups:
        group = group.sort_values(x)
        label = None
        if others:
            key = key if isinstance(key, tuple) else (key,)
            label = ", ".join(f"{n} = {k:g}" if isinstance(k, float) else f"{n} = {k}"
                              for n, k in zip(others, key, strict=True))
        ax.plot(group[x], group[quantity], "-o", ms=3, label=label)
    ax.set_xlabel(axis_label(x))
    ax.set_ylabel(axis_label(quantity))
    ax.grid(True, alpha=0.3)
    if others:
        ax.legend(fontsize=8)
    if title:
        ax.set_title(title)
    return ax


#: Study columns that are neither varied nor computed numbers.
_NOT_QUANTITIES = ("point", "stability", "error")


def _computed_columns(table, varied) -> list[str]:
    """The computed number columns of a study's table, in its order (a study's table holds
    ``point``, the varied parameters, then what was computed)."""
    return [c for c in table.columns if c not in varied and c not in _NOT_QUANTITIES]


def _positions(column):
    """(values, sorted unique values, tick labels or None): text (e.g. ``edges``) is placed
    at 0, 1, 2, ... with its words as tick labels."""
    if column.dtype.kind in "fiu":
        values = column.to_numpy(float)
        return values, np.unique(values), None
    words = sorted(set(column.astype(str)))
    values = np.array([words.index(w) for w in column.astype(str)], dtype=float)
    return values, np.arange(len(words), dtype=float), words


def _edges(centres: np.ndarray) -> np.ndarray:
    """Cell edges around sorted centres (midpoints; half a step beyond the ends)."""
    if len(centres) == 1:
        return np.array([centres[0] - 0.5, centres[0] + 0.5])
    mid = 0.5 * (centres[1:] + centres[:-1])
    return np.concatenate([[2 * centres[0] - mid[0]], mid, [2 * centres[-1] - mid[-1]]])
