"""Head designs: what a user states about a head (the ``gyroshell bearing`` options, a
``[head]`` table of a TOML file, the points of a head study), checked, and the head it
builds (:mod:`gyroshell.bearing.head`).

A :class:`HeadDesign` holds the head's parameters in SI units (angles in rad); the fields
of the other head kinds stay ``None``. It is checked as a whole by :func:`check_design`
before any numerical module is imported (one line naming the option and its range, as the
user spelled it: ``--land-length``, ``head.toml: [head] land_length``, ``--vary
land_length``), and :meth:`HeadDesign.head` builds the :class:`~gyroshell.bearing.head.Head`.

A ``[head]`` table, beside the ``[tape]`` table of the ``--config`` file::

    [head]
    kind = "flat"                 # "cylinder" (default), "flat" or "profile"
    land_length = "1 mm"          # each module's land, corner to corner
    corner_radius = "0 um"        # or ["5 um", "0 um"]: (leading, trailing)
    wrap_in = "2 deg"             # the incoming span's angle below the first land
    wrap_out = "2 deg"            # the outgoing span's angle below the last land
    modules = 3                   # equal modules (write-read-write) ...
    module_gap = "0.3 mm"         # ... this far apart (or a list of modules - 1 gaps)
    transducers = ["-1.3 mm", "0 mm", "1.3 mm"]   # element lines, m from the head's middle
    friction = 0.2                # Coulomb coefficient between tape and head
    # flank_angle = "20 deg"      # the fall-away beyond each corner (default 20 deg)
    # arc_contact = "auto"        # rounded corners: "auto", "point" or "wrapped"

    [[head.module]]               # optional, one table per module, in the tape's order:
    height = "0 um"               # the land's middle above the head datum
    tilt = "0 deg"                # the land's slope dz/dx
    # land_length, corner_radius: this module's own

A cylinder takes ``wrap_angle`` (default 15 deg) and ``radius`` (default: the tape's R); a
measured contour ``profile = "head.csv"`` (a path relative to the TOML file's folder, columns
(x, z) or (x, y, z) in m) with ``wrap_in`` and ``wrap_out``. Numbers without a unit are SI
(angles in rad), as everywhere in a TOML file; the command line takes degrees.

Rounded corners' contact (``arc_contact``, ``--arc-contact``; the model's option
``BearingModel(arc_contact=...)``): ``"point"``, the tape touches each rounded corner at
one tangent point (found by regridding; valid while the tape is less curved than the arc);
``"wrapped"``, the tape may lie on part of each arc (every arc node in the general contact
set); ``"auto"`` (the default), per corner: wrapped when its arc r_c θ_c (m) exceeds 0.3
bending lengths √(D/(T − ρV²)) (:data:`~gyroshell.bearing.model.WRAPPED_ARC_BENDING_LENGTHS`),
else a point.

Multi-module heads. ``modules = N`` makes N equal modules separated by ``module_gap``, all
coplanar (height 0, tilt 0) unless ``[[head.module]]`` tables set their heights and tilts:
the tape then runs straight over the inner corners and the wrap acts at the outer corners
only (``wrap_in`` at the first leading corner, ``wrap_out`` at the last trailing one). Set
heights or tilts to give the inner corners a wrap of their own (tilting the outer modules
down by α, up to 10°, gives each inner corner a wrap α). A flat head needs a wrap at its
ends (``wrap_in`` or ``wrap_out`` > 0): nothing else presses the tape onto it.
"""

from __future__ import annotations

import dataclasses
import math
import os
import re
from collections.abc import Collection, Mapping
from dataclasses import dataclass
from pathlib import Path

from ..core import validation
from ..core.errors import InputFileError, ParameterError
from .head import ARC_CONTACTS, DEFAULT_FLANK_ANGLE, MAX_MODULES, MAX_SIDE_WRAP, MAX_TILT

__all__ = ["DEFAULT_WRAP_ANGLE", "HEAD_KINDS", "MAX_MODULES", "HeadDesign", "ModuleShape",
           "build_head", "check_design", "design_from_table", "in_file", "kind_fields",
           "table_labels"]

