"""Sparse LU back-ends behind one call: ``factorize(matrix, backend="auto").solve(rhs)``.

Newmark's method factors K_eq = M + γΔt G + βΔt² K once and then does one forward/back
substitution per step, so the substitution speed is what matters. K_eq is real, square and
non-symmetric (G is skew), banded with a half-bandwidth of about 2 (n_y + 1).

The back-ends compared (``benchmarks/bench_newmark.py`` prints the measured medians):

* SuperLU, minimum degree on Aᵀ + A: the least fill of the orderings scipy offers and the
  fastest substitution among the always-installed back-ends (COLAMD fills more).
* UMFPACK (scikit-umfpack), iterative refinement off: ties SuperLU; it needs the SuiteSparse
  C library to build, so it is not a clean PyPI install.
* PARDISO (MKL, through pypardiso) on one thread: ties SuperLU; on two threads it is fast
  only on an idle machine and pulls in a large MKL.
* LAPACK banded LU (dgbtrf/dgbtrs through scipy): factors fastest but stores the full band
  and substitutes more slowly.

So "auto" is SuperLU: the fastest reliable one, shipped with scipy, always available. The
others are opt-in by name where installed, and the tests check that all agree. Newmark's
narrow bands (the symmetric halves) go further
(:func:`gyroshell.linalg.ordering.factorize_banded`): :class:`BandLU`, SuperLU's
diagonal-pivot LU in the natural order copied into band storage and solved by two BLAS
band substitutions, a third of SuperLU's own substitution there.

The bearing's Newton Jacobian (real, nonsymmetric, pattern nearly symmetric: the plate's
13-point bending stencil and the film's 5-point Reynolds stencil on one 2-D grid) is
factored by :class:`DiagonalPivotLU` (``factorization=`` of the bearing, :data:`PATTERN_LU`).
SuperLU's partial pivoting is what made it slow: it moves rows out of any symmetric
fill-reducing order (a pivot threshold of 10⁻³ already more than doubles the fill), so
COLAMD was the best ordering left. With diagonal pivots (symmetric mode, threshold 0) a
symmetric ordering keeps its fill, and every solve checks its backward error (falling
back to partial pivoting above :data:`BACKWARD_ERROR_LIMIT`; it never did on the
bearing's Jacobians, backward errors 1e-16). Measured with ``benchmarks/bench_bearing.py
--backends`` on the 12.65 mm tape's default grid (77,787 unknowns solved on the half
width, 1.24 M entries), one BLAS thread, medians of 3 alternating rounds on the loaded
2-core machine (load 3-5; on a quiet one every time is about 2.5x shorter):

=========  ================================  =======  ==========  ======  ===========
back-end   what                              fill     one LU      solve   whole solve
=========  ================================  =======  ==========  ======  ===========
metis      SuperLU, diagonal pivots, METIS   16.8 M   7.3 s [1]_  0.23 s  0.26x
           nested dissection (pymetis) once
           per grid (3.6 s)
mmd        SuperLU, diagonal pivots, minimum 17.9 M   9.1 s       0.22 s  0.22x
           degree on Aᵀ + A at each LU
colamd     SuperLU, COLAMD, partial pivots   39.2 M   24.4 s      0.18 s  1 (53.5 s)
pardiso    MKL PARDISO (pypardiso), 1        18.0 M   4.9 s       0.24 s  1.59x
           thread, analysis at each LU
umfpack    cvxopt's UMFPACK (not offered)    --       3.2 s [2]_  0.18 s  --
klu        PyKLU (not offered: no symbolic   --       --          --      --
           reuse, no supernodes)
=========  ================================  =======  ==========  ======  ===========

.. [1] One LU at the converged state in the same rounds; the whole solves' 17 LUs (all
   grids of the coarse start) took 16.4 s (metis), 24.7 s (mmd), 61.3 s (colamd).
.. [2] Measured apart in one earlier run (load about 4): UMFPACK 0.51 s symbolic + 3.2 s
   numeric against SuperLU + METIS 2.5 s and PARDISO 1.6 s + 2.1 s in the same minutes.

All reach the same state (relative differences 1e-11, Newton's tolerance 1e-8). Since
then "grid" (:mod:`gyroshell.linalg.grid_ordering`: nested dissection along the grid's
node lines, computed in numpy from the unknowns' node indices) orders the fine grid in
0.07 s against METIS's 0.66 s, fills 19.0 M against 16.8 M and factors in the same time
within the machine's noise (docs/performance.md); "auto" is "grid" (pure scipy, no
optional package); the infinitely wide tape keeps "colamd" (banded, milliseconds).
``single=True`` of :class:`DiagonalPivotLU` factors in single precision (0.6x the LU
time); the bearing does not use it by default: on ill-conditioned Jacobians its steps
mislead Newton although their backward errors are small
(:data:`gyroshell.bearing.steady.SINGLE_LU`).

Every sparse LU of the package goes through :func:`splu` (one place for SuperLU's options).
The eigen-solvers' symmetric/Hermitian factorizations choose between CHOLMOD's Cholesky and
SuperLU's LDLᴴ (:data:`gyroshell.linalg.cholesky.BACKENDS`): :func:`resolve_factorization`
says what ``"auto"`` means at the moment of the call, and :func:`use_factorization` sets
that for a block of code (every engine below it, inertia counts included, follows).
"""

