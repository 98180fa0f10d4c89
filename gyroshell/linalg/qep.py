"""Gyroscopic quadratic eigenproblem (λ²M + λ(G + C) + K) φ = 0 for any sparse matrices.

M symmetric positive definite, G skew-symmetric, K symmetric, C (optional viscous damping)
symmetric positive semi-definite. :func:`gyroscopic_modes` returns the eigenvalues nearest a
shift on the imaginary axis; the tape's :func:`gyroshell.eigen.modes` is a thin layer on it.

Three situations, three methods
-------------------------------
*Undamped, K positive definite* (below the critical speed). Every eigenvalue is a pair ±iω.
With z = [λφ; φ] the problem is the Hermitian-definite pencil

    H z = ω L z,   H = i [[G, K], [−K, 0]],   L = diag(M, K) > 0,

so shift-invert about ω_s, T = (H − ω_s L)⁻¹ L, is self-adjoint in the energy inner product
⟨x, y⟩ = x₁ᴴMy₁ + x₂ᴴKy₂ and a thick-restart Lanczos (Krylov–Schur) iteration applies. One
application of T is one solve with the Hermitian Q(iω_s) = K − ω_s²M + iω_sG:

    b = −i Q(iω_s)⁻¹ (M u₁ + (G + iω_s M) u₂),   a = i (u₂ + ω_s b).

The factorization that serves the shift also *certifies* the count: the number of
negative eigenvalues of Q(iω_s) equals the number of frequencies in (0, ω_s) (each
eigenvalue of Q(iω) crosses zero only downwards when K > 0, with slope −(ω²m + κ)/ω). The
automatic shift lies below the lowest frequency, where Q(iω_s) is positive definite: a
Cholesky factorization (CHOLMOD, :mod:`gyroshell.cholesky`, where cvxopt is installed)
proves the count zero by succeeding; otherwise, or where it fails, SuperLU's LDLᴴ counts
the negative pivots (Sylvester).

*Undamped, K indefinite* (above critical), and *damped*. No Hermitian structure and no
certificate: ARPACK (``eigs``) on the linearization A z = λ B z, A = [[0, I], [−K, −G − C]],
B = diag(I, M), in shift-invert form through one factorization of Q(σ) = K + σ(G + C) + σ²M:

    z₁ = −Q(σ)⁻¹ (M u₂ + (G + C + σM) u₁),   z₂ = u₁ + σ z₁,   λ = σ + 1/θ,

on the scaled state [ω_r m^½ z₁; m^½ z₂] (m the diagonal of M), whose Euclidean norm is close
to the energy norm.

Each eigenvalue is finally polished with the quadratic Rayleigh functional (the root of
m λ² + g λ + κ = 0, m = φᴴMφ, g = φᴴ(G + C)φ, κ = φᴴKφ, nearest to it) and every pair's
backward error is checked.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..core.errors import ConvergenceError, ParameterError, SingularError
from ..core.parallel import blas_threads
from . import cholesky as _cholesky
from .inertia import InertiaFactor, factor_inertia

#: Default relative tolerance of the eigen-iteration (on 1/(λ − σ)).
DEFAULT_TOL = 1e-10
#: Largest accepted relative residual (backward error) of a returned eigenpair.
RESIDUAL_LIMIT = 1e-6
#: Largest |Re λ| / |λ| accepted for an undamped eigenvalue below critical (a ±iω pair).
PAIR_DEFECT_LIMIT = 1e-6
#: Relative size of Re λ (or Im λ) below which it counts as zero when classifying.
STABILITY_RTOL = 1e-9
#: Relative symmetry defect ‖A − Aᵀ‖₁ / ‖A‖₁ accepted for M, K, C (and skewness for G).
STRUCTURE_RTOL = 1e-10
#: Stability labels, in the order of precedence of :func:`classify_stability`.
STABILITY_LABELS = ("divergence", "flutter", "stable")
#: Basis size of the Lanczos iteration: max(2 nev + LANCZOS_EXTRA, LANCZOS_MIN_BASIS).
LANCZOS_EXTRA = 10
LANCZOS_MIN_BASIS = 32
#: A second Gram-Schmidt pass is made when the first leaves less than this fraction of
#: the vector's norm (Daniel, Gragg, Kaufman and Stewart's criterion).
REORTHOGONALIZE = 0.7071
#: Thick restarts of the Lanczos iteration before falling back to ARPACK.
LANCZOS_RESTARTS = 30
#: Lanczos' Ritz values converge like the square of its vectors: testing the Ritz
#: residuals at this fraction of ``tol`` brings the eigenpairs' backward errors to round-off
#: (L_x/L_y = 19, V = 0/50/90 m/s: backward errors 1.3-1.7e-16 for 27/35/31 solves, against
#: 2.6-2.8e-14 for 24/32/27 testing at ``tol``), and never below LANCZOS_TOL_FLOOR.
LANCZOS_TOL_FACTOR = 1e-3
LANCZOS_TOL_FLOOR = 1e-15
#: Largest residual accepted from Lanczos before the ARPACK path is tried instead.
LANCZOS_RESIDUAL_LIMIT = 1e-10
#: Weight of the random part of a start vector built from previous modes.
WARM_START_NOISE = 1e-3
#: Extra eigenvalues asked for beyond those wanted, and how many times the request grows.
EXTRA_EIGENVALUES = 2
REQUEST_ATTEMPTS = 3
#: Fixed seed of the random start vector: reproducible results.
START_SEED = 12345


# ----- results --------------------------------------------------------------------------
class _EigenvalueProperties:
    """Derived quantities shared by :class:`GyroscopicModes` and the tape's ``Modes``."""

    eigenvalues: np.ndarray

    @property
    def count(self) -> int:
        return len(self.eigenvalues)

    @property
    def omega(self) -> np.ndarray:
        """Angular frequencies ω = |Im λ| (damped frequencies with damping), rad/s."""
        return np.abs(self.eigenvalues.imag)

    @property
    def frequency(self) -> np.ndarray:
        """Frequencies ω / 2π, Hz."""
        return self.omega / (2 * np.pi)

    @property
    def period(self) -> np.ndarray:
        """Periods 2π / ω, s (inf for a non-oscillating eigenvalue)."""
        with np.errstate(divide="ignore"):
            return np.where(self.omega > 0, 2 * np.pi / np.maximum(self.omega, 1e-300), np.inf)

    @property
    def growth_rate(self) -> np.ndarray:
        """max(Re λ, 0), 1/s: zero for stable modes, the divergence/flutter growth rate."""
        return np.maximum(self.eigenvalues.real, 0.0)

    @property
    def decay_rate(self) -> np.ndarray:
        """−Re λ, 1/s: positive for damped modes, zero undamped, negative if growing."""
        return -self.eigenvalues.real + 0.0   # + 0.0: no negative zero for undamped modes

    @property
    def damping_ratio(self) -> np.ndarray:
        """ζ = −Re λ / |λ| (dimensionless; 0 undamped, 1 critically damped)."""
        mag = np.abs(self.eigenvalues)
        return np.where(mag > 0, -self.eigenvalues.real / np.where(mag > 0, mag, 1.0), 0.0
                        ) + 0.0

    @property
    def stability(self) -> str:
        """``"stable"``, ``"divergence"`` or ``"flutter"`` (see :func:`classify_stability`)."""
        return classify_stability(self.eigenvalues)


