"""BearingModel: the tape (shell operators) and the air film on one grid, coupled.

Unknowns z = [u, p]: the tape's departure u from the dry wrapped configuration at the
tape's unknown nodes (m) and the film pressure p at the film-interior nodes (Pa). The
coupled residual is

    r_u = K u − W (p − p_a) + (T − ρV²) W κ − f_κ − λ          (N, or N/m per unit width)
    r_p = Σ_faces F + 12μ A ∂φ/∂t                               (film balance)

with λ the contact forces of the nodes in contact (see :mod:`.steady`). Its Jacobian is
assembled exactly: K, the coupling −W, and the film's ∂r_p/∂p, ∂r_p/∂h.
"""

from __future__ import annotations

import contextvars
import math
import warnings
from dataclasses import replace
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from ..core import validation
from ..core.errors import ParameterError
from ..linalg.factorization import check_pattern_lu
from ..tape.parameters import MIN_INTERVALS_ACROSS, TapeParameters
from . import budget
from .air import AIR_VISCOSITY, ROUGHNESS_RANGE, AirParameters, flow_factors_for
from .contact import ContactParameters
from .film import DryFilm, Film
from .head import (
    ARC_CONTACTS,
    CORNER_FRACTION,
    WRAPPED_ARC_BENDING_LENGTHS,
    Cylinder,
    FlatHead,
    Head,
    ProfileHead,
)
from .mesh import (
    UNIFORM,
    Grading,
    intervals_for,
    piecewise_line_nodes,
    symmetric_line_nodes,
)
from .tape import PlateOperators, StripOperators

#: Spans outside the wrap, in units of the larger of the film and bending lengths
#: (infinitely wide tape; the 2-D tape uses fewer: its cost grows with the domain).
SPAN_LENGTHS = 10.0
SPAN_LENGTHS_2D = 6.0
#: Shortest span, in the same units: the pressure must return to ambient before the tape's
#: pinned end. Measured (Table 1 tape at 1, 4 and 16 m/s, and D = 1e-10 N*m; infinitely
#: wide, against spans of 20 lengths): h_c is 2-4 % low at 3 lengths, 7-14 % at 2, 38-55 %
#: at 1 and 95 % at 1/4 (a span of 1e-12 m pinned the tape onto the head).
MIN_SPAN_LENGTHS = 3.0
#: Longest span, in units of the head radius R: the gap w₀ = s²/(2R) of the tangent spans is
#: the small-slope (shallow-shell) approximation, whose slope s/R must stay below 1.
MAX_SPAN_RADII = 1.0
#: Default x-spacing, in units of the resolution length (:func:`resolution_length`;
#: infinitely wide; 2-D).
#: Most intervals along the tape (an automatic grid past this means a film far shorter
#: than the wrap: a speed so low that the tape lies on the head).
MAX_INTERVALS_ALONG = 50_000
X_RESOLUTION = 1.0 / 12.0
X_RESOLUTION_2D = 1.0 / 6.0
#: A bending length shorter than this fraction of the film length is not resolved by the
#: default grid: its layers carry no error the film's own discretization does not already
#: make. Measured (infinitely wide, V = 4 m/s, uniform grids): with D = 1e-8 N*m (bending
#: length 0.03 film lengths) 400 intervals, 2.8 bending lengths each, put h_c within 7e-5
#: of the fully resolved value (25,600 intervals); with D = 1e-10 N*m 100 intervals,
#: 114 bending lengths each, within 0.12 %, the error of the same grid with no bending at
#: all. The Table 1 tape (0.53) is resolved by its bending length as before.
BENDING_RESOLVED = 0.5
#: Coarsest x-spacing within the wrap and one film length about it, in film lengths
#: R ε^(1/3): a coarser grid does not resolve the film. Measured (Table 1 tape, 4 m/s,
#: 15°; against the default grids): 2-D graded, h_c 48 % low at 1.94 film lengths
#: (nx = 8) and 2 % off at 0.88 (nx = 16); infinitely wide, 17 % at 2.8, 1.9 % at 1.9 and
#: 0.8 % at 1.4.
MAX_FILM_SPACING = 1.0
#: Coarsest y-spacing at the free edges before a warning, m: coarser edge rows falsely touch
#: down (measured on the 6.35 mm Table 1 tape at 4 m/s: 112 µm gave 2-17 nodes in contact
#: and h_min 20-90 % low, 74 µm none).
MAX_EDGE_SPACING = 100e-6
#: Default y-spacing of the uniform 2-D tape, m: resolves the free edges' boundary layer
#: (about 0.5 mm wide on the Table 1 tape at 4 m/s), whose spacing then converges to a few %.
Y_SPACING = 50e-6
#: The default 2-D grid is graded (see :mod:`.mesh`): this much finer at the wrap corners
#: than far along the spans, and at the free edges than in the middle of the width ...
DEFAULT_GRADING = Grading(x_ratio=4.0, x_width=None, y_ratio=10.0, y_width=0.4e-3)
#: ... with these spacings at the corners (in units of the resolution length) and at the
#: edges (m). Chosen by a refinement study (docs/bearing.md): on the
#: Table 1 tape at 4 m/s and 15° (12 µm both) the edge minimum is 0.55 % below its
#: Richardson value and the 12.65 mm tape solves in ~12 s.
X_RESOLUTION_GRADED = 1.0 / 15.0
Y_EDGE_SPACING = 12e-6
#: Width of the refined zones about the wrap corners, in units of the larger of the film
#: and bending lengths (when the grading leaves it unset).
X_GRADING_WIDTH = 1.5
#: Fewest intervals along x.
MIN_INTERVALS_ALONG = 8
#: Longest span of a flat or profile head, m (its spans are straight: no shallow-shell
#: limit; a sanity bound on the domain).
MAX_SPAN_FLAT = 0.1
#: The default grid of a flat or profile head resolves its shortest land, gap or wrapped
#: corner arc with at least this fraction of the resolution length ...
FEATURE_RESOLUTION = 0.5
#: ... and leaves at least this many intervals between two sharp corners.
FEWEST_BETWEEN_CORNERS = 4
#: A measured profile's feature the grid misses (:meth:`BearingModel._warn_unresolved_profile`)
#: is resolved by this many intervals across its width (the remedy the warning names).
FEATURE_NODES = 4
#: The default grid of a flat or profile head flying on its film refines towards every
#: corner geometrically (:func:`corner_grading`): spacing CORNER_GROWTH times the distance
#: from the corner beyond CORNER_WIDTH roughnesses. Measured (1 mm land, 2°/2°, Table 1
#: tape, 4 m/s, 1-D, against Richardson on 2 and 4 times finer grids): the spacing at
#: x = 0 within 0.21 % (growth 0.25, width 5 σ; 806 intervals, 0.04 s), 0.10 % at growth
#: 0.125, 0.85 % at 0.5; the width matters only logarithmically (0.17-0.66 % for 2.5-25 σ).
CORNER_GROWTH = 0.25
CORNER_WIDTH = 5.0
#: Classical flexible-foil constant, used only to size the domain and guess a start.
_FOIL_GUESS = 0.64
#: Newton's start over a flat or profile head: this fraction of the foil spacing scale
#: R_c ε^(2/3) at its sharpest corner (the sub-ambient flat pulls the tape far below it;
#: measured on single modules, 0.3-3 mm, 0.5-4°, 1-8 m/s: 7-13 iterations from 0.1,
#: 20-100 from the foil spacing itself) ...
FLAT_START = 0.1
#: ... and, dry, this fraction of the tent scale θ ℓ_bend; the sharp corners start at σ,
#: and (at speed) the spacing next to them rises from σ at this fraction of the corner's
#: turn: the tape's slope over the land at a touching corner (measured: 0.16 of the
#: 2° turn of a 1 mm land at 4 m/s; the start need only have the constriction's shape).
DRY_START = 0.25
START_SLOPE = 0.25


#: The least spacing the film sees under a smooth contact law, in roughnesses σ_s
#: (:attr:`BearingModel.film_floor`).
SMOOTH_FILM_FLOOR = 0.05
#: Under a smooth contact law the corners' geometric refinement (:func:`corner_grading`)
#: is sized by this many roughnesses σ_s: the leak through a pressed corner, which meters
#: the land's film, is set where the mean gap is least, over some 60 nm. Measured (1 mm
#: land, 2°/2°, 4 m/s, 1-D): at 10 σ_s (75 nm cells at the corner) the land's pressure was
#: 6.5, 8.1, 12.0 kPa on 1, 2, 4 times the intervals; at 2 σ_s (15 nm) 12.20, 12.08,
#: 12.03 kPa and the transducer spacing 10.420, 10.417, 10.416 nm (order 1.1).
SMOOTH_CORNER_SCALE = 2.0
#: A smooth contact law is evaluated only where h is below this many roughnesses σ_s:
#: beyond, the Gaussian summit heights give p_c < 1e-300 Pa (exp(−t²/2) at t = 38).
CONTACT_REACH = 38.0


#: The least mean gap the film sees, in roughnesses σ_s (:func:`mean_gap`): 6 pm at
#: σ_s = 6 nm, a tape pressed far into its summits.
MIN_MEAN_GAP = 1e-3


def mean_gap(d: np.ndarray, sigma: float) -> np.ndarray:
    """The mean gap h_T between the head and a tape whose surface heights are Gaussian of
    standard deviation σ (m) about a mean plane at the separation d (m): the expected
    clearance E[max(d − z, 0)] = σ (t Φ(t) + φ(t)), t = d/σ (Patir & Cheng's h_T, J.
    Lubr. Technol. 100:12, 1978), plus :data:`MIN_MEAN_GAP` σ. It is d for d ≫ σ
    (within σ φ(t)/t² : 1e-3 σ at t = 3) and falls smoothly to the floor as the tape is
    pressed into its summits (d < 0), where the air leaks only through the valleys: the
    film's gap under the asperity law. The summits' heights stand in for the surface's
    (their mean plane is d's)."""
    from scipy.special import ndtr

    t = d / sigma
    return sigma * (t * ndtr(t) + np.exp(-0.5 * t * t) / math.sqrt(2.0 * math.pi)
                    + MIN_MEAN_GAP)


def mean_gap_slope(d: np.ndarray, sigma: float) -> np.ndarray:
    """dh_T/dd = Φ(d/σ) of :func:`mean_gap` (dimensionless, in (0, 1))."""
    from scipy.special import ndtr

    return ndtr(d / sigma)


