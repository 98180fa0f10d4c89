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

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .grid import Grid
from .parameters import TapeParameters, check_velocity


def weighted_gram(op: sp.spmatrix, weights: np.ndarray) -> sp.csr_matrix:
    """opᵀ diag(weights) op: the matrix of the quadratic form Σ weights (op w)².

    Exactly symmetric: the product's mirrored entries sum the same terms in different
    orders (equal only to round-off on a graded line), so its symmetric part is returned;
    where they are already equal that part is the product bit for bit.
    """
    gram = (op.T @ sp.diags(weights) @ op).tocsr()
    return (0.5 * (gram + gram.T)).tocsr()


# ----- node-coordinate assembly (uniform or graded lines) ---------------------------------
# The tape's grid is uniform; the air bearing's (gyroshell.bearing.tape) is graded. Both
# assemble M, G, B and A here from their node coordinates: each term of the energy weighted
# by its own length or area, so M stays diagonal, G skew and B, A exactly symmetric for any
# spacing.
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


@dataclass(frozen=True)
class PlateCurvatures:
    """The discrete curvatures of the plate's bending energy on the node lines x × y, each
    with the weights (m²) that sum its square over the plate.

    Unknowns: the interior x-lines, and across every node (free edges) or the interior ones
    (simply supported edges), j fastest, as in :class:`Grid`. Build with :meth:`on_nodes`.

    Attributes
    ----------
    dxx, dyy : scipy.sparse.csr_matrix
        w_xx and w_yy at the interior nodes (1/m² per m of w), weighted by ``w_inner``,
        their control areas.
    dxx_edge : scipy.sparse.csr_matrix or None
        w_xx at the free-edge nodes (j = 0, n_y), weighted by ``w_edge`` (None with
        supported edges).
    dxy : scipy.sparse.csr_matrix
        The twist w_xy at the cell centres, weighted by ``w_cell``, the cell areas.
    areas : numpy.ndarray
        Control areas of the unknown nodes, m² (the foundation's weights).
    """

    dxx: sp.csr_matrix
    dyy: sp.csr_matrix
    dxx_edge: sp.csr_matrix | None
    dxy: sp.csr_matrix
    w_inner: np.ndarray
    w_edge: np.ndarray | None
    w_cell: np.ndarray
    areas: np.ndarray

    @classmethod
    def on_nodes(cls, x: np.ndarray, y: np.ndarray, free_edges: bool) -> PlateCurvatures:
        """The curvatures on the node abscissae ``x`` and ordinates ``y`` (m, uniform or
        graded), pinned ends x = x₀, x_n and free or simply supported lateral edges."""
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        ny = len(y) - 1
        wx, wy = dual_widths(x)[1:-1], dual_widths(y)
        lxx = second_difference(x)
        across = sp.identity(ny + 1 if free_edges else ny - 1, format="csr")
        inner = across[1:-1] if free_edges else across
        dxx = sp.kron(lxx, inner, format="csr")
        dyy = sp.kron(sp.identity(len(x) - 2, format="csr"),
                      second_difference(y, dirichlet=not free_edges), format="csr")
        dxx_edge = sp.kron(lxx, across[[0, ny]], format="csr") if free_edges else None
        dxy = sp.kron(forward_difference(x, dirichlet=True),
                      forward_difference(y, dirichlet=not free_edges), format="csr")
        return cls(dxx, dyy, dxx_edge, dxy, np.kron(wx, wy[1:-1]),
                   np.kron(wx, wy[[0, ny]]) if free_edges else None,
                   np.kron(np.diff(x), np.diff(y)),
                   np.kron(wx, unknown_widths(y, free_edges)))

    def stiffness(self, rigidity: float, poisson: float, foundation: float
                  ) -> sp.csr_matrix:
        """A, N/m: the bending energy D/2 Σ [w_xx² + w_yy² + 2ν w_xx w_yy + 2(1−ν) w_xy²]
        (the edge rows: (1 − ν²) w_xx², see the module notes) plus k/2 Σ W w², with the
        rigidity D (N·m), Poisson ratio ν and foundation stiffness k (N/m³).

        The interior density is written as the squares (w_yy + ν w_xx)² + (1 − ν²) w_xx²,
        so A is a sum of weighted Gram matrices and exactly symmetric.
        """
        nu = poisson
        bend = (weighted_gram(self.dyy + nu * self.dxx, self.w_inner)
                + (1 - nu**2) * weighted_gram(self.dxx, self.w_inner)
                + 2 * (1 - nu) * weighted_gram(self.dxy, self.w_cell))
        if self.dxx_edge is not None:
            bend = bend + (1 - nu**2) * weighted_gram(self.dxx_edge, self.w_edge)
        return (rigidity * bend + sp.diags(foundation * self.areas)).tocsr()


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
    + 2(1−ν) w_xy²] dA + k/2 ∫ w² dA (see the module notes for the free edges), assembled
    from the grid's node coordinates by :class:`PlateCurvatures`, as on the air bearing's
    graded grids.
    """
    curvatures = PlateCurvatures.on_nodes(grid.x, grid.y, grid.free_edges)
    return curvatures.stiffness(params.D, params.poisson, params.k)
