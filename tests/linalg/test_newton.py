"""The generic Newton (gyroshell.linalg.newton) on toy problems with known exact answers.

- a 1-D obstacle problem −u'' = −8, u(0) = u(1) = 0, u >= −c: the contact set is
  [√c/2, 1 − √c/2] and u = −c + 4 (x − √c/2)² left of it (tangency: u = −c, u' = 0 there);
  finite differences are exact for that quadratic, so the error comes from the contact edge
  alone and is O(h²);
- a strongly monotone complementarity problem r(z) = A z + z³ − b, z >= 0 on some
  unknowns, with a planted solution (some unknowns at the bound with r > 0): its solution is
  unique, so Newton must return the planted one;
- problems that need the line search: arctan(z) from 3 (plain Newton diverges), the cubic
  x³ − 2x + 2 from 0 (plain Newton cycles 0 → 1 → 0), and Dennis & Schnabel's system
  (x₁² + x₂² − 2, e^(x₁−1) + x₂³ − 2) from (2, 0.5) (plain Newton leaves the exponential's
  range), each damped to its known root;
- failures: z² + 1 (no root) raises ConvergenceError carrying the report and state.
"""

from __future__ import annotations

import doctest
import math
import pickle

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

import gyroshell.linalg.newton
from gyroshell import ConvergenceError, ParameterError
from gyroshell.linalg.newton import NewtonOptions, NewtonReport, newton
from tests.convergence import observed_order

#: NewtonOptions that turn the line search off: the first trial, α = 1, is the last.
PLAIN = NewtonOptions(min_step=1.0)


def reduced_solver(J, active):
    """solve(rhs) for J with the rows of ``active`` replaced by the identity (the
    NewtonProblem contract), by a sparse LU."""
    J = sp.csr_matrix(J, dtype=float)
    keep = sp.diags((~active).astype(float))
    lu = spla.splu((keep @ J + sp.diags(active.astype(float))).tocsc())
    return lu.solve


class Problem:
    """A small problem from a residual and a Jacobian function."""

    def __init__(self, residual, jacobian, *, lower=None, row_scale=1.0,
                 variable_scale=1.0) -> None:
        self._r, self._J = residual, jacobian
        self.lower, self.row_scale, self.variable_scale = lower, row_scale, variable_scale

    def residual(self, z):
        return self._r(z)

    def linearize(self, z, active):
        J = self._J(z)
        return reduced_solver(J if sp.issparse(J) else np.atleast_2d(J), active)


def second_difference(n_intervals: int) -> sp.csr_matrix:
    """−d²/dx² on (0, 1) by central differences at the interior nodes, Dirichlet ends."""
    n, h = n_intervals - 1, 1.0 / n_intervals
    return sp.diags([-np.ones(n - 1), 2.0 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1],
                    format="csr") / h**2


def obstacle(n_intervals: int, depth: float) -> tuple[Problem, np.ndarray]:
    """The obstacle problem −u'' = −8, u >= −depth; and its interior nodes x."""
    A, h = second_difference(n_intervals), 1.0 / n_intervals
    x = np.arange(1, n_intervals) * h
    problem = Problem(lambda u: A @ u + 8.0, lambda u: A, lower=np.full(x.size, -depth),
                      row_scale=h**2)
    return problem, x


def obstacle_exact(x: np.ndarray, depth: float) -> tuple[np.ndarray, float]:
    """The obstacle problem's solution and the contact set's left end a = √c/2."""
    a = math.sqrt(depth) / 2.0
    gap = np.maximum(a - x, 0.0) + np.maximum(x - (1.0 - a), 0.0)
    return -depth + 4.0 * gap**2, a


