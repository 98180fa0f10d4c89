"""Steady states under a smooth contact law (asperities or a measured compliance curve).

A smooth law p_c(h) acts on every tape node near the head (:meth:`.model.BearingModel.
asperity_force`): no contact set, no wall, and one problem (:class:`.problem.
SteadyProblem`) solved by one generic Newton (:func:`gyroshell.linalg.newton.newton`).
What remains is the start. Four paths are tried in turn, within one budget of Newton
iterations (:class:`SolverOptions`), every iteration counted in the solution's
:class:`~.results.NewtonInfo`:

1. **Direct**: Newton from the flying start (:func:`flying_start`: the flexible-foil or
   corner start, tapered to the pinned ends; a 2-D tape from its state on coarser grids,
   :func:`coarse_start`), then from the tape resting on its summits
   (:func:`resting_start`: over rounded corners, whose arcs the tape lies on, the flying
   start's film is far from the state).
2. **The speed**: the dry tape on its asperities (:func:`dry_state`, the same grid
   without the film), continued in V up from 3e-4 of the speed.
3. **The start grid** (a flat head, the infinitely wide tape): the steady state on the
   grid refined only at the corners the tape turns over (:func:`turned_corner_scales`),
   by these same paths there, interpolated, then Newton on the model's own grid (whose
   answer it is). The model's grid resolves every corner to 15 nm; under a tent
   ballooned tens of µm over a long land those cells carry only round-off.
4. **The law's scale**: the hard wall's state at the roughness σ_s (:func:`hard_wall_state`,
   the law's limit σ_s → 0, solved by the same Newton with the wall as bounds) continued
   along the law scaled by s, s p_c(h), from s = 100 (a stiff wall a few σ_s above) down
   to s = 1 (:func:`gyroshell.linalg.continuation.continuation`).

The first is cheap where it works (tens of iterations); the second follows the tape's own
path as the film builds up under it, through the collapse of the land's tents onto their
asperities at low speed (contact recording), and lifts a tent sealed by pressed corners
(designs 7 and 16 of benchmarks/bench_design_set.py, 3 s); the third solves a better
conditioned problem first (16 from a first speed of 1e-3 V: 5 s); the fourth starts from
where the wall puts the tape. Every path is bounded by the budget: a
design none of them reaches stops with a ConvergenceError naming each path's failure.
"""

from __future__ import annotations

import copy
import time
import warnings
from dataclasses import dataclass, replace

import numpy as np

from ..core import validation
from ..core.errors import ConvergenceError, ParameterError
from ..linalg.continuation import StepController, continuation
from ..linalg.newton import NewtonOptions, NewtonReport, newton
from ..tape.parameters import MIN_INTERVALS_ACROSS
from .film import DryFilm
from .model import MIN_INTERVALS_ALONG, BearingGridWarning, BearingModel
from .problem import SteadyProblem, check_cavitation
from .results import BearingSolution, NewtonInfo

#: A state whose scaled residual is at its round-off floor has converged once its full
#: step is below this fraction of the spacing scale (σ_s, or the foil spacing): 1 % of
#: σ_s is 0.06 nm, far below any reading's accuracy, while the plate's rows on the
#: corners' fine cells turn round-off into steps of 1e-3 σ_s and more (measured on the dry
#: tape over a 2.9 mm land: steps of 2e-4 to 1e-2 σ_s at a residual of 0.2 of its floor).
ROUND_OFF_STEP = 1e-2
#: The hard wall's: its grid is not refined to the roughness, and a step of 1e-2 of the
#: spacing scale there is a state 1e-6 off (the flux of a 1-D film balanced to 1e-5
#: instead of 1e-8).
WALL_ROUND_OFF_STEP = 1e-4


def round_off_step(model: BearingModel) -> float:
    """The relative step at the residual's round-off floor that has converged."""
    return ROUND_OFF_STEP if model.smooth_contact else WALL_ROUND_OFF_STEP

#: A 2-D grid's Newton reuses its factorization (chord steps) after whole steps below
#: this relative size while each chord step shrinks the step 4x: its LU costs tens of
#: residuals (the 12.65 mm tape's cylinder: 3 factorizations of 114,552 unknowns at 0.7 s
#: each against a residual's 0.05 s). The infinitely wide tape's banded LU costs less
#: than its residual: it factors every iteration.
CHORD_STEP_2D = 0.5


