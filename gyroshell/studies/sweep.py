"""Frequencies against tape speed, with mode tracking, as a :class:`SweepResult` and a plot.

At each speed the lowest ``count`` modes are computed (:func:`gyroshell.modes`) and
matched to the previous speed's by mode-shape correlation

    C_ij = |φ_iᴴ M ψ_j| / (‖φ_i‖_M ‖ψ_j‖_M),

with the assignment that maximizes the total correlation (Hungarian algorithm,
:mod:`gyroshell.studies.branches`). A branch
therefore keeps its label when frequencies cross or veer, instead of following the sorted
order. A mode that leaves the lowest-``count`` window is replaced by the newcomer with a low
correlation; the ``correlation`` column says how sure each match is.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from functools import partial
from typing import TYPE_CHECKING

import numpy as np

from ..core import budget, validation
from ..core.errors import ParameterError
from ..core.parallel import check_process_count, process_pool
from ..core.progress import stage_progress
from ..engines.eigen import Modes, check_speed, modes, stiffness_floor, strip_frequency_estimate
from ..linalg.qep.problem import check_count
from ..results import base, layout
from ..tape.model import TapeModel, check_model
from ..tape.parameters import TapeParameters, check_velocity
from .branches import BranchTracker, Match, track

if TYPE_CHECKING:  # pandas is imported when a sweep runs: keep `import gyroshell` fast
    import pandas as pd

    from ..tape.grid import Grid

#: Columns of the sweep table (long format, one row per speed and branch).
COLUMNS = ("velocity", "branch", "rank", "omega", "frequency", "period", "growth_rate",
           "residual", "correlation", "supercritical", "stability")
#: Resolution of :func:`plot_sweep`'s files, dots per inch.
SWEEP_DPI = 120
#: The variable of a sweep file holding the requested speeds, on dimension ``speed``.
VELOCITIES_VARIABLE = "velocities"


@dataclass(frozen=True, eq=False)
class SweepResult(base.Result, kind="sweep"):
    """Tracked frequencies of a sweep (:func:`sweep`) and the settings that made them.

    For one release a SweepResult also behaves like its table (``result["omega"]``,
    ``len(result)``, ``result.columns``, ``result.groupby(...)``), with a
    DeprecationWarning: use ``result.table``.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per speed and mode, columns :data:`COLUMNS` (see :func:`sweep`).
    velocities : numpy.ndarray
        The speeds, m/s, in the order they were tracked.
    count : int
        Modes per speed.
    min_correlation : float
        Weakest correlation that continued a branch.
    continuation : bool
        Whether each solve was continued from the previous speeds'.
    params : TapeParameters or None
        The tape.
    grid : Grid or None
        Its finite-difference grid.
    info : dict
        ``workers``: local processes used.
    """

    table: pd.DataFrame
    velocities: np.ndarray
    count: int
    min_correlation: float
    continuation: bool
    params: TapeParameters | None = None
    grid: Grid | None = None
    info: dict = field(default_factory=dict)

    #: The file: the speeds, the table's columns on ``row`` and the settings.
    file_layout = layout.Layout(
        {"velocities": layout.Variable(("speed",), check=layout.speed())},
        {"count": layout.Attr(layout.count("count", 1)),
         "min_correlation": layout.Attr(layout.of_type("min_correlation", (int, float),
                                                       "a number")),
         "continuation": layout.Attr(layout.of_type("continuation", bool, "true or false")),
         "info": layout.INFO}, check=lambda ds: _check_table(ds))

    def to_frame(self) -> pd.DataFrame:
        """The table (columns :data:`COLUMNS`)."""
        return self.table

    def to_xarray(self, *, params=None):
        """The table on dimension ``row``, the speeds on ``speed`` (m/s), and the settings;
        ``params`` is stored only if the sweep does not know its tape."""
        tape = self.params if self.params is not None else params
        ds = base.table_dataset(self.table, self.kind, params=tape,
                                grid=self.grid, info=self.info, count=self.count,
                                min_correlation=self.min_correlation,
                                continuation=self.continuation)
        ds[VELOCITIES_VARIABLE] = ("speed", self.velocities,
                                   {"units": "m/s", "long_name": "tape speeds swept"})
        return ds

    @classmethod
    def from_xarray(cls, ds) -> SweepResult:
        """The sweep stored by :meth:`to_xarray`."""
        attrs = ds.attrs
        return cls(base.table_from(ds.drop_vars(VELOCITIES_VARIABLE)),
                   ds[VELOCITIES_VARIABLE].values, int(base.from_json(attrs["count"])),
                   float(base.from_json(attrs["min_correlation"])),
                   bool(base.from_json(attrs["continuation"])), base.params_from(attrs),
                   base.grid_from(attrs), base.from_json(attrs["info"]))

    def summary(self) -> dict:
        """Speeds, modes per speed, branches, speed range (m/s), the lowest ω (rad/s), the
        supercritical speeds and the stability classes met."""
        t = self.table
        return {"speeds": len(self.velocities), "count": self.count,
                "branches": int(t["branch"].nunique()),
                "velocity_min": float(self.velocities.min()),
                "velocity_max": float(self.velocities.max()),
                "omega_min": float(t["omega"].min()),
                "supercritical_speeds": int(t.groupby("velocity")["supercritical"]
                                            .first().sum()),
                "stability": ",".join(dict.fromkeys(t["stability"]))}

    def plot(self, ax=None, *, title: str | None = None):
        """See :func:`gyroshell.plot.sweep`."""
        from .. import plot

        return plot.sweep(self, ax=ax, title=title)

    # ----- the DataFrame it was (deprecated) ---------------------------------------------
    def _as_table(self, what: str) -> pd.DataFrame:
        warnings.warn(f"sweep() returns a SweepResult, not a DataFrame: use .table{what} "
                      "(the DataFrame behaviour goes in the next release)",
                      DeprecationWarning, stacklevel=3)
        return self.table

    def __getattr__(self, name: str):
        if name.startswith("_"):  # copy, pickle and hasattr probes: not the table's
            raise AttributeError(name)
        return getattr(self._as_table(f".{name}"), name)

    def __getitem__(self, key):
        return self._as_table("[...]")[key]

    def __len__(self) -> int:
        return len(self._as_table(" (len)"))

    def __iter__(self):
        return iter(self._as_table(" (iteration)"))

    def __contains__(self, key) -> bool:
        return key in self._as_table(" (in)")


def parse_velocities(text: str, *, option: str = "velocities", notice=None) -> list[float]:
    """Speeds, m/s, from ``"START:STOP:NUM"`` (NUM speeds from START to STOP, both
    included, as every range option reads it: :mod:`gyroshell.core.ranges`) or
    ``"v1,v2,..."``.

    The old ``START:STOP:STEP`` form is read until
    :data:`~gyroshell.core.ranges.STEP_FORM_ENDS` where it gives other speeds than NUM
    would (:func:`~gyroshell.core.ranges.old_step_range`: ``0:100:10`` is 11 speeds,
    ``0:1:0.25`` 5), with a one-line notice passed to ``notice`` (default: a
    :class:`FutureWarning`). The number of speeds is checked against
    :data:`gyroshell.core.budget.MAX_SWEEP_SPEEDS` before the list is built, so
    ``0:100:1e-12`` is refused at once.

    Raises
    ------
    ParameterError
        For a malformed, empty or non-finite entry, NUM not a whole number >= 1, a
        negative speed, or too many speeds.
    """
    from ..core.ranges import old_step_range, parse_range

    text = text.strip()
    if ":" in text:
        old = old_step_range(text, option, unit="m/s")
        if old is None:
            values = parse_range(text, option, unit="m/s", limit=lambda n: budget.
                                 check_sweep_length(n, what=f"{option} {text!r}"))
            return [check_velocity(float(v)) for v in values]
        start, step, count, message = old
        budget.check_sweep_length(count, what=f"{option} {text!r}")
        if notice is None:
            warnings.warn(message, FutureWarning, stacklevel=2)
        else:
            notice(message)
        return [check_velocity(start + i * step) for i in range(count)]
    parts = text.split(",")
    if text and not all(t.strip() for t in parts):
        raise ParameterError(f"{option} {text!r}: an empty entry; give speeds in m/s "
                             "separated by single commas")
    try:
        numbers = [float(t) for t in parts]
    except ValueError:
        raise ParameterError(f"{option} must be 'START:STOP:NUM' or 'v1,v2,...' in m/s, "
                             f"got {text!r}") from None
    for number in numbers:
        if not math.isfinite(number):
            raise ParameterError(f"{option} {text!r}: every number must be finite (m/s)")
    budget.check_sweep_length(len(numbers), what=f"{option} {text[:40]!r}")
    return [check_velocity(v) for v in numbers]


def check_velocities(velocities: Iterable[float], *, name: str = "velocities"
                     ) -> list[float]:
    """Validated speeds: at least one, each finite and >= 0 m/s, no speed twice (a branch
    is tracked from one speed to the next, and a table has one row per speed and rank);
    in any order (a sweep tracks them in the order given). ``name`` is how the message
    names them (``--velocities`` on the command line).

    Examples
    --------
    >>> check_velocities([0, 20.0, 10])
    [0.0, 20.0, 10.0]
    >>> check_velocities([0, 10, 10])
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: velocities must be distinct speeds (m/s): 10 is given 2 times
    """
    out = [check_velocity(v) for v in velocities]
    if not out:
        raise ParameterError(f"{name} must contain at least one speed (m/s)")
    values, counts = np.unique(out, return_counts=True)
    if counts.max() > 1:
        twice = int(np.argmax(counts > 1))
        raise ParameterError(f"{name} must be distinct speeds (m/s): {values[twice]:g} is "
                             f"given {counts[twice]} times")
    return out


def correlation(md: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Mass-weighted mode-shape correlation matrix |aᴴ M b| / (‖a‖_M ‖b‖_M), in [0, 1]."""
    na = np.sqrt(np.einsum("ij,i,ij->j", a.conj(), md, a).real)
    nb = np.sqrt(np.einsum("ij,i,ij->j", b.conj(), md, b).real)
    return np.abs(a.conj().T @ (md[:, None] * b)) / np.outer(na, nb)


