"""Orthotropic tapes in every engine, against closed forms derived for orthotropic plates.

The tapes are strongly orthotropic (E_y/E_x = 0.5 and 2, G_xy independent of the other
constants), with soft foundations so that bending, not k, sets the answers and the free
edges' boundary layer is resolved by the coarse grids:

* all sides simply supported: Navier, ρω²_mn = D11α⁴ + 2(D12 + 2D66)α²β² + D22β⁴ + Tα² + k,
  and the Navier series of a uniform load;
* simply supported ends, free edges: Lévy, w = Y(y) sin(αx) with
  D22 Y⁗ − 2(D12 + 2D66)α²Y″ + (D11α⁴ + Tα² + k − ρω²)Y = q and the free-edge conditions
  D22 Y″ − D12α²Y = 0, D22 Y‴ − (D12 + 4D66)α²Y′ = 0 (tests/closed_forms.py), for the
  frequencies (roots of the edge determinant), the static deflection under a uniform load
  (a series of Lévy profiles) and the divergence (critical) speed of the lowest branch;
* the undamped trapezoidal Newmark run conserves energy and the gyroscopic eigen-solver
  gives real frequencies (±iω pairs) below the critical speed.
"""

from __future__ import annotations

import numpy as np
import pytest
from closed_forms import (
    levy_divergence_mu,
    levy_eigenvalues,
    levy_lowest,
    levy_profile_orthotropic,
    orthotropic_navier_frequency,
    orthotropic_navier_uniform,
)
from convergence import observed_order

from gyroshell import TapeModel, TapeParameters, march, modes, pressure_load, solve_static
from gyroshell.engines.critical import critical_speeds
from gyroshell.engines.divergence import divergence
from gyroshell.engines.eigen import relative_residuals

WIDTH = 6.35e-3
E_X, G_XY, NU_XY = 4.0e9, 1.0e9, 0.3
RATIOS = [0.5, 2.0]


def _tape(ratio: float, n: int, **changes) -> TapeParameters:
    """E_y = ratio × E_x, n intervals across; soft foundation and tension by default."""
    changes.setdefault("foundation_stiffness", 2.0e6)
    changes.setdefault("tension", 10.0)
    return TapeParameters(youngs_modulus=E_X, youngs_modulus_y=ratio * E_X,
                          shear_modulus=G_XY, poisson=NU_XY, spacing=WIDTH / n, **changes)


def _stiffnesses(p: TapeParameters) -> tuple[float, float, float, float]:
    """(D11, D22, D12, D66) = (Q11, Q22, Q12, G_xy) c³/12, N·m, written out here."""
    ex, ey = p.youngs_modulus, p.youngs_modulus_y
    det = 1.0 - NU_XY * NU_XY * ey / ex
    c3 = p.thickness**3 / 12
    return ex / det * c3, ey / det * c3, NU_XY * ey / det * c3, G_XY * c3


def _uniform(g):
    return pressure_load(g, lambda X, Y: np.ones_like(X))


# ----- all sides simply supported: Navier ----------------------------------------------------
@pytest.mark.parametrize("ratio", RATIOS)
def test_navier_frequencies_converge_at_second_order(ratio):
    """The four lowest (m, n) modes, each at second order (sin·sin is an exact discrete
    mode, so the error is the discrete symbol's)."""
    errors, intervals = [], np.array([8, 16, 32])
    for n in intervals:
        p = _tape(ratio, n, edges="simply-supported", length_ratio=2.0)
        D = _stiffnesses(p)
        exact = np.sort([orthotropic_navier_frequency(D, p, m, k)
                         for m in range(1, 8) for k in range(1, 4)])[:4]
        omega = modes(TapeModel(p), 0.0, 4).omega
        errors.append(np.abs(omega - exact) / exact)
    errors = np.array(errors)
    assert errors[-1].max() < 3e-3
    for j in range(4):
        assert observed_order(1.0 / intervals, errors[:, j]) == pytest.approx(2.0, abs=0.1)


@pytest.mark.parametrize("ratio", RATIOS)
def test_navier_series_of_a_uniform_load_converges_at_second_order(ratio):
    velocity, errors, intervals = 20.0, [], np.array([8, 16, 32])
    for n in intervals:
        p = _tape(ratio, n, edges="simply-supported", length_ratio=2.0)
        model = TapeModel(p)
        g = model.grid
        w = solve_static(model, velocity, _uniform(g)).field
        exact = orthotropic_navier_uniform(_stiffnesses(p), p, velocity, g.x, g.y, terms=401)
        errors.append(np.abs(w - exact).max() / np.abs(exact).max())
    assert errors[-1] < 2e-3
    assert observed_order(1.0 / intervals, errors) == pytest.approx(2.0, abs=0.1)


