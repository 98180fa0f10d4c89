"""Size before work for the air bearing: the memory of a steady solve and of a march,
estimated from the grid's counts alone (microseconds, nothing allocated) and checked
against the project's limit (:func:`gyroshell.core.budget.memory_limit`).

A steady solve holds the tape's operators, the film's pattern, the coupled Jacobian
(about 16 entries per row) and sparse LU factorizations of the Jacobian; the 2-D tape is
factored on half its width (:attr:`BearingModel.mirror`).

The 2-D estimate under the default ordering ("grid": a nested dissection along the grid's
node lines, :mod:`gyroshell.linalg.grid_ordering`; "metis" gives similar fill) is
calibrated against measured peaks. The factor's entries per row grow as log₂ m, m the
fewer nodes of the half grid's two sides (the dissection cuts the longer side until its
boxes are square, and a square's nested dissection fills O(n log n)): measured on 13 grids
of 96 × 8 to 388 × 512 intervals (855 to 198,531 half-width unknowns, m = 5 to 257), the
fill :data:`ND_FILL_SLOPE` log₂ m + :data:`ND_FILL_CONSTANT` is 1.00-1.23 times SuperLU's
nnz(L) + nnz(U). The peak resident size of the solve (its rise over the loaded
interpreter's) is then covered by :data:`ND_BYTES_PER_ENTRY` per estimated entry plus
:data:`ND_BYTES_PER_UNKNOWN` per unknown, at 1.00-1.69 times the measured peaks (the
tightest such cover); the estimate is that times :data:`SAFETY`. The 12.65 mm Table 1 tape's
default grid (388 × 200) measured 0.73 GB, a 50 mm tape's (388 × 512) 2.09 GB.

The other orderings ("mmd", "colamd", "pardiso") and the infinitely wide tape keep the
earlier, coarser bounds: COLAMD's fill on these Jacobians, measured on graded grids of
48 × 16 to 200 × 600 intervals (800 to 120,000 half-width unknowns), stays below both 8.5
entries per row per node across the half width (a band) and 2.6 √n per row (n the
half-width unknowns), at :data:`BYTES_PER_FILL` per entry for two factors and their
copies; the infinitely wide tape's factor has 10.8 entries per row.
``benchmarks/bench_bearing_memory.py`` prints the estimates against measured peaks.

Examples
--------
>>> steady_bytes(798, None) < 1e8            # the infinitely wide default grid
True
>>> check_steady(50000, 100000)
Traceback (most recent call last):
...
gyroshell.ParameterError: a bearing grid of 50000 x 100000 intervals (1e+10 unknowns) ...
"""

from __future__ import annotations

import math

from ..core.budget import MAX_FACTOR_ENTRIES, check_memory, memory_limit
from ..core.errors import ParameterError

#: Factor entries per row per node across the half width (2-D, a band bound) ...
BAND_FILL = 8.5
#: ... and per row over √n (2-D, n the half-width unknowns), whichever is smaller.
SQRT_FILL = 2.6
#: Factor entries per row of the infinitely wide tape's Jacobian (measured 10.8).
STRIP_FILL = 12.0
#: Bytes per factor entry at the solve's peak: two factors (the kept one and the new one),
#: each a value and an index inside SuperLU (12 bytes, plus its supernodal padding) and a
#: copy of L and U as CSC matrices (12 bytes): 2 x (16 + 12), rounded up.
BYTES_PER_FILL = 64.0
#: Bytes per unknown outside the factors: the operators (A, B, M, G, W and the pressure
#: load), the film's pattern, the Jacobian and its half-width copy in CSR/CSC and COO while
#: assembled (~16 entries per row, up to 24 bytes each, several copies), the residual
#: scaling and the Newton vectors; and the allocator's fragmentation over many
#: factorizations (a 1-D solve of 16,000 unknowns that took 822 Newton iterations peaked at
#: 8.6 kB per unknown, one of 6,400 in 6 iterations at 1.9 kB).
BYTES_PER_UNKNOWN = 9000.0
#: Factor entries per row of the half-width 2-D Jacobian under the grid's nested
#: dissection: ND_FILL_SLOPE log₂ m + ND_FILL_CONSTANT, m the fewer nodes of the half
#: grid's two sides (measured: module notes; the constant makes it cover every grid
#: measured, the slope is the least-squares one).
ND_FILL_SLOPE = 42.6
ND_FILL_CONSTANT = -39.5
#: Peak bytes per estimated factor entry and per unknown of a 2-D solve under the nested
#: dissection: the tightest cover of the measured peaks (module notes).
ND_BYTES_PER_ENTRY = 29.0
ND_BYTES_PER_UNKNOWN = 4200.0
#: The 2-D estimate's margin over that cover: Newton paths longer than the measured ones
#: (pseudo-time, continuation in V, contact passes) factor more often and fragment the
#: allocator (a 1-D solve of 822 iterations peaked at 4.5 times the memory per unknown of
#: one of 6), and grids between the measured ones.
SAFETY = 1.5
#: The orderings whose fill the nested-dissection estimate describes.
DISSECTION_ORDERINGS = ("auto", "grid", "metis")
#: Bytes the march keeps per recorded step, besides its centre line: six numbers (t, h_c,
#: h_min, contact force, T, iterations) as Python objects in lists (~40 bytes each), then
#: as arrays (8 bytes each), and the centre line's array header; doubled for margin.
BYTES_PER_RECORD = 600.0


