"""The bearing's graded grid: the plate operators keep their structure (exactly symmetric
A, B and K, skew G, exact control areas) and converge at second order to closed-form solutions on
smoothly graded nodes; the wrap loads stay consistent with the dry configuration."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse.linalg as spla
from closed_forms import beam_on_foundation, levy_profile
from convergence import observed_order

from gyroshell import TapeParameters
from gyroshell.bearing.geometry import dry_curvature
from gyroshell.bearing.mesh import LineGrading, line_nodes, symmetric_line_nodes
from gyroshell.bearing.tape import PlateOperators, StripOperators
from gyroshell.tape import operators as core
from gyroshell.tape.grid import Grid

WIDTH = 6.35e-3


def _graded_nodes(params: TapeParameters, nx: int, ny: int):
    """x refined 4× about two interior points (like the wrap corners), y 6× at the edges."""
    L, W = params.length, params.width
    gx = LineGrading(4.0, L / 10, (0.3 * L, 0.7 * L))
    gy = LineGrading(6.0, W / 10, (0.0, W))
    return symmetric_line_nodes(L, nx, gx), symmetric_line_nodes(W, ny, gy)


def test_mapped_nodes_are_smooth_nested_and_mirror_symmetric():
    g = LineGrading(5.0, 1e-3, (0.0, 6e-3))
    t = symmetric_line_nodes(6e-3, 40, g)
    fine = symmetric_line_nodes(6e-3, 80, g)
    assert np.allclose(fine[::2], t, rtol=0, atol=1e-15)
    assert np.allclose(t + t[::-1], 6e-3, rtol=0, atol=1e-18) and t[20] == 3e-3
    h = np.diff(fine)
    assert h[0] < h[len(h) // 2] / 2.5                   # graded: finer at the edges
    assert np.max(np.abs(np.diff(h)) / h[:-1]) < 0.1     # ... smoothly
    assert np.allclose(g.cumulative(line_nodes(6e-3, 40, g)),
                       np.linspace(0, g.cumulative(6e-3), 41), rtol=0, atol=1e-17)


def test_graded_plate_operators_keep_their_structure():
    params = TapeParameters(width=WIDTH, length_ratio=1.0)
    x, y = _graded_nodes(params, 24, 16)
    ops = PlateOperators(params, x, y)
    for M in (ops.A, ops.B, ops.A + params.tension * ops.B):
        assert abs(M - M.T).max() == 0.0
    strip = StripOperators(params, x)
    assert abs(strip.A - strip.A.T).max() == 0.0
    G = ops.G(30.0)
    assert abs(G + G.T).max() == 0.0
    assert np.all(ops.M.diagonal() > 0)
    # the control areas of the unknown nodes tile the tape between the half intervals
    # next to the pinned ends
    inner = params.width * (params.length - 0.5 * (x[1] - x[0]) - 0.5 * (x[-1] - x[-2]))
    assert ops.W.sum() == pytest.approx(inner, rel=1e-14)
    # positive definite: the smallest eigenvalue of the stiffness is positive
    K = (ops.A + params.tension * ops.B).tocsc()
    assert spla.eigsh(K, k=1, sigma=0, which="LM", return_eigenvectors=False)[0] > 0


def test_uniform_nodes_give_the_core_operators():
    """The tape's own operators on its uniform grid: A is the same assembly (bit for bit),
    B and G agree to round-off."""
    params = TapeParameters(width=3e-3)
    g = Grid(0.01, 3e-3, 40, 12, "free")
    ops = PlateOperators(params, g.x, g.y)
    assert abs(ops.A - core.bending_foundation(g, params)).max() == 0.0
    assert abs(PlateOperators(params, g).A - ops.A).max() == 0.0
    for mine, theirs in ((ops.B, core.membrane(g)),
                         (ops.G(3.0), core.gyroscopic(g, params, 3.0))):
        assert abs(mine - theirs).max() <= 1e-13 * abs(theirs).max()
    assert np.allclose(ops.W, g.areas, rtol=1e-14)


def _sine_response(params, velocity, nx, ny, m=2):
    """Static plate under p = sin(αx) uniform across, on the graded grid."""
    x, y = _graded_nodes(params, nx, ny)
    ops = PlateOperators(params, x, y)
    alpha = m * np.pi / params.length
    f = ops.W * np.repeat(np.sin(alpha * x[1:-1]), len(y))
    K = (ops.A + (params.tension - params.density * velocity**2) * ops.B).tocsc()
    w = spla.spsolve(K, f).reshape(len(x) - 2, len(y))
    return x, y, w, alpha


@pytest.mark.slow
@pytest.mark.parametrize("case", ["levy-free-edges", "beam-on-foundation"])
def test_graded_plate_converges_to_closed_forms_at_second_order(case):
    """Free lateral edges on graded nodes: ν = 0.3 against Lévy's solution (the free-edge
    moment and Kirchhoff shear conditions), ν = 0 against the beam on a foundation (the
    response stays uniform across the width exactly)."""
    overrides = (dict(foundation_stiffness=2.0e6, tension=10.0) if case.startswith("levy")
                 else dict(poisson=0.0))
    velocity = 20.0 if case.startswith("levy") else 60.0
    params = TapeParameters(width=WIDTH, length_ratio=1.0, **overrides)
    errors, steps = [], []
    for n in (24, 48, 96):
        x, y, w, alpha = _sine_response(params, velocity, n, n)
        if case.startswith("levy"):
            shape = levy_profile(params, velocity, 2, y)
        else:
            shape = np.full_like(y, beam_on_foundation(params, velocity, 2))
            assert np.ptp(w, axis=1).max() < 1e-10 * np.abs(w).max()   # round-off
        exact = np.sin(alpha * x[1:-1])[:, None] * shape[None, :]
        errors.append(np.abs(w - exact).max() / np.abs(exact).max())
        steps.append(1.0 / n)
    assert errors[-1] < 2e-3
    assert observed_order(steps, errors) == pytest.approx(2.0, abs=0.1)


def test_uniform_reference_curvature_gives_the_cylinder_on_graded_nodes():
    """A tape whose reference (stress-free) curvature is κ along x everywhere, pinned at
    both ends, takes the cylinder u = κ x (x − L)/2 without any curl across the width:
    the reference-curvature load and the plate operator are consistent on any spacing (the
    non-uniform second difference is exact on quadratics)."""
    params = TapeParameters(width=WIDTH, length_ratio=1.0, foundation_stiffness=0.0)
    x, y = _graded_nodes(params, 30, 20)
    ops = PlateOperators(params, x, y)
    kappa = 50.0
    u = spla.spsolve(ops.A.tocsc(), ops.curvature_load(np.full(len(x) - 2, kappa)))
    exact = np.repeat(kappa * x[1:-1] * (x[1:-1] - params.length) / 2, len(y))
    assert np.abs(u - exact).max() < 1e-9 * np.abs(exact).max()
    strip = StripOperators(params, x)
    u1 = spla.spsolve(strip.A.tocsc(), strip.curvature_load(np.full(len(x) - 2, kappa)))
    assert np.abs(u1 - exact[::len(y)]).max() < 1e-9 * np.abs(exact).max()


def test_wrap_load_turns_the_tape_through_the_wrap_angle_on_graded_nodes():
    """Σ W κ = θ exactly on any x-grid (κ = 1/R − δ²w₀ telescopes), so the discrete belt
    wrap load (T − ρV²) W κ carries the tension through exactly the wrap angle."""
    R, theta, L = 0.02, math.radians(15), 0.0093
    g = LineGrading(4.0, 5e-4, (L / 2 - R * theta / 2, L / 2 + R * theta / 2))
    for n in (64, 311):
        x = line_nodes(L, n, g)
        kappa = dry_curvature(x, L, R, theta)
        assert StripOperators(TapeParameters(), x).W @ kappa == pytest.approx(theta,
                                                                               rel=1e-12)
