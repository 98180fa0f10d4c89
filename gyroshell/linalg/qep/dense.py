"""Small problems (n <= DENSE_LIMIT): every eigenvalue of the 2n linearization by LAPACK."""

from __future__ import annotations

import time

import numpy as np
import scipy.linalg as la

from .problem import Problem
from .spectrum import clean_parts, quadratic_rayleigh, representatives


def _linearization(prob: Problem) -> tuple[np.ndarray, np.ndarray]:
    """Dense A = [[0, I], [−K, −(G + C)]] and B = diag(I, M) of A z = λ B z."""
    n = prob.n
    M, GC, K = (x.toarray() for x in (prob.M, prob.GC, prob.K))
    eye, zero = np.eye(n), np.zeros((n, n))
    A = np.block([[zero, eye], [-K, -GC]])
    B = np.block([[eye, zero], [zero, M]])
    return A, B


def solve_dense(prob: Problem, shift: complex | None, definite: bool | None
                ) -> tuple[np.ndarray, np.ndarray, bool]:
    """Every eigenvalue by LAPACK, then the same selection as the sparse paths.

    Returns
    -------
    (eigenvalues, vectors, definite)
        The ``count`` selected pairs (1/s; vectors as columns) and whether K is positive
        definite (found out here when ``definite`` is None).
    """
    n, count = prob.n, prob.count
    A, B = _linearization(prob)
    t0 = time.perf_counter()
    lam, Z = la.eig(A, B)
    prob.info.update(method="dense", solve_time=time.perf_counter() - t0, factor_time=0.0)
    phi = Z[:n]
    if definite is None:
        definite = bool(np.all(la.eigvalsh(prob.K.toarray()) > 0))
    damped = prob.C is not None
    omega_s = 0.0 if shift is None else shift.imag
    if not damped and definite:
        lam = quadratic_rayleigh(prob.M, prob.GC, prob.K, lam, phi)
        up = np.flatnonzero(lam.imag > 0)
        up = up[np.argsort(lam.imag[up])][:count]
        prob.info.update(shift=1j * omega_s, below_shift=int(np.count_nonzero(
            lam.imag[lam.imag > 0] < omega_s)))
        prob.info["pair_defect"] = float(np.max(np.abs(lam[up].real) / np.abs(lam[up])))
        return 1j * lam[up].imag, phi[:, up], definite
    reps, vecs = representatives(lam, phi, right_half=not damped)
    if damped:
        order = np.lexsort((np.abs(reps), np.abs(reps.imag)))
        reps, vecs = reps[order], vecs[:, order]
    lams, vecs = reps[:count], vecs[:, :count]
    if not damped:
        lams = clean_parts(lams)
    prob.info.update(shift=1j * omega_s, below_shift=None)
    return lams, vecs, definite
