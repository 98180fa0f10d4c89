"""The gyroscopic eigen-solver for any matrices, as a result: :func:`gyroscopic_modes`.

The numerical method is :func:`gyroshell.linalg.qep.solve_qep` (plain arrays, notes there);
this layer wraps its eigenpairs in a :class:`~gyroshell.results.modes.GyroscopicModes`.
"""

from __future__ import annotations

from ..linalg.qep import SolverOptions, solve_qep
from ..results.modes import GyroscopicModes

__all__ = ["GyroscopicModes", "SolverOptions", "gyroscopic_modes"]


def gyroscopic_modes(M, G, K, count: int = 6, *, sigma: complex | str | None = None,
                     C=None, estimate: float | None = None, definite: bool | None = None,
                     start=None, options: SolverOptions | None = None,
                     **tuning) -> GyroscopicModes:
    """Eigenpairs of (λ²M + λ(G + C) + K) φ = 0 nearest a shift on the imaginary axis.

    Parameters
    ----------
    M, G, K : array_like or scipy.sparse matrix, shape (n, n)
        Mass (symmetric positive definite, kg), gyroscopic (skew-symmetric, kg/s) and
        stiffness (symmetric, N/m) matrices. Checked and refused otherwise. ``K=0`` (or a
        zero matrix), undamped: λ = 0 is an n-fold eigenvalue and the others are those of
        −M⁻¹G; the result holds the ``count`` pairs +iμ of iGφ = μMφ nearest the shift
        (:mod:`gyroshell.linalg.qep.rigid`), ``info["zero_eigenvalues"]`` counts λ = 0.
    count : int
        Number of eigenvalue pairs, 1 <= count <= :func:`gyroshell.linalg.qep.max_count` (n).
    sigma : None, "auto", 0 or complex i·ω_s
        Shift, 1/s. None/"auto": i·ω_s just below ``estimate`` (moved down until the inertia
        of Q(iω_s) certifies at most ``count`` frequencies below it), or 0 without one.
    C : array_like or sparse matrix, optional
        Viscous damping, symmetric positive semi-definite, kg/s.
    estimate : float, optional
        Estimate of the lowest frequency, rad/s (undamped) or of the damped one.
    definite : bool, optional
        Whether K is known positive definite (skips its factorization); None: find out.
    start : tuple (eigenvalues, vectors), optional
        Previous eigenpairs (e.g. at a nearby speed) to start from.
    options : SolverOptions, optional
        The tuning knobs together (default :class:`~gyroshell.linalg.qep.SolverOptions`).
    **tuning
        Any knob of :class:`~gyroshell.linalg.qep.SolverOptions` by name, replacing the
        one in ``options``: ``tol`` (relative tolerance of the eigen-iteration), ``ncv``
        and ``maxiter`` (ARPACK's basis size and restarts; giving either selects ARPACK),
        ``method`` ({"auto", "lanczos", "arpack"}: the iteration of the undamped
        subcritical case; "auto" is Lanczos, ARPACK if it does not converge or if
        ncv/maxiter are given) and ``factorization`` ({"auto", "cholmod", "superlu"}: the
        factorization of the shift matrices Q(iω_s) and K; "cholmod" is CHOLMOD's
        supernodal Cholesky (cvxopt, the ``fast`` extra) wherever the matrix is positive
        definite, SuperLU's LDLᴴ otherwise and where the inertia count is needed;
        "superlu" is SuperLU only; "auto" follows
        :func:`gyroshell.linalg.factorization.resolve_factorization`).

    Returns
    -------
    GyroscopicModes

    Raises
    ------
    ParameterError
        Matrices without the structure, bad count, sigma or tol, a singular K at σ = 0.
    ConvergenceError
        The eigen-iteration did not converge, or residuals or the certified count failed.
    TypeError
        For a keyword that is neither an argument nor a knob.
    """
    pairs = solve_qep(M, G, K, count, sigma=sigma, C=C, estimate=estimate, definite=definite,
                      start=start, options=SolverOptions.of(options, **tuning))
    return GyroscopicModes(*pairs)
