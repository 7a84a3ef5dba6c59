# SPDX-License-Identifier: GPL-3.0-or-later
"""NURBS machinery for the solid model (Sec. 2, 3.2): vectorised B-spline basis functions, the
cubic B-spline that interpolates the key points (the middle control axis, Sec. 3.2.3), and the
general sweep of the control profiles along the axis with rotation-minimising frames.

The sweep surface SS(s, t) (Sec. 6) is a NURBS surface of degree 3 in s (along the axis) and
degree 2 in t (around it). Every cross-section profile - the bottom control circle, the middle
control ellipse and the tip control line (an ellipse with no minor axis) - is an affine image of
the 9-point rational quadratic unit circle, placed in the plane of a rotation-minimising frame
(double reflection, Wang et al. 2008, which computes the same frames as Maurer and Juttler's
construction cited by the paper, to O(h^4)). Sections at fixed stations along the axis are
skinned by cubic interpolation in s. Because the weights are constant along s, every row s of
the surface is itself an exact affine image of the unit circle: S(s, t) = c(s) + U(s) Cx(t) +
V(s) Cy(t). The engine evaluates that form with precomputed basis matrices; ``to_geomdl`` exports
the very same control net, and the tests check both against geomdl's own evaluation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .exact import matmul
from .frames import _NUMPY_2, diff, norm

# The 9-point rational quadratic unit circle (Piegl & Tiller, Ex. 7.2).
_W = np.sqrt(0.5)
CIRCLE_XY = np.array(
    [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1], [1, 0]], dtype=float
)
CIRCLE_W = np.array([1, _W, 1, _W, 1, _W, 1, _W, 1], dtype=float)
CIRCLE_KNOTS = np.array([0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1], dtype=float)
CIRCLE_DEGREE = 2


def bspline_basis(knots, degree: int, u) -> np.ndarray:
    """Dense B-spline basis matrix by the Cox-de Boor recursion, vectorised.

    knots: (..., K); u: (..., N) broadcastable on the leading axes. Returns (..., N, K-degree-1).
    The last knot is included in the last non-empty span (clamped knot vectors).
    """
    return bspline_bases(knots, degree, u)[-1]


def bspline_bases(knots, degree: int, u) -> list:
    """The basis matrices of every degree 0..degree of the recursion (see ``bspline_basis``).
    Degree d's functions 1..K-d-3 on ``knots`` are the degree-d basis on ``knots[..., 1:-1]``,
    the knot vector of the derivative curve (Piegl & Tiller Eq. 3.8), so one recursion gives a
    curve's points and tangents."""
    knots = np.asarray(knots, dtype=float)
    u = np.asarray(u, dtype=float)
    k = knots[..., None, :]
    uu = u[..., :, None]
    K = knots.shape[-1]
    basis = ((k[..., :-1] <= uu) & (uu < k[..., 1:])).astype(float)
    at_end = uu >= k[..., -1:]  # (there, no span holds u: the row is all zeros already)
    if at_end.any():
        last = K - degree - 2
        basis[..., last] = np.where(at_end[..., 0], 1.0, basis[..., last])
    spans = (k[..., d:] - k[..., : K - d] for d in range(1, degree + 1))
    spans = (np.where(den > 0, den, np.inf) for den in spans)  # x / inf = 0: 0/0 := 0
    return _raise_degree(basis, uu - k[..., :-1], k[..., 1:] - uu, spans)


def _raise_degree(basis, from_knot, to_knot, spans) -> list:
    """The Cox-de Boor recursion from the degree-0 ``basis`` (..., N, K - 1): ``from_knot`` and
    ``to_knot`` are u - k_j and k_j - u, each computed once, and ``spans`` gives degree d's knot
    spans k_{j+d} - k_j for d = 1, 2, ..., inf where a span is empty (x / inf = 0: the
    recursion's 0/0 := 0; its left denominators are the first K - d - 1 of them, its right ones
    the last: the same numbers; issue 28). Every degree's basis, 0 first."""
    out = [basis]
    for d, den in enumerate(spans, start=1):
        left = from_knot[..., : from_knot.shape[-1] - d] / den[..., :-1]
        right = to_knot[..., d:] / den[..., 1:]
        basis = left * basis[..., :-1] + right * basis[..., 1:]
        out.append(basis)
    return out


