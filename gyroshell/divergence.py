"""Divergence (static buckling) speed: where K(V) = A + (T − ρV²) B stops being definite.

K(V) is singular when ρV² − T equals an eigenvalue μ of the symmetric-definite pencil
A φ = μ B φ; the smallest μ (> 0, since A is positive definite) gives

    V_div = √((T + μ_min) / ρ).

Below V_div, K is positive definite and every gyroscopic frequency is real; at V_div the
lowest frequency reaches zero.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as spla

from .errors import ConvergenceError
from .model import TapeModel


@dataclass(frozen=True)
class Divergence:
    """Result of :func:`divergence`.

    Attributes
    ----------
    speed : float
        Divergence speed V_div, m/s.
    mu : float
        Smallest eigenvalue of A φ = μ B φ, N/m (the extra compression the plate resists).
    mode : numpy.ndarray
        Buckling mode φ (unknown vector, max |φ| = 1).
    """

    speed: float
    mu: float
    mode: np.ndarray


def divergence(model: TapeModel, *, tol: float = 1e-12) -> Divergence:
    """Divergence speed and buckling mode of the discrete model, by one ``eigsh`` call.

    Shift-invert about μ = 0 through one sparse factorization of A.
    """
    try:
        vals, vecs = spla.eigsh(model.A.tocsc(), k=1, M=model.B.tocsc(), sigma=0.0,
                                which="LM", tol=tol)
    except spla.ArpackNoConvergence as exc:  # pragma: no cover - ARPACK failure path
        raise ConvergenceError(f"divergence eigenvalue did not converge: {exc}") from None
    mu = float(vals[0])
    mode = vecs[:, 0] / vecs[np.argmax(np.abs(vecs[:, 0])), 0]
    p = model.params
    return Divergence(math.sqrt((p.tension + mu) / p.density), mu, mode)


def divergence_speed(model: TapeModel) -> float:
    """Divergence speed V_div = √((T + μ_min)/ρ), m/s (see :func:`divergence`)."""
    return divergence(model).speed
