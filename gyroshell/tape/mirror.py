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
    _AB: tuple   # per half: (A_h, B_h) on one sparsity pattern
    _M: tuple
    _G1: tuple
    _full: tuple = ()   # (column indices, A's values, B's values, columns) of the full A, B
    #: ‖G(1 m/s)‖₁ of the full problem, kg/s per m/s.
    gyroscopic_norm: float = 0.0

    def half(self, which: str) -> sp.csr_matrix:
        return self.symmetric if which == "symmetric" else self.antisymmetric

    def stiffness(self, which: str) -> tuple[sp.csr_matrix, sp.csr_matrix]:
        """(A_h, B_h) = (P_hᵀAP_h, P_hᵀBP_h) of one half, N/m, on one sparsity pattern
        (shared, read only)."""
        return self._AB[0 if which == "symmetric" else 1]

    def combination(self, which: str, tau: float) -> sp.csr_matrix:
        """A_h + τ B_h, N/m (τ in N/m), by one vector operation on the shared pattern."""
        A, B = self.stiffness(which)
        return sp.csr_matrix((A.data + tau * B.data, A.indices, A.indptr), shape=A.shape)

    def stiffness_norm(self, tension: float) -> float:
        """‖A + τB‖₁ of the full problem, N/m (τ = T − ρV² in N/m gives ‖K(V)‖₁): the
        largest absolute column sum, one pass over the entries of A and B laid on one
        sparsity pattern (no assembly)."""
        indices, a, b, columns = self._full
        if not indices.size:
            return 0.0
        return float(np.bincount(indices, weights=np.abs(a + tension * b),
                                 minlength=columns).max())

    def matrices(self, model, velocity: float, which: str
                 ) -> tuple[sp.csr_matrix, sp.csr_matrix, sp.csr_matrix]:
        """(M_h, G_h(V), K_h(V)) of one half: K_h = A_h + (T − ρV²) B_h as in the model,
        G_h(V) = V G_h(1 m/s) (G is linear in V), projected once per model."""
        k = 0 if which == "symmetric" else 1
        K = self.combination(which, model.effective_tension(velocity))
        G1 = self._G1[k]
        G = sp.csr_matrix((model.params.check_velocity(velocity) * G1.data, G1.indices,
                           G1.indptr), shape=G1.shape)
        return self._M[k], G, K


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


