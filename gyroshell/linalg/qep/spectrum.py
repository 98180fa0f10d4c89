"""Pure functions of computed eigenpairs: residuals, Rayleigh polishing, derived quantities.

``GC`` below is the matrix multiplying λ in (λ²M + λ(G + C) + K) φ = 0: G + C, or G alone
without damping (``D`` is kept for the bending rigidity).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.errors import ParameterError

#: Largest accepted relative residual (backward error) of a returned eigenpair.
RESIDUAL_LIMIT = 1e-6
#: Largest |Re λ| / |λ| accepted for an undamped eigenvalue below critical (a ±iω pair).
PAIR_DEFECT_LIMIT = 1e-6
#: Relative size of Re λ (or Im λ) below which it counts as zero when classifying.
STABILITY_RTOL = 1e-9
#: Stability labels, in the order of precedence of :func:`stability_label`.
STABILITY_LABELS = ("divergence", "flutter", "stable")
#: Two eigenvalues closer than this relative distance are one (a duplicate from ARPACK).
DUPLICATE_RTOL = 1e-8
#: Stands in for a zero |ω| in 2π/ω so that no division warning is raised (the result is
#: replaced by inf there).
TINY_OMEGA = 1e-300


def norm1(matrix: sp.spmatrix) -> float:
    """‖A‖₁ of a sparse matrix (largest absolute column sum); 0 for an empty one."""
    return float(abs(matrix).sum(axis=0).max()) if matrix.nnz else 0.0


def product(A, X: np.ndarray) -> np.ndarray:
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


def products(M, GC, K, vectors: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(Mφ, GC φ, Kφ) for the columns φ: what the residuals and the Rayleigh functional
    both need, computed once where both are wanted."""
    phi = np.asarray(vectors)
    return product(M, phi), product(GC, phi), product(K, phi)


def relative_residuals(M, GC, K, eigenvalues: np.ndarray, vectors: np.ndarray, *,
                       products_of=None) -> np.ndarray:
    """‖(λ²M + λ GC + K)φ‖₂ / ((|λ|²‖M‖₁ + |λ|‖GC‖₁ + ‖K‖₁) ‖φ‖₂) per column (dimensionless).

    ``GC`` is G + C (G alone undamped); ``products_of``: :func:`products` of these vectors,
    if already at hand.
    """
    lam = np.asarray(eigenvalues)
    phi = np.asarray(vectors)
    Mphi, GCphi, Kphi = products(M, GC, K, phi) if products_of is None else products_of
    r = Mphi * lam**2 + GCphi * lam + Kphi
    scale = np.abs(lam) ** 2 * norm1(sp.csr_matrix(M)) + np.abs(lam) * norm1(
        sp.csr_matrix(GC)) + norm1(sp.csr_matrix(K))
    denominator = scale * np.linalg.norm(phi, axis=0)
    numerator = np.linalg.norm(r, axis=0)
    # λ = 0 with K = 0: Q(0) = 0, an exact eigenpair (0 / 0 would be NaN)
    return np.divide(numerator, denominator, out=np.zeros_like(numerator),
                     where=(denominator > 0) | (numerator > 0))


def quadratic_rayleigh(M, GC, K, eigenvalues: np.ndarray, vectors: np.ndarray, *,
                       products_of=None) -> np.ndarray:
    """Roots of m λ² + g λ + κ = 0 (m = φᴴMφ, g = φᴴ GC φ, κ = φᴴKφ) nearest each λ, 1/s.

    The quadratic Rayleigh functional, column by column: second-order accurate in the error
    of φ. ``GC`` is G + C; ``products_of`` as in :func:`relative_residuals`.
    """
    phi = np.asarray(vectors)
    Mphi, GCphi, Kphi = products(M, GC, K, phi) if products_of is None else products_of
    c = phi.conj()
    m = np.einsum("ij,ij->j", c, Mphi)
    g = np.einsum("ij,ij->j", c, GCphi)
    kap = np.einsum("ij,ij->j", c, Kphi)
    disc = np.sqrt(g * g - 4 * m * kap + 0j)
    r1, r2 = (-g + disc) / (2 * m), (-g - disc) / (2 * m)
    lam = np.asarray(eigenvalues)
    return np.where(np.abs(r1 - lam) <= np.abs(r2 - lam), r1, r2)


