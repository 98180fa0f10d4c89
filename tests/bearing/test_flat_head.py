"""The bearing over head contours: the cylinder through the contour path, flat heads at
speed (mass balance, sub-ambient tents, contact at the corners), mirror symmetry,
cavitation, storage, the transient and the refusals."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD, flux_spread_1d

from gyroshell import ParameterError, TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.geometry import dry_curvature, dry_gap
from gyroshell.bearing.head import Cylinder, FlatHead, Module
from gyroshell.bearing.model import BearingGridWarning
from gyroshell.bearing.steady import solve_steady
from gyroshell.bearing.transient import march
from gyroshell.results.base import read

DEG = math.pi / 180.0
TAPE = TapeParameters()
AIR = FIRST_ORDER
FLAT = FlatHead((Module(1e-3),), 2 * DEG, 2 * DEG, transducers=(0.0,))


@pytest.mark.parametrize("two_d", [False, True], ids=["1-D", "2-D"])
def test_cylinder_through_the_contour_path_gives_todays_answers(two_d):
    """head=Cylinder(θ) is wrap_angle=θ: the same grid, loads and state; the loads equal
    the cylinder's closed-form gap and curvature of geometry.py to round-off."""
    kw = (dict(params=TAPE.replace(width=3e-3), nx=96, ny=24, span=2e-3) if two_d
          else dict(params=TAPE, infinitely_wide=True))
    params = kw.pop("params")
    old = BearingModel(params, AIR, velocity=4.0, wrap_angle=15 * DEG, **kw, contact=HARD)
    new = BearingModel(params, AIR, velocity=4.0, head=Cylinder(15 * DEG), **kw, contact=HARD)
    same_r = BearingModel(params, AIR, velocity=4.0,
                          head=Cylinder(15 * DEG, radius=params.radius), **kw, contact=HARD)
    R = params.radius
    np.testing.assert_allclose(new.dry_field[:, 0], dry_gap(new.x, new.length, R, 15 * DEG),
                               rtol=1e-12, atol=1e-18)
    np.testing.assert_allclose(new.kappa, dry_curvature(new.x, new.length, R, 15 * DEG),
                               rtol=1e-9, atol=1e-9 / R)
    sols = [solve_steady(m) for m in (old, new, same_r)]
    for sol in sols[1:]:
        assert np.array_equal(sol.model.x, old.x)
        for name in ("u", "p", "contact"):
            a, b = getattr(sols[0], name), getattr(sol, name)
            assert np.allclose(a, b, rtol=1e-9, atol=1e-9 * np.abs(a).max() + 1e-300)


def _flying(nx=None, head=FLAT, air=AIR, **kw):
    return BearingModel(TAPE, air, velocity=4.0, head=head, infinitely_wide=True, nx=nx,
                        **kw, contact=HARD)


def test_flat_head_at_speed_balances_mass_and_pulls_below_ambient():
    """1-D, 4 m/s: the face fluxes are one constant (in = out to the round-off of the
    pressure-driven terms Γ p/Δx, large where the spans' gap is wide); over the flat
    (in the tents next to the corners) the film is sub-ambient yet positive
    (compressible), and the corners carry the contact
    force: only their nodes touch, and more than T θ each (the suction adds to it)."""
    sol = solve_steady(_flying())
    m = sol.model
    spread, terms, flux = flux_spread_1d(sol)
    assert spread < 1e-12 * terms and spread < 1e-4 * flux
    gauge = sol.pressure[:, 0] - AIR.ambient_pressure
    on_land = np.abs(sol.x) < 0.5e-3
    assert gauge[on_land].min() < -0.3 * AIR.ambient_pressure    # in the tents by the corners
    assert sol.pressure.min() > 0.0
    inner = m.x_head[1:-1]
    corners = [int(np.argmin(np.abs(inner - c))) for c in m.head.corners()]
    assert set(np.flatnonzero(sol.contact)) == set(corners)
    assert np.all(sol.contact[corners] > TAPE.tension * 2 * DEG)


