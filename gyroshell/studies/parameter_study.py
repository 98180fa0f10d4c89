"""Parameter studies: vary tape parameters over a grid or a list of points, one row each.

A study takes a base tape (:class:`~gyroshell.TapeParameters` and a speed V), a
set of points (each point changes some fields, and possibly ``velocity``) and what to compute
at every point:

``critical``
    ``critical_speed`` (m/s, where the lowest frequency reaches zero) and
    ``divergence_speed`` (m/s, where K(V) loses definiteness) from
    :func:`gyroshell.critical_speeds`.
``modes``
    ``omega_1`` ... ``omega_<count>`` (rad/s, the lowest frequencies from
    :func:`gyroshell.modes`; above the critical speed the eigenvalues nearest zero),
    ``growth_rate`` (largest Re λ among them, 1/s) and ``stability``
    (:func:`tape_stability`: ``stable``, ``divergence`` or ``flutter``).
``static``
    ``load_point_deflection`` and ``max_deflection`` (m) from
    :func:`gyroshell.solve_static` (a speed at or above critical fails in its row).
``period``
    ``period`` = 2π/ω₁ (s), the dominant period of the load-point response (the band edge
    of its spectrum; see :mod:`gyroshell.reproduce.period`), and ``stability``.

Every point is an independent task. They run in this process (``workers=1``), in local
worker processes (``workers=N``, the default is the number of CPUs; no setup), or on a Dask
distributed cluster the user started (``scheduler="tcp://HOST:PORT"``); the rows are the
same in every case. A point that fails is reported in its row (``error``, the other values
NaN) and the study goes on. With ``cache=PATH`` each finished point is appended to a JSON
Lines file, and a study started again with the same cache computes only the points that are
missing (rows are read back bit for bit: JSON keeps float64 exactly).
"""

from __future__ import annotations

import dataclasses
import hashlib
import itertools
import json
import math
import os
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..core import budget
from ..core.errors import ParameterError
from ..core.parallel import process_pool
from ..core.progress import progress_bar
from ..core.units import unit_of
from ..results import base as results_base
from ..tape.parameters import TapeParameters, check_velocity

if TYPE_CHECKING:
    import pandas as pd

#: What a study can compute at each point.
COMPUTE_CHOICES: tuple[str, ...] = ("critical", "modes", "static", "period")
#: Parameters a study can vary: every TapeParameters field, plus the tape speed.
VARIABLE_NAMES: tuple[str, ...] = ("velocity",) + tuple(
    f.name for f in dataclasses.fields(TapeParameters))

STABLE, DIVERGENCE, FLUTTER = "stable", "divergence", "flutter"
#: K(V) indefinite with an even index and no growing eigenvalue among those computed.
UNDETERMINED = "undetermined"
#: Largest number of unknowns for which a point's whole spectrum is computed densely.
DENSE_LIMIT = 700
#: How long to wait for a Dask scheduler to answer.
CONNECT_TIMEOUT = "10s"
#: Chunks per worker when chunk size is automatic (balances load against overhead).
CHUNKS_PER_WORKER = 4


# ----- stability ---------------------------------------------------------------------------
def classify_stability(eigenvalues, *args, **kwargs):
    """:func:`gyroshell.classify_stability`, imported on first use (it loads scipy.linalg,
    which the CLI's parser and refusals do not need)."""
    from .stability import classify_stability as classify

    return classify(eigenvalues, *args, **kwargs)


def quadratic_eigenvalues(M, G, K) -> np.ndarray:
    """All 2n eigenvalues λ (1/s) of det(λ²M + λG + K) = 0, dense (M diagonal or full)."""
    M, G, K = (np.asarray(a.toarray() if hasattr(a, "toarray") else a, dtype=float)
               for a in (M, G, K))
    n = len(K)
    Minv = np.linalg.inv(M)
    companion = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ G]])
    import scipy.linalg as la

    from ..core.parallel import blas_threads

    with blas_threads(1):  # studies run one point per core
        return la.eigvals(companion)


