"""Steady flying state: monolithic Newton over (u, p) with a primal–dual active set for
contact; over flat and profile heads a continuation in V up from the dry tape (low speeds,
where the flying start is degenerate), then pseudo-transient continuation, then
continuation in V down from a faster film, when Newton cannot reach the state directly.

Contact keeps the spacing at or above the roughness σ. With the contact forces λ >= 0 the
conditions are complementary: h − σ >= 0, λ >= 0, λ (h − σ) = 0, written as the
semismooth equation λ − max(0, λ − c (h − σ)) = 0 (c = diag K, in N/m). Its Newton
method is the primal–dual active-set method: nodes with λ − c (h − σ) > 0 are in
contact, their tape rows become h = σ and their λ follows from the tape equation; the
others carry λ = 0. The active set changes only between iterations and the method stops
when the set is settled and the step is negligible, so contact never stalls Newton the way
a penalty with a step limiter does.
"""

from __future__ import annotations

import math
import time
import warnings

import numpy as np
import scipy.sparse as sp

from ..core import validation
from ..core.errors import ConvergenceError, ParameterError
from ..tape.parameters import MIN_INTERVALS_ACROSS
from .model import MIN_INTERVALS_ALONG, BearingGridWarning, BearingModel
from .problem import (  # noqa: F401  (the residual's pieces, also reached through here)
    _PATTERNS,
    JACOBIAN_ORDERING,
    SINGLE_LU,
    SPACING_GROWTH,
    SPACING_KEEP,
    Linearization,
    _jacobian_lu,
    _model_pattern,
    _pattern_digest,
    _Residual,
    _smooth_step_limit,
    _step_limit,
    _wrapped_at_speed,
    check_cavitation,
    pattern_ordering,
)
from .results import BearingSolution, NewtonInfo

#: Relative Newton step (|δu|/h_scale, |δp|/(T/R)) at which the solve has converged.
STEP_TOLERANCE = 1e-8
#: A full step below this relative size and within ROUND_OFF_MULTIPLE of the step that
#: the residual's round-off alone produces (:func:`_noise_step`) has converged: the state
#: is at its round-off floor.
ROUND_OFF_STEP = 1e-4
ROUND_OFF_MULTIPLE = 10.0
#: Most Newton iterations per solve.
MAX_ITERATIONS = 60
#: A step may shrink p to no less than this fraction of its value (compressible film).
PRESSURE_KEEP = 0.2
#: Below this relative step a factorization is reused (chord steps) ...
CHORD_SWITCH = 5e-2
#: ... while each step shrinks at least by this factor (the infinitely wide tape, whose
#: banded LU costs less than a residual).
CHORD_CONTRACTION = 0.1
#: The same for a 2-D tape, whose LU costs many residuals and substitutions: chord steps
#: from a relative step of 0.5 while each shrinks the step 4x (on the 12.65 mm tape's
#: default grid the fine-grid Newton then factors once instead of twice: 8 iterations
#: instead of 5, the chord steps contracting about 10x each).
CHORD_SWITCH_2D = 0.5
CHORD_CONTRACTION_2D = 0.25
#: Newton steps below this relative size are taken in full (the quadratic regime: the
#: scaled residual may already sit at its round-off floor, where a line search only stalls).
FULL_STEP = 1e-5
#: A merit within this multiple of its round-off floor cannot guide a line search: full
#: steps are taken (Newton's own contraction decides).
NOISE_MULTIPLE = 100.0
#: Smallest line-search step before a step is taken anyway.
MIN_STEP = 1.0 / 256.0
#: Sufficient decrease of the line search: the merit must fall by this fraction of α ...
ARMIJO = 1e-4
#: ... else α is cut by this factor.
BACKTRACK = 0.5
#: Newton has stagnated when, over this many iterations, the scaled residual has not halved
#: and no line-search step reached STAGNATION_STEP (the start is outside Newton's basin:
#: pseudo-time or continuation takes over).
STAGNATION_WINDOW = 10
STAGNATION_STEP = 0.5


def _project(z: np.ndarray, model: BearingModel, sigma: float) -> np.ndarray:
    """z with every spacing raised to at least σ (the feasible set of the contact; the
    rounded arcs' nodes off contact, :attr:`BearingModel.contact_floor`, to the film's
    floor σ/2: exempt from the step limit, they may dip below σ during the iteration)."""
    n_u = model.n_u
    floor = (np.where(model.contact_floor < sigma, 0.5 * sigma, sigma)   # arcs: film's floor
             - model.dry_field[1:-1, :].ravel())
    z[:n_u] = np.maximum(z[:n_u], floor)
    return z


def _norm(dz: np.ndarray, n_u: int, F) -> float:
    """max |δu|/h_scale, |δp|/(T/R): the relative size of a Newton step."""
    return max(np.max(np.abs(dz[:n_u])) / F.h_scale, np.max(np.abs(dz[n_u:])) / F.t_scale)



def _line_search(F, model, z, dz, h, active, merit, tol, noise=None):
    """Backtracking from the largest admissible step (:func:`_step_limit`, and p kept
    above a fifth of itself) on the scaled residual, each trial projected onto h >= σ.
    Full steps are taken when the step is small (the quadratic regime) or the merit is
    within NOISE_MULTIPLE of its round-off floor ``noise`` (:meth:`_Residual.noise`).
    Returns (α, relative step size, trial state, trial merit)."""
    n_u = model.n_u
    # dry (no film, a linear complementarity problem): no h³ coefficients to protect;
    # a smooth contact law: every spacing kept (no wall to project onto)
    alpha = (_smooth_step_limit(h, dz[:n_u], F.sigma) if F.smooth
             else 1.0 if model.dry else _step_limit(h, dz[:n_u], active, F.sigma, F.floor))
    alpha_p = 1.0
    if model.air.compressible:
        p, dp = z[n_u:], dz[n_u:]
        shrink = (dp < -(1 - PRESSURE_KEEP) * p) & (p > 0.0)
        if shrink.any():
            alpha_p = float(np.min(-(1 - PRESSURE_KEEP) * p[shrink] / dp[shrink]))
    alpha = min(alpha, alpha_p)
    step = _norm(dz, n_u, F)
    full = step < max(tol, FULL_STEP) or (noise is not None and merit < NOISE_MULTIPLE * noise)
    if full:     # near round-off the merit can no longer decrease reliably: full steps,
        alpha = alpha_p   # but never to a pressure <= 0 (the compressible film's φ = p h)
    while True:
        trial = z + alpha * dz if F.smooth else _project(z + alpha * dz, model, F.sigma)
        res_t, _, _ = F(trial, jacobian=False)
        merit_t = F.merit(res_t)
        if full or _decreased(merit_t, merit, alpha) or alpha < MIN_STEP:
            return alpha, step, trial, merit_t
        alpha *= BACKTRACK


