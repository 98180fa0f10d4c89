"""Frequencies against tape speed, with mode tracking, as a DataFrame and a plot.

At each speed the lowest ``count`` modes are computed (:func:`gyroshell.eigen.modes`) and
matched to the previous speed's by mode-shape correlation

    C_ij = |φ_iᴴ M ψ_j| / (‖φ_i‖_M ‖ψ_j‖_M),

with the assignment that maximizes the total correlation (Hungarian algorithm). A branch
therefore keeps its label when frequencies cross or veer, instead of following the sorted
order. A mode that leaves the lowest-``count`` window is replaced by the newcomer with a low
correlation; the ``correlation`` column says how sure each match is.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING

import numpy as np
from scipy.optimize import linear_sum_assignment

from ..core import budget
from ..core.errors import ParameterError
from ..engines.eigen import Modes, check_speed, modes, stiffness_floor, strip_frequency_estimate
from ..tape.model import TapeModel
from ..tape.parameters import check_velocity

if TYPE_CHECKING:  # pandas and tqdm are imported when a sweep runs: keep `import gyroshell` fast
    import pandas as pd

#: Columns of the sweep DataFrame (long format, one row per speed and branch).
COLUMNS = ("velocity", "branch", "rank", "omega", "frequency", "period", "growth_rate",
           "residual", "correlation", "supercritical", "stability")


def parse_velocities(text: str, *, option: str = "velocities") -> list[float]:
    """Speeds, m/s, from ``"start:stop:step"`` (stop included) or ``"v1,v2,..."``.

    The number of speeds is checked against :data:`gyroshell.budget.MAX_SWEEP_SPEEDS`
    before the list is built, so ``0:100:1e-12`` is refused at once.

    Raises
    ------
    ParameterError
        For a malformed or non-finite entry, a step <= 0, stop < start, a negative speed, or
        too many speeds.
    """
    text = text.strip()
    form = f"{option} must be 'start:stop:step' or 'v1,v2,...' in m/s, got {text!r}"
    parts = text.split(":") if ":" in text else [t for t in text.split(",") if t.strip()]
    try:
        numbers = [float(t) for t in parts]
    except ValueError:
        raise ParameterError(form) from None
    if not numbers or (":" in text and len(numbers) != 3):
        raise ParameterError(form)
    for number in numbers:
        if not math.isfinite(number):
            raise ParameterError(f"{option} {text!r}: every number must be finite (m/s)")
    if ":" not in text:
        budget.check_sweep_length(len(numbers), what=f"{option} {text[:40]!r}")
        velocities = numbers
    else:
        start, stop, step = numbers
        if not step > 0 or stop < start:
            raise ParameterError(f"{option} {text!r}: need step > 0 and stop >= start (m/s)")
        count = math.floor((stop - start) / step + 1e-9) + 1 \
            if math.isfinite((stop - start) / step) else math.inf
        budget.check_sweep_length(count, what=f"{option} {text!r}")
        velocities = [start + i * step for i in range(int(count))]
    return [check_velocity(v) for v in velocities]


def check_velocities(velocities: Iterable[float]) -> list[float]:
    """Validated speeds: at least one, each finite and >= 0 m/s."""
    out = [check_velocity(v) for v in velocities]
    if not out:
        raise ParameterError("velocities must contain at least one speed (m/s)")
    return out


def correlation(md: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Mass-weighted mode-shape correlation matrix |aᴴ M b| / (‖a‖_M ‖b‖_M), in [0, 1]."""
    na = np.sqrt(np.einsum("ij,i,ij->j", a.conj(), md, a).real)
    nb = np.sqrt(np.einsum("ij,i,ij->j", b.conj(), md, b).real)
    return np.abs(a.conj().T @ (md[:, None] * b)) / np.outer(na, nb)