def tape_stability(model, velocity: float, eigenvalues=None) -> str:
    """Stability of the moving tape at speed V: ``stable``, ``divergence`` or ``flutter``.

    The tape is a conservative gyroscopic system (G skew, K symmetric), so two facts decide
    most speeds without eigenvalues, from the inertia of K(V) (negative pivots of its LDLᵀ):

    * K(V) positive definite (below the critical speed): stable, by the energy
      ½vᵀMv + ½wᵀKw, which is conserved and positive definite.
    * An odd number of negative eigenvalues of K(V): det Q(λ) = det(λ²M + λG + K) is
      negative at λ = 0 and positive for large real λ, so a real positive eigenvalue exists:
      divergence.

    With an even, non-zero number, G may stabilize the tape or not: the whole spectrum is
    computed densely (up to :data:`DENSE_LIMIT` unknowns) and classified by
    :func:`classify_stability`. On larger grids the ``eigenvalues`` given (those nearest
    zero, from :func:`gyroshell.modes`) decide if one of them grows, else the answer
    is ``undetermined``: the modes nearest zero do not show a far-off growing one.
    """
    from ..linalg.inertia import factor_inertia

    K = model.K(velocity)
    negatives = factor_inertia(K).negatives
    if negatives is None:  # pivoting happened: count the negative eigenvalues densely
        if model.unknowns > DENSE_LIMIT:
            negatives = -1
        else:
            negatives = int(np.count_nonzero(np.linalg.eigvalsh(K.toarray()) < 0))
    if negatives == 0:
        return STABLE
    if negatives > 0 and negatives % 2 == 1:
        return DIVERGENCE
    if model.unknowns <= DENSE_LIMIT:
        return classify_stability(quadratic_eigenvalues(model.M, model.G(velocity), K))
    if eigenvalues is not None:
        verdict = classify_stability(eigenvalues)
        if verdict != STABLE:
            return verdict
    return UNDETERMINED


# ----- points ------------------------------------------------------------------------------
def _canonical(name: str) -> str:
    key = str(name).strip().replace("-", "_")
    if key not in VARIABLE_NAMES:
        raise ParameterError(f"cannot vary {name!r}: choose from {', '.join(VARIABLE_NAMES)}")
    return key


def grid_points(vary: Mapping[str, Sequence]) -> list[dict]:
    """All combinations of the values in ``vary`` (the first name varies slowest).

    Examples
    --------
    >>> grid_points({"velocity": [0.0, 50.0], "youngs-modulus": [4e9]})
    [{'velocity': 0.0, 'youngs_modulus': 4000000000.0},
     {'velocity': 50.0, 'youngs_modulus': 4000000000.0}]
    """
    names = [_canonical(n) for n in vary]
    values = []
    for name, vals in zip(names, vary.values(), strict=True):
        vals = list(vals) if not isinstance(vals, str) else [vals]
        if not vals:
            raise ParameterError(f"{name} needs at least one value")
        values.append(vals)
    budget.check_study_points(math.prod(len(v) for v in values))
    return [dict(zip(names, combo, strict=True)) for combo in itertools.product(*values)]


def _check_points(base: TapeParameters, velocity: float, points: Sequence[Mapping]
                  ) -> tuple[list[dict], tuple[str, ...]]:
    """Canonical names, validated values (ParameterError names the point), varied names."""
    out, names = [], []
    for i, point in enumerate(points):
        clean = {}
        for name, value in point.items():
            key = _canonical(name)
            if isinstance(value, np.generic):
                value = value.item()
            clean[key] = value
            if key not in names:
                names.append(key)
        try:
            params, v = _parameters_of(base, velocity, clean)
        except ParameterError as exc:
            raise ParameterError(f"point {i} {clean}: {exc}") from None
        clean = {k: (v if k == "velocity" else getattr(params, k)) for k in clean}
        out.append(clean)
    if not out:
        raise ParameterError("a study needs at least one point")
    return out, tuple(names)


