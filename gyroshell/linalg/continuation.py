"""One continuation driver: a family of problems solved along a scalar parameter.

:func:`continuation` solves ``solve_at(value, state)`` at the start value, then at values
stepping towards the target, each stage started from the last state reached. One
:class:`StepController` sets the steps, in the value itself (``"linear"``) or in its
logarithm (``"geometric"``: values a ratio apart): a stage that converges in few iterations
lets the step grow, a stage that fails is retried from the last value reached with the step
cut, and a step cut below its floor ends the path with a ConvergenceError naming the last
value reached.

The same driver runs a pseudo-time continuation: the parameter is the pseudo-time step s,
geometric from a small s to a large target, ``solve_at(s, state)`` one implicit step of
size s from ``state`` (at a large enough s the steady problem itself).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..core import validation
from ..core.errors import ConvergenceError, ParameterError

__all__ = ["StepController", "continuation"]

#: First geometric step: values this ratio apart ...
INITIAL_RATIO = 1.25
#: ... growing by this factor (of the step in log|value|, or of the linear step) after a
#: stage of at most EASY_ITERATIONS iterations ...
GROWTH = 2.0
EASY_ITERATIONS = 4
#: ... and cut by this factor after a failed stage, down to the floor MINIMUM_RATIO.
CUT = 0.5
MINIMUM_RATIO = 1.001
#: Most stages, failed ones included.
MAX_STAGES = 100
MODES = ("geometric", "linear")


@dataclass(frozen=True)
class StepController:
    """How :func:`continuation` steps (validated).

    Parameters
    ----------
    mode : {"geometric", "linear"}
        Steps in log|value| (values a ratio apart; start and target nonzero, of one sign)
        or in the value itself.
    initial : float
        The first step: a ratio > 1 (geometric) or a step > 0 in the value's units (linear).
    growth : float
        After an easy stage the step is multiplied by this (>= 1); a geometric ratio q
        becomes q**growth.
    easy_iterations : int
        A stage whose report counts at most this many iterations (>= 0) is easy.
    cut : float
        After a failed stage the step is multiplied by this, in (0, 1).
    minimum : float
        The floor of the step, as ``initial`` (a ratio > 1, or a step > 0): a cut below it
        ends the path with a ConvergenceError.
    maximum : float or None
        The cap of the step, as ``initial`` (None: no cap).
    max_stages : int
        Most stages (>= 1), failed ones included.
    """

    mode: str = "geometric"
    initial: float = INITIAL_RATIO
    growth: float = GROWTH
    easy_iterations: int = EASY_ITERATIONS
    cut: float = CUT
    minimum: float = MINIMUM_RATIO
    maximum: float | None = None
    max_stages: int = MAX_STAGES

    def __post_init__(self) -> None:
        put, real = object.__setattr__, validation.real
        put(self, "mode", validation.choice("mode", self.mode, MODES))
        low = 1.0 if self.mode == "geometric" else 0.0
        for name in ("initial", "minimum") + (("maximum",) if self.maximum is not None else ()):
            put(self, name, real(name, getattr(self, name), low=low, low_open=True))
        if self.minimum > self.initial or (self.maximum is not None
                                           and self.maximum < self.initial):
            raise ParameterError(f"minimum <= initial <= maximum is needed, got "
                                 f"{self.minimum:g}, {self.initial:g}, {self.maximum}")
        put(self, "growth", real("growth", self.growth, low=1.0))
        put(self, "cut", real("cut", self.cut, low=0.0, high=1.0, low_open=True,
                              high_open=True))
        put(self, "easy_iterations", validation.integer("easy_iterations",
                                                        self.easy_iterations, low=0))
        put(self, "max_stages", validation.integer("max_stages", self.max_stages, low=1))

    def coordinate(self, value: float) -> float:
        """The coordinate the steps are taken in: log|value| or the value."""
        return math.log(abs(value)) if self.mode == "geometric" else value

    def step(self, size: float) -> float:
        """A step's length in that coordinate from ``initial``/``minimum``/``maximum``."""
        return math.log(size) if self.mode == "geometric" else size


def _path(start_value: object, target: object, controller: StepController) -> tuple:
    """The checked start and target (finite; geometric: nonzero, of one sign)."""
    start = validation.real("start_value", start_value)
    end = validation.real("target", target)
    if controller.mode == "geometric" and (start == 0.0 or start * end <= 0.0):
        raise ParameterError("a geometric continuation needs start_value and target "
                             f"nonzero and of one sign, got {start:g} and {end:g}")
    return start, end


def _stopped(message: str, state: Any, value: float | None, stages: list,
             cause: ConvergenceError | None = None) -> ConvergenceError:
    """A ConvergenceError with the last state and value reached and the stages."""
    exc = ConvergenceError(message + (f" ({cause})" if cause is not None else ""))
    exc.state, exc.value, exc.stages = state, value, stages
    exc.report = getattr(cause, "report", None)
    return exc


