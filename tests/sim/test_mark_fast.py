# SPDX-License-Identifier: GPL-3.0-or-later
"""The fast current-drawing-mark rasteriser (scanline spans of cur_u, contact rows only, one
candidate section unless the axis folds) gives exactly the marks of the plain reference that
tests every bounding-box pixel against every row of the surface."""

import time

import numpy as np
import pytest

from sim.brush.mark import compute_marks
from sim.engine.simulation import Simulation
from tests.sim.builders import character, long_stroke, simulation, stepped
from tests.sim.reference_mark import reference_marks


def _states(primitives, ppm, every=37):
    """Brush states along a long pressed zig-zag stroke (bent, spread and split brushes)."""
    return stepped(simulation(long_stroke(), int(200 * ppm), ppm, primitives), every)


def _assert_marks_equal_reference(sims, ppm):
    """At every state of ``sims``: the fast marks have exactly the reference's pixels, and the
    same ink. Returns (marks compared, pixels compared)."""
    checked = pixels = 0
    for sim in sims:
        b = sim.brush
        sec = b.sections()
        ink = b.rows_ink(sec)
        fast = [mk for mk in compute_marks(b, sec, ink, ppm, sim.paper.shape) if mk.rows.size]
        ref = [mk for mk in reference_marks(b, sec, ink, ppm, sim.paper.shape) if mk.rows.size]
        assert [mk.primitive for mk in fast] == [mk.primitive for mk in ref]
        for a, r in zip(fast, ref, strict=True):
            ka = (a.rows + a.iy0) * 10**5 + a.cols + a.ix0
            kr = (r.rows + r.iy0) * 10**5 + r.cols + r.ix0
            oa, orr = np.argsort(ka), np.argsort(kr)
            np.testing.assert_array_equal(ka[oa], kr[orr])
            # the ink is float32, as the paper keeps it: equal to its rounding
            np.testing.assert_allclose(a.wet[oa], r.wet[orr], rtol=0, atol=5e-7)
            np.testing.assert_allclose(a.col[oa], r.col[orr], rtol=0, atol=5e-7)
            np.testing.assert_allclose(a.lateral[oa], r.lateral[orr], atol=1e-9)
            np.testing.assert_allclose(a.depth[oa], r.depth[orr], atol=1e-6)
            assert a.area_bbox == pytest.approx(r.area_bbox)
            checked += 1
            pixels += a.rows.size
    return checked, pixels


@pytest.mark.slow
@pytest.mark.parametrize("primitives, ppm, every", [(1, 10.24, 23), (16, 6.0, 37), (4, 20.48, 29)])
def test_fast_marks_equal_reference(primitives, ppm, every):
    checked, pixels = _assert_marks_equal_reference(_states(primitives, ppm, every), ppm)
    assert checked >= 5 and pixels > 1000


@pytest.mark.slow
def test_fast_marks_equal_reference_on_a_written_character():
    """The demo character (wolf brush, pressed and split): many pixels lie between several
    pairs of section planes, of which only the first and the last slab count."""
    sim = Simulation(character(6.0))
    checked, _ = _assert_marks_equal_reference(stepped(sim, 31), 6.0)
    assert checked > 20 and sim.brush.splits > 0


@pytest.mark.slow
def test_fast_marks_equal_reference_with_a_texture_function_that_varies():
    """Eq. 22 with the texture function (radiation and vector modes) changing from key point to
    key point, not one ink's everywhere: the fast marks' ink still equals the reference."""

    def states():
        for sim in _states(4, 10.24, 31):
            b = sim.brush
            kept = b.wr, b.cr, b.wv, b.cv
            j = np.linspace(0.0, 1.0, b.n)[None, :]
            b.wr = -0.05 + 0.04 * j + 0.01 * np.arange(b.m)[:, None]
            b.cr = 0.08 - 0.1 * j + 0.0 * b.cr
            b.wv = np.array([0.03, -0.02, 0.01]) * (1 + j[..., None]) + 0.0 * b.wv
            b.cv = np.array([-0.01, 0.04, 0.02]) * (2 - j[..., None]) + 0.0 * b.cv
            yield sim
            b.wr, b.cr, b.wv, b.cv = kept  # the stroke goes on as it was

    checked, pixels = _assert_marks_equal_reference(states(), 10.24)
    assert checked >= 5 and pixels > 1000


@pytest.mark.slow
def test_marks_evaluated_in_bands_are_the_same_marks(monkeypatch):
    """Many large marks are evaluated in bands of scanlines (bounded memory); a band may cut a
    mark in two. The marks are the same, bit for bit."""
    import sim.brush.mark as mark

    compared = 0
    for sim in _states(16, 6.0, 53):
        b = sim.brush
        sec = b.sections()
        ink = b.rows_ink(sec)
        whole = compute_marks(b, sec, ink, 6.0, sim.paper.shape)
        monkeypatch.setattr(mark, "BATCH_PIXELS", 300)
        banded = compute_marks(b, sec, ink, 6.0, sim.paper.shape)
        monkeypatch.undo()
        assert len(whole) == len(banded)
        for a, c in zip(whole, banded, strict=True):
            ka = a.rows * 10**5 + a.cols
            kc = c.rows * 10**5 + c.cols
            oa, oc = np.argsort(ka), np.argsort(kc)
            np.testing.assert_array_equal(ka[oa], kc[oc])
            np.testing.assert_array_equal(a.wet[oa], c.wet[oc])
            np.testing.assert_array_equal(a.col[oa], c.col[oc])
            compared += a.rows.size
    assert compared > 10 * 300


