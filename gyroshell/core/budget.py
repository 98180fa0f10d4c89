"""Size before work: memory estimates checked before anything large is allocated.

Every engine factors a sparse matrix of the grid's unknowns; a transient keeps one float per
step and the full fields it is asked for; a sweep runs one eigen-solve per speed. Each
estimate here takes microseconds and is checked against a limit, so that a request that
cannot fit (``--spacing 1e-9``, ``--steps 1e12``, ``--velocities 0:100:1e-12``) is refused
in one line naming the estimate and the limit, instead of exhausting the machine.

The memory limit is half the physical memory, or the environment variable
``GYROSHELL_MEMORY_LIMIT`` (bytes, e.g. ``4e9``) if set.

Examples
--------
>>> round(model_bytes(779, 41, "free") / 1e6)   # MB, the paper's L_x/L_y = 19 grid
181
>>> check_unknowns(10**7, 10**4, "free")
Traceback (most recent call last):
...
gyroshell.ParameterError: the grid of 10000000 x 10000 intervals ...
"""

from __future__ import annotations

import math
import os

from .errors import ParameterError

#: Environment variable overriding the memory limit, bytes.
MEMORY_LIMIT_VARIABLE = "GYROSHELL_MEMORY_LIMIT"
#: Share of the physical memory a run may plan to use.
MEMORY_FRACTION = 0.5
#: Bytes per stored entry of a sparse factor: a complex value (16) and a 32-bit index (4),
#: rounded up (the eigen-solver factors complex shifted matrices).
BYTES_PER_FACTOR_ENTRY = 24
#: Bytes per unknown outside the factor: K, A, B, G and the shifted matrices (~13 entries
#: per row each, 12 bytes per entry) and the work vectors.
BYTES_PER_UNKNOWN = 1500
#: Factor entries per unknown: the minimum-degree ordering on this 13-point stencil stays
#: below both four times the unknowns per x-line (a band) and 12 log2(n) (nested
#: dissection); measured 40-134 per unknown on grids of 400-33,000 unknowns.
BAND_FILL_FACTOR = 4
DISSECTION_FILL_FACTOR = 12
#: SuperLU indexes its factors with 32-bit integers.
MAX_FACTOR_ENTRIES = 2**31 - 1
#: Bytes a transient holds per step at its peak (measured by
#: ``benchmarks/bench_transient_memory.py``: 32 B per step by tracemalloc, 45 B by ru_maxrss,
#: between 200,000 and 400,000 steps; rounded up): the times t_n (8, and 8 more while they
#: are computed), the history under the load (8) and the result's copy of it (8), the
#: recorder's step flags (1) and the (t, w) table written to the CSV (16).
BYTES_PER_STEP = 56
#: Bytes a transient holds whatever its length: pandas formats a CSV 50,000 rows at a time
#: (about 15 MB of text at the peak, measured), and small work arrays.
TRANSIENT_FIXED_BYTES = 24e6
#: Bytes a moving head adds per step: what the march keeps of it, its centre (16), envelope
#: (8), first cells along x and y (16), bilinear indices and weights (64) and history (8),
#: plus the temporaries of computing them, at their peak (measured: 265 B per step with one
#: head, the step's own bytes included, between 200,000 and 400,000 steps; rounded up).
BYTES_PER_HEAD_STEP = 250
#: Bytes per step of a recorded energy (the array and the result's copy in a table).
BYTES_PER_ENERGY_STEP = 24
#: Longest speed list a sweep accepts (one eigen-solve each).
MAX_SWEEP_SPEEDS = 10_000
#: Most points one parameter study may hold (each is at least one solve).
MAX_STUDY_POINTS = 100_000


def limit_from_environment(variable: str, unit: str) -> float | None:
    """The number > 0 the environment ``variable`` holds (a limit in ``unit``), or None if
    it is unset or empty.

    Raises
    ------
    ParameterError
        If it holds anything but a finite number > 0: ``VARIABLE must be a number of UNIT
        > 0, got '...'``.
    """
    text = os.environ.get(variable)
    if not text:
        return None
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise ParameterError(f"{variable} must be a number of {unit} > 0, got {text!r}")
    return value


