"""``gyroshell static``: the static deflection under the Gaussian load."""

from __future__ import annotations

import argparse

from .common import print_json, tape_from_args
from .saving import (
    add_plot_option,
    add_save_option,
    check_plot_path,
    check_save_path,
    save_result,
    write_plot,
)


def register(sub, common: argparse.ArgumentParser,
             common_without_velocity: argparse.ArgumentParser) -> None:
    p = sub.add_parser(
        "static", parents=[common], help="static deflection K(V) w = F under the load",
        description="Static deflection of the tape under the Gaussian load of Eq. 17 at speed "
                    "V (below the critical speed). Prints the load-point and maximum "
                    "deflections, m.")
    p.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    add_save_option(p)
    add_plot_option(p, "the deflection w(x, y), m")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    params, velocity, grid = tape_from_args(args)
    from ..results.static import StaticSolution

    check_save_path(args.save, StaticSolution)  # not a table: .nc only, refused now
    check_plot_path(args.plot)
    from ..engines.static import solve_static
    from ..tape.model import TapeModel

    model = TapeModel(params, grid)
    sol = solve_static(model, velocity)
    from ..core.files import transaction

    with transaction():  # every output, or none
        save_result(args.save, sol, params)
        write_plot(args.plot, sol)
    g = model.grid
    if args.json:
        print_json(sol.summary())
    else:
        print(f"grid: {g.nx} x {g.ny} intervals, spacing {g.hx:.6g} m x {g.hy:.6g} m, "
              f"{g.unknowns} unknowns, {g.edges} edges")
        print(f"velocity:              {velocity:g} m/s")
        print(f"load-point deflection: {sol.load_point_deflection:.6e} m")
        print(f"maximum deflection:    {sol.max_deflection:.6e} m")
        if args.plot:
            print(f"wrote {args.plot}")
    return 0
