"""Newmark time marching of M a + G v + K w = f(t) F, displacement form (paper Eqs. 10-16).

Each step: predictors (Eqs. 10-11)

    w̃ = wⁿ + Δt vⁿ + (½ − β) Δt² aⁿ,        ṽ = vⁿ + (1 − γ) Δt aⁿ,

one solve K_eq wⁿ⁺¹ = f_eq (Eqs. 12, 15-16) with the matrix factored once,

    K_eq = M + γΔt G + βΔt² K,
    f_eq = βΔt² f(tⁿ⁺¹) F + M w̃ + G (γΔt w̃ − βΔt² ṽ),

and correctors (Eqs. 13-14) aⁿ⁺¹ = (wⁿ⁺¹ − w̃)/(βΔt²), vⁿ⁺¹ = ṽ + γΔt aⁿ⁺¹.

β = 1/4, γ = 1/2 (the default) is the trapezoidal rule: unconditionally stable, no
algorithmic damping, and with G skew and a constant load it conserves
E = ½vᵀMv + ½wᵀKw − Fᵀw to round-off. β = 1, γ = 3/2 damps strongly and brings a transient
to its static equilibrium with large steps (the paper's "t = ∞" pictures).

A :class:`Newmark` object holds one factorization for one (V, Δt, β, γ) and can march any
number of runs with it; :func:`march` is the one-call form.
"""

from __future__ import annotations

import math
import sys
import time
import warnings
from collections.abc import Sequence

import numpy as np
from scipy.sparse._sparsetools import csr_matvec

from .errors import ConvergenceError, ParameterError
from .factorization import factorize
from .loads import TimeProfile, step
from .model import TapeModel
from .parameters import check_velocity
from .threads import blas_threads as limit_blas_threads
from .transient_result import Recorder, TransientResult

#: The run stops when ‖w‖₂ grows past this many times its natural scale.
BLOWUP_FACTOR = 1e8


class NewmarkStabilityWarning(UserWarning):
    """β, γ outside the unconditionally stable region 2β ≥ γ ≥ ½."""


def _check_real(name: str, value: float, *, positive: bool = False) -> float:
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(value) or (positive and value <= 0.0):
        raise ParameterError(f"{name} must be {'> 0' if positive else 'finite'}, got {value:g}")
    return value


def check_steps(steps: int) -> int:
    """Validate a number of time steps (an integer >= 1)."""
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 1:
        raise ParameterError(f"steps must be an integer >= 1, got {steps!r}")
    return int(steps)


