"""Steady flying state: the entry point, its checks and the starts.

Every contact law is solved the same way: the model's equations as a problem
(:class:`.problem.SteadyProblem`: the residual, its Jacobian, and for the hard wall the
bounds h >= σ on the nodes that may touch the head) solved by the one generic Newton
(:func:`gyroshell.linalg.newton.newton`: a reduced-space active set for the bounds, one
line search), driven from its starts and continuations within one budget of iterations by
:func:`.smooth.solve_smooth`. Rounded corners touched at a point move their contacts
between such solves (:func:`.corners.solve_adapting_contacts`).

This module holds the starts the hard wall adds: a 2-D tape starts from its state on a
grid twice as coarse (large grids) or from the infinitely wide tape's state extruded
across the width, an infinitely wide tape on a very fine grid from its coarser grid's
state, each interpolated (:func:`interpolated_state`).
"""

from __future__ import annotations

import warnings

import numpy as np
import scipy.sparse as sp

from ..core import validation
from ..core.errors import ConvergenceError, ParameterError
from ..linalg.newton import STEP_TOLERANCE  # noqa: F401  (the solve's step tolerance)
from ..tape.parameters import MIN_INTERVALS_ACROSS
from .model import MIN_INTERVALS_ALONG, BearingGridWarning, BearingModel
from .problem import (  # noqa: F401  (the residual's pieces, also reached through here)
    _PATTERNS,
    JACOBIAN_ORDERING,
    SINGLE_LU,
    Linearization,
    _jacobian_lu,
    _model_pattern,
    _pattern_digest,
    _Residual,
    _step_limit,
    check_cavitation,
    pattern_ordering,
)
from .results import BearingSolution, NewtonInfo


def solve_steady(model: BearingModel, *, z0: np.ndarray | None = None,
                 tension: float | None = None, progress=None, iteration_log=None,
                 options=None) -> BearingSolution:
    """The steady flying state of ``model``.

    Newton from ``z0`` (default: :func:`initial_state` for the hard wall, the flying
    start of :mod:`.smooth` under a smooth law), then the continuations of
    :func:`.smooth.solve_smooth`, within one budget of Newton iterations; over rounded
    corners touched at a point, those solves with the contacts moved between them
    (:func:`.corners.solve_adapting_contacts`).

    Parameters
    ----------
    model : BearingModel
    z0 : numpy.ndarray, optional
        Start [u (m), p (Pa)], e.g. a neighbouring solution.
    tension : float, optional
        Tension T, N/m, in place of the model's (continuation in T).
    progress : callable, optional
        Called with a one-line message per stage: the starts, each path tried and each
        continuation stage. False, like None, reports nothing.
    iteration_log : callable, optional
        Called with a one-line message per Newton iteration (those of the starts too).
    options : gyroshell.bearing.smooth.SolverOptions, optional
        Tolerance, iteration limits and budget (default ``SolverOptions()``).

    Raises
    ------
    ParameterError
        If an argument is of the wrong type, shape or range (checked before any work).
    ConvergenceError
        If no path reaches the state within the budget.
    """
    from .smooth import solve_smooth

    progress = None if progress is False else progress  # False: no progress, as elsewhere
    tension, z0 = check_steady_arguments(model, z0, tension, progress, iteration_log)
    if model.adapt_contacts and model.corner_contacts and not model.smooth_contact:
        from .corners import solve_adapting_contacts

        return solve_adapting_contacts(
            model, solve_steady, z0=z0, tension=tension, progress=progress,
            iteration_log=iteration_log, options=options,
            coarse_start=None if tension is not None else _rounded_coarse_start(
                COARSE_START_MIN_UNKNOWNS, progress, iteration_log))

    def start(info: NewtonInfo) -> np.ndarray:
        return initial_state(model, progress=progress, iteration_log=iteration_log,
                             info=info)

    return solve_smooth(model, z0, tension, progress, iteration_log, options,
                        interpolate=interpolated_state,
                        start=None if model.smooth_contact else start)


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
                  iteration_log=None, info: NewtonInfo | None = None) -> np.ndarray:
    """A start [u (m), p (Pa)] for Newton. Infinitely wide: the flexible-foil spacing and
    the wrap pressure (:meth:`BearingModel.initial_state`), or on a very fine grid over a
    flat or profile head the state on the grid twice as coarse. 2-D: the steady state on a
    grid twice as coarse, interpolated, when the model is large enough
    (:func:`coarse_solution`); else the infinitely wide tape's solution on the same
    x-grid, extruded across the width (one cheap 1-D solve saves several 2-D Newton
    iterations).

    ``coarse_min_unknowns``: the fewest unknowns of a 2-D model started from the coarse
    grid (default :data:`COARSE_START_MIN_UNKNOWNS`). ``progress`` and ``iteration_log``
    (optional) get one line per start solved and per Newton iteration, as in
    :func:`solve_steady`; ``info`` (optional) gets the start's Newton iterations added."""
    sol = None
    if model.infinitely_wide:
        if (not model.cylindrical and not model.dry and model.nx > COARSE_START_MIN_NX
                and not model.corner_contacts):
            sol = coarse_solution(model, coarse_min_unknowns, progress, iteration_log)
        z = model.initial_state() if sol is None else interpolated_state(model, sol)
    elif model.unknowns >= coarse_min_unknowns and not model.corner_contacts:
        # rounded corners with fixed contacts (a pass of corners.solve_adapting_contacts):
        # the extruded strip; the adaptation itself starts a large 2-D model from the
        # coarse grid with its contacts adapted there (coarse_solution), whose contacts
        # differ
        sol = coarse_solution(model, coarse_min_unknowns, progress, iteration_log)
    if not model.infinitely_wide:
        if sol is None:
            z, sol = _extruded_strip_state(model, progress, iteration_log)
        else:
            z = interpolated_state(model, sol)
    if info is not None and sol is not None:
        _count(info, sol.info)
    return z


