# SPDX-License-Identifier: GPL-3.0-or-later
"""The hair bundles' fast signed distance from the trail (``sim.brush.trailpath``: each pixel
once, segments that cannot be nearest left out) gives, bit for bit, the plain measure of every
pixel of every mark against every segment (``bristles.across`` as it was first written)."""

from dataclasses import replace

import numpy as np
import pytest

from sim.brush import bristles, trailpath
from sim.brush.mark import Mark


def plain_across(marks, path, ppm):
    """The first ``bristles.across``: every mark's pixels against every segment, in blocks."""
    a, d = path[:-1], np.diff(path, axis=0)
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-12)
    lo = np.zeros(len(a))
    hi = np.ones(len(a))
    lo[0], hi[-1] = -np.inf, np.inf
    out = []
    for mk in marks:
        x = (mk.cols + mk.ix0 + 0.5) / ppm
        y = (mk.rows + mk.iy0 + 0.5) / ppm
        lateral = np.empty(x.size, dtype=np.float32)
        for at in range(0, x.size, 4096):
            rx = x[at : at + 4096, None] - a[None, :, 0]
            ry = y[at : at + 4096, None] - a[None, :, 1]
            t = np.clip((rx * d[:, 0] + ry * d[:, 1]) / dd, lo, hi)
            ex, ey = rx - t * d[:, 0], ry - t * d[:, 1]
            dist2 = ex * ex + ey * ey
            k = np.argmin(dist2, axis=1)
            rows = np.arange(k.size)
            side = d[k, 0] * ry[rows, k] - d[k, 1] * rx[rows, k]
            lateral[at : at + 4096] = np.sqrt(dist2[rows, k]) * np.where(side < 0, -1, 1)
        out.append(lateral)
    return out


def _mark(rng, primitive, centre, radius, ppm):
    """A disc of pixels around ``centre`` (mm), some dropped, in a window of its own."""
    iy0, ix0 = (np.floor((np.asarray(centre) - radius) * ppm)).astype(int)[::-1]
    n = int(2 * radius * ppm) + 1
    rr, cc = np.mgrid[0:n, 0:n]
    yy, xx = (rr + iy0 + 0.5) / ppm, (cc + ix0 + 0.5) / ppm
    inside = (xx - centre[0]) ** 2 + (yy - centre[1]) ** 2 <= radius**2
    inside &= rng.random(inside.shape) < 0.9
    rows, cols = rr[inside], cc[inside]
    z = np.zeros(rows.size, dtype=np.float32)
    return Mark(
        primitive=primitive, iy0=int(iy0), ix0=int(ix0), rows=rows, cols=cols, wet=z,
        col=np.zeros((rows.size, 3), np.float32), lateral=z, depth=z, shape=(n, n),
        segments=np.zeros((0, 2, 2)), area_bbox=0.0, height=0.0,
    )  # fmt: skip


def _trail(rng, kind, n=48, step=0.25):
    """A trail of the brush's kind: straight, curved, a zig-zag turning back, or a few points
    on one place (repeated points: zero-length segments)."""
    if kind == "still":
        return np.repeat(rng.random((1, 2)) * 3 + 20, n, axis=0)
    heading = rng.random() * 2 * np.pi
    turn = {"straight": 0.0, "curve": 0.08, "zigzag": 0.0}[kind] * rng.standard_normal()
    pts, here = [], np.array([20.0, 20.0])
    for i in range(n):
        if kind == "zigzag" and i % 12 == 11:
            heading += np.pi * 0.9  # a sharp turn back
        heading += turn
        here = here + step * np.array([np.cos(heading), np.sin(heading)])
        pts.append(here.copy())
    return np.array(pts)


@pytest.mark.parametrize("kind", ["straight", "curve", "zigzag", "still"])
@pytest.mark.parametrize("ppm", [3.0, 10.24, 20.48])
@pytest.mark.parametrize("sort_out", [False, True])
@pytest.mark.parametrize("levels", [1, 2, 3])
def test_fast_signed_distance_is_the_plain_measure_bit_for_bit(
    kind, ppm, sort_out, levels, monkeypatch
):
    """Also with the segments sorted out by tiles for every size of mark (``sort_out``), in
    one level of tiles or in several (blocks of tiles first)."""
    if sort_out:
        monkeypatch.setattr(trailpath, "PLAIN_ELEMENTS", 0)
    monkeypatch.setattr(trailpath, "TILE_LEVELS", levels)
    rng = np.random.default_rng(hash((kind, ppm)) % 2**32)
    for trial in range(6):
        path = _trail(rng, kind, n=int(rng.integers(2, 49)))
        end = path[-1]
        marks = [  # overlapping primitives' marks around the newest point, and one far away
            _mark(rng, i, end + rng.normal(0, 1.5, 2), rng.uniform(0.3, 4.0), ppm)
            for i in range(int(rng.integers(1, 6)))
        ]
        if trial % 3 == 0:
            marks.append(_mark(rng, 9, end + np.array([60.0, -40.0]), 1.0, ppm))
        want = plain_across(marks, path, ppm)
        st = bristles.BristleState(
            *(np.zeros((1, 1)),) * 3, np.ones(1), path, np.array([1.0, 0.0]), 10.0
        )
        got = bristles.across(marks, st, ppm)
        for g, w in zip(got, want, strict=True):
            assert g.lateral.dtype == np.float32
            np.testing.assert_array_equal(g.lateral.view(np.uint32), w.view(np.uint32))


