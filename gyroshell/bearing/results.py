"""The bearing's results on the result protocol (:mod:`gyroshell.results.base`).

:class:`BearingSolution` (kind ``"bearing"``) is a steady flying state,
:class:`BearingTransient` (kind ``"bearing_transient"``) the record of a march. Both save
to NetCDF with ``save(path)`` and come back through :func:`gyroshell.results.base.read`
equal to the saved ones: the nodal fields are stored on (x, y) with their coordinates
(uniform or graded), and everything that rebuilds the :class:`~.model.BearingModel`
(tape parameters, air, speed, wrap, span, grid counts and grading) as attributes; reading
rebuilds the model from them and checks its nodes against the stored coordinates.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..core import validation
from ..core.errors import ParameterError
from ..results import layout
from ..results.base import Result, dataset, from_json, params_from
from . import readings
from .air import LEGACY_AIR, AirParameters
from .contact import ContactParameters
from .head import FlatHead, head_from_dict
from .mesh import Grading
from .model import BearingGridWarning, BearingModel

#: Summary entries not stored in a file's ``summary`` attribute (lists, kept in ``info``).
_NOT_STORED = ("newton_step_norms",)
#: The nodal fields of a state stored on (x, y) and read back.
_STATE = ("spacing", "pressure", "departure", "contact")
#: The node coordinates of a file, m.
_COORDS = {"x": layout.X, "y": layout.Variable(("y",))}
#: Stored node coordinates must match the rebuilt grid's to this fraction of its extent.
COORDINATE_TOLERANCE = 1e-12


#: The keys of a stored grading (:class:`.mesh.Grading`'s fields).
_GRADING_KEYS = tuple(f.name for f in dataclasses.fields(Grading))


@dataclass
class NewtonInfo:
    """What a Newton solve did: iterations, step and residual norms per iteration, and more.

    The number of nodes in contact per iteration, the wall time (s), the pseudo-time steps
    taken (dimensionless, :mod:`.pseudo_time`; empty if Newton reached the state
    directly), the continuation path (speeds in m/s, empty if none was needed), over
    rounded corners touched at a point
    (:func:`gyroshell.bearing.corners.solve_adapting_contacts`) the passes that adapted
    the contacts and how far, in cells, they moved on the last (0 and 0.0 where none were
    adapted), and under a smooth contact law the scales of the law's continuation."""

    iterations: int = 0
    step_norms: list = field(default_factory=list)
    residual_norms: list = field(default_factory=list)
    contact_nodes: list = field(default_factory=list)
    seconds: float = 0.0
    continuation: list = field(default_factory=list)
    pseudo_time: list = field(default_factory=list)
    contact_passes: int = 0
    contact_move: float = 0.0
    #: the smooth contact law's scales s of the continuation from the hard wall
    #: (:mod:`.smooth`; empty if none was needed)
    law_scales: list = field(default_factory=list)
    #: Newton iterations of a 2-D tape's start on coarser grids and of the infinitely wide
    #: tape (:func:`.smooth.coarse_start`), not in ``iterations`` (the model's own grid's)
    start_iterations: int = 0