def bspline_bases_one(knots: list, degree: int, u: list) -> list:
    """``bspline_bases`` of one knot vector and its parameters, given as lists of Python
    floats (the arrays (1, N, K - d - 1)): the knot spans and the parameters at the clamped end
    looked at on the floats, the same arrays made from them (fewer numpy calls: the brush's
    step; issue 28)."""
    k = np.array(knots)
    uu = np.array(u)[:, None]
    K = len(knots)
    basis = ((k[:-1] <= uu) & (uu < k[1:])).astype(float)
    end = knots[-1]
    at_end = [i for i, v in enumerate(u) if v >= end]
    if at_end:
        basis[at_end, K - degree - 2] = 1.0
    spans = (
        np.array([_span(knots[j + d] - knots[j]) for j in range(K - d)])
        for d in range(1, degree + 1)
    )
    return [b[None] for b in _raise_degree(basis, uu - k[:-1], k[1:] - uu, spans)]


def _span(x: float) -> float:
    """A knot span as the recursion divides by it: inf where it is not positive."""
    return x if x > 0.0 else math.inf


def averaged_knots(params, degree: int = 3) -> np.ndarray:
    """Knot vector by averaging (Piegl & Tiller Eq. 9.8); params (..., n) -> (..., n+degree+1)."""
    params = np.asarray(params, dtype=float)
    n = params.shape[-1]
    lead = params.shape[:-1]
    inner = n - degree - 1
    c = np.zeros(lead + (n + 1,))
    params.cumsum(axis=-1, out=c[..., 1:])
    # u_{j+p} = (1/p) * sum_{i=j}^{j+p-1} params_i, j = 1..n-p-1 (written in place between
    # the clamped ends: issue 28)
    knots = np.empty(lead + (n + degree + 1,))
    knots[..., : degree + 1] = 0.0
    knots[..., degree + 1 + inner :] = 1.0
    mid = c[..., 1 + degree : 1 + degree + inner] - c[..., 1 : 1 + inner]
    np.divide(mid, degree, out=knots[..., degree + 1 : degree + 1 + inner])
    return knots


def chord_params(points) -> np.ndarray:
    """Chord-length parameters in [0, 1] for (..., n, dim) points."""
    points = np.asarray(points, dtype=float)
    seg = norm(diff(points, axis=-2), axis=-1)
    seg = np.maximum(seg, 1e-9)
    c = np.zeros(points.shape[:-1])
    seg.cumsum(axis=-1, out=c[..., 1:])
    return c / c[..., -1:]


def chord_params_one(points: list) -> list:
    """``chord_params`` of one polyline (a list of [x, y, z]) on Python floats: the same
    operations in the same order (a length as sqrt((x^2 + y^2) + z^2), numpy's order; the
    running sum from the first length), without a numpy call each (issue 28)."""
    c = [0.0]
    px, py, pz = points[0]
    for x, y, z in points[1:]:
        dx, dy, dz = x - px, y - py, z - pz
        seg = math.sqrt(dx * dx + dy * dy + dz * dz)
        seg = seg if (seg > 1e-9 or seg != seg) else 1e-9  # np.maximum(seg, 1e-9)
        c.append(seg if len(c) == 1 else c[-1] + seg)
        px, py, pz = x, y, z
    last = c[-1]
    return [v / last for v in c]


def averaged_knots_one(params: list, degree: int = 3) -> list:
    """``averaged_knots`` of one list of parameters on Python floats (the same sums)."""
    c = [0.0]
    for v in params:
        c.append(v if len(c) == 1 else c[-1] + v)
    inner = len(params) - degree - 1
    mid = [(c[1 + degree + j] - c[1 + j]) / degree for j in range(inner)]
    return [0.0] * (degree + 1) + mid + [1.0] * (degree + 1)


