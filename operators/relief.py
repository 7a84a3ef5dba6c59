# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.relief: the writing as a shape (Sec. 9's "3D writing effects"): the selected
meshes are carved (like a stone tablet) or embossed under the ink, through their UV maps.

It stays live: a Displace modifier reads the paper image, so re-simulating or a frame change
updates the relief. Displacement along the normal is (texture value - paper's value) x
strength, so the bare paper does not move and full ink moves by the depth. By default
(``follow='DENSITY'``, issue 17.3: "in proportion to the ink density") the modifier reads an ink
density image (images.density_image, refreshed with the paper image), and the displacement is
exactly the density x the depth. With ``follow='VALUE'`` it reads the paper image's value
instead (linear light for a float image, so thin ink moves more than in proportion to its
density: half density, 79% of the depth), which costs no second image refresh.

Any mesh shows it (issue 29.7; sim.surface.relief plans it): with Detail Auto (-1, the default)
the faces under the ink are cut in two as often as the ink's texels need (a Geometry Nodes
modifier before the Displace: Subdivide Mesh on the faces the attribute RELIEF_FACES marks, and
one ring around them), every texel of ink getting a vertex: no stroke falls between vertices,
no stairs. A mesh that would need more vertices than the plan allows gets the relief in its
materials instead (a bump map of the paper image), and the report says which it got. Detail 0
or more is the user's own uniform Simple subdivision, as before, with a warning when it leaves
the ink coarser than its texels."""

from __future__ import annotations

import bpy
import numpy as np

from ..blender import checks, images, materials, playback, surfaces, transforms
from ..sim.paper import display
from ..sim.surface.relief import INK_LEVEL, MAX_LEVELS, plan_relief
from . import polls

RELIEF = "HairyBrush Relief"
DETAIL = "HairyBrush Relief Detail"
CUT_GROUP = "HairyBrush Relief Cut"  # the Geometry Nodes group that cuts the faces under the ink
RELIEF_FACES = "hairy_brush_relief"  # the mesh's face attribute: the faces the group cuts
COARSE_TEXELS = 4.0  # the user's detail leaves edges longer than this (texels): a warning
LUMA = (1 / 3, 1 / 3, 1 / 3)  # a texture's value is its colour's mean (Blender's image texture)


def paper_value(st, img) -> float:
    """The texture value the blank paper has in the image (what the Displace modifier reads)."""
    color = display.encode(images.blank_color(st), linear=img.is_float)
    return float(sum(c * w for c, w in zip(color, LUMA, strict=True)))


def relief_texture(img) -> bpy.types.Texture:
    tex = bpy.data.textures.get(RELIEF)
    if tex is None or tex.type != "IMAGE":
        tex = bpy.data.textures.new(RELIEF, "IMAGE")
    tex.image = img
    tex.extension = "EXTEND"
    return tex


def add_relief(obj, tex, strength: float, mid: float, detail: int, auto: bool = False):
    """Displace modifier on ``obj``, after the cut that gives it ``detail`` levels: the cut
    group on the faces under the ink (``auto``), or a uniform Simple subdivision."""
    mods = obj.modifiers
    kind = "NODES" if auto else "SUBSURF"
    if DETAIL in mods and (detail == 0 or mods[DETAIL].type != kind):
        mods.remove(mods[DETAIL])
    if detail > 0 and auto:
        cut = mods.get(DETAIL) or mods.new(DETAIL, "NODES")
        cut.node_group = cut_group()
        cut[_level_socket(cut.node_group)] = detail
    elif detail > 0:
        sub = mods.get(DETAIL) or mods.new(DETAIL, "SUBSURF")
        sub.subdivision_type = "SIMPLE"
        sub.levels = sub.render_levels = detail
    disp = mods.get(RELIEF) or mods.new(RELIEF, "DISPLACE")
    disp.texture = tex
    disp.texture_coords = "UV"
    disp.uv_layer = obj.data.uv_layers.active.name
    disp.direction = "NORMAL"
    disp.mid_level = mid
    disp.strength = strength
    if DETAIL in mods:  # the cut comes first
        names = [m.name for m in mods]
        if names.index(DETAIL) > names.index(RELIEF):
            mods.move(names.index(DETAIL), names.index(RELIEF))


def remove_relief(obj):
    for name in (RELIEF, DETAIL):
        if name in obj.modifiers:
            obj.modifiers.remove(obj.modifiers[name])


def _level_socket(group) -> str:
    return next(i.identifier for i in group.interface.items_tree if i.name == "Level")


def cut_group():
    """The node group: the faces the mesh's RELIEF_FACES attribute marks, subdivided ``Level``
    times, joined again to the others (the shared vertices merged)."""
    group = bpy.data.node_groups.get(CUT_GROUP)
    if group is not None:
        return group
    group = bpy.data.node_groups.new(CUT_GROUP, "GeometryNodeTree")
    io = group.interface
    io.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    level = io.new_socket("Level", in_out="INPUT", socket_type="NodeSocketInt")
    level.default_value, level.min_value, level.max_value = 1, 0, MAX_LEVELS
    io.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    nodes, links = group.nodes, group.links
    gin, gout = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    marked = nodes.new("GeometryNodeInputNamedAttribute")
    marked.data_type = "BOOLEAN"
    marked.inputs["Name"].default_value = RELIEF_FACES
    split = nodes.new("GeometryNodeSeparateGeometry")
    split.domain = "FACE"
    cut = nodes.new("GeometryNodeSubdivideMesh")
    join = nodes.new("GeometryNodeJoinGeometry")
    weld = nodes.new("GeometryNodeMergeByDistance")
    weld.inputs["Distance"].default_value = 1e-7  # the vertices the two parts share
    for i, node in enumerate((gin, marked, split, cut, join, weld, gout)):
        node.location = (200 * i, 0)
    links.new(gin.outputs[0], split.inputs["Geometry"])
    links.new(marked.outputs["Attribute"], split.inputs["Selection"])
    links.new(split.outputs["Selection"], cut.inputs["Mesh"])
    links.new(gin.outputs[1], cut.inputs["Level"])
    links.new(split.outputs["Inverted"], join.inputs["Geometry"])
    links.new(cut.outputs["Mesh"], join.inputs["Geometry"])
    links.new(join.outputs["Geometry"], weld.inputs["Geometry"])
    links.new(weld.outputs["Geometry"], gout.inputs[0])
    return group


def mesh_faces(me):
    """(face start, face loop count, loop vertices, loop UVs) of a mesh, as Blender keeps them."""
    n, nl = len(me.polygons), len(me.loops)
    start, total = np.empty(n, np.int64), np.empty(n, np.int64)
    me.polygons.foreach_get("loop_start", start)
    me.polygons.foreach_get("loop_total", total)
    verts = np.empty(nl, np.int64)
    me.loops.foreach_get("vertex_index", verts)
    uv = np.empty(nl * 2, np.float64)
    me.uv_layers.active.data.foreach_get("uv", uv)
    return start, total, verts, uv.reshape(-1, 2)


def mark_faces(me, faces):
    """The mesh's RELIEF_FACES attribute: the faces the cut group subdivides."""
    attr = me.attributes.get(RELIEF_FACES)
    if attr is None or attr.domain != "FACE" or attr.data_type != "BOOLEAN":
        if attr is not None:
            me.attributes.remove(attr)
        attr = me.attributes.new(RELIEF_FACES, "BOOLEAN", "FACE")
    attr.data.foreach_set("value", np.asarray(faces, bool))


