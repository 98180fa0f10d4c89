"""Tensor-product node coordinates of the bearing's grid: uniform, or graded by a smooth
coordinate mapping towards the free edges (y) and the wrap's corners (x).

A graded line of n intervals on [0, L] puts its nodes at equal steps of

    S(t) = t + (r − 1) Σ_k δ [gd((t − c_k)/δ) − gd(−c_k/δ)],    gd(z) = 2 arctan(tanh(z/2)),

the integral of the node density g(t) = 1 + (r − 1) Σ_k sech((t − c_k)/δ): the spacing is
about r times finer at each refinement centre c_k than far from it, over a zone a few δ
wide. The mapping s ↦ t = S⁻¹(s) is analytic, so the spacing varies smoothly
(h_{i+1} − h_i = O(h²)) and the schemes written for non-uniform spacing keep their
second order; refining n with the mapping fixed nests the grids (every second node of
the 2n grid is a node of the n grid).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core import validation
from ..core.errors import ParameterError


def _sech(z):
    """sech z = 2 e^(−|z|) / (1 + e^(−2|z|)): no overflow far from the centres (cosh does)."""
    e = np.exp(-np.abs(np.asarray(z, dtype=float)))
    return 2.0 * e / (1.0 + e * e)


def _gd(z):
    """Gudermannian function, the integral of sech."""
    return 2.0 * np.arctan(np.tanh(0.5 * np.asarray(z, dtype=float)))


@dataclass(frozen=True)
class LineGrading:
    """Refinement of one line towards ``centres`` (m): ``ratio`` (>= 1) times finer there
    than far away, over zones of width ``width`` (m); and, if ``corner_ratio`` > 1, an
    algebraic refinement towards the same centres, ``corner_ratio`` times finer still at
    them, whose spacing grows in proportion to the distance s from the centre beyond
    ``corner_width`` (m): the density term (corner_ratio − 1)/√(1 + (s/corner_width)²),
    analytic, integrating to an asinh (a geometric grid about each centre, so resolving a
    length scale far below the zone's width costs only a logarithm of their ratio).
    ``corner_widths``: each centre's own corner width (m; None: ``corner_width`` at every
    centre; an entry None: no algebraic term there), its ratio such that the spacing grows
    at the same rate beyond it, 1 + (corner_ratio − 1) corner_width / width."""

    ratio: float
    width: float
    centres: tuple[float, ...]
    corner_ratio: float = 1.0
    corner_width: float = 0.0
    corner_widths: tuple[float | None, ...] | None = None

    def _corner_terms(self) -> list[tuple[float, float, float]]:
        """(centre, ratio, width) of each algebraic corner term."""
        if self.corner_ratio == 1.0:
            return []
        if self.corner_widths is None:
            return [(c, self.corner_ratio, self.corner_width) for c in self.centres]
        return [(c, 1.0 + (self.corner_ratio - 1.0) * self.corner_width / w, w)
                for c, w in zip(self.centres, self.corner_widths, strict=True)
                if w is not None]

    @property
    def graded(self) -> bool:
        """Whether the line is graded at all (else its nodes are uniform)."""
        return self.ratio != 1.0 or self.corner_ratio != 1.0

    def density(self, t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        g = np.ones_like(t)
        for c in self.centres:
            if self.ratio != 1.0:
                g = g + (self.ratio - 1.0) * _sech((t - c) / self.width)
        for c, ratio, w in self._corner_terms():
            g = g + (ratio - 1.0) / np.hypot(1.0, (t - c) / w)
        return g

    def cumulative(self, t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        s = t.copy()
        for c in self.centres:
            if self.ratio != 1.0:
                s = s + (self.ratio - 1.0) * self.width * (_gd((t - c) / self.width)
                                                           - _gd(-c / self.width))
        for c, ratio, w in self._corner_terms():
            s = s + (ratio - 1.0) * w * (np.arcsinh((t - c) / w) - np.arcsinh(-c / w))
        return s


def _graded(grading: LineGrading | None) -> bool:
    return grading is not None and grading.graded


def line_nodes(length: float, n: int, grading: LineGrading | None = None) -> np.ndarray:
    """n + 1 node coordinates on [0, length] (m): uniform, or equally spaced in the
    graded coordinate S (see the module notes); exact to round-off, ends exact."""
    if not _graded(grading):
        return np.linspace(0.0, length, n + 1)
    total = float(grading.cumulative(length))
    t = _solve_mapping(grading, np.linspace(0.0, total, n + 1), 0.0, length, table=n)
    t[0], t[-1] = 0.0, length
    return t


def symmetric_line_nodes(length: float, n: int, grading: LineGrading | None = None
                         ) -> np.ndarray:
    """As :func:`line_nodes` for a grading symmetric about length/2, made exactly mirror
    symmetric (t_j + t_{n−j} = length; the middle node at length/2 for even n)."""
    t = line_nodes(length, n, grading)
    t = 0.5 * (t + (length - t[::-1]))
    if n % 2 == 0:
        t[n // 2] = 0.5 * length
    return t


def _inverse(grading: LineGrading | None, s: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """t in [lo, hi] with S(t) = s (S the grading's cumulative; the identity if None)."""
    if not _graded(grading):
        return s.copy()
    return _solve_mapping(grading, s, lo, hi)


#: Newton iterations of :func:`_solve_mapping` (each halving its bracket at least).
_MAPPING_ITERATIONS = 60


def _solve_mapping(grading: LineGrading, s: np.ndarray, lo: float, hi: float, *,
                   table: int | None = None) -> np.ndarray:
    """t in [lo, hi] with S(t) = s (increasing), S the grading's (increasing) cumulative:
    Newton (S' = g >= 1) from a table of S. Where its few steps leave the nodes out of
    order (a corner term refining a 0.1 m span to a few tens of nm curves S far below the
    table's spacing, and bare steps overshoot), the roots are found again by Newton kept
    within the table's bracket about each root, bisecting where a step would leave it.
    (Grids that the few steps order keep their nodes to the bit: stored results
    compare their nodes with the rebuilt grid's.) ``table``: the table has 64 times
    this many intervals (default: as many as ``s`` has points)."""
    s = np.asarray(s, dtype=float)
    n = max(len(s), 2) if table is None else table
    dense = np.linspace(lo, hi, 64 * n + 1)
    table = grading.cumulative(dense)
    t = np.interp(s, table, dense)                              # start within round-off²
    for _ in range(4):                                          # Newton: S' = g >= 1
        t = t - (grading.cumulative(t) - s) / grading.density(t)
    t = np.clip(t, lo, hi)
    if np.all(np.diff(t) > 0.0):
        return t
    k = np.clip(np.searchsorted(table, s, side="right") - 1, 0, len(dense) - 2)
    a, b = dense[k].copy(), dense[k + 1].copy()
    t = np.interp(s, table, dense)
    for _ in range(_MAPPING_ITERATIONS):
        f = grading.cumulative(t) - s
        a = np.where(f < 0.0, t, a)
        b = np.where(f > 0.0, t, b)
        step = t - f / grading.density(t)
        t = np.where((step > a) & (step < b), step, 0.5 * (a + b))
        if np.all(b - a <= 4.0 * np.finfo(float).eps * np.maximum(np.abs(t), 1e-300)):
            break
    return np.clip(t, lo, hi)


def piecewise_line_nodes(length: float, n: int, grading: LineGrading | None,
                         breaks: tuple[float, ...], *, fewest: int = 2) -> np.ndarray:
    """n + 1 node coordinates on [0, length] (m) with a node exactly on every break (m,
    inside the line): the nodes of :func:`line_nodes`, moved so that the k-th break is the
    node nearest to it in the graded coordinate S. Between breaks the nodes are at equal
    steps of S, so the spacing stays smooth: at a break it changes by a factor
    1 + O(1/n), i.e. h_{i+1} − h_i = O(h²) as before. Mirror-symmetric breaks and grading
    give exactly mirror-symmetric nodes.

    Raises
    ------
    ValueError
        If ``n`` leaves fewer than ``fewest`` intervals between two breaks.
    """
    knots = np.unique(np.clip(np.asarray(breaks, dtype=float), 0.0, length))
    knots = knots[(knots > 0.0) & (knots < length)]
    if len(knots) == 0:
        return symmetric_line_nodes(length, n, grading)
    cum = grading.cumulative if _graded(grading) else (lambda t: np.asarray(t, float))
    edges = np.concatenate([[0.0], knots, [length]])
    S = cum(edges)
    index = np.rint(n * (S - S[0]) / (S[-1] - S[0])).astype(int)
    index[0], index[-1] = 0, n
    counts = np.diff(index)
    if counts.min() < fewest:
        raise ValueError(f"{n} intervals leave {counts.min()} between two of the head's "
                         f"corners, fewer than {fewest}")
    t = np.empty(n + 1)
    for k in range(len(edges) - 1):
        s = np.linspace(S[k], S[k + 1], counts[k] + 1)
        t[index[k]:index[k + 1] + 1] = _inverse(grading, s, edges[k], edges[k + 1])
        t[index[k]], t[index[k + 1]] = edges[k], edges[k + 1]
    mirror = length - t[::-1]
    if np.allclose(t, mirror, rtol=0, atol=1e-9 * length / n):
        t = 0.5 * (t + mirror)
        t[index] = edges      # the breaks exact again (mirror-symmetric to round-off)
        if n % 2 == 0:
            t[n // 2] = 0.5 * length if not np.isin(n // 2, index[1:-1]) else t[n // 2]
    return t


@dataclass(frozen=True)
class Grading:
    """How a 2-D bearing grid is graded.

    Parameters
    ----------
    x_ratio : float
        Spacing far from the wrap corners over the spacing at them (>= 1; 1: uniform in x).
    x_width : float or None
        Width δ of the refined zone about each corner, m (None: the model's default,
        1.5 times the larger of the film length R ε^(1/3) and the bending length
        √(D/(T − ρV²))).
    y_ratio : float
        Spacing in the middle of the width over the spacing at the free edges (>= 1).
    y_width : float
        Width δ of the refined zone at each edge, m (the free-edge layer is about 0.5 mm
        wide on the Table 1 tape).
    corner_ratio : float or None
        Spacing far from the corners over the spacing at them of the algebraic corner
        refinement (>= 1; 1: none), on top of the x-grading (:class:`LineGrading`): the
        spacing grows in proportion to the distance from each corner, so it resolves the
        film's constriction where a corner touches. None: the model's default (none on a
        cylinder; on a flat or profile head flying on its film see
        :func:`gyroshell.bearing.model.corner_grading`).
    corner_width : float or None
        Distance from a corner (m) beyond which that spacing grows in proportion to it
        (None: the model's default).
    corner_scales : tuple of (float or None), optional
        Each corner's own corner width as a multiple of ``corner_width`` (> 0; an entry
        None: no corner refinement at that corner), one per corner of the head in order;
        None (the default): ``corner_width`` at every corner. The spacing beyond each grows
        at the same rate (:class:`LineGrading` ``corner_widths``). The smooth-law solve's
        start grid (:func:`gyroshell.bearing.smooth.turned_corner_scales`).
    """

    x_ratio: float = 1.0
    x_width: float | None = None
    y_ratio: float = 1.0
    y_width: float = 0.5e-3
    corner_ratio: float | None = None
    corner_width: float | None = None
    corner_scales: tuple[float | None, ...] | None = None

    def __post_init__(self) -> None:
        for name in ("x_ratio", "y_ratio", "corner_ratio"):
            if getattr(self, name) is not None or name != "corner_ratio":
                validation.real(name, getattr(self, name), low=1.0)
        for name in ("x_width", "y_width", "corner_width"):
            if getattr(self, name) is not None or name == "y_width":
                validation.positive(name, getattr(self, name), "m")
        if self.corner_scales is not None:
            object.__setattr__(self, "corner_scales", tuple(
                None if c is None else validation.positive(f"corner_scales[{i}]", c)
                for i, c in enumerate(self.corner_scales)))

    @property
    def uniform(self) -> bool:
        return (self.x_ratio == 1.0 and self.y_ratio == 1.0
                and self.corner_ratio in (None, 1.0))

    def x_line(self, length: float, corners: tuple[float, ...]) -> LineGrading | None:
        """The x-line's grading about ``corners`` (m along the line; with
        ``corner_scales``, one per entry)."""
        corner = self.corner_ratio or 1.0
        scales = self.corner_scales
        if scales is not None:
            if len(scales) != len(corners):
                raise ParameterError(f"grading.corner_scales must hold one entry per corner "
                                     f"({len(corners)}), got {len(scales)}")
            if all(c is None for c in scales):
                corner = 1.0
        if self.x_ratio == 1.0 and corner == 1.0:
            return None
        width = float(self.corner_width or 0.0)
        widths = (None if scales is None or corner == 1.0
                  else tuple(None if c is None else c * width for c in scales))
        return LineGrading(float(self.x_ratio), float(self.x_width or 0.0), tuple(corners),
                           float(corner), width, widths)

    def y_line(self, width: float) -> LineGrading | None:
        if self.y_ratio == 1.0:
            return None
        return LineGrading(float(self.y_ratio), self.y_width, (0.0, width))

    def as_dict(self) -> dict:
        out = {"x_ratio": self.x_ratio, "x_width": self.x_width, "y_ratio": self.y_ratio,
               "y_width": self.y_width, "corner_ratio": self.corner_ratio,
               "corner_width": self.corner_width}
        if self.corner_scales is not None:      # a start grid's (not in stored defaults)
            out["corner_scales"] = list(self.corner_scales)
        return out


#: No grading: uniform spacing each way.
UNIFORM = Grading()


def intervals_for(length: float, finest: float, grading: LineGrading | None) -> int:
    """Number of intervals, a multiple of 4 (the grid twice as coarse is then nested and
    has a middle node), putting the finest spacing of the sech zones (at the refinement
    centres, without an algebraic corner term, which refines further within) at about
    ``finest`` (m)."""
    if grading is None:
        n = length / finest
    else:   # the finest spacing of the sech zones (the corner term refines within them)
        zones = LineGrading(grading.ratio, grading.width, grading.centres)
        peak = float(np.max(zones.density(np.array(grading.centres))))
        n = float(grading.cumulative(length)) / (finest * peak)
    return max(4, 4 * round(0.25 * n))
