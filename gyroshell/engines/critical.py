"""Critical speed of the moving tape, two independent ways, with the classical estimates.

(a) Eigenvalue route: the speed where the lowest frequency reaches zero, by bracketing
    and root-finding on V with the gyroscopic eigen-solver. ω(V) → 0 like √(V_c − V), so
    the root is sought for the smooth f(V) = −λ₀² (λ₀ the eigenvalue nearest zero):
    f = ω₁² > 0 below critical, −(Re λ₀)² < 0 above (divergence).
(b) Divergence route: K(V) = A + (T − ρV²)B loses definiteness at V_div = √((T + μ_min)/ρ)
    (:func:`gyroshell.divergence`, ``eigsh`` on the mirror halves).

:func:`critical_speeds` runs (b) first and starts (a) just below its speed (DIVERGENCE_GAP),
on the half that holds the buckling mode: (a) still finds its own zero of ω₁² by
extrapolating its eigen-solves and brackets it by a sign change, the point above proved by
an inertia count of K(V) (f <= 0 exactly where K(V) is not positive definite). L_x/L_y =
19: 3 eigen-solves and one count instead of 8 eigen-solves from :func:`default_guess`.

For a conservative gyroscopic system an eigenvalue is zero exactly when K is singular, so
the two must agree; they are computed by different algorithms and compared.

Context values: √(T/ρ) (moving string or beam, Wickert & Mote 1990: about 80 m/s), the
infinite strip on the shell foundation √((T + 2√(Dk))/ρ), Sundaram & Benson's 111 m/s and
the seed paper's "just above 100 m/s".
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..core import validation
from ..core.errors import ConvergenceError, SingularError
from ..linalg import cholesky
from ..linalg.factorization import resolve_factorization
from ..linalg.inertia import factor_inertia, proved_definite
from ..results.critical import PAPER_SPEED, SUNDARAM_BENSON_SPEED, CriticalSpeeds
from ..tape.mirror import mirror_split
from ..tape.model import TapeModel, check_model
from .divergence import DIVERGENCE_MEMBERS, beam_mu_estimate, divergence, proved_above
from .eigen import check_speed, modes
from .gyroscopic import gyroscopic_modes

__all__ = ["PAPER_SPEED", "SUNDARAM_BENSON_SPEED", "CriticalSpeeds", "critical_function",
           "critical_speed_eigen", "critical_speeds", "default_guess"]


def _evaluate(model: TapeModel, velocity: float, count: int, options: dict
              ) -> tuple[float, np.ndarray]:
    """f(V) (see :func:`critical_function`) and the eigenvector of the eigenvalue it uses."""
    # ARPACK on the linearization: near critical K(V) is nearly singular, and the energy
    # inner product of the Lanczos path degenerates with it.
    options = {"sigma": 0, "method": "arpack", **options}
    try:
        return _f_of(modes(model, velocity, count, **options))
    except SingularError:  # K(V) exactly singular: λ = 0, V is the critical speed
        return 0.0, np.zeros(model.unknowns)


def _f_of(result) -> tuple[float, np.ndarray]:
    """f and the vector it uses, from the eigenvalues nearest zero of one solve."""
    lam = result.eigenvalues
    if not result.supercritical:
        return float(result.omega[0] ** 2), result.vectors[:, 0]
    j = int(np.argmax(lam.real))
    if lam[j].real > 0:
        return float(-(lam[j].real ** 2)), result.vectors[:, j]
    return float(-abs(lam[0]) ** 2), result.vectors[:, 0]


def _proved_definite(K, factorization: str) -> bool:
    """True if the symmetric K is proved positive definite (:func:`proved_definite`)."""
    return proved_definite(K, factorization)


def _proved_indefinite(K, factorization: str) -> bool:
    """True if the symmetric K is proved not positive definite: SuperLU's inertia counts a
    negative pivot or finds K singular (a Cholesky that succeeds proves the opposite at
    once, where CHOLMOD is selected); False where the count is unknown."""
    if resolve_factorization(factorization) == "cholmod":
        factor = cholesky.cholesky(K)
        if factor is not None:
            factor.release()
            return False
        counted = cholesky.negative_count(K)   # LDLᵀ: the count, 2.5x faster than SuperLU
        if counted is not None:
            return counted > 0
    factor = factor_inertia(K)
    return factor.singular or (factor.negatives is not None and factor.negatives > 0)


#: Options of ``modes`` under which the root search may use the mirror-symmetric halves.
_HALF_OPTIONS = {"factorization", "tol"}


class _HalfCritical:
    """f on the mirror-symmetric half (:mod:`gyroshell.tape.mirror`) that reaches zero first.

    The two halves' frequencies together are the tape's, so f = min(f_s, f_a). The first
    evaluation computes both and keeps the half with the smaller f; later evaluations solve
    only that half while the other half's K_h(V) is proved positive definite (a Cholesky,
    or SuperLU's inertia): its frequencies are then all real and nonzero, so the kept
    half's f has the same zero as the tape's (its value can exceed the tape's ω₁² far below
    the root, where the other half holds the lowest frequency). If the other half's K_h is
    not definite, both are computed again and the choice is renewed.
    """

    def __init__(self, model: TapeModel, split, count: int, options: dict,
                 which: str | None = None, extra: dict | None = None) -> None:
        self.model, self.split, self.count = model, split, count
        self.options = {"sigma": 0, "method": "arpack", **(extra or {}), **options}
        self.which: str | None = which

    def _half(self, which: str, velocity: float) -> float:
        M, G, K = self.split.matrices(self.model, velocity, which)
        try:
            result = gyroscopic_modes(M, G, K, self.count, **self.options)
        except SingularError:  # K_h(V) exactly singular: λ = 0, this is the root
            return 0.0
        return _f_of(result)[0]

    def _definite(self, which: str, velocity: float) -> bool:
        p = self.model.params
        if p.density * velocity**2 - p.tension <= proved_above(self.model).get(which, -math.inf):
            return True   # route (b) proved A_h − μB_h > 0, hence K_h(V) for ρV² − T <= μ
        K = self.split.matrices(self.model, velocity, which)[2]
        return _proved_definite(K, self.options.get("factorization", "auto"))

    def definite(self, velocity: float) -> bool:
        """True if both halves' K_h(V), hence K(V), are proved positive definite."""
        return all(self._definite(w, velocity) for w in (self.which or "symmetric",
                   "antisymmetric" if self.which == "symmetric" else "symmetric"))

    def indefinite(self, velocity: float) -> bool:
        """True if K(V) is proved not positive definite (f(V) <= 0 without an eigen-solve:
        for a conservative gyroscopic system some λ² >= 0 exactly when K(V) is not
        positive definite): a half, the kept one first, whose K_h(V) is not."""
        first = self.which or "symmetric"
        other = "antisymmetric" if first == "symmetric" else "symmetric"
        factorization = self.options.get("factorization", "auto")
        return any(_proved_indefinite(self.split.matrices(self.model, velocity, w)[2],
                                      factorization) for w in (first, other))

    def __call__(self, velocity: float) -> float:
        if self.which is not None:
            other = "antisymmetric" if self.which == "symmetric" else "symmetric"
            if self._definite(other, velocity):
                return self._half(self.which, velocity)
        values = {w: self._half(w, velocity) for w in ("symmetric", "antisymmetric")}
        self.which = min(values, key=values.get)
        return values[self.which]


