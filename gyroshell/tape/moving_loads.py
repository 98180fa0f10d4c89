"""Moving and intermittent loads: heads that travel over the tape and touch it in windows.

A head presses with P(x, y, t) = P₀ e(t) p_x(x − x_c(t)) p_y(y − y_c(t)), where the centre
(x_c, y_c)(t) follows a path given in the lab frame (the frame of the supports x = 0, L_x),
e(t) ∈ [0, 1] is the contact envelope and p_x, p_y are 1-D shapes (default: the paper's
Gaussian of Eq. 17, so p_x p_y = exp(−α r²)). Each shape is integrated exactly over the
control cells through its antiderivative, so a load between nodes carries the right force.

The shape is separable, so the nodal force vector is P₀ e(t) kron(f_x(t), f_y(t)); only the
few cells under a narrow shape are non-zero, and a step adds them into the right-hand side
through small preallocated buffers: the update costs microseconds whatever the grid.

Usage: ``Newmark(...).march(steps, load=MovingLoad(StraightPath((x0, y0), (vx, vy))))``;
several heads are a list of loads (see :func:`drum_heads`).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.special import erf

from ..core import validation
from ..core.errors import ParameterError
from .grid import Grid
from .loads import check_exponent, gaussian_exponent
from .model import TapeModel

#: A Gaussian's cell integrals are cut where erfc(√α r) < 1e-17 (below round-off of the sum).
GAUSSIAN_CUTOFF = 6.0
#: Ramp shapes of a contact window.
RAMP_SHAPES = ("cosine", "linear")
#: A contact window must span at least this many time steps: a shorter one is sampled at one
#: instant or none, so its force depends on where the steps fall rather than on the window.
MIN_WINDOW_STEPS = 2
#: Instants on which a path is tried before it is evaluated over the whole run.
FIRST_INSTANTS = 4


def _pair(name: str, value, unit: str) -> tuple[float, float]:
    try:
        a, b = value
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a pair of numbers ({unit}), got {value!r}"
                             ) from None
    return validation.real(name, a, unit=unit), validation.real(name, b, unit=unit)


# ----- 1-D shapes ------------------------------------------------------------------------
class Shape1D:
    """A load shape p(s) along one axis, through its antiderivative P(s) = ∫ p ds (m).

    ``radius`` (m) bounds the support: cells farther than it from the centre get nothing.
    """

    radius: float = math.inf

    def antiderivative(self, s: np.ndarray, out: np.ndarray) -> np.ndarray:
        """P(s) into ``out`` (s is the offset from the centre, m)."""
        raise NotImplementedError


@dataclass(frozen=True)
class GaussianShape(Shape1D):
    """exp(−α s²), α in 1/m² (Eq. 17: α = ln 100 / (0.05 L_y)²)."""

    exponent: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "exponent", check_exponent(self.exponent))

    @property
    def radius(self) -> float:  # type: ignore[override]
        """Support radius, m: 6/√α, where erfc(√α r) < 1e-17 (nothing beyond it)."""
        return GAUSSIAN_CUTOFF / math.sqrt(self.exponent)

    def antiderivative(self, s: np.ndarray, out: np.ndarray) -> np.ndarray:
        root = math.sqrt(self.exponent)
        np.multiply(s, root, out=out)
        erf(out, out=out)
        out *= 0.5 * math.sqrt(math.pi) / root
        return out


@dataclass(frozen=True)
class UniformShape(Shape1D):
    """p = 1 everywhere (a line load uniform along this axis)."""

    def antiderivative(self, s: np.ndarray, out: np.ndarray) -> np.ndarray:
        np.copyto(out, s)
        return out


@dataclass(frozen=True)
class UserShape(Shape1D):
    """A user shape given by its antiderivative P(s) (vectorized, m) and support radius (m)."""

    function: Callable[[np.ndarray], np.ndarray]
    radius: float = math.inf

    def __post_init__(self) -> None:
        if not callable(self.function):
            raise ParameterError("function must be callable: the antiderivative P(s), m")
        if self.radius != math.inf:
            object.__setattr__(self, "radius",
                               validation.positive("radius", self.radius, "m"))

    def antiderivative(self, s: np.ndarray, out: np.ndarray) -> np.ndarray:
        out[...] = self.function(s)
        return out


# ----- paths and contact windows -----------------------------------------------------------
@dataclass(frozen=True)
class StraightPath:
    """Centre (x, y)(t) = start + velocity · t, lab frame (m, m/s)."""

    start: tuple[float, float]
    velocity: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", _pair("start", self.start, "m"))
        object.__setattr__(self, "velocity", _pair("load velocity", self.velocity, "m/s"))

    def __call__(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        t = np.asarray(t, dtype=float)
        return self.start[0] + self.velocity[0] * t, self.start[1] + self.velocity[1] * t


@dataclass(frozen=True)
class ContactWindows:
    """Contact on for ``duration`` in every ``period`` (s), starting at ``phase`` (s).

    Parameters
    ----------
    period, duration : float
        τ_p and τ_c, s (0 < τ_c <= τ_p).
    ramp : float
        Rise and fall time inside the window, s (0: abrupt; 2 ramp <= duration).
    ramp_shape : {"cosine", "linear"}
        Raised cosine (smooth) or linear ramps.
    phase : float
        Start of the first window, s (heads on a drum are offset by period / heads).
    """

    period: float
    duration: float
    ramp: float = 0.0
    ramp_shape: str = "cosine"
    phase: float = 0.0

    def __post_init__(self) -> None:
        put = object.__setattr__
        put(self, "period", validation.positive("contact period", self.period, "s"))
        put(self, "duration", validation.positive("contact duration", self.duration, "s"))
        put(self, "ramp", validation.nonnegative("contact ramp", self.ramp, "s"))
        put(self, "phase", validation.real("contact phase", self.phase, unit="s"))
        if self.duration > self.period:
            raise ParameterError(f"contact duration must be <= the contact period "
                                 f"{self.period:g} s, got {self.duration:g} s")
        if 2.0 * self.ramp > self.duration:
            raise ParameterError(f"contact ramp must be <= half the contact duration "
                                 f"({self.duration / 2:g} s), got {self.ramp:g} s")
        validation.choice("ramp_shape", self.ramp_shape, RAMP_SHAPES)

    def local_time(self, t: np.ndarray) -> np.ndarray:
        """Time since the start of the current window, s, in [0, period)."""
        return np.mod(np.asarray(t, dtype=float) - self.phase, self.period)

    def envelope(self, t: np.ndarray) -> np.ndarray:
        """e(t) in [0, 1]: 1 in contact, 0 out, ramps between (dimensionless).

        Examples
        --------
        >>> ContactWindows(period=10e-6, duration=4e-6, ramp=1e-6).envelope(
        ...     [0.5e-6, 2e-6, 5e-6, 10.5e-6])
        array([0.5, 1. , 0. , 0.5])
        """
        tau = self.local_time(t)
        on = tau < self.duration
        if self.ramp == 0.0:
            return on.astype(float)
        edge = np.minimum(tau, self.duration - tau) / self.ramp
        s = np.clip(edge, 0.0, 1.0)
        if self.ramp_shape == "cosine":
            s = 0.5 - 0.5 * np.cos(np.pi * s)
        return np.where(on, s, 0.0)


# ----- a head -------------------------------------------------------------------------------
@dataclass(frozen=True)
class MovingLoad:
    """One head: a load of peak pressure P₀ moving along ``path``, in contact per ``contact``.

    Parameters
    ----------
    path : callable
        t (s, array) -> (x, y) centre (m, arrays), lab frame; e.g. :class:`StraightPath`.
    pressure : float or None
        Peak pressure P₀, Pa; None: the model's ``params.load``.
    shape : (Shape1D, Shape1D) or None
        Shapes along x and y; None: the Gaussian of Eq. 17 for the model's width.
    contact : ContactWindows or None
        Intermittent contact; None: always in contact.
    restart_path : bool
        With contact windows, evaluate the path at the time since the window started, so
        every contact sweeps the same track (a head on a drum); otherwise at t.
    """

    path: Callable
    pressure: float | None = None
    shape: tuple[Shape1D, Shape1D] | None = None
    contact: ContactWindows | None = None
    restart_path: bool = False

    def __post_init__(self) -> None:
        if not callable(self.path):
            raise ParameterError("path must be callable: t (s) -> (x, y) (m)")
        if self.pressure is not None:
            object.__setattr__(self, "pressure",
                               validation.real("pressure", self.pressure, unit="Pa"))
        if self.shape is not None and (len(self.shape) != 2 or not all(
                isinstance(s, Shape1D) for s in self.shape)):
            raise ParameterError("shape must be a pair of Shape1D (along x, along y)")
        validation.instance("contact", self.contact, ContactWindows, optional=True)

    def centres(self, times: np.ndarray, *, name: str = "path"
                ) -> tuple[np.ndarray, np.ndarray]:
        """Centre coordinates (m) at ``times`` (s, a 1-D array).

        The path is called once with the array of times (or, if it only takes one time,
        once per time) and what it returns is checked (``name`` is the path's name in the
        messages).

        Raises
        ------
        ParameterError
            If the path raises, or returns anything but two finite real coordinates per time.
        """
        t = np.atleast_1d(np.asarray(times, dtype=float))
        if self.contact is not None and self.restart_path:
            t = self.contact.local_time(t)
        x, y = _positions(self.path, t, name)
        bad = ~(np.isfinite(x) & np.isfinite(y))
        if np.any(bad):
            n = int(np.argmax(bad))
            raise ParameterError(f"{name} must return finite positions (x, y) in m, got "
                                 f"({x[n]:g}, {y[n]:g}) at t = {t[n]:g} s")
        return x, y

    def envelope(self, times: np.ndarray) -> np.ndarray:
        """Contact envelope e(t) (dimensionless) at ``times`` (s)."""
        t = np.asarray(times, dtype=float)
        return np.ones_like(t) if self.contact is None else self.contact.envelope(t)


#: What a user's path may raise when it is called with times it cannot take; each becomes a
#: ParameterError naming the path (its own bugs of other kinds stay as they are).
PATH_ERRORS = (TypeError, ValueError, ArithmeticError, LookupError, AttributeError)
#: What a path must do, for the messages.
PATH_CONTRACT = ("must map times t (s) to positions (x, y) in m: two real numbers for one "
                 "time, two arrays shaped like t (or numbers) for an array of times")


def _coordinate(value, shape: tuple[int, ...]) -> np.ndarray:
    """One coordinate returned by a path, as floats broadcast to ``shape`` (ValueError if it
    is not real numbers of a shape that broadcasts)."""
    array = np.asarray(value)
    if array.dtype.kind not in "iuf":
        raise ValueError("not real numbers")
    return np.broadcast_to(array.astype(float), shape)


def _shown(value) -> str:
    """A path's return value for a one-line message: an array by its shape, else its repr."""
    if isinstance(value, np.ndarray):
        return f"an array of shape {value.shape}"
    text = " ".join(repr(value).split())
    return text if len(text) <= 80 else text[:77] + "..."


