"""Sparse Cholesky factorization of symmetric/Hermitian positive definite matrices (CHOLMOD).

The eigen-solver's shift matrix Q(iω_s) = K − ω_s²M + iω_sG is Hermitian, and positive
definite whenever the shift lies below the lowest frequency (no negative eigenvalue: the
count certificate of :mod:`gyroshell.linalg.qep` is then zero); K(V) is symmetric positive
definite below the critical speed. For such matrices a supernodal Cholesky LLᴴ does half
the work of an LU and proves definiteness by succeeding. CHOLMOD (SuiteSparse), reached
through the binary wheels of ``cvxopt`` (the ``fast`` extra), factors the L_x/L_y = 19
tape's Q(iω_s) 3-5x faster than SuperLU and solves 10-25 % faster (benchmarks/bench_eigen.py).

The sparsity pattern of Q(iω) never changes with the speed or the shift, so the symbolic
analysis (fill-reducing ordering, elimination tree, supernodes) is done once per pattern:
analysed factors wait in a small pool and are refactored numerically in place. A factor
taken from the pool belongs to its :class:`CholeskyFactor` until ``release()`` gives it
back (then the factor must not be used); one that is never released is simply collected.

Without cvxopt, :func:`available` is False and callers use SuperLU
(:func:`gyroshell.linalg.inertia.factor_inertia`).
"""

from __future__ import annotations

import threading

import numpy as np
import scipy.sparse as sp

try:  # optional: the ``fast`` extra
    import cvxopt
    import cvxopt.cholmod as _cholmod
except ImportError:  # pragma: no cover - exercised where cvxopt is absent
    cvxopt = None
    _cholmod = None

#: Factorization back-ends of the eigen-solver, and what "auto" means.
BACKENDS = ("auto", "cholmod", "superlu")
#: Analysed factors kept per sparsity pattern (one per concurrent solve; more are rebuilt).
POOL_SIZE = 4


def available() -> bool:
    """True if CHOLMOD can be used (``cvxopt`` is installed)."""
    return _cholmod is not None


class _Pattern:
    """One lower-triangle sparsity pattern and its analysed factors, each with the cvxopt
    matrix it refills (so concurrent factorizations never share one)."""

    def __init__(self, lower: sp.csc_matrix, typecode: str, supernodal: bool = True) -> None:
        self.n = lower.shape[0]
        self.supernodal = supernodal
        self.indptr = lower.indptr.copy()
        self.indices = lower.indices.copy()
        self.typecode = typecode
        self.slots: list[tuple] = []

    def matches(self, lower: sp.csc_matrix) -> bool:
        return (np.array_equal(self.indptr, lower.indptr)
                and np.array_equal(self.indices, lower.indices))

    def take(self, values: np.ndarray) -> tuple:
        """(cvxopt matrix holding ``values``, its analysed factor or None)."""
        with _lock:
            slot = self.slots.pop() if self.slots else None
        if slot is None:
            columns = np.repeat(np.arange(self.n, dtype=np.int64), np.diff(self.indptr))
            matrix = cvxopt.spmatrix(cvxopt.matrix(values), cvxopt.matrix(
                self.indices.astype(np.int64)), cvxopt.matrix(columns), (self.n, self.n),
                self.typecode)
            return matrix, None
        matrix, factor = slot
        matrix.V = cvxopt.matrix(values)
        return matrix, factor

    def analyse(self, matrix):
        """CHOLMOD's symbolic analysis: supernodal (for LLᴴ) or simplicial (for LDLᴴ); the
        choice is a global cvxopt option, set and restored under the module lock."""
        with _lock:
            saved = _cholmod.options.get("supernodal")
            _cholmod.options["supernodal"] = 2 if self.supernodal else 0
            try:
                return _cholmod.symbolic(matrix, uplo="L")
            finally:
                if saved is None:
                    _cholmod.options.pop("supernodal", None)
                else:
                    _cholmod.options["supernodal"] = saved

    def give_back(self, matrix, factor) -> None:
        with _lock:
            if len(self.slots) < POOL_SIZE:
                self.slots.append((matrix, factor))


_patterns: dict[tuple, list[_Pattern]] = {}
_lock = threading.Lock()


