"""The tape's mirror symmetry about its centre line (gyroshell.tape.mirror): the reflection
commutes with the operators, the two halves are an orthogonal splitting, and the eigen-solver
on the halves returns the full problem's modes, each symmetric or antisymmetric as the
Navier modes sin(mπx/L_x) sin(nπy/L_y) are for odd and even n."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
from closed_forms import navier_frequency
from conftest import moving_string

from gyroshell import ParameterError, TapeModel, TapeParameters
from gyroshell.engines.eigen import modes
from gyroshell.tape.mirror import _reflection, mirror_split

pytestmark = pytest.mark.usefixtures("every_factorization")

WIDTH = 6.35e-3


@pytest.mark.parametrize("edges", ["free", "simply-supported"])
def test_reflection_commutes_and_the_halves_split_orthogonally(edges):
    model = TapeModel(TapeParameters(edges=edges, length_ratio=2.0, spacing=WIDTH / 9))
    split = mirror_split(model)
    assert split is not None
    g = model.grid
    R, _, _ = _reflection(g.n_lines, g.n_across)
    for A in (model.K(40.0), model.G(40.0), sp.diags(model.mass_diagonal, format="csr")):
        assert abs(R @ A @ R - A).max() <= 1e-13 * abs(A).max()
    P = sp.hstack([split.symmetric, split.antisymmetric]).toarray()
    assert P.shape == (model.unknowns, model.unknowns)
    assert np.allclose(P.T @ P, np.eye(model.unknowns), atol=1e-14)
    assert np.allclose(R @ split.symmetric.toarray(), split.symmetric.toarray())
    assert np.allclose(R @ split.antisymmetric.toarray(), -split.antisymmetric.toarray())
    M_s, G_s, K_s = split.matrices(model, 40.0, "symmetric")
    assert np.allclose(K_s.toarray(), (split.symmetric.T @ model.K(40.0) @ split.symmetric)
                       .toarray(), rtol=0, atol=1e-9 * abs(K_s).max())
    assert abs(G_s + G_s.T).max() == 0
    assert (M_s - sp.diags(M_s.diagonal())).count_nonzero() == 0


@pytest.mark.parametrize("divisions", [8, 9])   # an odd and an even number across
def test_the_folded_halves_are_the_projections(divisions):
    """The halves folded from one side's rows by the mirror permutation equal the triple
    products P_hᵀ X P_h of the orthonormal bases (X = A, B, M, G, each half), and
    A_h + τB_h on the shared pattern is P_hᵀ(A + τB)P_h."""
    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / divisions))
    split = mirror_split(model)
    g = model.grid
    _, P_s, P_a = _reflection(g.n_lines, g.n_across)
    assert abs(split.symmetric - P_s).max() == 0 and abs(split.antisymmetric - P_a).max() == 0
    M = sp.diags(model.mass_diagonal, format="csr")
    tau = -0.7 * model.params.tension
    for which, P in (("symmetric", P_s), ("antisymmetric", P_a)):
        A_h, B_h = split.stiffness(which)
        M_h, G_h, K_h = split.matrices(model, 30.0, which)
        for folded, X in ((A_h, model.A), (B_h, model.B), (M_h, M), (G_h, model.G(30.0)),
                          (K_h, model.K(30.0)), (split.combination(which, tau),
                                                 model.A + tau * model.B)):
            exact = (P.T @ X @ P).toarray()
            assert np.abs(folded.toarray() - exact).max() <= 1e-13 * np.abs(exact).max()
        assert np.array_equal(A_h.indices, B_h.indices)


@pytest.mark.parametrize("velocity", [0.0, 60.0, 95.0])
def test_the_splits_full_norms_are_the_assembled_matrices(velocity):
    """‖K(V)‖₁ and ‖G(1 m/s)‖₁ kept by the split (for the halves' backward errors) equal the
    largest absolute column sums of the assembled full matrices, computed densely here."""
    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8))
    split = mirror_split(model)
    K, G1 = model.K(velocity).toarray(), model.G(1.0).toarray()
    expected = np.abs(K).sum(axis=0).max()
    got = split.stiffness_norm(model.effective_tension(velocity))
    assert got == pytest.approx(expected, rel=1e-14)
    assert split.gyroscopic_norm == pytest.approx(np.abs(G1).sum(axis=0).max(), rel=1e-14)


def test_an_asymmetric_model_has_no_split():
    """One entry of A changed on one side of the centre line breaks R A R = A."""
    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8))
    A = model.A.tolil()
    A[3, 3] *= 1 + 1e-9
    model.__dict__["A"] = A.tocsr()
    assert mirror_split(model) is None
    assert "mirror" not in modes(model, 0.0, 2).info


def test_navier_modes_split_by_the_parity_of_n():
    """All sides simply supported at V = 0: ω_mn closed form; n odd is symmetric about the
    centre line, n even antisymmetric; the half-width solves find each in its half."""
    p = TapeParameters(edges="simply-supported", length_ratio=2.0, spacing=WIDTH / 24,
                       foundation_stiffness=1.0e6)
    model = TapeModel(p)
    pairs = sorted((navier_frequency(p, m, n), n) for m in range(1, 12) for n in range(1, 6))
    res = modes(model, 0.0, 6)
    assert res.info["mirror"]["antisymmetric"] > 0          # both halves contribute
    g = model.grid
    R, _, _ = _reflection(g.n_lines, g.n_across)
    for omega, phi, (exact, n) in zip(res.omega, res.vectors.T, pairs[:6], strict=True):
        assert omega == pytest.approx(exact, rel=1e-2)      # O(h²) from the closed form
        parity = 1 if n % 2 else -1
        assert np.linalg.norm(R @ phi - parity * phi) < 1e-10 * np.linalg.norm(phi)


@pytest.mark.slow
@pytest.mark.parametrize("velocity", [0.0, 50.0, 90.0])
def test_halves_give_the_full_problem(velocity):
    model = TapeModel(TapeParameters(length_ratio=4.0))
    for count in (1, 6, 9):
        split = modes(model, velocity, count)
        full = modes(model, velocity, count, symmetry=False)
        assert "mirror" not in full.info
        if velocity < 80:  # K(V) > 0 proved by the stiffness floor without a factorization
            assert split.info["mirror"]["symmetric"] + split.info["mirror"][
                "antisymmetric"] == count
        assert np.max(np.abs(split.omega - full.omega) / full.omega) < 1e-10
        assert split.residuals.max() < 1e-14
        corr = np.abs(np.sum(split.vectors.conj() * full.vectors, axis=0)) / (
            np.linalg.norm(split.vectors, axis=0) * np.linalg.norm(full.vectors, axis=0))
        assert np.all(corr > 1 - 1e-8)                         # the same mode shapes


def test_models_without_the_symmetry_use_the_full_problem():
    string = moving_string(16)                 # a duck-typed width-uniform model
    assert mirror_split(string) is None
    res = modes(string, 10.0, 3)
    assert "mirror" not in res.info
    with pytest.raises(ParameterError, match="symmetry must be True or False"):
        modes(TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8)), 0.0, 2,
              symmetry="yes")


@pytest.mark.slow
def test_a_previous_speeds_split_guides_the_next_and_a_wrong_guess_is_caught():
    """Continuation asks the symmetric half for one more mode than the previous speed had;
    if that and the counted antisymmetric ones do not reach ``count``, it asks again."""
    model = TapeModel(TapeParameters(length_ratio=4.0))
    previous = modes(model, 45.0, 6)
    full = modes(model, 50.0, 6, symmetry=False)
    guided = modes(model, 50.0, 6, start=previous)
    assert np.max(np.abs(guided.omega - full.omega) / full.omega) < 1e-10
    info = dict(previous.info, mirror=dict(previous.info["mirror"], symmetric=0))
    wrong = modes(model, 50.0, 6, start=type(previous)(
        previous.grid, previous.velocity, previous.eigenvalues, previous.vectors,
        previous.residuals, False, info, False))
    assert np.max(np.abs(wrong.omega - full.omega) / full.omega) < 1e-10
