"""The tape's gyroscopic eigenproblem (λ² M + λ (G(V) + C) + K(V)) φ = 0: frequencies, modes.

Below the critical speed K(V) is positive definite and, G being skew-symmetric, every
undamped eigenvalue is a pair ±iω (ω > 0, rad/s) with eigenvectors φ, φ̄: the tape vibrates
but neither grows nor decays. Above it some eigenvalues may leave the imaginary axis
(divergence or flutter), or all stay on it (gyroscopic stabilization).

:func:`modes` is a thin layer over the matrix solver :func:`gyroshell.gyroscopic_modes`
(method, certificate and accuracy: see there). It adds what the tape knows: the automatic
shift i·ω_s just below the bottom of the width-uniform travelling-wave band (with σ = 0
the dozens of long-tape modes within 0.1 % of √(k/ρ) are nearly equal in |1/λ| and converge
slowly; measured from iω_s they are far apart), the definiteness of K(V) from a bound proved
once per model (:func:`stiffness_floor`), the damping matrix, and the tape's mirror symmetry
about its centre line (:mod:`gyroshell.tape.mirror`): below critical and undamped, the symmetric
and antisymmetric modes are computed on two problems of half the size, the antisymmetric
ones only as many as the inertia of their half counts below the symmetric ones
(:func:`_mirror_modes`). The factorization that counts them (CHOLMOD's LDLᴴ of
Q_a(iω̄), or SuperLU's) also serves their Lanczos solve, shifted at iω̄: the frequencies
wanted are then the extreme ones just below the shift, and no second factorization is made
(L_x/L_y = 19, V = 50 m/s: 41 half-size solves instead of 49). Above √(T/ρ), where the
stiffness floor does not cover the speed, the halves' K_s(V) and K_a(V) are proved
definite by a half-width Cholesky each (:func:`_halves_definite`) instead of factoring the
full K(V) and solving the full problem.
"""

from __future__ import annotations

import math
import time
import weakref

import numpy as np
import scipy.sparse as sp

from ..core import validation
from ..core.errors import ConvergenceError, ParameterError
from ..linalg import cholesky
from ..linalg.factorization import check_factorization, resolve_factorization
from ..linalg.inertia import factor_inertia, proved_definite
from ..linalg.qep import (
    DEFAULT_TOL,
    RESIDUAL_LIMIT,
    SHIFT_MARGIN,
    SolverOptions,
    check_count,
    check_family,
    max_count,
    normalize,
    solve_qep,
)
from ..linalg.qep import relative_residuals as _matrix_residuals
from ..linalg.qep.spectrum import norm1
from ..results.modes import GyroscopicModes, Modes
from ..tape.grid import Grid
from ..tape.mirror import mirror_split
from ..tape.model import TapeModel, check_model
from ..tape.parameters import TapeParameters, check_velocity
from .gyroscopic import gyroscopic_modes

__all__ = ["DEFAULT_TOL", "RESIDUAL_LIMIT", "SHIFT_MARGIN", "Modes", "SolverOptions",
           "check_speed", "damping_operator",
           "frequencies", "max_count", "modes", "relative_residuals", "stiffness_floor",
           "strip_frequency_estimate"]


# ----- small pieces -----------------------------------------------------------------------
def strip_frequency_estimate(params: TapeParameters, grid: Grid, velocity: float) -> float:
    """Bottom of the width-uniform travelling-wave band, rad/s (an estimate of ω₁).

    min over the discrete wavenumbers α_m = mπ/L_x of −Vα + √((Dα⁴ + Tα² + k)/ρ), the
    lowest frequency of a beam on the shell foundation moving at V (Wickert & Mote's
    dispersion relation plus k), D = D11 for an orthotropic or layered tape (cylindrical
    bending). Returns 0 if that is not positive (V near or above critical).
    """
    m = np.arange(1, grid.nx)
    alpha = m * np.pi / grid.length
    with np.errstate(all="ignore"):
        w = -velocity * alpha + np.sqrt(
            (params.D * alpha**4 + params.tension * alpha**2 + params.k) / params.density)
    best = float(np.min(w))
    return best if best > 0 and math.isfinite(best) else 0.0


