"""Issue 18 on `gyroshell frf` and `gyroshell transient`: hostile command lines are refused in
one line (exit 2) before any work, negative lists reach their validators, long work is
estimated (and refused beyond the time limit), and a closed stdout ends the command quietly."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
from conftest import WIDTH

COARSE = ["--spacing", WIDTH / 8, "--length-ratio", 2]
FRF = ["frf", *COARSE, "--quiet"]
TRANSIENT = ["transient", *COARSE, "--quiet", "--dt", "1e-6"]
WINDOWS = ["--contact-period", "40e-6", "--contact-duration", "20e-6"]

#: (case, argv, environment, what the one error line must say)
REFUSALS = [
    # 1. a moving-load transient's memory counts what it keeps per step and head
    ("moving head 3e7 steps", [*TRANSIENT, "--steps", "3e7", "--load-velocity", "1,0"], {},
     "a transient of 30000000 steps with 1 moving head needs about"),
    # 2. work that cannot finish in reasonable time is refused with its measured estimate
    ("frf 1e6 direct solves", [*FRF, "--frequencies", "0:1.5e5:1000000", "--method",
                               "direct"], {"GYROSHELL_TIME_LIMIT": "1"},
     "1000000 direct solves of 135 unknowns would take about"),
    ("transient 1e7 steps", [*TRANSIENT, "--steps", "1e7"], {"GYROSHELL_TIME_LIMIT": "1"},
     "a transient of 10000000 steps of 135 unknowns would take about"),
    ("time limit not a number", [*TRANSIENT, "--steps", "10"],
     {"GYROSHELL_TIME_LIMIT": "soon"}, "GYROSHELL_TIME_LIMIT must be a number of seconds > 0"),
    # 3. a frequency whose square overflows
    ("frequencies 1e300:1e301:3", [*FRF, "--frequencies", "1e300:1e301:3"], {},
     "frequencies must be in [0, 8.45154e+75] rad/s (rho omega^2 overflows the solvers' "
     "range above), got 1e+300"),
    ("frequencies 0:1:inf", [*FRF, "--frequencies", "0:1:inf"], {},
     "NUM must be an integer >= 1"),
    # 7. negative values reach the validator, for every option type
    ("frf --frequencies -5,10", [*FRF, "--frequencies", "-5,10"], {},
     "frequencies must be >= 0 rad/s, got -5"),
    ("frf --frequencies -1:5:3", [*FRF, "--frequencies", "-1:5:3"], {},
     "frequencies must be >= 0 rad/s, got -1"),
    ("frf --probe -0.001,0.003", [*FRF, "--frequencies", "0:1e5:20", "--probe",
                                  "-0.001,0.003"], {},
     "point (-0.001, 0.003) m must lie on the tape"),
    ("frf --rayleigh -1,0", [*FRF, "--frequencies", "0:1e5:20", "--rayleigh", "-1,0"], {},
     "error: --rayleigh A must be >= 0 1/s, got -1"),
    ("transient --rayleigh -1,0", [*TRANSIENT, "--steps", "5", "--rayleigh", "-1,0"], {},
     "error: --rayleigh A must be >= 0 1/s, got -1"),
    ("modes --rayleigh 0,-1", ["modes", *COARSE, "--rayleigh", "0,-1"], {},
     "error: --rayleigh B must be >= 0 s, got -1"),
    ("frf --damping -1", [*FRF, "--frequencies", "0:1e5:20", "--damping", "-1"], {},
     "error: --damping must be >= 0 N*s/m^3, got -1"),
    ("transient --contact-period -1", [*TRANSIENT, "--steps", "5", "--contact-period", "-1",
                                       "--contact-duration", "1e-5"], {},
     "contact period must be > 0 s, got -1"),
    ("sweep --velocities -5:5:3", ["sweep", *COARSE, "--velocities", "-5:5:3"], {},
     "velocity must be >= 0 m/s, got -5"),
    ("campbell --velocities -5,5", ["campbell", *COARSE, "--velocities", "-5,5"], {},
     "velocity must be >= 0 m/s, got -5"),
    ("static --velocity -1e", ["static", *COARSE, "--velocity", "-1e"], {},
     "not a number: '-1e'"),
    # 9. options ignored in some combination, nonsense ranges
    ("contact ramp without windows", [*TRANSIENT, "--steps", "5", "--contact-ramp", "1e-6"],
     {}, "--contact-ramp shapes the contact windows: it needs --contact-period and "
         "--contact-duration"),
    ("window shorter than a step", [*TRANSIENT, "--steps", "50", "--contact-period", "1e-5",
                                    "--contact-duration", "1e-9"], {},
     "contact duration must span at least 2 time steps (>= 2e-06 s with dt = 1e-06 s), "
     "got 1e-09 s"),
    ("ramp shorter than a step", [*TRANSIENT, "--steps", "50", *WINDOWS, "--contact-ramp",
                                  "1e-7"], {},
     "contact ramp must be 0 (abrupt) or at least one time step (dt = 1e-06 s), got 1e-07 s"),
    ("gap shorter than a step", [*TRANSIENT, "--steps", "50", "--contact-period", "20.5e-6",
                                 "--contact-duration", "20e-6"], {},
     "contact period must equal the contact duration (always in contact) or exceed it by "
     "at least one time step"),
    ("frf --tol 2", [*FRF, "--frequencies", "0:1e5:20", "--tol", "2"], {},
     "tol must be in (1e-08, 0.1], got 2"),
    ("frf --tol 1e-9", [*FRF, "--frequencies", "0:1e5:20", "--tol", "1e-9"], {},
     "tol must be in (1e-08, 0.1], got 1e-09"),
    ("frf --tol with direct", [*FRF, "--frequencies", "0:1e5:20", "--method", "direct",
                               "--tol", "1e-3"], {},
     "--tol sets the reduced model; --method direct solves every frequency without one"),
    ("frf --max-points with direct", [*FRF, "--frequencies", "0:1e5:20", "--method",
                                      "direct", "--max-points", "5"], {},
     "--max-points sets the reduced model"),
    ("frf --max-points 1000", [*FRF, "--frequencies", "0:1e5:20", "--max-points", "1000"],
     {}, "max_points must be an integer in [1, 100], got 1000"),
    ("frf NUM = 1 drops STOP", [*FRF, "--frequencies", "0:1e5:1"], {},
     "NUM = 1 gives START alone; use START = STOP or NUM >= 2"),
    ("snapshot every > steps", [*TRANSIENT, "--steps", "5", "--snapshot-every", "10",
                                "--snapshots", "s.npz"], {},
     "--snapshot-every must be <= --steps (5), got 10"),
    ("snapshots not .npz", [*TRANSIENT, "--steps", "5", "--snapshot-every", "1",
                            "--snapshots", "s.csv"], {},
     "--snapshots must be a .npz file, got s.csv"),
]


@pytest.mark.parametrize(("case", "argv", "env", "match"), REFUSALS,
                         ids=[r[0] for r in REFUSALS])
def test_refused_in_one_line_with_exit_2(cli, tmp_path, monkeypatch, case, argv, env, match):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("GYROSHELL_MEMORY_LIMIT", "8e9")  # the same refusals on any machine
    for name, value in env.items():
        monkeypatch.setenv(name, value)
    run = cli([*argv, "--out", "out.csv"] if argv[0] in ("frf", "transient") else argv)
    assert run.code == 2, run.err
    assert len(run.error_lines) == 1 and run.error_lines[0].startswith("gyroshell")
    assert match in run.err and "Traceback" not in run.err and run.out == ""
    assert list(tmp_path.iterdir()) == []


def test_time_refusal_says_it_is_an_estimate_and_how_to_lift_the_limit(cli, monkeypatch):
    monkeypatch.setenv("GYROSHELL_TIME_LIMIT", "1")
    run = cli([*TRANSIENT, "--steps", "1e7"])
    (line,) = run.error_lines
    assert "(an estimate from" in line and "s per step measured on 8 trial steps)" in line
    assert "more than the limit 1 s; use fewer steps" in line
    assert line.endswith("(or set GYROSHELL_TIME_LIMIT, seconds)")


def test_head_moving_upstream_is_valid(cli):
    run = cli([*TRANSIENT, "--steps", "20", "--load-position", "0.01,0.003",
               "--load-velocity", "-40,0", "--json"])
    assert run.code == 0, run.err
    assert '"moving_load": true' in run.out


def test_contact_windows_of_whole_steps_are_accepted(cli):
    run = cli([*TRANSIENT, "--steps", "40", "--load-position", "0.003,0.003",
               "--contact-period", "4e-6", "--contact-duration", "2e-6", "--contact-ramp",
               "1e-6"])
    assert run.code == 0, run.err


def test_conditionally_stable_newmark_warns_in_one_line(cli):
    run = cli([*TRANSIENT, "--steps", "5", "--gamma", "0.3"])
    assert run.code == 0
    (line,) = run.error_lines
    assert line.startswith("gyroshell: warning: beta = 0.25, gamma = 0.3 lie outside")


# ----- refusals before any work ------------------------------------------------------------
@pytest.mark.slow
def test_refusals_do_not_load_the_engines():
    """Every refusal above except the measured time estimates happens before the frequency
    response, Newmark or any factorization module is even imported."""
    argvs = [[str(a) for a in argv] for case, argv, env, _ in REFUSALS
             if not env and argv[0] in ("frf", "transient")]
    code = ("import os, sys, tempfile\n"
            "os.chdir(tempfile.mkdtemp())\n"
            "from gyroshell.cli import main\n"
            f"for argv in {argvs!r}:\n"
            "    assert main(argv) == 2, argv\n"
            "engines = ('gyroshell.engines.frequency_response', 'gyroshell.engines.newmark',\n"
            "           'gyroshell.linalg.factorization', 'pandas', 'matplotlib')\n"
            "print(sorted(m for m in engines if m in sys.modules))")
    env = {**os.environ, "GYROSHELL_MEMORY_LIMIT": "8e9"}
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120, env=env)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split() == ["[]"]


# ----- a closed stdout ---------------------------------------------------------------------
def closed_stdout_run(argv: list[str], cwd) -> subprocess.CompletedProcess:
    """Run ``python -m gyroshell argv`` with stdout a pipe whose reader has already gone
    (what `... | head -c 10` becomes once head exits)."""
    read, write = os.pipe()
    os.close(read)
    try:
        return subprocess.run([sys.executable, "-m", "gyroshell", *map(str, argv)],
                              stdout=write, stderr=subprocess.PIPE, text=True, cwd=cwd,
                              timeout=120)
    finally:
        os.close(write)


def test_frf_json_into_a_closed_pipe_exits_quietly_with_141(tmp_path):
    proc = closed_stdout_run([*FRF, "--frequencies", "0:1e5:20", "--json", "--out", "f.csv"],
                             tmp_path)
    assert proc.returncode == 141 and proc.stderr == ""
    assert (tmp_path / "f.csv").exists()  # the finished run's file is kept, as written


@pytest.mark.slow
@pytest.mark.parametrize("argv", [[*TRANSIENT, "--steps", "5"], ["static", *COARSE],
                                  ["frf", "--help"]], ids=["transient", "static", "help"])
def test_every_sub_command_into_a_closed_pipe_exits_quietly(tmp_path, argv):
    proc = closed_stdout_run(argv, tmp_path)
    # argparse itself drops a help text it cannot write (exit 0); the commands exit 141
    assert proc.returncode == (0 if "--help" in argv else 141) and proc.stderr == ""


def test_closed_pipe_through_head_in_a_shell(tmp_path):
    """The issue's own command line: a real `| head -c 10`."""
    argv = " ".join(str(a) for a in [*FRF, "--frequencies", "0:1e5:200", "--json"])
    shell = (f"{sys.executable} -m gyroshell {argv} | head -c 10 >/dev/null; "
             "echo ${PIPESTATUS[0]}")
    proc = subprocess.run(["bash", "-c", shell], capture_output=True, text=True, cwd=tmp_path,
                          timeout=120)
    assert proc.stdout.strip() in ("0", "141") and proc.stderr == ""
