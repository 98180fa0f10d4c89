"""The bearing's steady (or one time step's) equations as a problem for the generic Newton.

:class:`SteadyProblem` gives :func:`gyroshell.linalg.newton.newton` what it needs and
nothing of how to solve it: the coupled residual r(z) = [r_u, r_p] of the state
z = [u, p] (:mod:`.model`), its Jacobian reduced to the free unknowns and factored once per
iteration in the grid's fixed pattern (:mod:`.jacobian`), the scales of the rows (the
merit) and of the unknowns (the step's size), the largest step that keeps the film's
coefficients within reach, the residual's round-off floor, and, for the hard wall only,
the bounds h >= σ on the tape's nodes (a smooth contact law has none: its force is in
r_u). The residual's pieces (:class:`_Residual`: the tape and film rows, the wall's
semismooth contact rows (its Jacobian's checks), the scales, the assembly and
factorization in the grid's fixed pattern) serve this problem.
"""

from __future__ import annotations

import hashlib

import numpy as np
import scipy.sparse as sp

from ..core.errors import ConvergenceError, ParameterError
from ..linalg.factorization import (
    DiagonalPivotLU,
    PardisoFactor,
    SuperLUFactor,
    nested_dissection,
    resolve_pattern_lu,
)
from ..linalg.grid_ordering import grid_nested_dissection
from ..linalg.newton import BOUND_TOLERANCE
from .jacobian import JacobianPattern
from .model import BearingModel, wrapped_corners

#: ... and a free node's spacing to no less than this fraction of its value ...
SPACING_KEEP = 0.2

#: ... nor grow by more than this multiple of it (plus σ).
SPACING_GROWTH = 4.0

#: Whether a 2-D tape's Jacobian is factored in single precision ("grid" and "metis";
#: the residual, and so the state Newton converges to, stays in double precision; a solve
#: whose backward error exceeds
#: :data:`gyroshell.linalg.factorization.SINGLE_BACKWARD_ERROR_LIMIT` factors again in
#: double). Off: on the 12.65 mm tape's default grid it made the solve 0.81x (the LU 0.6x,
#: the same 8 iterations and states equal to 6e-11), but on a 3 mm tape over a flat head
#: touching at its corners (96 x 24, the plate's h⁻⁴ rows at the corners' fine cells) the
#: single-precision steps, backward errors below 1e-5 but forward errors of order one,
#: led Newton astray and the pseudo-time march failed (docs/performance.md).
SINGLE_LU = False

#: Column ordering of the Jacobian's sparse LU with partial pivoting (factorization
#: "colamd"): COLAMD, SuperLU's ordering for general unsymmetric matrices.
JACOBIAN_ORDERING = "COLAMD"


def _step_limit(h: np.ndarray, du: np.ndarray, active: np.ndarray, sigma: float,
                floor=None) -> float:
    """Largest α <= 1 keeping every free node's spacing within [h/5, 5 h + σ] (the film
    coefficients vary like h³). Nodes whose full step would take them below σ are exempt:
    the step is projected onto h >= σ (:func:`_project`) and they enter the contact set at
    the next iteration, all at once instead of a few per damped step. ``floor``: the
    contact floor per node (default σ; :attr:`BearingModel.contact_floor`)."""
    floor = sigma if floor is None else floor
    alpha = 1.0
    # a node below the head (a rounded arc's node off contact may dip there during the
    # iteration) has no spacing to keep a fraction of: the projection raises it
    free = ~active & (h > 0.0)
    down = free & (du < -(1 - SPACING_KEEP) * h) & (h + du > np.maximum(floor, sigma))
    if down.any():
        alpha = min(alpha, float(np.min(-(1 - SPACING_KEEP) * h[down] / du[down])))
    up = free & (du > SPACING_GROWTH * h + sigma)
    if up.any():
        alpha = min(alpha, float(np.min((SPACING_GROWTH * h[up] + sigma) / du[up])))
    return alpha


#: A smooth contact law's step may lower a spacing by this many roughnesses σ_s even
#: where that is more than SPACING_KEEP of it allows: the tape pressed onto its
#: asperities may reach d < 0 (the summits' mean plane below the head's surface).
CONTACT_STEP = 2.0


