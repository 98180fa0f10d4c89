"""gyroscopic_modes on user matrices: closed-form gyroscopic systems, dense references,
damping, stability classes and refusals."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as la
import scipy.sparse as sp

from gyroshell import ParameterError, TapeModel, TapeParameters
from gyroshell.engines.eigen import modes
from gyroshell.engines.gyroscopic import gyroscopic_modes
from gyroshell.linalg.qep import DENSE_LIMIT, max_count
from gyroshell.studies.stability import classify_stability

# Every test here runs on each factorization back-end (CHOLMOD and SuperLU).
pytestmark = pytest.mark.usefixtures("every_factorization")

WIDTH = TapeParameters().width


# ----- the two-degree-of-freedom gyroscopic system -------------------------------------------
def two_dof(k1: float, k2: float, g: float):
    """M = I, G = [[0, g], [−g, 0]], K = diag(k1, k2): det Q(λ) = (λ² + k1)(λ² + k2) + g²λ²,
    so λ² = (−b ± √(b² − 4 k1 k2)) / 2 with b = k1 + k2 + g²."""
    return np.eye(2), np.array([[0.0, g], [-g, 0.0]]), np.diag([k1, k2])


def two_dof_eigenvalues(k1: float, k2: float, g: float) -> np.ndarray:
    b = k1 + k2 + g * g
    root = np.sqrt(complex(b * b - 4 * k1 * k2))
    lam2 = np.array([(-b + root) / 2, (-b - root) / 2])
    lam = np.sqrt(lam2)
    return np.concatenate([lam, -lam])


@pytest.mark.parametrize("k1, k2, g, expected", [
    (1.0, 4.0, 1.0, "stable"),        # K > 0: always stable, two frequencies
    (-1.0, -4.0, 4.0, "stable"),      # K < 0 but g > √1 + √4: gyroscopically stabilized
    (-1.0, -4.0, 2.0, "flutter"),     # K < 0, g < 3: complex λ with Re λ > 0
    (-1.0, 4.0, 1.0, "divergence"),   # det K < 0: a real positive λ
])
def test_two_dof_closed_form_and_stability(k1, k2, g, expected):
    M, G, K = two_dof(k1, k2, g)
    res = gyroscopic_modes(M, G, K, 2)
    exact = two_dof_eigenvalues(k1, k2, g)
    for lam in res.eigenvalues:
        assert np.min(np.abs(exact - lam)) < 1e-12 * np.abs(exact).max()
    assert res.stability == expected
    assert res.supercritical == (min(k1, k2) < 0)
    assert res.residuals.max() < 1e-13


def test_stability_boundary_of_gyroscopic_stabilization():
    # K = −diag(1, 4): stable exactly for g > √1 + √4 = 3
    assert gyroscopic_modes(*two_dof(-1.0, -4.0, 3.0 * (1 + 1e-6)), 2).stability == "stable"
    assert gyroscopic_modes(*two_dof(-1.0, -4.0, 3.0 * (1 - 1e-6)), 2).stability == "flutter"


def blocks(ks, gs):
    """Many decoupled 2-DOF systems (n = 2 × blocks), sparse: the sparse solver's test."""
    parts = [two_dof(k1, k2, g) for (k1, k2), g in zip(ks, gs, strict=True)]
    M, G, K = (sp.block_diag([sp.csr_matrix(p[i]) for p in parts], format="csr")
               for i in range(3))
    exact = np.concatenate([two_dof_eigenvalues(k1, k2, g)
                            for (k1, k2), g in zip(ks, gs, strict=True)])
    return M, G, K, exact


@pytest.mark.parametrize("method, sigma", [("lanczos", None), ("arpack", None),
                                           ("lanczos", 0), ("arpack", 0)])
