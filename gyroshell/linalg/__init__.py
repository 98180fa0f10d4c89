"""Sparse linear algebra that knows nothing about tapes: LU back-ends, CHOLMOD Cholesky,
inertia counts, the quadratic (gyroscopic) eigenproblem solver returning plain arrays, and
the generic bound-constrained Newton (:mod:`.newton`) with its continuation driver
(:mod:`.continuation`).
"""
