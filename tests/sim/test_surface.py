# SPDX-License-Identifier: GPL-3.0-or-later
"""Writing on a 3D surface (issue 17), the engine's part: frames, chart, texels and the splat
of the marks (sim.surface), without Blender."""

from __future__ import annotations

import numpy as np
import pytest

from sim import surface as sf
from sim.core.frames import rotation_matrix
from sim.core.params import load_preset
from sim.core.recording import DEFAULT_BRUSH, Recording, from_dict
from sim.engine.simulation import Simulation

# the default brush's hair length (mm), as the engine reads it below
L = load_preset("brush", DEFAULT_BRUSH).data["geometry"]["hair_length_mm"]
PPM = 3.0


def grid(size=100.0, n=8, angle_deg=0.0, scale=1.0 / 100.0, centre=(0.5, 0.5)):
    """A flat n x n grid of size mm centred on the origin in z = 0; its UVs are the plane's
    turned by angle_deg and scaled by ``scale`` (UV units a mm) about ``centre``."""
    xs = np.linspace(-size / 2, size / 2, n + 1)
    X, Y = np.meshgrid(xs, xs)
    verts = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], axis=1)
    a = np.radians(angle_deg)
    rot = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    uv_of = np.asarray(centre) + (verts[:, :2] @ rot.T) * scale
    tris = []
    for j in range(n):
        for i in range(n):
            a0, b0 = j * (n + 1) + i, j * (n + 1) + i + 1
            c0, d0 = b0 + n + 1, a0 + n + 1
            tris += [(a0, b0, c0), (a0, c0, d0)]
    tris = np.array(tris)
    return sf.surface_from_arrays(verts, tris, uv_of[tris]), rot, scale, centre


def cylinder(radius=40.0, height=120.0, n=48, m=4):
    """An open cylinder about the z axis; u = angle / 360 deg, so its seam is at angle 0."""
    ang = 2 * np.pi * np.arange(n) / n
    rows = [
        (radius * np.cos(a), radius * np.sin(a), height * j / m) for j in range(m + 1) for a in ang
    ]
    verts = np.array(rows)
    tris, uvs = [], []
    for j in range(m):
        for i in range(n):
            a, b = j * n + i, j * n + (i + 1) % n
            c, d = b + n, a + n
            u0, u1, v0, v1 = i / n, (i + 1) / n, j / m, (j + 1) / m
            tris += [(a, b, c), (a, c, d)]
            uvs += [[(u0, v0), (u1, v0), (u1, v1)], [(u0, v0), (u1, v1), (u0, v1)]]
    return sf.surface_from_arrays(verts, np.array(tris), np.array(uvs))


def around(angles_deg, press, radius=40.0, z=60.0):
    """Brush poses upright against a cylinder's side (axis along the normal), pressing press
    (mm) at the given angles."""
    bases, rots = [], []
    for a, p in zip(np.radians(angles_deg), press, strict=True):
        n = np.array([np.cos(a), np.sin(a), 0.0])
        bases.append(np.array([0.0, 0.0, z]) + n * (radius + L - p))
        x = np.array([-np.sin(a), np.cos(a), 0.0])
        rots.append(np.stack([x, np.cross(n, x), n], axis=1))
    return np.array(bases), np.array(rots)


def stroke_press(n: int, press=3.0, lead=12) -> np.ndarray:
    p = np.full(n, -5.0)
    p[lead:-lead] = press
    return p


def simulate_on(surface, bases, rots, ppm=PPM, origin=None, paper_overrides=None):
    side = sf.texture_side_mm(surface)
    origin = (side / 2, side / 2) if origin is None else origin
    samples, frames = sf.develop(surface, bases, rots, origin)
    rec = Recording(
        samples, width_mm=side, height_mm=side, px_per_mm=ppm, paper_overrides=paper_overrides or {}
    )
    d = rec.to_dict()
    d["surface"] = {"frames": frames.tolist()}
    rec = from_dict(d)
    frames = sf.frames_from_dict(rec.extra["surface"], len(rec.samples))
    sp = sf.SurfacePaper(surface, frames, rec.width_px, rec.height_px, ppm, side)
    return Simulation(rec, surface=sp).run(), sp


