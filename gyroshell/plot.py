"""Plots of gyroshell results: each function takes the result and ``ax=``, returns the Axes.

* :func:`mode_shape` - real or imaginary part of a complex (travelling) mode;
  :func:`mode_shape_parts` draws both side by side;
* :func:`field` - a deflection field (static solution, snapshot, any array on the grid);
* :func:`campbell` - frequencies against speed with tracked branches, crossings, veerings,
  excitation lines ω = n·2πV/ℓ and the critical speed;
* :func:`stability_map` - stable / divergence / flutter over two varied parameters;
* :func:`study_lines` - a computed quantity against one varied parameter;
* :func:`animate_mode`, :func:`animate_transient` - GIF animations (matplotlib + Pillow).

matplotlib is imported when a function is called, never at ``import gyroshell``. Without
``ax`` a new figure is made; save it with ``ax.figure.savefig(path)``.
"""

from __future__ import annotations

import numpy as np

from .errors import ParameterError

#: Colours of the stability classes (colour-blind safe pairs).
STABILITY_COLOURS = {"stable": "#4daf4a", "divergence": "#e41a1c", "flutter": "#377eb8",
                     "undetermined": "#bbbbbb", "": "#ffffff"}


def pyplot(path=None):
    """matplotlib.pyplot, with the Agg back-end when writing files without a display."""
    import matplotlib

    if path is not None:
        import os

        if not os.environ.get("DISPLAY") and matplotlib.get_backend().lower() != "agg":
            matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


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
    for branch, group in frame.groupby("branch"):
        group = group.sort_values("velocity")
        ax.plot(group["velocity"], group["omega"], "-o", ms=2.5, lw=1.2,
                color=f"C{int(branch) % 10}",
                label=f"branch {branch}" if frame["branch"].nunique() <= 8 else None)
    grow = frame[frame["growth_rate"] > 0]
    if len(grow):
        ax.plot(grow["velocity"], grow["growth_rate"], "kx", ls="none",
                label="growth rate Re λ (1/s)")
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
    ax.set_xlabel("tape speed V (m/s)")
    ax.set_ylabel("angular frequency ω (rad/s)")
    ax.set_title(title or "Campbell diagram (branches tracked by MAC)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    return ax


# ----- studies -----------------------------------------------------------------------------
def _study_table(study):
    return study.table if hasattr(study, "table") else study


def stability_map(study, *, x: str | None = None, y: str | None = None, ax=None,
                  title: str | None = None):
    """Stable / divergence / flutter over two varied parameters of a study.

    ``study`` is a :class:`~gyroshell.study.StudyResult` (or its table); ``x`` and ``y``
    default to the first two varied parameters (x: the first). Each point is a coloured
    cell; the critical speed, if computed and x or y is the velocity, is drawn over it.
    """
    table = _study_table(study)
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
    ax.set_xlabel(_label(x))
    ax.set_ylabel(_label(y))
    ax.set_title(title or "Stability of the moving tape")
    return ax


def study_lines(study, *, quantity: str | None = None, x: str | None = None, ax=None,
                title: str | None = None):
    """A computed column against a varied parameter (one line per value of any other)."""
    from .study import result_columns

    table = _study_table(study)
    varied = list(getattr(study, "varied", ()))
    x = x or (varied[0] if varied else None)
    if x is None or x not in table:
        raise ParameterError("study_lines needs the varied parameter x")
    if quantity is None:
        compute = getattr(study, "compute", ())
        numeric = [c for c in result_columns(compute, getattr(study, "count", 1))
                   if c not in ("stability", "error")] if compute else []
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
    ax.set_xlabel(_label(x))
    ax.set_ylabel(_label(quantity))
    ax.grid(True, alpha=0.3)
    if others:
        ax.legend(fontsize=8)
    if title:
        ax.set_title(title)
    return ax


_UNITS = {"velocity": "m/s", "tension": "N/m", "thickness": "m", "youngs_modulus": "Pa",
          "radius": "m", "width": "m", "spacing": "m", "density": "kg/m²", "load": "Pa",
          "critical_speed": "m/s", "divergence_speed": "m/s", "growth_rate": "1/s",
          "load_point_deflection": "m", "max_deflection": "m", "period": "s",
          "bending_rigidity": "N·m", "foundation_stiffness": "N/m³"}


def _label(name: str) -> str:
    unit = "rad/s" if name.startswith("omega_") else _UNITS.get(name)
    return f"{name.replace('_', ' ')} ({unit})" if unit else name.replace("_", " ")


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


# ----- animations --------------------------------------------------------------------------
def _write_gif(fig, update, frames: int, path, fps: int):
    from matplotlib.animation import FuncAnimation, PillowWriter

    from .io import atomic_path

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
