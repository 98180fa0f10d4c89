"""The bearing's Python API refuses hostile arguments before any work, with a
ParameterError naming the argument and what it must be (issue 18, causes 1, 4, 5, 6, 10),
and the CLI turns each into one line and exit code 2, leaving no output behind."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD

from gyroshell import ParameterError, TapeParameters
from gyroshell.bearing import (
    AirParameters,
    BearingModel,
    march,
    solve_steady,
    tension_harmonic,
    tension_step,
)
from gyroshell.bearing.model import BearingGridWarning

WRAP = math.radians(15.0)


def strip(**kw) -> BearingModel:
    """The Table 1 tape, infinitely wide, at 4 m/s on a coarse but film-resolving grid."""
    kw.setdefault("nx", 60)
    return BearingModel(TapeParameters(), FIRST_ORDER, velocity=4.0, wrap_angle=WRAP,
                        infinitely_wide=True, **kw, contact=HARD)


@pytest.fixture(scope="module")
def flying():
    return solve_steady(strip())


# ----- 1. size before work -------------------------------------------------------------------
@pytest.mark.parametrize("tape, kw, message", [
    (TapeParameters(), {"nx": 50000, "ny": 100000}, "a bearing grid of 50000 x 100000"),
    (TapeParameters(width=5.0, spacing=1e-3), {}, "factor entries, more than the sparse"),
])
def test_grid_beyond_the_solver_is_refused_before_allocating(tape, kw, message):
    with pytest.raises(ParameterError, match=message):
        BearingModel(tape, velocity=4.0, wrap_angle=WRAP, **kw, contact=HARD, air=FIRST_ORDER)


def test_grid_beyond_the_memory_limit_names_estimate_and_limit(monkeypatch):
    monkeypatch.setenv("GYROSHELL_MEMORY_LIMIT", "1e6")
    with pytest.raises(ParameterError, match=r"a bearing grid of \d+ intervals .* needs "
                                             r"about .* MB, more than the limit 1 MB"):
        strip(nx=None)


def test_march_that_would_keep_too_many_centre_lines_is_refused(flying):
    with pytest.raises(ParameterError, match=r"100000000 steps keeping 100000002 centre "
                                             r"lines .* record_every >= \d+"):
        march(flying, dt=1e-5, steps=10**8, progress=False)


def _forged(tmp_path, flying, change):
    """A saved bearing whose metadata ``change`` rewrites (a real file on disk)."""
    import xarray as xr

    from gyroshell.bearing import storage
    from gyroshell.results.base import write_netcdf

    good = storage.save(flying, tmp_path / "good.nc")
    with xr.open_dataset(good) as ds:
        ds = ds.load()
    change(ds.attrs)
    return write_netcdf(ds, tmp_path / "forged.nc")


def _set(key, name, value):
    def change(attrs):
        data = json.loads(attrs[key])
        if value is KeyError:
            del data[name]
        else:
            data[name] = value
        attrs[key] = json.dumps(data)
    return change


@pytest.mark.parametrize("change, message", [
    (_set("model", "ny", 10**7), "y dimension has 1 nodes, but its grid settings say 10000001"),
    (_set("model", "ny", 2.5), "the stored ny must be None or an integer"),
    (_set("model", "nx", 10**7), "x dimension has 61 nodes, but its grid settings say"),
    (_set("model", "nx", "sixty"), "the stored nx must be an integer"),
    (_set("model", "color", "red"), r"unknown keys \['color'\]"),
    (_set("model", "span", KeyError), r"missing keys \['span'\]"),
    (_set("air", "temperature", 20), r"'air' attribute has unknown keys"),
    (_set("info", "extra", 1), r"'info' attribute has unknown keys"),
    (lambda attrs: attrs.update(model="{not json"), "is not valid JSON"),
])
def test_forged_metadata_is_refused_on_load(tmp_path, flying, change, message):
    from gyroshell.bearing import storage

    path = _forged(tmp_path, flying, change)
    with pytest.raises(ParameterError, match=message) as info:
        storage.load(path)
    assert str(path) in str(info.value)


@pytest.mark.parametrize("change, message", [
    (_set("model", "velocity", 0.0), "velocity must be nonzero"),
    (_set("model", "span", -1.0), "span must be > 0 m, got -1"),
    (_set("model", "head", {"kind": "flat", "modules": 99}),
     "a flat head's modules must be a list of objects"),
    (_set("air", "viscosity", -1.0), "viscosity must be in [1e-07, 1000] Pa*s, got -1"),
    (_set("parameters", "tension", -1.0), "tension must be >= 0 N/m, got -1"),
], ids=["speed 0", "span", "head", "viscosity", "tension"])
@pytest.mark.parametrize("loader", ["gyroshell.load", "bearing.storage.load"])
def test_a_tampered_file_is_named_once_with_what_is_wrong(tmp_path, flying, change, message,
                                                            loader):
    import gyroshell
    from gyroshell.bearing import storage

    path = _forged(tmp_path, flying, change)
    load = gyroshell.load if loader == "gyroshell.load" else storage.load
    with pytest.raises(ParameterError) as info:
        load(path)
    text = str(info.value)
    assert text.startswith(f"{path}: ") and text.count(str(path)) == 1
    assert message in text and "\n" not in text


def test_forged_2d_count_is_refused_before_allocating(tmp_path):
    """A 2-D file claiming ny = 10**7 (59 GiB of operators) is refused from its sizes."""
    from gyroshell.bearing import storage

    model = BearingModel(TapeParameters(width=3e-3), velocity=4.0, wrap_angle=WRAP, nx=48,
                         ny=16, span=2e-3, contact=HARD, air=FIRST_ORDER)
    sol = solve_steady(model)
    path = _forged(tmp_path, sol, _set("model", "ny", 10**7))
    with pytest.raises(ParameterError, match="y dimension has 17 nodes, but its grid "
                                             "settings say 10000001"):
        storage.load(path)


# ----- 4. foreign exceptions -----------------------------------------------------------------
def _bad_load(t):
    return np.zeros(3)


@pytest.mark.parametrize("call, message", [
    (lambda: BearingModel(TapeParameters(), {"viscosity": 1e-5}, velocity=4.0,
                          wrap_angle=WRAP, contact=HARD), "air must be a AirParameters, got dict"),
    (lambda: BearingModel(None, velocity=4.0, wrap_angle=WRAP, contact=HARD, air=FIRST_ORDER),
     "params must be a TapeParameters, got NoneType"),
    (lambda: strip(nx=60.5), "nx must be an integer, got 60.5"),
    (lambda: strip(nx=10**6), r"nx must be an integer in \[8, 50000\]"),
    (lambda: BearingModel(TapeParameters(), velocity=4.0, wrap_angle=WRAP,
                          infinitely_wide="yes", contact=HARD, air=FIRST_ORDER),
     "infinitely_wide must be True or False"),
    (lambda: strip(ny=9), "ny applies to the 2-D tape only"),
    (lambda: BearingModel(TapeParameters(), velocity=4.0, wrap_angle=WRAP, ny="8", contact=HARD,
                          air=FIRST_ORDER),
     "ny must be an integer"),
    (lambda: solve_steady(None), "model must be a BearingModel, got NoneType"),
    (lambda: solve_steady(strip(), z0=np.zeros(5)), "z0 must be a vector of length 118"),
    (lambda: solve_steady(strip(), z0=np.zeros(118)), "z0 must have pressures > 0 Pa"),
    (lambda: solve_steady(strip(), progress="yes"), "progress must be None or a callable"),
    (lambda: march(strip(), dt=1e-5, steps=3), "start must be a BearingSolution, got "
                                                "BearingModel"),
])
def test_wrong_argument_is_a_parameter_error_naming_it(call, message):
    with pytest.raises(ParameterError, match=message):
        call()


@pytest.mark.parametrize("kw, message", [
    ({"moving_load": _bad_load}, r"moving_load\(t\) must be a vector of length 59"),
    ({"moving_load": lambda t: ["a"] * 59}, r"moving_load\(t\) must be a real vector"),
    ({"moving_load": 3.0}, "moving_load must be None or a callable"),
    ({"tension": "90"}, "tension must be None or a callable"),
    ({"record_every": 0}, "record_every must be an integer >= 1"),
    ({"steps": 2.5}, "steps must be an integer"),
])
def test_wrong_march_argument_is_refused_before_stepping(flying, kw, message):
    args = {"dt": 1e-5, "steps": 3, "progress": False, **kw}
    with pytest.raises(ParameterError, match=message):
        march(flying, **args)


# ----- 5. bad arguments are not convergence failures --------------------------------------
@pytest.mark.parametrize("tension, message", [
    (-5.0, "tension must be > 0 N/m, got -5"),
    (0.1, r"tension must be > rho V\^2 = 0.224 N/m"),
    (math.nan, "tension must be finite"),
])
def test_steady_tension_is_checked_first(tension, message):
    with pytest.raises(ParameterError, match=message):
        solve_steady(strip(), tension=tension)


@pytest.mark.parametrize("kw, message", [
    ({"dt": 1e-300}, "dt 1e-300 s is too small"),
    ({"dt": -1e-5}, "dt must be > 0 s"),
    ({"tension": tension_step(90.0, 0.1)}, r"tension must stay > rho V\^2 = 0.224 N/m"),
    ({"beta": 0.1, "gamma": 0.5}, "2 beta >= gamma >= 1/2"),
])
def test_march_arguments_are_checked_first(flying, kw, message):
    args = {"dt": 1e-5, "steps": 3, "progress": False, **kw}
    with pytest.raises(ParameterError, match=message):
        march(flying, **args)


@pytest.mark.parametrize("call, message", [
    (lambda: tension_step(90.0, -5.0), "final must be > 0 N/m, got -5"),
    (lambda: tension_step(-1.0, 90.0), "initial must be > 0 N/m"),
    (lambda: tension_harmonic(90.0, 100.0, 20.0), "amplitude must be below the mean"),
    (lambda: tension_harmonic(90.0, 2.0, -1.0), "frequency must be >= 0 Hz"),
])
def test_tension_histories_check_their_arguments(call, message):
    with pytest.raises(ParameterError, match=message):
        call()


def test_own_tension_history_is_checked_as_the_march_reaches_it(flying):
    def dropping(t):
        return 90.0 if t < 1.5e-5 else -5.0

    with pytest.raises(ParameterError, match=r"tension\(t\) must be > rho V\^2 .* got -5 "
                                             r"at t = 2e-05 s"):
        march(flying, dt=1e-5, steps=3, tension=dropping, progress=False)


# ----- 6. messages name the real cause -------------------------------------------------------
@pytest.mark.parametrize("tape, air, kw, message", [
    (TapeParameters(), FIRST_ORDER, {"span": 5.0}, r"span must be in \[0.00101, 0.02\] m"),
    (TapeParameters(), AirParameters(viscosity=1000.0, rarefaction="first-order"), {},
     "the viscosity 1000 Pa.s makes the film thick"),
    (TapeParameters(thickness=1e-3), FIRST_ORDER, {}, "the tape is too stiff to wrap"),
])
def test_message_names_the_cause_not_the_velocity(tape, air, kw, message):
    with pytest.raises(ParameterError, match=message) as info:
        BearingModel(tape, air, velocity=4.0, wrap_angle=WRAP, **kw, contact=HARD)
    assert "use a higher velocity" not in str(info.value)


def test_very_low_speed_still_blames_the_velocity():
    with pytest.raises(ParameterError, match="velocity 1e-09 m/s gives a film only"):
        BearingModel(TapeParameters(), velocity=1e-9, wrap_angle=WRAP, infinitely_wide=True,
                     contact=HARD, air=FIRST_ORDER)


def test_flexible_foil_gets_a_default_grid_that_resolves_its_film():
    """D = 1e-10 N·m: a bending length 1 µm, 1/300 of the film's; the default grid resolves
    the film (its corners at 1/30 of the film length) in as many intervals as the Table 1
    tape's."""
    from gyroshell.bearing.model import foil_length_scales

    tape = TapeParameters(bending_rigidity=1e-10)
    model = BearingModel(tape, velocity=4.0, wrap_angle=WRAP, contact=HARD, air=FIRST_ORDER)
    _, l_film, l_bend = foil_length_scales(tape, model.air, 4.0)
    assert l_bend < 0.01 * l_film
    assert np.diff(model.x).min() == pytest.approx(l_film / 30, rel=0.1)
    assert model.nx <= 450      # Table 1 tape: 388