class TestObstacle:
    DEPTH = 4.0 / 9.0          # contact set [1/3, 2/3]
    # N = 10·4^k: 1/3 sits at the same fraction of a cell on every grid, so the error,
    # made at the contact edge only, scales exactly like h²
    GRIDS = (10, 40, 160, 640)

    def solve(self, n_intervals):
        problem, x = obstacle(n_intervals, self.DEPTH)
        z, report = newton(problem, np.zeros(x.size))
        return problem, x, z, report

    def test_contact_set_and_solution_converge_at_second_order(self):
        errors = []
        for n in self.GRIDS:
            _, x, z, report = self.solve(n)
            exact, a = obstacle_exact(x, self.DEPTH)
            contact = x[z == -self.DEPTH]
            h = 1.0 / n
            assert report.converged and report.reason == "step"
            assert abs(contact[0] - a) <= h and abs(contact[-1] - (1.0 - a)) <= h
            errors.append(np.max(np.abs(z - exact)))
            assert errors[-1] <= 1.0 * h**2
        assert observed_order([1.0 / n for n in self.GRIDS], errors) == pytest.approx(2.0,
                                                                                        abs=0.05)

    def test_complementarity_holds_at_the_solution(self):
        problem, x, z, report = self.solve(160)
        r = problem.residual(z) * problem.row_scale
        at_bound = z == -self.DEPTH
        assert np.all(z >= -self.DEPTH)
        assert np.all(r[at_bound] > 0.0)              # the contact force pushes up
        assert np.max(np.abs(r[~at_bound])) < 1e-12   # the equation holds off contact
        assert report.active_counts[-1] == np.count_nonzero(at_bound)

    def test_report_records_every_iteration(self):
        _, _, _, report = self.solve(40)
        k = report.iterations
        assert k >= 2 and report.factorizations >= k
        assert [len(report.step_norms), len(report.residual_norms),
                len(report.active_counts), len(report.alphas)] == [k] * 4
        assert all(0.0 < a <= 1.0 for a in report.alphas) and report.seconds > 0.0
        assert report.residual_norms[-1] < 1e-12 and report.active_counts[-1] > 0

    def test_nonmonotone_search_converges_where_a_monotone_one_stagnates(self):
        """On 2,560 cells the projected steps' contact edges raise the merit: a monotone
        search stalls, the nonmonotone default (memory 5) converges to the closed form."""
        problem, x = obstacle(2560, self.DEPTH)
        with pytest.raises(ConvergenceError, match="stagnated"):
            newton(problem, np.zeros(x.size), NewtonOptions(memory=1))
        z, report = newton(problem, np.zeros(x.size))
        assert np.max(np.abs(z - obstacle_exact(x, self.DEPTH)[0])) <= 2560.0**-2
        assert max(np.diff(report.residual_norms)) > 0.0      # the merit did rise

    def test_the_linearized_problems_own_active_set_solves_a_linear_obstacle(self):
        """The obstacle problem is linear: the step whose active set is consistent with
        its own linearization (the primal–dual rule on the linearization, the step that
        Newton adds where its projected path stalls) is its solution. From u = 0 on 40
        cells it lands on the closed form, contact set and all."""
        from gyroshell.linalg.newton import _factored_step, _set_step, _Setup

        problem, x = obstacle(40, self.DEPTH)
        setup = _Setup(problem, x.size, NewtonOptions())
        it = setup.iterate(np.zeros(x.size))
        report = NewtonReport()
        reduced, _ = _factored_step(setup, it, it.active, report)
        dz, active, _ = _set_step(setup, it, reduced, report)
        exact, _ = obstacle_exact(x, self.DEPTH)
        np.testing.assert_allclose(it.z + dz, exact, rtol=0, atol=40.0**-2)
        solved, _ = newton(problem, np.zeros(x.size))
        assert np.array_equal(active, solved == -self.DEPTH)      # the discrete contact set
        np.testing.assert_allclose(it.z + dz, solved, rtol=0, atol=1e-12)
        assert 2 <= report.factorizations <= 1 + NewtonOptions().max_set_updates

    def test_log_gets_one_line_per_iteration(self):
        problem, x = obstacle(40, self.DEPTH)
        lines = []
        _, report = newton(problem, np.zeros(x.size), log=lines.append)
        assert len(lines) == report.iterations and lines[0].startswith("Newton 1: step")


