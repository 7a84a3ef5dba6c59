# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.bake_samples: sample the animated brush empty into a recording in the .blend."""

from __future__ import annotations

import math

import bpy
import numpy as np

from ..blender import checks, keyframes, recordings, runtime, surfaces, transforms
from ..sim import surface as surf
from ..sim.core.recording import MAX_SAMPLES, from_dict
from . import polls


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
        for fc in keyframes.fcurves(ad):
            for kp in fc.keyframe_points:
                vals = (*kp.co, *kp.handle_left, *kp.handle_right)
                if not all(math.isfinite(v) for v in vals):
                    return o.name, fc.data_path, fc.array_index, kp.co[0]
    return None


def sample_brush(scene, st, frame_start: int, frame_end: int, rate: float, progress=None):
    """6-DOF samples of the brush relative to the paper, evaluated with everything that moves
    it (keyframes, constraints, drivers, parents) at rate samples per second. On a surface
    (issue 17), (samples, frames): the samples in the local frames where the brush's axis
    meets the surface, developed into its chart (sim.surface.develop)."""
    if surfaces.is_surface(st):
        surface = surfaces.mesh_surface(st.paper_object)[0]
        n = _count(scene, frame_start, frame_end, rate)
        poses = _brush_poses(scene, st, frame_start, rate, n, _half(progress, 0.0))
        return surf.develop(
            surface,
            poses[:, :3],
            poses[:, 3:].reshape(-1, 3, 3),
            surfaces.surface_origin(st),
            surfaces.surface_caster(st),
            surf.TriangleGrid(surface),  # the nearest points where the axis misses
            _half(progress, 0.5),
        )
    n = _count(scene, frame_start, frame_end, rate)
    out = np.empty((n, 6))
    for i in _at_frames(scene, frame_start, rate, n, progress):
        out[i] = transforms.sample_from_matrices(
            st, st.brush_object.matrix_world, st.paper_object.matrix_world
        )
    return out


def _half(progress, lo: float):
    """progress(fraction) reported on [lo, lo + 0.5] of the bar (None: None)."""
    return None if progress is None else (lambda f: progress(lo + 0.5 * f))


def _count(scene, frame_start, frame_end, rate) -> int:
    fps = scene.render.fps / scene.render.fps_base
    return int(math.floor((frame_end - frame_start) / fps * rate)) + 1


def _at_frames(scene, frame_start, rate, n, progress=None):
    """Yield 0..n-1 with the scene at each sample's (sub)frame, frame handlers held back; the
    scene's own frame is put back afterwards."""
    fps = scene.render.fps / scene.render.fps_base
    keep = scene.frame_current, scene.frame_subframe
    with runtime.get().frames_suspended():
        try:
            for i in range(n):
                f = frame_start + i * fps / rate
                fi = math.floor(f)
                scene.frame_set(fi, subframe=f - fi)
                yield i
                if progress is not None and i % 64 == 0:
                    progress(i / n)
        finally:
            scene.frame_set(keep[0], subframe=keep[1])


def _brush_poses(scene, st, frame_start, rate, n, progress=None) -> np.ndarray:
    """(n, 12): the brush's base (mm) and rotation (row-major) in the surface's space."""
    out = np.empty((n, 12))
    for i in _at_frames(scene, frame_start, rate, n, progress):
        base, rot = surfaces.surface_pose(st, st.brush_object.matrix_world)
        out[i, :3], out[i, 3:] = base, rot.ravel()
    bad = ~np.isfinite(out).all(axis=1)
    if bad.any():
        raise checks.UserError(f"The brush's pose is not a number at sample {int(np.argmax(bad))}")
    return out


def contact_problems(
    samples: np.ndarray, hair_mm: float, frame_of, what: str = "the paper"
) -> tuple[str, str]:
    """("ERROR" or "WARNING" or "", message) for baked samples that would draw nothing or
    nothing sensible: a brush that never moves, never reaches the paper, or is pushed through
    it (pressed deeper than its hair is long). ``frame_of(i)`` is sample i's frame."""
    z = samples[:, 2]
    low = int(np.argmin(z))
    if np.ptp(samples, axis=0).max() < 1e-6:
        if z[0] >= hair_mm:
            return "ERROR", (
                f"The brush does not move: all {len(samples)} samples hold the same pose, "
                f"{z[0] - hair_mm:.1f} mm above where it touches the paper (z = {hair_mm:g} mm)"
                ": keyframe the brush empty first"
            )
        return "WARNING", (
            f"The brush does not move: all {len(samples)} samples press {hair_mm - z[0]:.1f} mm "
            "at one spot (a blot): keyframe the brush empty to write a stroke"
        )
    if z[low] >= hair_mm:
        return "WARNING", (
            f"The brush never touches {what}: its lowest point is z = {z[low]:.1f} mm "
            f"(frame {frame_of(low):.0f}) and it touches at z = {hair_mm:g} mm, its hair "
            "length: nothing will be drawn"
        )
    if z[low] < 0.0:
        buried = np.flatnonzero(z < 0.0)
        return "WARNING", (
            f"The brush goes {-z[low]:.1f} mm through {what} at frame {frame_of(low):.0f} "
            f"({len(buried)} samples below it, from frame {frame_of(buried[0]):.0f}): it "
            f"touches at z = {hair_mm:g} mm, so press at most {hair_mm:g} mm (z above 0)"
        )
    return "", ""


