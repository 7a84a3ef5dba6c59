# SPDX-License-Identifier: GPL-3.0-or-later
"""Arithmetic that gives the same bits on any machine (issue 28.2).

IEEE 754 rounds + - * / and sqrt exactly, so numpy's elementwise arithmetic gives the same
numbers whatever SIMD kernel it picks at run time. Two kinds of numpy call do not:

- products through BLAS (``@``, ``np.dot``, ``x.dot(y)``, ``np.linalg.norm`` of a whole
  vector): OpenBLAS picks its kernels by CPU (with or without fused multiply-add, other
  summation splits), so ``local @ R.T`` differs in the last bits between an AVX2 and an older
  or an AVX512 machine. ``matmul`` here sums the products in a fixed order, with
  elementwise arithmetic.
- transcendentals: numpy's float64 exp, log, sin, cos, power, arctan2 ... take SIMD paths on
  AVX512 machines (its own or Intel's SVML) that round differently from the C library's.
  ``sin``, ``cos``, ``exp`` and ``exp2`` here are fdlibm's (Sun's freely distributable libm)
  range reductions and polynomials written out in + - * /, to about one unit in the last place.

The brush state passes through these; they accept numpy arrays and Python floats alike, with the
same operations in the same order on both (Python's float arithmetic is the same IEEE double).
"""

from __future__ import annotations

import functools
import math

import numpy as np

# the ufunc np.clip calls, without its Python wrappers (the same picks): numpy._core from 2.0,
# numpy.core before (1.26 has a numpy._core too, without umath, once something imports it);
# ``sim.core.frames`` hands it on
_NUMPY_2 = np.lib.NumpyVersion(np.__version__) >= "2.0.0"
clip = (np._core if _NUMPY_2 else np.core).umath.clip


def _keeps_float32(f):
    """f computed in float64 and rounded back to float32 when every argument is a float32
    array or scalar (numpy's float32 transcendentals have SIMD paths of their own)."""

    @functools.wraps(f)
    def wrapped(*args):
        if args[0].__class__ is not float and all(
            getattr(a, "dtype", None) == np.float32 for a in args
        ):
            out = f(*(np.asarray(a, dtype=float) for a in args))
            if isinstance(out, tuple):
                return tuple(o.astype(np.float32)[()] for o in out)
            return out.astype(np.float32)[()]
        return f(*args)

    return wrapped


# --- products in a fixed order ------------------------------------------------------------


def matmul(a, b):
    """a @ b (numpy's broadcasting rules for 1-d and stacked operands), each entry summed over
    the inner index 0, 1, 2, ... one product at a time: the same numbers on any machine.

    Where it can, all the products are made in one go, laid out with the inner index on an axis
    that is not the innermost, and np.add.reduce sums along it: numpy reduces such an axis by
    adding its slices in turn, the same sums as the loops (which take the other cases)."""
    if a.__class__ is not np.ndarray:
        a = np.asarray(a, dtype=float)
    if b.__class__ is not np.ndarray:
        b = np.asarray(b, dtype=float)
    k = a.shape[-1]
    if b.shape[-2 if b.ndim > 1 else 0] != k:
        raise ValueError(f"matmul: inner sizes {k} and {b.shape} do not match")
    if b.ndim == 1 and a.ndim > 1 and a.shape[-2] > 1:  # (..., n, k) @ (k,) -> (..., n)
        out = np.add.reduce(np.swapaxes(a, -1, -2) * b[:, None], axis=-2)
    elif a.ndim == 1 and b.ndim > 1 and b.shape[-1] > 1:  # (k,) @ (..., k, m) -> (..., m)
        out = np.add.reduce(a[:, None] * b, axis=-2)
    elif b.ndim == 1:
        out = a[..., 0] * b[0]
        for j in range(1, k):
            out += a[..., j] * b[j]
    elif a.ndim == 1:  # (k,) @ (..., k, m) -> (..., m)
        out = a[0] * b[..., 0, :]
        for j in range(1, k):
            out += a[j] * b[..., j, :]
    elif b.shape[-1] > 1:  # (..., n, k) @ (..., k, m) -> (..., n, m)
        out = np.add.reduce(a[..., :, :, None] * b[..., None, :, :], axis=-2)
    else:
        out = a[..., :, 0, None] * b[..., None, 0, :]
        for j in range(1, k):
            out += a[..., :, j, None] * b[..., None, j, :]
    return out