class TestComplementarity:
    """r(z) = A z + z³ − b, A tridiagonal SPD: r is strongly monotone, so the
    complementarity problem has one solution, the planted z*."""

    N = 12
    AT_BOUND = (0, 3, 4, 8)                  # z* = 0 there, with r(z*) = MULTIPLIERS > 0
    MULTIPLIERS = (0.5, 1.0, 2.0, 0.25)
    UNBOUNDED = (10, 11)                     # lower = −inf: z* < 0 allowed

    def planted(self):
        rng = np.random.default_rng(7)
        z = rng.uniform(0.5, 2.0, self.N)
        z[list(self.AT_BOUND)] = 0.0
        z[list(self.UNBOUNDED)] = -rng.uniform(0.5, 2.0, len(self.UNBOUNDED))
        mu = np.zeros(self.N)
        mu[list(self.AT_BOUND)] = self.MULTIPLIERS
        A = sp.diags([-np.ones(self.N - 1), 4.0 * np.ones(self.N), -np.ones(self.N - 1)],
                     [-1, 0, 1], format="csr")
        b = A @ z + z**3 - mu
        lower = np.zeros(self.N)
        lower[list(self.UNBOUNDED)] = -np.inf
        problem = Problem(lambda v: A @ v + v**3 - b, lambda v: A + sp.diags(3.0 * v**2),
                          lower=lower)
        return problem, z, mu

    @pytest.mark.parametrize("start", ["ones", "zeros", "random"])
    def test_newton_returns_the_planted_solution(self, start):
        problem, z_star, mu = self.planted()
        z0 = {"ones": np.ones(self.N), "zeros": np.zeros(self.N),
              "random": np.random.default_rng(3).uniform(-3.0, 3.0, self.N)}[start]
        z, report = newton(problem, z0)
        np.testing.assert_allclose(z, z_star, rtol=0, atol=1e-12)
        np.testing.assert_allclose(problem.residual(z), mu, rtol=0, atol=1e-12)
        assert report.active_counts[-1] == len(self.AT_BOUND)


def arctan_problem():
    return Problem(np.arctan, lambda z: np.diag(1.0 / (1.0 + z**2)))


def cubic_problem():
    return Problem(lambda x: x**3 - 2.0 * x + 2.0, lambda x: np.diag(3.0 * x**2 - 2.0))


def dennis_schnabel_problem():
    """Dennis & Schnabel's example 6.5.1 (roots (1, 1) and one near (−0.71, 1.22))."""
    return Problem(lambda z: np.array([z[0]**2 + z[1]**2 - 2.0, np.exp(z[0] - 1.0)
                                       + z[1]**3 - 2.0]),
                   lambda z: np.array([[2.0 * z[0], 2.0 * z[1]],
                                       [np.exp(z[0] - 1.0), 3.0 * z[1]**2]]))


