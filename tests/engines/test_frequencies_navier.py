"""V = 0 natural frequencies from K φ = ω² M φ against the Navier closed form."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla
from closed_forms import navier_frequency
from convergence import observed_order

from gyroshell import TapeModel, TapeParameters

# Every test here runs on each factorization back-end (CHOLMOD and SuperLU).
pytestmark = pytest.mark.usefixtures("every_factorization")

WIDTH = 6.35e-3
COUNT = 6


def _lowest_frequencies(params: TapeParameters, count: int) -> np.ndarray:
    model = TapeModel(params)
    omega2 = sla.eigh(model.K(0.0).toarray(), np.diag(model.mass_diagonal),
                      eigvals_only=True, subset_by_index=[0, count - 1])
    return np.sqrt(omega2)


def _params(n: int) -> TapeParameters:
    # A soft foundation so that bending and tension, not k, set the mode order.
    return TapeParameters(edges="simply-supported", length_ratio=2.0, spacing=WIDTH / n,
                          foundation_stiffness=1.0e6)


@pytest.mark.slow
def test_navier_frequencies_converge_at_second_order():
    p = _params(8)
    exact = np.sort([navier_frequency(p, m, n) for m in range(1, 9) for n in range(1, 5)])
    exact = exact[:COUNT]
    intervals = np.array([8, 16, 32])
    errors = []
    for n in intervals:
        numeric = _lowest_frequencies(_params(n), COUNT)
        errors.append(np.max(np.abs(numeric - exact) / exact))
    assert errors[-1] < 1e-2
    assert observed_order(1.0 / intervals, errors) == pytest.approx(2.0, abs=0.1)


def test_table1_lowest_frequency_is_near_the_foundation_value():
    """With Table 1's stiff foundation the lowest ω sits just above √(k/ρ)."""
    p = TapeParameters(edges="simply-supported", length_ratio=1.0, spacing=WIDTH / 16)
    omega = _lowest_frequencies(p, 1)[0]
    assert omega == pytest.approx(navier_frequency(p, 1, 1), rel=2e-3)
    assert omega > p.foundation_frequency
