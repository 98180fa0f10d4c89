"""Plots of gyroshell results: each function takes the result and ``ax=``, returns the Axes.

* :func:`mode_shape` - real or imaginary part of a complex (travelling) mode;
  :func:`mode_shape_parts` draws both side by side;
* :func:`field` - a deflection field (static solution, snapshot, any array on the grid);
* :func:`campbell` - frequencies against speed with tracked branches, crossings, veerings,
  excitation lines ω = n·2πV/ℓ and the critical speed;
* :func:`sweep` - frequencies against speed with the branches a sweep tracked;
* :func:`stability_map` - stable / divergence / flutter over two varied parameters;
* :func:`study_lines` - a computed quantity against one varied parameter;
* :func:`load_point_history`, :func:`head_histories`, :func:`wireframe`,
  :func:`waterfall`, :func:`period_vs_velocity`, :func:`spectra`, :func:`bode` - the
  drawings of ``gyroshell reproduce`` (load-point and moving-head histories, 3-D wire
  frames, centre-line waterfalls, period against speed, stacked spectra, frequency
  response), from arrays or results, so a notebook redraws them from its own runs;
* :func:`animate_mode`, :func:`animate_transient` - GIF animations (matplotlib + Pillow).

matplotlib is imported when a function is called, never at ``import gyroshell``. Without
``ax`` a new figure is made; :func:`save_figure` writes it atomically. :func:`pyplot` is
the one way gyroshell imports matplotlib.pyplot.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import ParameterError
from ..core.units import axis_label

#: Colours of the stability classes (colour-blind safe pairs).
STABILITY_COLOURS = {"stable": "#4daf4a", "divergence": "#e41a1c", "flutter": "#377eb8",
                     "undetermined": "#bbbbbb", "": "#ffffff"}


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


# ----- fields and modes --------------------------------------------------------------------
def field(values, x=None, y=None, *, ax=None, title: str | None = None, label="w (m)",
          cmap="RdBu_r", symmetric: bool = True):
    """Filled contours of a field on the tape, x along and y across (axes in mm).

    ``values`` is a :class:`~gyroshell.static.StaticSolution` (its deflection) or an array
    of shape (nx + 1, ny + 1) with the node coordinates ``x``, ``y`` (m).
    """
    if hasattr(values, "grid") and hasattr(values, "field"):
        grid = values.grid
        x, y, values = grid.x, grid.y, values.field
    values = np.asarray(values)
    if x is None or y is None or values.shape != (len(x), len(y)):
        raise ParameterError("field needs values of shape (len(x), len(y)) with x, y in m")
    ax = _axes(ax)
    vmax = float(np.max(np.abs(values))) or 1.0
    kw = {"vmin": -vmax, "vmax": vmax} if symmetric else {}
    cs = ax.contourf(_mm(x), _mm(y), values.T, levels=21, cmap=cmap, **kw)
    ax.figure.colorbar(cs, ax=ax, label=label, shrink=0.9)
    ax.set_xlabel("x along the tape (mm)")
    ax.set_ylabel("y across (mm)")
    ax.set_aspect("equal")
    if title:
        ax.set_title(title)
    return ax


def mode_shape(modes, index: int = 0, *, part: str = "real", ax=None, title: str | None = None):
    """Real or imaginary part of the complex mode shape ``index`` of a :class:`Modes`.

    A gyroscopic mode travels: w(t) = Re(φ e^{iωt}) = Re φ cos ωt − Im φ sin ωt, so the two
    parts are the shape a quarter period apart.
    """
    if part not in ("real", "imag"):
        raise ParameterError(f"part must be 'real' or 'imag', got {part!r}")
    if not 0 <= index < modes.count:
        raise ParameterError(f"index must be in [0, {modes.count - 1}], got {index}")
    phi = modes.field(index)
    values = phi.real if part == "real" else phi.imag
    lam = modes.eigenvalues[index]
    if title is None:
        what = "Re φ" if part == "real" else "Im φ"
        title = (f"mode {index + 1}, {what}: ω = {abs(lam.imag):.6g} rad/s"
                 + (f", Re λ = {lam.real:.4g} 1/s" if lam.real else "")
                 + f", V = {modes.velocity:g} m/s")
    grid = modes.grid
    return field(values, grid.x, grid.y, ax=ax, title=title, label=f"{part} part (1)")


def mode_shape_parts(modes, index: int = 0, *, axes=None):
    """Real and imaginary parts of mode ``index`` side by side; returns the two Axes."""
    if axes is None:
        plt = pyplot()
        _, axes = plt.subplots(2, 1, figsize=(8.0, 6.0), constrained_layout=True)
    mode_shape(modes, index, part="real", ax=axes[0])
    mode_shape(modes, index, part="imag", ax=axes[1])
    return axes


# ----- Campbell diagrams -------------------------------------------------------------------
def campbell(diagram, *, ax=None, circumference: float | None = None,
             orders=(1, 2, 3), title: str | None = None):
    """Campbell diagram: ω (rad/s) against V (m/s), one line per MAC-tracked branch.

    ``diagram`` is a :class:`gyroshell.campbell.CampbellDiagram`. Crossings are marked with
    circles, veerings with diamonds, growth rates above critical with crosses, the critical
    speed with a vertical line, and with ``circumference`` ℓ (m) of a roller or capstan the
    excitation lines ω = n·2πV/ℓ for n in ``orders``.
    """
    ax = _axes(ax, figsize=(8.0, 5.0))
    frame = diagram.frame
    _branch_lines(ax, frame, ms=2.5, colour_all=True)
    _growth_rates(ax, frame, "growth rate Re λ (1/s)")
    if len(diagram.crossings):
        ax.plot(diagram.crossings["velocity"], diagram.crossings["omega"], "o", ms=9,
                mfc="none", mec="k", label="crossing")
    if len(diagram.veerings):
        v = diagram.veerings
        ax.plot(v["velocity"], 0.5 * (v["omega_a"] + v["omega_b"]), "D", ms=8, mfc="none",
                mec="m", label="veering")
    vmax = float(frame["velocity"].max())
    crit = diagram.critical_speed
    if crit is not None and np.isfinite(crit) and crit <= 1.15 * vmax:
        vmax = max(vmax, crit * 1.01)  # show the critical speed just beyond the sweep
    top = float(np.nanmax(frame["omega"])) * 1.08 if len(frame) else 1.0
    if circumference is not None:
        speeds = np.linspace(0.0, vmax, 50)
        for n in orders:
            ax.plot(speeds, diagram.excitation(n, circumference, speeds), "--", color="0.4",
                    lw=0.9)
            v_end = min(vmax, top * circumference / (2 * np.pi * n))  # where it leaves
            ax.annotate(f"n = {n}", (v_end, float(diagram.excitation(n, circumference, v_end))),
                        fontsize=8, color="0.3", ha="right", va="top",
                        xytext=(-3, -3), textcoords="offset points")
    if crit is not None and np.isfinite(crit):
        ax.axvline(crit, color="k", ls=":", lw=1.2, label=f"critical speed {crit:.4g} m/s")
    ax.set_ylim(0, top)
    ax.set_xlim(float(frame["velocity"].min()), vmax)
    _speed_axes(ax, title or "Campbell diagram (branches tracked by MAC)")
    ax.legend(fontsize=8, loc="lower left")
    return ax


def sweep(result, *, ax=None, title: str | None = None):
    """Sweep: ω (rad/s) against V (m/s), one line per tracked branch; returns the Axes.

    ``result`` is a :class:`~gyroshell.sweep.SweepResult` (or its table, with columns
    ``velocity``, ``branch``, ``omega`` and optionally ``rank`` and ``growth_rate``). The
    k-th lowest frequencies are drawn in grey beneath (continuous where branches end), and
    growth rates above critical as crosses.
    """
    frame = _table(result)
    missing = {"velocity", "branch", "omega"} - set(frame.columns)
    if missing:
        raise ParameterError(f"frame lacks columns {sorted(missing)}")
    ax = _axes(ax)
    if "rank" in frame:  # the k-th lowest frequency: continuous even where branches end
        for rank, group in frame.groupby("rank"):
            group = group.sort_values("velocity")
            ax.plot(group["velocity"], group["omega"], color="0.75", lw=0.8, zorder=1,
                    label="k-th lowest ω" if rank == 0 else None)
    _branch_lines(ax, frame, ms=3, many_label="tracked branches (mode-shape correlation)")
    if "growth_rate" in frame:
        _growth_rates(ax, frame, "growth rate Re λ (1/s), divergence")
    _speed_axes(ax, title or "Lowest frequencies of the moving tape against speed")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8, ncol=2)
    return ax


#: Most branches that each get a legend entry.
LEGEND_BRANCHES = 8


def _branch_lines(ax, frame, *, ms: float, colour_all: bool = False,
                  many_label: str | None = None) -> None:
    """One line with dots per tracked branch of ``frame``; up to :data:`LEGEND_BRANCHES`
    branches are labelled one by one, more share ``many_label`` (and take colours from
    their labels, as they do always with ``colour_all``)."""
    branches = frame.groupby("branch")
    few = branches.ngroups <= LEGEND_BRANCHES
    for k, (branch, group) in enumerate(branches):
        group = group.sort_values("velocity")
        label = f"branch {branch}" if few else (many_label if k == 0 else None)
        ax.plot(group["velocity"], group["omega"], marker="o", ms=ms, lw=1.2, zorder=2,
                color=f"C{int(branch) % 10}" if colour_all or not few else None,
                label=label)


def _growth_rates(ax, frame, label: str) -> None:
    """Crosses at the growth rates Re λ > 0 (1/s) of ``frame``, if any."""
    grow = frame[frame["growth_rate"] > 0]
    if len(grow):
        ax.plot(grow["velocity"], grow["growth_rate"], "kx", ls="none", label=label)


def _speed_axes(ax, title: str) -> None:
    ax.set_xlabel("tape speed V (m/s)")
    ax.set_ylabel("angular frequency ω (rad/s)")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)


# ----- studies -----------------------------------------------------------------------------
def _table(result):
    """The table of a result that holds one (``.table``), or the table itself."""
    return result.table if hasattr(result, "table") else result


def stability_map(study, *, x: str | None = None, y: str | None = None, ax=None,
                  title: str | None = None):
    """Stable / divergence / flutter over two varied parameters of a study.

    ``study`` is a :class:`~gyroshell.study.StudyResult` (or its table); ``x`` and ``y``
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


