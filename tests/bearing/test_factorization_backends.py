"""The factorizations of the bearing's Jacobian (``factorization=`` of BearingModel) give
the same steady state: Newton's answer does not depend on how its linear systems are
solved, only its path may. Checked on a 2-D tape flying clear of the head and on one
whose land touches down (contact), against SuperLU with partial pivoting ("colamd", the
earlier default).

The LU with diagonal pivots (:class:`gyroshell.linalg.factorization.DiagonalPivotLU`) is
checked against solutions known by construction (b = A x for a chosen x), and its
fallback to partial pivoting on a matrix whose diagonal is zero; the nested-dissection
ordering is a permutation; the switch is validated; without pymetis "auto" is pure
scipy (the grid's nested dissection, :mod:`gyroshell.linalg.grid_ordering`)."""

from __future__ import annotations

import math
import sys
import warnings

import numpy as np
import pytest
import scipy.sparse as sp
from bearing_cases import FIRST_ORDER, HARD

from gyroshell import ParameterError, TapeParameters
from gyroshell.bearing import BearingModel, steady
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.model import BearingGridWarning
from gyroshell.linalg import factorization as fz

AIR = FIRST_ORDER
#: Two modules, the second raised by 0.3 µm: a 2 mm tape touches down on the second land.
TWO = FlatHead((Module(0.8e-3), Module(0.5e-3, height=0.3e-6)), math.radians(1.5),
               math.radians(3.0), gaps=(0.2e-3,))
#: The back-ends installed here, besides the reference "colamd" and "auto" (which is
#: "grid": the test without pymetis solves with it).
BACKENDS = [b for b in fz.PATTERN_LU if b not in ("colamd", "auto")
            and {"metis": fz.metis_available,
                 "pardiso": fz.PardisoFactor.available}.get(b, lambda: True)()]


def _clear(factorization):
    """A 3 mm tape flying clear of a 15° cylinder (no contact)."""
    return BearingModel(TapeParameters(width=3e-3), AIR, velocity=4.0,
                        wrap_angle=math.radians(15.0), nx=64, ny=16, span=2e-3,
                        factorization=factorization, contact=HARD)


