# SPDX-License-Identifier: GPL-3.0-or-later
"""What the Blender tests share: the installed extension's modules, the paper image's pixels, a
scene set up and a stroke keyframed, undo steps as the UI pushes them."""

from __future__ import annotations

import sys

import bpy
import numpy as np

from sim.core.params import load_preset
from sim.core.recording import DEFAULT_BRUSH
from sim.paper.display import linear_to_srgb
from tests.paths import ADDON

HAIR = load_preset("brush", DEFAULT_BRUSH).data["geometry"]["hair_length_mm"]  # the default's


def ext():
    """The installed extension's own modules (not the repository's copy)."""
    return sys.modules[ADDON]


def pixels(img) -> np.ndarray:
    """RGBA as the engine's visible colour (a float image holds linear light: decoded)."""
    a = np.empty(len(img.pixels), np.float32)
    img.pixels.foreach_get(a)
    a = a.reshape(img.size[1], img.size[0], 4)
    if img.is_float:
        a[..., :3] = linear_to_srgb(a[..., :3])
    return a


def setup_scene(bpy, ppm=2.0, **settings):
    st = bpy.context.scene.hairy_brush
    st.px_per_mm = ppm
    for k, v in settings.items():
        setattr(st, k, v)
    assert bpy.ops.hairy_brush.setup() == {"FINISHED"}
    return st


def keyframe_stroke(bpy, st, press=4.0, y=0.0, frames=(1, 8, 40, 48)):
    """A horizontal stroke across the paper's middle: touch down, press, travel, lift."""
    sc = bpy.context.scene
    sc.frame_start, sc.frame_end = frames[0], frames[-1]
    b = st.brush_object
    for f, x, z in zip(
        frames,
        (-0.05, -0.05, 0.05, 0.06),
        (HAIR + 5, HAIR - press, HAIR - press, HAIR + 5),
        strict=True,
    ):
        b.location = (x, y, z / 1000)
        b.keyframe_insert("location", frame=f)


def mesh_without_uv(bpy, name="NoUV"):
    """A one-triangle mesh object with no UV map, in the scene."""
    me = bpy.data.meshes.new(name)
    me.from_pydata([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [], [(0, 1, 2)])
    obj = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def select_only(*objs):
    for ob in bpy.context.scene.objects:
        ob.select_set(ob in objs)


def undo_step(bpy, message):
    # Blender's UI pushes an undo step after each REGISTER/UNDO operator; a script does it here
    with bpy.context.temp_override(window=bpy.context.window_manager.windows[0]):
        bpy.ops.ed.undo_push(message=message)


def call(bpy, fn_name, *args):
    win = bpy.context.window_manager.windows[0]
    with bpy.context.temp_override(window=win):
        getattr(bpy.ops.ed, fn_name)(*args)
