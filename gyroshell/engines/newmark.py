"""Newmark time marching of M a + (G + C) v + K w = F(t), displacement form (paper Eqs. 10-16).

Each step: predictors (Eqs. 10-11)

    w̃ = wⁿ + Δt vⁿ + (½ − β) Δt² aⁿ,        ṽ = vⁿ + (1 − γ) Δt aⁿ,

one solve K_eq wⁿ⁺¹ = f_eq (Eqs. 12, 15-16) with the matrix factored once,

    K_eq = M + γΔt (G + C) + βΔt² K,
    f_eq = βΔt² F(tⁿ⁺¹) + M w̃ + (G + C)(γΔt w̃ − βΔt² ṽ),

and correctors (Eqs. 13-14) aⁿ⁺¹ = (wⁿ⁺¹ − w̃)/(βΔt²), vⁿ⁺¹ = ṽ + γΔt aⁿ⁺¹.

β = 1/4, γ = 1/2 (the default) is the trapezoidal rule: unconditionally stable, no
algorithmic damping. With G skew, C the (optional) damping matrix and a constant force, the
energy E = ½vᵀMv + ½wᵀKw − Fᵀw then changes by exactly −Δt v̄ᵀC v̄ per step, v̄ the mean of
the step's two velocities: conserved without damping, decreasing with it. β = 1, γ = 3/2
damps strongly and brings a transient to its static equilibrium with large steps (the
paper's "t = ∞" pictures).

F(t) is either f(t) F (a fixed force with a time profile, by default the nodal forces of
the model's Gaussian pressure switched on at t = 0) or moving heads
(:mod:`gyroshell.tape.moving_loads`). A :class:`Newmark` object holds the factorizations for
one (V, Δt, β, γ, C) and can march any number of runs with them; :func:`march` is the
one-call form.

Mirror symmetry. When the tape is mirror symmetric about y = L_y/2
(:func:`gyroshell.tape.mirror.mirror_split`: A, B, M and G checked on the assembled
operators), and so are the damping C, the force (‖R F − F‖ ≤ 10⁻¹⁴ ‖F‖; a moving head
only with its centre on the centre line at every step and an even shape across the width)
and the initial state w⁰, v⁰, the answer stays symmetric: w = P_s z with z on the symmetric
half. The march then solves M_s a + (G_s + C_s) v + K_s z = P_sᵀ F, with the half's
matrices X_s = P_sᵀ X P_s and their own K_eq factored once, and expands what it records
(history, snapshots, centre lines, the final state) to the full field; the energy of the
half, ½v_sᵀM_s v_s + ½zᵀK_s z − (P_sᵀF)ᵀz, is that of the full field because P_s has
orthonormal columns. The result equals a full march to round-off and says which was used
(``info["symmetry"]``: "half" or "full"); ``symmetry=False`` always marches all the
unknowns. Nothing is assumed: any asymmetric input gives the full march. The half's K_eq
has less than a third of the full factor's entries (1.13 M against 3.62 M on L_x/L_y = 19),
so a half-size step measured 0.38x a bare full-size substitution there and 0.49x on the
Table 1 grid (``benchmarks/bench_newmark.py``, alternating rounds in one run; a full-size
step is 1.1-1.6x).

Ordering. K_eq is factored in its natural (grid) order when the band is narrow, as on the
symmetric half of the paper's grid, and by SuperLU in minimum-degree order otherwise
(:mod:`gyroshell.linalg.ordering`). With ``backend="auto"`` the narrow band's LU (diagonal
pivots while they are stable) is solved by two BLAS band substitutions
(:class:`gyroshell.linalg.factorization.BandLU`): a third of SuperLU's natural-order
substitution on the L_x/L_y = 19 half; a half-size step there measured 0.12x a bare
full-size substitution (``benchmarks/bench_newmark.py``, load 3-5).

Shared factorizations. Inside ``with sharing_factorizations():`` every :class:`Newmark`
for the same tape (equal parameters and grid) at the same (V, Δt, β, γ, C, back-end) uses
one factorization of each K_eq (full or half), made by the first that needs it and dropped
when the outermost block ends; outside such a block nothing is kept between objects.
"""

from __future__ import annotations

import contextvars
import math
import time
import warnings
from collections.abc import Callable, Hashable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import asdict

import numpy as np
import scipy.sparse as sp

from ..core import budget, validation
from ..core.context import outermost
from ..core.errors import ConvergenceError, ParameterError
from ..core.parallel import blas_threads as limit_blas_threads
from ..core.progress import LongWork
from ..linalg.factorization import resolve_backend
from ..linalg.ordering import factorize_banded
from ..results.transient import Recorder, TransientResult
from ..tape.damping import Damping, as_damping
from ..tape.loads import TimeProfile, step
from ..tape.mirror import SymmetricHalf, mirror_split
from ..tape.model import MODEL_MEMBERS, TapeModel, check_model
from ..tape.moving_loads import MovingLoad, PreparedLoads, as_loads, check_contact_steps
from ..tape.parameters import check_velocity

