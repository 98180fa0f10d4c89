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

from .eigen import Modes, check_speed, modes, stiffness_floor
from .errors import ParameterError
from .model import TapeModel
from .parameters import check_velocity

if TYPE_CHECKING:  # pandas and tqdm are imported when a sweep runs: keep `import gyroshell` fast
    import pandas as pd

#: Columns of the sweep DataFrame (long format, one row per speed and branch).
COLUMNS = ("velocity", "branch", "rank", "omega", "frequency", "period", "growth_rate",
           "residual", "correlation", "supercritical", "stability")


def parse_velocities(text: str) -> list[float]:
    """Speeds from ``"start:stop:step"`` (stop included) or ``"v1,v2,..."``, m/s."""
    text = text.strip()
    try:
        if ":" in text:
            parts = [float(t) for t in text.split(":")]
            if len(parts) != 3:
                raise ValueError
            start, stop, step = parts
            if not step > 0 or stop < start:
                raise ParameterError(
                    f"velocities {text!r}: need step > 0 and stop >= start (m/s)")
            n = int(math.floor((stop - start) / step + 1e-9)) + 1
            return [start + i * step for i in range(n)]
        return [float(t) for t in text.split(",") if t.strip()]
    except ValueError:
        raise ParameterError(
            f"velocities must be 'start:stop:step' or 'v1,v2,...' in m/s, got {text!r}"
        ) from None


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
          continuation: bool = True, **options) -> pd.DataFrame:
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
        Start each solve from the previous speed's modes and, when several speeds lie above
        √(T/ρ), certify K(V) > 0 once for the model (:func:`gyroshell.eigen.stiffness_floor`)
        instead of factoring K(V) at each of them. The results are those of independent
        solves; the saving is those factorizations (the start vectors do not shorten the
        shift-invert iteration, whose cost is set by the clustered spectrum).
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
    p = model.params
    above_string = sum(p.density * v * v > p.tension for v in velocities)
    if continuation and above_string >= FLOOR_WORTH_IT:
        stiffness_floor(model, near_divergence=True)
    tracker = _BranchTracker(model.mass_diagonal, min_correlation)
    rows: list[dict] = []
    history: list[Modes] = []
    for v in tqdm(velocities, disable=not progress, desc="sweep", unit="speed"):
        res = modes(model, v, count,
                    **{**_continuation_options(history, v, continuation), **options})
        labels, corr = tracker.match(res.vectors)
        rows.extend(_rows(res, labels, corr))
        history.append(res)
    return pd.DataFrame(rows, columns=list(COLUMNS))


#: Speeds above √(T/ρ) from which proving the stiffness floor near divergence (a few
#: factorizations once) pays: below √(T/ρ), K(V) > 0 holds by construction.
FLOOR_WORTH_IT = 4


def _continuation_options(history: list[Modes], velocity: float, enabled: bool) -> dict:
    """``start`` for :func:`modes`: the previous speed's modes, if subcritical and undamped.

    The shift needs no help: the bottom of the travelling-wave band that places it follows
    the lowest frequency to within a fraction of a percent at every speed, while an
    extrapolation of ω₁(V) from the previous speeds (ω₁ falls like V², not linearly) lands
    above it and makes the certified shift retreat.
    """
    if not enabled or not history:
        return {}
    last = history[-1]
    if last.supercritical or last.damped:
        return {}
    return {"start": last}


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
        from .io import write_atomic

        write_atomic(path, lambda tmp: fig.savefig(tmp, dpi=120))
    return fig