#: The kinds of head.
HEAD_KINDS: tuple[str, ...] = ("cylinder", "flat", "profile")
#: The cylinder's wrap when none is given, rad (the bearing's default since issue 7).
DEFAULT_WRAP_ANGLE = math.radians(15.0)
#: Largest wrap at either end of a flat or measured head, rad: the small-slope model.
MAX_CORNER_WRAP = MAX_SIDE_WRAP
#: The fields each kind of head uses (beside ``transducers`` and ``friction``).
_KIND_FIELDS: dict[str, tuple[str, ...]] = {
    "cylinder": ("wrap_angle", "radius"),
    "flat": ("wrap_in", "wrap_out", "land_length", "corner_radius", "modules", "module_gap",
             "module_shapes", "flank_angle", "arc_contact"),
    "profile": ("wrap_in", "wrap_out", "profile"),
}
#: How each field is named in a ``[head]`` table (and, with ``-`` for ``_``, on the CLI).
TABLE_NAMES = {"module_shapes": "module"}


def kind_fields(kind: str) -> tuple[str, ...]:
    """The fields of :class:`HeadDesign` a head of ``kind`` uses (and ``transducers``,
    ``friction``, which every head has)."""
    return _KIND_FIELDS[kind] + ("transducers", "friction")


@dataclass(frozen=True)
class ModuleShape:
    """One module of a flat head as a ``[[head.module]]`` table gives it; ``None``: the
    head's own value.

    Attributes
    ----------
    land_length : float or None
        m, corner to corner.
    corner_radius : float, (float, float) or None
        m, (leading, trailing); 0 is a sharp corner.
    height : float
        m, of the land's middle above the head datum.
    tilt : float
        rad, the land's slope dz/dx.
    """

    land_length: float | None = None
    corner_radius: float | tuple[float, float] | None = None
    height: float = 0.0
    tilt: float = 0.0


