"""The designer's readings (gyroshell.bearing.readings) on fields whose answers are known
exactly: Couette and Poiseuille films and the inclined slider (the shear and its integral in
closed form), the slip velocity profile behind the film's flow factor, the dry tape tented
over a flat land, and contact forces placed on known nodes."""

from __future__ import annotations

import math

import numpy as np
import pytest
from convergence import observed_order

from gyroshell.bearing import readings
from gyroshell.bearing.air import AirParameters
from gyroshell.bearing.film import face_fluxes
from gyroshell.bearing.mesh import LineGrading, line_nodes, symmetric_line_nodes

MU, V, PA = 1.81e-5, 4.0, 101325.0
NO_SLIP = AirParameters(mean_free_path=0.0, compressible=False, rarefaction="first-order")
WIDTH = 3e-3


def _graded(length: float, n: int, centres=(0.3, 0.7), ratio=4.0) -> np.ndarray:
    """Nodes on [0, length] refined ``ratio``× about the given fractions of it."""
    g = LineGrading(ratio, length / 10, tuple(c * length for c in centres))
    return symmetric_line_nodes(length, n, g)


def _areas(x: np.ndarray, y: np.ndarray | None) -> np.ndarray:
    """Control areas of the nodes (half intervals at the ends), m² (m if y is None)."""
    def widths(t):
        w = np.empty(len(t))
        h = np.diff(t)
        w[0], w[-1], w[1:-1] = 0.5 * h[0], 0.5 * h[-1], 0.5 * (h[:-1] + h[1:])
        return w
    return np.outer(widths(x), np.ones(1) if y is None else widths(y))


# ----- shear and drag ---------------------------------------------------------------------
def test_plane_couette_shear_is_mu_v_over_h_and_its_integral_the_area():
    x, y = _graded(1e-3, 40), _graded(WIDTH, 16, (0.0, 1.0))
    h0 = 0.2e-6
    H, P = np.full((41, 17), h0), np.full((41, 17), PA)
    tau = readings.shear_stress(x, H, P, V, NO_SLIP)
    assert np.allclose(tau, MU * V / h0, rtol=1e-14, atol=0)
    drag = readings.integral(tau, _areas(x, y))
    assert drag == pytest.approx(MU * V / h0 * 1e-3 * WIDTH, rel=1e-13)


def test_slip_lowers_the_couette_shear_by_the_local_mean_free_path():
    # compressible: λ_e = λ p_a / p; at p = 2 p_a the wall slip is λ/2 at each wall
    x = np.linspace(0.0, 1e-3, 11)
    h0, lam = 0.1e-6, 64e-9
    air = AirParameters(mean_free_path=lam, rarefaction="first-order")
    H, P = np.full((11, 1), h0), np.full((11, 1), 2 * PA)
    tau = readings.shear_stress(x, H, P, V, air)
    assert np.allclose(tau, MU * V / (h0 + lam), rtol=1e-14, atol=0)
    inc = AirParameters(mean_free_path=lam, compressible=False, rarefaction="first-order")
    tau_inc = readings.shear_stress(x, H, P, V, inc)
    assert np.allclose(tau_inc, MU * V / (h0 + 2 * lam), rtol=1e-14, atol=0)


def _slip_profile(h, gradient, lam, velocity):
    """u(z) = G z²/(2μ) + A z + B between the head (z = 0, at rest) and the tape (z = h,
    at V) with Maxwell slip λ at both walls: u(0) = λ u'(0), u(h) = V − λ u'(h).
    Returns (flux ∫ u dz, μ u'(h))."""
    G = gradient
    # B − λ A = 0;  (h + λ) A + B = V − G h²/(2μ) − λ G h/μ
    A, B = np.linalg.solve([[-lam, 1.0], [h + lam, 1.0]],
                           [0.0, velocity - G * h * h / (2 * MU) - lam * G * h / MU])
    flux = G * h**3 / (6 * MU) + A * h * h / 2 + B * h
    return flux, MU * (G * h / MU + A)