class TestDamping:
    def test_arctan_from_3_diverges_plain_and_converges_damped(self):
        with pytest.raises(ConvergenceError) as plain:
            newton(arctan_problem(), [3.0], PLAIN)
        steps = plain.value.report.step_norms
        assert np.all(np.diff(steps) > 0)      # |z| grows every step
        z, report = newton(arctan_problem(), [3.0])
        assert abs(z[0]) < 1e-12 and report.alphas[0] < 1.0

    def test_cubic_from_0_cycles_plain_and_converges_damped(self):
        with pytest.raises(ConvergenceError, match="did not converge in 50"):
            newton(cubic_problem(), [0.0], PLAIN)
        # Cardano: the real root of x³ + p x + q, p = −2, q = 2
        s = math.sqrt(1.0 - 8.0 / 27.0)
        root = np.cbrt(-1.0 + s) + np.cbrt(-1.0 - s)
        z, _ = newton(cubic_problem(), [0.0])
        assert z[0] == pytest.approx(root, abs=1e-14)

    def test_dennis_schnabel_system_fails_plain_and_converges_damped(self):
        with pytest.raises(ConvergenceError):
            newton(dennis_schnabel_problem(), [2.0, 0.5], PLAIN)
        z, report = newton(dennis_schnabel_problem(), [2.0, 0.5])
        np.testing.assert_allclose(z, [1.0, 1.0], rtol=0, atol=1e-14)
        assert min(report.alphas) < 1.0

    def test_step_limit_keeps_the_iterate_in_the_residual_domain(self):
        class Log(Problem):
            def step_limit(self, z, dz):      # z may shrink to no less than a fifth
                shrink = dz < 0
                return float(np.min(-0.8 * z[shrink] / dz[shrink], initial=1.0))

        problem = Log(np.log, lambda z: np.diag(1.0 / z))
        z, report = newton(problem, [10.0])
        assert z[0] == pytest.approx(1.0, abs=1e-14)
        # the first Newton step is −z ln z = −10 ln 10; the limit is 0.8 z / (z ln z)
        assert report.alphas[0] == pytest.approx(0.8 / math.log(10.0))

    def test_non_finite_trials_are_cut_without_a_step_limit(self):
        z, report = newton(Problem(np.log, lambda z: np.diag(1.0 / z)), [10.0])
        assert z[0] == pytest.approx(1.0, abs=1e-14) and report.alphas[0] < 0.5


