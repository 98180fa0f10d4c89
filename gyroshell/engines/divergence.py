"""Divergence (static buckling) speed: where K(V) = A + (T − ρV²) B stops being definite.

K(V) is singular when ρV² − T equals an eigenvalue μ of the symmetric-definite pencil
A φ = μ B φ; the smallest μ (> 0, since A is positive definite) gives

    V_div = √((T + μ_min) / ρ).

Below V_div, K is positive definite and every gyroscopic frequency is real; at V_div the
lowest frequency reaches zero.
"""

from __future__ import annotations

import math
import weakref

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..core import validation
from ..core.errors import ConvergenceError, ParameterError
from ..core.parallel import blas_threads
from ..linalg import cholesky
from ..linalg.factorization import resolve_factorization
from ..linalg.inertia import InertiaFactor, factor_inertia
from ..results.critical import Divergence
from ..tape.model import MODEL_MEMBERS, TapeModel, check_model

#: Factorizations tried by :func:`safe_shift` before giving up (τ = 0).
SHIFT_TRIES = 8
#: The second inertia count is taken this factor above the first, for the slope.
SLOPE_PROBE = 1.01
#: The extrapolated μ_min is undershot by this fraction of its distance to the last count.
SHIFT_UNDERSHOOT = 0.1
#: Default ARPACK relative tolerance of :func:`divergence`.
DIVERGENCE_TOL = 1e-12
#: Seed of ARPACK's start vector: reproducible results.
START_SEED = 12345

#: What the divergence solver reads from a model: the engines' members and K's parts A, B.
DIVERGENCE_MEMBERS = (*MODEL_MEMBERS, "A", "B")

__all__ = ["Divergence", "beam_mu_estimate", "divergence", "divergence_speed", "proved_shift",
           "safe_shift"]


def beam_mu_estimate(model: TapeModel) -> float:
    """min over m of D a_m² + k / a_m², N/m: μ of the width-uniform (beam) modes.

    a_m² = (4/h²) sin²(α_m h/2) is the discrete −∂²/∂x² eigenvalue of sin(α_m x), α_m = mπ/L_x,
    and D = D11 (orthotropic or layered tapes too). Exact for D12 = 0 (ν = 0) and free
    edges, where the width-uniform vectors are eigenvectors; otherwise an estimate of μ_min
    from above (the free edges relieve the bending towards D11 − D12²/D22).
    """
    g, p = model.grid, model.params
    alpha = np.arange(1, g.nx) * np.pi / g.length
    a2 = (2.0 / g.hx * np.sin(alpha * g.hx / 2)) ** 2
    return float(np.min(p.D * a2 + p.k / a2))


class _Pencils:
    """The pencil A φ = μ B φ as the mirror-symmetric halves (:mod:`gyroshell.tape.mirror`:
    A_h = P_hᵀAP_h, B_h = P_hᵀBP_h, whose eigenvalues together are the full pencil's) or
    whole, and the factorization of A − τB half by half.

    A count on the halves is the sum of theirs; a half-width factorization has an eighth
    of the full one's work and a quarter of its entries (the fill of a strip grows with
    the square of its width). CHOLMOD's LDLᵀ counts and solves where it is selected
    (:func:`gyroshell.linalg.factorization.resolve_factorization`), SuperLU's otherwise.
    """

    def __init__(self, model: TapeModel, *, factorization: str = "auto") -> None:
        from ..tape.mirror import mirror_split

        A, B = model.A, model.B
        split = mirror_split(model)
        self.split = split
        if split is None:
            self.parts = [(A, B, None)]
        else:
            self.parts = [(*split.stiffness(w), split.half(w)) for w in HALVES]
        self.cholmod = resolve_factorization(factorization) == "cholmod"
        #: Per part, the negative count at the last shift that had some (or None).
        self.counted: list | None = None

    def order(self) -> list[int]:
        """The parts, the one likeliest to hold μ_min first: the one with the most
        eigenvalues below the last shift that had any (the symmetric half on ties)."""
        counted = self.counted or [0] * len(self.parts)
        return sorted(range(len(self.parts)), key=lambda k: -counted[k])

    def shifted(self, k: int, tau: float) -> sp.csr_matrix:
        """A_k − τB_k (on the halves by one vector operation: A_h, B_h share a pattern)."""
        if self.split is not None:
            return self.split.combination(HALVES[k], -tau)
        A, B, _ = self.parts[k]
        return A - tau * B

    def above(self, k: int, mu: float) -> bool:
        """True if part k is proved to have no eigenvalue at or below μ (N/m): a Cholesky
        (CHOLMOD) or an inertia count of A_k − μB_k without a negative or zero pivot."""
        matrix = self.shifted(k, mu)
        if self.cholmod:
            factor = cholesky.cholesky(matrix)
            if factor is not None:
                factor.release()
                return True
            return False
        return factor_inertia(matrix).definite

    def factor(self, tau: float) -> list:
        """Factorizations of A_h − τB_h (``negatives``: their inertia, None if unknown)."""
        factors = []
        for k in range(len(self.parts)):
            matrix = self.shifted(k, tau)
            factor = cholesky.ldl(matrix) if self.cholmod else None
            factors.append(factor_inertia(matrix) if factor is None else factor)
        return factors

    @staticmethod
    def negatives(factors: list) -> int | None:
        counts = [f.negatives for f in factors]
        return None if any(c is None for c in counts) else sum(counts)

    @staticmethod
    def release(factors) -> None:
        for factor in factors or ():
            if hasattr(factor, "release"):
                factor.release()