def _smooth_step_limit(h: np.ndarray, du: np.ndarray, sigma: float, film: bool = True
                       ) -> float:
    """Largest α <= 1 keeping every spacing above the larger drop of h/5 and h −
    CONTACT_STEP σ_s (the asperity pressure varies like exp(−h²/2σ_s²)), and, with a
    ``film``, below 5 h + σ_s (the film's coefficients vary like h³; without one a
    spacing may rise freely: the law only falls)."""
    alpha = 1.0
    drop = np.maximum((1 - SPACING_KEEP) * np.maximum(h, 0.0), CONTACT_STEP * sigma)
    down = du < -drop
    if down.any():
        alpha = min(alpha, float(np.min(-drop[down] / du[down])))
    if not film:
        return alpha
    rise = SPACING_GROWTH * np.maximum(h, 0.0) + sigma
    up = du > rise
    if up.any():
        alpha = min(alpha, float(np.min(rise[up] / du[up])))
    return alpha


def _contact_scale(model: BearingModel) -> np.ndarray:
    return model.stiffness_diagonal


class _Residual:
    """The semismooth residual [min(r_u, c (h − σ)), r_p] of one solve, scaled for the
    merit function: tape rows by the wrap force W (T − ρV²)/R, film rows by the Couette
    flux 6μV h p_a (compressible) or 6μV h through one face. Over wrapped arcs at speed
    (:func:`_wrapped_at_speed`) W is √(W W̄) (W̄ the mean node width): the merit is then
    the quadrature of the tape's residual force density, so that the arcs' cells, down to
    25 nm (1/40 of W̄ and less), do not outweigh the rest by their 1/W (a contact force
    applied in part along a step there made every damped step's merit rise: measured,
    r_c = 2.5 mm at 4 m/s converged in 9 Newton iterations instead of 86)."""

    def __init__(self, model: BearingModel, tension, transient) -> None:
        self.model, self.tension, self.transient = model, tension, transient
        self.K = model.K(tension)
        self.c = _contact_scale(model)
        #: a smooth contact law: no contact set (the law's force is in the tape rows)
        self.smooth = model.smooth_contact
        self.sigma = model.air.roughness
        #: σ at the nodes that may touch the head (not the rounded arcs' other nodes)
        self.floor = model.contact_floor
        self.film_kw = ({} if transient is None else
                        {"phi_old": transient.phi_old, "dt": transient.dt})
        t_wrap = max(model.effective_tension(tension) / model.scale_radius, 1.0)
        self.t_scale = t_wrap
        self.h_scale = max(model.h_guess, self.sigma)
        film = model.film
        # the Couette flux through each pressure node's x-face (its control width across)
        flux = (6.0 * model.air.viscosity * abs(model.velocity) * self.h_scale
                * film.x_face_length[np.nonzero(film.interior)[1]])
        if model.air.compressible:
            flux *= model.air.ambient_pressure
        if model.dry:       # the rows p − p_a (Pa)
            flux = np.full(model.n_p, t_wrap)
        width = (np.sqrt(model.W * np.mean(model.W)) if _wrapped_at_speed(model)
                 else model.W)
        self.row_scale = np.concatenate([1.0 / (t_wrap * width), 1.0 / flux])
        J_uu = self.K if transient is None else self.K + transient.jacobian
        # The tape rows [J_uu, −L] do not change within a solve: assembled once.
        self.tape_rows = sp.hstack([J_uu, -model.pressure_load], format="csr")
        self.tape_rows.sort_indices()
        self._abs_tape_rows = abs(self.tape_rows)
        #: the Jacobian's folded pattern (:meth:`_pattern`), once formed
        self._jacobian_pattern = None
        #: (z, result) of the last residual evaluated alone, and |∂r_p/∂p| (the film's, of
        #: the last Jacobian: :meth:`update_noise`)
        self._last, self._abs_film_pp = None, None
        self._abs_loads = (np.abs(model.effective_tension(tension) * model.W
                                  * model.kappa_nodes) + np.abs(model.f_kappa))

    def _noise(self, u, p, abs_J_pp) -> float:
        """The scaled residual's round-off floor (the merit's): machine ε times the
        magnitudes of the terms each row sums, |K||u| + |L||p − p_a| + the wrap loads on
        the tape rows, |∂r_p/∂p||p| on the film rows. On a grid refined far below the
        bending length at a corner the tape rows' floor (∝ h⁻⁴) can exceed a converged
        state's residual: a line search below it sees only noise."""
        pa = self.model.air.ambient_pressure
        tape = self._abs_tape_rows @ np.concatenate([np.abs(u), np.abs(p - pa)]) \
            + self._abs_loads
        film = abs_J_pp @ np.abs(p)
        #: the round-off of each row (its units), for the step's floor (:func:`_noise_step`)
        self.noise_rows = np.finfo(float).eps * np.concatenate([tape, film])
        return float(np.linalg.norm(self.noise_rows * self.row_scale))

    def tape(self, u, p):
        r_u = self.model.tape_residual(u, p, self.K, self.tension)
        if self.smooth:
            r_u = r_u - self.model.asperity_force(u)[0]
        if self.transient is not None:
            r_u = r_u + self.transient.tape_terms(u)[0]
        return r_u

    def __call__(self, z, *, jacobian: bool, force=None, active=None):
        """(residual, contact set, Jacobian or None). ``force``: nodes put in the contact
        set whatever their residual (the nodes a Newton step predicts below σ);
        ``active``: the contact set itself, in place of the rule. The residual alone at
        the state last evaluated (the line search's accepted trial) is not formed again."""
        plain = not jacobian and force is None and active is None
        if plain and self._last is not None and self._last[0] is z:
            return self._last[1]
        m = self.model
        u, p = z[:m.n_u], z[m.n_u:]
        r_u = self.tape(u, p)
        r_p, J_pp, J_h, free = m.film_linearization(u, p, jacobian=jacobian, **self.film_kw)
        res, active = self.contact_rows(u, r_u, r_p, active, force)
        if not jacobian:
            self._last = (z, (res, active, None)) if plain else None
            return res, active, None
        self._film_jacobian_formed(u, p, J_pp)
        return res, active, Linearization(self, active, J_h, J_pp, free,
                                          self.contact_stiffness(u))

    def contact_rows(self, u, r_u, r_p, active=None, force=None):
        """(residual, contact set) from the tape's residual ``r_u`` at the tape state
        ``u`` and the film's ``r_p``: the contact set by the rule r_u > c (h − σ) unless
        ``active`` is given, with the nodes ``force`` added; its rows c (h − σ)."""
        if self.smooth:      # no wall: every tape row is its equation
            active = np.zeros(u.size, dtype=bool) if active is None else active
            return np.concatenate([r_u, r_p]), active
        gap = self.c * (u + self.model.dry_field[1:-1, :].ravel() - self.floor)
        if active is None:
            active = r_u > gap
        if force is not None:
            active = active | force
        return np.concatenate([np.where(active, gap, r_u), r_p]), active

    def linearize(self, z, active) -> Linearization:
        """The linearization at z with the contact set ``active``, without the residual
        (the film's blocks only: a 2-D tape's Jacobian formed when it is factored)."""
        m = self.model
        u, p = z[:m.n_u], z[m.n_u:]
        _, J_pp, J_h, free = m.film_linearization(u, p, jacobian=True, **self.film_kw)
        self._film_jacobian_formed(u, p, J_pp)
        return Linearization(self, active, J_h, J_pp, free, self.contact_stiffness(u))

    def contact_stiffness(self, u) -> np.ndarray | None:
        """−∂f/∂u of a smooth contact law's nodal forces f at the tape state u (N/m;
        None for the hard wall): added to the tape rows' diagonal."""
        return -self.model.asperity_force(u)[1] if self.smooth else None

    def contact_forces(self, z, active) -> np.ndarray:
        """The head's contact force on each tape node at the converged state z, N (N/m
        per unit width): the smooth law's, or the tape residual of the contact set."""
        n_u = self.model.n_u
        if self.smooth:
            return self.model.asperity_force(z[:n_u])[0]
        return np.where(active, self.tape(z[:n_u], z[n_u:]), 0.0)

    def with_contact(self, lin: Linearization, active) -> Linearization:
        """``lin`` with the contact set ``active`` (the film's blocks do not depend on
        it: they are reused)."""
        return Linearization(self, active, lin.J_h, lin.J_p, lin.free, lin.diagonal)

    def _film_jacobian_formed(self, u, p, J_pp) -> None:
        """Keep |∂r_p/∂p| of the film's new Jacobian at (u, p) and the merit's round-off
        floor there."""
        self._abs_film_pp = abs(J_pp)
        #: the round-off floor of the merit at the last state whose Jacobian was formed
        self.noise = self._noise(u, p, self._abs_film_pp)

    def update_noise(self, z) -> None:
        """:attr:`noise` (and :attr:`noise_rows`) at the state z, with the film's ∂r_p/∂p
        of the last Jacobian formed (a round-off estimate: chord steps do not form the
        Jacobian)."""
        m = self.model
        self.noise = self._noise(z[:m.n_u], z[m.n_u:], self._abs_film_pp)

    def jacobian(self, lin: Linearization, format: str = "csr") -> sp.spmatrix:
        """The whole (unfolded) Jacobian of the linearization ``lin``, the blocks stacked
        (a contact node's tape row is c on its diagonal, its column of the film's rows
        zero), as :meth:`_factor_pivoted` factors it."""
        m = self.model
        rows_u = self.tape_rows
        if lin.active.any():
            rows_u = (sp.diags((~lin.active).astype(float)) @ rows_u
                      + sp.diags(lin.active * self.c, shape=rows_u.shape))
        if lin.diagonal is not None:
            rows_u = rows_u + sp.diags(np.where(lin.active, 0.0, lin.diagonal),
                                       shape=rows_u.shape)
        film_rows = sp.hstack([m.film_tape_block(lin.J_h, lin.free), lin.J_p], format="csr")
        return sp.vstack([rows_u, film_rows], format=format)

    def factor(self, lin: Linearization, pressure_scale: np.ndarray | None = None):
        """A solver res ↦ −J⁻¹ res of the linearization ``lin``, by the model's
        ``factorization``. A 2-D tape, symmetric about its centre line, is solved on half
        the width (the step stays symmetric: P δ_half, P the mirror). The matrix is
        assembled into its grid's fixed pattern (:mod:`.jacobian`), in the elimination
        order of a nested dissection ("grid", "metis"). ``pressure_scale``: the pressure
        columns multiplied by it (J diag(1, s): the unknowns s-scaled, e.g. ln p with
        s = p)."""
        kind = _jacobian_lu(self.model)
        if kind == "colamd":
            return self._factor_pivoted(lin, pressure_scale)
        pattern = self._pattern(kind, lin)
        tape_values, J_p = self.tape_rows.data, lin.J_p
        if pressure_scale is not None:
            n_u = self.model.n_u
            scale = np.concatenate([np.ones(n_u), pressure_scale])
            tape_values = tape_values * scale[self.tape_rows.indices]
            J_p = J_p.copy()
            J_p.data = J_p.data * pressure_scale[J_p.indices]
        J = pattern.matrix(tape_values, lin.active, self.c, lin.J_h, J_p,
                           None if lin.free.dtype == bool and lin.free.all() else lin.free,
                           lin.diagonal)
        try:
            if kind in _ORDERED_KINDS:
                lu = DiagonalPivotLU(J, ordered=True, single=SINGLE_LU)
            elif kind == "mmd":
                lu = DiagonalPivotLU(J)
            else:
                lu = PardisoFactor(J)
        except RuntimeError as exc:  # exactly singular
            raise ConvergenceError(f"Newton: singular Jacobian ({exc})") from None
        take, put = pattern.input, pattern.output      # compiled by the assembly
        return lambda res: -lu.solve(res[take])[put]

    def _factor_pivoted(self, lin: Linearization, pressure_scale=None):
        """:meth:`factor` by SuperLU's partial pivoting after COLAMD (the infinitely wide
        tape's banded Jacobian, or ``factorization="colamd"``), on the matrix as it
        always was: the stacked blocks without explicit zeros (COLAMD orders the pattern
        it is given: explicit zeros would move its order and so the iterates'
        round-off), folded by the mirror on a symmetric 2-D tape."""
        m = self.model
        J = self.jacobian(lin, format="csc")
        if pressure_scale is not None:
            J = (J @ sp.diags(np.concatenate([np.ones(m.n_u), pressure_scale]))).tocsc()
        fold = m.mirror
        if fold is not None:
            P, rows = fold
            J = (J[rows, :] @ P).tocsc()
        try:
            lu = SuperLUFactor(J, ordering=JACOBIAN_ORDERING)
        except RuntimeError as exc:  # exactly singular
            raise ConvergenceError(f"Newton: singular Jacobian ({exc})") from None
        if fold is None:
            return lambda res: -lu.solve(res)
        return lambda res: -(P @ lu.solve(res[rows]))

    def _pattern(self, kind: str, lin: Linearization) -> JacobianPattern:
        """The Jacobian's folded pattern, ordered by nested dissection for "metis" and
        "grid" (the
        pattern without contact: valid for every contact set, a contact row keeping its
        entries as zeros). Formed once per grid and solver kind (:func:`_grid_pattern`)."""
        if self._jacobian_pattern is None:
            self._jacobian_pattern = _model_pattern(self.tape_rows, lin, self.model, kind)
        return self._jacobian_pattern

    def merit(self, res) -> float:
        return float(np.linalg.norm(res * self.row_scale))