def _decreased(merit_trial: float, merit: float, alpha: float) -> bool:
    """The Armijo condition of a step α: the merit fell by at least ARMIJO α of itself."""
    return merit_trial <= (1.0 - ARMIJO * alpha) * merit


class _Iterate:
    """Newton's current state: z, its residual, contact set, Jacobian and merit, the last
    factorization (a solver), whether the contact set has settled, and whether the last
    step was full and negligible (``tied``): if the next one, with the contact set the
    rule gave after it, is negligible too, the state solves both linearizations, so the
    nodes the rule flips are at the tie h = σ, λ = 0 (a tape lying on a flat land with no
    force, where the rule, decided by round-off, cycles) and Newton has converged."""

    def __init__(self, F: _Residual, z0: np.ndarray) -> None:
        self.z = np.array(z0, dtype=float)
        self.res, self.active, self.J = F(self.z, jacobian=True)
        self.merit = F.merit(self.res)
        self.solver, self.last_step, self.settled = None, np.inf, False
        self.tied = False
        #: the round-off step (:func:`_noise_step`) and the factorization it was formed by
        self.noise_step, self.noise_of = 0.0, None

    def converged(self, active: np.ndarray, negligible: bool) -> bool:
        """Take the new contact set ``active``; whether Newton has converged: a negligible
        full step with the set settled, or after a negligible full step (``tied``)."""
        self.settled = np.array_equal(active, self.active)
        self.active = active
        done = negligible and (self.settled or self.tied)
        self.tied = negligible
        return done


def _newton_direction(F: _Residual, it: _Iterate) -> np.ndarray:
    """The Newton step. Near the solution with a settled contact set, the last
    factorization is reused (a chord step) as long as it still contracts fast; else J is
    factored afresh."""
    n_u = F.model.n_u
    switch, contraction = ((CHORD_SWITCH, CHORD_CONTRACTION) if F.model.infinitely_wide
                           else (CHORD_SWITCH_2D, CHORD_CONTRACTION_2D))
    if it.solver is not None and it.settled and it.last_step < switch:
        dz = it.solver(it.res)
        if _norm(dz, n_u, F) <= contraction * it.last_step:
            return dz
    if it.J is None:       # a 2-D tape forms its Jacobian only to factor it
        it.J = F.linearize(it.z, it.active)
    it.solver = F.factor(it.J)
    return it.solver(it.res)


def _film_blocks(F: _Residual, it: _Iterate) -> Linearization:
    """A linearization at the iterate (its film blocks, whatever its contact set): the
    iterate's, formed now if a chord step left it unformed."""
    if it.J is None:
        it.J = F.linearize(it.z, it.active)
    return it.J


def _kept_if_better(F, model, it, dz, h, active, solver, found, merit_t, tol):
    """Line-search the candidate step ``dz`` (with its contact set ``active`` and the
    factorization ``solver``) and keep it if its merit beats ``merit_t``, the damped step
    ``found``'s; else ``found``."""
    retry = _line_search(F, model, it.z, dz, h, active, it.merit, tol)
    if retry[3] >= merit_t:
        return found
    it.solver, it.active = solver, active
    return retry


def _forced_contact_step(F, it: _Iterate, h, dz, found, tol):
    """The step again with the free nodes it would take below σ held there, if the damped
    step ``found`` (α, step, trial, merit) failed because of them; the better of the two.

    Those nodes join the contact set now (the primal–dual active-set rule evaluated at the
    full step): damped steps would otherwise let them enter a few per iteration, each time
    with a line search that barely moves. Updates ``it.solver`` and ``it.active`` when the
    forced step is taken."""
    model = F.model
    alpha, step, _, merit_t = found
    entering = ~it.active & (h + dz[:model.n_u] < F.floor)
    if _decreased(merit_t, it.merit, alpha) or step < FULL_STEP or not entering.any():
        return found
    u, p = it.z[:model.n_u], it.z[model.n_u:]
    res_f, active_f = F.contact_rows(u, F.tape(u, p), it.res[model.n_u:], force=entering)
    forced = F.factor(F.with_contact(_film_blocks(F, it), active_f))
    dz_f = forced(res_f)
    if not np.all(np.isfinite(dz_f)):
        return found
    return _kept_if_better(F, model, it, dz_f, h, active_f, forced, found, merit_t, tol)


#: Most updates of the contact set within one linearization (:func:`_contact_set_step`).
MAX_SET_UPDATES = 30


def _set_step_start(F, it: _Iterate, found):
    """(u, r_u, the trial's merit) for a contact-set step after the step ``found`` (α,
    step, trial, merit); None where none is wanted: a full step that decreased the merit,
    or a step below FULL_STEP (converged)."""
    alpha, step, _, merit_t = found
    if (alpha == 1.0 and _decreased(merit_t, it.merit, alpha)) or step < FULL_STEP:
        return None
    n_u = F.model.n_u
    u, p = it.z[:n_u], it.z[n_u:]
    return u, F.tape(u, p), merit_t


def _contact_set_step(F, it: _Iterate, h, dz, found, tol):
    """The step again with a contact set consistent with its own linearization, if the
    step ``found`` (α, step, trial, merit) was damped or failed while the full step would
    change the contact set; the better of the two.

    The primal–dual active-set rule applied to the linearized problem (J fixed at the
    iterate): a step with set A predicts the spacing h + δu and the contact forces
    λ = r_u + [J_uu, −L] δz (the tape rows are linear); the next set is
    {λ − c (h + δu − σ) > 0}: the free nodes the step takes below σ enter, the contact
    nodes whose force turns negative leave, all at once. Repeated until the set repeats
    (at most MAX_SET_UPDATES factorizations), so a plate's land contact zone, whose nodes
    press their neighbours down, grows or shrinks by many nodes per Newton iteration
    instead of a few. Updates ``it.solver`` and ``it.active`` when that step is taken."""
    model = F.model
    n_u = model.n_u
    start = _set_step_start(F, it, found)
    if start is None:
        return found
    u, r_u, merit_t = start
    active, d, solver = it.active, dz, it.solver
    for _ in range(MAX_SET_UPDATES):
        lam = r_u + F.tape_rows @ d
        nxt = lam - F.c * (h + d[:n_u] - F.floor) > 0.0
        if np.array_equal(nxt, active):
            break
        active = nxt
        res_a, _ = F.contact_rows(u, r_u, it.res[n_u:], active)
        solver = F.factor(F.with_contact(_film_blocks(F, it), active))
        d = solver(res_a)
        if not np.all(np.isfinite(d)):
            return found
    if d is dz:
        return found
    return _kept_if_better(F, model, it, d, h, active, solver, found, merit_t, tol)