@dataclass(frozen=True)
class HeadDesign:
    """A head as the user states it (SI units, angles in rad); ``None``: not given.

    Attributes
    ----------
    kind : str
        ``"cylinder"``, ``"flat"`` or ``"profile"`` (:data:`HEAD_KINDS`).
    wrap_angle : float or None
        Cylinder: the total wrap θ, rad, in (0, π/2] (None: :data:`DEFAULT_WRAP_ANGLE`).
    radius : float or None
        Cylinder: its radius, m (None: the tape's radius R).
    wrap_in, wrap_out : float or None
        Flat and measured heads: the incoming (outgoing) span's angle below the first
        (last) land, rad, in [0, 45°] (None: 0).
    land_length : float or None
        Flat: each module's land, corner to corner, m (required unless every module shape
        gives its own).
    corner_radius : float, (float, float) or None
        Flat: the corners' radius, m, >= 0, or (leading, trailing) (None: 0, sharp).
    modules : int or None
        Flat: the number of modules, 1 to :data:`MAX_MODULES` (None: one, or as many as
        ``module_shapes``).
    module_gap : float, tuple or None
        Flat: the gap between consecutive modules, m, > 0, corner to corner (one for all,
        or modules − 1 values; required for two modules or more).
    module_shapes : tuple of ModuleShape
        Flat: per-module heights, tilts, lands and corner radii (empty: equal coplanar
        modules).
    flank_angle : float or None
        Flat: the angle of the flanks below the land beyond each corner, rad, in (0, π/2)
        (None: the head's default, 20°); steeper than wrap_in and wrap_out.
    arc_contact : str or None
        Flat, rounded corners only (refused on sharp ones, where it has no effect): how the
        tape meets the rounded corners, one of
        :data:`~gyroshell.bearing.head.ARC_CONTACTS`
        (``"auto"``, ``"point"``, ``"wrapped"``: the module notes; None: ``"auto"``); an
        option of the bearing model (:meth:`model_options`), not of the contour.
    profile : str or None
        Measured head: the CSV file of its contour (x, z) or (x, y, z), m.
    transducers : tuple of float
        x of the read/write element lines, m from the head's middle.
    friction : float
        Coulomb coefficient μ >= 0 between tape and head.
    """

    kind: str = "cylinder"
    wrap_angle: float | None = None
    radius: float | None = None
    wrap_in: float | None = None
    wrap_out: float | None = None
    land_length: float | None = None
    corner_radius: float | tuple[float, float] | None = None
    modules: int | None = None
    module_gap: float | tuple[float, ...] | None = None
    module_shapes: tuple[ModuleShape, ...] = ()
    flank_angle: float | None = None
    arc_contact: str | None = None
    profile: str | None = None
    transducers: tuple[float, ...] = ()
    friction: float = 0.0

    def given(self) -> tuple[str, ...]:
        """The kind-specific fields that are set (not None, not empty)."""
        return tuple(name for names in _KIND_FIELDS.values() for name in names
                     if getattr(self, name) not in (None, ()))

    def replace(self, **changes) -> HeadDesign:
        """A copy with ``changes`` (fields of this class), checked (:func:`check_design`)."""
        unknown = sorted(set(changes) - {f.name for f in dataclasses.fields(self)})
        if unknown:
            raise ParameterError(f"a head has no {', '.join(unknown)}")
        return check_design(dataclasses.replace(self, **changes))

    @property
    def module_count(self) -> int:
        """The number of modules of a flat head."""
        if self.modules is not None:
            return self.modules
        return max(1, len(self.module_shapes))

    def model_options(self) -> dict:
        """The keyword arguments of :class:`~gyroshell.bearing.model.BearingModel` this
        design sets beside its head (``arc_contact``, if given)."""
        return {} if self.arc_contact is None else {"arc_contact": self.arc_contact}

    def head(self):
        """The :class:`~gyroshell.bearing.head.Head` of this design (a cylinder of
        radius None takes the tape's radius when the model is built).

        Raises
        ------
        ParameterError
            What the head's constructor refuses (transducers off the head, ...);
            InputFileError for a bad profile file.
        """
        from . import head as h

        common = {"transducers": tuple(self.transducers), "friction": self.friction}
        if self.kind == "cylinder":
            wrap = DEFAULT_WRAP_ANGLE if self.wrap_angle is None else self.wrap_angle
            return h.Cylinder(wrap, radius=self.radius, **common)
        wraps = {"wrap_in": self.wrap_in or 0.0, "wrap_out": self.wrap_out or 0.0}
        if self.kind == "profile":
            return h.ProfileHead.from_csv(self.profile, **wraps, **common)
        extra = {} if self.flank_angle is None else {"flank_angle": self.flank_angle}
        return h.FlatHead(modules=self._modules(h.Module), gaps=self._gaps(), **wraps,
                          **extra, **common)

    def _modules(self, module_class) -> tuple:
        """The flat head's modules (equal unless module shapes say otherwise)."""
        n = self.module_count
        shapes = self.module_shapes or (ModuleShape(),) * n
        corner = 0.0 if self.corner_radius is None else self.corner_radius
        return tuple(module_class(
            land_length=self.land_length if s.land_length is None else s.land_length,
            corner_radius=corner if s.corner_radius is None else s.corner_radius,
            height=s.height, tilt=s.tilt) for s in shapes)

    def _gaps(self) -> tuple[float, ...]:
        """The n − 1 gaps between the modules, m."""
        n = self.module_count
        if n == 1:
            return ()
        if isinstance(self.module_gap, tuple):
            return self.module_gap
        return (self.module_gap,) * (n - 1)


def check_design(design: HeadDesign, labels: Mapping[str, str] | None = None, *,
                 degrees: bool = False, varied: Collection[str] = ()) -> HeadDesign:
    """``design`` checked whole, without building the head; returns it.

    Parameters
    ----------
    design : HeadDesign
    labels : mapping, optional
        How the user named each field (``{"land_length": "--land-length"}``) and ``kind``
        (``"--head flat"``), for the messages; default: the field's name.
    degrees : bool
        State the angles' ranges in degrees (the command line's unit), not rad.
    varied : collection of str
        Fields a study sets at its points (``--vary wrap_in``): the checks that need them
        (a flat head's wrap at either end, its land length, the gap of several modules)
        are left to each point's head, checked whole when the point is
        (:func:`gyroshell.studies.head_study.head_of_point`).

    Raises
    ------
    ParameterError
        One line naming the option and its allowed range: an unknown kind; an option of
        another kind of head (``--wrap-angle`` on a flat head, ``--land-length`` on a
        cylinder); a value out of range; a flat head with no land length or no wrap at
        either end (nothing would press the tape onto it), fewer than 1 or more than
        :data:`MAX_MODULES` modules, a gap <= 0 or a gap without a second module; coplanar
        modules' wrap at either end not below the flank angle (the tape would lie on the
        flank); ``arc_contact`` on a head whose corners are all sharp; a profile head
        without its file; a friction coefficient < 0. What needs the contour (a land
        shorter than its corner radii allow, tilted or raised modules overlapping,
        transducers off the head, a bad profile file) is refused when
        :meth:`HeadDesign.head` builds it (:func:`build_head` names the fields as the
        user did).
    """
    name = _Names(labels or {}, degrees, varied)

    validation.choice(name("kind"), design.kind, HEAD_KINDS)
    kind_label = name.labels.get("kind", design.kind)
    for field in design.given():
        if field not in _KIND_FIELDS[design.kind]:
            owners = [k for k, names in _KIND_FIELDS.items() if field in names]
            raise ParameterError(
                f"{name(field)} is an option of a {' or '.join(owners)} head, and this head "
                f"is a {design.kind} ({kind_label}): drop {name(field)} or choose a "
                f"{owners[0]} head")
    transducers = tuple(validation.real(f"{name('transducers')}[{i}]", x, unit="m")
                        for i, x in enumerate(design.transducers))
    friction = validation.nonnegative(name("friction"), design.friction)
    checks = {"cylinder": _checked_cylinder, "flat": _checked_flat,
              "profile": _checked_profile}[design.kind]
    changes = checks(design, name)
    return dataclasses.replace(design, transducers=transducers, friction=friction, **changes)


