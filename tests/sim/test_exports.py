# SPDX-License-Identifier: GPL-3.0-or-later
"""The ink for compositing and print (issue 29.4), the engine's part: the matte (``--matte`` and
sim.image.matte), prints at a size and DPI (PNG and TIFF, resampled well), the SVG outline and
the recording as pen strokes."""

from __future__ import annotations

import io
import json
import xml.etree.ElementTree as ET
from types import SimpleNamespace

import numpy as np
import pytest
from PIL import Image

from sim.cli.main import main
from sim.core.recording import load
from sim.engine.pen import contact, pen_strokes
from sim.engine.simulation import Simulation
from sim.image.contours import area, trace
from sim.image.matte import ink_matte, paper_matte8
from sim.image.png import png_bytes
from sim.image.prints import PrintError, print_image, print_size_px, write_print
from sim.image.resample import resample, weights
from sim.image.svg import ink_outlines, ink_svg
from sim.image.tiff import tiff_bytes
from tests.paths import ROOT

VERMILION = np.array([0.89, 0.26, 0.2], np.float32)  # its colour on white paper at full density
REC = {
    "format": "hairy-brush-recording",
    "version": 1,
    "paper": {"width_mm": 40, "height_mm": 30, "px_per_mm": 4, "preset": "sized_xuan"},
    "ink": {"preset": "sumi_black"},
    "sample_rate_hz": 120,
    "seed": 3,
    "samples": [[8, 15, 34, 0, 0, 0], [9, 15, 24, 0, 0, 0]]
    + [[9 + k, 15 + 0.2 * k, 23, 0, 0, 0] for k in range(1, 23)]
    + [[32, 19.4, 34, 0, 0, 0]],
}


def fake_paper(ink, ppm=4.0, color=(0.95, 0.93, 0.86)):
    """What the exports read of a sim.paper.Paper: its ink (bottom row first), px/mm, colour."""
    return SimpleNamespace(ink=np.asarray(ink, np.float32), ppm=ppm, color=np.array(color))


def ring_paper(h=120, w=160, ppm=4.0):
    """Black ink in a ring (a hole in its middle) and a speck far from it."""
    yy, xx = np.mgrid[0:h, 0:w]
    r = np.hypot(xx - 60.0, yy - 60.0)
    d = ((r < 40) & (r >= 15)).astype(np.float32)
    d[100:102, 140:142] = 1.0  # 0.5 x 0.5 mm: a speck
    return fake_paper(np.repeat(d[::-1, :, None], 3, axis=2), ppm)


# ----------------------------------------------------------------------------- the matte
def test_the_matte_is_straight_alpha_that_gives_the_paper_back_over_white():
    rng = np.random.default_rng(1)
    a = rng.random((20, 30, 1)).astype(np.float32)
    ink = a * (1.0 - VERMILION)  # vermilion at every density
    m = ink_matte(ink)
    np.testing.assert_allclose(m[..., 3], a[..., 0] * (1 - VERMILION).max(), rtol=1e-5)
    inked = m[..., 3] > 0.05
    hue = m[inked][:, :3]
    np.testing.assert_allclose(hue, np.broadcast_to(hue[0], hue.shape), atol=1e-4)  # one colour
    over_white = m[..., 3:] * m[..., :3] + (1 - m[..., 3:])
    np.testing.assert_allclose(over_white, 1.0 - ink, atol=1e-5)  # the paper image's 1 - d
    blank = ink_matte(np.zeros((4, 4, 3)))
    assert (blank[..., 3] == 0).all()


def test_render_matte_writes_rgba_with_the_inks_density_as_alpha(tmp_path):
    rec = tmp_path / "rec.json"
    rec.write_text(json.dumps(REC))
    assert main(["render", str(rec), "-o", str(tmp_path / "paper.png"), "-q"]) == 0
    assert main(["render", str(rec), "-o", str(tmp_path / "m.png"), "-q", "--matte"]) == 0
    matte = np.asarray(Image.open(tmp_path / "m.png"))
    paper = np.asarray(Image.open(tmp_path / "paper.png")).astype(float) / 255
    assert matte.shape == (120, 160, 4) and matte.dtype == np.uint8
    sim = Simulation(load(rec)).run()
    alpha = np.clip(sim.paper.ink.max(axis=2), 0, 1)[::-1]
    np.testing.assert_allclose(matte[..., 3] / 255, alpha, atol=0.5 / 255 + 1e-6)
    assert alpha.max() > 0.8 and (alpha == 0).mean() > 0.5  # a stroke on bare paper
    # over white it is the paper image divided by the sheet's own colour (with its texture)
    m = matte.astype(float) / 255
    over_white = m[..., 3:] * m[..., :3] + (1 - m[..., 3:])
    H, W = sim.paper.shape
    sheet = sim.paper.visible(np.zeros(3), slice(0, H), slice(0, W))[::-1]
    assert sim.paper.texture > 0 and sheet.std() > 0.002  # the default paper shows its texture
    np.testing.assert_allclose(over_white, paper / sheet, atol=3 / 255)


