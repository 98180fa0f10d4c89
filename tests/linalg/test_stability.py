"""Stability classification (stable / divergence / flutter) on cases with known answers.

* A two-degree-of-freedom gyroscopic system M = I, G = g [[0, 1], [−1, 0]],
  K = diag(k₁, k₂): λ⁴ + (k₁ + k₂ + g²) λ² + k₁k₂ = 0 in closed form. With k₁, k₂ < 0 and
  a = √|k₁|, b = √|k₂|: divergence for g < |a − b|, flutter for |a − b| < g < a + b, and
  gyroscopic stabilization for g > a + b; with k₁k₂ < 0 divergence for every g.
* The axially moving string (k = 0, vanishing D): λ_n = i nπ (c² − V²)/(c L), purely
  imaginary for every V ≠ c = √(T/ρ) (Wickert & Mote 1990): beyond c the string's spectrum
  stays on the imaginary axis (stable in the classification), which the tape model reproduces
  at second order.
  The finite-difference string is another matter: beyond c, K(V) is negative definite, so
  with an odd number of unknowns a real positive eigenvalue must exist (next item). It
  sits at the grid scale (the sawtooth mode, which the centred difference in G does not
  see), with a growth rate ∝ 1/h: the discrete string beyond c diverges, at a rate set by
  the grid, while its low modes stay on the imaginary axis.
* Just above the divergence speed K(V) has exactly one negative eigenvalue. With an odd
  number, det Q(λ) = det(λ²M + λG + K) is negative at λ = 0 and positive as λ → ∞, so a real
  positive eigenvalue exists (Kelvin–Tait–Chetaev): divergence, whatever G does.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as la
from conftest import moving_string
from convergence import observed_order
from dense_reference import quadratic_eigenvalues

from gyroshell import TapeModel, TapeParameters, classify_stability, divergence_speed, modes
from gyroshell.core.errors import ParameterError
from gyroshell.studies.stability import tape_stability

# Every test here runs on each factorization back-end (CHOLMOD and SuperLU).
pytestmark = pytest.mark.usefixtures("every_factorization")

WIDTH = 6.35e-3


def two_dof(k1: float, k2: float, g: float):
    return np.eye(2), g * np.array([[0.0, 1.0], [-1.0, 0.0]]), np.diag([k1, k2])


def closed_form_2dof(k1: float, k2: float, g: float) -> str:
    if k1 * k2 < 0:
        return "divergence"
    if k1 > 0:
        return "stable"
    a, b = np.sqrt(-k1), np.sqrt(-k2)
    if g < abs(a - b):
        return "divergence"
    if g < a + b:
        return "flutter"
    return "stable"


@pytest.mark.parametrize("k1, k2", [(-1.0, -4.0), (-2.0, -0.5), (-1.0, -1.0)])
def test_two_dof_regions_match_closed_form(k1, k2):
    a, b = np.sqrt(-k1), np.sqrt(-k2)
    # sample each region away from its boundaries (double roots there)
    edges = sorted({0.0, abs(a - b), a + b})
    gs = [g for lo, hi in zip(edges, edges[1:] + [2 * (a + b) + 1], strict=True)
          for g in np.linspace(lo, hi, 7)[1:-1]]
    seen = set()
    for g in gs:
        expected = closed_form_2dof(k1, k2, g)
        assert classify_stability(quadratic_eigenvalues(*two_dof(k1, k2, g))) == expected, g
        seen.add(expected)
    assert seen == ({"flutter", "stable"} if a == b else {"divergence", "flutter", "stable"})


@pytest.mark.parametrize("g", [0.0, 0.7, 3.0, 30.0])
def test_two_dof_mixed_stiffness_always_diverges(g):
    lam = quadratic_eigenvalues(*two_dof(2.0, -1.0, g))
    assert classify_stability(lam) == "divergence"
    assert classify_stability(quadratic_eigenvalues(*two_dof(2.0, 1.0, g))) == "stable"


def test_classifier_on_explicit_eigenvalues():
    assert classify_stability([1j, -1j, 2j]) == "stable"
    assert classify_stability([-0.5 + 1j, 1j]) == "stable"              # damped
    assert classify_stability([0.3 + 0j, 2j]) == "divergence"
    assert classify_stability([0.3 + 2j, 2j]) == "flutter"
    assert classify_stability([0.3 + 2j, 0.1 + 0j]) == "divergence"      # both: divergence
    assert classify_stability([1e-12 + 1e4j]) == "stable"               # round-off size
    with pytest.raises(ParameterError, match="at least one"):
        classify_stability([])
    with pytest.raises(ParameterError, match="finite"):
        classify_stability([np.nan])


# ----- the moving string beyond √(T/ρ) -------------------------------------------------------
@pytest.mark.parametrize("ratio", [1.2, 1.5])
def test_string_beyond_string_speed_keeps_imaginary_spectrum(ratio):
    p = moving_string(16).params
    c, L = p.string_speed, p.length
    V = ratio * c
    exact = np.array([n * np.pi * (V**2 - c**2) / (c * L) for n in (1, 2, 3)])
    steps, errs = [], []
    for nx in (32, 64, 128):
        res = modes(moving_string(nx), V, 3)
        assert res.supercritical  # K(V) is negative definite here ...
        assert classify_stability(res.eigenvalues) == "stable"  # ... yet no growth
        errs.append(np.abs(np.sort(res.omega) - exact) / exact)
        steps.append(L / nx)
    errs = np.array(errs)
    for j in range(3):
        assert observed_order(steps, errs[:, j]) == pytest.approx(2.0, abs=0.2)
    assert errs[-1].max() < 1e-2  # mode 3 (error grows like n²)


@pytest.mark.slow
def test_odd_morse_index_just_above_divergence_diverges():
    p = TapeParameters(length_ratio=4, spacing=WIDTH / 8)
    model = TapeModel(p)
    # K(V) = A + (T − ρV²) B: its index is the number of μ_j (A φ = μ B φ) below ρV² − T
    mu = la.eigh(model.A.toarray(), model.B.toarray(), eigvals_only=True)
    v_div = divergence_speed(model)
    assert v_div == pytest.approx(np.sqrt((p.tension + mu[0]) / p.density), rel=1e-10)
    V = np.sqrt((p.tension + mu[0] + 0.3 * (mu[1] - mu[0])) / p.density)
    K = model.K(V).toarray()
    assert np.count_nonzero(np.linalg.eigvalsh(K) < 0) == 1  # odd index: det K < 0
    res = modes(model, V, 3)
    assert classify_stability(res.eigenvalues) == "divergence"
    lam = res.eigenvalues[np.argmax(res.eigenvalues.real)]
    assert lam.imag == 0 and lam.real > 0
    # an independent check of the root: Q(λ) is singular there (dense SVD)
    Q = lam.real**2 * model.M.toarray() + lam.real * model.G(V).toarray() + K
    s = np.linalg.svd(Q, compute_uv=False)
    assert s[-1] < 1e-9 * s[0]
    # and below V_div every eigenvalue is ±iω
    assert classify_stability(modes(model, 0.999 * v_div, 3).eigenvalues) == "stable"


@pytest.mark.parametrize("nx", [16, 32])  # 15 and 31 unknowns: K(V) has an odd index
def test_discrete_string_beyond_string_speed_diverges_at_grid_scale(nx):
    s = moving_string(nx)
    V = 1.2 * s.params.string_speed
    assert np.all(np.linalg.eigvalsh(s.K(V).toarray()) < 0)
    assert tape_stability(s, V) == "divergence"
    lam = quadratic_eigenvalues(s.M.toarray(), s.G(V).toarray(), s.K(V).toarray())
    assert classify_stability(lam) == "divergence"


def test_discrete_string_growth_rate_scales_with_one_over_h():
    V = 1.2 * moving_string(16).params.string_speed
    rates, steps = [], []
    for nx in (16, 32, 64):
        s = moving_string(nx)
        lam = quadratic_eigenvalues(s.M.toarray(), s.G(V).toarray(), s.K(V).toarray())
        rates.append(lam.real.max())
        steps.append(s.params.length / nx)
    assert observed_order(steps, rates) == pytest.approx(-1.0, abs=0.05)
    # with an even number of unknowns the grid-scale pairs flutter instead
    s = moving_string(17)
    assert tape_stability(s, V) == "flutter"


@pytest.mark.slow
def test_tape_stability_below_and_above_critical():
    p = TapeParameters(length_ratio=4, spacing=WIDTH / 8)
    model = TapeModel(p)
    v_div = divergence_speed(model)
    assert tape_stability(model, 0.99 * v_div) == "stable"
    for V in (1.02 * v_div, 1.1 * v_div, 1.3 * v_div):
        lam = quadratic_eigenvalues(model.M.toarray(), model.G(V).toarray(),
                                    model.K(V).toarray())
        assert tape_stability(model, V) == classify_stability(lam) != "stable"


@pytest.mark.slow
def test_eigenvalues_nearest_zero_can_miss_the_instability():
    # Far above critical the growing modes are not among the few nearest zero: a verdict
    # from modes(...)'s eigenvalues alone would call this speed stable.
    model = TapeModel(TapeParameters(length_ratio=4, spacing=WIDTH / 8))
    V = 130.0
    near_zero = modes(model, V, 3).eigenvalues
    lam = quadratic_eigenvalues(model.M.toarray(), model.G(V).toarray(), model.K(V).toarray())
    assert classify_stability(near_zero) == "stable"
    assert classify_stability(lam) == "divergence"
    assert tape_stability(model, V, near_zero) == "divergence"