def _jacobian_lu(model: BearingModel) -> str:
    """The factorization of ``model``'s Jacobian: its ``factorization``, where "auto" is
    "colamd" for the infinitely wide tape (a banded matrix of a few thousand unknowns,
    factored in milliseconds by any ordering: its Newton iterates keep the round-off of
    the partial-pivoting LU they always had) and
    :func:`gyroshell.linalg.factorization.resolve_pattern_lu` in 2-D."""
    if model.factorization == "auto" and model.infinitely_wide:
        return "colamd"
    return resolve_pattern_lu(model.factorization)


class Linearization:
    """Newton's linearization at one state: the contact set and the film's Jacobian
    blocks in their fixed patterns (∂r_p/∂h over every node, ∂r_p/∂p, and where the
    spacing was floored); :meth:`_Residual.factor` assembles and factors it,
    :meth:`_Residual.jacobian` gives the whole matrix."""

    def __init__(self, F: _Residual, active, J_h, J_p, free, diagonal=None) -> None:
        self.F, self.active, self.J_h, self.J_p, self.free = F, active, J_h, J_p, free
        #: a smooth contact law's stiffness on the tape rows' diagonal (N/m), or None
        self.diagonal = diagonal

    @property
    def matrix(self) -> sp.csr_matrix:
        """The whole (unfolded) Jacobian, CSR."""
        return self.F.jacobian(self)


