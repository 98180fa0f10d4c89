"""Physical and numerical parameters of the moving tape (seed paper, Table 1).

Everything is SI: lengths in m, pressures and moduli in Pa, areal density in kg/m²,
tension in N/m, bending rigidity in N·m, shell (foundation) stiffness in N/m³.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, fields, replace
from functools import cached_property
from typing import Literal

from ..core import validation
from ..core.errors import ParameterError
from .material import (
    BendingStiffness,
    Lamination,
    Layer,
    laminate,
    layers_from,
    orthotropic_bending,
    reduced_stiffness,
)

Edges = Literal["free", "simply-supported"]
EDGE_CHOICES: tuple[str, ...] = ("free", "simply-supported")

#: Fewest grid intervals allowed across the tape width.
MIN_INTERVALS_ACROSS = 8
#: Fewest grid intervals allowed along the tape length.
MIN_INTERVALS_ALONG = 8
#: Fields that describe an orthotropic or layered tape (None: the isotropic tape).
ORTHOTROPIC_FIELDS = ("youngs_modulus_y", "shear_modulus", "bending_stiffness",
                      "membrane_stiffness", "layers")
#: Fields a layer stack sets (:meth:`TapeParameters.from_layers`).
STACK_FIELDS = ("thickness", "density", "youngs_modulus", "poisson")
#: Relative tolerance of a typed thickness, density, E_x or ν_xy against the stack's.
STACK_RTOL = 1e-9


def _check_poisson(poisson: object) -> float:
    return validation.real("poisson", poisson, low=-1.0, high=0.5, low_open=True,
                           high_open=True)


def bending_rigidity(youngs_modulus: float, thickness: float, poisson: float) -> float:
    """Plate bending rigidity D = E c³ / (12 (1 − ν²)), N·m.

    Examples
    --------
    >>> round(bending_rigidity(4e9, 20e-6, 0.3), 12)
    2.93e-06
    """
    E = validation.positive("youngs_modulus", youngs_modulus, "Pa")
    c = validation.positive("thickness", thickness, "m")
    nu = _check_poisson(poisson)
    try:
        D = E * c**3 / (12.0 * (1.0 - nu**2))
    except OverflowError:
        D = math.inf
    return validation.finite_scale("bending_rigidity", D,
                                   "N*m", what="youngs_modulus, thickness, poisson")


def shell_stiffness(
    youngs_modulus: float, thickness: float, radius: float, poisson: float
) -> float:
    """Shell (elastic-foundation) stiffness k = E c / (R² (1 − ν²)), N/m³.

    Examples
    --------
    >>> f"{shell_stiffness(4e9, 20e-6, 20e-3, 0.3):.4g}"
    '2.198e+08'
    """
    E = validation.positive("youngs_modulus", youngs_modulus, "Pa")
    c = validation.positive("thickness", thickness, "m")
    R = validation.positive("radius", radius, "m")
    nu = _check_poisson(poisson)
    try:
        k = E * c / (R**2 * (1.0 - nu**2))
    except ZeroDivisionError:  # R² underflowed to 0
        k = math.inf
    except OverflowError:  # R² overflowed: k would be 0
        k = 0.0
    return validation.finite_scale("foundation_stiffness", k,
                                   "N/m^3", what="youngs_modulus, thickness, radius, poisson")


# gyroshell.bearing.model still imports this name; it is validation.positive itself.


def check_velocity(velocity: float) -> float:
    """Validate a tape transport speed V (m/s): finite and >= 0; returns it as float."""
    return validation.nonnegative("velocity", velocity, "m/s")


@dataclass(frozen=True)
class TapeParameters:
    """Validated parameters of the tape model (defaults: seed paper, Table 1).

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E, Pa (4e9).
    poisson : float
        Poisson's ratio ν, in (−1, 0.5) (0.3).
    thickness : float
        Shell thickness c, m (20e-6).
    radius : float
        Wrap radius R, m (20e-3).
    density : float
        Areal density ρ, kg/m² (0.014).
    tension : float
        Circumferential tension per unit width T, N/m, >= 0 (90).
    width : float
        Tape width L_y, m (6.35e-3).
    length_ratio : float
        L_x / L_y, > 0 (4; the paper also uses 19).
    spacing : float
        Requested grid spacing Δx = Δy, m (1.549e-4: 41 intervals across the width).
        The grid takes the nearest whole number of intervals along each side.
    load : float
        Peak pressure P_0 of the Gaussian load (Eq. 17), Pa (200); also readable as
        :attr:`load_pressure`.
    load_x, load_y : float or None
        Load centroid x_0, y_0, m; ``None`` means the centre of the tape.
    edges : {"free", "simply-supported"}
        Lateral edges y = 0, L_y: the paper's free edges, or simply supported (for comparison
        with all-sides-simply-supported closed forms). Ends x = 0, L_x are always simply
        supported.
    bending_rigidity : float or None
        Override D, N·m (> 0). ``None`` derives D = E c³ / (12 (1 − ν²)).
    foundation_stiffness : float or None
        Override k, N/m³ (>= 0). ``None`` derives k = E c / (R² (1 − ν²)).
    wrap_pressure : bool
        Include the uniform belt-wrap pressure −T/R of Eq. 2 in the static load. Off by
        default: the transient starts from the wrapped equilibrium (w⁰ = 0), so w is measured
        from it and the wrap pressure is already balanced.
    youngs_modulus_y : float or None
        Young's modulus across the tape E_y, Pa (> 0): an orthotropic tape, whose
        ``youngs_modulus`` is then E_x (along) and ``poisson`` the major ratio ν_xy
        (ν_yx = ν_xy E_y/E_x, with ν_xy² < E_x/E_y). Needs ``shear_modulus``.
    shear_modulus : float or None
        In-plane shear modulus G_xy, Pa (> 0), of an orthotropic tape; given with
        ``youngs_modulus_y`` and only with it (G_xy of a tensilized film is not
        E/(2(1+ν)), so it is never guessed).
    bending_stiffness : tuple of 4 floats or None
        Override (D11, D22, D12, D66), N·m (positive definite), as ``bending_rigidity``
        overrides D; not with ``bending_rigidity``, ``youngs_modulus_y`` or
        ``shear_modulus``. k still comes from E, c, ν (or ``membrane_stiffness``).
    membrane_stiffness : float or None
        Override the membrane stiffness along the tape A11, N/m (> 0), which sets
        k = A11/R²; ``foundation_stiffness`` still wins for k.
    layers : tuple of Layer or None
        A stack, bottom up (:class:`gyroshell.Layer`): D* and A11 by classical lamination
        theory (:mod:`gyroshell.tape.material`). Build it with :meth:`from_layers`, which
        sets ``thickness`` = Σ t_i, ``density`` = Σ ρ_i t_i and ``youngs_modulus``,
        ``poisson`` to the stack's in-plane E_x = (A11 − A12²/A22)/c and ν_xy = A12/A22;
        values inconsistent with the stack are refused, and so are ``youngs_modulus_y``,
        ``shear_modulus``, ``bending_stiffness``, ``bending_rigidity`` and
        ``membrane_stiffness`` with it.

    Raises
    ------
    ParameterError
        Naming the parameter and its allowed range: a value out of range, not a number, or
        one whose derived quantities (D, k, the operators' scales) overflow or underflow.

    Examples
    --------
    >>> p = TapeParameters(length_ratio=19)
    >>> round(p.length, 6), round(p.k / 1e6, 1)          # m, MN/m^3
    (0.12065, 219.8)
    >>> TapeParameters(thickness=-1e-6)
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: thickness must be > 0 m, got -1e-06
    """

    youngs_modulus: float = 4.0e9
    poisson: float = 0.3
    thickness: float = 20.0e-6
    radius: float = 20.0e-3
    density: float = 0.014
    tension: float = 90.0
    width: float = 6.35e-3
    length_ratio: float = 4.0
    spacing: float = 1.549e-4
    load: float = 200.0
    load_x: float | None = None
    load_y: float | None = None
    edges: Edges = "free"
    bending_rigidity: float | None = None
    foundation_stiffness: float | None = None
    wrap_pressure: bool = False
    youngs_modulus_y: float | None = None
    shear_modulus: float | None = None
    bending_stiffness: tuple[float, float, float, float] | None = None
    membrane_stiffness: float | None = None
    layers: tuple[Layer, ...] | None = None

    def __post_init__(self) -> None:
        put = object.__setattr__
        for name, unit in (
            ("youngs_modulus", "Pa"),
            ("thickness", "m"),
            ("radius", "m"),
            ("density", "kg/m^2"),
            ("width", "m"),
            ("spacing", "m"),
            ("length_ratio", ""),
        ):
            put(self, name, validation.positive(name, getattr(self, name), unit))
        put(self, "tension", validation.nonnegative("tension", self.tension, "N/m"))
        put(self, "load", validation.real("load", self.load, unit="Pa"))
        self._check_material()
        validation.choice("edges", self.edges, EDGE_CHOICES)
        if self.bending_rigidity is not None:
            put(self, "bending_rigidity",
                validation.positive("bending_rigidity", self.bending_rigidity, "N*m"))
        if self.foundation_stiffness is not None:
            put(self, "foundation_stiffness", validation.nonnegative(
                "foundation_stiffness", self.foundation_stiffness, "N/m^3"))
        put(self, "wrap_pressure", validation.boolean("wrap_pressure", self.wrap_pressure))
        self._check_intervals()
        for name, limit in (("load_x", self.length), ("load_y", self.width)):
            value = getattr(self, name)
            if value is not None:
                put(self, name, validation.real(name, value, low=0.0, high=limit, unit="m"))
        self._check_scales()

    def _check_material(self) -> None:
        """The orthotropic and layered inputs: types, ranges, combinations, consistency."""
        put = object.__setattr__
        given = {name for name in ORTHOTROPIC_FIELDS if getattr(self, name) is not None}
        if self.layers is not None:
            put(self, "layers", layers_from(self.layers))
            clash = sorted(given - {"layers"})
            if self.bending_rigidity is not None:
                clash.insert(0, "bending_rigidity")
            if clash:
                raise ParameterError(f"layers cannot be combined with {', '.join(clash)}: "
                                     "the stack sets the stiffnesses")
            self._check_stack()
            return
        if self.youngs_modulus_y is not None or self.shear_modulus is not None:
            if self.shear_modulus is None:
                raise ParameterError("shear_modulus (G_xy, Pa, > 0) is required with "
                                     "youngs_modulus_y: it is independent of E_x, E_y and "
                                     "nu_xy for an orthotropic tape")
            if self.youngs_modulus_y is None:
                raise ParameterError("youngs_modulus_y (E_y, Pa, > 0) is required with "
                                     "shear_modulus (an orthotropic tape)")
            for name in ("bending_stiffness", "bending_rigidity"):
                if getattr(self, name) is not None:
                    raise ParameterError(
                        f"{name} cannot be combined with youngs_modulus_y and shear_modulus: "
                        "give either the bending stiffnesses or the moduli")
            reduced_stiffness(self.youngs_modulus, self.youngs_modulus_y,
                              self.shear_modulus, self.poisson)
            for name in ("youngs_modulus_y", "shear_modulus", "poisson"):
                put(self, name, float(getattr(self, name)))
        else:
            put(self, "poisson", _check_poisson(self.poisson))
        if self.bending_stiffness is not None:
            if self.bending_rigidity is not None:
                raise ParameterError("bending_stiffness cannot be combined with "
                                     "bending_rigidity: give one of them")
            value = self.bending_stiffness
            if isinstance(value, (str, bytes)) or not isinstance(value, Sequence) \
                    or len(value) != 4:
                raise ParameterError("bending_stiffness must be 4 numbers (D11, D22, D12, "
                                     f"D66) in N*m, got {value!r}")
            put(self, "bending_stiffness", BendingStiffness(*value).as_tuple())
        if self.membrane_stiffness is not None:
            put(self, "membrane_stiffness", validation.finite_scale(
                "membrane_stiffness", validation.positive(
                    "membrane_stiffness", self.membrane_stiffness, "N/m"), "N/m"))

    def _check_stack(self) -> None:
        """thickness, density, youngs_modulus and poisson must be those of the stack."""
        lam = self.lamination
        for name, value, unit in (("thickness", lam.thickness, "m"),
                                  ("density", lam.areal_density, "kg/m^2"),
                                  ("youngs_modulus", lam.effective_modulus, "Pa"),
                                  ("poisson", lam.effective_poisson, "")):
            given = validation.real(name, getattr(self, name), unit=unit)
            if not math.isclose(given, value, rel_tol=STACK_RTOL, abs_tol=0.0):
                unit = f" {unit}" if unit else ""
                raise ParameterError(
                    f"{name} must be the layer stack's {value:.10g}{unit} with layers (use "
                    f"TapeParameters.from_layers), got {given:g}{unit}")
            object.__setattr__(self, name, given)

    def _check_intervals(self) -> None:
        """Enough intervals each way to mean anything, and a length that is a number."""
        validation.finite_scale("length", self.length, "m", what="length_ratio x width")
        across = self.width / self.spacing
        if not math.isfinite(across):
            raise ParameterError(f"width {self.width:g} m with spacing {self.spacing:g} m "
                                 "gives an infinite number of intervals")
        if round(across) < MIN_INTERVALS_ACROSS:
            raise ParameterError(
                f"spacing must leave at least {MIN_INTERVALS_ACROSS} intervals across the width "
                f"(spacing <= {self.width / (MIN_INTERVALS_ACROSS - 0.5):.4g} m for width "
                f"{self.width:g} m), got {self.spacing:g} m")
        along = self.length / self.spacing
        if not math.isfinite(along):
            raise ParameterError(f"length_ratio {self.length_ratio:g} with spacing "
                                 f"{self.spacing:g} m gives an infinite number of intervals")
        if round(along) < MIN_INTERVALS_ALONG:
            lowest = (MIN_INTERVALS_ALONG - 0.5) * self.spacing / self.width
            raise ParameterError(
                f"length_ratio must leave at least {MIN_INTERVALS_ALONG} intervals along the "
                f"length (length_ratio >= {lowest:.4g}"
                f" with spacing {self.spacing:g} m), got {self.length_ratio:g} "
                f"({round(along)} intervals)")

    def _check_scales(self) -> None:
        """Derived coefficients of K and M must lie within the solvers' range (no 1e±300
        inputs turning into inf or 0 inside the operators or the eigen-solver)."""
        h, D, k, rho = self.spacing, self.D, self.k, self.density
        scale = validation.scale
        scale("bending_rigidity / spacing^2", D / h / h, "N/m",
              what="the bending rigidity and spacing")
        if not self.isotropic:
            bend = self.bending_matrix
            for name, value in (("D22", bend.D22), ("D66", bend.D66), ("D11 - D12^2/D22",
                                                                       bend.edge)):
                scale(f"{name} / spacing^2", value / h / h, "N/m",
                      what="the bending stiffnesses and spacing")
        scale("density x spacing^2", rho * h * h, "kg", what="density and spacing")
        scale("bending_rigidity / density", D / rho, "m^4/s^2",
              what="the bending rigidity and density")
        scale("foundation_stiffness x spacing^2", k * h * h, "N/m", lower=False,
              what="the shell stiffness and spacing")
        scale("k / density", k / rho, "1/s^2", lower=False,
              what="the shell stiffness and density")
        scale("tension / density", self.tension / rho, "m^2/s^2", lower=False,
              what="tension and density")
        scale("tension / radius", self.tension / self.radius, "Pa", lower=False,
              what="tension and radius")
        scale("|load| x spacing^2", abs(self.load) * h * h, "N",
              lower=False, what="the load pressure and spacing")

    def max_velocity(self) -> float:
        """Largest speed V, m/s, whose ρV² stays within the solvers' range (1e150 N/m; far
        above any critical speed)."""
        return math.sqrt(validation.MAX_SCALE) / math.sqrt(self.density)

    def check_velocity(self, velocity: float) -> float:
        """Validate a speed V for this tape: finite, >= 0 and ρV² finite; returns it (m/s)."""
        velocity = check_velocity(velocity)
        if velocity > self.max_velocity():
            raise ParameterError(
                f"velocity {velocity:g} m/s is out of range: rho V^2 overflows the solvers' "
                f"range (velocity must be <= {self.max_velocity():g} m/s)")
        return velocity

    @property
    def load_pressure(self) -> float:
        """Peak pressure P_0 of the Gaussian load, Pa (the field ``load``; a pressure, unlike
        the nodal forces :attr:`gyroshell.TapeModel.force` in N)."""
        return self.load

    # ----- derived quantities ------------------------------------------------------------
    @property
    def length(self) -> float:
        """Tape length L_x = length_ratio × L_y, m."""
        return self.length_ratio * self.width

    @property
    def isotropic(self) -> bool:
        """True for the isotropic plate of E, ν (or ``bending_rigidity``): no
        ``youngs_modulus_y``, ``shear_modulus``, ``bending_stiffness`` or ``layers``
        (``membrane_stiffness`` changes k only)."""
        return (self.youngs_modulus_y is None and self.bending_stiffness is None
                and self.layers is None)

    @property
    def lamination(self) -> Lamination | None:
        """Classical lamination theory of :attr:`layers` (None without layers)."""
        return None if self.layers is None else self._lamination

    @cached_property
    def _lamination(self) -> Lamination:
        return laminate(self.layers)

    @property
    def bending_matrix(self) -> BendingStiffness:
        """(D11, D22, D12, D66), N·m: ``bending_stiffness``, the stack's D*, the
        orthotropic Q c³/12, or the isotropic D (D, D, νD, (1 − ν)D/2)."""
        if self.layers is not None:
            return self._lamination.bending
        if self.bending_stiffness is not None:
            return BendingStiffness(*self.bending_stiffness)
        if self.youngs_modulus_y is not None:
            return orthotropic_bending(self.youngs_modulus, self.youngs_modulus_y,
                                       self.shear_modulus, self.poisson, self.thickness)
        return BendingStiffness.isotropic(self.D, self.poisson)

    @property
    def D(self) -> float:
        """Bending rigidity along the tape D11, N·m: the isotropic D (override or
        E c³ / (12 (1 − ν²))), or D11 of :attr:`bending_matrix`. It sets the bending
        length √(D/T) and the width-uniform strip's stiffness (cylindrical bending,
        w_yy = 0)."""
        if self.isotropic:
            if self.bending_rigidity is not None:
                return self.bending_rigidity
            return bending_rigidity(self.youngs_modulus, self.thickness, self.poisson)
        return self.bending_matrix.D11

    @property
    def membrane_A11(self) -> float:
        """Membrane stiffness along the tape A11, N/m: ``membrane_stiffness``, the stack's
        Σ Q11 t, the orthotropic Q11 c, or the isotropic E c / (1 − ν²)."""
        if self.membrane_stiffness is not None:
            return self.membrane_stiffness
        if self.layers is not None:
            return self._lamination.A[0]
        if self.youngs_modulus_y is not None:
            q11 = reduced_stiffness(self.youngs_modulus, self.youngs_modulus_y,
                                    self.shear_modulus, self.poisson)[0]
            return validation.finite_scale("membrane A11", q11 * self.thickness, "N/m",
                                           what="youngs_modulus, thickness")
        return validation.finite_scale(
            "membrane A11", self.youngs_modulus * self.thickness / (1.0 - self.poisson**2),
            "N/m", what="youngs_modulus, thickness, poisson")

    @property
    def k(self) -> float:
        """Shell (foundation) stiffness k, N/m³: override, else A11 / R² (isotropic:
        E c / (R² (1 − ν²)))."""
        if self.foundation_stiffness is not None:
            return self.foundation_stiffness
        if self.isotropic and self.membrane_stiffness is None:
            return shell_stiffness(self.youngs_modulus, self.thickness, self.radius,
                                   self.poisson)
        try:
            k = self.membrane_A11 / self.radius**2
        except ZeroDivisionError:
            k = math.inf
        except OverflowError:
            k = 0.0
        return validation.finite_scale("foundation_stiffness", k, "N/m^3",
                                       what="the membrane stiffness A11 and radius")

    @property
    def load_centroid(self) -> tuple[float, float]:
        """Load centroid (x_0, y_0), m; the tape centre unless set."""
        x0 = self.length / 2 if self.load_x is None else self.load_x
        y0 = self.width / 2 if self.load_y is None else self.load_y
        return x0, y0

    @property
    def wrap_pressure_value(self) -> float:
        """Belt-wrap pressure T/R, Pa (4500 for Table 1)."""
        return self.tension / self.radius

    @property
    def string_speed(self) -> float:
        """√(T/ρ), m/s: where the effective tension T − ρV² vanishes (Eq. 18)."""
        return math.sqrt(self.tension / self.density)

    @property
    def strip_critical_speed(self) -> float:
        """√((T + 2√(D k))/ρ), m/s: divergence of an infinite strip on the shell foundation.

        A beam (width-uniform, w_yy = 0, bending with D = D11) on an elastic foundation with
        tension T buckles at the wavenumber α = (k/D)^(1/4), where
        ρV² = T + min_α (Dα² + k/α²) = T + 2√(D k). It is exact for the free-edged tape
        when D12 = 0 (ν = 0); otherwise the edges' anticlastic relief lowers the critical
        speed slightly (the lowest Lévy branch, docs/orthotropy.md), and it is an upper
        bound for an infinitely long tape.
        """
        return math.sqrt((self.tension + 2.0 * math.sqrt(self.D * self.k)) / self.density)

    @property
    def foundation_frequency(self) -> float:
        """√(k/ρ), rad/s: the V = 0 cut-on frequency (period 2π√(ρ/k) ≈ 50 µs)."""
        return math.sqrt(self.k / self.density)

    def replace(self, **changes: object) -> TapeParameters:
        """A copy with some fields changed (validated again); see :meth:`with_layers` to
        change the stack."""
        return replace(self, **changes)

    @classmethod
    def from_layers(cls, layers, **other: object) -> TapeParameters:
        """The tape of the stack ``layers`` (bottom up; Layers or mappings of their
        fields), with ``thickness``, ``density``, ``youngs_modulus`` and ``poisson`` set
        from it (Σ t_i, Σ ρ_i t_i, the in-plane E_x and ν_xy) and the other fields from
        ``other``.

        Examples
        --------
        >>> from gyroshell import Layer
        >>> p = TapeParameters.from_layers([Layer(20e-6, 4e9, 4e9, 4e9 / 2.6, 0.3, 700.0)])
        >>> round(p.thickness * 1e6, 9), round(p.density, 12), p.D == p.bending_matrix.D11
        (20.0, 0.014, True)
        """
        for name in STACK_FIELDS:
            if name in other:
                raise ParameterError(f"from_layers sets {name} from the stack; do not pass "
                                     f"{name}")
        stack = layers_from(layers)
        lam = laminate(stack)
        return cls(layers=stack, thickness=lam.thickness, density=lam.areal_density,
                   youngs_modulus=lam.effective_modulus, poisson=lam.effective_poisson,
                   **other)

    def with_layers(self, layers) -> TapeParameters:
        """A copy with the stack ``layers`` and the thickness, density, E_x and ν_xy that
        follow from it (see :meth:`from_layers`)."""
        other = {f.name: getattr(self, f.name) for f in fields(self)
                 if f.name not in STACK_FIELDS and f.name != "layers"}
        return type(self).from_layers(layers, **other)

    def as_dict(self) -> dict[str, object]:
        """Field values plus the derived D, k and L_x (SI); ``layers`` as a list of plain
        dicts (``TapeParameters(**d)`` of the fields rebuilds an equal tape)."""
        out: dict[str, object] = {f.name: getattr(self, f.name) for f in fields(self)}
        if self.layers is not None:
            out["layers"] = [layer.as_dict() for layer in self.layers]
        out.update(D=self.D, k=self.k, length=self.length)
        return out
