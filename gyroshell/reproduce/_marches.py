"""The step-load transients several studies share: one march per (tape, V, Δt), sliced.

fig2 (V = 0, 50, 90, 100 m/s; 1000 steps), period (1505 and 1898 steps at V = 0 and 50),
fig5 (V = 50, 400 steps), fig6 (V = 100, 400 steps) and observations (V = 50, 160 steps;
V = 0 and 50, 36 steps) march the same L_x/L_y = 19 tape from rest under the paper's step
load with β = 1/4, γ = 1/2 at the paper's Δt. A march is deterministic and its step n does
not depend on how many steps follow (nor on what is recorded), so the first n steps of a
longer run are the n-step run bit for bit (``tests/studies/test_shared_marches.py``).

:func:`step_response` therefore keeps, inside a :func:`sharing_marches` block, the longest
run asked for so far at each (tape, V, Δt) with its load point and centre line at every
step, and answers a request that is not longer by slicing it; a longer request marches
again and replaces it. What a study gets is the same numbers whether its run was sliced or
marched for it, so the files do not depend on the order of the studies or the number of
workers; only the time does (the runner puts the parts that share a run on one worker,
longest first: :data:`gyroshell.reproduce._runner.SHARED_RUNS`).
"""

from __future__ import annotations

import contextvars
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np

from ..core.context import outermost
from ..engines.newmark import march
from ..results.transient import steps_at
from ..tape.model import TapeModel
from ._common import Settings

#: The tape every shared run marches: Table 1 with L_x/L_y = 19.
LENGTH_RATIO = 19


@dataclass(frozen=True)
class StepResponse:
    """The first ``steps`` steps of a step-load transient.

    Attributes
    ----------
    times : numpy.ndarray
        t_n = n Δt, s, shape (steps + 1,).
    load_point : numpy.ndarray
        w at the load point, m, shape (steps + 1,).
    x : numpy.ndarray
        Node coordinates along the tape, m, shape (nx + 1,).
    centerline_times : numpy.ndarray
        Times of the kept centre lines, s (the steps nearest those asked for).
    centerlines : numpy.ndarray
        w(x, L_y/2), m, shape (len(centerline_times), nx + 1).
    """

    times: np.ndarray
    load_point: np.ndarray
    x: np.ndarray
    centerline_times: np.ndarray
    centerlines: np.ndarray


class SharedMarches:
    """The longest run kept per (tape, V, Δt) in one :func:`sharing_marches` block.

    Attributes
    ----------
    marches : int
        Runs marched in the block.
    slices : int
        Requests answered from a run marched before.
    """

    def __init__(self) -> None:
        self._runs: dict[tuple, tuple] = {}
        self.marches = 0
        self.slices = 0

    def run(self, key: tuple, steps: int, make) -> tuple:
        """(times, load point, x, every step's centre line) of at least ``steps`` steps:
        the kept run under ``key`` if it is as long, else ``make(steps)``, kept."""
        kept = self._runs.get(key)
        if kept is not None and len(kept[0]) > steps:
            self.slices += 1
            return kept
        self._runs[key] = kept = make(steps)
        self.marches += 1
        return kept


_SHARED: contextvars.ContextVar[SharedMarches | None] = contextvars.ContextVar(
    "gyroshell_shared_marches", default=None)


@contextmanager
def sharing_marches() -> Iterator[SharedMarches]:
    """A block in which :func:`step_response` keeps its runs; nested blocks are the outer
    one, and the runs are dropped when the outermost ends."""
    with outermost(_SHARED, SharedMarches) as (shared, _):
        yield shared


def _march(model: TapeModel, velocity: float, dt: float, steps: int, centerline_times,
           progress) -> tuple:
    res = march(model, velocity, dt=dt, steps=steps, centerline_times=centerline_times,
                progress=progress)
    s = res.snapshots
    return res.times, res.load_point, s.x, s.centerline_times, s.centerlines


def step_response(settings: Settings, velocity: float, dt: float, steps: int, *,
                  centerline_times: Sequence[float] | None = None,
                  progress: bool | None = None) -> StepResponse:
    """The step-load transient of the L_x/L_y = 19 tape (``settings``' grid) from rest,
    β = 1/4, γ = 1/2: ``march(model, velocity, dt=dt, steps=steps,
    centerline_times=centerline_times)``'s load point and centre lines, sliced from a longer
    run of the enclosing :func:`sharing_marches` block when there is one.

    Parameters
    ----------
    settings : Settings
    velocity : float
        Tape speed V, m/s.
    dt : float
        Time step Δt, s.
    steps : int
        Steps of the run.
    centerline_times : sequence of float, optional
        Times (s) of the centre lines to keep (nearest steps).
    progress : bool or None
        Progress bar of a march made here.
    """
    model = TapeModel(settings.params(length_ratio=LENGTH_RATIO))
    shared = _SHARED.get()
    if shared is None:
        times, load_point, x, line_times, lines = _march(model, velocity, dt, steps,
                                                         centerline_times, progress)
        return StepResponse(times, load_point, x, line_times, lines)

    def every_line(n: int) -> tuple:
        return _march(model, velocity, dt, n, dt * np.arange(n + 1), progress)

    times, load_point, x, _, lines = shared.run((model.params, velocity, dt), steps,
                                                every_line)
    kept = (np.zeros(0, dtype=np.int64) if centerline_times is None else
            steps_at(centerline_times, dt, steps, name="centerline_times"))
    return StepResponse(times[:steps + 1].copy(), load_point[:steps + 1].copy(), x.copy(),
                        times[kept], lines[kept])
