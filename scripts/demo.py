# SPDX-License-Identifier: GPL-3.0-or-later
"""Headless demo, run with the bpy module: install the extension from its built zip into a
private Blender user folder (out/blender_user) as a user would, set up a scene, write 永 with a
keyframed brush, bake and simulate, then save the paper (out/demo.png), the recording
(out/demo_recording.json), the scene (out/demo.blend) and a Cycles render of the calligraphy
mapped onto a curved hanging scroll (out/demo_render.png).

demo.blend says what it needs: opened without the extension, a text editor beside the viewport
shows "README - Virtual Hairy Brush" (which zip to install, and how); the paper image is packed,
so the writing shows in the material even then."""

from __future__ import annotations

import math
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "out"
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "scripts"))
if __name__ == "__main__":
    # Blender reads its user folders at import time: keep the user's own Blender untouched.
    os.environ["BLENDER_USER_RESOURCES"] = str(OUT / "blender_user")

import bpy  # noqa: E402
import numpy as np  # noqa: E402
from build_extension import build, read_manifest  # noqa: E402

from sim.image.png import write_png  # noqa: E402
from sim.paper.display import linear_to_srgb  # noqa: E402

CHAR = "永"
README = "README - Virtual Hairy Brush"


def readme_text() -> str:
    """What a user who opens the demo's .blend needs to know, first of all without the
    extension."""
    m = read_manifest()
    return f"""This scene was made with the Blender extension {m["name"]} (id {m["id"]},
version {m["version"]}, Blender {m["blender_version_min"]} or later).

Without the extension you still see the writing: the paper image is packed in this file and
the paper plane's material shows it.

To simulate, scrub the animation, write or paint more, install the extension:
  1. Get {m["id"]}-{m["version"]}.zip (python scripts/build_extension.py makes it from the
     repository; it needs only Python 3.11).
  2. Edit > Preferences > Get Extensions > Install from Disk, and pick the zip.
  3. Open this file again: everything is in View3D > Sidebar > Brush.
"""


def add_readme(bpy) -> bpy.types.Text:
    """The README text, shown in a text editor split off the largest area of every window's
    screen (what a user sees when the file opens with its UI)."""
    text = bpy.data.texts.get(README) or bpy.data.texts.new(README)
    text.from_string(readme_text())
    for win in bpy.context.window_manager.windows:
        screen = win.screen
        shown = [a for a in screen.areas if a.type == "TEXT_EDITOR"]
        if not shown:
            big = max(screen.areas, key=lambda a: a.width * a.height)
            before = set(screen.areas)
            with bpy.context.temp_override(window=win, screen=screen, area=big):
                bpy.ops.screen.area_split(direction="VERTICAL", factor=0.3)
            shown = [a for a in screen.areas if a not in before] or [big]
            shown[0].type = "TEXT_EDITOR"
        shown[0].spaces.active.text = text
    return text


def install():
    zip_path = build(OUT / "dist")
    res = bpy.ops.extensions.package_install_files(
        filepath=str(zip_path), repo="user_default", enable_on_install=True, overwrite=True
    )
    assert res == {"FINISHED"}, res
    print(f"installed {zip_path.name}")


def write_character():
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    st = scene.hairy_brush
    # the default brush, paper and ink (the fitted wolf brush on sized xuan, black ink)
    st.px_per_mm = 10.0
    st.sync_frames = False  # the demo simulates once, at the end
    bpy.ops.hairy_brush.setup()
    # the brush presses as wide as the font's strokes (its response calibrated by simulation);
    # size 0: the character is sized to the brush; the default practice passes
    bpy.ops.hairy_brush.write_character(
        filepath=str(ROOT / "data" / "hanzi" / f"{CHAR}.json"), size_mm=0.0
    )
    bpy.ops.hairy_brush.bake_samples()  # what an artist does after editing the keyframes
    t0 = time.perf_counter()
    bpy.ops.hairy_brush.simulate()
    print(
        f"simulated {scene.frame_end - scene.frame_start} frames "
        f"in {time.perf_counter() - t0:.1f} s"
    )
    bpy.ops.hairy_brush.export_recording(filepath=str(OUT / "demo_recording.json"))
    img = st.paper_image
    px = np.empty(len(img.pixels), np.float32)
    img.pixels.foreach_get(px)
    rgb = px.reshape(img.size[1], img.size[0], 4)[::-1, :, :3]
    if img.is_float:  # a float image holds linear light (blender/images.py); a PNG is sRGB
        rgb = linear_to_srgb(rgb)
    write_png(OUT / "demo.png", rgb)
    print(f"wrote {OUT / 'demo.png'}")
    return st


