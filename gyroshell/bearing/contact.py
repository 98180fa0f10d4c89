"""Head–tape contact laws: the nominal pressure the tape's asperities carry at a separation.

Three laws (:data:`CONTACT_LAWS`), chosen by :class:`ContactParameters`:

``"asperity"`` (:class:`GreenwoodWilliamson`)
    Greenwood & Williamson, *Contact of nominally flat surfaces*, Proc. R. Soc. A 295:300
    (1966): spherical summits of radius β, η per unit area, Gaussian heights of standard
    deviation σ_s, each a Hertz contact of composite modulus E* against the (smooth, rigid)
    head. With d the separation between the head and the mean plane of the summit heights,

        p(d) = (4/3) E* η √β ∫_d^∞ (z − d)^{3/2} φ(z) dz = p_s F_{3/2}(d/σ_s),

    p_s = (4/3) E* η √β σ_s^{3/2} (:attr:`GreenwoodWilliamson.pressure_scale`) and
    F_n(t) = (1/√(2π)) ∫_t^∞ (s − t)^n e^{−s²/2} ds, with dF_n/dt = −n F_{n−1}.
    Smooth (C^∞) and positive at every separation: it acts wherever the tape is near the
    head, and Newton sees one function everywhere.
``"compliance"`` (:class:`ComplianceCurve`)
    A measured curve of nominal pressure against separation (a CSV file), interpolated C¹
    and monotone.
``"hard"`` (:class:`HardWall`)
    A hard wall at h = gap: the limit σ_s → 0 at a fixed pressure scale p_s of the
    asperity law (the separation carrying any given pressure is σ_s F_{3/2}^{−1}(p/p_s) → 0).
    A bound on the spacing, not a pressure function: the closed forms of the dry wrap and
    the dry land use it.

**Evaluating F_n.** The closed form F_n(t) = Γ(n+1)/√(2π) e^{−t²/4} D_{−n−1}(t) with
scipy's parabolic cylinder function ``scipy.special.pbdv`` was measured against mpmath
(30 digits) on t ∈ [−8, 40], n = 3/2 and 1/2: relative error up to 3.4e-9 near t = 5.8
(where its method changes), up to 7e-11 on t ∈ [−6.5, −5.5], ≤ 5e-12 elsewhere, NaN from
t ≈ −55 down; about 1 µs a point. Good enough for the physics, but not uniformly to double
precision, so this module evaluates the defining integral by Gauss quadrature with u^{1/2}
(u = s − t; u for F_1) in the weight, the integrand's remaining power of u being smooth, so
that F_{1/2} and F_{3/2} share one set of exponentials. Measured the same way: ≤ 5e-14
relative on t ∈ [−12, 14] (3e-14 for F_{3/2}), about 2.5 µs a point for p and dp/dd together:

- t ≥ 2: u = s − t, F_n = e^{−t²/2} t^{−n−1}/√(2π) ∫_0^∞ v^n e^{−v} e^{−v²/(2t²)} dv
  (v = t u), 40-point generalized Gauss–Laguerre; F_n = 0 beyond t = 40 (it underflows
  from t ≈ 38.6);
- −8 < t < 2: ∫_0^U u^n e^{−(u+t)²/2} du, U = max(−t, 0) + 12 (the neglected tail is below
  e^{−72}), 60-point Gauss–Jacobi;
- t ≤ −8: 40-point Gauss–Hermite of (s − t)_+^n against the Gaussian (the part of the
  Gaussian below t, < 1e-15, is what it misses), accurate to 1e-16 and valid however
  negative t is.

The three pieces agree at their joins to the accuracy above, so p and dp/dd are smooth to
rounding; the tests check them against ``scipy.integrate.quad`` of the defining integrals
and against the ``pbdv`` closed form.
"""

from __future__ import annotations

import csv
import functools
import io
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..core import validation
from ..core.errors import InputFileError, ParameterError
from .air import ROUGHNESS

__all__ = ["ASPERITY_DENSITY", "ASPERITY_RADIUS", "COMPLIANCE_HEADER", "CONTACT_LAWS",
           "CONTACT_MODULUS", "HARD_WALL_GAP", "SUMMIT_ROUGHNESS", "ComplianceCurve",
           "ContactParameters", "GreenwoodWilliamson", "HardWall", "pchip_slopes",
           "summit_integral"]

#: The contact laws: a smooth asperity law, a hard wall, a measured compliance curve.
CONTACT_LAWS: tuple[str, ...] = ("asperity", "hard", "compliance")

# ----- defaults: a modern thin data tape against a lapped head (sources in ContactParameters)
#: Standard deviation σ_s of the tape's summit heights, m.
SUMMIT_ROUGHNESS = 6.0e-9
#: Radius β of the tape's summits, m.
ASPERITY_RADIUS = 10.0e-6
#: Summits per unit area η, 1/m²: η β σ_s = 0.04, in Greenwood & Williamson's 0.03–0.05.
ASPERITY_DENSITY = 6.7e11
#: Composite modulus E* of the tape's coating against the head, Pa.
CONTACT_MODULUS = 5.0e9
#: The hard wall's gap when none is given, m: the air film's roughness, the wall of old.
HARD_WALL_GAP = ROUGHNESS