@dataclass(frozen=True)
class BearingSolution(Result, kind="bearing"):
    """A steady flying state.

    Attributes
    ----------
    model : BearingModel
    u : numpy.ndarray
        Departure from the dry wrapped configuration at the tape unknowns, m.
    p : numpy.ndarray
        Film pressure at the film-interior nodes, Pa.
    contact : numpy.ndarray
        Contact force at the tape unknowns, N (N/m per unit width if infinitely wide).
    info : NewtonInfo
    """

    summary_units = {"minimum_x": "m", "minimum_y": "m", "central_pressure": "Pa",
                     "wrap_pressure": "Pa", "air_force": "N", "contact_force": "N",
                     "seconds": "s", "viscosity": "Pa*s", "ambient_pressure": "Pa",
                     "mean_free_path": "m", "roughness": "m", "length": "m",
                     "finest_x_spacing": "m", "finest_y_spacing": "m",
                     "wrap_angle_degrees": "deg", "viscous_drag": "N", "friction_drag": "N",
                     "drag": "N"}
    headline = ("minimum_spacing", "central_spacing", "air_force", "contact_force",
                "velocity", "wrap_angle", "tension_rise", "drag", "nx", "ny", "unknowns",
                "newton_iterations")

    def summary_unit(self, name: str) -> str | None:
        """As :meth:`Result.summary_unit`; forces per unit width (N/m) if infinitely wide."""
        unit = super().summary_unit(name)
        return "N/m" if unit == "N" and self.model.infinitely_wide else unit

    model: BearingModel
    u: np.ndarray
    p: np.ndarray
    contact: np.ndarray
    info: NewtonInfo

    #: The file: the state on (x, y), the air, model settings and Newton record.
    file_layout = layout.Layout(
        {**{name: layout.Variable(("x", "y")) for name in _STATE}, **_COORDS},
        {"air": layout.json_object("air"), "model": layout.json_object("model"),
         "info": layout.INFO},
        check=lambda ds: _check_attrs(ds))

    @property
    def spacing(self) -> np.ndarray:
        """h on every node, shape (nx + 1, nc), m."""
        return self.model.spacing_field(self.u)

    @property
    def pressure(self) -> np.ndarray:
        """p on every node, shape (nx + 1, nc), Pa."""
        return self.model.pressure_field(self.p)

    @property
    def x(self) -> np.ndarray:
        """Node abscissae measured from the middle of the wrap, m (tape moves along +x)."""
        return self.model.x - 0.5 * self.model.length

    @property
    def y(self) -> np.ndarray | None:
        """Node ordinates across the width, m (None if infinitely wide)."""
        return self.model.y

    def _at_centre_x(self, field: np.ndarray) -> np.ndarray:
        return np.array([np.interp(0.0, self.x, field[:, j]) for j in range(field.shape[1])])

    def _at_centre_y(self, row: np.ndarray) -> float:
        if self.model.infinitely_wide:
            return float(row[0])
        return float(np.interp(0.5 * self.model.params.width, self.model.y, row))

    @property
    def central_spacing(self) -> float:
        """h in the middle of the wrap and of the width, m."""
        return self._at_centre_y(self._at_centre_x(self.spacing))

    @property
    def central_pressure(self) -> float:
        """p − p_a in the middle of the wrap and of the width, Pa."""
        return self._at_centre_y(self._at_centre_x(self.pressure)) \
            - self.model.air.ambient_pressure

    @property
    def cross_width_spacing(self) -> np.ndarray:
        """h across the width in the middle of the wrap, m (one value if infinitely wide)."""
        return self._at_centre_x(self.spacing)

    @property
    def minimum_spacing(self) -> float:
        """Smallest nodal spacing, m."""
        return float(self.spacing.min())

    @property
    def minimum_location(self) -> tuple[float, float | None]:
        """(x, y) of the smallest spacing, m: x from the middle of the wrap (> 0 towards the
        exit), y across the width (None if infinitely wide)."""
        i, j = np.unravel_index(np.argmin(self.spacing), self.spacing.shape)
        return float(self.x[i]), (None if self.model.infinitely_wide
                                  else float(self.model.y[j]))

    @property
    def air_force(self) -> float:
        """∫ (p − p_a) dA, N (N/m per unit width if infinitely wide)."""
        return float(np.sum(self.model.pressure_load @ (self.p - self.model.air.ambient_pressure)))

    @property
    def contact_force(self) -> float:
        """Total contact force of the head on the tape, N (N/m if infinitely wide)."""
        return float(self.contact.sum())

    @property
    def contact_nodes(self) -> int:
        """Number of tape nodes in contact."""
        return int(np.count_nonzero(self.contact))

    @property
    def in_contact(self) -> bool:
        """Whether the tape touches the head somewhere: nodes in contact, or a spacing at
        or below the roughness σ (then :attr:`minimum_spacing` is σ, not a flying height)."""
        return self.contact_nodes > 0 or self.minimum_spacing <= self.model.air.roughness

    @property
    def range_warnings(self) -> list[str]:
        """One line per model used outside its range here: the rarefaction model beyond
        its Knudsen numbers, the hard wall below 3 gaps (:mod:`.validity`)."""
        from .validity import range_warnings

        return range_warnings(self)

    def magnetic_spacings(self, recession: float) -> list[dict]:
        """Each transducer line's magnetic spacing, m: its spacing (to the mean plane of
        the tape's summits) plus ``recession``, the head's recession and overcoats (m,
        >= 0): the centre's, the minimum's and the mean's."""
        recession = validation.nonnegative("recession", recession, "m")
        return [{"x": line.x, "magnetic_spacing": line.centre + recession,
                 "magnetic_spacing_minimum": line.minimum + recession,
                 "magnetic_spacing_mean": line.mean + recession}
                for line in self.transducer_lines]

    # ----- what the head designer reads (gyroshell.bearing.readings) -------------------------
    @cached_property
    def _layout(self) -> dict:
        return _head_layout(self.model)

    @cached_property
    def transducer_lines(self) -> tuple[readings.TransducerLine, ...]:
        """The spacing along each of the head's transducer lines x = x_t across the width
        (cubic interpolation along x, exact at nodes), with its centre value, minimum and
        trapezoid mean per line (:func:`gyroshell.bearing.readings.transducer_lines`)."""
        lay = self._layout
        return readings.transducer_lines(self.x, self.y, self.spacing, lay["transducers"],
                                         lay["corners"])

    @cached_property
    def tents(self) -> tuple[readings.Tent, ...]:
        """The tents next to each corner on its land and span sides: height (m) and x (m)
        of the spacing's local maximum along the middle of the width, and the largest
        across the width; None where there is none
        (:func:`gyroshell.bearing.readings.tents` defines them)."""
        lay = self._layout
        return readings.tents(self.x, self.y, self.spacing, lay["corners"], lay["lands"],
                              lay["transducers"])

    @cached_property
    def _contact_shares(self):
        lay, m = self._layout, self.model
        return readings.contact_shares(self.x, _nodal(m, self.contact), m.film.cell_area,
                                       lay["corners"], lay["lands"], lay["zones"])

    @property
    def corner_forces(self) -> tuple[readings.ContactShare, ...]:
        """The contact of each corner: the nodes within its zone, their force (N; N/m if
        infinitely wide), peak contact pressure (Pa), force centroid (m) and node count.
        The zone reaches from the corner's x the longer of its wrapped arc r_c θ_c and, on
        a flat head, half its arc r_c φ / 2 (land to flank), plus
        :data:`~gyroshell.bearing.readings.CORNER_ZONE_BENDING_LENGTHS` bending lengths
        √(D/(T − ρV²))."""
        return self._contact_shares[0]

    @property
    def land_forces(self) -> tuple[readings.ContactShare, ...]:
        """The contact of each land outside the corner zones (as :attr:`corner_forces`);
        corner and land forces sum to :attr:`contact_force`."""
        return self._contact_shares[1]

    @property
    def contact_pressure(self) -> np.ndarray:
        """The contact-pressure distribution, Pa, on every node, shape (nx + 1, nc): the
        nodal contact force over the node's control area (0 at the pinned span ends)."""
        m = self.model
        return readings.contact_pressure(_nodal(m, self.contact), m.film.cell_area)

    @cached_property
    def shear_stress(self) -> np.ndarray:
        """The air's shear stress on the tape, Pa, on every node, shape (nx + 1, nc);
        > 0 resists the tape's motion, whichever way it runs: sign(V) (μV/(h + 2λ_e) +
        (h/2) ∂p/∂x) with the rarefaction model's slip length, h the gap the film sees
        (under the asperity law the mean gap)
        (:func:`gyroshell.bearing.readings.shear_stress`); 0 for a dry model (no air
        film)."""
        m = self.model
        if m.dry:
            return np.zeros_like(self.spacing)
        if m.smooth_contact:
            h = m.film_spacing(self.spacing)[0]
        else:
            h = np.maximum(self.spacing, _FILM_FLOOR * m.air.roughness)  # as the film does
        return readings.shear_stress(self.x, h, self.pressure, m.velocity, m.air)

    @cached_property
    def _drag(self) -> readings.Drag:
        m = self.model
        return readings.drag(readings.integral(self.shear_stress, m.film.cell_area),
                             self.contact_force, self._layout["friction"], m.params.tension,
                             None if m.infinitely_wide else m.params.width)

    @property
    def viscous_drag(self) -> float:
        """∫ τ dA over the film (the whole domain: head and spans), N (N/m if infinitely
        wide)."""
        return self._drag.viscous

    @property
    def friction_drag(self) -> float:
        """The head's friction coefficient μ_f times the total contact force, N (N/m)."""
        return self._drag.friction

    @property
    def drag(self) -> float:
        """Viscous plus friction drag, N (N/m if infinitely wide)."""
        return self._drag.total

    @property
    def tension_rise(self) -> float:
        """The drag per unit width, N/m: the rise of the tension across the head to first
        order (the model keeps T uniform along the tape; see :mod:`.readings`)."""
        return self._drag.tension_rise

    @property
    def tension_ratio(self) -> float:
        """1 + :attr:`tension_rise` / T: outgoing over incoming tension to first order
        (friction alone over a wrap θ: 1 + μ_f θ (T − ρV²)/T, the capstan law e^{μ_f θ}
        of the moving tape's T − ρV² to first order)."""
        return self._drag.tension_ratio

    def readings(self) -> dict:
        """The designer's readings as plain JSON values (part of :meth:`summary`)."""
        return {"transducer_lines": [line.as_dict() for line in self.transducer_lines],
                "tents": [tent.as_dict() for tent in self.tents],
                "corner_forces": [share.as_dict() for share in self.corner_forces],
                "land_forces": [share.as_dict() for share in self.land_forces],
                "viscous_drag": self.viscous_drag, "friction_drag": self.friction_drag,
                "drag": self.drag, "tension_rise": self.tension_rise,
                "tension_ratio": self.tension_ratio, "friction": self._layout["friction"]}

    def summary(self) -> dict:
        """The scalar outputs (SI; the wrap angle also in degrees) and the designer's
        readings (:meth:`readings`): what ``gyroshell bearing --json`` prints."""
        m = self.model
        x_min, y_min = self.minimum_location
        return {
            "central_spacing": self.central_spacing,
            "minimum_spacing": self.minimum_spacing,
            "minimum_x": x_min,
            "minimum_y": y_min,
            "central_pressure": self.central_pressure,
            "wrap_pressure": (m.effective_tension() / m.head_radius if m.cylindrical
                              else None),
            "air_force": self.air_force,
            "contact_force": self.contact_force,
            "contact_nodes": self.contact_nodes,
            "in_contact": self.in_contact,
            "newton_iterations": self.info.iterations,
            "newton_step_norms": list(self.info.step_norms),
            "continuation_speeds": list(self.info.continuation),
            "pseudo_time_steps": list(self.info.pseudo_time),
            "seconds": self.info.seconds,
            "velocity": m.velocity,
            "wrap_angle": m.wrap_angle,
            "infinitely_wide": m.infinitely_wide,
            "width": None if m.infinitely_wide else m.params.width,
            "tension": m.params.tension,
            "radius": m.params.radius,
            "viscosity": m.air.viscosity,
            "ambient_pressure": m.air.ambient_pressure,
            "mean_free_path": m.air.mean_free_path,
            "compressible": m.air.compressible,
            "roughness": m.air.roughness,
            "rarefaction": m.air.rarefaction,
            "flow_factors": m.air.flow_factors,
            "contact_law": m.contact.law,
            "contact_parameters": m.contact.to_dict(),
            "warnings": self.range_warnings,
            "length": m.length,
            "nx": m.nx,
            "ny": m.ny,
            "graded": m.graded,
            "finest_x_spacing": float(np.diff(m.x).min()),
            "finest_y_spacing": None if m.infinitely_wide else float(np.diff(m.y).min()),
            "unknowns": m.unknowns,
            "wrap_angle_degrees": math.degrees(m.wrap_angle),
            **self.readings(),
        }

    # ----- the result protocol -----------------------------------------------------------
    def to_xarray(self, *, params=None):
        """The steady state as an :class:`xarray.Dataset`: ``spacing`` and ``departure``
        (m), ``pressure`` (Pa) and ``contact`` (N, N/m if infinitely wide) on dimensions
        (x, y), x from the middle of the wrap (m); the summary, air and model settings as
        attributes. ``params`` is ignored: the model carries its tape."""
        data = _state_variables(self)
        summary = {k: v for k, v in self.summary().items() if k not in _NOT_STORED}
        return dataset(data, _node_coords(self.model), self.kind, params=self.model.params,
                       info=dataclasses.asdict(self.info), air=dataclasses.asdict(self.model.air),
                       model=_settings(self.model), summary=summary)

    @classmethod
    def from_xarray(cls, ds) -> BearingSolution:
        """The state stored by :meth:`to_xarray` (or by the previous release's
        ``gyroshell.bearing.storage.save``): the model is rebuilt from the stored settings
        and checked against the stored node coordinates."""
        model = _model_from(ds)
        return _state_from(ds, model, _info_from(ds))

    def to_frame(self):
        """The nodal fields as a table: x (from the middle of the wrap) and y (0 if
        infinitely wide), m, the spacing h, m, the pressure p, the air's shear stress on
        the tape and the contact pressure, Pa."""
        import pandas as pd

        m = self.model
        y = np.zeros(1) if m.infinitely_wide else m.y
        X, Y = np.meshgrid(self.x, y, indexing="ij")
        return pd.DataFrame({"x": X.ravel(), "y": Y.ravel(),
                             "spacing": self.spacing.ravel(),
                             "pressure": self.pressure.ravel(),
                             "shear_stress": self.shear_stress.ravel(),
                             "contact_pressure": self.contact_pressure.ravel()})

    def plot(self, ax=None):
        """The spacing along the middle of the width with the pressure on a twin axis
        (:func:`gyroshell.bearing.plots.centreline`); returns the Axes."""
        from .plots import centreline

        return centreline(self, ax)


