"""The structure the physics guarantees: M diagonal positive, G skew, K symmetric and
positive definite exactly below the critical speed."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse.linalg as spla
from convergence import observed_order

from gyroshell import TapeModel, TapeParameters, divergence_speed
from gyroshell.tape.operators import PlateCurvatures, nodal_membrane, unknown_widths

WIDTH = 6.35e-3


@pytest.fixture(params=["free", "simply-supported"])
def model(request) -> TapeModel:
    return TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 10, edges=request.param))


def test_mass_is_diagonal_and_positive(model):
    M = model.M.toarray()
    assert np.count_nonzero(M - np.diag(np.diag(M))) == 0
    assert np.all(np.diag(M) > 0)
    # The lumped masses add up to the tape's mass on the unknown nodes' control areas.
    g = model.grid
    inner_area = (g.length - g.hx) * (g.width if g.free_edges else g.width - g.hy)
    assert np.diag(M).sum() == pytest.approx(model.params.density * inner_area)


@pytest.mark.parametrize("velocity", [0.0, 50.0, 120.0])
def test_gyroscopic_matrix_is_skew_symmetric(model, velocity):
    G = model.G(velocity)
    assert abs(G + G.T).max() == 0.0
    if velocity == 0.0:
        assert G.nnz == 0 or abs(G).max() == 0.0


@pytest.mark.parametrize("velocity", [0.0, 50.0, 120.0])
def test_stiffness_is_exactly_symmetric(model, velocity):
    K = model.K(velocity)
    assert abs(K - K.T).max() == 0.0


def test_stiffness_definite_below_and_indefinite_above_critical(model):
    v_c = divergence_speed(model)
    below = sla.eigvalsh(model.K(0.999 * v_c).toarray())
    above = sla.eigvalsh(model.K(1.001 * v_c).toarray())
    assert below.min() > 0.0
    assert above.min() < 0.0 < above.max()


def test_membrane_matrix_is_positive_definite(model):
    assert sla.eigvalsh(model.B.toarray()).min() > 0.0


def test_assembly_is_vectorised_and_fast_on_the_long_tape():
    """The L_x/L_y = 19 Table 1 grid (~33,000 unknowns) has the expected size and band."""
    m = TapeModel(TapeParameters(length_ratio=19))
    assert m.unknowns == 778 * 42
    K = m.K(50.0).tocoo()
    assert np.max(np.abs(K.row - K.col)) <= 2 * (m.grid.ny + 1) + 2


# ----- one node-coordinate assembly: uniform nodes give the uniform stencils -------------
#: Relative agreement of the node-coordinate assembly with the uniform stencils.
ROUND_OFF = 1e-12


def _uniform_stencils(model: TapeModel, velocity: float):
    """M, G(V), B from the uniform-grid stencils written out: trapezoid control areas
    hx × (hy, hy/2 at free edges), G = ρV (S⁺ − S⁻) ⊗ w_y, B = (δ⁺)ᵀ hx δ⁺ ⊗ w_y."""
    g, p = model.grid, model.params
    wy = np.full(g.n_across, g.hy)
    if g.free_edges:
        wy[0] = wy[-1] = 0.5 * g.hy
    n = g.n_lines
    shift = np.eye(n, k=1) - np.eye(n, k=-1)
    second = (2 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)) / g.hx
    M = p.density * np.kron(np.full(n, g.hx), wy)
    G = p.density * velocity * np.kron(shift, np.diag(wy))
    B = np.kron(second, np.diag(wy))
    return M, G, B


@pytest.mark.parametrize("spacing", [WIDTH / 8, WIDTH / 10])
@pytest.mark.parametrize("edges", ["free", "simply-supported"])
def test_node_coordinate_assembly_matches_the_uniform_stencils(edges, spacing):
    """M, G and K = A + (T − ρV²) B, assembled from the node coordinates (the air
    bearing's graded assembly), equal the uniform stencils to round-off."""
    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=spacing, edges=edges))
    velocity = 30.0
    M, G, B = _uniform_stencils(model, velocity)
    K = model.A.toarray() + model.effective_tension(velocity) * B
    for mine, reference in ((model.M.diagonal(), M), (model.G(velocity).toarray(), G),
                            (model.K(velocity).toarray(), K)):
        assert np.abs(mine - reference).max() <= ROUND_OFF * np.abs(reference).max()