#: Accepted ranges (SI): wide around tapes and heads, narrow enough that the pressure scale
#: (4/3) E* η √β σ_s^{3/2} stays a normal double.
ROUGHNESS_RANGE = (1e-12, 1e-4)          # m
ASPERITY_DENSITY_RANGE = (1.0, 1e20)     # 1/m² (1e20: 100 summits per nm²)
ASPERITY_RADIUS_RANGE = (1e-10, 1e-1)    # m
CONTACT_MODULUS_RANGE = (1e3, 1e13)      # Pa

#: The header line of a compliance CSV file.
COMPLIANCE_HEADER = ("separation_m", "pressure_Pa")

# ----- quadrature of F_n (module docstring) ----------------------------------------------------
_HERMITE_BELOW = -8.0       # Gauss–Hermite for t <= this
_LAGUERRE_FROM = 2.0        # Gauss–Laguerre for t >= this
_F_ZERO_BEYOND = 40.0       # F_n(t) = 0 (underflow) for t > this
_JACOBI_SPAN = 12.0         # U = max(-t, 0) + this: the Gaussian's tail beyond is e^-72
_JACOBI_NODES, _LAGUERRE_NODES, _HERMITE_NODES = 60, 40, 40
_CHUNK = 4096               # points a time: the (points x nodes) work arrays stay small
_SQRT_2PI = math.sqrt(2.0 * math.pi)


@functools.cache
def _rules(n: float):
    """The Hermite, Jacobi (weight (1+x)^n) and Laguerre (weight v^n e^-v) rules."""
    from scipy.special import roots_genlaguerre, roots_hermitenorm, roots_jacobi

    return (roots_hermitenorm(_HERMITE_NODES), roots_jacobi(_JACOBI_NODES, 0.0, n),
            roots_genlaguerre(_LAGUERRE_NODES, n))


def summit_integral(n: float, t) -> np.ndarray:
    """F_n(t) = (1/√(2π)) ∫_t^∞ (s − t)^n e^{−s²/2} ds, the GW integral of order n.

    Parameters
    ----------
    n : float
        The order: 1/2, 1 or 3/2 (the number of contacts, F_0, is
        ``scipy.special.ndtr(-t)``).
    t : float or array_like
        Separation over σ_s (dimensionless).

    Returns
    -------
    numpy.ndarray
        F_n(t), of the shape of t; relative accuracy about 5e-14 (module notes).

    Examples
    --------
    >>> round(float(summit_integral(1.5, 0.0)), 12)   # 2^{1/4} Γ(5/4) / √(2π)
    0.430019993662
    """
    if n not in (0.5, 1.0, 1.5):
        raise ParameterError(f"n must be 0.5, 1 or 1.5, got {n!r}")
    base = 1.0 if n == 1.0 else 0.5
    return _summits(t, base, (round(n - base),))[0]


def _summits(t, base: float, powers: tuple[int, ...]) -> list[np.ndarray]:
    """F_{base+k}(t) for k in ``powers``, one quadrature of weight u^base for them all (the
    integrand's extra u^k is smooth): F_{1/2} and F_{3/2} share their exponentials."""
    t = np.asarray(t, dtype=float)
    flat = t.ravel()
    out = [np.zeros(flat.shape) for _ in powers]
    for start in range(0, flat.size, _CHUNK):
        part = slice(start, start + _CHUNK)
        for o, value in zip(out, _summit_chunk(flat[part], base, powers), strict=True):
            o[part] = value
    return [o.reshape(t.shape) for o in out]


def _summit_chunk(t: np.ndarray, base: float, powers: tuple[int, ...]) -> list[np.ndarray]:
    (xh, wh), (xj, wj), (vl, wl) = _rules(base)
    out = [np.full(t.shape, np.nan) for _ in powers]
    low = t <= _HERMITE_BELOW
    mid = (t > _HERMITE_BELOW) & (t < _LAGUERRE_FROM)
    high = t >= _LAGUERRE_FROM
    beyond = t > _F_ZERO_BEYOND
    high &= ~beyond
    with np.errstate(under="ignore"):
        if low.any():
            gap = np.maximum(xh[None, :] - t[low, None], 0.0)
            root = gap ** base
            for o, k in zip(out, powers, strict=True):
                o[low] = (root * gap ** k) @ wh / _SQRT_2PI
        if mid.any():
            tm = t[mid, None]
            half = 0.5 * (np.maximum(-tm, 0.0) + _JACOBI_SPAN)
            u = half * (1.0 + xj[None, :])
            g = np.exp(-0.5 * (u + tm) ** 2)
            for o, k in zip(out, powers, strict=True):
                o[mid] = half[:, 0] ** (base + 1.0) * ((g * u ** k) @ wj) / _SQRT_2PI
        if high.any():
            th = t[high, None]
            g = np.exp(-0.5 * (vl[None, :] / th) ** 2)
            front = np.exp(-0.5 * th[:, 0] ** 2) / _SQRT_2PI
            for o, k in zip(out, powers, strict=True):
                o[high] = front * th[:, 0] ** (-base - k - 1.0) * ((g * vl ** k) @ wl)
    for o in out:
        o[beyond] = 0.0
    return out


def _scalar(a: np.ndarray):
    """A 0-d result as a NumPy scalar, an array as itself."""
    return a[()] if a.ndim == 0 else a


