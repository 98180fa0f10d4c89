"""The static deflection K(V) w = F as a saved result kind (``"static"``).

File layout (unchanged from the previous release, so its files still load): the deflection
on all nodes ``w`` (m) on dimensions ``x``, ``y``, the scalars ``velocity`` (m/s) and
``load_point_deflection`` (m), and the grid and tape parameters as metadata.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..plot import field as draw_field
from ..tape.grid import Grid
from ..tape.parameters import TapeParameters
from .base import Result, dataset, get, grid_from, params_from, put, xy_coords
from .layout import Layout, Variable, X, Y, finite_number, scalar_check, speed


@dataclass(frozen=True)
class StaticSolution(Result, kind="static"):
    """Static deflection under the model's load.

    Attributes
    ----------
    grid : Grid
    velocity : float
        Tape speed V, m/s.
    w : numpy.ndarray
        Deflection at the unknown nodes, m.
    load_point_deflection : float
        w at the load centroid (bilinear interpolation), m.
    params : TapeParameters or None
        The tape it was computed for (set by :func:`~gyroshell.solve_static`), saved with it.
    """

    summary_units = {"load_centroid": "m", "spacing_x": "m", "spacing_y": "m"}

    grid: Grid
    velocity: float
    w: np.ndarray
    load_point_deflection: float
    params: TapeParameters | None = None

    file_layout = Layout({
        "w": Variable(("x", "y")), "x": X, "y": Y,
        "velocity": Variable((), check=speed()),
        "load_point_deflection": Variable(
            (), check=scalar_check(finite_number("load_point_deflection", "m")))},
        needs=("grid",))

    @property
    def field(self) -> np.ndarray:
        """Deflection on all nodes, shape (nx + 1, ny + 1), m."""
        return self.grid.to_field(self.w)

    @property
    def max_deflection(self) -> float:
        """Deflection of largest magnitude (signed), m."""
        return float(self.w[np.argmax(np.abs(self.w))])

    def to_xarray(self, *, params=None):
        """Dataset: ``w`` (m) on ``x``, ``y``, ``velocity``, ``load_point_deflection``;
        ``params`` overrides the tape carried by the solution."""
        data_vars: dict = {}
        put(data_vars, "w", ("x", "y"), self.field, {"units": "m", "long_name": "deflection"})
        data_vars["velocity"] = ((), self.velocity, {"units": "m/s"})
        data_vars["load_point_deflection"] = ((), self.load_point_deflection, {"units": "m"})
        return dataset(data_vars, xy_coords(self.grid), self.kind,
                       params=self.params if params is None else params, grid=self.grid)

    @classmethod
    def from_xarray(cls, ds) -> StaticSolution:
        """The solution stored by :meth:`to_xarray` (or by the previous release)."""
        grid = grid_from(ds.attrs)
        return cls(grid, float(ds["velocity"]), grid.from_field(get(ds, "w")),
                   float(ds["load_point_deflection"]), params_from(ds.attrs))

    def summary(self) -> dict:
        """Deflections (m), speed (m/s), the grid and, if known, the tape (SI units)."""
        g = self.grid
        out = {"load_point_deflection": float(self.load_point_deflection),
               "max_deflection": self.max_deflection, "velocity": float(self.velocity)}
        if self.params is not None:
            out["load_centroid"] = [float(c) for c in self.params.load_centroid]
        out.update({"nx": g.nx, "ny": g.ny, "spacing_x": g.hx, "spacing_y": g.hy,
                    "unknowns": g.unknowns, "edges": g.edges})
        if self.params is not None:
            out.update({"bending_rigidity": self.params.D,
                        "foundation_stiffness": self.params.k})
        return out

    def plot(self, ax=None):
        """Filled contours of the deflection w(x, y), m; returns the Axes."""
        return draw_field(self, ax=ax)