def _mass(model) -> sp.dia_matrix:
    return sp.diags(model.mass_diagonal)


def relative_residuals(model: TapeModel, velocity: float, eigenvalues: np.ndarray,
                       vectors: np.ndarray, damping=None) -> np.ndarray:
    """‖(λ²M + λ(G + C) + K)φ‖₂ / ((|λ|²‖M‖₁ + |λ|‖G + C‖₁ + ‖K‖₁) ‖φ‖₂) per pair."""
    GC = model.G(velocity)
    C = damping_operator(model, velocity, damping)
    if C is not None:
        GC = GC + C
    return _matrix_residuals(_mass(model), GC, model.K(velocity), np.asarray(eigenvalues),
                             np.asarray(vectors))


def damping_operator(model, velocity: float, damping) -> sp.spmatrix | None:
    """C, kg/s, for ``damping`` at speed V (None: undamped), via :mod:`gyroshell.tape.damping`.

    ``damping`` is a :class:`gyroshell.Damping`, a viscous coefficient c >= 0 in
    N·s/m³ (C = c W, a damping pressure c ∂w/∂t), or a pair (a, b) for Rayleigh damping
    C = a M + b K(V) with a >= 0 in 1/s and b >= 0 in s.
    """
    from ..tape.damping import Damping, damping_matrix, rayleigh

    if isinstance(damping, (tuple, list)):
        if len(damping) != 2:
            raise ParameterError("Rayleigh damping must be a pair (a in 1/s, b in s), "
                                 f"got {damping!r}")
        damping = rayleigh(*damping)
    elif damping is not None and not isinstance(damping, Damping) and (
            isinstance(damping, bool) or not isinstance(damping, (int, float, np.number))):
        raise ParameterError("damping must be a real number >= 0 N*s/m^3, a pair (a, b) or "
                             f"a Damping, got {damping!r}")
    return damping_matrix(model, velocity, damping)


def check_speed(model, velocity: float) -> float:
    """A valid tape speed for ``model``, m/s: finite, >= 0, and ρV² representable."""
    velocity = check_velocity(velocity)
    if not math.isfinite(model.params.density * velocity * velocity):
        raise ParameterError(f"velocity {velocity:g} m/s is out of range: rho V^2 overflows")
    return velocity


#: Per model, τ >= 0 with A − τB proved positive definite by inertia (see stiffness_floor).
_FLOORS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def stiffness_floor(model: TapeModel, *, near_divergence: bool = False) -> float | None:
    """τ >= 0, N/m, with A − τB proved positive definite; None if A itself is not.

    K(V) = (A − τB) + (τ + T − ρV²) B with B positive semi-definite, so K(V) is positive
    definite whenever ρV² − T < τ: one proof per model certifies every such speed, and the
    eigen-solver skips factoring K(V). τ = 0 holds by construction when k > 0: the bending
    part of A is a sum of Gram forms (w_xx, w_yy)ᵀ[[D11, D12], [D12, D22]](w_xx, w_yy) + ...
    with a positive-definite bending matrix (isotropic: D[[1, ν], [ν, 1]], |ν| < 1;
    :func:`gyroshell.bending_foundation`), so A >= kW > 0; otherwise a
    factorization of A decides. With ``near_divergence``, τ is the inertia-proved shift just
    below μ_min of the divergence solver (a few half-width factorizations, worth it for
    sweeps).
    Cached per model.
    """
    known = _FLOORS.get(model)
    if known is not None and (known > 0 or known == -math.inf or not near_divergence):
        return None if known == -math.inf else known
    if not (hasattr(model, "A") and hasattr(model, "B")):
        return None
    tau = None
    if near_divergence:
        from .divergence import proved_shift

        tau = proved_shift(model)
    if tau is None and model.params.k > 0:
        tau = 0.0
    if tau is None:
        tau = 0.0 if factor_inertia(model.A).definite else -math.inf
    _FLOORS[model] = tau
    return None if tau == -math.inf else tau