#: Most factorizations of the feasible contact step (:func:`_feasible_contact_step`).
MAX_FEASIBLE_UPDATES = 30


def _feasible_contact_step(F, it: _Iterate, h, dz, found, tol):
    """The step again by a primal active-set method on the linearized contact problem, if
    the step ``found`` (α, step, trial, merit) was damped or failed; the better of the two.
    Over the wrapped arcs of an infinitely wide tape (:func:`_contact_step_rule`).

    J fixed at the iterate, the tape rows linear: from the iterate (feasible: h >= σ) the
    step with contact set W (empty at first) is followed until the first free node
    reaches σ (the ratio test); that node joins W and the step is formed again from
    there; at the step's end the contact nodes whose force λ = r_u + [J_uu, −L] δz is
    negative leave W, all at once. Every point of the path stays feasible, so the
    line search along the step needs no projection, and W grows by the nodes the tape
    actually reaches instead of all those a step would take below σ. The primal–dual
    rule (:func:`_contact_set_step`) lets those all enter and then removes only the
    contact zone's end nodes per update (their forces alone turn negative): over an arc
    the tape touches at one node, on cells down to 25 nm, the zone shrinks by a node
    at each end per update and cycles (measured: 108 to 2 nodes in 50 updates, or
    14 → 0 → 14), so Newton stagnated and pseudo-time took 200-550 iterations.
    At most MAX_FEASIBLE_UPDATES factorizations. Updates ``it.solver`` and ``it.active``
    when that step is taken."""
    model = F.model
    n_u = model.n_u
    start = _set_step_start(F, it, found)
    if start is None:
        return found
    u, r_u, merit_t = start
    gap = np.maximum(h - F.floor, 0.0)        # the iterate's clearance (projected: >= 0)
    lin = _film_blocks(F, it)
    work = np.zeros(n_u, dtype=bool)
    d = np.zeros_like(dz)                     # the path's point, from the iterate
    solver, taken = None, False
    for _ in range(MAX_FEASIBLE_UPDATES):
        res_w, _ = F.contact_rows(u, r_u, it.res[n_u:], work)
        solver = F.factor(F.with_contact(lin, work))
        target = solver(res_w)
        if not np.all(np.isfinite(target)):
            return found
        e = target - d
        clearance = gap + d[:n_u]
        falling = ~work & (e[:n_u] < 0.0) & (clearance + e[:n_u] < 0.0)
        if falling.any():                    # the ratio test: the first node to touch
            t_i = np.where(falling, np.maximum(clearance, 0.0)
                           / np.where(falling, -e[:n_u], 1.0), np.inf)
            t = float(t_i.min())
            d = d + t * e
            work |= falling & (t_i <= t * (1.0 + 1e-9) + 1e-15)
            taken = True
            continue
        d, taken = target, True
        lam = r_u + F.tape_rows @ d
        leaving = work & (lam < 0.0)
        if not leaving.any():
            break
        work &= ~leaving
    if not taken:
        return found
    return _kept_if_better(F, model, it, d, h, work, solver, found, merit_t, tol)


def _contact_step_rule(model: BearingModel, touching: bool, active_set: bool):
    """The contact-set step of a Newton solve (:func:`newton`): over the wrapped arcs of an
    infinitely wide tape at speed the feasible step (:func:`_feasible_contact_step`);
    else the linearized primal–dual rule from a start that touches (or ``active_set``),
    the forced entry from one clear of the head."""
    if _wrapped_at_speed(model):
        return _feasible_contact_step
    return _contact_set_step if touching or active_set else _forced_contact_step


def _noise_step(F: _Residual, it: _Iterate) -> float:
    """The relative size of the Newton step that the residual's round-off alone produces
    (the rows' round-off :attr:`_Residual.noise_rows` with fixed pseudo-random signs,
    through the step's factorization): the floor below which steps cannot shrink. On a
    grid refined far below the bending length at a corner (the plate's fourth difference
    scales like h⁻⁴) it may lie above the step tolerance. On a 2-D tape once per
    factorization (chord steps near convergence move the rows' round-off by a fraction of
    itself); the infinitely wide tape's banded substitution costs next to nothing, so it
    is formed at every state there."""
    if F.model.infinitely_wide or it.noise_of is not it.solver:
        signs = np.random.default_rng(0).choice((-1.0, 1.0), size=F.noise_rows.size)
        it.noise_step = _norm(it.solver(signs * F.noise_rows), F.model.n_u, F)
        it.noise_of = it.solver
    return it.noise_step


def _record(info: NewtonInfo, step: float, merit: float, contacts: int) -> None:
    """Append one iteration (its step, scaled residual and contact count) to ``info``."""
    info.iterations += 1
    info.step_norms.append(float(step))
    info.residual_norms.append(merit)
    info.contact_nodes.append(contacts)


def _stagnated(merits: list, alphas: list) -> bool:
    """Whether the scaled residual has not halved over STAGNATION_WINDOW damped
    iterations (none reaching STAGNATION_STEP)."""
    return (len(alphas) >= STAGNATION_WINDOW
            and merits[-1] > 0.5 * merits[-1 - STAGNATION_WINDOW]
            and max(alphas[-STAGNATION_WINDOW:]) < STAGNATION_STEP)


def _evaluate(F: _Residual, it: _Iterate, lazy: bool) -> np.ndarray:
    """The residual (``it.res``) at the new iterate ``it.z`` and its contact set by the
    rule (returned); the Jacobian (``it.J``) too unless ``lazy`` (then None: formed when
    it is factored, the round-off estimate updated with the last one's film block)."""
    if lazy:
        it.res, active, it.J = F(it.z, jacobian=False)
        F.update_noise(it.z)
    else:
        it.res, active, it.J = F(it.z, jacobian=True)
    return active