@dataclass(frozen=True)
class GyroscopicModes(_EigenvalueProperties):
    """Eigenpairs of (λ²M + λ(G + C) + K) φ = 0 nearest the shift.

    Attributes
    ----------
    eigenvalues : numpy.ndarray
        λ, 1/s, one representative per conjugate pair (Im λ >= 0). Undamped below critical:
        +iω, ascending ω. Otherwise ascending Im λ (undamped supercritical: the eigenvalues
        nearest zero, with Re λ >= 0).
    vectors : numpy.ndarray
        Mode shapes φ, complex, shape (n, count), largest entry 1.
    residuals : numpy.ndarray
        ‖Q(λ)φ‖₂ / ((|λ|²‖M‖₁ + |λ|‖G + C‖₁ + ‖K‖₁) ‖φ‖₂) (backward errors).
    supercritical : bool
        True if K is not positive definite (for the tape: V at or above critical).
    damped : bool
        True if a damping matrix C was given (the count certificate does not apply).
    info : dict
        Diagnostics: ``method`` ("lanczos" or "arpack"), ``shift`` σ (1/s), ``below_shift``
        (certified number of frequencies below the shift, None without certificate),
        ``factor_time``, ``solve_time`` (s), ``operator_applications``, ``pair_defect``,
        ``max_residual`` and method details.
    """

    eigenvalues: np.ndarray
    vectors: np.ndarray
    residuals: np.ndarray
    supercritical: bool = False
    damped: bool = False
    info: dict = field(default_factory=dict, compare=False)


def classify_stability(eigenvalues: np.ndarray, *, rtol: float = STABILITY_RTOL) -> str:
    """Stability of a motion from its eigenvalues λ (1/s).

    ``"divergence"`` if some real eigenvalue is positive (static buckling: the motion grows
    without oscillating), else ``"flutter"`` if some complex eigenvalue has a positive real
    part (growing oscillation), else ``"stable"`` (all on the imaginary axis or in the left
    half-plane: an undamped gyroscopic system above its critical speed can be stable this way,
    *gyroscopically stabilized*, although K is indefinite). A part smaller than ``rtol``·|λ|
    counts as zero. Only the eigenvalues given are judged (for a solver's result: those
    nearest its shift).

    Examples
    --------
    >>> classify_stability([125e3j, -125e3j])
    'stable'
    >>> classify_stability([2.3e4 + 0j, 1.5e4j])
    'divergence'
    >>> classify_stability([8e2 + 7.9e2j, 8e2 - 7.9e2j])
    'flutter'
    """
    lam = np.asarray(list(eigenvalues) if not isinstance(eigenvalues, np.ndarray)
                     else eigenvalues, dtype=complex).ravel()
    if lam.size == 0:
        raise ParameterError("classify_stability needs at least one eigenvalue")
    if not np.all(np.isfinite(lam)):
        raise ParameterError("eigenvalues must be finite")
    mag = np.abs(lam)
    growing = lam.real > rtol * mag
    real = np.abs(lam.imag) <= rtol * mag
    if np.any(growing & real):
        return "divergence"
    if np.any(growing):
        return "flutter"
    return "stable"


# ----- structure checks -----------------------------------------------------------------
def _norm1(matrix: sp.spmatrix) -> float:
    return float(abs(matrix).sum(axis=0).max()) if matrix.nnz else 0.0


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
    defect = _norm1(matrix - sign * matrix.T)
    scale = _norm1(matrix)
    if defect > STRUCTURE_RTOL * scale:
        raise ParameterError(
            f"{name} must be {what}: ‖{name} {'-' if sign > 0 else '+'} {name}ᵀ‖₁ / ‖{name}‖₁ = "
            f"{defect / scale:.1e} > {STRUCTURE_RTOL:g}")


def check_structure(M, G, K, C=None) -> tuple[sp.csr_matrix, ...]:
    """Validated sparse M, G, K, C (C None if absent), or a ParameterError naming the flaw.

    M symmetric positive definite, G skew-symmetric, K symmetric, C symmetric positive
    semi-definite; all real, square, finite and of one size.
    """
    M = _as_sparse("M", M, None)
    n = M.shape[0]
    G = _as_sparse("G", G, n)
    K = _as_sparse("K", K, n)
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


def _is_diagonal(matrix: sp.csr_matrix) -> bool:
    coo = matrix.tocoo()
    return bool(np.all(coo.row == coo.col))


def _positive_definite(M: sp.csr_matrix) -> bool:
    if _is_diagonal(M):
        d = M.diagonal()
        return bool(np.all(d > 0))
    return factor_inertia(M).definite


def _positive_semidefinite(C: sp.csr_matrix) -> bool:
    if _is_diagonal(C):
        return bool(np.all(C.diagonal() >= 0))
    # C + εI > 0 for every ε > 0 exactly when C >= 0; ε relative to ‖C‖ allows round-off.
    eps = 1e-12 * _norm1(C)
    return factor_inertia(C + eps * sp.identity(C.shape[0])).definite


