"""Alternatives to the eigen-solver's SuperLU + single-vector Lanczos, measured (L_x/L_y = 19).

    PYTHONPATH=. python benchmarks/bench_factor_eval.py [--rounds 5]

Q(iω_s) = K − ω_s²M + iω_sG at V = 50 m/s, ω_s just below the lowest frequency. Prints
medians over rounds (ms) of:

* SuperLU (symmetric mode, as :mod:`gyroshell.linalg.inertia`): factorization, one substitution,
  and the cost per vector of a 2/3/4/6-column substitution;
* MKL PARDISO through a small ctypes binding (needs ``pip install mkl``; skipped without):
  complex Hermitian indefinite (mtype −4) with 1×1 pivots, whose pivots give the inertia
  (checked against SuperLU's count), and the real symmetric 2n embedding
  [[K − ω²M, −ωG], [ωG, K − ω²M]] (mtype −2);
* the solves a block Krylov (Lanczos) method in the energy inner product needs for the 6
  lowest frequencies to the default accuracy at block sizes 1, 2, 3, 4, 6 (full
  reorthogonalization, no restart).

The eigen-solver keeps SuperLU and single-vector Lanczos unless these numbers say otherwise.
"""

from __future__ import annotations

import argparse
import ctypes
import glob
import os
import statistics
import sys
import time

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

from gyroshell import TapeModel, TapeParameters
from gyroshell.core.parallel import blas_threads
from gyroshell.engines.eigen import modes
from gyroshell.linalg.inertia import factor_inertia


def mkl():
    for name in sorted(glob.glob(os.path.join(sys.prefix, "lib", "libmkl_rt.so*"))):
        try:
            lib = ctypes.CDLL(name)
            lib.MKL_Set_Num_Threads(ctypes.c_int(1))
            return lib
        except (OSError, AttributeError):
            continue
    return None


class Pardiso:
    """Minimal PARDISO LDLᴴ (1x1 pivots) of a Hermitian/symmetric matrix; ``negatives``."""

    def __init__(self, lib, A: sp.spmatrix) -> None:
        U = sp.triu(sp.csr_matrix(A), format="csr")
        U.sort_indices()
        self.lib, self.n = lib, U.shape[0]
        self.dtype = np.complex128 if np.iscomplexobj(U.data) else np.float64
        self.mtype = -4 if self.dtype == np.complex128 else -2
        self.a = np.ascontiguousarray(U.data, dtype=self.dtype)
        self.ia = U.indptr.astype(np.int32)
        self.ja = U.indices.astype(np.int32)
        self.pt = np.zeros(64, np.int64)
        self.ip = np.zeros(64, np.int32)
        for k, v in {0: 1, 1: 2, 9: 8, 17: -1, 20: 0, 34: 1, 55: 1}.items():
            self.ip[k] = v   # own values, METIS, perturb 1e-8, report fill, 1x1, 0-based, diag
        self.call(12, np.zeros(1, self.dtype), np.zeros(1, self.dtype), 1)
        d = np.zeros(self.n, self.dtype)
        da = np.zeros(self.n, self.dtype)
        err = ctypes.c_int32(0)
        lib.pardiso_getdiag(self.ptr(self.pt), self.ptr(d), self.ptr(da),
                            ctypes.byref(ctypes.c_int32(1)), ctypes.byref(err))
        self.negatives = int(np.count_nonzero(d.real < 0)) if self.ip[13] == 0 else None

    @staticmethod
    def ptr(x):
        return x.ctypes.data_as(ctypes.c_void_p)

    def call(self, phase, b, x, nrhs):
        i32 = ctypes.c_int32
        err = i32(0)
        self.lib.pardiso(self.ptr(self.pt), ctypes.byref(i32(1)), ctypes.byref(i32(1)),
                         ctypes.byref(i32(self.mtype)), ctypes.byref(i32(phase)),
                         ctypes.byref(i32(self.n)), self.ptr(self.a), self.ptr(self.ia),
                         self.ptr(self.ja), None, ctypes.byref(i32(nrhs)), self.ptr(self.ip),
                         ctypes.byref(i32(0)), self.ptr(b), self.ptr(x), ctypes.byref(err))
        if err.value:
            raise RuntimeError(f"PARDISO phase {phase}: error {err.value}")

    def solve(self, b):
        b = np.asfortranarray(b, dtype=self.dtype)
        x = np.empty_like(b, order="F")
        self.call(33, b, x, 1 if b.ndim == 1 else b.shape[1])
        return x

    def release(self):
        self.call(-1, np.zeros(1, self.dtype), np.zeros(1, self.dtype), 1)


def timed(f, repeat=1):
    t0 = time.perf_counter()
    for _ in range(repeat):
        out = f()
    return (time.perf_counter() - t0) / repeat, out