def sweep(model: TapeModel, velocities: Sequence[float], count: int = 6, *,
          min_correlation: float = 0.5, progress: bool | None = False,
          continuation: bool = True, workers: int = 1, **options) -> pd.DataFrame:
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
        Show a tqdm progress bar on stderr; None: only if stderr is a terminal.
    continuation : bool
        Move the shift with the tracked lowest frequency (extrapolated from the previous
        speeds, see :func:`_continuation_options`), start each solve from the previous
        speed's modes and, when several speeds lie above √(T/ρ), certify K(V) > 0 once for
        the model (:func:`gyroshell.eigen.stiffness_floor`) instead of factoring K(V) at each
        of them. The results are those of independent solves (to round-off); the saving is
        Lanczos steps (a shift close below ω₁ separates the clustered long-tape frequencies)
        and those factorizations.
    workers : int
        Local processes (>= 1). With more than one, the speeds are split into that many
        contiguous runs, each solved with continuation in its own process, and the branches
        are tracked across them afterwards; the frequencies are the same as on one process
        (to round-off: each run starts its continuation afresh).
    **options
        Passed to :func:`gyroshell.eigen.modes` (``sigma``, ``tol``, ``damping``, ...).

    Returns
    -------
    pandas.DataFrame
        Columns :data:`COLUMNS`: ``velocity`` (m/s), ``branch`` (tracked label), ``rank``
        (position in ascending ω at that speed), ``omega`` (rad/s), ``frequency`` (Hz),
        ``period`` (s), ``growth_rate`` (1/s, > 0 only if unstable), ``residual``,
        ``correlation`` (with the previous speed's mode of the branch; 1 at the first speed),
        ``supercritical`` (K(V) indefinite), ``stability`` ("stable", "divergence" or
        "flutter", of the speed's computed eigenvalues).
    """
    import pandas as pd
    from tqdm import tqdm

    velocities = check_velocities(velocities)
    if progress is None:
        import sys

        progress = bool(getattr(sys.stderr, "isatty", lambda: False)())
    if not 0.0 <= min_correlation <= 1.0:
        raise ParameterError(f"min_correlation must be in [0, 1], got {min_correlation!r}")
    velocities = [check_speed(model, v) for v in velocities]   # all refused before any work
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1:
        raise ParameterError(f"workers must be an integer >= 1, got {workers!r}")
    workers = min(int(workers), len(velocities))
    bar = tqdm(total=len(velocities), disable=not progress, desc="sweep", unit="speed")
    with bar:
        if workers == 1:
            results = _solve_run(model, velocities, count, continuation, options, bar.update)
        else:
            results = _solve_parallel(model, velocities, count, continuation, options,
                                      workers, bar.update)
    tracker = _BranchTracker(model.mass_diagonal, min_correlation)
    rows: list[dict] = []
    for res in results:
        labels, corr = tracker.match(res.vectors)
        rows.extend(_rows(res, labels, corr))
    return pd.DataFrame(rows, columns=list(COLUMNS))


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
    """Contiguous runs of speeds on ``workers`` local processes (fork server: the parent
    may hold BLAS threads), results in the order of the speeds."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    from .parameter_study import _init_worker

    bounds = np.linspace(0, len(velocities), workers + 1).round().astype(int)
    runs = [velocities[a:b] for a, b in zip(bounds[:-1], bounds[1:], strict=True) if b > a]
    methods = multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
    with ProcessPoolExecutor(max_workers=workers, initializer=_init_worker,
                             mp_context=context) as pool:
        futures = [pool.submit(_solve_run, model, run, count, continuation, options)
                   for run in runs]
        try:
            results: list[Modes] = []
            for fut in futures:
                part = fut.result()
                done(len(part))
                results.extend(part)
        except BaseException:
            for fut in futures:
                fut.cancel()
            raise
    return results


#: Speeds above √(T/ρ) from which proving the stiffness floor near divergence (a few
#: factorizations once) pays: below √(T/ρ), K(V) > 0 holds by construction.
FLOOR_WORTH_IT = 4


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


class _BranchTracker:
    """Labels modes by mass-weighted correlation with the previous speed's (Hungarian)."""

    def __init__(self, md: np.ndarray, min_correlation: float) -> None:
        self.md, self.min_correlation = md, min_correlation
        self.previous: np.ndarray | None = None
        self.labels: list[int] = []
        self.next_label = 0

    def match(self, vectors: np.ndarray) -> tuple[list[int], np.ndarray]:
        k = vectors.shape[1]
        new_labels = [-1] * k
        corr_of = np.ones(k)
        if self.previous is not None:
            c = correlation(self.md, self.previous, vectors)
            for i, j in zip(*linear_sum_assignment(-c), strict=False):
                if c[i, j] >= self.min_correlation:
                    new_labels[j], corr_of[j] = self.labels[i], c[i, j]
                else:
                    corr_of[j] = c[i, j]
        for j in range(k):
            if new_labels[j] < 0:  # a mode that entered the window: a new branch
                new_labels[j], self.next_label = self.next_label, self.next_label + 1
        self.previous, self.labels = vectors, new_labels
        return new_labels, corr_of


def _rows(res: Modes, labels: list[int], corr: np.ndarray) -> list[dict]:
    stability = res.stability
    return [{
        "velocity": res.velocity, "branch": labels[j], "rank": j,
        "omega": float(res.omega[j]), "frequency": float(res.frequency[j]),
        "period": float(res.period[j]), "growth_rate": float(res.growth_rate[j]),
        "residual": float(res.residuals[j]), "correlation": float(corr[j]),
        "supercritical": bool(res.supercritical), "stability": stability,
    } for j in range(res.count)]


def plot_sweep(frame: pd.DataFrame, path=None, *, ax=None, title: str | None = None):
    """ω (rad/s) against V (m/s), one line per tracked branch; returns the Figure.

    Supercritical points (growth rate > 0) are marked with crosses. With ``path`` the figure
    is written there (PNG etc., atomically). matplotlib is imported here, not at import time.
    """
    missing = {"velocity", "branch", "omega"} - set(frame.columns)
    if missing:
        raise ParameterError(f"frame lacks columns {sorted(missing)}")
    import matplotlib

    if path is not None and ax is None:
        matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    if ax is None:
        fig, ax = plt.subplots(figsize=(7.0, 4.5), constrained_layout=True)
    else:
        fig = ax.figure
    if "rank" in frame:  # the k-th lowest frequency: continuous even where branches end
        for rank, group in frame.groupby("rank"):
            group = group.sort_values("velocity")
            ax.plot(group["velocity"], group["omega"], color="0.75", lw=0.8, zorder=1,
                    label="k-th lowest ω" if rank == 0 else None)
    branches = frame.groupby("branch")
    few = branches.ngroups <= 8
    for k, (branch, group) in enumerate(branches):
        group = group.sort_values("velocity")
        label = f"branch {branch}" if few else ("tracked branches (mode-shape correlation)"
                                                if k == 0 else None)
        ax.plot(group["velocity"], group["omega"], marker="o", ms=3, lw=1.2, zorder=2,
                color=None if few else f"C{branch % 10}", label=label)
    if "growth_rate" in frame and (frame["growth_rate"] > 0).any():
        sup = frame[frame["growth_rate"] > 0]
        ax.plot(sup["velocity"], sup["growth_rate"], "kx", ls="none",
                label="growth rate Re λ (1/s), divergence")
    ax.set_xlabel("tape speed V (m/s)")
    ax.set_ylabel("angular frequency ω (rad/s)")
    ax.set_title(title or "Lowest frequencies of the moving tape against speed")
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    if path is not None:
        from ..core.files import write_atomic

        write_atomic(path, lambda tmp: fig.savefig(tmp, dpi=120))
    return fig
