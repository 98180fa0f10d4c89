"""Rounded corners of a flat head: the tape touches each arc at one point, found by
regridding (gyroshell.bearing.corners).

Dry closed form (no air, V = 0, k = 0, small slopes): the tensioned plate D w'''' − T w'' = 0
on three pieces, touching the two arcs z_h = −d²/(2 r_c) (d the distance past the land's
tangent point) at unknown points x₁, x₂, where w = z_h + σ, w, w', w'' are continuous (a
point force: w''' jumps) and the tape is tangent to the arc, w'(x_k) = z_h'(x_k). This
holds while the tape is less curved than the arc, |w''| < 1/r_c (its curvature near a
corner is about θ/(2λ), λ = √(D/T) ≈ 0.1 mm: 175 1/m at 2°, against 1/r_c = 1e4 1/m
for r_c = 100 µm): the regime of a point contact, which these tests take.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD, flux_spread_1d
from closed_forms import plate_over_rounded_land
from convergence import observed_order

from gyroshell import ParameterError, TapeParameters
from gyroshell.bearing import BearingModel
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.steady import solve_steady

DEG = math.pi / 180.0
TAPE = TapeParameters(foundation_stiffness=0.0)
AIR = FIRST_ORDER
LAND = 1e-3
SPAN = 1e-3
RADIUS = 100e-6
FLANK = 20 * DEG


def _dry(nx, t_in=2 * DEG, t_out=2 * DEG, r=RADIUS, **kw):
    head = FlatHead((Module(LAND, corner_radius=r),), t_in, t_out, flank_angle=FLANK)
    return BearingModel(TAPE, AIR, velocity=0.0, head=head, span=SPAN, nx=nx, dry=True,
                        grading="uniform", infinitely_wide=True, **kw, contact=HARD)


def test_closed_form_touches_each_arc_tangentially_inside_its_wrapped_part():
    """The derivation's own checks: the contacts lie on the wrapped part of each arc
    (0 < d < r θ), the tape clears the head everywhere else, and r → 0 gives back the
    sharp corners' contacts at the corner points."""
    lam = math.sqrt(TAPE.D / TAPE.tension)
    t = 2 * DEG
    w, forces, (x1, x2) = plate_over_rounded_land(LAND, SPAN, t, t, lam, 0.0, RADIUS, FLANK,
                                                  TAPE.tension)
    lead = -LAND / 2 + 0.5 * RADIUS * FLANK
    assert 0.0 < lead - x1 < RADIUS * t
    x = np.linspace(-LAND / 2 - 0.5 * RADIUS * FLANK, LAND / 2 + 0.5 * RADIUS * FLANK, 4001)
    head = FlatHead((Module(LAND, corner_radius=RADIUS),), t, t, flank_angle=FLANK)
    clearance = w(x) - head.surface(x)
    assert clearance.min() > -1e-15
    assert forces == pytest.approx((TAPE.tension * t,) * 2, rel=0.15)
    _, _, tiny = plate_over_rounded_land(LAND, SPAN, t, t, lam, 0.0, 1e-12, FLANK, TAPE.tension)
    assert tiny == pytest.approx((-LAND / 2, LAND / 2), abs=1e-12)


@pytest.mark.parametrize("t_in, t_out", [(2 * DEG, 2 * DEG), (1 * DEG, 3 * DEG)],
                         ids=["equal", "unequal"])
def test_dry_tape_over_rounded_corners_matches_the_plate_and_converges(t_in, t_out):
    """Height along the tape and both corner forces against the closed form, one contact
    node per corner (at the adapted contact point), second order."""
    lam = math.sqrt(TAPE.D / TAPE.tension)
    w, forces, contacts = plate_over_rounded_land(LAND, SPAN, t_in, t_out, lam,
                                                  HARD.roughness, RADIUS, FLANK,
                                                  TAPE.tension)
    steps, errs, ferrs, xerrs = [], [], [], []
    for nx in (96, 192, 384):
        sol = solve_steady(_dry(nx, t_in, t_out))
        m = sol.model
        height = sol.spacing[:, 0] + m.head.surface(m.x_head)
        errs.append(np.max(np.abs(height - w(m.x_head))) / (max(t_in, t_out) * lam))
        line = sol.contact
        at = m.contact_nodes - 1
        assert set(np.flatnonzero(line)) == set(at)
        ferrs.append(max(abs(line[i] / f - 1.0) for i, f in zip(at, forces, strict=True)))
        xerrs.append(max(abs(c - e) for c, e in zip(m.corner_contacts, contacts, strict=True)))
        assert m.arc_clearance(sol.u) > 0.0
        assert sol.info.contact_passes <= 4
        steps.append(m.hx)
    assert errs[-1] < 1e-3 and ferrs[-1] < 2e-3
    assert observed_order(steps, errs) == pytest.approx(2.0, abs=0.25)
    assert observed_order(steps, ferrs) == pytest.approx(2.0, abs=0.3)
    assert xerrs[-1] < 0.05 * RADIUS * max(t_in, t_out)


