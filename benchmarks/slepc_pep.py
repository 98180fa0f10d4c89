"""SLEPc's polynomial eigen-solver on exported gyroshell matrices (run in its own venv).

    python slepc_pep.py MATRICES.npz --rounds 3

Reads M, G, K (CSR parts) and the target frequency from the .npz written by
``bench_eigen.py``, and solves (λ²M + λG + K) φ = 0 for the eigenvalues nearest
σ = i·ω_t with PEP/TOAR, shift-and-invert, a MUMPS LU (AMF ordering) and tolerance
``--tol``. Prints one JSON object: per round the setup time (matrices, PEP set-up with the
factorization) and the solve time (s), the CPU time of both (``cpu``, s: on a loaded
machine closer to the work done than the wall time), and the lowest positive frequencies
(rad/s).
Needs a complex-scalar PETSc/SLEPc (the ``dolfinx-solver-complex`` wheel).
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

try:  # the wheel's bootstrap orders MPI ahead of petsc4py
    import dolfinx_solver  # noqa: F401
except ImportError:  # a plain petsc4py/slepc4py install
    pass
from petsc4py import PETSc
from slepc4py import SLEPc

#: MUMPS ICNTL(7) = 2: the approximate minimum fill (AMF) ordering.
MUMPS_AMF = 2


def petsc_matrix(data: np.lib.npyio.NpzFile, name: str) -> PETSc.Mat:
    indptr, indices = data[f"{name}_indptr"], data[f"{name}_indices"]
    values = data[f"{name}_data"].astype(PETSc.ScalarType)
    n = len(indptr) - 1
    mat = PETSc.Mat().createAIJ(size=(n, n), csr=(indptr.astype(PETSc.IntType),
                                                  indices.astype(PETSc.IntType), values))
    mat.assemble()
    return mat


def solve_once(data, nev: int, tol: float, target: float) -> dict:
    t0, c0 = time.perf_counter(), time.process_time()
    K, G, M = (petsc_matrix(data, name) for name in ("K", "G", "M"))
    pep = SLEPc.PEP().create()
    pep.setOperators([K, G, M])
    pep.setProblemType(SLEPc.PEP.ProblemType.GYROSCOPIC)
    pep.setType(SLEPc.PEP.Type.TOAR)
    pep.setDimensions(nev=nev)
    pep.setTolerances(tol=tol)
    pep.setTarget(1j * target)
    pep.setWhichEigenpairs(SLEPc.PEP.Which.TARGET_MAGNITUDE)
    opts = PETSc.Options()
    for key, value in (("st_type", "sinvert"), ("st_ksp_type", "preonly"),
                       ("st_pc_type", "lu"), ("st_pc_factor_mat_solver_type", "mumps"),
                       ("st_mat_mumps_icntl_7", MUMPS_AMF)):
        opts.setValue(key, value)
    pep.setFromOptions()
    pep.setUp()
    pc = pep.getST().getKSP().getPC()
    ordering = pc.getFactorMatrix().getMumpsIcntl(7)
    t1 = time.perf_counter()
    pep.solve()
    t2, c2 = time.perf_counter(), time.process_time()
    lams = np.array([pep.getEigenpair(i) for i in range(pep.getConverged())])
    omega = np.sort(lams.imag[lams.imag > 0])[:nev]
    for obj in (pep, K, G, M):
        obj.destroy()
    return {"setup": t1 - t0, "solve": t2 - t1, "cpu": c2 - c0, "omega": omega.tolist(),
            "converged": int(len(lams)), "mumps_ordering": int(ordering)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("matrices")
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--nev", type=int, default=6)
    ap.add_argument("--tol", type=float, default=1e-8)
    args = ap.parse_args()
    data = np.load(args.matrices)
    target = float(data["target"])
    rounds = [solve_once(data, args.nev, args.tol, target) for _ in range(args.rounds)]
    print(json.dumps({"rounds": rounds, "petsc": PETSc.Sys.getVersion(),
                      "slepc": SLEPc.Sys.getVersion()}))


if __name__ == "__main__":
    main()