@dataclass(frozen=True)
class SolverOptions:
    """The one set of options of the steady solve under a smooth contact law.

    Parameters
    ----------
    tol : float
        Relative Newton step at which a solve has converged (of the spacing scale, m,
        and the wrap pressure, Pa).
    max_iterations : int
        Newton iterations of the direct path from the flying start (and of the dry and
        hard-wall starts): a run that still halves its residual every ten iterations may
        take them all (measured on the design set: 7-49), one that does not stops earlier
        (Newton's stagnation test).
    resting_iterations : int
        Newton iterations from the resting start (the same rule; measured: 20-50).
    stage_iterations : int
        Newton iterations of one continuation stage.
    budget : int
        Newton iterations of the whole solve, every path and stage together, those of
        a 2-D tape's start on coarser grids (and of its strip) included: a solve that has
        not converged within it stops with a ConvergenceError.
    law_scale : float
        The law's scale at the first stage of the law's continuation (> 1).
    pseudo_time_tol : float
        The tolerance of a pseudo-time stage (:mod:`.pseudo_time`), in (0, 1).
    chord_step : float
        A 2-D tape, whose factorization costs many residuals, reuses its last one (a
        chord step, :class:`gyroshell.linalg.newton.NewtonOptions`) after a whole step
        below this relative size (>= 0; 0: never; :data:`CHORD_STEP_2D`); the infinitely
        wide tape factors every iteration.
    speed_fraction : float
        The first speed of the continuation in V, as a fraction of V, in (0, 1). Measured
        on designs 7 and 16 of benchmarks/bench_design_set.py and their neighbours (40 in
        all: V ±1 %, ±5 %, T +2 %, inputs at full precision and rounded to 5 digits): all
        40 reached from 3e-4 (and from 1e-4), 36 from 1e-3, where the first stage, 16's
        sealed tent, stagnated on four.
    """

    tol: float = 1e-8
    max_iterations: int = 200
    resting_iterations: int = 200
    stage_iterations: int = 25
    budget: int = 500
    law_scale: float = 100.0
    speed_fraction: float = 3e-4
    pseudo_time_tol: float = 1e-4
    chord_step: float = CHORD_STEP_2D

    def __post_init__(self) -> None:
        put = object.__setattr__
        put(self, "tol", validation.real("tol", self.tol, low=0.0, high=1.0, low_open=True))
        for name in ("max_iterations", "resting_iterations", "stage_iterations", "budget"):
            put(self, name, validation.integer(name, getattr(self, name), low=1))
        put(self, "law_scale", validation.real("law_scale", self.law_scale, low=1.0,
                                               low_open=True))
        put(self, "chord_step", validation.nonnegative("chord_step", self.chord_step))
        put(self, "pseudo_time_tol", validation.real(
            "pseudo_time_tol", self.pseudo_time_tol, low=0.0, high=1.0, low_open=True,
            high_open=True))
        put(self, "speed_fraction", validation.real(
            "speed_fraction", self.speed_fraction, low=0.0, high=1.0, low_open=True,
            high_open=True))


class _Budget:
    """The Newton iterations left, and the record every solve adds to."""

    def __init__(self, options: SolverOptions, info: NewtonInfo, log) -> None:
        self.options, self.info, self.log = options, info, log

    @property
    def left(self) -> int:
        return self.options.budget - self.info.iterations - self.info.start_iterations

    def solve(self, model: BearingModel, z0: np.ndarray, limit: int, *, tension=None
              ) -> np.ndarray:
        """Newton on ``model`` from z0, at most ``limit`` iterations (and what is left);
        each iteration recorded in the NewtonInfo."""
        return self.solve_reporting(model, z0, limit, tension=tension)[0]

    def solve_reporting(self, model: BearingModel, z0: np.ndarray, limit: int, *,
                        tension=None, transient=None, tol=None
                        ) -> tuple[np.ndarray, NewtonReport]:
        """:meth:`solve` and its Newton report (a continuation stage's); ``transient``:
        a (pseudo-)time step's terms, ``tol``: in place of the options' tolerance."""
        limit = min(limit, self.left)
        if limit < 1:
            raise ConvergenceError(f"the budget of {self.options.budget} Newton iterations "
                                   "is spent")
        report = NewtonReport()
        options = NewtonOptions(tol=self.options.tol if tol is None else tol,
                                max_iterations=limit,
                                round_off_step=round_off_step(model),
                                chord_step=0.0 if model.infinitely_wide
                                else self.options.chord_step)
        problem = SteadyProblem(model, tension=tension, transient=transient)
        try:
            z, report = newton(problem, problem.unknowns(z0), options, report=report,
                               log=self.log)
        except ConvergenceError as exc:
            if getattr(exc, "state", None) is not None:
                exc.state = problem.state(exc.state)
            raise
        finally:
            self._record(model, report)
        return problem.state(z), report

    def _record(self, model: BearingModel, report: NewtonReport) -> None:
        info = self.info
        info.iterations += report.iterations
        info.step_norms += report.step_norms
        info.residual_norms += report.residual_norms
        info.contact_nodes += report.active_counts


