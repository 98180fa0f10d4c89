"""Head design studies over the corner radius at speed (compute="bearing", 4 m/s, a 1 mm
land at 2°/2°, the infinitely wide tape on each point's default grid): each row is the
point's single solve, bit for bit, in Python, on the command line and on a Dask cluster;
each point's corners and air carry the wrap load exactly; as r_c → 0 the rounded corners
tend to the sharp one."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD, LEGACY_CLI
from convergence import observed_order

from gyroshell import TapeParameters
from gyroshell.bearing import BearingModel
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.head_config import HeadDesign
from gyroshell.bearing.steady import solve_steady
from gyroshell.core.files import read_csv_exact
from gyroshell.studies.head_study import BearingStudy
from gyroshell.studies.parameter_study import run_study

WRAP = math.radians(2.0)
VELOCITY = 4.0
DESIGN = HeadDesign(kind="flat", land_length=1e-3, wrap_in=WRAP, wrap_out=WRAP,
                    transducers=(0.0,))
#: The hard wall with first-order slip: the sharp corner's point contacts, whose forces
#: carry the wrap load exactly, and the rounded ones' tending to them.
SETUP = BearingStudy(head=DESIGN, infinitely_wide=True, air=FIRST_ORDER, contact=HARD)
#: Sharp, three radii far below the film's constriction at the flank σ/α (57 nm: the
#: arc r_c θ_c, θ_c the 20° flank's turn, must be shorter for the corner to look sharp),
#: and a rounded corner (its arc 17 µm) ...
RADII = [0.0, 1e-8, 3e-8, 1e-7, 5e-5]
#: ... and the two of the fast test.
FEW = [0.0, 1e-8]


def _study(radii, **kw):
    if "scheduler" not in kw:
        kw.setdefault("workers", 1)
    return run_study(TapeParameters(), vary={"corner_radius": radii}, compute="bearing",
                     velocity=VELOCITY, bearing=SETUP, progress=False, **kw)


@pytest.fixture(scope="module")
def study():
    return _study(RADII)


def _single(radius: float):
    """The point's state solved directly, its head built from the head's own classes."""
    head = FlatHead((Module(1e-3, corner_radius=radius),), WRAP, WRAP, transducers=(0.0,))
    model = BearingModel(TapeParameters(), FIRST_ORDER, velocity=VELOCITY, head=head,
                         infinitely_wide=True, contact=HARD)
    return solve_steady(model)


def _assert_rows_are_single_solves_balancing_the_wrap_load(table):
    """Every row's readings equal its single solve's, bit for bit; and the solve's tape
    rows summed give corners + air = T'(θ_in + θ_out) + the ends' reaction (K 1)ᵀu, to
    1e-4 of the wrap load (the identity derived in
    tests/bearing/test_flat_head_convergence.py; rounded corners change only where the
    tape touches): only the corners touch, their forces sum to the contact force."""
    for row in table.itertuples():
        sol = _single(row.corner_radius)
        assert row.central_spacing == sol.central_spacing
        assert row.minimum_spacing == sol.minimum_spacing
        line = sol.transducer_lines[0]
        assert row.transducer_1_min_spacing == line.minimum
        assert row.transducer_1_mean_spacing == line.mean
        forces = [c.force for c in sol.corner_forces]
        assert [row.corner_1_force, row.corner_2_force] == forces
        assert row.contact_force == sol.contact_force
        assert row.drag == sol.drag and row.tension_ratio == sol.tension_ratio
        assert row.newton_iterations == sol.info.iterations
        m = sol.model
        assert sum(forces) == pytest.approx(sol.contact.sum(), rel=1e-12)
        assert sol.contact_nodes == 2
        t_eff = m.effective_tension()
        air = float(np.sum(m.pressure_load @ (sol.p - m.air.ambient_pressure)))
        reaction = float(m.K() @ np.ones(m.n_u) @ sol.u)
        balance = sum(forces) + air - t_eff * (WRAP + WRAP) - reaction
        assert abs(balance) < 1e-4 * t_eff * 2 * WRAP
        assert air < 0.0 and min(forces) > t_eff * WRAP     # the suction adds to T'θ


def test_sharp_and_nearly_sharp_rows_are_single_solves_balancing_the_wrap_load():
    few = _study(FEW)
    assert few.failed.empty, few.failed.error.tolist()
    _assert_rows_are_single_solves_balancing_the_wrap_load(few.table)


@pytest.mark.slow
def test_rounded_rows_are_single_solves_balancing_the_wrap_load(study):
    assert study.failed.empty, study.failed.error.tolist()
    _assert_rows_are_single_solves_balancing_the_wrap_load(study.table)


@pytest.mark.slow
def test_rounded_corners_tend_to_the_sharp_corner_as_the_radius_vanishes(study):
    """|h(r_c) − h(0)| at the transducer falls about linearly in r_c (measured order 1.15
    over 1e-8 to 1e-7 m: 0.022 %, 0.076 %, 0.33 %) and so do the corner forces; a 50 µm
    corner flies higher (its arc spreads the constriction) and carries less."""
    table = study.table.set_index("corner_radius")
    sharp = table.loc[0.0]
    small = [r for r in RADII if 0.0 < r <= 1e-7]
    gaps = [abs(table.loc[r].transducer_1_min_spacing / sharp.transducer_1_min_spacing - 1)
            for r in small]
    assert gaps[0] < 5e-4
    assert observed_order(small, gaps) == pytest.approx(1.15, abs=0.3)
    forces = [abs(table.loc[r].corner_1_force / sharp.corner_1_force - 1) for r in small]
    assert forces[0] < 1e-4 and observed_order(small, forces) > 0.8
    rounded = table.loc[5e-5]
    assert rounded.transducer_1_min_spacing > 1.05 * sharp.transducer_1_min_spacing
    assert rounded.corner_1_force < sharp.corner_1_force


@pytest.mark.slow
def test_the_command_line_study_gives_the_same_rows(cli, tmp_path, study):
    out = tmp_path / "radii.csv"
    run = cli(["study", "--compute", "bearing", *LEGACY_CLI, "--head", "flat", "--land-length",
               "1e-3",
               "--wrap-in", "2", "--wrap-out", "2", "--transducers", "0",
               "--infinitely-wide", "--vary", "corner_radius=" + ",".join(map(str, RADII)),
               "--velocity", VELOCITY, "--workers", "1", "--out", out, "--quiet"])
    assert run.code == 0, run.err
    table = read_csv_exact(out)
    assert table.corner_radius.tolist() == RADII
    columns = [c for c in study.table.columns if c != "error"]
    assert table[columns].equals(study.table[columns])


@pytest.mark.slow
def test_a_dask_cluster_gives_the_same_rows(study):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        again = _study(RADII, chunk_size=1, scheduler=cluster.scheduler_address)
    assert again.info["executor"].startswith("dask(tcp://")
    assert again.table.equals(study.table)