def sweep(model: TapeModel, velocities: Sequence[float], count: int = 6, *,
          min_correlation: float = 0.5, progress: bool | None = False,
          continuation: bool = True, workers: int = 1, **options) -> SweepResult:
    """Lowest ``count`` frequencies at each speed, tracked into branches.

    Parameters
    ----------
    model : TapeModel
    velocities : sequence of float
        Tape speeds V, m/s (finite, >= 0), in the order they are tracked.
    count : int
        Modes per speed.
    min_correlation : float
        A match weaker than this starts a new branch (the mode left the lowest-``count``
        window and another entered); take smaller speed steps to follow branches further.
    progress : bool or None
        True: a progress bar on stderr, False: nothing; None: the bar on a terminal, else
        one line per stage (:class:`gyroshell.core.progress.StageLines`).
    continuation : bool
        Move the shift with the tracked lowest frequency (extrapolated from the previous
        speeds, see :func:`_continuation_options`), start each solve from the previous
        speed's modes and, when a speed lies above √(T/ρ), certify K(V) > 0 once for
        the model (:func:`gyroshell.engines.eigen.stiffness_floor`) instead of factoring
        K(V) at each of them. The results are those of independent solves (to round-off);
        the saving is Lanczos steps (a shift close below ω₁ separates the clustered
        long-tape frequencies) and those factorizations.
    workers : int
        Local processes (>= 1). With more than one, the speeds are split into that many
        contiguous runs, each solved with continuation in its own process, and the branches
        are tracked across them afterwards; the frequencies are the same as on one process
        (to round-off: each run starts its continuation afresh).
    **options
        Passed to :func:`gyroshell.modes` (``sigma``, ``tol``, ``damping``, ...).

    Returns
    -------
    SweepResult
        Its ``table`` has the columns :data:`COLUMNS`: ``velocity`` (m/s), ``branch``
        (tracked label), ``rank`` (position in ascending ω at that speed), ``omega``
        (rad/s), ``frequency`` (Hz), ``period`` (s), ``growth_rate`` (1/s, > 0 only if
        unstable), ``residual``, ``correlation`` (with the previous speed's mode of the
        branch; 1 at the first speed), ``supercritical`` (K(V) indefinite), ``stability``
        ("stable", "divergence" or "flutter", of the speed's computed eigenvalues).
        Refused (ParameterError) above the time limit, timed on its first two solves.
    """
    import pandas as pd

    velocities, workers = _check_sweep(model, velocities, min_correlation, workers)
    progress = validation.progress(progress)
    results = solve_speeds(model, velocities, count, continuation=continuation,
                           workers=workers, options=options, progress=progress,
                           description="sweep")
    tracker = BranchTracker(partial(correlation, model.mass_diagonal), min_correlation)
    rows: list[dict] = []
    for res, match in zip(results, track(results, tracker), strict=True):
        rows.extend(_rows(res, match))
    return SweepResult(pd.DataFrame(rows, columns=list(COLUMNS)), np.array(velocities),
                       int(count), float(min_correlation), bool(continuation),
                       getattr(model, "params", None), getattr(model, "grid", None),
                       {"workers": workers})