def test_pixels_given_twice_get_the_same_distance():
    path = _trail(np.random.default_rng(1), "curve")
    rows = np.array([100, 101, 100, 250, 101])
    cols = np.array([200, 200, 200, 210, 200])
    got = trailpath.signed_distances(path, rows, cols, 10.0)
    assert got[0] == got[2] and got[1] == got[4]
    assert np.all(np.isfinite(got))


@pytest.mark.parametrize("kind", ["straight", "curve", "zigzag"])
def test_every_pixels_run_of_segments_holds_its_nearest_and_leaves_most_out(kind):
    """Each pixel's run of segments (from its tile) holds the first nearest segment of the
    plain measure, and a segment outside the run is farther by more than rounding; on a
    trail of 48 points the runs are short."""
    rng = np.random.default_rng(7)
    ppm = 10.24
    path = _trail(rng, kind)
    seg = trailpath.segments(path)
    rr, cc = np.mgrid[0:120, 0:120]
    r0, c0 = int(path[-1, 1] * ppm) - 60, int(path[-1, 0] * ppm) - 60
    ur, uc = rr.ravel(), cc.ravel()
    lo, hi = trailpath._segment_ranges(seg, ur, uc, r0, c0, ppm, path)
    x, y = (uc + c0 + 0.5) / ppm, (ur + r0 + 0.5) / ppm
    a, d, dd, tlo, thi = seg
    rx, ry = x[:, None] - a[:, 0], y[:, None] - a[:, 1]
    t = np.clip((rx * d[:, 0] + ry * d[:, 1]) / dd, tlo, thi)
    dist2 = (rx - t * d[:, 0]) ** 2 + (ry - t * d[:, 1]) ** 2
    k = np.argmin(dist2, axis=1)
    assert np.all((lo <= k) & (k < hi))
    inside = (np.arange(len(a)) >= lo[:, None]) & (np.arange(len(a)) < hi[:, None])
    best = dist2[np.arange(k.size), k]
    assert np.all(np.where(inside, True, dist2 > best[:, None] * (1 + 1e-9) + 1e-12))
    assert (hi - lo).mean() < 0.5 * len(a)


def _plain_bristles_across(marks, st, ppm):
    """``bristles.across`` as first written (the trail's start as in ``bristles.across``)."""
    path = st.trail
    if len(path) < 2:
        here = path[-1] if len(path) else np.zeros(2)
        path = np.stack([here - st.travel, here])
    lateral = iter(plain_across([mk for mk in marks if mk.rows.size], path, ppm))
    return [replace(mk, lateral=next(lateral)) if mk.rows.size else mk for mk in marks]


@pytest.mark.slow
@pytest.mark.parametrize(
    "primitives, size_px, ppm, samples", [(1, 2048, 10.24, 200), (8, 1024, 5.0, 120)]
)
def test_a_simulation_lays_the_same_bits_as_with_the_plain_measure(
    primitives, size_px, ppm, samples, monkeypatch
):
    """The benchmark's stroke, split brushes too: the paper and the brush after it are the same,
    bit for bit, with the plain measure of the trail's distances in its place."""
    from tests.sim.builders import long_stroke, simulation

    stroke = long_stroke()[:samples]
    fast = simulation(stroke, size_px, ppm, primitives).run()
    monkeypatch.setattr(bristles, "across", _plain_bristles_across)
    monkeypatch.setattr(  # the engine measures many small samples' marks at once (issue 28)
        bristles,
        "across_steps",
        lambda marks, states, ppm: [
            _plain_bristles_across(m, st, ppm) for m, st in zip(marks, states, strict=True)
        ],
    )
    plain = simulation(stroke, size_px, ppm, primitives).run()
    for name in ("ink", "wet", "last"):
        a, b = getattr(fast.paper, name), getattr(plain.paper, name)
        assert np.array_equal(a.view(np.uint8), b.view(np.uint8)), name
    assert np.count_nonzero(fast.paper.ink) > 1000  # the stroke laid ink
    for key, value in plain.brush.snapshot().items():
        if isinstance(value, np.ndarray):
            np.testing.assert_array_equal(fast.brush.snapshot()[key], value, err_msg=key)
