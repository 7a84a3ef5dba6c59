# SPDX-License-Identifier: GPL-3.0-or-later
"""The brush empty keyframed along 6-DOF samples or world matrices, and its F-curves (legacy
and slotted actions)."""

from __future__ import annotations

import numpy as np

from . import transforms


def keyframe_samples(scene, st, samples, rate_hz: float, frame_start: float):
    """Keyframe the brush empty along 6-DOF samples (one key per sample, linear), so the
    writing plays, can be edited, and bakes back into the same samples."""
    paper_mw = st.paper_object.matrix_world
    mats = [transforms.matrix_from_sample(st, paper_mw, s) for s in samples]
    return keyframe_matrices(scene, st, mats, rate_hz, frame_start)


def keyframe_matrices(scene, st, mats, rate_hz: float, frame_start: float):
    """Keyframe the brush empty through world matrices, one a sample (linear); returns the
    last key's frame."""
    from mathutils import Matrix

    obj = st.brush_object
    obj.rotation_mode = "ZYX"
    fps = scene.render.fps / scene.render.fps_base
    frames = frame_start + np.arange(len(mats)) * fps / rate_hz
    if obj.parent is not None:
        parent = np.array(obj.parent.matrix_world) @ np.array(obj.matrix_parent_inverse)
    else:
        parent = np.eye(4)
    inv_parent = np.linalg.inv(parent)
    loc = np.empty((len(mats), 3))
    rot = np.empty((len(mats), 3))
    prev = None
    for i, m in enumerate(mats):
        basis = Matrix((inv_parent @ np.asarray(m)).tolist())
        t, q, _scale = basis.decompose()
        e = q.to_euler("ZYX", prev) if prev is not None else q.to_euler("ZYX")
        loc[i], rot[i], prev = t[:], e[:], e
    remove_fcurves(obj, ("location", "rotation_euler"))  # other animation stays
    for path in ("location", "rotation_euler"):
        for k in range(3):
            obj.keyframe_insert(path, index=k, frame=float(frames[0]))
    curves = {(fc.data_path, fc.array_index): fc for fc in fcurves(obj.animation_data)}
    for path, values in (("location", loc), ("rotation_euler", rot)):
        for k in range(3):
            fc = curves[(path, k)]
            kp = fc.keyframe_points
            kp.add(len(mats) - len(kp))
            co = np.stack([frames, values[:, k]], axis=1).astype(np.float32)
            kp.foreach_set("co", co.ravel())
            for p in kp:
                p.interpolation = "LINEAR"
            fc.update()
    return float(frames[-1])


def remove_fcurves(obj, paths):
    """Delete the object's F-curves of these data paths (every index), keeping the rest."""
    ad = obj.animation_data
    if ad is None or ad.action is None:
        return
    action = ad.action
    if hasattr(action, "fcurves"):  # Blender < 5 (legacy actions)
        owners = [action.fcurves]
    else:
        slot = getattr(ad, "action_slot", None)
        owners = [
            bag.fcurves
            for layer in action.layers
            for strip in layer.strips
            if slot is not None and (bag := strip.channelbag(slot)) is not None
        ]
    for fcurves in owners:
        for fc in [fc for fc in fcurves if fc.data_path in paths]:
            fcurves.remove(fc)


def fcurves(ad):
    """The F-curves of an object's animation (legacy or slotted actions)."""
    action = ad.action
    if hasattr(action, "fcurves"):  # Blender < 5 (legacy actions)
        return list(action.fcurves)
    out = []
    slot = getattr(ad, "action_slot", None)
    for layer in action.layers:  # slotted actions (Blender 4.4+)
        for strip in layer.strips:
            bag = strip.channelbag(slot) if slot is not None else None
            if bag is not None:
                out.extend(bag.fcurves)
    return out