# --- sin and cos (fdlibm k_sin.c, k_cos.c, with a three-part Cody-Waite reduction) ---------------

_TWO_OVER_PI = 6.36619772367581382433e-01
# pi/2 in three parts, the first two of 33 significant bits (n * part is exact for |n| < 2**20)
_PIO2_1 = 1.57079632673412561417e00
_PIO2_2 = 6.07710050630396597660e-11
_PIO2_3 = 2.02226624871116645580e-21
_S = (
    -1.66666666666666324348e-01,
    8.33333333332248946124e-03,
    -1.98412698298579493134e-04,
    2.75573137070700676789e-06,
    -2.50507602534068634195e-08,
    1.58969099521155010221e-10,
)
_C = (
    4.16666666666666019037e-02,
    -1.38888888888741095749e-03,
    2.48015872894767294178e-05,
    -2.75573143513906633035e-07,
    2.08757232129817482790e-09,
    -1.13596475577881948265e-11,
)


def _kernels(r):
    """(sin r, cos r) for |r| <= pi/4 (fdlibm k_sin.c and k_cos.c, sharing r**2)."""
    z = r * r
    ps = _S[1] + z * (_S[2] + z * (_S[3] + z * (_S[4] + z * _S[5])))
    pc = z * (_C[0] + z * (_C[1] + z * (_C[2] + z * (_C[3] + z * (_C[4] + z * _C[5])))))
    return r + (z * r) * (_S[0] + z * ps), 1.0 - (0.5 * z - z * pc)


def _reduced(x, n):
    """r = x - n pi/2, |r| <= pi/4 (about; exact enough for |x| < 2**20); x itself for n = 0."""
    return ((x - n * _PIO2_1) - n * _PIO2_2) - n * _PIO2_3


_FEW = 8  # arrays up to this size go number by number (Python floats, the same operations)


@_keeps_float32
def sin_cos(x):
    """(sin x, cos x) for a float or an array of floats, the same bits on any machine."""
    if isinstance(x, float):
        n = float(round(x * _TWO_OVER_PI))
        s, c = _kernels(x if n == 0.0 else _reduced(x, n))
        q = int(n) & 3
        return (s, c, -s, -c)[q], (c, -s, -c, s)[q]
    x = np.asarray(x, dtype=float)
    if x.size <= _FEW:  # cheaper than the array operations below, for a few numbers
        pairs = [sin_cos(v) for v in x.ravel().tolist()]
        return tuple(np.array([p[k] for p in pairs]).reshape(x.shape) for k in (0, 1))
    n = np.rint(x * _TWO_OVER_PI)
    if not n.any():  # all within pi/4 of 0 (a turn's small angles)
        return _kernels(x)
    s, c = _kernels(np.where(n == 0.0, x, _reduced(x, n)))
    q = n.astype(np.int64) & 3
    odd = (q & 1).astype(bool)
    sin_x = np.where(odd, c, s)
    cos_x = np.where(odd, s, c)
    np.negative(sin_x, out=sin_x, where=q >= 2)
    np.negative(cos_x, out=cos_x, where=(q == 1) | (q == 2))
    return sin_x, cos_x


def sin(x):
    """sin x (see sin_cos)."""
    return sin_cos(x)[0]


def cos(x):
    """cos x (see sin_cos)."""
    return sin_cos(x)[1]


# --- exp (fdlibm e_exp.c) --------------------------------------------------------------------

