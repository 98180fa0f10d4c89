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