def _known_definite(model, velocity: float) -> bool | None:
    """True if the model's stiffness floor proves K(V) positive definite, else None."""
    tau = stiffness_floor(model)
    if tau is None:
        return None
    p = model.params
    return True if p.density * velocity**2 - p.tension < tau else None


# ----- the solver -------------------------------------------------------------------------
#: Symmetric modes asked for beyond the previous speed's number (continuation).
MIRROR_HINT_MARGIN = 1


def modes(model: TapeModel, velocity: float = 0.0, count: int = 6, *,
          sigma: complex | str = "auto", damping=None, start: Modes | None = None,
          estimate: float | None = None, symmetry: bool = True, progress: bool | None = None,
          options: SolverOptions | None = None, **tuning) -> Modes:
    """Lowest ``count`` frequencies and complex mode shapes of the tape at speed V.

    Parameters
    ----------
    model : TapeModel
    velocity : float
        Tape speed V, m/s (>= 0).
    count : int
        Number of frequencies (pairs ±iω), 1 <= count <= :func:`max_count` (n).
    sigma : "auto", 0 or complex i·ω_s
        Shift, 1/s. ``"auto"``: just below the estimated lowest frequency, certified by the
        inertia of Q(iω_s). ``0``: one factorization of K, the ±iω pairs found together.
    damping : Damping, float or (a, b), optional
        See :func:`damping_operator`. Damped eigenvalues are −δ + iω_d (``decay_rate`` δ,
        ``damping_ratio``); the count certificate does not apply to them.
    start : Modes, optional
        Modes at a nearby speed: their vectors start the iteration (continuation).
    estimate : float, optional
        Estimate of the lowest frequency for the automatic shift, rad/s (still certified by
        inertia); default :func:`strip_frequency_estimate`.
    symmetry : bool
        Solve on the mirror-symmetric halves where that applies (module notes; the same
        modes to round-off); False solves the full problem.
    options : SolverOptions, optional
        The tuning knobs together; ``**tuning`` gives any of them (``tol``, ``ncv``,
        ``maxiter``, ``method``, ``factorization``) by name, replacing the one in ``options``.
    progress : bool or None
        As for every engine (True, False or None); one eigen-solve shows no progress.

    Returns
    -------
    Modes
        Above critical (K(V) indefinite) ``supercritical`` is True, the eigenvalues are
        those nearest zero, and ``stability`` tells divergence, flutter or stable.

    Raises
    ------
    ParameterError
        Not a model, bad count, sigma, tol, ncv, damping or progress.
    ConvergenceError
        No convergence, or the residuals or the mode count failed.
    """
    opts = SolverOptions.of(options, **tuning)
    velocity = _check_modes(model, velocity, count, opts, progress)
    C = damping_operator(model, velocity, damping)
    estimate, shift, first = _checked_guesses(model, velocity, sigma, start, estimate)
    if check_flag("symmetry", symmetry) and C is None and shift is None:
        result = _try_mirror(model, velocity, count, start, first, estimate, opts)
        if result is not None:
            return result
    result = gyroscopic_modes(_mass(model), model.G(velocity), model.K(velocity), count,
                              sigma=shift, C=C, estimate=estimate if estimate > 0 else None,
                              definite=_known_definite(model, velocity), start=first,
                              options=opts)
    return Modes(model.grid, velocity, result.eigenvalues, result.vectors, result.residuals,
                 result.supercritical, result.info, result.damped)


def _check_modes(model, velocity: float, count: int, opts: SolverOptions, progress) -> float:
    """The checks of :func:`modes`, before any assembly (a refusal costs nothing): the model
    (:func:`gyroshell.tape.model.check_model`), speed, count, factorization and progress;
    returns the speed, m/s."""
    velocity = check_speed(check_model(model), velocity)
    check_count(count, model.unknowns)
    check_factorization(opts.factorization)
    validation.progress(progress)
    return velocity


def check_flag(name: str, value) -> bool:
    """``value`` if it is True or False, else a ParameterError naming ``name``."""
    return validation.boolean(name, value)


