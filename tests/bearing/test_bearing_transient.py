"""Transient flight: it settles onto the steady state, and a tension step moves it to the
new steady spacing."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD

from gyroshell import TapeParameters
from gyroshell.bearing import BearingModel
from gyroshell.bearing.steady import BearingSolution, solve_steady
from gyroshell.bearing.transient import march, tension_harmonic, tension_step
from gyroshell.core.errors import ParameterError

#: Newmark with numerical damping of the grid-scale ringing (unconditionally stable).
DAMPED = {"beta": 0.3025, "gamma": 0.6}


@pytest.fixture(scope="module")
def model():
    return BearingModel(TapeParameters(), FIRST_ORDER, velocity=4.0,
                        wrap_angle=math.radians(15), infinitely_wide=True, nx=160, contact=HARD)


@pytest.mark.slow
def test_tension_step_moves_to_the_new_steady_spacing(model):
    before = solve_steady(model)
    after = solve_steady(model, tension=120.0)
    run = march(before, dt=1e-5, steps=400, tension=tension_step(90.0, 120.0),
                record_every=50, **DAMPED)
    assert run.central_spacing[0] == pytest.approx(before.central_spacing, rel=1e-12)
    assert run.central_spacing[-1] == pytest.approx(after.central_spacing, rel=1e-3)
    assert np.allclose(run.centreline[-1], after.spacing[:, 0],
                       atol=1e-3 * after.central_spacing)
    assert after.central_spacing < before.central_spacing   # pulled closer to the head


@pytest.mark.slow
def test_disturbed_tape_settles_back(model):
    steady = solve_steady(model)
    bump = 0.3 * steady.central_spacing * np.exp(-((steady.x[1:-1] / 1e-3) ** 2))
    start = BearingSolution(model, steady.u + bump, steady.p, steady.contact, steady.info)
    run = march(start, dt=1e-5, steps=400, record_every=50, **DAMPED)
    assert abs(run.central_spacing[1] / steady.central_spacing - 1) > 1e-2
    assert run.central_spacing[-1] == pytest.approx(steady.central_spacing, rel=1e-3)
    assert run.final.p == pytest.approx(steady.p, rel=1e-5)


def test_refuses_unstable_newmark_parameters(model):
    with pytest.raises(ParameterError, match="beta, gamma"):
        march(solve_steady(model), dt=1e-6, steps=1, beta=0.1, gamma=0.5)


@pytest.mark.slow
def test_load_crossing_the_head_presses_the_tape_down_where_it_passes(model):
    """A narrow pad of 2 kPa sweeping along x at 2 m/s: the spacing below it drops while it
    crosses the wrap, and the tape flies at its steady spacing again once it has left."""
    steady = solve_steady(model)
    x = steady.x[1:-1]
    speed, width = 2.0, 0.3e-3
    start = -3e-3

    def pad(t):
        centre = start + speed * t
        return -2000.0 * model.W * np.exp(-(((x - centre) / width) ** 2))

    run = march(steady, dt=1e-5, steps=500, moving_load=pad, record_every=10, **DAMPED)
    at_centre = np.argmin(np.abs(run.t - (0.0 - start) / speed))
    assert run.central_spacing[at_centre] < 0.97 * steady.central_spacing
    assert run.central_spacing[-1] == pytest.approx(steady.central_spacing, rel=2e-3)


def _harmonic_fit(run, frequency, skip):
    """Mean, amplitude and phase of h_c(t) ≈ a + b sin ωt + c cos ωt after ``skip`` s."""
    keep = run.t >= skip
    wt = 2 * np.pi * frequency * run.t[keep]
    basis = np.column_stack([np.ones_like(wt), np.sin(wt), np.cos(wt)])
    a, b, c = np.linalg.lstsq(basis, run.central_spacing[keep], rcond=None)[0]
    return a, math.hypot(b, c), math.atan2(c, b)


@pytest.mark.slow
def test_slow_harmonic_tension_follows_the_steady_sensitivity(model):
    """T = 90 + 2 sin ωt N/m, slow against the film's settling time: the central spacing
    swings by |dh/dT| ΔT (dh/dT from two steady solves, a central difference), in
    antiphase (more tension, closer flight), lagging by ωτ: halving f halves the lag and
    brings the amplitude closer to the quasi-static one."""
    d_tension = 2.0
    steady = solve_steady(model)
    slope = (solve_steady(model, tension=90.0 + d_tension).central_spacing
             - solve_steady(model, tension=90.0 - d_tension).central_spacing) / (2 * d_tension)
    assert slope < 0
    fits = []
    for f in (40.0, 20.0):
        run = march(steady, dt=0.01 / f, steps=200,
                    tension=tension_harmonic(90.0, d_tension, f), **DAMPED)
        fits.append(_harmonic_fit(run, f, skip=1.0 / f))
    ratios = [amp / abs(slope * d_tension) for _, amp, _ in fits]
    lags = [math.pi - phase for _, _, phase in fits]
    assert abs(ratios[1] - 1) < abs(ratios[0] - 1) < 0.03
    assert abs(ratios[1] - 1) < 0.01
    assert 0 < lags[1] < lags[0] < 0.5
    assert lags[0] / lags[1] == pytest.approx(2.0, rel=0.1)
    assert fits[1][0] == pytest.approx(steady.central_spacing, rel=1e-3)


@pytest.mark.slow
@pytest.mark.parametrize("grading", ["uniform", None], ids=["uniform", "graded"])
def test_disturbed_2d_tape_settles_back_onto_the_2d_steady_state(grading):
    """A free-edged 3 mm tape: a bump across the whole width decays and the march ends on
    the 2-D steady state, spacing, pressure and contact. On the coarse uniform grid the
    edge rows rest on the head at the roughness height, so the contact set rides along;
    on the graded grid (finer at the edges) they fly."""
    model = BearingModel(TapeParameters(width=3e-3), FIRST_ORDER, velocity=4.0,
                         wrap_angle=math.radians(15), nx=60, ny=16, span=2e-3,
                         grading=grading, contact=HARD)
    assert model.graded == (grading is None)
    steady = solve_steady(model)
    assert (steady.contact_nodes > 0) == (grading == "uniform")
    x = steady.x[1:-1]
    bump = 0.3 * steady.central_spacing * np.repeat(np.exp(-((x / 1e-3) ** 2)), model.nc)
    start = BearingSolution(model, steady.u + bump, steady.p, steady.contact, steady.info)
    # on the graded grid the flying edge rows near the exit corner settle last
    run = march(start, dt=1e-5, steps=400 if grading else 600, record_every=50, **DAMPED)
    assert abs(run.central_spacing[1] / steady.central_spacing - 1) > 1e-2
    assert np.max(np.abs(run.final.spacing - steady.spacing)) < 1e-3 * steady.central_spacing
    assert np.max(np.abs(run.final.p - steady.p)) < 2e-3 * steady.central_pressure
    assert run.contact_force[-1] == pytest.approx(steady.contact_force, rel=1e-2)