def _parameters_of(base: TapeParameters, velocity: float, point: Mapping
                   ) -> tuple[TapeParameters, float]:
    changes = {k: v for k, v in point.items() if k != "velocity"}
    v = check_velocity(point.get("velocity", velocity))
    return (base.replace(**changes) if changes else base), v


# ----- one point ---------------------------------------------------------------------------
def result_columns(compute: Sequence[str], count: int) -> list[str]:
    """Names of the computed columns, in order, for ``compute`` and ``count``."""
    cols: list[str] = []
    if "critical" in compute:
        cols += ["critical_speed", "divergence_speed"]
    if "modes" in compute:
        cols += [f"omega_{j + 1}" for j in range(count)] + ["growth_rate"]
    if "static" in compute:
        cols += ["load_point_deflection", "max_deflection"]
    if "period" in compute:
        cols += ["period"]
    if "modes" in compute or "period" in compute:
        cols += ["stability"]
    return cols + ["error"]


def evaluate(base: dict, velocity: float, point: dict, compute: tuple[str, ...],
             count: int) -> dict:
    """Compute one point; returns the computed columns (see :func:`result_columns`).

    ``base`` holds the base TapeParameters fields. Each quantity is computed on its own: a
    failure (e.g. ``static`` above the critical speed) leaves NaN in that quantity's columns
    and is reported in ``error`` (``"static: SupercriticalError: message"``; several joined
    by " | "), while the other quantities of the point are kept.
    """
    row: dict = {c: math.nan for c in result_columns(compute, count)}
    if "stability" in row:
        row["stability"] = ""
    errors: list[str] = []

    def attempt(name: str, fn: Callable, *args) -> None:
        try:
            fn(*args)
        except Exception as exc:  # reported in the row; the study goes on
            errors.append(f"{name}: {type(exc).__name__}: {exc}".replace("\n", " "))

    built: list = []
    attempt("model", lambda: built.append(_model_of(base, velocity, point)))
    if built:
        model, v = built[0]
        eigen_name = "modes" if "modes" in compute else "period"
        for name, wanted, columns in (
                ("critical", "critical" in compute, _critical_columns),
                (eigen_name, "modes" in compute or "period" in compute, _eigen_columns),
                ("static", "static" in compute, _static_columns)):
            if wanted:
                attempt(name, columns, model, v, row, compute, count)
    row["error"] = " | ".join(errors)
    return row


def _model_of(base: dict, velocity: float, point: dict):
    """The point's TapeModel and speed V (m/s)."""
    from ..tape.model import TapeModel

    params, v = _parameters_of(TapeParameters(**base), velocity, point)
    return TapeModel(params), v


def _critical_columns(model, v: float, row: dict, compute, count: int) -> None:
    """``critical_speed`` and ``divergence_speed`` (m/s) into ``row``."""
    from ..engines.critical import critical_speeds

    c = critical_speeds(model)
    row.update(critical_speed=c.critical_speed, divergence_speed=c.divergence_speed)


def _eigen_columns(model, v: float, row: dict, compute, count: int) -> None:
    """``omega_k`` and ``growth_rate`` (modes), ``period`` and ``stability`` into ``row``,
    each as soon as it is known (a later failure keeps them)."""
    from ..engines.eigen import modes

    res = modes(model, v, count if "modes" in compute else 1)
    if "modes" in compute:
        for j, w in enumerate(res.omega):
            row[f"omega_{j + 1}"] = float(w)
        row["growth_rate"] = float(np.max(res.eigenvalues.real.clip(min=0.0)))
    if "period" in compute:
        row["period"] = float(res.period[0])
    row["stability"] = tape_stability(model, v, res.eigenvalues)


def _static_columns(model, v: float, row: dict, compute, count: int) -> None:
    """``load_point_deflection`` and ``max_deflection`` (m) into ``row``."""
    from ..engines.static import solve_static

    s = solve_static(model, v)
    row.update(load_point_deflection=s.load_point_deflection,
               max_deflection=s.max_deflection)


