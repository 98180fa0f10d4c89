"""Critical speeds as results: :class:`CriticalSpeeds` (both routes) and :class:`Divergence`.

Kinds ``"critical"`` and ``"divergence"``. Files of kind ``"critical"`` keep the variable
names of the previous release (one scalar per speed, m/s), so its files load here.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..core.errors import ParameterError
from ..tape.grid import Grid
from .base import Result, dataset, from_json, grid_from, xy_coords
from .layout import INFO, Layout, Variable, X, Y, finite_number, scalar_check, speed

__all__ = ["PAPER_SPEED", "SUNDARAM_BENSON_SPEED", "CriticalSpeeds", "Divergence"]

#: Sundaram & Benson (1989/1990), all sides simply supported shell, m/s (quoted by the paper).
SUNDARAM_BENSON_SPEED = 111.0
#: Seed paper: unbounded displacements "for a small positive change from 100 m/s", m/s.
PAPER_SPEED = 100.0
#: The speeds of a :class:`CriticalSpeeds`, in their order, each a scalar variable in m/s.
_SPEEDS = ("critical_speed", "divergence_speed", "string_speed", "strip_speed",
           "sundaram_benson_speed", "paper_speed")
#: Info entries that are pairs (JSON gives them back as lists).
_PAIR_INFO = ("bracket",)


@dataclass(frozen=True)
class CriticalSpeeds(Result, kind="critical"):
    """Critical speed by both routes, with context values (all m/s).

    Attributes
    ----------
    critical_speed : float
        (a) Where the lowest frequency crosses zero (eigen-solver + root-finding).
    divergence_speed : float
        (b) √((T + μ_min)/ρ) from one ``eigsh``.
    string_speed : float
        √(T/ρ): moving string / beam without foundation (Wickert & Mote 1990).
    strip_speed : float
        √((T + 2√(Dk))/ρ): infinite strip (beam) on the shell foundation.
    sundaram_benson_speed, paper_speed : float
        Values quoted by the seed paper: 111 m/s and "just above 100 m/s".
    info : dict
        ``evaluations`` of f, ``bracket`` (m/s), ``critical_time`` and ``divergence_time`` (s),
        ``relative_difference`` |a − b| / b, ``mu`` (N/m).
    """

    summary_units = {"string_speed": "m/s", "strip_speed": "m/s",
                     "sundaram_benson_speed": "m/s", "paper_speed": "m/s",
                     "critical_seconds": "s", "divergence_seconds": "s"}

    critical_speed: float
    divergence_speed: float
    string_speed: float
    strip_speed: float
    sundaram_benson_speed: float = SUNDARAM_BENSON_SPEED
    paper_speed: float = PAPER_SPEED
    info: dict = field(default_factory=dict, compare=False)

    file_layout = Layout({name: Variable((), check=speed(name)) for name in _SPEEDS},
                         {"info": INFO})

    @property
    def relative_difference(self) -> float:
        """|critical − divergence| / divergence."""
        return abs(self.critical_speed - self.divergence_speed) / self.divergence_speed

    def as_dict(self) -> dict[str, float]:
        """The speeds (m/s) as a plain dict (JSON-ready)."""
        return {
            "critical_speed": self.critical_speed,
            "divergence_speed": self.divergence_speed,
            "relative_difference": self.relative_difference,
            "string_speed": self.string_speed,
            "strip_speed": self.strip_speed,
            "sundaram_benson_speed": self.sundaram_benson_speed,
            "paper_speed": self.paper_speed,
        }

    def summary(self) -> dict:
        """What ``gyroshell critical --json`` prints of the result: the speeds (m/s), the
        routes' times (s), the eigen-solves and μ_min (N/m)."""
        info = self.info
        return {**self.as_dict(), "critical_seconds": info.get("critical_time"),
                "divergence_seconds": info.get("divergence_time"),
                "eigen_solves": info.get("evaluations"), "mu": info.get("mu")}

    def plot(self, ax=None):
        """The speeds as bars (:func:`gyroshell.plot.critical_speeds`); returns the Axes."""
        from ..plot import critical_speeds

        return critical_speeds(self, ax=ax)

    def to_xarray(self, *, params=None):
        """Dataset of scalar speeds (m/s); the diagnostics as the ``info`` attribute."""
        dv = {name: ((), getattr(self, name), {"units": "m/s"}) for name in _SPEEDS}
        return dataset(dv, {}, self.kind, params=params, info=self.info)

    @classmethod
    def from_xarray(cls, ds) -> CriticalSpeeds:
        info = from_json(ds.attrs["info"])
        for key in _PAIR_INFO:
            if isinstance(info.get(key), list):
                info[key] = tuple(info[key])
        return cls(*(float(ds[name]) for name in _SPEEDS), info=info)


@dataclass(frozen=True)
class Divergence(Result, kind="divergence"):
    """Result of :func:`gyroshell.divergence`.

    Attributes
    ----------
    speed : float
        Divergence speed V_div, m/s.
    mu : float
        Smallest eigenvalue of A φ = μ B φ, N/m (the extra compression the plate resists).
    mode : numpy.ndarray
        Buckling mode φ (unknown vector, max |φ| = 1).
    grid : Grid, optional
        The grid of the unknowns (for the mode on the nodes, :meth:`field`).
    """

    speed: float
    mu: float
    mode: np.ndarray
    grid: Grid | None = None

    file_layout = Layout({"speed": Variable((), check=speed("speed")),
                          "mu": Variable((), check=scalar_check(finite_number("mu", "N/m"))),
                          "mode": Variable(("unknown",)),
                          "mode_shape": Variable(("x", "y"), optional=True),
                          "x": replace(X, optional=True), "y": replace(Y, optional=True)})

    @property
    def field(self) -> np.ndarray:
        """The buckling mode on all nodes, shape (nx + 1, ny + 1) (needs the grid)."""
        if self.grid is None:
            raise ParameterError("this Divergence has no grid: its mode is an unknown vector")
        return self.grid.to_field(self.mode)

    def summary(self) -> dict:
        """Divergence speed (m/s) and μ_min (N/m)."""
        return {"divergence_speed": float(self.speed), "mu": float(self.mu),
                "unknowns": int(self.mode.shape[0])}

    def to_xarray(self, *, params=None):
        """Dataset: ``speed`` (m/s), ``mu`` (N/m), ``mode`` on ``unknown`` (and the grid,
        with the mode on ``x``, ``y`` as ``mode_shape``, when known)."""
        dv = {"speed": ((), self.speed, {"units": "m/s"}),
              "mu": ((), self.mu, {"units": "N/m"}),
              "mode": (("unknown",), self.mode, {"units": "1", "long_name": "buckling mode"})}
        coords = {}
        if self.grid is not None:
            coords = xy_coords(self.grid)
            dv["mode_shape"] = (("x", "y"), self.field, {"units": "1"})
        return dataset(dv, coords, self.kind, params=params, grid=self.grid)

    @classmethod
    def from_xarray(cls, ds) -> Divergence:
        return cls(float(ds["speed"]), float(ds["mu"]), ds["mode"].values, grid_from(ds.attrs))

    def plot(self, ax=None):
        """The buckling mode on the tape (needs the grid); returns the Axes."""
        from .. import plot

        return plot.field(self.field, self.grid.x, self.grid.y, ax=ax, label="mode (1)",
                          title=f"buckling mode: V_div = {self.speed:.6g} m/s")
