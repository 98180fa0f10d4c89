"""The discrete film and the coupled system: exact Jacobian, conservation, plateau."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD, flexible_model
from scipy.sparse.linalg import spsolve

from gyroshell import ParameterError, TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.film import Film, bernoulli, face_fluxes
from gyroshell.bearing.flow_factors import (
    FLOW_FACTOR_MODELS,
    pressure_flow_factor,
    shear_flow_factor,
)
from gyroshell.bearing.mesh import Grading
from gyroshell.bearing.rarefaction import RAREFACTION_MODELS, poiseuille_flow_factor
from gyroshell.bearing.steady import _Residual, solve_steady

#: The Jacobian checks use coarse grids on purpose (the derivatives, not the answer).
pytestmark = pytest.mark.filterwarnings("ignore::gyroshell.bearing.model.BearingGridWarning")

AIRS = {
    "compressible-slip": FIRST_ORDER,
    "compressible": AirParameters(mean_free_path=0.0, rarefaction="first-order"),
    "incompressible-slip": AirParameters(compressible=False, rarefaction="first-order"),
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


def test_bernoulli_beyond_the_clip():
    """Past |z| = 600 B takes its limits: B(−z) = z + B(z) still holds, B' = −1 or 0."""
    z = np.array([-3500.0, -601.0, 601.0, 3500.0])
    b, db = bernoulli(z)
    assert np.array_equal(b, [3500.0, 601.0, 0.0, 0.0])
    assert np.array_equal(db, [-1.0, -1.0, 0.0, 0.0])
    assert np.allclose(bernoulli(-z)[0] - b, z, rtol=1e-15)


def _model(air, infinitely_wide, nx=60, ny=8, grading=None):
    return BearingModel(TapeParameters(), air, velocity=4.0, wrap_angle=math.radians(15),
                        infinitely_wide=infinitely_wide, nx=nx,
                        ny=None if infinitely_wide else ny, grading=grading, contact=HARD)


GRADED = Grading(x_ratio=4.0, y_ratio=6.0, y_width=0.4e-3)


def _assert_coupled_jacobian_exact(model, rng):
    """The coupled residual's Jacobian against central differences along a random
    direction, at a perturbed initial state."""
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
    _assert_coupled_jacobian_exact(model, rng)


@pytest.mark.parametrize("rarefaction", ["fukui-kaneko", "second-order", "none"])
@pytest.mark.parametrize("wide", [True, False], ids=["1-D", "2-D"])
def test_jacobian_matches_finite_differences_with_rarefaction_models(rarefaction, wide, rng):
    """The coupled model's Jacobian stays exact with every rarefaction model."""
    _assert_coupled_jacobian_exact(_model(AirParameters(rarefaction=rarefaction), wide), rng)


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
    model = _model(FIRST_ORDER, False, nx=80, ny=12, grading=grading)
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
    model = flexible_model(1600, params=params, air=FIRST_ORDER, velocity=12.0)
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
                           air=FIRST_ORDER)
    sol = solve_steady(model)
    assert sol.contact_force == 0.0
    turn = float(np.sum(model.W * model.kappa_nodes))
    assert turn == pytest.approx(model.wrap_angle, rel=1e-6)
    ends = (sol.u[0] + sol.u[-1]) / model.hx
    assert sol.air_force == pytest.approx(model.effective_tension() * (turn + ends), rel=1e-6)


# ----- rarefaction models and flow factors in the film --------------------------------------
SIGMA = 20e-9


def _random_fields(film, rng, compressible):
    """Nodal P (Pa) and H (m): spacings log-uniform over 5 nm..1 µm (h/σ from 0.25, below
    the flow factors' fit, through the shear blend at 5, to 50; Kn from 0.06 to 13, all
    three pieces of the Fukui–Kaneko fit), pressures 0.5..2 p_a."""
    shape = (film.nx + 1, film.nc)
    H = np.exp(rng.uniform(np.log(5e-9), np.log(1e-6), shape))
    P = film.air.ambient_pressure * (0.5 + 1.5 * rng.random(shape)) if compressible \
        else film.air.ambient_pressure + 3e4 * rng.standard_normal(shape)
    return P, H