def _evaluate_chunk(base: dict, velocity: float, tasks: list[tuple[int, dict]],
                    compute: tuple[str, ...], count: int) -> list[tuple[int, dict]]:
    """Evaluate several points in one task (amortizes the per-task scheduling cost)."""
    return [(i, evaluate(base, velocity, point, compute, count)) for i, point in tasks]


# ----- cache -------------------------------------------------------------------------------
def _point_key(spec: str, point: dict) -> str:
    text = spec + json.dumps(point, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:32]


class _Cache:
    """Finished points in a JSON Lines file (one ``{"key", "row"}`` object per line)."""

    def __init__(self, path: str | os.PathLike[str] | None) -> None:
        self.path = None if path is None else Path(path)
        self._file = None
        if self.path is not None and not self.path.parent.is_dir():
            raise FileNotFoundError(f"cache folder does not exist: {self.path.parent}")

    def done(self) -> dict[str, dict]:
        """Rows already computed, by key; a line cut short by an interruption is skipped
        (that point runs again)."""
        rows: dict[str, dict] = {}
        if self.path is None or not self.path.exists():
            return rows
        with open(self.path, encoding="utf-8") as fh:
            for line in fh:
                try:
                    entry = json.loads(line)
                    rows[entry["key"]] = entry["row"]
                except (json.JSONDecodeError, KeyError, TypeError):
                    continue
        return rows

    def __enter__(self) -> _Cache:
        if self.path is not None:
            self._file = open(self.path, "a", encoding="utf-8")
        return self

    def add(self, entries: list[tuple[str, dict]]) -> None:
        if self._file is not None:
            for key, row in entries:
                self._file.write(json.dumps({"key": key, "row": row}) + "\n")
            self._file.flush()

    def __exit__(self, *exc) -> None:
        if self._file is not None:
            self._file.close()


# ----- the result --------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class StudyResult(results_base.Result, kind="study"):
    """The rows of a parameter study and what made them.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per point: ``point`` (index), the varied parameters (SI, named as in
        :class:`~gyroshell.TapeParameters`, plus ``velocity`` in m/s), the
        computed columns (:func:`result_columns`) and ``error`` ("" if the point succeeded).
    base : TapeParameters
        The tape the points change.
    velocity : float
        Tape speed V (m/s) where a point does not set it.
    varied : tuple of str
        Names of the varied parameters (table columns).
    compute : tuple of str
        What was computed (subset of :data:`COMPUTE_CHOICES`).
    count : int
        Frequencies per point for ``modes``.
    info : dict
        ``points``, ``computed`` (points run now), ``cached`` (points read from the cache),
        ``seconds``, ``executor``, ``chunk_size``.
    """

    table: pd.DataFrame
    base: TapeParameters
    velocity: float
    varied: tuple[str, ...]
    compute: tuple[str, ...]
    count: int
    info: dict = field(default_factory=dict)

    @property
    def failed(self) -> pd.DataFrame:
        """The rows whose point failed."""
        return self.table[self.table["error"] != ""]

    def to_xarray(self, *, params=None):
        """The table as an :class:`xarray.Dataset` (dimension ``row``) with the metadata:
        the base tape (a study knows its own, so ``params`` is not used), ``velocity``,
        ``varied``, ``compute``, ``count`` and ``info``."""
        return results_base.table_dataset(self.table, self.kind,
                                          **self._persistence_attrs())

    @classmethod
    def from_xarray(cls, ds) -> StudyResult:
        """The study stored by :meth:`to_xarray` (also files of the previous release)."""
        return cls._from_saved(results_base.table_from(ds), ds.attrs)

    def to_frame(self) -> pd.DataFrame:
        """The table, one row per point."""
        return self.table

    def summary(self) -> dict:
        """Points, how many were computed now, read from the cache and failed, the seconds
        taken and where they ran (the line ``gyroshell study`` prints)."""
        info = self.info
        return {"points": info["points"], "computed": info["computed"],
                "cached": info["cached"], "failed": len(self.failed),
                "seconds": info["seconds"], "executor": info["executor"]}

    def gridded(self):
        """The table as an :class:`xarray.Dataset` with one dimension per varied parameter
        (e.g. ``stability`` over (velocity, tension)); missing combinations are NaN/empty.

        Raises ParameterError if two points share the same varied values.
        """
        table = self.table.drop(columns=["point"])
        if table.duplicated(list(self.varied)).any():
            raise ParameterError("points repeat the same varied values: no grid")
        ds = table.set_index(list(self.varied)).to_xarray()
        for name in ds.variables:
            unit = unit_of(str(name))
            if unit:
                ds[name].attrs["units"] = unit
        return ds

    def plot(self, ax=None, **options):
        """Stability map (two varied parameters) or the quantity against one; see
        :func:`gyroshell.plot.stability_map` and :func:`gyroshell.plot.study_lines`."""
        from .. import plot

        if len(self.varied) == 2 and "stability" in self.table:
            return plot.stability_map(self, ax=ax, **options)
        return plot.study_lines(self, ax=ax, **options)

    def _persistence_attrs(self) -> dict:
        """The metadata of a study file (also used by the previous release's converter)."""
        return {"params": self.base, "velocity": self.velocity, "varied": list(self.varied),
                "compute": list(self.compute), "count": self.count, "info": self.info}

    @classmethod
    def _from_saved(cls, table: pd.DataFrame, attrs: Mapping) -> StudyResult:
        from_json = results_base.from_json
        table = table.copy()
        for col in ("error", "stability"):
            if col in table:
                table[col] = table[col].fillna("").astype(str)
        return cls(table, results_base.params_from(attrs), float(from_json(attrs["velocity"])),
                   tuple(from_json(attrs["varied"])), tuple(from_json(attrs["compute"])),
                   int(from_json(attrs["count"])), from_json(attrs.get("info", "{}")))