#: Folded Jacobian patterns by grid (a digest of the blocks' patterns and the fold), the
#: most recent PATTERNS_KEPT: continuation stages, pseudo-time steps and repeated solves
#: on one grid form the pattern and its nested-dissection ordering once.
_PATTERNS: dict[bytes, JacobianPattern] = {}
PATTERNS_KEPT = 4


#: The nested-dissection orderings of the folded pattern, by factorization kind.
_ORDERED_KINDS = ("metis", "grid")


def _model_pattern(tape_rows, lin: Linearization, model: BearingModel,
                   kind: str) -> JacobianPattern:
    """The folded pattern (:func:`_grid_pattern`) of ``model``'s Jacobian for ``kind``,
    found by the digest kept on the model (:attr:`BearingModel.jacobian_patterns`): the
    film's blocks have their grid's fixed patterns and the fold is the model's, so only
    the tape rows' pattern (K, or K plus a time step's terms) is compared; the digest of
    every block is formed only on the model's first solve of that kind, or when the tape
    rows' pattern changes."""
    kept = model.jacobian_patterns.get(kind)
    if (kept is not None and np.array_equal(kept[0], tape_rows.indptr)
            and np.array_equal(kept[1], tape_rows.indices)):
        key = kept[2]
    else:
        key = _pattern_digest(tape_rows, lin.J_h, lin.J_p, model, kind)
        model.jacobian_patterns[kind] = (tape_rows.indptr.copy(), tape_rows.indices.copy(),
                                         key)
    return _grid_pattern(tape_rows, lin.J_h, lin.J_p, model, kind, key)


