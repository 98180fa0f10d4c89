"""Stability of a motion from its eigenvalues: :func:`classify_stability`."""

from __future__ import annotations

import numpy as np

from ..linalg.qep.spectrum import (
    STABILITY_LABELS,
    STABILITY_RTOL,
    check_eigenvalues,
    stability_label,
)

__all__ = ["STABILITY_LABELS", "STABILITY_RTOL", "classify_stability"]


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