def ink_of(sim) -> np.ndarray:
    """Ink density (H, W), bottom row first."""
    return sim.paper.ink.mean(axis=2)


# ----------------------------------------------------------------------------- geometry
def test_ray_and_closest_point_on_a_cylinder():
    s = cylinder()
    hit = sf.ray_hit(s, [0.0, -100.0, 60.0], [0.0, 1.0, 0.0])
    assert hit is not None and abs(hit.point[1] + 40.0) < 1e-9  # a vertex of the polygon
    assert sf.ray_hit(s, [0.0, -100.0, 60.0], [0.0, -1.0, 0.0]) is None
    c = sf.closest_point(s, [0.0, -70.0, 200.0])  # above the rim: the rim's nearest point
    assert abs(c.point[2] - 120.0) < 1e-9 and c.point[1] < -39.0
    n = sf.normal_at(s, hit)
    np.testing.assert_allclose(n, [0.0, -1.0, 0.0], atol=1e-9)


def test_the_triangle_grid_finds_the_same_nearest_points_as_all_triangles():
    s = cylinder(n=96, m=12)
    grid = sf.TriangleGrid(s)
    rng = np.random.default_rng(1)
    points = rng.uniform([-60, -60, -20], [60, 60, 140], (40, 3))
    points[:20] *= [0.7, 0.7, 1.0]  # some near the surface, some far
    for p in points:
        a, b = sf.closest_point(s, p), sf.closest_point(s, p, grid)
        assert a.tri == b.tri and np.allclose(a.point, b.point) and a.distance == b.distance
    near = grid.query(np.array([40.0, 0.0, 60.0]))
    assert 0 < near.size < 0.15 * len(s.tris)  # a neighbourhood, not the mesh


def test_local_sample_is_the_pose_relative_to_the_frame_and_back():
    g = grid()[0]
    base = np.array([5.0, -3.0, 26.0])
    rot = rotation_matrix(10.0, -15.0, 30.0)  # tilted and turned about its axis
    frame = sf.new_frame(g, sf.axis_hit(g, base, rot), None, (50.0, 50.0))
    sample = sf.local_sample(frame, base, rot)  # on a flat surface: the plane's own sample
    np.testing.assert_allclose(sample, [55.0, 47.0, 26.0, 10.0, -15.0, 30.0], atol=1e-4)
    s = cylinder()  # on a curved one: relative to the normal where the axis meets it
    bases, rots = around([-90.0], [3.0])
    rots = rots @ rotation_matrix(10.0, -15.0, 30.0)
    hit = sf.axis_hit(s, bases[0], rots[0])
    frame = sf.new_frame(s, hit, None, (100.0, 100.0))
    sample = sf.local_sample(frame, bases[0], rots[0])
    n = sf.normal_at(s, hit)
    tilt = np.degrees(np.arccos(rots[0][:, 2] @ n))
    d, q = np.radians(sample[3:5])
    assert abs(np.degrees(np.arccos(np.cos(d) * np.cos(q))) - tilt) < 1e-3
    assert abs(sample[2] - (bases[0] - hit.point) @ n) < 1e-3
    base, back = sf.pose_from_sample(frame, sample)
    np.testing.assert_allclose(base, bases[0], atol=1e-3)
    np.testing.assert_allclose(back, rots[0], atol=1e-4)


def test_the_tangent_is_carried_without_twist_and_the_chart_unrolls_the_cylinder():
    s = cylinder()
    bases, rots = around(np.linspace(-150, -30, 61), np.full(61, 3.0))
    samples, frames = sf.develop(s, bases, rots, (0.0, 0.0))
    T = frames[:, 5:8]
    assert np.abs(T[:, 2]).max() < 1e-4  # stays horizontal around the cylinder
    # the chart's x grows by the arc length (the polygon's chord per step), y stays
    step = np.diff(frames[:, 0])
    arc = 40.0 * np.radians(2.0) * np.cos(np.pi / 48)
    np.testing.assert_allclose(step, arc, rtol=0.03)
    np.testing.assert_allclose(frames[:, 1], frames[0, 1], atol=1e-4)
    np.testing.assert_allclose(samples[:, 2], L - 3.0, atol=0.2)  # pressing 3 mm everywhere
    np.testing.assert_allclose(samples[:, 3:5], 0.0, atol=1e-3)  # upright against the normal


