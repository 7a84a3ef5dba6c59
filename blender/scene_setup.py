# SPDX-License-Identifier: GPL-3.0-or-later
"""Building the scene: the brush empty and its hair marker, the paper plane (or a mesh made the
paper, issue 17: the image's size follows the mesh's area and px/mm, the brush hovers above
it), and the brush following a change of hair length."""

from __future__ import annotations

import math

import bpy
import numpy as np
from mathutils import Matrix, Vector

from ..sim import surface as surf
from ..sim.core.params import HOVER_MM
from ..sim.core.recording import PAPER_MM_RANGE
from . import checks, images, keyframes, materials, presets, surfaces, transforms

HAIR_TAG = "hairy_brush_hair"


def paper_mesh(name: str, width_m: float, height_m: float) -> bpy.types.Mesh:
    """A plane of the paper's size, UV (0, 0) at its lower-left corner."""
    w, h = width_m / 2, height_m / 2
    me = bpy.data.meshes.new(name)
    me.from_pydata([(-w, -h, 0), (w, -h, 0), (w, h, 0), (-w, h, 0)], [], [(0, 1, 2, 3)])
    uv = me.uv_layers.new(name="UVMap")
    for loop, co in zip(me.loops, ((0, 0), (1, 0), (1, 1), (0, 1)), strict=True):
        uv.data[loop.index].uv = co
    me.update()
    return me


def resize_paper(st):
    """Make the paper plane match the paper size in the settings (the property update of Width
    and Height calls this, so the plane follows every change and every import)."""
    obj = st.paper_object
    if obj is None or obj.type != "MESH" or surfaces.SURFACE_TAG in obj:
        return  # a surface keeps its shape: its size is the texture's (setup(surface=True))
    w, h = st.paper_width_mm / transforms.MM, st.paper_height_mm / transforms.MM
    if not (math.isfinite(w) and math.isfinite(h)):
        return
    me = obj.data
    xs = [v.co.x for v in me.vertices]
    ys = [v.co.y for v in me.vertices]
    if xs and abs((max(xs) - min(xs)) - w) <= 1e-7 and abs((max(ys) - min(ys)) - h) <= 1e-7:
        return
    if len(me.vertices) == 4 and me.users == 1:  # the plane Setup made: move its corners
        for v in me.vertices:
            v.co.x = w / 2 if v.co.x > (max(xs) + min(xs)) / 2 else -w / 2
            v.co.y = h / 2 if v.co.y > (max(ys) + min(ys)) / 2 else -h / 2
        me.update()
        return
    obj.data = paper_mesh(me.name, w, h)
    for m in me.materials:
        obj.data.materials.append(m)
    if me.users == 0:
        bpy.data.meshes.remove(me)


def hair_marker(brush):
    """The brush's hair marker (a child empty drawn as an arrow from the base down to the
    tip of the unbent hair: where the arrow's point meets the paper, the brush touches)."""
    return next((c for c in brush.children if HAIR_TAG in c), None)


def show_hair_length(st, hair_mm: float):
    """Make or update the hair marker of the settings' brush."""
    brush = st.brush_object
    if brush is None:
        return
    marker = hair_marker(brush)
    if marker is None:
        marker = bpy.data.objects.new("HairyBrush Hair", None)
        marker[HAIR_TAG] = 1
        marker.empty_display_type = "SINGLE_ARROW"
        marker.rotation_euler = (math.pi, 0.0, 0.0)  # the arrow points down the hair
        marker.hide_render = True
        marker.hide_select = True
        for coll in brush.users_collection:
            coll.objects.link(marker)
        marker.parent = brush
    marker.empty_display_size = hair_mm / transforms.MM


def follow_hair_length(st):
    """After the brush preset changed: the marker shows the new hair length and the brush
    empty (with its location keyframes) moves by the change, so it hovers or presses as far
    above or into its touching height as before. Returns the change in mm."""
    new = presets.hair_length(st)
    delta = new - st.touch_height_mm
    st.touch_height_mm = new
    brush, paper = st.brush_object, st.paper_object
    if brush is None:
        return delta
    show_hair_length(st, new)
    # an old height that is not a number (a damaged .blend) moves nothing (issue 30)
    if not math.isfinite(delta) or abs(delta) < 1e-9 or paper is None:
        return delta
    move = _basis_offset(brush, paper, delta)
    brush.location = brush.location + Vector(move)
    ad = brush.animation_data
    if ad is not None and ad.action is not None:
        for fc in keyframes.fcurves(ad):
            if fc.data_path != "location" or abs(move[fc.array_index]) < 1e-12:
                continue
            d = move[fc.array_index]
            for kp in fc.keyframe_points:
                kp.co.y += d
                kp.handle_left.y += d
                kp.handle_right.y += d
            fc.update()
    return delta


def _basis_offset(brush, paper, delta_mm: float) -> np.ndarray:
    """The change of the brush's location that moves it ``delta_mm`` along the paper's
    normal (in the engine's millimetres, as a sample's z)."""
    world = np.array(paper.matrix_world)[:3, :3] @ np.array([0.0, 0.0, delta_mm / transforms.MM])
    if brush.parent is None:
        return world
    parent = np.array(brush.parent.matrix_world) @ np.array(brush.matrix_parent_inverse)
    return np.linalg.solve(parent[:3, :3], world)


