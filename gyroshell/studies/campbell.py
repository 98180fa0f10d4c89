"""Campbell diagrams: frequencies against tape speed, branches tracked by MAC.

At each speed the lowest ``count`` modes are computed (:func:`gyroshell.modes`) and
matched to the previous speed's by the modal assurance criterion

    MAC(φ_a, φ_b) = |φ_aᴴ φ_b|² / ((φ_aᴴ φ_a)(φ_bᴴ φ_b))   (0: orthogonal, 1: the same shape)

with an optimal assignment (Hungarian method). A match below ``min_mac`` starts a new
branch. Each point reports the MAC of its match, so a user sees how sure each link is.

Two branches whose frequencies swap order between neighbouring speeds *cross* (modes of
different shape pass through each other; the MAC keeps each on its branch). Two branches
whose relative gap |ω_a − ω_b| / ω̄ has a local minimum below ``veering_gap`` without
swapping *veer* (the curves approach and turn away, exchanging shapes). Excitation lines
ω = n·2πV/ℓ are the n-th harmonics of a roller or capstan of circumference ℓ (m) turning
with the tape; where a branch meets one, that speed excites the mode.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..core import validation
from ..core.errors import ParameterError
from ..core.progress import stage_line
from ..core.units import unit_of
from ..results import base, layout
from ..tape.parameters import TapeParameters
from .branches import BranchTracker, track

if TYPE_CHECKING:
    import pandas as pd

#: Default smallest MAC that continues a branch.
MIN_MAC = 0.5
#: Default largest relative gap |ω_a − ω_b| / ω̄ at a veering.
VEERING_GAP = 0.02
#: Columns of the tracked branches, the crossings and the veerings.
FRAME_COLUMNS = ("velocity", "branch", "rank", "omega", "growth_rate", "mac")
CROSSING_COLUMNS = ("velocity", "branch_a", "branch_b", "omega")
VEERING_COLUMNS = ("velocity", "branch_a", "branch_b", "omega_a", "omega_b", "gap")
#: How each table is stored in a file: (variable prefix, dimension).
_STORED_TABLES = {"frame": ("", "row"), "crossings": ("crossing_", "crossing"),
                  "veerings": ("veering_", "veering")}


#: Highest harmonic n of an excitation line ω = n·2πV/ℓ.
MAX_ORDER = 1000


def check_orders(orders) -> tuple[int, ...]:
    """The harmonics n of the excitation lines: one or more integers in [1,
    :data:`MAX_ORDER`], each once, in the order given.

    Examples
    --------
    >>> check_orders([1, 2, 2])
    (1, 2)
    >>> check_orders([0, -1])
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: orders must be integers in [1, 1000] (harmonics n of ...), got 0
    """
    if isinstance(orders, (str, bytes)) or not hasattr(orders, "__iter__"):
        raise ParameterError(f"orders must be a sequence of integers in [1, {MAX_ORDER}], "
                             f"got {orders!r}")
    out = []
    for n in orders:
        try:
            out.append(validation.integer("orders", n, low=1, high=MAX_ORDER))
        except ParameterError:
            raise ParameterError(f"orders must be integers in [1, {MAX_ORDER}] (harmonics n "
                                 f"of omega = n 2 pi V / circumference), got {n!r}") from None
    if not out:
        raise ParameterError("orders must hold at least one harmonic n >= 1")
    return tuple(dict.fromkeys(out))


def mac(phi_a: np.ndarray, phi_b: np.ndarray) -> np.ndarray:
    """MAC matrix between the columns of ``phi_a`` (n, p) and ``phi_b`` (n, q): (p, q)."""
    a, b = np.atleast_2d(phi_a.T).T, np.atleast_2d(phi_b.T).T
    cross = np.abs(a.conj().T @ b) ** 2
    na = np.real(np.sum(a.conj() * a, axis=0))
    nb = np.real(np.sum(b.conj() * b, axis=0))
    return cross / np.outer(na, nb)


@dataclass(frozen=True, eq=False)
class CampbellDiagram(base.Result, kind="campbell"):
    """Tracked frequency branches against speed.

    Attributes
    ----------
    frame : pandas.DataFrame
        ``velocity`` (m/s), ``branch``, ``rank`` (position in ascending ω at that speed),
        ``omega`` (rad/s), ``growth_rate`` (Re λ, 1/s), ``mac`` (with the branch's previous
        point; NaN at a branch's first point).
    crossings : pandas.DataFrame
        ``velocity`` (m/s, linear interpolation), ``branch_a``, ``branch_b``, ``omega``.
    veerings : pandas.DataFrame
        ``velocity`` (m/s), ``branch_a``, ``branch_b``, ``omega_a``, ``omega_b``, ``gap``
        (relative).
    critical_speed : float or None
        m/s, marked on the plot.
    info : dict
        The settings: ``min_mac``, ``veering_gap``, ``count``, ``continuation``,
        ``workers``.
    params : TapeParameters or None
        The tape.
    """

    frame: pd.DataFrame
    crossings: pd.DataFrame
    veerings: pd.DataFrame
    critical_speed: float | None = None
    info: dict = field(default_factory=dict)
    params: TapeParameters | None = None

    #: The file: the three tables' columns, the critical speed and the tracking record.
    file_layout = layout.Layout(attrs={
        "tables": layout.json_object("tables"), "info": layout.INFO,
        "critical_speed": layout.Attr(layout.of_type("critical_speed",
                                                     (int, float, type(None)),
                                                     "a speed in m/s or null"))},
        check=lambda ds: _check_tables(ds))

    @staticmethod
    def excitation(order: int, circumference: float, velocity):
        """ω = n·2πV/ℓ, rad/s, of the n-th harmonic of a roller of circumference ℓ (m)."""
        (order,) = check_orders([order])
        circumference = validation.positive("circumference", circumference, "m")
        return order * 2 * np.pi * np.asarray(velocity, dtype=float) / circumference

    def resonances(self, circumference: float, orders=(1, 2, 3)) -> pd.DataFrame:
        """Where branches meet excitation lines: ``order``, ``branch``, ``velocity`` (m/s),
        ``omega`` (rad/s), by linear interpolation between the computed speeds."""
        import pandas as pd

        orders = check_orders(orders)
        validation.positive("circumference", circumference, "m")
        rows = []
        for branch, g in self.frame.groupby("branch"):
            g = g.sort_values("velocity")
            v, w = g["velocity"].to_numpy(), g["omega"].to_numpy()
            for n in orders:
                d = w - self.excitation(n, circumference, v)
                for k in np.flatnonzero(np.sign(d[:-1]) * np.sign(d[1:]) < 0):
                    t = d[k] / (d[k] - d[k + 1])
                    vv = v[k] + t * (v[k + 1] - v[k])
                    rows.append({"order": n, "branch": branch, "velocity": vv,
                                 "omega": float(self.excitation(n, circumference, vv))})
        return pd.DataFrame(rows, columns=["order", "branch", "velocity", "omega"])

    def plot(self, ax=None, **options):
        """See :func:`gyroshell.plot.campbell` (``orders`` and ``circumference`` checked
        first)."""
        from .. import plot

        if "orders" in options:
            options["orders"] = check_orders(options["orders"])
        if options.get("circumference") is not None:
            validation.positive("circumference", options["circumference"], "m")
        return plot.campbell(self, ax=ax, **options)

    def to_frame(self) -> pd.DataFrame:
        """The tracked branches (CSV and Parquet files hold these only; NetCDF all)."""
        return self.frame

    def to_xarray(self, *, params=None):
        """The branches on dimension ``row``, the crossings on ``crossing`` (variables
        ``crossing_*``) and the veerings on ``veering`` (``veering_*``), SI units, with the
        critical speed and the settings; ``params`` if the diagram does not know its tape."""
        data_vars: dict = {}
        layout = {name: _put_table(data_vars, getattr(self, name), prefix, dim)
                  for name, (prefix, dim) in _STORED_TABLES.items()}
        tape = self.params if self.params is not None else params
        return base.dataset(data_vars, {}, self.kind, params=tape,
                            info=self.info, tables=layout,
                            critical_speed=self.critical_speed)

    @classmethod
    def from_xarray(cls, ds) -> CampbellDiagram:
        """The diagram stored by :meth:`to_xarray`."""
        layout = base.from_json(ds.attrs["tables"])
        tables = {name: _get_table(ds, _STORED_TABLES[name][0], columns)
                  for name, columns in layout.items()}
        return cls(tables["frame"], tables["crossings"], tables["veerings"],
                   base.from_json(ds.attrs["critical_speed"]),
                   base.from_json(ds.attrs["info"]), base.params_from(ds.attrs))

    def summary(self) -> dict:
        """Branches, speeds, the MAC of the links (min, median), the critical speed (m/s,
        None if not computed), and the numbers of crossings and veerings."""
        links = self.frame["mac"].dropna()
        return {"branches": int(self.frame["branch"].nunique()),
                "speeds": int(self.frame["velocity"].nunique()),
                "mac_min": float(links.min()) if len(links) else None,
                "mac_median": float(links.median()) if len(links) else None,
                "critical_speed": self.critical_speed,
                "crossings": len(self.crossings), "veerings": len(self.veerings)}


def _put_table(data_vars: dict, frame, prefix: str, dim: str) -> dict[str, str]:
    """Add ``frame``'s columns as variables ``prefix + column`` on ``dim`` (SI units);
    returns column -> dtype, so that an empty table comes back with its dtypes."""
    dtypes = {}
    for column in frame.columns:
        values = frame[column].to_numpy()
        dtypes[str(column)] = str(values.dtype)
        if values.dtype == object and not len(values):  # no crossings: nothing to keep
            values = values.astype(float)
        unit = unit_of(str(column))
        data_vars[prefix + str(column)] = (dim, values, {"units": unit} if unit else {})
    return dtypes


def _get_table(ds, prefix: str, dtypes: dict[str, str]):
    import pandas as pd

    return pd.DataFrame({column: ds[prefix + column].values.astype(dtype)
                         for column, dtype in dtypes.items()}, columns=list(dtypes))


def _frame(results, min_mac: float):
    """The tracked branches of consecutive speeds' modes (columns :data:`FRAME_COLUMNS`)."""
    import pandas as pd

    rows = []
    for res, match in zip(results, track(results, BranchTracker(mac, min_mac)), strict=True):
        macs = np.where(match.continued, match.similarity, np.nan)  # NaN: a branch begins
        rows.extend({"velocity": res.velocity, "branch": match.labels[j], "rank": j,
                     "omega": float(res.omega[j]),
                     "growth_rate": float(max(res.eigenvalues[j].real, 0.0)),
                     "mac": float(macs[j])} for j in range(res.count))
    return pd.DataFrame(rows, columns=list(FRAME_COLUMNS))


def _pairs(frame):
    """(branch a, branch b, velocities, ω_a, ω_b) over the speeds where both exist."""
    table = frame.pivot_table(index="velocity", columns="branch", values="omega")
    branches = list(table.columns)
    for i, a in enumerate(branches):
        for b in branches[i + 1:]:
            both = table[[a, b]].dropna()
            if len(both) >= 2:
                yield a, b, both.index.to_numpy(), both[a].to_numpy(), both[b].to_numpy()


def _crossings_and_veerings(frame, veering_gap: float):
    import pandas as pd

    cross, veer = [], []
    for a, b, v, wa, wb in _pairs(frame):
        d = wa - wb
        nz = np.flatnonzero(d != 0)  # a pair that touches exactly at a speed crosses there
        for i, j in zip(nz[:-1], nz[1:], strict=True):
            if np.sign(d[i]) != np.sign(d[j]):
                t = d[i] / (d[i] - d[j])
                cross.append({"velocity": v[i] + t * (v[j] - v[i]), "branch_a": a,
                              "branch_b": b, "omega": wa[i] + t * (wa[j] - wa[i])})
        gap = np.abs(d) / (0.5 * (wa + wb))
        for k in range(1, len(v) - 1):
            if (gap[k] < gap[k - 1] and gap[k] < gap[k + 1] and gap[k] < veering_gap
                    and np.sign(d[k - 1]) == np.sign(d[k]) == np.sign(d[k + 1])):
                veer.append({"velocity": v[k], "branch_a": a, "branch_b": b,
                             "omega_a": wa[k], "omega_b": wb[k], "gap": gap[k]})
    return (pd.DataFrame(cross, columns=list(CROSSING_COLUMNS)),
            pd.DataFrame(veer, columns=list(VEERING_COLUMNS)))


def campbell(model, velocities, count: int = 6, *, min_mac: float = MIN_MAC,
             veering_gap: float = VEERING_GAP, critical_speed: float | bool | None = True,
             progress: bool | None = None, continuation: bool = False, workers: int = 1,
             **options) -> CampbellDiagram:
    """Campbell diagram of the tape over ``velocities`` (m/s).

    Parameters
    ----------
    model : TapeModel
    velocities : sequence of float
        Speeds, m/s, ascending.
    count : int
        Modes per speed.
    min_mac : float
        Smallest MAC that continues a branch.
    veering_gap : float
        Largest relative gap at a veering.
    critical_speed : True, float or None
        True: compute it (:func:`gyroshell.critical_speeds`); a number: use it;
        None/False: none.
    progress : bool or None
        True: a progress bar on stderr, False: nothing; None: the bar on a terminal, else
        one line per stage (:class:`gyroshell.core.progress.StageLines`).
    continuation : bool
        Continue each solve from the previous speeds' modes, as :func:`gyroshell.sweep`
        does (the same frequencies to round-off, in fewer Lanczos steps); False solves each
        speed from scratch.
    workers : int
        Local processes (>= 1), each solving a contiguous run of the speeds, as in
        :func:`gyroshell.sweep`.
    **options
        Passed to :func:`gyroshell.modes`.
    """
    from ..engines.divergence import DIVERGENCE_MEMBERS
    from ..tape.model import check_model
    from .sweep import check_velocities, check_workers, solve_speeds

    check_model(model, **({"members": DIVERGENCE_MEMBERS} if critical_speed is True else {}))
    progress = validation.progress(progress)
    velocities = check_velocities(velocities)
    if np.any(np.diff(velocities) <= 0):
        raise ParameterError("velocities must be strictly ascending (m/s)")
    validation.real("min_mac", min_mac, low=0.0, high=1.0)
    if not (critical_speed is None or isinstance(critical_speed, bool)):
        validation.positive("critical_speed", critical_speed, "m/s")
    validation.positive("veering_gap", veering_gap)
    workers = check_workers(workers, len(velocities))
    results = solve_speeds(model, velocities, count, continuation=continuation,
                           workers=workers, options=options, progress=progress,
                           description="campbell")
    frame = _frame(results, min_mac)
    crossings, veerings = _crossings_and_veerings(frame, veering_gap)
    info = {"min_mac": min_mac, "veering_gap": veering_gap, "count": int(count),
            "continuation": bool(continuation), "workers": workers}
    if critical_speed is True:
        stage_line("campbell", "the critical speed (a few more eigen-solves)",
                   progress=progress)
    return CampbellDiagram(frame, crossings, veerings, _critical_speed(model, critical_speed),
                           info, getattr(model, "params", None))


def _critical_speed(model, critical_speed: float | bool | None) -> float | None:
    """The critical speed (m/s) to mark: computed for True, none for None or False."""
    if critical_speed is True:
        from ..engines.critical import critical_speeds

        critical_speed = critical_speeds(model).critical_speed
    elif critical_speed is False:
        critical_speed = None
    return None if critical_speed is None else float(critical_speed)


def _check_tables(ds) -> None:
    """A Campbell file's ``tables`` attribute: each table's columns stored on its
    dimension."""
    tables = base.from_json(ds.attrs["tables"])
    stored = {"frame": ("", "row"), "crossings": ("crossing_", "crossing"),
              "veerings": ("veering_", "veering")}
    if set(tables) != set(stored) or not all(isinstance(t, dict) for t in tables.values()):
        raise ParameterError(f"attribute tables must map {', '.join(stored)} to their columns")
    for name, columns in tables.items():
        prefix, dim = stored[name]
        for column in columns:
            variable = prefix + column
            if variable not in ds.variables or tuple(ds[variable].dims) != (dim,):
                raise ParameterError(f"column {column} of the {name} table is missing "
                                     f"(variable {variable} on {dim})")