class Newmark:
    """Newmark's method for one tape, speed, time step and (β, γ): factored once.

    Parameters
    ----------
    model : TapeModel
    velocity : float
        Tape speed V, m/s (>= 0).
    dt : float
        Time step Δt, s (> 0).
    beta, gamma : float
        Newmark parameters (β > 0). Outside 2β ≥ γ ≥ ½ a NewmarkStabilityWarning is issued.
    backend : str
        Sparse LU back-end (see :func:`gyroshell.factorization.factorize`).
    blas_threads : int or None
        BLAS threads while factoring and marching (needs the optional threadpoolctl; None
        leaves them alone). One is fastest here: the substitutions call BLAS on small
        supernodal blocks, where OpenBLAS's spinning worker threads only compete for cores.

    Notes
    -----
    Construction assembles K(V), G(V) and factors K_eq (the expensive part, reported as
    ``info["factor_time"]``); :meth:`march` then costs one substitution per step plus a few
    vector operations and one G mat-vec, all into preallocated arrays.
    """

    def __init__(self, model: TapeModel, velocity: float = 0.0, *, dt: float,
                 beta: float = 0.25, gamma: float = 0.5, backend: str = "auto",
                 blas_threads: int | None = 1) -> None:
        self.model = model
        self.velocity = check_velocity(velocity)
        self.dt = _check_real("dt", dt, positive=True)
        self.beta = _check_real("beta", beta, positive=True)
        self.gamma = _check_real("gamma", gamma)
        if not 2.0 * self.beta >= self.gamma >= 0.5:
            warnings.warn(
                f"Newmark beta={self.beta:g}, gamma={self.gamma:g} lie outside the "
                "unconditionally stable region 2*beta >= gamma >= 1/2: the march is stable "
                "only for small enough dt", NewmarkStabilityWarning, stacklevel=2)
        self.K = model.K(self.velocity)
        self.G = model.G(self.velocity).tocsr()
        self.G.sort_indices()
        self.m = np.ascontiguousarray(model.mass_diagonal, dtype=float)
        self.blas_threads = blas_threads
        dt, b, g = self.dt, self.beta, self.gamma
        K_eq = (model.M + (g * dt) * self.G + (b * dt * dt) * self.K).tocsc()
        with limit_blas_threads(blas_threads):
            self.factor = factorize(K_eq, backend)
        self.info = {"backend": self.factor.name, "factor_time": self.factor.factor_time,
                     "unknowns": model.size, "factorizations": 1,
                     "blas_threads": blas_threads}

    def __repr__(self) -> str:
        return (f"Newmark(V={self.velocity:g} m/s, dt={self.dt:g} s, beta={self.beta:g}, "
                f"gamma={self.gamma:g}, backend={self.factor.name!r}, n={self.model.size})")

    # ----- pieces ---------------------------------------------------------------------
    def _gmatvec(self, x: np.ndarray, out: np.ndarray) -> np.ndarray:
        """out += G x without allocating (scipy's csr kernel accumulates into out)."""
        G = self.G
        csr_matvec(G.shape[0], G.shape[1], G.indptr, G.indices, G.data, x, out)
        return out

    def initial_acceleration(self, w0: np.ndarray, v0: np.ndarray, force0: np.ndarray
                             ) -> np.ndarray:
        """a⁰ from M a⁰ = P(0) − K w⁰ − G v⁰, m/s²."""
        return (force0 - self.K @ w0 - self.G @ v0) / self.m

    def energy(self, w: np.ndarray, v: np.ndarray, force: np.ndarray) -> float:
        """½vᵀMv + ½wᵀKw − Fᵀw, J (G does no work, so it has no term)."""
        return float(0.5 * np.dot(v * self.m, v) + 0.5 * np.dot(w, self.K @ w)
                     - np.dot(force, w))

    def _state(self, vector, name: str) -> np.ndarray:
        n = self.model.size
        if vector is None:
            return np.zeros(n)
        out = np.array(vector, dtype=float)  # a copy: the march writes into it
        if out.shape != (n,) or not np.all(np.isfinite(out)):
            raise ParameterError(f"{name} must be a finite vector of length {n} (unknowns)")
        return out

    # ----- the march --------------------------------------------------------------------
    def march(self, steps: int, *, profile: TimeProfile = step,
              w0: np.ndarray | None = None, v0: np.ndarray | None = None, t0: float = 0.0,
              snapshot_times: Sequence[float] | None = None,
              snapshot_every: int | None = None,
              centerline_times: Sequence[float] | None = None,
              record_energy: bool = False, progress: bool | None = None,
              blowup_factor: float = BLOWUP_FACTOR) -> TransientResult:
        """March ``steps`` steps from (w⁰, v⁰) at t0 under F(t) = profile(t) · model.load.

        Parameters
        ----------
        steps : int
            Number of time steps (>= 1); the result holds steps + 1 instants.
        profile : callable
            f(t), dimensionless, t in s (default: a step switched on at t = 0).
        w0, v0 : numpy.ndarray, optional
            Initial displacement (m) and velocity (m/s) of the unknowns; default zero (the
            wrapped equilibrium).
        t0 : float
            Initial time, s (to continue a previous run).
        snapshot_times : sequence of float, optional
            Times (s) at which to keep the full field (the nearest step is taken).
        snapshot_every : int, optional
            Keep the full field every N steps (from step 0).
        centerline_times : sequence of float, optional
            Times (s) at which to keep w(x, L_y/2).
        record_energy : bool
            Record E_n = ½vᵀMv + ½wᵀKw − f(t_n)Fᵀw (J) every step (one K mat-vec per step).
        progress : bool or None
            Show a progress bar on stderr; None: only if stderr is a terminal.
        blowup_factor : float
            Stop with ConvergenceError once max |w| exceeds this many times its scale
            max(max|w⁰|, max|F| / max diag K, Δt steps max|v⁰|), m.

        Returns
        -------
        TransientResult

        Raises
        ------
        ConvergenceError
            If the solution becomes non-finite or grows past the bound.
        """
        steps = check_steps(steps)
        t0 = _check_real("t0", t0)
        model = self.model
        force = model.load
        w, v = self._state(w0, "w0"), self._state(v0, "v0")
        a = self.initial_acceleration(w, v, profile(t0) * force)
        recorder = Recorder(model.grid, steps, self.dt, t0, snapshot_times=snapshot_times,
                            snapshot_every=snapshot_every, centerline_times=centerline_times)
        scale = max(np.abs(w).max(), steps * self.dt * np.abs(v).max(),
                    np.abs(force).max() / np.abs(self.K.diagonal()).max())
        bound = blowup_factor * scale if scale > 0 else math.inf

        history = np.empty(steps + 1)
        energy = np.empty(steps + 1) if record_energy else None
        bar = _progress_bar(steps, progress)
        start = time.perf_counter()
        try:
            with limit_blas_threads(self.blas_threads):
                w, v, a, solve_time = self._loop(steps, t0, w, v, a, profile, recorder,
                                                 history, energy, bound, bar)
        finally:
            if bar is not None:
                bar.close()
        loop_time = time.perf_counter() - start

        times = t0 + self.dt * np.arange(steps + 1)
        info = dict(self.info, steps=steps, solve_time=solve_time, loop_time=loop_time,
                    step_time=loop_time / steps)
        return TransientResult(times, history, recorder.snapshots(times), w, v, a,
                               self.velocity, self.dt, self.beta, self.gamma, energy, info)

    def _loop(self, steps, t0, w, v, a, profile, recorder, history, energy, bound, bar):
        """The time loop; fills ``history`` (and ``energy``) and returns (w, v, a, solve s)."""
        dt, m, force, solve = self.dt, self.m, self.model.load, self.factor.solve
        bdt2, gdt = self.beta * dt * dt, self.gamma * dt
        c_w, c_v = (0.5 - self.beta) * dt * dt, (1.0 - self.gamma) * dt
        # r @ w through the row's few non-zeros: no BLAS call (no BLAS threads) per step
        row = self.model.load_point_row
        row_idx = np.flatnonzero(row)
        row_w = row[row_idx]
        wanted = recorder.wanted
        # Work vectors: the loop allocates only the solver's output.
        w_t, v_t, rhs, tmp = (np.empty_like(w) for _ in range(4))

        history[0] = w[row_idx] @ row_w
        if energy is not None:
            energy[0] = self.energy(w, v, profile(t0) * force)
        recorder.record(0, w)
        solve_time = 0.0
        n, t = 0, t0
        try:
            for n in range(1, steps + 1):
                t = t0 + n * dt
                # predictors (Eqs. 10-11)
                np.multiply(v, dt, out=w_t)
                w_t += w
                np.multiply(a, c_w, out=tmp)
                w_t += tmp
                np.multiply(a, c_v, out=v_t)
                v_t += v
                # f_eq (Eq. 16) = M w̃ + G (γΔt w̃ − βΔt² ṽ) + βΔt² f(t) F
                np.multiply(m, w_t, out=rhs)
                np.multiply(w_t, gdt, out=tmp)
                np.multiply(v_t, bdt2, out=a)  # a is free until the corrector
                tmp -= a
                self._gmatvec(tmp, rhs)
                f_t = profile(t)
                if f_t != 0.0:
                    np.multiply(force, bdt2 * f_t, out=tmp)
                    rhs += tmp
                tick = time.perf_counter()
                w_new = solve(rhs)  # Eq. 12
                solve_time += time.perf_counter() - tick
                # correctors (Eqs. 13-14)
                np.subtract(w_new, w_t, out=a)
                a *= 1.0 / bdt2
                np.multiply(a, gdt, out=v)
                v += v_t
                w = w_new
                size = np.abs(w, out=tmp).max()  # NaN propagates: "not <=" catches it
                if not size <= bound:
                    raise _blowup(n, t, size, bound, self)
                history[n] = w[row_idx] @ row_w
                if energy is not None:
                    energy[n] = self.energy(w, v, f_t * force)
                if wanted[n]:
                    recorder.record(n, w)
                if bar is not None:
                    bar.update(1)
        except FloatingPointError as exc:
            raise ConvergenceError(f"Newmark march overflowed at step {n} (t = {t:.6g} s): "
                                   f"{exc}") from None
        return w, v, a, solve_time