def smooth_floor(h: np.ndarray, floor: float) -> tuple[np.ndarray, np.ndarray]:
    """(h_f, dh_f/dh): a smooth maximum of h and ``floor`` (m), h_f = f + ((h − f) +
    √((h − f)² + f²))/2, which is f/2 + h/2 ... h for h ≫ f (h_f − h = f²/(4 (h − f))
    to leading order) and tends to f as h → −∞."""
    s = h - floor
    root = np.sqrt(s * s + floor * floor)
    return floor + 0.5 * (s + root), 0.5 * (1.0 + s / root)


def _resolved_contact(contact, air: AirParameters):
    """(contact, air) of the constructor: the contact parameters (default
    :func:`default_contact`) and the air with its ``roughness`` set to the contact's
    length (the one roughness the grid, the starts and the film's floor are sized by) and
    its ``"auto"`` flow factors resolved (Patir–Cheng's under the asperity law)."""
    contact = default_contact(air) if contact is None else contact
    contact = validation.instance("contact", contact, ContactParameters)
    scale = contact_length(contact)
    if scale != air.roughness:
        air = air.replace(roughness=scale)
    return contact, flow_factors_for(air, contact.law == "asperity")


def default_contact(air: AirParameters) -> ContactParameters:
    """The contact of ``contact=None``: Greenwood–Williamson asperities of a modern data
    tape (:class:`~.contact.ContactParameters`' defaults), with σ_s the air's
    ``roughness`` if given."""
    if air.roughness is None:
        return ContactParameters(law="asperity")
    return ContactParameters(law="asperity", roughness=air.roughness)


def contact_length(contact: ContactParameters) -> float:
    """The length the contact acts over, m: the wall's gap, the summits' σ_s, or for a
    measured curve a quarter of its separations' span (within the roughness range): the
    grid's corner refinement, the film's floor and Newton's steps are sized by it."""
    if contact.roughness is not None:
        return contact.roughness
    curve = contact.compliance
    low, high = ROUGHNESS_RANGE
    return float(min(max(0.25 * (curve.separations[-1] - curve.separations[0]), low), high))


#: The contact floor of the rounded arcs' nodes other than the contact node, m: far below
#: any spacing (they never enter the contact set; :attr:`BearingModel.contact_floor`).
NO_CONTACT_FLOOR = -1.0


#: Set while :meth:`BearingModel.at_velocity` builds a continuation stage.
_CONTINUATION_STAGE: contextvars.ContextVar[bool] = contextvars.ContextVar(
    "continuation_stage", default=False)


class BearingGridWarning(UserWarning):
    """The grid is coarse enough that the result may be off (the message says by how much)."""


class BearingModelWarning(BearingGridWarning):
    """The model's own assumptions stop holding for this input (the message says where);
    a kind of :class:`BearingGridWarning`, so that whatever shows or silences the one
    does the other."""


#: A cylinder keeps the wrapped shell's hoop stiffness k on its straight spans too, where
#: the flat tape has none; there it holds the tape up with about HOOP_SPAN_SUPPORT
#: k R² ε (N/m, ε = 6μ|V|/(T − ρV²)): the spacing ~ R ε^(2/3) over the entrance and
#: exit lengths ~ R ε^(1/3). Measured as the air force less the wrap load (T − ρV²) θ at
#: wraps of 0.01° and 0.1° (where the arc's own share is negligible; it also holds the
#: pinned span ends' reaction): 0.9-2.3 k R² ε over T 45-90 N/m, V 2-8 m/s, R 10-20 mm.
HOOP_SPAN_SUPPORT = 2.3
#: The model holds while that support is at most this fraction of the wrap load, i.e. for
#: θ >= (HOOP_SPAN_SUPPORT / HOOP_SPAN_SHARE) k R² ε/(T − ρV²)
#: = 23 (ℓ_film/R)(ℓ_film/ℓ_k)², ℓ_film = R ε^(1/3) and ℓ_k = √((T − ρV²)/k) (6.2° for the
#: Table 1 tape at 4 m/s); below it the model warns (:class:`BearingModelWarning`).
HOOP_SPAN_SHARE = 0.1


def foil_length_scales(params: TapeParameters, air: AirParameters, velocity: float,
                       radius: float | None = None) -> tuple[float, float, float]:
    """(h_foil, ℓ_film, ℓ_bend), m: the flexible-foil spacing scale R ε^(2/3), the entrance
    and exit length R ε^(1/3) (ε = 6μV/(T − ρV²)) and the bending length √(D/(T − ρV²));
    R is ``radius`` (m; default the tape's radius)."""
    t_eff = params.tension - params.density * velocity**2
    eps = 6.0 * air.viscosity * abs(velocity) / t_eff
    r = params.radius if radius is None else radius
    return r * eps ** (2 / 3), r * eps ** (1 / 3), math.sqrt(params.D / t_eff)


def effective_radius(head: Head, params: TapeParameters, velocity: float,
                     radius: float) -> float:
    """The radius R_c the tape bends to at the head's sharpest corner, m, sizing its film:
    the cylinder's radius; for other heads the smallest over corners turning by at least
    5 % of the wrap of max(r_c, ℓ_bend/θ_c) (a sharp corner is rounded by bending over the
    bending length ℓ_bend = √(D/(T − ρV²)))."""
    if isinstance(head, Cylinder):
        return radius
    l_bend = math.sqrt(params.D / (params.tension - params.density * velocity**2))
    radii = [max(r, l_bend / t) for r, t in zip(head.corner_radii(radius),
                                               head.corner_turns(radius), strict=True)
             if t >= CORNER_FRACTION * head.wrap]
    return float(min(radii))


def corner_grading(roughness: float, spacing: float) -> dict:
    """The corner refinement of a flat or profile head's default grid (the ``Grading``
    fields ``corner_ratio``, ``corner_width``), given the roughness σ (m) and the x-spacing
    the grid has far from the corners (m; density 1 of :class:`~.mesh.LineGrading`).

    A sharp corner that touches holds the tape at σ at a kink of the head: the spacing
    rises linearly from σ on both sides, h ≈ σ + α|s|, with α the angle between the tape
    and the head (the tape's slope over the land, 0.16 of the corner's turn on a 1 mm land
    at 4 m/s, and the flank angle minus it on the flank): the film's constriction, which
    meters the flow onto the land and so sets the spacing over it, is σ/α long (3.6 µm on
    the land side, 57 nm on a 20° flank), far below the film length R_c ε^(1/3) the grid
    is otherwise sized from. Lengths σ/α over that range are all resolved at the same
    relative resolution by a geometric grid: the spacing grows as :data:`CORNER_GROWTH`
    times the distance from the corner beyond :data:`CORNER_WIDTH` σ, and joins the
    grid's own spacing where that reaches it."""
    width = CORNER_WIDTH * roughness
    return {"corner_ratio": 1.0 + spacing / (CORNER_GROWTH * width),
            "corner_width": width}


def _resolved_head(wrap_angle, head) -> Head:
    """The head from the constructor's ``wrap_angle`` / ``head`` (exactly one)."""
    if (wrap_angle is None) == (head is None):
        raise ParameterError("give exactly one of wrap_angle (rad, a cylinder of the tape's "
                             f"radius) and head (a Cylinder, FlatHead or ProfileHead), got "
                             f"wrap_angle={wrap_angle!r} and head={type(head).__name__}")
    if head is None:
        return Cylinder(wrap_angle)
    return validation.instance("head", head, Head)


def resolution_length(l_film: float, l_bend: float) -> float:
    """The length the default grid resolves, m: the smaller of the film length ``l_film``
    and the bending length ``l_bend``, but no less than :data:`BENDING_RESOLVED` film
    lengths (thinner bending layers need no resolving)."""
    return min(l_film, max(l_bend, BENDING_RESOLVED * l_film))


#: A wrapped arc of r_c θ_c up to this many bending lengths is touched at about one point
#: (the dry tape lies on the arc less a bending length at either end: nothing of it below
#: two), so the default grid is refined there as about a point contact
#: (:meth:`BearingModel.wrapped_centres`); a longer arc is flown over as a cylinder.
POINT_LIKE_ARC_BENDING_LENGTHS = 2.0


def wrapped_corners(head: Head, l_bend: float, arc_contact: str = "auto") -> tuple[int, ...]:
    """Indices (into ``head.corners()``) of the rounded corners the tape wraps: those
    whose arc r_c θ_c exceeds :data:`WRAPPED_ARC_BENDING_LENGTHS` bending lengths
    ``l_bend`` (m) for ``arc_contact="auto"``, every rounded corner for "wrapped", none
    for "point" (the others are touched at one point, :mod:`.corners`)."""
    arc_contact = validation.choice("arc_contact", arc_contact, ARC_CONTACTS)
    if not isinstance(head, FlatHead) or arc_contact == "point":
        return ()
    radii, turns = head.corner_radii(), head.corner_turns()
    return tuple(k for k in head.rounded_corners()
                 if arc_contact == "wrapped"
                 or radii[k] * turns[k] > WRAPPED_ARC_BENDING_LENGTHS * l_bend)


def _check_below_string_speed(params: TapeParameters, velocity: float) -> None:
    """Raise unless |V| (m/s) is below the string speed √(T/ρ) (else the tape would not
    wrap)."""
    if params.tension - params.density * velocity**2 <= 0.0:
        raise ParameterError(
            f"velocity must be below the string speed sqrt(T/rho) = "
            f"{params.string_speed:.6g} m/s in magnitude (the tape would not wrap), got "
            f"{velocity:g}")


def _checked_velocity(velocity, dry: bool) -> float:
    """V, m/s: a finite real number, nonzero unless ``dry`` (the film needs the tape to
    move; either direction: negative V moves the tape along −x)."""
    velocity = validation.real("velocity", velocity, unit="m/s")
    if velocity == 0.0 and not dry:
        raise ParameterError("velocity must be nonzero (either sign: the tape moving along "
                             "+x or -x) for the air film, got 0; use dry=True for the tape "
                             "at rest")
    return velocity


def _resolved_grading(grading: Grading | str | None, infinitely_wide: bool,
                      x_width: float) -> Grading:
    """The grid's :class:`Grading` from the constructor's ``grading`` argument (see
    :class:`BearingModel`), its unset x-width set to ``x_width`` (m)."""
    if grading is None:
        grading = UNIFORM if infinitely_wide else DEFAULT_GRADING
    elif isinstance(grading, str):
        if grading != "uniform":
            raise ParameterError(f"grading must be a Grading or 'uniform', got {grading!r}")
        grading = replace(UNIFORM, corner_ratio=1.0)
    elif not isinstance(grading, Grading):
        raise ParameterError(f"grading must be a Grading or 'uniform', got {grading!r}")
    if grading.x_width is None:
        grading = replace(grading, x_width=x_width)
    return grading