def critical_function(model: TapeModel, velocity: float, *, count: int = 1,
                      **options) -> float:
    """f(V), 1/s²: ω₁² below the critical speed, −γ² above (γ the largest growth rate).

    The ``count`` eigenvalue pairs nearest zero come from :func:`gyroshell.modes` with
    shift-invert about σ = 0 (one factorization of K(V); near critical the small eigenvalue
    is well separated, so this is fast); ``options`` go to ``modes``. Near the root the
    eigenvalue nearest zero is the one crossing, so f = −λ₀² there, smooth in V. Farther
    above, an oscillating pair can be nearer zero than the divergent one; f then uses the
    growing eigenvalue if found, else −|λ₀|² (still negative: K(V) is indefinite).
    """
    return _evaluate(check_model(model), velocity, count, options)[0]


#: The default starting speed is this fraction of the beam estimate √((T + μ_beam)/ρ).
GUESS_FRACTION = 0.998
#: From a supercritical start, s = V² is multiplied by this until a subcritical point.
DESCENT_FACTOR = 0.99
#: Where no extrapolated zero lies ahead (and no point above is known), s grows by this.
ADVANCE_FACTOR = 1.004
#: Loosest relative tolerance on the critical speed: the extrapolation is confirmed
#: 2 xtol above it, which must stay a small step.
MAX_XTOL = 0.1


def default_guess(model: TapeModel) -> float:
    """A starting speed just below critical, m/s: GUESS_FRACTION √((T + μ_beam)/ρ).

    μ_beam = min_m (D a_m² + k/a_m²) over the width-uniform (beam) modes of the discrete
    model (:func:`gyroshell.engines.divergence.beam_mu_estimate`): exact for ν = 0 and free edges,
    close otherwise, and positive also without tension and foundation (then D a₁²).
    """
    p = model.params
    return GUESS_FRACTION * math.sqrt((p.tension + beam_mu_estimate(model)) / p.density)