def derivative_ctrl_one(ctrl: list, knots: list, degree: int) -> list:
    """The control points of ``derivative_ctrl`` of one curve (lists of rows) on Python
    floats (the same operations)."""
    out = []
    for i in range(len(ctrl) - 1):
        den = knots[degree + 1 + i] - knots[1 + i]
        den = den if den > 0 else 1.0
        a, b = ctrl[i], ctrl[i + 1]
        out.append([(degree * (v - w)) / den for v, w in zip(b, a, strict=True)])
    return out


def interpolate_cubic(points, params=None):
    """Global cubic B-spline interpolation of (..., n, dim) points, n >= 4 (Sec. 3.2.3: the
    middle control axis interpolates its key points). Returns (ctrl, knots, params)."""
    points = np.asarray(points, dtype=float)
    if params is None:
        params = chord_params(points)
    knots = averaged_knots(params, 3)
    N = bspline_basis(knots, 3, params)  # (..., n, n)
    ctrl = solve_collocation(N, points)
    return ctrl, knots, params


def solve_collocation(A, B):
    """Solve A X = B for stacks of B-spline collocation matrices (..., n, n), B (..., n, k).

    Collocation matrices are totally positive, so Gaussian elimination without pivoting is
    stable (de Boor); done here in numpy over the whole stack, it avoids LAPACK, whose threads
    cost more than the work itself on matrices this small (and fight each other in parallel
    worker processes), and whose kernels round differently from machine to machine. The
    matrix and the right-hand side are eliminated together, as one augmented matrix."""
    A = np.asarray(A, dtype=float)
    n = A.shape[-1]
    if A.ndim == 3 and A.shape[0] == 1:  # one system: the same steps on Python floats
        B = np.asarray(B, dtype=float)
        return np.array([solve_collocation_one(A[0], B[0])]).reshape(B.shape)
    M = np.concatenate([A, np.asarray(B, dtype=float)], axis=-1)  # (..., n, n + k)
    for k in range(n - 1):
        f = M[..., k + 1 :, k] / M[..., k, k, None]
        M[..., k + 1 :, k:] -= f[..., None] * M[..., k, None, k:]
    X = M[..., n:]
    for k in range(n - 1, -1, -1):
        X[..., k, :] /= M[..., k, k, None]
        if k:
            X[..., :k, :] -= M[..., :k, k, None] * X[..., k, None, :]
    return X


def solve_collocation_one(A: np.ndarray, B: np.ndarray) -> list:
    """``solve_collocation`` of one system, A (n, n) and B (n, k), on Python floats
    (``_solve_one``): the solution as a list of rows."""
    band = not (_negative_zero(A) or _negative_zero(B))
    return _solve_one(A.tolist(), B.tolist(), band)


_NEGATIVE_ZERO = 1 << 63  # the bits of -0.0 (float64)


def _negative_zero(a: np.ndarray) -> bool:
    """Whether any element of ``a`` is -0.0."""
    return bool((a.view(np.uint64) == _NEGATIVE_ZERO).any())  # its bits: the sign's alone


def _solve_one(A: list, B: list, band: bool = False) -> list:
    """``solve_collocation`` of one system on Python floats (lists of rows): the same
    operations in the same order, element by element, as the arrays' elimination, without a
    numpy call per step (issue 28). With ``band`` (the system holds no -0.0), a row whose
    multiplier is zero (outside a collocation matrix's band: a row's basis functions are the
    degree + 1 around its parameter) is left as it is, and so is a row of the solution that
    takes zero times another: subtracting a zero leaves every value as it was, and changes
    only -0.0 (to 0.0), which no step makes from a system without one (issue 28). For the
    same reason, with ``band`` a row takes a finite multiple of the pivot row only where the
    pivot row is not zero, and not in the pivot's own column (below the diagonal: no later
    step reads it)."""
    n = len(A)
    M = [a + b for a, b in zip(A, B, strict=True)]
    if band:
        return _solve_band(M, n)
    cols = range(len(M[0]))
    for k in range(n - 1):
        pivot = M[k]
        for i in range(k + 1, n):
            row = M[i]
            f = row[k] / pivot[k]
            for c in cols[k:]:
                row[c] -= f * pivot[c]
    return _back_substitute(M, n, band=False)


