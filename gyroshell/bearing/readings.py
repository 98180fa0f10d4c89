"""What the head designer reads off a steady bearing state: the spacing along the
transducer lines, the tents next to the corners, the contact force of each corner and land,
the air shear on the tape and the drag it adds (issue #19).

Every reading is a pure function of nodal arrays on the bearing's tensor grid (x from the
head's middle along the tape's motion, y across the width; uniform or graded), so that it
can be checked on fields whose answers are known exactly;
:class:`~gyroshell.bearing.results.BearingSolution` calls them with its own fields, the
head's corners, lands, transducers and friction. Arrays of nodal values have shape
(len(x), nc): one column for an infinitely wide tape (per unit width), len(y) in 2-D.

Shear stress. Between the stationary head (z = 0) and the tape moving at V (z = h) the
film's velocity is the lubrication profile μ u'' = ∂p/∂x with first-order (Maxwell) slip
at both walls, u(0) = λ_e u'(0), u(h) = V − λ_e u'(h):

    u(z) = (∂p/∂x) (z² − h z − λ_e h) / (2μ) + V (z + λ_e) / (h + 2λ_e).

Its flux ∫₀ʰ u dz = V h/2 − (h³/12μ)(1 + 6λ_e/h) ∂p/∂x is the one of :mod:`.film`: the
Couette term V h/2 without slip correction and the flow factor Q = 1 + 6λ_e/h, with
λ_e = λ p_a/p for the compressible film (the mean free path at the local pressure) and
λ_e = λ for the incompressible option. The stress the air puts on the tape is μ u'(h)
against its motion:

    τ = μV/(h + 2λ_e) + (h/2) ∂p/∂x      (Pa; > 0 resists the tape's motion).

That is the stress towards −x; a tape running backwards (V < 0) moves towards −x, and the
stress that resists its motion is −τ = μ|V|/(h + 2λ_e) − (h/2) ∂p/∂x: the readings
take τ sign(V) (sign 1 at V = 0), so that the drag acts against the motion and the tension
rises along it whichever way the tape runs (a reversed tape reads as the mirrored head's
forward one).

Drag and tension. ``viscous_drag`` = ∫ τ dA over the film (the model's whole domain: head
and spans), ``friction_drag`` = μ_f × the total contact force (Coulomb friction of the
head on the tape), ``drag`` their sum. The tape model keeps the tension T uniform along the
tape: the drag is the first-order change of tension across the head, ``tension_rise`` =
drag per unit width, and ``tension_ratio`` = 1 + tension_rise/T, outgoing (downstream in
the tape's motion) over incoming tension. For friction alone over
a wrap θ this is the capstan law to first order: the contact force is (T − ρV²)θ, so the
ratio is 1 + μ_f θ (T − ρV²)/T, against the exact (T_out − ρV²)/(T_in − ρV²) = e^{μ_f θ}
of a belt whose tension grows along the wrap; the difference is O((μ_f θ)²).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from ..core import validation
from ..core.errors import ParameterError

#: Contact within this many bending lengths √(D/(T − ρV²)) of a corner (beyond the
#: corner's own wrapped arc) belongs to the corner: the tape bends round a corner over
#: about one bending length, and a fixed physical zone keeps the reading grid-independent.
CORNER_ZONE_BENDING_LENGTHS = 1.0
#: Nodes closer than this fraction of the smallest interval to a point are at the point.
_AT_NODE = 1e-9


# ----- interpolation along x --------------------------------------------------------------
def along_x(x: np.ndarray, field: np.ndarray, x_t: float, kinks=()) -> np.ndarray:
    """The nodal ``field`` (shape (len(x), nc)) at the abscissa ``x_t`` (m), per column.

    Cubic Lagrange interpolation through the four nodes about ``x_t`` (fourth order on
    smooth fields, so it keeps the second order of the bearing's scheme on any grid),
    linear within the interval when one of ``kinks`` (m: the head's corners, where the
    spacing has a slope jump) lies inside the four-node stencil; exact at nodes.
    """
    x = np.asarray(x, dtype=float)
    field = np.asarray(field, dtype=float)
    n = len(x)
    if not x[0] <= x_t <= x[-1]:
        raise ParameterError(f"x = {x_t:g} m is off the grid [{x[0]:g}, {x[-1]:g}] m")
    i = int(np.clip(np.searchsorted(x, x_t, side="right") - 1, 0, n - 2))
    exact = np.flatnonzero(np.abs(x[i:i + 2] - x_t) <= _AT_NODE * (x[i + 1] - x[i]))
    if exact.size:
        return field[i + exact[0]].copy()
    lo = int(np.clip(i - 1, 0, max(n - 4, 0)))
    stencil = np.arange(lo, min(lo + 4, n))
    xs = x[stencil]
    if len(stencil) < 4 or any(xs[0] < k < xs[-1] for k in kinks):
        s = (x_t - x[i]) / (x[i + 1] - x[i])
        return (1.0 - s) * field[i] + s * field[i + 1]
    weights = np.array([np.prod([(x_t - xs[m]) / (xs[k] - xs[m])
                                 for m in range(4) if m != k]) for k in range(4)])
    return weights @ field[stencil]


def _width_mean(y: np.ndarray | None, row: np.ndarray) -> float:
    """The trapezoid-rule mean of ``row`` over the node line ``y`` (m); the one value of
    an infinitely wide tape."""
    if y is None:
        return float(row[0])
    y = np.asarray(y, dtype=float)
    return float(np.sum(0.5 * (row[1:] + row[:-1]) * np.diff(y)) / (y[-1] - y[0]))


@dataclass(frozen=True)
class TransducerLine:
    """The spacing along one transducer line x = x_t across the width.

    Attributes
    ----------
    x : float
        The line's abscissa, m (head coordinates).
    spacing : numpy.ndarray
        h(x_t, y_j) at the node columns, m (one value if infinitely wide).
    centre : float
        h at the middle of the width (the centre node), m.
    minimum : float
        Smallest of :attr:`spacing`, m.
    minimum_y : float or None
        Where it is, m across the width (None if infinitely wide).
    mean : float
        Trapezoid-rule mean over the width, m.
    """

    x: float
    spacing: np.ndarray
    centre: float
    minimum: float
    minimum_y: float | None
    mean: float

    def as_dict(self) -> dict:
        """The scalars as plain JSON values (the spacing array left out)."""
        return {"x": self.x, "centre": self.centre, "minimum": self.minimum,
                "minimum_y": self.minimum_y, "mean": self.mean}


def transducer_lines(x, y, spacing, transducers, kinks=()) -> tuple[TransducerLine, ...]:
    """The spacing along each transducer line x = x_t, its minimum and mean over the width.

    Parameters
    ----------
    x : numpy.ndarray
        Node abscissae, m, increasing.
    y : numpy.ndarray or None
        Node ordinates across the width, m (None: infinitely wide, one column).
    spacing : numpy.ndarray
        h on every node, m, shape (len(x), nc).
    transducers : sequence of float
        x_t of the read/write element lines, m, within [x[0], x[-1]].
    kinks : sequence of float
        Abscissae where h has a slope jump (the head's corners), m; see :func:`along_x`.
    """
    lines = []
    centre = 0 if y is None else (len(y) - 1) // 2
    for x_t in transducers:
        row = along_x(x, spacing, float(x_t), kinks)
        j = int(np.argmin(row))
        lines.append(TransducerLine(float(x_t), row, float(row[centre]), float(row[j]),
                                    None if y is None else float(y[j]), _width_mean(y, row)))
    return tuple(lines)


# ----- tents ------------------------------------------------------------------------------
@dataclass(frozen=True)
class Tent:
    """The tent next to one corner on one side (see :func:`tents`).

    Attributes
    ----------
    corner : float
        The corner's abscissa, m.
    side : str
        "land" or "span".
    height, x : float or None
        The tenting height along the middle of the width, m, and where it is, m; None if
        the spacing has no local maximum there.
    drop : float or None
        How far the centre line's spacing comes down past the tent: its height less the
        smallest nodal spacing between it and the search's far end, m (0 for a land
        tented end to end; a small drop marks a ripple rather than a tent).
    widest_height, widest_x, widest_y : float or None
        The largest of the tents of every node line across the width, m, and where it
        is, m (the same as the centre line's, with y None, if infinitely wide).
    """

    corner: float
    side: str
    height: float | None
    x: float | None
    drop: float | None
    widest_height: float | None
    widest_x: float | None
    widest_y: float | None

    def as_dict(self) -> dict:
        return asdict(self)


def _vertex(x: np.ndarray, h: np.ndarray, i: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Vertex (x*, h*) of the parabola through the nodes i − 1, i, i + 1 of each column
    (i per column; the grid may be graded)."""
    cols = np.arange(h.shape[1])
    x0, x1, x2 = x[i - 1], x[i], x[i + 1]
    h0, h1, h2 = h[i - 1, cols], h[i, cols], h[i + 1, cols]
    d1 = (h1 - h0) / (x1 - x0)
    d2 = (h2 - h1) / (x2 - x1)
    c2 = (d2 - d1) / (x2 - x0)
    curved = c2 < 0.0
    safe = np.where(curved, c2, -1.0)
    xv = np.where(curved, 0.5 * (x0 + x1) - d1 / (2.0 * safe), x1)
    hv = np.where(curved, h0 + d1 * (xv - x0) + c2 * (xv - x0) * (xv - x1), h1)
    return xv, hv


def _line_tents(x, spacing, start: float, end: float, *, with_end: bool = True):
    """Per column, the highest local maximum of the spacing (of the whole node line) at a
    node strictly past ``start`` and up to ``end`` (m, either order; ``with_end`` False:
    short of the nodes next to ``end``): (found, x*, h*), refined by the parabola through
    the node and its two neighbours."""
    n = len(x)
    lo, hi = min(start, end), max(start, end)
    tol = _AT_NODE * float(np.min(np.diff(x)))
    inner = np.arange(1, n - 1)
    xi = x[inner]
    beyond_start = np.abs(xi - start) > tol
    window = (xi >= lo - tol) & (xi <= hi + tol) & beyond_start
    if not with_end:
        window &= np.abs(xi - end) > x[inner + 1] - x[inner - 1]
    h = spacing
    peak = (h[inner] >= h[inner - 1]) & (h[inner] >= h[inner + 1]) \
        & ((h[inner] > h[inner - 1]) | (h[inner] > h[inner + 1]))
    peak &= window[:, None]
    found = peak.any(axis=0)
    masked = np.where(peak, h[inner], -np.inf)
    i = inner[np.argmax(masked, axis=0)]
    xv, hv = _vertex(x, h, np.where(found, i, inner[0]))
    return found, xv, hv


def _drop(x, line, x_tent: float, height: float, end: float) -> float:
    """The tent's height less the smallest nodal spacing of ``line`` between the tent
    and ``end`` (m), at least 0."""
    lo, hi = min(x_tent, end), max(x_tent, end)
    between = line[(x >= lo) & (x <= hi)]
    return max(height - float(between.min()), 0.0) if between.size else 0.0


def _land_of(corner: float, lands) -> tuple[float, float] | None:
    """The land (x_start, x_end) that ``corner`` (m) bounds: the one with the nearest end."""
    if not lands:
        return None
    return min(lands, key=lambda land: min(abs(land[0] - corner), abs(land[1] - corner)))


def _search_ends(corner: float, corners, lands, transducers, x_ends) -> dict:
    """{side: far end of the tent search, m} for a corner: on the land side the land's
    middle or the nearest transducer before it; on the span side the middle of the way to
    the next corner outward, or the domain's end."""
    land = _land_of(corner, lands)
    if land is None:
        return {}
    middle = 0.5 * (land[0] + land[1])
    toward = np.sign(middle - corner)
    between = [t for t in transducers if 0.0 < (t - corner) * toward < abs(middle - corner)]
    land_end = min(between, key=lambda t: abs(t - corner)) if between else middle
    outward = [c for c in corners if (c - corner) * toward < 0.0]
    if outward:
        span_end = 0.5 * (corner + min(outward, key=lambda c: abs(c - corner)))
    else:
        span_end = x_ends[0] if toward > 0 else x_ends[1]
    return {"land": land_end, "span": span_end}


def tents(x, y, spacing, corners, lands, transducers=()) -> tuple[Tent, ...]:
    """The tents next to each corner, on its land side and on its span side.

    A tent is the highest local maximum of the spacing h (tape above the head contour)
    along a node line, at a node past the corner and up to the search's far end; its
    height and position are the vertex of the parabola through that node and its two
    neighbours (second order on graded grids). The far end is, on the land side, the
    land's middle or the nearest transducer before it (a maximum there counts only if it
    is a local maximum of the whole line: the middle of a land tented end to end, not a
    spacing still rising towards a transducer); on the span side the middle of the way
    to the next corner outward (a module gap) or the domain's end, short of the nodes
    next to it (the spacing is largest in the middle of a gap, where the head falls
    away: that is the gap's depth, not a tent). Along the middle of
    the width (the centre node line) this gives :attr:`Tent.height` and :attr:`Tent.x`;
    over every node line across the width the largest gives the ``widest_*`` entries.
    A side with no local maximum reports None, not a made-up number.

    Parameters
    ----------
    x, y, spacing : numpy.ndarray
        As in :func:`transducer_lines` (y None if infinitely wide).
    corners : sequence of float
        The head's corners, m.
    lands : sequence of (float, float)
        The head's lands (x_start, x_end), m: each corner's land is the one whose end is
        nearest.
    transducers : sequence of float
        Transducer lines, m: a tent search on the land side stops at the first.
    """
    x = np.asarray(x, dtype=float)
    h = np.asarray(spacing, dtype=float)
    centre = 0 if y is None else (len(y) - 1) // 2
    out = []
    for c in corners:
        for side, end in _search_ends(float(c), corners, lands, transducers,
                                      (x[0], x[-1])).items():
            found, xv, hv = _line_tents(x, h, float(c), float(end),
                                        with_end=side == "land")
            if not found.any():
                out.append(Tent(float(c), side, None, None, None, None, None, None))
                continue
            j = int(np.argmax(np.where(found, hv, -np.inf)))
            mid = (float(hv[centre]), float(xv[centre]),
                   _drop(x, h[:, centre], float(xv[centre]), float(hv[centre]), float(end))
                   ) if found[centre] else (None, None, None)
            out.append(Tent(float(c), side, *mid, float(hv[j]), float(xv[j]),
                            None if y is None else float(y[j])))
    return tuple(out)


# ----- contact forces ---------------------------------------------------------------------
@dataclass(frozen=True)
class ContactShare:
    """The contact carried by one corner or land.

    Attributes
    ----------
    where : tuple of float
        (x,) of a corner or (x_start, x_end) of a land, m.
    force : float
        Sum of its nodal contact forces, N (N/m per unit width if infinitely wide).
    peak_pressure : float
        Largest contact pressure (nodal force over control area) among its nodes, Pa.
    centroid : float or None
        Force-weighted mean abscissa of its nodes, m (None without contact).
    nodes : int
        Its nodes in contact.
    """

    where: tuple
    force: float
    peak_pressure: float
    centroid: float | None
    nodes: int

    def as_dict(self) -> dict:
        return {"x" if len(self.where) == 1 else "extent":
                self.where[0] if len(self.where) == 1 else list(self.where),
                "force": self.force, "peak_pressure": self.peak_pressure,
                "centroid": self.centroid, "nodes": self.nodes}


def contact_owners(x, corners, lands, zones) -> np.ndarray:
    """Which corner or land each node line x_i belongs to, for the contact bookkeeping:
    k (< len(corners)) for corner k, len(corners) + l for land l.

    A node within ``zones[k]`` (m) of its nearest corner k belongs to it; otherwise to the
    land it lies on; a node on neither (a flank, a gap, a span) to its nearest corner.
    """
    x = np.asarray(x, dtype=float)
    corners = np.asarray(corners, dtype=float)
    nc = len(corners)
    if nc == 0:
        raise ParameterError("the head has no corner to assign contact to")
    zones = np.broadcast_to(np.asarray(zones, dtype=float), (nc,))
    distance = np.abs(x[:, None] - corners[None, :])
    nearest = np.argmin(distance, axis=1)
    owner = nearest.copy()
    in_zone = distance[np.arange(len(x)), nearest] <= zones[nearest]
    for k, (a, b) in enumerate(lands):
        on_land = (x >= a) & (x <= b) & ~in_zone
        owner[on_land] = nc + k
    return owner


def contact_shares(x, force, area, corners, lands, zones
                   ) -> tuple[tuple[ContactShare, ...], tuple[ContactShare, ...]]:
    """(corner shares, land shares) of the nodal contact forces.

    Parameters
    ----------
    x : numpy.ndarray
        Node abscissae of the rows of ``force``, m.
    force : numpy.ndarray
        Nodal contact forces, N (N/m if infinitely wide), shape (len(x), nc).
    area : numpy.ndarray
        The nodes' control areas, m² (m if infinitely wide), same shape.
    corners, lands : see :func:`tents`.
    zones : float or sequence of float
        Each corner's zone half-width, m (:func:`contact_owners`).

    Every node belongs to exactly one corner or land, so the shares' forces sum to the
    total contact force (to round-off).
    """
    x = np.asarray(x, dtype=float)
    force = np.asarray(force, dtype=float)
    owner = contact_owners(x, corners, lands, zones)
    pressure = contact_pressure(force, area)
    wheres = [(float(c),) for c in corners] + [(float(a), float(b)) for a, b in lands]
    shares = []
    for k, where in enumerate(wheres):
        rows = owner == k
        f = force[rows]
        total = float(f.sum())
        weight = f.sum(axis=1)
        shares.append(ContactShare(
            where, total, float(pressure[rows].max()) if f.size else 0.0,
            float(weight @ x[rows] / total) if total > 0.0 else None,
            int(np.count_nonzero(f))))
    n = len(corners)
    return tuple(shares[:n]), tuple(shares[n:])


def contact_pressure(force: np.ndarray, area: np.ndarray) -> np.ndarray:
    """The contact-pressure distribution on the nodes: nodal force over control area, Pa."""
    return np.asarray(force, dtype=float) / np.asarray(area, dtype=float)


# ----- shear and drag ---------------------------------------------------------------------
def shear_stress(x, spacing, pressure, velocity: float, air) -> np.ndarray:
    """The air's shear stress on the tape against its motion, Pa, on every node (> 0
    resists the motion, whichever way the tape runs): sign(V) (μV/(h + 2λ_e) +
    (h/2) ∂p/∂x) (module notes; sign 1 at V = 0), ∂p/∂x by the three-point difference of
    the graded grid (second order, one-sided at the domain's ends). The slip length λ_e
    is the local mean free path times the rarefaction model's slip coefficient
    (:data:`.rarefaction.SLIP_COEFFICIENTS`: 1 for first- and second-order slip, 1.147 for
    the Boltzmann flow rate, 0 without slip); the roughness's shear-stress factors
    (Patir & Cheng) are not applied: the mean gap h stands for the rough film.

    Parameters
    ----------
    x : numpy.ndarray
        Node abscissae, m.
    spacing, pressure : numpy.ndarray
        h (m) and p (Pa) on every node, shape (len(x), nc).
    velocity : float
        Tape speed V, m/s.
    air : AirParameters
        μ, λ, p_a and whether the film is compressible (λ_e = λ p_a/p) or not (λ_e = λ).
    """
    x = np.asarray(x, dtype=float)
    h = np.asarray(spacing, dtype=float)
    p = np.asarray(pressure, dtype=float)
    if np.any(h <= 0.0) or (air.compressible and np.any(p <= 0.0)):
        raise ParameterError("shear_stress needs positive spacings (and pressures for the "
                             "compressible film)")
    from .rarefaction import SLIP_COEFFICIENTS

    slip = (SLIP_COEFFICIENTS[air.rarefaction] * air.mean_free_path
            * (air.ambient_pressure / p if air.compressible else 1.0))
    dpdx = np.gradient(p, x, axis=0, edge_order=2)
    direction = -1.0 if velocity < 0.0 else 1.0
    return direction * (air.viscosity * velocity / (h + 2.0 * slip) + 0.5 * h * dpdx)


def integral(values: np.ndarray, area: np.ndarray) -> float:
    """Σ values × control area: ∫ values dA over the film (N for a stress in Pa; N/m per
    unit width if infinitely wide)."""
    return float(np.sum(np.asarray(values) * np.asarray(area)))


@dataclass(frozen=True)
class Drag:
    """The drag the head adds and the tension rise it implies (module notes).

    Attributes
    ----------
    viscous : float
        ∫ τ dA, N (N/m if infinitely wide).
    friction : float
        μ_f × total contact force, N (N/m).
    total : float
        viscous + friction, N (N/m).
    tension_rise : float
        total per unit width, N/m (the first-order change of T across the head).
    tension_ratio : float
        1 + tension_rise / T (dimensionless).
    """

    viscous: float
    friction: float
    total: float
    tension_rise: float
    tension_ratio: float


def drag(viscous: float, contact_force: float, friction: float, tension: float,
         width: float | None = None) -> Drag:
    """The :class:`Drag` of a viscous drag (N, N/m if ``width`` is None), a total contact
    force (N, N/m), a Coulomb coefficient ``friction`` (>= 0) and a tension T (N/m) of a
    tape of ``width`` (m; None: infinitely wide, everything per unit width)."""
    friction = validation.nonnegative("friction", friction)
    tension = validation.positive("tension", tension, "N/m")
    fric = friction * contact_force
    total = viscous + fric
    rise = total if width is None else total / width
    return Drag(float(viscous), float(fric), float(total), float(rise),
                float(1.0 + rise / tension))