# ----- reproductions: histories, wire frames, waterfalls, periods, Bode plots ---------------
def _vector(values, name: str) -> np.ndarray:
    arr = np.asarray(values, dtype=float)
    if arr.ndim != 1 or arr.size == 0:
        raise ParameterError(f"{name} must be a non-empty 1-D array")
    return arr


def load_point_history(times, w=None, *, steady: float | None = None, scale: float = 1.0,
                       ylabel: str = "load-point deflection w (m)", velocity=None,
                       label: str = "transient (Newmark, β=1/4)", ax=None):
    """The load-point displacement against time, with its steady state as a dot.

    Parameters
    ----------
    times : array_like or TransientResult
        Times, s (drawn in µs); or a :class:`~gyroshell.TransientResult`, whose
        ``times`` and ``load_point`` are used (then ``w`` is omitted).
    w : array_like, optional
        Load-point deflection at ``times``, m.
    steady : float, optional
        Steady-state deflection, m (e.g. :func:`~gyroshell.solve_static`'s
        ``load_point_deflection``): a dashed line and a dot at the last time.
    scale : float
        Factor applied to ``w`` and ``steady`` before drawing (e.g. k/P₀, m⁻¹, for the
        paper's nondimensional w k / P₀; then say so in ``ylabel``).
    ylabel : str
        Label of the vertical axis, with its unit.
    velocity : float, optional
        Tape speed, m/s, written in the corner.
    label : str
        Legend label of the history.
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure if None.

    Returns
    -------
    matplotlib.axes.Axes
    """
    if w is None:
        if not hasattr(times, "load_point"):
            raise ParameterError("load_point_history needs times and w, or a TransientResult")
        result = times
        times, w = result.times, result.load_point
        velocity = getattr(result, "velocity", None) if velocity is None else velocity
    t = _vector(times, "times")
    w = _vector(w, "w")
    if w.shape != t.shape:
        raise ParameterError(f"w must have the shape of times {t.shape}, got {w.shape}")
    ax = _axes(ax)
    t_us = t * 1e6
    ax.plot(t_us, w * scale, lw=0.9, color="C0", label=label)
    if steady is not None:
        ax.axhline(steady * scale, color="C3", lw=0.8, ls="--")
        ax.plot([t_us[-1]], [steady * scale], "o", color="C3", ms=7,
                label="steady state (static solver)", clip_on=False)
    ax.set_ylabel(ylabel)
    ax.set_xlabel("time t (µs)")
    if velocity is not None:
        ax.text(0.01, 0.9, f"V = {velocity:g} m/s", transform=ax.transAxes, va="top",
                fontweight="bold")
    ax.grid(alpha=0.3)
    return ax


