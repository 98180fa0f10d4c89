"""``gyroshell modes``, ``critical`` and ``sweep``: the quadratic eigen-solver from the shell."""

from __future__ import annotations

import argparse
import time

import numpy as np

from ..core.files import PLOT, check_outputs, transaction
from .common import (
    RANGE_HELP,
    grid_of,
    parameters_from_args,
    parse_velocities,
    positive_int,
    print_json,
    tape_from_args,
)
from .loading import add_damping_options, damping_from_args
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
        "modes", parents=[common], help="lowest frequencies and periods at speed V",
        description="Lowest angular frequencies (rad/s), frequencies (Hz) and periods (s) of "
                    "(lambda^2 M + lambda G + K) phi = 0 at the tape speed --velocity (m/s).")
    p.add_argument("--count", type=positive_int, default=6,
                   help="number of frequencies, >= 1 (default 6)")
    add_damping_options(p)
    p.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    add_save_option(p)
    add_plot_option(p, "the first mode's shape (its real part, normalized)")
    p.set_defaults(func=run_modes)

    p = sub.add_parser(
        "critical", parents=[common_without_velocity],
        help="critical speed, two ways, with context values",
        description="Critical tape speed (m/s): (a) where the lowest frequency reaches zero "
                    "(eigen-solves and root-finding) and (b) the divergence speed "
                    "sqrt((T + mu_min)/rho) (one eigsh), beside sqrt(T/rho), the strip value "
                    "sqrt((T + 2 sqrt(D k))/rho), Sundaram & Benson's 111 m/s and the paper's "
                    "'just above 100 m/s'.")
    p.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    add_save_option(p)
    add_plot_option(p, "the critical speeds beside their context values (m/s)")
    p.set_defaults(func=run_critical)

    p = sub.add_parser(
        "sweep", parents=[common_without_velocity],
        help="frequencies against tape speed (CSV, plot)",
        description="Lowest frequencies (rad/s) at a list of tape speeds (m/s), tracked into "
                    "branches by mode-shape correlation.")
    p.add_argument("--velocities", default="0:100:11", metavar="START:STOP:NUM",
                   help=f"speeds, m/s: {RANGE_HELP}; finite, >= 0, each once (in any "
                        "order), at most 10000 of them (default 0:100:11: every 10 m/s). "
                        "Until release 0.3 the old START:STOP:STEP is still read where it "
                        "gives other speeds (0:100:10: 11 speeds), with a notice")
    p.add_argument("--count", type=positive_int, default=6,
                   help="frequencies per speed, >= 1 (default 6)")
    p.add_argument("--workers", type=positive_int, default=1,
                   help="local processes, at most 4 per CPU: the speeds are split into "
                        "that many contiguous runs, each continued in its own process "
                        "(default 1)")
    p.add_argument("--out", metavar="FILE.csv",
                   help="write the table: CSV, or Parquet for a .parquet file")
    p.add_argument("--plot", metavar="FILE.png", help="write omega (rad/s) against V (m/s)")
    add_save_option(p)
    p.add_argument("--quiet", action="store_true",
                   help="no progress (a bar on a terminal, else one line per stage)")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (speeds, branches, speed range in m/s, the "
                        "lowest omega in rad/s, stability classes) instead of the table")
    p.set_defaults(func=run_sweep)


def run_modes(args: argparse.Namespace) -> int:
    params, velocity, grid = tape_from_args(args)
    from ..results.modes import Modes

    check_save_path(args.save, Modes)
    check_plot_path(args.plot)
    check_outputs({"--save": (args.save, None), "--plot": (args.plot, PLOT)})
    from ..engines.eigen import modes
    from ..tape.model import TapeModel

    model = TapeModel(params, grid)
    t0 = time.perf_counter()
    damping = damping_from_args(args)
    res = modes(model, velocity, args.count, damping=None if damping.is_zero else damping)
    elapsed = time.perf_counter() - t0
    with transaction():  # every output, or none
        save_result(args.save, res, params)
        write_plot(args.plot, res)
    g = model.grid
    out = {**res.summary(), "damping": damping.viscous,
           "rayleigh": [damping.mass_coefficient, damping.stiffness_coefficient],
           "foundation_frequency": params.foundation_frequency, "seconds": elapsed}
    if args.json:
        print_json(out)
        return 0
    print(f"grid: {g.nx} x {g.ny} intervals, {g.unknowns} unknowns, {g.edges} edges; "
          f"V = {velocity:g} m/s" + ("" if damping.is_zero else
                                     f", damping c = {damping.viscous:g} N*s/m^3, Rayleigh "
                                     f"a = {damping.mass_coefficient:g} 1/s, "
                                     f"b = {damping.stiffness_coefficient:g} s"))
    diagnosis = stability_sentence(res)
    if diagnosis:
        print(diagnosis)
    damped = res.damped
    print(f"{'#':>3} {'omega (rad/s)':>16} {'f (Hz)':>14} {'period (s)':>14} "
          f"{'decay (1/s)' if damped else 'growth (1/s)':>13} "
          f"{'zeta' if damped else '':>9} {'residual':>9}")
    for i in range(res.count):
        rate = res.decay_rate[i] if damped else res.growth_rate[i]
        zeta = f"{res.damping_ratio[i]:9.3g}" if damped else " " * 9
        print(f"{i + 1:>3} {res.omega[i]:16.8g} {res.frequency[i]:14.8g} "
              f"{res.period[i]:14.6e} {rate:13.6g} {zeta} {res.residuals[i]:9.1e}")
    print(f"sqrt(k/rho) = {params.foundation_frequency:.8g} rad/s; solved in {elapsed:.2f} s")
    return 0