def _count(info: NewtonInfo, start: NewtonInfo) -> None:
    """Add a start's Newton iterations to ``info``."""
    info.iterations += start.iterations
    info.step_norms += start.step_norms
    info.residual_norms += start.residual_norms
    info.contact_nodes += start.contact_nodes


def coarse_solution(model: BearingModel, coarse_min_unknowns: int = COARSE_START_MIN_UNKNOWNS,
                    progress=None, iteration_log=None) -> BearingSolution | None:
    """The steady state on the grid twice as coarse in x and y (the same mapping); None
    if that grid would be too coarse or its solve fails. The coarse grid starts from its
    own :func:`initial_state` (with ``coarse_min_unknowns``). With rounded corners
    (``model.adapt_contacts``) the coarse grid adapts its own contacts
    (:func:`~.corners.solve_adapting_contacts`, itself started from the grid twice as
    coarse again): the solution's model holds them, the start of the fine grid's
    contacts."""
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
    adapting = bool(coarse.corner_contacts) and model.adapt_contacts
    if progress is not None:
        progress(f"start: solving the coarse grid {nx} x {ny} ({coarse.unknowns} unknowns)"
                 + (", its rounded corners' contacts adapted" if adapting else ""))
    try:
        if adapting:
            from .corners import solve_adapting_contacts

            return solve_adapting_contacts(
                coarse, solve_steady, progress=progress, iteration_log=iteration_log,
                coarse_start=_rounded_coarse_start(coarse_min_unknowns, progress,
                                                   iteration_log))
        info = NewtonInfo()
        start = initial_state(coarse, coarse_min_unknowns=coarse_min_unknowns,
                              progress=progress, iteration_log=iteration_log, info=info)
        sol = solve_steady(coarse, z0=start, progress=progress, iteration_log=iteration_log)
    except ConvergenceError:
        return None
    _count(info, sol.info)
    sol.info.iterations, sol.info.step_norms = info.iterations, info.step_norms
    sol.info.residual_norms, sol.info.contact_nodes = info.residual_norms, info.contact_nodes
    return sol


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



def _extruded_strip_state(model: BearingModel, progress=None, iteration_log=None
                          ) -> tuple[np.ndarray, BearingSolution | None]:
    """The infinitely wide tape's steady state on the model's x-grid (its flexible-foil
    start if no path reaches it), repeated across the width; and that solution (None if
    it failed)."""
    strip = model.rebuilt(infinitely_wide=True, ny=None)
    if progress is not None:
        progress(f"start: solving the infinitely wide tape on the same x-grid "
                 f"({strip.unknowns} unknowns)")
    from .smooth import extruded, strip_state

    try:
        sol = solve_steady(strip, iteration_log=iteration_log)
    except ConvergenceError:
        return extruded(model, strip, strip.initial_state()), None
    return extruded(model, strip, strip_state(strip, sol, interpolated_state)), sol