def test_texel_points_follow_the_uv_map_and_pad_the_islands():
    s, rot, scale, centre = grid(angle_deg=30.0, scale=0.4 / 100)
    W = 200
    tp = sf.texel_points(s, W, W)
    uv = (np.stack([tp.index % W, tp.index // W], axis=1) + 0.5) / W
    xy = ((uv - centre) / scale) @ rot  # the inverse of the UV map
    np.testing.assert_allclose(tp.xyz[:, :2], xy, rtol=0, atol=1e-4)  # float32 points
    # every texel inside the UV square has a point; the pad reaches PAD_TEXELS beyond
    inside = np.abs(xy).max(axis=1) <= 50.0
    assert inside.sum() > 0.95 * 0.16 * W * W
    assert np.abs(xy).max() > 50.0 and np.abs(xy).max() < 50.0 + 2 * sf.PAD_TEXELS / (0.4 * W / 100)


def test_meshes_that_cannot_be_paper_get_one_message():
    s = cylinder()
    with pytest.raises(sf.SurfaceError, match="no UV map"):
        sf.surface_from_arrays(s.verts, s.tris, None, "Mesh 'Cube'")
    with pytest.raises(sf.SurfaceError, match="UV map has no area"):
        sf.surface_from_arrays(s.verts, s.tris, np.zeros_like(s.uvs), "Mesh 'Cube'")
    for shift in (1.0, -0.01):  # a UDIM tile (1002), an island just off the image
        with pytest.raises(sf.SurfaceError, match=r"UV map reaches outside the image \(0..1"):
            sf.surface_from_arrays(s.verts, s.tris, s.uvs + [shift, 0.0], "Mesh 'Cube'")
    fin = np.array([[0, 1, 2], [0, 1, 3], [0, 1, 4]])  # three faces on one edge
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1.0]])
    with pytest.raises(sf.SurfaceError, match="not manifold: 1 edge"):
        sf.surface_from_arrays(v, fin, np.random.default_rng(0).random((3, 3, 2)), "Mesh 'Fin'")
    with pytest.raises(sf.SurfaceError, match="frames for 3 samples"):
        sf.frames_from_dict({"frames": [[0.0] * 11]}, 3)


# ----------------------------------------------------------------------------- the ink
def test_a_flat_grid_with_turned_scaled_uvs_takes_the_planes_ink_through_its_uvs():
    s, rot, scale, centre = grid(angle_deg=30.0, scale=0.4 / 100)
    n = 150
    x = np.linspace(20.0, 80.0, n)
    y = 50.0 + 12.0 * np.sin(np.linspace(0, np.pi, n))
    z = L - stroke_press(n, 2.5)
    plane_samples = np.stack([x, y, z, np.zeros(n), np.full(n, -8.0), np.zeros(n)], axis=1)
    # no fibre on either sheet: the fibre field is fixed per pixel of the sheet (a hash of its
    # row and column, like the grain), and the texture's texels are not the plane's pixels
    # (turned, scaled), so it would refuse thin ink at other places of the two marks' fringes
    no_fibre = {"fibre": 0.0}
    plane = Simulation(
        Recording(
            plane_samples,
            width_mm=100.0,
            height_mm=100.0,
            px_per_mm=PPM,
            paper_overrides=no_fibre,
        )
    ).run()
    bases = plane_samples[:, :3] - [50.0, 50.0, 0.0]
    rots = np.array([rotation_matrix(*p[3:]) for p in plane_samples])
    sim, sp = simulate_on(s, bases, rots, origin=(50.0, 50.0), paper_overrides=no_fibre)
    np.testing.assert_allclose(sim.rec.samples, plane_samples, atol=1e-4)  # the chart is the plane
    tp = sp.texels
    inside = np.abs(tp.xyz[:, :2]).max(axis=1) < 50.0
    px = np.floor((tp.xyz[inside, :2] + 50.0) * PPM).astype(int)
    on_plane = ink_of(plane)[px[:, 1], px[:, 0]]
    on_grid = ink_of(sim).ravel()[tp.index[inside]]
    a, b = on_plane > 0.3, on_grid > 0.3
    assert a.sum() > 500
    assert (a & b).sum() / (a | b).sum() > 0.93  # the same mark, texel for texel
    assert np.abs(on_plane - on_grid).mean() < 0.02
    assert ink_of(sim).ravel()[tp.index[~inside]].max() < 0.9  # only the pad around the edge


