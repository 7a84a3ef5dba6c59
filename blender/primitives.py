# SPDX-License-Identifier: GPL-3.0-or-later
"""The NURBS surface objects that show the writing primitives (Sec. 2, 6): built once from the
engine's net shape, their control points set from the engine at every shown sample, in the
paper object's space (parented to it).

They are a viewport aid: their collection is hidden from final renders when it is made (the
sidebar's Show in Renders, or the collection's render switch, shows them). Their points are
placed from the engine's pose alone, never from the brush empty's matrix: while Blender renders
an animation, the frame handler sees the original objects' matrices of the frame the render
started from, not of the frame being rendered."""

from __future__ import annotations

import bpy
import numpy as np

from ..sim.core import placement
from ..sim.engine.simulation import Simulation
from . import checks, transforms

PRIMITIVE_COLLECTION = "HairyBrush Primitives"
PRIMITIVE_TAG = "hairy_brush_primitive"


def primitive_objects(scene) -> list:
    objs = [o for o in scene.objects if PRIMITIVE_TAG in o]
    return sorted(objs, key=lambda o: int(o[PRIMITIVE_TAG]))


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


def primitive_collection():
    """The primitives' collection (None before they are built)."""
    return bpy.data.collections.get(PRIMITIVE_COLLECTION)


def _collection(scene):
    coll = primitive_collection()
    if coll is None:
        coll = bpy.data.collections.new(PRIMITIVE_COLLECTION)
        coll.hide_render = True  # a viewport aid: not in F12 renders unless the artist asks
    if coll.name not in scene.collection.children:
        scene.collection.children.link(coll)
    return coll


def sync_primitives(scene, sim: Simulation, create: bool = True) -> int:
    """Show each writing primitive of the brush as a NURBS surface object parented to the paper
    object; control points, weights and knots come from the engine (``HairyBrush.surface_nets``)
    in the paper's local space, so they are right whatever frame the objects' matrices were last
    evaluated at. Splitting adds objects; merged primitives hide theirs. Returns the number
    shown."""
    st = checks.settings(scene)
    _brush_obj, paper_obj = checks.require_brush_and_paper(st)
    nets, _breaks = sim.brush.surface_nets()
    co = placement.primitive_points(nets, transforms.engine_to_paper_local(st)).astype(np.float32)
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
            obj[PRIMITIVE_TAG] = i
            coll.objects.link(obj)
            obj.parent = paper_obj
            objs.append(obj)
    for i, obj in enumerate(objs):
        shown = i < len(co)
        obj.hide_viewport = obj.hide_render = not shown
        if not shown:
            continue
        if obj.parent is not paper_obj:
            obj.parent = paper_obj
        obj.matrix_parent_inverse.identity()
        obj.matrix_basis.identity()
        obj.data.splines[0].points.foreach_set("co", co[i].ravel())
        obj.data.update_tag()
    return len(co)
