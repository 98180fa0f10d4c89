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
#: Nodes whose spacing is within this fraction above the roughness count as in contact.
CONTACT_MARGIN = 1e-9


def centreline(solution, ax=None, *, pressure: bool = True):
    """Spacing h(x) along the middle of the width (µm), with p − p_a (kPa) on a twin axis."""
    plt = _plt()
    ax = plt.subplots(figsize=(7, 3.6))[1] if ax is None else ax
    m = solution.model
    col = 0 if m.infinitely_wide else m.ny // 2
    x = solution.x * MM
    h = solution.spacing[:, col] * UM
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
