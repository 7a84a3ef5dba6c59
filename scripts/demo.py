# SPDX-License-Identifier: GPL-3.0-or-later
"""Headless demo: write the character 永 with the engine, save the paper as out/demo.png, and a
Blender scene with the paper as an image texture as out/demo.blend (bpy module, no UI)."""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from sim.engine import Simulation  # noqa: E402
from sim.hanzi import character_recording  # noqa: E402
from sim.png import write_png  # noqa: E402

OUT = ROOT / "out"


def write_character(char="永"):
    rec = character_recording(ROOT / "data" / "hanzi" / f"{char}.json")
    t0 = time.perf_counter()
    sim = Simulation(rec).run()
    print(f"simulated {len(rec.samples)} samples in {time.perf_counter() - t0:.1f} s")
    return rec, sim


def save_blend(rgb_bottom_up, path: Path):
    import bpy
    import numpy as np

    bpy.ops.wm.read_factory_settings(use_empty=True)
    h, w, _ = rgb_bottom_up.shape
    img = bpy.data.images.new("HairyBrush Paper", w, h, alpha=True, float_buffer=False)
    rgba = np.concatenate([rgb_bottom_up, np.ones((h, w, 1), np.float32)], axis=2)
    img.pixels.foreach_set(rgba.astype(np.float32).ravel())
    img.pack()
    bpy.ops.mesh.primitive_plane_add(size=0.16)
    plane = bpy.context.active_object
    plane.name = "Paper"
    mat = bpy.data.materials.new("Paper")
    if mat.node_tree is None:  # Blender < 5 creates materials without nodes
        mat.use_nodes = True
    nodes = mat.node_tree.nodes
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = img
    bsdf = nodes["Principled BSDF"]
    mat.node_tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    plane.data.materials.append(mat)
    bpy.ops.wm.save_as_mainfile(filepath=str(path))


def main():
    OUT.mkdir(exist_ok=True)
    rec, sim = write_character()
    rec.save(OUT / "demo_recording.json")
    write_png(OUT / "demo.png", sim.image())
    print(f"wrote {OUT / 'demo.png'} and {OUT / 'demo_recording.json'}")
    save_blend(sim.paper.rgb(), OUT / "demo.blend")
    print(f"wrote {OUT / 'demo.blend'}")


if __name__ == "__main__":
    main()
