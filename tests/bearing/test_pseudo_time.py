"""The pseudo-transient march (gyroshell.bearing.pseudo_time.pseudo_time_path): where the
steady solve at FINISH fails, pseudo-time marches on and the steady solve is tried
FINISH_RETRY times further, up to LAST_FINISH, and the march still ends at the state that
Newton reaches directly. The steady solve is made to fail below a chosen pseudo-time step
(a wrapper around the real one), so each branch of the march is exercised on a real
bearing: a 15° cylinder wrap at 4 m/s, the hard wall, the infinitely wide tape."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD

from gyroshell import ConvergenceError, TapeParameters
from gyroshell.bearing import BearingModel
from gyroshell.bearing.problem import SteadyProblem
from gyroshell.bearing.pseudo_time import FINISH, FINISH_RETRY, LAST_FINISH, pseudo_time_path
from gyroshell.bearing.steady import solve_steady
from gyroshell.linalg.newton import NewtonOptions, newton


@pytest.fixture(scope="module")
def case():
    model = BearingModel(TapeParameters(), FIRST_ORDER, velocity=4.0,
                         wrap_angle=math.radians(15.0), nx=200, infinitely_wide=True,
                         contact=HARD)
    reference = solve_steady(model)
    lifted = np.concatenate([np.full(model.n_u, 3.0 * reference.central_spacing),
                             np.full(model.n_p, model.air.ambient_pressure)])
    return model, reference, lifted


def _solver(model, steady_from):
    """solve(transient, state, limit) for pseudo_time_path whose steady solve fails
    unless the last pseudo-time step reached ``steady_from``; the pseudo-time steps taken
    and the steady attempts' last steps are recorded."""
    taken, attempts = [], []

    def solve(transient, state, limit):
        if transient is None:
            attempts.append(taken[-1])
            if taken[-1] < steady_from:
                raise ConvergenceError("steady solve refused by the test")
        else:
            taken.append(float(np.median(model.stiffness_diagonal / transient.c)))
        problem = SteadyProblem(model, transient=transient)
        return newton(problem, state, NewtonOptions(
            tol=1e-8 if transient is None else 1e-4, max_iterations=limit or 50))

    return solve, taken, attempts


def test_a_steady_solve_that_succeeds_at_finish_ends_the_march_there(case):
    """One steady solve, at FINISH: no pseudo-time step beyond it."""
    model, reference, lifted = case
    solve, taken, attempts = _solver(model, 0.0)
    z, steps = pseudo_time_path(model, lifted, solve)
    assert len(attempts) == 1 and max(taken) < FINISH and steps
    assert np.max(np.abs(z[:model.n_u] - reference.u)) < 1e-9 * reference.central_spacing


def test_the_march_goes_on_past_a_failed_steady_solve_to_the_same_state(case):
    """The steady solve refused until pseudo-time has passed 1e11: tried at 1e8 and 1e10
    (refused), then at 1e12 after steps beyond 1e11; the state is Newton's direct one."""
    model, reference, lifted = case
    solve, taken, attempts = _solver(model, 1e11)
    z, steps = pseudo_time_path(model, lifted, solve)
    assert attempts[0] < FINISH and attempts[-1] >= 1e11
    assert len(attempts) == 3 and max(steps) <= FINISH * FINISH_RETRY**2
    assert max(taken) >= 1e11 and max(steps) >= 1e11
    assert np.max(np.abs(z[:model.n_u] - reference.u)) < 1e-9 * reference.central_spacing


def test_a_steady_solve_that_never_succeeds_stops_the_march_at_the_last_finish(case):
    """Refused everywhere: pseudo-time marches past 1e14 but not past LAST_FINISH, and
    the steady solve's failure ends the path."""
    model, _, lifted = case
    solve, taken, attempts = _solver(model, math.inf)
    with pytest.raises(ConvergenceError, match="steady solve refused by the test"):
        pseudo_time_path(model, lifted, solve)
    assert FINISH * FINISH_RETRY**3 < max(taken) < LAST_FINISH