class _Names:
    """How the user named each field, and the angle check in the user's unit."""

    def __init__(self, labels: Mapping[str, str], degrees: bool,
                 varied: Collection[str] = ()) -> None:
        self.labels, self.degrees, self.varied = dict(labels), degrees, frozenset(varied)

    def __call__(self, field: str) -> str:
        return self.labels.get(field, TABLE_NAMES.get(field, field))

    def angle(self, label: str, value, *, high: float, low: float = 0.0,
              low_open: bool = False, high_open: bool = False) -> float:
        """``value`` (rad) checked within [low, high] rad (or open ends), the range stated
        in degrees if the user typed degrees."""
        value = validation.real(label, value, unit="rad")
        ends = {"low_open": low_open, "high_open": high_open}
        if not self.degrees:
            return validation.real(label, value, low=low, high=high, unit="rad", **ends)
        validation.real(label, math.degrees(value), low=math.degrees(low),
                        high=math.degrees(high), unit="degrees", **ends)
        return value


def _checked_cylinder(design: HeadDesign, name) -> dict:
    changes = {}
    if design.wrap_angle is not None:
        changes["wrap_angle"] = name.angle(name("wrap_angle"), design.wrap_angle,
                                           low_open=True, high=math.pi / 2)
    if design.radius is not None:
        changes["radius"] = validation.positive(name("radius"), design.radius, "m")
    return changes


def _checked_wraps(design: HeadDesign, name) -> dict:
    return {field: name.angle(name(field), getattr(design, field), high=MAX_CORNER_WRAP)
            for field in ("wrap_in", "wrap_out") if getattr(design, field) is not None}


def _checked_profile(design: HeadDesign, name) -> dict:
    if design.profile is None:
        raise ParameterError(f"a measured head needs its contour: give {name('profile')} "
                             "(a CSV file of x, z or x, y, z in m)")
    return {"profile": os.fspath(design.profile), **_checked_wraps(design, name)}


def _checked_flat(design: HeadDesign, name) -> dict:
    changes = _checked_wraps(design, name)
    n = design.modules
    if n is not None:
        n = validation.integer(name("modules"), n, low=1, high=MAX_MODULES)
        changes["modules"] = n
        if design.module_shapes and len(design.module_shapes) != n:
            raise ParameterError(f"{name('modules')} = {n} but {len(design.module_shapes)} "
                                 f"{name('module_shapes')} tables are given: one per module")
    n = n or max(1, len(design.module_shapes))
    changes["module_gap"] = _checked_gaps(design.module_gap, n, name)
    if design.flank_angle is not None:
        changes["flank_angle"] = name.angle(name("flank_angle"), design.flank_angle,
                                            low_open=True, high=math.pi / 2, high_open=True)
    if design.arc_contact is not None:
        changes["arc_contact"] = validation.choice(name("arc_contact"), design.arc_contact,
                                                   ARC_CONTACTS)
    corner = _checked_corner(name("corner_radius"), design.corner_radius)
    changes["corner_radius"] = corner
    _check_arc_contact_has_arcs(design, name)
    shapes = design.module_shapes or (ModuleShape(),)
    checked = []
    for i, shape in enumerate(shapes):
        where = f"{name('module_shapes')}[{i}] " if design.module_shapes else ""
        checked.append(_checked_shape(shape, design.land_length, where, name))
    if design.module_shapes:
        changes["module_shapes"] = tuple(checked)
    if design.land_length is not None:
        changes["land_length"] = validation.positive(name("land_length"), design.land_length,
                                                     "m")
    wraps_varied = {"wrap_in", "wrap_out"} & name.varied
    if not wraps_varied and not (changes.get("wrap_in") or 0.0) + (changes.get("wrap_out")
                                                                     or 0.0) > 0.0:
        raise ParameterError(
            f"a flat head needs a wrap: {name('wrap_in')} and {name('wrap_out')} are both 0, "
            "so nothing presses the tape onto the head; give at least one of them > 0 "
            f"(e.g. 2 {'degrees' if name.degrees else 'deg'})")
    if not design.module_shapes:
        _check_wraps_below_flank(changes, design.flank_angle, name)
    return changes