class TestStopping:
    def test_residual_tol_stops_early(self):
        z, report = newton(arctan_problem(), [3.0], NewtonOptions(residual_tol=1e-3))
        assert report.reason == "residual" and abs(np.arctan(z[0])) <= 1e-3

    def test_a_start_within_residual_tol_takes_no_iteration(self):
        z, report = newton(arctan_problem(), [1e-9], NewtonOptions(residual_tol=1e-6))
        assert report.iterations == 0 and report.converged and z[0] == 1e-9

    def test_noise_floor_ends_a_solve_its_tolerance_cannot(self):
        """A residual with round-off-like noise of 1e-10 (varying from one ulp to the next):
        steps cannot fall below ~1e-10, under tol = 1e-13 without the noise hook."""
        amplitude = 1e-10

        class Noisy(Problem):
            def noise(self, z):
                return amplitude * math.sqrt(z.size)

        def residual(z):
            return z - 1.0 + amplitude * np.sin(1e15 * z)

        options = NewtonOptions(tol=1e-13, max_iterations=20)
        with pytest.raises(ConvergenceError, match="did not converge in 20"):
            newton(Problem(residual, lambda z: np.eye(z.size)), np.zeros(3), options)
        z, report = newton(Noisy(residual, lambda z: np.eye(z.size)), np.zeros(3), options)
        assert report.reason == "round-off" and np.max(np.abs(z - 1.0)) <= 2 * amplitude

    def test_per_row_noise_ends_a_solve_whose_weak_unknown_only_noise_moves(self):
        """diag(1, s) z = (1, s) with s = 1e-9 and round-off-like noise of 1e-12 in each
        row: the second unknown's steps stay near 1e-12 / s = 1e-3, above round_off_step,
        so a scalar floor never ends the solve; the rows' floors (their noise step) do,
        and the well-held unknown is exact to the noise."""
        amplitude, s = 1e-12, 1e-9
        A = np.diag([1.0, s])

        def residual(z):
            return A @ z - np.array([1.0, s]) + amplitude * np.sin(1e15 * z)

        class Scalar(Problem):
            def noise(self, z):
                return amplitude * math.sqrt(2.0)

        class Rows(Problem):
            def noise(self, z):
                return np.full(2, amplitude)

        options = NewtonOptions(tol=1e-13, max_iterations=20)
        with pytest.raises(ConvergenceError, match="did not converge in 20"):
            newton(Scalar(residual, lambda z: A), np.zeros(2), options)
        z, report = newton(Rows(residual, lambda z: A), np.zeros(2), options)
        assert report.reason == "round-off"
        assert abs(z[0] - 1.0) <= 2 * amplitude and abs(z[1] - 1.0) <= 10 * amplitude / s

    def test_clip_step_limits_each_unknown_before_the_line_search(self):
        """arctan(z) = 0 from 3 with every change clipped to 1: the first step is 1
        (plain Newton's is −12.5), and the root is still found."""
        class Clipped(Problem):
            def clip_step(self, z, dz):
                return np.clip(dz, -1.0, 1.0)

        z, report = newton(Clipped(np.arctan, lambda z: np.diag(1.0 / (1.0 + z**2))), [3.0])
        assert report.converged and abs(z[0]) < 1e-12
        assert report.step_norms[0] <= 1.0 + 1e-15

    def test_a_clipped_step_that_does_not_descend_is_searched_unclipped(self,
                                                                         monkeypatch):
        """r = A z − b, A = [[1, 1000], [0, 1]], z* = (−9990, 10), from 0 with z₁'s change
        clipped to 1: the clipped step (−9990, 1) raises r₀ by 8,990 α (the merit's slope
        along it is +89,890), so every trial is rejected down to the smallest α; searched
        unclipped, Newton's whole step lands on z* (the first iteration). Without that
        alternative (UNCLIPPED_ALPHA 0) the run stagnates."""
        import gyroshell.linalg.newton as module

        A = np.array([[1.0, 1000.0], [0.0, 1.0]])
        b = A @ np.array([-9990.0, 10.0])

        class Clipped(Problem):
            def clip_step(self, z, dz):
                return np.array([dz[0], np.clip(dz[1], -1.0, 1.0)])

        problem = Clipped(lambda z: A @ z - b, lambda z: A)
        z, report = newton(problem, np.zeros(2))
        assert report.converged and report.alphas[0] == 1.0
        assert report.residual_norms[0] < 1e-9 * np.linalg.norm(b)    # z* in one step
        np.testing.assert_allclose(z, [-9990.0, 10.0], rtol=1e-12)
        monkeypatch.setattr(module, "UNCLIPPED_ALPHA", 0.0)
        with pytest.raises(ConvergenceError, match="stagnated"):
            newton(problem, np.zeros(2))

    def test_a_report_passed_in_adds_the_iterations_up(self):
        report = NewtonReport()
        _, report = newton(arctan_problem(), [3.0], report=report)
        first = report.iterations
        _, report = newton(cubic_problem(), [0.0], report=report)
        assert report.iterations > first and len(report.alphas) == report.iterations


class TestChord:
    """Chord steps (``chord_step`` > 0) reuse the last factorization near the solution."""

    OPTIONS = NewtonOptions(chord_step=0.5)

    class Counted(Problem):
        """A problem that records the iteration of each ``linearize`` call."""

        def __init__(self, problem: Problem) -> None:
            super().__init__(problem._r, problem._J, lower=problem.lower)
            self.calls = 0

        def linearize(self, z, active):
            self.calls += 1
            return super().linearize(z, active)

    def test_chord_steps_reach_the_planted_solution_with_fewer_factorizations(self):
        problem, z_star, mu = TestComplementarity().planted()
        counted = self.Counted(problem)
        z, report = newton(counted, np.ones(z_star.size), self.OPTIONS)
        # chord steps converge linearly, each at least chord_contraction (1/4) of the last:
        # the error after a last step below tol is below tol / 3
        tol = self.OPTIONS.tol
        np.testing.assert_allclose(z, z_star, rtol=0, atol=tol / 3.0)
        np.testing.assert_allclose(problem.residual(z), mu, rtol=0, atol=10.0 * tol)
        assert counted.calls == report.factorizations < report.iterations
        _, plain = newton(problem, np.ones(z_star.size))
        assert plain.factorizations == plain.iterations

    @pytest.mark.parametrize("case", ["arctan", "planted"])
    def test_every_chord_step_follows_a_small_whole_step_and_contracts(self, case):
        """An iteration without a factorization is a chord step: the step before it was
        whole and below chord_step, and it shrinks the step by chord_contraction."""
        if case == "arctan":
            problem, z0, exact = arctan_problem(), np.array([3.0]), np.zeros(1)
        else:
            problem, exact, _ = TestComplementarity().planted()
            z0 = np.ones(exact.size)
        counted = self.Counted(problem)
        calls = []
        z, report = newton(counted, z0, self.OPTIONS,
                           log=lambda line: calls.append(counted.calls))
        np.testing.assert_allclose(z, exact, rtol=0, atol=self.OPTIONS.tol / 3.0)
        steps, alphas = report.step_norms, report.alphas
        chord = [k for k in range(1, len(calls)) if calls[k] == calls[k - 1]]
        assert chord, "no chord step taken"
        for k in chord:
            assert alphas[k - 1] == 1.0 and steps[k - 1] < self.OPTIONS.chord_step
            assert steps[k] <= self.OPTIONS.chord_contraction * steps[k - 1]


