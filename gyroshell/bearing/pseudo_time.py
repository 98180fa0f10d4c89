"""Pseudo-transient continuation: a path to the steady state for starts outside Newton's
basin.

Each stage is one backward-Euler step of pseudo-time size s (dimensionless) from the last
state reached, solved by the steady solve's Newton with the terms of :class:`PseudoTime`
in its residual; s grows geometrically along :func:`gyroshell.linalg.continuation.
continuation` (one step controller: a stage that fails is retried with a smaller step) up
to :data:`FINISH`, where the steady equations themselves are solved. Far from the steady
state the terms keep each stage inside Newton's basin; as s grows they vanish.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..linalg.continuation import StepController, continuation
from .model import BearingModel

#: The first pseudo-time step (the pseudo-time terms are 1/s of each row's diagonal) ...
START = 0.1
#: ... and the last, where the steady equations themselves are solved (the pseudo-time
#: terms there would be 1e-8 of each row's diagonal).
FINISH = 1e8
#: The steps start at this ratio per stage, squared after an easy stage (at most
#: EASY_ITERATIONS Newton iterations) up to MAXIMUM_RATIO, and cut to its square root
#: after a failed one, down to MINIMUM_RATIO.
RATIO = 4.0
EASY_ITERATIONS = 4
MAXIMUM_RATIO = 100.0
MINIMUM_RATIO = 1.05
#: Newton iterations of one pseudo-time stage (a stage that needs more is retried with a
#: smaller step).
STAGE_ITERATIONS = 12


class PseudoTime:
    """Backward-Euler pseudo-time terms with local steps, from the state z ([u (m),
    p (Pa)]): each row gains its own diagonal over s. The tape rows gain (c/s)(u − u_old)
    (c = diag K, N/m); the film rows the squeeze term 12μ A ∂(ph)/∂t with a local step
    Δt_i chosen so that its p-derivative is |∂r_i/∂p_i|/s (compressible: Δt_i =
    12μ A_i h_i s/|J_ii|; incompressible: Δt = s ℓ_film/V). Local steps let a thin-gap
    region, whose film responds slowly, relax as fast as the rest. The object is a time
    step's ``transient`` of :class:`.problem.SteadyProblem` (``tape_terms``, ``jacobian``,
    ``phi_old``, ``dt``)."""

    def __init__(self, model: BearingModel, z: np.ndarray, s: float) -> None:
        n_u = model.n_u
        u, p = z[:n_u], z[n_u:]
        self.c = model.stiffness_diagonal / s
        self.u_old = u.copy()
        P, H = model.pressure_field(p), model.spacing_field(u)
        self.phi_old = model.film.transported(P, H)
        if model.air.compressible and not model.dry:
            _, J_pp, _ = model.film_residual(u, p, jacobian=True)
            film = model.film
            self.dt = (s * 12.0 * model.air.viscosity * film.cell_area[film.interior]
                       * H[film.interior] / np.maximum(np.abs(J_pp.diagonal()), 1e-300))
        else:
            transit = 1.0 if model.dry else model.film_length / abs(model.velocity)
            self.dt = s * transit
        self.jacobian = sp.diags(self.c).tocsr()

    def tape_terms(self, u):
        return self.c * (u - self.u_old), self.jacobian


def pseudo_time_path(model: BearingModel, z0: np.ndarray, solve, progress=None):
    """The steady state of ``model`` by pseudo-transient continuation from z0 ([u, p]).

    ``solve(transient, state, limit)`` solves the model's equations with the pseudo-time
    terms ``transient`` (None: the steady equations) from ``state`` in at most ``limit``
    Newton iterations, returning (state, report). Returns (state, the pseudo-time steps
    taken); raises ConvergenceError if the path stops."""
    def at(s, state):
        if s == FINISH:
            return solve(None, state, None)
        if progress is not None:
            progress(f"pseudo-time step {s:.3g}")
        return solve(PseudoTime(model, state, s), state, STAGE_ITERATIONS)

    z, stages = continuation(at, START, FINISH, z0, controller=StepController(
        initial=RATIO, growth=2.0, cut=0.5, minimum=MINIMUM_RATIO, maximum=MAXIMUM_RATIO,
        easy_iterations=EASY_ITERATIONS))
    return z, [s for s, report in stages if report is not None and s != FINISH
               and report.converged]
