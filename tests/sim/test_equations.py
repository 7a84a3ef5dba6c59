# SPDX-License-Identifier: GPL-3.0-or-later
"""One test per equation, against values computed by hand from the paper's formulas."""

import math
from dataclasses import replace

import numpy as np
import pytest

from sim.brush.dynamics import REF_RATE, V_REF
from sim.brush.inertia import InertiaPredictor
from sim.brush.mark import Mark, compute_marks
from sim.brush.primitive import HairyBrush
from sim.core.params import BrushGeometry, InkSpec, QualityParams
from sim.paper.paper import FULL_WET, GRAIN_DEPTH, Paper, paper_grain

DT = 1.0 / REF_RATE  # per-step equations apply unscaled at the reference rate


def test_eq9_inertia_predictor_paper_defaults():
    p = InertiaPredictor(dt=1.0)
    out = [p([x, 0, 0, 0, 0, 0])[0] for x in (0.0, 10.0, 20.0, 30.0)]
    # S1 = .6*10 + .4*(0 + 0); S2 = .6*20 + .4*(6 + 6); S3 = .6*30 + .4*(16.8 + (4*10.8 + 2*6)/6)
    assert out == pytest.approx([0.0, 6.0, 16.8, 28.4])


def test_eq7_eq8_dipping_interpolates_to_the_dry_first_key_point(brush):
    ink = InkSpec(color=(0.2, 0.4, 0.6), wetness=0.8)
    brush.dip(ink, depth=0.5)
    # 9 key points, 3.75 mm apart: sarc >= 15 mm soaked (k = index 4)
    dens = np.array([0.8, 0.6, 0.4])
    frac = np.array([0, 0.25, 0.5, 0.75, 1, 1, 1, 1, 1])
    assert np.allclose(brush.wet[0], 0.8 * frac)
    assert np.allclose(brush.col[0], frac[:, None] * dens)
    assert brush.state == "dipping"


def test_eq10_eq11_eq12_stress_and_pressure(brush):
    b = brush
    b.wet[:] = 0.5
    r, L = b.r, b.L
    # undeformed (hdd = 0), round ellipse, tip a point (hsd = 1); S = pi r^2, hei = L
    stress, gamma = b.update_stress(np.array([math.pi * r * r]), np.array([L]), 100.0, DT)
    ab_area = b.a[0] * b.b[0] / 4 / r**2
    expect = (1 - 0.5) * (9 / 4.5) * 1.0 * 1.0 * ab_area
    assert stress[0] == pytest.approx(expect)
    assert gamma[0] == pytest.approx(100.0 / V_REF * expect * 0.5 * 0.5)


def test_eq11_hdd_measures_displacement_from_the_free_state(brush):
    b = brush
    b.wet[:] = 1.0
    b.cc[0, 1:, 0] += 2.0  # every key point but the first moved 2 mm sideways
    stress, _ = b.update_stress(np.array([math.pi * b.r**2]), np.array([b.L]), 0.0, DT)
    # his = hsd + hdd = 1 + 2 / L (hdd made dimensionless by the hair length)
    base = (1 - 0.5) * 1.0 * 1.0 * (b.a[0] * b.b[0] / 4 / b.r**2)
    assert stress[0] == pytest.approx(base * (1 + 2.0 / b.L), rel=1e-6)


def test_eq13_active_point_inserted_with_interpolated_ink(brush):
    b = brush
    b.place([50, 50, 20, 0, 0, 0])
    new = b._rest_world(b.sarc, b.B, b.R)  # straight down through the paper, unclamped
    b.wet[0] = np.linspace(0, 0.8, 9)  # wet_5 = 0.5, wet_6 = 0.6 (0-based)
    b._insert_active_point(new)
    # crossing between sarc 18.75 (z = 1.25) and 22.5 (z = -2.5): at sarc 20, lam = 1/3
    j = b.active[0]
    assert b.n == 9 and b.cc.shape == (1, 9, 3)
    assert b.sarc[0, j] == pytest.approx(20.0)
    assert b.cc[0, j, 2] == 0.0
    assert b.wet[0, j] == pytest.approx((2 / 3) * 0.5 + (1 / 3) * 0.6)
    assert np.all(np.diff(b.sarc[0]) > 0)