def newton_step(model: BearingModel, z0: np.ndarray, *, tension=None, transient=None,
                max_iterations: int = 40) -> tuple[np.ndarray, np.ndarray, int]:
    """One Newton solve of ``model``'s equations under its smooth law from the state z0
    ([u (m), p (Pa)]), with a time step's ``transient`` terms (a march's step):
    (state, contact forces in N or N/m, iterations). Raises ConvergenceError."""
    problem = SteadyProblem(model, tension=tension, transient=transient)
    options = NewtonOptions(max_iterations=max_iterations,
                            round_off_step=round_off_step(model))
    z, report = newton(problem, problem.unknowns(z0), options)
    z = problem.state(z)
    return z, problem.forces(z), report.iterations


def resting_start(model: BearingModel) -> np.ndarray:
    """[u, p_a]: the dry string lifted to h_eq wherever it is nearer the head, h_eq the
    spacing at which the law carries the wrap pressure (T − ρV²)/R_c of the sharpest
    corner's radius R_c (m): the tape resting on its summits as over a cylinder."""
    from scipy.optimize import brentq

    law, sigma = model.contact_law, model.air.roughness
    target = model.effective_tension() / model.scale_radius
    h_eq = brentq(lambda h: law.pressure(h)[0] - target, -50.0 * sigma, 60.0 * sigma,
                  xtol=1e-3 * sigma)
    w0 = model.dry_field[1:-1, :].ravel()
    u = np.maximum(w0, h_eq) - w0
    return np.concatenate([u, np.full(model.n_p, model.air.ambient_pressure)])


def flying_start(model: BearingModel) -> np.ndarray:
    """The model's own start (:meth:`BearingModel.initial_state`) with u tapered to 0
    over the outer half of each span (C¹): u = 0 at the pinned ends, where the start's
    spacing above the dry gap would otherwise kink the tape; dry, :func:`resting_start`.
    The sharp corners and the rounded arcs the tape touches at about a point
    (:attr:`BearingModel.touching_arcs`) start at σ_s, the film's constriction rising
    from them (:meth:`BearingModel._corner_start`): left at the flying spacing, a touching
    arc's linearized law carries nothing and Newton's step sinks the tape microns into it,
    cut to 1e-5 of itself by the step limit (designs 15 and 19 of the design set
    stagnated so; they now take 10 and 9 iterations)."""
    if model.dry:
        return resting_start(model)
    z = np.array(model.initial_state(), dtype=float)
    x = model.x[1:-1]
    t = np.clip(np.minimum(x, model.length - x) / (0.5 * model.span), 0.0, 1.0)
    z[:model.n_u] *= np.repeat(t * t * (3.0 - 2.0 * t), model.nc)
    return z


#: A 2-D tape of at least this many unknowns starts from its steady state on the grid
#: twice as coarse each way (:func:`coarse_start`, recursively), interpolated; a smaller
#: one (the coarsest grid) from the infinitely wide tape's state extruded across the width.
COARSE_MIN_UNKNOWNS = 20_000


def _coarser(model: BearingModel) -> BearingModel | None:
    """``model`` on the grid twice as coarse each way (even counts, the same mapping), or
    None if that grid is below the fewest intervals or refused (a graded grid too coarse
    for its refinements)."""
    nx = model.nx // 2 + (model.nx // 2) % 2
    ny = model.ny // 2 + (model.ny // 2) % 2
    if nx < MIN_INTERVALS_ALONG or ny < MIN_INTERVALS_ACROSS:
        return None
    with warnings.catch_warnings():     # a start leads Newton; it need not be accurate
        warnings.simplefilter("ignore", BearingGridWarning)
        try:
            return model.rebuilt(nx=nx, ny=ny)
        except ParameterError:
            return None


