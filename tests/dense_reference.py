"""The tests' own dense solvers: independent of the package's sparse ones."""

from __future__ import annotations

import numpy as np
import scipy.linalg as la


def quadratic_eigenvalues(M, G, K) -> np.ndarray:
    """All 2n roots of det(λ²M + λG + K) = 0 by the generalized companion pencil (no
    inverse of M, unlike the package's linearization)."""
    from threadpoolctl import threadpool_limits

    n = len(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -G]])
    B = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), M]])
    with threadpool_limits(1):  # one BLAS thread: much faster on a shared machine
        return la.eig(A, B, right=False)