# ----- at speed: the air film over rounded corners ----------------------------------------
FILM_RADIUS = 5e-6


def _flying(r=FILM_RADIUS, velocity=4.0, **kw):
    head = FlatHead((Module(LAND, corner_radius=r),), 2 * DEG, 2 * DEG)
    return BearingModel(TapeParameters(), AIR, velocity=velocity, head=head,
                        infinitely_wide=True, **kw, contact=HARD)


def _h0(sol) -> float:
    """The spacing at the transducer x = 0, m (interpolated: x = 0 need not be a node)."""
    return float(np.interp(0.0, sol.model.x_head, sol.spacing[:, 0]))


def test_flying_over_rounded_corners_balances_mass_and_touches_each_arc_at_one_point():
    """1-D, 4 m/s, r_c = 5 µm, default grid: the face fluxes are one constant (to the
    round-off of the pressure-driven terms), only the two contact nodes touch, the tape
    clears the rest of each arc, the contacts lie on the arcs' wrapped parts (within
    r_c θ_c of the land's tangent points) and settled in at most 3 passes."""
    sol = solve_steady(_flying())
    m = sol.model
    spread, terms, flux = flux_spread_1d(sol)
    assert spread < 1e-12 * terms and spread < 1e-4 * flux
    assert set(np.flatnonzero(sol.contact)) == set(m.contact_nodes - 1)
    assert np.all(sol.contact[m.contact_nodes - 1] > TAPE.tension * 2 * DEG)
    assert m.arc_clearance(sol.u) >= 0.0
    lead = -LAND / 2 + 0.5 * FILM_RADIUS * FLANK
    x1, x2 = m.corner_contacts
    assert 0.0 < lead - x1 < FILM_RADIUS * 2 * DEG and 0.0 < x2 + lead < FILM_RADIUS * 2 * DEG
    assert sol.info.contact_passes <= 3 and sol.info.iterations <= 30


def test_small_corner_radius_tends_to_the_sharp_corners():
    """r_c → 0: 10 nm flies within 0.1 % of the sharp corners at x = 0 on the same number
    of intervals (measured 0.02 %), while 5 µm is clearly different (0.7 % lower)."""
    sharp = _h0(solve_steady(_flying(0.0)))
    nx = _flying(0.0).nx
    tiny = _h0(solve_steady(_flying(1e-8, nx=nx)))
    rounded = _h0(solve_steady(_flying(nx=nx)))
    assert abs(tiny / sharp - 1.0) < 1e-3
    assert abs(rounded / sharp - 1.0) > 3e-3


def test_reversed_tape_over_symmetric_rounded_corners_mirrors_the_solution():
    """A symmetric head at −V: the contacts are the mirror images of those at +V (to the
    passes' tolerance, 1 % of a cell), as are the spacing at x = 0 and the two corner
    forces (swapped)."""
    a, b = (solve_steady(_flying(velocity=v)) for v in (4.0, -4.0))
    ma, mb = a.model, b.model
    cells = np.diff(ma.x).min()
    assert np.allclose(np.array(mb.corner_contacts), -np.array(ma.corner_contacts)[::-1],
                       rtol=0, atol=0.02 * cells)
    assert _h0(b) == pytest.approx(_h0(a), rel=1e-4)
    fa, fb = a.contact[ma.contact_nodes - 1], b.contact[mb.contact_nodes - 1]
    assert np.allclose(fb[::-1], fa, rtol=1e-4)
    assert abs(fa[0] / fa[1] - 1.0) > 1e-3          # the state itself is asymmetric