@pytest.mark.parametrize("gradient", [-3e9, 0.0, 5e9])   # Pa/m
def test_shear_and_film_flux_come_from_one_slip_velocity_profile(gradient):
    h, lam, dx = 0.15e-6, 64e-9, 1e-6
    air = AirParameters(mean_free_path=lam, compressible=False, rarefaction="first-order")
    flux, wall_shear = _slip_profile(h, gradient, lam, V)
    f = face_fluxes(np.array([PA]), np.array([PA + gradient * dx]), np.array([h]),
                    np.array([h]), dx, V, air)
    assert f.flux[0] == pytest.approx(12 * MU * flux, rel=1e-10)
    x = np.linspace(0.0, 4 * dx, 5)
    P = (PA + gradient * x)[:, None]
    tau = readings.shear_stress(x, np.full((5, 1), h), P, V, air)
    assert np.allclose(tau, wall_shear, rtol=1e-10, atol=0)


@pytest.mark.parametrize("gradient", [-3e9, 0.0, 5e9])   # Pa/m
def test_shear_resists_a_reversed_tape_from_the_same_slip_profile(gradient):
    """A tape running towards −x (V < 0): the air pushes it towards +x with −μ u'(h),
    and that is the stress against its motion; in a Couette film it is μ|V|/(h + 2λ)."""
    h, lam = 0.15e-6, 64e-9
    air = AirParameters(mean_free_path=lam, compressible=False, rarefaction="first-order")
    _, wall_shear = _slip_profile(h, gradient, lam, -V)
    x = np.linspace(0.0, 4e-6, 5)
    P = (PA + gradient * x)[:, None]
    tau = readings.shear_stress(x, np.full((5, 1), h), P, -V, air)
    assert np.allclose(tau, -wall_shear, rtol=1e-10, atol=0)
    if gradient == 0.0:
        assert np.allclose(tau, MU * V / (h + 2 * lam), rtol=1e-12, atol=0)


@pytest.mark.parametrize("rarefaction", ["none", "first-order", "second-order",
                                         "fukui-kaneko"])
def test_couette_shear_slips_by_the_rarefaction_models_own_slip_length(rarefaction):
    """The Couette shear μV/(h + 2ζλ) takes the slip length ζλ whose Poiseuille flow is
    the model's first-order term: ζ = (Q − 1)/(6 Kn) as Kn → 0, read off the model's Q
    (Richardson-extrapolated from Kn = 1e-4, 2e-4): 0 without slip, 1 for Maxwell's slip,
    1.147 for the Boltzmann flow rate."""
    from gyroshell.bearing.rarefaction import poiseuille_flow_factor

    slope = [(poiseuille_flow_factor(rarefaction, kn)[0] - 1.0) / (6.0 * kn)
             for kn in (1e-4, 2e-4)]
    zeta = float(2.0 * slope[0] - slope[1])
    h, lam = 0.15e-6, 64e-9
    air = AirParameters(mean_free_path=lam, compressible=False, rarefaction=rarefaction)
    x = np.linspace(0.0, 4e-6, 5)
    tau = readings.shear_stress(x, np.full((5, 1), h), np.full((5, 1), PA), V, air)
    assert np.allclose(tau, MU * V / (h + 2.0 * zeta * lam), rtol=1e-6, atol=0)


def test_plane_poiseuille_part_with_a_linear_pressure():
    x = _graded(2e-3, 48)
    h0, g = 0.3e-6, -2e8                  # Pa/m: pressure falling along the motion
    H = np.full((49, 1), h0)
    P = (PA + 1e4 + g * x)[:, None]
    tau = readings.shear_stress(x, H, P, V, NO_SLIP)
    assert np.allclose(tau, MU * V / h0 + 0.5 * h0 * g, rtol=1e-9, atol=0)


def _slider(x, h1, h2, length):
    """The incompressible inclined slider without slip, h = h1 + (h2 − h1) x/L, p = p_a at
    both ends: (h, p, ∫₀ᴸ τ dx) in closed form. The flux q = V h/2 − h³p'/(12μ) is
    constant; ∫ p' = 0 gives q = V h1 h2/(h1 + h2), so p' = 6μV/h² − 12μq/h³ integrates
    exactly, and τ = μV/h + (h/2)p' = 4μV/h − 6μq/h²."""
    m = (h2 - h1) / length
    h = h1 + m * x
    q = V * h1 * h2 / (h1 + h2)
    p = PA + 6 * MU * V * (1 / h1 - 1 / h) / m - 6 * MU * q * (1 / h1**2 - 1 / h**2) / m
    drag = 4 * MU * V * length * math.log(h2 / h1) / (h2 - h1) - 6 * MU * q * length / (h1 * h2)
    return h, p, drag


