"""The continuation driver (gyroshell.linalg.continuation).

The Bratu problem −u'' = λ e^u, u(0) = u(1) = 0 has on its lower branch the closed form
u(x) = −2 ln(cosh((x − 1/2) θ/2) / cosh(θ/4)), θ the smaller root of θ = √(2λ) cosh(θ/4)
(the branch ends at λ_c ≈ 3.5138). Its central-difference solution converges to it at
second order. With a budget of STAGE_ITERATIONS Newton iterations per solve (a stage that
needs more has left the neighbourhood of its start), the direct solve at λ = 3.5 from u = 0
fails, while continuation in λ, and pseudo-time continuation, reach it. The step
controller's cuts and growth are checked on a synthetic family whose stages converge
exactly when the step is short enough.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.optimize import brentq

from gyroshell import ConvergenceError, ParameterError
from gyroshell.linalg.continuation import StepController, continuation
from gyroshell.linalg.newton import NewtonOptions, NewtonReport, newton
from tests.convergence import observed_order

LAMBDA = 3.5
#: Newton iterations per solve: from u = 0 at λ = 3.5, Newton needs more.
STAGE_ITERATIONS = 6
BUDGET = NewtonOptions(max_iterations=STAGE_ITERATIONS)


class Bratu:
    """−u'' − λ e^u at the interior nodes of n_intervals cells; with ``pseudo_time`` s and
    ``previous`` u⁰, the implicit pseudo-time step (u − u⁰)/s − u'' − λ e^u."""

    lower = None
    variable_scale = 1.0

    def __init__(self, n_intervals: int, lam: float, pseudo_time: float | None = None,
                 previous: np.ndarray | None = None) -> None:
        n, h = n_intervals - 1, 1.0 / n_intervals
        self.A = sp.diags([-np.ones(n - 1), 2.0 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1],
                          format="csc") / h**2
        self.lam, self.row_scale = lam, h**2
        self.inverse_s = 0.0 if pseudo_time is None else 1.0 / pseudo_time
        self.previous = np.zeros(n) if previous is None else previous

    def residual(self, u):
        return self.inverse_s * (u - self.previous) + self.A @ u - self.lam * np.exp(u)

    def linearize(self, u, active):
        J = self.A + sp.diags(self.inverse_s - self.lam * np.exp(u))
        return spla.splu(J.tocsc()).solve


def bratu_exact(x: np.ndarray, lam: float) -> np.ndarray:
    """The lower branch's closed form."""
    theta_c = 4.798714560            # the fold: θ = 4 coth(θ/4); the lower root lies below
    theta = brentq(lambda t: t - math.sqrt(2.0 * lam) * math.cosh(t / 4.0), 1e-12, theta_c)
    return -2.0 * np.log(np.cosh((x - 0.5) * theta / 2.0) / np.cosh(theta / 4.0))


def solve_bratu(n_intervals: int):
    """solve_at for continuation in λ."""
    def solve_at(lam, u):
        return newton(Bratu(n_intervals, lam), u, BUDGET)
    return solve_at


def nodes(n_intervals: int) -> np.ndarray:
    return np.arange(1, n_intervals) / n_intervals


class TestBratu:
    GRIDS = (50, 100, 200)

    def test_direct_solve_fails_within_the_budget(self):
        with pytest.raises(ConvergenceError, match=f"did not converge in {STAGE_ITERATIONS}"):
            solve_bratu(100)(LAMBDA, np.zeros(99))

    def test_continuation_in_lambda_reaches_the_closed_form_at_second_order(self):
        errors = []
        controller = StepController(mode="linear", initial=0.5, minimum=0.01)
        for n in self.GRIDS:
            u, stages = continuation(solve_bratu(n), 0.0, LAMBDA, np.zeros(n - 1),
                                     controller=controller)
            assert stages[-1][0] == LAMBDA and stages[-1][1].converged
            errors.append(np.max(np.abs(u - bratu_exact(nodes(n), LAMBDA))))
        assert observed_order([1.0 / n for n in self.GRIDS], errors) == pytest.approx(2.0,
                                                                                        abs=0.1)

    def test_cut_and_growth_on_the_lambda_path(self):
        """Straight to λ = 3.5 fails; each failure halves the step from the last λ reached,
        each easy stage (<= 4 iterations) doubles it, the last stage is at the target."""
        controller = StepController(mode="linear", initial=LAMBDA, minimum=0.01)
        _, stages = continuation(solve_bratu(100), 0.0, LAMBDA, np.zeros(99),
                                 controller=controller)
        reached, step = 0.0, LAMBDA
        for value, report in stages[1:]:
            assert value == pytest.approx(min(reached + step, LAMBDA))
            if report.converged:
                reached = value
                step *= 2.0 if report.iterations <= controller.easy_iterations else 1.0
            else:
                step = (value - reached) / 2.0
        assert not stages[1][1].converged and stages[-1][1].converged and reached == LAMBDA
        assert all(r.iterations <= STAGE_ITERATIONS for _, r in stages)

    def test_pseudo_time_reaches_the_steady_state(self):
        """The parameter is the pseudo-time step s, geometric from 1e-2 up to 1e8; from
        s = STEADY on, the stage is the steady problem itself (s = ∞)."""
        n, steady = 100, 1e8

        def solve_at(s, u):
            step = None if s >= steady else s
            return newton(Bratu(n, LAMBDA, pseudo_time=step, previous=u), u, BUDGET)

        controller = StepController(initial=2.0, growth=2.0, minimum=1.01)
        u, stages = continuation(solve_at, 1e-2, steady, np.zeros(n - 1),
                                 controller=controller)
        values = [v for v, r in stages if r.converged]
        assert np.all(np.diff(values) > 0) and values[-1] == steady
        error = np.max(np.abs(u - bratu_exact(nodes(n), LAMBDA)))
        assert error < 10.0 / n**2       # the grid's O(h²) (about 6 h² on this problem)
        assert all(r.iterations <= STAGE_ITERATIONS for _, r in stages)