def _positions(path: Callable, t: np.ndarray, name: str) -> tuple[np.ndarray, np.ndarray]:
    """(x, y) of ``path`` at the times ``t``: one call with the array, or one per time for a
    path that takes a single time (math functions raise TypeError on arrays)."""
    try:
        x, y = path(t)
        return _coordinate(x, t.shape), _coordinate(y, t.shape)
    except (TypeError, ValueError):
        pass  # not an array path: try one time at a time
    except PATH_ERRORS as exc:
        raise ParameterError(f"{name} {PATH_CONTRACT}; called with {len(t)} times from "
                             f"t = {t[0]:g} s it raised {type(exc).__name__}: {exc}") from exc
    xy = np.empty((len(t), 2))
    for n, s in enumerate(t):
        try:
            value = path(float(s))
        except PATH_ERRORS as exc:
            raise ParameterError(f"{name} {PATH_CONTRACT}; at t = {s:g} s it raised "
                                 f"{type(exc).__name__}: {exc}") from exc
        try:
            x, y = value
            xy[n] = _coordinate(x, ()), _coordinate(y, ())
        except (TypeError, ValueError):
            raise ParameterError(f"{name} {PATH_CONTRACT}; at t = {s:g} s it returned "
                                 f"{_shown(value)}") from None
    return xy[:, 0], xy[:, 1]