@dataclass(frozen=True)
class BearingTransient(Result, kind="bearing_transient"):
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

    summary_units = {"end_time": "s", "smallest_minimum_spacing": "m",
                     "largest_central_spacing": "m", "smallest_central_spacing": "m",
                     "largest_contact_force": "N", "final_central_spacing": "m",
                     "final_minimum_spacing": "m"}

    def summary_unit(self, name: str) -> str | None:
        """As :meth:`Result.summary_unit`; forces per unit width (N/m) if infinitely wide."""
        unit = super().summary_unit(name)
        return "N/m" if unit == "N" and self.final.model.infinitely_wide else unit

    t: np.ndarray
    central_spacing: np.ndarray
    minimum_spacing: np.ndarray
    contact_force: np.ndarray
    tension: np.ndarray
    x: np.ndarray
    centreline: np.ndarray
    newton_iterations: np.ndarray
    final: BearingSolution

    #: The file: the series on t, the centre lines on (t, x), the final state as
    #: ``final_*`` on (x, y), the air, model settings and the final Newton record.
    file_layout = layout.Layout(
        {**{f"final_{name}": layout.Variable(("x", "y")) for name in _STATE}, **_COORDS,
         **{name: layout.Variable(("t",)) for name in ("tension", "central_spacing",
                                                       "minimum_spacing", "contact_force",
                                                       "newton_iterations")},
         "t": layout.Variable(("t",), check=layout.monotonic("t")),
         "centreline": layout.Variable(("t", "x")), "x_record": layout.Variable(("x",))},
        {"air": layout.json_object("air"), "model": layout.json_object("model"),
         "info": layout.INFO},
        check=lambda ds: _check_attrs(ds))

    def summary(self) -> dict:
        """Headline numbers (SI): recorded times, the end time, the extremes of the
        spacings and of the contact force, the Newton iterations in all, and the final
        central and minimum spacings."""
        return {"records": int(len(self.t)), "end_time": float(self.t[-1]),
                "smallest_minimum_spacing": float(self.minimum_spacing.min()),
                "largest_central_spacing": float(self.central_spacing.max()),
                "smallest_central_spacing": float(self.central_spacing.min()),
                "largest_contact_force": float(self.contact_force.max()),
                "newton_iterations": int(self.newton_iterations.sum()),
                "final_central_spacing": self.final.central_spacing,
                "final_minimum_spacing": self.final.minimum_spacing,
                "velocity": self.final.model.velocity,
                "wrap_angle": self.final.model.wrap_angle,
                "infinitely_wide": self.final.model.infinitely_wide}

    def to_frame(self):
        """The time series as a table: t (s), tension (N/m), central and minimum spacing
        (m), contact force (N, N/m if infinitely wide) and Newton iterations per step."""
        import pandas as pd

        return pd.DataFrame({name: getattr(self, name) for name in _SERIES})

    def to_xarray(self, *, params=None):
        """The record as an :class:`xarray.Dataset`: the series on dimension ``t`` (s), the
        centre-line spacing on (t, x), the final state as ``final_*`` fields on (x, y), and
        the model, air and final Newton record as attributes. ``params`` is ignored: the
        model carries its tape."""
        m = self.final.model
        data = {name: (("t",), getattr(self, name), {"units": _SERIES[name]})
                for name in _SERIES if name != "t"}
        data["centreline"] = (("t", "x"), self.centreline,
                              {"units": "m", "long_name": "spacing along the middle"})
        data.update(_state_variables(self.final, prefix=_FINAL))
        coords = _node_coords(m)
        coords["t"] = ("t", self.t, {"units": "s"})
        coords["x_record"] = ("x", self.x, {"units": "m",
                                            "long_name": "abscissae of the record"})
        return dataset(data, coords, self.kind, params=m.params,
                       info=dataclasses.asdict(self.final.info),
                       air=dataclasses.asdict(m.air), model=_settings(m))

    @classmethod
    def from_xarray(cls, ds) -> BearingTransient:
        """The record stored by :meth:`to_xarray`."""
        model = _model_from(ds, prefix=_FINAL)
        final = _state_from(ds, model, _info_from(ds), prefix=_FINAL)
        records = ds.sizes.get("t")
        for name in [*_SERIES, "x_record", "centreline"]:
            if name not in ds.variables or ds[name].shape[:1] != (
                    ds.sizes["x"] if name == "x_record" else records,):
                raise ParameterError(f"the file has no variable {name!r} of the record's "
                                     "length")
        series = {name: ds[name].values for name in _SERIES if name != "t"}
        return cls(t=ds["t"].values, x=ds["x_record"].values,
                   centreline=ds["centreline"].values, final=final, **series)

    def plot(self, ax=None):
        """Central and minimum spacing against time
        (:func:`gyroshell.bearing.plots.transient_spacing`); returns the Axes."""
        from .plots import transient_spacing

        return transient_spacing(self, ax)


