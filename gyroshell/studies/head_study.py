"""Head design studies: what ``compute="bearing"`` computes at a point of a parameter study.

A point may change the tape (its fields, ``velocity``) and the head
(:data:`~gyroshell.studies.points.HEAD_VARIABLES`: the cylinder's ``wrap_angle``, the
wraps ``wrap_in`` and ``wrap_out`` (or ``wrap``, both at once), ``land_length``,
``corner_radius``, ``module_gap``; in SI units, angles in rad). Each point solves the
steady flying state (:func:`gyroshell.bearing.steady.solve_steady`) of the tape over the
point's head and reports, per point:

``central_spacing``, ``minimum_spacing``
    m (:class:`~gyroshell.bearing.results.BearingSolution`).
``transducer_<i>_min_spacing``, ``transducer_<i>_mean_spacing``
    m, the spacing's minimum and mean across the width along the i-th transducer line
    (i = 1, 2, ... in the head's order).
``corner_<j>_tent_height``, ``corner_<j>_tent_x``, ``corner_<j>_force``
    The tent next to the j-th corner on its land side, along the middle of the width
    (its height, m, and position, m from the head's middle; NaN where the spacing has no
    local maximum there, :attr:`~gyroshell.bearing.results.BearingSolution.tents`) and
    the corner's contact force (N; N/m per unit width when infinitely wide).
``contact_force``, ``viscous_drag``, ``friction_drag``, ``drag``
    N (N/m per unit width when infinitely wide).
``tension_rise``, ``tension_ratio``
    N/m and 1: the drag per unit width, and 1 + tension_rise / T.
``newton_iterations``
    The solve's Newton iterations.

The number of transducer and corner columns is the base head's; a point whose head has
another number of corners fails in its row.
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass

from ..bearing.air import LEGACY_AIR, AirParameters
from ..bearing.contact import HARD_WALL_GAP, ContactParameters
from ..bearing.head_config import (
    DEFAULT_WRAP_ANGLE,
    HeadDesign,
    ModuleShape,
    check_design,
    kind_fields,
)
from ..core import validation
from ..core.errors import ParameterError
from ..tape.parameters import TapeParameters
from .points import (
    BEARING_VARIABLES,
    BOTH_WRAPS,
    HEAD_VARIABLES,
    INTERFACE_VARIABLES,
    parameters_of,
)

__all__ = ["BearingStudy", "bearing_row", "head_of_point", "head_value"]

#: The columns every bearing point reports before its transducer and corner columns.
LEADING = ("central_spacing", "minimum_spacing")
#: ... and after them.
TRAILING = ("contact_force", "viscous_drag", "friction_drag", "drag", "tension_rise",
            "tension_ratio", "newton_iterations")
#: The values each bearing column may take: (lowest, unit) (NaN is always allowed). A
#: spacing is measured to the mean plane of the tape's summits: under asperity contact a
#: pressed corner takes it below zero.
NUMBER_RANGES = {"spacing": (-math.inf, "m"), "tent_height": (-math.inf, "m"),
                 "tent_x": (-math.inf, "m"), "force": (0.0, "N or N/m"),
                 "contact_force": (0.0, "N or N/m"), "viscous_drag": (-math.inf, "N or N/m"),
                 "friction_drag": (0.0, "N or N/m"), "drag": (-math.inf, "N or N/m"),
                 "tension_rise": (-math.inf, "N/m"), "tension_ratio": (0.0, "1"),
                 "newton_iterations": (0.0, "1")}
#: The keys of :meth:`BearingStudy.spec` (a saved study's ``bearing`` attribute).
SPEC_KEYS = ("head", "air", "infinitely_wide", "nx", "ny")
#: Keys a spec may hold beside them (absent in studies saved before contact laws).
OPTIONAL_SPEC_KEYS = ("contact",)
#: HeadDesign fields that hold tuples (JSON lists in a spec).
_TUPLE_FIELDS = ("corner_radius", "module_gap", "transducers")


@dataclass(frozen=True)
class BearingStudy:
    """What every bearing point of a study shares beside the tape.

    Attributes
    ----------
    head : HeadDesign
        The base head (:class:`gyroshell.bearing.head_config.HeadDesign`); points change
        its fields. What a study's points may set (a flat head's wraps, land length, module
        gap: :data:`~gyroshell.studies.points.HEAD_VARIABLES`) may be missing here; the
        study checks the base head without the fields its points vary, and every point's
        head whole (:func:`head_of_point`).
    air : AirParameters or None
        The air film (None: air at 20 °C).
    contact : ContactParameters or None
        How the tape touches the head (None: the bearing's default,
        :class:`gyroshell.bearing.model.BearingModel`'s ``contact=None``).
    infinitely_wide : bool
        Solve the 1-D infinitely wide tape (per unit width) instead of the 2-D tape.
    nx, ny : int or None
        The grid's intervals (None: the bearing's default grid at each point).
    columns : tuple of str
        The columns of a point (:meth:`with_columns` fills them for the base tape; empty
        until then).
    """

    head: HeadDesign = dataclasses.field(default_factory=HeadDesign)
    air: AirParameters | None = None
    contact: ContactParameters | None = None
    infinitely_wide: bool = False
    nx: int | None = None
    ny: int | None = None
    columns: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        validation.instance("head", self.head, HeadDesign)
        validation.instance("air", self.air, AirParameters, optional=True)
        validation.instance("contact", self.contact, ContactParameters, optional=True)
        validation.boolean("infinitely_wide", self.infinitely_wide)
        validation.integer("nx", self.nx, low=1, optional=True)
        validation.integer("ny", self.ny, low=1, optional=True)
        if self.infinitely_wide and self.ny is not None:
            raise ParameterError("ny applies to the 2-D tape only: leave it None with "
                                 "infinitely_wide=True")
        object.__setattr__(self, "head", check_design(self.head, varied=HEAD_VARIABLES))

    def spec(self) -> dict:
        """The setup as plain JSON values, lists for tuples (a cache key's part, a saved
        study's metadata: it reads back equal). The air and the contact are written out
        (the defaults' values for None), so that a cache keyed by it never serves rows of
        other defaults."""
        from ..bearing.model import default_contact

        air = AirParameters() if self.air is None else self.air
        contact = default_contact(air) if self.contact is None else self.contact
        return json.loads(json.dumps({
            "head": dataclasses.asdict(self.head), "air": dataclasses.asdict(air),
            "contact": contact.to_dict(),
            "infinitely_wide": self.infinitely_wide, "nx": self.nx, "ny": self.ny}))

    @classmethod
    def from_spec(cls, spec: object) -> BearingStudy:
        """The setup that :meth:`spec` describes (a saved study's ``bearing`` attribute),
        checked as when it is built (``modules: 99`` is refused as ``modules=99`` is).

        Raises
        ------
        ParameterError
            Naming the key and what is wrong with it.
        """
        try:
            return cls(**_fields_of_spec(spec))
        except (TypeError, ValueError) as exc:  # ParameterError, or a value of a wrong type
            raise ParameterError(f"bearing: {exc}") from None

    def with_columns(self, base: TapeParameters, design: HeadDesign | None = None
                     ) -> BearingStudy:
        """This setup with the columns of its points over the tape ``base``, counted on the
        head of ``design`` (a point's; default the base head, which is built here: one its
        constructor refuses, transducers off it, is refused now)."""
        head = (self.head if design is None else design).head()
        transducers = len(head.transducers)
        corners = len(head.corners(radius=base.radius))
        out = list(LEADING)
        for i in range(1, transducers + 1):
            out += [f"transducer_{i}_min_spacing", f"transducer_{i}_mean_spacing"]
        for j in range(1, corners + 1):
            out += [f"corner_{j}_tent_height", f"corner_{j}_tent_x", f"corner_{j}_force"]
        return dataclasses.replace(self, columns=tuple(out + list(TRAILING)))


def _fields_of_spec(spec: object) -> dict:
    """The BearingStudy fields of a :meth:`~BearingStudy.spec`, their keys checked."""
    _check_keys("the setup", spec, SPEC_KEYS + OPTIONAL_SPEC_KEYS, required=SPEC_KEYS)
    head = dict(_check_keys("head", spec["head"],
                            [f.name for f in dataclasses.fields(HeadDesign)]))
    shapes = head.get("module_shapes", [])
    if not isinstance(shapes, list):
        raise ParameterError(f"head: module_shapes must be a list, got {shapes!r}")
    shape_fields = [f.name for f in dataclasses.fields(ModuleShape)]
    head["module_shapes"] = tuple(
        ModuleShape(**_tuples(_check_keys(f"head: module_shapes[{i}]", shape, shape_fields)))
        for i, shape in enumerate(shapes))
    air = spec["air"]
    legacy = "contact" not in spec      # written before contact laws: their interface
    if air is not None or legacy:
        air = _check_keys("air", {} if air is None else air,
                          [f.name for f in dataclasses.fields(AirParameters)])
        air = AirParameters(**({**LEGACY_AIR, **air} if legacy else air))
    contact = (ContactParameters(law="hard", roughness=air.roughness or HARD_WALL_GAP)
               if legacy else spec.get("contact"))
    if contact is not None and not isinstance(contact, ContactParameters):
        if not isinstance(contact, dict):
            raise ParameterError(f"contact must be a JSON object, got {contact!r}")
        contact = ContactParameters.from_dict(contact)
    return {"head": HeadDesign(**_tuples(head)), "air": air, "contact": contact,
            "infinitely_wide": spec["infinitely_wide"], "nx": spec["nx"], "ny": spec["ny"]}


def _check_keys(name: str, value: object, allowed, required=()) -> dict:
    """``value``, a JSON object whose keys are among ``allowed`` and include
    ``required``."""
    if not isinstance(value, dict):
        raise ParameterError(f"{name} must be a JSON object, got {value!r}")
    unknown = sorted(set(value) - set(allowed))
    missing = [key for key in required if key not in value]
    if unknown or missing:
        raise ParameterError(f"{name}: " + "; ".join(
            part for part in (unknown and f"unknown key(s) {', '.join(unknown)}",
                              missing and f"missing key(s) {', '.join(missing)}") if part))
    return value


def _tuples(fields: dict) -> dict:
    """The fields with JSON lists back as the tuples a design holds."""
    return {key: tuple(value) if key in _TUPLE_FIELDS and isinstance(value, list) else value
            for key, value in fields.items()}


def head_of_point(setup: BearingStudy, point: Mapping) -> HeadDesign:
    """The point's head design: the base head with the point's head variables, checked
    whole (:func:`~gyroshell.bearing.head_config.check_design`: a flat head with both
    wraps 0 is refused here, even when the base head left them to the points); a variable
    the head's kind has not is refused, naming it. ``wrap``
    (:data:`~gyroshell.studies.points.BOTH_WRAPS`) sets ``wrap_in`` and ``wrap_out``."""
    changes = {k: v for k, v in point.items() if k in HEAD_VARIABLES}
    kind = setup.head.kind
    if BOTH_WRAPS in changes:
        both = [name for name in ("wrap_in", "wrap_out") if name in changes]
        if both:
            raise ParameterError(f"{BOTH_WRAPS} sets both wrap_in and wrap_out: vary "
                                 f"{BOTH_WRAPS} or {' and '.join(both)}, not both")
        if "wrap_in" not in kind_fields(kind):
            raise ParameterError(f"{BOTH_WRAPS} (wrap_in and wrap_out) is not a parameter "
                                 f"of a {kind} head")
        wrap = changes.pop(BOTH_WRAPS)
        changes.update(wrap_in=wrap, wrap_out=wrap)
    for name in changes:
        if name not in kind_fields(kind):
            raise ParameterError(f"{name} is not a parameter of a {kind} head")
    return setup.head.replace(**changes)


def head_value(design: HeadDesign, name: str) -> float:
    """The value of the head variable ``name`` (:data:`HEAD_VARIABLES`) the head of
    ``design`` is built with: 0 for a wrap or corner radius not given, the default wrap
    angle, NaN for a gap a single module has not; ``wrap``: both wraps, NaN if they
    differ."""
    if name == BOTH_WRAPS:
        wraps = head_value(design, "wrap_in"), head_value(design, "wrap_out")
        return wraps[0] if wraps[0] == wraps[1] else math.nan
    value = getattr(design, name)
    if value is not None:
        return value
    return {"wrap_in": 0.0, "wrap_out": 0.0, "corner_radius": 0.0,
            "wrap_angle": DEFAULT_WRAP_ANGLE}.get(name, math.nan)


def point_model(base: dict, velocity: float, point: dict, setup: BearingStudy):
    """The point's :class:`~gyroshell.bearing.model.BearingModel` (its tape, speed of
    either sign, head and grid), refused as the single ``gyroshell bearing`` refuses it: a
    speed of 0, a grid that does not fit in memory
    (:func:`gyroshell.bearing.budget.check_steady`), a speed at or above the string speed.

    Raises
    ------
    ParameterError
        What the model refuses (a speed of 0 in the study's own words: it has no dry tape).
    """
    from ..bearing import BearingModel

    tape = {k: v for k, v in point.items() if k not in BEARING_VARIABLES}
    params, v = parameters_of(TapeParameters(**base), velocity, tape, signed=True)
    if v == 0.0:
        raise ParameterError("velocity must be nonzero for an air bearing (either sign: "
                             "the tape running along +x or -x, e.g. 4 or -4 m/s), got 0")
    design = head_of_point(setup, point)
    air, contact = interface_of_point(setup, point)
    return BearingModel(params, air, velocity=v, head=design.head(),
                        infinitely_wide=setup.infinitely_wide, nx=setup.nx, ny=setup.ny,
                        contact=contact, **design.model_options())


def interface_of_point(setup: BearingStudy, point: Mapping):
    """(AirParameters, ContactParameters or None) of the point: the setup's, with the
    point's interface variables (:data:`~gyroshell.studies.points.INTERFACE_VARIABLES`;
    ``contact`` names the law, which starts from its own defaults)."""
    air = setup.air
    film = {k: point[k] for k in ("rarefaction", "flow_factors") if k in point}
    if film:
        air = (AirParameters() if air is None else air).replace(**film)
    fields = {k: point[k] for k in INTERFACE_VARIABLES
              if k in point and k not in ("rarefaction", "flow_factors", "contact")}
    contact = setup.contact
    if "contact" in point or fields:
        if contact is None:
            from ..bearing.model import default_contact

            contact = default_contact(AirParameters() if air is None else air)
        if "contact" in point:
            contact = contact.replace(law=point["contact"])
        contact = contact.replace(**fields) if fields else contact
    return air, contact


def interface_value(setup: BearingStudy | None, name: str):
    """The value of the interface variable ``name`` a point that does not set it runs
    with (the setup's, or the default)."""
    air = AirParameters() if setup is None or setup.air is None else setup.air
    if name in ("rarefaction", "flow_factors"):
        return getattr(air, name)
    contact = None if setup is None else setup.contact
    if contact is None:
        from ..bearing.model import default_contact

        contact = default_contact(air)
    if name == "contact":
        return contact.law
    value = getattr(contact, name)
    return math.nan if value is None else value


def bearing_row(base: dict, velocity: float, point: dict, setup: BearingStudy) -> dict:
    """Solve the point's steady bearing; its columns (see the module docstring). A solve
    that fails carries the hint the single command gives
    (:func:`gyroshell.bearing.corners.arc_contact_hint`)."""
    from ..bearing.corners import arc_contact_hint
    from ..bearing.steady import solve_steady
    from ..core.errors import ConvergenceError

    model = point_model(base, velocity, point, setup)
    try:
        sol = solve_steady(model)
    except ConvergenceError as exc:
        raise ConvergenceError(f"{exc}{arc_contact_hint(model)}") from None
    return readings_row(sol, list(setup.columns))


def readings_row(sol, columns: list[str]) -> dict:
    """A solution's readings as the study's columns."""
    row = {"central_spacing": sol.central_spacing, "minimum_spacing": sol.minimum_spacing,
           "contact_force": sol.contact_force, "viscous_drag": sol.viscous_drag,
           "friction_drag": sol.friction_drag, "drag": sol.drag,
           "tension_rise": sol.tension_rise, "tension_ratio": sol.tension_ratio,
           "newton_iterations": float(sol.info.iterations)}
    for i, line in enumerate(sol.transducer_lines, start=1):
        row[f"transducer_{i}_min_spacing"] = line.minimum
        row[f"transducer_{i}_mean_spacing"] = line.mean
    tents = [tent for tent in sol.tents if tent.side == "land"]
    forces = sol.corner_forces
    for j, (tent, force) in enumerate(zip(tents, forces, strict=True), start=1):
        row[f"corner_{j}_tent_height"] = math.nan if tent.height is None else tent.height
        row[f"corner_{j}_tent_x"] = math.nan if tent.x is None else tent.x
        row[f"corner_{j}_force"] = force.force
    if set(row) != set(columns):
        raise ParameterError(f"this point's head has {len(forces)} corners and "
                             f"{len(sol.transducer_lines)} transducer lines, not those of "
                             "the study's base head")
    return {c: float(row[c]) for c in columns}


def number_range(column: str) -> tuple[float, str]:
    """(lowest value, unit) of a bearing column (see :data:`NUMBER_RANGES`)."""
    if column.endswith("_spacing"):
        return NUMBER_RANGES["spacing"]
    for suffix in ("tent_height", "tent_x", "force"):
        if column.startswith("corner_") and column.endswith(suffix):
            return NUMBER_RANGES[suffix]
    return NUMBER_RANGES[column]
