"""Dry tape over a flat land (no air, V = 0, k = 0, small slopes) against the tensioned
plate's closed form: D w'''' − T w'' = 0 on the spans and the land, the corners point
supports at the roughness σ, slope and moment continuous through them."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD
from closed_forms import tensioned_plate_on_two_supports
from convergence import observed_order

from gyroshell import TapeParameters
from gyroshell.bearing import BearingModel
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.steady import solve_steady

DEG = math.pi / 180.0
TAPE = TapeParameters()
AIR = FIRST_ORDER
LAND = 1e-3
SPAN = 1e-3


def plate_over_land(L, S, t_in, t_out, lam, sigma):
    """The exact tape height w(x) (m) over the land [−L/2, L/2] with spans of length S
    pinned at the string's ends (w = −θ S, w'' = 0: the model's pinned, moment-free
    ends), touching only the two corners (w = σ there).

    The plate on two point supports, the corners
    (``closed_forms.tensioned_plate_on_two_supports``): w and w'' at both ends and, at each
    corner, w = σ with w' and w'' continuous. Returns (w, w', corner forces D [w''']) as
    (callable, callable, (F_lead, F_trail) in N/m)."""
    a, b = -L / 2, L / 2
    evaluate, forces = tensioned_plate_on_two_supports(
        (a - S, b + S), (a, b), lam, (-t_in * S, -t_out * S), (sigma, sigma), TAPE.tension)
    return (lambda x: evaluate(x, 0)), (lambda x: evaluate(x, 1)), forces


def _dry_model(nx, t_in=2 * DEG, t_out=2 * DEG, **kw):
    head = FlatHead((Module(LAND),), t_in, t_out)
    return BearingModel(TAPE, AIR, velocity=0.0, head=head, span=SPAN, nx=nx, dry=True,
                        grading="uniform", **kw, contact=HARD)


def _errors(sol, t_in, t_out):
    """(height error along the tape over θλ, the two corner forces' relative errors)."""
    lam = math.sqrt(TAPE.D / TAPE.tension)
    w, _, forces = plate_over_land(LAND, SPAN, t_in, t_out, lam, HARD.roughness)
    m = sol.model
    column = m.ny // 2 if m.ny else 0
    height = m.head.dry_tape(m.x_head) + (sol.spacing[:, column] - m.dry_field[:, column])
    err = np.max(np.abs(height - w(m.x_head))) / (max(t_in, t_out) * lam)
    line = sol.contact.reshape(m.nx - 1, m.nc)[:, column]
    if m.ny:     # per unit width: the middle node's force over its control width
        line = line / m.tape.wy[column]
    inner = m.x_head[1:-1]
    at = [int(np.argmin(np.abs(inner - c))) for c in (-LAND / 2, LAND / 2)]
    f_err = [abs(line[i] / f - 1.0) for i, f in zip(at, forces, strict=True)]
    return err, f_err, line, at


def test_closed_form_is_the_string_with_corner_forces_near_T_theta():
    """The derivation's checks: far from λ it tends to the string; each corner carries
    about T θ; the tape stays above the land (no contact there); the land's middle,
    with infinitely long spans, at θ λ e^{−c}(cosh c − 1), c = L/(2λ) (≈ θλ/(1 + tanh c)
    for long lands: the two differ by θ λ e^{−c})."""
    lam = math.sqrt(TAPE.D / TAPE.tension)
    theta = 2 * DEG
    w, _, forces = plate_over_land(LAND, SPAN, theta, theta, lam, 0.0)
    assert forces == pytest.approx((TAPE.tension * theta,) * 2, rel=0.1)
    x = np.linspace(-LAND / 2, LAND / 2, 401)[1:-1]
    assert np.all(w(x) > 0)
    c = LAND / (2 * lam)
    w_long, _, _ = plate_over_land(LAND, 1e4 * lam, theta, theta, lam, 0.0)
    exact = theta * lam * math.exp(-c) * (math.cosh(c) - 1.0)
    assert w_long(np.array([0.0]))[0] == pytest.approx(exact, rel=1e-3)
    assert exact == pytest.approx(theta * lam / (1 + math.tanh(c)) - theta * lam * math.exp(-c),
                                  rel=1e-12)


@pytest.mark.parametrize("t_in, t_out", [(2 * DEG, 2 * DEG), (1 * DEG, 3 * DEG)],
                         ids=["equal", "unequal"])
def test_dry_strip_over_a_flat_land_matches_the_plate_and_converges(t_in, t_out):
    """Infinitely wide tape: the height along the whole tape and both corner forces
    against the closed form, only the two corner nodes in contact, second order."""
    steps, errs, ferrs = [], [], []
    for nx in (96, 192, 384):
        sol = solve_steady(_dry_model(nx, t_in, t_out, infinitely_wide=True))
        err, f_err, line, at = _errors(sol, t_in, t_out)
        assert sol.contact_nodes == 2 and set(np.flatnonzero(line)) == set(at)
        steps.append(sol.model.hx)
        errs.append(err)
        ferrs.append(max(f_err))
    assert errs[-1] < 1e-3 and ferrs[-1] < 2e-3
    assert observed_order(steps, errs) == pytest.approx(2.0, abs=0.25)
    assert observed_order(steps, ferrs) == pytest.approx(2.0, abs=0.3)


@pytest.mark.filterwarnings("ignore::gyroshell.bearing.model.BearingGridWarning")
def test_dry_wide_plate_middle_matches_the_strip_closed_form():
    """A 12.65 mm tape: along the middle of the width the plate bends cylindrically, so
    its height and corner forces per unit width follow the same closed form, at second
    order under x-refinement (the y-grid fixed; its edges do not reach the middle)."""
    steps, errs = [], []
    for nx in (64, 128):
        sol = solve_steady(BearingModel(TAPE.replace(width=12.65e-3), AIR, velocity=0.0,
                                        head=FlatHead((Module(LAND),), 2 * DEG, 2 * DEG),
                                        span=SPAN, nx=nx, ny=16, dry=True,
                                        grading="uniform", contact=HARD))
        err, f_err, _, _ = _errors(sol, 2 * DEG, 2 * DEG)
        steps.append(sol.model.hx)
        errs.append(err)
    assert errs[-1] < 3e-3 and max(f_err) < 1e-2
    assert observed_order(steps, errs) == pytest.approx(2.0, abs=0.3)
