"""``gyroshell study`` (parameter studies, locally or on Dask) and ``gyroshell campbell``."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from ..core.errors import ParameterError
from .common import (
    OLD_SPELLINGS_END,
    RANGE_HELP,
    UserError,
    boolean,
    grid_of,
    notice,
    parameters_from_args,
    parse_velocities,
    positive_int,
    print_json,
    real,
    typed_tape_options,
    warnings_as_lines,
)
from .heads import DEGREE_FIELDS, add_head_options, head_design, typed_head_options
from .interface import add_interface_options, air_of, contact_of, interface_given
from .saving import add_save_option, check_save_path

#: Resolution of the --plot files, dots per inch.
PLOT_DPI = 120
#: The --vary names given in degrees (the head's wraps, and ``wrap``: both of them).
VARY_DEGREES = (*DEGREE_FIELDS, "wrap")


def register(sub, common: argparse.ArgumentParser,
             common_without_velocity: argparse.ArgumentParser) -> None:
    from ..studies.evaluation import COMPUTE_CHOICES
    from ..studies.points import LAYER_VARIABLES, VARIABLE_NAMES

    p = sub.add_parser(
        "study", parents=[common], help="parameter study: vary tape parameters, one row each",
        description="Vary tape parameters over a grid (every combination of the --vary "
                    "values) and compute, per point, the critical speed, the lowest "
                    "frequencies with the stability (stable/divergence/flutter), the static "
                    "deflection, the period or the air bearing over a head (--compute "
                    "bearing: spacings, transducer lines, tents, corner forces, drag; the "
                    "head's options below, or [head] in --config). Points run in local "
                    "worker processes, or on a running Dask cluster with --scheduler. A "
                    "point that fails is reported in its row. SI units: m, Pa, N/m, kg/m^2, "
                    "m/s; the head's angles in degrees.")
    p.add_argument("--vary", action="append", required=True, metavar="NAME=VALUES",
                   help="a parameter and its values: NAME=V1,V2,... or NAME=START:STOP:NUM "
                        "(NUM evenly spaced values from START to STOP, both included, as "
                        "in every range option); repeat for a grid. "
                        "Values in SI, or with a unit as in a --config file (20um,30um). "
                        f"NAME: {', '.join(VARIABLE_NAMES)} (SI units; the head's "
                        "wrap_angle, wrap_in and wrap_out in degrees, or 0.03rad; wrap: "
                        "both wrap_in and wrap_out, e.g. wrap=1:4:4), or for "
                        f"a layered tape (--config with [[layer]] tables) {LAYER_VARIABLES}, "
                        "layers counted from 1 at the bottom: layer2.thickness=4e-6:6e-6:5")
    p.add_argument("--compute", action="append", required=True, metavar="WHAT",
                   help=f"what to compute: {', '.join(COMPUTE_CHOICES)} (repeat or "
                        "comma-separate for several)")
    p.add_argument("--count", type=positive_int, default=None,
                   help="frequencies per point for 'modes', in [1, 50] (default 3; only "
                        "with --compute modes)")
    p.add_argument("--workers", type=positive_int, default=None,
                   help="local worker processes, at most 4 per CPU (default: one per CPU; "
                        "1 runs in this process; not with --scheduler)")
    p.add_argument("--scheduler", metavar="ADDRESS", default=None,
                   help="run on a Dask distributed scheduler, e.g. tcp://127.0.0.1:8786 "
                        "(start it with 'dask scheduler' and 'dask worker ADDRESS')")
    p.add_argument("--connect-timeout", type=real, default=None, metavar="SECONDS",
                   help="with --scheduler: seconds, in (0, 3600], to wait for the scheduler "
                        "to connect and complete Dask's handshake (default 10; a refused "
                        "connection fails at once)")
    p.add_argument("--cache", metavar="FILE.jsonl", default=None,
                   help="keep finished points here; running the same study again resumes")
    _add_output_options(p)
    _add_bearing_options(p)
    p.set_defaults(func=run, config_tables=("head", "air", "contact"))
    register_campbell(sub, common_without_velocity)


def _add_bearing_options(p: argparse.ArgumentParser) -> None:
    """The head and grid of --compute bearing."""
    add_head_options(p, title="head of --compute bearing")
    g = p.add_argument_group("air bearing grid of --compute bearing")
    g.add_argument("--infinitely-wide", action="store_true",
                   help="the 1-D infinitely wide tape (per unit width) instead of the 2-D "
                        "tape with free edges")
    g.add_argument("--nx", type=positive_int, default=None,
                   help="intervals along x (default: the bearing's default grid)")
    g.add_argument("--ny", type=positive_int, default=None,
                   help="intervals across the width, even, 2-D only (default: the "
                        "bearing's default grid)")
    add_interface_options(p, single=False)


def _add_output_options(p: argparse.ArgumentParser) -> None:
    """What a study writes and shows: --out, --save, --plot, --quantity, --sketch,
    --quiet, --json."""
    p.add_argument("--out", metavar="FILE.csv", default=None,
                   help="write the table (CSV, or .parquet); one row per point")
    add_save_option(p)
    p.add_argument("--plot", metavar="FILE.png", default=None,
                   help="two varied parameters: a colour map of --quantity over them (or, "
                        "without --quantity, of a study computing modes or period, the "
                        "stability map); one: --quantity against it. Angles in degrees")
    p.add_argument("--quantity", metavar="NAME", default=None,
                   help="the computed column --plot draws (default: the transducers' "
                        "minimum spacing, transducer_min_spacing, in a bearing study with "
                        "--transducers, else the first computed column); an unknown name "
                        "is refused with the list")
    p.add_argument("--sketch", metavar="FILE.png", default=None,
                   help="--compute bearing: draw the head of the first point (modules, "
                        "gaps, corners, transducer lines and the dry tape) before solving")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (points, computed, cached, failed, seconds, "
                        "executor) instead of the table")


def register_campbell(sub, common_without_velocity: argparse.ArgumentParser) -> None:
    """``gyroshell campbell``: its speeds are --velocities, so --velocity is refused."""
    p = sub.add_parser(
        "campbell", parents=[common_without_velocity],
        help="Campbell diagram: MAC-tracked frequencies vs speed",
        description="Lowest frequencies (rad/s) against tape speed (m/s), tracked into "
                    "branches by the modal assurance criterion (MAC of every link reported), "
                    "with crossings, veerings, the critical speed and, for a roller or "
                    "capstan of circumference L (m), the excitation lines omega = n 2 pi V/L "
                    "and the speeds where they meet a branch.")
    p.add_argument("--velocities", default="0:100:21", metavar="START:STOP:NUM",
                   help=f"speeds, m/s: {RANGE_HELP} (default 0:100:21: every 5 m/s; until "
                        "release 0.3 the old START:STOP:STEP is still read where it gives "
                        "other speeds, with a notice)")
    p.add_argument("--count", type=positive_int, default=6,
                   help="modes per speed (default 6)")
    p.add_argument("--min-mac", type=real, default=None,
                   help="smallest MAC that continues a branch, in [0, 1] (default 0.5)")
    p.add_argument("--min-step", type=real, default=None, metavar="M/S",
                   help="smallest speed step, m/s, > 0, down to which the step is halved "
                        "where the MAC falls below --min-mac (default: the largest step of "
                        "--velocities / 64)")
    p.add_argument("--circumference", type=real, default=None,
                   help="roller/capstan circumference, m, > 0: the excitation lines and "
                        "the speeds where they meet a branch")
    p.add_argument("--orders", default=None,
                   help="harmonics n of the excitation lines, integers in [1, 1000] "
                        "(default 1,2,3; only with --circumference)")
    p.add_argument("--out", metavar="FILE.csv", default=None,
                   help="write the tracked branches (velocity, branch, rank, omega, "
                        "growth_rate, mac): CSV or Parquet (a .nc file: the old spelling "
                        "of --save, with a notice)")
    p.add_argument("--plot", metavar="FILE.png", default=None, help="write the diagram")
    add_save_option(p, what="the whole diagram (branches, MAC of every link, crossings, "
                           "veerings)")
    p.add_argument("--workers", type=positive_int, default=1,
                   help="local processes, at most 4 per CPU, each solving a contiguous run "
                        "of the speeds (default 1)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (branches, speeds, MAC of the links, critical "
                        "speed in m/s, crossings, veerings; with --circumference the "
                        "resonances) instead of the text")
    p.set_defaults(func=run_campbell)


def parse_values(name: str, text: str) -> list:
    """``V1,V2,...`` or ``START:STOP:NUM`` (numbers in SI, or values with a unit such as
    ``20um`` / ``"20 um"``; words for ``edges``, true/false, yes/no or 1/0 for the yes-or-no
    variables such as ``wrap_pressure``)."""
    from ..core.budget import check_study_points
    from ..core.units import unit_of
    from ..studies.points import BOOLEAN_VARIABLES, CHOICE_VARIABLES
    from ..tape.config import parse_quantity

    text = text.strip()
    if not text:
        raise UserError(f"--vary {name}: no values")
    if name.replace("-", "_") in CHOICE_VARIABLES:
        words = CHOICE_VARIABLES[name.replace("-", "_")]
        items = [item.strip() for item in text.split(",")]
        for item in items:
            if item not in words:
                raise UserError(f"--vary {name}: {item!r} is not one of {', '.join(words)}")
        return items
    if name.replace("-", "_") in BOOLEAN_VARIABLES:
        try:
            return [boolean(item) for item in text.split(",")]
        except argparse.ArgumentTypeError as exc:
            raise UserError(f"--vary {name}: {exc}") from None
    if ":" in text:
        from ..core.ranges import parse_range

        key = name.replace("-", "_")
        unit = "degrees" if key in VARY_DEGREES else unit_of(key) or "SI"
        values = [float(v) for v in parse_range(
            text, f"--vary {name}", unit=unit,
            limit=lambda n: check_study_points(n, what=f"--vary {name}={text}"))]
        degrees = key in VARY_DEGREES
        return [math.radians(v) for v in values] if degrees else values
    items = [item.strip() for item in text.split(",")]
    if name.replace("-", "_") == "edges":
        return items
    key = name.replace("-", "_")
    si_unit = unit_of(key)
    out = []
    for item in items:
        try:
            out.append(math.radians(real(item)) if key in VARY_DEGREES else real(item))
        except argparse.ArgumentTypeError as exc:
            if si_unit is None or not item[:1].strip("+-.0123456789") == "":
                raise UserError(f"--vary {name}: {exc}") from None
            unit = item.lstrip("+-.0123456789eE")  # "20um" -> "um"
            number = item[:len(item) - len(unit)].strip()
            out.append(parse_quantity(key, f"{number} {unit.strip()}", "--vary ",
                                      unit=si_unit))
    return out


def parse_vary(specs: list[str]) -> dict[str, list]:
    vary: dict[str, list] = {}
    for spec in specs:
        name, sep, values = spec.partition("=")
        name = name.strip()
        if not sep or not name:
            raise UserError(f"--vary needs NAME=VALUES, got {spec!r}")
        key = name.replace("-", "_")
        if key in vary:
            raise UserError(f"--vary {name} given twice")
        vary[key] = parse_values(name, values)
    return vary


def _check_outputs(outputs: dict[str, tuple[str | None, tuple[str, ...]]]) -> None:
    """Refuse, before computing, a wrong suffix, an unwritable path or one file named twice;
    ``outputs`` maps each option to (path or None, allowed suffixes)."""
    from ..core.files import PLOT, check_outputs

    for flag, (path, suffixes) in outputs.items():
        if path is not None and Path(path).suffix.lower() not in suffixes:
            raise UserError(f"{flag}: use a {' or '.join(suffixes)} file, got {path}")
    check_outputs({flag: (path, PLOT if flag == "--plot" else None)
                   for flag, (path, _suffixes) in outputs.items()})


def _save_plot(path: str, ax, *, option: str = "--plot") -> None:
    from ..plot import save_figure

    save_figure(ax.figure, path, dpi=PLOT_DPI, option=option)


def run(args: argparse.Namespace) -> int:
    from ..studies.parameter_study import run_study

    typed = typed_tape_options(args)  # before --config fills in the defaults
    params = parameters_from_args(args)
    compute = [c.strip() for item in args.compute for c in item.split(",") if c.strip()]
    velocity = _study_velocity(args.velocity, compute)
    vary = parse_vary(args.vary)
    _check_study_options(args, typed, vary, compute)
    bearing = _bearing_setup(args, vary, compute)
    from ..results.base import NETCDF_SUFFIXES, TABLE_SUFFIXES

    check_save_path(args.save)
    _check_outputs({"--out": (args.out, (".csv", ".parquet")),
                    "--plot": (args.plot, (".png", ".pdf", ".svg")),
                    "--sketch": (args.sketch, (".png", ".pdf", ".svg")),
                    "--cache": (args.cache, (".jsonl",)),
                    "--save": (args.save, NETCDF_SUFFIXES + TABLE_SUFFIXES)})
    if args.plot and len(vary) > 2:
        raise UserError("--plot needs one or two varied parameters")
    _check_quantity(args, params, vary, compute, velocity, bearing)
    sketch = _sketch(params, vary, bearing) if args.sketch else None
    result = run_study(params, vary=vary, compute=compute, velocity=velocity,
                       count=args.count,
                       workers=args.workers, scheduler=args.scheduler,
                       cache=args.cache, progress=False if args.quiet else None,
                       bearing=bearing, inputs=[args.config] if args.config else [],
                       **_connect_timeout(args))
    from ..core.files import transaction

    with transaction():  # every output of the run, or none
        for path in (args.out, args.save):
            if path is not None:
                result.save(path)
        if args.plot:
            _save_plot(args.plot, result.plot(quantity=args.quantity))
        if sketch is not None:
            _save_plot(args.sketch, sketch, option="--sketch")
    _report_study(args, result)
    return 0


def _study_velocity(velocity: float, compute: list[str]) -> float:
    """--velocity, m/s: >= 0, or of either sign in a study of the air bearing alone."""
    from ..studies.points import check_speed

    return check_speed(velocity, signed=set(compute) == {"bearing"})


def _check_quantity(args: argparse.Namespace, params, vary: dict, compute: list[str],
                    velocity: float, bearing) -> None:
    """Refuse, before any work, --quantity without --plot or naming no column of the
    study (the message lists them)."""
    if args.quantity is None:
        return
    if not args.plot:
        raise UserError("--quantity chooses what --plot draws: add --plot or drop "
                        "--quantity")
    from ..plot.study_maps import plottable
    from ..studies.parameter_study import study_columns

    columns = study_columns(params, vary=vary, compute=compute, velocity=velocity,
                            count=args.count, bearing=bearing)
    names = plottable(columns, list(vary))
    if args.quantity not in names:
        raise UserError(f"--quantity {args.quantity}: this study has no such column; "
                        f"choose one of {', '.join(names)}")


def _sketch(params, vary: dict, bearing):
    """--sketch: the Axes of the head of the study's first point, drawn before the solves
    (its head refused in one line if it cannot be built)."""
    if bearing is None:
        raise UserError("--sketch draws the head of --compute bearing: add it or drop "
                        "--sketch")
    from ..bearing.plots import head_sketch
    from ..studies.head_study import head_of_point
    from ..studies.points import HEAD_VARIABLES, grid_points

    first = {k: v for k, v in grid_points({k: v[:1] for k, v in vary.items()})[0].items()
             if k in HEAD_VARIABLES}
    try:
        head = head_of_point(bearing, first).head()
    except ParameterError as exc:
        raise UserError(f"point 0 {first}: {exc}") from None
    shown = ", ".join(f"{k} = {math.degrees(v):g} deg" if k in VARY_DEGREES
                      else f"{k} = {v:g} m" for k, v in first.items())
    title = f"{head.kind} head" + (f" of the first point ({shown})" if shown else "")
    return head_sketch(head, radius=params.radius, title=title)


def _check_study_options(args: argparse.Namespace, typed: dict[str, str], vary: dict,
                         compute: list[str]) -> None:
    """Refuse options the study would ignore: a tape option that --vary replaces at every
    point, --count without --compute modes."""
    for name in vary:
        if name in typed:
            raise UserError(f"{typed[name]} and --vary {name} both set {name}: every point "
                            f"takes its value from --vary, so give one of them")
    if args.count is not None and "modes" not in compute:
        raise UserError("--count is the number of frequencies of --compute modes; add "
                        "--compute modes or drop --count")


def _bearing_setup(args: argparse.Namespace, vary: dict, compute: list[str]):
    """The BearingStudy of --compute bearing (the head options over the [head] table of
    --config, the grid options); without it, every head or grid option is refused."""
    table = getattr(args, "tables", {}).get("head")
    grid = [flag for flag, given in (("--infinitely-wide", args.infinitely_wide),
                                     ("--nx", args.nx is not None),
                                     ("--ny", args.ny is not None)) if given]
    tables = getattr(args, "tables", {})
    if "bearing" not in compute:
        typed = typed_head_options(args) + grid + interface_given(args)
        if typed:
            raise UserError(f"{typed[0]} sets up --compute bearing: add it or drop {typed[0]}")
        for name in ("head", "air", "contact"):
            if tables.get(name) is not None:
                raise UserError(f"{args.config}: its [{name}] table sets up --compute "
                                "bearing: add it, or drop the table")
        return None
    from ..studies.points import design_fields
    from .heads import HEAD_FLAGS

    design = head_design(args, table, args.config, varied=design_fields(vary))

    for name in vary:
        for field in design_fields([name]):
            if getattr(args, field, None) is not None and field in HEAD_FLAGS:
                raise UserError(f"{HEAD_FLAGS[field]} and --vary {name} both set {field}: "
                                "every point takes its value from --vary, so give one of "
                                "them")
    from ..studies.head_study import BearingStudy

    contact = (contact_of(args, tables.get("contact"), args.config)
               if interface_given(args) or tables.get("contact") else None)
    return BearingStudy(head=design, air=air_of(args, tables.get("air"), args.config),
                        contact=contact, infinitely_wide=args.infinitely_wide, nx=args.nx,
                        ny=args.ny)


def _connect_timeout(args: argparse.Namespace) -> dict:
    """``connect_timeout`` for run_study, if given; refused without --scheduler."""
    if args.connect_timeout is None:
        return {}
    if args.scheduler is None:
        raise UserError("--connect-timeout applies to --scheduler only (local processes "
                        "need no connection)")
    return {"connect_timeout": args.connect_timeout}


def _report_study(args: argparse.Namespace, result) -> None:
    """The table (unless written with --out) and one line on the run; or --json."""
    if args.json:
        print_json(result.summary())
        return
    summary = result.summary()
    if args.out is None:
        print(study_text(result))
    print(f"{summary['points']} points ({summary['computed']} computed, {summary['cached']} "
          f"from the cache, {summary['failed']} with errors) in {summary['seconds']:.2f} s "
          f"on {summary['executor']}")
    for path in (args.out, args.save, args.plot, args.sketch):
        if path is not None:
            print(f"wrote {path}")


def study_text(result) -> str:
    """The study's table as printed: the varied values in Python's shortest round-trip
    form (what the user typed: 2.04e-05; the head's angles in degrees, as typed, in a
    column ``<name>_deg``), the computed ones to 6 significant digits."""
    from pandas.api.types import is_float_dtype

    table = result.table.drop(columns=["point"])
    formats, degrees = {}, {}
    for column in table.columns:
        if not is_float_dtype(table[column].dtype):
            continue
        if column in result.varied and column in VARY_DEGREES:
            degrees[column] = f"{column}_deg"    # as typed: degrees, not the rad stored
            formats[degrees[column]] = lambda x: f"{x:.12g}"
        elif column in result.varied:
            formats[column] = lambda x: repr(float(x))
        else:
            formats[column] = lambda x: f"{x:.6g}"
    for column in degrees:
        table[column] = table[column].map(math.degrees)
    return table.rename(columns=degrees).to_string(index=False, formatters=formats)


def run_campbell(args: argparse.Namespace) -> int:
    from ..studies.campbell import MIN_MAC

    params = parameters_from_args(args)
    orders = _campbell_orders(args)
    min_mac = MIN_MAC if args.min_mac is None else args.min_mac
    _check_campbell_numbers(args, min_mac)
    _check_outputs({"--out": (args.out, (".csv", ".parquet", ".nc")),
                    "--plot": (args.plot, (".png", ".pdf", ".svg")),
                    "--save": (args.save, (".nc",))})
    if args.out and Path(args.out).suffix.lower() == ".nc":
        notice(f"campbell --out FILE.nc is now --save FILE.nc (--out is the table, CSV or "
               f"Parquet, in every sub-command); --out FILE.nc goes in release "
               f"{OLD_SPELLINGS_END}")
    grid_of(params)  # its size, before the operators are assembled
    velocities = parse_velocities(args.velocities)  # the engines load from here on
    from ..studies.sweep import check_velocities
    from ..tape.model import TapeModel

    velocities = check_velocities(velocities)
    d = _tracked_campbell(TapeModel(params), velocities, args, min_mac)
    from ..core.files import transaction

    with transaction():  # both files, or neither
        for path in (args.out, args.save):
            if path:
                d.save(path, params=params)
        if args.plot:
            _save_plot(args.plot, d.plot(circumference=args.circumference, orders=orders))
    if args.json:
        print_json(_campbell_json(d, args.circumference, orders))
        return 0
    _report_campbell(args, d, orders)
    return 0


def _tracked_campbell(model, velocities: list[float], args: argparse.Namespace,
                      min_mac: float):
    """The diagram; branches left unlinked are one ``gyroshell: warning:`` line."""

    from ..studies.campbell import CampbellTrackingWarning, campbell

    with warnings_as_lines(CampbellTrackingWarning):
        d = campbell(model, velocities, args.count, min_mac=min_mac,
                     progress=False if args.quiet else None, workers=args.workers,
                     min_step=args.min_step)
    return d


def _campbell_orders(args: argparse.Namespace) -> tuple[int, ...]:
    """The harmonics of --orders (default 1,2,3), refused without --circumference."""
    from ..studies.campbell import check_orders

    if args.orders is None:
        return (1, 2, 3)
    if args.circumference is None:
        raise UserError("--orders are the harmonics of the excitation lines of "
                        "--circumference: add --circumference or drop --orders")
    items = [n.strip() for n in args.orders.split(",")]
    try:
        numbers = [int(n) if n.lstrip("+-").isdigit() else float(n) for n in items]
    except ValueError:
        raise UserError(f"--orders must be integers like 1,2,3, got {args.orders!r}") from None
    try:
        return check_orders(numbers)
    except ParameterError as exc:
        raise UserError(f"--{exc}") from None


def _check_campbell_numbers(args: argparse.Namespace, min_mac: float) -> None:
    """--circumference, --min-mac and --workers, before any work."""
    from ..core import validation
    from ..core.parallel import check_process_count

    if args.circumference is not None:
        validation.positive("--circumference", args.circumference, "m")
    if args.min_step is not None:
        validation.positive("--min-step", args.min_step, "m/s")
    validation.real("--min-mac", min_mac, low=0.0, high=1.0)
    check_process_count("--workers", args.workers)


def _campbell_json(d, circumference: float | None, orders: tuple[int, ...]) -> dict:
    """The diagram's summary and, with a circumference, its resonances (order, branch,
    velocity in m/s, omega in rad/s)."""
    out = d.summary()
    if circumference is not None:
        out["resonances"] = [
            {"order": int(r.order), "branch": int(r.branch), "velocity": float(r.velocity),
             "omega": float(r.omega)}
            for r in d.resonances(circumference, orders).itertuples()]
    return out


def _report_campbell(args: argparse.Namespace, d, orders: list[int]) -> None:
    """Branches, MAC, critical speed, crossings, veerings and resonances, one per line."""
    summary = d.summary()
    inserted = f" ({summary['inserted']} inserted where the MAC fell)" if summary[
        "inserted"] else ""
    macs = ("none (one speed)" if d.mac_min is None
            else f"min {d.mac_min:.3f}, median {d.mac_median:.3f}")
    print(f"{summary['branches']} branches over {summary['speeds']} speeds{inserted}; "
          f"MAC of the matches: {macs}")
    print(f"critical speed: {d.critical_speed:.6g} m/s")
    for row in d.crossings.itertuples():
        print(f"crossing: branches {row.branch_a} and {row.branch_b} at V = "
              f"{row.velocity:.4g} m/s, omega = {row.omega:.6g} rad/s")
    for row in d.veerings.itertuples():
        print(f"veering: branches {row.branch_a} and {row.branch_b} at V = "
              f"{row.velocity:.4g} m/s, gap {100 * row.gap:.2g} %")
    if args.circumference is not None:
        for row in d.resonances(args.circumference, orders).itertuples():
            print(f"resonance: order {row.order} meets branch {row.branch} at V = "
                  f"{row.velocity:.4g} m/s (omega = {row.omega:.6g} rad/s)")
    for path in (args.out, args.plot, args.save):
        if path:
            print(f"wrote {path}")