def scroll_mesh(width=0.5, height=0.5, bend=0.35, n=48):
    """A gently curved hanging scroll with UVs over its whole face."""
    verts, faces, uvs = [], [], []
    for j in range(n + 1):
        for i in range(n + 1):
            u, v = i / n, j / n
            a = (u - 0.5) * bend * math.pi
            r = width / (bend * math.pi)
            verts.append(
                (r * math.sin(a), r * (1 - math.cos(a)) - 0.05 * math.sin(v * math.pi), v * height)
            )
    for j in range(n):
        for i in range(n):
            k = j * (n + 1) + i
            faces.append((k, k + 1, k + n + 2, k + n + 1))
    me = bpy.data.meshes.new("Scroll")
    me.from_pydata(verts, [], faces)
    uv = me.uv_layers.new(name="UVMap")
    for poly in me.polygons:
        for li, vi in zip(poly.loop_indices, poly.vertices, strict=True):
            i, j = vi % (n + 1), vi // (n + 1)
            uvs.append((i / n, j / n))
            uv.data[li].uv = uvs[-1]
    for p in me.polygons:
        p.use_smooth = True
    return me


def render(st):
    scene = bpy.context.scene
    st.paper_object.hide_render = True
    st.brush_object.hide_render = True
    scroll = bpy.data.objects.new("Scroll", scroll_mesh())
    scene.collection.objects.link(scroll)
    scroll.location = (0.6, 0.0, 0.0)
    silk = bpy.data.materials.new("Scroll Silk")
    if silk.node_tree is None:  # Blender before 5.0 makes materials without nodes
        silk.use_nodes = True
    bsdf = next(n for n in silk.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    bsdf.inputs["Base Color"].default_value = (0.93, 0.88, 0.76, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.8
    scroll.data.materials.append(silk)
    for o in scene.objects:
        o.select_set(o == scroll)
    bpy.context.view_layer.objects.active = scroll
    bpy.ops.hairy_brush.apply_to_mesh()
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    scene.collection.objects.link(cam)
    cam.location = (0.6, -1.05, 0.25)
    cam.rotation_euler = (math.radians(90), 0.0, 0.0)
    scene.camera = cam
    light = bpy.data.objects.new("Light", bpy.data.lights.new("Light", "AREA"))
    light.data.energy = 60.0
    light.data.size = 1.0
    light.location = (0.2, -0.9, 1.2)
    light.rotation_euler = (math.radians(40), 0.0, math.radians(-20))
    scene.collection.objects.link(light)
    world = bpy.data.worlds.new("World")
    if world.node_tree is None:  # Blender before 5.0 makes worlds without nodes
        world.use_nodes = True
    scene.world = world
    bg = world.node_tree.nodes.get("Background") if world.node_tree else None
    if bg is not None:
        bg.inputs["Color"].default_value = (0.25, 0.23, 0.21, 1.0)
    scene.render.engine = "CYCLES"
    scene.cycles.samples = 24
    scene.cycles.device = "CPU"
    scene.render.resolution_x, scene.render.resolution_y = 720, 720
    scene.render.resolution_percentage = 100
    scene.render.filepath = str(OUT / "demo_render.png")
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    print(f"rendered {OUT / 'demo_render.png'} with Cycles in {time.perf_counter() - t0:.1f} s")


def main():
    OUT.mkdir(exist_ok=True)
    install()
    st = write_character()
    render(st)
    add_readme(bpy)
    bpy.ops.wm.save_as_mainfile(filepath=str(OUT / "demo.blend"))
    print(f"wrote {OUT / 'demo.blend'}")


if __name__ == "__main__":
    main()
