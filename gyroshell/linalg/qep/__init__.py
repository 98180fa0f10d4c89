"""Gyroscopic quadratic eigenproblem (λ²M + λ(G + C) + K) φ = 0 for any sparse matrices.

M symmetric positive definite, G skew-symmetric, K symmetric, C (optional viscous damping)
symmetric positive semi-definite. :func:`solve_qep` returns the eigenvalues nearest a shift
on the imaginary axis as plain arrays; :func:`gyroshell.gyroscopic_modes` wraps them in a
result, and the tape's :func:`gyroshell.modes` is a thin layer on that.

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
Cholesky factorization (CHOLMOD, :mod:`gyroshell.linalg.cholesky`, where cvxopt is installed)
proves the count zero by succeeding; otherwise, or where it fails, SuperLU's LDLᴴ counts
the negative pivots (Sylvester). A caller that already counted at its shift (the mirror
halves' count, :mod:`gyroshell.engines.eigen`) passes that factorization on
(``solve_qep(..., shift_factor=)``) and no second one is made.

*Undamped, K indefinite* (above critical), and *damped*. No Hermitian structure and no
certificate: ARPACK (``eigs``) on the linearization A z = λ B z, A = [[0, I], [−K, −G − C]],
B = diag(I, M), in shift-invert form through one factorization of Q(σ) = K + σ(G + C) + σ²M:

    z₁ = −Q(σ)⁻¹ (M u₂ + (G + C + σM) u₁),   z₂ = u₁ + σ z₁,   λ = σ + 1/θ,

on the scaled state [ω_r m^½ z₁; m^½ z₂] (m the diagonal of M), whose Euclidean norm is close
to the energy norm.

Each eigenvalue is finally polished with the quadratic Rayleigh functional (the root of
m λ² + g λ + κ = 0, m = φᴴMφ, g = φᴴ(G + C)φ, κ = φᴴKφ, nearest to it) and every pair's
backward error is checked; on the Lanczos path both come from one product of each matrix
with the vectors (``spectrum.products``), and that one residual pass also decides the
fall-back to ARPACK.

Modules
-------
``problem``
    Validation, :class:`SolverOptions`, the :class:`~.problem.Problem` of one solve and its
    two operators (energy shift-invert, linearized shift-invert).
``spectrum``
    Pure functions of eigenpairs: residuals, the Rayleigh functional, frequencies, rates,
    stability labels.
``lanczos``, ``arpack``, ``dense``
    The three methods; ``solver`` chooses among them.
"""

from .problem import (
    DEFAULT_TOL,
    DENSE_LIMIT,
    MAX_COUNT,
    SolverOptions,
    check_count,
    check_family,
    check_shift,
    check_structure,
    max_count,
)
from .solver import SHIFT_MARGIN, Eigenpairs, solve_qep
from .spectrum import (
    PAIR_DEFECT_LIMIT,
    RESIDUAL_LIMIT,
    STABILITY_LABELS,
    STABILITY_RTOL,
    normalize,
    quadratic_rayleigh,
    relative_residuals,
    stability_label,
)

__all__ = ["DEFAULT_TOL", "DENSE_LIMIT", "MAX_COUNT", "PAIR_DEFECT_LIMIT", "RESIDUAL_LIMIT",
           "SHIFT_MARGIN", "STABILITY_LABELS", "STABILITY_RTOL", "Eigenpairs", "SolverOptions",
           "check_count", "check_family", "check_shift", "check_structure", "max_count",
           "normalize",
           "quadratic_rayleigh", "relative_residuals", "solve_qep", "stability_label"]