# ----- the asperity law --------------------------------------------------------------------------
@dataclass(frozen=True)
class GreenwoodWilliamson:
    """Greenwood–Williamson asperity contact of the tape's summits on a smooth head.

    Parameters
    ----------
    roughness : float
        Standard deviation σ_s of the summit heights, m, in [1e-12, 1e-4].
    asperity_density : float
        Summits per unit area η, 1/m², in [1, 1e20].
    asperity_radius : float
        Summit radius β, m, in [1e-10, 0.1].
    contact_modulus : float
        Composite (plane-strain) modulus E* = (Σ (1 − ν_i²)/E_i)^{−1}, Pa, in [1e3, 1e13].

    Notes
    -----
    d is the separation between the head and the mean plane of the summit heights, m;
    t = d/σ_s. Pressure p(d) = p_s F_{3/2}(t), p_s = (4/3) E* η √β σ_s^{3/2}; fraction of
    the nominal area in real contact π η β σ_s F_1(t); summits touching per unit area
    η F_0(t) (Greenwood & Williamson 1966, in this notation).

    Examples
    --------
    >>> law = GreenwoodWilliamson(6e-9, 6.7e11, 10e-6, 5e9)
    >>> p, dp = law.pressure(2 * 6e-9)
    >>> bool(p > 0 and dp < 0)
    True
    """

    roughness: float
    asperity_density: float
    asperity_radius: float
    contact_modulus: float

    kind = "asperity"

    def __post_init__(self) -> None:
        put = object.__setattr__
        for name, (low, high), unit in (
                ("roughness", ROUGHNESS_RANGE, "m"),
                ("asperity_density", ASPERITY_DENSITY_RANGE, "1/m^2"),
                ("asperity_radius", ASPERITY_RADIUS_RANGE, "m"),
                ("contact_modulus", CONTACT_MODULUS_RANGE, "Pa")):
            put(self, name, validation.real(name, getattr(self, name), low=low, high=high,
                                            unit=unit))
        validation.finite_scale(
            "pressure_scale", self.pressure_scale, "Pa",
            what="contact_modulus, asperity_density, asperity_radius and roughness")

    @property
    def pressure_scale(self) -> float:
        """p_s = (4/3) E* η √β σ_s^{3/2}, Pa: p(d) = p_s F_{3/2}(d/σ_s); p(0) ≈ 0.43 p_s."""
        return (4.0 / 3.0 * self.contact_modulus * self.asperity_density
                * math.sqrt(self.asperity_radius) * self.roughness ** 1.5)

    def pressure(self, separation):
        """Nominal contact pressure and its slope at a separation.

        Parameters
        ----------
        separation : float or array_like
            d, m, from the head to the mean plane of the summit heights (any real).

        Returns
        -------
        p : numpy.ndarray or float
            Pa, > 0 (0 once it underflows, d > 40 σ_s), decreasing in d.
        dp_dd : numpy.ndarray or float
            dp/dd, Pa/m, < 0: −(3/2) p_s F_{1/2}(d/σ_s) / σ_s.
        """
        t = np.asarray(separation, dtype=float) / self.roughness
        half, three_halves = _summits(t, 0.5, (0, 1))
        p = self.pressure_scale * three_halves
        dp = -1.5 * self.pressure_scale / self.roughness * half
        return _scalar(p), _scalar(dp)

    def real_area_fraction(self, separation):
        """Fraction of the nominal area in real contact, π η β σ_s F_1(d/σ_s) (GW's
        elastic area, which exceeds 1 only far beyond the model's validity)."""
        t = np.asarray(separation, dtype=float) / self.roughness
        return _scalar(math.pi * self.asperity_density * self.asperity_radius
                       * self.roughness * summit_integral(1.0, t))

    def asperity_count(self, separation):
        """Summits touching the head per unit area, 1/m²: η F_0(d/σ_s)."""
        from scipy.special import ndtr

        t = np.asarray(separation, dtype=float) / self.roughness
        return _scalar(self.asperity_density * ndtr(-t))

    def separation(self, pressure):
        """The separation d, m, at which the asperities carry ``pressure`` (Pa, > 0).

        Solves p(d) = pressure by Brent's method on the monotone F_{3/2}; d < 0 when the
        pressure exceeds p(0) ≈ 0.43 p_s.
        """
        from scipy.optimize import brentq

        values = np.asarray(pressure, dtype=float)
        out = np.empty(values.shape)
        for i, value in np.ndenumerate(values):
            target = validation.positive("pressure", float(value), "Pa") / self.pressure_scale
            # F_{3/2}(-a) >= a^{3/2} (Jensen), so t = -(target^{2/3} + 1) lies below the root
            low = -(target ** (2.0 / 3.0) + 1.0)
            out[i] = self.roughness * brentq(
                lambda t, target=target: float(summit_integral(1.5, t)) - target,
                low, _F_ZERO_BEYOND, xtol=1e-14, rtol=4 * np.finfo(float).eps)
        return _scalar(out)

    def to_dict(self) -> dict:
        """The parameters, SI numbers."""
        return {"roughness": self.roughness, "asperity_density": self.asperity_density,
                "asperity_radius": self.asperity_radius,
                "contact_modulus": self.contact_modulus}


