"""Newton's Jacobian assembled into one fixed sparse pattern, folded by the mirror.

The coupled Jacobian of :mod:`.steady` has four blocks of fixed pattern on a grid:

    [ J_uu   −L   ]     tape rows: K (plus a transient's terms), fixed within a solve;
    [ J_pu   J_pp ]     film rows: ∂r_p/∂h and ∂r_p/∂p, new values every iteration,

and a node in contact has its tape row replaced by c (h − σ) (the diagonal c only). A 2-D
tape symmetric about its centre line is solved on half the width: the folded matrix
J[rows, :] P sums each column with its mirror image's (:attr:`BearingModel.mirror`).

:class:`JacobianPattern` computes, once per grid, where every value of the four blocks
lands in the folded (and, for a nested-dissection ordering, permuted) matrix in CSC form;
an assembly is then one weighted ``bincount`` of the blocks' data arrays into that
pattern, with no stacking, slicing, folding or permuting of sparse matrices. The pattern
holds every entry the grid can have: a contact row keeps its off-diagonal entries as
explicit zeros, so one ordering and one symbolic structure serve every contact set.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp


class JacobianPattern:
    """The folded Jacobian's CSC pattern and the maps of its blocks' values into it.

    Parameters
    ----------
    tape_rows : scipy.sparse.csr_matrix, shape (n_u, n_u + n_p)
        [J_uu, −L] (N/m, m²), whose values stay fixed within a solve.
    J_h : scipy.sparse.csr_matrix, shape (n_p, n_nodes)
        The film's ∂r_p/∂h over every node, in its fixed pattern (:class:`.film.Film`).
    J_p : scipy.sparse.csr_matrix, shape (n_p, n_p)
        The film's ∂r_p/∂p, in its fixed pattern.
    nc : int
        Node columns across (the tape's unknown u_k is node nc + k: the first node line
        x = 0 is pinned).
    mirror : (scipy.sparse.csr_matrix, numpy.ndarray) or None
        (P, rows) of :attr:`BearingModel.mirror`, or None to solve on every unknown.
    """

    def __init__(self, tape_rows: sp.csr_matrix, J_h: sp.csr_matrix, J_p: sp.csr_matrix,
                 nc: int, mirror) -> None:
        n_u = tape_rows.shape[0]
        n = n_u + J_p.shape[0]
        # 32-bit indices (a grid has far fewer than 2³¹ unknowns): half the memory to
        # allocate and touch, which is most of the cost here
        index = np.int32

        def row_of_entries(A):
            return np.repeat(np.arange(A.shape[0], dtype=index), np.diff(A.indptr))

        self.tape_row = row_of_entries(tape_rows)
        h_row = row_of_entries(J_h)
        #: the entries of J_h on the tape's unknowns (the end node lines carry no u): the
        #: columns of BearingModel.film_tape_block, scattered by value
        self.h_take = np.flatnonzero((J_h.indices >= nc) & (J_h.indices < nc + n_u))
        self.h_col = (J_h.indices[self.h_take] - nc).astype(index)
        p_row = row_of_entries(J_p)
        diag = np.arange(n_u, dtype=index)
        rows = np.concatenate([self.tape_row, diag, n_u + h_row[self.h_take], n_u + p_row])
        cols = np.concatenate([tape_rows.indices.astype(index, copy=False), diag, self.h_col,
                               n_u + J_p.indices.astype(index, copy=False)])
        if mirror is None:
            kept, to_half = np.arange(n), np.arange(n, dtype=index)
        else:
            P, kept = mirror
            to_half = P.tocsr().indices.astype(index)    # P has one entry, 1, per row
        row_of = np.full(n, -1, dtype=index)
        row_of[kept] = np.arange(len(kept), dtype=index)
        folded = row_of[rows]
        #: the entries (of the concatenated blocks) in the solved rows
        self.keep = np.flatnonzero(folded >= 0)
        self.rows, self.cols = folded[self.keep], to_half[cols[self.keep]]
        self.size = len(kept)
        #: input[k] = full row of the solved system's k-th equation; output[i] = the
        #: solved unknown of full unknown i (numberings before any ordering)
        self.kept, self.to_half = kept, to_half
        self.permutation = None
        self._map = None           # compiled at the first assembly (after any ordering)

    def graph(self) -> sp.coo_matrix:
        """The folded pattern (ones; an entry summed by the fold appears more than once)
        in its natural numbering, for an ordering."""
        return sp.coo_matrix((np.ones(len(self.rows)), (self.rows, self.cols)),
                             shape=(self.size, self.size))

    def order(self, permutation: np.ndarray) -> None:
        """Assemble from now on into P A Pᵀ (row and column k are perm[k] of A)."""
        self.permutation = np.asarray(permutation)
        self._map = None

    def compile(self) -> None:
        """Form the CSC pattern (in the order set by :meth:`order`) and the scatter map;
        :attr:`input` and :attr:`output` then take a full residual to the solved system's
        right-hand side and its solution back to the full unknowns."""
        permutation = np.arange(self.size) if self.permutation is None else self.permutation
        inverse = np.empty(self.size, dtype=np.intp)
        inverse[permutation] = np.arange(self.size)
        key = inverse[self.cols].astype(np.int64) * self.size + inverse[self.rows]
        entries, self._map = np.unique(key, return_inverse=True)   # column-major: CSC
        self.indices = entries % self.size
        self.indptr = np.searchsorted(entries // self.size, np.arange(self.size + 1))
        self.input = self.kept[permutation]
        self.output = inverse[self.to_half]

    def matrix(self, tape_values: np.ndarray, active: np.ndarray, contact: np.ndarray,
               J_h: sp.csr_matrix, J_p: sp.csr_matrix, free: np.ndarray | None = None,
               diagonal: np.ndarray | None = None) -> sp.csc_matrix:
        """The folded (ordered) Jacobian, CSC.

        Parameters
        ----------
        tape_values : numpy.ndarray
            The data array of ``tape_rows`` (its CSR order).
        active : numpy.ndarray of bool, shape (n_u,)
            The contact set: those tape rows become c (h − σ).
        contact : numpy.ndarray, shape (n_u,)
            c, N/m: the contact rows' diagonal.
        J_h, J_p : scipy.sparse.csr_matrix
            The film's blocks at this state, in the patterns given at construction.
        free : numpy.ndarray of bool, shape (n_u,), optional
            False where the film saw a spacing floored (no dependence on u there).
        diagonal : numpy.ndarray, shape (n_u,), optional
            Added to the diagonal of the tape rows not in the contact set, N/m: a smooth
            contact law's stiffness −∂f/∂u.
        """
        if self._map is None:
            self.compile()
        h_values = J_h.data[self.h_take]
        if free is not None:
            h_values = h_values * free[self.h_col]
        added = np.where(active, contact, 0.0 if diagonal is None else diagonal)
        values = np.concatenate([tape_values * ~active[self.tape_row], added, h_values,
                                 J_p.data])
        data = np.bincount(self._map, weights=values[self.keep], minlength=len(self.indices))
        return sp.csc_matrix((data, self.indices, self.indptr), shape=(self.size,) * 2)
