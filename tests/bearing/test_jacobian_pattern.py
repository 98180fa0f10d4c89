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

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel, steady
from gyroshell.bearing.jacobian import JacobianPattern
from gyroshell.linalg import factorization as fz


def _model(factorization="auto", infinitely_wide=False):
    return BearingModel(TapeParameters(width=3e-3), AirParameters(), velocity=4.0,
                        wrap_angle=math.radians(15.0), nx=48, span=2e-3,
                        ny=None if infinitely_wide else 16, factorization=factorization,
                        infinitely_wide=infinitely_wide)


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
