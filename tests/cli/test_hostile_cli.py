"""Hostile command lines: each is refused in one line (exit 2, no traceback), before any
work, and leaves the output folder as it was."""

from __future__ import annotations

import pytest
from conftest import WIDTH

COARSE = ["--spacing", WIDTH / 8, "--length-ratio", 2]
TRANSIENT = ["transient", *COARSE, "--quiet"]

#: (case, argv, what the one error line must say)
REFUSALS = [
    # 1. size before work
    ("spacing 1e-9", ["static", "--spacing", "1e-9"], "more than the sparse solver's limit"),
    ("length ratio 1e12", ["static", "--length-ratio", "1e12"], "factor entries"),
    ("grid beyond memory", ["static", "--spacing", "5e-6"], "more than the limit"),
    ("steps 1e12", [*TRANSIENT, "--steps", "1e12", "--dt", "2e-6"],
     "a transient of 1000000000000 steps needs about"),
    ("snapshots every step", ["transient", "--length-ratio", "19", "--steps", "200000",
                              "--dt", "2e-6", "--snapshot-every", "1", "--snapshots", "s.npz"],
     "200001 full fields"),
    ("velocities 0:100:1e-12", ["sweep", *COARSE, "--velocities", "0:100:1e-12"],
     "gives 1e+14 speeds, more than the limit 10000"),
    ("campbell velocities 0:100:1e-12", ["campbell", *COARSE, "--velocities", "0:100:1e-12"],
     "--velocities '0:100:1e-12' gives 1e+14 speeds"),
    ("study NUM 1e12", ["study", *COARSE, "--vary", "velocity=0:100:1000000000000",
                        "--compute", "static"], "has 1e+12 points, more than the limit"),
    ("study product too large", ["study", *COARSE, "--vary", "velocity=0:100:1000",
                                 "--vary", "tension=1:100:1000", "--compute", "static"],
     "the study has 1e+06 points, more than the limit"),
    ("campbell velocities 0:inf:10", ["campbell", *COARSE, "--velocities", "0:inf:10"],
     "every number must be finite"),
    ("length ratio 1e-6", ["critical", "--length-ratio", "1e-6"],
     "length_ratio must leave at least 8 intervals along the length"),
    # 2. numbers at the edges
    ("V^2 overflows", ["static", *COARSE, "--velocity", "1e200"], "velocity must be <="),
    ("V^2 overflows in modes", ["modes", *COARSE, "--velocity", "1e160"],
     "velocity must be <="),
    ("velocities 0:inf:10", ["sweep", *COARSE, "--velocities", "0:inf:10"],
     "every number must be finite"),
    ("velocities nan", ["sweep", *COARSE, "--velocities", "1,nan"],
     "every number must be finite"),
    ("dt underflows beta dt^2", [*TRANSIENT, "--steps", "5", "--dt", "1e-170"],
     "beta x dt^2 = 0 s^2 underflows"),
    ("dt subnormal beta dt^2", [*TRANSIENT, "--steps", "5", "--dt", "1e-155"],
     "underflows"),
    ("dt overflows", [*TRANSIENT, "--steps", "5", "--dt", "1e160"], "too large"),
    ("E = 1e-300", ["static", *COARSE, "--youngs-modulus", "1e-300"],
     "bending_rigidity (from youngs_modulus, thickness, poisson) underflows"),
    ("E = 1e308", ["static", *COARSE, "--youngs-modulus", "1e308"], "overflows"),
    ("density 1e-300", ["static", *COARSE, "--density", "1e-300"],
     "density x spacing^2 (from density and spacing) underflows the solvers' range"),
    ("radius 1e-300", ["static", *COARSE, "--radius", "1e-300"],
     "foundation_stiffness (from youngs_modulus, thickness, radius, poisson) overflows"),
    ("spacing 1e-300", ["static", "--spacing", "1e-300"], "bending_rigidity / spacing^2"),
    ("spacing 5e-324", ["static", "--spacing", "5e-324"], "infinite number of intervals"),
    ("E = 1e300 in the eigen-solver", ["modes", *COARSE, "--youngs-modulus", "1e300"],
     "overflows the solvers' range"),
    ("T = 1e300 in the eigen-solver", ["modes", *COARSE, "--tension", "1e300"],
     "tension / density (from tension and density) overflows the solvers' range"),
    ("V = 1e150 in the eigen-solver", ["modes", *COARSE, "--velocity", "1e150"],
     "velocity must be <= 8.45154e+75 m/s"),
    ("heavy tape", ["modes", *COARSE, "--density", "1e300"],
     "density x spacing^2 (from density and spacing) overflows the solvers' range"),
    ("D = 1e-320", ["static", *COARSE, "--bending-rigidity", "1e-320"], "underflows"),
    # 6. CLI habits
    ("negative spacing reaches the validator", ["static", "--spacing", "-1e-4"],
     "spacing must be > 0 m, got -0.0001"),
    ("negative exponent form", ["static", *COARSE, "--velocity", "-2.5e1"],
     "velocity must be >= 0 m/s, got -25"),
    ("no abbreviations", ["static", *COARSE, "--veloc", "5"], "unrecognized arguments"),
    ("critical refuses --velocity", ["critical", *COARSE, "--velocity", "5"],
     "unrecognized arguments: --velocity 5"),
    ("sweep refuses --velocity", ["sweep", *COARSE, "--velocity", "5"],
     "unrecognized arguments: --velocity 5"),
    ("backend choices", [*TRANSIENT, "--steps", "5", "--dt", "2e-6", "--backend", "fast"],
     "invalid choice: 'fast'"),
    ("steps not whole", [*TRANSIENT, "--steps", "2.5", "--dt", "2e-6"],
     "not an integer: '2.5'"),
]


