"""Parameter studies: maps of a quantity or of the stability over two varied parameters, a
quantity against one.

Values are shown in the units a user reads them in: angles (the head's wraps) in degrees,
lengths in m, mm, µm or nm by their size; every other quantity in SI. A bearing study
with transducers shows by default :data:`TRANSDUCER_MIN_SPACING`, the smallest spacing
along any transducer line.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import ParameterError
from ..core.units import display_unit, unit_of
from .figures import _axes, _table

#: The quantity a bearing study with transducers maps by default: at each point the
#: smallest of the ``transducer_<i>_min_spacing`` columns (m), the closest any transducer
#: line comes to the tape.
TRANSDUCER_MIN_SPACING = "transducer_min_spacing"
#: How derived quantities are labelled.
_DERIVED_LABELS = {TRANSDUCER_MIN_SPACING: "minimum spacing at the transducers"}
#: Display units of lengths, largest first: (unit, factor from m, smallest value shown).
_LENGTH_UNITS = (("m", 1.0, 1.0), ("mm", 1e3, 1e-3), ("µm", 1e6, 1e-6), ("nm", 1e9, 0.0))
#: A map's axis has a tick at each value up to this many values ...
MAX_TICKED = 12
#: ... and its cells are labelled with their values up to this many cells.
MAX_ANNOTATED = 60
#: Columns of a bearing study whose unit is N, or N/m for the infinitely wide tape.
_FORCE_COLUMNS = ("contact_force", "viscous_drag", "friction_drag", "drag")

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
    (xs, xlabel), (ys, ylabel) = _axis(study, x, xs, xticks), _axis(study, y, ys, yticks)
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
            factor = display_scale(study, other, table[other])[0]
            cx, cy = (crit.to_numpy(), factor * crit.index.to_numpy()) if x == "velocity" \
                else (factor * crit.index.to_numpy(), crit.to_numpy())
            (line,) = ax.plot(cx, cy, "k-", lw=1.5, label="critical speed")
            handles.append(line)
    ax.legend(handles=handles, fontsize=8, loc="best", framealpha=0.9)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title or "Stability of the moving tape")
    return ax


def study_lines(study, *, quantity: str | None = None, x: str | None = None, ax=None,
                title: str | None = None):
    """A computed quantity against a varied parameter (one line per value of any other),
    angles in degrees and lengths in the unit of their size.

    ``quantity`` defaults to :func:`default_quantity` (the transducers' minimum spacing of
    a bearing study with transducers, else the first computed number of the study)."""
    table = _table(study)
    varied = list(getattr(study, "varied", ()))
    x = x or (varied[0] if varied else None)
    if x is None or x not in table:
        raise ParameterError("study_lines needs the varied parameter x")
    quantity = default_quantity(study) if quantity is None else quantity
    values = quantity_values(study, quantity)
    ax = _axes(ax)
    others = [v for v in varied if v != x]
    groups = table.groupby(others) if others else [((), table)]
    ys_all, ylabel = shown(study, quantity, values)
    numeric_x = table[x].dtype.kind in "fiu"
    xs_all, xlabel = shown(study, x, table[x]) if numeric_x else (table[x].to_numpy(), x)
    for key, group in groups:
        rows = table.index.get_indexer(group.sort_values(x).index)
        label = None
        if others:
            key = key if isinstance(key, tuple) else (key,)
            label = ", ".join(_value_text(study, n, k, table[n])
                              for n, k in zip(others, key, strict=True))
        ax.plot(xs_all[rows], ys_all[rows], "-o", ms=3, label=label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    if others:
        ax.legend(fontsize=8)
    if title:
        ax.set_title(title)
    return ax


def _value_text(study, name: str, value, column) -> str:
    """``name = value`` as a legend shows it: in the unit the whole ``column`` is shown in
    (angles in degrees)."""
    if not isinstance(value, (float, int, np.floating, np.integer)) or isinstance(value, bool):
        return f"{name} = {value}"
    factor, label = display_scale(study, name, column)
    unit = label.rsplit(" (", 1)[1].rstrip(")") if " (" in label else ""
    return f"{name} = {factor * float(value):g}{' ' + unit if unit else ''}"


#: Study columns that are neither varied nor computed numbers.
_NOT_QUANTITIES = ("point", "stability", "error")


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


def _transducer_columns(columns) -> list[str]:
    """The ``transducer_<i>_min_spacing`` among a bearing study's table's columns."""
    return [c for c in columns
            if c.startswith("transducer_") and c.endswith("_min_spacing")
            and c[len("transducer_"):-len("_min_spacing")].isdigit()]


def quantities(study) -> list[str]:
    """The quantities a study can plot: :data:`TRANSDUCER_MIN_SPACING` for a bearing study
    with transducers, then its computed number columns (:func:`plottable`)."""
    return plottable(list(_table(study).columns), getattr(study, "varied", ()))


def plottable(columns, varied) -> list[str]:
    """The quantities of a study's table with these ``columns`` and ``varied``
    parameters: :data:`TRANSDUCER_MIN_SPACING` if it has transducer lines, then each
    computed number column (not ``point``, ``stability`` or ``error``).

    Examples
    --------
    >>> plottable(["point", "wrap", "central_spacing", "transducer_1_min_spacing",
    ...            "error"], ["wrap"])
    ['transducer_min_spacing', 'central_spacing', 'transducer_1_min_spacing']
    """
    columns = list(columns)
    derived = [TRANSDUCER_MIN_SPACING] if _transducer_columns(columns) else []
    return derived + [c for c in columns if c not in varied and c not in _NOT_QUANTITIES]


def default_quantity(study) -> str:
    """What a study's plot shows unless told: the transducers' minimum spacing for a
    bearing study with transducers, else the first computed number.

    Raises
    ------
    ParameterError
        If the study computed no number.
    """
    table = _table(study)
    if _transducer_columns(table.columns):
        return TRANSDUCER_MIN_SPACING
    names = quantities(study) if getattr(study, "compute", ()) else []
    if not names:
        raise ParameterError("a study plot needs a quantity column (a computed number)")
    return names[0]


def quantity_values(study, quantity: str) -> np.ndarray:
    """The values of ``quantity`` (a column or :data:`TRANSDUCER_MIN_SPACING`), one per
    row, float (NaN where the point failed).

    Raises
    ------
    ParameterError
        For a quantity the study has not, listing those it has.
    """
    table = _table(study)
    lines = _transducer_columns(table.columns)
    if quantity == TRANSDUCER_MIN_SPACING and lines:
        return table[lines].to_numpy(float).min(axis=1)
    if quantity not in table or quantity in getattr(study, "varied", ()):
        raise ParameterError(f"no quantity {quantity!r} in the study: choose one of "
                             f"{', '.join(quantities(study))}")
    if table[quantity].dtype.kind not in "fiu":
        raise ParameterError(f"{quantity!r} is not a number: choose one of "
                             f"{', '.join(quantities(study))}")
    return table[quantity].to_numpy(float)


def _unit(study, name: str) -> str | None:
    """The SI unit of a column of the study (a bearing force per unit width when the
    study's tape is infinitely wide)."""
    if name in _FORCE_COLUMNS or (name.startswith("corner_") and name.endswith("_force")):
        wide = bool((getattr(study, "bearing", None) or {}).get("infinitely_wide"))
        return "N/m" if wide else "N"
    if name == TRANSDUCER_MIN_SPACING or name.endswith(("_spacing", "_tent_height",
                                                        "_tent_x")):
        return "m"
    return unit_of(name)


def display_scale(study, name: str, values) -> tuple[float, str]:
    """(factor, axis label) of a quantity as a plot shows it: radians in degrees, lengths
    in the unit of the largest of ``values`` (m, mm, µm, nm), other quantities in SI."""
    unit = _unit(study, name)
    text = _DERIVED_LABELS.get(name, name.replace("_", " "))
    if unit == "rad":
        return float(np.degrees(1.0)), f"{text} (deg)"
    if unit == "m":
        values = np.asarray(values, dtype=float)
        finite = np.abs(values[np.isfinite(values)])
        size = float(finite.max()) if finite.size else 1.0
        unit, factor, _low = next(u for u in _LENGTH_UNITS if size >= u[2])
        return factor, f"{text} ({unit})"
    if unit is None or unit == "1":
        return 1.0, text
    return 1.0, f"{text} ({display_unit(unit)})"


def shown(study, name: str, values) -> tuple[np.ndarray, str]:
    """(values, axis label) as a plot shows them (:func:`display_scale`)."""
    values = np.asarray(values, dtype=float)
    factor, label = display_scale(study, name, values)
    return values * factor, label


def study_map(study, quantity: str | None = None, *, x: str | None = None,
              y: str | None = None, ax=None, title: str | None = None, cmap: str = "viridis"):
    """A computed quantity over two varied parameters: one coloured cell per point, a
    colour bar, and the axes labelled with their units (angles in degrees).

    Parameters
    ----------
    study : StudyResult
        Or its table with ``quantity``, ``x`` and ``y`` given.
    quantity : str, optional
        A computed column (:func:`quantities`); default :func:`default_quantity` (the
        transducers' minimum spacing for a bearing study with transducers).
    x, y : str, optional
        The varied parameters along each axis (default: the first two, x the first).
    ax : matplotlib Axes, optional
    title : str, optional
    cmap : str
        The colour map; points that failed are left grey.

    Returns
    -------
    matplotlib.axes.Axes (a ParameterError without two varied parameters, for an unknown
    quantity, listing the study's, or if two points share the same varied values)
    """
    table = _table(study)
    varied = list(getattr(study, "varied", ()))
    x = x or (varied[0] if varied else None)
    y = y or (varied[1] if len(varied) > 1 else None)
    if x is None or y is None or x not in table or y not in table or x == y:
        raise ParameterError("study_map needs two varied parameters (x, y)")
    if table.duplicated([x, y]).any():
        raise ParameterError(f"points repeat the same ({x}, {y}): study_map needs one "
                             "point per pair; choose x and y among all the varied "
                             "parameters")
    quantity = default_quantity(study) if quantity is None else quantity
    values = quantity_values(study, quantity)
    import matplotlib as mpl

    ax = _axes(ax)
    xv, xs, xticks = _positions(table[x])
    yv, ys, yticks = _positions(table[y])
    grid = np.full((len(ys), len(xs)), np.nan)
    grid[np.searchsorted(ys, yv), np.searchsorted(xs, xv)] = values
    shown_grid, label = shown(study, quantity, grid)
    (xs_shown, xlabel), (ys_shown, ylabel) = _axis(study, x, xs, xticks), _axis(study, y, ys,
                                                                                 yticks)
    colours = mpl.colormaps[cmap].with_extremes(bad="0.85")
    mesh = ax.pcolormesh(_edges(xs_shown), _edges(ys_shown), np.ma.masked_invalid(shown_grid),
                         cmap=colours, shading="flat", edgecolors="w", linewidth=0.3)
    ax.figure.colorbar(mesh, ax=ax, label=label)
    _ticks(ax, (xs_shown, xticks), (ys_shown, yticks))
    if shown_grid.size <= MAX_ANNOTATED:
        _annotate(ax, mesh, xs_shown, ys_shown, shown_grid)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title or _title(label, int(np.isnan(values).sum())))
    return ax