def test_inclined_slider_drag_converges_at_second_order_on_graded_nodes():
    length, h1, h2 = 1e-3, 1.0e-6, 0.25e-6
    errors, steps = [], []
    for n in (32, 64, 128, 256):
        # refined 4x towards the thin trailing end, where the shear is largest
        x = line_nodes(length, n, LineGrading(4.0, length / 10, (length,)))
        h, p, exact = _slider(x, h1, h2, length)
        tau = readings.shear_stress(x, h[:, None], p[:, None], V, NO_SLIP)
        errors.append(abs(readings.integral(tau, _areas(x, None)) / exact - 1))
        steps.append(length / n)
    assert errors[-1] < 1e-4
    assert observed_order(steps, errors) == pytest.approx(2.0, abs=0.1)


def test_drag_adds_friction_times_the_contact_force_and_gives_the_tension_rise():
    T, W, mu_f = 90.0, 12.65e-3, 0.3
    d = readings.drag(2e-3, 0.5, mu_f, T, W)           # N, N
    assert d.friction == pytest.approx(mu_f * 0.5, rel=1e-15)
    assert d.total == pytest.approx(2e-3 + 0.15, rel=1e-15)
    assert d.tension_rise == pytest.approx(d.total / W, rel=1e-15)
    assert d.tension_ratio == pytest.approx(1 + d.total / W / T, rel=1e-15)
    wide = readings.drag(0.1, 2.0, 0.0, T)             # per unit width: N/m
    assert wide.friction == 0.0 and wide.tension_rise == 0.1


# ----- transducer lines -------------------------------------------------------------------
def test_transducer_line_is_exact_for_cubics_in_x_and_at_nodes():
    x, y = _graded(2e-3, 32) - 1e-3, _graded(WIDTH, 16, (0.0, 1.0))
    X, Y = np.meshgrid(x, y, indexing="ij")
    across = 1 + 4e4 * (Y - WIDTH / 2) ** 2

    def along(t):
        return 1e-7 + 2e-5 * t - 3e-2 * t * t + 40.0 * t**3

    H = along(X) * across
    x_t = 0.123e-3                                       # off-node
    line, at_node = readings.transducer_lines(x, y, H, [x_t, x[7]])
    assert np.allclose(line.spacing, along(x_t) * across[0], rtol=1e-12, atol=0)
    assert np.array_equal(at_node.spacing, H[7])
    assert line.minimum == pytest.approx(along(x_t), rel=1e-12)
    assert line.minimum_y == pytest.approx(WIDTH / 2, abs=1e-18)
    assert line.centre == line.minimum


def test_transducer_line_next_to_a_corner_interpolates_within_its_interval():
    x = np.linspace(-1e-3, 1e-3, 21)
    corner = x[10] + 0.5 * (x[11] - x[10]) + (x[12] - x[11])   # in the stencil, not the cell
    H = (1e-7 + np.abs(x - corner))[:, None]
    x_t = x[10] + 0.3 * (x[11] - x[10])
    free, kinked = readings.transducer_lines(x, None, H, [x_t], kinks=()), \
        readings.transducer_lines(x, None, H, [x_t], kinks=(corner,))
    assert kinked[0].centre == pytest.approx(1e-7 + abs(x_t - corner), rel=1e-13)
    assert abs(free[0].centre - (1e-7 + abs(x_t - corner))) > 1e-9   # the cubic would not


def test_transducer_line_mean_is_the_width_average_at_second_order():
    a, e = 1e-7, 4e4
    errors, steps = [], []
    for n in (8, 16, 32, 64):
        y = _graded(WIDTH, n, (0.0, 1.0), ratio=6.0)
        x = np.linspace(-1e-3, 1e-3, 5)
        H = a * np.ones((5, 1)) * (1 + e * (y[None, :] - WIDTH / 2) ** 2)
        (line,) = readings.transducer_lines(x, y, H, [0.2e-3])
        errors.append(abs(line.mean / (a * (1 + e * WIDTH**2 / 12)) - 1))
        steps.append(WIDTH / n)
    assert observed_order(steps, errors) == pytest.approx(2.0, abs=0.1)


