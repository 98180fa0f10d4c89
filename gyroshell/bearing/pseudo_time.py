"""Pseudo-transient continuation: a path to the steady state for starts outside Newton's
basin.

Each stage is one backward-Euler step of pseudo-time size s (dimensionless) from the last
state reached, solved by the steady solve's Newton with the terms of :class:`PseudoTime`
in its residual; s grows geometrically along :func:`gyroshell.linalg.continuation.
continuation` (one step controller: a stage that fails is retried with a smaller step) up
to :data:`FINISH`, where the steady equations themselves are solved. Far from the steady
state the terms keep each stage inside Newton's basin; as s grows they vanish.

Where the steady solve at :data:`FINISH` fails, the march goes on at once, with
pseudo-time steps up to :data:`FINISH_RETRY` times further and the steady solve tried
there, until :data:`LAST_FINISH` (at most :data:`MARCH_STAGES` stages each time). The
tape's terms are each row's own diagonal c = diag K over s, and on a grid graded to fine
cells (a corner's, 25 nm beside 2 µm) c of those rows, ∝ D/Δ³, exceeds the stiffness of
the modes still relaxing (the tape's bending over its bending length ℓ, the film) by about
(ℓ/Δ)⁴: at s = 1e8 the terms still hold those nodes, and the steady solve from there
stagnates (measured: arcs of r_c = 1.4 mm wrapped on a 1 mm land, 4 m/s, reached after
pseudo-time steps up to 1e14). Retried at FINISH after shorter steps below it instead, as
the step controller would, it failed there again at 2.5e7, 5e7, 7e7 ... 9.2e7, 20 Newton
iterations each, and a march on from 9.2e7 stopped near 7e11.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..core.errors import ConvergenceError
from ..linalg.continuation import StepController, continuation
from .model import BearingModel

#: The first pseudo-time step (the pseudo-time terms are 1/s of each row's diagonal) ...
START = 0.1
#: ... and the last, where the steady equations themselves are solved (the pseudo-time
#: terms there would be 1e-8 of each row's diagonal) ...
FINISH = 1e8
#: ... or, where that steady solve fails, this many times further on, after pseudo-time
#: steps up to there, and so on up to LAST_FINISH (the terms there are below the
#: round-off of each row's diagonal: a steady solve that fails there fails the path).
FINISH_RETRY = 100.0
LAST_FINISH = 1e16
#: Most stages of each hundredfold march past FINISH: an easy march takes 3-4 (ratios 4,
#: 16, the cap); one that creeps, its stages failing by turns, is not relaxing slow modes,
#: and stops with the budget left to the next path (measured: the 1.4 mm wrapped arcs at
#: 4 m/s took 4, 9 and 4 stages from 1e8 to 1e14; a 3 mm land at 1 m/s crept from 1e8 at
#: ratios 1.1-1.2, 240 Newton iterations for 16x, where the speed's path takes 88).
MARCH_STAGES = 12
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
    steps, state, start, finish = [], z0, START, FINISH
    while True:
        steady = [True]     # whether the last stage at ``finish`` solved the steady equations

        def at(s, state, finish=finish, steady=steady):
            if s == finish:
                try:
                    out = solve(None, state, None)
                    steady[0] = True
                    return out
                except ConvergenceError:
                    if finish * FINISH_RETRY > LAST_FINISH:
                        raise
                    steady[0] = False           # march on: a pseudo-time step there
            if progress is not None:
                progress(f"pseudo-time step {s:.3g}")
            return solve(PseudoTime(model, state, s), state, STAGE_ITERATIONS)

        state, stages = continuation(at, start, finish, state, controller=StepController(
            initial=RATIO, growth=2.0, cut=0.5, minimum=MINIMUM_RATIO,
            maximum=MAXIMUM_RATIO, easy_iterations=EASY_ITERATIONS,
            **({} if start == START else {"max_stages": MARCH_STAGES})))
        # a later segment's first stage repeats the last one's step at its finish
        steps += [s for s, report in stages[0 if start == START else 1:]
                  if report is not None and report.converged
                  and not (steady[0] and s == finish)]
        if steady[0]:
            return state, steps
        start, finish = finish, finish * FINISH_RETRY