from __future__ import annotations

import contextvars
import math
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Protocol

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.linalg import blas, lapack

from ..core.errors import ParameterError
from . import cholesky

#: Column ordering of every SuperLU factorization: minimum degree on Aᵀ + A (least fill on
#: the tape's matrices, whose pattern is symmetric; about 20 % less than COLAMD).
ORDERING = "MMD_AT_PLUS_A"


def splu(matrix: sp.spmatrix, *, symmetric_mode: bool = False, ordering: str = ORDERING,
         pivot_threshold: float = 0.0) -> spla.SuperLU:
    """SuperLU of a square sparse matrix, by default with the package's ordering.

    Parameters
    ----------
    matrix : scipy.sparse matrix, shape (n, n)
        Real or complex.
    symmetric_mode : bool
        Prefer diagonal pivots (SuperLU's symmetric mode): with ``pivot_threshold = 0``,
        P A Pᵀ = L D Lᴴ for a symmetric or Hermitian matrix, whose pivots then give its
        inertia (:mod:`gyroshell.linalg.inertia`).
    ordering : str
        SuperLU's column ordering (``permc_spec``); :data:`ORDERING` unless a caller's
        matrices are known to fill less under another (the bearing's Jacobian: COLAMD).
    pivot_threshold : float
        In symmetric mode, how much smaller than the column's largest a diagonal pivot may
        be before another is taken (SuperLU's ``diag_pivot_thresh``), 0 to 1.

    Raises
    ------
    RuntimeError
        SuperLU's "Factor is exactly singular".
    """
    if symmetric_mode:
        return spla.splu(sp.csc_matrix(matrix), permc_spec=ordering,
                         diag_pivot_thresh=pivot_threshold, options={"SymmetricMode": True})
    return spla.splu(sp.csc_matrix(matrix), permc_spec=ordering)


#: What "auto" means for the eigen-solvers' factorizations inside :func:`use_factorization`
#: (None: CHOLMOD where installed).
_AUTO_FACTORIZATION: contextvars.ContextVar[str | None] = contextvars.ContextVar(
    "gyroshell_auto_factorization", default=None)


def check_factorization(factorization) -> str:
    """One of :data:`gyroshell.linalg.cholesky.BACKENDS`; "cholmod" only where cvxopt is
    installed. Raises ParameterError otherwise."""
    if factorization not in cholesky.BACKENDS:
        raise ParameterError(f"factorization must be one of {', '.join(cholesky.BACKENDS)}, "
                             f"got {factorization!r}")
    if factorization == "cholmod" and not cholesky.available():
        raise ParameterError("factorization 'cholmod' needs cvxopt "
                             "(pip install 'gyroshell[fast]'); use 'superlu' or 'auto'")
    return factorization


