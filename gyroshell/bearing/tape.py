"""The tape's operators on the bearing's grid, the infinitely wide strip, and the loads of
the wrapped configuration.

The tape obeys the seed paper's shell equation with the load
P = (p − p_a) − (T − ρV²)/R: the paper's Eq. 2 writes the belt-wrap pressure as T/R and
leaves out the centrifugal ρV²/R of a tape transported around the curve, which is included
here. Written for u = w − w₀ (see :mod:`.geometry`), the equation reads

    A u + (T − ρV²) B u = W (p − p_a) − (T − ρV²) W κ + f_κ + λ,

with f_κ the bending reference load of the dry curvature κ, λ the contact forces and the
foundation term k acting on u (the tape's hoop stiffness resists departures from the
wrapped configuration only).

The grid is a tensor product of node lines x_i, y_j, uniform or graded (:mod:`.mesh`).
The operators are those of :mod:`gyroshell.tape.operators`, written for non-uniform spacing
from the same discrete energies: second differences
δ²w_i = [(w_{i+1} − w_i)/h_i − (w_i − w_{i−1})/h_{i−1}] / w_i (w_i the node's
control width, half the two neighbouring intervals), first differences and the twist on
the intervals and cells, each term weighted by its own length or area. A, B are sums of
weighted Gram matrices and therefore exactly symmetric for any spacing, G = 2ρV W C_x is
skew (W C_x is ρV times the antisymmetric shift, whatever the spacing) and on a uniform
grid every matrix equals the core one to round-off. On a smoothly graded grid the second
difference is second-order accurate.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..tape.grid import Grid
from ..tape.operators import (
    PlateCurvatures,
    dual_widths,
    nodal_gyroscopic,
    nodal_mass,
    nodal_membrane,
    second_difference,
    weighted_gram,
)
from ..tape.parameters import TapeParameters

#: The strip's "width": it is solved per unit width (one node across, weight 1).
_UNIT_WIDTH = np.ones(1)


class StripOperators:
    """A, B, M, G and the nodal widths W of an infinitely wide tape (per unit width).

    The plate in cylindrical bending (w_yy = 0): bending rigidity D = D11 (the 2-D plate's
    middle, far from the free edges, bends with D11 for an orthotropic or layered tape),
    foundation k, membrane ∫ w_x² dx, mass ρ; unknowns at the interior nodes i = 1..nx−1
    of the node abscissae ``x`` (m, uniform or graded).
    """

    def __init__(self, params: TapeParameters, x: np.ndarray) -> None:
        x = np.asarray(x, dtype=float)
        self.x, self.n = x, len(x) - 2
        self.W = dual_widths(x)[1:-1]
        self.lxx = second_difference(x)
        self.A = (params.D * weighted_gram(self.lxx, self.W)
                  + params.k * sp.diags(self.W)).tocsr()
        self.B = nodal_membrane(x, _UNIT_WIDTH)
        self.M = nodal_mass(params.density, self.W, _UNIT_WIDTH)
        self.params = params

    def G(self, velocity: float) -> sp.csr_matrix:
        """G(V) = 2ρV W C_x, kg/s per unit width (V in m/s)."""
        return nodal_gyroscopic(self.params.density, velocity, self.n, _UNIT_WIDTH)

    def curvature_load(self, kappa: np.ndarray) -> np.ndarray:
        """f_κ = D δ²ᵀ W κ, N/m: the bending force of the reference curvature κ (1/m)."""
        return self.params.D * (self.lxx.T @ (self.W * kappa))

    def elastic_force(self, u: np.ndarray, kappa: np.ndarray, tension: float) -> np.ndarray:
        """A u + T' B u + T' W κ − f_κ, N/m (T' = ``tension``, N/m; u in m, κ in 1/m):
        the tape rows' elastic terms, equal to those of the matrices to round-off, summed
        as nested differences: the slopes s = δ⁺u on the intervals, the net curvature
        c = δ²u − κ = δ⁻s / W − κ at the nodes (0 at the pinned ends), then
        D δ⁻(δ⁺c) + k W u − T' W c (A = D δ²ᵀWδ² + k W, B u = −δ⁻s, f_κ = D δ²ᵀWκ).

        The sum K u of the assembled matrix carries a round-off of ε Σ|K_ij||u_j|: on a
        corner's 15 nm cells, the plate's entries D/Δx³ ~ 1e18 N/m² per m times a tape
        50 µm above the dry string, 1e-2 N/m per node, random in sign and above the
        corner's own contact force per node; the tension carries each such force over
        the span (a point force F lifts a string by F ℓ/T', tens of nm), so Newton's
        steps on those rows' round-off alone were tens of σ_s (measured on design 7 of
        benchmarks/bench_design_set.py). Differenced first, each level's round-off is ε
        times that level's own size (ε|s| in a slope of 0.05, not ε|u|/Δx in one of
        3,000): about 1e-7 N/m there."""
        h = np.diff(self.x)
        s = np.diff(np.concatenate([[0.0], u, [0.0]])) / h
        c = np.diff(s) / self.W - kappa
        shear = np.diff(np.concatenate([[0.0], c, [0.0]])) / h
        return (self.params.D * np.diff(shear) + self.params.k * self.W * u
                - tension * self.W * c)


class PlateOperators:
    """A, B, M, G and W of the free-edged plate on the tensor grid ``x`` × ``y`` (m).

    Unknowns: the interior x-lines i = 1..nx−1, every node across (j fastest), as in
    :class:`gyroshell.Grid` with free edges. A is assembled by
    :class:`gyroshell.tape.operators.PlateCurvatures`, the one assembly of the tape's
    :func:`gyroshell.tape.operators.bending_foundation`: ½ Σ W [D11 w_xx² + 2 D12 w_xx w_yy
    + D22 w_yy²] at the interior nodes, ½ Σ W (D11 − D12²/D22) w_xx² at the edge nodes (the
    edge moment M_y = −(D12 w_xx + D22 w_yy) is zero: free-edge conditions as natural
    boundary conditions), 2 D66 Σ a w_xy² over the cells (a their areas), plus k/2 Σ W w²
    (``params.bending_matrix``; isotropic: D11 = D22 = D, D12 = νD, D66 = (1 − ν)D/2).
    """

    def __init__(self, params: TapeParameters, x, y=None) -> None:
        if isinstance(x, Grid):
            if not x.free_edges:
                raise ValueError("the bearing's plate has free edges")
            x, y = x.x, x.y
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        self.x, self.y, self.params = x, y, params
        wx, wy = dual_widths(x)[1:-1], dual_widths(y)
        self.n = (len(x) - 2) * len(y)
        self.wx, self.wy = wx, wy
        self.W = np.kron(wx, wy)
        curvatures = PlateCurvatures(x, y, free_edges=True)
        self._dxx, self._dyy = curvatures.dxx, curvatures.dyy
        self._dxx_edge = curvatures.dxx_edge
        self._w_inner, self._w_edge = curvatures.w_inner, curvatures.w_edge
        self._bending = params.bending_matrix
        self.A = curvatures.stiffness(self._bending, params.k)
        self.B = nodal_membrane(x, wy)
        self.M = nodal_mass(params.density, wx, wy)

    def G(self, velocity: float) -> sp.csr_matrix:
        """G(V) = 2ρV W C_x, kg/s (V in m/s)."""
        return nodal_gyroscopic(self.params.density, velocity, len(self.x) - 2, self.wy)

    def curvature_load(self, kappa: np.ndarray) -> np.ndarray:
        """f_κ, N: gradient of the bending energy's cross terms with a reference curvature
        κ(x) (1/m, at the interior x-nodes) in w_xx, uniform across the width.

        The bending energy above with w_xx replaced by w_xx − κ; the part linear in u is
        −f_κ·u: f_κ = D11 δxxᵀWκ + D12 δyyᵀWκ + (D11 − D12²/D22) δxx,edgeᵀW_edge κ, with
        the Poisson moment D12 κ w_yy and the free-edge term (isotropic: D [δxxᵀWκ
        + ν δyyᵀWκ + (1 − ν²) δxx,edgeᵀW_edge κ], bit for bit).
        """
        ny = len(self.y) - 1
        _, r12, _, r_edge = self._bending.ratios
        k_int = self._w_inner * np.repeat(kappa, ny - 1)
        f = self._dxx.T @ k_int + r12 * (self._dyy.T @ k_int)
        f += r_edge * (self._dxx_edge.T @ (self._w_edge * np.repeat(kappa, 2)))
        return self._bending.D11 * f