def extruded_strip(model: BearingModel, interpolate, tension=None, progress=None,
                   iteration_log=None, options=None) -> tuple[np.ndarray, int]:
    """(start [u (m), p (Pa)] of a 2-D ``model``, Newton iterations it took): the
    infinitely wide tape's steady state on the same x-grid (:func:`solve_smooth`),
    repeated across the width; the 2-D :func:`flying_start` if that solve fails."""
    strip = model.rebuilt(infinitely_wide=True, ny=None)
    if progress is not None:
        progress(f"start: solving the infinitely wide tape on the same x-grid "
                 f"({strip.unknowns} unknowns)")
    try:
        sol = solve_smooth(strip, None, tension, progress, iteration_log, options,
                           interpolate=interpolate)
    except (ConvergenceError, ParameterError) as exc:
        if progress is not None:
            progress(f"start: the infinitely wide tape not reached ({exc}): the flying "
                     "start")
        return flying_start(model), _taken(exc)
    return (extruded(model, strip, strip_state(strip, sol, interpolate)),
            sol.info.iterations + sol.info.start_iterations)


def strip_state(strip: BearingModel, sol: BearingSolution, interpolate) -> np.ndarray:
    """[u (m), p (Pa)] of the infinitely wide ``strip``'s solution ``sol`` on the strip's
    grid (``interpolate``-d from the grid it was solved on if another: its corners
    refined for a tape flying over them, :meth:`BearingModel.with_flown_corners`)."""
    if sol.model.nx == strip.nx and np.array_equal(sol.model.x, strip.x):
        return np.concatenate([sol.u, sol.p])
    return interpolate(strip, sol)


def extruded(model: BearingModel, strip: BearingModel, z1: np.ndarray) -> np.ndarray:
    """The state of the 2-D ``model`` with the infinitely wide ``strip``'s state ``z1``
    (on the same x-grid) repeated across the width."""
    u = np.repeat(z1[:strip.n_u], model.nc)
    P = np.repeat(strip.pressure_field(z1[strip.n_u:]), model.nc, axis=1)
    return np.concatenate([u, P[model.film.interior]])


def _spending(options: SolverOptions | None, taken: int) -> SolverOptions:
    """``options`` with ``taken`` Newton iterations spent of its budget (at least one
    left: a solve with none stops at its first): the start's coarser grids and the
    model's own grid share one budget."""
    options = SolverOptions() if options is None else options
    return replace(options, budget=max(options.budget - taken, 1))


def _taken(exc: ConvergenceError) -> int:
    """The Newton iterations of a failed :func:`solve_smooth` (its start's included)."""
    info = getattr(exc, "info", None)
    return 0 if info is None else info.iterations + info.start_iterations


def coarse_start(model: BearingModel, interpolate, tension=None, progress=None,
                 iteration_log=None, options=None) -> tuple[np.ndarray, int]:
    """(start [u (m), p (Pa)] of a 2-D ``model``, Newton iterations it took on the coarser
    grids): the steady state on the grid twice as coarse each way (:func:`solve_smooth`,
    itself started by this function), interpolated by ``interpolate``
    (:func:`.steady.interpolated_state`); below :data:`COARSE_MIN_UNKNOWNS` unknowns, or if
    that grid is refused or not solved, :func:`extruded_strip`.

    The coarse grids carry the 2-D state's edges and the film's leak across the width
    into the start. The strip alone is a poor start for Newton on a fine grid: its land's
    sub-ambient film (1 % of ambient between two modules) against ambient edges leaves
    Newton a step in ln p of thousands, cut to nothing by the step limit (measured: two
    1 mm modules on a 12.65 mm tape, 262,000 unknowns, stagnated at α 1e-4 to 1e-9; from
    the coarse grids it converged in 4 iterations). On the coarsest grid a failed direct
    path costs a few tenths of a second."""
    coarse = None if model.unknowns < COARSE_MIN_UNKNOWNS else _coarser(model)
    if coarse is None:
        return extruded_strip(model, interpolate, tension, progress, iteration_log, options)
    z, taken = coarse_start(coarse, interpolate, tension, progress, iteration_log, options)
    if progress is not None:
        progress(f"start: solving the coarse grid {coarse.nx} x {coarse.ny} "
                 f"({coarse.unknowns} unknowns)")
    try:
        sol = solve_smooth(coarse, z, tension, progress, iteration_log,
                           _spending(options, taken), interpolate=interpolate)
    except (ConvergenceError, ParameterError) as exc:   # ParameterError: a continuation
        if progress is not None:                         # stage's grid too coarse for it
            progress(f"start: the coarse grid not reached ({exc})")
        taken += _taken(exc)
        z, more = extruded_strip(model, interpolate, tension, progress, iteration_log,
                                 _spending(options, taken))
        return z, taken + more
    return interpolate(model, sol), taken + sol.info.iterations + sol.info.start_iterations