def _checked_guesses(model: TapeModel, velocity: float, sigma, start: Modes | None,
                     estimate: float | None):
    """(estimate in rad/s, shift or None for automatic, start pairs or None), validated."""
    if estimate is None:
        estimate = strip_frequency_estimate(model.params, model.grid, velocity)
    else:
        estimate = validation.nonnegative("estimate", estimate, "rad/s")
    shift = None if isinstance(sigma, str) and sigma == "auto" else sigma
    if isinstance(sigma, str) and sigma != "auto":
        raise ParameterError(f"sigma must be 'auto', 0 or i*omega_s, got {sigma!r}")
    first = None
    if start is not None:
        if not isinstance(start, Modes) or start.vectors.shape[0] != model.unknowns:
            raise ParameterError("start must be the Modes of the same model")
        first = (start.eigenvalues, start.vectors)
    return estimate, shift, first


def _try_mirror(model: TapeModel, velocity: float, count: int, start: Modes | None, first,
                estimate: float, options: SolverOptions) -> Modes | None:
    """The modes from the mirror-symmetric halves (undamped, automatic shift), or None where
    the halves do not apply: K(V) not proved definite, ARPACK asked for, no mirror symmetry,
    too many modes for a half, or the counts did not close."""
    if options.method not in ("auto", "lanczos") or options.ncv is not None or \
            options.maxiter is not None:
        return None
    known = _known_definite(model, velocity)
    split = mirror_split(model)
    if split is None or count > max_count(split.antisymmetric.shape[1]):
        return None
    if not known and not _halves_definite(model, split, velocity, options.factorization):
        return None
    # a previous speed's split (continuation) says how many are symmetric
    previous = (start.info.get("mirror") or {}) if start else {}
    hint = previous.get("symmetric")
    guess = count if hint is None else min(count, hint + MIRROR_HINT_MARGIN)
    # none of the previous speed's antisymmetric frequencies below its ω̄: a Cholesky of
    # Q_a(iω̄) is tried first (it proves the count zero by succeeding, at about half the
    # cost of the LDLᴴ that counts and solves)
    none_below = previous.get("antisymmetric_below") == 0
    for symmetric in dict.fromkeys((guess, count)):
        result = _mirror_modes(model, split, velocity, count, first, estimate, symmetric,
                               options, none_below)
        if result is not None:
            return result
    return None


def _halves_definite(model: TapeModel, split, velocity: float, factorization: str) -> bool:
    """True if K_s(V) and K_a(V) are proved positive definite (one half-width Cholesky, or
    SuperLU's inertia, each), hence K(V) = P_s K_s P_sᵀ + P_a K_a P_aᵀ: a speed above
    √(T/ρ) that the model's stiffness floor does not cover runs on the halves without a
    full-size factorization of K(V) (L_x/L_y = 19: two half-width Choleskys of K_h, ~15 ms
    each, against the full K(V)'s and a full-size solve)."""
    return all(proved_definite(split.matrices(model, velocity, w)[2], factorization,
                               fallback=False) for w in ("symmetric", "antisymmetric"))


