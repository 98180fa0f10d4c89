"""gyroscopic_modes estimates its memory before any work (issue 18, cause 1): a system that
cannot fit is refused with a ParameterError naming the unknowns, the estimate and the
limit. The big system is never built: the limit is lowered instead, and the 3e7-unknown
estimate is computed from its sizes alone."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from gyroshell import ParameterError, gyroscopic_modes
from gyroshell.core.budget import MEMORY_LIMIT_VARIABLE
from gyroshell.linalg.qep.problem import qep_bytes


def chain(n: int):
    """A spring-mass chain with a skew coupling: M = I, G, K tridiagonal."""
    K = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1], format="csr")
    G = sp.diags([np.ones(n - 1), -np.ones(n - 1)], [-1, 1], format="csr")
    return sp.identity(n, format="csr"), G, K


def test_a_solve_beyond_the_limit_is_refused_before_work(monkeypatch):
    M, G, K = chain(2000)
    monkeypatch.setenv(MEMORY_LIMIT_VARIABLE, "1e6")
    with pytest.raises(ParameterError, match=r"an eigen-solve of 2000 unknowns .* needs "
                                             r"about .* GB, more than the limit 0\.001 GB"):
        gyroscopic_modes(M, G, K, 4)


def test_the_same_solve_runs_under_the_default_limit():
    M, G, K = chain(2000)
    assert gyroscopic_modes(M, G, K, 2).count == 2


def test_thirty_million_unknowns_need_more_than_a_workstation_has():
    # The case: 3e7 unknowns of a 13-point stencil, 6 pairs.
    n = 30_000_000
    assert qep_bytes(n, 3 * 13 * n, 6) > 100e9


def test_the_estimate_grows_with_the_pairs_asked_for():
    assert qep_bytes(10_000, 130_000, 50) > qep_bytes(10_000, 130_000, 6)