#: The run stops when ‖w‖₂ grows past this many times its natural scale.
BLOWUP_FACTOR = 1e8
#: Runs of at least this many steps are timed on a few trial steps before their per-step
#: arrays are allocated (shorter runs on their own first steps), so that a run beyond the
#: time limit (:func:`gyroshell.core.progress.time_limit`) is refused at once.
TRIAL_FROM_STEPS = 100_000
#: Timed trial steps (after one warm-up step).
TRIAL_STEPS = 8


class NewmarkStabilityWarning(UserWarning):
    """β, γ outside the unconditionally stable region 2β ≥ γ ≥ ½."""


def check_steps(steps: int, name: str = "steps") -> int:
    """Validate a number of time steps (an integer >= 1)."""
    return validation.integer(name, steps, low=1)


def check_force(force, size: int, name: str = "force", unit: str = "N") -> np.ndarray:
    """Validate a vector over the unknowns (a nodal force in N by default): finite, shape
    (size,); returns a new float array."""
    return validation.vector(name, force, size, unit)


class SharedFactorizations:
    """The factorizations of K_eq kept for one :func:`sharing_factorizations` block.

    Keyed by the tape (a :class:`TapeModel` by its parameters and grid, so that equal
    models share; any other model object, subclasses included, by its identity, kept alive
    by the entry), V, Δt, β, γ, C, the back-end and the unknowns marched (all, or the
    symmetric half).

    Attributes
    ----------
    factorizations : int
        Factorizations made in the block.
    reuses : int
        Times a Newmark object was given one made before.
    """

    def __init__(self) -> None:
        self._factors: dict[Hashable, tuple] = {}
        self.factorizations = 0
        self.reuses = 0

    def __len__(self) -> int:
        return len(self._factors)

    def __repr__(self) -> str:
        return (f"SharedFactorizations({len(self)} kept, {self.factorizations} made, "
                f"{self.reuses} reused)")

    def factor(self, key: Hashable, keep_alive: object, build: Callable[[], object]
               ) -> tuple[object, bool]:
        """(the factorization under ``key``, whether it was made before); ``build()`` makes
        it the first time (``keep_alive`` is held with it)."""
        if key in self._factors:
            self.reuses += 1
            return self._factors[key][0], True
        factor = build()
        self._factors[key] = (factor, keep_alive)
        self.factorizations += 1
        return factor, False

    def clear(self) -> None:
        """Drop every kept factorization."""
        self._factors.clear()


_SHARING: contextvars.ContextVar[SharedFactorizations | None] = contextvars.ContextVar(
    "gyroshell_shared_factorizations", default=None)


@contextmanager
def sharing_factorizations() -> Iterator[SharedFactorizations]:
    """A block in which Newmark objects of the same tape and (V, Δt, β, γ, C, back-end)
    share their factorizations of K_eq.

    The first :class:`Newmark` that needs a K_eq (full or half) factors it; every later one
    in the block with equal settings uses that factor (``info["factor_shared"]`` is then
    True and ``info["factorizations"]`` does not grow). A nested block is the outer one;
    the factors are dropped when the outermost block ends. The sharing follows the context
    (:mod:`contextvars`): other threads and worker processes do not see it.

    Yields
    ------
    SharedFactorizations
        The block's factors, with counts of those made and reused.

    Examples
    --------
    >>> from gyroshell import TapeModel, TapeParameters
    >>> model = TapeModel(TapeParameters(spacing=6.35e-3 / 8))
    >>> with sharing_factorizations() as shared:
    ...     a = march(model, 10.0, dt=2e-6, steps=5)
    ...     b = march(model, 10.0, dt=2e-6, steps=9)
    >>> shared.factorizations, shared.reuses, b.info["factor_shared"]
    (1, 1, True)
    """
    with outermost(_SHARING, SharedFactorizations) as (shared, owner):
        try:
            yield shared
        finally:
            if owner:
                shared.clear()


def _model_key(model: TapeModel) -> tuple[Hashable, object]:
    """(the sharing key of a tape, what the key needs kept alive): a TapeModel's operators
    are those of its parameters and grid; any other model (a subclass may hold more) is
    itself."""
    if type(model) is TapeModel:
        try:
            key = ("tape", model.params, model.grid)
            hash(key)
            return key, None
        except TypeError:
            pass
    return ("object", id(model)), model