def _mirror_modes(model: TapeModel, split, velocity: float, count: int, start, estimate,
                  symmetric: int, options: SolverOptions, none_below: bool = False
                  ) -> Modes | None:
    """The lowest ``count`` modes of a mirror-symmetric tape below critical, from its halves.

    The symmetric half gives its ``symmetric`` lowest frequencies, up to ω̄; the inertia of
    the antisymmetric half's Q_a(iω̄) counts its frequencies below ω̄ (Sylvester, K_a > 0),
    and that many (at most ``count``) are computed there (often none: the width-uniform
    travelling waves are symmetric). Every frequency below ω̄ is then known; if they are at
    least ``count`` (always when ``symmetric`` = ``count``), the ``count`` lowest of the
    tape are among them. None if they are fewer, or if the count is not available (SuperLU
    pivoted off the diagonal): the caller asks for more or solves the full problem.
    """
    checked = _prove_halves(model, split)
    halves = {}
    for which in ("symmetric", "antisymmetric"):
        M, G, K = split.matrices(model, velocity, which)
        first = None if start is None else (start[0], split.half(which).T @ start[1])
        halves[which] = (M, G, K, first)
    guess = estimate if estimate > 0 else None
    M, G, K, first = halves["symmetric"]
    sym = GyroscopicModes(*solve_qep(M, G, K, symmetric, estimate=guess, definite=True,
                                     start=first, options=options, checked=checked))
    omega_bar = float(sym.omega[-1])
    M, G, K, first = halves["antisymmetric"]
    t0 = time.perf_counter()
    factor, counted_by = _count_below(K - omega_bar**2 * M + 1j * omega_bar * G,
                                      options.factorization, none_below)
    count_time = time.perf_counter() - t0
    try:
        below = factor.negatives
        if below is None or symmetric + below < count:
            return None
        parts = [(sym, split.symmetric, halves["symmetric"][:3])]
        if below:
            anti = _below_count_frequency(M, G, K, min(below, count), omega_bar, factor,
                                          first, guess, options, checked)
            if np.any(anti.omega >= omega_bar):   # the count and the solve disagree
                return None
            parts.append((anti, split.antisymmetric, (M, G, K)))
    finally:
        if hasattr(factor, "release"):
            factor.release()
    return _joined(model, split, velocity, count, parts, {
        "antisymmetric_below": below, "count_frequency": omega_bar,
        "count_factorization": counted_by,
        "count_by_cholesky": isinstance(factor, cholesky.CholeskyFactor) and not isinstance(
            factor, cholesky.LDLFactor),
        "count_factor_solved": bool(below and anti.info.get("shift_factor_reused")),
        "count_time": count_time})


def _joined(model: TapeModel, split, velocity: float, count: int, parts: list,
            mirror: dict) -> Modes:
    """The ``count`` lowest of the halves' modes (``parts``: (result, embedding, (M_h, G_h,
    K_h)) triples, the symmetric first), with the halves' costs summed and ``mirror``
    added to the info.

    The backward errors are the full problem's, ‖Q(λ) P_hφ‖₂ / (s(λ) ‖P_hφ‖₂) with the
    full matrices' norms in s(λ) = |λ|²‖M‖₁ + |λ|‖G‖₁ + ‖K‖₁, obtained from the halves'
    own: Q(λ) P_h = P_h Q_h(λ) (the split's invariance, checked when it was made) and P_h
    has orthonormal columns, so ‖Q(λ) P_hφ‖₂ = ‖Q_h(λ) φ‖₂ and ‖P_hφ‖₂ = ‖φ‖₂, and each
    half's backward error ‖Q_h(λ)φ‖₂ / (s_h(λ) ‖φ‖₂) (computed by its solve for exactly
    these λ and φ, up to the scaling of φ, which it does not depend on) is rescaled by
    s_h(λ) / s(λ): no second pass of products over the vectors, no full-size assembly."""
    sym = parts[0][0]
    lam = np.concatenate([r.eigenvalues for r, _, _ in parts])
    source = np.concatenate([np.full(r.count, k) for k, (r, _, _) in enumerate(parts)])
    column = np.concatenate([np.arange(r.count) for r, _, _ in parts])
    order = np.argsort(np.abs(lam.imag), kind="stable")[:count]
    lam = lam[order]
    vecs = np.empty((model.unknowns, count), dtype=complex)
    numerators = np.empty(count)   # ‖Q_h(λ)φ‖₂ / ‖φ‖₂ of each kept pair
    size = np.abs(lam)
    for k, (r, P, (M, G, K)) in enumerate(parts):
        mine = np.flatnonzero(source[order] == k)
        kept = column[order[mine]]
        vecs[:, mine] = P @ r.vectors[:, kept]
        half_scale = size[mine]**2 * norm1(M) + size[mine] * norm1(G) + norm1(K)
        numerators[mine] = r.residuals[kept] * half_scale
    vecs = normalize(vecs)
    res = numerators / _residual_scale(model, split, velocity, size)
    info = dict(sym.info)
    for key in ("factor_time", "solve_time", "substitution_time", "operator_applications"):
        info[key] = sum(r.info.get(key, 0) or 0 for r, _, _ in parts)
    # the count's factorization is the antisymmetric half's (its solves reuse it)
    info["factor_time"] += mirror["count_time"]
    info.update(max_residual=float(res.max()), mirror={
        "symmetric": int(np.count_nonzero(order < sym.count)),
        "antisymmetric": int(np.count_nonzero(order >= sym.count)), **mirror})
    return Modes(model.grid, velocity, lam, vecs, res, False, info, False)