def test_a_stroke_around_a_cylinder_inks_only_under_its_path_with_constant_width():
    s = cylinder()
    n = 160
    ang = np.linspace(-160.0, -20.0, n)
    sim, sp = simulate_on(s, *around(ang, stroke_press(n, 3.0)))
    tp = sp.texels
    inked = ink_of(sim).ravel()[tp.index] > 0.3
    X = tp.xyz[inked]
    a = np.degrees(np.arctan2(X[:, 1], X[:, 0]))
    assert inked.sum() > 300
    assert a.min() > -165 and a.max() < -15  # along the path only
    assert np.abs(np.hypot(X[:, 0], X[:, 1]) - 40.0).max() < 0.5  # on the surface itself
    centre = np.abs(X[:, 2] - 60.0)
    assert centre.max() < 6.0  # within the brush's half width of the path
    # the same width all along the middle of the stroke (in the surface's millimetres)
    bins = np.arange(-130.0, -50.0, 10.0)
    widths = [np.ptp(X[(a >= b0) & (a < b0 + 10), 2]) for b0 in bins]
    assert min(widths) > 2.0 and max(widths) - min(widths) < 0.5


def test_a_stroke_across_the_seam_has_no_gap():
    s = cylinder()
    n = 160
    ang = np.linspace(-50.0, 50.0, n)  # u = 0 and u = 1 meet at angle 0
    sim, sp = simulate_on(s, *around(ang, stroke_press(n, 3.0)))
    tp = sp.texels
    ink = ink_of(sim).ravel()[tp.index]
    inked = ink > 0.3
    X = tp.xyz[inked]
    a = np.degrees(np.arctan2(X[:, 1], X[:, 0]))
    u = (tp.index % tp.W)[inked] / tp.W
    assert (u < 0.1).any() and (u > 0.9).any()  # both islands' sides of the seam
    # every degree of the stroke's middle has ink, the seam's too
    covered = np.histogram(a, bins=np.arange(-30.0, 30.0, 1.0))[0]
    assert covered.min() > 0
    # and the texels at the seam's two sides (u just above 0, just below 1) are as dark
    near = np.abs(X[:, 2] - 60.0) < 1.0
    left = ink[inked][near & (np.abs(a) < 2.0) & (u < 0.5)]
    right = ink[inked][near & (np.abs(a) < 2.0) & (u > 0.5)]
    assert left.size and right.size and abs(left.mean() - right.mean()) < 0.1


def test_replay_is_bit_for_bit_and_a_snapshot_resumes_exactly():
    s = cylinder()
    n = 90
    bases, rots = around(np.linspace(-30.0, 30.0, n), stroke_press(n, 3.0, lead=8))
    a, sp = simulate_on(s, bases, rots)
    side = sf.texture_side_mm(s)
    rec = from_dict(a.rec.to_dict())  # through the file's values
    frames = sf.frames_from_dict(rec.extra["surface"], len(rec.samples))
    b = Simulation(rec, sf.SurfacePaper(s, frames, rec.width_px, rec.height_px, PPM, side))
    b.run(40)
    snap = b.snapshot()
    b.run()
    assert np.array_equal(a.paper.ink, b.paper.ink) and np.array_equal(a.paper.wet, b.paper.wet)
    b.restore(snap)
    b.run()
    assert np.array_equal(a.paper.ink, b.paper.ink)


def test_live_samples_get_frames_that_follow_the_surface():
    s = cylinder()
    bases, rots = around([-90.0], [-5.0])
    samples, frames = sf.develop(s, bases, rots, (100.0, 100.0))
    sp = sf.SurfacePaper(s, frames, 64, 64, PPM, 100.0)
    arc = 40.0 * np.radians(30.0)  # 30 degrees along the chart's x
    for k in range(1, 31):
        sp.frame(k, [samples[0, 0] + arc * k / 30, samples[0, 1]])
    p = sp.frames[30][2:5]
    ang = np.degrees(np.arctan2(p[1], p[0]))
    assert abs(ang - (-60.0)) < 1.5 and abs(p[2] - 60.0) < 1e-3
    assert abs(np.hypot(p[0], p[1]) - 40.0) < 0.5


