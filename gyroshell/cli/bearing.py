"""``gyroshell bearing``: the tape flying over a cylindrical head on its air film."""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

from .common import UserError, parameters_from_args, positive_int, print_json, real

#: Columns of ``fields.csv``: the solution's table with its units in the names.
FIELD_COLUMNS = {"x": "x_m", "y": "y_m", "spacing": "spacing_m", "pressure": "pressure_Pa"}


def register(sub, common: argparse.ArgumentParser) -> None:
    from ..bearing import air as a

    p = sub.add_parser(
        "bearing", parents=[common], help="steady head-tape air bearing (flying height)",
        description="Steady flying state of the tape over a cylindrical head of the tape's "
                    "radius R: compressible Reynolds film with slip coupled to the shell "
                    "model, contact where the spacing reaches the roughness. Prints the "
                    "central and minimum spacings (m). Air at 20 C by default; --velocity "
                    "is required here (> 0, e.g. 4). The tape options --spacing, "
                    "--length-ratio, --edges and --load do not apply.")
    g = p.add_argument_group("air bearing (SI units)")
    g.add_argument("--wrap-angle", type=real, default=15.0,
                   help="wrap angle of the tape on the head, degrees, in (0, 90] (default 15)")
    g.add_argument("--viscosity", type=real, default=a.AIR_VISCOSITY,
                   help=f"air viscosity, Pa*s (default {a.AIR_VISCOSITY:g}, air at 20 C)")
    g.add_argument("--ambient-pressure", type=real, default=a.AMBIENT_PRESSURE,
                   help=f"ambient pressure p_a, Pa (default {a.AMBIENT_PRESSURE:g})")
    g.add_argument("--mean-free-path", type=real, default=a.MEAN_FREE_PATH,
                   help=f"mean free path at p_a, m; 0 turns slip off "
                        f"(default {a.MEAN_FREE_PATH:g})")
    g.add_argument("--roughness", type=real, default=a.ROUGHNESS,
                   help=f"combined roughness: the smallest spacing, m "
                        f"(default {a.ROUGHNESS:g})")
    g.add_argument("--incompressible", action="store_true",
                   help="incompressible film (p h -> h) instead of the compressible one")
    g.add_argument("--infinitely-wide", action="store_true",
                   help="1-D infinitely wide tape (per unit width) instead of free edges")
    g.add_argument("--span", type=real, default=None,
                   help="length of each tangent span in the domain, m (default: automatic)")
    g.add_argument("--nx", type=positive_int, default=None,
                   help="intervals along x (default: 2-D, a spacing of 1/15 of the film or "
                        "bending length at the wrap corners, graded to 4x coarser along the "
                        "spans; infinitely wide or --uniform, a uniform 1/12 (2-D: 1/6) of it)")
    g.add_argument("--ny", type=positive_int, default=None,
                   help="intervals across the width, even (default: graded, about 12 um at "
                        "the free edges and 10x coarser in the middle; the edge minimum is "
                        "then within about 0.6 %% of its converged value, see "
                        "docs/bearing.md; --uniform: about 50 um everywhere)")
    g.add_argument("--uniform", action="store_true",
                   help="uniform grid each way instead of the 2-D grid graded towards the "
                        "free edges and the wrap corners (the counts --nx/--ny then set "
                        "uniform spacings)")
    p.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    p.add_argument("--out", metavar="DIR", default=None,
                   help="write summary.json and the spacing/pressure fields (CSV) into DIR")
    p.add_argument("--plot", metavar="FILE.png", default=None,
                   help="write a PNG of the spacing and pressure")
    p.set_defaults(func=run)


def _progress(message: str) -> None:
    """One progress line on stderr."""
    print(message, file=sys.stderr, flush=True)


