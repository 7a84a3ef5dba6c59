# SPDX-License-Identifier: GPL-3.0-or-later
"""The realism measure (sim.fitting.realism, issue 26 point 5): its image tools against
scipy's, and its answers on images whose structure is known - a flat glyph, the same glyph
with streaks along and across its strokes, with isotropic pixel noise, with specks around it,
with its tone changing along the strokes - and on a font against the brush's own writing of a
character the engine was not tuned on."""

import json

import numpy as np
import pytest

from sim.fitting import realism as R
from tests.paths import ROOT

PAPER = np.array([0.95, 0.93, 0.87])
INK = np.array([0.03, 0.03, 0.04])


def glyph(n=320):
    """A 'ten' of two bars, 4x supersampled, as a coverage image in [0, 1]."""
    k = 4
    yy, xx = np.mgrid[0 : n * k, 0 : n * k] / k
    m = ((np.abs(yy - n / 2) < 14) & (np.abs(xx - n / 2) < 120)) | (
        (np.abs(xx - n / 2) < 14) & (np.abs(yy - n / 2) < 130)
    )
    return m.reshape(n, k, n, k).mean(axis=(1, 3)), yy[::k, ::k], xx[::k, ::k]


def rgb(cover):
    c = np.clip(cover, 0.0, 1.0)[..., None]
    return PAPER * (1 - c) + INK * c


