"""Steady flying state: monolithic Newton over (u, p) with a primal–dual active set for
contact; over flat and profile heads a continuation in V up from the dry tape (low speeds,
where the flying start is degenerate), then pseudo-transient continuation, then
continuation in V down from a faster film, when Newton cannot reach the state directly.

Contact keeps the spacing at or above the roughness σ. With the contact forces λ >= 0 the
conditions are complementary: h − σ >= 0, λ >= 0, λ (h − σ) = 0, written as the
semismooth equation λ − max(0, λ − c (h − σ)) = 0 (c = diag K, in N/m). Its Newton
method is the primal–dual active-set method: nodes with λ − c (h − σ) > 0 are in
contact, their tape rows become h = σ and their λ follows from the tape equation; the
others carry λ = 0. The active set changes only between iterations and the method stops
when the set is settled and the step is negligible, so contact never stalls Newton the way
a penalty with a step limiter does.
"""

from __future__ import annotations

import hashlib
import math
import time
import warnings

import numpy as np
import scipy.sparse as sp

from ..core import validation
from ..core.errors import ConvergenceError, ParameterError
from ..linalg.factorization import (
    DiagonalPivotLU,
    PardisoFactor,
    SuperLUFactor,
    nested_dissection,
    resolve_pattern_lu,
)
from ..linalg.grid_ordering import grid_nested_dissection
from ..tape.parameters import MIN_INTERVALS_ACROSS
from .jacobian import JacobianPattern
from .model import MIN_INTERVALS_ALONG, BearingGridWarning, BearingModel, wrapped_corners
from .results import BearingSolution, NewtonInfo

#: Relative Newton step (|δu|/h_scale, |δp|/(T/R)) at which the solve has converged.
STEP_TOLERANCE = 1e-8
#: A full step below this relative size and within ROUND_OFF_MULTIPLE of the step that
#: the residual's round-off alone produces (:func:`_noise_step`) has converged: the state
#: is at its round-off floor.
ROUND_OFF_STEP = 1e-4
ROUND_OFF_MULTIPLE = 10.0
#: Most Newton iterations per solve.
MAX_ITERATIONS = 60
#: A step may shrink p to no less than this fraction of its value (compressible film).
PRESSURE_KEEP = 0.2
#: ... and a free node's spacing to no less than this fraction of its value ...
SPACING_KEEP = 0.2
#: ... nor grow by more than this multiple of it (plus σ).
SPACING_GROWTH = 4.0
#: Below this relative step a factorization is reused (chord steps) ...
CHORD_SWITCH = 5e-2
#: ... while each step shrinks at least by this factor (the infinitely wide tape, whose
#: banded LU costs less than a residual).
CHORD_CONTRACTION = 0.1
#: The same for a 2-D tape, whose LU costs many residuals and substitutions: chord steps
#: from a relative step of 0.5 while each shrinks the step 4x (on the 12.65 mm tape's
#: default grid the fine-grid Newton then factors once instead of twice: 8 iterations
#: instead of 5, the chord steps contracting about 10x each).
CHORD_SWITCH_2D = 0.5
CHORD_CONTRACTION_2D = 0.25
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
#: Newton steps below this relative size are taken in full (the quadratic regime: the
#: scaled residual may already sit at its round-off floor, where a line search only stalls).
FULL_STEP = 1e-5
#: A merit within this multiple of its round-off floor cannot guide a line search: full
#: steps are taken (Newton's own contraction decides).
NOISE_MULTIPLE = 100.0
#: Smallest line-search step before a step is taken anyway.
MIN_STEP = 1.0 / 256.0
#: Sufficient decrease of the line search: the merit must fall by this fraction of α ...
ARMIJO = 1e-4
#: ... else α is cut by this factor.
BACKTRACK = 0.5
#: Column ordering of the Jacobian's sparse LU with partial pivoting (factorization
#: "colamd"): COLAMD, SuperLU's ordering for general unsymmetric matrices.
JACOBIAN_ORDERING = "COLAMD"
#: Newton has stagnated when, over this many iterations, the scaled residual has not halved
#: and no line-search step reached STAGNATION_STEP (the start is outside Newton's basin:
#: pseudo-time or continuation takes over).
STAGNATION_WINDOW = 10
STAGNATION_STEP = 0.5


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


def _smooth_step_limit(h: np.ndarray, du: np.ndarray, sigma: float) -> float:
    """Largest α <= 1 keeping every spacing above the larger drop of h/5 and h −
    CONTACT_STEP σ_s, and below 5 h + σ_s (a smooth contact law: the film's
    coefficients vary like h³, the asperity pressure like exp(−h²/2σ_s²))."""
    alpha = 1.0
    drop = np.maximum((1 - SPACING_KEEP) * np.maximum(h, 0.0), CONTACT_STEP * sigma)
    down = du < -drop
    if down.any():
        alpha = min(alpha, float(np.min(-drop[down] / du[down])))
    rise = SPACING_GROWTH * np.maximum(h, 0.0) + sigma
    up = du > rise
    if up.any():
        alpha = min(alpha, float(np.min(rise[up] / du[up])))
    return alpha


def _project(z: np.ndarray, model: BearingModel, sigma: float) -> np.ndarray:
    """z with every spacing raised to at least σ (the feasible set of the contact; the
    rounded arcs' nodes off contact, :attr:`BearingModel.contact_floor`, to the film's
    floor σ/2: exempt from the step limit, they may dip below σ during the iteration)."""
    n_u = model.n_u
    floor = (np.where(model.contact_floor < sigma, 0.5 * sigma, sigma)   # arcs: film's floor
             - model.dry_field[1:-1, :].ravel())
    z[:n_u] = np.maximum(z[:n_u], floor)
    return z