def _blowup(n: int, t: float, size: float, bound: float, stepper: Newmark
            ) -> ConvergenceError:
    what = "became non-finite" if not math.isfinite(size) else (
        f"grew to {size:.3g} m, past the bound {bound:.3g} m")
    return ConvergenceError(
        f"Newmark march blew up: the displacement {what} at step {n} (t = {t:.6g} s) with "
        f"V = {stepper.velocity:g} m/s, dt = {stepper.dt:g} s, beta = {stepper.beta:g}, "
        f"gamma = {stepper.gamma:g}; is V at or above the critical speed, or dt too large "
        "for these beta, gamma?")


def _progress_bar(steps: int, progress: bool | None):
    if progress is None:
        progress = bool(getattr(sys.stderr, "isatty", lambda: False)())
    if not progress:
        return None
    from tqdm import tqdm

    return tqdm(total=steps, unit="step", desc="newmark", mininterval=0.25, leave=False,
                file=sys.stderr)


def march(model: TapeModel, velocity: float = 0.0, *, dt: float, steps: int,
          beta: float = 0.25, gamma: float = 0.5, backend: str = "auto",
          blas_threads: int | None = 1, **options) -> TransientResult:
    """Transient response of the tape: one call that factors and marches.

    ``march(model, V, dt=..., steps=..., beta=..., gamma=..., backend=..., blas_threads=...,
    **options)`` is ``Newmark(model, V, dt=dt, beta=beta, gamma=gamma, backend=backend,
    blas_threads=blas_threads).march(steps, **options)``; keep the :class:`Newmark` object
    instead to reuse its factorization across runs with the same (V, Δt, β, γ). See
    :meth:`Newmark.march` for ``options`` (profile, w0, v0, t0, snapshot_times,
    snapshot_every, centerline_times, record_energy, progress, blowup_factor).
    """
    steps = check_steps(steps)
    return Newmark(model, velocity, dt=dt, beta=beta, gamma=gamma, backend=backend,
                   blas_threads=blas_threads).march(steps, **options)