class _FixedForce:
    """F(t) = f(t) F at the instants of one run, with the load-point interpolation row."""

    heads = 1

    def __init__(self, force: np.ndarray, profile: TimeProfile, row: np.ndarray,
                 times: np.ndarray) -> None:
        if not callable(profile):
            raise ParameterError("profile must be callable: f(t) with t in s")
        self.force, self.profile, self.row, self.times = force, profile, row, times
        self._tmp = np.empty_like(force)
        # r @ w through the row's few non-zeros: no BLAS call (no BLAS threads) per step
        self._idx = np.flatnonzero(row)
        self._wts = row[self._idx]

    def on_half(self, half: SymmetricHalf) -> _FixedForce:
        """The same forcing on the symmetric half's unknowns z: P_sᵀ F, and the row P_sᵀ r
        (r·w = r·P_s z)."""
        return _FixedForce(half.restrict(self.force), self.profile, half.restrict(self.row),
                           self.times)

    def factor(self, n: int) -> float:
        f = float(self.profile(float(self.times[n])))
        if not math.isfinite(f):
            raise ParameterError(f"profile must return finite values, got {f} at "
                                 f"t = {self.times[n]:g} s")
        return f

    def add(self, n: int, scale: float, out: np.ndarray) -> None:
        f = self.factor(n)
        if f != 0.0:
            np.multiply(self.force, scale * f, out=self._tmp)
            out += self._tmp

    def vector(self, n: int) -> np.ndarray:
        return self.factor(n) * self.force

    def displacement(self, n: int, w: np.ndarray, out: np.ndarray) -> None:
        out[0] = w[self._idx] @ self._wts


class _Operators:
    """The matrices of the unknowns one march moves (all, or the symmetric half ``half``)
    and the factor of their K_eq."""

    def __init__(self, K, damped_gyroscopic, C, m: np.ndarray, factor, shared: bool,
                 half: SymmetricHalf | None) -> None:
        self.K, self.damped_gyroscopic, self.C, self.m = K, damped_gyroscopic, C, m
        self.factor, self.shared, self.half = factor, shared, half

    @property
    def unknowns(self) -> int:
        return len(self.m)

    def initial_acceleration(self, w, v, force0) -> np.ndarray:
        return (force0 - self.K @ w - self.damped_gyroscopic @ v) / self.m

    def energy(self, w, v, force) -> float:
        return float(0.5 * np.dot(v * self.m, v) + 0.5 * np.dot(w, self.K @ w)
                     - np.dot(force, w))