def _check_arc_contact_has_arcs(design: HeadDesign, name) -> None:
    """Refuse ``arc_contact`` on a flat head whose corners are all sharp: it sets how the
    tape meets rounded corners, and would be ignored."""
    if design.arc_contact is None or "corner_radius" in name.varied:
        return
    radii = [design.corner_radius] + [m.corner_radius for m in design.module_shapes]
    flat = [r for radius in radii if radius is not None
            for r in (radius if isinstance(radius, tuple | list) else (radius,))]
    if not any(r > 0.0 for r in flat):
        raise ParameterError(
            f"{name('arc_contact')} {design.arc_contact} sets how the tape meets rounded "
            f"corners, and this head's corners are all sharp ({name('corner_radius')} 0): "
            f"drop {name('arc_contact')} or give {name('corner_radius')} > 0")


def _check_wraps_below_flank(changes: dict, flank: float | None, name) -> None:
    """Coplanar modules: the span at the outer corners (wrap_in, wrap_out) must be less
    steep than the flank beyond them, or the tape would lie on the flank (what
    :class:`~gyroshell.bearing.head.FlatHead` refuses, said here in the user's names)."""
    flank = DEFAULT_FLANK_ANGLE if changes.get("flank_angle") is None \
        else changes["flank_angle"]
    unit, scale = ("degrees", math.degrees) if name.degrees else ("rad", float)
    for field in ("wrap_in", "wrap_out"):
        wrap = changes.get(field)
        if field in name.varied or wrap is None or wrap < flank:
            continue
        given = "" if changes.get("flank_angle") is not None else ", its default"
        raise ParameterError(
            f"{name(field)} must be below the flank angle {scale(flank):.4g} {unit} "
            f"({name('flank_angle')}{given}), got {scale(wrap):.4g}: beyond the outer "
            "corners the head falls away along the flanks, and a steeper span would lie on "
            f"them; use a smaller {name(field)} or a steeper {name('flank_angle')} (< "
            f"{scale(math.pi / 2):g} {unit})")


def _checked_gaps(gap, n: int, name):
    """The module gap(s), m, > 0, for ``n`` modules."""
    if gap is None:
        if n > 1 and "module_gap" not in name.varied:
            raise ParameterError(f"{n} modules need the gap between them: give "
                                 f"{name('module_gap')} (m, > 0)")
        return None
    if n == 1:
        raise ParameterError(f"{name('module_gap')} is the gap between modules, and this "
                             f"head has one: drop it or give {name('modules')} >= 2")
    if isinstance(gap, tuple | list):
        if len(gap) != n - 1:
            raise ParameterError(f"{name('module_gap')} must be one gap or {n - 1} (one "
                                 f"between each two of the {n} modules), got {len(gap)}")
        return tuple(validation.positive(f"{name('module_gap')}[{i}]", g, "m")
                     for i, g in enumerate(gap))
    return validation.positive(name("module_gap"), gap, "m")  # touching modules are one


def _checked_corner(label: str, corner):
    """A corner radius, m, >= 0, or a (leading, trailing) pair of them; None stays."""
    if corner is None:
        return None
    if isinstance(corner, tuple | list):
        if len(corner) != 2:
            raise ParameterError(f"{label} must be one radius or two (leading, trailing), "
                                 f"got {len(corner)}")
        return tuple(validation.nonnegative(f"{label}[{i}]", c, "m")
                     for i, c in enumerate(corner))
    return validation.nonnegative(label, corner, "m")