def without_film(model: BearingModel) -> BearingModel:
    """``model`` on the same grid with no film (p = p_a): the tape resting on the head's
    asperities at the model's T − ρV² (a shallow copy sharing grid and operators)."""
    out = copy.copy(model)
    out.film = DryFilm(model.nx, model.nc, np.diff(model.x),
                       None if model.infinitely_wide else np.diff(model.y), model.air,
                       model.velocity, roughness=model.air.roughness)
    out.dry = True
    out.jacobian_patterns = {}   # its film blocks are empty: not the film model's pattern
    return out


class _ScaledLaw:
    """A contact law times s (pressure and derivative)."""

    def __init__(self, law, scale: float) -> None:
        self.law, self.scale = law, scale

    def pressure(self, h):
        p, dp = self.law.pressure(h)
        return self.scale * p, self.scale * dp


def scaled_law(model: BearingModel, scale: float) -> BearingModel:
    """``model`` with its contact law multiplied by ``scale`` (a shallow copy)."""
    if scale == 1.0:
        return model
    out = copy.copy(model)
    out.contact_law = _ScaledLaw(model.contact_law, scale)
    return out


def dry_state(model: BearingModel, budget: _Budget, tension=None) -> np.ndarray:
    """[u, p_a]: the tape at rest on its asperities on ``model``'s grid, by Newton from
    the dry start with the sharp corners held at σ_s (:meth:`BearingModel.dry_start`),
    else (a smooth law) from :func:`resting_start`."""
    dry = without_film(model)
    try:
        return budget.solve(dry, dry.dry_start(), budget.options.max_iterations,
                            tension=tension)
    except ConvergenceError:
        if not model.smooth_contact:     # the wall has no resting spacing
            raise
        return budget.solve(dry, resting_start(dry), budget.options.max_iterations,
                            tension=tension)


def hard_wall_state(model: BearingModel, budget: _Budget, tension,
                    interpolated_state) -> np.ndarray:
    """[u, p] of the hard wall at the roughness σ_s on ``model``'s head (every rounded arc
    resolved, as the smooth law needs), by the same generic Newton with the wall as
    bounds (:class:`.problem.SteadyProblem`), from its flying start; interpolated onto
    ``model``'s grid by ``interpolated_state`` if its grid differs."""
    from .contact import ContactParameters
    from .results import BearingSolution

    hard = model.rebuilt(contact=ContactParameters(law="hard",
                                                   roughness=model.air.roughness),
                         arc_contact="wrapped")
    z = budget.solve(hard, flying_start(hard), budget.options.max_iterations,
                     tension=tension)
    if np.array_equal(hard.x, model.x) and hard.nc == model.nc:
        return z
    sol = BearingSolution(hard, z[:hard.n_u], z[hard.n_u:], np.zeros(hard.n_u),
                          NewtonInfo())
    return interpolated_state(model, sol)


def _law_path(model, budget, tension, progress, interpolate) -> np.ndarray:
    """Path 4: the hard wall's state (``interpolate``: a state onto another grid), then
    the law's scale from ``law_scale`` to 1."""
    if progress is not None:
        progress("start: the hard wall at the roughness")
    z = hard_wall_state(model, budget, tension, interpolate)

    def at(scale, state):
        if progress is not None:
            progress(f"contact law scaled by {scale:.3g}")
        return budget.solve_reporting(scaled_law(model, scale), state,
                                      budget.options.stage_iterations, tension=tension)

    z, stages = continuation(at, budget.options.law_scale, 1.0, z,
                             controller=StepController(initial=10.0, growth=1.0,
                                                       minimum=1.05, max_stages=40))
    budget.info.law_scales += [s for s, _ in stages]
    return z