def test_eq14_lifting_raises_key_points(brush):
    """Eq. 14: lifting the brush by dsz > 0 raises the free key points by gamma * dsz besides
    carrying them up with the brush (by dsz); the hair held on the paper stays there (the hair
    pressing above holds it) unless the lifted base pulls it off."""
    b = brush
    b.place([50, 50, 20, 0, 0, 0])  # hair 30 mm: its last three key points lie on the paper
    b.gamma[:] = 0.5
    before = b.cc[0, 1:].copy()
    held = before[:, 2] <= 0.0
    assert held.sum() == 3
    b.move([50, 50, 21, 0, 0, 0], np.zeros(6), DT)
    lift = 1.0
    expect = np.where(held, 0.0, before[:, 2] + lift + 0.5 * lift)
    np.testing.assert_allclose(b.cc[0, 1:, 2], expect, rtol=0, atol=1e-12)
    free = ~held
    np.testing.assert_array_equal(b.cc[0, 1:][free, :2], before[free, :2])  # straight up
    for _ in range(2):  # lifted past the hair's length: it pulls the lying hair off
        b.move([50, 50, 31, 0, 0, 0], np.zeros(6), DT)
    assert np.all(b.cc[0, 1:, 2] > 0.0)
    assert b.active[0] == -1  # nothing is on the paper any more


def test_eq15_wetness_loss_around_the_active_point(brush):
    b = brush
    b.wet[:] = 0.5
    b.active[:] = 4
    b.touching[:] = True
    b.gamma[:] = 0.2
    b.lose_wetness(DT)
    ab = b.q.ab
    loss = np.array([ab * 0.2 / 2 ** (abs(j - 4) + (1 if j == 4 else 2)) for j in range(9)])
    assert np.allclose(b.wet[0], 0.5 - loss)


def test_eq16_rotation_along_minor_axis_and_elongation_across(brush):
    b = brush
    b.touching[:] = True
    b.gamma[:] = 0.5
    area = b.a[0] * b.b[0]
    b.adjust_ellipse(np.array([0.0, V_REF, 0, 0, 0, 0]), DT)  # along eori = +y
    rot = b.q.re * 0.5 * 1.0
    assert b.eori[0, :2] == pytest.approx([-math.sin(rot), math.cos(rot)])
    assert b.a[0] * b.b[0] == pytest.approx(area)
    b2 = HairyBrush(BrushGeometry(), QualityParams(), np.random.default_rng(0))
    b2.touching[:] = True
    b2.gamma[:] = 0.5
    a0 = b2.a[0]
    b2.adjust_ellipse(np.array([V_REF, 0.0, 0, 0, 0, 0]), DT)  # across eori
    inc = b2.q.ie * 0.5 * 1.0
    assert b2.a[0] == pytest.approx(a0 + inc * b2.r)
    assert math.pi * b2.a[0] * b2.b[0] / 4 == pytest.approx(math.pi * a0 * a0 / 4)  # Sec. 5.3
    assert b2.tiplen[0] == pytest.approx(inc * b2.r)  # Sec. 5.4


def test_eq17_relocation_toward_the_middle_of_the_key_points(brush):
    b = brush
    b.touching[:] = True
    loc0 = b.loc[0]
    b.adjust_ellipse(np.zeros(6), DT)
    # evenly spaced: (1/n) sum_{j=1}^{n-1} j/(n-1) = 1/2
    assert b.loc[0] == pytest.approx(0.75 * loc0 + 0.25 * 0.5)


def test_eq18_eq19_split_keeps_the_hair(brush):
    b = brush
    b.q = QualityParams(tre=0.3)
    b.touching[:] = True
    b.stress[:] = 1.0
    b.tiplen[:] = 3.0
    a0, area0 = b.a[0], b.hair_area()
    assert b.split() == 2  # k = floor(1.0 / 0.3) = 3 primitives
    assert b.m == 3
    assert np.allclose(b.a, a0 / math.sqrt(3)) and np.allclose(b.tiplen, 1.0)
    assert b.hair_area() == pytest.approx(area0)
    assert np.allclose(b.cc[:, 0], b.B)  # the bottom control circle is shared
    off = np.linalg.norm(b.cc[:, -1] - b.cc[0, -1], axis=1)
    assert off.max() > 0  # children spread apart, by (str - tre) * r at most at the tip
    assert np.all(
        np.linalg.norm(b.cc[:, -1] - b._rest_world(b.sarc, b.B, b.R)[:, -1], axis=1)
        <= (1.0 - 0.3) * b.r + 1e-9
    )


def test_eq20_ink_flows_between_nearby_primitives(brush):
    b = brush
    b.touching[:] = True
    b.stress[:] = 0.9
    b.q = QualityParams(tre=0.45)
    b.split()
    b.cc[1] = b.cc[0]  # the two clusters lie on each other
    b.wet[0], b.wet[1] = 0.2, 0.8
    b.ink_flow()
    pw = b.q.pw
    assert np.allclose(b.wet[0], 0.2 * (1 - pw) + 0.8 * pw)
    assert np.allclose(b.wet[1], 0.8 * (1 - pw) + 0.2 * pw)


