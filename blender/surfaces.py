# SPDX-License-Identifier: GPL-3.0-or-later
"""A mesh that is the paper (issue 17): its engine Surface and SurfacePaper, kept while the mesh
is unchanged (in the runtime's caches), ray casts through Blender's BVH tree, and writing done
on flat paper laid on the surface."""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib

import numpy as np

from ..sim import surface as surf
from ..sim.core.recording import Recording
from . import checks, recordings, runtime, transforms

SURFACE_TAG = "hairy_brush_surface"  # on a mesh that is the paper (setup(surface=True))


def is_surface(st) -> bool:
    """Whether the paper is a mesh made paper by setup(surface=True), not the flat plane."""
    obj = st.paper_object
    return obj is not None and SURFACE_TAG in obj


def paper_texture(st) -> float:
    """How much the paper's own texture shows (``sim.paper.texture``): the scene's Texture on
    the flat paper, none on a mesh made paper (the engine's ``Simulation``: a mesh is not
    xuan)."""
    return 0.0 if is_surface(st) else float(st.paper_texture)


def surface_space(paper_obj) -> np.ndarray:
    """4x4: the surface's space (the paper object's axes and origin, metres, its scale applied
    to the mesh instead) -> world. The engine's surface is this space in millimetres."""
    m = np.array(paper_obj.matrix_world)
    m[:3, :3] /= np.maximum(np.linalg.norm(m[:3, :3], axis=0), 1e-30)
    return m


def mesh_arrays(obj) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """(vertices in the surface's space in mm, triangles, UVs per triangle corner or None)."""
    me = obj.data
    me.calc_loop_triangles()
    co = np.empty(len(me.vertices) * 3)
    me.vertices.foreach_get("co", co)
    to_surface = np.linalg.inv(surface_space(obj)) @ np.array(obj.matrix_world)
    verts = (co.reshape(-1, 3) @ to_surface[:3, :3].T) * transforms.MM
    tris = np.empty(len(me.loop_triangles) * 3, np.int64)
    me.loop_triangles.foreach_get("vertices", tris)
    uv_layer = me.uv_layers.active
    if uv_layer is None:
        return verts, tris.reshape(-1, 3), None
    loops = np.empty(len(me.loop_triangles) * 3, np.int64)
    me.loop_triangles.foreach_get("loops", loops)
    uv = np.empty(len(me.loops) * 2)
    uv_layer.data.foreach_get("uv", uv)
    return verts, tris.reshape(-1, 3), uv.reshape(-1, 2)[loops].reshape(-1, 3, 2)


def _digest(verts, tris, uvs) -> str:
    h = hashlib.sha1(verts.tobytes(), usedforsecurity=False)
    h.update(tris.tobytes())
    h.update(b"-" if uvs is None else uvs.tobytes())
    return h.hexdigest()


def mesh_surface(obj) -> tuple[surf.Surface, str]:
    """The engine's surface of a mesh and a digest of it (kept until the mesh changes)."""
    verts, tris, uvs = mesh_arrays(obj)
    digest = _digest(verts, tris, uvs)
    key = (obj.name, digest)
    kept = runtime.get().surfaces
    if key not in kept:
        kept.clear()
        kept[key] = surf.surface_from_arrays(verts, tris, uvs, f"Mesh '{obj.name}'")
    return kept[key], digest


@contextlib.contextmanager
def trusting_digests():
    """Within it (following frames), surface_digest takes a kept digest of the paper mesh while
    its cheap key (name, datablock, sizes, matrices, UV map) holds and no mesh changed since
    (handlers.on_depsgraph_update forgets them): a frame change neither reads nor hashes the
    mesh. Elsewhere (operators) the mesh is read and hashed, and the digest kept."""
    rt = runtime.get()
    old, rt.trust_digests = rt.trust_digests, True
    try:
        yield
    finally:
        rt.trust_digests = old