def _pattern_digest(tape_rows, J_h, J_p, model: BearingModel, kind: str) -> bytes:
    """A digest of the blocks' patterns, the fold and ``kind``'s ordering: the key of
    :data:`_PATTERNS`."""
    fold = model.mirror
    ordering = _ORDERED_KINDS.index(kind) + 1 if kind in _ORDERED_KINDS else 0
    parts = [np.asarray([model.nc, ordering, *J_h.shape, *J_p.shape], dtype=np.int64)]
    for A in (tape_rows, J_h, J_p):
        parts += [A.indptr, A.indices]
    if fold is not None:
        parts += [fold[1], fold[0].indices]
    digest = hashlib.blake2b(digest_size=16)
    for part in parts:
        part = np.ascontiguousarray(part)
        digest.update(f"{part.dtype.str}{part.size};".encode())
        digest.update(part.data)
    return digest.digest()


def _grid_pattern(tape_rows, J_h, J_p, model: BearingModel, kind: str,
                  key: bytes | None = None) -> JacobianPattern:
    """:class:`.jacobian.JacobianPattern` of the blocks, in the elimination order of a
    nested dissection for ``kind`` "metis"
    (:func:`gyroshell.linalg.factorization.nested_dissection`) and "grid"
    (:func:`gyroshell.linalg.grid_ordering.grid_nested_dissection` from the unknowns'
    grid nodes), formed once per pattern (``key``: its :func:`_pattern_digest`, if known)."""
    if key is None:
        key = _pattern_digest(tape_rows, J_h, J_p, model, kind)
    pattern = _PATTERNS.pop(key, None)
    if pattern is None:
        pattern = JacobianPattern(tape_rows, J_h, J_p, model.nc, model.mirror)
        if kind in _ORDERED_KINDS:
            pattern.order(pattern_ordering(pattern, model, kind))
    _PATTERNS[key] = pattern
    while len(_PATTERNS) > PATTERNS_KEPT:
        del _PATTERNS[next(iter(_PATTERNS))]
    return pattern


