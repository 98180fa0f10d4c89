"""Memory of gyroscopic_modes: the estimate checked before work against the measured peak.

Each case runs in a fresh process: the tape's M, G(V), K(V) (V = 50 m/s) are built and
written to an .npz first, so the measuring process only loads them, notes its resident
memory, calls ``gyroshell.gyroscopic_modes`` and reads its peak (``ru_maxrss``). The
measured figure is peak − resident before the call; the estimate
(:func:`gyroshell.linalg.qep.problem.qep_bytes`) must be at or above it. Both back-ends of
the shift factorization are run (CHOLMOD where cvxopt is installed, SuperLU).

    python benchmarks/bench_qep_memory.py [--ratios 2,4,8,19] [--count 6]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile

CHILD = r"""
import json, resource, sys
import numpy as np, scipy.sparse as sp
from gyroshell import gyroscopic_modes
from gyroshell.linalg.qep.problem import qep_bytes
data = np.load(sys.argv[1])
def csr(p):
    return sp.csr_matrix((data[p + "data"], data[p + "indices"], data[p + "indptr"]),
                         shape=tuple(data[p + "shape"]))
M, G, K = csr("M"), csr("G"), csr("K")
count, factorization = int(sys.argv[2]), sys.argv[3]
with open("/proc/self/statm") as fh:
    before = int(fh.read().split()[1]) * resource.getpagesize()
gyroscopic_modes(M, G, K, count, factorization=factorization)
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
n, nnz = M.shape[0], M.nnz + G.nnz + K.nnz
print(json.dumps({"n": n, "nnz": nnz, "estimate": qep_bytes(n, nnz, count),
                  "measured": max(peak - before, 0)}))
"""


def save_matrices(ratio: float, path: str) -> None:
    import numpy as np

    from gyroshell import TapeModel, TapeParameters

    model = TapeModel(TapeParameters(length_ratio=ratio))
    parts = {}
    for name, A in (("M", model.M), ("G", model.G(50.0)), ("K", model.K(50.0))):
        A = A.tocsr()
        parts.update({name + "data": A.data, name + "indices": A.indices,
                      name + "indptr": A.indptr, name + "shape": np.array(A.shape)})
    np.savez(path, **parts)


def measure(ratio: float, count: int, factorization: str) -> dict:
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "qep.npz")
        save_matrices(ratio, path)
        out = subprocess.run([sys.executable, "-c", CHILD, path, str(count), factorization],
                             capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ratios", default="2,4,8,19")
    parser.add_argument("--count", type=int, default=6)
    args = parser.parse_args()
    from gyroshell.linalg import cholesky

    backends = ["cholmod", "superlu"] if cholesky.available() else ["superlu"]
    print(f"{'L_x/L_y':>8} {'factor':>8} {'unknowns':>9} {'entries':>9} {'estimate MB':>12} "
          f"{'measured MB':>12} {'ratio':>6}")
    for ratio in (float(r) for r in args.ratios.split(",")):
        for backend in backends:
            row = measure(ratio, args.count, backend)
            print(f"{ratio:8g} {backend:>8} {row['n']:9d} {row['nnz']:9d} "
                  f"{row['estimate'] / 1e6:12.1f} {row['measured'] / 1e6:12.1f} "
                  f"{row['estimate'] / max(row['measured'], 1):6.2f}")


if __name__ == "__main__":
    main()
