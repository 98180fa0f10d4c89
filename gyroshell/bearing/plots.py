"""Plots of bearing results (matplotlib imported only when called). Each function draws
into ``ax`` (or a new figure) and returns the Axes."""

from __future__ import annotations

import numpy as np

from ..plot import pyplot as _plt

#: m -> µm, m -> mm and s -> ms for the axes ...
UM = 1e6
MM = 1e3
MS = 1e3
#: ... and Pa per kPa.
PA_PER_KPA = 1e3
#: Spacing axes reach this many central spacings (the film's scale) ...
SPACING_AXIS_SPAN = 3.0
#: ... and the log colour scale of a spacing map ends at this many.
MAP_TOP_SPACINGS = 10.0
#: Smallest spacing of the colour scale, µm (LogNorm needs a positive floor).
MAP_FLOOR_UM = 1e-3
#: The contour panel shows the tape's height range and this fraction more each way.
CONTOUR_MARGIN = 0.15
#: Nodes whose spacing is within this fraction above the roughness count as in contact.
CONTACT_MARGIN = 1e-9


def _centre_line(solution, ax):
    """(Axes, model, column, x in mm, h in µm) of the middle of the width (a new Axes if
    ``ax`` is None)."""
    ax = _plt().subplots(figsize=(7, 3.6))[1] if ax is None else ax
    m = solution.model
    col = 0 if m.infinitely_wide else m.ny // 2
    return ax, m, col, solution.x * MM, solution.spacing[:, col] * UM


def centreline(solution, ax=None, *, pressure: bool = True):
    """Spacing h(x) along the middle of the width (µm), with p − p_a (kPa) on a twin axis."""
    ax, m, col, x, h = _centre_line(solution, ax)
    ax.plot(x, h, color="C0", label="spacing h")
    half = 0.5 * m.params.radius * m.wrap_angle * MM
    for s in (-half, half):
        ax.axvline(s, color="0.6", lw=0.8, ls=":")
    ax.set_xlabel("x from the middle of the wrap (mm), tape moves →")
    ax.set_ylabel("spacing h (µm)", color="C0")
    ax.set_ylim(0, SPACING_AXIS_SPAN * max(solution.central_spacing * UM, MAP_FLOOR_UM))
    if pressure:
        twin = ax.twinx()
        twin.plot(x, (solution.pressure[:, col] - m.air.ambient_pressure) / PA_PER_KPA,
                  color="C3", lw=1.0)
        twin.axhline(m.effective_tension() / m.params.radius / PA_PER_KPA, color="C3", lw=0.6,
                     ls="--")
        twin.set_ylabel("p − p_a (kPa); dashed: (T − ρV²)/R", color="C3")
    ax.set_title(f"V = {m.velocity:g} m/s, wrap {np.degrees(m.wrap_angle):g}°, "
                 f"h_c = {solution.central_spacing * UM:.3f} µm, "
                 f"h_min = {solution.minimum_spacing * UM:.3f} µm")
    return ax


def spacing_map(solution, ax=None, *, field: str = "spacing"):
    """Map of the spacing (µm, log colour scale) or of p − p_a (kPa) over the 2-D tape."""
    plt = _plt()
    from matplotlib.colors import LogNorm

    ax = plt.subplots(figsize=(7, 3.6))[1] if ax is None else ax
    m = solution.model
    x, y = solution.x * MM, m.y * MM
    if field == "spacing":
        data = solution.spacing.T * UM
        top = MAP_TOP_SPACINGS * solution.central_spacing * UM
        mesh = ax.pcolormesh(x, y, np.minimum(data, top), shading="auto", cmap="viridis",
                             norm=LogNorm(vmin=max(data.min(), MAP_FLOOR_UM), vmax=top))
        label = "spacing h (µm)"
        i, j = np.unravel_index(np.argmin(solution.spacing), solution.spacing.shape)
        ax.plot(x[i], y[j], "rx", ms=8, label=f"minimum {data.T[i, j]:.3f} µm")
        contact = (solution.model.spacing_field(solution.u)
                   <= m.air.roughness * (1 + CONTACT_MARGIN))
        if contact.any():
            ci, cj = np.nonzero(contact)
            ax.plot(x[ci], y[cj], "w.", ms=2, label="contact")
        ax.legend(loc="upper right", fontsize=8)
    else:
        data = (solution.pressure.T - m.air.ambient_pressure) / PA_PER_KPA
        mesh = ax.pcolormesh(x, y, data, shading="auto", cmap="magma")
        label = "p − p_a (kPa)"
    plt.colorbar(mesh, ax=ax, label=label)
    half = 0.5 * m.params.radius * m.wrap_angle * MM
    for s in (-half, half):
        ax.axvline(s, color="w", lw=0.8, ls=":")
    ax.set_xlabel("x from the middle of the wrap (mm), tape moves →")
    ax.set_ylabel("y across the width (mm)")
    return ax


