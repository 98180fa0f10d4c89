"""The Python API of the frequency response, Newmark and moving loads refuses hostile
arguments with a ParameterError naming the argument (issue 18), before any large work."""

from __future__ import annotations

import math

import numpy as np
import pytest

import gyroshell as gs
from gyroshell import (
    ContactWindows,
    MovingLoad,
    StraightPath,
    TapeParameters,
    frequency_response,
    march,
)
from gyroshell.core.errors import ParameterError
from gyroshell.engines.frequency_response import ReducedModel
from gyroshell.engines.newmark import Newmark

CONTRACT = "path must map times t (s) to positions (x, y) in m"


def upstream(t):
    """A head moving upstream at 40 m/s (valid)."""
    return 0.01 - 40.0 * np.asarray(t), 0.003 + 0.0 * np.asarray(t)


#: (case, path, what the message must say)
BROKEN_PATHS = [
    ("wrong shape", lambda t: np.zeros((3, np.size(t))), "it returned an array of shape (3, 1)"),
    ("strings", lambda t: ("a", "b"), "it returned ('a', 'b')"),
    ("None", lambda t: None, "it returned None"),
    ("complex", lambda t: (0.005 + 0j * np.asarray(t), 0.003), "it returned"),
    ("NaN", lambda t: (np.full(np.shape(t), np.nan), 0.003),
     "path must return finite positions (x, y) in m, got (nan, 0.003) at t = 0 s"),
    ("NaN later", lambda t: (np.where(np.asarray(t) > 5e-6, np.nan, 0.005), 0.003),
     "got (nan, 0.003) at t = 6e-06 s"),
    ("raises", lambda t: 1 / 0, "it raised ZeroDivisionError: division by zero"),
    ("raises KeyError", lambda t: {}["x"], "it raised KeyError: 'x'"),
]


@pytest.mark.parametrize(("case", "path", "match"), BROKEN_PATHS,
                         ids=[c[0] for c in BROKEN_PATHS])
def test_a_broken_path_is_a_parameter_error_naming_the_path(small, case, path, match):
    with pytest.raises(ParameterError) as info:
        march(small, 10.0, dt=1e-6, steps=20, load=MovingLoad(path))
    message = str(info.value)
    assert message.startswith("path ") and match in message and "\n" not in message
    if case not in ("NaN", "NaN later"):
        assert CONTRACT in message


def test_a_broken_path_of_one_of_several_heads_is_named(small):
    good = MovingLoad(StraightPath((0.005, 0.003)))
    with pytest.raises(ParameterError, match="^path of head 1 must map"):
        march(small, 10.0, dt=1e-6, steps=5, load=[good, MovingLoad(lambda t: "x")])


def test_a_path_of_one_time_at_a_time_and_one_moving_upstream_are_valid(small):
    scalar = MovingLoad(lambda t: (0.005 + 40.0 * t, 0.003 + math.sin(t)))
    assert np.all(np.isfinite(march(small, 10.0, dt=1e-6, steps=20, load=scalar).load_point))
    run = march(small, 10.0, dt=1e-6, steps=20, load=MovingLoad(upstream))
    assert np.abs(run.load_point).max() > 0


@pytest.mark.parametrize(("contact", "match"), [
    (ContactWindows(1e-5, 1e-6), "contact duration must span at least 2 time steps"),
    (ContactWindows(1e-5, 4e-6, ramp=0.5e-6), "contact ramp must be 0 (abrupt) or at least one"),
    (ContactWindows(1e-5, 9.5e-6), "contact period must equal the contact duration"),
], ids=["window", "ramp", "gap"])
def test_contact_windows_the_time_step_cannot_resolve_are_refused(small, contact, match):
    head = MovingLoad(StraightPath((0.005, 0.003)), contact=contact)
    with pytest.raises(ParameterError, match=match.replace("(", r"\(").replace(")", r"\)")):
        Newmark(small, 10.0, dt=1e-6).march(20, load=head)


def test_moving_head_memory_counts_what_each_step_keeps(small, monkeypatch):
    monkeypatch.setenv("GYROSHELL_MEMORY_LIMIT", "1e9")
    stepper = Newmark(small, 10.0, dt=1e-9)
    head = MovingLoad(StraightPath((0.005, 0.003)))
    stepper.march(10, load=head)  # a short run fits
    with pytest.raises(ParameterError, match="steps with 1 moving head needs about .* more "
                                             "than the limit 1 GB"):
        stepper.march(4 * 10**6, load=head)  # 4e6 steps: the step load alone would fit
    stepper.march(10, load=head, record_energy=True)


