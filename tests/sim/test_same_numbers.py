# SPDX-License-Identifier: GPL-3.0-or-later
"""Issue 28.2: the engine's faster forms give the very numbers of the plain forms they replace,
bit for bit, on random input (the plain forms written out here as they were)."""

import math

import numpy as np

from sim.brush.primitive import HairyBrush
from sim.core import exact
from sim.core.frames import per_pixel
from sim.core.params import BrushGeometry, QualityParams
from sim.paper import lift
from sim.paper.lift import box_mean, level_rows, same_colours
from sim.paper.paper import FULL_WET, Paper
from sim.paper.wick import WICK_PIGMENT, WICK_RATE, _wick

RNG = np.random.default_rng(28)


def _plain_wick(w, ink, draw, passes, rate=WICK_RATE):
    """The wicking with its colours broadcast three numbers at a time (before issue 28; laid
    up to the darkest giver's colour, issue 26)."""
    rate = np.float32(rate)
    down = rate * draw[:-1] * draw[1:]
    along = rate * draw[:, :-1] * draw[:, 1:]
    for _ in range(passes):
        if not (w > 0.0).any():
            return
        inflow = np.zeros_like(w)
        carried = np.zeros_like(ink)
        darkest = np.zeros_like(ink)
        for g, a, b in ((down, np.s_[:-1], np.s_[1:]), (along, np.s_[:, :-1], np.s_[:, 1:])):
            flux = g * (w[a] - w[b])
            to_b, to_a = np.maximum(flux, 0.0), np.maximum(-flux, 0.0)
            inflow[b] += to_b
            inflow[a] += to_a
            carried[b] += to_b[..., None] * ink[a]
            carried[a] += to_a[..., None] * ink[b]
            darkest[b] = np.maximum(darkest[b], np.where(to_b[..., None] > 0.0, ink[a], 0.0))
            darkest[a] = np.maximum(darkest[a], np.where(to_a[..., None] > 0.0, ink[b], 0.0))
            w[a] -= flux
            w[b] += flux
        take = WICK_PIGMENT * -exact.expm1(-inflow / FULL_WET)
        take /= np.where(inflow > 0.0, inflow, 1.0)
        laid = (1.0 - ink) * (carried * take[..., None])
        ink += np.minimum(laid, np.maximum(darkest - ink, 0.0))


def test_wicking_on_rows_of_colours_gives_the_broadcast_numbers():
    for h, w, passes in ((1, 7, 1), (9, 1, 1), (23, 31, 1), (40, 17, 3)):
        wet = (RNG.random((h, w)) * 0.6).astype(np.float32)
        wet[RNG.random((h, w)) < 0.3] = 0.0
        sheet = RNG.random((h + 4, w + 6, 3)).astype(np.float32)  # a window of a sheet
        draw = (0.05 + 0.95 * RNG.random((h, w))).astype(np.float32)
        ink, ref_ink = sheet[2:-2, 3:-3], sheet[2:-2, 3:-3].copy()
        ref_w = wet.copy()
        _wick(wet, ink, draw, passes)
        _plain_wick(ref_w, ref_ink, draw, passes)
        assert wet.tobytes() == ref_w.tobytes()
        assert ink.tobytes() == ref_ink.tobytes()
        assert sheet[:2].any()  # (the sheet around the window is left as it was)


def _equal_colours(shape, same):
    """Random ink of ``shape`` (h, w, 3) whose colours are those of ``same``'s (same_colours)."""
    return np.ascontiguousarray(RNG.random(shape).astype(np.float32)[..., same])


def test_ink_of_equal_colours_wicks_them_once_and_gives_the_broadcast_numbers():
    for same in ([0, 0, 0], [0, 0, 2], [0, 1, 1], [0, 1, 0]):
        for h, w, passes in ((1, 7, 1), (9, 1, 1), (23, 31, 1), (40, 17, 3)):
            wet = (RNG.random((h, w)) * 0.6).astype(np.float32)
            wet[RNG.random((h, w)) < 0.3] = 0.0
            sheet = _equal_colours((h + 4, w + 6, 3), same)
            draw = (0.05 + 0.95 * RNG.random((h, w))).astype(np.float32)
            ink, ref_ink = sheet[2:-2, 3:-3], sheet[2:-2, 3:-3].copy()
            assert same_colours(ink) == same  # (worked on as fewer colours)
            ref_w = wet.copy()
            _wick(wet, ink, draw, passes)
            _plain_wick(ref_w, ref_ink, draw, passes)
            assert wet.tobytes() == ref_w.tobytes()
            assert ink.tobytes() == ref_ink.tobytes()