def surface_target(context):
    """The mesh to make paper: the active object if it is a selected mesh, else the first
    selected mesh; None when no mesh is selected."""
    act = context.active_object
    if act is not None and act.type == "MESH" and act.select_get():
        return act
    return next((o for o in context.selected_objects or [] if o.type == "MESH"), None)


def surface_side(st, surface) -> float:
    """The texture's side (mm at the average texel size), checked against what the paper
    settings and the memory hold."""
    side = surf.texture_side_mm(surface)
    lo, hi = PAPER_MM_RANGE
    if not lo <= side <= hi:
        raise checks.UserError(
            f"The mesh's texture would be {side:.3g} mm a side at its size; it must lie between "
            f"{lo:g} and {hi:g} mm: scale the mesh"
        )
    n = max(1, int(round(side * st.px_per_mm)))
    checks.check_paper_pixels(n, n, checks.SURFACE_BYTES_PER_PIXEL)
    return side


def hover_above(surface, clearance_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """(base, rotation) in the surface's space of a brush upright above the surface, facing it
    where it faces the viewer: along its mean normal for an open sheet (a tablet), from the
    front (-y) for a closed or round one (a vase)."""
    c = surface.corners
    area_n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]).sum(axis=0) / 2
    look = np.array([0.0, -1.0, 0.0])
    if np.linalg.norm(area_n) > 0.5 * surface.area_mm2:
        look = area_n / np.linalg.norm(area_n)
    lo, hi = surface.verts.min(axis=0), surface.verts.max(axis=0)
    far = (lo + hi) / 2 + look * (np.linalg.norm(hi - lo) + 1000.0)
    hit = surf.closest_point(surface, far)
    n = surf.normal_at(surface, hit)
    t = surf.transport(np.array([1.0, 0.0, 0.0]), n)
    return hit.point + n * clearance_mm, np.stack([t, np.cross(n, t), n], axis=1)


def place_brush(st, surface, clearance_mm: float):
    base, rot = hover_above(surface, clearance_mm)
    rel = np.eye(4)
    rel[:3, :3], rel[:3, 3] = rot, base / transforms.MM
    brush = st.brush_object
    brush.parent = st.paper_object
    brush.matrix_parent_inverse.identity()
    brush.matrix_world = Matrix((surfaces.surface_space(st.paper_object) @ rel).tolist())


def new_brush(coll):
    """The brush empty: upright (the hair hangs down its -Z), Euler ZYX (X = q, Y = d, Z = r)."""
    brush = bpy.data.objects.new("HairyBrush Brush", None)
    brush.empty_display_type = "SINGLE_ARROW"
    brush.empty_display_size = 0.03
    brush.rotation_mode = "ZYX"  # Rx(q) Ry(d) Rz(r): X = q, Y = d, Z = r
    brush.rotation_euler = (0.0, 0.0, 0.0)
    coll.objects.link(brush)
    return brush


def set_up_flat(scene) -> str:
    """A brush empty and a paper plane whose material shows the paper image (from a surface
    paper: back to a new plane, the mesh stays). Returns what was set up, for the report."""
    st = checks.settings(scene)
    checks.check_paper_size(st)
    color = images.blank_color(st)
    geom_len = presets.hair_length(st)
    coll = scene.collection
    from_surface = surfaces.is_surface(st)
    if st.paper_object is None or from_surface:
        me = paper_mesh("HairyBrush Paper", st.paper_width_mm / 1000, st.paper_height_mm / 1000)
        paper = bpy.data.objects.new("HairyBrush Paper", me)
        coll.objects.link(paper)
        st.paper_object = paper
    else:
        resize_paper(st)
    img = images.ensure_paper_image(st, color)
    if images.SHOWN_TAG not in img:
        img = images.show_blank(st, surfaces.paper_texture(st))
    mat = materials.paper_material(img)
    if mat.name not in st.paper_object.data.materials:
        st.paper_object.data.materials.append(mat)
    if st.brush_object is None or from_surface:
        brush = st.brush_object or new_brush(coll)
        brush.parent = st.paper_object
        brush.matrix_parent_inverse.identity()
        brush.rotation_mode = "ZYX"
        brush.rotation_euler = (0.0, 0.0, 0.0)
        brush.location = (0.0, 0.0, (geom_len + HOVER_MM) / transforms.MM)
        st.brush_object = brush
    st.touch_height_mm = geom_len
    show_hair_length(st, geom_len)
    return f"Paper {st.paper_object.name}, brush {st.brush_object.name}"


def set_up_surface(scene, obj) -> str:
    """The mesh ``obj`` becomes the paper (nothing changes when it cannot be: UserError).
    Returns what was set up, for the report."""
    st = checks.settings(scene)
    checks.check_settings(st)
    surface, _digest = surfaces.mesh_surface(obj)
    side = surface_side(st, surface)
    geom_len = presets.hair_length(st)
    obj[surfaces.SURFACE_TAG] = 1
    st.paper_object = obj
    st.paper_width_mm = st.paper_height_mm = side
    img = images.show_blank(st, surfaces.paper_texture(st))
    materials.surface_material(obj, img)
    if st.brush_object is None:
        st.brush_object = new_brush(scene.collection)
    place_brush(st, surface, geom_len + HOVER_MM)
    st.touch_height_mm = geom_len
    show_hair_length(st, geom_len)
    w, h = img.size
    return (
        f"Paper is the surface of '{obj.name}': a {w} x {h} px image ({side:.0f} mm a side "
        f"at {st.px_per_mm:g} px/mm), brush {st.brush_object.name} above it"
    )