def normalize(phi: np.ndarray) -> np.ndarray:
    """Each column divided by its largest-magnitude entry (that entry becomes 1)."""
    return phi / phi[np.argmax(np.abs(phi), axis=0), np.arange(phi.shape[1])]


def representatives(lam: np.ndarray, phi: np.ndarray, *, right_half: bool
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
        if all(abs(lam[j] - lam[i]) > DUPLICATE_RTOL * abs(lam[j]) for i in chosen):
            chosen.append(int(j))
    sel = np.array(chosen, dtype=int)
    return lam[sel], phi[:, sel]


def clean_parts(lams: np.ndarray) -> np.ndarray:
    """Undamped representatives (Re, Im >= 0): parts at round-off level set to zero, so a
    gyroscopically stable eigenvalue is exactly imaginary and a divergent one exactly real."""
    lams = np.where(lams.real < STABILITY_RTOL * np.abs(lams), 1j * lams.imag, lams)
    return np.where(lams.imag < STABILITY_RTOL * np.abs(lams), lams.real + 0j, lams)


# ----- derived quantities of eigenvalues λ (1/s) ---------------------------------------------
def omega(eigenvalues: np.ndarray) -> np.ndarray:
    """Angular frequencies ω = |Im λ| (damped frequencies with damping), rad/s."""
    return np.abs(eigenvalues.imag)


def period(eigenvalues: np.ndarray) -> np.ndarray:
    """Periods 2π / ω, s (inf for a non-oscillating eigenvalue)."""
    w = omega(eigenvalues)
    with np.errstate(divide="ignore"):
        return np.where(w > 0, 2 * np.pi / np.maximum(w, TINY_OMEGA), np.inf)


def growth_rate(eigenvalues: np.ndarray) -> np.ndarray:
    """max(Re λ, 0), 1/s: zero for stable modes, the divergence/flutter growth rate."""
    return np.maximum(eigenvalues.real, 0.0)


def decay_rate(eigenvalues: np.ndarray) -> np.ndarray:
    """−Re λ, 1/s: positive for damped modes, zero undamped, negative if growing."""
    return -eigenvalues.real + 0.0   # + 0.0: no negative zero for undamped modes


def damping_ratio(eigenvalues: np.ndarray) -> np.ndarray:
    """ζ = −Re λ / |λ| (dimensionless; 0 undamped, 1 critically damped)."""
    mag = np.abs(eigenvalues)
    return np.where(mag > 0, -eigenvalues.real / np.where(mag > 0, mag, 1.0), 0.0) + 0.0


def stability_label(eigenvalues: np.ndarray, rtol: float = STABILITY_RTOL) -> str:
    """``"divergence"``, ``"flutter"`` or ``"stable"`` for finite complex eigenvalues λ, 1/s.

    A positive real eigenvalue is divergence, a complex one with positive real part flutter
    (parts below ``rtol``·|λ| count as zero); the public, validating entry is
    :func:`gyroshell.studies.stability.classify_stability`.
    """
    mag = np.abs(eigenvalues)
    growing = eigenvalues.real > rtol * mag
    real = np.abs(eigenvalues.imag) <= rtol * mag
    if np.any(growing & real):
        return "divergence"
    if np.any(growing):
        return "flutter"
    return "stable"


def check_eigenvalues(eigenvalues) -> np.ndarray:
    """Eigenvalues as a flat complex array, at least one, all finite (else ParameterError)."""
    lam = np.asarray(list(eigenvalues) if not isinstance(eigenvalues, np.ndarray)
                     else eigenvalues, dtype=complex).ravel()
    if lam.size == 0:
        raise ParameterError("classify_stability needs at least one eigenvalue")
    if not np.all(np.isfinite(lam)):
        raise ParameterError("eigenvalues must be finite")
    return lam