class TestFailure:
    def test_no_root_raises_with_the_report_and_state(self):
        problem = Problem(lambda z: z**2 + 1.0, lambda z: np.diag(2.0 * z))
        with pytest.raises(ConvergenceError, match="scaled residual") as failure:
            newton(problem, [0.3])
        exc = failure.value
        assert exc.report.iterations <= NewtonOptions().max_iterations
        assert not exc.report.converged and exc.report.reason in ("stagnation",
                                                                  "max_iterations")
        assert exc.state.shape == (1,) and exc.report.residual_norms[-1] >= 1.0
        assert "try" in str(exc) and "unknowns at their bound" in str(exc)
        again = pickle.loads(pickle.dumps(exc))      # studies send errors across processes
        assert again.report == exc.report and str(again) == str(exc)

    def test_a_singular_jacobian_is_a_non_finite_step(self):
        problem = Problem(lambda z: z**2 + 1.0, lambda z: np.diag(2.0 * z))
        with pytest.raises(ConvergenceError, match="not finite") as failure:
            newton(problem, [0.0])
        assert failure.value.report.reason == "non-finite"


class TestValidation:
    @pytest.mark.parametrize("field, value, message", [
        ("tol", 0.0, "tol must be > 0"),
        ("armijo", 0.5, r"armijo must be in \(0, 0.5\)"),
        ("min_step", 0.0, r"min_step must be in \(0, 1\]"),
        ("memory", 0, "memory must be an integer >= 1"),
        ("max_iterations", 2.5, "max_iterations must be an integer"),
        ("residual_tol", -1.0, "residual_tol must be >= 0"),
        ("chord_step", -0.1, "chord_step must be >= 0"),
        ("chord_contraction", 1.0, r"chord_contraction must be in \(0, 1\)"),
    ])
    def test_options(self, field, value, message):
        with pytest.raises(ParameterError, match=message):
            NewtonOptions(**{field: value})

    def test_problem_and_start(self):
        good = arctan_problem()
        with pytest.raises(ParameterError, match="problem.lower must be None or a vector"):
            newton(Problem(np.arctan, np.eye, lower=np.zeros(3)), [1.0, 2.0])
        with pytest.raises(ParameterError, match="problem.row_scale must be > 0"):
            newton(Problem(np.arctan, np.eye, row_scale=-1.0), [1.0])
        with pytest.raises(ParameterError, match="z0 must be a non-empty vector"):
            newton(good, [[1.0]])
        with pytest.raises(ParameterError, match="z0 must give a finite residual"):
            newton(Problem(np.log, np.eye), [-1.0])
        with pytest.raises(ParameterError, match="options must be a NewtonOptions"):
            newton(good, [1.0], {"tol": 1e-8})


def test_docstring_example():
    result = doctest.testmod(gyroshell.linalg.newton)
    assert result.attempted > 0 and result.failed == 0
