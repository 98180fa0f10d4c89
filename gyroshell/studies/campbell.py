"""Campbell diagrams: frequencies against tape speed, branches tracked by MAC.

At each speed the lowest ``count`` modes are computed (:func:`gyroshell.modes`) and
matched to the previous speed's by the modal assurance criterion

    MAC(φ_a, φ_b) = |φ_aᴴ φ_b|² / ((φ_aᴴ φ_a)(φ_bᴴ φ_b))   (0: orthogonal, 1: the same shape)

with an optimal assignment (Hungarian method). A match below ``min_mac`` starts a new
branch. Each point reports the MAC of its match, so a user sees how sure each link is.

The MAC of a mode with itself falls as the speed step grows (the gyroscopic modes of a
moving tape turn complex, and close frequencies mix), so where a link between neighbouring
speeds falls below ``min_mac`` the step is halved there: the speed halfway is solved and
inserted, and again, down to ``min_step``. One mode more than ``count`` is solved at each
speed and tracked too (not reported), so that a mode entering the lowest ``count`` from
above continues its branch. Links still below ``min_mac`` at the floor are named in one
:class:`CampbellTrackingWarning`.

Two branches whose frequencies swap order between neighbouring speeds *cross* (modes of
different shape pass through each other; the MAC keeps each on its branch). Two branches
whose relative gap |ω_a − ω_b| / ω̄ has a local minimum below ``veering_gap`` without
swapping *veer* (the curves approach and turn away, exchanging shapes). Excitation lines
ω = n·2πV/ℓ are the n-th harmonics of a roller or capstan of circumference ℓ (m) turning
with the tape; where a branch meets one, that speed excites the mode.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..core import validation
from ..core.errors import ParameterError
from ..core.progress import check_time, stage_line
from ..core.units import unit_of
from ..results import base, layout
from ..tape.parameters import TapeParameters
from .branches import BranchTracker, _assignment, track

if TYPE_CHECKING:
    import pandas as pd

#: Default smallest MAC that continues a branch.
MIN_MAC = 0.5
#: Default largest relative gap |ω_a − ω_b| / ω̄ at a veering.
VEERING_GAP = 0.02
#: Halvings of the largest given speed step that the default ``min_step`` allows.
REFINE_LEVELS = 6
#: Modes solved above ``count`` at each speed, tracked but not reported: a mode that enters
#: the lowest ``count`` from above continues its branch.
GUARD_MODES = 1
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
        ``omega`` (rad/s), ``growth_rate`` (Re λ, 1/s), ``mac`` (with the mode it continues
        at the previous speed, which may be the one tracked just above the lowest ``count``;
        NaN where a branch begins).
    crossings : pandas.DataFrame
        ``velocity`` (m/s, linear interpolation), ``branch_a``, ``branch_b``, ``omega``.
    veerings : pandas.DataFrame
        ``velocity`` (m/s), ``branch_a``, ``branch_b``, ``omega_a``, ``omega_b``, ``gap``
        (relative).
    critical_speed : float or None
        m/s, marked on the plot.
    info : dict
        The settings: ``min_mac``, ``veering_gap``, ``count``, ``continuation``,
        ``workers``, ``min_step`` (m/s); and how the tracking went: ``inserted`` (speeds
        added by refinement), ``mac_min``, ``mac_median`` (see :attr:`mac_min`) and
        ``unlinked`` (``[V_a, V_b]`` in m/s of each step where a branch still broke).
    params : TapeParameters or None
        The tape.
    """

    summary_units = {"unlinked": "m/s"}

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

    @property
    def mac_min(self) -> float | None:
        """The smallest MAC between a mode and the one it is matched to at the previous
        speed, below ``min_mac`` where a branch broke (None with one speed; a file of an
        older version: over the links kept)."""
        return self._mac_figures()[0]

    @property
    def mac_median(self) -> float | None:
        """The median of the same MACs as :attr:`mac_min`."""
        return self._mac_figures()[1]

    def _mac_figures(self) -> tuple[float | None, float | None]:
        if "mac_min" in self.info:
            return self.info["mac_min"], self.info["mac_median"]
        links = self.frame["mac"].dropna()
        return ((float(links.min()), float(links.median())) if len(links)
                else (None, None))

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
        """Branches, speeds (those inserted by refinement among them), the MAC of the
        matches (:attr:`mac_min`, :attr:`mac_median`), the steps where a branch broke
        (m/s), the critical speed (m/s, None if not computed), and the numbers of
        crossings and veerings."""
        return {"branches": int(self.frame["branch"].nunique()),
                "speeds": int(self.frame["velocity"].nunique()),
                "inserted": int(self.info.get("inserted", 0)),
                "mac_min": self.mac_min, "mac_median": self.mac_median,
                "unlinked": [list(map(float, step)) for step in self.info.get("unlinked", [])],
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


class CampbellTrackingWarning(UserWarning):
    """Branches left broken: the MAC between neighbouring speeds stayed below ``min_mac``
    with the speed step refined down to ``min_step``."""


def _frame(results, count: int, min_mac: float):
    """The tracked branches of consecutive speeds' modes (columns :data:`FRAME_COLUMNS`),
    the lowest ``count`` of each speed (the modes above are tracked, not reported), and
    the MAC of each reported mode's match at the previous speed (below ``min_mac`` where a
    branch broke)."""
    import pandas as pd

    rows, matched = [], []
    for k, (res, match) in enumerate(zip(results, track(results, BranchTracker(mac, min_mac)),
                                         strict=True)):
        macs = np.where(match.continued, match.similarity, np.nan)  # NaN: a branch begins
        shown = min(count, res.count)
        if k:
            matched.extend(np.where(match.assigned, match.similarity, 0.0)[:shown])
        rows.extend({"velocity": res.velocity, "branch": match.labels[j], "rank": j,
                     "omega": float(res.omega[j]),
                     "growth_rate": float(max(res.eigenvalues[j].real, 0.0)),
                     "mac": float(macs[j])} for j in range(shown))
    frame = pd.DataFrame(rows, columns=list(FRAME_COLUMNS))
    # branch labels 0, 1, ... in order of appearance among the reported modes
    labels = {b: i for i, b in enumerate(dict.fromkeys(frame["branch"]))}
    frame["branch"] = frame["branch"].map(labels).astype(int)
    figures = ((float(np.min(matched)), float(np.median(matched))) if matched
               else (None, None))
    return frame, figures


def _broken(before, after, count: int, min_mac: float) -> bool:
    """Whether a mode among the lowest ``count`` at either speed is matched (MAC, optimal
    assignment over every mode solved) below ``min_mac`` at the other."""
    c = mac(before.vectors, after.vectors)
    for i, j in zip(*_assignment(-c), strict=True):
        if (i < count or j < count) and c[i, j] < min_mac:
            return True
    return False


class _Refinement:
    """The speeds of a diagram and their modes, the step halved where a link breaks.

    ``solve(velocities)`` returns the modes at those speeds; ``min_step`` (m/s) is the
    smallest step refinement makes. The time limit covers the speeds added: before each
    round, the time since ``started`` (:func:`time.perf_counter`) per speed solved predicts
    the round's (:func:`gyroshell.core.progress.check_time`)."""

    def __init__(self, velocities, results, count: int, min_mac: float, min_step: float,
                 solve, started: float) -> None:
        self.modes = dict(zip(velocities, results, strict=True))
        self.count, self.min_mac, self.min_step, self.solve = count, min_mac, min_step, solve
        self.inserted = 0
        self._start, self._solved = started, len(results)

    def speeds(self) -> list[float]:
        return sorted(self.modes)

    def broken_steps(self) -> list[tuple[float, float]]:
        """The neighbouring speeds (m/s) between which a link breaks."""
        v = self.speeds()
        return [(a, b) for a, b in zip(v[:-1], v[1:], strict=True)
                if _broken(self.modes[a], self.modes[b], self.count, self.min_mac)]

    def run(self) -> list[tuple[float, float]]:
        """Halve every broken step wider than twice ``min_step`` until none is left;
        returns the steps still broken."""
        while True:
            broken = self.broken_steps()
            halves = [0.5 * (a + b) for a, b in broken if b - a >= 2 * self.min_step]
            if not halves:
                return broken
            self._check_time(len(halves))
            for v, res in zip(halves, self.solve(halves), strict=True):
                self.modes[v] = res
            self._solved += len(halves)
            self.inserted += len(halves)

    def _check_time(self, more: int) -> None:
        elapsed = time.perf_counter() - self._start
        per_speed = elapsed / self._solved
        check_time(elapsed + per_speed * more,
                   size=f"a Campbell diagram of {len(self.modes) + more} speeds "
                        f"({self.inserted + more} inserted where the MAC fell)",
                   how=f"an estimate from {per_speed:.3g} s per speed so far",
                   advice="raise min_step (--min-step) or lower min_mac (--min-mac)")


def _unlinked_message(steps, min_mac: float, min_step: float) -> str:
    """One line: where branches broke and what to do."""
    where = ", ".join(f"{a:.4g}-{b:.4g}" for a, b in steps[:5])
    more = f" and {len(steps) - 5} more" if len(steps) > 5 else ""
    return (f"branches left unlinked between V = {where}{more} m/s: the MAC of neighbouring "
            f"speeds stays below min_mac = {min_mac:g} down to the step min_step = "
            f"{min_step:.3g} m/s; lower min_step (--min-step) or min_mac (--min-mac), or ask "
            f"for more modes (--count)")


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
             min_step: float | None = None, **options) -> CampbellDiagram:
    """Campbell diagram of the tape over ``velocities`` (m/s, ascending).

    Where a mode's MAC with its match at the neighbouring speed falls below ``min_mac``,
    the step there is halved (the speed halfway solved and inserted), down to ``min_step``.

    Parameters
    ----------
    model : TapeModel
    velocities : sequence of float
        Speeds, m/s, ascending.
    count : int
        Modes per speed.
    min_mac, veering_gap : float
        Smallest MAC that continues a branch; largest relative gap at a veering.
    critical_speed : True, float or None
        True: compute it (:func:`gyroshell.critical_speeds`); a number: use it; None/False:
        none.
    progress : bool or None
        True: a bar on stderr; False: nothing; None: a bar on a terminal, else stage lines.
    continuation : bool
        Continue each given speed's solve from the previous ones, as :func:`gyroshell.sweep`
        does (the same frequencies to round-off); inserted speeds are solved from scratch.
    workers : int
        Local processes (>= 1), each solving a contiguous run of the speeds.
    min_step : float or None
        Smallest step (m/s, > 0) refinement makes; None: the largest given step /
        2**:data:`REFINE_LEVELS`.
    **options
        Passed to :func:`gyroshell.modes`.

    Warns
    -----
    CampbellTrackingWarning
        One line naming the steps (m/s) where branches are still broken at ``min_step``.
    """
    progress, started = _checked_model(model, critical_speed, progress), time.perf_counter()
    velocities, min_step, workers = _checked(velocities, min_mac, veering_gap, critical_speed,
                                             min_step, workers)
    refinement = _refined(model, velocities, count, min_mac, min_step, started, progress,
                          continuation=continuation, workers=workers, options=options)
    unlinked = refinement.run()
    frame, (mac_min, mac_median) = _frame([refinement.modes[v] for v in refinement.speeds()],
                                          refinement.count, min_mac)
    info = {"min_mac": min_mac, "veering_gap": veering_gap, "count": refinement.count,
            "continuation": bool(continuation), "workers": workers, "min_step": min_step,
            "inserted": refinement.inserted, "mac_min": mac_min, "mac_median": mac_median,
            "unlinked": [[a, b] for a, b in unlinked]}
    if unlinked:
        warnings.warn(_unlinked_message(unlinked, min_mac, min_step),
                      CampbellTrackingWarning, stacklevel=2)
    if critical_speed is True:
        stage_line("campbell", "the critical speed (a few more eigen-solves)",
                   progress=progress)
    return CampbellDiagram(frame, *_crossings_and_veerings(frame, veering_gap),
                           _critical_speed(model, critical_speed), info,
                           getattr(model, "params", None))


