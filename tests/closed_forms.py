"""Independent exact solutions the discrete model is checked against (continuous PDE).

* Navier: a plate simply supported on all four sides under p sin(αx) sin(βy).
* Beam on an elastic foundation with tension: width-uniform solution for ν = 0 and a load
  uniform across the width.
* Lévy: simply supported ends, free lateral edges, any ν, a load p sin(αx) uniform across
  the width: w = Y(y) sin(αx), Y from a 4th-order ODE with the free-edge conditions.
* Orthotropic plates, the bending stiffnesses D = (D11, D22, D12, D66) (N·m) given as
  numbers, H = D12 + 2 D66: Navier frequencies and series (all sides simply supported); the
  Lévy solution with free lateral edges, D22 Y⁗ − 2Hα²Y″ + λY = q with D22 Y″ − D12α²Y = 0
  and D22 Y‴ − (D12 + 4D66)α²Y′ = 0 at the edges: the static profile, the eigenvalues
  ℓ = D11α⁴ − λ of the free-free cross-width problem (roots of its determinant) and the
  divergence μ of the lowest branch.
* The dry tensioned plate D w'''' − T w'' = 0 over a flat land between two corners: on two
  point supports; touching two rounded corners' arcs at one tangent point each; lying on
  part of each arc (a wrapped arc: the contact ends where w'' reaches the arc's −1/r_c).
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

from gyroshell import TapeParameters


def navier_static(p: TapeParameters, velocity: float, m: int, n: int) -> float:
    """Amplitude of w = W sin(mπx/L_x) sin(nπy/L_y) under a unit-amplitude pressure, m/Pa."""
    a, b = m * np.pi / p.length, n * np.pi / p.width
    S = p.tension - p.density * velocity**2
    return 1.0 / (p.D * (a**2 + b**2) ** 2 + S * a**2 + p.k)


def navier_frequency(p: TapeParameters, m: int, n: int) -> float:
    """V = 0 natural frequency of the all-sides simply supported shell, rad/s."""
    a, b = m * np.pi / p.length, n * np.pi / p.width
    return float(np.sqrt((p.D * (a**2 + b**2) ** 2 + p.tension * a**2 + p.k) / p.density))


def beam_on_foundation(p: TapeParameters, velocity: float, m: int) -> float:
    """Amplitude of the width-uniform w = W sin(αx) under unit pressure sin(αx), m/Pa."""
    a = m * np.pi / p.length
    return 1.0 / (p.D * a**4 + (p.tension - p.density * velocity**2) * a**2 + p.k)


def levy_profile(p: TapeParameters, velocity: float, m: int, y: np.ndarray) -> np.ndarray:
    """Y(y) of w = Y(y) sin(mπx/L_x) under unit pressure sin(mπx/L_x), free edges, m/Pa.

    D(Y'''' − 2α²Y'' + α⁴Y) + (T − ρV²)α²Y + kY = 1 on 0 < y < L_y with zero moment
    Y'' − να²Y = 0 and zero Kirchhoff shear Y''' − (2 − ν)α²Y' = 0 at y = 0, L_y.
    """
    a, D, nu = m * np.pi / p.length, p.D, p.poisson
    S = p.tension - p.density * velocity**2
    Yp = 1.0 / (D * a**4 + S * a**2 + p.k)
    beta = np.sqrt(complex((S * a**2 + p.k) / D))
    r = np.sqrt(np.array([a**2 + 1j * beta, a**2 - 1j * beta]))
    roots = np.concatenate([r, -r])
    rows, rhs = [], []
    for edge in (-p.width / 2, p.width / 2):
        e = np.exp(roots * edge)
        rows.append(e * (roots**2 - nu * a**2))
        rhs.append(nu * a**2 * Yp)
        rows.append(e * (roots**3 - (2 - nu) * a**2 * roots))
        rhs.append(0.0)
    c = np.linalg.solve(np.array(rows), np.array(rhs, dtype=complex))
    return (Yp + np.exp(np.outer(np.asarray(y) - p.width / 2, roots)) @ c).real


def moving_line_load(p: TapeParameters, velocity: float, load_speed: float, damping: float,
                     exponent: float, xi: np.ndarray, *, points: int = 200_001) -> np.ndarray:
    """Steady deflection W(ξ), ξ = x − U t, m, of the infinite beam on the shell foundation
    under a line load P_0 exp(−α ξ²) (uniform across the width, ν = 0) moving at U, tape at V.

    In the load's frame D W'''' + (ρ(V − U)² − T) W'' − c U W' + k W = p(ξ) (lab-frame
    viscous damping c), so by Fourier transform (Frýba's moving-load solution)

        W(ξ) = (1/π) ∫₀^∞ Re[ p̂(κ) e^{iκξ} / (Dκ⁴ − (ρ(V−U)² − T)κ² − i c U κ + k) ] dκ,

    p̂(κ) = P_0 √(π/α) exp(−κ²/4α); evaluated by the trapezoid rule on [0, 13√α] (the
    integrand is smooth and p̂ is below 1e-18 of its peak beyond).
    """
    kappa = np.linspace(0.0, 13.0 * np.sqrt(exponent), points)
    s = p.density * (velocity - load_speed) ** 2 - p.tension
    den = p.D * kappa**4 - s * kappa**2 + p.k - 1j * damping * load_speed * kappa
    p_hat = p.load * np.sqrt(np.pi / exponent) * np.exp(-kappa**2 / (4 * exponent))
    g = p_hat / den
    dk = kappa[1] - kappa[0]
    out = np.empty(len(np.atleast_1d(xi)))
    for i, x in enumerate(np.atleast_1d(xi)):
        f = (g * np.exp(1j * kappa * x)).real
        out[i] = dk * (f.sum() - 0.5 * (f[0] + f[-1])) / np.pi
    return out


# ----- orthotropic plates ------------------------------------------------------------------
def orthotropic_symbol(D, alpha, beta):
    """D11 α⁴ + 2(D12 + 2 D66) α²β² + D22 β⁴, N/m³ per m: the bending of sin(αx) sin(βy)."""
    d11, d22, d12, d66 = D
    return d11 * alpha**4 + 2 * (d12 + 2 * d66) * alpha**2 * beta**2 + d22 * beta**4


def orthotropic_navier_frequency(D, p: TapeParameters, m: int, n: int) -> float:
    """V = 0 frequency of the all-sides simply supported orthotropic shell, rad/s:
    ρω² = D11 α⁴ + 2(D12 + 2D66) α²β² + D22 β⁴ + Tα² + k."""
    a, b = m * np.pi / p.length, n * np.pi / p.width
    return float(np.sqrt((orthotropic_symbol(D, a, b) + p.tension * a**2 + p.k) / p.density))


def orthotropic_navier_uniform(D, p: TapeParameters, velocity: float, x, y,
                               terms: int = 201) -> np.ndarray:
    """w(x, y), m, of the simply supported orthotropic shell under a unit uniform pressure:
    Σ over odd m, n of 16 / (π² m n) sin(αx) sin(βy) / (symbol + (T − ρV²)α² + k)."""
    S = p.tension - p.density * velocity**2
    odd = np.arange(1, terms + 1, 2)
    a, b = odd * np.pi / p.length, odd * np.pi / p.width
    A, B = np.meshgrid(a, b, indexing="ij")
    coef = 16.0 / (np.pi**2 * np.outer(odd, odd)) / (orthotropic_symbol(D, A, B)
                                                     + S * A**2 + p.k)
    return np.sin(np.outer(x, a)) @ coef @ np.sin(np.outer(b, y))


def _levy_exponents(D, alpha: float, lam: float) -> np.ndarray:
    """(r₁, r₂) with Y = e^{±r y} solving D22 r⁴ − 2Hα² r² + λ = 0, H = D12 + 2 D66."""
    d11, d22, d12, d66 = D
    h = (d12 + 2 * d66) * alpha**2
    disc = np.sqrt(complex(h * h - d22 * lam))
    return np.sqrt(np.array([h + disc, h - disc]) / d22)


def levy_profile_orthotropic(D, p: TapeParameters, velocity: float, alpha: float,
                             y: np.ndarray) -> np.ndarray:
    """Y(y), m/Pa, of w = Y(y) sin(αx) under the pressure sin(αx) with free edges:
    D22 Y⁗ − 2Hα²Y″ + (D11α⁴ + (T − ρV²)α² + k) Y = 1, D22 Y″ − D12α²Y = 0 and
    D22 Y‴ − (D12 + 4D66)α²Y′ = 0 at y = 0, L_y."""
    d11, d22, d12, d66 = D
    lam = d11 * alpha**4 + (p.tension - p.density * velocity**2) * alpha**2 + p.k
    Yp = 1.0 / lam
    roots = _levy_exponents(D, alpha, lam)
    roots = np.concatenate([roots, -roots])
    rows, rhs = [], []
    for edge in (-p.width / 2, p.width / 2):
        e = np.exp(roots * edge)
        rows.append(e * (d22 * roots**2 - d12 * alpha**2))
        rhs.append(d12 * alpha**2 * Yp)
        rows.append(e * (d22 * roots**3 - (d12 + 4 * d66) * alpha**2 * roots))
        rhs.append(0.0)
    c = np.linalg.solve(np.array(rows), np.array(rhs, dtype=complex))
    return (Yp + np.exp(np.outer(np.asarray(y) - p.width / 2, roots)) @ c).real


def levy_condition(D, alpha: float, width: float, lam: float, symmetric: bool) -> float:
    """A real function of λ whose zeros are the free-free cross-width modes of
    D22 Y⁗ − 2Hα²Y″ + λY = 0 (even or odd about the centre line).

    The 2 × 2 determinant of the two edge conditions on the even (cosh rs) or odd
    (sinh rs / r) solutions, divided by r₁² − r₂² (so that the double root is no spurious
    zero) and by exp((|Re r₁| + |Re r₂|) b), b = width/2 (no overflow): real, continuous.
    """
    d11, d22, d12, d66 = D
    b = width / 2
    r = _levy_exponents(D, alpha, lam)
    moment = d22 * r**2 - d12 * alpha**2
    shear = d22 * r**2 - (d12 + 4 * d66) * alpha**2
    if symmetric:
        m, s = np.cosh(r * b) * moment, r * np.sinh(r * b) * shear
    else:
        small = np.abs(r) < 1e-300
        sinhc = np.where(small, b, np.sinh(r * b) / np.where(small, 1.0, r))
        m, s = sinhc * moment, np.cosh(r * b) * shear
    det = (m[0] * s[1] - m[1] * s[0]) / (r[0] ** 2 - r[1] ** 2)
    return float((det * np.exp(-np.abs(r.real).sum() * b)).real)


def _root(f, lo: float, hi: float) -> float:
    return brentq(f, lo, hi, xtol=1e-15 * abs(hi), rtol=1e-14)


def levy_eigenvalues(D, alpha: float, width: float, top: float, *, points: int = 4000
                     ) -> np.ndarray:
    """Eigenvalues ℓ < ``top`` (N/m³ per m) of the free-free cross-width bending operator
    D22 Y⁗ − 2Hα²Y″ + D11α⁴Y = ℓY (λ = D11α⁴ − ℓ), even and odd modes, sorted.

    Every ℓ >= (D11 − D12²/D22)α⁴ (the energy density is at least that times w_xx²), so
    the scan starts there; roots are bracketed on ``points`` steps and refined by brentq.
    """
    d11, d22, d12, _ = D
    grid = np.linspace((d11 - d12 * d12 / d22) * alpha**4 * (1 - 1e-9), top, points)
    out = []
    for symmetric in (True, False):
        def f(ell, s=symmetric):
            return levy_condition(D, alpha, width, d11 * alpha**4 - ell, s)
        values = np.array([f(ell) for ell in grid])
        for i in np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0):
            out.append(_root(f, grid[i], grid[i + 1]))
    return np.sort(out)


def levy_lowest(D, alpha: float, width: float) -> float:
    """The lowest eigenvalue ℓ₁ of the free-free cross-width operator (the even mode next to
    Y = 1), in [(D11 − D12²/D22)α⁴, D11α⁴]: the lowest Lévy branch (D11α⁴ for D12 = 0)."""
    d11, d22, d12, _ = D
    if d12 == 0:
        return d11 * alpha**4
    lo, hi = (d11 - d12 * d12 / d22) * alpha**4 * (1 - 1e-12), d11 * alpha**4 * (1 - 1e-15)

    def f(ell):
        return levy_condition(D, alpha, width, d11 * alpha**4 - ell, True)

    assert f(lo) * f(hi) < 0, "the lowest Levy root is not bracketed"
    return _root(f, lo, hi)


def levy_divergence_mu(D, p: TapeParameters, alphas) -> float:
    """μ_min = min over the axial wavenumbers α of (ℓ₁(α) + k)/α², N/m: K(V) of the
    free-edged tape turns singular at ρV² − T = μ_min (the lowest Lévy branch at ω = 0)."""
    return float(min((levy_lowest(D, a, p.width) + p.k) / a**2 for a in alphas))


def tensioned_plate_on_two_supports(ends, contacts, lam: float, end_heights, contact_heights,
                                    tension: float):
    """The exact tensioned plate D w'''' − T w'' = 0 (λ = √(D/T), m) on [e₀, e₁] = ``ends``,
    pinned at its ends (w given by ``end_heights``, w'' = 0) and resting on two point
    supports x₁ < x₂ (``contacts``) at heights ``contact_heights`` (m), w' and w''
    continuous through them.

    On each of the three pieces [x₀, xₑ], w = c₁ + c₂ (x − x₀) + c₃ e^{(x − xₑ)/λ}
    + c₄ e^{−(x − x₀)/λ}: twelve constants from four end and eight support conditions.
    Returns (evaluate(x, d): the d-th derivative of w at x, (F₁, F₂): the supports' point
    forces D [w'''] in N/m)."""
    (e0, e1), (x1, x2) = ends, contacts
    pieces = [(e0, x1), (x1, x2), (x2, e1)]

    def basis(x, k, d):
        """d-th derivative of the four basis functions of piece k at x."""
        x0, xe = pieces[k]
        x = np.asarray(x, dtype=float)
        one, zero = np.ones_like(x), np.zeros_like(x)
        grow, decay = np.exp((x - xe) / lam), np.exp(-(x - x0) / lam)
        lin = [one, x - x0] if d == 0 else ([zero, one] if d == 1 else [zero, zero])
        return np.array(lin + [grow / lam**d, (-1) ** d * decay / lam**d])

    rows, rhs = [], []

    def condition(x, k, d, value, other=None):
        row = np.zeros(12)
        row[4 * k:4 * k + 4] = basis(x, k, d)
        if other is not None:
            row[4 * other:4 * other + 4] -= basis(x, other, d)
        rows.append(row)
        rhs.append(value)

    for x, k, height in ((e0, 0, end_heights[0]), (e1, 2, end_heights[1])):
        condition(x, k, 0, height)
        condition(x, k, 2, 0.0)
    for x, left, height in ((x1, 0, contact_heights[0]), (x2, 1, contact_heights[1])):
        condition(x, left, 0, height)
        condition(x, left + 1, 0, height)
        condition(x, left, 1, 0.0, left + 1)
        condition(x, left, 2, 0.0, left + 1)
    c = np.linalg.solve(np.array(rows), np.array(rhs)).reshape(3, 4)

    def evaluate(x, d):
        x = np.asarray(x, dtype=float)
        k = np.where(x < x1, 0, np.where(x <= x2, 1, 2))
        out = np.zeros_like(x)
        for j in range(3):
            on = k == j
            if on.any():
                out[on] = (c[j][:, None] * basis(x[on], j, d)).sum(axis=0)
        return out

    D = lam * lam * tension
    forces = tuple(D * float(np.sum(c[k + 1] * basis(x, k + 1, 3)) - np.sum(c[k] * basis(x, k, 3)))
                   for k, x in enumerate((x1, x2)))
    return evaluate, forces


def tensioned_plate_wrapping_two_arcs(ends, end_heights, arcs, lam: float, sigma: float,
                                      tension: float, start, *, tol: float = 1e-15):
    """The exact tensioned plate D w'''' − T w'' = 0 (λ = √(D/T), m) on [e₀, e₁] = ``ends``,
    pinned at its ends (w given by ``end_heights``, w'' = 0), lying σ above two convex arcs
    over parts [a₁, b₁], [a₂, b₂] of them (a₁ < b₁ < a₂ < b₂) and free elsewhere.

    ``arcs`` holds two callables ``arc(x, d)``: the d-th derivative (d = 0, 1, 2) of the
    head's height on each arc (a parabola of curvature −1/r_c: the small-slope circle).
    On the contacts w = z_h + σ, so w'' = −1/r_c and w'''' = 0: the contact pressure is
    q = D w'''' − T w'' = T/r_c (Pa), uniform. On the three free pieces w = c₁ + c₂(x − x₀)
    + c₃e^{(x − xₑ)/λ} + c₄e^{−(x − x₀)/λ}; for given contact ends the twelve constants
    follow from the four end conditions and w, w' matching the arc at the four contact
    ends (linear). The ends themselves make w'' continuous there as well, w''(end) =
    z_h''(end) (four equations, solved by Newton from ``start`` = (a₁, b₁, a₂, b₂)); w'''
    jumps at each end: a point force D[w'''] (N/m).

    Returns (height(x): w at x (the arc + σ on the contacts), the contact ends (a₁, b₁,
    a₂, b₂), the four end point forces (N/m), the uniform pressure's two integrals
    T(b_k − a_k)/r_c (N/m) as the callable arcs' curvature times −T).
    """
    e0, e1 = ends
    D = lam * lam * tension

    def pieces(c):
        return [(e0, c[0]), (c[1], c[2]), (c[3], e1)]

    def basis(p, x, d):
        x0, xe = p
        grow, decay = np.exp((x - xe) / lam), np.exp(-(x - x0) / lam)
        lin = [1.0, x - x0] if d == 0 else ([0.0, 1.0] if d == 1 else [0.0, 0.0])
        return np.array(lin + [grow / lam**d, (-1) ** d * decay / lam**d])

    # (piece, contact end, arc) for the four contact ends
    touching = [(0, 0, 0), (1, 1, 0), (1, 2, 1), (2, 3, 1)]

    def constants(c):
        ps = pieces(c)
        rows, rhs = [], []

        def condition(k, x, d, value):
            row = np.zeros(12)
            row[4 * k:4 * k + 4] = basis(ps[k], x, d)
            rows.append(row)
            rhs.append(value)

        for k, x, height in ((0, e0, end_heights[0]), (2, e1, end_heights[1])):
            condition(k, x, 0, height)
            condition(k, x, 2, 0.0)
        for k, j, a in touching:
            condition(k, c[j], 0, arcs[a](c[j], 0) + sigma)
            condition(k, c[j], 1, arcs[a](c[j], 1))
        return np.linalg.solve(np.array(rows), np.array(rhs)).reshape(3, 4)

    def residual(c):
        coef, ps = constants(c), pieces(c)
        return np.array([coef[k] @ basis(ps[k], c[j], 2) - arcs[a](c[j], 2)
                         for k, j, a in touching])

    c = np.array(start, dtype=float)
    scale = max(abs(e1 - e0), 1e-30)
    for _ in range(100):
        r = residual(c)
        step = 1e-7 * scale
        J = np.column_stack([(residual(c + step * e) - r) / step for e in np.eye(4)])
        dc = np.linalg.solve(J, -r)
        c = c + dc
        if np.max(np.abs(dc)) < tol * scale:
            break
    else:
        raise RuntimeError("the wrapped plate's contact ends did not converge")
    if not (e0 < c[0] < c[1] < c[2] < c[3] < e1):
        raise RuntimeError(f"the contact ends {c} are not ordered: the tape does not wrap "
                           "both arcs")
    coef, ps = constants(c), pieces(c)

    def height(x):
        x = np.asarray(x, dtype=float)
        out = np.empty_like(x)
        free = [(x <= c[0]), (x >= c[1]) & (x <= c[2]), (x >= c[3])]
        for k, on in enumerate(free):
            out[on] = np.array([coef[k] @ basis(ps[k], xi, 0) for xi in x[on]])
        for j, a in ((0, 0), (2, 1)):
            on = (x > c[j]) & (x < c[j + 1])
            out[on] = arcs[a](x[on], 0) + sigma
        return out

    forces = tuple(D * (-(coef[k] @ basis(ps[k], c[j], 3)) if j % 2 == 0
                        else coef[k] @ basis(ps[k], c[j], 3))
                   for k, j, _ in touching)
    spread = tuple(-tension * arcs[a](0.5 * (c[j] + c[j + 1]), 2) * (c[j + 1] - c[j])
                   for j, a in ((0, 0), (2, 1)))
    return height, tuple(c), forces, spread


def plate_over_rounded_land(L, S, t_in, t_out, lam, sigma, r, phi, tension):
    """The exact tape at the tension T = ``tension`` (N/m) (w, corner forces D[w'''] in
    N/m, contact points x₁, x₂ in m) over a land [−L/2, L/2] at height 0 whose corners
    are arcs of radius r (parabolas, small slopes) reaching r φ/2 either side of the
    corner points, spans pinned at
    x = −L/2 − S and L/2 + S on the dry string (the arcs' tangent lines of slopes
    +t_in, −t_out) with w'' = 0 there.

    For given contacts the 12 constants of c₁ + c₂(x − x₀) + c₃e^{(x − x₁)/λ} + c₄e^{−(x −
    x₀)/λ} per piece follow from a linear system; the contacts from the tangency, by the
    fixed point x_k ← the arc's point of slope w'(x_k) (a contraction: r |w''| ≪ 1)."""
    a, b = -L / 2, L / 2
    lead, trail = a + 0.5 * r * phi, b - 0.5 * r * phi      # the land's tangent points

    def arc(x, k):           # (z_h, z_h') on the arc of corner k (0 leading, 1 trailing)
        d = lead - x if k == 0 else x - trail
        return -d * d / (2 * r), (d / r if k == 0 else -d / r)

    # the dry string's end heights: the tangent line of slope t at d = r t on each arc
    z_left = -r * t_in**2 / 2 + t_in * ((a - S) - (lead - r * t_in))
    z_right = -r * t_out**2 / 2 - t_out * ((b + S) - (trail + r * t_out))

    def solve(x1, x2):
        return tensioned_plate_on_two_supports(
            (a - S, b + S), (x1, x2), lam, (z_left, z_right),
            (arc(x1, 0)[0] + sigma, arc(x2, 1)[0] + sigma), tension)

    x1, x2 = lead - r * t_in / 2, trail + r * t_out / 2
    for _ in range(50):
        evaluate, forces = solve(x1, x2)
        s1, s2 = evaluate(np.array([x1, x2]), 1)
        new = (lead - r * s1, trail - r * s2)       # slope s at d = r s (lead), −r s (trail)
        moved = max(abs(new[0] - x1), abs(new[1] - x2))
        x1, x2 = new
        if moved < 1e-16:
            break
    evaluate, forces = solve(x1, x2)
    return (lambda x: evaluate(x, 0)), forces, (x1, x2)
