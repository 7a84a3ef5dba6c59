# SPDX-License-Identifier: GPL-3.0-or-later
"""The artwork at any frame: one engine Simulation per scene, moved to the sample a frame asks
for. A move restores the nearest snapshot at or before the target (backwards or forwards) and
steps on from there, so frame N always gives exactly the image of simulating straight to N.
Also the NURBS surface objects that show the writing primitives (Sec. 2, 6)."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import bpy
import numpy as np

from . import bridge
from .sim.core import placement
from .sim.engine.checkpoints import cache_key_of, load_checkpoints
from .sim.engine.simulation import Simulation
from .sim.engine.timeline import Timeline

MAX_SNAPSHOT_EVERY = 64  # samples


class Playback:
    """The scene's simulation on a Timeline (delta snapshots, see sim.timeline): a snapshot
    every frame's worth of samples, so a step of one frame back or forth re-simulates at most
    one frame."""

    def __init__(self, rec, key: str, samples_per_frame: float = 5.0, surface=None):
        self.key = key
        self.rec = rec
        every = int(min(max(round(samples_per_frame), 1), MAX_SNAPSHOT_EVERY))
        sim = Simulation(rec, surface=surface)  # surface: the mesh's SurfacePaper, or flat
        self.timeline = Timeline(sim, every, bridge.SNAPSHOT_BUDGET_BYTES)

    @property
    def sim(self) -> Simulation:
        return self.timeline.sim

    def seek(self, index: int, progress=None, should_stop=None) -> Simulation:
        return self.timeline.seek(index, progress, should_stop)


_PLAYBACKS: dict[str, Playback] = {}


def clear():
    _PLAYBACKS.clear()
    _FAILED.clear()


def cache_key(scene) -> str:
    """Identifies the stored recording text and every setting that renders it; cheap, so a
    frame change does not re-parse and re-validate an unchanged recording."""
    st = bridge.settings(scene)
    text = st.recording.as_string() if st.recording is not None else ""
    h = hashlib.sha1(text.encode("utf-8"), usedforsecurity=False)
    h.update(json.dumps(bridge.scene_overrides(st), sort_keys=True).encode("utf-8"))
    h.update(repr((scene.frame_start, scene.render.fps, scene.render.fps_base)).encode())
    h.update(bridge.surface_digest(st).encode())  # writing on a mesh: the mesh as it is
    return h.hexdigest()


_FAILED: dict[str, tuple[str, str]] = {}  # scene -> (cache key, message) of a failed parse


CACHE_EVERY = 256  # samples between the farm cache's checkpoints (see operators/bake_cache)


def cache_folder(scene):
    """Where the farm cache of ``scene`` lives, next to the saved .blend (None: not saved)."""
    if not bpy.data.filepath:
        return None
    blend = Path(bpy.data.filepath)
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in scene.name)
    return blend.parent / f"hairy_brush_cache_{blend.stem}" / safe


def _load_cache(pb: Playback, scene):
    """A fresh playback starts from the farm cache's checkpoints when they are current."""
    folder = cache_folder(scene)
    if folder is not None and cache_key_of(folder) == pb.key:
        load_checkpoints(pb.timeline, folder)


def playback_for(scene) -> Playback:
    """The scene's Playback, rebuilt only when the recording or a setting changed; a recording
    that failed to load fails again at once until it or a setting changes."""
    key = cache_key(scene)
    pb = _PLAYBACKS.get(scene.name)
    failed = _FAILED.get(scene.name)
    if failed is not None and failed[0] == key:
        raise bridge.UserError(failed[1])
    if pb is None or pb.key != key:
        try:
            rec = bridge.recording_from_scene(scene)
            surface = bridge.surface_paper(bridge.settings(scene), rec)
        except bridge.USER_ERRORS as exc:
            _FAILED[scene.name] = (key, str(exc))
            raise
        per = bridge.timeline(rec, scene)[1]  # frames per sample
        pb = Playback(rec, key, samples_per_frame=1.0 / per, surface=surface)
        _load_cache(pb, scene)
        _PLAYBACKS[scene.name] = pb
    return pb


def adopt(scene, sim: Simulation):
    """After a live stroke was stored: the scene's Playback goes on from the live simulation
    (same samples, same state) instead of simulating the whole recording again."""
    pb = _PLAYBACKS.get(scene.name)
    if pb is None or pb.sim is not sim:
        return
    pb.key, pb.rec = cache_key(scene), sim.rec


def show(scene, index: int, progress=None, should_stop=None) -> Simulation:
    """Put the paper image (and the primitive objects, if built) at sample ``index``; only what
    changed since the image was last shown is converted (see bridge.show_paper)."""
    st = bridge.settings(scene)
    sim = playback_for(scene).seek(index, progress, should_stop)
    bridge.show_paper(bridge.ensure_paper_image(st), sim.paper, sim.index)
    if primitive_objects(scene):
        sync_primitives(scene, sim, create=False)
    return sim