def resolve_factorization(factorization: str = "auto") -> str:
    """"cholmod" or "superlu": what an eigen-solver uses for ``factorization``, now.

    "auto" is the back-end set by an enclosing :func:`use_factorization`, else CHOLMOD where
    cvxopt is installed (measured faster: module notes of :mod:`gyroshell.linalg.cholesky`),
    else SuperLU. Read at call time by every caller, so one setting reaches all of them.
    """
    if factorization != "auto":
        return factorization
    chosen = _AUTO_FACTORIZATION.get()
    if chosen is not None:
        return chosen
    return "cholmod" if cholesky.available() else "superlu"


@contextmanager
def use_factorization(factorization: str) -> Iterator[str]:
    """Within the block, ``factorization="auto"`` means ``factorization`` ("cholmod" or
    "superlu") for every eigen-solver, engine and inertia count that resolves it.

    Examples
    --------
    >>> with use_factorization("superlu"):
    ...     resolve_factorization("auto")
    'superlu'
    """
    factorization = check_factorization(factorization)
    token = _AUTO_FACTORIZATION.set(None if factorization == "auto" else factorization)
    try:
        yield resolve_factorization("auto")
    finally:
        _AUTO_FACTORIZATION.reset(token)


class Factorization(Protocol):
    """A factored square matrix A: ``solve(rhs)`` returns A⁻¹ rhs."""

    name: str
    factor_time: float

    def solve(self, rhs: np.ndarray) -> np.ndarray: ...


class SuperLUFactor:
    """SuperLU (scipy.sparse.linalg.splu), minimum-degree ordering on Aᵀ + A.

    Parameters
    ----------
    matrix : scipy.sparse matrix
        Square, real; ordered by :data:`ORDERING`, which gave the least fill on K_eq.
    ordering : str
        Another SuperLU column ordering, for matrices that fill less under it.
    """

    name = "superlu"

    def __init__(self, matrix: sp.spmatrix, *, ordering: str = ORDERING) -> None:
        start = time.perf_counter()
        self._lu = splu(matrix, ordering=ordering)
        self.factor_time = time.perf_counter() - start

    @property
    def nnz(self) -> int:
        """Entries of L and U (formed on demand: extracting them costs a third of a
        factorization of the bearing's Jacobian)."""
        return int(self._lu.L.nnz + self._lu.U.nnz)

    @staticmethod
    def available() -> bool:
        return True

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        return self._lu.solve(rhs)


class BandedFactor:
    """LAPACK banded LU with partial pivoting (dgbtrf/dgbtrs through scipy).

    Stores (2 k_l + k_u + 1) × n numbers: fine for the tape's narrow band, wasteful for
    matrices with a few far-off entries.
    """

    name = "banded"

    def __init__(self, matrix: sp.spmatrix) -> None:
        start = time.perf_counter()
        coo = sp.coo_matrix(matrix)
        n = coo.shape[0]
        offset = coo.row.astype(np.int64) - coo.col
        kl = max(int(offset.max(initial=0)), 0)
        ku = max(int(-offset.min(initial=0)), 0)
        ab = np.zeros((2 * kl + ku + 1, n))
        np.add.at(ab, (kl + ku + offset, coo.col), coo.data)
        lub, piv, info = lapack.dgbtrf(ab, kl, ku, overwrite_ab=True)
        if info > 0:
            raise np.linalg.LinAlgError(f"banded LU: exactly singular pivot {info}")
        self._lub, self._piv, self._kl, self._ku = lub, piv, kl, ku
        self.factor_time = time.perf_counter() - start
        self.nnz = int(lub.size)

    @staticmethod
    def available() -> bool:
        return True

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        x, info = lapack.dgbtrs(self._lub, self._kl, self._ku, rhs, self._piv)
        if info != 0:
            raise np.linalg.LinAlgError(f"dgbtrs failed (info = {info})")
        return x