def test_block_two_dof_sparse_paths(method, sigma, rng):
    nb = 40
    ks = rng.uniform(1.0, 50.0, size=(nb, 2))
    M, G, K, exact = blocks(ks, rng.uniform(0.5, 3.0, nb))
    w = np.sort(exact.imag[exact.imag > 0])
    res = gyroscopic_modes(M, G, K, 6, method=method, sigma=sigma,
                           estimate=0.9 * w[0] if sigma is None else None)
    assert res.omega == pytest.approx(w[:6], rel=1e-10)
    assert res.info["below_shift"] == 0
    assert np.all(res.eigenvalues.real == 0)


def test_certified_count_below_an_inner_shift(rng):
    nb = 40
    M, G, K, exact = blocks(rng.uniform(1.0, 50.0, size=(nb, 2)), rng.uniform(0.5, 3.0, nb))
    w = np.sort(exact.imag[exact.imag > 0])
    res = gyroscopic_modes(M, G, K, 5, sigma=1j * 0.5 * (w[2] + w[3]))
    assert res.info["below_shift"] == 3        # the inertia of Q(iω_s) counts them
    assert res.omega == pytest.approx(w[:5], rel=1e-10)


@pytest.mark.parametrize("below", [3, 5])
def test_a_counted_factorization_serves_the_solve_below_its_shift(below, rng):
    """solve_qep with the shift's factorization made (and counted) by the caller: the same
    certified frequencies below the shift as the closed form, without a second
    factorization; with count = below only those below the shift are asked for."""
    from gyroshell.linalg import cholesky
    from gyroshell.linalg.factorization import resolve_factorization
    from gyroshell.linalg.inertia import factor_inertia
    from gyroshell.linalg.qep import solve_qep

    nb = 40
    M, G, K, exact = blocks(rng.uniform(1.0, 50.0, size=(nb, 2)), rng.uniform(0.5, 3.0, nb))
    w = np.sort(exact.imag[exact.imag > 0])
    ws = 0.5 * (w[below - 1] + w[below])
    Q = (K - ws**2 * M + 1j * ws * G).tocsc()
    counted = cholesky.ldl(Q) if resolve_factorization("auto") == "cholmod" else None
    factor = counted or factor_inertia(Q)
    assert factor.negatives == below
    for count in (below, 2):
        pairs = solve_qep(M, G, K, count, sigma=1j * ws, definite=True, shift_factor=factor)
        assert pairs.info["shift_factor_reused"] is True
        assert pairs.info["below_shift"] == below
        assert pairs.eigenvalues.imag == pytest.approx(w[:count], rel=1e-10)
        assert pairs.residuals.max() < 1e-14
    if counted is not None:
        counted.release()
    with pytest.raises(ParameterError, match="shift_factor needs an explicit sigma"):
        solve_qep(M, G, K, 2, shift_factor=factor)


def random_system(rng, n: int, *, damping: float = 0.0):
    X = rng.standard_normal((n, n))
    M = X @ X.T / n + np.eye(n)                  # SPD, full
    Y = rng.standard_normal((n, n))
    K = Y @ Y.T / n + 0.5 * np.eye(n)            # SPD
    S = rng.standard_normal((n, n))
    G = 0.5 * (S - S.T)                          # skew
    Z = rng.standard_normal((n, 3))
    C = damping * (Z @ Z.T)                      # PSD, rank 3
    return M, G, K, C


def dense_eigenvalues(M, G, K, C=None) -> np.ndarray:
    n = len(M)
    D = G if C is None else G + C
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -D]])
    B = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), M]])
    return la.eig(A, B, right=False)


@pytest.mark.parametrize("method", ["lanczos", "arpack"])
def test_random_undamped_against_dense(method, rng):
    M, G, K, _ = random_system(rng, 60)
    ref = dense_eigenvalues(M, G, K)
    w = np.sort(ref.imag[ref.imag > 0])
    res = gyroscopic_modes(sp.csr_matrix(M), G, K, 5, method=method)
    assert res.omega == pytest.approx(w[:5], rel=1e-10)
    assert res.residuals.max() < 1e-12


