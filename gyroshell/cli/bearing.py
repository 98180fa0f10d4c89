"""``gyroshell bearing``: the tape flying over a head on its air film: a cylinder (the
default), a flat head of one or more modules, or a measured contour (``--head``, the head
options of :mod:`.heads` and the ``[head]`` table of ``--config``).

The bearing has its own tape options: the physical ones of the other sub-commands, without
the plate grid's ``--spacing``, ``--length-ratio`` and ``--edges`` (the bearing sizes its
own grid with ``--nx``/``--ny``; its tape has free edges or is infinitely wide) and without
``--load`` (its load is the air film). Every option it offers changes the run; one that
means nothing in the chosen mode (``--ny``, ``--uniform`` or ``--width`` with
``--infinitely-wide``, ...) is refused in one line. All inputs and every output target are
checked before the solve. Unless ``--quiet``, the solve reports on stderr, on a terminal
or not, one line per stage: the model's size and an estimate of the time at the start, then
one line per Newton iteration, pseudo-time step and continuation stage.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

from .common import (
    TAPE_OVERRIDES,
    UserError,
    add_out_dir_option,
    add_tape_overrides,
    positive_int,
    print_json,
    real,
    typed_overrides,
    warnings_as_lines,
)
from .heads import add_head_options, build_head_of, head_design
from .interface import (
    add_interface_options,
    air_of,
    check_recession,
    contact_of,
    refuse_film_options_when_dry,
)
from .saving import add_save_option, check_save_path, save_result

#: Columns of ``fields.csv``: the solution's table with its units in the names.
FIELD_COLUMNS = {"x": "x_m", "y": "y_m", "spacing": "spacing_m", "pressure": "pressure_Pa"}
#: The files ``--out-dir DIR`` writes: the summary, the fields, and the readings' tables (the
#: spacing across the width along each transducer line; each corner's contact and tents).
OUT_FILES = ("summary.json", "fields.csv", "transducer_lines.csv", "corners.csv")
#: The tape options of the bearing: those of the plate sub-commands but ``--load``.
TAPE_OPTIONS = tuple(option for option in TAPE_OVERRIDES if option[1] != "load")
#: The plate fields a --config file may set that the bearing does not use (replaced).
PLATE_ONLY_FIELDS = ("length_ratio", "spacing", "load", "load_x", "load_y")
#: Intervals across the width of the (unused) plate grid of the bearing's TapeParameters:
#: its spacing is set to width / this, so that no plate-grid check can refuse a tape the
#: bearing can fly.
PLATE_INTERVALS = 41
#: Seconds of one Newton iteration that factors the Jacobian afresh, measured by
#: benchmarks/bench_bearing_cli.py (2-core machine, shared): 1-D, a constant plus this much
#: per unknown; 2-D, per unknown this much plus that much per interval across (the
#: factor's fill grows with the width of the half-width grid Newton solves on). The 2-D
#: figures since the grid's nested dissection (issue 21): on 7,960 to 114,552 unknowns
#: the first iteration measured 0.46-0.50x these estimates in a quiet minute and
#: 0.98-1.09x in a loaded one (two runs of the benchmark at load 4).
SECONDS_1D = (5e-3, 6e-6)
SECONDS_2D = (6e-6, 6e-8)
#: A usual solve costs between this few and this many such iterations (chord steps near
#: the solution are cheaper; the 2-D starting state costs a few; a contact set that keeps
#: changing costs one each, 22 at 0.01 m/s); more when pseudo-time or the continuation in
#: V are needed.
USUAL_FACTORIZATIONS = (2, 15)
#: Under a smooth contact law (asperities or a measured curve) a usual solve costs about
#: this many times :func:`iteration_seconds` (infinitely wide, 2-D): the infinitely wide
#: tape takes 5-20 Newton iterations whose residuals (the Boltzmann flow factor, the
#: asperity law) cost about as much as its banded LU; a 2-D tape takes its coarse grids'
#: start (about one fine factorization's worth) and 3-5 iterations on its own grid, of
#: which chord steps factor 1-2. Measured (benchmarks/bench_heads_2d.py, fresh processes,
#: the 2-core machine shared): 2-D, 0.93-2.2 times at load 3.5-4 (the cylinder and 1-3
#: flat modules, 114,552-383,600 unknowns) and 1.9-7.7 times at load 6-10; the centre is
#: their geometric middle, so that both ends lie within the band.
SMOOTH_FACTORIZATIONS = (6.0, 2.7)
#: ... plus, infinitely wide, this much for the first solve in a fresh process (the
#: imports and caches its first iteration fills), s: measured, the default flat module's
#: and cylinder's 1-D solves took 0.07-0.09 s at load 3.5 and up to 0.36 s at load 12.
SMOOTH_FIRST_SECONDS = 0.07
#: The band printed around the central estimate of a smooth law's solve: divided and
#: multiplied by this (the time estimates hold within a factor of 3).
SMOOTH_BAND = 3.0


def register(sub, common: argparse.ArgumentParser) -> None:
    """Add ``bearing`` to ``sub``. ``common`` (the plate sub-commands' tape options) is not
    used: the bearing has no plate grid and no load (see the module docstring)."""
    del common
    p = sub.add_parser(
        "bearing", parents=[_tape_parser()], help="steady head-tape air bearing (flying height)",
        description="Steady flying state of the tape over a head (--head: a cylinder of the "
                    "tape's radius R by default, a flat head with sharp or rounded corners "
                    "and one or more modules, or a measured contour): compressible Reynolds "
                    "film with slip coupled to the shell model, contact where the spacing "
                    "reaches the roughness. Prints the central and minimum spacings (m) and "
                    "the head's readings (transducer lines, tents, corner forces, drag). "
                    "Air at 20 C by default; --velocity "
                    "is required here (> 0, e.g. 4). The bearing sizes its own grid "
                    "(--nx, --ny): the plate grid's --spacing, --length-ratio and --edges "
                    "and the plate load --load do not exist here.")
    add_head_options(p)
    _add_bearing_options(p)
    add_interface_options(p)
    p.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    add_out_dir_option(p, "write summary.json, the spacing/pressure fields (fields.csv), "
                          "the spacing across the width along each transducer line "
                          "(transducer_lines.csv) and each corner's contact force and tents "
                          "(corners.csv) into DIR (created if missing; its parent must "
                          "exist)")
    p.add_argument("--plot", metavar="FILE.png", default=None,
                   help="write a PNG of the spacing and pressure (over a flat or measured "
                        "head, or with --transducers: the head's contour, the spacing over "
                        "its lands and corners and the transducer lines across the width)")
    add_save_option(p, what="the steady state")
    p.add_argument("--error-estimate", action="store_true",
                   help="also solve on a grid with half the intervals each way and report "
                        "the differences of the spacings (central, minimum, each transducer "
                        "line's minimum and mean), m, as grid_error: about the grid's own "
                        "error if the readings converge at first order, three times it at "
                        "second (costs about a quarter of the solve more)")
    p.add_argument("--quiet", action="store_true",
                   help="no progress lines (by default stderr gets the model's size and an "
                        "estimate of the time, then one line per Newton iteration and stage)")
    p.set_defaults(func=run)


def _tape_parser() -> argparse.ArgumentParser:
    """Parent parser with the bearing's tape options (all default None: not typed)."""
    p = argparse.ArgumentParser(add_help=False)
    g = p.add_argument_group("tape (SI units; defaults: the paper's Table 1)")
    g.add_argument("--config", metavar="TAPE.toml", default=None,
                   help="tape definition file (TOML, values with units, e.g. tension = "
                        "\"90 N/m\"); options given here override it; its plate-grid and "
                        "load keys (spacing, length_ratio, load, load_x, load_y) do not "
                        "apply to the bearing (the file is still checked whole)")
    g.add_argument("--velocity", type=real, default=None,
                   help="tape speed V, m/s, nonzero, abs(V) below the string speed "
                        "sqrt(T/rho); negative: the tape runs along -x (reversed) "
                        "(required, here or as velocity in --config)")
    add_tape_overrides(g, TAPE_OPTIONS, help_of={
        "width": "tape width L_y, m (default 6.35e-3; not with --infinitely-wide)"})
    return p


#: The choices of --factorization (gyroshell.linalg.factorization.PATTERN_LU, spelled out
#: so that the options are refused before scipy is imported).
FACTORIZATION_CHOICES: tuple[str, ...] = ("auto", "grid", "metis", "mmd", "colamd",
                                           "pardiso")


def _add_bearing_options(p: argparse.ArgumentParser) -> None:
    """The air, head and grid options."""
    from ..bearing import air as a

    g = p.add_argument_group("air bearing (SI units)")
    g.add_argument("--viscosity", type=real, default=None,
                   help=f"air viscosity, Pa*s (default: the file's [air] table, else "
                        f"{a.AIR_VISCOSITY:g}, air at 20 C)")
    g.add_argument("--ambient-pressure", type=real, default=None,
                   help=f"ambient pressure p_a, Pa (default: the file's [air] table, else "
                        f"{a.AMBIENT_PRESSURE:g})")
    g.add_argument("--mean-free-path", type=real, default=None,
                   help=f"mean free path at p_a, m; 0 turns rarefaction off (default: the "
                        f"file's [air] table, else {a.MEAN_FREE_PATH:g})")
    g.add_argument("--incompressible", action="store_true",
                   help="incompressible film (p h -> h) instead of the compressible one")
    g.add_argument("--infinitely-wide", action="store_true",
                   help="1-D infinitely wide tape (per unit width) instead of free edges; "
                        "its grid is uniform along x (no --ny, --uniform or --width)")
    g.add_argument("--span", type=real, default=None,
                   help="length of each tangent span in the domain, m (default: automatic)")
    g.add_argument("--nx", type=positive_int, default=None,
                   help="intervals along x (default: 2-D, a spacing of 1/15 of the film or "
                        "bending length at the wrap corners, graded to 4x coarser along the "
                        "spans; infinitely wide or --uniform, a uniform 1/12 (2-D: 1/6) of it)")
    g.add_argument("--ny", type=positive_int, default=None,
                   help="intervals across the width, even, 2-D only (default: graded, about "
                        "12 um at the free edges and 10x coarser in the middle; the edge "
                        "minimum is then within about 0.6 %% of its converged value, see "
                        "docs/theory/bearing.md; --uniform: about 50 um everywhere)")
    g.add_argument("--uniform", action="store_true",
                   help="2-D only: uniform grid each way instead of the grid graded towards "
                        "the free edges and the wrap corners (the counts --nx/--ny then set "
                        "uniform spacings)")
    g.add_argument("--factorization", choices=FACTORIZATION_CHOICES, default="auto",
                   help="sparse LU of Newton's Jacobian: grid (SuperLU, diagonal pivots, "
                        "nested dissection along the grid's node lines once per grid, pure "
                        "scipy), metis (the same with METIS's ordering; needs pymetis), mmd "
                        "(minimum degree), colamd (SuperLU with partial pivoting, 3-5x "
                        "slower), pardiso (needs pypardiso); default auto: grid (the "
                        "infinitely wide tape: colamd); all give the same state")


def run(args: argparse.Namespace) -> int:
    """Check every input and output target, solve the steady flying state of the arguments'
    tape, write the asked outputs (all or none) and print the summary (JSON or text).
    Returns the exit code 0."""
    from ..core.files import folder_transaction, transaction

    _refuse_unused_in_mode(args)
    refuse_film_options_when_dry(args)
    params, velocity, tables = _tape(args)
    head_table = tables.get("head")
    design = head_design(args, head_table, args.config)
    # the contour's checks: transducers on it, a profile file's
    head = build_head_of(args, design, head_table, args.config)
    air = _air(args, tables.get("air"))
    contact = contact_of(args, tables.get("contact"), args.config)
    recession = check_recession(args)
    out = _check_outputs(args)
    from ..bearing.results import BearingSolution

    check_save_path(args.save, BearingSolution)
    options = {**design.model_options(), "contact": contact, "dry": args.dry}
    model = _model(args, params, air, velocity, head, options)
    sol = _solve(model, None if args.quiet else _progress)
    summary = sol.summary()
    add_interface_readings(summary, sol, recession, quiet=args.json)
    if design.kind == "flat":
        summary["arc_contact"] = sol.model.arc_contact
        summary["corner_arc_models"] = corner_arc_models(sol.model)
    if args.error_estimate:
        summary["grid_error"] = _grid_error(args, sol,
                                            (params, air, velocity, head, options))
    if design.kind == "cylinder":
        # the angle as typed: degrees -> radians -> degrees need not give it back exactly
        summary["wrap_angle_degrees"] = (15.0 if design.wrap_angle is None else
                                         args.wrap_angle if args.wrap_angle is not None
                                         else math.degrees(design.wrap_angle))
    # every output, or none (and no folder this run created)
    with transaction() if out is None else folder_transaction(out):
        if out is not None:
            _write_out(out, sol, summary)
        save_result(args.save, sol, params)
        if args.plot is not None:
            from ..bearing.plots import head_overview, overview
            from ..reproduce._common import save_figure

            plain = head.kind == "cylinder" and not head.transducers
            save_figure((overview if plain else head_overview)(sol), Path(args.plot))
    if args.json:
        print_json(summary)
    else:
        _print_text(sol, summary.get("grid_error"), summary.get("magnetic_spacings"))
    return 0


def add_interface_readings(summary: dict, sol, recession: float | None, *,
                           quiet: bool = False) -> None:
    """The summary's magnetic spacings (with --recession), and its range warnings, each
    also one ``gyroshell: warning:`` line on stderr."""
    if recession is not None:
        summary["recession"] = recession
        summary["magnetic_spacings"] = sol.magnetic_spacings(recession)
    for text in summary.get("warnings", ()):
        print(f"gyroshell: warning: {text}", file=sys.stderr, flush=True)


def _refuse_unused_in_mode(args: argparse.Namespace) -> None:
    """Refuse the options that mean nothing for the infinitely wide tape."""
    if not args.infinitely_wide:
        return
    wide = "the infinitely wide tape (--infinitely-wide"
    for given, option, why in (
            (args.ny is not None, "--ny",
             f"sets the intervals across the width, which {wide}) does not have"),
            (args.width is not None, "--width",
             f"sets the tape width, which {wide}, results per unit width) does not have"),
            (args.uniform, "--uniform",
             f"switches off the 2-D grid's grading; the grid of {wide}) is always uniform")):
        if given:
            raise UserError(f"{option} {why}: drop {option} or --infinitely-wide")


def _tape(args: argparse.Namespace):
    """(TapeParameters, velocity in m/s, the file's [head] table or None) of the tape
    options and --config, validated. The plate-grid fields, which the bearing does not use,
    are set so that they pass."""
    from ..core import validation
    from ..tape.parameters import TapeParameters

    typed = typed_overrides(args, TAPE_OPTIONS)
    base, velocity, tables = TapeParameters(), args.velocity, {}
    if args.config is not None:
        from ..tape.config import load_config

        cfg = load_config(args.config, adjust=_without_plate_fields,
                          tables=("head", "air", "contact"))
        base, tables = cfg.params, cfg.tables
        velocity = cfg.velocity if velocity is None else velocity
        if base.edges != "free" and not args.infinitely_wide:
            raise UserError(f"{args.config}: edges = {base.edges!r}: the bearing's tape has "
                            "free edges (use edges = \"free\" or --infinitely-wide)")
    width = validation.positive("width", typed.get("width", base.width), "m")
    params = base.replace(**typed, edges="free", length_ratio=4.0,
                          spacing=width / PLATE_INTERVALS, load=0.0, load_x=None, load_y=None)
    _refuse_unused_material(args, params)
    dry = getattr(args, "dry", False)
    if velocity is None and dry:
        velocity = 0.0
    if velocity is None:
        raise UserError("velocity must be nonzero for an air bearing: give --velocity "
                        "(e.g. --velocity 4, or -4 for the tape running backwards) or "
                        "velocity in the --config file (or --dry for the tape at rest)")
    if velocity == 0.0 and not dry:
        raise UserError("velocity must be nonzero for an air bearing (e.g. --velocity 4, or "
                        "-4 for the tape running backwards), got 0; --dry: the tape at rest")
    return params, math.copysign(params.check_velocity(abs(velocity)), velocity), tables


def _without_plate_fields(fields: dict) -> dict:
    """A config file's tape fields with the plate grid's (unused here) set so that they
    pass: the spacing from the file's width (or the default width)."""
    from ..tape.parameters import TapeParameters

    width = fields.get("width", TapeParameters.width)
    spacing = width / PLATE_INTERVALS if width > 0 else TapeParameters.spacing
    return {**fields, "length_ratio": 4.0, "spacing": spacing, "load": 0.0,
            "load_x": None, "load_y": None}


def _refuse_unused_material(args: argparse.Namespace, params) -> None:
    """With the bending stiffness and k both given, E and c are not used, nor ν for the
    infinitely wide tape or beside D11, D22, D12, D66. The bending: D or the orthotropic
    D11, D22, D12, D66; k: itself or through the membrane stiffness A11 (k = A11/R²)."""
    bending = params.bending_rigidity is not None or params.bending_stiffness is not None
    shell = params.foundation_stiffness is not None or params.membrane_stiffness is not None
    if not (bending and shell):
        return
    unused = [("--youngs-modulus", args.youngs_modulus), ("--thickness", args.thickness),
              ("--youngs-modulus-x", getattr(args, "youngs_modulus_x", None))]
    if args.infinitely_wide or params.bending_stiffness is not None:
        unused += [("--poisson", args.poisson),
                   ("--poisson-xy", getattr(args, "poisson_xy", None))]
    for option, value in unused:
        if value is not None:
            raise UserError(f"{option} is not used when the bending rigidity and the "
                            "foundation stiffness are both given (--bending-rigidity or "
                            "--bending-stiffness, --foundation-stiffness or "
                            "--membrane-stiffness, or the --config file): drop it")


def _air(args: argparse.Namespace, table: dict | None = None):
    """The AirParameters of the arguments over the file's ``[air]`` table."""
    from ..bearing import AirParameters

    air = air_of(args, table, args.config)
    return AirParameters() if air is None else air


def _check_outputs(args: argparse.Namespace) -> Path | None:
    """Refuse, before the solve, a --plot or --out that could not be written (including
    the files --out writes into a folder that exists); returns the --out folder."""
    from ..core.files import PLOT, check_output_folder_with_files, check_outputs

    if args.plot is not None and Path(args.plot).suffix.lower() != ".png":
        raise UserError(f"--plot must name a .png file, got {args.plot!r}")
    check_outputs({"--plot": (args.plot, PLOT)})
    if args.out is None:
        return None
    return check_output_folder_with_files(args.out, OUT_FILES, option="--out-dir")


def _model(args: argparse.Namespace, params, air, velocity: float, head, options=None, *,
           nx=None, ny=None):
    """The BearingModel of the arguments (speed, head, grid) on the tape and the air, with
    the head design's model ``options`` (``arc_contact``); a grid coarse enough to be off
    (BearingGridWarning) is one ``gyroshell: warning:`` line. ``nx``, ``ny``: other
    intervals than the arguments'."""

    from ..bearing import BearingModel
    from ..bearing.model import BearingGridWarning

    with warnings_as_lines(BearingGridWarning):
        model = BearingModel(params, air, velocity=velocity,
                             head=head,
                             infinitely_wide=args.infinitely_wide, span=args.span,
                             nx=args.nx if nx is None else nx,
                             ny=args.ny if ny is None else ny,
                             grading="uniform" if args.uniform else None,
                             factorization=getattr(args, "factorization", "auto"),
                             **(options or {}))
    return model


def corner_arc_models(model) -> list[str | None]:
    """How the model meets each corner of a flat head (in the order of ``head.corners()``,
    the summary's ``corner_forces``): "sharp" (r_c = 0), "point" (one tangent point
    contact), "wrapped" (the arc nodes in the general contact set), or None for a rounded
    corner the dry tape runs straight over (no turn: no arc model applies)."""
    radii = model.head.corner_radii()
    out: list[str | None] = []
    for k, radius in enumerate(radii):
        out.append("sharp" if radius == 0.0 else "wrapped" if k in model.wrapped_corners
                   else "point" if k in model.rounded_corners else None)
    return out


def _grid_error(args: argparse.Namespace, sol, inputs) -> dict:
    """The spacings of ``sol`` less those on the grid with half its intervals each way
    (m): the coarse grid's intervals and, per reading, the difference."""
    from ..bearing.model import MIN_INTERVALS_ALONG
    from ..tape.parameters import MIN_INTERVALS_ACROSS

    model = sol.model
    nx = max(MIN_INTERVALS_ALONG, model.nx // 2)
    ny = None if model.infinitely_wide else max(MIN_INTERVALS_ACROSS, 2 * (model.ny // 4))
    kept = [f"{name} = {fine} (the fewest is {low})" for name, fine, coarse, low in (
        ("nx", model.nx, nx, MIN_INTERVALS_ALONG), ("ny", model.ny, ny, MIN_INTERVALS_ACROSS))
        if coarse is not None and 2 * coarse > fine + 2]
    if kept:
        print(f"gyroshell: warning: --error-estimate cannot halve {' or '.join(kept)}: the "
              f"coarse grid is {nx}" + ("" if ny is None else f" x {ny}") + " intervals, so "
              "grid_error understates (or leaves out) that direction's error; use at least "
              "twice the fewest intervals", file=sys.stderr, flush=True)
    progress = None if args.quiet else _progress
    if progress is not None:
        progress(f"error estimate: the same on {nx}" + ("" if ny is None else f" x {ny}")
                 + " intervals")
    coarse = _solve(_model(args, *inputs, nx=nx, ny=ny), progress)
    return {"coarse_nx": nx, "coarse_ny": ny,
            "central_spacing": sol.central_spacing - coarse.central_spacing,
            "minimum_spacing": sol.minimum_spacing - coarse.minimum_spacing,
            "transducer_lines": [
                {"x": fine.x, "minimum": fine.minimum - rough.minimum,
                 "mean": fine.mean - rough.mean}
                for fine, rough in zip(sol.transducer_lines, coarse.transducer_lines,
                                       strict=True)]}


def _progress(message: str) -> None:
    """One progress line on stderr."""
    print(f"gyroshell bearing: {message}", file=sys.stderr, flush=True)


def iteration_seconds(model) -> float:
    """Estimated seconds of one Newton iteration of ``model`` that factors its Jacobian
    afresh (:data:`SECONDS_1D`, :data:`SECONDS_2D`)."""
    if model.infinitely_wide:
        constant, per_unknown = SECONDS_1D
        return constant + per_unknown * model.unknowns
    per_unknown, per_interval = SECONDS_2D
    return (per_unknown + per_interval * model.ny) * model.unknowns


def solve_seconds(model) -> tuple[float, float, float]:
    """(low, central, high) estimate of the seconds of ``model``'s steady solve, its start
    included: under a smooth contact law :data:`SMOOTH_FACTORIZATIONS` times
    :func:`iteration_seconds` (and :data:`SMOOTH_FIRST_SECONDS` infinitely wide), within a
    factor :data:`SMOOTH_BAND` either way; under the hard wall :data:`USUAL_FACTORIZATIONS`
    (the central estimate their geometric mean)."""
    each = iteration_seconds(model)
    if model.smooth_contact:
        one_d, two_d = SMOOTH_FACTORIZATIONS
        central = (one_d * each + SMOOTH_FIRST_SECONDS if model.infinitely_wide
                   else two_d * each)
        return central / SMOOTH_BAND, central, central * SMOOTH_BAND
    low, high = USUAL_FACTORIZATIONS
    return low * each, math.sqrt(low * high) * each, high * each


def size_line(model) -> str:
    """The first progress line: the grid, the unknowns and the estimated time."""
    from ..core.progress import duration

    if model.infinitely_wide:
        grid = f"infinitely wide tape, {model.nx} intervals along x"
    else:
        grid = (f"{model.params.width:g} m wide tape, {model.nx} x {model.ny} intervals "
                f"({'graded' if model.graded else 'uniform'})")
    from ..bearing.smooth import SolverOptions

    each = iteration_seconds(model)
    low, central, high = solve_seconds(model)
    longer = ("the direct path fails and a continuation is needed" if model.smooth_contact
              else "Newton needs pseudo-time or continuation in V")
    budget = SolverOptions().budget
    return (f"{grid}, {model.unknowns} unknowns; estimated {duration(low)} to "
            f"{duration(high)}, about {duration(central)} (about {duration(each)} per "
            f"Newton iteration that factors afresh; longer if {longer}, and stopped "
            f"within {budget} Newton iterations, at most about "
            f"{duration(budget * each)})")


def _solve(model, progress):
    """The steady state, with one line per stage through ``progress`` (None: silent);
    a UserError if none is reached."""
    from ..bearing.corners import arc_contact_hint
    from ..bearing.steady import initial_state, solve_steady
    from ..core.errors import ConvergenceError

    start = time.perf_counter()

    def stamped(message: str) -> None:
        progress(f"{time.perf_counter() - start:.1f} s: {message}")

    log = None if progress is None else stamped
    if log is not None:
        progress(size_line(model))
        if not model.infinitely_wide:
            log("start: a first solve on a coarser grid (or of the infinitely wide tape) "
                "for Newton's starting state")
    try:
        # rounded corners start inside their contacts' adaptation (from the coarse grid
        # with its contacts adapted there: steady.coarse_solution); a 2-D tape under a
        # smooth contact law inside its own solve (smooth.coarse_start)
        own_start = (model.adapt_contacts and model.corner_contacts) or (
            model.smooth_contact and not model.infinitely_wide)
        z0 = None if own_start else initial_state(model)
        if log is not None and not model.infinitely_wide and z0 is not None:
            log("start: ready")
        sol = solve_steady(model, z0=z0, progress=log, iteration_log=log)
    except ConvergenceError as exc:
        raise UserError(f"no steady flying state reached for this input: {exc}"
                        f"{arc_contact_hint(model)}") from None
    sol.info.seconds = time.perf_counter() - start     # the starting state included
    if log is not None:
        extra = sol.info.start_iterations
        log(f"done: {sol.info.iterations} Newton iterations"
            + (f" ({extra} more on the start's coarser grids)" if extra else ""))
    return sol


def _print_text(sol, grid_error: dict | None = None, summary_magnetic=None) -> None:
    """The headline numbers as text (``summary_magnetic``: the transducer lines'
    magnetic spacings, if --recession was given)."""
    model = sol.model
    force_unit = "N/m" if model.infinitely_wide else "N"
    x_min, y_min = sol.minimum_location
    where = f"x = {x_min:.4e} m" + ("" if y_min is None else f", y = {y_min:.4e} m")
    print(f"model:            {model!r}")
    print(f"interface:        {model.air.rarefaction} rarefaction, flow factors "
          f"{model.air.flow_factors}, {'dry, ' if model.dry else ''}contact "
          f"{model.contact.law} (spacings to the mean plane of the tape's summits)")
    print(f"central spacing:  {sol.central_spacing:.6e} m")
    print(f"minimum spacing:  {sol.minimum_spacing:.6e} m at {where}")
    print(f"air force:        {sol.air_force:.6e} {force_unit}")
    print(f"contact force:    {sol.contact_force:.6e} {force_unit} ({sol.contact_nodes} nodes)")
    magnetic = {m["x"]: m for m in summary_magnetic} if summary_magnetic else {}
    for line in sol.transducer_lines:
        extra = (f", magnetic spacing {magnetic[line.x]['magnetic_spacing']:.6e} m"
                 if line.x in magnetic else "")
        print(f"transducer line:  x = {line.x:.4e} m: minimum {line.minimum:.6e} m, "
              f"mean {line.mean:.6e} m{extra}")
    for share in sol.corner_forces:
        print(f"corner:           x = {share.where[0]:.4e} m: contact force "
              f"{share.force:.6e} {force_unit}")
    for tent in sol.tents:
        if tent.height is not None:
            print(f"tent:             {tent.height:.6e} m at x = {tent.x:.4e} m "
                  f"({tent.side} side of the corner at {tent.corner:.4e} m)")
    print(f"drag:             {sol.drag:.6e} {force_unit} (viscous {sol.viscous_drag:.6e}, "
          f"friction {sol.friction_drag:.6e}); tension rise {sol.tension_rise:.6e} N/m, "
          f"ratio {sol.tension_ratio:.6f}")
    if grid_error is not None:
        lines = "".join(f", line x = {line['x']:.4e} m: minimum {line['minimum']:+.3e}, "
                        f"mean {line['mean']:+.3e}" for line in grid_error["transducer_lines"])
        print(f"grid error:       against half the intervals: central "
              f"{grid_error['central_spacing']:+.3e} m{lines}")
    start = (f" (+{sol.info.start_iterations} on the start's grids)"
             if sol.info.start_iterations else "")
    print(f"Newton:           {sol.info.iterations} iterations{start}, "
          f"{sol.info.seconds:.2f} s")


def _write_out(out: Path, sol, summary: dict) -> None:
    """fields.csv (the solution's table) and summary.json into the folder ``out``."""
    from ..core.files import write_atomic
    from ..results.base import write_table

    write_table(sol.to_frame().rename(columns=FIELD_COLUMNS), out / "fields.csv",
                option="--out-dir")
    lines, corners = readings_tables(sol)
    write_table(lines, out / "transducer_lines.csv", option="--out-dir")
    write_table(corners, out / "corners.csv", option="--out-dir")
    write_atomic(out / "summary.json",
                 lambda tmp: tmp.write_text(json.dumps(summary, indent=1) + "\n"))


def readings_tables(sol):
    """(transducer lines, corners) as DataFrames, units in the column names: the spacing
    across the width along each line (one row per node; y empty if infinitely wide), and
    per corner its contact force (N, N/m if infinitely wide), peak contact pressure, force
    centroid and nodes in contact, and its tents on the land and span sides (NaN: none)."""
    import pandas as pd

    model = sol.model
    ys = [math.nan] if model.infinitely_wide else list(model.y)
    lines = pd.DataFrame(
        [{"line": k, "x_m": line.x, "y_m": y, "spacing_m": float(h),
          "line_minimum_m": line.minimum, "line_mean_m": line.mean}
         for k, line in enumerate(sol.transducer_lines, start=1)
         for y, h in zip(ys, line.spacing, strict=True)],
        columns=["line", "x_m", "y_m", "spacing_m", "line_minimum_m", "line_mean_m"])
    unit = "N_per_m" if model.infinitely_wide else "N"
    rows = []
    for k, share in enumerate(sol.corner_forces, start=1):
        row = {"corner": k, "x_m": share.where[0], f"contact_force_{unit}": share.force,
               "peak_contact_pressure_Pa": share.peak_pressure,
               "centroid_m": math.nan if share.centroid is None else share.centroid,
               "contact_nodes": share.nodes}
        for tent in sol.tents:
            if tent.corner == share.where[0]:
                row[f"{tent.side}_tent_height_m"] = (math.nan if tent.height is None
                                                     else tent.height)
                row[f"{tent.side}_tent_x_m"] = math.nan if tent.x is None else tent.x
        rows.append(row)
    return lines, pd.DataFrame(rows)