def newton(model: BearingModel, z0: np.ndarray, *, tension: float | None = None,
           transient=None, tol: float = STEP_TOLERANCE,
           max_iterations: int = MAX_ITERATIONS, info: NewtonInfo | None = None,
           log=None, active_set: bool = False):
    """Solve the coupled residual from z0 by semismooth Newton with a backtracking line
    search on the scaled residual norm.

    ``log`` (optional) is called with a one-line message per iteration. ``active_set``:
    update the contact set by the linearized active-set rule even from a start clear of
    the head (a march's retried sub-step, whose start is a neighbouring state).
    ``transient`` (optional) supplies the time-discrete terms of one implicit step: an
    object with ``tape_terms(u) -> (r_extra, J_extra)`` and the film's ``phi_old``, ``dt``.

    Returns (z, λ, active, info): the state, the contact forces (N; zero off contact), the
    contact set and the iteration record. Raises ConvergenceError if Newton fails.
    """
    info = NewtonInfo() if info is None else info
    n_u = model.n_u
    F = _Residual(model, tension, transient)
    it = _Iterate(F, z0)
    # A start that touches the head (a neighbouring state: the infinitely wide tape, a
    # coarser grid, a pseudo-time step) has its contact set grown and shrunk by the
    # linearized active-set rule; a start clear of the head keeps the damped steps with
    # the forced entry of the nodes a step takes below σ (far from the state, e.g. a
    # lifted tape, pseudo-time leads Newton instead).
    contact_step = _contact_step_rule(model, bool(it.active.any()), active_set)
    merits, alphas = [it.merit], []
    # A 2-D tape's chord steps need no Jacobian: it is formed when factored; the
    # infinitely wide tape's (a few thousand unknowns) at every iterate, as it always was.
    lazy = not model.infinitely_wide
    for _ in range(max_iterations):
        h = it.z[:n_u] + model.dry_field[1:-1, :].ravel()
        dz = _newton_direction(F, it)
        if not np.all(np.isfinite(dz)):
            raise ConvergenceError("Newton: non-finite step")
        floor = (ROUND_OFF_MULTIPLE * _noise_step(F, it)
                 if _norm(dz, n_u, F) < ROUND_OFF_STEP else 0.0)
        found = _line_search(F, model, it.z, dz, h, it.active, it.merit, tol, F.noise)
        alpha, step, it.z, _ = contact_step(F, it, h, dz, found, tol)
        it.last_step = step
        active_new = _evaluate(F, it, lazy)
        it.merit = F.merit(it.res)
        contacts = int(active_new.sum())
        _record(info, alpha * step, it.merit, contacts)
        if log is not None:
            log(f"Newton {info.iterations}: step {alpha * step:.2e} (alpha {alpha:.3g}), "
                f"residual {it.merit:.2e}, {contacts} nodes in contact")
        if it.converged(active_new, alpha == 1.0 and step < max(tol, floor)):
            return it.z, F.contact_forces(it.z, it.active), it.active, info
        merits.append(it.merit)
        alphas.append(alpha)
        if _stagnated(merits, alphas):
            raise ConvergenceError(
                f"Newton stagnated (scaled residual {it.merit:.3g}, not halved in "
                f"{STAGNATION_WINDOW} damped iterations)")
    raise ConvergenceError(
        f"Newton did not converge in {max_iterations} iterations "
        f"(last relative step {info.step_norms[-1]:.3g}, scaled residual {it.merit:.3g})")


#: Continuation in V starts this many times faster (a thicker, easier film) ...
CONTINUATION_START = 4.0
#: ... and comes down by this factor per stage.
CONTINUATION_FACTOR = 0.7


def solve_steady(model: BearingModel, *, z0: np.ndarray | None = None,
                 tension: float | None = None, progress=None,
                 iteration_log=None) -> BearingSolution:
    """The steady flying state of ``model``.

    Under a smooth contact law: :func:`.smooth.solve_smooth`. The hard wall: Newton from
    ``z0`` (default :func:`initial_state`); if it fails, pseudo-transient continuation,
    then continuation in V down from a faster, thicker film.

    Parameters
    ----------
    model : BearingModel
    z0 : numpy.ndarray, optional
        Start [u (m), p (Pa)], e.g. a neighbouring solution.
    tension : float, optional
        Tension T, N/m, in place of the model's (continuation in T).
    progress : callable, optional
        Called with a one-line message per stage: the coarse-grid start of a 2-D tape,
        Newton giving way to the pseudo-time march, each pseudo-time step and each
        continuation stage. False, like None, reports nothing.
    iteration_log : callable, optional
        Called with a one-line message per Newton iteration (those of the coarse-grid
        start too).

    Raises
    ------
    ParameterError
        If an argument is of the wrong type, shape or range (checked before any work).
    ConvergenceError
        If neither Newton, the pseudo-time march nor the continuation reaches the state.
    """
    progress = None if progress is False else progress  # False: no progress, as elsewhere
    tension, z0 = check_steady_arguments(model, z0, tension, progress, iteration_log)
    if model.smooth_contact:      # asperities or a measured curve: see .smooth
        from .smooth import solve_smooth

        return solve_smooth(model, z0, tension, progress, iteration_log,
                            interpolate=interpolated_state)
    if model.adapt_contacts and model.corner_contacts:   # rounded corners: see .corners
        from .corners import solve_adapting_contacts

        return solve_adapting_contacts(
            model, solve_steady, z0=z0, tension=tension, progress=progress,
            iteration_log=iteration_log,
            coarse_start=None if tension is not None else _rounded_coarse_start(
                COARSE_START_MIN_UNKNOWNS, progress, iteration_log))
    start = time.perf_counter()
    info = NewtonInfo()
    if z0 is None:
        z0 = initial_state(model, progress=progress, iteration_log=iteration_log)
    try:
        z, lam, info = _newton_or_pseudo_time(model, z0, tension, info, progress,
                                              iteration_log)
    except ConvergenceError:
        if progress is not None:
            progress("pseudo-time did not reach the state: continuation in V")
        z, lam, info = _continuation(model, tension, progress, iteration_log)
    info.seconds = time.perf_counter() - start
    check_cavitation(model, z[model.n_u:])
    return BearingSolution(model, z[:model.n_u], z[model.n_u:], lam, info)


