"""``gyroshell transient``: Newmark time march under the step load; load-point history CSV."""

from __future__ import annotations

import argparse
import sys
import warnings

from .common import UserError, parameters_from_args, positive_int, print_json, real
from .loading import add_damping_options, add_load_options, damping_from_args, load_from_args
from .saving import (
    add_plot_option,
    add_save_option,
    check_plot_path,
    check_save_path,
    save_result,
    write_plot,
)

#: --backend values: "auto" and the names of gyroshell.linalg.factorization.BACKENDS (not imported
#: here, so that parsing and refusals do not load scipy).
BACKEND_CHOICES: tuple[str, ...] = ("auto", "superlu", "umfpack", "pardiso", "banded")


def register(sub, common: argparse.ArgumentParser,
             common_without_velocity: argparse.ArgumentParser) -> None:
    p = sub.add_parser(
        "transient", parents=[common],
        help="transient response to the step load or moving heads (Newmark)",
        description="March M a + G v + K w = H(t) F with Newmark's method (paper Eqs. 10-16) "
                    "from rest at the wrapped equilibrium. Writes the load-point displacement "
                    "history (CSV: t in s, w in m) and, if asked, full-field snapshots (.npz).")
    p.add_argument("--steps", type=positive_int, required=True, help="number of time steps")
    p.add_argument("--dt", type=real, required=True, help="time step, s, > 0 (paper: 2e-6)")
    p.add_argument("--beta", type=real, default=0.25,
                   help="Newmark beta (default 1/4; 1 with gamma 3/2 damps to steady state)")
    p.add_argument("--gamma", type=real, default=0.5, help="Newmark gamma (default 1/2)")
    p.add_argument("--out", metavar="FILE.csv", default=None,
                   help="write the load-point history: columns t (s), w (m), one row per step "
                        "including t = 0 (CSV, or Parquet for a .parquet file)")
    p.add_argument("--snapshot-every", metavar="N", type=positive_int, default=None,
                   help="keep the full field w (m) every N steps (needs --snapshots)")
    p.add_argument("--snapshots", metavar="FILE.npz", default=None,
                   help="write the snapshots: x, y (m), times (s), fields (m)")
    p.add_argument("--backend", default="auto", choices=BACKEND_CHOICES,
                   help="sparse LU back-end (default auto)")
    p.add_argument("--no-symmetry", action="store_true",
                   help="march all the unknowns even when the tape, load and damping are "
                        "mirror symmetric about y = L_y/2 (by default the symmetric half is "
                        "marched then: the same answer to round-off, about half the time)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument("--json", action="store_true", help="print one JSON summary (SI units)")
    add_save_option(p)
    add_plot_option(p, "the load-point displacement against time (m, s)")
    add_load_options(p)
    add_damping_options(p)
    p.set_defaults(func=run)


def _stiffness_scale(model, velocity: float) -> float:
    """Largest |K_ii|, N/m: the size of the βΔt² K term in Newmark's matrix."""
    import numpy as np

    return float(np.abs(model.K(velocity).diagonal()).max())


#: Warn from this fraction of the critical-speed estimate on: the estimate (width-uniform
#: modes) lies slightly above the true divergence speed when ν > 0.
WARNING_FRACTION = 0.99


def _warn_if_supercritical(model, velocity: float) -> None:
    """One warning line when V is above or near the critical speed: the run is legal, but
    above critical its displacement grows without bound."""
    estimate = model.divergence_speed_estimate()
    if velocity >= WARNING_FRACTION * estimate:
        where = "above" if velocity >= estimate else \
            f"within {100 * (1 - WARNING_FRACTION):g} % of"
        print(f"gyroshell: warning: V = {velocity:g} m/s is {where} the critical speed (about "
              f"{estimate:.5g} m/s, an upper estimate); above it the displacement grows "
              "without bound", file=sys.stderr)


def _check_snapshots(args: argparse.Namespace) -> None:
    """--snapshot-every and --snapshots: both or neither, a kept field after t = 0, .npz."""
    if (args.snapshot_every is None) != (args.snapshots is None):
        raise UserError("--snapshot-every and --snapshots go together")
    if args.snapshot_every is not None and args.snapshot_every > args.steps:
        raise UserError(f"--snapshot-every must be <= --steps ({args.steps}), got "
                        f"{args.snapshot_every}: only the field at rest (t = 0) would be kept")
    if args.snapshots is not None and not args.snapshots.lower().endswith(".npz"):
        raise UserError(f"--snapshots must be a .npz file, got {args.snapshots}")


def _warn_if_conditionally_stable(beta: float, gamma: float) -> None:
    """One warning line (instead of Python's two) outside 2 beta >= gamma >= 1/2."""
    if not 2.0 * beta >= gamma >= 0.5:
        print(f"gyroshell: warning: beta = {beta:g}, gamma = {gamma:g} lie outside the "
              "unconditionally stable region 2 beta >= gamma >= 1/2: the march is stable "
              "only for small enough dt", file=sys.stderr)


def _marched(info: dict) -> str:
    """What the march moved: all the unknowns, or the mirror-symmetric half."""
    if info.get("symmetry") == "half":
        return f"the symmetric half ({info['marched_unknowns']} unknowns)"
    return "all the unknowns"


def run(args: argparse.Namespace) -> int:
    from ..core import budget, files, validation
    from ..tape.grid import Grid

    _check_snapshots(args)
    params = parameters_from_args(args)
    velocity = params.check_velocity(args.velocity)
    validation.time_step(args.dt, args.beta)
    from ..results.base import TABLE_SUFFIXES
    from ..results.transient import TransientResult

    files.check_outputs({"--out": (args.out, TABLE_SUFFIXES),
                         "--snapshots": (args.snapshots, None), "--save": (args.save, None),
                         "--plot": (args.plot, files.PLOT)})
    check_save_path(args.save, TransientResult)
    check_plot_path(args.plot)
    grid = Grid.from_parameters(params)
    load, damping = load_from_args(args, params, args.dt), damping_from_args(args)
    budget.check_transient(grid.nx, grid.ny, grid.edges, args.steps,
                           fields=budget.snapshot_count(args.steps, args.snapshot_every),
                           heads=0 if load is None else 1)
    from ..engines.newmark import NewmarkStabilityWarning, march
    from ..tape.model import TapeModel

    model = TapeModel(params, grid)
    validation.time_step(args.dt, args.beta, stiffness_scale=_stiffness_scale(model, velocity))
    _warn_if_supercritical(model, velocity)
    _warn_if_conditionally_stable(args.beta, args.gamma)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NewmarkStabilityWarning)  # said above, in one line
        result = march(model, velocity, dt=args.dt, steps=args.steps, beta=args.beta,
                       gamma=args.gamma, backend=args.backend, damping=damping, load=load,
                       snapshot_every=args.snapshot_every, symmetry=not args.no_symmetry,
                       progress=False if args.quiet else None)
    with files.transaction():
        if args.out is not None:
            result.to_csv(args.out)
        if args.snapshots is not None:
            result.save_snapshots(args.snapshots)
        save_result(args.save, result, params)
        write_plot(args.plot, result)
    g, info, w = model.grid, result.info, result.load_point
    if args.json:  # the output paths are the command's, not the run's
        print_json({**result.summary(), "out": args.out, "snapshots": args.snapshots,
                    "plot": args.plot})
    else:
        print(f"grid: {g.nx} x {g.ny} intervals, {g.unknowns} unknowns; V = {result.velocity:g} "
              f"m/s, dt = {result.dt:g} s, {result.steps} steps, beta = {result.beta:g}, "
              f"gamma = {result.gamma:g}")
        print(f"load-point displacement: final {w[-1]:.6e} m, range [{w.min():.6e}, "
              f"{w.max():.6e}] m")
        print(f"time: factor {info['factor_time']:.3g} s ({info['backend']}), march "
              f"{info['loop_time']:.3g} s ({1e3 * info['step_time']:.3g} ms/step) on "
              f"{_marched(info)}")
        for label, path in (("history", args.out), ("snapshots", args.snapshots),
                            ("plot", args.plot)):
            if path is not None:
                print(f"{label}: {path}")
    return 0
