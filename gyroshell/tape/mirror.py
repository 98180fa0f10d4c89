"""Mirror symmetry of the tape about its centre line y = L_y/2.

With the same edges on both sides and a uniform grid, the reflection R: y → L_y − y maps the
unknowns onto themselves and commutes with A, B, M and G (G differentiates along x only), so
R K(V) R = K(V) and every eigenvector of the gyroscopic problem can be chosen symmetric or
antisymmetric across the width. With the orthonormal bases

    P_s: (e_j + e_R(j)) / √2 (and e_c on a centre line),   P_a: (e_j − e_R(j)) / √2,

the problem splits exactly into two of half the size, (λ²M_s + λG_s + K_s)ψ = 0 with
M_s = P_sᵀMP_s (diagonal), G_s = P_sᵀGP_s (skew), K_s = P_sᵀKP_s (symmetric), and the same
for P_a; φ = P_s ψ. On the long tape a half-width solve costs half a full one (its
factorization has half the entries) and needs fewer Lanczos steps, each half as long
(:func:`gyroshell.modes` uses the split; module notes there).
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

#: Relative size of ‖R A R − A‖ (entry-wise) below which A counts as mirror symmetric.
SYMMETRY_RTOL = 1e-13


@dataclass(frozen=True)
class MirrorSplit:
    """The symmetric and antisymmetric halves of a mirror-symmetric tape model.

    Attributes
    ----------
    symmetric, antisymmetric : scipy.sparse.csr_matrix
        P_s (n × n_s) and P_a (n × n_a), orthonormal columns spanning the symmetric and
        antisymmetric fields; together an orthogonal n × n matrix.
    """

    symmetric: sp.csr_matrix
    antisymmetric: sp.csr_matrix
    _A: tuple
    _B: tuple
    _M: tuple
    _G1: tuple

    def half(self, which: str) -> sp.csr_matrix:
        return self.symmetric if which == "symmetric" else self.antisymmetric

    def matrices(self, model, velocity: float, which: str
                 ) -> tuple[sp.csr_matrix, sp.csr_matrix, sp.csr_matrix]:
        """(M_h, G_h(V), K_h(V)) of one half: K_h = A_h + (T − ρV²) B_h as in the model,
        G_h(V) = V G_h(1 m/s) (G is linear in V), projected once per model."""
        k = 0 if which == "symmetric" else 1
        K = (self._A[k] + model.effective_tension(velocity) * self._B[k]).tocsr()
        return self._M[k], (model.params.check_velocity(velocity) * self._G1[k]).tocsr(), K


def _reflection(n_lines: int, n_across: int) -> tuple[sp.csr_matrix, sp.csr_matrix,
                                                      sp.csr_matrix]:
    """(R, P_s, P_a) for unknowns numbered line by line, n_across per line."""
    j = np.arange(n_across)
    mirror = n_across - 1 - j
    eye = sp.identity(n_lines, format="csr")
    R = sp.kron(eye, sp.csr_matrix((np.ones(n_across), (j, mirror)),
                                   shape=(n_across, n_across)), format="csr")
    half = n_across // 2
    low = np.arange(half)
    s = 1 / math.sqrt(2)
    rows_s = np.concatenate([low, mirror[low]] + ([np.array([half])] if n_across % 2 else []))
    cols_s = np.concatenate([low, low] + ([np.array([half])] if n_across % 2 else []))
    vals_s = np.concatenate([np.full(2 * half, s)] + ([np.ones(1)] if n_across % 2 else []))
    ps = sp.csr_matrix((vals_s, (rows_s, cols_s)), shape=(n_across, half + n_across % 2))
    pa = sp.csr_matrix((np.concatenate([np.full(half, s), np.full(half, -s)]),
                        (np.concatenate([low, mirror[low]]), np.concatenate([low, low]))),
                       shape=(n_across, half))
    return R, sp.kron(eye, ps, format="csr"), sp.kron(eye, pa, format="csr")


def _invariant(R: sp.csr_matrix, A: sp.spmatrix) -> bool:
    A = sp.csr_matrix(A)
    scale = abs(A).max() if A.nnz else 0.0
    defect = abs(R @ A @ R - A).max() if A.nnz else 0.0
    return bool(defect <= SYMMETRY_RTOL * scale)


_SPLITS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def mirror_split(model) -> MirrorSplit | None:
    """The split of a :class:`gyroshell.TapeModel`, or None if it is not mirror symmetric
    (or not a tape model: other objects duck-typing the eigen-solver's needs). Checked on
    the assembled A, B, M and G(1 m/s) and cached per model."""
    try:
        return _SPLITS[model]
    except (KeyError, TypeError):
        pass
    split = None
    grid = getattr(model, "grid", None)
    if all(hasattr(model, a) for a in ("A", "B", "M", "G", "effective_tension")) and \
            hasattr(grid, "n_lines") and hasattr(grid, "n_across") and grid.n_across >= 2 \
            and getattr(model, "unknowns", None) == grid.n_lines * grid.n_across:
        R, Ps, Pa = _reflection(grid.n_lines, grid.n_across)
        M = sp.diags(model.mass_diagonal, format="csr")
        G1 = model.G(1.0)
        if all(_invariant(R, X) for X in (model.A, model.B, M, G1)):
            def project(P, X):
                return (P.T @ X @ P).tocsr()
            split = MirrorSplit(
                Ps, Pa,
                (project(Ps, model.A), project(Pa, model.A)),
                (project(Ps, model.B), project(Pa, model.B)),
                (sp.diags((Ps.T @ M @ Ps).diagonal(), format="csr"),
                 sp.diags((Pa.T @ M @ Pa).diagonal(), format="csr")),
                (project(Ps, G1), project(Pa, G1)))
    try:
        _SPLITS[model] = split
    except TypeError:  # not weak-referenceable: no cache
        pass
    return split
