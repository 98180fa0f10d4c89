"""The transient recorder's centre lines (gyroshell.results.transient.Recorder).

A centre line is read off the two columns of unknowns beside y = L_y/2, from the full
unknowns or from the mirror-symmetric half's z, without forming the field. The reference is
the definition: Grid.centerline of the nodal field Grid.to_field(P_s z), built here.
"""

from __future__ import annotations

import numpy as np
import pytest

from gyroshell.results.transient import Recorder
from gyroshell.tape.grid import Grid
from gyroshell.tape.mirror import SymmetricHalf


@pytest.mark.parametrize("ny", [8, 9])
@pytest.mark.parametrize("edges", ["free", "simply-supported"])
def test_centre_lines_from_the_half_and_the_full_unknowns_equal_the_fields(ny, edges, rng):
    grid = Grid(0.03, 6.35e-3, 12, ny, edges=edges)
    half = SymmetricHalf.of(grid)
    steps = 3
    zs = rng.standard_normal((steps + 1, half.unknowns))
    from_half = Recorder(grid, steps, 1e-6, centerline_times=1e-6 * np.arange(steps + 1),
                         snapshot_times=[2e-6])
    from_full = Recorder(grid, steps, 1e-6, centerline_times=1e-6 * np.arange(steps + 1),
                         snapshot_times=[2e-6])
    for n, z in enumerate(zs):
        from_half.record(n, z, half)
        from_full.record(n, half.expand(z))
    fields = [grid.to_field(half.expand(z)) for z in zs]
    expected = np.array([grid.centerline(f) for f in fields])
    times = 1e-6 * np.arange(steps + 1)
    for rec in (from_half, from_full):
        snaps = rec.snapshots(times)
        assert np.array_equal(snaps.centerlines, expected)  # the same arithmetic: bit for bit
        assert np.array_equal(snaps.fields[0], fields[2])
    assert not expected[:, [0, -1]].any() and np.abs(expected).min(axis=0)[1:-1].all()
