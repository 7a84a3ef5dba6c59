# SPDX-License-Identifier: GPL-3.0-or-later
"""The demo's .blend opened without the extension (issue 29.10): it says what to install and
how, and still shows the writing (the paper image is packed, the material shows it)."""

from __future__ import annotations

import sys

import numpy as np
import pytest

from tests.blender.helpers import keyframe_stroke, pixels, setup_scene
from tests.paths import ADDON, ROOT

bpy = pytest.importorskip("bpy")


@pytest.mark.slow
def test_the_example_inside_the_extension_opens_as_calligraphy(hb):
    assert bpy.ops.hairy_brush.open_example() == {"FINISHED"}
    st = bpy.context.scene.hairy_brush
    assert st.recording is not None and st.paper_width_mm == 80.0
    grey = pixels(st.paper_image)[..., :3].mean(axis=2)
    assert (grey < 0.2).mean() > 0.08  # the character's black strokes on the paper


@pytest.mark.slow
def test_the_demo_file_tells_a_user_without_the_extension_what_to_install(hb, tmp_path):
    import addon_utils

    sys.path.insert(0, str(ROOT / "scripts"))
    import demo
    from build_extension import read_manifest

    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    bpy.ops.hairy_brush.simulate()
    demo.add_readme(bpy)
    path = tmp_path / "demo.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    addon_utils.disable(ADDON, default_set=True)
    try:
        bpy.ops.wm.open_mainfile(filepath=str(path), load_ui=True)
        assert not hasattr(bpy.types.Scene, "hairy_brush")  # as a user without it opens it
        text = bpy.data.texts[demo.README]
        body = text.as_string()
        m = read_manifest()
        assert f"{m['id']}-{m['version']}.zip" in body and "Install from Disk" in body
        screen = bpy.context.window_manager.windows[0].screen
        assert any(a.type == "TEXT_EDITOR" and a.spaces.active.text == text for a in screen.areas)
        # the writing is there all the same: the paper image is packed and the material shows it
        img = next(i for i in bpy.data.images if i.name.startswith("HairyBrush Paper"))
        assert img.packed_file is not None
        grey = pixels(img)[..., :3].mean(axis=2)
        assert np.ptp(grey) > 0.5
        plane = next(o for o in bpy.data.objects if o.type == "MESH")
        nodes = plane.active_material.node_tree.nodes
        assert any(n.type == "TEX_IMAGE" and n.image == img for n in nodes)
    finally:
        addon_utils.enable(ADDON, default_set=True)