def drum_heads(heads: int, start: tuple[float, float], velocity: tuple[float, float], *,
               revolution_period: float, contact_duration: float, ramp: float = 0.0,
               pressure: float | None = None,
               shape: tuple[Shape1D, Shape1D] | None = None) -> list[MovingLoad]:
    """Heads on a rotating drum: each sweeps the same straight track once per revolution.

    Head k touches the tape from ``k · revolution_period / heads`` for ``contact_duration``
    (s), moving from ``start`` (m) at ``velocity`` (m/s, lab frame).
    """
    heads = validation.integer("heads", heads, low=1)
    path = StraightPath(start, velocity)
    return [MovingLoad(path, pressure=pressure, shape=shape, restart_path=True,
                       contact=ContactWindows(revolution_period, contact_duration, ramp=ramp,
                                              phase=k * revolution_period / heads))
            for k in range(heads)]


def check_contact_steps(loads: Sequence[MovingLoad], dt: float) -> None:
    """Refuse contact windows the time step ``dt`` (s) cannot resolve: a window shorter than
    :data:`MIN_WINDOW_STEPS` steps, a ramp (> 0) shorter than one step, or a gap between
    windows (period − duration, > 0) shorter than one step.

    Raises
    ------
    ParameterError
        Naming the window's duration, ramp or period, the time step and the head.
    """
    slack = 1.0 - 1e-9  # times that are whole multiples of dt up to round-off pass
    for k, head in enumerate(loads):
        c = head.contact
        if c is None:
            continue
        who = f" of head {k}" if len(loads) > 1 else ""
        if c.duration < MIN_WINDOW_STEPS * dt * slack:
            raise ParameterError(
                f"contact duration{who} must span at least {MIN_WINDOW_STEPS} time steps "
                f"(>= {MIN_WINDOW_STEPS * dt:g} s with dt = {dt:g} s), got {c.duration:g} s")
        if 0.0 < c.ramp < dt * slack:
            raise ParameterError(
                f"contact ramp{who} must be 0 (abrupt) or at least one time step "
                f"(dt = {dt:g} s), got {c.ramp:g} s")
        gap = c.period - c.duration
        if 1e-12 * c.period < gap < dt * slack:
            raise ParameterError(
                f"contact period{who} must equal the contact duration (always in contact) or "
                f"exceed it by at least one time step (dt = {dt:g} s), got {c.period:g} s, "
                f"a gap of {gap:g} s")