def _norm(dz: np.ndarray, n_u: int, F) -> float:
    """max |δu|/h_scale, |δp|/(T/R): the relative size of a Newton step."""
    return max(np.max(np.abs(dz[:n_u])) / F.h_scale, np.max(np.abs(dz[n_u:])) / F.t_scale)


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

    def factor(self, lin: Linearization):
        """A solver res ↦ −J⁻¹ res of the linearization ``lin``, by the model's
        ``factorization``. A 2-D tape, symmetric about its centre line, is solved on half
        the width (the step stays symmetric: P δ_half, P the mirror). The matrix is
        assembled into its grid's fixed pattern (:mod:`.jacobian`), in the elimination
        order of a nested dissection ("grid", "metis")."""
        kind = _jacobian_lu(self.model)
        if kind == "colamd":
            return self._factor_pivoted(lin)
        pattern = self._pattern(kind, lin)
        J = pattern.matrix(self.tape_rows.data, lin.active, self.c, lin.J_h, lin.J_p,
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

    def _factor_pivoted(self, lin: Linearization):
        """:meth:`factor` by SuperLU's partial pivoting after COLAMD (the infinitely wide
        tape's banded Jacobian, or ``factorization="colamd"``), on the matrix as it
        always was: the stacked blocks without explicit zeros (COLAMD orders the pattern
        it is given: explicit zeros would move its order and so the iterates'
        round-off), folded by the mirror on a symmetric 2-D tape."""
        m = self.model
        J = self.jacobian(lin, format="csc")
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


def _line_search(F, model, z, dz, h, active, merit, tol, noise=None):
    """Backtracking from the largest admissible step (:func:`_step_limit`, and p kept
    above a fifth of itself) on the scaled residual, each trial projected onto h >= σ.
    Full steps are taken when the step is small (the quadratic regime) or the merit is
    within NOISE_MULTIPLE of its round-off floor ``noise`` (:meth:`_Residual.noise`).
    Returns (α, relative step size, trial state, trial merit)."""
    n_u = model.n_u
    # dry (no film, a linear complementarity problem): no h³ coefficients to protect;
    # a smooth contact law: every spacing kept (no wall to project onto)
    alpha = (_smooth_step_limit(h, dz[:n_u], F.sigma) if F.smooth
             else 1.0 if model.dry else _step_limit(h, dz[:n_u], active, F.sigma, F.floor))
    alpha_p = 1.0
    if model.air.compressible:
        p, dp = z[n_u:], dz[n_u:]
        shrink = (dp < -(1 - PRESSURE_KEEP) * p) & (p > 0.0)
        if shrink.any():
            alpha_p = float(np.min(-(1 - PRESSURE_KEEP) * p[shrink] / dp[shrink]))
    alpha = min(alpha, alpha_p)
    step = _norm(dz, n_u, F)
    full = step < max(tol, FULL_STEP) or (noise is not None and merit < NOISE_MULTIPLE * noise)
    if full:     # near round-off the merit can no longer decrease reliably: full steps,
        alpha = alpha_p   # but never to a pressure <= 0 (the compressible film's φ = p h)
    while True:
        trial = z + alpha * dz if F.smooth else _project(z + alpha * dz, model, F.sigma)
        res_t, _, _ = F(trial, jacobian=False)
        merit_t = F.merit(res_t)
        if full or _decreased(merit_t, merit, alpha) or alpha < MIN_STEP:
            return alpha, step, trial, merit_t
        alpha *= BACKTRACK


def _decreased(merit_trial: float, merit: float, alpha: float) -> bool:
    """The Armijo condition of a step α: the merit fell by at least ARMIJO α of itself."""
    return merit_trial <= (1.0 - ARMIJO * alpha) * merit


class _Iterate:
    """Newton's current state: z, its residual, contact set, Jacobian and merit, the last
    factorization (a solver), whether the contact set has settled, and whether the last
    step was full and negligible (``tied``): if the next one, with the contact set the
    rule gave after it, is negligible too, the state solves both linearizations, so the
    nodes the rule flips are at the tie h = σ, λ = 0 (a tape lying on a flat land with no
    force, where the rule, decided by round-off, cycles) and Newton has converged."""

    def __init__(self, F: _Residual, z0: np.ndarray) -> None:
        self.z = np.array(z0, dtype=float)
        self.res, self.active, self.J = F(self.z, jacobian=True)
        self.merit = F.merit(self.res)
        self.solver, self.last_step, self.settled = None, np.inf, False
        self.tied = False
        #: the round-off step (:func:`_noise_step`) and the factorization it was formed by
        self.noise_step, self.noise_of = 0.0, None

    def converged(self, active: np.ndarray, negligible: bool) -> bool:
        """Take the new contact set ``active``; whether Newton has converged: a negligible
        full step with the set settled, or after a negligible full step (``tied``)."""
        self.settled = np.array_equal(active, self.active)
        self.active = active
        done = negligible and (self.settled or self.tied)
        self.tied = negligible
        return done


def _newton_direction(F: _Residual, it: _Iterate) -> np.ndarray:
    """The Newton step. Near the solution with a settled contact set, the last
    factorization is reused (a chord step) as long as it still contracts fast; else J is
    factored afresh."""
    n_u = F.model.n_u
    switch, contraction = ((CHORD_SWITCH, CHORD_CONTRACTION) if F.model.infinitely_wide
                           else (CHORD_SWITCH_2D, CHORD_CONTRACTION_2D))
    if it.solver is not None and it.settled and it.last_step < switch:
        dz = it.solver(it.res)
        if _norm(dz, n_u, F) <= contraction * it.last_step:
            return dz
    if it.J is None:       # a 2-D tape forms its Jacobian only to factor it
        it.J = F.linearize(it.z, it.active)
    it.solver = F.factor(it.J)
    return it.solver(it.res)


def _film_blocks(F: _Residual, it: _Iterate) -> Linearization:
    """A linearization at the iterate (its film blocks, whatever its contact set): the
    iterate's, formed now if a chord step left it unformed."""
    if it.J is None:
        it.J = F.linearize(it.z, it.active)
    return it.J


def _kept_if_better(F, model, it, dz, h, active, solver, found, merit_t, tol):
    """Line-search the candidate step ``dz`` (with its contact set ``active`` and the
    factorization ``solver``) and keep it if its merit beats ``merit_t``, the damped step
    ``found``'s; else ``found``."""
    retry = _line_search(F, model, it.z, dz, h, active, it.merit, tol)
    if retry[3] >= merit_t:
        return found
    it.solver, it.active = solver, active
    return retry


def _forced_contact_step(F, it: _Iterate, h, dz, found, tol):
    """The step again with the free nodes it would take below σ held there, if the damped
    step ``found`` (α, step, trial, merit) failed because of them; the better of the two.

    Those nodes join the contact set now (the primal–dual active-set rule evaluated at the
    full step): damped steps would otherwise let them enter a few per iteration, each time
    with a line search that barely moves. Updates ``it.solver`` and ``it.active`` when the
    forced step is taken."""
    model = F.model
    alpha, step, _, merit_t = found
    entering = ~it.active & (h + dz[:model.n_u] < F.floor)
    if _decreased(merit_t, it.merit, alpha) or step < FULL_STEP or not entering.any():
        return found
    u, p = it.z[:model.n_u], it.z[model.n_u:]
    res_f, active_f = F.contact_rows(u, F.tape(u, p), it.res[model.n_u:], force=entering)
    forced = F.factor(F.with_contact(_film_blocks(F, it), active_f))
    dz_f = forced(res_f)
    if not np.all(np.isfinite(dz_f)):
        return found
    return _kept_if_better(F, model, it, dz_f, h, active_f, forced, found, merit_t, tol)


#: Most updates of the contact set within one linearization (:func:`_contact_set_step`).
MAX_SET_UPDATES = 30


def _set_step_start(F, it: _Iterate, found):
    """(u, r_u, the trial's merit) for a contact-set step after the step ``found`` (α,
    step, trial, merit); None where none is wanted: a full step that decreased the merit,
    or a step below FULL_STEP (converged)."""
    alpha, step, _, merit_t = found
    if (alpha == 1.0 and _decreased(merit_t, it.merit, alpha)) or step < FULL_STEP:
        return None
    n_u = F.model.n_u
    u, p = it.z[:n_u], it.z[n_u:]
    return u, F.tape(u, p), merit_t


def _contact_set_step(F, it: _Iterate, h, dz, found, tol):
    """The step again with a contact set consistent with its own linearization, if the
    step ``found`` (α, step, trial, merit) was damped or failed while the full step would
    change the contact set; the better of the two.

    The primal–dual active-set rule applied to the linearized problem (J fixed at the
    iterate): a step with set A predicts the spacing h + δu and the contact forces
    λ = r_u + [J_uu, −L] δz (the tape rows are linear); the next set is
    {λ − c (h + δu − σ) > 0}: the free nodes the step takes below σ enter, the contact
    nodes whose force turns negative leave, all at once. Repeated until the set repeats
    (at most MAX_SET_UPDATES factorizations), so a plate's land contact zone, whose nodes
    press their neighbours down, grows or shrinks by many nodes per Newton iteration
    instead of a few. Updates ``it.solver`` and ``it.active`` when that step is taken."""
    model = F.model
    n_u = model.n_u
    start = _set_step_start(F, it, found)
    if start is None:
        return found
    u, r_u, merit_t = start
    active, d, solver = it.active, dz, it.solver
    for _ in range(MAX_SET_UPDATES):
        lam = r_u + F.tape_rows @ d
        nxt = lam - F.c * (h + d[:n_u] - F.floor) > 0.0
        if np.array_equal(nxt, active):
            break
        active = nxt
        res_a, _ = F.contact_rows(u, r_u, it.res[n_u:], active)
        solver = F.factor(F.with_contact(_film_blocks(F, it), active))
        d = solver(res_a)
        if not np.all(np.isfinite(d)):
            return found
    if d is dz:
        return found
    return _kept_if_better(F, model, it, d, h, active, solver, found, merit_t, tol)


#: Most factorizations of the feasible contact step (:func:`_feasible_contact_step`).
MAX_FEASIBLE_UPDATES = 30


def _feasible_contact_step(F, it: _Iterate, h, dz, found, tol):
    """The step again by a primal active-set method on the linearized contact problem, if
    the step ``found`` (α, step, trial, merit) was damped or failed; the better of the two.
    Over the wrapped arcs of an infinitely wide tape (:func:`_contact_step_rule`).

    J fixed at the iterate, the tape rows linear: from the iterate (feasible: h >= σ) the
    step with contact set W (empty at first) is followed until the first free node
    reaches σ (the ratio test); that node joins W and the step is formed again from
    there; at the step's end the contact nodes whose force λ = r_u + [J_uu, −L] δz is
    negative leave W, all at once. Every point of the path stays feasible, so the
    line search along the step needs no projection, and W grows by the nodes the tape
    actually reaches instead of all those a step would take below σ. The primal–dual
    rule (:func:`_contact_set_step`) lets those all enter and then removes only the
    contact zone's end nodes per update (their forces alone turn negative): over an arc
    the tape touches at one node, on cells down to 25 nm, the zone shrinks by a node
    at each end per update and cycles (measured: 108 to 2 nodes in 50 updates, or
    14 → 0 → 14), so Newton stagnated and pseudo-time took 200-550 iterations.
    At most MAX_FEASIBLE_UPDATES factorizations. Updates ``it.solver`` and ``it.active``
    when that step is taken."""
    model = F.model
    n_u = model.n_u
    start = _set_step_start(F, it, found)
    if start is None:
        return found
    u, r_u, merit_t = start
    gap = np.maximum(h - F.floor, 0.0)        # the iterate's clearance (projected: >= 0)
    lin = _film_blocks(F, it)
    work = np.zeros(n_u, dtype=bool)
    d = np.zeros_like(dz)                     # the path's point, from the iterate
    solver, taken = None, False
    for _ in range(MAX_FEASIBLE_UPDATES):
        res_w, _ = F.contact_rows(u, r_u, it.res[n_u:], work)
        solver = F.factor(F.with_contact(lin, work))
        target = solver(res_w)
        if not np.all(np.isfinite(target)):
            return found
        e = target - d
        clearance = gap + d[:n_u]
        falling = ~work & (e[:n_u] < 0.0) & (clearance + e[:n_u] < 0.0)
        if falling.any():                    # the ratio test: the first node to touch
            t_i = np.where(falling, np.maximum(clearance, 0.0)
                           / np.where(falling, -e[:n_u], 1.0), np.inf)
            t = float(t_i.min())
            d = d + t * e
            work |= falling & (t_i <= t * (1.0 + 1e-9) + 1e-15)
            taken = True
            continue
        d, taken = target, True
        lam = r_u + F.tape_rows @ d
        leaving = work & (lam < 0.0)
        if not leaving.any():
            break
        work &= ~leaving
    if not taken:
        return found
    return _kept_if_better(F, model, it, d, h, work, solver, found, merit_t, tol)


def _wrapped_at_speed(model: BearingModel) -> bool:
    """Whether ``model`` is an infinitely wide tape at speed over wrapped arcs
    (:attr:`BearingModel.wrapped_corners`) that it touches at about one point
    (:attr:`BearingModel.touching_arcs`: the grid refined to 25 nm there), each past the
    handover (those ``arc_contact="auto"`` wraps): its Newton solves take the feasible
    contact step and the merit's quadrature weights (:class:`_Residual`). Other wrapped
    arcs keep the primal–dual rule: forced wrapped below the handover, the feasible
    step's path (up to MAX_FEASIBLE_UPDATES factorizations per iteration) took fewer
    Newton iterations but more time (measured, 1 mm land at 2°/2°, 4 m/s: r_c = 1.2 mm
    391 iterations, 24.9 s, against 345, 6.3 s; 1.4 mm 195, 7.4 s, against 335, 7.9 s);
    over the long 10 mm arcs of a 4 mm land at 4°/4° (no corner refinement) at 0.5 m/s it
    reached another steady state (h(0) = 1.53 µm instead of 0.356 µm, both converged:
    the head has two)."""
    if not (model.infinitely_wide and model.wrapped_corners) or model.dry \
            or model.smooth_contact:
        return False
    return (model.touching_arcs == model.wrapped_corners
            == wrapped_corners(model.head, model.bending_length, "auto"))


def _contact_step_rule(model: BearingModel, touching: bool, active_set: bool):
    """The contact-set step of a Newton solve (:func:`newton`): over the wrapped arcs of an
    infinitely wide tape at speed the feasible step (:func:`_feasible_contact_step`);
    else the linearized primal–dual rule from a start that touches (or ``active_set``),
    the forced entry from one clear of the head."""
    if _wrapped_at_speed(model):
        return _feasible_contact_step
    return _contact_set_step if touching or active_set else _forced_contact_step


def _noise_step(F: _Residual, it: _Iterate) -> float:
    """The relative size of the Newton step that the residual's round-off alone produces
    (the rows' round-off :attr:`_Residual.noise_rows` with fixed pseudo-random signs,
    through the step's factorization): the floor below which steps cannot shrink. On a
    grid refined far below the bending length at a corner (the plate's fourth difference
    scales like h⁻⁴) it may lie above the step tolerance. On a 2-D tape once per
    factorization (chord steps near convergence move the rows' round-off by a fraction of
    itself); the infinitely wide tape's banded substitution costs next to nothing, so it
    is formed at every state there."""
    if F.model.infinitely_wide or it.noise_of is not it.solver:
        signs = np.random.default_rng(0).choice((-1.0, 1.0), size=F.noise_rows.size)
        it.noise_step = _norm(it.solver(signs * F.noise_rows), F.model.n_u, F)
        it.noise_of = it.solver
    return it.noise_step


def _record(info: NewtonInfo, step: float, merit: float, contacts: int) -> None:
    """Append one iteration (its step, scaled residual and contact count) to ``info``."""
    info.iterations += 1
    info.step_norms.append(float(step))
    info.residual_norms.append(merit)
    info.contact_nodes.append(contacts)


def _stagnated(merits: list, alphas: list) -> bool:
    """Whether the scaled residual has not halved over STAGNATION_WINDOW damped
    iterations (none reaching STAGNATION_STEP)."""
    return (len(alphas) >= STAGNATION_WINDOW
            and merits[-1] > 0.5 * merits[-1 - STAGNATION_WINDOW]
            and max(alphas[-STAGNATION_WINDOW:]) < STAGNATION_STEP)


def _evaluate(F: _Residual, it: _Iterate, lazy: bool) -> np.ndarray:
    """The residual (``it.res``) at the new iterate ``it.z`` and its contact set by the
    rule (returned); the Jacobian (``it.J``) too unless ``lazy`` (then None: formed when
    it is factored, the round-off estimate updated with the last one's film block)."""
    if lazy:
        it.res, active, it.J = F(it.z, jacobian=False)
        F.update_noise(it.z)
    else:
        it.res, active, it.J = F(it.z, jacobian=True)
    return active


def newton(model: BearingModel, z0: np.ndarray, *, tension: float | None = None,
           transient=None, tol: float = STEP_TOLERANCE,
           max_iterations: int = MAX_ITERATIONS, info: NewtonInfo | None = None,
           log=None, active_set: bool = False):
    """Solve the coupled residual from z0 by semismooth Newton with a backtracking line
    search on the scaled residual norm.

    ``log`` (optional) is called with a one-line message per iteration. ``active_set``:
    update the contact set by the linearized active-set rule even from a start clear of
    the head (a march's retried sub-step, whose start is a neighbouring state).
    ``transient`` (optional) supplies the time-discrete terms of one implicit step: an
    object with ``tape_terms(u) -> (r_extra, J_extra)`` and the film's ``phi_old``, ``dt``.

    Returns (z, λ, active, info): the state, the contact forces (N; zero off contact), the
    contact set and the iteration record. Raises ConvergenceError if Newton fails.
    """
    info = NewtonInfo() if info is None else info
    n_u = model.n_u
    F = _Residual(model, tension, transient)
    it = _Iterate(F, z0)
    # A start that touches the head (a neighbouring state: the infinitely wide tape, a
    # coarser grid, a pseudo-time step) has its contact set grown and shrunk by the
    # linearized active-set rule; a start clear of the head keeps the damped steps with
    # the forced entry of the nodes a step takes below σ (far from the state, e.g. a
    # lifted tape, pseudo-time leads Newton instead).
    contact_step = _contact_step_rule(model, bool(it.active.any()), active_set)
    merits, alphas = [it.merit], []
    # A 2-D tape's chord steps need no Jacobian: it is formed when factored; the
    # infinitely wide tape's (a few thousand unknowns) at every iterate, as it always was.
    lazy = not model.infinitely_wide
    for _ in range(max_iterations):
        h = it.z[:n_u] + model.dry_field[1:-1, :].ravel()
        dz = _newton_direction(F, it)
        if not np.all(np.isfinite(dz)):
            raise ConvergenceError("Newton: non-finite step")
        floor = (ROUND_OFF_MULTIPLE * _noise_step(F, it)
                 if _norm(dz, n_u, F) < ROUND_OFF_STEP else 0.0)
        found = _line_search(F, model, it.z, dz, h, it.active, it.merit, tol, F.noise)
        alpha, step, it.z, _ = contact_step(F, it, h, dz, found, tol)
        it.last_step = step
        active_new = _evaluate(F, it, lazy)
        it.merit = F.merit(it.res)
        contacts = int(active_new.sum())
        _record(info, alpha * step, it.merit, contacts)
        if log is not None:
            log(f"Newton {info.iterations}: step {alpha * step:.2e} (alpha {alpha:.3g}), "
                f"residual {it.merit:.2e}, {contacts} nodes in contact")
        if it.converged(active_new, alpha == 1.0 and step < max(tol, floor)):
            return it.z, F.contact_forces(it.z, it.active), it.active, info
        merits.append(it.merit)
        alphas.append(alpha)
        if _stagnated(merits, alphas):
            raise ConvergenceError(
                f"Newton stagnated (scaled residual {it.merit:.3g}, not halved in "
                f"{STAGNATION_WINDOW} damped iterations)")
    raise ConvergenceError(
        f"Newton did not converge in {max_iterations} iterations "
        f"(last relative step {info.step_norms[-1]:.3g}, scaled residual {it.merit:.3g})")


#: Continuation in V starts this many times faster (a thicker, easier film) ...
CONTINUATION_START = 4.0
#: ... and comes down by this factor per stage.
CONTINUATION_FACTOR = 0.7


def solve_steady(model: BearingModel, *, z0: np.ndarray | None = None,
                 tension: float | None = None, progress=None,
                 iteration_log=None) -> BearingSolution:
    """The steady flying state of ``model``.

    Newton starts from ``z0`` (default :func:`initial_state`). If it fails
    (no convergence, or stagnation: the start is outside Newton's basin, typically when
    part of the tape must come down onto the head), pseudo-transient continuation marches
    the state towards the steady one in growing pseudo-time steps, and if that fails too,
    continuation in V brings it down from a faster, thicker film (each stage by Newton,
    then by pseudo-time).

    Parameters
    ----------
    model : BearingModel
    z0 : numpy.ndarray, optional
        Start [u (m), p (Pa)], e.g. a neighbouring solution.
    tension : float, optional
        Tension T, N/m, in place of the model's (continuation in T).
    progress : callable, optional
        Called with a one-line message per stage: the coarse-grid start of a 2-D tape,
        Newton giving way to the pseudo-time march, each pseudo-time step and each
        continuation stage. False, like None, reports nothing.
    iteration_log : callable, optional
        Called with a one-line message per Newton iteration (those of the coarse-grid
        start too).

    Raises
    ------
    ParameterError
        If an argument is of the wrong type, shape or range (checked before any work).
    ConvergenceError
        If neither Newton, the pseudo-time march nor the continuation reaches the state.
    """
    progress = None if progress is False else progress  # False: no progress, as elsewhere
    tension, z0 = check_steady_arguments(model, z0, tension, progress, iteration_log)
    if model.smooth_contact:      # asperities or a measured curve: see .smooth
        from .smooth import solve_smooth

        return solve_smooth(model, z0, tension, progress, iteration_log)
    if model.adapt_contacts and model.corner_contacts:   # rounded corners: see .corners
        from .corners import solve_adapting_contacts

        return solve_adapting_contacts(
            model, solve_steady, z0=z0, tension=tension, progress=progress,
            iteration_log=iteration_log,
            coarse_start=None if tension is not None else _rounded_coarse_start(
                COARSE_START_MIN_UNKNOWNS, progress, iteration_log))
    start = time.perf_counter()
    info = NewtonInfo()
    if z0 is None:
        z0 = initial_state(model, progress=progress, iteration_log=iteration_log)
    try:
        z, lam, info = _newton_or_pseudo_time(model, z0, tension, info, progress,
                                              iteration_log)
    except ConvergenceError:
        if progress is not None:
            progress("pseudo-time did not reach the state: continuation in V")
        z, lam, info = _continuation(model, tension, progress, iteration_log)
    info.seconds = time.perf_counter() - start
    check_cavitation(model, z[model.n_u:])
    return BearingSolution(model, z[:model.n_u], z[model.n_u:], lam, info)


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


def check_steady_arguments(model, z0, tension, progress, iteration_log):
    """(tension, z0) of :func:`solve_steady`, checked: ``model`` a BearingModel, ``z0`` None
    or a finite vector of ``model.unknowns`` with positive pressures (compressible film),
    ``tension`` None or > ρV² (N/m, the tape must wrap), the callbacks None or callable."""
    validation.instance("model", model, BearingModel)
    if tension is not None:
        tension = validation.positive("tension", tension, "N/m")
        floor = model.params.density * model.velocity**2
        if not tension > floor:
            raise ParameterError(
                f"tension must be > rho V^2 = {floor:.6g} N/m at {model.velocity:g} m/s "
                f"(the tape would not wrap), got {tension:g}")
    for name, hook in (("progress", progress), ("iteration_log", iteration_log)):
        if hook is not None and not callable(hook):
            raise ParameterError(f"{name} must be None or a callable taking one message, "
                                 f"got {type(hook).__name__}")
    if z0 is not None:
        z0 = validation.vector("z0", z0, model.unknowns, "m and Pa")
        if model.air.compressible and not np.all(z0[model.n_u:] > 0.0):
            raise ParameterError("z0 must have pressures > 0 Pa (entries n_u: of [u, p]) "
                                 "for a compressible film")
    return tension, z0


# ----- the start of Newton -----------------------------------------------------------------
#: A 2-D tape with at least this many unknowns starts Newton from its solution on a grid
#: twice as coarse (recursively), interpolated; smaller ones from the infinitely wide tape ...
COARSE_START_MIN_UNKNOWNS = 20_000
#: An infinitely wide tape over a flat or profile head with more than this many
#: x-intervals starts from its solution on the grid twice as coarse (recursively): the
#: corner-start (:meth:`BearingModel.initial_state`) leads Newton there in a few
#: iterations only on coarse grids.
COARSE_START_MIN_NX = 4000
#: ... unless that grid would be coarser than this at the edges (m): an under-resolved
#: free-edge row falsely touches down and the coarse solve would lead Newton astray.
COARSE_START_MAX_Y_SPACING = 110e-6


def initial_state(model: BearingModel, *,
                  coarse_min_unknowns: int = COARSE_START_MIN_UNKNOWNS, progress=None,
                  iteration_log=None) -> np.ndarray:
    """A start [u (m), p (Pa)] for Newton. Infinitely wide: the flexible-foil spacing and
    the wrap pressure (:meth:`BearingModel.initial_state`). 2-D: the steady state on a grid
    twice as coarse, interpolated, when the model is large enough (:func:`_coarse_state`);
    else the infinitely wide tape's solution on the same x-grid, extruded across the width
    (one cheap 1-D solve saves several 2-D Newton iterations).

    ``coarse_min_unknowns``: the fewest unknowns of a 2-D model started from the coarse
    grid (default :data:`COARSE_START_MIN_UNKNOWNS`). ``progress`` and ``iteration_log``
    (optional) get one line per start solved and per Newton iteration, as in
    :func:`solve_steady`."""
    if model.infinitely_wide:
        z = None
        if (not model.cylindrical and not model.dry and model.nx > COARSE_START_MIN_NX
                and not model.corner_contacts):
            z = _coarse_state(model, coarse_min_unknowns, progress, iteration_log)
        if z is None and _dry_retry(model) and _flying_start_degenerate(model):
            try:
                z = _continuation_from_dry(model, None, NewtonInfo(), progress,
                                           iteration_log)[0]
            except ConvergenceError:
                z = None
        return model.initial_state() if z is None else z
    # rounded corners with fixed contacts (a pass of corners.solve_adapting_contacts): the
    # extruded strip; the adaptation itself starts a large 2-D model from the coarse grid
    # with its contacts adapted there (coarse_solution), whose contacts differ
    z = (_coarse_state(model, coarse_min_unknowns, progress, iteration_log)
         if model.unknowns >= coarse_min_unknowns and not model.corner_contacts else None)
    return _extruded_strip_state(model, progress, iteration_log) if z is None else z


#: Over a flat or profile head (infinitely wide tape) a flying start whose land spacing
#: (:attr:`BearingModel.flying_start_spacing`) is below this many roughnesses σ leads
#: Newton nowhere: the land lies at σ with no contact force, a tie the contact rule
#: cannot decide. The continuation up from the dry tape starts Newton instead. Measured
#: (3 mm land, 4°/4°, Table 1 tape): the flying start at 1.45 σ (1 m/s) and below
#: stagnates, at 1.9 σ (1.5 m/s) it converges in 14 iterations.
FLYING_START_MIN_ROUGHNESS = 1.5


def _flying_start_degenerate(model: BearingModel) -> bool:
    """Whether the flying start of ``model`` (a flat or profile head, at speed) lies within
    FLYING_START_MIN_ROUGHNESS σ of the land: the infinitely wide tape then starts from
    the continuation up from the dry tape, and a 2-D tape that Newton cannot bring to its
    state takes that continuation before pseudo-time."""
    return (not (model.cylindrical or model.dry) and model.flying_start_spacing
            < FLYING_START_MIN_ROUGHNESS * model.air.roughness)


def _coarse_state(model: BearingModel, coarse_min_unknowns: int, progress=None,
                  iteration_log=None) -> np.ndarray | None:
    """The steady state on the grid twice as coarse in x and y, interpolated
    (bilinearly) onto the model's grid; None if that grid would be too coarse or neither
    Newton nor the pseudo-time march reaches the state there (:func:`coarse_solution`).
    Most of Newton's iterations move the free edges down from the infinitely wide start;
    on the coarse grid they cost a fraction of a fine-grid factorization."""
    sol = coarse_solution(model, coarse_min_unknowns, progress, iteration_log)
    return None if sol is None else interpolated_state(model, sol)


def coarse_solution(model: BearingModel, coarse_min_unknowns: int = COARSE_START_MIN_UNKNOWNS,
                    progress=None, iteration_log=None) -> BearingSolution | None:
    """The steady state on the grid twice as coarse in x and y (the same mapping); None
    if that grid would be too coarse or its solve fails. The coarse grid starts from its
    own :func:`initial_state` (with ``coarse_min_unknowns``): Newton, then pseudo-time
    (no continuation in V). With rounded corners (``model.adapt_contacts``) the coarse
    grid adapts its own contacts (:func:`~.corners.solve_adapting_contacts`, itself
    started from the grid twice as coarse again): the solution's model holds them, the
    start of the fine grid's contacts."""
    nx = model.nx // 2 + (model.nx // 2) % 2
    ny = None if model.infinitely_wide else model.ny // 2 + (model.ny // 2) % 2
    if (ny is not None and ny < MIN_INTERVALS_ACROSS) or nx < MIN_INTERVALS_ALONG:
        return None
    try:
        coarse = _quiet_model(model, nx, ny)
    except ParameterError:     # too coarse for the film: no coarse start
        return None
    if ny is not None and coarse.y[1] - coarse.y[0] > COARSE_START_MAX_Y_SPACING:
        return None
    if coarse.corner_contacts and model.adapt_contacts:
        from .corners import solve_adapting_contacts

        if progress is not None:
            progress(f"start: solving the coarse grid {nx} x {ny} ({coarse.unknowns} "
                     "unknowns), its rounded corners' contacts adapted")
        try:
            return solve_adapting_contacts(
                coarse, _coarse_newton, progress=progress, iteration_log=iteration_log,
                coarse_start=_rounded_coarse_start(coarse_min_unknowns, progress,
                                                   iteration_log))
        except ConvergenceError:
            return None
    try:   # Newton, then pseudo-time (no continuation in V): cheap on a coarse grid
        start = initial_state(coarse, coarse_min_unknowns=coarse_min_unknowns,
                              progress=progress, iteration_log=iteration_log)
        if progress is not None:
            progress(f"start: solving the coarse grid {nx} x {ny} ({coarse.unknowns} "
                     "unknowns)")
        z, lam, info = _newton_or_pseudo_time(coarse, start, None, NewtonInfo(), progress,
                                              iteration_log)
    except ConvergenceError:
        return None
    return BearingSolution(coarse, z[:coarse.n_u], z[coarse.n_u:], lam, info)


def _rounded_coarse_start(coarse_min_unknowns: int, progress, iteration_log):
    """The coarse start of a 2-D tape over rounded corners, for
    :func:`~.corners.solve_adapting_contacts`: a callable taking the model and returning
    (the contacts of its :func:`coarse_solution`, adapted there; a callable giving that
    solution :func:`interpolated_state` onto a model's grid), or None when the model is
    infinitely wide, has fewer than ``coarse_min_unknowns`` unknowns or the coarse solve
    fails."""
    def start(model: BearingModel):
        if model.infinitely_wide or model.unknowns < coarse_min_unknowns:
            return None
        sol = coarse_solution(model, coarse_min_unknowns, progress, iteration_log)
        if sol is None:
            return None
        return sol.model.corner_contacts, lambda fine: interpolated_state(fine, sol)
    return start


def _coarse_newton(model: BearingModel, *, z0=None, progress=None,
                   iteration_log=None) -> BearingSolution:
    """One fixed-contact pass of a coarse start (:func:`coarse_solution`): Newton, then
    pseudo-time, from ``z0`` or the model's :func:`initial_state`; no continuation."""
    if z0 is None:
        z0 = initial_state(model, progress=progress, iteration_log=iteration_log)
    z, lam, info = _newton_or_pseudo_time(model, z0, None, NewtonInfo(), progress,
                                          iteration_log)
    return BearingSolution(model, z[:model.n_u], z[model.n_u:], lam, info)


def interpolated_state(model: BearingModel, sol: BearingSolution) -> np.ndarray:
    """The state [u, p] of ``sol`` (on its own model's grid, of the same mapping)
    interpolated (bilinearly) onto ``model``'s grid.

    Over rounded corners the tape's height w = z₀ + u is interpolated, not u: the dry
    string z₀ follows each arc (curvature 1/r_c) over a cell or two between nodes, which
    the tape does not (it touches the arc at one point), so u is curved by 1/r_c there and
    the plate's fourth difference on the corners' fine cells turns its interpolation error
    into a residual that led Newton astray (measured: scaled residual 7e12, 90
    iterations), while w is smooth. Elsewhere u is interpolated: the tape follows the
    curvature of z₀ where it has any (a cylinder's wrap, 1/R: interpolating w there costs
    the coarse start of a 3 mm tape 24 Newton iterations instead of 11, measured), and over
    sharp corners (z₀ piecewise linear, its kinks on both grids' nodes) the two agree."""
    coarse = sol.model

    def tape_height(m: BearingModel) -> np.ndarray:
        if not m.corner_contacts:
            return np.zeros((m.nx + 1, 1))
        return m.head.dry_tape(m.x_head, m.head_radius)[:, None]

    w = sol.spacing - coarse.dry_field + tape_height(coarse)
    if model.infinitely_wide:
        u = (np.interp(model.x, coarse.x, w[:, 0]) - tape_height(model)[:, 0])[1:-1]
        p = np.interp(model.x, coarse.x, sol.pressure[:, 0])[1:-1]
        return np.concatenate([u, p])
    along, across = _linear_weights(coarse.x, model.x), _linear_weights(coarse.y, model.y)
    fields = [along @ (across @ f.T).T for f in (w, sol.pressure)]
    u = (fields[0] - tape_height(model))[1:-1, :].ravel()
    return np.concatenate([u, fields[1][model.film.interior]])


def _linear_weights(nodes: np.ndarray, points: np.ndarray) -> sp.csr_matrix:
    """The matrix of piecewise-linear interpolation from ``nodes`` (increasing) to
    ``points`` (within their range): a tensor product of two gives the bilinear
    interpolant on a grid."""
    k = np.clip(np.searchsorted(nodes, points, side="right") - 1, 0, len(nodes) - 2)
    t = np.clip((points - nodes[k]) / (nodes[k + 1] - nodes[k]), 0.0, 1.0)
    rows = np.arange(len(points))
    return sp.csr_matrix((np.concatenate([1.0 - t, t]),
                          (np.concatenate([rows, rows]), np.concatenate([k, k + 1]))),
                         shape=(len(points), len(nodes)))


def _quiet_model(model: BearingModel, nx: int, ny: int) -> BearingModel:
    """``model`` on nx × ny intervals (the same mapping), without the coarse-edge warning:
    a start only needs to lead Newton, not to be accurate."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        return model.rebuilt(nx=nx, ny=ny)


def _extruded_strip_state(model: BearingModel, progress=None,
                          iteration_log=None) -> np.ndarray:
    """The infinitely wide tape's steady state on the model's x-grid (its flexible-foil
    start if Newton fails there), repeated across the width."""
    strip = model.rebuilt(infinitely_wide=True, ny=None)
    if progress is not None:
        progress(f"start: solving the infinitely wide tape on the same x-grid "
                 f"({strip.unknowns} unknowns)")
    try:
        sol = solve_steady(strip, iteration_log=iteration_log)
    except ConvergenceError:
        z = strip.initial_state()
        u1, p1 = z[:strip.n_u], z[strip.n_u:]
    else:
        u1, p1 = sol.u, sol.p
    u = np.repeat(u1, model.nc)
    P = np.repeat(strip.pressure_field(p1), model.nc, axis=1)
    return np.concatenate([u, P[model.film.interior]])


#: Pseudo-time continuation: first step (pseudo-time terms 1/s of each row's diagonal) ...
PSEUDO_START = 0.1
#: ... grown by this factor after an easy step (few Newton iterations) ...
PSEUDO_GROWTH = 4.0
#: ... cut by this factor after a failed one ...
PSEUDO_CUT = 4.0
#: ... and plain Newton is tried once the step exceeds this (and, if it fails, again
#: after the step has grown by PSEUDO_FINISH_RETRY).
PSEUDO_FINISH = 1e4
PSEUDO_FINISH_RETRY = 100.0
#: Pseudo-time steps at most, Newton iterations per step, and the step's tolerance.
PSEUDO_MAX_STEPS = 60
PSEUDO_NEWTON = 12
PSEUDO_TOLERANCE = 1e-4


class _PseudoTime:
    """Backward-Euler pseudo-time terms of pseudo-transient continuation with local steps:
    each row gains its own diagonal over s (s the pseudo-time step, dimensionless). The
    tape rows gain (c/s)(u − u_old) (c = diag K); the film rows the squeeze term
    12μ A ∂(ph)/∂t with a local step Δt_i chosen so that its p-derivative is |∂r_i/∂p_i|/s
    (compressible: Δt_i = 12μ A_i h_i s/|J_ii|; incompressible: Δt = s ℓ_film/V). Local
    steps let a thin-gap region, whose film responds slowly, relax as fast as the rest.
    Far from the steady state they keep each step inside Newton's basin; as s grows they
    vanish and the steady equations remain."""

    def __init__(self, model: BearingModel, z: np.ndarray, s: float, transit: float) -> None:
        n_u = model.n_u
        u, p = z[:n_u], z[n_u:]
        self.c = model.stiffness_diagonal / s
        self.u_old = u.copy()
        P, H = model.pressure_field(p), model.spacing_field(u)
        self.phi_old = model.film.transported(P, H)
        if model.air.compressible:
            _, J_pp, _ = model.film_residual(u, p, jacobian=True)
            film = model.film
            self.dt = (s * 12.0 * model.air.viscosity * film.cell_area[film.interior]
                       * H[film.interior] / np.maximum(np.abs(J_pp.diagonal()), 1e-300))
        else:
            self.dt = s * transit
        self.jacobian = sp.diags(self.c).tocsr()

    def tape_terms(self, u):
        return self.c * (u - self.u_old), self.jacobian


def _newton_or_pseudo_time(model, z0, tension, info, progress, iteration_log):
    """Newton from z0; over a flat or profile head of an infinitely wide tape, if it fails,
    Newton from the dry tape (:meth:`BearingModel.dry_start`: at low speeds the film
    barely pulls the tape below its dry tents), then the continuation in V up from the
    dry tape (:func:`_continuation_from_dry`; also for a 2-D tape whose flying start is
    degenerate, :func:`_flying_start_degenerate`); if that fails, pseudo-transient
    continuation from z0."""
    up = _dry_retry(model) or (not model.infinitely_wide and _flying_start_degenerate(model))
    try:
        z, lam, _, info = newton(model, z0, tension=tension, info=info, log=iteration_log)
        return z, lam, info
    except ConvergenceError as exc:
        if progress is not None:
            progress(f"{exc}: " + ("Newton from the dry tape" if _dry_retry(model) else
                                   "continuation in V up from the dry tape" if up else
                                   "pseudo-time continuation"))
    if _dry_retry(model):
        try:
            z, lam, _, info = newton(model, model.dry_start(), tension=tension, info=info,
                                     log=iteration_log)
            return z, lam, info
        except ConvergenceError as exc:
            if progress is not None:
                progress(f"{exc}: continuation in V up from the dry tape")
    if up:
        try:
            return _continuation_from_dry(model, tension, info, progress, iteration_log)
        except ConvergenceError as exc:
            if progress is not None:
                progress(f"{exc}: pseudo-time continuation")
    return pseudo_transient(model, z0, tension=tension, info=info, progress=progress,
                            iteration_log=iteration_log)


def _dry_retry(model: BearingModel) -> bool:
    """Whether Newton gets a second start from the dry tape (infinitely wide, flat or
    profile head, at speed)."""
    return model.infinitely_wide and not (model.cylindrical or model.dry)


#: Continuation in V up from the dry tape (V -> 0 is the dry limit): the first stage
#: runs at this fraction of the target speed, started from the dry tape ...
DRY_CONTINUATION_START = 0.1
#: ... and each next one this many times faster, up to the target. Measured (3 mm land,
#: 4°/4°, Table 1 tape, 1-D, on the 0.3 m/s grid): Newton from the dry tape converges in
#: 4-6 iterations at 1-100 mm/s and stagnates at 0.3 m/s; stages 1.25 apart take 5-8
#: iterations each from 0.1 to 1.2 m/s, stages 1.5 apart fail near 0.76 and 1 m/s.
DRY_CONTINUATION_FACTOR = 1.25
#: Newton iterations per stage at most (a stage starts next to its state: one that needs
#: more has left the branch and is retried halfway) ...
DRY_STAGE_ITERATIONS = 15
#: ... and a stage that fails is retried halfway at most this many times in a row ...
DRY_CONTINUATION_HALVINGS = 4
#: ... and only while halfway is at least this ratio above the last speed reached: else
#: the stages creep up to a speed they cannot pass (each success there restarts the
#: halvings). Measured (wrapped r_c = 1.2 mm arcs on a 1 mm land at 2°/2°, 4 m/s):
#: without it the stages crept from 0.4742 to 0.4749 m/s, 0.0004 apart, 460 Newton
#: iterations before pseudo-time took over.
DRY_CONTINUATION_MIN_RATIO = 1.01


def _dry_continuation_speeds(velocity: float) -> list[float]:
    """The speeds of the continuation up from the dry tape, m/s: geometric from
    DRY_CONTINUATION_START times ``velocity`` to ``velocity`` (same sign), at most
    DRY_CONTINUATION_FACTOR apart."""
    stages = math.ceil(math.log(1.0 / DRY_CONTINUATION_START)
                       / math.log(DRY_CONTINUATION_FACTOR) - 1e-9)
    ratio = (1.0 / DRY_CONTINUATION_START) ** (1.0 / stages)
    return [velocity * DRY_CONTINUATION_START * ratio**k for k in range(stages)] + [velocity]


def _continuation_from_dry(model: BearingModel, tension, info: NewtonInfo, progress,
                           iteration_log):
    """Continuation in V up from the dry tape to ``model``'s speed on its grid: the first
    stage by Newton from the dry tape (:meth:`BearingModel.dry_start`; a 2-D tape from its
    :func:`initial_state` there, the infinitely wide tape's state extruded), each next one
    from the last; a stage that fails is retried halfway (geometrically) from the last
    speed reached, at most DRY_CONTINUATION_HALVINGS times in a row. At low speeds over a long
    land this reaches the state that Newton from a flying start cannot: the tape tents
    over the land much as it does dry (7.0-9.9 um at the middle of a 3 mm land at 4°/4°,
    0.3-1 m/s, against 6.6 um dry). Returns (z, λ, info); raises ConvergenceError if a
    stage fails after its halvings."""
    targets = _dry_continuation_speeds(model.velocity)
    z, reached, lam, halvings = None, [], None, 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        while targets:
            v = targets[0]
            stage = model if v == model.velocity else model.at_velocity(v)
            if progress is not None:
                progress(f"continuation from the dry tape: V = {v:.4g} m/s")
            try:
                start = (z if z is not None else stage.dry_start() if stage.infinitely_wide
                         else initial_state(stage, progress=progress,
                                            iteration_log=iteration_log))
                z1, lam, _, info = newton(stage, start,
                                          tension=tension, info=info, log=iteration_log,
                                          max_iterations=DRY_STAGE_ITERATIONS)
            except ConvergenceError:
                if z is None or halvings == DRY_CONTINUATION_HALVINGS:
                    raise
                mid = math.sqrt(reached[-1] * abs(v))
                if mid < DRY_CONTINUATION_MIN_RATIO * reached[-1]:
                    raise
                halvings += 1
                targets.insert(0, math.copysign(mid, v))
                continue
            z, halvings = z1, 0
            reached.append(abs(targets.pop(0)))
    info.continuation = [math.copysign(v, model.velocity) for v in reached]
    return z, lam, info


def pseudo_transient(model: BearingModel, z0: np.ndarray, *, tension: float | None = None,
                     info: NewtonInfo | None = None, progress=None, iteration_log=None):
    """Pseudo-transient continuation (switched evolution) from z0 to the steady state.

    Each pseudo-time step s (:class:`_PseudoTime`) is solved by Newton; s grows by
    PSEUDO_GROWTH while Newton converges quickly within it, by 1.5 otherwise, and is cut
    by PSEUDO_CUT when it fails. Once s exceeds PSEUDO_FINISH plain Newton finishes (if it
    fails there, the march goes on and tries again 100 times further).

    Returns (z, λ, info). Raises ConvergenceError if the march does not get there.
    """
    info = NewtonInfo() if info is None else info
    transit = 1.0 if model.dry else model.film_length / abs(model.velocity)
    z, s, finish = np.array(z0, dtype=float), PSEUDO_START, PSEUDO_FINISH
    for _ in range(PSEUDO_MAX_STEPS):
        if s >= finish:
            try:
                z, lam, _, info = newton(model, z, tension=tension, info=info,
                                         log=iteration_log)
                return z, lam, info
            except ConvergenceError:   # slow modes still relaxing: march on
                finish *= PSEUDO_FINISH_RETRY
        before = info.iterations
        try:
            z, _, _, info = newton(model, z, tension=tension,
                                   transient=_PseudoTime(model, z, s, transit),
                                   tol=PSEUDO_TOLERANCE, max_iterations=PSEUDO_NEWTON,
                                   info=info, log=iteration_log)
        except ConvergenceError:
            s /= PSEUDO_CUT
            if s < PSEUDO_START / PSEUDO_CUT**4:
                break
            continue
        info.pseudo_time.append(s)
        if progress is not None:
            progress(f"pseudo-time step {s:.3g}: {info.iterations - before} Newton iterations")
        s *= PSEUDO_GROWTH if info.iterations - before <= PSEUDO_NEWTON // 2 else 1.5
    raise ConvergenceError("pseudo-time continuation did not reach the steady state")


def _continuation_stages(model: BearingModel) -> list[BearingModel]:
    """The models of the continuation in V, from CONTINUATION_START times faster down to
    ``model`` itself; speeds at which the model cannot be built (above the string speed,
    or a film too long for the given span) are left out."""
    speeds, v = [], model.velocity * CONTINUATION_START
    while abs(v) > abs(model.velocity):      # either direction: |V| comes down
        speeds.append(v)
        v *= CONTINUATION_FACTOR
    stages = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        for v in speeds:
            try:
                stages.append(model.at_velocity(v))
            except ParameterError:
                continue
    return [*stages, model]


def _continuation(model: BearingModel, tension, progress, iteration_log):
    stages = _continuation_stages(model)
    info = NewtonInfo(continuation=[stage.velocity for stage in stages])
    z = None
    for stage in stages:
        if progress is not None:
            progress(f"continuation: V = {stage.velocity:.4g} m/s")
        z0 = (initial_state(stage, progress=progress, iteration_log=iteration_log)
              if z is None else z)
        z, lam, info = _newton_or_pseudo_time(stage, z0, tension, info, progress,
                                              iteration_log)
    return z, lam, info
