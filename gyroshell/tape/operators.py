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
  definite, assembled from the node coordinates (uniform or graded) by
  :class:`PlateCurvatures`, exactly symmetric on any spacing.

The orthotropic bending energy density ½ [D11 w_xx² + 2 D12 w_xx w_yy + D22 w_yy²
+ 4 D66 w_xy²] (:mod:`gyroshell.tape.material`; isotropic: D11 = D22 = D, D12 = νD,
D66 = (1 − ν)D/2, i.e. D/2 [w_xx² + w_yy² + 2ν w_xx w_yy + 2(1−ν) w_xy²]) is summed with
second differences at nodes and the twist w_xy at cell centres. In the interior this gives
the 13-point (orthotropic) biharmonic stencil. On a free edge the density is written as
(D11 − D12²/D22) w_xx² + (D22 w_yy + D12 w_xx)²/D22 (isotropic: D[(1 − ν²) w_xx²
+ (w_yy + ν w_xx)²]), whose second part is the square of the edge moment
M_y = −(D12 w_xx + D22 w_yy) over D22 and is dropped there (Eq. 5): the variation then
yields the zero-moment and zero Kirchhoff-shear conditions (Eqs. 5–6; orthotropic:
D22 w_yyy + (D12 + 4 D66) w_xxy = 0) as natural boundary conditions, the 2-D analogue of
ghost-point elimination but with a symmetric K. Corners lie on the simply supported ends
(w = 0); the twisting-moment corner force there is a support reaction.

All rows are multiplied by control areas (units: force per node), so F is the nodal force
vector (N) and w, v, a are in m, m/s, m/s².
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .grid import Grid
from .material import BendingStiffness
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


class PlateCurvatures:
    """The discrete curvatures of the plate's bending energy on the node lines ``x`` × ``y``
    (m, uniform or graded), with the weights (m²) that sum their squares over the plate.

    Unknowns: the interior x-lines (pinned ends), and across every node (``free_edges``)
    or the interior ones (simply supported edges), j fastest, as in :class:`Grid`. Every
    curvature is a tensor product of line operators and every weight a product of line
    widths, so each term of the energy is the Kronecker product of two one-dimensional
    weighted Gram matrices: A is assembled from those without any two-dimensional product.

    Attributes
    ----------
    w_inner, w_edge : numpy.ndarray
        Control areas (m²) of the interior-across nodes and of the free-edge nodes
        (j = 0, n_y; None with supported edges), the weights of :attr:`dxx`, :attr:`dyy`
        and :attr:`dxx_edge`.
    areas : numpy.ndarray
        Control areas of the unknown nodes, m² (the foundation's weights).
    """

    def __init__(self, x: np.ndarray, y: np.ndarray, free_edges: bool) -> None:
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        ny = len(y) - 1
        self.free_edges = bool(free_edges)
        self._lxx = second_difference(x)
        self._wx, wy = dual_widths(x)[1:-1], dual_widths(y)
        across = sp.identity(ny + 1 if free_edges else ny - 1, format="csr")
        self._inner = across[1:-1] if free_edges else across
        self._edge = across[[0, ny]] if free_edges else None
        self._lyy = second_difference(y, dirichlet=not free_edges)
        self._wy_inner, self._wy_edge = wy[1:-1], wy[[0, ny]] if free_edges else None
        self._fx = forward_difference(x, dirichlet=True)
        self._fy = forward_difference(y, dirichlet=not free_edges)
        self._hx, self._hy = np.diff(x), np.diff(y)
        self.w_inner = np.kron(self._wx, self._wy_inner)
        self.w_edge = np.kron(self._wx, self._wy_edge) if free_edges else None
        self.areas = np.kron(self._wx, unknown_widths(y, free_edges))

    @property
    def dxx(self) -> sp.csr_matrix:
        """w_xx at the interior-across nodes, 1/m² per m of w."""
        return sp.kron(self._lxx, self._inner, format="csr")

    @property
    def dyy(self) -> sp.csr_matrix:
        """w_yy at the interior-across nodes, 1/m² per m of w."""
        return sp.kron(sp.identity(len(self._wx), format="csr"), self._lyy, format="csr")

    @property
    def dxx_edge(self) -> sp.csr_matrix | None:
        """w_xx at the free-edge nodes (None with supported edges)."""
        return None if self._edge is None else sp.kron(self._lxx, self._edge, format="csr")

    def stiffness(self, bending: BendingStiffness, foundation: float) -> sp.csr_matrix:
        """A, N/m: the bending energy ½ Σ W [D11 w_xx² + 2 D12 w_xx w_yy + D22 w_yy²]
        + ½ Σ a 4 D66 w_xy² (the edge rows: (D11 − D12²/D22) w_xx², see the module notes)
        plus k/2 Σ W w², with the bending stiffnesses ``bending`` (N·m) and the foundation
        stiffness k (N/m³).

        Written as D11 × [...] with the ratios of :attr:`BendingStiffness.ratios`, which for
        an isotropic plate are exactly 1, ν, 2(1 − ν), 1 − ν²: its operator is assembled by
        the isotropic formula D [...] bit for bit. Exactly symmetric: the one-dimensional
        Gram matrices are, so are their Kronecker products, and the mixed term
        2 D12 w_xx w_yy enters as C + Cᵀ.
        """
        r22, r12, r66, r_edge = bending.ratios
        wx = self._wx
        across = weighted_gram(self._inner, self._wy_inner)           # diagonal
        if self._edge is not None:
            across = across + r_edge * weighted_gram(self._edge, self._wy_edge)
        mixed = sp.kron(self._lxx.T @ sp.diags(wx),
                        self._inner.T @ sp.diags(self._wy_inner) @ self._lyy, format="csr")
        bend = (sp.kron(weighted_gram(self._lxx, wx), across)
                + _scaled(r22, sp.kron(sp.diags(wx), weighted_gram(self._lyy, self._wy_inner)))
                + r12 * (mixed + mixed.T)
                + r66 * sp.kron(weighted_gram(self._fx, self._hx),
                                weighted_gram(self._fy, self._hy)))
        return (bending.D11 * bend + sp.diags(foundation * self.areas)).tocsr()


def _scaled(ratio: float, matrix: sp.spmatrix) -> sp.spmatrix:
    """ratio × matrix, without the copy for the isotropic ratio 1 (the same values)."""
    return matrix if ratio == 1.0 else ratio * matrix


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

    The quadratic form ½ wᵀ A w is the discrete ½ ∫ [D11 w_xx² + 2 D12 w_xx w_yy
    + D22 w_yy² + 4 D66 w_xy²] dA + k/2 ∫ w² dA (isotropic: D/2 ∫ [w_xx² + w_yy²
    + 2ν w_xx w_yy + 2(1−ν) w_xy²] dA; see the module notes for the free edges), with
    ``params.bending_matrix`` and ``params.k``, assembled from the grid's node coordinates by
    :class:`PlateCurvatures`, as on the air bearing's graded grids.
    """
    curvatures = PlateCurvatures(grid.x, grid.y, grid.free_edges)
    return curvatures.stiffness(params.bending_matrix, params.k)
