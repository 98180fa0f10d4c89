"""Nested dissection of a matrix whose unknowns sit on a structured 2-D grid.

A matrix from finite differences on an n₁ × n₂ grid couples each unknown only to unknowns
within a few node lines of it. Its nested-dissection ordering then needs no graph
partitioner: the separators are straight node lines. The box of the grid is cut across
its longer side into two halves and a separator between them; the halves are ordered
first (recursively), the separator last, down to boxes of at most LEAF_NODES nodes, which
keep their natural order. Computed in numpy from the unknowns' grid indices in
milliseconds (METIS takes about a second on the bearing's 78,000-unknown Jacobian, for
similar fill and factorization time: docs/performance.md).

The separator's width is read from the matrix itself, per kind of unknown (e.g. the
bearing's tape deflection u, coupled by the plate's 13-point stencil to u two lines away,
and its film pressure p, coupled to its neighbours one line away): a cut at line m holds
the unknowns of kind s on lines m … m + w_s − 1, where w_s is the largest distance along
that axis between an unknown of kind s and any unknown it is coupled to. Unknowns before
line m and after the separator are then never coupled (the distance across is at least
w_s + 1 > every reach), so the two halves are independent and the separator is the
thinnest one of straight lines (for the bearing 3 unknowns per node across: two lines of
u, one of p, instead of the 4 of two whole node lines).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..core.errors import ParameterError

#: Boxes of at most this many nodes (along × across) keep their natural order (measured
#: on the bearing's Jacobian: 16 gives the least fill and factorization time; 9 and 36
#: within a few per cent).
LEAF_NODES = 16

#: At most this many places (kinds × the nodes of the grid's box) per unknown: the
#: bearing's unknowns fill their box (1.0 and 1.06 places per unknown on its default 2-D
#: and a 64 × 16 grid); sparser ones are refused, to bound the memory of the dissection.
PLACES_PER_UNKNOWN = 4


def separator_widths(graph: sp.spmatrix, coordinates: np.ndarray,
                     kinds: np.ndarray) -> np.ndarray:
    """The separator's width along each axis for each kind of unknown.

    Parameters
    ----------
    graph : scipy.sparse matrix, shape (n, n)
        The matrix (its pattern: where A or Aᵀ has an entry, the unknowns are coupled).
    coordinates : numpy.ndarray of int, shape (n, 2)
        Each unknown's node indices along the two axes.
    kinds : numpy.ndarray of int, shape (n,)
        Each unknown's kind, 0 … k − 1.

    Returns
    -------
    numpy.ndarray of int, shape (2, k)
        w[a, s]: the largest distance along axis a from an unknown of kind s to an unknown
        it is coupled to (at least 1).
    """
    A = sp.coo_matrix(graph)
    n_kinds = int(kinds.max()) + 1 if len(kinds) else 1
    widths = np.ones((2, n_kinds), dtype=np.int64)
    for axis in (0, 1):
        distance = np.abs(coordinates[A.row, axis] - coordinates[A.col, axis])
        span = int(distance.max(initial=0)) + 1
        for side in (A.row, A.col):          # coupled either way (the pattern of A + Aᵀ)
            # how many couplings of each (kind, distance): the largest distance present
            counts = np.bincount(kinds[side] * span + distance, minlength=n_kinds * span)
            present = counts.reshape(n_kinds, span) > 0
            farthest = span - 1 - np.argmax(present[:, ::-1], axis=1)
            widths[axis] = np.maximum(widths[axis], np.where(present.any(axis=1), farthest, 0))
    return np.maximum(widths, 1)


def grid_nested_dissection(graph: sp.spmatrix, coordinates: np.ndarray,
                           kinds: np.ndarray | None = None) -> np.ndarray:
    """Nested-dissection ordering of a matrix whose unknowns sit on a 2-D grid.

    Parameters
    ----------
    graph : scipy.sparse matrix, shape (n, n)
        The matrix or its pattern (for the separators' widths, :func:`separator_widths`).
    coordinates : numpy.ndarray of int, shape (n, 2)
        Each unknown's node indices (i along, j across; any origin). Several unknowns may
        share a node (of different kinds).
    kinds : numpy.ndarray of int, shape (n,), optional
        Each unknown's kind, 0 … k − 1 (default: all one kind).

    Returns
    -------
    numpy.ndarray of int, shape (n,)
        A permutation: row and column k of the reordered matrix A[perm][:, perm] are row
        and column perm[k] of A (the convention of
        :func:`gyroshell.linalg.factorization.nested_dissection`).

    Raises
    ------
    ParameterError
        If the coordinates or kinds do not match the matrix, the coordinates are not
        integers, a kind is negative, or the unknowns do not fill their grid: the box of
        n₁ × n₂ nodes they span, times the k kinds, holds more than PLACES_PER_UNKNOWN
        · n places (scattered unknowns: order them with
        :func:`gyroshell.linalg.factorization.nested_dissection` instead).

    Notes
    -----
    Memory is bounded by O(nnz + k·n₁·n₂) = O(nnz + n) (the refusal above): the block
    number of each of the box's k·n₁·n₂ places, the separators' widths from the nnz
    couplings, and a stack of at most 2(n₁ + n₂) + 1 boxes — every cut takes at least a
    node line off each half, whatever the widths, so the dissection is at most n₁ + n₂
    cuts deep. Long-range couplings are allowed (the ordering is still a valid
    permutation): they widen the separators to their reach, and an axis too short for a
    separator of that width with a node line on either side is not cut, so the ordering
    falls back towards the natural one along it, with more fill.
    """
    n = graph.shape[0]
    ij, kinds = _grid_indices(n, coordinates, kinds)
    if n < 2:
        return np.arange(n)
    widths = separator_widths(graph, ij, kinds)
    shape = tuple(int(s) + 1 for s in ij.max(axis=0))
    block = _blocks(shape, widths)
    # within a block: node by node (i, then j), the kinds of one node together
    return np.lexsort((kinds, ij[:, 1], ij[:, 0], block[kinds, ij[:, 0], ij[:, 1]]))


def _grid_indices(n: int, coordinates, kinds) -> tuple[np.ndarray, np.ndarray]:
    """(node indices from 0, kinds) of :func:`grid_nested_dissection`'s n unknowns,
    checked (its Raises)."""
    coordinates = np.asarray(coordinates)
    kinds = np.zeros(n, dtype=np.int64) if kinds is None else np.asarray(kinds, dtype=np.int64)
    if coordinates.shape != (n, 2) or kinds.shape != (n,):
        raise ParameterError(f"grid_nested_dissection: coordinates must have shape ({n}, 2) "
                             f"and kinds ({n},), got {coordinates.shape} and {kinds.shape}")
    if n < 2:
        return coordinates, kinds
    if not np.issubdtype(coordinates.dtype, np.integer):
        raise ParameterError("grid_nested_dissection: coordinates must be integer node "
                             f"indices, got dtype {coordinates.dtype}")
    if kinds.min() < 0:
        raise ParameterError(f"grid_nested_dissection: kinds must be >= 0, got {kinds.min()}")
    ij = coordinates - coordinates.min(axis=0)
    places = (int(kinds.max()) + 1) * int(np.prod(ij.max(axis=0) + 1, dtype=object))
    if places > PLACES_PER_UNKNOWN * n:
        raise ParameterError(
            f"grid_nested_dissection: the unknowns must fill their grid (kinds × the nodes "
            f"of the box they span <= {PLACES_PER_UNKNOWN} × {n} unknowns), got "
            f"{places}")
    return ij, kinds


def _blocks(shape: tuple, widths: np.ndarray) -> np.ndarray:
    """The elimination block of every node of every kind (shape (kinds, *shape)): the
    leaves and separators of the dissection numbered in post-order (first half, second
    half, separator), so that sorting by block gives the elimination order."""
    n_kinds = widths.shape[1]
    block = np.zeros((n_kinds, *shape), dtype=np.int64)
    count = 0
    w = widths.tolist()
    w_max = [max(w[0]), max(w[1])]
    # A box: per kind, its node ranges [lo, hi) along each axis. Visited in post-order
    # (first half, second half, separator) by an explicit stack.
    stack = [([[(0, shape[0]), (0, shape[1])]] * n_kinds, False)]
    while stack:
        box, done = stack.pop()
        extent = [max(max(hi - lo for lo, hi in (ranges[a] for ranges in box)), 0)
                  for a in (0, 1)]
        axis = None if done else _cut_axis(extent, w_max)
        if axis is None:
            for s, ((a0, a1), (b0, b1)) in enumerate(box):
                if a1 > a0 and b1 > b0:
                    block[s, a0:a1, b0:b1] = count
            count += 1
            continue
        # the box's node lines along the axis, over the kinds present in it
        present = [ranges[axis] for ranges in box if ranges[axis][1] > ranges[axis][0]]
        lo = min(a0 for a0, _ in present)
        hi = max(a1 for _, a1 in present)
        cut = lo + (hi - lo - w_max[axis]) // 2
        first, second, separator = [], [], []
        for s, ranges in enumerate(box):
            a0, a1 = ranges[axis]
            parts = ((a0, min(a1, cut)), (max(a0, cut + w[axis][s]), a1),
                     (max(a0, cut), min(a1, cut + w[axis][s])))
            for part, new in zip(parts, (first, second, separator), strict=True):
                new.append([part, ranges[1]] if axis == 0 else [ranges[0], part])
        stack += [(separator, True), (second, False), (first, False)]
    return block


def _cut_axis(extent: list, widths: list) -> int | None:
    """The axis a box of these extents (nodes along each axis) is cut across: the longer
    of those that hold a separator (of these widths) with a node line on either side;
    None (the box keeps its natural order) if it has at most LEAF_NODES nodes or neither
    axis holds one. A cut then leaves at least one line of the box in each half, so the
    halves are smaller than the box and the dissection ends."""
    if extent[0] * extent[1] <= LEAF_NODES:
        return None
    cuttable = [a for a in (0, 1) if extent[a] - widths[a] >= 2]
    return max(cuttable, key=lambda a: (extent[a], -a)) if cuttable else None
