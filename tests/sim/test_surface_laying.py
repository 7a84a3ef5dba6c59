# SPDX-License-Identifier: GPL-3.0-or-later
"""Writing done on flat paper laid on a surface (issue 29.7): the same chart position lands at
the same place and turn whatever order the strokes come in, a character across a sphere's UV
seam is the flat one, whole, and strokes cross a sharp crease (sim.surface.geodesic)."""

from __future__ import annotations

import numpy as np
import pytest

from sim import surface as sf
from sim.core.params import load_preset
from sim.core.recording import DEFAULT_BRUSH, Recording, from_dict
from sim.engine.simulation import Simulation

L = load_preset("brush", DEFAULT_BRUSH).data["geometry"]["hair_length_mm"]
PPM = 4.0


def sphere(radius=30.0, n=48, m=24):
    """A UV sphere about the origin, u = longitude / 360 deg (its seam at longitude 0, the +x
    side), v = latitude; one vertex at each pole."""
    rows = [(0.0, 0.0, -radius)]
    for j in range(1, m):
        lat = -np.pi / 2 + np.pi * j / m
        for i in range(n):
            lon = 2 * np.pi * i / n
            rows.append(radius * np.array([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon),
                                           np.sin(lat)]))  # fmt: skip
    rows.append((0.0, 0.0, radius))
    top = len(rows) - 1

    def vid(j, i):
        return 1 + (j - 1) * n + i % n

    tris, uvs = [], []
    for i in range(n):
        u0, u1, um = i / n, (i + 1) / n, (i + 0.5) / n
        tris += [(0, vid(1, i + 1), vid(1, i)), (top, vid(m - 1, i), vid(m - 1, i + 1))]
        uvs += [[(um, 0), (u1, 1 / m), (u0, 1 / m)], [(um, 1), (u0, 1 - 1 / m), (u1, 1 - 1 / m)]]
        for j in range(1, m - 1):
            a, b, c, d = vid(j, i), vid(j, i + 1), vid(j + 1, i + 1), vid(j + 1, i)
            v0, v1 = j / m, (j + 1) / m
            tris += [(a, b, c), (a, c, d)]
            uvs += [[(u0, v0), (u1, v0), (u1, v1)], [(u0, v0), (u1, v1), (u0, v1)]]
    return sf.surface_from_arrays(np.array(rows), np.array(tris), np.array(uvs))


def roof(bend_deg, half=40.0, n=20):
    """Two 40 x 80 mm faces meeting at the ridge x = 0, the +x one bent down by bend_deg (over
    60 degrees: a sharp edge, its normals not smoothed); UVs of the sheet unbent."""
    b = np.radians(bend_deg)
    xs = np.linspace(-half, half, 2 * n + 1)
    verts, uv = [], []
    for y in xs:
        for x in xs:
            verts.append((x, y, 0.0) if x <= 0 else (x * np.cos(b), y, -x * np.sin(b)))
            uv.append(((x + half) / (2 * half), (y + half) / (2 * half)))
    m = 2 * n + 1
    tris = []
    for j in range(m - 1):
        for i in range(m - 1):
            a, c = j * m + i, (j + 1) * m + i + 1
            tris += [(a, a + 1, c), (a, c, c - 1)]
    tris = np.array(tris)
    return sf.surface_from_arrays(np.array(verts), tris, np.array(uv)[tris])


def grid_character(press=3.0, half=12.0, gap=5.0, step=0.25):
    """井 as samples on flat paper about (0, 0): two horizontals, two verticals, each touched
    down, drawn and lifted, with moves in the air between them."""
    strokes = [((-half, gap), (half, gap)), ((-half, -gap), (half, -gap)),
               ((-gap, half), (-gap, -half)), ((gap, half), (gap, -half))]  # fmt: skip
    rows, prev = [], None
    for a, b in strokes:
        a, b = np.array(a), np.array(b)
        if prev is not None:
            rows += [(*(prev + (a - prev) * t), L + 5) for t in np.linspace(0, 1, 12)[1:-1]]
        rows += [(*a, L + 5 - (5 + press) * k / 5) for k in range(6)]
        n = int(np.hypot(*(b - a)) / step)
        rows += [(*(a + (b - a) * t), L - press) for t in np.linspace(0, 1, n)]
        rows += [(*b, L - press + (5 + press) * k / 5) for k in range(1, 6)]
        prev = b
    s = np.array(rows)
    return np.c_[s, np.zeros((len(s), 3))]


def stroke_runs(samples):
    """The samples split where each stroke touches down (its move in the air before it)."""
    down = np.flatnonzero(np.diff((samples[:, 2] < L).astype(int)) == 1) + 1
    return np.split(np.arange(len(samples)), down)


def laid(surface, point, first_t, samples):
    """(start frame, frames) of samples about (0, 0) laid on the surface from ``point``."""
    side = sf.texture_side_mm(surface)
    c0 = np.array([side / 2, side / 2])
    start = sf.start_frame(surface, sf.closest_point(surface, point), c0, first_t)
    s = samples.copy()
    s[:, :2] += c0
    return start, s, sf.lay_on(surface, start, s, sf.TriangleGrid(surface))