def _check_sweep(model, velocities, min_correlation: float, workers
                 ) -> tuple[list[float], int]:
    """The validated speeds (m/s) and number of processes; all refused before any work."""
    check_model(model)
    velocities = check_velocities(velocities)
    if not 0.0 <= min_correlation <= 1.0:
        raise ParameterError(f"min_correlation must be in [0, 1], got {min_correlation!r}")
    velocities = [check_speed(model, v) for v in velocities]
    return velocities, check_workers(workers, len(velocities))


def check_workers(workers, speeds: int) -> int:
    """The number of local processes for ``speeds`` speeds: an integer in [1,
    :func:`gyroshell.core.parallel.max_processes`], used at most one per speed."""
    return min(check_process_count("workers", workers), speeds)


def solve_speeds(model, velocities: list[float], count: int, *, continuation: bool,
                 workers: int, options: dict, progress: bool | None,
                 description: str, above: int = 0) -> list[Modes]:
    """The modes at each speed, in the order of ``velocities`` (validated, m/s).

    One process continues each speed from the previous ones (``continuation``); several
    ``workers`` each continue one contiguous run of the speeds. ``options`` go to
    :func:`gyroshell.modes`; the bar is labelled ``description``. ``count`` is checked
    first (against the model's unknowns), before the progress starts; ``above`` of the
    ``count`` modes are solved only to be tracked (the start line says so).
    """
    count = check_count(count, model.unknowns)
    with stage_progress(len(velocities), description, progress=progress,
                        unit="speed") as bar:
        extra = f" (and {above} above, tracked)" if above else ""
        bar.start(f"of {count - above} modes each{extra}, {model.unknowns} unknowns, "
                  + ("in this process" if workers == 1 else f"on {workers} processes"))
        if workers == 1:
            check = _time_check(model, len(velocities), len(velocities), count, 1)
            return _solve_run(model, velocities, count, continuation, options,
                              lambda n: (check(n), bar.update(n)))
        return _solve_parallel(model, velocities, count, continuation, options, workers,
                               bar.update)


