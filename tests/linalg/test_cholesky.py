"""CHOLMOD's Cholesky (gyroshell.linalg.cholesky) and the eigen-solver's factorization back-ends:
solutions against the matrices, definiteness decided by success, the symbolic analysis reused
per pattern, and the same frequencies and certificate as the pure-scipy path."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from gyroshell import ParameterError, TapeModel, TapeParameters
from gyroshell.engines.eigen import modes, strip_frequency_estimate
from gyroshell.linalg import cholesky
from gyroshell.linalg.factorization import resolve_factorization
from gyroshell.linalg.inertia import factor_inertia

pytestmark = pytest.mark.skipif(not cholesky.available(), reason="cvxopt not installed")


def laplacian_2d(n: int) -> sp.csr_matrix:
    """The 5-point Laplacian on an n x n grid (Dirichlet): SPD, eigenvalues known."""
    t = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n))
    return (sp.kron(t, sp.identity(n)) + sp.kron(sp.identity(n), t)).tocsr()


def hermitian(n: int, shift: float, rng) -> sp.csr_matrix:
    """L + i S − shift·I with S real skew: Hermitian, definite iff shift < λ_min(L + iS)."""
    L = laplacian_2d(n)
    S = sp.random(n * n, n * n, density=4 / (n * n), random_state=rng.integers(1 << 31))
    S = 0.3 * (S - S.T)
    return (L + 1j * S - shift * sp.identity(n * n)).tocsr()


def test_real_and_complex_solves_match_the_matrix(rng):
    for A in (laplacian_2d(30), hermitian(30, -1.0, rng)):
        f = cholesky.cholesky(A)
        assert f is not None and f.definite and f.negatives == 0
        b = rng.standard_normal((A.shape[0], 3)) + 1j * rng.standard_normal((A.shape[0], 3))
        x = f.solve(b)
        assert np.linalg.norm(A @ x - b) < 1e-12 * np.linalg.norm(b)
        x1 = f.solve(b[:, 0])                       # one vector
        assert x1.shape == (A.shape[0],) and np.allclose(x1, x[:, 0], rtol=0, atol=1e-14)
        f.release()


def test_definiteness_is_decided_by_success_as_sylvester_counts(rng):
    # λ_min of the 30 x 30 Dirichlet Laplacian: 2·(2 − 2 cos(π/31))
    lam_min = 4 * (1 - np.cos(np.pi / 31))
    L = laplacian_2d(30)
    assert cholesky.cholesky(L - 0.999 * lam_min * sp.identity(900)) is not None
    assert cholesky.cholesky(L - 1.001 * lam_min * sp.identity(900)) is None
    counts = []
    for shift in (-1.0, -0.2, 0.0, 0.5, 1.0):
        A = hermitian(20, shift, rng)
        count = factor_inertia(A).negatives
        counts.append(count)
        assert (cholesky.cholesky(A) is not None) == (count == 0)
    assert counts[0] == 0 and counts[-1] > 0             # both outcomes were exercised


def test_symbolic_analysis_is_reused_for_a_pattern(rng):
    A = laplacian_2d(25)
    first = cholesky.cholesky(A)
    first.release()
    pattern = cholesky._pattern(sp.tril(A, format="csc"), "d")
    assert len(pattern.slots) >= 1                      # the analysed factor waits
    slots = len(pattern.slots)
    B = (2 * A + 3 * sp.identity(A.shape[0])).tocsr()  # same pattern, other values
    second = cholesky.cholesky(B)
    assert len(pattern.slots) == slots - 1              # taken from the pool, not rebuilt
    b = rng.standard_normal(A.shape[0])
    assert np.linalg.norm(B @ second.solve(b) - b) < 1e-12 * np.linalg.norm(b)
    # a second live factor of the same pattern is independent of the first
    third = cholesky.cholesky(A)
    assert np.linalg.norm(A @ third.solve(b) - b) < 1e-12 * np.linalg.norm(b)
    assert np.linalg.norm(B @ second.solve(b) - b) < 1e-12 * np.linalg.norm(b)
    second.release()
    third.release()
    with pytest.raises(RuntimeError, match="released"):
        second.solve(b)


@pytest.mark.slow
def test_tape_modes_agree_with_the_superlu_path_and_keep_the_certificate():
    model = TapeModel(TapeParameters(length_ratio=4))
    for velocity in (0.0, 50.0, 95.0):
        fast = modes(model, velocity, 6, factorization="cholmod")
        ref = modes(model, velocity, 6, factorization="superlu")
        assert fast.info["factorization"] == "cholmod"
        assert ref.info["factorization"] == "superlu"
        assert np.max(np.abs(fast.omega - ref.omega) / ref.omega) < 1e-10
        assert fast.info["below_shift"] == ref.info["below_shift"] == 0
        assert fast.residuals.max() < 1e-14


@pytest.mark.slow
def test_a_shift_above_frequencies_falls_back_to_the_inertia_count():
    model = TapeModel(TapeParameters(length_ratio=4))
    ref = modes(model, 50.0, 6, factorization="superlu")
    inner = 0.5 * (ref.omega[1] + ref.omega[2])        # two frequencies below the shift
    res = modes(model, 50.0, 4, sigma=1j * inner, factorization="cholmod")
    assert res.info["below_shift"] == 2                 # Q(iω_s) indefinite: SuperLU counts
    assert np.max(np.abs(res.omega - ref.omega[:4]) / ref.omega[:4]) < 1e-10


@pytest.mark.slow
def test_shift_matrix_below_the_lowest_frequency_is_positive_definite():
    model = TapeModel(TapeParameters(length_ratio=4))
    v = 50.0
    omega_1 = modes(model, v, 1, factorization="superlu").omega[0]
    for omega_s, definite in ((0.999 * omega_1, True), (1.001 * omega_1, False)):
        Q = model.K(v) - omega_s**2 * model.M + 1j * omega_s * model.G(v)
        assert (cholesky.cholesky(Q) is not None) is definite
    assert strip_frequency_estimate(model.params, model.grid, v) < omega_1


@pytest.mark.slow
def test_factorization_refusals(monkeypatch):
    model = TapeModel(TapeParameters(length_ratio=4))
    with pytest.raises(ParameterError, match="factorization must be one of"):
        modes(model, 10.0, 2, factorization="mumps")
    monkeypatch.setattr(cholesky, "_cholmod", None)
    assert not cholesky.available()
    with pytest.raises(ParameterError, match="needs cvxopt"):
        modes(model, 10.0, 2, factorization="cholmod")
    assert resolve_factorization("auto") == "superlu"
    assert modes(model, 10.0, 2).info["factorization"] == "superlu"


def test_negative_count_is_sylvesters_inertia(rng):
    """CHOLMOD's LDLᴴ count equals SuperLU's pivot count and, for the Laplacian, the number
    of its eigenvalues 2(2 − cos(iπ/31) − cos(jπ/31)) below the shift."""
    lam = np.sort([2 * (2 - np.cos(i * np.pi / 31) - np.cos(j * np.pi / 31))
                   for i in range(1, 31) for j in range(1, 31)])
    L = laplacian_2d(30)
    for shift in (0.01, 0.3, 1.1, 2.5):
        assert cholesky.negative_count(L - shift * sp.identity(900)) == np.count_nonzero(
            lam < shift)
    for shift in (-1.0, 0.5, 1.0, 2.0):
        A = hermitian(20, shift, rng)
        assert cholesky.negative_count(A) == factor_inertia(A).negatives


def test_ldl_counts_and_solves_the_indefinite_matrix_it_counted(rng):
    """The LDLᴴ that counts (Sylvester: the Laplacian's eigenvalues 2(2 − cos(iπ/31) −
    cos(jπ/31)) below the shift) also solves the indefinite matrix, real and Hermitian."""
    lam = np.sort([2 * (2 - np.cos(i * np.pi / 31) - np.cos(j * np.pi / 31))
                   for i in range(1, 31) for j in range(1, 31)])
    L = laplacian_2d(30)
    for shift in (0.3, 1.1, 2.5):
        A = (L - shift * sp.identity(900)).tocsr()
        factor = cholesky.ldl(A)
        assert factor.negatives == np.count_nonzero(lam < shift)
        assert factor.definite is False and factor.singular is False
        b = rng.standard_normal(900) + 1j * rng.standard_normal(900)
        x = factor.solve(b)
        assert np.linalg.norm(A @ x - b) <= 1e-12 * np.linalg.norm(b) * np.abs(lam).max() \
            / np.min(np.abs(lam - shift))
        factor.release()
    H = hermitian(20, 1.0, rng)
    factor = cholesky.ldl(H)
    assert factor.negatives == factor_inertia(H).negatives
    b = rng.standard_normal(400) + 1j * rng.standard_normal(400)
    assert np.linalg.norm(H @ factor.solve(b) - b) < 1e-10 * np.linalg.norm(b)
    factor.release()
    with pytest.raises(RuntimeError, match="released"):
        factor.solve(b)


def test_ldl_refuses_a_zero_pivot():
    """A zero pivot (the diagonal solve D x = 1 is not finite) leaves the inertia unknown."""
    A = sp.csr_matrix(np.array([[0.0, 1.0], [1.0, 0.0]]))
    assert cholesky.ldl(A) is None
    assert cholesky.negative_count(A) is None


def test_the_lower_triangle_is_gathered_by_a_map_made_once_per_pattern(rng):
    """The triangle CHOLMOD reads equals scipy's tril → CSC → sorted indices entry by
    entry, the first, second (map made) and third (map reused) time a pattern is seen and
    when only the values change (a new shift); a non-canonical input takes scipy's path
    and agrees too."""
    A = hermitian(12, 0.5, rng)
    for values in (A.data, 3.0 * A.data - 1j):
        B = sp.csr_matrix((values, A.indices, A.indptr), shape=A.shape)
        expected = sp.tril(B, format="csc")
        expected.sort_indices()
        for _ in range(3):   # scipy's path (pattern noted), the map made, the map reused
            got = cholesky._lower(B)
            assert np.array_equal(got.indptr, expected.indptr)
            assert np.array_equal(got.indices, expected.indices)
            assert np.array_equal(got.data, expected.data)
    coo = A.tocoo()
    got = cholesky._lower(coo)
    assert abs(got - sp.tril(A, format="csc")).max() == 0
