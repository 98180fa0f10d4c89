"""Options shared by every sub-command, and the parser that fails in one line."""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import re
import sys
import warnings

from ..tape.parameters import EDGE_CHOICES, TapeParameters

#: Option values that start with a negative number: ``-1e-4``, ``-.5``, ``-inf``, and the
#: comma lists and ``START:STOP:NUM`` ranges that begin with one (``-5,10``, ``-5:5:3``,
#: ``-0.001,0.003``). argparse's own pattern misses exponents and lists, so
#: ``--spacing -1e-4`` or ``--load-velocity -40,0`` would be taken for an option; no option
#: of gyroshell starts with a dash and a digit (or ``inf``, ``nan``), so every such word is a
#: value and reaches its option's validator, which names the allowed range (``-1e`` gets
#: "not a number", not "expected one argument").
NEGATIVE_NUMBER = re.compile(r"^-(\d|\.\d|inf|nan)", re.IGNORECASE)


class UserError(Exception):
    """A command-line mistake: reported in one line, exit code 2."""


class ArgumentParser(argparse.ArgumentParser):
    """argparse, but a usage error is one line on stderr and exit code 2, option names must be
    spelled out (no abbreviations), and negative numbers are option values."""

    def __init__(self, *args, **kwargs) -> None:
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = NEGATIVE_NUMBER

    def error(self, message: str):  # noqa: D401 - argparse API
        print(f"{self.prog}: error: {message}", file=sys.stderr)
        raise SystemExit(2)


#: The release from which the old spellings of renamed options are no longer read.
OLD_SPELLINGS_END = "0.3"


class _OneFolder(argparse.Action):
    """``--out-dir DIR``, or its old spelling ``--out DIR`` with a one-line notice on
    stderr; both at once are refused."""

    def __call__(self, parser, namespace, values, option_string=None) -> None:
        given = getattr(namespace, "out_dir_flag", None)
        if given is not None and given != option_string:
            parser.error(f"{given} and {option_string} both name the output folder: give "
                         "--out-dir alone")
        if option_string == "--out":
            notice(f"{parser.prog} --out DIR is now --out-dir DIR (the folder of the "
                   f"files); --out goes in release {OLD_SPELLINGS_END}")
        namespace.out_dir_flag = option_string
        setattr(namespace, self.dest, values)


def add_out_dir_option(p: argparse.ArgumentParser, text: str) -> None:
    """``--out-dir DIR`` (help ``text``; ``args.out``), and ``--out DIR``, its old
    spelling, read until :data:`OLD_SPELLINGS_END` with a notice: ``--out`` names a file
    in every sub-command (a table), ``--out-dir`` a folder."""
    p.add_argument("--out-dir", dest="out", metavar="DIR", default=None, action=_OneFolder,
                   help=text)
    p.add_argument("--out", dest="out", metavar="DIR", default=None, action=_OneFolder,
                   help=f"the old spelling of --out-dir, read with a notice until release "
                        f"{OLD_SPELLINGS_END}")


def real(text: str) -> float:
    """A finite real number."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be finite, got {text!r}")
    return value


#: The words a yes/no option value may be (any case), and what they mean.
BOOLEAN_WORDS = {"true": True, "yes": True, "1": True, "false": False, "no": False, "0": False}


def boolean(text: str) -> bool:
    """True or False from ``true``/``false``, ``yes``/``no`` or ``1``/``0`` (any case).

    Examples
    --------
    >>> boolean("True"), boolean("no"), boolean(" 1 ")
    (True, False, True)
    """
    try:
        return BOOLEAN_WORDS[text.strip().lower()]
    except KeyError:
        raise argparse.ArgumentTypeError(f"not true or false: {text!r} (give true, false, "
                                         "yes, no, 1 or 0)") from None


def positive_int(text: str) -> int:
    """An integer >= 1; whole numbers in exponent form (``1e6``) are accepted."""
    try:
        value = int(text)
    except ValueError:
        try:
            number = float(text)
        except ValueError:
            number = math.nan
        if not (math.isfinite(number) and number.is_integer()):
            raise argparse.ArgumentTypeError(f"not an integer: {text!r}") from None
        value = int(number)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1, got {value}")
    return value


def stiffness_list(text: str) -> tuple[float, float, float, float]:
    """Four finite numbers ``D11,D22,D12,D66`` (N*m) of --bending-stiffness.

    Examples
    --------
    >>> stiffness_list("2e-7, 1e-7, 3e-8, 4e-8")
    (2e-07, 1e-07, 3e-08, 4e-08)
    """
    items = [item.strip() for item in text.split(",")]
    if len(items) != len(BENDING_STIFFNESS_NAMES):
        raise argparse.ArgumentTypeError(
            f"give four numbers {','.join(BENDING_STIFFNESS_NAMES)} (N*m), got {text!r}")
    return tuple(real(item) for item in items)


def parse_velocities(text: str, *, option: str = "--velocities") -> list[float]:
    """Speeds, m/s, from an option's text: :func:`gyroshell.studies.sweep.parse_velocities`
    (the old START:STOP:STEP form with a one-line notice on stderr)."""
    from ..studies.sweep import parse_velocities as parse

    return parse(text, option=option, notice=notice)


@contextlib.contextmanager
def warnings_as_lines(category: type[Warning]):
    """Within it, warnings of ``category`` become one ``gyroshell: warning:`` line each on
    stderr (as they are raised, once the block ends); any other warning is raised again."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", category)
        yield
    for warning in caught:
        if issubclass(warning.category, category):
            print(f"gyroshell: warning: {warning.message}", file=sys.stderr, flush=True)
        else:
            warnings.warn_explicit(warning.message, warning.category, warning.filename,
                                   warning.lineno)


