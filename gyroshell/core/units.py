"""The one table of units: the SI unit of every named quantity, the units a file may give.

Every quantity the package reads, writes or plots is SI. :data:`SI_UNITS` gives the SI unit
of each named parameter and table column (what saved files state as ``units`` attributes,
what axis labels show); :data:`ACCEPTED` gives, for each SI unit, the other units a tape file
(``--config``) may use and their factors to SI. A small table serves better than a general
units library here: the set of quantities is fixed, decimal prefixes are applied in decimal
(``"20 um"`` is exactly ``2e-05``), and ``import gyroshell`` stays fast.

Examples
--------
>>> unit_of("tension"), unit_of("omega_3"), axis_label("density")
('N/m', 'rad/s', 'density (kg/m²)')
>>> unit_of("layer2.thickness"), axis_label("layer1.density")
('m', 'layer1.density (kg/m³)')
"""

from __future__ import annotations

import math
import re

#: SI unit of each named quantity (ASCII: ``^`` for powers, ``*`` for products).
SI_UNITS: dict[str, str] = {
    "youngs_modulus": "Pa", "poisson": "1", "thickness": "m", "radius": "m",
    "density": "kg/m^2", "tension": "N/m", "width": "m", "length_ratio": "1", "spacing": "m",
    "load": "Pa", "load_x": "m", "load_y": "m", "bending_rigidity": "N*m",
    "foundation_stiffness": "N/m^3", "velocity": "m/s",
    "youngs_modulus_x": "Pa", "youngs_modulus_y": "Pa", "shear_modulus": "Pa",
    "poisson_xy": "1", "bending_stiffness": "N*m", "membrane_stiffness": "N/m",
    "critical_speed": "m/s", "divergence_speed": "m/s", "growth_rate": "1/s",
    "omega": "rad/s", "frequency": "Hz", "period": "s", "load_point_deflection": "m",
    "max_deflection": "m",
    # heads (issue 19): their design parameters and what a bearing study reports
    "wrap_angle": "rad", "wrap_in": "rad", "wrap_out": "rad", "wrap": "rad", "land_length": "m",
    "corner_radius": "m", "module_gap": "m", "friction": "1", "central_spacing": "m",
    "minimum_spacing": "m", "tension_rise": "N/m",
    "tension_ratio": "1",
}

#: SI unit of each quantity of one layer of a stack (a ``[[layer]]`` table of a tape file;
#: a study's ``layer<N>.<key>``): its density is per volume, unlike the tape's areal one.
LAYER_UNITS: dict[str, str] = {
    "thickness": "m", "youngs_modulus_x": "Pa", "youngs_modulus_y": "Pa",
    "shear_modulus": "Pa", "poisson_xy": "1", "density": "kg/m^3",
}
#: A layer's quantity named as a study varies it: ``layer2.thickness`` (layers counted from 1
#: at the bottom).
LAYER_NAME = re.compile(r"^layer(\d+)\.(\w+)$")

#: Columns named ``omega_<k>`` (the k-th frequency of a sweep or study) are in rad/s.
OMEGA_PREFIX = "omega_"

#: For each SI unit, the units a file may give and their factors to SI.
ACCEPTED: dict[str, dict[str, float]] = {
    "m": {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "μm": 1e-6,
          "nm": 1e-9, "in": 0.0254, "mil": 2.54e-5},
    "Pa": {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9, "N/m^2": 1.0, "N/mm^2": 1e6,
           "psi": 6894.757293168361},
    "kg/m^2": {"kg/m^2": 1.0, "g/m^2": 1e-3},
    "kg/m^3": {"kg/m^3": 1.0, "g/cm^3": 1e3, "g/cc": 1e3},
    "N/m": {"N/m": 1.0, "N/mm": 1e3, "mN/m": 1e-3},
    "N*m": {"N*m": 1.0, "N m": 1.0, "N·m": 1.0, "Nm": 1.0},
    "N/m^3": {"N/m^3": 1.0, "Pa/m": 1.0, "MPa/m": 1e6, "GPa/m": 1e9},
    "m/s": {"m/s": 1.0, "mm/s": 1e-3, "km/h": 1 / 3.6, "in/s": 0.0254},
    "Pa*s": {"Pa*s": 1.0, "Pa s": 1.0, "Pa·s": 1.0, "mPa*s": 1e-3, "cP": 1e-3,
             "uPa*s": 1e-6, "µPa*s": 1e-6},
    "1": {"": 1.0, "1": 1.0},
    "rad": {"rad": 1.0, "mrad": 1e-3, "deg": math.pi / 180.0, "°": math.pi / 180.0},
}

#: How an ASCII unit is printed on a figure.
_DISPLAY = {"kg/m^2": "kg/m²", "N*m": "N·m", "N/m^3": "N/m³", "kg/m^3": "kg/m³"}


def unit_of(name: str) -> str | None:
    """The SI unit of a named quantity or table column, or None if it has none listed."""
    if name.startswith(OMEGA_PREFIX):
        return SI_UNITS["omega"]
    layer = LAYER_NAME.match(name)
    if layer is not None:
        return LAYER_UNITS.get(layer.group(2))
    return SI_UNITS.get(name)


def display_unit(unit: str) -> str:
    """How an ASCII SI unit is printed on a figure (``kg/m^2`` as ``kg/m²``)."""
    return _DISPLAY.get(unit, unit)


def axis_label(name: str) -> str:
    """``"<name> (<unit>)"`` with underscores as spaces; no unit for dimensionless ones."""
    unit = unit_of(name)
    text = name.replace("_", " ")
    if unit is None or unit == "1":
        return text
    return f"{text} ({display_unit(unit)})"