# ----- 10. wrong answers -------------------------------------------------------------------
def test_span_that_cannot_hold_the_film_is_refused():
    with pytest.raises(ParameterError, match=r"span must be in \[0.00101, 0.02\] m, got "
                                             r"1e-12: at least 3 film lengths"):
        strip(span=1e-12)


def test_grid_too_coarse_for_the_film_gives_the_minimum_nx():
    with pytest.raises(ParameterError, match=r"nx = 8 is too coarse for the film: .* use "
                                             r"nx >= 16"):
        BearingModel(TapeParameters(), velocity=4.0, wrap_angle=WRAP, nx=8, ny=8, contact=HARD,
                     air=FIRST_ORDER)
    BearingModel(TapeParameters(), velocity=4.0, wrap_angle=WRAP, nx=16, ny=32, contact=HARD,
                 air=FIRST_ORDER)


def test_coarse_free_edges_warn_with_the_measured_error():
    with pytest.warns(BearingGridWarning, match=r"ny = 8 leaves 231 um at the free edges.*"
                                                r"off by 20-90 %"):
        BearingModel(TapeParameters(), velocity=4.0, wrap_angle=WRAP, nx=16, ny=8, contact=HARD,
                     air=FIRST_ORDER)


def test_a_tape_on_the_head_is_reported_in_contact():
    from bearing_cases import flexible_model

    sol = solve_steady(flexible_model(400, params=TapeParameters(foundation_stiffness=0.0),
                                      air=FIRST_ORDER, velocity=1e-6))
    assert sol.minimum_spacing == pytest.approx(sol.model.air.roughness)
    assert sol.in_contact and sol.summary()["in_contact"] is True