class HAIRY_BRUSH_OT_relief(bpy.types.Operator):
    """Carve the writing into the selected meshes, or emboss it, through their UV maps: a live
    modifier that reads the paper image (re-simulating updates it)"""

    bl_idname = "hairy_brush.relief"
    bl_label = "Carve or Emboss the Writing"
    bl_options = {"REGISTER", "UNDO"}

    mode: bpy.props.EnumProperty(
        name="Mode",
        items=(
            ("CARVE", "Carve", "The surface goes in under the ink, like a stone tablet"),
            ("EMBOSS", "Emboss", "The surface comes out under the ink"),
        ),
        default="CARVE",
    )
    depth_mm: bpy.props.FloatProperty(
        name="Depth (mm)",
        default=2.0,
        min=0.0,
        max=1000.0,
        description="How far full ink moves the surface, in millimetres of the mesh's own "
        "units (metres in a scene at scale 1)",
    )
    follow: bpy.props.EnumProperty(
        name="Depth Follows",
        items=(
            (
                "VALUE",
                "Image Value",
                "The paper image's value (linear light): full ink moves by the depth, thin ink "
                "somewhat more than its share",
            ),
            (
                "DENSITY",
                "Ink Density",
                "The ink's density, exactly in proportion: the relief reads an ink density image "
                "that follows the paper (it costs a second image refresh)",
            ),
        ),
        default="DENSITY",
    )
    detail: bpy.props.IntProperty(
        name="Detail",
        default=-1,
        min=-1,
        max=MAX_LEVELS,
        description="How often the faces are cut in two before the relief (-1, Auto: the faces "
        "under the ink, as often as the ink's texels need; 0: the mesh as it is; more: a "
        "uniform Simple subdivision of that many levels)",
    )
    method: bpy.props.EnumProperty(
        name="Relief In",
        items=(
            (
                "AUTO",
                "Auto",
                "The mesh's shape, cut where the ink is, unless that would take too many "
                "vertices: then a bump map in its material",
            ),
            ("GEOMETRY", "Geometry", "The mesh's shape (a Displace modifier)"),
            ("MATERIAL", "Material", "A bump map in the mesh's materials (renders show it)"),
        ),
        default="AUTO",
    )

    @classmethod
    def poll(cls, context):
        return polls.paper_image_and_meshes(cls, context)

    def execute(self, context):
        st = checks.settings(context.scene)
        meshes = polls.selected_meshes(context)
        with_uv = [o for o in meshes if o.data.uv_layers]
        if not with_uv:
            self.report({"ERROR"}, "None of the selected meshes has a UV map to read the ink")
            return {"CANCELLED"}
        img = st.paper_image
        sign = 1.0 if self.mode == "CARVE" else -1.0
        try:  # the engine's own density at the sample the image shows
            ink = playback.show(context.scene, int(img[images.SHOWN_TAG])).paper.ink
            density = images.density_of(ink)
        except (*checks.USER_ERRORS, KeyError, MemoryError):  # else as the image shows it
            density = images.density_from_image(st, img, surfaces.paper_texture(st))
        if self.follow == "DENSITY":  # displacement = density x (-sign depth)
            dens = images.density_image(img, create=True)  # made once nothing can fail
            images.write_density(dens, density)
            mid, strength, tex = 0.0, -sign * self.depth_mm / transforms.MM, relief_texture(dens)
        else:  # displacement = (value - paper's value) x strength: 0 bare, -sign depth full
            mid = paper_value(st, img)
            strength = sign * self.depth_mm / transforms.MM / max(mid, 1e-6)
            tex = relief_texture(img)
        inked = density > INK_LEVEL
        said = []
        try:
            for obj in with_uv:
                said.append(self._relief_on(obj, tex, strength, mid, inked, st, img))
        except checks.USER_ERRORS as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        skipped = [o.name for o in meshes if not o.data.uv_layers]
        if skipped:
            self.report({"WARNING"}, f"No UV map, skipped: {', '.join(skipped)}")
        for level, text in said:
            self.report({level}, text)
        verb = "Carved into" if self.mode == "CARVE" else "Embossed on"
        self.report({"INFO"}, f"{verb} {len(with_uv)} mesh(es), {self.depth_mm:g} mm")
        return {"FINISHED"}

    def _relief_on(self, obj, tex, strength, mid, inked, st, img):
        """The relief on one mesh, as its plan says; returns (report level, message)."""
        me = obj.data
        user_levels = None if self.detail < 0 else self.detail
        plan = plan_relief(*mesh_faces(me), len(me.vertices), inked, user_levels)
        method = plan.method if self.method == "AUTO" else self.method
        if method == "MATERIAL":
            remove_relief(obj)
            mats = [m for m in me.materials if m is not None]
            if not mats:
                mats = [materials.new_material(f"{obj.name} Relief")]
                me.materials.append(mats[0])
            depth_m = self.depth_mm / transforms.MM / max(paper_value(st, img), 1e-6)
            for mat in mats:
                materials.add_relief_bump(
                    mat, img, me.uv_layers.active.name, depth_m, self.mode == "EMBOSS"
                )
            if plan.method == "MATERIAL":
                return "INFO", plan.message(obj.name)
            return "INFO", f"'{obj.name}': the relief is a bump map in its material"
        for mat in me.materials:
            if mat is not None:
                materials.remove_relief_bump(mat)
        auto = user_levels is None
        if auto:
            mark_faces(me, plan.faces)
        add_relief(obj, tex, strength, mid, plan.levels, auto=auto)
        left = plan.edge_texels / 2**plan.levels  # the ink's texels between vertices
        if not auto and left > COARSE_TEXELS:
            return "WARNING", (
                f"'{obj.name}': its edges under the ink span {left:.0f} of the ink's texels: "
                "the relief shows in blocks or not at all (Detail Auto cuts the faces under "
                "the ink as finely as it needs)"
            )
        if plan.method == "MATERIAL":
            return "WARNING", f"'{obj.name}': about {plan.vertices:,} vertices for the relief"
        return "INFO", plan.message(obj.name)