def cross_width(solution, ax=None, **kw):
    """Spacing across the width at the middle of the wrap, µm."""
    plt = _plt()
    ax = plt.subplots(figsize=(6, 3.4))[1] if ax is None else ax
    m = solution.model
    kw.setdefault("label", "spacing")
    ax.plot(m.y * MM, solution.cross_width_spacing * UM, marker=".", ms=3, **kw)
    ax.axhline(m.air.roughness * UM, color="0.5", lw=0.8, ls=":", label="roughness")
    ax.legend(fontsize=8)
    ax.set_xlabel("y across the width (mm)")
    ax.set_ylabel("spacing at the wrap centre (µm)")
    ax.set_ylim(bottom=0)
    return ax


def overview(solution):
    """One figure: centre-line profile, and for a 2-D tape the spacing and pressure maps
    and the cross-width profile. Returns the Figure."""
    plt = _plt()
    if solution.model.infinitely_wide:
        fig, ax = plt.subplots(figsize=(8, 4))
        centreline(solution, ax)
        return fig
    fig, axes = plt.subplots(2, 2, figsize=(13, 7.5))
    spacing_map(solution, axes[0, 0])
    spacing_map(solution, axes[0, 1], field="pressure")
    centreline(solution, axes[1, 0])
    cross_width(solution, axes[1, 1])
    fig.tight_layout()
    return fig


def transient_spacing(run, ax=None):
    """Central and minimum spacing (µm) against time (ms) of a bearing transient."""
    plt = _plt()
    ax = plt.subplots(figsize=(7, 3.6))[1] if ax is None else ax
    t = run.t * MS
    ax.plot(t, run.central_spacing * UM, label="central spacing")
    ax.plot(t, run.minimum_spacing * UM, label="minimum spacing")
    ax.set_xlabel("time (ms)")
    ax.set_ylabel("spacing (µm)")
    ax.legend()
    return ax


def _marks(solution, ax, *, labels: bool = True) -> None:
    """The head's lands (shaded), corners (dotted) and transducer lines (dashed), mm."""
    lay = solution._layout
    for k, (a, b) in enumerate(lay["lands"]):
        ax.axvspan(a * MM, b * MM, color="0.92", zorder=0,
                   label="land" if labels and k == 0 else None)
    for k, c in enumerate(lay["corners"]):
        ax.axvline(c * MM, color="0.5", lw=0.8, ls=":",
                   label="corner" if labels and k == 0 else None)
    for k, t in enumerate(lay["transducers"]):
        ax.axvline(t * MM, color="C2", lw=0.9, ls="--",
                   label="transducer" if labels and k == 0 else None)