def test_random_damped_against_dense(rng):
    M, G, K, C = random_system(rng, 60, damping=0.02)
    ref = dense_eigenvalues(M, G, K, C)
    up = ref[ref.imag > 0]
    up = up[np.argsort(up.imag)]
    res = gyroscopic_modes(M, G, K, 4, C=C, estimate=0.95 * up[0].imag)
    assert res.damped and not res.supercritical
    assert res.eigenvalues == pytest.approx(up[:4], rel=1e-10)
    assert np.all(res.decay_rate > 0) and res.stability == "stable"
    assert res.damping_ratio == pytest.approx(-up[:4].real / np.abs(up[:4]), rel=1e-8)


# ----- the tape with damping: C ∝ M ------------------------------------------------------------
@pytest.mark.parametrize("damping_of", [lambda c, rho: c, lambda c, rho: (c / rho, 0.0)])
def test_mass_proportional_damping_shifts_every_eigenvalue(damping_of):
    """C = cW = (c/ρ) M at V = 0: ρλ² + cλ + μ = 0 with ω² = μ/ρ, so every eigenvalue is
    −c/(2ρ) ± i√(ω² − (c/2ρ)²)."""
    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8))
    rho = model.params.density
    free = modes(model, 0.0, 5)
    c = 0.2 * rho * free.omega[0]              # 10 % of critical damping for mode 1
    res = modes(model, 0.0, 5, damping=damping_of(c, rho))
    delta = c / (2 * rho)
    exact = -delta + 1j * np.sqrt(free.omega**2 - delta**2)
    assert res.damped
    assert np.abs(res.eigenvalues - exact).max() < 1e-10 * np.abs(exact).max()
    assert res.decay_rate == pytest.approx(np.full(5, delta), rel=1e-9)
    assert res.damping_ratio[0] == pytest.approx(0.1, rel=1e-9)


def test_damping_refusals():
    model = TapeModel(TapeParameters(length_ratio=1.0, spacing=WIDTH / 8))
    for bad, match in ((-1.0, "damping must be >= 0 N\\*s/m\\^3, got -1"),
                       ("x", "damping must be a real number"),
                       ((1.0,), "Rayleigh damping must be a pair"),
                       ((1.0, -2.0), "stiffness_coefficient must be >= 0 s, got -2")):
        with pytest.raises(ParameterError, match=match):
            modes(model, 0.0, 2, damping=bad)


# ----- classification and refusals ---------------------------------------------------------------
def test_classify_stability():
    assert classify_stability([1j, 2j]) == "stable"
    assert classify_stability([-0.1 + 1j]) == "stable"
    assert classify_stability([0.5 + 0j, 1j]) == "divergence"
    assert classify_stability([0.1 + 2j]) == "flutter"
    assert classify_stability([0.1 + 2j, 0.3 + 0j]) == "divergence"
    assert classify_stability([1e-14 + 1j]) == "stable"     # round-off is not growth


@pytest.mark.parametrize("mutate, match", [
    (lambda M, G, K: (M, G, K + np.triu(np.ones_like(K), 1)), "K must be symmetric"),
    (lambda M, G, K: (M, G + np.eye(len(G)), K), "G must be skew-symmetric"),
    (lambda M, G, K: (M + np.triu(np.ones_like(M), 1), G, K), "M must be symmetric"),
    (lambda M, G, K: (-M, G, K), "M must be positive definite"),
    (lambda M, G, K: (M, G, K[:-1, :-1]), "K must have the shape of M"),
    (lambda M, G, K: (M, G, K * np.nan), "K must be finite"),
    (lambda M, G, K: (M, G * 1j, K), "G must be real"),
    (lambda M, G, K: (M[:, :-1], G, K), "M must be square"),
])
def test_structure_refusals(mutate, match, rng):
    M, G, K, _ = random_system(rng, 6)
    with pytest.raises(ParameterError, match=match):
        gyroscopic_modes(*mutate(M, G, K), 2)