def _title(label: str, failed: int) -> str:
    """The map's default title: its quantity, and how many failed points are grey."""
    name = label.split(" (")[0]
    return (name[:1].upper() + name[1:]
            + (f"; {failed} failed point{'s' * (failed > 1)} grey" if failed else ""))


def _ticks(ax, x_axis, y_axis) -> None:
    """Ticks at the cells' centres: the given labels (degrees, choices), or the values
    where there are at most MAX_TICKED of them."""
    for (centres, ticks), set_ticks in ((x_axis, ax.set_xticks), (y_axis, ax.set_yticks)):
        if ticks is not None:
            set_ticks(centres, ticks)
        elif len(centres) <= MAX_TICKED:
            set_ticks(centres, [f"{c:.4g}" for c in centres])


def _annotate(ax, mesh, xs: np.ndarray, ys: np.ndarray, grid: np.ndarray) -> None:
    """Each cell's value, in black or white against its colour."""
    for (j, i), value in np.ndenumerate(grid):
        if not np.isfinite(value):
            continue
        r, g, b, _ = mesh.cmap(mesh.norm(value))
        light = 0.299 * r + 0.587 * g + 0.114 * b > 0.5
        ax.text(xs[i], ys[j], f"{value:.3g}", ha="center", va="center", fontsize=7,
                color="k" if light else "w")


def _axis(study, name: str, centres: np.ndarray, ticks) -> tuple[np.ndarray, str]:
    """A map axis's cell centres and label as shown (word parameters: their positions)."""
    if ticks is not None:
        return centres, name.replace("_", " ")
    return shown(study, name, centres)