def stability_sentence(res) -> str:
    """One line saying what the computed eigenvalues show (empty when stable below critical)."""
    growing = int(np.count_nonzero(res.growth_rate > 0))
    if res.stability == "divergence":
        real = int(np.count_nonzero((res.growth_rate > 0) & (res.omega == 0)))
        return (f"unstable: the tape diverges (K(V) indefinite; {real} real positive "
                f"eigenvalue(s) among those shown, largest growth rate "
                f"{res.growth_rate.max():.6g} 1/s)")
    if res.stability == "flutter":
        return (f"unstable: the tape flutters ({growing} complex eigenvalue(s) with positive "
                f"real part among those shown, largest growth rate "
                f"{res.growth_rate.max():.6g} 1/s)")
    if res.supercritical:
        return ("supercritical: K(V) is indefinite, yet every eigenvalue shown is on the "
                "imaginary axis: gyroscopically stable at this speed")
    return ""


def run_critical(args: argparse.Namespace) -> int:
    params = parameters_from_args(args)
    from ..results.critical import CriticalSpeeds

    check_save_path(args.save, CriticalSpeeds)
    check_plot_path(args.plot)
    check_outputs({"--save": (args.save, None), "--plot": (args.plot, PLOT)})
    grid = grid_of(params)
    from ..engines.critical import critical_speeds
    from ..tape.model import TapeModel

    model = TapeModel(params, grid)
    t0 = time.perf_counter()
    c = critical_speeds(model)
    elapsed = time.perf_counter() - t0
    with transaction():  # every output, or none
        save_result(args.save, c, params)
        write_plot(args.plot, c)
    out = dict(c.summary(), seconds=elapsed, length_ratio=params.length_ratio,
               edges=params.edges, unknowns=model.unknowns)
    if args.json:
        print_json(out)
        return 0
    g = model.grid
    print(f"grid: {g.nx} x {g.ny} intervals, {g.unknowns} unknowns, {g.edges} edges, "
          f"L_x/L_y = {params.length_ratio:g}")
    print(f"critical speed (a), lowest frequency -> 0:   {c.critical_speed:.9g} m/s "
          f"({c.info['evaluations']} eigen-solves, {c.info['critical_time']:.2f} s)")
    print(f"divergence speed (b), sqrt((T + mu)/rho):    {c.divergence_speed:.9g} m/s "
          f"(mu = {c.info['mu']:.6g} N/m, {c.info['divergence_time']:.2f} s)")
    print(f"relative difference |a - b| / b:             {c.relative_difference:.1e}")
    print("context:")
    print(f"  string/beam sqrt(T/rho) (Wickert & Mote):   {c.string_speed:.6g} m/s")
    print(f"  strip on foundation sqrt((T+2sqrt(Dk))/rho): {c.strip_speed:.6g} m/s")
    print(f"  Sundaram & Benson (all sides s.s.):         {c.sundaram_benson_speed:g} m/s")
    print(f"  seed paper ('just above'):                  {c.paper_speed:g} m/s")
    print(f"total {elapsed:.2f} s")
    return 0


def run_sweep(args: argparse.Namespace) -> int:
    from ..core.parallel import check_process_count
    from ..results.base import TABLE_SUFFIXES
    from ..studies.sweep import SweepResult, check_velocities

    params = parameters_from_args(args)
    velocities = check_velocities([params.check_velocity(v) for v in
                                   parse_velocities(args.velocities)], name="--velocities")
    check_process_count("--workers", args.workers)
    check_outputs({"--out": (args.out, TABLE_SUFFIXES), "--plot": (args.plot, PLOT),
                   "--save": (args.save, None)})
    check_save_path(args.save, SweepResult)
    grid = grid_of(params)
    from ..studies.sweep import plot_sweep, sweep
    from ..tape.model import TapeModel

    model = TapeModel(params, grid)
    result = sweep(model, velocities, args.count, progress=False if args.quiet else None,
                   workers=args.workers)
    text = None if args.out or args.json else _sweep_text(result.table)  # what can fail
    with transaction():  # every output of the run, or none
        save_result(args.save, result, params)
        if args.out:
            result.save(args.out)
        if args.plot:
            plot_sweep(result, args.plot,
                       title=f"L_x/L_y = {params.length_ratio:g}, {params.edges} edges")
    if args.json:
        print_json({**result.summary(), "out": args.out, "plot": args.plot,
                    "save": args.save})
        return 0
    if text is not None:
        print(text)
    else:
        print(f"wrote {args.out} ({len(result.table)} rows)")
    if args.plot:
        print(f"wrote {args.plot}")
    return 0


def _sweep_text(frame) -> str:
    """The printed sweep: one row per speed (m/s, ascending), one column per rank
    of ω (rad/s)."""
    table = frame.pivot(index="velocity", columns="rank", values="omega")
    table.columns = [f"omega_{c + 1}" for c in table.columns]
    return ("angular frequencies, rad/s, at each speed V, m/s (ascending below critical;"
            " above it ordered by |lambda|, nearest zero first)\n"
            + table.to_string(float_format=lambda x: f"{x:.6g}"))