def test_write_and_compose_have_the_matte_option_too():
    from sim.cli.main import _parser

    assert _parser().parse_args(["write", "永", "-o", "x.png", "--matte"]).matte is True
    assert _parser().parse_args(["compose", "永", "-o", "x.png", "--matte"]).matte is True


# ----------------------------------------------------------------------------- prints
def test_resampling_keeps_flat_paper_flat_and_lines_straight_and_does_not_alias():
    flat = np.full((50, 70), 0.3)
    np.testing.assert_allclose(resample(flat, 173, 211), 0.3, atol=1e-6)
    ramp = np.tile(np.linspace(0.0, 1.0, 64), (8, 1))  # a cubic that reproduces straight lines
    up = resample(ramp, 8, 256)
    x = (np.arange(256) + 0.5) / 4 - 0.5
    inner = (x > 2) & (x < 61)
    np.testing.assert_allclose(up[4, inner], x[inner] / 63, atol=1e-4)
    checker = (np.indices((256, 256)).sum(axis=0) % 2).astype(float)  # the finest grain
    down = resample(checker, 37, 37)
    assert abs(down.mean() - 0.5) < 0.01 and down.std() < 0.02  # grey, no moire
    idx, w = weights(100, 25)
    np.testing.assert_allclose(w.sum(axis=1), 1.0, atol=1e-6)
    assert idx.shape[1] >= 16  # a reduction by 4 looks at 4 times the taps


def test_a_print_has_its_size_and_dpi_in_png_and_tiff(tmp_path):
    paper = ring_paper()  # 40 x 30 mm
    w, h = write_print(tmp_path / "p.png", paper, width_mm=80.0, dpi=300)
    assert (w, h) == print_size_px(80.0, 60.0, 300) == (945, 709)
    im = Image.open(tmp_path / "p.png")
    assert im.size == (945, 709) and im.mode == "RGB"
    assert im.info["dpi"] == pytest.approx((300, 300), abs=0.01)
    write_print(tmp_path / "m.tif", paper, width_mm=40.0, dpi=600, matte=True, bits=16)
    import tifffile

    with tifffile.TiffFile(tmp_path / "m.tif") as tf:
        page = tf.pages[0]
        img = page.asarray()
        assert img.shape == (709, 945, 4) and img.dtype == np.uint16
        assert page.tags["XResolution"].value == (6000000, 10000)
        assert page.tags["ResolutionUnit"].value == 2  # inch
        assert [int(v) for v in page.tags["ExtraSamples"].value] == [2]  # unassociated alpha
    alpha = img[..., 3] / 65535.0
    # the ring at 600 dpi (23.6 px a mm): full ink inside it, none in its hole or outside
    s = 600 / 25.4 / 4
    assert alpha[int(60 * s), int(30 * s)] > 0.99 and alpha[int(60 * s), int(60 * s)] == 0
    assert alpha[int(5 * s), int(150 * s)] == 0
    with pytest.raises(PrintError, match=r"\.png, \.tif"):
        write_print(tmp_path / "p.jpg", paper, 80.0, 300)
    with pytest.raises(PrintError, match="at most"):
        print_size_px(2000.0, 2000.0, 1200)


def test_print_files_round_trip_exactly():
    import tifffile

    rng = np.random.default_rng(2)
    for dtype, bits in ((np.uint8, 8), (np.uint16, 16)):
        a = (rng.random((31, 17, 4)) * np.iinfo(dtype).max).astype(dtype)
        np.testing.assert_array_equal(tifffile.imread(io.BytesIO(tiff_bytes(a, 150))), a)
        back = tifffile.imread(io.BytesIO(tiff_bytes(a[..., :3], 150)))
        np.testing.assert_array_equal(back, a[..., :3])
        png = Image.open(io.BytesIO(png_bytes(a[..., :3].astype(np.uint8), dpi=72)))
        assert png.info["dpi"] == pytest.approx((72, 72), abs=0.01) and bits in (8, 16)


def test_a_resampled_matte_has_no_fringe():
    """Black ink on white, reduced: where alpha is small the colour stays the ink's (black),
    not a grey mixed from the unpremultiplied colour of bare paper."""
    paper = ring_paper()
    img = print_image(paper, 53, 40, matte=True)
    edge = (img[..., 3] > 0) & (img[..., 3] < 255)
    assert edge.sum() > 20 and img[edge][:, :3].max() <= 1


