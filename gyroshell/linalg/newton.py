"""One generic Newton for bound-constrained nonlinear systems, knowing nothing of physics.

The problem (a mixed complementarity problem with lower bounds only): find z with z ≥ l
such that, for every unknown i,

    z_i > l_i  ⇒  r_i(z) = 0,        z_i = l_i  ⇒  r_i(z) ≥ 0,

where l_i = −inf leaves z_i unbounded (r_i = 0); with no bounds at all it is r(z) = 0. An
obstacle (a wall, a contact) is such a bound: r_i ≥ 0 at the bound is the contact force.

The method is the reduced-space active-set Newton of PETSc SNES ``vinewtonrsls``:

- the active set is A = {z_i ≤ l_i (+ ``bound_tol`` × ``variable_scale_i``) and r_i > 0}:
  the unknowns held at their bound by a positive residual;
- the Newton step solves the Jacobian reduced to the free set F: J_FF δz_F = −r_F, δz_A = 0
  (the problem's ``linearize`` replaces the rows of A by the identity and the right-hand
  side there is 0);
- one globalization: a backtracking Armijo line search on the merit ½‖D Φ(z)‖², D the
  problem's ``row_scale``, along the projected path z(α) = max(z + α δz, l), nonmonotone
  (Grippo, Lampariello and Lucidi 1986): a trial is measured against the largest merit of
  the last ``memory`` iterates, not only the current one.

Φ is the reduced residual, Φ_i = 0 on A and r_i elsewhere. The iterates are feasible (the
path is projected), and for feasible z it is the natural residual min(c (z − l), r) in the
limit c → ∞: both equal min(0, r_i) at the bound, and Φ = 0 exactly when z solves the
problem. A finite c would charge a free unknown near its bound with c (z_i − l_i), which the
reduced step does not aim to reduce (it aims at r_i = 0), so the step need not be a descent
direction; the reduced residual is exactly what the step linearizes: where the projection
does not clip and A does not change, Φ(z + α δz) = (1 − α) Φ(z) + O(α²).

Why nonmonotone: where the projection clips a step, the new contact edge is a kink whose
residual is of order 1/h on a grid of spacing h (the rows next to a wall that the step
reached at a slant), while the residual it removes elsewhere is O(1): on a fine grid a
monotone search then accepts only steps too short to change the active set, and stalls
(the 1-D obstacle problem of the tests stagnates at 2,559 unknowns; with ``memory=5`` it
converges in 25 iterations). The increase is undone in the next iterations, once the active
set has followed; the stagnation test still ends a run that does not make progress.

The projected path changes the active set by the unknowns a damped step reaches, a few
per iteration: a contact zone that a step crosses wholesale (a tape coming down onto a
land, its steps cut by the problem's ``step_limit``) can stall it. Where the path stalls
(this step and the last, if any, damped below ``stagnation_alpha``, or whole without
halving the scaled residual) and the reduced step takes free unknowns through their
bounds, the step of the linearized problem's own active set is formed too
(:func:`_set_step`: the primal–dual active-set rule of Hintermüller, Ito and Kunisch 2002
on the linearization, at most ``max_set_updates`` factorizations) and line-searched, and
the one reaching the lower merit is taken. (Tried at every damped step it also took sets
far too large, and the iterates left the basin.) An active set far too large (a start
through the wall) is released at its edges only: the iterations then grow with the grid
(the obstacle problem from u = 0: 16 iterations on 640 cells, 26 on 2,560). A start from
a coarser grid or a continuation keeps them few.

Where a factorization costs many residuals (a large 2-D grid), ``chord_step`` lets an
iteration near the solution reuse the last one (a chord step, PETSc's lagged Jacobian):
once the last reduced step was taken whole, below ``chord_step`` in relative size and with
the active set unchanged, the old factorization's step is taken if it contracts to at most
``chord_contraction`` of the last step; otherwise J is factored afresh.

Steps of relative size at most ``full_step`` are taken whole (in the quadratic regime the
merit changes by less than its round-off), as are steps from an iterate at the problem's
round-off floor (``noise``). A step whose trial has a non-finite residual is cut like one
that fails the Armijo test; the smallest trial (``min_step``) is taken anyway, and a run of
such damped steps that does not halve the scaled residual is a stagnation.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from ..core import validation
from ..core.errors import ConvergenceError, ParameterError

__all__ = ["NewtonOptions", "NewtonProblem", "NewtonReport", "newton"]

#: Relative Newton step (max |δz_i| / variable_scale_i) at which Newton has converged.
STEP_TOLERANCE = 1e-8
#: Most Newton iterations per solve.
MAX_ITERATIONS = 50
#: Sufficient decrease: the merit ½‖DΦ‖² must fall to (1 − 2 ARMIJO α) of itself ...
ARMIJO = 1e-4
#: ... or of the largest of the last MEMORY merits (a nonmonotone line search) ...
MEMORY = 5
#: ... else α is multiplied by BACKTRACK, down to MIN_STEP (that trial is taken anyway).
BACKTRACK = 0.5
MIN_STEP = 1.0 / 1024.0
#: Steps of at most this relative size are taken whole (the quadratic regime).
FULL_STEP = 1e-5
#: An unknown within BOUND_TOLERANCE × variable_scale of its bound is at the bound.
BOUND_TOLERANCE = 1e-12
#: Stagnation: over this many iterations the scaled residual has not halved and no step
#: reached STAGNATION_ALPHA of the Newton step.
STAGNATION_WINDOW = 10
STAGNATION_ALPHA = 0.5
#: With a ``noise`` hook: an iterate whose scaled residual is within ROUND_OFF_MULTIPLE of
#: the round-off floor is at the floor (whole steps); a whole step there of relative size
#: at most ROUND_OFF_STEP has converged.
ROUND_OFF_MULTIPLE = 100.0
ROUND_OFF_STEP = 1e-4
#: With a per-row ``noise`` hook: a whole step at the floor within NOISE_STEP_MULTIPLE of
#: the step the rows' round-off alone produces has converged, whatever its size.
NOISE_STEP_MULTIPLE = 10.0
#: Chord steps (off by default, ``chord_step=0``): a chord step must shrink the step at
#: least by this factor, or the Jacobian is factored afresh.
CHORD_CONTRACTION = 0.25
#: A step that the problem's ``clip_step`` changed and the line search cut below this α is
#: line-searched unclipped too (:func:`_unclipped`).
UNCLIPPED_ALPHA = 1.0 / 64.0
#: Most active sets tried per iteration on the linearized problem (each a factorization).
MAX_SET_UPDATES = 10


@dataclass(frozen=True)
class NewtonOptions:
    """The options of :func:`newton` (validated; all dimensionless).

    Parameters
    ----------
    tol : float
        Converged when a whole step has relative size max |δz_i| / variable_scale_i at most
        this (> 0).
    residual_tol : float or None
        Also converged when the scaled residual ‖D Φ(z)‖ is at most this (>= 0); None: off.
    max_iterations : int
        Most iterations (>= 1).
    armijo : float
        Sufficient decrease σ in (0, 0.5): a trial is accepted when
        ½‖DΦ(trial)‖² <= ½ R² − σα ‖DΦ(z)‖², R the reference (``memory``).
    memory : int
        The reference R is the largest scaled residual of the last ``memory`` iterates
        (>= 1; 1: the current one, a monotone line search).
    backtrack : float
        Factor in (0, 1) by which α is cut after a rejected trial.
    min_step : float
        Smallest α in (0, 1]; that trial is taken whether it decreases the merit or not.
        ``min_step=1`` turns the line search off (plain Newton).
    full_step : float
        Steps of relative size at most this (>= 0) are taken whole.
    bound_tol : float
        An unknown within bound_tol × variable_scale of its bound is at it, in [0, 1).
    stagnation_window : int
        Iterations (>= 1) over which the scaled residual must halve ...
    stagnation_alpha : float
        ... unless some step in the window reached this α, in (0, 1].
    round_off_multiple : float
        With a ``noise`` hook: a scaled residual within this multiple (>= 1) of the
        round-off floor is at the floor.
    round_off_step : float
        ... and a whole step there of relative size at most this (> 0) has converged.
    noise_step_multiple : float
        With a per-row ``noise`` hook: a whole step at the floor of relative size at most
        this multiple (>= 1) of the noise step (the step that the rows' round-off alone
        produces, through the same factorization) has converged.
    chord_step : float
        Chord steps: after a whole step of relative size below this (>= 0), with the
        active set unchanged, the last factorization is reused (no ``linearize``) as long
        as the chord step is at most ``chord_contraction`` times that step; else the
        Jacobian is factored afresh. 0 (the default): every iteration factors. Worth it
        where a factorization costs many residuals (a 2-D grid).
    chord_contraction : float
        The factor in (0, 1) by which a chord step must shrink the last step.
    max_set_updates : int
        Most further active sets (>= 0, each a factorization) tried on the linearized
        problem per iteration when the projected path stalls and the reduced step crosses
        bounds (:func:`_set_step`); 0: the reduced step only.
    """

    tol: float = STEP_TOLERANCE
    residual_tol: float | None = None
    max_iterations: int = MAX_ITERATIONS
    armijo: float = ARMIJO
    memory: int = MEMORY
    backtrack: float = BACKTRACK
    min_step: float = MIN_STEP
    full_step: float = FULL_STEP
    bound_tol: float = BOUND_TOLERANCE
    stagnation_window: int = STAGNATION_WINDOW
    stagnation_alpha: float = STAGNATION_ALPHA
    round_off_multiple: float = ROUND_OFF_MULTIPLE
    round_off_step: float = ROUND_OFF_STEP
    noise_step_multiple: float = NOISE_STEP_MULTIPLE
    chord_step: float = 0.0
    chord_contraction: float = CHORD_CONTRACTION
    max_set_updates: int = MAX_SET_UPDATES

    def __post_init__(self) -> None:
        put, real = object.__setattr__, validation.real
        put(self, "tol", validation.positive("tol", self.tol))
        if self.residual_tol is not None:
            put(self, "residual_tol", validation.nonnegative("residual_tol", self.residual_tol))
        for name in ("max_iterations", "memory", "stagnation_window"):
            put(self, name, validation.integer(name, getattr(self, name), low=1))
        put(self, "max_set_updates", validation.integer("max_set_updates",
                                                        self.max_set_updates, low=0))
        put(self, "armijo", real("armijo", self.armijo, low=0.0, high=0.5, low_open=True,
                                 high_open=True))
        put(self, "backtrack", real("backtrack", self.backtrack, low=0.0, high=1.0,
                                    low_open=True, high_open=True))
        for name in ("min_step", "stagnation_alpha"):
            put(self, name, real(name, getattr(self, name), low=0.0, high=1.0, low_open=True))
        put(self, "full_step", validation.nonnegative("full_step", self.full_step))
        put(self, "bound_tol", real("bound_tol", self.bound_tol, low=0.0, high=1.0,
                                    high_open=True))
        put(self, "round_off_multiple", real("round_off_multiple", self.round_off_multiple,
                                             low=1.0))
        put(self, "round_off_step", validation.positive("round_off_step", self.round_off_step))
        put(self, "noise_step_multiple", real("noise_step_multiple",
                                              self.noise_step_multiple, low=1.0))
        put(self, "chord_step", validation.nonnegative("chord_step", self.chord_step))
        put(self, "chord_contraction", real("chord_contraction", self.chord_contraction,
                                            low=0.0, high=1.0, low_open=True,
                                            high_open=True))


class NewtonProblem(Protocol):
    """What :func:`newton` needs of a problem (n unknowns; physics-free).

    Attributes
    ----------
    lower : numpy.ndarray or None
        Lower bounds l, shape (n,), −inf where an unknown is unbounded; None: no bounds.
    row_scale : float or numpy.ndarray
        Merit weights D > 0 (scalar or shape (n,)): the scaled residual is ‖D Φ(z)‖₂, so D
        makes the rows' units commensurate.
    variable_scale : float or numpy.ndarray
        Unknowns' scales s > 0 (scalar or shape (n,)): a step's relative size is
        max |δz_i| / s_i.

    Methods
    -------
    residual(z)
        r(z), a float vector of shape (n,); non-finite entries mark z as outside the
        residual's domain (the line search then cuts the step).
    linearize(z, active)
        A function ``solve(rhs)`` returning J⁻¹ rhs for the Jacobian J of r at z with the
        rows of the boolean mask ``active`` (unknowns at their bound) replaced by the
        identity: solve returns rhs at those entries (the caller passes 0 there) and solves
        the free rows J_FF δz_F = rhs_F. Called once per iteration (one factorization;
        chord steps, :class:`NewtonOptions` ``chord_step``, reuse the last solve). A
        singular J may give non-finite values or raise (numpy's LinAlgError, SuperLU's
        RuntimeError, an ArithmeticError): Newton's step is then not finite.

    Optional hooks (looked up with ``getattr``):

    clip_step(z, dz)
        The Newton step dz with some unknowns' changes limited one by one (e.g. a
        logarithmic unknown's change per iteration, as a circuit simulator limits a
        junction's exponential), before ``step_limit`` and the line search. Absent: dz.
    step_limit(z, dz)
        The largest admissible α in (0, 1] along dz (e.g. one that keeps a spacing
        positive); the line search starts there. Absent: 1.
    noise(z)
        The round-off floor of the scaled residual ‖D r(z)‖ at z (e.g. machine ε times the
        scaled magnitudes of the terms each row sums), a number, or of each scaled row,
        |D_i r_i(z)|, a vector of shape (n,). Near it the merit cannot guide a line
        search: steps are taken whole, and a small whole step there has converged
        (:class:`NewtonOptions` ``round_off_multiple``, ``round_off_step``). Given per
        row, a whole step there also converges when every free row lies within
        ``round_off_multiple`` of its own floor (the norm alone can hide a residual far
        above the floor of most rows under the round-off of a few) and the step is within
        ``noise_step_multiple`` of the step the rows' round-off alone produces (with
        fixed pseudo-random signs, through the step's factorization) and below one
        variable scale (a step as large as an unknown's own scale has not converged,
        whatever the noise): on a badly
        conditioned system (a fourth-order operator on cells far finer than its length
        scale) round-off alone makes steps far above ``round_off_step`` in the unknowns
        the rows barely hold.
    """

    lower: np.ndarray | None
    row_scale: float | np.ndarray
    variable_scale: float | np.ndarray

    def residual(self, z: np.ndarray) -> np.ndarray: ...

    def linearize(self, z: np.ndarray,
                  active: np.ndarray) -> Callable[[np.ndarray], np.ndarray]: ...


@dataclass
class NewtonReport:
    """What :func:`newton` did, one entry per iteration in each list (a report passed to
    several solves adds their iterations up).

    Attributes
    ----------
    iterations : int
        Newton iterations (steps taken).
    step_norms : list of float
        Relative size of each step taken, α max |δz_i| / variable_scale_i.
    residual_norms : list of float
        Scaled residual ‖D Φ(z)‖ after each step.
    active_counts : list of int
        Unknowns held at their bound during each step (the active set's size).
    alphas : list of float
        Line-search factor α of each step (1: the whole Newton step).
    factorizations : int
        Calls of the problem's ``linearize`` (fewer than the iterations with chord steps).
    seconds : float
        Wall time, s.
    converged : bool
        Whether the (last) solve converged.
    reason : str
        Why the (last) solve stopped: "step", "residual" or "round-off" (converged), or
        "max_iterations", "stagnation", "non-finite" (failed); "" before any solve.
    """

    iterations: int = 0
    step_norms: list = field(default_factory=list)
    residual_norms: list = field(default_factory=list)
    active_counts: list = field(default_factory=list)
    alphas: list = field(default_factory=list)
    factorizations: int = 0
    seconds: float = 0.0
    converged: bool = False
    reason: str = ""


@dataclass
class _Iterate:
    """An iterate: z, its residual r, active set, scaled residual ‖DΦ‖ and floor flag."""

    z: np.ndarray
    r: np.ndarray
    active: np.ndarray
    norm: float
    at_floor: bool = False
    #: the rows' round-off floors (unscaled, shape (n,)) of a per-row ``noise`` hook
    floor_rows: np.ndarray | None = None


class _Setup:
    """The problem's bounds and scales checked against its size n, and the iterate maps."""

    def __init__(self, problem: NewtonProblem, n: int, options: NewtonOptions) -> None:
        self.problem, self.options, self.n = problem, options, n
        self.lower = _lower_bounds(problem.lower, n)
        self.row_scale = _scale("problem.row_scale", problem.row_scale, n)
        self.variable_scale = _scale("problem.variable_scale", problem.variable_scale, n)
        self.band = options.bound_tol * self.variable_scale
        self.step_limit = getattr(problem, "step_limit", None)
        self.noise = getattr(problem, "noise", None)

    def residual(self, z: np.ndarray) -> np.ndarray:
        """r(z) as floats (overflow and invalid operations give non-finite entries)."""
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            try:
                r = np.asarray(self.problem.residual(z), dtype=float)
            except ArithmeticError:
                return np.full(self.n, np.nan)
        if r.shape != (self.n,):
            raise ParameterError(f"problem.residual must return a vector of length {self.n}, "
                                 f"got shape {r.shape}")
        return r

    def iterate(self, z: np.ndarray) -> _Iterate:
        """z with its residual, active set and scaled reduced residual."""
        r = self.residual(z)
        if self.lower is None:
            active = np.zeros(self.n, dtype=bool)
        else:
            active = (z <= self.lower + self.band) & (r > 0.0)
        with np.errstate(over="ignore", invalid="ignore"):
            phi = np.where(active, 0.0, r) * self.row_scale
            norm = float(np.linalg.norm(phi))
        return _Iterate(z, r, active, norm if math.isfinite(norm) else math.inf)

    def accept(self, it: _Iterate) -> _Iterate:
        """The iterate taken, marked if it lies at the problem's round-off floor (the
        ``noise`` hook, called once per iteration, not per trial)."""
        if self.noise is not None:
            floor = np.asarray(self.noise(it.z), dtype=float)
            multiple = self.options.round_off_multiple
            if floor.ndim:
                it.floor_rows = floor / self.row_scale
                floor = np.linalg.norm(floor)
            it.at_floor = it.norm <= multiple * float(floor)
        return it

    def noise_step(self, it: _Iterate, solve) -> tuple[float, bool]:
        """The step that the rows' round-off at ``it`` alone produces through ``solve``
        (fixed pseudo-random signs): its relative size, and whether every free row's
        scaled residual lies within ``round_off_multiple`` of its own floor plus
        ``noise_step_multiple`` times the change that step makes in it (the round-off a
        badly conditioned solve spreads from a few rows to all: a row the step moves by
        more than its own floor cannot be brought below that). (0, False) without
        per-row floors."""
        if it.floor_rows is None:
            return 0.0, False
        signs = np.random.default_rng(0).choice((-1.0, 1.0), size=self.n)
        rhs = np.where(it.active, 0.0, signs * it.floor_rows)
        with np.errstate(all="ignore"):
            dz = np.asarray(solve(rhs), dtype=float)
            step = self.relative(dz)
            if not math.isfinite(step):
                return 0.0, False
            moved = np.abs(self.residual(self.project(it.z + dz, it.active)) - it.r)
        options = self.options
        free = ~it.active
        allowed = (options.round_off_multiple * it.floor_rows
                   + options.noise_step_multiple * moved)
        rows = bool(np.all(np.abs(it.r[free]) <= allowed[free]))
        return step, rows

    def project(self, z: np.ndarray, active: np.ndarray) -> np.ndarray:
        """z onto z >= l, the unknowns of ``active`` exactly at their bound."""
        if self.lower is None:
            return z
        z = np.maximum(z, self.lower)
        z[active] = self.lower[active]
        return z

    def relative(self, dz: np.ndarray) -> float:
        """The relative size max |δz_i| / s_i of a step."""
        return float(np.max(np.abs(dz) / self.variable_scale, initial=0.0))


def _lower_bounds(lower, n: int) -> np.ndarray | None:
    """The lower bounds as a float vector of length n (−inf allowed), or None."""
    if lower is None:
        return None
    out = np.array(lower, dtype=float)
    if out.shape != (n,):
        raise ParameterError(f"problem.lower must be None or a vector of length {n}, "
                             f"got shape {out.shape}")
    if np.any(np.isnan(out) | (out == np.inf)):
        raise ParameterError("problem.lower must be finite or -inf, got NaN or +inf entries")
    return None if np.all(out == -np.inf) else out


def _scale(name: str, value, n: int) -> np.ndarray:
    """A positive finite scale (scalar or length n) as a vector of length n."""
    out = np.array(value, dtype=float)
    if out.ndim == 0:
        out = np.full(n, float(out))
    if out.shape != (n,):
        raise ParameterError(f"{name} must be a number or a vector of length {n}, "
                             f"got shape {out.shape}")
    if not np.all(np.isfinite(out) & (out > 0.0)):
        raise ParameterError(f"{name} must be > 0 and finite, got min {np.min(out):g}")
    return out


def _failure(message: str, report: NewtonReport, state: np.ndarray,
             reason: str) -> ConvergenceError:
    """A ConvergenceError carrying the report (``.report``) and last iterate (``.state``)."""
    report.converged, report.reason = False, reason
    exc = ConvergenceError(message)
    exc.report, exc.state = report, state
    return exc


def _reached(report: NewtonReport, it: _Iterate) -> str:
    """What the solve reached: iterations, last step and α, scaled residual, active count."""
    last = (f"last relative step {report.step_norms[-1]:.3g} (alpha {report.alphas[-1]:.3g}), "
            if report.step_norms else "")
    return (f"{report.iterations} iterations, {last}scaled residual {it.norm:.3g}, "
            f"{int(it.active.sum())} of {it.z.size} unknowns at their bound")


def _substituted(setup: _Setup, it: _Iterate, solve, active: np.ndarray | None = None
                 ) -> np.ndarray | None:
    """``solve`` applied to the right-hand side of the active set ``active`` (default the
    iterate's): −r_F on the free rows, l − z on the held ones (0 for the iterate's own set,
    whose unknowns sit at their bounds); None if it is singular or not finite."""
    active = it.active if active is None else active
    held = 0.0 if setup.lower is None else setup.lower - it.z
    rhs = np.where(active, held, -it.r)
    with np.errstate(all="ignore"):
        try:
            dz = np.asarray(solve(rhs), dtype=float)
        except ConvergenceError:
            raise
        except (ArithmeticError, np.linalg.LinAlgError, RuntimeError):  # singular: SuperLU's
            return None                                                  # is a RuntimeError
    if dz.shape != (setup.n,) or not np.all(np.isfinite(dz)):
        return None
    dz[active] = rhs[active]
    return dz


def _clipped(setup: _Setup, it: _Iterate, dz: np.ndarray) -> np.ndarray:
    """dz through the problem's ``clip_step`` hook, if it has one."""
    clip = getattr(setup.problem, "clip_step", None)
    return dz if clip is None else np.asarray(clip(it.z, dz), dtype=float)


def _factored_step(setup: _Setup, it: _Iterate, active: np.ndarray, report: NewtonReport):
    """(the Newton step with the active set ``active``, its unknowns moved to their
    bounds, by a new factorization; that factorization's solve)."""
    report.factorizations += 1
    with np.errstate(all="ignore"):
        try:
            solve = setup.problem.linearize(it.z, active)
        except ConvergenceError:
            raise
        except (ArithmeticError, np.linalg.LinAlgError, RuntimeError):
            solve = None
    dz = None if solve is None else _substituted(setup, it, solve, active)
    if dz is None:
        raise _failure(f"Newton's step is not finite ({_reached(report, it)}): the Jacobian "
                       "is singular or not finite there; check the problem's linearize, or "
                       "start elsewhere", report, it.z, "non-finite")
    return _clipped(setup, it, dz), solve


class _Chord:
    """The last factorization, reused for chord steps (:class:`NewtonOptions`
    ``chord_step``) while the last whole step was small and a chord step contracts."""

    def __init__(self, options: NewtonOptions) -> None:
        self.options = options
        self.solve, self.active, self.last = None, None, math.inf
        #: whether the last step was a chord step (its error contracts linearly only)
        self.used = False

    def direction(self, setup: _Setup, it: _Iterate, report: NewtonReport):
        """(a chord step if it qualifies, else the reduced Newton step, which factors;
        the factorization's solve)."""
        options = self.options
        self.used = False
        if (self.solve is not None and self.last < options.chord_step
                and np.array_equal(it.active, self.active)):
            dz = _substituted(setup, it, self.solve)
            if dz is not None and setup.relative(dz) <= options.chord_contraction * self.last:
                self.used = True
                return _clipped(setup, it, dz), self.solve
        self.solve = None                   # freed before the next factorization
        dz, self.solve = _factored_step(setup, it, it.active, report)
        self.active = it.active.copy()
        return dz, self.solve

    def taken(self, alpha: float, step: float, reduced: bool) -> None:
        """Record the step taken: only a whole reduced step qualifies the next for a chord
        step (``reduced``: the step of the iterate's own active set)."""
        self.last = step if alpha == 1.0 and reduced else math.inf


def _step(setup: _Setup, it: _Iterate, report: NewtonReport, chord: _Chord,
          reference: float, stalling: bool):
    """One iteration's step: the reduced step (or a chord step) line-searched; if the
    problem's ``clip_step`` changed it and the search cut it below
    :data:`UNCLIPPED_ALPHA`, the unclipped step too (:func:`_unclipped`), the one reaching
    the lower merit taken; if the
    projected path stalls (this step and the last, if any, slow: ``stalling`` for the
    last, :func:`_slow`) and the step takes free unknowns through their bounds, also the
    step of the linearized problem's own active set (:func:`_set_step`), line-searched,
    the one reaching the lower merit taken. Returns (α, new iterate, relative step, the
    step's active set, the factorization's solve)."""
    options = setup.options
    dz, solve = chord.direction(setup, it, report)
    step = setup.relative(dz)
    alpha, new = _line_search(setup, it, dz, step, report, reference, it.active)
    if alpha < UNCLIPPED_ALPHA and not chord.used:
        raw = _unclipped(setup, it, solve, dz)
        if raw is not None:
            step_raw = setup.relative(raw)
            try:
                alpha_raw, new_raw = _line_search(setup, it, raw, step_raw, report,
                                                  reference, it.active)
            except ConvergenceError:        # no finite residual along it
                new_raw = None
            if new_raw is not None and new_raw.norm < new.norm:
                alpha, new, dz, step = alpha_raw, new_raw, raw, step_raw
    stalled = stalling and _slow(options, alpha, new.norm, it.norm)
    if not stalled or chord.used or setup.lower is None or options.max_set_updates == 0:
        return alpha, new, step, it.active, solve
    other = _set_step(setup, it, dz, report)
    if other is None:
        return alpha, new, step, it.active, solve
    dz_set, active, solve_set = other
    step_set = setup.relative(dz_set)
    alpha_set, new_set = _line_search(setup, it, dz_set, step_set, report, reference,
                                      active)
    if new_set.norm < new.norm:
        return alpha_set, new_set, step_set, active, solve_set
    return alpha, new, step, it.active, solve


def _unclipped(setup: _Setup, it: _Iterate, solve, dz: np.ndarray) -> np.ndarray | None:
    """The reduced step of ``solve`` without the problem's ``clip_step`` hook, if that
    hook changed ``dz`` (else None). Clipped unknown by unknown, a step is no longer
    Newton's and need not be a descent direction of the merit: where the clip took many
    unknowns (a film's log-pressures, 54 nodes over a wrapped arc), every trial along it
    raised the merit and the search cut α to its floor, while the whole step, cut by the
    problem's ``step_limit``, descended (the merit 41.4 → 33.9 at α = 0.08)."""
    if getattr(setup.problem, "clip_step", None) is None or solve is None:
        return None
    raw = _substituted(setup, it, solve)
    if raw is None or np.array_equal(raw, dz):
        return None
    return raw


def _slow(options: NewtonOptions, alpha: float, norm: float, before: float) -> bool:
    """Whether a step made slow progress: damped below ``stagnation_alpha``, or whole
    without halving the scaled residual (``before`` → ``norm``)."""
    return alpha < options.stagnation_alpha or (alpha == 1.0 and norm > 0.5 * before)


def _set_step(setup: _Setup, it: _Iterate, dz: np.ndarray, report: NewtonReport):
    """The step whose active set is consistent with its own linearization, if the
    reduced step ``dz`` takes free unknowns through their bounds: the primal–dual
    active-set method on the linearized problem (Hintermüller, Ito and Kunisch 2002).
    With the set A, δz_A = l_A − z_A and J_FF δz_F = −r_F − J_FA δz_A; the next set holds
    the free unknowns the step takes below their bounds and the unknowns of A whose
    residual at z + δz (their bound's force, exact where those rows are linear) stays
    positive. Repeated until the set repeats: a contact zone then grows or shrinks by many
    unknowns per iteration, where the projected path alone moves it by the few a damped
    step reaches. At most ``max_set_updates`` factorizations (the rule may shrink an
    overshooting zone by one unknown per end and update: the last set's step is then
    taken). Returns (δz, its set, its factorization's solve), or None if the reduced
    step crosses no bound."""
    lower, active, solve = setup.lower, it.active, None
    if not np.any(~active & (it.z + dz < lower)):
        return None
    for _ in range(setup.options.max_set_updates):
        z1 = it.z + dz
        with np.errstate(all="ignore"):
            r1 = setup.residual(z1)
        if not np.all(np.isfinite(r1[active])):
            break
        nxt = (active & (r1 > 0.0)) | (~active & (z1 < lower))
        if np.array_equal(nxt, active):
            break
        active = nxt
        dz, solve = _factored_step(setup, it, active, report)
    return None if solve is None else (dz, active, solve)


def _first_alpha(setup: _Setup, it: _Iterate, dz: np.ndarray) -> float:
    """The largest admissible α: 1, or the problem's ``step_limit`` if smaller."""
    if setup.step_limit is None:
        return 1.0
    alpha = float(setup.step_limit(it.z, dz))
    if not alpha > 0.0:
        raise ParameterError(f"problem.step_limit must return a number > 0, got {alpha}")
    return min(alpha, 1.0)


def _line_search(setup: _Setup, it: _Iterate, dz: np.ndarray, step: float,
                 report: NewtonReport, reference: float,
                 active: np.ndarray) -> tuple[float, _Iterate]:
    """Backtracking from the largest admissible α along the projected path, against the
    scaled residual ``reference`` (the largest of the last ``memory``); the whole step when
    it is small or the iterate is at its round-off floor. ``active``: the step's active
    set (the iterate's unknowns in it stay at their bounds). Returns (α, new iterate)."""
    options = setup.options
    alpha = _first_alpha(setup, it, dz)
    # at the floor the merit cannot judge a step, but a step of more than one variable
    # scale is no round-off: the line search judges it
    whole = step <= options.full_step or (it.at_floor and step <= 1.0)
    held = it.active & active
    while True:
        trial = setup.iterate(setup.project(it.z + alpha * dz, held))
        finite = math.isfinite(trial.norm)
        decrease = trial.norm**2 <= reference**2 - 2.0 * options.armijo * alpha * it.norm**2
        last = alpha * options.backtrack < options.min_step
        if finite and (whole or decrease or last):
            return alpha, trial
        if last:
            raise _failure(f"Newton's line search found no finite residual down to alpha "
                           f"{alpha:.3g} ({_reached(report, it)}): the step leaves the "
                           "residual's domain; give the problem a step_limit, or start "
                           "elsewhere", report, it.z, "non-finite")
        alpha *= options.backtrack


def _record(report: NewtonReport, alpha: float, step: float, it: _Iterate,
            active_count: int, log) -> None:
    """Append one iteration to the report (and log it)."""
    report.iterations += 1
    report.step_norms.append(alpha * step)
    report.residual_norms.append(it.norm)
    report.active_counts.append(active_count)
    report.alphas.append(alpha)
    if log is not None:
        log(f"Newton {report.iterations}: step {alpha * step:.2e} (alpha {alpha:.3g}), "
            f"scaled residual {it.norm:.2e}, {active_count} at their bound")


def _converged(setup: _Setup, alpha: float, step: float, it: _Iterate, solve,
               chord: bool = False) -> str:
    """Why the iterate after a step of relative size ``step`` (by the factorization
    ``solve``) has converged, or "". A chord step (``chord``) converges by the tolerance
    alone: its error contracts only linearly, so a step at the round-off floor leaves an
    error of its own size."""
    options = setup.options
    if alpha == 1.0 and step <= options.tol:
        return "step"
    if options.residual_tol is not None and it.norm <= options.residual_tol:
        return "residual"
    if alpha == 1.0 and it.at_floor and not chord:
        if step <= options.round_off_step:
            return "round-off"
        noise, rows = setup.noise_step(it, solve)
        if rows and step <= min(1.0, options.noise_step_multiple * noise):
            return "round-off"
    return ""


def _stagnated(options: NewtonOptions, norms: list, alphas: list) -> bool:
    """Whether the scaled residual has not halved over the last ``stagnation_window``
    iterations, all damped below ``stagnation_alpha``."""
    window = options.stagnation_window
    return (len(alphas) >= window and norms[-1] > 0.5 * norms[-1 - window]
            and max(alphas[-window:]) < options.stagnation_alpha)


def _start(problem: NewtonProblem, z0, options: NewtonOptions) -> tuple[_Setup, _Iterate]:
    """The checked problem and the first iterate (z0 projected onto its bounds)."""
    z = np.array(z0, dtype=float)
    if z.ndim != 1 or z.size == 0:
        raise ParameterError(f"z0 must be a non-empty vector, got shape {z.shape}")
    z = validation.vector("z0", z, z.size)
    setup = _Setup(problem, z.size, options)
    it = setup.iterate(setup.project(z, np.zeros(z.size, dtype=bool)))
    if not math.isfinite(it.norm):
        raise ParameterError("z0 must give a finite residual, got "
                             f"{int(np.count_nonzero(~np.isfinite(it.r)))} non-finite entries")
    return setup, setup.accept(it)


def _solve(setup: _Setup, it: _Iterate, report: NewtonReport, log) -> np.ndarray:
    """Newton's iterations from the iterate ``it``; returns the solution."""
    options = setup.options
    if options.residual_tol is not None and it.norm <= options.residual_tol:
        report.converged, report.reason = True, "residual"
        return it.z
    norms, alphas = [it.norm], []
    chord = _Chord(options)
    for _ in range(options.max_iterations):
        reference = max(norms[-options.memory:])
        stalling = not alphas or _slow(options, alphas[-1], norms[-1], norms[-2])
        alpha, new, step, active, solve = _step(setup, it, report, chord, reference,
                                                stalling)
        chord.taken(alpha, step, active is it.active)
        _record(report, alpha, step, new, int(active.sum()), log)
        it = setup.accept(new)
        reason = _converged(setup, alpha, step, it, solve, chord.used)
        if reason:
            report.converged, report.reason = True, reason
            return it.z
        norms.append(it.norm)
        alphas.append(alpha)
        if _stagnated(options, norms, alphas):
            raise _failure(
                f"Newton stagnated ({_reached(report, it)}): the scaled residual did not "
                f"halve in {options.stagnation_window} damped iterations (alpha < "
                f"{options.stagnation_alpha:g}); the start is outside Newton's basin or "
                "there is no solution nearby: try continuation (pseudo-time or in a "
                "parameter, gyroshell.linalg.continuation) or another start",
                report, it.z, "stagnation")
    raise _failure(f"Newton did not converge in {options.max_iterations} iterations "
                   f"({_reached(report, it)}): try a start nearer the solution "
                   "(continuation), more iterations (max_iterations) or a looser tol",
                   report, it.z, "max_iterations")


def newton(problem: NewtonProblem, z0, options: NewtonOptions | None = None, *, log=None,
           report: NewtonReport | None = None) -> tuple[np.ndarray, NewtonReport]:
    """Solve the bound-constrained system of ``problem`` from z0 by reduced-space
    active-set Newton with a projected Armijo line search (see the module docstring).

    Parameters
    ----------
    problem : NewtonProblem
        Residual, reduced linearization, bounds and scales (:class:`NewtonProblem`).
    z0 : array_like
        The start, shape (n,); projected onto the bounds.
    options : NewtonOptions, optional
        Tolerances and line-search constants (default: ``NewtonOptions()``).
    log : callable, optional
        Called with a one-line message per iteration.
    report : NewtonReport, optional
        A report to add this solve's iterations to (e.g. one per continuation path).

    Returns
    -------
    z : numpy.ndarray
        The solution, shape (n,), z >= lower.
    report : NewtonReport
        Every iteration: steps, scaled residuals, active counts, α; ``converged`` True.

    Raises
    ------
    ConvergenceError
        After ``max_iterations``, on a stagnation or on a non-finite step; its ``report``
        attribute holds the report and ``state`` the last iterate.
    ParameterError
        If the options, the problem's bounds or scales, or z0 are invalid.

    Examples
    --------
    arctan(z) = 0 from z = 3, where the whole Newton step overshoots to −9.5 and beyond:

    >>> class Arctan:
    ...     lower, row_scale, variable_scale = None, 1.0, 1.0
    ...     def residual(self, z):
    ...         return np.arctan(z)
    ...     def linearize(self, z, active):
    ...         return lambda rhs: np.where(active, rhs, rhs * (1.0 + z**2))
    >>> z, report = newton(Arctan(), [3.0])
    >>> float(abs(z[0])) < 1e-12, report.converged, report.alphas[0]
    (True, True, 0.25)
    """
    options = NewtonOptions() if options is None else validation.instance(
        "options", options, NewtonOptions)
    report = NewtonReport() if report is None else report
    clock = time.perf_counter()
    try:
        setup, it = _start(problem, z0, options)
        return _solve(setup, it, report, log), report
    finally:
        report.seconds += time.perf_counter() - clock