def pattern_ordering(pattern: JacobianPattern, model: BearingModel, kind: str) -> np.ndarray:
    """The nested-dissection ordering of ``pattern`` (folded, natural numbering) for
    ``kind`` "metis" (:func:`gyroshell.linalg.factorization.nested_dissection`) or "grid"
    (:func:`gyroshell.linalg.grid_ordering.grid_nested_dissection` from the unknowns'
    grid nodes: u is kind 0, p kind 1)."""
    if kind == "metis":
        return nested_dissection(pattern.graph())
    node = model.unknown_nodes[pattern.kept]
    return grid_nested_dissection(pattern.graph(), np.column_stack(np.divmod(node, model.nc)),
                                  (pattern.kept >= model.n_u).astype(int))



def _wrapped_at_speed(model: BearingModel) -> bool:
    """Whether ``model`` is an infinitely wide tape at speed over wrapped arcs
    (:attr:`BearingModel.wrapped_corners`) that it touches at about one point
    (:attr:`BearingModel.touching_arcs`: the grid refined to 25 nm there), each past the
    handover (those ``arc_contact="auto"`` wraps): its merit takes the quadrature weights
    (:class:`_Residual`)."""
    if not (model.infinitely_wide and model.wrapped_corners) or model.dry \
            or model.smooth_contact:
        return False
    return (model.touching_arcs == model.wrapped_corners
            == wrapped_corners(model.head, model.bending_length, "auto"))


#: A step may shrink a compressible film's pressure to no less than this fraction of it,
#: or, with the film's unknowns ln p, change ln p by at most this.
PRESSURE_KEEP = 0.2
LOG_PRESSURE_STEP = 2.0


