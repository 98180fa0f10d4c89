"""The head–tape interface options of the bearing commands: the film's rarefaction and
roughness flow factors, the contact law and its parameters, the dry tape and the head's
recession (``gyroshell bearing``, ``gyroshell study --compute bearing``).

The options override the TOML file's ``[air]`` and ``[contact]`` tables, which override
the defaults (:data:`gyroshell.bearing.air.RAREFACTION`, the contact law
:data:`DEFAULT_CONTACT`).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from .common import UserError, real

#: The contact law when neither an option nor the file's [contact] table names one.
DEFAULT_CONTACT = "asperity"

#: The contact options and the ContactParameters field each sets.
CONTACT_FIELDS = {"roughness": "--roughness", "asperity_density": "--asperity-density",
                  "asperity_radius": "--asperity-radius",
                  "contact_modulus": "--contact-modulus"}
#: The film options that --dry refuses (there is no film).
FILM_OPTIONS = {"rarefaction": "--rarefaction", "flow_factors": "--flow-factors",
                "incompressible": "--incompressible", "viscosity": "--viscosity",
                "mean_free_path": "--mean-free-path"}


def add_interface_options(p: argparse.ArgumentParser, *, single: bool = True) -> None:
    """The film models and the contact options; ``single`` (the single bearing command,
    not a study): also --dry and --recession."""
    from ..bearing.air import FLOW_FACTOR_CHOICES
    from ..bearing.contact import CONTACT_LAWS
    from ..bearing.rarefaction import RAREFACTION_MODELS

    g = p.add_argument_group("air film models")
    g.add_argument("--rarefaction", choices=RAREFACTION_MODELS, default=None,
                   help="Poiseuille flow factor of the rarefied film: fukui-kaneko (the "
                        "linearized Boltzmann flow rate, Fukui & Kaneko 1990), "
                        "first-order (slip, 1 + 6 Kn), second-order (1 + 6 Kn + 6 Kn^2) "
                        "or none (default: the file's [air] table, else fukui-kaneko)")
    g.add_argument("--flow-factors", choices=FLOW_FACTOR_CHOICES, default=None,
                   help="roughness in the film: patir-cheng (pressure and shear flow "
                        "factors of the summits' roughness, Patir & Cheng 1978/79), none, "
                        "or auto: patir-cheng under --contact asperity, none under the "
                        "hard wall or a compliance curve (default: the file's [air] "
                        "table, else auto)")
    g = p.add_argument_group("contact (SI units; spacings are reported to the mean plane "
                             "of the tape's summits)")
    g.add_argument("--contact", choices=tuple(c for c in CONTACT_LAWS if c != "compliance"),
                   default=None,
                   help="contact law: asperity (Greenwood-Williamson, acting wherever the "
                        "tape is near the head) or hard (a wall at the gap --roughness); "
                        f"--compliance FILE gives a measured curve (default: the file's "
                        f"[contact] table, else {DEFAULT_CONTACT})")
    g.add_argument("--roughness", type=real, default=None,
                   help="asperity: the summits' height standard deviation sigma_s, m "
                        "(default 6e-9); hard: the wall's gap, m (default 2e-08)")
    g.add_argument("--asperity-density", type=real, default=None,
                   help="asperity: summits per unit area, 1/m^2 (default 6.7e11)")
    g.add_argument("--asperity-radius", type=real, default=None,
                   help="asperity: summit radius, m (default 1e-05)")
    g.add_argument("--contact-modulus", type=real, default=None,
                   help="asperity: composite elastic modulus E*, Pa (default 5e9)")
    g.add_argument("--compliance", metavar="FILE.csv", default=None,
                   help="a measured compliance curve: CSV with the header "
                        "separation_m,pressure_Pa, pressure falling with separation")
    if not single:
        return
    g.add_argument("--dry", action="store_true",
                   help="no air film: the tape resting on the head through its contact "
                        "alone, at any speed including 0 (it enters through T - rho V^2)")
    g.add_argument("--recession", type=real, default=None,
                   help="head recession plus overcoats, m (>= 0): each transducer line "
                        "also reports its magnetic_spacing, the spacing plus it")


def contact_of(args: argparse.Namespace, table: dict | None = None, config=None):
    """The ContactParameters of the options over the file's ``[contact]`` table
    (``config``: the file, whose folder a compliance path is relative to)."""
    from ..bearing.contact import ComplianceCurve, ContactParameters

    base = (ContactParameters.from_table(table, Path(config).parent if config else None,
                                         where=f"{os.fspath(config)}: ")
            if table else None)
    law = args.contact
    if args.compliance is not None:
        if law not in (None, "compliance"):
            raise UserError(f"--compliance gives the contact law 'compliance': drop "
                            f"--contact {law} or --compliance")
        law = "compliance"
    typed = {field: getattr(args, field) for field in CONTACT_FIELDS
             if getattr(args, field) is not None}
    chosen = law or (base.law if base is not None else DEFAULT_CONTACT)
    for field in typed:
        if field != "roughness" and chosen != "asperity":
            raise UserError(f"{CONTACT_FIELDS[field]} sets the asperity contact law, and the "
                            f"contact here is {chosen!r}: drop {CONTACT_FIELDS[field]} or "
                            "use --contact asperity")
    if "roughness" in typed and chosen == "compliance":
        raise UserError("--roughness does not apply to a measured compliance curve "
                        "(--compliance): drop --roughness")
    if args.compliance is not None:
        typed["compliance"] = ComplianceCurve.from_csv(args.compliance)
    if base is None:
        return ContactParameters(law=law or DEFAULT_CONTACT, **typed)
    if law is not None and law != base.law:
        return ContactParameters(law=law, **typed)
    return base.replace(**typed) if typed else base


def check_recession(args: argparse.Namespace) -> float | None:
    """--recession, m (>= 0), or None."""
    from ..core import validation

    if getattr(args, "recession", None) is None:
        return None
    return validation.nonnegative("--recession", args.recession, "m")


def refuse_film_options_when_dry(args: argparse.Namespace) -> None:
    """--dry has no film: refuse the film's options beside it, in one line."""
    if not getattr(args, "dry", False):
        return
    for field, option in FILM_OPTIONS.items():
        if getattr(args, field, None) not in (None, False):
            raise UserError(f"{option} sets the air film, which --dry does not have: drop "
                            f"{option} or --dry")


def interface_given(args: argparse.Namespace) -> list[str]:
    """The interface options given (for a refusal where they do not apply)."""
    names = {"rarefaction": "--rarefaction", "flow_factors": "--flow-factors",
             "contact": "--contact", "compliance": "--compliance", **CONTACT_FIELDS}
    return [option for field, option in names.items()
            if getattr(args, field, None) is not None]


def air_of(args: argparse.Namespace, table: dict | None = None, config=None):
    """The AirParameters of the film options over the file's ``[air]`` table (None if
    neither sets anything: the bearing's default air)."""
    from ..bearing import AirParameters
    from ..bearing.air import air_changes_from_table

    fields = air_changes_from_table(table, f"{os.fspath(config)}: ") if table else {}
    typed = {name: getattr(args, name, None) for name in
             ("viscosity", "ambient_pressure", "mean_free_path", "rarefaction",
              "flow_factors")}
    fields.update({k: v for k, v in typed.items() if v is not None})
    if getattr(args, "incompressible", False):
        fields["compressible"] = False
    return AirParameters(**fields) if fields else None
