"""The problem of one solve: validated matrices, options, and its linear operators.

:class:`Problem` holds M, G, K, C and the options; its ``factor`` chooses CHOLMOD or
SuperLU. Two operators act on the state z = [λφ; φ]: :class:`EnergyOperator`, the
shift-invert of the Hermitian pencil H z = ω L z in the energy inner product (Lanczos), and
:func:`linearized_operator`, the shift-invert of the linearization A z = λ B z (ARPACK);
both are described in the notes of :mod:`gyroshell.linalg.qep`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, fields, replace

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ...core import validation
from ...core.errors import ParameterError
from .. import cholesky
from ..inertia import InertiaFactor, factor_inertia
from .spectrum import norm1, product

#: Default relative tolerance of the eigen-iteration (on 1/(λ − σ)).
DEFAULT_TOL = 1e-10
#: Relative symmetry defect ‖A − Aᵀ‖₁ / ‖A‖₁ accepted for M, K, C (and skewness for G).
STRUCTURE_RTOL = 1e-10
#: C >= 0 is tested as C + εI > 0 with ε this fraction of ‖C‖₁ (round-off allowance).
SEMIDEFINITE_RTOL = 1e-12
#: Fixed seed of the random start vector: reproducible results.
START_SEED = 12345
#: Most eigenpairs one sparse call computes: the Krylov basis (about 2·count + 10 vectors
#: of length 2n, twice) and its orthogonalization grow with the count; beyond it, use
#: several shifts.
MAX_COUNT = 50
#: Up to this many unknowns the problem is solved densely (every eigenvalue, LAPACK).
DENSE_LIMIT = 40



#: Eigen-iterations of the undamped subcritical case.
METHODS = ("auto", "lanczos", "arpack")


@dataclass(frozen=True)
class SolverOptions:
    """The tuning knobs of the eigen-solver (every one keyword-only in the solvers).

    Attributes
    ----------
    tol : float
        Relative tolerance of the eigen-iteration, in [0, 1).
    ncv, maxiter : int, optional
        ARPACK's basis size and restarts; giving either selects ARPACK.
    method : {"auto", "lanczos", "arpack"}
        Eigen-iteration of the undamped subcritical case ("auto": Lanczos, ARPACK if it does
        not converge or if ncv/maxiter are given). The other cases use ARPACK.
    factorization : {"auto", "cholmod", "superlu"}
        Factorization of the shift matrices (see
        :func:`gyroshell.linalg.factorization.resolve_factorization`).

    Notes
    -----
    The values are checked by the solver, in its order of checks.
    """

    tol: float = DEFAULT_TOL
    ncv: int | None = None
    maxiter: int | None = None
    method: str = "auto"
    factorization: str = "auto"

    @classmethod
    def of(cls, options: SolverOptions | None = None, /, **tuning) -> SolverOptions:
        """``options`` (default: the defaults) with the knobs in ``tuning`` replaced.

        Raises
        ------
        TypeError
            For a keyword that is not a knob (as for an unknown keyword argument).
        """
        validation.instance("options", options, SolverOptions, optional=True)
        unknown = set(tuning) - {f.name for f in fields(cls)}
        if unknown:
            raise TypeError(f"unexpected keyword argument {sorted(unknown)[0]!r}")
        return replace(options or cls(), **tuning)

    def as_dict(self) -> dict:
        """The knobs as keyword arguments."""
        return {f.name: getattr(self, f.name) for f in fields(self)}


# ----- structure checks -----------------------------------------------------------------
def _as_sparse(name: str, matrix, n: int | None) -> sp.csr_matrix:
    try:
        out = sp.csr_matrix(matrix)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a square real matrix (dense or sparse), "
                             f"got {type(matrix).__name__}") from None
    if out.ndim != 2 or out.shape[0] != out.shape[1]:
        raise ParameterError(f"{name} must be square, got shape {out.shape}")
    if n is not None and out.shape[0] != n:
        raise ParameterError(f"{name} must have the shape of M, {(n, n)}, got {out.shape}")
    if np.iscomplexobj(out.data) or not np.issubdtype(out.dtype, np.number):
        raise ParameterError(f"{name} must be real, got dtype {out.dtype}")
    out = out.astype(float)
    if not np.all(np.isfinite(out.data)):
        raise ParameterError(f"{name} must be finite (it has NaN or inf entries)")
    return out


def _check_symmetry(name: str, matrix: sp.csr_matrix, sign: int, what: str) -> None:
    defect = norm1(matrix - sign * matrix.T)
    scale = norm1(matrix)
    if defect > STRUCTURE_RTOL * scale:
        raise ParameterError(
            f"{name} must be {what}: ‖{name} {'-' if sign > 0 else '+'} {name}ᵀ‖₁ / ‖{name}‖₁ = "
            f"{defect / scale:.1e} > {STRUCTURE_RTOL:g}")


#: Bytes per stored entry of a sparse factor of Q(σ): a complex value and a 32-bit index.
FACTOR_ENTRY_BYTES = 20
#: Bytes per stored entry of the real input matrices and their checked copies and
#: transposes (value 8, index 4; about four copies alive during the checks).
MATRIX_ENTRY_BYTES = 48
#: Work vectors of the 2n first-order state alive beside the Krylov basis (operator
#: applications, residuals, Rayleigh quotients, normalization), complex.
WORK_VECTORS = 16
#: Basis sizes of the iterations (lanczos: max(2 count + 10, 32) + 1; ARPACK: max(2 count +
#: 1, count + 20)); the larger is planned for.
LANCZOS_BASIS = (10, 32)
ARPACK_BASIS_EXTRA = 20


def qep_bytes(n: int, nnz: int, count: int) -> float:
    """Estimated peak memory of a sparse quadratic eigen-solve, bytes.

    The input matrices' checked copies (``nnz`` entries of M, G and K together), Q(σ) and
    its factor (nnz(Q) · max(1, log₂ n) entries: the fill of a nested-dissection ordering
    on a 2-D mesh, as for the tape's stencil), the Krylov basis of 2n-vectors (complex) and
    the work vectors. Measured peaks: ``benchmarks/bench_qep_memory.py``.
    """
    n = float(n)
    basis = max(2 * count + LANCZOS_BASIS[0], LANCZOS_BASIS[1]) + 1
    basis = max(basis, 2 * count + 1, count + ARPACK_BASIS_EXTRA)
    factor = (nnz + n) * max(1.0, math.log2(max(n, 2.0)))
    return (MATRIX_ENTRY_BYTES * nnz + FACTOR_ENTRY_BYTES * (nnz + factor)
            + 16.0 * 2 * n * (basis + WORK_VECTORS))


def check_memory(n: int, nnz: int, count) -> float:
    """Refuse a sparse eigen-solve that cannot fit in memory, before any work; returns the
    estimate (:func:`qep_bytes`) in bytes.

    Raises
    ------
    ParameterError
        Naming the unknowns, the estimate and the limit (``GYROSHELL_MEMORY_LIMIT`` or half
        the physical memory).
    """
    from ...core import budget

    if n <= DENSE_LIMIT:
        return 0.0
    valid = isinstance(count, (int, np.integer)) and not isinstance(count, bool)
    count = int(count) if valid and 1 <= count <= MAX_COUNT else 1
    estimate = qep_bytes(n, nnz, count)
    limit = budget.memory_limit()
    if estimate > limit:
        raise ParameterError(
            f"an eigen-solve of {n} unknowns ({nnz} matrix entries, {count} pairs) needs "
            f"about {estimate / 1e9:.3g} GB, more than the limit {limit / 1e9:.3g} GB; use "
            f"smaller matrices (or set {budget.MEMORY_LIMIT_VARIABLE})")
    return estimate


def _is_zero_scalar(value) -> bool:
    """``K=0`` (a plain zero) stands for the zero matrix: no stiffness."""
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
        value, bool) and value == 0


def check_structure(M, G, K, C=None, *, count=None) -> tuple[sp.csr_matrix, ...]:
    """Validated sparse M, G, K, C (C None if absent), or a ParameterError naming the flaw.

    M symmetric positive definite, G skew-symmetric, K symmetric, C symmetric positive
    semi-definite; all real, square, finite and of one size. ``K=0`` (a scalar zero) is the
    zero matrix. With ``count``, the memory of the solve is estimated right after the
    conversion and refused if it cannot fit (:func:`check_memory`).
    """
    M = _as_sparse("M", M, None)
    n = M.shape[0]
    G = _as_sparse("G", G, n)
    K = _as_sparse("K", sp.csr_matrix((n, n)) if _is_zero_scalar(K) else K, n)
    if count is not None:
        check_memory(n, M.nnz + G.nnz + K.nnz, count)
    _check_symmetry("M", M, 1, "symmetric")
    _check_symmetry("G", G, -1, "skew-symmetric")
    _check_symmetry("K", K, 1, "symmetric")
    if n < 2:
        raise ParameterError(f"the matrices must be at least 2 x 2, got {n} x {n}")
    if not _positive_definite(M):
        raise ParameterError("M must be positive definite (a mass matrix)")
    if C is not None:
        C = _as_sparse("C", C, n)
        _check_symmetry("C", C, 1, "symmetric")
        if C.nnz and not _positive_semidefinite(C):
            raise ParameterError("C must be positive semi-definite (dissipative damping)")
        if not C.count_nonzero():
            C = None
    return M, G, K, C


def check_family(M, G1, A, B) -> None:
    """Prove the structure of every member (M, V·G1, A + τB) of a family of problems once
    (any real V, τ): M symmetric positive definite, G1 skew-symmetric, A and B symmetric;
    a ParameterError naming the flaw otherwise. Members built from proved parts are
    solved with ``solve_qep(..., checked=True)``.

    A and B are tested together, as the complex X = A + i s B with s = ‖A‖₁/‖B‖₁: each
    part's defect is at most |X − Xᵀ| entry by entry, so ‖X − Xᵀ‖₁ <= STRUCTURE_RTOL ‖A‖₁
    proves both (one transpose instead of two); where it does not hold, each is tested
    alone for the message."""
    M = _as_sparse("M", M, None)
    n = M.shape[0]
    G1, A, B = (_as_sparse(name, X, n) for name, X in (("G", G1), ("A", A), ("B", B)))
    if n < 2:
        raise ParameterError(f"the matrices must be at least 2 x 2, got {n} x {n}")
    if not is_diagonal(M):
        _check_symmetry("M", M, 1, "symmetric")
    if not _positive_definite(M):
        raise ParameterError("M must be positive definite (a mass matrix)")
    _check_symmetry("G", G1, -1, "skew-symmetric")
    size_a, size_b = norm1(A), norm1(B)
    X = A + (1j * size_a / size_b) * B if size_a and size_b else A + 1j * B
    if norm1(X - X.T) > STRUCTURE_RTOL * (size_a or size_b):
        _check_symmetry("A", A, 1, "symmetric")
        _check_symmetry("B", B, 1, "symmetric")


def is_diagonal(matrix: sp.csr_matrix) -> bool:
    coo = matrix.tocoo()
    return bool(np.all(coo.row == coo.col))


def _positive_definite(M: sp.csr_matrix) -> bool:
    if is_diagonal(M):
        d = M.diagonal()
        return bool(np.all(d > 0))
    return factor_inertia(M).definite


def _positive_semidefinite(C: sp.csr_matrix) -> bool:
    if is_diagonal(C):
        return bool(np.all(C.diagonal() >= 0))
    # C + εI > 0 for every ε > 0 exactly when C >= 0; ε relative to ‖C‖ allows round-off.
    eps = SEMIDEFINITE_RTOL * norm1(C)
    return factor_inertia(C + eps * sp.identity(C.shape[0])).definite


def check_count(count: int, n: int) -> int:
    """1 <= count <= the most a Krylov eigen-solver delivers in reasonable time here."""
    count = validation.integer("count", count)
    limit = max_count(n)
    if not 1 <= count <= limit:
        raise ParameterError(f"count must be in [1, {limit}] for {n} unknowns, got {count}")
    return count


def max_count(n: int) -> int:
    """Largest ``count`` accepted for n unknowns: n when solved densely (n <= DENSE_LIMIT),
    else min(MAX_COUNT, n/2 − 1)."""
    if n <= DENSE_LIMIT:
        return n
    return max(1, min(MAX_COUNT, n // 2 - 1))


def check_optional_int(name: str, value) -> int | None:
    """None or an integer >= 1 (ARPACK's ncv and maxiter)."""
    return validation.integer(name, value, low=1, optional=True)


def check_tol(tol) -> float:
    return validation.real("tol", tol, low=0.0, high=1.0, high_open=True)


def check_shift(sigma) -> complex | None:
    """None (automatic), 0, or iω_s with ω_s >= 0 rad/s; a ParameterError otherwise."""
    if sigma is None:
        return None
    if isinstance(sigma, str):
        if sigma != "auto":
            raise ParameterError(f"sigma must be 'auto', 0 or i*omega_s, got {sigma!r}")
        return None
    try:
        s = complex(sigma)
    except (TypeError, ValueError):
        raise ParameterError(f"sigma must be 'auto', 0 or i*omega_s, got {sigma!r}") from None
    if not (math.isfinite(s.real) and math.isfinite(s.imag)) or s.real != 0 or s.imag < 0:
        raise ParameterError(
            f"sigma must be 0 or purely imaginary i*omega_s with omega_s >= 0 rad/s, got {s}")
    return s



def check_start(start, n: int):
    if start is None:
        return None
    try:
        lam, phi = start
        lam = np.asarray(lam, dtype=complex).ravel()
        phi = np.asarray(phi, dtype=complex).reshape(n, -1)
    except (TypeError, ValueError):
        raise ParameterError("start must be (eigenvalues, vectors) with vectors of shape "
                             f"({n}, k)") from None
    if phi.shape[1] != len(lam) or not (np.all(np.isfinite(lam)) and
                                        np.all(np.isfinite(phi))):
        raise ParameterError("start must be finite (eigenvalues, vectors) of matching size")
    return lam, phi


def random_start(n2: int, dtype) -> np.ndarray:
    return np.random.default_rng(START_SEED).standard_normal(n2).astype(dtype)


@dataclass
class Problem:
    """Validated matrices and the options of one solve."""

    M: sp.csr_matrix
    G: sp.csr_matrix
    K: sp.csr_matrix
    C: sp.csr_matrix | None
    count: int
    tol: float
    ncv: int | None
    maxiter: int | None
    start: tuple[np.ndarray, np.ndarray] | None
    info: dict
    factorization: str = "superlu"
    factors: list = field(default_factory=list)
    #: A factorization of Q(σ) at the explicit shift, with its inertia count, made by the
    #: caller (who releases it); used instead of factoring Q(σ) again.
    shift_factor: object = None

    def factor(self, matrix: sp.spmatrix) -> InertiaFactor | cholesky.CholeskyFactor:
        """Factor a symmetric/Hermitian matrix: CHOLMOD's Cholesky when that back-end is
        selected and the matrix is positive definite (its success is the certificate: no
        negative eigenvalue), else SuperLU's LDLᴴ with its inertia count."""
        if self.factorization == "cholmod":
            factor = cholesky.cholesky(matrix)
            if factor is not None:
                self.factors.append(factor)
                return factor
        return factor_inertia(matrix)

    def release(self) -> None:
        """Return CHOLMOD's analysed factors to their pool (see gyroshell.cholesky)."""
        for factor in self.factors:
            factor.release()
        self.factors.clear()

    @property
    def n(self) -> int:
        return self.M.shape[0]

    @property
    def GC(self) -> sp.csr_matrix:
        """G + C, the matrix multiplying λ (G alone without damping), kg/s."""
        return self.G if self.C is None else self.G + self.C

    @property
    def mass_diagonal(self) -> np.ndarray:
        return self.M.diagonal()



class EnergyOperator:
    """T = (H − ω_s L)⁻¹ L and the energy inner product on z = [λφ; φ] (module notes).

    G and K are copied to complex once: scipy multiplies a complex CSR matrix by a complex
    vector 1.7-2.6x faster than the real matrix by the vector's (n, 2) real view (measured
    at L_x/L_y = 19: 0.68 ms against 1.15-1.8 ms for K), and the copy (4 ms) pays back
    within a few steps; a diagonal M is applied as a vector. Work arrays are allocated once.
    """

    def __init__(self, prob: Problem, omega_s: float, factor: InertiaFactor) -> None:
        self.G = prob.G.tocsr().astype(complex)
        self.K = prob.K.tocsr().astype(complex)
        self.md = prob.M.diagonal() if is_diagonal(prob.M) else None
        self.M = prob.M.tocsr()
        self.omega_s, self.factor, self.n = omega_s, factor, prob.n
        self.applications = 0
        self.solve_time = 0.0
        self._rhs = np.empty(prob.n, dtype=complex)

    def mass(self, u: np.ndarray) -> np.ndarray:
        return self.md * u if self.md is not None else product(self.M, u)

    def apply(self, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(T z, L T z). L T z without a product with K: with b = Q(iω_s)⁻¹ r,
        K b = r + ω_s² M b − iω_s G b (G has a sixth of K's entries on the tape)."""
        self.applications += 1
        n, ws = self.n, self.omega_s
        u1, u2 = z[:n], z[n:]
        rhs = self._rhs
        np.multiply(u2, 1j * ws, out=rhs)
        rhs += u1
        rhs = self.mass(rhs)
        rhs += self.G @ u2
        t0 = time.perf_counter()
        b = self.factor.solve(rhs)
        self.solve_time += time.perf_counter() - t0
        out = np.empty(2 * n, dtype=complex)
        np.multiply(b, -1j, out=out[n:])
        out[:n] = u2
        out[:n] += ws * out[n:]
        out[:n] *= 1j
        weighted = np.empty(2 * n, dtype=complex)
        weighted[:n] = self.mass(out[:n])
        kb = self.G @ b
        kb *= -1j * ws
        kb += rhs
        kb += ws * ws * self.mass(b)
        np.multiply(kb, -1j, out=weighted[n:])
        return out, weighted

    def weight(self, z: np.ndarray) -> np.ndarray:
        """L z."""
        n = self.n
        out = np.empty(2 * n, dtype=complex)
        out[:n] = self.mass(z[:n])
        out[n:] = self.K @ z[n:]
        return out



def linearized_operator(prob: Problem, solve, sigma: complex, omega_ref: float,
                         counter: list[int]) -> spla.LinearOperator:
    """(A − σB)⁻¹B on the scaled state y = [ω_r m^½ z₁; m^½ z₂]."""
    n = prob.n
    sm = np.sqrt(prob.mass_diagonal)
    M, GC = prob.M, prob.GC
    dtype = complex if sigma.imag != 0 else float
    sigma = sigma if dtype is complex else sigma.real

    def matvec(y: np.ndarray) -> np.ndarray:
        counter[0] += 1
        y = np.asarray(y).ravel()
        u1 = y[:n] / (omega_ref * sm)
        u2 = y[n:] / sm
        z1 = -solve(M @ u2 + GC @ u1 + sigma * (M @ u1))
        z2 = u1 + sigma * z1
        return np.concatenate([omega_ref * sm * z1, sm * z2])

    return spla.LinearOperator((2 * n, 2 * n), matvec=matvec, dtype=dtype)