def _speed_path(model, budget, tension, progress) -> np.ndarray:
    """Path 2: the dry tape on its asperities, then V up from ``speed_fraction`` V.

    The first stage is a solve from the dry state, not a step from a neighbouring
    solution: it has the direct path's ``max_iterations`` (Newton's stagnation test ends
    a hopeless one), the later stages ``stage_iterations``. A tent sealed at both ends by
    pressed corners is lifted by the film's pressure even at a thousandth of the speed
    (the leaks, not V, meter it): tens of µm from the dry tape's few, which took 26
    iterations on design 16 of benchmarks/bench_design_set.py (the last four
    quadratic)."""
    z = dry_state(model, budget, tension)
    options = budget.options
    v0 = model.velocity * options.speed_fraction

    def at(v, state):
        if progress is not None:
            progress(f"continuation in V: {v:.4g} m/s")
        try:
            stage = model if v == model.velocity else model.at_velocity(v)
        except ParameterError as exc:    # e.g. a grid too coarse for the slower film
            raise ConvergenceError(f"no model at {v:.4g} m/s: {exc}") from None
        limit = options.max_iterations if v == v0 else options.stage_iterations
        return budget.solve_reporting(stage, state, limit, tension=tension)

    z, stages = continuation(at, v0, model.velocity, z,
                             controller=StepController(initial=3.0, growth=1.5, cut=0.5,
                                                       minimum=1.01, max_stages=80))
    budget.info.continuation += [v for v, _ in stages]
    return z


def _pseudo_time_path(model, z0, budget, tension, progress) -> np.ndarray:
    """Pseudo-transient continuation from z0 (:mod:`.pseudo_time`)."""
    from .pseudo_time import pseudo_time_path

    def solve(transient, state, limit):
        return budget.solve_reporting(
            model, state, budget.options.max_iterations if limit is None else limit,
            tension=tension, transient=transient,
            tol=None if transient is None else budget.options.pseudo_time_tol)

    z, steps = pseudo_time_path(model, z0, solve, progress)
    budget.info.pseudo_time += steps
    return z


def turned_corner_scales(model: BearingModel) -> tuple[float | None, ...] | None:
    """The corner widths of the start grid of :func:`_start_grid_path` (the grading's
    ``corner_scales``: multiples of its ``corner_width``), one per corner of a flat head
    under a smooth law, from the length of the film's constriction where each corner is
    pressed; None where that grid is the model's own (another head, the hard wall, no
    corner refinement, or already a start grid):

    * a sharp corner the tape turns over: 1 (σ_s/α, :func:`.model.corner_grading`);
    * a rounded one: √(2 r_c s)/s, s the grading's spacing scale (``corner_width`` /
      CORNER_WIDTH, 2 σ_s under a smooth law): the head is smooth there, the gap growing
      as Δx²/(2 r_c) from its least over √(2 r_c s) (7 µm at r_c = 2 mm), not over s/α;
    * a corner the tape does not turn over (a module's edge into a gap between coplanar
      lands, turn 0): none (None). It carries no wrap load; the film may still pull the
      tape onto it (two coplanar modules at speed), which is why the model's own grid
      refines it.

    The model's grid resolves every corner to 15 nm whether the tape is near or not;
    where it hangs microns above (a tent ballooned over a long land, sealed by a pressed
    corner) those cells carry only round-off (the film's fluxes through 50 µm gaps over
    15 nm, the plate's rows), in which Newton's first steps wander."""
    from .head import FlatHead
    from .model import CORNER_WIDTH

    grading = model.grading
    if (not isinstance(model.head, FlatHead) or not model.smooth_contact
            or grading.corner_scales is not None or (grading.corner_ratio or 1.0) == 1.0
            or not grading.corner_width):
        return None
    spacing = grading.corner_width / CORNER_WIDTH
    radii = model.head.corner_radii()
    turns = model.head.corner_turns(model.head_radius)
    scales = tuple(None if t <= 0.0 else 1.0 if r == 0.0
                   else max(1.0, float(np.sqrt(2.0 * r / spacing)))
                   for r, t in zip(radii, turns, strict=True))
    return None if all(c == 1.0 for c in scales) else scales


def _start_grid_path(model, budget, tension, progress, iteration_log, interpolate,
                     scales) -> np.ndarray:
    """The steady state on the start grid (the corner refinement of
    :func:`turned_corner_scales`), by every path of :func:`solve_smooth` there within
    what is left of the budget, interpolated (``interpolate``) and Newton on the model's
    own grid: the model's grid, and so its answer, is unchanged."""
    from dataclasses import replace

    if progress is not None:
        progress("start: the grid refined only at the corners the tape turns over")
    with warnings.catch_warnings():     # a start leads Newton; it need not be accurate
        warnings.simplefilter("ignore", BearingGridWarning)
        try:
            start = model.rebuilt(grading=replace(model.grading, corner_scales=scales),
                                  nx=None)
        except ParameterError as exc:
            raise ConvergenceError(f"no start grid: {exc}") from None
    sol = _solve_elsewhere(start, budget, tension, progress, iteration_log, interpolate)
    budget.info.start_iterations += sol.info.iterations + sol.info.start_iterations
    return budget.solve(model, interpolate(model, sol), budget.options.max_iterations,
                        tension=tension)


