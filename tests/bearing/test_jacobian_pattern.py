"""Newton's Jacobian assembled into its grid's fixed pattern (:mod:`gyroshell.bearing.jacobian`)
is the folded Jacobian J[rows, :] P formed the plain way (sparse products of the whole
matrix with the mirror), entry for entry, for any contact set and floored spacings, in
the natural and in a nested-dissection order; its solver gives the same Newton step as a
dense solve of the whole (unfolded) system. The start's bilinear interpolation is exact on
bilinear fields."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp
from bearing_cases import FIRST_ORDER, HARD

from gyroshell import TapeParameters
from gyroshell.bearing import BearingModel, problem, steady
from gyroshell.bearing.jacobian import JacobianPattern
from gyroshell.linalg import factorization as fz


def _model(factorization="auto", infinitely_wide=False):
    return BearingModel(TapeParameters(width=3e-3), FIRST_ORDER, velocity=4.0,
                        wrap_angle=math.radians(15.0), nx=48, span=2e-3,
                        ny=None if infinitely_wide else 16, factorization=factorization,
                        infinitely_wide=infinitely_wide, contact=HARD)


def _state(model, rng):
    """A perturbed start with some nodes pressed below the film's floor σ/2 (their
    columns of ∂r_p/∂u drop out) and a contact set of a few mirror-symmetric nodes."""
    z = model.initial_state()
    z[:model.n_u] *= 1 + 0.3 * rng.random(model.n_u)
    z[model.n_u:] += 2000.0 * rng.random(model.n_p)
    low = np.flatnonzero(np.abs(np.arange(model.n_u) % model.nc - model.nc // 2) == 3)[:4]
    z[low] = -model.dry_field[1:-1, :].ravel()[low]            # h = 0 < σ/2 there
    active = np.zeros(model.n_u, dtype=bool)
    edge = np.arange(model.n_u) % model.nc
    active[(edge == 0) | (edge == model.ny)] = True              # both free edges
    return z, active


def _plain_fold(model, J):
    P, rows = model.mirror
    return (sp.csr_matrix(J)[rows, :] @ P).toarray()


@pytest.mark.parametrize("ordered", [False, True])
def test_the_assembled_fold_is_the_folded_jacobian(rng, ordered):
    if ordered and not fz.metis_available():
        pytest.skip("pymetis not installed")
    model = _model()
    F = steady._Residual(model, None, None)
    z, active = _state(model, rng)
    _, got_active, lin = F(z, jacobian=True, active=active)
    assert np.array_equal(got_active, active) and not lin.free.all()
    pattern = JacobianPattern(F.tape_rows, lin.J_h, lin.J_p, model.nc, model.mirror)
    if ordered:
        pattern.order(fz.nested_dissection(pattern.graph()))
    A = pattern.matrix(F.tape_rows.data, lin.active, F.c, lin.J_h, lin.J_p, lin.free)
    expected = _plain_fold(model, lin.matrix)
    perm = np.arange(A.shape[0]) if pattern.permutation is None else pattern.permutation
    assert np.allclose(A.toarray(), expected[np.ix_(perm, perm)], rtol=1e-14, atol=0.0)
    # every entry the grid can have, contact rows' off-diagonal ones as zeros
    assert A.nnz >= np.count_nonzero(expected)


@pytest.mark.parametrize("infinitely_wide", [False, True])
def test_the_factored_step_solves_the_whole_system(rng, infinitely_wide):
    """The solver of the assembled pattern (half the width in 2-D) gives −J⁻¹ r of the
    whole system, to round-off: the step is mirror-symmetric because the state is."""
    model = _model(infinitely_wide=infinitely_wide)
    F = steady._Residual(model, None, None)
    z = model.initial_state()
    res, _, lin = F(z, jacobian=True)
    step = F.factor(lin)(res)
    J = lin.matrix
    assert np.linalg.norm(J @ step + res) <= 1e-10 * np.linalg.norm(res)


def test_reused_film_blocks_give_the_fresh_linearization(rng):
    """Newton's contact-set steps reuse the iterate's film blocks and residual rows: with
    another contact set they equal a linearization formed afresh at the same state, bit
    for bit (only the contact rows depend on the set), and the film's blocks formed alone
    equal those formed with the residual, with the same round-off floor."""
    model = _model()
    F = steady._Residual(model, None, None)
    z, active = _state(model, rng)
    res, rule, lin = F(z, jacobian=True)
    other = rule.copy()
    other[rng.choice(model.n_u, 20, replace=False)] ^= True
    assert not np.array_equal(other, rule)
    fresh_res, _, fresh = F(z, jacobian=True, active=other)
    noise = F.noise
    u, p = z[:model.n_u], z[model.n_u:]
    got_res, got_active = F.contact_rows(u, F.tape(u, p), res[model.n_u:], other)
    assert np.array_equal(got_active, other) and np.array_equal(got_res, fresh_res)
    reused = F.with_contact(lin, other)
    assert (reused.matrix != fresh.matrix).nnz == 0
    alone = F.linearize(z, other)
    assert F.noise == noise
    assert (alone.matrix != fresh.matrix).nnz == 0
    forced = np.zeros(model.n_u, dtype=bool)
    forced[:5] = True
    assert np.array_equal(F.contact_rows(u, F.tape(u, p), res[model.n_u:], force=forced)[0],
                          F(z, jacobian=False, force=forced)[0])


def test_the_model_keeps_its_pattern_until_the_tape_rows_change(rng, monkeypatch):
    """The folded pattern is looked up by the digest kept on the model: a second solve's
    tape rows with the same pattern form no digest; tape rows of another pattern (an
    entry added) get their own pattern, which assembles their folded Jacobian."""
    digests = []
    original = problem._pattern_digest
    monkeypatch.setattr(problem, "_pattern_digest",
                        lambda *a: digests.append(1) or original(*a))
    model = _model()
    kind = steady._jacobian_lu(model)
    z, active = _state(model, rng)
    F = steady._Residual(model, None, None)
    lin = F(z, jacobian=True, active=active)[2]
    first = F._pattern(kind, lin)
    again = steady._Residual(model, None, None)
    assert again._pattern(kind, lin) is first and len(digests) == 1
    changed = steady._Residual(model, None, None)
    row = 5 * model.nc       # coupled to the node three x-lines on: off the plate's stencil
    extra = sp.csr_matrix(([1.0], ([row], [row + 3 * model.nc])),
                          shape=changed.tape_rows.shape)
    changed.tape_rows = (changed.tape_rows + extra).tocsr()
    changed.tape_rows.sort_indices()
    assert changed.tape_rows.nnz > F.tape_rows.nnz
    pattern = changed._pattern(kind, lin)
    assert pattern is not first and len(digests) == 2
    lin_c = steady.Linearization(changed, active, lin.J_h, lin.J_p, lin.free)
    A = pattern.matrix(changed.tape_rows.data, active, changed.c, lin.J_h, lin.J_p, lin.free)
    perm = np.arange(A.shape[0]) if pattern.permutation is None else pattern.permutation
    expected = _plain_fold(model, lin_c.matrix)
    assert np.allclose(A.toarray(), expected[np.ix_(perm, perm)], rtol=1e-14, atol=0.0)
