"""gyroscopic_modes(M, G, K=0) (issue 18): λ²M + λG = λ(λM + G) has λ = 0 n times and the
eigenvalues of −M⁻¹G; checked against that closed form, densely and on the sparse path."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from gyroshell import gyroscopic_modes
from gyroshell.linalg.qep import DENSE_LIMIT


def rotation_generator(rates) -> sp.csr_matrix:
    """Block-diagonal skew G of 2 x 2 rotation generators [[0, w], [−w, 0]], kg/s."""
    return sp.block_diag([sp.csr_matrix([[0.0, w], [-w, 0.0]]) for w in rates], format="csr")


def closed_form(M, G) -> np.ndarray:
    """+Im of the eigenvalues of −M⁻¹G, ascending (positive ones), 1/s."""
    lam = np.linalg.eigvals(-np.linalg.solve(np.asarray(M.todense()), G.toarray()))
    return np.sort(lam.imag[lam.imag > 1e-9 * np.abs(lam).max()])


def spd(n: int, seed: int) -> sp.csr_matrix:
    rng = np.random.default_rng(seed)
    A = rng.standard_normal((n, n))
    return sp.csr_matrix(A @ A.T / n + np.eye(n))


@pytest.mark.parametrize("K", ["scalar", "sparse", "dense"])
def test_identity_mass_gives_the_rotation_rates(K):
    rates = np.array([3.0, 1.0, 2.0])
    G = rotation_generator(rates)
    M = sp.identity(6, format="csr")
    zero = {"scalar": 0, "sparse": sp.csr_matrix((6, 6)), "dense": np.zeros((6, 6))}[K]
    res = gyroscopic_modes(M, G, zero, count=3)
    np.testing.assert_allclose(res.eigenvalues, 1j * np.sort(rates), rtol=1e-12)
    assert res.info["zero_eigenvalues"] == 6  # λ = 0, n-fold; G has no kernel
    assert res.stability == "stable" and res.residuals.max() < 1e-12


def test_full_mass_matches_minus_inverse_mass_times_g():
    G = rotation_generator([0.5, 4.0, 9.0, 20.0])
    M = spd(8, seed=1)
    res = gyroscopic_modes(M, G, 0, count=4)
    np.testing.assert_allclose(res.eigenvalues.imag, closed_form(M, G), rtol=1e-10)
    np.testing.assert_array_equal(res.eigenvalues.real, 0.0)


def test_odd_size_counts_the_kernel_of_g_among_the_zeros():
    G = sp.block_diag([rotation_generator([2.0]), sp.csr_matrix((1, 1))], format="csr")
    res = gyroscopic_modes(sp.identity(3, format="csr"), G, 0, count=1)
    np.testing.assert_allclose(res.eigenvalues, [2j], rtol=1e-12)
    assert res.info["zero_eigenvalues"] == 3 + 1


def test_more_pairs_than_g_has_begin_with_lambda_zero():
    res = gyroscopic_modes(sp.identity(4, format="csr"), rotation_generator([1.0, 5.0]), 0,
                           count=3)
    np.testing.assert_allclose(res.eigenvalues, [0, 1j, 5j], atol=1e-12)
    assert np.all(res.residuals < 1e-12)


def test_sparse_path_matches_the_closed_form():
    n = 2 * (DENSE_LIMIT + 60)
    rng = np.random.default_rng(7)
    rates = rng.uniform(1.0, 100.0, n // 2)
    mass = rng.uniform(0.5, 2.0, n)
    M, G = sp.diags(mass, format="csr"), rotation_generator(rates)
    res = gyroscopic_modes(M, G, sp.csr_matrix((n, n)), count=5)
    assert res.info["method"] == "arpack"
    np.testing.assert_allclose(res.eigenvalues.imag, closed_form(M, G)[:5], rtol=1e-9)
    assert res.residuals.max() < 1e-10


def test_a_shift_picks_the_pairs_nearest_it():
    rates = np.arange(1.0, 61.0)
    M, G = sp.identity(120, format="csr"), rotation_generator(rates)
    res = gyroscopic_modes(M, G, 0, count=3, sigma=30.2j)
    np.testing.assert_allclose(res.eigenvalues.imag, [29.0, 30.0, 31.0], rtol=1e-9)
