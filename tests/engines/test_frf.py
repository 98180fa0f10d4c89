"""The frequency response (K − ω²M + iω(G + C)) W = F against independent answers.

Statics at ω → 0, the Navier closed form of a damped plate on the foundation under a
harmonic sin·sin pressure (order 2 in h), peaks at the eigen-solver's frequencies, the
steady state of a long damped Newmark run under a harmonic load (order 2 in Δt), and the
reduced model against direct solves within its own error estimate.
"""

from __future__ import annotations

import numpy as np
import pytest
from closed_forms import navier_static
from convergence import observed_order

from gyroshell import ParameterError, TapeModel, TapeParameters, pressure_load, solve_static
from gyroshell.engines.eigen import modes
from gyroshell.engines.frequency_response import (
    direct_response,
    frequency_response,
    parse_frequencies,
)
from gyroshell.engines.newmark import march
from gyroshell.tape.loads import Harmonic

WIDTH = 6.35e-3


@pytest.fixture(scope="module")
def small() -> TapeModel:
    """L_x/L_y = 2, 16 x 8 intervals, load off the centre lines (every mode is excited)."""
    return TapeModel(TapeParameters(length_ratio=2, spacing=WIDTH / 8, load_x=0.3 * 2 * WIDTH,
                                    load_y=0.3 * WIDTH))


def test_zero_frequency_is_the_static_deflection(small):
    """ω = 0 is K w = F; as ω → 0 the response approaches it as ω² (V = 0, no damping) or
    as ω (the iω(G + C) term)."""
    static = solve_static(small, 50.0)
    res = direct_response(small, 50.0, [0.0], damping=300.0)
    assert res.response[0, 0] == pytest.approx(static.load_point_deflection, rel=1e-12)
    w1 = modes(small, 0.0, 1).omega[0]
    steps = w1 * np.array([1e-2, 5e-3, 2.5e-3])
    for velocity, damping, order in ((0.0, None, 2.0), (50.0, 300.0, 1.0)):
        h0 = solve_static(small, velocity).load_point_deflection
        h = direct_response(small, velocity, steps, damping=damping).response[:, 0]
        errors = np.abs(h - h0) / abs(h0)
        assert errors[-1] < 1e-3
        assert observed_order(steps, errors) == pytest.approx(order, abs=0.05)


def test_damped_navier_plate_with_order_two():
    """All sides simply supported, V = 0, pressure p sin(πx/L_x) sin(πy/L_y) e^{iωt}:
    W = p / (D(α² + β²)² + Tα² + k − ρω² + iωc) at the centre; h halved twice."""
    c = 800.0
    errors, spacings = [], []
    for n in (8, 16, 32):
        p = TapeParameters(length_ratio=2, spacing=WIDTH / n, edges="simply-supported")
        model = TapeModel(p)
        omega = np.array([0.5, 0.99, 1.3]) * p.foundation_frequency
        force = pressure_load(model.grid, lambda X, Y, p=p: p.load * np.sin(
            np.pi * X / p.length) * np.sin(np.pi * Y / p.width))
        res = direct_response(model, 0.0, omega, damping=c, force=force)
        stiffness = 1.0 / navier_static(p, 0.0, 1, 1)
        exact = p.load / (stiffness - p.density * omega**2 + 1j * omega * c)
        errors.append(np.abs(res.response[:, 0] - exact).max() / np.abs(exact).max())
        spacings.append(model.grid.hx)
    assert errors[-1] < 2e-3
    assert observed_order(spacings, errors) == pytest.approx(2.0, abs=0.1)


@pytest.mark.slow
@pytest.mark.parametrize("velocity", [0.0, 50.0])
def test_peaks_sit_at_the_undamped_frequencies(velocity):
    """Lightly damped (ζ ~ 1e-4), the amplitude peaks at the eigen-solver's ω_j."""
    p = TapeParameters(length_ratio=2, spacing=WIDTH / 8, foundation_stiffness=0.0,
                       load_x=0.3 * 2 * WIDTH, load_y=0.3 * WIDTH)
    model = TapeModel(p)
    found = modes(model, velocity, 4).omega
    for w in found:
        local = w * np.linspace(0.995, 1.005, 41)
        for _ in range(2):  # locate the peak, then zoom in around it
            amplitude = direct_response(model, velocity, local, damping=0.05).amplitude[:, 0]
            k = int(np.argmax(amplitude))
            assert 0 < k < len(local) - 1, "no interior peak"
            local = np.linspace(local[k - 1], local[k + 1], 41)
        assert abs(local[20] / w - 1) < 1e-6
    # the peaks sit lower when the tape moves
    if velocity:
        assert np.all(found < modes(model, 0.0, 4).omega)