def safe_shift(model: TapeModel, *, tries: int = SHIFT_TRIES
               ) -> tuple[float, InertiaFactor | None]:
    """A shift τ < μ_min close to it, proved by inertia, and the factorization of A − τB.

    Near the bottom of a one-parameter band μ ≈ μ_min + c (α − α*)², the number of
    eigenvalues below τ grows like √(τ − μ_min): the squared inertia counts at two shifts
    are nearly linear in τ and extrapolate to μ_min. Each guess is checked (no negative
    pivot); if the counts are not informative the shift is halved, down to τ = 0.
    The counts are taken on the mirror halves where the tape has them (:class:`_Pencils`);
    the factorization returned is SuperLU's of the full A − τB (None where τ = 0).
    """
    pencils = _Pencils(model)
    tau, factors = _safe_shift(pencils, beam_mu_estimate(model), tries)
    pencils.release(factors)
    if factors is None:
        return 0.0, None
    return tau, factor_inertia(model.A - tau * model.B)


def proved_shift(model: TapeModel, *, tries: int = SHIFT_TRIES) -> float | None:
    """τ of :func:`safe_shift` without a factorization to return, N/m: the counts and the
    proof on the mirror halves only (a few half-width LDLᵀ factorizations); None if the
    counts were not informative."""
    pencils = _Pencils(model)
    tau, factors = _safe_shift(pencils, beam_mu_estimate(model), tries)
    pencils.release(factors)
    return None if factors is None else tau


def _safe_shift(pencils: _Pencils, tau: float, tries: int) -> tuple[float, list | None]:
    """τ proved below μ_min by the inertia of the halves, from the estimate ``tau``, and
    their factorizations (None, with τ = 0, if the counts were not informative)."""
    points: list[tuple[float, int]] = []
    for _ in range(tries):
        factors = pencils.factor(tau)
        negatives = pencils.negatives(factors)
        if negatives == 0:
            return tau, factors
        pencils.counted = [f.negatives for f in factors]
        pencils.release(factors)
        if negatives is None:
            break
        points.append((tau, negatives))
        if len(points) == 1:
            tau = tau * SLOPE_PROBE  # a second count above, for the slope
            continue
        (t1, c1), (t2, c2) = sorted(points)[:2]
        if c2 > c1:
            guess = t1 - c1**2 * (t2 - t1) / (c2**2 - c1**2)
            tau = guess - SHIFT_UNDERSHOOT * (t1 - guess)
        else:
            tau = 0.5 * t1
        if tau <= 0:
            break
    return 0.0, None