@pytest.mark.parametrize("compressible", [True, False], ids=["compressible", "incompressible"])
@pytest.mark.parametrize("flow", FLOW_FACTOR_MODELS)
@pytest.mark.parametrize("rarefaction", RAREFACTION_MODELS)
@pytest.mark.parametrize("nc", [1, 6], ids=["1-D", "2-D"])
def test_film_jacobian_every_model(rarefaction, flow, compressible, nc, rng):
    """∂r/∂p and ∂r/∂h of the film (with its squeeze term) against central differences,
    for every rarefaction model and flow-factor model."""
    air = AirParameters(compressible=compressible, rarefaction=rarefaction, flow_factors=flow)
    film = Film(16, nc, 2e-6 * (1 + rng.random(16)),
                None if nc == 1 else 5e-6 * (1 + rng.random(nc - 1)), air, 4.0,
                roughness=SIGMA)
    P, H = _random_fields(film, rng, compressible)
    phi_old = film.transported(P, H) * (1 + 0.1 * rng.random(P.shape))
    kw = dict(phi_old=phi_old, dt=1e-7)
    r, J_p, J_h = film.residual(P, H, **kw)
    dP = np.zeros_like(P)
    dP[film.interior] = 0.01 * P[film.interior] * rng.standard_normal(film.size)
    dH = 0.01 * H * rng.standard_normal(H.shape)
    eps = 1e-4
    for (a, b), exact in (((dP, 0 * dH), J_p @ dP[film.interior]), ((0 * dP, dH),
                                                                      J_h @ dH.ravel())):
        plus, minus = (film.residual(P + s * a, H + s * b, jacobian=False, **kw)[0]
                       for s in (eps, -eps))
        fd = (plus - minus) / (2 * eps)
        assert np.allclose(exact, fd, rtol=1e-6, atol=1e-8 * np.abs(fd).max())


def test_first_order_slip_without_flow_factors_keeps_its_fluxes_bit_for_bit(rng):
    """rarefaction="first-order" with flow_factors="none" (the legacy film) gives exactly the
    fluxes of Γ = p h³ + 6 λ p_a h² (h³ + 6 λ h²) and Couette 6μV h̄."""
    pl, pr = 1e5 * (0.5 + rng.random((2, 50)))
    hl, hr = 1e-7 * (0.2 + rng.random((2, 50)))
    dx, V = 3e-6, 7.0
    for compressible in (True, False):
        air = AirParameters(compressible=compressible, rarefaction="first-order",
                            flow_factors="none")
        got = face_fluxes(pl, pr, hl, hr, dx, V, air, roughness=SIGMA)
        mu, lam, pa = air.viscosity, air.mean_free_path, air.ambient_pressure
        h = 0.5 * (hl + hr)
        c = 6.0 * mu * V * h
        if not compressible:
            gamma = h**3 + 6.0 * lam * h**2
            grad = (pr - pl) / dx
            assert np.array_equal(got.flux, -gamma * grad + c)
            assert np.array_equal(got.d_pl, gamma / dx)
            continue
        gamma = 0.5 * (pl + pr) * h**3 + 6.0 * lam * pa * h**2
        pe = c * dx / gamma
        assert np.array_equal(got.flux, gamma / dx * (bernoulli(-pe)[0] * pl
                                                      - bernoulli(pe)[0] * pr))


@pytest.mark.parametrize("compressible", [True, False], ids=["compressible", "incompressible"])
def test_general_path_meets_the_first_order_path(compressible, rng):
    """First-order slip through the general path with flow factors on a film far above its
    roughness (h/σ ~ 1e5: φ_x = 1, σ Φ_s = 0) gives the default fluxes to round-off; so do
    second-order slip and no slip without a mean free path."""
    pl, pr = 1e5 * (0.5 + rng.random((2, 40)))
    hl, hr = 1e-7 * (0.5 + rng.random((2, 40)))
    args = (pl, pr, hl, hr, 2e-6, 5.0)
    base = AirParameters(compressible=compressible, rarefaction="first-order")
    ref = face_fluxes(*args, base)
    smooth = face_fluxes(*args, base.replace(flow_factors="patir-cheng"), roughness=1e-12)
    still = [face_fluxes(*args, base.replace(mean_free_path=0.0, rarefaction=m))
             for m in ("first-order", "second-order", "none")]
    for got, want in [(smooth, ref), (still[1], still[0]), (still[2], still[0])]:
        for name in ("flux", "d_pl", "d_pr", "d_h"):
            a, b = getattr(got, name), getattr(want, name)
            assert np.allclose(a, b, rtol=1e-12, atol=1e-13 * np.abs(b).max())


