"""Finite-difference operators M, G(V), K(V) of the semi-discrete system (paper Eq. 9).

    M a + G(V) v + K(V) w = F,      K(V) = A + (T − ρV²) B

The speed-independent parts A, B and M are assembled here; K(V) itself is formed by
:meth:`gyroshell.TapeModel.K`, which caches A and B across speeds.

Every matrix is assembled from a discrete *energy* (or power) with trapezoid weights, so the
structure that the physics guarantees holds by construction, not by luck:

* ``M = ρ W`` with W the nodal control areas: diagonal and positive.
* ``G = 2ρV W Cx``, Cx the central difference along x: skew-symmetric (gyroscopic forces do
  no work).
* ``B`` from Σ (δx⁺w)² over x-edges, the discrete ∫ w_x² dA: symmetric positive definite.
* ``A`` from the plate bending energy plus the foundation ½ k ∫ w² dA: symmetric positive
  definite.

The bending energy density D/2 [w_xx² + w_yy² + 2ν w_xx w_yy + 2(1−ν) w_xy²] is summed with
second differences at nodes and the twist w_xy at cell centres. In the interior this gives
the standard 13-point biharmonic stencil. On a free edge the density is written as
(1 − ν²) w_xx² + (w_yy + ν w_xx)², whose second part is the square of the edge moment M_y/D
and is dropped there (Eq. 5): the variation then yields the zero-moment and zero
Kirchhoff-shear conditions (Eqs. 5–6) as natural boundary conditions, the 2-D analogue of
ghost-point elimination but with a symmetric K. Corners lie on the simply supported ends
(w = 0); the twisting-moment corner force there is a support reaction.

All rows are multiplied by control areas (units: force per node), so F is the nodal force
vector (N) and w, v, a are in m, m/s, m/s².
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .grid import Grid
from .parameters import TapeParameters, check_velocity


def _second_difference(n_unknowns: int, h: float) -> sp.csr_matrix:
    """δ² on the interior nodes of a line with zero values at both ends, (n, n)."""
    e = np.ones(n_unknowns)
    return sp.diags([e[1:], -2 * e, e[1:]], [-1, 0, 1], format="csr") / h**2


def _forward_difference(n_nodes: int, h: float, dirichlet: bool) -> sp.csr_matrix:
    """δ⁺ from nodes to the n_intervals midpoints.

    With ``dirichlet`` the unknowns are the n_nodes − 2 interior nodes (end values zero),
    otherwise all n_nodes nodes are unknown.
    """
    n_int = n_nodes - 1
    full = sp.diags([-np.ones(n_int), np.ones(n_int)], [0, 1], shape=(n_int, n_nodes),
                    format="csr") / h
    return full[:, 1:-1] if dirichlet else full


def _y_second_difference(grid: Grid) -> sp.csr_matrix:
    """δy² at the interior nodes j = 1..ny−1, acting on the unknowns of one x-line."""
    if not grid.free_edges:
        return _second_difference(grid.ny - 1, grid.hy)
    d = _forward_difference(grid.ny + 1, grid.hy, dirichlet=False)
    return (d[1:] - d[:-1]) / grid.hy


def _y_selector(grid: Grid, rows: np.ndarray) -> sp.csr_matrix:
    """Rows picking node indices ``rows`` (in 0..ny) out of one x-line's unknowns."""
    offset = 0 if grid.free_edges else 1
    cols = rows - offset
    return sp.csr_matrix((np.ones(len(rows)), (np.arange(len(rows)), cols)),
                         shape=(len(rows), grid.n_across))


def weighted_gram(op: sp.spmatrix, weights: np.ndarray) -> sp.csr_matrix:
    """opᵀ diag(weights) op: the matrix of the quadratic form Σ weights (op w)²."""
    return (op.T @ sp.diags(weights) @ op).tocsr()


# ----- node-coordinate assembly (uniform or graded lines) ---------------------------------
# The tape's grid is uniform; the air bearing's (gyroshell.bearing.tape) is graded. Both
# assemble M, G and B here from their node coordinates: each term of the energy weighted by
# its own length or area, so M stays diagonal, G skew and B symmetric for any spacing.
def dual_widths(t: np.ndarray) -> np.ndarray:
    """Control-volume widths of the nodes t (m): half the two neighbouring intervals
    (one half-interval at the ends)."""
    h = np.diff(t)
    w = np.empty(len(t))
    w[0], w[-1] = 0.5 * h[0], 0.5 * h[-1]
    w[1:-1] = 0.5 * (h[:-1] + h[1:])
    return w


def unknown_widths(t: np.ndarray, free_ends: bool) -> np.ndarray:
    """Control widths (m) of the unknown nodes of the line t: every node with free ends,
    the interior ones with supported (zero) ends."""
    w = dual_widths(t)
    return w if free_ends else w[1:-1]


def second_difference(t: np.ndarray, dirichlet: bool = True) -> sp.csr_matrix:
    """δ² at the interior nodes of the line t, acting on its interior nodes (``dirichlet``,
    zero end values: square) or on all its nodes, 1/m².

    δ²w_i = [(w_{i+1} − w_i)/h_i − (w_i − w_{i−1})/h_{i−1}] / w_i with w_i the node's
    control width: second-order accurate on a smoothly graded line.
    """
    h = np.diff(t)
    w = dual_widths(t)[1:-1]
    lo, hi = 1.0 / (h[:-1] * w), 1.0 / (h[1:] * w)
    n = len(t) - 2
    full = sp.diags([lo, -(lo + hi), hi], [0, 1, 2], shape=(n, n + 2), format="csr")
    return full[:, 1:-1].tocsr() if dirichlet else full