#: Spacings below this fraction of the roughness are floored there (as in the film).
_FILM_FLOOR = 0.5


def _head_layout(model: BearingModel) -> dict:
    """The head's corners, lands, transducers (m, head coordinates), friction coefficient
    and each corner's contact zone half-width (m: its wrapped arc r_c θ_c, or on a flat
    head half its arc r_c φ / 2 if longer, plus
    :data:`~gyroshell.bearing.readings.CORNER_ZONE_BENDING_LENGTHS` bending lengths
    √(D/(T − ρV²)); a cylinder's corners, its tangent points, get the bending lengths
    only: its wrapped arc is its land)."""
    head, radius = model.head, model.head_radius
    corners, lands = tuple(head.corners(radius)), tuple(head.lands(radius))
    arcs = tuple(r * t for r, t in zip(head.corner_radii(radius), head.corner_turns(radius),
                                       strict=True))
    if model.cylindrical:                             # its wrapped arc is its land
        arcs = (0.0,) * len(corners)
    elif isinstance(head, FlatHead):   # a rounded corner's x is its arc's middle, and the
        # tape touches it anywhere on the arc (near its land end at speed): half the arc
        # from the land to the flank, r_c φ / 2, is in the zone
        arcs = tuple(max(a, 0.5 * r * head.flank_angle)
                     for a, r in zip(arcs, head.corner_radii(radius), strict=True))
    bending = model.bending_length
    zones = tuple(readings.CORNER_ZONE_BENDING_LENGTHS * bending + a for a in arcs)
    return {"corners": corners, "lands": lands, "transducers": tuple(head.transducers),
            "friction": float(head.friction), "zones": zones}


