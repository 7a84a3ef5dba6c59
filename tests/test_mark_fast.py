# SPDX-License-Identifier: GPL-3.0-or-later
"""The fast current-drawing-mark rasteriser (scanline spans of cur_u, contact rows only, one
candidate section unless the axis folds) gives exactly the marks of the plain reference that
tests every bounding-box pixel against every row of the surface."""

import numpy as np
import pytest

from sim.bench import _long_stroke, _sim
from sim.mark import compute_marks
from tests.reference_mark import reference_marks


def _states(primitives, ppm, every=37):
    """Brush states along a long pressed zig-zag stroke (bent, spread and split brushes)."""
    s = _long_stroke()
    sim = _sim(s, int(200 * ppm), ppm, primitives)
    while not sim.done:
        sim.step()
        if sim.index % every == 0:
            yield sim


@pytest.mark.parametrize("primitives, ppm", [(1, 10.24), (16, 6.0), (4, 20.48)])
def test_fast_marks_equal_reference(primitives, ppm):
    checked = pixels = 0
    for sim in _states(primitives, ppm):
        b = sim.brush
        sec = b.sections()
        ink = b.rows_ink(sec)
        fast = compute_marks(b, sec, ink, ppm, sim.paper.shape)
        ref = reference_marks(b, sec, ink, ppm, sim.paper.shape)
        ref = [mk for mk in ref if mk.rows.size]
        fast = [mk for mk in fast if mk.rows.size]
        assert [mk.primitive for mk in fast] == [mk.primitive for mk in ref]
        for a, r in zip(fast, ref, strict=True):
            ga = set(zip((a.rows + a.iy0).tolist(), (a.cols + a.ix0).tolist(), strict=True))
            gr = set(zip((r.rows + r.iy0).tolist(), (r.cols + r.ix0).tolist(), strict=True))
            assert ga == gr
            order_a = np.lexsort((a.cols + a.ix0, a.rows + a.iy0))
            order_r = np.lexsort((r.cols + r.ix0, r.rows + r.iy0))
            np.testing.assert_allclose(a.wet[order_a], r.wet[order_r], rtol=0, atol=1e-9)
            np.testing.assert_allclose(a.col[order_a], r.col[order_r], rtol=0, atol=1e-9)
            np.testing.assert_allclose(a.lateral[order_a], r.lateral[order_r], atol=1e-9)
            assert a.area_bbox == pytest.approx(r.area_bbox)
            checked += 1
            pixels += a.rows.size
    assert checked >= 5 and pixels > 1000


def test_banded_uint8_image_and_png_equal_the_float_image(tmp_path):
    from sim.png import read_png, to_uint8, write_png

    sim = _sim(_long_stroke(), 700, 3.5, 1)
    sim.paper.ink[...] = np.random.default_rng(3).random(sim.paper.ink.shape, dtype=np.float32)
    img8 = sim.image8()
    np.testing.assert_array_equal(img8, to_uint8(sim.image()))
    wide = np.concatenate([img8] * 4, axis=1)  # rows of 8400 bytes: several bands per file
    write_png(tmp_path / "a.png", wide)
    np.testing.assert_array_equal(read_png(tmp_path / "a.png"), wide)
