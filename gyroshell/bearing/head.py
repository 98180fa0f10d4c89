"""Head contours: the surface under the tape and the dry string configuration over it.

Head coordinates: x (m) from the head's middle, the tape moving along +x (the leading,
entry corner at negative x); z (m) upward from the head, the tape above it; y (m) across
the tape from its lower edge. Angles in rad. Three kinds of head:

* :class:`Cylinder` (``kind = "cylinder"``): today's head, a cylinder of radius R (the
  tape's own radius by default) wrapped over the total angle θ, in the shallow-shell
  approximation z_h = −x²/(2R); its middle is the middle of the arc.
* :class:`FlatHead` (``"flat"``): 1 to 8 flat :class:`Module` lands in a row, each between
  two corners (sharp, or rounded with a radius r_c), set at its own height and tilt, with
  gaps between modules; beyond each corner the head falls away along a flank at
  ``flank_angle`` below the land. The tape arrives along a straight span at ``wrap_in``
  below the x-axis and leaves at ``wrap_out``. The middle (x = 0) lies half way between
  the first leading and the last trailing corner.
* :class:`ProfileHead` (``"profile"``): a measured contour z(x) or z(x, y) (a
  profilometer's CSV), interpolated linearly; beyond the measured range the head falls
  away at 20°. Its x is stored shifted so that the middle of the wrapped region (where
  the dry tape first and last touches it) is x = 0.

How the tape's reference follows the contour (the bearing's model, :mod:`.model`):

* **Reference geometry.** The dry string configuration z₀(x) (:meth:`Head.dry_tape`) is
  the smallest concave function on or above the contour whose slopes far away are
  +wrap_in (left) and −wrap_out (right): the straight spans and, between them, the
  concave envelope of the contour (of max_y z_h over a 2-D contour). The tape's
  displacement is measured from it (w = z₀ + u) and the dry gap w₀ = z₀ − z_h ≥ 0
  (:meth:`Head.dry_gap`) starts the spacing h = w₀ + u.
* **Wrap load.** The curvature κ = −δ²z₀ (:meth:`Head.dry_curvature`, the tape's own
  discrete second difference) gives the load (T − ρV²) W κ and the bending reference: the
  cylinder's κ = 1/R on the wrap; on a flat land κ = 0; at a sharp corner on a node a
  discrete delta θ_c / w_i, so that (T − ρV²) W κ is the corner's point load (T − ρV²) θ_c
  per unit width; on a rounded corner 1/r_c over the wrapped arc r_c θ_c.
* **Shell stiffness k** (:meth:`Head.foundation_stiffness`). A wrapped shell of radius R
  resists departures from its wrapped shape with the hoop stiffness k = E c/(R²(1 − ν²)):
  the cylinder keeps ``params.k`` over the whole domain, as before, its straight spans
  included, where it holds the tape up with about k R² ε (ε = 6μ|V|/(T − ρV²)). That is
  small against the wrap load (T − ρV²) θ only for θ above
  :meth:`~.model.BearingModel.smallest_valid_wrap`, 23 (ℓ_film/R)(ℓ_film/ℓ_k)²
  (ℓ_film = R ε^(1/3), ℓ_k = √((T − ρV²)/k); 6.2° for the Table 1 tape at 4 m/s);
  below it the spacing comes out too low and the model warns. A flat land has no
  wrap curvature, so a tape lying on it has no hoop stiffness; the corners' wrapped arcs
  r_c θ_c are mostly far shorter than the bending length √(D/T), so their hoop stiffness
  acts over a negligible length. Flat and profile heads therefore use k =
  ``foundation_stiffness`` when the user gave one, else 0 (also over an arc the tape wraps,
  whose hoop stiffness E c/(r_c²(1 − ν²)) is then neglected).
* **Rounded corners.** An arc short against the bending length ℓ_bend = √(D/(T − ρV²))
  (r_c θ_c <= 0.3 ℓ_bend) is touched at one tangent point (a node there, found by
  regridding: :mod:`.corners`); a longer one is wrapped: the tape lies on it but for about
  ℓ_bend at each end, with the contact pressure T/r_c and a point force D/(r_c ℓ_bend) at
  each end of the contact, and its arc nodes join the bearing's general contact set
  (:func:`.model.wrapped_corners`; ``BearingModel(arc_contact=...)`` forces either).
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, field

import numpy as np

from ..core import budget, validation
from ..core.errors import InputFileError, ParameterError
from ..core.files import check_input

#: Largest wrap angle at either end of a flat or profile head, rad (small slopes).
MAX_SIDE_WRAP = math.radians(45.0)
#: Largest total wrap of a cylinder, rad (the shallow-shell gap).
MAX_CYLINDER_WRAP = math.radians(90.0)
#: Most modules on a flat head.
MAX_MODULES = 8
#: Largest tilt of a land, rad (small slopes).
MAX_TILT = math.radians(10.0)
#: How the tape may meet a rounded corner (``BearingModel(arc_contact=...)``, the CLI's
#: ``--arc-contact``): per corner by its arc's length, at one tangent point, or wrapped.
ARC_CONTACTS = ("auto", "point", "wrapped")
#: A rounded corner whose wrapped arc r_c θ_c is at most this many bending lengths
#: ℓ_bend = √(D/(T − ρV²)) is touched at one point (the tangent-point model,
#: :mod:`.corners`); a longer one is wrapped: its arc nodes join the general contact set
#: (any node may touch, as on the cylinder) and the tape lies on the arc over part of it.
#: For a plate between a long land and a long span the tape touches at one point while
#: its curvature there, about θ_c/(2ℓ_bend), is below the arc's 1/r_c, i.e. up to
#: r_c θ_c = 2 ℓ_bend, where the wrapped contact has shrunk to that point: both models
#: hold below 2 and agree there (tests/bearing/test_wrapped_arcs.py); the handover is
#: made well inside that range, where the tangent point is still second order and the
#: general contact set already resolves the arc.
WRAPPED_ARC_BENDING_LENGTHS = 0.3
#: Beyond each corner of a flat head the head falls away along a flank at this angle below
#: the land, rad, unless the head says otherwise (``FlatHead(flank_angle=...)``).
DEFAULT_FLANK_ANGLE = math.radians(20.0)
#: Beyond a measured profile the head falls away at this angle, rad.
PROFILE_FALLOFF = math.radians(20.0)
#: Samples along each rounded corner's arc for the dry envelope (its chords lie within
#: (r φ / n)² / (8 r) of the arc, picometres; the envelope is then raised onto the arc).
ARC_SAMPLES = 2049
#: A corner whose turn is below this fraction of the total wrap does not set the default
#: grid's resolution; a profile's envelope vertex is a corner when the tape turns there by
#: at least this fraction of the wrap ...
CORNER_FRACTION = 0.05
#: ... and a sharp corner (a node is put on it) when by at least this fraction (a rounded
#: contour spreads its turn over many samples).
PROFILE_SHARP_FRACTION = 0.25
#: Fewest samples of a measured profile along x, and across y for an (x, y, z) profile.
MIN_PROFILE_POINTS = 4
MIN_PROFILE_COLUMNS = 2
#: Longest measured profile along x, m: longer than any head (a few cm at most), shorter than
#: a profile of one written in mm (a 2 mm contour would read 2 m).
MAX_PROFILE_LENGTH = 0.1
#: Bytes of memory a CSV file's byte costs when read whole (its text, the parsed rows and
#: the float array), generously.
CSV_BYTES_PER_BYTE = 16.0
#: Relative tolerance of geometric checks (overlaps, wrapped region), of the head's extent.
GEOMETRY_TOLERANCE = 1e-9


def _floats(name: str, values, unit: str) -> tuple[float, ...]:
    """A tuple of finite floats (one value is accepted as a 1-tuple)."""
    if isinstance(values, (int, float, np.floating, np.integer)) and not isinstance(
            values, bool):
        values = (values,)
    try:
        items = tuple(values)
    except TypeError:
        raise ParameterError(f"{name} must be a sequence of numbers in {unit}, got "
                             f"{values!r}") from None
    return tuple(validation.real(f"{name}[{i}]", v, unit=unit) for i, v in enumerate(items))


def _side_wrap(name: str, value) -> float:
    return validation.real(name, value, low=0.0, high=MAX_SIDE_WRAP, unit="rad")


def _friction(value) -> float:
    return validation.nonnegative("friction", value)


def _check_transducers(head, transducers, radius=None) -> tuple[float, ...]:
    """The transducer lines x_t (m), each on the wrapped region [x_first, x_last] and on
    one of the head's lands (not in a gap between two modules, where the spacing read is
    the gap's depth)."""
    xs = _floats("transducers", transducers, "m")
    lo, hi = head.extent(radius)
    tol = GEOMETRY_TOLERANCE * (hi - lo)
    lands = head.lands(radius)
    for i, xt in enumerate(xs):
        if not lo - tol <= xt <= hi + tol:
            raise ParameterError(
                f"transducers[{i}] must lie on the head's wrapped region [{lo:.6g}, "
                f"{hi:.6g}] m (head coordinates, from its middle), got {xt:g}")
        if not any(a - tol <= xt <= b + tol for a, b in lands):
            spans = ", ".join(f"[{a:.6g}, {b:.6g}]" for a, b in lands)
            raise ParameterError(
                f"transducers[{i}] must lie on a land of the head ({spans} m, from its "
                f"middle), got {xt:g}: it is in a gap between modules")
    return xs