def show_frame(scene, frame: float) -> Simulation:
    pb = playback_for(scene)
    return show(scene, bridge.samples_at_frame(pb.rec, scene, frame))


# ------------------------------------------------------------------------------ primitives
def primitive_objects(scene) -> list:
    objs = [o for o in scene.objects if bridge.PRIMITIVE_TAG in o]
    return sorted(objs, key=lambda o: int(o[bridge.PRIMITIVE_TAG]))


def _new_surface_curve(name: str, shape) -> bpy.types.Curve:
    """A NURBS surface curve of the engine's net shape (``SweepLayout.bezier_net_shape``: the
    control points and orders of a primitive in Bezier form). Blender's Python API cannot size a
    surface directly, so rows are added as splines and joined with Make Segment, once."""
    cu = bpy.data.curves.new(name, "SURFACE")
    cu.dimensions = "3D"
    nu, nv = shape.points_u, shape.points_v
    for j in range(nu):
        sp = cu.splines.new("NURBS")
        sp.points.add(nv - 1)
        for i, p in enumerate(sp.points):
            p.co = (i, j, 0.0, 1.0)
            p.select = True
    tmp = bpy.data.objects.new(name + " (building)", cu)
    scene = bpy.context.scene
    scene.collection.objects.link(tmp)
    vl = bpy.context.view_layer
    prev_active = vl.objects.active
    if bpy.context.mode != "OBJECT":
        bpy.ops.object.mode_set(mode="OBJECT")
    try:
        vl.objects.active = tmp
        bpy.ops.object.mode_set(mode="EDIT")
        bpy.ops.curve.make_segment()
        bpy.ops.object.mode_set(mode="OBJECT")
    finally:
        vl.objects.active = prev_active
        bpy.data.objects.remove(tmp)
    sp = cu.splines[0]
    if len(cu.splines) != 1 or (sp.point_count_u, sp.point_count_v) != (nu, nv):
        raise RuntimeError(
            f"building a NURBS surface gave {len(cu.splines)} splines of "
            f"{sp.point_count_u} x {sp.point_count_v} points (expected 1 of {nu} x {nv})"
        )
    sp.order_u, sp.order_v = shape.order_u, shape.order_v  # cubic along the axis, quadratic around
    sp.use_endpoint_u = sp.use_endpoint_v = True
    sp.use_bezier_u = sp.use_bezier_v = True  # the engine net is refined to Bezier form
    sp.resolution_u, sp.resolution_v = 3, 3
    sp.use_smooth = True
    return cu


def _collection(scene):
    coll = bpy.data.collections.get(bridge.PRIMITIVE_COLLECTION)
    if coll is None:
        coll = bpy.data.collections.new(bridge.PRIMITIVE_COLLECTION)
    if coll.name not in scene.collection.children:
        scene.collection.children.link(coll)
    return coll


def sync_primitives(scene, sim: Simulation, create: bool = True) -> int:
    """Show each writing primitive of the brush as a NURBS surface object parented to the brush
    empty; control points, weights and knots come from the engine (``HairyBrush.surface_nets``).
    Splitting adds objects; merged primitives hide theirs. Returns the number shown."""
    st = bridge.settings(scene)
    brush_obj, paper_obj = bridge.require_brush_and_paper(st)
    nets, _breaks = sim.brush.surface_nets()
    to_local = np.linalg.inv(np.array(brush_obj.matrix_world)) @ bridge.engine_to_world(
        st, paper_obj
    )
    co = placement.primitive_points(nets, to_local).astype(np.float32)
    objs = primitive_objects(scene)
    if len(objs) < len(co) and (create or objs):
        coll = _collection(scene)
        template = objs[0].data if objs else None
        for i in range(len(objs), len(co)):
            name = f"HairyBrush Primitive {i:02d}"
            cu = (
                template.copy()
                if template is not None
                else _new_surface_curve(name, sim.brush.layout.bezier_net_shape())
            )
            cu.name = name
            template = cu
            obj = bpy.data.objects.new(name, cu)
            obj[bridge.PRIMITIVE_TAG] = i
            coll.objects.link(obj)
            obj.parent = brush_obj
            objs.append(obj)
    for i, obj in enumerate(objs):
        shown = i < len(co)
        obj.hide_viewport = obj.hide_render = not shown
        if not shown:
            continue
        if obj.parent is not brush_obj:
            obj.parent = brush_obj
        obj.matrix_parent_inverse.identity()
        obj.matrix_basis.identity()
        obj.data.splines[0].points.foreach_set("co", co[i].ravel())
        obj.data.update_tag()
    return len(co)