def _time_check(model, speeds: int, run: int, count: int, workers: int):
    """The time limit over a run of ``run`` of the ``speeds`` speeds (one of ``workers``
    runs side by side): measured on its first solves
    (:class:`gyroshell.core.progress.TimeCheck`)."""
    from ..core.progress import TimeCheck

    return TimeCheck(run, unit="speed", parallel=workers,
                     size=f"{speeds} speeds of {count} modes of {model.unknowns} unknowns",
                     advice="use fewer speeds, more workers or a larger spacing")


def _solve_run(model: TapeModel, velocities: list[float], count: int, continuation: bool,
               options: dict, done=None) -> list[Modes]:
    """Modes at consecutive speeds, each continued from the previous ones."""
    p = model.params
    above_string = sum(p.density * v * v > p.tension for v in velocities)
    if continuation and above_string >= FLOOR_WORTH_IT:
        stiffness_floor(model, near_divergence=True)
    history: list[Modes] = []
    for v in velocities:
        history.append(modes(model, v, count, **{
            **_continuation_options(model, history, v, continuation), **options}))
        if done is not None:
            done(1)
    return history


def _solve_parallel(model: TapeModel, velocities: list[float], count: int,
                    continuation: bool, options: dict, workers: int, done) -> list[Modes]:
    """Contiguous runs of speeds on ``workers`` processes, results in the order of the
    speeds: this process solves the first run (timed on its first solves: the time limit,
    :func:`_time_check`), ``workers - 1`` local processes the others. The model goes to
    them pickled before this process touches it (its caches fill as it solves)."""
    import pickle

    bounds = np.linspace(0, len(velocities), workers + 1).round().astype(int)
    runs = [velocities[a:b] for a, b in zip(bounds[:-1], bounds[1:], strict=True) if b > a]
    payload = pickle.dumps(model, protocol=pickle.HIGHEST_PROTOCOL)
    check = _time_check(model, len(velocities), len(runs[0]), count, len(runs))
    with process_pool(len(runs) - 1) as pool:
        futures = [pool.submit(_solve_pickled, payload, run, count, continuation, options)
                   for run in runs[1:]]
        results = _solve_run(model, runs[0], count, continuation, options,
                             lambda n: (check(n), done(n)))
        for fut in futures:
            part = fut.result()
            done(len(part))
            results.extend(part)
    return results


