"""Command-line options for damping and moving / intermittent loads, shared by sub-commands."""

from __future__ import annotations

import argparse
import math

from .common import UserError


def pair(text: str) -> tuple[float, float]:
    """'A,B': two finite numbers."""
    parts = text.split(",")
    try:
        a, b = (float(s) for s in parts)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected two numbers 'A,B', got {text!r}") from None
    if not (math.isfinite(a) and math.isfinite(b)):
        raise argparse.ArgumentTypeError(f"must be finite, got {text!r}")
    return a, b


def add_damping_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("damping (lab frame)")
    g.add_argument("--damping", metavar="C", type=float, default=None,
                   help="viscous damping c, N*s/m^3 (>= 0; damping pressure c dw/dt)")
    g.add_argument("--rayleigh", metavar="A,B", type=pair, default=None,
                   help="Rayleigh damping C = A M + B K: A in 1/s, B in s (both >= 0)")


def damping_from_args(args: argparse.Namespace):
    """A Damping from --damping and --rayleigh (validated; raises ParameterError naming the
    option, not the API's parameter)."""
    from ..core import validation
    from ..tape.damping import Damping

    a, b = args.rayleigh if args.rayleigh is not None else (0.0, 0.0)
    c = 0.0 if args.damping is None else args.damping
    return Damping(viscous=validation.nonnegative("--damping", c, "N*s/m^3"),
                   mass_coefficient=validation.nonnegative("--rayleigh A", a, "1/s"),
                   stiffness_coefficient=validation.nonnegative("--rayleigh B", b, "s"))


def add_load_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group(
        "moving and intermittent load (lab frame, where the supports x = 0, L_x stand)")
    g.add_argument("--load-position", metavar="X,Y", type=pair, default=None,
                   help="load centre at t = 0 (or at the start of each contact), m "
                        "(default: the tape centre)")
    g.add_argument("--load-velocity", metavar="VX,VY", type=pair, default=None,
                   help="load centre velocity, m/s; the history's w is then the "
                        "displacement under the load's current centre")
    g.add_argument("--contact-period", metavar="S", type=float, default=None,
                   help="intermittent contact: one window every S seconds (needs "
                        "--contact-duration); each contact restarts the head at "
                        "--load-position")
    g.add_argument("--contact-duration", metavar="S", type=float, default=None,
                   help="length of each contact window, s (<= --contact-period, and at "
                        "least two time steps)")
    g.add_argument("--contact-ramp", metavar="S", type=float, default=None,
                   help="raised-cosine rise and fall time inside each window, s (0, or at "
                        "least one time step; needs the contact windows; default 0: abrupt)")


def load_from_args(args: argparse.Namespace, params, dt: float | None = None):
    """A MovingLoad from the load options, or None for the paper's fixed step load; with
    ``dt`` (s) its contact windows are checked against the time step
    (:func:`gyroshell.tape.moving_loads.check_contact_steps`)."""
    from ..tape.moving_loads import ContactWindows, MovingLoad, StraightPath, check_contact_steps

    contact_given = (args.contact_period is not None, args.contact_duration is not None)
    if any(contact_given) and not all(contact_given):
        raise UserError("--contact-period and --contact-duration go together")
    if args.contact_ramp is not None and not all(contact_given):
        raise UserError("--contact-ramp shapes the contact windows: it needs "
                        "--contact-period and --contact-duration")
    if args.load_position is None and args.load_velocity is None and not any(contact_given):
        return None
    start = params.load_centroid if args.load_position is None else args.load_position
    velocity = (0.0, 0.0) if args.load_velocity is None else args.load_velocity
    contact = None
    if all(contact_given):
        ramp = 0.0 if args.contact_ramp is None else args.contact_ramp
        contact = ContactWindows(args.contact_period, args.contact_duration, ramp=ramp)
    load = MovingLoad(StraightPath(start, velocity), contact=contact,
                      restart_path=contact is not None)
    if dt is not None:
        check_contact_steps([load], dt)
    return load