def _solve_elsewhere(other: BearingModel, budget: _Budget, tension, progress,
                     iteration_log, interpolate) -> BearingSolution:
    """The steady state on ``other``, the model on another grid (a start grid,
    :func:`_start_grid_path`, or the corners refined for a tape flying over them,
    :func:`_flown_path`), by every path of :func:`solve_smooth` there from its own start,
    within what is left of the budget; a failure's iterations are booked as the start's
    (the caller books a success's)."""
    try:
        return solve_smooth(other, None, tension, progress, iteration_log,
                            _spending(budget.options, budget.options.budget - budget.left),
                            interpolate=interpolate)
    except ConvergenceError as exc:
        budget.info.start_iterations += _taken(exc)
        raise ConvergenceError(f"not reached on that grid ({other.nx} intervals along x, "
                               f"{_taken(exc)} Newton iterations)") from None


def _paths(model: BearingModel, first, budget: _Budget, tension, progress, interpolate,
           flown=None, iteration_log=None):
    """(name, path) of the paths tried in turn from the first state ``first``: each a
    callable returning the state (or a solution on another grid) or raising
    ConvergenceError. A smooth law: direct, the resting start, the speed, the law's scale;
    the wall: direct, pseudo-time, the speed. An infinitely wide tape with ``flown``
    (:meth:`BearingModel.with_flown_corners`) tries that grid second: a tape flying over
    corners refined to the roughness is not reached (its state is below their rows'
    round-off), while one pressing onto the head is reached directly (as before)."""
    if flown is not None and model.infinitely_wide:
        paths = list(_paths(model, first, budget, tension, progress, interpolate))
        return [paths[0], ("the tape flying over the head's corners",
                           lambda: _flown_path(flown, budget, tension, progress,
                                               iteration_log, interpolate)), *paths[1:]]
    options = budget.options
    direct = ("direct", lambda: budget.solve(model, first, options.max_iterations,
                                             tension=tension))
    speed = ("the speed from the dry tape",
             lambda: _speed_path(model, budget, tension, progress))
    if not model.smooth_contact:     # the wall: its own first state, no law to scale
        return (direct, ("pseudo-time from the start", lambda: _pseudo_time_path(
            model, first, budget, tension, progress)), speed)
    resting = ("Newton from the tape resting on its summits",
               lambda: budget.solve(model, resting_start(model), options.resting_iterations,
                                    tension=tension))
    law = ("the law's scale from the hard wall",
           lambda: _law_path(model, budget, tension, progress, interpolate))
    scales = turned_corner_scales(model) if model.infinitely_wide else None
    if scales is None:
        return (direct, resting, speed, law)
    start_grid = ("the grid refined at the corners the tape turns over",
                  lambda: _start_grid_path(model, budget, tension, progress, iteration_log,
                                           interpolate, scales))
    return (direct, resting, speed, start_grid, law)


def _flown_path(flown: BearingModel, budget: _Budget, tension, progress, iteration_log,
                interpolate) -> BearingSolution:
    """The steady state on ``flown``, the model with its corners refined for a tape
    flying over them (:meth:`BearingModel.with_flown_corners`), from its own start,
    within what is left of the budget."""
    if progress is not None:
        progress("one film covers the head: its corners refined for the tape flying over "
                 f"them ({flown.nx} intervals along x)")
    return _solve_elsewhere(flown, budget, tension, progress, iteration_log, interpolate)


