"""Static solver: K(V) w = F by one sparse factorization, with a definiteness check.

The factorization is a symmetric-mode LU (diagonal pivots, symmetric fill-reducing
ordering), i.e. an LDLᵀ in disguise: by Sylvester's law of inertia the number of negative
pivots is the number of negative eigenvalues of K(V). A negative or zero pivot means the
speed is at or above critical, where no stable equilibrium exists; the solver then refuses
and names the critical speed instead of returning an unstable "equilibrium".
"""

from __future__ import annotations

import numpy as np

from ..core import validation
from ..core.errors import SupercriticalError
from ..linalg.inertia import factor_inertia
from ..results.static import StaticSolution
from ..tape.model import TapeModel, check_model
from .divergence import DIVERGENCE_MEMBERS, divergence_speed

#: What the static solver reads from a model (its critical speed needs A and B).
STATIC_MEMBERS = (*DIVERGENCE_MEMBERS, "force", "load_point_row")


def _check_model(model: object) -> TapeModel:
    return check_model(model, members=STATIC_MEMBERS)


def factor_definite(model: TapeModel, velocity: float):
    """Factor K(V) (SuperLU, symmetric mode); refuse if K(V) is not positive definite.

    Returns
    -------
    scipy.sparse.linalg.SuperLU

    Raises
    ------
    SupercriticalError
        If K(V) has a non-positive pivot: V is at or above the critical speed.
    """
    velocity = _check_model(model).params.check_velocity(velocity)
    factor = factor_inertia(model.K(velocity))
    lu = factor.lu
    if factor.negatives is not None or factor.singular:
        definite = factor.definite
        v_c = None
    else:  # SuperLU had to pivot off the diagonal: decide from the divergence speed.
        v_c = divergence_speed(model)
        definite = velocity < v_c
    if not definite:
        v_c = divergence_speed(model) if v_c is None else v_c
        raise SupercriticalError(
            f"velocity {velocity:g} m/s is at or above the critical speed {v_c:.6g} m/s: "
            "K(V) is not positive definite, there is no stable static equilibrium "
            f"(use velocity < {v_c:.6g} m/s)",
            velocity=velocity, critical_speed=v_c)
    return lu


def solve_static(model: TapeModel, velocity: float = 0.0,
                 force: np.ndarray | None = None, *,
                 progress: bool | None = None) -> StaticSolution:
    """Static deflection K(V) w = F, m.

    Parameters
    ----------
    model : TapeModel
    velocity : float
        Tape speed V, m/s (>= 0, below the critical speed).
    force : numpy.ndarray, optional
        Nodal forces, N, a finite vector of length ``model.unknowns``; default the model's
        force (its Gaussian pressure, Eq. 17).
    progress : bool or None
        As for every engine (True, False or None); one factorization and one solve have
        no progress to show.

    Raises
    ------
    SupercriticalError
        At or above the critical speed (the message names it).
    ParameterError
        For a negative or non-finite speed, or a force of the wrong shape or not finite.

    Examples
    --------
    >>> from gyroshell import TapeModel, TapeParameters
    >>> model = TapeModel(TapeParameters(spacing=6.35e-3 / 8))
    >>> w = solve_static(model, 50.0).load_point_deflection       # m
    >>> 1e-8 < w < 1e-7
    True
    """
    velocity = _check_model(model).params.check_velocity(velocity)
    validation.progress(progress)
    force = (model.force if force is None
             else validation.vector("force", force, model.unknowns, "N"))
    w = factor_definite(model, velocity).solve(force)
    return StaticSolution(model.grid, velocity, w, float(model.load_point_row @ w),
                          model.params)
