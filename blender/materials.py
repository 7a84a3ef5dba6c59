# SPDX-License-Identifier: GPL-3.0-or-later
"""Materials that show the paper image: the paper plane's own, and ink multiplied over a mesh's
materials through its UV map (Apply to Mesh, a surface paper)."""

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