def _checked_model(model, critical_speed, progress):
    """Refuse a non-model (with what the critical speed needs, if asked); the checked
    ``progress``."""
    from ..engines.divergence import DIVERGENCE_MEMBERS
    from ..tape.model import check_model

    check_model(model, **({"members": DIVERGENCE_MEMBERS} if critical_speed is True else {}))
    return validation.progress(progress)


def _checked(velocities, min_mac, veering_gap, critical_speed, min_step, workers):
    """The speeds, the smallest step (m/s) and the workers of :func:`campbell`, checked."""
    from .sweep import check_velocities, check_workers

    velocities = check_velocities(velocities)
    if np.any(np.diff(velocities) <= 0):
        raise ParameterError("velocities must be strictly ascending (m/s)")
    validation.real("min_mac", min_mac, low=0.0, high=1.0)
    if not (critical_speed is None or isinstance(critical_speed, bool)):
        validation.positive("critical_speed", critical_speed, "m/s")
    validation.positive("veering_gap", veering_gap)
    largest = float(np.max(np.diff(velocities))) if len(velocities) > 1 else 0.0
    if min_step is None:
        min_step = largest / 2**REFINE_LEVELS if largest else 1.0
    min_step = validation.positive("min_step", min_step, "m/s")
    return velocities, min_step, check_workers(workers, len(velocities))


def _refined(model, velocities, count, min_mac, min_step, started, progress, *,
             continuation: bool, workers: int, options: dict) -> _Refinement:
    """The modes at the given speeds (``count`` and :data:`GUARD_MODES` more), ready to be
    refined."""
    from ..linalg.qep.problem import check_count, max_count
    from .sweep import solve_speeds

    count = check_count(count, model.unknowns)
    solved = min(count + GUARD_MODES, max_count(model.unknowns))

    def solve(speeds, description="campbell: refining", continued=False):
        return solve_speeds(model, speeds, solved, continuation=continued,
                            workers=min(workers, len(speeds)), options=options,
                            progress=progress, description=description,
                            above=solved - count)

    return _Refinement(velocities, solve(velocities, "campbell", continuation), count,
                       min_mac, min_step, solve, started)


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