def run(args: argparse.Namespace) -> int:
    """Solve the steady flying state of the arguments' tape, write the asked outputs (all
    or none) and print the summary (JSON or text). Returns the exit code 0."""
    from ..core.files import (
        PLOT,
        check_output_folder,
        check_outputs,
        folder_transaction,
        transaction,
    )

    if args.velocity <= 0.0:
        raise UserError(f"velocity must be > 0 m/s for an air bearing (e.g. --velocity 4), "
                        f"got {args.velocity:g}")
    params = parameters_from_args(args)
    air = _air(args)
    if args.plot is not None and Path(args.plot).suffix.lower() != ".png":
        raise UserError(f"--plot must name a .png file, got {args.plot!r}")
    check_outputs({"--plot": (args.plot, PLOT)})
    out = None if args.out is None else check_output_folder(args.out, option="--out")
    sol = _solve(_model(args, params, air))
    summary = sol.summary()
    # the angle as typed: degrees -> radians -> degrees need not give it back exactly
    summary["wrap_angle_degrees"] = args.wrap_angle
    # every output, or none (and no folder this run created)
    with transaction() if out is None else folder_transaction(out):
        if out is not None:
            _write_out(out, sol, summary)
        if args.plot is not None:
            from ..bearing.plots import overview
            from ..reproduce._common import save_figure

            save_figure(overview(sol), Path(args.plot))
    if args.json:
        print_json(summary)
    else:
        _print_text(sol)
    return 0


def _air(args: argparse.Namespace):
    """The AirParameters of the arguments."""
    from ..bearing import AirParameters

    return AirParameters(viscosity=args.viscosity, ambient_pressure=args.ambient_pressure,
                         mean_free_path=args.mean_free_path, roughness=args.roughness,
                         compressible=not args.incompressible)


def _model(args: argparse.Namespace, params, air):
    """The BearingModel of the arguments (speed, wrap, grid) on the tape and the air."""
    from ..bearing import BearingModel

    return BearingModel(params, air, velocity=args.velocity,
                        wrap_angle=math.radians(args.wrap_angle),
                        infinitely_wide=args.infinitely_wide, span=args.span, nx=args.nx,
                        ny=args.ny, grading="uniform" if args.uniform else None)


def _solve(model):
    """The steady state, with progress lines on a terminal; a UserError if none is reached."""
    from ..bearing.steady import solve_steady
    from ..core.errors import ConvergenceError
    from ..core.progress import progress_wanted

    show = progress_wanted(None)
    if show:
        _progress(f"gyroshell bearing: {model.unknowns} unknowns ({model!r})")
    try:
        return solve_steady(model, progress=_progress if show else None,
                            iteration_log=_progress if show else None)
    except ConvergenceError as exc:
        raise UserError(f"no steady flying state reached for this input: {exc}") from None


def _print_text(sol) -> None:
    """The headline numbers as text."""
    model = sol.model
    force_unit = "N/m" if model.infinitely_wide else "N"
    x_min, y_min = sol.minimum_location
    where = f"x = {x_min:.4e} m" + ("" if y_min is None else f", y = {y_min:.4e} m")
    print(f"model:            {model!r}")
    print(f"central spacing:  {sol.central_spacing:.6e} m")
    print(f"minimum spacing:  {sol.minimum_spacing:.6e} m at {where}")
    print(f"air force:        {sol.air_force:.6e} {force_unit}")
    print(f"contact force:    {sol.contact_force:.6e} {force_unit} ({sol.contact_nodes} nodes)")
    print(f"Newton:           {sol.info.iterations} iterations, {sol.info.seconds:.2f} s")


def _write_out(out: Path, sol, summary: dict) -> None:
    """fields.csv (the solution's table) and summary.json into the folder ``out``."""
    from ..core.files import write_atomic

    fields = sol.to_frame().rename(columns=FIELD_COLUMNS)
    write_atomic(out / "fields.csv", lambda tmp: fields.to_csv(tmp, index=False))
    write_atomic(out / "summary.json",
                 lambda tmp: tmp.write_text(json.dumps(summary, indent=1) + "\n"))