def test_infinitely_wide_transducer_line_is_one_value():
    x = np.linspace(-1e-3, 1e-3, 21)
    (line,) = readings.transducer_lines(x, None, (1e-7 + x * x)[:, None], [x[4]])
    assert line.minimum == line.mean == line.centre == 1e-7 + x[4] ** 2
    assert line.minimum_y is None and line.as_dict()["x"] == x[4]


# ----- tents ------------------------------------------------------------------------------
def _dry_land(x, theta, lam, a, flank):
    """The dry tape over a flat land |x| <= a between sharp corners (k = 0, small slopes,
    D w'''' = T w'', λ = √(D/T)), both wraps θ, the head falling away at ``flank`` beyond
    the corners: the spacing above the head. On the land w = A + B cosh(x/λ), on each
    span w = −θ s + F (e^{−s/λ} − 1), s = |x| − a; w(a) = 0 and w, w', w'' continuous
    give B = −θλ e^{−α}, F = B cosh α (α = a/λ), so the tent is at x = 0 with height
    θλ(1 − e^{−α})²/2 and the span side has no local maximum."""
    alpha = a / lam
    B = -theta * lam * math.exp(-alpha)
    F = B * math.cosh(alpha)
    s = np.abs(x) - a
    land = B * (np.cosh(x / lam) - math.cosh(alpha))
    span = -theta * s + F * (np.exp(-np.maximum(s, 0) / lam) - 1) + flank * s
    return np.where(s <= 0, land, span), theta * lam * (1 - math.exp(-alpha)) ** 2 / 2


def test_dry_land_tents_end_to_end_with_the_closed_form_height():
    theta, lam, a = math.radians(2.0), 180e-6, 0.5e-3
    x = _graded(4e-3, 200, (0.375, 0.625)) - 2e-3
    h, height = _dry_land(x, theta, lam, a, math.radians(20))
    found = readings.tents(x, None, h[:, None], (-a, a), ((-a, a),))
    assert [t.side for t in found] == ["land", "span", "land", "span"]
    for tent in found:
        if tent.side == "span":
            assert tent.height is None and tent.widest_height is None
        else:
            assert tent.height == pytest.approx(height, rel=1e-6)
            assert tent.x == pytest.approx(0.0, abs=1e-12)
            assert tent.drop == pytest.approx(0.0, abs=1e-9 * height)   # tented end to end
            assert tent.widest_height == tent.height and tent.widest_y is None


def _corner_tents(x, y, ell, a):
    """A spacing that tents next to both corners of the land [−a, a]: per corner
    A(y) s e^{−s/ℓ} (s from the corner into the land), A(y) largest at the edges."""
    amplitude = 1e-3 * (1 + 4 * ((y - WIDTH / 2) / WIDTH) ** 2)
    s_in, s_out = x + a, a - x
    bump = s_in * np.exp(-s_in / ell) + s_out * np.exp(-s_out / ell)
    return 1e-8 + np.clip(bump, 0, None)[:, None] * amplitude[None, :]


def _exact_tent(ell, a):
    """Peak of s e^{−s/ℓ} + (2a − s) e^{−(2a−s)/ℓ} near s = ℓ (root of its derivative)."""
    from scipy.optimize import brentq

    def slope(s):
        return (1 - s / ell) * math.exp(-s / ell) - (1 - (2 * a - s) / ell) * math.exp(
            -(2 * a - s) / ell)
    s = brentq(slope, 0.5 * ell, 1.5 * ell, xtol=1e-16)
    return s - a, s * math.exp(-s / ell) + (2 * a - s) * math.exp(-(2 * a - s) / ell)


def test_corner_tents_along_the_centre_line_and_across_the_width():
    ell, a = 100e-6, 0.6e-3
    x = _graded(1.2e-3, 240, (0.0, 1.0)) - 0.6e-3
    y = _graded(WIDTH, 16, (0.0, 1.0))
    H = _corner_tents(x, y, ell, a)
    x_peak, bump = _exact_tent(ell, a)
    lead, _span, trail, _ = readings.tents(x, y, H, (-a, a), ((-a, a),))
    assert lead.x == pytest.approx(x_peak, abs=2e-7)
    assert trail.x == pytest.approx(-x_peak, abs=2e-7)
    assert lead.height == pytest.approx(1e-8 + 1e-3 * bump, rel=1e-5)
    assert lead.widest_height == pytest.approx(1e-8 + 2e-3 * bump, rel=1e-5)
    assert lead.widest_y in (0.0, WIDTH)
    # down to the land's middle, where both bumps are (2a − s) e^{...} small: the drop is
    # the tent less the spacing at x = 0
    middle = 1e-8 + 1e-3 * 2 * a * math.exp(-a / ell)
    assert lead.drop == pytest.approx(lead.height - middle, rel=1e-5)
    # a transducer between the corner and the tent ends the search before it
    (early, *_rest) = readings.tents(x, y, H, (-a, a), ((-a, a),), transducers=(x_peak - 5e-5,))
    assert early.height is None and early.x is None


