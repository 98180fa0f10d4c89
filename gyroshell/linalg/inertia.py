"""Inertia-counting factorization of a symmetric or Hermitian sparse matrix.

SuperLU in symmetric mode (diagonal pivots, fill-reducing ordering on Aᵀ + A) computes
P A Pᵀ = L U with U = D Lᴴ, i.e. an LDLᴴ factorization. By Sylvester's law of inertia the
number of negative pivots d_i is then the number of negative eigenvalues of A. If SuperLU
had to pivot off the diagonal (a tiny diagonal entry), or a pivot is zero or not finite, the
count is unknown and reported as ``None``; the factorization still solves when it is not
singular.

One helper serves every engine: the definiteness check of K(V) (static and eigen solvers),
the certificate of the eigen-solver's shift Q(iω) = K − ω²M + iωG, and the divergence
shift A − τB.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .factorization import ORDERING, splu

__all__ = ["ORDERING", "InertiaFactor", "factor_inertia"]


@dataclass(frozen=True)
class InertiaFactor:
    """A symmetric-mode LU of a symmetric/Hermitian matrix and its negative-pivot count.

    Attributes
    ----------
    lu : scipy.sparse.linalg.SuperLU or None
        The factorization; None if the matrix is exactly singular.
    negatives : int or None
        Number of negative eigenvalues (Sylvester), or None if unknown (off-diagonal
        pivoting, a zero or non-finite pivot, or a singular matrix).
    """

    lu: spla.SuperLU | None
    negatives: int | None

    @property
    def singular(self) -> bool:
        """True if SuperLU found the matrix exactly singular (no factorization)."""
        return self.lu is None

    @property
    def definite(self) -> bool:
        """True if the matrix is proved positive definite (no negative or zero pivot)."""
        return self.negatives == 0

    @property
    def fill(self) -> int:
        """Stored entries of L and U."""
        return 0 if self.lu is None else int(self.lu.L.nnz + self.lu.U.nnz)

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """A⁻¹ rhs; a complex right-hand side with a real factor is solved in two parts."""
        if self.lu is None:
            raise np.linalg.LinAlgError("the matrix is exactly singular")
        rhs = np.asarray(rhs)
        if np.iscomplexobj(rhs) and not np.iscomplexobj(self.lu.U.data[:1]):
            return self.lu.solve(np.ascontiguousarray(rhs.real)) + 1j * self.lu.solve(
                np.ascontiguousarray(rhs.imag))
        return self.lu.solve(np.ascontiguousarray(rhs))


def factor_inertia(matrix: sp.spmatrix) -> InertiaFactor:
    """Factor a symmetric/Hermitian sparse matrix with diagonal pivots; count its inertia.

    Parameters
    ----------
    matrix : scipy.sparse matrix, shape (n, n)
        Symmetric (real) or Hermitian (complex); only this structure makes the count mean
        anything, and it is not checked here.

    Returns
    -------
    InertiaFactor
        ``negatives`` = the number of negative eigenvalues, or None where SuperLU pivoted
        off the diagonal or met a zero or non-finite pivot; ``lu`` None if exactly singular.
    """
    try:
        lu = splu(matrix, symmetric_mode=True)
    except RuntimeError:  # "Factor is exactly singular"
        return InertiaFactor(None, None)
    if not np.array_equal(lu.perm_r, lu.perm_c):
        return InertiaFactor(lu, None)
    d = lu.U.diagonal()
    if not np.all(np.isfinite(d)) or np.any(d == 0):
        return InertiaFactor(lu, None)
    return InertiaFactor(lu, int(np.count_nonzero(np.real(d) < 0)))


def proved_definite(matrix: sp.spmatrix, factorization: str = "auto", *,
                    fallback: bool = True) -> bool:
    """True if the symmetric/Hermitian ``matrix`` is proved positive definite: CHOLMOD's
    Cholesky succeeds (where ``factorization`` selects it), else SuperLU's inertia shows no
    negative or zero pivot (after a failed Cholesky only with ``fallback``: a failed
    Cholesky met a pivot <= 0, the matrix is then almost surely not definite). False where
    neither proves it (not definite, or unknown)."""
    from . import cholesky
    from .factorization import resolve_factorization

    if resolve_factorization(factorization) == "cholmod":
        factor = cholesky.cholesky(matrix)
        if factor is not None:
            factor.release()
            return True
        if not fallback:
            return False
    return factor_inertia(matrix).definite