def _solve_pickled(payload: bytes, velocities: list[float], count: int, continuation: bool,
                   options: dict) -> list[Modes]:
    """:func:`_solve_run` of a pickled model (in a worker process)."""
    import pickle

    return _solve_run(pickle.loads(payload), velocities, count, continuation, options)


#: Speeds above √(T/ρ) from which proving the stiffness floor near divergence (a few
#: half-width factorizations once, :func:`gyroshell.engines.divergence.proved_shift`) pays:
#: below √(T/ρ), K(V) > 0 holds by construction. Without the proof each such speed proves
#: its halves' K_s(V), K_a(V) > 0 by a half-width Cholesky each
#: (:func:`gyroshell.engines.eigen`'s ``_halves_definite``) and still runs on the halves;
#: measured at L_x/L_y = 19 (CPU time): the proof 105 ms, the two Choleskys 21 ms per
#: speed, so the proof pays from five such speeds.
FLOOR_WORTH_IT = 5


def _continuation_options(model: TapeModel, history: list[Modes], velocity: float,
                          enabled: bool) -> dict:
    """``start`` and ``estimate`` for :func:`modes` from the previous speeds' modes.

    The shift is moved with the tracked lowest frequency: ω₁ at the new speed is
    extrapolated from the last (up to three) subcritical undamped speeds by the polynomial
    in V² through them (ω₁ falls like V² from V = 0), lowered by twice the error the same
    extrapolation made at the previous speed (at least :data:`TRACK_MARGIN`), and never
    below the bottom of the travelling-wave band that :func:`modes` would use. A shift that
    close to ω₁ separates the
    clustered long-tape frequencies better than the bottom of the travelling-wave band
    (fewer Lanczos steps); it is still certified by the inertia of Q(iω_s), and an
    overshoot only adds the frequencies below it to those computed.
    """
    if not enabled or not history:
        return {}
    last = history[-1]
    if last.supercritical or last.damped:
        return {}
    options: dict = {"start": last}
    track = [h for h in history[-4:] if not (h.supercritical or h.damped)]
    if len(track) >= 2 and len(track) == min(len(history), 4):
        guess = _extrapolate(track[-3:], velocity)
        if len(track) >= 3:
            seen = _extrapolate(track[-4:-1], track[-1].velocity)
            error = abs(seen - track[-1].omega[0]) / track[-1].omega[0]
        else:
            error = TRACK_FIRST_ERROR
        guess *= 1 - max(2 * error, TRACK_MARGIN)
        guess = max(guess, strip_frequency_estimate(model.params, model.grid, velocity))
        if math.isfinite(guess) and guess > 0:
            options["estimate"] = guess
    return options