def check_steady_arguments(model, z0, tension, progress, iteration_log):
    """(tension, z0) of :func:`solve_steady`, checked: ``model`` a BearingModel, ``z0`` None
    or a finite vector of ``model.unknowns`` with positive pressures (compressible film),
    ``tension`` None or > ρV² (N/m, the tape must wrap), the callbacks None or callable."""
    validation.instance("model", model, BearingModel)
    if tension is not None:
        tension = validation.positive("tension", tension, "N/m")
        floor = model.params.density * model.velocity**2
        if not tension > floor:
            raise ParameterError(
                f"tension must be > rho V^2 = {floor:.6g} N/m at {model.velocity:g} m/s "
                f"(the tape would not wrap), got {tension:g}")
    for name, hook in (("progress", progress), ("iteration_log", iteration_log)):
        if hook is not None and not callable(hook):
            raise ParameterError(f"{name} must be None or a callable taking one message, "
                                 f"got {type(hook).__name__}")
    if z0 is not None:
        z0 = validation.vector("z0", z0, model.unknowns, "m and Pa")
        if model.air.compressible and not np.all(z0[model.n_u:] > 0.0):
            raise ParameterError("z0 must have pressures > 0 Pa (entries n_u: of [u, p]) "
                                 "for a compressible film")
    return tension, z0


# ----- the start of Newton -----------------------------------------------------------------
#: A 2-D tape with at least this many unknowns starts Newton from its solution on a grid
#: twice as coarse (recursively), interpolated; smaller ones from the infinitely wide tape ...
COARSE_START_MIN_UNKNOWNS = 20_000
#: An infinitely wide tape over a flat or profile head with more than this many
#: x-intervals starts from its solution on the grid twice as coarse (recursively): the
#: corner-start (:meth:`BearingModel.initial_state`) leads Newton there in a few
#: iterations only on coarse grids.
COARSE_START_MIN_NX = 4000
#: ... unless that grid would be coarser than this at the edges (m): an under-resolved
#: free-edge row falsely touches down and the coarse solve would lead Newton astray.
COARSE_START_MAX_Y_SPACING = 110e-6


def initial_state(model: BearingModel, *,
                  coarse_min_unknowns: int = COARSE_START_MIN_UNKNOWNS, progress=None,
                  iteration_log=None) -> np.ndarray:
    """A start [u (m), p (Pa)] for Newton. Infinitely wide: the flexible-foil spacing and
    the wrap pressure (:meth:`BearingModel.initial_state`). 2-D: the steady state on a grid
    twice as coarse, interpolated, when the model is large enough (:func:`_coarse_state`);
    else the infinitely wide tape's solution on the same x-grid, extruded across the width
    (one cheap 1-D solve saves several 2-D Newton iterations).

    ``coarse_min_unknowns``: the fewest unknowns of a 2-D model started from the coarse
    grid (default :data:`COARSE_START_MIN_UNKNOWNS`). ``progress`` and ``iteration_log``
    (optional) get one line per start solved and per Newton iteration, as in
    :func:`solve_steady`."""
    if model.infinitely_wide:
        z = None
        if (not model.cylindrical and not model.dry and model.nx > COARSE_START_MIN_NX
                and not model.corner_contacts):
            z = _coarse_state(model, coarse_min_unknowns, progress, iteration_log)
        if z is None and _dry_retry(model) and _flying_start_degenerate(model):
            try:
                z = _continuation_from_dry(model, None, NewtonInfo(), progress,
                                           iteration_log)[0]
            except ConvergenceError:
                z = None
        return model.initial_state() if z is None else z
    # rounded corners with fixed contacts (a pass of corners.solve_adapting_contacts): the
    # extruded strip; the adaptation itself starts a large 2-D model from the coarse grid
    # with its contacts adapted there (coarse_solution), whose contacts differ
    z = (_coarse_state(model, coarse_min_unknowns, progress, iteration_log)
         if model.unknowns >= coarse_min_unknowns and not model.corner_contacts else None)
    return _extruded_strip_state(model, progress, iteration_log) if z is None else z


#: Over a flat or profile head (infinitely wide tape) a flying start whose land spacing
#: (:attr:`BearingModel.flying_start_spacing`) is below this many roughnesses σ leads
#: Newton nowhere: the land lies at σ with no contact force, a tie the contact rule
#: cannot decide. The continuation up from the dry tape starts Newton instead. Measured
#: (3 mm land, 4°/4°, Table 1 tape): the flying start at 1.45 σ (1 m/s) and below
#: stagnates, at 1.9 σ (1.5 m/s) it converges in 14 iterations.
FLYING_START_MIN_ROUGHNESS = 1.5


def _flying_start_degenerate(model: BearingModel) -> bool:
    """Whether the flying start of ``model`` (a flat or profile head, at speed) lies within
    FLYING_START_MIN_ROUGHNESS σ of the land: the infinitely wide tape then starts from
    the continuation up from the dry tape, and a 2-D tape that Newton cannot bring to its
    state takes that continuation before pseudo-time."""
    return (not (model.cylindrical or model.dry) and model.flying_start_spacing
            < FLYING_START_MIN_ROUGHNESS * model.air.roughness)


def _coarse_state(model: BearingModel, coarse_min_unknowns: int, progress=None,
                  iteration_log=None) -> np.ndarray | None:
    """The steady state on the grid twice as coarse in x and y, interpolated
    (bilinearly) onto the model's grid; None if that grid would be too coarse or neither
    Newton nor the pseudo-time march reaches the state there (:func:`coarse_solution`).
    Most of Newton's iterations move the free edges down from the infinitely wide start;
    on the coarse grid they cost a fraction of a fine-grid factorization."""
    sol = coarse_solution(model, coarse_min_unknowns, progress, iteration_log)
    return None if sol is None else interpolated_state(model, sol)