def _solve_band(M: list, n: int) -> list:
    """``_solve_one``'s elimination with ``band``, of the augmented rows M (changed in place):
    the same operations on the same numbers, in fewer Python steps (the pivot row's nonzero
    columns listed once it has a row to eliminate, a row of the solution updated in place)."""
    width = len(M[0])
    for k in range(n - 1):
        pivot = M[k]
        d = pivot[k]
        nonzero = None
        for i in range(k + 1, n):
            row = M[i]
            rk = row[k]
            if rk == 0.0:  # outside the band: nothing to subtract
                continue
            f = rk / d
            if f - f == 0.0:  # f finite: f * 0.0 is a zero
                if nonzero is None:
                    nonzero = [c for c in range(k + 1, width) if pivot[c] != 0.0]
                for c in nonzero:
                    row[c] -= f * pivot[c]
            else:
                for c in range(k, width):
                    row[c] -= f * pivot[c]
    return _back_substitute(M, n, band=True)


def _back_substitute(M: list, n: int, band: bool) -> list:
    """The solution of the eliminated augmented rows M (upper triangular in their first
    ``n`` columns), from the last row up. With ``band`` a row of the solution that would take
    zero times another is left as it is (``_solve_one``)."""
    X = [row[n:] for row in M]
    for k in range(n - 1, -1, -1):
        d = M[k][k]
        xk = X[k] = [v / d for v in X[k]]
        for i in range(k):
            mik = M[i][k]
            if band and mik == 0.0:
                continue
            X[i] = [v - mik * w for v, w in zip(X[i], xk, strict=True)]
    return X


def derivative_ctrl(ctrl, knots, degree: int):
    """Control points and knots of the derivative curve (Piegl & Tiller Eq. 3.8)."""
    k = knots
    den = k[..., degree + 1 : -1] - k[..., 1 : -degree - 1]
    den = np.where(den > 0, den, 1.0)
    q = degree * diff(ctrl, axis=-2) / den[..., None]
    return q, k[..., 1:-1]


_EYE3 = np.eye(3)
# np.einsum without its Python wrapper (with optimize off it calls this: the same sums; issue 28)
einsum = (np._core if _NUMPY_2 else np.core).multiarray.c_einsum


def _reflection_factors(c, out) -> None:
    """2 / c of reflections' squared vector lengths c into ``out`` (zeros), left 0 where the
    vector is about 0."""
    np.divide(2.0, c, out=out, where=c > 1e-18)


def _products(a, b, out=None):
    """``exact.matmul`` of stacks of matrices (..., n, k) @ (..., k, m), m > 1, without its
    checks (the same products and sums), into ``out`` when given (it may be ``a`` or ``b``:
    the products are all made before the sums are written)."""
    return np.add.reduce(a[..., :, :, None] * b[..., None, :, :], axis=-2, out=out)


