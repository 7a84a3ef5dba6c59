# SPDX-License-Identifier: GPL-3.0-or-later
"""Blender (the bpy module) with a checkout's add-on loaded from its folder, an A4 recording
imported at 600 dpi and simulated into the paper image: the artist's path in one process, whose
peak memory ``python -m sim speed`` reports (the engine, ``sim/``, never imports bpy).

    python scripts/blender_a4.py CHECKOUT RECORDING PX_PER_MM
"""

from __future__ import annotations

import importlib.util
import sys

import bpy


def main(root: str, recording: str, px_per_mm: float) -> None:
    spec = importlib.util.spec_from_file_location(
        "hairy_brush", root + "/__init__.py", submodule_search_locations=[root]
    )
    mod = importlib.util.module_from_spec(spec)
    sys.modules["hairy_brush"] = mod
    spec.loader.exec_module(mod)
    mod.register()
    st = bpy.context.scene.hairy_brush
    st.sync_frames = False
    assert bpy.ops.hairy_brush.setup() == {"FINISHED"}
    assert bpy.ops.hairy_brush.import_recording(filepath=recording) == {"FINISHED"}
    st.px_per_mm = px_per_mm
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]))
