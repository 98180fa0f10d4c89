"""Critical speed two ways, the beam-on-foundation closed form, sweeps and the CLI."""

from __future__ import annotations

import json

import numpy as np
import pytest
from convergence import observed_order

from gyroshell import Grid, ParameterError, TapeModel, TapeParameters
from gyroshell.cli import main
from gyroshell.engines.critical import (
    PAPER_SPEED,
    SUNDARAM_BENSON_SPEED,
    critical_function,
    critical_speeds,
)
from gyroshell.engines.divergence import beam_mu_estimate, divergence
from gyroshell.engines.eigen import modes
from gyroshell.studies.sweep import parse_velocities, plot_sweep, sweep

# Every test here runs on each factorization back-end (CHOLMOD and SuperLU).
pytestmark = pytest.mark.usefixtures("every_factorization")

WIDTH = TapeParameters().width
SMALL = ["--spacing", str(WIDTH / 8), "--length-ratio", "2"]


# ----- (a) = (b) ----------------------------------------------------------------------------
@pytest.mark.slow
@pytest.mark.parametrize("edges", ["free", "simply-supported"])
@pytest.mark.parametrize("ratio", [1.0, 3.0])
def test_critical_and_divergence_agree(edges, ratio):
    model = TapeModel(TapeParameters(length_ratio=ratio, edges=edges, spacing=WIDTH / 8))
    c = critical_speeds(model)
    assert c.relative_difference < 1e-5
    lo, hi = c.info["bracket"]
    assert lo <= c.critical_speed <= hi          # bracketed by a sign change of ω₁²
    assert c.string_speed < c.critical_speed      # A > 0: always above √(T/ρ)
    assert c.string_speed == pytest.approx(80.178, abs=1e-3)
    assert c.sundaram_benson_speed == SUNDARAM_BENSON_SPEED == 111.0
    assert c.paper_speed == PAPER_SPEED
    assert set(c.as_dict()) >= {"critical_speed", "divergence_speed", "string_speed",
                                "strip_speed"}


def test_lowest_frequency_vanishes_like_sqrt():
    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8))
    vc = divergence(model).speed
    d = np.array([1e-3, 1e-4, 1e-5]) * vc
    omega = np.sqrt([critical_function(model, vc - x) for x in d])
    # ω₁ ∝ (V_c − V)^½ near the critical speed
    assert observed_order(d, omega) == pytest.approx(0.5, abs=0.02)
    assert critical_function(model, vc * (1 + 1e-4)) < 0   # divergence above


# ----- ν = 0, free edges: beam on a foundation -------------------------------------------------
def _beam_case(ny: int) -> TapeModel:
    p = TapeParameters(poisson=0.0, length_ratio=2.0, spacing=WIDTH / 8,
                       foundation_stiffness=1e6)
    return TapeModel(p, Grid(p.length, p.width, 2 * ny, ny, "free"))


def _continuous_beam_speed(p: TapeParameters) -> float:
    alpha = np.arange(1, 200) * np.pi / p.length
    return float(np.sqrt((p.tension + np.min(p.D * alpha**2 + p.k / alpha**2)) / p.density))


def test_beam_on_foundation_divergence():
    steps, errs = [], []
    for ny in (8, 16, 32):
        model = _beam_case(ny)
        p, g = model.params, model.grid
        d = divergence(model)
        # the discrete closed form: α² → (4/h²) sin²(αh/2), α⁴ → its square
        alpha = np.arange(1, g.nx) * np.pi / g.length
        a2 = (2 / g.hx * np.sin(alpha * g.hx / 2)) ** 2
        mu_discrete = float(np.min(p.D * a2 + p.k / a2))
        assert d.mu == pytest.approx(mu_discrete, rel=1e-10)
        assert beam_mu_estimate(model) == pytest.approx(mu_discrete, rel=1e-14)
        exact = _continuous_beam_speed(p)
        steps.append(g.hx)
        errs.append(abs(d.speed - exact) / exact)
        # the buckling mode is uniform across the width
        field = g.to_field(d.mode)[1:-1]
        assert np.allclose(field, field[:, :1], atol=1e-8)
    assert observed_order(steps, errs) == pytest.approx(2.0, abs=0.1)


