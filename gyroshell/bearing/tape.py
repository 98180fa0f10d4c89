"""The tape side of the bearing: the shell operators of :mod:`gyroshell.operators` on the
bearing's grid, the infinitely wide strip, and the loads of the wrapped configuration.

The tape obeys the seed paper's shell equation with the load
P = (p − p_a) − (T − ρV²)/R: the paper's Eq. 2 writes the belt-wrap pressure as T/R and
leaves out the centrifugal ρV²/R of a tape transported around the curve, which is included
here. Written for u = w − w₀ (see :mod:`.geometry`), the equation reads

    A u + (T − ρV²) B u = W (p − p_a) − (T − ρV²) W κ + f_κ + λ,

with f_κ the bending reference load of the dry curvature κ, λ the contact forces and the
foundation term k acting on u (the tape's hoop stiffness resists departures from the
wrapped configuration only).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .. import operators
from ..grid import Grid
from ..operators import _forward_difference, _second_difference, _y_second_difference, _y_selector
from ..parameters import TapeParameters


class StripOperators:
    """A, B, M, G and the nodal widths W of an infinitely wide tape (per unit width).

    The plate in cylindrical bending (w_yy = 0): bending rigidity D, foundation k,
    membrane ∫ w_x² dx, mass ρ; unknowns at the interior nodes i = 1..nx−1.
    """

    def __init__(self, params: TapeParameters, nx: int, hx: float) -> None:
        self.hx, self.n = hx, nx - 1
        self.lxx = _second_difference(self.n, hx)
        dx = _forward_difference(nx + 1, hx, dirichlet=True)
        self.A = (params.D * hx * (self.lxx.T @ self.lxx)
                  + params.k * hx * sp.identity(self.n)).tocsr()
        self.B = (hx * (dx.T @ dx)).tocsr()
        self.W = np.full(self.n, hx)
        self.M = sp.diags(params.density * self.W)
        self.params = params

    def G(self, velocity: float) -> sp.csr_matrix:
        e = np.ones(self.n - 1)
        cx = sp.diags([-e, e], [-1, 1], shape=(self.n, self.n)) / (2 * self.hx)
        return (2 * self.params.density * velocity * self.hx * cx).tocsr()

    def curvature_load(self, kappa: np.ndarray) -> np.ndarray:
        """f_κ = D Δx δ²ᵀ κ, N/m: the bending force of the reference curvature κ (1/m)."""
        return self.params.D * self.hx * (self.lxx.T @ kappa)


class PlateOperators:
    """A, B, M, G (from :mod:`gyroshell.operators`) and W on the bearing's 2-D grid."""

    def __init__(self, params: TapeParameters, grid: Grid) -> None:
        self.grid, self.params = grid, params
        self.A = operators.bending_foundation(grid, params)
        self.B = operators.membrane(grid)
        self.M = operators.mass(grid, params)
        self.W = grid.areas
        self.n = grid.size

    def G(self, velocity: float) -> sp.csr_matrix:
        return operators.gyroscopic(self.grid, self.params, velocity)

    def curvature_load(self, kappa: np.ndarray) -> np.ndarray:
        """f_κ, N: gradient of the bending energy's cross terms with a reference curvature
        κ(x) (1/m, at the interior x-nodes) in w_xx, uniform across the width.

        The bending energy of :func:`gyroshell.operators.bending_foundation` with w_xx
        replaced by w_xx − κ; the part linear in u is −f_κ·u.
        """
        g, p = self.grid, self.params
        area = g.hx * g.hy
        ny = g.ny
        lxx = _second_difference(g.n_lines, g.hx)
        ix = sp.identity(g.n_lines, format="csr")
        k_int = np.repeat(kappa, ny - 1)
        dxx = sp.kron(lxx, _y_selector(g, np.arange(1, ny)))
        dyy = sp.kron(ix, _y_second_difference(g))
        f = area * (dxx.T @ k_int + p.poisson * (dyy.T @ k_int))
        dxx_edge = sp.kron(lxx, _y_selector(g, np.array([0, ny])))
        f += (1 - p.poisson**2) * 0.5 * area * (dxx_edge.T @ np.repeat(kappa, 2))
        return p.D * f