_LN2_HI = 6.93147180369123816490e-01  # ln 2 in two parts, the first of 32 significant bits
_LN2_LO = 1.90821492927058770002e-10
_INV_LN2 = 1.44269504088896338700e00
_LN2 = 6.93147180559945286227e-01
_P = (
    1.66666666666666019037e-01,
    -2.77777777770155933842e-03,
    6.61375632143793436117e-05,
    -1.65339022054652515390e-06,
    4.13813679705723846039e-08,
)
_EXP_RANGE = (-746.0, 710.0)  # beyond: 0 and inf


def _exp_reduced(x, n):
    """e**x / 2**n for n = rint(x / ln 2) (|x - n ln 2| <= ln 2 / 2)."""
    hi = x - n * _LN2_HI
    lo = n * _LN2_LO
    r = hi - lo
    t = r * r
    c = r - t * (_P[0] + t * (_P[1] + t * (_P[2] + t * (_P[3] + t * _P[4]))))
    return 1.0 - ((lo - (r * c) / (2.0 - c)) - hi)


def _ldexp(y: float, n: float) -> float:
    """y 2**n for Python floats, inf where that overflows (as numpy's ldexp)."""
    try:
        return math.ldexp(y, int(n))
    except OverflowError:
        return math.inf


@_keeps_float32
def exp(x):
    """e**x for a float or an array of floats, the same bits on any machine."""
    if isinstance(x, float):
        if x != x:
            return x
        x = min(max(x, _EXP_RANGE[0]), _EXP_RANGE[1])
        n = float(round(x * _INV_LN2))
        return _ldexp(_exp_reduced(x, n), n)
    x = np.clip(np.asarray(x, dtype=float), *_EXP_RANGE)
    n = np.rint(x * _INV_LN2)
    return np.ldexp(_exp_reduced(x, n), n.astype(np.int32))


@_keeps_float32
def exp2(x):
    """2**x for a float or an array of floats (np.power(2.0, x)), the same bits on any machine:
    2**n e**(f ln 2) with n = rint(x), f = x - n exact."""
    if isinstance(x, float):
        if x != x:
            return x
        x = min(max(x, -1100.0), 1100.0)
        n = float(round(x))
        return _ldexp(exp((x - n) * _LN2), n)
    x = np.clip(np.asarray(x, dtype=float), -1100.0, 1100.0)
    n = np.rint(x)
    return np.ldexp(exp((x - n) * _LN2), n.astype(np.int32))


# --- arctan and arctan2 (fdlibm s_atan.c, e_atan2.c) -------------------------------------------

_ATAN_HI = (
    4.63647609000806093515e-01,  # atan(0.5)
    7.85398163397448278999e-01,  # atan(1)
    9.82793723247329054082e-01,  # atan(1.5)
    1.57079632679489655800e00,  # atan(inf)
)
_ATAN_LO = (
    2.26987774529616870924e-17,
    3.06161699786838301793e-17,
    1.39033110312309984516e-17,
    6.12323399573676603587e-17,
)
_AT = (
    3.33333333333329318027e-01,
    -1.99999999998764832476e-01,
    1.42857142725034663711e-01,
    -1.11111104054623557880e-01,
    9.09088713343650656196e-02,
    -7.69187620504482999495e-02,
    6.66107313738753120669e-02,
    -5.83357013379057348645e-02,
    4.97687799461593236017e-02,
    -3.65315727442169155270e-02,
    1.62858201153657823623e-02,
)
_ATAN_CUTS = (0.4375, 0.6875, 1.1875, 2.4375)  # the intervals reduced about 0, 0.5, 1, 1.5, inf
_PI = 3.14159265358979311600e00
_PI_LO = 1.2246467991473531772e-16


def _atan_poly(t):
    """t - atan(t) for |t| <= 7/16, as t (s1 + s2) (fdlibm's odd polynomial in two halves)."""
    z = t * t
    w = z * z
    s1 = z * (_AT[0] + w * (_AT[2] + w * (_AT[4] + w * (_AT[6] + w * (_AT[8] + w * _AT[10])))))
    s2 = w * (_AT[1] + w * (_AT[3] + w * (_AT[5] + w * (_AT[7] + w * _AT[9]))))
    return t * (s1 + s2)