#: The time series of a :class:`BearingTransient` and their units.
_SERIES = {"t": "s", "tension": "N/m", "central_spacing": "m", "minimum_spacing": "m",
           "contact_force": "N", "newton_iterations": "1"}
#: Prefix of the final state's variables in a transient's file.
_FINAL = "final_"


# ----- storage helpers shared by both kinds ----------------------------------------------
def _node_coords(model: BearingModel) -> dict:
    """x (from the middle of the wrap) and y (a single 0 if infinitely wide), m."""
    y = np.zeros(1) if model.infinitely_wide else model.y
    return {"x": ("x", model.x - 0.5 * model.length,
                  {"units": "m", "long_name": "from the middle of the wrap"}),
            "y": ("y", y, {"units": "m", "long_name": "across the tape"})}


def _nodal(model: BearingModel, values: np.ndarray) -> np.ndarray:
    """Values at the tape unknowns on every node (0 at the span ends), shape (nx + 1, nc)."""
    out = np.zeros((model.nx + 1, model.nc))
    out[1:-1, :] = values.reshape(model.nx - 1, model.nc)
    return out


def _state_variables(sol: BearingSolution, prefix: str = "") -> dict:
    """The Dataset variables of a steady state, their names prefixed by ``prefix``."""
    m = sol.model
    return {f"{prefix}spacing": (("x", "y"), sol.spacing, {"units": "m"}),
            f"{prefix}pressure": (("x", "y"), sol.pressure, {"units": "Pa"}),
            f"{prefix}departure": (("x", "y"), _nodal(m, sol.u),
                                   {"units": "m",
                                    "long_name": "from the dry wrapped configuration"}),
            f"{prefix}contact": (("x", "y"), _nodal(m, sol.contact), {"units": "N"}),
            # derived (recomputed on reading): for other tools that open the file
            f"{prefix}shear_stress": (("x", "y"), sol.shear_stress,
                                      {"units": "Pa", "long_name": "air shear on the tape"}),
            f"{prefix}contact_pressure": (("x", "y"), sol.contact_pressure,
                                          {"units": "Pa"})}