def test_mirrored_head_mirrors_the_dry_solution():
    """At rest the direction does not matter: the tape over the mirrored head (wraps
    swapped, modules reversed) is the reflection of the tape over the head, on the
    reflected grid, to round-off."""
    head = FlatHead((Module(0.8e-3), Module(0.5e-3, height=0.5e-6)), 1.5 * DEG, 3 * DEG,
                    gaps=(0.2e-3,))
    kw = dict(velocity=0.0, infinitely_wide=True, dry=True, nx=400)
    a = solve_steady(BearingModel(TAPE, AIR, head=head, **kw, contact=HARD))
    b = solve_steady(BearingModel(TAPE, AIR, head=head.mirrored(), **kw, contact=HARD))
    np.testing.assert_allclose(b.x[::-1], -a.x, rtol=0, atol=1e-15)
    scale = np.abs(a.spacing).max()
    np.testing.assert_allclose(b.spacing[::-1], a.spacing, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(b.contact[::-1], a.contact, rtol=0,
                               atol=1e-9 * a.contact.max())
    assert a.contact_nodes >= 2
    sym = BearingModel(TAPE, AIR, head=FLAT.mirrored(), **kw, contact=HARD)
    assert FLAT.symmetric and np.array_equal(sym.x, BearingModel(TAPE, AIR, head=FLAT,
                                                                 **kw, contact=HARD).x)
    np.testing.assert_allclose(sym.x[::-1], sym.length - sym.x, rtol=0, atol=1e-18)


def test_incompressible_film_over_a_flat_is_refused_where_it_would_cavitate():
    model = _flying(air=AirParameters(compressible=False, rarefaction="first-order"))
    with pytest.raises(ParameterError, match="incompressible film would cavitate: p = .* Pa "
                                             "absolute at x = .*; use compressible=True"):
        solve_steady(model)


def test_two_d_flat_head_smoke_and_storage_round_trip(tmp_path):
    """A 3 mm tape on a small grid: converges, corners carry the contact, the film stays
    positive and sub-ambient in the tents; saved and loaded with its head, equal."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        model = BearingModel(TAPE.replace(width=3e-3), AIR, velocity=4.0, head=FLAT, nx=96,
                             ny=24, contact=HARD)
    sol = solve_steady(model)
    assert 0.0 < sol.pressure.min() < 0.8 * AIR.ambient_pressure
    inner = model.x_head[1:-1]
    lines = sol.contact.reshape(model.nx - 1, model.nc).sum(axis=1)
    near = np.min(np.abs(inner[:, None] - np.array(FLAT.corners())[None, :]), axis=1) < 30e-6
    assert lines[near].sum() > 0.9 * lines.sum() > 0
    path = tmp_path / "flat.nc"
    sol.save(path)
    back = read(path)
    assert back.model.head == FLAT and np.array_equal(back.u, sol.u)
    assert np.array_equal(back.p, sol.p) and np.array_equal(back.contact, sol.contact)


@pytest.mark.parametrize("velocity", [4.0, -4.0], ids=["+V", "-V"])
def test_march_from_a_flat_head_steady_state_stays_there(velocity):
    """A steady state is a fixed point of the coupled march (constant tension), in either
    direction of the tape."""
    start = solve_steady(BearingModel(TAPE, AIR, velocity=velocity, head=FLAT,
                                      infinitely_wide=True, contact=HARD))
    run = march(start, dt=2e-6, steps=4)
    np.testing.assert_allclose(run.final.u, start.u, rtol=0, atol=1e-6 * np.abs(start.u).max())
    assert run.final.contact_nodes == start.contact_nodes


@pytest.mark.parametrize("kw, match", [
    (dict(wrap_angle=DEG, head=FLAT), "exactly one of wrap_angle"),
    (dict(), "exactly one of wrap_angle"),
    (dict(head="flat"), "head must be a Head"),
    (dict(head=FLAT, nx=8, span=1.5e-3), "nx = 8 is too small for the head"),
    (dict(head=Cylinder(2 * DEG, transducers=(1e-3,))), r"transducers\[0\] must lie"),
    (dict(head=FLAT, velocity=0.0), "velocity must be nonzero .*use dry=True"),
    (dict(head=FLAT, velocity=-90.0), "below the string speed .* in magnitude"),
    (dict(head=FLAT, velocity=math.nan), "velocity must be finite"),
    (dict(head=FLAT, dry="yes"), "dry must be True or False"),
])
def test_model_refuses_bad_heads_in_one_line(kw, match):
    kw = {"velocity": 4.0, "infinitely_wide": True, **kw}
    with pytest.raises(ParameterError, match=match) as err:
        BearingModel(TAPE, AIR, **kw, contact=HARD)
    assert "\n" not in str(err.value)


def test_rounded_corners_choose_point_contacts_or_wrapped_arcs_by_their_arc_length():
    """A rounded corner whose arc r_c θ_c is within 0.3 bending lengths gets a tangent
    point contact (tests/bearing/test_rounded_corners.py), a longer one is wrapped: its arc
    nodes join the contact set (tests/bearing/test_wrapped_arcs.py), flying or dry."""
    import math

    from gyroshell import TapeParameters
    from gyroshell.bearing import BearingModel, FlatHead, Module

    head = FlatHead((Module(1e-3, corner_radius=2.5e-3),), math.radians(2), math.radians(2))
    for kw in (dict(velocity=4.0), dict(velocity=0.0, dry=True, nx=400)):
        wrapped = BearingModel(TapeParameters(), head=head, infinitely_wide=True, **kw,
                               contact=HARD, air=FIRST_ORDER)
        assert wrapped.wrapped_corners == (0, 1) and wrapped.corner_contacts == ()
    flown = BearingModel(TapeParameters(), velocity=4.0, infinitely_wide=True,
                         head=FlatHead((Module(1e-3, corner_radius=20e-6),),
                                       math.radians(2), math.radians(2)), contact=HARD,
                                       air=FIRST_ORDER)
    assert len(flown.corner_contacts) == 2 and flown.wrapped_corners == ()