def _atan_float(a: float) -> float:
    """atan a for a >= 0 (a Python float; inf allowed)."""
    if a >= 2.0**66:
        return _ATAN_HI[3] + _ATAN_LO[3]
    if a < _ATAN_CUTS[0]:
        return a - _atan_poly(a)
    if a < _ATAN_CUTS[1]:
        k, t = 0, (2.0 * a - 1.0) / (2.0 + a)
    elif a < _ATAN_CUTS[2]:
        k, t = 1, (a - 1.0) / (a + 1.0)
    elif a < _ATAN_CUTS[3]:
        k, t = 2, (a - 1.5) / (1.0 + 1.5 * a)
    else:
        k, t = 3, -1.0 / a
    return _ATAN_HI[k] - ((_atan_poly(t) - _ATAN_LO[k]) - t)


def _atan_array(a):
    """atan a for an array a >= 0 (inf allowed): the same steps as _atan_float, all at once."""
    k = np.searchsorted(np.array(_ATAN_CUTS), a, side="right")
    big = a >= 2.0**66
    # every branch is computed for every a, and only its own a's kept: -1 / a of a subnormal
    # a overflows (where a's branch is k == 0), 2 a - 1 of a huge one too (where it is ``big``)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t = np.select(
            [k == 0, k == 1, k == 2, k == 3],
            [a, (2.0 * a - 1.0) / (2.0 + a), (a - 1.0) / (a + 1.0), (a - 1.5) / (1.0 + 1.5 * a)],
            -1.0 / np.where(big, 1.0, a),
        )
    p = _atan_poly(t)
    hi, lo = np.array((0.0, *_ATAN_HI))[k], np.array((0.0, *_ATAN_LO))[k]
    out = np.where(k == 0, t - p, hi - ((p - lo) - t))
    return np.where(big, _ATAN_HI[3] + _ATAN_LO[3], out)


def _atan2_quadrant(z):
    """atan2's angle in each quadrant (y >= 0 and x >= 0, y < 0, x < 0, both) from
    z = atan |y / x| (fdlibm e_atan2.c)."""
    return z, -z, _PI - (z - _PI_LO), (z - _PI_LO) - _PI


@_keeps_float32
def arctan2(y, x):
    """np.arctan2(y, x) for floats or arrays of floats, the same bits on any machine (finite
    y and x; atan2(0, 0) is 0 or pi by the sign of x, as the C library's)."""
    if isinstance(y, float) and isinstance(x, float):
        if x == 0.0 and y == 0.0:
            return math.copysign(_PI if math.copysign(1.0, x) < 0 else 0.0, y)
        z = _atan_float(abs(y) / abs(x)) if x != 0.0 else _ATAN_HI[3] + _ATAN_LO[3]
        q = _atan2_quadrant(z)
        return q[(1 if y < 0 or (y == 0 and math.copysign(1.0, y) < 0) else 0) + 2 * (x < 0)]
    y, x = np.broadcast_arrays(np.asarray(y, dtype=float), np.asarray(x, dtype=float))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # inf: atan's ``big``
        a = np.abs(y) / np.abs(x)
    both0 = (x == 0.0) & (y == 0.0)
    z = _atan_array(np.where(both0, 0.0, a))
    neg_y, neg_x = np.signbit(y), np.signbit(x) & ((x != 0.0) | (y == 0.0))  # x = -0: +pi/2
    q = _atan2_quadrant(z)
    return np.where(neg_x, np.where(neg_y, q[3], q[2]), np.where(neg_y, q[1], q[0]))


# --- log, log1p, expm1 (fdlibm e_log.c; Goldberg's and Kahan's corrections) -----------------------

