"""Every study stays runnable: quick settings here (coarse grid, short records) through the
same code path as the full reproduction; the full settings run under `-m slow`."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

from gyroshell.cli import main
from gyroshell.reproduce import STUDIES

# Slow as a whole: every test reads the studies' outputs, which a module fixture
# computes (about 30 s).
pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def quick_results(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("quick")
    assert main(["reproduce", "all", "--out-dir", str(out), "--quick", "--quiet"]) == 0
    return out


EXPECTED = {
    "critical": ("critical_speeds.csv", None),
    "fig2": ("fig2_load_point.csv", "fig2_load_point.png"),
    "fig3": ("fig3_snapshots.csv", "fig3_wireframes.png"),
    "fig4": ("fig4_snapshots.csv", "fig4_wireframes.png"),
    "fig5": ("fig5_centerline.csv", "fig5_waterfall.png"),
    "fig6": ("fig6_centerline.csv", "fig6_waterfall.png"),
    "period": ("period_vs_velocity.csv", "period_vs_velocity.png"),
    "observations": ("observations.csv", "observations.png"),
    "helical": ("helical_heads.csv", "helical_heads.png"),
    "frf": ("frf.csv", "frf_bode.png"),
    "bearing": ("bearing_speed.csv", "bearing_speed.png"),
    "orthotropy": ("orthotropy_speeds.csv", "orthotropy_speeds.png"),
    "heads": ("heads_modules.csv", "heads_modules.png"),
}


def test_every_study_is_covered():
    assert set(EXPECTED) == set(STUDIES)


@pytest.mark.parametrize("name", STUDIES)
def test_each_study_writes_csv_and_png(quick_results, name):
    csv, png = EXPECTED[name]
    assert len(pd.read_csv(quick_results / csv)) > 0
    if png:
        assert (quick_results / png).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not [p for p in quick_results.iterdir() if p.name.startswith(".")], \
        "temporary files left behind"


@pytest.mark.slow
def test_helical_heads_alternate_and_each_sees_a_spacing_variation(quick_results):
    contacts = pd.read_csv(quick_results / "helical_contacts.csv")
    assert set(contacts["head"]) == {0, 1}
    assert (contacts["range_w"] > 0).all() and (contacts["mean_w"] > 0).all()
    heads = pd.read_csv(quick_results / "helical_heads.csv")
    both = (heads["contact_head0"] > 0) & (heads["contact_head1"] > 0)
    assert not both.any()  # wrap below 180 degrees: never two heads at once
    assert (quick_results / "helical_wireframes.png").read_bytes()[:4] == b"\x89PNG"


def test_frf_first_resonance_follows_the_eigen_solver_down(quick_results):
    from scipy.signal import find_peaks

    table = pd.read_csv(quick_results / "frf.csv")
    found = pd.read_csv(quick_results / "frf_modes.csv")
    first = []
    for v, rows in table.groupby("velocity"):
        peaks, _ = find_peaks(rows["amplitude"].to_numpy())
        omega = rows["omega"].to_numpy()
        step = omega[1] - omega[0]
        w1 = found[(found["velocity"] == v) & (found["rank"] == 1)]["omega"].iloc[0]
        assert abs(omega[peaks[0]] - w1) <= 1.5 * step
        first.append(omega[peaks[0]])
    assert first[0] > first[1] > first[2]


def test_critical_table_routes_agree(quick_results):
    table = pd.read_csv(quick_results / "critical_speeds.csv")
    ours = table[table["model"].str.startswith("this model")]
    assert len(ours) == 4
    rel = (ours["critical_speed"] - ours["divergence_speed"]).abs() / ours["divergence_speed"]
    assert rel.max() < 1e-5
    assert {"model", "critical_speed"} <= set(table.columns)


def test_fig2_steady_states_agree_with_damped_run(quick_results):
    steady = pd.read_csv(quick_results / "fig2_steady_state.csv")
    assert steady["rel_difference"].max() < 1e-6
    # The mean deflection grows with speed, as in the paper's Fig. 2.
    assert steady["w_static"].is_monotonic_increasing


def test_period_grows_with_speed(quick_results):
    table = pd.read_csv(quick_results / "period_vs_velocity.csv")
    assert {"velocity", "period_transient", "period_eigen"} <= set(table.columns)
    assert table["period_eigen"].is_monotonic_increasing
    assert table["period_transient"].iloc[-1] > 10 * table["period_transient"].iloc[0]


def test_wavelength_longer_downstream(quick_results):
    obs = pd.read_csv(quick_results / "observations.csv").set_index("quantity")
    up = obs.loc["dominant wavelength upstream of the load, V = 50", "value"]
    down = obs.loc["dominant wavelength downstream of the load, V = 50", "value"]
    assert down > up


def test_orthotropy_table_holds_the_plane_stress_stiffnesses(quick_results):
    """E_x = 4 GPa, nu_xy = 0.3, c = 20 um held: D11 = E_x c^3 / (12 (1 - nu^2 E_y/E_x)),
    and the critical speed stays below the width-uniform strip's, which it nears as D12
    (the anticlastic relief of the free edges) falls with E_y."""
    table = pd.read_csv(quick_results / "orthotropy_speeds.csv")
    ex, nu, c = 4e9, 0.3, 20e-6
    det = 1 - nu**2 * table["ratio"]
    assert ((table["D11"] - ex * c**3 / (12 * det)).abs() < 1e-12 * table["D11"]).all()
    assert ((table["D22"] - table["ratio"] * table["D11"]).abs() < 1e-12 * table["D22"]).all()
    assert (table["critical_speed"] <= table["strip_critical_speed"]).all()
    gap = table["strip_critical_speed"] - table["critical_speed"]
    assert gap.is_monotonic_increasing
    cuts = pd.read_csv(quick_results / "orthotropy_bearing.csv")
    assert set(cuts["ratio"]) == {0.25, 1.0, 4.0} and (cuts["spacing"] > 0).all()


def test_unknown_study_is_a_user_error(capsys, tmp_path):
    with pytest.raises(SystemExit) as info:
        main(["reproduce", "fig9", "--out-dir", str(tmp_path)])
    assert info.value.code == 2
    assert "invalid choice" in capsys.readouterr().err


def test_study_script_runs_as_a_program(tmp_path):
    proc = subprocess.run([sys.executable, str(ROOT / "studies" / "fig3.py"), "--out-dir",
                           str(tmp_path), "--quick", "--quiet"],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "fig3_wireframes.png").exists()


def test_full_reproduction_of_fig2(tmp_path):
    assert main(["reproduce", "fig2", "--out-dir", str(tmp_path), "--quiet"]) == 0
    steady = pd.read_csv(tmp_path / "fig2_steady_state.csv")
    assert steady["rel_difference"].max() < 1e-6
