"""The ordering of a banded LU (gyroshell.linalg.ordering).

A matrix numbered line by line on an m-wide strip with a two-line stencil has half-bandwidth
2m: the rule keeps the natural order up to NATURAL_HALF_BANDWIDTH and takes minimum degree
beyond. Whatever the order, A x = b with b made from a chosen x must give that x back to
round-off (the exact solution is known because b was built from it).
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from gyroshell import ParameterError, TapeModel, TapeParameters
from gyroshell.engines.newmark import Newmark
from gyroshell.linalg.factorization import BAND_GROWTH_LIMIT, ORDERING, BandLU
from gyroshell.linalg.ordering import (
    NATURAL,
    NATURAL_HALF_BANDWIDTH,
    column_ordering,
    factorize_banded,
    half_bandwidth,
)


def strip_matrix(across: int, lines: int, rng) -> sp.csc_matrix:
    """A nonsymmetric, diagonally dominant matrix coupling each node to the nodes up to two
    lines on (half-bandwidth 2·across + 2), like K_eq's pattern."""
    n = across * lines
    offsets = [d for d in range(-2 * across - 2, 2 * across + 3)]
    diagonals = [rng.uniform(-1, 1, n - abs(d)) for d in offsets]
    A = sp.diags(diagonals, offsets, shape=(n, n), format="csc")
    return (A + sp.diags(np.full(n, 4.0 * across + 8.0))).tocsc()


def test_half_bandwidth_of_patterns():
    assert half_bandwidth(sp.identity(5)) == 0
    assert half_bandwidth(sp.csr_matrix((4, 4))) == 0
    assert half_bandwidth(sp.diags([1.0, 2.0], [0, -3], shape=(6, 6))) == 3


@pytest.mark.parametrize("across", [8, 30])
def test_narrow_bands_keep_their_order_wide_ones_take_minimum_degree(across, rng):
    A = strip_matrix(across, 12, rng)
    narrow = half_bandwidth(A) <= NATURAL_HALF_BANDWIDTH
    assert half_bandwidth(A) == 2 * across + 2
    assert column_ordering(A) == (NATURAL if narrow else ORDERING)
    x = rng.standard_normal(A.shape[0])
    factor = factorize_banded(A)
    # "auto": the narrow band in its own order with diagonal pivots (a dominant diagonal)
    assert factor.ordering == column_ordering(A)
    assert factor.name == ("band" if narrow else "superlu")
    assert not narrow or (not factor.pivoted and factor.growth <= BAND_GROWTH_LIMIT)
    np.testing.assert_allclose(factor.solve(A @ x), x, rtol=0, atol=1e-13 * np.abs(x).max())
    superlu = factorize_banded(A, "superlu")
    assert (superlu.name, superlu.ordering) == ("superlu", column_ordering(A))
    np.testing.assert_allclose(superlu.solve(A @ x), x, rtol=0, atol=1e-13 * np.abs(x).max())


@pytest.mark.parametrize("diagonal", [0.0, 1e-6])
def test_a_band_whose_diagonal_pivots_are_unstable_is_factored_with_partial_pivoting(
        diagonal, rng):
    """A zero diagonal has no LU without pivoting; a tiny one has one of growth ~1e6 (its
    first multipliers are ~1/diagonal): both are refused and factored by SuperLU with
    partial pivoting, and A x = b still gives the chosen x back."""
    A = strip_matrix(4, 10, rng).tolil()
    A.setdiag(diagonal)
    A = A.tocsc()
    x = rng.standard_normal(A.shape[0])
    band = BandLU(A)
    assert band.pivoted and not band.growth <= BAND_GROWTH_LIMIT
    scale = np.abs(x).max() * np.linalg.cond(A.toarray())
    np.testing.assert_allclose(band.solve(A @ x), x, rtol=0, atol=1e-14 * scale)


def test_the_band_solves_a_block_of_right_hand_sides_column_by_column(rng):
    A = strip_matrix(5, 9, rng)
    X = rng.standard_normal((A.shape[0], 3))
    band = BandLU(A)
    assert not band.pivoted
    np.testing.assert_allclose(band.solve(A @ X), X, rtol=0, atol=1e-13 * np.abs(X).max())


def test_the_band_refuses_complex_input_instead_of_dropping_its_imaginary_part(rng):
    A = strip_matrix(4, 8, rng)
    with pytest.raises(ParameterError, match="BandLU: matrix must be real"):
        BandLU(A * (1 + 1j))
    band = BandLU(A)
    with pytest.raises(ParameterError, match="rhs must be real"):
        band.solve(np.ones(A.shape[0]) * 1j)


def test_other_backends_keep_their_own_order(rng):
    A = strip_matrix(6, 10, rng)
    x = rng.standard_normal(A.shape[0])
    factor = factorize_banded(A, "banded")
    assert factor.name == "banded" and factor.ordering is None
    np.testing.assert_allclose(factor.solve(A @ x), x, rtol=0, atol=1e-13 * np.abs(x).max())
    with pytest.raises(ParameterError, match="backend must be one of auto"):
        factorize_banded(A, "magic")
    with pytest.raises(ParameterError, match="must be square"):
        factorize_banded(sp.eye(3, 4).tocsc())


def test_newmark_orders_the_papers_half_naturally_and_its_full_grid_by_minimum_degree():
    """Table 1's grid (41 intervals across): the symmetric half's K_eq has half-bandwidth
    42 (natural order), the full one 84 (minimum degree); both marches agree to round-off."""
    stepper = Newmark(TapeModel(TapeParameters(length_ratio=1.5)), 50.0, dt=2e-6)
    half = stepper.march(20, progress=False)
    full = stepper.march(20, progress=False, symmetry=False)
    assert (half.info["symmetry"], half.info["ordering"]) == ("half", NATURAL)
    assert (full.info["symmetry"], full.info["ordering"]) == ("full", ORDERING)
    np.testing.assert_allclose(half.load_point, full.load_point, rtol=0,
                               atol=1e-12 * np.abs(full.load_point).max())