_LG = (
    6.666666666666735130e-01,
    3.999999999940941908e-01,
    2.857142874366239149e-01,
    2.222219843214978396e-01,
    1.818357216161805012e-01,
    1.531383769920937332e-01,
    1.479819860511658591e-01,
)
_SQRT_HALF = 7.07106781186547524401e-01


def _log_reduced(f, k):
    """log((1 + f) 2**k) for sqrt(1/2) - 1 <= f < sqrt(2) - 1."""
    s = f / (2.0 + f)
    z = s * s
    w = z * z
    t1 = w * (_LG[1] + w * (_LG[3] + w * _LG[5]))
    t2 = z * (_LG[0] + w * (_LG[2] + w * (_LG[4] + w * _LG[6])))
    hfsq = 0.5 * f * f
    return k * _LN2_HI - ((hfsq - (s * (hfsq + (t1 + t2)) + k * _LN2_LO)) - f)


@_keeps_float32
def log(x):
    """The natural logarithm of a float or an array of floats, the same bits on any machine
    (x > 0 and finite; elsewhere nan, or -inf at 0)."""
    if isinstance(x, float):
        if not 0.0 < x < math.inf:
            return -math.inf if x == 0.0 else math.nan
        m, e = math.frexp(x)
        if m < _SQRT_HALF:
            m, e = 2.0 * m, e - 1
        return _log_reduced(m - 1.0, float(e))
    x = np.asarray(x, dtype=float)
    m, e = np.frexp(x)
    low = m < _SQRT_HALF
    m = np.where(low, 2.0 * m, m)
    e = (e - low).astype(float)
    out = _log_reduced(m - 1.0, e)
    bad = ~((x > 0.0) & (x < math.inf))
    if not bad.any():
        return out
    return np.where(bad, np.where(x == 0.0, -math.inf, np.where(x > 0.0, x, math.nan)), out)


@_keeps_float32
def log1p(x):
    """log(1 + x) accurate near 0 (Goldberg: log(u) x / (u - 1) with u = 1 + x rounded)."""
    if isinstance(x, float):
        u = 1.0 + x
        return x if u == 1.0 else log(u) * (x / (u - 1.0))
    x = np.asarray(x, dtype=float)
    u = 1.0 + x
    d = u - 1.0
    with np.errstate(divide="ignore", invalid="ignore"):
        out = log(u) * (x / d)
    return np.where(d == 0.0, x, out)


def expm1(x):
    """e**x - 1 accurate near 0 (Kahan: (u - 1) x / log u with u = e**x rounded); for float32
    arrays, a shorter sum in float64 (_expm1_float32)."""
    if isinstance(x, float):
        u = exp(x)
        if u == 1.0:
            return x
        return u - 1.0 if u - 1.0 == -1.0 or u == math.inf else (u - 1.0) * x / log(u)
    x = np.asarray(x)
    if x.dtype == np.float32:
        return _expm1_float32(x)
    x = x.astype(float, copy=False)
    u = exp(x)
    d = u - 1.0
    with np.errstate(divide="ignore", invalid="ignore"):
        out = d * x / log(u)
    return np.where((u == 1.0), x, np.where((d == -1.0) | (u == math.inf), d, out))


_EXPM1_TAYLOR = tuple(1.0 / math.factorial(k) for k in range(2, 10))  # 1/2! ... 1/9!
_FLOAT32_EXP_RANGE = (-110.0, 90.0)  # beyond: -1 and inf in float32


def _expm1_float32(x):
    """expm1 of a float32 array: 2**n expm1(r) + (2**n - 1) with x = n ln 2 + r, |r| <= ln 2 / 2,
    expm1(r) by its Taylor sum to r**9 / 9! (relative error under 1e-9, far below float32's
    rounding) in float64, rounded once to float32. The sum is made in place and 2**n read
    from a table (the same numbers as ldexp's; issue 28)."""
    x = clip(x.astype(float), *_FLOAT32_EXP_RANGE)
    n = np.rint(x * _INV_LN2)
    if not n.any():  # all within ln 2 / 2 of 0 (most calls while writing): r = x, 2**n = 1
        return _expm1_unreduced(x)
    r = (x - n * _LN2_HI) - n * _LN2_LO
    p = _expm1_taylor(r)
    two_n = _POW2.take(n.astype(np.intp) - _POW2_FROM)
    p *= two_n
    two_n -= 1.0
    p += two_n
    return p.astype(np.float32)[()]