class UmfpackFactor:
    """UMFPACK through scikit-umfpack (optional), iterative refinement off.

    UMFPACK's default two refinement steps cost two extra substitutions and mat-vecs per
    solve (3x slower here) and gain nothing on this well-conditioned K_eq.
    """

    name = "umfpack"

    def __init__(self, matrix: sp.spmatrix) -> None:
        import scikits.umfpack as um

        start = time.perf_counter()
        self._A = sp.csc_matrix(matrix, dtype=float)
        self._A.sort_indices()
        self._ctx = um.UmfpackContext("dl" if self._A.indices.dtype == np.int64 else "di")
        self._ctx.control[um.UMFPACK_IRSTEP] = 0
        self._ctx.numeric(self._A)
        self._sys = um.UMFPACK_A
        self.factor_time = time.perf_counter() - start

    @staticmethod
    def available() -> bool:
        try:
            import scikits.umfpack  # noqa: F401
        except Exception:  # ImportError, or a broken shared library
            return False
        return True

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        return self._ctx.solve(self._sys, self._A, rhs, autoTranspose=True)


class PardisoFactor:
    """Intel MKL PARDISO through pypardiso (optional), real non-symmetric, no refinement."""

    name = "pardiso"

    def __init__(self, matrix: sp.spmatrix) -> None:
        import pypardiso

        start = time.perf_counter()
        self._A = sp.csr_matrix(matrix, dtype=float)
        self._A.sort_indices()
        self._solver = pypardiso.PyPardisoSolver(mtype=11)
        self._solver.set_iparm(8, 0)  # iparm(8): no iterative refinement steps
        self._solver.factorize(self._A)
        self._solver.set_phase(33)  # later calls: substitution only, no re-hash of A
        self.factor_time = time.perf_counter() - start

    @staticmethod
    def available() -> bool:
        try:
            import pypardiso  # noqa: F401
        except Exception:
            return False
        return True

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        return np.asarray(self._solver._call_pardiso(self._A, rhs)).reshape(rhs.shape)


#: name -> back-end class, fastest first ("auto" takes the first installed one).
BACKENDS: dict[str, Callable[..., Factorization]] = {
    "superlu": SuperLUFactor,
    "umfpack": UmfpackFactor,
    "pardiso": PardisoFactor,
    "banded": BandedFactor,
}

#: What "auto" uses: SuperLU (measured fastest of the reliable ones, always installed).
AUTO_BACKEND = "superlu"


def available_backends() -> tuple[str, ...]:
    """Names of the back-ends installed here (``"superlu"`` and ``"banded"`` always)."""
    return tuple(name for name, cls in BACKENDS.items() if cls.available())


def resolve_backend(backend: str = "auto") -> str:
    """The back-end name ``factorize`` would use; raises ParameterError if unusable."""
    if backend == "auto":
        return AUTO_BACKEND
    if backend not in BACKENDS:
        raise ParameterError(f"backend must be one of auto, {', '.join(BACKENDS)}; "
                             f"got {backend!r}")
    if not BACKENDS[backend].available():
        package = {"umfpack": "scikit-umfpack", "pardiso": "pypardiso"}[backend]
        raise ParameterError(f"backend {backend!r} needs the optional package {package}, "
                             f"which is not installed (installed: "
                             f"{', '.join(available_backends())})")
    return backend


def factorize(matrix: sp.spmatrix, backend: str = "auto") -> Factorization:
    """Factor a square real sparse matrix once for many solves.

    Parameters
    ----------
    matrix : scipy.sparse matrix, shape (n, n)
    backend : {"auto", "superlu", "umfpack", "pardiso", "banded"}
        ``"auto"`` picks the fastest reliable installed back-end (SuperLU, see the module
        notes). Optional ones need their package (scikit-umfpack, pypardiso).

    Returns
    -------
    Factorization
        An object with ``solve(rhs) -> x``, ``name`` and ``factor_time`` (s).

    Raises
    ------
    ParameterError
        For an unknown or uninstalled back-end (the message lists the valid ones).
    """
    name = resolve_backend(backend)
    if matrix.shape[0] != matrix.shape[1]:
        raise ParameterError(f"matrix must be square, got shape {matrix.shape}")
    return BACKENDS[name](matrix)