# ----- free edges: Lévy -------------------------------------------------------------------------
def _levy_frequencies(p: TapeParameters, count: int) -> np.ndarray:
    """The lowest ``count`` ω, rad/s: ρω² = ℓ(α_m) + Tα_m² + k over the cross-width
    eigenvalues ℓ of each axial wavenumber α_m = mπ/L_x."""
    D = _stiffnesses(p)
    top = 30 * D[0] * (np.pi / p.width) ** 4
    out = []
    for m in range(1, 5):
        a = m * np.pi / p.length
        ell = levy_eigenvalues(D, a, p.width, top, points=1500)
        out.extend(np.sqrt((ell + p.tension * a**2 + p.k) / p.density))
    return np.sort(out)[:count]


@pytest.mark.parametrize("ratio", RATIOS)
def test_levy_frequencies_converge_at_second_order(ratio):
    errors, intervals = [], np.array([8, 16, 32])
    exact = _levy_frequencies(_tape(ratio, 8, length_ratio=1.0), 3)
    for n in intervals:
        omega = modes(TapeModel(_tape(ratio, n, length_ratio=1.0)), 0.0, 3).omega
        errors.append(np.abs(omega - exact) / exact)
    errors = np.array(errors)
    assert errors[-1].max() < 2e-3
    for j in range(3):
        assert observed_order(1.0 / intervals, errors[:, j]) == pytest.approx(2.0, abs=0.1)


@pytest.mark.parametrize("ratio", RATIOS)
def test_levy_static_deflection_under_a_uniform_load_converges_at_second_order(ratio):
    """w = Σ over odd m of 4/(mπ) Y_m(y) sin(α_m x), Y_m the Lévy profile of sin(α_m x)."""
    velocity, errors, intervals = 20.0, [], np.array([8, 16, 32])
    for n in intervals:
        p = _tape(ratio, n, length_ratio=2.0)
        model = TapeModel(p)
        g = model.grid
        w = solve_static(model, velocity, _uniform(g)).field
        D = _stiffnesses(p)
        exact = sum(4 / (m * np.pi) * np.outer(
            np.sin(m * np.pi * g.x / p.length),
            levy_profile_orthotropic(D, p, velocity, m * np.pi / p.length, g.y))
            for m in range(1, 400, 2))
        errors.append(np.abs(w - exact).max() / np.abs(exact).max())
    assert errors[-1] < 1e-3
    assert observed_order(1.0 / intervals, errors) == pytest.approx(2.0, abs=0.1)


# ----- critical speed: the lowest Lévy branch at ω = 0 --------------------------------------
def _levy_mu(p: TapeParameters, g=None) -> float:
    """μ_min = min over α of (ℓ₁(α) + k)/α², N/m: α = α_m = mπ/L_x (the continuous tape), or
    with ``g`` the grid's a_m = (2/h_x) sin(α_m h_x/2): sin(α_m x) is an exact discrete
    eigenfunction along x with −δ² → a_m², so only the cross-width discretization differs."""
    alpha = np.arange(1, 400) * np.pi / p.length
    if g is not None:
        alpha = 2 / g.hx * np.sin(alpha[: g.nx - 1] * g.hx / 2)
    return levy_divergence_mu(_stiffnesses(p), p, alpha)


def _long(ratio: float, n: int) -> TapeParameters:
    """A long tape: L_x = 4 L_y holds ~6 buckling wavelengths 2π(D11/k)^¼."""
    return _tape(ratio, n, length_ratio=4.0, foundation_stiffness=2.0e7, tension=90.0)


@pytest.mark.parametrize("ratio", RATIOS)
def test_divergence_lies_on_the_lowest_levy_branch_below_the_width_uniform_strip(ratio):
    p = _long(ratio, 16)
    D = _stiffnesses(p)
    alpha = np.arange(1, 400) * np.pi / p.length
    mu_levy = _levy_mu(p)
    mu_strip = np.min(D[0] * alpha**2 + p.k / alpha**2)     # width-uniform, D11
    mu_edge = np.min((D[0] - D[2] ** 2 / D[1]) * alpha**2 + p.k / alpha**2)
    assert mu_edge < mu_levy < mu_strip        # the free edges relieve D11 towards D11 − D12²/D22
    mu = divergence(TapeModel(p)).mu
    assert mu == pytest.approx(mu_levy, rel=2e-3) and mu < mu_strip


