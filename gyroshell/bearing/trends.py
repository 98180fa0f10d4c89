"""The measured trends of a flat head's spacing, and whether a model reproduces them.

Magnetic spacing over a flat, lapped module, measured at IBM Research (Engelen, Furrer,
Rothuizen and Lantz, IEEE Trans. Magn. 50(3), 2014; "Asymmetrically wrapped flat-profile
tape-head friction and spacing", Tribology Letters), **falls** as the leading wrap grows,
does **not depend** on the trailing wrap, **falls** as the tension grows and **rises**
with speed. :func:`spacing_trends` sweeps each of the four about a base design, solving
the spacing at a mid-land transducer of the infinitely wide tape, and reports each
sweep's sign beside the measured one.

The base design (:data:`DATA_TAPE`, :data:`BASE`): a thin data tape (6 µm thick,
E = 7 GPa, 60 N/m) over one sharp-cornered 1 mm module at 2°/2° and 4 m/s, the film with
the Boltzmann flow factor and Patir–Cheng's flow factors, asperity contact (the defaults
of :class:`~gyroshell.bearing.contact.ContactParameters`).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

from ..tape.parameters import TapeParameters
from .air import AirParameters
from .contact import ContactParameters
from .head import FlatHead, Module
from .model import BearingGridWarning, BearingModel

#: A thin data tape: 6 µm thick, E = 7 GPa (a PEN or aramid base), 8.4 g/m², 60 N/m.
DATA_TAPE = TapeParameters(thickness=6e-6, youngs_modulus=7e9, density=0.0084,
                           tension=60.0)
#: The base design: wraps (deg), tension (N/m), speed (m/s), land (m).
BASE = {"wrap_in": 2.0, "wrap_out": 2.0, "tension": 60.0, "velocity": 4.0}
LAND = 1e-3
#: Each sweep: (what is varied, its values, the measured sign of the spacing's change:
#: −1 falls, 0 does not depend, +1 rises).
SWEEPS = (("wrap_in", (1.0, 2.0, 3.0, 4.0), -1), ("wrap_out", (1.0, 2.0, 3.0, 4.0), 0),
          ("tension", (40.0, 60.0, 90.0, 120.0), -1), ("velocity", (2.0, 4.0, 6.0, 8.0), 1))
#: A change below this fraction of the spacing (0.01 nm here) counts as "does not
#: depend": the trailing wrap moves it by 3e-5, the speed by 3e-2.
INDEPENDENT = 1e-3
#: The film and contact of the default physics (the Boltzmann film, Patir–Cheng's flow
#: factors, Greenwood–Williamson asperities).
AIR = AirParameters()
CONTACT = ContactParameters()


@dataclass(frozen=True)
class Trend:
    """One sweep: the parameter, its values, the spacings (m), the model's sign (−1, 0,
    +1, relative change under :data:`INDEPENDENT` counting as 0) and the measured one."""

    parameter: str
    values: tuple
    spacings: tuple
    sign: int
    measured: int

    @property
    def agrees(self) -> bool:
        return self.sign == self.measured

    @property
    def change(self) -> float:
        """The spacing's relative change from the first value to the last."""
        return self.spacings[-1] / self.spacings[0] - 1.0


def spacing_at(air: AirParameters = AIR, contact: ContactParameters | None = CONTACT,
               **design) -> float:
    """The spacing at the mid-land transducer (m) of :data:`BASE` changed by ``design``
    (wraps in degrees, tension N/m, velocity m/s)."""
    d = {**BASE, **design}
    head = FlatHead((Module(LAND),), math.radians(d["wrap_in"]), math.radians(d["wrap_out"]),
                    transducers=(0.0,))
    from .steady import solve_steady

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        model = BearingModel(DATA_TAPE.replace(tension=d["tension"]), air,
                             velocity=d["velocity"], head=head, infinitely_wide=True,
                             contact=contact)
    return solve_steady(model).transducer_lines[0].centre


def spacing_trends(air: AirParameters = AIR, contact: ContactParameters | None = CONTACT,
                   sweeps=SWEEPS) -> list[Trend]:
    """Each sweep of ``sweeps`` about :data:`BASE` with the film ``air`` and the contact
    ``contact`` (None: the model's default, :func:`.model.default_contact`)."""
    out = []
    for name, values, measured in sweeps:
        h = tuple(spacing_at(air, contact, **{name: v}) for v in values)
        change = h[-1] / h[0] - 1.0
        sign = 0 if abs(change) < INDEPENDENT else (1 if change > 0 else -1)
        out.append(Trend(name, tuple(values), h, sign, measured))
    return out