@pytest.mark.slow
def test_transducer_spacing_over_rounded_corners_converges_at_second_order():
    """The default 1-D grid and the same mapping with 2 and 4 times the intervals: h(0)
    converges at order about 2 (measured 2.01: 31.3129, 31.2801, 31.2720 nm), the
    default grid within 0.5 % of the Richardson value (measured 0.14 %), the contact
    force too (within 0.1 %)."""
    base = _flying()
    sols = [solve_steady(base if k == 1 else base.rebuilt(nx=k * base.nx,
                                                            corner_contacts=None))
            for k in (1, 2, 4)]
    h = [_h0(s) for s in sols]
    order = math.log((h[0] - h[1]) / (h[1] - h[2])) / math.log(2.0)
    limit = h[2] + (h[2] - h[1]) / (2.0**order - 1.0)
    assert order == pytest.approx(2.0, abs=0.3)
    assert abs(h[0] / limit - 1.0) < 5e-3
    forces = [s.contact.sum() for s in sols]
    assert abs(forces[0] / forces[2] - 1.0) < 1e-3
    assert all(s.info.contact_passes <= 3 for s in sols)


def test_rounded_corners_state_saves_and_loads_with_its_contacts(tmp_path):
    """The contacts place nodes: they are stored, and the state loads on the same grid,
    bit for bit."""
    from gyroshell.results.base import read

    pytest.importorskip("xarray")
    sol = solve_steady(_dry(96))
    path = tmp_path / "rounded.nc"
    sol.save(path)
    back = read(path)
    assert back.model.corner_contacts == sol.model.corner_contacts
    assert np.array_equal(back.model.x, sol.model.x) and np.array_equal(back.u, sol.u)
    assert np.array_equal(back.contact, sol.contact)


