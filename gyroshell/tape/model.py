"""TapeModel: one tape (parameters + grid) with its operators assembled once.

A thin cache over the plain functions of :mod:`gyroshell.tape.operators` and
:mod:`gyroshell.tape.loads`, so that engines and studies that need K(V) at many speeds assemble
the speed-independent parts A, B, M, W only once.
"""

from __future__ import annotations

import math
import warnings
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from ..core import validation
from ..core.errors import ParameterError
from . import operators
from .grid import Grid
from .loads import gaussian_load
from .parameters import TapeParameters


class TapeModel:
    """The semi-discrete tape M a + G(V) v + K(V) w = F (paper Eq. 9).

    Parameters
    ----------
    params : TapeParameters
        Physical and numerical parameters (SI).
    grid : Grid, optional
        Override the grid derived from ``params.spacing`` (e.g. for refinement studies): it
        must span the tape (``params``' length, width and edges; else ParameterError).
    force : numpy.ndarray, optional
        Override the nodal force vector F, N (default: the Gaussian of Eq. 17).
    load : numpy.ndarray, optional
        Deprecated name of ``force``.

    Examples
    --------
    >>> TapeModel(TapeParameters(spacing=6.35e-3 / 8))
    TapeModel(L_x=0.0254 m, L_y=0.00635 m, 32x8 intervals, edges='free', n=279)
    """

    def __init__(self, params: TapeParameters | None = None, grid: Grid | None = None,
                 force: np.ndarray | None = None, *, load: np.ndarray | None = None) -> None:
        validation.instance("params", params, TapeParameters, optional=True)
        validation.instance("grid", grid, Grid, optional=True)
        self.params = TapeParameters() if params is None else params
        self.grid = Grid.from_parameters(self.params) if grid is None else \
            grid.check_matches(self.params)
        if load is not None:
            warnings.warn("TapeModel(load=...) is deprecated; use force= (N)",
                          DeprecationWarning, stacklevel=2)
            force = load if force is None else force
        if force is not None:
            self.__dict__["force"] = validation.vector("force", force, self.grid.unknowns,
                                                       "N")

    def __repr__(self) -> str:
        g = self.grid
        return (f"TapeModel(L_x={g.length:.4g} m, L_y={g.width:.4g} m, {g.nx}x{g.ny} intervals,"
                f" edges={g.edges!r}, n={g.unknowns})")

    @property
    def unknowns(self) -> int:
        """Number of unknowns n."""
        return self.grid.unknowns

    @property
    def size(self) -> int:
        """Deprecated name of :attr:`unknowns`."""
        warnings.warn("TapeModel.size is deprecated; use unknowns", DeprecationWarning,
                      stacklevel=2)
        return self.grid.unknowns

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
        """T − ρV², N/m.

        Raises
        ------
        ParameterError
            If V is negative, not finite, or so large that ρV² overflows.
        """
        velocity = self.params.check_velocity(velocity)
        return self.params.tension - self.params.density * velocity * velocity

    def K(self, velocity: float) -> sp.csr_matrix:
        """Stiffness K(V) = A + (T − ρV²) B, N/m: symmetric, positive definite below the
        critical (divergence) speed and indefinite above it."""
        return (self.A + self.effective_tension(velocity) * self.B).tocsr()

    def G(self, velocity: float) -> sp.csr_matrix:
        """Gyroscopic matrix G(V), kg/s (skew-symmetric)."""
        return operators.gyroscopic(self.grid, self.params, self.params.check_velocity(velocity))

    def divergence_speed_estimate(self) -> float:
        """√((T + μ)/ρ), m/s, with μ = min_m (D a_m² + k/a_m²) over the width-uniform modes.

        D = D11 (orthotropic or layered tapes too). Exact for D12 = 0 (ν = 0) and free
        edges, otherwise close (from above): a cheap (one vector over the x-wavenumbers, no
        factorization) estimate of the critical speed for warnings.
        """
        g, p = self.grid, self.params
        alpha = np.arange(1, g.nx) * np.pi / g.length
        a2 = (2.0 / g.hx * np.sin(alpha * g.hx / 2)) ** 2
        mu = float(np.min(p.D * a2 + p.k / a2))
        return math.sqrt((p.tension + mu) / p.density)

    @cached_property
    def force(self) -> np.ndarray:
        """Nodal forces of the Gaussian load of Eq. 17, N (wrap pressure if enabled)."""
        return gaussian_load(self.grid, self.params)

    @property
    def load(self) -> np.ndarray:
        """Deprecated name of :attr:`force` (N)."""
        warnings.warn("TapeModel.load is deprecated; use force (N)", DeprecationWarning,
                      stacklevel=2)
        return self.force

    @cached_property
    def load_point_row(self) -> np.ndarray:
        """Weights r with r @ w = w at the load centroid (bilinear interpolation)."""
        return self.grid.interpolation_row(*self.params.load_centroid)


#: What the tape's engines read from a model. A TapeModel has them all; another object that
#: has them (e.g. the tape restricted to an invariant subspace) stands in for one.
MODEL_MEMBERS: tuple[str, ...] = ("params", "grid", "unknowns", "mass_diagonal", "M", "K", "G")


def check_model(model: object, name: str = "model", *,
                members: tuple[str, ...] = MODEL_MEMBERS) -> TapeModel:
    """``model`` unchanged if it is a :class:`TapeModel` or has every one of ``members``
    (the engine's needs, default :data:`MODEL_MEMBERS`); the check at every engine's door.

    Raises
    ------
    ParameterError
        Naming ``name``, the expected type and the type received (and the first member
        missing, for an object that has some of them).

    Examples
    --------
    >>> check_model(None)
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: model must be a TapeModel, got NoneType
    """
    if isinstance(model, TapeModel):
        return model
    missing = [m for m in members if not hasattr(model, m)]
    if not missing:
        return model
    some = len(missing) < len(members)
    raise ParameterError(
        f"{name} must be a TapeModel, got {type(model).__name__}"
        + (f" (it has no {missing[0]})" if some else ""))