@pytest.mark.parametrize(("case", "argv", "match"), REFUSALS, ids=[r[0] for r in REFUSALS])
def test_refused_in_one_line_with_exit_2(cli, tmp_path, monkeypatch, case, argv, match):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("GYROSHELL_MEMORY_LIMIT", "8e9")  # the same refusals on any machine
    run = cli(argv)
    assert run.code == 2, run.err
    assert len(run.error_lines) == 1 and run.error_lines[0].startswith("gyroshell")
    assert "error: " in run.err and match in run.err
    assert "Traceback" not in run.err and run.out == ""
    assert list(tmp_path.iterdir()) == []


def test_memory_limit_comes_from_the_environment(cli, monkeypatch):
    monkeypatch.setenv("GYROSHELL_MEMORY_LIMIT", "1e5")
    run = cli(["static", *COARSE])
    assert run.code == 2 and "more than the limit 100 kB" in run.err


@pytest.mark.slow
def test_refusal_in_a_fresh_process_is_one_line(cli_process, tmp_path):
    run = cli_process(["sweep", "--velocities", "0:100:1e-12", "--out", "s.csv"],
                      cwd=tmp_path)
    assert run.code == 2
    assert run.err == ("gyroshell: error: --velocities '0:100:1e-12' gives 1e+14 speeds, more "
                       "than the limit 10000 per sweep (one eigen-solve each); use a larger "
                       "step\n")
    assert list(tmp_path.iterdir()) == []


def test_exponent_integers_are_accepted_as_counts(cli, tmp_path):
    run = cli([*TRANSIENT, "--steps", "1e1", "--dt", "2e-6", "--json"])
    assert run.code == 0, run.err
    assert '"steps": 10' in run.out


@pytest.mark.parametrize(("velocity", "where"), [("101.1", "within 1 % of"),
                                               ("120", "above")])
def test_transient_near_or_above_critical_warns_once_and_runs(cli, velocity, where):
    # this grid's divergence speed is 101.06 m/s; the estimate 101.20 m/s
    run = cli([*TRANSIENT, "--velocity", velocity, "--steps", "20", "--dt", "2e-6"])
    assert run.code == 0, run.err
    (line,) = run.error_lines
    assert line.startswith(f"gyroshell: warning: V = {velocity} m/s is {where} the critical")


def test_transient_below_critical_does_not_warn(cli):
    run = cli([*TRANSIENT, "--velocity", "95", "--steps", "20", "--dt", "2e-6"])
    assert run.code == 0 and run.err == ""


def test_backend_choices_are_the_factorization_back_ends():
    from gyroshell.cli.transient import BACKEND_CHOICES
    from gyroshell.linalg.factorization import BACKENDS

    assert BACKEND_CHOICES == ("auto", *BACKENDS)


def test_sweep_list_of_speeds_is_limited_too(cli):
    speeds = ",".join(["1"] * 10_001)
    run = cli(["sweep", *COARSE, "--velocities", speeds])
    assert run.code == 2 and "gives 1e+04 speeds" in run.err


@pytest.mark.slow
def test_import_and_refusals_do_not_load_the_engines():
    """`import gyroshell` loads neither scipy, pandas nor matplotlib; a refusal loads neither
    pandas nor matplotlib (building the parser imports what sub-commands need for their
    defaults)."""
    import subprocess
    import sys

    code = ("import sys, gyroshell\n"
            "heavy = ('scipy', 'pandas', 'matplotlib')\n"
            "print(sorted(m for m in heavy if m in sys.modules))\n"
            "from gyroshell.cli import main\n"
            "assert main(['sweep', '--velocities', '0:inf:1', '--plot', 'a.png']) == 2\n"
            "assert main(['static', '--spacing', '1e-9']) == 2\n"
            "print(sorted(m for m in heavy[1:] if m in sys.modules))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=60)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split() == ["[]", "[]"]


def test_public_names_resolve_lazily():
    import gyroshell

    for name in gyroshell.__all__:
        assert getattr(gyroshell, name) is not None
    import gyroshell.engines.divergence
    import gyroshell.studies.sweep  # noqa: F401 - a submodule does not shadow a public function

    assert callable(gyroshell.sweep) and callable(gyroshell.divergence)
    assert gyroshell.__version__ and gyroshell.__version__[0].isdigit()


EXTREME_FLAGS = ("--youngs-modulus", "--poisson", "--thickness", "--radius", "--density",
                 "--tension", "--width", "--bending-rigidity", "--foundation-stiffness",
                 "--load", "--length-ratio", "--spacing", "--velocity")
EXTREME_VALUES = ("5e-324", "1e-308", "1e-300", "1e-150", "1e-30", "1e30", "1e150", "1e300",
                  "1.7e308", "0", "-0", "-1e-300")


@pytest.mark.slow
@pytest.mark.parametrize("command", [["static"], ["modes", "--count", "2"]],
                         ids=["static", "modes"])
def test_every_option_at_every_extreme_answers_or_refuses_in_one_line(cli, command):
    """Each tape option set to each extreme double: a result (exit 0, silent stderr) or one
    refusal line (exit 2); never a traceback, an overflow or a numerical failure."""
    failures = []
    for flag in EXTREME_FLAGS:
        for value in EXTREME_VALUES:
            run = cli([*command, *COARSE, flag, value])
            ok = (run.code == 0 and run.err == "") or (
                run.code == 2 and len(run.error_lines) == 1
                and run.error_lines[0].startswith("gyroshell"))
            if not ok:
                failures.append(f"{flag} {value}: exit {run.code}: {run.err[:160]!r}")
    assert failures == []
