"""Sparse linear algebra that knows nothing about tapes: LU back-ends, CHOLMOD Cholesky,
inertia counts, and the quadratic (gyroscopic) eigenproblem solver returning plain arrays.
"""
