"""A flat head one film covers: 0.01° wraps over a 1 mm land at 4 m/s, where the film
length R_c ε^(1/3) (17 mm, R_c = ℓ_bend/θ ≈ 1 m) exceeds the head, the tape flies microns
above the land and its corners, and the spans (0.1 m) carry only the tape.

The default grid resolves the land about the head alone (not over the spans), the tape
flying over the corners is solved on corners refined to its spacing (refined to the
roughness, the residual's round-off left its height undetermined by tens of %), and the
answers converge under refinement and balance the wrap load with the spans' rotation.
Where the tape still presses onto the land (0.03°), the state is the pressed one as
before."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gyroshell import TapeParameters
from gyroshell.bearing import BearingModel
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.model import (
    DEFAULT_GRADING,
    X_RESOLUTION_GRADED,
    foil_length_scales,
    resolution_length,
)
from gyroshell.bearing.steady import solve_steady

DEG = math.pi / 180.0
TAPE = TapeParameters()
LAND = 1e-3
TINY = FlatHead((Module(LAND),), 0.01 * DEG, 0.01 * DEG)


def _model(head=TINY, **kw) -> BearingModel:
    return BearingModel(TAPE, velocity=4.0, head=head, **kw)


def test_the_film_covers_the_head_only_at_tiny_wraps():
    """At 0.01° the film length exceeds the 1 mm land; at 2° (88 µm) it does not, and
    the default grading and corner refinement are as before."""
    tiny, usual = _model(infinitely_wide=True), _model(
        FlatHead((Module(LAND),), 2 * DEG, 2 * DEG))
    assert tiny.film_over_head and tiny.film_length > 10 * LAND
    assert not usual.film_over_head and usual.film_length < 0.2 * LAND
    assert usual.grading.x_ratio == DEFAULT_GRADING.x_ratio
    assert usual.grading.x_width == pytest.approx(
        1.5 * max(usual.film_length, usual.bending_length))
    assert usual.with_flown_corners() is None


def test_the_foil_spacing_scale_is_the_heads_length_times_eps_cube_root():
    """The foil's h/ℓ = ε^(1/3) (T h/ℓ² against 6μV ℓ/h²) over the head's length: 17 µm,
    not the 290 µm of R_c ε^(2/3) with R_c ≈ 1 m."""
    model = _model(infinitely_wide=True)
    t_eff = TAPE.tension - TAPE.density * 16.0
    eps = 6.0 * model.air.viscosity * 4.0 / t_eff
    assert model.h_guess / 0.64 == pytest.approx(eps ** (1 / 3) * LAND, rel=1e-12)
    h_foil = foil_length_scales(TAPE, model.air, 4.0, model.scale_radius)[0]
    assert h_foil > 10 * model.h_guess


@pytest.mark.parametrize("infinitely_wide", [True, False], ids=["1-D", "2-D"])
def test_the_default_grid_resolves_the_land_not_the_spans(infinitely_wide):
    """The land keeps the feature's spacing (half the land over 15 at the most, at
    the middle of the land), while the 0.1 m spans are spaced by the film and bending
    lengths' resolution (not finer than 1/15 of it far along them): 336 x 148 intervals
    in 2-D instead of 3064 x 148 (906,648 unknowns, 42 s to build)."""
    model = _model(infinitely_wide=infinitely_wide)
    x, dx = model.x_head, np.diff(model.x_head)
    mid = 0.5 * (x[1:] + x[:-1])
    land = np.abs(mid) < 0.5 * LAND
    assert dx[land].max() <= 0.5 * LAND / 15.0
    assert land.sum() >= 30
    film = resolution_length(model.film_length, model.bending_length)
    far = np.abs(mid) > 0.5 * LAND + 30 * LAND
    assert model.span == pytest.approx(0.1)
    assert np.median(dx[far]) > X_RESOLUTION_GRADED * film
    assert model.nx < 600
    if not infinitely_wide:
        assert model.unknowns < 150_000


def test_the_flying_state_is_the_same_from_every_start_and_on_twice_the_intervals():
    """1-D: the tape flies microns above the land and its corners; on the default grid
    and on twice its intervals (the same mapping) the spacings agree within 0.1 %, and
    Newton reaches the same state from flat starts 6-20 µm above the head (on corners
    refined to the roughness, main's states scattered over 6.3-9.5 µm)."""
    model = _model(infinitely_wide=True)
    sols = [solve_steady(m) for m in (model, model.rebuilt(nx=2 * model.nx))]
    hc = [s.central_spacing for s in sols]
    hmin = [s.minimum_spacing for s in sols]
    assert 1e-6 < hmin[0] < hc[0] < 20e-6
    assert hc[1] == pytest.approx(hc[0], rel=1e-3)
    assert hmin[1] == pytest.approx(hmin[0], rel=1e-3)
    assert sols[0].contact_force == 0.0
    flown = sols[0].model
    assert flown.corners_flown and flown.nx == model.nx
    for h in (6e-6, 20e-6):
        z0 = np.concatenate([np.full(flown.n_u, h) * _taper(flown),
                             np.full(flown.n_p, flown.air.ambient_pressure)])
        assert solve_steady(flown, z0=z0).central_spacing == pytest.approx(hc[0],
                                                                           rel=1e-4)


def _taper(model: BearingModel) -> np.ndarray:
    x = model.x[1:-1]
    t = np.clip(np.minimum(x, model.length - x) / (0.5 * model.span), 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def test_the_air_carries_the_wrap_and_the_spans_rotation():
    """Summed tape rows (see test_flat_head_convergence): air + corners = T'(θ_in +
    θ_out) + T'(u₁/h₀ + u_{n−1}/h_{n−1}), the spans' rotation by the tape's lift over
    their 0.1 m, which is a fair share of the load at a wrap this small (the lift h over
    the span S turns the tape by h/S against θ: 7 µm / 0.1 m = 7e-5 against 1.7e-4)."""
    sol = solve_steady(_model(infinitely_wide=True))
    model = sol.model
    t_eff = model.effective_tension()
    air = float((model.pressure_load @ (sol.p - model.air.ambient_pressure)).sum())
    h = np.diff(model.x)
    rotation = t_eff * (sol.u[0] / h[0] + sol.u[-1] / h[-1])
    wrap = t_eff * TINY.wrap
    assert air + sol.contact.sum() == pytest.approx(wrap + rotation, rel=1e-3)
    lift = 2.0 * t_eff * sol.central_spacing / model.span
    assert rotation == pytest.approx(lift, rel=0.3)
    assert rotation > 0.2 * wrap


def test_a_tape_pressed_onto_the_land_stays_pressed():
    """0.03°: the film still covers the head, but the tape presses onto the land at
    about 3.5 σ_s (the state the corners' start leads to, as before): the flying path is
    tried only where that one is not reached."""
    head = FlatHead((Module(LAND),), 0.03 * DEG, 0.03 * DEG)
    model = _model(head, infinitely_wide=True)
    assert model.film_over_head
    sol = solve_steady(model)
    assert sol.model is model
    assert sol.central_spacing < 100e-9


@pytest.mark.slow
def test_the_2d_tape_flies_below_the_infinitely_wide_one_and_converges():
    """2-D (6.35 mm wide): the strip decides that the tape flies over the corners, and
    the 2-D state (its free edges leaking the film: the middle a few % below the strip,
    the minimum at the trailing corner's edges) agrees within 0.1 % on twice the
    intervals along x."""
    strip = solve_steady(_model(infinitely_wide=True))
    model = _model()
    sols = [solve_steady(m) for m in (model, model.rebuilt(nx=2 * model.nx))]
    for s in sols:
        assert s.model.corners_flown
        assert 0.8 * strip.central_spacing < s.central_spacing < strip.central_spacing
        assert s.minimum_spacing < s.central_spacing
        assert s.air_force / TAPE.width == pytest.approx(strip.air_force, rel=0.1)
    assert sols[1].central_spacing == pytest.approx(sols[0].central_spacing, rel=1e-3)
    assert sols[1].minimum_spacing == pytest.approx(sols[0].minimum_spacing, rel=1e-3)


def test_the_hard_wall_flies_the_same_tape():
    """Flying microns above the head, the tape touches nothing: the hard wall (no
    asperity law, no roughness flow factors) gives the asperity law's flying state
    within 0.1 % (it stopped with a ConvergenceError after 97 s before)."""
    from gyroshell.bearing.contact import ContactParameters

    asperity = solve_steady(_model(infinitely_wide=True))
    hard = solve_steady(_model(infinitely_wide=True,
                               contact=ContactParameters(law="hard", roughness=20e-9)))
    assert hard.contact_force == 0.0
    assert hard.central_spacing == pytest.approx(asperity.central_spacing, rel=1e-3)
    assert hard.minimum_spacing == pytest.approx(asperity.minimum_spacing, rel=1e-3)