def painted_samples(rec) -> int:
    """How many of a recording's samples were painted live (0 for None)."""
    info = rec.extra.get("blender", {}) if rec is not None and isinstance(rec.extra, dict) else {}
    n = info.get(recordings.PAINTED_KEY, 0) if isinstance(info, dict) else 0
    return int(n) if isinstance(n, int) else 0


class HAIRY_BRUSH_OT_bake_samples(bpy.types.Operator):
    """Sample the animated brush empty over the scene's frame range into the recording"""

    bl_idname = "hairy_brush.bake_samples"
    bl_label = "Bake Brush Samples"
    bl_options = {"REGISTER", "UNDO"}

    replace_painted: bpy.props.BoolProperty(
        name="Replace Painted Strokes",
        default=False,
        description="Bake even though the recording holds strokes painted live, which the "
        "keyframes do not have: they are replaced",
    )

    @classmethod
    def poll(cls, context):
        return polls.brush_and_paper(cls, context)

    def execute(self, context):
        scene = context.scene
        st = checks.settings(scene)
        try:
            checks.require_brush_and_paper(st)
            checks.check_settings(st)
        except checks.USER_ERRORS as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        old, unreadable = None, None
        if st.recording is not None:
            try:
                old = from_dict(recordings.read_recording_dict(st))
            except checks.USER_ERRORS as exc:
                unreadable = str(exc)
        painted = painted_samples(old)
        if painted and not self.replace_painted:
            self.report(
                {"ERROR"},
                f"The recording holds {painted} samples painted live, which baking the "
                "keyframes would replace: export it first, or bake with Replace Painted Strokes",
            )
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
        n = _count(scene, scene.frame_start, scene.frame_end, st.sample_rate_hz)
        if n > MAX_SAMPLES:  # known before the frames are stepped through (issue 30)
            self.report(
                {"ERROR"},
                f"Frames {scene.frame_start}-{scene.frame_end} at {st.sample_rate_hz:g} Hz make "
                f"{n:,} samples, more than a recording holds ({MAX_SAMPLES:,}): shorten the "
                "frame range or lower Sample Rate",
            )
            return {"CANCELLED"}
        try:
            samples, frames = self.sampled(context, st)
        except checks.USER_ERRORS as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        dips = None
        if old is not None and old.dips and not painted:  # re-baking keeps the dips recorded
            dips = [dp for dp in old.dips if dp.before_sample <= len(samples)]
        try:
            # and the brush's size (a character written at a size: brush_size)
            rec = recordings.new_recording(scene, samples, dips, written=old)
        except checks.USER_ERRORS as exc:
            self.report({"ERROR"}, f"Cannot bake: {exc}")
            return {"CANCELLED"}
        if frames is not None:
            rec.extra[recordings.SURFACE_KEY] = {"frames": frames.tolist()}
        fps = scene.render.fps / scene.render.fps_base
        level, problem = contact_problems(
            samples,
            rec.resolve()[1].hair_length_mm,  # the brush's (its size kept: brush_size)
            lambda i: scene.frame_start + i * fps / rec.sample_rate_hz,
            f"the surface of '{st.paper_object.name}'" if frames is not None else "the paper",
        )
        if level == "ERROR":
            self.report({"ERROR"}, problem)
            return {"CANCELLED"}
        if unreadable is not None:  # the unreadable text stays in the file, a new one is made
            old_name = st.recording.name
            st.recording = None
            self.report({"WARNING"}, f"{unreadable}; kept as '{old_name}', baked into a new text")
        recordings.store_recording(st, rec)
        self.report({"INFO"}, f"Baked {len(samples)} samples at {st.sample_rate_hz:g} Hz")
        if level:
            self.report({level}, problem)
        return {"FINISHED"}

    def sampled(self, context, st) -> tuple[np.ndarray, np.ndarray | None]:
        """(samples, surface frames or None) over the scene's frame range, with a progress
        bar; UserError for a pose that is not a number."""
        scene = context.scene
        wm = context.window_manager
        wm.progress_begin(0, 100)
        frames = None
        try:
            samples = sample_brush(
                scene,
                st,
                scene.frame_start,
                scene.frame_end,
                st.sample_rate_hz,
                lambda f: wm.progress_update(int(100 * f)),
            )
            if isinstance(samples, tuple):  # on a surface: the samples and their frames
                samples, frames = samples
        finally:
            wm.progress_end()
        bad_rows = ~np.all(np.isfinite(samples), axis=1)
        if bad_rows.any():
            i = int(np.argmax(bad_rows))
            raise checks.UserError(f"The brush's pose is not a number at sample {i}")
        return samples, frames
