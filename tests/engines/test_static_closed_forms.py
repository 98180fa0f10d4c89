"""The static solver against exact solutions of the continuous problem, with observed orders.

Each case fixes a load whose exact response is known in closed form, solves K(V) w = F on
three grids (spacing halved each time) and checks both the error and the log-log slope.
"""

from __future__ import annotations

import numpy as np
import pytest
from closed_forms import beam_on_foundation, levy_profile, navier_static
from convergence import observed_order

from gyroshell import TapeModel, TapeParameters, pressure_load, solve_static

WIDTH = 6.35e-3


def _sine_load_error(params: TapeParameters, velocity: float, exact_field) -> float:
    """Max-norm relative error of the static answer to a sinusoidal pressure."""
    model = TapeModel(params)
    g = model.grid
    m = exact_field.m
    alpha = m * np.pi / params.length
    shape_y = exact_field.shape_y
    sol = solve_static(model, velocity,
                       pressure_load(g, lambda X, Y: np.sin(alpha * X) * shape_y(Y)))
    exact = np.sin(alpha * g.X) * exact_field(params, velocity, g.y)[None, :]
    return float(np.abs(sol.field - exact).max() / np.abs(exact).max())


class _Case:
    m = 2
    shape_y = staticmethod(lambda Y: 1.0)


class NavierCase(_Case):
    """All sides simply supported, p sin(2πx/L_x) sin(πy/L_y)."""

    velocity = 40.0
    shape_y = staticmethod(lambda Y: np.sin(np.pi * Y / WIDTH))

    def __call__(self, p, velocity, y):
        return navier_static(p, velocity, self.m, 1) * np.sin(np.pi * y / p.width)


class BeamCase(_Case):
    """Free edges with ν = 0, p sin(2πx/L_x) uniform across: a beam on a foundation."""

    velocity = 60.0

    def __call__(self, p, velocity, y):
        return np.full_like(y, beam_on_foundation(p, velocity, self.m))


class LevyCase(_Case):
    """Free edges with ν = 0.3: the Lévy solution, not uniform across the width."""

    velocity = 20.0

    def __call__(self, p, velocity, y):
        return levy_profile(p, velocity, self.m, y)


CASES = {
    "navier": (NavierCase(), dict(edges="simply-supported")),
    "beam-on-foundation": (BeamCase(), dict(poisson=0.0)),
    # A soft foundation keeps the free-edge boundary layer wider than the coarsest grid.
    "levy-free-edges": (LevyCase(), dict(foundation_stiffness=2.0e6, tension=10.0)),
}


@pytest.mark.parametrize("name", CASES)
def test_static_deflection_converges_at_second_order(name):
    case, overrides = CASES[name]
    intervals = np.array([8, 16, 32])
    errors = [
        _sine_load_error(TapeParameters(length_ratio=1.0, spacing=WIDTH / n, **overrides),
                         case.velocity, case)
        for n in intervals
    ]
    assert errors[-1] < 5e-3
    assert observed_order(1.0 / intervals, errors) == pytest.approx(2.0, abs=0.1)


def test_table1_levy_solution_within_one_percent_on_paper_grid():
    """Table 1 parameters (stiff foundation, narrow edge layer) on the paper's spacing."""
    p = TapeParameters(length_ratio=1.0)
    err = _sine_load_error(p, 50.0, LevyCase())
    assert err < 5e-3


def test_free_edges_with_zero_poisson_give_a_width_uniform_beam():
    p = TapeParameters(poisson=0.0, length_ratio=2.0, spacing=WIDTH / 12)
    model = TapeModel(p)
    alpha = 3 * np.pi / p.length
    field = solve_static(model, 30.0, pressure_load(model.grid,
                                                    lambda X, Y: np.sin(alpha * X))).field
    spread = np.ptp(field, axis=1).max()
    assert spread < 1e-12 * np.abs(field).max()


def test_poisson_coupling_bends_the_free_edges_like_levy():
    """With ν > 0 the free edges deflect differently from the centre, as Lévy predicts."""
    p = TapeParameters(length_ratio=1.0, spacing=WIDTH / 32, foundation_stiffness=2.0e6,
                       tension=10.0)
    model = TapeModel(p)
    alpha = 2 * np.pi / p.length
    field = solve_static(model, 0.0, pressure_load(model.grid,
                                                   lambda X, Y: np.sin(alpha * X))).field
    i = model.grid.nx // 4
    exact = levy_profile(p, 0.0, 2, model.grid.y)
    numeric_effect = field[i, 0] - field[i, model.grid.ny // 2]
    exact_effect = exact[0] - exact[model.grid.ny // 2]
    assert abs(exact_effect) > 0.05 * abs(exact[0])
    assert numeric_effect == pytest.approx(exact_effect, rel=0.02)