def unknowns(nx: int, ny: int | None) -> float:
    """Unknowns [u, p] of the grid, as a float (no overflow): (nx − 1) nodes along, times
    ny + 1 tape nodes and ny − 1 film nodes across (1 and 1 if infinitely wide)."""
    along = float(nx) - 1.0
    if ny is None:
        return 2.0 * along
    return along * (2.0 * float(ny))


def _dissected(ny: int | None, factorization: str) -> bool:
    """Whether the 2-D estimate of the nested dissection applies."""
    return ny is not None and factorization in DISSECTION_ORDERINGS


def factor_entries(nx: int, ny: int | None, factorization: str = "auto") -> float:
    """Estimated entries of one LU factor (L and U) of the (half-width) Jacobian under
    ``factorization`` (:data:`gyroshell.linalg.factorization.PATTERN_LU`)."""
    if ny is None:
        return STRIP_FILL * unknowns(nx, ny)
    half = 0.5 * unknowns(nx, ny) + float(nx)
    across = 0.5 * float(ny) + 1.0
    if _dissected(ny, factorization):
        sides = max(min(float(nx) - 1.0, across), 2.0)
        return half * (ND_FILL_SLOPE * math.log2(sides) + ND_FILL_CONSTANT)
    return half * min(BAND_FILL * across, SQRT_FILL * math.sqrt(half))


def steady_bytes(nx: int, ny: int | None, factorization: str = "auto") -> float:
    """Estimated peak memory of a steady solve on ``nx`` × ``ny`` intervals (``ny`` None:
    infinitely wide) with ``factorization``, bytes (module notes)."""
    entries = factor_entries(nx, ny, factorization)
    if _dissected(ny, factorization):
        return SAFETY * (ND_BYTES_PER_ENTRY * entries
                         + ND_BYTES_PER_UNKNOWN * unknowns(nx, ny))
    return BYTES_PER_FILL * entries + BYTES_PER_UNKNOWN * unknowns(nx, ny)


def _grid(nx: int, ny: int | None) -> str:
    n = unknowns(nx, ny)
    count = f"{n:.0f}" if n < 1e9 else f"{n:.3g}"
    across = "" if ny is None else f" x {ny}"
    return f"a bearing grid of {nx}{across} intervals ({count} unknowns)"


def check_steady(nx: int, ny: int | None, factorization: str = "auto") -> float:
    """Refuse a grid whose steady solve with ``factorization`` cannot fit in memory;
    returns the estimate, bytes.

    Raises
    ------
    ParameterError
        Naming the grid, the estimate and the limit (or the sparse solver's index limit).
    """
    what = _grid(nx, ny)
    entries = factor_entries(nx, ny, factorization)
    if entries > MAX_FACTOR_ENTRIES:
        raise ParameterError(
            f"{what} needs about {entries:.3g} factor entries, more than the sparse "
            f"solver's limit {MAX_FACTOR_ENTRIES:.3g}; use a smaller nx or ny (or a "
            "narrower tape)")
    return check_memory(what, steady_bytes(nx, ny, factorization),
                        "use a smaller nx or ny (or a narrower tape)")


def records(steps: int, record_every: int) -> int:
    """Recorded states of a march of ``steps`` steps: the start, every ``record_every``-th
    step and the last."""
    return steps // record_every + 2


def march_bytes(nx: int, ny: int | None, steps: int, record_every: int,
                factorization: str = "auto") -> float:
    """Estimated peak memory of a march, bytes: one steady solve's (one Newton solve per
    step) and the record, whose centre lines (nx + 1 spacings) exist twice at the end (the
    lists and the arrays made from them)."""
    per_record = BYTES_PER_RECORD + 2.0 * 8.0 * (float(nx) + 1.0)
    return steady_bytes(nx, ny, factorization) + per_record * records(steps, record_every)


def check_march(nx: int, ny: int | None, steps: int, record_every: int,
                factorization: str = "auto") -> float:
    """Refuse a march whose record cannot fit in memory; returns the estimate, bytes.

    Raises
    ------
    ParameterError
        Naming the steps, the records, the estimate, the limit and the ``record_every``
        that would fit.
    """
    check_steady(nx, ny, factorization)
    estimate = march_bytes(nx, ny, steps, record_every, factorization)
    spare = memory_limit() - steady_bytes(nx, ny, factorization)
    per_record = BYTES_PER_RECORD + 16.0 * (nx + 1.0)
    fits = (math.ceil(steps / max(spare / per_record - 2.0, 1.0)) if spare > per_record
            else None)
    advice = ("record fewer steps: record_every >= " f"{max(fits, record_every + 1)}"
              if fits is not None else "use fewer steps")
    return check_memory(f"a bearing march of {steps} steps keeping "
                        f"{records(steps, record_every)} centre lines of {nx + 1} nodes",
                        estimate, advice)
