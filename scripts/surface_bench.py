# SPDX-License-Identifier: GPL-3.0-or-later
"""Time per sample writing on a surface against the flat paper (issue 17), the engine alone:
one 2 s stroke at 100 mm/s (120 Hz) by the default brush, on the flat paper, on a flat grid
mesh (the same stroke through its UVs) and round a cylinder; prints ms per sample, the share
of the surface's splat, what making the surface paper costs (its texel points are built a tile
at a time where the marks reach, during the first run), the first run's time per sample (which
builds them) and, for comparison, building every texel's point of the texture at once (what
every first Simulate or frame change paid before the points were built lazily).

    .venv/bin/python scripts/surface_bench.py [--ppm 5 10] [--glibc-trim]

Once, on this shared machine, a process that had freed a large paper ran every stage 3-4 times
slower, which looked like glibc's malloc trimming and growing its heap; it was not reproduced
later (scripts/surface_malloc.py measures it: no slowdown). ``--glibc-trim`` sets a fixed trim
threshold (mallopt) first, as MALLOC_TRIM_THRESHOLD_ would."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from sim import surface as sf  # noqa: E402
from sim.core.frames import rotation_matrix  # noqa: E402
from sim.core.recording import Recording, from_dict  # noqa: E402
from sim.engine.simulation import Simulation  # noqa: E402

L = 30.0  # the default brush's hair length, mm
N = 240  # 2 s at 120 Hz


def grid(size=200.0, n=16):
    xs = np.linspace(-size / 2, size / 2, n + 1)
    X, Y = np.meshgrid(xs, xs)
    verts = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], axis=1)
    tris = []
    for j in range(n):
        for i in range(n):
            a, b = j * (n + 1) + i, j * (n + 1) + i + 1
            tris += [(a, b, b + n + 1), (a, b + n + 1, a + n + 1)]
    tris = np.array(tris)
    return sf.surface_from_arrays(verts, tris, (verts[:, :2] / size + 0.5)[tris])


def cylinder(radius=40.0, height=160.0, n=96, m=8):
    ang = 2 * np.pi * np.arange(n) / n
    verts = np.array(
        [
            (radius * np.cos(a), radius * np.sin(a), height * j / m)
            for j in range(m + 1)
            for a in ang
        ]
    )
    tris, uvs = [], []
    for j in range(m):
        for i in range(n):
            a, b = j * n + i, j * n + (i + 1) % n
            u0, u1, v0, v1 = i / n, (i + 1) / n, j / m, (j + 1) / m
            tris += [(a, b, b + n), (a, b + n, a + n)]
            uvs += [[(u0, v0), (u1, v0), (u1, v1)], [(u0, v0), (u1, v1), (u0, v1)]]
    return sf.surface_from_arrays(verts, np.array(tris), np.array(uvs))


def press() -> np.ndarray:
    p = np.full(N, -5.0)
    p[12:-12] = 4.0
    return p


def flat_poses():
    x = np.linspace(-100.0, 100.0, N) * 0.99
    bases = np.stack([x, np.zeros(N), L - press()], axis=1)
    return bases, np.repeat(rotation_matrix(0.0, -8.0, 0.0)[None], N, axis=0)


def round_poses(radius=40.0):
    ang = np.linspace(-np.pi, np.pi, N) * 0.95  # 2 s at 100 mm/s is 200 mm: most of 251 mm
    bases, rots = [], []
    for a, p in zip(ang, press(), strict=True):
        n = np.array([np.cos(a), np.sin(a), 0.0])
        bases.append(np.array([0.0, 0.0, 80.0]) + n * (radius + L - p))
        x = np.array([-np.sin(a), np.cos(a), 0.0])
        rots.append(np.stack([x, np.cross(n, x), n], axis=1))
    return np.array(bases), np.array(rots)


def run(rec, surface=None, repeat: int = 3) -> tuple[float, dict, float]:
    """ms per sample and the stages' seconds of the fastest of ``repeat`` runs (this machine
    is shared: the first run after building a large texture is often slowed by the system),
    and the first run's ms per sample."""
    best, first = None, None
    for _ in range(repeat):
        sim = Simulation(rec, surface=surface)
        sim.timings = {}
        t0 = time.perf_counter()
        sim.run()
        ms = (time.perf_counter() - t0) / len(rec.samples) * 1000
        first = ms if first is None else first
        if best is None or ms < best[0]:
            best = (ms, sim.timings)
    return (*best, first)


def on_surface(surface, bases, rots, ppm):
    side = sf.texture_side_mm(surface)
    samples, frames = sf.develop(surface, bases, rots, (side / 2, side / 2))
    d = Recording(samples, width_mm=side, height_mm=side, px_per_mm=ppm).to_dict()
    d["surface"] = {"frames": frames.tolist()}
    rec = from_dict(d)
    t0 = time.perf_counter()
    sp = sf.SurfacePaper(surface, frames, rec.width_px, rec.height_px, ppm, side)
    return rec, sp, time.perf_counter() - t0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ppm", type=float, nargs="+", default=[5.0, 10.0])
    ap.add_argument("--glibc-trim", action="store_true", help="a fixed malloc trim threshold")
    args = ap.parse_args(argv)
    if args.glibc_trim:
        import ctypes

        ctypes.CDLL("libc.so.6").mallopt(-1, 1 << 30)  # M_TRIM_THRESHOLD
    print(
        "| paper | px/mm | texture | ms / sample | of which splat | first run ms / sample "
        "| surface paper made | all texels built at once |"
    )
    print("|---|---|---|---|---|---|---|---|")
    for ppm in args.ppm:
        bases, rots = flat_poses()
        samples = np.c_[bases[:, :2] + 100.0, bases[:, 2], np.tile([0.0, -8.0, 0.0], (N, 1))]
        plane = Recording(samples, width_mm=200.0, height_mm=200.0, px_per_mm=ppm)
        ms, _t, first = run(plane)
        print(
            f"| flat paper | {ppm:g} | {plane.width_px} px | {ms:.2f} | - | {first:.2f} | - | - |"
        )
        for name, surface, poses in (
            ("grid mesh", grid(), (bases, rots)),
            ("cylinder", cylinder(), round_poses()),
        ):
            rec, sp, build = on_surface(surface, *poses, ppm)
            ms, t, first = run(rec, sp)
            splat = t.get("surface splat", 0.0) / len(rec.samples) * 1000
            t0 = time.perf_counter()
            sf.texel_points(surface, rec.width_px, rec.height_px)
            every = time.perf_counter() - t0
            print(
                f"| {name} | {ppm:g} | {rec.width_px} px | {ms:.2f} | {splat:.2f} | {first:.2f} "
                f"| {build:.2f} s | {every:.1f} s |"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
