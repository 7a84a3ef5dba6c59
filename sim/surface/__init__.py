# SPDX-License-Identifier: GPL-3.0-or-later
"""Writing on a 3D surface (layer 4; issue 17; the paper's Sec. 9 "3D writing effects"): any
UV-mapped triangle mesh is the paper, as plain arrays (no bpy), and every geometric question is
answered here.

The design, in three parts:

1. **The local frame.** Each sample is taken where the brush's axis meets the surface (the
   closest surface point when the axis misses it): the point P, the smooth normal N there (the
   paper's z: the brush's height above the surface and its tilts are measured against it; faces
   meeting at less than SMOOTH_ANGLE_DEG are smoothed, sharper edges stay) and a tangent T
   (B = N x T). T is carried from sample to sample by the smallest rotation that keeps it
   tangent (parallel transport, ``transport``); the first sample's T is the brush's own x axis
   (baking) or the surface's x axis (painting) on the tangent plane, and the rotation r is kept
   continuous. The engine's sample is the brush's pose in that frame, so the
   brush model, which only knows a flat paper at z = 0, is unchanged: it writes on the tangent
   plane at P.
2. **The chart.** The brush's dynamics need one continuous plane to move on, so the surface is
   *developed* along the writing: the chart position c of a sample's point is the previous one
   plus the step P_i - P_(i-1) seen in the previous frame (``develop``). On a flat surface this
   is the plane itself, exactly; on a curved one it unrolls the surface along the path (as a
   sheet laid on a vase). The recording keeps the chart samples (its usual ``samples``) and, per
   sample, the frame (c, P, T, N) in ``surface.frames``; replay reads them, so it is bit for bit.
3. **Where the ink lands** (``SurfacePaper.splat``). The marks are rasterised on the chart's own
   pixel grid at the paper's px/mm, then splatted into the texels whose 3D points lie under
   them: every texel knows its 3D point (``TexelTiles``: each UV triangle rasterised in the
   texture, plus a pad of PAD_TEXELS around it for filtering, a tile at a time when the marks
   first reach it), the triangles' pieces binned in 3D find the texels near P, and each is
   projected on the tangent plane and takes the chart pixel it falls in.
   So the UV map's stretch is exact (a texel's ink is decided in the surface's own millimetres)
   and seams are free (a mark straddling a seam inks the texels of both islands, whatever their
   place in the texture). The work per sample is the texels near the mark, never the texture;
   nor is the texture's whole set of texel points ever built before writing.

What is approximate: a mark is the brush's cut by the tangent plane at P, projected along N onto
the surface (a decal): on a surface curving with radius R a mark of radius r is off by about
r^2 / (2R) in depth and (r/R)^2 in size (1% for a 5 mm mark on a 50 mm vase). Texels take the
chart pixel under their centre (nearest): where the UVs give fewer texels a millimetre than the
paper's px/mm, edges alias. The paper's physics (absorption, drying, the saturation spreading of
``sim.paper``) runs on the texture's grid: its spreading is measured in texels, so it is
anisotropic where the UVs stretch and stops at seams (ink does not bleed from one island into
the next).

The modules: ``mesh`` (the checked mesh), ``query`` (rays, nearest points, normals), ``chart``
(frames and the chart), ``geodesic`` (writing done on flat paper laid on the surface: the chart
map, straightest walks over the mesh), ``texels`` (the texels' 3D points), ``paper``
(SurfacePaper, the splat), ``relief`` (how a mesh carries the writing as a relief: where it is
cut, or a bump map).
Their public names are re-exported here.

May import: ``core``, ``paper``.
"""

from .chart import (
    FRAME_DECIMALS,
    FRAME_WIDTH,
    LAY_STEP_MM,
    MAX_WALK_STEPS,
    axis_hit,
    chart_xy,
    chart_xy_over,
    develop,
    follow,
    frame_parts,
    frames_from_dict,
    local_sample,
    new_frame,
    pose_from_sample,
    quantise,
    start_frame,
    step_to,
    transport,
)
from .geodesic import ChartMap, edge_neighbours, lay_on, walk
from .mesh import (
    SMOOTH_ANGLE_DEG,
    UV_SLACK,
    Surface,
    SurfaceError,
    corner_normals,
    surface_from_arrays,
    texture_side_mm,
)
from .paper import (
    CHART_SHAPE,
    CHART_SIDES,
    DEPTH_TOL_MM,
    GROUP_TILE,
    NORMAL_DOT_MIN,
    SurfacePaper,
    group_marks,
)
from .query import (
    MAX_BOX_CELLS,
    BoxGrid,
    Hit,
    TriangleGrid,
    closest_point,
    hit_at,
    normal_at,
    ray_hit,
    uv_axes,
    uv_hit,
)
from .texels import BUILD_CHUNK, PAD_TEXELS, TEXEL_TILE, TexelPoints, TexelTiles, texel_points

__all__ = [
    "ChartMap",
    "BUILD_CHUNK",
    "BoxGrid",
    "CHART_SHAPE",
    "CHART_SIDES",
    "DEPTH_TOL_MM",
    "FRAME_DECIMALS",
    "FRAME_WIDTH",
    "GROUP_TILE",
    "Hit",
    "LAY_STEP_MM",
    "MAX_BOX_CELLS",
    "MAX_WALK_STEPS",
    "NORMAL_DOT_MIN",
    "PAD_TEXELS",
    "SMOOTH_ANGLE_DEG",
    "Surface",
    "SurfaceError",
    "SurfacePaper",
    "TEXEL_TILE",
    "TexelPoints",
    "TexelTiles",
    "TriangleGrid",
    "UV_SLACK",
    "axis_hit",
    "chart_xy",
    "chart_xy_over",
    "closest_point",
    "corner_normals",
    "develop",
    "edge_neighbours",
    "follow",
    "frame_parts",
    "frames_from_dict",
    "group_marks",
    "hit_at",
    "lay_on",
    "local_sample",
    "new_frame",
    "normal_at",
    "pose_from_sample",
    "quantise",
    "ray_hit",
    "start_frame",
    "step_to",
    "surface_from_arrays",
    "texel_points",
    "texture_side_mm",
    "transport",
    "uv_axes",
    "uv_hit",
    "walk",
]
