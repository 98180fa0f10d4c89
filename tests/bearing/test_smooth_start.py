"""The start of a 2-D solve under a smooth contact law (gyroshell.bearing.smooth.coarse_start).

Two 1 mm flat modules 0.3 mm apart under a 3 mm tape, the Boltzmann film over asperities:

- the coarse grids' start and the tape resting on its summits lead Newton to the same
  steady state (the state does not depend on the start: its spacing field agrees to a
  small fraction of σ_s);
- below the coarse grids' threshold the start is the infinitely wide tape's steady state,
  solved on its own, on every line across the width.
"""

from __future__ import annotations

import math

import numpy as np

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel, smooth
from gyroshell.bearing.contact import ContactParameters
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.steady import interpolated_state

HEAD = FlatHead((Module(1e-3), Module(1e-3)), math.radians(2.0), math.radians(2.0),
                gaps=(0.3e-3,))


def two_modules(**grid) -> BearingModel:
    return BearingModel(TapeParameters(width=3e-3), AirParameters(rarefaction="fukui-kaneko"),
                        velocity=4.0, head=HEAD, contact=ContactParameters(law="asperity"),
                        **grid)


def test_the_coarse_start_and_the_resting_start_reach_the_same_state(monkeypatch):
    model = two_modules(nx=200, ny=20)
    monkeypatch.setattr(smooth, "COARSE_MIN_UNKNOWNS", model.unknowns // 2)
    lines: list[str] = []
    coarse = smooth.solve_smooth(model, None, None, lines.append, None,
                                 interpolate=interpolated_state)
    assert any("coarse grid 100 x 10" in line for line in lines)
    assert coarse.info.start_iterations > 0
    resting = smooth.solve_smooth(model, smooth.resting_start(model), None, None, None,
                                  interpolate=interpolated_state)
    sigma = model.air.roughness
    np.testing.assert_allclose(coarse.spacing, resting.spacing, rtol=0, atol=0.05 * sigma)


def test_below_the_threshold_the_start_is_the_infinitely_wide_state_on_every_line():
    model = two_modules(nx=200, ny=20)
    assert model.unknowns < smooth.COARSE_MIN_UNKNOWNS
    z, taken = smooth.coarse_start(model, interpolated_state)
    strip = smooth.solve_smooth(model.rebuilt(infinitely_wide=True, ny=None), None, None,
                                None, None, interpolate=interpolated_state)
    assert taken == strip.info.iterations
    u = z[:model.n_u].reshape(model.nx - 1, model.nc)
    np.testing.assert_array_equal(u, np.repeat(strip.u[:, None], model.nc, axis=1))
    p = np.full((model.nx + 1, model.ny + 1), np.nan)
    p[model.film.interior] = z[model.n_u:]
    inner = p[1:-1, 1:-1]
    np.testing.assert_array_equal(inner, np.repeat(strip.p[:, None], model.ny - 1, axis=1))
    assert np.all(np.isfinite(inner))


def test_the_dry_tape_of_a_2d_model_already_solved_with_its_film():
    """The speed path's first state (:func:`smooth.dry_state`, the model without its film)
    after a solve with the film on the same grid, whose Jacobian patterns it must not
    take: the tape at rest on its asperities, as the dry model solves it."""
    model = two_modules(nx=200, ny=20)
    smooth.solve_smooth(model, smooth.resting_start(model), None, None, None,
                        interpolate=interpolated_state)
    budget = smooth._Budget(smooth.SolverOptions(), smooth.NewtonInfo(), None)
    z = smooth.dry_state(model, budget)
    dry = smooth.solve_smooth(model.rebuilt(dry=True), None, None, None, None,
                              interpolate=interpolated_state)
    np.testing.assert_allclose(z[:model.n_u], dry.u, rtol=0,
                               atol=0.05 * model.air.roughness)