def check_count(count: int, n: int) -> int:
    """1 <= count <= the most a Krylov eigen-solver delivers in reasonable time here."""
    if isinstance(count, bool) or not isinstance(count, (int, np.integer, float)) or \
            int(count) != count:
        raise ParameterError(f"count must be an integer, got {count!r}")
    count = int(count)
    limit = max_count(n)
    if not 1 <= count <= limit:
        raise ParameterError(f"count must be in [1, {limit}] for {n} unknowns, got {count}")
    return count


#: Most eigenpairs one sparse call computes: the Krylov basis (about 2·count + 10 vectors
#: of length 2n, twice) and its orthogonalization grow with the count; beyond it, use
#: several shifts.
MAX_COUNT = 50
#: Up to this many unknowns the problem is solved densely (every eigenvalue, LAPACK).
DENSE_LIMIT = 40


def max_count(n: int) -> int:
    """Largest ``count`` accepted for n unknowns: n when solved densely (n <= DENSE_LIMIT),
    else min(MAX_COUNT, n/2 − 1)."""
    if n <= DENSE_LIMIT:
        return n
    return max(1, min(MAX_COUNT, n // 2 - 1))


def _check_optional_int(name: str, value) -> int | None:
    """None or an integer >= 1 (ARPACK's ncv and maxiter)."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise ParameterError(f"{name} must be None or an integer >= 1, got {value!r}")
    return int(value)


def _check_tol(tol) -> float:
    if isinstance(tol, bool) or not isinstance(tol, (int, float, np.floating)) or \
            not 0 <= tol < 1:
        raise ParameterError(f"tol must be in [0, 1), got {tol!r}")
    return float(tol)


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


# ----- shared numerical pieces -------------------------------------------------------------
def _product(A, X: np.ndarray) -> np.ndarray:
    """A X; a real sparse A times complex X as a real product on X's real and imaginary
    parts side by side (no complex copy of A)."""
    X = np.asarray(X)
    if not (sp.issparse(A) and np.iscomplexobj(X) and X.dtype == np.complex128
            and not np.iscomplexobj(A.data) and A.dtype == np.float64):
        return A @ X
    X = np.ascontiguousarray(X)
    shape = X.shape
    out = sp.csr_matrix(A) @ X.view(float).reshape(shape[0], -1)
    return np.ascontiguousarray(out).view(complex).reshape(shape)


def relative_residuals(M, D, K, eigenvalues: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """‖(λ²M + λD + K)φ‖₂ / ((|λ|²‖M‖₁ + |λ|‖D‖₁ + ‖K‖₁) ‖φ‖₂) per column (dimensionless).

    ``D`` is G + C (G alone undamped).
    """
    lam = np.asarray(eigenvalues)
    phi = np.asarray(vectors)
    r = _product(M, phi) * lam**2 + _product(D, phi) * lam + _product(K, phi)
    scale = np.abs(lam) ** 2 * _norm1(sp.csr_matrix(M)) + np.abs(lam) * _norm1(
        sp.csr_matrix(D)) + _norm1(sp.csr_matrix(K))
    return np.linalg.norm(r, axis=0) / (scale * np.linalg.norm(phi, axis=0))


def quadratic_rayleigh(M, D, K, eigenvalues: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """Roots of m λ² + g λ + κ = 0 (m = φᴴMφ, g = φᴴDφ, κ = φᴴKφ) nearest each λ, 1/s.

    The quadratic Rayleigh functional, column by column: second-order accurate in the error
    of φ. ``D`` is G + C.
    """
    phi = np.asarray(vectors)
    c = phi.conj()
    m = np.einsum("ij,ij->j", c, _product(M, phi))
    g = np.einsum("ij,ij->j", c, _product(D, phi))
    kap = np.einsum("ij,ij->j", c, _product(K, phi))
    disc = np.sqrt(g * g - 4 * m * kap + 0j)
    r1, r2 = (-g + disc) / (2 * m), (-g - disc) / (2 * m)
    lam = np.asarray(eigenvalues)
    return np.where(np.abs(r1 - lam) <= np.abs(r2 - lam), r1, r2)


def _normalize(phi: np.ndarray) -> np.ndarray:
    return phi / phi[np.argmax(np.abs(phi), axis=0), np.arange(phi.shape[1])]


def _random_start(n2: int, dtype) -> np.ndarray:
    return np.random.default_rng(START_SEED).standard_normal(n2).astype(dtype)


@dataclass
class _Problem:
    """Validated matrices and the options of one solve."""

    M: sp.csr_matrix
    G: sp.csr_matrix
    K: sp.csr_matrix
    C: sp.csr_matrix | None
    count: int
    tol: float
    ncv: int | None
    maxiter: int | None
    start: np.ndarray | None
    info: dict
    factorization: str = "superlu"
    factors: list = field(default_factory=list)

    def factor(self, matrix: sp.spmatrix) -> InertiaFactor | _cholesky.CholeskyFactor:
        """Factor a symmetric/Hermitian matrix: CHOLMOD's Cholesky when that back-end is
        selected and the matrix is positive definite (its success is the certificate: no
        negative eigenvalue), else SuperLU's LDLᴴ with its inertia count."""
        if self.factorization == "cholmod":
            factor = _cholesky.cholesky(matrix)
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
    def D(self) -> sp.csr_matrix:
        return self.G if self.C is None else self.G + self.C

    @property
    def mass_diagonal(self) -> np.ndarray:
        return self.M.diagonal()


# ----- the Hermitian (undamped, K > 0) path ---------------------------------------------------
def _hermitian_shift(prob: _Problem, estimate: float | None, shift: complex | None,
                     k_factor: InertiaFactor) -> tuple[float, InertiaFactor]:
    """ω_s and the certified factorization of Q(iω_s).

    An explicit shift is used as given. The automatic one sits SHIFT_MARGIN below the
    estimate, and moves down by the SHIFT_RETREAT fractions while the inertia shows more
    than ``count`` frequencies below it (the estimate was too high); without an estimate,
    or if that fails, ω_s = 0 (Q(0) = K, already factored).
    """
    if shift is not None:
        omega_s = shift.imag
    elif estimate is not None and estimate > 0 and math.isfinite(estimate):
        omega_s = estimate * (1 - SHIFT_MARGIN)
    else:
        return 0.0, k_factor or prob.factor(prob.K)
    if omega_s == 0:
        return 0.0, k_factor or prob.factor(prob.K)
    retreats = iter(SHIFT_RETREAT)
    tries = 0
    while True:
        tries += 1
        Q = prob.K - omega_s**2 * prob.M + 1j * omega_s * prob.G
        factor = prob.factor(Q)
        prob.info["shift_tries"] = tries
        if shift is not None:
            if factor.singular:
                raise ParameterError(f"sigma = {shift} is an eigenvalue (Q(sigma) is singular);"
                                     " move the shift")
            return omega_s, factor
        if factor.negatives is not None and factor.negatives <= prob.count:
            return omega_s, factor
        fraction = next(retreats, None)
        if fraction is None:  # the estimate is far off: shift at zero instead
            return 0.0, k_factor or prob.factor(prob.K)
        omega_s *= fraction


#: The automatic shift sits this fraction below the estimated lowest frequency.
SHIFT_MARGIN = 2e-4
#: Factors applied to the automatic shift while too many frequencies lie below it.
SHIFT_RETREAT = (0.98, 0.8)


class _EnergyOperator:
    """T = (H − ω_s L)⁻¹ L and the energy inner product on z = [λφ; φ] (module notes).

    G and K are copied to complex once: scipy multiplies a complex CSR matrix by a complex
    vector 1.7-2.6x faster than the real matrix by the vector's (n, 2) real view (measured
    at L_x/L_y = 19: 0.68 ms against 1.15-1.8 ms for K), and the copy (4 ms) pays back
    within a few steps; a diagonal M is applied as a vector. Work arrays are allocated once.
    """

    def __init__(self, prob: _Problem, omega_s: float, factor: InertiaFactor) -> None:
        self.G = prob.G.tocsr().astype(complex)
        self.K = prob.K.tocsr().astype(complex)
        self.md = prob.M.diagonal() if _is_diagonal(prob.M) else None
        self.M = prob.M.tocsr()
        self.omega_s, self.factor, self.n = omega_s, factor, prob.n
        self.applications = 0
        self.solve_time = 0.0
        self._rhs = np.empty(prob.n, dtype=complex)

    def mass(self, u: np.ndarray) -> np.ndarray:
        return self.md * u if self.md is not None else _product(self.M, u)

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


def _lanczos(op: _EnergyOperator, start: np.ndarray, wanted, nev: int, tol: float,
             ) -> tuple[np.ndarray, np.ndarray, int] | None:
    """Thick-restart Lanczos with full reorthogonalization in the energy inner product.

    ``wanted(theta)`` ranks Ritz values (larger first). Returns (θ, Ritz vectors as
    columns, restarts) for the ``nev`` best once each residual |β sₘ| <= tol·|θ|, or None if
    not converged within LANCZOS_RESTARTS restarts. The basis is stored by rows in a
    preallocated array. A step applies T once (with L T v_j as a by-product), removes the
    three-term (Lanczos) components along the last two basis vectors (most of T v_j),
    applies L once and makes one classical
    Gram-Schmidt pass over the whole basis (two matrix-vector products with it); the new
    vector's norm follows from Pythagoras, ‖w − Vh‖² = ‖w‖² − ‖h‖², and a second full pass
    is made only when the first cancelled most of w (DGKS). Without the three-term part
    first, nearly every step cancels and needs two full passes (measured ~20 % more
    overhead).
    """
    n2 = len(start)
    m = min(max(2 * nev + LANCZOS_EXTRA, LANCZOS_MIN_BASIS), n2 - 1)
    V = np.empty((m + 1, n2), dtype=complex)
    H = np.zeros((m + 1, m), dtype=complex)

    def energy(w: np.ndarray, Lw: np.ndarray) -> float:
        return math.sqrt(max(np.vdot(w, Lw).real, 0.0))

    def put(j: int, w: np.ndarray, norm: float) -> None:
        if norm > 0:
            np.multiply(w, 1.0 / norm, out=V[j])

    v = start.astype(complex)
    put(0, v, energy(v, op.weight(v)))

    def ritz(size: int):
        Hs = H[:size, :size]
        theta, S = la.eigh(0.5 * (Hs + Hs.conj().T))
        order = np.argsort(-wanted(theta), kind="stable")
        resid = np.abs(H[size, size - 1] * S[size - 1, :])
        best = order[:nev]
        return theta, S, order, bool(np.all(resid[best] <= tol * np.abs(theta[best])))

    kept = 0  # Ritz vectors kept at the front after a restart
    for restart in range(LANCZOS_RESTARTS + 1):
        for j in range(kept, m):
            w, Lw = op.apply(V[j])
            size = energy(w, Lw)
            basis = V[: j + 1]
            beta = 0.0
            if j - 1 > kept:  # the three-term part first: the rest is then small
                local = V[j - 1: j + 1]
                h = np.conj(local @ np.conj(Lw))
                w -= h @ local
                H[j - 1: j + 1, j] += h
                Lw = op.weight(w)
                size = energy(w, Lw)
            for _ in range(2):  # classical Gram-Schmidt, repeated if it cancelled (DGKS)
                h = np.conj(basis @ np.conj(Lw))
                w -= h @ basis
                H[: j + 1, j] += h
                left2 = size * size - float(np.vdot(h, h).real)
                if left2 > (REORTHOGONALIZE * size) ** 2:
                    beta = math.sqrt(left2)
                    break
                Lw = op.weight(w)
                size = beta = energy(w, Lw)
            put(j + 1, w, beta)
            H[j + 1, j] = beta
            if beta == 0.0:  # an invariant subspace: continue from a fresh direction
                w = _random_start(n2, complex)
                for _ in range(2):
                    w -= np.conj(basis @ np.conj(op.weight(w))) @ basis
                put(j + 1, w, energy(w, op.weight(w)))
            if j + 1 >= nev + EXTRA_EIGENVALUES or j == m - 1:
                theta, S, order, done = ritz(j + 1)
                if done:
                    best = order[:nev]
                    return theta[best], (S[:, best].T @ V[: j + 1]).T, restart
        # keep the wanted Ritz vectors plus some more, and the residual direction
        kept = min(nev + (m - nev) // 2, m - 1)
        keep = order[:kept]
        coupling = H[m, m - 1] * S[m - 1, keep]
        V[:kept] = S[:, keep].T @ V[:m]
        V[kept] = V[m]
        # T Y = Y Θ + v (β sₘ)ᵀ: an arrowhead; column `kept` is filled by the next step
        H[:] = 0.0
        H[np.arange(kept), np.arange(kept)] = theta[keep]
        H[kept, :kept] = coupling
    return None


def _solve_hermitian(prob: _Problem, omega_s: float, factor: InertiaFactor, below: int
                     ) -> tuple[np.ndarray, np.ndarray] | None:
    """The undamped subcritical eigenpairs by Lanczos on T; None if it did not converge."""
    op = _EnergyOperator(prob, omega_s, factor)
    n, count = prob.n, prob.count
    # with ω_s = 0 the ±ω pairs are equally near the shift: ask for both members
    nev = min(count + below + (count if omega_s == 0 else 0), 2 * n - 2)
    start = _start_vector(prob)

    def wanted(theta):  # nearest the shift among positive frequencies
        with np.errstate(divide="ignore"):
            omega = omega_s + 1.0 / theta
        return np.where(omega > 0, np.abs(theta), -np.abs(theta))

    t0 = time.perf_counter()
    tol = max(prob.tol * LANCZOS_TOL_FACTOR, LANCZOS_TOL_FLOOR)
    out = _lanczos(op, start, wanted, nev, tol)
    prob.info.update(method="lanczos", solve_time=time.perf_counter() - t0,
                     substitution_time=op.solve_time, operator_applications=op.applications)
    if out is None:
        return None
    theta, Z, restarts = out
    prob.info.update(restarts=restarts, nev=nev)
    omega = omega_s + 1.0 / theta
    keep = np.flatnonzero(omega > 0)
    keep = keep[np.argsort(omega[keep])]
    found_below = int(np.count_nonzero(omega[keep] < omega_s))
    if found_below < below or len(keep) < count:
        return None
    keep = keep[:count]
    lams, vecs = 1j * omega[keep], Z[n:, keep]
    # Near a critical point K is nearly singular and the energy norm degenerates: the
    # Ritz pairs may then be less accurate than their Lanczos residuals say.
    res = relative_residuals(prob.M, prob.G, prob.K, lams, vecs)
    prob.info["lanczos_residual"] = float(res.max())
    if res.max() > LANCZOS_RESIDUAL_LIMIT:
        return None
    return lams, vecs


def _start_vector(prob: _Problem) -> np.ndarray:
    """z = [λφ; φ] summed over previous modes (warm start) plus a little noise, or random."""
    n = prob.n
    noise = _random_start(2 * n, float).astype(complex)
    if prob.start is None:
        return noise
    lam, phi = prob.start
    Z = np.concatenate([phi * lam, phi])
    z = Z.sum(axis=1)
    scale = np.linalg.norm(z) / math.sqrt(2 * n)
    return z + WARM_START_NOISE * scale * noise


# ----- the general (ARPACK) path ------------------------------------------------------------
def _arpack(op: spla.LinearOperator, nev: int, *, tol: float, ncv: int | None,
            maxiter: int | None, v0: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    n2 = op.shape[0]
    ncv = min(n2 - 1, max(2 * nev + 1, nev + 20)) if ncv is None else ncv
    if not nev + 1 < ncv <= n2:
        raise ParameterError(f"ncv must be in ({nev + 1}, {n2}] for {nev} eigenvalues, "
                             f"got {ncv}")
    try:
        theta, vecs = spla.eigs(op, k=nev, which="LM", tol=tol, ncv=ncv, maxiter=maxiter,
                                v0=v0)
    except spla.ArpackNoConvergence as exc:
        raise ConvergenceError(
            f"ARPACK found only {len(exc.eigenvalues)} of {nev} eigenvalues "
            f"(ncv={ncv}, tol={tol:g}); try a larger ncv, a looser tol or fewer modes"
        ) from None
    except spla.ArpackError as exc:
        raise ConvergenceError(f"ARPACK failed ({exc}); try a larger ncv or fewer modes"
                               ) from None
    return theta, vecs, ncv


def _linearized_operator(prob: _Problem, solve, sigma: complex, omega_ref: float,
                         counter: list[int]) -> spla.LinearOperator:
    """(A − σB)⁻¹B on the scaled state y = [ω_r m^½ z₁; m^½ z₂]."""
    n = prob.n
    sm = np.sqrt(prob.mass_diagonal)
    M, D = prob.M, prob.D
    dtype = complex if sigma.imag != 0 else float
    sigma = sigma if dtype is complex else sigma.real

    def matvec(y: np.ndarray) -> np.ndarray:
        counter[0] += 1
        y = np.asarray(y).ravel()
        u1 = y[:n] / (omega_ref * sm)
        u2 = y[n:] / sm
        z1 = -solve(M @ u2 + D @ u1 + sigma * (M @ u1))
        z2 = u1 + sigma * z1
        return np.concatenate([omega_ref * sm * z1, sm * z2])

    return spla.LinearOperator((2 * n, 2 * n), matvec=matvec, dtype=dtype)


def _representatives(lam: np.ndarray, phi: np.ndarray, *, right_half: bool
                     ) -> tuple[np.ndarray, np.ndarray]:
    """One member per conjugate pair (Im λ >= 0, from λ̄, φ̄ where needed), duplicates
    dropped, ascending |λ|; ``right_half`` also drops Re λ < 0 (undamped: −λ̄ is there too,
    but its right eigenvector is not at hand)."""
    lam, phi = lam.copy(), phi.astype(complex)
    low = lam.imag < 0
    lam[low], phi[:, low] = np.conj(lam[low]), np.conj(phi[:, low])
    tiny = STABILITY_RTOL * np.abs(lam)
    chosen: list[int] = []
    for j in np.argsort(np.abs(lam), kind="stable"):
        if right_half and lam[j].real < -tiny[j]:
            continue
        if all(abs(lam[j] - lam[i]) > 1e-8 * abs(lam[j]) for i in chosen):
            chosen.append(int(j))
    sel = np.array(chosen, dtype=int)
    return lam[sel], phi[:, sel]


def _solve_general(prob: _Problem, sigma: complex, solve, omega_ref: float, *,
                   symmetric_pairs: bool, imaginary_pairs: bool = False
                   ) -> tuple[np.ndarray, np.ndarray]:
    """ARPACK nearest σ; one representative per pair. ``symmetric_pairs``: undamped
    supercritical, where λ, −λ, λ̄, −λ̄ come together (Re λ >= 0 representative).
    ``imaginary_pairs``: undamped below critical, every λ = ±iω; the +iω are kept by the
    sign of Im λ alone (an eigenvalue near zero has a real part of round-off size relative
    to the others, not to itself), ascending."""
    n, count = prob.n, prob.count
    counter = [0]
    op = _linearized_operator(prob, solve, sigma, omega_ref, counter)
    real = sigma == 0
    extra = EXTRA_EIGENVALUES
    t0 = time.perf_counter()
    for attempt in range(1, REQUEST_ATTEMPTS + 1):  # noqa: B007 - reported in info
        nev = min((2 * count if real else count) + extra, 2 * n - 2)
        theta, y, used = _arpack(op, nev, tol=prob.tol, ncv=prob.ncv, maxiter=prob.maxiter,
                                 v0=_random_start(2 * n, float if real else complex))
        lam = sigma + 1.0 / theta
        phi = y[:n] / (omega_ref * np.sqrt(prob.mass_diagonal))[:, None]
        lam = quadratic_rayleigh(prob.M, prob.D, prob.K, lam, phi)
        if imaginary_pairs:
            up = np.flatnonzero(lam.imag > 0)
            up = up[np.argsort(lam.imag[up])]
            reps, vecs = lam[up], phi[:, up]
        else:
            reps, vecs = _representatives(lam, phi, right_half=symmetric_pairs)
        if len(reps) >= count or nev == 2 * n - 2:
            break
        extra = 2 * extra + 2 * (count - len(reps))
    prob.info.update(method="arpack", solve_time=time.perf_counter() - t0, ncv=used,
                     nev=nev, attempts=attempt, operator_applications=counter[0])
    if not (symmetric_pairs or imaginary_pairs):  # damped: ascending damped frequency
        order = np.lexsort((np.abs(reps), np.abs(reps.imag)))
        reps, vecs = reps[order], vecs[:, order]
    lams, vecs = reps[:count], vecs[:, :count]
    if symmetric_pairs:
        lams = _clean_parts(lams)
    return lams, vecs


def _clean_parts(lams: np.ndarray) -> np.ndarray:
    """Undamped representatives (Re, Im >= 0): parts at round-off level set to zero, so a
    gyroscopically stable eigenvalue is exactly imaginary and a divergent one exactly real."""
    lams = np.where(lams.real < STABILITY_RTOL * np.abs(lams), 1j * lams.imag, lams)
    return np.where(lams.imag < STABILITY_RTOL * np.abs(lams), lams.real + 0j, lams)


def _solve_pairs_real(prob: _Problem, factor: InertiaFactor, omega_ref: float
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Undamped, K > 0, σ = 0 by ARPACK: 2·count eigenvalues, checked as ±iω pairs."""
    return _solve_general(prob, 0j, factor.solve, omega_ref, symmetric_pairs=False,
                          imaginary_pairs=True)


# ----- the solver -----------------------------------------------------------------------------
def gyroscopic_modes(M, G, K, count: int = 6, *, sigma: complex | str | None = None,
                     C=None, estimate: float | None = None, definite: bool | None = None,
                     tol: float = DEFAULT_TOL, ncv: int | None = None,
                     maxiter: int | None = None, start=None,
                     method: str = "auto", factorization: str = "auto") -> GyroscopicModes:
    """Eigenpairs of (λ²M + λ(G + C) + K) φ = 0 nearest a shift on the imaginary axis.

    Parameters
    ----------
    M, G, K : array_like or scipy.sparse matrix, shape (n, n)
        Mass (symmetric positive definite, kg), gyroscopic (skew-symmetric, kg/s) and
        stiffness (symmetric, N/m) matrices. Checked and refused otherwise.
    count : int
        Number of eigenvalue pairs, 1 <= count <= :func:`max_count` (n).
    sigma : None, "auto", 0 or complex i·ω_s
        Shift, 1/s. None/"auto": i·ω_s just below ``estimate`` (moved down until the inertia
        of Q(iω_s) certifies at most ``count`` frequencies below it), or 0 without one.
    C : array_like or sparse matrix, optional
        Viscous damping, symmetric positive semi-definite, kg/s.
    estimate : float, optional
        Estimate of the lowest frequency, rad/s (undamped) or of the damped one.
    definite : bool, optional
        Whether K is known positive definite (skips its factorization); None: find out.
    tol : float
        Relative tolerance of the eigen-iteration.
    ncv, maxiter : int, optional
        ARPACK's basis size and restarts; giving either selects ARPACK.
    start : tuple (eigenvalues, vectors), optional
        Previous eigenpairs (e.g. at a nearby speed) to start from.
    method : {"auto", "lanczos", "arpack"}
        Eigen-iteration for the undamped subcritical case ("auto": Lanczos, ARPACK if it
        does not converge or if ncv/maxiter are given). The other cases use ARPACK.
    factorization : {"auto", "cholmod", "superlu"}
        Factorization of the shift matrices Q(iω_s) and K. "cholmod": CHOLMOD's supernodal
        Cholesky (cvxopt, the ``fast`` extra) wherever the matrix is positive definite,
        its symbolic analysis reused across calls with the same pattern; SuperLU's LDLᴴ
        otherwise and where the inertia count is needed. "superlu": SuperLU only (pure
        scipy). "auto": "cholmod" if cvxopt is installed.

    Returns
    -------
    GyroscopicModes

    Raises
    ------
    ParameterError
        Matrices without the structure, bad count, sigma or tol, a singular K at σ = 0.
    ConvergenceError
        The eigen-iteration did not converge, or residuals or the certified count failed.
    """
    # Out-of-range scales surface as non-finite results, refused in _finish; no warnings.
    with blas_threads(1), np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        return _gyroscopic_modes(M, G, K, count, sigma=sigma, C=C, estimate=estimate,
                                 definite=definite, tol=tol, ncv=ncv, maxiter=maxiter,
                                 start=start, method=method,
                                 factorization=check_factorization(factorization))


def _gyroscopic_modes(M, G, K, count, *, sigma, C, estimate, definite, tol, ncv, maxiter,
                      start, method, factorization) -> GyroscopicModes:
    M, G, K, C = check_structure(M, G, K, C)
    prob = _Problem(M, G, K, C, check_count(count, M.shape[0]), _check_tol(tol),
                    _check_optional_int("ncv", ncv), _check_optional_int("maxiter", maxiter),
                    _check_start(start, M.shape[0]), {"operator_applications": 0})
    shift = check_shift(sigma)
    if method not in ("auto", "lanczos", "arpack"):
        raise ParameterError(f"method must be 'auto', 'lanczos' or 'arpack', got {method!r}")
    if prob.n <= DENSE_LIMIT:
        return _solve_dense(prob, shift, definite)
    prob.factorization = _resolve_factorization(factorization)
    prob.info["factorization"] = prob.factorization
    try:
        return _solve_sparse(prob, shift, estimate, definite, method)
    except ConvergenceError:
        if prob.factorization != "cholmod":
            raise
        # A Cholesky that succeeds on a K(V) singular to working precision (at a critical
        # point) does not prove K > 0 as robustly as SuperLU's pivots count negative
        # eigenvalues: such a case is solved again with SuperLU throughout.
        prob.release()
        prob.factorization = "superlu"
        prob.info.clear()
        prob.info.update(operator_applications=0, factorization="superlu",
                         cholmod_fallback=True)
        return _solve_sparse(prob, shift, estimate, definite, method)
    finally:
        prob.release()


def _solve_sparse(prob: _Problem, shift, estimate, definite, method) -> GyroscopicModes:
    C = prob.C
    t0 = time.perf_counter()
    k_factor = _factor_stiffness(prob, definite, need=C is not None or shift == 0 or (
        shift is None and estimate is None))
    prob.info["factor_time"] = time.perf_counter() - t0
    if C is not None:
        lams, vecs = _damped(prob, shift, estimate, k_factor)
        return _finish(prob, lams, vecs, supercritical=not _k_definite(k_factor, definite),
                       damped=True)
    if not _k_definite(k_factor, definite):
        lams, vecs = _supercritical(prob, k_factor, estimate)
        return _finish(prob, lams, vecs, supercritical=True, damped=False)
    lams, vecs = _subcritical(prob, shift, estimate, k_factor, method)
    return _finish(prob, lams, vecs, supercritical=False, damped=False)


def check_factorization(factorization) -> str:
    """One of :data:`gyroshell.cholesky.BACKENDS`; "cholmod" only where cvxopt is installed."""
    if factorization not in _cholesky.BACKENDS:
        raise ParameterError(f"factorization must be one of {', '.join(_cholesky.BACKENDS)}, "
                             f"got {factorization!r}")
    if factorization == "cholmod" and not _cholesky.available():
        raise ParameterError("factorization 'cholmod' needs cvxopt "
                             "(pip install 'gyroshell[fast]'); use 'superlu' or 'auto'")
    return factorization


def _resolve_factorization(factorization: str) -> str:
    """"auto": CHOLMOD where installed (measured faster: module notes of gyroshell.cholesky),
    else SuperLU."""
    if factorization == "auto":
        return "cholmod" if _cholesky.available() else "superlu"
    return factorization


def _solve_dense(prob: _Problem, shift: complex | None, definite: bool | None
                 ) -> GyroscopicModes:
    """Small problems: every eigenvalue of the 2n linearization by LAPACK, then the same
    selection as the sparse paths."""
    n, count = prob.n, prob.count
    M, D, K = (x.toarray() for x in (prob.M, prob.D, prob.K))
    eye, zero = np.eye(n), np.zeros((n, n))
    A = np.block([[zero, eye], [-K, -D]])
    B = np.block([[eye, zero], [zero, M]])
    t0 = time.perf_counter()
    lam, Z = la.eig(A, B)
    prob.info.update(method="dense", solve_time=time.perf_counter() - t0, factor_time=0.0)
    phi = Z[:n]
    if definite is None:
        definite = bool(np.all(la.eigvalsh(K) > 0))
    damped = prob.C is not None
    omega_s = 0.0 if shift is None else shift.imag
    if not damped and definite:
        lam = quadratic_rayleigh(prob.M, prob.D, prob.K, lam, phi)
        up = np.flatnonzero(lam.imag > 0)
        up = up[np.argsort(lam.imag[up])][:count]
        prob.info.update(shift=1j * omega_s, below_shift=int(np.count_nonzero(
            lam.imag[lam.imag > 0] < omega_s)))
        prob.info["pair_defect"] = float(np.max(np.abs(lam[up].real) / np.abs(lam[up])))
        lams, vecs = 1j * lam[up].imag, phi[:, up]
    else:
        reps, vecs = _representatives(lam, phi, right_half=not damped)
        if damped:
            order = np.lexsort((np.abs(reps), np.abs(reps.imag)))
            reps, vecs = reps[order], vecs[:, order]
        lams, vecs = reps[:count], vecs[:, :count]
        if not damped:
            lams = _clean_parts(lams)
        prob.info.update(shift=1j * omega_s, below_shift=None)
    return _finish(prob, lams, vecs, supercritical=not definite, damped=damped)


def _check_start(start, n: int):
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


def _factor_stiffness(prob: _Problem, definite: bool | None, *, need: bool
                      ) -> InertiaFactor | None:
    if definite is True and not need:
        return None
    return prob.factor(prob.K)


def _k_definite(k_factor: InertiaFactor | None, definite: bool | None) -> bool:
    if definite is not None:
        return definite
    return k_factor is not None and k_factor.definite


def _omega_ref(prob: _Problem, estimate: float | None) -> float:
    """A frequency scale for the state scaling, rad/s: the estimate, else √(‖K‖/‖M‖)."""
    if estimate is not None and estimate > 0 and math.isfinite(estimate):
        return float(estimate)
    ratio = _norm1(prob.K) / max(_norm1(prob.M), 1e-300)
    return math.sqrt(ratio) if ratio > 0 else 1.0


def _require_solvable(factor: InertiaFactor, what: str) -> None:
    if factor is None or factor.singular:
        raise SingularError(f"{what} is singular: λ = 0 is an eigenvalue (the system is "
                             "exactly at a critical point); change a parameter slightly")


def _subcritical(prob, shift, estimate, k_factor, method):
    """K > 0, undamped: certified shift, Lanczos on the energy pencil (ARPACK fallback)."""
    t0 = time.perf_counter()
    omega_s, factor = _hermitian_shift(prob, estimate, shift, k_factor)
    prob.info["factor_time"] += time.perf_counter() - t0
    below = factor.negatives
    prob.info.update(shift=1j * omega_s, below_shift=below)
    if below is None:  # no certificate (SuperLU pivoted): still solvable, count unchecked
        below = 0
    _require_solvable(factor, "K")
    use_arpack = method == "arpack" or (method == "auto" and (prob.ncv is not None or
                                                              prob.maxiter is not None))
    result = None if use_arpack else _solve_hermitian(prob, omega_s, factor, below)
    if result is None:
        if method == "lanczos":
            raise ConvergenceError("Lanczos did not converge; try method='arpack'")
        if omega_s == 0:
            result = _solve_pairs_real(prob, factor, _omega_ref(prob, estimate))
        else:
            result = _solve_shifted_pairs(prob, omega_s, factor, below,
                                          _omega_ref(prob, omega_s))
    lams, vecs = result
    lams = quadratic_rayleigh(prob.M, prob.G, prob.K, lams, vecs)
    scale = np.maximum(np.abs(lams), omega_s or _omega_ref(prob, estimate))
    prob.info["pair_defect"] = float(np.max(np.abs(lams.real) / scale))
    if prob.info["pair_defect"] > PAIR_DEFECT_LIMIT:
        raise ConvergenceError(f"eigenvalues off the imaginary axis below critical "
                               f"(|Re λ|/|λ| = {prob.info['pair_defect']:.1e}); "
                               "try a larger ncv or a smaller tol")
    return 1j * np.abs(lams.imag), vecs


def _solve_shifted_pairs(prob, omega_s, factor, below, omega_ref):
    """ARPACK about iω_s: the certified ``below`` frequencies and the next ones above."""
    n, count = prob.n, prob.count
    sigma = 1j * omega_s
    counter = [0]
    op = _linearized_operator(prob, factor.solve, sigma, omega_ref, counter)
    extra = EXTRA_EIGENVALUES
    t0 = time.perf_counter()
    for attempt in range(1, REQUEST_ATTEMPTS + 1):  # noqa: B007 - reported in info
        nev = min(count + below + extra, 2 * n - 2)
        theta, y, used = _arpack(op, nev, tol=prob.tol, ncv=prob.ncv, maxiter=prob.maxiter,
                                 v0=_random_start(2 * n, complex))
        lam = sigma + 1.0 / theta
        phi = y[:n] / (omega_ref * np.sqrt(prob.mass_diagonal))[:, None]
        lam = quadratic_rayleigh(prob.M, prob.G, prob.K, lam, phi)
        pos = np.flatnonzero(lam.imag > 0)
        pos = pos[np.argsort(lam.imag[pos])]
        found_below = int(np.count_nonzero(lam.imag[pos] < omega_s))
        if len(pos) >= count and found_below >= below:
            break
        extra = 2 * extra + (count - len(pos)) + (below - found_below)
    else:
        raise ConvergenceError(
            f"found {found_below} of the {below} frequencies certified below the shift "
            f"{omega_s:.6g} rad/s; try sigma=0 or a larger ncv")
    prob.info.update(method="arpack", solve_time=time.perf_counter() - t0, ncv=used, nev=nev,
                     attempts=attempt, operator_applications=counter[0])
    sel = pos[:count]
    return lam[sel], phi[:, sel]


def _supercritical(prob, k_factor, estimate):
    """K indefinite, undamped: the eigenvalues nearest zero by ARPACK about σ = 0."""
    _require_solvable(k_factor, "K")
    prob.info.update(shift=0j, below_shift=None)
    lams, vecs = _solve_general(prob, 0j, k_factor.solve, _omega_ref(prob, estimate),
                                symmetric_pairs=True)
    prob.info["growing"] = int(np.count_nonzero(lams.real > 0))
    return lams, vecs


def _damped(prob, shift, estimate, k_factor):
    """Damped: ARPACK about σ = iω_s (general LU of Q(σ)) or σ = 0; no count certificate."""
    if shift is None:
        omega_s = estimate * (1 - SHIFT_MARGIN) if estimate and math.isfinite(estimate) \
            and estimate > 0 else 0.0
    else:
        omega_s = shift.imag
    prob.info.update(shift=1j * omega_s, below_shift=None)
    if omega_s == 0:
        _require_solvable(k_factor, "K")
        solve = k_factor.solve
    else:
        t0 = time.perf_counter()
        Q = (prob.K + 1j * omega_s * prob.D - omega_s**2 * prob.M).tocsc()
        try:
            lu = spla.splu(Q, permc_spec="MMD_AT_PLUS_A")
        except RuntimeError:
            raise ParameterError(f"the shift i*{omega_s:g} rad/s is an eigenvalue; "
                                 "move the shift") from None
        prob.info["factor_time"] += time.perf_counter() - t0
        solve = lu.solve
    return _solve_general(prob, 1j * omega_s, solve, _omega_ref(prob, estimate or omega_s),
                          symmetric_pairs=False)


def _finish(prob: _Problem, lams, vecs, *, supercritical: bool, damped: bool
            ) -> GyroscopicModes:
    with np.errstate(all="ignore"):  # overflow is reported below, not as a warning
        vecs = _normalize(np.asarray(vecs, dtype=complex))
        if damped:
            lams = quadratic_rayleigh(prob.M, prob.D, prob.K, lams, vecs)
        res = relative_residuals(prob.M, prob.D, prob.K, lams, vecs)
    if not (np.all(np.isfinite(lams)) and np.all(np.isfinite(res))):
        raise ConvergenceError("eigenvalues out of floating-point range: the matrices' "
                               "scales (stiffness, damping, mass) are too far apart")
    prob.info["max_residual"] = float(res.max())
    if res.max() > RESIDUAL_LIMIT:
        raise ConvergenceError(
            f"eigenpairs not accurate: largest relative residual {res.max():.2e} > "
            f"{RESIDUAL_LIMIT:g}; try a larger ncv or a smaller tol")
    return GyroscopicModes(np.asarray(lams, dtype=complex), vecs, res, supercritical, damped,
                           prob.info)