# ----- LU with a symmetric fill-reducing ordering and diagonal pivots (the bearing) ------
#: SuperLU's column ordering of :class:`DiagonalPivotLU` without a given permutation:
#: minimum degree on Aᵀ + A (pure scipy), recomputed at each factorization.
DIAGONAL_PIVOT_ORDERING = "MMD_AT_PLUS_A"
#: A solve whose backward error max|A x − b| / max(|A||x| + |b|) exceeds this was spoilt by
#: a small diagonal pivot: the matrix is factored again with partial pivoting.
BACKWARD_ERROR_LIMIT = 1e-10
#: The same for factors in single precision (``single=True`` of :class:`DiagonalPivotLU`):
#: a solve above it factors the matrix again in double precision.
SINGLE_BACKWARD_ERROR_LIMIT = 1e-5


def metis_available() -> bool:
    """Whether METIS (the optional package pymetis) is installed."""
    try:
        import pymetis  # noqa: F401
    except Exception:  # ImportError, or a broken shared library
        return False
    return True


def nested_dissection(matrix: sp.spmatrix) -> np.ndarray:
    """METIS's nested-dissection ordering (pymetis) of the pattern of |A| + |A|ᵀ.

    Parameters
    ----------
    matrix : scipy.sparse matrix, shape (n, n)

    Returns
    -------
    numpy.ndarray of int, shape (n,)
        A permutation: row and column k of the reordered matrix A[perm][:, perm] are
        row and column perm[k] of A.

    Raises
    ------
    ParameterError
        If pymetis is not installed.
    """
    if not metis_available():
        raise ParameterError("the nested-dissection ordering needs pymetis "
                             "(pip install 'gyroshell[fast]')")
    import pymetis

    n = matrix.shape[0]
    if n < 2:
        return np.arange(n)
    graph = sp.csr_matrix(abs(sp.csr_matrix(matrix)) + abs(sp.csr_matrix(matrix)).T)
    graph.setdiag(0)
    graph.eliminate_zeros()
    perm, _ = pymetis.nested_dissection(
        adjacency=pymetis.CSRAdjacency(graph.indptr, graph.indices))
    return np.asarray(perm, dtype=np.intp)


class DiagonalPivotLU:
    """SuperLU of P A Pᵀ with diagonal pivots: the fill of a symmetric ordering kept.

    A fill-reducing ordering of a matrix with a symmetric pattern (nested dissection,
    minimum degree on Aᵀ + A) is spoilt by SuperLU's partial pivoting: every off-diagonal
    pivot moves a row out of the order (on the bearing's Jacobian a pivot threshold of
    even 10⁻³ more than doubles the fill). Here SuperLU runs in its symmetric mode with
    pivot threshold 0, so the diagonal is always the pivot and P A Pᵀ = L U. Each solve
    checks its backward error; above :data:`BACKWARD_ERROR_LIMIT` (a small pivot) the
    matrix is factored again with partial pivoting (COLAMD) and the solve repeated.

    Parameters
    ----------
    matrix : scipy.sparse matrix, shape (n, n)
        Square, real.
    permutation : numpy.ndarray of int, optional
        The symmetric ordering P (e.g. :func:`nested_dissection`, computed once for many
        matrices of one pattern); default minimum degree on Aᵀ + A, computed by SuperLU.
    ordered : bool
        The matrix is already in its elimination order (P A Pᵀ assembled as such, e.g. by
        :class:`gyroshell.bearing.jacobian.JacobianPattern`): factored as it is, and
        solves are in its numbering. Excludes ``permutation``.
    single : bool
        Factor in single precision (half the memory, about 0.6x the time); a solve whose
        backward error against the double-precision matrix exceeds
        :data:`SINGLE_BACKWARD_ERROR_LIMIT` factors the matrix again in double.
    """

    name = "superlu-diagonal"

    def __init__(self, matrix: sp.spmatrix, *, permutation: np.ndarray | None = None,
                 ordered: bool = False, single: bool = False) -> None:
        start = time.perf_counter()
        if ordered and permutation is not None:
            raise ParameterError("DiagonalPivotLU: give a permutation or ordered=True, "
                                 "not both")
        csc = sp.csc_matrix(matrix)
        self._perm = permutation
        if permutation is not None:
            csc = csc[permutation][:, permutation]
        self._A = csc          # the factored matrix, in the order of its elimination
        self._abs = abs(csc)
        self._permc = ("NATURAL" if ordered or permutation is not None
                       else DIAGONAL_PIVOT_ORDERING)
        #: whether the factors are in single precision (:data:`SINGLE_BACKWARD_ERROR_LIMIT`)
        self.single = single
        self._lu = self._factor(csc.astype(np.float32) if single else csc)
        #: whether a small pivot made it fall back to partial pivoting
        self.pivoted = False
        self.factor_time = time.perf_counter() - start

    def _factor(self, csc):
        return splu(csc, symmetric_mode=True, ordering=self._permc)

    @staticmethod
    def available() -> bool:
        return True

    def backward_error(self, x: np.ndarray, rhs: np.ndarray) -> float:
        """max|A x − b| / max(|A||x| + |b|): the relative backward error of a solve (x and
        b in the factored matrix's order)."""
        scale = float(np.max(self._abs @ np.abs(x) + np.abs(rhs), initial=0.0))
        return float(np.max(np.abs(self._A @ x - rhs), initial=0.0)) / scale if scale else 0.0

    def _solve_ordered(self, rhs: np.ndarray) -> np.ndarray:
        if self.single:
            x = self._lu.solve(rhs.astype(np.float32)).astype(float)
            if np.all(np.isfinite(x)) and (self.backward_error(x, rhs)
                                           <= SINGLE_BACKWARD_ERROR_LIMIT):
                return x
            start = time.perf_counter()          # factored again in double precision
            self._lu, self.single = self._factor(self._A), False
            self.factor_time += time.perf_counter() - start
        x = self._lu.solve(rhs)
        if not self.pivoted and not (np.all(np.isfinite(x))
                                     and self.backward_error(x, rhs) <= BACKWARD_ERROR_LIMIT):
            start = time.perf_counter()
            self._lu = splu(self._A, ordering="COLAMD")
            self.pivoted = True
            self.factor_time += time.perf_counter() - start
            x = self._lu.solve(rhs)
        return x

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        if self._perm is None:
            return self._solve_ordered(rhs)
        x = np.empty_like(rhs)
        x[self._perm] = self._solve_ordered(rhs[self._perm])
        return x



