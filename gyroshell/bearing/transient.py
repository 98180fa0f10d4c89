"""Transient flight: the tape marched by Newmark's method, the film by backward Euler with
its squeeze term, solved together (monolithic Newton) at every step.

Per step the tape's Newmark predictors (paper Eqs. 10-11, as in :mod:`gyroshell.engines.newmark`)

    ũ = uⁿ + Δt vⁿ + (½ − β) Δt² aⁿ,        ṽ = vⁿ + (1 − γ) Δt aⁿ,

make aⁿ⁺¹ = (uⁿ⁺¹ − ũ)/(βΔt²) and vⁿ⁺¹ = ṽ + γΔt aⁿ⁺¹ functions of uⁿ⁺¹, and the coupled
residual gains M aⁿ⁺¹ + G(V) vⁿ⁺¹ on the tape rows and 12μ A (φⁿ⁺¹ − φⁿ)/Δt on the film
rows. The steady solve's Newton (:func:`.smooth.newton_step`: the generic Newton, the hard
wall as bounds) solves for (uⁿ⁺¹, pⁿ⁺¹) from the previous state, so the tape and the film
are strongly coupled. A steady state of the march is exactly a steady state of
:func:`gyroshell.bearing.steady.solve_steady`. A step whose Newton fails is retried as two
half steps (:data:`MAX_HALVINGS`). Over
rounded corners touched at one point the contact nodes stay where the start put them, and a
state cutting into an arc off its node is refused (:func:`.corners.check_point_contacts`).

Drivers: the tension T(t) (a step or a harmonic change; it enters K and the wrap load)
and an extra pressure load moving across the head.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..core import validation
from ..core.errors import ConvergenceError, ParameterError
from ..core.progress import progress_bar
from ..engines.newmark import check_steps
from . import budget
from .corners import check_point_contacts
from .model import BearingModel
from .problem import check_cavitation
from .results import BearingSolution, BearingTransient, NewtonInfo
from .smooth import newton_step

#: Newmark's default parameters: the trapezoidal rule (no numerical damping).
NEWMARK_BETA = 0.25
NEWMARK_GAMMA = 0.5
#: The progress bar's label.
PROGRESS_LABEL = "bearing transient"


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


class _Tension:
    """A tension history T(t), N/m, that knows its lowest value (checked before a march)."""

    lowest: float

    def __call__(self, t: float) -> float:  # pragma: no cover - overridden
        raise NotImplementedError


class _TensionStep(_Tension):
    def __init__(self, initial: float, final: float, at: float) -> None:
        self.initial = validation.positive("initial", initial, "N/m")
        self.final = validation.positive("final", final, "N/m")
        self.at = validation.nonnegative("at", at, "s")
        self.lowest = min(self.initial, self.final)

    def __call__(self, t: float) -> float:
        return self.final if t >= self.at else self.initial


class _TensionHarmonic(_Tension):
    def __init__(self, mean: float, amplitude: float, frequency: float) -> None:
        self.mean = validation.positive("mean", mean, "N/m")
        self.amplitude = validation.real("amplitude", amplitude, unit="N/m")
        self.frequency = validation.nonnegative("frequency", frequency, "Hz")
        self.lowest = self.mean - abs(self.amplitude)
        if not self.lowest > 0.0:
            raise ParameterError(f"amplitude must be below the mean tension {self.mean:g} "
                                 f"N/m (T(t) > 0), got {self.amplitude:g}")

    def __call__(self, t: float) -> float:
        return self.mean + self.amplitude * np.sin(2 * np.pi * self.frequency * t)


def tension_step(initial: float, final: float, at: float = 0.0) -> Callable[[float], float]:
    """T(t): ``initial`` before ``at`` (s), ``final`` from then on, N/m (both > 0)."""
    return _TensionStep(initial, final, at)


def tension_harmonic(mean: float, amplitude: float, frequency: float
                     ) -> Callable[[float], float]:
    """T(t) = mean + amplitude sin(2π f t), N/m (f in Hz; mean − |amplitude| > 0)."""
    return _TensionHarmonic(mean, amplitude, frequency)


def _tension_at(T, t: float, floor: float) -> float:
    """T(t), N/m, checked: a real number above ρV² (``floor``), else a ParameterError
    naming t (a user's own T(t) can only be checked as the march reaches t)."""
    try:
        value = validation.real("tension(t)", T(t), unit="N/m")
    except ParameterError as exc:
        raise ParameterError(f"{exc} at t = {t:g} s") from None
    if not value > floor:
        raise ParameterError(f"tension(t) must be > rho V^2 = {floor:.6g} N/m (the tape "
                             f"must wrap the head), got {value:g} at t = {t:g} s")
    return value


def _moving_force(moving_load, t: float, size: int):
    """The extra nodal forces at t, N: None without a load, else checked (finite, one per
    tape unknown)."""
    if moving_load is None:
        return None
    try:
        return validation.vector("moving_load(t)", moving_load(t), size, "N")
    except ParameterError as exc:
        raise ParameterError(f"{exc} at t = {t:g} s") from None


def march(start: BearingSolution, *, dt: float, steps: int,
          tension: Callable[[float], float] | None = None,
          moving_load: Callable[[float], np.ndarray] | None = None,
          beta: float = NEWMARK_BETA, gamma: float = NEWMARK_GAMMA, record_every: int = 1,
          progress: bool | None = None) -> BearingTransient:
    """March the flying tape from a steady state.

    Parameters
    ----------
    start : BearingSolution
        The initial state (at rest: v = 0, and a from the tape equation).
    dt : float
        Time step, s (> 0, with β Δt² within the solvers' range).
    steps : int
        Number of steps (>= 1).
    tension : callable, optional
        T(t), N/m, above ρV² at every step (default: the model's constant T).
    moving_load : callable, optional
        Extra nodal forces on the tape at time t, N, ``model.n_u`` of them (e.g. a load
        crossing the head).
    beta, gamma : float
        Newmark parameters (default the trapezoidal rule; γ > ½ damps numerically).
    record_every : int
        Record every this many steps (each keeps the centre line, nx + 1 values).
    progress : bool or None
        A progress bar on stderr (:func:`~gyroshell.core.progress.progress_bar`); None: on a
        terminal only.

    Raises
    ------
    ParameterError
        If an argument is of the wrong type, shape or range, or the record would not fit
        in memory (before any work; a user's T(t) and load are checked at each t).
    """
    model, dt, steps, record_every, beta, gamma, T = _checked_march(
        start, dt, steps, record_every, beta, gamma, tension, moving_load)
    floor = model.params.density * model.velocity**2      # T(t) must stay above it
    G = model.tape.G(model.velocity)
    u, p = start.u.copy(), start.p.copy()
    v, a = np.zeros_like(u), np.zeros_like(u)   # at rest, an equilibrium at T(0)
    phi = model.transported(u, p)
    record = _Record(model)
    sol = record(0.0, u, p, start.contact, 0, _tension_at(T, 0.0, floor))
    state = _State(u, p, v, a, phi)
    step = _Stepper(model, G, beta, gamma, T, floor, moving_load)
    with progress_bar(steps, PROGRESS_LABEL, progress=progress, unit="step") as bar:
        for n in range(1, steps + 1):
            t = n * dt
            state, lam, its = step.advance(state, t - dt, dt)
            _check_step(model, state.u, state.p, t)
            if n % record_every == 0 or n == steps:
                sol = record(t, state.u, state.p, lam, its, _tension_at(T, t, floor))
            bar.update(1)
    return record.result(start.x, sol)


#: A step whose Newton fails is retried as two half steps, at most this many times
#: halved (1/1024 of Δt: a lift of the tape off its corners measured, 0.6 nm, needs steps
#: of 1e-8 s where the film's pressure jumps to balance it).
MAX_HALVINGS = 10


@dataclass
class _State:
    """The march's state: u (m), p (Pa), v (m/s), a (m/s²), the film's transported φ."""

    u: np.ndarray
    p: np.ndarray
    v: np.ndarray
    a: np.ndarray
    phi: np.ndarray


class _Stepper:
    """One implicit step of the march (module notes), retried in halves if it fails."""

    def __init__(self, model, G, beta, gamma, T, floor, moving_load) -> None:
        self.model, self.G, self.beta, self.gamma = model, G, beta, gamma
        self.T, self.floor, self.moving_load = T, floor, moving_load

    def step(self, s: _State, t: float, dt: float):
        """(state at t, contact forces, Newton iterations) from the state at t − dt."""
        model, beta, gamma = self.model, self.beta, self.gamma
        u_tilde = s.u + dt * s.v + (0.5 - beta) * dt * dt * s.a
        v_tilde = s.v + (1.0 - gamma) * dt * s.a
        force = _moving_force(self.moving_load, t, model.n_u)
        terms = _StepTerms(model, self.G, dt, beta, gamma, u_tilde, v_tilde, s.phi, force)
        tension = _tension_at(self.T, t, self.floor)
        z, lam, iterations = newton_step(model, np.concatenate([s.u, s.p]),
                                         tension=tension, transient=terms)
        u, p = z[:model.n_u], z[model.n_u:]
        a, v = terms.kinematics(u)
        phi = model.transported(u, p)
        return _State(u, p, v, a, phi), lam, iterations

    def advance(self, s: _State, t0: float, dt: float, halvings: int = 0):
        """The state at t0 + dt (s): one step, or, if its Newton fails, two half steps
        (recursively, at most :data:`MAX_HALVINGS` times)."""
        try:
            return self.step(s, t0 + dt, dt)
        except ConvergenceError as exc:
            if halvings >= MAX_HALVINGS:
                raise ConvergenceError(f"{exc} at t = {t0 + dt:g} s, in steps of {dt:g} s "
                                       f"({MAX_HALVINGS} times halved)") from None
        mid, _, first = self.advance(s, t0, 0.5 * dt, halvings + 1)
        end, lam, second = self.advance(mid, t0 + 0.5 * dt, 0.5 * dt, halvings + 1)
        return end, lam, first + second


def _check_step(model: BearingModel, u, p, t: float) -> None:
    """A step's state at t (s): no cavitation, and the tape not cutting into a rounded
    corner's arc off its contact node (the march keeps the tangent points' nodes)."""
    check_cavitation(model, p, f" at t = {t:g} s")
    if model.corner_contacts:
        check_point_contacts(model, u, f" at t = {t:g} s")


def _checked_march(start, dt, steps, record_every, beta, gamma, tension, moving_load):
    """The arguments of :func:`march`, checked before any work: (model, dt, steps,
    record_every, beta, gamma, T) with T the tension history (the model's constant T if
    None). The record's memory is estimated (:func:`gyroshell.bearing.budget.check_march`),
    a known history's lowest tension (:func:`tension_step`, :func:`tension_harmonic`) must
    exceed ρV², and a moving load is tried once at t = dt."""
    validation.instance("start", start, BearingSolution)
    model = start.model
    steps = check_steps(steps)
    record_every = check_steps(record_every, "record_every")
    beta, gamma = _checked_newmark(beta, gamma)
    dt = validation.time_step(dt, beta, stiffness_scale=float(
        np.abs(model.stiffness_diagonal).max()))
    floor = model.params.density * model.velocity**2
    if tension is None:
        T = _TensionStep(model.params.tension, model.params.tension, 0.0)
    elif not callable(tension):
        raise ParameterError(f"tension must be None or a callable T(t) in N/m (e.g. "
                             f"tension_step(90, 120)), got {type(tension).__name__}")
    else:
        T = tension
    if isinstance(T, _Tension) and not T.lowest > floor:
        raise ParameterError(f"tension must stay > rho V^2 = {floor:.6g} N/m (the tape must "
                             f"wrap the head), but it reaches {T.lowest:g}")
    if moving_load is not None and not callable(moving_load):
        raise ParameterError(f"moving_load must be None or a callable f(t) giving nodal "
                             f"forces in N, got {type(moving_load).__name__}")
    _moving_force(moving_load, dt, model.n_u)
    budget.check_march(model.nx, model.ny, steps, record_every, model.factorization)
    return model, dt, steps, record_every, beta, gamma, T


def _checked_newmark(beta: float, gamma: float) -> tuple[float, float]:
    """(β, γ), checked for unconditional stability: 2β >= γ >= ½."""
    beta = validation.positive("beta", beta)
    gamma = validation.real("gamma", gamma)
    if not 2.0 * beta >= gamma >= 0.5:
        raise ParameterError(f"beta, gamma must satisfy 2 beta >= gamma >= 1/2 "
                             f"(unconditional stability), got {beta:g}, {gamma:g}")
    return beta, gamma


class _Record:
    """The series a march records; called with a state, returns its BearingSolution."""

    def __init__(self, model: BearingModel) -> None:
        self.model = model
        self.centre_col = 0 if model.infinitely_wide else model.ny // 2
        self.series = {k: [] for k in ("t", "hc", "hmin", "fc", "T", "line", "it")}

    def __call__(self, t, u, p, lam, its, tension_now) -> BearingSolution:
        sol = BearingSolution(self.model, u, p, lam, NewtonInfo(iterations=its))
        H = sol.spacing
        rec = self.series
        rec["t"].append(t)
        rec["hc"].append(sol.central_spacing)
        rec["hmin"].append(H.min())
        rec["fc"].append(float(lam.sum()))
        rec["T"].append(tension_now)
        rec["line"].append(H[:, self.centre_col].copy())
        rec["it"].append(its)
        return sol

    def result(self, x: np.ndarray, final: BearingSolution) -> BearingTransient:
        """The record as a BearingTransient on the abscissae ``x`` (m), ending at ``final``."""
        rec = {k: np.array(v) for k, v in self.series.items()}
        return BearingTransient(rec["t"], rec["hc"], rec["hmin"], rec["fc"], rec["T"], x,
                                rec["line"], rec["it"], final)