def _checked_shape(shape: ModuleShape, land: float | None, where: str, name) -> ModuleShape:
    """One module's shape checked: a land length, radii >= 0, a tilt within 10°."""
    if not isinstance(shape, ModuleShape):
        raise ParameterError(f"{where or 'a module'} must be a ModuleShape, got "
                             f"{type(shape).__name__}")
    own = shape.land_length is not None
    land = shape.land_length if own else land
    label = f"{where}land_length" if own else name("land_length")
    if land is not None:
        validation.positive(label, land, "m")
    elif "land_length" not in name.varied:  # else each point gives its own
        raise ParameterError(f"a flat head needs its land length: give {name('land_length')} "
                             "(m, corner to corner, e.g. 1e-3)")
    if shape.corner_radius is not None:
        _checked_corner(f"{where}corner_radius", shape.corner_radius)
    height = validation.real(f"{where}height", shape.height, unit="m")
    tilt = name.angle(f"{where}tilt", shape.tilt, low=-MAX_TILT, high=MAX_TILT)
    return ModuleShape(land_length=shape.land_length, corner_radius=shape.corner_radius,
                       height=height, tilt=tilt)


# --- the [head] table of a TOML file -------------------------------------------------------

#: The keys of a ``[head]`` table and the SI unit of each number ("" : text or a count).
_TABLE_KEYS: dict[str, str] = {
    "kind": "", "wrap_angle": "rad", "radius": "m", "wrap_in": "rad", "wrap_out": "rad",
    "land_length": "m", "corner_radius": "m", "modules": "", "module_gap": "m",
    "flank_angle": "rad", "arc_contact": "", "profile": "", "transducers": "m",
    "friction": "1", "module": ""}
_MODULE_KEYS: dict[str, str] = {"land_length": "m", "corner_radius": "m", "height": "m",
                                "tilt": "rad"}


def design_from_table(table: object, *, where: str = "", folder: str | os.PathLike | None = None
                      ) -> HeadDesign:
    """The :class:`HeadDesign` of a parsed ``[head]`` table (see the module docstring),
    checked (:func:`check_design`).

    Parameters
    ----------
    table : dict
        The table as ``tomllib`` parsed it.
    where : str
        The file, as messages name it (``"head.toml: "``).
    folder : path, optional
        The TOML file's folder: a relative ``profile`` path is read from there.

    Raises
    ------
    ParameterError
        Naming the file and the key: an unknown key, a value of the wrong type, unit or
        range, options of another kind of head (see :func:`check_design`).
    """
    prefix = f"{where}[head] "
    if not isinstance(table, dict):
        raise ParameterError(f"{prefix.rstrip()} must be a table")
    unknown = sorted(set(table) - set(_TABLE_KEYS))
    if unknown:
        raise ParameterError(f"{prefix}unknown key(s) {', '.join(unknown)}; allowed: "
                             f"{', '.join(_TABLE_KEYS)}")
    fields = _table_fields(table, prefix)
    if "profile" in fields and folder is not None:
        fields["profile"] = os.fspath(Path(folder) / fields["profile"])
    kind = fields.get("kind", "cylinder")
    if kind not in HEAD_KINDS:
        raise ParameterError(f"{prefix}kind must be one of {', '.join(HEAD_KINDS)}, "
                             f"got {kind!r}")
    return in_file(where, lambda: check_design(HeadDesign(**fields),
                                               table_labels("kind" in fields and kind)))