#: :class:`BandLU` keeps its unpivoted factors while ‖ |L||U| ‖∞ stays below this many
#: times ‖A‖∞ (then every solve is backward stable: |ΔA| ≤ γ |L||U|); above it, partial
#: pivoting.
BAND_GROWTH_LIMIT = 10.0


class BandLU:
    """LU of a banded matrix in its own order with diagonal pivots, solved by two BLAS band
    substitutions.

    SuperLU factors A in the natural order with diagonal pivots (symmetric mode, pivot
    threshold 0, as in :class:`DiagonalPivotLU`), so L and U stay inside A's band; they are
    copied into LAPACK band storage and each solve is two ``dtbsv`` calls (unit lower, then
    upper triangular band), with no index arrays and no supernode bookkeeping: on
    Newmark's K_eq of the symmetric half of the L_x/L_y = 19 tape (16,338 unknowns,
    half-bandwidth 42) a third of SuperLU's natural-order substitution
    (:mod:`gyroshell.linalg.ordering`). Without pivoting the factors are kept only if
    ‖ |L||U| ‖∞ ≤ :data:`BAND_GROWTH_LIMIT` ‖A‖∞, which bounds the backward error of every
    solve (Higham, *Accuracy and Stability of Numerical Algorithms*, Thm. 9.4); K_eq's
    dominant mass diagonal gives about 1. Otherwise (or if SuperLU moved a row or column)
    the matrix is factored again by SuperLU with partial pivoting in the natural order
    (``pivoted`` True) and solved by it.

    Parameters
    ----------
    matrix : scipy.sparse matrix, shape (n, n)
        Square, real.
    """

    name = "band"

    def __init__(self, matrix: sp.spmatrix) -> None:
        start = time.perf_counter()
        if np.iscomplexobj(matrix.data if sp.issparse(matrix) else matrix):
            raise ParameterError("BandLU: matrix must be real (its band substitutions are "
                                 "dtbsv's), got a complex one")
        A = sp.csc_matrix(matrix, dtype=float)
        n = A.shape[0]
        try:
            lu = splu(A, symmetric_mode=True, ordering="NATURAL")
        except RuntimeError:  # a zero pivot on the diagonal
            lu = None
        identity = np.arange(n)
        #: whether the unpivoted factors were refused (solves then go through SuperLU)
        self.pivoted = lu is None or not (np.array_equal(lu.perm_r, identity)
                                          and np.array_equal(lu.perm_c, identity))
        self._lu = None
        #: ‖ |L||U| ‖∞ / ‖A‖∞ of the unpivoted factors (inf if there are none)
        self.growth = math.inf
        if not self.pivoted:
            L, U = lu.L.tocoo(), lu.U.tocoo()
            self._kl = int(np.max(L.row - L.col, initial=0))
            self._ku = int(np.max(U.col - U.row, initial=0))
            self._lower = np.zeros((self._kl + 1, n), order="F")
            self._lower[L.row - L.col, L.col] = L.data
            self._upper = np.zeros((self._ku + 1, n), order="F")
            self._upper[self._ku + U.row - U.col, U.col] = U.data
            ones = np.ones(n)
            growth = np.max(abs(L.tocsr()) @ (abs(U.tocsr()) @ ones))
            self.growth = float(growth / np.max(abs(A) @ ones))
            self.pivoted = not self.growth <= BAND_GROWTH_LIMIT
        if self.pivoted:
            self._lu = splu(A, ordering="NATURAL")
        self.factor_time = time.perf_counter() - start

    @staticmethod
    def available() -> bool:
        return True

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        if np.iscomplexobj(rhs):
            raise ParameterError("BandLU.solve: rhs must be real, got a complex array")
        if self._lu is not None:
            return self._lu.solve(rhs)
        rhs = np.asarray(rhs, dtype=float)
        if rhs.ndim != 1:
            return np.column_stack([self.solve(b) for b in rhs.T])
        y = blas.dtbsv(self._kl, self._lower, rhs, lower=1, diag=1)
        return blas.dtbsv(self._ku, self._upper, y, lower=0, overwrite_x=1)