def _pattern(lower: sp.csc_matrix, typecode: str, supernodal: bool = True) -> _Pattern:
    key = (lower.shape[0], lower.nnz, typecode, supernodal)
    with _lock:
        for pattern in _patterns.get(key, ()):
            if pattern.matches(lower):
                return pattern
        pattern = _Pattern(lower, typecode, supernodal)
        _patterns.setdefault(key, []).append(pattern)
        del _patterns[key][:-POOL_SIZE]
        return pattern


#: Lower-triangle maps kept (one per CSR sparsity pattern seen most recently).
LOWER_MAPS = 8
_lower_maps: list[tuple] = []


def _lower(matrix: sp.spmatrix) -> sp.csc_matrix:
    """The lower triangle of ``matrix`` in CSC with sorted indices, as CHOLMOD reads it.

    For a canonical CSR matrix the positions of its entries in that triangle depend on the
    sparsity pattern only (the same for every shift and speed): the second time a pattern
    is seen they are found, and from then on the triangle is one gather of the values,
    not a triangle extraction, a conversion and a sort (the tape's shift matrices: ~2 ms
    each time; a pattern seen once, as in a single eigen-solve, costs nothing extra)."""
    if not (sp.issparse(matrix) and matrix.format == "csr" and matrix.has_canonical_format):
        lower = sp.tril(matrix, format="csc")
        lower.sort_indices()
        return lower
    shape, nnz = matrix.shape, matrix.nnz
    with _lock:
        found = next((entry for entry in _lower_maps if entry[0] == shape and entry[1] == nnz
                      and np.array_equal(entry[2], matrix.indptr)
                      and np.array_equal(entry[3], matrix.indices)), None)
    if found is None or found[4] is None:
        # first sight: scipy's path, the pattern noted; second: the map, made once
        if found is None:
            lower = sp.tril(matrix, format="csc")
            lower.sort_indices()
            entry = (shape, nnz, matrix.indptr.copy(), matrix.indices.copy(), None)
        else:
            marks = sp.csr_matrix((np.arange(1, nnz + 1, dtype=float), matrix.indices,
                                   matrix.indptr), shape=shape)
            skeleton = sp.tril(marks, format="csc")
            skeleton.sort_indices()
            take = skeleton.data.astype(np.int64) - 1
            lower = sp.csc_matrix((matrix.data[take], skeleton.indices, skeleton.indptr),
                                  shape=shape)
            entry = (*found[:4], take, skeleton.indices, skeleton.indptr)
        with _lock:
            _lower_maps[:] = [e for e in _lower_maps if e is not found]
            _lower_maps.insert(0, entry)
            del _lower_maps[LOWER_MAPS:]
        return lower
    take, indices, indptr = found[4:]
    return sp.csc_matrix((matrix.data[take], indices, indptr), shape=shape)


class CholeskyFactor:
    """A CHOLMOD factorization P A Pᵀ = L Lᴴ of a positive definite matrix.

    Duck-compatible with :class:`gyroshell.linalg.inertia.InertiaFactor` where the solvers use it:
    ``negatives`` is 0 (proved definite), ``singular`` and ``definite`` follow, ``solve``
    takes real or complex right-hand sides (one vector or columns).
    """

    negatives = 0
    singular = False
    definite = True
    backend = "cholmod"

    def __init__(self, matrix, factor, pattern: _Pattern, complex_: bool) -> None:
        self._matrix, self._factor, self._pattern = matrix, factor, pattern
        self._complex, self.n = complex_, pattern.n

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """A⁻¹ rhs for a vector (n,) or columns (n, k)."""
        if self._factor is None:
            raise RuntimeError("this Cholesky factor was released")
        rhs = np.asarray(rhs)
        if rhs.ndim == 1:
            return self.solve(rhs[:, None])[:, 0]
        if np.iscomplexobj(rhs) and not self._complex:  # real factor: both parts at once
            parts = self.solve(np.hstack([rhs.real, rhs.imag]))
            k = rhs.shape[1]
            return parts[:, :k] + 1j * parts[:, k:]
        dtype = complex if self._complex else float
        b = cvxopt.matrix(np.asfortranarray(rhs, dtype=dtype))
        _cholmod.solve(self._factor, b)
        return np.array(b, dtype=dtype).reshape(rhs.shape)

    def release(self) -> None:
        """Give the analysed factor back to the pool (this object can no longer solve)."""
        factor, self._factor = self._factor, None
        if factor is not None:
            self._pattern.give_back(self._matrix, factor)


