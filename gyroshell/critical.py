"""Critical speed of the moving tape, two independent ways, with the classical estimates.

(a) Eigenvalue route: the speed where the lowest frequency reaches zero, by bracketing
    and root-finding on V with the gyroscopic eigen-solver. ω(V) → 0 like √(V_c − V), so
    the root is sought for the smooth f(V) = −λ₀² (λ₀ the eigenvalue nearest zero):
    f = ω₁² > 0 below critical, −(Re λ₀)² < 0 above (divergence).
(b) Divergence route: K(V) = A + (T − ρV²)B loses definiteness at V_div = √((T + μ_min)/ρ)
    (:func:`gyroshell.divergence.divergence`, one ``eigsh``).

For a conservative gyroscopic system an eigenvalue is zero exactly when K is singular, so
the two must agree; they are computed by different algorithms and compared.

Context values: √(T/ρ) (moving string or beam, Wickert & Mote 1990: about 80 m/s), the
infinite strip on the shell foundation √((T + 2√(Dk))/ρ), Sundaram & Benson's 111 m/s and
the seed paper's "just above 100 m/s".
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from . import persistence
from .divergence import divergence
from .eigen import modes
from .errors import ConvergenceError, ParameterError
from .model import TapeModel

#: Sundaram & Benson (1989/1990), all sides simply supported shell, m/s (quoted by the paper).
SUNDARAM_BENSON_SPEED = 111.0
#: Seed paper: unbounded displacements "for a small positive change from 100 m/s", m/s.
PAPER_SPEED = 100.0


def _evaluate(model: TapeModel, velocity: float, count: int, options: dict
              ) -> tuple[float, np.ndarray]:
    """f(V) (see :func:`critical_function`) and the eigenvector of the eigenvalue it uses."""
    options = {"sigma": 0, **options}
    result = modes(model, velocity, count, **options)
    lam = result.eigenvalues
    if not result.supercritical:
        return float(result.omega[0] ** 2), result.vectors[:, 0]
    j = int(np.argmax(lam.real))
    if lam[j].real > 0:
        return float(-(lam[j].real ** 2)), result.vectors[:, j]
    return float(-abs(lam[0]) ** 2), result.vectors[:, 0]


def critical_function(model: TapeModel, velocity: float, *, count: int = 1,
                      **options) -> float:
    """f(V), 1/s²: ω₁² below the critical speed, −γ² above (γ the largest growth rate).

    The ``count`` eigenvalue pairs nearest zero come from :func:`gyroshell.eigen.modes` with
    shift-invert about σ = 0 (one factorization of K(V); near critical the small eigenvalue
    is well separated, so this is fast); ``options`` go to ``modes``. Near the root the
    eigenvalue nearest zero is the one crossing, so f = −λ₀² there, smooth in V. Farther
    above, an oscillating pair can be nearer zero than the divergent one; f then uses the
    growing eigenvalue if found, else −|λ₀|² (still negative: K(V) is indefinite).
    """
    return _evaluate(model, velocity, count, options)[0]


def _rayleigh_speed(model: TapeModel, phi: np.ndarray) -> float:
    """Speed at which φᴴK(V)φ = 0, m/s: √((T + φᴴAφ/φᴴBφ)/ρ).

    For the mode about to cross zero, κ = φᴴK(V)φ → 0 with λ, so this is a Newton-like step
    for the root; being a Rayleigh quotient of A φ = μ B φ it never lies below the root.
    """
    p = model.params
    c = np.conj(phi)
    mu = float(np.real(c @ (model.A @ phi)) / np.real(c @ (model.B @ phi)))
    return math.sqrt(max(p.tension + mu, 0.0) / p.density)


@dataclass(frozen=True)
class CriticalSpeeds:
    """Critical speed by both routes, with context values (all m/s).

    Attributes
    ----------
    critical_speed : float
        (a) Where the lowest frequency crosses zero (eigen-solver + root-finding).
    divergence_speed : float
        (b) √((T + μ_min)/ρ) from one ``eigsh``.
    string_speed : float
        √(T/ρ): moving string / beam without foundation (Wickert & Mote 1990).
    strip_speed : float
        √((T + 2√(Dk))/ρ): infinite strip (beam) on the shell foundation.
    sundaram_benson_speed, paper_speed : float
        Values quoted by the seed paper: 111 m/s and "just above 100 m/s".
    info : dict
        ``evaluations`` of f, ``bracket`` (m/s), ``critical_time`` and ``divergence_time`` (s),
        ``relative_difference`` |a − b| / b, ``mu`` (N/m).
    """

    critical_speed: float
    divergence_speed: float
    string_speed: float
    strip_speed: float
    sundaram_benson_speed: float = SUNDARAM_BENSON_SPEED
    paper_speed: float = PAPER_SPEED
    info: dict = field(default_factory=dict, compare=False)

    @property
    def relative_difference(self) -> float:
        """|critical − divergence| / divergence."""
        return abs(self.critical_speed - self.divergence_speed) / self.divergence_speed

    def as_dict(self) -> dict[str, float]:
        """The speeds (m/s) as a plain dict (JSON-ready)."""
        return {
            "critical_speed": self.critical_speed,
            "divergence_speed": self.divergence_speed,
            "relative_difference": self.relative_difference,
            "string_speed": self.string_speed,
            "strip_speed": self.strip_speed,
            "sundaram_benson_speed": self.sundaram_benson_speed,
            "paper_speed": self.paper_speed,
        }

    def to_xarray(self, *, params=None):
        """xarray Dataset with units and metadata (see :mod:`gyroshell.persistence`)."""
        return persistence.to_xarray(self, params=params)

    def save(self, path, *, params=None):
        """Write NetCDF (.nc) whole; ``gyroshell.load(path)`` reads it back exactly."""
        return persistence.save(self, path, params=params)


def _extrapolate_zero(points: list[tuple[float, float]]) -> float:
    """Zero of the interpolant of (s, f) beyond the last point: quadratic through three
    points (f ≈ a d + c d², d = s_c − s, seen in practice), else the secant; s·1.004 if
    neither gives a zero beyond the last point."""
    s_last = points[-1][0]
    if len(points) == 3:
        s = np.array([q[0] for q in points]) - s_last
        fv = np.array([q[1] for q in points])
        scale = abs(s[0]) or 1.0
        c2, c1, c0 = np.polyfit(s / scale, fv, 2)
        roots = np.roots([c2, c1, c0]) if c2 != 0 else np.array([-c0 / c1])
        roots = roots[np.isreal(roots)].real * scale
        roots = roots[roots > 0]
        if roots.size:
            return float(s_last + roots.min())
    if len(points) >= 2:
        (s1, f1), (s2, f2) = points[-2:]
        if s2 > s1 and f1 > f2:
            return s2 - f2 * (s2 - s1) / (f2 - f1)
    return s_last * 1.004


def critical_speed_eigen(model: TapeModel, *, guess: float | None = None,
                         xtol: float = 1e-9, count: int = 1, max_evaluations: int = 30,
                         **options) -> tuple[float, dict]:
    """(a) The speed where the lowest frequency reaches zero, m/s, and diagnostics.

    Near the root ω₁² is a smooth, nearly linear function of s = V² (ω₁ ∝ √(V_c − V)), while
    above it the eigenvalue nearest zero may belong to another branch. So the root is
    approached from below by secant steps on ω₁²(s) (extrapolating its zero), each step an
    eigen-solve; a point found above critical (f < 0) caps the bracket and the next trial is
    the bisection in s. It stops when the extrapolated zero moves less than ``xtol`` (relative)
    and the bracket [V_below, V_root (1 + xtol)] is confirmed by a sign change.

    Parameters
    ----------
    guess : float, optional
        Starting speed, m/s; default 0.99 × the strip speed √((T + 2√(Dk))/ρ).
    xtol : float
        Relative tolerance on V.
    count : int
        Eigenvalue pairs per solve (see :func:`critical_function`).

    Raises
    ------
    ConvergenceError
        If no bracketed root is found within ``max_evaluations`` eigen-solves.
    """
    p = model.params
    guess = 0.99 * p.strip_critical_speed if guess is None else float(guess)
    if not (math.isfinite(guess) and guess > 0):
        raise ParameterError(f"guess must be a positive speed in m/s, got {guess!r}")
    trace: list[tuple[float, float]] = []

    def f(v: float) -> float:
        if len(trace) >= max_evaluations:
            raise ConvergenceError(
                f"critical speed: no bracketed zero of the lowest frequency in "
                f"{max_evaluations} eigen-solves")
        value = critical_function(model, v, count=count, **options)
        trace.append((v, value))
        return value

    below: list[tuple[float, float]] = []   # (s, ω₁²) with ω₁² > 0
    above = math.inf                          # smallest s with f <= 0
    s = guess**2
    while True:  # a first point below critical
        if f(math.sqrt(s)) > 0:
            below.append((s, trace[-1][1]))
            break
        above = min(above, s)
        s *= 0.96
    s *= 1.004
    root = None
    while root is None:
        if s < above:
            value = f(math.sqrt(s))
            if value > 0:
                below.append((s, value))
            else:
                above = s
        pred = _extrapolate_zero(sorted(below)[-3:])
        lo = max(b for b, _ in below)
        if pred >= above or pred <= lo:
            pred = 0.5 * (lo + above) if math.isfinite(above) else lo * 1.004
        if abs(pred - lo) <= 2 * xtol * pred:
            cap = pred * (1 + 2 * xtol)
            if cap >= above or f(math.sqrt(cap)) <= 0:
                root = math.sqrt(pred)
                above = min(above, cap)
                break
            below.append((cap, trace[-1][1]))
            pred = cap * (1 + 2 * xtol)
        s = pred
    return float(root), {"evaluations": len(trace),
                         "bracket": (math.sqrt(max(b for b, _ in below)), math.sqrt(above)),
                         "trace": trace}


def critical_speeds(model: TapeModel, **options) -> CriticalSpeeds:
    """Critical speed by both routes (a) and (b), with the context values, m/s.

    ``options`` go to :func:`critical_speed_eigen` (``guess``, ``xtol``, solver options).
    """
    p = model.params
    t0 = time.perf_counter()
    div = divergence(model)
    t1 = time.perf_counter()
    v_a, info = critical_speed_eigen(model, **options)
    t2 = time.perf_counter()
    info.update(divergence_time=t1 - t0, critical_time=t2 - t1, mu=div.mu)
    info.pop("trace", None)
    result = CriticalSpeeds(v_a, div.speed, p.string_speed, p.strip_critical_speed,
                            info=info)
    info["relative_difference"] = result.relative_difference
    return result