def test_a_flying_tape_is_not_in_contact(flying):
    assert not flying.in_contact and flying.summary()["in_contact"] is False
    assert flying.minimum_spacing > 10 * flying.model.air.roughness


# ----- progress --------------------------------------------------------------------------------
def test_a_2d_solve_reports_every_stage_and_iteration():
    model = BearingModel(TapeParameters(width=3e-3), velocity=4.0, wrap_angle=WRAP, nx=96,
                         ny=24, span=2e-3, contact=HARD, air=FIRST_ORDER)
    stages, iterations = [], []
    sol = solve_steady(model, progress=stages.append, iteration_log=iterations.append)
    assert any(line.startswith("start: solving the infinitely wide tape") for line in stages)
    newton_lines = [line for line in iterations if line.startswith("Newton ")]
    # every iteration logged is counted, the start's too
    assert len(newton_lines) == sol.info.iterations


def test_progress_false_reports_nothing_as_in_every_engine(flying):
    quiet = solve_steady(strip(), progress=False)
    np.testing.assert_array_equal(quiet.u, flying.u)
    np.testing.assert_array_equal(quiet.p, flying.p)


def test_progress_false_on_a_2d_tape_whose_start_reports_stages(capsys):
    model = BearingModel(TapeParameters(width=3e-3), velocity=4.0, wrap_angle=WRAP, nx=96,
                         ny=24, span=2e-3, contact=HARD, air=FIRST_ORDER)
    iterations = []
    sol = solve_steady(model, progress=False, iteration_log=iterations.append)
    assert sol.info.iterations >= 1 and iterations     # the coarse start ran (and was quiet)
    assert capsys.readouterr().err == ""


# ----- through the CLI -------------------------------------------------------------------------
@pytest.mark.parametrize("argv, message", [
    (["--nx", "50000", "--ny", "100000"], "a bearing grid of 50000 x 100000 intervals"),
    (["--width", "5"], "more than the sparse solver's limit"),
    (["--span", "5"], "span must be in [0.00101, 0.02] m, got 5"),
    (["--viscosity", "1000"], "the viscosity 1000 Pa*s makes the film thick"),
    (["--infinitely-wide", "--span", "1e-12"], "span must be in [0.00101, 0.02] m"),
    (["--nx", "8", "--ny", "8"], "nx = 8 is too coarse for the film"),
    (["--thickness", "1e-3", "--infinitely-wide"], "the tape is too stiff to wrap the head"),
])
def test_cli_refuses_in_one_line(cli, tmp_path, argv, message):
    out = tmp_path / "out"
    run = cli(["bearing", "--velocity", "4", *argv, "--out-dir", out])
    assert run.code == 2
    assert len(run.error_lines) == 1 and run.error_lines[0].startswith("gyroshell: error:")
    assert message in run.error_lines[0] and "Traceback" not in run.err
    assert not out.exists()