def _next_value(controller: StepController, value: float, target: float,
                step: float) -> tuple[float, float]:
    """The next value from ``value`` towards ``target`` by ``step`` (in the controller's
    coordinate), the target itself if within it; and the step length taken."""
    t, t_end = controller.coordinate(value), controller.coordinate(target)
    if step >= abs(t_end - t):
        return target, abs(t_end - t)
    t_next = t + math.copysign(step, t_end - t)
    if controller.mode == "geometric":
        return math.copysign(math.exp(t_next), value), step
    return t_next, step


def _first_stage(solve_at: Callable, start: float, first_state: Any, stages: list) -> Any:
    """The stage at the start value, from ``first_state``; its failure ends the path."""
    try:
        state, report = solve_at(start, first_state)
    except ConvergenceError as exc:
        stages.append((start, getattr(exc, "report", None)))
        raise _stopped(f"continuation: the first stage, at {start:g}, failed; try a better "
                       "first state or another start value", first_state, None, stages,
                       exc) from exc
    stages.append((start, report))
    return state



class _Walk:
    """The path's progress: the last value and state reached, the step, the stages."""

    def __init__(self, controller: StepController, start: float, target: float,
                 state: Any, stages: list) -> None:
        self.controller, self.start, self.target = controller, start, target
        self.state, self.value, self.stages = state, start, stages
        self.step = controller.step(controller.initial)
        self.floor = controller.step(controller.minimum)
        self.cap = (math.inf if controller.maximum is None
                    else controller.step(controller.maximum))

    def advance(self, solve_at: Callable, log) -> None:
        """Try one stage: on success move there (the step grows if it was easy), on
        failure cut the step (raising ConvergenceError below its floor)."""
        c = self.controller
        if len(self.stages) >= c.max_stages:
            raise _stopped(f"continuation from {self.start:g} to {self.target:g} stopped at "
                           f"{self.value:g} after {len(self.stages)} stages (max_stages): "
                           "try a larger initial step or more stages", self.state,
                           self.value, self.stages)
        nxt, taken = _next_value(c, self.value, self.target, self.step)
        try:
            state, report = solve_at(nxt, self.state)
        except ConvergenceError as exc:
            self.stages.append((nxt, getattr(exc, "report", None)))
            self.step = taken * c.cut
            if log is not None:
                log(f"continuation: {nxt:g} failed, step cut to {self.step:.3g}")
            if self.step < self.floor:
                raise _stopped(f"continuation from {self.start:g} to {self.target:g} stopped "
                               f"at {self.value:g}: the stage at {nxt:g} failed and the step "
                               "fell below its floor (StepController.minimum); try a better "
                               "first state, a smaller minimum or another path", self.state,
                               self.value, self.stages, exc) from exc
            return
        self.stages.append((nxt, report))
        self.state, self.value = state, nxt
        if report.iterations <= c.easy_iterations:
            self.step = min(self.step * c.growth, self.cap)
        if log is not None:
            log(f"continuation: {nxt:g} in {report.iterations} iterations")


def continuation(solve_at: Callable[[float, Any], tuple[Any, Any]], start_value: float,
                 target: float, first_state: Any, *,
                 controller: StepController | None = None,
                 log: Callable[[str], None] | None = None) -> tuple[Any, list]:
    """Solve a family of problems along a scalar parameter from ``start_value`` to
    ``target`` (either direction), each stage started from the last state reached.

    Parameters
    ----------
    solve_at : callable
        ``solve_at(value, state) -> (state, report)``: the problem at the parameter value,
        from ``state``; ``report`` has an ``iterations`` count (e.g. a
        :class:`~gyroshell.linalg.newton.NewtonReport`). Raises ConvergenceError on failure.
    start_value, target : float
        The path's ends (the parameter's units).
    first_state : object
        The start of the first stage, at ``start_value``.
    controller : StepController, optional
        The steps (default: geometric, :class:`StepController`).
    log : callable, optional
        Called with a one-line message per stage.

    Returns
    -------
    state : object
        The state at ``target``.
    stages : list of (float, object)
        Every stage tried, in order, as (value, report), failed ones included (their
        report is the exception's ``report`` attribute, or None).

    Raises
    ------
    ConvergenceError
        If the first stage fails, a cut step falls below ``controller.minimum``, or
        ``controller.max_stages`` stages have been tried; the message names the last value
        reached, the exception carries ``state`` and ``value`` (the last reached; value None
        if none), ``stages`` and ``report`` (the failed stage's, if any).
    """
    controller = StepController() if controller is None else validation.instance(
        "controller", controller, StepController)
    start, target = _path(start_value, target, controller)
    stages: list = []
    walk = _Walk(controller, start, target, _first_stage(solve_at, start, first_state, stages),
                 stages)
    while walk.value != target:
        walk.advance(solve_at, log)
    return walk.state, stages