def wireframe(x, y, w, *, ax=None, title: str | None = None, zmax: float | None = None,
              zmin: float | None = None, rstride: int | None = None, cstride: int = 2,
              elev: float = 28.0, azim: float = -62.0, zoom: float = 1.3):
    """A 3-D wire frame of a field w(x, y) on the tape (x, y in mm, w in nm).

    Parameters
    ----------
    x, y : array_like
        Node coordinates along and across the tape, m, lengths nx + 1 and ny + 1.
    w : array_like
        Deflection, m, shape (nx + 1, ny + 1) (a snapshot, ``solve_static(...).field``).
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D, optional
        A 3-D Axes (``projection="3d"``); a new figure if None.
    title : str, optional
        Panel title.
    zmax, zmin : float, optional
        Vertical limits, m; default ``zmax = max|w|`` and ``zmin = -0.6 zmax``, so that
        panels of one history share their scale when given the history's maximum.
    rstride, cstride : int, optional
        Row (along x) and column strides of the wire frame; ``rstride`` defaults to about
        80 lines along the tape.
    elev, azim : float
        Viewing angles, degrees.
    zoom : float
        Zoom of the box (matplotlib ``set_box_aspect``).

    Returns
    -------
    mpl_toolkits.mplot3d.axes3d.Axes3D
    """
    x, y = _vector(x, "x"), _vector(y, "y")
    w = np.asarray(w, dtype=float)
    if w.shape != (len(x), len(y)):
        raise ParameterError(f"w must have shape (len(x), len(y)) = {(len(x), len(y))}, "
                             f"got {w.shape}")
    if ax is None:
        plt = pyplot()
        ax = plt.figure(figsize=(7.0, 4.0)).add_subplot(projection="3d")
    elif not hasattr(ax, "plot_wireframe"):
        raise ParameterError("wireframe needs a 3-D Axes (add_subplot(projection='3d'))")
    X, Y = np.meshgrid(_mm(x), _mm(y), indexing="ij")
    top = float(np.max(np.abs(w))) if zmax is None else float(zmax)
    top = top or 1e-12
    bottom = -0.6 * top if zmin is None else float(zmin)
    stride = max(1, len(x) // 80) if rstride is None else int(rstride)
    ax.plot_wireframe(X, Y, w * 1e9, rstride=stride, cstride=int(cstride), lw=0.4, color="k")
    ax.set_zlim(bottom * 1e9, top * 1e9)
    ax.set_box_aspect((4, 1.3, 1.2), zoom=zoom)
    ax.view_init(elev=elev, azim=azim)
    if title:
        ax.set_title(title, fontsize=10, pad=-2)
    ax.set_xlabel("x (mm)", fontsize=7, labelpad=-4)
    ax.set_ylabel("y (mm)", fontsize=7, labelpad=-6)
    ax.set_zlabel("w (nm)", fontsize=7, labelpad=-6)
    ax.tick_params(labelsize=6, pad=-2)
    return ax


def edge_reflection(times, tape, reference, *, t_edge: float, t_reflection: float,
                    ax=None):
    """Load-point histories of a tape and of a wider reference tape, with the instants the
    front reaches the free edge and its reflection returns to the load (seed paper, §4).

    Parameters
    ----------
    times : array_like
        Times, s (drawn in µs).
    tape, reference : array_like
        Load-point displacement of the tape and of the wider reference, m (drawn in nm),
        same length as ``times``.
    t_edge, t_reflection : float
        Arrival of the front at the free edge and of its reflection at the load point, s.
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure if None.

    Returns
    -------
    matplotlib.axes.Axes
    """
    t = _vector(times, "times")
    series = {}
    for name, values in (("tape", tape), ("reference", reference)):
        series[name] = _vector(values, name)
        if series[name].shape != t.shape:
            raise ParameterError(f"{name} must have the shape of times {t.shape}, "
                                 f"got {series[name].shape}")
    ax = _axes(ax)
    ax.plot(t * 1e6, series["tape"] * 1e9, label="tape, width L_y (free edges)")
    ax.plot(t * 1e6, series["reference"] * 1e9, "--", label="reference, wider tape")
    ax.axvline(t_edge * 1e6, color="C2", lw=0.8, ls=":",
               label=f"front reaches the free edge: {t_edge * 1e6:.1f} µs")
    ax.axvline(t_reflection * 1e6, color="C3", lw=0.8,
               label=f"edge reflection back at the load: {t_reflection * 1e6:.1f} µs")
    ax.set_xlabel("time t (µs)")
    ax.set_ylabel("load-point displacement w (nm)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return ax


def wave_fronts(table, *, speeds: dict | None = None, ax=None):
    """Distance of the apparent wave fronts from the load against time, downstream (solid)
    and upstream (dashed), one colour per tape speed.

    Parameters
    ----------
    table : pandas.DataFrame
        Columns ``velocity`` (m/s), ``t`` (s, drawn in µs), ``downstream`` and
        ``upstream`` (m, drawn in mm).
    speeds : dict, optional
        {(velocity, "downstream" or "upstream"): apparent front speed, m/s} for the legend.
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure if None.

    Returns
    -------
    matplotlib.axes.Axes
    """
    missing = {"velocity", "t", "downstream", "upstream"} - set(getattr(table, "columns", ()))
    if missing:
        raise ParameterError(f"table needs the columns {sorted(missing)}")
    ax = _axes(ax)
    for k, (v, ft) in enumerate(table.groupby("velocity")):
        for side, ls in (("downstream", "-"), ("upstream", "--")):
            speed = None if speeds is None else speeds.get((v, side))
            extra = "" if speed is None else f" ({speed:.0f} m/s)"
            ax.plot(ft["t"] * 1e6, ft[side] * 1e3, ls, color=f"C{k}", marker=".",
                    label=f"V = {v:g} m/s, {side}{extra}")
    ax.set_xlabel("time t (µs)")
    ax.set_ylabel("front distance from the load (mm)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return ax


def waterfall(times, x, lines, *, ax=None, gap: float | None = None,
              load_point: float | None = None, title: str | None = None):
    """Centre-line displacements at a series of times, each raised by its rank (waterfall).

    Parameters
    ----------
    times : array_like
        Times of the lines, s (written at the right end in µs), length m.
    x : array_like
        Positions along the tape, m (drawn in mm), length n.
    lines : array_like
        Displacements, m, shape (m, n) (``TransientResult.snapshots.centerlines``).
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure if None.
    gap : float, optional
        Offset between successive lines, m; default 0.55 max|w|.
    load_point : float, optional
        x of the load centroid, m: a dotted vertical line.
    title : str, optional
        Axes title.

    Returns
    -------
    matplotlib.axes.Axes
    """
    t, x = _vector(times, "times"), _vector(x, "x")
    lines = np.asarray(lines, dtype=float)
    if lines.shape != (len(t), len(x)):
        raise ParameterError(f"lines must have shape (len(times), len(x)) = "
                             f"{(len(t), len(x))}, got {lines.shape}")
    if gap is None:
        gap = 0.55 * float(np.max(np.abs(lines)))
    ax = _axes(ax, figsize=(9.0, 10.0))
    x_mm = _mm(x)
    for k, (tk, line) in enumerate(zip(t, lines, strict=True)):
        ax.plot(x_mm, line + k * gap, color="k", lw=0.7)
        ax.text(x_mm.max() * 1.01, k * gap, f"{tk * 1e6:.0f}", fontsize=7, va="center")
    if load_point is not None:
        ax.axvline(load_point * 1e3, color="C3", lw=0.6, ls=":", label="load point")
        ax.legend(loc="upper left", fontsize=8)
    step = f" per {np.median(np.diff(t)) * 1e6:.3g} µs" if len(t) > 1 else ""
    ax.set_xlabel("x (mm)   (tape moves left → right)")
    ax.set_ylabel(f"w + offset (each curve raised {gap * 1e9:.3g} nm{step})")
    ax.set_yticks([])
    ax.text(1.0, 1.0, "t (µs)", transform=ax.transAxes, fontsize=8, ha="left", va="bottom")
    for side in ("top", "right", "left"):
        ax.spines[side].set_visible(False)
    if title:
        ax.set_title(title, fontsize=11)
    return ax


def head_histories(times, w_heads, contact, *, axes=None):
    """Contact envelopes and the displacement under each moving head while in contact.

    Parameters
    ----------
    times : array_like
        Times, s (drawn in µs), length n.
    w_heads : array_like
        Displacement under each head, m (drawn in nm), shape (n, heads)
        (``TransientResult.head_displacements``).
    contact : array_like
        Contact envelope of each head, 0..1, shape (n, heads) (``head.envelope(times)``);
        w is drawn only where it is positive.
    axes : sequence of matplotlib.axes.Axes, optional
        heads + 1 Axes: the envelopes, then one per head; a new figure if None.

    Returns
    -------
    numpy.ndarray of matplotlib.axes.Axes
    """
    t = _vector(times, "times")
    w = np.asarray(w_heads, dtype=float).reshape(len(t), -1)
    env = np.asarray(contact, dtype=float).reshape(len(t), -1)
    if w.shape != env.shape:
        raise ParameterError(f"w_heads and contact must have one column per head, shapes "
                             f"{w.shape} and {env.shape}")
    heads = w.shape[1]
    if axes is None:
        plt = pyplot()
        _, axes = plt.subplots(heads + 1, 1, figsize=(9.0, 7.5), sharex=True,
                               gridspec_kw={"height_ratios": [1] + [2] * heads})
    axes = np.asarray(axes).ravel()
    if axes.size != heads + 1:
        raise ParameterError(f"axes must hold heads + 1 = {heads + 1} Axes, got {axes.size}")
    t_us = t * 1e6
    for k in range(heads):
        axes[0].plot(t_us, env[:, k], lw=1.2, label=f"head {k + 1}")
        ax = axes[k + 1]
        ax.plot(t_us, np.where(env[:, k] > 0, w[:, k] * 1e9, np.nan), lw=1.1,
                color=f"C{k}", label="w under the head while in contact (spacing variation)")
        ax.axhline(0, color="k", lw=0.5)
        ax.set_ylabel("w under head (nm)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("contact")
    axes[0].legend(fontsize=8, loc="upper right", ncol=2)
    axes[1].legend(fontsize=8, loc="lower right")
    axes[0].set_title("contact envelopes", fontsize=9)
    axes[-1].set_xlabel("time t (µs)")
    return axes


def period_vs_velocity(velocity, period_eigen, *, transient_edge=None, transient=None,
                       critical_speed: float | None = None, ax=None,
                       title: str | None = None):
    """Dominant period of the load-point displacement against tape speed (log scale, µs).

    Parameters
    ----------
    velocity : array_like
        Tape speeds, m/s.
    period_eigen : array_like
        2π/ω₁ from the gyroscopic eigen-solver at each speed, s.
    transient_edge, transient : array_like, optional
        Periods from the load-point spectrum of a transient, s: the lowest peak (band
        edge) and the tallest peak.
    critical_speed : float, optional
        Critical (divergence) speed, m/s: a dashed vertical line.
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure if None.
    title : str, optional
        Axes title.

    Returns
    -------
    matplotlib.axes.Axes
    """
    v = _vector(velocity, "velocity")
    series = {"period_eigen": period_eigen, "transient_edge": transient_edge,
              "transient": transient}
    series = {k: _vector(s, k) for k, s in series.items() if s is not None}
    for name, s in series.items():
        if s.shape != v.shape:
            raise ParameterError(f"{name} must have the shape of velocity {v.shape}")
    ax = _axes(ax)
    p0 = series["period_eigen"] * 1e6
    ax.semilogy(v, p0, "-", color="C0", lw=1.2, marker="s", ms=5,
                label="2π/ω₁ (gyroscopic eigen-solver)")
    if "transient_edge" in series:
        ax.semilogy(v, series["transient_edge"] * 1e6, "o", color="C2", mfc="none", ms=10,
                    mew=1.5, label="transient: lowest spectral peak (band edge)")
    if "transient" in series:
        ax.semilogy(v, series["transient"] * 1e6, "x", color="C3", ms=8, mew=1.5,
                    label="transient: tallest spectral peak")
    first = p0[int(np.argmin(np.abs(v)))]
    ax.axhline(first, color="0.6", lw=0.7, ls=":")
    ax.text(1, first * 1.08, f"at V = {v[int(np.argmin(np.abs(v)))]:g} m/s: {first:.3g} µs",
            color="0.4", fontsize=8)
    if critical_speed is not None:
        ax.axvline(critical_speed, color="k", lw=0.7, ls="--",
                   label=f"critical speed {critical_speed:.2f} m/s")
    ax.set_xlabel("tape speed V (m/s)")
    ax.set_ylabel("period of the load-point displacement (µs)")
    if title:
        ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="upper left")
    return ax


def spectra(labels, omegas, amplitudes, *, omega_ref=None, ax=None, xmax: float | None = None,
            spacing: float = 1.1, title: str | None = None):
    """Amplitude spectra stacked one above the other, each normalized to its peak.

    Parameters
    ----------
    labels : sequence of str or float
        One label per spectrum (a number is written as a speed, ``"50 m/s"``).
    omegas : sequence of array_like
        Angular frequencies of each spectrum, rad/s (lengths may differ).
    amplitudes : sequence of array_like
        Amplitudes at ``omegas`` (any unit: each curve is divided by its maximum).
    omega_ref : array_like, optional
        One reference angular frequency per spectrum, rad/s (e.g. ω₁(V) from the
        eigen-solver): the curves are drawn against ω/ω_ref with a dashed line at 1.
        Without it they are drawn against ω in rad/s.
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure if None.
    xmax : float, optional
        Right end of the horizontal axis (in ω/ω_ref or rad/s); labels are written there.
    spacing : float
        Vertical offset between successive spectra (normalized units).
    title : str, optional
        Axes title.

    Returns
    -------
    matplotlib.axes.Axes
    """
    labels, omegas, amplitudes = list(labels), list(omegas), list(amplitudes)
    if not (len(labels) == len(omegas) == len(amplitudes)) or not labels:
        raise ParameterError("labels, omegas and amplitudes need one entry per spectrum")
    ref = None if omega_ref is None else _vector(omega_ref, "omega_ref")
    if ref is not None and (ref.shape != (len(labels),) or np.any(ref <= 0)):
        raise ParameterError("omega_ref needs one positive value (rad/s) per spectrum")
    ax = _axes(ax)
    right = xmax
    for k, (lab, om, amp) in enumerate(zip(labels, omegas, amplitudes, strict=True)):
        om, amp = _vector(om, "omegas"), np.abs(_vector(amp, "amplitudes"))
        if om.shape != amp.shape:
            raise ParameterError(f"spectrum {k}: omegas and amplitudes differ in length")
        xs = om / ref[k] if ref is not None else om
        top = float(amp.max()) or 1.0
        ax.plot(xs, amp / top + spacing * k, color=f"C{k % 10}", lw=0.8)
        text = f"{lab:g} m/s" if isinstance(lab, (int, float, np.number)) else str(lab)
        at = right if right is not None else float(xs.max())
        ax.text(at * (1 + 1 / 60), spacing * k + 0.1, text, fontsize=8)
    if ref is not None:
        ax.axvline(1.0, color="k", lw=0.7, ls="--", label="ω₁ from the eigen-solver")
        ax.set_xlabel("ω / ω₁(V)")
        ax.legend(fontsize=8, loc="upper left")
    else:
        ax.set_xlabel("angular frequency ω (rad/s)")
    if right is not None:
        ax.set_xlim(0, right)
    ax.set_ylabel("amplitude spectrum (normalized, offset)")
    ax.set_yticks([])
    if title:
        ax.set_title(title, fontsize=10)
    return ax


def bode(omega, response=None, phase=None, *, axes=None, label: str | None = None,
         color=None, mode_omegas=None, scale: float = 1e-3):
    """Bode plot: amplitude (m, log scale) and phase (rad) against angular frequency.

    Parameters
    ----------
    omega : array_like or FrequencyResponse
        Angular frequencies, rad/s; or a :class:`~gyroshell.frf.FrequencyResponse`
        (its load-point column is drawn; omit ``response``).
    response : array_like, optional
        Complex displacement amplitude, m, or its modulus |W| (then give ``phase``).
    phase : array_like, optional
        Phase, rad, when ``response`` is the modulus.
    axes : pair of matplotlib.axes.Axes, optional
        (amplitude, phase) Axes; a new two-row figure if None.
    label : str, optional
        Legend label of the curve.
    color : optional
        matplotlib colour of the curve and its mode ticks.
    mode_omegas : array_like, optional
        Eigenfrequencies, rad/s, drawn as dotted vertical lines on the amplitude.
    scale : float
        ω is drawn as ω·scale; the default 1e-3 gives 10³ rad/s, 1 gives rad/s.

    Returns
    -------
    numpy.ndarray of matplotlib.axes.Axes
        The (amplitude, phase) Axes.
    """
    if response is None:
        if not hasattr(omega, "amplitude"):
            raise ParameterError("bode needs omega and response, or a FrequencyResponse")
        omega, response, phase = omega.omega, omega.amplitude[:, 0], omega.phase[:, 0]
    om = _vector(omega, "omega")
    response = np.asarray(response)
    if np.iscomplexobj(response):
        amplitude, phase = np.abs(response), np.angle(response)
    else:
        if phase is None:
            raise ParameterError("bode needs phase (rad) when response is real (|W|, m)")
        amplitude, phase = response.astype(float), np.asarray(phase, dtype=float)
    if amplitude.shape != om.shape or phase.shape != om.shape:
        raise ParameterError(f"response and phase must have the shape of omega {om.shape}")
    if axes is None:
        plt = pyplot()
        _, axes = plt.subplots(2, 1, sharex=True, figsize=(9.0, 7.0))
    axes = np.asarray(axes).ravel()
    if axes.size != 2:
        raise ParameterError("axes must be a pair (amplitude, phase)")
    line, = axes[0].semilogy(om * scale, amplitude, lw=1.0, color=color, label=label)
    axes[1].plot(om * scale, phase, lw=1.0, color=line.get_color())
    for w in ([] if mode_omegas is None else np.asarray(mode_omegas, dtype=float)):
        axes[0].axvline(w * scale, color=line.get_color(), lw=0.6, ls=":", alpha=0.8)
    unit = "rad/s" if scale == 1 else f"{1 / scale:.0e} rad/s".replace("1e+03", "10³")
    axes[0].set_ylabel("load-point amplitude |W| (m)")
    axes[1].set_ylabel("phase (rad)")
    axes[1].set_xlabel(f"angular frequency ω ({unit})")
    for a in axes:
        a.grid(alpha=0.3)
    return axes


# ----- animations --------------------------------------------------------------------------
def _write_gif(fig, update, frames: int, path, fps: int):
    from matplotlib.animation import FuncAnimation, PillowWriter

    from ..core.files import atomic_path

    anim = FuncAnimation(fig, update, frames=frames, blit=False)
    with atomic_path(path) as tmp:
        anim.save(tmp, writer=PillowWriter(fps=fps))
    return anim


def animate_mode(modes, path, index: int = 0, *, frames: int = 24, fps: int = 12, ax=None):
    """GIF of one period of Re(φ e^{iωt}) for mode ``index``; returns the Axes."""
    if path is None or not str(path).lower().endswith(".gif"):
        raise ParameterError(f"animate_mode writes a .gif file, got {path!r}")
    if isinstance(frames, bool) or int(frames) != frames or frames < 2:
        raise ParameterError(f"frames must be an integer >= 2, got {frames!r}")
    phi = modes.field(index)
    grid = modes.grid
    ax = _axes(ax)
    vmax = float(np.max(np.abs(phi))) or 1.0
    levels = np.linspace(-vmax, vmax, 21)

    def update(k):
        ax.clear()
        wt = 2 * np.pi * k / frames
        ax.contourf(_mm(grid.x), _mm(grid.y), (phi * np.exp(1j * wt)).real.T, levels=levels,
                    cmap="RdBu_r")
        ax.set_aspect("equal")
        ax.set_xlabel("x along the tape (mm)")
        ax.set_ylabel("y across (mm)")
        ax.set_title(f"mode {index + 1} at V = {modes.velocity:g} m/s, "
                     f"ωt = {np.degrees(wt):.0f}°")

    _write_gif(ax.figure, update, int(frames), path, fps)
    return ax


def animate_transient(result, path, *, fps: int = 10, ax=None):
    """GIF of the snapshot fields of a :class:`TransientResult` (m); returns the Axes."""
    if path is None or not str(path).lower().endswith(".gif"):
        raise ParameterError(f"animate_transient writes a .gif file, got {path!r}")
    snaps = result.snapshots
    if len(snaps) < 2:
        raise ParameterError("animate_transient needs >= 2 snapshots (march with "
                             "snapshot_every=N)")
    ax = _axes(ax)
    vmax = float(np.max(np.abs(snaps.fields))) or 1.0
    levels = np.linspace(-vmax, vmax, 21)

    def update(k):
        ax.clear()
        ax.contourf(_mm(snaps.x), _mm(snaps.y), snaps.fields[k].T, levels=levels,
                    cmap="RdBu_r")
        ax.set_aspect("equal")
        ax.set_xlabel("x along the tape (mm)")
        ax.set_ylabel("y across (mm)")
        ax.set_title(f"w at t = {1e6 * snaps.times[k]:.1f} µs, V = {result.velocity:g} m/s")

    _write_gif(ax.figure, update, len(snaps), path, fps)
    return ax