def _expm1_taylor(r):
    """expm1(r) for |r| <= ln 2 / 2 by its Taylor sum to r**9 / 9!, in place in a new array:
    r (1 + r (c0 + r (c1 + ... r c7)))."""
    p = r * _EXPM1_TAYLOR[-1]
    for c in _EXPM1_TAYLOR[-2::-1]:
        p += c
        p *= r
    p += 1.0
    p *= r
    return p


def _expm1_unreduced(x):
    """``_expm1_float32``'s sum where every n is 0 (+0 or -0): there r = (x - n hi) - n lo is
    x itself but for the sign of a zero, and 2**n expm1(r) + (2**n - 1) is expm1(r) + 0, which
    turns a -0 into +0 and leaves every other number as it is: the same numbers without the
    reduction's steps (issue 28; about three float32 calls in four while writing a character,
    of laying, lift and wicking, a quarter of the wicking passes' alone)."""
    p = _expm1_taylor(x)
    p += 0.0
    return p.astype(np.float32)[()]


_POW2_FROM = -160  # 2**n for the n of _FLOAT32_EXP_RANGE: ldexp(1, n), exact
_POW2 = np.ldexp(1.0, np.arange(_POW2_FROM, 131, dtype=np.int32))


def arcsin(x):
    """arcsin x for |x| <= 1, as arctan2(x, sqrt((1 - x)(1 + x)))."""
    if isinstance(x, float):
        return arctan2(x, math.sqrt((1.0 - x) * (1.0 + x)))
    x = np.asarray(x, dtype=float)
    return arctan2(x, np.sqrt((1.0 - x) * (1.0 + x)))


def arccos(x):
    """arccos x for |x| <= 1, as arctan2(sqrt((1 - x)(1 + x)), x)."""
    if isinstance(x, float):
        return arctan2(math.sqrt((1.0 - x) * (1.0 + x)), x)
    x = np.asarray(x, dtype=float)
    return arctan2(np.sqrt((1.0 - x) * (1.0 + x)), x)


# --- small linear algebra (LAPACK's kernels differ by CPU as BLAS's do) -----------------------


def inv(m) -> np.ndarray:
    """The inverse of a small square matrix (a pose's 4 x 4, a 2 x 2), by Gauss-Jordan
    elimination with partial pivoting on Python floats: the same steps on any machine. Raises
    ValueError for a singular matrix (np.linalg.inv's LinAlgError)."""
    a = np.asarray(m, dtype=float)
    n = a.shape[0]
    if a.shape != (n, n):
        raise ValueError(f"inv: not a square matrix: {a.shape}")
    rows = [r + [1.0 if i == j else 0.0 for j in range(n)] for i, r in enumerate(a.tolist())]
    for k in range(n):
        p = max(range(k, n), key=lambda i: abs(rows[i][k]))  # the first of the largest
        if rows[p][k] == 0.0:
            raise ValueError("inv: singular matrix")
        rows[k], rows[p] = rows[p], rows[k]
        pivot = rows[k][k]
        rows[k] = [v / pivot for v in rows[k]]
        for i in range(n):
            f = rows[i][k]
            if i != k and f != 0.0:
                rows[i] = [v - f * w for v, w in zip(rows[i], rows[k], strict=True)]
    return np.array([r[n:] for r in rows])


def det3(m) -> float:
    """The determinant of a 3 x 3 matrix by its first row's cofactors."""
    (a, b, c), (d, e, f), (g, h, i) = np.asarray(m, dtype=float).tolist()
    return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
