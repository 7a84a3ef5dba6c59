# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.fit_parameters: configure the brush automatically (Sec. 7.2) - fit the quality
parameters to training samples by minimising Eq. 28, then keep the result as the scene's
quality values and as a preset of the user's own."""

from __future__ import annotations

import os

import bpy
import numpy as np

from .. import bridge
from ..sim.fit import FitSettings, TrainingSample, character_samples, fit
from ..sim.hanzi import find_char
from ..sim.params import QualityParams
from .add_settings_preset import PRESET_SUBDIR, HAIRY_BRUSH_OT_add_settings_preset


def write_user_preset(st, name: str) -> str:
    """Save the scene's settings as a Blender preset file, in the format (and the folder) of the
    add-on's own preset menu, so it appears there beside the user's other presets."""
    folder = bpy.utils.user_resource("SCRIPTS", path=os.path.join("presets", PRESET_SUBDIR))
    os.makedirs(folder, exist_ok=True)
    safe = bpy.path.clean_name(name) or "fitted"
    path = os.path.join(folder, safe + ".py")
    lines = ["import bpy", *HAIRY_BRUSH_OT_add_settings_preset.preset_defines, ""]
    for expr in HAIRY_BRUSH_OT_add_settings_preset.preset_values:
        value = eval(expr, {"st": st})  # noqa: S307 - the preset's own attribute paths
        if hasattr(value, "__len__") and not isinstance(value, str):
            value = tuple(value)
        lines.append(f"{expr} = {value!r}")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    return path


class HAIRY_BRUSH_OT_fit_parameters(bpy.types.Operator):
    """Fit the quality parameters to training samples (Eq. 28): characters written inside
    their font outlines, or the scene's recording against an image of the real artwork"""

    bl_idname = "hairy_brush.fit_parameters"
    bl_label = "Fit Quality Parameters"
    bl_options = {"REGISTER", "UNDO"}

    source: bpy.props.EnumProperty(
        name="Training",
        items=[
            ("CHARACTERS", "Characters", "Characters from stroke data, outline as boundary"),
            ("IMAGE", "Image", "The scene's recording and an image of what it should make"),
        ],
        default="CHARACTERS",
    )
    characters: bpy.props.StringProperty(
        name="Characters", default="一心", description="Training characters"
    )
    data_path: bpy.props.StringProperty(
        name="Stroke Data",
        subtype="FILE_PATH",
        default="",
        description="Folder of <char>.json or graphics.txt (empty: the bundled characters)",
    )
    image: bpy.props.StringProperty(name="Image", default="", description="Target image name")
    size_px: bpy.props.IntProperty(name="Training Size", default=64, min=16, max=512)
    divisions: bpy.props.IntProperty(name="Divisions", default=2, min=1, max=4)
    rounds: bpy.props.IntProperty(name="Rounds", default=2, min=1, max=6)
    iterations: bpy.props.IntProperty(name="Descent Steps", default=3, min=1, max=20)
    max_grid: bpy.props.IntProperty(name="Grid Points", default=16, min=1, max=729)
    preset_name: bpy.props.StringProperty(name="Preset Name", default="Fitted")

    def invoke(self, context, event):
        return context.window_manager.invoke_props_dialog(self)

    def _samples(self, scene, st):
        template = bridge.settings_recording(scene)
        if self.source == "CHARACTERS":
            chars = [find_char(c, self.data_path or None) for c in self.characters if c.strip()]
            if not chars:
                raise ValueError("type at least one training character")
            return character_samples(chars, self.size_px, template, names=list(self.characters))
        img = bpy.data.images.get(self.image)
        if img is None:
            raise ValueError(f"no image named {self.image!r} to train against")
        rec = bridge.recording_from_scene(scene)
        w, h = img.size
        if (w, h) != (rec.width_px, rec.height_px):
            raise ValueError(
                f"image {img.name!r} is {w} x {h} px but the paper is "
                f"{rec.width_px} x {rec.height_px} px"
            )
        a = np.empty(w * h * 4, dtype=np.float32)
        img.pixels.foreach_get(a)
        rgb = a.reshape(h, w, 4)[::-1, :, :3]  # top row first, as Eq. 28's images
        return [TrainingSample(rec, rgb, img.name)]

    def execute(self, context):
        scene = context.scene
        st = bridge.settings(scene)
        wm = context.window_manager
        try:
            bridge.require_brush_and_paper(st)
            samples = self._samples(scene, st)
        except (*bridge.USER_ERRORS, ValueError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        settings = FitSettings(
            divisions=self.divisions,
            rounds=self.rounds,
            iterations=self.iterations,
            max_grid=self.max_grid,
            workers=1,  # Blender's executable is not a plain Python to fork workers from
            seed=int(st.seed),
        )
        wm.progress_begin(0, 100)
        try:
            res = fit(
                samples,
                st.quality.as_dict(),
                settings,
                progress=lambda f, *_: wm.progress_update(int(100 * f)),
            )
        except bridge.USER_ERRORS as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        finally:
            wm.progress_end()
        checked = QualityParams().with_values(res.quality).to_dict()
        for k, v in checked.items():
            setattr(st.quality, k, v)
        path = write_user_preset(st, self.preset_name)
        self.report(
            {"INFO"},
            f"Eq. 28 {res.start_target:.4f} -> {res.target:.4f} ({res.evaluations} runs); "
            f"preset {os.path.basename(path)}",
        )
        return {"FINISHED"}
