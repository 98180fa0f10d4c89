"""TapeModel: one tape (parameters + grid) with its operators assembled once.

A thin cache over the plain functions of :mod:`gyroshell.operators` and
:mod:`gyroshell.loads`, so that engines and studies that need K(V) at many speeds assemble
the speed-independent parts A, B, M, W only once.
"""

from __future__ import annotations

from functools import cached_property

import numpy as np
import scipy.sparse as sp

from . import operators
from .errors import ParameterError
from .grid import Grid
from .loads import gaussian_load
from .parameters import TapeParameters, check_velocity


class TapeModel:
    """The semi-discrete tape M a + G(V) v + K(V) w = F (paper Eq. 9).

    Parameters
    ----------
    params : TapeParameters
        Physical and numerical parameters (SI).
    grid : Grid, optional
        Override the grid derived from ``params.spacing`` (e.g. for refinement studies).
    load : numpy.ndarray, optional
        Override the nodal load vector F, N (default: the Gaussian of Eq. 17).
    """

    def __init__(self, params: TapeParameters | None = None, grid: Grid | None = None,
                 load: np.ndarray | None = None) -> None:
        self.params = TapeParameters() if params is None else params
        self.grid = Grid.from_parameters(self.params) if grid is None else grid
        if load is not None:
            load = np.asarray(load, dtype=float)
            if load.shape != (self.grid.size,) or not np.all(np.isfinite(load)):
                raise ParameterError(
                    f"load must be a finite vector of length {self.grid.size} (N)")
            self.__dict__["load"] = load

    def __repr__(self) -> str:
        g = self.grid
        return (f"TapeModel(L_x={g.length:.4g} m, L_y={g.width:.4g} m, {g.nx}x{g.ny} intervals,"
                f" edges={g.edges!r}, n={g.size})")

    @property
    def size(self) -> int:
        return self.grid.size

    @cached_property
    def A(self) -> sp.csr_matrix:
        """Bending + foundation part of K, N/m (SPD)."""
        return operators.bending_foundation(self.grid, self.params)

    @cached_property
    def B(self) -> sp.csr_matrix:
        """Membrane part of K: discrete ∫ w_x² dA (SPD)."""
        return operators.membrane(self.grid)

    @cached_property
    def M(self) -> sp.dia_matrix:
        """Mass matrix, kg (diagonal, positive)."""
        return operators.mass(self.grid, self.params)

    @property
    def mass_diagonal(self) -> np.ndarray:
        """Diagonal of M, kg."""
        return self.params.density * self.grid.areas

    def effective_tension(self, velocity: float) -> float:
        """T − ρV², N/m."""
        return self.params.tension - self.params.density * check_velocity(velocity) ** 2

    def K(self, velocity: float) -> sp.csr_matrix:
        """Stiffness K(V) = A + (T − ρV²) B, N/m (symmetric)."""
        return (self.A + self.effective_tension(velocity) * self.B).tocsr()

    def G(self, velocity: float) -> sp.csr_matrix:
        """Gyroscopic matrix G(V), kg/s (skew-symmetric)."""
        return operators.gyroscopic(self.grid, self.params, velocity)

    @cached_property
    def load(self) -> np.ndarray:
        """Nodal forces of the Gaussian load of Eq. 17, N (wrap pressure if enabled)."""
        return gaussian_load(self.grid, self.params)

    @cached_property
    def load_point_row(self) -> np.ndarray:
        """Weights r with r @ w = w at the load centroid (bilinear interpolation)."""
        return self.grid.interpolation_row(*self.params.load_centroid)