class _Envelope:
    """The smallest concave function above the points (t, z) with slopes s_left far left
    and s_right far right: the upper hull of the points between the tangent spans."""

    def __init__(self, t: np.ndarray, z: np.ndarray, s_left: float, s_right: float) -> None:
        # sorted by t: a module's flank samples may reach past the next module's start
        order = np.argsort(np.asarray(t, float), kind="stable")
        vx, vz = _upper_hull(np.asarray(t, float)[order], np.asarray(z, float)[order])
        slopes = np.diff(vz) / np.diff(vx)
        first = int(np.searchsorted(-slopes, -s_left, side="left"))    # slope <= s_left
        last = len(vx) - 1 - int(np.searchsorted(slopes[::-1], s_right, side="left"))
        last = max(last, first)
        self.vx, self.vz = vx[first:last + 1], vz[first:last + 1]
        self.slopes = np.concatenate([[s_left], slopes[first:last], [s_right]])
        self.touched_ends = (first == 0, last == len(vx) - 1)

    def __call__(self, x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        inside = np.interp(x, self.vx, self.vz)
        left = self.vz[0] + self.slopes[0] * (x - self.vx[0])
        right = self.vz[-1] + self.slopes[-1] * (x - self.vx[-1])
        return np.where(x < self.vx[0], left, np.where(x > self.vx[-1], right, inside))

    @property
    def turns(self) -> np.ndarray:
        """The tape's turn at each hull vertex, rad (slope before minus slope after)."""
        return self.slopes[:-1] - self.slopes[1:]


def _upper_hull(t: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Vertices of the upper convex hull of points sorted by t (monotone chain)."""
    keep: list[int] = []
    for i in range(len(t)):
        while len(keep) >= 2:
            a, b = keep[-2], keep[-1]
            cross = (t[b] - t[a]) * (z[i] - z[a]) - (z[b] - z[a]) * (t[i] - t[a])
            if cross >= 0.0:        # b lies on or below the chord a–i
                keep.pop()
            else:
                break
        keep.append(i)
    idx = np.array(keep)
    return t[idx], z[idx]


def _second_difference_curvature(x: np.ndarray, z: np.ndarray) -> np.ndarray:
    """−δ²z at the interior nodes of the abscissae x (the tape's second difference)."""
    h = np.diff(x)
    return -np.diff(np.diff(z) / h) / (0.5 * (h[:-1] + h[1:]))


class Head:
    """What every head provides (see the module notes); subclasses are dataclasses."""

    kind: str = ""
    transducers: tuple[float, ...] = ()
    friction: float = 0.0

    # --- to be provided by each kind -------------------------------------------------
    def extent(self, radius: float | None = None) -> tuple[float, float]:
        """(x_first, x_last), m: the wrapped region."""
        raise NotImplementedError

    def surface(self, x, y=None, radius: float | None = None) -> np.ndarray:
        """The head's height z_h, m, at x (and y: shape (len(x), len(y)))."""
        raise NotImplementedError

    def dry_tape(self, x, radius: float | None = None) -> np.ndarray:
        """The dry string configuration z₀(x), m (see the module notes)."""
        raise NotImplementedError

    def corners(self, radius: float | None = None) -> tuple[float, ...]:
        """Every corner's x, m (the cylinder's two tangent points)."""
        raise NotImplementedError

    def sharp_corners(self, radius: float | None = None) -> tuple[float, ...]:
        """The corners where z₀ has a kink, m: the bearing's grid puts a node on each."""
        return ()

    def lands(self, radius: float | None = None) -> tuple[tuple[float, float], ...]:
        """The lands (x_start, x_end), m (the cylinder: its arc)."""
        raise NotImplementedError

    def corner_turns(self, radius: float | None = None) -> tuple[float, ...]:
        """The tape's dry turn θ_c at each corner of :meth:`corners`, rad."""
        raise NotImplementedError

    def corner_radii(self, radius: float | None = None) -> tuple[float, ...]:
        """The radius of the head at each corner of :meth:`corners`, m (0: sharp)."""
        raise NotImplementedError

    def shortest_feature(self, radius: float | None = None) -> float:
        """The shortest land, gap or wrapped corner arc r_c θ_c, m (> 0): the default
        grid resolves it."""
        raise NotImplementedError

    @property
    def wrap(self) -> float:
        """The total angle the head turns the tape by, rad."""
        raise NotImplementedError

    @property
    def symmetric(self) -> bool:
        """Whether the head (with its wraps) is mirror-symmetric about x = 0."""
        raise NotImplementedError

    def mirrored(self) -> Head:
        """The head reflected x → −x (wrap_in and wrap_out swapped)."""
        raise NotImplementedError

    def as_dict(self) -> dict:
        """A JSON-friendly dict (floats exact); :func:`head_from_dict` inverts it."""
        raise NotImplementedError

    # --- shared ------------------------------------------------------------------------
    def dry_gap(self, x, y=None, radius: float | None = None) -> np.ndarray:
        """w₀ = z₀ − z_h >= 0 at x (and y), m: shape (len(x),) or (len(x), len(y))."""
        x = np.asarray(x, dtype=float)
        z0 = self.dry_tape(x, radius)
        zh = self.surface(x, y, radius)
        if zh.ndim == 2:
            z0 = z0[:, None]
        return np.maximum(z0 - zh, 0.0)

    def dry_curvature(self, x, radius: float | None = None) -> np.ndarray:
        """κ = −δ²z₀ at the interior nodes of x, 1/m (the tape's second difference: at a
        sharp corner on a node the discrete delta θ_c/w_i)."""
        x = np.asarray(x, dtype=float)
        return _second_difference_curvature(x, self.dry_tape(x, radius))

    def foundation_stiffness(self, params) -> float:
        """The shell stiffness k, N/m³: ``params.foundation_stiffness`` if given, else 0
        (a flat land has no wrap curvature and so no hoop stiffness; module notes)."""
        k = params.foundation_stiffness
        return 0.0 if k is None else float(k)

    def check(self, radius: float | None = None) -> None:
        """Checks that need the tape's radius (a cylinder of radius None): transducers."""
        _check_transducers(self, self.transducers, radius)


# ======================================================================================
@dataclass(frozen=True)
class Cylinder(Head):
    """A cylindrical head of radius R wrapped over the total angle θ (today's head).

    Parameters
    ----------
    wrap_angle : float
        Total wrap θ, rad, in (0, π/2].
    radius : float or None
        R, m; None: the tape's radius (``params.radius``).
    transducers : tuple of float
        x of the read/write element lines, m (head coordinates, on the arc).
    friction : float
        Coulomb coefficient μ >= 0 between tape and head.
    """

    wrap_angle: float
    radius: float | None = None
    transducers: tuple[float, ...] = ()
    friction: float = 0.0
    kind = "cylinder"

    def __post_init__(self) -> None:
        put = object.__setattr__
        angle = validation.real("wrap_angle", self.wrap_angle, unit="rad")
        if not 0.0 < angle <= MAX_CYLINDER_WRAP:
            raise ParameterError(
                f"wrap_angle must be in (0, {math.degrees(MAX_CYLINDER_WRAP):g}] degrees, "
                f"got {math.degrees(angle):g} degrees")
        put(self, "wrap_angle", angle)
        if self.radius is not None:
            put(self, "radius", validation.positive("radius", self.radius, "m"))
        put(self, "friction", _friction(self.friction))
        put(self, "transducers", _floats("transducers", self.transducers, "m"))
        if self.radius is not None:
            _check_transducers(self, self.transducers)

    def _r(self, radius: float | None) -> float:
        r = self.radius if self.radius is not None else radius
        if r is None:
            raise ParameterError("radius must be given for a Cylinder(radius=None): the "
                                 "tape's radius R, m")
        return float(r)

    def extent(self, radius=None):
        half = 0.5 * self._r(radius) * self.wrap_angle
        return (-half, half)

    def surface(self, x, y=None, radius=None):
        x = np.asarray(x, dtype=float)
        zh = -x * x / (2.0 * self._r(radius))
        return zh if y is None else np.repeat(zh[:, None], len(y), axis=1)

    def dry_tape(self, x, radius=None):
        r = self._r(radius)
        x = np.asarray(x, dtype=float)
        return -x * x / (2.0 * r) + self._gap(x, r)

    def _gap(self, x, r):
        s = np.maximum(np.abs(x) - 0.5 * r * self.wrap_angle, 0.0)
        return s * s / (2.0 * r)

    def dry_gap(self, x, y=None, radius=None):
        """w₀ = (|x| − Rθ/2)₊²/(2R), m (the shallow-shell gap of the tangent spans)."""
        w0 = self._gap(np.asarray(x, dtype=float), self._r(radius))
        return w0 if y is None else np.repeat(w0[:, None], len(y), axis=1)

    def dry_curvature(self, x, radius=None):
        """κ = 1/R − δ²w₀ at the interior nodes of x, 1/m (1/R on the wrap, 0 on the
        spans; a node straddling a tangent point gets the right fraction)."""
        r = self._r(radius)
        x = np.asarray(x, dtype=float)
        h = np.diff(x)
        slope = np.diff(self._gap(x, r)) / h
        return 1.0 / r - np.diff(slope) / (0.5 * (h[:-1] + h[1:]))

    def corners(self, radius=None):
        return self.extent(radius)

    def lands(self, radius=None):
        return (self.extent(radius),)

    def corner_turns(self, radius=None):
        return (0.5 * self.wrap_angle, 0.5 * self.wrap_angle)

    def corner_radii(self, radius=None):
        r = self._r(radius)
        return (r, r)

    def shortest_feature(self, radius=None):
        return self._r(radius) * self.wrap_angle

    def foundation_stiffness(self, params):
        """``params.k``: the wrapped shell's stiffness, over the whole domain as before."""
        return params.k

    @property
    def wrap(self):
        return self.wrap_angle

    @property
    def symmetric(self):
        return True

    def mirrored(self):
        return Cylinder(self.wrap_angle, self.radius, tuple(sorted(-x for x in self.transducers)),
                        self.friction)

    def as_dict(self):
        return {"kind": self.kind, "wrap_angle": self.wrap_angle, "radius": self.radius,
                "transducers": list(self.transducers), "friction": self.friction}


# ======================================================================================
@dataclass(frozen=True)
class Module:
    """One flat land of a :class:`FlatHead`.

    Parameters
    ----------
    land_length : float
        m, corner to corner (between the two corner points: where the land's line meets
        the flanks' lines), > 0.
    corner_radius : float or (float, float)
        m, >= 0; 0 is a sharp corner; or (leading, trailing). A rounded corner is the arc
        (parabola, small slopes) tangent to the land and the flank, reaching r_c φ/2 either
        side of the corner point (φ the flank angle).
    height : float
        m, of the land's middle above the head datum.
    tilt : float
        rad, the land's slope dz/dx (small, |tilt| <= 10°).
    """

    land_length: float
    corner_radius: float | tuple[float, float] = 0.0
    height: float = 0.0
    tilt: float = 0.0

    def __post_init__(self) -> None:
        put = object.__setattr__
        put(self, "land_length", validation.positive("land_length", self.land_length, "m"))
        radii = self.corner_radius
        if isinstance(radii, (tuple, list)):
            if len(radii) != 2:
                raise ParameterError(f"corner_radius must be one radius or (leading, "
                                     f"trailing) in m, got {radii!r}")
            radii = tuple(validation.nonnegative("corner_radius", r, "m") for r in radii)
        else:
            radii = validation.nonnegative("corner_radius", radii, "m")
        put(self, "corner_radius", radii)
        put(self, "height", validation.real("height", self.height, unit="m"))
        put(self, "tilt", validation.real("tilt", self.tilt, low=-MAX_TILT, high=MAX_TILT,
                                          unit="rad"))

    @property
    def radii(self) -> tuple[float, float]:
        """(leading, trailing) corner radii, m."""
        r = self.corner_radius
        return (float(r[0]), float(r[1])) if isinstance(r, tuple) else (float(r), float(r))

    def mirrored(self) -> Module:
        lead, trail = self.radii
        radius = (trail, lead) if isinstance(self.corner_radius, tuple) else self.corner_radius
        return Module(self.land_length, radius, self.height, -self.tilt)

    def as_dict(self) -> dict:
        r = self.corner_radius
        return {"land_length": self.land_length,
                "corner_radius": list(r) if isinstance(r, tuple) else r,
                "height": self.height, "tilt": self.tilt}


@dataclass(frozen=True)
class _Mesa:
    """One module placed on the head: land [a, b] (corner points), its line, radii."""

    a: float
    b: float
    mid: float
    height: float
    tilt: float
    r_lead: float
    r_trail: float
    flank: float

    def land(self, x):
        return self.height + self.tilt * (x - self.mid)

    def _drop(self, d, r):
        """How far the head lies below the land's line at the distance d (m) past a
        corner's tangent point of the land (d <= 0: on the land)."""
        d = np.maximum(d, 0.0)
        if r == 0.0:
            return self.flank * d
        arc = r * self.flank
        return np.where(d <= arc, d * d / (2.0 * r), 0.5 * r * self.flank**2
                        + self.flank * (d - arc))

    def __call__(self, x):
        x = np.asarray(x, dtype=float)
        lead = self.a + 0.5 * self.r_lead * self.flank      # the land's tangent points
        trail = self.b - 0.5 * self.r_trail * self.flank
        return (self.land(x) - self._drop(lead - x, self.r_lead)
                - self._drop(x - trail, self.r_trail))

    def samples(self) -> tuple[np.ndarray, np.ndarray]:
        """Points of the land and its corner arcs (the parts the tape can touch)."""
        parts = []
        for c, r in ((self.a, self.r_lead), (self.b, self.r_trail)):
            if r == 0.0:
                parts.append(np.array([c]))
            else:
                half = 0.5 * r * self.flank
                parts.append(np.linspace(c - half, c + half, ARC_SAMPLES))
        t = np.concatenate(parts)
        return t, self(t)


@dataclass(frozen=True)
class FlatHead(Head):
    """A flat head: 1 to 8 flat modules in a row with sharp or rounded corners.

    Parameters
    ----------
    modules : tuple of Module
        In the order the tape meets them.
    wrap_in : float
        rad, in [0, 45°]: the incoming span's angle below the x-axis (the first land's
        direction when it is not tilted); its slope is +wrap_in.
    wrap_out : float
        rad, in [0, 45°]: the outgoing span's angle below the x-axis (slope −wrap_out).
        At least one of wrap_in, wrap_out must be > 0: nothing else presses the tape onto
        a flat head.
    gaps : tuple of float
        m, > 0, between consecutive modules (n − 1 values; corner to corner).
    flank_angle : float
        rad, in (0, 90°), default :data:`DEFAULT_FLANK_ANGLE`: beyond each corner the head
        falls away along a flank at this angle below the land; it must be steeper than the
        tape's span at that corner (for coplanar modules: steeper than wrap_in and
        wrap_out).
    transducers : tuple of float
        x of the read/write element lines, m (head coordinates, on the wrapped region).
    friction : float
        Coulomb coefficient μ >= 0 between tape and head.

    Examples
    --------
    >>> import math
    >>> head = FlatHead((Module(1e-3),), math.radians(2), math.radians(2))
    >>> head.extent(), head.corners(), head.wrap == math.radians(4)
    ((-0.0005, 0.0005), (-0.0005, 0.0005), True)
    >>> FlatHead((Module(1e-3),), 0.0, 0.0)
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: wrap_in and wrap_out are both 0: nothing presses the tape ...
    """

    modules: tuple[Module, ...]
    wrap_in: float
    wrap_out: float
    gaps: tuple[float, ...] = ()
    flank_angle: float = DEFAULT_FLANK_ANGLE
    transducers: tuple[float, ...] = ()
    friction: float = 0.0
    _mesas: tuple = field(default=(), init=False, repr=False, compare=False)
    _envelope: object = field(default=None, init=False, repr=False, compare=False)
    kind = "flat"

    def __post_init__(self) -> None:
        put = object.__setattr__
        modules = self.modules
        if isinstance(modules, Module):
            modules = (modules,)
        try:
            modules = tuple(modules)
        except TypeError:
            raise ParameterError(f"modules must be a sequence of Module, got "
                                 f"{type(modules).__name__}") from None
        if not 1 <= len(modules) <= MAX_MODULES:
            raise ParameterError(f"modules must hold 1 to {MAX_MODULES} Module, got "
                                 f"{len(modules)}")
        for i, m in enumerate(modules):
            validation.instance(f"modules[{i}]", m, Module)
        put(self, "modules", modules)
        put(self, "wrap_in", _side_wrap("wrap_in", self.wrap_in))
        put(self, "wrap_out", _side_wrap("wrap_out", self.wrap_out))
        if self.wrap_in == 0.0 and self.wrap_out == 0.0:
            raise ParameterError("wrap_in and wrap_out are both 0: nothing presses the tape "
                                 "onto the flat head; give at least one of them > 0 rad")
        gaps = _floats("gaps", self.gaps, "m")
        if len(gaps) != len(modules) - 1:
            raise ParameterError(f"gaps must hold {len(modules) - 1} values (m, between "
                                 f"consecutive modules) for {len(modules)} modules, got "
                                 f"{len(gaps)}")
        for i, g in enumerate(gaps):
            if not g > 0.0:   # modules that touch are one module
                raise ParameterError(f"gaps[{i}] must be > 0 m, got {g:g}")
        put(self, "gaps", gaps)
        put(self, "flank_angle", validation.real("flank_angle", self.flank_angle, low=0.0,
                                                 high=0.5 * math.pi, low_open=True,
                                                 high_open=True, unit="rad"))
        put(self, "friction", _friction(self.friction))
        put(self, "_mesas", self._placed())
        self._check_lands()
        self._check_overlaps()
        t, z = zip(*(m.samples() for m in self._mesas), strict=True)
        put(self, "_envelope", _Envelope(np.concatenate(t), np.concatenate(z),
                                         self.wrap_in, -self.wrap_out))
        self._check_flanks()
        put(self, "transducers", _check_transducers(self, self.transducers))

    def _placed(self) -> tuple[_Mesa, ...]:
        starts, x = [], 0.0
        for i, m in enumerate(self.modules):
            starts.append(x)
            x += m.land_length + (self.gaps[i] if i < len(self.gaps) else 0.0)
        shift = -0.5 * x
        out = []
        for s, m in zip(starts, self.modules, strict=True):
            a, b = s + shift, s + shift + m.land_length
            out.append(_Mesa(a, b, 0.5 * (a + b), m.height, m.tilt, *m.radii,
                             self.flank_angle))
        return tuple(out)

    def _check_lands(self) -> None:
        for i, (m, mesa) in enumerate(zip(self.modules, self._mesas, strict=True)):
            reach = 0.5 * (mesa.r_lead + mesa.r_trail) * self.flank_angle
            if reach > m.land_length:
                raise ParameterError(
                    f"modules[{i}].land_length {m.land_length:g} m is shorter than its "
                    f"corner radii allow: the corner arcs reach (r_lead + r_trail) "
                    f"flank_angle / 2 = {reach:.4g} m onto the land; use a longer land or "
                    "smaller corner_radius")

    def _check_overlaps(self) -> None:
        mesas = self._mesas
        scale = GEOMETRY_TOLERANCE * (mesas[-1].b - mesas[0].a)
        for i, m in enumerate(mesas):
            ends = np.array([m.a, m.b])
            for j, other in enumerate(mesas):
                if j != i and np.any(other(ends) > m.land(ends) + scale):
                    raise ParameterError(
                        f"modules[{j}] overlaps modules[{i}]: with these heights, tilts and "
                        f"gaps its flank rises above the land of modules[{i}]; use a larger "
                        "gap or closer heights")

    def _check_flanks(self) -> None:
        """The flank beyond each corner must be steeper than the tape leaving it."""
        env = self._envelope
        for i, m in enumerate(self._mesas):
            for x, side, sign in ((m.a, "leading", 1.0), (m.b, "trailing", -1.0)):
                r = m.r_lead if sign > 0 else m.r_trail
                outside = x - sign * (0.5 * r * self.flank_angle + 1e-3 * (m.b - m.a))
                k = int(np.clip(np.searchsorted(env.vx, outside), 0, len(env.slopes) - 1))
                tape = sign * env.slopes[k] - sign * m.tilt       # the span's angle below the land
                if tape >= self.flank_angle:
                    raise ParameterError(
                        f"flank_angle {math.degrees(self.flank_angle):.4g} degrees is not "
                        f"steeper than the tape at the {side} corner of modules[{i}] "
                        f"({math.degrees(tape):.4g} degrees below the land): the tape would "
                        "lie on the flank; use a steeper flank_angle or a smaller wrap")

    # --- the contour ---------------------------------------------------------------------
    def extent(self, radius=None):
        return (self._mesas[0].a, self._mesas[-1].b)

    def surface(self, x, y=None, radius=None):
        x = np.asarray(x, dtype=float)
        zh = np.max([m(x) for m in self._mesas], axis=0)
        return zh if y is None else np.repeat(zh[:, None], len(y), axis=1)

    def dry_tape(self, x, radius=None):
        x = np.asarray(x, dtype=float)
        return np.maximum(self._envelope(x), self.surface(x))

    def corners(self, radius=None):
        return tuple(c for m in self._mesas for c in (m.a, m.b))

    def sharp_corners(self, radius=None):
        """The sharp corners the tape turns over (nodes go exactly there)."""
        turns = self.corner_turns()
        radii = self.corner_radii()
        return tuple(c for c, t, r in zip(self.corners(), turns, radii, strict=True)
                     if r == 0.0 and t > 0.0)

    def lands(self, radius=None):
        return tuple((m.a, m.b) for m in self._mesas)

    def corner_radii(self, radius=None):
        return tuple(r for m in self._mesas for r in (m.r_lead, m.r_trail))

    def rounded_corners(self, radius=None) -> tuple[int, ...]:
        """Indices (into :meth:`corners`) of the rounded corners the tape turns over."""
        return tuple(k for k, (r, t) in enumerate(zip(self.corner_radii(),
                                                     self.corner_turns(), strict=True))
                     if r > 0.0 and t > 0.0)

    def arc_point(self, k: int, slope: float) -> float:
        """x (m) on the arc of the rounded corner ``k`` (index into :meth:`corners`) where
        the head's slope dz_h/dx equals ``slope`` (rad, small slopes), clamped to the arc:
        the point a tape of that slope touches it at (a tangent contact), or, if the tape
        flies, its nearest approach. The arc z_h = land − d²/(2 r_c) at the distance d
        past the land's tangent point has the slope tilt ∓ d/r_c (leading/trailing), so
        d = r_c |slope − tilt|, within [0, r_c φ] (φ the flank angle)."""
        m = self._mesas[k // 2]
        lead = k % 2 == 0
        r = m.r_lead if lead else m.r_trail
        if r == 0.0:
            raise ParameterError(f"corner {k} is sharp: it has no arc")
        d = float(np.clip(r * ((slope - m.tilt) if lead else (m.tilt - slope)), 0.0,
                          r * self.flank_angle))
        return (m.a + 0.5 * r * self.flank_angle - d if lead
                else m.b - 0.5 * r * self.flank_angle + d)

    def arc_tangent_points(self, k: int) -> tuple[float, float]:
        """(x_start, x_end), m: the ends of the rounded corner ``k``'s arc (its tangent
        points on the land and on the flank, in increasing x)."""
        m = self._mesas[k // 2]
        r = m.r_lead if k % 2 == 0 else m.r_trail
        c = m.a if k % 2 == 0 else m.b
        return (c - 0.5 * r * self.flank_angle, c + 0.5 * r * self.flank_angle)

    def land_slope(self, k: int) -> float:
        """The slope dz_h/dx (rad) of the land whose corner is ``k``."""
        return float(self._mesas[k // 2].tilt)

    def corner_turns(self, radius=None):
        """The tape's turn over each corner: the envelope's turns at the hull vertices
        within the corner's arc (a sharp corner: its one vertex), rad."""
        env = self._envelope
        tol = GEOMETRY_TOLERANCE * (self._mesas[-1].b - self._mesas[0].a)
        turns = env.turns
        out = []
        for c, r in zip(self.corners(), self.corner_radii(), strict=True):
            half = 0.5 * r * self.flank_angle + tol
            out.append(float(turns[np.abs(env.vx - c) <= half].sum()))
        return tuple(out)

    def shortest_land(self, radius=None):
        """The shortest land or gap, m (the default grid resolves it when its rounded
        corners' arcs carry a node at the tape's contact instead of being resolved)."""
        lengths = [m.land_length for m in self.modules] + [g for g in self.gaps if g > 0]
        return float(min(lengths))

    def shortest_feature(self, radius=None):
        lengths = [m.land_length for m in self.modules] + [g for g in self.gaps if g > 0]
        arcs = [r * t for r, t in zip(self.corner_radii(), self.corner_turns(), strict=True)
                if r > 0 and t >= CORNER_FRACTION * self.wrap]
        return float(min(lengths + arcs))

    @property
    def wrap(self):
        return self.wrap_in + self.wrap_out

    @property
    def symmetric(self):
        return self.mirrored().as_dict() == self.as_dict()

    def mirrored(self):
        return FlatHead(tuple(m.mirrored() for m in reversed(self.modules)), self.wrap_out,
                        self.wrap_in, tuple(reversed(self.gaps)), self.flank_angle,
                        tuple(sorted(-x for x in self.transducers)), self.friction)

    def as_dict(self):
        return {"kind": self.kind, "modules": [m.as_dict() for m in self.modules],
                "wrap_in": self.wrap_in, "wrap_out": self.wrap_out, "gaps": list(self.gaps),
                "flank_angle": self.flank_angle, "transducers": list(self.transducers),
                "friction": self.friction}


# ======================================================================================
@dataclass(frozen=True, eq=False)
class ProfileHead(Head):
    """A measured head contour (a profilometer's), interpolated linearly.

    Parameters
    ----------
    x : numpy.ndarray
        m, strictly increasing, at least 4 values. Stored shifted so that the middle of
        the wrapped region (where the dry tape first and last touches the contour) is
        x = 0 (:attr:`shift` holds the shift added, m).
    z : numpy.ndarray
        m, the head's height: shape (len(x),), or (len(x), len(y)) for (x, y, z) data.
    wrap_in, wrap_out : float
        rad, in [0, 45°], the spans' angles below the x-axis (slopes +wrap_in far left,
        −wrap_out far right); their sum > 0.
    y : numpy.ndarray or None
        m, strictly increasing, across the tape from its lower edge (2-D data); outside
        its range the nearest column is used.
    transducers, friction
        As for :class:`FlatHead` (transducers in the shifted coordinates).

    Notes
    -----
    Beyond the measured x-range the head falls away at 20° (:data:`PROFILE_FALLOFF`).
    The profile must contain the wrapped region: the tape must not meet it at its first
    or last sample. Corners are the envelope's vertices where the tape turns by at least
    5 % of the wrap, and the wrapped region's ends; the sharp ones (a node of the
    bearing's grid on each) those where it turns by 25 % in one sample. The bearing flies
    over the contour interpolated through its grid's nodes: a feature narrower than the
    node spacing (an asperity between two nodes) that stands more than the roughness above
    that contour makes :class:`~gyroshell.bearing.model.BearingModel` warn, naming its
    place, width and height (:meth:`unresolved_features`).
    """

    x: np.ndarray
    z: np.ndarray
    wrap_in: float
    wrap_out: float
    y: np.ndarray | None = None
    transducers: tuple[float, ...] = ()
    friction: float = 0.0
    shift: float = field(default=0.0, init=False)
    _envelope: object = field(default=None, init=False, repr=False)
    _raw_x: object = field(default=None, init=False, repr=False)
    kind = "profile"

    def __post_init__(self) -> None:
        put = object.__setattr__
        x = _profile_array("x", self.x, 1)
        if len(x) < MIN_PROFILE_POINTS:
            raise ParameterError(f"x must hold at least {MIN_PROFILE_POINTS} points, got "
                                 f"{len(x)}")
        if not np.all(np.diff(x) > 0):
            i = int(np.argmin(np.diff(x) > 0))
            raise ParameterError(f"x must be strictly increasing, but x[{i + 1}] = "
                                 f"{x[i + 1]:g} m follows x[{i}] = {x[i]:g} m")
        y = None
        if self.y is not None:
            y = _profile_array("y", self.y, 1)
            if len(y) < MIN_PROFILE_COLUMNS or not np.all(np.diff(y) > 0):
                raise ParameterError(f"y must hold at least {MIN_PROFILE_COLUMNS} strictly "
                                     "increasing values, m")
        z = _profile_array("z", self.z, 1 if y is None else 2)
        shape = (len(x),) if y is None else (len(x), len(y))
        if z.shape != shape:
            raise ParameterError(f"z must have the shape {shape} of x (and y), got {z.shape}")
        if x[-1] - x[0] > MAX_PROFILE_LENGTH:
            raise ParameterError(
                f"x spans {x[-1] - x[0]:.4g} m, longer than any head ({MAX_PROFILE_LENGTH:g} "
                "m): a profile is in m; are its numbers in mm or um?")
        put(self, "wrap_in", _side_wrap("wrap_in", self.wrap_in))
        put(self, "wrap_out", _side_wrap("wrap_out", self.wrap_out))
        if self.wrap_in + self.wrap_out <= 0.0:
            raise ParameterError("wrap_in and wrap_out are both 0: nothing presses the tape "
                                 "onto the head; give at least one of them > 0 rad")
        ridge = z if y is None else z.max(axis=1)
        env = _Envelope(x, ridge, self.wrap_in, -self.wrap_out)
        if any(env.touched_ends):
            end = "first" if env.touched_ends[0] else "last"
            raise ParameterError(
                f"the profile does not contain the wrapped region: the dry tape meets it at "
                f"its {end} point; measure a longer profile (or check wrap_in, wrap_out)")
        shift = -0.5 * (env.vx[0] + env.vx[-1])
        put(self, "_raw_x", x)
        x = x + shift
        put(self, "x", x)
        put(self, "y", y)
        put(self, "z", z)
        put(self, "shift", float(shift))
        put(self, "_envelope", _Envelope(x, ridge, self.wrap_in, -self.wrap_out))
        put(self, "friction", _friction(self.friction))
        put(self, "transducers", _check_transducers(self, self.transducers))

    @classmethod
    def from_csv(cls, path, *, wrap_in, wrap_out, transducers=(), friction=0.0
                 ) -> ProfileHead:
        """A profile from a CSV file of columns (x, z) or (x, y, z), m, with an optional
        header line; (x, y, z) rows must fill a grid of x × y.

        Raises
        ------
        ParameterError
            For the arguments (wraps, friction, transducers off the wrapped region).
        InputFileError
            Naming the file and what is wrong with its contour: missing, a folder or not a
            regular file (a FIFO), too large for the memory limit, empty, a line not
            numbers or of another number of columns, x not increasing, (x, y) not a grid,
            too short to hold the wrapped region.
        """
        wrap_in, wrap_out = _side_wrap("wrap_in", wrap_in), _side_wrap("wrap_out", wrap_out)
        friction = _friction(friction)
        x, y, z = _read_profile(path)
        try:
            head = cls(x, z, wrap_in, wrap_out, y, friction=friction)
        except ParameterError as exc:   # the arguments are checked: the contour is wrong
            if "nothing presses the tape" in str(exc):
                raise
            raise InputFileError(f"{os.fspath(path)}: {exc}") from None
        object.__setattr__(head, "transducers", _check_transducers(head, transducers))
        return head

    # --- the contour ---------------------------------------------------------------------
    def extent(self, radius=None):
        env = self._envelope
        return (float(env.vx[0]), float(env.vx[-1]))

    def _line(self, x, column):
        z = np.interp(x, self.x, column)
        below = np.clip(self.x[0] - x, 0.0, None) + np.clip(x - self.x[-1], 0.0, None)
        return z - PROFILE_FALLOFF * below

    def surface(self, x, y=None, radius=None):
        x = np.asarray(x, dtype=float)
        if self.y is None:
            zh = self._line(x, self.z)
            return zh if y is None else np.repeat(zh[:, None], len(y), axis=1)
        if y is None:
            return self._line(x, self.z.max(axis=1))
        y = np.clip(np.asarray(y, dtype=float), self.y[0], self.y[-1])
        cols = np.column_stack([self._line(x, self.z[:, j]) for j in range(len(self.y))])
        return np.array([np.interp(y, self.y, row) for row in cols])

    def dry_tape(self, x, radius=None):
        return self._envelope(np.asarray(x, dtype=float))

    def _corner_mask(self):
        env = self._envelope
        mask = env.turns >= CORNER_FRACTION * self.wrap
        mask[0] = mask[-1] = True
        return mask

    def corners(self, radius=None):
        return tuple(float(c) for c in self._envelope.vx[self._corner_mask()])

    def sharp_corners(self, radius=None):
        env = self._envelope
        return tuple(float(c) for c in env.vx[env.turns >= PROFILE_SHARP_FRACTION * self.wrap])

    def corner_turns(self, radius=None):
        return tuple(float(t) for t in self._envelope.turns[self._corner_mask()])

    def corner_radii(self, radius=None):
        return tuple(0.0 for _ in self.corners())

    def lands(self, radius=None):
        c = self.corners()
        return tuple(zip(c[:-1], c[1:], strict=True)) or ((c[0], c[-1]),)

    def shortest_feature(self, radius=None):
        c = np.array(self.corners())
        gaps = np.diff(c)
        return float(gaps.min()) if len(gaps) else float(np.diff(self.x).min())

    def unresolved_features(self, nodes, height: float) -> tuple[tuple, ...]:
        """The profile's features that a grid with the x-``nodes`` (m, head coordinates,
        increasing) does not see: where, within the wrapped region (:meth:`extent`), the
        measured contour (the highest line across a 2-D profile) stands more than
        ``height`` (m; the bearing passes the roughness σ) above its linear interpolation
        through the nodes, which is the contour the bearing flies over.

        Returns
        -------
        tuple of (missed, width, x)
            Per feature, highest first: how far it stands above the grid's contour, m;
            its width, m (between the samples on either side where it does not); and the
            x of its highest point, m (head coordinates).
        """
        nodes = np.asarray(nodes, dtype=float)
        ridge = self.z if self.y is None else self.z.max(axis=1)
        first, last = self.extent()
        inside = (self.x >= first) & (self.x <= last)
        missed = np.where(inside, ridge - np.interp(self.x, nodes, self._line(nodes, ridge)),
                          0.0)
        above = missed > GEOMETRY_TOLERANCE * max(float(np.ptp(ridge)), height)
        # runs of samples above the grid's contour: [start, stop) index pairs
        edges = np.flatnonzero(np.diff(np.concatenate([[0], above.astype(np.int8), [0]])))
        features = []
        for start, stop in zip(edges[::2], edges[1::2], strict=True):
            peak = start + int(np.argmax(missed[start:stop]))
            if missed[peak] <= height:
                continue
            lo, hi = max(start - 1, 0), min(stop, len(self.x) - 1)
            features.append((float(missed[peak]), float(self.x[hi] - self.x[lo]),
                             float(self.x[peak])))
        return tuple(sorted(features, reverse=True))

    @property
    def wrap(self):
        return self.wrap_in + self.wrap_out

    @property
    def symmetric(self):
        if self.wrap_in != self.wrap_out:
            return False
        span = self.x[-1] - self.x[0]
        return (np.allclose(self.x, -self.x[::-1], rtol=0, atol=GEOMETRY_TOLERANCE * span)
                and np.allclose(self.z, self.z[::-1], rtol=0,
                                atol=GEOMETRY_TOLERANCE * max(np.ptp(self.z), 1e-300)))

    def mirrored(self):
        return ProfileHead(-self.x[::-1], self.z[::-1].copy(), self.wrap_out, self.wrap_in,
                           None if self.y is None else self.y.copy(),
                           tuple(sorted(-x for x in self.transducers)), self.friction)

    def as_dict(self):
        return {"kind": self.kind, "x": self._raw_x.tolist(), "z": self.z.tolist(),
                "wrap_in": self.wrap_in, "wrap_out": self.wrap_out,
                "y": None if self.y is None else self.y.tolist(),
                "transducers": list(self.transducers), "friction": self.friction}

    def __eq__(self, other):
        return isinstance(other, ProfileHead) and self.as_dict() == other.as_dict()

    __hash__ = None


def _profile_array(name: str, value, ndim: int) -> np.ndarray:
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be an array of numbers, m") from None
    if a.ndim != ndim or a.size == 0:
        raise ParameterError(f"{name} must be a non-empty {ndim}-D array, m, got shape "
                             f"{a.shape}")
    if not np.all(np.isfinite(a)):
        raise ParameterError(f"{name} must hold finite numbers, m")
    return a


def _read_profile(path):
    """(x, y or None, z) from a profile CSV (see :meth:`ProfileHead.from_csv`)."""
    name = os.fspath(path)
    if os.path.isdir(name):
        raise InputFileError(f"{name}: is a folder, not a profile CSV file")
    name = os.fspath(check_input(name, what="profile CSV file"))  # not a FIFO: it would block
    size = os.path.getsize(name)
    budget.check_memory(f"the profile file {name} ({size} bytes)",
                        CSV_BYTES_PER_BYTE * size, "use a shorter profile (fewer samples)")
    try:
        with open(name, encoding="utf-8-sig") as f:   # -sig: a byte-order mark is no header
            lines = [(k, line.strip()) for k, line in enumerate(f, 1) if line.strip()
                     and not line.lstrip().startswith("#")]
    except (OSError, UnicodeDecodeError) as exc:
        raise InputFileError(f"{name}: cannot be read as UTF-8 text ({exc})") from None
    if lines and not _numeric(lines[0][1]):
        lines = lines[1:]                    # a header
    if not lines:
        raise InputFileError(f"{name}: the profile file is empty (no rows of numbers)")
    rows = np.array(_rows(name, lines))
    if rows.shape[1] not in (2, 3):
        raise InputFileError(f"{name}: the profile must have 2 columns (x, z) or 3 "
                             f"(x, y, z) in m on every row, got {rows.shape[1]}")
    if not np.all(np.isfinite(rows)):
        raise InputFileError(f"{name}: the profile holds non-finite values")
    if rows.shape[1] == 2:
        return rows[:, 0], None, rows[:, 1]
    xs, ys = np.unique(rows[:, 0]), np.unique(rows[:, 1])
    if len(xs) * len(ys) != len(rows):
        raise InputFileError(f"{name}: the (x, y) of the rows must fill a grid of "
                             f"{len(xs)} x {len(ys)} points, got {len(rows)} rows")
    z = np.full((len(xs), len(ys)), np.nan)
    z[np.searchsorted(xs, rows[:, 0]), np.searchsorted(ys, rows[:, 1])] = rows[:, 2]
    if np.isnan(z).any():
        raise InputFileError(f"{name}: the (x, y) of the rows repeat a point instead of "
                             "filling the grid")
    return xs, ys, z


def _rows(name: str, lines: list[tuple[int, str]]) -> list[list[float]]:
    """The numbers of the (line number, text) ``lines`` of the profile file ``name``, each
    with as many as the first; InputFileError naming the file and line otherwise."""
    rows = []
    for row, (k, line) in enumerate(lines, 1):
        try:
            rows.append([float(v) for v in _fields(line)])
        except ValueError:
            raise InputFileError(f"{name}: line {k}: row {row} is not numbers: "
                                 f"{line[:60]!r}") from None
        if len(rows[-1]) != len(rows[0]):
            raise InputFileError(
                f"{name}: line {k}: row {row} has {len(rows[-1])} values, but the rows "
                f"before have {len(rows[0])}: every row must be (x, z) or every row "
                "(x, y, z), m")
    return rows


def _fields(line: str) -> list[str]:
    """The values of a CSV row separated by commas, semicolons or blanks."""
    return re.split(r"[,;\s]+", line.strip())


def _numeric(line: str) -> bool:
    try:
        [float(v) for v in _fields(line)]
    except ValueError:
        return False
    return True


def head_from_dict(d: dict) -> Head:
    """The head stored by ``head.as_dict()``.

    Raises
    ------
    ParameterError
        An unknown kind, unknown or missing keys, or values out of range.
    """
    if not isinstance(d, dict) or d.get("kind") not in _KINDS:
        raise ParameterError(f"a head must be a dict with kind one of {', '.join(_KINDS)}, "
                             f"got {d!r:.80}")
    data = {k: v for k, v in d.items() if k != "kind"}
    cls, keys = _KINDS[d["kind"]]
    if set(data) - set(keys):
        raise ParameterError(f"a {d['kind']} head has no keys {sorted(set(data) - set(keys))}")
    try:
        if cls is FlatHead:
            mods = data.get("modules")
            if not isinstance(mods, list) or not all(isinstance(m, dict) for m in mods):
                raise ParameterError("a flat head's modules must be a list of objects")
            data["modules"] = tuple(
                Module(**{**m, "corner_radius": tuple(m["corner_radius"])
                          if isinstance(m.get("corner_radius"), list)
                          else m.get("corner_radius", 0.0)}) for m in mods)
            data["gaps"] = tuple(data.get("gaps", ()))
        if cls is ProfileHead:
            data["x"] = np.array(data.get("x"), dtype=float)
            data["z"] = np.array(data.get("z"), dtype=float)
            if data.get("y") is not None:
                data["y"] = np.array(data["y"], dtype=float)
        data["transducers"] = tuple(data.get("transducers", ()))
        return cls(**data)
    except (TypeError, ValueError) as exc:
        if isinstance(exc, ParameterError):
            raise
        raise ParameterError(f"a {d['kind']} head's fields are wrong ({exc})") from None


_KINDS = {
    "cylinder": (Cylinder, ("wrap_angle", "radius", "transducers", "friction")),
    "flat": (FlatHead, ("modules", "wrap_in", "wrap_out", "gaps", "flank_angle",
                        "transducers", "friction")),
    "profile": (ProfileHead, ("x", "z", "wrap_in", "wrap_out", "y", "transducers",
                              "friction")),
}
