"""Command-line interface: a thin layer over the public API.

``main(argv)`` builds one sub-command per module listed in :data:`SUBCOMMANDS`; each module
has ``register(subparsers, common[, common_without_velocity])`` which adds its parser and
sets ``func``. User errors
(bad parameters, supercritical requests, unwritable outputs) print one line on stderr and
exit with code 2; numerical failures exit with code 1; no tracebacks for either. Ctrl-C,
SIGTERM and SIGHUP stop the run, remove its temporary files and leave no output (exit codes
130, 143 and 129). A standard output closed early (``gyroshell frf ... --json | head -c 10``)
ends the command quietly, as coreutils' ``seq`` or ``yes`` end when SIGPIPE kills them:
no message and exit code 141 (128 + SIGPIPE), the code a shell reports for them
(``python -m json.tool`` also stays quiet, with exit code 32, the errno); the output files a
finished run wrote are kept.
"""

from __future__ import annotations

import importlib
import inspect
import os
import signal
import sys

from ..core.errors import ConvergenceError, ParameterError
from ..core.files import Terminated, termination_signals
from .common import ArgumentParser, UserError, common_parser

#: Sub-command modules (gyroshell.cli.<name>), in help order.
SUBCOMMANDS: tuple[str, ...] = ("static", "transient", "eigen", "frf", "study",
                               "reproduce", "bearing")


def build_parser() -> ArgumentParser:
    parser = ArgumentParser(
        prog="gyroshell",
        description="Dynamics of a moving magnetic tape modelled as a gyroscopic cylindrical "
                    "shell (SI units throughout).")
    from ..core.version import __version__
    parser.add_argument("--version", action="version", version=f"gyroshell {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True,
                                parser_class=ArgumentParser)
    common = common_parser()
    common_without_velocity = common_parser(velocity=False)
    for name in SUBCOMMANDS:
        try:
            module = importlib.import_module(f"{__name__}.{name}")
        except ModuleNotFoundError as exc:
            if exc.name == f"{__name__}.{name}":
                continue  # sub-command not built yet
            raise
        if len(inspect.signature(module.register).parameters) >= 3:
            module.register(sub, common, common_without_velocity)
        else:  # a sub-command every variant of which takes --velocity
            module.register(sub, common)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; returns the exit code (0 ok, 1 numerical failure, 2 user error)."""
    parser = build_parser()
    try:
        with termination_signals():
            args = parser.parse_args(argv)
            code = int(args.func(args) or 0)
            sys.stdout.flush()  # a closed pipe shows here, not at the interpreter's exit
            return code
    except BrokenPipeError:  # before OSError, of which it is one
        return _stdout_closed()
    except (UserError, ParameterError) as exc:
        return _fail(str(exc), 2)
    except OSError as exc:  # an output that failed while being written (disk full, ...)
        return _fail(str(exc), 2)
    except ConvergenceError as exc:
        return _fail(f"numerical failure: {exc}", 1)
    except Terminated as exc:
        return _fail(f"terminated by {exc}; no output written", 128 + exc.signum)
    except KeyboardInterrupt:
        return _fail("interrupted; no output written", 130)


def _fail(message: str, code: int) -> int:
    print(f"gyroshell: error: {message}", file=sys.stderr)
    return code


#: Exit code when standard output is closed early: 128 + SIGPIPE, as a shell reports for
#: coreutils killed by SIGPIPE (``seq 1 1000000 | head -c 10``).
BROKEN_PIPE_EXIT = 128 + getattr(signal, "SIGPIPE", 13)


def _stdout_closed() -> int:
    """Stop quietly after the reader of stdout went away (the recipe of Python's ``signal``
    documentation): stdout is pointed at the null device, so that the interpreter's final
    flush of what is still buffered does not report the broken pipe again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        try:
            os.dup2(devnull, sys.stdout.fileno())
        finally:
            os.close(devnull)
    except (OSError, ValueError):  # stdout is not a file descriptor (captured in tests)
        pass
    return BROKEN_PIPE_EXIT