def memory_limit() -> float:
    """Bytes a run may plan to use: ``GYROSHELL_MEMORY_LIMIT`` or half the physical memory."""
    value = limit_from_environment(MEMORY_LIMIT_VARIABLE, "bytes")
    if value is not None:
        return value
    try:
        total = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):  # pragma: no cover - not POSIX
        total = 8e9
    return MEMORY_FRACTION * total


def _bytes(value: float) -> str:
    if not math.isfinite(value):
        return "more bytes than a float can count"
    for unit, scale in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if value >= scale:
            return f"{value / scale:.3g} {unit}"
    return f"{value:.0f} B"


def grid_unknowns(nx: int, ny: int, edges: str) -> int:
    """Unknowns of an ``nx`` x ``ny``-interval grid: (nx − 1)(ny ± 1)."""
    return (nx - 1) * (ny + 1 if edges == "free" else ny - 1)


def _unknowns_float(nx: int, ny: int, edges: str) -> float:
    """Unknowns as a float (inf for absurd grids, where the int would not convert)."""
    try:
        return float(nx - 1) * float(ny + 1 if edges == "free" else ny - 1)
    except OverflowError:
        return math.inf


def _count(n: float) -> str:
    return f"{n:.0f}" if n < 1e15 else f"{n:.3g}"


def factor_entries(nx: int, ny: int, edges: str) -> float:
    """Estimated stored entries of a sparse LU factor of a grid operator (an upper bound)."""
    n = _unknowns_float(nx, ny, edges)
    try:
        across = float(ny + 1)
    except OverflowError:
        return math.inf
    per_row = min(BAND_FILL_FACTOR * across, DISSECTION_FILL_FACTOR * math.log2(max(n, 2.0)))
    return n * per_row


def model_bytes(nx: int, ny: int, edges: str) -> float:
    """Estimated memory of the operators and one factorization on the grid, bytes."""
    n = _unknowns_float(nx, ny, edges)
    return BYTES_PER_FACTOR_ENTRY * factor_entries(nx, ny, edges) + BYTES_PER_UNKNOWN * n


def check_unknowns(nx: int, ny: int, edges: str) -> float:
    """Refuse a grid whose operators and factorization cannot fit; returns the estimate.

    Raises
    ------
    ParameterError
        Naming the grid, the estimated memory and the limit.
    """
    estimate = model_bytes(nx, ny, edges)
    limit = memory_limit()
    what = (f"the grid of {_count(float(nx))} x {_count(float(ny))} intervals "
            f"({_count(_unknowns_float(nx, ny, edges))} unknowns)"
            if max(nx, ny) < 1e300 else "the grid")
    if factor_entries(nx, ny, edges) > MAX_FACTOR_ENTRIES:
        raise ParameterError(
            f"{what} needs about {factor_entries(nx, ny, edges):.3g} factor entries, more "
            f"than the sparse solver's limit {MAX_FACTOR_ENTRIES:.3g} (about "
            f"{_bytes(estimate)}); use a larger spacing or a smaller length_ratio")
    if estimate > limit:
        raise ParameterError(
            f"{what} needs about {_bytes(estimate)} for its operators and factorization, "
            f"more than the limit {_bytes(limit)}; use a larger spacing or a smaller "
            f"length_ratio (or set {MEMORY_LIMIT_VARIABLE})")
    return estimate


def transient_bytes(nx: int, ny: int, edges: str, steps: int, *, fields: int = 0,
                    centerlines: int = 0, heads: int = 0, energy: bool = False) -> float:
    """Estimated memory of a transient run, bytes: the model, what the run holds whatever
    its length (:data:`TRANSIENT_FIXED_BYTES`), what every step keeps
    (:data:`BYTES_PER_STEP`, :data:`BYTES_PER_HEAD_STEP` per moving head,
    :data:`BYTES_PER_ENERGY_STEP` with a recorded energy) and the kept full fields and
    centre lines.

    Examples
    --------
    >>> round(transient_bytes(16, 8, "free", 10**6, heads=1) / 1e6)   # MB, one moving head
    330
    """
    nodes = float(nx + 1) * float(ny + 1)
    per_step = (BYTES_PER_STEP + BYTES_PER_HEAD_STEP * heads
                + (BYTES_PER_ENERGY_STEP if energy else 0))
    return (model_bytes(nx, ny, edges) + TRANSIENT_FIXED_BYTES + per_step * (steps + 1.0)
            + 8.0 * nodes * fields + 8.0 * (nx + 1) * centerlines)


