"""``gyroshell frf``: frequency response (amplitude and phase) to a harmonic load."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from .common import (
    RANGE_HELP,
    UserError,
    grid_of,
    parameters_from_args,
    positive_int,
    print_json,
    real,
)
from .loading import add_damping_options, damping_from_args, pair
from .saving import add_save_option, check_save_path, save_result


def register(sub, common: argparse.ArgumentParser) -> None:
    p = sub.add_parser(
        "frf", parents=[common], help="frequency response to a harmonic load (Bode plot)",
        description="Steady response W e^(i omega t) to the Gaussian load P_0 e^(i omega t) "
                    "(Eq. 17): (K - omega^2 M + i omega (G + C)) W = F at each angular "
                    "frequency, at the load centroid and any probe points. Amplitude in m "
                    "(for the peak pressure --load), phase in rad (negative: lagging). "
                    "Many frequencies use a reduced (rational Krylov) model whose error is "
                    "estimated; direct solves take over wherever it is above --tol.")
    p.add_argument("--frequencies", required=True, metavar="START:STOP:NUM",
                   help=f"angular frequencies, rad/s: {RANGE_HELP}; START <= STOP")
    p.add_argument("--probe", metavar="X,Y", type=pair, action="append", default=[],
                   help="extra response point, m (repeatable)")
    p.add_argument("--method", choices=("auto", "direct", "reduced"), default="auto",
                   help="auto (default): reduced model, direct solves where it is not "
                        "accurate enough; direct: one sparse LU per frequency; reduced: the "
                        "reduced model alone, with its estimated error")
    p.add_argument("--tol", type=real, default=None,
                   help="target relative error of the reduced model, in (1e-8, 0.1] "
                        "(default 1e-6; not with --method direct)")
    p.add_argument("--max-points", type=positive_int, default=None,
                   help="most interpolation frequencies (factorizations) of the reduced "
                        "model, at most 100 (default 40; not with --method direct)")
    p.add_argument("--out", metavar="FILE.csv", default=None,
                   help="write omega (rad/s), frequency (Hz), amplitude (m), phase (rad), "
                        "method, error_estimate, and amplitude_k, phase_k per probe (CSV, "
                        "or Parquet for a .parquet file)")
    p.add_argument("--plot", metavar="FILE.png", default=None, help="write a Bode plot (PNG)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    add_save_option(p)
    add_damping_options(p)
    p.set_defaults(func=run)


def _check_outputs(out: str | None, plot: str | None, save: str | None = None) -> None:
    """Fail before computing if an output could never be written (or two are one file)."""
    from ..core.files import PLOT, check_outputs
    from ..results.base import TABLE_SUFFIXES

    if plot is not None and Path(plot).suffix.lower() != ".png":
        raise UserError(f"--plot must be a .png file, got {plot}")
    check_outputs({"--out": (out, TABLE_SUFFIXES), "--plot": (plot, PLOT),
                   "--save": (save, None)})


def _reduced_options(args: argparse.Namespace) -> tuple[float, int]:
    """--tol and --max-points, checked (refused with --method direct, which ignores them)."""
    from ..engines.frequency_options import DEFAULT_TOL, MAX_POINTS, check_options

    if args.method == "direct":
        typed = [flag for flag, value in (("--tol", args.tol), ("--max-points", args.max_points))
                 if value is not None]
        if typed:
            verb = "sets" if len(typed) == 1 else "set"
            raise UserError(f"{' and '.join(typed)} {verb} the reduced model; --method direct "
                            "solves every frequency without one")
    tol = DEFAULT_TOL if args.tol is None else args.tol
    return check_options(args.method, tol,
                         MAX_POINTS if args.max_points is None else args.max_points)


def run(args: argparse.Namespace) -> int:
    from ..engines.frequency_options import check_frequencies, parse_frequencies

    params = parameters_from_args(args)
    velocity = params.check_velocity(args.velocity)
    omega = check_frequencies(parse_frequencies(args.frequencies), density=params.density)
    tol, max_points = _reduced_options(args)
    damping = damping_from_args(args)
    _check_outputs(args.out, args.plot, args.save)
    from ..results.frequency_response import FrequencyResponse

    check_save_path(args.save, FrequencyResponse)
    grid = grid_of(params)
    for x, y in args.probe:  # every probe on the tape, before anything is assembled
        grid.interpolation_row(x, y)
    from ..engines.frequency_response import frequency_response
    from ..tape.model import TapeModel

    model = TapeModel(params, grid)
    start = time.perf_counter()
    result = frequency_response(model, velocity, omega, damping=damping, probes=args.probe,
                                method=args.method, tol=tol, max_points=max_points,
                                progress=False if args.quiet else None)
    elapsed = time.perf_counter() - start
    from ..core.files import transaction

    with transaction():  # every file, or none
        save_result(args.save, result, params)
        if args.out is not None:
            result.to_csv(args.out)
        if args.plot is not None:
            _plot(result, params, damping, args.plot)
    info = result.info
    if args.json:  # the wall time and output paths are the command's, not the response's
        print_json({**result.summary(), "seconds": elapsed, "out": args.out,
                    "plot": args.plot, "save": args.save})
        return 0
    g = model.grid
    print(f"grid: {g.nx} x {g.ny} intervals, {g.unknowns} unknowns; V = {velocity:g} m/s; "
          f"{len(omega)} frequencies in [{omega.min():g}, {omega.max():g}] rad/s")
    print(f"method: {info['factorizations']} factorizations ({info['direct_solves']} direct "
          f"solves), reduced basis {info['basis_size']}, largest estimated relative error "
          f"{result.error_estimate.max():.2e}; {elapsed:.2f} s")
    k = int(result.amplitude[:, 0].argmax())
    print(f"load point: largest amplitude {result.amplitude[k, 0]:.6e} m at omega = "
          f"{result.omega[k]:.6g} rad/s")
    if args.out is None:
        print(f"{'omega (rad/s)':>14} {'amplitude (m)':>14} {'phase (rad)':>12}")
        step = max(1, len(omega) // 20)
        for i in range(0, len(omega), step):
            print(f"{result.omega[i]:14.6g} {result.amplitude[i, 0]:14.6e} "
                  f"{result.phase[i, 0]:12.6f}")
    for label, path in (("table", args.out), ("plot", args.plot), ("saved", args.save)):
        if path is not None:
            print(f"{label}: {path}")
    return 0


def _plot(result, params, damping, path: str) -> None:
    from ..core.files import write_atomic
    from ..reproduce._common import pyplot

    plt = pyplot()
    fig, ax = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    result.plot(ax)
    ax[0].legend(fontsize=8)
    ax[0].set_title(f"Frequency response, V = {result.velocity:g} m/s, L_x/L_y = "
                    f"{params.length_ratio:g}, c = {damping.viscous:g} N·s/m³")
    fig.tight_layout()
    try:
        write_atomic(path, lambda tmp: fig.savefig(tmp, dpi=110, format="png"))
    finally:
        plt.close(fig)