class _Counted:
    """f(s) = critical_function at V = √s, remembered, counted and capped at ``limit``."""

    def __init__(self, model: TapeModel, count: int, options: dict, limit: int,
                 which: str | None = None, extra: dict | None = None) -> None:
        self.model, self.count, self.limit = model, count, limit
        split = mirror_split(model) if set(options) <= _HALF_OPTIONS else None
        self.half = None if split is None else _HalfCritical(model, split, count, options,
                                                             which, extra)
        self.options = {**(extra or {}), **options}
        self.trace: list[tuple[float, float]] = []
        self.below: list[tuple[float, float]] = []   # (s, ω₁²) with ω₁² > 0
        self.above = math.inf                         # smallest s with f <= 0
        self.proved_below = 0.0                       # largest s with K(√s) proved > 0
        self.inertia_checks = 0

    def definite(self, s: float) -> bool:
        """True if K(√s) is proved positive definite by Cholesky or inertia (then ω₁² > 0
        there without an eigen-solve: with K > 0 and G skew every eigenvalue is ±iω,
        ω > 0), and s is a point below the root."""
        found = self._proof(s, "definite")
        if found:
            self.proved_below = max(self.proved_below, s)
        return found

    def indefinite(self, s: float) -> bool:
        """True if K(√s) is proved not positive definite by inertia (then f <= 0 there and
        s caps the bracket); one factorization per half instead of an eigen-solve."""
        found = self._proof(s, "indefinite")
        if found:
            self.above = min(self.above, s)
        return found

    def _proof(self, s: float, kind: str) -> bool:
        """Whether K(√s) is proved ``kind`` ("definite" or "indefinite"): on the mirror
        halves where the model has them, else on the whole K; counted in inertia_checks."""
        velocity = check_speed(self.model, math.sqrt(s))
        self.inertia_checks += 1
        if self.half is not None:
            return getattr(self.half, kind)(velocity)
        prove = _proved_definite if kind == "definite" else _proved_indefinite
        return prove(self.model.K(velocity), self.options.get("factorization", "auto"))

    def __call__(self, s: float) -> float:
        if len(self.trace) >= self.limit:
            raise ConvergenceError(
                f"critical speed: no bracketed zero of the lowest frequency in "
                f"{self.limit} eigen-solves")
        velocity = check_speed(self.model, math.sqrt(s))
        value = self.half(velocity) if self.half is not None else critical_function(
            self.model, velocity, count=self.count, **self.options)
        self.trace.append((math.sqrt(s), value))
        if value > 0:
            self.below.append((s, value))
            self.below.sort()
        else:
            self.above = min(self.above, s)
        return value

    @property
    def highest_below(self) -> float:
        """Largest s known below the root: an eigen-solve's ω₁² > 0 or a proof K(√s) > 0."""
        return max(self.below[-1][0], self.proved_below)


def _extrapolate_zero(points: list[tuple[float, float]]) -> float | None:
    """Zero of the interpolant of (s, ω₁²) beyond the last point: quadratic through three
    points (ω₁² ≈ a d + c d², d = s_c − s, seen in practice), else the secant; None if
    neither has a zero beyond the last point."""
    s_last = points[-1][0]
    if len(points) == 3:
        s = np.array([q[0] for q in points]) - s_last
        fv = np.array([q[1] for q in points])
        scale = abs(s[0]) or 1.0
        c2, c1, c0 = np.polyfit(s / scale, fv, 2)
        roots = np.roots([c2, c1, c0]) if c2 != 0 else np.array([-c0 / c1])
        roots = roots[np.isreal(roots)].real * scale
        roots = roots[roots > 0]
        if roots.size:
            return float(s_last + roots.min())
    if len(points) >= 2:
        (s1, f1), (s2, f2) = points[-2:]
        if s2 > s1 and f1 > f2:
            return s2 - f2 * (s2 - s1) / (f2 - f1)
    return None


def _first_subcritical(f: _Counted, s: float) -> None:
    """Step s down by DESCENT_FACTOR from the start until ω₁² > 0 (a point below)."""
    while f(s) <= 0:
        s *= DESCENT_FACTOR