# ----- the hard wall ---------------------------------------------------------------------------
@dataclass(frozen=True)
class HardWall:
    """A hard wall: the spacing h never falls below ``gap``; where it would, a contact force
    holds the tape at h = gap. The limit σ_s → 0 of :class:`GreenwoodWilliamson` at a
    fixed pressure scale. A bound on the spacing, so it has no pressure function.

    Parameters
    ----------
    gap : float
        m, in [1e-12, 1e-4].
    """

    gap: float = HARD_WALL_GAP

    kind = "hard"

    def __post_init__(self) -> None:
        object.__setattr__(self, "gap", validation.real(
            "gap", self.gap, low=ROUGHNESS_RANGE[0], high=ROUGHNESS_RANGE[1], unit="m"))

    def to_dict(self) -> dict:
        """The gap, m."""
        return {"gap": self.gap}


# ----- a measured compliance curve ---------------------------------------------------------------
class ComplianceCurve:
    """A measured curve of nominal contact pressure against separation.

    Parameters
    ----------
    separation : array_like
        Separations d_i, m, strictly increasing, at least 2.
    pressure : array_like
        Nominal pressures p_i, Pa, >= 0, non-increasing with d, not all equal.
    source : str, optional
        The file the points came from: refusals then raise
        :class:`~gyroshell.core.errors.InputFileError` naming it.

    Notes
    -----
    Between the points: the monotone C¹ piecewise-cubic Hermite interpolant of Fritsch &
    Carlson (PCHIP, :func:`pchip_slopes`); if the last pressure is 0 its end slope is set to 0, so
    that the curve meets p = 0 with zero slope (still monotone: a zero slope keeps the
    Fritsch–Carlson conditions). Beyond the table, both C¹:

    - d > d_n: 0 if p_n = 0; else p_n exp(s_n δ/p_n − (δ/Δ_n)²/2), δ = d − d_n, s_n the end
      slope, Δ_n the last interval: decays to 0 with a Gaussian tail even if s_n = 0.
    - d < d_0: p_0 + |s_0| δ + (K/Δ_0) δ², δ = d_0 − d, K the steepest secant stiffness of
      the table (Pa/m), Δ_0 the first interval: stiffens without bound, its stiffness
      growing by 2K every Δ_0, so Newton meets a wall however far the tape is pushed.
    """

    kind = "compliance"

    def __init__(self, separation, pressure, *, source: str | None = None) -> None:
        self.source = None if source is None else os.fspath(source)
        where = (f"{self.source}: " if self.source is not None else "compliance curve: ")
        error = InputFileError if self.source is not None else ParameterError
        self.separations, self.pressures = _checked_points(separation, pressure, where, error)
        self._build()

    def _build(self) -> None:
        for a in (self.separations, self.pressures):
            a.setflags(write=False)
        d, p = self.separations, self.pressures
        widths = np.diff(d)
        slopes = pchip_slopes(d, p)
        if p[-1] == 0.0:
            slopes[-1] = 0.0
        self._slopes, self._widths = slopes, widths
        self._stiffness = float(np.max(-np.diff(p) / widths))

    @classmethod
    def from_csv(cls, path: str | os.PathLike[str]) -> ComplianceCurve:
        """The curve of a CSV file: the header line ``separation_m,pressure_Pa``, then one
        row of two numbers (m, Pa) per point; blank lines are skipped.

        Raises
        ------
        InputFileError
            One line naming the file and what is wrong: missing, a folder, not UTF-8 text,
            no header or another header, a row that is not two numbers, no rows or one, a
            NaN or infinite value, separations not strictly increasing, a negative
            pressure, pressures increasing with separation or all equal.
        """
        from ..core.files import read_input

        name = os.fspath(path)
        raw = read_input(name, what="compliance CSV file")
        try:
            text = raw.decode("utf-8-sig")
        except UnicodeDecodeError as exc:
            raise InputFileError(f"{name}: cannot be read as UTF-8 text ({exc})") from None
        lines = [(i + 1, row) for i, row in enumerate(csv.reader(io.StringIO(text)))
                 if any(cell.strip() for cell in row)]
        header = ",".join(COMPLIANCE_HEADER)
        if not lines:
            raise InputFileError(f"{name}: the compliance table is empty (want the header "
                                 f"{header} and at least 2 rows)")
        first = [cell.strip() for cell in lines[0][1]]
        if tuple(first) != COMPLIANCE_HEADER:
            if _numbers(first) is not None:
                raise InputFileError(f"{name}: no header: the first line must be {header}, "
                                     f"got the numbers {','.join(first)}")
            raise InputFileError(f"{name}: the header must be {header}, got "
                                 f"{','.join(first)}")
        rows = []
        for number, row in lines[1:]:
            values = _numbers([cell.strip() for cell in row])
            if values is None or len(values) != 2:
                raise InputFileError(f"{name}: line {number} must be 2 numbers ({header}), "
                                     f"got {','.join(row)[:60]!r}")
            rows.append(values)
        table = np.array(rows, dtype=float).reshape(-1, 2)
        return cls(table[:, 0], table[:, 1], source=name)

    @classmethod
    def from_dict(cls, data: Mapping) -> ComplianceCurve:
        """The curve of :meth:`to_dict` (points in SI)."""
        if not isinstance(data, Mapping):
            raise ParameterError(f"a compliance curve must be a table of {COMPLIANCE_HEADER[0]}"
                                 f" and {COMPLIANCE_HEADER[1]}, got {type(data).__name__}")
        allowed = (*COMPLIANCE_HEADER, "source")
        unknown = sorted(set(data) - set(allowed))
        missing = [key for key in COMPLIANCE_HEADER if key not in data]
        if unknown or missing:
            what = (f"unknown key(s) {', '.join(unknown)}" if unknown
                    else f"missing {', '.join(missing)}")
            raise ParameterError(f"compliance curve: {what}; allowed: {', '.join(allowed)}")
        try:
            d = np.array(data[COMPLIANCE_HEADER[0]], dtype=float)
            p = np.array(data[COMPLIANCE_HEADER[1]], dtype=float)
        except (TypeError, ValueError):
            raise ParameterError(f"compliance curve: {COMPLIANCE_HEADER[0]} and "
                                 f"{COMPLIANCE_HEADER[1]} must be lists of numbers") from None
        source = data.get("source")
        if source is not None:
            source = validation.instance("source", source, str)
        curve = cls.__new__(cls)
        curve.source = source
        where = "compliance curve" + (f" (from {source})" if source else "") + ": "
        curve.separations, curve.pressures = _checked_points(d, p, where, ParameterError)
        curve._build()
        return curve

    def to_dict(self) -> dict:
        """The points (lists of floats, m and Pa) and the source file, if any."""
        out = {COMPLIANCE_HEADER[0]: self.separations.tolist(),
               COMPLIANCE_HEADER[1]: self.pressures.tolist()}
        if self.source is not None:
            out["source"] = self.source
        return out

    def pressure(self, separation):
        """Nominal contact pressure and its slope at a separation.

        Parameters
        ----------
        separation : float or array_like
            d, m (any real: the curve is extended beyond the table, see the class notes).

        Returns
        -------
        p : numpy.ndarray or float
            Pa, >= 0, non-increasing in d; equal to the table at its points.
        dp_dd : numpy.ndarray or float
            dp/dd, Pa/m, <= 0, continuous.
        """
        d = np.asarray(separation, dtype=float)
        d0, dn = float(self.separations[0]), float(self.separations[-1])
        p0, pn = float(self.pressures[0]), float(self.pressures[-1])
        s0, sn = float(self._slopes[0]), float(self._slopes[-1])
        w0, wn = float(self._widths[0]), float(self._widths[-1])
        p, dp = np.zeros(d.shape), np.zeros(d.shape)
        inside = (d >= d0) & (d <= dn)
        if inside.any():
            p[inside], dp[inside] = self._hermite(d[inside])
        below = d < d0
        if below.any():
            delta = d0 - d[below]
            p[below] = p0 + abs(s0) * delta + self._stiffness / w0 * delta ** 2
            dp[below] = -(abs(s0) + 2.0 * self._stiffness / w0 * delta)
        above = d > dn
        if above.any() and pn > 0.0:
            delta = d[above] - dn
            with np.errstate(under="ignore"):
                p[above] = pn * np.exp(sn * delta / pn - 0.5 * (delta / wn) ** 2)
            dp[above] = p[above] * (sn / pn - delta / wn ** 2)
        nan = np.isnan(d)
        p[nan] = dp[nan] = np.nan
        return _scalar(p), _scalar(dp)

    def _hermite(self, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The cubic Hermite interpolant and its slope at d inside the table, in the basis
        form, which gives the table's value and slope exactly at its points."""
        knots, values, slopes, widths = (self.separations, self.pressures, self._slopes,
                                         self._widths)
        i = np.clip(np.searchsorted(knots, d, side="right") - 1, 0, len(knots) - 2)
        h = widths[i]
        s = (d - knots[i]) / h
        r = 1.0 - s
        p = (values[i] * (1.0 + 2.0 * s) * r * r + h * slopes[i] * s * r * r
             + values[i + 1] * s * s * (3.0 - 2.0 * s) - h * slopes[i + 1] * s * s * r)
        dp = (6.0 * s * r * (values[i + 1] - values[i]) / h + slopes[i] * r * (1.0 - 3.0 * s)
              + slopes[i + 1] * s * (3.0 * s - 2.0))
        return p, dp

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, ComplianceCurve):
            return NotImplemented
        return (np.array_equal(self.separations, other.separations)
                and np.array_equal(self.pressures, other.pressures))

    def __hash__(self) -> int:
        return hash((self.separations.tobytes(), self.pressures.tobytes()))

    def __repr__(self) -> str:
        source = f", source={self.source!r}" if self.source else ""
        return (f"ComplianceCurve({len(self.separations)} points, d in "
                f"[{self.separations[0]:g}, {self.separations[-1]:g}] m{source})")

    def __getstate__(self) -> dict:
        return {"separations": self.separations, "pressures": self.pressures,
                "source": self.source}

    def __setstate__(self, state: dict) -> None:
        self.separations, self.pressures = state["separations"], state["pressures"]
        self.source = state["source"]
        self._build()


