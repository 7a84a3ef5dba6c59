# SPDX-License-Identifier: GPL-3.0-or-later
"""The smoke test of one Blender version, run by a Python that has its bpy module (CI runs it
on each LTS through scripts/smoke.sh; the full suite runs on the newest):

    python scripts/smoke.py [ZIP]

In a private Blender user folder it installs the extension from the zip (built in plain Python
when none is given) as a user does, writes a character on the paper, simulates it, renders the
paper with Cycles, saves the .blend, opens it again and checks the writing is still there, then
disables the extension. Each step prints one line; any failure ends in "smoke: FAILED ..." and
exit code 1. Exiting cleanly is part of the test (Blender 4.2's bpy module crashed at exit)."""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ADDON = "bl_ext.user_default.hairy_brush"
CHAR = "十"


def step(what: str, t0: float) -> float:
    now = time.perf_counter()
    print(f"smoke: {what} ({now - t0:.1f} s)", flush=True)
    return now


def check(cond: bool, message: str):
    if not cond:
        raise AssertionError(message)


def paper_darkness(img):
    """How much darker than the blank paper the darkest part of the image is (0..1)."""
    import numpy as np

    a = np.empty(len(img.pixels), np.float32)
    img.pixels.foreach_get(a)
    rgb = a.reshape(-1, 4)[:, :3].mean(axis=1)
    return float(rgb.max() - rgb.min())


def write_and_simulate(bpy):
    bpy.ops.wm.read_homefile(use_empty=True)
    st = bpy.context.scene.hairy_brush
    st.px_per_mm = 2.0
    check(bpy.ops.hairy_brush.setup() == {"FINISHED"}, "setup did not finish")
    res = bpy.ops.hairy_brush.write_character(
        filepath=str(ROOT / "data" / "hanzi" / f"{CHAR}.json"), size_mm=40.0, passes=1
    )
    check(res == {"FINISHED"}, f"write_character: {res}")
    check(st.recording is not None, "no recording was stored")
    check(bpy.ops.hairy_brush.simulate() == {"FINISHED"}, "simulate did not finish")
    check(paper_darkness(st.paper_image) > 0.5, "the paper image shows no ink")
    return st


def render(bpy, st, out: Path) -> Path:
    """A Cycles render of the paper from above; returns the PNG."""
    import numpy as np

    sc = bpy.context.scene
    cam = bpy.data.objects.new("Smoke Camera", bpy.data.cameras.new("Smoke Camera"))
    sc.collection.objects.link(cam)
    cam.data.type = "ORTHO"
    cam.data.ortho_scale = st.paper_width_mm / 1000
    cam.location = (0.0, 0.0, 0.5)
    sc.camera = cam
    light = bpy.data.objects.new("Smoke Sun", bpy.data.lights.new("Smoke Sun", "SUN"))
    light.data.energy = 3.0
    sc.collection.objects.link(light)
    for ob in (st.brush_object, *st.brush_object.children_recursive):
        ob.hide_render = True
    sc.render.engine = "CYCLES"
    sc.cycles.samples = 4
    sc.cycles.device = "CPU"
    sc.render.resolution_x = sc.render.resolution_y = 96
    sc.render.resolution_percentage = 100
    sc.render.filepath = str(out)
    sc.frame_set(sc.frame_end)
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(str(out))
    a = np.empty(len(img.pixels), np.float32)
    img.pixels.foreach_get(a)
    grey = a.reshape(96, 96, 4)[..., :3].mean(axis=2)
    check(grey.max() > 0.3, f"the render is dark all over (brightest {grey.max():.2f})")
    check(grey.min() < 0.5 * grey.max(), "the render shows no writing on the paper")
    return out


def save_and_reopen(bpy, path: Path):
    st = bpy.context.scene.hairy_brush
    before = paper_darkness(st.paper_image)
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    bpy.ops.wm.open_mainfile(filepath=str(path))
    st = bpy.context.scene.hairy_brush
    check(st.recording is not None and st.paper_image is not None, "the file lost its writing")
    check(st.paper_image.packed_file is not None, "the paper image is not packed in the file")
    check(abs(paper_darkness(st.paper_image) - before) < 0.05, "the reopened paper differs")


def main(argv) -> int:
    user = tempfile.mkdtemp(prefix="hairy-brush-smoke-")
    os.environ["BLENDER_USER_RESOURCES"] = user  # read at `import bpy`: never the user's own
    os.environ["HAIRY_BRUSH_CACHE"] = os.path.join(user, "cache")
    sys.path.insert(0, str(ROOT / "scripts"))
    from build_extension import build

    t0 = time.perf_counter()
    zip_path = Path(argv[0]) if argv else build(Path(user) / "dist")
    import bpy  # noqa: I001 - bpy first: it puts addon_utils on the path
    import addon_utils

    print(f"smoke: Blender {bpy.app.version_string}, {zip_path.name}", flush=True)
    try:
        res = bpy.ops.extensions.package_install_files(
            filepath=str(zip_path), repo="user_default", enable_on_install=True
        )
        check(res == {"FINISHED"} and hasattr(bpy.types.Scene, "hairy_brush"), "not installed")
        t0 = step("installed and enabled", t0)
        st = write_and_simulate(bpy)
        t0 = step(f"wrote {CHAR}, simulated it into the paper image", t0)
        render(bpy, st, Path(user) / "render.png")
        t0 = step("rendered the paper with Cycles", t0)
        save_and_reopen(bpy, Path(user) / "smoke.blend")
        t0 = step("saved, reopened: the writing is there", t0)
        addon_utils.disable(ADDON, default_set=True)
        check(not hasattr(bpy.types.Scene, "hairy_brush"), "disabling left the settings")
        step("disabled", t0)
    except Exception as exc:  # one line, then a failing exit code
        print(f"smoke: FAILED: {type(exc).__name__}: {exc}", flush=True)
        return 1
    print(f"smoke: ok on Blender {bpy.app.version_string}", flush=True)
    shutil.rmtree(user, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