def coarse_solution(model: BearingModel, coarse_min_unknowns: int = COARSE_START_MIN_UNKNOWNS,
                    progress=None, iteration_log=None) -> BearingSolution | None:
    """The steady state on the grid twice as coarse in x and y (the same mapping); None
    if that grid would be too coarse or its solve fails. The coarse grid starts from its
    own :func:`initial_state` (with ``coarse_min_unknowns``): Newton, then pseudo-time
    (no continuation in V). With rounded corners (``model.adapt_contacts``) the coarse
    grid adapts its own contacts (:func:`~.corners.solve_adapting_contacts`, itself
    started from the grid twice as coarse again): the solution's model holds them, the
    start of the fine grid's contacts."""
    nx = model.nx // 2 + (model.nx // 2) % 2
    ny = None if model.infinitely_wide else model.ny // 2 + (model.ny // 2) % 2
    if (ny is not None and ny < MIN_INTERVALS_ACROSS) or nx < MIN_INTERVALS_ALONG:
        return None
    try:
        coarse = _quiet_model(model, nx, ny)
    except ParameterError:     # too coarse for the film: no coarse start
        return None
    if ny is not None and coarse.y[1] - coarse.y[0] > COARSE_START_MAX_Y_SPACING:
        return None
    if coarse.corner_contacts and model.adapt_contacts:
        from .corners import solve_adapting_contacts

        if progress is not None:
            progress(f"start: solving the coarse grid {nx} x {ny} ({coarse.unknowns} "
                     "unknowns), its rounded corners' contacts adapted")
        try:
            return solve_adapting_contacts(
                coarse, _coarse_newton, progress=progress, iteration_log=iteration_log,
                coarse_start=_rounded_coarse_start(coarse_min_unknowns, progress,
                                                   iteration_log))
        except ConvergenceError:
            return None
    try:   # Newton, then pseudo-time (no continuation in V): cheap on a coarse grid
        start = initial_state(coarse, coarse_min_unknowns=coarse_min_unknowns,
                              progress=progress, iteration_log=iteration_log)
        if progress is not None:
            progress(f"start: solving the coarse grid {nx} x {ny} ({coarse.unknowns} "
                     "unknowns)")
        z, lam, info = _newton_or_pseudo_time(coarse, start, None, NewtonInfo(), progress,
                                              iteration_log)
    except ConvergenceError:
        return None
    return BearingSolution(coarse, z[:coarse.n_u], z[coarse.n_u:], lam, info)


def _rounded_coarse_start(coarse_min_unknowns: int, progress, iteration_log):
    """The coarse start of a 2-D tape over rounded corners, for
    :func:`~.corners.solve_adapting_contacts`: a callable taking the model and returning
    (the contacts of its :func:`coarse_solution`, adapted there; a callable giving that
    solution :func:`interpolated_state` onto a model's grid), or None when the model is
    infinitely wide, has fewer than ``coarse_min_unknowns`` unknowns or the coarse solve
    fails."""
    def start(model: BearingModel):
        if model.infinitely_wide or model.unknowns < coarse_min_unknowns:
            return None
        sol = coarse_solution(model, coarse_min_unknowns, progress, iteration_log)
        if sol is None:
            return None
        return sol.model.corner_contacts, lambda fine: interpolated_state(fine, sol)
    return start


def _coarse_newton(model: BearingModel, *, z0=None, progress=None,
                   iteration_log=None) -> BearingSolution:
    """One fixed-contact pass of a coarse start (:func:`coarse_solution`): Newton, then
    pseudo-time, from ``z0`` or the model's :func:`initial_state`; no continuation."""
    if z0 is None:
        z0 = initial_state(model, progress=progress, iteration_log=iteration_log)
    z, lam, info = _newton_or_pseudo_time(model, z0, None, NewtonInfo(), progress,
                                          iteration_log)
    return BearingSolution(model, z[:model.n_u], z[model.n_u:], lam, info)


def interpolated_state(model: BearingModel, sol: BearingSolution) -> np.ndarray:
    """The state [u, p] of ``sol`` (on its own model's grid, of the same mapping)
    interpolated (bilinearly) onto ``model``'s grid.

    Over rounded corners the tape's height w = z₀ + u is interpolated, not u: the dry
    string z₀ follows each arc (curvature 1/r_c) over a cell or two between nodes, which
    the tape does not (it touches the arc at one point), so u is curved by 1/r_c there and
    the plate's fourth difference on the corners' fine cells turns its interpolation error
    into a residual that led Newton astray (measured: scaled residual 7e12, 90
    iterations), while w is smooth. Elsewhere u is interpolated: the tape follows the
    curvature of z₀ where it has any (a cylinder's wrap, 1/R: interpolating w there costs
    the coarse start of a 3 mm tape 24 Newton iterations instead of 11, measured), and over
    sharp corners (z₀ piecewise linear, its kinks on both grids' nodes) the two agree."""
    coarse = sol.model

    def tape_height(m: BearingModel) -> np.ndarray:
        if not m.corner_contacts:
            return np.zeros((m.nx + 1, 1))
        return m.head.dry_tape(m.x_head, m.head_radius)[:, None]

    w = sol.spacing - coarse.dry_field + tape_height(coarse)
    if model.infinitely_wide:
        u = (np.interp(model.x, coarse.x, w[:, 0]) - tape_height(model)[:, 0])[1:-1]
        p = np.interp(model.x, coarse.x, sol.pressure[:, 0])[1:-1]
        return np.concatenate([u, p])
    along, across = _linear_weights(coarse.x, model.x), _linear_weights(coarse.y, model.y)
    fields = [along @ (across @ f.T).T for f in (w, sol.pressure)]
    u = (fields[0] - tape_height(model))[1:-1, :].ravel()
    return np.concatenate([u, fields[1][model.film.interior]])


def _linear_weights(nodes: np.ndarray, points: np.ndarray) -> sp.csr_matrix:
    """The matrix of piecewise-linear interpolation from ``nodes`` (increasing) to
    ``points`` (within their range): a tensor product of two gives the bilinear
    interpolant on a grid."""
    k = np.clip(np.searchsorted(nodes, points, side="right") - 1, 0, len(nodes) - 2)
    t = np.clip((points - nodes[k]) / (nodes[k + 1] - nodes[k]), 0.0, 1.0)
    rows = np.arange(len(points))
    return sp.csr_matrix((np.concatenate([1.0 - t, t]),
                          (np.concatenate([rows, rows]), np.concatenate([k, k + 1]))),
                         shape=(len(points), len(nodes)))