def test_option_refusals(rng):
    M, G, K, C = random_system(rng, 6, damping=1.0)
    with pytest.raises(ParameterError, match="C must be positive semi-definite"):
        gyroscopic_modes(M, G, K, 2, C=-C)
    with pytest.raises(ParameterError, match="C must be symmetric"):
        gyroscopic_modes(M, G, K, 2, C=C + np.triu(np.ones_like(C), 1))
    for count in (0, None, 2.5, 7):
        with pytest.raises(ParameterError, match="count must be"):
            gyroscopic_modes(M, G, K, count)
    with pytest.raises(ParameterError, match="method must be"):
        gyroscopic_modes(M, G, K, 2, method="qr")


def test_count_limit_is_finite_for_large_problems():
    assert max_count(DENSE_LIMIT) == DENSE_LIMIT
    assert max_count(10**6) == max_count(10**5) < 10**3


@pytest.mark.slow
def test_damped_navier_frequencies_converge_second_order():
    """All sides simply supported, V = 0, C = cW: λ = −c/2ρ ± i√(ω_mn² − (c/2ρ)²) with the
    Navier ω_mn; the discrete damped frequencies converge to it at second order."""
    from closed_forms import navier_frequency
    from convergence import observed_order

    from gyroshell import Grid

    p = TapeParameters(edges="simply-supported", length_ratio=2.0, spacing=WIDTH / 8,
                       foundation_stiffness=1e6)
    exact_w = sorted(navier_frequency(p, m, n) for m in range(1, 8) for n in range(1, 8))[:3]
    c = 0.1 * p.density * exact_w[0]
    delta = c / (2 * p.density)
    exact = -delta + 1j * np.sqrt(np.array(exact_w) ** 2 - delta**2)
    grid = Grid.from_parameters(p)
    steps, errs = [], []
    for _ in range(3):
        res = modes(TapeModel(p, grid), 0.0, 3, damping=c)
        errs.append(np.abs(res.eigenvalues - exact) / np.abs(exact))
        steps.append(grid.hx)
        grid = grid.refined()
    errs = np.array(errs)
    for j in range(3):
        assert observed_order(steps, errs[:, j]) == pytest.approx(2.0, abs=0.1)
    assert res.decay_rate == pytest.approx(np.full(3, delta), rel=1e-9)


@pytest.mark.parametrize("name", ["gyroshell.studies.stability",
                                  "gyroshell.linalg.factorization"])
def test_docstring_examples(name):
    import doctest
    import importlib

    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0


def test_classify_stability_refuses_empty_or_nonfinite():
    with pytest.raises(ParameterError, match="at least one eigenvalue"):
        classify_stability([])
    with pytest.raises(ParameterError, match="finite"):
        classify_stability([np.nan + 1j])


def test_out_of_range_damping_is_a_clean_convergence_error():
    from gyroshell import ConvergenceError

    model = TapeModel(TapeParameters(length_ratio=1.0, spacing=WIDTH / 8))
    with pytest.raises(ConvergenceError, match="out of floating-point range"):
        modes(model, 0.0, 2, damping=1e300)


def test_one_superlu_helper_serves_lu_and_inertia(rng):
    """linalg.factorization.splu is the package's SuperLU: general LU and the symmetric-mode
    LDLᴴ whose pivots factor_inertia counts."""
    from gyroshell.linalg.factorization import splu
    from gyroshell.linalg.inertia import factor_inertia

    X = rng.standard_normal((60, 60))
    A = sp.csc_matrix(X + X.T - 3.0 * np.eye(60))
    b = rng.standard_normal(60)
    assert np.allclose(A @ splu(A).solve(b), b)
    lu = splu(A, symmetric_mode=True)
    assert np.array_equal(lu.perm_r, lu.perm_c)   # diagonal pivots only
    negatives = int(np.count_nonzero(np.linalg.eigvalsh(A.toarray()) < 0))
    assert factor_inertia(A).negatives in (None, negatives)
    with pytest.raises(RuntimeError):
        splu(sp.csc_matrix((3, 3)))


