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
    (:func:`gyroshell.studies.stability.tape_stability`: ``stable``, ``divergence`` or
    ``flutter``).
``static``
    ``load_point_deflection`` and ``max_deflection`` (m) from
    :func:`gyroshell.solve_static` (a speed at or above critical fails in its row).
``period``
    ``period`` = 2π/ω₁ (s), the dominant period of the load-point response (the band edge
    of its spectrum; see :mod:`gyroshell.reproduce.period`), and ``stability``.
``bearing``
    The steady air bearing over a head (``bearing=BearingStudy(head, ...)``): central,
    minimum and transducer-line spacings, tents, corner forces, drag and tension rise
    (:mod:`~gyroshell.studies.head_study`); points may also vary the head
    (:data:`~gyroshell.studies.points.HEAD_VARIABLES`). The speed may have either sign
    when nothing else is computed, never 0; every point's model is built before any work,
    so that what the single ``gyroshell bearing`` refuses (a grid beyond the memory) is
    refused for the study.

Every point is an independent task. They run in this process (``workers=1``), in local
processes (``workers=N``, the default is the number of CPUs; no setup: this one and N - 1
workers; this process's first two points time the study against the time limit), or on a Dask
distributed cluster the user started (``scheduler="tcp://HOST:PORT"``); the rows are the
same in every case. A point that fails is reported in its row (``error``, the other values
NaN) and the study goes on. With ``cache=PATH`` each finished point is appended to a JSON
Lines file, and a study started again with the same cache computes only the points that are
missing (rows are read back bit for bit: JSON keeps float64 exactly).

This module holds the study's result and :func:`run_study`; the pieces live beside it:
:mod:`~gyroshell.studies.points` (what may vary, grids, checks),
:mod:`~gyroshell.studies.evaluation` (what one point computes),
:mod:`~gyroshell.studies.cache` (the JSON Lines cache) and
:mod:`~gyroshell.studies.executors` (this process, local processes, Dask).
"""

from __future__ import annotations

import json
import os
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ..bearing.head_config import check_design
from ..core import validation
from ..core.errors import ParameterError
from ..core.progress import stage_progress
from ..core.units import unit_of
from ..results import base as results_base
from ..results import layout
from ..tape.config import parameter_fields
from ..tape.parameters import TapeParameters
from .cache import PointCache, file_digest, point_key
from .evaluation import COMPUTE_CHOICES, MAX_COUNT, check_compute, check_row, result_columns
from .executors import (
    CONNECT_TIMEOUT,
    Executor,
    StudyTask,
    check_executor,
    connected,
    execute,
)
from .head_study import (
    BearingStudy,
    head_of_point,
    head_value,
    interface_value,
    point_model,
)
from .points import (
    BOTH_WRAPS,
    HEAD_VARIABLES,
    INTERFACE_VARIABLES,
    VARIABLE_NAMES,
    canonical_name,
    check_points,
    check_speed,
    design_fields,
    grid_points,
    parameters_of,
    value_of,
)

if TYPE_CHECKING:
    import pandas as pd

#: Frequencies per point of ``compute="modes"`` unless ``count`` says otherwise.
DEFAULT_COUNT = 3

__all__ = ["COMPUTE_CHOICES", "VARIABLE_NAMES", "BearingStudy", "StudyResult", "run_study",
           "study_columns"]


@dataclass(frozen=True, eq=False)
class StudyResult(results_base.Result, kind="study"):
    """The rows of a parameter study and what made them.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per point: ``point`` (index), the varied parameters (SI, named as in
        :class:`~gyroshell.TapeParameters`, plus ``velocity`` in m/s; where a point of a
        list does not set one, the value it ran with, the base's), the computed
        columns (:func:`~gyroshell.studies.evaluation.result_columns`) and ``error`` ("" if
        the point succeeded).
    base : TapeParameters
        The tape the points change.
    velocity : float
        Tape speed V (m/s) where a point does not set it.
    varied : tuple of str
        Names of the varied parameters (table columns).
    compute : tuple of str
        What was computed (subset of :data:`~gyroshell.studies.evaluation.COMPUTE_CHOICES`).
    count : int
        Frequencies per point for ``modes``.
    info : dict
        ``points``, ``computed`` (points run now), ``cached`` (points read from the cache),
        ``seconds``, ``executor``, ``chunk_size``.
    bearing : dict or None
        The head, air and grid of a ``bearing`` study
        (:meth:`~gyroshell.studies.head_study.BearingStudy.spec`).
    """

    summary_units = {"seconds": "s"}

    table: pd.DataFrame
    base: TapeParameters
    velocity: float
    varied: tuple[str, ...]
    compute: tuple[str, ...]
    count: int
    info: dict = field(default_factory=dict)
    bearing: dict | None = None

    #: The file: the table's columns on ``row`` (every varied name among them), the speed,
    #: what was computed and, for a bearing study, its setup.
    file_layout = layout.Layout(attrs={
        "velocity": layout.Attr(layout.of_type("velocity", (int, float), "a number")),
        "count": layout.Attr(layout.count("count", 1)),
        "varied": layout.Attr(layout.of_type("varied", list, "a list")),
        "compute": layout.Attr(layout.of_type("compute", list, "a list")),
        "bearing": layout.Attr(layout.of_type("bearing", dict, "a JSON object"),
                               optional=True)},
        check=lambda ds: _check_file(ds))

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

    def plot(self, ax=None, *, quantity: str | None = None, **options):
        """Two varied parameters: a map of ``quantity`` (:func:`gyroshell.plot.study_map`),
        or without one of a study that computed the stability, the stability map
        (:func:`gyroshell.plot.stability_map`); one: the quantity against it
        (:func:`gyroshell.plot.study_lines`). ``quantity`` defaults to
        :func:`gyroshell.plot.study_maps.default_quantity` (a bearing study with
        transducers: their minimum spacing). Angles are shown in degrees."""
        from .. import plot

        if len(self.varied) == 2:
            if quantity is None and "stability" in self.table:
                return plot.stability_map(self, ax=ax, **options)
            return plot.study_map(self, quantity, ax=ax, **options)
        return plot.study_lines(self, ax=ax, quantity=quantity, **options)

    def _persistence_attrs(self) -> dict:
        """The metadata of a study file (also used by the previous release's converter)."""
        attrs = {"params": self.base, "velocity": self.velocity, "varied": list(self.varied),
                 "compute": list(self.compute), "count": self.count, "info": self.info}
        if self.bearing is not None:
            attrs["bearing"] = self.bearing
        return attrs

    @classmethod
    def _from_saved(cls, table: pd.DataFrame, attrs: Mapping) -> StudyResult:
        from_json = results_base.from_json
        table = table.copy()
        for col in ("error", "stability"):
            if col in table:
                table[col] = table[col].fillna("").astype(str)
        return cls(table, results_base.params_from(attrs), float(from_json(attrs["velocity"])),
                   tuple(from_json(attrs["varied"])), tuple(from_json(attrs["compute"])),
                   int(from_json(attrs["count"])), from_json(attrs.get("info", "{}")),
                   from_json(attrs["bearing"]) if "bearing" in attrs else None)



def _check_file(ds) -> None:
    """A study file: its columns stored, among them every varied name; the bearing setup
    of a bearing study, as checked when built (:meth:`BearingStudy.from_spec`)."""
    layout.table_columns(ds)
    from_json = results_base.from_json
    columns = from_json(ds.attrs["columns"])
    varied = from_json(ds.attrs["varied"])
    missing = [name for name in varied if name not in columns]
    if missing:
        raise ParameterError(f"varied lists {', '.join(map(str, missing))}, which the table "
                             "has no column for")
    bearing = "bearing" in from_json(ds.attrs["compute"])
    if bearing != ("bearing" in ds.attrs):
        raise ParameterError("compute lists bearing but the bearing setup is missing" if
                             bearing else "a bearing setup is stored but compute does not "
                             "list bearing")
    if bearing:
        BearingStudy.from_spec(from_json(ds.attrs["bearing"]))


def run_study(base: TapeParameters | None = None, *, vary: Mapping[str, Sequence] | None = None,
              points: Sequence[Mapping] | None = None, compute: str | Sequence[str] = "critical",
              velocity: float = 0.0, count: int | None = None, workers: int | None = None,
              scheduler: str | None = None, connect_timeout: float = CONNECT_TIMEOUT,
              cache: str | os.PathLike[str] | None = None, chunk_size: int | None = None,
              progress: bool | None = None, bearing: BearingStudy | None = None,
              inputs: Sequence[str | os.PathLike[str]] = ()) -> StudyResult:
    """Run a parameter study; one row per point.

    Parameters
    ----------
    base : TapeParameters, optional
        The tape the points change (default: Table 1).
    vary : mapping name -> values, optional
        A grid: every combination (first name slowest) of :data:`VARIABLE_NAMES`' values, SI.
    points : sequence of mappings, optional
        Or a list of points, e.g. ``[{"tension": 80, "velocity": 50}, ...]``.
    compute : str or sequence of str
        Any of ``critical``, ``modes``, ``static``, ``period``, ``bearing`` (module doc).
    velocity : float
        Tape speed V, m/s, where a point does not set it.
    count : int, optional
        Frequencies per point for ``modes``, in [1, 50] (default 3; not without ``modes``).
    workers : int, optional
        Local processes (1: this process; at most 4 per CPU). Default: one per CPU.
    scheduler : str, optional
        A Dask scheduler's address (``tcp://HOST:PORT``, :mod:`~.scheduler`): its workers run it.
    connect_timeout : float
        Seconds, in (0, 3600], to connect and complete Dask's handshake (refused: at once).
    cache : path, optional
        JSON Lines file of finished points, which a repeated study skips (checked as
        strictly as computed rows; several studies may share it).
    chunk_size : int, optional
        Points per task (default: 1 in this process, else ``CHUNKS_PER_WORKER`` per worker).
    progress : bool, optional
        True: a bar on stderr, False: nothing, None: a bar on a terminal, else a line per stage.
    bearing : BearingStudy, optional
        The head, air and grid of ``compute="bearing"`` (default ``BearingStudy()``).
    inputs : sequence of paths, optional
        Files the settings were read from (a tape file): their content keys the cache.

    Returns
    -------
    StudyResult

    Raises
    ------
    ParameterError
        Bad names, values (naming the point) or options; a scheduler unreachable or not
        Dask's, or workers of another gyroshell; a damaged cache; over the time limit.

    Examples
    --------
    >>> study = run_study(TapeParameters(length_ratio=1, spacing=6.35e-3 / 8),
    ...                   points=[{"tension": 80.0}], compute="critical", workers=1)
    >>> list(study.table.columns)
    ['point', 'tension', 'critical_speed', 'divergence_speed', 'error']
    """
    return _run(_plan(base, vary, points, compute, velocity, count, bearing, inputs),
                check_executor(workers, scheduler, chunk_size, connect_timeout), cache, progress)


def study_columns(base: TapeParameters | None = None, *,
                  vary: Mapping[str, Sequence] | None = None,
                  points: Sequence[Mapping] | None = None,
                  compute: str | Sequence[str] = "critical", velocity: float = 0.0,
                  count: int | None = None, bearing: BearingStudy | None = None) -> list[str]:
    """The columns of the table :func:`run_study` would return for these settings (checked
    as it checks them), without computing any point: to refuse, before the work, an
    option that names a column the study will not have.

    Examples
    --------
    >>> study_columns(vary={"tension": [80.0, 90.0]}, compute="critical")
    ['point', 'tension', 'critical_speed', 'divergence_speed', 'error']
    """
    plan = _plan(base, vary, points, compute, velocity, count, bearing)
    return ["point", *plan.varied, *result_columns(plan.compute, plan.count, plan.bearing)]


@dataclass(frozen=True)
class _Plan:
    """A validated study: the base tape, the speed (m/s) where a point sets none, the
    points, the varied names, what to compute and how many frequencies."""

    base: TapeParameters
    velocity: float
    points: list[dict]
    varied: tuple[str, ...]
    compute: tuple[str, ...]
    count: int
    bearing: BearingStudy | None = None
    #: Each point's row of varied values in the table: the point's own, and the value
    #: used (the base's) for a name this point does not set.
    cells: list[dict] = field(default_factory=list)
    #: The files the rows depend on (the settings' files, a measured head's profile).
    inputs: tuple[str, ...] = ()

    @property
    def task(self) -> StudyTask:
        """What every point's evaluation shares (the base tape as plain fields)."""
        fields = parameter_fields(self.base)  # plain values: layers as dicts
        return StudyTask(fields, self.velocity, self.compute, self.count, self.bearing)

    def keys(self) -> list[str]:
        """Each point's cache key: its values, the rest of the study, the version and the
        content of every input file."""
        from ..core.version import __version__

        task = self.task
        parts = [task.base, self.velocity, self.compute, self.count, __version__]
        if self.bearing is not None:
            parts.append(self.bearing.spec())
        if self.inputs:
            parts.append({"input_sha256": [file_digest(path) for path in self.inputs]})
        spec = json.dumps(parts, sort_keys=True, default=repr)
        return [point_key(spec, p) for p in self.points]


def _plan(base, vary, points, compute, velocity, count, bearing=None, inputs=()) -> _Plan:
    """The study's settings validated (ParameterError names what is wrong)."""
    base = TapeParameters() if base is None else base
    validation.instance("base", base, TapeParameters)
    compute = check_compute(compute)
    signed = compute == ("bearing",)   # the tape alone runs one way; the bearing either
    velocity = check_speed(velocity, signed=signed)
    if count is not None and "modes" not in compute:
        raise ParameterError("count is the number of frequencies of compute='modes': add "
                             "'modes' to compute or leave count out")
    count = validation.integer("count", DEFAULT_COUNT if count is None else count, low=1,
                               high=MAX_COUNT)
    if (vary is None) == (points is None):
        raise ParameterError("give either vary (a grid) or points (a list), not both")
    raw = grid_points(vary) if vary is not None else list(points)
    pts, varied = check_points(base, velocity, raw, signed=signed)
    if vary is not None:
        varied = tuple(canonical_name(n) for n in vary)
    bearing = _bearing_plan(base, velocity, pts, varied, compute, bearing)
    cells = [_cells(base, velocity, point, varied, bearing) for point in pts]
    return _Plan(base, velocity, pts, varied, compute, int(count), bearing, cells,
                 _input_files(inputs, bearing))


def _input_files(inputs, bearing: BearingStudy | None) -> tuple[str, ...]:
    """The files whose content the rows depend on: ``inputs`` and a measured head's
    profile."""
    if isinstance(inputs, (str, os.PathLike)):
        raise ParameterError(f"inputs must be a sequence of paths, got the one path {inputs!r}")
    files = [os.fspath(path) for path in inputs]
    for path in files:
        if not os.path.isfile(path):
            raise ParameterError(f"inputs: {path} is not a file")
    if bearing is not None and bearing.head.profile is not None:
        files.append(os.fspath(bearing.head.profile))
    return tuple(files)


def _cells(base: TapeParameters, velocity: float, point: dict, varied: tuple[str, ...],
           bearing: BearingStudy | None) -> dict:
    """The point's varied values as the table shows them: a name the point does not set
    (points given as a list may set different names) holds the value it ran with."""
    missing = [name for name in varied if name not in point]
    if not missing:
        return point
    params, v = parameters_of(base, velocity, point, signed=True)   # checked before
    design = None if bearing is None else head_of_point(bearing, point)
    used = {name: head_value(design, name) if name in HEAD_VARIABLES
            else interface_value(bearing, name) if name in INTERFACE_VARIABLES
            else value_of(params, v, name) for name in missing}
    return {name: point[name] if name in point else used[name] for name in varied}


def _bearing_plan(base: TapeParameters, velocity: float, pts: list[dict],
                  varied: tuple[str, ...], compute: tuple[str, ...], bearing
                  ) -> BearingStudy | None:
    """The bearing setup with its columns, every point's head checked; None without
    ``bearing`` in ``compute`` (then no head variable may vary and no setup be given)."""
    if "bearing" not in compute:
        for group, what in ((HEAD_VARIABLES, "a head's"),
                            (INTERFACE_VARIABLES, "the head-tape interface's")):
            names = [name for name in varied if name in group]
            if names:
                raise ParameterError(f"{', '.join(names)}: {what} parameters vary in a "
                                     "bearing study: add compute='bearing'")
        if bearing is not None:
            raise ParameterError("bearing sets up compute='bearing': add it to compute or "
                                 "drop bearing")
        return None
    bearing = BearingStudy() if bearing is None else bearing
    validation.instance("bearing", bearing, BearingStudy)
    if base.edges != "free" and not bearing.infinitely_wide:
        raise ParameterError(f"the bearing's tape has free edges, got edges = {base.edges!r}")
    both = [name for name in ("wrap_in", "wrap_out") if name in varied]
    if BOTH_WRAPS in varied and both:
        raise ParameterError(f"{BOTH_WRAPS} sets both wrap_in and wrap_out: vary "
                             f"{BOTH_WRAPS} or {' and '.join(both)}, not both")
    check_design(bearing.head, varied=design_fields(varied))
    for i, point in enumerate(pts):
        try:
            head_of_point(bearing, point).head()   # the contour's own checks too
        except ParameterError as exc:
            raise ParameterError(f"point {i} {point}: {exc}") from None
    _check_bearing_points(base, velocity, pts, bearing)
    return bearing.with_columns(base, head_of_point(bearing, pts[0]))


def _check_bearing_points(base: TapeParameters, velocity: float, pts: list[dict],
                          bearing: BearingStudy) -> None:
    """Refuse, before any work, a point whose bearing model the single ``gyroshell
    bearing`` would refuse (:func:`~gyroshell.studies.head_study.point_model`: its head,
    a speed of 0, a grid beyond the memory), naming the point; the speed where no point
    sets one first."""
    import warnings

    from ..bearing.model import BearingGridWarning

    if velocity == 0.0 and any("velocity" not in point for point in pts):
        raise ParameterError("velocity must be nonzero for an air bearing (either sign: the "
                             "tape running along +x or -x, e.g. 4 or -4 m/s), got 0: give "
                             "it (--velocity), or vary it")
    fields = parameter_fields(base)
    for i, point in enumerate(pts):
        try:
            with warnings.catch_warnings():   # a coarse grid warns when the point runs
                warnings.simplefilter("ignore", BearingGridWarning)
                point_model(fields, velocity, point, bearing)
        except ParameterError as exc:
            raise ParameterError(f"point {i} {point}: {exc}") from None


def _run(plan: _Plan, where: Executor, cache, progress: bool | None) -> StudyResult:
    """Compute the points the cache lacks, where asked, and gather the rows.

    The cache is read and checked, and the scheduler connected, before any work and before
    the cache file is opened for appending: a refusal leaves the file as it was (and
    costs no import of pandas or Dask).
    """
    keys, pts = plan.keys(), plan.points
    ours = set(keys)
    cache = PointCache(cache)
    done = cache.done(lambda key, row: check_row(row, plan.compute, plan.count, plan.bearing)
                      if key in ours else row)
    rows: dict[int, dict] = {i: done[k] for i, k in enumerate(keys) if k in done}
    todo = [(i, pts[i]) for i in range(len(pts)) if i not in rows]
    t0 = time.perf_counter()
    bar = stage_progress(len(pts), "study", progress=progress, unit="point",
                         initial=len(rows))
    with connected(where if todo else None) as client, cache, bar:
        def record(results: list[tuple[int, dict]]) -> None:
            rows.update(results)
            cache.add([(keys[i], row) for i, row in results])
            bar.update(len(results))

        bar.start(_where_text(where, todo))
        executor, size = execute(todo, record, plan.task, where, client,
                                 _time_check(plan, where, len(todo)))
    import pandas as pd

    columns = result_columns(plan.compute, plan.count, plan.bearing)
    records = [{"point": i, **plan.cells[i], **{c: rows[i][c] for c in columns}}
               for i in range(len(pts))]
    table = pd.DataFrame(records, columns=["point", *plan.varied, *columns])
    info = {"points": len(pts), "computed": len(todo), "cached": len(pts) - len(todo),
            "seconds": time.perf_counter() - t0, "executor": executor, "chunk_size": size}
    return StudyResult(table, plan.base, plan.velocity, plan.varied, plan.compute,
                       plan.count, info, None if plan.bearing is None else plan.bearing.spec())


def _time_check(plan: _Plan, where: Executor, points: int):
    """The time limit over a local study of ``points`` points: this process's share
    (all, or one in N beside N - 1 workers) timed on its first two points, the first left
    out as warm-up (:class:`~gyroshell.core.progress.TimeCheck`); None on a Dask cluster
    (its workers are not these)."""
    if where.scheduler is not None:
        return None
    from ..core.progress import TimeCheck

    return TimeCheck(-(-points // where.workers), unit="point", parallel=where.workers,
                     size=f"a study of {points} points ({', '.join(plan.compute)})",
                     advice="use fewer points, more workers or a Dask cluster")


def _where_text(where: Executor, todo: list) -> str:
    """Where the points run, for the first progress line."""
    if not todo:
        return "(nothing to compute)"
    if where.scheduler is not None:
        return f"on the Dask scheduler {where.scheduler}"
    return "in this process" if where.workers == 1 else f"on {where.workers} processes"