def notice(message: str) -> None:
    """One ``gyroshell: notice:`` line on stderr (a deprecated form that still works)."""
    print(f"gyroshell: notice: {message}", file=sys.stderr, flush=True)


#: The help of every option that takes a range of values: one form everywhere.
RANGE_HELP = ("START:STOP:NUM (NUM evenly spaced values from START to STOP, both "
              "included) or a list V1,V2,...")


#: (flag, TapeParameters field, help) for the physical overrides.
TAPE_OVERRIDES = (
    ("--youngs-modulus", "youngs_modulus", "Young's modulus E, Pa (default 4e9)"),
    ("--poisson", "poisson", "Poisson's ratio, in (-1, 0.5) (default 0.3)"),
    ("--youngs-modulus-y", "youngs_modulus_y",
     "Young's modulus across the tape E_y, Pa (default: E_x, isotropic)"),
    ("--shear-modulus", "shear_modulus",
     "in-plane shear modulus G_xy, Pa (default: E_x / (2 (1 + nu_xy)), isotropic)"),
    ("--thickness", "thickness", "shell thickness c, m (default 20e-6)"),
    ("--radius", "radius", "wrap radius R, m (default 20e-3)"),
    ("--density", "density", "areal density rho, kg/m^2 (default 0.014)"),
    ("--tension", "tension", "tension per unit width T, N/m (default 90)"),
    ("--width", "width", "tape width L_y, m (default 6.35e-3)"),
    ("--bending-rigidity", "bending_rigidity",
     "override D, N*m (default E c^3 / (12 (1 - nu^2)))"),
    ("--foundation-stiffness", "foundation_stiffness",
     "override the shell stiffness k, N/m^3 (default E c / (R^2 (1 - nu^2)))"),
    ("--membrane-stiffness", "membrane_stiffness",
     "membrane stiffness along the tape A11, N/m; sets k = A11 / R^2 (default: from "
     "E_x, E_y, nu_xy and c, or the layers)"),
    ("--load", "load",
     "peak pressure P_0 of the Gaussian load (Eq. 17), Pa (default 200)"),
)

#: (flag, TapeParameters field, the option it is another name of, help): the orthotropic
#: names of two isotropic options; typing both names of one field is refused.
TAPE_ALIASES = (
    ("--youngs-modulus-x", "youngs_modulus", "--youngs-modulus",
     "Young's modulus along the tape E_x, Pa (another name of --youngs-modulus)"),
    ("--poisson-xy", "poisson", "--poisson",
     "major Poisson's ratio nu_xy (strain across per strain along; another name of "
     "--poisson)"),
)

#: The bending stiffnesses, typed as one comma list: (flag, TapeParameters field, help).
BENDING_STIFFNESS = (
    "--bending-stiffness", "bending_stiffness",
    "the orthotropic bending stiffnesses D11,D22,D12,D66, N*m each (D11 along the tape, "
    "D22 across, D12 the coupling, D66 the twist; default: from E_x, E_y, G_xy, nu_xy and "
    "c, or the layers)")
#: Names of the bending stiffnesses, in the order --bending-stiffness takes them.
BENDING_STIFFNESS_NAMES = ("D11", "D22", "D12", "D66")


class _Unset(float):
    """A float default that was not typed on the command line (a --config file may set it)."""


class _UnsetText(str):
    """A text default that was not typed on the command line."""


def common_parser(*, velocity: bool = True) -> argparse.ArgumentParser:
    """Parent parser with the tape options; ``--velocity`` only for sub-commands that use
    one speed (so that ``critical --velocity 5`` is refused, not ignored)."""
    p = argparse.ArgumentParser(add_help=False)
    g = p.add_argument_group("tape model (SI units; defaults: the paper's Table 1)")
    g.add_argument("--config", metavar="TAPE.toml", default=None,
                   help="tape definition file (TOML, values with units, e.g. tension = "
                        "\"90 N/m\"); options given here override it")
    g.add_argument("--length-ratio", type=real, default=_Unset(4.0),
                   help="L_x / L_y, > 0 (default 4; the paper also uses 19)")
    g.add_argument("--edges", choices=EDGE_CHOICES, default=_UnsetText("free"),
                   help="lateral edges y = 0, L_y (default free; ends are simply supported)")
    g.add_argument("--spacing", type=real, default=_Unset(1.549e-4),
                   help="grid spacing, m (default 1.549e-4: 41 intervals across)")
    if velocity:
        g.add_argument("--velocity", type=real, default=_Unset(0.0),
                       help="tape transport speed V, m/s, >= 0 (default 0)")
    add_tape_overrides(g, TAPE_OVERRIDES)
    return p