def _next_trial(f: _Counted) -> float:
    """The extrapolated zero from the last three points below, kept inside the bracket
    (bisection of [highest below, lowest above] where it falls outside)."""
    lo, hi = f.highest_below, f.above
    pred = _extrapolate_zero(f.below[-3:])
    if pred is None or pred >= hi or pred <= lo:
        pred = 0.5 * (lo + hi) if math.isfinite(hi) else lo * ADVANCE_FACTOR
    return pred


def critical_speed_eigen(model: TapeModel, *, guess: float | None = None,
                         xtol: float = 1e-9, count: int = 1, max_evaluations: int = 30,
                         step: float | None = None, progress: bool | None = None,
                         **options) -> tuple[float, dict]:
    """Route (a): the speed where the lowest frequency reaches zero, m/s, and diagnostics.

    Below the root ω₁²(s), s = V², is smooth; above it the eigenvalue nearest zero may
    belong to any of the long tape's many nearly critical branches, so values there are
    not a continuation of ω₁² (a two-sided root finder, scipy's toms748 on f, needed more
    than twice the eigen-solves: the values above are erratic). The root is therefore
    approached from below by extrapolating ω₁² (:func:`_extrapolate_zero`), a point above
    (f <= 0) only capping the bracket, with bisection where the extrapolation leaves it.
    It stops when the extrapolated zero is within ``xtol`` (relative, in V) of the highest
    point below and a point just above it confirms the sign change.

    Parameters
    ----------
    guess : float, optional
        Starting speed, m/s; default :func:`default_guess`.
    xtol : float
        Relative tolerance on V, in (0, 0.1).
    count : int
        Eigenvalue pairs per solve (see :func:`critical_function`).
    max_evaluations : int
        Most eigen-solves allowed (>= 2).
    step : float, optional
        Relative step in s = V² from the first point below to the second, in (0, 0.1);
        default ADVANCE_FACTOR − 1 (0.4 %). A guess known to lie close below the root
        (:func:`critical_speeds` starts DIVERGENCE_GAP below route (b)'s speed) wants a
        step of that size.
    progress : bool or None
        As for every engine (True, False or None); the few eigen-solves show no progress.

    Notes
    -----
    Each trial aims ``xtol`` below the extrapolated zero, so that it lands below the root
    and closes the bracket with the next prediction; the point just above that confirms
    the sign change is an inertia count of K(V) (f <= 0 exactly where K(V) is not positive
    definite), not an eigen-solve. Once the extrapolated zero is within
    :data:`PROOF_RANGE` of the highest point below, the trial just below it is first tried
    as a proof that K(V) is positive definite there (a Cholesky per half, f > 0 without an
    eigen-solve; the eigen-solve is made only where the proof fails).

    Raises
    ------
    ParameterError
        Not a model, bad guess, xtol, max_evaluations or progress.
    ConvergenceError
        If no bracketed root is found within ``max_evaluations`` eigen-solves.
    """
    check_model(model)
    validation.progress(progress)
    guess = default_guess(model) if guess is None else guess
    guess = validation.positive("guess", guess, "m/s")
    xtol = validation.real("xtol", xtol, low=0.0, high=MAX_XTOL, low_open=True, high_open=True)
    max_evaluations = validation.integer("max_evaluations", max_evaluations, low=2)
    step = ADVANCE_FACTOR - 1 if step is None else validation.real(
        "step", step, low=0.0, high=MAX_XTOL, low_open=True, high_open=True)
    return _search(_Counted(model, count, options, max_evaluations), float(guess), xtol,
                   step)


def _search(f: _Counted, guess: float, xtol: float, step: float) -> tuple[float, dict]:
    """The root search of :func:`critical_speed_eigen` on the counted f, from ``guess``
    (m/s), with the relative ``xtol`` and first ``step`` (both in s = V²)."""
    _first_subcritical(f, guess**2)
    s = f.highest_below * (1 + step)
    proof_tried = False
    while True:
        if s < f.above:
            f(s)
        pred = _next_trial(f)
        gap = pred - f.highest_below
        if len(f.below) >= 2 and 2 * xtol * pred < gap <= PROOF_RANGE * pred and \
                not proof_tried:
            # close to the root: K(V) > 0 proved just below the prediction stands for the
            # eigen-solve that would land there (one factorization per half, not a solve)
            proof_tried = True
            f.definite(pred * (1 - xtol))
        if abs(pred - f.highest_below) <= 2 * xtol * pred:
            cap = pred * (1 + 2 * xtol)   # confirm the sign change just above
            if cap >= f.above or f.indefinite(cap) or f(cap) <= 0:
                root = math.sqrt(pred)
                break
            pred = cap * (1 + 2 * xtol)
        # aim just below the predicted zero: a landing there closes the bracket next time
        s = max(pred * (1 - xtol), 0.5 * (f.highest_below + pred))
    return root, {"evaluations": len(f.trace), "inertia_checks": f.inertia_checks,
                  "bracket": (math.sqrt(f.highest_below), math.sqrt(f.above)),
                  "trace": f.trace}


