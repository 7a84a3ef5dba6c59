# SPDX-License-Identifier: GPL-3.0-or-later
"""The texture statistics (sim.fitting.texture, numpy only) against scikit-image's and scipy's own
tools, and on images whose texture is known."""

import numpy as np
import pytest

from sim.fitting import texture as T
from sim.image import filters as F

skimage = pytest.importorskip("skimage")
ndimage = pytest.importorskip("scipy.ndimage")
from skimage import filters, measure, morphology  # noqa: E402


def blobs(seed=0, keep=0.4):
    a = F._gaussian(np.random.default_rng(seed).random((256, 256)), 4.0)
    mask = a > np.quantile(a, 1 - keep)
    out = np.zeros_like(mask)
    out[20:-20, 20:-20] = mask[20:-20, 20:-20]
    return out


def test_the_image_tools_equal_scikit_images():
    mask = blobs()
    assert F.perimeter(mask) == pytest.approx(measure.perimeter(mask, 4), rel=1e-12)
    disk = morphology.disk
    np.testing.assert_array_equal(F._erode(mask, 3), ndimage.binary_erosion(mask, disk(3)))
    np.testing.assert_array_equal(
        F._erode(F._dilate(mask, 2), 2), ndimage.binary_closing(mask, disk(2))
    )
    g = filters.gaussian(mask.astype(float), sigma=1.0, mode="nearest", truncate=4.0)
    np.testing.assert_allclose(F._gaussian(mask.astype(float), 1.0), g, atol=1e-12)
    v = np.random.default_rng(1).random((64, 64)) ** 2
    np.testing.assert_allclose(F._median3(v), ndimage.median_filter(v, 3, mode="constant"))
    assert abs(F.otsu(v) - filters.threshold_otsu(v, nbins=256)) < 1 / 256
    skel = F.skeleton(mask)
    edt = ndimage.distance_transform_edt(mask)
    np.testing.assert_allclose(T._distance_to(~mask, skel), edt[skel], atol=1e-12)
    # Zhang-Suen thinning: a one-pixel-wide skeleton inside the shape, near skimage's
    assert skel.sum() == pytest.approx(morphology.skeletonize(mask).sum(), rel=0.1)
    assert not (skel & ~mask).any()


def test_a_flat_font_like_glyph_has_no_texture_and_a_ragged_dry_one_has():
    img = np.ones((300, 300, 3))
    img[60:240, 130:170] = 0.0  # a solid vertical bar
    img[130:170, 60:240] = 0.0  # crossed by a horizontal one
    flat = T.texture_stats(img)
    assert flat.ink_tone < 1e-6 and flat.partial_ink < 0.02 and flat.flying_white < 0.01
    assert flat.ragged_edge < 0.02
    rng = np.random.default_rng(2)
    dry = img.copy()
    streaks = rng.random(300) < 0.15  # dry hair leaves white lines along the strokes
    dry[60:240][:, streaks] = np.where(dry[60:240][:, streaks] < 0.5, 0.9, 1.0)
    dry += rng.normal(0, 0.03, dry.shape) * (dry < 0.5)
    dry = np.clip(dry, 0, 1)
    rough = T.texture_stats(dry)
    assert rough.flying_white > 3 * flat.flying_white + 0.005
    assert rough.ragged_edge > flat.ragged_edge
    assert T.score(rough) > T.score(flat)
    assert T.score(T.REAL_WRITING) == pytest.approx(1.0)