@pytest.mark.slow
def test_a_span_that_cuts_the_solid_short_is_scanned_again(monkeypatch):
    """With no margin past cur_u, the solid often reaches the end of a span (where the surface
    grazes the paper); those marks are scanned again over the whole cut, so they still equal
    the reference."""
    import sim.brush.mark as mark

    calls = {"windows": 0, "again": 0}
    plain = mark._marks_ink

    def counting(*args):
        out = plain(*args)
        calls["windows"] += len(args[0])
        calls["again"] += int(out[1].sum())
        return out

    monkeypatch.setattr(mark, "SPAN_MARGIN_PX", 0.0)
    monkeypatch.setattr(mark, "_marks_ink", counting)
    checked, _ = _assert_marks_equal_reference(_states(4, 20.48, 41), 20.48)
    assert checked >= 5 and calls["again"] > 0


@pytest.mark.slow
def test_batched_deposit_equals_one_mark_after_another():
    """Overlapping primitives visit a pixel several times in one step; the batched deposit
    takes the visits in the marks' order and gives the plain loop's paper bit for bit."""
    from sim.paper.paper import Paper
    from tests.sim.reference_paper import reference_deposit

    s = long_stroke()[:260]
    a = simulation(s, 1200, 6.0, 16)
    b = simulation(s, 1200, 6.0, 16)
    for sim in (a, b):
        sim.paper.dry_per_step = 0.004  # lazy drying on
        sim.paper.fibre = 0.7  # the sheet's grain
        sim.q = sim.brush.q = sim.brush.q.with_values({"ren": 1.0, "ab": 0.6})
    b.paper.deposit = lambda *args: reference_deposit(b.paper, *args, saturate=Paper._saturate)
    overlap = 0
    while not a.done:
        a.step()
        b.step()
        marks = [mk for mk in a.last_marks if mk.rows.size]
        if len(marks) > 1:
            idx = np.concatenate([(mk.rows + mk.iy0) * 10**5 + mk.cols + mk.ix0 for mk in marks])
            overlap += idx.size - np.unique(idx).size
    assert overlap > 1000
    assert a.paper.wet.tobytes() == b.paper.wet.tobytes()
    assert a.paper.ink.tobytes() == b.paper.ink.tobytes()
    assert a.paper.last.tobytes() == b.paper.last.tobytes()
    assert np.count_nonzero(a.paper.ink) > 1000


def test_banded_uint8_image_and_png_equal_the_float_image(tmp_path):
    from sim.image.png import read_png, to_uint8, write_png

    sim = simulation(long_stroke(), 700, 3.5, 1)
    sim.paper.ink[...] = np.random.default_rng(3).random(sim.paper.ink.shape, dtype=np.float32)
    img8 = sim.image8()
    np.testing.assert_array_equal(img8, to_uint8(sim.image()))
    wide = np.concatenate([img8] * 4, axis=1)  # rows of 8400 bytes: several bands per file
    write_png(tmp_path / "a.png", wide)
    np.testing.assert_array_equal(read_png(tmp_path / "a.png"), wide)


def test_box_sum_saturation_equals_neighbour_by_neighbour():
    """Eq. 25 by 3 x 3 box sums gives the plain neighbour-by-neighbour spreading (to float32
    rounding) and keeps the water."""
    from sim.paper.paper import Paper
    from tests.sim.reference_paper import reference_saturate

    rng = np.random.default_rng(5)
    w = rng.random((60, 70), dtype=np.float32) * 1.6
    w[rng.random(w.shape) < 0.5] *= 0.3
    ink = rng.random((60, 70, 3), dtype=np.float32)
    a_w, a_ink = w.copy(), ink.copy()
    b_w, b_ink = w.copy(), ink.copy()
    Paper._saturate(a_w, a_ink, 1.0)
    reference_saturate(b_w, b_ink, 1.0)
    assert np.abs(a_w - w).max() > 0.1  # it did spread
    np.testing.assert_allclose(a_w, b_w, rtol=0, atol=2e-6)
    np.testing.assert_allclose(a_ink, b_ink, rtol=0, atol=2e-6)
    assert a_w.sum(dtype=np.float64) == pytest.approx(w.sum(dtype=np.float64), rel=1e-5)