# ----- running -----------------------------------------------------------------------------
def _check_compute(compute) -> tuple[str, ...]:
    items = (compute,) if isinstance(compute, str) else tuple(compute)
    bad = [c for c in items if c not in COMPUTE_CHOICES]
    if bad or not items:
        raise ParameterError(f"compute must be one or more of {', '.join(COMPUTE_CHOICES)}, "
                             f"got {', '.join(map(repr, bad)) or 'nothing'}")
    return tuple(dict.fromkeys(items))


def _check_workers(workers) -> int:
    if workers is None:
        return max(1, os.cpu_count() or 1)
    if isinstance(workers, bool) or int(workers) != workers or workers < 1:
        raise ParameterError(f"workers must be an integer >= 1, got {workers!r}")
    return int(workers)


def _chunks(tasks: list, size: int) -> list[list]:
    """Tasks dealt round-robin into chunks of about ``size``: neighbouring points (similar
    cost, e.g. all the supercritical speeds) spread over the chunks, balancing the load."""
    n = max(1, math.ceil(len(tasks) / size))
    return [tasks[i::n] for i in range(n) if tasks[i::n]]


def run_study(base: TapeParameters | None = None, *, vary: Mapping[str, Sequence] | None = None,
              points: Sequence[Mapping] | None = None, compute: str | Sequence[str] = "critical",
              velocity: float = 0.0, count: int = 3, workers: int | None = None,
              scheduler: str | None = None, cache: str | os.PathLike[str] | None = None,
              chunk_size: int | None = None, progress: bool | None = None) -> StudyResult:
    """Run a parameter study; one row per point.

    Parameters
    ----------
    base : TapeParameters, optional
        The tape the points change (default: Table 1).
    vary : mapping name -> values, optional
        A grid: every combination of the values (first name slowest). Names are the
        TapeParameters fields (SI units) and ``velocity`` (m/s).
    points : sequence of mappings, optional
        Or an explicit list of points, e.g. ``[{"tension": 80, "velocity": 50}, ...]``.
    compute : str or sequence of str
        Any of ``critical``, ``modes``, ``static``, ``period`` (see the module docstring).
    velocity : float
        Tape speed V, m/s, where a point does not set it.
    count : int
        Frequencies per point for ``modes``.
    workers : int, optional
        Local worker processes (1: run in this process). Default: the number of CPUs.
    scheduler : str, optional
        Address of a running Dask distributed scheduler (``tcp://HOST:PORT``); the points
        run on its workers instead (needs ``pip install "gyroshell[cluster]"``).
    cache : path, optional
        JSON Lines file of finished points; a repeated study skips them.
    chunk_size : int, optional
        Points per task; default about ``CHUNKS_PER_WORKER`` tasks per worker (1 in
        this process).
    progress : bool, optional
        Progress bar on stderr (:func:`gyroshell.core.progress.progress_bar`); default
        only when stderr is a terminal.

    Returns
    -------
    StudyResult

    Raises
    ------
    ParameterError
        Unknown parameter names, invalid values (naming the point), bad options.
    """
    plan = _plan(base, vary, points, compute, velocity, count)
    return _run(plan, _check_executor(workers, scheduler, chunk_size), cache, progress)


