"""Fields on the tape and (travelling) mode shapes."""

from __future__ import annotations

import numpy as np

from ..core.errors import ParameterError
from .figures import _axes, _mm, pyplot


def field(values, x=None, y=None, *, ax=None, title: str | None = None, label="w (m)",
          cmap="RdBu_r", symmetric: bool = True):
    """Filled contours of a field on the tape, x along and y across (axes in mm).

    ``values`` is a :class:`~gyroshell.StaticSolution` (its deflection) or an array
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
