"""Properties of the lubricating air film (SI), validated.

Defaults are dry air at 20 °C and one standard atmosphere: dynamic viscosity
μ = 1.81e-5 Pa·s and mean free path λ = 64 nm at p_a = 101325 Pa (e.g. White, *Viscous
Fluid Flow*, Table A.1 for μ; λ = μ/p_a · √(π R_air T/2) ≈ 65 nm, the value 64 nm used in
tape and slider bearing work since Fukui & Kaneko).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..core import validation

#: Accepted ranges (SI): wide around air at 20 °C, narrow enough that the film's scales stay
#: inside double precision (p_a 1e-300 Pa overflowed the slip factor 6 λ p_a / (p h)).
VISCOSITY_RANGE = (1e-7, 1e3)          # Pa·s
AMBIENT_PRESSURE_RANGE = (1e2, 1e9)    # Pa
MEAN_FREE_PATH_MAX = 1e-3              # m
ROUGHNESS_RANGE = (1e-12, 1e-4)        # m

#: Dynamic viscosity of air at 20 °C, Pa·s.
AIR_VISCOSITY = 1.81e-5
#: Standard atmosphere, Pa.
AMBIENT_PRESSURE = 101325.0
#: Mean free path of air molecules at 20 °C and one atmosphere, m.
MEAN_FREE_PATH = 64.0e-9
#: Combined surface roughness below which tape and head touch, m.
ROUGHNESS = 20.0e-9


@dataclass(frozen=True)
class AirParameters:
    """The air film between tape and head.

    Parameters
    ----------
    viscosity : float
        Dynamic viscosity μ, Pa·s (> 0).
    ambient_pressure : float
        Ambient pressure p_a, Pa (> 0); the film pressure on every film boundary.
    mean_free_path : float
        Mean free path λ at p_a, m (>= 0); the slip flow factor is
        Q = 1 + 6 λ p_a / (p h). ``0`` turns slip off.
    compressible : bool
        Compressible (isothermal ideal gas, p h transported) or incompressible Reynolds
        equation (p h → h in the flux and the sources; slip then uses Q = 1 + 6 λ / h).
    roughness : float
        Combined surface roughness σ, m (> 0): the spacing never drops below it; where it
        would, the tape touches the head and a contact force holds it at h = σ.
    """

    viscosity: float = AIR_VISCOSITY
    ambient_pressure: float = AMBIENT_PRESSURE
    mean_free_path: float = MEAN_FREE_PATH
    compressible: bool = True
    roughness: float = ROUGHNESS

    def __post_init__(self) -> None:
        put = object.__setattr__
        for name, (low, high), unit in (("viscosity", VISCOSITY_RANGE, "Pa*s"),
                                        ("ambient_pressure", AMBIENT_PRESSURE_RANGE, "Pa"),
                                        ("roughness", ROUGHNESS_RANGE, "m")):
            put(self, name, validation.real(name, getattr(self, name), low=low, high=high,
                                            unit=unit))
        put(self, "mean_free_path", validation.real(
            "mean_free_path", self.mean_free_path, low=0.0, high=MEAN_FREE_PATH_MAX, unit="m"))
        put(self, "compressible", validation.boolean("compressible", self.compressible))

    def replace(self, **changes: object) -> AirParameters:
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)
