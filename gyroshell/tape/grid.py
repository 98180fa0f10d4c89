"""Uniform finite-difference grid on the tape and the vector ↔ field mapping.

Nodes are (x_i, y_j) = (i h_x, j h_y), i = 0..n_x, j = 0..n_y. The ends x = 0 and x = L_x
are simply supported (w = 0), so their nodes carry no unknown; with simply supported lateral
edges the nodes at y = 0 and y = L_y carry none either. Unknowns are numbered with j fastest,
which keeps every operator banded with a half-bandwidth of about 2 (n_y + 1).

Callers never touch that numbering: use :meth:`Grid.to_field` and :meth:`Grid.from_field`.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..core import budget, validation
from ..core.errors import ParameterError
from .parameters import EDGE_CHOICES, MIN_INTERVALS_ACROSS, MIN_INTERVALS_ALONG, TapeParameters

#: Relative difference of a grid's length or width from its tape's accepted as equal (the
#: round-off of length_ratio x width and of a file's decimal text).
MATCH_RTOL = 1e-12


@dataclass(frozen=True)
class Grid:
    """A uniform grid of ``nx`` × ``ny`` intervals on [0, length] × [0, width].

    Parameters
    ----------
    length, width : float
        L_x and L_y, m.
    nx, ny : int
        Number of intervals along x and across y (each >= 8).
    edges : {"free", "simply-supported"}
        Condition on the lateral edges y = 0, L_y.

    Raises
    ------
    ParameterError
        For a non-positive or non-finite length, a fractional or too small interval count,
        or a grid whose operators and factorization cannot fit in memory
        (:func:`gyroshell.core.budget.check_unknowns`).

    Examples
    --------
    >>> g = Grid(0.0254, 6.35e-3, 16, 8)
    >>> g.unknowns, g.shape
    (135, (17, 9))
    """

    length: float
    width: float
    nx: int
    ny: int
    edges: str = "free"

    def __post_init__(self) -> None:
        put = object.__setattr__
        put(self, "length", validation.positive("length", self.length, "m"))
        put(self, "width", validation.positive("width", self.width, "m"))
        put(self, "nx", validation.integer("nx", self.nx, low=MIN_INTERVALS_ALONG))
        put(self, "ny", validation.integer("ny", self.ny, low=MIN_INTERVALS_ACROSS))
        validation.choice("edges", self.edges, EDGE_CHOICES)
        budget.check_unknowns(self.nx, self.ny, self.edges)

    @classmethod
    def from_parameters(cls, params: TapeParameters) -> Grid:
        """The grid nearest to ``params.spacing``: whole numbers of intervals per side."""
        nx = round(params.length / params.spacing)
        ny = round(params.width / params.spacing)
        return cls(params.length, params.width, nx, ny, params.edges)

    def check_matches(self, params) -> Grid:
        """This grid, if it spans the tape of ``params`` (a :class:`TapeParameters`): the
        same length and width, m (to :data:`MATCH_RTOL`), and the same lateral edges; else a
        ParameterError naming what differs. A grid may refine the tape's spacing, not
        change its size or its edges."""
        for name, mine, theirs in (("length", self.length, params.length),
                                   ("width", self.width, params.width)):
            if abs(mine - theirs) > MATCH_RTOL * abs(theirs):
                raise ParameterError(f"grid {name} {mine:.9g} m differs from the tape's "
                                     f"{name} {theirs:.9g} m: a grid must span the tape")
        if self.edges != params.edges:
            raise ParameterError(f"grid edges {self.edges!r} differ from the tape's edges "
                                 f"{params.edges!r}")
        return self

    def refined(self, factor: int = 2) -> Grid:
        """The same tape with ``factor`` times as many intervals each way."""
        factor = validation.integer("factor", factor, low=1)
        return Grid(self.length, self.width, self.nx * factor, self.ny * factor, self.edges)

    # ----- geometry -------------------------------------------------------------------
    @property
    def hx(self) -> float:
        """Spacing along x actually used, m."""
        return self.length / self.nx

    @property
    def hy(self) -> float:
        """Spacing across y actually used, m."""
        return self.width / self.ny

    @cached_property
    def x(self) -> np.ndarray:
        """Node abscissae x_i, m, shape (nx + 1,)."""
        return np.linspace(0.0, self.length, self.nx + 1)

    @cached_property
    def y(self) -> np.ndarray:
        """Node ordinates y_j, m, shape (ny + 1,)."""
        return np.linspace(0.0, self.width, self.ny + 1)

    @property
    def shape(self) -> tuple[int, int]:
        """Shape of a nodal field, (nx + 1, ny + 1); axis 0 is x."""
        return (self.nx + 1, self.ny + 1)

    @cached_property
    def X(self) -> np.ndarray:
        """x of every node, shape :attr:`shape`."""
        return np.broadcast_to(self.x[:, None], self.shape)

    @cached_property
    def Y(self) -> np.ndarray:
        """y of every node, shape :attr:`shape`."""
        return np.broadcast_to(self.y[None, :], self.shape)

    # ----- unknowns ---------------------------------------------------------------------
    @property
    def free_edges(self) -> bool:
        return self.edges == "free"

    @property
    def x_unknowns(self) -> slice:
        """Node indices i that carry unknowns (the interior, 1..nx−1)."""
        return slice(1, self.nx)

    @property
    def y_unknowns(self) -> slice:
        """Node indices j that carry unknowns (0..ny with free edges, else 1..ny−1)."""
        return slice(0, self.ny + 1) if self.free_edges else slice(1, self.ny)

    @property
    def n_lines(self) -> int:
        """Number of unknown x-lines, nx − 1."""
        return self.nx - 1

    @property
    def n_across(self) -> int:
        """Unknowns per x-line: ny + 1 (free) or ny − 1 (simply supported)."""
        return self.ny + 1 if self.free_edges else self.ny - 1

    @property
    def unknowns(self) -> int:
        """Number of unknowns n (nodes that are not on a supported line)."""
        return self.n_lines * self.n_across

    @property
    def size(self) -> int:
        """Deprecated name of :attr:`unknowns` (it counts unknowns, not nodes)."""
        warnings.warn("Grid.size is deprecated; use unknowns", DeprecationWarning,
                      stacklevel=2)
        return self.unknowns

    @cached_property
    def y_weights(self) -> np.ndarray:
        """Trapezoid weights (m) across the width for the unknown nodes of one x-line."""
        w = np.full(self.n_across, self.hy)
        if self.free_edges:
            w[0] = w[-1] = 0.5 * self.hy
        return w

    @cached_property
    def areas(self) -> np.ndarray:
        """Control area of every unknown node, m² (trapezoid rule), shape (n,)."""
        return np.tile(self.hx * self.y_weights, self.n_lines)

    def to_field(self, vector: np.ndarray) -> np.ndarray:
        """Nodal field (shape :attr:`shape`, zeros on supported lines) from an unknown vector.

        ``vector`` may carry trailing axes (e.g. several modes): shape (n, ...) gives
        (nx + 1, ny + 1, ...). Complex vectors give complex fields.
        """
        vector = np.asarray(vector)
        if vector.shape[0] != self.unknowns:
            raise ParameterError(f"vector must have length {self.unknowns}, got {vector.shape[0]}")
        field = np.zeros(self.shape + vector.shape[1:], dtype=vector.dtype)
        field[self.x_unknowns, self.y_unknowns] = vector.reshape(
            (self.n_lines, self.n_across) + vector.shape[1:]
        )
        return field

    def from_field(self, field: np.ndarray) -> np.ndarray:
        """Unknown vector from a nodal field (values on supported lines are ignored)."""
        field = np.asarray(field)
        if field.shape[:2] != self.shape:
            raise ParameterError(f"field must have shape {self.shape}, got {field.shape[:2]}")
        sub = field[self.x_unknowns, self.y_unknowns]
        return sub.reshape((self.unknowns,) + field.shape[2:]).copy()

    def sample(self, function) -> np.ndarray:
        """Unknown vector of ``function(X, Y)`` evaluated at the unknown nodes."""
        return self.from_field(np.asarray(function(self.X, self.Y), dtype=float)
                               * np.ones(self.shape))

    def interpolation_row(self, x0: float, y0: float) -> np.ndarray:
        """Weights r with r @ w = w(x0, y0), bilinear in the cell holding (x0, y0).

        Second-order accurate, like the scheme; a point on a node gets that node's value.
        """
        x0, y0 = validation.real("x0", x0, unit="m"), validation.real("y0", y0, unit="m")
        if not (0.0 <= x0 <= self.length and 0.0 <= y0 <= self.width):
            raise ParameterError(
                f"point ({x0:g}, {y0:g}) m must lie on the tape "
                f"[0, {self.length:g}] x [0, {self.width:g}] m"
            )
        field = np.zeros(self.shape)
        sx, sy = x0 / self.hx, y0 / self.hy
        i, j = min(int(sx), self.nx - 1), min(int(sy), self.ny - 1)
        fx, fy = sx - i, sy - j
        field[i, j] = (1 - fx) * (1 - fy)
        field[i + 1, j] = fx * (1 - fy)
        field[i, j + 1] = (1 - fx) * fy
        field[i + 1, j + 1] = fx * fy
        return self.from_field(field)

    def centerline_weights(self) -> tuple[int, float]:
        """(j, f): the centre line y = L_y/2 is (1 − f) column j + f column j + 1 of a field."""
        s = 0.5 * self.width / self.hy
        j = min(int(s), self.ny - 1)
        return j, s - j

    def centerline(self, field: np.ndarray) -> np.ndarray:
        """w(x, L_y/2) of a nodal field (shape :attr:`shape`), m: linear across y if the
        centre line falls between nodes; shape (nx + 1,).

        Examples
        --------
        >>> g = Grid(0.0254, 6.35e-3, 16, 9)
        >>> g.centerline(g.Y * np.ones(g.shape))[:2] * 1e3   # y = L_y/2 = 3.175 mm
        array([3.175, 3.175])
        """
        field = np.asarray(field)
        if field.shape[:2] != self.shape:
            raise ParameterError(f"field must have shape {self.shape}, got {field.shape[:2]}")
        j, f = self.centerline_weights()
        return (1.0 - f) * field[:, j] + f * field[:, j + 1]