def snapshot_count(steps: int, every: int | None) -> int:
    """Full fields kept when one is kept every ``every`` steps (0 if None)."""
    return 0 if every is None else steps // every + 1


def check_transient(nx: int, ny: int, edges: str, steps: int, *, fields: int = 0,
                    centerlines: int = 0, heads: int = 0, energy: bool = False) -> float:
    """Refuse a transient that cannot fit in memory; returns the estimate, bytes
    (:func:`transient_bytes`).

    Raises
    ------
    ParameterError
        Naming the steps, the moving heads, the kept fields, the estimate and the limit.
    """
    check_unknowns(nx, ny, edges)
    estimate = transient_bytes(nx, ny, edges, steps, fields=fields, centerlines=centerlines,
                               heads=heads, energy=energy)
    limit = memory_limit()
    if estimate > limit:
        moving = (f" with {heads} moving head{'s' if heads > 1 else ''}" if heads else "")
        kept = f" and {fields} full fields of {(nx + 1) * (ny + 1)} nodes" if fields else ""
        raise ParameterError(
            f"a transient of {steps} steps{moving}{kept} needs about {_bytes(estimate)}, more "
            f"than the limit {_bytes(limit)}; use fewer steps or keep fewer snapshots "
            f"(or set {MEMORY_LIMIT_VARIABLE})")
    return estimate


def eigen_bytes(nx: int, ny: int, edges: str, ncv: int) -> float:
    """Estimated memory of a quadratic eigen-solve, bytes: the model, its complex shifted
    factorization and ARPACK's ``ncv`` Lanczos/Arnoldi vectors of the 2n first-order system
    (complex, 16 bytes per entry)."""
    n = _unknowns_float(nx, ny, edges)
    return model_bytes(nx, ny, edges) + 16.0 * ncv * 2 * n


def check_eigen(nx: int, ny: int, edges: str, ncv: int) -> float:
    """Refuse an eigen-solve whose Krylov basis of ``ncv`` vectors cannot fit; returns the
    estimate, bytes.

    Raises
    ------
    ParameterError
        Naming the number of vectors, the estimate and the limit.
    """
    check_unknowns(nx, ny, edges)
    estimate = eigen_bytes(nx, ny, edges, ncv)
    limit = memory_limit()
    if estimate > limit:
        raise ParameterError(
            f"an eigen-solve with {ncv} Krylov vectors of "
            f"{_count(2 * _unknowns_float(nx, ny, edges))} "
            f"entries needs about {_bytes(estimate)}, more than the limit {_bytes(limit)}; "
            f"ask for fewer modes (or set {MEMORY_LIMIT_VARIABLE})")
    return estimate


def check_sweep_length(count: float, *, what: str = "velocities") -> int:
    """Refuse a speed sweep with more than :data:`MAX_SWEEP_SPEEDS` speeds; returns count."""
    if not count <= MAX_SWEEP_SPEEDS:
        raise ParameterError(
            f"{what} gives {count:.4g} speeds, more than the limit {MAX_SWEEP_SPEEDS} per "
            "sweep (one eigen-solve each); use a larger step")
    return int(count)


def check_study_points(count: float, *, what: str = "the study") -> int:
    """Refuse a parameter study with more than :data:`MAX_STUDY_POINTS` points; returns
    count."""
    if not count <= MAX_STUDY_POINTS:
        raise ParameterError(
            f"{what} has {count:.4g} points, more than the limit {MAX_STUDY_POINTS} per "
            "study (one or more solves each); use fewer values")
    return int(count)


def check_memory(what: str, estimate: float, advice: str) -> float:
    """Refuse a computation whose estimated memory ``estimate`` (bytes) exceeds
    :func:`memory_limit`; returns the estimate.

    ``what`` names the computation ("a bearing of 400 x 8000 intervals"), ``advice`` says
    what to change ("use a smaller nx").

    Raises
    ------
    ParameterError
        ``"<what> needs about <estimate>, more than the limit <limit>; <advice> (or set
        GYROSHELL_MEMORY_LIMIT)"``.
    """
    limit = memory_limit()
    if not estimate <= limit:
        raise ParameterError(f"{what} needs about {_bytes(estimate)}, more than the limit "
                             f"{_bytes(limit)}; {advice} (or set {MEMORY_LIMIT_VARIABLE})")
    return estimate