def _cheap_mesh_key(obj) -> tuple:
    me, uv = obj.data, obj.data.uv_layers.active
    mats = np.r_[np.ravel(obj.matrix_world), np.ravel(surface_space(obj))]
    sizes = (len(me.vertices), len(me.loops), len(me.polygons))
    return (obj.name, me.as_pointer(), sizes, mats.tobytes(), uv.name if uv else None)


def surface_digest(st) -> str:
    """Changes whenever the surface the scene writes on changes ('' for the flat paper)."""
    if not is_surface(st):
        return ""
    key = _cheap_mesh_key(st.paper_object)
    rt = runtime.get()
    if not rt.trust_digests or key not in rt.digests:
        rt.digests.clear()
        rt.digests[key] = _digest(*mesh_arrays(st.paper_object))
    return rt.digests[key]


def surface_paper(st, rec: Recording):
    """The engine's SurfacePaper of the scene's surface for ``rec`` (None on flat paper)."""
    if not is_surface(st):
        return None
    surface, digest = mesh_surface(st.paper_object)
    frames = surf.frames_from_dict(rec.extra.get(recordings.SURFACE_KEY), len(rec.samples))
    if frames is None:
        raise checks.UserError(
            f"The recording has no surface frames (it was made on flat paper): bake or paint "
            f"it again on '{st.paper_object.name}', or set up a flat paper to replay it"
        )
    return surface_paper_base(surface, digest, rec).with_frames(frames)


def surface_paper_base(surface, digest: str, rec: Recording, build: bool = True):
    """The SurfacePaper (no frames) of a surface at the recording's texture size and px/mm,
    kept for the session; None when it is not kept yet and ``build`` is False."""
    key = (digest, rec.width_px, rec.height_px, rec.px_per_mm, rec.width_mm)  # all it depends on
    kept = runtime.get().papers
    if key not in kept:
        if not build:
            return None
        keep_surface_paper(
            digest,
            surf.SurfacePaper(
                surface, None, rec.width_px, rec.height_px, rec.px_per_mm, rec.width_mm
            ),
        )
    return kept[key]


def keep_surface_paper(digest: str, paper):
    """Keep a SurfacePaper built elsewhere (a worker) for the session."""
    kept = runtime.get().papers
    kept.clear()
    kept[(digest, paper.W, paper.H, paper.ppm, paper.side_mm)] = paper


class SurfaceWriting:
    """Writing done on flat paper (Write Character, Imitate Picture) laid on the scene's surface
    (issue 17) around the point under the brush empty. Made on Blender's thread; ``lay`` is
    numpy only, so a worker runs it."""

    def __init__(self, scene):
        st = checks.settings(scene)
        self.surface, self.digest = mesh_surface(st.paper_object)
        base, rot = surface_pose(st, st.brush_object.matrix_world)
        hit = surf.axis_hit(self.surface, base, rot, surface_caster(st))
        self.centre = np.array(surface_origin(st))  # the writing's centre: under the brush
        self.start = surf.start_frame(self.surface, hit, self.centre, rot[:, 0])
        self.template = recordings.settings_recording(scene)
        self.paper = surface_paper_base(self.surface, self.digest, self.template, build=False)

    def lay(self, flat: Recording, size_mm: float, progress=None):
        """(recording on the surface, its finished Simulation) of a recording written on a
        flat size_mm square: the samples moved so the square's centre is the chart's point
        under the brush, their frames followed over the surface from there (sim.surface.lay_on),
        the scene's settings (the texture keeps its size), simulated on the surface."""
        from ..sim.core.recording import quantise
        from ..sim.engine.simulation import Simulation

        samples = np.array(flat.samples, dtype=float)
        samples[:, :2] += self.centre - size_mm / 2
        samples = quantise(samples)
        reach = 10 * max(self.template.width_mm, self.template.height_mm)  # what a recording holds
        if np.abs(samples[:, :2]).max() > reach:
            raise checks.UserError(
                f"A {size_mm:.0f} mm character is far larger than the surface it is laid on "
                f"(its texture covers {self.template.width_mm:.0f} mm a side): choose a smaller "
                "size"
            )

        def part(lo, hi, what):
            return None if progress is None else (lambda f: progress(lo + (hi - lo) * f, what))

        t = self.template
        if self.paper is None:  # its triangle grid also serves lay_on
            self.paper = surf.SurfacePaper(
                self.surface, None, t.width_px, t.height_px, t.px_per_mm, t.width_mm
            )
        near = self.paper.near
        frames = surf.lay_on(self.surface, self.start, samples, near, part(0, 0.3, "laying"))
        extra = {**self.template.extra, recordings.SURFACE_KEY: {"frames": frames.tolist()}}
        rec = dataclasses.replace(self.template, samples=samples, dips=list(flat.dips))
        rec = recordings.with_brush_scale(rec, flat)  # the brush it was written with
        rec.extra = extra
        sim = Simulation(rec, surface=self.paper.with_frames(frames))
        return rec, sim.run(progress=part(0.3, 1.0, "simulating on the surface"))

    def matrices(self, st, rec: Recording) -> list:
        """World matrices of the brush along the laid recording (its surface poses)."""
        frames = np.asarray(rec.extra[recordings.SURFACE_KEY]["frames"], dtype=float)
        return [surface_matrix(st, f, s) for f, s in zip(frames, rec.samples, strict=True)]


