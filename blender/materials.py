# SPDX-License-Identifier: GPL-3.0-or-later
"""Materials that show the paper image: the paper plane's own, ink multiplied over a mesh's
materials through its UV map (Apply to Mesh, a surface paper), and the relief as a bump map in
a mesh's materials (Carve/Emboss on a mesh too coarse to carry it, issue 29.7)."""

from __future__ import annotations

import bpy

from . import checks

PAPER_MATERIAL = "HairyBrush Paper"
INK_NODE = "HairyBrush Ink"


def new_material(name: str) -> bpy.types.Material:
    """A new material with its node tree (a Principled BSDF) on every Blender version: before
    5.0, ``materials.new`` makes one without nodes until ``use_nodes`` is set."""
    mat = bpy.data.materials.new(name)
    if mat.node_tree is None:
        mat.use_nodes = True
    return mat


def add_ink(mat, img, uv_name: str):
    """Multiply the material's base colour by the paper image read through ``uv_name``: white
    paper leaves the mesh's own shading as it was, ink darkens or tints it."""
    if mat.node_tree is None:
        mat.use_nodes = True
    nt = mat.node_tree
    if INK_NODE in nt.nodes:
        nt.nodes[INK_NODE].image = img
        return False
    bsdf = next((n for n in nt.nodes if n.type == "BSDF_PRINCIPLED"), None)
    if bsdf is None:
        raise checks.UserError(f"Material '{mat.name}' has no Principled BSDF to put ink on")
    base = bsdf.inputs["Base Color"]
    uv = nt.nodes.new("ShaderNodeUVMap")
    uv.uv_map = uv_name
    uv.location = bsdf.location.x - 900, bsdf.location.y - 200
    tex = nt.nodes.new("ShaderNodeTexImage")
    tex.name = tex.label = INK_NODE
    tex.image = img
    tex.location = bsdf.location.x - 700, bsdf.location.y - 200
    mix = nt.nodes.new("ShaderNodeMix")
    mix.data_type = "RGBA"
    mix.blend_type = "MULTIPLY"
    mix.name = mix.label = INK_NODE + " Multiply"
    mix.inputs["Factor"].default_value = 1.0
    mix.location = bsdf.location.x - 300, bsdf.location.y
    a = _socket(mix.inputs, "A_Color")
    b = _socket(mix.inputs, "B_Color")
    if base.is_linked:
        nt.links.new(base.links[0].from_socket, a)
    else:
        a.default_value = base.default_value
    nt.links.new(uv.outputs["UV"], tex.inputs["Vector"])
    nt.links.new(tex.outputs["Color"], b)
    nt.links.new(_socket(mix.outputs, "Result_Color"), base)
    return True


def _socket(sockets, identifier):
    return next(s for s in sockets if s.identifier == identifier)


def paper_material(img) -> bpy.types.Material:
    mat = bpy.data.materials.get(PAPER_MATERIAL)
    if mat is None:
        mat = new_material(PAPER_MATERIAL)
    if mat.node_tree is None:  # a material of that name made elsewhere without nodes
        mat.use_nodes = True
    nodes = mat.node_tree.nodes
    tex = next((n for n in nodes if n.type == "TEX_IMAGE"), None)
    if tex is None:
        tex = nodes.new("ShaderNodeTexImage")
        tex.location = (-400, 300)
    tex.image = img
    bsdf = next((n for n in nodes if n.type == "BSDF_PRINCIPLED"), None)
    if bsdf is not None:
        mat.node_tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
        bsdf.inputs["Roughness"].default_value = 0.9
    return mat


def surface_material(obj, img):
    """Every material of the mesh shows the paper image through its active UV map over its own
    base colour (a new plain material when it has none)."""
    mats = [m for m in obj.data.materials if m is not None]
    if not mats:
        mat = new_material(f"{obj.name} Paper")
        obj.data.materials.append(mat)
        mats = [mat]
    for mat in mats:
        add_ink(mat, img, obj.data.uv_layers.active.name)


BUMP_NODE = "HairyBrush Relief Bump"


def add_relief_bump(mat, img, uv_name: str, distance_m: float, emboss: bool):
    """The relief in the material: a Bump node whose height is the paper image's value read
    through ``uv_name`` (it follows the paper image), into the Principled BSDF's Normal (after
    a normal map already there). Ink is dark: its value is low, so a carve is the value as it
    is, an emboss the value inverted; ``distance_m`` is the bump of full ink."""
    if mat.node_tree is None:
        mat.use_nodes = True
    nt = mat.node_tree
    bsdf = next((n for n in nt.nodes if n.type == "BSDF_PRINCIPLED"), None)
    if bsdf is None:
        raise checks.UserError(f"Material '{mat.name}' has no Principled BSDF for the relief")
    bump = nt.nodes.get(BUMP_NODE)
    if bump is None:
        x, y = bsdf.location.x, bsdf.location.y
        uv = nt.nodes.new("ShaderNodeUVMap")
        uv.name = uv.label = BUMP_NODE + " UV"
        uv.location = x - 900, y - 500
        tex = nt.nodes.new("ShaderNodeTexImage")
        tex.name = tex.label = BUMP_NODE + " Height"
        tex.location = x - 700, y - 500
        grey = nt.nodes.new("ShaderNodeRGBToBW")
        grey.name = BUMP_NODE + " Value"
        grey.location = x - 420, y - 500
        bump = nt.nodes.new("ShaderNodeBump")
        bump.name = bump.label = BUMP_NODE
        bump.location = x - 250, y - 500
        normal = bsdf.inputs["Normal"]
        if normal.is_linked:  # the material's own normal map goes on under the relief
            nt.links.new(normal.links[0].from_socket, bump.inputs["Normal"])
        nt.links.new(uv.outputs["UV"], tex.inputs["Vector"])
        nt.links.new(tex.outputs["Color"], grey.inputs["Color"])
        nt.links.new(grey.outputs["Val"], bump.inputs["Height"])
        nt.links.new(bump.outputs["Normal"], normal)
    nt.nodes[BUMP_NODE + " UV"].uv_map = uv_name
    nt.nodes[BUMP_NODE + " Height"].image = img
    bump.invert = emboss
    bump.inputs["Strength"].default_value = 1.0
    bump.inputs["Distance"].default_value = distance_m


def remove_relief_bump(mat) -> bool:
    """Take the relief's bump out of the material (the normal map under it, if any, goes back
    to the BSDF); True when there was one."""
    nt = mat.node_tree
    if nt is None or BUMP_NODE not in nt.nodes:
        return False
    bump = nt.nodes[BUMP_NODE]
    under = bump.inputs["Normal"].links[0].from_socket if bump.inputs["Normal"].is_linked else None
    targets = [lk.to_socket for lk in bump.outputs["Normal"].links]
    for suffix in ("", " UV", " Height", " Value"):
        node = nt.nodes.get(BUMP_NODE + suffix)
        if node is not None:
            nt.nodes.remove(node)
    if under is not None:
        for sock in targets:
            nt.links.new(under, sock)
    return True