def test_a_spacing_falling_from_the_corner_has_no_tent():
    x = np.linspace(-1e-3, 1e-3, 101)
    H = (1e-6 * (1 + np.cos(np.pi * x / 1e-3)) + 1e-8)[:, None]     # max at 0, falls out
    found = readings.tents(x, None, H, (-1e-3, 1e-3), ((-1e-3, 1e-3),))
    land = [t for t in found if t.side == "land"]
    assert all(t.x == pytest.approx(0.0, abs=1e-15) for t in land)   # the land's middle
    H2 = (1e-8 + 1e-3 * np.abs(x))[:, None]                          # V-shaped: no maximum
    assert all(t.height is None for t in readings.tents(x, None, H2, (-5e-4, 5e-4),
                                                        ((-5e-4, 5e-4),)))


# ----- contact bookkeeping ----------------------------------------------------------------
def test_contact_forces_go_to_their_corner_or_land_and_sum_to_the_total():
    # two modules: lands [-1.2, -0.2] and [0.2, 1.2] mm, a gap between them
    x = _graded(3e-3, 300, (0.1, 0.9333)) - 1.5e-3
    y = _graded(WIDTH, 8, (0.0, 1.0))
    corners = (-1.2e-3, -0.2e-3, 0.2e-3, 1.2e-3)
    lands = ((-1.2e-3, -0.2e-3), (0.2e-3, 1.2e-3))
    area = _areas(x, y)
    force = np.zeros((len(x), len(y)))
    spikes = {k: int(np.argmin(np.abs(x - c))) for k, c in enumerate(corners)}
    for k, i in spikes.items():
        force[i, :] = 1e-3 * (k + 1)
    on_land = np.flatnonzero(np.abs(x - 0.7e-3) < 0.05e-3)
    force[on_land, 3] = 2e-5
    flank = int(np.argmin(np.abs(x + 1.45e-3)))           # past the first corner's zone
    force[flank, 0] = 7e-6
    cs, ls = readings.contact_shares(x, force, area, corners, lands, zones=0.1e-3)
    total = force.sum()
    assert sum(s.force for s in cs + ls) == pytest.approx(total, rel=1e-14)
    for k, share in enumerate(cs):
        expected = 1e-3 * (k + 1) * len(y) + (7e-6 if k == 0 else 0.0)
        assert share.force == pytest.approx(expected, rel=1e-14)
        assert share.peak_pressure == pytest.approx(
            1e-3 * (k + 1) / area[spikes[k]].min(), rel=1e-14)
    assert ls[0].force == 0.0 and ls[0].centroid is None and ls[0].nodes == 0
    assert ls[1].force == pytest.approx(2e-5 * len(on_land), rel=1e-14)
    assert ls[1].nodes == len(on_land)
    assert ls[1].centroid == pytest.approx(x[on_land].mean(), rel=1e-12)
    pressure = readings.contact_pressure(force, area)
    assert readings.integral(pressure, area) == pytest.approx(total, rel=1e-14)


def test_the_depth_of_a_module_gap_is_no_tent():
    """Two lands with a gap between them: the spacing above the head peaks in the middle
    of the gap, where the head falls away; the span-side searches report no tent."""
    x = np.linspace(-1.5e-3, 1.5e-3, 301)
    gap = np.abs(x) < 0.25e-3
    H = np.where(gap, 1e-8 + 0.35 * (0.25e-3 - np.abs(x)), 1e-8)[:, None]
    corners = (-1.25e-3, -0.25e-3, 0.25e-3, 1.25e-3)
    lands = ((-1.25e-3, -0.25e-3), (0.25e-3, 1.25e-3))
    inner = [t for t in readings.tents(x, None, H, corners, lands)
             if t.side == "span" and abs(t.corner) < 1e-3]
    assert len(inner) == 2 and all(t.height is None for t in inner)