def test_two_d_tape_over_rounded_corners_touches_along_the_contact_lines():
    """A 2 mm tape (96 x 16, spans 1 mm): the contacts are lines across the width at the
    width-averaged tangent point; only their nodes touch, the tape clears the rest of the
    arcs, the film stays positive, and its middle flies within 1 % of the 1-D tape on the
    same x-grid and contacts (measured 0.025 %: the free edges are 1 mm away)."""
    import warnings

    from gyroshell.bearing.model import BearingGridWarning

    head = FlatHead((Module(LAND, corner_radius=FILM_RADIUS),), 2 * DEG, 2 * DEG)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        model = BearingModel(TapeParameters(width=2e-3), AIR, velocity=4.0, head=head,
                             nx=96, ny=16, span=1e-3, contact=HARD)
    sol = solve_steady(model)
    m = sol.model
    touching = np.flatnonzero(sol.contact.reshape(m.nx - 1, m.nc).sum(axis=1))
    assert set(touching) <= set(m.contact_nodes - 1) and len(touching) == 2
    assert m.arc_clearance(sol.u) >= 0.0 and sol.pressure.min() > 0.0
    assert sol.info.contact_passes <= 3
    strip = solve_steady(m.rebuilt(infinitely_wide=True, ny=None, adapt_contacts=False))
    middle = np.interp(0.0, m.x_head, sol.spacing[:, m.ny // 2])
    assert middle == pytest.approx(_h0(strip), rel=0.01)


@pytest.mark.parametrize("contacts, match", [
    ((0.0,), r"corner_contacts must hold one x \(m\) per rounded corner .* \(2\), got 1"),
    ((-0.0005, 0.0), r"corner_contacts\[1\] must lie on the arc of corner 1"),
    ((-0.0005, math.nan), r"corner_contacts\[1\] must be finite"),
])
def test_bad_corner_contacts_are_refused_in_one_line(contacts, match):
    with pytest.raises(ParameterError, match=match) as info:
        _dry(96, corner_contacts=contacts)
    assert "\n" not in str(info.value)


# ----- 2-D: the coarse-grid start and the default grid of a wide tape ---------------------
def _two_d(width=2e-3, **kw):
    import warnings

    from gyroshell.bearing.model import BearingGridWarning

    head = FlatHead((Module(LAND, corner_radius=FILM_RADIUS),), 2 * DEG, 2 * DEG,
                    transducers=(0.0,))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        return BearingModel(TapeParameters(width=width), AIR, velocity=4.0, head=head, **kw,
                            contact=HARD)


@pytest.mark.parametrize("wide", [False, True])
def test_interpolated_start_carries_the_tape_height_across_the_arcs(wide):
    """The coarse start moves the tape's height w = z₀ + u from one grid to another: for
    a smooth w (linear between the dry string's ends plus c x (L − x)) the fine grid's
    u equals w − z₀ at its own nodes within the linear interpolation error c Δ²/4 of the
    coarse cells Δ, although u itself is curved by 1/r_c on each arc (interpolating u
    would miss there: measured 1.1e-9 and 1.3e-9 m, 1400 and 150 times the bound)."""
    from gyroshell.bearing.results import BearingSolution, NewtonInfo
    from gyroshell.bearing.steady import interpolated_state

    kw = dict(nx=96, ny=16, span=1e-3) if wide else dict(nx=200, infinitely_wide=True)
    fine = _two_d(**kw)
    coarse = _two_d(**{**kw, "nx": fine.nx // 2, "ny": fine.ny // 2 if wide else None})
    c, length = 1e-3, fine.length

    def smooth_w(m):
        z0 = m.head.dry_tape(m.x_head, m.head_radius)
        ends = z0[0] + (z0[-1] - z0[0]) * m.x / length
        return ends + c * m.x * (length - m.x), z0

    w_c, z0_c = smooth_w(coarse)
    u_c = np.repeat((w_c - z0_c)[1:-1], coarse.nc)
    p_c = np.full(coarse.n_p, AIR.ambient_pressure)
    sol = BearingSolution(coarse, u_c, p_c, np.zeros(coarse.n_u), NewtonInfo())
    z = interpolated_state(fine, sol)
    w_f, z0_f = smooth_w(fine)
    u_f = z[:fine.n_u].reshape(fine.nx - 1, fine.nc)
    bound = c * np.diff(coarse.x).max() ** 2 / 4
    assert np.abs(u_f - (w_f - z0_f)[1:-1, None]).max() <= bound * (1 + 1e-6) + 1e-18
    arcs = np.abs(np.diff(z0_f, 2) / np.diff(fine.x)[:-1] ** 2).max()
    assert arcs > 1e3 * c          # the arcs' curvature: u is not smooth there
    assert np.allclose(z[fine.n_u:], AIR.ambient_pressure, rtol=1e-14)


@pytest.mark.slow
def test_two_d_rounded_corners_converge_at_second_order():
    """A 2 mm tape on 125 x 28, 250 x 56 and 500 x 112 intervals (the default grid's
    mapping, 500 x 108 by default): the spacing at the middle of the read line converges
    at order about 2 (measured 2.02: 32.673, 32.106, 31.967 nm), its mean along the line
    too (measured 2.5: 42.46, 41.37, 41.18 nm), the corner forces within 0.2 % (measured
    0.17 % between the two finer grids); each solve adapts its contacts in at most 3
    passes."""
    base = _two_d(nx=125, ny=28)
    sols = [solve_steady(base if k == 1 else base.rebuilt(nx=k * 125, ny=k * 28,
                                                          corner_contacts=None))
            for k in (1, 2, 4)]

    def middle(sol):
        m = sol.model
        return float(np.interp(0.0, m.x_head, sol.spacing[:, m.ny // 2]))

    for values, expected, tol in (([middle(s) for s in sols], 2.0, 0.3),
                                  ([s.transducer_lines[0].mean for s in sols], 2.0, 0.7)):
        order = math.log((values[0] - values[1]) / (values[1] - values[2])) / math.log(2.0)
        assert order == pytest.approx(expected, abs=tol)
    forces = [s.contact.sum() for s in sols]
    assert abs(forces[1] / forces[2] - 1.0) < 2e-3
    assert all(s.info.contact_passes <= 3 for s in sols)


@pytest.mark.slow
def test_wide_tape_over_rounded_corners_on_its_default_grid_tends_to_the_strip():
    """The issue's 12.65 mm tape over the 1 mm land (2°/2°, r_c = 5 µm, 4 m/s) on its
    default grid, started from the coarse grids with their contacts adapted there: its
    middle flies at the infinitely wide tape's spacing on the same x-grid and contacts
    (within 1e-5; measured 1.1e-7 on the 6.35 mm tape), the contacts settle in at most 3
    passes with few Newton iterations on the default grid (measured 2 passes, 6), and only
    the contact lines' nodes touch."""
    model = _two_d(width=12.65e-3)
    sol = solve_steady(model)
    m = sol.model
    assert sol.info.contact_passes <= 3 and sol.info.iterations <= 20
    touching = np.flatnonzero(sol.contact.reshape(m.nx - 1, m.nc).sum(axis=1))
    assert set(touching) <= set(m.contact_nodes - 1)
    assert m.arc_clearance(sol.u) >= 0.0
    strip = solve_steady(m.rebuilt(infinitely_wide=True, ny=None, adapt_contacts=False))
    middle = np.interp(0.0, m.x_head, sol.spacing[:, m.ny // 2])
    assert m.y[m.ny // 2] == pytest.approx(0.5 * m.params.width)
    assert middle == pytest.approx(_h0(strip), rel=1e-5)


def test_newton_never_steps_backwards_when_an_arc_node_dips_below_the_head():
    """A rounded arc's nodes off its contact may dip below the head during the iteration
    (they are projected back afterwards): the step limit keeps every other node's spacing
    within [h/5, 5h + σ] and must stay a fraction 0 < α <= 1 of the step. With a node at
    h < 0 its ratios once gave α = −2.2 (measured on a 1.2 mm corner at 4 m/s: Newton
    went backwards to pressures of −4e6 Pa). Closed form of the limit here: the free node
    at h = 1 µm moving down by 0.9 µm may go a fraction (1 − 1/5) / 0.9 = 0.889 of the way."""
    from gyroshell.bearing.steady import _step_limit

    sigma = 20e-9
    h = np.array([-33e-9, 1e-6, 2e-6])
    du = np.array([65e-9, -0.9e-6, 0.0])
    floor = np.array([-1.0, sigma, sigma])
    alpha = _step_limit(h, du, np.zeros(3, dtype=bool), sigma, floor)
    assert alpha == pytest.approx(0.8 / 0.9, rel=1e-12)
    assert 0.0 < _step_limit(h[:1], du[:1], np.zeros(1, dtype=bool), sigma, floor[:1]) <= 1.0


@pytest.mark.slow
def test_a_large_point_contact_corner_at_speed_converges_with_floating_point_errors_raised():
    """r_c = 1.2 mm at 2° (r_c θ = 0.23 ℓ_bend: the tangent-point model) at 4 m/s: with
    numpy's floating-point errors raised the solve once failed in the line search's
    pressure guard (a division by zero at p <= 0, after a backward step). It now converges,
    its mass flux constant along the film to round-off."""
    head = FlatHead((Module(1e-3, corner_radius=1.2e-3),), 2 * DEG, 2 * DEG,
                    transducers=(0.0,))
    model = BearingModel(TapeParameters(), AIR, velocity=4.0, head=head,
                         infinitely_wide=True, arc_contact="point", contact=HARD)
    with np.errstate(all="raise"):
        sol = solve_steady(model)
    assert sol.transducer_lines[0].minimum >= HARD.roughness
    assert np.all(sol.pressure > 0.0)
    spread, terms, _ = flux_spread_1d(sol)
    assert spread < 1e-9 * terms


@pytest.mark.slow
def test_the_contact_on_a_large_rounded_corner_is_read_as_that_corners():
    """In the tangent-point model only each arc's contact node may touch the head, so the
    whole contact force belongs to the corners and none to the land (an exact
    consequence). At 4 m/s a 1.4 mm corner (r_c θ_c = 0.27 ℓ_bend) is touched near its
    arc's land end, 0.22 mm from the corner's x (its arc's middle, r_c φ/2 = 0.244 mm
    from either end): the readings' zones once reached only r_c θ_c + ℓ_bend = 0.23 mm and
    gave the whole 7.3 N/m to the land."""
    head = FlatHead((Module(1e-3, corner_radius=1.4e-3),), 2 * DEG, 2 * DEG,
                    transducers=(0.0,))
    model = BearingModel(TapeParameters(), AIR, velocity=4.0, head=head,
                         infinitely_wide=True, contact=HARD)
    assert model.wrapped_corners == ()
    sol = solve_steady(model)
    corners = [c.force for c in sol.corner_forces]
    assert sol.contact_force > 1.0                                  # it touches (N/m)
    assert sum(corners) == pytest.approx(sol.contact_force, rel=1e-12)
    assert all(f > 0.0 for f in corners)
    assert sum(land.force for land in sol.land_forces) == 0.0