def test_work_per_sample_is_the_texels_near_the_mark():
    s = cylinder()
    n = 60
    bases, rots = around(np.linspace(-100.0, -80.0, n), stroke_press(n, 3.0, lead=10))
    side = sf.texture_side_mm(s)
    samples, frames = sf.develop(s, bases, rots, (side / 2, side / 2))
    rec = Recording(samples, width_mm=side, height_mm=side, px_per_mm=PPM)
    sp = sf.SurfacePaper(s, frames, rec.width_px, rec.height_px, PPM, side)
    assert not sp.tiles.built.any()  # nothing is built before the first mark
    looked_at, query = [], sp.tiles.query_box
    sp.tiles.query_box = lambda lo, hi: looked_at.append(query(lo, hi)) or looked_at[-1]
    sim = Simulation(rec, surface=sp)
    inked = []
    while not sim.done:
        sim.step()
        inked.append(sum(mk.rows.size for mk in sim.last_marks))
    assert len(looked_at) > 30 and max(inked) > 50
    # each sample looks at a few times the texels it inks, a sliver of the texture's
    assert max(len(q) for q in looked_at) < 6 * max(inked)
    assert max(len(q) for q in looked_at) < 0.01 * rec.width_px * rec.height_px
    # only the tiles the marks reached have their texel points built (20 degrees of 360)
    assert 0 < sp.tiles.built.mean() < 0.02