def _touching(factorization):
    """A 2 mm tape over two modules, touching down on the raised land."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        return BearingModel(TapeParameters(width=2e-3), AIR, velocity=4.0, head=TWO,
                            nx=96, ny=16, factorization=factorization, contact=HARD)


@pytest.fixture(scope="module")
def references():
    return {case: steady.solve_steady(build("colamd"))
            for case, build in (("clear", _clear), ("touching", _touching))}


def _same_state(a, b, tol=steady.STEP_TOLERANCE):
    """States equal to Newton's tolerance, relative to the scales the step is measured
    in (the spacing scale h_scale and the wrap pressure T/R, :func:`steady._norm`)."""
    F = steady._Residual(a.model, None, None)
    du = np.max(np.abs(a.u - b.u)) / F.h_scale
    dp = np.max(np.abs(a.p - b.p)) / F.t_scale
    return max(du, dp) < 100 * tol, (du, dp)


#: PARDISO analyses the pattern at every factorization and is slow on a loaded machine
#: (OpenMP): its cases are slow tests.
CASES = [pytest.param(b, c, marks=[pytest.mark.slow] if b == "pardiso" else [])
         for b in BACKENDS for c in ("clear", "touching")
         if not (b == "pardiso" and c == "touching")]


@pytest.mark.parametrize(("backend", "case"), CASES)
def test_every_backend_reaches_the_same_state(references, backend, case):
    ref = references[case]
    build = _clear if case == "clear" else _touching
    sol = steady.solve_steady(build(backend))
    ok, diff = _same_state(sol, ref)
    assert ok, diff
    assert sol.contact_nodes == ref.contact_nodes
    assert (ref.contact_nodes > 0) == (case == "touching")


def _grid_matrix(n=12):
    """A nonsymmetric matrix with the pattern of a 2-D grid: the 5-point Laplacian plus
    a convective (upwind) term and a shift, diagonally dominant."""
    one = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n))
    upwind = sp.diags([-1.0, 1.0], [-1, 0], shape=(n, n))
    eye = sp.identity(n)
    return (sp.kron(one, eye) + sp.kron(eye, one) + 0.5 * sp.kron(upwind, eye)
            + 0.1 * sp.identity(n * n)).tocsc()


@pytest.mark.skipif(not fz.metis_available(), reason="pymetis not installed")
def test_nested_dissection_is_a_permutation_that_fills_less():
    A = _grid_matrix(24)
    perm = fz.nested_dissection(A)
    assert np.array_equal(np.sort(perm), np.arange(A.shape[0]))
    ordered = fz.DiagonalPivotLU(A, permutation=perm)
    natural = fz.DiagonalPivotLU(A, permutation=np.arange(A.shape[0]))
    # the banded natural order fills n^(3/2) per row band; dissection far less
    assert ordered._lu.nnz < 0.8 * natural._lu.nnz


@pytest.mark.parametrize("ordered", [False, True])
def test_diagonal_pivot_lu_solves_to_round_off(ordered):
    if ordered and not fz.metis_available():
        pytest.skip("pymetis not installed")
    A = _grid_matrix()
    x = np.cos(np.arange(A.shape[0]))
    lu = fz.DiagonalPivotLU(A, permutation=fz.nested_dissection(A) if ordered else None)
    got = lu.solve(A @ x)
    assert not lu.pivoted
    assert np.max(np.abs(got - x)) < 1e-13 * np.max(np.abs(x)) * np.linalg.cond(A.toarray())


def test_a_small_diagonal_pivot_falls_back_to_partial_pivoting():
    """[[d, 1], [1, 1]] blocks in their natural order: the diagonal pivot d = 1e-15 grows
    the factors by 1/d (backward error about 1e-2), partial pivoting solves them to
    round-off."""
    A = sp.kron(sp.identity(5), sp.csr_matrix([[1e-15, 1.0], [1.0, 1.0]])).tocsc()
    x = np.cos(np.arange(10.0))
    lu = fz.DiagonalPivotLU(A, permutation=np.arange(10))
    got = lu.solve(A @ x)
    assert lu.pivoted
    assert np.max(np.abs(got - x)) < 1e-14


def test_single_precision_factors_solve_to_their_backward_error_limit():
    """Factors in single precision (ε = 1.2e-7): a solve's backward error is a small multiple
    of ε, below SINGLE_BACKWARD_ERROR_LIMIT, and the error of x within cond(A) times it;
    the factors stay single."""
    A = _grid_matrix()
    x = np.cos(np.arange(A.shape[0]))
    lu = fz.DiagonalPivotLU(A, permutation=np.arange(A.shape[0]), single=True)
    got = lu.solve(A @ x)
    eps = np.finfo(np.float32).eps
    assert lu.single and not lu.pivoted
    assert lu.backward_error(got, A @ x) < 10 * eps < fz.SINGLE_BACKWARD_ERROR_LIMIT
    assert np.max(np.abs(got - x)) < 10 * eps * np.linalg.cond(A.toarray())


def test_single_precision_falls_back_to_double_then_to_partial_pivoting():
    """The [[d, 1], [1, 1]] blocks of the test below in single precision: the pivot
    d = 1e-15 spoils the single factors too (backward error about 1), so the matrix is
    factored again in double, and then with partial pivoting: x to round-off."""
    A = sp.kron(sp.identity(5), sp.csr_matrix([[1e-15, 1.0], [1.0, 1.0]])).tocsc()
    x = np.cos(np.arange(10.0))
    lu = fz.DiagonalPivotLU(A, permutation=np.arange(10), single=True)
    got = lu.solve(A @ x)
    assert not lu.single and lu.pivoted
    assert np.max(np.abs(got - x)) < 1e-14


@pytest.mark.parametrize("bad", ["umfpack", "METIS", 3, None])
def test_the_switch_is_validated(bad):
    with pytest.raises(ParameterError,
                       match=r"factorization must be one of auto, grid, metis"):
        _clear(bad)


def test_without_pymetis_auto_is_pure_scipy(monkeypatch, references):
    monkeypatch.setitem(sys.modules, "pymetis", None)      # import pymetis fails
    assert not fz.metis_available()
    assert fz.resolve_pattern_lu("auto") == "grid"
    with pytest.raises(ParameterError, match="factorization 'metis' needs the optional "
                                             "package pymetis"):
        _clear("metis")
    sol = steady.solve_steady(_clear("auto"))
    assert _same_state(sol, references["clear"])[0]


def test_the_cli_choices_are_the_library_s():
    from gyroshell.cli.bearing import FACTORIZATION_CHOICES

    assert FACTORIZATION_CHOICES == fz.PATTERN_LU


def test_the_cli_refuses_an_unknown_factorization_in_one_line(cli):
    run = cli(["bearing", "--factorization", "lapack"])
    assert run.code == 2 and len(run.error_lines) == 1
    assert "--factorization" in run.err and "invalid choice: 'lapack'" in run.err
    assert "Traceback" not in run.err and run.out == ""
