"""Quadratic gyroscopic eigenproblem (λ² M + λ G(V) + K(V)) φ = 0: frequencies and modes.

Below the critical speed K(V) is positive definite and, G being skew-symmetric, every
eigenvalue is a pair ±iω (ω > 0, rad/s) with eigenvectors φ, φ̄: the tape vibrates but
neither grows nor decays. Above it some eigenvalues leave the imaginary axis (divergence).

Method
------
State-space linearization z = [φ; λφ]: A z = λ B z with A = [[0, I], [−K, −G]] and
B = diag(I, M). ARPACK (``eigs``) runs on the shift-invert operator (A − σB)⁻¹B, applied
through one sparse factorization of the n × n matrix Q(σ) = K + σG + σ²M:

    z₁ = −Q(σ)⁻¹ (M u₂ + (G + σM) u₁),   z₂ = u₁ + σ z₁,   λ = σ + 1/θ.

The automatic shift is σ = iω_s just below the bottom of the spectrum: with σ = 0 the dozens
of long-tape modes within 0.1 % of √(k/ρ) are nearly equal in |1/λ| and converge slowly;
measured from iω_s they are far apart. For a Hermitian Q(iω) = K − ω²M + iωG (K > 0) the
number of negative pivots of its LDLᴴ factorization equals the number of frequencies in
(0, ω) (each eigenvalue of Q(iω) crosses zero only downwards, with slope −(ω²m + κ)/ω < 0),
so the factorization that serves the shift also *certifies* that no low mode was missed.

The state is scaled, y = [ω_r M^½ φ; M^½ λφ], so that ARPACK's Euclidean norm is close to
the energy norm: unscaled, the displacement part is 10⁵ times smaller than the velocity
part, and clustered eigenvalues "converge" with errors of 10⁻⁶ while the residual test
passes. Each eigenvalue is finally polished with the quadratic Rayleigh functional
(the root of m λ² + g λ + κ = 0 with m = φᴴMφ, g = φᴴGφ, κ = φᴴKφ nearest to it).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from . import persistence
from .errors import ConvergenceError, ParameterError
from .grid import Grid
from .model import TapeModel
from .parameters import TapeParameters, check_velocity
from .threads import blas_threads

#: Default relative tolerance of ARPACK.
DEFAULT_TOL = 1e-10
#: Largest accepted relative residual (backward error) of a returned eigenpair.
RESIDUAL_LIMIT = 1e-6
#: The automatic shift sits this fraction below the estimated lowest frequency.
SHIFT_MARGIN = 2e-4


@dataclass(frozen=True)
class Modes:
    """Lowest eigenpairs of the gyroscopic tape at one speed.

    Attributes
    ----------
    grid : Grid
    velocity : float
        Tape speed V, m/s.
    eigenvalues : numpy.ndarray
        λ (complex, 1/s), one per pair: +iω below critical (ascending ω); above critical the
        eigenvalues nearest zero with Re λ >= 0 (ascending |λ|).
    vectors : numpy.ndarray
        Mode shapes φ, complex, shape (n, count), largest entry 1.
    residuals : numpy.ndarray
        Relative residuals ‖Q(λ)φ‖ / ((|λ|²‖M‖ + |λ|‖G‖ + ‖K‖) ‖φ‖) (backward errors).
    supercritical : bool
        True if K(V) is not positive definite (V at or above the critical speed).
    info : dict
        Diagnostics: ``shift`` (σ, 1/s), ``below_shift`` (certified number of frequencies
        below the shift), ``factor_time`` and ``solve_time`` (s), ``ncv``, ``nev``,
        ``operator_applications``, ``attempts``, ``pair_defect`` (max |Re λ|/|λ| before cleaning).
    """

    grid: Grid
    velocity: float
    eigenvalues: np.ndarray
    vectors: np.ndarray
    residuals: np.ndarray
    supercritical: bool = False
    info: dict = field(default_factory=dict, compare=False)

    @property
    def count(self) -> int:
        return len(self.eigenvalues)

    @property
    def omega(self) -> np.ndarray:
        """Angular frequencies ω = |Im λ|, rad/s."""
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
        """Re λ >= 0, 1/s: zero below critical, the divergence growth rate above."""
        return np.abs(self.eigenvalues.real)

    @property
    def fields(self) -> np.ndarray:
        """Complex mode shapes on all nodes, shape (nx + 1, ny + 1, count)."""
        return self.grid.to_field(self.vectors)

    def field(self, index: int) -> np.ndarray:
        """Complex mode shape ``index`` on all nodes, shape (nx + 1, ny + 1)."""
        return self.grid.to_field(self.vectors[:, index])

    def to_xarray(self, *, params=None):
        """xarray Dataset with units and metadata (see :mod:`gyroshell.persistence`)."""
        return persistence.to_xarray(self, params=params)

    def save(self, path, *, params=None):
        """Write NetCDF (.nc) whole; ``gyroshell.load(path)`` reads it back exactly."""
        return persistence.save(self, path, params=params)


# ----- small pieces -----------------------------------------------------------------------
def strip_frequency_estimate(params: TapeParameters, grid: Grid, velocity: float) -> float:
    """Bottom of the width-uniform travelling-wave band, rad/s (an estimate of ω₁).

    min over the discrete wavenumbers α_m = mπ/L_x of −Vα + √((Dα⁴ + Tα² + k)/ρ), the
    lowest frequency of a beam on the shell foundation moving at V (Wickert & Mote's
    dispersion relation plus k). Returns 0 if that is not positive (V near or above critical).
    """
    m = np.arange(1, grid.nx)
    alpha = m * np.pi / grid.length
    with np.errstate(all="ignore"):
        w = -velocity * alpha + np.sqrt(
            (params.D * alpha**4 + params.tension * alpha**2 + params.k) / params.density)
    best = float(np.min(w))
    return best if best > 0 and math.isfinite(best) else 0.0


def _norm1(matrix: sp.spmatrix) -> float:
    return float(abs(matrix).sum(axis=0).max()) if matrix.nnz else 0.0


def relative_residuals(model: TapeModel, velocity: float, eigenvalues: np.ndarray,
                       vectors: np.ndarray) -> np.ndarray:
    """‖(λ²M + λG + K)φ‖₂ / ((|λ|²‖M‖₁ + |λ|‖G‖₁ + ‖K‖₁) ‖φ‖₂) for each pair (dimensionless)."""
    K, G, md = model.K(velocity), model.G(velocity), model.mass_diagonal
    nK, nG, nM = _norm1(K), _norm1(G), float(md.max())
    out = np.empty(len(eigenvalues))
    for j, lam in enumerate(eigenvalues):
        phi = vectors[:, j]
        r = lam**2 * (md * phi) + lam * (G @ phi) + K @ phi
        scale = abs(lam) ** 2 * nM + abs(lam) * nG + nK
        out[j] = np.linalg.norm(r) / (scale * np.linalg.norm(phi))
    return out


def rayleigh_polish(M: np.ndarray, G: sp.spmatrix, K: sp.spmatrix, lam: complex,
                    phi: np.ndarray) -> complex:
    """Root of m λ² + g λ + κ = 0 (m = φᴴMφ, g = φᴴGφ, κ = φᴴKφ) nearest to ``lam``, 1/s.

    The quadratic Rayleigh functional: second-order accurate in the error of φ. ``M`` is the
    mass diagonal, kg.
    """
    c = np.conj(phi)
    m = float(np.real(c @ (M * phi)))
    g = complex(c @ (G @ phi))
    kap = complex(c @ (K @ phi))
    disc = np.sqrt(complex(g * g - 4 * m * kap))
    roots = ((-g + disc) / (2 * m), (-g - disc) / (2 * m))
    return min(roots, key=lambda r: abs(r - lam))


def factor_hermitian(Q: sp.spmatrix) -> tuple[spla.SuperLU, int | None]:
    """Factor a symmetric/Hermitian Q with diagonal pivots; return (LU, negative pivots).

    The count is the number of negative eigenvalues of Q (Sylvester's law of inertia), or
    ``None`` if SuperLU had to pivot off the diagonal (then the count is unknown).
    """
    lu = spla.splu(sp.csc_matrix(Q), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                   options={"SymmetricMode": True})
    if not np.array_equal(lu.perm_r, lu.perm_c):
        return lu, None
    d = lu.U.diagonal()
    if not np.all(np.isfinite(d)) or np.any(d == 0):
        return lu, None
    return lu, int(np.count_nonzero(np.real(d) < 0))


def _operator(lu: spla.SuperLU, G: sp.spmatrix, md: np.ndarray, sigma: complex,
              omega_ref: float, counter: list[int]) -> spla.LinearOperator:
    """(A − σB)⁻¹B on the scaled state y = [ω_r M^½ φ; M^½ λφ]."""
    n = len(md)
    sm = np.sqrt(md)
    dtype = complex if sigma.imag != 0 else float
    sigma = sigma if dtype is complex else sigma.real

    def matvec(y: np.ndarray) -> np.ndarray:
        counter[0] += 1
        y = np.asarray(y).ravel()
        u1 = y[:n] / (omega_ref * sm)
        u2 = y[n:] / sm
        z1 = -lu.solve(np.ascontiguousarray(md * u2 + G @ u1 + sigma * (md * u1)))
        z2 = u1 + sigma * z1
        return np.concatenate([omega_ref * sm * z1, sm * z2])

    return spla.LinearOperator((2 * n, 2 * n), matvec=matvec, dtype=dtype)


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
    return theta, vecs, ncv


def _check_count(count: int, n: int) -> int:
    if isinstance(count, bool) or int(count) != count:
        raise ParameterError(f"count must be an integer, got {count!r}")
    count = int(count)
    if not 1 <= count < n // 2:
        raise ParameterError(f"count must be in [1, {n // 2 - 1}] for {n} unknowns, "
                             f"got {count}")
    return count


def _check_sigma(sigma) -> complex | None:
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


# ----- the solver -------------------------------------------------------------------------
def modes(model: TapeModel, velocity: float = 0.0, count: int = 6, *,
          sigma: complex | str = "auto", tol: float = DEFAULT_TOL, ncv: int | None = None,
          maxiter: int | None = None) -> Modes:
    """Lowest ``count`` frequencies and complex mode shapes of the tape at speed V.

    Parameters
    ----------
    model : TapeModel
    velocity : float
        Tape speed V, m/s (>= 0).
    count : int
        Number of frequencies (pairs ±iω), 1 <= count < n/2.
    sigma : "auto", 0 or complex i·ω_s
        Shift, 1/s. ``"auto"``: i·ω_s just below the estimated lowest frequency, moved down
        until the inertia of Q(iω_s) certifies few modes below it. ``0``: real arithmetic,
        one factorization of K; asks ARPACK for 2·count eigenvalues (the pairs).
    tol : float
        ARPACK relative tolerance.
    ncv : int, optional
        Krylov subspace size; default max(2·nev + 1, nev + 20).
    maxiter : int, optional
        ARPACK restarts; default scipy's.

    Returns
    -------
    Modes
        Above the critical speed (K(V) indefinite) ``supercritical`` is True and the
        eigenvalues nearest zero are returned, with their growth rates Re λ > 0.

    Raises
    ------
    ParameterError
        Bad count, sigma, tol or ncv.
    ConvergenceError
        ARPACK did not converge, or the residuals or the mode count could not be verified.
    """
    with blas_threads(1):
        return _modes(model, velocity, count, sigma=sigma, tol=tol, ncv=ncv, maxiter=maxiter)


def _modes(model, velocity, count, *, sigma, tol, ncv, maxiter) -> Modes:
    velocity = check_velocity(velocity)
    n = model.size
    count = _check_count(count, n)
    shift = _check_sigma(sigma)
    if not (isinstance(tol, (int, float)) and 0 <= tol < 1):
        raise ParameterError(f"tol must be in [0, 1), got {tol!r}")
    K, G, md = model.K(velocity), model.G(velocity), model.mass_diagonal
    info: dict = {"operator_applications": 0, "attempts": 0}
    t0 = time.perf_counter()
    lu_k, negatives = factor_hermitian(K)
    info["factor_time"] = time.perf_counter() - t0
    definite = negatives == 0
    if negatives is None:  # pivoting happened: decide definiteness from K's pivots anyway
        definite = False
    estimate = strip_frequency_estimate(model.params, model.grid, velocity)
    if not definite or shift == 0:
        lu = lu_k if negatives is not None else spla.splu(K.tocsc())
        result = _solve_real(model, velocity, count, lu, K, G, md, estimate, info,
                             definite=definite, tol=tol, ncv=ncv, maxiter=maxiter)
    else:
        omega_s = estimate * (1 - SHIFT_MARGIN) if shift is None else shift.imag
        if omega_s <= 0:  # nothing to shift to (e.g. next to the critical speed): σ = 0
            return _solve_real(model, velocity, count, lu_k, K, G, md, estimate, info,
                               definite=True, tol=tol, ncv=ncv, maxiter=maxiter)
        result = _solve_complex(model, velocity, count, K, G, md, omega_s, info,
                                auto=shift is None, tol=tol, ncv=ncv, maxiter=maxiter)
    return result


def _v0(n2: int, dtype) -> np.ndarray:
    # A fixed, generic start vector: reproducible results, no accidental orthogonality.
    v = np.random.default_rng(12345).standard_normal(n2)
    return v.astype(dtype)


def _finish(model, velocity, lams, phis, info, supercritical) -> Modes:
    phis = phis / phis[np.argmax(np.abs(phis), axis=0), np.arange(phis.shape[1])]
    res = relative_residuals(model, velocity, lams, phis)
    info["max_residual"] = float(res.max())
    if res.max() > RESIDUAL_LIMIT:
        raise ConvergenceError(
            f"eigenpairs not accurate: largest relative residual {res.max():.2e} > "
            f"{RESIDUAL_LIMIT:g}; try a larger ncv or a smaller tol")
    return Modes(model.grid, velocity, lams, phis, res, supercritical, info)


def _solve_real(model, velocity, count, lu, K, G, md, estimate, info, *, definite, tol, ncv,
                maxiter) -> Modes:
    """σ = 0: factor K once, ask for 2·count eigenvalues (conjugate pairs) nearest zero."""
    n = model.size
    omega_ref = estimate if estimate > 0 else math.sqrt(model.params.k / model.params.density
                                                       or 1.0) or 1.0
    counter = [0]
    op = _operator(lu, G, md, 0j, omega_ref, counter)
    nev = min(2 * count + 1, 2 * n - 2)
    t0 = time.perf_counter()
    theta, y, used = _arpack(op, nev, tol=tol, ncv=ncv, maxiter=maxiter,
                             v0=_v0(2 * n, float))
    info.update(solve_time=time.perf_counter() - t0, ncv=used, nev=nev, shift=0j,
                below_shift=None, operator_applications=counter[0], attempts=1)
    lam = 1.0 / theta
    phi = y[:n] / (omega_ref * np.sqrt(md))[:, None]
    lam = np.array([rayleigh_polish(md, G, K, lam[j], phi[:, j]) for j in range(len(lam))])
    if definite:
        scale = np.maximum(np.abs(lam), omega_ref)
        info["pair_defect"] = float(np.max(np.abs(lam.real) / scale))
        if info["pair_defect"] > 1e-6:
            raise ConvergenceError(
                f"eigenvalues are not ±iω pairs below critical (|Re λ|/|λ| = "
                f"{info['pair_defect']:.1e}); try a larger ncv")
        keep = np.flatnonzero(lam.imag > 0)
        order = keep[np.argsort(lam.imag[keep])]
        # every +iω must have its partner −iω among the results
        partners = np.sort(-lam.imag[lam.imag < 0])
        if len(order) < count or len(partners) < count or not np.allclose(
                partners[:count], lam.imag[order[:count]], rtol=1e-6):
            raise ConvergenceError("could not match the eigenvalues in ±iω pairs; "
                                   "try a larger ncv or count")
        sel = order[:count]
        lams = 1j * lam.imag[sel]
        return _finish(model, velocity, lams, phi[:, sel], info, False)
    # supercritical: one representative per group (λ, −λ, λ̄, −λ̄), Re >= 0 and Im >= 0,
    # taken from a found member with Re λ >= 0 (conjugated if Im λ < 0)
    reps = np.abs(lam.real) + 1j * np.abs(lam.imag)
    tiny = 1e-9 * np.abs(lam)
    order = np.argsort(np.abs(reps), kind="stable")
    chosen: list[int] = []
    for j in order:
        if lam[j].real < -tiny[j]:
            continue
        if all(abs(reps[j] - reps[i]) > 1e-8 * abs(reps[j]) for i in chosen):
            chosen.append(int(j))
    sel = np.array(chosen[:count], dtype=int)
    lams = reps[sel]
    lams = np.where(lams.real < 1e-9 * np.abs(lams), 1j * lams.imag, lams)
    lams = np.where(lams.imag < 1e-9 * np.abs(lams), lams.real + 0j, lams)
    phi = phi[:, sel].astype(complex)
    flip = lam[sel].imag < 0
    phi[:, flip] = np.conj(phi[:, flip])
    info["growing"] = int(np.count_nonzero(lams.real > 0))
    return _finish(model, velocity, lams, phi, info, True)


def _solve_complex(model, velocity, count, K, G, md, omega_s, info, *, auto, tol, ncv,
                   maxiter) -> Modes:
    """σ = iω_s: factor the Hermitian Q(iω_s) once, certify the count below ω_s."""
    n = model.size
    factor_time = info["factor_time"]
    tries = 0
    while True:  # move an automatic shift down until few modes lie below it
        tries += 1
        t0 = time.perf_counter()
        Q = (K - omega_s**2 * sp.diags(md) + 1j * omega_s * G).tocsc()
        lu, below = factor_hermitian(Q)
        factor_time += time.perf_counter() - t0
        if not auto or (below is not None and below <= count):
            break
        if tries >= 3:  # the estimate is far off (e.g. next to critical): σ = 0 instead
            info["factor_time"] = factor_time
            lu_k, _ = factor_hermitian(K)
            return _solve_real(model, velocity, count, lu_k, K, G, md, omega_s, info,
                               definite=True, tol=tol, ncv=ncv, maxiter=maxiter)
        omega_s *= (0.98, 0.8)[tries - 1]
    info.update(factor_time=factor_time, shift=1j * omega_s, below_shift=below,
                shift_tries=tries)
    if below is None:
        below = 0
    sigma = 1j * omega_s
    omega_ref = omega_s if omega_s > 0 else max(strip_frequency_estimate(
        model.params, model.grid, velocity), 1.0)
    extra = 2
    t0 = time.perf_counter()
    counter = [0]
    for attempt in range(1, 4):  # noqa: B007 - reported in info
        nev = min(count + below + extra, 2 * n - 2)
        op = _operator(lu, G, md, sigma, omega_ref, counter)
        theta, y, used = _arpack(op, nev, tol=tol, ncv=ncv, maxiter=maxiter,
                                 v0=_v0(2 * n, complex))
        lam = sigma + 1.0 / theta
        phi = y[:n] / (omega_ref * np.sqrt(md))[:, None]
        lam = np.array([rayleigh_polish(md, G, K, lam[j], phi[:, j]) for j in range(nev)])
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
    info.update(solve_time=time.perf_counter() - t0, ncv=used, nev=nev, attempts=attempt,
                operator_applications=counter[0])
    scale = np.maximum(np.abs(lam[pos]), omega_s)
    info["pair_defect"] = float(np.max(np.abs(lam[pos].real) / scale))
    if info["pair_defect"] > 1e-6:
        raise ConvergenceError(f"eigenvalues off the imaginary axis below critical "
                               f"(|Re λ|/|λ| = {info['pair_defect']:.1e})")
    sel = pos[:count]
    return _finish(model, velocity, 1j * lam.imag[sel], phi[:, sel], info, False)


def frequencies(model: TapeModel, velocity: float = 0.0, count: int = 6, **options
                ) -> np.ndarray:
    """The lowest ``count`` angular frequencies ω, rad/s, ascending (see :func:`modes`)."""
    return modes(model, velocity, count, **options).omega