def _state_from(ds, model: BearingModel, info: NewtonInfo,
                prefix: str = "") -> BearingSolution:
    """The steady state stored by :func:`_state_variables`."""
    U, P, C = (ds[f"{prefix}{k}"].values for k in ("departure", "pressure", "contact"))
    return BearingSolution(model, U[1:-1, :].ravel(), P[model.film.interior],
                           C[1:-1, :].ravel(), info)


def _settings(model: BearingModel) -> dict:
    """The keyword arguments that rebuild ``model`` with its tape and air (the rounded
    corners' contact points, which place nodes, only when there are any)."""
    out = {"velocity": model.velocity, "wrap_angle": model.wrap_angle,
           "infinitely_wide": model.infinitely_wide, "span": model.span, "nx": model.nx,
           "ny": model.ny, "grading": model.grading.as_dict(),
           "head": model.head.as_dict(), "dry": model.dry}
    if model.corner_contacts:
        out["corner_contacts"] = list(model.corner_contacts)
    if model.arc_contact != "auto":
        out["arc_contact"] = model.arc_contact
    out["contact"] = model.contact.to_dict()
    return out


#: The keys of a file's ``model`` attribute (``grading``, ``head``, ``dry`` and
#: ``contact`` may be absent: older files, whose head is the cylinder of ``wrap_angle``,
#: flying, its contact the hard wall at the air's roughness).

