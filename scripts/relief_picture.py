# SPDX-License-Identifier: GPL-3.0-or-later
"""The writing carved into a stone tablet (hairy_brush.relief), rendered with Cycles: run after
`bash scripts/demo.sh` (it reads out/demo_recording.json); writes out/relief_tablet.png.

    .venv/bin/python scripts/relief_picture.py"""

from __future__ import annotations

import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
import bench_live  # noqa: E402 - sets Blender's user folder before bpy is imported

bpy = bench_live.bpy
OUT = ROOT / "out"


def stone(obj):
    mat = bpy.data.materials.new("Stone")
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.32, 0.31, 0.29, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.85
    obj.data.materials.append(mat)


def main() -> int:
    bench_live.install()
    bpy.ops.wm.read_homefile(use_empty=True)
    sc = bpy.context.scene
    assert bpy.ops.hairy_brush.import_recording(filepath=str(OUT / "demo_recording.json"))
    st = sc.hairy_brush
    st.px_per_mm = 8.0
    assert bpy.ops.hairy_brush.setup() == {"FINISHED"}
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    sc.frame_set(sc.frame_end)  # Follow Frames: a render shows the paper at its frame
    w, h = st.paper_width_mm / 1000, st.paper_height_mm / 1000
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=600, y_subdivisions=600, size=1.0)
    tablet = bpy.context.active_object
    tablet.scale = (w, h, 1.0)
    stone(tablet)
    for ob in sc.objects:
        ob.select_set(ob == tablet)
    assert bpy.ops.hairy_brush.relief(mode="CARVE", depth_mm=1.5) == {"FINISHED"}
    st.paper_object.hide_render = st.brush_object.hide_render = True
    for child in st.brush_object.children:
        child.hide_render = True
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    sc.collection.objects.link(cam)
    cam.data.type, cam.data.ortho_scale = "ORTHO", max(w, h) * 1.05
    cam.location = (0.0, 0.0, 1.0)
    sc.camera = cam
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 4.0
    sun.rotation_euler = (math.radians(-62), 0.0, math.radians(35))  # low, from the top left
    sc.collection.objects.link(sun)
    sc.world = bpy.data.worlds.new("World")
    sc.world.color = (0.05, 0.05, 0.05)
    sc.render.engine = "CYCLES"
    sc.cycles.samples, sc.cycles.device = 32, "CPU"
    sc.view_settings.view_transform = "Standard"
    sc.render.resolution_x = sc.render.resolution_y = 640
    sc.render.filepath = str(OUT / "relief_tablet.png")
    bpy.ops.render.render(write_still=True)
    print(f"wrote {OUT / 'relief_tablet.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
