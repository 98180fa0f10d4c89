"""Transient flight: the tape marched by Newmark's method, the film by backward Euler with
its squeeze term, solved together (monolithic Newton) at every step.

Per step the tape's Newmark predictors (paper Eqs. 10-11, as in :mod:`gyroshell.newmark`)

    ũ = uⁿ + Δt vⁿ + (½ − β) Δt² aⁿ,        ṽ = vⁿ + (1 − γ) Δt aⁿ,

make aⁿ⁺¹ = (uⁿ⁺¹ − ũ)/(βΔt²) and vⁿ⁺¹ = ṽ + γΔt aⁿ⁺¹ functions of uⁿ⁺¹, and the coupled
residual gains M aⁿ⁺¹ + G(V) vⁿ⁺¹ on the tape rows and 12μ A (φⁿ⁺¹ − φⁿ)/Δt on the film
rows. Newton (with the contact set) solves for (uⁿ⁺¹, pⁿ⁺¹) from the previous state, so
the tape and the film are strongly coupled. A steady state of the march is exactly a
steady state of :func:`gyroshell.bearing.steady.solve_steady`.

Drivers: the tension T(t) (a step or a harmonic change; it enters K and the wrap load)
and an extra pressure load moving across the head.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..core.errors import ParameterError
from ..engines.newmark import _check_real, check_steps
from .model import BearingModel
from .steady import BearingSolution, NewtonInfo, newton


class _StepTerms:
    """Time-discrete terms of one implicit step (see the module notes)."""

    def __init__(self, model: BearingModel, G, dt, beta, gamma, u_tilde, v_tilde, phi_old,
                 extra_force) -> None:
        self.m = model.tape.M.diagonal()
        self.G, self.dt, self.beta, self.gamma = G, dt, beta, gamma
        self.u_tilde, self.v_tilde = u_tilde, v_tilde
        self.phi_old = phi_old
        self.extra_force = extra_force
        self.jacobian = (sp.diags(self.m / (beta * dt * dt)) + (gamma / (beta * dt)) * G).tocsr()

    def kinematics(self, u):
        a = (u - self.u_tilde) / (self.beta * self.dt * self.dt)
        return a, self.v_tilde + self.gamma * self.dt * a

    def tape_terms(self, u):
        a, v = self.kinematics(u)
        r = self.m * a + self.G @ v
        if self.extra_force is not None:
            r = r - self.extra_force
        return r, self.jacobian


@dataclass(frozen=True)
class BearingTransient:
    """A march's record (every ``record_every`` steps).

    Attributes
    ----------
    t : numpy.ndarray
        Times, s.
    central_spacing, minimum_spacing : numpy.ndarray
        h at the middle of the wrap and width, and its minimum, m.
    contact_force : numpy.ndarray
        Total contact force, N (N/m if infinitely wide).
    tension : numpy.ndarray
        T(t), N/m.
    x : numpy.ndarray
        Node abscissae from the middle of the wrap, m.
    centreline : numpy.ndarray
        h(x) along the middle of the width at each recorded time, m, shape (len(t), nx + 1).
    newton_iterations : numpy.ndarray
        Newton iterations of each recorded step.
    final : BearingSolution
        The last state (velocity v and acceleration a not included).
    """

    t: np.ndarray
    central_spacing: np.ndarray
    minimum_spacing: np.ndarray
    contact_force: np.ndarray
    tension: np.ndarray
    x: np.ndarray
    centreline: np.ndarray
    newton_iterations: np.ndarray
    final: BearingSolution


def tension_step(initial: float, final: float, at: float = 0.0) -> Callable[[float], float]:
    """T(t): ``initial`` before ``at`` (s), ``final`` from then on, N/m."""
    return lambda t: final if t >= at else initial


def tension_harmonic(mean: float, amplitude: float, frequency: float
                     ) -> Callable[[float], float]:
    """T(t) = mean + amplitude sin(2π f t), N/m (f in Hz)."""
    return lambda t: mean + amplitude * np.sin(2 * np.pi * frequency * t)


def march(start: BearingSolution, *, dt: float, steps: int,
          tension: Callable[[float], float] | None = None,
          moving_load: Callable[[float], np.ndarray] | None = None,
          beta: float = 0.25, gamma: float = 0.5, record_every: int = 1,
          progress: bool | None = None) -> BearingTransient:
    """March the flying tape from a steady state.

    Parameters
    ----------
    start : BearingSolution
        The initial state (at rest: v = 0, and a from the tape equation).
    dt : float
        Time step, s (> 0).
    steps : int
        Number of steps (>= 1).
    tension : callable, optional
        T(t), N/m (default: the model's constant T).
    moving_load : callable, optional
        Extra nodal forces on the tape at time t, N (e.g. a load crossing the head).
    beta, gamma : float
        Newmark parameters (default the trapezoidal rule; γ > ½ damps numerically).
    record_every : int
        Record every this many steps.
    progress : bool or None
        A progress bar (tqdm) on stderr; None: only if stderr is a terminal.
    """
    model = start.model
    dt = _check_real("dt", dt, positive=True)
    steps = check_steps(steps)
    record_every = check_steps(record_every)
    beta = _check_real("beta", beta, positive=True)
    gamma = _check_real("gamma", gamma)
    if not 2.0 * beta >= gamma >= 0.5:
        raise ParameterError(f"beta, gamma must satisfy 2 beta >= gamma >= 1/2 "
                             f"(unconditional stability), got {beta:g}, {gamma:g}")
    T = (lambda _t: model.params.tension) if tension is None else tension
    G = model.tape.G(model.velocity)
    u, p = start.u.copy(), start.p.copy()
    v = np.zeros_like(u)
    a = np.zeros_like(u)   # the start is an equilibrium of the tape at T(0)
    phi = model.film.transported(model.pressure_field(p), model.spacing_field(u))
    rec = {k: [] for k in ("t", "hc", "hmin", "fc", "T", "line", "it")}
    lam = start.contact
    centre_col = 0 if model.infinitely_wide else model.ny // 2

    def record(t, u, p, lam, its, tension_now):
        sol = BearingSolution(model, u, p, lam, NewtonInfo(iterations=its))
        H = sol.spacing
        rec["t"].append(t)
        rec["hc"].append(sol.central_spacing)
        rec["hmin"].append(H.min())
        rec["fc"].append(float(lam.sum()))
        rec["T"].append(tension_now)
        rec["line"].append(H[:, centre_col].copy())
        rec["it"].append(its)
        return sol

    sol = record(0.0, u, p, lam, 0, T(0.0))
    bar = _progress(steps, progress)
    for n in range(1, steps + 1):
        t = n * dt
        u_tilde = u + dt * v + (0.5 - beta) * dt * dt * a
        v_tilde = v + (1.0 - gamma) * dt * a
        force = None if moving_load is None else moving_load(t)
        terms = _StepTerms(model, G, dt, beta, gamma, u_tilde, v_tilde, phi, force)
        info = NewtonInfo()
        z, lam, _, info = newton(model, np.concatenate([u, p]), tension=T(t),
                                 transient=terms, info=info)
        u, p = z[:model.n_u], z[model.n_u:]
        a, v = terms.kinematics(u)
        phi = model.film.transported(model.pressure_field(p), model.spacing_field(u))
        if n % record_every == 0 or n == steps:
            sol = record(t, u, p, lam, info.iterations, T(t))
        if bar is not None:
            bar.update(1)
    if bar is not None:
        bar.close()
    return BearingTransient(np.array(rec["t"]), np.array(rec["hc"]), np.array(rec["hmin"]),
                            np.array(rec["fc"]), np.array(rec["T"]), start.x,
                            np.array(rec["line"]), np.array(rec["it"]), sol)


def _progress(steps: int, progress: bool | None):
    if progress is None:
        progress = sys.stderr.isatty()
    if not progress:
        return None
    from tqdm import tqdm

    return tqdm(total=steps, desc="bearing transient", unit="step", file=sys.stderr)