#: The sparse LUs of a nonsymmetric matrix whose pattern is (nearly) symmetric, e.g. the
#: bearing's Jacobian (``factorization=`` of :class:`gyroshell.bearing.BearingModel`):
#: "grid" SuperLU with diagonal pivots after a nested dissection along the grid's node
#: lines (:mod:`gyroshell.linalg.grid_ordering`, pure numpy, once per grid); "metis" the
#: same after METIS's nested dissection (pymetis), once per grid; "mmd" the same after
#: minimum degree on Aᵀ + A (pure scipy, ordered at each factorization); "colamd" SuperLU
#: with COLAMD and partial pivoting (the earlier default); "pardiso" MKL PARDISO
#: (pypardiso); "auto" is "grid".
PATTERN_LU = ("auto", "grid", "metis", "mmd", "colamd", "pardiso")
#: factorization -> (its optional package, whether it is installed, the pip command that
#: installs it: pymetis is in the ``fast`` extra, pypardiso in no extra).
_PATTERN_LU_PACKAGES = {
    "metis": ("pymetis", metis_available, "pip install 'gyroshell[fast]'"),
    "pardiso": ("pypardiso", PardisoFactor.available, "pip install pypardiso")}


def check_pattern_lu(factorization, *, name: str = "factorization") -> str:
    """One of :data:`PATTERN_LU`, with its optional package installed; else
    ParameterError naming ``name`` and the choices."""
    if not isinstance(factorization, str) or factorization not in PATTERN_LU:
        raise ParameterError(f"{name} must be one of {', '.join(PATTERN_LU)}, "
                             f"got {factorization!r}")
    if factorization in _PATTERN_LU_PACKAGES:
        package, available, install = _PATTERN_LU_PACKAGES[factorization]
        if not available():
            raise ParameterError(f"{name} {factorization!r} needs the optional package "
                                 f"{package} ({install}); use 'auto'")
    return factorization


def resolve_pattern_lu(factorization: str = "auto") -> str:
    """What ``factorization`` (:data:`PATTERN_LU`) means: "auto" is "grid" (pure scipy;
    module notes: the measured back-ends)."""
    return "grid" if factorization == "auto" else factorization