#: Least relative margin below the extrapolated lowest frequency.
TRACK_MARGIN = 1e-4
#: Assumed relative error of the first (linear) extrapolation.
TRACK_FIRST_ERROR = 5e-3


def _extrapolate(points: list[Modes], velocity: float) -> float:
    """ω₁ at ``velocity``, rad/s: the polynomial in V² through the points' (V², ω₁)."""
    v = np.array([p.velocity for p in points]) ** 2
    w = np.array([p.omega[0] for p in points])
    if len(np.unique(v)) < len(v):
        return float(w[-1])
    return float(np.polyval(np.polyfit(v, w, len(v) - 1), velocity**2))


def _rows(res: Modes, match: Match) -> list[dict]:
    stability = res.stability
    # a mode with no previous one to compare (the first speed, a newcomer) counts as sure
    corr = np.where(match.assigned, match.similarity, 1.0)
    return [{
        "velocity": res.velocity, "branch": match.labels[j], "rank": j,
        "omega": float(res.omega[j]), "frequency": float(res.frequency[j]),
        "period": float(res.period[j]), "growth_rate": float(res.growth_rate[j]),
        "residual": float(res.residuals[j]), "correlation": float(corr[j]),
        "supercritical": bool(res.supercritical), "stability": stability,
    } for j in range(res.count)]


def plot_sweep(result, path=None, *, ax=None, title: str | None = None):
    """ω (rad/s) against V (m/s), one line per tracked branch; returns the Figure.

    ``result`` is a :class:`SweepResult` (or its table); the drawing is
    :func:`gyroshell.plot.sweep`. With ``path`` the figure is also written there (PNG etc.,
    atomically, at :data:`SWEEP_DPI` dots per inch).
    """
    from .. import plot

    if path is not None:
        plot.pyplot(path=path)  # a figure only written to a file needs no window
    ax = plot.sweep(result, ax=ax, title=title)
    if path is not None:
        plot.save_figure(ax.figure, path, dpi=SWEEP_DPI, close=False)
    return ax.figure


def _check_table(ds) -> None:
    """A sweep file's table: its columns stored, its speeds those of ``velocities``, and
    ``count`` modes at each speed (a solve returns ``count`` modes; fewer only where a tiny
    model has no more)."""
    layout.table_columns(ds)
    if "velocity" not in ds.variables:
        raise ParameterError("column velocity is missing")
    count = int(ds.attrs["count"])
    rows = ds["velocity"].values
    speeds = np.asarray(ds["velocities"].values).ravel()
    stray = np.setdiff1d(rows, speeds)
    if stray.size:
        raise ParameterError(f"the table has rows at {stray[0]:g} m/s, not one of the "
                             "stored velocities")
    per_speed = np.array([np.count_nonzero(rows == v) for v in np.unique(speeds)])
    if per_speed.size and (per_speed.max() > count or per_speed.max() < count
                           or per_speed.min() == 0):
        raise ParameterError(f"count is {count} but the table holds {per_speed.min()} to "
                             f"{per_speed.max()} modes per speed")