def pchip_slopes(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The slopes of the monotone piecewise-cubic Hermite interpolant at its points
    (Fritsch & Carlson, SIAM J. Numer. Anal. 17:238, 1980, with Fritsch & Butland's weighted
    harmonic mean, as SLATEC's PCHIM and scipy's ``PchipInterpolator``): 0 at a local
    extremum or a flat neighbour, the three-point shape-preserving formula at the ends.

    Parameters
    ----------
    x : numpy.ndarray
        Strictly increasing abscissae, at least 2.
    y : numpy.ndarray
        Values at x.
    """
    h = np.diff(x)
    m = np.diff(y) / h
    slopes = np.empty(len(x))
    if len(x) == 2:
        slopes[:] = m[0]
        return slopes
    w1, w2 = 2.0 * h[1:] + h[:-1], h[1:] + 2.0 * h[:-1]
    same = m[:-1] * m[1:] > 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        mean = (w1 + w2) / (w1 / m[:-1] + w2 / m[1:])
    slopes[1:-1] = np.where(same, mean, 0.0)
    slopes[0] = _end_slope(h[0], h[1], m[0], m[1])
    slopes[-1] = _end_slope(h[-1], h[-2], m[-1], m[-2])
    return slopes


def _end_slope(h0: float, h1: float, m0: float, m1: float) -> float:
    """The shape-preserving three-point end slope of PCHIP."""
    s = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
    if np.sign(s) != np.sign(m0):
        return 0.0
    if np.sign(m0) != np.sign(m1) and abs(s) > abs(3.0 * m0):
        return 3.0 * m0
    return float(s)


def _numbers(cells: list[str]) -> list[float] | None:
    try:
        return [float(cell) for cell in cells]
    except ValueError:
        return None


def _checked_points(separation, pressure, where: str, error: type[ParameterError]):
    """(d, p) as float arrays, or ``error`` with one line starting with ``where``."""
    d_name, p_name = COMPLIANCE_HEADER
    try:
        d = np.array(separation, dtype=float).ravel()
        p = np.array(pressure, dtype=float).ravel()
    except (TypeError, ValueError):
        raise error(f"{where}{d_name} and {p_name} must be numbers") from None
    if d.size != p.size:
        raise error(f"{where}{d_name} and {p_name} must have one value per point, got "
                    f"{d.size} and {p.size}")
    if d.size == 0:
        raise error(f"{where}the compliance table is empty (want at least 2 points)")
    if d.size < 2:
        raise error(f"{where}a compliance curve needs at least 2 points, got 1")
    bad = ~(np.isfinite(d) & np.isfinite(p))
    if bad.any():
        i = int(np.argmax(bad))
        raise error(f"{where}point {i + 1} is not finite: {d_name} {d[i]}, {p_name} {p[i]}")
    if (p < 0).any():
        i = int(np.argmax(p < 0))
        raise error(f"{where}{p_name} must be >= 0, point {i + 1} has {p[i]:g}")
    steps = np.diff(d)
    if (steps <= 0).any():
        i = int(np.argmax(steps <= 0))
        raise error(f"{where}{d_name} must increase strictly, point {i + 2} ({d[i + 1]:g}) "
                    f"follows {d[i]:g}")
    rises = np.diff(p) > 0
    if rises.any():
        i = int(np.argmax(rises))
        raise error(f"{where}{p_name} must not increase with separation (a compliance curve "
                    f"is monotone), point {i + 2} ({p[i + 1]:g}) follows {p[i]:g}")
    if p[0] == p[-1]:
        raise error(f"{where}{p_name} is {p[0]:g} at every point: a compliance curve must "
                    "fall with separation")
    return d, p


# ----- the parameters a user states --------------------------------------------------------
#: The fields each law uses.
_LAW_FIELDS: dict[str, tuple[str, ...]] = {
    "asperity": ("roughness", "asperity_density", "asperity_radius", "contact_modulus"),
    "hard": ("roughness",),
    "compliance": ("compliance",),
}
#: Each law's defaults of its fields (compliance has none: it must be given).
_DEFAULTS: dict[str, dict[str, float]] = {
    "asperity": {"roughness": SUMMIT_ROUGHNESS, "asperity_density": ASPERITY_DENSITY,
                 "asperity_radius": ASPERITY_RADIUS, "contact_modulus": CONTACT_MODULUS},
    "hard": {"roughness": HARD_WALL_GAP},
    "compliance": {},
}
#: SI unit of each number of a ``[contact]`` table.
_UNITS = {"roughness": "m", "asperity_radius": "m", "contact_modulus": "Pa"}
#: Units a ``[contact]`` table may give asperity_density in, with factors to 1/m².
_DENSITY_UNITS = {"1/m^2": 1.0, "1/mm^2": 1e6, "1/um^2": 1e12, "1/µm^2": 1e12,
                  "1/μm^2": 1e12}


@dataclass(frozen=True)
class ContactParameters:
    """How the tape touches the head: the contact law and its parameters (SI).

    A field left ``None`` takes its law's default; a field the chosen law does not use must
    stay ``None`` (``law="hard"`` with ``asperity_density`` set is refused), so every value
    a user gives is one that acts. After construction the law's fields hold numbers and
    the others ``None``.

    Parameters
    ----------
    law : str
        One of :data:`CONTACT_LAWS`: ``"asperity"`` (default), ``"hard"``, ``"compliance"``.
    roughness : float, optional
        ``"asperity"``: σ_s, the standard deviation of the tape's summit heights, m
        (default :data:`SUMMIT_ROUGHNESS`, 6 nm). ``"hard"``: the wall's gap, m (default
        :data:`HARD_WALL_GAP`, 20 nm, the air film's ``roughness``). In [1e-12, 1e-4].
    asperity_density : float, optional
        ``"asperity"``: summits per unit area η, 1/m² (default 6.7e11), in [1, 1e20].
    asperity_radius : float, optional
        ``"asperity"``: summit radius β, m (default 10 µm), in [1e-10, 0.1].
    contact_modulus : float, optional
        ``"asperity"``: composite modulus E*, Pa (default 5 GPa), in [1e3, 1e13].
    compliance : ComplianceCurve, optional
        ``"compliance"``: the measured curve (required).

    Notes
    -----
    The asperity defaults describe a modern thin particulate (BaFe or MP) data tape on a
    lapped ceramic head. No source found tabulates all four numbers for today's tapes, so
    each is a stated assumption, placed by the published work below:

    - σ_s = 6 nm (assumed): summit heights of a modern data tape, 5–10 nm. Data tapes run at
      h/σ >= 4 and their roughness limits the spacing (Bhushan & Tønder, J. Tribol.
      111:228, 1989; Wu & Talke, J. Tribol. 118:376, 1996, who fitted GW to measured tape
      compliance curves); smoother media are the route to lower magnetic spacing (IBM
      Research Zurich, BaFe prototype media). Summit deviation taken ≈ the surface rms.
    - β = 10 µm (assumed): summits of micrometre lateral scale, the scale that deforms
      elastically (Oden, Majumdar, Bhushan et al., J. Tribol. 114:666, 1992: the tape's
      curvatures depend strongly on the instrument's resolution; nanometre-scale
      asperities deform plastically, micrometre-scale ones elastically).
    - η = 6.7e11 1/m² (0.67 per µm²): from η β σ_s = 0.04, inside the 0.03–0.05 Greenwood
      & Williamson (1966) found for real surfaces.
    - E* = 5 GPa (assumed): the order of a particulate coating's modulus (nanoindentation
      of tape layers: Li & Bhushan, Scripta Materialia, 2000, pp. 929–935; flexible media
      generally: Bhushan, *Mechanics and Reliability of Flexible Magnetic Media*, 2nd ed.,
      2000), ν ≈ 0.3, the head (AlTiC, ~400 GPa) taken rigid. Such tape contacts are
      elastic, GW's assumption (Bhushan, J. Tribol. 106:26, 1984).

    With these p_s = (4/3) E* η √β σ_s^{3/2} ≈ 6.6 MPa, and a land load of 10–100 kPa
    (sub-ambient film and wrap) rests at d ≈ 1.6–2.5 σ_s, near the h/σ_s ≈ 2–3 at which an
    independent 1-D solver found a flat land resting on its asperities. For a given tape use
    its measured values, or give its measured curve (``law="compliance"``).

    Examples
    --------
    >>> ContactParameters().law_object.roughness
    6e-09
    >>> ContactParameters(law="hard", asperity_density=1e12)
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: asperity_density applies to contact='asperity' only, ...
    """

    law: str = "asperity"
    roughness: float | None = None
    asperity_density: float | None = None
    asperity_radius: float | None = None
    contact_modulus: float | None = None
    compliance: ComplianceCurve | None = None
    _law: object = field(default=None, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        law = validation.choice("contact", self.law, CONTACT_LAWS)
        used = _LAW_FIELDS[law]
        for name in _ALL_FIELDS:
            if name not in used and getattr(self, name) is not None:
                owners = [k for k, names in _LAW_FIELDS.items() if name in names]
                them = " or ".join(repr(k) for k in owners)
                raise ParameterError(
                    f"{name} applies to contact={them} only, and this contact is {law!r}: "
                    f"drop {name} or choose contact={owners[0]!r}")
        put = object.__setattr__
        for name, value in _DEFAULTS[law].items():
            if getattr(self, name) is None:
                put(self, name, value)
        if law == "compliance":
            if self.compliance is None:
                raise ParameterError("contact='compliance' needs its curve: give compliance "
                                     "(a ComplianceCurve, or a CSV file of separation_m, "
                                     "pressure_Pa)")
            validation.instance("compliance", self.compliance, ComplianceCurve)
            put(self, "_law", self.compliance)
        elif law == "hard":
            gap = validation.real("roughness", self.roughness, low=ROUGHNESS_RANGE[0],
                                  high=ROUGHNESS_RANGE[1], unit="m")
            put(self, "roughness", gap)
            put(self, "_law", HardWall(gap))
        else:
            put(self, "_law", GreenwoodWilliamson(self.roughness, self.asperity_density,
                                                  self.asperity_radius, self.contact_modulus))
            for name in used:
                put(self, name, getattr(self._law, name))

    @property
    def law_object(self) -> GreenwoodWilliamson | HardWall | ComplianceCurve:
        """The law itself: :class:`GreenwoodWilliamson`, :class:`HardWall` or
        :class:`ComplianceCurve` (each has ``kind``, the law's name)."""
        return self._law

    @property
    def smooth(self) -> bool:
        """True when the law is a pressure function (``pressure(d) -> (p, dp_dd)``), False
        for the hard wall (a bound on the spacing)."""
        return self.law != "hard"

    def pressure(self, separation):
        """The law's ``pressure(separation) -> (p, dp_dd)``, Pa and Pa/m (not for "hard")."""
        if not self.smooth:
            raise ParameterError("contact='hard' is a bound on the spacing (h >= gap), not a "
                                 "pressure function")
        return self._law.pressure(separation)

    def replace(self, **changes) -> ContactParameters:
        """A copy with ``changes``, checked again. Changing the law starts from the new
        law's defaults: the old law's values are dropped unless given again."""
        unknown = sorted(set(changes) - {"law", *_ALL_FIELDS})
        if unknown:
            raise ParameterError(f"contact parameters have no {', '.join(unknown)}; allowed: "
                                 f"law, {', '.join(_ALL_FIELDS)}")
        if "law" in changes and changes["law"] != self.law:
            base = dict.fromkeys(_ALL_FIELDS)
        else:
            base = {name: getattr(self, name) for name in _ALL_FIELDS}
        base.update(changes)
        return ContactParameters(**{"law": self.law, **base})

    def to_dict(self) -> dict:
        """``law`` and the law's parameters, SI numbers; the compliance curve as its points
        (:meth:`ComplianceCurve.to_dict`). :meth:`from_dict` reads it back."""
        out: dict = {"law": self.law}
        for name in _LAW_FIELDS[self.law]:
            value = getattr(self, name)
            out[name] = value.to_dict() if isinstance(value, ComplianceCurve) else value
        return out

    @classmethod
    def from_dict(cls, data: Mapping) -> ContactParameters:
        """The parameters of :meth:`to_dict` (a saved result), checked.

        Raises
        ------
        ParameterError
            Unknown keys (naming them and the allowed ones), a parameter of another law,
            a value out of range.
        """
        fields = _known_keys(data, "contact parameters: ")
        if isinstance(fields.get("compliance"), Mapping):
            fields["compliance"] = ComplianceCurve.from_dict(fields["compliance"])
        return cls(**fields)

    @classmethod
    def from_table(cls, table: Mapping, base_dir: str | os.PathLike[str] | None = None, *,
                   where: str = "") -> ContactParameters:
        """The parameters of a ``[contact]`` table of a TOML file.

        The table reads, for example::

            [contact]
            law = "asperity"            # "asperity" (default), "hard" or "compliance"
            roughness = "6 nm"          # numbers without a unit are SI
            asperity_density = 6.7e11   # 1/m^2, or "0.67 1/um^2"
            asperity_radius = "10 um"
            contact_modulus = "5 GPa"
            # compliance = "tape.csv"   # law = "compliance": the curve's CSV file

        Parameters
        ----------
        table : mapping
            The table as ``tomllib`` parsed it.
        base_dir : path, optional
            The TOML file's folder: a relative ``compliance`` path is read from there.
        where : str
            The file, as messages name it (``"run.toml: "``).

        Raises
        ------
        ParameterError
            One line naming the file and the key: an unknown key (and the allowed ones), a
            value of the wrong type, unit or range, a parameter of another law;
            InputFileError for a bad compliance file.
        """
        from ..tape.config import parse_quantity

        prefix = f"{where}[contact] "
        if not isinstance(table, Mapping):
            raise ParameterError(f"{prefix.rstrip()} must be a table")
        fields = _known_keys(table, prefix)
        for key, value in list(fields.items()):
            if key == "law":
                if not isinstance(value, str):
                    raise ParameterError(f"{prefix}law must be text, one of "
                                         f"{', '.join(CONTACT_LAWS)}, got {value!r}")
            elif key == "compliance":
                if not isinstance(value, str):
                    raise ParameterError(f"{prefix}compliance must be the path of a CSV file "
                                         f"({','.join(COMPLIANCE_HEADER)}), got {value!r}")
                path = Path(value)
                if base_dir is not None and not path.is_absolute():
                    path = Path(base_dir) / path
                fields[key] = ComplianceCurve.from_csv(path)
            elif key == "asperity_density":
                fields[key] = _density(value, prefix)
            else:
                fields[key] = parse_quantity(key, value, prefix, unit=_UNITS[key])
        try:
            return cls(**fields)
        except InputFileError:
            raise
        except ParameterError as exc:
            raise type(exc)(f"{prefix}{exc}") from None


_ALL_FIELDS: tuple[str, ...] = ("roughness", "asperity_density", "asperity_radius",
                                "contact_modulus", "compliance")


def _known_keys(data: object, prefix: str) -> dict:
    if not isinstance(data, Mapping):
        raise ParameterError(f"{prefix}must be a table of law and its parameters, got "
                             f"{type(data).__name__}")
    allowed = ("law", *_ALL_FIELDS)
    unknown = sorted(set(data) - set(allowed))
    if unknown:
        raise ParameterError(f"{prefix}unknown key(s) {', '.join(map(str, unknown))}; "
                             f"allowed: {', '.join(allowed)}")
    return dict(data)


def _density(value: object, prefix: str) -> float:
    """asperity_density of a table: a number (1/m²) or ``"<number> 1/um^2"``."""
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        raise ParameterError(f"{prefix}asperity_density must be a number (1/m^2) or "
                             f"'<number> <unit>', got {value!r}")
    if not isinstance(value, str):
        return float(value)
    number, _, unit = value.strip().partition(" ")
    unit = unit.strip()
    try:
        factor = _DENSITY_UNITS[unit]
        return float(number) * factor
    except (KeyError, ValueError):
        raise ParameterError(f"{prefix}asperity_density must look like '<number> <unit>' with "
                             f"a unit of {', '.join(_DENSITY_UNITS)}, got {value!r}") from None