@pytest.mark.slow
def test_run_fills_marks_for_several_samples_at_once_and_equals_step_by_step():
    """``run`` lets the brush run ahead of the paper and fills several samples' marks in one
    pass; the paper is the same, bit for bit, as one sample at a time (a written character with
    dips and splits), also when run stops and goes on, or snapshots in between."""
    from sim.core.recording import Dip
    from sim.engine.simulation import BATCH_STEPS

    rec = character(4.0)
    rec.dips.append(Dip(411, 0.7, (0.6, 0.1, 0.1), 0.9))  # a second dip, mid-batch
    a = Simulation(rec).run()
    b = Simulation(rec)
    while not b.done:
        b.step()
    c = Simulation(rec).run(until=5 * BATCH_STEPS + 3)
    snap = c.snapshot()
    c.run(until=c.index + 2)
    c.restore(snap)
    c.run()
    assert a.brush.splits > 0 and len(rec.dips_or_default()) > 1
    for other in (b, c):
        assert a.paper.ink.tobytes() == other.paper.ink.tobytes()
        assert a.paper.wet.tobytes() == other.paper.wet.tobytes()
        assert a.paper.last.tobytes() == other.paper.last.tobytes()
    assert [mk.primitive for mk in a.last_marks] == [mk.primitive for mk in b.last_marks]


@pytest.mark.slow
def test_timings_split_a_run_into_its_stages_without_changing_it():
    """The benchmark's per-stage figures: every sample's time lands in a named stage, and
    keeping timings does not change the artwork."""
    from sim.cli.bench import STAGES, samples_per_second

    s = long_stroke()[:90]
    a, b = simulation(s, 400, 2.0, 4), simulation(s, 400, 2.0, 4)
    a.timings = {}
    t0 = time.perf_counter()
    a.run()
    total = time.perf_counter() - t0
    b.run()
    assert a.paper.ink.tobytes() == b.paper.ink.tobytes()
    assert set(a.timings) == set(STAGES)
    assert all(v > 0 for v in a.timings.values())
    assert sum(a.timings.values()) <= total
    stages = {}
    rate, m = samples_per_second(s, 400, 2.0, 4, repeats=1, stages=stages)
    assert rate > 0 and m == 4
    assert set(stages) == set(STAGES) | {"other"} and stages["other"] >= 0
    assert 0.5 < sum(stages.values()) * rate / 1e3 <= 1.01  # ms a sample add up to the rate


def test_per_pixel_stages_in_cache_sized_runs_are_the_same_bits():
    """The section solve and the cover run over runs of whole intervals of about
    CHUNK_ENTRIES entries (issue 28): every run's entries are those of its intervals, the runs
    cover every interval once, in order, and the answers are those of one run over all of
    them, bit for bit."""
    import sim.brush.mark as mark

    rng = np.random.default_rng(3)
    count = rng.integers(0, 40, 3000)  # intervals of 0..39 entries (empty ones too)
    count[:5] = 0
    E = int(count.sum())
    assert E > 5 * mark.CHUNK_ENTRIES
    for size in (1, 37, mark.CHUNK_ENTRIES, 10 * E):
        runs = list(mark._interval_chunks(count, size))
        assert runs[0][0] == 0 and runs[0][2] == 0 and runs[-1][1] == len(count)
        assert runs[-1][3] == E
        for (_, i1, _, e1), (j0, _, f0, _) in zip(runs[:-1], runs[1:], strict=True):
            assert i1 == j0 and e1 == f0
        for i0, i1, e0, e1 in runs:  # about ``size`` entries: at most one interval more
            assert i1 > i0 and e1 - e0 == count[i0:i1].sum() <= size + count.max()
        assert len(runs) == 1 if size >= E else len(runs) > 1

    iq = mark.IntervalQuadratics._make(rng.normal(size=(23, len(count))))
    x = rng.normal(size=E)
    chunked = mark._section_solve(iq, count, x)
    whole = mark._section_solve_run(np.stack(iq), count, x)
    for a, b in zip(chunked, whole, strict=True):
        assert a.tobytes() == b.tobytes()

    U = rng.normal(size=(len(count), 3))
    V = rng.normal(size=(len(count), 3))
    dU, dV = 0.1 * rng.normal(size=U.shape), 0.1 * rng.normal(size=V.shape)
    rk = mark.ContactRows(
        c=None,
        U=np.stack([U, U + dU], axis=1),
        V=np.stack([V, V + dV], axis=1),
        T=None,
        slab_ok=None,
        j0=0,
        j1=2,
    )
    lam, p, q = rng.random(E), rng.normal(size=E), rng.normal(size=E)
    slab = np.arange(len(count))
    got = mark._cover(rk, slab, count, lam, p, q, 8.0)
    L = lam[:, None]
    Ue = np.repeat(U, count, axis=0) + L * np.repeat(np.diff(rk.U, axis=1)[:, 0], count, axis=0)
    Ve = np.repeat(V, count, axis=0) + L * np.repeat(np.diff(rk.V, axis=1)[:, 0], count, axis=0)
    assert got.tobytes() == mark.section_cover(Ue, Ve, p, q, 8.0).tobytes()
