"""Transients on the mirror-symmetric half (gyroshell.engines.newmark, module notes).

A tape whose load, damping and initial state are symmetric about its centre line y = L_y/2
stays symmetric: w = P_s z with z on the symmetric half, and the half's equations
M_s a + (G_s + C_s) v + K_s z = P_sᵀ F are the full ones projected. So the half march must
give the full march's answer to round-off, in every recorded output; anything asymmetric
must be marched full size, and then its answer is visibly not symmetric. Shared
factorizations: within ``sharing_factorizations()`` a second march of an equal tape at the
same settings does not factor.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import scipy.sparse as sp

import gyroshell.engines.newmark as newmark
from gyroshell import ParameterError, TapeModel, TapeParameters
from gyroshell.engines.newmark import Newmark, march, sharing_factorizations
from gyroshell.tape.damping import Damping
from gyroshell.tape.mirror import SymmetricHalf
from gyroshell.tape.moving_loads import ContactWindows, MovingLoad, StraightPath

WIDTH = 6.35e-3  # m
SPEED = 30.0  # m/s
DT = 2e-6  # s
STEPS = 80
#: Relative agreement of half and full marches: a few hundred roundings of each step.
# The half and the full grid are factored in different orderings (natural vs minimum
# degree): their round-off differs by up to ~1e-12 of the size over 250 steps.
ROUND_OFF = 1e-11


def tape(intervals_across: int = 10, edges: str = "free", **overrides) -> TapeModel:
    """L_x/L_y = 3 with ``intervals_across`` intervals across the width."""
    return TapeModel(TapeParameters(length_ratio=3, spacing=WIDTH / intervals_across,
                                    edges=edges, **overrides))


def mirrored(model: TapeModel, vector: np.ndarray) -> np.ndarray:
    """R w: the vector over the unknowns reflected y -> L_y - y, by the grid's numbering."""
    g = model.grid
    return vector.reshape(g.n_lines, g.n_across)[:, ::-1].ravel()


def asymmetry(model: TapeModel, vector: np.ndarray) -> float:
    """‖R w − w‖ / ‖w‖."""
    return float(np.linalg.norm(mirrored(model, vector) - vector) / np.linalg.norm(vector))


def work_scale(model: TapeModel, run) -> float:
    """Σ|F| max|w|, J: the size of the energy's terms (E itself stays near 0 from rest)."""
    return float(np.abs(model.force).sum() * np.abs(run.load_point).max())


def assert_same_run(half, full, model: TapeModel) -> None:
    """Every recorded output of two runs agrees to round-off of its own size."""
    def close(a, b):
        scale = np.abs(b).max()
        assert np.abs(a - b).max() <= ROUND_OFF * scale, (np.abs(a - b).max(), scale)

    assert half.info["symmetry"] == "half" and full.info["symmetry"] == "full"
    assert half.info["marched_unknowns"] < full.info["marched_unknowns"] == len(full.w)
    np.testing.assert_array_equal(half.times, full.times)
    for name in ("load_point", "w", "v", "a"):
        close(getattr(half, name), getattr(full, name))
    close(half.snapshots.fields, full.snapshots.fields)
    close(half.snapshots.centerlines, full.snapshots.centerlines)
    if full.head_displacements is not None:
        close(half.head_displacements, full.head_displacements)
    if full.energy is not None:
        assert np.abs(half.energy - full.energy).max() <= ROUND_OFF * work_scale(model, full)


RECORDED = dict(snapshot_every=20, centerline_times=[40e-6, 120e-6], record_energy=True,
                progress=False)


def both(model, velocity=SPEED, *, damping=None, **options):
    """(the default march, the same with symmetry=False), from one stepper."""
    stepper = Newmark(model, velocity, dt=DT, damping=damping)
    half = stepper.march(STEPS, **RECORDED, **options)
    full = stepper.march(STEPS, **RECORDED, symmetry=False, **options)
    return half, full


# ----- symmetric inputs: the half gives the full answer --------------------------------
@pytest.mark.parametrize(("across", "edges"), [(10, "free"), (9, "free"),
                                                (10, "simply-supported")],
                         ids=["centre node", "no centre node", "simply supported edges"])
