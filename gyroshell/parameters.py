"""Physical and numerical parameters of the moving tape (seed paper, Table 1).

Everything is SI: lengths in m, pressures and moduli in Pa, areal density in kg/m²,
tension in N/m, bending rigidity in N·m, shell (foundation) stiffness in N/m³.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import Literal

from .errors import ParameterError

Edges = Literal["free", "simply-supported"]
EDGE_CHOICES: tuple[str, ...] = ("free", "simply-supported")

#: Fewest grid intervals allowed across the tape width.
MIN_INTERVALS_ACROSS = 8


def bending_rigidity(youngs_modulus: float, thickness: float, poisson: float) -> float:
    """Plate bending rigidity D = E c³ / (12 (1 − ν²)), N·m."""
    return youngs_modulus * thickness**3 / (12.0 * (1.0 - poisson**2))


def shell_stiffness(
    youngs_modulus: float, thickness: float, radius: float, poisson: float
) -> float:
    """Shell (elastic-foundation) stiffness k = E c / (R² (1 − ν²)), N/m³."""
    return youngs_modulus * thickness / (radius**2 * (1.0 - poisson**2))


def _check_finite(name: str, value: float) -> float:
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(value):
        raise ParameterError(f"{name} must be finite, got {value}")
    return value


def _check_positive(name: str, value: float, unit: str) -> float:
    value = _check_finite(name, value)
    if value <= 0.0:
        raise ParameterError(f"{name} must be > 0 {unit}, got {value:g}")
    return value


def _check_nonnegative(name: str, value: float, unit: str) -> float:
    value = _check_finite(name, value)
    if value < 0.0:
        raise ParameterError(f"{name} must be >= 0 {unit}, got {value:g}")
    return value


def check_velocity(velocity: float) -> float:
    """Validate a tape transport speed V (m/s): finite and >= 0; returns it as float."""
    return _check_nonnegative("velocity", velocity, "m/s")


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
        Peak pressure P_0 of the Gaussian load (Eq. 17), Pa (200).
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
        ):
            put(self, name, _check_positive(name, getattr(self, name), unit))
        put(self, "length_ratio", _check_positive("length_ratio", self.length_ratio, ""))
        put(self, "tension", _check_nonnegative("tension", self.tension, "N/m"))
        put(self, "load", _check_finite("load", self.load))
        nu = _check_finite("poisson", self.poisson)
        if not -1.0 < nu < 0.5:
            raise ParameterError(f"poisson must be in (-1, 0.5), got {nu:g}")
        put(self, "poisson", nu)
        if self.edges not in EDGE_CHOICES:
            raise ParameterError(
                f"edges must be one of {', '.join(EDGE_CHOICES)}, got {self.edges!r}"
            )
        if self.bending_rigidity is not None:
            put(self, "bending_rigidity",
                _check_positive("bending_rigidity", self.bending_rigidity, "N*m"))
        if self.foundation_stiffness is not None:
            put(self, "foundation_stiffness",
                _check_nonnegative("foundation_stiffness", self.foundation_stiffness, "N/m^3"))
        intervals = round(self.width / self.spacing)
        if intervals < MIN_INTERVALS_ACROSS:
            raise ParameterError(
                f"spacing must leave at least {MIN_INTERVALS_ACROSS} intervals across the width "
                f"(spacing <= {self.width / (MIN_INTERVALS_ACROSS - 0.5):.4g} m for width "
                f"{self.width:g} m), got {self.spacing:g} m"
            )
        for name, limit in (("load_x", self.length), ("load_y", self.width)):
            value = getattr(self, name)
            if value is not None:
                value = _check_finite(name, value)
                if not 0.0 <= value <= limit:
                    raise ParameterError(f"{name} must be in [0, {limit:.6g}] m, got {value:g}")
                put(self, name, value)
        put(self, "wrap_pressure", bool(self.wrap_pressure))

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
