"""The discrete film and the coupled system: exact Jacobian, conservation, plateau."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bearing_cases import flexible_model

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.film import bernoulli
from gyroshell.bearing.mesh import Grading
from gyroshell.bearing.steady import _Residual, solve_steady

#: The Jacobian checks use coarse grids on purpose (the derivatives, not the answer).
pytestmark = pytest.mark.filterwarnings("ignore::gyroshell.bearing.model.BearingGridWarning")

AIRS = {
    "compressible-slip": AirParameters(),
    "compressible": AirParameters(mean_free_path=0.0),
    "incompressible-slip": AirParameters(compressible=False),
}


def test_bernoulli_function_and_derivative():
    z = np.array([-30.0, -1.0, -0.04, -1e-9, 0.0, 1e-9, 0.03, 0.5, 7.0, 700.0])
    b, db = bernoulli(z)
    zs = np.where(z == 0, 1.0, z)
    exact = np.where(z == 0, 1.0, zs / np.expm1(zs))
    assert np.allclose(b[:-1], exact[:-1], rtol=1e-13)
    assert 0.0 <= b[-1] < 1e-250
    eps = 1e-6
    fd = (bernoulli(z[:-1] + eps)[0] - bernoulli(z[:-1] - eps)[0]) / (2 * eps)
    assert np.allclose(db[:-1], fd, rtol=1e-7, atol=1e-9)
    assert np.allclose(bernoulli(-z[:-1])[0] - b[:-1], z[:-1], atol=1e-12)  # B(−z) = B(z) + z


def _model(air, infinitely_wide, nx=60, ny=8, grading=None):
    return BearingModel(TapeParameters(), air, velocity=4.0, wrap_angle=math.radians(15),
                        infinitely_wide=infinitely_wide, nx=nx,
                        ny=None if infinitely_wide else ny, grading=grading)


GRADED = Grading(x_ratio=4.0, y_ratio=6.0, y_width=0.4e-3)


@pytest.mark.parametrize("air", AIRS.values(), ids=AIRS.keys())
@pytest.mark.parametrize("wide, grading", [(True, "uniform"), (False, "uniform"),
                                           (True, GRADED), (False, GRADED)],
                         ids=["1-D", "2-D", "1-D-graded", "2-D-graded"])
def test_jacobian_matches_finite_differences(air, wide, grading, rng):
    """Newton's Jacobian is exact: against central differences of the residual, on
    uniform and graded grids."""
    model = _model(air, wide, grading=grading)
    if grading is GRADED:
        assert np.ptp(np.diff(model.x)) > 0.5 * np.diff(model.x).max()
        assert wide or np.ptp(np.diff(model.y)) > 0.5 * np.diff(model.y).max()
    F = _Residual(model, None, None)
    z = model.initial_state()
    z[:model.n_u] *= 1 + 0.3 * rng.random(model.n_u)
    z[model.n_u:] += 2000.0 * rng.random(model.n_p)
    res, active, J = F(z, jacobian=True)
    assert not active.any()
    direction = np.concatenate([model.h_guess * rng.standard_normal(model.n_u),
                                1000.0 * rng.standard_normal(model.n_p)])
    eps = 1e-6
    fd = (F(z + eps * direction, jacobian=False)[0]
          - F(z - eps * direction, jacobian=False)[0]) / (2 * eps)
    assert np.allclose(J.matrix @ direction, fd, rtol=1e-6, atol=1e-7 * np.abs(fd).max())


@pytest.mark.parametrize("wide", [True, False], ids=["1-D", "2-D"])
def test_film_residual_blocks_match_finite_differences(wide, rng):
    """BearingModel.film_residual's ∂r_p/∂u and ∂r_p/∂p against central differences of
    its r_p, with a few nodes pressed below the film's floor σ/2: their columns of ∂r_p/∂u
    are zero, and r_p does not move with u there (the spacing stays floored)."""
    model = _model(AIRS["compressible-slip"], wide)
    z = model.initial_state()
    u = z[:model.n_u] * (1 + 0.3 * rng.random(model.n_u))
    p = z[model.n_u:] + 2000.0 * rng.random(model.n_p)
    low = rng.choice(model.n_u, 4, replace=False)
    u[low] = -model.dry_field[1:-1, :].ravel()[low]                 # h = 0 < σ/2
    r, J_p, J_u = model.film_residual(u, p)
    assert np.array_equal(model.film_residual(u, p, jacobian=False)[0], r)
    assert abs(J_u[:, low]).sum() == 0.0
    du = model.h_guess * rng.standard_normal(model.n_u)
    dp = 1000.0 * rng.standard_normal(model.n_p)
    eps = 1e-4   # r_p sums terms ~50x its derivative's size: smaller steps see round-off
    for step, exact in (((du, 0 * dp), J_u @ du), ((0 * du, dp), J_p @ dp)):
        plus, minus = (model.film_residual(u + s * step[0], p + s * step[1],
                                           jacobian=False)[0] for s in (eps, -eps))
        fd = (plus - minus) / (2 * eps)
        assert np.allclose(exact, fd, rtol=1e-6, atol=1e-7 * np.abs(fd).max())
    only_low = np.zeros(model.n_u)
    only_low[low] = 0.4 * model.air.roughness                       # h = 0.4 σ: floored
    assert np.array_equal(model.film_residual(u + only_low, p, jacobian=False)[0], r)


@pytest.mark.parametrize("air", AIRS.values(), ids=AIRS.keys())
def test_fluxes_balance_to_round_off_1d(air):
    """Steady and one-dimensional: every face carries the same flux."""
    model = flexible_model(800, air=air, params=TapeParameters())
    sol = solve_steady(model)
    faces = model.film.fluxes(sol.pressure, sol.spacing)[0]
    flux = faces.flux[:, 0]
    # The net flux is a small difference of Poiseuille and Couette terms: round-off is
    # measured against the largest single term.
    term = np.max(np.abs(faces.d_pl[:, 0] * sol.pressure[:-1, 0]))
    assert np.ptp(flux) < 1e-9 * term
    assert np.ptp(flux) < 1e-6 * abs(flux.mean())


def _boundary_outflow(film, P, H):
    """Net flux out of the film's interior control volumes through their outer faces,
    each face flux times its own face length (the control width across or along)."""
    fx, fy = film.fluxes(P, H)
    wx, wy = film.x_widths, film.y_widths
    return ((fx.flux[-1, 1:-1] - fx.flux[0, 1:-1]) @ wy[1:-1]
            + (fy.flux[1:-1, -1] - fy.flux[1:-1, 0]) @ wx[1:-1]), fx.flux[0, 1:-1] @ wy[1:-1]


@pytest.mark.slow
@pytest.mark.parametrize("grading", ["uniform", None], ids=["uniform", "graded"])
def test_fluxes_balance_to_round_off_2d(grading, rng):
    """Conservation: the node balances of any fields sum to the net outflow through the
    film's boundary (every inner face flux cancels), on uniform and graded grids alike;
    in the steady state what enters at x = 0 leaves at x = L_x or through the edges."""
    model = _model(AirParameters(), False, nx=80, ny=12, grading=grading)
    assert model.graded == (grading is None)
    sol = solve_steady(model)
    for P, H in ((sol.pressure, sol.spacing),
                 (sol.pressure * (1 + 0.1 * rng.random(sol.pressure.shape)),
                  sol.spacing * (1 + 0.5 * rng.random(sol.spacing.shape)))):
        r, _, _ = model.film.residual(P, H, jacobian=False)
        net, inflow = _boundary_outflow(model.film, P, H)
        terms = np.abs(model.film.fluxes(P, H)[0].flux).max() * model.params.width
        assert r.sum() == pytest.approx(net, abs=1e-13 * terms)
    r, _, _ = model.film.residual(sol.pressure, sol.spacing, jacobian=False)
    net, inflow = _boundary_outflow(model.film, sol.pressure, sol.spacing)
    assert inflow > 0 and abs(net) < 1e-10 * inflow
    # the graded film's control volumes tile the tape exactly
    assert model.film.cell_area.sum() == pytest.approx(model.length * model.params.width,
                                                       rel=1e-14)


def test_central_plateau_balances_the_wrap():
    """On the wrap, p − p_a = (T − ρV²)/R + k h for a flexible tape."""
    params = TapeParameters(bending_rigidity=1e-12)
    model = flexible_model(1600, params=params, air=AirParameters(), velocity=12.0)
    sol = solve_steady(model)
    expected = model.effective_tension() / params.radius + params.k * sol.central_spacing
    assert sol.central_pressure == pytest.approx(expected, rel=1e-4)
    # ... and the transport's centrifugal part is really there: (T − ρV²)/R, not T/R.
    assert abs(sol.central_pressure - params.tension / params.radius
               - params.k * sol.central_spacing) > 100 * abs(sol.central_pressure - expected)


def test_air_force_is_tension_turn_plus_end_reactions_1d():
    """Global balance of a flexible strip: ∫ (p − p_a) dx equals the tension turned through
    the wrap, (T − ρV²) Σ W κ ≈ (T − ρV²) θ, plus the pinned ends' reactions
    (T − ρV²)(u₁ + u_n)/Δx."""
    model = flexible_model(1600, params=TapeParameters(bending_rigidity=1e-12,
                                                       foundation_stiffness=0.0),
                           air=AirParameters())
    sol = solve_steady(model)
    assert sol.contact_force == 0.0
    turn = float(np.sum(model.W * model.kappa_nodes))
    assert turn == pytest.approx(model.wrap_angle, rel=1e-6)
    ends = (sol.u[0] + sol.u[-1]) / model.hx
    assert sol.air_force == pytest.approx(model.effective_tension() * (turn + ends), rel=1e-6)