_SETTINGS = ("velocity", "wrap_angle", "infinitely_wide", "span", "nx", "ny")
_OPTIONAL_SETTINGS = ("grading", "head", "dry", "corner_contacts", "arc_contact", "contact")


def _stored_dict(attrs, name: str, allowed, required=()) -> dict:
    """The JSON object stored in the attribute ``name``, checked: an object whose keys are
    among ``allowed`` and include ``required``."""
    import json

    text = attrs.get(name)
    if not isinstance(text, str):
        raise ParameterError(f"the file's {name!r} attribute must be JSON text, got "
                             f"{type(text).__name__}")
    try:
        data = from_json(text)
    except json.JSONDecodeError as exc:
        raise ParameterError(f"the file's {name!r} attribute is not valid JSON ({exc})"
                             ) from None
    if not isinstance(data, dict):
        raise ParameterError(f"the file's {name!r} attribute must be a JSON object, got "
                             f"{type(data).__name__}")
    extra, missing = set(data) - set(allowed), set(required) - set(data)
    if extra or missing:
        raise ParameterError(
            f"the file's {name!r} attribute has " + "; ".join(
                part for part in (extra and f"unknown keys {sorted(extra)}",
                                  missing and f"missing keys {sorted(missing)}") if part))
    return data


def _check_stored_sizes(ds, nx, ny, names) -> None:
    """The file's dimensions and variables agree with the stored grid counts, before the
    model is rebuilt (a forged count must not allocate anything)."""
    nx = validation.integer("the stored nx", nx, low=1)
    ny = validation.integer("the stored ny", ny, low=1, optional=True)
    expected = {"x": nx + 1, "y": 1 if ny is None else ny + 1}
    for dim, size in expected.items():
        if ds.sizes.get(dim) != size:
            raise ParameterError(f"the file's {dim} dimension has {ds.sizes.get(dim)} nodes, "
                                 f"but its grid settings say {size}")
    for name in names:
        if name not in ds.variables or ds[name].dims[-2:] != ("x", "y"):
            raise ParameterError(f"the file has no variable {name!r} on (x, y)")


