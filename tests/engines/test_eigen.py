"""Quadratic eigen-solver: closed forms (Navier, moving string), pairs, clusters, refusals."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp
from closed_forms import navier_frequency
from conftest import moving_string
from convergence import observed_order

from gyroshell import ConvergenceError, Grid, ParameterError, TapeModel, TapeParameters
from gyroshell.engines.eigen import modes, relative_residuals

# Every test here runs on each factorization back-end (CHOLMOD and SuperLU).
pytestmark = pytest.mark.usefixtures("every_factorization")

WIDTH = TapeParameters().width


def _model(**kw) -> TapeModel:
    kw.setdefault("spacing", WIDTH / 8)
    return TapeModel(TapeParameters(**kw))


# ----- Navier: all sides simply supported, V = 0 ------------------------------------------
class TestNavier:
    """ω_mn² = (D(α² + β²)² + Tα² + k)/ρ; the discrete operator has exact sin·sin modes."""

    ratio = 2.0

    def exact_lowest(self, p: TapeParameters, count: int) -> np.ndarray:
        w = sorted(navier_frequency(p, m, n) for m in range(1, 12) for n in range(1, 12))
        return np.array(w[:count])

    def errors(self, count: int = 3):
        base = TapeParameters(edges="simply-supported", length_ratio=self.ratio,
                              spacing=WIDTH / 8, foundation_stiffness=1e6)
        grid = Grid.from_parameters(base)
        steps, errs = [], []
        for _ in range(3):
            res = modes(TapeModel(base, grid), 0.0, count)
            exact = self.exact_lowest(base, count)
            errs.append(np.abs(res.omega - exact) / exact)
            steps.append(grid.hx)
            grid = grid.refined()
        return np.array(steps), np.array(errs)

    def test_second_order(self):
        steps, errs = self.errors()
        for j in range(errs.shape[1]):
            assert observed_order(steps, errs[:, j]) == pytest.approx(2.0, abs=0.1)
        assert errs[-1].max() < 1e-2

    def test_mode_shape_is_sin_sin(self):
        p = TapeParameters(edges="simply-supported", length_ratio=self.ratio,
                           spacing=WIDTH / 8, foundation_stiffness=1e6)
        model = TapeModel(p)
        res = modes(model, 0.0, 1)
        g = model.grid
        exact = g.from_field(np.sin(np.pi * g.X / g.length) * np.sin(np.pi * g.Y / g.width))
        phi = res.vectors[:, 0]
        cos = abs(np.vdot(exact, phi)) / (np.linalg.norm(exact) * np.linalg.norm(phi))
        assert cos == pytest.approx(1.0, abs=1e-10)
        assert res.fields.shape == g.shape + (1,)
        assert np.iscomplexobj(res.field(0))


# ----- moving string (Wickert & Mote 1990) --------------------------------------------------
def test_width_uniform_subspace_is_invariant():
    red = moving_string(16)
    full, P = red.full, red.P
    md = full.mass_diagonal
    for op, op_r in ((full.K(30.0), red.K(30.0)), (full.G(30.0), red.G(30.0))):
        # op P = M P M_r⁻¹ op_r: the image of a uniform field is a uniform force density
        lhs = (op @ P).toarray()
        rhs = (sp.diags(md) @ P @ sp.diags(1 / red.mass_diagonal) @ op_r).toarray()
        assert np.abs(lhs - rhs).max() <= 1e-12 * np.abs(lhs).max()


def test_moving_string_second_order():
    p = moving_string(16).params
    c, L = p.string_speed, p.length
    V = 0.5 * c
    exact = np.array([n * np.pi * c * (1 - V**2 / c**2) / L for n in (1, 2, 3)])
    steps, errs = [], []
    for nx in (32, 64, 128):
        red = moving_string(nx)
        res = modes(red, V, 3)
        errs.append(np.abs(res.omega - exact) / exact)
        steps.append(L / nx)
    errs = np.array(errs)
    for j in range(3):
        assert observed_order(steps, errs[:, j]) == pytest.approx(2.0, abs=0.1)
    assert errs[-1].max() < 1e-3


# ----- structure: pairs, agreement of shifts, clusters --------------------------------------
@pytest.mark.slow
def test_pairs_and_shift_independence():
    model = _model(length_ratio=3.0)
    auto = modes(model, 60.0, 5)
    real = modes(model, 60.0, 5, sigma=0)   # 2·count eigenvalues, checked as ±iω pairs
    assert np.all(np.diff(auto.omega) >= 0)
    assert np.allclose(auto.omega, real.omega, rtol=1e-10)
    assert np.all(auto.eigenvalues.real == 0) and np.all(real.eigenvalues.real == 0)
    assert auto.info["pair_defect"] < 1e-8 and real.info["pair_defect"] < 1e-8
    assert auto.residuals.max() < 1e-10
    # the −iω partner: φ̄ solves the conjugate problem
    phi, lam = auto.vectors[:, 0], auto.eigenvalues[0]
    back = relative_residuals(model, 60.0, np.array([np.conj(lam)]), np.conj(phi)[:, None])
    assert back[0] < 1e-10
    assert np.allclose(auto.period, 2 * np.pi / auto.omega)
    assert np.allclose(auto.frequency, auto.omega / (2 * np.pi))


def test_gyroscopic_mode_is_complex_travelling():
    res = modes(_model(length_ratio=2.0), 60.0, 1)
    phi = res.vectors[:, 0]
    # a standing (real) mode at V = 0 becomes complex (travelling) at V > 0
    assert np.linalg.norm(phi.imag) > 0.05 * np.linalg.norm(phi.real)


@pytest.mark.slow
def test_clustered_long_tape_converges():
    model = _model(length_ratio=19.0)
    p = model.params
    res = modes(model, 0.0, 12)
    wf = p.foundation_frequency
    assert res.info["below_shift"] == 0          # certified: nothing below the shift
    assert np.all(res.omega > wf)                 # K(0) >= k W, so ω >= √(k/ρ)
    assert res.omega[-1] / wf - 1 < 4e-3          # twelve modes within 0.4 % of √(k/ρ)
    assert res.omega[1] / res.omega[0] - 1 < 1e-5  # a near-degenerate pair, resolved
    assert res.residuals.max() < 1e-10
    ref = modes(model, 0.0, 12, sigma=0)
    assert np.allclose(res.omega, ref.omega, rtol=1e-10)


def test_explicit_complex_shift_inside_spectrum():
    model = _model(length_ratio=3.0)
    ref = modes(model, 40.0, 6)
    mid = 0.5 * (ref.omega[1] + ref.omega[2])
    res = modes(model, 40.0, 6, sigma=1j * mid)
    assert res.info["below_shift"] == 2         # inertia counts the two below the shift
    assert np.allclose(res.omega, ref.omega, rtol=1e-10)


def test_supercritical_reports_divergence():
    model = _model(length_ratio=2.0)
    res = modes(model, 110.0, 3)
    assert res.supercritical
    assert res.growth_rate.max() > 0
    assert np.all(res.eigenvalues.real >= 0) and np.all(res.eigenvalues.imag >= 0)
    assert res.residuals.max() < 1e-8
    assert np.isinf(res.period[res.omega == 0]).all()


# ----- refusals ------------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs, match", [
    ({"count": 0}, "count must be in"),
    ({"count": 10**6}, "count must be in"),
    ({"count": 2.5}, "count must be an integer"),
    ({"velocity": -1.0}, "velocity must be >= 0"),
    ({"velocity": math.nan}, "velocity must be finite"),
    ({"sigma": 1.0 + 2j}, "sigma must be 0 or purely imaginary"),
    ({"sigma": "low"}, "sigma must be 'auto'"),
    ({"tol": 2.0}, "tol must be in"),
    ({"ncv": 3}, "ncv must be in"),
    ({"ncv": "a"}, "ncv must be None or an integer"),
    ({"maxiter": 0}, "maxiter must be None or an integer >= 1"),
    ({"maxiter": 2.5}, "maxiter must be None or an integer, got 2.5"),
    ({"count": None}, "count must be an integer"),
    ({"estimate": -1.0}, "estimate must be >= 0 rad/s, got -1"),
    ({"start": "x"}, "start must be the Modes"),
    ({"velocity": 1e200}, "rho V\\^2 overflows"),
])
def test_refusals(kwargs, match):
    args = {"velocity": 0.0, "count": 2, **kwargs}
    with pytest.raises(ParameterError, match=match):
        modes(_model(length_ratio=1.0), **args)


def test_arpack_failure_is_a_convergence_error():
    with pytest.raises(ConvergenceError, match="ARPACK"):
        modes(_model(length_ratio=19.0), 0.0, 8, sigma=0, maxiter=1, ncv=20)


@pytest.mark.parametrize("velocity", [0.0, 50.0, 95.0])
def test_lanczos_and_arpack_agree(velocity):
    model = _model(length_ratio=6.0)
    lanczos = modes(model, velocity, 6, method="lanczos")
    arpack = modes(model, velocity, 6, method="arpack")
    assert lanczos.info["method"] == "lanczos" and arpack.info["method"] == "arpack"
    assert np.allclose(lanczos.omega, arpack.omega, rtol=1e-10, atol=0)
    assert lanczos.info["below_shift"] == arpack.info["below_shift"] == 0
    assert lanczos.residuals.max() < 1e-13


def test_count_above_the_limit_is_refused_quickly():
    from gyroshell.engines.eigen import max_count

    model = _model(length_ratio=19.0)
    limit = max_count(model.unknowns)
    with pytest.raises(ParameterError, match=rf"count must be in \[1, {limit}\]"):
        modes(model, 0.0, limit + 1)


@pytest.mark.parametrize("edges", ["free", "simply-supported"])
@pytest.mark.parametrize("nu", [-0.5, 0.0, 0.3, 0.49])
def test_bending_is_positive_semidefinite_so_K_is_definite_below_string_speed(edges, nu):
    """The stiffness floor takes A >= kW from the construction of A (Gram forms): check it."""
    from gyroshell.linalg.inertia import factor_inertia

    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8, edges=edges,
                                     poisson=nu))
    bending = model.A - sp.diags(model.params.k * model.grid.areas)
    shift = 1e-12 * abs(bending).sum(axis=0).max()
    assert factor_inertia(bending + shift * sp.identity(model.unknowns)).negatives == 0


def test_every_factorization_reaches_the_mirror_inertia_count(every_factorization):
    """The fixture's back-end reaches the antisymmetric half's inertia count too (it was
    CHOLMOD wherever cvxopt is installed, whatever the fixture said): the count reports
    which factorization made it."""
    model = _model(length_ratio=2.0)
    res = modes(model, 10.0, 4)
    assert res.info["factorization"] == every_factorization
    assert res.info["mirror"]["count_factorization"] == every_factorization
    assert res.info["mirror"]["antisymmetric_below"] >= res.info["mirror"]["antisymmetric"]


def test_use_factorization_is_read_at_call_time_and_restored(every_factorization):
    from gyroshell.linalg.factorization import resolve_factorization, use_factorization

    outside = resolve_factorization("auto")
    assert outside == every_factorization
    with use_factorization("superlu") as chosen:
        assert chosen == "superlu" == resolve_factorization("auto")
        assert resolve_factorization("cholmod") == "cholmod"   # an explicit choice stands
        assert modes(_model(length_ratio=2.0), 10.0, 2).info["factorization"] == "superlu"
    assert resolve_factorization("auto") == outside
    with pytest.raises(ParameterError, match="factorization must be one of"):
        with use_factorization("mumps"):
            pass


def test_solver_options_group_the_knobs_and_keywords_still_work():
    from gyroshell.linalg.qep import SolverOptions

    model = _model(length_ratio=2.0)
    by_keyword = modes(model, 20.0, 3, tol=1e-12, method="arpack", symmetry=False)
    grouped = modes(model, 20.0, 3, options=SolverOptions(tol=1e-12, method="arpack"),
                    symmetry=False)
    assert np.array_equal(by_keyword.eigenvalues, grouped.eigenvalues)
    assert grouped.info["method"] == "arpack"
    # a keyword knob replaces the one in options
    assert modes(model, 20.0, 3, options=SolverOptions(method="arpack"),
                 method="lanczos", symmetry=False).info["method"] == "lanczos"
    with pytest.raises(TypeError, match="unexpected keyword argument 'tolerance'"):
        modes(model, 20.0, 3, tolerance=1e-9)


@pytest.mark.parametrize("velocity", [0.0, 50.0])
def test_antisymmetric_half_is_solved_with_its_counts_factorization(velocity):
    """The antisymmetric half's modes come from Lanczos shifted at the count frequency ω̄
    with the count's own LDLᴴ (no second factorization): the same frequencies as the full
    problem, every one below ω̄ as many as counted, at round-off backward error."""
    model = _model(length_ratio=4.0, spacing=WIDTH / 12)
    halves = modes(model, velocity, 6)
    mirror = halves.info["mirror"]
    assert mirror["count_factor_solved"] is True and mirror["antisymmetric"] >= 1
    full = modes(model, velocity, 6, symmetry=False)
    assert halves.omega == pytest.approx(full.omega, rel=1e-11)
    assert halves.residuals.max() < 1e-14
    assert np.count_nonzero(halves.omega < mirror["count_frequency"]) >= 6


@pytest.mark.parametrize("velocity", [0.0, 50.0])
def test_the_joined_backward_errors_are_the_full_problems(velocity, monkeypatch):
    """The mirror path's backward errors, computed on the halves with the full matrices'
    norms, are ‖(λ²M + λG + K)φ‖₂ / ((|λ|²‖M‖₁ + |λ|‖G‖₁ + ‖K‖₁)‖φ‖₂) of the full
    problem recomputed from scratch (both round-off: they agree to its scatter), and the
    halves' structure is proved once per model (the first speed checks its own matrices,
    the second proves the family), not per speed."""
    import gyroshell.engines.eigen as eigen

    model = _model(length_ratio=4.0, spacing=WIDTH / 12)
    proofs = []
    proved = eigen.check_family
    monkeypatch.setattr(eigen, "check_family", lambda *a: proofs.append(1) or proved(*a))
    for speed in (velocity, velocity + 5.0, velocity + 10.0):
        halves = modes(model, speed, 6)
        assert "mirror" in halves.info
        full = relative_residuals(model, speed, halves.eigenvalues, halves.vectors)
        assert halves.residuals.max() < 1e-14 and full.max() < 1e-14
        assert halves.residuals == pytest.approx(full, rel=0.25, abs=1e-17)
        assert halves.info["max_residual"] == halves.residuals.max()
    assert len(proofs) == 2   # the two halves, once (at the second speed)


def test_a_previous_speed_without_antisymmetric_modes_below_tries_a_cholesky_first():
    """Continued from a speed whose antisymmetric half had no frequency below ω̄, the count
    at the next speed is first tried by a Cholesky of Q_a(iω̄) (its success proves the
    count zero). Right guess and wrong guess both give the full problem's frequencies and
    the true count (L_x/L_y = 8, two modes: none below ω̄ at 60 m/s, one at 40 m/s)."""
    model = _model(length_ratio=8.0)
    at_60 = modes(model, 60.0, 2)
    assert at_60.info["mirror"]["antisymmetric_below"] == 0
    for speed, below in ((62.0, 0), (40.0, 1)):
        continued = modes(model, speed, 2, start=at_60)
        mirror = continued.info["mirror"]
        assert mirror["antisymmetric_below"] == below == modes(model, speed, 2).info[
            "mirror"]["antisymmetric_below"]
        assert continued.omega == pytest.approx(modes(model, speed, 2, symmetry=False).omega,
                                                rel=1e-11)
        # the Cholesky proof stands where it succeeded (CHOLMOD only; SuperLU counts)
        assert mirror["count_by_cholesky"] == (below == 0 and mirror["count_factorization"]
                                               == "cholmod")