def _dest(flag: str) -> str:
    return flag[2:].replace("-", "_")


def add_tape_overrides(group, options=TAPE_OVERRIDES, *, help_of=None) -> None:
    """Add the physical tape options to an argparse group: ``options`` (a selection of
    :data:`TAPE_OVERRIDES`), the aliases of :data:`TAPE_ALIASES` and
    --bending-stiffness; ``help_of`` maps a field to a help text replacing its own.
    Every one defaults to None (not typed)."""
    help_of = help_of or {}
    for flag, field, text in options:
        group.add_argument(flag, dest=field, metavar=_dest(flag).upper(), type=real,
                           default=None, help=help_of.get(field, text))
    for flag, _field, _original, text in TAPE_ALIASES:
        group.add_argument(flag, dest=_dest(flag), metavar=_dest(flag).upper(), type=real,
                           default=None, help=text)
    flag, field, text = BENDING_STIFFNESS
    group.add_argument(flag, dest=field, metavar=",".join(BENDING_STIFFNESS_NAMES),
                       type=stiffness_list, default=None, help=text)


def typed_overrides(args: argparse.Namespace, options=TAPE_OVERRIDES) -> dict:
    """The TapeParameters fields of the physical options typed: {field: value}, an alias
    read as its original.

    Raises
    ------
    UserError
        If an option and its alias (--youngs-modulus and --youngs-modulus-x, --poisson and
        --poisson-xy) are both typed.

    Examples
    --------
    >>> args = common_parser().parse_args(["--youngs-modulus-x", "8e9", "--tension", "60"])
    >>> typed_overrides(args)
    {'tension': 60.0, 'youngs_modulus': 8000000000.0}
    """
    typed = {field: getattr(args, field) for _flag, field, _text in options
             if getattr(args, field, None) is not None}
    for flag, field, original, _text in TAPE_ALIASES:
        value = getattr(args, _dest(flag), None)
        if value is None:
            continue
        if field in typed:
            raise UserError(f"{flag} and {original} are two names of {field}: give one")
        typed[field] = value
    field = BENDING_STIFFNESS[1]
    if getattr(args, field, None) is not None:
        typed[field] = getattr(args, field)
    return typed


def parameters_from_args(args: argparse.Namespace) -> TapeParameters:
    """TapeParameters from the common options (validated; raises ParameterError).

    With ``--config`` the file's values replace the defaults of the options not typed (and
    its ``velocity`` becomes ``args.velocity``).
    """
    kwargs = typed_overrides(args)
    if getattr(args, "config", None):
        return _with_config(args, kwargs)
    return TapeParameters(length_ratio=args.length_ratio, edges=args.edges,
                          spacing=args.spacing, **kwargs)


def typed_tape_options(args: argparse.Namespace) -> dict[str, str]:
    """The tape options typed on the command line: {TapeParameters field or 'velocity':
    flag}. Defaults and --config values are not typed.

    Examples
    --------
    >>> args = common_parser().parse_args(["--tension", "80", "--spacing", "1e-4"])
    >>> typed_tape_options(args)
    {'tension': '--tension', 'spacing': '--spacing'}
    """
    typed = {field: flag for flag, field, _text in TAPE_OVERRIDES
             if getattr(args, field, None) is not None}
    for flag, field, _original, _text in TAPE_ALIASES:
        if getattr(args, _dest(flag), None) is not None:
            typed[field] = flag
    flag, field, _text = BENDING_STIFFNESS
    if getattr(args, field, None) is not None:
        typed[field] = flag
    for name in ("length_ratio", "edges", "spacing", "velocity"):
        value = getattr(args, name, None)
        if value is not None and not isinstance(value, (_Unset, _UnsetText)):
            typed[name] = "--" + name.replace("_", "-")
    return typed


def _with_config(args: argparse.Namespace, kwargs: dict) -> TapeParameters:
    from ..tape.config import load_config

    cfg = load_config(args.config, tables=getattr(args, "config_tables", ()))
    args.tables = cfg.tables  # the other tables a sub-command asked for ([head])
    typed = typed_tape_options(args)
    kwargs.update({name: getattr(args, name) for name in ("length_ratio", "edges", "spacing")
                   if name in typed})
    if "velocity" not in typed and hasattr(args, "velocity") and cfg.velocity is not None:
        args.velocity = cfg.velocity
    return cfg.params.replace(**kwargs)


def grid_of(params: TapeParameters):
    """The grid of ``params``, refused (size, interval counts) before scipy is even loaded."""
    from ..tape.grid import Grid

    return Grid.from_parameters(params)


def tape_from_args(args: argparse.Namespace):
    """(parameters, velocity in m/s, grid) of the tape options, each checked, before scipy
    is loaded."""
    params = parameters_from_args(args)
    return params, params.check_velocity(args.velocity), grid_of(params)


def print_json(obj: dict) -> None:
    """One JSON object on stdout."""
    print(json.dumps(obj, indent=None, sort_keys=False))