def _residual_scale(model: TapeModel, split, velocity: float, size: np.ndarray
                    ) -> np.ndarray:
    """|λ|²‖M‖₁ + |λ|‖G(V)‖₁ + ‖K(V)‖₁ of the full undamped problem for |λ| = ``size``,
    from the mirror split's norms of the full matrices (‖G(V)‖₁ = V ‖G(1 m/s)‖₁, G being
    linear in V; ‖K(V)‖₁ without assembling K(V))."""
    mass = float(np.max(np.abs(model.mass_diagonal)))
    return (size**2 * mass + size * velocity * split.gyroscopic_norm
            + split.stiffness_norm(model.effective_tension(velocity)))


#: Per model, the mirror split whose halves' structure :func:`_prove_halves` proved (or,
#: the first time, saw: with the flag False).
_PROVED: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _prove_halves(model: TapeModel, split) -> bool:
    """True if every speed's halves (M_h, V G_h(1), A_h + τB_h) are proved to have the
    solver's structure (:func:`gyroshell.linalg.qep.check_family`), so that each solve on
    them may skip the checks (``checked=True``). The proof is made the second time a
    model's halves are solved (a sweep, a critical-speed search): a single solve checks
    its own matrices as before, at the same cost."""
    seen = _PROVED.get(model)
    if seen is not None and seen[0] is split:
        if not seen[1]:
            for which in ("symmetric", "antisymmetric"):
                M, G1, _ = split.matrices(model, 1.0, which)
                check_family(M, G1, *split.stiffness(which))
            _PROVED[model] = (split, True)
        return True
    _PROVED[model] = (split, False)
    return False


def _count_below(Q: sp.spmatrix, factorization: str, none_expected: bool = False):
    """The factorization of the Hermitian Q that counts its negative eigenvalues
    (``negatives``) and solves with it, and its back-end: CHOLMOD's LDLᴴ (where selected;
    the caller releases it), else (or if it has no answer) SuperLU's (``negatives`` None
    where it pivoted off the diagonal). With ``none_expected``, CHOLMOD's supernodal
    Cholesky is tried first: its success proves Q > 0 (``negatives`` 0)."""
    if resolve_factorization(factorization) == "cholmod":
        if none_expected:
            factor = cholesky.cholesky(Q)
            if factor is not None:
                return factor, "cholmod"
        factor = cholesky.ldl(Q)
        if factor is not None:
            return factor, "cholmod"
    return factor_inertia(Q), "superlu"


def _below_count_frequency(M, G, K, count: int, omega_bar: float, factor, start,
                           estimate, options: SolverOptions, checked: bool = False):
    """The ``count`` lowest modes of the antisymmetric half, all below ω̄ (rad/s), by
    Lanczos shifted at iω̄ with the count's own factorization of Q_a(iω̄) (no second
    factorization; the frequencies wanted are the extreme ones just below the shift).
    Where that does not converge (Q_a(iω̄) nearly singular: an antisymmetric frequency at
    ω̄), the automatic shift below the lowest frequency is used instead."""
    try:
        pairs = solve_qep(M, G, K, count, sigma=1j * omega_bar, definite=True, start=start,
                          options=options, shift_factor=factor, checked=checked)
        return GyroscopicModes(*pairs)
    except (ConvergenceError, ParameterError):
        return GyroscopicModes(*solve_qep(M, G, K, count, estimate=estimate, definite=True,
                                          start=start, options=options,
                                          checked=checked))


def frequencies(model: TapeModel, velocity: float = 0.0, count: int = 6, **options
                ) -> np.ndarray:
    """The lowest ``count`` angular frequencies ω, rad/s, ascending (see :func:`modes`;
    ``options`` include ``progress``)."""
    return modes(model, velocity, count, **options).omega
