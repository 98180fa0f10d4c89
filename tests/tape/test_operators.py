"""The structure the physics guarantees: M diagonal positive, G skew, K symmetric and
positive definite exactly below the critical speed."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla

from gyroshell import TapeModel, TapeParameters, divergence_speed

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
