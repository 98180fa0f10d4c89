"""Physical and numerical parameters of the moving tape (seed paper, Table 1).

Everything is SI: lengths in m, pressures and moduli in Pa, areal density in kg/m²,
tension in N/m, bending rigidity in N·m, shell (foundation) stiffness in N/m³.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import Literal

from ..core import validation
from ..core.errors import ParameterError

Edges = Literal["free", "simply-supported"]
EDGE_CHOICES: tuple[str, ...] = ("free", "simply-supported")

#: Fewest grid intervals allowed across the tape width.
MIN_INTERVALS_ACROSS = 8
#: Fewest grid intervals allowed along the tape length.
MIN_INTERVALS_ALONG = 8


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
        put(self, "poisson", _check_poisson(self.poisson))
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
    def D(self) -> float:
        """Bending rigidity D, N·m (override or E c³ / (12 (1 − ν²)))."""
        if self.bending_rigidity is not None:
            return self.bending_rigidity
        return bending_rigidity(self.youngs_modulus, self.thickness, self.poisson)

    @property
    def k(self) -> float:
        """Shell (foundation) stiffness k, N/m³ (override or E c / (R² (1 − ν²)))."""
        if self.foundation_stiffness is not None:
            return self.foundation_stiffness
        return shell_stiffness(self.youngs_modulus, self.thickness, self.radius, self.poisson)

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

        A beam (ν-free, width-uniform) on an elastic foundation with tension T buckles at the
        wavenumber α = (k/D)^(1/4), where ρV² = T + min_α (Dα² + k/α²) = T + 2√(D k).
        """
        return math.sqrt((self.tension + 2.0 * math.sqrt(self.D * self.k)) / self.density)

    @property
    def foundation_frequency(self) -> float:
        """√(k/ρ), rad/s: the V = 0 cut-on frequency (period 2π√(ρ/k) ≈ 50 µs)."""
        return math.sqrt(self.k / self.density)

    def replace(self, **changes: object) -> TapeParameters:
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)

    def as_dict(self) -> dict[str, object]:
        """Field values plus the derived D, k and L_x (SI)."""
        out: dict[str, object] = {f.name: getattr(self, f.name) for f in fields(self)}
        out.update(D=self.D, k=self.k, length=self.length)
        return out