def as_loads(load) -> list[MovingLoad]:
    """A list of MovingLoad from one load or a sequence of them."""
    loads = [load] if isinstance(load, MovingLoad) else list(load)
    if not loads or not all(isinstance(h, MovingLoad) for h in loads):
        raise ParameterError("load must be a MovingLoad or a non-empty list of them")
    return loads


# ----- a run: precomputed centres, envelopes, windows and interpolation -----------------------
class PreparedLoads:
    """The heads of one run at the instants t0 + n Δt, ready for the time loop.

    ``add(n, scale, out)`` adds scale · F(t_n) (N) into ``out`` touching only the cells
    under each head; ``displacement(n, w, out)`` writes w under each head's centre (m).

    :meth:`on_half` gives the same heads on the symmetric half's unknowns, for heads that
    :meth:`mirror_symmetric` accepts.
    """

    #: The symmetric half the vectors live on (None: all the unknowns).
    half = None

    def __init__(self, model: TapeModel, loads: Sequence[MovingLoad], times: np.ndarray):
        grid, params = model.grid, model.params
        self.grid, self.heads = grid, len(loads)
        self.centres = np.empty((len(times), self.heads, 2))
        self.envelopes = np.empty((len(times), self.heads))
        self.amplitudes = np.empty(self.heads)
        default = GaussianShape(gaussian_exponent(params.width))
        self._axes = []
        xs, ys = grid.x[grid.x_unknowns], grid.y[grid.y_unknowns]
        for k, head in enumerate(loads):
            name = "path" if self.heads == 1 else f"path of head {k}"
            head.centres(times[:FIRST_INSTANTS], name=name)  # a broken path fails here, at once
            x, y = head.centres(times, name=name)
            env = head.envelope(times)
            _check_on_tape(grid, x, y, env, k)
            self.centres[:, k, 0], self.centres[:, k, 1] = x, y
            self.envelopes[:, k] = env
            self.amplitudes[k] = params.load if head.pressure is None else head.pressure
            sx, sy = head.shape if head.shape is not None else (default, default)
            ax = _Window(xs, grid.hx, 0.0, grid.length, sx)
            ay = _Window(ys, grid.hy, 0.0, grid.width, sy)
            self._axes.append((ax, ay, ax.first(x), ay.first(y)))
        self._field = np.empty(0)
        self._interp = _interpolation(grid, self.centres)

    def on_half(self, half) -> PreparedLoads:
        """These heads on the unknowns z of the symmetric half ``half`` (a
        :class:`gyroshell.tape.mirror.SymmetricHalf`; w = P_s z), for heads that
        :meth:`mirror_symmetric` accepts: ``add`` then adds P_sᵀ F(t_n) (the cells left of
        and on the centre line, times the half's force weights), ``vector`` returns it, and
        ``displacement`` reads w = P_s z under the centres."""
        folded = copy.copy(self)
        idx, wts = self._interp
        folded.half, folded._force_weights = half, half.force_weights
        folded._interp = half.index(idx), wts * half.weight(idx)  # w_j = weight(j) z_index(j)
        return folded

    def mirror_symmetric(self, width: float) -> bool:
        """True if every head's force is symmetric about y = ``width``/2 (m) at every step:
        its centre on the centre line (to 1e-14 of the width) and a shape across the width
        that is even (the Gaussian or uniform shape; a user's shape is not assumed even).
        The path along x, the contact windows and the pressure do not matter."""
        centred = np.abs(self.centres[:, :, 1] - 0.5 * width) <= 1e-14 * width
        return bool(np.all(centred)) and all(
            isinstance(ay.shape, (GaussianShape, UniformShape)) for _, ay, _, _ in self._axes)

    def add(self, n: int, scale: float, out: np.ndarray) -> None:
        """out += scale · F(t_n), N (only the cells under the heads are touched); with
        ``half``, scale · P_sᵀ F(t_n) over the half's unknowns (F symmetric)."""
        half = self.half
        columns = self.grid.n_across if half is None else half.columns
        view = out.reshape(self.grid.n_lines, columns)
        for k in range(self.heads):
            e = self.envelopes[n, k]
            if e == 0.0:
                continue
            ax, ay, ix, iy = self._axes[k]
            i0, j0 = int(ix[n]), int(iy[n])
            kept = min(ay.width, columns - j0)     # the half keeps its own side's columns
            if kept <= 0:
                continue
            fx = ax.integrals(i0, self.centres[n, k, 0])
            fy = ay.integrals(j0, self.centres[n, k, 1])[:kept]
            if half is not None:
                fy *= self._force_weights[j0:j0 + kept]
            fy *= scale * e * self.amplitudes[k]
            block = ax.block(kept)
            np.multiply(fx[:, None], fy[None, :], out=block)
            view[i0:i0 + ax.width, j0:j0 + kept] += block

    def vector(self, n: int) -> np.ndarray:
        """F(t_n), N (P_sᵀ F(t_n) with ``half``; allocates: for the initial acceleration and
        energies)."""
        out = np.zeros(self.grid.unknowns if self.half is None else self.half.unknowns)
        self.add(n, 1.0, out)
        return out

    def displacement(self, n: int, w: np.ndarray, out: np.ndarray) -> None:
        """w under each head's centre at step n (bilinear), m, into ``out[heads]``."""
        idx, wts = self._interp
        np.sum(w[idx[n]] * wts[n], axis=1, out=out)


