"""K = 0, undamped: λ²M + λG = λ(λM + G), solved as the linear pencil it is.

With no stiffness, Q(λ) = λ(λM + G): λ = 0 is an eigenvalue of multiplicity n (Q(0) = 0,
every φ is a static mode), and the other n eigenvalues are those of −M⁻¹G. As G is real
skew-symmetric, iG is Hermitian, and λ = iμ with

    iG φ = μ M φ,   M > 0,

a Hermitian-definite pencil whose real μ come in pairs ±μ (plus μ = 0 on the kernel of G).
The result holds the ``count`` pairs +iμ, μ > 0, nearest the shift (the lowest without
one), like the undamped subcritical case; λ = 0 is counted in ``info["zero_eigenvalues"]``
(n plus the kernel of G, where the dense path sees it). If G has fewer than ``count``
nonzero pairs, λ = 0 comes first, as many times as needed (any vector is its eigenvector).

The quadratic solver would otherwise divide by the zero ‖K‖ (its frequency scale, its
σ = 0 factorization of K): "matrices' scales too far apart" or "K is singular".
"""

from __future__ import annotations

import time

import numpy as np
import scipy.linalg as la
import scipy.sparse.linalg as spla

from .problem import DENSE_LIMIT, Problem
from .spectrum import norm1

#: |μ| at or below this fraction of ‖G‖₁/‖M‖₁ is a zero eigenvalue (the kernel of G).
ZERO_RTOL = 1e-10
#: Extra eigenpairs asked of the sparse iteration per try (zeros and −μ sit near the shift).
SPARSE_MARGIN = 4


def without_stiffness(prob: Problem, shift: complex | None) -> tuple[np.ndarray, np.ndarray]:
    """The ``count`` eigenpairs (λ = iμ, μ >= 0; vectors as columns) of λ²M + λG (K = 0)."""
    t0 = time.perf_counter()
    omega_s = 0.0 if shift is None else abs(shift.imag)
    zero = ZERO_RTOL * norm1(prob.G) / max(norm1(prob.M), 1e-300)
    if prob.n <= max(DENSE_LIMIT, 2 * prob.count + SPARSE_MARGIN + 2):
        mu, phi = la.eigh(1j * prob.G.toarray(), prob.M.toarray())
        method = "dense"
        prob.info["zero_eigenvalues"] = prob.n + int(np.count_nonzero(np.abs(mu) <= zero))
    else:
        mu, phi = _sparse(prob, omega_s, zero)
        method = "arpack"
        prob.info["zero_eigenvalues"] = None  # at least n; the kernel of G is not counted
    keep, zeros = _select(mu, zero, omega_s, prob.count)
    prob.info.update(method=method, shift=1j * omega_s, below_shift=None, stiffness="zero",
                     solve_time=time.perf_counter() - t0, factor_time=0.0)
    return 1j * np.where(zeros, 0.0, mu[keep]), phi[:, keep]


def _select(mu: np.ndarray, zero: float, omega_s: float, count: int
            ) -> tuple[np.ndarray, np.ndarray]:
    """Indices of the ``count`` positive μ nearest ω_s (ascending) and which of them stand
    for λ = 0: if G has too few nonzero pairs, the vectors of the smallest |μ| left, as
    eigenvectors of λ = 0 (any vector is one: Q(0) = 0)."""
    positive = np.flatnonzero(mu > zero)
    chosen = positive[np.argsort(np.abs(mu[positive] - omega_s), kind="stable")][:count]
    chosen = chosen[np.argsort(mu[chosen], kind="stable")]
    missing = count - len(chosen)
    if missing <= 0:
        return chosen, np.zeros(len(chosen), dtype=bool)
    rest = np.setdiff1d(np.arange(len(mu)), chosen)
    rest = rest[np.argsort(np.abs(mu[rest]), kind="stable")][:missing]
    return (np.concatenate([rest, chosen]),
            np.concatenate([np.ones(len(rest), bool), np.zeros(len(chosen), bool)]))


def _sparse(prob: Problem, omega_s: float, zero: float) -> tuple[np.ndarray, np.ndarray]:
    """Shift-invert Lanczos (ARPACK) on iG φ = μ M φ just above ω_s, asking for more pairs
    until ``count`` positive μ are found (the zeros and the −μ also lie near the shift)."""
    A = (1j * prob.G).tocsc()
    M = prob.M.tocsc()
    sigma = omega_s + max(zero, 1e-300) * 10.0
    k = min(2 * prob.count + SPARSE_MARGIN, prob.n - 1)
    while True:
        mu, phi = spla.eigsh(A, k=k, M=M, sigma=sigma, which="LM", tol=prob.tol)
        prob.info["operator_applications"] += k
        if np.count_nonzero(mu > zero) >= prob.count or k >= prob.n - 1:
            return mu, phi
        k = min(2 * k, prob.n - 1)