@dataclass(frozen=True)
class _Numbering:
    """The reflection j → R(j) of a grid's unknowns and the two halves' numbering.

    Per full unknown (line ℓ, column c of ``n_across``): ``mirror`` = its image ℓ·n_across
    + (n_across − 1 − c); ``sym`` its symmetric half unknown ℓ·⌈n_across/2⌉ + min(c, c̄);
    ``anti`` its antisymmetric one ℓ·⌊n_across/2⌋ + min(c, c̄) and ``sign`` ±1 (0 on a
    centre line, which P_a omits); ``weight_s`` the entry of P_s in its column (1/√2 on
    pairs, 1 on a centre line).
    """

    n_lines: int
    n_across: int
    mirror: np.ndarray
    sym: np.ndarray
    anti: np.ndarray
    sign: np.ndarray
    weight_s: np.ndarray

    @classmethod
    def of(cls, n_lines: int, n_across: int) -> _Numbering:
        line, c = np.divmod(np.arange(n_lines * n_across), n_across)
        cbar = n_across - 1 - c
        low = np.minimum(c, cbar)
        columns, pairs = (n_across + 1) // 2, n_across // 2
        sign = np.sign(cbar - c).astype(float)
        weight_s = np.where(c == cbar, 1.0, 1 / math.sqrt(2))
        anti = np.where(sign != 0, line * pairs + np.minimum(low, pairs - 1), 0)
        return cls(n_lines, n_across, line * n_across + cbar, line * columns + low, anti,
                   sign, weight_s)

    def bases(self) -> tuple[sp.csr_matrix, sp.csr_matrix]:
        """(P_s, P_a) as sparse matrices (n × n_s, n × n_a)."""
        n = self.mirror.size
        n_s = self.n_lines * ((self.n_across + 1) // 2)
        n_a = self.n_lines * (self.n_across // 2)
        P_s = sp.csr_matrix((self.weight_s, self.sym, np.arange(n + 1)), shape=(n, n_s))
        keep = self.sign != 0
        P_a = sp.csr_matrix((self.sign[keep] / math.sqrt(2), (np.flatnonzero(keep),
                             self.anti[keep])), shape=(n, n_a))
        return P_s, P_a

    def reflected(self, A: sp.csr_matrix) -> sp.csr_matrix:
        """R A R (canonical CSR): A's rows permuted, its column indices mapped."""
        out = A[self.mirror]
        out.indices = self.mirror[out.indices]
        out.has_sorted_indices = False
        out.sort_indices()
        return out

    def invariant(self, A: sp.spmatrix) -> bool:
        """R A R = A to round-off (entry-wise, :data:`SYMMETRY_RTOL`)."""
        A = sp.csr_matrix(A)
        if not A.nnz:
            return True
        A.sum_duplicates()
        RAR = self.reflected(A)
        if np.array_equal(RAR.indptr, A.indptr) and np.array_equal(RAR.indices, A.indices):
            defect = np.abs(RAR.data - A.data).max()
        else:
            defect = abs(RAR - A).max()
        return bool(defect <= SYMMETRY_RTOL * np.abs(A.data).max())

    def fold(self, A: sp.csr_matrix, which: str, dtype=float) -> sp.csr_matrix:
        """P_hᵀ A P_h of an R-invariant A from the rows of one side: for pairs k, l,
        (P_sᵀAP_s)_kl = A_kl + A_k,R(l) and (P_aᵀAP_a)_kl = A_kl − A_k,R(l), with the
        weights of a centre line (exact where RAR = A; a few vectorized passes)."""
        if which == "symmetric":
            rows = np.flatnonzero(self.mirror >= np.arange(self.mirror.size))
            index, n_h = self.sym, self.n_lines * ((self.n_across + 1) // 2)
            row_scale = 1 / self.weight_s[rows]
            col_scale = self.weight_s
        else:
            rows = np.flatnonzero(self.sign > 0)
            index, n_h = self.anti, self.n_lines * (self.n_across // 2)
            row_scale = np.ones(rows.size)
            col_scale = self.sign
        sub = A[rows]
        lengths = np.diff(sub.indptr)
        data = sub.data * np.repeat(row_scale, lengths) * col_scale[sub.indices]
        out = sp.csr_matrix((data.astype(dtype, copy=False), index[sub.indices], sub.indptr),
                            shape=(n_h, n_h))
        out.sum_duplicates()   # sorts each row's indices and merges the pairs' entries
        if which != "symmetric":
            out.eliminate_zeros()   # the centre line's entries (P_a has no centre column)
        return out


def _invariant(R: sp.csr_matrix, A: sp.spmatrix) -> bool:
    A = sp.csr_matrix(A)
    scale = abs(A).max() if A.nnz else 0.0
    defect = abs(R @ A @ R - A).max() if A.nnz else 0.0
    return bool(defect <= SYMMETRY_RTOL * scale)


def _on_one_pattern(numbering: _Numbering, AB: sp.csr_matrix, which: str
                    ) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """(P_hᵀAP_h, P_hᵀBP_h) sharing one sparsity pattern, folded together from AB = A + iB."""
    both = numbering.fold(AB, which, dtype=complex)
    pattern = (both.indices, both.indptr)
    return (sp.csr_matrix((both.data.real.copy(), *pattern), shape=both.shape),
            sp.csr_matrix((both.data.imag.copy(), *pattern), shape=both.shape))


_SPLITS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def mirror_split(model) -> MirrorSplit | None:
    """The split of a :class:`gyroshell.TapeModel`, or None if it is not mirror symmetric
    (or not a tape model: other objects duck-typing the eigen-solver's needs). Checked on
    the assembled A, B, M and G(1 m/s) and cached per model.

    The reflection is a permutation of the unknowns and the bases combine mirrored pairs,
    so the check (R A R by permuting A's rows and relabelling its columns) and the halves
    (:meth:`_Numbering.fold`) are a few vectorized passes over the entries, not sparse
    triple products.
    """
    try:
        return _SPLITS[model]
    except (KeyError, TypeError):
        pass
    split = None
    grid = getattr(model, "grid", None)
    if all(hasattr(model, a) for a in ("A", "B", "M", "G", "effective_tension")) and \
            hasattr(grid, "n_lines") and hasattr(grid, "n_across") and grid.n_across >= 2 \
            and getattr(model, "unknowns", None) == grid.n_lines * grid.n_across:
        numbering = _Numbering.of(grid.n_lines, grid.n_across)
        mass = np.asarray(model.mass_diagonal, dtype=float)
        A, B, G1 = (sp.csr_matrix(X) for X in (model.A, model.B, model.G(1.0)))
        mass_scale = np.abs(mass).max() if mass.size else 0.0
        if np.abs(mass[numbering.mirror] - mass).max() <= SYMMETRY_RTOL * mass_scale and \
                all(numbering.invariant(X) for X in (A, B, G1)):
            Ps, Pa = numbering.bases()
            AB = sp.csr_matrix(A, dtype=complex) + 1j * B
            split = MirrorSplit(
                Ps, Pa,
                tuple(_on_one_pattern(numbering, AB, w)
                      for w in ("symmetric", "antisymmetric")),
                (sp.diags(mass[numbering.mirror >= np.arange(mass.size)], format="csr"),
                 sp.diags(mass[numbering.sign > 0], format="csr")),
                tuple(numbering.fold(G1, w) for w in ("symmetric", "antisymmetric")),
                (AB.indices, AB.data.real.copy(), AB.data.imag.copy(), AB.shape[1]),
                float(abs(G1).sum(axis=0).max()) if G1.nnz else 0.0)
    try:
        _SPLITS[model] = split
    except TypeError:  # not weak-referenceable: no cache
        pass
    return split


#: Relative size of ‖R f − f‖₂ below which a vector (force, initial state) counts as mirror
#: symmetric: round-off of its assembly, far below any physical asymmetry.
VECTOR_RTOL = 1e-14


@dataclass(frozen=True)
class SymmetricHalf:
    """The numbering of the symmetric half P_s of a grid's unknowns, for vectors.

    Unknowns are numbered line by line, ``n_across`` per line; the half keeps ``columns``
    = ⌈n_across/2⌉ per line, column k standing for the pair (k, n_across − 1 − k) (the
    centre alone when n_across is odd), as the columns of :attr:`MirrorSplit.symmetric`.
    With it the time loop moves between a symmetric field w = P_s z and its half z by
    slicing, without a sparse product.

    Examples
    --------
    >>> half = SymmetricHalf(n_lines=1, n_across=3)
    >>> half.expand(np.array([np.sqrt(2.0), 5.0]))
    array([1., 5., 1.])
    >>> half.restrict(np.array([1.0, 5.0, 1.0]))  # P_sᵀ f
    array([1.41421356, 5.        ])
    """

    n_lines: int
    n_across: int

    @classmethod
    def of(cls, grid) -> SymmetricHalf:
        """The half of a :class:`gyroshell.tape.grid.Grid`'s unknowns."""
        return cls(grid.n_lines, grid.n_across)

    @property
    def columns(self) -> int:
        """Half columns per line (⌈n_across/2⌉)."""
        return (self.n_across + 1) // 2

    @property
    def unknowns(self) -> int:
        """Unknowns of the half, n_s = n_lines · columns."""
        return self.n_lines * self.columns

    @property
    def value_weights(self) -> np.ndarray:
        """w_j / z_k for j = k or its mirror: 1/√2 on pairs, 1 on a centre line (w = P_s z)."""
        weights = np.full(self.columns, 1 / math.sqrt(2))
        if self.n_across % 2:
            weights[-1] = 1.0
        return weights

    @property
    def force_weights(self) -> np.ndarray:
        """(P_sᵀ f)_k / f_k for a symmetric f: √2 on pairs, 1 on a centre line."""
        return 1.0 / self.value_weights

    def index(self, unknown: np.ndarray) -> np.ndarray:
        """Half unknown k of full unknowns j (the pair's, or the centre's), integer arrays."""
        line, j = np.divmod(np.asarray(unknown), self.n_across)
        return line * self.columns + np.minimum(j, self.n_across - 1 - j)

    def weight(self, unknown: np.ndarray) -> np.ndarray:
        """w_j / z_index(j) of full unknowns j (:attr:`value_weights`)."""
        j = np.asarray(unknown) % self.n_across
        return self.value_weights[np.minimum(j, self.n_across - 1 - j)]

    def reflect(self, vector: np.ndarray) -> np.ndarray:
        """R f: the vector over the unknowns mirrored across the centre line (a new array)."""
        return vector.reshape(self.n_lines, self.n_across)[:, ::-1].ravel()

    def is_symmetric(self, vector: np.ndarray, rtol: float = VECTOR_RTOL) -> bool:
        """‖R f − f‖₂ ≤ rtol ‖f‖₂ (a zero vector is symmetric)."""
        f = np.asarray(vector, dtype=float)
        return bool(np.linalg.norm(self.reflect(f) - f) <= rtol * np.linalg.norm(f))

    def restrict(self, vector: np.ndarray) -> np.ndarray:
        """P_sᵀ f (a new array of the half's unknowns); exact for any f."""
        f = vector.reshape(self.n_lines, self.n_across)
        c, pairs = self.columns, self.n_across // 2
        out = np.empty((self.n_lines, c))
        np.add(f[:, :pairs], f[:, ::-1][:, :pairs], out=out[:, :pairs])
        out[:, :pairs] *= 1 / math.sqrt(2)
        if c > pairs:
            out[:, -1] = f[:, pairs]
        return out.ravel()

    def expand(self, half: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """w = P_s z over all the unknowns (into ``out`` if given)."""
        out = np.empty(self.n_lines * self.n_across) if out is None else out
        w = out.reshape(self.n_lines, self.n_across)
        c = self.columns
        np.multiply(half.reshape(self.n_lines, c), self.value_weights, out=w[:, :c])
        w[:, c:] = w[:, :self.n_across - c][:, ::-1]
        return out

    def project(self, matrix: sp.spmatrix) -> sp.csr_matrix:
        """P_sᵀ A P_s (an operator on the half's unknowns)."""
        P = _reflection(self.n_lines, self.n_across)[1]
        return (P.T @ sp.csr_matrix(matrix) @ P).tocsr()

    def is_invariant(self, matrix: sp.spmatrix) -> bool:
        """R A R = A to round-off (entry-wise, :data:`SYMMETRY_RTOL`)."""
        return _invariant(_reflection(self.n_lines, self.n_across)[0], matrix)