@pytest.mark.slow
def test_texels_built_in_any_order_give_the_same_ink_bit_for_bit():
    """The texel points are built a tile at a time where the marks reach: building them all
    first, or other tiles in a shuffled order first, changes nothing in the points or the ink."""
    s = cylinder()
    n = 90
    bases, rots = around(np.linspace(-30.0, 30.0, n), stroke_press(n, 3.0, lead=8))
    a, sp = simulate_on(s, bases, rots)
    every = sp.tiles.all()
    tiles = sf.TexelTiles(s, sp.W, sp.H)
    order = np.random.default_rng(1).permutation(tiles.built.size)
    for k in range(0, order.size, 37):  # shuffled groups of tiles
        tiles.build(order[k : k + 37])
    np.testing.assert_array_equal(tiles.owner, sp.tiles.owner)
    np.testing.assert_array_equal(tiles.xyz, sp.tiles.xyz)
    assert every.index.size == np.count_nonzero(tiles.owner >= 0)
    rec = a.rec
    frames = sf.frames_from_dict(rec.extra["surface"], len(rec.samples))
    for prepare in ("all", "shuffled half"):
        side = sf.texture_side_mm(s)
        other = sf.SurfacePaper(s, frames, rec.width_px, rec.height_px, PPM, side)
        if prepare == "all":
            other.tiles.all()
        else:
            other.tiles.build(order[: order.size // 2])
        b = Simulation(rec, surface=other).run()
        assert np.array_equal(a.paper.ink, b.paper.ink), prepare
        assert np.array_equal(a.paper.wet, b.paper.wet), prepare


def sphere(radius=50.0, n=48, m=24):
    """A UV sphere (poles on z, u = longitude / 360 deg with its seam at longitude 0)."""
    verts = [(0.0, 0.0, -radius)]
    for j in range(1, m):
        lat = -np.pi / 2 + np.pi * j / m
        for i in range(n):
            lon = 2 * np.pi * i / n
            verts.append((radius * np.cos(lat) * np.cos(lon), radius * np.cos(lat) * np.sin(lon),
                          radius * np.sin(lat)))  # fmt: skip
    verts.append((0.0, 0.0, radius))
    top = len(verts) - 1
    tris, uvs = [], []

    def ring(j, i):
        return 1 + (j - 1) * n + i % n

    for i in range(n):
        u0, u1 = i / n, (i + 1) / n
        tris.append((0, ring(1, i + 1), ring(1, i)))
        uvs.append([((u0 + u1) / 2, 0.0), (u1, 1 / m), (u0, 1 / m)])
        tris.append((top, ring(m - 1, i), ring(m - 1, i + 1)))
        uvs.append([((u0 + u1) / 2, 1.0), (u0, (m - 1) / m), (u1, (m - 1) / m)])
        for j in range(1, m - 1):
            v0, v1 = j / m, (j + 1) / m
            a, b, c, d = ring(j, i), ring(j, i + 1), ring(j + 1, i + 1), ring(j + 1, i)
            tris += [(a, b, c), (a, c, d)]
            uvs += [[(u0, v0), (u1, v0), (u1, v1)], [(u0, v0), (u1, v1), (u0, v1)]]
    return sf.surface_from_arrays(np.array(verts), np.array(tris), np.array(uvs))


def test_a_stroke_over_a_spheres_pole_and_along_its_seam_has_no_gap():
    s = sphere()
    n = 150
    lat = np.radians(np.linspace(50.0, 130.0, n))  # up the seam's meridian, over the pole
    press = stroke_press(n, 3.0)
    bases, rots = [], []
    for t, p in zip(lat, press, strict=True):
        nrm = np.array([np.cos(t), 0.0, np.sin(t)])  # past 90 deg: down the other side
        bases.append(nrm * (50.0 + L - p))
        x = np.array([0.0, 1.0, 0.0])
        rots.append(np.stack([x, np.cross(nrm, x), nrm], axis=1))
    sim, sp = simulate_on(s, np.array(bases), np.array(rots))
    tp = sp.texels
    inked = ink_of(sim).ravel()[tp.index] > 0.3
    X = tp.xyz[inked]
    assert np.abs(X[:, 1]).max() < 6.0  # under the path only
    along = np.degrees(np.arctan2(X[:, 2], X[:, 0]))  # 90 at the pole
    assert np.histogram(along, bins=np.arange(65.0, 115.0, 1.0))[0].min() > 0
    u = (tp.index % tp.W)[inked] / tp.W
    assert (u < 0.1).any() and (u > 0.9).any()  # the seam's both sides


def test_flat_writing_laid_on_a_cylinder_goes_round_it_by_its_length():
    """lay_on (Write Character on a surface): a flat horizontal line and a jump back in the
    air laid on a cylinder from the point under the brush: the frames stay on the cylinder,
    the line's length becomes arc length, a vertical stays vertical, and a flat grid's frames
    are the plane's own points."""
    cyl = cylinder()
    hit = sf.closest_point(cyl, [0.0, -60.0, 60.0])  # the front (-y side), half way up
    start = sf.start_frame(cyl, hit, (100.0, 100.0), np.array([1.0, 0.0, 0.0]))
    xs = np.r_[np.linspace(80.0, 130.0, 51), 100.0]  # 30 mm right, then 30 mm back in one jump
    samples = np.zeros((len(xs) + 20, 6))
    samples[: len(xs), 0], samples[: len(xs), 1] = xs, 100.0
    samples[len(xs) :, 0], samples[len(xs) :, 1] = 100.0, np.linspace(100.0, 120.0, 20)
    frames = sf.lay_on(cyl, start, samples, sf.TriangleGrid(cyl))
    P = frames[:, 2:5]
    r = np.hypot(P[:, 0], P[:, 1])
    assert (r > 40 * np.cos(np.pi / 48) - 1e-6).all() and (r < 40 + 1e-6).all()
    arc = np.unwrap(np.arctan2(P[:51, 0], -P[:51, 1])) * 40.0  # the arc from the front
    np.testing.assert_allclose(arc, xs[:51] - 100.0, atol=0.15)  # length kept as arc length
    np.testing.assert_allclose(P[:51, 2], 60.0, atol=1e-3)
    np.testing.assert_allclose(P[51], P[20], atol=0.05)  # the jump back lands where it was
    np.testing.assert_allclose(P[52:, 2] - 60.0, samples[52:, 1] - 100.0, atol=1e-3)
    np.testing.assert_allclose(P[52:, :2], P[51:52, :2].repeat(20, 0), atol=0.01)
    flat = grid()[0]
    hit = sf.closest_point(flat, [5.0, -7.0, 10.0])
    start = sf.start_frame(flat, hit, (100.0, 100.0), np.array([1.0, 0.0, 0.0]))
    frames = sf.lay_on(flat, start, samples, sf.TriangleGrid(flat))
    want = samples[:, :2] - 100.0 + [5.0, -7.0]
    np.testing.assert_allclose(frames[:, 2:4], want, atol=1e-4)


def small_and_huge(n=2000, huge=400.0):
    """n disjoint 1 mm triangles on a 10 mm wide strip and one huge tilted triangle."""
    rng = np.random.default_rng(7)
    at = rng.uniform(0, 10, (n, 3))
    small = at[:, None, :] + np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.2]])
    big = np.array([[[-huge / 2, -huge / 2, -huge / 3], [huge, 0, huge / 2], [0, huge, huge]]])
    corners = np.concatenate([small, big]).reshape(-1, 3)
    tris = np.arange(len(corners)).reshape(-1, 3)
    uvs = np.tile([[0.1, 0.1], [0.2, 0.1], [0.1, 0.2]], (len(tris), 1, 1))
    return sf.surface_from_arrays(corners, tris, uvs)