def test_eq21_to_23_pixel_ink_is_the_texture_function_at_the_pixel(brush):
    """With V^ on a vertical axis, Eq. 22 + 23 reduce to Eq. 5 at the pixel's offset."""
    b = brush
    b.place([50, 50, 25, 0, 0, 0])
    b.cc = b._rest_world(b.sarc, b.B, b.R)  # straight, crossing psi at (50, 50)
    b.wet[:] = 0.8
    b.col[:] = 0.5
    b.wr[:] = -0.05
    b.cr[:] = 0.1
    sec = b.sections()
    (mk,) = compute_marks(b, sec, b.rows_ink(sec), 10.0, (1000, 1000))
    px = (mk.cols + mk.ix0 + 0.5) / 10.0
    py = (mk.rows + mk.iy0 + 0.5) / 10.0
    dist = np.hypot(px - 50, py - 50)
    assert mk.rows.size > 100
    assert np.allclose(mk.wet, 0.8 * (1 - 0.05 * dist), atol=1e-6)
    # the colour, where the section covers the whole pixel (model addition: at the edge, the
    # share it covers, sim.brush.mark.section_cover)
    col = 0.5 * (1 + 0.1 * dist)
    whole = dist < dist.max() - 0.15
    assert whole.mean() > 0.8 and np.allclose(mk.col[whole, 0], col[whole], atol=1e-6)
    assert np.all(mk.col[:, 0] <= col + 1e-6)
    # the mark is the round section of the tapering tip: radius from the profile
    alpha, _ = b.profile_semiaxes(np.array([25 / 30]))
    assert dist.max() == pytest.approx(alpha[0, 0], abs=0.15)


def _one_pixel_mark(wet, col):
    return Mark(
        primitive=0,
        iy0=1,
        ix0=1,
        rows=np.array([0]),
        cols=np.array([0]),
        wet=np.array([wet]),
        col=np.array([col]),
        lateral=np.array([0.0]),
        depth=np.array([0.0]),
        shape=(1, 1),
        segments=np.zeros((0, 2, 2)),
        area_bbox=1.0,
        height=1.0,
    )


def _plain_paper(*args, **kwargs) -> Paper:
    """A paper with only the paper's equations: no wicking (a model addition, tested in
    test_paper_wicking)."""
    paper = Paper(*args, **kwargs)
    paper.wick_passes = 0
    return paper


def test_eq24_eq26_absorption_and_colour():
    q = QualityParams(ab=0.5, ren=0.0, dry=0.0)
    paper = _plain_paper(4, 4, 1.0)  # no fibre: the grain is off
    mk = _one_pixel_mark(0.8, [0.5, 0.5, 0.5])
    paper.deposit([mk], q, DT, 1)
    assert paper.wet[1, 1] == pytest.approx(0.4)  # Eq. 24: .5 * 0 + .5 * .8
    # Eq. 26 as the model changes it (sim.paper.laying.FULL_WET): the colour the liquid offered
    # can hold, at once
    held = 0.5 * (1.0 - np.exp(-0.8 / FULL_WET))
    assert paper.ink[1, 1, 0] == pytest.approx(held, rel=1e-5)
    paper.deposit([mk], q, DT, 2)
    assert paper.wet[1, 1] == pytest.approx(0.6)
    assert paper.ink[1, 1, 0] == pytest.approx(held, rel=1e-5)  # the same offer, the same colour
    paper.deposit([_one_pixel_mark(0.1, [0.5, 0.5, 0.5])], q, DT, 3)
    assert paper.ink[1, 1, 0] == pytest.approx(held, rel=1e-5)  # a drier pass takes none back
    paper.deposit([_one_pixel_mark(2.0, [0.5, 0.5, 0.5])], q, DT, 4)
    assert held < paper.ink[1, 1, 0] <= 0.5  # a wetter one (a pool) lays more, up to the ink's
    # the sheet's grain changes the offer a pixel takes, a pixel at a time, by +- fibre / 4
    grainy = _plain_paper(4, 4, 1.0, fibre=0.8)
    grainy.deposit([mk], q, DT, 1)
    g = 1.0 - GRAIN_DEPTH * 0.8 * (float(paper_grain(1 * 4 + 1)) - 0.5)
    assert grainy.ink[1, 1, 0] == pytest.approx(0.5 * (1.0 - np.exp(-0.8 * g / FULL_WET)), 1e-5)


def test_eq27_dry_brush_leaves_the_pixel_as_it_was():
    # Cr = 0 where the hair bundle lays no ink (its gap, sim.brush.bristles): no colour, but
    # Eq. 24's wetness still
    paper = _plain_paper(4, 4, 1.0)
    mk = replace(_one_pixel_mark(0.8, [0.5, 0.5, 0.5]), skip=np.array([True]))
    paper.deposit([mk], QualityParams(ab=0.5, ren=1.0, dry=0.0), DT, 1)
    assert paper.ink[1, 1, 0] == 0 and paper.wet[1, 1] == pytest.approx(0.4)