class Synthetic:
    """A family whose stage at v, from the state s (the last value reached), converges
    iff |v − s| <= 1, in 1 iteration if |v − s| <= 0.75 and 3 otherwise."""

    def __init__(self) -> None:
        self.calls = []

    def __call__(self, value, state):
        self.calls.append(value)
        distance = abs(value - state)
        if distance > 1.0 + 1e-12:
            report = NewtonReport(iterations=2, reason="max_iterations")
            exc = ConvergenceError(f"stage {value} failed")
            exc.report = report
            raise exc
        return value, NewtonReport(iterations=1 if distance <= 0.75 + 1e-12 else 3,
                                   converged=True)


class TestController:
    def test_linear_trace_of_cuts_and_growth(self):
        """Steps 1.5 (fail), 0.75 (ok, easy: 1.5), 1.5 (fail), 0.75 ... by hand."""
        family = Synthetic()
        controller = StepController(mode="linear", initial=1.5, easy_iterations=1,
                                    minimum=0.1)
        state, stages = continuation(family, 0.0, 3.0, 0.0, controller=controller)
        assert [v for v, _ in stages] == [0.0, 1.5, 0.75, 2.25, 1.5, 3.0, 2.25, 3.0]
        assert [r.converged for _, r in stages] == [True, False, True, False, True, False,
                                                    True, True]
        assert state == 3.0

    @pytest.mark.parametrize("start, target, expected", [
        (1.0, 16.0, [1.0, 2.0, 8.0, 16.0]),       # ratios 2, 4 (= 2²), then the target
        (16.0, 1.0, [16.0, 8.0, 2.0, 1.0]),       # the same downwards
        (-1.0, -16.0, [-1.0, -2.0, -8.0, -16.0]),
    ])
    def test_geometric_steps_grow_by_powers_of_the_ratio(self, start, target, expected):
        def easy(value, state):
            return value, NewtonReport(iterations=1, converged=True)

        _, stages = continuation(easy, start, target, None,
                                 controller=StepController(initial=2.0, growth=2.0))
        assert [v for v, _ in stages] == pytest.approx(expected)

    def test_giving_up_below_the_floor_names_the_last_value_reached(self):
        def fails_beyond_zero(value, state):
            if value != 0.0:
                raise ConvergenceError("no")
            return f"solved at {value}", NewtonReport(iterations=1, converged=True)

        controller = StepController(mode="linear", initial=1.0, minimum=0.1)
        with pytest.raises(ConvergenceError, match="stopped at 0: the stage at 0.125") as e:
            continuation(fails_beyond_zero, 0.0, 3.0, "first", controller=controller)
        # steps 1, 0.5, 0.25, 0.125 fail; the next, 0.0625, is below the floor 0.1
        assert [v for v, _ in e.value.stages] == [0.0, 1.0, 0.5, 0.25, 0.125]
        assert e.value.value == 0.0 and e.value.state == "solved at 0.0"

    def test_stage_cap(self):
        def hard(value, state):
            return value, NewtonReport(iterations=10, converged=True)

        controller = StepController(mode="linear", initial=0.1, minimum=0.01, max_stages=5)
        with pytest.raises(ConvergenceError, match="stopped at 0.4 after 5 stages"):
            continuation(hard, 0.0, 1.0, 0.0, controller=controller)

    def test_first_stage_failure(self):
        def never(value, state):
            raise ConvergenceError("no")

        with pytest.raises(ConvergenceError, match="the first stage, at 2, failed") as e:
            continuation(never, 2.0, 3.0, 0.0)
        assert e.value.value is None and e.value.state == 0.0

    @pytest.mark.parametrize("kwargs, message", [
        ({"mode": "log"}, "mode must be one of geometric, linear"),
        ({"initial": 1.0}, "initial must be > 1"),
        ({"mode": "linear", "initial": 0.5, "minimum": 1.0}, "minimum <= initial"),
        ({"cut": 1.0}, r"cut must be in \(0, 1\)"),
        ({"growth": 0.5}, "growth must be >= 1"),
    ])
    def test_controller_validation(self, kwargs, message):
        with pytest.raises(ParameterError, match=message):
            StepController(**kwargs)

    def test_geometric_path_through_zero_is_refused(self):
        with pytest.raises(ParameterError, match="nonzero and of one sign"):
            continuation(lambda v, s: (s, NewtonReport()), 0.0, 1.0, None)