def _model_from(ds, prefix: str = "") -> BearingModel:
    """The model rebuilt from a file's attributes, checked against its node coordinates."""
    a = ds.attrs
    settings = _stored_dict(a, "model", (*_SETTINGS, *_OPTIONAL_SETTINGS), _SETTINGS)
    _check_stored_sizes(ds, settings["nx"], settings["ny"],
                        [f"{prefix}{k}" for k in ("departure", "pressure", "contact")])
    grading = settings.get("grading", {})   # files written before graded grids: uniform
    if not isinstance(grading, dict) or not set(grading) <= set(_GRADING_KEYS):
        raise ParameterError(f"the file's grading must be an object with keys among "
                             f"{sorted(_GRADING_KEYS)}, got {grading!r}")
    settings["grading"] = Grading(**grading)
    if "head" in settings:      # the head rebuilds the wrap
        settings["head"] = head_from_dict(settings["head"])
        del settings["wrap_angle"]
    air = {**LEGACY_AIR, **_stored_dict(a, "air",
                                        [f.name for f in dataclasses.fields(AirParameters)])}
    if "contact" in settings:
        if not isinstance(settings["contact"], dict):
            raise ParameterError(f"the file's contact must be an object, got "
                                 f"{settings['contact']!r}")
        settings["contact"] = ContactParameters.from_dict(settings["contact"])
    else:     # written before contact laws: the hard wall at the stored roughness
        settings["contact"] = ContactParameters(law="hard", roughness=air.get("roughness"))
    with warnings.catch_warnings():   # the grid was the saver's choice: no warning on load
        warnings.simplefilter("ignore", BearingGridWarning)
        model = BearingModel(params_from(a), AirParameters(**air), **settings)
    x_ok = np.allclose(ds["x"].values, model.x - 0.5 * model.length, rtol=0,
                       atol=COORDINATE_TOLERANCE * model.length)
    y_ok = model.infinitely_wide or np.allclose(
        ds["y"].values, model.y, rtol=0, atol=COORDINATE_TOLERANCE * model.params.width)
    if not (x_ok and y_ok):
        raise ParameterError("the stored node coordinates do not match the grid rebuilt "
                             "from its settings")
    return model


def _check_attrs(ds) -> None:
    """The JSON attributes air, model and info: objects whose keys are those this module
    writes (:func:`_settings`, :class:`AirParameters`, :class:`NewtonInfo`, the grading's),
    checked before the model is rebuilt."""
    _stored_dict(ds.attrs, "air", [f.name for f in dataclasses.fields(AirParameters)])
    _stored_dict(ds.attrs, "info", [f.name for f in dataclasses.fields(NewtonInfo)])
    settings = _stored_dict(ds.attrs, "model", (*_SETTINGS, *_OPTIONAL_SETTINGS), _SETTINGS)
    grading = settings.get("grading", {})
    if not isinstance(grading, dict) or not set(grading) <= set(_GRADING_KEYS):
        raise ParameterError(f"the file's grading must be an object with keys among "
                             f"{sorted(_GRADING_KEYS)}, got {grading!r}")


def _info_from(ds) -> NewtonInfo:
    """The Newton record stored in a file's ``info`` attribute (checked keys)."""
    return NewtonInfo(**_stored_dict(ds.attrs, "info",
                                     [f.name for f in dataclasses.fields(NewtonInfo)]))
