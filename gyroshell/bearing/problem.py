"""The bearing's steady (or one time step's) equations as a problem for the generic Newton.

:class:`SteadyProblem` gives :func:`gyroshell.linalg.newton.newton` what it needs and
nothing of how to solve it: the coupled residual r(z) = [r_u, r_p] of the state
z = [u, p] (:mod:`.model`), its Jacobian reduced to the free unknowns and factored once per
iteration in the grid's fixed pattern (:mod:`.jacobian`), the scales of the rows (the
merit) and of the unknowns (the step's size), the largest step that keeps the film's
coefficients within reach, the residual's round-off floor, and, for the hard wall only,
the bounds h >= σ on the tape's nodes (a smooth contact law has none: its force is in
r_u).
"""

from __future__ import annotations

import numpy as np

from .model import BearingModel

#: A step may shrink a compressible film's pressure to no less than this fraction of it.
PRESSURE_KEEP = 0.2


class SteadyProblem:
    """The coupled residual of ``model`` (at ``tension``, N/m, and with a time step's
    ``transient`` terms, if given) for :func:`gyroshell.linalg.newton.newton`.

    Attributes
    ----------
    lower : numpy.ndarray or None
        Lower bounds of [u, p]: σ − w₀ on the tape nodes that may touch a hard wall
        (m), −inf elsewhere; None under a smooth contact law.
    row_scale, variable_scale : numpy.ndarray
        The merit's row weights (1/N and the film rows' inverse Couette flux) and the
        unknowns' scales (m, Pa): see :class:`.steady._Residual`.
    """

    def __init__(self, model: BearingModel, *, tension: float | None = None,
                 transient=None) -> None:
        from .steady import _Residual

        self.model = model
        self.F = _Residual(model, tension, transient)
        n_u, n_p = model.n_u, model.n_p
        self.lower = None
        if not model.smooth_contact:
            floor = model.contact_floor
            bound = np.where(floor > 0.0, floor - model.dry_field[1:-1, :].ravel(), -np.inf)
            self.lower = np.concatenate([bound, np.full(n_p, -np.inf)])
        self.row_scale = self.F.row_scale.copy()
        if model.smooth_contact and not model.dry:
            # the film rows by the Couette flux through each node's own dry gap (plus the
            # spacing scale): in the spans, tens of µm wide, the Poiseuille terms' round-off
            # would otherwise dwarf a flux sized by the nm spacings of the contact zones
            film = model.film
            gap = model.dry_field[film.interior] + self.F.h_scale
            self.row_scale[n_u:] *= self.F.h_scale / gap
        self.variable_scale = np.concatenate([np.full(n_u, self.F.h_scale),
                                              np.full(n_p, self.F.t_scale)])

    def split(self, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(u, p) of a state z."""
        n_u = self.model.n_u
        return z[:n_u], z[n_u:]

    def residual(self, z: np.ndarray) -> np.ndarray:
        """[r_u, r_p]: the tape rows (N, N/m per unit width) with the smooth law's force,
        and the film's node balances."""
        u, p = self.split(z)
        r_u = self.F.tape(u, p)
        r_p = self.model.film_linearization(u, p, jacobian=False, **self.F.film_kw)[0]
        return np.concatenate([r_u, r_p])

    def linearize(self, z: np.ndarray, active: np.ndarray):
        """A solver rhs ↦ J⁻¹ rhs of the Jacobian at z with the rows of ``active`` (tape
        nodes at the wall) replaced by the identity (their right-hand side is 0)."""
        lin = self.F.linearize(z, active[:self.model.n_u])
        solve = self.F.factor(lin)           # res ↦ −J⁻¹ res
        return lambda rhs: -solve(rhs)

    def step_limit(self, z: np.ndarray, dz: np.ndarray) -> float:
        """The largest α <= 1 keeping each spacing within reach of its value (a factor 5
        each way; under a smooth law, down by 2 σ_s at least) and a compressible film's
        pressure above PRESSURE_KEEP of itself."""
        from .steady import _smooth_step_limit, _step_limit

        m, F = self.model, self.F
        u, p = self.split(z)
        du, dp = self.split(dz)
        h = u + m.dry_field[1:-1, :].ravel()
        if m.smooth_contact:
            alpha = _smooth_step_limit(h, du, F.sigma)
        elif m.dry:
            alpha = 1.0
        else:
            at_wall = h <= F.floor
            alpha = _step_limit(h, du, at_wall, F.sigma, F.floor)
        if m.air.compressible and not m.dry:
            shrink = (dp < -(1 - PRESSURE_KEEP) * p) & (p > 0.0)
            if shrink.any():
                alpha = min(alpha, float(np.min(-(1 - PRESSURE_KEEP) * p[shrink]
                                                / dp[shrink])))
        return max(alpha, 1e-12)

    def noise(self, z: np.ndarray) -> float:
        """The scaled residual's round-off floor at z (:meth:`.steady._Residual._noise`):
        on a grid refined far below the bending length the plate's rows alone can hold a
        converged state's residual above the step's tolerance."""
        F = self.F
        u, p = self.split(z)
        if F._abs_film_pp is None:
            _, J_pp, _ = self.model.film_residual(u, p, jacobian=True, **F.film_kw)
            F._abs_film_pp = abs(J_pp)
        F._noise(u, p, F._abs_film_pp)
        return float(np.linalg.norm(F.noise_rows * self.row_scale))

    def contact_forces(self, z: np.ndarray, active: np.ndarray) -> np.ndarray:
        """The head's force on each tape node at z, N (N/m per unit width)."""
        return self.F.contact_forces(z, active[:self.model.n_u])
