"""The solver's driver: validation, the choice of path, the shift, and the final checks.

:func:`solve_qep` returns plain arrays (:class:`Eigenpairs`); the result object
:class:`gyroshell.results.modes.GyroscopicModes` is built by
:func:`gyroshell.engines.gyroscopic.gyroscopic_modes`.
"""

from __future__ import annotations

import math
import time
from typing import NamedTuple

import numpy as np

from ...core.errors import ConvergenceError, ParameterError, SingularError
from ...core.parallel import blas_threads
from ..factorization import check_factorization, resolve_factorization, splu
from ..inertia import InertiaFactor
from .arpack import solve_general, solve_pairs_real, solve_shifted_pairs
from .dense import solve_dense
from .lanczos import LANCZOS_RESIDUAL_LIMIT, solve_hermitian
from .problem import (
    DENSE_LIMIT,
    METHODS,
    Problem,
    SolverOptions,
    check_count,
    check_memory,
    check_optional_int,
    check_shift,
    check_start,
    check_structure,
    check_tol,
)
from .rigid import without_stiffness
from .spectrum import (
    PAIR_DEFECT_LIMIT,
    RESIDUAL_LIMIT,
    norm1,
    normalize,
    products,
    quadratic_rayleigh,
    relative_residuals,
)

#: The automatic shift sits this fraction below the estimated lowest frequency.
SHIFT_MARGIN = 2e-4
#: Factors applied to the automatic shift while too many frequencies lie below it.
SHIFT_RETREAT = (0.98, 0.8)
#: Floor of ‖M‖₁ in the frequency scale √(‖K‖₁/‖M‖₁) (no division by zero).
TINY_NORM = 1e-300


class Eigenpairs(NamedTuple):
    """What :func:`solve_qep` computes (fields as in
    :class:`gyroshell.results.modes.GyroscopicModes`)."""

    eigenvalues: np.ndarray
    vectors: np.ndarray
    residuals: np.ndarray
    supercritical: bool
    damped: bool
    info: dict


def solve_qep(M, G, K, count: int, *, sigma=None, C=None, estimate: float | None = None,
              definite: bool | None = None, start=None,
              options: SolverOptions | None = None, shift_factor=None,
              checked: bool = False) -> Eigenpairs:
    """Eigenpairs of (λ²M + λ(G + C) + K) φ = 0 nearest a shift on the imaginary axis.

    The arguments and the errors are those of
    :func:`gyroshell.engines.gyroscopic.gyroscopic_modes` (see there), the tuning knobs
    gathered in ``options`` (default :class:`SolverOptions`). ``shift_factor``, with an
    explicit ``sigma`` = iω_s, undamped and K > 0: a factorization of the Hermitian
    Q(iω_s) = K − ω_s²M + iω_sG that already counted its negative eigenvalues (an
    :class:`~gyroshell.linalg.inertia.InertiaFactor` or a CHOLMOD
    :class:`~gyroshell.linalg.cholesky.LDLFactor`, e.g. the one an inertia count made),
    solved with instead of factoring Q(iω_s) again; the caller keeps (and releases) it.
    ``checked``: M, G, K (no C) are CSR matrices of floats whose structure the caller has
    already proved (:func:`check_structure`, e.g. once per model for the mirror halves of
    :mod:`gyroshell.engines.eigen`); only the memory estimate is made here.
    """
    options = SolverOptions() if options is None else options
    factorization = check_factorization(options.factorization)
    # Out-of-range scales surface as non-finite results, refused in _finish; no warnings.
    with blas_threads(1), np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        if checked and C is None:
            check_memory(M.shape[0], M.nnz + G.nnz + K.nnz, count)
        else:
            M, G, K, C = check_structure(M, G, K, C, count=count)
        prob = Problem(M, G, K, C, check_count(count, M.shape[0]), check_tol(options.tol),
                       check_optional_int("ncv", options.ncv),
                       check_optional_int("maxiter", options.maxiter),
                       check_start(start, M.shape[0]), {"operator_applications": 0},
                       shift_factor=shift_factor)
        shift = check_shift(sigma)
        if shift_factor is not None and (shift is None or shift == 0 or C is not None):
            raise ParameterError("shift_factor needs an explicit sigma = i*omega_s > 0 and "
                                 "no damping")
        if options.method not in METHODS:
            raise ParameterError(f"method must be 'auto', 'lanczos' or 'arpack', got "
                                 f"{options.method!r}")
        if prob.C is None and prob.K.count_nonzero() == 0:
            lams, vecs = without_stiffness(prob, shift)
            return _finish(prob, lams, vecs, supercritical=True, damped=False)
        if prob.n <= DENSE_LIMIT:
            lams, vecs, definite = solve_dense(prob, shift, definite)
            return _finish(prob, lams, vecs, supercritical=not definite,
                           damped=prob.C is not None)
        return _solve_factored(prob, shift, estimate, definite, options.method,
                               resolve_factorization(factorization))


def _solve_factored(prob: Problem, shift, estimate, definite, method: str,
                    factorization: str) -> Eigenpairs:
    """The sparse paths with ``factorization``; a CHOLMOD run that fails is run again on
    SuperLU."""
    prob.factorization = factorization
    prob.info["factorization"] = factorization
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
        prob.shift_factor = None
        prob.info.clear()
        prob.info.update(operator_applications=0, factorization="superlu",
                         cholmod_fallback=True)
        return _solve_sparse(prob, shift, estimate, definite, method)
    finally:
        prob.release()