def test_divergence_shift_options_agree():
    model = TapeModel(TapeParameters(length_ratio=4.0, spacing=WIDTH / 8))
    assert divergence(model).speed == pytest.approx(divergence(model, shift=0.0).speed,
                                                    rel=1e-12)


# ----- sweeps -----------------------------------------------------------------------------------
def test_parse_velocities():
    assert parse_velocities("0:100:10") == pytest.approx(np.arange(0, 101, 10))
    assert parse_velocities("0, 5,7.5") == [0.0, 5.0, 7.5]
    for bad in ("a:b:c", "0:10", "10:0:1", "0:10:0"):
        with pytest.raises(ParameterError, match="velocities"):
            parse_velocities(bad)


@pytest.mark.slow
def test_sweep_tracks_branches(tmp_path):
    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8))
    frame = sweep(model, [0, 2, 4, 6, 8], 4).table
    assert list(frame.columns)[:4] == ["velocity", "branch", "rank", "omega"]
    assert len(frame) == 20
    # small steps: every mode continues its branch
    assert sorted(frame.branch.unique()) == [0, 1, 2, 3]
    assert frame.correlation.min() > 0.9
    for _, g in frame.groupby("branch"):
        assert np.all(np.diff(g.sort_values("velocity").omega) < 0)   # ω falls with V
    fig = plot_sweep(frame, tmp_path / "s.png")
    assert (tmp_path / "s.png").stat().st_size > 1000
    ax = fig.axes[0]
    assert "m/s" in ax.get_xlabel() and "rad/s" in ax.get_ylabel()
    with pytest.raises(ParameterError, match="velocity"):
        sweep(model, [0, -1], 2)
    with pytest.raises(ParameterError, match="at least one"):
        sweep(model, [], 2)


