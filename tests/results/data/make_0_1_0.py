"""Write the small result files of tests/results/data/0.1.0 with release 0.1.0 (commit
24513fb): run `python tests/results/data/make_0_1_0.py tests/results/data/0.1.0` with a
checkout of that commit first on PYTHONPATH. The files prove that results saved by that
release keep loading."""
import sys
from pathlib import Path

import numpy as np

import gyroshell as g

out = Path(sys.argv[1])
out.mkdir(parents=True, exist_ok=True)
W = 6.35e-3
p = g.TapeParameters(length_ratio=2, spacing=W / 8)
m = g.TapeModel(p)
g.solve_static(m, 10.0).save(out / "static.nc", params=p)
g.modes(m, 10.0, count=4).save(out / "modes.nc", params=p)
g.critical_speeds(m).save(out / "critical.nc", params=p)
g.march(m, 10.0, dt=2e-6, steps=40, snapshot_every=20, record_energy=True).save(
    out / "transient.nc", params=p)
frame = g.sweep(m, [0.0, 10.0, 20.0], count=3)
g.save(frame, out / "sweep_table.nc", params=p)
g.save(frame, out / "sweep_table.csv")
study = g.run_study(p, vary={"tension": [80.0, 100.0]}, compute=("critical", "modes"), workers=1)
study.save(out / "study.nc")
from gyroshell.campbell import campbell
campbell(m, [0.0, 10.0, 20.0], count=3).save(out / "campbell_table.nc")
from gyroshell import bearing
bm = bearing.BearingModel(p, bearing.AirParameters(), velocity=4.0, wrap_angle=np.radians(15.0),
                          infinitely_wide=True, nx=64)
sol = bearing.solve_steady(bm)
from gyroshell.bearing import storage as bstorage
bstorage.save(sol, out / "bearing.nc")
narrow = g.TapeParameters(width=3e-3)
bm2 = bearing.BearingModel(narrow, bearing.AirParameters(), velocity=4.0,
                           wrap_angle=np.radians(15.0), nx=32, ny=16)
from gyroshell.bearing import storage as bstorage
bstorage.save(bearing.solve_steady(bm2), out / "bearing_2d.nc")
print(sorted(x.name for x in out.iterdir()))