def ink_seen(surface, start, samples, frames, to_plane) -> np.ndarray:
    """The ink simulated on the surface, its texels' points taken to the flat paper's plane by
    ``to_plane`` (points - start's point -> (N, 2) mm), at 2 px/mm, (80, 80) bool about the
    start."""
    side = sf.texture_side_mm(surface)
    rec = Recording(samples, width_mm=side, height_mm=side, px_per_mm=PPM,
                    paper_overrides={"fibre": 0.0})  # fmt: skip
    d = rec.to_dict()
    d["surface"] = {"frames": frames.tolist()}
    rec = from_dict(d)
    sp = sf.SurfacePaper(surface, frames, rec.width_px, rec.height_px, PPM, side)
    sim = Simulation(rec, surface=sp).run()
    tp = sp.texels
    dark = sim.paper.ink.mean(axis=2).ravel()[tp.index] > 0.3
    uv = to_plane(tp.xyz[dark] - start[2:5], tp.normal[dark])
    return _raster(uv)


def _raster(uv) -> np.ndarray:
    img = np.zeros((80, 80), bool)
    c = np.floor((uv[:, 0] + 20) * 2).astype(int)
    r = np.floor((uv[:, 1] + 20) * 2).astype(int)
    ok = (c >= 0) & (c < 80) & (r >= 0) & (r < 80)
    img[r[ok], c[ok]] = True
    return img


def flat_ink(samples) -> np.ndarray:
    s = samples.copy()
    s[:, :2] += 20.0
    rec = Recording(s, width_mm=40, height_mm=40, px_per_mm=PPM, paper_overrides={"fibre": 0.0})
    ink = Simulation(rec).run().paper.ink.mean(axis=2) > 0.3  # rows from y = 0 (bottom)
    return ink.reshape(80, 2, 80, 2).any(axis=(1, 3))


def iou(a, b) -> float:
    return float((a & b).sum() / (a | b).sum())


@pytest.mark.slow
def test_a_chart_position_lands_at_the_same_place_whatever_order_the_strokes_come_in():
    s = sphere()
    lat = np.radians(30.0)
    point = 30.0 * np.array([np.cos(lat), 0.0, np.sin(lat)])  # on the seam, 30 degrees up
    samples = grid_character()
    start, placed, frames = laid(s, point, np.array([0.0, 1.0, 0.0]), samples)
    order = np.concatenate(stroke_runs(samples)[::-1])  # the strokes the other way round
    again = np.empty_like(frames)
    again[order] = sf.lay_on(s, start, placed[order], sf.TriangleGrid(s))
    touch = samples[:, 2] < L
    np.testing.assert_allclose(again[touch, 2:5], frames[touch, 2:5], atol=1e-4)  # points
    np.testing.assert_allclose(again[touch, 5:8], frames[touch, 5:8], atol=1e-4)  # turns
    # and the frames lie on the sphere, the chart's distances from the start kept over it
    r = np.linalg.norm(frames[:, 2:5], axis=1)
    assert np.abs(r - 30.0).max() < 0.2
    geo = 30.0 * np.arccos(np.clip(frames[:, 2:5] @ point / (r * 30.0), -1, 1))
    chart = np.hypot(*(placed[:, :2] - start[:2]).T)
    np.testing.assert_allclose(geo, chart, atol=0.2)


@pytest.mark.slow
def test_a_character_across_a_spheres_uv_seam_is_the_flat_one_whole():
    s = sphere()
    lat = np.radians(30.0)
    n = np.array([np.cos(lat), 0.0, np.sin(lat)])
    east = np.array([0.0, 1.0, 0.0])
    samples = grid_character()
    start, placed, frames = laid(s, 30.0 * n, east, samples)
    north = np.cross(n, east)
    seen = ink_seen(s, start, placed, frames, lambda d, nrm: np.c_[d @ east, d @ north])
    assert iou(seen, flat_ink(samples)) > 0.85  # it was 0.68: strokes shifted and turned


@pytest.mark.slow
def test_strokes_cross_a_sharp_crease_as_a_sheet_folded_over_it():
    s = roof(80.0)
    samples = grid_character()
    start, placed, frames = laid(s, np.array([-6.0, 0.0, 1.0]), np.array([1.0, 0, 0]), samples)

    def unfold(d, _n):  # the bent face laid flat again: the sheet's own coordinates
        x = d[:, 0] + start[2]
        x = np.where(d[:, 2] + start[4] < -1e-6, np.hypot(x, d[:, 2] + start[4]), x)
        return np.c_[x - start[2], d[:, 1]]

    seen = ink_seen(s, start, placed, frames, unfold)
    assert iou(seen, flat_ink(samples)) > 0.85  # it was 0.79: the walk stopped at the ridge
    right = seen[:, 60:].sum()  # ink past the ridge (x > 10 mm): the horizontals' ends
    assert right > 0.8 * flat_ink(samples)[:, 60:].sum()


def test_a_walk_unfolds_over_edges_and_stops_at_the_boundary():
    s = roof(90.0)
    nbr = sf.edge_neighbours(s.tris)
    assert (nbr >= -1).all() and (nbr == -1).sum() == 4 * 40  # the sheet's rim
    start = sf.closest_point(s, np.array([-5.0, 0.3, 0.0]))
    tri, p, d, t = sf.walk(s, nbr, start.tri, start.point, np.array([1.0, 0, 0]),
                           np.array([0, 1.0, 0]), 15.0)  # fmt: skip
    np.testing.assert_allclose(p, [0.0, 0.3, -10.0], atol=1e-9)  # 5 mm, over the edge, 10 down
    np.testing.assert_allclose(d, [0.0, 0.0, -1.0], atol=1e-9)
    np.testing.assert_allclose(t, [0.0, 1.0, 0.0], atol=1e-9)  # the tangent along the edge
    tri, p, _d, _t = sf.walk(s, nbr, start.tri, start.point, np.array([-1.0, 0, 0]),
                             np.array([0, 1.0, 0]), 100.0)  # fmt: skip
    np.testing.assert_allclose(p, [-40.0, 0.3, 0.0], atol=1e-9)  # the rim
