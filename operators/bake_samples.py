# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.bake_samples: sample the animated brush empty into a recording in the .blend."""

from __future__ import annotations

import math

import bpy
import numpy as np

from .. import bridge, handlers
from ..sim.recording import RecordingError, from_dict


def nan_keyframes(obj):
    """(data path, index, frame) of the first keyframe or handle that is not finite, or None."""
    objs = [obj]
    p = obj.parent
    while p is not None:
        objs.append(p)
        p = p.parent
    for o in objs:
        ad = o.animation_data
        if ad is None or ad.action is None:
            continue
        for fc in bridge._fcurves(ad):
            for kp in fc.keyframe_points:
                vals = (*kp.co, *kp.handle_left, *kp.handle_right)
                if not all(math.isfinite(v) for v in vals):
                    return o.name, fc.data_path, fc.array_index, kp.co[0]
    return None


def sample_brush(scene, st, frame_start: int, frame_end: int, rate: float, progress=None):
    """6-DOF samples of the brush relative to the paper, evaluated with everything that moves
    it (keyframes, constraints, drivers, parents) at rate samples per second."""
    fps = scene.render.fps / scene.render.fps_base
    n = int(math.floor((frame_end - frame_start) / fps * rate)) + 1
    out = np.empty((n, 6))
    keep = scene.frame_current, scene.frame_subframe
    with handlers.suspended():
        try:
            for i in range(n):
                f = frame_start + i * fps / rate
                fi = math.floor(f)
                scene.frame_set(fi, subframe=f - fi)
                out[i] = bridge.sample_from_matrices(
                    st, st.brush_object.matrix_world, st.paper_object.matrix_world
                )
                if progress is not None and i % 64 == 0:
                    progress(i / n)
        finally:
            scene.frame_set(keep[0], subframe=keep[1])
    return out


class HAIRY_BRUSH_OT_bake_samples(bpy.types.Operator):
    """Sample the animated brush empty over the scene's frame range into the recording"""

    bl_idname = "hairy_brush.bake_samples"
    bl_label = "Bake Brush Samples"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        scene = context.scene
        st = bridge.settings(scene)
        try:
            bridge.require_brush_and_paper(st)
        except bridge.UserError as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        bad = nan_keyframes(st.brush_object)
        if bad is not None:
            name, path, idx, frame = bad
            self.report(
                {"ERROR"},
                f"'{name}' has a keyframe that is not a number on {path}[{idx}] "
                f"near frame {frame}: fix or delete it",
            )
            return {"CANCELLED"}
        if scene.frame_end <= scene.frame_start:
            self.report({"ERROR"}, "The scene's frame range is empty")
            return {"CANCELLED"}
        wm = context.window_manager
        wm.progress_begin(0, 100)
        try:
            samples = sample_brush(
                scene,
                st,
                scene.frame_start,
                scene.frame_end,
                st.sample_rate_hz,
                lambda f: wm.progress_update(int(100 * f)),
            )
        finally:
            wm.progress_end()
        bad_rows = ~np.all(np.isfinite(samples), axis=1)
        if bad_rows.any():
            i = int(np.argmax(bad_rows))
            self.report({"ERROR"}, f"The brush's pose is not a number at sample {i}")
            return {"CANCELLED"}
        dips = None
        if st.recording is not None:  # re-baking keeps the dips already recorded
            try:
                old = from_dict(bridge.read_recording_dict(st))
                if old.dips:
                    dips = [dp for dp in old.dips if dp.before_sample <= len(samples)]
            except (bridge.UserError, RecordingError):
                pass  # an unreadable old recording is replaced
        try:
            rec = bridge.new_recording(scene, samples, dips)
        except (RecordingError, bridge.UserError) as exc:
            self.report({"ERROR"}, f"Cannot bake: {exc}")
            return {"CANCELLED"}
        bridge.store_recording(st, rec)
        self.report({"INFO"}, f"Baked {len(samples)} samples at {st.sample_rate_hz:g} Hz")
        return {"FINISHED"}