@pytest.mark.slow
def test_frf_is_the_steady_state_of_a_long_damped_newmark_run(small):
    """F sin ωt from rest, damped: after the start-up dies out the load point moves as
    Im(H e^{iωt}); amplitude and phase from a least-squares fit over the last period."""
    c, velocity = 2000.0, 50.0
    omega = 0.8 * modes(small, velocity, 1).omega[0]
    h = direct_response(small, velocity, [omega], damping=c).response[0, 0]
    period = 2 * np.pi / omega
    errors, dts = [], []
    for dt in (1e-6, 5e-7, 2.5e-7):
        steps = round(400e-6 / dt)
        res = march(small, velocity, dt=dt, steps=steps, damping=c,
                    profile=Harmonic(omega / (2 * np.pi)))
        last = res.times > res.times[-1] - period
        t, w = res.times[last], res.load_point[last]
        basis = np.c_[np.sin(omega * t), np.cos(omega * t)]
        (a, b), *_ = np.linalg.lstsq(basis, w, rcond=None)
        fitted = a + 1j * b  # w = Im((a + ib) e^{iωt}) = a sin + b cos
        errors.append(abs(fitted - h) / abs(h))
        dts.append(dt)
    assert errors[-1] < 1e-3
    assert observed_order(dts, errors) == pytest.approx(2.0, abs=0.2)


@pytest.mark.slow
def test_reduced_model_matches_direct_solves_within_its_estimate():
    model = TapeModel(TapeParameters(length_ratio=4, spacing=WIDTH / 12))
    omega = np.linspace(0.0, 2.0e5, 400)
    res = frequency_response(model, 50.0, omega, damping=100.0, probes=[(0.01, 0.001)],
                             method="reduced", tol=1e-6)
    assert res.info["basis_size"] < model.unknowns / 2
    check = np.random.default_rng(1).choice(len(omega), 12, replace=False)
    direct = direct_response(model, 50.0, omega[check], damping=100.0,
                             probes=[(0.01, 0.001)])
    scale = np.abs(direct.response).max(axis=0)
    err = (np.abs(res.response[check] - direct.response)
           / np.maximum(np.abs(direct.response), 1e-6 * scale)).max(axis=1)
    assert np.all(err <= np.maximum(res.error_estimate[check], 1e-10))
    assert res.error_estimate.max() <= 1e-6


@pytest.mark.slow
def test_auto_falls_back_to_direct_solves_where_the_estimate_is_too_large():
    model = TapeModel(TapeParameters(length_ratio=4, spacing=WIDTH / 12))
    omega = np.linspace(0.0, 2.0e5, 60)
    res = frequency_response(model, 50.0, omega, damping=100.0, max_points=2, tol=1e-5)
    direct = res.method == "direct"
    assert direct.any() and (~direct).any()
    assert res.info["direct_solves"] == direct.sum()
    assert np.all(res.error_estimate <= 1e-5)
    exact = direct_response(model, 50.0, omega[direct], damping=100.0).response
    np.testing.assert_allclose(res.response[direct], exact, rtol=1e-12)


@pytest.mark.parametrize(("call", "match"), [
    (lambda m: frequency_response(m, 0.0, []), "non-empty"),
    (lambda m: frequency_response(m, 0.0, [-1.0]), ">= 0 rad/s, got -1"),
    (lambda m: frequency_response(m, 0.0, [1.0], damping=-1.0),
     "damping must be >= 0 N\\*s/m\\^3, got -1"),
    (lambda m: frequency_response(m, 0.0, [1.0], method="fast"), "method must be one of"),
    (lambda m: frequency_response(m, 0.0, [1.0], tol=0), r"tol must be in \(1e-08, 0.1\], got 0"),
    (lambda m: frequency_response(m, 0.0, [1.0], probes=[(1.0, 0.0)]), "must lie on the tape"),
    (lambda m: frequency_response(m, 200.0, [1.0]), "at or above the critical speed"),
    (lambda m: parse_frequencies("0:1:0"), "NUM must be an integer >= 1"),
    (lambda m: parse_frequencies("5:1:3"), "START <= STOP"),
    (lambda m: parse_frequencies("a:b"), "START:STOP:NUM"),
])
def test_bad_requests_raise_parameter_error(small, call, match):
    with pytest.raises(ParameterError, match=match):
        call(small)
