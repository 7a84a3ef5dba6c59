# SPDX-License-Identifier: GPL-3.0-or-later
"""A dry flick (issue 26.2): as the belly lifts off, the hair gathers to the point, its bundles
close up inside the narrowing mark (``bristles.spread``) and, held together by the ink, part
less once it is narrower than half the belly (``bristles.GATHER``): streaks along the stroke at
its wide root, a tapering outline and a point that reaches the end of the flick. (Before, the
bundles were laid across the belly's width whatever the contact: the narrow point held one or
two of them, and where those were dry it broke off short, or splayed.) No Blender."""

import numpy as np
import pytest

from sim.brush import bristles
from sim.brush.primitive import HairyBrush  # noqa: I001 (after the engine: the package's order)
from sim.core.params import BrushGeometry, QualityParams
from sim.writing.strokes import stroke
from tests.sim.test_bristles import density, simulate


def _pressed_brush(seed: int) -> HairyBrush:
    b = HairyBrush(BrushGeometry(), QualityParams(), np.random.default_rng(seed))
    b._free_state(300)
    b.cc[..., 2] = 0.0
    b.touching[:] = True
    return b


def test_the_bundles_lie_across_the_contact_not_the_belly():
    b = _pressed_brush(5)
    speed = 60.0
    half = 0.5 * b.a
    b.sweep = 0.3 * b.a * speed  # a contact 0.3 a wide across the way (main: a / 2 always)
    assert np.allclose(bristles.state(b, speed).radius, 0.3 * half)
    b.sweep = 2.0 * b.a * speed  # never wider than the belly
    assert np.allclose(bristles.state(b, speed).radius, half)
    b.sweep[:] = 0.0  # sweeping no paper: the belly's
    assert np.allclose(bristles.state(b, speed).radius, half)
    assert np.allclose(bristles.state(b, 0.0).radius, half)


def test_gathered_hair_parts_less():
    parted = {}
    for share in (1.0, 0.5, 0.25):
        b = _pressed_brush(6)
        b.wet[:], b.moist[:], b.gap[:] = 0.25, 0.0, 0.0
        b.sweep = share * b.a * 50.0
        b.step_bundles(50.0, bristles.RAMP_S)
        parted[share] = (b.gap > 0.5).mean()
    # a dry brush's bundles part across the full belly, half of them, and as many across a
    # pressed stroke's contact; gathered to a point, a quarter of its width, hardly any (main:
    # as many as across the belly)
    assert parted[1.0] > 0.4
    assert parted[0.5] == parted[1.0]
    assert parted[0.25] < 0.1 * parted[1.0]


def _fifths(ink):
    """The ink's reach (its last column) and, over each fifth of its length, its mean width
    across (first to last inked row, px) and the share of that width inked."""
    cols = np.flatnonzero(ink.any(axis=0))
    x0, x1 = int(cols[0]), int(cols[-1])
    widths, fills = [], []
    for k in range(5):
        part = ink[:, x0 + (x1 - x0) * k // 5 : x0 + (x1 - x0) * (k + 1) // 5]
        span = fill = 0
        for col in part.T:
            rows = np.flatnonzero(col)
            if rows.size:
                span += int(rows[-1] - rows[0] + 1)
                fill += rows.size
        widths.append(span / part.shape[1])
        fills.append(fill / max(span, 1))
    return x1, widths, fills


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_dry_flick_tapers_to_its_point(seed):
    # a dry brush pressed 9 mm lets go evenly over 80 mm at 100 mm/s (as a hook flicks out):
    # the mark reaches past 82 mm every time (main: 76, 79 and 56 mm with seeds 0, 1, 2), its
    # width falls fifth by fifth (main: 20 then 6 px, or 38, 34, 16 px), and its point is ink
    # (main: half of it bare with seed 0)
    flick = stroke(
        [[10, 30], [90, 30]],
        press_mm=lambda f: 9.0 * (1.0 - f),
        speed_mm_s=100,
        hair_length_mm=28.0,
        lift_fraction=0.05,
    )
    ink = density(simulate(flick, wet=0.3, seed=seed)) > 0.1
    reach, widths, fills = _fifths(ink)
    assert reach / 6.0 > 82.0
    assert all(w1 < w0 for w0, w1 in zip(widths[1:], widths[2:], strict=False))
    assert fills[-1] > 0.9


def _short_of_the_point(ink, char: dict, n: int) -> list[float]:
    """Per hook flicked up from its foot (``scripts.hooks_eval.hooks``): how far (px) the ink
    near the stroke's own outline stops short of the font's tip along the hook."""
    from scipy.ndimage import binary_dilation

    from scripts.hooks_eval import hooks
    from sim.writing.outline import fill, stroke_polygons, to_image

    polys = stroke_polygons(char)
    yy, xx = np.mgrid[0:n, 0:n]
    out = []
    for si, corner, tip, *_ in hooks(char):
        own = binary_dilation(fill([to_image(q, n) for q in polys[si]], n), iterations=2)
        c, t = to_image(corner[None], n)[0], to_image(tip[None], n)[0]
        length = float(np.linalg.norm(t - c))
        u = (t - c) / length
        along = (xx - c[0]) * u[0] + (yy - c[1]) * u[1]
        across = (yy - c[1]) * u[0] - (xx - c[0]) * u[1]
        near = ink & own & (along > 0.2 * length) & (along < 1.15 * length)
        near &= np.abs(across) < 0.5 * length
        out.append(length - float(along[near].max()))
    return out


@pytest.mark.slow
def test_a_written_hook_reaches_its_point(stiff_ink):
    # a 竖钩 flicked out of its heel: the hair, bent back in the heel, trails the base by the
    # heel's lag to the point (``feet._bent``), and the ink reaches the font's tip (main, the
    # base led by the lag of the lightening press: 3.9 3.9 1.4 4.8 px short, 3.5 on average)
    from sim.writing.hanzi import find_char

    short = [s for ch in "寸小丁于" for s in _short_of_the_point(stiff_ink(ch), find_char(ch), 256)]
    assert len(short) == 4
    assert np.mean(short) < 3.0