def _table_fields(table: dict, prefix: str) -> dict:
    """The HeadDesign fields of a ``[head]`` table's keys (numbers to SI)."""
    from ..tape.config import parse_quantity

    def number(key, value, unit, at=prefix):
        return parse_quantity(key, value, at, unit=unit)

    def numbers(key, value, unit, at=prefix):
        if isinstance(value, list):
            return tuple(number(f"{key}[{i}]", v, unit, at) for i, v in enumerate(value))
        return number(key, value, unit, at)

    fields: dict = {}
    for key, value in table.items():
        unit = _TABLE_KEYS[key]
        if key in ("kind", "profile", "arc_contact"):
            if not isinstance(value, str):
                raise ParameterError(f"{prefix}{key} must be text, got {value!r}")
            fields[key] = value
        elif key == "modules":
            fields[key] = validation.integer(f"{prefix}modules", value, low=1,
                                             high=MAX_MODULES)
        elif key == "module":
            fields["module_shapes"] = _shapes_of(value, prefix, number, numbers)
        elif key == "transducers":
            items = value if isinstance(value, list) else [value]
            fields[key] = tuple(number(f"{key}[{i}]", v, unit) for i, v in enumerate(items))
        elif key in ("corner_radius", "module_gap"):
            fields[key] = numbers(key, value, unit)
        else:
            fields[key] = number(key, value, unit)
    return fields


def table_labels(kind: str | None) -> dict[str, str]:
    """How the messages name the fields of a ``[head]`` table whose ``kind`` is given
    (None: not given); the messages of :func:`in_file` add the file."""
    fields = [f.name for f in dataclasses.fields(HeadDesign)]
    labels = {field: f"[head] {TABLE_NAMES.get(field, field)}" for field in fields}
    labels["kind"] = f"[head] kind = {kind!r}" if kind else "[head] without a kind"
    return labels


def build_head(design: HeadDesign, labels: Mapping[str, str] | None = None, where: str = ""):
    """:meth:`HeadDesign.head`, its contour's refusals (a land shorter than its corner
    radii allow, modules overlapping, a flank not steeper than the tape) naming the fields
    as ``labels`` do (how the user named them, as for :func:`check_design`) and, for a
    ``[head]`` key, the file ``where`` (``"head.toml: "``).

    Raises
    ------
    ParameterError
        As :meth:`HeadDesign.head`, in the user's names; InputFileError (a profile file's)
        as it is: it names its file.
    """
    try:
        return design.head()
    except InputFileError:
        raise
    except ParameterError as exc:
        if not labels:
            raise
        text = _in_users_names(str(exc), design, _Names(labels, degrees=True))
        if where and "[head]" in text:
            text = f"{where}{text}"
        raise type(exc)(text) from None


def _in_users_names(text: str, design: HeadDesign, name: _Names) -> str:
    """A message of :class:`~gyroshell.bearing.head.FlatHead` (``modules[i]``,
    ``land_length``, ``flank_angle``, ``corner_radius``, "a smaller wrap") in the names
    ``name`` gives the fields: a ``[[head.module]]`` table is ``[head] module[i]``."""
    module = name("module_shapes") if design.module_shapes else None

    def land(match) -> str:
        i = int(match.group(1))
        own = module is not None and design.module_shapes[i].land_length is not None
        return f"{module}[{i}] land_length" if own else name("land_length")

    text = re.sub(r"modules\[(\d+)\]\.land_length", land, text)
    if module is not None:
        text = re.sub(r"modules\[(\d+)\]", lambda m: f"{module}[{m.group(1)}]", text)
    for field in ("flank_angle", "corner_radius"):
        text = re.sub(rf"\b{field}\b", name(field), text)
    return text.replace("a smaller wrap", f"a smaller {name('wrap_in')} or {name('wrap_out')}")


def in_file(where: str, check):
    """``check()``, a message that names a ``[head]`` key starting with the file ``where``."""
    try:
        return check()
    except ParameterError as exc:
        if where and "[head]" in str(exc) and not str(exc).startswith(where):
            raise type(exc)(f"{where}{exc}") from None
        raise


def _shapes_of(value, prefix: str, number, numbers) -> tuple[ModuleShape, ...]:
    """The ``[[head.module]]`` tables as module shapes."""
    if not isinstance(value, list) or not all(isinstance(t, dict) for t in value):
        raise ParameterError(f"{prefix}module must be [[head.module]] tables, one per module")
    shapes = []
    for i, table in enumerate(value):
        at = f"{prefix}module[{i}] "
        unknown = sorted(set(table) - set(_MODULE_KEYS))
        if unknown:
            raise ParameterError(f"{at}unknown key(s) {', '.join(unknown)}; allowed: "
                                 f"{', '.join(_MODULE_KEYS)}")
        shape = {key: (numbers if key == "corner_radius" else number)(key, v,
                                                                       _MODULE_KEYS[key], at)
                 for key, v in table.items()}
        shapes.append(ModuleShape(**shape))
    return tuple(shapes)