def test_the_papers_step_load_at_mid_width_marches_the_half(across, edges):
    model = tape(across, edges)
    half, full = both(model)
    assert_same_run(half, full, model)
    assert asymmetry(model, full.w) < 1e-13          # the full answer is symmetric too
    assert half.summary()["symmetry"] == "half"


def test_damped_transients_march_the_half():
    """Viscous, mass- and stiffness-proportional damping are all mirror symmetric."""
    damping = Damping(viscous=200.0, mass_coefficient=50.0, stiffness_coefficient=1e-7)
    model = tape()
    assert_same_run(*both(model, damping=damping), model)


def test_a_symmetric_initial_state_and_a_time_profile_keep_the_half():
    """w⁰, v⁰ even in y − L_y/2 (a smooth bump) and a scalar profile f(t) = sin(ωt)."""
    model = tape()
    g = model.grid
    X, Y = np.meshgrid(g.x[g.x_unknowns], g.y[g.y_unknowns], indexing="ij")
    bump = (np.sin(np.pi * X / g.length) * np.cos(2 * np.pi * (Y - g.width / 2) / g.width)
            ).ravel()
    half, full = both(model, w0=1e-8 * bump, v0=-2e-3 * bump,
                      profile=lambda t: np.sin(2e4 * t))
    assert_same_run(half, full, model)


def test_a_continued_run_stays_on_the_half():
    """A run continued from a half run's final state is the whole run."""
    stepper = Newmark(tape(), SPEED, dt=DT)
    whole = stepper.march(60, progress=False)
    first = stepper.march(30, progress=False)
    rest = stepper.march(30, w0=first.w, v0=first.v, t0=first.times[-1], progress=False)
    assert rest.info["symmetry"] == "half"
    np.testing.assert_allclose(rest.load_point, whole.load_point[30:], rtol=0,
                               atol=ROUND_OFF * np.abs(whole.load_point).max())


def test_a_head_moving_along_the_centre_line_marches_the_half():
    """A Gaussian head travelling along y = L_y/2 with contact windows: symmetric."""
    model = tape()
    g = model.grid
    head = MovingLoad(StraightPath((g.length / 4, g.width / 2), (40.0, 0.0)),
                      contact=ContactWindows(period=60e-6, duration=40e-6, ramp=8e-6))
    half, full = both(model, load=head)
    assert_same_run(half, full, model)


# ----- asymmetric inputs: full size, and the answer shows it ----------------------------
def _off_centre_runs(model, **options):
    default = march(model, SPEED, dt=DT, steps=STEPS, progress=False, **options)
    full = march(model, SPEED, dt=DT, steps=STEPS, progress=False, symmetry=False,
                 **options)
    assert default.info["symmetry"] == "full"
    np.testing.assert_array_equal(default.load_point, full.load_point)
    np.testing.assert_array_equal(default.w, full.w)
    assert asymmetry(model, default.w) > 1e-2      # not mirror symmetric: it could not be halved
    return default


def test_an_off_centre_load_marches_full_size():
    _off_centre_runs(tape(load_y=WIDTH / 3))


@pytest.mark.parametrize("where", ["off the centre line", "moving across"])
def test_a_head_off_the_centre_line_or_moving_across_marches_full_size(where):
    model = tape()
    g = model.grid
    path = StraightPath((g.length / 4, g.width / 3), (40.0, 0.0)) if where.startswith("off") \
        else StraightPath((g.length / 4, g.width / 2), (40.0, 10.0))
    _off_centre_runs(model, load=MovingLoad(path))


def test_an_asymmetric_initial_state_marches_full_size():
    model = tape()
    g = model.grid
    tilt = np.tile(g.y[g.y_unknowns] - g.width / 2, g.n_lines)   # odd in y − L_y/2
    _off_centre_runs(model, w0=1e-5 * tilt)