# ----- CLI ---------------------------------------------------------------------------------------
def test_cli_modes_json(capsys):
    assert main(["modes", *SMALL, "--count", "3", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    omega, period = np.array(out["omega"]), np.array(out["period"])
    assert len(omega) == 3 and np.all(np.diff(omega) >= 0)
    assert np.allclose(period, 2 * np.pi / omega)


def test_cli_modes_text_and_supercritical(capsys):
    assert main(["modes", *SMALL, "--count", "2", "--velocity", "120"]) == 0
    out = capsys.readouterr().out
    assert "the tape diverges" in out and "K(V) indefinite" in out


@pytest.mark.slow
def test_cli_critical_json(capsys):
    assert main(["critical", *SMALL, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert abs(out["critical_speed"] - out["divergence_speed"]) < 1e-5 * out["divergence_speed"]
    for key in ("string_speed", "strip_speed", "sundaram_benson_speed", "paper_speed"):
        assert key in out


@pytest.mark.slow
def test_cli_critical_text(capsys):
    assert main(["critical", *SMALL]) == 0
    text = capsys.readouterr().out
    assert "critical speed (a)" in text and "divergence speed (b)" in text


@pytest.mark.slow
def test_cli_sweep_files(tmp_path, capsys):
    csv, png = tmp_path / "s.csv", tmp_path / "s.png"
    assert main(["sweep", *SMALL, "--velocities", "0:20:10", "--count", "2",
                 "--out", str(csv), "--plot", str(png)]) == 0
    assert csv.read_text().startswith("velocity,branch,rank,omega")
    assert png.stat().st_size > 1000


@pytest.mark.parametrize("argv, match", [
    (["modes", *SMALL, "--count", "100000"], "count must be in"),
    (["sweep", *SMALL, "--velocities", "0:10"], "velocities"),
    (["sweep", *SMALL, "--velocities=-5,1"], "velocity must be >= 0"),
    (["sweep", *SMALL, "--out", "/nonexistent/dir/x.csv"], "does not exist"),
    (["modes", *SMALL, "--velocity", "-3"], "velocity must be >= 0"),
    (["modes", *SMALL, "--velocity", "1e200"], "rho V^2 overflows"),
    (["sweep", *SMALL, "--velocities", "0,1e200", "--count", "2"], "rho V^2 overflows"),
    (["modes", *SMALL, "--count", "51"], "count must be in [1, 50]"),
])
def test_cli_user_errors(argv, match, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert match in err and len(err.strip().splitlines()) == 1


# ----- no tension, no foundation: bending alone resists ------------------------------------------
def _bending_only(ny: int) -> TapeModel:
    p = TapeParameters(tension=0.0, foundation_stiffness=0.0, poisson=0.0, length_ratio=2.0,
                       spacing=WIDTH / 8)
    return TapeModel(p, Grid(p.length, p.width, 2 * ny, ny, "free"))


@pytest.mark.slow
def test_critical_speed_without_tension_and_foundation():
    """T = 0, k = 0, ν = 0, free edges: K(V) = A − ρV²B with width-uniform modes sin(mπx/L):
    μ = D α² (continuous), so V_c = (π/L_x) √(D/ρ); the discrete model has α² → a₁² =
    (4/h²) sin²(πh/2L_x), exactly."""
    steps, errs = [], []
    for ny in (8, 16, 32):
        model = _bending_only(ny)
        p, g = model.params, model.grid
        c = critical_speeds(model)
        a1 = (2 / g.hx * np.sin(np.pi * g.hx / (2 * g.length))) ** 2
        assert c.critical_speed == pytest.approx(np.sqrt(p.D * a1 / p.density), rel=1e-8)
        assert c.relative_difference < 1e-8
        exact = np.pi / p.length * np.sqrt(p.D / p.density)
        steps.append(g.hx)
        errs.append(abs(c.critical_speed - exact) / exact)
    assert observed_order(steps, errs) == pytest.approx(2.0, abs=0.1)


@pytest.mark.slow
def test_cli_critical_without_tension_and_foundation(capsys):
    assert main(["critical", *SMALL, "--tension", "0", "--foundation-stiffness", "0",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    p = TapeParameters(length_ratio=2.0)
    beam = np.pi / p.length * np.sqrt(p.D / p.density)     # ν-free beam value, m/s
    assert out["critical_speed"] == pytest.approx(out["divergence_speed"], rel=1e-6)
    assert 0.5 * beam < out["critical_speed"] < 1.5 * beam


def test_critical_refusals():
    model = TapeModel(TapeParameters(length_ratio=1.0, spacing=WIDTH / 8))
    for kwargs, match in (({"guess": 0.0}, "guess must be"), ({"xtol": 0.0}, "xtol must be"),
                          ({"xtol": -1.0}, "xtol must be"),
                          ({"max_evaluations": 0}, "max_evaluations must be")):
        with pytest.raises(ParameterError, match=match):
            critical_speeds(model, **kwargs)


def test_modes_text_says_what_is_true():
    from gyroshell.cli.eigen import stability_sentence
    from gyroshell.engines.gyroscopic import gyroscopic_modes

    def two_dof(k1, k2, g):
        return gyroscopic_modes(np.eye(2), np.array([[0.0, g], [-g, 0.0]]), np.diag([k1, k2]),
                                2)

    assert stability_sentence(two_dof(1.0, 4.0, 1.0)) == ""
    assert "gyroscopically stable" in stability_sentence(two_dof(-1.0, -4.0, 4.0))
    assert "flutters" in stability_sentence(two_dof(-1.0, -4.0, 2.0))
    assert "diverges" in stability_sentence(two_dof(-1.0, 4.0, 1.0))


def test_cli_modes_damped_json(capsys):
    assert main(["modes", *SMALL, "--count", "2", "--damping", "50", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    rho = TapeParameters().density
    assert out["decay_rate"] == pytest.approx([50 / (2 * rho)] * 2, rel=1e-9)
    assert all(0 < z < 1 for z in out["damping_ratio"]) and out["stability"] == "stable"


# ----- continuation ------------------------------------------------------------------------------
@pytest.mark.slow
def test_continuation_sweep_equals_independent_solves():
    model = TapeModel(TapeParameters(length_ratio=4.0, spacing=WIDTH / 8))
    speeds = np.linspace(0, 95, 8)
    cont = sweep(model, speeds, 4, continuation=True).table
    fresh = sweep(TapeModel(model.params), speeds, 4, continuation=False).table
    assert np.allclose(cont.omega, fresh.omega, rtol=1e-10, atol=0)
    assert (cont.branch == fresh.branch).all()
    assert set(cont.stability) == {"stable"}


def test_sweep_stability_column_above_critical():
    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8))
    frame = sweep(model, [90.0, 120.0], 2).table
    by_speed = frame.groupby("velocity").stability.first()
    assert by_speed[90.0] == "stable" and by_speed[120.0] == "divergence"


def test_divergence_refusals():
    model = TapeModel(TapeParameters(length_ratio=1.0, spacing=WIDTH / 8))
    for kwargs, match in (({"tol": -1.0}, "tol must be"), ({"tol": 2.0}, "tol must be"),
                          ({"shift": float("nan")}, "shift must be")):
        with pytest.raises(ParameterError, match=match):
            divergence(model, **kwargs)


def test_continuation_shift_extrapolates_omega1_in_v_squared():
    """ω₁ = a − b V² + c V⁴ is reproduced exactly from three speeds (the polynomial in V²)."""
    from types import SimpleNamespace

    from gyroshell.studies.sweep import _extrapolate

    def omega1(v):
        return 1.25e5 - 3.0 * v**2 - 2e-4 * v**4

    points = [SimpleNamespace(velocity=v, omega=np.array([omega1(v)])) for v in (40, 45, 50)]
    assert _extrapolate(points, 55.0) == pytest.approx(omega1(55.0), rel=1e-12)
    assert _extrapolate(points[1:], 55.0) == pytest.approx(
        omega1(50) + (omega1(50) - omega1(45)) * (55**2 - 50**2) / (50**2 - 45**2), rel=1e-12)


@pytest.mark.slow
def test_continuation_shift_is_certified_and_close_below_omega1():
    model = TapeModel(TapeParameters(length_ratio=4.0, spacing=WIDTH / 8))
    from gyroshell.engines.eigen import modes
    from gyroshell.studies.sweep import _continuation_options

    history = [modes(model, v, 4) for v in (40.0, 45.0, 50.0)]
    options = _continuation_options(model, history, 55.0, True)
    exact = modes(model, 55.0, 4)
    assert options["start"] is history[-1]
    assert 0.99 * exact.omega[0] < options["estimate"] < exact.omega[0]
    tracked = modes(model, 55.0, 4, **options)
    assert tracked.info["below_shift"] == 0
    assert np.allclose(tracked.omega, exact.omega, rtol=1e-10, atol=0)


# ----- the mirror-symmetric halves in the root search -------------------------------------
@pytest.mark.slow
def test_halves_give_the_full_critical_function_and_speed():
    from gyroshell.engines.critical import _HalfCritical, critical_function, critical_speed_eigen
    from gyroshell.tape.mirror import mirror_split

    model = TapeModel(TapeParameters(length_ratio=4.0, spacing=WIDTH / 8))
    half = _HalfCritical(model, mirror_split(model), 1, {})
    for v in (60.0, 95.0, 99.5):                 # below critical: ω₁² of the tape
        assert half(v) == pytest.approx(critical_function(model, v), rel=1e-9)
        half.which = None                          # both halves again at the next speed
    for v in (102.0, 105.0):                     # above (V_c = 101.02): negative, erratic
        assert half(v) < 0 and critical_function(model, v) < 0
        half.which = None
    v_half, info = critical_speed_eigen(model)
    v_full, _ = critical_speed_eigen(TapeModel(model.params), symmetry=False)  # whole tape
    assert v_half == pytest.approx(v_full, rel=1e-9)
    assert info["evaluations"] <= 12


def test_an_exactly_singular_stiffness_is_the_root(monkeypatch):
    """If an evaluation lands on V_c to working precision (K(V) exactly singular), f = 0
    there instead of an error: the root search brackets it like any f <= 0."""
    import gyroshell.engines.critical as crit
    from gyroshell.core.errors import SingularError
    from gyroshell.tape.mirror import mirror_split

    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8))

    def singular(*args, **kwargs):
        raise SingularError("K is singular")

    half = crit._HalfCritical(model, mirror_split(model), 1, {})
    monkeypatch.setattr(crit, "gyroscopic_modes", singular)
    assert half(80.0) == 0.0
    monkeypatch.setattr(crit, "modes", singular)
    assert crit.critical_function(model, 80.0) == 0.0


# ----- route (b) on the halves, route (a) from route (b) ----------------------------------
def test_divergence_on_the_halves_is_the_pencils_smallest_eigenvalue():
    """μ_min of A φ = μ B φ from the mirror halves equals the dense generalized eigenvalue
    problem's smallest on the whole tape, and its mode is an eigenvector of the pencil."""
    import scipy.linalg as la

    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8))
    A, B = model.A.toarray(), model.B.toarray()
    exact = la.eigh(A, B, eigvals_only=True, subset_by_index=[0, 0])[0]
    d = divergence(model)
    assert d.mu == pytest.approx(exact, rel=1e-10)
    r = A @ d.mode - d.mu * (B @ d.mode)
    assert np.linalg.norm(r) < 1e-9 * np.linalg.norm(A, 1) * np.linalg.norm(d.mode)


def test_critical_speed_from_the_divergence_route_in_two_eigen_solves():
    """Without a guess, route (a) starts just below route (b)'s speed: two eigen-solves
    extrapolate the zero of ω₁²; K(V) proved definite just below it (ω₁² > 0 there) and
    indefinite just above bracket it, and it agrees with (b) far inside the tolerance."""
    model = TapeModel(TapeParameters(length_ratio=3.0, spacing=WIDTH / 8))
    c = critical_speeds(model)
    assert c.info["evaluations"] <= 3 and c.info["inertia_checks"] >= 2
    lo, hi = c.info["bracket"]
    assert lo <= c.critical_speed <= hi and (hi - lo) / hi < 4e-9
    assert critical_function(model, lo) > 0          # the proved point below: ω₁ real
    assert c.relative_difference < 1e-11
    assert critical_function(model, lo) > 0          # below: a real lowest frequency


def test_a_sweep_past_the_string_speed_stays_on_the_halves():
    """One speed above √(T/ρ) is enough to prove the stiffness floor near divergence once
    (on the mirror halves); that speed is then solved on the halves, with the frequencies
    of an independent solve (which factors K(V) and solves the full problem)."""
    from gyroshell.studies.sweep import solve_speeds

    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8))
    assert model.params.string_speed < 85.0 < divergence(model).speed
    results = solve_speeds(model, [70.0, 85.0], 4, continuation=True, workers=1,
                           options={}, progress=False, description="sweep")
    assert "mirror" in results[-1].info
    independent = modes(TapeModel(model.params), 85.0, 4, symmetry=False)
    assert "mirror" not in independent.info
    assert results[-1].omega == pytest.approx(independent.omega, rel=1e-10)


def test_a_single_call_past_the_string_speed_proves_the_halves_definite():
    """Above √(T/ρ) a lone call (no stiffness floor proved near divergence) proves K_s(V)
    and K_a(V) definite, solves on the halves and finds the full problem's frequencies;
    past divergence (K(V) indefinite: a real pair ±λ, Wickert & Mote's instability) the
    halves' proof fails and the full problem is solved."""
    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8))
    v_div = divergence(model).speed
    halves = modes(TapeModel(model.params), 85.0, 4)
    assert "mirror" in halves.info
    assert halves.omega == pytest.approx(
        modes(TapeModel(model.params), 85.0, 4, symmetry=False).omega, rel=1e-10)
    assert halves.residuals.max() < 1e-14
    beyond = modes(TapeModel(model.params), 1.05 * v_div, 4)
    assert "mirror" not in beyond.info and beyond.supercritical


def test_the_half_divergence_skips_is_proved_above_the_buckling_value():
    """divergence() skips the mirror half proved to lie above the other's μ_min; on the
    dense matrices that half's A_h − μ_min B_h is positive definite and the other half's
    A_h − μB_h turns indefinite just above μ_min (the buckling half), so the root search
    may treat the skipped half's K_h(V) as definite below V_div."""
    from gyroshell.engines.divergence import proved_above
    from gyroshell.tape.mirror import mirror_split

    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8))
    d = divergence(model)
    proved = proved_above(model)
    assert len(proved) == 1
    (which, mu), = proved.items()
    assert mu == pytest.approx(d.mu, rel=1e-12)
    split = mirror_split(model)
    other = "antisymmetric" if which == "symmetric" else "symmetric"
    A, B = (X.toarray() for X in split.stiffness(which))
    assert np.linalg.eigvalsh(A - mu * B).min() > 0
    A, B = (X.toarray() for X in split.stiffness(other))
    assert np.linalg.eigvalsh(A - d.mu * (1 - 1e-6) * B).min() > 0
    assert np.linalg.eigvalsh(A - d.mu * (1 + 1e-6) * B).min() < 0