def test_levy_branch_is_the_width_uniform_strip_without_poisson_coupling():
    """D12 = 0: Y = 1 satisfies the free-edge conditions, ℓ₁ = D11α⁴ exactly."""
    D = (3e-6, 2e-6, 0.0, 1e-6)
    assert levy_lowest(D, 500.0, WIDTH) == 3e-6 * 500.0**4
    D = (3e-6, 2e-6, 1e-12, 1e-6)
    assert levy_lowest(D, 500.0, WIDTH) == pytest.approx(3e-6 * 500.0**4, rel=1e-9)


@pytest.mark.slow
@pytest.mark.parametrize("ratio", RATIOS)
def test_divergence_converges_to_the_levy_branch_minimum_at_second_order(ratio):
    errors, continuous, intervals = [], [], np.array([16, 32, 64])
    for n in intervals:
        p = _long(ratio, n)
        model = TapeModel(p)
        mu = divergence(model).mu
        errors.append(abs(mu - _levy_mu(p, model.grid)) / mu)
        continuous.append(abs(mu - _levy_mu(p)) / mu)
    assert observed_order(1.0 / intervals, errors) == pytest.approx(2.0, abs=0.1)
    assert continuous[-1] < 2e-4 and errors[-1] < 2e-4


@pytest.mark.slow
@pytest.mark.parametrize("ratio", RATIOS)
def test_critical_speed_by_both_routes_matches_the_levy_branch(ratio):
    """(a) the eigen-solver's ω₁ → 0 and (b) the divergence of K(V) agree, and both give
    √((T + μ_min)/ρ) of the lowest Lévy branch on Table 1's stiff foundation."""
    p = _tape(ratio, 32, length_ratio=4.0, foundation_stiffness=None, tension=90.0)
    c = critical_speeds(TapeModel(p))
    exact = np.sqrt((p.tension + _levy_mu(p)) / p.density)
    assert c.relative_difference < 1e-5
    assert c.critical_speed == pytest.approx(exact, rel=3e-4)
    assert c.divergence_speed == pytest.approx(exact, rel=3e-4)
    assert c.strip_speed == pytest.approx(p.strip_critical_speed)


# ----- Newmark and the gyroscopic eigen-solver --------------------------------------------------
def _small(ratio: float) -> TapeModel:
    """16 × 8 intervals, Table 1 foundation and tension (critical speed near 100 m/s)."""
    return TapeModel(_tape(ratio, 8, length_ratio=2.0, foundation_stiffness=None,
                           tension=90.0))


@pytest.mark.parametrize("ratio", RATIOS)
def test_trapezoidal_newmark_conserves_energy_on_an_orthotropic_tape(ratio, rng):
    """β = 1/4, γ = 1/2, constant load, V > 0: E = ½vᵀMv + ½wᵀKw − Fᵀw is constant."""
    model, speed = _small(ratio), 50.0
    w0 = 1e-8 * rng.standard_normal(model.unknowns)
    v0 = 1e-3 * rng.standard_normal(model.unknowns)
    result = march(model, speed, dt=2e-6, steps=2000, w0=w0, v0=v0, record_energy=True)
    static = 0.5 * abs(model.force @ solve_static(model, speed).w)
    scale = max(static, np.abs(result.energy).max())
    assert np.abs(result.energy - result.energy[0]).max() / scale < 1e-10
    K, m, F, w, v = model.K(speed), model.mass_diagonal, model.force, result.w, result.v
    final = 0.5 * v @ (m * v) + 0.5 * w @ (K @ w) - F @ w
    assert final == pytest.approx(result.energy[-1], rel=1e-12, abs=1e-12 * scale)


@pytest.mark.parametrize("ratio", RATIOS)
def test_gyroscopic_modes_are_real_pm_i_omega_pairs_below_critical(ratio):
    model = _small(ratio)
    critical = divergence(model).speed
    assert 90.0 < critical < 110.0
    for speed in (0.3 * critical, 0.9 * critical):
        auto = modes(model, speed, 4)
        pairs = modes(model, speed, 4, sigma=0)
        assert not auto.supercritical
        assert np.all(auto.eigenvalues.real == 0) and np.all(auto.omega > 0)
        assert np.allclose(auto.omega, pairs.omega, rtol=1e-10)
        assert auto.info["pair_defect"] < 1e-8 and pairs.info["pair_defect"] < 1e-8
        assert auto.residuals.max() < 1e-10
        phi, lam = auto.vectors[:, 0], auto.eigenvalues[0]
        back = relative_residuals(model, speed, np.array([np.conj(lam)]), np.conj(phi)[:, None])
        assert back[0] < 1e-10
    above = modes(model, 1.05 * critical, 2)
    assert above.supercritical and above.growth_rate.max() > 0