class EdgeSpringTape(TapeModel):
    """The tape with extra foundation springs on its edge y = 0 only (N/m per node)."""

    @property
    def A(self):
        g = self.grid
        spring = np.zeros((g.n_lines, g.n_across))
        spring[:, 0] = 1e3 * self.params.k * g.hx * g.hy
        return (super().A + sp.diags(spring.ravel())).tocsr()


def test_a_tape_that_is_not_symmetric_marches_full_size():
    model = EdgeSpringTape(TapeParameters(length_ratio=3, spacing=WIDTH / 10))
    _off_centre_runs(model)


# ----- the trapezoidal rule's energy on the half ---------------------------------------
def test_the_half_march_conserves_the_full_fields_energy():
    """β = 1/4, γ = 1/2, no damping, constant force: E_n = ½vᵀMv + ½wᵀKw − Fᵀw is constant;
    recomputed from the half run's full final state, it is the recorded value."""
    model = tape()
    stepper = Newmark(model, SPEED, dt=DT)
    run = stepper.march(400, record_energy=True, progress=False)
    assert run.info["symmetry"] == "half"
    work = work_scale(model, run)
    assert np.abs(run.energy - run.energy[0]).max() <= 1e-10 * work
    assert abs(stepper.energy(run.w, run.v, model.force) - run.energy[-1]) <= 1e-12 * work


# ----- the switch -------------------------------------------------------------------------
@pytest.mark.parametrize("value", ["yes", 1, None])
def test_the_symmetry_switch_is_true_or_false(value):
    with pytest.raises(ParameterError, match="symmetry must be True or False"):
        march(tape(), SPEED, dt=DT, steps=2, symmetry=value)


def test_symmetric_half_restricts_and_expands_with_the_orthonormal_basis():
    """P_sᵀ P_s = I and P_s P_sᵀ f = f for symmetric f, on both parities of n_across."""
    for across in (5, 6):
        half = SymmetricHalf(n_lines=3, n_across=across)
        z = np.random.default_rng(across).standard_normal(half.unknowns)
        np.testing.assert_allclose(half.restrict(half.expand(z)), z, rtol=1e-15)
        w = half.expand(z)
        np.testing.assert_array_equal(half.reflect(w), w)
        assert half.is_symmetric(w) and not half.is_symmetric(w + np.arange(w.size))


# ----- shared factorizations ----------------------------------------------------------------
@pytest.fixture
def counted(monkeypatch):
    """Newmark's factorization, counting its calls."""
    calls = []

    def counting(matrix, backend="auto"):
        calls.append(matrix.shape[0])
        return factorize(matrix, backend)

    factorize = newmark.factorize_banded
    monkeypatch.setattr(newmark, "factorize_banded", counting)
    return calls


def test_a_second_march_of_an_equal_tape_in_the_block_does_not_factor(counted):
    with sharing_factorizations() as shared:
        first = march(tape(), SPEED, dt=DT, steps=10, progress=False)
        again = march(tape(), SPEED, dt=DT, steps=10, progress=False)  # another equal model
        assert len(counted) == 1 and again.info["factor_shared"]
        assert not first.info["factor_shared"] and again.info["factorizations"] == 0
        np.testing.assert_array_equal(again.load_point, first.load_point)
        march(tape(), SPEED, dt=2 * DT, steps=10, progress=False)       # another Δt
        march(tape(), SPEED, dt=DT, steps=10, symmetry=False, progress=False)  # full size
        with sharing_factorizations() as inner:                          # nested: the same
            march(tape(), SPEED, dt=DT, steps=10, progress=False)
        assert inner is shared and len(counted) == 3
        assert (shared.factorizations, shared.reuses) == (3, 2)
    assert len(shared) == 0                                              # dropped at the end
    march(tape(), SPEED, dt=DT, steps=10, progress=False)                # outside: factors
    assert len(counted) == 4


def test_one_stepper_factors_each_size_once(counted):
    stepper = Newmark(tape(), SPEED, dt=DT)
    assert counted == []                                   # nothing factored before a march
    for symmetry in (True, False, True, False):
        stepper.march(5, symmetry=symmetry, progress=False)
    n = stepper.model.unknowns
    assert sorted(counted) == [SymmetricHalf.of(stepper.model.grid).unknowns, n]
    assert stepper.info["factorizations"] == 2



