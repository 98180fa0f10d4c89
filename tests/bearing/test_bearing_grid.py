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


def test_corner_widths_refine_each_corner_to_its_own_constriction():
    """Per-centre corner widths: the density at a centre is 1 + (corner_ratio − 1)
    corner_width / width (the spacing growing at the same rate beyond), an entry None
    adds nothing there, and the cumulative stays the density's integral (trapezoidal
    quadrature on 200,000 intervals)."""
    L, ratio, width = 1e-3, 101.0, 1e-6
    g = LineGrading(1.0, 0.0, (0.2e-3, 0.5e-3, 0.8e-3), ratio, width,
                    (width, 10.0 * width, None))
    terms = ((0.2e-3, ratio, width), (0.5e-3, 1.0 + (ratio - 1.0) / 10.0, 10.0 * width))
    t = np.array([0.2e-3, 0.5e-3, 0.8e-3, 0.9e-3])
    expected = [1.0 + sum((rk - 1.0) / math.hypot(1.0, (tk - c) / w) for c, rk, w in terms)
                for tk in t]
    assert np.allclose(g.density(t), expected, rtol=1e-12, atol=0.0)
    two = LineGrading(1.0, 0.0, (0.2e-3, 0.5e-3), ratio, width, (width, 10.0 * width))
    assert np.array_equal(g.density(t), two.density(t))     # nothing at the third centre
    t = np.linspace(0.0, L, 200001)
    integral = np.concatenate([[0.0], np.cumsum(0.5 * (g.density(t[1:])
                                                       + g.density(t[:-1])) * np.diff(t))])
    assert np.allclose(g.cumulative(t), integral, rtol=1e-6, atol=0.0)


def test_start_grid_refines_only_the_corners_the_tape_turns_over():
    """Two coplanar modules under the smooth law, the first with rounded corners: the
    smooth solve's start grid (turned_corner_scales) keeps the sharp outer corner's
    width (1), widens the rounded outer one to √(2 r_c s) (s = corner_width /
    CORNER_WIDTH) and drops the refinement at the inner edges into the gap (turn 0);
    the model's own grid refines all four. A scale per corner is checked."""
    from dataclasses import replace

    from gyroshell import ParameterError
    from gyroshell.bearing import AirParameters, BearingModel
    from gyroshell.bearing.contact import ContactParameters
    from gyroshell.bearing.head import FlatHead, Module
    from gyroshell.bearing.mesh import Grading
    from gyroshell.bearing.model import CORNER_WIDTH
    from gyroshell.bearing.smooth import turned_corner_scales

    r = 1e-3
    head = FlatHead((Module(1e-3, corner_radius=r), Module(1e-3)), math.radians(2.0),
                    math.radians(2.0), gaps=(0.2e-3,))
    model = BearingModel(TapeParameters(), AirParameters(), velocity=4.0, head=head,
                         infinitely_wide=True, contact=ContactParameters())
    s = model.grading.corner_width / CORNER_WIDTH
    scales = turned_corner_scales(model)
    assert scales[0] == pytest.approx(math.sqrt(2.0 * r * s) / s, rel=1e-12)
    assert scales[1:] == (None, None, 1.0)
    start = model.rebuilt(grading=replace(model.grading, corner_scales=scales), nx=None)
    assert turned_corner_scales(start) is None          # a start grid has none of its own
    width = model.grading.corner_width
    for m, widths in ((model, (1.0,) * 4), (start, scales)):
        spacing, x = np.diff(m.x), m.x_head[:-1]
        for centre, w in zip(m._centres(), widths, strict=True):
            near = spacing[np.argmin(np.abs(x - centre))]
            if w is None:
                assert near > 100.0 * width
            else:
                assert near < 2.0 * w * width
    with pytest.raises(ParameterError, match="one entry per corner"):
        model.rebuilt(grading=replace(model.grading, corner_scales=(1.0, None)), nx=None)
    with pytest.raises(ParameterError, match=r"corner_scales\[1\]"):
        Grading(corner_scales=(1.0, -2.0))


def test_strip_elastic_force_is_the_matrices_rows_without_their_round_off():
    """StripOperators.elastic_force against the exact (rational) value of the same rows,
    A u + T' B u + T' W κ − f_κ from the same float spacings and widths, on nodes refined
    to 15 nm about a corner under a tape 50 µm up (smooth u): within a tenth of the
    matrices' round-off bound ε Σ|K_ij||u_j| + ε|T' W κ| + ε|f_κ| on every row and 1e-5
    of it on the sub-100 nm cells (plus the result's own rounding), while the assembled
    K u + T' W κ − f_κ, within that bound, misses the exact rows by 1e4 times the nested
    form's largest error (the round-off that drove Newton's steps)."""
    from fractions import Fraction

    params = TapeParameters()
    L = 0.5e-3
    x = line_nodes(L, 80, LineGrading(1.0, 0.0, (0.25e-3,), 1.0 + 20e-6 / 15e-9, 15e-9))
    assert np.diff(x).min() < 30e-9
    ops = StripOperators(params, x)
    t_eff = 80.0
    xi = x[1:-1]
    u = 50e-6 * np.sin(np.pi * xi / L) * (1.0 + 0.1 * np.sin(3.0 * xi / L))
    kappa = np.where(np.abs(xi - 0.25e-3) < 20e-6, 1.0 / 2e-3, 0.0)
    nested = ops.elastic_force(u, kappa, t_eff)
    fine = (ops.W < 100e-9)
    K = (ops.A + t_eff * ops.B).tocsr()
    matrix = K @ u + t_eff * ops.W * kappa - ops.curvature_load(kappa)

    F = Fraction
    h = [F(v) for v in np.diff(x)]
    W = [F(v) for v in ops.W]
    uf = [F(0)] + [F(v) for v in u] + [F(0)]
    D, k, T = F(params.D), F(ops.params.k), F(t_eff)
    s = [(uf[j + 1] - uf[j]) / h[j] for j in range(len(h))]
    c = [(s[i + 1] - s[i]) / W[i] - F(kappa[i]) for i in range(len(W))]
    cf = [F(0)] + c + [F(0)]
    shear = [(cf[j + 1] - cf[j]) / h[j] for j in range(len(h))]
    exact = np.array([float(D * (shear[i + 1] - shear[i]) + k * W[i] * uf[i + 1]
                            - T * W[i] * c[i]) for i in range(len(W))])
    eps = np.finfo(float).eps
    bound = eps * (abs(K) @ np.abs(u) + np.abs(t_eff * ops.W * kappa)
                   + np.abs(ops.curvature_load(kappa)))
    err, own = np.abs(nested - exact), 4.0 * eps * np.abs(exact)
    assert np.all(err <= 0.1 * bound + own)                 # measured 0.03
    assert np.all(err[fine] <= 1e-5 * bound[fine] + own[fine])   # measured 2.6e-7
    assert np.all(np.abs(matrix - exact) <= 10.0 * bound)   # the same rows (0.75)
    assert np.abs(matrix - exact).max() > 1e4 * err.max()   # measured 6.6e6