def _head_contour(solution) -> np.ndarray:
    """z_h(x) along the middle of the width, m (head coordinates)."""
    m = solution.model
    z = np.asarray(m.head.surface(solution.x, None if m.infinitely_wide else m.y,
                                  radius=m.head_radius))
    return z if z.ndim == 1 else z[:, m.ny // 2]


def head_contour(solution, ax=None):
    """The head contour z_h(x) and the tape z_h + h along the middle of the width (µm),
    with the lands, corners and transducer lines marked."""
    plt = _plt()
    ax = plt.subplots(figsize=(7, 2.6))[1] if ax is None else ax
    m = solution.model
    col = 0 if m.infinitely_wide else m.ny // 2
    x, z = solution.x * MM, _head_contour(solution)
    tape = (z + solution.spacing[:, col]) * UM
    low, high = tape.min(), tape.max()
    bottom = low - CONTOUR_MARGIN * (high - low)      # the flanks fall far below the tape
    ax.fill_between(x, np.maximum(z * UM, bottom), bottom, color="0.75", label="head")
    ax.plot(x, tape, color="C0", lw=1.0, label="tape")
    _marks(solution, ax, labels=False)
    ax.set_xlim(x[0], x[-1])
    ax.set_ylim(bottom, high + CONTOUR_MARGIN * (high - low))
    ax.set_ylabel("z (µm)")
    ax.legend(loc="lower center", fontsize=8)
    return ax


def head_spacing(solution, ax=None):
    """Spacing h(x) along the middle of the width (µm) over the head's lands, corners and
    transducer lines (each labelled with its spacing), the tents marked, and p − p_a (kPa)
    on a twin axis."""
    ax, m, col, x, h = _centre_line(solution, ax)
    _marks(solution, ax)
    ax.plot(x, h, color="C0", label="spacing h")
    tents = [t for t in solution.tents if t.height is not None]
    if tents:
        ax.plot([t.x * MM for t in tents], [t.height * UM for t in tents], "v", color="C1",
                ms=5, label="tent")
    for line in solution.transducer_lines:
        ax.annotate(f"{line.centre * UM:.3g} µm", (line.x * MM, line.centre * UM),
                    xytext=(3, 6), textcoords="offset points", fontsize=7, color="C2")
    on_land = np.zeros(len(x), dtype=bool)       # the scale of the lands, not of the gaps
    for a, b in solution._layout["lands"]:
        on_land |= (solution.x >= a) & (solution.x <= b)
    top = np.max(h[on_land]) if on_land.any() else np.max(h)
    ax.set_ylim(0, SPACING_AXIS_SPAN / 2 * max(top, MAP_FLOOR_UM))
    ax.set_xlim(x[0], x[-1])
    ax.set_xlabel("x from the head's middle (mm), tape moves →")
    ax.set_ylabel("spacing h (µm)", color="C0")
    twin = ax.twinx()
    twin.plot(x, (solution.pressure[:, col] - m.air.ambient_pressure) / PA_PER_KPA,
              color="C3", lw=1.0)
    twin.axhline(0.0, color="C3", lw=0.5, ls=":")
    twin.set_ylabel("p − p_a (kPa)", color="C3")
    ax.legend(loc="upper left", fontsize=7)
    ax.set_title(f"V = {m.velocity:g} m/s, h_min = {solution.minimum_spacing * UM:.3g} µm, "
                 f"drag {solution.drag:.3g} {'N/m' if m.infinitely_wide else 'N'}, "
                 f"T_out/T_in = {solution.tension_ratio:.4f}", fontsize=9)
    return ax


def transducer_cut(solution, ax=None):
    """The spacing across the width along each transducer line (µm), its mean dashed."""
    plt = _plt()
    ax = plt.subplots(figsize=(6, 3.4))[1] if ax is None else ax
    m = solution.model
    if m.infinitely_wide:
        raise ValueError("the infinitely wide tape has no width to cut across")
    for k, line in enumerate(solution.transducer_lines):
        ax.plot(m.y * MM, line.spacing * UM, color=f"C{k}", marker=".", ms=3,
                label=f"x = {line.x * MM:.3g} mm: min {line.minimum * UM:.3g}, "
                      f"mean {line.mean * UM:.3g} µm")
        ax.axhline(line.mean * UM, color=f"C{k}", lw=0.6, ls="--")
    ax.axhline(m.air.roughness * UM, color="0.5", lw=0.8, ls=":", label="roughness")
    ax.set_xlabel("y across the width (mm)")
    ax.set_ylabel("spacing along the transducer line (µm)")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7)
    return ax


