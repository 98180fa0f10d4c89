"""Thick-restart Lanczos in the energy inner product: the undamped, K > 0 path.

The shift-invert operator T of the Hermitian pencil (:class:`~.problem.EnergyOperator`) is
self-adjoint in the energy inner product, so a Krylov-Schur (thick-restart Lanczos)
iteration with full reorthogonalization finds its Ritz pairs (notes of
:mod:`gyroshell.linalg.qep`).

With the shift below the lowest frequency, the wanted θ = 1/(ω − ω_s) are the largest
positive ones. Where the inertia counts at least ``count`` frequencies below the shift
(a caller's count shift, e.g. the mirror halves' ω̄), exactly those are asked for: their θ
are the most negative ones, the other extreme of T's spectrum, and converge as fast.
"""

from __future__ import annotations

import math
import time

import numpy as np
import scipy.linalg as la
from scipy.linalg.blas import zgemv as _zgemv

from ..inertia import InertiaFactor
from .problem import EnergyOperator, Problem, random_start

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
#: Ritz values are first tested once the basis holds this many vectors beyond ``nev``.
RITZ_TEST_EXTRA = 2


def _energy(w: np.ndarray, Lw: np.ndarray) -> float:
    """‖w‖ in the energy inner product, from w and L w (a round-off negative counts as 0)."""
    return math.sqrt(max(np.vdot(w, Lw).real, 0.0))


def _coefficients(rows: np.ndarray, Lw: np.ndarray) -> np.ndarray:
    """The energy inner products ⟨v_i, w⟩ = v_iᴴ L w of the rows v_i of ``rows``
    (C-contiguous) with w, from L w: one BLAS product Vᴴ(Lw), the rows read as the columns
    of a Fortran array, with no conjugated copy of Lw (BLAS conjugates)."""
    return _zgemv(1.0, rows.T, Lw, trans=2)


def _subtract(w: np.ndarray, rows: np.ndarray, h: np.ndarray) -> None:
    """w −= Σ h_i v_i over the rows v_i of ``rows``, in place (one BLAS product, no
    temporary)."""
    out = _zgemv(-1.0, rows.T, h, beta=1.0, y=w, overwrite_y=True)
    if out is not w:   # BLAS worked on a copy (w not contiguous complex128)
        w[...] = out