#: Relative distance in s = V² from the highest point below to the extrapolated zero
#: within which the point just below the zero is proved by a factorization of K(V)
#: (:meth:`_Counted.definite`) instead of an eigen-solve, once per search: the
#: extrapolation from two points DIVERGENCE_GAP apart is that accurate (module notes).
PROOF_RANGE = 1e-5
#: Without a ``guess``, route (a) starts this fraction below route (b)'s speed (in s = V²
#: twice that), with a first step of the same size: close enough that the secant through
#: the first two points predicts the zero of ω₁²(s) to well within ``xtol`` = 1e-9 (the
#: curvature error grows with the square of the gap; route (a) against route (b) on the
#: L_x/L_y = 19 tape: 2.4e-8 at 1e-6, 2.6e-10 at 1e-7, 2.6e-12 at 1e-8), so two
#: eigen-solves, a Cholesky of K(V) just below the predicted zero and one inertia count
#: just above settle the root.
DIVERGENCE_GAP = 1e-8
#: ARPACK's basis for the solves about σ = 0 that close: the pair ±iω₁ nearest zero is far
#: from the others there, and a short basis converges in fewer solves (19 against 25).
NEAR_ROOT_NCV = 10


def _from_divergence(model: TapeModel, div, options: dict) -> tuple[float, dict]:
    """Route (a) started just below route (b)'s speed, on the half of its buckling mode."""
    options = dict(options)
    options.pop("guess", None)
    xtol = validation.real("xtol", options.pop("xtol", 1e-9), low=0.0, high=MAX_XTOL,
                           low_open=True, high_open=True)
    count = options.pop("count", 1)
    limit = validation.integer("max_evaluations", options.pop("max_evaluations", 30), low=2)
    step = options.pop("step", None)
    step = DIVERGENCE_GAP if step is None else validation.real(
        "step", step, low=0.0, high=MAX_XTOL, low_open=True, high_open=True)
    f = _Counted(model, count, options, limit, _half_of(model, div.mode),
                 {"ncv": NEAR_ROOT_NCV})
    return _search(f, div.speed * (1 - DIVERGENCE_GAP), xtol, step)


def _half_of(model: TapeModel, mode: np.ndarray) -> str | None:
    """"symmetric" or "antisymmetric": the mirror half a mode lies in (None: neither, or
    no mirror symmetry)."""
    split = mirror_split(model)
    if split is None:
        return None
    sym = np.linalg.norm(split.symmetric.T @ mode)
    anti = np.linalg.norm(split.antisymmetric.T @ mode)
    return "symmetric" if sym > anti else "antisymmetric"


def critical_speeds(model: TapeModel, *, progress: bool | None = None,
                    **options) -> CriticalSpeeds:
    """Critical speed by both routes (a) and (b), with the context values, m/s.

    ``options`` go to :func:`critical_speed_eigen` (``guess``, ``xtol``, solver options).
    Without a ``guess``, route (b) runs first and route (a)'s root search starts
    DIVERGENCE_GAP below its speed, on the mirror half that holds the buckling mode (the
    other half's K_h(V) is still proved definite at each speed): route (a)'s root is still
    the zero of its own eigen-solves' ω₁², extrapolated and bracketed by a sign change, so
    the comparison of the two routes keeps its meaning; it needs 2-3 eigen-solves instead
    of about 8 from :func:`default_guess` (the point just below the zero is a proof that
    K(V) > 0, :data:`PROOF_RANGE`). ``progress`` is as for every engine (True, False or
    None); the few eigen-solves show no progress.
    """
    p = check_model(model, members=DIVERGENCE_MEMBERS).params
    validation.progress(progress)
    t0 = time.perf_counter()
    div = divergence(model)
    t1 = time.perf_counter()
    if options.get("guess") is None and math.isfinite(div.speed) and div.speed > 0:
        v_a, info = _from_divergence(model, div, options)
    else:
        v_a, info = critical_speed_eigen(model, **options)
    t2 = time.perf_counter()
    info.update(divergence_time=t1 - t0, critical_time=t2 - t1, mu=div.mu)
    info.pop("trace", None)
    result = CriticalSpeeds(v_a, div.speed, p.string_speed, p.strip_critical_speed,
                            info=info)
    info["relative_difference"] = result.relative_difference
    return result
