"""What a transient run keeps: the load-point history, snapshots, centre lines, and files.

The time marcher (:mod:`gyroshell.engines.newmark`) fills these; studies and plots read
them. Full fields are kept only at the steps asked for, so a run of thousands of steps on
the L_x/L_y = 19 grid holds one float per step unless told otherwise.

A :class:`TransientResult` is the saved kind ``"transient"``. Its file holds, on dimension
``t`` (s): ``load_point`` (m), ``energy`` (J, if recorded) and ``head_displacements`` (m,
on ``t`` x ``head``, with several moving heads); the snapshots ``fields`` (m) on
``snapshot_time`` x ``x`` x ``y`` and ``centerlines`` (m) on ``centerline_time`` x ``x``;
the final state ``final_w``, ``final_v``, ``final_a`` (m, m/s, m/s²) on ``unknown``; the
scalars ``velocity``, ``dt``, ``beta``, ``gamma``; and the run's ``info``. Files of the
previous release (without head histories) load as results without them.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..core import budget, validation
from ..core.errors import ParameterError
from ..core.files import atomic_path
from ..plot import load_point_history
from ..tape.grid import Grid
from .base import Result, dataset, from_json, write_table
from .layout import INFO, Layout, Variable, X, Y, monotonic, nonnegative, positive, speed


def steps_at(times, dt: float, steps: int, t0: float = 0.0, *, name: str) -> np.ndarray:
    """Step indices n (time t0 + n dt) nearest to ``times`` (s); sorted, unique.

    Raises
    ------
    ParameterError
        If a time is not finite or lies outside [t0, t0 + steps dt] (by more than dt/2).
    """
    try:
        t = np.atleast_1d(np.asarray(times, dtype=float))
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a list of finite times, s") from None
    if t.ndim != 1 or not np.all(np.isfinite(t)):
        raise ParameterError(f"{name} must be a list of finite times, s")
    n = np.rint((t - t0) / dt)
    if np.any(n < 0) or np.any(n > steps):
        raise ParameterError(f"{name} must lie in [{t0:g}, {t0 + steps * dt:g}] s "
                             f"(the run's {steps} steps of {dt:g} s)")
    return np.unique(n.astype(np.int64))


def every(interval: int, steps: int, *, name: str) -> np.ndarray:
    """Step indices 0, N, 2N, ... <= steps."""
    interval = validation.integer(name, interval, low=1)
    return np.arange(0, steps + 1, interval, dtype=np.int64)


def _how_many(times) -> int:
    return 0 if times is None else int(np.size(times))


class Recorder:
    """Keeps full fields and centre lines at chosen steps of one run (preallocated).

    Parameters
    ----------
    grid : Grid
    steps : int
        Steps of the run (instants 0..steps).
    dt, t0 : float
        Time step and initial time, s.
    snapshot_times, snapshot_every, centerline_times
        As in :meth:`gyroshell.engines.newmark.Newmark.march`.

    Raises
    ------
    ParameterError
        If the history and the kept fields cannot fit in memory
        (:func:`gyroshell.core.budget.check_transient`), checked before allocating them.
    """

    def __init__(self, grid: Grid, steps: int, dt: float, t0: float = 0.0, *,
                 snapshot_times=None, snapshot_every: int | None = None,
                 centerline_times=None) -> None:
        steps = validation.integer("steps", steps, low=1)
        kept = budget.snapshot_count(steps, snapshot_every) if snapshot_every else 0
        budget.check_transient(grid.nx, grid.ny, grid.edges, steps,
                               fields=kept + _how_many(snapshot_times),
                               centerlines=_how_many(centerline_times))
        snap = np.zeros(0, dtype=np.int64)
        if snapshot_times is not None:
            snap = steps_at(snapshot_times, dt, steps, t0, name="snapshot_times")
        if snapshot_every is not None:
            snap = np.union1d(snap, every(snapshot_every, steps, name="snapshot_every"))
        line = np.zeros(0, dtype=np.int64)
        if centerline_times is not None:
            line = steps_at(centerline_times, dt, steps, t0, name="centerline_times")
        self.grid, self._snap, self._line = grid, snap, line
        self._fields = np.empty((len(snap), *grid.shape))
        self._lines = np.empty((len(line), grid.nx + 1))
        self._k_snap = self._k_line = 0
        self._plan = None  # (the half it is for, or None; its centre-line plan)
        #: wanted[n] is non-zero at the steps where something is kept.
        self.wanted = np.zeros(steps + 1, dtype=np.int8)
        self.wanted[snap] |= 1
        self.wanted[line] |= 2

    def record(self, n: int, w: np.ndarray, half=None) -> None:
        """Keep what step n asks for, from the unknown vector w (m), or from the half's
        unknowns z of a mirror-symmetric field w = P_s z if ``half`` (a
        :class:`gyroshell.tape.mirror.SymmetricHalf`) is given.

        A centre line is read off the two columns of unknowns next to y = L_y/2 (those of
        the half for z), without forming the field: the same numbers as
        :meth:`Grid.centerline` of the field, which a march recording its centre line at
        every step would otherwise build at every step."""
        flags = self.wanted[n]
        if not flags:
            return
        if flags & 1:
            self._fields[self._k_snap] = self.grid.to_field(
                w if half is None else half.expand(w))
            self._k_snap += 1
        if flags & 2:
            self._centerline(w, half, self._lines[self._k_line])
            self._k_line += 1

    def _centerline(self, w: np.ndarray, half, out: np.ndarray) -> None:
        """w(x, L_y/2) into ``out`` (shape (nx + 1,)) from the unknowns w, or z on ``half``:
        (1 − f) w[:, j] + f w[:, j + 1] (:meth:`Grid.centerline_weights`), zero on
        supported lines; w = z times the half's value weight on the column's pair."""
        if self._plan is None or self._plan[0] is not half:
            self._plan = (half, self._centerline_plan(half))
        across, (a, wa), (b, wb), f = self._plan[1]
        values = w.reshape(-1, across)
        out[:] = 0.0
        out[self.grid.x_unknowns] = (1.0 - f) * (values[:, a] * wa) + f * (values[:, b] * wb)

    def _centerline_plan(self, half) -> tuple:
        """(unknowns per line of w, (column, weight) of the two columns beside the centre
        line, weight 0 on a supported edge's, and the fraction f)."""
        g = self.grid
        j, f = g.centerline_weights()
        first = g.y_unknowns.start  # the field column of unknown column 0

        def column(k: int) -> tuple:
            k -= first
            if not 0 <= k < g.n_across:
                return 0, 0.0               # a supported line: w = 0 there
            if half is None:
                return k, 1.0
            k = min(k, g.n_across - 1 - k)
            return k, float(half.value_weights[k])

        return (g.n_across if half is None else half.columns), column(j), column(j + 1), f

    def snapshots(self, times: np.ndarray) -> Snapshots:
        """The kept fields and lines, given the run's instants ``times`` (s)."""
        g = self.grid
        return Snapshots(g.x.copy(), g.y.copy(), times[self._snap], self._fields,
                         times[self._line], self._lines)


@dataclass(frozen=True)
class Snapshots:
    """Full fields and centre lines y = L_y/2 at chosen times.

    Attributes
    ----------
    x, y : numpy.ndarray
        Node coordinates, m, shapes (nx + 1,) and (ny + 1,).
    times : numpy.ndarray
        Times of the full fields, s, shape (k,).
    fields : numpy.ndarray
        w on all nodes, m, shape (k, nx + 1, ny + 1); axis 1 is x.
    centerline_times : numpy.ndarray
        Times of the centre lines, s, shape (c,).
    centerlines : numpy.ndarray
        w(x, L_y/2), m, shape (c, nx + 1) (linear interpolation across y if needed).
    """

    x: np.ndarray
    y: np.ndarray
    times: np.ndarray = field(default_factory=lambda: np.zeros(0))
    fields: np.ndarray | None = None
    centerline_times: np.ndarray = field(default_factory=lambda: np.zeros(0))
    centerlines: np.ndarray | None = None

    def __post_init__(self) -> None:
        put = object.__setattr__
        nx1, ny1 = len(self.x), len(self.y)
        if self.fields is None:
            put(self, "fields", np.zeros((0, nx1, ny1)))
        if self.centerlines is None:
            put(self, "centerlines", np.zeros((0, nx1)))
        if self.fields.shape != (len(self.times), nx1, ny1):
            raise ParameterError(f"fields must have shape ({len(self.times)}, {nx1}, {ny1})")
        if self.centerlines.shape != (len(self.centerline_times), nx1):
            raise ParameterError(f"centerlines must have shape "
                                 f"({len(self.centerline_times)}, {nx1})")

    def __len__(self) -> int:
        return len(self.times)

    def coords(self) -> dict:
        """Dataset coordinates of the snapshots: ``x``, ``y`` (m), ``snapshot_time``,
        ``centerline_time`` (s)."""
        return {"x": ("x", self.x, {"units": "m"}), "y": ("y", self.y, {"units": "m"}),
                "snapshot_time": ("snapshot_time", self.times, {"units": "s"}),
                "centerline_time": ("centerline_time", self.centerline_times,
                                    {"units": "s"})}

    def data_vars(self) -> dict:
        """Dataset variables of the snapshots: ``fields`` and ``centerlines`` (m)."""
        return {"fields": (("snapshot_time", "x", "y"), self.fields, {"units": "m"}),
                "centerlines": (("centerline_time", "x"), self.centerlines, {"units": "m"})}

    @classmethod
    def from_xarray(cls, ds) -> Snapshots:
        """The snapshots stored by :meth:`coords` and :meth:`data_vars` in ``ds``."""
        return cls(ds["x"].values, ds["y"].values, ds["snapshot_time"].values,
                   ds["fields"].values, ds["centerline_time"].values,
                   ds["centerlines"].values)

    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write an .npz (x, y, times, fields, centerline_times, centerlines); whole or not."""
        with atomic_path(path) as tmp, open(tmp, "wb") as fh:
            np.savez(fh, x=self.x, y=self.y, times=self.times, fields=self.fields,
                     centerline_times=self.centerline_times, centerlines=self.centerlines)
        return Path(path)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Snapshots:
        """Read what :meth:`save` wrote."""
        with np.load(path) as data:
            return cls(**{k: data[k] for k in ("x", "y", "times", "fields",
                                                "centerline_times", "centerlines")})


@dataclass(frozen=True)
class TransientResult(Result, kind="transient"):
    """One time march of M a + G v + K w = f(t) F.

    Attributes
    ----------
    times : numpy.ndarray
        t_n = t0 + n Δt, s, shape (steps + 1,), including the initial instant.
    load_point : numpy.ndarray
        Load-point displacement w(x_0, y_0, t_n), m, shape (steps + 1,).
    snapshots : Snapshots
        Full fields and centre lines at the requested times (empty if none asked).
    w, v, a : numpy.ndarray
        Final displacement (m), velocity (m/s) and acceleration (m/s²) of the unknowns:
        pass ``w0=w, v0=v, t0=times[-1]`` to continue the run.
    energy : numpy.ndarray or None
        E_n = ½vᵀMv + ½wᵀKw − f(t_n) Fᵀw, J, if recorded.
    velocity, dt, beta, gamma : float
        Tape speed V (m/s), time step Δt (s) and Newmark's β, γ.
    info : dict
        Run statistics: back-end, factor_time, solve_time, loop_time (s), steps, unknowns;
        ``symmetry`` ("half" if the mirror-symmetric half was marched, else "full") and
        ``marched_unknowns``.
    head_displacements : numpy.ndarray or None
        With several moving heads: w under each head's current centre, m, shape
        (steps + 1, heads); ``load_point`` is then head 0's column.
    """

    summary_units = {"dt": "s", "final_time": "s", "final_load_point_displacement": "m",
                     "max_load_point_displacement": "m", "min_load_point_displacement": "m",
                     "factor_time": "s", "loop_time": "s", "step_time": "s",
                     "damping": "N*s/m^3"}

    times: np.ndarray
    load_point: np.ndarray
    snapshots: Snapshots
    w: np.ndarray
    v: np.ndarray
    a: np.ndarray
    velocity: float
    dt: float
    beta: float
    gamma: float
    energy: np.ndarray | None = None
    info: dict = field(default_factory=dict)
    head_displacements: np.ndarray | None = None

    file_layout = Layout({
        "t": Variable(("t",), check=monotonic("t")), "load_point": Variable(("t",)),
        "x": X, "y": Y,
        "snapshot_time": Variable(("snapshot_time",), check=monotonic("snapshot_time")),
        "centerline_time": Variable(("centerline_time",),
                                    check=monotonic("centerline_time")),
        "fields": Variable(("snapshot_time", "x", "y")),
        "centerlines": Variable(("centerline_time", "x")),
        "final_w": Variable(("unknown",)), "final_v": Variable(("unknown",)),
        "final_a": Variable(("unknown",)),
        "energy": Variable(("t",), optional=True),
        "head_displacements": Variable(("t", "head"), optional=True),
        "velocity": Variable((), check=speed()), "dt": Variable((), check=positive("dt", "s")),
        "beta": Variable((), check=nonnegative("beta")),
        "gamma": Variable((), check=nonnegative("gamma"))},
        {"info": INFO})

    @property
    def steps(self) -> int:
        return len(self.times) - 1

    def to_xarray(self, *, params=None):
        """Dataset of the whole run (see the module docstring); ``params`` (a
        :class:`~gyroshell.TapeParameters`) is stored as metadata."""
        coords = {"t": ("t", self.times, {"units": "s"}), **self.snapshots.coords()}
        data_vars = {"load_point": (("t",), self.load_point,
                                    {"units": "m", "long_name": "load-point displacement"}),
                     **self.snapshots.data_vars()}
        for name, unit in (("w", "m"), ("v", "m/s"), ("a", "m/s^2")):
            data_vars[f"final_{name}"] = (("unknown",), getattr(self, name), {"units": unit})
        if self.energy is not None:
            data_vars["energy"] = (("t",), self.energy, {"units": "J"})
        if self.head_displacements is not None:
            data_vars["head_displacements"] = (
                ("t", "head"), self.head_displacements,
                {"units": "m", "long_name": "displacement under each head's centre"})
        for name, unit in (("velocity", "m/s"), ("dt", "s"), ("beta", "1"), ("gamma", "1")):
            data_vars[name] = ((), getattr(self, name), {"units": unit})
        return dataset(data_vars, coords, self.kind, params=params, info=self.info)

    @classmethod
    def from_xarray(cls, ds) -> TransientResult:
        """The run stored by :meth:`to_xarray` (or by the previous release)."""
        def optional(name):
            return ds[name].values if name in ds else None

        return cls(ds["t"].values, ds["load_point"].values, Snapshots.from_xarray(ds),
                   ds["final_w"].values, ds["final_v"].values, ds["final_a"].values,
                   float(ds["velocity"]), float(ds["dt"]), float(ds["beta"]),
                   float(ds["gamma"]), optional("energy"), from_json(ds.attrs["info"]),
                   head_displacements=optional("head_displacements"))

    def summary(self) -> dict:
        """The run's settings, load-point extremes (m), grid and timings (s), SI units."""
        w, info = self.load_point, self.info
        damping = info.get("damping", {})
        return {
            "velocity": self.velocity, "dt": self.dt, "steps": self.steps,
            "beta": self.beta, "gamma": self.gamma, "final_time": float(self.times[-1]),
            "final_load_point_displacement": float(w[-1]),
            "max_load_point_displacement": float(w.max()),
            "min_load_point_displacement": float(w.min()),
            "nx": len(self.snapshots.x) - 1, "ny": len(self.snapshots.y) - 1,
            "unknowns": info.get("unknowns", len(self.w)),
            "backend": info.get("backend"), "factor_time": info.get("factor_time"),
            "loop_time": info.get("loop_time"), "step_time": info.get("step_time"),
            "moving_load": bool(info.get("moving_load", self.head_displacements is not None)),
            "symmetry": info.get("symmetry", "full"),
            "damping": damping.get("viscous", 0.0),
            "rayleigh": [damping.get("mass_coefficient", 0.0),
                         damping.get("stiffness_coefficient", 0.0)],
        }

    def plot(self, ax=None):
        """The load-point displacement against time (:func:`gyroshell.plot.load_point_history`);
        returns the Axes."""
        return load_point_history(self, ax=ax)

    def to_frame(self):
        """pandas DataFrame with columns ``t`` (s) and ``w`` (m) (+ ``w_head<k>``, m, with
        several heads; + ``energy``, J)."""
        import pandas as pd

        data = {"t": self.times, "w": self.load_point}
        if self.head_displacements is not None:
            for k in range(self.head_displacements.shape[1]):
                data[f"w_head{k}"] = self.head_displacements[:, k]
        if self.energy is not None:
            data["energy"] = self.energy
        return pd.DataFrame(data)

    def to_csv(self, path: str | os.PathLike[str]) -> Path:
        """Write the load-point history (``t``, ``w``) as CSV (Parquet for a ``.parquet``
        path), whole or not at all (:func:`gyroshell.results.base.write_table`)."""
        return write_table(self.to_frame()[["t", "w"]], path)

    @staticmethod
    def read_csv(path: str | os.PathLike[str]):
        """The load-point history written by :meth:`to_csv`, as a DataFrame (t in s, w in m),
        bit-exact (pandas' round-trip float parser)."""
        from ..core.files import read_csv_exact

        return read_csv_exact(path)

    def save_snapshots(self, path: str | os.PathLike[str]) -> Path:
        """Write the snapshots (fields, centre lines, coordinates) as .npz."""
        return self.snapshots.save(path)