@dataclass(frozen=True)
class _Plan:
    """A validated study: the base tape's fields, the speed (m/s) where a point sets none,
    the points, the varied names, what to compute and how many frequencies."""

    base: TapeParameters
    velocity: float
    points: list[dict]
    varied: tuple[str, ...]
    compute: tuple[str, ...]
    count: int

    @property
    def base_fields(self) -> dict:
        return {f.name: getattr(self.base, f.name) for f in dataclasses.fields(self.base)}

    def keys(self) -> list[str]:
        """Each point's cache key: its values, the rest of the study and the version."""
        from ..core.version import __version__

        spec = json.dumps([self.base_fields, self.velocity, self.compute, self.count,
                           __version__], sort_keys=True, default=repr)
        return [_point_key(spec, p) for p in self.points]


@dataclass(frozen=True)
class _Executor:
    """Where the points run: ``workers`` local processes, or a Dask ``scheduler``."""

    workers: int | None
    scheduler: str | None
    chunk_size: int | None


def _plan(base, vary, points, compute, velocity, count) -> _Plan:
    """The study's settings validated (ParameterError names what is wrong)."""
    base = TapeParameters() if base is None else base
    if not isinstance(base, TapeParameters):
        raise ParameterError("base must be a TapeParameters")
    velocity = check_velocity(velocity)
    compute = _check_compute(compute)
    if isinstance(count, bool) or int(count) != count or count < 1:
        raise ParameterError(f"count must be an integer >= 1, got {count!r}")
    if (vary is None) == (points is None):
        raise ParameterError("give either vary (a grid) or points (a list), not both")
    raw = grid_points(vary) if vary is not None else list(points)
    pts, varied = _check_points(base, velocity, raw)
    if vary is not None:
        varied = tuple(_canonical(n) for n in vary)
    return _Plan(base, velocity, pts, varied, compute, int(count))


def _check_executor(workers, scheduler, chunk_size) -> _Executor:
    if scheduler is not None and (not isinstance(scheduler, str) or "://" not in scheduler):
        raise ParameterError(f"scheduler must be an address like tcp://HOST:PORT, got "
                             f"{scheduler!r}")
    if scheduler is not None and workers is not None:
        raise ParameterError("give workers (local processes) or scheduler (a Dask cluster, "
                             "whose workers run the points), not both")
    workers = _check_workers(workers) if scheduler is None else None
    if chunk_size is not None and (int(chunk_size) != chunk_size or chunk_size < 1):
        raise ParameterError(f"chunk_size must be an integer >= 1, got {chunk_size!r}")
    return _Executor(workers, scheduler, chunk_size)


