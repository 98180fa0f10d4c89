"""The free-edged 2-D tape: its centre tends to the infinitely wide tape as it widens, its
edges come closer to the head, the edge spacing converges under refinement, and contact
is handled by the active set (Newton converges with the edges touching down)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD
from convergence import observed_order

from gyroshell import TapeParameters
from gyroshell.bearing import BearingModel
from gyroshell.bearing.steady import solve_steady

# Slow as a whole: 2-D bearing states on refined graded grids (about 20 s of module fixtures).
pytestmark = pytest.mark.slow

WRAP = math.radians(15.0)
SPAN = 2e-3


def _solve(width=None, nx=100, ny=None, grading=None, **tape):
    params = TapeParameters(**({} if width is None else {"width": width}), **tape)
    model = BearingModel(params, FIRST_ORDER, velocity=4.0, wrap_angle=WRAP, nx=nx,
                         ny=ny, span=SPAN, infinitely_wide=width is None, grading=grading,
                         contact=HARD)
    return solve_steady(model)


def test_centre_tends_to_the_infinitely_wide_tape():
    wide = _solve().central_spacing
    gaps = [abs(_solve(w, ny=n).central_spacing - wide) / wide
            for w, n in ((3e-3, 12), (6e-3, 24), (12e-3, 48))]
    assert gaps[0] > gaps[1] > gaps[2]
    assert gaps[2] < 5e-3


def test_edges_fly_lower_and_the_minimum_sits_at_an_edge_near_the_exit():
    sol = _solve(3e-3, ny=30)
    across = sol.cross_width_spacing
    assert across[0] < 0.5 * across[len(across) // 2]
    assert np.allclose(across, across[::-1], rtol=1e-9)          # symmetric
    x_min, y_min = sol.minimum_location
    half_wrap = 0.5 * sol.model.params.radius * WRAP
    assert y_min in (0.0, sol.model.params.width)
    assert 0.5 * half_wrap < x_min < 1.5 * half_wrap


def test_edge_spacing_converges_under_refinement():
    nys = [30, 60, 120]
    edge = np.array([_solve(3e-3, ny=n).cross_width_spacing[0] for n in nys])
    order = observed_order(1.0 / np.array(nys[:-1]), np.abs(np.diff(edge)))
    assert order > 1.5
    assert abs(edge[-1] - edge[-2]) < 0.06 * edge[-1]


@pytest.mark.slow
def test_contact_set_converges_without_stalling():
    """A coarse grid leaves the edge rows unsupported: they touch down and Newton's active
    set settles; the contact force balances what the air cannot carry."""
    sol = _solve(6.35e-3, nx=80, ny=16, grading="uniform", foundation_stiffness=0.0)
    assert sol.contact_nodes > 0 and sol.contact_force > 0
    assert sol.info.iterations < 40
    assert sol.minimum_spacing == pytest.approx(sol.model.air.roughness, rel=1e-9)
    touching = sol.spacing <= sol.model.air.roughness * (1 + 1e-9)
    assert touching[:, 0].any() and not touching[:, sol.model.ny // 2].any()
    assert np.all(sol.contact >= 0.0)


def test_coarse_grid_start_reaches_the_same_state_in_fewer_iterations():
    """Starting the 2-D Newton from the solution on a grid twice as coarse (interpolated)
    instead of the extruded infinitely wide tape changes only the path: the same state,
    reached in fewer fine-grid iterations."""
    from gyroshell.bearing.steady import initial_state

    def solve(threshold):
        model = BearingModel(TapeParameters(width=3e-3), FIRST_ORDER, velocity=4.0,
                             wrap_angle=WRAP, nx=100, ny=60, span=SPAN, contact=HARD)
        return solve_steady(model, z0=initial_state(model, coarse_min_unknowns=threshold))

    extruded, coarse = solve(10**9), solve(0)
    assert coarse.info.iterations < extruded.info.iterations
    assert np.allclose(coarse.spacing, extruded.spacing, rtol=0,
                       atol=1e-7 * extruded.central_spacing)


@pytest.fixture(scope="module")
def graded_sequence():
    """The 3 mm tape on three nested graded grids (both counts doubled each time), and
    on the uniform grid as large as the finest of them."""
    graded = [_solve(3e-3, nx=nx, ny=ny) for nx, ny in ((96, 24), (192, 48), (384, 96))]
    uniform = _solve(3e-3, nx=384, ny=96, grading="uniform")
    return graded, uniform


def test_edge_minimum_converges_at_second_order_on_graded_grids(graded_sequence):
    """Doubling both counts of the graded grid (the mapping fixed): the central spacing,
    the edge spacing at the wrap centre and the minimum at the exit corner converge with
    observed order about 2 (the schemes keep their order on the smooth mapping)."""
    graded, _ = graded_sequence
    for quantity in ("central_spacing", "minimum_spacing"):
        v = np.array([getattr(s, quantity) for s in graded])
        assert observed_order([1.0, 0.5], np.abs(np.diff(v))) == pytest.approx(2.2, abs=0.4)
    edge = np.array([s.cross_width_spacing[0] for s in graded])
    assert observed_order([1.0, 0.5], np.abs(np.diff(edge))) == pytest.approx(2.2, abs=0.4)
    for s in graded:                       # an edge node at the exit corner
        x_min, y_min = s.minimum_location
        assert y_min == 0.0 and 0.0 < x_min - 0.5 * s.model.params.radius * WRAP < 0.3e-3


@pytest.mark.slow
def test_graded_grid_matches_the_uniform_grid_of_its_finest_spacing(graded_sequence):
    """The graded grid with the finest spacing of a uniform one (about 24 µm along at the
    corners, 30 µm across at the edges) gives the same flying state with a quarter of the
    unknowns; at equal unknowns the graded grid is closer to the extrapolated minimum."""
    graded, uniform = graded_sequence
    g = graded[1]
    assert g.model.unknowns < 0.26 * uniform.model.unknowns
    assert np.diff(g.model.x).min() < 1.02 * np.diff(uniform.model.x).min()
    assert np.diff(g.model.y).min() < 1.02 * np.diff(uniform.model.y).min()
    assert g.minimum_spacing == pytest.approx(uniform.minimum_spacing, rel=1e-2)
    assert g.cross_width_spacing[0] == pytest.approx(uniform.cross_width_spacing[0],
                                                     rel=5e-3)
    assert g.central_spacing == pytest.approx(uniform.central_spacing, rel=3e-3)
    h = np.array([s.minimum_spacing for s in graded])
    p = np.log2((h[1] - h[0]) / (h[2] - h[1]))
    extrapolated = h[2] + (h[2] - h[1]) / (2**p - 1)
    assert abs(graded[2].minimum_spacing - extrapolated) \
        < 0.5 * abs(uniform.minimum_spacing - extrapolated)