def test_one_huge_triangle_among_small_ones_keeps_the_grid_small_and_is_still_found():
    s = small_and_huge()
    grid = sf.TriangleGrid(s)
    assert grid.cell == 1.0  # the median triangle's size
    assert len(grid.keys) < 20 * len(s.tris)  # unbinned: 64 M cubes for the huge one
    assert list(grid.big) == [len(s.tris) - 1]
    for p in ([100.0, 100.0, 120.0], [5.0, 5.0, 5.0], [-150.0, -150.0, -90.0]):
        p = np.array(p)
        near = sf.closest_point(s, p, grid)
        full = sf.closest_point(s, p)
        assert near.tri == full.tri and np.allclose(near.point, full.point)
    far = grid.query(np.array([1000.0, 1000.0, 1000.0]))
    assert len(far) == 0


def test_a_fan_of_thousands_of_faces_gets_its_normals_in_linear_time():
    n = 4000
    ang = np.linspace(0, 2 * np.pi, n, endpoint=False)
    rim = np.c_[np.cos(ang), np.sin(ang), np.zeros(n)] * 30
    verts = np.r_[[[0.0, 0.0, 0.0]], rim]
    tris = np.c_[np.zeros(n, int), 1 + np.arange(n), 1 + (np.arange(n) + 1) % n]
    c = verts[tris]
    cross = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    fn = cross / np.linalg.norm(cross, axis=1)[:, None]
    calls = []
    real = sf.mesh._pairwise_normals
    try:
        sf.mesh._pairwise_normals = lambda v, cr, f, corners: (
            calls.append(len(corners)) or real(v, cr, f, corners)
        )
        cn = sf.corner_normals(tris, cross, fn)
    finally:
        sf.mesh._pairwise_normals = real
    assert np.allclose(cn, [0, 0, 1])
    assert sum(calls) == 0  # a flat fan: no pairs (n^2 = 16 M before)
    # a sharp vertex still compares its faces pairwise: a cube's corner keeps its faces' normals
    box = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    t = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2]])
    cb = box[t]
    crb = np.cross(cb[:, 1] - cb[:, 0], cb[:, 2] - cb[:, 0])
    fnb = crb / np.linalg.norm(crb, axis=1)[:, None]
    assert np.allclose(sf.corner_normals(t, crb, fnb)[:, 0], fnb)


def test_closest_point_through_the_grid_is_exact_and_cheap_far_off_the_surface():
    """A brush beside a vase (its axis missing the surface) finds the nearest point through
    the triangle grid, widening the cube it looks in, not by looking at every triangle."""
    s = cylinder(n=96, m=24)
    grid = sf.TriangleGrid(s)
    looked = []
    real = sf.query._closest_among
    try:
        sf.query._closest_among = lambda surface, p, tris: (
            looked.append(len(surface.tris) if tris is None else len(tris))
            or real(surface, p, tris)
        )
        cost = []
        for p in ([80.0, 10.0, 60.0], [35.0, 2.0, 60.0], [0.0, 300.0, -50.0]):
            p = np.array(p)
            looked.clear()
            got = sf.closest_point(s, p, grid)
            cost.append(sum(looked))
            want = real(s, p, None)
            assert got.tri == want.tri and np.array_equal(got.point, want.point)
    finally:
        sf.query._closest_among = real
    # beside the cylinder (40 mm off its side, 5 mm inside it): a small part of it is looked at
    assert max(cost[:2]) < len(s.tris) / 4
    # develop uses the grid where the axis misses: poses beside the cylinder, pointing away
    bases = np.array([[70.0, 0.0, 60.0], [70.0, 1.0, 60.0]])
    rots = np.array([rotation_matrix(0.0, 90.0, 0.0)] * 2)
    a = sf.develop(s, bases, rots, (0.0, 0.0), near=grid)
    b = sf.develop(s, bases, rots, (0.0, 0.0))
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])