def _run(plan: _Plan, where: _Executor, cache, progress: bool | None) -> StudyResult:
    """Compute the points the cache lacks, where asked, and gather the rows."""
    import pandas as pd

    keys, pts = plan.keys(), plan.points
    cache = _Cache(cache)
    done = cache.done()
    rows: dict[int, dict] = {i: done[k] for i, k in enumerate(keys) if k in done}
    todo = [(i, pts[i]) for i in range(len(pts)) if i not in rows]
    t0 = time.perf_counter()
    bar = progress_bar(len(pts), "study", progress=progress, unit="point", initial=len(rows))
    with cache, bar:
        def record(results: list[tuple[int, dict]]) -> None:
            rows.update(results)
            cache.add([(keys[i], row) for i, row in results])
            bar.update(len(results))

        executor, size = _execute(todo, record, plan, where)
    columns = result_columns(plan.compute, plan.count)
    records = [{"point": i, **pts[i], **{c: rows[i][c] for c in columns}}
               for i in range(len(pts))]
    table = pd.DataFrame(records, columns=["point", *plan.varied, *columns])
    info = {"points": len(pts), "computed": len(todo), "cached": len(pts) - len(todo),
            "seconds": time.perf_counter() - t0, "executor": executor, "chunk_size": size}
    return StudyResult(table, plan.base, plan.velocity, plan.varied, plan.compute,
                       plan.count, info)


def _execute(todo, record: Callable, plan: _Plan, where: _Executor) -> tuple[str, int]:
    """Run the tasks where asked; ``record`` gets each finished chunk's (index, row)s.
    Returns the executor's name and the chunk size."""
    args = (plan.base_fields, plan.velocity)
    compute, count, chunk_size = plan.compute, plan.count, where.chunk_size
    if not todo:
        return "cache", 0
    if where.scheduler is not None:
        return _execute_dask(todo, record, args, compute, count, where.scheduler, chunk_size)
    if where.workers == 1:
        size = chunk_size or 1
        for chunk in _chunks(todo, size):
            record(_evaluate_chunk(*args, chunk, compute, count))
        return "serial", size
    from concurrent.futures import as_completed

    workers = where.workers
    size = chunk_size or max(1, math.ceil(len(todo) / (workers * CHUNKS_PER_WORKER)))
    with process_pool(workers) as pool:
        futures = [pool.submit(_evaluate_chunk, *args, chunk, compute, count)
                   for chunk in _chunks(todo, size)]
        for fut in as_completed(futures):
            record(fut.result())
    return f"processes({workers})", size


def _worker_version() -> str:
    try:
        from ..core.version import __version__
    except ImportError:
        return "not installed"
    return __version__


def _check_worker_versions(client, scheduler: str) -> None:
    """Refuse workers that run another gyroshell: their rows would not be this version's."""
    from ..core.version import __version__

    versions = client.run(_worker_version)
    if not versions:
        raise ParameterError(f"the Dask scheduler at {scheduler} has no workers: start some "
                             f"with 'dask worker {scheduler}'")
    other = {addr: v for addr, v in versions.items() if v != __version__}
    if other:
        addr, v = next(iter(other.items()))
        raise ParameterError(f"Dask worker {addr} runs gyroshell {v}, this process "
                             f"{__version__}: install the same version on every worker")


def _execute_dask(todo, record, args, compute, count, scheduler, chunk_size
                  ) -> tuple[str, int]:
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise ParameterError('--scheduler needs Dask: pip install "gyroshell[cluster]"'
                             ) from None
    try:
        client = Client(scheduler, timeout=CONNECT_TIMEOUT)
    except (OSError, TimeoutError) as exc:
        raise ParameterError(f"cannot reach the Dask scheduler at {scheduler}: {exc}"
                             ) from None
    try:
        _check_worker_versions(client, scheduler)
        threads = max(1, sum(client.nthreads().values()))
        size = chunk_size or max(1, math.ceil(len(todo) / (threads * CHUNKS_PER_WORKER)))
        futures = [client.submit(_evaluate_chunk, *args, chunk, compute, count, pure=False)
                   for chunk in _chunks(todo, size)]
        for fut in as_completed(futures):
            record(fut.result())
    finally:
        client.close()
    return f"dask({scheduler})", size
