# SPDX-License-Identifier: GPL-3.0-or-later
"""Imitate a picture in Blender, headless (run with the bpy module): install the extension from
its built zip into a private Blender user folder (out/picture_user), load a scan-like picture
(``picture_scan.py``: the brush's 永 on raw xuan, aged) as an image datablock, run Imitate
Picture, then play the keyframed writing back: the paper image at five frames of the timeline
(docs/img/picture_blender_replay.png) - what Blender shows and renders at those frames.

    .venv/bin/python scripts/picture_blender.py
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "out"
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "scripts"))
OUT.mkdir(exist_ok=True)
os.environ["BLENDER_USER_RESOURCES"] = str(OUT / "picture_user")  # the user's Blender untouched

import bpy  # noqa: E402
import numpy as np  # noqa: E402
from build_extension import build  # noqa: E402
from picture_scan import scan_picture, written_size_mm  # noqa: E402

from sim.image.morph import resize  # noqa: E402
from sim.image.png import write_png  # noqa: E402
from sim.paper.display import linear_to_srgb  # noqa: E402
from sim.writing.hanzi import find_char  # noqa: E402


def install():
    zip_path = build(OUT / "dist")
    res = bpy.ops.extensions.package_install_files(
        filepath=str(zip_path), repo="user_default", enable_on_install=True, overwrite=True
    )
    assert res == {"FINISHED"}, res


def paper_rgb(st, half: bool = True) -> np.ndarray:
    img = st.paper_image
    px = np.empty(len(img.pixels), np.float32)
    img.pixels.foreach_get(px)
    rgb = linear_to_srgb(px.reshape(img.size[1], img.size[0], 4)[::-1, :, :3])
    if half:
        h, w = rgb.shape[0] // 2, rgb.shape[1] // 2
        rgb = np.stack([resize(rgb[..., c], h, w) for c in range(3)], axis=2)
    return np.clip(rgb, 0, 1)


def main() -> int:
    install()
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    st = scene.hairy_brush
    st.brush_preset, st.paper_preset, st.ink_preset = "wolf_stiff", "smooth", "sumi_black"
    size = written_size_mm(find_char("永"))  # the piece's own size (Size (mm))
    st.px_per_mm = 512 / size  # the resolution of the engine's figure (picture_scan.png)
    bpy.ops.hairy_brush.setup()
    scan, _ = scan_picture(find_char("永"), 512)
    path = OUT / "picture_scan.png"
    write_png(path, scan)
    img = bpy.data.images.load(str(path))
    t0 = time.perf_counter()
    res = bpy.ops.hairy_brush.imitate_image(image=img.name, size_mm=size)
    assert res == {"FINISHED"}, res
    print(f"imitated {path.name} in {time.perf_counter() - t0:.1f} s")
    st.sync_frames = True
    f0, f1 = scene.frame_start, scene.frame_end
    frames = []
    for k in range(1, 6):
        scene.frame_set(f0 + round((f1 - f0) * k / 5))  # the frame handler replays the writing
        frames.append(paper_rgb(st, half=False))
    sep = np.full((frames[0].shape[0], 6, 3), 0.6)
    strip = np.concatenate([x for f in frames for x in (f, sep)][:-1], axis=1)
    write_png(ROOT / "docs" / "img" / "picture_blender_replay.png", strip)
    print(f"frames {f0}-{f1}: docs/img/picture_blender_replay.png")
    bpy.ops.hairy_brush.export_recording(filepath=str(OUT / "picture_recording.json"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
