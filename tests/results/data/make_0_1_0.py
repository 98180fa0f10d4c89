"""Write the small result files of tests/results/data/0.1.0 with release 0.1.0 (commit
24513fb): run `python tests/results/data/make_0_1_0.py tests/results/data/0.1.0` with a
checkout of that commit first on PYTHONPATH. The files prove that results saved by that
release keep loading; the module names below are that release's."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

#: Table 1 tape width, m.
WIDTH = 6.35e-3
#: The 15° wrap of the bearing cases, rad.
WRAP = np.radians(15.0)


def main(out: Path) -> None:
    from gyroshell.campbell import campbell

    import gyroshell as g
    from gyroshell import bearing
    from gyroshell.bearing import storage

    out.mkdir(parents=True, exist_ok=True)
    p = g.TapeParameters(length_ratio=2, spacing=WIDTH / 8)
    m = g.TapeModel(p)
    g.solve_static(m, 10.0).save(out / "static.nc", params=p)
    g.modes(m, 10.0, count=4).save(out / "modes.nc", params=p)
    g.critical_speeds(m).save(out / "critical.nc", params=p)
    g.march(m, 10.0, dt=2e-6, steps=40, snapshot_every=20, record_energy=True).save(
        out / "transient.nc", params=p)
    frame = g.sweep(m, [0.0, 10.0, 20.0], count=3)
    g.save(frame, out / "sweep_table.nc", params=p)
    g.save(frame, out / "sweep_table.csv")
    g.run_study(p, vary={"tension": [80.0, 100.0]}, compute=("critical", "modes"),
                workers=1).save(out / "study.nc")
    campbell(m, [0.0, 10.0, 20.0], count=3).save(out / "campbell_table.nc")
    wide = bearing.BearingModel(p, bearing.AirParameters(), velocity=4.0, wrap_angle=WRAP,
                                infinitely_wide=True, nx=64)
    storage.save(bearing.solve_steady(wide), out / "bearing.nc")
    narrow = bearing.BearingModel(g.TapeParameters(width=3e-3), bearing.AirParameters(),
                                  velocity=4.0, wrap_angle=WRAP, nx=32, ny=16)
    storage.save(bearing.solve_steady(narrow), out / "bearing_2d.nc")
    print(sorted(x.name for x in out.iterdir()))


if __name__ == "__main__":
    main(Path(sys.argv[1]))
