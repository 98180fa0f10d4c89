"""GIF animations of a mode and of a transient run (matplotlib + Pillow)."""

from __future__ import annotations

import numpy as np

from ..core import validation
from ..core.errors import ParameterError
from .figures import _axes, _mm


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
    frames = validation.integer("frames", frames, low=2)
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
