"""The head options of ``gyroshell bearing`` and ``gyroshell study --compute bearing``:
``--head cylinder|flat|FILE.csv`` and the head's dimensions, merged over the ``[head]``
table of the ``--config`` file into one checked
:class:`~gyroshell.bearing.head_config.HeadDesign`.

Lengths are in m (x from the head's middle), angles in degrees. An option of another kind of
head (``--wrap-angle`` with ``--head flat``, ``--land-length`` on a cylinder) is refused in
one line, as is every value out of range (:func:`gyroshell.bearing.head_config.check_design`).
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
from pathlib import Path

from ..bearing.head import WRAPPED_ARC_BENDING_LENGTHS
from .common import UserError, real

__all__ = ["HEAD_FLAGS", "add_head_options", "build_head_of", "head_design",
           "typed_head_options"]

#: The head options: HeadDesign field -> flag.
HEAD_FLAGS: dict[str, str] = {
    "wrap_angle": "--wrap-angle", "wrap_in": "--wrap-in", "wrap_out": "--wrap-out",
    "land_length": "--land-length", "corner_radius": "--corner-radius",
    "modules": "--modules", "module_gap": "--module-gap", "flank_angle": "--flank-angle",
    "transducers": "--transducers", "friction": "--friction", "arc_contact": "--arc-contact"}
#: The options given in degrees.
DEGREE_FIELDS = ("wrap_angle", "wrap_in", "wrap_out", "flank_angle")
#: The kinds ``--head`` names; anything else is a profile file.
NAMED_KINDS = ("cylinder", "flat")


def add_head_options(p: argparse.ArgumentParser, *, title: str = "head") -> None:
    """Add ``--head`` and the head's dimensions (every default None: not typed)."""
    g = p.add_argument_group(f"{title} (lengths in m, x from the head's middle, the tape "
                             "moving towards +x; angles in degrees)")
    g.add_argument("--head", metavar="cylinder|flat|FILE.csv", default=None,
                   help="the head: a cylinder (default; of the tape's radius R), a flat head "
                        "of one or more modules with sharp or rounded corners, or a measured "
                        "contour: a CSV file of x, z or x, y, z in m (also [head] in "
                        "--config)")
    g.add_argument("--wrap-angle", type=real, default=None,
                   help="cylinder: wrap angle of the tape on the head, degrees, in (0, 90] "
                        "(default 15)")
    g.add_argument("--wrap-in", type=real, default=None,
                   help="flat or measured head: angle of the incoming span below the first "
                        "land, degrees, in [0, 45] (default 0; e.g. 2); on a flat head "
                        "below --flank-angle (default 20)")
    g.add_argument("--wrap-out", type=real, default=None,
                   help="flat or measured head: angle of the outgoing span below the last "
                        "land, degrees, in [0, 45] (default 0); on a flat head below "
                        "--flank-angle (default 20)")
    g.add_argument("--land-length", type=real, default=None,
                   help="flat head: each module's land, corner to corner, m (e.g. 1e-3)")
    g.add_argument("--corner-radius", default=None, metavar="R or R_IN,R_OUT",
                   help="flat head: radius of the corners, m, >= 0 (default 0, sharp), or "
                        "the leading and trailing radii")
    g.add_argument("--modules", type=_integer, default=None,
                   help="flat head: number of equal coplanar modules, 1 to 8 (default 1; the "
                        "wrap acts at the outer corners; per-module heights and tilts in "
                        "[[head.module]] tables of --config)")
    g.add_argument("--module-gap", type=real, default=None,
                   help="flat head: gap between consecutive modules, m, > 0 (required with "
                        "--modules 2 or more)")
    g.add_argument("--flank-angle", type=real, default=None,
                   help="flat head: angle below the land at which the head falls away "
                        "beyond each corner, degrees, in (0, 90) (default 20); steeper than "
                        "the tape's spans, so above --wrap-in and --wrap-out")
    g.add_argument("--transducers", default=None, metavar="X1,X2,...",
                   help="x of the read/write element lines, m from the head's middle, on "
                        "the wrapped region (the spacing along each is reported)")
    g.add_argument("--friction", type=real, default=None,
                   help="Coulomb friction coefficient between tape and head, >= 0 (default "
                        "0): friction drag = friction x contact force")
    g.add_argument("--arc-contact", default=None, metavar="auto|point|wrapped",
                   help="flat head with rounded corners (refused on sharp ones, where it "
                        "has no effect): how the tape meets each arc: point, at "
                        "one tangent point (found by regridding; valid while the tape is "
                        "less curved than the arc); wrapped, lying on part of the arc (every "
                        "arc node may touch); auto (default), per corner: wrapped when the "
                        f"arc r_c theta_c, m, exceeds {WRAPPED_ARC_BENDING_LENGTHS:g} bending "
                        "lengths sqrt(D/(T - rho V^2)), else point")