class _Basis:
    """The Lanczos basis V (by rows, preallocated) and its projected matrix H."""

    def __init__(self, op: EnergyOperator, start: np.ndarray, nev: int) -> None:
        self.op, self.n2 = op, len(start)
        self.m = min(max(2 * nev + LANCZOS_EXTRA, LANCZOS_MIN_BASIS), self.n2 - 1)
        self.V = np.empty((self.m + 1, self.n2), dtype=complex)
        self.H = np.zeros((self.m + 1, self.m), dtype=complex)
        v = start.astype(complex)
        self.put(0, v, _energy(v, op.weight(v)))

    def put(self, j: int, w: np.ndarray, norm: float) -> None:
        if norm > 0:
            np.multiply(w, 1.0 / norm, out=self.V[j])

    def extend(self, j: int, kept: int) -> None:
        """Basis vector j + 1 from T v_j: the three-term (Lanczos) components along the last
        two vectors removed first (most of T v_j), then one classical Gram-Schmidt pass
        over the whole basis, a second only when the first cancelled most of w (DGKS); the
        new norm follows from Pythagoras, ‖w − Vh‖² = ‖w‖² − ‖h‖². Without the three-term
        part first nearly every step cancels and needs two full passes (~20 % more work)."""
        V, H, op = self.V, self.H, self.op
        w, Lw = op.apply(V[j])
        size = _energy(w, Lw)
        basis = V[: j + 1]
        beta = 0.0
        if j - 1 > kept:  # the three-term part first: the rest is then small
            local = V[j - 1: j + 1]
            h = _coefficients(local, Lw)
            _subtract(w, local, h)
            H[j - 1: j + 1, j] += h
            Lw = op.weight(w)
            size = _energy(w, Lw)
        for _ in range(2):  # classical Gram-Schmidt, repeated if it cancelled (DGKS)
            h = _coefficients(basis, Lw)
            _subtract(w, basis, h)
            H[: j + 1, j] += h
            left2 = size * size - float(np.vdot(h, h).real)
            if left2 > (REORTHOGONALIZE * size) ** 2:
                beta = math.sqrt(left2)
                break
            Lw = op.weight(w)
            size = beta = _energy(w, Lw)
        self.put(j + 1, w, beta)
        H[j + 1, j] = beta
        if beta == 0.0:  # an invariant subspace: continue from a fresh direction
            w = random_start(self.n2, complex)
            for _ in range(2):
                w -= np.conj(basis @ np.conj(op.weight(w))) @ basis
            self.put(j + 1, w, _energy(w, op.weight(w)))

    def ritz(self, size: int, wanted, nev: int, tol: float):
        """(θ, S, order by ``wanted``, whether the ``nev`` best have converged). SciPy's
        eigh (LAPACK's MRRR driver): NumPy's (divide and conquer) has less call overhead
        but failed to converge on one projected matrix of a warm-started solve."""
        H = self.H
        Hs = H[:size, :size]
        theta, S = la.eigh(0.5 * (Hs + Hs.conj().T))
        order = np.argsort(-wanted(theta), kind="stable")
        resid = np.abs(H[size, size - 1] * S[size - 1, :])
        best = order[:nev]
        return theta, S, order, bool(np.all(resid[best] <= tol * np.abs(theta[best])))

    def restart(self, theta, S, order, nev: int) -> int:
        """Keep the wanted Ritz vectors plus some more, and the residual direction; returns
        how many are kept at the front."""
        V, H, m = self.V, self.H, self.m
        kept = min(nev + (m - nev) // 2, m - 1)
        keep = order[:kept]
        coupling = H[m, m - 1] * S[m - 1, keep]
        V[:kept] = S[:, keep].T @ V[:m]
        V[kept] = V[m]
        # T Y = Y Θ + v (β sₘ)ᵀ: an arrowhead; column `kept` is filled by the next step
        H[:] = 0.0
        H[np.arange(kept), np.arange(kept)] = theta[keep]
        H[kept, :kept] = coupling
        return kept


def lanczos(op: EnergyOperator, start: np.ndarray, wanted, nev: int, tol: float,
            ) -> tuple[np.ndarray, np.ndarray, int] | None:
    """Thick-restart Lanczos with full reorthogonalization in the energy inner product.

    Parameters
    ----------
    op : EnergyOperator
        T and the energy inner product.
    start : numpy.ndarray
        Start vector, length 2n.
    wanted : callable
        ``wanted(theta)`` ranks Ritz values (larger first).
    nev : int
        Ritz pairs wanted.
    tol : float
        Convergence when each residual |β sₘ| <= tol·|θ|.

    Returns
    -------
    (θ, Ritz vectors as columns, restarts) or None
        None if not converged within LANCZOS_RESTARTS restarts.
    """
    basis = _Basis(op, start, nev)
    kept = 0  # Ritz vectors kept at the front after a restart
    for restart in range(LANCZOS_RESTARTS + 1):
        for j in range(kept, basis.m):
            basis.extend(j, kept)
            if j + 1 >= nev + RITZ_TEST_EXTRA or j == basis.m - 1:
                theta, S, order, done = basis.ritz(j + 1, wanted, nev, tol)
                if done:
                    best = order[:nev]
                    return theta[best], (S[:, best].T @ basis.V[: j + 1]).T, restart
        kept = basis.restart(theta, S, order, nev)
    return None


def solve_hermitian(prob: Problem, omega_s: float, factor: InertiaFactor, below: int
                     ) -> tuple[np.ndarray, np.ndarray] | None:
    """The undamped subcritical eigenpairs by Lanczos on T; None if it did not converge."""
    op = EnergyOperator(prob, omega_s, factor)
    n, count = prob.n, prob.count
    start = _start_vector(prob)
    if omega_s > 0 and below >= count:
        # Every wanted frequency lies in (0, ω_s), where θ = 1/(ω − ω_s) < −1/ω_s: the
        # ``below`` most negative θ are exactly those frequencies (the pairs −ω give θ in
        # (−1/ω_s, 0)), an extreme end of T's spectrum; ask for them alone.
        nev = min(below, 2 * n - 2)

        def wanted(theta):
            return np.where(theta * omega_s < -1.0, np.abs(theta), -np.abs(theta))
    else:
        # with ω_s = 0 the ±ω pairs are equally near the shift: ask for both members
        nev = min(count + below + (count if omega_s == 0 else 0), 2 * n - 2)

        def wanted(theta):  # nearest the shift among positive frequencies
            with np.errstate(divide="ignore"):
                omega = omega_s + 1.0 / theta
            return np.where(omega > 0, np.abs(theta), -np.abs(theta))

    t0 = time.perf_counter()
    tol = max(prob.tol * LANCZOS_TOL_FACTOR, LANCZOS_TOL_FLOOR)
    out = lanczos(op, start, wanted, nev, tol)
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
    # The caller checks the backward errors against LANCZOS_RESIDUAL_LIMIT (near a
    # critical point K is nearly singular and the energy norm degenerates: the Ritz pairs
    # may then be less accurate than their Lanczos residuals say).
    return 1j * omega[keep], Z[n:, keep]


def _start_vector(prob: Problem) -> np.ndarray:
    """z = [λφ; φ] summed over previous modes (warm start) plus a little noise, or random."""
    n = prob.n
    noise = random_start(2 * n, float).astype(complex)
    if prob.start is None:
        return noise
    lam, phi = prob.start
    Z = np.concatenate([phi * lam, phi])
    z = Z.sum(axis=1)
    scale = np.linalg.norm(z) / math.sqrt(2 * n)
    if not (scale > 0 and math.isfinite(scale)):
        # previous modes with no part here (e.g. all symmetric, projected on the
        # antisymmetric half): a zero start would leave the first basis vector unset
        return noise
    return z + WARM_START_NOISE * scale * noise
