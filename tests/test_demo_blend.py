# SPDX-License-Identifier: GPL-3.0-or-later
"""The demo's .blend keeps the paper image packed, so nothing is lost on reload (real bpy)."""

import importlib.util

import numpy as np
import pytest
from conftest import ROOT

bpy = pytest.importorskip("bpy")


def test_demo_blend_keeps_the_paper_packed(tmp_path):
    spec = importlib.util.spec_from_file_location("demo", ROOT / "scripts" / "demo.py")
    demo = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(demo)
    rgb = np.full((32, 48, 3), 0.9, dtype=np.float32)
    rgb[10:20, 5:40] = 0.05  # a dark bar
    path = tmp_path / "paper.blend"
    demo.save_blend(rgb, path)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.wm.open_mainfile(filepath=str(path))
    img = bpy.data.images["HairyBrush Paper"]
    assert img.packed_file is not None
    px = np.empty(48 * 32 * 4, dtype=np.float32)
    img.pixels.foreach_get(px)
    px = px.reshape(32, 48, 4)
    assert abs(px[15, 20, 0] - 0.05) < 0.01 and abs(px[2, 2, 0] - 0.9) < 0.01
    assert "Paper" in bpy.data.objects