class _Window:
    """One axis of one head: the window of cells under it and its buffers."""

    def __init__(self, nodes: np.ndarray, h: float, lo: float, hi: float, shape: Shape1D):
        self.nodes, self.h, self.lo, self.hi, self.shape = nodes, h, lo, hi, shape
        n = len(nodes)
        self.width = n if not math.isfinite(shape.radius) else min(
            n, int(math.ceil(2 * shape.radius / h)) + 3)
        # cell edges of the first `width` nodes relative to node 0 (shifted per step)
        self._offsets = (np.arange(self.width + 1) - 0.5) * h
        self._edges = np.empty(self.width + 1)
        self._prim = np.empty(self.width + 1)
        self._values = np.empty(self.width)
        self._block = np.empty(0)

    def first(self, centre: np.ndarray) -> np.ndarray:
        """Index (into the unknown nodes) of each window's first node."""
        n = len(self.nodes)
        if self.width == n:
            return np.zeros(len(centre), dtype=np.int64)
        start = np.floor((centre - self.shape.radius - self.nodes[0]) / self.h)
        return np.clip(start, 0, n - self.width).astype(np.int64)

    def integrals(self, first: int, centre: float) -> np.ndarray:
        """∫ p(s − centre) ds over the control cells of the window's nodes (clipped), m."""
        e = self._edges
        np.add(self._offsets, self.nodes[first] - centre, out=e)
        np.clip(e, self.lo - centre, self.hi - centre, out=e)
        P = self.shape.antiderivative(e, self._prim)
        np.subtract(P[1:], P[:-1], out=self._values)
        return self._values

    def block(self, columns: int) -> np.ndarray:
        """A (width, columns) work buffer."""
        if self._block.shape != (self.width, columns):
            self._block = np.empty((self.width, columns))
        return self._block