def divergence(model: TapeModel, *, tol: float = DIVERGENCE_TOL, shift: float | None = None,
               progress: bool | None = None) -> Divergence:
    """Divergence speed and buckling mode of the discrete model, by ``eigsh``.

    Shift-invert about a shift τ just below μ_min, through one sparse factorization of
    A − τB. The μ cluster (every wavenumber near (k/D)^¼ buckles at nearly the same μ) is
    nearly flat seen from τ = 0 but well spread seen from τ ≈ μ_min. τ is extrapolated from
    inertia counts of A − τB (see :func:`safe_shift`), starting at the beam estimate
    :func:`beam_mu_estimate`; a factorization with no negative pivot proves τ < μ_min, so
    the eigenvalue nearest τ is μ_min. A mirror-symmetric tape is solved on its two halves
    (one ``eigsh`` each, the smaller μ kept; :class:`_Pencils`).

    Parameters
    ----------
    tol : float
        ARPACK relative tolerance.
    shift : float, optional
        τ, N/m, to use instead (must be below μ_min); 0 reproduces plain shift-invert.
    progress : bool or None
        As for every engine (True, False or None); one eigen-solve (or two, on the
        halves) has no progress to show.
    """
    check_model(model, members=DIVERGENCE_MEMBERS)
    validation.progress(progress)
    tol = validation.real("tol", tol, low=0.0, high=1.0, high_open=True)
    if shift is not None:
        shift = validation.real("shift", shift, unit="N/m")
    pencils = _Pencils(model)
    if shift is None:
        tau, factors = _safe_shift(pencils, beam_mu_estimate(model), SHIFT_TRIES)
    else:
        tau, factors = float(shift), None
    if factors is None:
        factors = pencils.factor(tau)
    try:
        if any(f.singular for f in factors):
            raise ParameterError(f"shift {tau:g} N/m is an eigenvalue of A phi = mu B phi; "
                                 "choose another")
        mu, mode = math.inf, None
        proved = {}
        for k in pencils.order():   # a part proved to lie above the best μ is skipped
            if mode is not None and pencils.above(k, mu):
                proved[k] = mu
                continue
            found = _lowest(*pencils.parts[k], factors[k], tau, tol)
            if found[0] < mu:
                mu, mode = found
    finally:
        pencils.release(factors)
    if pencils.split is not None:
        _PROVED_ABOVE[model] = {HALVES[k]: value for k, value in proved.items()}
    mode = mode / mode[np.argmax(np.abs(mode))]
    p = model.params
    return Divergence(math.sqrt((p.tension + mu) / p.density), mu, mode, model.grid)


#: The mirror halves in the order of :class:`_Pencils`' parts.
HALVES = ("symmetric", "antisymmetric")
#: Per model, the halves h with A_h − μB_h proved positive definite by :func:`divergence`
#: (the half it skipped), and that μ, N/m.
_PROVED_ABOVE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def proved_above(model: TapeModel) -> dict[str, float]:
    """{half: μ}: the mirror halves whose A_h − μB_h the last :func:`divergence` of
    ``model`` proved positive definite (a Cholesky or an inertia count), so K_h(V) > 0 for
    ρV² − T <= μ; empty if none (or not computed)."""
    return dict(_PROVED_ABOVE.get(model, {}))


def _lowest(A, B, P, factor, tau: float, tol: float) -> tuple[float, np.ndarray]:
    """The eigenvalue of A φ = μ B φ nearest τ (N/m) and its vector (embedded by P)."""
    opinv = spla.LinearOperator(A.shape, matvec=factor.solve, dtype=float)
    v0 = np.random.default_rng(START_SEED).standard_normal(A.shape[0])
    try:
        with blas_threads(1):
            vals, vecs = spla.eigsh(A, k=1, M=B, sigma=tau, which="LM", tol=tol,
                                    OPinv=opinv, v0=v0)
    except (spla.ArpackNoConvergence, spla.ArpackError) as exc:
        raise ConvergenceError(f"divergence eigenvalue did not converge: {exc}") from None
    vec = vecs[:, 0]
    return float(vals[0]), vec if P is None else P @ vec


def divergence_speed(model: TapeModel, *, progress: bool | None = None) -> float:
    """Divergence speed V_div = √((T + μ_min)/ρ), m/s (see :func:`divergence`)."""
    return divergence(model, progress=progress).speed
