"""Divergence (static buckling) speed: where K(V) = A + (T − ρV²) B stops being definite.

K(V) is singular when ρV² − T equals an eigenvalue μ of the symmetric-definite pencil
A φ = μ B φ; the smallest μ (> 0, since A is positive definite) gives

    V_div = √((T + μ_min) / ρ).

Below V_div, K is positive definite and every gyroscopic frequency is real; at V_div the
lowest frequency reaches zero.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse.linalg as spla

from ..core import validation
from ..core.errors import ConvergenceError, ParameterError
from ..core.parallel import blas_threads
from ..linalg.inertia import InertiaFactor, factor_inertia
from ..results.critical import Divergence
from ..tape.model import TapeModel

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

__all__ = ["Divergence", "beam_mu_estimate", "divergence", "divergence_speed", "safe_shift"]


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


def safe_shift(model: TapeModel, *, tries: int = SHIFT_TRIES
               ) -> tuple[float, InertiaFactor | None]:
    """A shift τ < μ_min close to it, proved by inertia, and the factorization of A − τB.

    Near the bottom of a one-parameter band μ ≈ μ_min + c (α − α*)², the number of
    eigenvalues below τ grows like √(τ − μ_min): the squared inertia counts at two shifts
    are nearly linear in τ and extrapolate to μ_min. Each guess is checked (no negative
    pivot); if the counts are not informative the shift is halved, down to τ = 0.
    """
    A, B = model.A, model.B
    points: list[tuple[float, int]] = []
    tau = beam_mu_estimate(model)
    for _ in range(tries):
        factor = factor_inertia(A - tau * B)
        if factor.negatives is None:
            break
        if factor.negatives == 0:
            return tau, factor
        points.append((tau, factor.negatives))
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


def divergence(model: TapeModel, *, tol: float = DIVERGENCE_TOL, shift: float | None = None
               ) -> Divergence:
    """Divergence speed and buckling mode of the discrete model, by one ``eigsh`` call.

    Shift-invert about a shift τ just below μ_min, through one sparse factorization of
    A − τB. The μ cluster (every wavenumber near (k/D)^¼ buckles at nearly the same μ) is
    nearly flat seen from τ = 0 but well spread seen from τ ≈ μ_min. τ is extrapolated from
    inertia counts of A − τB (see :func:`safe_shift`), starting at the beam estimate
    :func:`beam_mu_estimate`; a factorization with no negative pivot proves τ < μ_min, so
    the eigenvalue nearest τ is μ_min.

    Parameters
    ----------
    tol : float
        ARPACK relative tolerance.
    shift : float, optional
        τ, N/m, to use instead (must be below μ_min); 0 reproduces plain shift-invert.
    """
    tol = validation.real("tol", tol, low=0.0, high=1.0, high_open=True)
    if shift is not None:
        shift = validation.real("shift", shift, unit="N/m")
    A, B = model.A, model.B
    tau, factor = safe_shift(model) if shift is None else (float(shift), None)
    if factor is None:
        factor = factor_inertia(A - tau * B)
    if factor.singular:
        raise ParameterError(f"shift {tau:g} N/m is an eigenvalue of A phi = mu B phi; "
                             "choose another")
    opinv = spla.LinearOperator(A.shape, matvec=factor.solve, dtype=float)
    v0 = np.random.default_rng(START_SEED).standard_normal(A.shape[0])
    try:
        with blas_threads(1):
            vals, vecs = spla.eigsh(A, k=1, M=B, sigma=tau, which="LM", tol=tol,
                                    OPinv=opinv, v0=v0)
    except (spla.ArpackNoConvergence, spla.ArpackError) as exc:
        raise ConvergenceError(f"divergence eigenvalue did not converge: {exc}") from None
    mu = float(vals[0])
    mode = vecs[:, 0] / vecs[np.argmax(np.abs(vecs[:, 0])), 0]
    p = model.params
    return Divergence(math.sqrt((p.tension + mu) / p.density), mu, mode, model.grid)


def divergence_speed(model: TapeModel) -> float:
    """Divergence speed V_div = √((T + μ_min)/ρ), m/s (see :func:`divergence`)."""
    return divergence(model).speed