def test_time_limit_refuses_a_march_before_its_arrays_exist(small, monkeypatch):
    monkeypatch.setenv("GYROSHELL_TIME_LIMIT", "0.5")
    monkeypatch.setenv("GYROSHELL_MEMORY_LIMIT", "1e15")  # the arrays would never fit here
    with pytest.raises(ParameterError, match=r"a transient of 1000000000 steps of 135 "
                                             r"unknowns would take about"):
        march(small, 10.0, dt=1e-9, steps=10**9)


@pytest.mark.parametrize(("call", "match"), [
    (lambda m: frequency_response(m, 0.0, [0.0, 1e300]),
     r"frequencies must be in \[0, 8.45154e\+75\] rad/s"),
    (lambda m: frequency_response(m, 0.0, [-5.0, 10.0]), "frequencies must be >= 0 rad/s"),
    (lambda m: frequency_response(m, 0.0, [1.0, math.inf]), "frequencies must be finite"),
    (lambda m: frequency_response(m, 0.0, np.linspace(0, 1e5, 20), tol=2.0),
     r"tol must be in \(1e-08, 0.1\], got 2"),
    (lambda m: frequency_response(m, 0.0, np.linspace(0, 1e5, 20), max_points=10**4),
     r"max_points must be an integer in \[1, 100\]"),
    (lambda m: ReducedModel(m, 0.0).add_points([1e301]), "frequencies must be in"),
], ids=["overflow", "negative", "infinite", "tol 200 %", "max_points", "add_points"])
def test_frequency_response_refusals_name_the_argument(small, call, match):
    with pytest.raises(ParameterError, match=match):
        call(small)


def test_frequency_at_the_top_of_the_range_answers(small):
    res = frequency_response(small, 0.0, [8e75], damping=100.0)
    assert np.all(np.isfinite(res.amplitude)) and res.amplitude[0, 0] > 0


#: Every engine's door, called with a model (issue 32): (name, call(model, progress)).
ENGINES = [
    ("solve_static", lambda m, p: gs.solve_static(m, 1.0, progress=p)),
    ("modes", lambda m, p: gs.modes(m, 1.0, 2, progress=p)),
    ("frequencies", lambda m, p: gs.frequencies(m, 1.0, 2, progress=p)),
    ("critical_speeds", lambda m, p: gs.critical_speeds(m, progress=p)),
    ("critical_speed_eigen", lambda m, p: gs.critical_speed_eigen(m, progress=p)),
    ("divergence_speed", lambda m, p: gs.divergence_speed(m, progress=p)),
    ("divergence", lambda m, p: gs.divergence(m, progress=p)),
    ("frequency_response", lambda m, p: gs.frequency_response(m, 1.0, [0.0, 1e4],
                                                              progress=p)),
    ("direct_response", lambda m, p: gs.direct_response(m, 1.0, [0.0, 1e4], progress=p)),
    ("march", lambda m, p: gs.march(m, 1.0, dt=1e-6, steps=3, progress=p)),
    ("sweep", lambda m, p: gs.sweep(m, [0.0, 1.0], 2, progress=p)),
    ("campbell", lambda m, p: gs.campbell(m, [0.0, 1.0], 2, progress=p)),
    ("campbell without critical speed",
     lambda m, p: gs.campbell(m, [0.0, 1.0], 2, critical_speed=None, progress=p)),
]


@pytest.mark.parametrize(("name", "call"), ENGINES, ids=[e[0] for e in ENGINES])
@pytest.mark.parametrize("model", [None, 3.0, "tape", TapeParameters()],
                         ids=["None", "float", "str", "TapeParameters"])
def test_every_engine_refuses_what_is_not_a_model(name, call, model):
    with pytest.raises(ParameterError) as info:
        call(model, False)
    assert str(info.value) == f"model must be a TapeModel, got {type(model).__name__}"


def test_a_model_missing_what_the_engine_reads_is_named(small):
    class Partial:  # has some of a model's members, not the divergence solver's A and B
        params, grid, unknowns = small.params, small.grid, small.unknowns
        mass_diagonal, M, K, G = small.mass_diagonal, small.M, small.K, small.G

    with pytest.raises(ParameterError, match=r"^model must be a TapeModel, got Partial "
                                             r"\(it has no A\)$"):
        gs.divergence_speed(Partial())
    assert gs.frequencies(Partial(), 0.0, 2) == pytest.approx(gs.frequencies(small, 0.0, 2),
                                                              rel=1e-9)


@pytest.mark.parametrize(("name", "call"), ENGINES, ids=[e[0] for e in ENGINES])
def test_every_engine_takes_progress_false_and_none_and_refuses_other_values(
        small, capsys, name, call):
    quiet = call(small, False)
    assert capsys.readouterr().err == ""          # False: nothing on stderr
    call(small, None)
    with pytest.raises(ParameterError, match="^progress must be True, False or None, "
                                             "got 'yes'$"):
        call(small, "yes")
    assert quiet is not None