def streaked(cover, yy, xx, along=True, seed=0):
    """Light streaks 1-3 px wide running along (or across) each bar."""
    rng = np.random.default_rng(seed)
    out = cover.copy()
    n = cover.shape[0]
    horiz_bar = np.abs(yy - n / 2) < 14
    for lo in rng.choice(np.arange(n), size=n // 7, replace=False):
        wdt = rng.integers(1, 3)
        # in the horizontal bar, along = a line of constant y; in the vertical one, of constant x
        if along:
            line = np.where(horiz_bar, np.abs(yy - lo) < wdt, np.abs(xx - lo) < wdt)
        else:
            line = np.where(horiz_bar, np.abs(xx - lo) < wdt, np.abs(yy - lo) < wdt)
        start = rng.integers(0, n)
        span = (np.where(horiz_bar, xx, yy) - start) % n < n // 3
        out = np.where(line & span, out * 0.15, out)
    return out


def test_the_grey_morphology_equals_scipys():
    ndimage = pytest.importorskip("scipy.ndimage")
    morphology = pytest.importorskip("skimage.morphology")
    a = np.random.default_rng(3).random((60, 70))
    disk = morphology.disk(R.FINE).astype(bool)
    np.testing.assert_allclose(
        R._grey(a, R.FINE, np.maximum, 0.0),
        ndimage.grey_dilation(a, footprint=disk, mode="constant", cval=0.0),
    )
    np.testing.assert_allclose(
        R._grey(a, R.FINE, np.minimum, 1.0),
        ndimage.grey_erosion(a, footprint=disk, mode="constant", cval=1.0),
    )


@pytest.mark.slow
def test_a_flat_glyph_has_no_structure_and_scores_near_zero():
    cover, _, _ = glyph()
    r = R.realism(rgb(cover))
    assert abs(r.streaks) < 0.01 and r.noise < 0.01 and r.specks == 0 and r.tone < 0.01
    assert r.score < 0.05


@pytest.mark.slow
def test_streaks_along_the_strokes_count_and_across_them_do_not():
    cover, yy, xx = glyph()
    flat = R.realism(rgb(cover))
    along = R.realism(rgb(streaked(cover, yy, xx, along=True)))
    across = R.realism(rgb(streaked(cover, yy, xx, along=False)))
    assert along.streaks > 0.1 > flat.streaks + 0.05
    assert across.streaks < -0.05  # structure across the stroke: the wrong way round
    assert across.noise > 3 * along.noise
    assert along.streak_score > 0.4 and across.streak_score == 0.0
    assert along.score > across.score + 0.1 and along.score > flat.score + 0.1


@pytest.mark.slow
def test_isotropic_pixel_noise_and_specks_are_no_texture():
    cover, yy, xx = glyph()
    rng = np.random.default_rng(5)
    flat = R.realism(rgb(cover))
    # stipple: every pixel near the edge flips at random (spray paint)
    edge = (cover > 0.02) & (cover < 0.98)
    near = np.zeros_like(edge)
    for dy in range(-3, 4):
        for dx in range(-3, 4):
            near |= np.roll(np.roll(edge, dy, 0), dx, 1)
    stipple = np.where(near, (rng.random(cover.shape) < 0.5).astype(float), cover)
    st = R.realism(rgb(stipple))
    assert st.noise > 0.1 and abs(st.streaks) < 0.5 * st.noise
    assert st.specks > 1.0  # isolated specks around the strokes
    assert st.score < flat.score + 0.05
    # grain over the whole ink: pixel noise, no tone at stroke scale
    grain = R.realism(rgb(cover * (1 - 0.4 * rng.random(cover.shape))))
    assert grain.noise > 0.05 and grain.tone < 0.02
    assert grain.score < flat.score + 0.05
    # the streaked glyph with the same grain still beats the grainy one
    streak_grain = streaked(cover, yy, xx) * (1 - 0.4 * rng.random(cover.shape))
    assert R.realism(rgb(streak_grain)).score > grain.score + 0.05


@pytest.mark.slow
def test_tone_at_stroke_scale_counts_and_pixel_noise_does_not():
    cover, yy, xx = glyph()
    n = cover.shape[0]
    # the ink fades along each bar (a brush running dry): from full to 0.55
    fade = 1.0 - 0.45 * np.clip(np.where(np.abs(yy - n / 2) < 14, xx, yy) / n, 0, 1)
    faded = R.realism(rgb(cover * fade))
    flat = R.realism(rgb(cover))
    assert faded.tone > 0.08 and faded.tone_score > 0.5 and faded.score > flat.score + 0.2
    assert abs(faded.streaks) < 0.02 and faded.noise < 0.02  # a slow change is no texture
    # the same fade seen through pixel noise: the tone is the same, the noise is not texture
    rng = np.random.default_rng(7)
    noisy = R.realism(rgb(cover * fade * (1 - 0.3 * rng.random(cover.shape))))
    assert abs(noisy.tone - faded.tone) < 0.2 * faded.tone
    assert noisy.score < faded.score


@pytest.mark.slow
def test_the_measure_reads_a_character_the_same_at_any_resolution():
    cover, yy, xx = glyph(320)
    img = rgb(streaked(cover, yy, xx))
    small = img.reshape(160, 2, 160, 2, 3).mean(axis=(1, 3))
    a, b = R.realism(img), R.realism(small)
    assert abs(a.half_width - b.half_width) < 0.1 * a.half_width
    assert b.streaks > 0.5 * a.streaks > 0.03


def test_an_empty_image_is_refused():
    with pytest.raises(ValueError, match="no ink"):
        R.realism(np.ones((50, 50, 3)))


@pytest.mark.slow
@pytest.mark.parametrize("name", ["口", "王"])
def test_the_brushs_writing_beats_the_flat_font_of_an_unseen_character(name):
    from sim.core.recording import Recording
    from sim.writing.outline import rasterise
    from sim.writing.writer import write_character

    ch = json.loads((ROOT / "tests" / "data" / "unseen" / f"{name}.json").read_text("utf-8"))
    n = 256
    font = rasterise(ch, 4 * n).reshape(n, 4, n, 4).mean(axis=(1, 3))
    template = Recording(np.zeros((1, 6)))
    _, _, sim = write_character(ch, n, template)
    brush = R.realism(sim.image())
    flat = R.realism(rgb(font))
    assert flat.score < 0.05
    assert brush.score > flat.score + 0.05
    assert brush.tone > 2 * flat.tone and brush.specks < 0.5  # tone at stroke scale, no spray


@pytest.mark.slow
def test_a_brush_mark_beats_its_own_outline_filled():
    """Fast (no character writer): two crossing strokes simulated by the engine with a brush
    dipped once, against the same silhouette filled flat (the ink's outline closed over its
    gaps, holes filled, anti-aliased as a font renderer does): the measure rates the flat
    fill about 0 and the brush's mark above it, for its tone and its streaks along the
    strokes, with no spray of specks."""
    from sim.core.recording import Dip, Recording
    from sim.engine.simulation import Simulation
    from sim.fitting.texture import density
    from sim.writing.strokes import stroke

    ndimage = pytest.importorskip("scipy.ndimage")
    s1 = stroke([[15, 40], [85, 40]], press_mm=7, speed_mm_s=80)
    s2 = stroke([[50, 10], [50, 75]], press_mm=7, speed_mm_s=80)
    rec = Recording(
        np.concatenate([s1, s2]),
        width_mm=100,
        height_mm=85,
        px_per_mm=3.0,
        seed=0,
        dips=[Dip(0, 0.6, (0, 0, 0), 0.6)],
    )
    img = Simulation(rec).run().image()
    ink = density(img) > 0.25
    filled = ndimage.binary_fill_holes(ndimage.binary_closing(ink, np.ones((7, 7)), iterations=2))
    flat = ndimage.gaussian_filter(filled.astype(float), 0.8)
    brush, font = R.realism(img), R.realism(rgb(flat))
    assert font.score < 0.05 and font.tone < 0.02
    assert brush.score > font.score + 0.1
    assert brush.tone > 2 * font.tone and brush.streaks > font.streaks and brush.specks < 0.5