def _check_on_tape(grid: Grid, x: np.ndarray, y: np.ndarray, env: np.ndarray, k: int) -> None:
    on = env > 0.0
    bad = on & ~((x >= 0.0) & (x <= grid.length) & (y >= 0.0) & (y <= grid.width))
    bad |= on & ~(np.isfinite(x) & np.isfinite(y))
    if np.any(bad):
        n = int(np.argmax(bad))
        raise ParameterError(
            f"load path leaves the tape: head {k} is at ({x[n]:.6g}, {y[n]:.6g}) m at step "
            f"{n} while in contact; the path must stay in [0, {grid.length:.6g}] x "
            f"[0, {grid.width:.6g}] m")


def _interpolation(grid: Grid, centres: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unknown indices and bilinear weights, shapes (steps, heads, 4), of each centre.

    Supported nodes (w = 0) get index 0 with weight 0.
    """
    x = np.clip(centres[..., 0], 0.0, grid.length)
    y = np.clip(centres[..., 1], 0.0, grid.width)
    sx, sy = x / grid.hx, y / grid.hy
    i = np.minimum(sx.astype(np.int64), grid.nx - 1)
    j = np.minimum(sy.astype(np.int64), grid.ny - 1)
    fx, fy = sx - i, sy - j
    jo = 0 if grid.free_edges else 1
    idx = np.empty(x.shape + (4,), dtype=np.int64)
    wts = np.empty(x.shape + (4,))
    for c, (di, dj, wt) in enumerate(((0, 0, (1 - fx) * (1 - fy)), (1, 0, fx * (1 - fy)),
                                      (0, 1, (1 - fx) * fy), (1, 1, fx * fy))):
        ii, jj = i + di, j + dj
        valid = (ii >= 1) & (ii <= grid.nx - 1) & (jj - jo >= 0) & (jj - jo < grid.n_across)
        idx[..., c] = np.where(valid, (ii - 1) * grid.n_across + (jj - jo), 0)
        wts[..., c] = np.where(valid, wt, 0.0)
    return idx, wts