def test_a_live_stroke_started_across_the_cylinder_lands_under_the_cursor():
    """Live painting: the mouse's next point 120 degrees round the cylinder (a new stroke on
    its far side) gets a chart position walked over the surface, and the frame made for it,
    followed in short steps, lies where the mouse is."""
    s = cylinder()
    bases, rots = around([-90.0], [-5.0])
    samples, frames = sf.develop(s, bases, rots, (100.0, 100.0))
    sp = sf.SurfacePaper(s, frames, 64, 64, PPM, 100.0)
    for ang, z in ((30.0, 80.0), (-130.0, 40.0), (-80.0, 62.0)):
        a = np.radians(ang)
        hit = sf.closest_point(s, [40 * np.cos(a), 40 * np.sin(a), z], sp.near)
        xy = sf.chart_xy_over(s, sp.frames[-1], hit.point, sp.near)
        p = sp.frame(len(sp.frames), xy)[2:5]
        assert np.linalg.norm(p - hit.point) < 1.0, (ang, p, hit.point)


def test_texel_tiles_built_from_two_threads_at_once_give_the_same_points():
    """A kept SurfacePaper is shared by a writing worker and Blender's thread: tiles built by
    both at once (under the tiles' lock) hold the points built by one."""
    import threading

    s = cylinder(n=96, m=24)
    one = sf.TexelTiles(s, 512, 512)
    ref = one.all()
    two = sf.TexelTiles(s, 512, 512)
    boxes = [
        (np.array([-50.0, -50.0, z]), np.array([50.0, 50.0, z + 30.0])) for z in range(0, 120, 30)
    ]
    ts = [
        threading.Thread(target=lambda bs=bs: [two.query_box(lo, hi) for lo, hi in bs])
        for bs in (boxes, boxes[::-1])
    ]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    got = two.all()
    assert np.array_equal(got.index, ref.index) and np.array_equal(got.xyz, ref.xyz)
    assert isinstance(two._lock, type(threading.Lock()))


def test_a_uv_point_is_found_on_the_surface_with_the_textures_axes():
    """uv_hit reads the UV map backwards (a layout made in the texture, put on the mesh) and
    uv_axes gives the texture's x and y on the surface: on the turned, scaled grid they are the
    plane's point and the turned axes; on the cylinder u goes round it; off the islands None."""
    s, rot, scale, centre = grid(angle_deg=30.0, scale=1.0 / 250.0)
    xy = np.array([12.0, -20.0])
    uv = np.asarray(centre) + rot @ xy * scale
    hit = sf.uv_hit(s, uv)
    np.testing.assert_allclose(hit.point, [*xy, 0.0], atol=1e-9)
    du, dv = sf.uv_axes(s, hit.tri)
    np.testing.assert_allclose(du[:2], rot[0] / scale, atol=1e-6)  # mm per unit of u
    np.testing.assert_allclose(dv[:2], rot[1] / scale, atol=1e-6)
    assert sf.uv_hit(s, (0.95, 0.95)) is None  # the grid's island covers 0.3 .. 0.7 only
    c = cylinder()
    hit = sf.uv_hit(c, (0.25, 0.5))  # a quarter round, half way up
    np.testing.assert_allclose(hit.point, [0.0, 40.0, 60.0], atol=1e-9)
    du, _ = sf.uv_axes(c, hit.tri)
    assert du[0] < 0 and abs(du[1]) < 0.2 * abs(du[0]) and abs(du[2]) < 1e-9  # round it