def check_cavitation(model: BearingModel, p: np.ndarray, when: str = "") -> None:
    """Refuse an incompressible film state with p < 0 absolute (Pa): a gas film cannot
    cavitate below vacuum, and the incompressible Reynolds equation has no cavitation
    model here (the compressible film, φ = p h, stays positive by construction)."""
    if model.air.compressible or model.dry or p.size == 0 or p.min() >= 0.0:
        return
    k = int(np.argmin(p))
    i, j = np.argwhere(model.film.pressure_index == k)[0]
    where = f"x = {model.x_head[i]:.4g} m" + ("" if model.infinitely_wide
                                              else f", y = {model.y[j]:.4g} m")
    raise ParameterError(
        f"the incompressible film would cavitate: p = {p[k]:.4g} Pa absolute at {where}"
        f"{when}; use compressible=True (the compressible film stays positive)")


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
        unknowns' scales (m, Pa): see :class:`_Residual`.
    """

    def __init__(self, model: BearingModel, *, tension: float | None = None,
                 transient=None) -> None:
        self.model = model
        self.F = _Residual(model, tension, transient)
        n_u, n_p = model.n_u, model.n_p
        self.lower = None
        if not model.smooth_contact:
            floor = model.contact_floor
            bound = np.where(floor > 0.0, floor - model.dry_field[1:-1, :].ravel(), -np.inf)
            self.lower = np.concatenate([bound, np.full(n_p, -np.inf)])
        #: the film's unknowns are q = ln(p/p_a) (a smooth contact law's solve): Newton
        #: then keeps p > 0 and crosses the decades of a tent's sub-ambient pressure in
        #: a few steps, where steps in p were cut to a fifth of p each
        self.log_pressure = model.smooth_contact and model.air.compressible and not model.dry
        self.row_scale = self.F.row_scale.copy()
        if model.smooth_contact and not model.dry:
            # the film rows by the Couette flux through each node's own dry gap (plus the
            # spacing scale): in the spans, tens of µm wide, the Poiseuille terms' round-off
            # would otherwise dwarf a flux sized by the nm spacings of the contact zones
            film = model.film
            gap = np.maximum(model.dry_field[film.interior], 0.0) + self.F.h_scale
            self.row_scale[n_u:] *= self.F.h_scale / gap
        self.variable_scale = np.concatenate([np.full(n_u, self.F.h_scale),
                                              np.full(n_p, 1.0 if self.log_pressure
                                                      else self.F.t_scale)])

    def split(self, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(u, p) of a state z (its unknowns: q = ln(p/p_a) with :attr:`log_pressure`)."""
        n_u = self.model.n_u
        if self.log_pressure:
            return z[:n_u], self.model.air.ambient_pressure * np.exp(z[n_u:])
        return z[:n_u], z[n_u:]

    def unknowns(self, state: np.ndarray) -> np.ndarray:
        """The problem's unknowns of a state [u (m), p (Pa)]."""
        if not self.log_pressure:
            return np.array(state, dtype=float)
        n_u = self.model.n_u
        p = np.maximum(state[n_u:], 1e-12 * self.model.air.ambient_pressure)
        return np.concatenate([state[:n_u], np.log(p / self.model.air.ambient_pressure)])

    def state(self, z: np.ndarray) -> np.ndarray:
        """The state [u (m), p (Pa)] of the problem's unknowns z."""
        u, p = self.split(z)
        return np.concatenate([u, p])

    def residual(self, z: np.ndarray) -> np.ndarray:
        """[r_u, r_p]: the tape rows (N, N/m per unit width) with the smooth law's force,
        and the film's node balances."""
        u, p = self.split(z)
        r_u = self.F.tape(u, p)
        r_p = self.model.film_linearization(u, p, jacobian=False, **self.F.film_kw)[0]
        return np.concatenate([r_u, r_p])

    def linearize(self, z: np.ndarray, active: np.ndarray):
        """A solver rhs ↦ J⁻¹ rhs of the Jacobian at z with the rows of ``active`` (tape
        nodes held at the wall) replaced by the identity."""
        u, p = self.split(z)
        held = active[:self.model.n_u]
        lin = self.F.linearize(np.concatenate([u, p]), held)
        m = self.model
        if _jacobian_lu(m) == "colamd" and m.mirror is None:
            solve = self._scaled_solver(lin, p)                      # rhs ↦ J⁻¹ rhs
        else:
            factored = self.F.factor(lin, p if self.log_pressure else None)  # ↦ −J⁻¹ res
            solve = lambda rhs: -factored(rhs)                       # noqa: E731
        if not held.any():
            return solve
        # the factored rows of ``active`` are c e_i (c = diag K): their rhs times c
        scale = np.ones(active.size)
        scale[:held.size][held] = self.F.c[held]
        return lambda rhs: solve(rhs * scale)

    def _scaled_solver(self, lin, p: np.ndarray):
        """rhs ↦ J⁻¹ rhs by SuperLU (COLAMD, partial pivoting) on D J S, D the merit's row
        weights and S the unknowns' scales: the dimensionless system whose residual and
        steps Newton measures. Unscaled, the plate's rows on the corners' 15 nm cells
        (D/Δx⁴ Δx, 1e18 N/m² per m) beside the film's led the pivoting astray: on design
        11 of the design set the dry tape's first step at V/1000 left |J δz + r| at 80
        times |r| (no descent; Newton stagnated at α = 1e-3), scaled 0.06 times."""
        m, F = self.model, self.F
        col = self.variable_scale
        if self.log_pressure:
            col = col * np.concatenate([np.ones(m.n_u), p])
        J = (sp.diags(self.row_scale) @ F.jacobian(lin, format="csr") @ sp.diags(col)).tocsc()
        try:
            lu = SuperLUFactor(J, ordering=JACOBIAN_ORDERING)
        except RuntimeError as exc:  # exactly singular
            raise ConvergenceError(f"Newton: singular Jacobian ({exc})") from None
        scale = self.variable_scale
        row = self.row_scale
        return lambda rhs: scale * lu.solve(row * rhs)

    def step_limit(self, z: np.ndarray, dz: np.ndarray) -> float:
        """The largest α <= 1 keeping each spacing within reach of its value (a factor 5
        each way; under a smooth law, down by 2 σ_s at least) and a compressible film's
        pressure above PRESSURE_KEEP of itself."""
        m, F = self.model, self.F
        n_u = m.n_u
        u, p = self.split(z)
        du, dp = dz[:n_u], dz[n_u:]
        h = u + m.dry_field[1:-1, :].ravel()
        if m.smooth_contact:
            alpha = _smooth_step_limit(h, du, F.sigma, film=not m.dry)
        elif m.dry:
            alpha = 1.0
        else:
            at_wall = h <= F.floor
            alpha = _step_limit(h, du, at_wall, F.sigma, F.floor)
        if not self.log_pressure and m.air.compressible and not m.dry:
            shrink = (dp < -(1 - PRESSURE_KEEP) * p) & (p > 0.0)
            if shrink.any():
                alpha = min(alpha, float(np.min(-(1 - PRESSURE_KEEP) * p[shrink]
                                                / dp[shrink])))
        return max(alpha, 1e-12)

    def clip_step(self, z: np.ndarray, dz: np.ndarray) -> np.ndarray:
        """The Newton step with each ln(p/p_a) change clipped to ±LOG_PRESSURE_STEP (with
        :attr:`log_pressure`; else dz): where a pressed corner or land chokes the film,
        its nodes' pressures barely enter their rows (fluxes through a mean gap of pm)
        and Newton asks them for changes of e^100 and more; cut per node (as a circuit
        simulator limits a junction's exponential), that node no longer shortens the
        step of every other unknown, which a common α did (stagnation at α ~ 1e-5)."""
        if not self.log_pressure:
            return dz
        n_u = self.model.n_u
        out = dz.copy()
        out[n_u:] = np.clip(dz[n_u:], -LOG_PRESSURE_STEP, LOG_PRESSURE_STEP)
        return out

    def noise(self, z: np.ndarray) -> np.ndarray:
        """The round-off floor of each scaled residual row at z (:meth:`._Residual._noise`,
        the tape rows with the smooth law's force): on a grid refined far below the
        bending length the plate's rows alone can hold a converged state's residual, and
        its steps in the nodes the tape barely holds (a span microns above a corner's fine
        cells), above the step's tolerance."""
        F = self.F
        u, p = self.split(z)
        if F._abs_film_pp is None:
            _, J_pp, _ = self.model.film_residual(u, p, jacobian=True, **F.film_kw)
            F._abs_film_pp = abs(J_pp)
        F._noise(u, p, F._abs_film_pp)
        rows = F.noise_rows
        if F.smooth:
            rows = rows.copy()
            rows[:u.size] += np.finfo(float).eps * np.abs(self.model.asperity_force(u)[0])
        return rows * self.row_scale

    def contact_forces(self, z: np.ndarray, active: np.ndarray) -> np.ndarray:
        """The head's force on each tape node at the unknowns z, N (N/m per unit width)."""
        return self.F.contact_forces(self.state(z), active[:self.model.n_u])

    def forces(self, state: np.ndarray) -> np.ndarray:
        """The head's force on each tape node at a solved state [u (m), p (Pa)], N (N/m
        per unit width): the smooth law's, or at the wall the tape's residual on the
        nodes held at their bound by it (the generic Newton's active set), 0 elsewhere."""
        n_u = self.model.n_u
        if self.lower is None:
            return self.F.contact_forces(state, np.zeros(n_u, dtype=bool))
        u = state[:n_u]
        r_u = self.F.tape(u, state[n_u:])
        band = BOUND_TOLERANCE * self.F.h_scale
        at_wall = (u <= self.lower[:n_u] + band) & (r_u > 0.0)
        return np.where(at_wall, r_u, 0.0)