def _flown_if_the_strip_flies(model: BearingModel, flown: BearingModel, tension, progress,
                              iteration_log, options: SolverOptions, interpolate
                              ) -> BearingSolution:
    """The steady state of a 2-D ``model`` over a head one film covers: the infinitely
    wide tape on the same x-grid first (a fraction of the 2-D solve's cost), which either
    presses onto the head (its corners touch: the 2-D model as it is, started from its
    coarse grids) or flies over its corners (the 2-D model on ``flown``'s grid, whose
    corners are refined for that). Raises the strip's ConvergenceError if it reaches
    neither: without the strip's state the 2-D model has no start, and its paths cost
    hundreds of times more for nothing (measured: 0.01 deg wraps over a 1 mm land, 906,648
    unknowns, past 300 s)."""
    strip = model.rebuilt(infinitely_wide=True, ny=None)
    if progress is not None:
        progress(f"start: the infinitely wide tape on the same x-grid ({strip.unknowns} "
                 "unknowns): does the tape fly over the head's corners?")
    try:
        sol = solve_smooth(strip, None, tension, progress, iteration_log, options,
                           interpolate=interpolate)
    except ConvergenceError as exc:
        raise ConvergenceError(
            f"the infinitely wide tape over this head reaches no steady state, so the "
            f"2-D tape has no start ({exc})") from None
    taken = sol.info.iterations + sol.info.start_iterations
    target = flown if sol.model.corners_flown else model
    options = _spending(options, taken)
    if progress is not None and target is flown:
        progress("the infinitely wide tape flies over the head's corners: the 2-D tape "
                 f"on a grid refined for that ({flown.nx} x {flown.ny} intervals)")
    out = solve_smooth(target, None, tension, progress, iteration_log, options,
                       interpolate=interpolate, decided=True)
    out.info.start_iterations += taken
    return out


def _no_state(model: BearingModel, options: SolverOptions, info: NewtonInfo,
              failures: list) -> ConvergenceError:
    """The ConvergenceError of a solve no path completed: each path's failure, the
    iterations taken (the start's among them) and what to try; ``info`` attached."""
    start = (f", {info.start_iterations} of them on the start's grids"
             if info.start_iterations else "")
    exc = ConvergenceError(
        f"no steady state reached within {options.budget} Newton iterations "
        f"({info.iterations + info.start_iterations} taken{start}): " + "; ".join(failures)
        + "; try a finer grid (nx), a start (z0) from a neighbouring state"
        + (", or contact='hard'" if model.smooth_contact else ""))
    exc.info = info
    return exc


def solve_smooth(model: BearingModel, z0, tension, progress, iteration_log,
                 options: SolverOptions | None = None, *,
                 interpolate, start=None, decided: bool = False) -> BearingSolution:
    """The steady state under the model's contact law (see the module notes): Newton
    from ``z0`` (default ``start(info)`` if given, else :func:`flying_start`), then the
    law's and the speed's continuations, within ``options.budget`` Newton iterations.
    ``interpolate``: the interpolation of a state onto another grid
    (:func:`.steady.interpolated_state`). The hard wall (bounds h >= σ on the same
    Newton) takes the direct path and the speed's: the resting start and the law's scale
    belong to a smooth law. Over a head one film covers (:attr:`BearingModel.
    film_over_head`) the tape may fly over the corners (:func:`_paths`); a 2-D tape then
    follows its strip (:func:`_flown_if_the_strip_flies`; ``decided``: it has).

    Raises
    ------
    ConvergenceError
        Naming each path's failure and what to try.
    """
    options = SolverOptions() if options is None else options
    clock = time.perf_counter()
    info = NewtonInfo()
    flown = None if decided else model.with_flown_corners()
    if flown is not None and z0 is None and model.smooth_contact and not model.infinitely_wide:
        return _flown_if_the_strip_flies(model, flown, tension, progress, iteration_log,
                                         options, interpolate)
    if z0 is None and not model.infinitely_wide and model.smooth_contact:
        z0, info.start_iterations = coarse_start(model, interpolate, tension, progress,
                                                 iteration_log, options)
    budget = _Budget(options, info, iteration_log)
    failures = []
    z = None
    first = (z0 if z0 is not None else flying_start(model) if start is None
             else start(info))
    for name, path in _paths(model, first, budget, tension, progress, interpolate,
                             flown, iteration_log):
        if budget.left < 1:
            break
        try:
            z = path()
            if isinstance(z, BearingSolution):      # solved on the flown corners' grid
                z.info.start_iterations += info.iterations + info.start_iterations
                return z
            break
        except ConvergenceError as exc:
            failures.append(f"{name}: {exc}")
            if progress is not None:
                progress(f"{name} did not reach the state ({exc})")
    if z is None:
        raise _no_state(model, options, info, failures)
    info.seconds = time.perf_counter() - clock
    check_cavitation(model, z[model.n_u:])
    lam = SteadyProblem(model, tension=tension).forces(z)
    return BearingSolution(model, z[:model.n_u], z[model.n_u:], lam, info)