def _half_bandwidth(*matrices) -> int:
    """The largest |i − j| of an entry of any of the matrices (that of K_eq = M + γΔt G +
    βΔt² K, M being diagonal)."""
    return max(int(np.abs(A.row - A.col).max()) for A in map(sp.coo_matrix, matrices))


def test_info_names_the_backend_of_the_k_eq_last_factored():
    """None before anything is factored; after each march the back-end of that march's
    K_eq, which "auto" chooses by its half-bandwidth (LAPACK's band LU up to
    NATURAL_HALF_BANDWIDTH, else SuperLU): 25 nodes across give the full K_eq a
    half-bandwidth of 50 (the plate's stencil reaches two lines), the half's 13 nodes 26."""
    from gyroshell.linalg.ordering import NATURAL_HALF_BANDWIDTH
    from gyroshell.tape.mirror import mirror_split

    model = tape(24)
    M_s, G_s, K_s = mirror_split(model).matrices(model, SPEED, "symmetric")
    bandwidth = {"half": _half_bandwidth(G_s, K_s),
                 "full": _half_bandwidth(model.G(SPEED), model.K(SPEED))}
    assert bandwidth["half"] <= NATURAL_HALF_BANDWIDTH < bandwidth["full"], bandwidth
    expected = {"half": "band", "full": "superlu"}
    stepper = Newmark(model, SPEED, dt=DT)
    assert stepper.info["backend"] is None
    for symmetry in (True, False, True):
        run = stepper.march(5, symmetry=symmetry, progress=False)
        which = run.info["symmetry"]
        assert which == ("half" if symmetry else "full")
        assert stepper.info["backend"] == run.info["backend"] == expected[which]
    assert Newmark(model, SPEED, dt=DT, backend="superlu").info["backend"] is None


def test_the_half_factor_exists_only_for_a_symmetric_tape():
    stepper = Newmark(tape(), SPEED, dt=DT)
    assert stepper.half_factor is stepper.half_factor is not None
    assert Newmark(EdgeSpringTape(TapeParameters(length_ratio=3, spacing=WIDTH / 10)),
                   SPEED, dt=DT).half_factor is None


# ----- the command line -------------------------------------------------------------------
def test_the_cli_marches_the_half_unless_told_no_symmetry(cli):
    argv = ["transient", "--spacing", WIDTH / 10, "--length-ratio", 3, "--velocity", SPEED,
            "--steps", 30, "--dt", DT, "--quiet", "--json"]
    half, full = (json.loads(cli(args).out) for args in (argv, [*argv, "--no-symmetry"]))
    assert (half["symmetry"], full["symmetry"]) == ("half", "full")
    assert half["max_load_point_displacement"] == pytest.approx(
        full["max_load_point_displacement"], rel=ROUND_OFF)
    text = cli(argv[:-1]).out
    assert "on the symmetric half (" in text


# ----- the paper's grid -----------------------------------------------------------------------
@pytest.mark.slow
def test_the_papers_run_on_the_table_1_grid_is_the_same_on_the_half():
    """L_x/L_y = 4, 164 x 41 intervals, 250 steps of 2 µs at 50 m/s (the paper's run)."""
    model = TapeModel(TapeParameters(length_ratio=4))
    stepper = Newmark(model, 50.0, dt=DT)
    options = dict(snapshot_times=[100e-6, 500e-6], centerline_times=[250e-6],
                   record_energy=True, progress=False)
    half, full = (stepper.march(250, symmetry=s, **options) for s in (True, False))
    assert_same_run(half, full, model)


def test_other_models_share_only_with_themselves(counted):
    """A TapeModel subclass may hold more than its parameters say: keyed by identity."""
    params = TapeParameters(length_ratio=3, spacing=WIDTH / 10)
    one, other = EdgeSpringTape(params), EdgeSpringTape(params)
    with sharing_factorizations():
        for model in (one, one, other):
            march(model, SPEED, dt=DT, steps=5, progress=False)
    assert len(counted) == 2