def forward_difference(t: np.ndarray, dirichlet: bool) -> sp.csr_matrix:
    """δ⁺ from the nodes t to the interval midpoints, 1/m (``dirichlet``: on the interior
    nodes only, end values zero)."""
    h = np.diff(t)
    full = sp.diags([-1.0 / h, 1.0 / h], [0, 1], shape=(len(h), len(t)), format="csr")
    return full[:, 1:-1].tocsr() if dirichlet else full


def half_shift(n: int) -> sp.csr_matrix:
    """½ (S⁺ − S⁻): W C_x for any spacing (the central difference times the control width,
    whose 2 w_i = x_{i+1} − x_{i−1} cancels)."""
    e = np.ones(n - 1)
    return (0.5 * sp.diags([-e, e], [-1, 1], shape=(n, n))).tocsr()


def nodal_mass(density: float, wx: np.ndarray, wy: np.ndarray) -> sp.dia_matrix:
    """M = ρ W, kg, W = wx ⊗ wy the control areas (m²) of the unknowns (x-lines outer)."""
    return sp.diags(density * np.kron(wx, wy))


def nodal_gyroscopic(density: float, velocity: float, n_lines: int,
                     wy: np.ndarray) -> sp.csr_matrix:
    """G = 2ρV W C_x, kg/s, on ``n_lines`` unknown x-lines with the control widths ``wy``
    (m) across: exactly skew for any spacing."""
    return (2 * density * velocity * sp.kron(half_shift(n_lines), sp.diags(wy))).tocsr()


def nodal_membrane(x: np.ndarray, wy: np.ndarray) -> sp.csr_matrix:
    """B, the discrete ∫ w_x² dA over the interior x-lines of the nodes ``x`` (m) with the
    control widths ``wy`` (m) across: Σ over the x-intervals of h (δ⁺w)², symmetric."""
    return sp.kron(weighted_gram(forward_difference(x, dirichlet=True), np.diff(x)),
                   sp.diags(wy)).tocsr()


def mass(grid: Grid, params: TapeParameters) -> sp.dia_matrix:
    """Mass matrix M = ρ W, kg: diagonal, positive (lumped areal density × control area).

    Examples
    --------
    >>> from gyroshell import TapeParameters, Grid
    >>> p = TapeParameters(width=8.0, spacing=1.0, length_ratio=1.0)
    >>> mass(Grid.from_parameters(p), p).diagonal()[:4]
    array([0.007, 0.014, 0.014, 0.014])
    """
    return nodal_mass(params.density, dual_widths(grid.x)[1:-1],
                      unknown_widths(grid.y, grid.free_edges))


def gyroscopic(grid: Grid, params: TapeParameters, velocity: float) -> sp.csr_matrix:
    """Gyroscopic matrix G = 2ρV W Cx, kg/s: skew-symmetric (Gᵀ = −G).

    Discretizes the Coriolis term 2ρV w_xt with central differences along x; zero at V = 0.

    Parameters
    ----------
    velocity : float
        Tape transport speed V, m/s (>= 0), in the +x direction.
    """
    velocity = check_velocity(velocity)
    return nodal_gyroscopic(params.density, velocity, grid.n_lines,
                            unknown_widths(grid.y, grid.free_edges))


def membrane(grid: Grid) -> sp.csr_matrix:
    """B, the discrete ∫ w_x² dA (dimensionless ratio m²/m²): symmetric positive definite.

    B w approximates −∂²w/∂x² times the control areas; K(V) = A + (T − ρV²) B.
    """
    return nodal_membrane(grid.x, unknown_widths(grid.y, grid.free_edges))


def bending_foundation(grid: Grid, params: TapeParameters) -> sp.csr_matrix:
    """A: plate bending plus shell foundation, N/m: symmetric positive definite.

    The quadratic form ½ wᵀ A w is the discrete D/2 ∫ [w_xx² + w_yy² + 2ν w_xx w_yy
    + 2(1−ν) w_xy²] dA + k/2 ∫ w² dA (see the module notes for the free edges).
    """
    D, nu, k = params.D, params.poisson, params.k
    hx, hy = grid.hx, grid.hy
    n_lines, ny = grid.n_lines, grid.ny
    Ix = sp.identity(n_lines, format="csr")
    lxx = _second_difference(n_lines, hx)                       # x: i = 1..nx−1
    interior = np.arange(1, ny)
    s_int = _y_selector(grid, interior)                          # y: j = 1..ny−1
    dxx = sp.kron(lxx, s_int)                                    # w_xx at interior nodes
    dyy = sp.kron(Ix, _y_second_difference(grid))               # w_yy at interior nodes
    area = hx * hy
    bend = area * (dxx.T @ dxx + dyy.T @ dyy + nu * (dxx.T @ dyy + dyy.T @ dxx))
    if grid.free_edges:
        dxx_edge = sp.kron(lxx, _y_selector(grid, np.array([0, ny])))
        bend = bend + (1 - nu**2) * 0.5 * area * (dxx_edge.T @ dxx_edge)
    dxy = sp.kron(_forward_difference(grid.nx + 1, hx, dirichlet=True),
                  _forward_difference(grid.ny + 1, hy, dirichlet=not grid.free_edges))
    bend = bend + 2 * (1 - nu) * area * (dxy.T @ dxy)
    return (D * bend + sp.diags(params.k * grid.areas)).tocsr() if k else (D * bend).tocsr()