def surface_pose(st, mw) -> tuple[np.ndarray, np.ndarray]:
    """(base point in mm, rotation) of an object's world matrix in the surface's space."""
    rel = np.linalg.inv(surface_space(st.paper_object)) @ np.asarray(mw, dtype=float)
    rot = rel[:3, :3] / np.maximum(np.linalg.norm(rel[:3, :3], axis=0), 1e-30)
    return rel[:3, 3] * transforms.MM, rot


def surface_matrix(st, frame, sample) -> np.ndarray:
    """World matrix of the brush for a sample in a surface frame."""
    base, rot = surf.pose_from_sample(frame, sample)
    rel = np.eye(4)
    rel[:3, :3], rel[:3, 3] = rot, base / transforms.MM
    return surface_space(st.paper_object) @ rel


def surface_caster(st):
    """``cast(origin, direction)`` in the surface's space (mm) -> its first sim.surface.Hit or
    None, through a BVH tree of the surface's triangles (sim.surface.ray_hit looks at every
    triangle: fine for tests, slow for a mesh of many thousands while painting or baking)."""
    from mathutils import Vector
    from mathutils.bvhtree import BVHTree

    surface, digest = mesh_surface(st.paper_object)
    kept = runtime.get().casters
    if digest not in kept:
        kept.clear()
        tree = BVHTree.FromPolygons(surface.verts.tolist(), surface.tris.tolist())

        def cast(o, d):
            loc, _normal, index, dist = tree.ray_cast(Vector(o), Vector(d))
            if loc is None:
                return None
            if surface.face_normals[index] @ d > 0:
                # in through a crack (a ray along an edge can slip between faces in the
                # tree's single precision): the exact test over all triangles decides
                return surf.ray_hit(surface, o, d)
            return surf.hit_at(surface, index, loc, dist)

        kept[digest] = cast
    return kept[digest]


def surface_ray(st, origin, direction):
    """Where a world ray first meets the surface: the sim.surface.Hit, or None."""
    to_surface = np.linalg.inv(surface_space(st.paper_object))
    o = (to_surface @ np.r_[np.asarray(origin, dtype=float), 1.0])[:3] * transforms.MM
    d = to_surface[:3, :3] @ np.asarray(direction, dtype=float)
    return surface_caster(st)(o, d)


def surface_origin(st) -> tuple[float, float]:
    """The chart position a surface's first frame is developed from (see sim.surface)."""
    return float(st.paper_width_mm) / 2, float(st.paper_height_mm) / 2