def block_krylov_solves(model, velocity, factor, omega_s, p, reference, tol=1e-14, nev=6):
    """Solves a block Krylov method (block size p) needs for ``nev`` Ritz pairs of T."""
    n = model.unknowns
    md = model.mass_diagonal
    K, G = model.K(velocity).tocsr(), model.G(velocity).tocsr()

    def L(Z):
        return np.concatenate([md[:, None] * Z[:n], K @ Z[n:]])

    def T(Z):
        b = factor.solve(np.asfortranarray(md[:, None] * (Z[:n] + 1j * omega_s * Z[n:])
                                           + G @ Z[n:]))
        return np.concatenate([1j * (Z[n:] - 1j * omega_s * b), -1j * b])

    mmax = 120
    V = np.empty((2 * n, mmax + p), complex)
    H = np.zeros((mmax + p, mmax), complex)
    W = np.random.default_rng(1).standard_normal((2 * n, p)).astype(complex)
    R = la.cholesky(W.conj().T @ L(W))
    V[:, :p] = la.solve_triangular(R, W.T, trans="T").T
    k = solves = 0
    while k + p <= mmax:
        W = T(V[:, k:k + p])
        solves += p
        B = V[:, :k + p]
        for _ in range(2):
            c = B.conj().T @ L(W)
            W -= B @ c
            H[:k + p, k:k + p] += c
        Gm = W.conj().T @ L(W)
        R = la.cholesky(0.5 * (Gm + Gm.conj().T))
        V[:, k + p:k + 2 * p] = la.solve_triangular(R, W.T, trans="T").T
        H[k + p:k + 2 * p, k:k + p] = R
        k += p
        theta, S = la.eigh(0.5 * (H[:k, :k] + H[:k, :k].conj().T))
        best = np.argsort(-np.abs(theta))[:nev]
        if np.all(np.linalg.norm(R @ S[k - p:k, best], axis=0) <= tol * np.abs(theta[best])):
            break
    omega = np.sort(omega_s + 1 / theta[best])
    return solves, float(np.max(np.abs(omega - reference) / reference))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    model = TapeModel(TapeParameters(length_ratio=19.0))
    velocity = 50.0
    ref = modes(model, velocity, 6)
    omega_s = abs(ref.info["shift"])
    K, G, M = model.K(velocity), model.G(velocity), sp.diags(model.mass_diagonal)
    Q = (K - omega_s**2 * M + 1j * omega_s * G).tocsr()
    A, Bm = K - omega_s**2 * M, omega_s * G
    E = sp.bmat([[A, -Bm], [Bm, A]]).tocsr()
    n = Q.shape[0]
    rng = np.random.default_rng(0)
    b = rng.standard_normal(n) + 1j * rng.standard_normal(n)
    lib = mkl()
    rows: dict[str, list[float]] = {}

    def add(key, value):
        rows.setdefault(key, []).append(1e3 * value)

    with blas_threads(1):
        for _ in range(args.rounds):
            t, slu = timed(lambda: factor_inertia(Q))
            add("SuperLU factor", t)
            add("SuperLU solve, 1 vector", timed(lambda s=slu: s.solve(b), 10)[0])
            for k in (2, 3, 4, 6):
                X = np.asfortranarray(np.repeat(b[:, None], k, axis=1))
                add(f"SuperLU solve, per vector of {k}",
                    timed(lambda s=slu, x=X: s.solve(x), 3)[0] / k)
            if lib is not None:
                t, par = timed(lambda: Pardiso(lib, Q))
                add("PARDISO Hermitian factor", t)
                add("PARDISO Hermitian solve, 1 vector", timed(lambda s=par: s.solve(b), 10)[0])
                X = np.repeat(b[:, None], 6, axis=1)
                add("PARDISO Hermitian solve, per vector of 6",
                    timed(lambda s=par, x=X: s.solve(x), 3)[0] / 6)
                assert par.negatives == slu.negatives, (par.negatives, slu.negatives)
                par.release()
                t, emb = timed(lambda: Pardiso(lib, E))
                add("PARDISO real 2n embedding factor", t)
                bb = np.concatenate([b.real, b.imag])
                add("PARDISO real 2n embedding solve", timed(lambda s=emb, x=bb: s.solve(x), 10)[0])
                emb.release()
        print(f"Q(i omega_s) at V = {velocity:g} m/s, n = {n}; medians of {args.rounds} "
              f"rounds (ms); inertia counts agree: {slu.negatives} below the shift")
        for key, values in rows.items():
            print(f"  {key:45s} {statistics.median(values):8.2f}")
        if lib is None:
            print("  PARDISO: skipped (pip install mkl)")
        for p in (1, 2, 3, 4, 6):
            solves, err = block_krylov_solves(model, velocity, slu, omega_s, p, ref.omega)
            print(f"  block Krylov, block size {p}: {solves} solves for 6 modes "
                  f"(frequency difference {err:.1e})")


if __name__ == "__main__":
    main()