@pytest.mark.parametrize("poisson", [0.0, 0.3])
@pytest.mark.parametrize("edges", ["free", "simply-supported"])
def test_bending_operator_is_the_13_point_biharmonic_in_the_interior(edges, poisson):
    """Away from the edges a row of A is D hx hy times the 13-point ∇⁴ stencil plus the
    foundation k hx hy, whatever ν (the Poisson and twist terms add up to 2 ∂x²∂y²)."""
    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 10, edges=edges,
                                     poisson=poisson))
    g, p = model.grid, model.params
    hx, hy = g.hx, g.hy
    stencil = {(0, 0): 6 / hx**4 + 6 / hy**4 + 8 / (hx * hy) ** 2,
               (1, 0): -4 / hx**4 - 4 / (hx * hy) ** 2, (2, 0): 1 / hx**4,
               (0, 1): -4 / hy**4 - 4 / (hx * hy) ** 2, (0, 2): 1 / hy**4,
               (1, 1): 2 / (hx * hy) ** 2}
    full = {}
    for (a, b), value in stencil.items():
        for sa in (1, -1):
            for sb in (1, -1):
                full[(sa * a, sb * b)] = value
    centre = np.zeros(g.shape)
    i, j = g.nx // 2, g.ny // 2
    centre[i, j] = 1.0
    row = g.to_field(model.A @ g.from_field(centre))
    expected = np.zeros(g.shape)
    for (a, b), value in full.items():
        expected[i + a, j + b] = p.D * hx * hy * value
    expected[i, j] += p.k * hx * hy
    assert np.abs(row - expected).max() <= ROUND_OFF * np.abs(expected).max()


def _graded(length: float, n: int, bunching: float = 0.6) -> np.ndarray:
    """n + 1 nodes on [0, length] (m), smoothly (1 + bunching)/(1 − bunching) times finer at
    both ends than in the middle."""
    s = np.linspace(0.0, 1.0, n + 1)
    return length * (s - bunching * np.sin(2 * np.pi * s) / (2 * np.pi))


@pytest.mark.parametrize("free_edges", [True, False])
def test_graded_bending_operator_is_exactly_symmetric(free_edges):
    p = TapeParameters(width=WIDTH, length_ratio=1.0)
    curvatures = PlateCurvatures(_graded(p.length, 24), _graded(p.width, 16), free_edges)
    A = curvatures.stiffness(p.bending_matrix, p.k)
    assert abs(A - A.T).max() == 0.0
    assert sla.eigvalsh(A.toarray()).min() > 0.0


@pytest.mark.slow
def test_graded_simply_supported_plate_converges_to_navier_at_second_order():
    """All edges simply supported, load sin(πx/L) sin(πy/W) on graded nodes: the deflection
    D (α² + β²)² + k + (T − ρV²) α² = 1 per unit load (Navier), at second order."""
    p = TapeParameters(width=WIDTH, length_ratio=1.0, poisson=0.3)
    velocity = 20.0
    alpha, beta = np.pi / p.length, np.pi / p.width
    exact = 1.0 / (p.D * (alpha**2 + beta**2) ** 2 + p.k
                   + (p.tension - p.density * velocity**2) * alpha**2)
    errors, steps = [], []
    for n in (16, 32, 64):
        x, y = _graded(p.length, 2 * n), _graded(p.width, n)
        curvatures = PlateCurvatures(x, y, free_edges=False)
        A = curvatures.stiffness(p.bending_matrix, p.k)
        B = nodal_membrane(x, unknown_widths(y, free_ends=False))
        shape = np.outer(np.sin(alpha * x[1:-1]), np.sin(beta * y[1:-1])).ravel()
        K = (A + (p.tension - p.density * velocity**2) * B).tocsc()
        w = spla.spsolve(K, curvatures.areas * shape)
        errors.append(np.abs(w - exact * shape).max() / exact)
        steps.append(1.0 / n)
    assert errors[-1] < 5e-5
    assert observed_order(steps, errors) == pytest.approx(2.0, abs=0.1)