def typed_head_options(args: argparse.Namespace) -> list[str]:
    """The head options typed on the command line (flags)."""
    typed = [flag for field, flag in HEAD_FLAGS.items() if getattr(args, field) is not None]
    return (["--head"] if args.head is not None else []) + typed


def head_design(args: argparse.Namespace, table: dict | None = None,
                config: str | os.PathLike | None = None, *, varied=()):
    """The :class:`~gyroshell.bearing.head_config.HeadDesign` of the head options over the
    ``[head]`` table ``table`` of the file ``config`` (options win), checked; without what
    a study's ``--vary`` sets at every point (``varied``, HeadDesign fields), which is
    checked with each point.

    Raises
    ------
    UserError, ParameterError
        One line naming the option or the file's key.
    """
    from ..bearing.head_config import check_design, in_file

    merged, labels, where = _stated(args, table, config)
    return in_file(where, lambda: check_design(merged, labels, degrees=True,
                                                    varied=varied))


def build_head_of(args: argparse.Namespace, design, table: dict | None = None,
                  config: str | os.PathLike | None = None):
    """The :class:`~gyroshell.bearing.head.Head` of ``design`` (:func:`head_design` of the
    same arguments), its contour's refusals naming the options, ``[head]`` keys and file
    as the user wrote them (:func:`gyroshell.bearing.head_config.build_head`)."""
    from ..bearing.head_config import build_head

    _, labels, where = _stated(args, table, config)
    return build_head(design, labels, where)


def _stated(args: argparse.Namespace, table: dict | None, config) -> tuple:
    """(the design the options state over the table, unchecked; how the user named each
    field; the file as messages name it, ``"head.toml: "`` or "")."""
    from ..bearing.head_config import HeadDesign, design_from_table, table_labels

    design = HeadDesign()
    labels = {**HEAD_FLAGS, "kind": "the default cylinder", "profile": "--head FILE.csv"}
    where = ""
    if table is not None:
        where = f"{os.fspath(config)}: "
        folder = None if config is None else Path(config).parent
        design = design_from_table(table, where=where, folder=folder)
        named = table_labels(table.get("kind"))
        labels.update({field: named[field] for field in (*design.given(), "kind")})
    changes = _typed_fields(args)
    labels.update({field: HEAD_FLAGS[field] for field in changes})
    if args.head is not None:
        kind, profile = _kind_of(args.head)
        if kind != design.kind:  # the table's fields of the other kind stay, to be refused
            changes["kind"] = kind
        changes["profile"] = profile
        labels["kind"] = f"--head {args.head}"
        labels["profile"] = "--head"
    return dataclasses.replace(design, **changes), labels, where


def _integer(text: str) -> int:
    """An integer (its range is checked with the head: 1 to 8 modules)."""
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an integer: {text!r}") from None


def _kind_of(text: str) -> tuple[str, str | None]:
    """(kind, profile path or None) of ``--head``."""
    if text in NAMED_KINDS:
        return text, None
    if Path(text).suffix.lower() != ".csv":
        raise UserError(f"--head must be cylinder, flat or a measured contour FILE.csv, got "
                        f"{text!r}")
    return "profile", text


def _typed_fields(args: argparse.Namespace) -> dict:
    """The typed head options as HeadDesign fields, in SI (angles in rad)."""
    out: dict = {}
    for field, flag in HEAD_FLAGS.items():
        value = getattr(args, field)
        if value is None:
            continue
        if field in DEGREE_FIELDS:
            value = math.radians(value)
        elif field == "transducers":
            value = _numbers(flag, value)
        elif field == "corner_radius":
            radii = _numbers(flag, value)
            if len(radii) > 2:
                raise UserError(f"{flag} takes one radius or two (leading,trailing), got "
                                f"{len(radii)}")
            value = radii[0] if len(radii) == 1 else radii
        out[field] = value
    return out


def _numbers(flag: str, text: str) -> tuple[float, ...]:
    """``X1,X2,...`` as floats (m)."""
    items = [item.strip() for item in text.split(",")]
    try:
        if not all(items):
            raise argparse.ArgumentTypeError(f"an empty item in {text!r}")
        return tuple(real(item) for item in items)
    except argparse.ArgumentTypeError as exc:
        raise UserError(f"{flag}: {exc} (give numbers in m separated by commas)") from None