def rotation_minimising_frames(points, tangents, r0):
    """Double-reflection RMF (Wang, Juttler, Zheng, Liu 2008). points, tangents: (m, N, 3);
    r0: (m, 3) initial normal, perpendicular to tangents[:, 0]. Returns normals (m, N, 3).

    Each step is two reflections, r_{i+1} = H2_i H1_i r_i, and the reflections depend only on
    the points and tangents: they are built for all steps at once, and so are their running
    products."""
    m, N, _ = points.shape
    # the two reflections' vectors and factors side by side, so that both are built in one
    # go (the same products as one at a time; issue 28)
    v = np.empty((2, m, N - 1, 3))
    f = np.zeros((2, m, N - 1))
    v1 = np.subtract(points[:, 1:], points[:, :-1], out=v[0])  # (m, N-1, 3)
    _reflection_factors(einsum("mik,mik->mi", v1, v1), f[0])
    t0 = tangents[:, :-1]
    tl = t0 - (f[0] * einsum("mik,mik->mi", v1, t0))[..., None] * v1
    v2 = np.subtract(tangents[:, 1:], tl, out=v[1])
    _reflection_factors(einsum("mik,mik->mi", v2, v2), f[1])
    H = _EYE3 - f[..., None, None] * v[..., :, None] * v[..., None, :]  # H1, H2
    P = _products(H[1], H[0])  # (m, N-1, 3, 3)
    # the running products M_i ... M_0 by doubling: log2(N) batched products, not N - 1 steps
    span = 1
    while span < N - 1:  # (the sums written over P's own later rows: no copy of them)
        _products(P[:, span:], P[:, :-span], out=P[:, span:])
        span *= 2
    out = np.empty_like(points)
    out[:, 0] = r0
    out[:, 1:] = einsum("mnij,mj->mni", P, np.asarray(r0, dtype=float))
    # against round-off: exactly perpendicular to the tangents and of unit length
    out -= einsum("mik,mik->mi", out, tangents)[..., None] * tangents
    out /= np.maximum(norm(out, axis=2), 1e-12)[..., None]
    return out


def circle_points(t) -> np.ndarray:
    """The unit rational circle evaluated at parameters t: (N, 2) with exact unit length."""
    B = bspline_basis(CIRCLE_KNOTS, CIRCLE_DEGREE, t)
    hw = matmul(B, CIRCLE_W)
    return matmul((B * CIRCLE_W), CIRCLE_XY) / hw[:, None]


@dataclass(frozen=True)
class SurfaceShape:
    """A NURBS surface's control points along the axis (u) and around it (v), and its orders
    (degree + 1) in each direction."""

    points_u: int
    points_v: int
    order_u: int
    order_v: int


class SweepLayout:
    """Fixed parameters of the sweep: station parameters along the axis, the s knot vector, the
    interpolation matrix and evaluation grids. Fixed, so every matrix is computed once."""

    def __init__(self, stations: int = 12, grid_s: int = 28, grid_t: int = 24):
        if grid_t % 8:
            raise ValueError("grid_t must be a multiple of 8 (symmetric sampling of the circle)")
        k = np.arange(stations) / (stations - 1)
        # denser near the tip, where the section shrinks to the tip control line
        self.station_u = 1.0 - (1.0 - k) ** 1.35
        self.knots_s = averaged_knots(self.station_u, 3)
        collocation = bspline_basis(self.knots_s, 3, self.station_u)
        # control rows = interp @ section rows: the inverse by the same elimination as
        # interpolate_cubic (no LAPACK: no BLAS workspace, the same bits on every machine)
        self.interp = solve_collocation(collocation, np.eye(stations))
        g = np.arange(grid_s) / (grid_s - 1)
        self.grid_s = 1.0 - (1.0 - g) ** 1.35
        self.grid_t = np.arange(grid_t) / grid_t  # periodic: t = 1 is t = 0
        # rows of the surface grid as combinations of the stations' sections
        self.row_from_station = matmul(bspline_basis(self.knots_s, 3, self.grid_s), self.interp)
        self.ring = circle_points(self.grid_t)  # (Nt, 2): Cx(t), Cy(t)

    @property
    def stations(self) -> int:
        return len(self.station_u)

    def bezier_net_shape(self) -> SurfaceShape:
        """Control points and orders of a primitive's surface in Bezier form (``bezier_form``
        along the axis, the rational circle around it): what a Blender NURBS surface holds."""
        spans = len(np.unique(self.knots_s)) - 1
        return SurfaceShape(3 * spans + 1, len(CIRCLE_W), 3 + 1, CIRCLE_DEGREE + 1)


