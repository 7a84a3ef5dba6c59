# SPDX-License-Identifier: GPL-3.0-or-later
"""The scene maths behind the Blender glue (sim.placement), without Blender."""

import math

import numpy as np
import pytest

from sim.core.frames import rotation_matrix
from sim.core.placement import (
    PlacementError,
    engine_to_paper_local,
    first_sample_from_frame,
    matrix_from_sample,
    primitive_points,
    ray_to_paper,
    sample_from_matrices,
    samples_at_frame,
)


def paper_matrix(scale=1.0):
    """A paper tilted 30 degrees about x, turned 20 about z, moved and scaled."""
    m = np.eye(4)
    rx = np.array(
        [
            [1, 0, 0],
            [0, math.cos(0.5236), -math.sin(0.5236)],
            [0, math.sin(0.5236), math.cos(0.5236)],
        ]
    )
    rz = np.array(
        [[math.cos(0.35), -math.sin(0.35), 0], [math.sin(0.35), math.cos(0.35), 0], [0, 0, 1]]
    )
    m[:3, :3] = rz @ rx * scale
    m[:3, 3] = (0.3, -0.2, 1.1)
    return m


@pytest.mark.parametrize("scale", [1.0, 2.5])
def test_a_sample_and_the_brushs_matrix_are_inverse(scale):
    pm = paper_matrix(scale)
    sample = np.array([37.0, 112.0, 25.0, 12.0, -7.0, 33.0])
    mw = matrix_from_sample(pm, sample, 150.0, 200.0)
    # the brush is not scaled with the paper: its rotation stays a rotation
    np.testing.assert_allclose(mw[:3, :3] @ mw[:3, :3].T, np.eye(3), atol=1e-12)
    back = sample_from_matrices(mw, pm, 150.0, 200.0)
    # positions are read in the paper's own units (a scaled paper shrinks them), angles are not
    centre = np.array([75.0, 100.0, 0.0])
    np.testing.assert_allclose(back[:3], (sample[:3] - centre) / scale + centre, atol=1e-9)
    np.testing.assert_allclose(back[3:], sample[3:], atol=1e-9)


def test_an_upright_brush_over_the_papers_centre():
    pm = np.eye(4)
    mw = np.eye(4)
    mw[:3, 3] = (0.0, 0.0, 0.035)
    s = sample_from_matrices(mw, pm, 200.0, 100.0)
    np.testing.assert_allclose(s, [100.0, 50.0, 35.0, 0.0, 0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(rotation_matrix(0, 0, 0), np.eye(3))


def test_a_paper_scaled_to_nothing_is_refused():
    pm = paper_matrix()
    pm[:3, 0] = 0.0
    with pytest.raises(PlacementError, match="scaled to nothing"):
        sample_from_matrices(np.eye(4), pm, 100.0, 100.0)


def test_a_view_ray_meets_the_paper_where_it_points():
    to_world = paper_matrix() @ engine_to_paper_local(150.0, 200.0)
    target = to_world @ np.array([40.0, 70.0, 0.0, 1.0])
    origin = target[:3] + np.array([0.1, 0.2, 0.9])
    assert ray_to_paper(to_world, origin, target[:3] - origin) == pytest.approx((40.0, 70.0))
    assert ray_to_paper(to_world, origin, origin - target[:3]) is None  # pointing away


def test_samples_on_the_timeline():
    # 120 Hz at 24 fps: 5 samples a frame, sample 0 at frame 1
    per = 24 / 120
    assert samples_at_frame(100, 1.0, per, 0.0) == 0
    assert samples_at_frame(100, 1.0, per, 1.0) == 1
    assert samples_at_frame(100, 1.0, per, 2.0) == 6
    assert samples_at_frame(100, 1.0, per, 500.0) == 100
    assert first_sample_from_frame(100, 1.0, per, 2.0) == 5
    assert first_sample_from_frame(100, 1.0, per, 2.1) == 6


def test_primitive_points_are_cartesian_in_blenders_order():
    nets = np.zeros((1, 3, 2, 4))
    nets[..., 3] = 2.0
    nets[0, :, :, 0] = np.arange(3)[:, None] * 2.0  # x = u index (homogeneous, weight 2)
    nets[0, :, :, 1] = np.arange(2)[None, :] * 2.0  # y = v index
    co = primitive_points(nets, np.eye(4))
    assert co.shape == (1, 6, 4)
    np.testing.assert_allclose(co[0, :, 0], [0, 1, 2, 0, 1, 2])  # u runs fastest
    np.testing.assert_allclose(co[0, :, 1], [0, 0, 0, 1, 1, 1])
    np.testing.assert_allclose(co[0, :, 3], 2.0)