class BearingModel:
    """A tape flying over a head on its self-generated air film.

    Parameters
    ----------
    params : TapeParameters
        The tape (E, ν, c, R, ρ, T, width, D, k overrides); its ``spacing`` and
        ``length_ratio`` are not used: the bearing sizes its own grid.
    air : AirParameters
    velocity : float
        Tape speed V, m/s: |V| below the string speed √(T/ρ), nonzero unless ``dry``;
        V > 0 moves the tape along +x (from the head's leading corner, at negative x, to
        its trailing one), V < 0 along −x (a linear drive reading backwards: the solution
        over a head at −V is the mirror image of the solution at +V over the mirrored head).
    wrap_angle : float, optional
        Wrap angle θ of the tape on a cylindrical head of the tape's radius R, rad, in
        (0, π/2]: the same as ``head=Cylinder(wrap_angle)``. The cylinder keeps the
        hoop stiffness k on its straight spans too: the model holds for θ at least
        :meth:`smallest_valid_wrap`, 23 (ℓ_film/R)(ℓ_film/ℓ_k)² with ℓ_film = R ε^(1/3),
        ℓ_k = √((T − ρV²)/k) (6.2° for the Table 1 tape at 4 m/s; see
        :data:`HOOP_SPAN_SHARE`), and warns below it (:class:`BearingModelWarning`).
    head : Head, optional
        The head (:mod:`gyroshell.bearing.head`): a Cylinder, FlatHead or ProfileHead;
        exactly one of ``wrap_angle`` and ``head``. The domain is [x_first − span,
        x_last + span] in head coordinates (``head.extent``).
    infinitely_wide : bool
        Infinitely wide tape (1-D, per unit width) instead of the free-edged 2-D tape.
    span : float, optional
        Length of each tangent span in the domain, m, in [3 ℓ, R] with ℓ the larger of the
        film length R ε^(1/3) and the bending length √(D/(T − ρV²)) (default: 10 (2-D: 6)
        ℓ, at most R).
    nx : int, optional
        Intervals along x, in [8, 50000], leaving at most one film length between nodes
        near the wrap corners (default: on the graded 2-D grid a spacing of 1/15 of the
        resolution length at the wrap corners, a multiple of 4; on a uniform grid 1/12
        (2-D: 1/6) of it, made even). The resolution length is the smaller of the film
        and bending lengths, but no less than half the film length
        (:func:`resolution_length`).
    ny : int, optional
        Intervals across the width in 2-D (even, >= 8; default: an edge spacing near
        12 µm on the graded grid, a multiple of 4; a spacing near 50 µm on a uniform one;
        an edge spacing above 100 µm warns, :class:`BearingGridWarning`). None for the
        infinitely wide tape.
    grading : Grading or "uniform", optional
        How the grid is graded (:class:`gyroshell.bearing.mesh.Grading`). Default: the
        2-D tape's grid is graded towards the free edges and the wrap corners
        (:data:`DEFAULT_GRADING`), the infinitely wide tape's is uniform. ``"uniform"``:
        uniform each way (no corner refinement either). A grading given to an infinitely
        wide tape grades its x-grid. Every corner is a refinement centre, and a flat or
        profile head's grid has a node exactly on every sharp corner; flying on its film,
        it is also geometric about every corner unless the grading's ``corner_ratio`` is
        set (:func:`corner_grading`: the film's constriction where a corner touches).
    dry : bool
        No air film (p = p_a; the tape and its contact with the head only): the dry
        string and plate over the head, corner forces at rest (V may be 0; it enters only
        through T − ρV²).
    factorization : {"auto", "grid", "metis", "mmd", "colamd", "pardiso"}
        The sparse LU of Newton's Jacobian (:data:`gyroshell.linalg.factorization.PATTERN_LU`):
        "auto" is, in 2-D, "grid": SuperLU with diagonal pivots after a nested dissection
        along the grid's node lines (pure numpy and scipy, once per grid); "metis" the
        same after METIS's nested dissection (pymetis); "mmd" after minimum degree on
        Jᵀ + J (ordered at each factorization); for the
        infinitely wide tape "colamd": SuperLU with partial pivoting (the earlier default,
        3-5x slower on a 2-D grid); "pardiso" needs pypardiso. All give the same state to
        Newton's tolerance.
    corner_contacts : tuple of float, optional
        x of the tape's contact on each rounded corner the tape turns over (head
        coordinates, m, each on its arc, in the order of :attr:`rounded_corners`): a node
        goes there, the centre of the corner's refinement, the only node of the arc that
        may touch (:mod:`.corners`). Default: :meth:`estimated_contacts`.
    adapt_contacts : bool
        Whether :func:`~gyroshell.bearing.steady.solve_steady` moves the contacts to the
        tangent points by solve-and-regrid passes (default) or keeps them.
    arc_contact : {"auto", "point", "wrapped"}
        How the tape meets a rounded corner: "point", at one tangent point (a node there,
        the corner's other arc nodes free of contact, :mod:`.corners`), valid while the
        tape is less curved than the arc; "wrapped", lying on part of the arc (every arc
        node may touch: the general contact set, the arc resolved by the grid); "auto"
        (default) per corner, wrapped when r_c θ_c exceeds
        :data:`WRAPPED_ARC_BENDING_LENGTHS` bending lengths (:func:`wrapped_corners`).

    Raises
    ------
    ParameterError
        Before anything of the grid's size is allocated: an argument of the wrong type or
        range, a span outside its range (naming the film or bending length that sets it,
        and whether the viscosity, the speed or the tape's stiffness makes it so), a grid
        too coarse for the film (naming the smallest nx) or too large for the memory limit
        (:func:`gyroshell.bearing.budget.check_steady`).
    """

    def __init__(self, params: TapeParameters, air: AirParameters | None = None, *,
                 velocity: float, wrap_angle: float | None = None, head: Head | None = None,
                 infinitely_wide: bool = False, span: float | None = None,
                 nx: int | None = None, ny: int | None = None,
                 grading: Grading | str | None = None, dry: bool = False,
                 factorization: str = "auto", corner_contacts=None,
                 adapt_contacts: bool = True, arc_contact: str = "auto",
                 contact: ContactParameters | None = None) -> None:
        self.factorization = check_pattern_lu(factorization)
        self.params = validation.instance("params", params, TapeParameters)
        self.air = validation.instance("air", AirParameters() if air is None else air,
                                       AirParameters)
        self._set_contact(contact)
        self.dry = validation.boolean("dry", dry)
        self.velocity = _checked_velocity(velocity, self.dry)
        self.head = _resolved_head(wrap_angle, head)
        self.cylindrical = isinstance(self.head, Cylinder)
        self.head_radius = (self.head.radius if self.cylindrical and self.head.radius
                            else params.radius)
        self.head.check(self.head_radius)
        self.wrap_angle = self.head.wrap
        self.infinitely_wide = validation.boolean("infinitely_wide", infinitely_wide)
        _check_below_string_speed(params, self.velocity)
        self.scale_radius = effective_radius(self.head, params, self.velocity,
                                             self.head_radius)
        h_foil, l_film, l_bend = foil_length_scales(params, self.air, self.velocity,
                                                    self.scale_radius)
        h_foil, l_film = (0.0, 0.0) if self.dry else (h_foil, l_film)
        self.film_length, self.bending_length = l_film, l_bend
        self._warn_small_wrap()
        self._set_arcs(arc_contact, l_bend)
        self.h_guess = _FOIL_GUESS * self._foil_spacing(h_foil, l_film)
        self.span = self._checked_span(span, l_film, l_bend)
        self.adapt_contacts = validation.boolean("adapt_contacts", adapt_contacts)
        self.corner_contacts = self._checked_contacts(corner_contacts)
        x_first, x_last = self.head.extent(self.head_radius)
        self.length = ((self.head_radius * self.wrap_angle if self.cylindrical
                        else x_last - x_first) + 2.0 * self.span)
        self.grading = _resolved_grading(grading, self.infinitely_wide,
                                         X_GRADING_WIDTH * max(l_film, l_bend))
        resolution = self._resolution(l_film, l_bend)
        self.grading = self._feature_zones(grading is None, l_film, l_bend, resolution)
        if self.grading.corner_ratio is None:
            self.grading = replace(self.grading, **self._corner_grading(resolution))
        x_line = self._x_count(nx, l_film, resolution, span is not None)
        ny, y_line = self._y_grid(ny)
        budget.check_steady(self.nx, ny, self.factorization)   # before any array of that size
        self.x = self._x_nodes(x_line)
        self._check_film_resolved(l_film, x_line)
        self._warn_unresolved_profile()
        tape_params = (params if self.cylindrical else params.replace(
            foundation_stiffness=self.head.foundation_stiffness(params)))
        if self.infinitely_wide:
            self.ny, self.y, self.nc = None, None, 1
            self.tape = StripOperators(tape_params, self.x)
        else:
            self._build_y_line(ny, y_line)
            self.tape = PlateOperators(tape_params, self.x, self.y)
        self._couple_film_and_loads()

    def _set_contact(self, contact) -> None:
        """:attr:`contact`, :attr:`smooth_contact` and :attr:`contact_law` of the
        constructor's ``contact`` (the air's roughness set to the contact's)."""
        self.contact, self.air = _resolved_contact(contact, self.air)
        #: Whether contact is a smooth law of the spacing (asperities, a measured curve)
        #: acting wherever the tape is near the head, rather than a hard wall
        self.smooth_contact = self.contact.law != "hard"
        #: The smooth law (``pressure(h) -> (p_c, dp_c/dh)``, Pa and Pa/m) or None
        self.contact_law = self.contact.law_object if self.smooth_contact else None

    def _set_arcs(self, arc_contact: str, l_bend: float) -> None:
        """:attr:`arc_contact` and :attr:`wrapped_corners`: under a smooth contact law
        every rounded corner's arc is resolved by the grid (its law acts on every node)."""
        self.arc_contact = validation.choice("arc_contact", arc_contact, ARC_CONTACTS)
        if self.smooth_contact and self.arc_contact == "point":
            raise ParameterError(
                "arc_contact='point' applies to the hard wall (contact law 'hard') only: a "
                f"smooth contact law ({self.contact.law!r}) acts on every node of a rounded "
                "corner's arc; use arc_contact='auto' (or 'wrapped')")
        self.wrapped_corners = wrapped_corners(
            self.head, l_bend, "wrapped" if self.smooth_contact else self.arc_contact)

    @cached_property
    def jacobian_patterns(self) -> dict:
        """Newton's folded Jacobian patterns' digests on this grid by factorization kind,
        with the tape rows' pattern each was formed from
        (:func:`gyroshell.bearing.problem._model_pattern`): a cache, formed again on use
        (not part of the model's state: a loaded model starts it empty)."""
        return {}

    def _y_grid(self, ny):
        """(ny, the y-line of :meth:`Grading.y_line`) of a 2-D tape; (None, None) if
        infinitely wide (where ``ny`` must be None)."""
        if self.infinitely_wide:
            if ny is not None:
                raise ParameterError(f"ny applies to the 2-D tape only: leave it None with "
                                     f"infinitely_wide=True, got {ny!r}")
            return None, None
        y_line = self.grading.y_line(self.params.width)
        return self._y_count(ny, y_line), y_line

    def _resolution(self, l_film: float, l_bend: float) -> float:
        """The length the default x-grid resolves, m (:func:`resolution_length`; dry: the
        bending length; a flat or profile head also its shortest feature)."""
        length = l_bend if self.dry else resolution_length(l_film, l_bend)
        if isinstance(self.head, FlatHead):      # lands, gaps and the wrapped arcs
            radii, turns = self.head.corner_radii(), self.head.corner_turns()
            # under a smooth law a short arc the tape touches at about a point is
            # resolved by the corner grading about its centre, not by the whole grid
            short = self.touching_arcs if self.smooth_contact else ()
            feature = min([self.head.shortest_land()] + [
                radii[k] * turns[k] for k in self.wrapped_corners
                if turns[k] >= CORNER_FRACTION * self.wrap_angle and k not in short])
            length = min(length, FEATURE_RESOLUTION * feature)
        elif not self.cylindrical:
            length = min(length, FEATURE_RESOLUTION
                         * self.head.shortest_feature(self.head_radius))
        return length

    @property
    def film_over_head(self) -> bool:
        """Whether the film length R_c ε^(1/3) (:attr:`film_length`, m) exceeds a flat or
        profile head's wrapped region: one film then covers the whole head, the tape flies
        over its corners (at 0.01 deg over a 1 mm land, 4 m/s, 6.7-7 µm above them) and
        the spacing scale is the head's (:meth:`_foil_spacing`)."""
        if self.cylindrical or self.film_length == 0.0:
            return False
        x_first, x_last = self.head.extent(self.head_radius)
        return self.film_length > x_last - x_first

    def _foil_spacing(self, h_foil: float, l_film: float) -> float:
        """The flexible-foil spacing scale, m: R_c ε^(2/3) (``h_foil``), or, where the film
        covers the whole head (:attr:`film_over_head`), the wrapped region's length times
        ε^(1/3): the foil's spacing is ε^(1/3) times the length its film forms over (the
        tape's curvature T h/ℓ² against the film's 6μV ℓ/h²), and no film forms over more
        than the head. Measured (a 1 mm land at 0.01 deg, 4 m/s, 1-D): the spacing is
        7 µm against this scale's 17 µm and the foil's 290 µm."""
        if not self.film_over_head:
            return h_foil
        x_first, x_last = self.head.extent(self.head_radius)
        return h_foil / l_film * (x_last - x_first)

    def _feature_zones(self, default: bool, l_film: float, l_bend: float,
                       resolution: float) -> Grading:
        """The grading (``default``: the constructor's default, else left as given) of a
        head one film covers (:attr:`film_over_head`), its short features resolved about
        the head alone.

        A land, gap or wrapped arc shorter than the film or bending length sets the
        default x-spacing at the corners (:meth:`_resolution`). Where the film length
        R_c ε^(1/3) exceeds the whole head, the film reaches no further than the head
        (beyond its outer corners the flanks fall away), while the spans, sized from the
        film length (:meth:`_checked_span`), carry only the tape. The zones about the
        corners are then as wide as :data:`X_GRADING_WIDTH` features (no wider than
        before) and the spacing beyond them is that of the film and bending lengths: the
        grading's ratio grows by their resolution length over the feature's. Without it
        the feature's spacing filled the spans: at 0.01 deg wraps over a 1 mm land (film
        length 17 mm, spans of 0.1 m) 3064 intervals along x, with it 336 (the spacings
        within 0.01 % of those on twice the intervals)."""
        grading = self.grading
        film = l_bend if self.dry else resolution_length(l_film, l_bend)
        if not default or resolution >= film or not self.film_over_head:
            return grading
        feature = resolution / FEATURE_RESOLUTION
        return replace(grading, x_ratio=grading.x_ratio * film / resolution,
                       x_width=min(grading.x_width, X_GRADING_WIDTH * feature))

    def wrapped_contact(self, k: int) -> tuple[float, float]:
        """(x_start, x_end), m (head coordinates): where the dry tape lies on the wrapped
        arc of corner ``k`` (index into ``head.corners()``) for a long land and a long
        span, the arc less a bending length ℓ_bend at either end (each free side of the
        contact turns by ℓ_bend/r_c: its boundary layer's curvature decays from the arc's
        1/r_c over ℓ_bend); the arc's middle if the arc is shorter than 2 ℓ_bend."""
        r, turn = self.head.corner_radii()[k], self.head.corner_turns()[k]
        sign = 1.0 if k % 2 == 0 else -1.0          # the arc's slope turns from the land's
        free = self.bending_length / r
        ends = [self.head.arc_point(k, self.head.land_slope(k) + sign * s)
                for s in (min(free, 0.5 * turn), max(turn - free, 0.5 * turn))]
        return min(ends), max(ends)

    @property
    def rounded_corners(self) -> tuple[int, ...]:
        """Indices (into ``head.corners()``) of the rounded corners the tape turns over and
        touches at one point, in the order of :attr:`corner_contacts` (empty but on a flat
        head; the wrapped ones, :attr:`wrapped_corners`, are not among them)."""
        if not isinstance(self.head, FlatHead):
            return ()
        return tuple(k for k in self.head.rounded_corners()
                     if k not in self.wrapped_corners)

    def _checked_contacts(self, contacts) -> tuple[float, ...]:
        """The x (head coordinates, m) of the tape's contact on each rounded corner: given
        (each on its corner's arc), or the estimate :meth:`estimated_contacts`."""
        rounded = self.rounded_corners
        if contacts is None:
            return self.estimated_contacts()
        values = tuple(validation.real(f"corner_contacts[{i}]", c, unit="m")
                       for i, c in enumerate(np.atleast_1d(np.asarray(contacts, float))))
        if len(values) != len(rounded):
            raise ParameterError(f"corner_contacts must hold one x (m) per rounded corner "
                                 f"the tape turns over ({len(rounded)}), got {len(values)}")
        for i, (k, c) in enumerate(zip(rounded, values, strict=True)):
            lo, hi = self.head.arc_tangent_points(k)
            if not lo <= c <= hi:
                raise ParameterError(f"corner_contacts[{i}] must lie on the arc of corner "
                                     f"{k}, [{lo:.9g}, {hi:.9g}] m, got {c:.9g}")
        return values

    def estimated_contacts(self) -> tuple[float, ...]:
        """The start of the contact points on the rounded corners, m (head coordinates):
        where the arc's slope has turned from the land's by :data:`START_SLOPE` of the
        corner's turn at speed (the tape's slope at a touching sharp corner, measured
        0.16 of it), half of it dry (the turn split between the two bending layers)."""
        turns = self.head.corner_turns(self.head_radius) if self.rounded_corners else ()
        share = 0.5 if self.dry else START_SLOPE
        out = []
        for k in self.rounded_corners:
            sign = 1.0 if k % 2 == 0 else -1.0
            out.append(self.head.arc_point(k, self.head.land_slope(k)
                                           + sign * share * turns[k]))
        return tuple(out)

    def _centres(self) -> tuple[float, ...]:
        """The grading's refinement centres, head coordinates, m: every corner, a rounded
        one at its contact point (the film's constriction and the tape's point load)."""
        centres = list(self.head.corners(self.head_radius))
        for k, c in zip(self.rounded_corners, self.corner_contacts, strict=True):
            centres[k] = c
        for k, c in zip(self.touching_arcs, self.wrapped_centres(), strict=True):
            centres[k] = c
        return tuple(centres)

    @property
    def touching_arcs(self) -> tuple[int, ...]:
        """The wrapped arcs (:attr:`wrapped_corners`) the tape touches at about one point:
        r_c θ_c at most :data:`POINT_LIKE_ARC_BENDING_LENGTHS` bending lengths (a longer
        arc the dry tape lies on, and at speed flies over as over a cylinder)."""
        if not self.wrapped_corners:
            return ()
        radii, turns = self.head.corner_radii(), self.head.corner_turns()
        return tuple(k for k in self.wrapped_corners
                     if radii[k] * turns[k] <= POINT_LIKE_ARC_BENDING_LENGTHS
                     * self.bending_length)

    def wrapped_centres(self) -> tuple[float, ...]:
        """The refinement centre on each touching wrapped arc (:attr:`touching_arcs`), m (head
        coordinates): where a point contact would start (as :meth:`estimated_contacts`:
        the arc's slope turned from the land's by :data:`START_SLOPE` of the corner's turn
        at speed, half of it dry). Near the handover the tape touches a wrapped arc at one
        point, 1-5 µm from there at 4 m/s (measured): the film's constriction about it is
        then resolved as on the point model's grid (refined about the arcs' geometric
        corner points instead, as before, the corner forces at the handover radii were
        1.9-33 % off the refined grid's, and 0.2-8 % with this centre: measured,
        benchmarks/bearing_arc_handover.py)."""
        turns = self.head.corner_turns(self.head_radius)
        share = 0.5 if self.dry else START_SLOPE
        return tuple(self.head.arc_point(k, self.head.land_slope(k)
                                         + (1.0 if k % 2 == 0 else -1.0) * share * turns[k])
                     for k in self.touching_arcs)

    @property
    def contact_nodes(self) -> np.ndarray:
        """Indices into :attr:`x` of the nodes on the rounded corners' contact points."""
        x = self.x_head
        return np.array([int(np.argmin(np.abs(x - c))) for c in self.corner_contacts],
                        dtype=int)

    def tape_slopes(self, u: np.ndarray, nodes: np.ndarray) -> np.ndarray:
        """The tape's slope dw/dx (rad) at the interior ``nodes`` (indices into :attr:`x`),
        from w = z0 + u by the three-point difference on the non-uniform grid (second
        order where w is C2, as at a point contact, where only w''' jumps), averaged
        across the width (shape (len(nodes),))."""
        w = self.head.dry_tape(self.x_head, self.head_radius)[:, None] + np.vstack(
            [np.zeros((1, self.nc)), u.reshape(self.nx - 1, self.nc),
             np.zeros((1, self.nc))])
        i = np.asarray(nodes, dtype=int)
        hm, hp = (self.x[i] - self.x[i - 1])[:, None], (self.x[i + 1] - self.x[i])[:, None]
        slope = (hm**2 * w[i + 1] - hp**2 * w[i - 1] + (hp**2 - hm**2) * w[i]) / (
            hm * hp * (hm + hp))
        return slope.mean(axis=1)

    @cached_property
    def contact_floor(self) -> np.ndarray:
        """The spacing below which each tape unknown's node touches the head, m: the
        roughness σ, except on the rounded corners' arcs, where only the contact node
        touches (a tangent point contact: the arc's other nodes lie within Δ²/(2 r_c) of σ
        next to it, a degenerate contact set Newton cannot settle; they are left free and
        checked after the solve, :meth:`arc_clearance`) and the floor is
        :data:`NO_CONTACT_FLOOR`."""
        if self.smooth_contact:      # no wall: the contact law acts at every spacing
            return np.full(self.n_u, -np.inf)
        floor = np.full((self.nx - 1, self.nc), self.air.roughness)
        x = self.x_head[1:-1]
        for k, i in zip(self.rounded_corners, self.contact_nodes, strict=True):
            lo, hi = self.head.arc_tangent_points(k)
            on_arc = (x >= lo) & (x <= hi)
            on_arc[i - 1] = False
            floor[on_arc, :] = NO_CONTACT_FLOOR
        return floor.ravel()

    def arc_clearance(self, u: np.ndarray) -> float:
        """The least h − σ (m) over the rounded corners' arc nodes left free of contact
        (:attr:`contact_floor`; +inf if none): negative if the tape cuts into an arc, i.e.
        does not touch it at one point."""
        free = self.contact_floor < 0.0
        if not free.any():
            return math.inf
        h = u + self.dry_field[1:-1, :].ravel()
        return float(np.min(h[free]) - self.air.roughness)

    def updated_contacts(self, u: np.ndarray) -> tuple[float, ...]:
        """The contact points the state u moves the rounded corners' contacts to, m: on
        each arc, the point whose slope is the tape's at the present contact node (the
        tangency of a point contact; the nearest approach if the tape flies)."""
        slopes = self.tape_slopes(u, self.contact_nodes)
        return tuple(self.head.arc_point(k, float(s))
                     for k, s in zip(self.rounded_corners, slopes, strict=True))

    def _zone_spacing(self, resolution: float) -> float:
        """The default x-spacing at the corners without the corner term, m: the
        resolution length over 12 (1-D uniform), 6 (2-D uniform) or 15 (graded)."""
        if self.grading.x_ratio != 1.0:
            return X_RESOLUTION_GRADED * resolution
        return (X_RESOLUTION if self.infinitely_wide else X_RESOLUTION_2D) * resolution

    def _corner_grading(self, resolution: float) -> dict:
        """The default corner refinement (``corner_ratio``, ``corner_width``): none on a
        cylinder or dry; else :func:`corner_grading` from the spacing far from the
        corners (the zone spacing times the x-grading's ratio), so that the spacing grows
        at CORNER_GROWTH times the distance from a corner whatever the sech zones do."""
        if (self.cylindrical or self.dry
                or (self._all_corners_wrapped() and not self.touching_arcs)):
            return {"corner_ratio": 1.0, "corner_width": None}
        return corner_grading(self.air.roughness * (SMOOTH_CORNER_SCALE if self.smooth_contact
                                                    else 1.0),
                              self._zone_spacing(resolution) * self.grading.x_ratio)

    def with_flown_corners(self) -> BearingModel | None:
        """This model with its corners refined for a tape flying over them, on as many
        intervals, or None unless one film covers the whole head (:attr:`film_over_head`)
        under the default corner refinement. The default refines every corner to the
        roughness, where a touching corner holds the tape (:func:`corner_grading`); a tape
        flying microns above them needs the refinement only down to its spacing, here
        the flying start's (:attr:`flying_start_spacing`). Refined to σ, the plate's
        rows on the corners' 30 nm cells put the residual's round-off above what sets
        the flying height, and Newton's states 'converged' at its floor scattered by up
        to 40 % between starts and grids (a 1 mm land at 0.01 deg, 4 m/s, 1-D: 6.3-9.5
        µm); refined to the flying spacing they agree within 0.02 % (6.98 µm) from
        every start and on twice the intervals."""
        g = self.grading
        if (not self.film_over_head or self.dry or self.corners_flown
                or g.corner_ratio in (None, 1.0)):
            return None
        far = (g.corner_ratio - 1.0) * CORNER_GROWTH * g.corner_width
        return self.rebuilt(grading=replace(
            g, **corner_grading(self.flying_start_spacing, far)))

    @property
    def corners_flown(self) -> bool:
        """Whether the corners are refined for a tape flying over them
        (:meth:`with_flown_corners`): down to the flying start's spacing, not the
        roughness; Newton then starts with the tape flying over the whole head
        (:meth:`_corner_start`)."""
        width = self.grading.corner_width
        return (self.film_over_head and not self.dry and width is not None
                and self.grading.corner_ratio not in (None, 1.0)
                and width >= 0.5 * CORNER_WIDTH * self.flying_start_spacing)

    @property
    def x_head(self) -> np.ndarray:
        """The node abscissae in head coordinates, m (from the head's middle)."""
        return self.x - 0.5 * self.length

    def _internal(self, xs) -> tuple[float, ...]:
        """Head abscissae (m) as positions along the domain [0, length], m."""
        return tuple(0.5 * self.length + float(c) for c in xs)

    def _x_nodes(self, x_line) -> np.ndarray:
        """The x-nodes, m on [0, length]: a flat or profile head's with a node on every
        sharp corner (:func:`~.mesh.piecewise_line_nodes`)."""
        breaks = () if self.cylindrical else self._internal(
            self.head.sharp_corners(self.head_radius) + self.corner_contacts)
        try:
            x = piecewise_line_nodes(self.length, self.nx, x_line, breaks,
                                     fewest=FEWEST_BETWEEN_CORNERS)
        except ValueError as exc:
            raise ParameterError(f"nx = {self.nx} is too small for the head: {exc}; use a "
                                 "larger nx (or the default)") from None
        if not np.all(np.diff(x) > 0.0):
            # the graded pieces between the head's corners overlap: too few intervals
            # for the grading (measured: 0.01 deg wraps over a 1 mm land, nx = 1532 of
            # the default 3064, the coarse start's grid)
            raise ParameterError(f"nx = {self.nx} is too small for the head's graded grid "
                                 "(its nodes would not increase along x); use a larger nx "
                                 "(or the default)")
        return x

    def _checked_span(self, span: float | None, l_film: float, l_bend: float) -> float:
        """The span, m: given (checked) or the default, within [MIN_SPAN_LENGTHS times
        the longer of the film and bending lengths, MAX_SPAN_RADII R]."""
        longest = max(l_film, l_bend)
        low = MIN_SPAN_LENGTHS * longest
        high = MAX_SPAN_RADII * self.head_radius if self.cylindrical else MAX_SPAN_FLAT
        if low > high:
            raise ParameterError(self._too_long_for_the_head(l_film, l_bend))
        if span is None:
            spans = SPAN_LENGTHS if self.infinitely_wide else SPAN_LENGTHS_2D
            return min(spans * longest, high)
        span = validation.positive("span", span, "m")
        if not low <= span <= high:
            which = "film" if l_film >= l_bend else "bending"
            raise ParameterError(
                f"span must be in [{low:.3g}, {high:.3g}] m, got {span:g}: at least "
                f"{MIN_SPAN_LENGTHS:g} {which} lengths ({MIN_SPAN_LENGTHS:g} x {longest:.3g} m) "
                "for the film "
                "pressure to return to ambient before the tape's pinned end, at most "
                + ("the head radius R for the shallow-shell gap" if self.cylindrical
                   else f"{MAX_SPAN_FLAT:g} m"))
        return span

    def _too_long_for_the_head(self, l_film: float, l_bend: float) -> str:
        """The message for a film or bending length too long for spans within R."""
        p, air, v = self.params, self.air, self.velocity
        t_eff = self.effective_tension()
        shortest = MIN_SPAN_LENGTHS * max(l_film, l_bend)
        head = (f"spans of {MIN_SPAN_LENGTHS:g} times it ({shortest:.3g} m) "
                + (f"exceed the head radius R = {self.head_radius:g} m (the shallow-shell "
                   "gap)" if self.cylindrical else f"exceed {MAX_SPAN_FLAT:g} m"))
        if l_bend > l_film:
            return (f"the tape is too stiff to wrap the head: its bending length "
                    f"sqrt(D/(T - rho V^2)) = {l_bend:.3g} m is so long that {head}; use a "
                    "smaller bending_rigidity (a thinner tape), a higher tension or a larger "
                    "radius")
        eps = 6.0 * air.viscosity * v / t_eff
        text = (f"the film is too thick for the head: eps = 6 mu V/(T - rho V^2) = {eps:.3g} "
                f"(viscosity {air.viscosity:g} Pa*s, velocity {v:g} m/s, T - rho V^2 = "
                f"{t_eff:.3g} N/m) gives a film length R eps^(1/3) = {l_film:.3g} m and a "
                f"spacing scale R eps^(2/3) = {self.scale_radius * eps ** (2 / 3):.3g} m, and "
                f"{head}; ")
        if air.viscosity > 10.0 * AIR_VISCOSITY:
            return text + (f"the viscosity {air.viscosity:g} Pa*s makes the film thick: use "
                           f"one nearer air's {AIR_VISCOSITY:g} Pa*s")
        if t_eff < 0.5 * p.tension:
            return text + (f"velocity {v:g} m/s is near the string speed "
                           f"{p.string_speed:.4g} m/s: use a lower velocity")
        return text + "use a lower velocity or viscosity, or a higher tension"

    def _x_count(self, nx: int | None, l_film: float, resolution: float,
                 span_given: bool):
        """The number of x-intervals :attr:`nx` (default from the ``resolution`` length, m;
        see :meth:`_default_nx`), checked; returns the x-line's grading (None: uniform)."""
        x_line = self.grading.x_line(self.length, self._internal(self._centres()))
        if nx is None:
            nx = self._default_nx(x_line, l_film, resolution, span_given)
        self.nx = validation.integer("nx", nx, low=MIN_INTERVALS_ALONG,
                                     high=MAX_INTERVALS_ALONG)
        return x_line

    def _check_film_resolved(self, l_film: float, x_line) -> None:
        """Refuse an x-grid coarser than MAX_FILM_SPACING film lengths within a film length
        of the wrap's corners, the film's entrance and exit (see :data:`MAX_FILM_SPACING`;
        the plateau between them may be coarser). A tape whose flexible-foil spacing is
        below the roughness lies on the head: it has no film to resolve; a continuation
        stage's grid is the final speed's (:meth:`at_velocity`)."""
        if (self.dry or self.h_guess / _FOIL_GUESS < self.air.roughness
                or _CONTINUATION_STAGE.get()):
            return
        mid = 0.5 * (self.x[1:] + self.x[:-1])
        corners = np.array(self._internal(self.head.corners(self.head_radius)))
        zone = np.min(np.abs(mid[:, None] - corners[None, :]), axis=1) <= l_film
        coarsest = float(np.diff(self.x)[zone].max()) if zone.any() else self.hx
        if coarsest <= MAX_FILM_SPACING * l_film:
            return
        step = 2 if x_line is None else 4
        needed = step * math.ceil(self.nx * coarsest / (MAX_FILM_SPACING * l_film) / step)
        raise ParameterError(
            f"nx = {self.nx} is too coarse for the film: it leaves {coarsest:.3g} m between "
            f"nodes at the head's corners, more than the film length R eps^(1/3) = "
            f"{l_film:.3g} m, and "
            f"the spacings are then wrong by up to 50 % (measured: h_c 48 % low at 1.9 film "
            f"lengths, 2 % at 0.9); use nx >= {needed} (or the default)")

    def smallest_valid_wrap(self) -> float:
        """The cylinder's smallest wrap angle the model holds for, rad (0 for other heads
        or dry): below it the hoop stiffness k it keeps on the straight spans carries more
        than :data:`HOOP_SPAN_SHARE` of the wrap load (:data:`HOOP_SPAN_SUPPORT`)."""
        if not self.cylindrical or self.dry:
            return 0.0
        t_eff = self.effective_tension()
        eps = 6.0 * self.air.viscosity * abs(self.velocity) / t_eff
        return (HOOP_SPAN_SUPPORT / HOOP_SPAN_SHARE * self.params.k
                * self.scale_radius**2 * eps / t_eff)

    def _warn_small_wrap(self) -> None:
        """One :class:`BearingModelWarning` line if the cylinder's wrap is below
        :meth:`smallest_valid_wrap`."""
        limit = self.smallest_valid_wrap()
        if self.wrap_angle >= limit:
            return
        share = HOOP_SPAN_SHARE * limit / self.wrap_angle
        below = (f"below {math.degrees(limit):.3g} deg" if limit <= 0.5 * math.pi
                 else "below every wrap a cylinder allows (90 deg at most)")
        warnings.warn(
            f"a wrap of {math.degrees(self.wrap_angle):.3g} deg is {below}, where this "
            f"model stops holding: it keeps the "
            f"wrapped shell's hoop stiffness k = {self.params.k:.3g} N/m^3 on the straight "
            f"spans, which then hold the tape up with up to {share:.2g} times the wrap load "
            "(T - rho V^2) theta, so the spacing comes out too low; "
            + ("use a larger wrap (or a flat or profile head, whose spans have no hoop "
               "stiffness)" if limit <= 0.5 * math.pi else
               "use a flat or profile head, whose spans have no hoop stiffness"),
            BearingModelWarning, stacklevel=3)

    def _warn_unresolved_profile(self) -> None:
        """One :class:`BearingGridWarning` line if a measured profile has a feature the
        x-grid does not see (:meth:`ProfileHead.unresolved_features`: standing more than
        the roughness σ above the contour through the nodes), with its size and place."""
        if not isinstance(self.head, ProfileHead):
            return
        found = self.head.unresolved_features(self.x_head, self.air.roughness)
        if not found:
            return
        missed, width, x = found[0]
        i = int(np.clip(np.searchsorted(self.x_head, x), 1, self.nx))
        spacing = float(self.x_head[i] - self.x_head[i - 1])
        needed = 4 * math.ceil(self.nx * spacing * FEATURE_NODES / width / 4)
        remedy = (f"use nx >= {needed} (a quarter of its width between nodes) or smooth "
                  "the profile" if needed <= MAX_INTERVALS_ALONG else "smooth the profile")
        shift = self.head.shift
        where = f"x = {x * 1e3:.6g} mm" + (f" ({(x - shift) * 1e3:.6g} mm in the profile)"
                                           if shift else "")
        warnings.warn(
            f"the profile's feature at {where}, {width * 1e6:.3g} um wide, stands "
            f"{missed * 1e9:.3g} nm above the contour the grid sees, more than the roughness "
            f"{self.air.roughness * 1e9:.3g} nm: nodes {spacing * 1e6:.3g} um apart there "
            "step over it and the tape flies through it"
            + (f" ({len(found) - 1} more such features)" if len(found) > 1 else "")
            + f"; {remedy}", BearingGridWarning, stacklevel=3)

    def _default_nx(self, x_line, l_film: float, resolution: float,
                    span_given: bool) -> int:
        """The default number of x-intervals (see the class docstring)."""
        if x_line is None:
            spacing = (X_RESOLUTION if self.infinitely_wide else X_RESOLUTION_2D) * resolution
            nx = 2 * math.ceil(0.5 * self.length / spacing)
        else:
            nx = intervals_for(self.length, self._zone_spacing(resolution), x_line)
        if nx > MAX_INTERVALS_ALONG:
            raise ParameterError(self._too_many_intervals(nx, l_film, resolution,
                                                          span_given))
        return nx

    def _too_many_intervals(self, nx: int, l_film: float, resolution: float,
                            span_given: bool) -> str:
        """The message for a default grid of more than MAX_INTERVALS_ALONG intervals,
        naming what makes it so fine: a long given span or a film short against the wrap."""
        wrap = self.length - 2.0 * self.span
        need = (f"resolving the {resolution:.3g} m {'film' if resolution == l_film else 'bending'}"
                f" length over the {self.length:.3g} m domain needs {nx} intervals, more "
                f"than the limit {MAX_INTERVALS_ALONG}")
        if span_given and 2.0 * self.span > wrap:
            fit = 0.5 * (self.length * MAX_INTERVALS_ALONG / nx - wrap)
            return (f"span {self.span:g} m is too long for the grid: {need}; use a span <= "
                    f"{fit:.3g} m or set nx")
        if resolution < l_film:
            return (f"the bending length sqrt(D/(T - rho V^2)) = {resolution:.3g} m is short "
                    f"against the {wrap:.3g} m wrap: {need}; set nx (and a grading)")
        return (f"velocity {self.velocity:g} m/s gives a film only {l_film:.3g} m long: "
                f"{need}; use a higher speed |V| (the tape is then in contact with the head "
                "anyway) or set nx")

    def _y_count(self, ny: int | None, y_line) -> int:
        """The number of y-intervals (default: see the class docstring), checked."""
        width = self.params.width
        if ny is None:
            ny = max(MIN_INTERVALS_ACROSS,
                     2 * round(0.5 * width / Y_SPACING) if y_line is None
                     else intervals_for(width, Y_EDGE_SPACING, y_line))
        ny = validation.integer("ny", ny, low=MIN_INTERVALS_ACROSS)
        if ny % 2:
            raise ParameterError(f"ny must be an even integer >= {MIN_INTERVALS_ACROSS} "
                                 f"(a node on the centre line), got {ny!r}")
        return ny

    def _build_y_line(self, ny: int, y_line) -> None:
        """The y-nodes (:attr:`y`, m), their count :attr:`ny` and :attr:`nc` = ny + 1;
        warns if the free edges are under-resolved (:data:`MAX_EDGE_SPACING`)."""
        self.ny = ny
        self.y = symmetric_line_nodes(self.params.width, self.ny, y_line)
        self.nc = self.ny + 1
        edge = float(self.y[1] - self.y[0])
        if edge > MAX_EDGE_SPACING:
            warnings.warn(
                f"ny = {ny} leaves {edge * 1e6:.0f} um at the free edges, more than "
                f"{MAX_EDGE_SPACING * 1e6:.0f} um: the edge rows may falsely touch down and "
                "the minimum spacing be off by 20-90 % (measured at 112 um); use a larger ny "
                "or the default", BearingGridWarning, stacklevel=3)

    def _couple_film_and_loads(self) -> None:
        """The film on the tape's grid, and the loads of the dry wrapped configuration."""
        film = DryFilm if self.dry else Film
        self.film = film(self.nx, self.nc, np.diff(self.x),
                         None if self.infinitely_wide else np.diff(self.y), self.air,
                         self.velocity, roughness=self.air.roughness)
        self.n_u = self.tape.n
        self.n_p = self.film.size
        x, r = self.x_head, self.head_radius
        if self.infinitely_wide:
            self.dry_field = self.head.dry_gap(x, radius=r)[:, None]
        else:
            self.dry_field = np.broadcast_to(self.head.dry_gap(x, self.y, radius=r),
                                             (self.nx + 1, self.nc)).copy()
        self.kappa = self.head.dry_curvature(x, radius=r)
        self.f_kappa = self.tape.curvature_load(self.kappa)
        self.W = self.tape.W
        self.kappa_nodes = np.repeat(self.kappa, self.nc)
        self.pressure_load = self._pressure_load_matrix()

    def _hold_wrapped_arcs(self, U: np.ndarray, held: np.ndarray) -> None:
        """The dry start on the wrapped arcs (in place): the tape held at σ where it lies on
        each (:meth:`wrapped_contact`, at least the node nearest its middle)."""
        inner = self.x_head[1:-1]
        for k in self.wrapped_corners:
            lo, hi = self.wrapped_contact(k)
            on = (inner >= lo) & (inner <= hi)
            on[int(np.argmin(np.abs(inner - 0.5 * (lo + hi))))] = True
            U[on, :] = self.air.roughness - self.dry_field[1:-1][on, :]
            held[on, :] = True

    def _corner_start(self, dry: bool | None = None) -> np.ndarray:
        """u of Newton's start on a flat or profile head (or dry): h = :data:`FLAT_START`
        foil spacings above the dry gap, tapering to the roughness σ at the sharp corners
        turning by at least 5 % of the wrap (in contact: their point loads are carried at
        once), or the foil spacing :attr:`h_guess` everywhere if the corners are
        refined for a tape flying over them (:attr:`corners_flown`); ``dry`` (default:
        the model's): the dry tape, :data:`DRY_START` θ ℓ_bend above the dry gap but with
        the sharp corners held at σ, solved."""
        dry = self.dry if dry is None else dry
        if not dry and self.corners_flown:
            # the tape flying over the whole head at the foil spacing, its corners flown
            # over (from the corners at σ and the land at FLAT_START foil scales Newton
            # stagnated at 0.01 deg; from 6-20 µm it took 6-8 iterations, measured)
            return np.full(self.n_u, max(self.h_guess, self.air.roughness))
        h0 = (DRY_START * self.wrap_angle * self.bending_length if dry
              else self.flying_start_spacing)
        sigma = self.air.roughness
        h0 = max(h0, sigma)
        U = np.full((self.nx - 1, self.nc), h0)
        inner = self.x_head[1:-1]
        held = np.zeros(U.shape, dtype=bool)
        turns = dict(zip(self.head.corners(self.head_radius),
                         self.head.corner_turns(self.head_radius), strict=True))
        all_turns = self.head.corner_turns(self.head_radius)
        all_radii = self.head.corner_radii(self.head_radius)
        radii = dict(zip(self.head.corners(self.head_radius), all_radii, strict=True))
        # the points the tape touches the rounded corners at: the point contacts' and,
        # under a smooth law, the touching wrapped arcs' (:meth:`wrapped_centres`)
        touches = (tuple(zip(self.rounded_corners, self.corner_contacts, strict=True))
                   + (tuple(zip(self.touching_arcs, self.wrapped_centres(), strict=True))
                      if self.smooth_contact else ()))
        for k, c in touches:
            turns[c], radii[c] = all_turns[k], all_radii[k]
        for c in self.head.sharp_corners(self.head_radius) + tuple(c for _, c in touches):
            turn = turns.get(c, self.wrap_angle)
            if not dry and turn < CORNER_FRACTION * self.wrap_angle:
                continue     # its point load is small: the film carries it (measured)
            i = int(np.argmin(np.abs(inner - c)))
            if not dry:   # the film's constriction: h rising from σ at the tape's slope
                reach = max(h0 - sigma, sigma) / (START_SLOPE * turn)
                s = np.abs(inner - c)
                # on a rounded corner h rises as a parabola of curvature 1/(2 r_c) over
                # the first s₀ (the tape less curved than the arc: it presses on its
                # contact node at once), then at the same slope as at a sharp one
                s0 = 2.0 * radii.get(c, 0.0) * (h0 - sigma) / reach
                if s0 > 0.0:
                    s = np.where(s < s0, 0.5 * s * s / s0, s - 0.5 * s0)
                taper = sigma + (h0 - sigma) * -np.expm1(-s / reach)
                U = np.minimum(U, taper[:, None])
            U[i, :] = sigma - self.dry_field[i + 1, :]
            held[i, :] = True
        if dry:
            self._hold_wrapped_arcs(U, held)
        if not dry or not held.any():
            return U.ravel()
        return self._held_dry_tape(U, held)

    def _held_dry_tape(self, U: np.ndarray, held: np.ndarray) -> np.ndarray:
        """u of the dry tape with the nodes ``held`` at their values in ``U`` (m): the
        exact state when only they touch (the active set of a 4th-order operator
        otherwise moves a node per step)."""
        held = held.ravel()
        scale = np.where(held, self.stiffness_diagonal, 0.0)   # rows scaled like K's
        rhs = np.where(held, scale * U.ravel(), self.f_kappa
                       - self.effective_tension() * self.W * self.kappa_nodes)
        keep = sp.diags((~held).astype(float))
        system = (keep @ self.K() + sp.diags(scale)).tocsc()
        from scipy.sparse.linalg import spsolve

        u = spsolve(system, rhs)
        # held exactly: h = σ to the last bit, so that the contact rule λ > c (h − σ)
        # (c ~ D/h⁴ on the corner's fine cells) is not decided by the solve's round-off
        u[held] = U.ravel()[held]
        return u

    @property
    def flying_start_spacing(self) -> float:
        """The land spacing of Newton's flying start over a flat or profile head, m:
        :data:`FLAT_START` foil spacing scales (before it is raised to the roughness)."""
        return FLAT_START * self.h_guess / _FOIL_GUESS

    def __repr__(self) -> str:
        kind = "infinitely wide" if self.infinitely_wide else f"width {self.params.width:g} m"
        grid = "graded" if self.graded else "uniform"
        dry = ", dry" if self.dry else ""
        return (f"BearingModel(V={self.velocity:g} m/s, {self.head.kind} head, wrap="
                f"{math.degrees(self.wrap_angle):g} deg, {kind}, L_x={self.length:.4g} m, "
                f"nx={self.nx}, ny={self.ny}, {grid}{dry})")

    def _pressure_load_matrix(self) -> sp.csr_matrix:
        """L with L (p − p_a) the nodal air forces, N: the exact integral of the bilinear
        interpolant of p − p_a over each tape node's control area.

        At a free edge the control strip [0, h_y/2] then feels the pressure rising from
        p_a at the edge, which plain nodal sampling (zero there) would miss.
        """
        def weights(t: np.ndarray, rows: slice) -> sp.csr_matrix:
            # ∫ of the hat functions over [t_i − h_{i−1}/2, t_i + h_i/2]: h/8, 3h/8 per side
            h = np.diff(t)
            n = len(t)
            main = np.zeros(n)
            main[:-1] += 3 * h / 8
            main[1:] += 3 * h / 8
            m = sp.diags([h / 8, main, h / 8], [-1, 0, 1], format="csr")
            return m[rows]

        ex = weights(self.x, slice(1, self.nx))
        ey = (sp.identity(1, format="csr") if self.infinitely_wide
              else weights(self.y, slice(None)))
        full = sp.kron(ex, ey, format="csc")
        return full[:, self.film._pattern["node_of_p"]].tocsr()

    @cached_property
    def unknown_nodes(self) -> np.ndarray:
        """The grid node (i nc + j) of each unknown: the tape's u (every node but the
        pinned end lines x = 0 and x = L), then the film's p (its interior nodes)."""
        return np.concatenate([np.arange(self.n_u) + self.nc,
                               self.film._pattern["node_of_p"]])

    @cached_property
    def mirror(self) -> tuple[sp.csr_matrix, np.ndarray] | None:
        """(P, rows) for states symmetric about the tape's centre line y = L_y/2: P maps
        the unknowns of the half 0 <= y <= L_y/2 to the whole, ``rows`` picks that half's
        equations. None for the infinitely wide tape (or an odd ny)."""
        if self.infinitely_wide or self.ny % 2:
            return None
        half = self.ny // 2
        nodes = np.arange((self.nx + 1) * self.nc).reshape(self.nx + 1, self.nc)
        jj = np.broadcast_to(np.arange(self.nc), nodes.shape)
        folded = nodes - jj + np.minimum(jj, self.ny - jj)       # node of the mirror image
        blocks, rows, offset = [], [], 0
        for node_of, n in ((np.arange(self.n_u) + self.nc, self.n_u),
                           (self.film._pattern["node_of_p"], self.n_p)):
            keep = jj.ravel()[node_of] <= half
            index = np.full(nodes.size, -1)
            index[node_of[keep]] = np.arange(int(keep.sum()))
            cols = index[folded.ravel()[node_of]]
            blocks.append(sp.csr_matrix((np.ones(n), (np.arange(n), cols)),
                                        shape=(n, int(keep.sum()))))
            rows.append(offset + np.flatnonzero(keep))
            offset += n
        return sp.block_diag(blocks, format="csr"), np.concatenate(rows)

    def at_velocity(self, velocity: float) -> BearingModel:
        """The same tape, head and grid at another speed V, m/s (for continuation): a
        stage on the way to this model's speed, so its grid is not refused for a film
        too short for it at that speed (the check is the final speed's)."""
        token = _CONTINUATION_STAGE.set(True)
        try:
            return self.rebuilt(velocity=velocity)
        finally:
            _CONTINUATION_STAGE.reset(token)

    def rebuilt(self, **changes) -> BearingModel:
        """The same model with some constructor arguments changed (velocity, nx, ny,
        infinitely_wide, head, span, grading, dry, factorization, corner_contacts,
        adapt_contacts, arc_contact, contact); its :class:`BearingGridWarning` lines are
        given again only for a new head or grid (head, nx, ny, span or grading changed)."""
        kw = dict(velocity=self.velocity, head=self.head,
                  infinitely_wide=self.infinitely_wide, span=self.span, nx=self.nx,
                  ny=self.ny, grading=self.grading, dry=self.dry,
                  factorization=self.factorization,
                  corner_contacts=self.corner_contacts or None,
                  adapt_contacts=self.adapt_contacts, arc_contact=self.arc_contact,
                  contact=self.contact)
        if {"head", "dry", "arc_contact"} & set(changes) or self._regime_changes(changes):
            kw["corner_contacts"] = None        # the new head's (or regime's) own estimate
        new_grid = (any(k in changes and changes[k] is not kw[k] and changes[k] != kw[k]
                        for k in ("head", "nx", "span", "grading"))
                    or changes.get("ny") not in (None, kw["ny"]))
        kw.update(changes)
        with warnings.catch_warnings():
            if not new_grid:     # the same head on the same grid (or its strip): said
                warnings.simplefilter("ignore", BearingGridWarning)
            return BearingModel(self.params, self.air, **kw)

    def _regime_changes(self, changes: dict) -> bool:
        """Whether a new speed in ``changes`` moves a rounded corner across the handover
        (:func:`wrapped_corners`: the bending length changes with V), so that the point
        contacts carried over would belong to another set of corners."""
        v = changes.get("velocity")
        if v is None or not self.corner_contacts or self.arc_contact != "auto":
            return False
        t_eff = self.params.tension - self.params.density * float(v) ** 2
        if not t_eff > 0.0:
            return False                        # the constructor refuses the speed
        l_bend = math.sqrt(self.params.D / t_eff)
        return wrapped_corners(self.head, l_bend, "auto") != self.wrapped_corners

    # ----- state <-> fields ----------------------------------------------------------------
    @property
    def unknowns(self) -> int:
        """Number of unknowns of the coupled state [u, p]."""
        return self.n_u + self.n_p

    @property
    def size(self) -> int:
        """Deprecated: use :attr:`unknowns`."""
        warnings.warn("BearingModel.size is deprecated: use BearingModel.unknowns",
                      DeprecationWarning, stacklevel=2)
        return self.unknowns

    @property
    def hx(self) -> float:
        """Mean x-spacing L_x/nx, m (the spacing of a uniform grid; see :attr:`x`)."""
        return self.length / self.nx

    @property
    def graded(self) -> bool:
        """Whether the grid is graded (non-uniform) in x or y."""
        return not (self.grading.x_ratio == 1.0 and self.grading.corner_ratio == 1.0
                    and (self.infinitely_wide or self.grading.y_ratio == 1.0))

    def effective_tension(self, tension: float | None = None) -> float:
        """T − ρV², N/m."""
        t = self.params.tension if tension is None else tension
        return t - self.params.density * self.velocity**2

    def spacing_field(self, u: np.ndarray) -> np.ndarray:
        """h = w₀ + u on every node, shape (nx + 1, nc), m."""
        H = self.dry_field.copy()
        H[1:-1, :] += u.reshape(self.nx - 1, self.nc)
        return H

    def pressure_field(self, p: np.ndarray) -> np.ndarray:
        """p on every node (p_a on the film boundaries), shape (nx + 1, nc), Pa."""
        P = np.full((self.nx + 1, self.nc), self.air.ambient_pressure)
        P[self.film.interior] = p
        return P

    @cached_property
    def stiffness_diagonal(self) -> np.ndarray:
        """diag K at the nominal tension, N/m: scales the contact rows."""
        return (self.tape.A + self.effective_tension() * self.tape.B).diagonal()

    def K(self, tension: float | None = None) -> sp.csr_matrix:
        """K = A + (T − ρV²) B, N/m."""
        return (self.tape.A + self.effective_tension(tension) * self.tape.B).tocsr()

    # ----- residual and Jacobian -------------------------------------------------------------
    def tape_residual(self, u: np.ndarray, p: np.ndarray, K: sp.spmatrix,
                      tension: float | None = None) -> np.ndarray:
        """K u − W (p − p_a) + (T − ρV²) W κ − f_κ (no contact force), N. The
        infinitely wide tape's elastic terms are summed as nested differences
        (:meth:`.tape.StripOperators.elastic_force`: the same rows without the round-off
        of K u on the corners' fine cells; K, the same matrix, is then not used)."""
        pa = self.air.ambient_pressure
        t_eff = self.effective_tension(tension)
        if isinstance(self.tape, StripOperators):
            elastic = self.tape.elastic_force(u, self.kappa, t_eff)
        else:
            elastic = K @ u + t_eff * self.W * self.kappa_nodes - self.f_kappa
        return elastic - self.pressure_load @ (p - pa)

    def film_residual(self, u: np.ndarray, p: np.ndarray, *, phi_old=None, dt=None,
                      jacobian: bool = True):
        """Film balances and their Jacobian blocks (∂/∂p, ∂/∂u); see :class:`Film`.

        Spacings below half the roughness (reachable only during Newton iterations, before
        the contact set catches them) are floored there so that the film stays defined.
        """
        r, J_p, J_h, free = self.film_linearization(u, p, phi_old=phi_old, dt=dt,
                                                    jacobian=jacobian)
        if not jacobian:
            return r, None, None
        return r, J_p, self.film_tape_block(J_h, free)

    def film_tape_block(self, J_h: sp.csr_matrix, free: np.ndarray) -> sp.csr_matrix:
        """∂r_p/∂u (r_p's units per m) from the film's ∂r_p/∂h over every node and
        ``free`` of :meth:`film_linearization`: its columns at the tape's
        unknowns (u_k is node nc + k: the first node line is pinned), zero where the
        spacing was floored. The one formula of the film rows' u-block, for
        :meth:`film_residual` and Newton's stacked Jacobian
        (``_Residual.jacobian`` in :mod:`.steady`)."""
        J_u = J_h[:, self.nc:self.nc + self.n_u]
        if free.dtype != bool or not free.all():
            J_u = J_u @ sp.diags(free.astype(float))
        return J_u.tocsr()

    def film_linearization(self, u: np.ndarray, p: np.ndarray, *, phi_old=None, dt=None,
                           jacobian: bool = True):
        """(r_p, ∂r_p/∂p, ∂r_p/∂h over every node, free): :meth:`film_residual` with the
        film's blocks in their fixed patterns (:class:`.film.Film`), for an assembly into
        a fixed pattern (:mod:`.jacobian`); ``free`` is False at the unknowns whose
        spacing was floored (r_p does not depend on them there). Without ``jacobian``
        the blocks are None."""
        Hf, free = self.film_spacing(self.spacing_field(u))
        r, J_p, J_h = self.film_residual_fields(self.pressure_field(p), Hf, phi_old=phi_old,
                                                dt=dt, jacobian=jacobian)
        return r, J_p, J_h, free

    def film_spacing(self, H: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(h_f, free): the spacing the film sees on every node (m), floored at
        :attr:`film_floor`, and for the tape's unknowns ∂h_f/∂h (a smooth law's smooth
        floor) or whether h was above the floor (the hard wall's clip)."""
        floor = self.film_floor
        if self.smooth_contact and self.contact.law == "asperity":
            return mean_gap(H, self.air.roughness), mean_gap_slope(
                H[1:-1, :], self.air.roughness).ravel()
        if self.smooth_contact:
            # a smooth floor (C∞): under a smooth law the tape presses through it at the
            # corners, and a kink there makes Newton cycle; h_f − h < 3e-4 h above 10 f
            Hf, slope = smooth_floor(H, floor)
            free = slope[1:-1, :].ravel()
        else:
            clipped = H < floor
            Hf = np.where(clipped, floor, H)
            free = ~clipped[1:-1, :].ravel()
        return Hf, free

    def transported(self, u: np.ndarray, p: np.ndarray) -> np.ndarray:
        """The film's transported φ (p h_f, Pa·m, or h_f, m) of the state (u, p) on every
        node, with the spacing the film sees (:meth:`film_spacing`)."""
        return self.film.transported(self.pressure_field(p),
                                     self.film_spacing(self.spacing_field(u))[0])

    @property
    def film_floor(self) -> float:
        """The least spacing the film sees, m: half the wall's gap σ (hard wall: reached
        only during Newton's iterations), or :data:`SMOOTH_FILM_FLOOR` σ_s under a smooth
        contact law (the asperities carry the tape there; the film's flow through such a
        gap is negligible, and the rarefaction fits stay within their range)."""
        return (SMOOTH_FILM_FLOOR if self.smooth_contact else 0.5) * self.air.roughness

    def asperity_force(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(f, ∂f/∂u): the smooth contact law's nodal force on the tape, N (N/m per unit
        width if infinitely wide), at the tape unknowns, f = A p_c(h) with A the nodes'
        control areas (widths) and p_c the law's nominal pressure at the spacing h
        (:mod:`.contact`); and its derivative by u, N/m (N/m² per unit width), <= 0.
        Zero for the hard wall."""
        if not self.smooth_contact:
            return np.zeros(self.n_u), np.zeros(self.n_u)
        # Newton asks for the force at the same state for its residual, its Jacobian and
        # its round-off floor: the law's quadrature is kept for the last state and law
        last = self.__dict__.get("_asperity_last")
        key = (self.contact_law, self.W, self.dry_field)
        if (last is not None and all(a is b for a, b in zip(last[0], key, strict=True))
                and last[1].shape == u.shape and np.array_equal(last[1], u)):
            return last[2].copy(), last[3].copy()
        h = u + self.dry_field[1:-1, :].ravel()
        near = h < CONTACT_REACH * self.air.roughness
        f, df = np.zeros(self.n_u), np.zeros(self.n_u)
        if near.any():
            p, dp = self.contact_law.pressure(h[near])
            f[near], df[near] = self.W[near] * p, self.W[near] * dp
        self.__dict__["_asperity_last"] = (key, np.array(u, dtype=float), f, df)
        return f.copy(), df.copy()

    def film_residual_fields(self, P, H, **kw):
        return self.film.residual(P, H, **kw)

    def air_force(self, p: np.ndarray) -> float:
        """∫ (p − p_a) dA over the film, N (per unit width, N/m, for the infinitely wide)."""
        area = self.film.cell_area[self.film.interior]
        return float(np.sum(area * (p - self.air.ambient_pressure)))

    def dry_start(self, u: np.ndarray | None = None) -> np.ndarray:
        """[u (m), p = p_a (Pa)]: by default the dry tape over the head with its sharp
        corners held at σ (Newton's second start over a flat or profile head: at low
        speeds the film's suction barely pulls the tape below its dry tents)."""
        u = self._corner_start(dry=True) if u is None else u
        return np.concatenate([u, np.full(self.n_p, self.air.ambient_pressure)])

    def _all_corners_wrapped(self) -> bool:
        """Whether every corner turning the tape by 5 % of the wrap is a wrapped arc: the
        tape then flies over the head as over cylinders of the arcs' radii (the foil
        start, sized by the smallest, :attr:`scale_radius`; the flat start, 1/10 of it
        with p = p_a, gives Newton a singular Jacobian there: measured)."""
        if not self.wrapped_corners:
            return False
        turns = self.head.corner_turns(self.head_radius)
        return all(k in self.wrapped_corners for k, t in enumerate(turns)
                   if t >= CORNER_FRACTION * self.wrap_angle)

    def initial_state(self) -> np.ndarray:
        """The flexible-foil start [u (m), p (Pa)]: the foil spacing scale everywhere and
        the wrap pressure (T − ρV²) κ + p_a. :func:`gyroshell.bearing.steady.solve_steady`
        starts a 2-D tape from a better (solved) state, :func:`~gyroshell.bearing.steady.
        initial_state`."""
        # a smooth law's touching arcs are started as point contacts (:meth:`_corner_start`)
        flies = self.cylindrical or (self._all_corners_wrapped()
                                     and not (self.smooth_contact and self.touching_arcs))
        if self.dry or not flies:
            return self.dry_start(self._corner_start())   # the corners' point loads
        u = np.full(self.n_u, self.h_guess)
        kappa = np.repeat(self.kappa[:, None], self.nc, axis=1)
        p = self.air.ambient_pressure + self.effective_tension() * kappa[
            self.film.interior[1:-1, :]]
        return np.concatenate([u, p])