# ----------------------------------------------------------------------------- outline
def test_the_outline_has_the_ring_and_its_hole_in_mm_and_drops_the_speck():
    paper = ring_paper()
    loops = ink_outlines(paper, threshold=0.5, smooth_mm=0.0, min_area_mm2=0.5)
    areas = sorted(area(lp) for lp in loops)
    assert len(loops) == 2  # outer and hole; the 0.25 mm^2 speck is gone
    # 40 px = 10 mm and 15 px = 3.75 mm radii, the hole running the other way
    assert areas[0] == pytest.approx(-np.pi * 3.75**2, rel=0.05)
    assert areas[1] == pytest.approx(np.pi * 10**2, rel=0.02)
    doc = ET.fromstring(ink_svg(paper, smooth_mm=0.0, min_area_mm2=0.5, width_mm=80.0))
    assert doc.get("width") == "80.000mm" and doc.get("height") == "60.000mm"
    assert doc.get("viewBox") == "0 0 80.000 60.000"
    path = doc.find("{http://www.w3.org/2000/svg}path")
    assert path.get("fill-rule") == "evenodd" and path.get("d").count("M") == 2
    # the curves pass through points on the ring's two circles, scaled to 80 mm (x 2)
    for sub in path.get("d").split("M")[1:]:
        curves = [c.split() for c in sub.rstrip("Z").split("C")[1:]]
        on = np.array([[float(v) for v in c[4:6]] for c in curves])  # each curve's end point
        r = np.hypot(on[:, 0] - 2 * 15.125, on[:, 1] - 2 * 15.125)
        want = 20.0 if r.mean() > 14 else 7.5
        np.testing.assert_allclose(r, want, atol=0.35)


@pytest.mark.slow
def test_the_outline_of_written_ink_fills_the_ink():
    from skimage.draw import polygon

    from sim.image.filters import _gaussian

    sim = Simulation(load(ROOT / "examples" / "strokes.json")).run()
    loops = ink_outlines(sim.paper)
    ppm = sim.paper.ppm
    h, w = sim.paper.shape
    filled = np.zeros((h, w), bool)
    for lp in loops:  # even-odd
        rr, cc = polygon(lp[:, 1] * ppm - 0.5, lp[:, 0] * ppm - 0.5, (h, w))
        one = np.zeros((h, w), bool)
        one[rr, cc] = True
        filled ^= one
    density = np.clip(sim.paper.ink.max(axis=2), 0, 1)[::-1].astype(float)
    ink = _gaussian(density, 0.1 * ppm) >= 0.5
    assert (filled & ink).sum() / (filled | ink).sum() > 0.99


def test_trace_closes_contours_at_the_border_and_takes_saddles_consistently():
    f = np.zeros((5, 6))
    f[0, 0] = f[1, 1] = 1.0  # touching at a corner: a saddle
    f[:, 5] = 1.0  # along the border
    loops = trace(f, 0.5)
    # two outlines: the column along the border, and the diagonal pair (the saddle's cell mean
    # is at the level: joined), both closed, both outer
    assert len(loops) == 2 and all(len(lp) >= 4 and area(lp) > 0 for lp in loops)
    assert all(np.abs(lp).max() <= 6 for lp in loops)


# ----------------------------------------------------------------------------- pen strokes
@pytest.mark.slow
def test_the_recording_as_pen_strokes_follows_the_touches_with_pressure_from_the_press():
    rec = load(ROOT / "examples" / "strokes.json")
    strokes = pen_strokes(rec)
    xy, press = contact(rec.samples, 28.0)
    touching = np.flatnonzero(press > 0)
    stroked = np.concatenate([s.samples for s in strokes])
    assert len(strokes) >= 5 and set(stroked) <= set(touching)  # 永's five strokes, at least
    assert len(stroked) >= len(touching) - len(strokes)  # every touch but single samples
    for s in strokes:  # a stroke is a whole touch: the brush is up before and after it
        assert press[s.samples[0] - 1] <= 0 and press[s.samples[-1] + 1] <= 0
    allp = np.concatenate([s.pressure for s in strokes])
    assert allp.max() == 1.0 and allp.min() > 0 and np.ptp(allp) > 0.5
    for s in strokes:
        np.testing.assert_allclose(
            s.pressure * press.max(), press[s.samples], atol=1e-3 * press.max()
        )
    # the points lie in the ink
    sim = Simulation(rec).run()
    dens = sim.paper.ink.max(axis=2)
    pts = np.concatenate([s.points for s in strokes])
    col = np.clip((pts[:, 0] * rec.px_per_mm).astype(int), 0, rec.width_px - 1)
    row = np.clip((pts[:, 1] * rec.px_per_mm).astype(int), 0, rec.height_px - 1)
    assert (dens[row, col] > 0.5).mean() > 0.9
    # a tilted brush meets the paper ahead of its base, along its axis
    tilted = np.array([[10.0, 10.0, 20.0, 0.0, 30.0, 0.0]])
    (p,), (depth,) = contact(tilted, 28.0)
    axis_len = 20.0 / np.cos(np.radians(30.0))
    assert depth == pytest.approx(28.0 - axis_len)
    assert np.hypot(*(p - [10.0, 10.0])) == pytest.approx(20.0 * np.tan(np.radians(30.0)))


def test_paper_matte8_is_top_row_first_like_the_image():
    ink = np.zeros((3, 2, 3), np.float32)
    ink[0] = 1.0  # the bottom row (the engine's first)
    m = paper_matte8(fake_paper(ink))
    assert m[2, :, 3].tolist() == [255, 255] and m[0, :, 3].tolist() == [0, 0]
