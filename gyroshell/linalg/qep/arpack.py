"""ARPACK (``eigs``) on the linearization A z = λ B z in shift-invert form: the general path.

Used above the critical speed, with damping, and where Lanczos is not wanted or did not
converge (notes of :mod:`gyroshell.linalg.qep`).
"""

from __future__ import annotations

import time

import numpy as np
import scipy.sparse.linalg as spla

from ...core.errors import ConvergenceError, ParameterError
from ..inertia import InertiaFactor
from .problem import Problem, linearized_operator, random_start
from .spectrum import clean_parts, quadratic_rayleigh, representatives

#: Extra eigenvalues asked for beyond those wanted, and how many times the request grows.
EXTRA_EIGENVALUES = 2
REQUEST_ATTEMPTS = 3
#: Default ARPACK basis: max(2 nev + 1, nev + ARPACK_EXTRA_BASIS), at most 2n − 1.
ARPACK_EXTRA_BASIS = 20


def arpack(op: spla.LinearOperator, nev: int, *, tol: float, ncv: int | None,
            maxiter: int | None, v0: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    n2 = op.shape[0]
    ncv = min(n2 - 1, max(2 * nev + 1, nev + ARPACK_EXTRA_BASIS)) if ncv is None else ncv
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


def solve_general(prob: Problem, sigma: complex, solve, omega_ref: float, *,
                   symmetric_pairs: bool, imaginary_pairs: bool = False
                   ) -> tuple[np.ndarray, np.ndarray]:
    """ARPACK nearest σ; one representative per pair. ``symmetric_pairs``: undamped
    supercritical, where λ, −λ, λ̄, −λ̄ come together (Re λ >= 0 representative).
    ``imaginary_pairs``: undamped below critical, every λ = ±iω; the +iω are kept by the
    sign of Im λ alone (an eigenvalue near zero has a real part of round-off size relative
    to the others, not to itself), ascending."""
    n, count = prob.n, prob.count
    counter = [0]
    op = linearized_operator(prob, solve, sigma, omega_ref, counter)
    real = sigma == 0
    extra = EXTRA_EIGENVALUES
    t0 = time.perf_counter()
    for attempt in range(1, REQUEST_ATTEMPTS + 1):  # noqa: B007 - reported in info
        nev = min((2 * count if real else count) + extra, 2 * n - 2)
        theta, y, used = arpack(op, nev, tol=prob.tol, ncv=prob.ncv, maxiter=prob.maxiter,
                                 v0=random_start(2 * n, float if real else complex))
        lam = sigma + 1.0 / theta
        phi = y[:n] / (omega_ref * np.sqrt(prob.mass_diagonal))[:, None]
        lam = quadratic_rayleigh(prob.M, prob.GC, prob.K, lam, phi)
        if imaginary_pairs:
            up = np.flatnonzero(lam.imag > 0)
            up = up[np.argsort(lam.imag[up])]
            reps, vecs = lam[up], phi[:, up]
        else:
            reps, vecs = representatives(lam, phi, right_half=symmetric_pairs)
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
        lams = clean_parts(lams)
    return lams, vecs


def solve_pairs_real(prob: Problem, factor: InertiaFactor, omega_ref: float
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Undamped, K > 0, σ = 0 by ARPACK: 2·count eigenvalues, checked as ±iω pairs."""
    return solve_general(prob, 0j, factor.solve, omega_ref, symmetric_pairs=False,
                          imaginary_pairs=True)


def solve_shifted_pairs(prob: Problem, omega_s: float, factor: InertiaFactor, below: int,
                        omega_ref: float) -> tuple[np.ndarray, np.ndarray]:
    """ARPACK about iω_s: the certified ``below`` frequencies and the next ones above."""
    n, count = prob.n, prob.count
    sigma = 1j * omega_s
    counter = [0]
    op = linearized_operator(prob, factor.solve, sigma, omega_ref, counter)
    extra = EXTRA_EIGENVALUES
    t0 = time.perf_counter()
    for attempt in range(1, REQUEST_ATTEMPTS + 1):  # noqa: B007 - reported in info
        nev = min(count + below + extra, 2 * n - 2)
        theta, y, used = arpack(op, nev, tol=prob.tol, ncv=prob.ncv, maxiter=prob.maxiter,
                                 v0=random_start(2 * n, complex))
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