def head_overview(solution):
    """One figure: the head contour and the tape, the spacing and pressure along the
    middle of the width, and (2-D, with transducers) the transducer-line cuts across the
    width. Returns the Figure."""
    plt = _plt()
    cut = not solution.model.infinitely_wide and bool(solution.transducer_lines)
    fig = plt.figure(figsize=(8, 8.5 if cut else 6))
    grid = fig.add_gridspec(3 if cut else 2, 1, height_ratios=[1, 1.6, 1.4][:3 if cut else 2])
    top = fig.add_subplot(grid[0])
    head_contour(solution, top)
    middle = fig.add_subplot(grid[1], sharex=top)
    head_spacing(solution, middle)
    if cut:
        transducer_cut(solution, fig.add_subplot(grid[2]))
    fig.tight_layout()
    return fig


#: A head sketch shows the wrapped region and this fraction of its length beyond each end.
SKETCH_MARGIN = 0.25
#: Samples of a head sketch's contour along x.
SKETCH_SAMPLES = 1601


def head_sketch(head, ax=None, *, radius: float | None = None, title: str | None = None):
    """Where a head's modules, gaps, corners and transducer lines sit: the contour z_h(x)
    (µm, filled) and the dry tape over it (the tape's path with no air film) against x
    (mm, from the head's middle), before any solve.

    Parameters
    ----------
    head : gyroshell.bearing.head.Head
        A cylinder, flat or measured head.
    ax : matplotlib Axes, optional
    radius : float, optional
        A cylinder's radius, m, when the head has none of its own (the tape's R).
    title : str, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    plt = _plt()
    ax = plt.subplots(figsize=(8, 3.2), constrained_layout=True)[1] if ax is None else ax
    lo, hi = head.extent(radius)
    margin = SKETCH_MARGIN * (hi - lo)
    x = np.union1d(np.linspace(lo - margin, hi + margin, SKETCH_SAMPLES),
                   np.asarray(head.corners(radius), dtype=float))
    z = np.asarray(head.surface(x, radius=radius), dtype=float) * UM
    tape = np.asarray(head.dry_tape(x, radius), dtype=float) * UM
    inside = (x >= lo) & (x <= hi)
    low = min(z[inside].min(), tape.min())
    high = tape.max()
    bottom = low - CONTOUR_MARGIN * (high - low)
    xm = x * MM
    ax.fill_between(xm, np.maximum(z, bottom), bottom, color="0.75", label="head")
    ax.plot(xm, tape, color="C0", lw=1.2, label="dry tape (no air film)")
    top = high + 2 * CONTOUR_MARGIN * (high - low)
    lands = head.lands(radius)
    for k, (a, b) in enumerate(lands, start=1):
        on = (x >= a) & (x <= b)
        ax.plot(xm[on], z[on], color="C1", lw=3, solid_capstyle="butt",
                label="land" if k == 1 else None)
        if len(lands) > 1:
            ax.text(0.5 * (a + b) * MM, top, f"module {k}", ha="center", va="top",
                    fontsize=8)
    for (_, b), (a, _) in zip(lands[:-1], lands[1:], strict=True):
        if a > b:
            ax.text(0.5 * (a + b) * MM, bottom, f"gap\n{(a - b) * MM:.3g} mm",
                    ha="center", va="bottom", fontsize=7)
    for k, t in enumerate(head.transducers, start=1):
        ax.axvline(t * MM, color="C2", lw=1.0, ls="--",
                   label="transducer" if k == 1 else None)
        ax.text(t * MM, 0.5 * (high + top), f" T{k}", color="C2", ha="left",
                va="center", fontsize=8)
    ax.set_xlim(xm[0], xm[-1])
    ax.set_ylim(bottom, top + CONTOUR_MARGIN * (high - low))
    ax.set_xlabel("x from the head's middle (mm), tape moves →")
    ax.set_ylabel("z (µm)")
    ax.legend(loc="lower left", fontsize=7, framealpha=0.9)
    ax.set_title(title or f"{head.kind} head: wrap {np.degrees(head.wrap):.3g}°", fontsize=9)
    return ax
