"""Properties of the lubricating air film (SI), validated.

Defaults are dry air at 20 °C and one standard atmosphere: dynamic viscosity
μ = 1.81e-5 Pa·s and mean free path λ = 64 nm at p_a = 101325 Pa (e.g. White, *Viscous
Fluid Flow*, Table A.1 for μ; λ = μ/p_a · √(π R_air T/2) ≈ 65 nm, the value 64 nm used in
tape and slider bearing work since Fukui & Kaneko).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..core import validation
from .flow_factors import FLOW_FACTOR_MODELS
from .rarefaction import RAREFACTION_MODELS

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
#: The film's rarefaction model (:mod:`.rarefaction`) and roughness flow factors
#: (:mod:`.flow_factors`) by default: the Boltzmann flow rate, valid at every Knudsen
#: number, and ``"auto"`` flow factors, Patir–Cheng's wherever the film knows the
#: summits' roughness σ_s (asperity contact), none otherwise (:func:`flow_factors_for`).
RAREFACTION = "fukui-kaneko"
FLOW_FACTORS = "auto"
#: The film's flow-factor choices: ``"auto"`` and the models of :mod:`.flow_factors`.
FLOW_FACTOR_CHOICES = ("auto", *FLOW_FACTOR_MODELS)
#: The film of a result written before the rarefaction and flow-factor models (its air
#: without those keys): first-order slip, no flow factors, as it was computed.
LEGACY_AIR = {"rarefaction": "first-order", "flow_factors": "none"}
#: The hard wall's gap of the legacy contact (``ContactParameters(law="hard")``), m.
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
        Mean free path λ at p_a, m (>= 0), in [0, 1e-3]: the local Knudsen number is
        Kn = λ p_a / (p h) (compressible) or λ / h (incompressible). ``0`` turns
        rarefaction off whatever the model.
    compressible : bool
        Compressible (isothermal ideal gas, p h transported) or incompressible Reynolds
        equation (p h → h in the flux and the sources).
    roughness : float or None
        The contact's length scale σ, m, in [1e-12, 1e-4], or None (the default): the
        contact law's. A :class:`~.model.BearingModel` sets it from its contact
        (:class:`~.contact.ContactParameters`): the summits' σ_s of the asperity law, the
        hard wall's gap. Given with ``contact=None``, it is the asperity law's σ_s.
    rarefaction : str
        The Poiseuille flow factor Q(Kn) multiplying the pressure-driven flux
        (:mod:`.rarefaction`): ``"first-order"`` slip, Q = 1 + 6 Kn (Burgdorfer 1959; good
        to Kn ≈ 0.5); ``"second-order"`` slip, Q = 1 + 6 Kn + 6 Kn² (Hsia & Domoto 1983;
        good to Kn ≈ 1); ``"fukui-kaneko"``, the linearized Boltzmann flow rate of Fukui &
        Kaneko (J. Tribol. 112:78, 1990), valid at every Kn; ``"none"``, Q = 1.
    flow_factors : str
        Average-flow factors of the rough film (:mod:`.flow_factors`): ``"patir-cheng"``
        (Patir & Cheng 1978, 1979; isotropic roughness, the pressure flow factor φ_x(h/σ)
        and the shear flow factor Φ_s(h/σ), fitted for h/σ > 0.5 and mattering below
        h/σ ≈ 4; the film then needs its roughness σ, see :class:`.film.Film`) or
        ``"none"`` (φ_x = 1, Φ_s = 0); ``"auto"`` (the default): Patir–Cheng's under
        the asperity contact law, whose σ_s the film then uses, none under the hard wall
        or a measured compliance curve (:func:`flow_factors_for`).
    """

    viscosity: float = AIR_VISCOSITY
    ambient_pressure: float = AMBIENT_PRESSURE
    mean_free_path: float = MEAN_FREE_PATH
    compressible: bool = True
    roughness: float | None = None
    rarefaction: str = RAREFACTION
    flow_factors: str = FLOW_FACTORS

    def __post_init__(self) -> None:
        put = object.__setattr__
        for name, (low, high), unit in (("viscosity", VISCOSITY_RANGE, "Pa*s"),
                                        ("ambient_pressure", AMBIENT_PRESSURE_RANGE, "Pa"),
                                        ("roughness", ROUGHNESS_RANGE, "m")):
            if name == "roughness" and self.roughness is None:
                continue
            put(self, name, validation.real(name, getattr(self, name), low=low, high=high,
                                            unit=unit))
        put(self, "mean_free_path", validation.real(
            "mean_free_path", self.mean_free_path, low=0.0, high=MEAN_FREE_PATH_MAX, unit="m"))
        put(self, "compressible", validation.boolean("compressible", self.compressible))
        validation.choice("rarefaction", self.rarefaction, RAREFACTION_MODELS)
        validation.choice("flow_factors", self.flow_factors, FLOW_FACTOR_CHOICES)

    def replace(self, **changes: object) -> AirParameters:
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)


def flow_factors_for(air: AirParameters, summits: bool) -> AirParameters:
    """``air`` with ``"auto"`` flow factors resolved: ``"patir-cheng"`` if the film knows
    the summits' roughness σ_s (``summits``: asperity contact, or a film given its
    roughness), else ``"none"``; any other choice unchanged."""
    if air.flow_factors != "auto":
        return air
    return air.replace(flow_factors="patir-cheng" if summits else "none")


#: The numbers of an ``[air]`` table and their SI units.
_AIR_UNITS = {"viscosity": "Pa*s", "ambient_pressure": "Pa", "mean_free_path": "m"}
_AIR_CHOICES = {"rarefaction": RAREFACTION_MODELS, "flow_factors": FLOW_FACTOR_CHOICES}


def air_changes_from_table(table, where: str = "") -> dict:
    """The :class:`AirParameters` fields of a TOML file's ``[air]`` table, checked::

        [air]
        viscosity = "1.81e-5 Pa*s"      # numbers without a unit are SI
        ambient_pressure = "101.325 kPa"
        mean_free_path = "64 nm"
        compressible = true
        rarefaction = "fukui-kaneko"    # or first-order, second-order, none
        flow_factors = "patir-cheng"    # or none, auto

    ``where`` names the file in messages (``"run.toml: "``). Raises ParameterError in one
    line naming the file and the key (an unknown key lists the allowed ones)."""
    from collections.abc import Mapping

    from ..core.errors import ParameterError
    from ..tape.config import parse_quantity

    prefix = f"{where}[air] "
    if not isinstance(table, Mapping):
        raise ParameterError(f"{prefix.rstrip()} must be a table")
    allowed = (*_AIR_UNITS, "compressible", *_AIR_CHOICES)
    out = {}
    for key, value in table.items():
        if key in _AIR_UNITS:
            out[key] = parse_quantity(key, value, prefix, unit=_AIR_UNITS[key])
        elif key == "compressible":
            if not isinstance(value, bool):
                raise ParameterError(f"{prefix}compressible must be true or false, got "
                                     f"{value!r}")
            out[key] = value
        elif key in _AIR_CHOICES:
            if value not in _AIR_CHOICES[key]:
                raise ParameterError(f"{prefix}{key} must be one of "
                                     f"{', '.join(_AIR_CHOICES[key])}, got {value!r}")
            out[key] = value
        else:
            raise ParameterError(f"{prefix}has no key {key!r}; allowed: {', '.join(allowed)}")
    return out
