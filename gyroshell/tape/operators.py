"""Finite-difference operators M, G(V), K(V) of the semi-discrete system (paper Eq. 9).

    M a + G(V) v + K(V) w = F,      K(V) = A + (T − ρV²) B

The speed-independent parts A, B and M are assembled here; K(V) itself is formed by
:meth:`gyroshell.model.TapeModel.K`, which caches A and B across speeds.

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


def _weighted_gram(op: sp.spmatrix, weights: np.ndarray) -> sp.csr_matrix:
    """opᵀ diag(weights) op: the matrix of the quadratic form Σ weights (op w)²."""
    return (op.T @ sp.diags(weights) @ op).tocsr()


def mass(grid: Grid, params: TapeParameters) -> sp.dia_matrix:
    """Mass matrix M = ρ W, kg: diagonal, positive (lumped areal density × control area).

    Examples
    --------
    >>> from gyroshell import TapeParameters, Grid
    >>> p = TapeParameters(width=8.0, spacing=1.0, length_ratio=1.0)
    >>> mass(Grid.from_parameters(p), p).diagonal()[:4]
    array([0.007, 0.014, 0.014, 0.014])
    """
    return sp.diags(params.density * grid.areas)


def gyroscopic(grid: Grid, params: TapeParameters, velocity: float) -> sp.csr_matrix:
    """Gyroscopic matrix G = 2ρV W Cx, kg/s: skew-symmetric (Gᵀ = −G).

    Discretizes the Coriolis term 2ρV w_xt with central differences along x; zero at V = 0.

    Parameters
    ----------
    velocity : float
        Tape transport speed V, m/s (>= 0), in the +x direction.
    """
    velocity = check_velocity(velocity)
    n = grid.n_lines
    e = np.ones(n - 1)
    cx = sp.diags([-e, e], [-1, 1], shape=(n, n)) / (2 * grid.hx)
    return (2 * params.density * velocity * sp.kron(cx, sp.diags(grid.hx * grid.y_weights))
            ).tocsr()


def membrane(grid: Grid) -> sp.csr_matrix:
    """B, the discrete ∫ w_x² dA (dimensionless ratio m²/m²): symmetric positive definite.

    B w approximates −∂²w/∂x² times the control areas; K(V) = A + (T − ρV²) B.
    """
    dx = _forward_difference(grid.nx + 1, grid.hx, dirichlet=True)
    return sp.kron(_weighted_gram(dx, np.full(grid.nx, grid.hx)),
                   sp.diags(grid.y_weights)).tocsr()


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
