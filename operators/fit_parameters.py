# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.fit_parameters: configure the brush automatically (Sec. 7.2) - fit the quality
parameters to training samples by minimising Eq. 28, then keep the result as the scene's
quality values and as a preset of the user's own."""

from __future__ import annotations

import os

import bpy

from ..blender import checks, images, recordings
from ..blender.jobs import JobOperator, WorkerJob
from ..sim.core.params import QualityParams
from ..sim.fitting.samples import TRAINING_SIZE_PX, TrainingSample, character_samples
from ..sim.fitting.search import FitSettings, fit
from ..sim.writing.hanzi import find_char
from . import polls
from .add_settings_preset import PRESET_SUBDIR, write_settings_preset

_DEFAULTS = FitSettings()  # the fit's defaults have one home (sim.fitting.search)


def write_user_preset(st, name: str) -> str:
    """Save the scene's settings as a Blender preset file, in the format (and the folder) of the
    add-on's own preset menu, so it appears there beside the user's other presets."""
    folder = bpy.utils.user_resource("SCRIPTS", path=os.path.join("presets", PRESET_SUBDIR))
    safe = bpy.path.clean_name(name) or "fitted"
    return write_settings_preset(st, os.path.join(folder, safe + ".py"))


class FitJob(WorkerJob):
    """Eq. 28's fit in a worker (the training characters are written there too); ``finish``
    sets the scene's quality values and saves the preset."""

    title = "Fitting quality parameters"

    def __init__(self, st, make_samples, settings: FitSettings, preset_name: str):
        self.st = st
        self.preset_name = preset_name
        seed_quality = checks.quality_values(st)
        super().__init__(
            lambda progress: fit(make_samples(), seed_quality, settings, progress=progress)
        )

    def describe(self, details) -> str:
        if len(details) < 3:
            return ""
        stage, rnd, best = details[:3]
        return f"{'shape (Qp1)' if stage == 'qp1' else 'texture (Qp2)'}, round {rnd + 1}, " + (
            f"Eq. 28 = {best:.4f}"
        )

    def finish(self, context):
        res = self.result
        checked = QualityParams().with_values(res.quality).to_dict()
        for k, v in checked.items():
            setattr(self.st.quality, k, v)
        path = write_user_preset(self.st, self.preset_name)
        return "INFO", (
            f"Eq. 28 {res.start_target:.4f} -> {res.target:.4f} ({res.evaluations} runs); "
            f"preset {os.path.basename(path)}"
        )


class HAIRY_BRUSH_OT_fit_parameters(JobOperator, bpy.types.Operator):
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
        name="Characters",
        default="一心",
        description="The characters the brush learns from: it writes each and is scored "
        "against the font's outline",
    )
    data_path: bpy.props.StringProperty(
        name="Stroke Data",
        subtype="FILE_PATH",
        default="",
        description="Folder of <char>.json or graphics.txt (empty: the bundled characters)",
    )
    image: bpy.props.StringProperty(
        name="Image",
        default="",
        description="The image of the real artwork the scene's recording should make (the "
        "paper's size in pixels)",
    )
    size_px: bpy.props.IntProperty(
        name="Training Size (px)",
        default=TRAINING_SIZE_PX,
        min=16,
        max=512,
        description="Larger: each training character is written bigger - a closer fit, but "
        "every evaluation takes longer",
    )
    divisions: bpy.props.IntProperty(
        name="Divisions",
        default=_DEFAULTS.divisions,
        min=1,
        max=4,
        description="More: a finer grid of starting points over the values' range (d "
        "divisions per value)",
    )
    rounds: bpy.props.IntProperty(
        name="Rounds",
        default=_DEFAULTS.rounds,
        min=1,
        max=6,
        description="More: the search range shrinks around the best point more times, for "
        "a more precise result",
    )
    iterations: bpy.props.IntProperty(
        name="Descent Steps",
        default=_DEFAULTS.iterations,
        min=1,
        max=20,
        description="More: each descent from a starting point goes further downhill",
    )
    max_grid: bpy.props.IntProperty(
        name="Grid Points",
        default=_DEFAULTS.max_grid,
        min=1,
        max=729,
        description="At most this many grid points are tried a round (drawn at random when "
        "the grid has more): more is slower and surer",
    )
    preset_name: bpy.props.StringProperty(
        name="Preset Name",
        default="Fitted",
        description="The fitted values are saved as a preset of yours under this name",
    )

    @classmethod
    def poll(cls, context):
        return polls.brush_and_paper(cls, context)

    def invoke(self, context, event):
        self.in_background = True
        return context.window_manager.invoke_props_dialog(self)

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.prop(self, "source")
        if self.source == "CHARACTERS":
            layout.prop(self, "characters")
            layout.prop(self, "data_path")
            layout.prop(self, "size_px")
        else:
            layout.prop_search(self, "image", bpy.data, "images")
        col = layout.column(align=True)
        for name in ("divisions", "rounds", "iterations", "max_grid"):
            col.prop(self, name)
        layout.prop(self, "preset_name")

    def _samples(self, scene):
        """A function that makes the training samples (in the worker: characters are written
        there); what needs Blender's data is read here."""
        template = recordings.settings_recording(scene)
        if self.source == "CHARACTERS":
            chars = [find_char(c, self.data_path or None) for c in self.characters if c.strip()]
            if not chars:
                raise ValueError("type at least one training character")
            names, size = list(self.characters), self.size_px
            return lambda: character_samples(chars, size, template, names=names)
        img = bpy.data.images.get(self.image)
        if img is None:
            raise ValueError(f"no image named {self.image!r} to train against")
        rec = recordings.recording_from_scene(scene)
        w, h = img.size
        if (w, h) != (rec.width_px, rec.height_px):
            raise ValueError(
                f"image {img.name!r} is {w} x {h} px but the paper is "
                f"{rec.width_px} x {rec.height_px} px"
            )
        # the visible colour (a float image holds linear light), top row first as Eq. 28's
        rgb = images.image_rgb(img)[::-1]
        return lambda: [TrainingSample(rec, rgb, img.name)]

    def execute(self, context):
        scene = context.scene
        st = checks.settings(scene)
        try:
            checks.require_brush_and_paper(st)
            make_samples = self._samples(scene)
        except (*checks.USER_ERRORS, ValueError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        settings = FitSettings(
            divisions=self.divisions,
            rounds=self.rounds,
            iterations=self.iterations,
            max_grid=self.max_grid,
            workers=1,  # Blender's executable is not a plain Python to fork workers from
            seed=recordings.scene_seed(st),
        )
        return self.run_job(context, FitJob(st, make_samples, settings, self.preset_name))
