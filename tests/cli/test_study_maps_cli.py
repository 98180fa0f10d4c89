"""Maps from the shell: ``study --plot`` over two varied parameters draws the computed
quantity (for a head with transducers, their minimum spacing), ``--quantity`` chooses
another, angles are in degrees, ``--vary wrap`` sets both wraps, ``--sketch`` draws the
head, and a transducer in a gap between modules is refused."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gyroshell.core.files import read_csv_exact

#: A two-module flat head with a transducer on each land, the infinitely wide tape on a
#: coarse grid (about 0.2 s a point).
HEAD = ["--compute", "bearing", "--head", "flat", "--land-length", "1e-3", "--modules", "2",
        "--module-gap", "3e-4", "--transducers=-6.5e-4,6.5e-4", "--infinitely-wide",
        "--nx", "160", "--workers", "1", "--quiet"]
PNG = b"\x89PNG\r\n\x1a\n"


def _pixels(path):
    import matplotlib.image as mpimg

    return mpimg.imread(path)[..., :3]


def test_a_map_over_wrap_and_speed_of_the_transducers_minimum_spacing(cli, tmp_path):
    out, png = tmp_path / "s.csv", tmp_path / "map.png"
    run = cli(["study", *HEAD, "--vary", "wrap=1:3:3", "--vary", "velocity=2,4",
               "--out", out, "--plot", png])
    assert run.code == 0, run.err
    assert png.read_bytes()[:8] == PNG
    pixels = _pixels(png)
    # a colour map, not a blank page: many distinct colours, most of the picture not white
    assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 50
    assert (pixels < 0.95).any(axis=-1).mean() > 0.3
    table = read_csv_exact(out)
    # wrap sets both wraps: the table keeps it in rad, as typed in degrees
    np.testing.assert_allclose(table["wrap"], np.radians([1, 1, 2, 2, 3, 3]), rtol=1e-15)
    assert table.error.isna().all()


def test_the_map_axes_colour_bar_and_cells_from_python(tmp_path):
    from gyroshell import TapeParameters
    from gyroshell.bearing.head_config import HeadDesign
    from gyroshell.plot import save_figure
    from gyroshell.studies.head_study import BearingStudy
    from gyroshell.studies.parameter_study import run_study

    design = HeadDesign(kind="flat", land_length=1e-3, modules=2, module_gap=3e-4,
                        transducers=(-6.5e-4, 6.5e-4))
    wraps = np.radians([1.0, 3.0])
    study = run_study(TapeParameters(), vary={"wrap": wraps, "velocity": [2.0, 4.0, 6.0]},
                      compute="bearing", workers=1, progress=False,
                      bearing=BearingStudy(head=design, infinitely_wide=True, nx=160))
    ax = study.plot()
    assert ax.get_xlabel() == "wrap (deg)" and ax.get_ylabel() == "velocity (m/s)"
    colour_bar = ax.figure.axes[-1]
    assert colour_bar.get_ylabel() == "minimum spacing at the transducers (nm)"
    # the default quantity: the smaller of the two lines' minima, in nm, cell by cell
    t = study.table
    expected = 1e9 * np.minimum(t.transducer_1_min_spacing, t.transducer_2_min_spacing)
    cells = ax.collections[0].get_array()
    np.testing.assert_allclose(np.sort(np.ravel(cells)), np.sort(expected), rtol=1e-12)
    assert 10 < expected.min() < expected.max() < 1000   # nm: on the lands, not the gap
    # the x cells sit at the degrees typed (edges half way between)
    x_edges = ax.collections[0].get_coordinates()[0, :, 0]
    np.testing.assert_allclose(x_edges, [0.0, 2.0, 4.0], atol=1e-12)
    assert save_figure(ax.figure, tmp_path / "m.png", dpi=60).read_bytes()[:8] == PNG
    other = study.plot(quantity="central_spacing")
    assert other.figure.axes[-1].get_ylabel() == "central spacing (µm)"  # the gap's depth
    line = study.table[study.table.velocity == 4.0]
    one = run_study(TapeParameters(), vary={"wrap": wraps}, velocity=4.0, compute="bearing",
                    workers=1, progress=False,
                    bearing=BearingStudy(head=design, infinitely_wide=True, nx=160))
    ax = one.plot()
    assert ax.get_xlabel() == "wrap (deg)"
    assert ax.get_ylabel() == "minimum spacing at the transducers (nm)"
    np.testing.assert_allclose(ax.lines[0].get_xdata(), [1.0, 3.0], rtol=1e-14)
    np.testing.assert_allclose(
        ax.lines[0].get_ydata(),
        1e9 * np.minimum(line.transducer_1_min_spacing, line.transducer_2_min_spacing),
        rtol=1e-14)


def test_quantity_chooses_the_column_and_an_unknown_one_is_refused_listing_them(
        cli, tmp_path):
    png = tmp_path / "map.png"
    run = cli(["study", *HEAD, "--vary", "wrap=1,3", "--vary", "velocity=2,4",
               "--plot", png, "--quantity", "spacing"])
    assert run.code == 2 and len(run.error_lines) == 1, run.err
    assert "--quantity spacing: this study has no such column; choose one of " \
           "transducer_min_spacing, central_spacing, minimum_spacing, " in run.err
    assert "newton_iterations" in run.err and not png.exists()
    run = cli(["study", *HEAD, "--vary", "wrap=1,3", "--quantity", "drag"])
    assert run.code == 2 and "--quantity chooses what --plot draws" in run.err
    run = cli(["study", *HEAD, "--vary", "wrap=1,3", "--vary", "velocity=2,4",
               "--plot", png, "--quantity", "drag"])
    assert run.code == 0, run.err
    assert png.read_bytes()[:8] == PNG


def test_the_printed_table_shows_the_wraps_in_degrees(cli):
    run = cli(["study", *HEAD, "--vary", "wrap=1:2:2", "--velocity", "4"])
    assert run.code == 0, run.err
    header, first, second = run.out.splitlines()[:3]
    assert header.split()[0] == "wrap_deg"
    assert first.split()[0] == "1" and second.split()[0] == "2"


def test_wrap_sets_both_wraps(cli, tmp_path):
    both, each = tmp_path / "both.csv", tmp_path / "each.csv"
    assert cli(["study", *HEAD, "--vary", "wrap=2", "--velocity", "4", "--out", both]).code == 0
    run = cli(["study", *HEAD, "--vary", "wrap_in=2", "--wrap-out", "2", "--velocity", "4",
               "--out", each])
    assert run.code == 0, run.err
    a, b = read_csv_exact(both), read_csv_exact(each)
    assert a.wrap[0] == b.wrap_in[0] == math.radians(2.0)
    computed = [c for c in a.columns if c not in ("point", "wrap", "error")]
    assert a[computed].equals(b[computed])


@pytest.mark.parametrize("argv, message", [
    (["--vary", "wrap=1,2", "--wrap-in", "2"],
     "--wrap-in and --vary wrap both set wrap_in"),
    (["--vary", "wrap=1,2", "--vary", "wrap_out=1,2"],
     "wrap sets both wrap_in and wrap_out: vary wrap or wrap_out, not both"),
])
def test_wrap_with_either_wrap_is_refused_in_one_line(cli, argv, message):
    run = cli(["study", *HEAD, *argv])
    assert run.code == 2 and len(run.error_lines) == 1, run.err
    assert message in run.err


def test_sketch_draws_the_head_of_the_first_point(cli, tmp_path):
    png = tmp_path / "head.png"
    run = cli(["study", *HEAD, "--vary", "wrap=2,3", "--velocity", "4", "--sketch", png])
    assert run.code == 0, run.err
    assert png.read_bytes()[:8] == PNG and f"wrote {png}" in run.out
    run = cli(["study", "--compute", "critical", "--vary", "tension=80,90", "--sketch", png])
    assert run.code == 2 and "--sketch draws the head of --compute bearing" in run.err


def test_head_sketch_marks_modules_gap_and_transducers():
    from gyroshell.bearing.head import FlatHead, Module
    from gyroshell.bearing.plots import head_sketch

    head = FlatHead((Module(1e-3), Module(1e-3)), math.radians(2), math.radians(2),
                    gaps=(3e-4,), transducers=(-6.5e-4, 6.5e-4))
    ax = head_sketch(head)
    texts = [t.get_text() for t in ax.texts]
    assert {"module 1", "module 2", " T1", " T2"} <= set(texts)
    assert "gap\n0.3 mm" in texts
    assert ax.get_xlabel().startswith("x from the head's middle (mm)")
    assert ax.get_ylabel() == "z (µm)"
    # the dry tape lies on the lands (z = 0) and runs straight over the gap
    tape = next(line for line in ax.lines if line.get_label().startswith("dry tape"))
    x, z = tape.get_xdata(), tape.get_ydata()
    over = np.abs(x) <= 1.15
    np.testing.assert_allclose(z[over], 0.0, atol=1e-9)


@pytest.mark.parametrize("command", [
    ["bearing", "--velocity", "4", "--wrap-in", "2", "--wrap-out", "2"],
    ["study", "--vary", "wrap=1,2", "--velocity", "4", "--compute", "bearing",
     "--workers", "1"],
])
def test_a_transducer_in_the_gap_is_refused_in_one_line(cli, command):
    run = cli([*command, "--head", "flat", "--land-length", "1e-3", "--modules", "2",
               "--module-gap", "3e-4", "--transducers", "0", "--infinitely-wide",
               "--quiet"])
    assert run.code == 2 and len(run.error_lines) == 1, run.err
    assert ("transducers[0] must lie on a land of the head ([-0.00115, -0.00015], "
            "[0.00015, 0.00115] m, from its middle), got 0: it is in a gap between "
            "modules") in run.err