def _solve_sparse(prob: Problem, shift, estimate, definite, method) -> Eigenpairs:
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
    lams, vecs, res = _subcritical(prob, shift, estimate, k_factor, method)
    return _finish(prob, lams, vecs, supercritical=False, damped=False, residuals=res)


def _hermitian_shift(prob: Problem, estimate: float | None, shift: complex | None,
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
        if shift is not None and prob.shift_factor is not None:
            factor = prob.shift_factor   # counted by the caller at this shift
            prob.info["shift_factor_reused"] = True
        else:
            factor = prob.factor(prob.K - omega_s**2 * prob.M + 1j * omega_s * prob.G)
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


def _factor_stiffness(prob: Problem, definite: bool | None, *, need: bool
                      ) -> InertiaFactor | None:
    if definite is True and not need:
        return None
    return prob.factor(prob.K)


def _k_definite(k_factor: InertiaFactor | None, definite: bool | None) -> bool:
    if definite is not None:
        return definite
    return k_factor is not None and k_factor.definite


def _omega_ref(prob: Problem, estimate: float | None) -> float:
    """A frequency scale for the state scaling, rad/s: the estimate, else √(‖K‖/‖M‖)."""
    if estimate is not None and estimate > 0 and math.isfinite(estimate):
        return float(estimate)
    ratio = norm1(prob.K) / max(norm1(prob.M), TINY_NORM)
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
    result = None if use_arpack else solve_hermitian(prob, omega_s, factor, below)
    if result is not None:
        lams, vecs, res, defect = _polished_pairs(prob, *result, omega_s, estimate)
        prob.info["lanczos_residual"] = float(res.max())
        if res.max() > LANCZOS_RESIDUAL_LIMIT:
            result = None
    if result is None:
        if method == "lanczos":
            raise ConvergenceError("Lanczos did not converge; try method='arpack'")
        if omega_s == 0:
            result = solve_pairs_real(prob, factor, _omega_ref(prob, estimate))
        else:
            result = solve_shifted_pairs(prob, omega_s, factor, below,
                                          _omega_ref(prob, omega_s))
        lams, vecs, res, defect = _polished_pairs(prob, *result, omega_s, estimate)
    prob.info["pair_defect"] = defect
    if defect > PAIR_DEFECT_LIMIT:
        raise ConvergenceError(f"eigenvalues off the imaginary axis below critical "
                               f"(|Re λ|/|λ| = {defect:.1e}); "
                               "try a larger ncv or a smaller tol")
    return lams, vecs, res


def _polished_pairs(prob: Problem, lams, vecs, omega_s: float, estimate):
    """(iω from the quadratic Rayleigh functional, the vectors, their backward errors at
    iω, the pair defect max |Re λ|/|λ|), from one product of each matrix with the vectors."""
    done = products(prob.M, prob.G, prob.K, vecs)
    lams = quadratic_rayleigh(prob.M, prob.G, prob.K, lams, vecs, products_of=done)
    scale = np.maximum(np.abs(lams), omega_s or _omega_ref(prob, estimate))
    defect = float(np.max(np.abs(lams.real) / scale))
    lams = 1j * np.abs(lams.imag)
    res = relative_residuals(prob.M, prob.G, prob.K, lams, vecs, products_of=done)
    return lams, vecs, res, defect


def _supercritical(prob, k_factor, estimate):
    """K indefinite, undamped: the eigenvalues nearest zero by ARPACK about σ = 0."""
    _require_solvable(k_factor, "K")
    prob.info.update(shift=0j, below_shift=None)
    lams, vecs = solve_general(prob, 0j, k_factor.solve, _omega_ref(prob, estimate),
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
        Q = (prob.K + 1j * omega_s * prob.GC - omega_s**2 * prob.M).tocsc()
        try:
            lu = splu(Q)
        except RuntimeError:
            raise ParameterError(f"the shift i*{omega_s:g} rad/s is an eigenvalue; "
                                 "move the shift") from None
        prob.info["factor_time"] += time.perf_counter() - t0
        solve = lu.solve
    return solve_general(prob, 1j * omega_s, solve, _omega_ref(prob, estimate or omega_s),
                          symmetric_pairs=False)


def _finish(prob: Problem, lams, vecs, *, supercritical: bool, damped: bool,
            residuals: np.ndarray | None = None) -> Eigenpairs:
    """Normalized vectors and the backward errors checked (``residuals``: already computed
    for exactly these eigenvalues; scaling a vector leaves its relative residual as is)."""
    with np.errstate(all="ignore"):  # overflow is reported below, not as a warning
        vecs = normalize(np.asarray(vecs, dtype=complex))
        if damped:
            lams = quadratic_rayleigh(prob.M, prob.GC, prob.K, lams, vecs)
        res = residuals if residuals is not None else relative_residuals(
            prob.M, prob.GC, prob.K, lams, vecs)
    if not (np.all(np.isfinite(lams)) and np.all(np.isfinite(res))):
        raise ConvergenceError("eigenvalues out of floating-point range: the matrices' "
                               "scales (stiffness, damping, mass) are too far apart")
    prob.info["max_residual"] = float(res.max())
    if res.max() > RESIDUAL_LIMIT:
        raise ConvergenceError(
            f"eigenpairs not accurate: largest relative residual {res.max():.2e} > "
            f"{RESIDUAL_LIMIT:g}; try a larger ncv or a smaller tol")
    return Eigenpairs(np.asarray(lams, dtype=complex), vecs, res, supercritical, damped,
                      prob.info)