def _quiet_model(model: BearingModel, nx: int, ny: int) -> BearingModel:
    """``model`` on nx × ny intervals (the same mapping), without the coarse-edge warning:
    a start only needs to lead Newton, not to be accurate."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        return model.rebuilt(nx=nx, ny=ny)


def _extruded_strip_state(model: BearingModel, progress=None,
                          iteration_log=None) -> np.ndarray:
    """The infinitely wide tape's steady state on the model's x-grid (its flexible-foil
    start if Newton fails there), repeated across the width."""
    strip = model.rebuilt(infinitely_wide=True, ny=None)
    if progress is not None:
        progress(f"start: solving the infinitely wide tape on the same x-grid "
                 f"({strip.unknowns} unknowns)")
    try:
        sol = solve_steady(strip, iteration_log=iteration_log)
    except ConvergenceError:
        z = strip.initial_state()
        u1, p1 = z[:strip.n_u], z[strip.n_u:]
    else:
        u1, p1 = sol.u, sol.p
    u = np.repeat(u1, model.nc)
    P = np.repeat(strip.pressure_field(p1), model.nc, axis=1)
    return np.concatenate([u, P[model.film.interior]])


#: Pseudo-time continuation: first step (pseudo-time terms 1/s of each row's diagonal) ...
PSEUDO_START = 0.1
#: ... grown by this factor after an easy step (few Newton iterations) ...
PSEUDO_GROWTH = 4.0
#: ... cut by this factor after a failed one ...
PSEUDO_CUT = 4.0
#: ... and plain Newton is tried once the step exceeds this (and, if it fails, again
#: after the step has grown by PSEUDO_FINISH_RETRY).
PSEUDO_FINISH = 1e4
PSEUDO_FINISH_RETRY = 100.0
#: Pseudo-time steps at most, Newton iterations per step, and the step's tolerance.
PSEUDO_MAX_STEPS = 60
PSEUDO_NEWTON = 12
PSEUDO_TOLERANCE = 1e-4


class _PseudoTime:
    """Backward-Euler pseudo-time terms of pseudo-transient continuation with local steps:
    each row gains its own diagonal over s (s the pseudo-time step, dimensionless). The
    tape rows gain (c/s)(u − u_old) (c = diag K); the film rows the squeeze term
    12μ A ∂(ph)/∂t with a local step Δt_i chosen so that its p-derivative is |∂r_i/∂p_i|/s
    (compressible: Δt_i = 12μ A_i h_i s/|J_ii|; incompressible: Δt = s ℓ_film/V). Local
    steps let a thin-gap region, whose film responds slowly, relax as fast as the rest.
    Far from the steady state they keep each step inside Newton's basin; as s grows they
    vanish and the steady equations remain."""

    def __init__(self, model: BearingModel, z: np.ndarray, s: float, transit: float) -> None:
        n_u = model.n_u
        u, p = z[:n_u], z[n_u:]
        self.c = model.stiffness_diagonal / s
        self.u_old = u.copy()
        P, H = model.pressure_field(p), model.spacing_field(u)
        self.phi_old = model.film.transported(P, H)
        if model.air.compressible:
            _, J_pp, _ = model.film_residual(u, p, jacobian=True)
            film = model.film
            self.dt = (s * 12.0 * model.air.viscosity * film.cell_area[film.interior]
                       * H[film.interior] / np.maximum(np.abs(J_pp.diagonal()), 1e-300))
        else:
            self.dt = s * transit
        self.jacobian = sp.diags(self.c).tocsr()

    def tape_terms(self, u):
        return self.c * (u - self.u_old), self.jacobian


def _newton_or_pseudo_time(model, z0, tension, info, progress, iteration_log):
    """Newton from z0; over a flat or profile head of an infinitely wide tape, if it fails,
    Newton from the dry tape (:meth:`BearingModel.dry_start`: at low speeds the film
    barely pulls the tape below its dry tents), then the continuation in V up from the
    dry tape (:func:`_continuation_from_dry`; also for a 2-D tape whose flying start is
    degenerate, :func:`_flying_start_degenerate`); if that fails, pseudo-transient
    continuation from z0."""
    up = _dry_retry(model) or (not model.infinitely_wide and _flying_start_degenerate(model))
    try:
        z, lam, _, info = newton(model, z0, tension=tension, info=info, log=iteration_log)
        return z, lam, info
    except ConvergenceError as exc:
        if progress is not None:
            progress(f"{exc}: " + ("Newton from the dry tape" if _dry_retry(model) else
                                   "continuation in V up from the dry tape" if up else
                                   "pseudo-time continuation"))
    if _dry_retry(model):
        try:
            z, lam, _, info = newton(model, model.dry_start(), tension=tension, info=info,
                                     log=iteration_log)
            return z, lam, info
        except ConvergenceError as exc:
            if progress is not None:
                progress(f"{exc}: continuation in V up from the dry tape")
    if up:
        try:
            return _continuation_from_dry(model, tension, info, progress, iteration_log)
        except ConvergenceError as exc:
            if progress is not None:
                progress(f"{exc}: pseudo-time continuation")
    return pseudo_transient(model, z0, tension=tension, info=info, progress=progress,
                            iteration_log=iteration_log)


def _dry_retry(model: BearingModel) -> bool:
    """Whether Newton gets a second start from the dry tape (infinitely wide, flat or
    profile head, at speed)."""
    return model.infinitely_wide and not (model.cylindrical or model.dry)


#: Continuation in V up from the dry tape (V -> 0 is the dry limit): the first stage
#: runs at this fraction of the target speed, started from the dry tape ...
DRY_CONTINUATION_START = 0.1
#: ... and each next one this many times faster, up to the target. Measured (3 mm land,
#: 4°/4°, Table 1 tape, 1-D, on the 0.3 m/s grid): Newton from the dry tape converges in
#: 4-6 iterations at 1-100 mm/s and stagnates at 0.3 m/s; stages 1.25 apart take 5-8
#: iterations each from 0.1 to 1.2 m/s, stages 1.5 apart fail near 0.76 and 1 m/s.
DRY_CONTINUATION_FACTOR = 1.25
#: Newton iterations per stage at most (a stage starts next to its state: one that needs
#: more has left the branch and is retried halfway) ...
DRY_STAGE_ITERATIONS = 15
#: ... and a stage that fails is retried halfway at most this many times in a row ...
DRY_CONTINUATION_HALVINGS = 4
#: ... and only while halfway is at least this ratio above the last speed reached: else
#: the stages creep up to a speed they cannot pass (each success there restarts the
#: halvings). Measured (wrapped r_c = 1.2 mm arcs on a 1 mm land at 2°/2°, 4 m/s):
#: without it the stages crept from 0.4742 to 0.4749 m/s, 0.0004 apart, 460 Newton
#: iterations before pseudo-time took over.
DRY_CONTINUATION_MIN_RATIO = 1.01


def _dry_continuation_speeds(velocity: float) -> list[float]:
    """The speeds of the continuation up from the dry tape, m/s: geometric from
    DRY_CONTINUATION_START times ``velocity`` to ``velocity`` (same sign), at most
    DRY_CONTINUATION_FACTOR apart."""
    stages = math.ceil(math.log(1.0 / DRY_CONTINUATION_START)
                       / math.log(DRY_CONTINUATION_FACTOR) - 1e-9)
    ratio = (1.0 / DRY_CONTINUATION_START) ** (1.0 / stages)
    return [velocity * DRY_CONTINUATION_START * ratio**k for k in range(stages)] + [velocity]


def _continuation_from_dry(model: BearingModel, tension, info: NewtonInfo, progress,
                           iteration_log):
    """Continuation in V up from the dry tape to ``model``'s speed on its grid: the first
    stage by Newton from the dry tape (:meth:`BearingModel.dry_start`; a 2-D tape from its
    :func:`initial_state` there, the infinitely wide tape's state extruded), each next one
    from the last; a stage that fails is retried halfway (geometrically) from the last
    speed reached, at most DRY_CONTINUATION_HALVINGS times in a row. At low speeds over a long
    land this reaches the state that Newton from a flying start cannot: the tape tents
    over the land much as it does dry (7.0-9.9 um at the middle of a 3 mm land at 4°/4°,
    0.3-1 m/s, against 6.6 um dry). Returns (z, λ, info); raises ConvergenceError if a
    stage fails after its halvings."""
    targets = _dry_continuation_speeds(model.velocity)
    z, reached, lam, halvings = None, [], None, 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        while targets:
            v = targets[0]
            stage = model if v == model.velocity else model.at_velocity(v)
            if progress is not None:
                progress(f"continuation from the dry tape: V = {v:.4g} m/s")
            try:
                start = (z if z is not None else stage.dry_start() if stage.infinitely_wide
                         else initial_state(stage, progress=progress,
                                            iteration_log=iteration_log))
                z1, lam, _, info = newton(stage, start,
                                          tension=tension, info=info, log=iteration_log,
                                          max_iterations=DRY_STAGE_ITERATIONS)
            except ConvergenceError:
                if z is None or halvings == DRY_CONTINUATION_HALVINGS:
                    raise
                mid = math.sqrt(reached[-1] * abs(v))
                if mid < DRY_CONTINUATION_MIN_RATIO * reached[-1]:
                    raise
                halvings += 1
                targets.insert(0, math.copysign(mid, v))
                continue
            z, halvings = z1, 0
            reached.append(abs(targets.pop(0)))
    info.continuation = [math.copysign(v, model.velocity) for v in reached]
    return z, lam, info


def pseudo_transient(model: BearingModel, z0: np.ndarray, *, tension: float | None = None,
                     info: NewtonInfo | None = None, progress=None, iteration_log=None):
    """Pseudo-transient continuation (switched evolution) from z0 to the steady state.

    Each pseudo-time step s (:class:`_PseudoTime`) is solved by Newton; s grows by
    PSEUDO_GROWTH while Newton converges quickly within it, by 1.5 otherwise, and is cut
    by PSEUDO_CUT when it fails. Once s exceeds PSEUDO_FINISH plain Newton finishes (if it
    fails there, the march goes on and tries again 100 times further).

    Returns (z, λ, info). Raises ConvergenceError if the march does not get there.
    """
    info = NewtonInfo() if info is None else info
    transit = 1.0 if model.dry else model.film_length / abs(model.velocity)
    z, s, finish = np.array(z0, dtype=float), PSEUDO_START, PSEUDO_FINISH
    for _ in range(PSEUDO_MAX_STEPS):
        if s >= finish:
            try:
                z, lam, _, info = newton(model, z, tension=tension, info=info,
                                         log=iteration_log)
                return z, lam, info
            except ConvergenceError:   # slow modes still relaxing: march on
                finish *= PSEUDO_FINISH_RETRY
        before = info.iterations
        try:
            z, _, _, info = newton(model, z, tension=tension,
                                   transient=_PseudoTime(model, z, s, transit),
                                   tol=PSEUDO_TOLERANCE, max_iterations=PSEUDO_NEWTON,
                                   info=info, log=iteration_log)
        except ConvergenceError:
            s /= PSEUDO_CUT
            if s < PSEUDO_START / PSEUDO_CUT**4:
                break
            continue
        info.pseudo_time.append(s)
        if progress is not None:
            progress(f"pseudo-time step {s:.3g}: {info.iterations - before} Newton iterations")
        s *= PSEUDO_GROWTH if info.iterations - before <= PSEUDO_NEWTON // 2 else 1.5
    raise ConvergenceError("pseudo-time continuation did not reach the steady state")


def _continuation_stages(model: BearingModel) -> list[BearingModel]:
    """The models of the continuation in V, from CONTINUATION_START times faster down to
    ``model`` itself; speeds at which the model cannot be built (above the string speed,
    or a film too long for the given span) are left out."""
    speeds, v = [], model.velocity * CONTINUATION_START
    while abs(v) > abs(model.velocity):      # either direction: |V| comes down
        speeds.append(v)
        v *= CONTINUATION_FACTOR
    stages = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        for v in speeds:
            try:
                stages.append(model.at_velocity(v))
            except ParameterError:
                continue
    return [*stages, model]


def _continuation(model: BearingModel, tension, progress, iteration_log):
    stages = _continuation_stages(model)
    info = NewtonInfo(continuation=[stage.velocity for stage in stages])
    z = None
    for stage in stages:
        if progress is not None:
            progress(f"continuation: V = {stage.velocity:.4g} m/s")
        z0 = (initial_state(stage, progress=progress, iteration_log=iteration_log)
              if z is None else z)
        z, lam, info = _newton_or_pseudo_time(stage, z0, tension, info, progress,
                                              iteration_log)
    return z, lam, info