class Newmark:
    """Newmark's method for one tape, speed, time step, (β, γ) and damping: factored once.

    Parameters
    ----------
    model : TapeModel
    velocity : float
        Tape speed V, m/s (>= 0).
    dt : float
        Time step Δt, s (> 0).
    beta, gamma : float
        Newmark parameters (β > 0). Outside 2β ≥ γ ≥ ½ a NewmarkStabilityWarning is issued.
    damping : Damping, float or None
        Damping C (:class:`gyroshell.tape.damping.Damping`; a number is viscous c, N·s/m³).
    backend : str
        Sparse LU back-end (see :func:`gyroshell.linalg.factorization.factorize`).
        "auto" (:func:`gyroshell.linalg.ordering.factorize_banded`): on a narrow band such
        as the symmetric half's, LAPACK's banded LU with two BLAS band substitutions per
        step; otherwise SuperLU, which orders K_eq by
        :func:`gyroshell.linalg.ordering.column_ordering` (``info["backend"]``,
        ``info["ordering"]``).
    blas_threads : int or None
        BLAS threads while factoring and marching (needs the optional threadpoolctl; None
        leaves them alone). One is fastest here: the substitutions call BLAS on small
        supernodal blocks, where OpenBLAS's spinning worker threads only compete for cores.

    Notes
    -----
    Construction assembles K(V), G(V), C; the first march that needs K_eq on all the
    unknowns, or on the symmetric half (module notes), factors it (the expensive part,
    reported as ``info["factor_time"]``), once per object, or once per
    :func:`sharing_factorizations` block. :meth:`march` then costs one substitution per
    step plus a few vector operations and one (G + C) mat-vec.

    ``info["backend"]`` is None until a K_eq is factored (or taken from a sharing block),
    then the back-end of the K_eq last used (by a march, :attr:`factor` or
    :attr:`half_factor`). With "auto" it depends on which K_eq: "band" (BandLU) on a
    narrow band such as the symmetric half's, "superlu" otherwise, so it can change
    between a half-size and a full-size march. A run's ``result.info["backend"]`` is its
    own K_eq's.
    """

    def __init__(self, model: TapeModel, velocity: float = 0.0, *, dt: float,
                 beta: float = 0.25, gamma: float = 0.5,
                 damping: Damping | float | None = None, backend: str = "auto",
                 blas_threads: int | None = 1) -> None:
        self.model = check_model(model, members=(*MODEL_MEMBERS, "force", "load_point_row"))
        self.velocity = check_velocity(velocity)
        self.beta = validation.positive("beta", beta)
        self.K = model.K(self.velocity)
        self.dt = validation.time_step(dt, self.beta,
                                       stiffness_scale=float(abs(self.K.diagonal()).max()))
        self.gamma = validation.real("gamma", gamma)
        self.damping = as_damping(damping)
        if not 2.0 * self.beta >= self.gamma >= 0.5:
            warnings.warn(
                f"Newmark beta={self.beta:g}, gamma={self.gamma:g} lie outside the "
                "unconditionally stable region 2*beta >= gamma >= 1/2: the march is stable "
                "only for small enough dt", NewmarkStabilityWarning, stacklevel=2)
        self.G = model.G(self.velocity).tocsr()
        self.C = None if self.damping.is_zero else self.damping.matrix(model, self.velocity)
        #: G + C, the velocity-proportional operator, kg/s.
        self.damped_gyroscopic = self.G if self.C is None else (self.G + self.C).tocsr()
        self.damped_gyroscopic.sort_indices()
        self.m = np.ascontiguousarray(model.mass_diagonal, dtype=float)
        self.blas_threads = blas_threads
        #: The LU back-end asked for: "auto" or a name (refused here if unknown or not
        #: installed); ``info["backend"]`` is the one that factored K_eq (class notes).
        self.backend = "auto" if backend == "auto" else resolve_backend(backend)
        self._operators: dict[str, _Operators] = {}
        self._half_allowed: bool | None = None
        self.info = {"backend": None, "factor_time": 0.0,
                     "unknowns": model.unknowns, "factorizations": 0,
                     "blas_threads": blas_threads}

    def __repr__(self) -> str:
        return (f"Newmark(V={self.velocity:g} m/s, dt={self.dt:g} s, beta={self.beta:g}, "
                f"gamma={self.gamma:g}, damping={self.damping}, backend={self.backend!r},"
                f" n={self.model.unknowns})")

    @property
    def D(self):
        """Deprecated name of :attr:`damped_gyroscopic` (G + C, kg/s); D is the bending
        rigidity elsewhere."""
        warnings.warn("Newmark.D is deprecated; use damped_gyroscopic (G + C)",
                      DeprecationWarning, stacklevel=2)
        return self.damped_gyroscopic

    @property
    def factor(self):
        """The factorization of K_eq on all the unknowns (made on first use)."""
        return self._system(None).factor

    @property
    def half_factor(self):
        """The factorization of the symmetric half's K_eq (made on first use), or None if
        the tape or its damping is not mirror symmetric (module notes)."""
        if not self._half_possible():
            return None
        return self._system(SymmetricHalf.of(self.model.grid)).factor

    # ----- pieces ---------------------------------------------------------------------
    def initial_acceleration(self, w0: np.ndarray, v0: np.ndarray, force0: np.ndarray
                             ) -> np.ndarray:
        """a⁰ from M a⁰ = F(0) − K w⁰ − (G + C) v⁰, m/s²."""
        return (force0 - self.K @ w0 - self.damped_gyroscopic @ v0) / self.m

    def energy(self, w: np.ndarray, v: np.ndarray, force: np.ndarray) -> float:
        """½vᵀMv + ½wᵀKw − Fᵀw, J (G does no work, so it has no term)."""
        return float(0.5 * np.dot(v * self.m, v) + 0.5 * np.dot(w, self.K @ w)
                     - np.dot(force, w))

    def dissipation(self, v: np.ndarray) -> float:
        """vᵀCv, W: the power the damping takes out (0 without damping)."""
        return 0.0 if self.C is None else float(np.dot(v, self.C @ v))

    def _state(self, vector, name: str, unit: str) -> np.ndarray:
        n = self.model.unknowns
        if vector is None:
            return np.zeros(n)
        return check_force(vector, n, name, unit)  # a new array: the march writes into it

    def _fixed_force(self, load, force, profile) -> np.ndarray | None:
        """The checked fixed force F (N), or None with moving heads."""
        if load is not None:
            if force is not None:
                raise ParameterError("give either load (moving heads) or force, not both")
            if profile is not step:
                raise ParameterError("profile applies to a fixed load; a moving head's time "
                                     "dependence is its contact windows (ContactWindows)")
            return None
        return self.model.force if force is None else check_force(force, self.model.unknowns)

    def _prepare_forcing(self, load, force, profile, times: np.ndarray):
        """The run's F(t): moving heads, or f(t) F with F the checked fixed ``force``."""
        if load is not None:
            return PreparedLoads(self.model, as_loads(load), times)
        return _FixedForce(force, profile, self.model.load_point_row, times)

    # ----- the unknowns marched: all, or the symmetric half --------------------------------
    def _half(self, symmetry: bool, w: np.ndarray, v: np.ndarray, force) -> SymmetricHalf | None:
        """The symmetric half if the tape, C, w⁰, v⁰ and the fixed force (None: moving heads,
        checked on their prepared centres later) are all mirror symmetric, else None."""
        if not symmetry or not self._half_possible():
            return None
        half = SymmetricHalf.of(self.model.grid)
        vectors = (w, v) if force is None else (w, v, force)
        return half if all(half.is_symmetric(x) for x in vectors) else None

    def _half_possible(self) -> bool:
        """The tape (:func:`mirror_split`) and the damping C are mirror symmetric."""
        if self._half_allowed is None:
            split = mirror_split(self.model)
            self._half_allowed = split is not None and (
                self.C is None or SymmetricHalf.of(self.model.grid).is_invariant(self.C))
        return self._half_allowed

    def _system(self, half: SymmetricHalf | None) -> _Operators:
        """The operators and factor of all the unknowns (``half`` None) or of the half."""
        which = "full" if half is None else "half"
        if which not in self._operators:
            if half is None:
                K, GC, C, m = self.K, self.damped_gyroscopic, self.C, self.m
            else:
                M_s, G_s, K_s = mirror_split(self.model).matrices(self.model, self.velocity,
                                                                  "symmetric")
                C = None if self.C is None else half.project(self.C)
                GC = G_s if C is None else (G_s + C).tocsr()
                GC.sort_indices()
                K, m = K_s, np.ascontiguousarray(M_s.diagonal(), dtype=float)
            factor, shared = self._factored(which, K, GC, m)
            self._operators[which] = _Operators(K, GC, C, m, factor, shared, half)
        self.info["backend"] = self._operators[which].factor.name
        return self._operators[which]

    def _factored(self, which: str, K, GC, m: np.ndarray) -> tuple[object, bool]:
        """The factor of K_eq = M + γΔt (G + C) + βΔt² K (this object's, or the block's of
        :func:`sharing_factorizations`) and whether it was shared."""
        def build():
            dt, b, g = self.dt, self.beta, self.gamma
            K_eq = (sp.diags(m) + (g * dt) * GC + (b * dt * dt) * K).tocsc()
            with limit_blas_threads(self.blas_threads):
                factor = factorize_banded(K_eq, self.backend)
            self.info["factorizations"] += 1
            self.info["factor_time"] += factor.factor_time
            return factor

        sharing = _SHARING.get()
        if sharing is None:
            return build(), False
        model, alive = _model_key(self.model)
        key = (model, self.velocity, self.dt, self.beta, self.gamma, self.damping,
               self.backend, which)
        return sharing.factor(key, alive, build)

    # ----- the march --------------------------------------------------------------------
    def march(self, steps: int, *, profile: TimeProfile = step,
              force: np.ndarray | None = None,
              load: MovingLoad | Sequence[MovingLoad] | None = None,
              w0: np.ndarray | None = None, v0: np.ndarray | None = None, t0: float = 0.0,
              snapshot_times: Sequence[float] | None = None, snapshot_every: int | None = None,
              centerline_times: Sequence[float] | None = None,
              record_energy: bool = False, progress: bool | None = None,
              blowup_factor: float = BLOWUP_FACTOR, symmetry: bool = True) -> TransientResult:
        """March ``steps`` steps from (w⁰, v⁰) at t0 under F(t).

        Parameters
        ----------
        steps : int
            Number of time steps (>= 1); the result holds steps + 1 instants.
        profile : callable
            f(t), dimensionless, t in s (default: a step at t = 0); the force is f(t) F.
        force : numpy.ndarray, optional
            Nodal force vector F, N (default: the model's force).
        load : MovingLoad or list of MovingLoad, optional
            Moving heads instead of f(t) F (the history is then w under each head's centre).
        w0, v0 : numpy.ndarray, optional
            Initial displacement (m) and velocity (m/s) of the unknowns; default zero (the
            wrapped equilibrium).
        t0 : float
            Initial time, s (to continue a previous run).
        snapshot_times, centerline_times : sequence of float, optional
            Times (s) at which to keep the full field, or w(x, L_y/2) (nearest steps).
        snapshot_every : int, optional
            Keep the full field every N steps (from step 0).
        record_energy : bool
            Record E_n = ½vᵀMv + ½wᵀKw − F(t_n)ᵀw (J) every step (one K mat-vec per step).
        progress : bool or None
            Show a progress bar on stderr; None: only if stderr is a terminal.
        blowup_factor : float
            Stop with ConvergenceError once max |w| exceeds this many times its scale,
            max(max|w⁰|, max|F| / max diag K, Δt steps max|v⁰|) m (> 0).
        symmetry : bool
            March the mirror-symmetric half when the inputs allow it (module notes; the
            same result to round-off, ``info["symmetry"]``); False: all the unknowns.

        Returns
        -------
        TransientResult

        Raises
        ------
        ConvergenceError
            If the solution becomes non-finite or grows past the bound.
        """
        steps, t0 = check_steps(steps), validation.real("t0", t0, unit="s")
        blowup_factor = validation.positive("blowup_factor", blowup_factor)
        kept = _kept(snapshot_times, snapshot_every, centerline_times)
        w, v, fixed, half = self._inputs(load, force, profile, w0, v0, symmetry)
        work = self._plan(steps, load, kept, record_energy, progress, half)
        times = t0 + self.dt * np.arange(steps + 1)  # t_n, s
        system, forcing, w, v, bound = self._marched(
            half, self._prepare_forcing(load, fixed, profile, times), w, v, blowup_factor)
        recorder, state, history, energy, timing = self._timed_loop(
            system, times, (w, v), forcing, kept, bound, record_energy, work)
        return self._result(system, times, history, recorder, state, energy, timing, load)

    def _inputs(self, load, force, profile, w0, v0, symmetry):
        """The checked w⁰ (m), v⁰ (m/s), fixed force (N, None with moving heads) and the
        symmetric half if all the inputs known before the run's instants allow it."""
        symmetry = validation.boolean("symmetry", symmetry)
        fixed = self._fixed_force(load, force, profile)
        w, v = self._state(w0, "w0", "m"), self._state(v0, "v0", "m/s")
        return w, v, fixed, self._half(symmetry, w, v, fixed)

    def _marched(self, half: SymmetricHalf | None, forcing, w, v, blowup_factor: float):
        """(operators, forcing, w⁰, v⁰, blow-up bound in m) on the unknowns to march: the
        half if ``half`` is given and moving heads (checked now, on their centres) keep
        it, with z = P_sᵀ w (max|z| <= √2 max|w|, so √2 times the bound is the same run's)."""
        if half is not None and isinstance(forcing, PreparedLoads) and \
                not forcing.mirror_symmetric(self.model.grid.width):
            half = None
        steps = len(forcing.times if isinstance(forcing, _FixedForce) else forcing.envelopes)
        bound = self._blowup_bound(w, v, forcing, steps - 1, blowup_factor)
        if half is None:
            return self._system(None), forcing, w, v, bound
        return (self._system(half), forcing.on_half(half), half.restrict(w), half.restrict(v),
                math.sqrt(2.0) * bound)

    def _plan(self, steps: int, load, kept, record_energy: bool, progress,
              half: SymmetricHalf | None) -> LongWork:
        """Check the run before any of its per-step arrays exists: the heads' contact windows
        against Δt, the memory of all it keeps per step (:func:`budget.check_transient`:
        times, history, heads' positions and weights, energy, fields) and, from
        :data:`TRIAL_FROM_STEPS` steps on, its time measured on :data:`TRIAL_STEPS` trial
        steps (on the half if the inputs known so far allow it); returns the run's progress
        (shorter runs are timed on their first steps)."""
        grid, progress = self.model.grid, validation.progress(progress)
        loads = None if load is None else as_loads(load)
        if loads is not None:
            check_contact_steps(loads, self.dt)
        snapshot_times, snapshot_every, centerline_times = kept.values()
        if snapshot_every is not None:
            snapshot_every = validation.integer("snapshot_every", snapshot_every, low=1)
        budget.check_transient(
            grid.nx, grid.ny, grid.edges, steps, heads=0 if loads is None else len(loads),
            fields=budget.snapshot_count(steps, snapshot_every) + _how_many(snapshot_times),
            centerlines=_how_many(centerline_times), energy=bool(record_energy))
        work = LongWork(steps, "newmark", progress=progress, unit="step",
                        size=f"a transient of {steps} steps of {self.model.unknowns} unknowns",
                        advice="use fewer steps, a larger dt or a larger spacing")
        if steps >= TRIAL_FROM_STEPS:
            work.assess(self._trial_step_time(self._system(half)), f"{TRIAL_STEPS} trial steps")
        return work

    def _trial_step_time(self, system: _Operators) -> float:
        """Seconds per step, measured on :data:`TRIAL_STEPS` steps from rest under the
        model's force, on scratch vectors, after one untimed warm-up step."""
        n = system.unknowns
        forcing = _FixedForce(self.model.force, step, self.model.load_point_row, np.zeros(1))
        if system.half is not None:
            forcing = forcing.on_half(system.half)
        w, v, a = (np.zeros(n) for _ in range(3))
        w_t, v_t, rhs, tmp, tmp2 = (np.empty(n) for _ in range(5))
        start = 0.0
        with limit_blas_threads(self.blas_threads):
            for k in range(TRIAL_STEPS + 1):
                start = time.perf_counter() if k == 1 else start
                self._predict(w, v, a, w_t, v_t, tmp)
                self._right_hand_side(system, 0, w_t, v_t, forcing, rhs, tmp, tmp2)
                w = system.factor.solve(rhs)
                self._correct(w, w_t, v_t, a, v)
        return (time.perf_counter() - start) / TRIAL_STEPS

    def _timed_loop(self, system, times, state, forcing, kept, bound, record_energy, work):
        """The time loop from (w⁰, v⁰) with its recorder (of ``kept``), progress (``work``)
        and BLAS threads; returns the recorder, the final (w, v, a) over all the unknowns,
        the history under each head (m), the energy (J, or None) and the (solve, loop)
        times, s."""
        steps = len(times) - 1
        w, v = state
        a = system.initial_acceleration(w, v, forcing.vector(0))
        recorder = Recorder(self.model.grid, steps, self.dt, times[0], **kept)
        history = np.empty((steps + 1, forcing.heads))
        energy = np.empty(steps + 1) if record_energy else None
        start = time.perf_counter()
        with work as bar, limit_blas_threads(self.blas_threads):
            w, v, a, solve_time = self._loop(system, steps, times, w, v, a, forcing,
                                             recorder, history, energy, bound, bar)
        timing = (solve_time, time.perf_counter() - start)
        if system.half is not None:
            w, v, a = (system.half.expand(x) for x in (w, v, a))
        return recorder, (w, v, a), history, energy, timing

    def _result(self, system, times, history, recorder, state, energy, timing, load
                ) -> TransientResult:
        """The TransientResult of a finished run; ``info`` gains the run's statistics."""
        steps = len(times) - 1
        solve_time, loop_time = timing
        info = dict(self.info, steps=steps, solve_time=solve_time, loop_time=loop_time,
                    step_time=loop_time / steps, damping=asdict(self.damping),
                    moving_load=load is not None, factor_time=system.factor.factor_time,
                    backend=system.factor.name,
                    factor_shared=system.shared, marched_unknowns=system.unknowns,
                    ordering=getattr(system.factor, "ordering", None),
                    symmetry="full" if system.half is None else "half")
        heads = history if history.shape[1] > 1 else None
        w, v, a = state
        return TransientResult(times, history[:, 0].copy(), recorder.snapshots(times), w, v,
                               a, self.velocity, self.dt, self.beta, self.gamma, energy, info,
                               head_displacements=heads)

    def _blowup_bound(self, w, v, forcing, steps: int, factor: float) -> float:
        """The displacement (m) past which the run counts as blown up."""
        if isinstance(forcing, _FixedForce):
            peak = np.abs(forcing.force).max()
        else:  # the largest force a head can put on one node: its peak over all steps
            peak = max(np.abs(forcing.vector(n)).max() for n in
                       np.unique(np.linspace(0, steps, min(steps + 1, 64)).astype(int)))
        scale = max(np.abs(w).max(), steps * self.dt * np.abs(v).max(),
                    peak / np.abs(self.K.diagonal()).max())
        return factor * scale if scale > 0 else math.inf

    # ----- one step, in named pieces -----------------------------------------------------
    def _predict(self, w, v, a, w_t, v_t, tmp) -> None:
        """w̃ = w + Δt v + (½ − β)Δt² a, ṽ = v + (1 − γ)Δt a (Eqs. 10-11)."""
        dt = self.dt
        np.multiply(v, dt, out=w_t)
        w_t += w
        np.multiply(a, (0.5 - self.beta) * dt * dt, out=tmp)
        w_t += tmp
        np.multiply(a, (1.0 - self.gamma) * dt, out=v_t)
        v_t += v

    def _right_hand_side(self, system, n, w_t, v_t, forcing, rhs, tmp, tmp2) -> None:
        """f_eq = M w̃ + (G + C)(γΔt w̃ − βΔt² ṽ) + βΔt² F(t_n) (Eq. 16)."""
        bdt2 = self.beta * self.dt * self.dt
        np.multiply(w_t, self.gamma * self.dt, out=tmp)
        np.multiply(v_t, bdt2, out=tmp2)
        tmp -= tmp2
        np.multiply(system.m, w_t, out=rhs)
        rhs += system.damped_gyroscopic @ tmp
        forcing.add(n, bdt2, rhs)

    def _correct(self, w_new, w_t, v_t, a, v) -> None:
        """a = (w − w̃)/(βΔt²), v = ṽ + γΔt a (Eqs. 13-14)."""
        np.subtract(w_new, w_t, out=a)
        a *= 1.0 / (self.beta * self.dt * self.dt)
        np.multiply(a, self.gamma * self.dt, out=v)
        v += v_t

    def _loop(self, system, steps, times, w, v, a, forcing, recorder, history, energy,
              bound, bar):
        """The time loop; fills ``history`` (and ``energy``) and returns (w, v, a, solve s)
        on the marched unknowns (the half's z if ``system.half``)."""
        solve, wanted, half = system.factor.solve, recorder.wanted, system.half
        w_t, v_t, rhs, tmp, tmp2 = (np.empty_like(w) for _ in range(5))

        def record(n, w):
            recorder.record(n, w, half)

        forcing.displacement(0, w, history[0])
        if energy is not None:
            energy[0] = system.energy(w, v, forcing.vector(0))
        record(0, w)
        solve_time = 0.0
        n = 0
        try:
            for n in range(1, steps + 1):
                self._predict(w, v, a, w_t, v_t, tmp)
                self._right_hand_side(system, n, w_t, v_t, forcing, rhs, tmp, tmp2)
                tick = time.perf_counter()
                w = solve(rhs)  # Eq. 12
                solve_time += time.perf_counter() - tick
                self._correct(w, w_t, v_t, a, v)
                size = np.abs(w, out=tmp).max()  # NaN propagates: "not <=" catches it
                if not size <= bound:  # said in w's units: z = √2 w on the pairs
                    shown = 1.0 if half is None else 1 / math.sqrt(2.0)
                    raise _blowup(n, times[n], shown * size, shown * bound, self)
                forcing.displacement(n, w, history[n])
                if energy is not None:
                    energy[n] = system.energy(w, v, forcing.vector(n))
                if wanted[n]:
                    record(n, w)
                bar.update(1)
        except FloatingPointError as exc:
            raise ConvergenceError(f"Newmark march overflowed at step {n} (t = "
                                   f"{times[n]:.6g} s): {exc}") from None
        return w, v, a, solve_time


