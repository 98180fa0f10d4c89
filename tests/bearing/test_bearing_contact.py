"""Touch-down: at low speed the free edges of a 2-D tape come down onto the head. The
steady solver must settle the contact set without stalling, the contact force must
converge under refinement, and a start far from the flying state must still reach it
(directly, or by pseudo-transient continuation)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD
from convergence import observed_order

from gyroshell import TapeParameters
from gyroshell.bearing import BearingModel
from gyroshell.bearing.problem import SteadyProblem
from gyroshell.bearing.pseudo_time import pseudo_time_path
from gyroshell.bearing.steady import solve_steady
from gyroshell.linalg.newton import NewtonOptions, newton

# Slow as a whole: a touch-down on nested grids (about 20 s of module fixtures).
pytestmark = pytest.mark.slow

WRAP = math.radians(15.0)
#: A 3 mm Table 1 tape at 0.2 m/s: its edges touch down between the wrap centre and the
#: exit corner (the flying height is ~0.3 µm, the edge layer's dip reaches σ = 20 nm).
WIDTH, SLOW = 3e-3, 0.2


def _model(nx, ny, velocity=SLOW, width=WIDTH):
    params = TapeParameters(width=width) if width else TapeParameters()
    return BearingModel(params, FIRST_ORDER, velocity=velocity, wrap_angle=WRAP,
                        nx=nx, ny=ny, infinitely_wide=width is None, contact=HARD)


@pytest.fixture(scope="module")
def touch_down():
    """The slow tape on three nested graded grids (both counts doubled each time)."""
    return [solve_steady(_model(nx, ny)) for nx, ny in ((80, 24), (160, 48), (320, 96))]


def test_edges_touch_down_and_newton_settles_the_contact_set_directly(touch_down):
    """Newton's active set takes the edges down onto the roughness height: on the two
    finer grids directly (no pseudo-time, no continuation, <= 40 iterations with those of
    the coarse-grid start; measured 21); contact only at the free edges, none in the
    middle, λ >= 0 and h >= σ everywhere, λ = 0 off contact (complementarity)."""
    sigma = HARD.roughness
    for k, sol in enumerate(touch_down):
        assert sol.info.continuation == []
        if k > 0:
            assert sol.info.pseudo_time == [] and sol.info.iterations <= 40
        assert sol.contact_nodes > 0 and sol.contact_force > 0.0
        assert np.all(sol.contact >= 0.0)
        assert sol.spacing.min() >= sigma * (1 - 1e-12)
        touching = sol.spacing <= sigma * (1 + 1e-9)
        # along lines within 0.2 mm of each free edge (the very edge row is curled up by
        # the Poisson moment of the wrap), symmetric, nowhere else
        y = sol.model.y
        rows = np.flatnonzero(touching.any(axis=0))
        assert np.all(np.minimum(y[rows], WIDTH - y[rows]) < 0.2e-3)
        assert np.array_equal(touching, touching[:, ::-1])
        assert (y[rows] < 0.5 * WIDTH).any()
        # off contact the contact force vanishes (at the tape unknowns: interior x-nodes)
        h_u = sol.spacing[1:-1, :].ravel()
        assert np.all(sol.contact[h_u > sigma * (1 + 1e-9)] == 0.0)
        x = sol.model.x[np.flatnonzero(touching.any(axis=1))] - 0.5 * sol.model.length
        half_wrap = 0.5 * sol.model.params.radius * WRAP
        assert np.all((0.0 < x) & (x < 1.1 * half_wrap))   # downstream half of the wrap


@pytest.mark.slow
def test_contact_force_converges_under_refinement(touch_down):
    """The total contact force (N) converges as the grid is refined (observed order about
    1.5: the edge of the contact zone is a free boundary, so less than the scheme's 2),
    and the central spacing at second order."""
    force = np.array([s.contact_force for s in touch_down])
    order = observed_order([1.0, 0.5], np.abs(np.diff(force)))
    assert order > 1.2
    assert abs(force[2] - force[1]) < 0.1 * force[2]
    hc = np.array([s.central_spacing for s in touch_down])
    assert observed_order([1.0, 0.5], np.abs(np.diff(hc))) == pytest.approx(2.0, abs=0.5)


@pytest.mark.parametrize("width, velocity, nx, ny", [(None, 4.0, 200, None),
                                                     (WIDTH, SLOW, 80, 24)],
                         ids=["infinitely wide, 4 m/s", "3 mm, 0.2 m/s, contact"])
def test_a_lifted_start_reaches_the_same_state_directly_and_through_pseudo_time(
        width, velocity, nx, ny):
    """From a tape lifted to three times its flying height over ambient air, solve_steady
    and the pseudo-transient march alone (:func:`~gyroshell.bearing.pseudo_time.
    pseudo_time_path`, each stage by the generic Newton with the wall as bounds) reach the
    state found from the solver's own start: spacing to 1e-9 of h_c, the same contact
    forces, without continuation in V."""
    model = _model(nx, ny, velocity=velocity, width=width)
    reference = solve_steady(model)
    lifted = np.concatenate([np.full(model.n_u, 3.0 * reference.central_spacing),
                             np.full(model.n_p, model.air.ambient_pressure)])

    def solve(transient, state, limit):
        problem = SteadyProblem(model, transient=transient)
        return newton(problem, state, NewtonOptions(
            tol=1e-8 if transient is None else 1e-4, max_iterations=limit or 50))

    z, steps = pseudo_time_path(model, lifted, solve)
    routed = solve_steady(model, z0=lifted)
    assert steps and routed.info.continuation == []
    lam = SteadyProblem(model).forces(z)
    for u, force in ((z[:model.n_u], lam), (routed.u, routed.contact)):
        assert np.max(np.abs(u - reference.u)) < 1e-9 * reference.central_spacing
        assert np.allclose(force, reference.contact, rtol=1e-6,
                           atol=1e-9 * max(reference.contact_force, 1e-12))
