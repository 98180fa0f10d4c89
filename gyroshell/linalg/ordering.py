"""The column ordering of a banded sparse LU: the matrix's own order when its band is narrow.

Newmark's K_eq = M + γΔt (G + C) + βΔt² K on a grid numbered line by line is banded: its
half-bandwidth is about twice the unknowns across the width (the plate's 13-point stencil
reaches two lines on). SuperLU's default minimum-degree ordering (on Aᵀ + A) gives the
least fill, but on a narrow band the natural order (no permutation: the band itself,
larger supernodes and contiguous access) substitutes faster although it fills more. Measured
with one BLAS thread (CPU time of one substitution, medians of 25 alternating solves,
``benchmarks/bench_newmark.py --orderings``, at a load average of 7; natural order against
minimum degree, fill and time):

================================  =====  ==============  ==============
K_eq (Table 1 spacing unless      half-  natural fill    natural time
said; V = 50 m/s, Δt = 2 µs)      band   / min. degree   / min. degree
================================  =====  ==============  ==============
L_x/L_y = 19, symmetric half      42     1.24            0.65
L_x/L_y = 4, symmetric half       42     1.26            0.63
L_x/L_y = 19, s.s., half          40     1.20            0.62
L_x/L_y = 19, 12 intervals, full  26     1.08            0.57
L_x/L_y = 19, 27 intervals, full  56     1.40            1.42
L_x/L_y = 19, full                84     1.53            1.68
L_x/L_y = 4, full                 84     1.64            1.78
================================  =====  ==============  ==============

On a quiet machine the gain is smaller than under load (where the natural order's
contiguous access suffers less from the other jobs): on the L_x/L_y = 19 half at V = 90 m/s
one substitution took 1.51 ms natural against 1.67 ms minimum degree (0.90x) and a whole
Newmark step 2.09 against 2.47 ms (0.85x), alternating rounds, load average 1.5.

So :func:`column_ordering` takes the natural order up to a half-bandwidth of
:data:`NATURAL_HALF_BANDWIDTH` and minimum degree above it: a rule by shape, read off the
pattern in microseconds, with no trial factorization. COLAMD tied the natural order on the
halves and lost to minimum degree on the full grids (1.05-1.25x); LAPACK's banded LU
(dgbtrf/dgbtrs, the "banded" back-end) substituted 1.05-2.65x slower than minimum degree
on every case above, half or full. K_eq is not symmetric (G is skew), so a banded Cholesky
does not apply. The ordering changes the result only at round-off.

The band's substitution. In the natural order with diagonal pivots (SuperLU's symmetric
mode, threshold 0) L and U stay inside the band, so :func:`factorize_banded` ("auto")
copies them into LAPACK band storage and solves by two BLAS ``dtbsv`` calls
(:class:`gyroshell.linalg.factorization.BandLU`): no index arrays, no supernodes. The
unpivoted factors are kept only while ‖ |L||U| ‖∞ ≤ 10 ‖A‖∞ (a bound on every solve's
backward error); on K_eq it is about 0.8, also at V = 90-100 m/s with Δt = 5.5 µs-0.3 ms
where dgbtrf's partial pivoting swapped ~780 rows. CPU time of one substitution, medians
of 11 alternating rounds of 20 solves, one BLAS thread, load average 5-7 (Δt = 2 µs
unless said):

==========================================  =========  ==========  ======
K_eq                                        SuperLU    band        ratio
==========================================  =========  ==========  ======
L_x/L_y = 19, symmetric half, V = 50 m/s    2.37 ms    0.76 ms     0.32
L_x/L_y = 19, s.s., half, V = 90 m/s        1.45 ms    0.61 ms     0.42
L_x/L_y = 4, symmetric half, V = 0          0.25 ms    0.10 ms     0.40
L_x/L_y = 19, half, V = 90, Δt = 5.5 µs     1.84 ms    0.61 ms     0.33
L_x/L_y = 19, full (min. degree), V = 50    7.29 ms    4.12 ms     0.57
==========================================  =========  ==========  ======

(the last with dgbtrf's band, unpivoted there, whose factorization took 3.0 s against
SuperLU's 0.53 s: the full grids keep SuperLU in minimum-degree order). The band's
answers differ from SuperLU's by 3e-16 to 8e-14 of their size.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .factorization import (
    ORDERING,
    BandLU,
    Factorization,
    SuperLUFactor,
    factorize,
    resolve_backend,
)

#: Largest half-bandwidth (in unknowns) at which SuperLU keeps the natural order: between
#: the symmetric halves of the paper's grid (42, faster natural) and the full grids (56 and
#: up, faster minimum degree) measured in the module notes.
NATURAL_HALF_BANDWIDTH = 48
#: SuperLU's name of the natural (identity) column order.
NATURAL = "NATURAL"


def half_bandwidth(matrix: sp.spmatrix) -> int:
    """max |i − j| over the stored entries (i, j) of a sparse matrix (0 for a diagonal)."""
    coo = sp.coo_matrix(matrix)
    if coo.nnz == 0:
        return 0
    return int(np.abs(coo.row.astype(np.int64) - coo.col).max())


def column_ordering(matrix: sp.spmatrix) -> str:
    """SuperLU's column ordering for a banded matrix: :data:`NATURAL` up to a half-bandwidth
    of :data:`NATURAL_HALF_BANDWIDTH`, else the package's minimum degree
    (:data:`gyroshell.linalg.factorization.ORDERING`)."""
    return NATURAL if half_bandwidth(matrix) <= NATURAL_HALF_BANDWIDTH else ORDERING


def factorize_banded(matrix: sp.spmatrix, backend: str = "auto") -> Factorization:
    """:func:`gyroshell.linalg.factorization.factorize` for a banded matrix.

    ``"auto"``: up to a half-bandwidth of :data:`NATURAL_HALF_BANDWIDTH`,
    :class:`gyroshell.linalg.factorization.BandLU` (the natural order, diagonal pivots
    while they are stable, two BLAS band substitutions per solve: module notes, a third of
    SuperLU's substitution); above it SuperLU in minimum-degree order. ``"superlu"``:
    SuperLU in the ordering of :func:`column_ordering`. Either way
    the factor's ``ordering`` names the order (:data:`NATURAL` for the band). Any other
    back-end as ``factorize`` makes it (``ordering`` None).

    Parameters
    ----------
    matrix : scipy.sparse matrix, shape (n, n)
        Square, real.
    backend : str
        As for ``factorize``.

    Returns
    -------
    Factorization
        ``solve(rhs)``, ``name``, ``factor_time`` (s) and ``ordering``.
    """
    name = resolve_backend(backend)
    if name != "superlu":
        factor = factorize(matrix, name)
        factor.ordering = None
        return factor
    if matrix.shape[0] != matrix.shape[1]:
        return factorize(matrix, name)  # refused there, in its words
    order = column_ordering(matrix)
    if backend == "auto" and order == NATURAL:
        band = BandLU(matrix)
        band.ordering = NATURAL
        return band
    factor = SuperLUFactor(matrix, ordering=order)
    factor.ordering = order
    return factor
