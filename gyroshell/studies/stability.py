"""Stability of a motion from its eigenvalues (:func:`classify_stability`) and of the
moving tape at a speed (:func:`tape_stability`).

Importing this module loads scipy (through :mod:`gyroshell.linalg.qep`): the modules that the
CLI's parser and refusals import reach it only inside functions.
"""

from __future__ import annotations

import numpy as np

from ..core.parallel import blas_threads
from ..linalg.inertia import factor_inertia
from ..linalg.qep.spectrum import (
    STABILITY_LABELS,
    STABILITY_RTOL,
    check_eigenvalues,
    stability_label,
)

__all__ = ["DENSE_SPECTRUM_LIMIT", "DIVERGENCE", "FLUTTER", "STABILITY_LABELS",
           "STABILITY_RTOL", "STABLE", "UNDETERMINED", "classify_stability",
           "quadratic_eigenvalues", "tape_stability"]

#: The stability classes of :func:`classify_stability`: stable, divergence (a real positive
#: eigenvalue: static buckling) and flutter (a complex eigenvalue with a positive real part).
STABLE, DIVERGENCE, FLUTTER = "stable", "divergence", "flutter"
#: K(V) indefinite with an even index and no growing eigenvalue among those computed.
UNDETERMINED = "undetermined"
#: Largest number of unknowns for which :func:`tape_stability` computes the whole spectrum
#: densely (a 2n×2n companion matrix); above it only the eigenvalues near zero are known.
DENSE_SPECTRUM_LIMIT = 700


def classify_stability(eigenvalues: np.ndarray, *, rtol: float = STABILITY_RTOL) -> str:
    """Stability of a motion from its eigenvalues λ (1/s).

    ``"divergence"`` if some real eigenvalue is positive (static buckling: the motion grows
    without oscillating), else ``"flutter"`` if some complex eigenvalue has a positive real
    part (growing oscillation), else ``"stable"`` (all on the imaginary axis or in the left
    half-plane: an undamped gyroscopic system above its critical speed can be stable this way,
    *gyroscopically stabilized*, although K is indefinite). A part smaller than ``rtol``·|λ|
    counts as zero. Only the eigenvalues given are judged (for a solver's result: those
    nearest its shift).

    Raises
    ------
    ParameterError
        For no eigenvalue, or a non-finite one.

    Examples
    --------
    >>> classify_stability([125e3j, -125e3j])
    'stable'
    >>> classify_stability([2.3e4 + 0j, 1.5e4j])
    'divergence'
    >>> classify_stability([8e2 + 7.9e2j, 8e2 - 7.9e2j])
    'flutter'
    """
    return stability_label(check_eigenvalues(eigenvalues), rtol)


def quadratic_eigenvalues(M, G, K) -> np.ndarray:
    """All 2n eigenvalues λ (1/s) of det(λ²M + λG + K) = 0, dense.

    Parameters
    ----------
    M, G, K : array_like or sparse matrix, shape (n, n)
        Mass (kg/m², M invertible), gyroscopic (kg/(m²·s)) and stiffness (N/m³) matrices.

    Returns
    -------
    numpy.ndarray of complex, shape (2n,)

    Examples
    --------
    >>> lam = quadratic_eigenvalues([[1.0]], [[0.0]], [[4.0]])  # λ² + 4 = 0
    >>> print(lam)
    [0.+2.j 0.-2.j]
    """
    import scipy.linalg as la

    M, G, K = (np.asarray(a.toarray() if hasattr(a, "toarray") else a, dtype=float)
               for a in (M, G, K))
    n = len(K)
    Minv = np.linalg.inv(M)
    companion = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ G]])
    with blas_threads(1):  # studies run one point per core
        return la.eigvals(companion)


def tape_stability(model, velocity: float, eigenvalues=None) -> str:
    """Stability of the moving tape at speed V: ``stable``, ``divergence`` or ``flutter``.

    The tape is a conservative gyroscopic system (G skew, K symmetric), so two facts decide
    most speeds without eigenvalues, from the inertia of K(V) (negative pivots of its LDLᵀ):

    * K(V) positive definite (below the critical speed): stable, by the energy
      ½vᵀMv + ½wᵀKw, which is conserved and positive definite.
    * An odd number of negative eigenvalues of K(V): det Q(λ) = det(λ²M + λG + K) is
      negative at λ = 0 and positive for large real λ, so a real positive eigenvalue exists:
      divergence.

    With an even, non-zero number, G may stabilize the tape or not: the whole spectrum is
    computed densely (up to :data:`DENSE_SPECTRUM_LIMIT` unknowns) and classified by
    :func:`classify_stability`. On larger grids the ``eigenvalues`` given (those nearest
    zero, from :func:`gyroshell.modes`) decide if one of them grows, else the answer
    is ``undetermined``: the modes nearest zero do not show a far-off growing one.

    Parameters
    ----------
    model : TapeModel
        The tape (its operators M, G(V), K(V)).
    velocity : float
        Tape speed V, m/s.
    eigenvalues : array_like of complex, optional
        Eigenvalues λ (1/s) already computed near zero, used above the dense limit.

    Returns
    -------
    str
        :data:`STABLE`, :data:`DIVERGENCE`, :data:`FLUTTER` or :data:`UNDETERMINED`.
    """
    K = model.K(velocity)
    negatives = factor_inertia(K).negatives
    if negatives is None:  # pivoting happened: count the negative eigenvalues densely
        if model.unknowns > DENSE_SPECTRUM_LIMIT:
            negatives = -1
        else:
            negatives = int(np.count_nonzero(np.linalg.eigvalsh(K.toarray()) < 0))
    if negatives == 0:
        return STABLE
    if negatives > 0 and negatives % 2 == 1:
        return DIVERGENCE
    if model.unknowns <= DENSE_SPECTRUM_LIMIT:
        return classify_stability(quadratic_eigenvalues(model.M, model.G(velocity), K))
    if eigenvalues is not None:
        verdict = classify_stability(eigenvalues)
        if verdict != STABLE:
            return verdict
    return UNDETERMINED
