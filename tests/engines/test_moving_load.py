"""Moving and intermittent loads against the classical moving-load solutions (Frýba).

A line load uniform across a free-edged tape with ν = 0 keeps the deflection uniform across
the width, so the tape is exactly a beam on the shell foundation with tension: the steady
deflection under a load moving at U (tape at V, lab-frame damping c) is the Fourier
integral of :func:`closed_forms.moving_line_load`. The load is switched on with a smooth
ramp and the damping lets the start-up transient die out before the comparison.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from closed_forms import moving_line_load
from convergence import observed_order

from gyroshell import Grid, ParameterError, TapeModel, TapeParameters, gaussian_load
from gyroshell.engines.newmark import march
from gyroshell.engines.static import solve_static
from gyroshell.tape.loads import gaussian_exponent
from gyroshell.tape.moving_loads import (
    ContactWindows,
    GaussianShape,
    MovingLoad,
    PreparedLoads,
    StraightPath,
    UniformShape,
    UserShape,
    drum_heads,
)

#: Line-load exponent, 1/m²: a Gaussian of 1 mm scale along x (resolved by coarse grids).
ALPHA = 1.0 / 1e-3**2
LINE = (GaussianShape(ALPHA), UniformShape())
#: A smooth switch-on (one long contact window with a raised-cosine ramp), s.
SWITCH_ON = ContactWindows(period=1.0, duration=1.0, ramp=50e-6)


def beam_model(nx: int, ratio: float = 4.0) -> TapeModel:
    """A free-edged ν = 0 tape of L_x/L_y = ``ratio``, nx x 8 intervals."""
    p = TapeParameters(poisson=0.0, length_ratio=ratio)
    return TapeModel(p, grid=Grid(p.length, p.width, nx, 8, "free"))


def steady_line_error(model: TapeModel, velocity: float, load_speed: float, damping: float,
                      *, dt: float, duration: float, x0: float) -> tuple[float, float]:
    """Relative max error of w(x, L_y/2) at the end against the closed form, and its peak."""
    p, g = model.params, model.grid
    load = MovingLoad(StraightPath((x0, p.width / 2), (load_speed, 0.0)), shape=LINE,
                      contact=SWITCH_ON)
    steps = round(duration / dt)
    result = march(model, velocity, dt=dt, steps=steps, load=load, damping=damping,
                   snapshot_times=[steps * dt])
    field = result.snapshots.fields[-1]
    assert np.ptp(field, axis=1).max() < 1e-10 * np.abs(field).max()  # width-uniform
    centre = x0 + load_speed * steps * dt
    exact = moving_line_load(p, velocity, load_speed, damping, ALPHA, g.x - centre)
    return np.abs(field[:, 4] - exact).max() / np.abs(exact).max(), np.abs(exact).max()


# ----- the nodal forces ---------------------------------------------------------------
def test_a_resting_head_is_the_gaussian_load_of_eq_17():
    model = TapeModel(TapeParameters(length_ratio=4))
    x0, y0 = model.params.load_centroid
    prepared = PreparedLoads(model, [MovingLoad(StraightPath((x0, y0)))], np.zeros(1))
    np.testing.assert_allclose(prepared.vector(0), gaussian_load(model.grid, model.params),
                               rtol=0, atol=1e-14 * model.force.max())


@pytest.mark.parametrize("fraction", [0.0, 0.3, 0.5, 0.77])
def test_a_head_between_nodes_carries_the_whole_force(fraction):
    """Exact cell integration: Σ F = P₀ π/α wherever the centre sits, as the head moves."""
    p = TapeParameters(length_ratio=4)
    model = TapeModel(p)
    h = model.grid.hx
    start = (p.length / 2 + fraction * h, p.width / 2 + 0.4 * fraction * model.grid.hy)
    head = MovingLoad(StraightPath(start, (h / 1e-6 * 0.37, 0.0)))
    prepared = PreparedLoads(model, [head], 1e-6 * np.arange(5))
    total = p.load * math.pi / gaussian_exponent(p.width)
    for n in range(5):
        assert prepared.vector(n).sum() == pytest.approx(total, rel=1e-12)


def test_a_user_shape_is_integrated_through_its_antiderivative():
    """A box of half-width b along x (antiderivative clip(s, −b, b)): force = P₀ 2b L_y."""
    model = beam_model(64)
    p, b = model.params, 1.3e-3
    box = UserShape(lambda s: np.clip(s, -b, b), radius=b)
    head = MovingLoad(StraightPath((0.41 * p.length, p.width / 2)), shape=(box, UniformShape()))
    force = PreparedLoads(model, [head], np.zeros(1)).vector(0)
    assert force.sum() == pytest.approx(p.load * 2 * b * p.width, rel=1e-12)


# ----- Frýba's moving load ----------------------------------------------------------------
@pytest.mark.slow
def test_moving_load_matches_fryba_with_order_two():
    """U = 50 m/s, V = 0: the steady travelling deflection, h and Δt halved twice."""
    errors, spacings = [], []
    for nx, dt in ((64, 2e-6), (128, 1e-6), (256, 5e-7)):
        model = beam_model(nx)
        err, _ = steady_line_error(model, 0.0, 50.0, 1000.0, dt=dt, duration=300e-6,
                                   x0=5e-3)
        errors.append(err)
        spacings.append(model.grid.hx)
    assert errors[-1] < 5e-4
    assert observed_order(spacings, errors) == pytest.approx(2.0, abs=0.15)


@pytest.mark.slow
def test_moving_load_on_a_moving_tape_matches_fryba():
    """V = 40 m/s, the load moving upstream at U = −20 m/s: relative speed 60 m/s."""
    err, _ = steady_line_error(beam_model(128), 40.0, -20.0, 1000.0, dt=1e-6,
                               duration=250e-6, x0=20e-3)
    assert err < 2e-3


@pytest.mark.slow
def test_resonant_load_speed_amplifies_and_converges():
    """At U = √((T + 2√(Dk))/ρ), the undamped resonance, the deflection peaks: the damped
    Newmark answer matches the closed form with order two and beats slower and faster loads."""
    model = beam_model(250, ratio=8)
    u_cr = model.params.strip_critical_speed
    errors, spacings, peaks = [], [], {}
    for nx, dt in ((250, 1e-6), (500, 5e-7), (1000, 2.5e-7)):
        m = beam_model(nx, ratio=8)
        err, peak = steady_line_error(m, 0.0, u_cr, 1000.0, dt=dt, duration=400e-6, x0=5e-3)
        errors.append(err)
        spacings.append(m.grid.hx)
    assert errors[-1] < 2e-3
    assert observed_order(spacings, errors) == pytest.approx(2.0, abs=0.2)
    for factor in (0.0, 0.6, 1.0, 1.4):
        speed = factor * u_cr
        duration = min(400e-6, 40e-3 / max(speed, 1.0))
        result = march(model, 0.0, dt=1e-6, steps=round(duration / 1e-6), damping=1000.0,
                       load=MovingLoad(StraightPath((5e-3, model.params.width / 2),
                                                    (speed, 0.0)), shape=LINE,
                                       contact=SWITCH_ON))
        peaks[factor] = np.abs(result.w).max()
    assert peaks[1.0] > 1.4 * peaks[0.0]
    assert peaks[1.0] > max(peaks[0.6], peaks[1.4])


@pytest.mark.slow
@pytest.mark.parametrize(("velocity", "load_speed"), [(40.0, 15.0), (10.0, 25.0)])
def test_load_moving_at_u_settles_to_the_static_solution_at_v_minus_u(velocity, load_speed):
    """In the load's frame the equation is the static one at speed V − U plus the lab-frame
    damping term −cU W': the settled deflection approaches the static solver's at |V − U|
    linearly in c."""
    model = beam_model(256)
    p = model.params
    x0 = 6e-3
    differences, dampings = [], (2000.0, 1000.0, 500.0)
    for c in dampings:
        duration = 8 * 2 * p.density / c + 200e-6
        dt = 1e-6
        steps = round(duration / dt)
        head = MovingLoad(StraightPath((x0, p.width / 2), (load_speed, 0.0)), shape=LINE,
                          contact=SWITCH_ON)
        result = march(model, velocity, dt=dt, steps=steps, load=head, damping=c)
        centre = x0 + load_speed * steps * dt
        resting = MovingLoad(StraightPath((centre, p.width / 2)), shape=LINE)
        force = PreparedLoads(model, [resting], np.zeros(1)).vector(0)
        static = solve_static(model, abs(velocity - load_speed), force=force).w
        differences.append(np.abs(result.w - static).max() / np.abs(static).max())
    assert differences[-1] < 0.03
    assert observed_order(dampings, differences) == pytest.approx(1.0, abs=0.15)


# ----- contact windows and several heads -------------------------------------------------
def test_contact_envelope_abrupt_and_smooth():
    abrupt = ContactWindows(period=10e-6, duration=4e-6)
    t = np.array([0.0, 3.9e-6, 4.1e-6, 9.9e-6, 10e-6, 13e-6])
    np.testing.assert_array_equal(abrupt.envelope(t), [1, 1, 0, 0, 1, 1])
    smooth = ContactWindows(period=10e-6, duration=4e-6, ramp=1e-6)
    e = smooth.envelope(np.array([0.0, 0.5e-6, 1e-6, 2e-6, 3.5e-6, 4e-6, 5e-6]))
    np.testing.assert_allclose(e, [0, 0.5, 1, 1, 0.5, 0, 0], atol=1e-12)


def test_intermittent_force_follows_the_envelope():
    model = TapeModel(TapeParameters(length_ratio=4, spacing=6.35e-3 / 12))
    p = model.params
    contact = ContactWindows(period=20e-6, duration=8e-6, ramp=2e-6, ramp_shape="linear")
    head = MovingLoad(StraightPath(p.load_centroid), contact=contact)
    times = 1e-6 * np.arange(41)
    prepared = PreparedLoads(model, [head], times)
    totals = np.array([prepared.vector(n).sum() for n in range(41)])
    full = prepared.vector(4).sum()
    np.testing.assert_allclose(totals, full * contact.envelope(times), rtol=1e-12, atol=0)


def test_drum_heads_alternate_and_each_resweeps_its_track():
    heads = drum_heads(2, (1e-3, 1e-3), (40.0, 10.0), revolution_period=100e-6,
                       contact_duration=50e-6)
    t = np.array([10e-6, 60e-6])
    on = np.array([h.envelope(t) for h in heads])
    np.testing.assert_array_equal(on, [[1, 0], [0, 1]])
    x0, _ = heads[0].centres(np.array([10e-6]))
    x1, _ = heads[1].centres(np.array([60e-6]))
    assert x0[0] == pytest.approx(x1[0]) == pytest.approx(1e-3 + 40.0 * 10e-6)


def test_two_heads_record_the_displacement_under_each():
    model = TapeModel(TapeParameters(length_ratio=4, spacing=6.35e-3 / 12))
    p = model.params
    heads = drum_heads(2, (0.2 * p.length, 0.2 * p.width), (200.0, 30.0),
                       revolution_period=60e-6, contact_duration=30e-6, ramp=3e-6)
    result = march(model, 20.0, dt=1e-6, steps=120, load=heads, damping=200.0)
    assert result.head_displacements.shape == (121, 2)
    np.testing.assert_array_equal(result.load_point, result.head_displacements[:, 0])
    frame = result.to_frame()
    assert {"w_head0", "w_head1"} <= set(frame.columns)


# ----- refusals --------------------------------------------------------------------------
@pytest.mark.parametrize(("make", "match"), [
    (lambda: ContactWindows(period=1e-6, duration=2e-6), "contact duration must be <="),
    (lambda: ContactWindows(period=-1e-6, duration=1e-7), "contact period must be > 0"),
    (lambda: ContactWindows(period=1e-5, duration=2e-6, ramp=2e-6), "contact ramp"),
    (lambda: ContactWindows(1e-5, 2e-6, ramp_shape="sine"), "ramp_shape must be one of"),
    (lambda: StraightPath((0.0, float("nan"))), "start must be finite"),
    (lambda: StraightPath((0.0, 0.0), "fast"), "load velocity must be a pair"),
    (lambda: GaussianShape(0.0), "exponent must be > 0 1/m\\^2, got 0"),
    (lambda: MovingLoad(3.0), "path must be callable"),
    (lambda: drum_heads(0, (0, 0), (1, 1), revolution_period=1, contact_duration=1),
     "heads must be an integer >= 1"),
])
def test_bad_load_definitions_raise_parameter_error(make, match):
    with pytest.raises(ParameterError, match=match):
        make()


def test_a_path_leaving_the_tape_is_refused_before_marching():
    model = TapeModel(TapeParameters(length_ratio=2, spacing=6.35e-3 / 8))
    head = MovingLoad(StraightPath((1e-3, 3e-3), (0.0, 100.0)))
    with pytest.raises(ParameterError, match="load path leaves the tape: head 0"):
        march(model, 0.0, dt=1e-6, steps=100, load=head)
    # out of contact it may be anywhere (a drum head between sweeps)
    idle = MovingLoad(StraightPath((1e-3, 3e-3), (0.0, 100.0)),
                      contact=ContactWindows(period=1e-3, duration=20e-6))
    march(model, 0.0, dt=1e-6, steps=100, load=idle)
    with pytest.raises(ParameterError, match="give either load"):
        march(model, 0.0, dt=1e-6, steps=2, load=idle, force=model.force)
    with pytest.raises(ParameterError, match="profile applies to a fixed load"):
        march(model, 0.0, dt=1e-6, steps=2, load=idle, profile=lambda t: 1.0)


def test_a_path_given_as_a_function_of_time():
    """A curved path, vectorized or scalar-only (math functions): same centres and forces."""
    import math as m

    model = TapeModel(TapeParameters(length_ratio=4, spacing=6.35e-3 / 12))
    p = model.params
    x0, y0 = p.load_centroid

    def vectorized(t):
        return x0 + 2e-3 * np.cos(2e4 * t), y0 + 1e-3 * np.sin(2e4 * t)

    def scalar(t):
        return x0 + 2e-3 * m.cos(2e4 * t), y0 + 1e-3 * m.sin(2e4 * t)

    times = 1e-5 * np.arange(8)
    a = PreparedLoads(model, [MovingLoad(vectorized)], times)
    b = PreparedLoads(model, [MovingLoad(scalar)], times)
    np.testing.assert_allclose(a.centres, b.centres, rtol=1e-15)
    np.testing.assert_allclose(a.centres[3, 0], [x0 + 2e-3 * m.cos(0.6), y0 + 1e-3 * m.sin(0.6)])
    for n in range(8):
        np.testing.assert_array_equal(a.vector(n), b.vector(n))
    result = march(model, 0.0, dt=1e-5, steps=7, load=MovingLoad(scalar))
    assert np.all(np.isfinite(result.load_point))