def cholesky(matrix: sp.spmatrix) -> CholeskyFactor | None:
    """CHOLMOD Cholesky of a symmetric (real) or Hermitian (complex) sparse matrix.

    Parameters
    ----------
    matrix : scipy.sparse matrix, shape (n, n)
        Only its lower triangle is read; symmetry is not checked here.

    Returns
    -------
    CholeskyFactor or None
        None if the matrix is not positive definite (CHOLMOD met a non-positive pivot).

    Raises
    ------
    RuntimeError
        If cvxopt is not installed (check :func:`available` first).
    """
    if _cholmod is None:
        raise RuntimeError("CHOLMOD needs cvxopt: pip install 'gyroshell[fast]'")
    lower = _lower(matrix)
    complex_ = np.iscomplexobj(lower.data)
    pattern = _pattern(lower, "z" if complex_ else "d")
    matrix, factor = pattern.take(lower.data.astype(complex if complex_ else float))
    if factor is None:
        factor = pattern.analyse(matrix)
    try:
        _cholmod.numeric(matrix, factor)
    except ArithmeticError:  # not positive definite; the analysis stays reusable
        pattern.give_back(matrix, factor)
        return None
    return CholeskyFactor(matrix, factor, pattern, complex_)


class LDLFactor(CholeskyFactor):
    """CHOLMOD's simplicial P A Pᵀ = L D Lᴴ of a symmetric/Hermitian matrix (no pivoting)
    and its inertia: ``negatives`` is the number of negative entries of D (Sylvester), so
    the same factorization both counts and solves (duck-compatible with
    :class:`gyroshell.linalg.inertia.InertiaFactor`, like :class:`CholeskyFactor`)."""

    backend = "cholmod-ldl"

    def __init__(self, matrix, factor, pattern: _Pattern, complex_: bool,
                 negatives: int) -> None:
        super().__init__(matrix, factor, pattern, complex_)
        self.negatives = negatives
        self.definite = negatives == 0


def ldl(matrix: sp.spmatrix) -> LDLFactor | None:
    """CHOLMOD's simplicial LDLᴴ of a symmetric (real) or Hermitian (complex) sparse matrix.

    A fill-reducing symmetric permutation and no pivoting: the same factorization as
    :func:`gyroshell.linalg.inertia.factor_inertia`'s SuperLU in symmetric mode with
    diagonal pivots, about 2.5x faster on the tape's half-width shift matrices. D is read
    by one diagonal solve D x = 1 (``sys=6``), not by extracting the factor (which costs
    three numeric factorizations). The symbolic analysis is pooled per pattern as for
    :func:`cholesky`.

    Returns
    -------
    LDLFactor or None
        None if a pivot is zero or not finite, or CHOLMOD fails: the inertia is then
        unknown (use SuperLU's). Release it when done (see :class:`CholeskyFactor`).
    """
    if _cholmod is None:
        raise RuntimeError("CHOLMOD needs cvxopt: pip install 'gyroshell[fast]'")
    lower = _lower(matrix)
    complex_ = np.iscomplexobj(lower.data)
    dtype = complex if complex_ else float
    pattern = _pattern(lower, "z" if complex_ else "d", supernodal=False)
    matrix_, factor = pattern.take(lower.data.astype(dtype))
    try:
        if factor is None:
            factor = pattern.analyse(matrix_)
        _cholmod.numeric(matrix_, factor)
        ones = cvxopt.matrix(np.ones(pattern.n, dtype=dtype))
        with np.errstate(divide="ignore", invalid="ignore"):
            _cholmod.solve(factor, ones, sys=6)   # ones <- D⁻¹ 1
            d = np.array(ones, dtype=dtype).ravel().real
    except (ArithmeticError, ValueError):
        d = None
    if d is None or not np.all(np.isfinite(d)) or np.any(d == 0):
        if factor is not None:
            pattern.give_back(matrix_, factor)
        return None
    return LDLFactor(matrix_, factor, pattern, complex_, int(np.count_nonzero(d < 0)))


def negative_count(matrix: sp.spmatrix) -> int | None:
    """Number of negative eigenvalues of a symmetric/Hermitian sparse matrix (Sylvester).

    The count of :func:`ldl` (its factor released at once); None where that has no
    answer (a zero or non-finite pivot, or CHOLMOD fails): use SuperLU's.
    """
    factor = ldl(matrix)
    if factor is None:
        return None
    factor.release()
    return factor.negatives