def test_a_checked_solve_gives_the_same_pairs_and_the_family_proof_refuses_flaws(rng):
    """solve_qep(checked=True) skips only the structure checks: the block 2-DOF closed form
    and bit-identical eigenvalues to the checked call; check_family proves (M, V·G1,
    A + τB) for every V, τ from its parts and names a non-symmetric A or B (each on its
    own scale), a non-skew G1, an indefinite M."""
    from gyroshell.linalg.qep import check_family, solve_qep

    nb = 30
    ks = rng.uniform(1.0, 50.0, size=(nb, 2))
    M, G, K, exact = blocks(ks, rng.uniform(0.5, 3.0, nb))
    w = np.sort(exact.imag[exact.imag > 0])
    plain = solve_qep(M, G, K, 4, estimate=0.9 * w[0])
    trusted = solve_qep(M, G, K, 4, estimate=0.9 * w[0], checked=True)
    assert np.array_equal(plain.eigenvalues, trusted.eigenvalues)
    assert trusted.eigenvalues.imag == pytest.approx(w[:4], rel=1e-10)
    B = sp.identity(M.shape[0], format="csr")
    check_family(M, G, K, B)   # no error
    skew = sp.csr_matrix(np.triu(np.ones(M.shape), 1))
    with pytest.raises(ParameterError, match="B must be symmetric"):
        check_family(M, G, K, B + skew)
    with pytest.raises(ParameterError, match="A must be symmetric"):
        check_family(M, G, K + skew, B)
    with pytest.raises(ParameterError, match="B must be symmetric"):
        check_family(M, G, K, 1e-9 * (B + skew))   # a small B's flaw is not masked by A
    with pytest.raises(ParameterError, match="M must be positive definite"):
        check_family(-M, G, K, B)
    with pytest.raises(ParameterError, match="G must be skew-symmetric"):
        check_family(M, G + B, K, B)


def test_a_warm_start_with_no_part_in_the_problem_starts_at_random(rng):
    """Previous modes whose vectors vanish here (all symmetric ones projected on the
    antisymmetric half of a tape) give a zero start vector; the solve starts from the
    random one instead of an unset basis vector (it used to fill H with NaN): the block
    2-DOF closed form."""
    nb = 30
    ks = rng.uniform(1.0, 50.0, size=(nb, 2))
    M, G, K, exact = blocks(ks, rng.uniform(0.5, 3.0, nb))
    w = np.sort(exact.imag[exact.imag > 0])
    zero_start = (1j * w[:3], np.zeros((M.shape[0], 3), dtype=complex))
    res = gyroscopic_modes(M, G, K, 3, estimate=0.9 * w[0], start=zero_start)
    assert res.omega == pytest.approx(w[:3], rel=1e-10)


def test_the_gram_schmidt_products_are_the_energy_inner_products(rng):
    """The Lanczos basis's BLAS products: ⟨v_i, w⟩ = v_iᴴ(Lw) for every row v_i, and
    w − Σ h_i v_i in place, also for a w that BLAS cannot overwrite (a strided view)."""
    from gyroshell.linalg.qep.lanczos import _coefficients, _subtract

    V = rng.standard_normal((7, 50)) + 1j * rng.standard_normal((7, 50))
    Lw = rng.standard_normal(50) + 1j * rng.standard_normal(50)
    h = _coefficients(V, Lw)
    assert np.allclose(h, [np.vdot(v, Lw) for v in V], rtol=1e-14, atol=0)
    for w in (Lw.copy(), np.repeat(Lw, 2)[::2]):
        expected = w - sum(hi * v for hi, v in zip(h, V, strict=True))
        _subtract(w, V, h)
        assert np.allclose(w, expected, rtol=0, atol=1e-13 * np.abs(expected).max())