def test_eq24_lazy_drying_equals_drying_every_step():
    q = QualityParams(ab=0.3, ren=0.0)
    d = 0.02
    lazy = _plain_paper(4, 4, 1.0, dry_per_step=d)
    mk = _one_pixel_mark(0.9, [1, 1, 1])
    lazy.deposit([mk], q, DT, 1)
    lazy.deposit([mk], q, DT, 10)
    w = max(0.7 * 0.9 - d, 0)
    for _ in range(8):  # steps 2..9 dry it
        w = max(w - d, 0)
    assert lazy.wet[1, 1] == pytest.approx(max(0.3 * w + 0.7 * 0.9 - d, 0), abs=1e-6)


def test_eq25_saturation_spreads_to_unsaturated_neighbours():
    w = np.full((3, 3), 0.5, dtype=np.float32)
    w[1, 1] = 1.5
    ink = np.zeros((3, 3, 3), dtype=np.float32)
    ink[1, 1] = 1.0
    Paper._saturate(w, ink, 1.0)
    assert w[1, 1] == pytest.approx(1.0)
    assert w[0, 0] == pytest.approx(0.5 + 0.5 * 0.5 / 4.0)  # unsat 0.5 of rho = 8 * 0.5
    assert w.sum() == pytest.approx(0.5 * 8 + 1.5)  # water is conserved
    assert 0 < ink[0, 0, 0] < 1  # the ink goes with it, diluted


def test_split_respects_the_primitive_cap(brush):
    b = brush
    b.max_primitives = 3
    b.touching[:] = True
    b.stress[:] = 10.0
    b.q = QualityParams(tre=0.1)
    b.split()
    assert b.m == 3
    b.touching[:] = True
    b.stress[:] = 10.0
    assert b.split() == 0 and b.m == 3


def test_every_primitive_field_is_declared_once_and_kept_by_snapshots(brush):
    """The fields of key points and primitives are those of ``brush_state.FIELDS``: every array
    of the brush with a row per primitive is one of them, and a snapshot taken before a split
    brings all of them back."""
    from sim.brush.state import FIELDS, KEY

    b = brush
    assert b.split_under(4.5 * b.q.tre) == 3 and b.m == 4  # 4 rows: no pose vector has 4
    declared = {f.name for f in FIELDS}
    per_primitive = {k for k, v in vars(b).items() if isinstance(v, np.ndarray) and len(v) == 4}
    assert per_primitive == declared
    for f in FIELDS:
        lead = (b.m, b.n) if f.per == KEY else (b.m,)
        assert getattr(b, f.name).shape == lead + f.shape
    snap = b.snapshot()
    assert b.split_under(2.5 * b.q.tre) == 4 and b.m == 8
    b.restore(snap)
    again = b.snapshot()
    assert b.m == 4 and set(again) == set(snap)
    for k, v in snap.items():
        assert np.array_equal(again[k], v), k


def test_a_diluted_ink_needs_more_liquid_for_its_colour():
    """Light ink (``InkSpec.pigment`` below 1) carries less pigment in the same liquid: a quick,
    thin offer lays a paler share of its colour than a full-strength ink's, a soaking one
    nearly all of it - the tone of a pale stroke follows how long the hair lingered."""
    from sim.core.params import ink_from_preset, load_preset

    assert ink_from_preset(load_preset("ink", "sumi_black")).pigment == 1.0
    assert ink_from_preset(load_preset("ink", "light_ink")).pigment == 0.5
    q = QualityParams(ab=0.5, ren=0.0, dry=0.0)
    ratio = {}
    for pigment in (1.0, 0.5):
        taken = []
        for offer in (0.3, 2.0):  # quick and thin; lingering
            paper = _plain_paper(4, 4, 1.0)
            paper.pigment = pigment
            paper.deposit([_one_pixel_mark(offer, [0.5, 0.5, 0.5])], q, DT, 1)
            taken.append(float(paper.ink[1, 1, 0]))
        assert taken[1] <= 0.5 and taken[1] > 0.45  # a soaked pixel takes the ink's colour
        ratio[pigment] = taken[0] / taken[1]
    assert ratio[0.5] < ratio[1.0] - 0.15  # the quick pass much paler for the diluted ink
    assert ratio[0.5] == pytest.approx(
        (1 - np.exp(-0.3 * 0.5 / FULL_WET)) / (1 - np.exp(-4.0)), 1e-4
    )
