# SPDX-License-Identifier: GPL-3.0-or-later
"""Planning a relief on a mesh (issue 29.7, sim.surface.relief): which faces are cut, how often,
and when the relief goes into the material instead."""

from __future__ import annotations

import numpy as np
import pytest

from sim.surface.relief import MAX_LEVELS, TARGET_EDGE_TEXELS, plan_relief


def quad_grid(n: int):
    """An n x n grid of quads whose UVs cover the unit square: Blender's face arrays."""
    v = lambda i, j: j * (n + 1) + i  # noqa: E731
    loops = [
        (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)) for j in range(n) for i in range(n)
    ]
    loop_vert = np.array(loops).ravel()
    xy = np.array([(i / n, j / n) for j in range(n + 1) for i in range(n + 1)])
    return np.arange(n * n) * 4, np.full(n * n, 4), loop_vert, xy[loop_vert], (n + 1) ** 2


def test_the_faces_under_the_ink_and_a_ring_around_them_are_cut_as_the_texels_need():
    start, total, verts, uv, nv = quad_grid(8)
    ink = np.zeros((256, 256), bool)
    ink[100:110, 40:200] = True  # a horizontal stroke: rows of faces 3 (v 0.39 - 0.43)
    plan = plan_relief(start, total, verts, uv, nv, ink)
    faces = plan.faces.reshape(8, 8)
    assert faces[3, 1:7].all()  # under the ink
    assert faces[2:5].sum() == faces.sum() and faces[2, 0] and faces[4, 7]  # and its ring
    assert not faces[0].any() and not faces[7].any()
    edge = 256 / 8  # texels a face's side spans
    assert plan.levels == int(np.ceil(np.log2(edge / TARGET_EDGE_TEXELS)))
    assert edge / 2**plan.levels <= TARGET_EDGE_TEXELS < edge / 2 ** (plan.levels - 1)
    assert plan.method == "GEOMETRY"
    assert plan.vertices == pytest.approx(nv + faces.sum() * 4**plan.levels, rel=0.01)


@pytest.mark.slow
def test_no_ink_no_cut_and_too_many_vertices_go_into_the_material():
    start, total, verts, uv, nv = quad_grid(4)
    blank = np.zeros((64, 64), bool)
    plan = plan_relief(start, total, verts, uv, nv, blank)
    assert plan.levels == 0 and not plan.faces.any() and plan.method == "GEOMETRY"
    ink = np.ones((4096, 4096), bool)
    plan = plan_relief(start, total, verts, uv, nv, ink, budget=1_000_000)
    assert plan.faces.all() and plan.method == "MATERIAL" and plan.vertices > 1_000_000
    assert "in the material instead" in plan.message("Cube")
    mine = plan_relief(start, total, verts, uv, nv, ink, levels=2)
    assert mine.levels == 2 and mine.method == "GEOMETRY"
    assert plan_relief(start, total, verts, uv, nv, ink, levels=MAX_LEVELS).levels == MAX_LEVELS
