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
density: half density, 79% of the depth), which costs no second image refresh."""

from __future__ import annotations

import bpy

from ..blender import checks, images, playback, transforms
from ..sim.paper import display
from . import polls

RELIEF = "HairyBrush Relief"
DETAIL = "HairyBrush Relief Detail"
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


def add_relief(obj, tex, strength: float, mid: float, detail: int):
    """Displace modifier (and a Simple subdivision before it, for detail) on ``obj``."""
    mods = obj.modifiers
    if detail > 0:
        sub = mods.get(DETAIL) or mods.new(DETAIL, "SUBSURF")
        sub.subdivision_type = "SIMPLE"
        sub.levels = sub.render_levels = detail
    elif DETAIL in mods:
        mods.remove(mods[DETAIL])
    disp = mods.get(RELIEF) or mods.new(RELIEF, "DISPLACE")
    disp.texture = tex
    disp.texture_coords = "UV"
    disp.uv_layer = obj.data.uv_layers.active.name
    disp.direction = "NORMAL"
    disp.mid_level = mid
    disp.strength = strength
    if DETAIL in mods:  # the subdivision comes first
        names = [m.name for m in mods]
        if names.index(DETAIL) > names.index(RELIEF):
            mods.move(names.index(DETAIL), names.index(RELIEF))


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
        default=0,
        min=0,
        max=6,
        description="Simple subdivision levels before the relief, so a coarse mesh can follow "
        "the strokes (0: the mesh as it is)",
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
        if self.follow == "DENSITY":  # displacement = density x (-sign depth)
            try:  # the engine's own density at the sample the image shows
                ink = playback.show(context.scene, int(img[images.SHOWN_TAG])).paper.ink
                density = images.density_of(ink)
            except (*checks.USER_ERRORS, KeyError, MemoryError):  # else as the image shows it
                density = images.density_from_image(st, img)
            dens = images.density_image(img, create=True)  # made once nothing can fail
            images.write_density(dens, density)
            mid, strength, tex = 0.0, -sign * self.depth_mm / transforms.MM, relief_texture(dens)
        else:  # displacement = (value - paper's value) x strength: 0 bare, -sign depth full
            mid = paper_value(st, img)
            strength = sign * self.depth_mm / transforms.MM / max(mid, 1e-6)
            tex = relief_texture(img)
        for obj in with_uv:
            add_relief(obj, tex, strength, mid, self.detail)
        skipped = [o.name for o in meshes if not o.data.uv_layers]
        if skipped:
            self.report({"WARNING"}, f"No UV map, skipped: {', '.join(skipped)}")
        verb = "Carved into" if self.mode == "CARVE" else "Embossed on"
        self.report({"INFO"}, f"{verb} {len(with_uv)} mesh(es), {self.depth_mm:g} mm")
        return {"FINISHED"}