def section_control_net(centres, U, V):
    """Homogeneous control net (..., Ms, 9, 4) of the sections c + U Cx + V Cy at the stations."""
    P = (
        centres[..., None, :]
        + CIRCLE_XY[:, 0, None] * U[..., None, :]
        + (CIRCLE_XY[:, 1, None] * V[..., None, :])
    )
    w = np.broadcast_to(CIRCLE_W[:, None], P.shape[:-1] + (1,))
    return np.concatenate([P * w, w], axis=-1)


def surface_control_net(layout: SweepLayout, centres, U, V):
    """Skin the station sections (Ms) into the sweep's NURBS control net (..., Ms, 9, 4)."""
    Pw = section_control_net(centres, U, V)
    return np.einsum("ij,...jkl->...ikl", layout.interp, Pw)


def evaluate_nurbs_surface(ctrlw, knots_u, deg_u, knots_v, deg_v, u, v) -> np.ndarray:
    """Full rational evaluation at parameter pairs (u_i, v_i) of a homogeneous control net
    (nu, nv, 4). Vectorised reference used by tests and benchmarks."""
    Bu = bspline_basis(knots_u, deg_u, u)  # (N, nu)
    Bv = bspline_basis(knots_v, deg_v, v)  # (N, nv)
    h = np.einsum("ni,ijk,nj->nk", Bu, ctrlw, Bv)
    return h[:, :3] / h[:, 3:4]


def to_geomdl(ctrlw, knots_u, knots_v, deg_u: int = 3, deg_v: int = 2):
    """Export one sweep surface as a geomdl NURBS surface (control points, weights, knots)."""
    from geomdl import NURBS

    ctrlw = np.asarray(ctrlw, dtype=float)
    nu, nv, _ = ctrlw.shape
    surf = NURBS.Surface()
    surf.degree_u = deg_u
    surf.degree_v = deg_v
    surf.ctrlpts_size_u = nu
    surf.ctrlpts_size_v = nv
    surf.ctrlptsw = ctrlw.reshape(-1, 4).tolist()
    surf.knotvector_u = list(map(float, knots_u))
    surf.knotvector_v = list(map(float, knots_v))
    return surf


def insert_knot(ctrlw, knots, degree: int, u: float):
    """Boehm's single knot insertion along axis 0 of a homogeneous net (n, ..., 4) (Piegl &
    Tiller Alg. A5.1 with r = 1). Returns (new_ctrlw, new_knots); the surface is unchanged."""
    knots = np.asarray(knots, dtype=float)
    k = int(np.searchsorted(knots, u, side="right") - 1)
    k = min(k, len(knots) - degree - 2)
    new = np.empty((ctrlw.shape[0] + 1,) + ctrlw.shape[1:])
    new[: k - degree + 1] = ctrlw[: k - degree + 1]
    new[k + 1 :] = ctrlw[k:]
    for i in range(k - degree + 1, k + 1):
        a = (u - knots[i]) / (knots[i + degree] - knots[i])
        new[i] = a * ctrlw[i] + (1.0 - a) * ctrlw[i - 1]
    return new, np.insert(knots, k + 1, u)


def bezier_form(ctrlw, knots, degree: int):
    """Refine axis 0 of a clamped homogeneous net until every interior knot has multiplicity
    ``degree`` (Bezier form; same surface). Blender's 'Bezier' + 'Endpoint' knot mode spaces
    such breakpoints uniformly, so this is the exact form a Blender NURBS surface can hold.
    Returns (ctrlw, breakpoints): span i of Blender's parameter [i, i+1] is the engine's
    [breakpoints[i], breakpoints[i+1]], mapped affinely."""
    knots = np.asarray(knots, dtype=float)
    out = np.asarray(ctrlw, dtype=float)
    breaks = np.unique(knots)
    for u in breaks[1:-1]:
        while np.count_nonzero(np.isclose(knots, u, rtol=0, atol=1e-12)) < degree:
            out, knots = insert_knot(out, knots, degree, float(u))
    return out, breaks