def test_ink_of_equal_colours_levels_them_once_and_gives_the_three_colours_numbers(monkeypatch):
    paper = Paper(90, 70, 8.0, capacity=1.0)
    paper.wet[...] = RNG.random((70, 90)).astype(np.float32) * 0.9
    paper.last[...] = RNG.integers(0, 3, (70, 90))
    args = (paper, 1, (0.9, 0.9, 0.9), (10, 60), (0, 70, 5, 85))
    for same in ([0, 0, 0], [0, 0, 2]):
        paper.ink[...] = _equal_colours((70, 90, 3), same) * 0.95
        with monkeypatch.context() as m:
            at, fewer = level_rows(*args)
            m.setattr(lift, "same_colours", lambda ink: [0, 1, 2])  # every colour on its own
            at3, three = level_rows(*args)
        assert at[0].size > 100 and all(
            a.tobytes() == b.tobytes() for a, b in zip(at, at3, strict=True)
        )
        assert fewer.tobytes() == three.tobytes()


def test_expm1_of_float32_gives_ldexps_numbers():
    x = np.concatenate(
        [
            -np.abs(RNG.standard_normal(4000)) * 10.0 ** RNG.uniform(-8, 2, 4000),
            RNG.uniform(-200.0, 100.0, 2000),
            [0.0, -0.0, -1e-45, 88.7, 90.0, 91.0, -110.0, -111.0],
        ]
    ).astype(np.float32)
    y = np.clip(x.astype(float), -110.0, 90.0)
    n = np.rint(y * exact._INV_LN2)
    r = (y - n * exact._LN2_HI) - n * exact._LN2_LO
    p = 0.0
    for c in exact._EXPM1_TAYLOR[::-1]:
        p = c + r * p
    p = r * (1.0 + r * p)
    two_n = np.ldexp(1.0, n.astype(np.int32))
    with np.errstate(over="ignore"):
        plain = (p * two_n + (two_n - 1.0)).astype(np.float32)
        assert exact._expm1_float32(x).tobytes() == plain.tobytes()


def test_box_mean_along_the_rows_is_the_transposed_columns_mean():
    for shape, r in (((5, 30), 2), ((30, 5), 7), ((17, 19), 1), ((3, 3), 4)):
        a = RNG.random(shape).astype(np.float32)
        assert box_mean(a, r, 1).tobytes() == np.ascontiguousarray(box_mean(a.T, r, 0).T).tobytes()


def test_per_pixel_is_the_broadcast_product():
    col = RNG.random((1001, 3)).astype(np.float32)
    a = RNG.random(1001).astype(np.float32)
    assert per_pixel(col, a).tobytes() == (col * a[:, None]).tobytes()
    assert per_pixel(col[::2], a[::2]).tobytes() == (col[::2] * a[::2, None]).tobytes()


def test_one_primitives_profile_is_the_arrays():
    brush = HairyBrush(BrushGeometry(), QualityParams(), np.random.default_rng(0))
    cc = brush.cc[:1].copy()
    u = np.linspace(0.0, 1.0, 23)
    for _ in range(50):
        loc, tip = RNG.uniform(0.05, 0.9), RNG.random()
        a, b = RNG.uniform(0.2, 3.0, 2)
        fields = (np.array([loc]), np.array([a]), np.array([b]), np.array([tip]))
        brush.cc = np.concatenate([cc, cc])  # two primitives: the arrays' form
        brush.loc, brush.a, brush.b, brush.tiplen = (np.r_[v, v] for v in fields)
        two = brush.profile_semiaxes(u)
        brush.cc = cc  # one: Python floats
        brush.loc, brush.a, brush.b, brush.tiplen = fields
        one = brush.profile_semiaxes(u)
        assert two[0][:1].tobytes() == one[0].tobytes()
        assert two[1][:1].tobytes() == one[1].tobytes()
    assert math.isclose(float(one[0][0, 0]), brush.r)


def test_arctan2_of_tiny_and_huge_ratios_warns_of_nothing():
    # every branch of atan is computed for every ratio and only its own kept: a subnormal
    # ratio's -1 / a, a huge one's 2 a - 1 and |y| / |x| overflow where they are not kept
    import warnings

    y = np.array([1e-310, 1e300, 3.0, -2e-320, 0.0, 1e308])
    x = np.array([1.0, 1e-10, 4.0, 5.0, -1.0, 0.5])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = exact.arctan2(y, x)
    assert got.tolist() == [exact.arctan2(float(a), float(b)) for a, b in zip(y, x, strict=True)]
    assert np.allclose(got, np.arctan2(y, x), rtol=1e-15, atol=0.0)