def _kept(snapshot_times, snapshot_every, centerline_times) -> dict:
    """What a run keeps besides its history, as :class:`Recorder` takes it."""
    return dict(snapshot_times=snapshot_times, snapshot_every=snapshot_every,
                centerline_times=centerline_times)


def _how_many(times) -> int:
    """How many instants a list of times (s) asks for (0 for None)."""
    return 0 if times is None else int(np.size(times))


def _blowup(n: int, t: float, size: float, bound: float, stepper: Newmark
            ) -> ConvergenceError:
    what = "became non-finite" if not math.isfinite(size) else (
        f"grew to {size:.3g} m, past the bound {bound:.3g} m")
    return ConvergenceError(
        f"Newmark march blew up: the displacement {what} at step {n} (t = {t:.6g} s) with "
        f"V = {stepper.velocity:g} m/s, dt = {stepper.dt:g} s, beta = {stepper.beta:g}, "
        f"gamma = {stepper.gamma:g}; is V at or above the critical speed, or dt too large "
        "for these beta, gamma?")


def march(model: TapeModel, velocity: float = 0.0, *, dt: float, steps: int,
          beta: float = 0.25, gamma: float = 0.5, damping: Damping | float | None = None,
          backend: str = "auto", blas_threads: int | None = 1, **options
          ) -> TransientResult:
    """Transient response of the tape: one call that factors and marches.

    ``march(model, V, dt=..., steps=..., beta=..., gamma=..., damping=..., backend=...,
    blas_threads=..., **options)`` is ``Newmark(model, V, dt=dt, beta=beta, gamma=gamma,
    damping=damping, backend=backend, blas_threads=blas_threads).march(steps, **options)``;
    keep the :class:`Newmark` object instead to reuse its factorization across runs with
    the same (V, Δt, β, γ, C). See :meth:`Newmark.march` for ``options`` (profile, force,
    load, w0, v0, t0, snapshot_times, snapshot_every, centerline_times, record_energy,
    progress, blowup_factor, symmetry); wrap several calls in :func:`sharing_factorizations`
    to factor each K_eq once across them.
    """
    steps = check_steps(steps)
    return Newmark(model, velocity, dt=dt, beta=beta, gamma=gamma, damping=damping,
                   backend=backend, blas_threads=blas_threads).march(steps, **options)