def test_flow_factors_need_the_roughness():
    air = AirParameters(flow_factors="patir-cheng", rarefaction="first-order")
    with pytest.raises(ParameterError,
                       match=r"roughness must be given \(in \[1e-12, 0.0001\] m\) with flow_f"):
        Film(8, 1, 1e-6, None, air, 1.0)
    with pytest.raises(ParameterError, match="roughness must be in"):
        Film(8, 1, 1e-6, None, air, 1.0, roughness=-1.0)
    with pytest.raises(ParameterError, match="rarefaction must be one of"):
        AirParameters(rarefaction="boltzmann")
    with pytest.raises(ParameterError, match="flow_factors must be one of"):
        AirParameters(flow_factors="christensen", rarefaction="first-order")


def _slider_exact(air, sigma, V, L, h0, h1, xs):
    """p(xs) − p_a of the incompressible infinitely wide slider h = h0 + (h1 − h0) x/L with
    p = p_a at both ends, by quadrature of its flux F = −Γ p' + 6μV h_c:
    p' = (6μV h_c − F)/Γ, F = 6μV ∫h_c/Γ / ∫1/Γ, Γ = h³ Q(λ/h) φ_x, h_c = h + σ Φ_s."""
    from scipy.integrate import quad

    def h_of(x):
        return h0 + (h1 - h0) * x / L

    def gamma(x):
        h = h_of(x)
        q = poiseuille_flow_factor(air.rarefaction, air.mean_free_path / h)[0]
        return float(h**3 * q * pressure_flow_factor(air.flow_factors, h / sigma)[0])

    def h_c(x):
        h = h_of(x)
        return float(h + sigma * shear_flow_factor(air.flow_factors, h / sigma)[0])

    opts = dict(epsabs=0.0, epsrel=1e-13, limit=200)
    a = 6 * air.viscosity * V
    F = a * quad(lambda x: h_c(x) / gamma(x), 0, L, **opts)[0] \
        / quad(lambda x: 1 / gamma(x), 0, L, **opts)[0]
    return np.array([quad(lambda x: (a * h_c(x) - F) / gamma(x), 0, x, **opts)[0]
                     for x in xs])


@pytest.mark.parametrize("rarefaction, flow", [("none", "none"),
                                               ("fukui-kaneko", "patir-cheng"),
                                               ("second-order", "patir-cheng")])
def test_incompressible_slider_converges_to_quadrature(rarefaction, flow):
    """An incompressible, infinitely long and wide slider: the film's pressure converges at
    second order to the exact solution (quadrature), with rarefaction and flow factors
    (h/σ 2.5..10 across the shear factor's blend, Kn 0.3..1.3)."""
    air = AirParameters(compressible=False, rarefaction=rarefaction, flow_factors=flow)
    L, V, h0, h1 = 1e-3, 5.0, 200e-9, 50e-9
    xs = np.array([0.25, 0.5, 0.75]) * L
    exact = _slider_exact(air, SIGMA, V, L, h0, h1, xs)
    if rarefaction == flow == "none":       # the textbook slider (e.g. Hamrock, ch. 8)
        h = h0 + (h1 - h0) * xs / L
        textbook = 6 * air.viscosity * V * L * (h0 - h) * (h - h1) / ((h0**2 - h1**2) * h**2)
        assert np.allclose(exact, textbook, rtol=1e-10)
    errors = []
    for nx in (40, 80, 160):
        film = Film(nx, 1, L / nx, None, air, V, roughness=SIGMA)
        x = np.linspace(0, L, nx + 1)[:, None]
        H = h0 + (h1 - h0) * x / L
        P = np.full_like(H, air.ambient_pressure)
        r, J_p, _ = film.residual(P, H)
        P[film.interior] -= spsolve(J_p.tocsc(), r)      # r is affine in p: one step
        errors.append(np.abs(P[np.rint(xs / L * nx).astype(int), 0] - air.ambient_pressure
                             - exact).max())
    assert errors[-1] < 2e-3 * np.abs(exact).max()
    assert np.log2(errors[0] / errors[1]) > 1.8 and np.log2(errors[1] / errors[2]) > 1.8
